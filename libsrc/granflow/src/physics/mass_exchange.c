/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Mass exchange with the bed and obstacles: see granflow/mass_exchange.h.
 * "spec §n": doc/theory/mass-exchange.md, section n (after AvaFrame com1DFA;
 * Tonnel et al. 2023, Geosci. Model Dev. 16, 7013). */
#include "granflow/mass_exchange.h"
#include "internal.h"

#include <math.h>
#include <string.h>

void gf_mass_exchange_config_default(gf_mass_exchange_config *c)
{
    memset(c, 0, sizeof *c);
    c->entrainment = 0; /* simType null */
    c->resistance = 0;
    c->detrainment = 1;
    c->rho_ent = 100.0; /* spec §1 */
    c->h_ent = 0.3;     /* spec §1: `thickness` where missing */
    c->e_b = 5000.0;    /* spec §1 */
    c->e_s = 0.0;       /* spec §1: entShearResistance */
    c->e_d = 0.0;       /* spec §1: entDefResistance */
    c->K = 5.0;         /* spec §2 (Feistl et al. 2014) */
    c->c_res = 0.01;    /* spec §2 */
    c->v_min = 6.0;     /* spec §2 */
    c->v_max = 40.0;
    c->h_min = 0.6;
    c->h_max = 10.0;
}

gf_status gf_mass_exchange_simtype(gf_mass_exchange_config *c, const char *name)
{
    static const struct {
        const char *name;
        int ent, res;
    } types[] = {{"null", 0, 0}, {"ent", 1, 0}, {"res", 0, 1}, {"entres", 1, 1}};
    if (!c || !name)
        return gf_fail(GF_EINVAL, "mass exchange: simType: null argument");
    for (size_t i = 0; i < sizeof types / sizeof types[0]; ++i)
        if (strcmp(name, types[i].name) == 0) {
            c->entrainment = types[i].ent;
            c->resistance = types[i].res;
            return GF_SUCCESS;
        }
    return gf_fail(GF_ENOTFOUND, "mass exchange: simType '%s' unknown; allowed: null, ent, res, entres", name);
}

gf_status gf_mass_exchange_config_check(const gf_mass_exchange_config *c)
{
    if (!c)
        return gf_fail(GF_EINVAL, "mass exchange: null configuration");
    const struct {
        const char *name;
        int v;
    } sw[] = {{"entrainment", c->entrainment}, {"resistance", c->resistance}, {"detrainment", c->detrainment}};
    for (size_t i = 0; i < sizeof sw / sizeof sw[0]; ++i)
        if (sw[i].v != 0 && sw[i].v != 1)
            return gf_fail(GF_EINVAL, "mass exchange: switch %s = %d; allowed: 0 (off) or 1 (on)", sw[i].name,
                           sw[i].v);
    const double big = 1e300;
    gf_status st;
#define GF_MX1 " (doc/theory/mass-exchange.md, section 1)"
#define GF_MX2 " (doc/theory/mass-exchange.md, section 2)"
    if ((st = gf_check_range("mass exchange: entrainable snow density rho_ent [kg/m^3]" GF_MX1,
                             c->rho_ent, 1e-300, big)) ||
        (st = gf_check_range("mass exchange: default entrainable thickness h_ent [m]" GF_MX1, c->h_ent,
                             0.0, big)) ||
        (st = gf_check_range("mass exchange: specific erosion energy e_b [J/kg] (doc/theory/mass-exchange.md,"
                             " section 1; 0: ploughing)",
                             c->e_b, 0.0, big)) ||
        (st = gf_check_range("mass exchange: breaking energy e_s [J/m^2]" GF_MX1, c->e_s, 0.0, big)) ||
        (st = gf_check_range("mass exchange: deformation energy e_d [J/kg]" GF_MX1, c->e_d, 0.0, big)) ||
        (st = gf_check_range("mass exchange: detrainment coefficient K [Pa]" GF_MX2, c->K, 0.0, big)) ||
        (st = gf_check_range("mass exchange: increased-friction coefficient c_res [-]" GF_MX2, c->c_res,
                             0.0, big)) ||
        (st = gf_check_range("mass exchange: resistance window v_min [m/s]" GF_MX2, c->v_min, 0.0, big)) ||
        (st = gf_check_range("mass exchange: resistance window v_max [m/s]" GF_MX2, c->v_max, 0.0, big)) ||
        (st = gf_check_range("mass exchange: resistance window h_min [m]" GF_MX2, c->h_min, 0.0, big)) ||
        (st = gf_check_range("mass exchange: resistance window h_max [m]" GF_MX2, c->h_max, 0.0, big)))
#undef GF_MX1
#undef GF_MX2
        return st;
    if (c->v_min > c->v_max)
        return gf_fail(GF_EDOM, "mass exchange: speed window inverted: v_min = %g m/s > v_max = %g m/s (doc/theory/"
                                "mass-exchange.md, section 2, needs v_min <= v_max)", c->v_min, c->v_max);
    if (c->h_min > c->h_max)
        return gf_fail(GF_EDOM, "mass exchange: thickness window inverted: h_min = %g m > h_max = %g m (doc/theory/"
                                "mass-exchange.md, section 2, needs h_min <= h_max)", c->h_min, c->h_max);
    return GF_SUCCESS;
}

