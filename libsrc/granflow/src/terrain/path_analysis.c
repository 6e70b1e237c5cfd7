/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Path analysis of peak rasters: see granflow/path_analysis.h and the
 * model reference doc/theory/hazard-analysis.md, sections 1-3 (Fischer 2013,
 * NHESS 13, 1655). */
#include "granflow/path_analysis.h"
#include "internal.h"
#include "terrain_internal.h"

#include <cpl_conv.h>
#include <ogr_api.h>
#include <ogr_srs_api.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/*------------------------------------------------------- rasters, bilinear --*/

/* fractional pixel indices of (x, y) on r, pixel centres at integers; 1 when
 * (x, y) lies in the square of pixel centres (to 1e-9 of a cell), the one
 * test of gf_raster_bilinear and gf_raster_covers */
static int pixel_position(const gf_raster *r, double x, double y, double *fc, double *fr)
{
    *fc = (x - r->gt[0]) / r->gt[1] - 0.5, *fr = (y - r->gt[3]) / r->gt[5] - 0.5;
    const double eps = 1e-9;
    return *fc >= -eps && *fc <= r->nx - 1 + eps && *fr >= -eps && *fr <= r->ny - 1 + eps;
}

int gf_raster_covers(const gf_raster *r, double x, double y)
{
    double fc, fr;
    return pixel_position(r, x, y, &fc, &fr);
}

double gf_raster_bilinear(const gf_raster *r, double x, double y)
{
    double fc, fr;
    if (!pixel_position(r, x, y, &fc, &fr))
        return NAN;
    int c0 = (int)floor(fc), r0 = (int)floor(fr);
    c0 = c0 < 0 ? 0 : (c0 > r->nx - 2 ? r->nx - 2 : c0);
    r0 = r0 < 0 ? 0 : (r0 > r->ny - 2 ? r->ny - 2 : r0);
    double tc = fc - c0, tr = fr - r0;
    tc = tc < 0 ? 0 : (tc > 1 ? 1 : tc);
    tr = tr < 0 ? 0 : (tr > 1 ? 1 : tr);
    const double w[4] = {(1 - tc) * (1 - tr), tc * (1 - tr), (1 - tc) * tr, tc * tr};
    const size_t nx = (size_t)r->nx, k0 = (size_t)r0 * nx + (size_t)c0;
    const double v[4] = {r->z[k0], r->z[k0 + 1], r->z[k0 + nx], r->z[k0 + nx + 1]};
    double sum = 0.0;
    for (int k = 0; k < 4; ++k) {
        if (w[k] == 0.0)
            continue;
        if (isnan(v[k]))
            return NAN; /* a NODATA pixel with weight */
        sum += w[k] * v[k];
    }
    return sum;
}

int gf_raster_same_grid(const gf_raster *a, const gf_raster *b)
{
    if (a->nx != b->nx || a->ny != b->ny)
        return 0;
    const double tol = 1e-6 * fabs(a->gt[1]);
    for (int k = 0; k < 6; ++k)
        if (fabs(a->gt[k] - b->gt[k]) > tol)
            return 0;
    return 1;
}

/*------------------------------------------------------------- the grid --*/

void gf_path_grid_free(gf_path_grid *g)
{
    if (!g)
        return;
    free(g->s), free(g->l), free(g->xp), free(g->yp), free(g->zp);
    free(g->nx), free(g->ny), free(g->x), free(g->y), free(g->area);
    memset(g, 0, sizeof *g);
}

/* horizontal length of a polyline */
static double polyline_length(size_t n, const double *xy)
{
    double L = 0.0;
    for (size_t k = 1; k < n; ++k)
        L += hypot(xy[2 * k] - xy[2 * k - 2], xy[2 * k + 1] - xy[2 * k - 1]);
    return L;
}

/* the DEM's extent of pixel centres, for messages */
static void centre_box(const gf_raster *dem, double b[4])
{
    double x0, y0, x1, y1;
    gf_raster_centre(dem, 0, dem->ny - 1, &x0, &y0);
    gf_raster_centre(dem, dem->nx - 1, 0, &x1, &y1);
    b[0] = x0, b[1] = y0, b[2] = x1, b[3] = y1;
}

