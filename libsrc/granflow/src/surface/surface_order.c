/* SPDX-License-Identifier: GPL-3.0-or-later */
/* A face order for the explicit surface scheme (gf_surface_face_order):
 * the faces along a Hilbert curve through their centres, so that the
 * active set of an avalanche (a patch of the terrain and two rings) is a
 * few runs of consecutive faces, and the per-face and per-edge arrays that
 * a step reads lie together in memory. */
#include "surface_internal.h"

#include <stdint.h>
#include <stdlib.h>

/* The index of cell (x, y) along the Hilbert curve through a 2^b x 2^b
 * grid (the classic bit-by-bit walk, quadrant rotations included). */
static uint64_t hilbert2(uint32_t x, uint32_t y, int b)
{
    uint64_t d = 0;
    for (uint32_t q = (uint32_t)1 << (b - 1); q > 0; q >>= 1) {
        const uint32_t rx = (x & q) ? 1u : 0u, ry = (y & q) ? 1u : 0u;
        d += (uint64_t)q * q * ((3u * rx) ^ ry);
        if (ry == 0) { /* rotate the quadrant */
            if (rx == 1) {
                x = q - 1 - (x & (q - 1)) + (x & ~(q - 1));
                y = q - 1 - (y & (q - 1)) + (y & ~(q - 1));
            }
            const uint32_t t = x;
            x = y, y = t;
        }
    }
    return d;
}

struct keyed {
    uint64_t key;
    int face;
};

static int cmp_keyed(const void *a, const void *b)
{
    const struct keyed *x = a, *y = b;
    if (x->key != y->key)
        return x->key < y->key ? -1 : 1;
    return (x->face > y->face) - (x->face < y->face);
}

gf_status gf_surface_face_order(size_t n, const double *centre, int *order)
{
    if (n > 0 && (!centre || !order))
        return gf_fail(GF_EINVAL, "gf_surface_face_order: null argument");
    if (n > (size_t)0x7fffffff)
        return gf_fail(GF_EINVAL, "gf_surface_face_order: %zu faces, at most 2^31 - 1", n);
    if (n == 0)
        return GF_SUCCESS;
    double lo[3], hi[3];
    for (int k = 0; k < 3; ++k)
        lo[k] = hi[k] = centre[k];
    for (size_t f = 0; f < n; ++f)
        for (int k = 0; k < 3; ++k) {
            const double v = centre[3 * f + k];
            if (!isfinite(v))
                return gf_fail(GF_ENONFINITE, "gf_surface_face_order: centre of face %zu is not finite", f);
            lo[k] = gmin(lo[k], v), hi[k] = gmax(hi[k], v);
        }
    /* the plane of the two largest extents (a terrain's x and y) */
    int a = 0, b = 1, c = 2;
    if (hi[c] - lo[c] > hi[b] - lo[b]) {
        const int t = b;
        b = c, c = t;
    }
    if (hi[b] - lo[b] > hi[a] - lo[a]) {
        const int t = a;
        a = b, b = t;
    }
    struct keyed *k = malloc(n * sizeof *k);
    if (!k)
        return gf_fail(GF_ENOMEM, "gf_surface_face_order: out of memory for %zu faces", n);
    enum { BITS = 24 };
    const double cells = (double)((uint32_t)1 << BITS) - 1.0;
    const double ext = gmax(hi[a] - lo[a], hi[b] - lo[b]), sc = ext > 0.0 ? cells / ext : 0.0;
    for (size_t f = 0; f < n; ++f) {
        const uint32_t x = (uint32_t)((centre[3 * f + a] - lo[a]) * sc);
        const uint32_t y = (uint32_t)((centre[3 * f + b] - lo[b]) * sc);
        k[f].key = hilbert2(x, y, BITS);
        k[f].face = (int)f;
    }
    qsort(k, n, sizeof *k, cmp_keyed);
    for (size_t i = 0; i < n; ++i)
        order[i] = k[i].face;
    free(k);
    return GF_SUCCESS;
}