/* spec §1, erosion: ṁ = τ_b |u| / e_b */
double gf_erosion_rate(const gf_mass_exchange_config *c, double tau_b, double speed)
{
    return c->e_b > 0.0 ? tau_b * speed / c->e_b : 0.0;
}

/* spec §1: erosion Δm = min(ṁ A Δt, q_ent A); ploughing Δm = q w |u| Δt,
 * w = √A, with q the intact layer ahead of the front, capped by q_ent A */
double gf_entrainment_mass(const gf_mass_exchange_config *c, double tau_b, double speed, double area, double dt,
                           double q_ent, double q_front)
{
    const double avail = q_ent * area;
    const double dm = c->e_b > 0.0 ? gf_erosion_rate(c, tau_b, speed) * area * dt : q_front * sqrt(area) * speed * dt;
    return dm < avail ? dm : avail;
}

/* spec §1, momentum: u <- u m/(m + Δm); energy loss ΔE = e_s A_ent + e_d Δm
 * from the kinetic energy, the speed scaled by √(1 - ΔE/(½ m |u|²)), >= 0 */
double gf_entrainment_speed(const gf_mass_exchange_config *c, double m, double dm, double a_ent, double speed)
{
    const double mt = m + dm, s = speed * (m / mt);
    const double de = c->e_s * a_ent + c->e_d * dm;
    if (!(de > 0.0))
        return s;
    const double ke = 0.5 * mt * s * s;
    return ke > de ? s * sqrt(1.0 - de / ke) : 0.0;
}

/* spec §2: the speed and thickness windows */
gf_resistance_process gf_resistance_window(const gf_mass_exchange_config *c, double speed, double h)
{
    if (!c->detrainment)
        return GF_RESISTANCE_FRICTION;
    if (speed < c->v_min || h < c->h_min)
        return GF_RESISTANCE_DETRAIN;
    if (speed > c->v_max || h > c->h_max)
        return GF_RESISTANCE_NONE;
    return GF_RESISTANCE_FRICTION;
}

/* spec §2: Δm_det = min(K/|u| A Δt, m) (Feistl et al. 2014's rate K/|u|);
 * at rest (|u| = 0) the rate is unbounded and the whole mass goes, unless
 * K = 0: no rate, nothing detrained (0 · ∞ taken as 0, not as the mass) */
double gf_detrainment_mass(const gf_mass_exchange_config *c, double speed, double m, double area, double dt)
{
    const double kad = c->K * area * dt; /* Δm_det |u| */
    if (!(kad > 0.0))
        return 0.0;
    return kad >= m * speed ? m : kad / speed;
}

/* spec §2: h d|u|/dt = -c |u|^2 by backward Euler, the positive root of
 * c dt s^2 + h s - h |u| = 0 in its cancellation-free form */
