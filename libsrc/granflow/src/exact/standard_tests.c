/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * granflow — references and error measures of the field's standard analytic
 * tests (granflow/standard_tests.h, doc/theory/standard-tests.md).
 *
 *  - Similarity solution: K. Hutter, M. Siegel, S.B. Savage, Y. Nohguchi
 *    (1993), Two-dimensional spreading of a granular avalanche down an
 *    inclined plane. Part I: Theory. Acta Mechanica 100, 37-68,
 *    doi:10.1007/BF01176861.  The stretching factors g (along) and f (across
 *    the slope) of a parabolic cap obey
 *        g'' = 2B / (g^2 f),
 *        f'' = 2D / (g f^2) - C f' / ((A - C) tau),
 *    g(0) = f(0) = 1, g'(0) = f'(0) = 0.  The friction term is singular at
 *    tau = 0, so the solution starts from its Taylor expansion up to
 *    tau1 = 0.1 and is integrated from there with GSL's odeiv2 (rk8pd).
 *  - Dam break on an inclined Coulomb plane: G. Faccanoni, A. Mangeney
 *    (2013), Exact solution for granular flows. Int. J. Numer. Anal. Methods
 *    Geomech. 37(10), 1408-1433 (test 2, release from rest onto a dry bed):
 *    in the frame that slides with the block at acceleration m0 the problem
 *    is Ritter's dam break; the rarefaction from the release's rear edge is
 *    not part of the solution (xmid bounds its influence).
 *  - Flat-plane pile: a cone with a flat top whose flank slope equals the
 *    Coulomb coefficient stays at rest.
 *  - Energy line: mass-averaged path against the alpha line z0 - mu s.
 * Error norms: relative L2 and Lmax as the field computes them.
 */
#include "granflow/standard_tests.h"
#include "granflow/earth_pressure.h"
#include "internal.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <math.h>
#include <stdlib.h>

/* ---- 1. similarity solution ---------------------------------------------- */

#define SIMI_TAU1 0.1      /* end of the Taylor start (Hutter et al. 1993) */
#define SIMI_DTAU 0.005    /* spacing of the stored solution (dense output) */
#define SIMI_TAU_MAX 1000.0 /* largest tau_end accepted (200,000 stored nodes) */

struct gf_simisol {
    gf_simisol_params p;
    gf_simisol_coeffs c;
    double kx[2], ky[4];  /* flag_earth: Kx act/pass, Ky act/pass for Kx act, for Kx pass */
    double t_end, tau_end;
    size_t n;             /* stored nodes from tau1 (0: t_end inside the Taylor start) */
    double *tau, *y, *dy; /* node times, states (g, g', f, f') and their derivatives */
};

gf_simisol_params gf_simisol_default(void)
{
    return (gf_simisol_params){.g = 9.81,
                               .zeta = 35.0 * GF_DEG,
                               .delta = 25.0 * GF_DEG,
                               .H = 4.0,
                               .Lx = 80.0,
                               .Ly = 80.0,
                               .Kx = 1.0,
                               .Ky = 1.0,
                               .flag_earth = 0,
                               .phi = 25.0 * GF_DEG};
}

static gf_status simisol_check(const gf_simisol_params *p)
{
    gf_status st;
    if ((st = gf_check_range("similarity solution gravity g", p->g, 1e-300, HUGE_VAL)) ||
        (st = gf_check_range("similarity solution plane inclination zeta [rad]", p->zeta, 1e-12,
                             0.5 * GF_PI - 1e-12)) ||
        (st = gf_check_range("similarity solution bed friction angle delta [rad]", p->delta, 0.0,
                             0.5 * GF_PI - 1e-12)) ||
        (st = gf_check_range("similarity solution thickness H", p->H, 1e-300, HUGE_VAL)) ||
        (st = gf_check_range("similarity solution semi-axis Lx", p->Lx, 1e-300, HUGE_VAL)) ||
        (st = gf_check_range("similarity solution semi-axis Ly", p->Ly, 1e-300, HUGE_VAL)))
        return st;
    if (p->delta >= p->zeta)
        return gf_fail(GF_EPHYS,
                       "similarity solution: bed friction angle delta = %g deg >= plane "
                       "inclination zeta = %g deg: the cap does not slide (A - C <= 0; Hutter "
                       "et al. 1993 need delta < zeta)",
                       p->delta * GF_RAD2DEG, p->zeta * GF_RAD2DEG);
    if (p->flag_earth != 0 && p->flag_earth != 1)
        return gf_fail(GF_EINVAL, "similarity solution: flag_earth = %d must be 0 or 1",
                       p->flag_earth);
    if (!p->flag_earth &&
        ((st = gf_check_range("similarity solution earth pressure coefficient Kx", p->Kx, 1e-300,
                              HUGE_VAL)) ||
         (st = gf_check_range("similarity solution earth pressure coefficient Ky", p->Ky, 1e-300,
                              HUGE_VAL))))
        return st;
    return GF_SUCCESS;
}

