/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The field's standard analytic tests (granflow/standard_tests.h;
 * doc/theory/standard-tests.md): the similarity solution of Hutter et al.
 * (1993) against its check values at t = 5 s, its volume, its centre of
 * mass and the balances it solves; the inclined dam break of Faccanoni &
 * Mangeney (2013) against its check values, the volume of its fan and its
 * equations; the flat-plane pile at its marginal slope; the error norms on
 * hand-made fields; the energy line analysis on synthetic paths; bad input
 * refused by every function that can fail. */
#include "../gf_test.h"

#include <stdio.h>

#include "granflow/constants.h"
#include "granflow/earth_pressure.h"
#include "granflow/standard_tests.h"

static const double G = 9.81;

/* |a - b| <= half a unit of the last printed digit of b */
#define assert_digits(a, b, half_unit) assert_close((a), (b), (half_unit))

/* ---- 1. similarity solution ---------------------------------------------- */

static gf_simisol *simisol_standard(double t_end)
{
    const gf_simisol_params p = gf_simisol_default();
    gf_simisol *s = NULL;
    assert_int_equal(gf_simisol_alloc(&s, &p, t_end, 1e-10), GF_SUCCESS);
    assert_non_null(s);
    return s;
}

static void similarity_coefficients_of_the_standard_test(void **state)
{
    (void)state;
    gf_simisol *s = simisol_standard(6.0);
    gf_simisol_coeffs c;
    gf_simisol_coefficients(s, &c);
    printf("  T %.7f s, A - C %.8f, B %.8f, D %.8f, E %.8f\n", c.T, c.A - c.C, c.B, c.D, c.E);
    assert_digits(c.T, 2.855686, 0.5e-6);
    assert_digits(c.A - c.C, 0.1915996, 0.5e-7);
    assert_digits(c.B, 0.0409576, 0.5e-7);
    assert_digits(c.D, 0.0409576, 0.5e-7);
    assert_digits(c.E, 0.3340436, 0.5e-7);
    assert_close(c.U, sqrt(G * 80.0), 1e-14);
    assert_close(c.V, sqrt(G * 80.0), 1e-14);
    gf_simisol_free(s);
}

static void similarity_stretching_at_5s_matches_the_reference_integration(void **state)
{
    (void)state;
    gf_simisol *s = simisol_standard(6.0);
    const gf_simisol_params p = gf_simisol_default();
    double g, dg, f, df;
    assert_int_equal(gf_simisol_stretch(s, 5.0, &g, &dg, &f, &df), GF_SUCCESS);
    const double peak = p.H / (f * g), xc = gf_simisol_xc(&p, 5.0);
    printf("  t = 5 s: g %.8f, g' %.8f, f %.8f, f' %.9f, H/(fg) %.6f m, xc %.5f m\n", g, dg, f,
           df, peak, xc);
    assert_digits(g, 1.11999, 0.5e-5);
    assert_digits(dg, 0.131241, 0.5e-6);
    assert_digits(f, 1.03954, 0.5e-5);
    assert_digits(df, 0.0426557, 0.5e-7);
    assert_digits(peak, 3.4356, 0.5e-4);
    assert_digits(xc, 19.246, 0.5e-3);
    /* the peak thickness the field samples is H/(fg): at the centre of mass */
    double h, vel[3];
    assert_int_equal(gf_simisol_sample(s, xc, 0.0, 5.0, &h, vel), GF_SUCCESS);
    assert_close(h, peak, 1e-12);
    gf_verify("Hutter et al. 1993", "difference of g(5 s) from 1.11999", fabs(g - 1.11999), "<=",
              0.5e-5, "similarity solution, standard test");
    gf_verify("Hutter et al. 1993", "difference of H/(fg) at 5 s from 3.4356 m [m]",
              fabs(peak - 3.4356), "<=", 0.5e-4, "similarity solution, standard test");
    gf_simisol_free(s);
}

/* the Taylor start joins the integration continuously, and the dense output
 * between stored nodes equals an integration that ends at that time */
static void similarity_dense_output_equals_integration_to_that_time(void **state)
{
    (void)state;
    gf_simisol *s = simisol_standard(6.0);
    double worst = 0.0;
    const double times[] = {0.2855686 * 1.0001, 1.234567, 3.3333, 5.0, 5.987};
    for (size_t i = 0; i < sizeof times / sizeof times[0]; ++i) {
        gf_simisol *e = simisol_standard(times[i]);
        double a[4], b[4];
        assert_int_equal(gf_simisol_stretch(s, times[i], &a[0], &a[1], &a[2], &a[3]), GF_SUCCESS);
        assert_int_equal(gf_simisol_stretch(e, times[i], &b[0], &b[1], &b[2], &b[3]), GF_SUCCESS);
        for (int k = 0; k < 4; ++k)
            worst = fmax(worst, fabs(a[k] - b[k]));
        gf_simisol_free(e);
    }
    printf("  dense output against integration to the time: max difference %.2e\n", worst);
    assert_true(worst < 1e-10);
    /* continuity at the end of the Taylor start tau1 = 0.1 */
    gf_simisol_coeffs c;
    gf_simisol_coefficients(s, &c);
    double lo[4], hi[4];
    const double t1 = 0.1 * c.T;
    assert_int_equal(gf_simisol_stretch(s, t1 * (1.0 - 1e-12), &lo[0], &lo[1], &lo[2], &lo[3]),
                     GF_SUCCESS);
    assert_int_equal(gf_simisol_stretch(s, t1 * (1.0 + 1e-12), &hi[0], &hi[1], &hi[2], &hi[3]),
                     GF_SUCCESS);
    for (int k = 0; k < 4; ++k)
        assert_close(lo[k], hi[k], 1e-11);
    assert_close(lo[0], 1.0 + c.B * 0.01, 1e-11);
    assert_close(lo[3], 2.0 * c.D * c.E * 0.1, 1e-11);
    gf_simisol_free(s);
}

/* volume V = sum h dx dy / cos(zeta) (h normal to the bed, the sloping cell
 * area) and the horizontal centre of mass on a 0.25 m grid */
