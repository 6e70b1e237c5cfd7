/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Mass exchange (granflow/mass_exchange.h; model reference
 * doc/theory/mass-exchange.md, "spec §n" = its section n) pointwise and in the
 * explicit surface scheme (gf_surface_set_mass_exchange), against closed
 * forms: erosion at τ_b|u|/e_b per area with the momentum kept, ploughing
 * taking the swept layer, a layer running out, detrainment K/|u| (and the
 * detrained volume split by speed: the speed window, at rest), the
 * increased friction u0/(1 + c u0 t/h) and its order in dt, the windows,
 * the mass balance with the exchanged volumes, the null run unchanged, and
 * bad parameters refused. */
#include "../gf_test.h"
#include "../surface_mesh.h"

#include <stdio.h>

#include "granflow/constants.h"
#include "granflow/mass_exchange.h"
#include "granflow/surface.h"

static const int WALLS[4] = {GF_EDGE_WALL, GF_EDGE_WALL, GF_EDGE_WALL, GF_EDGE_WALL};
static const double G = 9.81;

static double const_zeta(double s, void *ctx)
{
    (void)s;
    return *(double *)ctx;
}

/* A strip periodic along the flow: the strip_mesh of nx x ny faces on a
 * plane inclined at zeta, its edges at s0 dropped and those at s1 joining
 * the last face of each row to the first (walls along the sides).  A
 * uniform layer moving along the strip stays uniform: every face sees the
 * same fluxes in and out, so the exchange acts on one state, as the closed
 * forms assume. */
typedef struct periodic {
    strip_mesh *sm;
    int *owner, *neighbour, *kind;
    double *length, *enormal, *ecentre, *epoints;
    gf_surface_mesh m;
} periodic;

static periodic *periodic_new(size_t nx, size_t ny, double len, double width, double zeta_deg)
{
    periodic *p = calloc(1, sizeof *p);
    static double zeta;
    zeta = zeta_deg * GF_DEG;
    p->sm = strip_mesh_new(nx, ny, 0, len, -0.5 * width, 0.5 * width, const_zeta, &zeta, WALLS);
    const gf_surface_mesh *m = &p->sm->m;
    const size_t ne = m->n_edges - ny;
    p->owner = malloc(ne * sizeof(int)), p->neighbour = malloc(ne * sizeof(int)), p->kind = malloc(ne * sizeof(int));
    p->length = malloc(ne * sizeof(double)), p->enormal = malloc(3 * ne * sizeof(double));
    p->ecentre = malloc(3 * ne * sizeof(double)), p->epoints = malloc(6 * ne * sizeof(double));
    size_t e2 = 0;
    for (size_t e = 0; e < m->n_edges; ++e) {
        const int first = e < (nx + 1) * ny && e % (nx + 1) == 0, last = e < (nx + 1) * ny && e % (nx + 1) == nx;
        if (first)
            continue;
        p->owner[e2] = m->owner[e];
        p->neighbour[e2] = last ? (int)(e / (nx + 1) * nx) : m->neighbour[e];
        p->kind[e2] = last ? GF_EDGE_INTERNAL : m->kind[e];
        p->length[e2] = m->length[e];
        memcpy(p->enormal + 3 * e2, m->edge_normal + 3 * e, 3 * sizeof(double));
        memcpy(p->ecentre + 3 * e2, m->edge_centre + 3 * e, 3 * sizeof(double));
        memcpy(p->epoints + 6 * e2, m->edge_points + 6 * e, 6 * sizeof(double));
        e2++;
    }
    assert_int_equal(e2, ne);
    p->m = *m;
    p->m.n_edges = ne;
    p->m.owner = p->owner, p->m.neighbour = p->neighbour, p->m.kind = p->kind, p->m.length = p->length;
    p->m.edge_normal = p->enormal, p->m.edge_centre = p->ecentre, p->m.edge_points = p->epoints;
    return p;
}

static void periodic_free(periodic *p)
{
    void *b[] = {p->owner, p->neighbour, p->kind, p->length, p->enormal, p->ecentre, p->epoints};
    for (size_t i = 0; i < sizeof b / sizeof b[0]; ++i)
        free(b[i]);
    strip_mesh_free(p->sm);
    free(p);
}

/* A solver on mesh m with a uniform layer h0 moving at u0 down the strip
 * (along the face plane's s direction) */
static gf_surface *uniform_layer(const gf_surface_mesh *m, const gf_surface_config *c, double h0, double u0)
{
    gf_surface *s = NULL;
    if (gf_surface_alloc(m, c, &s))
        fail_msg("gf_surface_alloc: %s", gf_error_detail());
    const size_t nf = m->n_faces;
    double *h = malloc(nf * sizeof *h), *mom = malloc(3 * nf * sizeof *mom);
    for (size_t f = 0; f < nf; ++f) {
        const double *n = m->normal + 3 * f; /* the downslope tangent: (-n_z, 0, n_x) normalised */
        const double tx = n[2], tz = -n[0], l = sqrt(tx * tx + tz * tz);
        h[f] = h0;
        mom[3 * f] = h0 * u0 * tx / l, mom[3 * f + 1] = 0.0, mom[3 * f + 2] = h0 * u0 * tz / l;
    }
    assert_int_equal(gf_surface_set_state(s, h, mom), GF_SUCCESS);
    free(h), free(mom);
    return s;
}

/* mean, smallest and largest thickness and speed of the owned faces */
typedef struct layer {
    double h, hmin, hmax, u, umin, umax, mom; /* mom: sum A |h u| */
} layer;

static layer layer_of(const gf_surface *s, const gf_surface_mesh *m)
{
    layer L = {0, HUGE_VAL, 0, 0, HUGE_VAL, 0, 0};
    const double *h = gf_surface_h(s), *mo = gf_surface_momentum(s);
    double area = 0.0;
    for (size_t f = 0; f < m->n_faces; ++f) {
        const double *q = mo + 3 * f, M = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]), u = h[f] > 0 ? M / h[f] : 0;
        L.h += m->area[f] * h[f], L.u += m->area[f] * u, L.mom += m->area[f] * M, area += m->area[f];
        L.hmin = fmin(L.hmin, h[f]), L.hmax = fmax(L.hmax, h[f]);
        L.umin = fmin(L.umin, u), L.umax = fmax(L.umax, u);
    }
    L.h /= area, L.u /= area;
    return L;
}

static double *filled(size_t n, double v)
{
    double *a = malloc(n * sizeof *a);
    for (size_t i = 0; i < n; ++i)
        a[i] = v;
    return a;
}

static double min_of(const double *a, size_t n)
{
    double v = HUGE_VAL;
    for (size_t i = 0; i < n; ++i)
        v = fmin(v, a[i]);
    return v;
}

static void coulomb(gf_surface_config *c, double mu)
{
    assert_int_equal(gf_friction_init(&c->friction, "coulomb"), GF_SUCCESS);
    assert_int_equal(gf_friction_set(&c->friction, "mu", mu), GF_SUCCESS);
    assert_int_equal(gf_friction_set(&c->friction, "u0", 0.0), GF_SUCCESS);
}

/* The eroding layer of the next two tests: h0 1 m at 5 m/s on a 30 deg
 * periodic plane (10 x 3 faces of 2 m) whose Coulomb friction mu = tan
 * 30 deg balances gravity, rho 200, simType ent with the defaults and
 * hent0 of snow on every face */
