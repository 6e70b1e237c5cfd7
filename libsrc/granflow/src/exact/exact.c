/* SPDX-License-Identifier: GPL-3.0-or-later */
#include "granflow/exact.h"
#include "internal.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_roots.h>
#include <math.h>

/* Toro's depth function with beta in place of g. */
/* Root of F in the bracket [lo, hi] by GSL's Brent solver, iterated until
 * gsl_root_test_interval(epsabs, epsrel) holds (at most 200 iterations).
 * `what` names the problem in the GF_ENOMEM message; `nonconv` is the
 * GF_ENOCONV message. */
static gf_status brent_root(gsl_function *F, double lo, double hi, double epsabs, double epsrel,
                            const char *what, const char *nonconv, double *root)
{
    gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    if (!s)
        return gf_fail(GF_ENOMEM, "%s: out of memory", what);
    gsl_root_fsolver_set(s, F, lo, hi);
    int status = GSL_CONTINUE;
    for (int it = 0; it < 200 && status == GSL_CONTINUE; ++it) {
        gsl_root_fsolver_iterate(s);
        status = gsl_root_test_interval(gsl_root_fsolver_x_lower(s), gsl_root_fsolver_x_upper(s),
                                        epsabs, epsrel);
    }
    *root = gsl_root_fsolver_root(s);
    gsl_root_fsolver_free(s);
    if (status != GSL_SUCCESS)
        return gf_fail(GF_ENOCONV, "%s", nonconv);
    return GF_SUCCESS;
}

static double fk(double beta, double h, double hk)
{
    if (h <= hk)
        return 2.0 * (sqrt(beta * h) - sqrt(beta * hk));
    return (h - hk) * sqrt(0.5 * beta * (h + hk) / (h * hk));
}

static double riemann_fn(double h, void *params)
{
    const gf_riemann *rp = params;
    return fk(rp->beta, h, rp->hl) + fk(rp->beta, h, rp->hr) + rp->ur - rp->ul;
}

gf_status gf_riemann_solve(gf_riemann *rp, double beta, double hl, double ul, double hr,
                           double ur, double x0)
{
    gf_status st;
    if (!rp)
        return gf_fail(GF_EINVAL, "gf_riemann_solve: null pointer");
    if ((st = gf_check_range("Riemann problem beta", beta, 1e-300, HUGE_VAL)) ||
        (st = gf_check_range("Riemann problem left depth h_l", hl, 0.0, HUGE_VAL)) ||
        (st = gf_check_range("Riemann problem right depth h_r", hr, 0.0, HUGE_VAL)) ||
        (st = gf_check_range("Riemann problem left velocity u_l", ul, -HUGE_VAL, HUGE_VAL)) ||
        (st = gf_check_range("Riemann problem right velocity u_r", ur, -HUGE_VAL, HUGE_VAL)) ||
        (st = gf_check_range("Riemann problem position x0", x0, -HUGE_VAL, HUGE_VAL)))
        return st;
    rp->beta = beta;
    rp->hl = hl;
    rp->ul = ul;
    rp->hr = hr;
    rp->ur = ur;
    rp->x0 = x0;
    rp->hm = rp->um = 0.0;
    rp->vacuum = 0;
    const double cl = sqrt(beta * hl), cr = sqrt(beta * hr);
    if (hl == 0.0 || hr == 0.0 || 2.0 * (cl + cr) <= ur - ul) {
        rp->vacuum = 1; /* dry side(s) or vacuum generated in the middle */
        return GF_SUCCESS;
    }
    /* f is increasing in h; f(0) < 0 here.  Bracket the root. */
    double lo = 0.0, hi = fmax(hl, hr);
    int expand = 0;
    while (riemann_fn(hi, rp) < 0.0) {
        lo = hi;
        hi *= 2.0;
        if (++expand > 200)
            return gf_fail(GF_ENOCONV, "Riemann problem: could not bracket the middle depth");
    }
    gsl_function F = {riemann_fn, rp};
    double hm;
    st = brent_root(&F, lo, hi, 0.0, 4e-16, "Riemann problem",
                    "Riemann problem: Brent iteration did not converge", &hm);
    if (st)
        return st;
    rp->hm = hm;
    rp->um = 0.5 * (ul + ur) + 0.5 * (fk(beta, hm, hr) - fk(beta, hm, hl));
    return GF_SUCCESS;
}

