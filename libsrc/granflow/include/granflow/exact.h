/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * granflow — exact solutions of the 1D Savage–Hutter / shallow-water system
 * without source,
 *
 *     h_t + (hu)_x = 0,   (hu)_t + (hu^2 + beta h^2/2)_x = 0,
 *
 * with constant beta:  beta = epsilon K cos(zeta) in the dimensionless
 * Savage–Hutter form (kinetic paper eq. 1, section 4, first test; rkdg
 * eq. 1), beta = g for the dimensional shallow-water dam breaks of the
 * finite-area paper, section 6.1 (Stoker: wet downstream, Ritter: dry).
 *
 * The Riemann problem (h_l, u_l | h_r, u_r) at x0 is solved exactly: two
 * waves, each a rarefaction or a shock, the middle depth h_m from the root of
 *     f_l(h_m) + f_r(h_m) + u_r - u_l = 0,
 *     f_k(h) = 2 (sqrt(beta h) - sqrt(beta h_k))                 h <= h_k,
 *     f_k(h) = (h - h_k) sqrt(beta (h + h_k) / (2 h h_k))        h >  h_k,
 * found by GSL's Brent solver; dry states (h = 0) on either side and vacuum
 * in the middle are handled in closed form.  For u_l = u_r = 0, h_l > h_r > 0
 * it is the kinetic paper's section 4 solution (left rarefaction, right
 * shock with speed s = (h_m u_m - h_r u_r)/(h_m - h_r)).
 */
#ifndef GRANFLOW_EXACT_H
#define GRANFLOW_EXACT_H

#include "granflow/source.h" /* gf_sh_beta */
#include "granflow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct gf_riemann {
    double beta;
    double hl, ul, hr, ur, x0;
    double hm, um;   /* middle state (h_m = 0 when vacuum forms) */
    int vacuum;      /* 1 when a dry middle region separates the waves */
} gf_riemann;

/* Solve the Riemann problem.  beta > 0, depths >= 0, all finite. */
gf_status gf_riemann_solve(gf_riemann *rp, double beta, double hl, double ul, double hr,
                           double ur, double x0);

/* Exact h and u at (x, t), t > 0 (t = 0 gives the initial data). */
void gf_riemann_sample(const gf_riemann *rp, double x, double t, double *h, double *u);

/*
 * Dressler's dam break on a dry bed with Chezy friction (finite-area paper,
 * section 6.1.3, eq. 71; Dressler 1952, as collected by Delestre et al.
 * 2013, SWASHES):
 *
 *     h_t + (hu)_x = 0,   u_t + u u_x + g h_x = -g u|u| / (C^2 h),
 *
 * h = h_l for x < x0, h = 0 for x > x0, u = 0 at t = 0.  With X = x - x0,
 * c0 = sqrt(g h_l), xi = X / (c0 t) and f = g^2 t / C^2, Dressler's
 * first-order expansion in the resistance (outer region, -1 < xi < xi_tip):
 *
 *     h = (2 c0/3 - X/(3t) + f a1(xi))^2 / g,
 *     u =  2 c0/3 + 2X/(3t) + f a2(xi),
 *     a1 = 6/(5(2-xi)) - 2/3 + 4 sqrt3/135 (2-xi)^(3/2),
 *     a2 = 12/(2-xi) - 8/3 + 8 sqrt3/189 (2-xi)^(3/2) - 108/(7 (2-xi)^2).
 *
 * Both corrections vanish at xi = -1 (the still reservoir), and the
 * residual of the equations is second order in 1/C^2 (tests/unit/
 * test_exact.c checks both).  The expansion breaks down towards the front,
 * where u(X) would fall again; following Whitham (1955) and Valiani et al.
 * (2002) the tip region X_tip <= X <= X_front (X_tip: maximum of u) moves
 * with the uniform velocity u_tip = u(X_tip).  Our closure of the tip: the
 * momentum balance there is dominated by friction, g h_x = -g u_tip^2/(C^2 h),
 * so h = (u_tip/C) sqrt(2 (X_front - X)); X_front follows from mass
 * conservation (the tip holds the released volume h_l c0 t minus the volume
 * of the outer region).  This closure is ours: the SWASHES implementation of
 * the tip is not in the finite-area paper.  Valid while the reservoir is not
 * reached by the reflection from a wall and while f is small against c0.
 */
typedef struct gf_dressler {
    double g, hl, chezy, x0;
    /* set by gf_dressler_at() (or a sample at a new time) for its time t: */
    double t;
    double x_tip, u_tip, h_tip; /* where the outer region ends, u and outer h there */
    double x_front;             /* wet front (h = 0) */
} gf_dressler;

/* Parameters: g > 0, h_l > 0, Chezy C > 0, dam position x0. */
gf_status gf_dressler_init(gf_dressler *d, double g, double hl, double chezy, double x0);

/* Tip and front at time t > 0.  Fails (GF_EDOM) when the first-order
 * expansion no longer describes a flow (friction too strong for that t):
 * depth radicand negative before the tip, no volume left for the tip, or a
 * front ahead of Ritter's frictionless front x0 + 2 sqrt(g h_l) t. */
gf_status gf_dressler_at(gf_dressler *d, double t);

/* h and u at (x, t), as gf_riemann_sample: the tip and front of time t are
 * computed (gf_dressler_at) when t differs from the last one; its errors are
 * returned. */
gf_status gf_dressler_sample(gf_dressler *d, double x, double t, double *h, double *u);

/* Outer (first-order) expansion alone, at any (x, t > 0), for tests; the
 * still reservoir for xi <= -1, dry (h = u = 0) beyond Ritter's front. */
void gf_dressler_outer(const gf_dressler *d, double x, double t, double *h, double *u);

/*
 * Spreading parabolic cap on a flat frictionless bed: the self-similar
 * solution of the source-free system above with two dry fronts,
 *
 *     h = (h0/lam) (1 - X^2/(lam l0)^2)_+,   u = X lam'/lam,   X = x - x0,
 *
 * where the momentum equation reduces to lam'' = k/lam^2, k = 2 beta h0/l0^2,
 * lam(0) = 1, lam'(0) = 0.  Its energy integral lam'^2 = 2k(1 - 1/lam) gives
 * t(lam) = (sqrt(lam (lam - 1)) + ln(sqrt(lam) + sqrt(lam - 1))) / sqrt(2k),
 * inverted by GSL's Brent solver.  The fronts x0 +- lam l0 move at
 * l0 lam' -> 2 sqrt(beta h0), Ritter's front speed, as t -> infinity.
 * Smooth initial data with dry fronts: the 1D solvers' dry-front test
 * without the start-up error of a dam break.
 */
typedef struct gf_spreading_cap {
    double beta, h0, l0, x0;
} gf_spreading_cap;

/* beta > 0, h0 > 0, half-width l0 > 0, centre x0; all finite. */
gf_status gf_spreading_cap_init(gf_spreading_cap *c, double beta, double h0, double l0, double x0);

/* lam(t) and lam'(t) for t >= 0. */
gf_status gf_spreading_cap_stretch(const gf_spreading_cap *c, double t, double *lam, double *dlam);

/* h and u at (x, t >= 0); dry (0, 0) outside the fronts.  Fails only when t
 * is negative or not finite. */
gf_status gf_spreading_cap_sample(const gf_spreading_cap *c, double x, double t, double *h,
                                  double *u);

#ifdef __cplusplus
}
#endif

#endif
