/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Uncertainty and identifiability of the calibrated parameters: rejection
 * ABC on a design, the quadratic emulator of the loss and its ridge, the
 * reachability verdict (granflow/calibration.h; doc/theory/calibration.md,
 * section 4). */
#include "granflow/calibration.h"
#include "granflow/ensemble.h"
#include "internal.h"

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_multifit.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---------------------------------------------------------------- ABC */

typedef struct wv {
    double x, w;
} wv;

static int cmp_wv(const void *a, const void *b)
{
    const double x = ((const wv *)a)->x, y = ((const wv *)b)->x;
    return (x > y) - (x < y);
}

/* weighted percentile q in [0, 1] of v [k] sorted by x, weights summing to 1:
 * piecewise linear through (c_i, x_i), c_i = the cumulative weight up to the
 * middle of point i; constant beyond the first and last middles */
static double weighted_percentile(const wv *v, size_t k, double q)
{
    double c = 0, cprev = 0;
    for (size_t i = 0; i < k; ++i) {
        const double ci = c + 0.5 * v[i].w;
        if (q <= ci) {
            if (i == 0 || ci == cprev)
                return v[i].x;
            return v[i - 1].x + (q - cprev) / (ci - cprev) * (v[i].x - v[i - 1].x);
        }
        c += v[i].w;
        cprev = ci;
    }
    return v[k - 1].x;
}

void gf_abc_result_free(gf_abc_result *res)
{
    if (!res)
        return;
    free(res->weight);
    free(res->mean);
    free(res->lo);
    free(res->median);
    free(res->hi);
    free(res->corr);
    memset(res, 0, sizeof *res);
}

gf_status gf_abc_rejection(size_t n, size_t d, const double *u, const double *loss,
                           double quantile, gf_abc_kernel kernel, double level,
                           gf_abc_result *res)
{
    gf_status st;
    if (!res)
        return gf_fail(GF_EINVAL, "ABC: res NULL");
    memset(res, 0, sizeof *res);
    if (n < 2 || d < 1 || !u || !loss)
        return gf_fail(GF_EINVAL, "ABC: points n = %zu must be >= 2 and parameters d = %zu >= 1 (and u, loss given)",
                       n, d);
    if ((st = gf_check_range("ABC: quantile", quantile, 0.0, 1.0)))
        return st;
    if (quantile == 0)
        return gf_fail(GF_EDOM, "ABC: quantile = 0 accepts nothing; it must be in (0, 1]");
    if ((st = gf_check_range("ABC: credible level", level, 0.0, 1.0)))
        return st;
    if (level == 0 || level == 1)
        return gf_fail(GF_EDOM, "ABC: credible level %g must be in (0, 1)", level);
    if (kernel != GF_ABC_UNIFORM && kernel != GF_ABC_EPANECHNIKOV)
        return gf_fail(GF_EDOM, "ABC: kernel %d is neither GF_ABC_UNIFORM nor GF_ABC_EPANECHNIKOV", (int)kernel);
    for (size_t i = 0; i < n * d; ++i)
        if (!isfinite(u[i]))
            return gf_fail(GF_ENONFINITE, "ABC: coordinate %zu of point %zu is %g", i % d, i / d, u[i]);
    for (size_t i = 0; i < n; ++i) {
        if (!isfinite(loss[i]))
            return gf_fail(GF_ENONFINITE, "ABC: loss of point %zu is %g, not a finite number", i, loss[i]);
        if (loss[i] < 0)
            return gf_fail(GF_EDOM, "ABC: loss of point %zu is %g < 0 (the loss is a distance)", i, loss[i]);
    }
    double eps;
    if ((st = gf_percentile(loss, n, 100.0 * quantile, &eps)))
        return st;
    res->d = d;
    res->n = n;
    res->epsilon = eps;
    res->level = level;
    res->weight = calloc(n, sizeof *res->weight);
    res->mean = calloc(d, sizeof *res->mean);
    res->lo = calloc(d, sizeof *res->lo);
    res->median = calloc(d, sizeof *res->median);
    res->hi = calloc(d, sizeof *res->hi);
    res->corr = calloc(d * d, sizeof *res->corr);
    wv *v = malloc(n * sizeof *v);
    if (!res->weight || !res->mean || !res->lo || !res->median || !res->hi || !res->corr || !v) {
        free(v);
        gf_abc_result_free(res);
        return gf_fail(GF_ENOMEM, "ABC: %zu points of %zu parameters", n, d);
    }
    double sw = 0;
    size_t na = 0;
    for (size_t i = 0; i < n; ++i)
        if (loss[i] <= eps) {
            ++na;
            const double w = kernel == GF_ABC_EPANECHNIKOV && eps > 0 ? 1.0 - (loss[i] / eps) * (loss[i] / eps) : 1.0;
            res->weight[i] = w;
            sw += w;
        }
    res->n_accepted = na;
    if (na < 2) {
        free(v);
        gf_abc_result_free(res);
        return gf_fail(GF_EDOM, "ABC: %zu point(s) accepted at the %g quantile (loss <= %g); at least 2 are needed", na,
                       quantile, eps);
    }
    if (sw == 0) /* every accepted point at epsilon: equal weights */
        for (size_t i = 0; i < n; ++i)
            if (loss[i] <= eps) {
                res->weight[i] = 1.0;
                sw += 1.0;
            }
    for (size_t i = 0; i < n; ++i)
        res->weight[i] /= sw;
    for (size_t j = 0; j < d; ++j) {
        size_t k = 0;
        double m = 0;
        for (size_t i = 0; i < n; ++i)
            if (res->weight[i] > 0) {
                v[k].x = u[i * d + j];
                v[k++].w = res->weight[i];
                m += res->weight[i] * u[i * d + j];
            }
        res->mean[j] = m;
        qsort(v, k, sizeof *v, cmp_wv);
        res->lo[j] = weighted_percentile(v, k, 0.5 * (1.0 - level));
        res->median[j] = weighted_percentile(v, k, 0.5);
        res->hi[j] = weighted_percentile(v, k, 0.5 * (1.0 + level));
    }
    for (size_t j = 0; j < d; ++j)
        for (size_t l = 0; l < d; ++l) {
            double cjl = 0, cjj = 0, cll = 0;
            for (size_t i = 0; i < n; ++i) {
                const double w = res->weight[i], a = u[i * d + j] - res->mean[j], b = u[i * d + l] - res->mean[l];
                cjl += w * a * b;
                cjj += w * a * a;
                cll += w * b * b;
            }
            res->corr[j * d + l] = cjj > 0 && cll > 0 ? cjl / sqrt(cjj * cll) : NAN;
        }
    free(v);
    return GF_SUCCESS;
}

