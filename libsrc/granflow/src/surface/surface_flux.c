/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Edge fluxes of the surface scheme: HLL in the edge frame, the static
 * edges' donor flux and pressures, boundary edges; their sums per face and
 * the positivity fallback. */
#include "surface_internal.h"
#include "surface_flux.h"
#include "surface_halo.h"
#include "surface_recon.h"
#include "surface_simd.h"

/* HLL flux of (h, h u_nu, h u_t) with flux (h u_nu, h u_nu^2 + a h^2/2,
 * h u_nu u_t); speeds: Davis/Einfeldt bounds with the two-rarefaction
 * middle state, Toro's dry-bed speeds.  Returns the largest |speed|.  *fpress
 * is the pressure part of the normal momentum flux. */
static inline double hll(double hl, double ul, double vl, double al, double hr, double ur, double vr,
                         double ar, double *F, double *fpress)
{
    const double cl = sqrt(al * hl), cr = sqrt(ar * hr);
    double sl, sr;
    if (hl <= 0.0 && hr <= 0.0) {
        F[0] = F[1] = F[2] = *fpress = 0.0;
        return 0.0;
    }
    hll_speeds(hl, ul, cl, hr, ur, cr, &sl, &sr);
    const double pl = 0.5 * al * hl * hl, pr = 0.5 * ar * hr * hr;
    if (sl >= 0.0) {
        F[0] = hl * ul;
        F[1] = hl * ul * ul + pl;
        F[2] = hl * ul * vl;
        *fpress = pl;
        return fabs(sr);
    }
    if (sr <= 0.0) {
        F[0] = hr * ur;
        F[1] = hr * ur * ur + pr;
        F[2] = hr * ur * vr;
        *fpress = pr;
        return fabs(sl);
    }
    const double r = 1.0 / (sr - sl), ss = sl * sr;
    F[0] = (sr * hl * ul - sl * hr * ur + ss * (hr - hl)) * r;
    F[1] = (sr * (hl * ul * ul + pl) - sl * (hr * ur * ur + pr) + ss * (hr * ur - hl * ul)) * r;
    F[2] = (sr * hl * ul * vl - sl * hr * ur * vr + ss * (hr * vr - hl * vl)) * r;
    *fpress = (sr * pl - sl * pr) * r;
    return gmax(-sl, sr);
}

/* Pressure a_f h_f delta / 2 that face f in the hydrostatic mode feels at
 * its edge to face N: delta = h_N - h_N^eq, h_N^eq the thickness whose basal
 * pressure continues f's hydrostatically, a_N h_N^eq = a_f h_f + g.(x_N -
 * x_f), a = -g.n.  Where that is <= 0 and N is dry, N is a shore above the
 * lake: h_N^eq = 0 (delta = 0, no force).  A wet N keeps the negative
 * h_N^eq: summed over the face the pressures are -A h (grad(a h) - g_s) to
 * first order only so.  Up to 0.3.0 h_N^eq was 0 there too, a shoreline
 * inside the layer wherever the bed drops more between face centres than
 * the basal pressure head a h / |g| (5 m faces of a 1 m layer on 22 deg):
 * a uniform layer there felt 73 % of its weight along the slope and stayed
 * at rest under friction tan 21 deg (the inclined dam break of
 * doc/theory/standard-tests.md). */
static inline double hydrostatic_pressure(const gf_surface *s, const double *H, int f, int N)
{
    const double *xf = s->m.centre + 3 * f, *xn = s->m.centre + 3 * N, *g = s->c.g;
    const double P = s->ahyd[f] * H[f] + g[0] * (xn[0] - xf[0]) + g[1] * (xn[1] - xf[1]) + g[2] * (xn[2] - xf[2]);
    const double heq = (P > 0.0 || H[N] > s->c.h_dry) && s->ahyd[N] > 0.0 ? P / s->ahyd[N] : 0.0;
    return 0.5 * s->ahyd[f] * H[f] * (H[N] - heq);
}

/* Flux of edge e from the stage state (thickness H, velocities s->u): fh, fm (3D), fp (pressure
 * along nu); per unit length. */
