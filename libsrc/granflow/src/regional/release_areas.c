/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Potential release areas of a DEM (granflow/regional.h;
 * doc/theory/regional.md, section 1): Horn's slope and aspect, the vector
 * ruggedness measure, plan curvature, and the delineation into separate
 * areas by aspect classes. */
#include "granflow/regional.h"
#include "internal.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define RAD GF_DEG

static gf_status check_grid(const gf_raster *dem, const char *what)
{
    if (!dem || !dem->z || dem->nx < 3 || dem->ny < 3)
        return gf_fail(GF_EINVAL, "%s: the DEM must be a grid of at least 3 x 3 cells (got %d x %d)", what,
                       dem ? dem->nx : 0, dem ? dem->ny : 0);
    double d = fabs(dem->gt[1]);
    if (!isfinite(d) || d <= 0 || !isfinite(dem->gt[5]) || dem->gt[5] == 0)
        return gf_fail(GF_EINVAL, "%s: the DEM's pixel size %g must be finite and > 0", what, d);
    return GF_SUCCESS;
}

/* The 3 x 3 neighbourhood of interior cell (i, j) as w[0..8] (rows top to
 * bottom as in the raster, i.e. north to south for gt5 < 0); 0 when a value
 * is NAN. */
static int window3(const gf_raster *dem, int i, int j, double w[9])
{
    if (i < 1 || j < 1 || i >= dem->nx - 1 || j >= dem->ny - 1)
        return 0;
    for (int b = -1; b <= 1; ++b)
        for (int a = -1; a <= 1; ++a) {
            double v = dem->z[(size_t)(j + b) * (size_t)dem->nx + (size_t)(i + a)];
            if (!isfinite(v))
                return 0;
            w[3 * (b + 1) + (a + 1)] = v;
        }
    return 1;
}

/* Horn's gradient (dz/dx east, dz/dy north) of a 3 x 3 window */
static void horn(const gf_raster *dem, const double w[9], double *zx, double *zy)
{
    double dx = fabs(dem->gt[1]), dy = fabs(dem->gt[5]);
    double sx = dem->gt[1] > 0 ? 1.0 : -1.0;  /* columns run east */
    double sy = dem->gt[5] < 0 ? 1.0 : -1.0;  /* rows run south */
    *zx = sx * ((w[2] + 2 * w[5] + w[8]) - (w[0] + 2 * w[3] + w[6])) / (8 * dx);
    *zy = sy * ((w[0] + 2 * w[1] + w[2]) - (w[6] + 2 * w[7] + w[8])) / (8 * dy);
}

static double aspect_of(double ex, double ny)
{ /* downslope direction (ex east, ny north) clockwise from north */
    double a = atan2(ex, ny) / RAD;
    return a < 0 ? a + 360.0 : a;
}

gf_status gf_slope_aspect(const gf_raster *dem, double *slope, double *aspect)
{
    gf_status st = check_grid(dem, "slope");
    if (st)
        return st;
    for (int j = 0; j < dem->ny; ++j)
        for (int i = 0; i < dem->nx; ++i) {
            size_t c = (size_t)j * (size_t)dem->nx + (size_t)i;
            double w[9], zx, zy;
            if (!window3(dem, i, j, w)) {
                if (slope)
                    slope[c] = NAN;
                if (aspect)
                    aspect[c] = NAN;
                continue;
            }
            horn(dem, w, &zx, &zy);
            if (slope)
                slope[c] = atan(hypot(zx, zy)) / RAD;
            if (aspect)
                aspect[c] = (zx == 0 && zy == 0) ? NAN : aspect_of(-zx, -zy);
        }
    return GF_SUCCESS;
}

