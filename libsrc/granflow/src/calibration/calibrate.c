/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The calibration's runs: design, Morris trajectories, simplex refinements,
 * with several evaluations at once (granflow/calibration.h;
 * doc/theory/calibration.md, section 5). */
#include "granflow/calibration.h"
#include "internal.h"

#include <gsl/gsl_errno.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

size_t gf_calib_refine_index(const gf_calib_plan *plan, size_t k, size_t j)
{
    const size_t nm = plan->morris_r ? plan->morris_r * (plan->d + 1) : 0;
    return plan->n_sobol + nm + k * plan->refine_evals + j;
}

size_t gf_calib_explore_index(const gf_calib_plan *plan, size_t j)
{
    return gf_calib_refine_index(plan, plan->n_starts, 0) + j;
}

void gf_calib_run_free(gf_calib_run *run)
{
    if (!run)
        return;
    free(run->u);
    free(run->ev);
    free(run->phase);
    free(run->start);
    free(run->converged);
    memset(run, 0, sizeof *run);
}

/* shared by the threads */
typedef struct shared {
    const gf_calib_plan *plan;
    gf_calib_evaluate f;
    void *ctx;
    gf_calib_run *run;
    pthread_mutex_t lock;
    size_t next;         /* the design's next index */
    size_t design_end;
    gf_status status;    /* the first error */
    char detail[1024];
    /* refinements */
    size_t next_start, n_starts;
    const size_t *starts; /* the design indices the refinements start from */
} shared;

static void record_error(shared *s, gf_status st)
{
    pthread_mutex_lock(&s->lock);
    if (!s->status) {
        s->status = st;
        snprintf(s->detail, sizeof s->detail, "%s", gf_error_detail());
    }
    pthread_mutex_unlock(&s->lock);
}

static int stopped(shared *s)
{
    pthread_mutex_lock(&s->lock);
    const int r = s->status != GF_SUCCESS;
    pthread_mutex_unlock(&s->lock);
    return r;
}

static gf_status evaluate(shared *s, size_t index)
{
    gf_calib_run *run = s->run;
    gf_calib_eval e = {0, NAN, {NAN, NAN, NAN, NAN, NAN}, NAN, 0};
    const gf_status st = s->f(index, run->u + index * run->d, run->d, s->ctx, &e);
    if (st)
        return st;
    if (!e.ok) {
        e.loss = NAN;
        e.accepted = 0;
    }
    else if (!isfinite(e.loss) || e.loss < 0)
        return gf_fail(GF_ENONFINITE, "calibration: evaluation %zu returned loss %g (a failed member is ok = 0)",
                       index, e.loss);
    run->ev[index] = e;
    return GF_SUCCESS;
}

static void *design_thread(void *arg)
{
    shared *s = arg;
    for (;;) {
        pthread_mutex_lock(&s->lock);
        const size_t i = s->next++;
        const int stop = s->status != GF_SUCCESS || i >= s->design_end;
        pthread_mutex_unlock(&s->lock);
        if (stop)
            return NULL;
        const gf_status st = evaluate(s, i);
        if (st) {
            record_error(s, st);
            return NULL;
        }
    }
}

typedef struct refine_ctx {
    shared *s;
    size_t k, j; /* the refinement, its evaluations so far */
} refine_ctx;

static gf_status refine_objective(const double *u, size_t d, void *arg, double *loss)
{
    refine_ctx *r = arg;
    shared *s = r->s;
    if (stopped(s))
        return GF_EINVAL; /* another thread's error ends this refinement too */
    const size_t index = gf_calib_refine_index(s->plan, r->k, r->j++);
    memcpy(s->run->u + index * d, u, d * sizeof *u);
    const gf_status st = evaluate(s, index);
    if (st) {
        record_error(s, st);
        return st;
    }
    *loss = s->run->ev[index].ok ? s->run->ev[index].loss : s->plan->failed_loss;
    return GF_SUCCESS;
}

static void *refine_thread(void *arg)
{
    shared *s = arg;
    const size_t d = s->plan->d;
    for (;;) {
        pthread_mutex_lock(&s->lock);
        const size_t k = s->next_start++;
        const int stop = s->status != GF_SUCCESS || k >= s->n_starts;
        pthread_mutex_unlock(&s->lock);
        if (stop)
            return NULL;
        refine_ctx r = {s, k, 0};
        gf_simplex_result res;
        const gf_status st =
            gf_refine_simplex(refine_objective, &r, d, s->run->u + s->starts[k] * d, s->plan->step, s->plan->tol,
                              s->plan->refine_evals, &res);
        if (st == GF_SUCCESS || st == GF_ENOCONV) {
            s->run->converged[k] = res.converged;
        } else if (!stopped(s)) {
            record_error(s, st);
        }
        gf_simplex_result_free(&res);
    }
}

