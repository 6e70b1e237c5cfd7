/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Verification helpers (granflow/verification.h). */
#include "granflow/verification.h"
#include "internal.h"
#include "sh1d_internal.h"

#include <math.h>

double gf_sh1d_l1_difference(const gf_sh1d *a, const gf_sh1d *b)
{
    double x5[5], w5[5];
    if (gf_gauss_legendre5(x5, w5))
        return NAN;
    double e = 0.0;
    for (size_t i = 0; i < a->n; ++i)
        for (int g = 0; g < 5; ++g) {
            const double x = gf_sh1d_cell_centre(a, i) + 0.5 * a->dx * x5[g];
            double ha, ua, hb, ub;
            if (gf_sh1d_eval(a, x, &ha, &ua) || gf_sh1d_eval(b, x, &hb, &ub))
                return NAN;
            e += 0.5 * a->dx * w5[g] * fabs(ha - hb);
        }
    return e;
}

typedef struct { const gf_riemann *rp; double t; } riemann_at;
static double riemann_depth(double x, void *ctx)
{
    const riemann_at *r = ctx;
    double h, u;
    gf_riemann_sample(r->rp, x, r->t, &h, &u);
    return h;
}

double gf_sh1d_l1_error_riemann(const gf_sh1d *s, const gf_riemann *exact, double t)
{
    double *h = s->scratch, e = 0.0;
    gf_sh1d_means(s, h, h + s->n);
    for (size_t i = 0; i < s->n; ++i) {
        double mean = 0.0;
        for (int k = 0; k < 16; ++k) {
            double he, ue;
            gf_riemann_sample(exact, gf_sh1d_cell_centre(s, i) + s->dx * ((k + 0.5) / 16.0 - 0.5), t,
                              &he, &ue);
            mean += he / 16.0;
        }
        e += fabs(h[i] - mean) * s->dx;
    }
    /* the moving mesh: the exact depth beyond its ends, where it is dry */
    riemann_at rt = {exact, t};
    return e + gf_sh1d_depth_beyond(s, riemann_depth, &rt, 16 * s->n);
}

double gf_sh1d_depth_beyond(const gf_sh1d *s, double (*depth)(double x, void *ctx), void *ctx, size_t samples)
{
    double lo, hi, e = 0.0;
    gf_sh1d_extent(s, &lo, &hi);
    for (int side = 0; side < 2; ++side) {
        const double a = side ? hi : s->cfg.x_min, b = side ? s->cfg.x_max : lo;
        for (size_t k = 0; k < samples && b > a; ++k)
            e += depth(a + (b - a) * ((double)k + 0.5) / (double)samples, ctx) * (b - a) / (double)samples;
    }
    return e;
}
