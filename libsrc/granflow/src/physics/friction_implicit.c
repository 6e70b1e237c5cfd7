/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The implicit friction update's speed, law by law (friction_implicit.h):
 * the solvers of h s + dt tau(s) = M behind gf_friction_implicit_speed, and
 * its named failure.  Calls only down, into the laws (friction.c, through
 * friction.h); the inline entry that calls these (friction_speed.h) sits
 * above. */
#include "granflow/friction.h"
#include "internal.h"
#include "friction_implicit.h"
#include "simd4.h"

#include <math.h>

/* tau(s) of the law at state st with speed s; no argument checks (done once
 * by the caller). */
static double tau_at(const gf_friction *f, const gf_friction_state *st, double s)
{
    gf_friction_state x = *st;
    x.speed = s;
    gf_friction_result r;
    f->type->eval(f->p, &x, &r);
    return r.tau;
}

gf_status gf_friction_implicit_speed_fail(const gf_friction_state *s, double M, double dt)
{
    gf_status st;
    if ((st = gf_check_range("flow thickness h", s->h, 1e-300, HUGE_VAL)) ||
        (st = gf_check_range("trial momentum |h u|", M, 0.0, HUGE_VAL)) ||
        (st = gf_check_range("time step dt", dt, 0.0, HUGE_VAL)) ||
        (st = gf_check_range("density rho", s->rho, 1e-300, HUGE_VAL)) ||
        (st = gf_check_range("gravity g", s->g, 0.0, HUGE_VAL)))
        return st;
    return gf_fail(GF_ENONFINITE, "basal pressure p_b = %g is not a finite number", s->pb);
}