/* Ky active (sign -1) or passive (+1) for a given Kx (Hutter et al. 1993). */
static double simisol_ky(double kx, double delta, double sign)
{
    const double t = tan(delta);
    return 0.5 * (kx + 1.0 + sign * sqrt((1.0 - kx) * (1.0 - kx) + 4.0 * t * t));
}

/* B and D of Kx, Ky */
static void simisol_bd(const gf_simisol *s, double kx, double ky, double *B, double *D)
{
    const double ex = s->p.H / s->p.Lx, ey = s->p.H / s->p.Ly, cz = cos(s->p.zeta);
    *B = ex * cz * kx;
    *D = ey * ey / ex * cz * ky;
}

static int simisol_rhs(double tau, const double y[], double dydt[], void *params)
{
    const gf_simisol *s = params;
    double B = s->c.B, D = s->c.D;
    if (s->p.flag_earth) {
        const int xpass = y[1] < 0.0, ypass = y[3] < 0.0;
        simisol_bd(s, s->kx[xpass], s->ky[2 * xpass + ypass], &B, &D);
    }
    const double g = y[0], f = y[2];
    dydt[0] = y[1];
    dydt[1] = 2.0 * B / (g * g * f);
    dydt[2] = y[3];
    dydt[3] = 2.0 * D / (g * f * f) - s->c.C * y[3] / ((s->c.A - s->c.C) * tau);
    return GSL_SUCCESS;
}

/* The Taylor start, tau <= tau1: g = 1 + B tau^2, f = 1 + D E tau^2. */
static void simisol_taylor(const gf_simisol *s, double tau, double y[4])
{
    y[0] = 1.0 + s->c.B * tau * tau;
    y[1] = 2.0 * s->c.B * tau;
    y[2] = 1.0 + s->c.D * s->c.E * tau * tau;
    y[3] = 2.0 * s->c.D * s->c.E * tau;
}

void gf_simisol_free(gf_simisol *s)
{
    if (!s)
        return;
    free(s->tau);
    free(s->y);
    free(s->dy);
    free(s);
}