static void similarity_conserves_volume_and_its_centre_slides_with_the_frame(void **state)
{
    (void)state;
    const gf_simisol_params p = gf_simisol_default();
    gf_simisol *s = simisol_standard(5.0);
    const double v_exact = GF_PI * p.H * p.Lx * p.Ly / 2.0, dx = 0.25, cz = cos(p.zeta);
    const double times[] = {0.0, 2.5, 5.0};
    for (int it = 0; it < 3; ++it) {
        const double t = times[it], xc = gf_simisol_xc(&p, t);
        double g, dg, f, df;
        assert_int_equal(gf_simisol_stretch(s, t, &g, &dg, &f, &df), GF_SUCCESS);
        /* cell centres symmetric about the centre of mass (x_c, 0) */
        const int nx = (int)(1.05 * g * p.Lx * cz / dx) + 1, ny = (int)(1.05 * f * p.Ly / dx) + 1;
        double vol = 0.0, mx = 0.0, my = 0.0;
        for (int i = -nx; i < nx; ++i)
            for (int j = -ny; j < ny; ++j) {
                const double x = xc + (i + 0.5) * dx, y = (j + 0.5) * dx;
                double h, vel[3];
                assert_int_equal(gf_simisol_sample(s, x, y, t, &h, vel), GF_SUCCESS);
                vol += h * dx * dx / cz;
                mx += x * h * dx * dx / cz;
                my += y * h * dx * dx / cz;
                if (t == 0.0) {
                    assert_close(h, gf_simisol_h0(&p, x, y), 1e-14);
                    assert_true(vel[0] == 0.0 && vel[1] == 0.0 && vel[2] == 0.0);
                }
            }
        const double tau = t / sqrt(p.Lx / G), amc = sin(p.zeta) - cos(p.zeta) * tan(p.delta);
        printf("  t = %.1f s: volume %.3f m3 (pi H Lx Ly / 2 = %.3f, rel. %.1e), centre (%.6f, "
               "%.1e) m against %.6f m\n",
               t, vol, v_exact, vol / v_exact - 1.0, mx / vol, my / vol, xc);
        assert_true(fabs(vol / v_exact - 1.0) < 1e-6);
        assert_close(xc, p.Lx * amc * tau * tau / 2.0 * cz, 1e-12);
        assert_close(mx / vol, xc, 1e-6);
        assert_close(my / vol, 0.0, 1e-9);
    }
    /* the cap's outline: h > 0 just inside the front, 0 just outside */
    double g, dg, f, df, h, vel[3];
    assert_int_equal(gf_simisol_stretch(s, 5.0, &g, &dg, &f, &df), GF_SUCCESS);
    const double xf = gf_simisol_xc(&p, 5.0) + g * p.Lx * cz;
    assert_int_equal(gf_simisol_sample(s, xf - 0.01, 0.0, 5.0, &h, vel), GF_SUCCESS);
    assert_true(h > 0.0 && vel[0] > 0.0 && vel[2] < 0.0);
    assert_int_equal(gf_simisol_sample(s, xf + 0.01, 0.0, 5.0, &h, vel), GF_SUCCESS);
    assert_true(h == 0.0 && vel[0] == 0.0 && vel[1] == 0.0 && vel[2] == 0.0);
    gf_simisol_free(s);
}

/* along-slope xi, cross-slope y: h, u (downslope) and v at (xi, y, t) */
static void simi_at(const gf_simisol *s, double xi, double y, double t, double *h, double *u,
                    double *v)
{
    const double cz = cos(gf_simisol_default().zeta);
    double vel[3];
    assert_int_equal(gf_simisol_sample(s, xi * cz, y, t, h, vel), GF_SUCCESS);
    assert_close(vel[2], -vel[0] * tan(gf_simisol_default().zeta), 1e-12); /* tangent to the bed */
    *u = vel[0] / cz;
    *v = vel[1];
}

/* The fields solve, by central differences inside the cap, the mass balance
 * h_t + (hu)_xi + (hv)_y = 0 and the momentum balances of the similarity
 * approximation (Hutter et al. 1993; K = 1, friction along the centre's
 * velocity U (A - C) tau):
 *   u_t + u u_xi + v u_y = g (sin zeta - cos zeta tan delta) - g cos zeta h_xi
 *   v_t + u v_xi + v v_y = -g cos zeta h_y - g cos zeta tan delta v / (U (A - C) tau) */
static void similarity_fields_solve_the_mass_and_momentum_balances(void **state)
{
    (void)state;
    gf_simisol *s = simisol_standard(6.0);
    const gf_simisol_params p = gf_simisol_default();
    gf_simisol_coeffs c;
    gf_simisol_coefficients(s, &c);
    const double cz = cos(p.zeta), tz = tan(p.zeta), td = tan(p.delta);
    const double ex = 1e-3, et = 1e-4;
    double rm = 0.0, rx = 0.0, ry = 0.0;
    const double times[] = {1.0, 3.0, 5.0}, as[] = {-0.6, 0.0, 0.5}, bs[] = {-0.5, 0.0, 0.3};
    for (int it = 0; it < 3; ++it)
        for (int ia = 0; ia < 3; ++ia)
            for (int ib = 0; ib < 3; ++ib) {
                const double t = times[it], tau = t / c.T;
                double g, dg, f, df;
                assert_int_equal(gf_simisol_stretch(s, t, &g, &dg, &f, &df), GF_SUCCESS);
                const double xi = p.Lx * (as[ia] * g + (c.A - c.C) * tau * tau / 2.0);
                const double y = p.Ly * bs[ib] * f;
                double h, u, v, hxp, uxp, vxp, hxm, uxm, vxm, hyp, uyp, vyp, hym, uym, vym;
                double htp, utp, vtp, htm, utm, vtm;
                simi_at(s, xi, y, t, &h, &u, &v);
                simi_at(s, xi + ex, y, t, &hxp, &uxp, &vxp);
                simi_at(s, xi - ex, y, t, &hxm, &uxm, &vxm);
                simi_at(s, xi, y + ex, t, &hyp, &uyp, &vyp);
                simi_at(s, xi, y - ex, t, &hym, &uym, &vym);
                simi_at(s, xi, y, t + et, &htp, &utp, &vtp);
                simi_at(s, xi, y, t - et, &htm, &utm, &vtm);
                const double hx = (hxp - hxm) / (2 * ex), hy = (hyp - hym) / (2 * ex);
                const double ux = (uxp - uxm) / (2 * ex), uy = (uyp - uym) / (2 * ex);
                const double vx = (vxp - vxm) / (2 * ex), vy = (vyp - vym) / (2 * ex);
                const double mass = (htp - htm) / (2 * et) + (hxp * uxp - hxm * uxm) / (2 * ex) +
                                    (hyp * vyp - hym * vym) / (2 * ex);
                const double momx = (utp - utm) / (2 * et) + u * ux + v * uy -
                                    (G * cz * (tz - td) - G * cz * hx);
                const double momy = (vtp - vtm) / (2 * et) + u * vx + v * vy -
                                    (-G * cz * hy - G * cz * td * v / (c.U * (c.A - c.C) * tau));
                rm = fmax(rm, fabs(mass));
                rx = fmax(rx, fabs(momx));
                ry = fmax(ry, fabs(momy));
            }
    printf("  similarity residuals: mass %.1e m/s, momentum %.1e / %.1e m/s2 (driving %.2f m/s2)\n",
           rm, rx, ry, G * cz * (tz - td));
    assert_true(rm < 1e-7 && rx < 1e-6 && ry < 1e-6);
    gf_simisol_free(s);
}

