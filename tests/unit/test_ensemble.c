/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Ensembles (doc/theory/hazard-analysis.md, section 4): the samplers and
 * percentiles of libgranflow (granflow/ensemble.h) and the probability raster
 * and its contour lines of libgranflowTerrain (granflow/terrain.h), against
 * what they must be exactly. */
#include "../gf_test.h"

#include "granflow/ensemble.h"
#include "granflow/terrain.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "../gf_tmpdir.h"
GF_TMPDIR_FIXTURES("gf_ensemble")

/* Latin hypercube: for every input each stratum [k/n, (k+1)/n) holds exactly
 * one member; the same seed gives the same sample, another seed another */
static void latin_hypercube_fills_every_stratum_once(void **state)
{
    (void)state;
    enum { N = 40, D = 3 };
    double u[N * D], v[N * D], w[N * D];
    assert_int_equal(gf_sample_latin_hypercube(N, D, 12345, u), GF_SUCCESS);
    for (int j = 0; j < D; ++j) {
        int hits[N] = {0};
        for (int i = 0; i < N; ++i) {
            const double x = u[i * D + j];
            assert_true(x >= 0.0 && x < 1.0);
            const int k = (int)floor(x * N);
            assert_true(k >= 0 && k < N);
            ++hits[k];
        }
        for (int k = 0; k < N; ++k)
            assert_int_equal(hits[k], 1);
    }
    assert_int_equal(gf_sample_latin_hypercube(N, D, 12345, v), GF_SUCCESS);
    assert_memory_equal(u, v, sizeof u);
    assert_int_equal(gf_sample_latin_hypercube(N, D, 12346, w), GF_SUCCESS);
    int same = 0;
    for (int i = 0; i < N * D; ++i)
        same += u[i] == w[i];
    assert_true(same < N * D / 10);
    /* the inputs are not paired stratum to stratum (independent permutations) */
    int diagonal = 0;
    for (int i = 0; i < N; ++i)
        diagonal += floor(u[i * D] * N) == floor(u[i * D + 1] * N);
    assert_true(diagonal < N / 2);
    /* the generator's mean over many draws is 1/2 to its standard error */
    gf_rng r;
    gf_rng_seed(&r, 1);
    double s = 0;
    for (int i = 0; i < 100000; ++i)
        s += gf_rng_uniform(&r);
    assert_close(s / 100000, 0.5, 5 * sqrt(1.0 / 12 / 100000));
    assert_int_equal(gf_sample_latin_hypercube(0, 2, 1, u), GF_EINVAL);
    assert_int_equal(gf_sample_latin_hypercube(3, 0, 1, u), GF_EINVAL);
}

/* one at a time: input j from 0 to 1 in steps, the others at 0.5 */
static void one_at_a_time_varies_one_input_per_member(void **state)
{
    (void)state;
    double u[3 * 5 * 3];
    assert_int_equal(gf_sample_one_at_a_time(5, 3, u), GF_SUCCESS);
    for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 5; ++k)
            for (int i = 0; i < 3; ++i)
                assert_close(u[(j * 5 + k) * 3 + i], i == j ? k / 4.0 : 0.5, 0);
    assert_int_equal(gf_sample_one_at_a_time(1, 3, u), GF_EINVAL);
}

/* type-7 percentiles of 1..10 (shuffled): p50 = 5.5, p5 = 1.45, p95 = 9.55,
 * p0/p100 the extremes; one value is every percentile; NaN refused */
static void percentiles_interpolate_the_order_statistics(void **state)
{
    (void)state;
    const double x[10] = {7, 3, 10, 1, 5, 9, 2, 8, 4, 6};
    double p;
    assert_int_equal(gf_percentile(x, 10, 50, &p), GF_SUCCESS);
    assert_close(p, 5.5, 1e-15);
    assert_int_equal(gf_percentile(x, 10, 5, &p), GF_SUCCESS);
    assert_close(p, 1.45, 1e-14);
    assert_int_equal(gf_percentile(x, 10, 95, &p), GF_SUCCESS);
    assert_close(p, 9.55, 1e-14);
    assert_int_equal(gf_percentile(x, 10, 0, &p), GF_SUCCESS);
    assert_close(p, 1, 0);
    assert_int_equal(gf_percentile(x, 10, 100, &p), GF_SUCCESS);
    assert_close(p, 10, 0);
    assert_close(x[0], 7, 0); /* not sorted in place */
    const double one = 3.25;
    assert_int_equal(gf_percentile(&one, 1, 95, &p), GF_SUCCESS);
    assert_close(p, 3.25, 0);
    const double bad[3] = {1, NAN, 2};
    assert_int_equal(gf_percentile(bad, 3, 50, &p), GF_ENONFINITE);
    assert_non_null(strstr(gf_error_detail(), "value 1 of 3"));
    assert_int_equal(gf_percentile(x, 10, 101, &p), GF_EDOM);
    assert_int_equal(gf_percentile(x, 0, 50, &p), GF_EINVAL);
}

/* a 6 x 4 raster of values f(col, row), NAN where nodata(col, row) */
static const char *member(const char *name, double base, int nodata_col, gf_raster *grid)
{
    gf_raster g = {.nx = 6, .ny = 4, .gt = {1000, 10, 0, 2040, 0, -10}, .nodata = -9999, .wkt = (char *)""};
    double z[24];
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 6; ++c)
            z[r * 6 + c] = c == nodata_col ? NAN : base + c; /* column c: base + c */
    const char *p = tmp(name);
    assert_int_equal(gf_raster_write(p, strstr(name, ".tif") ? "GTiff" : "AAIGrid", &g, z), GF_SUCCESS);
    if (grid)
        *grid = g;
    return p;
}

