/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Chute topography: rkdg eq. 3 / finite-area eq. 74, the rkdg appendix
 * mapping (re-implemented here from the appendix text), and the tabulated
 * GSL-spline profile against the closed-form arc of a linear zeta(x). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include "../gf_test.h"

#include "granflow/topography.h"
#include "granflow/constants.h"


/* rkdg paper, appendix */
static void appendix_mapping(double zeta0, double x, double *xb, double *yb)
{
    const double r = 4.0 / zeta0;
    const double x1 = 17.5 * cos(zeta0), y1 = r * (1 - cos(zeta0));
    const double x2 = x1 + r * sin(zeta0);
    if (x >= 21.5) {
        *xb = x2 + (x - 21.5);
        *yb = 0;
    } else if (x >= 17.5) {
        const double z = (21.5 - x) / r;
        *xb = x2 - r * sin(z);
        *yb = r * (1 - cos(z));
    } else {
        *xb = x * cos(zeta0);
        *yb = y1 + (17.5 - x) * sin(zeta0);
    }
}

static void chute_inclination_and_curvature(void **state)
{
    (void)state;
    gf_topography *t;
    double z, k;
    assert_int_equal(gf_topography_chute_alloc(35 * GF_DEG, 10 * GF_DEG, 17.5, 21.5, &t), GF_SUCCESS);
    gf_topography_eval(t, 3.0, &z, &k);
    assert_close(z, 35 * GF_DEG, 1e-15);
    assert_close(k, 0.0, 0);
    gf_topography_eval(t, 19.5, &z, &k); /* eq. 74: 35 - 6.25 (x - 17.5) deg */
    assert_close(z, (35 - 6.25 * 2.0) * GF_DEG, 1e-14);
    assert_close(k, 6.25 * GF_DEG, 1e-14);
    gf_topography_eval(t, 25.0, &z, &k);
    assert_close(z, 10 * GF_DEG, 1e-15);
    assert_close(k, 0.0, 0);
    gf_topography_free(t);
}

static void chute_position_equals_rkdg_appendix(void **state)
{
    (void)state;
    for (double z0d = 35; z0d <= 40; z0d += 5) {
        gf_topography *t;
        assert_int_equal(gf_topography_chute_alloc(z0d * GF_DEG, 0.0, 17.5, 21.5, &t), GF_SUCCESS);
        double z, k;
        gf_topography_eval(t, 18.0, &z, &k);
        assert_close(k, z0d * GF_DEG / 4.0, 1e-14); /* kappa = zeta0/4 (rkdg section 4) */
        for (double x = 0; x <= 30; x += 0.37) {
            double X, Z, xb, yb;
            assert_int_equal(gf_topography_position(t, x, &X, &Z), GF_SUCCESS);
            appendix_mapping(z0d * GF_DEG, x, &xb, &yb);
            assert_close(X, xb, 1e-12);
            assert_close(Z, yb, 1e-12);
        }
        gf_topography_free(t);
    }
}

static void tabulated_linear_profile_is_exact(void **state)
{
    (void)state;
    /* zeta = a - b x, sampled; natural cubic spline reproduces it; the bed is
     * a circular arc: X = (sin a - sin zeta)/b, Z = (cos a - cos zeta)/b. */
    const double a = 40 * GF_DEG, b = 0.03;
    double x[31], zeta[31];
    for (int i = 0; i < 31; ++i) {
        x[i] = i;
        zeta[i] = a - b * i;
    }
    gf_topography *t;
    assert_int_equal(gf_topography_tabulated_alloc(x, zeta, 31, &t), GF_SUCCESS);
    for (double s = 0; s <= 30; s += 0.71) {
        double z, k, X, Z;
        assert_int_equal(gf_topography_eval(t, s, &z, &k), GF_SUCCESS);
        assert_close(z, a - b * s, 1e-12);
        assert_close(k, b, 1e-10);
        assert_int_equal(gf_topography_position(t, s, &X, &Z), GF_SUCCESS);
        assert_close(X, (sin(a) - sin(z)) / b, 1e-10);
        assert_close(Z, (cos(a) - cos(z)) / b, 1e-10);
    }
    double lo, hi;
    gf_topography_range(t, &lo, &hi);
    assert_close(lo, 0, 0);
    assert_close(hi, 30, 0);
    double z, k;
    assert_int_equal(gf_topography_eval(t, 30.5, &z, &k), GF_EDOM);
    assert_non_null(strstr(gf_error_detail(), "outside the table"));
    gf_topography_free(t);
}

static void bad_topography_input(void **state)
{
    (void)state;
    gf_topography *t = (gf_topography *)1;
    double x[3] = {0, 1, 1}, z[3] = {0.1, 0.1, 0.1};
    assert_int_equal(gf_topography_tabulated_alloc(x, z, 3, &t), GF_EDOM);
    assert_null(t);
    assert_non_null(strstr(gf_error_detail(), "increase strictly"));
    assert_int_equal(gf_topography_tabulated_alloc(x, z, 2, &t), GF_EINVAL);
    double x2[3] = {0, 1, 2}, z2[3] = {0.1, NAN, 0.1};
    assert_int_equal(gf_topography_tabulated_alloc(x2, z2, 3, &t), GF_ENONFINITE);
    double z3[3] = {0.1, 1.6, 0.1};
    assert_int_equal(gf_topography_tabulated_alloc(x2, z3, 3, &t), GF_EDOM);
    assert_int_equal(gf_topography_chute_alloc(0.6, 0.0, 21.5, 17.5, &t), GF_EDOM);
    assert_int_equal(gf_topography_chute_alloc(2.0, 0.0, 17.5, 21.5, &t), GF_EDOM);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(chute_inclination_and_curvature),
        cmocka_unit_test(chute_position_equals_rkdg_appendix),
        cmocka_unit_test(tabulated_linear_profile_is_exact),
        cmocka_unit_test(bad_topography_input),
    };
    return gf_run_tests("topography", tests, NULL, NULL);
}
