/* SPDX-License-Identifier: GPL-3.0-or-later */
#include "granflow/dg1d.h"
#include "granflow/source.h"
#include "internal.h"
#include "sh1d_internal.h"

#include <gsl/gsl_integration.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAXM 3 /* modes of P2 */
#define MAXG 3 /* Gauss points of P2 */

typedef struct dg {
    int m, ng;                  /* modes, Gauss points */
    double xg[MAXG], wg[MAXG];  /* Gauss rule on [-1, 1], weights sum 2 */
    double pg[MAXG][MAXM];      /* P_m(x_g) */
    double dpg[MAXG][MAXM];     /* P_m'(x_g) */
    size_t nc;                  /* n + 2 cells with ghosts */
    double *h, *q;              /* solution, nc * m */
    double *h0, *q0, *h1, *q1;  /* RK stages */
    double *rh, *rq;            /* right-hand side without friction, nc * m */
    double *fm;                 /* friction term of the q modes per unit time, nc * m */
    double *lim;                /* scratch: modes before limiting, nc * m */
    double *cap;                /* friction capacity per unit time (cell mean), nc */
    double *k;                  /* earth-pressure coefficient per cell, nc */
    double *ubar;               /* scratch: mean velocities, nc */
    unsigned char *moving;      /* M_j, nc */
    unsigned char *stopped;     /* stopped by friction in the last Euler stage, nc */
    unsigned char *moving0;     /* M_j at the start of a step, to repeat it, nc */
    unsigned char *stopped0;    /* the same for stopped */
    /* the bed (fixed): cos and sin of zeta and the curvature kappa at the
     * Gauss points (nc * ng; ghost cells flat), cos zeta at the interfaces */
    double *czg, *szg, *kg;
    double *czf;
    double *fh, *fqx;           /* interface fluxes, n + 1 */
    /* the cells a step computes, lo..hi (gf_sh1d_active_range); outside them every
     * mode is exactly 0 and stays so */
    size_t lo, hi;
    /* the moving mesh (cfg.moving_mesh): which ends are dry fronts (their
     * node moves), the node velocities of the state rhs saw last, and the
     * solution's nodes (the stages' are rk3_step's locals) */
    int ale, free_l, free_r;
    double va, vb;
    double xa, xb;
} dg;

/* min and max of two numbers (no NaN here): inline, where fmin and fmax
 * are library calls */
static inline double dmin(double a, double b) { return a < b ? a : b; }
static inline double dmax(double a, double b) { return a > b ? a : b; }

static double dlegendre(int m, double x) { return m == 0 ? 0.0 : m == 1 ? 1.0 : 3.0 * x; }

static void dg_free(gf_sh1d *s)
{
    dg *d = s->impl;
    if (!d)
        return;
    free(d->h);
    free(d->moving);
    free(d);
    s->impl = NULL;
}

/* The bed at the Gauss points and interfaces of the grid (ghost cells flat). */
static void bed_at_points(const gf_sh1d *s, dg *d)
{
    const size_t n = s->n, G = (size_t)d->ng;
    for (size_t c = 0; c < d->nc; ++c)
        for (size_t g = 0; g < G; ++g) {
            double zeta = 0.0; /* ghost cells: flat */
            if (c >= 1 && c <= n)
                gf_sh1d_bed(s, gf_sh1d_cell_centre(s, c - 1) + 0.5 * s->dx * d->xg[g], &zeta, &d->kg[c * G + g]);
            d->czg[c * G + g] = cos(zeta);
            d->szg[c * G + g] = sin(zeta);
        }
    for (size_t f = 0; f <= n; ++f) {
        double zeta, kap;
        gf_sh1d_bed(s, s->x0 + (double)f * s->dx, &zeta, &kap);
        d->czf[f] = cos(zeta);
    }
}

/* The moving mesh's nodes xa, xb: the grid of s (and the bed's values at
 * its points, where the bed is not a plane: without topography they do not
 * depend on x). */
static void set_geometry(gf_sh1d *s, dg *d, double xa, double xb)
{
    s->x0 = xa;
    s->dx = (xb - xa) / (double)s->n;
    if (s->cfg.topo)
        bed_at_points(s, d);
}

static gf_status dg_init(gf_sh1d *s)
{
    const int k = s->cfg.degree;
    dg *d = calloc(1, sizeof *d);
    if (!d)
        return gf_fail(GF_ENOMEM, "rkdg: out of memory");
    d->m = k + 1;
    d->ng = k + 1;
    gsl_integration_glfixed_table *t = gsl_integration_glfixed_table_alloc((size_t)d->ng);
    if (!t) {
        free(d);
        return gf_fail(GF_ENOMEM, "rkdg: out of memory");
    }
    for (int g = 0; g < d->ng; ++g) {
        gsl_integration_glfixed_point(-1.0, 1.0, (size_t)g, &d->xg[g], &d->wg[g], t);
        for (int m = 0; m < d->m; ++m) {
            d->pg[g][m] = gf_sh1d_legendre(m, d->xg[g]);
            d->dpg[g][m] = dlegendre(m, d->xg[g]);
        }
    }
    gsl_integration_glfixed_table_free(t);

    const size_t n = s->n, nc = n + 2, M = (size_t)d->m, G = (size_t)d->ng;
    d->nc = nc;
    const size_t total = 10 * nc * M + 3 * nc + 3 * nc * G + 3 * (n + 1);
    double *blk = calloc(total, sizeof *blk);
    unsigned char *flags = calloc(4 * nc, 1);
    if (!blk || !flags) {
        free(blk);
        free(flags);
        free(d);
        return gf_fail(GF_ENOMEM, "rkdg: out of memory");
    }
    double *p = blk;
    d->h = p; p += nc * M;
    d->q = p; p += nc * M;
    d->h0 = p; p += nc * M;
    d->q0 = p; p += nc * M;
    d->h1 = p; p += nc * M;
    d->q1 = p; p += nc * M;
    d->rh = p; p += nc * M;
    d->rq = p; p += nc * M;
    d->fm = p; p += nc * M;
    d->lim = p; p += nc * M;
    d->cap = p; p += nc;
    d->k = p; p += nc;
    d->ubar = p; p += nc;
    d->kg = p; p += nc * G;
    d->czf = p; p += n + 1;
    d->czg = p; p += nc * G;
    d->szg = p; p += nc * G;
    d->fh = p; p += n + 1;
    d->fqx = p;
    d->moving = flags;
    d->stopped = flags + nc;
    d->moving0 = flags + 2 * nc;
    d->stopped0 = flags + 3 * nc;
    s->impl = d;
    d->ale = s->cfg.moving_mesh;
    d->xa = s->x0;
    d->xb = s->x0 + (double)n * s->dx;
    bed_at_points(s, d);
    for (size_t c = 0; c < nc; ++c)
        d->k[c] = 1.0;
    static const double w_gl[3] = {1.0, 0.5, 1.0 / 6.0};
    s->cfl = s->cfg.cfl > 0.0 ? s->cfg.cfl : 0.9 * fmin(1.0 / (2.0 * k + 1.0), w_gl[k]);
    return GF_SUCCESS;
}

