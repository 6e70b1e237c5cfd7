/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Back-calculation (granflow/calibration.h; doc/theory/calibration.md): the
 * designs, the scores of a run against an observation, the simplex
 * refinement, the ABC ranges, the emulator's ridge and the unreachable
 * verdict, against what they must be exactly or on losses whose minimum and
 * ridge are known. */
#include "../gf_test.h"

#include "granflow/calibration.h"
#include "granflow/ensemble.h"

#define PI 3.14159265358979323846

/* Sobol design: GSL's sequence is Sobol's in Gray-code order with Bratley &
 * Fox's direction numbers, without its origin (dimensions 1-3: 1/2 1/2 1/2,
 * 3/4 1/4 3/4, 1/4 3/4 1/4, 3/8 3/8 5/8, 7/8 7/8 1/8); its first 15 points
 * with the origin fill every stratum of 1/16 once in each dimension and every
 * box of 1/4 x 1/4 once in dimensions 1-2 (a (0, 4, 2)-net); skip drops the
 * first points */
static void sobol_design_is_the_sobol_sequence_and_stratified(void **state)
{
    (void)state;
    const double first[5][3] = {{0.5, 0.5, 0.5},
                                {0.75, 0.25, 0.75},
                                {0.25, 0.75, 0.25},
                                {0.375, 0.375, 0.625},
                                {0.875, 0.875, 0.125}};
    double u[15 * 3], v[2 * 3];
    assert_int_equal(gf_design_sobol(15, 3, 0, u), GF_SUCCESS);
    for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 3; ++j)
            assert_close(u[i * 3 + j], first[i][j], 0);
    for (int j = 0; j < 3; ++j) {
        int hits[16] = {1, 0}; /* the origin */
        for (int i = 0; i < 15; ++i) {
            assert_true(u[i * 3 + j] >= 0 && u[i * 3 + j] < 1);
            ++hits[(int)floor(u[i * 3 + j] * 16)];
        }
        for (int k = 0; k < 16; ++k)
            assert_int_equal(hits[k], 1);
    }
    int box[4][4] = {{1, 0}};
    for (int i = 0; i < 15; ++i)
        ++box[(int)floor(u[i * 3] * 4)][(int)floor(u[i * 3 + 1] * 4)];
    for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b)
            assert_int_equal(box[a][b], 1);
    assert_int_equal(gf_design_sobol(2, 3, 3, v), GF_SUCCESS);
    assert_memory_equal(v, u + 3 * 3, sizeof v);
    assert_int_equal(gf_design_sobol(1, GF_SOBOL_MAX_DIM + 1, 0, u), GF_EINVAL);
    assert_true(strlen(gf_error_detail()) > 0);
    assert_int_equal(gf_design_sobol(0, 2, 0, u), GF_EINVAL);
    assert_int_equal(gf_design_sobol(1, 2, 0, NULL), GF_EINVAL);
}

/* Morris trajectories (p = 4, Delta = 2/3): every point on the grid
 * {0, 1/3, 2/3, 1}, every step +-Delta in one coordinate, each parameter
 * once per trajectory; the seed reproduces them */
static void morris_trajectories_step_delta_on_the_grid(void **state)
{
    (void)state;
    enum { R = 20, D = 5, P = 4 };
    double u[R * (D + 1) * D], w[R * (D + 1) * D];
    const double delta = gf_morris_delta(P);
    assert_close(delta, 2.0 / 3.0, 1e-15);
    assert_close(gf_morris_delta(2), 1.0, 0);
    assert_int_equal(gf_design_morris(R, D, P, 7, u), GF_SUCCESS);
    int ups = 0, downs = 0;
    for (int t = 0; t < R; ++t) {
        int seen[D] = {0};
        for (int k = 0; k <= D; ++k)
            for (int j = 0; j < D; ++j) {
                const double x = u[(t * (D + 1) + k) * D + j];
                assert_true(x >= 0 && x <= 1);
                assert_close(x * (P - 1), round(x * (P - 1)), 1e-12);
            }
        for (int k = 0; k < D; ++k) {
            const double *a = u + (t * (D + 1) + k) * D, *b = a + D;
            int changed = 0;
            for (int j = 0; j < D; ++j)
                if (a[j] != b[j]) {
                    ++changed;
                    ++seen[j];
                    assert_close(fabs(b[j] - a[j]), delta, 1e-15);
                    ups += b[j] > a[j];
                    downs += b[j] < a[j];
                }
            assert_int_equal(changed, 1);
        }
        for (int j = 0; j < D; ++j)
            assert_int_equal(seen[j], 1);
    }
    assert_true(ups > R * D / 4 && downs > R * D / 4); /* both directions drawn */
    assert_int_equal(gf_design_morris(R, D, P, 7, w), GF_SUCCESS);
    assert_memory_equal(u, w, sizeof u);
    assert_int_equal(gf_design_morris(R, D, 3, 7, u), GF_EINVAL);
    assert_int_equal(gf_design_morris(0, D, P, 7, u), GF_EINVAL);
}