/* flag_earth: from rest g'' > 0 and f'' > 0 where g' = f' = 0, so both
 * stay active; the switch gives the run with Kx = K_act(phi, delta) and
 * Ky = Ky_act(K_act), a cap that spreads less than with K = 1 */
static void similarity_earth_pressure_switch_stays_active_while_spreading(void **state)
{
    (void)state;
    gf_simisol_params pe = gf_simisol_default();
    pe.flag_earth = 1;
    pe.phi = 30.0 * GF_DEG;
    double ka, kp;
    assert_int_equal(gf_earth_pressure_coefficients(pe.phi, pe.delta, &ka, &kp), GF_SUCCESS);
    const double td = tan(pe.delta);
    gf_simisol_params pk = gf_simisol_default();
    pk.Kx = ka;
    pk.Ky = 0.5 * (ka + 1.0 - sqrt((1.0 - ka) * (1.0 - ka) + 4.0 * td * td));
    gf_simisol *se, *sk, *s1;
    assert_int_equal(gf_simisol_alloc(&se, &pe, 5.0, 1e-10), GF_SUCCESS);
    assert_int_equal(gf_simisol_alloc(&sk, &pk, 5.0, 1e-10), GF_SUCCESS);
    s1 = simisol_standard(5.0);
    gf_simisol_coeffs ce, ck;
    gf_simisol_coefficients(se, &ce);
    gf_simisol_coefficients(sk, &ck);
    assert_close(ce.B, ck.B, 1e-15);
    assert_close(ce.D, ck.D, 1e-15);
    double a[4], b[4], one[4];
    assert_int_equal(gf_simisol_stretch(se, 5.0, &a[0], &a[1], &a[2], &a[3]), GF_SUCCESS);
    assert_int_equal(gf_simisol_stretch(sk, 5.0, &b[0], &b[1], &b[2], &b[3]), GF_SUCCESS);
    assert_int_equal(gf_simisol_stretch(s1, 5.0, &one[0], &one[1], &one[2], &one[3]), GF_SUCCESS);
    printf("  phi 30 deg: K_act %.4f, Ky_act %.4f; g(5 s) %.6f (K = 1: %.6f), f(5 s) %.6f (%.6f)\n",
           ka, pk.Ky, a[0], one[0], a[2], one[2]);
    for (int k = 0; k < 4; ++k)
        assert_close(a[k], b[k], 1e-13);
    assert_true(a[1] > 0.0 && a[3] > 0.0);
    assert_true(ka < 1.0 && a[0] < one[0]);
    gf_simisol_free(se);
    gf_simisol_free(sk);
    gf_simisol_free(s1);
}

static void expect_simisol_refused(const gf_simisol_params *p, double t_end, double rtol,
                                   gf_status want, const char *word)
{
    gf_simisol *s = (gf_simisol *)(void *)&s; /* not NULL: alloc must clear it on failure */
    assert_int_equal(gf_simisol_alloc(&s, p, t_end, rtol), want);
    assert_null(s);
    if (!strstr(gf_error_detail(), word)) {
        print_error("message '%s' lacks '%s'\n", gf_error_detail(), word);
        fail();
    }
}

static void similarity_rejects_bad_parameters(void **state)
{
    (void)state;
    const gf_simisol_params d = gf_simisol_default();
    gf_simisol_params p = d;
    gf_simisol *s;
    assert_int_equal(gf_simisol_alloc(NULL, &p, 5.0, 1e-10), GF_EINVAL);
    assert_int_equal(gf_simisol_alloc(&s, NULL, 5.0, 1e-10), GF_EINVAL);
    p.g = 0.0;
    expect_simisol_refused(&p, 5.0, 1e-10, GF_EDOM, "gravity");
    p = d;
    p.zeta = 0.0;
    expect_simisol_refused(&p, 5.0, 1e-10, GF_EDOM, "zeta");
    p = d;
    p.delta = p.zeta;
    expect_simisol_refused(&p, 5.0, 1e-10, GF_EPHYS, "does not slide");
    p = d;
    p.H = -1.0;
    expect_simisol_refused(&p, 5.0, 1e-10, GF_EDOM, "thickness H");
    p = d;
    p.Lx = NAN;
    expect_simisol_refused(&p, 5.0, 1e-10, GF_ENONFINITE, "Lx");
    p = d;
    p.Ky = 0.0;
    expect_simisol_refused(&p, 5.0, 1e-10, GF_EDOM, "Ky");
    p = d;
    p.flag_earth = 2;
    expect_simisol_refused(&p, 5.0, 1e-10, GF_EINVAL, "flag_earth");
    p = d;
    p.flag_earth = 1;
    p.phi = 20.0 * GF_DEG; /* delta 25 deg > phi: K complex */
    expect_simisol_refused(&p, 5.0, 1e-10, GF_EPHYS, "internal friction");
    p = d;
    expect_simisol_refused(&p, -1.0, 1e-10, GF_EDOM, "t_end");
    expect_simisol_refused(&p, INFINITY, 1e-10, GF_ENONFINITE, "t_end");
    expect_simisol_refused(&p, 1e5, 1e-10, GF_EDOM, "stored range");
    expect_simisol_refused(&p, 5.0, 0.0, GF_EDOM, "rtol");
    /* queries outside [0, t_end] or at non-finite positions */
    s = simisol_standard(5.0);
    double g, dg, f, df, h, vel[3];
    assert_int_equal(gf_simisol_stretch(s, 5.0 + 1e-9, &g, &dg, &f, &df), GF_EDOM);
    assert_int_equal(gf_simisol_stretch(s, -1e-9, &g, &dg, &f, &df), GF_EDOM);
    assert_int_equal(gf_simisol_sample(s, NAN, 0.0, 1.0, &h, vel), GF_ENONFINITE);
    assert_int_equal(gf_simisol_sample(s, 0.0, 0.0, 1.0, NULL, vel), GF_EINVAL);
    assert_true(isnan(gf_simisol_xc(&p, -1.0)));
    gf_simisol_free(s);
    /* a t_end inside the Taylor start needs no integration */
    assert_int_equal(gf_simisol_alloc(&s, &d, 0.1, 1e-10), GF_SUCCESS);
    assert_int_equal(gf_simisol_stretch(s, 0.1, &g, &dg, &f, &df), GF_SUCCESS);
    assert_close(g, 1.0 + 0.0409576 * (0.1 / 2.855686) * (0.1 / 2.855686), 1e-9);
    gf_simisol_free(s);
    gf_simisol_free(NULL);
}

