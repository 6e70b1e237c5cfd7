/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Calibration scores of a run against an observation and their weighted loss
 * (granflow/calibration.h; doc/theory/calibration.md, section 2). */
#include "granflow/calibration.h"
#include "internal.h"

#include <math.h>

gf_status gf_score_outline(size_t n, const double *sim, double threshold,
                           const unsigned char *observed, const unsigned char *valid,
                           double cell_area, double alpha, double beta, gf_outline_score *s)
{
    gf_status st;
    if (n < 1 || !sim || !observed || !s)
        return gf_fail(GF_EINVAL, "outline score: cells n = %zu must be >= 1 (and sim, observed, s given)", n);
    if (!isfinite(threshold))
        return gf_fail(GF_ENONFINITE, "outline score: threshold = %g is not a finite number", threshold);
    if (!isfinite(cell_area))
        return gf_fail(GF_ENONFINITE, "outline score: cell area = %g m2 is not a finite number", cell_area);
    if (!(cell_area > 0))
        return gf_fail(GF_EDOM, "outline score: cell area = %g m2 must be > 0", cell_area);
    if ((st = gf_check_range("outline score: Tversky alpha", alpha, 0.0, HUGE_VAL)) ||
        (st = gf_check_range("outline score: Tversky beta", beta, 0.0, HUGE_VAL)))
        return st;
    size_t tp = 0, fp = 0, fn = 0, nv = 0;
    for (size_t i = 0; i < n; ++i) {
        if (valid && !valid[i])
            continue;
        if (isinf(sim[i]))
            return gf_fail(GF_ENONFINITE, "outline score: simulated value at cell %zu is %g", i, sim[i]);
        ++nv;
        const int a = sim[i] > threshold, b = observed[i] != 0; /* NaN > t is false: not reached */
        tp += a && b;
        fp += a && !b;
        fn += !a && b;
    }
    if (tp + fn == 0)
        return gf_fail(GF_EDOM,
                       "outline score: the observed outline covers none of the %zu valid cells: nothing to compare "
                       "with",
                       nv);
    s->tp = (double)tp * cell_area;
    s->fp = (double)fp * cell_area;
    s->fn = (double)fn * cell_area;
    s->n_valid = nv;
    s->jaccard = (double)tp / (double)(tp + fp + fn);
    const double den = (double)tp + alpha * (double)fp + beta * (double)fn;
    s->tversky = tp == 0 ? 0.0 : (double)tp / den;
    return GF_SUCCESS;
}

gf_status gf_score_deposit_rmse(size_t n, const double *sim, const double *obs,
                                const unsigned char *valid, double threshold,
                                gf_rmse_region region, double *rmse, size_t *count)
{
    if (n < 1 || !sim || !obs || !rmse)
        return gf_fail(GF_EINVAL, "deposit RMSE: cells n = %zu must be >= 1 (and sim, obs, rmse given)", n);
    if (region != GF_RMSE_UNION && region != GF_RMSE_OBSERVED)
        return gf_fail(GF_EINVAL, "deposit RMSE: region %d is neither GF_RMSE_UNION nor GF_RMSE_OBSERVED",
                       (int)region);
    if (!isfinite(threshold))
        return gf_fail(GF_ENONFINITE, "deposit RMSE: threshold = %g is not a finite number", threshold);
    double ss = 0;
    size_t c = 0;
    for (size_t i = 0; i < n; ++i) {
        if (valid && !valid[i])
            continue;
        if (!isfinite(obs[i]))
            return gf_fail(GF_ENONFINITE,
                           "deposit RMSE: observed thickness at valid cell %zu is %g (mark NODATA cells in valid)", i,
                           obs[i]);
        if (isinf(sim[i]))
            return gf_fail(GF_ENONFINITE, "deposit RMSE: simulated thickness at cell %zu is %g", i, sim[i]);
        const double h = isnan(sim[i]) ? 0.0 : sim[i];
        const int in = region == GF_RMSE_OBSERVED ? obs[i] > threshold : (obs[i] > threshold || h > threshold);
        if (!in)
            continue;
        ss += (h - obs[i]) * (h - obs[i]);
        ++c;
    }
    if (c == 0)
        return gf_fail(GF_EDOM, "deposit RMSE: no valid cell has a thickness above %g m in the %s", threshold,
                       region == GF_RMSE_OBSERVED ? "observed deposit" : "union of the deposits");
    *rmse = sqrt(ss / (double)c);
    if (count)
        *count = c;
    return GF_SUCCESS;
}

gf_status gf_score_runout(double s_sim, double s_obs, double *err)
{
    if (!err)
        return gf_fail(GF_EINVAL, "runout error: err NULL");
    if (!isfinite(s_sim) || !isfinite(s_obs))
        return gf_fail(GF_ENONFINITE, "runout error: simulated runout %g m, observed %g m: both must be finite", s_sim,
                       s_obs);
    *err = s_sim - s_obs;
    return GF_SUCCESS;
}

