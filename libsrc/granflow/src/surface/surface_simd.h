/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Four-lane vectors of the surface kernels (GCC vector extensions): the
 * lane helpers of the reconstruction, edge fluxes and step bound.  Private. */
#ifndef GRANFLOW_SURFACE_SIMD_H
#define GRANFLOW_SURFACE_SIMD_H

#include "simd4.h"

#ifdef __AVX__

/* rows r0..r3 (4 doubles each) to columns: c_k = (r0[k], r1[k], r2[k], r3[k]) */
static inline void transpose4(v4d r0, v4d r1, v4d r2, v4d r3, v4d *c)
{
    const v4d t0 = __builtin_shuffle(r0, r1, (v4i){0, 4, 2, 6}), t1 = __builtin_shuffle(r0, r1, (v4i){1, 5, 3, 7});
    const v4d t2 = __builtin_shuffle(r2, r3, (v4i){0, 4, 2, 6}), t3 = __builtin_shuffle(r2, r3, (v4i){1, 5, 3, 7});
    c[0] = __builtin_shuffle(t0, t2, (v4i){0, 1, 4, 5});
    c[1] = __builtin_shuffle(t1, t3, (v4i){0, 1, 4, 5});
    c[2] = __builtin_shuffle(t0, t2, (v4i){2, 3, 6, 7});
    c[3] = __builtin_shuffle(t1, t3, (v4i){2, 3, 6, 7});
}

#endif

#endif