/* ---- 2. dam break on an inclined Coulomb plane --------------------------- */

static gf_incdam incdam_standard(void)
{
    gf_incdam d;
    assert_int_equal(gf_incdam_init(&d, G, 22.0 * GF_DEG, 21.0 * GF_DEG, 1.0, -120.0),
                     GF_SUCCESS);
    return d;
}

static void incdam_check_values_at_5s(void **state)
{
    (void)state;
    const gf_incdam d = incdam_standard();
    double xt, xf, h, u;
    gf_incdam_fan(&d, 5.0, &xt, &xf);
    const double xm = gf_incdam_xmid(&d, 5.0);
    gf_incdam_sample(&d, -50.0, 5.0, &h, &u);
    const double ub = u;
    gf_incdam_sample(&d, xf - 1e-9, 5.0, &h, &u);
    printf("  gz %.7f, m0 %.8f, cL %.7f; t = 5 s: body/fan %.4f m, front %.4f m, xmid %.4f m, "
           "body %.5f m/s, front %.5f m/s\n",
           d.gz, d.m0, d.cL, xt, xf, xm, ub, u);
    assert_digits(d.gz, 9.095674, 0.5e-6);
    assert_digits(d.m0, 0.1833887, 0.5e-7);
    assert_digits(d.cL, 3.015903, 0.5e-6);
    assert_digits(xt, -11.856, 0.5e-3);
    assert_digits(xf, 30.088, 0.5e-3);
    assert_digits(xm, -73.214, 0.5e-3);
    assert_digits(ub, 0.9169, 0.5e-4);
    /* doc/theory/standard-tests.md prints 6.9487 for 6.94875043 (2 cL + 5 m0): its
     * last digit is truncated, not rounded, so one unit of it is allowed */
    assert_digits(u, 6.9487, 1e-4);
    assert_close(u, 2.0 * d.cL + d.m0 * 5.0, 1e-6);
    /* the error box's first column (Python's round, halves to even) */
    assert_int_equal((int)nearbyint((xm + 602.5) / 3.0), 176);
    assert_int_equal((int)nearbyint((xm + 602.5) / 5.0), 106);
    /* body, fan and dry bed */
    gf_incdam_sample(&d, xt - 1e-9, 5.0, &h, &u);
    assert_close(h, 1.0, 1e-9);
    gf_incdam_sample(&d, xt + 1e-9, 5.0, &h, &u);
    assert_close(h, 1.0, 1e-9);
    assert_close(u, d.m0 * 5.0, 1e-9);
    gf_incdam_sample(&d, xf + 1e-9, 5.0, &h, &u);
    assert_true(h == 0.0 && u == 0.0);
    gf_incdam_sample(&d, -1.0, 0.0, &h, &u);
    assert_true(h == 1.0 && u == 0.0);
    gf_incdam_sample(&d, 1.0, 0.0, &h, &u);
    assert_true(h == 0.0 && u == 0.0);
    gf_verify("Faccanoni & Mangeney 2013", "difference of the front x(5 s) from 30.088 m [m]",
              fabs(xf - 30.088), "<=", 0.5e-3, "inclined dam break, standard test");
}

/* In the frame sliding with the block the fan is Ritter's: it holds the
 * volume the body lost behind the moving dam, hL (m0 t^2/2 - xi_tail) = hL cL t
 * per unit width (along the slope; dxi = dx / cos phi) */
static void incdam_fan_holds_the_volume_the_body_lost(void **state)
{
    (void)state;
    const gf_incdam d = incdam_standard();
    const double cp = cos(d.phi);
    for (double t = 1.0; t <= 9.0; t += 4.0) {
        double xt, xf;
        gf_incdam_fan(&d, t, &xt, &xf);
        const int n = 200000; /* Simpson's rule on the fan, a parabola in x */
        double vol = 0.0;
        for (int i = 0; i <= n; ++i) {
            double h, u;
            gf_incdam_sample(&d, xt + (xf - xt) * i / n, t, &h, &u);
            vol += (i == 0 || i == n ? 1.0 : i % 2 ? 4.0 : 2.0) * h;
        }
        vol *= (xf - xt) / n / 3.0 / cp;
        const double lost = d.hL * (0.5 * d.m0 * t * t - xt / cp);
        printf("  t = %.0f s: fan volume %.9f m2, lost by the body %.9f m2, hL cL t %.9f m2\n", t,
               vol, lost, d.hL * d.cL * t);
        assert_close(vol, lost, 1e-9 * lost);
        assert_close(lost, d.hL * d.cL * t, 1e-12 * lost);
    }
}

/* h_t + (hu)_xi = 0 and u_t + u u_xi + gz h_xi = m0 (K = 1, Coulomb
 * friction of the downslope motion) by central differences in the fan and
 * in the body */
static void incdam_profile_solves_mass_and_momentum_with_coulomb_source(void **state)
{
    (void)state;
    const gf_incdam d = incdam_standard();
    const double cp = cos(d.phi), e = 1e-4;
    double rm = 0.0, rq = 0.0;
    const double t = 5.0, xis[] = {-50.0, -10.0, 0.0, 10.0, 20.0, 30.0, 32.0};
    for (size_t i = 0; i < sizeof xis / sizeof xis[0]; ++i) {
        const double xi = xis[i];
        double h, u, hp, up, hm, um, htp, utp, htm, utm;
        gf_incdam_sample(&d, xi * cp, t, &h, &u);
        gf_incdam_sample(&d, (xi + e) * cp, t, &hp, &up);
        gf_incdam_sample(&d, (xi - e) * cp, t, &hm, &um);
        gf_incdam_sample(&d, xi * cp, t + e, &htp, &utp);
        gf_incdam_sample(&d, xi * cp, t - e, &htm, &utm);
        assert_true(h > 0.0);
        rm = fmax(rm, fabs((htp - htm) / (2 * e) + (hp * up - hm * um) / (2 * e)));
        rq = fmax(rq, fabs((utp - utm) / (2 * e) + u * (up - um) / (2 * e) +
                           d.gz * (hp - hm) / (2 * e) - d.m0));
    }
    printf("  dam break residuals at t = 5 s: mass %.1e m/s, momentum %.1e m/s2 (m0 %.3f)\n", rm,
           rq, d.m0);
    assert_true(rm < 1e-7 && rq < 1e-6);
}