static gf_status run_threads(shared *s, void *(*fn)(void *), size_t nthreads)
{
    pthread_t *t = calloc(nthreads, sizeof *t);
    if (!t)
        return gf_fail(GF_ENOMEM, "calibration: out of memory");
    size_t started = 0;
    for (; started < nthreads; ++started)
        if (pthread_create(&t[started], NULL, fn, s) != 0)
            break;
    for (size_t i = 0; i < started; ++i)
        pthread_join(t[i], NULL);
    free(t);
    if (started == 0)
        return gf_fail(GF_ENOMEM, "calibration: cannot start a thread");
    if (s->status)
        return gf_fail(s->status, "%s", s->detail);
    return GF_SUCCESS;
}

gf_status gf_calibrate_run(const gf_calib_plan *plan, gf_calib_evaluate f, void *ctx, gf_calib_run *run)
{
    if (!plan || !f || !run)
        return gf_fail(GF_EINVAL, "calibration: a NULL argument");
    memset(run, 0, sizeof *run);
    const size_t d = plan->d;
    if (d < 1 || d > GF_SOBOL_MAX_DIM)
        return gf_fail(GF_EINVAL, "calibration: %zu parameters (allowed 1..%d)", d, GF_SOBOL_MAX_DIM);
    if (plan->n_sobol < 1 || plan->n_sobol > 1000000)
        return gf_fail(GF_EDOM, "calibration: %zu design points (allowed 1..1e6)", plan->n_sobol);
    if (plan->morris_r == 1 || plan->morris_r > 10000)
        return gf_fail(GF_EDOM, "calibration: %zu Morris trajectories (allowed 0, or 2..10000)", plan->morris_r);
    if (plan->morris_r && (plan->morris_p < 2 || plan->morris_p % 2))
        return gf_fail(GF_EDOM, "calibration: Morris levels %zu (an even number >= 2)", plan->morris_p);
    if (plan->n_starts > 1000 || (plan->n_starts && plan->refine_evals < d + 1))
        return gf_fail(GF_EDOM, "calibration: %zu refinements of %zu evaluations (at most 1000 refinements, each of "
                                "at least d + 1 = %zu evaluations)",
                       plan->n_starts, plan->refine_evals, d + 1);
    if (plan->n_starts &&
        (!(plan->step > 0 && plan->step <= 1) || !(plan->tol > 0) || !isfinite(plan->tol) ||
         !(plan->failed_loss > 0) || !isfinite(plan->failed_loss)))
        return gf_fail(GF_EDOM, "calibration: simplex step %g (allowed (0, 1]), tolerance %g (> 0), failed-member "
                                "loss %g (> 0, finite)",
                       plan->step, plan->tol, plan->failed_loss);
    if (plan->n_explore > 1000000 || !(plan->explore_margin >= 0) || !isfinite(plan->explore_margin) ||
        (plan->n_explore && (plan->explore_rounds < 1 || plan->explore_rounds > 100)))
        return gf_fail(GF_EDOM,
                       "calibration: %zu exploration points (at most 1e6) in %zu rounds (1..100), margin %g (>= 0, "
                       "finite)",
                       plan->n_explore, plan->explore_rounds, plan->explore_margin);
    if (plan->threads < 1 || plan->threads > 256)
        return gf_fail(GF_EDOM, "calibration: %zu threads (allowed 1..256)", plan->threads);

    const size_t nm = plan->morris_r ? plan->morris_r * (d + 1) : 0;
    const size_t rounds = plan->n_explore ? plan->explore_rounds : 0;
    const size_t n = plan->n_sobol + nm + plan->n_starts * plan->refine_evals + rounds * plan->n_explore;
    run->d = d;
    run->n = n;
    run->n_sobol = plan->n_sobol;
    run->n_morris = nm;
    run->n_starts = plan->n_starts;
    run->n_explore = plan->n_explore;
    run->explore_rounds = 0;
    run->u = calloc(n * d, sizeof *run->u);
    run->ev = calloc(n, sizeof *run->ev);
    run->phase = calloc(n, sizeof *run->phase);
    run->start = calloc(n, sizeof *run->start);
    run->converged = calloc(plan->n_starts + 1, sizeof *run->converged);
    size_t *starts = calloc(plan->n_starts + 1, sizeof *starts);
    if (!run->u || !run->ev || !run->phase || !run->start || !run->converged || !starts) {
        free(starts);
        gf_calib_run_free(run);
        return gf_fail(GF_ENOMEM, "calibration: out of memory (%zu evaluations)", n);
    }
    const size_t explore0 = gf_calib_explore_index(plan, 0);
    for (size_t i = 0; i < n; ++i) {
        run->ev[i] = (gf_calib_eval){0, NAN, {NAN, NAN, NAN, NAN, NAN}, NAN, 0};
        run->phase[i] = i < plan->n_sobol        ? GF_PHASE_SOBOL
                        : i < plan->n_sobol + nm ? GF_PHASE_MORRIS
                        : i < explore0           ? GF_PHASE_REFINE
                                                 : GF_PHASE_EXPLORE;
        run->start[i] = run->phase[i] == GF_PHASE_REFINE ? (int)((i - plan->n_sobol - nm) / plan->refine_evals) : -1;
    }
    gf_status st = gf_design_sobol(plan->n_sobol, d, 0, run->u);
    if (!st && nm)
        st = gf_design_morris(plan->morris_r, d, plan->morris_p, plan->seed, run->u + plan->n_sobol * d);
    if (st) {
        free(starts);
        return st;
    }
    /* GSL's error handler is global: off for the whole calibration (the
     * threads' simplexes would otherwise switch it under each other) */
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    shared s = {.plan = plan, .f = f, .ctx = ctx, .run = run, .next = 0, .design_end = plan->n_sobol + nm,
                .status = GF_SUCCESS, .starts = starts};
    pthread_mutex_init(&s.lock, NULL);
    st = run_threads(&s, design_thread, plan->threads);
    if (!st && plan->n_starts) {
        /* the starts: the best successful design points, apart from each other */
        size_t ns = 0;
        for (size_t k = 0; k < plan->n_starts; ++k) {
            size_t best = (size_t)-1;
            for (size_t i = 0; i < s.design_end; ++i) {
                if (!run->ev[i].ok)
                    continue;
                int taken = 0;
                for (size_t q = 0; q < ns && !taken; ++q) {
                    double dist2 = 0;
                    for (size_t j = 0; j < d; ++j) {
                        const double du = run->u[i * d + j] - run->u[starts[q] * d + j];
                        dist2 += du * du;
                    }
                    taken = dist2 <= 4 * plan->tol * plan->tol;
                }
                if (!taken && (best == (size_t)-1 || run->ev[i].loss < run->ev[best].loss))
                    best = i;
            }
            if (best == (size_t)-1)
                break;
            starts[ns++] = best;
        }
        if (ns == 0) {
            st = gf_fail(GF_EDOM, "calibration: every one of the %zu design members failed: nothing to refine from",
                         s.design_end);
        } else {
            s.n_starts = ns;
            s.next_start = 0;
            st = run_threads(&s, refine_thread, plan->threads < ns ? plan->threads : ns);
        }
    }
    for (size_t round = 0; !st && round < rounds; ++round) {
        /* the box of the accepted evaluations so far (around the best one
         * when none is accepted), widened; a Sobol design in it */
        double *lo = run->explore_box, *hi = run->explore_box + GF_SOBOL_MAX_DIM;
        double prev[2 * GF_SOBOL_MAX_DIM];
        memcpy(prev, run->explore_box, sizeof prev);
        const size_t first = explore0 + round * plan->n_explore;
        size_t nacc = 0, best = (size_t)-1;
        for (size_t j = 0; j < d; ++j)
            lo[j] = INFINITY, hi[j] = -INFINITY;
        for (size_t i = 0; i < first; ++i) {
            if (!run->ev[i].ok)
                continue;
            if (best == (size_t)-1 || run->ev[i].loss < run->ev[best].loss)
                best = i;
            if (!run->ev[i].accepted)
                continue;
            ++nacc;
            for (size_t j = 0; j < d; ++j) {
                lo[j] = fmin(lo[j], run->u[i * d + j]);
                hi[j] = fmax(hi[j], run->u[i * d + j]);
            }
        }
        if (best == (size_t)-1) {
            st = gf_fail(GF_EDOM, "calibration: every member failed: nothing to explore around");
            break;
        }
        for (size_t j = 0; j < d; ++j) {
            if (!nacc)
                lo[j] = hi[j] = run->u[best * d + j];
            const double w = fmax(plan->explore_margin * (hi[j] - lo[j]), 2 * plan->step);
            lo[j] = fmax(0, lo[j] - w);
            hi[j] = fmin(1, hi[j] + w);
        }
        if (round > 0) { /* the last round did not widen the box: the accepted region is sampled */
            int grew = 0;
            for (size_t j = 0; j < d; ++j)
                grew |= lo[j] < prev[j] - plan->tol || hi[j] > prev[GF_SOBOL_MAX_DIM + j] + plan->tol;
            if (!grew) {
                memcpy(run->explore_box, prev, sizeof prev);
                break;
            }
        }
        /* Sobol points after the design's (another part of the sequence) */
        st = gf_design_sobol(plan->n_explore, d, plan->n_sobol + round * plan->n_explore, run->u + first * d);
        for (size_t i = 0; !st && i < plan->n_explore; ++i)
            for (size_t j = 0; j < d; ++j) {
                double *u = &run->u[(first + i) * d + j];
                *u = lo[j] + (hi[j] - lo[j]) * *u;
            }
        if (!st) {
            s.next = first;
            s.design_end = first + plan->n_explore;
            st = run_threads(&s, design_thread, plan->threads);
            run->explore_rounds = round + 1;
        }
    }
    pthread_mutex_destroy(&s.lock);
    gsl_set_error_handler(old);
    free(starts);
    return st;
}