void gf_riemann_sample(const gf_riemann *rp, double x, double t, double *h, double *u)
{
    const double beta = rp->beta;
    if (t <= 0.0) {
        *h = x <= rp->x0 ? rp->hl : rp->hr;
        *u = x <= rp->x0 ? rp->ul : rp->ur;
        return;
    }
    const double S = (x - rp->x0) / t;
    const double cl = sqrt(beta * rp->hl), cr = sqrt(beta * rp->hr);

    if (rp->vacuum) {
        /* left wave: rarefaction into dry bed, tail u_l - c_l, head u_l + 2c_l */
        if (rp->hl > 0.0) {
            const double head = rp->ul + 2.0 * cl;
            if (S <= rp->ul - cl) {
                *h = rp->hl;
                *u = rp->ul;
                return;
            }
            if (S < head) {
                const double c = (rp->ul + 2.0 * cl - S) / 3.0;
                *h = c * c / beta;
                *u = (rp->ul + 2.0 * cl + 2.0 * S) / 3.0;
                return;
            }
        }
        if (rp->hr > 0.0) {
            const double head = rp->ur - 2.0 * cr;
            if (S >= rp->ur + cr) {
                *h = rp->hr;
                *u = rp->ur;
                return;
            }
            if (S > head) {
                const double c = (-rp->ur + 2.0 * cr + S) / 3.0;
                *h = c * c / beta;
                *u = (rp->ur - 2.0 * cr + 2.0 * S) / 3.0;
                return;
            }
        }
        *h = 0.0;
        *u = 0.0;
        return;
    }

    const double hm = rp->hm, um = rp->um, cm = sqrt(beta * hm);
    if (S <= um) { /* left of the contact: left wave */
        if (hm > rp->hl) { /* left shock */
            const double ql = sqrt(0.5 * (hm + rp->hl) * hm / (rp->hl * rp->hl));
            const double sl = rp->ul - cl * ql;
            if (S <= sl) {
                *h = rp->hl;
                *u = rp->ul;
            } else {
                *h = hm;
                *u = um;
            }
        } else { /* left rarefaction */
            if (S <= rp->ul - cl) {
                *h = rp->hl;
                *u = rp->ul;
            } else if (S >= um - cm) {
                *h = hm;
                *u = um;
            } else {
                const double c = (rp->ul + 2.0 * cl - S) / 3.0;
                *h = c * c / beta;
                *u = (rp->ul + 2.0 * cl + 2.0 * S) / 3.0;
            }
        }
    } else { /* right wave */
        if (hm > rp->hr) { /* right shock */
            const double qr = sqrt(0.5 * (hm + rp->hr) * hm / (rp->hr * rp->hr));
            const double sr = rp->ur + cr * qr;
            if (S >= sr) {
                *h = rp->hr;
                *u = rp->ur;
            } else {
                *h = hm;
                *u = um;
            }
        } else { /* right rarefaction */
            if (S >= rp->ur + cr) {
                *h = rp->hr;
                *u = rp->ur;
            } else if (S <= um + cm) {
                *h = hm;
                *u = um;
            } else {
                const double c = (-rp->ur + 2.0 * cr + S) / 3.0;
                *h = c * c / beta;
                *u = (rp->ur - 2.0 * cr + 2.0 * S) / 3.0;
            }
        }
    }
}

/* ---- Dressler's dam break with Chezy friction (see exact.h) ------------- */

static double dressler_a1(double xi)
{
    const double s = 2.0 - xi;
    return 6.0 / (5.0 * s) - 2.0 / 3.0 + 4.0 * sqrt(3.0) / 135.0 * s * sqrt(s);
}

static double dressler_a2(double xi)
{
    const double s = 2.0 - xi;
    return 12.0 / s - 8.0 / 3.0 + 8.0 * sqrt(3.0) / 189.0 * s * sqrt(s) - 108.0 / (7.0 * s * s);
}

/* d a2 / d xi */
static double dressler_da2(double xi)
{
    const double s = 2.0 - xi;
    return 12.0 / (s * s) - 4.0 * sqrt(3.0) / 63.0 * sqrt(s) - 216.0 / (7.0 * s * s * s);
}

gf_status gf_dressler_init(gf_dressler *d, double g, double hl, double chezy, double x0)
{
    gf_status st;
    if (!d)
        return gf_fail(GF_EINVAL, "gf_dressler_init: null pointer");
    if ((st = gf_check_range("Dressler dam break g", g, 1e-300, HUGE_VAL)) ||
        (st = gf_check_range("Dressler dam break reservoir depth h_l", hl, 1e-300, HUGE_VAL)) ||
        (st = gf_check_range("Dressler dam break Chezy coefficient C", chezy, 1e-300, HUGE_VAL)) ||
        (st = gf_check_range("Dressler dam break position x0", x0, -HUGE_VAL, HUGE_VAL)))
        return st;
    *d = (gf_dressler){.g = g, .hl = hl, .chezy = chezy, .x0 = x0};
    d->t = NAN; /* no time yet: the first sample computes its tip */
    return GF_SUCCESS;
}

