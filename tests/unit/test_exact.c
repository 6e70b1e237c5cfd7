/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Exact and approximate solutions of libgranflow (exact.h).
 * Dressler's dam break with Chezy friction (finite-area paper, section
 * 6.1.3): the first-order expansion is checked against the equations
 * themselves (its residual must fall like 1/C^4 when C grows, a wrong
 * coefficient leaves a 1/C^2 residual), against Ritter as C -> infinity,
 * for the still reservoir at xi = -1, for the velocity maximum at the tip,
 * and for the released volume. */
#include <math.h>
#include <stdio.h>

#include "../gf_test.h"
#include "granflow/exact.h"

static const double G = 9.81, HL = 0.5, X0 = 5.0;

/* max over the outer region of |residual| of mass and momentum at time t */
static void outer_residual(const gf_dressler *d, double t, double *rm, double *rq)
{
    const double c0 = sqrt(G * HL), e = 1e-5;
    /* xi in [-0.95, 1]: inside the outer region for C >= 40 at t = 1 (tip at
     * xi = 1.07 for C = 40, nearer 2 for larger C) */
    const double xa = X0 - 0.95 * c0 * t, xb = X0 + c0 * t;
    *rm = *rq = 0.0;
    for (int i = 0; i <= 60; ++i) {
        const double x = xa + (xb - xa) * i / 60.0;
        double h, u, hxp, uxp, hxm, uxm, htp, utp, htm, utm;
        gf_dressler_outer(d, x, t, &h, &u);
        gf_dressler_outer(d, x + e, t, &hxp, &uxp);
        gf_dressler_outer(d, x - e, t, &hxm, &uxm);
        gf_dressler_outer(d, x, t + e, &htp, &utp);
        gf_dressler_outer(d, x, t - e, &htm, &utm);
        const double hx = (hxp - hxm) / (2 * e), ux = (uxp - uxm) / (2 * e);
        const double ht = (htp - htm) / (2 * e), ut = (utp - utm) / (2 * e);
        const double C = d->chezy;
        *rm = fmax(*rm, fabs(ht + u * hx + h * ux));
        *rq = fmax(*rq, fabs(ut + u * ux + G * hx + G * u * fabs(u) / (C * C * h)));
    }
}

static void dressler_expansion_is_second_order_in_the_resistance(void **state)
{
    (void)state;
    double rm[3], rq[3];
    const double C[3] = {40, 80, 160};
    for (int k = 0; k < 3; ++k) {
        gf_dressler d;
        assert_int_equal(gf_dressler_init(&d, G, HL, C[k], X0), GF_SUCCESS);
        outer_residual(&d, 1.0, &rm[k], &rq[k]);
        printf("  Dressler outer residual, C = %3.0f: mass %.3e, momentum %.3e\n", C[k], rm[k],
               rq[k]);
    }
    /* first-order consistency: doubling C divides the residual by ~16
     * (measured 16.6 / 16.2 for mass, 12.3 / 15.1 for momentum); a first-order error would give 4 */
    for (int k = 0; k < 2; ++k) {
        assert_true(rm[k] / rm[k + 1] > 10.0);
        assert_true(rq[k] / rq[k + 1] > 10.0);
    }
    /* the frictionless parts cancel: C = 40 leaves a small residual */
    assert_true(rm[0] < 5e-3 && rq[0] < 0.15);
}

static void dressler_tends_to_ritter_without_friction(void **state)
{
    (void)state;
    gf_dressler d;
    gf_riemann r;
    assert_int_equal(gf_dressler_init(&d, G, HL, 1e7, X0), GF_SUCCESS);
    assert_int_equal(gf_riemann_solve(&r, G, HL, 0, 0, 0, X0), GF_SUCCESS);
    for (double x = 2.0; x < 8.0; x += 0.37) {
        double h, u, hr, ur;
        gf_dressler_outer(&d, x, 1.0, &h, &u);
        gf_riemann_sample(&r, x, 1.0, &hr, &ur);
        if (x - X0 < 1.9 * sqrt(G * HL)) { /* a1, a2 grow like (2-xi)^-2 at the front */
            assert_close(h, hr, 1e-9);
            assert_close(u, ur, 1e-9);
        }
    }
}