gf_status gf_simisol_alloc(gf_simisol **out, const gf_simisol_params *p, double t_end,
                           double rtol)
{
    gf_status st;
    if (!out || !p)
        return gf_fail(GF_EINVAL, "gf_simisol_alloc: null pointer");
    *out = NULL;
    if ((st = simisol_check(p)) ||
        (st = gf_check_range("similarity solution end time t_end", t_end, 0.0, HUGE_VAL)) ||
        (st = gf_check_range("similarity solution relative tolerance rtol", rtol, 1e-13, 1e-3)))
        return st;
    gf_simisol *s = calloc(1, sizeof *s);
    if (!s)
        return gf_fail(GF_ENOMEM, "gf_simisol_alloc: out of memory");
    s->p = *p;
    gf_simisol_coeffs *c = &s->c;
    c->T = sqrt(p->Lx / p->g);
    c->U = sqrt(p->g * p->Lx);
    /* the field's V (AvaFrame's simiSolTest); the kinematic scale of the
     * cross-slope velocity is Ly / T = Ly sqrt(g / Lx), equal for Lx = Ly */
    c->V = sqrt(p->g * p->Ly);
    c->A = sin(p->zeta);
    c->C = cos(p->zeta) * tan(p->delta);
    c->E = (c->A - c->C) / c->A;
    double kx = p->Kx, ky = p->Ky;
    if (p->flag_earth) {
        if ((st = gf_earth_pressure_coefficients(p->phi, p->delta, &s->kx[0], &s->kx[1]))) {
            free(s);
            return st;
        }
        for (int i = 0; i < 2; ++i) {
            s->ky[2 * i] = simisol_ky(s->kx[i], p->delta, -1.0);
            s->ky[2 * i + 1] = simisol_ky(s->kx[i], p->delta, 1.0);
        }
        kx = s->kx[0]; /* the start: g' = f' = 0, both active */
        ky = s->ky[0];
    }
    simisol_bd(s, kx, ky, &c->B, &c->D);
    s->t_end = t_end;
    s->tau_end = t_end / c->T;
    if (s->tau_end > SIMI_TAU_MAX) {
        const double t_max = SIMI_TAU_MAX * c->T;
        gf_simisol_free(s);
        return gf_fail(GF_EDOM,
                       "similarity solution: t_end = %g s is beyond the stored range "
                       "(tau = t/sqrt(Lx/g) <= %g, t <= %g s)",
                       t_end, SIMI_TAU_MAX, t_max);
    }
    if (s->tau_end <= SIMI_TAU1) {
        *out = s;
        return GF_SUCCESS;
    }
    /* nodes tau1 + i dtau, the last one at tau_end (spacing in (0, dtau]) */
    const size_t m = (size_t)ceil((s->tau_end - SIMI_TAU1) / SIMI_DTAU - 1e-9);
    s->n = (m < 1 ? 1 : m) + 1;
    s->tau = malloc(s->n * sizeof *s->tau);
    s->y = malloc(4 * s->n * sizeof *s->y);
    s->dy = malloc(4 * s->n * sizeof *s->dy);
    if (!s->tau || !s->y || !s->dy) {
        gf_simisol_free(s);
        return gf_fail(GF_ENOMEM, "gf_simisol_alloc: out of memory");
    }
    gsl_odeiv2_system sys = {simisol_rhs, NULL, 4, s};
    gsl_odeiv2_driver *drv =
        gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, 1e-3, 1e-3 * rtol, rtol);
    if (!drv) {
        gf_simisol_free(s);
        return gf_fail(GF_ENOMEM, "gf_simisol_alloc: out of memory (GSL driver)");
    }
    double tau = SIMI_TAU1, y[4];
    simisol_taylor(s, tau, y);
    int status = GSL_SUCCESS;
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    for (size_t i = 0; i < s->n && status == GSL_SUCCESS; ++i) {
        const double ti = i + 1 == s->n ? s->tau_end : SIMI_TAU1 + (double)i * SIMI_DTAU;
        if (i > 0)
            status = gsl_odeiv2_driver_apply(drv, &tau, ti, y);
        s->tau[i] = ti;
        for (int k = 0; k < 4; ++k)
            s->y[4 * i + k] = y[k];
        simisol_rhs(ti, y, s->dy + 4 * i, s);
    }
    gsl_set_error_handler(old);
    gsl_odeiv2_driver_free(drv);
    if (status != GSL_SUCCESS) {
        gf_simisol_free(s);
        return gf_fail(GF_EGSL, "similarity solution: GSL odeiv2 integration failed: %s",
                       gsl_strerror(status));
    }
    *out = s;
    return GF_SUCCESS;
}

void gf_simisol_coefficients(const gf_simisol *s, gf_simisol_coeffs *c) { *c = s->c; }

gf_status gf_simisol_stretch(const gf_simisol *s, double t, double *gv, double *dg, double *fv,
                             double *df)
{
    if (!s || !gv || !dg || !fv || !df)
        return gf_fail(GF_EINVAL, "gf_simisol_stretch: null pointer");
    gf_status st = gf_check_range("similarity solution time t", t, 0.0, s->t_end);
    if (st)
        return st;
    const double tau = fmin(t / s->c.T, s->tau_end);
    double y[4];
    if (tau <= SIMI_TAU1) {
        simisol_taylor(s, tau, y);
    } else {
        /* cubic Hermite interpolation between the stored nodes: each
         * component from its value and its derivative (the ODE's right side) */
        size_t i = (size_t)floor((tau - SIMI_TAU1) / SIMI_DTAU);
        if (i > s->n - 2)
            i = s->n - 2;
        const double h = s->tau[i + 1] - s->tau[i], x = (tau - s->tau[i]) / h;
        const double h00 = (1.0 + 2.0 * x) * (1.0 - x) * (1.0 - x), h10 = x * (1.0 - x) * (1.0 - x);
        const double h01 = x * x * (3.0 - 2.0 * x), h11 = x * x * (x - 1.0);
        const double *y0 = s->y + 4 * i, *y1 = y0 + 4, *d0 = s->dy + 4 * i, *d1 = d0 + 4;
        for (int k = 0; k < 4; ++k)
            y[k] = h00 * y0[k] + h * h10 * d0[k] + h01 * y1[k] + h * h11 * d1[k];
    }
    *gv = y[0];
    *dg = y[1];
    *fv = y[2];
    *df = y[3];
    return GF_SUCCESS;
}