static void incdam_rejects_bad_parameters(void **state)
{
    (void)state;
    gf_incdam d;
    assert_int_equal(gf_incdam_init(NULL, G, 0.4, 0.3, 1.0, -120.0), GF_EINVAL);
    assert_int_equal(gf_incdam_init(&d, -G, 0.4, 0.3, 1.0, -120.0), GF_EDOM);
    assert_int_equal(gf_incdam_init(&d, G, 2.0, 0.3, 1.0, -120.0), GF_EDOM);
    assert_int_equal(gf_incdam_init(&d, G, 0.4, NAN, 1.0, -120.0), GF_ENONFINITE);
    assert_int_equal(gf_incdam_init(&d, G, 0.3, 0.4, 1.0, -120.0), GF_EPHYS);
    assert_non_null(strstr(gf_error_detail(), "would not slide"));
    assert_int_equal(gf_incdam_init(&d, G, 0.4, 0.3, 0.0, -120.0), GF_EDOM);
    assert_int_equal(gf_incdam_init(&d, G, 0.4, 0.3, 1.0, 10.0), GF_EDOM);
    assert_non_null(strstr(gf_error_detail(), "x_back"));
    /* delta = phi: no net acceleration, Ritter's dam break */
    assert_int_equal(gf_incdam_init(&d, G, 0.4, 0.4, 1.0, -120.0), GF_SUCCESS);
    assert_close(d.m0, 0.0, 1e-15);
}

/* ---- 3. flat-plane pile --------------------------------------------------- */

static void flat_pile_flank_at_the_coulomb_slope_and_dry_beyond_60m(void **state)
{
    (void)state;
    const double H0 = 4.0, r0 = 20.0, sp = 0.1, csz = 5.0;
    assert_close(gf_flatpile_h0(H0, r0, sp, 0.0, 0.0), 4.0, 0.0);
    assert_close(gf_flatpile_h0(H0, r0, sp, 12.0, 16.0), 4.0, 1e-15);
    assert_close(gf_flatpile_h0(H0, r0, sp, 24.0, 32.0), 2.0, 1e-14);
    assert_close(gf_flatpile_h0(H0, r0, sp, 0.0, -60.0), 0.0, 1e-15);
    assert_close(gf_flatpile_h0(H0, r0, sp, 70.0, 0.0), 0.0, 0.0);
    /* on the 201 x 201, 5 m grid: no neighbour difference steeper than mu
     * = sp, the flank as steep as mu, nothing wet beyond r = 60 m */
    double steepest = 0.0;
    for (int j = 0; j < 201; ++j)
        for (int i = 0; i < 201; ++i) {
            const double x = -500.0 + i * csz, y = -500.0 + j * csz;
            const double h = gf_flatpile_h0(H0, r0, sp, x, y);
            if (i < 200)
                steepest = fmax(steepest, fabs(gf_flatpile_h0(H0, r0, sp, x + csz, y) - h) / csz);
            if (j < 200)
                steepest = fmax(steepest, fabs(gf_flatpile_h0(H0, r0, sp, x, y + csz) - h) / csz);
            if (hypot(x, y) >= 60.0)
                assert_true(h == 0.0);
        }
    printf("  flat pile: steepest neighbour slope %.15f (mu = %.1f)\n", steepest, sp);
    assert_true(steepest <= sp + 1e-14 && steepest >= sp - 1e-14);
}

/* ---- error measures ------------------------------------------------------- */

static void error_norms_of_hand_made_fields(void **state)
{
    (void)state;
    gf_error_norms e;
    /* scalar: e = 0, 1, 4, 0.25; r = 1, 4, 9, 0 */
    const double a[] = {1, 2, 3, 0}, n[] = {1, 1, 5, 0.5};
    assert_int_equal(gf_error_scalar(a, n, 4, 2.0, &e), GF_SUCCESS);
    assert_close(e.l2, sqrt(2.0 * 5.25), 1e-15);
    assert_close(e.l2ref, sqrt(2.0 * 14.0), 1e-15);
    assert_close(e.rel_l2, sqrt(5.25 / 14.0), 1e-15);
    assert_close(e.lmax, 2.0, 0.0);
    assert_close(e.lmaxref, 3.0, 0.0);
    assert_close(e.rel_lmax, 2.0 / 3.0, 1e-15);
    assert_int_equal(e.n_used, 4);
    /* NaN terms skipped sum by sum (nansum): a NaN analytic value drops the
     * cell from both sums, a NaN numerical value only from the error */
    const double an[] = {1, 2, 3, 0, NAN, 2}, nn[] = {1, 1, 5, 0.5, 7, NAN};
    assert_int_equal(gf_error_scalar(an, nn, 6, 2.0, &e), GF_SUCCESS);
    assert_close(e.l2, sqrt(2.0 * 5.25), 1e-15);
    assert_close(e.l2ref, sqrt(2.0 * 18.0), 1e-15);
    assert_close(e.lmax, 2.0, 0.0);
    assert_close(e.lmaxref, 3.0, 0.0);
    assert_int_equal(e.n_used, 4);
    /* a zero reference (momentum at rest): the absolute values */
    const double z[] = {0, 0, 0}, nz[] = {0.5, -1, 0};
    assert_int_equal(gf_error_scalar(z, nz, 3, 4.0, &e), GF_SUCCESS);
    assert_close(e.rel_l2, sqrt(4.0 * 1.25), 1e-15);
    assert_close(e.rel_l2, e.l2, 0.0);
    assert_close(e.rel_lmax, 1.0, 0.0);
    assert_true(e.l2ref == 0.0 && e.lmaxref == 0.0);
    /* vector: |a - n|^2 = 1, 4 and |a|^2 = 1, 4; a NaN component drops the cell */
    const double av[] = {1, 0, 0, 0, 2, 0, 1, NAN, 0}, nv[] = {1, 1, 0, 0, 2, 2, 0, 0, 0};
    assert_int_equal(gf_error_vector(av, nv, 3, 1.0, &e), GF_SUCCESS);
    assert_close(e.rel_l2, 1.0, 1e-15);
    assert_close(e.l2, sqrt(5.0), 1e-15);
    assert_close(e.lmax, 2.0, 0.0);
    assert_close(e.rel_lmax, 1.0, 0.0);
    assert_int_equal(e.n_used, 2);
    /* a vector with one component is the scalar measure */
    const double a1[] = {3, 0, 0, -1, 0, 0}, n1[] = {2, 0, 0, 1, 0, 0};
    const double a0[] = {3, -1}, n0[] = {2, 1};
    gf_error_norms es;
    assert_int_equal(gf_error_vector(a1, n1, 2, 3.0, &e), GF_SUCCESS);
    assert_int_equal(gf_error_scalar(a0, n0, 2, 3.0, &es), GF_SUCCESS);
    assert_close(e.rel_l2, es.rel_l2, 1e-15);
    assert_close(e.rel_lmax, es.rel_lmax, 1e-15);
    /* the output grids of the standard tests */
    assert_int_equal(gf_output_grid_cells(401, 5.0, 3.0), 667);
    assert_int_equal(gf_output_grid_cells(101, 5.0, 3.0), 167);
    assert_int_equal(gf_output_grid_cells(401, 5.0, 5.0), 401);
    assert_int_equal(gf_output_grid_cells(242, 5.0, 3.0), 402);
    assert_int_equal(gf_output_grid_cells(162, 5.0, 3.0), 269);
    assert_int_equal(gf_output_grid_cells(0, 5.0, 3.0), 0);
    assert_int_equal(gf_output_grid_cells(10, 5.0, 0.0), 0);
}