/* ghost cells 0 and n+1 from the boundary conditions */
static void fill_ghosts(const gf_sh1d *s, dg *d, double *h, double *q)
{
    const size_t n = s->n, M = (size_t)d->m;
    for (int side = 0; side < 2; ++side) {
        const gf_bc bc = side == 0 ? s->cfg.bc_left : s->cfg.bc_right;
        const size_t gc = side == 0 ? 0 : n + 1;
        const size_t in = side == 0 ? 1 : n;
        const size_t per = side == 0 ? n : 1;
        if (d->ale && (side == 0 ? d->free_l : d->free_r)) {
            /* beyond a dry front node: the end cell's own polynomial, extended
             * (P(xi -/+ 2) in the ghost's xi), so that the limiters see no jump
             * on the dry side, where no flux passes */
            const double sg = side == 0 ? -1.0 : 1.0;
            const double *hi = &h[in * M], *qi = &q[in * M];
            for (int v = 0; v < 2; ++v) {
                const double *u = v ? qi : hi;
                double *o = v ? &q[gc * M] : &h[gc * M];
                double e[MAXM] = {u[0], 0.0, 0.0};
                if (M > 1) {
                    e[0] += 2.0 * sg * u[1];
                    e[1] = u[1];
                }
                if (M > 2) {
                    e[0] += 6.0 * u[2];
                    e[1] += 6.0 * sg * u[2];
                    e[2] = u[2];
                }
                for (size_t m = 0; m < M; ++m)
                    o[m] = e[m];
            }
            d->moving[gc] = d->moving[in];
            d->k[gc] = d->k[in];
            continue;
        }
        for (size_t m = 0; m < M; ++m) {
            const double sg = (m % 2) ? -1.0 : 1.0;
            if (bc == GF_BC_PERIODIC) {
                h[gc * M + m] = h[per * M + m];
                q[gc * M + m] = q[per * M + m];
            } else if (bc == GF_BC_WALL) {
                h[gc * M + m] = sg * h[in * M + m];
                q[gc * M + m] = -sg * q[in * M + m];
            } else {
                h[gc * M + m] = h[in * M + m];
                q[gc * M + m] = q[in * M + m];
            }
        }
        d->moving[gc] = bc == GF_BC_PERIODIC ? d->moving[per] : d->moving[in];
        d->k[gc] = bc == GF_BC_PERIODIC ? d->k[per] : d->k[in];
    }
}

static inline double poly(const double *u, int M, double x)
{
    double v = u[0];
    if (M > 1)
        v += u[1] * x;
    if (M > 2)
        v += u[2] * 0.5 * (3.0 * x * x - 1.0);
    return v;
}
static inline double right_value(const double *u, int M)
{
    double v = 0.0;
    for (int m = 0; m < M; ++m)
        v += u[m];
    return v;
}
static inline double left_value(const double *u, int M)
{
    double v = 0.0;
    for (int m = 0; m < M; ++m)
        v += (m % 2) ? -u[m] : u[m];
    return v;
}

/* Whether cell c (1..n) is the moving mesh's end cell at a right or a left
 * dry front (both when n = 1): beyond its node is no neighbour and no flux. */
static inline int front_right(const gf_sh1d *s, const dg *d, size_t c) { return d->ale && d->free_r && c == s->n; }
static inline int front_left(const dg *d, size_t c) { return d->ale && d->free_l && c == 1; }

/* point state: depth >= 0 and velocity (0 below h_semi) */
static inline void point_state(const gf_sh1d *s, double h, double q, double *hp, double *up)
{
    *hp = h > 0.0 ? h : 0.0;
    *up = *hp > s->cfg.h_semi ? q / *hp : 0.0;
}

static void update_k(const gf_sh1d *s, dg *d, const double *h, const double *q)
{
    const size_t M = (size_t)d->m;
    for (size_t c = d->lo - 1; c <= d->hi + 1; ++c)
        d->ubar[c] = gf_sh1d_velocity(s, h[c * M], q[c * M]);
    for (size_t c = d->lo; c <= d->hi; ++c) {
        /* next to a front node the one-sided difference (the ghost beyond it
         * is the end cell's polynomial extended, whose velocity means nothing) */
        const size_t r = front_right(s, d, c) ? c : c + 1;
        const size_t l = front_left(d, c) ? c : c - 1;
        d->k[c] = gf_earth_pressure_k(&s->cfg.earth_pressure, d->ubar[r] - d->ubar[l]);
    }
}

/* The velocity at a front node: of the linear velocity u = a + b xi whose
 * h u has the cell's q moments 0 and 1 (int h u P_m = int q P_m, m = 0, 1),
 * at xi = +1 (right) or -1 (left).  Exact for a linear velocity whatever the
 * depth's shape (the cap's edge, Ritter's front, where h vanishes at the node
 * and q/h there means nothing); the mean velocity where the depth's moments
 * leave no second unknown (P0, or h nearly a point mass). */
static double front_velocity(const gf_sh1d *s, const dg *d, const double *h, const double *q, size_t c, double side)
{
    const int M = d->m;
    const double *hc = &h[c * (size_t)M], *qc = &q[c * (size_t)M];
    const double ubar = gf_sh1d_velocity(s, hc[0], qc[0]);
    if (M < 2)
        return ubar;
    /* int h, int xi h, int xi^2 h over [-1, 1]; int q, int xi q */
    const double H0 = 2.0 * hc[0], H1 = 2.0 / 3.0 * hc[1], H2 = 2.0 / 3.0 * hc[0] + (M > 2 ? 4.0 / 15.0 * hc[2] : 0.0);
    const double Q0 = 2.0 * qc[0], Q1 = 2.0 / 3.0 * qc[1];
    const double det = H0 * H2 - H1 * H1;
    if (!(det > 1e-12 * H0 * H2))
        return ubar;
    const double a = (Q0 * H2 - Q1 * H1) / det, b = (H0 * Q1 - H1 * Q0) / det;
    return a + side * b;
}

/* Bounds no front outruns on the moving mesh: the largest Riemann invariant
 * u + 2 sqrt(beta h) of the means of the wet cells between the front cells
 * (rmax), the smallest u - 2 sqrt(beta h) (rmin).  They keep a front cell's
 * thin, poorly resolved layer from accelerating itself and its node (the
 * velocity bound and node_velocities); +-HUGE_VAL where no cell is wet. */