/* Elementary effects: on y = sum a_j u_j every effect is a_j, so mu = a_j,
 * mu* = |a_j| and sigma = 0 to 1e-12; an inert parameter has mu* = sigma =
 * 0 exactly; the interaction y = u0 u1 gives sigma > 0 to both and 0 to the
 * third; a bad trajectory and a NaN output are refused */
static void morris_effects_of_linear_and_inert_parameters(void **state)
{
    (void)state;
    enum { R = 12, D = 4, P = 6, M = 2, NP = R * (D + 1) };
    const double a[D] = {3.0, -2.0, 0.5, 0.0};
    double u[NP * D], y[NP * M], mu[M * D], mus[M * D], sg[M * D];
    assert_int_equal(gf_design_morris(R, D, P, 11, u), GF_SUCCESS);
    for (int i = 0; i < NP; ++i) {
        y[i * M] = 0;
        for (int j = 0; j < D; ++j)
            y[i * M] += a[j] * u[i * D + j];
        y[i * M + 1] = u[i * D] * u[i * D + 1] + 0.3 * u[i * D + 2];
    }
    assert_int_equal(gf_morris_effects(R, D, u, y, M, mu, mus, sg), GF_SUCCESS);
    for (int j = 0; j < D; ++j) {
        assert_close(mu[j], a[j], 1e-12);
        assert_close(mus[j], fabs(a[j]), 1e-12);
        assert_close(sg[j], 0.0, 1e-12);
    }
    assert_close(mus[3], 0.0, 0);
    assert_close(sg[3], 0.0, 0);
    /* the second output: u2 linear (0.3, no spread), u3 inert, u0 and u1 interacting */
    assert_close(mus[D + 2], 0.3, 1e-12);
    assert_close(sg[D + 2], 0.0, 1e-12);
    assert_close(mus[D + 3], 0.0, 0);
    assert_true(sg[D] > 0.05 && sg[D + 1] > 0.05);
    /* refusals */
    assert_int_equal(gf_morris_effects(1, D, u, y, M, mu, mus, sg), GF_EINVAL);
    double bad[NP * D];
    memcpy(bad, u, sizeof bad);
    bad[1 * D + 0] += 0.1, bad[1 * D + 1] += 0.1; /* a step that changes two coordinates */
    bad[1 * D + 2] += 0.1, bad[1 * D + 3] += 0.1;
    assert_int_equal(gf_morris_effects(R, D, bad, y, M, mu, mus, sg), GF_EDOM);
    y[5] = NAN;
    assert_int_equal(gf_morris_effects(R, D, u, y, M, mu, mus, sg), GF_ENONFINITE);
}

/* Outline scores on a 4 x 4 raster of 5 m cells (25 m2), threshold 1:
 *   sim      0 2 3 0    observed  0 1 1 0    valid: all but (3,3)
 *            0 5 N 1              0 1 1 1    N = NaN (not reached);
 *            0 4 2 0              0 0 1 0    1 is not > 1
 *            0 0 0 7              0 0 0 1
 * TP = (0,1) (0,2) (1,1) (2,2) = 4 cells, FP = (2,1) = 1, FN = (1,2) (1,3) = 2;
 * (3,3) is NODATA.  TP 100, FP 25, FN 50 m2; Jaccard 4/7; Dice (alpha = beta
 * = 1/2) 4/5.5 = 8/11; Tversky (0.2, 0.8) 4/5.8 */