static void error_norms_reject_bad_input(void **state)
{
    (void)state;
    gf_error_norms e;
    const double a[] = {1, 2, 3}, n[] = {1, INFINITY, 3}, nan3[] = {NAN, NAN, NAN};
    assert_int_equal(gf_error_scalar(NULL, a, 3, 1.0, &e), GF_EINVAL);
    assert_int_equal(gf_error_scalar(a, a, 3, 1.0, NULL), GF_EINVAL);
    assert_int_equal(gf_error_scalar(a, a, 0, 1.0, &e), GF_EINVAL);
    assert_int_equal(gf_error_scalar(a, a, 3, 0.0, &e), GF_EDOM);
    assert_int_equal(gf_error_scalar(a, a, 3, NAN, &e), GF_ENONFINITE);
    assert_int_equal(gf_error_scalar(a, n, 3, 1.0, &e), GF_ENONFINITE);
    assert_non_null(strstr(gf_error_detail(), "cell 1"));
    assert_int_equal(gf_error_scalar(a, nan3, 3, 1.0, &e), GF_ENONFINITE);
    assert_non_null(strstr(gf_error_detail(), "NaN"));
    assert_int_equal(gf_error_vector(a, n, 1, 1.0, &e), GF_ENONFINITE);
    assert_int_equal(gf_error_vector(a, a, 1, -1.0, &e), GF_EDOM);
}

/* ---- 4. energy line --------------------------------------------------------- */

static const double Z0 = 1000.0, MU = 0.4, CSZ = 5.0;

/* A block sliding with Coulomb friction: z + v^2/(2g) = z0 - mu s at every
 * saved time, at rest at the start and the end */
static void energy_line_coulomb_path_ends_on_the_alpha_line(void **state)
{
    (void)state;
    enum { N = 11 };
    double s[N], z[N], v2[N];
    for (int k = 0; k < N; ++k) {
        s[k] = 100.0 * k;
        v2[k] = k == 0 || k == N - 1 ? 0.0 : 2.0 * G * 30.0 * sin(GF_PI * k / (N - 1.0));
        z[k] = Z0 - MU * s[k] - v2[k] / (2.0 * G);
    }
    gf_energy_line r;
    assert_int_equal(gf_energy_line_analyse(s, z, v2, N, MU, G, CSZ, &r), GF_SUCCESS);
    printf("  on the alpha line: err_s %.1e m, err_z %.1e m, err_angle %.1e rad, rmse %.1e m\n",
           r.err_s, r.err_z, r.err_angle, r.rmse_v);
    assert_int_equal(r.extrapolated, 0);
    assert_close(r.s_alpha, 1000.0, 1e-9);
    assert_close(r.z_alpha, Z0 - MU * 1000.0, 1e-9);
    assert_close(r.err_s, 0.0, 1e-9);
    assert_close(r.err_z, 0.0, 1e-9);
    assert_close(r.gamma, atan(MU), 1e-14);
    assert_close(r.err_angle, 0.0, 1e-14);
    assert_close(r.rmse_v, 0.0, 1e-12);
}

/* A run with more dissipation than Coulomb stops short, below the alpha
 * line: the only sign change is the start's, the path is extended along the
 * slope p of its points within 4 csz = 20 m of the end (here a runout line
 * z = 150 - 0.1 (s - 2000); the point 20 m before the end is not in the
 * fit), and the intersection is that line's with the alpha line. */
static void energy_line_short_runout_extrapolates_the_last_slope(void **state)
{
    (void)state;
    enum { N = 8 };
    const double s[N] = {0, 500, 1000, 1500, 1980, 1985, 1992, 2000};
    const double z[N] = {1000, 770, 560, 360, 158.5, 151.5, 150.8, 150};
    const double v2[N] = {0, 400, 500, 300, 20, 8, 2, 0};
    gf_energy_line r;
    assert_int_equal(gf_energy_line_analyse(s, z, v2, N, MU, G, CSZ, &r), GF_SUCCESS);
    const double p = -0.1, sa = (Z0 - 150.0 + p * 2000.0) / (MU + p);
    printf("  short runout: s_alpha %.6f m (%.6f), err_s %.4f m, err_z %.4f m, gamma %.4f deg\n",
           r.s_alpha, sa, r.err_s, r.err_z, r.gamma * GF_RAD2DEG);
    assert_int_equal(r.extrapolated, 1);
    assert_close(r.s_alpha, sa, 1e-9);
    assert_close(r.z_alpha, 150.0 + p * (sa - 2000.0), 1e-9);
    assert_true(r.err_s < 0.0);
    assert_close(r.err_s, 2000.0 - sa, 1e-9);
    assert_close(r.gamma, atan(850.0 / 2000.0), 1e-14);
    assert_true(r.err_angle > 0.0); /* the centre of mass stopped on a steeper line */
    double e2 = 0.0;
    for (int k = 0; k < N; ++k) {
        const double ek = z[k] + v2[k] / (2.0 * G) - (Z0 - MU * s[k]);
        e2 += ek * ek;
    }
    assert_close(r.rmse_v, sqrt(e2 / N), 1e-12);
    /* a runout line almost parallel to the alpha line (slope -0.395 against
     * -0.4) meets it at s = 12,000 m, beyond the last extension to 4 s_end */
    const double zp[N] = {1000, 770, 560, 360, 161, 150 + 0.395 * 15, 150 + 0.395 * 8, 150};
    assert_int_equal(gf_energy_line_analyse(s, zp, v2, N, MU, G, CSZ, &r), GF_ENOCONV);
    assert_non_null(strstr(gf_error_detail(), "no intersection"));
    assert_true(isnan(r.s_alpha) && isnan(r.err_s) && r.extrapolated == 1);
    assert_close(r.gamma, atan(850.0 / 2000.0), 1e-14);
}