/* ----------------------------------------------------------- emulator */

void gf_emulator_free(gf_emulator *em)
{
    if (!em)
        return;
    free(em->center);
    free(em->gradient);
    free(em->hessian);
    free(em->curvature);
    free(em->direction);
    free(em->direction_param);
    free(em->ridge);
    free(em->ridge_point);
    memset(em, 0, sizeof *em);
}

typedef struct dist_index {
    double r2;
    size_t i;
} dist_index;

static int cmp_dist(const void *a, const void *b)
{
    const dist_index *x = a, *y = b;
    if (x->r2 != y->r2)
        return (x->r2 > y->r2) - (x->r2 < y->r2);
    return (x->i > y->i) - (x->i < y->i);
}

/* the quadratic's regressors at delta [d]: 1, delta_j, then for j <= l
 * delta_j^2 / 2 (j = l) or delta_j delta_l (j < l): the coefficients are
 * then c, g_j and H_jl */
static void regressors(size_t d, const double *delta, gsl_vector_view row)
{
    size_t c = 0;
    gsl_vector_set(&row.vector, c++, 1.0);
    for (size_t j = 0; j < d; ++j)
        gsl_vector_set(&row.vector, c++, delta[j]);
    for (size_t j = 0; j < d; ++j)
        for (size_t l = j; l < d; ++l)
            gsl_vector_set(&row.vector, c++, j == l ? 0.5 * delta[j] * delta[j] : delta[j] * delta[l]);
}

