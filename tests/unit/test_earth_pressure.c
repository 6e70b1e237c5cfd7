/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Earth-pressure coefficients K_act/K_pass (rkdg paper, section 2).
 * Expected values: computed independently (Python, double precision) and
 * the sum/product relations of the two roots (Vieta), a different formula. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include "../gf_test.h"

#include "granflow/earth_pressure.h"
#include "granflow/constants.h"


static void k_equals_reference_values(void **state)
{
    (void)state;
    double ka, kp;
    assert_int_equal(gf_earth_pressure_coefficients(37 * GF_DEG, 30 * GF_DEG, &ka, &kp), GF_SUCCESS);
    assert_close(ka, 0.922962196580577, 1e-13);
    assert_close(kp, 3.34841262912472, 1e-13);
    assert_int_equal(gf_earth_pressure_coefficients(30 * GF_DEG, 23 * GF_DEG, &ka, &kp), GF_SUCCESS);
    assert_close(ka, 0.76288361382812, 1e-13);
    assert_close(kp, 2.57044971950521, 1e-13);
}

static void k_roots_satisfy_vieta_relations(void **state)
{
    (void)state;
    /* K_act + K_pass = 4 sec^2 phi - 2 ; K_act K_pass = 1 - 4 sec^2 phi + 4 sec^2 phi sec^2 delta */
    for (double phi = 5; phi < 85; phi += 7)
        for (double del = 0; del <= phi; del += 3) {
            double ka, kp;
            assert_int_equal(gf_earth_pressure_coefficients(phi * GF_DEG, del * GF_DEG, &ka, &kp), GF_SUCCESS);
            const double s2p = 1 / pow(cos(phi * GF_DEG), 2), s2d = 1 / pow(cos(del * GF_DEG), 2);
            assert_close(ka + kp, 4 * s2p - 2, 1e-9 * s2p);
            assert_close(ka * kp, 1 - 4 * s2p + 4 * s2p * s2d, 1e-8 * s2p * s2p);
            assert_true(ka <= kp);
        }
}

static void k_act_equals_k_pass_when_delta_equals_phi(void **state)
{
    (void)state;
    double ka, kp;
    assert_int_equal(gf_earth_pressure_coefficients(30 * GF_DEG, 30 * GF_DEG, &ka, &kp), GF_SUCCESS);
    assert_close(ka, 5.0 / 3.0, 1e-14); /* 2 sec^2(30) - 1 */
    assert_close(kp, 5.0 / 3.0, 1e-14);
}

static void delta_above_phi_is_rejected_with_reason(void **state)
{
    (void)state;
    double ka = -7, kp = -7;
    assert_int_equal(gf_earth_pressure_coefficients(30 * GF_DEG, 35 * GF_DEG, &ka, &kp), GF_EPHYS);
    assert_non_null(strstr(gf_error_detail(), "exceeds internal friction angle"));
    assert_non_null(strstr(gf_error_detail(), "complex"));
    assert_close(ka, -7, 0); /* outputs untouched */
    gf_earth_pressure ep;
    assert_int_equal(gf_earth_pressure_init(&ep, GF_EARTH_PRESSURE_SAVAGE_HUTTER, 30 * GF_DEG, 35 * GF_DEG),
                     GF_EPHYS);
    assert_string_not_equal(gf_strerror(GF_EPHYS), "");
}

static void bad_angles_are_rejected(void **state)
{
    (void)state;
    double ka, kp;
    assert_int_equal(gf_earth_pressure_coefficients(NAN, 0.1, &ka, &kp), GF_ENONFINITE);
    assert_int_equal(gf_earth_pressure_coefficients(0.5, NAN, &ka, &kp), GF_ENONFINITE);
    assert_int_equal(gf_earth_pressure_coefficients(0.0, 0.0, &ka, &kp), GF_EDOM);
    assert_int_equal(gf_earth_pressure_coefficients(95 * GF_DEG, 0.1, &ka, &kp), GF_EDOM);
    assert_non_null(strstr(gf_error_detail(), "phi"));
    assert_int_equal(gf_earth_pressure_coefficients(0.5, -0.1, &ka, &kp), GF_EDOM);
    assert_int_equal(gf_earth_pressure_coefficients(0.5, 0.1, NULL, &kp), GF_EINVAL);
}

static void k_switches_active_passive_on_sign_of_dudx(void **state)
{
    (void)state;
    gf_earth_pressure ep;
    assert_int_equal(gf_earth_pressure_init(&ep, GF_EARTH_PRESSURE_SAVAGE_HUTTER, 37 * GF_DEG, 30 * GF_DEG),
                     GF_SUCCESS);
    assert_close(gf_earth_pressure_k(&ep, 0.3), 0.922962196580577, 1e-13);
    assert_close(gf_earth_pressure_k(&ep, 0.0), 0.922962196580577, 1e-13);
    assert_close(gf_earth_pressure_k(&ep, -1e-9), 3.34841262912472, 1e-13);
    assert_int_equal(gf_earth_pressure_init(&ep, GF_EARTH_PRESSURE_ISOTROPIC, 0, 0), GF_SUCCESS);
    assert_close(gf_earth_pressure_k(&ep, -1), 1.0, 0);
    assert_close(gf_earth_pressure_k(&ep, 1), 1.0, 0);
}

static void model_names(void **state)
{
    (void)state;
    gf_earth_pressure_model m;
    assert_int_equal(gf_earth_pressure_model_from_name("savageHutter", &m), GF_SUCCESS);
    assert_int_equal(m, GF_EARTH_PRESSURE_SAVAGE_HUTTER);
    assert_int_equal(gf_earth_pressure_model_from_name("isotropic", &m), GF_SUCCESS);
    assert_int_equal(m, GF_EARTH_PRESSURE_ISOTROPIC);
    assert_int_equal(gf_earth_pressure_model_from_name("rankine", &m), GF_ENOTFOUND);
    assert_non_null(strstr(gf_error_detail(), "isotropic, savageHutter"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(k_equals_reference_values),
        cmocka_unit_test(k_roots_satisfy_vieta_relations),
        cmocka_unit_test(k_act_equals_k_pass_when_delta_equals_phi),
        cmocka_unit_test(delta_above_phi_is_rejected_with_reason),
        cmocka_unit_test(bad_angles_are_rejected),
        cmocka_unit_test(k_switches_active_passive_on_sign_of_dudx),
        cmocka_unit_test(model_names),
    };
    return gf_run_tests("earth_pressure", tests, NULL, NULL);
}
