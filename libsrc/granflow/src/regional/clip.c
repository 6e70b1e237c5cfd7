/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * granflow — the clipped sub-domain of one release (issue 52, scale;
 * doc/theory/regional.md, section 6): the box of its cells and of the
 * steepest-descent paths from them, so that a release runs on a mesh whose
 * size depends on its own path, not on the region.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "granflow/regional.h"
#include "internal.h"

/* a set of cell indices (open addressing, linear probing; SIZE_MAX empty),
 * with a value per cell when f is not NULL (the paths' flat distance) */
typedef struct cellset {
    size_t *v, cap, n;
    double *f;
} cellset;

static size_t hash(size_t c)
{
    c ^= c >> 33;
    c *= 0xff51afd7ed558ccdULL;
    c ^= c >> 33;
    return c;
}

static int set_init(cellset *s, size_t want, int values)
{
    s->cap = 64;
    while (s->cap < 2 * want) s->cap *= 2;
    s->n = 0;
    s->v = malloc(s->cap * sizeof *s->v);
    s->f = values ? malloc(s->cap * sizeof *s->f) : NULL;
    if (!s->v || (values && !s->f)) return -1;
    memset(s->v, 0xff, s->cap * sizeof *s->v);
    return 0;
}

static void set_free(cellset *s)
{
    free(s->v), free(s->f);
    s->v = NULL, s->f = NULL;
}

/* the slot of c, or -1 when c is not in the set */
static long set_slot(const cellset *s, size_t c)
{
    for (size_t i = hash(c) & (s->cap - 1);; i = (i + 1) & (s->cap - 1)) {
        if (s->v[i] == c) return (long)i;
        if (s->v[i] == (size_t)-1) return -1;
    }
}

static int set_has(const cellset *s, size_t c) { return set_slot(s, c) >= 0; }

static int set_put(cellset *s, size_t c, double f); /* 1 added, 0 there (value set), -1 no memory */

static int set_grow(cellset *s)
{
    cellset t;
    t.cap = 2 * s->cap, t.n = 0;
    t.v = malloc(t.cap * sizeof *t.v);
    t.f = s->f ? malloc(t.cap * sizeof *t.f) : NULL;
    if (!t.v || (s->f && !t.f)) {
        free(t.v), free(t.f);
        return -1;
    }
    memset(t.v, 0xff, t.cap * sizeof *t.v);
    for (size_t i = 0; i < s->cap; ++i)
        if (s->v[i] != (size_t)-1) set_put(&t, s->v[i], s->f ? s->f[i] : 0);
    set_free(s);
    *s = t;
    return 0;
}

static int set_put(cellset *s, size_t c, double f)
{
    if (2 * (s->n + 1) > s->cap && set_grow(s)) return -1;
    for (size_t i = hash(c) & (s->cap - 1);; i = (i + 1) & (s->cap - 1)) {
        if (s->v[i] == c) {
            if (s->f) s->f[i] = f;
            return 0;
        }
        if (s->v[i] == (size_t)-1) {
            s->v[i] = c;
            if (s->f) s->f[i] = f;
            ++s->n;
            return 1;
        }
    }
}

static int set_add(cellset *s, size_t c) { return set_put(s, c, 0); }

static void set_clear(cellset *s)
{
    memset(s->v, 0xff, s->cap * sizeof *s->v);
    s->n = 0;
}

static void grow_box(int *box, int col, int row)
{
    if (col < box[0]) box[0] = col;
    if (row < box[1]) box[1] = row;
    if (col > box[2]) box[2] = col;
    if (row > box[3]) box[3] = row;
}

/* the steepest neighbour of cell (col, row) lower than it; -1 when none */
static long steepest(const gf_raster *dem, int col, int row)
{
    const double dx = fabs(dem->gt[1]), dy = fabs(dem->gt[5]);
    const double z = dem->z[(size_t)row * (size_t)dem->nx + (size_t)col];
    double best = 0;
    long e = -1;
    for (int b = -1; b <= 1; ++b)
        for (int a = -1; a <= 1; ++a) {
            const int i = col + a, j = row + b;
            if ((!a && !b) || i < 0 || j < 0 || i >= dem->nx || j >= dem->ny) continue;
            const double v = dem->z[(size_t)j * (size_t)dem->nx + (size_t)i];
            if (!isfinite(v)) continue;
            const double g = (z - v) / hypot(a * dx, b * dy);
            if (g > best) best = g, e = (long)((size_t)j * (size_t)dem->nx + (size_t)i);
        }
    return e;
}