gf_status gf_emulator_fit(size_t n, size_t d, const double *u, const double *loss, size_t n_fit,
                          const double *lo, const double *hi, double fraction, gf_emulator *em)
{
    if (!em)
        return gf_fail(GF_EINVAL, "emulator: em NULL");
    memset(em, 0, sizeof *em);
    if (d < 1 || !u || !loss || !lo || !hi)
        return gf_fail(GF_EINVAL, "emulator: parameters d = %zu must be >= 1 (and u, loss, lo, hi given)", d);
    const size_t p = 1 + d + d * (d + 1) / 2;
    if (n_fit == 0)
        n_fit = n;
    if (n_fit > n || n_fit < p)
        return gf_fail(GF_EDOM,
                       "emulator: %zu points to fit of %zu; a quadratic in %zu parameters has %zu coefficients, "
                       "at least as many points are needed",
                       n_fit, n, d, p);
    if (!(fraction > 0 && fraction < 1))
        return gf_fail(isnan(fraction) ? GF_ENONFINITE : GF_EDOM, "emulator: ridge fraction %g must be in (0, 1)",
                       fraction);
    for (size_t j = 0; j < d; ++j) {
        if (!isfinite(lo[j]) || !isfinite(hi[j]))
            return gf_fail(GF_ENONFINITE, "emulator: range of parameter %zu [%g, %g] is not finite", j, lo[j], hi[j]);
        if (!(hi[j] > lo[j]))
            return gf_fail(GF_EDOM, "emulator: range of parameter %zu [%g, %g] is empty (hi must exceed lo)", j,
                           lo[j], hi[j]);
    }
    size_t best = 0;
    for (size_t i = 0; i < n; ++i) {
        if (!isfinite(loss[i]))
            return gf_fail(GF_ENONFINITE, "emulator: loss of point %zu is %g, not a finite number", i, loss[i]);
        for (size_t j = 0; j < d; ++j)
            if (!isfinite(u[i * d + j]))
                return gf_fail(GF_ENONFINITE, "emulator: coordinate %zu of point %zu is %g", j, i, u[i * d + j]);
        if (loss[i] < loss[best])
            best = i;
    }
    gf_status st = GF_SUCCESS;
    dist_index *di = malloc(n * sizeof *di);
    double *delta = malloc(d * sizeof *delta);
    gsl_matrix *X = gsl_matrix_alloc(n_fit, p), *cov = gsl_matrix_alloc(p, p), *H = gsl_matrix_alloc(d, d),
               *evec = gsl_matrix_alloc(d, d);
    gsl_vector *y = gsl_vector_alloc(n_fit), *c = gsl_vector_alloc(p), *eval = gsl_vector_alloc(d);
    gsl_multifit_linear_workspace *w = gsl_multifit_linear_alloc(n_fit, p);
    gsl_eigen_symmv_workspace *ew = gsl_eigen_symmv_alloc(d);
    em->d = d;
    em->n_fit = n_fit;
    em->center = malloc(d * sizeof *em->center);
    em->gradient = malloc(d * sizeof *em->gradient);
    em->hessian = malloc(d * d * sizeof *em->hessian);
    em->curvature = malloc(d * sizeof *em->curvature);
    em->direction = malloc(d * d * sizeof *em->direction);
    em->direction_param = malloc(d * d * sizeof *em->direction_param);
    em->ridge = calloc(d, sizeof *em->ridge);
    em->ridge_point = malloc(d * sizeof *em->ridge_point);
    if (!di || !delta || !X || !cov || !H || !evec || !y || !c || !eval || !w || !ew || !em->center ||
        !em->gradient || !em->hessian || !em->curvature || !em->direction || !em->direction_param || !em->ridge ||
        !em->ridge_point) {
        st = gf_fail(GF_ENOMEM, "emulator: %zu points, %zu parameters", n_fit, d);
        goto done;
    }
    memcpy(em->center, u + best * d, d * sizeof *em->center);
    for (size_t i = 0; i < n; ++i) {
        double r2 = 0;
        for (size_t j = 0; j < d; ++j)
            r2 += (u[i * d + j] - em->center[j]) * (u[i * d + j] - em->center[j]);
        di[i].r2 = r2;
        di[i].i = i;
    }
    qsort(di, n, sizeof *di, cmp_dist);
    double ymean = 0;
    for (size_t k = 0; k < n_fit; ++k) {
        const size_t i = di[k].i;
        for (size_t j = 0; j < d; ++j)
            delta[j] = u[i * d + j] - em->center[j];
        regressors(d, delta, gsl_matrix_row(X, k));
        gsl_vector_set(y, k, loss[i]);
        ymean += loss[i];
    }
    ymean /= (double)n_fit;
    double chisq;
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    int gs = gsl_multifit_linear(X, y, c, cov, &chisq, w);
    const double rcond = gs ? 0.0 : gsl_multifit_linear_rcond(w);
    if (!gs) {
        gsl_matrix *A = gsl_matrix_alloc(d, d);
        if (!A)
            gs = GSL_ENOMEM;
        else {
            size_t k = 1 + d;
            for (size_t j = 0; j < d; ++j)
                for (size_t l = j; l < d; ++l, ++k) {
                    gsl_matrix_set(H, j, l, gsl_vector_get(c, k));
                    gsl_matrix_set(H, l, j, gsl_vector_get(c, k));
                }
            gsl_matrix_memcpy(A, H);
            gs = gsl_eigen_symmv(A, eval, evec, ew);
            if (!gs)
                gs = gsl_eigen_symmv_sort(eval, evec, GSL_EIGEN_SORT_VAL_DESC);
            gsl_matrix_free(A);
        }
    }
    gsl_set_error_handler(old);
    if (gs) {
        st = gf_fail(GF_EGSL, "emulator: GSL's least squares or eigen-decomposition failed: %s", gsl_strerror(gs));
        goto done;
    }
    if (!(rcond > 1e-12)) {
        st = gf_fail(GF_EDOM,
                     "emulator: the quadratic's least squares are singular (reciprocal condition %g): the %zu "
                     "points nearest the best lie on a lower-dimensional set",
                     rcond, n_fit);
        goto done;
    }
    double sst = 0;
    for (size_t k = 0; k < n_fit; ++k)
        sst += (gsl_vector_get(y, k) - ymean) * (gsl_vector_get(y, k) - ymean);
    em->r2 = sst > 0 ? 1.0 - chisq / sst : 1.0;
    em->loss0 = gsl_vector_get(c, 0);
    for (size_t j = 0; j < d; ++j) {
        em->gradient[j] = gsl_vector_get(c, 1 + j);
        for (size_t l = 0; l < d; ++l)
            em->hessian[j * d + l] = gsl_matrix_get(H, j, l);
    }
    const double lmax = gsl_vector_get(eval, 0);
    if (!(lmax > 0)) {
        st = gf_fail(GF_EDOM,
                     "emulator: the fitted loss has no positive curvature (largest %g) near the best point: it has "
                     "no minimum there to constrain the parameters",
                     lmax);
        goto done;
    }
    em->n_ridge = 0;
    for (size_t j = 0; j < d; ++j)
        em->ridge_point[j] = em->center[j]; /* unit coordinates until the end */
    for (size_t k = 0; k < d; ++k) {
        const double lk = gsl_vector_get(eval, k);
        em->curvature[k] = lk;
        /* a reproducible sign: the largest component positive */
        size_t jm = 0;
        for (size_t j = 1; j < d; ++j)
            if (fabs(gsl_matrix_get(evec, j, k)) > fabs(gsl_matrix_get(evec, jm, k)))
                jm = j;
        const double sgn = gsl_matrix_get(evec, jm, k) < 0 ? -1.0 : 1.0;
        double norm = 0, vg = 0;
        for (size_t j = 0; j < d; ++j) {
            const double v = sgn * gsl_matrix_get(evec, j, k);
            em->direction[k * d + j] = v;
            em->direction_param[k * d + j] = (hi[j] - lo[j]) * v;
            norm += em->direction_param[k * d + j] * em->direction_param[k * d + j];
            vg += v * em->gradient[j];
        }
        for (size_t j = 0; j < d; ++j)
            em->direction_param[k * d + j] /= sqrt(norm);
        em->ridge[k] = lk < fraction * lmax;
        em->n_ridge += (size_t)em->ridge[k];
        if (!em->ridge[k]) /* the minimum across a constrained direction: -(v.g / lambda) v */
            for (size_t j = 0; j < d; ++j)
                em->ridge_point[j] -= vg / lk * em->direction[k * d + j];
    }
    for (size_t j = 0; j < d; ++j)
        em->ridge_point[j] = lo[j] + (hi[j] - lo[j]) * em->ridge_point[j];
    em->ridge_t_min = em->ridge_t_max = 0;
    if (em->n_ridge) {
        size_t k = d - 1; /* the smallest curvature: the last of the descending order */
        double tmin = -INFINITY, tmax = INFINITY;
        for (size_t j = 0; j < d; ++j) {
            const double v = em->direction_param[k * d + j], x = em->ridge_point[j];
            if (v == 0) {
                if (x < lo[j] || x > hi[j])
                    tmin = INFINITY, tmax = -INFINITY;
                continue;
            }
            double a = (lo[j] - x) / v, b = (hi[j] - x) / v;
            if (a > b) {
                const double t = a;
                a = b;
                b = t;
            }
            tmin = fmax(tmin, a);
            tmax = fmin(tmax, b);
        }
        if (tmin > tmax)
            tmin = tmax = NAN; /* the line misses the box */
        em->ridge_t_min = tmin;
        em->ridge_t_max = tmax;
    }
done:
    free(di);
    free(delta);
    gsl_matrix_free(X);
    gsl_matrix_free(cov);
    gsl_matrix_free(H);
    gsl_matrix_free(evec);
    gsl_vector_free(y);
    gsl_vector_free(c);
    gsl_vector_free(eval);
    if (w)
        gsl_multifit_linear_free(w);
    if (ew)
        gsl_eigen_symmv_free(ew);
    if (st)
        gf_emulator_free(em);
    return st;
}

