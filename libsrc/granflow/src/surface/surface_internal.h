/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Private interface of the explicit surface scheme (granflow/surface.h):
 * the kernel's struct and its per-edge and per-slot layouts, the small
 * inline helpers that the parts' hot loops share, and the core's functions
 * that other parts call.  Not installed.  The parts:
 *   surface.c          the core: configuration and mesh checks, edge frames,
 *                      alloc/free, the state, the SSP-RK2 step driver (its
 *                      stages, step halving), the accessors;
 *   surface_halo.c     parallel runs: the caller's exchange and minimum
 *                      callbacks, the refined levels' halos (surface_halo.h);
 *   surface_active.c   the active set: wet faces, two rings, their edges
 *                      (surface_active.h);
 *   surface_recon.c    reconstruction: limited gradients and the states at
 *                      the edges (surface_recon.h);
 *   surface_flux.c     edge fluxes: HLL, static and boundary edges, the sums
 *                      per face, the positivity fallback (surface_flux.h);
 *   surface_cfl.c      the step bound, gf_surface_max_dt;
 *   surface_source.c   sources and friction: the face update (surface_source.h);
 *   surface_startup.c  the start-up on refined meshes (surface_startup.h);
 *   surface_exchange.c mass exchange (granflow/mass_exchange.h) once per
 *                      step: entrainment, detrainment, increased friction,
 *                      their per-face and total volumes (surface_exchange.h);
 *   refine.c           the refined meshes (gf_surface_mesh_refine).
 * The lane helpers of the four-lane kernels are in surface_simd.h. */
#ifndef GRANFLOW_SURFACE_INTERNAL_H
#define GRANFLOW_SURFACE_INTERNAL_H

#include "granflow/mass_exchange.h"
#include "granflow/surface.h"
#include "internal.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

/* The mass exchange's per-face fields and totals (surface_exchange.c) */
struct gf_surface_mx {
    gf_mass_exchange_config c;
    double *h_ent;   /* entrainable depth left [n_faces] (at rho_ent) */
    double *h_front; /* the layer as set: intact ahead of a ploughing front [n_faces] */
    double *res;     /* resistance factor [n_faces], or NULL (no resistance area) */
    double *ent;     /* flow thickness entrained, cumulative [n_faces] */
    double *det;     /* flow thickness detrained, cumulative [n_faces] */
    double ent_step, det_step, ent_total, det_total; /* volumes [m^3] */
    /* of det_step/det_total: detrained in the speed window |u| < v_min, and
     * of that at rest (|u| = 0) [m^3] (spec §2; AvaFrame detrains neither
     * material at rest nor anything faster by its speed) */
    double det_slow_step, det_rest_step, det_slow_total, det_rest_total;
};

#define NV 4 /* reconstructed variables: h, u_x, u_y, u_z */
/* Per-edge geometry, written once (gf_surface_geometry, when a face of the
 * edge first joins the active set), so that each pass reads only what it
 * needs (on meshes larger than the cache the passes are bound by these
 * reads):
 *  - gf_surface.frame, EF doubles per edge on two cache lines (edge fluxes,
 *    step bound): the frame's nu_L, nu_R (the first line: all the step
 *    bound reads), nu, t, [12] the length, [13], [14] length * nu . n_owner,
 *    length * nu . n_neighbour (the normal part of the edge pressure in
 *    eq. 33);
 *  - the edge's vectors, EG doubles (edge_vectors in surface.c, from which
 *    the face-slot tables below are built; not stored per edge: the edge
 *    fluxes of ghosts and inactive faces take edge centre minus face centre
 *    from the mesh): [0..2] length * edge normal (the Green–Gauss weight of
 *    the owner), [3..5], [6..8] edge centre minus owner / neighbour centre. */