/* radicand c = sqrt(g h) of the outer depth, u of the outer region */
static void dressler_outer_cu(const gf_dressler *d, double X, double t, double *c, double *u)
{
    const double c0 = sqrt(d->g * d->hl), xi = X / (c0 * t);
    const double f = d->g * d->g * t / (d->chezy * d->chezy);
    *c = 2.0 * c0 / 3.0 - X / (3.0 * t) + f * dressler_a1(xi);
    *u = 2.0 * c0 / 3.0 + 2.0 * X / (3.0 * t) + f * dressler_a2(xi);
}

void gf_dressler_outer(const gf_dressler *d, double x, double t, double *h, double *u)
{
    const double X = x - d->x0, c0 = sqrt(d->g * d->hl);
    if (t <= 0.0 || X <= -c0 * t) {
        *h = X <= 0.0 ? d->hl : 0.0;
        *u = 0.0;
        return;
    }
    if (X >= 2.0 * c0 * t) { /* beyond Ritter's front: dry (a1, a2 need xi < 2) */
        *h = 0.0;
        *u = 0.0;
        return;
    }
    double c;
    dressler_outer_cu(d, X, t, &c, u);
    *h = c > 0.0 ? c * c / d->g : 0.0;
}

typedef struct {
    const gf_dressler *d;
    double t;
} dressler_at_t;

static double dressler_dudxi(double xi, void *p)
{
    const dressler_at_t *a = p;
    const double c0 = sqrt(a->d->g * a->d->hl);
    const double f = a->d->g * a->d->g * a->t / (a->d->chezy * a->d->chezy);
    return 2.0 * c0 / 3.0 + f * dressler_da2(xi); /* c0 t du/dX */
}

static double dressler_h_of_X(double X, void *p)
{
    const dressler_at_t *a = p;
    double c, u;
    dressler_outer_cu(a->d, X, a->t, &c, &u);
    return c * c / a->d->g;
}

gf_status gf_dressler_at(gf_dressler *d, double t)
{
    if (!d)
        return gf_fail(GF_EINVAL, "gf_dressler_at: null pointer");
    gf_status st = gf_check_range("Dressler dam break time t", t, 1e-300, HUGE_VAL);
    if (st)
        return st;
    const double c0 = sqrt(d->g * d->hl);
    dressler_at_t a = {d, t};
    /* du/dxi > 0 at xi = -1 (a2'(-1) = 0) and -> -inf at xi -> 2: the tip is
     * the first sign change, found on a grid and refined by Brent. */
    double lo = -1.0, hi = -1.0;
    const int n = 3000;
    for (int i = 1; i <= n; ++i) {
        hi = -1.0 + 3.0 * i / (n + 1.0);
        if (dressler_dudxi(hi, &a) <= 0.0)
            break;
        lo = hi;
    }
    /* weak friction: the maximum sits very near xi = 2; approach it in s = 2 - xi */
    for (double sg = 2.0 - hi; dressler_dudxi(hi, &a) > 0.0; sg *= 0.1) {
        if (sg < 1e-12)
            return gf_fail(GF_EDOM,
                           "Dressler dam break: Chezy C = %g gives no velocity maximum before "
                           "Ritter's front at t = %g (friction too weak for the expansion; the "
                           "frictionless solution is Ritter's)",
                           d->chezy, t);
        lo = hi;
        hi = 2.0 - sg;
    }
    gsl_function F = {dressler_dudxi, &a};
    double xi_tip;
    st = brent_root(&F, lo, hi, 1e-15, 0.0, "Dressler dam break",
                    "Dressler dam break: tip position did not converge", &xi_tip);
    if (st)
        return st;
    const double X_tip = xi_tip * c0 * t;
    double c, u;
    dressler_outer_cu(d, X_tip, t, &c, &u);
    /* the outer depth must stay positive up to the tip */
    for (int i = 0; i <= 200; ++i) {
        double ci, ui;
        dressler_outer_cu(d, -c0 * t + (X_tip + c0 * t) * i / 200.0, t, &ci, &ui);
        if (ci <= 0.0)
            return gf_fail(GF_EDOM,
                           "Dressler dam break: t = %g is outside the first-order expansion "
                           "(g^2 t / C^2 = %g against sqrt(g h_l) = %g): negative depth",
                           t, d->g * d->g * t / (d->chezy * d->chezy), c0);
    }
    /* volume of the outer region, -c0 t < X < X_tip */
    gsl_integration_workspace *w = gsl_integration_workspace_alloc(200);
    if (!w)
        return gf_fail(GF_ENOMEM, "Dressler dam break: out of memory");
    gsl_function H = {dressler_h_of_X, &a};
    double vol, err;
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    const int status = gsl_integration_qag(&H, -c0 * t, X_tip, 0.0, 1e-13, 200,
                                           GSL_INTEG_GAUSS31, w, &vol, &err);
    gsl_set_error_handler(old);
    gsl_integration_workspace_free(w);
    if (status)
        return gf_fail(GF_EGSL, "Dressler dam break: outer volume integral: %s",
                       gsl_strerror(status));
    /* the released volume h_l c0 t (the rarefaction's deficit left of x0) */
    const double tip = d->hl * c0 * t - vol;
    if (!(tip > 0.0))
        return gf_fail(GF_EDOM,
                       "Dressler dam break: t = %g is outside the first-order expansion: the "
                       "outer region holds more than the released volume",
                       t);
    /* h = (u/C) sqrt(2 (X_f - X)): volume (2 sqrt2 / 3) (u/C) L^(3/2) */
    const double L = pow(3.0 * tip * d->chezy / (2.0 * sqrt(2.0) * u), 2.0 / 3.0);
    if (X_tip + L >= 2.0 * c0 * t)
        return gf_fail(GF_EDOM,
                       "Dressler dam break: t = %g is outside the first-order expansion "
                       "(g^2 t / C^2 = %g against sqrt(g h_l) = %g): the front would run ahead "
                       "of the frictionless (Ritter) front",
                       t, d->g * d->g * t / (d->chezy * d->chezy), c0);
    d->t = t;
    d->x_tip = d->x0 + X_tip;
    d->u_tip = u;
    d->h_tip = c * c / d->g;
    d->x_front = d->x_tip + L;
    return GF_SUCCESS;
}