double gf_resistance_speed(double c, double h, double speed, double dt)
{
    const double x = 4.0 * c * dt * speed / h;
    return x > 0.0 ? 2.0 * speed / (1.0 + sqrt(1.0 + x)) : speed;
}

gf_status gf_mass_exchange_face_update(const gf_mass_exchange_config *c, const gf_mass_exchange_face *f, double dt,
                                       gf_mass_exchange_result *r)
{
    if (!c || !f || !r)
        return gf_fail(GF_EINVAL, "mass exchange: null argument");
    const struct {
        const char *name;
        double v, lo;
    } in[] = {{"flow thickness h [m]", f->h, 0.0},          {"speed |u| [m/s]", f->speed, 0.0},
              {"face area A [m^2]", f->area, 1e-300},        {"flow density rho [kg/m^3]", f->rho, 1e-300},
              {"basal shear stress tau_b [Pa]", f->tau_b, 0.0}, {"entrainable depth h_ent [m]", f->h_ent, 0.0},
              {"intact layer depth h_front [m]", f->h_front, f->h_ent}, {"resistance factor", f->resistance, 0.0},
              {"time step dt [s]", dt, 0.0}};
    for (size_t i = 0; i < sizeof in / sizeof in[0]; ++i)
        if (!isfinite(in[i].v) || !(in[i].v >= in[i].lo))
            return gf_fail(isfinite(in[i].v) ? GF_EDOM : GF_ENONFINITE,
                           "mass exchange: %s = %g (must be finite and >= %g)", in[i].name, in[i].v, in[i].lo);
    double h = f->h, speed = f->speed, mf = 1.0, h_ent = f->h_ent;
    const double rA = f->rho * f->area;
    /* spec §2: the window from the state on entry */
    const gf_resistance_process proc = c->resistance && f->resistance > 0.0 ? gf_resistance_window(c, speed, h)
                                                                           : GF_RESISTANCE_NONE;
    double ent = 0.0, det = 0.0;
    /* spec §1: entrainment */
    if (c->entrainment && h_ent > 0.0 && speed > 0.0 && h > 0.0) {
        const double q_ent = c->rho_ent * h_ent, q_front = c->rho_ent * f->h_front;
        const double dm = gf_entrainment_mass(c, f->tau_b, speed, f->area, dt, q_ent, q_front);
        if (dm > 0.0) {
            const double m = rA * h, avail = q_ent * f->area;
            const double a_ent = c->e_b > 0.0 ? f->area : dm / q_front; /* fracture area of the energy loss */
            const double s = gf_entrainment_speed(c, m, dm, a_ent, speed);
            /* the layer: Δm/(rho_ent A) taken, 0 exactly when it runs out, never below */
            h_ent = dm >= avail ? 0.0 : fmax(0.0, h_ent - dm / (c->rho_ent * f->area));
            const double hn = h + dm / rA; /* spec §1: joins at the flow's density */
            ent = hn - h;
            /* momentum kept (spec §1): the factor is 1 without energy loss */
            if (c->e_s > 0.0 || c->e_d > 0.0)
                mf = s * hn / (speed * h);
            h = hn;
            speed = s;
        }
    }
    /* spec §2: detrainment or increased friction */
    if (proc == GF_RESISTANCE_DETRAIN && h > 0.0) {
        const double m = rA * h, dm = gf_detrainment_mass(c, speed, m, f->area, dt);
        const double hn = dm >= m ? 0.0 : fmax(0.0, h - dm / rA);
        det = h - hn;
        mf = hn > 0.0 ? mf * (hn / h) : 0.0; /* the remaining flow keeps its velocity */
        h = hn;
        if (hn == 0.0)
            speed = 0.0;
    } else if (proc == GF_RESISTANCE_FRICTION && h > 0.0 && speed > 0.0) {
        const double s = gf_resistance_speed(c->c_res * f->resistance, h, speed, dt);
        mf *= s / speed;
        speed = s;
    }
    r->h = h;
    r->speed = speed;
    r->mom_factor = mf;
    r->h_ent = h_ent;
    r->entrained = ent;
    r->detrained = det;
    r->process = proc;
    return GF_SUCCESS;
}