#define EF 16 /* 15 used */
#define EF_NUL 0
#define EF_NUR 3
#define EF_NU 6
#define EF_T 9
#define EF_L 12
#define EF_PO 13
#define EF_PN 14
#define EG 9
#define EG_LW 0
#define EG_RO 3
#define EG_RN 6
/* Per face slot (gf_surface.fe[j], the face's edges in the order of their centres, gf_surface_alloc), SG
 * doubles in gf_surface.fs_geo, so that the per-face passes read their
 * geometry in one run instead of from each edge's block: [0..2] w L nu_e
 * (the Green–Gauss weight, w = +1 for the edge's owner, -1 for its
 * neighbour), [3..5] edge centre minus face centre; beside it
 * gf_surface.fs_other (the face across, -1 on a boundary edge) and
 * gf_surface.fs_nb (1 when the face is the edge's neighbour). */
#define SG 6
/* Per-edge sums for accumulate (gf_surface.eacc, EA per edge, one cache
 * line), written by edge_flux: the products it adds, in the order it adds
 * them: [0] L fh, [1] fp L nu.n_o, [2] fpn L nu.n_n, [3..5] L fm (the
 * owner's momentum flux, and the neighbour's unless [6] is 1), [6] 1 on a
 * static edge, whose neighbour feels L fmn (gf_surface.efmn), [7] unused */
#define EA 8
/* Software prefetch distance (edges, or faces) of the passes over the
 * active set: their edge blocks are read through index lists, in an order
 * (two or more interleaved runs of edge numbers) that the hardware
 * prefetchers do not follow; measured on the 40,000-face wet bench, the edge
 * flux pass takes 0.63x its time with it. */
#ifndef PF_DIST
#define PF_DIST 8
#endif
/* prefetch the n doubles at p, which starts a 64-byte line (the edge blocks
 * of calloc_lines: frame, es, eacc): one prefetch per line */
static inline void prefetch_block(const double *p, int n, int write)
{
    if (write) {
        for (int k = 0; k < n; k += 8)
            __builtin_prefetch(p + k, 1);
    } else {
        for (int k = 0; k < n; k += 8)
            __builtin_prefetch(p + k, 0);
    }
}

/* Where the edges' length, unit normal and centre come from: the mesh's
 * arrays (index NULL), or computed from the points (gf_surface_alloc_edges:
 * edge e is entry index[e] of ends[0], sn[0], or -1 - index[e] of ends[1],
 * sn[1]) */
struct gf_edge_geo {
    int *index;
    const double *points;
    const int *ends[2];
    const double *sn[2];
};