gf_status gf_dressler_sample(gf_dressler *d, double x, double t, double *h, double *u)
{
    if (!(d->t == t)) {
        const gf_status st = gf_dressler_at(d, t);
        if (st)
            return st;
    }
    if (x < d->x_tip) {
        gf_dressler_outer(d, x, d->t, h, u);
    } else if (x < d->x_front) {
        *u = d->u_tip;
        *h = d->u_tip / d->chezy * sqrt(2.0 * (d->x_front - x));
    } else {
        *h = 0.0;
        *u = 0.0;
    }
    return GF_SUCCESS;
}

/* ---- spreading parabolic cap ------------------------------------------------ */
gf_status gf_spreading_cap_init(gf_spreading_cap *c, double beta, double h0, double l0, double x0)
{
    gf_status st;
    if (!c)
        return gf_fail(GF_EINVAL, "gf_spreading_cap_init: null argument");
    if ((st = gf_check_range("spreading cap beta", beta, 1e-300, 1e300)) ||
        (st = gf_check_range("spreading cap depth h0", h0, 1e-300, 1e300)) ||
        (st = gf_check_range("spreading cap half-width l0", l0, 1e-300, 1e300)) ||
        (st = gf_check_range("spreading cap centre x0", x0, -1e300, 1e300)))
        return st;
    c->beta = beta;
    c->h0 = h0;
    c->l0 = l0;
    c->x0 = x0;
    return GF_SUCCESS;
}

typedef struct { double t, s2k; } cap_time;

/* t(lam) - t of the energy integral, lam = 1 + m^2 (m >= 0 keeps it smooth at 1) */
static double cap_time_fn(double m, void *params)
{
    const cap_time *p = params;
    const double lam = 1.0 + m * m;
    return (sqrt(lam) * m + asinh(m)) / p->s2k - p->t;
}

gf_status gf_spreading_cap_stretch(const gf_spreading_cap *c, double t, double *lam, double *dlam)
{
    if (!(t >= 0.0) || !isfinite(t))
        return gf_fail(GF_EDOM, "spreading cap: time t = %g must be finite and >= 0", t);
    const double k = 2.0 * c->beta * c->h0 / (c->l0 * c->l0), s2k = sqrt(2.0 * k);
    double m = 0.0;
    if (t > 0.0) {
        cap_time p = {t, s2k};
        gsl_function F = {cap_time_fn, &p};
        double hi = 1.0;
        while (cap_time_fn(hi, &p) < 0.0)
            hi *= 2.0;
        gf_status st = brent_root(&F, 0.0, hi, 0.0, 4e-16, "spreading cap",
                                  "spreading cap: Brent iteration did not converge", &m);
        if (st)
            return st;
    }
    *lam = 1.0 + m * m;
    *dlam = s2k * sqrt(1.0 - 1.0 / *lam);
    return GF_SUCCESS;
}

gf_status gf_spreading_cap_sample(const gf_spreading_cap *c, double x, double t, double *h,
                                  double *u)
{
    double lam, dlam;
    gf_status st = gf_spreading_cap_stretch(c, t, &lam, &dlam);
    if (st)
        return st;
    const double X = x - c->x0, eta = X / (lam * c->l0);
    if (fabs(eta) >= 1.0) {
        *h = *u = 0.0;
        return GF_SUCCESS;
    }
    *h = c->h0 / lam * (1.0 - eta * eta);
    *u = X * dlam / lam;
    return GF_SUCCESS;
}
