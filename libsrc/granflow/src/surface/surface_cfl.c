/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The step bound of the surface scheme (gf_surface_max_dt): the Courant
 * condition of positivity from HLL's outgoing wave speeds. */
#include "surface_internal.h"
#include "surface_active.h"
#include "surface_flux.h"
#include "surface_halo.h"
#include "surface_simd.h"

#ifdef __AVX__

/* The step bound's outgoing rates (gf_surface_max_dt) of four internal
 * edges, one per lane: velocity, the frame's normal components, sqrt(a h)
 * and hll_speeds with the same operations in the same order as the scalar
 * loop, branches as selections, so each lane's rates are the scalar ones
 * bit for bit. */
static void edge_speeds4(gf_surface *s, const int *q)
{
    const gf_surface_mesh *m = &s->m;
    v4d FA[4], FB[4];
    {
        const double *f0 = s->frame + EF * q[0], *f1 = s->frame + EF * q[1], *f2 = s->frame + EF * q[2],
                     *f3 = s->frame + EF * q[3];
        transpose4(vload(f0), vload(f1), vload(f2), vload(f3), FA);
        transpose4(vload(f0 + 4), vload(f1 + 4), vload(f2 + 4), vload(f3 + 4), FB);
    }
    const int o0 = m->owner[q[0]], o1 = m->owner[q[1]], o2 = m->owner[q[2]], o3 = m->owner[q[3]];
    const int n0 = m->neighbour[q[0]], n1 = m->neighbour[q[1]], n2 = m->neighbour[q[2]], n3 = m->neighbour[q[3]];
    const double *h = s->h, *M = s->mom, *a = s->a;
    const v4d zero = vsplat(0.0), one = vsplat(1.0), hd = vsplat(s->c.h_dry);
    const v4d hl = {h[o0], h[o1], h[o2], h[o3]}, hr = {h[n0], h[n1], h[n2], h[n3]};
    /* velocity(): M / h (r = 1 / h) where h > h_dry, else 0 */
    const v4i wl = hl > hd, wr = hr > hd;
    const v4d rl = one / vsel(wl, hl, one), rr = one / vsel(wr, hr, one);
    const v4d uo0 = vsel(wl, (v4d){M[3 * o0], M[3 * o1], M[3 * o2], M[3 * o3]} * rl, zero);
    const v4d uo1 = vsel(wl, (v4d){M[3 * o0 + 1], M[3 * o1 + 1], M[3 * o2 + 1], M[3 * o3 + 1]} * rl, zero);
    const v4d uo2 = vsel(wl, (v4d){M[3 * o0 + 2], M[3 * o1 + 2], M[3 * o2 + 2], M[3 * o3 + 2]} * rl, zero);
    const v4d un0 = vsel(wr, (v4d){M[3 * n0], M[3 * n1], M[3 * n2], M[3 * n3]} * rr, zero);
    const v4d un1 = vsel(wr, (v4d){M[3 * n0 + 1], M[3 * n1 + 1], M[3 * n2 + 1], M[3 * n3 + 1]} * rr, zero);
    const v4d un2 = vsel(wr, (v4d){M[3 * n0 + 2], M[3 * n1 + 2], M[3 * n2 + 2], M[3 * n3 + 2]} * rr, zero);
    /* dot3(uo, nu_L), dot3(un, nu_R); sqrt(a h) */
    const v4d ul = uo0 * FA[0] + uo1 * FA[1] + uo2 * FA[2], ur = un0 * FA[3] + un1 * FB[0] + un2 * FB[1];
    const v4d al = {a[o0], a[o1], a[o2], a[o3]}, ar = {a[n0], a[n1], a[n2], a[n3]};
    const v4d cl = __builtin_ia32_sqrtpd256(al * hl), cr = __builtin_ia32_sqrtpd256(ar * hr);
    v4d sl, sr;
    hll_speeds4(hl, ul, cl, hr, ur, cr, &sl, &sr);
    const v4d L = {s->len[q[0]], s->len[q[1]], s->len[q[2]], s->len[q[3]]};
    const v4d out = L * vmax(zero, sr), in = L * vmax(zero, -sl);
    for (int k = 0; k < 4; ++k) {
        s->spd[2 * q[k]] = out[k];
        s->spd[2 * q[k] + 1] = in[k];
    }
}
#endif