/* The cap H/(f g) (1 - s^2/g^2 - eta^2/f^2), cut at 0. */
static double simisol_cap(double H, double s, double eta, double gv, double fv)
{
    const double q = 1.0 - s * s / (gv * gv) - eta * eta / (fv * fv);
    return q > 0.0 ? H / (fv * gv) * q : 0.0;
}

gf_status gf_simisol_sample(const gf_simisol *s, double x, double y, double t, double *h,
                            double vel[3])
{
    if (!s || !h || !vel)
        return gf_fail(GF_EINVAL, "gf_simisol_sample: null pointer");
    gf_status st;
    if ((st = gf_check_range("similarity solution position x", x, -HUGE_VAL, HUGE_VAL)) ||
        (st = gf_check_range("similarity solution position y", y, -HUGE_VAL, HUGE_VAL)))
        return st;
    double gv, dg, fv, df;
    if ((st = gf_simisol_stretch(s, t, &gv, &dg, &fv, &df)))
        return st;
    const gf_simisol_coeffs *c = &s->c;
    const double tau = t / c->T, cz = cos(s->p.zeta);
    const double sx = x / cz / s->p.Lx - 0.5 * (c->A - c->C) * tau * tau, eta = y / s->p.Ly;
    *h = simisol_cap(s->p.H, sx, eta, gv, fv);
    if (*h == 0.0) {
        vel[0] = vel[1] = vel[2] = 0.0;
        return GF_SUCCESS;
    }
    const double u = c->U * ((c->A - c->C) * tau + sx * dg / gv), v = c->V * eta * df / fv;
    vel[0] = u * cz;
    vel[1] = v;
    vel[2] = -u * sin(s->p.zeta);
    return GF_SUCCESS;
}

double gf_simisol_h0(const gf_simisol_params *p, double x, double y)
{
    return simisol_cap(p->H, x / cos(p->zeta) / p->Lx, y / p->Ly, 1.0, 1.0);
}

double gf_simisol_xc(const gf_simisol_params *p, double t)
{
    if (!p || simisol_check(p) || !(t >= 0.0))
        return NAN;
    const double amc = sin(p->zeta) - cos(p->zeta) * tan(p->delta), tau2 = t * t * p->g / p->Lx;
    return p->Lx * amc * 0.5 * tau2 * cos(p->zeta);
}

/* ---- 2. dam break on an inclined Coulomb plane --------------------------- */

gf_status gf_incdam_init(gf_incdam *d, double g, double phi, double delta, double hL,
                         double x_back)
{
    gf_status st;
    if (!d)
        return gf_fail(GF_EINVAL, "gf_incdam_init: null pointer");
    if ((st = gf_check_range("inclined dam break gravity g", g, 1e-300, HUGE_VAL)) ||
        (st = gf_check_range("inclined dam break plane inclination phi [rad]", phi, 0.0,
                             0.5 * GF_PI - 1e-12)) ||
        (st = gf_check_range("inclined dam break bed friction angle delta [rad]", delta, 0.0,
                             0.5 * GF_PI - 1e-12)) ||
        (st = gf_check_range("inclined dam break released thickness hL", hL, 1e-300, HUGE_VAL)) ||
        (st = gf_check_range("inclined dam break rear edge x_back", x_back, -HUGE_VAL,
                             -1e-300)))
        return st;
    if (delta > phi)
        return gf_fail(GF_EPHYS,
                       "inclined dam break: bed friction angle delta = %g deg > plane "
                       "inclination phi = %g deg: the block would not slide (m0 < 0), and the "
                       "solution of Faccanoni & Mangeney assumes it does",
                       delta * GF_RAD2DEG, phi * GF_RAD2DEG);
    *d = (gf_incdam){.g = g, .phi = phi, .delta = delta, .hL = hL, .x_back = x_back};
    d->gz = g * cos(phi);
    d->m0 = d->gz * (tan(phi) - tan(delta));
    d->cL = sqrt(d->gz * hL);
    return GF_SUCCESS;
}