static void invariant_bounds(const gf_sh1d *s, const dg *d, const double *h, const double *q, double *rmin,
                             double *rmax)
{
    const size_t M = (size_t)d->m;
    *rmax = -HUGE_VAL;
    *rmin = HUGE_VAL;
    const size_t lo = d->free_l && d->lo == 1 ? 2 : d->lo, hi = d->free_r && d->hi == s->n ? s->n - 1 : d->hi;
    for (size_t c = lo; c <= hi; ++c)
        if (h[c * M] >= s->cfg.h_semi) {
            const double u = q[c * M] / h[c * M];
            const double c2 = 2.0 * sqrt(gf_sh_beta_c(s->cfg.epsilon, d->k[c], d->czg[c * (size_t)d->ng]) * h[c * M]);
            *rmax = dmax(*rmax, u + c2);
            *rmin = dmin(*rmin, u - c2);
        }
    if (*rmax == -HUGE_VAL) {
        *rmax = HUGE_VAL;
        *rmin = -HUGE_VAL;
    }
}

/* The moving mesh's node velocities (cfg.moving_mesh) for the state h, q:
 * at a front, the edge of the wet/dry Riemann fan at the node, u + 2 sqrt(beta
 * h) (right) or u - 2 sqrt(beta h) (left), h the end cell's trace and u
 * front_velocity's, so that no wave leaves the grid and no flux passes the
 * node; 0 while friction holds the end cell at rest (stopped) or where it is
 * not wet (h < h_semi); 0 at an end on the domain's boundary. */
static void node_velocities(const gf_sh1d *s, const dg *d, const double *h, const double *q, double *va,
                            double *vb)
{
    const size_t n = s->n, M = (size_t)d->m;
    *va = *vb = 0.0;
    if (!d->free_l && !d->free_r)
        return;
    double rmin, rmax;
    invariant_bounds(s, d, h, q, &rmin, &rmax);
    if (d->free_r && h[n * M] >= s->cfg.h_semi && !d->stopped[n]) {
        const double hb = dmax(right_value(&h[n * M], d->m), 0.0);
        *vb = front_velocity(s, d, h, q, n, 1.0) + 2.0 * sqrt(gf_sh_beta_c(s->cfg.epsilon, d->k[n], d->czf[n]) * hb);
        *vb = dmin(*vb, rmax);
    }
    if (d->free_l && h[M] >= s->cfg.h_semi && !d->stopped[1]) {
        const double hb = dmax(left_value(&h[M], d->m), 0.0);
        *va = front_velocity(s, d, h, q, 1, -1.0) - 2.0 * sqrt(gf_sh_beta_c(s->cfg.epsilon, d->k[1], d->czf[0]) * hb);
        *va = dmax(*va, rmin);
    }
}

/* Interface flux: the rkdg paper's Lax–Friedrichs flux (eq. 9, its mass
 * diffusion switched off between cells at rest), except where both sides
 * move towards the same side at more than SUPERCRITICAL times their wave
 * speed (a dry side counts as such).  There every wave of the Riemann
 * problem moves one way, so the exact (Godunov) flux is the upwind flux,
 * and the scheme takes it: Lax–Friedrichs' diffusion alpha (h_R - h_L)
 * would push slower fluid into the thin fast layer ahead of a dry front,
 * which then travels as a shelf of constant depth and velocity (P2 on
 * Ritter from a resolved start: the h = 1e-3 front +10.5 cells ahead at
 * N = 1600 instead of 0.0).  The margin 2 (not 1) keeps the diffusion in
 * transonic fans: upwinding from Froude number 1 lets P1 hold a stationary
 * expansion jump next to the sonic point of a dam break (Ritter, N = 800:
 * L1 0.098 instead of 0.010). */
#define SUPERCRITICAL 2.0

/* Right-hand side without friction (rh, rq), the friction term of every q
 * mode (fm) and the friction capacity of the mean (cap), per unit time.
 * The moving mesh (ALE = 1; not in the papers: the arbitrary
 * Lagrangian-Eulerian form of the weak form, rkdg eq. 12, on cells that move
 * with the nodes): every flux is relative to the mesh velocity w, linear
 * between the node velocities va and vb (F - w U, waves u - w +- c), and the
 * modes' equations are those of the cell's content, d(dx U_m)/dt
 * (euler_stage); no flux passes a front node. */