static const double BAL_ZETA = 30.0, BAL_H0 = 1.0, BAL_U0 = 5.0;
static gf_surface *balanced_layer(double hent0, periodic **p, gf_surface_config *c, gf_mass_exchange_config *x)
{
    *p = periodic_new(10, 3, 20, 6, BAL_ZETA);
    gf_surface_config_default(c);
    c->rho = 200.0;
    coulomb(c, tan(BAL_ZETA * GF_DEG));
    gf_surface *s = uniform_layer(&(*p)->m, c, BAL_H0, BAL_U0);
    gf_mass_exchange_config_default(x);
    assert_int_equal(gf_mass_exchange_simtype(x, "ent"), GF_SUCCESS);
    double *hent = filled((*p)->m.n_faces, hent0);
    assert_int_equal(gf_surface_set_mass_exchange(s, x, hent, NULL), GF_SUCCESS);
    free(hent);
    return s;
}

/* Erosion (spec §1) on a uniform layer (h0 1 m, 5 m/s) sliding on a 30 deg
 * periodic plane whose Coulomb friction mu = tan 30 deg balances gravity:
 * the net force is 0 at any thickness, so the momentum per area M = h|u|
 * is conserved, τ_b = mu rho g cos(zeta) h and the mass grows at
 *   rho dh/dt = τ_b |u| / e_b = rho g sin(zeta) M / e_b,
 * a constant: h(t) = h0 + g sin(zeta) M t / e_b, |u| = M / h.  Asserted to
 * 1e-12 relative over 20 s (ρ = 200, e_b = 5000 J/kg: +9.8 cm); the layer
 * (2 m at 100 kg/m^3) loses rho/rho_ent times the flow's gain, the
 * entrained-depth field and volume match, the layer stays uniform. */
static void erosion_grows_mass_at_tau_u_over_eb(void **state)
{
    (void)state;
    const double zeta = BAL_ZETA, h0 = BAL_H0, u0 = BAL_U0, hent0 = 2.0, t_end = 20.0;
    periodic *p;
    gf_surface_config c;
    gf_mass_exchange_config x;
    gf_surface *s = balanced_layer(hent0, &p, &c, &x);
    const size_t nf = p->m.n_faces;
    const double v0 = gf_surface_volume(s), M = h0 * u0, rate = G * sin(zeta * GF_DEG) * M / x.e_b;
    double t = 0.0, worst_rate = 0.0;
    long steps = 0;
    while (t < t_end - 1e-12) {
        double dt;
        assert_int_equal(gf_surface_max_dt(s, &dt), GF_SUCCESS);
        dt = fmin(dt, t_end - t);
        const layer b = layer_of(s, &p->m);
        assert_int_equal(gf_surface_step(s, dt), GF_SUCCESS);
        t += dt, ++steps;
        /* this step's growth against τ_b|u|/e_b of the state (per area, / rho) */
        gf_surface_exchange ex;
        gf_surface_get_exchange(s, &ex);
        const double tau_u = tan(zeta * GF_DEG) * c.rho * G * cos(zeta * GF_DEG) * b.h * b.u;
        worst_rate = fmax(worst_rate, fabs(ex.entrained_step / (v0 / h0) / dt - tau_u / x.e_b / c.rho) /
                                          (tau_u / x.e_b / c.rho));
    }
    const layer L = layer_of(s, &p->m);
    const double h_exact = h0 + rate * t_end, e_h = fabs(L.h - h_exact) / h_exact;
    const double e_m = fabs(L.mom / (v0 / h0) - M) / M, e_u = fabs(L.u - M / h_exact) / (M / h_exact);
    const double *hl = gf_surface_entrainable_depth(s), *ed = gf_surface_entrained_depth(s);
    double e_layer = 0.0, e_ed = 0.0;
    for (size_t f = 0; f < nf; ++f) {
        e_layer = fmax(e_layer, fabs(hl[f] - (hent0 - c.rho / x.rho_ent * (h_exact - h0))));
        e_ed = fmax(e_ed, fabs(ed[f] - (h_exact - h0)));
    }
    gf_surface_exchange ex;
    gf_surface_get_exchange(s, &ex);
    const double e_vol = fabs(ex.entrained - (gf_surface_volume(s) - v0)) / v0;
    printf("  erosion, 30 deg, %ld steps to t = %g: h %.12f (exact %.12f, rel. error %.1e), growth rate vs "
           "tau_b|u|/e_b %.1e, h|u| %.1e, |u| %.1e, layer %.1e m, entrained depth %.1e m, volume %.1e, spread "
           "%.1e\n", steps, t_end, L.h, h_exact, e_h, worst_rate, e_m, e_u, e_layer, e_ed, e_vol, L.hmax - L.hmin);
    gf_verify("h0 + g sin(zeta) M t / e_b", "relative error of h", e_h, "<=", 1e-12,
              "erosion on a uniform layer, 30 deg, mu = tan 30 deg, t = %g s", t_end);
    gf_verify("h|u| = M (momentum kept)", "relative error of h|u|", e_m, "<=", 1e-12,
              "erosion on a uniform layer, 30 deg, mu = tan 30 deg, t = %g s", t_end);
    assert_true(e_h <= 1e-12 && worst_rate <= 1e-12 && e_m <= 1e-12 && e_u <= 1e-12);
    assert_true(e_layer <= 1e-12 && e_ed <= 1e-12 && e_vol <= 1e-12);
    assert_true(L.hmax - L.hmin <= 1e-12);
    assert_true(L.h - h0 > 0.09); /* it did grow: 9.8 cm */
    gf_surface_free(s);
    periodic_free(p);
}

/* The erosion integrated pointwise in time (gf_mass_exchange_face_update)
 * on a frictionless plane with a prescribed τ_b = 100 Pa (the spec's
 * driver, held fixed): mass m and momentum P = m|u| of a face (A = 4 m^2,
 * m0 = 800 kg, 8 m/s); the snow joins at rest, so P stays m0 u0 to 1e-13
 * while m grows; the closed form of dm/dt = τ_b (P/m) A / e_b is
 * m(t)^2 = m0^2 + 2 τ_b P A t / e_b, approached at first order in dt (the
 * step takes the rate at its start): the error halves with dt. */
static void erosion_keeps_momentum_pointwise(void **state)
{
    (void)state;
    gf_mass_exchange_config x;
    gf_mass_exchange_config_default(&x);
    x.entrainment = 1;
    const double rho = 200.0, A = 4.0, h0 = 1.0, u0 = 8.0, tau = 100.0, t_end = 50.0;
    const double m0 = rho * A * h0, P = m0 * u0, m_exact = sqrt(m0 * m0 + 2.0 * tau * P * A * t_end / x.e_b);
    double err[3];
    for (int k = 0; k < 3; ++k) {
        const int n = 250 << k;
        const double dt = t_end / n;
        gf_mass_exchange_face f = {h0, u0, A, rho, tau, 100.0, 100.0, 0.0};
        double e_p = 0.0;
        for (int i = 0; i < n; ++i) {
            gf_mass_exchange_result r;
            assert_int_equal(gf_mass_exchange_face_update(&x, &f, dt, &r), GF_SUCCESS);
            assert_true(r.mom_factor == 1.0); /* momentum h|u| per area untouched */
            f.h = r.h, f.speed = r.speed, f.h_ent = r.h_ent;
            e_p = fmax(e_p, fabs(rho * A * f.h * f.speed - P) / P);
        }
        err[k] = fabs(rho * A * f.h - m_exact) / m_exact;
        printf("  erosion pointwise, tau_b 100 Pa, dt %.4f: m %.6f kg (closed form %.6f), rel. error %.2e, "
               "m|u| drift %.1e\n", dt, rho * A * f.h, m_exact, err[k], e_p);
        assert_true(e_p <= 1e-13);
    }
    const double order = log2(err[1] / err[2]);
    printf("  observed order %.3f\n", order);
    gf_verify("m^2 = m0^2 + 2 tau_b P A t / e_b", "observed order in dt", order, ">=", 0.95,
              "erosion pointwise, frictionless, tau_b prescribed");
    assert_true(err[0] < 1e-3 && order >= 0.95 && order <= 1.05);
}