gf_status gf_vrm(const gf_raster *dem, int window, double *vrm, double *aspect_smooth)
{
    gf_status st = check_grid(dem, "roughness");
    if (st)
        return st;
    if (window < 3 || window % 2 == 0 || window > dem->nx || window > dem->ny)
        return gf_fail(GF_EDOM, "roughness: window %d cells must be odd, >= 3 and at most the grid (%d x %d)",
                       window, dem->nx, dem->ny);
    size_t nc = (size_t)dem->nx * (size_t)dem->ny;
    double *n = malloc(3 * nc * sizeof *n);
    if (!n)
        return gf_fail(GF_ENOMEM, "roughness: %zu cells", nc);
    for (int j = 0; j < dem->ny; ++j)
        for (int i = 0; i < dem->nx; ++i) {
            size_t c = (size_t)j * (size_t)dem->nx + (size_t)i;
            double w[9], zx, zy;
            if (!window3(dem, i, j, w)) {
                n[3 * c] = NAN;
                continue;
            }
            horn(dem, w, &zx, &zy);
            double l = sqrt(1 + zx * zx + zy * zy);
            n[3 * c] = -zx / l;
            n[3 * c + 1] = -zy / l;
            n[3 * c + 2] = 1 / l;
        }
    int h = window / 2;
    for (int j = 0; j < dem->ny; ++j)
        for (int i = 0; i < dem->nx; ++i) {
            size_t c = (size_t)j * (size_t)dem->nx + (size_t)i;
            double r[3] = {0, 0, 0};
            int cnt = 0;
            if (isfinite(n[3 * c]))
                for (int b = -h; b <= h; ++b)
                    for (int a = -h; a <= h; ++a) {
                        int ii = i + a, jj = j + b;
                        if (ii < 0 || jj < 0 || ii >= dem->nx || jj >= dem->ny)
                            continue;
                        size_t d = (size_t)jj * (size_t)dem->nx + (size_t)ii;
                        if (!isfinite(n[3 * d]))
                            continue;
                        r[0] += n[3 * d];
                        r[1] += n[3 * d + 1];
                        r[2] += n[3 * d + 2];
                        ++cnt;
                    }
            if (!cnt) {
                if (vrm)
                    vrm[c] = NAN;
                if (aspect_smooth)
                    aspect_smooth[c] = NAN;
                continue;
            }
            double v = 1 - sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]) / cnt;
            if (vrm)
                vrm[c] = v < 0 ? 0 : v; /* round-off of a plane */
            if (aspect_smooth)
                aspect_smooth[c] = (r[0] == 0 && r[1] == 0) ? NAN : aspect_of(r[0], r[1]);
        }
    free(n);
    return GF_SUCCESS;
}

gf_status gf_plan_curvature(const gf_raster *dem, double *curv)
{
    gf_status st = check_grid(dem, "curvature");
    if (st)
        return st;
    double L = fabs(dem->gt[1]);
    for (int j = 0; j < dem->ny; ++j)
        for (int i = 0; i < dem->nx; ++i) {
            size_t c = (size_t)j * (size_t)dem->nx + (size_t)i;
            double w[9];
            if (!window3(dem, i, j, w)) {
                curv[c] = NAN;
                continue;
            }
            /* second-order polynomial of the window (Zevenbergen and Thorne
             * 1987) with x east and y north: rows of w run north to south */
            double sx = dem->gt[1] > 0 ? 1.0 : -1.0, sy = dem->gt[5] < 0 ? 1.0 : -1.0;
            double p = sx * (w[5] - w[3]) / (2 * L);
            double q = sy * (w[1] - w[7]) / (2 * L);
            double r = (w[3] + w[5] - 2 * w[4]) / (L * L);
            double t = (w[1] + w[7] - 2 * w[4]) / (L * L);
            double s = sx * sy * (w[2] + w[6] - w[0] - w[8]) / (4 * L * L);
            double g2 = p * p + q * q;
            curv[c] = g2 == 0 ? NAN : -(q * q * r - 2 * p * q * s + p * p * t) / (g2 * sqrt(1 + g2));
        }
    return GF_SUCCESS;
}

void gf_pra_params_default(gf_pra_params *p)
{
    p->slope_min = 28;
    p->slope_max = 60;
    p->roughness_window = 5;
    p->roughness_max = 0.05;
    p->curvature_max = NAN;
    p->aspect_sectors = 8;
    p->merge_sectors = 1;
    p->min_area = 10000;
}

void gf_pra_set_free(gf_pra_set *s)
{
    if (!s)
        return;
    free(s->label);
    free(s->pra);
    s->label = NULL;
    s->pra = NULL;
    s->n = 0;
}

/* union-find over fragments */
static size_t find(size_t *parent, size_t a)
{
    while (parent[a] != a) {
        parent[a] = parent[parent[a]];
        a = parent[a];
    }
    return a;
}

