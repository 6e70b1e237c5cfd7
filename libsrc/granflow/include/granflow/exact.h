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

/* beta of the dimensionless Savage–Hutter equations: epsilon K cos(zeta). */
double gf_sh_beta(double epsilon, double k, double zeta);

#ifdef __cplusplus
}
#endif

#endif