static inline __attribute__((always_inline)) void edge_flux(gf_surface *s, const double *H, int e, int order2)
{
    const gf_surface_mesh *m = &s->m;
    const double *fr = s->frame + EF * e, *nu = fr + EF_NU, *t = fr + EF_T, *nul = fr + EF_NUL, *nur = fr + EF_NUR;
    const double L = fr[EF_L];
    const int o = m->owner[e], n = m->neighbour[e], kind = m->kind[e];
    const unsigned st = s->stamp;
    /* the sums of accumulate: L fh, fp PO, fpn PN, L fm, L fmn */
    double *ea = s->eacc + EA * e;
    double hl, ul[3], F[3], fpress, un_b = 0.0, ut_b = 0.0;
    if (kind == GF_EDGE_INTERNAL) {
        if (s->sedge[e] & 1) {
            /* Both sides slow (|u| < dt |g|, at most what one step of
             * gravity gives; at rest included).  HLL's mass diffusion
             * s_L s_R (h_R - h_L), of the size of the wave speed, would keep
             * moving material that friction holds (deposits creeping at
             * 1e-4 m/s); instead the mass flux is the donor flux of the mean
             * normal velocity (the kinetic paper's Scheme 3 idea on the
             * surface; zero at rest) and each side feels its own pressure:
             *  - a face in the hydrostatic mode (every edge static,
             *    gf_surface.stat) feels a_f h_f delta / 2, delta = h_N -
             *    h_N^eq, where h_N^eq = max(0, a_f h_f + g.(x_N - x_f)) / a_N
             *    is the thickness of the neighbour that continues the
             *    face's basal pressure hydrostatically (a = -g.n); the face
             *    gets no pointwise gravity, so a lake whose basal pressure
             *    is that of one horizontal free surface (shorelines and
             *    walls included) feels exactly no force.  Summed over a
             *    face, -A h (grad(a h) - g_s) to first order (walls: the
             *    hydrostatic ghost, delta = 0);
             *  - any other face feels a_f h_f h_N / 2 with its pointwise
             *    gravity: summed, A a_f h_f grad h (Green–Gauss).
             * Either way friction holds a pile whose discrete surface slope
             * is admissible, however thin the face (kinetic paper, Def. 1,
             * in 2D).  p_b's lateral feedback takes a_f h_f h_N / 2 on both.
             * Momentum is not exchanged conservatively across such an edge;
             * nothing moves there faster than dt |g|. */
            const double *uo = s->u + 3 * o, *un = s->u + 3 * n;
            const double vo = dot3(uo, nul), vn = dot3(un, nur), vm = 0.5 * (vo + vn);
            const int up = vm >= 0.0 ? o : n;
            const double *uu = s->u + 3 * up, unu = up == o ? vo : vn, ut = dot3(uu, t);
            const double po = 0.5 * s->a[o] * H[o] * H[n], pn = 0.5 * s->a[n] * H[n] * H[o];
            const double qo = s->stat[o] ? hydrostatic_pressure(s, H, o, n) : po;
            const double qn = s->stat[n] ? hydrostatic_pressure(s, H, n, o) : pn;
            const double fh = H[up] * vm;
            s->fh[e] = fh;
            ea[0] = L * fh;
            ea[1] = po * fr[EF_PO];
            ea[2] = pn * fr[EF_PN];
            for (int k = 0; k < 3; ++k) {
                const double adv = fh * (unu * nu[k] + ut * t[k]);
                ea[3 + k] = L * (adv + qo * nu[k]);
                s->efmn[3 * e + k] = L * (adv + qn * nu[k]);
            }
            ea[6] = 1.0;
            return;
        }
        double hr, ur[3];
        const int rec = order2 && !s->first[e];
        const int dry_o = H[o] <= s->c.h_dry, dry_n = H[n] <= s->c.h_dry;
        edge_side(s, H, o, e, 0, rec ? (dry_n ? 2 : 1) : 0, &hl, ul);
        edge_side(s, H, n, e, 1,
                  rec && ((size_t)n >= m->n_faces || s->mark_f[n] == st) ? (dry_o ? 2 : 1) : 0, &hr, ur);
        hll(hl, dot3(ul, nul), dot3(ul, t), s->a[o], hr, dot3(ur, nur), dot3(ur, t), s->a[n], F, &fpress);
    } else {
        edge_side(s, H, o, e, 0, order2 && !s->first[e], &hl, ul);
        const double un = dot3(ul, nul), ut = dot3(ul, t), p = 0.5 * s->a[o] * hl * hl;
        un_b = un, ut_b = ut;
        if (kind == GF_EDGE_WALL) { /* mirror state: no mass, pressure and reflection */
            hll(hl, un, ut, s->a[o], hl, -un, ut, s->a[o], F, &fpress);
            F[0] = 0.0;
            F[2] = 0.0;
        } else if (kind == GF_EDGE_OUTFLOW) {
            if (un > 0.0) {
                F[0] = hl * un, F[1] = hl * un * un + p, F[2] = hl * un * ut;
            } else
                F[0] = 0.0, F[1] = p, F[2] = 0.0;
            fpress = p;
        } else { /* inflow: the flux of the prescribed state */
            const double *b = s->inflow + 4 * e, hb = b[0];
            const double ub = dot3(b + 1, nul), vb = dot3(b + 1, t), pbf = 0.5 * s->a[o] * hb * hb;
            F[0] = hb * ub, F[1] = hb * ub * ub + pbf, F[2] = hb * ub * vb;
            fpress = pbf;
        }
    }
    s->fh[e] = F[0];
    ea[6] = 0.0;
    ea[0] = L * F[0];
    ea[1] = fpress * fr[EF_PO];
    ea[2] = fpress * fr[EF_PN];
    if (kind != GF_EDGE_INTERNAL && s->stat[o]) {
        /* a wall (or an outflow edge nothing leaves) of a face in the
         * hydrostatic mode: the hydrostatic ghost (delta = 0), no force
         * along the surface; fpress still enters p_b */
        for (int k = 0; k < 3; ++k)
            ea[3 + k] = L * (F[0] * (un_b * nu[k] + ut_b * t[k]));
        return;
    }
    for (int k = 0; k < 3; ++k) /* the momentum flux F[1] nu + F[2] t, alike on both sides */
        ea[3 + k] = L * (F[1] * nu[k] + F[2] * t[k]);
}

