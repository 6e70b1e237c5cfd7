/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The calibration's runs (gf_calibrate_run, granflow/calibration.h section
 * "The calibration's runs"; doc/theory/calibration.md section 5) on
 * synthetic losses in unit coordinates instead of solver runs: the design is
 * GSL's Sobol sequence then gf_design_morris's trajectories, the
 * refinements start at the best successful design points and reach the
 * loss's minimum, each index is evaluated once and the run is the same bit
 * for bit with 1, 2 or 4 threads, the exploration's boxes and rounds follow
 * their rule (recomputed here from the run), a callback's error stops the
 * run with its detail, and bad plans are refused. */
#include "../gf_test.h"

#include <sched.h>
#include <stdatomic.h>

#include "granflow/calibration.h"

/* ------------------------------------------------------------------ */
/* A synthetic member: the loss, failures and errors by index or place  */
/* ------------------------------------------------------------------ */

enum { LOSS_BOWL = 0, LOSS_VALLEY = 1 };

typedef struct member_ctx {
    int kind;              /* LOSS_BOWL or LOSS_VALLEY */
    double c[4], s[4];     /* the bowl's centre and scales (d <= 4) */
    double eps;            /* accepted: loss <= eps */
    size_t fail_mod, fail_rem; /* fail_mod > 0: index % fail_mod == fail_rem fails (ok = 0) */
    size_t fail_index;     /* this index fails (SIZE_MAX: none) */
    double fail_above;     /* u_0 > fail_above fails (>= 1: none) */
    int all_fail;
    size_t error_at;       /* this index returns an error (SIZE_MAX: none) */
    int nonfinite_at_error; /* the error is a loss of NaN with ok = 1 instead */
    /* what the calls were: per index, counted from every thread */
    size_t cap, d;
    atomic_int *calls;
    double *seen_u;        /* [cap d] the u each index was called with */
    atomic_int out_of_range; /* an index >= cap, or a u outside [0, 1] */
    atomic_int concurrent, max_concurrent;
    /* a rendezvous: the first `meet` design evaluations, and the first
     * evaluations of the first `meet` refinements, wait (a bounded spin)
     * until `meet` of them are under way at once: the threads run together */
    size_t meet, refine0, refine_evals;
    atomic_int met_design, met_refine;
    /* this index waits until the error's evaluation has been called */
    size_t hold_index;
    atomic_int error_called;
} member_ctx;

/* the bowl: sum ((u_j - c_j) / s_j)^2, minimum 0 at c; the valley
 * (Rosenbrock-like, curved): x = 3 u_0 - 0.8, y = 3 u_1 - 1.1,
 * 10 (y - x^2)^2 + (1 - x)^2, minimum 0 at u = (0.6, 0.7) */
static double synthetic_loss(const member_ctx *m, const double *u, size_t d)
{
    if (m->kind == LOSS_VALLEY) {
        const double x = 3 * u[0] - 0.8, y = 3 * u[1] - 1.1;
        return 10 * (y - x * x) * (y - x * x) + (1 - x) * (1 - x);
    }
    double L = 0;
    for (size_t j = 0; j < d; ++j) {
        const double z = (u[j] - m->c[j]) / m->s[j];
        L += z * z;
    }
    return L;
}

static int member_fails(const member_ctx *m, size_t index, const double *u)
{
    return m->all_fail || (m->fail_mod && index % m->fail_mod == m->fail_rem) || index == m->fail_index ||
           u[0] > m->fail_above;
}

/* the status and detail a failing library call leaves (the callback's error) */
static gf_status failing_call(void)
{
    double u[GF_SOBOL_MAX_DIM + 1];
    return gf_design_sobol(1, GF_SOBOL_MAX_DIM + 1, 0, u); /* GF_EINVAL, its detail set */
}

static atomic_int gave_up; /* a rendezvous that failed: the others do not wait */

static void meet_others(const member_ctx *m, atomic_int *met)
{
    atomic_fetch_add(met, 1);
    for (long spin = 0; spin < 2000000L && !atomic_load(&gave_up) && atomic_load(met) < (int)m->meet; ++spin)
        sched_yield();
    if (atomic_load(met) < (int)m->meet)
        atomic_store(&gave_up, 1);
}

static gf_status evaluate(size_t index, const double *u, size_t d, void *ctx, gf_calib_eval *out)
{
    member_ctx *m = ctx;
    const int now = atomic_fetch_add(&m->concurrent, 1) + 1;
    int seen = atomic_load(&m->max_concurrent);
    while (now > seen && !atomic_compare_exchange_weak(&m->max_concurrent, &seen, now)) {
    }
    if (index < m->meet)
        meet_others(m, &m->met_design);
    else if (m->meet && index >= m->refine0 && (index - m->refine0) % m->refine_evals == 0 &&
             (index - m->refine0) / m->refine_evals < m->meet)
        meet_others(m, &m->met_refine);
    int bad = index >= m->cap || d != m->d;
    for (size_t j = 0; j < d; ++j)
        bad |= !(u[j] >= 0 && u[j] <= 1);
    if (bad) {
        atomic_store(&m->out_of_range, 1);
    } else {
        atomic_fetch_add(&m->calls[index], 1);
        memcpy(m->seen_u + index * d, u, d * sizeof *u);
    }
    if (index == m->hold_index) {
        for (long spin = 0; spin < 2000000L && !atomic_load(&m->error_called); ++spin)
            sched_yield();
        for (int k = 0; k < 200; ++k)
            sched_yield();
    }
    gf_status st = GF_SUCCESS;
    if (index == m->error_at && !m->nonfinite_at_error) {
        st = failing_call();
        atomic_store(&m->error_called, 1);
    } else if (index == m->error_at) {
        out->ok = 1, out->loss = NAN, out->accepted = 0;
    } else if (member_fails(m, index, u)) {
        /* a failed member: its loss and acceptance must be dropped by the run */
        out->ok = 0, out->loss = 0.25, out->accepted = 1;
    } else {
        out->ok = 1;
        out->loss = synthetic_loss(m, u, d);
        out->accepted = out->loss <= m->eps;
        out->jaccard = 1 - out->loss;
        out->scores.runout_error = (double)index;
    }
    atomic_fetch_sub(&m->concurrent, 1);
    return st;
}

