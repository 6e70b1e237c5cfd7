/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * granflow — verification helpers: errors of a 1D solution against a
 * reference or an exact solution.  For tests and benchmarks (tests/,
 * tests/bench); no solver needs them.
 */
#ifndef GRANFLOW_VERIFICATION_H
#define GRANFLOW_VERIFICATION_H

#include "granflow/exact.h"
#include "granflow/sh1d.h"

#ifdef __cplusplus
extern "C" {
#endif

/* L1 distance of the depths of two solutions, integral of |h_a - h_b| over
 * the domain of a by 5-point Gauss quadrature in every cell of a (b is
 * evaluated at the same points; both must cover them).  For errors against
 * a fine reference solution. */
double gf_sh1d_l1_difference(const gf_sh1d *a, const gf_sh1d *b);

/* L1 error of the cell-mean depths against the exact Riemann solution at
 * time t: sum_i |h_i - mean of the exact h over cell i| dx, the exact mean
 * from 16 midpoint samples per cell; on the moving mesh (moving_mesh) plus
 * the exact depth beyond its ends, where it is dry. */
double gf_sh1d_l1_error_riemann(const gf_sh1d *s, const gf_riemann *exact, double t);

/* The integral of an exact depth over the parts of the domain beyond the
 * grid's ends (gf_sh1d_extent; none on the fixed grid), by the midpoint rule
 * with `samples` points on each part: what the L1 error of a moving mesh
 * (moving_mesh) adds for the depth it does not cover. */
double gf_sh1d_depth_beyond(const gf_sh1d *s, double (*depth)(double x, void *ctx), void *ctx, size_t samples);

#ifdef __cplusplus
}
#endif

#endif