void gf_incdam_sample(const gf_incdam *d, double x, double t, double *h, double *u)
{
    const double xi = x / cos(d->phi);
    if (!(t > 0.0)) {
        *h = xi <= 0.0 ? d->hL : 0.0;
        *u = 0.0;
        return;
    }
    const double m0t = d->m0 * t, S = xi / t;
    if (S <= 0.5 * m0t - d->cL) { /* the body slides as a whole */
        *h = d->hL;
        *u = m0t;
    } else if (S <= 2.0 * d->cL + 0.5 * m0t) { /* the rarefaction fan */
        const double c = 2.0 * d->cL - S + 0.5 * m0t;
        *h = c * c / (9.0 * d->gz);
        *u = 2.0 / 3.0 * (d->cL + S + m0t);
    } else {
        *h = 0.0;
        *u = 0.0;
    }
}

void gf_incdam_fan(const gf_incdam *d, double t, double *x_tail, double *x_front)
{
    const double cp = cos(d->phi), m0t = d->m0 * t;
    *x_tail = (0.5 * m0t - d->cL) * t * cp;
    *x_front = (2.0 * d->cL + 0.5 * m0t) * t * cp;
}

double gf_incdam_xmid(const gf_incdam *d, double t)
{
    const double cp = cos(d->phi), m0t = d->m0 * t, x0R = d->x_back / cp;
    /* two thirds of the way from the rear fan's head to the front fan's tail */
    const double xi = (2.0 * (x0R + (0.5 * m0t + d->cL) * t) + (0.5 * m0t - d->cL) * t) / 3.0;
    return xi * cp;
}

/* ---- 3. flat-plane pile --------------------------------------------------- */

double gf_flatpile_h0(double H0, double r0, double slope, double x, double y)
{
    const double r = sqrt(x * x + y * y);
    return fmin(H0, fmax(0.0, H0 - slope * (r - r0)));
}

/* ---- error measures ------------------------------------------------------- */

/* e_c and r_c are formed per cell by the caller; NaN terms are skipped in
 * each sum and maximum on its own (numpy's nansum / nanmax), as the field
 * does: a cell whose numerical value is NaN counts in the reference. */
typedef struct {
    double se, sr, me, mr;
    size_t n_used;
} norm_acc;

static void norm_add(norm_acc *a, double e, double r)
{
    if (!isnan(e)) {
        a->se += e;
        a->me = fmax(a->me, e);
        ++a->n_used;
    }
    if (!isnan(r)) {
        a->sr += r;
        a->mr = fmax(a->mr, r);
    }
}

static gf_status norm_finish(const norm_acc *a, double w, size_t n, gf_error_norms *out)
{
    if (a->n_used == 0)
        return gf_fail(GF_ENONFINITE, "error norms: all %zu cells are NaN: no error to measure",
                       n);
    out->l2 = sqrt(w * a->se);
    out->l2ref = sqrt(w * a->sr);
    out->lmax = sqrt(a->me);
    out->lmaxref = sqrt(a->mr);
    out->rel_l2 = out->l2ref > 0.0 ? out->l2 / out->l2ref : out->l2;
    out->rel_lmax = out->lmaxref > 0.0 ? out->lmax / out->lmaxref : out->lmax;
    out->n_used = a->n_used;
    return GF_SUCCESS;
}

static gf_status norm_check(const char *what, const double *a, const double *nu, size_t n,
                            size_t dim, double w, gf_error_norms *out)
{
    if (!a || !nu || !out)
        return gf_fail(GF_EINVAL, "%s: null pointer", what);
    if (n == 0)
        return gf_fail(GF_EINVAL, "%s: no cells (n = 0)", what);
    gf_status st = gf_check_range("error norms cell weight w", w, 1e-300, HUGE_VAL);
    if (st)
        return st;
    for (size_t i = 0; i < n * dim; ++i)
        if (isinf(a[i]) || isinf(nu[i]))
            return gf_fail(GF_ENONFINITE, "%s: cell %zu has an infinite %s value", what, i / dim,
                           isinf(a[i]) ? "analytic" : "numerical");
    return GF_SUCCESS;
}

