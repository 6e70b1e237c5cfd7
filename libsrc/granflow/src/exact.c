#include "granflow/exact.h"
#include "internal.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>
#include <math.h>

double gf_sh_beta(double epsilon, double k, double zeta) { return epsilon * k * cos(zeta); }

/* Toro's depth function with beta in place of g. */
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
    gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    if (!s)
        return gf_fail(GF_ENOMEM, "Riemann problem: out of memory");
    gsl_root_fsolver_set(s, &F, lo, hi);
    int status = GSL_CONTINUE;
    for (int it = 0; it < 200 && status == GSL_CONTINUE; ++it) {
        gsl_root_fsolver_iterate(s);
        lo = gsl_root_fsolver_x_lower(s);
        hi = gsl_root_fsolver_x_upper(s);
        status = gsl_root_test_interval(lo, hi, 0.0, 4e-16);
    }
    const double hm = gsl_root_fsolver_root(s);
    gsl_root_fsolver_free(s);
    if (status != GSL_SUCCESS)
        return gf_fail(GF_ENOCONV, "Riemann problem: Brent iteration did not converge");
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
