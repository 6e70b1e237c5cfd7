/* SPDX-License-Identifier: GPL-3.0-or-later */
#include "granflow/friction.h"
#include "internal.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* A rate-independent shear (per unit density) with the regularisation
 * |u|/(|u|+u0) of finite-area paper eq. 24, and its implicit coefficient
 * (eq. 60); at rest with u0 = 0 the full value, infinitely stiff. */
static void regularised_part(double stress, double u0, double speed, double *tau, double *nu)
{
    if (stress == 0.0) {
        *tau = 0.0;
        *nu = 0.0;
        return;
    }
    const double denom = speed + u0;
    if (denom == 0.0) { /* exact at rest: static bound, infinite stiffness */
        *tau = stress;
        *nu = HUGE_VAL;
        return;
    }
    *nu = stress / denom;      /* finite-area paper eq. 60 */
    *tau = *nu * speed;        /* eq. 24 */
}

/* Coulomb-type part mu p_b/rho |u|/(|u|+u0) and its implicit coefficient;
 * none without contact (p_b <= 0). */
static void coulomb_part(double mu, double u0, const gf_friction_state *s, double *tau, double *nu)
{
    const double p = s->pb > 0.0 ? s->pb / s->rho : 0.0;
    regularised_part(mu * p, u0, s->speed, tau, nu);
}

/* ---- coulomb ---------------------------------------------------------- */
static const gf_friction_param coulomb_params[] = {
    {"mu", "-", "bed friction coefficient tan(delta)", 0.5, 0.0, 10.0},
    {"u0", "m/s", "regularisation speed of |u|/|u| (0 = exact Coulomb)", 0.0, 0.0, 1.0},
};
static void coulomb_eval(const double *p, const gf_friction_state *s, gf_friction_result *r)
{
    coulomb_part(p[0], p[1], s, &r->tau, &r->nu);
}
static const gf_friction_type coulomb_type = {
    "coulomb", "Coulomb friction tau_b = mu p_b u/(|u|+u0)", 2, coulomb_params, NULL, coulomb_eval};

/* ---- mu(I) -------------------------------------------------------------- */
static const gf_friction_param mu_i_params[] = {
    {"mu_s", "-", "friction coefficient at I -> 0 (Table 1: 0.38)", 0.38, 0.0, 10.0},
    {"mu_2", "-", "friction coefficient at I -> infinity (Table 1: 0.65)", 0.65, 0.0, 10.0},
    {"I_0", "-", "reference inertial number (Table 1: 0.3)", 0.3, 1e-12, 1e6},
    {"d", "m", "particle diameter (Table 1: 0.005)", 0.005, 1e-12, 10.0},
    {"rho_p", "kg/m^3", "particle density (Table 1: 2500)", 2500.0, 1e-12, 1e6},
    {"u0", "m/s", "regularisation speed (Table 1: 1e-4)", 1e-4, 0.0, 1.0},
};
static gf_status mu_i_check(const double *p)
{
    if (p[1] < p[0])
        return gf_fail(GF_EPHYS,
                       "mu(I) friction: mu_2 = %g is below mu_s = %g; friction must not "
                       "decrease with the inertial number (finite-area paper eq. 25)",
                       p[1], p[0]);
    return GF_SUCCESS;
}
static void mu_i_eval(const double *p, const gf_friction_state *s, gf_friction_result *r)
{
    const double mu_s = p[0], mu_2 = p[1], I0 = p[2], d = p[3], rho_p = p[4], u0 = p[5];
    double mu = mu_s;
    if (s->pb > 0.0 && s->speed > 0.0) {
        /* I = num/den, eq. 26; I/(I0 + I) = num/(I0 den + num), eq. 25, has
         * no overflow or 0/0 for a vanishing h or p_b (I -> infinity: mu_2) */
        const double num = 2.5 * s->speed * d, den = s->h * sqrt(s->pb / rho_p);
        mu = mu_s + (mu_2 - mu_s) * num / (I0 * den + num);
    }
    coulomb_part(mu, u0, s, &r->tau, &r->nu);
}
static const gf_friction_type mu_i_type = {
    "mu_i", "mu(I) rheology, finite-area paper eqs. 24-26", 6, mu_i_params, mu_i_check, mu_i_eval};