/* Ploughing (spec §1, e_b = 0) pointwise: a front at constant 0.5 m/s
 * crossing a face of 4 m^2 (w = 2 m) with a layer of q = 30 kg/m^2 takes
 * q w |u| t, the swept layer, until t = √A/|u| = 4 s, then exactly the
 * whole layer q A = 120 kg and nothing more; the layer never goes
 * negative.  In the scheme (flat frictionless periodic strip, 2 m faces,
 * h0 0.5 m at 4 m/s, layer 0.2 m at 100 kg/m^3): each step takes the swept
 * layer of each face, (rho_ent h_ent/rho) √A |u| dt / A in flow thickness
 * with |u| the step's, to 1e-12; the layer is gone once the front has
 * travelled √A (sum of |u| dt), and the total momentum stays to 1e-12. */
static void ploughing_takes_the_swept_layer(void **state)
{
    (void)state;
    gf_mass_exchange_config x;
    gf_mass_exchange_config_default(&x);
    x.entrainment = 1;
    x.e_b = 0.0;
    {
        const double A = 4.0, u = 0.5, q = 30.0, dt = 0.1;
        double taken = 0.0, qe = q, worst = 0.0;
        for (int i = 1; i <= 60; ++i) {
            const double dm = gf_entrainment_mass(&x, 0.0, u, A, dt, qe, q);
            taken += dm;
            qe = fmax(0.0, qe - dm / A);
            const double t = i * dt, swept = t < sqrt(A) / u ? q * sqrt(A) * u * t : q * A;
            worst = fmax(worst, fabs(taken - swept) / (q * A));
            assert_true(qe >= 0.0);
        }
        printf("  ploughing pointwise: taken %.12f kg of q A = %.12f, worst |taken - swept layer| %.1e q A\n", taken,
               q * A, worst);
        assert_true(worst <= 1e-12);
        assert_close(taken, q * A, 1e-12 * q * A);
    }
    periodic *p = periodic_new(8, 2, 16, 4, 0.0);
    const size_t nf = p->m.n_faces;
    gf_surface_config c;
    gf_surface_config_default(&c);
    c.rho = 200.0;
    const double h0 = 0.5, u0 = 4.0, hent0 = 0.2, A = p->m.area[0];
    gf_surface *s = uniform_layer(&p->m, &c, h0, u0);
    double *hent = filled(nf, hent0);
    assert_int_equal(gf_surface_set_mass_exchange(s, &x, hent, NULL), GF_SUCCESS);
    const double v0 = gf_surface_volume(s), P0 = layer_of(s, &p->m).mom;
    double t = 0.0, travel = 0.0, worst = 0.0, cleared_at = -1.0, travel_before = 0.0;
    for (int n = 0; n < 400 && t < 3.0; ++n) {
        double dt;
        assert_int_equal(gf_surface_max_dt(s, &dt), GF_SUCCESS);
        const layer b = layer_of(s, &p->m);
        const double left = min_of(gf_surface_entrainable_depth(s), nf);
        assert_int_equal(gf_surface_step(s, dt), GF_SUCCESS);
        gf_surface_exchange ex;
        gf_surface_get_exchange(s, &ex);
        const double swept = x.rho_ent * hent0 / c.rho * sqrt(A) * b.u * dt / A * (v0 / h0);
        const double cap = x.rho_ent * left / c.rho * (v0 / h0);
        worst = fmax(worst, fabs(ex.entrained_step - fmin(swept, cap)) / fmin(swept, cap == 0 ? 1 : cap));
        travel_before = travel;
        travel += b.u * dt;
        t += dt;
        if (cleared_at < 0 && min_of(gf_surface_entrainable_depth(s), nf) == 0.0 &&
            gf_surface_entrainable_depth(s)[0] == 0.0)
            cleared_at = travel;
        if (cleared_at < 0)
            assert_true(travel < sqrt(A) * (1 + 1e-12));
        assert_true(min_of(gf_surface_entrainable_depth(s), nf) >= 0.0);
    }
    (void)travel_before;
    gf_surface_exchange ex;
    gf_surface_get_exchange(s, &ex);
    const layer L = layer_of(s, &p->m);
    const double whole = x.rho_ent * hent0 / c.rho * v0 / h0, e_tot = fabs(ex.entrained - whole) / whole;
    const double e_p = fabs(L.mom - P0) / P0;
    printf("  ploughing in the scheme: per step vs swept layer %.1e, layer gone after a travel of %.4f m "
           "(sqrt A = %.4f), total %.1e of the layer, momentum %.1e, u %.4f -> %.4f m/s\n",
           worst, cleared_at, sqrt(A), e_tot, e_p, u0, L.u);
    gf_verify("swept layer q w |u| dt", "relative error per step", worst, "<=", 1e-12,
              "ploughing, flat frictionless periodic strip");
    assert_true(worst <= 1e-12);
    assert_true(cleared_at >= sqrt(A) * (1 - 1e-12) && cleared_at < sqrt(A) + 0.5);
    assert_true(e_tot <= 1e-12 && e_p <= 1e-12);
    assert_close(L.u, u0 * h0 / (h0 + whole / (v0 / h0)), 1e-12 * u0); /* momentum kept: u = P / m */
    gf_surface_free(s);
    periodic_free(p);
    free(hent);
}

/* A layer that runs out stops taking (spec §1: Δm <= q_ent A): the eroding
 * layer of the first test, 1 cm of snow (the flow can gain rho_ent/rho
 * 1 cm = 5 mm), on the 30 deg balanced plane for 3 s (runs out near
 * 1.02 s): the entrainable depth is never negative, ends at 0 exactly on
 * every face, the flow gained exactly the layer (to 1e-12) and nothing
 * after, and h|u| is kept throughout. */
