/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Friction-law table: values against independent Python computations of
 * finite-area paper eqs. 24-26, 60, 71; selection by name; bad input. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include "../gf_test.h"

#include "granflow/friction.h"
#include "granflow/constants.h"
/* the explicit scheme's four-lane samosAT solver (internal) */
#include "../../libsrc/granflow/src/physics/friction_implicit.h"


/* h = 0.5 m, |u| = 2 m/s, rho = 1500, p_b = rho g cos(35 deg) h */
static gf_friction_state reference_state(void)
{
    gf_friction_state s = {0.5, 2.0, 1500 * 9.81 * cos(35 * GF_DEG) * 0.5, 1500.0, 9.81};
    return s;
}

static void mu_i_matches_table1_reference(void **state)
{
    (void)state;
    gf_friction f;
    gf_friction_result r;
    assert_int_equal(gf_friction_init(&f, "mu_i"), GF_SUCCESS); /* Table 1 defaults */
    const gf_friction_state s = reference_state();
    assert_int_equal(gf_friction_eval(&f, &s, &r), GF_SUCCESS);
    assert_close(s.pb, 6026.911165856257, 1e-9);
    assert_close(r.tau, 1.631897387669238, 1e-12);
    /* the implicit coefficient against the reference shear: tau_b/rho = nu |u| */
    assert_close(r.nu, 1.631897387669238 / s.speed, 1e-12);
    assert_close(r.mu * (2.0 + 1e-4) / 2.0, 0.4061729808921356, 1e-12);
}

static void mu_i_limits_are_mu_s_and_mu_2(void **state)
{
    (void)state;
    gf_friction f;
    gf_friction_result r;
    gf_friction_init(&f, "mu_i");
    gf_friction_set(&f, "u0", 0.0);
    gf_friction_state s = reference_state();
    s.speed = 1e-12; /* I -> 0 */
    gf_friction_eval(&f, &s, &r);
    assert_close(r.mu, 0.38, 1e-9);
    s.speed = 1e9; /* I -> infinity */
    gf_friction_eval(&f, &s, &r);
    assert_close(r.mu, 0.65, 1e-6);
}

static void coulomb_chezy_voellmy_none(void **state)
{
    (void)state;
    gf_friction f;
    gf_friction_result r;
    gf_friction_state s = reference_state();
    gf_friction_init(&f, "coulomb");
    gf_friction_set(&f, "mu", tan(30 * GF_DEG));
    gf_friction_eval(&f, &s, &r);
    assert_close(r.tau, tan(30 * GF_DEG) * 9.81 * cos(35 * GF_DEG) * 0.5, 1e-12);
    s.speed = 0.0; /* exact Coulomb at rest: static bound, infinite stiffness */
    gf_friction_eval(&f, &s, &r);
    assert_close(r.tau, tan(30 * GF_DEG) * 9.81 * cos(35 * GF_DEG) * 0.5, 1e-12);
    assert_true(isinf(r.nu));
    s = reference_state();
    gf_friction_init(&f, "chezy"); /* C = 40 default, eq. 71 */
    gf_friction_eval(&f, &s, &r);
    assert_close(r.tau, 0.024525, 1e-15);
    gf_friction_init(&f, "voellmy");
    gf_friction_eval(&f, &s, &r);
    assert_close(r.tau, 0.8427879780485986, 1e-12);
    gf_friction_init(&f, "none");
    gf_friction_eval(&f, &s, &r);
    assert_close(r.tau, 0.0, 0);
    assert_close(r.nu, 0.0, 0);
}

static void no_contact_no_coulomb_friction(void **state)
{
    (void)state;
    gf_friction f;
    gf_friction_result r;
    gf_friction_state s = reference_state();
    s.pb = -10.0; /* lift-off */
    gf_friction_init(&f, "mu_i");
    gf_friction_eval(&f, &s, &r);
    assert_close(r.tau, 0.0, 0);
    s.h = 0.0;
    s.pb = 0.0;
    gf_friction_eval(&f, &s, &r);
    assert_close(r.tau, 0.0, 0);
}