static void outline_scores_on_hand_made_masks(void **state)
{
    (void)state;
    const double sim[16] = {0, 2, 3, 0, 0, 5, NAN, 1, 0, 4, 2, 0, 0, 0, 0, 7};
    const unsigned char obs[16] = {0, 1, 1, 0, 0, 1, 1, 1, 0, 0, 1, 0, 0, 0, 0, 1};
    unsigned char valid[16];
    memset(valid, 1, sizeof valid);
    valid[15] = 0;
    gf_outline_score s;
    assert_int_equal(gf_score_outline(16, sim, 1.0, obs, valid, 25.0, 1.0, 1.0, &s), GF_SUCCESS);
    assert_close(s.tp, 100.0, 0);
    assert_close(s.fp, 25.0, 0);
    assert_close(s.fn, 50.0, 0);
    assert_int_equal(s.n_valid, 15);
    assert_close(s.jaccard, 4.0 / 7.0, 1e-15);
    assert_close(s.tversky, 4.0 / 7.0, 1e-15);
    assert_int_equal(gf_score_outline(16, sim, 1.0, obs, valid, 25.0, 0.5, 0.5, &s), GF_SUCCESS);
    assert_close(s.tversky, 8.0 / 11.0, 1e-15);
    assert_int_equal(gf_score_outline(16, sim, 1.0, obs, valid, 25.0, 0.2, 0.8, &s), GF_SUCCESS);
    assert_close(s.tversky, 4.0 / 5.8, 1e-15);
    /* without the NODATA mask, (3,3) is a fifth true positive: Jaccard 5/8 */
    assert_int_equal(gf_score_outline(16, sim, 1.0, obs, NULL, 25.0, 1.0, 1.0, &s), GF_SUCCESS);
    assert_close(s.tp, 125.0, 0);
    assert_close(s.jaccard, 5.0 / 8.0, 1e-15);
    /* no overlap: Tversky 0 */
    const unsigned char far[16] = {1, 0};
    assert_int_equal(gf_score_outline(16, sim, 1.0, far, valid, 25.0, 0.5, 0.5, &s), GF_SUCCESS);
    assert_close(s.tversky, 0.0, 0);
    assert_close(s.jaccard, 0.0, 0);
    /* refusals */
    const unsigned char none[16] = {0};
    assert_int_equal(gf_score_outline(16, sim, 1.0, none, valid, 25.0, 1, 1, &s), GF_EDOM);
    assert_int_equal(gf_score_outline(16, sim, 1.0, obs, valid, 0.0, 1, 1, &s), GF_EDOM);
    assert_int_equal(gf_score_outline(16, sim, 1.0, obs, valid, 25.0, -0.1, 1, &s), GF_EDOM);
    assert_int_equal(gf_score_outline(16, sim, NAN, obs, valid, 25.0, 1, 1, &s), GF_ENONFINITE);
    assert_int_equal(gf_score_outline(0, sim, 1.0, obs, valid, 25.0, 1, 1, &s), GF_EINVAL);
    double inf_sim[16];
    memcpy(inf_sim, sim, sizeof inf_sim);
    inf_sim[0] = INFINITY;
    assert_int_equal(gf_score_outline(16, inf_sim, 1.0, obs, valid, 25.0, 1, 1, &s), GF_ENONFINITE);
}

/* The front along the path from an arrival-time map, by hand: cells at
 * s = 0, 5, .., 495 m on the path (l = 0) reached at s/10 s up to s = 400 m
 * (a front at 10 m/s that stops there), never beyond (NaN); one cell 500 m
 * off the path at s = 1000 m reached at 0 s (outside a 300 m half width: not
 * the front).  Front at 20 s: 200 m; at 0.05 s: 0 m; at 60 s: 400 m; speed
 * at 20 s (window 2 s): (220 - 180)/4 = 10 m/s; at 1 s: (30 - 0)/3 = 10
 * (one-sided from 0); at 60 s: 0 (stopped); before the start: NaN.  The
 * loss's front speed term: speed RMSE 2 m/s at scale 4 m/s (weight 2) with
 * the position RMSE 10 m at scale 20 m (weight 1): (0.5 + 2 * 0.5)/3 = 0.5. */
static void front_position_and_speed_from_arrival_times(void **state)
{
    (void)state;
    enum { N = 101 };
    double ta[N], s[N], l[N], x;
    for (int i = 0; i < 100; ++i) {
        s[i] = 5.0 * i;
        l[i] = 0;
        ta[i] = s[i] <= 400 ? s[i] / 10 : NAN;
    }
    s[100] = 1000, l[100] = 500, ta[100] = 0;
    assert_int_equal(gf_front_position(N, ta, s, l, 300, 20, &x), GF_SUCCESS);
    assert_close(x, 200, 0);
    assert_int_equal(gf_front_position(N, ta, s, l, 300, 0.05, &x), GF_SUCCESS);
    assert_close(x, 0, 0);
    assert_int_equal(gf_front_position(N, ta, s, l, 300, 60, &x), GF_SUCCESS);
    assert_close(x, 400, 0);
    assert_int_equal(gf_front_position(N, ta, s, l, 600, 0, &x), GF_SUCCESS);
    assert_close(x, 1000, 0); /* the wider corridor takes the far cell */
    assert_int_equal(gf_front_position(N, ta, s, l, 300, -1, &x), GF_SUCCESS);
    assert_true(isnan(x));
    assert_int_equal(gf_front_speed(N, ta, s, l, 300, 20, 2, &x), GF_SUCCESS);
    assert_close(x, 10, 1e-12);
    assert_int_equal(gf_front_speed(N, ta, s, l, 300, 1, 2, &x), GF_SUCCESS);
    assert_close(x, 10, 1e-12);
    assert_int_equal(gf_front_speed(N, ta, s, l, 300, 60, 2, &x), GF_SUCCESS);
    assert_close(x, 0, 0);
    /* refusals */
    assert_int_equal(gf_front_position(0, ta, s, l, 300, 20, &x), GF_EINVAL);
    assert_int_equal(gf_front_position(N, NULL, s, l, 300, 20, &x), GF_EINVAL);
    assert_int_equal(gf_front_position(N, ta, s, l, 0, 20, &x), GF_EDOM);
    assert_int_equal(gf_front_position(N, ta, s, l, 300, NAN, &x), GF_EDOM);
    assert_int_equal(gf_front_speed(N, ta, s, l, 300, 20, 0, &x), GF_EDOM);

    gf_scores sc = {.runout_error = NAN, .tversky = NAN, .rmse = NAN, .series_rmse = 10, .speed_rmse = 2};
    gf_loss_weights w = {.series = 1, .series_scale = 20, .speed = 2, .speed_scale = 4};
    double L;
    assert_int_equal(gf_loss(&sc, &w, &L), GF_SUCCESS);
    assert_close(L, 0.5, 1e-15);
    sc.speed_rmse = -1;
    assert_int_equal(gf_loss(&sc, &w, &L), GF_EDOM);
    sc.speed_rmse = NAN; /* not observed: the position alone */
    assert_int_equal(gf_loss(&sc, &w, &L), GF_SUCCESS);
    assert_close(L, 0.5, 1e-15);
}