#ifdef __AVX__

/* the frames (EF doubles) of four edges as 16 columns: FA[k] = (frame[k] of
 * each edge), FB: [4..7], FC: [8..11], FD: [12..15] */
static inline void frames4(const gf_surface *s, const int *q, v4d *FA, v4d *FB, v4d *FC, v4d *FD)
{
    const double *f0 = s->frame + EF * q[0], *f1 = s->frame + EF * q[1], *f2 = s->frame + EF * q[2],
                 *f3 = s->frame + EF * q[3];
    transpose4(vload(f0), vload(f1), vload(f2), vload(f3), FA);
    transpose4(vload(f0 + 4), vload(f1 + 4), vload(f2 + 4), vload(f3 + 4), FB);
    transpose4(vload(f0 + 8), vload(f1 + 8), vload(f2 + 8), vload(f3 + 8), FC);
    transpose4(vload(f0 + 12), vload(f1 + 12), vload(f2 + 12), vload(f3 + 12), FD);
}

/* edge_flux of four plain edges (gf_surface.sedge bit 1) at once, one per lane: the same
 * operations in the same order as edge_flux, side_state's stored states,
 * hll and hll_speeds, every branch taken as a selection per lane, so that
 * each lane's results are those of edge_flux bit for bit. */
static void edge_flux4(gf_surface *s, const int *q)
{
    const gf_surface_mesh *m = &s->m;
    v4d SL[4], SR[4], FA[4], FB[4], FC[4], FD[4];
    {
        const double *e0 = s->es + 8 * q[0], *e1 = s->es + 8 * q[1], *e2 = s->es + 8 * q[2], *e3 = s->es + 8 * q[3];
        transpose4(vload(e0), vload(e1), vload(e2), vload(e3), SL);
        transpose4(vload(e0 + 4), vload(e1 + 4), vload(e2 + 4), vload(e3 + 4), SR);
    }
    frames4(s, q, FA, FB, FC, FD);
    /* frame: nu_L = FA0..2, nu_R = FA3 FB0 FB1, nu = FB2 FB3 FC0, t = FC1..3, L PO PN = FD0..2 */
    const v4d nul0 = FA[0], nul1 = FA[1], nul2 = FA[2], nur0 = FA[3], nur1 = FB[0], nur2 = FB[1];
    const v4d nu0 = FB[2], nu1 = FB[3], nu2 = FC[0], t0 = FC[1], t1 = FC[2], t2 = FC[3];
    const v4d L = FD[0], PO = FD[1], PN = FD[2];
    const v4d hl = SL[0], hr = SR[0];
    const v4d al = {s->a[m->owner[q[0]]], s->a[m->owner[q[1]]], s->a[m->owner[q[2]]], s->a[m->owner[q[3]]]};
    const v4d ar = {s->a[m->neighbour[q[0]]], s->a[m->neighbour[q[1]]], s->a[m->neighbour[q[2]]],
                    s->a[m->neighbour[q[3]]]};
    /* dot3(ul, nul), dot3(ul, t), dot3(ur, nur), dot3(ur, t) */
    const v4d ul = SL[1] * nul0 + SL[2] * nul1 + SL[3] * nul2, vl = SL[1] * t0 + SL[2] * t1 + SL[3] * t2;
    const v4d ur = SR[1] * nur0 + SR[2] * nur1 + SR[3] * nur2, vr = SR[1] * t0 + SR[2] * t1 + SR[3] * t2;
    /* hll (both sides dry: no flux, below) */
    const v4d zero = vsplat(0.0), half = vsplat(0.5);
    const v4d cl = __builtin_ia32_sqrtpd256(al * hl), cr = __builtin_ia32_sqrtpd256(ar * hr);
    v4d sl, sr;
    hll_speeds4(hl, ul, cl, hr, ur, cr, &sl, &sr);
    const v4d pl = half * al * hl * hl, pr = half * ar * hr * hr;
    /* 1 / (s_R - s_L) where HLL's middle case takes it (s_L < 0 < s_R); 1 in
     * the other lanes, whose results are discarded: no division by zero,
     * which traps under OpenFOAM's floating-point exception handling */
    const v4i mid = (sl < zero) & (sr > zero);
    const v4d r = vsplat(1.0) / vsel(mid, sr - sl, vsplat(1.0)), ss = sl * sr;
    v4d F0 = (sr * hl * ul - sl * hr * ur + ss * (hr - hl)) * r;
    v4d F1 = (sr * (hl * ul * ul + pl) - sl * (hr * ur * ur + pr) + ss * (hr * ur - hl * ul)) * r;
    v4d F2 = (sr * hl * ul * vl - sl * hr * ur * vr + ss * (hr * vr - hl * vl)) * r;
    v4d fp = (sr * pl - sl * pr) * r;
    const v4i right = sr <= zero, left = sl >= zero, none = (hl <= zero) & (hr <= zero); /* in this order */
    F0 = vsel(right, hr * ur, F0), F1 = vsel(right, hr * ur * ur + pr, F1), F2 = vsel(right, hr * ur * vr, F2);
    fp = vsel(right, pr, fp);
    F0 = vsel(left, hl * ul, F0), F1 = vsel(left, hl * ul * ul + pl, F1), F2 = vsel(left, hl * ul * vl, F2);
    fp = vsel(left, pl, fp);
    F0 = vsel(none, zero, F0), F1 = vsel(none, zero, F1), F2 = vsel(none, zero, F2), fp = vsel(none, zero, fp);
    /* the sums of accumulate, as edge_flux writes them */
    v4d out[8] = {L * F0, fp * PO, fp * PN, L * (F1 * nu0 + F2 * t0), L * (F1 * nu1 + F2 * t1),
                  L * (F1 * nu2 + F2 * t2), zero, zero};
    v4d rows[8];
    transpose4(out[0], out[1], out[2], out[3], rows);
    transpose4(out[4], out[5], out[6], out[7], rows + 4);
    for (int k = 0; k < 4; ++k) {
        double *ea = s->eacc + EA * q[k];
        memcpy(ea, &rows[k], sizeof rows[k]);
        memcpy(ea + 4, &rows[4 + k], sizeof rows[k]);
        s->fh[q[k]] = F0[k];
    }
}