static void a_layer_that_runs_out_stops_taking(void **state)
{
    (void)state;
    const double zeta = BAL_ZETA, h0 = BAL_H0, u0 = BAL_U0, hent0 = 0.01;
    periodic *p;
    gf_surface_config c;
    gf_mass_exchange_config x;
    gf_surface *s = balanced_layer(hent0, &p, &c, &x);
    const size_t nf = p->m.n_faces;
    const double gain = x.rho_ent / c.rho * hent0, v0 = gf_surface_volume(s);
    double t = 0.0, lowest = HUGE_VAL, t_out = -1.0;
    while (t < 3.0 - 1e-12) {
        double dt;
        assert_int_equal(gf_surface_max_dt(s, &dt), GF_SUCCESS);
        dt = fmin(dt, 3.0 - t);
        assert_int_equal(gf_surface_step(s, dt), GF_SUCCESS);
        t += dt;
        const double *hl = gf_surface_entrainable_depth(s);
        lowest = fmin(lowest, min_of(hl, nf));
        gf_surface_exchange ex;
        gf_surface_get_exchange(s, &ex);
        if (t_out < 0 && hl[0] == 0.0)
            t_out = t;
        else if (t_out >= 0)
            assert_true(ex.entrained_step == 0.0); /* stopped taking */
    }
    const layer L = layer_of(s, &p->m);
    const double *hl = gf_surface_entrainable_depth(s);
    double hl_max = 0.0;
    for (size_t f = 0; f < nf; ++f)
        hl_max = fmax(hl_max, hl[f]);
    gf_surface_exchange ex;
    gf_surface_get_exchange(s, &ex);
    const double e_gain = fabs(L.h - h0 - gain) / gain, e_m = fabs(L.mom / (v0 / h0) - h0 * u0) / (h0 * u0);
    const double t_exact = gain / (G * sin(zeta * GF_DEG) * h0 * u0 / x.e_b);
    printf("  layer of %g m runs out at t = %.4f s (closed form %.4f s): layer min %.1e, max %.1e at the end; "
           "flow gained %.12f m (the layer: %.12f, rel. error %.1e), entrained volume %.1e, h|u| %.1e\n",
           hent0, t_out, t_exact, lowest, hl_max, L.h - h0, gain, e_gain,
           fabs(ex.entrained - gain * v0 / h0) / (gain * v0 / h0), e_m);
    gf_verify("rho_ent h_ent / rho", "relative error of the thickness gained", e_gain, "<=", 1e-12,
              "a layer of 1 cm that runs out, 30 deg balanced plane, t = 3 s");
    assert_true(lowest >= 0.0 && hl_max == 0.0);
    assert_true(e_gain <= 1e-12 && e_m <= 1e-12);
    assert_true(fabs(ex.entrained - gain * v0 / h0) <= 1e-12 * gain * v0 / h0);
    assert_true(t_out > t_exact - 0.2 && t_out < t_exact + 0.2); /* within a step or two (dt ~0.1 s) */
    gf_surface_free(s);
    periodic_free(p);
}

/* Detrainment (spec §2) over a resistance area covering a flat frictionless
 * periodic strip: a layer of 0.2 m at 2 m/s (below v_min and h_min: the
 * detrainment window) loses ṁ = K/|u| per area while keeping its speed, so
 *   h(t) = h0 - K t / (rho |u|)  (rho 200, K 5 Pa: 12.5 mm/s, empty at 16 s);
 * asserted to 1e-12 at 4, 8 and 12 s with |u| = 2 m/s to 1e-12; at 20 s
 * every face is empty (h = 0 exactly) and the detrained volume is the
 * initial volume to 1e-12. */
static void detrainment_loses_mass_as_k_over_u(void **state)
{
    (void)state;
    periodic *p = periodic_new(8, 2, 16, 4, 0.0);
    const size_t nf = p->m.n_faces;
    gf_surface_config c;
    gf_surface_config_default(&c);
    c.rho = 200.0;
    const double h0 = 0.2, u0 = 2.0;
    gf_surface *s = uniform_layer(&p->m, &c, h0, u0);
    gf_mass_exchange_config x;
    gf_mass_exchange_config_default(&x);
    assert_int_equal(gf_mass_exchange_simtype(&x, "res"), GF_SUCCESS);
    double *res = filled(nf, 1.0);
    assert_int_equal(gf_surface_set_mass_exchange(s, &x, NULL, res), GF_SUCCESS);
    const double v0 = gf_surface_volume(s), rate = x.K / (c.rho * u0);
    double t = 0.0, worst = 0.0, worst_u = 0.0;
    for (int k = 1; k <= 4; ++k) {
        const double t_end = k < 4 ? 4.0 * k : 20.0;
        assert_true(surface_advance(s, &t, t_end) > 0);
        const layer L = layer_of(s, &p->m);
        if (k < 4) {
            const double e = fabs(L.h - (h0 - rate * t_end)) / h0;
            worst = fmax(worst, e);
            worst_u = fmax(worst_u, fmax(L.umax - u0, u0 - L.umin) / u0);
            printf("  detrainment, t = %4.1f s: h %.12f (closed form %.12f), rel. error %.1e, |u| %.15f..%.15f\n",
                   t_end, L.h, h0 - rate * t_end, e, L.umin, L.umax);
        } else {
            gf_surface_exchange ex;
            gf_surface_get_exchange(s, &ex);
            printf("  detrainment, t = 20 s: h max %.1e, |detrained volume - initial volume| %.1e relative\n", L.hmax,
                   fabs(ex.detrained - v0) / v0);
            assert_true(L.hmax == 0.0);
            assert_true(fabs(ex.detrained - v0) <= 1e-12 * v0);
            /* all of it in the speed window (2 m/s < v_min), none at rest */
            assert_true(ex.detrained_slow == ex.detrained && ex.detrained_rest == 0.0);
            const double *dd = gf_surface_detrained_depth(s);
            for (size_t f = 0; f < nf; ++f)
                assert_close(dd[f], h0, 1e-12 * h0);
        }
    }
    gf_verify("h0 - K t / (rho |u|)", "relative error of h", worst, "<=", 1e-12,
              "detrainment over a resistance area, 2 m/s, 0.2 m");
    assert_true(worst <= 1e-12 && worst_u <= 1e-12);
    gf_surface_free(s);
    periodic_free(p);
    free(res);
}

/* |u| of a uniform layer (h 1 m, 10 m/s) on a flat frictionless periodic
 * strip of 5 m faces in a resistance area with detrainment off (the
 * increased friction everywhere, spec §2) after 10 s at a fixed step */
static double drag_speed(double dt, double *hdrift)
{
    periodic *p = periodic_new(6, 2, 30, 10, 0.0);
    const size_t nf = p->m.n_faces;
    gf_surface_config c;
    gf_surface_config_default(&c);
    c.rho = 200.0;
    gf_surface *s = uniform_layer(&p->m, &c, 1.0, 10.0);
    gf_mass_exchange_config x;
    gf_mass_exchange_config_default(&x);
    x.resistance = 1;
    x.detrainment = 0;
    double *res = filled(nf, 1.0);
    assert_int_equal(gf_surface_set_mass_exchange(s, &x, NULL, res), GF_SUCCESS);
    const int n = (int)lround(10.0 / dt);
    for (int i = 0; i < n; ++i)
        assert_int_equal(gf_surface_step(s, dt), GF_SUCCESS);
    const layer L = layer_of(s, &p->m);
    *hdrift = fmax(L.hmax - 1.0, 1.0 - L.hmin);
    gf_surface_free(s);
    periodic_free(p);
    free(res);
    return L.u;
}

/* The increased friction (spec §2: F = -c_res rho A |u|^2 u/|u|, implicit)
 * on a frictionless flat plane: u(t) = u0 / (1 + c_res u0 t / h), 10 -> 5 m/s
 * over 10 s (c_res 0.01, h 1 m).  Backward Euler in the pointwise update:
 * first order in dt (as the scheme's implicit friction); measured at
 * dt = 0.1 .. 0.0125 s: error 3.4e-3 relative at 0.1 s (bound 4e-3), observed order
 * 1 +- 0.05; h unchanged to 1e-12. */