static gf_status outside(const gf_raster *dem, const char *what, size_t k, double x, double y,
                         double s)
{
    double b[4];
    centre_box(dem, b);
    const int in_box = x >= b[0] && x <= b[2] && y >= b[1] && y <= b[3];
    char along[64] = "";
    if (!isnan(s))
        snprintf(along, sizeof along, ", %.1f m along it", s);
    return gf_fail(GF_EDOM, "path %s %zu at (%.2f, %.2f)%s: %s; the path must lie inside the DEM"
                            " (pixel centres x %.2f .. %.2f, y %.2f .. %.2f) and off its NODATA"
                            " (doc/theory/hazard-analysis.md, section 1)", what, k, x, y, along,
                   in_box ? "the DEM is NODATA there" : "outside the DEM", b[0], b[2], b[1], b[3]);
}

gf_status gf_path_grid_make(const gf_raster *dem, size_t n, const double *xy_in, double width,
                            gf_path_grid *g)
{
    if (!dem || !xy_in || !g)
        return gf_fail(GF_EINVAL, "gf_path_grid_make: null argument");
    memset(g, 0, sizeof *g);
    if (n < 2)
        return gf_fail(GF_EDOM, "path: %zu point(s); a path needs at least 2", n);
    if (!(isfinite(width) && width > 0.0))
        return gf_fail(GF_EDOM, "path: domain width %g m; it must be finite and > 0", width);
    for (size_t k = 0; k < 2 * n; ++k)
        if (!isfinite(xy_in[k]))
            return gf_fail(GF_EDOM, "path: point %zu has a non-finite coordinate", k / 2);
    const double h = dem->gt[1];
    /* every vertex on the DEM */
    for (size_t k = 0; k < n; ++k)
        if (isnan(gf_raster_bilinear(dem, xy_in[2 * k], xy_in[2 * k + 1])))
            return outside(dem, "vertex", k, xy_in[2 * k], xy_in[2 * k + 1], NAN);
    const double L = polyline_length(n, xy_in);
    if (!(L >= 2.0 * h))
        return gf_fail(GF_EDOM, "path: horizontal length %.3g m; at least two cell sizes (%.3g m)"
                                " are needed", L, 2.0 * h);
    double *xy = malloc(2 * n * sizeof *xy);
    if (!xy)
        return gf_fail(GF_ENOMEM, "path: out of memory");
    memcpy(xy, xy_in, 2 * n * sizeof *xy);
    /* from the top down, as AvaFrame turns a path drawn upwards */
    if (gf_raster_bilinear(dem, xy[2 * n - 2], xy[2 * n - 1]) > gf_raster_bilinear(dem, xy[0], xy[1])) {
        g->reversed = 1;
        for (size_t a = 0, b = n - 1; a < b; ++a, --b)
            for (int c = 0; c < 2; ++c) {
                const double t = xy[2 * a + c];
                xy[2 * a + c] = xy[2 * b + c], xy[2 * b + c] = t;
            }
    }
    /* Resampled at s_i = i h along the polyline.  (AvaFrame first resamples
     * at h / 5 and then takes one point per cell size; on the straight
     * pieces between the given vertices that gives these same points.) */
    const size_t ns = (size_t)floor(L / h * (1.0 + 1e-12)) + 1;
    const size_t half = (size_t)floor(width / (2.0 * h) * (1.0 + 1e-12));
    const size_t nl = 2 * half + 1;
    g->ns = ns, g->nl = nl, g->h = h, g->width = width, g->length = L;
    const size_t N = ns * nl;
    g->s = malloc(ns * sizeof(double)), g->l = malloc(nl * sizeof(double));
    g->xp = malloc(ns * sizeof(double)), g->yp = malloc(ns * sizeof(double));
    g->zp = malloc(ns * sizeof(double)), g->nx = malloc(ns * sizeof(double));
    g->ny = malloc(ns * sizeof(double));
    g->x = malloc(N * sizeof(double)), g->y = malloc(N * sizeof(double));
    g->area = malloc(N * sizeof(double));
    gf_status st = GF_SUCCESS;
    if (!g->s || !g->l || !g->xp || !g->yp || !g->zp || !g->nx || !g->ny || !g->x || !g->y || !g->area) {
        st = gf_fail(GF_ENOMEM, "path: out of memory for a grid of %zu x %zu points", ns, nl);
        goto done;
    }
    size_t seg = 0;
    double s0 = 0.0; /* s at the start of segment seg */
    for (size_t i = 0; i < ns; ++i) {
        const double si = (double)i * h;
        double len = hypot(xy[2 * seg + 2] - xy[2 * seg], xy[2 * seg + 3] - xy[2 * seg + 1]);
        while (seg + 2 < n && s0 + len < si) {
            s0 += len, ++seg;
            len = hypot(xy[2 * seg + 2] - xy[2 * seg], xy[2 * seg + 3] - xy[2 * seg + 1]);
        }
        double t = len > 0.0 ? (si - s0) / len : 0.0;
        t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
        g->s[i] = si;
        g->xp[i] = xy[2 * seg] + t * (xy[2 * seg + 2] - xy[2 * seg]);
        g->yp[i] = xy[2 * seg + 1] + t * (xy[2 * seg + 3] - xy[2 * seg + 1]);
        g->zp[i] = gf_raster_bilinear(dem, g->xp[i], g->yp[i]);
        if (isnan(g->zp[i])) {
            st = outside(dem, "point", i, g->xp[i], g->yp[i], si);
            goto done;
        }
    }
    for (size_t j = 0; j < nl; ++j)
        g->l[j] = ((double)j - (double)half) * h;
    /* cross-section directions: the bisector of the adjacent segments'
     * normals (left normals (-dy, dx) / |d|) */
    for (size_t i = 0; i < ns; ++i) {
        double nsum[2] = {0.0, 0.0};
        for (int side = 0; side < 2; ++side) {
            const size_t a = side == 0 ? (i > 0 ? i - 1 : i) : i;
            const size_t b = side == 0 ? (i > 0 ? i : i + 1) : (i + 1 < ns ? i + 1 : i);
            if (a == b)
                continue;
            const double dx = g->xp[b] - g->xp[a], dy = g->yp[b] - g->yp[a], d = hypot(dx, dy);
            if (d > 0.0)
                nsum[0] += -dy / d, nsum[1] += dx / d;
        }
        const double m = hypot(nsum[0], nsum[1]);
        if (!(m > 1e-12)) {
            st = gf_fail(GF_EDOM, "path: it turns back on itself at point %zu (%.2f, %.2f), %.1f m"
                                  " along it; no cross-section direction", i, g->xp[i], g->yp[i],
                         g->s[i]);
            goto done;
        }
        g->nx[i] = nsum[0] / m, g->ny[i] = nsum[1] / m;
        for (size_t j = 0; j < nl; ++j) {
            g->x[i * nl + j] = g->xp[i] + g->l[j] * g->nx[i];
            g->y[i * nl + j] = g->yp[i] + g->l[j] * g->ny[i];
        }
    }
    /* cell areas |dX/di x dX/dj| */
    for (size_t i = 0; i < ns; ++i) {
        const size_t ia = i > 0 ? i - 1 : i, ib = i + 1 < ns ? i + 1 : i;
        for (size_t j = 0; j < nl; ++j) {
            const size_t ja = j > 0 ? j - 1 : j, jb = j + 1 < nl ? j + 1 : j;
            const double di = (double)(ib - ia), dj = (double)(jb - ja);
            const double ax = (g->x[ib * nl + j] - g->x[ia * nl + j]) / di;
            const double ay = (g->y[ib * nl + j] - g->y[ia * nl + j]) / di;
            const double bx = (g->x[i * nl + jb] - g->x[i * nl + ja]) / dj;
            const double by = (g->y[i * nl + jb] - g->y[i * nl + ja]) / dj;
            g->area[i * nl + j] = fabs(ax * by - ay * bx);
        }
    }
done:
    free(xy);
    if (st)
        gf_path_grid_free(g);
    return st;
}

