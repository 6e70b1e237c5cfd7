/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Four-lane vectors of libgranflow's kernels (GCC vector extensions): the
 * type, splat, load and the lane-wise selections, shared by the surface
 * kernels (surface/surface_simd.h adds their transposes) and the four-lane
 * samosAT speeds (physics/friction_implicit.c).  Private. */
#ifndef GRANFLOW_SIMD4_H
#define GRANFLOW_SIMD4_H

#include <string.h>

/* Four values as the lanes of one vector (the four reconstructed variables
 * of a face, four edges, four faces): each lane does the scalar operations
 * it replaces, in the same order, so the results are the same bit for bit;
 * on SSE2 a lane pair per instruction, on AVX one instruction. */
/* the helpers are static and inlined: the ABI of passing 32-byte vectors
 * without AVX, which GCC warns about, does not arise */
#pragma GCC diagnostic ignored "-Wpsabi"
typedef double v4d __attribute__((vector_size(32)));
typedef long long v4i __attribute__((vector_size(32)));
static inline v4d vsplat(double x) { return (v4d){x, x, x, x}; }
static inline v4d vload(const double *p)
{
    v4d v;
    memcpy(&v, p, sizeof v);
    return v;
}
/* lane-wise m ? a : b (every lane of m all ones or all zeros) */
#ifdef __AVX__
/* (vminpd a, b is a < b ? a : b per lane, vmaxpd a > b ? a : b: gmin, gmax) */
static inline v4d vsel(v4i m, v4d a, v4d b) { return __builtin_ia32_blendvpd256(b, a, (v4d)m); }
static inline v4d vmin(v4d a, v4d b) { return __builtin_ia32_minpd256(a, b); }
static inline v4d vmax(v4d a, v4d b) { return __builtin_ia32_maxpd256(a, b); }
static inline int vany(v4i m) { return __builtin_ia32_movmskpd256((v4d)m) != 0; }
#else
static inline v4d vsel(v4i m, v4d a, v4d b) { return (v4d)(((v4i)a & m) | ((v4i)b & ~m)); }
static inline v4d vmin(v4d a, v4d b) { return vsel(a < b, a, b); } /* gmin per lane */
static inline v4d vmax(v4d a, v4d b) { return vsel(a > b, a, b); } /* gmax per lane */
static inline int vany(v4i m) { return (m[0] | m[1] | m[2] | m[3]) != 0; }
#endif

#endif
