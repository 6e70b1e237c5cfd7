/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Scenario release depths (Salm, Burkard and Gubler 1990), the alpha-beta
 * screening (Lied and Bakkehoi 1980) on a thalweg, and the merge of many
 * releases' peak rasters (granflow/regional.h; doc/theory/regional.md,
 * sections 2-4). */
#include "granflow/regional.h"
#include "internal.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define RAD GF_DEG

gf_status gf_salm_slope_factor(double psi_deg, double *f)
{
    if (!(psi_deg >= 15 && psi_deg <= 90))
        return gf_fail(GF_EDOM,
                       "release depth: slope psi = %g deg must be in [15, 90] (the slope factor "
                       "0.291 / (sin psi - 0.202 cos psi) is not defined below 11.4 deg)",
                       psi_deg);
    *f = 0.291 / (sin(psi_deg * RAD) - 0.202 * cos(psi_deg * RAD));
    return GF_SUCCESS;
}

gf_status gf_release_depth(double d0star, double gradient, double z, double z_ref, double psi_deg,
                           double *d0)
{
    if (!(d0star >= 0 && isfinite(d0star)))
        return gf_fail(GF_EDOM, "release depth: d0* = %g m must be finite and >= 0", d0star);
    if (!isfinite(gradient) || !isfinite(z) || !isfinite(z_ref))
        return gf_fail(GF_EDOM, "release depth: gradient %g m/m, altitude %g m and reference altitude %g m must be finite",
                       gradient, z, z_ref);
    double f;
    gf_status st = gf_salm_slope_factor(psi_deg, &f);
    if (st)
        return st;
    double d = d0star + gradient * (z - z_ref);
    if (d < 0)
        return gf_fail(GF_EDOM,
                       "release depth: d0* + gradient (z - z_ref) = %g + %g (%g - %g) = %g m is negative at altitude %g m",
                       d0star, gradient, z, z_ref, d, z);
    *d0 = d * f;
    return GF_SUCCESS;
}

void gf_alpha_beta_params_default(gf_alpha_beta_params *p)
{
    p->k1 = 0.96;
    p->k2 = -1.4;
    p->sd = 2.3;
    p->beta_slope = 10;
    p->ds_min = 30;
}

/* z of the profile at s (linear; the ends held) */
static double profile_z(size_t n, const double *s, const double *z, double x, size_t from)
{
    if (x <= s[0])
        return z[0];
    for (size_t i = from; i + 1 < n; ++i)
        if (x <= s[i + 1]) {
            double t = (x - s[i]) / (s[i + 1] - s[i]);
            return z[i] + t * (z[i + 1] - z[i]);
        }
    return z[n - 1];
}