gf_status gf_error_scalar(const double *analytic, const double *numeric, size_t n, double w,
                          gf_error_norms *out)
{
    gf_status st = norm_check("gf_error_scalar", analytic, numeric, n, 1, w, out);
    if (st)
        return st;
    norm_acc a = {0};
    for (size_t i = 0; i < n; ++i) {
        const double d = analytic[i] - numeric[i];
        norm_add(&a, d * d, analytic[i] * analytic[i]);
    }
    return norm_finish(&a, w, n, out);
}

gf_status gf_error_vector(const double *analytic, const double *numeric, size_t n, double w,
                          gf_error_norms *out)
{
    gf_status st = norm_check("gf_error_vector", analytic, numeric, n, 3, w, out);
    if (st)
        return st;
    norm_acc a = {0};
    for (size_t i = 0; i < n; ++i) {
        double e = 0.0, r = 0.0;
        for (int k = 0; k < 3; ++k) {
            const double d = analytic[3 * i + k] - numeric[3 * i + k];
            e += d * d;
            r += analytic[3 * i + k] * analytic[3 * i + k];
        }
        norm_add(&a, e, r);
    }
    return norm_finish(&a, w, n, out);
}

size_t gf_output_grid_cells(size_t n0, double csz0, double csz)
{
    if (n0 == 0 || !(csz0 > 0.0) || !(csz > 0.0) || !isfinite(csz0) || !isfinite(csz))
        return 0;
    return (size_t)floor((double)(n0 - 1) * csz0 / csz) + 1;
}

/* ---- 4. energy line --------------------------------------------------------- */

static int sign_of(double v) { return (v > 0.0) - (v < 0.0); }

/* The last sign change of z - (z0 - mu s) along the points (s, z) and the
 * intersection interpolated in its segment; 0 when there is none. */
static int alpha_intersection(const double *s, const double *z, size_t n, double z0, double mu,
                              size_t *seg, double *s_a, double *z_a)
{
    int found = 0;
    for (size_t j = 0; j + 1 < n; ++j)
        if (sign_of(z[j] - (z0 - mu * s[j])) != sign_of(z[j + 1] - (z0 - mu * s[j + 1]))) {
            *seg = j;
            found = 1;
        }
    if (!found)
        return 0;
    const size_t j = *seg;
    const double s0 = s[j], s1 = s[j + 1], zP0 = z[j], zP1 = z[j + 1];
    const double zA0 = z0 - mu * s0, zA1 = z0 - mu * s1;
    *s_a = s0 + (s1 - s0) * (zA0 - zP0) / ((zP1 - zP0) - (zA1 - zA0));
    *z_a = zP0 + (*s_a - s0) * (zP1 - zP0) / (s1 - s0);
    return 1;
}