size_t gf_path_snap(const gf_path_grid *g, double x, double y, double *dist)
{
    size_t best = 0;
    double d = HUGE_VAL;
    for (size_t i = 0; i < g->ns; ++i) {
        const double di = hypot(g->xp[i] - x, g->yp[i] - y);
        if (di < d)
            d = di, best = i;
    }
    if (dist)
        *dist = d;
    return best;
}

/*------------------------------------------------- fields and profiles --*/

void gf_path_sample(const gf_path_grid *g, const gf_raster *r, double *out)
{
    const size_t N = g->ns * g->nl;
    for (size_t k = 0; k < N; ++k)
        out[k] = gf_raster_bilinear(r, g->x[k], g->y[k]);
}

void gf_path_coverage(const gf_path_grid *g, const gf_raster *r, const gf_raster *within,
                      gf_path_cover *c)
{
    memset(c, 0, sizeof *c);
    c->s_min = c->l_min = c->path_s_min = HUGE_VAL, c->s_max = c->l_max = c->path_s_max = -HUGE_VAL;
    for (size_t i = 0; i < g->ns; ++i) {
        if (!gf_raster_covers(r, g->xp[i], g->yp[i])) {
            ++c->n_path_out;
            c->path_s_min = fmin(c->path_s_min, g->s[i]), c->path_s_max = fmax(c->path_s_max, g->s[i]);
        }
        for (size_t j = 0; j < g->nl; ++j) {
            const size_t k = i * g->nl + j;
            if (within && !gf_raster_covers(within, g->x[k], g->y[k]))
                continue;
            ++c->n_grid;
            if (gf_raster_covers(r, g->x[k], g->y[k]))
                continue;
            ++c->n_out;
            c->area_out += g->area[k];
            c->s_min = fmin(c->s_min, g->s[i]), c->s_max = fmax(c->s_max, g->s[i]);
            c->l_min = fmin(c->l_min, g->l[j]), c->l_max = fmax(c->l_max, g->l[j]);
        }
    }
    if (!c->n_out)
        c->s_min = c->s_max = c->l_min = c->l_max = NAN;
    if (!c->n_path_out)
        c->path_s_min = c->path_s_max = NAN;
}