static inline __attribute__((always_inline)) void rhs_m(const gf_sh1d *s, dg *d, double *h, double *q,
                                                        const int M, const int ALE)
{
    const int G = M; /* d->ng */
    const double eps = s->cfg.epsilon, grav = s->cfg.g, dx = s->dx;
    fill_ghosts(s, d, h, q);
    update_k(s, d, h, q);
    fill_ghosts(s, d, h, q);
    double va = 0.0, dv = 0.0;
    if (ALE) {
        node_velocities(s, d, h, q, &d->va, &d->vb);
        va = d->va;
        dv = (d->vb - d->va) / (double)s->n;
    }

    for (size_t f = d->lo - 1; f <= d->hi; ++f) { /* interface between cells f and f+1 */
        if (ALE && ((f == 0 && d->free_l) || (f == s->n && d->free_r))) {
            d->fh[f] = d->fqx[f] = 0.0; /* a front node: the edge of the fan, h = 0 */
            continue;
        }
        double hl, ul, hr, ur;
        point_state(s, right_value(&h[f * M], M), right_value(&q[f * M], M), &hl, &ul);
        point_state(s, left_value(&h[(f + 1) * M], M), left_value(&q[(f + 1) * M], M), &hr, &ur);
        const double w = ALE ? va + dv * (double)f : 0.0;
        const double vl = ALE ? ul - w : ul, vr = ALE ? ur - w : ur; /* relative to the mesh */
        const double bl = gf_sh_beta_c(eps, d->k[f], d->czf[f]), br = gf_sh_beta_c(eps, d->k[f + 1], d->czf[f]);
        const double cl = sqrt(bl * hl), cr = sqrt(br * hr);
        const double al = fabs(vl) + cl, ar = fabs(vr) + cr;
        const double alpha = al > ar ? al : ar;
        const double eta = (d->moving[f] || d->moving[f + 1]) ? 1.0 : 0.0;
        const double ql = hl * ul, qr = hr * ur;
        const double fl1 = ql * vl + 0.5 * bl * hl * hl, fr1 = qr * vr + 0.5 * br * hr * hr;
        const double gl = ALE ? hl * vl : ql, gr = ALE ? hr * vr : qr; /* mass fluxes */
        if (hl > 0.0 && vl > SUPERCRITICAL * cl && (hr <= 0.0 || vr > SUPERCRITICAL * cr)) {
            d->fh[f] = gl; /* every wave moves right: the exact flux is the upwind one */
            d->fqx[f] = fl1;
        } else if (hr > 0.0 && -vr > SUPERCRITICAL * cr && (hl <= 0.0 || -vl > SUPERCRITICAL * cl)) {
            d->fh[f] = gr;
            d->fqx[f] = fr1;
        } else {
            d->fh[f] = 0.5 * (gl + gr) - 0.5 * eta * alpha * (hr - hl); /* eq. 9 with eta */
            d->fqx[f] = 0.5 * (fl1 + fr1) - 0.5 * alpha * (qr - ql);
        }
    }
    for (size_t c = d->lo; c <= d->hi; ++c) {
        const double *hc = &h[c * M], *qc = &q[c * M];
        double vh[MAXM] = {0}, vq[MAXM] = {0}, sq[MAXM] = {0}, fr[MAXM] = {0};
        double cap = 0.0;
        for (int g = 0; g < G; ++g) {
            const double cz = d->czg[c * G + g], sz = d->szg[c * G + g], kap = d->kg[c * G + g];
            double hp, up;
            point_state(s, poly(hc, M, d->xg[g]), poly(qc, M, d->xg[g]), &hp, &up);
            const double beta = gf_sh_beta_c(eps, d->k[c], cz);
            const double vp = ALE ? up - (va + dv * ((double)(c - 1) + 0.5 * (1.0 + d->xg[g]))) : up;
            const double f1 = hp * vp, f2 = hp * up * vp + 0.5 * beta * hp * hp;
            const double src = hp * grav * sz;
            const double tau = gf_sh1d_friction_c(s, hp, up, cz, kap);
            const double w = d->wg[g];
            const double sgn = up > 0.0 ? 1.0 : (up < 0.0 ? -1.0 : 0.0);
            cap += 0.5 * w * tau;
            for (int m = 0; m < M; ++m) {
                vh[m] += w * f1 * d->dpg[g][m];                    /* H_m of eq. 12 */
                vq[m] += w * f2 * d->dpg[g][m];
                sq[m] += 0.5 * dx * w * src * d->pg[g][m];
                fr[m] -= 0.5 * w * sgn * tau * d->pg[g][m];
            }
        }
        for (int m = 0; m < M; ++m) {
            const double c2 = (2.0 * m + 1.0) / dx, sl = (m % 2) ? -1.0 : 1.0;
            d->rh[c * M + m] = c2 * (vh[m] - (d->fh[c] - sl * d->fh[c - 1]));
            d->rq[c * M + m] = c2 * (vq[m] - (d->fqx[c] - sl * d->fqx[c - 1]) + sq[m]);
            d->fm[c * M + m] = (2.0 * m + 1.0) * fr[m];
        }
        d->cap[c] = cap;
    }
}

/* rhs_m with the number of modes a constant, so that the loops over modes
 * and Gauss points unroll (the same operations in the same order) */
static void rhs(const gf_sh1d *s, dg *d, double *h, double *q)
{
    if (d->ale)
        switch (d->m) {
        case 1: rhs_m(s, d, h, q, 1, 1); break;
        case 2: rhs_m(s, d, h, q, 2, 1); break;
        default: rhs_m(s, d, h, q, 3, 1); break;
        }
    else
        switch (d->m) {
        case 1: rhs_m(s, d, h, q, 1, 0); break;
        case 2: rhs_m(s, d, h, q, 2, 0); break;
        default: rhs_m(s, d, h, q, 3, 0); break;
        }
}

/* TVB-modified minmod: the first argument unchanged when small (M dx^2) */
static inline double mmt(const gf_sh1d *s, double a, double b, double c)
{
    if (s->cfg.tvb_m > 0.0 && fabs(a) <= s->cfg.tvb_m * s->dx * s->dx)
        return a;
    return gf_sh1d_minmod3(a, b, c);
}

/* Hierarchical moment limiter (Krivodonova 2007): from the highest mode
 * down, u_m = minmod(u_m, (u_{m-1}^{j+1} - u_{m-1}^j)/(2m-1),
 * (u_{m-1}^j - u_{m-1}^{j-1})/(2m-1)) (TVB-relaxed when M > 0); stops at the
 * first mode left unchanged. */
static void limit_moments(const gf_sh1d *s, const dg *d, double *u)
{
    const int M = d->m;
    /* neighbours' modes as they were before this sweep: left-right symmetric */
    memcpy(d->lim + (d->lo - 1) * (size_t)M, u + (d->lo - 1) * (size_t)M,
           (d->hi - d->lo + 3) * (size_t)M * sizeof *u);
    for (size_t c = d->lo; c <= d->hi; ++c) {
        double *uc = &u[c * (size_t)M];
        const double *ul = &d->lim[(c - 1) * (size_t)M], *ur = &d->lim[(c + 1) * (size_t)M];
        for (int m = M - 1; m >= 1; --m) {
            const double w = 1.0 / (2.0 * m - 1.0);
            const double lim = mmt(s, uc[m], w * (ur[m - 1] - uc[m - 1]), w * (uc[m - 1] - ul[m - 1]));
            if (lim == uc[m])
                break;
            uc[m] = lim;
        }
    }
}

/* The limiter of the configuration on one variable (h or q): the moment
 * limiter, or the limiting procedure of rkdg eq. 13. */
static void limit_var(const gf_sh1d *s, const dg *d, double *u)
{
    if (s->cfg.limiter == GF_LIMITER_MOMENT && d->m > 1) {
        limit_moments(s, d, u);
        return;
    }
    const int M = d->m;
    const double gam = s->cfg.gamma;
    if (M < 2 || s->cfg.limiter != GF_LIMITER_MINMOD)
        return;
    /* means are not changed by limiting: use them directly */
    for (size_t c = d->lo; c <= d->hi; ++c) {
        double *uc = &u[c * (size_t)M];
        const double dm = gam * (uc[0] - u[(c - 1) * (size_t)M]);
        const double dp = gam * (u[(c + 1) * (size_t)M] - uc[0]);
        const double vr = right_value(uc, M) - uc[0];
        const double vl = uc[0] - left_value(uc, M);
        const double mr = mmt(s, vr, dm, dp), ml = mmt(s, vl, dm, dp);
        if (mr == vr && ml == vl)
            continue;
        uc[1] = mmt(s, uc[1], dm, dp);
        if (M > 2)
            uc[2] = 0.0;
    }
}

