/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Savage–Hutter net driving acceleration (rkdg eq. 2) and the static
 * friction bound at rest (kinetic paper, Definition 1).  Reference values
 * computed independently in Python. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include "../gf_test.h"

#include "granflow/source.h"
#include "granflow/constants.h"


static void driving_matches_eq2_with_curvature(void **state)
{
    (void)state;
    const double mu = tan(30 * GF_DEG);
    /* zeta = 35 deg, chi*kappa = 0.1, |u| = 1.5 */
    assert_close(gf_sh_driving(1.0, 35 * GF_DEG, 0.1, mu, 1.5), -0.0292650274941013, 1e-14);
    assert_close(gf_sh_driving(1.0, 35 * GF_DEG, 0.1, mu, -1.5), 1.17641790019619, 1e-14);
}

static void friction_vanishes_on_lift_off(void **state)
{
    (void)state;
    /* strongly convex bed: cos(zeta) + c u^2 < 0 -> max(0, .) = 0 */
    assert_close(gf_sh_driving(1.0, 35 * GF_DEG, -10.0, 0.6, 1.0), sin(35 * GF_DEG), 1e-15);
    assert_close(gf_sh_normal_acceleration(9.81, 0.2, -10.0, 1.0), 0.0, 0);
}

static void dimensional_form_scales_with_g(void **state)
{
    (void)state;
    const double g = 9.81, z = 20 * GF_DEG, mu = 0.4, kap = 0.05, u = 3.0;
    const double expect = g * sin(z) - mu * (g * cos(z) + kap * u * u);
    assert_close(gf_sh_driving(g, z, kap, mu, u), expect, 1e-13);
}

static void static_source_clamps_to_coulomb_bound(void **state)
{
    (void)state;
    const double z = 10 * GF_DEG, mu = tan(20 * GF_DEG);
    const double R = cos(z) * mu, gs = sin(z);
    assert_close(gf_sh_static_bound(1.0, z, mu), R, 1e-15);
    /* admissible: returned unchanged */
    assert_close(gf_sh_static_source(1.0, z, mu, gs + 0.5 * R), gs + 0.5 * R, 0);
    assert_true(gf_sh_admissible(1.0, z, mu, gs - 0.99 * R));
    /* inadmissible: clamped */
    assert_close(gf_sh_static_source(1.0, z, mu, gs + 2 * R), gs + R, 1e-15);
    assert_close(gf_sh_static_source(1.0, z, mu, gs - 2 * R), gs - R, 1e-15);
    assert_false(gf_sh_admissible(1.0, z, mu, gs + 1.01 * R));
    /* flat bed, no slope: a flat pile (dh/dx = 0) is admissible */
    assert_true(gf_sh_admissible(1.0, 0.0, mu, 0.0));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(driving_matches_eq2_with_curvature),
        cmocka_unit_test(friction_vanishes_on_lift_off),
        cmocka_unit_test(dimensional_form_scales_with_g),
        cmocka_unit_test(static_source_clamps_to_coulomb_bound),
    };
    return gf_run_tests("source", tests, NULL, NULL);
}