gf_status gf_alpha_beta_profile(size_t n, const double *s, const double *z, const gf_alpha_beta_params *p,
                                gf_alpha_beta *out)
{
    if (n < 2 || !s || !z || !p || !out)
        return gf_fail(GF_EINVAL, "alpha-beta: a profile needs at least 2 points (got %zu)", n);
    if (!(isfinite(p->k1) && p->k1 > 0 && isfinite(p->k2) && isfinite(p->sd) && p->sd >= 0 &&
          p->beta_slope > 0 && p->beta_slope < 90 && isfinite(p->ds_min) && p->ds_min >= 0))
        return gf_fail(GF_EDOM,
                       "alpha-beta: parameters k1 = %g (> 0), k2 = %g, sd = %g (>= 0), beta slope %g deg (in (0, 90)), "
                       "ds_min %g m (>= 0) out of range",
                       p->k1, p->k2, p->sd, p->beta_slope, p->ds_min);
    for (size_t i = 0; i < n; ++i) {
        if (!isfinite(s[i]) || !isfinite(z[i]))
            return gf_fail(GF_EDOM, "alpha-beta: profile point %zu (s = %g m, z = %g m) is not finite", i, s[i], z[i]);
        if (i && !(s[i] > s[i - 1]))
            return gf_fail(GF_EDOM, "alpha-beta: profile distance s must increase strictly (s[%zu] = %g m, s[%zu] = %g m)",
                           i - 1, s[i - 1], i, s[i]);
    }
    double gb = tan(p->beta_slope * RAD);
    size_t kb = SIZE_MAX;
    for (size_t k = 0; k + 1 < n; ++k) {
        double g = -(z[k + 1] - z[k]) / (s[k + 1] - s[k]);
        if (g >= gb)
            continue;
        /* stays below beta_slope over ds_min after the segment's end */
        double s1 = s[k + 1], s2 = fmin(s1 + p->ds_min, s[n - 1]);
        if (s2 > s1) {
            double chord = -(profile_z(n, s, z, s2, k) - z[k + 1]) / (s2 - s1);
            if (chord >= gb)
                continue;
        }
        kb = k;
        break;
    }
    if (kb == SIZE_MAX)
        return gf_fail(GF_EDOM, "alpha-beta: the profile (%.1f m long, %zu points) never falls below %g deg: no beta point",
                       s[n - 1] - s[0], n, p->beta_slope);
    if (kb == 0)
        return gf_fail(GF_EDOM, "alpha-beta: the profile starts below %g deg (its first segment): no beta point below a top",
                       p->beta_slope);
    double g0 = -(z[kb] - z[kb - 1]) / (s[kb] - s[kb - 1]);
    double g1 = -(z[kb + 1] - z[kb]) / (s[kb + 1] - s[kb]);
    double m0 = 0.5 * (s[kb - 1] + s[kb]), m1 = 0.5 * (s[kb] + s[kb + 1]);
    double t = (g0 - gb) / (g0 - g1);
    memset(out, 0, sizeof *out);
    out->s_beta = m0 + t * (m1 - m0);
    out->i_beta = out->s_beta < s[kb] ? kb - 1 : kb;
    out->z_beta = profile_z(n, s, z, out->s_beta, out->i_beta);
    out->beta = atan((z[0] - out->z_beta) / (out->s_beta - s[0])) / RAD;
    out->alpha = p->k1 * out->beta + p->k2;
    const double a[3] = {out->alpha, out->alpha - p->sd, out->alpha + p->sd};
    for (int m = 0; m < 3; ++m) {
        double ta = tan(a[m] * RAD);
        out->s_alpha[m] = out->z_alpha[m] = NAN;
        /* d = profile - line: < 0 while the profile is below the line */
        double sp = out->s_beta, dp = out->z_beta - (z[0] - ta * (out->s_beta - s[0]));
        if (dp >= 0) {
            out->s_alpha[m] = out->s_beta;
            out->z_alpha[m] = out->z_beta;
            continue;
        }
        for (size_t i = out->i_beta + 1; i < n; ++i) {
            double d = z[i] - (z[0] - ta * (s[i] - s[0]));
            if (d >= 0) {
                double u = dp / (dp - d);
                out->s_alpha[m] = sp + u * (s[i] - sp);
                out->z_alpha[m] = z[0] - ta * (out->s_alpha[m] - s[0]);
                break;
            }
            sp = s[i];
            dp = d;
        }
    }
    return GF_SUCCESS;
}

/* is cell c one of the path's m cells? */
static int visited(const size_t *cell, size_t m, size_t c)
{
    for (size_t k = m; k-- > 0;)
        if (cell[k] == c)
            return 1;
    return 0;
}

