/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * granflow — kinetic schemes for the 1D Savage–Hutter equations
 * (Kaland & Struckmeier, kinetic paper, section 3), solver type
 * gf_sh1d_kinetic of sh1d.h; config.scheme selects:
 *
 *  Scheme 1: upwind kinetic flux F = P(h_i, u_i) + N(h_{i+1}, u_{i+1}) (I1-I4)
 *            and the source g(u_i) h^{n+1}, g~ at u = 0 (eq. 24).
 *  Scheme 2: modified flux (eq. 25): both halves with the mean depth
 *            (h_i + h_{i+1})/2, upwinding only in u; for slow cells,
 *            |q| < |dt g(q) h^n|, friction as an implicit Coulomb update of
 *            the whole discrete force with the paper's weighted depth
 *            hbar = (h_{i+1} + 2h_i + h_{i-1})/4:
 *              q* = q - lam dF + dt g sin(zeta) hbar,
 *              q^{n+1} = 0 if |q*| <= dt R hbar, else q* - sgn(q*) dt R hbar
 *            (R the static bound per unit depth).  At rest this is the
 *            paper's g~ (h_{i+1} + 2h_i + h_{i-1})/4 source exactly, so an
 *            admissible profile stays at rest at any time step; the paper's
 *            blend (1 - mu) dt g~ hbar, mu = -q/(dt g(q) h^{n+1}), drops q and
 *            leaves the velocity part of the modified flux unopposed, which let
 *            round-off grow at rest for Courant numbers above about 0.75.
 *  Scheme 3: coupled: Scheme 2 where the mass is slow (starting, stopping,
 *            at rest), Scheme 1 elsewhere.
 *
 * P and N are the half moments of the equilibrium density
 * M = sqrt(h) chi((xi-u)/sqrt(h)), chi(w) = sqrt((2 beta - w^2)_+)/(pi beta)
 * (eq. 12).  With c = sqrt(2 beta h), a = -u/c clipped to [-1, 1],
 * theta = asin(a):
 *   J0 = pi/4 - theta/2 - sin(2 theta)/4,  J1 = (1 - a^2)^{3/2}/3,
 *   J2 = pi/16 - theta/8 + sin(4 theta)/32,
 *   P = (2h/pi) (u J0 + c J1,  u^2 J0 + 2 u c J1 + c^2 J2),
 *   N = (2h/pi) (u (pi/2 - J0) - c J1,  u^2 (pi/2 - J0) - 2 u c J1 + c^2 (pi/8 - J2)).
 * (Derived here; the printed I3/I4 of the paper carry typos: a sign of the
 * middle term of I3 and sin(a1) for sin(4 arcsin a1).)
 *
 * Choices the paper leaves open, stated:
 *  - Scheme 3 decides per interface, so that mass is conserved exactly: an
 *    interface uses the modified flux when a cell on either side is slow.
 *  - "Slow" is tested with h^n in place of h^{n+1} (which depends on the
 *    choice); a cell with q = 0 is always slow (mu = 0).
 *  - Schemes 2 and 3: where the modified flux would make a depth negative,
 *    the interfaces of that cell fall back to the Scheme 1 flux, which keeps
 *    h >= 0 under the CFL condition of Theorem 3:
 *    dt max(|u| + sqrt(2 beta h)) <= cfl dx (default cfl = 0.9).
 *  - Constant inclination only (the paper's section 3); a topography is
 *    rejected.  K (active/passive) per cell from the sign of the central
 *    difference of u.
 */
#ifndef GRANFLOW_KINETIC1D_H
#define GRANFLOW_KINETIC1D_H

#include "granflow/sh1d.h"

#ifdef __cplusplus
extern "C" {
#endif

/* First and second moments of the positive (xi >= 0) and negative (xi < 0)
 * halves of the equilibrium density M(h, xi - u) with pressure factor beta:
 * p[0] = int_{xi>=0} xi M, p[1] = int_{xi>=0} xi^2 M; n[] likewise for xi < 0.
 * p + n = (h u, h u^2 + beta h^2/2). */
void gf_kinetic_half_fluxes(double h, double u, double beta, double p[2], double n[2]);

#ifdef __cplusplus
}
#endif

#endif