gf_status gf_surface_max_dt(gf_surface *s, double *dt)
{
    gf_status st;
    if ((st = gf_surface_halo_exchange(s, s->h, 1)) || (st = gf_surface_halo_exchange(s, s->mom, 3)) ||
        (st = gf_surface_halo_exchange(s, s->a, 1)) ||
        (!s->active_fresh && (st = gf_surface_build_active(s))))
        return st;
    const gf_surface_mesh *m = &s->m;
    /* Positivity of the first-order update: the volume leaving face f through
     * edge e in dt is at most dt L_e h_f s_out, s_out = max(0, s_R) for the
     * owner and max(0, -s_L) for the neighbour (HLL's outgoing wave speeds of
     * the first-order states); Co = dt sum_e L_e s_out / (2 A) <= 1/2 keeps
     * h >= 0.  A wall's mirror state and an outflow's extrapolated state give
     * the same bounds with u_R = -u_L or u_R = u_L.  Internal edges four at
     * a time (edge_speeds4). */
#ifdef __AVX__
    int quad[4], nq = 0;
#endif
    for (size_t i = 0; i < s->n_act_e; ++i) {
        const int e = s->act_e[i];
        if (i + PF_DIST < s->n_act_e)
            prefetch_block(s->frame + EF * s->act_e[i + PF_DIST], 6, 0);
        const int o = m->owner[e], n = m->neighbour[e], kind = m->kind[e];
        if (kind == GF_EDGE_INTERNAL && s->h[o] <= 0.0 && s->h[n] <= 0.0) {
            /* both sides dry: no outgoing wave (hll_speeds' 0, 0), and the
             * per-face sums below are the same with +0 as with its -0 */
            s->spd[2 * e] = s->spd[2 * e + 1] = 0.0;
            continue;
        }
#ifdef __AVX__
        if (kind == GF_EDGE_INTERNAL) {
            quad[nq++] = e;
            if (nq == 4) {
                edge_speeds4(s, quad);
                nq = 0;
            }
            continue;
        }
#endif
        const double *fr = s->frame + EF * e;
        double uo[3];
        velocity(s, s->h, s->mom, o, uo);
        const double hl = s->h[o], ul = dot3(uo, fr + EF_NUL), cl = sqrt(s->a[o] * hl);
        double hr = hl, ur = -ul, cr = cl;
        if (kind == GF_EDGE_INTERNAL) {
            double un[3];
            velocity(s, s->h, s->mom, n, un);
            hr = s->h[n], ur = dot3(un, fr + EF_NUR), cr = sqrt(s->a[n] * hr);
        } else if (kind == GF_EDGE_OUTFLOW) {
            ur = ul;
        } else if (kind == GF_EDGE_INFLOW) {
            const double *b = s->inflow + 4 * e;
            hr = b[0], ur = dot3(b + 1, fr + EF_NUL), cr = sqrt(s->a[o] * hr);
        }
        double sl, sr;
        hll_speeds(hl, ul, cl, hr, ur, cr, &sl, &sr);
        s->spd[2 * e] = s->len[e] * gmax(0.0, sr);
        s->spd[2 * e + 1] = s->len[e] * gmax(0.0, -sl);
    }
#ifdef __AVX__
    if (nq > 0) { /* the last internal edges, padded with the first (its rates written twice, alike) */
        for (int k = nq; k < 4; ++k)
            quad[k] = quad[0];
        edge_speeds4(s, quad);
    }
#endif
    /* per face, over its edges in slot order (as accumulate) */
    double best = HUGE_VAL;
    for (size_t i = 0; i < s->n_act_owned; ++i) {
        const int f = s->act_f[i];
        double out = 0.0;
        for (size_t j = s->fe_start[f]; j < s->fe_start[f + 1]; ++j)
            out += s->spd[2 * s->fe[j] + s->fs_nb[j]];
        if (out > 0.0)
            best = gmin(best, 2.0 * s->c.courant * m->area[f] / out);
    }
    *dt = best;
    return GF_SUCCESS;
}