static void increased_friction_slows_as_closed_form(void **state)
{
    (void)state;
    const double u_exact = 10.0 / (1.0 + 0.01 * 10.0 * 10.0 / 1.0);
    double err[4], drift = 0.0;
    for (int k = 0; k < 4; ++k) {
        const double dt = 0.1 / (1 << k);
        double hd;
        const double u = drag_speed(dt, &hd);
        err[k] = fabs(u - u_exact) / u_exact;
        drift = fmax(drift, hd);
        printf("  increased friction, dt = %.4f s: u(10 s) = %.10f m/s (closed form %.10f), rel. error %.3e%s",
               dt, u, u_exact, err[k], k ? "" : "\n");
        if (k)
            printf(", order %.3f\n", log2(err[k - 1] / err[k]));
    }
    const double order = log2(err[2] / err[3]);
    gf_verify("u0 / (1 + c_res u0 t / h)", "relative error at dt = 0.1 s", err[0], "<=", 4e-3,
              "increased friction, frictionless flat plane, 10 -> 5 m/s in 10 s");
    gf_verify("u0 / (1 + c_res u0 t / h)", "observed order in dt", order, ">=", 0.95,
              "increased friction, dt 0.025 -> 0.0125 s");
    assert_true(err[0] <= 4e-3);
    for (int k = 1; k < 4; ++k)
        assert_true(fabs(log2(err[k - 1] / err[k]) - 1.0) <= 0.05);
    assert_true(drift <= 1e-12);
}

/* The split of the detrained volume by the face's speed (gf_surface_exchange,
 * spec §2): one step of 0.1 s over the frictionless periodic strip, all of it
 * a resistance area, a 0.2 m layer (below h_min) at rest: the whole layer
 * goes (K/|u| unbounded), all of it in the speed window and at rest; at
 * 10 m/s (above v_min, detrained by the thickness window): K dt/(rho |u|),
 * none of it in the speed window; at 2 m/s: all in the window, none at rest. */
static void detrained_volume_split_by_speed(void **state)
{
    (void)state;
    const double speeds[3] = {0.0, 10.0, 2.0};
    for (int k = 0; k < 3; ++k) {
        periodic *p = periodic_new(8, 2, 16, 4, 0.0);
        gf_surface_config c;
        gf_surface_config_default(&c);
        c.rho = 200.0;
        gf_surface *s = uniform_layer(&p->m, &c, 0.2, speeds[k]);
        gf_mass_exchange_config x;
        gf_mass_exchange_config_default(&x);
        assert_int_equal(gf_mass_exchange_simtype(&x, "res"), GF_SUCCESS);
        double *res = filled(p->m.n_faces, 1.0);
        assert_int_equal(gf_surface_set_mass_exchange(s, &x, NULL, res), GF_SUCCESS);
        const double v0 = gf_surface_volume(s);
        assert_int_equal(gf_surface_step(s, 0.1), GF_SUCCESS);
        gf_surface_exchange ex;
        gf_surface_get_exchange(s, &ex);
        printf("  |u| %4.1f m/s: detrained %.6e m^3 (of %.6e), in the speed window %.6e, at rest %.6e\n", speeds[k],
               ex.detrained_step, v0, ex.detrained_slow_step, ex.detrained_rest_step);
        assert_true(ex.detrained_step == ex.detrained && ex.detrained_slow_step == ex.detrained_slow &&
                    ex.detrained_rest_step == ex.detrained_rest);
        if (k == 0) {
            assert_close(ex.detrained, v0, 1e-12 * v0);
            assert_true(ex.detrained_slow == ex.detrained && ex.detrained_rest == ex.detrained);
        } else {
            assert_close(ex.detrained, v0 * x.K * 0.1 / (c.rho * speeds[k] * 0.2), 1e-9 * v0);
            assert_true(ex.detrained_rest == 0.0);
            assert_true(k == 1 ? ex.detrained_slow == 0.0 : ex.detrained_slow == ex.detrained);
        }
        gf_surface_free(s);
        periodic_free(p);
        free(res);
    }
}

/* The windows of spec §2 choose the process: pointwise at the edges of the
 * default windows (v 6..40 m/s, h 0.6..10 m) and with detrainment off; in
 * the scheme the layer of the previous test with detrainment on slows by
 * the increased friction only (nothing detrained, h kept) while |u| >= 6,
 * then detrains only (|u| kept, h falling at K/(rho |u|)) from the first
 * step that starts below 6 m/s (closed form: t = 6.67 s). */
