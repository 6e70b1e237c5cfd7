/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * granflow — Runge–Kutta discontinuous Galerkin solver for the 1D
 * Savage–Hutter equations (rkdg paper, section 3), solver type gf_sh1d_rkdg
 * of sh1d.h.
 *
 *  - scaled Legendre basis P_0..P_k, k = config.degree in {0, 1, 2} (eq. 6),
 *    diagonal mass matrix dx/(2m+1);
 *  - local Lax–Friedrichs flux (eq. 9) with the reposing factor
 *    eta = max(M_j, M_{j+1}) on the mass dissipation (M = 0 for a cell at
 *    rest, 1 for a moving one); where both sides move towards the same side
 *    faster than twice their wave speed sqrt(beta h) (or one side is dry),
 *    the upwind flux, which is the exact flux there (no Lax–Friedrichs mass
 *    diffusion into the thin fast layer ahead of a dry front);
 *  - (k+1)-point Gauss quadrature of flux and source (eq. 11; 3 points for P2);
 *  - SSP-RK3 (section 3.2); dt = cfl dx / max(|u| + sqrt(beta h)) over every
 *    point the fluxes see (both cell ends and the Gauss points); default
 *    cfl = 0.9 min(1/(2k+1), w_GL) where w_GL is the end weight of the
 *    Gauss–Lobatto rule that keeps the means positive (1, 1/2, 1/6 for
 *    k = 0, 1, 2).  A stage that would still make a mean depth negative (wave
 *    speeds that grew inside the step) repeats the step as two halves, down
 *    to dt/2^20, counted by gf_sh1d_rejected_steps();
 *  - limiters on h and q after every stage and on the projected initial data
 *    (config.limiter): GF_LIMITER_MOMENT (default), Krivodonova's (2007)
 *    hierarchical moment limiter, u_m limited by minmod against
 *    (u_{m-1}^{j+1} - u_{m-1}^j)/(2m-1) and (u_{m-1}^j - u_{m-1}^{j-1})/(2m-1)
 *    from the highest mode down, stopping at the first mode left unchanged;
 *    GF_LIMITER_MINMOD, the minmod limiter of eq. 13 with gamma (P2 -> P1
 *    where it acts).  config.tvb_m > 0 turns either into its TVB variant (a
 *    mode or edge deviation below M dx^2 is not limited; default M = 1);
 *  - velocity bound (config.velocity_limiter, default on): the higher modes
 *    of q are blended towards u_mean h(x) until q/h at every end and Gauss
 *    point lies within the mean velocities of the cell and its wet
 *    neighbours (a 1e-8 relative tolerance keeps mirror images alike);
 *  - dry cells (mean h < h_eps): u = 0; semi-wet cells (h_eps <= h < h_semi):
 *    velocity extrapolated from the wetter neighbour (section 3.4), higher
 *    modes of q zero.
 *
 * Choices the paper leaves open (it defers the reposing test to its ref. 40):
 *  - Friction is applied in every forward-Euler stage after the flux and
 *    gravity update, never reversing the mean momentum: with the friction
 *    capacity C = dt * (cell mean of |tau_b|/rho), a cell whose updated
 *    mean momentum satisfies |q| <= C is stopped (q = 0 in all modes,
 *    M = 0) — the discrete form of the kinetic paper's admissibility bound
 *    (the net non-friction force is within the static Coulomb bound);
 *    otherwise |q| is reduced by C.  A cell stopped in the last stage of a
 *    step is at rest after the step.
 *  - Positivity: after limiting, the higher modes of h and q of a cell are
 *    scaled (Zhang–Shu) so that h >= 0 at every quadrature and end point.
 *  - K (active/passive) per cell from the sign of the central difference of
 *    the mean velocity.
 */
#ifndef GRANFLOW_DG1D_H
#define GRANFLOW_DG1D_H

#include "granflow/sh1d.h"

#endif