gf_status gf_friction_implicit_speed_laws(const gf_friction *f, const gf_friction_state *s, double M, double dt,
                                          double *speed)
{
    const double h = s->h;
    /* Coulomb with u0 > 0: h s + dt mu p s/(s + u0) = M, i.e. h s^2 + (h u0 + dt mu p - M) s - M u0 = 0
     * (u0 = 0: gf_friction_implicit_speed_inline, friction_speed.h) */
    if (f->type == gf_friction_coulomb) {
        const double mp = gf_friction_coulomb_mp(f, s), u0 = f->p[1];
        const double b = h * u0 + dt * mp - M;
        /* positive root, written without cancellation */
        const double disc = sqrt(b * b + 4.0 * h * M * u0);
        *speed = b < 0.0 ? (disc - b) / (2.0 * h) : 2.0 * M * u0 / (disc + b);
        return GF_SUCCESS;
    }
    /* mu(I), u0 = 0: tau = p (mu_s + (mu_2 - mu_s) k s/(A + k s)), k = 5/2 d,
     * A = I_0 h sqrt(p_b/rho_p) (eqs. 24-26); times (A + k s) the equation
     * is the quadratic h k s^2 + (h A + dt p mu_2 k - M k) s + A (dt p mu_s - M) = 0 */
    if (f->type == gf_friction_mu_i && f->p[5] == 0.0 && s->pb > 0.0) {
        const double p = s->pb / s->rho, mus = f->p[0], mu2 = f->p[1], k = 2.5 * f->p[3];
        const double A = f->p[2] * h * sqrt(s->pb / f->p[4]);
        if (dt * p * mus >= M) {
            *speed = 0.0;
            return GF_SUCCESS;
        }
        const double a2 = h * k, a1 = h * A + dt * p * mu2 * k - M * k, a0 = A * (dt * p * mus - M);
        const double disc = sqrt(a1 * a1 - 4.0 * a2 * a0); /* a0 < 0: two real roots, one > 0 */
        *speed = a1 < 0.0 ? (disc - a1) / (2.0 * a2) : -2.0 * a0 / (disc + a1);
        return GF_SUCCESS;
    }
    /* voellmy, u0 = 0: h s + dt (mu p + g s^2/xi) = M, a quadratic with
     * a2 = dt g/xi, a1 = h, a0 = dt mu p - M < 0 for a moving face */
    if (f->type == gf_friction_voellmy && f->p[2] == 0.0) {
        const double mp = s->pb > 0.0 ? f->p[0] * s->pb / s->rho : 0.0, a0 = dt * mp - M;
        if (a0 >= 0.0) {
            *speed = 0.0;
            return GF_SUCCESS;
        }
        const double a2 = dt * s->g / f->p[1];
        *speed = -2.0 * a0 / (h + sqrt(h * h - 4.0 * a2 * a0));
        return GF_SUCCESS;
    }
    /* samosAT, u0 = 0: for s > 0 tau = t0 + A (1 + Rs0/(Rs0 + c s^2)) + cd s^2
     * (t0 = tau0/rho and A = mu p_b/rho with contact, c = rho/(p_b + 0.001),
     * cd the drag coefficient; the law's eval), at rest t0 + 2 A.  Newton on
     * g(s) = h s + dt tau(s) - M, kept inside the bracket [lo, hi] of
     * [0, M/h] (bisection when a step leaves it): a few iterations where
     * regula falsi needs tens, each without the law's logarithm. */
    if (f->type == gf_friction_samosat && f->p[6] == 0.0) {
        const double sig = s->pb > 0.0 ? s->pb : 0.0, rs0 = f->p[2];
        const double A = f->p[0] * sig / s->rho, t0 = sig > 0.0 ? f->p[1] / s->rho : 0.0;
        const double c = s->rho / (sig + 0.001);
        const double lr = h > f->p[4] ? log(h / f->p[4]) : 0.0, den = lr / f->p[3] + f->p[5];
        const double cd = 1.0 / (den * den);
        if (dt * (t0 + 2.0 * A) >= M) {
            *speed = 0.0;
            return GF_SUCCESS;
        }
        double lo = 0.0, hi = M / h, x = hi;
        /* start: the root with the Coulomb factor frozen at speed M/h, a
         * quadratic; the factor only grows as the speed falls, so that root
         * is an upper bound of the true one */
        {
            const double Af = A * (1.0 + rs0 / (rs0 + c * hi * hi)), b = M - dt * (t0 + Af);
            if (b > 0.0)
                hi = x = 2.0 * b / (h + sqrt(h * h + 4.0 * dt * cd * b));
            else
                x = 0.5 * hi;
        }
        for (int it = 0; it < 100; ++it) {
            const double r = 1.0 / (rs0 + c * x * x), ar = A * rs0 * r; /* one division per iteration */
            const double gx = h * x + dt * (t0 + A + ar + cd * x * x) - M;
            if (gx == 0.0)
                break;
            if (gx < 0.0)
                lo = x;
            else
                hi = x;
            const double dg = h + dt * (2.0 * cd * x - 2.0 * ar * c * x * r);
            double xn = dg > 0.0 ? x - gx / dg : -1.0;
            const int newton = xn > lo && xn < hi;
            if (!newton)
                xn = 0.5 * (lo + hi);
            const double step = fabs(xn - x);
            x = xn;
            /* Newton converges quadratically: the error after a step d is
             * about |g''| d^2 / (2 g'), and with g' >= h/2 (dt tau'' x is at
             * most of the order of dt tau <= M = h s_max) a Newton step of at
             * most 1e-8 x leaves an error of order 1e-16 x, the last bit: the
             * next evaluation, which only confirmed it, is skipped.  A
             * bisection step never ends the loop this way. */
            if ((newton && dg >= 0.5 * h && step <= 1e-8 * x) || step <= 1e-15 * x || hi - lo <= 1e-15 * hi)
                break;
        }
        *speed = x;
        return GF_SUCCESS;
    }
    const double tau0 = tau_at(f, s, 0.0);
    if (dt * tau0 >= M) {
        *speed = 0.0;
        return GF_SUCCESS;
    }
    double lo = 0.0, hi = M / h;
    double glo = dt * tau0 - M, ghi = dt * tau_at(f, s, hi); /* g(lo) < 0 <= g(hi) */
    if (ghi <= 0.0) {
        *speed = hi;
        return GF_SUCCESS;
    }
    int side = 0;
    for (int it = 0; it < 200 && hi - lo > 1e-14 * hi; ++it) {
        /* Illinois regula falsi, with a bisection step every fourth iteration */
        double x = (it % 4 == 3) ? 0.5 * (lo + hi) : (lo * ghi - hi * glo) / (ghi - glo);
        if (!(x > lo && x < hi))
            x = 0.5 * (lo + hi);
        const double gx = h * x + dt * tau_at(f, s, x) - M;
        if (gx == 0.0) {
            lo = hi = x;
            break;
        }
        if (gx < 0.0) {
            lo = x, glo = gx;
            if (side == -1)
                ghi *= 0.5;
            side = -1;
        } else {
            hi = x, ghi = gx;
            if (side == 1)
                glo *= 0.5;
            side = 1;
        }
    }
    *speed = 0.5 * (lo + hi);
    return GF_SUCCESS;
}