static void windows_switch_the_right_process(void **state)
{
    (void)state;
    gf_mass_exchange_config x;
    gf_mass_exchange_config_default(&x);
    x.resistance = 1;
    const struct {
        double u, h;
        gf_resistance_process want;
    } cases[] = {{5.999, 1.0, GF_RESISTANCE_DETRAIN}, {6.0, 1.0, GF_RESISTANCE_FRICTION},
                 {10.0, 0.599, GF_RESISTANCE_DETRAIN}, {10.0, 0.6, GF_RESISTANCE_FRICTION},
                 {40.0, 10.0, GF_RESISTANCE_FRICTION}, {40.001, 1.0, GF_RESISTANCE_NONE},
                 {10.0, 10.001, GF_RESISTANCE_NONE}, {50.0, 0.5, GF_RESISTANCE_DETRAIN},
                 {0.0, 0.0, GF_RESISTANCE_DETRAIN}};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        assert_int_equal(gf_resistance_window(&x, cases[i].u, cases[i].h), cases[i].want);
        /* the face update applies exactly that process */
        const gf_mass_exchange_face f = {cases[i].h, cases[i].u, 1.0, 200.0, 0.0, 0.0, 0.0, 1.0};
        gf_mass_exchange_result r;
        assert_int_equal(gf_mass_exchange_face_update(&x, &f, 0.1, &r), GF_SUCCESS);
        assert_int_equal(r.process, cases[i].want);
        assert_true((r.detrained > 0.0) == (cases[i].want == GF_RESISTANCE_DETRAIN && cases[i].h > 0.0));
        assert_true((r.speed < cases[i].u) == (cases[i].want == GF_RESISTANCE_FRICTION));
    }
    /* at rest the rate K/|u| is unbounded: the whole mass; with K = 0 (or a
     * step of 0) no rate and nothing, at rest too (detK 0 once detrained a
     * face at rest entirely) */
    assert_true(gf_detrainment_mass(&x, 0.0, 50.0, 1.0, 0.1) == 50.0);
    assert_true(gf_detrainment_mass(&x, 0.0, 50.0, 1.0, 0.0) == 0.0);
    x.K = 0.0;
    assert_true(gf_detrainment_mass(&x, 0.0, 50.0, 1.0, 0.1) == 0.0);
    assert_true(gf_detrainment_mass(&x, 2.0, 50.0, 1.0, 0.1) == 0.0);
    {
        const gf_mass_exchange_face rest = {0.3, 0.0, 1.0, 200.0, 0.0, 0.0, 0.0, 1.0};
        gf_mass_exchange_result rr;
        assert_int_equal(gf_mass_exchange_face_update(&x, &rest, 0.1, &rr), GF_SUCCESS);
        assert_true(rr.process == GF_RESISTANCE_DETRAIN && rr.h == 0.3 && rr.detrained == 0.0);
    }
    x.K = 5.0;
    x.detrainment = 0;
    assert_int_equal(gf_resistance_window(&x, 1.0, 0.1), GF_RESISTANCE_FRICTION);
    assert_int_equal(gf_resistance_window(&x, 50.0, 20.0), GF_RESISTANCE_FRICTION);
    x.detrainment = 1;
    /* outside a resistance area (factor 0) nothing, whatever the window */
    const gf_mass_exchange_face out = {0.3, 2.0, 1.0, 200.0, 0.0, 0.0, 0.0, 0.0};
    gf_mass_exchange_result r;
    assert_int_equal(gf_mass_exchange_face_update(&x, &out, 0.1, &r), GF_SUCCESS);
    assert_true(r.process == GF_RESISTANCE_NONE && r.h == 0.3 && r.speed == 2.0);

    periodic *p = periodic_new(6, 2, 30, 10, 0.0);
    const size_t nf = p->m.n_faces;
    gf_surface_config c;
    gf_surface_config_default(&c);
    c.rho = 200.0;
    gf_surface *s = uniform_layer(&p->m, &c, 1.0, 10.0);
    double *res = filled(nf, 1.0);
    assert_int_equal(gf_surface_set_mass_exchange(s, &x, NULL, res), GF_SUCCESS);
    const double dt = 0.05, v0 = gf_surface_volume(s);
    double t_switch = -1.0, u_switch = 0.0;
    int bad = 0;
    for (int i = 0; i < 300; ++i) {
        const layer b = layer_of(s, &p->m);
        assert_int_equal(gf_surface_step(s, dt), GF_SUCCESS);
        const layer a = layer_of(s, &p->m);
        gf_surface_exchange ex;
        gf_surface_get_exchange(s, &ex);
        if (b.u >= x.v_min) { /* friction: slower, nothing detrained */
            bad += !(a.u < b.u && ex.detrained_step == 0.0 && fabs(a.h - b.h) <= 1e-12);
        } else { /* detrainment: |u| kept, h down by K dt/(rho |u|) */
            if (t_switch < 0)
                t_switch = i * dt, u_switch = b.u;
            bad += !(fabs(a.u - b.u) <= 1e-12 * b.u &&
                     fabs(ex.detrained_step / (v0 / 1.0) - x.K * dt / (c.rho * b.u)) <= 1e-12);
        }
    }
    const double t_closed = (10.0 / x.v_min - 1.0) / (0.01 * 10.0);
    printf("  windows in the scheme: friction until t = %.2f s (closed form %.2f s), then detrainment at %.4f m/s; "
           "%d steps with the wrong process\n", t_switch, t_closed, u_switch, bad);
    assert_int_equal(bad, 0);
    assert_true(fabs(t_switch - t_closed) < 0.1 && u_switch < x.v_min && u_switch > 5.9);
    gf_surface_free(s);
    periodic_free(p);
    free(res);
}

/* A pile (paraboloid, 0.5 m high, radius 2 m, at s = 2.5) on a 35 deg
 * strip 20 m x 6 m of nx x ny faces with walls on three sides and an
 * outflow edge at the bottom, Coulomb 20 deg, rho 200; returns the initial
 * thickness (allocated), the mesh and configuration out */
static double *outflow_pile(size_t nx, size_t ny, strip_mesh **sm, gf_surface_config *c)
{
    static double zeta = 35 * GF_DEG;
    const int kinds[4] = {GF_EDGE_WALL, GF_EDGE_OUTFLOW, GF_EDGE_WALL, GF_EDGE_WALL};
    *sm = strip_mesh_new(nx, ny, 0, 20, -3, 3, const_zeta, &zeta, kinds);
    gf_surface_config_default(c);
    c->rho = 200.0;
    coulomb(c, tan(20 * GF_DEG));
    const size_t nf = (*sm)->m.n_faces;
    double *h = calloc(nf, sizeof *h);
    for (size_t f = 0; f < nf; ++f) {
        const double sf = (*sm)->s_of_face[f], y = (*sm)->centre[3 * f + 1], r2 = (sf - 2.5) * (sf - 2.5) + y * y;
        h[f] = r2 < 4.0 ? 0.5 * (1.0 - r2 / 4.0) : 0.0;
    }
    return h;
}

/* Mass balance with the exchange (spec §1, last line): the outflow pile
 * (60 x 16 faces) slides over an entrainment band (0.3 m of snow for
 * 5 < s < 11, e_b 200 J/kg) and a resistance band (13 < s < 16), simType
 * entres, for 4 s: at every step
 *   volume + outflow - entrained + detrained = initial
 * to 1e-12 relative; each term is exercised (entrained, detrained, outflow
 * all > 1% of the initial volume) and the layer stays >= 0. */
static void mass_balance_with_exchange(void **state)
{
    (void)state;
    strip_mesh *sm;
    gf_surface_config c;
    double *h = outflow_pile(60, 16, &sm, &c);
    const size_t nf = sm->m.n_faces;
    gf_surface *s = NULL;
    assert_int_equal(gf_surface_alloc(&sm->m, &c, &s), GF_SUCCESS);
    double *hent = calloc(nf, sizeof *hent), *res = calloc(nf, sizeof *res);
    for (size_t f = 0; f < nf; ++f) {
        const double sf = sm->s_of_face[f];
        hent[f] = sf > 5.0 && sf < 11.0 ? 0.3 : 0.0;
        res[f] = sf > 13.0 && sf < 16.0 ? 1.0 : 0.0;
    }
    assert_int_equal(gf_surface_set_state(s, h, NULL), GF_SUCCESS);
    gf_mass_exchange_config x;
    gf_mass_exchange_config_default(&x);
    assert_int_equal(gf_mass_exchange_simtype(&x, "entres"), GF_SUCCESS);
    x.e_b = 200.0; /* erodible snow, so that entrainment is a visible term of the balance */
    assert_int_equal(gf_surface_set_mass_exchange(s, &x, hent, res), GF_SUCCESS);
    const double v0 = gf_surface_volume(s);
    double t = 0.0, worst = 0.0, out = 0.0, lowest = HUGE_VAL;
    gf_surface_exchange ex;
    long steps = 0;
    while (t < 4.0 - 1e-12) {
        double dt;
        assert_int_equal(gf_surface_max_dt(s, &dt), GF_SUCCESS);
        dt = fmin(dt, 4.0 - t);
        assert_int_equal(gf_surface_step(s, dt), GF_SUCCESS);
        t += dt, ++steps;
        const double *ev = gf_surface_edge_volume(s);
        out = 0.0;
        for (size_t e = 0; e < sm->m.n_edges; ++e)
            if (sm->m.kind[e] != GF_EDGE_INTERNAL)
                out += ev[e];
        gf_surface_get_exchange(s, &ex);
        const double bal = gf_surface_volume(s) + out - ex.entrained + ex.detrained;
        worst = fmax(worst, fabs(bal - v0) / v0);
        lowest = fmin(lowest, min_of(gf_surface_entrainable_depth(s), nf));
    }
    printf("  mass balance, %ld steps to t = 4 s: initial %.4f m^3, now %.4f, outflow %.4f, entrained %.4f, "
           "detrained %.4f; worst |balance - initial| %.1e relative; layer min %.2e\n",
           steps, v0, gf_surface_volume(s), out, ex.entrained, ex.detrained, worst, lowest);
    gf_verify("initial volume", "worst relative balance error over all steps", worst, "<=", 1e-12,
              "pile over entrainment and resistance bands with an outflow edge, simType entres, t = 4 s");
    assert_true(worst <= 1e-12);
    assert_true(ex.entrained > 0.01 * v0 && ex.detrained > 0.01 * v0 && out > 0.01 * v0);
    assert_true(lowest >= 0.0);
    /* the per-face fields sum to the totals */
    const double *ed = gf_surface_entrained_depth(s), *dd = gf_surface_detrained_depth(s);
    double se = 0.0, sd = 0.0;
    for (size_t f = 0; f < nf; ++f)
        se += sm->area[f] * ed[f], sd += sm->area[f] * dd[f];
    assert_close(se, ex.entrained, 1e-12 * v0);
    assert_close(sd, ex.detrained, 1e-12 * v0);
    gf_surface_free(s);
    strip_mesh_free(sm);
    free(h), free(hent), free(res);
}