/* Deposit RMSE, runout error, series RMSE and the weighted loss, by hand:
 * sim (1, 2, 0, NaN), obs (1.5, 0, 0, 1): over the union (cells 0, 1, 3)
 * sqrt((0.25 + 4 + 1)/3) = sqrt(1.75); over the observed deposit (0, 3)
 * sqrt(0.625); runout 1554.3 - 1500 = 54.3 m; fronts (100, 210, 290) against
 * (100, 200, 300): sqrt(200/3); loss with runout error 50 m / scale 100 m
 * (weight 1), Tversky 0.8 (weight 2), no deposit observed, series weight 0:
 * (0.5 + 2 * 0.2)/3 = 0.3 */
static void deposit_runout_series_scores_and_the_loss(void **state)
{
    (void)state;
    const double hs[4] = {1, 2, 0, NAN}, ho[4] = {1.5, 0, 0, 1};
    double r;
    size_t c;
    assert_int_equal(gf_score_deposit_rmse(4, hs, ho, NULL, 0.0, GF_RMSE_UNION, &r, &c), GF_SUCCESS);
    assert_close(r, sqrt(1.75), 1e-15);
    assert_int_equal(c, 3);
    assert_int_equal(gf_score_deposit_rmse(4, hs, ho, NULL, 0.0, GF_RMSE_OBSERVED, &r, &c), GF_SUCCESS);
    assert_close(r, sqrt(0.625), 1e-15);
    assert_int_equal(c, 2);
    const unsigned char v[4] = {1, 1, 1, 0};
    assert_int_equal(gf_score_deposit_rmse(4, hs, ho, v, 0.0, GF_RMSE_OBSERVED, &r, NULL), GF_SUCCESS);
    assert_close(r, 0.5, 1e-15);
    const double zero[4] = {0};
    assert_int_equal(gf_score_deposit_rmse(4, zero, zero, NULL, 0.0, GF_RMSE_UNION, &r, &c), GF_EDOM);
    const double ho_nan[4] = {1.5, NAN, 0, 1};
    assert_int_equal(gf_score_deposit_rmse(4, hs, ho_nan, NULL, 0.0, GF_RMSE_UNION, &r, &c), GF_ENONFINITE);
    assert_int_equal(gf_score_deposit_rmse(4, hs, ho, NULL, 0.0, (gf_rmse_region)7, &r, &c), GF_EINVAL);

    double e;
    assert_int_equal(gf_score_runout(1554.3, 1500.0, &e), GF_SUCCESS);
    assert_close(e, 54.3, 1e-12);
    assert_int_equal(gf_score_runout(NAN, 1500.0, &e), GF_ENONFINITE);

    const double fs[3] = {100, 210, 290}, fo[3] = {100, 200, 300};
    assert_int_equal(gf_score_series_rmse(3, fs, fo, &r), GF_SUCCESS);
    assert_close(r, sqrt(200.0 / 3.0), 1e-12);
    assert_int_equal(gf_score_series_rmse(0, fs, fo, &r), GF_EINVAL);

    gf_scores s = {.runout_error = -50.0, .tversky = 0.8, .rmse = NAN, .series_rmse = 7.0};
    gf_loss_weights w = {.runout = 1, .runout_scale = 100, .outline = 2, .rmse = 1, .rmse_scale = 0.5,
                         .series = 0, .series_scale = 0};
    double L;
    assert_int_equal(gf_loss(&s, &w, &L), GF_SUCCESS);
    assert_close(L, 0.3, 1e-15);
    /* a perfect match is 0 */
    gf_scores p = {.runout_error = 0, .tversky = 1, .rmse = 0, .series_rmse = NAN};
    assert_int_equal(gf_loss(&p, &w, &L), GF_SUCCESS);
    assert_close(L, 0.0, 0);
    /* refusals: a weighted score without a scale, nothing observed and weighted, a negative weight */
    gf_loss_weights w0 = w;
    w0.runout_scale = 0;
    assert_int_equal(gf_loss(&s, &w0, &L), GF_EDOM);
    gf_scores none = {NAN, NAN, NAN, NAN, NAN};
    assert_int_equal(gf_loss(&none, &w, &L), GF_EDOM);
    w0 = w;
    w0.outline = -1;
    assert_int_equal(gf_loss(&s, &w0, &L), GF_EDOM);
    w0.outline = NAN;
    assert_int_equal(gf_loss(&s, &w0, &L), GF_ENONFINITE);
    s.tversky = 1.5;
    assert_int_equal(gf_loss(&s, &w, &L), GF_EDOM);
}

