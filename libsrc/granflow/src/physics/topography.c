/* SPDX-License-Identifier: GPL-3.0-or-later */
#include "granflow/topography.h"
#include "internal.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_spline.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

enum kind { CHUTE, TABULATED };

struct gf_topography {
    enum kind kind;
    /* chute */
    double zeta0, zeta1, x1, x2;
    /* tabulated */
    size_t n;
    double *x;
    gsl_spline *spline;
    double *X, *Z; /* positions at the nodes */
    gsl_integration_glfixed_table *gl;
};

gf_status gf_topography_chute_alloc(double zeta0, double zeta1, double x1, double x2,
                                    gf_topography **out)
{
    gf_status st;
    if (!out)
        return gf_fail(GF_EINVAL, "gf_topography_chute_alloc: null output pointer");
    *out = NULL;
    if ((st = gf_check_range("chute inclination zeta0 [rad]", zeta0, -0.5 * GF_PI, 0.5 * GF_PI)) ||
        (st = gf_check_range("chute run-out inclination zeta1 [rad]", zeta1, -0.5 * GF_PI,
                             0.5 * GF_PI)) ||
        (st = gf_check_range("transition start x1", x1, -HUGE_VAL, HUGE_VAL)) ||
        (st = gf_check_range("transition end x2", x2, -HUGE_VAL, HUGE_VAL)))
        return st;
    if (!(x2 > x1))
        return gf_fail(GF_EDOM, "chute transition end x2 = %g must exceed its start x1 = %g", x2, x1);
    gf_topography *t = calloc(1, sizeof *t);
    if (!t)
        return gf_fail(GF_ENOMEM, "gf_topography_chute_alloc: out of memory");
    t->kind = CHUTE;
    t->zeta0 = zeta0;
    t->zeta1 = zeta1;
    t->x1 = x1;
    t->x2 = x2;
    *out = t;
    return GF_SUCCESS;
}

void gf_topography_free(gf_topography *t)
{
    if (!t)
        return;
    if (t->spline)
        gsl_spline_free(t->spline);
    if (t->gl)
        gsl_integration_glfixed_table_free(t->gl);
    free(t->x);
    free(t->X);
    free(t->Z);
    free(t);
}

/* Gauss–Legendre integral of cos(zeta) and -sin(zeta) over [a, b] of the spline. */
static void spline_segment(const gf_topography *t, double a, double b, double *dX, double *dZ)
{
    double sx = 0.0, sz = 0.0;
    for (size_t i = 0; i < t->gl->n; ++i) {
        double xi, wi;
        gsl_integration_glfixed_point(a, b, i, &xi, &wi, t->gl);
        const double z = gsl_spline_eval(t->spline, xi, NULL);
        sx += wi * cos(z);
        sz -= wi * sin(z);
    }
    *dX = sx;
    *dZ = sz;
}

gf_status gf_topography_tabulated_alloc(const double *x, const double *zeta, size_t n,
                                        gf_topography **out)
{
    if (!out || !x || !zeta)
        return gf_fail(GF_EINVAL, "gf_topography_tabulated_alloc: null argument");
    *out = NULL;
    if (n < 3)
        return gf_fail(GF_EINVAL, "tabulated topography needs at least 3 points, got %zu", n);
    for (size_t i = 0; i < n; ++i) {
        if (!isfinite(x[i]) || !isfinite(zeta[i]))
            return gf_fail(GF_ENONFINITE, "tabulated topography: point %zu (x = %g, zeta = %g) "
                                          "is not finite", i, x[i], zeta[i]);
        if (fabs(zeta[i]) >= 0.5 * GF_PI)
            return gf_fail(GF_EDOM, "tabulated topography: inclination zeta = %g rad at point %zu "
                                    "is outside (-pi/2, pi/2)", zeta[i], i);
        if (i > 0 && !(x[i] > x[i - 1]))
            return gf_fail(GF_EDOM, "tabulated topography: x must increase strictly, but "
                                    "x[%zu] = %g <= x[%zu] = %g", i, x[i], i - 1, x[i - 1]);
    }
    gf_topography *t = calloc(1, sizeof *t);
    if (!t)
        return gf_fail(GF_ENOMEM, "gf_topography_tabulated_alloc: out of memory");
    t->kind = TABULATED;
    t->n = n;
    t->x = malloc(n * sizeof *t->x);
    t->X = malloc(n * sizeof *t->X);
    t->Z = malloc(n * sizeof *t->Z);
    t->spline = gsl_spline_alloc(gsl_interp_cspline, n);
    t->gl = gsl_integration_glfixed_table_alloc(10);
    if (!t->x || !t->X || !t->Z || !t->spline || !t->gl) {
        gf_topography_free(t);
        return gf_fail(GF_ENOMEM, "gf_topography_tabulated_alloc: out of memory");
    }
    memcpy(t->x, x, n * sizeof *x);
    if (gsl_spline_init(t->spline, x, zeta, n) != GSL_SUCCESS) {
        gf_topography_free(t);
        return gf_fail(GF_EGSL, "tabulated topography: gsl_spline_init failed");
    }
    t->X[0] = t->Z[0] = 0.0;
    for (size_t i = 1; i < n; ++i) {
        double dX, dZ;
        spline_segment(t, x[i - 1], x[i], &dX, &dZ);
        t->X[i] = t->X[i - 1] + dX;
        t->Z[i] = t->Z[i - 1] + dZ;
    }
    *out = t;
    return GF_SUCCESS;
}

