/* SPDX-License-Identifier: GPL-3.0-or-later */
#include "granflow/kinetic1d.h"
#include "granflow/source.h"
#include "internal.h"
#include "sh1d_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct kinetic {
    double *h, *q;          /* n + 2 with one ghost cell each side */
    double *beta;           /* per cell, n + 2 */
    double *f1, *f2;        /* interface fluxes, n + 1 (interface i between cells i, i+1) */
    unsigned char *slow;    /* per cell */
    unsigned char *mod;     /* per interface: modified flux */
    unsigned char *first;   /* per interface: first-order states (kinetic_order 2) */
    double *hn, *qn;        /* new depth and discharge */
    double *dh, *du;        /* kinetic_order 2: limited slopes of h and u per cell (n + 2) */
    double *h0, *q0;        /* kinetic_order 2: the state at the start of the step */
    /* the cells a step computes, lo..hi (gf_sh1d_active_range); outside them h and q
     * are exactly 0 and stay so */
    size_t lo, hi;
} kinetic;

void gf_kinetic_half_fluxes(double h, double u, double beta, double p[2], double n[2])
{
    if (!(h > 0.0)) {
        p[0] = p[1] = n[0] = n[1] = 0.0;
        return;
    }
    const double c = sqrt(2.0 * beta * h);
    double a = -u / c;
    if (a <= -1.0) { /* all particles move right */
        p[0] = h * u;
        p[1] = h * u * u + 0.5 * beta * h * h;
        n[0] = n[1] = 0.0;
        return;
    }
    if (a >= 1.0) {
        n[0] = h * u;
        n[1] = h * u * u + 0.5 * beta * h * h;
        p[0] = p[1] = 0.0;
        return;
    }
    const double th = asin(a);
    const double j0 = 0.25 * GF_PI - 0.5 * th - 0.25 * sin(2.0 * th);
    const double j1 = pow(1.0 - a * a, 1.5) / 3.0;
    const double j2 = GF_PI / 16.0 - th / 8.0 + sin(4.0 * th) / 32.0;
    const double k0 = 0.5 * GF_PI - j0, k2 = 0.125 * GF_PI - j2;
    const double f = 2.0 * h / GF_PI;
    p[0] = f * (u * j0 + c * j1);
    p[1] = f * (u * u * j0 + 2.0 * u * c * j1 + c * c * j2);
    n[0] = f * (u * k0 - c * j1);
    n[1] = f * (u * u * k0 - 2.0 * u * c * j1 + c * c * k2);
}

static void kinetic_free(gf_sh1d *s)
{
    kinetic *k = s->impl;
    if (!k)
        return;
    free(k->h);    /* the block of all double arrays */
    free(k->slow); /* the block of both flag arrays */
    free(k);
    s->impl = NULL;
}

static gf_status kinetic_init(gf_sh1d *s)
{
    if (s->cfg.topo)
        return gf_fail(GF_EINVAL, "the kinetic schemes are formulated for a constant inclination "
                                  "(doc/theory/one-d-schemes.md, kinetic schemes); use rkdg for a curved chute");
    if (s->cfg.moving_mesh)
        return gf_fail(GF_EINVAL, "moving_mesh = 1 is an RKDG option; the kinetic schemes run on the fixed grid");
    kinetic *k = calloc(1, sizeof *k);
    if (!k)
        return gf_fail(GF_ENOMEM, "kinetic: out of memory");
    const size_t n = s->n;
    if (s->cfg.kinetic_order == 2 && s->cfg.scheme == 2) {
        free(k);
        return gf_fail(GF_EINVAL, "kinetic_order = 2 needs scheme 1 or 3: Scheme 2 takes the modified "
                                  "flux of the cell means at every interface, so nothing is reconstructed");
    }
    /* one block: h, q, beta, hn, qn, dh, du, h0, q0 (n+2 each), f1, f2 (n+1 each); flags separately */
    double *blk = calloc(9 * (n + 2) + 2 * (n + 1), sizeof *blk);
    unsigned char *flags = calloc(3 * (n + 2), 1);
    if (!blk || !flags) {
        free(blk);
        free(flags);
        free(k);
        return gf_fail(GF_ENOMEM, "kinetic: out of memory");
    }
    k->h = blk;
    k->q = blk + (n + 2);
    k->beta = blk + 2 * (n + 2);
    k->hn = blk + 3 * (n + 2);
    k->qn = blk + 4 * (n + 2);
    k->dh = blk + 5 * (n + 2);
    k->du = blk + 6 * (n + 2);
    k->h0 = blk + 7 * (n + 2);
    k->q0 = blk + 8 * (n + 2);
    k->f1 = blk + 9 * (n + 2);
    k->f2 = k->f1 + (n + 1);
    k->slow = flags;
    k->mod = flags + (n + 2);
    k->first = flags + 2 * (n + 2);
    k->lo = 1, k->hi = n;
    s->impl = k;
    /* second order: the cell's mass leaves through both of its reconstructed
     * edge states, each carrying half of it (h = (h_L + h_R)/2), so the
     * positivity bound of Theorem 3 halves */
    s->cfl = s->cfg.cfl > 0.0 ? s->cfg.cfl : s->cfg.kinetic_order == 2 ? 0.45 : 0.9;
    return GF_SUCCESS;
}