gf_status gf_thalweg_d8(const gf_raster *dem, int col, int row, double max_climb, double max_flat, double **xyzs,
                       size_t *n)
{
    if (!dem || !dem->z || !xyzs || !n)
        return gf_fail(GF_EINVAL, "thalweg: no DEM or output given");
    *xyzs = NULL;
    *n = 0;
    int nx = dem->nx, ny = dem->ny;
    if (col < 0 || row < 0 || col >= nx || row >= ny)
        return gf_fail(GF_EDOM, "thalweg: start cell (%d, %d) outside the grid of %d x %d cells", col, row, nx, ny);
    if (!isfinite(dem->z[(size_t)row * (size_t)nx + (size_t)col]))
        return gf_fail(GF_EDOM, "thalweg: start cell (%d, %d) is NODATA", col, row);
    if (!(max_climb >= 0 && isfinite(max_climb)) || !(max_flat >= 0 && isfinite(max_flat)))
        return gf_fail(GF_EDOM, "thalweg: max_climb %g m and max_flat %g m must be finite and >= 0", max_climb,
                       max_flat);
    double dx = fabs(dem->gt[1]), dy = fabs(dem->gt[5]);
    size_t cap = 256, m = 0;
    double *p = malloc(4 * cap * sizeof *p);
    size_t *cell = malloc(cap * sizeof *cell);
    if (!p || !cell) {
        free(p);
        free(cell);
        return gf_fail(GF_ENOMEM, "thalweg: %zu points", cap);
    }
    double s = 0, zlow = INFINITY, s_low = 0;
    int pa = 0, pb = 0; /* the last step's direction */
    size_t nc = (size_t)nx * (size_t)ny;
    for (;;) {
        size_t c = (size_t)row * (size_t)nx + (size_t)col;
        if (m == cap) {
            double *q = realloc(p, 8 * cap * sizeof *p);
            size_t *r = q ? realloc(cell, 2 * cap * sizeof *cell) : NULL;
            if (!q || !r) {
                free(q ? q : p);
                free(cell);
                return gf_fail(GF_ENOMEM, "thalweg: %zu points", 2 * cap);
            }
            p = q;
            cell = r;
            cap *= 2;
        }
        p[4 * m] = dem->gt[0] + (col + 0.5) * dem->gt[1];
        p[4 * m + 1] = dem->gt[3] + (row + 0.5) * dem->gt[5];
        p[4 * m + 2] = dem->z[c];
        p[4 * m + 3] = s;
        cell[m] = c;
        ++m;
        if (dem->z[c] < zlow) {
            zlow = dem->z[c];
            s_low = s;
        }
        if (m >= nc || s - s_low > max_flat)
            break;
        /* the steepest drop; in a pit (no lower neighbour) the lowest
         * neighbour not on the path, while it stays within max_climb of the
         * lowest point reached */
        double best = 0, bd = 0, lowest = INFINITY, ld = 0;
        int bi = -1, bj = -1, li = -1, lj = -1;
        for (int b = -1; b <= 1; ++b)
            for (int a = -1; a <= 1; ++a) {
                int i = col + a, j = row + b;
                if ((!a && !b) || i < 0 || j < 0 || i >= nx || j >= ny)
                    continue;
                size_t e = (size_t)j * (size_t)nx + (size_t)i;
                double v = dem->z[e];
                if (!isfinite(v))
                    continue;
                double d = hypot(a * dx, b * dy), g = (dem->z[c] - v) / d;
                if (g > best) {
                    best = g;
                    bd = d;
                    bi = i;
                    bj = j;
                }
                /* ties (a level floor) keep the last step's direction */
                int keep = v == lowest && a == pa && b == pb;
                if (max_climb > 0 && (v < lowest || keep) && v - zlow <= max_climb && !visited(cell, m, e)) {
                    lowest = v;
                    ld = d;
                    li = i;
                    lj = j;
                }
            }
        if (bi < 0 || visited(cell, m, (size_t)bj * (size_t)nx + (size_t)bi)) {
            if (li < 0)
                break;
            bi = li;
            bj = lj;
            bd = ld;
        }
        pa = bi - col;
        pb = bj - row;
        col = bi;
        row = bj;
        s += bd;
    }
    free(cell);
    *xyzs = p;
    *n = m;
    return GF_SUCCESS;
}

gf_status gf_merge_max(size_t m, size_t ncell, const double *const *fields, const long *ids, double threshold,
                       double *max, unsigned *count, long *who)
{
    if (m < 1 || !fields || !max)
        return gf_fail(GF_EINVAL, "merge: at least one raster is needed (got %zu)", m);
    if (!isfinite(threshold))
        return gf_fail(GF_EDOM, "merge: threshold %g must be finite", threshold);
    for (size_t c = 0; c < ncell; ++c) {
        double v = NAN;
        long w = -1;
        unsigned cnt = 0;
        for (size_t k = 0; k < m; ++k) {
            double f = fields[k][c];
            if (isnan(f))
                continue;
            if (isnan(v) || f > v) {
                v = f;
                w = ids ? ids[k] : (long)k;
            }
            if (f > threshold)
                ++cnt;
        }
        max[c] = v;
        if (count)
            count[c] = cnt;
        if (who)
            who[c] = w;
    }
    return GF_SUCCESS;
}