static size_t plan_n(const gf_calib_plan *p)
{
    return p->n_sobol + (p->morris_r ? p->morris_r * (p->d + 1) : 0) + p->n_starts * p->refine_evals +
           (p->n_explore ? p->explore_rounds * p->n_explore : 0);
}

static void member_init(member_ctx *m, const gf_calib_plan *p, int kind, double eps)
{
    memset(m, 0, sizeof *m);
    m->kind = kind;
    const double c[4] = {0.3, 0.7, 0.45, 0.62}, s[4] = {1, 0.5, 2, 1};
    memcpy(m->c, c, sizeof c);
    memcpy(m->s, s, sizeof s);
    m->eps = eps;
    m->fail_index = SIZE_MAX;
    m->fail_above = 2;
    m->error_at = SIZE_MAX;
    m->hold_index = SIZE_MAX;
    m->d = p->d;
    m->cap = plan_n(p) + 16;
    m->calls = calloc(m->cap, sizeof *m->calls);
    m->seen_u = calloc(m->cap * (p->d ? p->d : 1), sizeof *m->seen_u);
    assert_non_null(m->calls);
    assert_non_null(m->seen_u);
    for (size_t i = 0; i < m->cap; ++i)
        atomic_init(&m->calls[i], 0);
    atomic_init(&m->out_of_range, 0);
    atomic_init(&m->concurrent, 0);
    atomic_init(&m->max_concurrent, 0);
    atomic_init(&m->met_design, 0);
    atomic_init(&m->met_refine, 0);
    atomic_init(&m->error_called, 0);
}

static void member_reset(member_ctx *m)
{
    for (size_t i = 0; i < m->cap; ++i)
        atomic_store(&m->calls[i], 0);
    memset(m->seen_u, 0, m->cap * m->d * sizeof *m->seen_u);
    atomic_store(&m->out_of_range, 0);
    atomic_store(&m->max_concurrent, 0);
    atomic_store(&m->met_design, 0);
    atomic_store(&m->met_refine, 0);
    atomic_store(&m->error_called, 0);
}

static void member_free(member_ctx *m)
{
    free(m->calls);
    free(m->seen_u);
}

static size_t total_calls(const member_ctx *m)
{
    size_t n = 0;
    for (size_t i = 0; i < m->cap; ++i)
        n += (size_t)atomic_load(&m->calls[i]);
    return n;
}

static gf_calib_plan base_plan(size_t d)
{
    gf_calib_plan p = {0};
    p.d = d;
    p.n_sobol = 16;
    p.morris_r = 0;
    p.morris_p = 4;
    p.seed = 2024;
    p.n_starts = 0;
    p.refine_evals = 60;
    p.step = 0.1;
    p.tol = 1e-4;
    p.failed_loss = 10;
    p.n_explore = 0;
    p.explore_rounds = 1;
    p.explore_margin = 0.25;
    p.threads = 2;
    return p;
}

/* ------------------------------------------------------------------ */
/* Checks every run gets                                                */
/* ------------------------------------------------------------------ */

static int unused(const gf_calib_eval *e)
{
    return e->ok == 0 && isnan(e->loss) && e->accepted == 0;
}

/* The run against the plan and the calls: the sizes and index ranges, the
 * phase and refinement of every index; every index evaluated at most once,
 * the design's and every exploration round's exactly once, each refinement's
 * a prefix of its indices; an index not evaluated is unused (ok 0, loss NAN);
 * each evaluation called with the u recorded in run and recorded as the
 * callback gave it (a failed member's loss and acceptance dropped).  The
 * evaluations made are returned. */
static size_t check_run(const gf_calib_plan *p, const member_ctx *m, const gf_calib_run *run)
{
    const size_t d = p->d, nm = p->morris_r ? p->morris_r * (d + 1) : 0;
    assert_int_equal(atomic_load(&m->out_of_range), 0);
    assert_int_equal(run->d, d);
    assert_int_equal(run->n, plan_n(p));
    assert_int_equal(run->n_sobol, p->n_sobol);
    assert_int_equal(run->n_morris, nm);
    assert_int_equal(run->n_starts, p->n_starts);
    assert_int_equal(run->n_explore, p->n_explore);
    assert_true(run->explore_rounds <= (p->n_explore ? p->explore_rounds : 0));
    const size_t explore0 = gf_calib_explore_index(p, 0);
    assert_int_equal(gf_calib_refine_index(p, 0, 0), p->n_sobol + nm);
    assert_int_equal(explore0, p->n_sobol + nm + p->n_starts * p->refine_evals);
    for (size_t i = run->n; i < m->cap; ++i)
        assert_int_equal(atomic_load(&m->calls[i]), 0);
    size_t made = 0;
    for (size_t i = 0; i < run->n; ++i) {
        const int calls = atomic_load(&m->calls[i]);
        assert_true(calls == 0 || calls == 1);
        made += (size_t)calls;
        const gf_calib_eval *e = &run->ev[i];
        if (i < p->n_sobol + nm) {
            assert_int_equal(run->phase[i], i < p->n_sobol ? GF_PHASE_SOBOL : GF_PHASE_MORRIS);
            assert_int_equal(run->start[i], -1);
        } else if (i < explore0) {
            const size_t k = (i - p->n_sobol - nm) / p->refine_evals, j = (i - p->n_sobol - nm) % p->refine_evals;
            assert_int_equal(gf_calib_refine_index(p, k, j), i);
            assert_int_equal(run->phase[i], GF_PHASE_REFINE);
            assert_int_equal(run->start[i], (int)k);
            if (j > 0 && calls) /* the refinement's evaluations: a prefix of its indices */
                assert_int_equal(atomic_load(&m->calls[i - 1]), 1);
        } else {
            assert_int_equal(gf_calib_explore_index(p, i - explore0), i);
            assert_int_equal(run->phase[i], GF_PHASE_EXPLORE);
            assert_int_equal(run->start[i], -1);
            /* the rounds run are evaluated whole, the others not at all */
            assert_int_equal(calls, (i - explore0) / p->n_explore < run->explore_rounds);
        }
        if (!calls) {
            assert_true(unused(e));
            continue;
        }
        assert_memory_equal(m->seen_u + i * d, run->u + i * d, d * sizeof(double));
        if (i == m->error_at)
            continue;
        if (member_fails(m, i, run->u + i * d)) {
            assert_true(unused(e)); /* ok 0, loss NAN, not accepted: the callback's 0.25 and 1 dropped */
        } else {
            const double L = synthetic_loss(m, run->u + i * d, d);
            assert_int_equal(e->ok, 1);
            assert_memory_equal(&e->loss, &L, sizeof L);
            assert_int_equal(e->accepted, L <= m->eps);
            assert_close(e->scores.runout_error, (double)i, 0);
        }
    }
    return made;
}