/* ------------------------------------------------------------------ */

typedef struct quad {
    double x0, y0; /* the unconstrained minimum */
    double floor;
    size_t calls;
    int fail_at; /* a failing evaluation (0: none) */
} quad;

/* (x - x0)^2 + 2 (y - y0)^2 + (x - x0)(y - y0) + floor, x, y in [0, 1] */
static gf_status quad_loss(const double *u, size_t d, void *ctx, double *loss)
{
    quad *q = ctx;
    assert_int_equal(d, 2);
    assert_true(u[0] >= 0 && u[0] <= 1 && u[1] >= 0 && u[1] <= 1); /* never outside the box */
    ++q->calls;
    if (q->fail_at && q->calls == (size_t)q->fail_at)
        return GF_EIO;
    const double a = u[0] - q->x0, b = u[1] - q->y0;
    *loss = a * a + 2 * b * b + a * b + q->floor;
    return GF_SUCCESS;
}

/* Nelder-Mead on the box: an interior minimum (0.3, 0.7) found to 1e-6 in
 * at most 300 evaluations; a minimum outside the box (1.4, -0.2) gives the
 * box's constrained minimum, the corner (1, 0), to 1e-6, the callback never
 * called outside the box; the budget of 10 stops it after exactly 10
 * evaluations; a failing member's status is returned with the 5 evaluations
 * before it */
static void nelder_mead_finds_the_minimum_inside_the_box(void **state)
{
    (void)state;
    const double u0[2] = {0.9, 0.1};
    quad q = {0.3, 0.7, 0.0, 0, 0};
    gf_simplex_result r;
    assert_int_equal(gf_refine_simplex(quad_loss, &q, 2, u0, 0.1, 1e-9, 300, &r), GF_SUCCESS);
    assert_true(r.converged);
    assert_true(r.n_evals <= 300);
    assert_int_equal(r.n_evals, q.calls);
    assert_close(r.u[r.best * 2], 0.3, 1e-6);
    assert_close(r.u[r.best * 2 + 1], 0.7, 1e-6);
    assert_close(r.loss[r.best], 0.0, 1e-11);
    printf("simplex: interior minimum in %zu evaluations, %zu iterations\n", r.n_evals, r.iterations);
    gf_simplex_result_free(&r);

    /* minimum outside: over the box, x = 1 (the gradient in x is negative
     * on the whole box) and y minimises 2 b^2 + a b with a = 1 - 1.4 = -0.4:
     * b = 0.1, y = -0.1 < 0, so y = 0: the corner (1, 0) */
    quad out = {1.4, -0.2, 0.0, 0, 0};
    const double u1[2] = {0.5, 0.5};
    assert_int_equal(gf_refine_simplex(quad_loss, &out, 2, u1, 0.1, 1e-9, 400, &r), GF_SUCCESS);
    assert_close(r.u[r.best * 2], 1.0, 1e-6);
    assert_close(r.u[r.best * 2 + 1], 0.0, 1e-6);
    for (size_t i = 0; i < r.n_evals; ++i)
        assert_true(r.u[2 * i] >= 0 && r.u[2 * i] <= 1 && r.u[2 * i + 1] >= 0 && r.u[2 * i + 1] <= 1);
    gf_simplex_result_free(&r);

    /* the budget */
    quad b = {0.3, 0.7, 0.0, 0, 0};
    assert_int_equal(gf_refine_simplex(quad_loss, &b, 2, u0, 0.1, 1e-12, 10, &r), GF_SUCCESS);
    assert_int_equal(r.n_evals, 10);
    assert_int_equal(b.calls, 10);
    assert_false(r.converged);
    gf_simplex_result_free(&r);

    /* a failing member */
    quad f = {0.3, 0.7, 0.0, 0, 6};
    assert_int_equal(gf_refine_simplex(quad_loss, &f, 2, u0, 0.1, 1e-9, 100, &r), GF_EIO);
    assert_int_equal(r.n_evals, 5);
    gf_simplex_result_free(&r);

    /* refusals */
    const double outside[2] = {1.2, 0.5};
    assert_int_equal(gf_refine_simplex(quad_loss, &q, 2, outside, 0.1, 1e-9, 100, &r), GF_EDOM);
    assert_int_equal(gf_refine_simplex(quad_loss, &q, 2, u0, 0.1, 1e-9, 2, &r), GF_EINVAL);
    assert_int_equal(gf_refine_simplex(quad_loss, &q, 2, u0, 0.0, 1e-9, 100, &r), GF_EDOM);
    assert_int_equal(gf_refine_simplex(NULL, &q, 2, u0, 0.1, 1e-9, 100, &r), GF_EINVAL);
}

