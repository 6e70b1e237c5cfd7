/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Ensembles: sampling of the uncertain inputs and the members' statistics
 * (granflow/ensemble.h; doc/theory/hazard-analysis.md, section 4). */
#include "granflow/ensemble.h"
#include "internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* splitmix64: the seed's expansion into the generator's state */
static uint64_t splitmix64(uint64_t *x)
{
    uint64_t z = (*x += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

static uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

void gf_rng_seed(gf_rng *r, uint64_t seed)
{
    uint64_t x = seed;
    for (int i = 0; i < 4; ++i)
        r->s[i] = splitmix64(&x);
}

/* xoshiro256** */
static uint64_t next(gf_rng *r)
{
    uint64_t *s = r->s;
    const uint64_t result = rotl(s[1] * 5, 7) * 9, t = s[1] << 17;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = rotl(s[3], 45);
    return result;
}

double gf_rng_uniform(gf_rng *r) { return (double)(next(r) >> 11) * 0x1.0p-53; }

/* uniform integer in [0, n), without modulo bias (rejection) */
static size_t below(gf_rng *r, size_t n)
{
    const uint64_t lim = UINT64_MAX - UINT64_MAX % n;
    uint64_t x;
    do
        x = next(r);
    while (x >= lim);
    return (size_t)(x % n);
}

gf_status gf_sample_latin_hypercube(size_t n, size_t d, uint64_t seed, double *u)
{
    if (n < 1 || d < 1 || !u)
        return gf_fail(GF_EINVAL, "Latin hypercube: members n = %zu and inputs d = %zu must be >= 1 (and u given)",
                       n, d);
    size_t *perm = malloc(n * sizeof *perm);
    if (!perm)
        return gf_fail(GF_ENOMEM, "Latin hypercube: %zu members", n);
    gf_rng r;
    gf_rng_seed(&r, seed);
    for (size_t j = 0; j < d; ++j) {
        /* the strata in a random order (Fisher-Yates), one member each */
        for (size_t k = 0; k < n; ++k)
            perm[k] = k;
        for (size_t k = n - 1; k > 0; --k) {
            const size_t m = below(&r, k + 1), t = perm[k];
            perm[k] = perm[m];
            perm[m] = t;
        }
        for (size_t i = 0; i < n; ++i) {
            double v = ((double)perm[i] + gf_rng_uniform(&r)) / (double)n;
            /* (k + w)/n with w < 1 can round up to (k + 1)/n: stay in the stratum */
            if (v >= (double)(perm[i] + 1) / (double)n)
                v = nextafter((double)(perm[i] + 1) / (double)n, 0.0);
            u[i * d + j] = v;
        }
    }
    free(perm);
    return GF_SUCCESS;
}

gf_status gf_sample_one_at_a_time(size_t steps, size_t d, double *u)
{
    if (steps < 2 || d < 1 || !u)
        return gf_fail(GF_EINVAL, "one at a time: steps = %zu must be >= 2 and inputs d = %zu >= 1 (and u given)",
                       steps, d);
    for (size_t j = 0; j < d; ++j)
        for (size_t k = 0; k < steps; ++k) {
            double *row = u + (j * steps + k) * d;
            for (size_t i = 0; i < d; ++i)
                row[i] = 0.5;
            row[j] = (double)k / (double)(steps - 1);
        }
    return GF_SUCCESS;
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

gf_status gf_percentile(const double *x, size_t n, double p, double *out)
{
    gf_status st;
    if (!x || !out || n < 1)
        return gf_fail(GF_EINVAL, "percentile: no values (n = %zu)", n);
    if ((st = gf_check_range("percentile p", p, 0.0, 100.0)))
        return st;
    for (size_t i = 0; i < n; ++i)
        if (!isfinite(x[i]))
            return gf_fail(GF_ENONFINITE, "percentile: value %zu of %zu is %g, not a finite number", i, n, x[i]);
    double *y = malloc(n * sizeof *y);
    if (!y)
        return gf_fail(GF_ENOMEM, "percentile: %zu values", n);
    memcpy(y, x, n * sizeof *y);
    qsort(y, n, sizeof *y, cmp_double);
    const double rank = p / 100.0 * (double)(n - 1);
    const size_t lo = (size_t)floor(rank), hi = lo + 1 < n ? lo + 1 : lo;
    const double w = rank - (double)lo;
    *out = w == 0.0 ? y[lo] : y[lo] + w * (y[hi] - y[lo]);
    free(y);
    return GF_SUCCESS;
}