gf_status gf_score_series_rmse(size_t n, const double *sim, const double *obs, double *rmse)
{
    if (n < 1 || !sim || !obs || !rmse)
        return gf_fail(GF_EINVAL, "series RMSE: times n = %zu must be >= 1 (and sim, obs, rmse given)", n);
    double ss = 0;
    for (size_t i = 0; i < n; ++i) {
        if (!isfinite(sim[i]) || !isfinite(obs[i]))
            return gf_fail(GF_ENONFINITE, "series RMSE: value %zu: simulated %g, observed %g: both must be finite", i,
                           sim[i], obs[i]);
        ss += (sim[i] - obs[i]) * (sim[i] - obs[i]);
    }
    *rmse = sqrt(ss / (double)n);
    return GF_SUCCESS;
}

gf_status gf_front_position(size_t n, const double *arrival, const double *s, const double *l,
                            double half_width, double t, double *s_front)
{
    if (n < 1 || !arrival || !s || !l || !s_front)
        return gf_fail(GF_EINVAL, "front position: cells n = %zu must be >= 1 (and the arrays given)", n);
    if (!isfinite(t) || !(isfinite(half_width) && half_width > 0))
        return gf_fail(GF_EDOM, "front position: time %g must be finite, half width %g finite and > 0", t, half_width);
    double best = NAN;
    for (size_t i = 0; i < n; ++i)
        if (isfinite(arrival[i]) && arrival[i] <= t && fabs(l[i]) <= half_width && !(s[i] <= best))
            best = s[i];
    *s_front = best;
    return GF_SUCCESS;
}

gf_status gf_front_speed(size_t n, const double *arrival, const double *s, const double *l,
                         double half_width, double t, double w, double *speed)
{
    if (!speed)
        return gf_fail(GF_EINVAL, "front speed: speed must be given");
    if (!(isfinite(w) && w > 0))
        return gf_fail(GF_EDOM, "front speed: window %g s must be finite and > 0", w);
    const double t0 = t - w > 0 ? t - w : 0, t1 = t + w;
    double a, b;
    gf_status st;
    if ((st = gf_front_position(n, arrival, s, l, half_width, t0, &a)) ||
        (st = gf_front_position(n, arrival, s, l, half_width, t1, &b)))
        return st;
    *speed = (b - a) / (t1 - t0);
    return GF_SUCCESS;
}

/* one term of the loss: weight w >= 0, the error raw / scale (raw NAN: not
 * observed, the term is left out) */
static gf_status loss_term(const char *name, double w, double scale, double raw, double *sw, double *swe)
{
    if (!isfinite(w) || w < 0)
        return gf_fail(isfinite(w) ? GF_EDOM : GF_ENONFINITE, "loss: weight of %s = %g must be finite and >= 0", name,
                       w);
    if (w == 0 || isnan(raw))
        return GF_SUCCESS;
    if (!(isfinite(scale) && scale > 0))
        return gf_fail(GF_EDOM, "loss: scale of %s = %g must be finite and > 0", name, scale);
    if (isinf(raw))
        return gf_fail(GF_ENONFINITE, "loss: %s is infinite", name);
    *sw += w;
    *swe += w * (raw / scale);
    return GF_SUCCESS;
}

gf_status gf_loss(const gf_scores *s, const gf_loss_weights *w, double *loss)
{
    gf_status st;
    if (!s || !w || !loss)
        return gf_fail(GF_EINVAL, "loss: scores, weights and loss must be given");
    if (!isnan(s->tversky) && !(s->tversky >= 0 && s->tversky <= 1))
        return gf_fail(GF_EDOM, "loss: Tversky index %g outside [0, 1]", s->tversky);
    if (s->rmse < 0 || s->series_rmse < 0 || s->speed_rmse < 0)
        return gf_fail(GF_EDOM, "loss: an RMSE is negative (deposit %g, front position %g, front speed %g)", s->rmse,
                       s->series_rmse, s->speed_rmse);
    double sw = 0, swe = 0;
    if ((st = loss_term("the runout error", w->runout, w->runout_scale, fabs(s->runout_error), &sw, &swe)) ||
        (st = loss_term("the outline (1 - Tversky)", w->outline, 1.0, 1.0 - s->tversky, &sw, &swe)) ||
        (st = loss_term("the deposit RMSE", w->rmse, w->rmse_scale, s->rmse, &sw, &swe)) ||
        (st = loss_term("the front position RMSE", w->series, w->series_scale, s->series_rmse, &sw, &swe)) ||
        (st = loss_term("the front speed RMSE", w->speed, w->speed_scale, s->speed_rmse, &sw, &swe)))
        return st;
    if (sw == 0)
        return gf_fail(GF_EDOM, "loss: no score is both observed (not NAN) and weighted (weight > 0)");
    *loss = swe / sw;
    return GF_SUCCESS;
}