struct gf_surface {
    gf_surface_mesh m;
    struct gf_edge_geo eg;
    /* per edge, its length, where the passes read it (step bound, boundary
     * volumes): the mesh's array, or len_own, written with the edge's frame
     * (gf_surface_geometry) */
    const double *len;
    double *len_own;
    gf_surface_config c;
    size_t nt; /* owned + ghost faces */
    gf_surface_exchange_fn xfn;
    void *xctx;
    gf_surface_edge_exchange_fn xefn; /* per-processor-edge blocks (start-up in parallel) */
    void *xectx;
    gf_surface_min_fn minfn; /* global minima (start-up in parallel) */
    void *minctx;
    int *send_f;   /* the owned faces the exchange sends (NULL: all; gf_surface_set_send_faces) */
    size_t n_send;
    double gmag;
    /* face -> edges (all nt faces; a ghost has its one processor edge) */
    size_t *fe_start;
    int *fe;
    int *fs_other;          /* per slot: the face across the edge, -1 on a boundary */
    unsigned char *fs_nb;   /* per slot: the face is the edge's neighbour */
    double *fs_geo;         /* SG per slot */
    /* per-edge geometry: frame nu, t, nu_L (owner plane), nu_R (neighbour
     * plane) (EF per edge) */
    double *frame;
    /* written when a face first joins the active set (gf_surface_geometry):
     * per edge, its frame block; per face, its slots' fs_geo */
    unsigned char *geo_edge, *geo_face;
    /* state and stage buffers (nt, 3 nt) */
    double *h, *mom, *h1, *m1, *h2, *m2;
    double *a;    /* normal acceleration p_b/(rho h) per face (nt) */
    double *u;    /* velocity of the stage state per face (3 nt; 0 where h <= h_dry) */
    double *pb;   /* n_faces */
    double *grad; /* 3 NV per face (nt): written for the faces next to a ghost (the halo exchange's);
                   * the others' stay 0 (edge_side reads s->es for them) */
    unsigned char *pface; /* per owned face: it has a processor edge (its gradient goes to a ghost) */
    /* per edge and side (owner 0, neighbour 1): h and u reconstructed at the
     * edge centre by gf_surface_gradients() for owned active faces (8 per edge), so
     * that edge_flux reads 64 bytes per edge instead of two gradients */
    double *es;
    /* accumulators per owned face */
    double *acc_h, *acc_m, *acc_pn;
    /* per-edge fluxes: the mass flux per unit length fh (boundary volumes),
     * and the products accumulate sums (EA per edge): of fh, of the momentum
     * fluxes fm, fmn and of the pressure part along nu fp, fpn as the owner
     * and the neighbour feel them (they differ on static edges only) */
    double *fh, *eacc, *efmn; /* efmn: 3 per edge, the neighbour's L fmn of a static edge */
    double *spd; /* per edge: L max(0, s_R), L max(0, -s_L): the owner's and the neighbour's outgoing
                  * rates of the step bound (HLL speeds s_L, s_R) */
    double *ahyd;     /* hydrostatic normal acceleration max(0, -g.n) per face (nt) */
    unsigned char *stat; /* face in the hydrostatic (static) mode this stage (nt) */
    unsigned char *slow; /* |u| < dt |g| this stage (bit 0); owned and wet (bit 1); 0 outside the
                            active set (nt) */
    unsigned char *sedge; /* internal edge with both sides slow this stage (bit 0); bit 1: the
                             stage's edge_flux4 takes it ("plain", stage()) (ne) */
    unsigned char *first;
    double *edge_vol, *edge_vol_step;
    double *inflow; /* per edge: h, u[3] */
    int *inflow_edges;
    size_t n_inflow;
    /* active set */
    unsigned *mark_f, *mark_e, *mark_g, stamp;
    int *act_f, *act_e, *ring, *prev_f;
    int *act_b; /* the boundary edges among act_e (their volumes) */
    int *neg;   /* the owned active faces whose thickness a stage's fluxes would take below 0 (accumulate) */
    int *defer; /* the stage's static and boundary edges, whose fluxes wait for the hydrostatic modes */
    size_t n_act_f, n_act_e, n_act_owned, n_prev_f, n_prev_owned, n_act_b;
    int scan_all; /* the next gf_surface_build_active scans every face for h > 0 (state loaded) */
    double *a_save;
    double *lvl; /* ring level for the parallel active set (nt) */
    int active_fresh; /* the active set matches the state (built since the last change) */
    double h_scale;
    double u_slow; /* speed below which a face next to one at rest is slow: dt |g| */
    int startup_pending; /* the next step begins the start-up on refined meshes (startup_levels) */
    struct gf_startup *su; /* the running start-up, or NULL */
    struct gf_surface_mx *mx; /* mass exchange, or NULL (off: costs one test per step) */
    gf_surface_stats st;
};

/* branch-free min/max for the kernels (finite arguments; fmin/fmax are
 * library calls without -ffinite-math-only) */
static inline double gmin(double a, double b) { return a < b ? a : b; }
static inline double gmax(double a, double b) { return a > b ? a : b; }

static inline double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static inline void cross3(const double *a, const double *b, double *c)
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}
static inline int normalise3(double *a)
{
    const double l = sqrt(dot3(a, a));
    if (!(l > 0.0) || !isfinite(l))
        return -1;
    a[0] /= l, a[1] /= l, a[2] /= l;
    return 0;
}