/* samosAT, u0 = 0, four states at once: the scalar branch above lane by
 * lane, each operation the same in the same order (GCC vector extensions;
 * -ffp-contract=off: no fused multiply-adds on either side; IEEE division
 * and square root are exact in both), its branches as selections and its
 * loop run until every lane has left it, a lane frozen from the iteration
 * it leaves at; so each lane's speed is the scalar one bit for bit
 * (test_friction checks it).  Every lane's operations are kept finite
 * (guarded divisor and square-root argument): OpenFOAM traps floating-point
 * exceptions. */
void gf_friction_implicit_speed_samosat4(const gf_friction *f, const double h[4], const double pb[4], double rho,
                                         const double M[4], double dt, double speed[4])
{
    const double rs0 = f->p[2];
    const v4d zero = vsplat(0.0), one = vsplat(1.0), vdt = vsplat(dt), vrho = vsplat(rho), vrs0 = vsplat(rs0);
    const v4d H = {h[0], h[1], h[2], h[3]}, PB = {pb[0], pb[1], pb[2], pb[3]}, MM = {M[0], M[1], M[2], M[3]};
    const v4d sig = vsel(PB > zero, PB, zero);
    const v4d A = vsplat(f->p[0]) * sig / vrho, t0 = vsel(sig > zero, vsplat(f->p[1] / rho), zero);
    const v4d c = vrho / (sig + vsplat(0.001));
    v4d lr;
    for (int k = 0; k < 4; ++k)
        lr[k] = h[k] > f->p[4] ? log(h[k] / f->p[4]) : 0.0;
    const v4d den = lr / vsplat(f->p[3]) + vsplat(f->p[5]);
    const v4d cd = one / (den * den);
    const v4i rest = vdt * (t0 + vsplat(2.0) * A) >= MM;
    v4d lo = zero, hi = MM / H, x = hi;
    {
        const v4d Af = A * (one + vrs0 / (vrs0 + c * hi * hi)), b = MM - vdt * (t0 + Af);
        const v4i bp = b > zero;
        const v4d q = vsel(bp, H * H + vsplat(4.0) * vdt * cd * b, H * H);
        v4d sq;
        for (int k = 0; k < 4; ++k)
            sq[k] = sqrt(q[k]);
        const v4d xq = vsplat(2.0) * b / (H + sq);
        hi = vsel(bp, xq, hi);
        x = vsel(bp, xq, vsplat(0.5) * hi);
    }
    v4i act = ~rest;
    for (int it = 0; it < 100 && vany(act); ++it) {
        const v4d r = one / (vrs0 + c * x * x), ar = A * vrs0 * r;
        const v4d gx = H * x + vdt * (t0 + A + ar + cd * x * x) - MM;
        const v4i run = act & ~(gx == zero);
        const v4i neg = gx < zero;
        lo = vsel(run & neg, x, lo);
        hi = vsel(run & ~neg, x, hi);
        const v4d dg = H + vdt * (vsplat(2.0) * cd * x - vsplat(2.0) * ar * c * x * r);
        const v4i dp = dg > zero;
        v4d xn = vsel(dp, x - gx / vsel(dp, dg, one), vsplat(-1.0));
        const v4i newton = (xn > lo) & (xn < hi);
        xn = vsel(newton, xn, vsplat(0.5) * (lo + hi));
        const v4d d = xn - x, step = vsel(d < zero, -d, d);
        x = vsel(run, xn, x);
        const v4i brk = (newton & (dg >= vsplat(0.5) * H) & (step <= vsplat(1e-8) * x)) |
                        (step <= vsplat(1e-15) * x) | (hi - lo <= vsplat(1e-15) * hi);
        act = run & ~brk;
    }
    x = vsel(rest, zero, x);
    for (int k = 0; k < 4; ++k)
        speed[k] = x[k];
}