void gf_path_profiles(const gf_path_grid *g, const double *a, double *cross_max,
                      double *cross_mean)
{
    for (size_t i = 0; i < g->ns; ++i) {
        double mx = -HUGE_VAL, sum = 0.0;
        size_t cnt = 0;
        for (size_t j = 0; j < g->nl; ++j) {
            const double v = a[i * g->nl + j];
            if (isnan(v))
                continue;
            mx = v > mx ? v : mx, sum += v, ++cnt;
        }
        if (cross_max)
            cross_max[i] = cnt ? mx : NAN;
        if (cross_mean)
            cross_mean[i] = cnt ? sum / (double)cnt : NAN;
    }
}

gf_status gf_path_runout(const gf_path_grid *g, const double *a, double threshold, gf_runout *r)
{
    if (!g || !a || !r)
        return gf_fail(GF_EINVAL, "gf_path_runout: null argument");
    memset(r, 0, sizeof *r);
    if (!isfinite(threshold))
        return gf_fail(GF_EDOM, "runout: threshold %g is not finite", threshold);
    size_t first = g->ns, last = 0;
    double top = -HUGE_VAL;
    for (size_t i = 0; i < g->ns; ++i)
        for (size_t j = 0; j < g->nl; ++j) {
            const double v = a[i * g->nl + j];
            if (isnan(v))
                continue;
            top = v > top ? v : top;
            if (v > threshold) {
                first = i < first ? i : first;
                last = i;
            }
        }
    if (first == g->ns)
        return gf_fail(GF_EDOM, "runout: no value on the path's grid exceeds the threshold %g"
                                " (the largest is %g); lower the threshold or check the path",
                       threshold, top);
    r->i_start = first, r->i_runout = last;
    r->s_start = g->s[first], r->s_runout = g->s[last];
    size_t jbest = 0;
    double vbest = -HUGE_VAL;
    for (size_t j = 0; j < g->nl; ++j) {
        const double v = a[last * g->nl + j];
        if (!isnan(v) && v > vbest)
            vbest = v, jbest = j;
    }
    r->x_runout = g->x[last * g->nl + jbest], r->y_runout = g->y[last * g->nl + jbest];
    r->l_runout = g->l[jbest];
    r->z_start = g->zp[first], r->z_runout = g->zp[last];
    r->delta_sxy = r->s_runout - r->s_start;
    r->delta_z = r->z_start - r->z_runout;
    r->angle = r->delta_sxy > 0.0 ? atan2(r->delta_z, r->delta_sxy) * GF_RAD2DEG : NAN;
    return GF_SUCCESS;
}

void gf_path_indicators(const gf_path_grid *g, const double *cross_max, const gf_runout *r,
                        double *mma, double *ama)
{
    double mx = -HUGE_VAL, sum = 0.0;
    size_t cnt = 0;
    for (size_t i = 0; i < g->ns; ++i) {
        const double v = cross_max[i];
        if (isnan(v))
            continue;
        mx = v > mx ? v : mx;
        if (r && i >= r->i_start && i <= r->i_runout)
            sum += v, ++cnt;
    }
    if (mma)
        *mma = mx > -HUGE_VAL ? mx : NAN;
    if (ama)
        *ama = cnt ? sum / (double)cnt : NAN;
}