/* the design's part of the run: all evaluated */
static void check_design_evaluated(const gf_calib_plan *p, const member_ctx *m)
{
    const size_t nd = p->n_sobol + (p->morris_r ? p->morris_r * (p->d + 1) : 0);
    for (size_t i = 0; i < nd; ++i)
        assert_int_equal(atomic_load(&m->calls[i]), 1);
}

/* two runs the same bit for bit */
static void assert_runs_equal(const gf_calib_run *a, const gf_calib_run *b)
{
    assert_int_equal(a->n, b->n);
    assert_int_equal(a->d, b->d);
    assert_memory_equal(a->u, b->u, a->n * a->d * sizeof *a->u);
    for (size_t i = 0; i < a->n; ++i) {
        assert_int_equal(a->ev[i].ok, b->ev[i].ok);
        assert_memory_equal(&a->ev[i].loss, &b->ev[i].loss, sizeof(double));
        assert_int_equal(a->ev[i].accepted, b->ev[i].accepted);
        assert_memory_equal(&a->ev[i].jaccard, &b->ev[i].jaccard, sizeof(double));
    }
    assert_memory_equal(a->phase, b->phase, a->n * sizeof *a->phase);
    assert_memory_equal(a->start, b->start, a->n * sizeof *a->start);
    assert_memory_equal(a->converged, b->converged, a->n_starts * sizeof *a->converged);
    assert_int_equal(a->explore_rounds, b->explore_rounds);
    assert_memory_equal(a->explore_box, b->explore_box, sizeof a->explore_box);
}

/* The refinements' starts the rule gives: k-th, the design point of lowest
 * loss (the first index among equal ones) among the successful ones farther
 * than 2 tol from every start already taken.  Returns how many. */
static size_t expected_starts(const gf_calib_plan *p, const gf_calib_run *run, size_t *starts)
{
    const size_t d = p->d, nd = p->n_sobol + (p->morris_r ? p->morris_r * (d + 1) : 0);
    size_t ns = 0;
    for (size_t k = 0; k < p->n_starts; ++k) {
        size_t best = SIZE_MAX;
        for (size_t i = 0; i < nd; ++i) {
            if (!run->ev[i].ok)
                continue;
            int near = 0;
            for (size_t q = 0; q < ns; ++q) {
                double r2 = 0;
                for (size_t j = 0; j < d; ++j)
                    r2 += (run->u[i * d + j] - run->u[starts[q] * d + j]) *
                          (run->u[i * d + j] - run->u[starts[q] * d + j]);
                near |= r2 <= 4 * p->tol * p->tol;
            }
            if (!near && (best == SIZE_MAX || run->ev[i].loss < run->ev[best].loss))
                best = i;
        }
        if (best == SIZE_MAX)
            break;
        starts[ns++] = best;
    }
    return ns;
}

/* z reflected into [0, 1] (the simplex's fold) */
static double fold01(double z)
{
    double t = fmod(z, 2.0);
    if (t < 0)
        t += 2.0;
    return t <= 1.0 ? t : 2.0 - t;
}

/* Each refinement starts at its design point: its first evaluation there,
 * the next d at the start moved by step along each axis (GSL's initial
 * simplex, folded into the box). */
static void check_refinement_starts(const gf_calib_plan *p, const gf_calib_run *run, const member_ctx *m)
{
    const size_t d = p->d;
    size_t starts[64];
    assert_true(p->n_starts <= 64);
    const size_t ns = expected_starts(p, run, starts);
    for (size_t k = 0; k < p->n_starts; ++k) {
        const size_t i0 = gf_calib_refine_index(p, k, 0);
        if (k >= ns) { /* no start left: the refinement did not run */
            for (size_t j = 0; j < p->refine_evals; ++j)
                assert_int_equal(atomic_load(&m->calls[i0 + j]), 0);
            continue;
        }
        for (size_t j = 0; j <= d; ++j)
            assert_int_equal(atomic_load(&m->calls[i0 + j]), 1);
        assert_memory_equal(run->u + i0 * d, run->u + starts[k] * d, d * sizeof(double));
        for (size_t a = 0; a < d; ++a)
            for (size_t j = 0; j < d; ++j) {
                const double x = run->u[starts[k] * d + j];
                assert_close(run->u[(i0 + 1 + a) * d + j], j == a ? fold01(x + p->step) : x, 1e-15);
            }
    }
}

/* The exploration's box before the round whose first index is `first`:
 * around the accepted evaluations made before it (around the best one
 * when none is), widened by max(margin width, 2 step) each side, clipped to
 * [0, 1].  0 when no evaluation succeeded. */
static int expected_box(const gf_calib_plan *p, const gf_calib_run *run, size_t first, double *lo, double *hi)
{
    const size_t d = p->d;
    size_t best = SIZE_MAX, nacc = 0;
    for (size_t j = 0; j < d; ++j)
        lo[j] = INFINITY, hi[j] = -INFINITY;
    for (size_t i = 0; i < first; ++i) {
        if (!run->ev[i].ok)
            continue;
        if (best == SIZE_MAX || run->ev[i].loss < run->ev[best].loss)
            best = i;
        if (run->ev[i].accepted) {
            ++nacc;
            for (size_t j = 0; j < d; ++j) {
                lo[j] = fmin(lo[j], run->u[i * d + j]);
                hi[j] = fmax(hi[j], run->u[i * d + j]);
            }
        }
    }
    if (best == SIZE_MAX)
        return 0;
    for (size_t j = 0; j < d; ++j) {
        if (!nacc)
            lo[j] = hi[j] = run->u[best * d + j];
        const double w = fmax(p->explore_margin * (hi[j] - lo[j]), 2 * p->step);
        lo[j] = fmax(0, lo[j] - w);
        hi[j] = fmin(1, hi[j] + w);
    }
    return 1;
}