/* A restart (gf_surface_restore and gf_surface_restore_mass_exchange)
 * continues the exchanging run bit for bit: the outflow pile (40 x 12
 * faces) over a ploughed band (e_b 0, 4 < s < 12) overlapping a
 * resistance band (7 < s < 12), restarted after 20 steps with part of the
 * layer still untouched: the next 60 equal the uninterrupted run's
 * in h, momentum, layer left, entrained and detrained depths and totals. */
static void restart_continues_the_exchange_exactly(void **state)
{
    (void)state;
    strip_mesh *sm;
    gf_surface_config c;
    double *h = outflow_pile(40, 12, &sm, &c);
    const size_t nf = sm->m.n_faces;
    double *hent = calloc(nf, sizeof *hent), *res = calloc(nf, sizeof *res);
    for (size_t f = 0; f < nf; ++f) {
        hent[f] = sm->s_of_face[f] > 4.0 && sm->s_of_face[f] < 12.0 ? 0.3 : 0.0;
        res[f] = sm->s_of_face[f] > 7.0 && sm->s_of_face[f] < 12.0 ? 1.0 : 0.0;
    }
    gf_mass_exchange_config x;
    gf_mass_exchange_config_default(&x);
    assert_int_equal(gf_mass_exchange_simtype(&x, "entres"), GF_SUCCESS);
    x.e_b = 0.0;
    gf_surface *a = NULL, *b = NULL;
    assert_int_equal(gf_surface_alloc(&sm->m, &c, &a), GF_SUCCESS);
    assert_int_equal(gf_surface_alloc(&sm->m, &c, &b), GF_SUCCESS);
    assert_int_equal(gf_surface_set_state(a, h, NULL), GF_SUCCESS);
    assert_int_equal(gf_surface_set_mass_exchange(a, &x, hent, res), GF_SUCCESS);
    assert_int_equal(gf_surface_restore_mass_exchange(b, NULL, NULL, NULL, NULL), GF_EINVAL);
    for (int n = 0; n < 20; ++n) {
        double dt;
        assert_int_equal(gf_surface_max_dt(a, &dt), GF_SUCCESS);
        assert_int_equal(gf_surface_step(a, dt), GF_SUCCESS);
    }
    gf_surface_exchange ea, eb;
    gf_surface_get_exchange(a, &ea);
    printf("  at the restart: entrained %.6f m^3 of %.6f, detrained %.6f\n", ea.entrained, 0.15 * 8 * 6,
           ea.detrained);
    assert_true(ea.entrained > 0.0 && ea.entrained < 0.9 * 0.15 * 8 * 6 && ea.detrained > 0.0);
    assert_int_equal(gf_surface_restore(b, gf_surface_h(a), gf_surface_momentum(a), gf_surface_normal_acceleration(a)),
                     GF_SUCCESS);
    assert_int_equal(gf_surface_set_mass_exchange(b, &x, hent, res), GF_SUCCESS);
    double *bad = filled(nf, 0.0);
    bad[7] = 0.5; /* above the layer set */
    assert_int_equal(gf_surface_restore_mass_exchange(b, bad, NULL, NULL, NULL), GF_EDOM);
    assert_non_null(strstr(gf_error_detail(), "face 7"));
    assert_int_equal(gf_surface_restore_mass_exchange(b, gf_surface_entrainable_depth(a), gf_surface_entrained_depth(a),
                                                      gf_surface_detrained_depth(a), &ea),
                     GF_SUCCESS);
    int same = 1;
    for (int n = 0; n < 60; ++n) {
        double dta, dtb;
        assert_int_equal(gf_surface_max_dt(a, &dta), GF_SUCCESS);
        assert_int_equal(gf_surface_max_dt(b, &dtb), GF_SUCCESS);
        assert_true(dta == dtb);
        assert_int_equal(gf_surface_step(a, dta), GF_SUCCESS);
        assert_int_equal(gf_surface_step(b, dtb), GF_SUCCESS);
        same &= !memcmp(gf_surface_h(a), gf_surface_h(b), nf * sizeof(double)) &&
                !memcmp(gf_surface_momentum(a), gf_surface_momentum(b), 3 * nf * sizeof(double)) &&
                !memcmp(gf_surface_entrainable_depth(a), gf_surface_entrainable_depth(b), nf * sizeof(double)) &&
                !memcmp(gf_surface_entrained_depth(a), gf_surface_entrained_depth(b), nf * sizeof(double)) &&
                !memcmp(gf_surface_detrained_depth(a), gf_surface_detrained_depth(b), nf * sizeof(double));
    }
    gf_surface_get_exchange(a, &ea);
    gf_surface_get_exchange(b, &eb);
    printf("  restart with mass exchange after 20 steps: the next 60 steps %s; entrained %.6f / %.6f m^3, "
           "detrained %.6f / %.6f\n", same ? "bit for bit" : "DIFFER", ea.entrained, eb.entrained, ea.detrained,
           eb.detrained);
    assert_true(same);
    assert_memory_equal(&ea, &eb, sizeof ea);
    gf_surface_free(a), gf_surface_free(b);
    free(h), free(hent), free(res), free(bad);
    strip_mesh_free(sm);
}

/* simType null, or entres with no entrainable snow and no resistance
 * anywhere, gives bit for bit the run without mass exchange (the outflow
 * pile, 40 x 12 faces, 2 s). */