/* The static branch of edge_flux (gf_surface.sedge bit 0: an internal edge
 * with both sides slow) for four edges at once, one per lane: the same
 * operations in the same order (the upwind side, the pressures of each
 * side, hydrostatic_pressure where a face is in the hydrostatic mode, every
 * branch a selection per lane), so that each lane's results are those of
 * edge_flux bit for bit.  At rest, and in deposits, these are most edges. */
static inline v4d hydrostatic_pressure4(v4d ahf, v4d hf, v4d ahn, v4d hn, v4d dx, v4d dy, v4d dz, const double *g,
                                        double h_dry)
{
    const v4d zero = vsplat(0.0);
    const v4d P = ahf * hf + vsplat(g[0]) * dx + vsplat(g[1]) * dy + vsplat(g[2]) * dz;
    const v4i ok = ((P > zero) | (hn > vsplat(h_dry))) & (ahn > zero);
    const v4d heq = vsel(ok, P / vsel(ok, ahn, vsplat(1.0)), zero);
    return vsplat(0.5) * ahf * hf * (hn - heq);
}
static void edge_static4(gf_surface *s, const double *H, const int *q)
{
    const gf_surface_mesh *m = &s->m;
    v4d FA[4], FB[4], FC[4], FD[4];
    frames4(s, q, FA, FB, FC, FD);
    const v4d nul0 = FA[0], nul1 = FA[1], nul2 = FA[2], nur0 = FA[3], nur1 = FB[0], nur2 = FB[1];
    const v4d nu0 = FB[2], nu1 = FB[3], nu2 = FC[0], t0 = FC[1], t1 = FC[2], t2 = FC[3];
    const v4d L = FD[0], PO = FD[1], PN = FD[2];
    const int o0 = m->owner[q[0]], o1 = m->owner[q[1]], o2 = m->owner[q[2]], o3 = m->owner[q[3]];
    const int n0 = m->neighbour[q[0]], n1 = m->neighbour[q[1]], n2 = m->neighbour[q[2]], n3 = m->neighbour[q[3]];
    const double *u = s->u, *a = s->a, *ah = s->ahyd, *x = m->centre;
    const unsigned char *stat = s->stat;
#define G4(arr, st, k, i0, i1, i2, i3) ((v4d){arr[st * i0 + k], arr[st * i1 + k], arr[st * i2 + k], arr[st * i3 + k]})
    const v4d uo0 = G4(u, 3, 0, o0, o1, o2, o3), uo1 = G4(u, 3, 1, o0, o1, o2, o3), uo2 = G4(u, 3, 2, o0, o1, o2, o3);
    const v4d un0 = G4(u, 3, 0, n0, n1, n2, n3), un1 = G4(u, 3, 1, n0, n1, n2, n3), un2 = G4(u, 3, 2, n0, n1, n2, n3);
    const v4d Ho = G4(H, 1, 0, o0, o1, o2, o3), Hn = G4(H, 1, 0, n0, n1, n2, n3);
    const v4d ao = G4(a, 1, 0, o0, o1, o2, o3), an = G4(a, 1, 0, n0, n1, n2, n3);
    const v4d aho = G4(ah, 1, 0, o0, o1, o2, o3), ahn = G4(ah, 1, 0, n0, n1, n2, n3);
    /* x_n - x_o, and x_o - x_n for the neighbour's side */
    const v4d dx = G4(x, 3, 0, n0, n1, n2, n3) - G4(x, 3, 0, o0, o1, o2, o3);
    const v4d dy = G4(x, 3, 1, n0, n1, n2, n3) - G4(x, 3, 1, o0, o1, o2, o3);
    const v4d dz = G4(x, 3, 2, n0, n1, n2, n3) - G4(x, 3, 2, o0, o1, o2, o3);
    const v4d mx = G4(x, 3, 0, o0, o1, o2, o3) - G4(x, 3, 0, n0, n1, n2, n3);
    const v4d my = G4(x, 3, 1, o0, o1, o2, o3) - G4(x, 3, 1, n0, n1, n2, n3);
    const v4d mz = G4(x, 3, 2, o0, o1, o2, o3) - G4(x, 3, 2, n0, n1, n2, n3);
#undef G4
    const v4i so = {stat[o0] ? -1 : 0, stat[o1] ? -1 : 0, stat[o2] ? -1 : 0, stat[o3] ? -1 : 0};
    const v4i sn = {stat[n0] ? -1 : 0, stat[n1] ? -1 : 0, stat[n2] ? -1 : 0, stat[n3] ? -1 : 0};
    const v4d half = vsplat(0.5);
    const v4d vo = uo0 * nul0 + uo1 * nul1 + uo2 * nul2, vn = un0 * nur0 + un1 * nur1 + un2 * nur2;
    const v4d vm = half * (vo + vn);
    const v4i upo = vm >= vsplat(0.0); /* the upwind side is the owner */
    const v4d unu = vsel(upo, vo, vn);
    const v4d ut = vsel(upo, uo0, un0) * t0 + vsel(upo, uo1, un1) * t1 + vsel(upo, uo2, un2) * t2;
    const v4d po = half * ao * Ho * Hn, pn = half * an * Hn * Ho;
    const v4d qo = vsel(so, hydrostatic_pressure4(aho, Ho, ahn, Hn, dx, dy, dz, s->c.g, s->c.h_dry), po);
    const v4d qn = vsel(sn, hydrostatic_pressure4(ahn, Hn, aho, Ho, mx, my, mz, s->c.g, s->c.h_dry), pn);
    const v4d fh = vsel(upo, Ho, Hn) * vm;
    const v4d adv0 = fh * (unu * nu0 + ut * t0), adv1 = fh * (unu * nu1 + ut * t1), adv2 = fh * (unu * nu2 + ut * t2);
    const v4d out[8] = {L * fh, po * PO, pn * PN, L * (adv0 + qo * nu0), L * (adv1 + qo * nu1),
                        L * (adv2 + qo * nu2), vsplat(1.0), vsplat(0.0)};
    const v4d mn0 = L * (adv0 + qn * nu0), mn1 = L * (adv1 + qn * nu1), mn2 = L * (adv2 + qn * nu2);
    v4d rows[8];
    transpose4(out[0], out[1], out[2], out[3], rows);
    transpose4(out[4], out[5], out[6], out[7], rows + 4);
    for (int k = 0; k < 4; ++k) {
        double *ea = s->eacc + EA * q[k], *fn = s->efmn + 3 * q[k];
        memcpy(ea, &rows[k], sizeof rows[k]);
        memcpy(ea + 4, &rows[4 + k], sizeof rows[k]);
        s->fh[q[k]] = fh[k];
        fn[0] = mn0[k], fn[1] = mn1[k], fn[2] = mn2[k];
    }
}