static int box_grew(size_t d, const double *lo, const double *hi, const double *plo, const double *phi, double tol)
{
    int grew = 0;
    for (size_t j = 0; j < d; ++j)
        grew |= lo[j] < plo[j] - tol || hi[j] > phi[j] + tol;
    return grew;
}

/* The exploration against its rule, recomputed from the run: each round's
 * box from the evaluations before it, its points a Sobol design (after the
 * design's and the earlier rounds' part of the sequence) mapped into the
 * box; every round after the first ran because the box grew by more than
 * tol, and the rounds stopped early only when it no longer did; the run's
 * box is the last round's, inside [0, 1], and holds every accepted
 * evaluation.  Returns the rounds run. */
static size_t check_exploration(const gf_calib_plan *p, const gf_calib_run *run)
{
    const size_t d = p->d, rounds = run->explore_rounds;
    double lo[GF_SOBOL_MAX_DIM], hi[GF_SOBOL_MAX_DIM], plo[GF_SOBOL_MAX_DIM], phi[GF_SOBOL_MAX_DIM];
    double *sob = malloc(p->n_explore * d * sizeof *sob);
    assert_non_null(sob);
    for (size_t r = 0; r < rounds; ++r) {
        const size_t first = gf_calib_explore_index(p, r * p->n_explore);
        assert_int_equal(expected_box(p, run, first, lo, hi), 1);
        if (r > 0)
            assert_true(box_grew(d, lo, hi, plo, phi, p->tol));
        assert_int_equal(gf_design_sobol(p->n_explore, d, p->n_sobol + r * p->n_explore, sob), GF_SUCCESS);
        for (size_t i = 0; i < p->n_explore; ++i)
            for (size_t j = 0; j < d; ++j) {
                const double x = run->u[(first + i) * d + j];
                assert_close(x, lo[j] + (hi[j] - lo[j]) * sob[i * d + j], 1e-15);
                assert_true(x >= lo[j] && x <= hi[j]);
            }
        memcpy(plo, lo, sizeof lo);
        memcpy(phi, hi, sizeof hi);
    }
    free(sob);
    if (rounds == 0)
        return 0;
    if (rounds < p->explore_rounds) { /* stopped early: the next box would not have grown */
        assert_int_equal(expected_box(p, run, gf_calib_explore_index(p, rounds * p->n_explore), lo, hi), 1);
        assert_false(box_grew(d, lo, hi, plo, phi, p->tol));
    }
    const double *blo = run->explore_box, *bhi = run->explore_box + GF_SOBOL_MAX_DIM;
    for (size_t j = 0; j < d; ++j) {
        assert_close(blo[j], plo[j], 0);
        assert_close(bhi[j], phi[j], 0);
        assert_true(0 <= blo[j] && blo[j] < bhi[j] && bhi[j] <= 1);
    }
    for (size_t i = 0; i < run->n; ++i)
        if (run->ev[i].accepted)
            for (size_t j = 0; j < d; ++j)
                assert_true(run->u[i * d + j] >= blo[j] && run->u[i * d + j] <= bhi[j]);
    return rounds;
}

/* ------------------------------------------------------------------ */
/* The cases                                                            */
/* ------------------------------------------------------------------ */

/* The design is GSL's Sobol sequence from its start, then the Morris
 * trajectories of gf_design_morris (r (d + 1) rows, the plan's seed), bit
 * for bit; each point evaluated once, recorded with its phase; with
 * neither refinements nor exploration nothing else is called */
static void design_is_sobol_then_morris(void **state)
{
    (void)state;
    gf_calib_plan p = base_plan(3);
    p.n_sobol = 21;
    p.morris_r = 4;
    p.morris_p = 6;
    p.seed = 77;
    member_ctx m;
    member_init(&m, &p, LOSS_BOWL, 0.05);
    m.fail_mod = 5, m.fail_rem = 2; /* some members fail: still the same design */
    gf_calib_run run;
    assert_int_equal(gf_calibrate_run(&p, evaluate, &m, &run), GF_SUCCESS);
    assert_int_equal(run.n, 21 + 4 * 4);
    assert_int_equal(check_run(&p, &m, &run), run.n);
    check_design_evaluated(&p, &m);
    double sob[21 * 3], mor[16 * 3];
    assert_int_equal(gf_design_sobol(21, 3, 0, sob), GF_SUCCESS);
    assert_int_equal(gf_design_morris(4, 3, 6, 77, mor), GF_SUCCESS);
    assert_memory_equal(run.u, sob, sizeof sob);
    assert_memory_equal(run.u + 21 * 3, mor, sizeof mor);
    assert_close(run.u[0], 0.5, 0); /* GSL's first point: the centre */
    /* another seed, other trajectories; the Sobol part unchanged */
    gf_calib_run other;
    p.seed = 78;
    member_reset(&m);
    assert_int_equal(gf_calibrate_run(&p, evaluate, &m, &other), GF_SUCCESS);
    assert_memory_equal(other.u, sob, sizeof sob);
    assert_memory_not_equal(other.u + 21 * 3, mor, sizeof mor);
    /* the failed members: ok 0 and loss NAN whatever the callback wrote */
    size_t failed = 0;
    for (size_t i = 0; i < run.n; ++i)
        failed += run.ev[i].ok == 0;
    assert_int_equal(failed, (run.n + 5 - 1 - 2) / 5);
    gf_calib_run_free(&other);
    gf_calib_run_free(&run);
    assert_null(run.u);
    member_free(&m);
}

/* Refinements from the best design points: the first evaluation of
 * refinement k is the design point of k-th lowest loss, the next d the
 * start moved by step along each axis; on the bowl (minimum at (0.3, 0.7,
 * 0.45)) every refinement converges to the minimum within 1e-3 in every
 * coordinate, loss below 1e-6; a design point that failed is never a
 * start, even with the lowest loss */