static void fill_ghosts(const gf_sh1d *s, double *h, double *q)
{
    const size_t n = s->n;
    switch (s->cfg.bc_left) {
    case GF_BC_PERIODIC: h[0] = h[n]; q[0] = q[n]; break;
    case GF_BC_WALL: h[0] = h[1]; q[0] = -q[1]; break;
    default: h[0] = h[1]; q[0] = q[1]; break;
    }
    switch (s->cfg.bc_right) {
    case GF_BC_PERIODIC: h[n + 1] = h[1]; q[n + 1] = q[1]; break;
    case GF_BC_WALL: h[n + 1] = h[n]; q[n + 1] = -q[n]; break;
    default: h[n + 1] = h[n]; q[n + 1] = q[n]; break;
    }
}

/* Gauss quadrature of the initial data to cell means. */
static gf_status kinetic_set_initial(gf_sh1d *s, gf_sh1d_initial_fn fn, void *ctx)
{
    kinetic *k = s->impl;
    static const double xg[3] = {-0.774596669241483377, 0.0, 0.774596669241483377};
    static const double wg[3] = {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};
    for (size_t i = 0; i < s->n; ++i) {
        double hm, qm; /* the weights sum to 1: the means */
        gf_status st = gf_sh1d_project_cell(s, fn, ctx, gf_sh1d_cell_centre(s, i), s->dx, xg, wg, 3, 1, &hm, &qm);
        if (st)
            return st;
        k->h[i + 1] = hm;
        k->q[i + 1] = hm > s->cfg.h_eps ? qm : 0.0;
    }
    fill_ghosts(s, k->h, k->q);
    return GF_SUCCESS;
}

/* Cell means of the fine solver's pairs of cells. */
static gf_status kinetic_restrict_from(gf_sh1d *s, const gf_sh1d *fs)
{
    kinetic *k = s->impl;
    const kinetic *f = fs->impl;
    for (size_t i = 0; i < s->n; ++i) {
        const double hm = 0.5 * (f->h[2 * i + 1] + f->h[2 * i + 2]);
        k->h[i + 1] = hm;
        k->q[i + 1] = hm > s->cfg.h_eps ? 0.5 * (f->q[2 * i + 1] + f->q[2 * i + 2]) : 0.0;
    }
    fill_ghosts(s, k->h, k->q);
    return GF_SUCCESS;
}

static void update_beta(const gf_sh1d *s, kinetic *k)
{
    for (size_t i = k->lo; i <= k->hi; ++i) {
        const double ul = gf_sh1d_velocity(s, k->h[i - 1], k->q[i - 1]);
        const double ur = gf_sh1d_velocity(s, k->h[i + 1], k->q[i + 1]);
        k->beta[i] = gf_sh1d_beta(s, s->cfg.zeta, ur - ul);
    }
    k->beta[0] = k->beta[1];
    k->beta[s->n + 1] = k->beta[s->n];
}