#endif

/* edge_flux out of line, for the positivity fallback's recomputations (the
 * pass over the active edges has it inlined) */
static __attribute__((noinline)) void edge_flux_again(gf_surface *s, const double *H, int e, int order2)
{
    edge_flux(s, H, e, order2);
}

/* The edge fluxes summed per owned active face, over its edges in the
 * order of the mesh (gathered, not scattered: the sum's rounding does not
 * depend on which faces are active or on how the mesh is decomposed).  The
 * owner takes + L (fh, fm, fp nu.n), the neighbour - L (fh, fmn, fpn nu.n),
 * so a processor edge, owned on both of its ranks, gives each side what the
 * serial mesh gives it (the edge frame and HLL are antisymmetric).  The faces
 * whose thickness H - dt/A sum L fh would be below 0 are listed in
 * gf_surface.neg in the order of the active set; returns their number. */
static size_t accumulate(gf_surface *s, const double *H, double dt)
{
    size_t nneg = 0;
    const gf_surface_mesh *m = &s->m;
    for (size_t i = 0; i < s->n_act_owned; ++i) {
        const int f = s->act_f[i];
        if (i + PF_DIST / 2 < s->n_act_owned) {
            const int fp = s->act_f[i + PF_DIST / 2];
            for (size_t j = s->fe_start[fp]; j < s->fe_start[fp + 1]; ++j)
                prefetch_block(s->eacc + EA * s->fe[j], EA, 0);
        }
        /* lanes (sum L fh, sum fp nu.n, sum L fm_x, sum L fm_y), and sum L fm_z */
        v4d A = vsplat(0.0);
        double amz = 0.0;
        for (size_t j = s->fe_start[f]; j < s->fe_start[f + 1]; ++j) {
            const int e = s->fe[j];
            const v4d v = vload(s->eacc + EA * e), w = vload(s->eacc + EA * e + 4); /* [0..3], [4..7] */
            if (!s->fs_nb[j]) { /* the owner: + L fh, fp PO, L fm */
                A += __builtin_shuffle(v, w, (v4i){0, 1, 3, 4});
                amz += w[1];
            } else if (w[2] == 0.0) { /* the neighbour: - L fh, fpn PN, L fm */
                A -= __builtin_shuffle(v, w, (v4i){0, 2, 3, 4});
                amz -= w[1];
            } else { /* the neighbour of a static edge: L fmn */
                const double *fn = s->efmn + 3 * e;
                A -= (v4d){v[0], v[2], fn[0], fn[1]};
                amz -= fn[2];
            }
        }
        s->acc_h[f] = A[0], s->acc_pn[f] = A[1];
        s->acc_m[3 * f] = A[2], s->acc_m[3 * f + 1] = A[3], s->acc_m[3 * f + 2] = amz;
        if (H[f] - dt / m->area[f] * A[0] < 0.0)
            s->neg[nneg++] = f;
    }
    return nneg;
}

