/*
 * granflow — Runge–Kutta discontinuous Galerkin solver for the 1D
 * Savage–Hutter equations (rkdg paper, section 3), solver type gf_sh1d_rkdg
 * of sh1d.h.
 *
 *  - scaled Legendre basis P_0..P_k, k = config.degree in {0, 1, 2} (eq. 6),
 *    diagonal mass matrix dx/(2m+1);
 *  - local Lax–Friedrichs flux (eq. 9) with the reposing factor
 *    eta = max(M_j, M_{j+1}) on the mass dissipation (M = 0 for a cell at
 *    rest, 1 for a moving one);
 *  - (k+1)-point Gauss quadrature of flux and source (eq. 11; 3 points for P2);
 *  - SSP-RK3 (section 3.2); dt = cfl dx / max(|u| + sqrt(beta h)) over the
 *    cell means; default cfl = 0.9 min(1/(2k+1), w_GL) where w_GL is the end
 *    weight of the Gauss–Lobatto rule that keeps the means positive (1, 1/2,
 *    1/6 for k = 0, 1, 2);
 *  - minmod limiter of eq. 13 with gamma on h and q after every stage and on
 *    the projected initial data; config.tvb_m > 0 turns it into the TVB
 *    variant (no limiting where |difference| <= M dx^2);
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