static void refinements_start_at_the_best_design_points_and_reach_the_minimum(void **state)
{
    (void)state;
    gf_calib_plan p = base_plan(3);
    p.n_sobol = 24;
    p.n_starts = 3;
    p.refine_evals = 200;
    p.tol = 1e-5;
    member_ctx m;
    member_init(&m, &p, LOSS_BOWL, 0.01);
    /* the design point of lowest loss fails */
    double sob[24 * 3];
    assert_int_equal(gf_design_sobol(24, 3, 0, sob), GF_SUCCESS);
    size_t best = 0;
    for (size_t i = 1; i < 24; ++i)
        if (synthetic_loss(&m, sob + i * 3, 3) < synthetic_loss(&m, sob + best * 3, 3))
            best = i;
    m.fail_index = best;
    gf_calib_run run;
    assert_int_equal(gf_calibrate_run(&p, evaluate, &m, &run), GF_SUCCESS);
    check_run(&p, &m, &run);
    check_design_evaluated(&p, &m);
    check_refinement_starts(&p, &run, &m);
    for (size_t k = 0; k < p.n_starts; ++k)
        assert_memory_not_equal(run.u + gf_calib_refine_index(&p, k, 0) * 3, sob + best * 3, 3 * sizeof(double));
    /* the start of the first refinement: the best successful design point */
    size_t second = best == 0 ? 1 : 0;
    for (size_t i = 0; i < 24; ++i)
        if (i != best && synthetic_loss(&m, sob + i * 3, 3) < synthetic_loss(&m, sob + second * 3, 3))
            second = i;
    assert_memory_equal(run.u + gf_calib_refine_index(&p, 0, 0) * 3, sob + second * 3, 3 * sizeof(double));
    for (size_t k = 0; k < p.n_starts; ++k) {
        assert_int_equal(run.converged[k], 1);
        size_t kb = SIZE_MAX;
        for (size_t j = 0; j < p.refine_evals; ++j) {
            const size_t i = gf_calib_refine_index(&p, k, j);
            if (run.ev[i].ok && (kb == SIZE_MAX || run.ev[i].loss < run.ev[kb].loss))
                kb = i;
        }
        assert_true(kb != SIZE_MAX);
        assert_true(run.ev[kb].loss < 1e-6);
        for (size_t j = 0; j < 3; ++j)
            assert_close(run.u[kb * 3 + j], m.c[j], 1e-3);
        /* converged before the budget: the rest of its indices unused */
        assert_true(unused(&run.ev[gf_calib_refine_index(&p, k, p.refine_evals - 1)]));
    }
    gf_calib_run_free(&run);
    member_free(&m);
}

/* Starts apart from each other: in one parameter, Morris trajectories on
 * the 4-level grid repeat their points, and the bowl's minimum sits on the
 * grid point 1/3: the starts are the distinct points of lowest loss (the
 * rule recomputed), each farther than 2 tol from the others; with fewer
 * distinct successful points than refinements, the extra refinements do not
 * run (their indices unused, converged 0) */
static void refinement_starts_are_distinct_points(void **state)
{
    (void)state;
    gf_calib_plan p = base_plan(1);
    p.n_sobol = 1;
    p.morris_r = 6;
    p.morris_p = 4;
    p.n_starts = 6;
    p.refine_evals = 40;
    p.tol = 1e-4;
    member_ctx m;
    member_init(&m, &p, LOSS_BOWL, 0.01);
    m.c[0] = 1.0 / 3.0;
    gf_calib_run run;
    assert_int_equal(gf_calibrate_run(&p, evaluate, &m, &run), GF_SUCCESS);
    check_run(&p, &m, &run);
    check_design_evaluated(&p, &m);
    check_refinement_starts(&p, &run, &m);
    /* the design's distinct points: 0.5 and the grid's four at most */
    size_t ran = 0;
    for (size_t k = 0; k < p.n_starts; ++k) {
        const size_t i0 = gf_calib_refine_index(&p, k, 0);
        if (!atomic_load(&m.calls[i0])) {
            assert_int_equal(run.converged[k], 0);
            for (size_t j = 0; j < p.refine_evals; ++j)
                assert_true(unused(&run.ev[i0 + j]));
            continue;
        }
        ++ran;
        for (size_t q = 0; q < k; ++q)
            assert_true(fabs(run.u[i0] - run.u[gf_calib_refine_index(&p, q, 0)]) > 2 * p.tol);
    }
    assert_true(ran >= 2 && ran <= 5);
    assert_close(run.u[gf_calib_refine_index(&p, 0, 0)], 1.0 / 3.0, 1e-15); /* the best: the grid point 1/3 */
    gf_calib_run_free(&run);
    member_free(&m);
}

/* The curved valley (minimum 0 at (0.6, 0.7), a Rosenbrock-like banana),
 * refinements whose simplex meets a failed member (the first refinement's
 * first step along u_0: it counts failed_loss) and members failing beyond
 * u_0 > 0.9: the best refinement evaluation lies within 2e-3 of the
 * minimum, loss below 1e-5, both refinements converged; no failed
 * evaluation is accepted */
static void refinements_follow_a_curved_valley_past_failed_members(void **state)
{
    (void)state;
    gf_calib_plan p = base_plan(2);
    p.n_sobol = 16;
    p.n_starts = 2;
    p.refine_evals = 300;
    p.tol = 1e-6;
    p.step = 0.15;
    p.threads = 2;
    member_ctx m;
    member_init(&m, &p, LOSS_VALLEY, 1e-3);
    m.fail_index = gf_calib_refine_index(&p, 0, 1);
    m.fail_above = 0.9;
    gf_calib_run run;
    assert_int_equal(gf_calibrate_run(&p, evaluate, &m, &run), GF_SUCCESS);
    check_run(&p, &m, &run);
    check_refinement_starts(&p, &run, &m);
    assert_int_equal(atomic_load(&m.calls[m.fail_index]), 1);
    assert_true(unused(&run.ev[m.fail_index]));
    size_t kb = SIZE_MAX, nfailed = 0;
    for (size_t i = gf_calib_refine_index(&p, 0, 0); i < run.n; ++i) {
        if (atomic_load(&m.calls[i]) && !run.ev[i].ok)
            ++nfailed;
        if (run.ev[i].ok && (kb == SIZE_MAX || run.ev[i].loss < run.ev[kb].loss))
            kb = i;
    }
    assert_true(kb != SIZE_MAX);
    assert_true(nfailed >= 1);
    assert_true(run.ev[kb].loss < 1e-5);
    assert_close(run.u[kb * 2], 0.6, 2e-3);
    assert_close(run.u[kb * 2 + 1], 0.7, 2e-3);
    assert_int_equal(run.converged[0], 1);
    assert_int_equal(run.converged[1], 1);
    for (size_t i = 0; i < run.n; ++i)
        if (run.ev[i].accepted)
            assert_true(run.ev[i].ok && run.u[i * 2] <= 0.9);
    print_message("valley: best refinement loss %.3g at (%.6f, %.6f), %zu failed refinement members\n",
                  run.ev[kb].loss, run.u[kb * 2], run.u[kb * 2 + 1], nfailed);
    gf_calib_run_free(&run);
    member_free(&m);
}