typedef struct edge {
    size_t a, b; /* fragment a (small) borders fragment b */
} edge;

static int edge_cmp(const void *x, const void *y)
{
    const edge *e = x, *f = y;
    if (e->a != f->a)
        return e->a < f->a ? -1 : 1;
    if (e->b != f->b)
        return e->b < f->b ? -1 : 1;
    return 0;
}

static int sector_gap(int a, int b, int n)
{
    int d = abs(a - b) % n;
    return d > n - d ? n - d : d;
}

static gf_status check_params(const gf_pra_params *p)
{
    if (!(p->slope_min > 0 && p->slope_min < p->slope_max && p->slope_max <= 90))
        return gf_fail(GF_EDOM, "release areas: slope window [%g, %g] deg must satisfy 0 < min < max <= 90",
                       p->slope_min, p->slope_max);
    if (p->roughness_window < 3 || p->roughness_window % 2 == 0)
        return gf_fail(GF_EDOM, "release areas: roughness window %d cells must be odd and >= 3",
                       p->roughness_window);
    if (!isnan(p->roughness_max) && !(p->roughness_max >= 0 && p->roughness_max <= 1))
        return gf_fail(GF_EDOM, "release areas: roughness maximum (VRM) %g must be in [0, 1]", p->roughness_max);
    if (!isnan(p->curvature_max) && !(p->curvature_max > 0 && isfinite(p->curvature_max)))
        return gf_fail(GF_EDOM, "release areas: curvature maximum %g 1/m must be finite and > 0", p->curvature_max);
    if (p->aspect_sectors < 1 || p->aspect_sectors > 36)
        return gf_fail(GF_EDOM, "release areas: aspect sectors %d must be in [1, 36]", p->aspect_sectors);
    if (!(p->merge_sectors >= 0 && isfinite(p->merge_sectors)))
        return gf_fail(GF_EDOM, "release areas: merge sectors %g must be finite and >= 0", p->merge_sectors);
    if (!(p->min_area >= 0 && isfinite(p->min_area)))
        return gf_fail(GF_EDOM, "release areas: minimum area %g m2 must be finite and >= 0", p->min_area);
    return GF_SUCCESS;
}

typedef struct frag_stat {
    size_t cells;
    double slope, z, ex, ny, x, y, zmax;
    size_t top;
} frag_stat;

static int pra_cmp(const void *x, const void *y)
{
    const gf_pra *a = x, *b = y;
    if (a->z_max != b->z_max)
        return a->z_max > b->z_max ? -1 : 1;
    if (a->top_row != b->top_row)
        return a->top_row < b->top_row ? -1 : 1;
    return (a->top_col > b->top_col) - (a->top_col < b->top_col);
}