/* ABC on a 1024-point Sobol design with a loss of known minimum
 * (0.4, 0.6), the distance sqrt(((x - 0.4)/0.1)^2 + ((y - 0.6)/0.2)^2): the
 * 90 % ranges cover the truth, narrow as the quantile shrinks from 0.2 to
 * 0.02, and y's is wider than x's (its scale is twice x's); along a tilted
 * valley |x - y| the accepted points correlate (> 0.9) */
static void abc_ranges_cover_the_truth_and_narrow(void **state)
{
    (void)state;
    enum { N = 1024 };
    double *u = malloc(N * 2 * sizeof *u), *L = malloc(N * sizeof *L);
    assert_non_null(u);
    assert_non_null(L);
    assert_int_equal(gf_design_sobol(N, 2, 0, u), GF_SUCCESS);
    for (int i = 0; i < N; ++i)
        L[i] = hypot((u[2 * i] - 0.4) / 0.1, (u[2 * i + 1] - 0.6) / 0.2);
    double width[2][2];
    const double quantile[2] = {0.2, 0.02};
    for (int k = 0; k < 2; ++k)
        for (int kernel = 0; kernel < 2; ++kernel) {
            gf_abc_result a;
            assert_int_equal(gf_abc_rejection(N, 2, u, L, quantile[k], (gf_abc_kernel)kernel, 0.9, &a), GF_SUCCESS);
            assert_true(a.n_accepted >= (size_t)(quantile[k] * N) && a.n_accepted <= (size_t)(quantile[k] * N) + 2);
            double sw = 0;
            for (int i = 0; i < N; ++i)
                sw += a.weight[i];
            assert_close(sw, 1.0, 1e-12);
            assert_true(a.lo[0] <= 0.4 && a.hi[0] >= 0.4);
            assert_true(a.lo[1] <= 0.6 && a.hi[1] >= 0.6);
            assert_close(a.median[0], 0.4, 0.05);
            assert_close(a.median[1], 0.6, 0.1);
            assert_close(a.corr[0], 1.0, 1e-12);
            assert_true(fabs(a.corr[1]) < 0.3);
            if (kernel == GF_ABC_UNIFORM) {
                width[k][0] = a.hi[0] - a.lo[0];
                width[k][1] = a.hi[1] - a.lo[1];
            }
            printf("ABC q %.2f %s: eps %.3f, %zu accepted, x [%.3f, %.3f], y [%.3f, %.3f]\n", quantile[k],
                   kernel ? "Epanechnikov" : "uniform", a.epsilon, a.n_accepted, a.lo[0], a.hi[0], a.lo[1], a.hi[1]);
            gf_abc_result_free(&a);
        }
    for (int j = 0; j < 2; ++j)
        assert_true(width[1][j] < 0.5 * width[0][j]);
    assert_true(width[0][1] > 1.5 * width[0][0]);
    /* a valley along x = y: the parameters trade off */
    for (int i = 0; i < N; ++i)
        L[i] = fabs(u[2 * i] - u[2 * i + 1]) + 0.05 * fabs(u[2 * i] + u[2 * i + 1] - 1.0);
    gf_abc_result a;
    assert_int_equal(gf_abc_rejection(N, 2, u, L, 0.05, GF_ABC_EPANECHNIKOV, 0.9, &a), GF_SUCCESS);
    assert_true(a.corr[1] > 0.9 && a.corr[2] > 0.9);
    gf_abc_result_free(&a);
    /* refusals */
    assert_int_equal(gf_abc_rejection(N, 2, u, L, 0.0, GF_ABC_UNIFORM, 0.9, &a), GF_EDOM);
    assert_int_equal(gf_abc_rejection(N, 2, u, L, 0.1, GF_ABC_UNIFORM, 1.0, &a), GF_EDOM);
    assert_int_equal(gf_abc_rejection(N, 2, u, L, 0.0005, GF_ABC_UNIFORM, 0.9, &a), GF_EDOM); /* 1 accepted */
    L[3] = -1;
    assert_int_equal(gf_abc_rejection(N, 2, u, L, 0.1, GF_ABC_UNIFORM, 0.9, &a), GF_EDOM);
    L[3] = NAN;
    assert_int_equal(gf_abc_rejection(N, 2, u, L, 0.1, GF_ABC_UNIFORM, 0.9, &a), GF_ENONFINITE);
    free(u);
    free(L);
}

/* angle between two 2D directions, in degrees, sign-blind */
static double angle_deg(const double *a, const double *b)
{
    const double c = fabs(a[0] * b[0] + a[1] * b[1]) / (hypot(a[0], a[1]) * hypot(b[0], b[1]));
    return acos(fmin(1.0, c)) * 180.0 / PI;
}

/* The emulator on L = (x - 2y)^2 + 0.01 y^2, x in [0, 4], y in [0, 2] (64
 * Sobol points): exact fit (R^2 = 1 to 1e-12, the emulator equal to the loss
 * to 1e-9), one ridge whose direction in
 * parameter units is (2, 1)/sqrt(5) within 1 deg (the unit-coordinate one is
 * (1, 1)/sqrt(2): the ranges convert it), the ridge point on the valley
 * x = 2y and the ridge line crossing the box from (0, 0) to (4, 2) (length
 * sqrt(20)); on the bowl (x - 0.3)^2 + 2 (y - 0.6)^2 no ridge, curvatures 4
 * and 2 and the minimum (0.3, 0.6) to 1e-9; a loss without a minimum and too
 * few points are refused */