/* The same plan with 1, 2 and 4 threads: the same u, losses, acceptances,
 * phases, refinements' convergence and exploration box, bit for bit; every
 * index evaluated at most once (the design's and the exploration rounds'
 * exactly once), the same evaluations every time; the threads do evaluate
 * together (a rendezvous of the first design evaluations and of the
 * refinements' first ones: `threads` callbacks under way at once) and never
 * more than `threads` at once */
static void threads_give_the_same_run_bit_for_bit(void **state)
{
    (void)state;
    gf_calib_plan p = base_plan(2);
    p.n_sobol = 20;
    p.morris_r = 3;
    p.morris_p = 4;
    p.n_starts = 4;
    p.refine_evals = 40;
    p.tol = 1e-3;
    p.n_explore = 12;
    p.explore_rounds = 3;
    p.explore_margin = 0.5;
    p.step = 0.05;
    member_ctx m;
    member_init(&m, &p, LOSS_VALLEY, 0.3);
    m.fail_mod = 7, m.fail_rem = 3;
    gf_calib_run run[3];
    size_t made[3];
    const size_t threads[3] = {1, 2, 4};
    int max_concurrent[3];
    for (int t = 0; t < 3; ++t) {
        member_reset(&m);
        p.threads = threads[t];
        m.meet = threads[t];
        m.refine0 = gf_calib_refine_index(&p, 0, 0);
        m.refine_evals = p.refine_evals;
        assert_int_equal(gf_calibrate_run(&p, evaluate, &m, &run[t]), GF_SUCCESS);
        made[t] = check_run(&p, &m, &run[t]);
        assert_int_equal(total_calls(&m), made[t]);
        check_design_evaluated(&p, &m);
        check_refinement_starts(&p, &run[t], &m);
        check_exploration(&p, &run[t]);
        max_concurrent[t] = atomic_load(&m.max_concurrent);
        assert_int_equal(max_concurrent[t], (int)threads[t]);
        assert_int_equal(atomic_load(&m.met_design), (int)threads[t]);
        assert_int_equal(atomic_load(&m.met_refine), (int)threads[t]);
    }
    assert_runs_equal(&run[0], &run[1]);
    assert_runs_equal(&run[0], &run[2]);
    assert_int_equal(made[0], made[1]);
    assert_int_equal(made[0], made[2]);
    assert_true(run[0].explore_rounds >= 1);
    print_message("%zu evaluations of %zu indices, %zu exploration rounds\n", made[0], run[0].n,
                  run[0].explore_rounds);
    for (int t = 0; t < 3; ++t)
        gf_calib_run_free(&run[t]);
    member_free(&m);
}

/* The exploration: the box holds every accepted evaluation of the earlier
 * phases, lies in [0, 1], and its rounds follow the rule (recomputed);
 * a narrow accepted region found by the refinements widens over several
 * rounds; when everything is accepted the first box is the whole unit box,
 * the second would not grow, and the rounds stop after one of five (the
 * others' indices unused); with none accepted the box is around the best
 * evaluation */
static void exploration_box_holds_the_accepted_and_stops_when_it_no_longer_grows(void **state)
{
    (void)state;
    /* a narrow accepted bowl: several rounds */
    gf_calib_plan p = base_plan(2);
    p.n_sobol = 8;
    p.n_starts = 1;
    p.refine_evals = 60;
    p.tol = 1e-3;
    p.step = 0.02;
    p.n_explore = 16;
    p.explore_rounds = 6;
    p.explore_margin = 0.5;
    member_ctx m;
    member_init(&m, &p, LOSS_BOWL, 0.02);
    gf_calib_run run;
    assert_int_equal(gf_calibrate_run(&p, evaluate, &m, &run), GF_SUCCESS);
    check_run(&p, &m, &run);
    const size_t rounds = check_exploration(&p, &run);
    assert_true(rounds >= 2);
    /* the accepted of the design and refinement inside the first box */
    double lo[2], hi[2];
    const size_t explore0 = gf_calib_explore_index(&p, 0);
    assert_int_equal(expected_box(&p, &run, explore0, lo, hi), 1);
    size_t nacc = 0;
    for (size_t i = 0; i < explore0; ++i)
        if (run.ev[i].accepted) {
            ++nacc;
            for (size_t j = 0; j < 2; ++j)
                assert_true(run.u[i * 2 + j] >= lo[j] && run.u[i * 2 + j] <= hi[j]);
        }
    assert_true(nacc >= 1);
    /* the accepted bowl: |u_0 - 0.3| <= 0.141, |u_1 - 0.7| <= 0.0707; the
     * box reaches past it by its margin in u_1 (clipped to [0, 1]) */
    const double *blo = run.explore_box, *bhi = run.explore_box + GF_SOBOL_MAX_DIM;
    assert_true(blo[1] < 0.7 - 0.0707 && bhi[1] > 0.7 + 0.0707);
    print_message("narrow bowl: %zu rounds of %zu, box [%.4f, %.4f] x [%.4f, %.4f]\n", rounds, p.explore_rounds,
                  blo[0], bhi[0], blo[1], bhi[1]);
    gf_calib_run_free(&run);

    /* the bowl mirrored (centre (0.7, 0.3)): the box grows the other way */
    member_reset(&m);
    m.c[0] = 0.7, m.c[1] = 0.3;
    assert_int_equal(gf_calibrate_run(&p, evaluate, &m, &run), GF_SUCCESS);
    check_run(&p, &m, &run);
    assert_true(check_exploration(&p, &run) >= 2);
    gf_calib_run_free(&run);
    m.c[0] = 0.3, m.c[1] = 0.7;

    /* everything accepted: the whole box at once, one round of five */
    member_reset(&m);
    m.eps = 1e9;
    p.explore_rounds = 5;
    assert_int_equal(gf_calibrate_run(&p, evaluate, &m, &run), GF_SUCCESS);
    check_run(&p, &m, &run);
    assert_int_equal(check_exploration(&p, &run), 1);
    assert_int_equal(run.explore_rounds, 1);
    for (size_t j = 0; j < 2; ++j) {
        assert_close(run.explore_box[j], 0, 0);
        assert_close(run.explore_box[GF_SOBOL_MAX_DIM + j], 1, 0);
    }
    for (size_t i = gf_calib_explore_index(&p, p.n_explore); i < run.n; ++i) {
        assert_int_equal(atomic_load(&m.calls[i]), 0);
        assert_true(unused(&run.ev[i]));
    }
    gf_calib_run_free(&run);

    /* none accepted, no refinement: the box around the best design point,
     * 2 step each side */
    member_reset(&m);
    m.eps = -1;
    p.n_starts = 0;
    p.explore_rounds = 3;
    p.step = 0.05;
    assert_int_equal(gf_calibrate_run(&p, evaluate, &m, &run), GF_SUCCESS);
    check_run(&p, &m, &run);
    assert_true(check_exploration(&p, &run) >= 1);
    size_t b = 0;
    for (size_t i = 1; i < p.n_sobol; ++i)
        if (run.ev[i].loss < run.ev[b].loss)
            b = i;
    assert_int_equal(expected_box(&p, &run, p.n_sobol, lo, hi), 1);
    for (size_t j = 0; j < 2; ++j) {
        assert_close(lo[j], fmax(0, run.u[b * 2 + j] - 0.1), 1e-15);
        assert_close(hi[j], fmin(1, run.u[b * 2 + j] + 0.1), 1e-15);
    }
    gf_calib_run_free(&run);
    member_free(&m);
}