gf_status gf_path_beta_point(const gf_path_grid *g, size_t i_from, double angle_deg,
                             double ds_min, size_t *i_beta)
{
    if (!g || !i_beta)
        return gf_fail(GF_EINVAL, "gf_path_beta_point: null argument");
    if (!(isfinite(angle_deg) && angle_deg > 0.0 && angle_deg < 90.0))
        return gf_fail(GF_EDOM, "beta point: angle %g deg outside (0, 90)", angle_deg);
    if (!(isfinite(ds_min) && ds_min >= 0.0))
        return gf_fail(GF_EDOM, "beta point: dsMin %g m must be finite and >= 0", ds_min);
    const size_t ns = g->ns;
    if (i_from >= ns)
        return gf_fail(GF_EDOM, "beta point: start index %zu beyond the path (%zu points)", i_from, ns);
    unsigned char *below = malloc(ns);
    if (!below)
        return gf_fail(GF_ENOMEM, "beta point: out of memory");
    const double tb = tan(angle_deg * GF_DEG);
    for (size_t i = 0; i < ns; ++i) {
        const size_t a = i > 0 ? i - 1 : i, b = i + 1 < ns ? i + 1 : i;
        const double slope = -(g->zp[b] - g->zp[a]) / (g->s[b] - g->s[a]);
        below[i] = slope < tb;
    }
    gf_status st = gf_fail(GF_EDOM, "beta point: no path point from %.1f m on where the slope stays"
                                    " below %g deg for %g m (startOfRunoutAreaAngle, dsMin); check"
                                    " the path and the split point", g->s[i_from], angle_deg, ds_min);
    for (size_t i = i_from; i < ns; ++i) {
        if (!below[i] || g->s[ns - 1] - g->s[i] < ds_min * (1.0 - 1e-12))
            continue;
        size_t k = i;
        while (k + 1 < ns && g->s[k + 1] - g->s[i] <= ds_min * (1.0 + 1e-12) && below[k + 1])
            ++k;
        if (k + 1 >= ns || g->s[k + 1] - g->s[i] > ds_min * (1.0 + 1e-12)) {
            *i_beta = i;
            st = GF_SUCCESS;
            break;
        }
    }
    free(below);
    return st;
}

/*------------------------------------------------------- comparison --*/

static int cell_class(double a, double ref, double thr)
{
    if (isnan(a) && isnan(ref))
        return 0;
    const int ra = a > thr, rr = ref > thr;
    return ra && rr ? 1 : (ra ? 2 : (rr ? 3 : 4));
}

void gf_path_compare(const gf_path_grid *g, const double *a, const double *ref, double threshold,
                     size_t i_from, gf_path_areas *ar)
{
    memset(ar, 0, sizeof *ar);
    for (size_t i = i_from; i < g->ns; ++i)
        for (size_t j = 0; j < g->nl; ++j) {
            const size_t k = i * g->nl + j;
            const int c = cell_class(a[k], ref[k], threshold);
            const double A = g->area[k];
            if (c == 1)
                ar->tp += A;
            else if (c == 2)
                ar->fp += A;
            else if (c == 3)
                ar->fn += A;
            else if (c == 4)
                ar->tn += A;
        }
    ar->a_ref = ar->tp + ar->fn;
}

void gf_path_compare_map(const gf_path_grid *g, const double *a, const double *ref,
                         double threshold, size_t i_from, unsigned char *out)
{
    for (size_t i = 0; i < g->ns; ++i)
        for (size_t j = 0; j < g->nl; ++j) {
            const size_t k = i * g->nl + j;
            out[k] = i < i_from ? 0 : (unsigned char)cell_class(a[k], ref[k], threshold);
        }
}

/*------------------------------------------------------ vector input --*/