/* ---- Voellmy ------------------------------------------------------------ */
static const gf_friction_param voellmy_params[] = {
    {"mu", "-", "dry (Coulomb) friction coefficient", 0.2, 0.0, 10.0},
    {"xi", "m/s^2", "turbulent friction coefficient", 1000.0, 1e-12, 1e9},
    {"u0", "m/s", "regularisation speed of the Coulomb part", 1e-4, 0.0, 1.0},
};
static void voellmy_eval(const double *p, const gf_friction_state *s, gf_friction_result *r)
{
    double tau, nu;
    coulomb_part(p[0], p[2], s, &tau, &nu);
    const double k = s->g / p[1];
    r->tau = tau + k * s->speed * s->speed;
    r->nu = nu + k * s->speed;
}
static const gf_friction_type voellmy_type = {
    "voellmy", "Voellmy: Coulomb plus turbulent g|u|^2/xi", 3, voellmy_params, NULL, voellmy_eval};

/* ---- Chezy -------------------------------------------------------------- */
static const gf_friction_param chezy_params[] = {
    {"C", "m^0.5/s", "Chezy coefficient (section 6.1.3: 40)", 40.0, 1e-12, 1e9},
};
static void chezy_eval(const double *p, const gf_friction_state *s, gf_friction_result *r)
{
    const double k = s->g / (p[0] * p[0]); /* eq. 71: tau_b = rho g/C^2 |u| u */
    r->nu = k * s->speed;
    r->tau = r->nu * s->speed;
}
static const gf_friction_type chezy_type = {
    "chezy", "Chezy friction, finite-area paper eq. 71", 1, chezy_params, NULL, chezy_eval};

/* ---- samosAT (AvaFrame com1DFA's standard snow law; doc/theory/friction.md) ---- */
static const gf_friction_param samosat_params[] = {
    {"mu", "-", "Coulomb coefficient (AvaFrame standard 0.155; Medium 0.17, Small 0.22)", 0.155, 0.0, 10.0},
    {"tau0", "Pa", "yield stress", 0.0, 0.0, 1e6},
    {"Rs0", "-", "fluidisation ratio scale", 0.222, 1e-12, 1e6},
    {"kappa", "-", "von Karman constant of the drag profile", 0.43, 1e-12, 10.0},
    {"R", "m", "roughness length of the drag profile", 0.05, 1e-12, 10.0},
    {"B", "-", "drag profile constant (> 0: the drag of h <= R is 1/B^2)", 4.13, 1e-12, 1e3},
    {"u0", "m/s", "regularisation speed of the Coulomb and yield parts", 1e-4, 0.0, 1.0},
};
/* tau_b = tau0 + mu (1 + Rs0/(Rs0 + Rs)) sigma_b + rho u^2 / (ln(h/R)/kappa + B)^2,
 * Rs = rho u^2/(sigma_b + 0.001 Pa), ln(h/R) = 0 for h < R (doc/theory/friction.md);
 * the yield and Coulomb parts need contact (sigma_b > 0) and carry the factor
 * |u|/(|u| + u0) of the other laws, so tau at rest is tau0 + 2 mu sigma_b with
 * u0 = 0 (exact) and 0 with u0 > 0 (regularised, as the implicit scheme needs). */
static void samosat_eval(const double *p, const gf_friction_state *s, gf_friction_result *r)
{
    const double mu = p[0], tau0 = p[1], rs0 = p[2], kappa = p[3], R = p[4], B = p[5], u0 = p[6];
    const double u = s->speed, sig = s->pb > 0.0 ? s->pb : 0.0;
    const double rs = s->rho * u * u / (sig + 0.001);
    double tau, nu;
    coulomb_part(mu * (1.0 + rs0 / (rs0 + rs)), u0, s, &tau, &nu);
    double ty, nuy; /* yield part, regularised like the Coulomb part, with contact only */
    regularised_part(sig > 0.0 ? tau0 / s->rho : 0.0, u0, u, &ty, &nuy);
    tau += ty;
    nu += nuy;
    const double lr = s->h > R ? log(s->h / R) : 0.0, den = lr / kappa + B;
    const double cd = 1.0 / (den * den); /* den >= B > 0 */
    r->tau = tau + cd * u * u;
    r->nu = nu + cd * u;
}
static const gf_friction_type samosat_type = {
    "samosAT", "samosAT snow friction (Sampl 2007; AvaFrame's standard)", 7, samosat_params, NULL,
    samosat_eval};