/* A callback's error in the design, a refinement or the exploration stops
 * the run and is returned with its detail (the failing call's, carried from
 * the evaluating thread to the caller's gf_error_detail); nothing of a later
 * phase is evaluated and no index twice; a loss that is not finite from a
 * member that says ok is GF_ENONFINITE naming its index */
static void callback_error_stops_the_run_with_its_detail(void **state)
{
    (void)state;
    assert_int_equal(failing_call(), GF_EINVAL);
    char want[1024];
    snprintf(want, sizeof want, "%s", gf_error_detail());
    assert_true(strlen(want) > 0);

    gf_calib_plan p = base_plan(2);
    p.n_sobol = 16;
    p.morris_r = 2;
    p.n_starts = 2;
    p.refine_evals = 30;
    p.n_explore = 8;
    p.explore_rounds = 2;
    p.threads = 2;
    p.tol = 1e-3;
    member_ctx m;
    member_init(&m, &p, LOSS_BOWL, 0.05);
    const size_t explore0 = gf_calib_explore_index(&p, 0);
    const size_t at[3] = {5, gf_calib_refine_index(&p, 1, 3), explore0 + 2};
    for (int c = 0; c < 3; ++c) {
        for (size_t threads = 1; threads <= 3; threads += 2) {
            member_reset(&m);
            m.error_at = at[c];
            p.threads = threads;
            gf_calib_run run;
            assert_int_equal(gf_calibrate_run(&p, evaluate, &m, &run), GF_EINVAL);
            assert_string_equal(gf_error_detail(), want);
            assert_int_equal(atomic_load(&m.calls[at[c]]), 1);
            for (size_t i = 0; i < run.n; ++i)
                assert_true(atomic_load(&m.calls[i]) <= 1);
            if (c == 0) /* in the design: no refinement nor exploration */
                for (size_t i = gf_calib_refine_index(&p, 0, 0); i < run.n; ++i)
                    assert_int_equal(atomic_load(&m.calls[i]), 0);
            if (c <= 1) /* no exploration */
                for (size_t i = explore0; i < run.n; ++i)
                    assert_int_equal(atomic_load(&m.calls[i]), 0);
            if (c == 2) /* the exploration's first round was started: the design was all done */
                check_design_evaluated(&p, &m);
            assert_true(unused(&run.ev[at[c]]));
            gf_calib_run_free(&run);
        }
    }
    /* an error in one refinement stops the other under way: refinement 0
     * (a budget of 200, never converged) holds at its 6th evaluation until
     * refinement 1's 4th has failed, then makes at most a few more */
    {
        gf_calib_plan q = p;
        q.threads = 2;
        q.refine_evals = 200;
        q.tol = 1e-300;
        member_ctx h;
        member_init(&h, &q, LOSS_BOWL, 0.05);
        h.error_at = gf_calib_refine_index(&q, 1, 3);
        h.hold_index = gf_calib_refine_index(&q, 0, 5);
        gf_calib_run run;
        assert_int_equal(gf_calibrate_run(&q, evaluate, &h, &run), GF_EINVAL);
        assert_string_equal(gf_error_detail(), want);
        assert_int_equal(atomic_load(&h.error_called), 1);
        size_t made0 = 0;
        for (size_t j = 0; j < q.refine_evals; ++j)
            made0 += (size_t)atomic_load(&h.calls[gf_calib_refine_index(&q, 0, j)]);
        assert_true(made0 >= 6 && made0 < 50);
        gf_calib_run_free(&run);
        member_free(&h);
    }
    /* ok with a NaN loss */
    member_reset(&m);
    m.error_at = 9;
    m.nonfinite_at_error = 1;
    gf_calib_run run;
    assert_int_equal(gf_calibrate_run(&p, evaluate, &m, &run), GF_ENONFINITE);
    assert_non_null(strstr(gf_error_detail(), "evaluation 9 "));
    gf_calib_run_free(&run);
    member_free(&m);
}