gf_status gf_pra_delineate(const gf_raster *dem, const unsigned char *excluded, const gf_pra_params *p,
                           gf_pra_set *out)
{
    if (!out)
        return gf_fail(GF_EINVAL, "release areas: no output given");
    memset(out, 0, sizeof *out);
    if (!p)
        return gf_fail(GF_EINVAL, "release areas: no parameters given");
    gf_status st = check_grid(dem, "release areas");
    if (st || (st = check_params(p)))
        return st;
    int nx = dem->nx, ny = dem->ny;
    size_t nc = (size_t)nx * (size_t)ny;
    double cell_area = fabs(dem->gt[1] * dem->gt[5]);
    double *slope = malloc(nc * sizeof *slope), *aspect = malloc(nc * sizeof *aspect);
    double *vrm = malloc(nc * sizeof *vrm), *curv = malloc(nc * sizeof *curv);
    size_t *frag = malloc(nc * sizeof *frag); /* fragment of each cell, SIZE_MAX: none */
    int *sector = NULL;
    size_t *parent = NULL;
    frag_stat *fs = NULL;
    edge *edges = NULL;
    out->label = calloc(nc, sizeof *out->label);
    out->nx = nx;
    out->ny = ny;
    if (!slope || !aspect || !vrm || !curv || !frag || !out->label) {
        st = gf_fail(GF_ENOMEM, "release areas: %zu cells", nc);
        goto done;
    }
    if ((st = gf_slope_aspect(dem, slope, NULL)) || (st = gf_vrm(dem, p->roughness_window, vrm, aspect)))
        goto done;
    if (!isnan(p->curvature_max) && (st = gf_plan_curvature(dem, curv)))
        goto done;

    /* candidates and their aspect class */
    int nsec = p->aspect_sectors;
    double width = 360.0 / nsec;
    for (size_t c = 0; c < nc; ++c) {
        int ok = isfinite(slope[c]) && slope[c] >= p->slope_min && slope[c] <= p->slope_max &&
                 isfinite(aspect[c]) && (!excluded || !excluded[c]);
        if (ok && !isnan(p->roughness_max))
            ok = isfinite(vrm[c]) && vrm[c] <= p->roughness_max;
        if (ok && !isnan(p->curvature_max))
            ok = isfinite(curv[c]) && fabs(curv[c]) <= p->curvature_max;
        /* vrm holds the class from here on, -1 for no candidate */
        vrm[c] = ok ? fmin(floor(fmod(aspect[c] + width / 2, 360.0) / width), nsec - 1) : -1;
    }

    /* fragments: 4-connected cells of one class (a scan-line flood fill) */
    size_t nf = 0;
    size_t *stack = (size_t *)malloc(nc * sizeof *stack);
    if (!stack) {
        st = gf_fail(GF_ENOMEM, "release areas: %zu cells", nc);
        goto done;
    }
    for (size_t c = 0; c < nc; ++c)
        frag[c] = SIZE_MAX;
    for (size_t c0 = 0; c0 < nc; ++c0) {
        if (vrm[c0] < 0 || frag[c0] != SIZE_MAX)
            continue;
        size_t top = 0;
        stack[top++] = c0;
        frag[c0] = nf;
        while (top) {
            size_t c = stack[--top];
            int i = (int)(c % (size_t)nx), j = (int)(c / (size_t)nx);
            const int di[4] = {1, -1, 0, 0}, dj[4] = {0, 0, 1, -1};
            for (int k = 0; k < 4; ++k) {
                int ii = i + di[k], jj = j + dj[k];
                if (ii < 0 || jj < 0 || ii >= nx || jj >= ny)
                    continue;
                size_t d = (size_t)jj * (size_t)nx + (size_t)ii;
                if (frag[d] == SIZE_MAX && vrm[d] == vrm[c0]) {
                    frag[d] = nf;
                    stack[top++] = d;
                }
            }
        }
        ++nf;
    }
    free(stack);
    sector = malloc((nf + 1) * sizeof *sector);
    parent = malloc((nf + 1) * sizeof *parent);
    fs = calloc(nf + 1, sizeof *fs);
    size_t cap_edges = 1024; /* grows: only borders of small fragments are kept */
    edges = malloc(cap_edges * sizeof *edges);
    if (!sector || !parent || !fs || !edges) {
        st = gf_fail(GF_ENOMEM, "release areas: %zu fragments", nf);
        goto done;
    }
    for (size_t f = 0; f < nf; ++f)
        parent[f] = f;
    for (size_t c = 0; c < nc; ++c)
        if (frag[c] != SIZE_MAX) {
            sector[frag[c]] = (int)vrm[c];
            fs[frag[c]].cells++;
        }

    /* merge small fragments into the neighbour of the longest shared border */
    size_t min_cells = (size_t)ceil(p->min_area / cell_area - 1e-9);
    for (int pass = 0; pass < 1000; ++pass) {
        size_t ne = 0;
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                size_t c = (size_t)j * (size_t)nx + (size_t)i;
                if (frag[c] == SIZE_MAX)
                    continue;
                size_t a = find(parent, frag[c]);
                size_t nb[2] = {i + 1 < nx ? c + 1 : SIZE_MAX, j + 1 < ny ? c + (size_t)nx : SIZE_MAX};
                for (int k = 0; k < 2; ++k) {
                    if (nb[k] == SIZE_MAX || frag[nb[k]] == SIZE_MAX)
                        continue;
                    size_t b = find(parent, frag[nb[k]]);
                    if (a == b || sector_gap(sector[a], sector[b], nsec) > p->merge_sectors)
                        continue;
                    if (ne + 2 > cap_edges) {
                        edge *more = realloc(edges, 2 * cap_edges * sizeof *edges);
                        if (!more) {
                            st = gf_fail(GF_ENOMEM, "release areas: %zu fragment borders", 2 * cap_edges);
                            goto done;
                        }
                        edges = more;
                        cap_edges *= 2;
                    }
                    if (fs[a].cells < min_cells)
                        edges[ne++] = (edge){a, b};
                    if (fs[b].cells < min_cells)
                        edges[ne++] = (edge){b, a};
                }
            }
        if (!ne)
            break;
        qsort(edges, ne, sizeof *edges, edge_cmp);
        int merged = 0;
        for (size_t e = 0; e < ne;) {
            size_t a = edges[e].a, best = SIZE_MAX, best_len = 0;
            while (e < ne && edges[e].a == a) {
                size_t b = edges[e].b, len = 0;
                while (e < ne && edges[e].a == a && edges[e].b == b) {
                    ++len;
                    ++e;
                }
                if (len > best_len || (len == best_len && fs[b].cells > fs[best].cells)) {
                    best = b;
                    best_len = len;
                }
            }
            size_t ra = find(parent, a), rb = find(parent, best);
            if (ra == rb || fs[ra].cells >= min_cells)
                continue;
            /* the larger keeps its class */
            if (fs[ra].cells > fs[rb].cells) {
                size_t t = ra;
                ra = rb;
                rb = t;
            }
            parent[ra] = rb;
            fs[rb].cells += fs[ra].cells;
            merged = 1;
        }
        if (!merged)
            break;
    }

    /* statistics of the merged areas */
    for (size_t f = 0; f < nf; ++f) {
        memset(&fs[f], 0, sizeof fs[f]);
        fs[f].zmax = -INFINITY;
    }
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            size_t c = (size_t)j * (size_t)nx + (size_t)i;
            if (frag[c] == SIZE_MAX)
                continue;
            size_t r = find(parent, frag[c]);
            frag[c] = r;
            frag_stat *s = &fs[r];
            s->cells++;
            s->slope += slope[c];
            s->z += dem->z[c];
            s->ex += sin(aspect[c] * RAD);
            s->ny += cos(aspect[c] * RAD);
            double x, y;
            x = dem->gt[0] + (i + 0.5) * dem->gt[1];
            y = dem->gt[3] + (j + 0.5) * dem->gt[5];
            s->x += x;
            s->y += y;
            if (dem->z[c] > s->zmax) {
                s->zmax = dem->z[c];
                s->top = c;
            }
        }
    size_t n = 0;
    for (size_t f = 0; f < nf; ++f)
        if (fs[f].cells && fs[f].cells >= min_cells && (double)fs[f].cells * cell_area >= p->min_area)
            ++n;
    out->pra = calloc(n + 1, sizeof *out->pra);
    if (!out->pra) {
        st = gf_fail(GF_ENOMEM, "release areas: %zu areas", n);
        goto done;
    }
    size_t k = 0;
    for (size_t f = 0; f < nf; ++f) {
        frag_stat *s = &fs[f];
        if (!(s->cells && s->cells >= min_cells && (double)s->cells * cell_area >= p->min_area))
            continue;
        gf_pra *a = &out->pra[k];
        a->id = (int)f; /* the fragment, for now */
        a->cells = s->cells;
        a->area_m2 = (double)s->cells * cell_area;
        a->slope_deg = s->slope / (double)s->cells;
        a->altitude_m = s->z / (double)s->cells;
        a->aspect_deg = aspect_of(s->ex, s->ny);
        a->z_max = s->zmax;
        a->top_col = (int)(s->top % (size_t)nx);
        a->top_row = (int)(s->top / (size_t)nx);
        a->x = s->x / (double)s->cells;
        a->y = s->y / (double)s->cells;
        ++k;
    }
    qsort(out->pra, n, sizeof *out->pra, pra_cmp);
    /* fragment -> id */
    for (size_t f = 0; f < nf; ++f)
        parent[f] = 0;
    for (size_t a = 0; a < n; ++a) {
        parent[out->pra[a].id] = a + 1;
        out->pra[a].id = (int)(a + 1);
    }
    for (size_t c = 0; c < nc; ++c)
        out->label[c] = frag[c] == SIZE_MAX ? 0 : (int)parent[frag[c]];
    out->n = n;
    st = GF_SUCCESS;
done:
    free(slope);
    free(aspect);
    free(vrm);
    free(curv);
    free(frag);
    free(sector);
    free(parent);
    free(fs);
    free(edges);
    return st;
}