/* kinetic_order 2 (the higher-order method the kinetic paper leaves to
 * future work, section 6): slopes per cell (differences over one cell) of h
 * and of u = q/h, minmod-limited against both neighbours; u only where the
 * cell and both neighbours are wet (a dry cell has no velocity), else 0.  Ghosts:
 * periodic copies; a wall's mirror image (h even, u odd: dh_0 = -dh_1,
 * du_0 = du_1); zero-gradient boundaries constant (no slope). */
static void cell_slopes(const gf_sh1d *s, const kinetic *k, size_t i, double *dh, double *du)
{
    const double he = s->cfg.h_eps, *h = k->h;
    *dh = gf_sh1d_minmod(h[i + 1] - h[i], h[i] - h[i - 1]);
    *du = 0.0;
    if (h[i - 1] <= he || h[i] <= he || h[i + 1] <= he)
        return;
    const double u = gf_sh1d_velocity(s, h[i], k->q[i]);
    const double ul = gf_sh1d_velocity(s, h[i - 1], k->q[i - 1]), ur = gf_sh1d_velocity(s, h[i + 1], k->q[i + 1]);
    *du = gf_sh1d_minmod(u - ul, ur - u);
}

static void slopes(const gf_sh1d *s, kinetic *k)
{
    const size_t n = s->n;
    for (size_t i = k->lo; i <= k->hi; ++i)
        cell_slopes(s, k, i, &k->dh[i], &k->du[i]);
    switch (s->cfg.bc_left) {
    case GF_BC_PERIODIC: k->dh[0] = k->dh[n], k->du[0] = k->du[n]; break;
    case GF_BC_WALL: k->dh[0] = -k->dh[1], k->du[0] = k->du[1]; break;
    default: k->dh[0] = k->du[0] = 0.0; break;
    }
    switch (s->cfg.bc_right) {
    case GF_BC_PERIODIC: k->dh[n + 1] = k->dh[1], k->du[n + 1] = k->du[1]; break;
    case GF_BC_WALL: k->dh[n + 1] = -k->dh[n], k->du[n + 1] = k->du[n]; break;
    default: k->dh[n + 1] = k->du[n + 1] = 0.0; break;
    }
}

/* The states at interface f (between cells f and f+1) that the kinetic
 * fluxes take: the cell means, or with kinetic_order 2 the reconstructed
 * edge values, except at an interface between two slow cells (the modified
 * flux of a pile at rest: its rest balance is that of the means), one that
 * positivity put back to first order, and one next to a dry cell (towards a
 * dry cell the wet cell's mean, so the tip of a front is not reconstructed
 * to zero).  An interface with the modified flux between a slow and a
 * moving cell takes the reconstructed states. */
static void interface_states(const gf_sh1d *s, const kinetic *k, size_t f, double *hl, double *ul, double *hr,
                             double *ur)
{
    *hl = k->h[f], *hr = k->h[f + 1];
    *ul = gf_sh1d_velocity(s, *hl, k->q[f]), *ur = gf_sh1d_velocity(s, *hr, k->q[f + 1]);
    if (s->cfg.kinetic_order != 2 || (k->mod[f] && k->slow[f] && k->slow[f + 1]) || k->first[f] ||
        *hl <= s->cfg.h_eps || *hr <= s->cfg.h_eps)
        return;
    *hl += 0.5 * k->dh[f], *ul += 0.5 * k->du[f];
    *hr -= 0.5 * k->dh[f + 1], *ur -= 0.5 * k->du[f + 1];
}

static double kinetic_max_dt(const gf_sh1d *s)
{
    kinetic *k = s->impl;
    gf_sh1d_active_range(s, k->h, k->q, 1, &k->lo, &k->hi);
    update_beta(s, k);
    const int o2 = s->cfg.kinetic_order == 2;
    if (o2)
        slopes(s, k);
    double smax = 0.0;
    for (size_t i = k->lo; i <= k->hi; ++i) {
        const double u = gf_sh1d_velocity(s, k->h[i], k->q[i]);
        smax = fmax(smax, fabs(u) + sqrt(2.0 * k->beta[i] * k->h[i])); /* Theorem 3 */
        if (o2 && k->h[i] > s->cfg.h_eps) /* and of the reconstructed edge states */
            for (int side = -1; side <= 1; side += 2) {
                const double he = k->h[i] + 0.5 * side * k->dh[i], ue = u + 0.5 * side * k->du[i];
                smax = fmax(smax, fabs(ue) + sqrt(2.0 * k->beta[i] * fmax(he, 0.0)));
            }
    }
    return smax > 0.0 ? s->cfl * s->dx / smax : HUGE_VAL;
}