/* Bad plans are refused before any evaluation, with the documented statuses
 * and a detail; run left empty (freeing it is harmless) */
static void bad_plans_are_refused(void **state)
{
    (void)state;
    const gf_calib_plan good = base_plan(2);
    member_ctx m;
    member_init(&m, &good, LOSS_BOWL, 0.1);
    struct {
        const char *what;
        gf_calib_plan p;
        gf_status st;
    } bad[] = {
        {"d = 0", good, GF_EINVAL},
        {"d > GF_SOBOL_MAX_DIM", good, GF_EINVAL},
        {"no design point", good, GF_EDOM},
        {"one Morris trajectory", good, GF_EDOM},
        {"odd Morris levels", good, GF_EDOM},
        {"Morris levels 0", good, GF_EDOM},
        {"refine_evals < d + 1", good, GF_EDOM},
        {"simplex step 0", good, GF_EDOM},
        {"simplex step > 1", good, GF_EDOM},
        {"tolerance 0", good, GF_EDOM},
        {"failed_loss 0", good, GF_EDOM},
        {"failed_loss infinite", good, GF_EDOM},
        {"threads 0", good, GF_EDOM},
        {"explore_rounds 0 with n_explore > 0", good, GF_EDOM},
        {"negative explore_margin", good, GF_EDOM},
    };
    int c = 0;
    bad[c++].p.d = 0;
    bad[c++].p.d = GF_SOBOL_MAX_DIM + 1;
    bad[c++].p.n_sobol = 0;
    bad[c++].p.morris_r = 1;
    bad[c].p.morris_r = 2, bad[c++].p.morris_p = 5;
    bad[c].p.morris_r = 2, bad[c++].p.morris_p = 0;
    bad[c].p.n_starts = 1, bad[c++].p.refine_evals = 2;
    bad[c].p.n_starts = 1, bad[c++].p.step = 0;
    bad[c].p.n_starts = 1, bad[c++].p.step = 1.5;
    bad[c].p.n_starts = 1, bad[c++].p.tol = 0;
    bad[c].p.n_starts = 1, bad[c++].p.failed_loss = 0;
    bad[c].p.n_starts = 1, bad[c++].p.failed_loss = INFINITY;
    bad[c++].p.threads = 0;
    bad[c].p.n_explore = 4, bad[c++].p.explore_rounds = 0;
    bad[c].p.n_explore = 4, bad[c++].p.explore_margin = -0.1;
    assert_int_equal(c, sizeof bad / sizeof bad[0]);
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; ++k) {
        gf_calib_run run;
        memset(&run, 0xff, sizeof run);
        const gf_status st = gf_calibrate_run(&bad[k].p, evaluate, &m, &run);
        if (st != bad[k].st)
            print_error("%s: status %d, expected %d\n", bad[k].what, (int)st, (int)bad[k].st);
        assert_int_equal(st, bad[k].st);
        assert_true(strlen(gf_error_detail()) > 0);
        assert_int_equal(run.n, 0);
        assert_null(run.u);
        gf_calib_run_free(&run);
    }
    /* refine_evals = d + 1 and explore_rounds 0 without exploration are fine */
    gf_calib_plan p = good;
    p.n_starts = 1, p.refine_evals = 3;
    gf_calib_run run;
    assert_int_equal(gf_calibrate_run(&p, evaluate, &m, &run), GF_SUCCESS);
    assert_int_equal(total_calls(&m), 16 + 3);
    gf_calib_run_free(&run);
    /* NULL arguments */
    assert_int_equal(gf_calibrate_run(NULL, evaluate, &m, &run), GF_EINVAL);
    assert_int_equal(gf_calibrate_run(&good, NULL, &m, &run), GF_EINVAL);
    assert_int_equal(gf_calibrate_run(&good, evaluate, &m, NULL), GF_EINVAL);
    assert_int_equal(total_calls(&m), 16 + 3);
    member_free(&m);
}

/* Every member failed: nothing to refine from, nor to explore around
 * (GF_EDOM); the design was evaluated and every evaluation is ok 0; a
 * design of failures alone, without refinement or exploration, is a run */
static void all_members_failed_is_edom(void **state)
{
    (void)state;
    gf_calib_plan p = base_plan(2);
    p.morris_r = 2;
    p.n_starts = 2;
    member_ctx m;
    member_init(&m, &p, LOSS_BOWL, 0.1);
    m.all_fail = 1;
    gf_calib_run run;
    assert_int_equal(gf_calibrate_run(&p, evaluate, &m, &run), GF_EDOM);
    assert_non_null(strstr(gf_error_detail(), "failed"));
    check_run(&p, &m, &run);
    check_design_evaluated(&p, &m);
    assert_int_equal(total_calls(&m), 16 + 6);
    gf_calib_run_free(&run);

    member_reset(&m);
    p.n_starts = 0;
    p.n_explore = 4;
    p.explore_rounds = 2;
    assert_int_equal(gf_calibrate_run(&p, evaluate, &m, &run), GF_EDOM);
    assert_non_null(strstr(gf_error_detail(), "failed"));
    assert_int_equal(total_calls(&m), 16 + 6);
    assert_int_equal(run.explore_rounds, 0);
    gf_calib_run_free(&run);

    member_reset(&m);
    p.n_explore = 0;
    assert_int_equal(gf_calibrate_run(&p, evaluate, &m, &run), GF_SUCCESS);
    assert_int_equal(check_run(&p, &m, &run), 16 + 6);
    gf_calib_run_free(&run);
    member_free(&m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(design_is_sobol_then_morris),
        cmocka_unit_test(refinements_start_at_the_best_design_points_and_reach_the_minimum),
        cmocka_unit_test(refinement_starts_are_distinct_points),
        cmocka_unit_test(refinements_follow_a_curved_valley_past_failed_members),
        cmocka_unit_test(threads_give_the_same_run_bit_for_bit),
        cmocka_unit_test(exploration_box_holds_the_accepted_and_stops_when_it_no_longer_grows),
        cmocka_unit_test(callback_error_stops_the_run_with_its_detail),
        cmocka_unit_test(bad_plans_are_refused),
        cmocka_unit_test(all_members_failed_is_edom),
    };
    return gf_run_tests("calibrate_run", tests, NULL, NULL);
}