gf_status gf_downslope_box(const gf_raster *dem, size_t n, const size_t *cells, double max_climb, double max_flat,
                           int box[4], size_t *path_cells)
{
    if (!dem || !dem->z || !box || (n && !cells))
        return gf_fail(GF_EINVAL, "downslope box: no DEM, cells or output given");
    if (!(max_climb >= 0 && isfinite(max_climb)) || !(max_flat >= 0 && isfinite(max_flat)))
        return gf_fail(GF_EDOM, "downslope box: max_climb %g m and max_flat %g m must be finite and >= 0", max_climb,
                       max_flat);
    const size_t nc = (size_t)dem->nx * (size_t)dem->ny;
    box[0] = box[1] = 1 << 30;
    box[2] = box[3] = -1;
    cellset rel = {0}, all = {0}, path = {0};
    if (set_init(&rel, n, 0) || set_init(&all, 4 * n + 64, 1) || set_init(&path, 256, 0)) {
        set_free(&rel), set_free(&all), set_free(&path);
        return gf_fail(GF_ENOMEM, "downslope box: %zu cells", n);
    }
    gf_status st = GF_SUCCESS;
    size_t valid = 0;
    for (size_t k = 0; k < n; ++k) {
        if (cells[k] >= nc) {
            st = gf_fail(GF_EDOM, "downslope box: cell %zu outside the grid of %d x %d", cells[k], dem->nx, dem->ny);
            goto done;
        }
        if (!isfinite(dem->z[cells[k]])) continue;
        ++valid;
        if (set_add(&rel, cells[k]) < 0) goto nomem;
        grow_box(box, (int)(cells[k] % (size_t)dem->nx), (int)(cells[k] / (size_t)dem->nx));
    }
    if (!valid) {
        st = gf_fail(GF_EDOM, "downslope box: none of the %zu cells has a DEM value", n);
        goto done;
    }
    const double dx = fabs(dem->gt[1]), dy = fabs(dem->gt[5]);
    /* a path from every release cell whose steepest descent leaves the release
     * (or that has none): the others' paths run through the release into them */
    for (size_t k = 0; k < n; ++k) {
        const size_t c0 = cells[k];
        if (!isfinite(dem->z[c0])) continue;
        const long e0 = steepest(dem, (int)(c0 % (size_t)dem->nx), (int)(c0 / (size_t)dem->nx));
        if (e0 >= 0 && set_has(&rel, (size_t)e0)) continue;
        /* the walk of gf_thalweg_d8 (pits up to max_climb walked through, level
         * ground followed for max_flat); it ends where an earlier path of this
         * release went on with as much of max_flat left (all holds each
         * cell's smallest flat distance so far: the box does not depend on
         * the order of the cells) */
        set_clear(&path);
        int col = (int)(c0 % (size_t)dem->nx), row = (int)(c0 / (size_t)dem->nx), pa = 0, pb = 0;
        double s = 0, zlow = INFINITY, s_low = 0;
        for (;;) {
            const size_t c = (size_t)row * (size_t)dem->nx + (size_t)col;
            if (dem->z[c] < zlow) zlow = dem->z[c], s_low = s;
            const double flat = s - s_low;
            const long slot = set_slot(&all, c);
            if (c != c0 && slot >= 0 && all.f[slot] <= flat) break;
            if (set_add(&path, c) < 0 || set_put(&all, c, flat) < 0) goto nomem;
            grow_box(box, col, row);
            if (path.n >= nc || s - s_low > max_flat) break;
            double best = 0, bd = 0, lowest = INFINITY, ld = 0;
            int bi = -1, bj = -1, li = -1, lj = -1;
            for (int b = -1; b <= 1; ++b)
                for (int a = -1; a <= 1; ++a) {
                    const int i = col + a, j = row + b;
                    if ((!a && !b) || i < 0 || j < 0 || i >= dem->nx || j >= dem->ny) continue;
                    const size_t e = (size_t)j * (size_t)dem->nx + (size_t)i;
                    const double v = dem->z[e];
                    if (!isfinite(v)) continue;
                    const double d = hypot(a * dx, b * dy), g = (dem->z[c] - v) / d;
                    if (g > best) best = g, bd = d, bi = i, bj = j;
                    const int keep = v == lowest && a == pa && b == pb;
                    if (max_climb > 0 && (v < lowest || keep) && v - zlow <= max_climb && !set_has(&path, e))
                        lowest = v, ld = d, li = i, lj = j;
                }
            if (bi < 0 || set_has(&path, (size_t)bj * (size_t)dem->nx + (size_t)bi)) {
                if (li < 0) break;
                bi = li, bj = lj, bd = ld;
            }
            pa = bi - col, pb = bj - row;
            col = bi, row = bj;
            s += bd;
        }
    }
    if (path_cells) *path_cells = all.n;
    goto done;
nomem:
    st = gf_fail(GF_ENOMEM, "downslope box: the paths of %zu cells", n);
done:
    set_free(&rel), set_free(&all), set_free(&path);
    return st;
}
