/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Calibration designs: GSL's Sobol sequence, Morris trajectories and their
 * elementary effects (granflow/calibration.h; doc/theory/calibration.md,
 * section 1). */
#include "granflow/calibration.h"
#include "granflow/ensemble.h"
#include "internal.h"

#include <gsl/gsl_qrng.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

gf_status gf_design_sobol(size_t n, size_t d, size_t skip, double *u)
{
    if (n < 1 || d < 1 || d > GF_SOBOL_MAX_DIM || !u)
        return gf_fail(GF_EINVAL,
                       "Sobol design: points n = %zu must be >= 1 and dimensions d = %zu in [1, %d] (and u given)",
                       n, d, GF_SOBOL_MAX_DIM);
    gsl_qrng *q = gsl_qrng_alloc(gsl_qrng_sobol, (unsigned)d);
    if (!q)
        return gf_fail(GF_ENOMEM, "Sobol design: GSL's generator for d = %zu", d);
    for (size_t i = 0; i < skip; ++i)
        gsl_qrng_get(q, u); /* u has room for one point: overwritten below */
    for (size_t i = 0; i < n; ++i)
        gsl_qrng_get(q, u + i * d);
    gsl_qrng_free(q);
    return GF_SUCCESS;
}

double gf_morris_delta(size_t p) { return p < 2 ? NAN : (double)p / (2.0 * (double)(p - 1)); }

/* uniform integer in [0, n) (n small: the modulo bias is below 2^-50) */
static size_t below(gf_rng *r, size_t n) { return (size_t)(gf_rng_uniform(r) * (double)n) % n; }

gf_status gf_design_morris(size_t r, size_t d, size_t p, uint64_t seed, double *u)
{
    if (r < 1 || d < 1 || p < 2 || p % 2 || !u)
        return gf_fail(GF_EINVAL,
                       "Morris design: trajectories r = %zu and parameters d = %zu must be >= 1, levels p = %zu even "
                       "and >= 2 (and u given)",
                       r, d, p);
    size_t *order = malloc(d * sizeof *order), *level = malloc(d * sizeof *level);
    int *down = malloc(d * sizeof *down);
    if (!order || !level || !down) {
        free(order);
        free(level);
        free(down);
        return gf_fail(GF_ENOMEM, "Morris design: %zu parameters", d);
    }
    gf_rng g;
    gf_rng_seed(&g, seed);
    const size_t half = p / 2; /* Delta = (p/2) / (p - 1): half the levels */
    for (size_t t = 0; t < r; ++t) {
        double *x = u + t * (d + 1) * d;
        /* the base point on levels 0 .. p/2 - 1 (base + Delta stays on the grid)
         * and each parameter's direction (Morris's D*): a parameter that steps
         * down starts Delta higher, so both its values lie on the grid */
        for (size_t j = 0; j < d; ++j) {
            const size_t base = below(&g, half);
            down[j] = gf_rng_uniform(&g) < 0.5;
            level[j] = down[j] ? base + half : base;
            x[j] = (double)level[j] / (double)(p - 1);
            order[j] = j;
        }
        for (size_t k = d - 1; k > 0; --k) { /* a random order of the parameters (Morris's P*) */
            const size_t m = below(&g, k + 1), tmp = order[k];
            order[k] = order[m];
            order[m] = tmp;
        }
        for (size_t k = 0; k < d; ++k) {
            const double *prev = x + k * d;
            double *next = x + (k + 1) * d;
            memcpy(next, prev, d * sizeof *next);
            const size_t j = order[k];
            level[j] = down[j] ? level[j] - half : level[j] + half;
            next[j] = (double)level[j] / (double)(p - 1);
        }
    }
    free(order);
    free(level);
    free(down);
    return GF_SUCCESS;
}

gf_status gf_morris_effects(size_t r, size_t d, const double *u, const double *y, size_t m,
                            double *mu, double *mu_star, double *sigma)
{
    if (r < 2 || d < 1 || m < 1 || !u || !y || !mu || !mu_star || !sigma)
        return gf_fail(GF_EINVAL,
                       "Morris effects: trajectories r = %zu must be >= 2, parameters d = %zu and outputs m = %zu "
                       ">= 1 (and every array given)",
                       r, d, m);
    const size_t np = r * (d + 1);
    for (size_t i = 0; i < np * d; ++i)
        if (!isfinite(u[i]))
            return gf_fail(GF_ENONFINITE, "Morris effects: coordinate %zu of point %zu is %g", i % d, i / d, u[i]);
    for (size_t i = 0; i < np * m; ++i)
        if (!isfinite(y[i]))
            return gf_fail(GF_ENONFINITE,
                           "Morris effects: output %zu of point %zu is %g, not a finite number (rerun or drop the "
                           "trajectory of a failed member)",
                           i % m, i / m, y[i]);
    double *ee = malloc(r * d * m * sizeof *ee); /* [t][j][k] */
    unsigned char *seen = malloc(d);
    if (!ee || !seen) {
        free(ee);
        free(seen);
        return gf_fail(GF_ENOMEM, "Morris effects: %zu effects", r * d * m);
    }
    gf_status st = GF_SUCCESS;
    for (size_t t = 0; t < r && !st; ++t) {
        memset(seen, 0, d);
        for (size_t k = 0; k < d && !st; ++k) {
            const size_t a = t * (d + 1) + k, b = a + 1;
            size_t changed = d, n_changed = 0;
            for (size_t j = 0; j < d; ++j)
                if (u[b * d + j] != u[a * d + j]) {
                    changed = j;
                    ++n_changed;
                }
            if (n_changed != 1) {
                st = gf_fail(GF_EDOM, "Morris effects: step %zu of trajectory %zu changes %zu coordinates, not one", k,
                             t, n_changed);
                break;
            }
            if (seen[changed]) {
                st = gf_fail(GF_EDOM,
                             "Morris effects: trajectory %zu steps in parameter %zu twice (each parameter once per "
                             "trajectory)",
                             t, changed);
                break;
            }
            seen[changed] = 1;
            const double du = u[b * d + changed] - u[a * d + changed];
            for (size_t o = 0; o < m; ++o)
                ee[(t * d + changed) * m + o] = (y[b * m + o] - y[a * m + o]) / du;
        }
    }
    if (!st)
        for (size_t o = 0; o < m; ++o)
            for (size_t j = 0; j < d; ++j) {
                double s = 0, sa = 0;
                for (size_t t = 0; t < r; ++t) {
                    const double e = ee[(t * d + j) * m + o];
                    s += e;
                    sa += fabs(e);
                }
                const double mean = s / (double)r;
                double v = 0;
                for (size_t t = 0; t < r; ++t) {
                    const double e = ee[(t * d + j) * m + o] - mean;
                    v += e * e;
                }
                mu[o * d + j] = mean;
                mu_star[o * d + j] = sa / (double)r;
                sigma[o * d + j] = sqrt(v / (double)(r - 1));
            }
    free(ee);
    free(seen);
    return st;
}