static void implicit_update_never_reverses_velocity(void **state)
{
    (void)state;
    const char *laws[] = {"coulomb", "mu_i", "voellmy", "chezy"};
    gf_friction_state s = reference_state();
    for (size_t i = 0; i < 4; ++i) {
        gf_friction f;
        gf_friction_result r;
        gf_friction_init(&f, laws[i]);
        if (i == 0)
            gf_friction_set(&f, "u0", 1e-4);
        gf_friction_eval(&f, &s, &r);
        for (double dt = 1e-4; dt < 1e4; dt *= 10) {
            const double u_new = s.speed / (1 + dt * r.nu / s.h);
            assert_true(u_new >= 0 && u_new <= s.speed);
        }
    }
    assert_close(gf_friction_decelerate(1.0, 0.25), 0.75, 1e-15);
    assert_close(gf_friction_decelerate(-1.0, 0.25), -0.75, 1e-15);
    assert_close(gf_friction_decelerate(0.1, 5.0), 0.0, 0);
    assert_close(gf_friction_decelerate(-0.1, 5.0), 0.0, 0);
}

/* The static bound is the limit of the unregularised shear as |u| -> 0+,
 * whatever u0 the law carries: mu_s p_b/rho for mu_i (eq. 25 at I_b = 0),
 * mu p_b/rho for coulomb and voellmy, 0 for chezy, none and p_b <= 0. */
static void static_bound_is_the_coulomb_limit(void **state)
{
    (void)state;
    gf_friction_state s = reference_state();
    const double p = s.pb / s.rho;
    gf_friction f;
    double tau_s = -1;
    gf_friction_init(&f, "mu_i"); /* Table 1, u0 = 1e-4 */
    assert_int_equal(gf_friction_static_bound(&f, &s, &tau_s), GF_SUCCESS);
    assert_close(tau_s, 0.38 * p, 1e-14);
    /* independent: unregularised shear at vanishing speed */
    gf_friction_set(&f, "u0", 0.0);
    gf_friction_result r;
    s.speed = 1e-12;
    gf_friction_eval(&f, &s, &r);
    assert_close(r.tau, tau_s, 1e-9);
    /* the regularised law at rest exerts nothing: the bound is not its value */
    gf_friction_set(&f, "u0", 1e-4);
    s.speed = 0.0;
    gf_friction_eval(&f, &s, &r);
    assert_close(r.tau, 0.0, 0);
    gf_friction_init(&f, "coulomb");
    gf_friction_set(&f, "mu", 0.7);
    gf_friction_set(&f, "u0", 1e-3);
    gf_friction_static_bound(&f, &s, &tau_s);
    assert_close(tau_s, 0.7 * p, 1e-14);
    gf_friction_init(&f, "voellmy");
    gf_friction_static_bound(&f, &s, &tau_s);
    assert_close(tau_s, 0.2 * p, 1e-14);
    gf_friction_init(&f, "chezy");
    gf_friction_static_bound(&f, &s, &tau_s);
    assert_close(tau_s, 0.0, 0);
    gf_friction_init(&f, "mu_i");
    s.pb = -5.0; /* lift-off */
    gf_friction_static_bound(&f, &s, &tau_s);
    assert_close(tau_s, 0.0, 0);
    s.pb = NAN;
    assert_int_equal(gf_friction_static_bound(&f, &s, &tau_s), GF_ENONFINITE);
    assert_int_equal(gf_friction_static_bound(NULL, &s, &tau_s), GF_EINVAL);
}