static void null_exchange_is_bit_identical(void **state)
{
    (void)state;
    strip_mesh *sm;
    gf_surface_config c;
    double *h = outflow_pile(40, 12, &sm, &c);
    const size_t nf = sm->m.n_faces;
    double *zero = calloc(nf, sizeof *zero);
    double *hr = NULL, *mr = NULL;
    for (int mode = 0; mode < 3; ++mode) {
        gf_surface *s = NULL;
        assert_int_equal(gf_surface_alloc(&sm->m, &c, &s), GF_SUCCESS);
        assert_int_equal(gf_surface_set_state(s, h, NULL), GF_SUCCESS);
        gf_mass_exchange_config x;
        gf_mass_exchange_config_default(&x);
        if (mode == 2)
            assert_int_equal(gf_mass_exchange_simtype(&x, "entres"), GF_SUCCESS);
        if (mode)
            assert_int_equal(gf_surface_set_mass_exchange(s, &x, zero, zero), GF_SUCCESS);
        assert_true((gf_surface_entrainable_depth(s) != NULL) == (mode == 2));
        double t = 0.0;
        assert_true(surface_advance(s, &t, 2.0) > 0);
        if (!mode) {
            hr = malloc(nf * sizeof *hr), mr = malloc(3 * nf * sizeof *mr);
            memcpy(hr, gf_surface_h(s), nf * sizeof *hr);
            memcpy(mr, gf_surface_momentum(s), 3 * nf * sizeof *mr);
        } else {
            assert_memory_equal(hr, gf_surface_h(s), nf * sizeof *hr);
            assert_memory_equal(mr, gf_surface_momentum(s), 3 * nf * sizeof *mr);
        }
        gf_surface_free(s);
    }
    printf("  simType null and entres without areas: h and momentum bit for bit those of the run without\n");
    free(hr), free(mr), free(h), free(zero);
    strip_mesh_free(sm);
}

/* Bad parameters are refused with a message naming them. */
static void bad_parameters_refused(void **state)
{
    (void)state;
    gf_mass_exchange_config x;
    struct {
        double *field;
        double v;
        gf_status want;
        const char *needle;
    } tests[] = {
        {&x.e_b, -1.0, GF_EDOM, "erosion energy e_b"},
        {&x.rho_ent, -100.0, GF_EDOM, "rho_ent"},
        {&x.rho_ent, 0.0, GF_EDOM, "rho_ent"},
        {&x.h_ent, -0.3, GF_EDOM, "h_ent"},
        {&x.e_s, -1.0, GF_EDOM, "e_s"},
        {&x.e_d, -1.0, GF_EDOM, "e_d"},
        {&x.K, NAN, GF_ENONFINITE, "K [Pa]"},
        {&x.c_res, -0.01, GF_EDOM, "c_res"},
        {&x.v_min, 50.0, GF_EDOM, "speed window inverted"},
        {&x.h_max, 0.5, GF_EDOM, "thickness window inverted"},
        {&x.v_max, INFINITY, GF_ENONFINITE, "v_max"},
    };
    for (size_t i = 0; i < sizeof tests / sizeof tests[0]; ++i) {
        gf_mass_exchange_config_default(&x);
        x.entrainment = 1;
        *tests[i].field = tests[i].v;
        const gf_status st = gf_mass_exchange_config_check(&x);
        printf("  refused (%s): %s\n", gf_strerror(st), gf_error_detail());
        assert_int_equal(st, tests[i].want);
        assert_non_null(strstr(gf_error_detail(), tests[i].needle));
    }
    gf_mass_exchange_config_default(&x);
    assert_int_equal(gf_mass_exchange_config_check(&x), GF_SUCCESS);
    x.detrainment = 2;
    assert_int_equal(gf_mass_exchange_config_check(&x), GF_EINVAL);
    assert_non_null(strstr(gf_error_detail(), "detrainment"));
    gf_mass_exchange_config_default(&x);
    assert_int_equal(gf_mass_exchange_simtype(&x, "entrainment"), GF_ENOTFOUND);
    printf("  refused: %s\n", gf_error_detail());
    assert_non_null(strstr(gf_error_detail(), "null, ent, res, entres"));
    /* the scheme: a bad configuration, a missing or bad field, the start-up refinement */
    strip_mesh *sm = strip_mesh_new(4, 2, 0, 4, -1, 1, NULL, NULL, WALLS);
    const size_t nf = sm->m.n_faces;
    gf_surface_config c;
    gf_surface_config_default(&c);
    gf_surface *s = NULL;
    assert_int_equal(gf_surface_alloc(&sm->m, &c, &s), GF_SUCCESS);
    double *hent = filled(nf, 0.3), *res = filled(nf, 1.0);
    gf_mass_exchange_config_default(&x);
    assert_int_equal(gf_mass_exchange_simtype(&x, "entres"), GF_SUCCESS);
    x.e_b = -5.0;
    assert_int_equal(gf_surface_set_mass_exchange(s, &x, hent, res), GF_EDOM);
    assert_non_null(strstr(gf_error_detail(), "e_b"));
    x.e_b = 5000.0;
    assert_int_equal(gf_surface_set_mass_exchange(s, &x, NULL, res), GF_EINVAL);
    printf("  refused: %s\n", gf_error_detail());
    assert_non_null(strstr(gf_error_detail(), "entrainable depth"));
    assert_int_equal(gf_surface_set_mass_exchange(s, &x, hent, NULL), GF_EINVAL);
    assert_non_null(strstr(gf_error_detail(), "resistance"));
    hent[3] = -0.1;
    assert_int_equal(gf_surface_set_mass_exchange(s, &x, hent, res), GF_EDOM);
    printf("  refused: %s\n", gf_error_detail());
    assert_non_null(strstr(gf_error_detail(), "face 3"));
    hent[3] = 0.3, res[5] = NAN;
    assert_int_equal(gf_surface_set_mass_exchange(s, &x, hent, res), GF_ENONFINITE);
    assert_non_null(strstr(gf_error_detail(), "face 5"));
    res[5] = 1.0;
    assert_int_equal(gf_surface_set_mass_exchange(s, &x, hent, res), GF_SUCCESS);
    assert_non_null(gf_surface_entrainable_depth(s));
    gf_surface_free(s);
    c.startup_levels = 1;
    assert_int_equal(gf_surface_alloc(&sm->m, &c, &s), GF_SUCCESS);
    assert_int_equal(gf_surface_set_mass_exchange(s, &x, hent, res), GF_EINVAL);
    printf("  refused: %s\n", gf_error_detail());
    assert_non_null(strstr(gf_error_detail(), "startup_levels"));
    assert_null(gf_surface_entrainable_depth(s));
    gf_surface_free(s);
    /* the pointwise update: a negative thickness, a non-finite step */
    gf_mass_exchange_face f = {-1.0, 1.0, 1.0, 200.0, 0.0, 0.0, 0.0, 0.0};
    gf_mass_exchange_result r;
    assert_int_equal(gf_mass_exchange_face_update(&x, &f, 0.1, &r), GF_EDOM);
    assert_non_null(strstr(gf_error_detail(), "flow thickness"));
    f.h = 1.0;
    assert_int_equal(gf_mass_exchange_face_update(&x, &f, NAN, &r), GF_ENONFINITE);
    assert_non_null(strstr(gf_error_detail(), "time step"));
    free(hent), free(res);
    strip_mesh_free(sm);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(erosion_grows_mass_at_tau_u_over_eb),
        cmocka_unit_test(erosion_keeps_momentum_pointwise),
        cmocka_unit_test(ploughing_takes_the_swept_layer),
        cmocka_unit_test(a_layer_that_runs_out_stops_taking),
        cmocka_unit_test(detrainment_loses_mass_as_k_over_u),
        cmocka_unit_test(detrained_volume_split_by_speed),
        cmocka_unit_test(increased_friction_slows_as_closed_form),
        cmocka_unit_test(windows_switch_the_right_process),
        cmocka_unit_test(mass_balance_with_exchange),
        cmocka_unit_test(restart_continues_the_exchange_exactly),
        cmocka_unit_test(null_exchange_is_bit_identical),
        cmocka_unit_test(bad_parameters_refused),
    };
    return gf_run_tests("tests", tests, NULL, NULL);
}