/* A run with less dissipation than Coulomb crosses the alpha line and ends
 * above it: the last sign change (between s = 1500 and 1600, the crossing
 * near s = 500 is an earlier one) gives s_alpha = 1550 m, z_alpha = 380 m. */
static void energy_line_long_runout_crosses_the_alpha_line(void **state)
{
    (void)state;
    enum { N = 8 };
    const double s[N] = {0, 200, 500, 800, 1500, 1600, 1800, 2000};
    const double z[N] = {1000, 900, 810, 660, 390, 370, 320, 250};
    double v2[N], e2 = 0.0;
    for (int k = 0; k < N; ++k) { /* energy on the alpha line while below it, at rest above */
        v2[k] = 2.0 * G * fmax(0.0, Z0 - MU * s[k] - z[k]);
        const double ek = z[k] + v2[k] / (2.0 * G) - (Z0 - MU * s[k]);
        e2 += ek * ek;
    }
    gf_energy_line r;
    assert_int_equal(gf_energy_line_analyse(s, z, v2, N, MU, G, CSZ, &r), GF_SUCCESS);
    printf("  long runout: s_alpha %.6f m, z_alpha %.6f m, err_s %.4f m, err_z %.4f m, err_angle "
           "%.4f deg, rmse %.4f m\n",
           r.s_alpha, r.z_alpha, r.err_s, r.err_z, r.err_angle * GF_RAD2DEG, r.rmse_v);
    assert_int_equal(r.extrapolated, 0);
    assert_close(r.s_alpha, 1550.0, 1e-9);
    assert_close(r.z_alpha, 380.0, 1e-9);
    assert_close(r.err_s, 450.0, 1e-9);
    assert_close(r.err_z, -130.0, 1e-9);
    assert_close(r.gamma, atan(750.0 / 2000.0), 1e-14);
    assert_close(r.err_angle, atan(750.0 / 2000.0) - atan(MU), 1e-14);
    assert_close(r.rmse_v, sqrt((100.0 + 100.0 + 1600.0 + 2500.0) / 8.0), 1e-9);
    assert_close(r.rmse_v, sqrt(e2 / N), 1e-12);
}

static void energy_line_rejects_bad_input(void **state)
{
    (void)state;
    const double s[3] = {0, 10, 20}, z[3] = {100, 93, 91}, v2[3] = {0, 1, 0};
    const double sb[3] = {0, 0, 0}, vb[3] = {0, -1, 0}, zb[3] = {100, NAN, 91};
    gf_energy_line r;
    assert_int_equal(gf_energy_line_analyse(NULL, z, v2, 3, MU, G, CSZ, &r), GF_EINVAL);
    assert_int_equal(gf_energy_line_analyse(s, z, v2, 3, MU, G, CSZ, NULL), GF_EINVAL);
    assert_int_equal(gf_energy_line_analyse(s, z, v2, 1, MU, G, CSZ, &r), GF_EINVAL);
    assert_int_equal(gf_energy_line_analyse(s, z, v2, 3, -0.1, G, CSZ, &r), GF_EDOM);
    assert_int_equal(gf_energy_line_analyse(s, z, v2, 3, MU, 0.0, CSZ, &r), GF_EDOM);
    assert_int_equal(gf_energy_line_analyse(s, z, v2, 3, MU, G, 0.0, &r), GF_EDOM);
    assert_int_equal(gf_energy_line_analyse(s, zb, v2, 3, MU, G, CSZ, &r), GF_ENONFINITE);
    assert_int_equal(gf_energy_line_analyse(s, z, vb, 3, MU, G, CSZ, &r), GF_EDOM);
    assert_int_equal(gf_energy_line_analyse(sb, z, v2, 3, MU, G, CSZ, &r), GF_EDOM);
    assert_non_null(strstr(gf_error_detail(), "did not move"));
    /* short of the line with only the end point within 4 csz: no slope */
    assert_int_equal(gf_energy_line_analyse(s, z, v2, 3, MU, G, 1.0, &r), GF_EDOM);
    assert_non_null(strstr(gf_error_detail(), "two distinct"));
    /* the same path with the last two points within 4 csz: slope -0.2,
     * the alpha line met at s = 25 m */
    assert_int_equal(gf_energy_line_analyse(s, z, v2, 3, MU, G, CSZ, &r), GF_SUCCESS);
    assert_int_equal(r.extrapolated, 1);
    assert_close(r.s_alpha, 25.0, 1e-12);
}

/* the energy-line sums of hand-made faces: an unlisted face does not
 * count, a film below h_dry only in the volume; the horizontal speed is the part normal to gravity,
 * whichever way gravity points */
