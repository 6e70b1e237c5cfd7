/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Internal interface between the 1D driver (sh1d.c) and the schemes. */
#ifndef GRANFLOW_SH1D_INTERNAL_H
#define GRANFLOW_SH1D_INTERNAL_H

#include "granflow/sh1d.h"

#include <math.h>

struct gf_sh1d_type {
    const char *name;
    gf_status (*init)(gf_sh1d *s);                   /* allocate s->impl, check options */
    void (*free)(gf_sh1d *s);
    gf_status (*set_initial)(gf_sh1d *s, gf_sh1d_initial_fn fn, void *ctx);
    double (*max_dt)(const gf_sh1d *s);              /* CFL step at Courant number cfl */
    gf_status (*step)(gf_sh1d *s, double dt);
    void (*means)(const gf_sh1d *s, double *h, double *q);
    void (*eval)(const gf_sh1d *s, size_t cell, double xi, double *h, double *q);
    double (*min_depth)(const gf_sh1d *s);
    /* the state of `coarse` from `fine`, a solver of the same type and
     * configuration on twice the cells: the L2 projection (cell means
     * exactly), then the scheme's limiting as after set_initial */
    gf_status (*restrict_from)(gf_sh1d *coarse, const gf_sh1d *fine);
    /* the largest |u| + sqrt(beta h) of the state (the start-up's length);
     * NULL: the speed of max_dt's step bound */
    double (*wave_speed)(const gf_sh1d *s);
    /* how many cells the dam-break fan spans when the start-up refinement
     * ends; NULL: STARTUP_CELLS (sh1d.c) */
    double (*startup_cells)(const gf_sh1d *s);
    /* the step that lands a moving boundary on the domain's end (like an
     * output time: not a stability bound, so a fixed dt is shortened to it);
     * NULL or HUGE_VAL: none */
    double (*landing_dt)(const gf_sh1d *s);
};

struct gf_sh1d {
    const gf_sh1d_type *type;
    gf_sh1d_config cfg;
    size_t n;
    double dx, t, cfl;
    double x0;                   /* left end of the grid: x_min, or the moving mesh's left
                                    node (moving_mesh; dx then changes with time too) */
    size_t steps;
    double outflow;              /* mass out through the ends since set_initial (gf_sh1d_outflow) */
    size_t rejected;             /* steps repeated with a smaller dt (positivity) */
    double *scratch;             /* 2 n: cell means for checks and diagnostics */
    void *impl;
    gf_sh1d *startup;            /* start-up refinement: the finest grid at t = 0, taken by
                                    the first step; NULL otherwise */
    double t_startup;            /* its end time (set by set_initial) */
    /* breakpoints of the initial data being projected (the Riemann start's
     * fan edges: kinks of a piecewise polynomial; set_initial only) */
    double breaks[4];
    int nbreaks;
    size_t startup_steps;
};

/* The cells lo..hi (1-based, ghosts 0 and n + 1) that a step of either
 * scheme can change: within 4 cells of one whose values (stride per cell in
 * h and q, ghost-indexed) are not all exactly 0; hi = 0 when every cell is
 * dry; every cell with a periodic boundary. */
void gf_sh1d_active_range(const gf_sh1d *s, const double *h, const double *q, size_t stride, size_t *lo,
                          size_t *hi);

/* The end of the initial data's wet set between a dry point and a wet one
 * (bisection to round-off). */
double gf_sh1d_wet_end(gf_sh1d_initial_fn fn, void *ctx, double dry, double wet);

/* The Legendre moments sum_g w_g h P_m(xi_g) and sum_g w_g h u P_m(xi_g),
 * m < M, of the initial data on the cell of centre xc and width dx, with the
 * Gauss rule (xg, wg, ng) on [-1, 1]: the caller scales them to the L2
 * projection's coefficients.  Where breakpoints (s->breaks) lie inside the
 * cell the rule is applied on each piece, so that piecewise polynomial data
 * are integrated exactly; without one, the operations are those of one rule.
 * GF_EDOM, naming x, for a value that is not finite or a negative depth. */
gf_status gf_sh1d_project_cell(const gf_sh1d *s, gf_sh1d_initial_fn fn, void *ctx, double xc, double dx,
                               const double *xg, const double *wg, int ng, int M, double *hm, double *qm);

/* The wet interval [xl, xr] of the initial data: sampled 16 times per cell
 * of the fixed grid (every sample checked: finite, h >= 0), its ends found
 * by bisection where the data are dry beyond them (*dry_l, *dry_r), else
 * the domain's ends. */
gf_status gf_sh1d_wet_interval(const gf_sh1d *s, gf_sh1d_initial_fn fn, void *ctx, double *xl, double *xr,
                               int *dry_l, int *dry_r);

/* Inclination and curvature at x (constant zeta when no topography). */
void gf_sh1d_bed(const gf_sh1d *s, double x, double *zeta, double *kappa);

/* Earth-pressure coefficient times epsilon cos(zeta): beta. */
double gf_sh1d_beta(const gf_sh1d *s, double zeta, double dudx);

/* Basal friction per unit density |tau_b|/rho >= 0 at depth h, velocity u. */
double gf_sh1d_friction(const gf_sh1d *s, double h, double u, double zeta, double kappa);
/* the same from cos(zeta) */
double gf_sh1d_friction_c(const gf_sh1d *s, double h, double u, double cos_zeta, double kappa);

/* Static friction bound at rest, per unit density: the law with u0 = 0 at
 * speed 0 (mu h g cos(zeta) for Coulomb). */
double gf_sh1d_static_friction(const gf_sh1d *s, double h, double zeta);

/* The 5-point Gauss–Legendre rule on [-1, 1] (weights sum to 2), from GSL's
 * glfixed table: initial projections and L1 differences. */
gf_status gf_gauss_legendre5(double x[5], double w[5]);

/* minmod: of the arguments the one nearest 0 where all have one sign, else
 * 0 (RKDG's limiters: three; the kinetic order-2 slopes: two) */
static inline double gf_sh1d_minmod3(double a, double b, double c)
{
    if (a > 0.0 && b > 0.0 && c > 0.0)
        return fmin(a, fmin(b, c));
    if (a < 0.0 && b < 0.0 && c < 0.0)
        return fmax(a, fmax(b, c));
    return 0.0;
}
static inline double gf_sh1d_minmod(double a, double b) { return gf_sh1d_minmod3(a, b, b); }

/* The Legendre polynomial P_m(x), m = 0, 1, 2 (the RKDG modes, the
 * initial projection's weights). */
static inline double gf_sh1d_legendre(int m, double x)
{
    return m == 0 ? 1.0 : m == 1 ? x : 0.5 * (3.0 * x * x - 1.0);
}

/* Velocity q/h, 0 where h <= h_eps. */
static inline double gf_sh1d_velocity(const gf_sh1d *s, double h, double q)
{
    return h > s->cfg.h_eps ? q / h : 0.0;
}

#endif