double gf_emulator_eval(const gf_emulator *em, const double *u)
{
    if (!em || !u || !em->d || !em->center || !em->gradient || !em->hessian)
        return NAN;
    const size_t d = em->d;
    double L = em->loss0;
    for (size_t j = 0; j < d; ++j) {
        const double a = u[j] - em->center[j];
        L += em->gradient[j] * a;
        for (size_t l = 0; l < d; ++l)
            L += 0.5 * a * em->hessian[j * d + l] * (u[l] - em->center[l]);
    }
    return L;
}

/* ------------------------------------------------------------ verdict */

gf_status gf_reach_verdict(size_t n, const double *loss, const double *jaccard,
                           const double *runout_error, const gf_reach_criteria *c,
                           gf_reach_result *res)
{
    if (n < 1 || !loss || !c || !res)
        return gf_fail(GF_EINVAL, "reach verdict: evaluations n = %zu must be >= 1 (and loss, criteria, res given)", n);
    const int use_loss = !isnan(c->max_loss), use_j = !isnan(c->min_jaccard), use_r = !isnan(c->runout_tolerance);
    if (!use_loss && !use_j && !use_r)
        return gf_fail(GF_EINVAL, "reach verdict: no criterion given (max_loss, min_jaccard, runout_tolerance all NAN)");
    if ((use_j && !jaccard) || (use_r && !runout_error))
        return gf_fail(GF_EINVAL, "reach verdict: a criterion on the %s is given without its values",
                       use_j && !jaccard ? "Jaccard index" : "runout error");
    if ((use_loss && isinf(c->max_loss)) || (use_j && isinf(c->min_jaccard)) || (use_r && isinf(c->runout_tolerance)))
        return gf_fail(GF_ENONFINITE, "reach verdict: criteria max_loss %g, min_jaccard %g, runout tolerance %g must "
                                      "be finite or NAN (not used)",
                       c->max_loss, c->min_jaccard, c->runout_tolerance);
    if (use_r && c->runout_tolerance < 0)
        return gf_fail(GF_EDOM, "reach verdict: runout tolerance %g m must be >= 0", c->runout_tolerance);
    size_t best = 0, meet = 0;
    for (size_t i = 0; i < n; ++i) {
        if (!isfinite(loss[i]) || (use_j && !isfinite(jaccard[i])) || (use_r && !isfinite(runout_error[i])))
            return gf_fail(GF_ENONFINITE, "reach verdict: evaluation %zu has a value that is not finite", i);
        if (loss[i] < loss[best])
            best = i;
        meet += (!use_loss || loss[i] <= c->max_loss) && (!use_j || jaccard[i] >= c->min_jaccard) &&
                (!use_r || fabs(runout_error[i]) <= c->runout_tolerance);
    }
    res->best = best;
    res->n_meeting = meet;
    res->verdict = meet ? GF_REACHABLE : GF_UNREACHABLE;
    if (meet) {
        snprintf(res->reason, sizeof res->reason, "reachable: %zu of %zu evaluations meet every criterion", meet, n);
        return GF_SUCCESS;
    }
    /* which criterion the best evaluation misses */
    char buf[128] = "";
    size_t len = 0;
    if (use_loss && loss[best] > c->max_loss)
        len += (size_t)snprintf(buf + len, sizeof buf - len, "; loss %.4g > %.4g", loss[best], c->max_loss);
    if (use_j && jaccard[best] < c->min_jaccard && len < sizeof buf)
        len += (size_t)snprintf(buf + len, sizeof buf - len, "; Jaccard %.4g < %.4g", jaccard[best], c->min_jaccard);
    if (use_r && fabs(runout_error[best]) > c->runout_tolerance && len < sizeof buf)
        snprintf(buf + len, sizeof buf - len, "; |runout error| %.4g m > %.4g m", fabs(runout_error[best]),
                 c->runout_tolerance);
    snprintf(res->reason, sizeof res->reason,
             "unreachable: none of %zu evaluations meets every criterion; the best (evaluation %zu)%s", n, best,
             buf);
    return GF_SUCCESS;
}