static void path_moments_of_hand_made_faces(void **state)
{
    (void)state;
    const double area[3] = {2.0, 3.0, 5.0};
    const double centre[9] = {1, 2, 3, -4, 0, 10, 7, 7, 7};
    const double h[3] = {0.5, 2.0, 1e-9};
    /* face 0: u = (2, 0, -2) (|u|^2 8, horizontal 2); face 1: u = (0, 3, 4)
     * (|u|^2 25, horizontal 3); face 2 dry */
    const double mom[9] = {1, 0, -1, 0, 6, 8, 1e3, 1e3, 1e3};
    const double g[3] = {0, 0, -9.81};
    double out[6];
    gf_path_moments(3, NULL, area, centre, h, mom, 1e-6, g, out);
    /* the film of face 2 counts in the volume and its moments, not in the speeds */
    assert_close(out[0], 2 * 0.5 + 3 * 2.0 + 5e-9, 1e-14);
    assert_close(out[1], 1.0 * 1 + 6.0 * -4 + 5e-9 * 7, 1e-14);
    assert_close(out[2], 1.0 * 2 + 6.0 * 0 + 5e-9 * 7, 1e-14);
    assert_close(out[3], 1.0 * 3 + 6.0 * 10 + 5e-9 * 7, 1e-14);
    assert_close(out[4], 1.0 * 8 + 6.0 * 25, 1e-12);
    assert_close(out[5], 1.0 * 2 + 6.0 * 3, 1e-12);
    /* gravity along -y: the horizontal part is (x, z) */
    const double gy[3] = {0, -2.0, 0};
    gf_path_moments(3, NULL, area, centre, h, mom, 1e-6, gy, out);
    assert_close(out[5], 1.0 * sqrt(8.0) + 6.0 * 4, 1e-12);
    /* only face 1 listed */
    const int faces[1] = {1};
    gf_path_moments(1, faces, area, centre, h, mom, 1e-6, g, out);
    assert_close(out[0], 6.0, 1e-14);
    assert_close(out[5], 18.0, 1e-12);
}

/* rotating back: a field that is itself the rotated image of a linear
 * field comes back exactly (bilinear is exact for linear fields); 90 deg
 * maps cell centres onto cell centres; outside and NaN give NaN */
static void rotate_back_linear_field_and_quarter_turn(void **state)
{
    (void)state;
    enum { NX = 21, NY = 17 };
    const double gt[6] = {-52.5, 5.0, 0.0, 42.5, 0.0, -5.0}; /* centres x -50..50, y 40..-40 */
    double v[NX * NY], out[NX * NY];
    const double ang = 120.0, a = ang * 3.14159265358979323846 / 180.0, cx = 3.0, cy = -2.0;
    /* the reference field f(p) = 2 + 0.3 x - 0.7 y; the run holds f(R^-1 (q)),
     * R clockwise by ang about (cx, cy), so that out(p) = run(R p) = f(p) */
    for (int r = 0; r < NY; ++r)
        for (int c = 0; c < NX; ++c) {
            const double x = gt[0] + (c + 0.5) * gt[1] - cx, y = gt[3] + (r + 0.5) * gt[5] - cy;
            /* R^-1: anticlockwise by ang */
            const double xi = cx + x * cos(a) - y * sin(a), yi = cy + x * sin(a) + y * cos(a);
            v[r * NX + c] = 2 + 0.3 * xi - 0.7 * yi;
        }
    assert_int_equal(gf_grid_rotate_back(NX, NY, gt, v, ang, cx, cy, out), GF_SUCCESS);
    int inside = 0, outside = 0;
    for (int r = 0; r < NY; ++r)
        for (int c = 0; c < NX; ++c) {
            const double x = gt[0] + (c + 0.5) * gt[1], y = gt[3] + (r + 0.5) * gt[5];
            const double o = out[r * NX + c];
            if (isnan(o)) {
                ++outside;
                continue;
            }
            ++inside;
            assert_close(o, 2 + 0.3 * x - 0.7 * y, 1e-11);
        }
    /* the corners of this 100 m x 80 m grid rotate outside it */
    assert_true(inside > 100);
    assert_true(outside > 50);
    /* a quarter turn about a cell centre: cell (c, r) takes the value of
     * the cell a quarter turn clockwise away, exactly */
    const double g2[6] = {-2.5, 1.0, 0.0, 2.5, 0.0, -1.0}; /* 5 x 5, centres -2..2 */
    double w[25], o2[25];
    for (int k = 0; k < 25; ++k)
        w[k] = k;
    w[0] = NAN;
    assert_int_equal(gf_grid_rotate_back(5, 5, g2, w, 90.0, 0.0, 0.0, o2), GF_SUCCESS);
    /* p = (x, y) -> R p = (y, -x): centre (x, y) at col x + 2, row 2 - y */
    for (int r = 0; r < 5; ++r)
        for (int c = 0; c < 5; ++c) {
            const int x = c - 2, y = 2 - r, xr = y, yr = -x;
            const int k = (2 - yr) * 5 + (xr + 2);
            if (k == 0)
                assert_true(isnan(o2[r * 5 + c]));
            else
                assert_close(o2[r * 5 + c], (double)k, 1e-12);
        }
    const double bad[6] = {-2.5, 1.0, 0.1, 2.5, 0.0, -1.0};
    assert_int_equal(gf_grid_rotate_back(5, 5, bad, w, 90.0, 0.0, 0.0, o2), GF_EDOM);
    assert_int_equal(gf_grid_rotate_back(5, 5, g2, w, NAN, 0.0, 0.0, o2), GF_EDOM);
    assert_int_equal(gf_grid_rotate_back(0, 5, g2, w, 90.0, 0.0, 0.0, o2), GF_EINVAL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(similarity_coefficients_of_the_standard_test),
        cmocka_unit_test(similarity_stretching_at_5s_matches_the_reference_integration),
        cmocka_unit_test(similarity_dense_output_equals_integration_to_that_time),
        cmocka_unit_test(similarity_conserves_volume_and_its_centre_slides_with_the_frame),
        cmocka_unit_test(similarity_fields_solve_the_mass_and_momentum_balances),
        cmocka_unit_test(similarity_earth_pressure_switch_stays_active_while_spreading),
        cmocka_unit_test(similarity_rejects_bad_parameters),
        cmocka_unit_test(incdam_check_values_at_5s),
        cmocka_unit_test(incdam_fan_holds_the_volume_the_body_lost),
        cmocka_unit_test(incdam_profile_solves_mass_and_momentum_with_coulomb_source),
        cmocka_unit_test(incdam_rejects_bad_parameters),
        cmocka_unit_test(flat_pile_flank_at_the_coulomb_slope_and_dry_beyond_60m),
        cmocka_unit_test(error_norms_of_hand_made_fields),
        cmocka_unit_test(error_norms_reject_bad_input),
        cmocka_unit_test(energy_line_coulomb_path_ends_on_the_alpha_line),
        cmocka_unit_test(energy_line_short_runout_extrapolates_the_last_slope),
        cmocka_unit_test(energy_line_long_runout_crosses_the_alpha_line),
        cmocka_unit_test(energy_line_rejects_bad_input),
        cmocka_unit_test(path_moments_of_hand_made_faces),
        cmocka_unit_test(rotate_back_linear_field_and_quarter_turn),
    };
    return gf_run_tests("standard_tests", tests, NULL, NULL);
}