/* Edge e's length *L, centre xc[3] and, unless nu is NULL, unit normal
 * nu[3] in the surface (owner -> out): the mesh's, or from the points
 * (gf_surface_alloc_edges: OpenFOAM's magLe, edgeCentres and Le / magLe,
 * the same operations in the same order).  A degenerate edge (zero length,
 * or d x n_e = 0) gives a zero normal, without a division by zero
 * (OpenFOAM traps floating-point exceptions); the set-up refuses it. */
static inline void edge_geo(const gf_surface_mesh *m, const struct gf_edge_geo *g, size_t e, double *L,
                            double *xc, double *nu)
{
    if (!g->index) {
        const double *c = m->edge_centre + 3 * e;
        *L = m->length[e];
        xc[0] = c[0], xc[1] = c[1], xc[2] = c[2];
        if (nu)
            memcpy(nu, m->edge_normal + 3 * e, 3 * sizeof *nu);
        return;
    }
    const int j = g->index[e], k = j < 0;
    const size_t i = j < 0 ? (size_t)(-1 - j) : (size_t)j;
    const int *pe = g->ends[k] + 2 * i;
    const double *a = g->points + 3 * (size_t)pe[0], *b = g->points + 3 * (size_t)pe[1];
    const double d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    *L = l;
    for (int q = 0; q < 3; ++q)
        xc[q] = 0.5 * (a[q] + b[q]);
    if (!nu)
        return;
    const double *n = g->sn[k] + 3 * i, *xo = m->centre + 3 * m->owner[e];
    double v[3] = {d[1] * n[2] - d[2] * n[1], d[2] * n[0] - d[0] * n[2], d[0] * n[1] - d[1] * n[0]};
    const double s = v[0] * (xo[0] - xc[0]) + v[1] * (xo[1] - xc[1]) + v[2] * (xo[2] - xc[2]);
    const double sg = s >= 0.0 ? -1.0 : 1.0; /* away from the owner */
    for (int q = 0; q < 3; ++q)
        v[q] *= sg;
    const double vm = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (!(vm > 0.0) || !(l > 0.0)) {
        nu[0] = nu[1] = nu[2] = 0.0;
        return;
    }
    const double r = l / vm; /* Le, of length |d| */
    for (int q = 0; q < 3; ++q)
        nu[q] = v[q] * r / l;
}

/* the velocity of face f in the stage state (H, M): M / H where wet, else 0 */
static inline void velocity(const gf_surface *s, const double *H, const double *M, int f, double *u)
{
    const double h = H[f];
    if (h > s->c.h_dry) {
        const double r = 1.0 / h;
        u[0] = M[3 * f] * r, u[1] = M[3 * f + 1] * r, u[2] = M[3 * f + 2] * r;
    } else
        u[0] = u[1] = u[2] = 0.0;
}

/* the offset of slot j's side of its edge in gf_surface.es (owner 0,
 * neighbour 4) */
static inline size_t es_slot(const gf_surface *s, size_t j)
{
    return 8 * (size_t)s->fe[j] + 4 * (size_t)s->fs_nb[j];
}

#pragma GCC visibility push(hidden) /* the library's own: not exported */
/* The state of the owned faces.  exact == 0 (an initial condition): m
 * projected onto the tangent planes, 0 where h <= h_dry, a hydrostatic;
 * exact == 1 (gf_surface_restore): h, m and a as given (surface.c) */
gf_status gf_surface_load_state(gf_surface *s, const double *h, const double *mom, const double *a, int exact);
/* A step on this mesh, repeated as two half steps where a stage would make a
 * thickness negative even at first order (surface.c) */
gf_status gf_surface_step_split(gf_surface *s, double dt, int depth);
/* The geometry of faces[0..n) and of their edges, unless written before
 * (surface.c; the active set's, gf_surface_build_active) */
void gf_surface_geometry(gf_surface *s, const int *faces, size_t n);
#pragma GCC visibility pop

#endif
