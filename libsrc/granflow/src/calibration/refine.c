/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Local refinement: GSL's Nelder-Mead simplex on the unit box, kept inside
 * by reflection (granflow/calibration.h; doc/theory/calibration.md,
 * section 3). */
#include "granflow/calibration.h"
#include "internal.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_multimin.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* z folded into [0, 1]: reflected at 0 and 1 (a triangle wave of period 2) */
static double fold(double z)
{
    double t = fmod(z, 2.0);
    if (t < 0)
        t += 2.0;
    return t <= 1.0 ? t : 2.0 - t;
}

typedef struct nm_ctx {
    gf_objective f;
    void *ctx;
    gf_simplex_result *res;
    size_t max_evals, cap;
    double *u;        /* [d] the folded point */
    gf_status status; /* first failure of f, or GF_ENOCONV once the budget is spent */
} nm_ctx;

static double nm_eval(const gsl_vector *z, void *params)
{
    nm_ctx *c = params;
    gf_simplex_result *r = c->res;
    const size_t d = r->d;
    if (c->status)
        return NAN; /* stops GSL's iteration: the result is the history's best */
    if (r->n_evals >= c->max_evals) {
        c->status = GF_ENOCONV;
        return NAN;
    }
    for (size_t j = 0; j < d; ++j)
        c->u[j] = fold(gsl_vector_get(z, j));
    double L = NAN;
    gf_status st = c->f(c->u, d, c->ctx, &L);
    if (!st && !isfinite(L))
        st = gf_fail(GF_ENONFINITE,
                     "simplex refinement: the objective returned loss %g at evaluation %zu (give a failed member a "
                     "large finite loss)",
                     L, r->n_evals);
    if (st) {
        c->status = st;
        return NAN;
    }
    memcpy(r->u + r->n_evals * d, c->u, d * sizeof *c->u);
    r->loss[r->n_evals] = L;
    if (L < r->loss[r->best])
        r->best = r->n_evals;
    ++r->n_evals;
    return L;
}

void gf_simplex_result_free(gf_simplex_result *res)
{
    if (!res)
        return;
    free(res->u);
    free(res->loss);
    res->u = res->loss = NULL;
    res->n_evals = 0;
}

gf_status gf_refine_simplex(gf_objective f, void *ctx, size_t d, const double *u0, double step,
                            double tol, size_t max_evals, gf_simplex_result *res)
{
    if (!res)
        return gf_fail(GF_EINVAL, "simplex refinement: res NULL");
    memset(res, 0, sizeof *res);
    if (d < 1 || !f || !u0)
        return gf_fail(GF_EINVAL, "simplex refinement: parameters d = %zu must be >= 1 (and f, u0 given)", d);
    if (max_evals < d + 1)
        return gf_fail(GF_EINVAL, "simplex refinement: budget max_evals = %zu below the initial simplex's d + 1 = %zu",
                       max_evals, d + 1);
    gf_status st;
    for (size_t j = 0; j < d; ++j)
        if ((st = gf_check_range("simplex refinement: start u0", u0[j], 0.0, 1.0)))
            return st;
    if ((st = gf_check_range("simplex refinement: step", step, 0.0, 1.0)))
        return st;
    if (step == 0)
        return gf_fail(GF_EDOM, "simplex refinement: step = 0: the initial simplex is a point");
    if (!isfinite(tol) || !(tol > 0))
        return gf_fail(isfinite(tol) ? GF_EDOM : GF_ENONFINITE, "simplex refinement: tolerance %g must be > 0", tol);
    res->d = d;
    res->u = malloc(max_evals * d * sizeof *res->u);
    res->loss = malloc(max_evals * sizeof *res->loss);
    double *u = malloc(d * sizeof *u);
    gsl_vector *x = gsl_vector_alloc(d), *ss = gsl_vector_alloc(d);
    gsl_multimin_fminimizer *m = gsl_multimin_fminimizer_alloc(gsl_multimin_fminimizer_nmsimplex2, d);
    nm_ctx c = {f, ctx, res, max_evals, max_evals, u, GF_SUCCESS};
    st = GF_SUCCESS;
    if (!res->u || !res->loss || !u || !x || !ss || !m)
        st = gf_fail(GF_ENOMEM, "simplex refinement: %zu evaluations of %zu parameters", max_evals, d);
    if (!st) {
        res->loss[0] = INFINITY; /* best index 0 until the first evaluation */
        for (size_t j = 0; j < d; ++j) {
            gsl_vector_set(x, j, u0[j]);
            gsl_vector_set(ss, j, step);
        }
        gsl_multimin_function fn = {nm_eval, d, &c};
        gsl_error_handler_t *old = gsl_set_error_handler_off();
        int gs = gsl_multimin_fminimizer_set(m, &fn, x, ss);
        while (!gs && !c.status) {
            gs = gsl_multimin_fminimizer_iterate(m);
            ++res->iterations;
            if (gs || c.status)
                break;
            if (gsl_multimin_test_size(gsl_multimin_fminimizer_size(m), tol) == GSL_SUCCESS) {
                res->converged = 1;
                break;
            }
        }
        gsl_set_error_handler(old);
        if (c.status && c.status != GF_ENOCONV)
            st = c.status; /* the callback's failure, its message recorded */
        else if (gs && !c.status)
            st = gf_fail(GF_EGSL, "simplex refinement: GSL's nmsimplex2 stopped: %s", gsl_strerror(gs));
    }
    free(u);
    gsl_vector_free(x);
    gsl_vector_free(ss);
    gsl_multimin_fminimizer_free(m);
    if (st && !res->n_evals)
        gf_simplex_result_free(res);
    return st;
}