/* Velocity bound of the wet cells: the point velocities q/h at the end and
 * Gauss points stay within the range of the mean velocities of the cell and
 * its wet neighbours.  The higher modes of q are blended towards u_mean h(x)
 * (the same mean q, constant velocity):
 *   q(x) = u_mean h(x) + theta (q(x) - u_mean h(x)),
 * with the largest theta in [0, 1] that satisfies the bound at every point.
 * Without it, where h(x) nearly vanishes at a cell end (a dry front, after
 * the positivity scaling) q/h there is arbitrary: spurious speeds, wave-speed
 * estimates and fluxes follow. */
static inline __attribute__((always_inline)) void limit_velocity(const gf_sh1d *s, dg *d, double *h, double *q,
                                                                 const int M)
{
    const double hs = s->cfg.h_semi;
    double rmin = -HUGE_VAL, rmax = HUGE_VAL;
    if (d->ale && (d->free_l || d->free_r))
        invariant_bounds(s, d, h, q, &rmin, &rmax);
    for (size_t c = d->lo; c <= d->hi; ++c) {
        double *hc = &h[c * (size_t)M], *qc = &q[c * (size_t)M];
        if (hc[0] < hs)
            continue;
        const double ub = d->ubar[c];
        double lo = ub, hi = ub;
        /* the moving mesh's end cell at a front (-1 left, +1 right, 0 not):
         * beyond its node is no neighbour, and the depth vanishes at the node,
         * where q/h means nothing; its range is the inner neighbour's mean and
         * the two means extrapolated one cell on, 2 u_c - u_in, within
         * invariant_bounds (a velocity that grows towards the front is not an
         * overshoot), and the node is not tested */
        const int front = front_right(s, d, c) ? 1 : front_left(d, c) ? -1 : 0;
        for (size_t nb = c - 1; nb <= c + 1; nb += 2)
            if (h[nb * (size_t)M] >= hs && !(front && (nb == 0 || nb == s->n + 1))) {
                lo = dmin(lo, d->ubar[nb]);
                hi = dmax(hi, d->ubar[nb]);
            }
        if (front) {
            const size_t in = front > 0 ? c - 1 : c + 1;
            if (h[in * (size_t)M] >= hs) {
                const double uf = dmax(dmin(2.0 * ub - d->ubar[in], rmax), rmin);
                lo = dmin(lo, uf);
                hi = dmax(hi, uf);
            }
        }
        /* a tolerance far above round-off and far below any physical velocity
         * difference keeps the decision continuous at velocity extrema (left and
         * right mirror images are limited alike) */
        const double tol = 1e-8 * (dmax(fabs(lo), fabs(hi)) + sqrt(s->cfg.epsilon * d->k[c] * hc[0]));
        lo -= tol;
        hi += tol;
        double theta = 1.0;
        for (int p = -2; p < M && theta > 0.0; ++p) {
            if ((front == -1 && p == -2) || (front == 1 && p == -1))
                continue;
            const double x = p == -2 ? -1.0 : p == -1 ? 1.0 : d->xg[p];
            const double hp = poly(hc, M, x), dq = poly(qc, M, x) - ub * hp;
            if (dq == 0.0)
                continue;
            if (hp <= 0.0) {
                theta = 0.0;
                break;
            }
            const double room = (dq > 0.0 ? hi - ub : lo - ub) * hp / dq;
            theta = dmin(theta, dmax(room, 0.0));
        }
        if (theta < 1.0)
            for (int m = 1; m < M; ++m)
                qc[m] = ub * hc[m] + theta * (qc[m] - ub * hc[m]);
    }
}

/* Positivity scaling, dry and semi-wet treatment (section 3.4). */
static inline __attribute__((always_inline)) gf_status fix_cells_m(gf_sh1d *s, dg *d, double *h, double *q,
                                                                   const int M)
{
    const double he = s->cfg.h_eps, hs = s->cfg.h_semi;
    for (size_t c = d->lo; c <= d->hi; ++c) {
        double *hc = &h[c * (size_t)M], *qc = &q[c * (size_t)M];
        const double hb = hc[0];
        if (hb < 0.0) {
            if (hb < -1e-13)
                return gf_fail(GF_EPHYS, "rkdg: negative mean depth %g in cell %zu at t = %g; "
                                         "lower the Courant number", hb, c - 1, s->t);
            hc[0] = 0.0; /* round-off */
        }
        if (M > 1) {
            double hmin = dmin(right_value(hc, M), left_value(hc, M));
            for (int g = 0; g < M; ++g)
                hmin = dmin(hmin, poly(hc, M, d->xg[g]));
            if (hmin < 0.0) {
                /* a hair inside [0, 1] so that round-off leaves every point >= 0 */
                const double th = hb > 0.0 ? (1.0 - 1e-12) * hb / (hb - hmin) : 0.0;
                for (int m = 1; m < M; ++m) {
                    hc[m] *= th;
                    qc[m] *= th;
                }
            }
        }
    }
    fill_ghosts(s, d, h, q);
    for (size_t c = d->lo - 1; c <= d->hi + 1; ++c)
        d->ubar[c] = h[c * (size_t)M] >= hs ? q[c * (size_t)M] / h[c * (size_t)M] : 0.0;
    for (size_t c = d->lo; c <= d->hi; ++c) {
        double *hc = &h[c * (size_t)M], *qc = &q[c * (size_t)M];
        const double hb = hc[0];
        if (hb >= hs)
            continue;
        double ub = 0.0;
        if (hb >= he) { /* semi-wet: velocity from the wetter neighbour (not a front's ghost) */
            const double hl = front_left(d, c) ? 0.0 : h[(c - 1) * (size_t)M];
            const double hr = front_right(s, d, c) ? 0.0 : h[(c + 1) * (size_t)M];
            if (hl < hs && hr < hs)
                ub = 0.0;
            else if (hl >= hr)
                ub = d->ubar[c - 1];
            else
                ub = d->ubar[c + 1];
        } else {
            for (int m = 1; m < M; ++m)
                hc[m] = 0.0;
        }
        qc[0] = hb * ub;
        for (int m = 1; m < M; ++m)
            qc[m] = 0.0;
    }
    if (M > 1 && s->cfg.velocity_limiter)
        limit_velocity(s, d, h, q, M);
    return GF_SUCCESS;
}

static gf_status fix_cells(gf_sh1d *s, dg *d, double *h, double *q)
{
    switch (d->m) {
    case 1: return fix_cells_m(s, d, h, q, 1);
    case 2: return fix_cells_m(s, d, h, q, 2);
    default: return fix_cells_m(s, d, h, q, 3);
    }
}