static void emulator_reports_the_ridge_and_the_bowl(void **state)
{
    (void)state;
    enum { N = 64 };
    double u[N * 2], L[N];
    const double lo[2] = {0, 0}, hi[2] = {4, 2}, one[2] = {1, 1};
    assert_int_equal(gf_design_sobol(N, 2, 0, u), GF_SUCCESS);
    for (int i = 0; i < N; ++i) {
        const double x = 4 * u[2 * i], y = 2 * u[2 * i + 1];
        L[i] = (x - 2 * y) * (x - 2 * y) + 0.01 * y * y;
    }
    gf_emulator em;
    assert_int_equal(gf_emulator_fit(N, 2, u, L, 0, lo, hi, GF_RIDGE_FRACTION, &em), GF_SUCCESS);
    assert_close(em.r2, 1.0, 1e-12);
    assert_int_equal(em.n_ridge, 1);
    assert_false(em.ridge[0]);
    assert_true(em.ridge[1]);
    const double ridge_dir[2] = {2 / sqrt(5), 1 / sqrt(5)}, unit_dir[2] = {1 / sqrt(2), 1 / sqrt(2)};
    const double a = angle_deg(em.direction_param + 2, ridge_dir);
    printf("emulator: ridge direction (%.6f, %.6f), %.4f deg from (2, 1)/sqrt(5); curvatures %.4g, %.4g; "
           "ridge point (%.6f, %.6f), t [%.4f, %.4f]\n",
           em.direction_param[2], em.direction_param[3], a, em.curvature[0], em.curvature[1], em.ridge_point[0],
           em.ridge_point[1], em.ridge_t_min, em.ridge_t_max);
    assert_true(a < 1.0);
    assert_true(angle_deg(em.direction + 2, unit_dir) < 1.0);
    assert_true(em.curvature[1] < GF_RIDGE_FRACTION * em.curvature[0]);
    assert_close(em.ridge_point[0] - 2 * em.ridge_point[1], 0.0, 1e-3);
    assert_close(em.ridge_t_max - em.ridge_t_min, sqrt(20.0), 0.01);
    for (int i = 0; i < N; i += 7) /* the loss is quadratic: the emulator reproduces it */
        assert_close(gf_emulator_eval(&em, u + 2 * i), L[i], 1e-9);
    gf_emulator_free(&em);
    assert_true(isnan(gf_emulator_eval(&em, u)));

    for (int i = 0; i < N; ++i) {
        const double x = u[2 * i], y = u[2 * i + 1];
        L[i] = (x - 0.3) * (x - 0.3) + 2 * (y - 0.6) * (y - 0.6);
    }
    assert_int_equal(gf_emulator_fit(N, 2, u, L, 20, lo, one, GF_RIDGE_FRACTION, &em), GF_SUCCESS);
    assert_int_equal(em.n_ridge, 0);
    assert_close(em.curvature[0], 4.0, 1e-9);
    assert_close(em.curvature[1], 2.0, 1e-9);
    assert_close(fabs(em.direction[1]), 1.0, 1e-9); /* the stiffest direction: y */
    assert_close(em.ridge_point[0], 0.3, 1e-9);
    assert_close(em.ridge_point[1], 0.6, 1e-9);
    assert_close(em.ridge_t_min, 0.0, 0);
    gf_emulator_free(&em);

    /* a dome: no minimum to constrain anything */
    for (int i = 0; i < N; ++i)
        L[i] = 2.0 - u[2 * i] * u[2 * i] - u[2 * i + 1] * u[2 * i + 1];
    assert_int_equal(gf_emulator_fit(N, 2, u, L, 0, lo, one, GF_RIDGE_FRACTION, &em), GF_EDOM);
    assert_true(strstr(gf_error_detail(), "curvature") != NULL);
    assert_int_equal(gf_emulator_fit(5, 2, u, L, 0, lo, one, GF_RIDGE_FRACTION, &em), GF_EDOM);
    assert_int_equal(gf_emulator_fit(N, 2, u, L, 0, lo, one, 1.0, &em), GF_EDOM);
    const double empty_hi[2] = {0, 1};
    assert_int_equal(gf_emulator_fit(N, 2, u, L, 0, lo, empty_hi, 0.01, &em), GF_EDOM);
    /* points on a line: singular */
    double line[N * 2];
    for (int i = 0; i < N; ++i)
        line[2 * i] = line[2 * i + 1] = u[2 * i];
    assert_int_equal(gf_emulator_fit(N, 2, line, L, 0, lo, one, 0.01, &em), GF_EDOM);
}

