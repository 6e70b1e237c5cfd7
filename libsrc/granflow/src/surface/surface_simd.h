/* Four-lane vectors of the surface kernels (GCC vector extensions): the
 * lane helpers of the reconstruction, edge fluxes and step bound.  Private. */
#ifndef GRANFLOW_SURFACE_SIMD_H
#define GRANFLOW_SURFACE_SIMD_H

#include <string.h>

/* The four reconstructed variables (h, u_x, u_y, u_z) of a face as the four
 * lanes of one vector (GCC vector extensions: each lane does the scalar
 * operations of the per-variable loops it replaces, in the same order, so
 * the results are the same bit for bit; on SSE2 a lane pair per
 * instruction, on AVX one instruction). */
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