/* After new modes: limiting, positivity and dry treatment, moving flags. */
static gf_status finish_state(gf_sh1d *s, dg *d)
{
    d->lo = 1, d->hi = s->n; /* every cell */
    fill_ghosts(s, d, d->h, d->q);
    limit_var(s, d, d->h);
    limit_var(s, d, d->q);
    gf_status st = fix_cells(s, d, d->h, d->q);
    for (size_t c = 1; c <= s->n; ++c)
        d->moving[c] = d->q[c * (size_t)d->m] != 0.0;
    fill_ghosts(s, d, d->h, d->q);
    return st;
}

/* L2 projection of the fine solver's two cells onto each coarse cell: on
 * the coarse cell's left half xi_c = (xi_f - 1)/2, on its right half
 * (xi_f + 1)/2; 5-point Gauss on each half is exact for the degree <= 4
 * integrands, so the means are the fine pair's exactly (mass to round-off). */
static gf_status dg_restrict_from(gf_sh1d *s, const gf_sh1d *fs)
{
    dg *d = s->impl;
    const dg *f = fs->impl;
    const int M = d->m;
    if (d->ale) { /* the moving mesh: the fine grid's nodes */
        d->free_l = f->free_l;
        d->free_r = f->free_r;
        d->xa = f->xa;
        d->xb = f->xb;
        d->va = f->va;
        d->vb = f->vb;
        set_geometry(s, d, d->xa, d->xb);
        for (size_t c = 1; c <= s->n; ++c)
            d->stopped[c] = f->stopped[2 * c - 1] && f->stopped[2 * c];
    }
    double x5[5], w5[5];
    gf_status st = gf_gauss_legendre5(x5, w5);
    if (st)
        return st;
    for (size_t c = 1; c <= s->n; ++c)
        for (int m = 0; m < M; ++m) {
            double sh = 0.0, sq = 0.0;
            for (int half = 0; half < 2; ++half) {
                const size_t fc = 2 * (c - 1) + (size_t)half + 1;
                for (int g = 0; g < 5; ++g) {
                    const double xc = 0.5 * (x5[g] + (half ? 1.0 : -1.0)), w = 0.5 * w5[g] * gf_sh1d_legendre(m, xc);
                    sh += w * poly(&f->h[fc * (size_t)M], M, x5[g]);
                    sq += w * poly(&f->q[fc * (size_t)M], M, x5[g]);
                }
            }
            d->h[c * (size_t)M + m] = 0.5 * (2.0 * m + 1.0) * sh;
            d->q[c * (size_t)M + m] = 0.5 * (2.0 * m + 1.0) * sq;
        }
    return finish_state(s, d);
}

/* The moving mesh's first nodes: the wet interval of the initial data,
 * sampled 16 times per cell of the fixed grid, its ends found by bisection;
 * an end on the domain's boundary stays there. */
static gf_status initial_nodes(gf_sh1d *s, dg *d, gf_sh1d_initial_fn fn, void *ctx)
{
    double xa, xb;
    gf_status st = gf_sh1d_wet_interval(s, fn, ctx, &xa, &xb, &d->free_l, &d->free_r);
    if (st) {
        char why[512];
        snprintf(why, sizeof why, "%s", gf_error_detail());
        return gf_fail(st, "rkdg moving mesh (the mesh spans the wet interval): %s", why);
    }
    d->xa = xa;
    d->xb = xb;
    set_geometry(s, d, xa, xb);
    return GF_SUCCESS;
}

/* The moving mesh's first stopped flags: friction holds an initial cell
 * at rest when the net force on its mean is within the friction capacity
 * (the Euler stage's test as dt -> 0); it decides whether a front node
 * moves in the first stage. */
static void initial_stopped(gf_sh1d *s, dg *d)
{
    const size_t M = (size_t)d->m;
    for (size_t c = 0; c < d->nc; ++c)
        d->stopped[c] = 1; /* nodes still in this call of rhs */
    rhs(s, d, d->h, d->q);
    for (size_t c = 1; c <= s->n; ++c)
        d->stopped[c] = d->q[c * M] == 0.0 && fabs(d->rq[c * M]) <= d->cap[c];
}

static gf_status dg_set_initial(gf_sh1d *s, gf_sh1d_initial_fn fn, void *ctx)
{
    dg *d = s->impl;
    const int M = d->m;
    double x5[5], w5[5];
    gf_status gst = gf_gauss_legendre5(x5, w5);
    if (gst)
        return gst;
    if (d->ale && (gst = initial_nodes(s, d, fn, ctx)))
        return gst;
    for (size_t c = 1; c <= s->n; ++c) {
        double sh[MAXM], sq[MAXM];
        if ((gst = gf_sh1d_project_cell(s, fn, ctx, gf_sh1d_cell_centre(s, c - 1), s->dx, x5, w5, 5, M, sh, sq)))
            return gst;
        for (int m = 0; m < M; ++m) {
            d->h[c * (size_t)M + m] = 0.5 * (2.0 * m + 1.0) * sh[m]; /* eq. 8 */
            d->q[c * (size_t)M + m] = 0.5 * (2.0 * m + 1.0) * sq[m];
        }
    }
    gst = finish_state(s, d);
    if (!gst && d->ale)
        initial_stopped(s, d);
    return gst;
}

/* The largest |u - w| + sqrt(beta h) over both end values and the Gauss
 * points of every wet cell, w the mesh velocity, linear va + dv (x - x0) / dx
 * (0 on the fixed grid, and for the speed in the bed's frame).  Not at a
 * moving mesh's front node: no flux passes it, the node's own velocity is
 * the fan's edge (node_velocities), and q/h of the trace there, where the
 * depth vanishes, means nothing (the velocity bound does not test it
 * either).  Counting it cut P2's step up to 40-fold while a dam break's fan was
 * inside the end cell (Ritter, N = 400, t = 0.03-0.2: the trace's q/h up to
 * 107 at h = 3e-5). */
static double max_point_speed(const gf_sh1d *s, double va, double dv)
{
    const dg *d = s->impl;
    const int M = d->m;
    double amax = 0.0;
    for (size_t c = 1; c <= s->n; ++c) {
        const double *hc = &d->h[c * (size_t)M], *qc = &d->q[c * (size_t)M];
        if (hc[0] <= s->cfg.h_eps)
            continue;
        const double beta = gf_sh_beta_c(s->cfg.epsilon, d->k[c], d->czg[c * (size_t)d->ng]);
        double hp, up;
        const double wl = va + dv * (double)(c - 1), wr = wl + dv; /* 0 on the fixed grid */
        if (!front_right(s, d, c)) {
            point_state(s, right_value(hc, M), right_value(qc, M), &hp, &up);
            amax = dmax(amax, fabs(up - wr) + sqrt(beta * hp));
        }
        if (!front_left(d, c)) {
            point_state(s, left_value(hc, M), left_value(qc, M), &hp, &up);
            amax = dmax(amax, fabs(up - wl) + sqrt(beta * hp));
        }
        for (int g = 0; g < d->ng; ++g) {
            point_state(s, poly(hc, M, d->xg[g]), poly(qc, M, d->xg[g]), &hp, &up);
            amax = dmax(amax, fabs(up - (wl + 0.5 * dv * (1.0 + d->xg[g]))) + sqrt(beta * hp));
        }
    }
    return amax;
}