void gf_path_locate(size_t n, const double *xy, double x, double y, double *s, double *l)
{
    double best = HUGE_VAL, s0 = 0.0;
    *s = 0.0, *l = 0.0;
    for (size_t i = 0; i + 1 < n; ++i) {
        const double ax = xy[2 * i], ay = xy[2 * i + 1], dx = xy[2 * i + 2] - ax, dy = xy[2 * i + 3] - ay;
        const double len2 = dx * dx + dy * dy, len = sqrt(len2);
        if (len2 > 0.0) {
            double t = ((x - ax) * dx + (y - ay) * dy) / len2;
            t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
            const double px = ax + t * dx - x, py = ay + t * dy - y, d = sqrt(px * px + py * py);
            if (d < best) {
                best = d;
                *s = s0 + t * len;
                /* left of the direction (dx, dy): cross product > 0 */
                const double cr = dx * (y - ay) - dy * (x - ax);
                *l = cr >= 0.0 ? d : -d;
            }
        }
        s0 += len;
    }
}

gf_status gf_path_read(const char *path, size_t *n, double **xy)
{
    if (!path || !n || !xy)
        return gf_fail(GF_EINVAL, "gf_path_read: null argument");
    *n = 0, *xy = NULL;
    gf_terrain_gdal_init();
    gf_status st;
    GDALDatasetH ds = gf_terrain_open_vector("path", path, &st);
    if (!ds)
        return st;
    st = GF_SUCCESS;
    OGRFeatureH f = gf_terrain_first_feature(ds, "path", path, &st);
    if (!f)
        goto done;
    OGRwkbGeometryType t;
    OGRGeometryH g = gf_terrain_single_line(OGR_F_GetGeometryRef(f), &t);
    if (t != wkbLineString) {
        st = gf_fail(GF_EDOM, "path %s: feature %ld is a %s, not a line (the path is one line"
                              " string drawn from the release down through the runout)", path,
                     (long)OGR_F_GetFID(f), g ? OGRGeometryTypeToName(t) : "feature without geometry");
        goto done;
    }
    const int np = OGR_G_GetPointCount(g);
    if (np < 2) {
        st = gf_fail(GF_EDOM, "path %s: %d point(s); a path needs at least 2", path, np);
        goto done;
    }
    *xy = malloc(2 * (size_t)np * sizeof **xy);
    if (!*xy) {
        st = gf_fail(GF_ENOMEM, "path %s: out of memory", path);
        goto done;
    }
    for (int i = 0; i < np; ++i) {
        (*xy)[2 * i] = OGR_G_GetX(g, i), (*xy)[2 * i + 1] = OGR_G_GetY(g, i);
        if (!isfinite((*xy)[2 * i]) || !isfinite((*xy)[2 * i + 1])) {
            st = gf_fail(GF_EDOM, "path %s: point %d is not finite", path, i);
            goto done;
        }
    }
    *n = (size_t)np;
done:
    if (f)
        OGR_F_Destroy(f);
    GDALClose(ds);
    if (st) {
        free(*xy);
        *xy = NULL, *n = 0;
    }
    return st;
}

gf_status gf_point_read(const char *path, double *x, double *y)
{
    if (!path || !x || !y)
        return gf_fail(GF_EINVAL, "gf_point_read: null argument");
    gf_terrain_gdal_init();
    gf_status st;
    GDALDatasetH ds = gf_terrain_open_vector("point", path, &st);
    if (!ds)
        return st;
    st = GF_SUCCESS;
    OGRFeatureH f = gf_terrain_first_feature(ds, "point", path, &st);
    if (!f)
        goto done;
    OGRGeometryH g = OGR_F_GetGeometryRef(f);
    OGRwkbGeometryType t = g ? wkbFlatten(OGR_G_GetGeometryType(g)) : wkbNone;
    if (t == wkbMultiPoint && OGR_G_GetGeometryCount(g) >= 1) {
        g = OGR_G_GetGeometryRef(g, 0);
        t = wkbFlatten(OGR_G_GetGeometryType(g));
    }
    if (t != wkbPoint) {
        st = gf_fail(GF_EDOM, "point %s: feature %ld is a %s, not a point", path,
                     (long)OGR_F_GetFID(f), g ? OGRGeometryTypeToName(t) : "feature without geometry");
        goto done;
    }
    *x = OGR_G_GetX(g, 0), *y = OGR_G_GetY(g, 0);
    if (!isfinite(*x) || !isfinite(*y))
        st = gf_fail(GF_EDOM, "point %s: not finite", path);
done:
    if (f)
        OGR_F_Destroy(f);
    GDALClose(ds);
    return st;
}