/* The fluxes of a stage's active edges, the hydrostatic mode of its faces
 * (gf_surface.stat), and their sums per face, with the positivity fallback
 * (surface_flux.h). */
gf_status gf_surface_edge_fluxes(gf_surface *s, const double *H, double dt, int order2)
{
    const gf_surface_mesh *m = &s->m;
    const unsigned char *slow = s->slow;
    gf_status st;
    /* One pass over the active edges classifies each (gf_surface.sedge),
     * clears the hydrostatic mode of the faces of a non-static edge, and
     * computes the flux of every internal edge that is not static (which
     * reads no hydrostatic mode); the static and boundary edges, whose
     * fluxes read the faces' final modes, follow in a second pass. */
    size_t nd = 0;
#ifdef __AVX__
    int quad[4], nq = 0;
#endif
    for (size_t i = 0; i < s->n_act_e; ++i) {
        const int e = s->act_e[i], o = m->owner[e], n = m->neighbour[e], kind = m->kind[e];
        if (i + PF_DIST < s->n_act_e) {
            const int ep = s->act_e[i + PF_DIST];
            prefetch_block(s->frame + EF * ep, EF, 0);
            prefetch_block(s->es + 8 * ep, 8, 0);
            prefetch_block(s->eacc + EA * ep, EA, 1);
        }
        s->first[e] = 0;
        /* a neighbour outside the active set is dry and at rest */
        const int se = kind == GF_EDGE_INTERNAL && (slow[o] & 1) && ((slow[n] & 1) || s->mark_f[n] != s->stamp);
        /* plain (bit 1): an internal edge whose flux edge_flux4 computes at
         * order 2, not static, both faces owned, active and wet (bit 1 of
         * slow), so that both sides take the reconstructed states
         * gf_surface_gradients() stores */
        const int plain = order2 && !se && kind == GF_EDGE_INTERNAL && (slow[o] & slow[n] & 2);
        s->sedge[e] = (unsigned char)(se | plain << 1);
        if (kind == GF_EDGE_INFLOW || (kind == GF_EDGE_INTERNAL && !se)) {
            s->stat[o] = 0;
            if (n >= 0)
                s->stat[n] = 0;
        }
        if (se && H[o] <= 0.0 && H[n] <= 0.0) {
            /* both sides dry (the rings of the active set): every flux and
             * pressure of the static edge is 0 (h = 0, u = 0), written as
             * such instead of computed; the sums of a face with material
             * are the same, a dry face's differ at most in the sign of a
             * zero, which its update does not read */
            memset(s->eacc + EA * e, 0, EA * sizeof *s->eacc);
            s->fh[e] = 0.0;
            continue;
        }
#ifdef __AVX__
        if (plain) { /* four at a time */
            quad[nq++] = e;
            if (nq == 4) {
                edge_flux4(s, quad);
                nq = 0;
            }
            continue;
        }
#endif
        if (kind == GF_EDGE_INTERNAL && !se)
            edge_flux(s, H, e, order2);
        else
            s->defer[nd++] = e;
    }
#ifdef __AVX__
    for (int k = 0; k < nq; ++k)
        edge_flux(s, H, quad[k], order2);
#endif
#ifdef __AVX__
    /* the deferred internal edges are static: four at a time */
    nq = 0;
    for (size_t i = 0; i < nd; ++i) {
        const int e = s->defer[i];
        if (m->kind[e] != GF_EDGE_INTERNAL) {
            edge_flux(s, H, e, order2);
            continue;
        }
        quad[nq++] = e;
        if (nq == 4) {
            edge_static4(s, H, quad);
            nq = 0;
        }
    }
    for (int k = 0; k < nq; ++k)
        edge_flux(s, H, quad[k], order2);
#else
    for (size_t i = 0; i < nd; ++i)
        edge_flux(s, H, s->defer[i], order2);
#endif
    /* Positivity: a face whose thickness would fall below 0 has its edges
     * recomputed at first order (up to 3 passes), one that still would
     * (or any at order 1) fails the stage, and the step is halved.  In
     * parallel every rank takes the same decisions as the serial run: a
     * face's mark reaches the ranks that hold its processor edges (their
     * ghost), and whether to pass again or fail is decided over all ranks,
     * so that their exchanges stay paired and an edge's two copies carry one
     * flux. */
    const double tiny = 1e-13 * s->h_scale;
    double *badf = s->lvl; /* per face: marked this pass (scratch, exchanged; gf_surface_build_active's otherwise) */
    int *badl = s->ring;   /* the faces marked this pass (scratch) */
    const int par = s->m.n_ghosts > 0 || s->minfn;
    for (int pass = 0;; ++pass) {
        const size_t nneg = accumulate(s, H, dt);
        int bad = 0, fail = 0, fail_f = -1;
        size_t nbad = 0;
        double fail_h = 0.0;
        for (size_t i = 0; i < nneg; ++i) { /* the faces with H - dt/A sum L fh < 0 */
            const int f = s->neg[i];
            const double hn = H[f] - dt / m->area[f] * s->acc_h[f];
            if (hn < -tiny || (hn < 0.0 && pass < 3 && order2)) {
                if (pass >= 3 || !order2) {
                    if (!fail)
                        fail = 1, fail_f = f, fail_h = hn;
                    continue;
                }
                badl[nbad++] = f;
                for (size_t j = s->fe_start[f]; j < s->fe_start[f + 1]; ++j) {
                    const int e = s->fe[j];
                    if (!s->first[e]) {
                        s->first[e] = 1;
                        s->st.first_order_edges++;
                        edge_flux_again(s, H, e, order2);
                    }
                }
                bad = 1;
            }
        }
        if (par) {
            double v[2] = {fail ? -1.0 : 0.0, bad ? -1.0 : 0.0};
            if ((st = gf_surface_halo_min(s, v, 2)))
                return st;
            if (v[0] < 0.0 && !fail)
                return gf_fail(GF_EPHYS, "surface scheme: a thickness below 0 on another rank after a step of "
                                         "%g s; lower the Courant number", dt);
            bad = v[1] < 0.0;
        }
        if (fail)
            return gf_fail(GF_EPHYS, "surface scheme: thickness %g in face %d after a step of %g s; "
                                     "lower the Courant number", fail_h, fail_f, dt);
        if (!bad)
            break;
        if (par) { /* processor edges of faces marked on the other side */
            if (s->send_f) /* only what the exchange sends (gf_surface_set_send_faces) */
                for (size_t i = 0; i < s->n_send; ++i)
                    badf[s->send_f[i]] = 0.0;
            else
                memset(badf, 0, m->n_faces * sizeof *badf); /* only in a pass that marked faces somewhere */
            for (size_t i = 0; i < nbad; ++i)
                badf[badl[i]] = 1.0;
            if ((st = gf_surface_halo_exchange(s, badf, 1)))
                return st;
            for (size_t i = 0; i < s->n_act_e; ++i) {
                const int e = s->act_e[i], n = m->neighbour[e];
                if (n >= 0 && (size_t)n >= m->n_faces && badf[n] > 0.0 && !s->first[e]) {
                    s->first[e] = 1;
                    s->st.first_order_edges++;
                    edge_flux_again(s, H, e, order2);
                }
            }
        }
    }
    return GF_SUCCESS;
}