/* The largest |u| + sqrt(beta h): the speed of the waves, below the step
 * bound's |u| + sqrt(2 beta h) (the start-up refinement's length). */
static double kinetic_wave_speed(const gf_sh1d *s)
{
    kinetic *k = s->impl;
    gf_sh1d_active_range(s, k->h, k->q, 1, &k->lo, &k->hi);
    update_beta(s, k);
    double a = 0.0;
    for (size_t i = 1; i <= s->n; ++i)
        a = fmax(a, fabs(gf_sh1d_velocity(s, k->h[i], k->q[i])) + sqrt(k->beta[i] * k->h[i]));
    return a;
}

/* g(u) = g sin zeta - sgn(u) tau/(rho h): net acceleration of a moving cell. */
static double accel(const gf_sh1d *s, double h, double u)
{
    const double gs = s->cfg.g * sin(s->cfg.zeta);
    if (u == 0.0 || h <= s->cfg.h_eps)
        return gs;
    return gf_sh_moving_accel(gs, gf_sh1d_friction(s, h, u, s->cfg.zeta, 0.0) / h, u);
}

/* g~ of the kinetic paper: beta dh/dx clamped to the static bounds. */
static double g_tilde(const gf_sh1d *s, const kinetic *k, size_t i)
{
    const double bdh = k->beta[i] * (k->h[i + 1] - k->h[i - 1]) / (2.0 * s->dx);
    const double gs = s->cfg.g * sin(s->cfg.zeta);
    const double r = k->h[i] > s->cfg.h_eps ? gf_sh1d_static_friction(s, k->h[i], s->cfg.zeta) / k->h[i]
                                             : 0.0;
    return gf_sh_clamp_static(gs, r, bdh);
}

static void interface_flux(const gf_sh1d *s, kinetic *k, size_t f)
{
    /* interface f between cells f and f+1 (ghost-indexed) */
    double hl, ul, hr, ur, pl[2], nl[2], pr[2], nr[2];
    interface_states(s, k, f, &hl, &ul, &hr, &ur);
    if (k->mod[f]) { /* eq. 25: mean depth, upwind velocity */
        const double hm = 0.5 * (hl + hr);
        gf_kinetic_half_fluxes(hm, ul, k->beta[f], pl, nl);
        gf_kinetic_half_fluxes(hm, ur, k->beta[f + 1], pr, nr);
    } else {
        gf_kinetic_half_fluxes(hl, ul, k->beta[f], pl, nl);
        gf_kinetic_half_fluxes(hr, ur, k->beta[f + 1], pr, nr);
    }
    k->f1[f] = pl[0] + nr[0];
    k->f2[f] = pl[1] + nr[1];
}

/* One forward-Euler step of the scheme: (k->h, k->q) -> itself; *out: the
 * mass it lets out through the domain's ends. */