/* CFL step from the largest wave speed |u| + sqrt(beta h) (on the moving
 * mesh relative to it) over every point the fluxes see (both end values and
 * the Gauss points of every cell), not only the means: the positivity of the
 * means (Zhang–Shu) needs dt alpha_interface <= w_GL dx. */
static double dg_max_dt(const gf_sh1d *s)
{
    const dg *d = s->impl;
    double amax = 0.0, va = 0.0, dv = 0.0;
    if (d->ale) { /* speeds relative to the mesh */
        double vb;
        node_velocities(s, d, d->h, d->q, &va, &vb);
        dv = (vb - va) / (double)s->n;
        /* and the cells shrink by at most a quarter in a step */
        amax = dmax(amax, -4.0 * dv * s->cfl);
    }
    amax = dmax(amax, max_point_speed(s, va, dv));
    return amax > 0.0 ? s->cfl * s->dx / amax : HUGE_VAL;
}

/* out = a*base + b*(in + dt L(in)), with friction that never reverses the
 * mean momentum, then limiter, positivity and dry treatment.
 * The moving mesh: the stage's nodes are the same combination of the base's
 * nodes and the input's moved at its node velocities, x_out = a x_b + b (x_in
 * + dt v), and the cells' contents dx U combine alike (U_out = (a dx_b U_b +
 * b dx_in U_e) / dx_out), so that a uniform state stays uniform (the
 * geometric conservation law) and the mass is kept.  xin, xbase, xout: the
 * nodes (xa, xb) of hin, hb and hout.  *out: the mass that has left through
 * the domain's ends in the step so far, combined like the contents (out_in
 * that of hin, 0 that of the base, the step's start). */
static gf_status euler_stage(gf_sh1d *s, dg *d, double *hin, double *qin, const double xin[2], double a,
                             const double *hb, const double *qb, const double xbase[2], double b, double dt,
                             double *hout, double *qout, double xout[2], double out_in, double *out)
{
    const int M = d->m;
    double ra = a, rb = b; /* weights of the base and the Euler update */
    if (d->ale) {
        set_geometry(s, d, xin[0], xin[1]);
        rhs(s, d, hin, qin);
        /* a + b = 1: written as the base moved by b times the input's
         * displacement, and the weights as a and b times width ratios, so
         * that nodes at rest (v = 0, x_in = x_base) stay where they are to
         * the bit and the weights stay a and b; a x_b + b x_b and a w / w
         * are not always x_b and a in floating point, and a resting pile's
         * depths crept by an ulp a step (Coulomb pile, P2: the mass 3e-12
         * off after 23,000 steps) */
        const double xa = hb ? xbase[0] + b * ((xin[0] - xbase[0]) + dt * d->va) : xin[0] + dt * d->va;
        const double xe = hb ? xbase[1] + b * ((xin[1] - xbase[1]) + dt * d->vb) : xin[1] + dt * d->vb;
        if (!(xe - xa > 0.0)) /* the wet interval collapsed in this step: repeat it in halves */
            return gf_fail(GF_EPHYS, "rkdg moving mesh: the wet interval collapsed at t = %g", s->t);
        ra = hb ? a * ((xbase[1] - xbase[0]) / (xe - xa)) : 0.0;
        rb = b * ((xin[1] - xin[0]) / (xe - xa));
        xout[0] = xa;
        xout[1] = xe;
    } else
        rhs(s, d, hin, qin);
    /* d(sum h_0 dx)/dt = fh[0] - fh[n]: the boundary fluxes, where computed
     * (outside lo..hi every cell is dry and no flux passes) */
    const double rate = (d->hi == s->n ? d->fh[s->n] : 0.0) - (d->lo == 1 ? d->fh[0] : 0.0);
    *out = b * (out_in + dt * rate);
    for (size_t c = d->lo; c <= d->hi; ++c) {
        const size_t o = c * (size_t)M;
        double he[MAXM] = {0}, qe[MAXM] = {0};
        for (int m = 0; m < M; ++m) {
            he[m] = hin[o + m] + dt * d->rh[o + m];
            qe[m] = qin[o + m] + dt * d->rq[o + m];
        }
        const double capacity = dt * d->cap[c];
        if (fabs(qe[0]) <= capacity || he[0] <= s->cfg.h_eps) { /* friction holds: at rest */
            for (int m = 0; m < M; ++m)
                qe[m] = 0.0;
            d->stopped[c] = 1;
        } else {
            qe[0] = gf_friction_decelerate(qe[0], capacity);
            for (int m = 1; m < M; ++m)
                qe[m] += dt * d->fm[o + m];
            d->stopped[c] = 0;
        }
        for (int m = 0; m < M; ++m) {
            hout[o + m] = (hb ? ra * hb[o + m] : 0.0) + rb * he[m];
            qout[o + m] = (qb ? ra * qb[o + m] : 0.0) + rb * qe[m];
        }
    }
    if (d->ale)
        set_geometry(s, d, xout[0], xout[1]); /* the limiters' TVB bound M dx^2 */
    fill_ghosts(s, d, hout, qout);
    limit_var(s, d, hout);
    limit_var(s, d, qout);
    gf_status st = fix_cells(s, d, hout, qout);
    for (size_t c = d->lo; c <= d->hi; ++c)
        d->moving[c] = !d->stopped[c] && qout[c * (size_t)M] != 0.0;
    return st;
}

/* One SSP-RK3 step (section 3.2) from (h, q); GF_EPHYS when a stage made a
 * mean depth negative (the state is then restored by the caller). */