/* Unreachable: a loss with a floor of 0.5 above the threshold 0.2 at every
 * design point (32 Sobol) and after the simplex refinement is unreachable,
 * the reason naming the loss; with floor 0 it is reachable; a Jaccard of at
 * most 0.5 against a bound of 0.7 is unreachable and named; a runout error
 * beyond its tolerance too */
static void unreachable_observation_is_reported(void **state)
{
    (void)state;
    enum { N = 32, B = 100 };
    double u[N * 2], L[N + B], J[N + B], R[N + B];
    assert_int_equal(gf_design_sobol(N, 2, 0, u), GF_SUCCESS);
    for (int floor_case = 0; floor_case < 2; ++floor_case) {
        quad q = {0.3, 0.7, floor_case ? 0.5 : 0.0, 0, 0};
        for (int i = 0; i < N; ++i)
            assert_int_equal(quad_loss(u + 2 * i, 2, &q, &L[i]), GF_SUCCESS);
        size_t best = 0;
        for (int i = 1; i < N; ++i)
            if (L[i] < L[best])
                best = (size_t)i;
        gf_simplex_result r;
        assert_int_equal(gf_refine_simplex(quad_loss, &q, 2, u + 2 * best, 0.05, 1e-6, B, &r), GF_SUCCESS);
        memcpy(L + N, r.loss, r.n_evals * sizeof *L);
        const size_t n = N + r.n_evals;
        gf_simplex_result_free(&r);
        gf_reach_criteria c = {.max_loss = 0.2, .min_jaccard = NAN, .runout_tolerance = NAN};
        gf_reach_result v;
        assert_int_equal(gf_reach_verdict(n, L, NULL, NULL, &c, &v), GF_SUCCESS);
        printf("%s\n", v.reason);
        if (floor_case) {
            assert_int_equal(v.verdict, GF_UNREACHABLE);
            assert_int_equal(v.n_meeting, 0);
            assert_true(strstr(v.reason, "unreachable") && strstr(v.reason, "loss"));
            assert_close(L[v.best], 0.5, 1e-9); /* the refinement reached the floor */
        } else {
            assert_int_equal(v.verdict, GF_REACHABLE);
            assert_true(v.n_meeting > 0);
        }
    }
    /* outline and runout criteria */
    for (int i = 0; i < N; ++i) {
        L[i] = 0.1 + 0.01 * i;
        J[i] = 0.5 * i / (N - 1.0);
        R[i] = 60.5 - 3.0 * i; /* |error| <= 20 m for i = 14 .. 26, >= 0.5 m */
    }
    gf_reach_criteria cj = {.max_loss = NAN, .min_jaccard = 0.7, .runout_tolerance = NAN};
    gf_reach_result v;
    assert_int_equal(gf_reach_verdict(N, L, J, R, &cj, &v), GF_SUCCESS);
    assert_int_equal(v.verdict, GF_UNREACHABLE);
    assert_true(strstr(v.reason, "Jaccard") != NULL);
    gf_reach_criteria cr = {.max_loss = NAN, .min_jaccard = NAN, .runout_tolerance = 20.0};
    assert_int_equal(gf_reach_verdict(N, L, J, R, &cr, &v), GF_SUCCESS);
    assert_int_equal(v.verdict, GF_REACHABLE);
    assert_int_equal(v.n_meeting, 13);
    cr.runout_tolerance = 0.4; /* errors 60.5 - 3 i: at best 0.5 m */
    assert_int_equal(gf_reach_verdict(N, L, J, R, &cr, &v), GF_SUCCESS);
    assert_int_equal(v.verdict, GF_UNREACHABLE);
    assert_true(strstr(v.reason, "runout") != NULL);
    /* refusals */
    gf_reach_criteria cn = {NAN, NAN, NAN};
    assert_int_equal(gf_reach_verdict(N, L, J, R, &cn, &v), GF_EINVAL);
    assert_int_equal(gf_reach_verdict(N, L, NULL, R, &cj, &v), GF_EINVAL);
    gf_reach_criteria neg = {NAN, NAN, -1.0};
    assert_int_equal(gf_reach_verdict(N, L, J, R, &neg, &v), GF_EDOM);
    L[4] = NAN;
    assert_int_equal(gf_reach_verdict(N, L, J, R, &cr, &v), GF_ENONFINITE);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(sobol_design_is_the_sobol_sequence_and_stratified),
        cmocka_unit_test(morris_trajectories_step_delta_on_the_grid),
        cmocka_unit_test(morris_effects_of_linear_and_inert_parameters),
        cmocka_unit_test(outline_scores_on_hand_made_masks),
        cmocka_unit_test(deposit_runout_series_scores_and_the_loss),
        cmocka_unit_test(front_position_and_speed_from_arrival_times),
        cmocka_unit_test(nelder_mead_finds_the_minimum_inside_the_box),
        cmocka_unit_test(abc_ranges_cover_the_truth_and_narrow),
        cmocka_unit_test(emulator_reports_the_ridge_and_the_bowl),
        cmocka_unit_test(unreachable_observation_is_reported),
    };
    return gf_run_tests("calibration", tests, NULL, NULL);
}