/* ---- none --------------------------------------------------------------- */
static void none_eval(const double *p, const gf_friction_state *s, gf_friction_result *r)
{
    (void)p;
    (void)s;
    r->tau = 0.0;
    r->nu = 0.0;
}
static const gf_friction_type none_type = {"none", "no basal friction", 0, NULL, NULL, none_eval};

const gf_friction_type *const gf_friction_coulomb = &coulomb_type;
const gf_friction_type *const gf_friction_mu_i = &mu_i_type;
const gf_friction_type *const gf_friction_voellmy = &voellmy_type;
const gf_friction_type *const gf_friction_chezy = &chezy_type;
const gf_friction_type *const gf_friction_samosat = &samosat_type;
const gf_friction_type *const gf_friction_none = &none_type;

static const gf_friction_type *const all_types[] = {&coulomb_type, &mu_i_type, &voellmy_type, &chezy_type,
                                                     &samosat_type, &none_type, NULL};

const gf_friction_type *const *gf_friction_types(void) { return all_types; }

const char *gf_friction_names(void) { return "coulomb, mu_i, voellmy, chezy, samosAT, none"; }

const gf_friction_type *gf_friction_lookup(const char *name)
{
    if (!name)
        return NULL;
    for (size_t i = 0; all_types[i]; ++i)
        if (strcmp(all_types[i]->name, name) == 0)
            return all_types[i];
    return NULL;
}

gf_status gf_friction_init(gf_friction *f, const char *name)
{
    if (!f)
        return gf_fail(GF_EINVAL, "gf_friction_init: null friction pointer");
    const gf_friction_type *t = gf_friction_lookup(name);
    if (!t)
        return gf_fail(GF_ENOTFOUND, "unknown friction law '%s'; valid names: %s",
                       name ? name : "(null)", gf_friction_names());
    memset(f, 0, sizeof *f);
    f->type = t;
    for (size_t i = 0; i < t->n_params; ++i)
        f->p[i] = t->params[i].default_value;
    return GF_SUCCESS;
}

static int param_index(const gf_friction_type *t, const char *key)
{
    for (size_t i = 0; i < t->n_params; ++i)
        if (strcmp(t->params[i].name, key) == 0)
            return (int)i;
    return -1;
}

static gf_status unknown_key(const gf_friction_type *t, const char *key)
{
    char names[256] = "";
    size_t used = 0;
    for (size_t i = 0; i < t->n_params && used < sizeof names; ++i)
        used += (size_t)snprintf(names + used, sizeof names - used, "%s%s", i ? ", " : "",
                                 t->params[i].name);
    return gf_fail(GF_ENOTFOUND, "friction law '%s' has no coefficient '%s'; its coefficients: %s",
                   t->name, key, t->n_params ? names : "(none)");
}

gf_status gf_friction_set(gf_friction *f, const char *key, double value)
{
    if (!f || !f->type || !key)
        return gf_fail(GF_EINVAL, "gf_friction_set: null argument or uninitialised law");
    const int i = param_index(f->type, key);
    if (i < 0)
        return unknown_key(f->type, key);
    const gf_friction_param *p = &f->type->params[i];
    char what[128];
    snprintf(what, sizeof what, "friction law '%s' coefficient %s [%s]", f->type->name, key, p->unit);
    gf_status st = gf_check_range(what, value, p->min, p->max);
    if (st)
        return st;
    f->p[i] = value;
    return GF_SUCCESS;
}

gf_status gf_friction_get(const gf_friction *f, const char *key, double *value)
{
    if (!f || !f->type || !key || !value)
        return gf_fail(GF_EINVAL, "gf_friction_get: null argument or uninitialised law");
    const int i = param_index(f->type, key);
    if (i < 0)
        return unknown_key(f->type, key);
    *value = f->p[i];
    return GF_SUCCESS;
}

gf_status gf_friction_check(const gf_friction *f)
{
    if (!f || !f->type)
        return gf_fail(GF_EINVAL, "gf_friction_check: uninitialised friction law");
    for (size_t i = 0; i < f->type->n_params; ++i) {
        const gf_friction_param *p = &f->type->params[i];
        gf_status st = gf_check_range(p->name, f->p[i], p->min, p->max);
        if (st)
            return st;
    }
    return f->type->check ? f->type->check(f->p) : GF_SUCCESS;
}

