/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * granflow — Savage–Hutter net driving acceleration (gravity minus Coulomb
 * bed friction with curvature) in the down-slope direction.
 *
 * rkdg paper eq. (2), written with the gravity scale g so that one formula
 * serves the dimensionless equations (g = 1) and the dimensional ones
 * (g = 9.81 m/s^2):
 *
 *   s(u) = g sin(zeta) - sgn(u) mu max(0, g cos(zeta) + c u^2),   u != 0,
 *
 * with mu = tan(delta) the bed friction coefficient and c = chi*kappa the
 * curvature term (kappa = -d zeta/dx; chi = 1 in the rkdg paper; in
 * dimensional form c = kappa [1/m]).  The max(0, .) cut removes friction
 * where the flow would lift off a convex bed.
 *
 * At rest (u = 0) friction is static and bounded by the dynamic value
 * R = mu max(0, g cos zeta) (kinetic paper, Definition 1 and g-tilde in
 * Scheme 1):  g~ = min(g sin zeta + R, max(beta dh/dx, g sin zeta - R)).
 * A profile is admissible (stays at rest) when beta dh/dx lies within
 * [g sin zeta - R, g sin zeta + R].
 */
#ifndef GRANFLOW_SOURCE_H
#define GRANFLOW_SOURCE_H

#ifdef __cplusplus
extern "C" {
#endif

/* beta = epsilon K cos(zeta): the coefficient of the hydrostatic pressure
 * beta h^2/2 of the dimensionless Savage–Hutter equations (rkdg eq. 1;
 * kinetic paper eq. 1 with K the earth-pressure coefficient). */
double gf_sh_beta(double epsilon, double k, double zeta);
/* the same from cos(zeta) (solvers that evaluate it once per point of a
 * fixed bed) */
double gf_sh_beta_c(double epsilon, double k, double cos_zeta);

/* Net acceleration of moving material g sin(zeta) - sgn(u) r, with r >= 0 the
 * friction deceleration tau/(rho h) of any law (rkdg eq. 2 for Coulomb);
 * u == 0 gives the gravity part only. */
double gf_sh_moving_accel(double g_sin_zeta, double r, double u);

/* g~ for any friction law: beta dh/dx clamped to [g sin zeta - r, g sin zeta
 * + r], r >= 0 the static bound per unit thickness (kinetic paper, g-tilde of
 * Schemes 1-3; gf_sh_static_source is the Coulomb case). */
double gf_sh_clamp_static(double g_sin_zeta, double r, double beta_dhdx);

/* Normal (bed-normal) acceleration max(0, g cos(zeta) + c u^2): basal
 * pressure divided by density and thickness, p_b / (rho h). */
double gf_sh_normal_acceleration(double g, double zeta, double curv, double u);
/* the same from cos(zeta) */
double gf_sh_normal_acceleration_c(double g, double cos_zeta, double curv, double u);

/* s(u) of rkdg eq. (2) for u != 0; for u == 0 returns the gravity part
 * g sin(zeta) only (use gf_sh_static_source for the bounded static value). */
double gf_sh_driving(double g, double zeta, double curv, double mu, double u);

/* Static friction bound R = mu max(0, g cos zeta) (kinetic paper, Def. 1):
 * the Coulomb law's gf_friction_static_bound per unit thickness; NaN for mu
 * outside the law's range [0, 10]. */
double gf_sh_static_bound(double g, double zeta, double mu);

/* g~: the source at rest, beta dh/dx clamped to [g sin zeta - R,
 * g sin zeta + R] (kinetic paper, g-tilde of Schemes 1-3). */
double gf_sh_static_source(double g, double zeta, double mu, double beta_dhdx);

/* 1 when beta dh/dx is admissible for a pile at rest (kinetic paper,
 * Definition 1 / eq. 22), 0 otherwise. */
int gf_sh_admissible(double g, double zeta, double mu, double beta_dhdx);

/* Dynamic (impact) pressure rho u^2 [Pa] of a flow of density rho [kg/m3]
 * at speed u [m/s]: the peak-pressure field of hazard maps (AvaFrame's
 * "ppr", there in kPa). */
double gf_dynamic_pressure(double rho, double u);

#ifdef __cplusplus
}
#endif

#endif