gf_status gf_energy_line_analyse(const double *s, const double *z, const double *v2, size_t n,
                                 double mu, double g, double csz, gf_energy_line *out)
{
    gf_status st;
    if (!s || !z || !v2 || !out)
        return gf_fail(GF_EINVAL, "gf_energy_line_analyse: null pointer");
    if (n < 2)
        return gf_fail(GF_EINVAL, "gf_energy_line_analyse: %zu points, at least 2 needed", n);
    if ((st = gf_check_range("energy line friction coefficient mu", mu, 0.0, HUGE_VAL)) ||
        (st = gf_check_range("energy line gravity g", g, 1e-300, HUGE_VAL)) ||
        (st = gf_check_range("energy line cell size csz", csz, 1e-300, HUGE_VAL)))
        return st;
    for (size_t k = 0; k < n; ++k) {
        if (!isfinite(s[k]) || !isfinite(z[k]) || !isfinite(v2[k]))
            return gf_fail(GF_ENONFINITE,
                           "energy line: point %zu (s %g, z %g, v2 %g) is not finite", k, s[k],
                           z[k], v2[k]);
        if (v2[k] < 0.0)
            return gf_fail(GF_EDOM, "energy line: point %zu has a negative mean(u^2) = %g", k,
                           v2[k]);
    }
    const double s_end = s[n - 1], z_end = z[n - 1], z0 = z[0];
    if (!(s_end > s[0]))
        return gf_fail(GF_EDOM,
                       "energy line: the path did not move forward (s_end = %g <= s_0 = %g)",
                       s_end, s[0]);
    gf_energy_line r = {0};
    r.gamma = atan(fabs(z_end - z0) / (s_end - s[0]));
    r.err_angle = r.gamma - atan(mu);
    double sum = 0.0;
    for (size_t k = 0; k < n; ++k) {
        const double e = z[k] + v2[k] / (2.0 * g) - (z0 - mu * s[k]);
        sum += e * e;
    }
    r.rmse_v = sqrt(sum / (double)n);

    /* the path extended by one point at (1 + k) s_end, z_end + k p s_end,
     * k = 0 .. 3, until an intersection other than the trivial one at the
     * start (the first point lies on the alpha line) appears */
    double *se = malloc((n + 1) * sizeof *se), *ze = malloc((n + 1) * sizeof *ze);
    if (!se || !ze) {
        free(se);
        free(ze);
        return gf_fail(GF_ENOMEM, "gf_energy_line_analyse: out of memory");
    }
    for (size_t k = 0; k < n; ++k) {
        se[k] = s[k];
        ze[k] = z[k];
    }
    double p = 0.0;
    int have_p = 0, done = 0;
    for (int k = 0; k <= 3 && !done; ++k) {
        if (k > 0 && !have_p) {
            /* least-squares slope over the points with s_end - s_j < 4 csz
             * (from the first such point on) */
            size_t j0 = n - 1;
            for (size_t j = 0; j < n; ++j)
                if (s_end - s[j] < 4.0 * csz) {
                    j0 = j;
                    break;
                }
            const double m = (double)(n - j0);
            double ms = 0.0, mz = 0.0, sss = 0.0, ssz = 0.0;
            for (size_t j = j0; j < n; ++j) {
                ms += s[j] / m;
                mz += z[j] / m;
            }
            for (size_t j = j0; j < n; ++j) {
                sss += (s[j] - ms) * (s[j] - ms);
                ssz += (s[j] - ms) * (z[j] - mz);
            }
            if (!(sss > 0.0)) {
                free(se);
                free(ze);
                return gf_fail(GF_EDOM,
                               "energy line: the path ends below the alpha line and the points "
                               "within 4 csz = %g m of its end have fewer than two distinct s: "
                               "no slope to extrapolate with",
                               4.0 * csz);
            }
            p = ssz / sss;
            have_p = 1;
        }
        se[n] = (1.0 + k) * s_end;
        ze[n] = k > 0 ? z_end + k * p * s_end : z_end;
        size_t seg;
        double sa, za;
        if (alpha_intersection(se, ze, n + 1, z0, mu, &seg, &sa, &za) &&
            !(seg == 0 && sa == s[0])) {
            r.s_alpha = sa;
            r.z_alpha = za;
            r.extrapolated = k > 0;
            done = 1;
        }
    }
    free(se);
    free(ze);
    if (!done) {
        r.s_alpha = r.z_alpha = r.err_s = r.err_z = NAN;
        r.extrapolated = 1;
        *out = r;
        return gf_fail(GF_ENOCONV,
                       "energy line: no intersection with the alpha line (tan alpha = %g) up to "
                       "4 s_end = %g m, even on the extrapolated path (slope %g)",
                       mu, 4.0 * s_end, p);
    }
    r.err_s = s_end - r.s_alpha;
    r.err_z = z_end - r.z_alpha;
    *out = r;
    return GF_SUCCESS;
}

void gf_path_moments(size_t n, const int *faces, const double *area, const double *centre,
                     const double *h, const double *mom, double h_dry, const double g[3], double out[6])
{
    const double gn = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    const double e[3] = {g[0] / gn, g[1] / gn, g[2] / gn};
    for (int k = 0; k < 6; ++k)
        out[k] = 0.0;
    for (size_t i = 0; i < n; ++i) {
        const size_t f = faces ? (size_t)faces[i] : i;
        if (!(h[f] > 0.0))
            continue;
        const double *m = mom + 3 * f, *x = centre + 3 * f, a = area[f];
        const double v = a * h[f];
        out[0] += v;
        out[1] += v * x[0], out[2] += v * x[1], out[3] += v * x[2];
        if (!(h[f] > h_dry))
            continue; /* a film without velocity (the kernel's u = 0 there) */
        const double me = m[0] * e[0] + m[1] * e[1] + m[2] * e[2];
        const double mh[3] = {m[0] - me * e[0], m[1] - me * e[1], m[2] - me * e[2]};
        out[4] += a * (m[0] * m[0] + m[1] * m[1] + m[2] * m[2]) / h[f];
        out[5] += a * sqrt(mh[0] * mh[0] + mh[1] * mh[1] + mh[2] * mh[2]);
    }
}