static void dressler_reservoir_still_and_tip_at_the_velocity_maximum(void **state)
{
    (void)state;
    gf_dressler d;
    assert_int_equal(gf_dressler_init(&d, G, HL, 40, X0), GF_SUCCESS);
    assert_int_equal(gf_dressler_at(&d, 1.0), GF_SUCCESS);
    const double c0 = sqrt(G * HL);
    double h, u;
    /* both corrections vanish at xi = -1: continuous with the still reservoir */
    assert_int_equal(gf_dressler_sample(&d, X0 - c0 * (1 - 1e-9), 1.0, &h, &u), GF_SUCCESS);
    assert_close(h, HL, 1e-8);
    assert_close(u, 0.0, 1e-8);
    assert_int_equal(gf_dressler_sample(&d, X0 - c0 - 0.1, 1.0, &h, &u), GF_SUCCESS);
    assert_close(h, HL, 0);
    assert_close(u, 0.0, 0);
    gf_dressler_outer(&d, X0 + 2 * c0 + 0.1, 1.0, &h, &u); /* beyond Ritter's front */
    assert_close(h, 0.0, 0);
    assert_close(u, 0.0, 0);
    /* u of the outer region is largest at the tip */
    for (double dx = 1e-3; dx < 0.3; dx *= 2) {
        double hl, ul, hr, ur;
        gf_dressler_outer(&d, d.x_tip - dx, 1.0, &hl, &ul);
        gf_dressler_outer(&d, d.x_tip + dx, 1.0, &hr, &ur);
        assert_true(ul < d.u_tip && ur < d.u_tip);
    }
    /* the tip moves at u_tip behind Ritter's front, ahead of the tip start */
    printf("  Dressler C = 40, t = 1: tip x = %.4f (u %.4f, h %.4f), front x = %.4f "
           "(Ritter %.4f)\n", d.x_tip, d.u_tip, d.h_tip, d.x_front, X0 + 2 * c0);
    assert_true(d.x_tip < d.x_front && d.x_front < X0 + 2 * c0);
    assert_int_equal(gf_dressler_sample(&d, d.x_front + 1e-12, 1.0, &h, &u), GF_SUCCESS);
    assert_close(h, 0.0, 0);
    /* the tip profile solves its friction-dominated momentum balance
     * g h_x = -g u_tip^2/(C^2 h), i.e. (h^2)_x = -2 u_tip^2/C^2 (finite
     * differences), and its velocity is uniform and below Ritter's front speed */
    for (int k = 1; k < 10; ++k) {
        const double x = d.x_tip + (d.x_front - d.x_tip) * k / 10.0, e = 1e-7;
        double hp, up, hm, um;
        assert_int_equal(gf_dressler_sample(&d, x + e, 1.0, &hp, &up), GF_SUCCESS);
        assert_int_equal(gf_dressler_sample(&d, x - e, 1.0, &hm, &um), GF_SUCCESS);
        const double dh2 = (hp * hp - hm * hm) / (2 * e);
        assert_close(dh2, -2.0 * d.u_tip * d.u_tip / (40.0 * 40.0), 1e-6);
        assert_true(fabs(up - um) < 1e-12 && up > 0.0 && up < 2 * c0);
    }
}

static void dressler_conserves_the_released_volume(void **state)
{
    (void)state;
    const double c0 = sqrt(G * HL);
    for (double t = 0.25; t <= 2.0; t *= 2) {
        gf_dressler d;
        assert_int_equal(gf_dressler_init(&d, G, HL, 40, X0), GF_SUCCESS);
        assert_int_equal(gf_dressler_at(&d, t), GF_SUCCESS);
        /* midpoint rule on 2e5 cells, exact sqrt integral near the front
         * makes ~1e-8; the tip region is integrated in closed form */
        const double a = X0 - c0 * t, b = d.x_tip;
        const int n = 200000;
        double v = 0.0;
        for (int i = 0; i < n; ++i) {
            double h, u;
            assert_int_equal(gf_dressler_sample(&d, a + (b - a) * (i + 0.5) / n, t, &h, &u), GF_SUCCESS);
            v += h * (b - a) / n;
        }
        const double L = d.x_front - d.x_tip;
        v += 2.0 * sqrt(2.0) / 3.0 * d.u_tip / d.chezy * L * sqrt(L);
        assert_close(v, HL * (X0 - a), 1e-9);
    }
}

static void dressler_rejects_bad_input(void **state)
{
    (void)state;
    gf_dressler d;
    assert_int_equal(gf_dressler_init(&d, G, HL, 0.0, X0), GF_EDOM);
    assert_int_equal(gf_dressler_init(&d, G, -1.0, 40.0, X0), GF_EDOM);
    assert_int_equal(gf_dressler_init(&d, G, HL, NAN, X0), GF_ENONFINITE);
    assert_int_equal(gf_dressler_init(&d, G, HL, 40.0, X0), GF_SUCCESS);
    assert_int_equal(gf_dressler_at(&d, 0.0), GF_EDOM);
    /* nearly frictionless: the tip approaches Ritter's front or is refused */
    assert_int_equal(gf_dressler_init(&d, G, HL, 1e4, X0), GF_SUCCESS);
    assert_int_equal(gf_dressler_at(&d, 1.0), GF_SUCCESS);
    assert_true(d.x_front < X0 + 2 * sqrt(G * HL) && d.x_tip > X0 + 1.9 * sqrt(G * HL));
    assert_int_equal(gf_dressler_init(&d, G, HL, 1e9, X0), GF_SUCCESS);
    assert_int_equal(gf_dressler_at(&d, 1.0), GF_SUCCESS);
    assert_close(d.x_front, X0 + 2 * sqrt(G * HL), 1e-3);
    assert_int_equal(gf_dressler_init(&d, G, HL, 1e20, X0), GF_SUCCESS);
    assert_int_equal(gf_dressler_at(&d, 1.0), GF_EDOM);
    printf("  expected message: %s\n", gf_error_detail());
    /* strong friction for a long time leaves the first-order expansion */
    assert_int_equal(gf_dressler_init(&d, G, HL, 3.0, X0), GF_SUCCESS);
    assert_int_equal(gf_dressler_at(&d, 8.0), GF_EDOM);
    printf("  expected message: %s\n", gf_error_detail());
}