static void unknown_law_lists_valid_names(void **state)
{
    (void)state;
    gf_friction f;
    assert_int_equal(gf_friction_init(&f, "coulmb"), GF_ENOTFOUND);
    assert_non_null(strstr(gf_error_detail(), "coulmb"));
    assert_non_null(strstr(gf_error_detail(), "coulomb, mu_i, voellmy, chezy, samosAT, none"));
    assert_null(gf_friction_lookup("Coulomb"));
    size_t n = 0;
    for (const gf_friction_type *const *t = gf_friction_types(); *t; ++t, ++n)
        assert_ptr_equal(gf_friction_lookup((*t)->name), *t);
    assert_int_equal(n, 6);
}

static void bad_coefficients_name_key_and_range(void **state)
{
    (void)state;
    gf_friction f;
    double v;
    gf_friction_init(&f, "mu_i");
    assert_int_equal(gf_friction_set(&f, "mu_s", -0.1), GF_EDOM);
    assert_non_null(strstr(gf_error_detail(), "mu_s"));
    assert_non_null(strstr(gf_error_detail(), "[0, 10]"));
    assert_int_equal(gf_friction_set(&f, "mu_s", NAN), GF_ENONFINITE);
    assert_int_equal(gf_friction_set(&f, "xi", 100), GF_ENOTFOUND);
    assert_non_null(strstr(gf_error_detail(), "mu_s, mu_2, I_0, d, rho_p, u0"));
    assert_int_equal(gf_friction_get(&f, "mu_s", &v), GF_SUCCESS);
    assert_close(v, 0.38, 0); /* unchanged by the rejected sets */
    assert_int_equal(gf_friction_set(&f, "mu_s", 0.7), GF_SUCCESS);
    assert_int_equal(gf_friction_check(&f), GF_EPHYS); /* mu_2 = 0.65 < mu_s */
    assert_non_null(strstr(gf_error_detail(), "mu_2"));
}

static void bad_state_is_an_error_not_nan(void **state)
{
    (void)state;
    gf_friction f;
    gf_friction_result r;
    gf_friction_init(&f, "mu_i");
    gf_friction_state s = reference_state();
    s.h = -1e-3;
    assert_int_equal(gf_friction_eval(&f, &s, &r), GF_EDOM);
    assert_non_null(strstr(gf_error_detail(), "thickness"));
    s = reference_state();
    s.speed = NAN;
    assert_int_equal(gf_friction_eval(&f, &s, &r), GF_ENONFINITE);
    s = reference_state();
    s.pb = INFINITY;
    assert_int_equal(gf_friction_eval(&f, &s, &r), GF_ENONFINITE);
}

/* gf_friction_implicit_speed solves h s + dt tau(s) = M: for every law the
 * returned speed satisfies it to 1e-12 relative (or is 0 exactly where the
 * law at rest holds M: Coulomb with u0 = 0 stops at dt mu p/rho >= M). */
