/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * granflow — ensembles of runs: the sampling of uncertain inputs and the
 * statistics of the members' results (doc/theory/hazard-analysis.md,
 * section 4 "Probability maps from an ensemble").
 *
 * An ensemble varies d uncertain inputs around a reference case.  The
 * samplers here return unit coordinates u in [0, 1) per member and input
 * (row-major, n members x d inputs); the caller maps each to its input's
 * range (for instance mu (1 + 0.3 (2u - 1)) for "mu +- 30 %").  The random
 * numbers come from granflow's own generator (xoshiro256** seeded by
 * splitmix64), so a seed gives the same members on every machine and
 * compiler.  The probability raster that counts the members above a
 * threshold is libgranflowTerrain's (granflow/terrain.h, gf_probability).
 */
#ifndef GRANFLOW_ENSEMBLE_H
#define GRANFLOW_ENSEMBLE_H

#include <stddef.h>
#include <stdint.h>

#include "granflow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The pseudo-random generator (xoshiro256**, state from splitmix64(seed)). */
typedef struct gf_rng {
    uint64_t s[4];
} gf_rng;

void gf_rng_seed(gf_rng *r, uint64_t seed);
/* Uniform in [0, 1), 53 random bits. */
double gf_rng_uniform(gf_rng *r);

/* Latin hypercube sample (AvaFrame's default,
 * "latinHypercube"): n members, d inputs; u [n d] row-major.  For every
 * input each of the n strata [k/n, (k+1)/n) holds exactly one member, at a
 * uniformly random place inside it, the strata assigned to the members by
 * a random permutation per input.  Refused (GF_EINVAL): n < 1, d < 1, u
 * NULL. */
gf_status gf_sample_latin_hypercube(size_t n, size_t d, uint64_t seed, double *u);

/* One parameter at a time (doc/theory/hazard-analysis.md's alternative): d x steps
 * members; member j steps + k varies input j to k/(steps - 1) (steps >= 2:
 * from the lower to the upper end of its range) and holds every other input
 * at 0.5 (the reference); u [d steps, d].  Refused: steps < 2, d < 1, u
 * NULL. */
gf_status gf_sample_one_at_a_time(size_t steps, size_t d, double *u);

/* Percentile p in [0, 100] of x [n] (linear interpolation between the
 * order statistics at rank p/100 (n - 1), the common "type 7" definition:
 * p = 50 is the median, p = 0 the minimum, p = 100 the maximum).  x is not
 * changed.  Refused: n < 1, p outside [0, 100], a value that is not finite
 * (a failed member is reported, not averaged in). */
gf_status gf_percentile(const double *x, size_t n, double p, double *out);

#ifdef __cplusplus
}
#endif

#endif