/* four members, column c of member m holds m + c (m = 0..3); threshold
 * 3.5: member m reaches the columns c > 3.5 - m, so column c is reached by
 * min(c + 1, 4) of the 4 members; member 2 has column 5 NODATA (not reached
 * there: 3/4); a column NODATA in every member stays NODATA */
static void probability_is_the_fraction_of_members_above_the_threshold(void **state)
{
    (void)state;
    const char *paths[4] = {member("m0.asc", 0, -1, NULL), member("m1.tif", 1, -1, NULL),
                            member("m2.asc", 2, 5, NULL), member("m3.tif", 3, -1, NULL)};
    gf_raster p;
    assert_int_equal(gf_probability_map(4, paths, 3.5, &p), GF_SUCCESS);
    assert_int_equal(p.nx, 6);
    assert_int_equal(p.ny, 4);
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 6; ++c) {
            int reached = 0;
            for (int m = 0; m < 4; ++m)
                reached += !(m == 2 && c == 5) && m + c > 3.5;
            assert_close(p.z[r * 6 + c], reached / 4.0, 0);
        }
    /* the threshold is strict: at 4 member 0's column 4 (value 4) is not above */
    gf_raster q;
    assert_int_equal(gf_probability_map(4, paths, 4.0, &q), GF_SUCCESS);
    assert_close(q.z[4], 3.0 / 4, 0); /* column 4: member 0 at 4 is not above, members 1-3 at 5, 6, 7 are */
    gf_raster_free(&q);
    gf_raster_free(&p);
    /* a column NODATA in the only member */
    const char *one[1] = {member("nd.asc", 10, 2, NULL)};
    assert_int_equal(gf_probability_map(1, one, 0, &p), GF_SUCCESS);
    assert_true(isnan(p.z[2]) && isnan(p.z[8]));
    assert_close(p.z[3], 1, 0);
    gf_raster_free(&p);
}

static void probability_refuses_members_on_other_grids(void **state)
{
    (void)state;
    const char *a = member("a.asc", 0, -1, NULL);
    gf_raster g = {.nx = 6, .ny = 4, .gt = {1005, 10, 0, 2040, 0, -10}, .nodata = -9999, .wkt = (char *)""};
    double z[24];
    for (int i = 0; i < 24; ++i)
        z[i] = 1;
    const char *b = tmp("shifted.asc");
    assert_int_equal(gf_raster_write(b, "AAIGrid", &g, z), GF_SUCCESS);
    const char *paths[2] = {a, b};
    gf_raster p;
    assert_int_equal(gf_probability_map(2, paths, 0.5, &p), GF_EDOM);
    assert_non_null(strstr(gf_error_detail(), "shifted.asc"));
    assert_non_null(strstr(gf_error_detail(), "one grid"));
    assert_null(p.z);
    const char *missing[2] = {a, tmp("nothere.asc")};
    assert_int_not_equal(gf_probability_map(2, missing, 0.5, &p), GF_SUCCESS);
    assert_non_null(strstr(gf_error_detail(), "nothere.asc"));
    assert_non_null(strstr(gf_error_detail(), "member 2 of 2"));
    assert_int_equal(gf_probability_map(1, paths, NAN, &p), GF_ENONFINITE);
}

/* the contour of a cone's distance field at level L is the circle of radius
 * L: every vertex of the written line within half a pixel of it (linear
 * interpolation between pixel centres of a linear field is exact along the
 * grid lines; a vertex lies on them); GeoJSON written */
static void contours_of_a_cone_are_circles(void **state)
{
    (void)state;
    enum { N = 41 };
    gf_raster g = {.nx = N, .ny = N, .gt = {-20.5, 1, 0, 20.5, 0, -1}, .nodata = -9999, .wkt = (char *)""};
    double *z = malloc(N * N * sizeof *z);
    assert_non_null(z);
    for (int r = 0; r < N; ++r)
        for (int c = 0; c < N; ++c) {
            double x, y;
            gf_raster_centre(&g, c, r, &x, &y);
            z[r * N + c] = sqrt(x * x + y * y);
        }
    const double levels[2] = {5, 12};
    const char *xy = tmp("cone.xy"), *gj = tmp("cone.geojson");
    assert_int_equal(gf_raster_contours(gj, xy, &g, z, 2, levels), GF_SUCCESS);
    FILE *f = fopen(xy, "r");
    assert_non_null(f);
    char line[256];
    int n[2] = {0, 0};
    double worst = 0;
    while (fgets(line, sizeof line, f)) {
        double x, y, l;
        if (sscanf(line, "%lf %lf %lf", &x, &y, &l) != 3)
            continue;
        const int k = l == 5 ? 0 : l == 12 ? 1 : -1;
        assert_true(k >= 0);
        ++n[k];
        worst = fmax(worst, fabs(sqrt(x * x + y * y) - l));
    }
    fclose(f);
    assert_true(n[0] > 20 && n[1] > 50);
    assert_true(worst < 0.02); /* the interpolation error of the cone between pixel centres */
    gf_verify("exact circle", "largest |r - L| of a contour vertex [m]", worst, "<", 0.02,
              "contours of r = sqrt(x^2 + y^2) at L = 5, 12 on 1 m pixels");
    assert_int_equal(access(gj, R_OK), 0);
    free(z);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(latin_hypercube_fills_every_stratum_once),
        cmocka_unit_test(one_at_a_time_varies_one_input_per_member),
        cmocka_unit_test(percentiles_interpolate_the_order_statistics),
        cmocka_unit_test(probability_is_the_fraction_of_members_above_the_threshold),
        cmocka_unit_test(probability_refuses_members_on_other_grids),
        cmocka_unit_test(contours_of_a_cone_are_circles),
    };
    return gf_run_tests("ensemble", tests, setup, teardown);
}