static void implicit_speed_solves_backward_euler(void **state)
{
    (void)state;
    const char *laws[] = {"coulomb", "mu_i", "voellmy", "chezy", "samosAT", "none"};
    const double h = 0.3, rho = 1500.0, g = 9.81, pb = rho * g * h * 0.9, dt = 0.01;
    for (size_t l = 0; l < sizeof laws / sizeof laws[0]; ++l)
        for (int reg = 0; reg < 2; ++reg) {
            gf_friction f;
            assert_int_equal(gf_friction_init(&f, laws[l]), GF_SUCCESS);
            double u0;
            if (gf_friction_get(&f, "u0", &u0) == GF_SUCCESS)
                assert_int_equal(gf_friction_set(&f, "u0", reg ? 1e-3 : 0.0), GF_SUCCESS);
            else if (reg)
                continue;
            const gf_friction_state st = {h, 0.0, pb, rho, g};
            for (double M = 1e-6; M < 100.0; M *= 3.7) {
                double s;
                assert_int_equal(gf_friction_implicit_speed(&f, &st, M, dt, &s), GF_SUCCESS);
                assert_true(s >= 0.0 && s <= M / h);
                gf_friction_state x = st;
                x.speed = s;
                gf_friction_result r;
                assert_int_equal(gf_friction_eval(&f, &x, &r), GF_SUCCESS);
                if (s == 0.0)
                    assert_true(dt * r.tau >= M * (1.0 - 1e-12)); /* held at rest */
                else
                    assert_true(fabs(h * s + dt * r.tau - M) <= 1e-12 * M);
            }
        }
    /* samosAT's Newton branch (u0 = 0) over its regimes: thinner than R (no
     * log term), thick, with a yield stress, without contact (lift-off) */
    {
        gf_friction f;
        assert_int_equal(gf_friction_init(&f, "samosAT"), GF_SUCCESS);
        assert_int_equal(gf_friction_set(&f, "u0", 0.0), GF_SUCCESS);
        const double hs[] = {0.01, 0.3, 4.0}, tau0s[] = {0.0, 150.0}, pbf[] = {0.9, 0.0};
        size_t n = 0;
        for (size_t a = 0; a < 3; ++a)
            for (size_t b = 0; b < 2; ++b)
                for (size_t c = 0; c < 2; ++c) {
                    assert_int_equal(gf_friction_set(&f, "tau0", tau0s[b]), GF_SUCCESS);
                    const gf_friction_state st = {hs[a], 0.0, 200.0 * g * hs[a] * pbf[c], 200.0, g};
                    for (double M = 1e-7; M < 300.0; M *= 2.3)
                        for (double dtk = 1e-3; dtk < 2.0; dtk *= 10.0) {
                            double s;
                            assert_int_equal(gf_friction_implicit_speed(&f, &st, M, dtk, &s), GF_SUCCESS);
                            assert_true(s >= 0.0 && s <= M / st.h);
                            gf_friction_state x = st;
                            x.speed = s;
                            gf_friction_result r;
                            assert_int_equal(gf_friction_eval(&f, &x, &r), GF_SUCCESS);
                            if (s == 0.0)
                                assert_true(dtk * r.tau >= M * (1.0 - 1e-12));
                            else if (fabs(st.h * s + dtk * r.tau - M) > 1e-12 * M)
                                fail_msg("samosAT h %g tau0 %g pb %g M %g dt %g: s %.17g, residual %.3g", st.h,
                                         tau0s[b], st.pb, M, dtk, s, st.h * s + dtk * r.tau - M);
                            ++n;
                        }
                }
        assert_true(n > 500);
    }
    /* exact Coulomb stops exactly at the bound and not below it */
    gf_friction c;
    assert_int_equal(gf_friction_init(&c, "coulomb"), GF_SUCCESS);
    assert_int_equal(gf_friction_set(&c, "mu", 0.5), GF_SUCCESS);
    const gf_friction_state st = {h, 0.0, pb, rho, g};
    const double bound = dt * 0.5 * pb / rho;
    double s;
    assert_int_equal(gf_friction_implicit_speed(&c, &st, bound, dt, &s), GF_SUCCESS);
    assert_true(s == 0.0);
    assert_int_equal(gf_friction_implicit_speed(&c, &st, 2.0 * bound, dt, &s), GF_SUCCESS);
    assert_close(s, bound / h, 1e-15);
    assert_int_equal(gf_friction_implicit_speed(&c, &st, -1.0, dt, &s), GF_EDOM);
}

/* samosAT against the limits of its specification (doc/theory/friction.md): u -> 0 gives tau0 + 2 mu sigma_b (u0 = 0), large u
 * Coulomb mu sigma_b plus the drag, whose coefficient at h = 1 m is
 * 1/(ln(20)/0.43 + 4.13)^2 = 8.12e-3; below h = R the logarithm is 0 (drag
 * 1/B^2); the fluidisation factor is 1 + Rs0/(Rs0 + Rs) at every speed; no
 * contact, no yield or Coulomb part; the regularised default has no shear at rest. */
