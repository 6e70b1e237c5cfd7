/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * granflow — 1D chute topography: inclination zeta(x) and curvature
 * kappa(x) = -d zeta/dx along the down-slope arc length x of the bed, and
 * the bed position (X horizontal, Z vertical up) obtained by integrating
 * dX = cos(zeta) dx, dZ = -sin(zeta) dx (finite-area paper, after eq. 74;
 * rkdg paper, appendix).
 *
 * Kinds:
 *  - chute: zeta0 for x < x1, linear from zeta0 to zeta1 over [x1, x2],
 *    zeta1 beyond.  rkdg paper eq. (3): zeta1 = 0, x1 = 17.5, x2 = 21.5;
 *    finite-area paper eq. (74): zeta0 = 35 deg, zeta1 = 10 deg, same x1, x2.
 *    X = 0 at x = 0 and Z = 0 at x = x2 (the start of the run-out), which for
 *    zeta1 = 0 is the (x_b, y_b) mapping of the rkdg paper's appendix.
 *  - tabulated: zeta given at points x_i (strictly increasing, n >= 3),
 *    interpolated by a cubic GSL spline; kappa is minus its derivative.
 *    X = Z = 0 at the first point; evaluation outside [x_0, x_{n-1}] is an
 *    error.
 * Angles in radians.
 */
#ifndef GRANFLOW_TOPOGRAPHY_H
#define GRANFLOW_TOPOGRAPHY_H

#include <stddef.h>

#include "granflow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct gf_topography gf_topography;

/* Chute of rkdg eq. (3) / finite-area eq. (74).  zeta0, zeta1 in
 * (-pi/2, pi/2); x1 < x2. */
gf_status gf_topography_chute_alloc(double zeta0, double zeta1, double x1, double x2,
                                    gf_topography **out);

/* Tabulated inclination zeta_i at arc lengths x_i (copied). */
gf_status gf_topography_tabulated_alloc(const double *x, const double *zeta, size_t n,
                                        gf_topography **out);

void gf_topography_free(gf_topography *topo);

/* Range of x where the topography is defined (+-HUGE_VAL for a chute). */
void gf_topography_range(const gf_topography *topo, double *xmin, double *xmax);

/* Inclination zeta(x) and curvature kappa(x) = -d zeta/dx. */
gf_status gf_topography_eval(const gf_topography *topo, double x, double *zeta, double *kappa);

/* Bed position: horizontal X(x) and elevation Z(x). */
gf_status gf_topography_position(const gf_topography *topo, double x, double *X, double *Z);

#ifdef __cplusplus
}
#endif

#endif