static gf_status kinetic_stage(gf_sh1d *s, double dt, double *out)
{
    kinetic *k = s->impl;
    const size_t n = s->n;
    const double lam = dt / s->dx;
    const int scheme = s->cfg.scheme, o2 = s->cfg.kinetic_order == 2;
    fill_ghosts(s, k->h, k->q);
    update_beta(s, k);
    if (o2)
        slopes(s, k);
    memset(k->first, 0, n + 1);

    for (size_t i = k->lo - 1; i <= k->hi + 1; ++i) {
        const double u = gf_sh1d_velocity(s, k->h[i], k->q[i]);
        k->slow[i] = k->q[i] == 0.0 || fabs(k->q[i]) < fabs(dt * accel(s, k->h[i], u) * k->h[i]);
        /* kinetic_order 2: a dry cell is not slow, so the interface at a
         * front takes the standard flux.  The modified flux there (mean
         * depth of the tip and the dry cell) sends back the left-moving
         * half of a phantom state of that depth: the newly wetted cell gets
         * more momentum than mass, and at second order, without the first
         * order's diffusion, a film ran ahead of the front at twice the
         * front speed (Ritter). */
        if (o2 && k->h[i] <= s->cfg.h_eps)
            k->slow[i] = 0;
    }
    for (size_t f = k->lo - 1; f <= k->hi; ++f) {
        k->mod[f] = scheme == 2 || (scheme == 3 && (k->slow[f] || k->slow[f + 1]));
        interface_flux(s, k, f);
    }
    /* positivity fallback to the Scheme 1 flux (Theorem 3) */
    for (int pass = 0; pass < 8; ++pass) {
        int changed = 0;
        for (size_t i = k->lo; i <= k->hi; ++i) {
            k->hn[i] = k->h[i] - lam * (k->f1[i] - k->f1[i - 1]);
            if (k->hn[i] < 0.0 && (k->mod[i] || k->mod[i - 1] || (o2 && !(k->first[i] && k->first[i - 1])))) {
                k->mod[i] = k->mod[i - 1] = 0;
                k->first[i] = k->first[i - 1] = 1; /* kinetic_order 2: the cell means */
                interface_flux(s, k, i);
                interface_flux(s, k, i - 1);
                changed = 1;
            }
        }
        if (!changed)
            break;
    }
    /* the boundary fluxes, where computed (outside lo..hi every cell is dry) */
    *out = dt * ((k->hi == n ? k->f1[n] : 0.0) - (k->lo == 1 ? k->f1[0] : 0.0));
    for (size_t i = k->lo; i <= k->hi; ++i) {
        const double hn = k->hn[i];
        if (hn < 0.0)
            return gf_fail(GF_EPHYS, "kinetic scheme %d: negative depth %g in cell %zu at t = %g; "
                                     "lower the Courant number", scheme, hn, i - 1, s->t);
        const double q = k->q[i], h = k->h[i];
        const double u = gf_sh1d_velocity(s, h, q);
        const double dF = k->f2[i] - k->f2[i - 1];
        double qn;
        if (scheme != 1 && k->slow[i]) {
            /* Slow cell (starting, stopping, at rest): friction as an implicit
             * Coulomb update of the whole discrete force.  The trial momentum
             * q* = q - lam dF + dt g sin(zeta) hbar (hbar the weighted depth of
             * the paper's Scheme 2 source) is stopped when friction can hold
             * it, |q*| <= dt R hbar, and reduced by dt R hbar otherwise.  At
             * rest dF is the pressure difference beta (hm+^2 - hm-^2)/2 =
             * dx beta dh/dx hbar, so q* = dt hbar (g sin zeta - beta dh/dx) and
             * an admissible profile (kinetic paper, Def. 1) stays exactly at
             * rest at any time step.  (The paper's blend q = -lam dF +
             * (1 - mu) dt g~ hbar drops q and balances only beta dh/dx, not
             * the velocity-dependent part of the modified flux, so round-off
             * velocities at rest grew for Courant numbers above about 0.75.) */
            const double hbar = 0.25 * (k->h[i + 1] + 2.0 * h + k->h[i - 1]);
            const double r = h > s->cfg.h_eps ? gf_sh1d_static_friction(s, h, s->cfg.zeta) / h : 0.0;
            const double qs = q - lam * dF + dt * s->cfg.g * sin(s->cfg.zeta) * hbar;
            qn = gf_friction_decelerate(qs, dt * r * hbar);
        } else {
            const double a = u != 0.0 ? accel(s, h, u) : g_tilde(s, k, i);
            qn = q - lam * dF + dt * a * hn;
        }
        k->qn[i] = hn > s->cfg.h_eps ? qn : 0.0;
    }
    if (k->hi >= k->lo) {
        memcpy(k->h + k->lo, k->hn + k->lo, (k->hi - k->lo + 1) * sizeof *k->h);
        memcpy(k->q + k->lo, k->qn + k->lo, (k->hi - k->lo + 1) * sizeof *k->q);
    }
    fill_ghosts(s, k->h, k->q);
    return GF_SUCCESS;
}

/* kinetic_order 1: the paper's forward-Euler step.  2: Heun's method (the
 * two-stage SSP Runge-Kutta scheme), u^(1) = E(u^n), u^(n+1) = (u^n +
 * E(u^(1)))/2, with E the reconstructed step: a convex combination of
 * positivity-preserving steps stays positive, and a state at rest (every
 * interface slow, the means' rest balance) stays at rest in both stages. */