static void samosat_limits(void **state)
{
    (void)state;
    gf_friction f;
    assert_int_equal(gf_friction_init(&f, "samosAT"), GF_SUCCESS);
    double v;
    assert_int_equal(gf_friction_get(&f, "mu", &v), GF_SUCCESS);
    assert_close(v, 0.155, 0);
    assert_int_equal(gf_friction_get(&f, "u0", &v), GF_SUCCESS);
    assert_close(v, 1e-4, 0);
    assert_int_equal(gf_friction_set(&f, "u0", 0.0), GF_SUCCESS);
    assert_int_equal(gf_friction_set(&f, "tau0", 150.0), GF_SUCCESS);
    const double rho = 200.0, h = 1.0, sig = rho * 9.81 * h * cos(30 * GF_DEG);
    gf_friction_state st = {h, 0.0, sig, rho, 9.81};
    gf_friction_result r;
    /* at rest: tau0 + 2 mu sigma_b (the static bound too) */
    assert_int_equal(gf_friction_eval(&f, &st, &r), GF_SUCCESS);
    assert_close(r.tau, (150.0 + 2.0 * 0.155 * sig) / rho, 1e-12);
    double tau_s;
    assert_int_equal(gf_friction_static_bound(&f, &st, &tau_s), GF_SUCCESS);
    assert_close(tau_s, r.tau, 1e-12);
    /* any speed: the formula evaluated independently */
    const double cd1 = 1.0 / pow(log(1.0 / 0.05) / 0.43 + 4.13, 2);
    assert_close(cd1, 8.12e-3, 5e-6);
    for (double u = 0.01; u < 200.0; u *= 3.0) {
        st.speed = u;
        assert_int_equal(gf_friction_eval(&f, &st, &r), GF_SUCCESS);
        const double rs = rho * u * u / (sig + 0.001);
        const double expect = (150.0 + 0.155 * (1.0 + 0.222 / (0.222 + rs)) * sig) / rho + cd1 * u * u;
        assert_close(r.tau, expect, 1e-12 * expect);
        assert_close(r.nu * u, r.tau, 1e-12 * r.tau);
    }
    /* large speed: the Coulomb factor tends to 1 */
    st.speed = 1e4;
    assert_int_equal(gf_friction_eval(&f, &st, &r), GF_SUCCESS);
    assert_close(r.tau - cd1 * 1e8, (150.0 + 0.155 * sig) / rho, 1e-6 * r.tau);
    /* h below the roughness length R: ln(h/R) = 0, drag 1/B^2 */
    st.h = 0.01;
    st.speed = 2.0;
    assert_int_equal(gf_friction_set(&f, "tau0", 0.0), GF_SUCCESS);
    assert_int_equal(gf_friction_eval(&f, &st, &r), GF_SUCCESS);
    const double rs = rho * 4.0 / (sig + 0.001);
    assert_close(r.tau, 0.155 * (1.0 + 0.222 / (0.222 + rs)) * sig / rho + 4.0 / (4.13 * 4.13), 1e-12);
    /* lift-off: the drag only */
    st.pb = -1.0;
    assert_int_equal(gf_friction_eval(&f, &st, &r), GF_SUCCESS);
    assert_close(r.tau, 4.0 / (4.13 * 4.13), 1e-15);
    /* the regularised default: no shear at rest, so the implicit scheme's nu is finite */
    gf_friction g;
    assert_int_equal(gf_friction_init(&g, "samosAT"), GF_SUCCESS);
    gf_friction_state rest = {h, 0.0, sig, rho, 9.81};
    assert_int_equal(gf_friction_eval(&g, &rest, &r), GF_SUCCESS);
    assert_close(r.tau, 0.0, 0);
    assert_true(isfinite(r.nu));
    /* a denormal basal pressure with a yield stress stays finite (no tau0/sigma_b) */
    assert_int_equal(gf_friction_set(&g, "tau0", 150.0), GF_SUCCESS);
    gf_friction_state thin = {h, 1.0, 1e-310, rho, 9.81};
    assert_int_equal(gf_friction_eval(&g, &thin, &r), GF_SUCCESS);
    assert_true(isfinite(r.tau) && isfinite(r.nu));
    assert_close(r.tau, 150.0 / rho * 1.0 / (1.0 + 1e-4) + cd1, 1e-12);
    /* B must be positive */
    assert_int_equal(gf_friction_set(&g, "B", 0.0), GF_EDOM);
}