gf_status gf_grid_rotate_back(int nx, int ny, const double gt[6], const double *v, double angle_deg, double cx,
                              double cy, double *out)
{
    if (!gt || !v || !out || nx < 1 || ny < 1)
        return gf_fail(GF_EINVAL, "gf_grid_rotate_back: null pointer or empty grid (%d x %d)", nx, ny);
    if (gt[2] != 0.0 || gt[4] != 0.0 || !(fabs(gt[1]) > 0.0) || !(fabs(gt[5]) > 0.0) || !isfinite(gt[1]) ||
        !isfinite(gt[5]) || !isfinite(gt[0]) || !isfinite(gt[3]))
        return gf_fail(GF_EDOM, "gf_grid_rotate_back: the grid is not north-up with finite cells");
    if (!isfinite(angle_deg) || !isfinite(cx) || !isfinite(cy))
        return gf_fail(GF_EDOM, "gf_grid_rotate_back: angle %g deg or centre (%g, %g) not finite", angle_deg, cx,
                       cy);
    const double a = angle_deg * (3.14159265358979323846 / 180.0), c = cos(a), s = sin(a);
    for (int row = 0; row < ny; ++row)
        for (int col = 0; col < nx; ++col) {
            const double x = gt[0] + (col + 0.5) * gt[1] - cx, y = gt[3] + (row + 0.5) * gt[5] - cy;
            /* clockwise by a: (x, y) -> (x cos a + y sin a, -x sin a + y cos a) */
            const double xr = cx + x * c + y * s, yr = cy - x * s + y * c;
            double fc = (xr - gt[0]) / gt[1] - 0.5, fr = (yr - gt[3]) / gt[5] - 0.5;
            /* on a centre line to round-off (a quarter turn): on it, so that
             * the neighbour across takes no weight (nor its NaN) */
            if (fabs(fc - round(fc)) < 1e-9)
                fc = round(fc);
            if (fabs(fr - round(fr)) < 1e-9)
                fr = round(fr);
            double *o = out + (size_t)row * (size_t)nx + (size_t)col;
            /* within half a millionth of a cell of the last centre counts as on it */
            const double eps = 1e-6;
            if (fc < -eps || fr < -eps || fc > nx - 1 + eps || fr > ny - 1 + eps) {
                *o = NAN;
                continue;
            }
            int c0 = (int)floor(fc), r0 = (int)floor(fr);
            c0 = c0 < 0 ? 0 : c0 > nx - 2 ? (nx > 1 ? nx - 2 : 0) : c0;
            r0 = r0 < 0 ? 0 : r0 > ny - 2 ? (ny > 1 ? ny - 2 : 0) : r0;
            const int c1 = nx > 1 ? c0 + 1 : c0, r1 = ny > 1 ? r0 + 1 : r0;
            const double tc = nx > 1 ? fc - c0 : 0.0, tr = ny > 1 ? fr - r0 : 0.0;
            const double v00 = v[(size_t)r0 * nx + c0], v01 = v[(size_t)r0 * nx + c1];
            const double v10 = v[(size_t)r1 * nx + c0], v11 = v[(size_t)r1 * nx + c1];
            /* a neighbour of weight 0 does not count (its NaN neither) */
            const double w00 = (1 - tr) * (1 - tc), w01 = (1 - tr) * tc, w10 = tr * (1 - tc), w11 = tr * tc;
            *o = (w00 > 0 ? w00 * v00 : 0.0) + (w01 > 0 ? w01 * v01 : 0.0) + (w10 > 0 ? w10 * v10 : 0.0) +
                 (w11 > 0 ? w11 * v11 : 0.0);
        }
    return GF_SUCCESS;
}