static gf_status kinetic_step(gf_sh1d *s, double dt)
{
    kinetic *k = s->impl;
    gf_sh1d_active_range(s, k->h, k->q, 1, &k->lo, &k->hi); /* for both stages */
    double o1, o2;
    gf_status st;
    if (s->cfg.kinetic_order != 2) {
        if (!(st = kinetic_stage(s, dt, &o1)))
            s->outflow += o1;
        return st;
    }
    const size_t n = s->n;
    memcpy(k->h0, k->h, (n + 2) * sizeof *k->h);
    memcpy(k->q0, k->q, (n + 2) * sizeof *k->q);
    if ((st = kinetic_stage(s, dt, &o1)) || (st = kinetic_stage(s, dt, &o2))) {
        memcpy(k->h, k->h0, (n + 2) * sizeof *k->h); /* the state changes only on success */
        memcpy(k->q, k->q0, (n + 2) * sizeof *k->q);
        return st;
    }
    for (size_t i = k->lo; i <= k->hi; ++i) {
        const double h = 0.5 * (k->h0[i] + k->h[i]);
        k->q[i] = h > s->cfg.h_eps ? 0.5 * (k->q0[i] + k->q[i]) : 0.0;
        k->h[i] = h;
    }
    s->outflow += 0.5 * (o1 + o2); /* the mass of (u^n + E(u^(1)))/2 */
    fill_ghosts(s, k->h, k->q);
    return GF_SUCCESS;
}

static void kinetic_means(const gf_sh1d *s, double *h, double *q)
{
    const kinetic *k = s->impl;
    memcpy(h, k->h + 1, s->n * sizeof *h);
    memcpy(q, k->q + 1, s->n * sizeof *q);
}

/* The cell mean, or with kinetic_order 2 the limited linear reconstruction
 * of h and u at xi in [-1, 1] (q = h u). */
static void kinetic_eval(const gf_sh1d *s, size_t cell, double xi, double *h, double *q)
{
    const kinetic *k = s->impl;
    *h = k->h[cell + 1];
    *q = k->q[cell + 1];
    if (s->cfg.kinetic_order != 2 || *h <= s->cfg.h_eps)
        return;
    double dh, du;
    cell_slopes(s, k, cell + 1, &dh, &du);
    const double u = gf_sh1d_velocity(s, *h, *q) + 0.5 * xi * du;
    *h = fmax(0.0, *h + 0.5 * xi * dh);
    *q = *h * u;
}

static double kinetic_min_depth(const gf_sh1d *s)
{
    const kinetic *k = s->impl;
    double m = HUGE_VAL;
    for (size_t i = 1; i <= s->n; ++i)
        m = fmin(m, k->h[i]);
    return m;
}

/* kinetic_order 2 ends the start-up refinement when the fan spans 60 cells
 * (RKDG: 40).  Its interface next to a dry cell takes the cell means (the
 * tip is not reconstructed), so a tip that is still steep when a coarser
 * level takes over costs it a few cells of front: with 40, five levels put
 * Ritter's h = 1e-3 front -3.6 / -4.9 / -3.4 cells behind at N = 400 / 800 /
 * 1600; with 60, -2.3 / -2.7 / -0.5 (the Coulomb incline +0.4 / +1.2 / +2.7,
 * was -0.6 / -0.6 / +0.7), L1 at N = 800 2.9e-3 instead of 3.5e-3.  At 80
 * the incline's front runs 3.4 cells ahead at N = 1600.  Order 1: 40 (its
 * lag grows with N whatever the start). */
static double kinetic_startup_cells(const gf_sh1d *s) { return s->cfg.kinetic_order == 2 ? 60.0 : 40.0; }

static const gf_sh1d_type kinetic_type = {
    "kinetic",     kinetic_init,  kinetic_free, kinetic_set_initial, kinetic_max_dt,
    kinetic_step,  kinetic_means, kinetic_eval,     kinetic_min_depth, kinetic_restrict_from,
    kinetic_wave_speed, kinetic_startup_cells, NULL,
};
const gf_sh1d_type *const gf_sh1d_kinetic = &kinetic_type;