/* samosATAuto (AvaFrame com1DFA: volClassSmall 25,000 m^3, volClassMedium
 * 60,000 m^3): below 25,000 m^3 samosATSmall (mu 0.22), from it to below
 * 60,000 m^3 samosATMedium (0.17), from 60,000 m^3 on samosAT (0.155), at
 * and one ulp around both thresholds, and far from them; the sets differ in
 * mu only (tau0 0, Rs0 0.222, kappa 0.43, R 0.05, B 4.13, AvaFrame's
 * com1DFACfg.ini); a law initialised with a set evaluates as samosAT with
 * that mu; no volume (0), a negative or non-finite one is an error. */
static void samosat_auto_by_release_volume(void **state)
{
    (void)state;
    assert_true(GF_SAMOSAT_VOL_SMALL == 25000.0 && GF_SAMOSAT_VOL_MEDIUM == 60000.0);
    const struct {
        double v;
        const char *set;
        double mu;
    } cases[] = {
        {1.0, "samosATSmall", 0.22},
        {nextafter(25000.0, 0.0), "samosATSmall", 0.22},
        {25000.0, "samosATMedium", 0.17},
        {nextafter(25000.0, 1e9), "samosATMedium", 0.17},
        {41000.0, "samosATMedium", 0.17},
        {nextafter(60000.0, 0.0), "samosATMedium", 0.17},
        {60000.0, "samosAT", 0.155},
        {nextafter(60000.0, 1e9), "samosAT", 0.155},
        {1e9, "samosAT", 0.155},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k) {
        const gf_samosat_set *set = NULL;
        assert_int_equal(gf_samosat_auto(cases[k].v, &set), GF_SUCCESS);
        assert_non_null(set);
        assert_string_equal(set->name, cases[k].set);
        assert_true(set->mu == cases[k].mu);
        assert_true(set->tau0 == 0.0 && set->Rs0 == 0.222 && set->kappa == 0.43 && set->R == 0.05 && set->B == 4.13);
        /* the law of the set is samosAT with its mu */
        gf_friction a, b;
        assert_int_equal(gf_friction_init_samosat_set(&a, set), GF_SUCCESS);
        assert_int_equal(gf_friction_init(&b, "samosAT"), GF_SUCCESS);
        assert_int_equal(gf_friction_set(&b, "mu", cases[k].mu), GF_SUCCESS);
        assert_ptr_equal(a.type, gf_friction_samosat);
        const gf_friction_state st = {0.8, 3.0, 200 * 9.81 * 0.8 * cos(30 * GF_DEG), 200.0, 9.81};
        gf_friction_result ra, rb;
        assert_int_equal(gf_friction_eval(&a, &st, &ra), GF_SUCCESS);
        assert_int_equal(gf_friction_eval(&b, &st, &rb), GF_SUCCESS);
        assert_true(ra.tau == rb.tau && ra.nu == rb.nu);
        double u0;
        assert_int_equal(gf_friction_get(&a, "u0", &u0), GF_SUCCESS);
        assert_true(u0 == 1e-4);
    }
    const gf_samosat_set *sets = gf_samosat_sets(), *set = NULL;
    assert_string_equal(sets[0].name, "samosATSmall");
    assert_string_equal(sets[1].name, "samosATMedium");
    assert_string_equal(sets[2].name, "samosAT");
    assert_null(sets[3].name);
    assert_int_equal(gf_samosat_auto(0.0, &set), GF_EDOM);
    assert_non_null(strstr(gf_error_detail(), "allowed > 0"));
    assert_int_equal(gf_samosat_auto(-5.0, &set), GF_EDOM);
    assert_int_equal(gf_samosat_auto(NAN, &set), GF_ENONFINITE);
    assert_int_equal(gf_samosat_auto(INFINITY, &set), GF_ENONFINITE);
    assert_int_equal(gf_samosat_auto(1.0, NULL), GF_EINVAL);
}