void gf_topography_range(const gf_topography *t, double *xmin, double *xmax)
{
    if (t->kind == CHUTE) {
        *xmin = -HUGE_VAL;
        *xmax = HUGE_VAL;
    } else {
        *xmin = t->x[0];
        *xmax = t->x[t->n - 1];
    }
}

static gf_status check_x(const gf_topography *t, double x)
{
    if (!isfinite(x))
        return gf_fail(GF_ENONFINITE, "topography evaluated at non-finite x = %g", x);
    if (t->kind == TABULATED && (x < t->x[0] || x > t->x[t->n - 1]))
        return gf_fail(GF_EDOM, "topography evaluated at x = %g outside the table [%g, %g]", x,
                       t->x[0], t->x[t->n - 1]);
    return GF_SUCCESS;
}

gf_status gf_topography_eval(const gf_topography *t, double x, double *zeta, double *kappa)
{
    if (!t || !zeta || !kappa)
        return gf_fail(GF_EINVAL, "gf_topography_eval: null argument");
    gf_status st = check_x(t, x);
    if (st)
        return st;
    if (t->kind == CHUTE) {
        const double k = (t->zeta0 - t->zeta1) / (t->x2 - t->x1);
        if (x < t->x1) {
            *zeta = t->zeta0;
            *kappa = 0.0;
        } else if (x <= t->x2) { /* rkdg eq. (3), finite-area eq. (74) */
            *zeta = t->zeta0 - k * (x - t->x1);
            *kappa = k;
        } else {
            *zeta = t->zeta1;
            *kappa = 0.0;
        }
        return GF_SUCCESS;
    }
    *zeta = gsl_spline_eval(t->spline, x, NULL);
    *kappa = -gsl_spline_eval_deriv(t->spline, x, NULL);
    return GF_SUCCESS;
}

/* Chute position with X(0) = 0 and Z(x1) = 0 first; shifted below. */
static void chute_position_raw(const gf_topography *t, double x, double *X, double *Z)
{
    const double z0 = t->zeta0, z1 = t->zeta1, x1 = t->x1;
    const double k = (z0 - z1) / (t->x2 - x1);
    if (x <= x1) {
        *X = x * cos(z0);
        *Z = (x1 - x) * sin(z0);
        return;
    }
    const double xe = x < t->x2 ? x : t->x2;
    const double ze = z0 - k * (xe - x1);
    double Xe, Ze;
    if (k != 0.0) { /* circular arc of radius 1/k */
        Xe = x1 * cos(z0) + (sin(z0) - sin(ze)) / k;
        Ze = (cos(z0) - cos(ze)) / k;
    } else {
        Xe = x1 * cos(z0) + (xe - x1) * cos(z0);
        Ze = -(xe - x1) * sin(z0);
    }
    if (x > t->x2) {
        Xe += (x - t->x2) * cos(z1);
        Ze -= (x - t->x2) * sin(z1);
    }
    *X = Xe;
    *Z = Ze;
}

gf_status gf_topography_position(const gf_topography *t, double x, double *X, double *Z)
{
    if (!t || !X || !Z)
        return gf_fail(GF_EINVAL, "gf_topography_position: null argument");
    gf_status st = check_x(t, x);
    if (st)
        return st;
    if (t->kind == CHUTE) {
        double X2, Z2;
        chute_position_raw(t, t->x2, &X2, &Z2);
        chute_position_raw(t, x, X, Z);
        *Z -= Z2;
        return GF_SUCCESS;
    }
    size_t i = gsl_interp_bsearch(t->x, x, 0, t->n - 1);
    double dX, dZ;
    spline_segment(t, t->x[i], x, &dX, &dZ);
    *X = t->X[i] + dX;
    *Z = t->Z[i] + dZ;
    return GF_SUCCESS;
}