static gf_status rk3_step(gf_sh1d *s, dg *d, double dt)
{
    const size_t nm = d->nc * (size_t)d->m;
    gf_status st;
    gf_sh1d_active_range(s, d->h, d->q, (size_t)d->m, &d->lo, &d->hi); /* the cells that can change */
    memcpy(d->h0, d->h, nm * sizeof *d->h);
    memcpy(d->q0, d->q, nm * sizeof *d->q);
    memcpy(d->moving0, d->moving, d->nc);
    memcpy(d->stopped0, d->stopped, d->nc);
    const double x0[2] = {d->xa, d->xb};
    double x1[2] = {d->xa, d->xb}, x2[2] = {d->xa, d->xb}, xn[2] = {d->xa, d->xb};
    double o1, o2, on; /* the mass out through the ends after each stage */
    if ((st = euler_stage(s, d, d->h0, d->q0, x0, 0.0, NULL, NULL, x0, 1.0, dt, d->h1, d->q1, x1, 0.0, &o1)) ||
        (st = euler_stage(s, d, d->h1, d->q1, x1, 0.75, d->h0, d->q0, x0, 0.25, dt, d->h1, d->q1, x2, o1, &o2)) ||
        (st = euler_stage(s, d, d->h1, d->q1, x2, 1.0 / 3.0, d->h0, d->q0, x0, 2.0 / 3.0, dt, d->h, d->q, xn, o2,
                          &on))) {
        memcpy(d->h, d->h0, nm * sizeof *d->h);
        memcpy(d->q, d->q0, nm * sizeof *d->q);
        memcpy(d->moving, d->moving0, d->nc);
        memcpy(d->stopped, d->stopped0, d->nc);
        if (d->ale)
            set_geometry(s, d, d->xa, d->xb);
        fill_ghosts(s, d, d->h, d->q);
        return st;
    }
    d->xa = xn[0];
    d->xb = xn[1];
    s->outflow += on;
    /* cells stopped by friction in the last stage are at rest */
    for (size_t c = d->lo; c <= d->hi; ++c)
        if (d->stopped[c])
            for (int m = 0; m < d->m; ++m)
                d->q[c * (size_t)d->m + m] = 0.0;
    fill_ghosts(s, d, d->h, d->q);
    return GF_SUCCESS;
}

/* A step of dt: where a stage would make a mean depth negative (the wave
 * speeds grew inside the step beyond the CFL estimate), the step is
 * repeated as two half steps, down to dt / 2^20; the number of such
 * rejections is counted (gf_sh1d_rejected_steps). */
static gf_status dg_substep(gf_sh1d *s, dg *d, double dt, int depth)
{
    gf_status st = rk3_step(s, d, dt);
    if (st != GF_EPHYS)
        return st;
    if (depth == 20)
        return gf_fail(GF_EPHYS, "rkdg: negative mean depth at t = %g even with the step "
                                 "halved 20 times", s->t);
    s->rejected++;
    if ((st = dg_substep(s, d, 0.5 * dt, depth + 1)))
        return st;
    return dg_substep(s, d, 0.5 * dt, depth + 1);
}

/* A front node that reached the domain's end stays there: the node is put
 * on the end exactly, every cell stretched or squeezed alike by what the
 * landing step (dg_landing_dt) missed it by, at most LANDING_GAP of a cell
 * short or O(dt^2) past; the cells' contents are kept, so the mass is.  From
 * then on the end is a fixed node with the configured boundary condition
 * (wall: the flow is reflected; transmissive: it leaves). */
#define LANDING_GAP 1e-3
static void land_fronts(gf_sh1d *s, dg *d)
{
    const double gap = LANDING_GAP * s->dx;
    const int right = d->free_r && d->xb >= s->cfg.x_max - gap;
    const int left = d->free_l && d->xa <= s->cfg.x_min + gap;
    if (!right && !left)
        return;
    const double xa = left ? s->cfg.x_min : d->xa, xb = right ? s->cfg.x_max : d->xb;
    const double r = (d->xb - d->xa) / (xb - xa); /* old width over new: contents kept */
    const size_t M = (size_t)d->m;
    for (size_t c = 1; c <= s->n; ++c)
        for (size_t m = 0; m < M; ++m) {
            d->h[c * M + m] *= r;
            d->q[c * M + m] *= r;
        }
    d->xa = xa;
    d->xb = xb;
    if (right)
        d->free_r = 0;
    if (left)
        d->free_l = 0;
    set_geometry(s, d, xa, xb);
    fill_ghosts(s, d, d->h, d->q);
}

static gf_status dg_step(gf_sh1d *s, double dt)
{
    dg *d = s->impl;
    gf_status st = dg_substep(s, d, dt, 0);
    if (st || !d->ale)
        return st;
    land_fronts(s, d);
    return GF_SUCCESS;
}

/* The step after which a moving front node reaches the domain's end, at the
 * node velocity of the last stage (no new scan; the landing is then within
 * O(dt^2), and land_fronts puts the node on the end once it is within
 * LANDING_GAP of a cell), HUGE_VAL when none moves towards it. */
static double dg_landing_dt(const gf_sh1d *s)
{
    const dg *d = s->impl;
    double dt = HUGE_VAL;
    if (d->ale && d->free_r && d->vb > 0.0)
        dt = dmin(dt, (s->cfg.x_max - d->xb) / d->vb);
    if (d->ale && d->free_l && d->va < 0.0)
        dt = dmin(dt, (s->cfg.x_min - d->xa) / d->va);
    return dt > 0.0 ? dt : HUGE_VAL;
}

static void dg_means(const gf_sh1d *s, double *h, double *q)
{
    const dg *d = s->impl;
    for (size_t i = 0; i < s->n; ++i) {
        h[i] = d->h[(i + 1) * (size_t)d->m];
        q[i] = d->q[(i + 1) * (size_t)d->m];
    }
}

static void dg_eval(const gf_sh1d *s, size_t cell, double xi, double *h, double *q)
{
    const dg *d = s->impl;
    *h = poly(&d->h[(cell + 1) * (size_t)d->m], d->m, xi);
    *q = poly(&d->q[(cell + 1) * (size_t)d->m], d->m, xi);
}

static double dg_min_depth(const gf_sh1d *s)
{
    const dg *d = s->impl;
    const int M = d->m;
    double mn = HUGE_VAL;
    for (size_t c = 1; c <= s->n; ++c) {
        const double *hc = &d->h[c * (size_t)M];
        mn = fmin(mn, fmin(right_value(hc, M), left_value(hc, M)));
        for (int g = 0; g < d->ng; ++g)
            mn = fmin(mn, poly(hc, M, d->xg[g]));
    }
    return mn;
}

/* The largest wave speed |u| + sqrt(beta h) (the start-up's length): on the
 * fixed grid that of max_dt's bound; on the moving mesh in the bed's frame,
 * not relative to the mesh. */
static double dg_wave_speed(const gf_sh1d *s)
{
    const dg *d = s->impl;
    return d->ale ? max_point_speed(s, 0.0, 0.0) : s->cfl * s->dx / dg_max_dt(s);
}

static const gf_sh1d_type dg_type = {
    "rkdg", dg_init, dg_free, dg_set_initial, dg_max_dt, dg_step, dg_means, dg_eval, dg_min_depth,
    dg_restrict_from, dg_wave_speed, NULL, dg_landing_dt,
};
const gf_sh1d_type *const gf_sh1d_rkdg = &dg_type;