/* The four-lane samosAT solver of the explicit scheme gives each lane the
 * scalar solver's speed bit for bit, over the regimes of
 * implicit_speed_solves_backward_euler (thin and thick, yield stress,
 * lift-off, held at rest) with the lanes' states mixed, so that lanes leave
 * the Newton loop at different iterations */
static void samosat_four_lanes_equal_scalar(void **state)
{
    (void)state;
    const double g = 9.81, rho = 200.0;
    gf_friction f;
    assert_int_equal(gf_friction_init(&f, "samosAT"), GF_SUCCESS);
    assert_int_equal(gf_friction_set(&f, "u0", 0.0), GF_SUCCESS);
    assert_true(gf_friction_samosat4(&f));
    const double hs[] = {0.01, 0.04, 0.3, 1.7, 4.0}, tau0s[] = {0.0, 150.0}, pbf[] = {0.9, 0.0, 0.35};
    const double dts[] = {1e-3, 0.05, 0.3, 1.5};
    unsigned seed = 12345;
    size_t n = 0, moving = 0, iters = 0;
    for (size_t b = 0; b < 2; ++b) {
        assert_int_equal(gf_friction_set(&f, "tau0", tau0s[b]), GF_SUCCESS);
        for (size_t d = 0; d < 4; ++d)
            for (int rep = 0; rep < 400; ++rep) {
                double h[4], pb[4], M[4], s4[4];
                for (int k = 0; k < 4; ++k) {
                    seed = seed * 1103515245u + 12345u;
                    h[k] = hs[(seed >> 8) % 5];
                    pb[k] = rho * g * h[k] * pbf[(seed >> 12) % 3];
                    M[k] = h[k] * 1e-4 * pow(10.0, 6.0 * ((seed >> 16) % 1000) / 1000.0); /* speeds 1e-4 .. 100 */
                }
                gf_friction_implicit_speed_samosat4(&f, h, pb, rho, M, dts[d], s4);
                for (int k = 0; k < 4; ++k) {
                    const gf_friction_state st = {h[k], 0.0, pb[k], rho, g};
                    double s1;
                    assert_int_equal(gf_friction_implicit_speed(&f, &st, M[k], dts[d], &s1), GF_SUCCESS);
                    if (memcmp(&s1, &s4[k], sizeof s1) != 0)
                        fail_msg("lane %d: h %g pb %g M %g dt %g: scalar %.17g, four lanes %.17g", k, h[k], pb[k],
                                 M[k], dts[d], s1, s4[k]);
                    moving += s1 > 0.0;
                    ++n;
                }
                ++iters;
            }
    }
    /* both branches exercised: faces held at rest and moving ones */
    assert_true(n == 4 * iters && moving > n / 4 && moving < n);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(mu_i_matches_table1_reference),
        cmocka_unit_test(mu_i_limits_are_mu_s_and_mu_2),
        cmocka_unit_test(coulomb_chezy_voellmy_none),
        cmocka_unit_test(no_contact_no_coulomb_friction),
        cmocka_unit_test(implicit_update_never_reverses_velocity),
        cmocka_unit_test(static_bound_is_the_coulomb_limit),
        cmocka_unit_test(implicit_speed_solves_backward_euler),
        cmocka_unit_test(samosat_limits),
        cmocka_unit_test(samosat_four_lanes_equal_scalar),
        cmocka_unit_test(samosat_auto_by_release_volume),
        cmocka_unit_test(unknown_law_lists_valid_names),
        cmocka_unit_test(bad_coefficients_name_key_and_range),
        cmocka_unit_test(bad_state_is_an_error_not_nan),
    };
    return gf_run_tests("friction", tests, NULL, NULL);
}
