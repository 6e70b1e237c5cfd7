/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Reconstruction of the surface scheme: Green-Gauss gradients, limited,
 * and the reconstructed states at the edges of the owned active faces. */
#include "surface_internal.h"
#include "surface_recon.h"
#include "surface_simd.h"

/* Green–Gauss gradients of h and u over the face's edges (mean of the two
 * sides; velocity only from wet neighbours), projected onto the tangent
 * plane, Barth–Jespersen limited at the edge midpoints; then the
 * reconstructed h and u at the face's edges (gf_surface.es).  Face f, its
 * edge slots j0 .. j0 + ne - 1 (inlined: called with ne = 4, the
 * quadrilaterals', the loops are straight code). */
static inline __attribute__((always_inline)) void gradient_face(gf_surface *s, const double *H, int f, size_t j0,
                                                                size_t ne)
{
    const gf_surface_mesh *m = &s->m;
    const double hd = s->c.h_dry;
    const int *oth = s->fs_other;
    const v4i all = {-1, -1, -1, -1}, lane0 = {-1, 0, 0, 0};
    const double h0 = H[f], *u0 = s->u + 3 * f;
    const int wet = h0 > hd;
    const v4d q0 = {h0, u0[0], u0[1], u0[2]};
    /* Gx, Gy, Gz: the x, y, z components of the gradients of the four
     * variables (lane v: grad h, grad u_x, grad u_y, grad u_z) */
    v4d Gx = vsplat(0.0), Gy = Gx, Gz = Gx, qmn = q0, qmx = q0;
    const size_t j1 = j0 + ne;
    const double *sg0 = s->fs_geo + SG * j0;
    for (size_t j = j0; j < j1; ++j) {
        const int other = oth[j];
        const double *lw = sg0 + SG * (j - j0); /* w L nu_e */
        v4d qe = q0;
        if (other >= 0) {
            const double hn = H[other], *un = s->u + 3 * other;
            const v4d qn = {hn, un[0], un[1], un[2]};
            if (wet && hn > hd) { /* all four lanes */
                qe = vsplat(0.5) * (q0 + qn);
                qmn = vmin(qmn, qn);
                qmx = vmax(qmx, qn);
            } else { /* h only */
                qe = vsel(lane0, vsplat(0.5) * (q0 + qn), q0);
                qmn = vsel(lane0, vmin(qmn, qn), qmn);
                qmx = vsel(lane0, vmax(qmx, qn), qmx);
            }
        }
        Gx += qe * vsplat(lw[0]);
        Gy += qe * vsplat(lw[1]);
        Gz += qe * vsplat(lw[2]);
    }
    /* tangential part, per unit area (no velocity slope on a face without velocity) */
    const double rA = 1.0 / m->area[f], *nf = m->normal + 3 * f;
    {
        const v4d gn = Gx * vsplat(nf[0]) + Gy * vsplat(nf[1]) + Gz * vsplat(nf[2]);
        const v4d ra = vsplat(rA);
        Gx = (Gx - gn * vsplat(nf[0])) * ra;
        Gy = (Gy - gn * vsplat(nf[1])) * ra;
        Gz = (Gz - gn * vsplat(nf[2])) * ra;
    }
    if (!wet) {
        const v4d z = vsplat(0.0);
        Gx = vsel(lane0, Gx, z), Gy = vsel(lane0, Gy, z), Gz = vsel(lane0, Gz, z);
    }
    /* Barth–Jespersen: alpha = min over the edges of room/d, divided
     * only when the ratio is below alpha <= 1 (no overflow for a
     * denormal slope); towards a dry neighbour the velocity is
     * extrapolated, not bounded: the thin tip of a front accelerates to
     * u + 2c */
    v4d alpha = vsplat(1.0);
    const v4d rp = qmx - q0, rm = qmn - q0;
    for (size_t j = j0; j < j1; ++j) {
        const int other = oth[j];
        const double *r = sg0 + SG * (j - j0) + 3; /* edge centre - face centre */
        const v4i lanes = (other >= 0 && H[other] <= hd) ? lane0 : all;
        const v4d d = Gx * vsplat(r[0]) + Gy * vsplat(r[1]) + Gz * vsplat(r[2]);
        const v4d ad = alpha * d, zero = vsplat(0.0);
        /* d > 0 && room_max < alpha d, or d < 0 && room_min > alpha d */
        const v4i pos = d > zero;
        const v4i hit = ((pos & (rp < ad)) | ((d < zero) & (rm > ad))) & lanes;
        if (vany(hit))
            alpha = vsel(hit, vsel(pos, rp, rm) / vsel(hit, d, vsplat(1.0)), alpha);
    }
    const v4d c = vmax(vsplat(0.0), alpha);
    Gx *= c, Gy *= c, Gz *= c;
    if (s->pface[f]) { /* for the halo exchange */
        double *Gf = s->grad + 3 * NV * f;
        for (int v = 0; v < NV; ++v) {
            Gf[3 * v] = Gx[v];
            Gf[3 * v + 1] = Gy[v];
            Gf[3 * v + 2] = Gz[v];
        }
    }
    /* the reconstructed states at the face's edges (side_state, rec 1):
     * h (not below 0: round-off of the limiter), and u where wet */
    const v4i rec = wet ? all : lane0;
    for (size_t j = j0; j < j1; ++j) {
        const double *r = sg0 + SG * (j - j0) + 3;
        double *q = s->es + es_slot(s, j);
        const v4d qr = vsel(rec, q0 + (Gx * vsplat(r[0]) + Gy * vsplat(r[1]) + Gz * vsplat(r[2])), q0);
        q[0] = qr[0] < 0.0 ? 0.0 : qr[0];
        q[1] = qr[1], q[2] = qr[2], q[3] = qr[3];
    }
}

void gf_surface_gradients(gf_surface *s, const double *H)
{
    for (size_t i = 0; i < s->n_act_owned; ++i) {
        const int f = s->act_f[i];
        if (i + PF_DIST / 2 < s->n_act_owned) {
            const int fp = s->act_f[i + PF_DIST / 2];
            for (size_t j = s->fe_start[fp]; j < s->fe_start[fp + 1]; ++j)
                prefetch_block(s->es + 8 * s->fe[j], 8, 1);
        }
        const size_t j0 = s->fe_start[f], ne = s->fe_start[f + 1] - j0;
        /* A dry face (h = +0: its velocity is 0, and no neighbour is below
         * it) reconstructs 0 at every edge: where its gradient is not 0 some
         * edge's slope d is negative, and Barth–Jespersen's room there,
         * min(h) - h = 0, makes alpha 0.  Its states are written as that
         * (the rings of the active set; not for the halo's gradients). */
        if (H[f] == 0.0 && !signbit(H[f]) && !s->pface[f]) {
            for (size_t j = j0; j < j0 + ne; ++j)
                memset(s->es + es_slot(s, j), 0, 4 * sizeof *s->es);
            continue;
        }
        if (ne == 4)
            gradient_face(s, H, f, j0, 4);
        else
            gradient_face(s, H, f, j0, ne);
    }
}