gf_status gf_friction_eval(const gf_friction *f, const gf_friction_state *s, gf_friction_result *r)
{
    if (!f || !f->type || !s || !r)
        return gf_fail(GF_EINVAL, "gf_friction_eval: null argument or uninitialised law");
    /* one test on the hot path (the 1D solvers call this per quadrature
     * point and stage), the named checks only on failure */
    if (!(s->h >= 0.0 && s->h < HUGE_VAL && s->speed >= 0.0 && s->speed < HUGE_VAL && s->rho >= 1e-300 &&
          s->rho < HUGE_VAL && s->g >= 0.0 && s->g < HUGE_VAL && isfinite(s->pb))) {
        gf_status st;
        if ((st = gf_check_range("flow thickness h", s->h, 0.0, HUGE_VAL)) ||
            (st = gf_check_range("speed |u|", s->speed, 0.0, HUGE_VAL)) ||
            (st = gf_check_range("density rho", s->rho, 1e-300, HUGE_VAL)) ||
            (st = gf_check_range("gravity g", s->g, 0.0, HUGE_VAL)))
            return st;
        return gf_fail(GF_ENONFINITE, "basal pressure p_b = %g is not a finite number", s->pb);
    }
    f->type->eval(f->p, s, r);
    r->mu = s->pb > 0.0 ? r->tau / (s->pb / s->rho) : 0.0;
    return GF_SUCCESS;
}

double gf_friction_decelerate(double u, double decel_dt)
{
    const double m = fabs(u) - decel_dt;
    if (m <= 0.0)
        return 0.0;
    return u > 0.0 ? m : -m;
}

gf_status gf_friction_static_bound(const gf_friction *f, const gf_friction_state *s, double *tau_s)
{
    if (!f || !f->type || !s || !tau_s)
        return gf_fail(GF_EINVAL, "gf_friction_static_bound: null argument or uninitialised law");
    gf_friction at_rest = *f;
    for (size_t i = 0; i < f->type->n_params; ++i)
        if (strcmp(f->type->params[i].name, "u0") == 0)
            at_rest.p[i] = 0.0; /* exact Coulomb: tau(0+) is the static bound */
    gf_friction_state rest = *s;
    rest.speed = 0.0;
    gf_friction_result r;
    const gf_status st = gf_friction_eval(&at_rest, &rest, &r);
    if (st)
        return st;
    *tau_s = r.tau;
    return GF_SUCCESS;
}

/* ---- samosATAuto (AvaFrame com1DFA: com1DFACfg.ini's three sets) ---------- */
static const gf_samosat_set samosat_sets[] = {
    {"samosATSmall", 0.22, 0.0, 0.222, 0.43, 0.05, 4.13},
    {"samosATMedium", 0.17, 0.0, 0.222, 0.43, 0.05, 4.13},
    {"samosAT", 0.155, 0.0, 0.222, 0.43, 0.05, 4.13},
    {NULL, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0},
};

const gf_samosat_set *gf_samosat_sets(void) { return samosat_sets; }

gf_status gf_samosat_auto(double volume, const gf_samosat_set **set)
{
    if (!set)
        return gf_fail(GF_EINVAL, "gf_samosat_auto: null output");
    if (!isfinite(volume))
        return gf_fail(GF_ENONFINITE, "the release volume %g m^3 that chooses the samosAT set is not a finite number",
                       volume);
    if (!(volume > 0.0))
        return gf_fail(GF_EDOM,
                       "the release volume %g m^3 that chooses the samosAT set: allowed > 0 (the volume"
                       " released at the start; without one there is nothing to choose by)",
                       volume);
    *set = volume < GF_SAMOSAT_VOL_SMALL ? &samosat_sets[0]
           : volume < GF_SAMOSAT_VOL_MEDIUM ? &samosat_sets[1]
                                            : &samosat_sets[2];
    return GF_SUCCESS;
}

gf_status gf_friction_init_samosat_set(gf_friction *f, const gf_samosat_set *set)
{
    if (!f || !set || !set->name)
        return gf_fail(GF_EINVAL, "gf_friction_init_samosat_set: null argument");
    gf_status st = gf_friction_init(f, "samosAT");
    const char *keys[6] = {"mu", "tau0", "Rs0", "kappa", "R", "B"};
    const double vals[6] = {set->mu, set->tau0, set->Rs0, set->kappa, set->R, set->B};
    for (int k = 0; k < 6 && st == GF_SUCCESS; ++k)
        st = gf_friction_set(f, keys[k], vals[k]);
    return st;
}