/* Spreading parabolic cap: the sampled solution satisfies the source-free
 * equations (finite-difference residual at interior points, small against
 * the terms), keeps its volume 4/3 h0 l0, starts at rest from the cap, and
 * its fronts tend to Ritter's speed 2 sqrt(beta h0). */
static void spreading_cap_solves_the_equations(void **state)
{
    (void)state;
    gf_spreading_cap c;
    const double beta = 0.8, h0 = 1.0, l0 = 2.0, x0 = 1.0;
    assert_int_equal(gf_spreading_cap_init(&c, beta, h0, l0, x0), GF_SUCCESS);
    double rm = 0.0, rq = 0.0, scale = 0.0;
    const double e = 1e-5;
    for (double t = 0.5; t <= 5.0; t += 1.5) {
        double lam, dlam;
        assert_int_equal(gf_spreading_cap_stretch(&c, t, &lam, &dlam), GF_SUCCESS);
        for (int i = -9; i <= 9; ++i) {
            const double x = x0 + 0.1 * i * lam * l0;
            double h, u, hxp, uxp, hxm, uxm, htp, utp, htm, utm;
            gf_spreading_cap_sample(&c, x, t, &h, &u);
            gf_spreading_cap_sample(&c, x + e, t, &hxp, &uxp);
            gf_spreading_cap_sample(&c, x - e, t, &hxm, &uxm);
            gf_spreading_cap_sample(&c, x, t + e, &htp, &utp);
            gf_spreading_cap_sample(&c, x, t - e, &htm, &utm);
            const double hx = (hxp - hxm) / (2 * e), ux = (uxp - uxm) / (2 * e);
            const double ht = (htp - htm) / (2 * e), ut = (utp - utm) / (2 * e);
            rm = fmax(rm, fabs(ht + u * hx + h * ux));
            rq = fmax(rq, fabs(ut + u * ux + beta * hx));
            scale = fmax(scale, fabs(beta * hx));
        }
        /* volume by the trapezoidal rule on 20,000 intervals */
        double vol = 0.0;
        const int n = 20000;
        for (int i = 0; i <= n; ++i) {
            double h, u;
            gf_spreading_cap_sample(&c, x0 - lam * l0 + 2.0 * lam * l0 * i / n, t, &h, &u);
            vol += (i == 0 || i == n ? 0.5 : 1.0) * h * 2.0 * lam * l0 / n;
        }
        assert_close(vol, 4.0 / 3.0 * h0 * l0, 1e-6);
    }
    printf("  spreading cap: residual mass %.1e, momentum %.1e (terms up to %.2f)\n", rm, rq, scale);
    assert_true(rm < 1e-8 && rq < 1e-8);
    double h, u, lam, dlam;
    assert_int_equal(gf_spreading_cap_sample(&c, x0 + 0.5, 0.0, &h, &u), GF_SUCCESS);
    assert_close(h, h0 * (1.0 - 0.0625), 1e-15);
    assert_close(u, 0.0, 1e-15);
    assert_int_equal(gf_spreading_cap_sample(&c, x0 + 2.01, 0.0, &h, &u), GF_SUCCESS);
    assert_true(h == 0.0 && u == 0.0);
    assert_int_equal(gf_spreading_cap_stretch(&c, 1e6, &lam, &dlam), GF_SUCCESS);
    assert_close(l0 * dlam, 2.0 * sqrt(beta * h0), 1e-3);
    assert_int_equal(gf_spreading_cap_stretch(&c, -1.0, &lam, &dlam), GF_EDOM);
    assert_int_equal(gf_spreading_cap_init(&c, beta, -1.0, l0, x0), GF_EDOM);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(dressler_expansion_is_second_order_in_the_resistance),
        cmocka_unit_test(dressler_tends_to_ritter_without_friction),
        cmocka_unit_test(dressler_reservoir_still_and_tip_at_the_velocity_maximum),
        cmocka_unit_test(dressler_conserves_the_released_volume),
        cmocka_unit_test(dressler_rejects_bad_input),
        cmocka_unit_test(spreading_cap_solves_the_equations),
    };
    return gf_run_tests("tests", tests, NULL, NULL);
}
