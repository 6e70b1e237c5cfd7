/* Explicit finite-volume scheme on a surface mesh: see granflow/surface.h. */
#include "granflow/surface.h"
#include "friction_speed.h"
#include "internal.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define NV 4 /* reconstructed variables: h, u_x, u_y, u_z */
/* Per-edge geometry, built once by build_frames, in two blocks so that each
 * pass reads only what it needs (a face's edges are not adjacent in memory;
 * on meshes larger than the cache the passes are bound by these reads):
 *  - gf_surface.frame, EF doubles per edge on two cache lines (edge fluxes,
 *    step bound): the frame's nu_L, nu_R (the first line: all the step
 *    bound reads), nu, t, [12] the length, [13], [14] length * nu . n_owner,
 *    length * nu . n_neighbour (the normal part of the edge pressure in
 *    eq. 33);
 *  - gf_surface.geo, EG doubles per edge (the face-slot tables below are
 *    built from it; edge fluxes of ghosts and inactive faces): [0..2]
 *    length * edge normal (the Green–Gauss weight of the owner), [3..5],
 *    [6..8] edge centre minus owner / neighbour centre. */
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
/* Per face slot (gf_surface.fe[j], the face's edges in mesh order), SG
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

struct gf_surface {
    gf_surface_mesh m;
    gf_surface_config c;
    size_t nt; /* owned + ghost faces */
    gf_surface_exchange_fn xfn;
    void *xctx;
    gf_surface_edge_exchange_fn xefn; /* per-processor-edge blocks (start-up in parallel) */
    void *xectx;
    gf_surface_min_fn minfn; /* global minima (start-up in parallel) */
    void *minctx;
    double gmag;
    /* face -> edges (all nt faces; a ghost has its one processor edge) */
    size_t *fe_start;
    int *fe;
    int *fs_other;          /* per slot: the face across the edge, -1 on a boundary */
    unsigned char *fs_nb;   /* per slot: the face is the edge's neighbour */
    int *fs_es;             /* per slot: the offset of the face's side of the edge in gf_surface.es */
    double *fs_geo;         /* SG per slot */
    /* per-edge geometry: frame nu, t, nu_L (owner plane), nu_R (neighbour
     * plane) (EF per edge), and the kernels' precomputed vectors (EG) */
    double *frame, *geo;
    /* state and stage buffers (nt, 3 nt) */
    double *h, *mom, *h1, *m1, *h2, *m2;
    double *a;    /* normal acceleration p_b/(rho h) per face (nt) */
    double *u;    /* velocity of the stage state per face (3 nt; 0 where h <= h_dry) */
    double *pb;   /* n_faces */
    double *grad; /* 3 NV per face (nt): written for the faces next to a ghost (the halo exchange's);
                   * the others' stay 0 (edge_side reads s->es for them) */
    unsigned char *pface; /* per owned face: it has a processor edge (its gradient goes to a ghost) */
    /* per edge and side (owner 0, neighbour 1): h and u reconstructed at the
     * edge centre by gradients() for owned active faces (8 per edge), so
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
    int scan_all; /* the next build_active scans every face for h > 0 (the state was loaded) */
    double *a_save;
    double *lvl; /* ring level for the parallel active set (nt) */
    int active_fresh; /* the active set matches the state (built since the last change) */
    double h_scale;
    double u_slow; /* speed below which a face next to one at rest is slow: dt |g| */
    int startup_pending; /* the next step begins the start-up on refined meshes (startup_levels) */
    struct gf_startup *su; /* the running start-up, or NULL */
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

void gf_surface_config_default(gf_surface_config *c)
{
    memset(c, 0, sizeof *c);
    c->g[2] = -9.81;
    c->rho = 1000.0;
    c->h_dry = 1e-6;
    c->courant = 0.5;
    c->order = 2;
    c->centrifugal = 1;
    c->lateral_feedback = 1;
    gf_friction_init(&c->friction, "none");
}

static void startup_free(gf_surface *s);

void gf_surface_free(gf_surface *s)
{
    if (!s)
        return;
    startup_free(s);
    void *bufs[] = {s->fe_start, s->fe,     s->frame,  s->geo,      s->h,    s->mom,    s->h1,     s->m1,
                    s->h2,       s->m2,     s->a,      s->u,      s->pb,       s->grad, s->es, s->acc_h,  s->acc_m,
                    s->acc_pn,   s->fh,     s->eacc, s->efmn, s->spd, s->ahyd, s->stat, s->slow, s->sedge, s->first, s->edge_vol,
                    s->edge_vol_step, s->inflow, s->mark_f, s->mark_e, s->mark_g, s->act_f, s->act_b, s->neg, s->defer,
                    s->act_e,    s->ring,     s->prev_f, s->a_save, s->inflow_edges, s->lvl,
                    s->fs_other, s->fs_nb, s->fs_geo, s->fs_es, s->pface};
    for (size_t i = 0; i < sizeof bufs / sizeof bufs[0]; ++i)
        free(bufs[i]);
    free(s);
}

static gf_status check_config(const gf_surface_config *c)
{
    gf_status st;
    for (int k = 0; k < 3; ++k)
        if (!isfinite(c->g[k]))
            return gf_fail(GF_ENONFINITE, "surface scheme: gravity component %d is not finite", k);
    if ((st = gf_check_range("surface scheme: density rho [kg/m^3]", c->rho, 1e-300, 1e300)) ||
        (st = gf_check_range("surface scheme: dry thickness h_dry [m]", c->h_dry, 1e-300, 1e300)) ||
        (st = gf_check_range("surface scheme: Courant number (positivity bound 0.5)", c->courant, 1e-12, 0.5)))
        return st;
    if (c->order != 1 && c->order != 2)
        return gf_fail(GF_EDOM, "surface scheme: order = %d; allowed: 1 or 2", c->order);
    if (c->startup_levels < 0 || c->startup_levels > 3)
        return gf_fail(GF_EDOM, "surface scheme: startup_levels = %d; allowed: 0 (off) to 3 (4^3 faces per "
                                "quadrilateral)", c->startup_levels);
    if (!c->friction.type)
        return gf_fail(GF_EINVAL, "surface scheme: friction law not initialised");
    return gf_friction_check(&c->friction);
}

static gf_status check_mesh(const gf_surface_mesh *m)
{
    const size_t nt = m->n_faces + m->n_ghosts;
    if (!m->area || !m->centre || !m->normal || !m->owner || !m->neighbour || !m->kind || !m->length ||
        !m->edge_normal || !m->edge_centre)
        return gf_fail(GF_EINVAL, "surface mesh: a geometry array is missing");
    if (m->n_faces == 0 || nt > (size_t)0x7fffffff || m->n_edges > (size_t)0x7fffffff)
        return gf_fail(GF_EINVAL, "surface mesh: %zu faces, %zu ghosts: need 1 to 2^31 faces", m->n_faces,
                       m->n_ghosts);
    for (size_t f = 0; f < nt; ++f) {
        const double *n = m->normal + 3 * f;
        if (!(m->area[f] > 0.0) || !isfinite(m->area[f]))
            return gf_fail(GF_EDOM, "surface mesh: face %zu has area %g (must be > 0)", f, m->area[f]);
        if (!(fabs(dot3(n, n) - 1.0) < 1e-8))
            return gf_fail(GF_EDOM, "surface mesh: normal of face %zu is not a unit vector (|n|^2 = %g)", f,
                           dot3(n, n));
        for (int k = 0; k < 3; ++k)
            if (!isfinite(m->centre[3 * f + k]))
                return gf_fail(GF_ENONFINITE, "surface mesh: centre of face %zu is not finite", f);
    }
    for (size_t e = 0; e < m->n_edges; ++e) {
        const int o = m->owner[e], nb = m->neighbour[e], k = m->kind[e];
        if (o < 0 || (size_t)o >= m->n_faces)
            return gf_fail(GF_EDOM, "surface mesh: edge %zu has owner %d outside 0..%zu", e, o, m->n_faces - 1);
        if (k < GF_EDGE_INTERNAL || k > GF_EDGE_INFLOW)
            return gf_fail(GF_EDOM, "surface mesh: edge %zu has kind %d (allowed 0..3)", e, k);
        if (k == GF_EDGE_INTERNAL ? (nb < 0 || (size_t)nb >= nt || nb == o) : nb != -1)
            return gf_fail(GF_EDOM, "surface mesh: edge %zu (kind %d) has neighbour %d", e, k, nb);
        if (!(m->length[e] > 0.0) || !isfinite(m->length[e]))
            return gf_fail(GF_EDOM, "surface mesh: edge %zu has length %g (must be > 0)", e, m->length[e]);
        for (int j = 0; j < 3; ++j)
            if (!isfinite(m->edge_normal[3 * e + j]) || !isfinite(m->edge_centre[3 * e + j]))
                return gf_fail(GF_ENONFINITE, "surface mesh: edge %zu has non-finite geometry", e);
    }
    return GF_SUCCESS;
}

/* Edge frame: n_e = (n_o + n_n)/|.|, nu orthogonalised against n_e, t = n_e x nu;
 * nu_L = t x n_o lies in the owner's plane (the rotation of nu about t). */
static gf_status build_frames(gf_surface *s)
{
    const gf_surface_mesh *m = &s->m;
    for (size_t e = 0; e < m->n_edges; ++e) {
        double *fr = s->frame + EF * e, *ge = s->geo + EG * e, ne[3];
        const double *no = m->normal + 3 * m->owner[e];
        const double *nn = m->neighbour[e] >= 0 ? m->normal + 3 * m->neighbour[e] : no;
        for (int k = 0; k < 3; ++k)
            ne[k] = no[k] + nn[k];
        double *nu = fr + EF_NU, *t = fr + EF_T, *nul = fr + EF_NUL, *nur = fr + EF_NUR;
        memcpy(nu, m->edge_normal + 3 * e, 3 * sizeof *nu);
        if (normalise3(ne))
            return gf_fail(GF_EDOM, "surface mesh: faces across edge %zu have opposite normals", e);
        const double d = dot3(nu, ne);
        for (int k = 0; k < 3; ++k)
            nu[k] -= d * ne[k];
        if (normalise3(nu))
            return gf_fail(GF_EDOM, "surface mesh: edge normal of edge %zu is zero or normal to the surface", e);
        cross3(ne, nu, t);
        cross3(t, no, nul);
        cross3(t, nn, nur);
        if (normalise3(t) || normalise3(nul) || normalise3(nur))
            return gf_fail(GF_EDOM, "surface mesh: degenerate frame at edge %zu", e);
        const double L = m->length[e], *xe = m->edge_centre + 3 * e, *xo = m->centre + 3 * m->owner[e];
        const double *xn = m->neighbour[e] >= 0 ? m->centre + 3 * m->neighbour[e] : xo;
        for (int k = 0; k < 3; ++k) {
            ge[EG_LW + k] = L * m->edge_normal[3 * e + k];
            ge[EG_RO + k] = xe[k] - xo[k];
            ge[EG_RN + k] = xe[k] - xn[k];
        }
        fr[EF_L] = L;
        fr[EF_PO] = L * dot3(nu, no);
        fr[EF_PN] = L * dot3(nu, nn);
    }
    for (size_t j = 0; j < s->fe_start[s->nt]; ++j) {
        const double *ge = s->geo + EG * s->fe[j], w = s->fs_nb[j] ? -1.0 : 1.0;
        double *sg = s->fs_geo + SG * j;
        for (int k = 0; k < 3; ++k) {
            sg[k] = w * ge[EG_LW + k];
            sg[3 + k] = ge[(s->fs_nb[j] ? EG_RN : EG_RO) + k];
        }
    }
    return GF_SUCCESS;
}

/* n doubles, zeroed, on 64-byte boundaries: an edge's 8-double block of
 * gf_surface.es is then one cache line, not two */
static double *calloc_lines(size_t n)
{
    const size_t bytes = (n * sizeof(double) + 63) / 64 * 64;
    double *p = aligned_alloc(64, bytes);
    if (p)
        memset(p, 0, bytes);
    return p;
}

gf_status gf_surface_alloc(const gf_surface_mesh *mesh, const gf_surface_config *cfg, gf_surface **out)
{
    if (!mesh || !cfg || !out)
        return gf_fail(GF_EINVAL, "gf_surface_alloc: null argument");
    *out = NULL;
    gf_status st;
    if ((st = check_config(cfg)) || (st = check_mesh(mesh)))
        return st;
    if (cfg->startup_levels > 0 && !mesh->edge_points)
        return gf_fail(GF_EINVAL, "surface scheme: startup_levels = %d needs the mesh's edge_points (the end "
                                  "points of each edge)", cfg->startup_levels);
    if (mesh->n_edges > (size_t)INT_MAX / 8) /* the per-slot offsets into gf_surface.es are int */
        return gf_fail(GF_EDOM, "surface mesh: %zu edges, at most %d allowed", mesh->n_edges, INT_MAX / 8);
    gf_surface *s = calloc(1, sizeof *s);
    if (!s)
        return gf_fail(GF_ENOMEM, "surface scheme: out of memory");
    s->scan_all = 1; /* (and after every load_state) */
    s->m = *mesh;
    s->c = *cfg;
    s->gmag = sqrt(dot3(cfg->g, cfg->g));
    const size_t nt = s->nt = mesh->n_faces + mesh->n_ghosts, ne = mesh->n_edges, nf = mesh->n_faces;
    s->fe_start = calloc(nt + 1, sizeof *s->fe_start);
    s->fe = malloc((2 * ne + 1) * sizeof *s->fe);
    s->frame = calloc_lines(EF * ne + 1);
    s->geo = malloc((EG * ne + 1) * sizeof *s->geo);
    double **d3[] = {&s->mom, &s->m1, &s->m2, &s->u};
    for (int i = 0; i < 4; ++i)
        *d3[i] = calloc(3 * nt, sizeof(double));
    double **d1[] = {&s->h, &s->h1, &s->h2, &s->a};
    for (int i = 0; i < 4; ++i)
        *d1[i] = calloc(nt, sizeof(double));
    s->pb = calloc(nf, sizeof *s->pb);
    s->grad = calloc(3 * NV * nt, sizeof *s->grad);
    s->es = calloc_lines(8 * ne + 1);
    s->acc_h = calloc(nf, sizeof *s->acc_h);
    s->acc_m = calloc(3 * nf, sizeof *s->acc_m);
    s->acc_pn = calloc(nf, sizeof *s->acc_pn);
    s->fh = calloc(ne + 1, sizeof *s->fh);
    s->eacc = calloc_lines(EA * ne + 1);
    s->efmn = calloc(3 * ne + 1, sizeof *s->efmn);
    s->spd = calloc(2 * ne + 1, sizeof *s->spd);
    s->ahyd = calloc(nt, sizeof *s->ahyd);
    s->stat = calloc(nt, 1);
    s->slow = calloc(nt, 1);
    s->sedge = calloc(ne + 1, 1);
    s->first = calloc(ne + 1, 1);
    s->edge_vol = calloc(ne + 1, sizeof *s->edge_vol);
    s->edge_vol_step = calloc(ne + 1, sizeof *s->edge_vol_step);
    s->inflow = calloc(4 * ne + 1, sizeof *s->inflow);
    s->mark_f = calloc(nt, sizeof *s->mark_f);
    s->mark_g = calloc(nt, sizeof *s->mark_g);
    s->mark_e = calloc(ne + 1, sizeof *s->mark_e);
    s->act_f = malloc(nt * sizeof *s->act_f);
    s->ring = malloc(nt * sizeof *s->ring);
    s->act_e = malloc((ne + 1) * sizeof *s->act_e);
    s->act_b = malloc((ne + 1) * sizeof *s->act_b);
    s->neg = malloc(nt * sizeof *s->neg);
    s->defer = malloc((ne + 1) * sizeof *s->defer);
    s->prev_f = malloc(nt * sizeof *s->prev_f);
    s->a_save = malloc(nt * sizeof *s->a_save);
    s->lvl = malloc(nt * sizeof *s->lvl);
    if (!s->fe_start || !s->fe || !s->frame || !s->geo || !s->mom || !s->m1 || !s->m2 || !s->u || !s->h || !s->h1 || !s->h2 ||
        !s->a || !s->pb || !s->grad || !s->es || !s->acc_h || !s->acc_m || !s->acc_pn || !s->fh || !s->eacc || !s->efmn || !s->spd || !s->ahyd || !s->stat || !s->slow || !s->sedge ||
        !s->first || !s->edge_vol || !s->edge_vol_step || !s->inflow || !s->mark_f || !s->mark_g ||
        !s->mark_e || !s->act_f || !s->ring || !s->act_e || !s->act_b || !s->neg || !s->defer || !s->prev_f || !s->a_save || !s->lvl) {
        gf_surface_free(s);
        return gf_fail(GF_ENOMEM, "surface scheme: out of memory for %zu faces", nt);
    }
    s->inflow_edges = malloc((ne + 1) * sizeof *s->inflow_edges);
    if (!s->inflow_edges) {
        gf_surface_free(s);
        return gf_fail(GF_ENOMEM, "surface scheme: out of memory");
    }
    for (size_t e = 0; e < ne; ++e)
        if (mesh->kind[e] == GF_EDGE_INFLOW)
            s->inflow_edges[s->n_inflow++] = (int)e;
    /* CSR face -> edges */
    for (size_t e = 0; e < ne; ++e) {
        s->fe_start[mesh->owner[e] + 1]++;
        if (mesh->neighbour[e] >= 0)
            s->fe_start[mesh->neighbour[e] + 1]++;
    }
    for (size_t f = 0; f < nt; ++f)
        s->fe_start[f + 1] += s->fe_start[f];
    size_t *fill = calloc(nt, sizeof *fill);
    if (!fill) {
        gf_surface_free(s);
        return gf_fail(GF_ENOMEM, "surface scheme: out of memory");
    }
    for (size_t e = 0; e < ne; ++e) {
        const int o = mesh->owner[e], n = mesh->neighbour[e];
        s->fe[s->fe_start[o] + fill[o]++] = (int)e;
        if (n >= 0)
            s->fe[s->fe_start[n] + fill[n]++] = (int)e;
    }
    free(fill);
    const size_t ns = s->fe_start[nt];
    s->fs_other = malloc((ns + 1) * sizeof *s->fs_other);
    s->fs_nb = malloc(ns + 1);
    s->fs_geo = malloc((SG * ns + 1) * sizeof *s->fs_geo);
    s->pface = calloc(nf + 1, 1);
    s->fs_es = malloc((ns + 1) * sizeof *s->fs_es);
    if (!s->fs_other || !s->fs_nb || !s->fs_geo || !s->pface || !s->fs_es) {
        gf_surface_free(s);
        return gf_fail(GF_ENOMEM, "surface scheme: out of memory");
    }
    for (size_t f = 0; f < nt; ++f)
        for (size_t j = s->fe_start[f]; j < s->fe_start[f + 1]; ++j) {
            const int e = s->fe[j], isown = mesh->owner[e] == (int)f;
            s->fs_other[j] = isown ? mesh->neighbour[e] : mesh->owner[e];
            s->fs_nb[j] = (unsigned char)!isown;
            s->fs_es[j] = 8 * e + (isown ? 0 : 4);
            if (f < nf && s->fs_other[j] >= (int)nf)
                s->pface[f] = 1;
        }
    for (size_t f = 0; f < nt; ++f) {
        const double gn = -dot3(cfg->g, mesh->normal + 3 * f);
        s->a[f] = s->ahyd[f] = gn > 0.0 ? gn : 0.0;
    }
    if ((st = build_frames(s))) {
        gf_surface_free(s);
        return st;
    }
    *out = s;
    return GF_SUCCESS;
}

void gf_surface_set_min(gf_surface *s, gf_surface_min_fn fn, void *ctx)
{
    s->minfn = fn;
    s->minctx = ctx;
}

/* v[0..n-1] to their minima over all ranks (serial: unchanged) */
static gf_status global_min(gf_surface *s, double *v, int n)
{
    if (s->m.n_ghosts == 0 && !s->minfn)
        return GF_SUCCESS;
    if (!s->minfn)
        return gf_fail(GF_EINVAL, "surface scheme: a parallel run (ghost faces) needs gf_surface_set_min");
    if (s->minfn(s->minctx, v, n))
        return gf_fail(GF_EIO, "surface scheme: the global minimum failed");
    return GF_SUCCESS;
}

void gf_surface_set_edge_exchange(gf_surface *s, gf_surface_edge_exchange_fn fn, void *ctx)
{
    s->xefn = fn;
    s->xectx = ctx;
}

void gf_surface_set_exchange(gf_surface *s, gf_surface_exchange_fn fn, void *ctx)
{
    s->xfn = fn;
    s->xctx = ctx;
}

static gf_status exchange(gf_surface *s, double *field, int ncomp)
{
    if (s->m.n_ghosts == 0)
        return GF_SUCCESS;
    if (!s->xfn)
        return gf_fail(GF_EINVAL, "surface scheme: %zu ghost faces but no exchange callback", s->m.n_ghosts);
    if (s->xfn(s->xctx, field, ncomp))
        return gf_fail(GF_EIO, "surface scheme: halo exchange failed");
    return GF_SUCCESS;
}

/* The state of the owned faces.  exact == 0 (an initial condition): m
 * projected onto the tangent planes, 0 where h <= h_dry, a hydrostatic;
 * exact == 1 (gf_surface_restore): h, m and a as given. */
static gf_status load_state(gf_surface *s, const double *h, const double *mom, const double *a, int exact)
{
    const size_t nf = s->m.n_faces;
    s->active_fresh = 0;
    s->scan_all = 1;
    s->h_scale = 0.0;
    s->startup_pending = !exact && s->c.startup_levels > 0;
    for (size_t f = 0; f < nf; ++f) {
        if (!isfinite(h[f]) || h[f] < 0.0)
            return gf_fail(GF_EDOM, "surface scheme: thickness h = %g in face %zu (must be finite, >= 0)", h[f],
                           f);
        s->h[f] = h[f];
        s->h_scale = gmax(s->h_scale, h[f]);
        double *m = s->mom + 3 * f;
        const double *n = s->m.normal + 3 * f;
        for (int k = 0; k < 3; ++k) {
            m[k] = mom ? mom[3 * f + k] : 0.0;
            if (!isfinite(m[k]))
                return gf_fail(GF_ENONFINITE, "surface scheme: momentum of face %zu is not finite", f);
        }
        if (exact) {
            if (!isfinite(a[f]) || a[f] < 0.0)
                return gf_fail(GF_EDOM, "surface scheme: normal acceleration %g in face %zu (must be finite, >= 0)",
                               a[f], f);
            s->a[f] = a[f];
            continue;
        }
        const double mn = dot3(m, n);
        for (int k = 0; k < 3; ++k)
            m[k] = h[f] > s->c.h_dry ? m[k] - mn * n[k] : 0.0;
        const double gn = -dot3(s->c.g, n);
        s->a[f] = gn > 0.0 ? gn : 0.0;
    }
    gf_status st;
    double hs = -s->h_scale; /* the positivity tolerance's scale: the same on every rank */
    if ((st = global_min(s, &hs, 1)))
        return st;
    s->h_scale = -hs;
    if ((st = exchange(s, s->h, 1)) || (st = exchange(s, s->mom, 3)) || (st = exchange(s, s->a, 1)))
        return st;
    /* stage buffers equal to the state everywhere (as for faces that leave
     * the active set): a neighbour outside the set reads true values */
    const size_t nt = s->nt;
    memcpy(s->h1, s->h, nt * sizeof *s->h1);
    memcpy(s->h2, s->h, nt * sizeof *s->h2);
    memcpy(s->m1, s->mom, 3 * nt * sizeof *s->m1);
    memcpy(s->m2, s->mom, 3 * nt * sizeof *s->m2);
    return GF_SUCCESS;
}

gf_status gf_surface_set_state(gf_surface *s, const double *h, const double *mom)
{
    startup_free(s);
    return load_state(s, h, mom, NULL, 0);
}

gf_status gf_surface_restore(gf_surface *s, const double *h, const double *mom, const double *a)
{
    if (!h || !mom || !a)
        return gf_fail(GF_EINVAL, "gf_surface_restore: h, momentum and normal acceleration are all needed");
    startup_free(s);
    return load_state(s, h, mom, a, 1);
}

const double *gf_surface_normal_acceleration(const gf_surface *s) { return s->a; }

gf_status gf_surface_set_inflow(gf_surface *s, size_t edge, double h, const double u[3])
{
    if (edge >= s->m.n_edges || s->m.kind[edge] != GF_EDGE_INFLOW)
        return gf_fail(GF_EINVAL, "surface scheme: edge %zu is not an inflow edge", edge);
    if (!isfinite(h) || h < 0.0 || !isfinite(u[0]) || !isfinite(u[1]) || !isfinite(u[2]))
        return gf_fail(GF_EDOM, "surface scheme: inflow state h = %g at edge %zu (h must be finite, >= 0)", h,
                       edge);
    const double *n = s->m.normal + 3 * s->m.owner[edge], un = dot3(u, n);
    double *b = s->inflow + 4 * edge;
    if ((b[0] > 0.0) != (h > 0.0)) /* the edge starts or stops bringing material */
        s->active_fresh = 0;
    b[0] = h;
    for (int k = 0; k < 3; ++k)
        b[1 + k] = u[k] - un * n[k];
    return GF_SUCCESS;
}

static inline void velocity(const gf_surface *s, const double *H, const double *M, int f, double *u)
{
    const double h = H[f];
    if (h > s->c.h_dry) {
        const double r = 1.0 / h;
        u[0] = M[3 * f] * r, u[1] = M[3 * f + 1] * r, u[2] = M[3 * f + 2] * r;
    } else
        u[0] = u[1] = u[2] = 0.0;
}

/* Mark the unmarked neighbours of ring[a..b) and append them; returns the
 * new end. */
static size_t expand(gf_surface *s, size_t a, size_t b, size_t nr, unsigned st)
{
    for (size_t i = a; i < b; ++i) {
        const int f = s->ring[i];
        for (size_t j = s->fe_start[f]; j < s->fe_start[f + 1]; ++j) {
            const int e = s->fe[j];
            const int o = s->m.owner[e], n = s->m.neighbour[e];
            const int other = o == f ? n : o;
            if (other >= 0 && s->mark_g[other] != st) {
                s->mark_g[other] = st;
                s->ring[nr++] = other;
            }
        }
    }
    return nr;
}

static int cmp_int(const void *a, const void *b)
{
    const int x = *(const int *)a, y = *(const int *)b;
    return (x > y) - (x < y);
}

/* Sort the distinct face numbers v[0..n) increasingly: the unsorted tail
 * after the longest increasing run is sorted and merged with it (tmp: n
 * ints of scratch). */
static void sort_faces(int *v, size_t n, int *tmp)
{
    size_t k = 1;
    while (k < n && v[k - 1] < v[k])
        ++k;
    if (k >= n)
        return;
    qsort(v + k, n - k, sizeof *v, cmp_int);
    size_t a = 0, b = k, o = 0;
    while (a < k && b < n)
        tmp[o++] = v[a] < v[b] ? v[a++] : v[b++];
    while (a < k)
        tmp[o++] = v[a++];
    while (b < n)
        tmp[o++] = v[b++];
    memcpy(v, tmp, n * sizeof *v);
}

/* Active set: faces with h > 0 (owned and ghost) and two rings of
 * neighbours; their edges.  act_f lists owned faces first (n_act_owned).
 * In parallel the first ring is exchanged before the second is grown, so
 * that a face whose first-ring neighbour lies on another rank is active as
 * it is in serial. */
static gf_status build_active(gf_surface *s)
{
    const size_t nt = s->nt, nf = s->m.n_faces;
    const unsigned st = ++s->stamp;
    size_t nr = 0;
    if (s->scan_all) {
        for (size_t f = 0; f < nt; ++f)
            if (s->h[f] > 0.0)
                s->ring[nr++] = (int)f;
        s->scan_all = 0;
    } else {
        /* A step changes only the owned active faces, and every other owned
         * face is dry (h = 0, it would be active otherwise): the owned faces
         * with h > 0 are among the previous set's, listed in increasing
         * order as the full scan lists them (the previously wet ones are
         * a sorted run, the few that became wet follow), so a step costs
         * nothing on the dry part of the mesh.  Ghosts, which another rank
         * updates, are all scanned. */
        for (size_t i = 0; i < s->n_prev_owned; ++i)
            if (s->h[s->prev_f[i]] > 0.0)
                s->ring[nr++] = s->prev_f[i];
        sort_faces(s->ring, nr, s->act_f);
        for (size_t g = nf; g < nt; ++g)
            if (s->h[g] > 0.0)
                s->ring[nr++] = (int)g;
    }
    for (size_t i = 0; i < nr; ++i)
        s->mark_g[s->ring[i]] = st;
    /* an inflow edge that brings material makes its face active */
    for (size_t i = 0; i < s->n_inflow; ++i) {
        const int e = s->inflow_edges[i], f = s->m.owner[e];
        if (s->inflow[4 * e] > 0.0 && s->mark_g[f] != st) {
            s->mark_g[f] = st;
            s->ring[nr++] = f;
        }
    }
    const size_t r0 = nr;
    nr = expand(s, 0, r0, nr, st);
    size_t r1 = nr;
    if (s->m.n_ghosts > 0) {
        double *lvl = s->lvl;
        for (size_t f = 0; f < nf; ++f)
            lvl[f] = s->mark_g[f] == st ? 1.0 : 3.0;
        gf_status x = exchange(s, lvl, 1);
        if (x)
            return x;
        for (size_t g = nf; g < nt; ++g)
            if (lvl[g] <= 1.0 && s->mark_g[g] != st) {
                s->mark_g[g] = st;
                s->ring[nr++] = (int)g;
            }
        r1 = nr;
    }
    nr = expand(s, r0, r1, nr, st);
    /* owned first, then ghosts */
    s->n_act_f = 0;
    for (size_t i = 0; i < nr; ++i)
        if ((size_t)s->ring[i] < nf)
            s->act_f[s->n_act_f++] = s->ring[i];
    s->n_act_owned = s->n_act_f;
    for (size_t i = 0; i < nr; ++i)
        if ((size_t)s->ring[i] >= nf)
            s->act_f[s->n_act_f++] = s->ring[i];
    for (size_t i = 0; i < s->n_act_f; ++i)
        s->mark_f[s->act_f[i]] = st;
    /* faces that left the set (dry, two rings from material): stage buffers
     * equal to the state, no gradient, so that neighbours read true values */
    for (size_t i = 0; i < s->n_prev_f; ++i) {
        const int f = s->prev_f[i];
        if (s->mark_f[f] == st)
            continue;
        s->h1[f] = s->h2[f] = s->h[f];
        memcpy(s->m1 + 3 * f, s->mom + 3 * f, 3 * sizeof *s->m1);
        memcpy(s->m2 + 3 * f, s->mom + 3 * f, 3 * sizeof *s->m2);
        memset(s->grad + 3 * NV * f, 0, 3 * NV * sizeof *s->grad);
        memset(s->u + 3 * f, 0, 3 * sizeof *s->u);
        s->slow[f] = 0;
    }
    memcpy(s->prev_f, s->act_f, s->n_act_f * sizeof *s->prev_f);
    s->n_prev_f = s->n_act_f;
    s->n_prev_owned = s->n_act_owned;
    s->n_act_e = 0;
    for (size_t i = 0; i < s->n_act_owned; ++i) {
        const int f = s->act_f[i];
        for (size_t j = s->fe_start[f]; j < s->fe_start[f + 1]; ++j) {
            const int e = s->fe[j];
            if (s->mark_e[e] != st) {
                s->mark_e[e] = st;
                s->act_e[s->n_act_e++] = e;
            }
        }
    }
    s->n_act_b = 0;
    for (size_t i = 0; i < s->n_act_e; ++i)
        if (s->m.neighbour[s->act_e[i]] < 0)
            s->act_b[s->n_act_b++] = s->act_e[i];
    s->active_fresh = 1;
    return GF_SUCCESS;
}

/* The four reconstructed variables (h, u_x, u_y, u_z) of a face as the four
 * lanes of one vector (GCC vector extensions: each lane does the scalar
 * operations of the per-variable loops it replaces, in the same order, so
 * the results are the same bit for bit; on SSE2 a lane pair per
 * instruction, on AVX one instruction). */
/* the helpers are static and inlined: the ABI of passing 32-byte vectors
 * without AVX, which GCC warns about, does not arise */
#pragma GCC diagnostic ignored "-Wpsabi"
typedef double v4d __attribute__((vector_size(32)));
typedef long long v4i __attribute__((vector_size(32)));
static inline v4d vsplat(double x) { return (v4d){x, x, x, x}; }
static inline v4d vload(const double *p)
{
    v4d v;
    memcpy(&v, p, sizeof v);
    return v;
}
/* lane-wise m ? a : b (every lane of m all ones or all zeros) */
#ifdef __AVX__
/* (vminpd a, b is a < b ? a : b per lane, vmaxpd a > b ? a : b: gmin, gmax) */
static inline v4d vsel(v4i m, v4d a, v4d b) { return __builtin_ia32_blendvpd256(b, a, (v4d)m); }
static inline v4d vmin(v4d a, v4d b) { return __builtin_ia32_minpd256(a, b); }
static inline v4d vmax(v4d a, v4d b) { return __builtin_ia32_maxpd256(a, b); }
static inline int vany(v4i m) { return __builtin_ia32_movmskpd256((v4d)m) != 0; }
#else
static inline v4d vsel(v4i m, v4d a, v4d b) { return (v4d)(((v4i)a & m) | ((v4i)b & ~m)); }
static inline v4d vmin(v4d a, v4d b) { return vsel(a < b, a, b); } /* gmin per lane */
static inline v4d vmax(v4d a, v4d b) { return vsel(a > b, a, b); } /* gmax per lane */
static inline int vany(v4i m) { return (m[0] | m[1] | m[2] | m[3]) != 0; }
#endif

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
        double *q = s->es + s->fs_es[j];
        const v4d qr = vsel(rec, q0 + (Gx * vsplat(r[0]) + Gy * vsplat(r[1]) + Gz * vsplat(r[2])), q0);
        q[0] = qr[0] < 0.0 ? 0.0 : qr[0];
        q[1] = qr[1], q[2] = qr[2], q[3] = qr[3];
    }
}

static void gradients(gf_surface *s, const double *H)
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
                memset(s->es + s->fs_es[j], 0, 4 * sizeof *s->es);
            continue;
        }
        if (ne == 4)
            gradient_face(s, H, f, j0, 4);
        else
            gradient_face(s, H, f, j0, ne);
    }
}

/* Side state at edge e of face f: h and velocity (3D) of the stage, linearly
 * reconstructed when rec == 1 (owned active faces and ghosts carry
 * gradients), the face values when rec == 0 or 2 (2: towards a dry face). */
static inline void side_state(const gf_surface *s, const double *H, int f, const double *r, int rec, double *h,
                              double *u)
{
    *h = H[f];
    memcpy(u, s->u + 3 * f, 3 * sizeof *u);
    /* rec == 2, edge towards a dry face: the face value, so that the
     * limiter cannot reconstruct the tip of a front to zero */
    if (rec != 1)
        return;
    const double *G = s->grad + 3 * NV * f; /* r: edge centre - face centre */
    *h += dot3(G, r);
    if (*h < 0.0) /* round-off of the limiter */
        *h = 0.0;
    if (H[f] > s->c.h_dry)
        for (int k = 0; k < 3; ++k)
            u[k] += dot3(G + 3 * (k + 1), r);
}

/* side_state at edge e for side 0 (owner) or 1 (neighbour): an owned active
 * face's reconstruction as gradients() stored it, else side_state. */
static inline void edge_side(const gf_surface *s, const double *H, int f, int e, int side, const double *r, int rec,
                             double *h, double *u)
{
    if (rec == 1 && (size_t)f < s->m.n_faces && s->mark_f[f] == s->stamp) {
        const double *q = s->es + 8 * e + 4 * side;
        *h = q[0];
        u[0] = q[1], u[1] = q[2], u[2] = q[3];
        return;
    }
    side_state(s, H, f, r, rec, h, u);
}

/* HLL speed bounds (sl, sr) of the first-order states across an edge, as in
 * hll(). */
static inline void hll_speeds(double hl, double ul, double cl, double hr, double ur, double cr, double *sl,
                              double *sr)
{
    if (hl <= 0.0 && hr <= 0.0) {
        *sl = *sr = 0.0;
    } else if (hl <= 0.0) {
        *sl = ur - 2.0 * cr;
        *sr = ur + cr;
    } else if (hr <= 0.0) {
        *sl = ul - cl;
        *sr = ul + 2.0 * cl;
    } else {
        /* written so that swapping the sides (ul, ur -> -ur, -ul) gives
         * exactly (-sr, -sl): a processor edge's two ranks agree bitwise */
        const double us = 0.5 * (ul + ur) + (cl - cr), cs = gmax(0.0, 0.5 * (cl + cr) + 0.25 * (ul - ur));
        *sl = gmin(gmin(ul - cl, ur - cr), us - cs);
        *sr = gmax(gmax(ul + cl, ur + cr), us + cs);
    }
}

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
 * x_f) (0 where that is <= 0: a shoreline), a = -g.n. */
static inline double hydrostatic_pressure(const gf_surface *s, const double *H, int f, int N)
{
    const double *xf = s->m.centre + 3 * f, *xn = s->m.centre + 3 * N, *g = s->c.g;
    const double P = s->ahyd[f] * H[f] + g[0] * (xn[0] - xf[0]) + g[1] * (xn[1] - xf[1]) + g[2] * (xn[2] - xf[2]);
    const double heq = P > 0.0 && s->ahyd[N] > 0.0 ? P / s->ahyd[N] : 0.0;
    return 0.5 * s->ahyd[f] * H[f] * (H[N] - heq);
}

/* Flux of edge e from the stage state (thickness H, velocities s->u): fh, fm (3D), fp (pressure
 * along nu); per unit length. */
static inline __attribute__((always_inline)) void edge_flux(gf_surface *s, const double *H, int e, int order2)
{
    const gf_surface_mesh *m = &s->m;
    const double *fr = s->frame + EF * e, *nu = fr + EF_NU, *t = fr + EF_T, *nul = fr + EF_NUL, *nur = fr + EF_NUR;
    const double *ge = s->geo + EG * e, L = fr[EF_L]; /* ge: read by side_state only */
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
        edge_side(s, H, o, e, 0, ge + EG_RO, rec ? (dry_n ? 2 : 1) : 0, &hl, ul);
        edge_side(s, H, n, e, 1, ge + EG_RN,
                  rec && ((size_t)n >= m->n_faces || s->mark_f[n] == st) ? (dry_o ? 2 : 1) : 0, &hr, ur);
        hll(hl, dot3(ul, nul), dot3(ul, t), s->a[o], hr, dot3(ur, nur), dot3(ur, t), s->a[n], F, &fpress);
    } else {
        edge_side(s, H, o, e, 0, ge + EG_RO, order2 && !s->first[e], &hl, ul);
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

/* rows r0..r3 (4 doubles each) to columns: c_k = (r0[k], r1[k], r2[k], r3[k]) */
static inline void transpose4(v4d r0, v4d r1, v4d r2, v4d r3, v4d *c)
{
    const v4d t0 = __builtin_shuffle(r0, r1, (v4i){0, 4, 2, 6}), t1 = __builtin_shuffle(r0, r1, (v4i){1, 5, 3, 7});
    const v4d t2 = __builtin_shuffle(r2, r3, (v4i){0, 4, 2, 6}), t3 = __builtin_shuffle(r2, r3, (v4i){1, 5, 3, 7});
    c[0] = __builtin_shuffle(t0, t2, (v4i){0, 1, 4, 5});
    c[1] = __builtin_shuffle(t1, t3, (v4i){0, 1, 4, 5});
    c[2] = __builtin_shuffle(t0, t2, (v4i){2, 3, 6, 7});
    c[3] = __builtin_shuffle(t1, t3, (v4i){2, 3, 6, 7});
}

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

/* hll_speeds on four lanes: the same operations and cases, selected per
 * lane (both sides dry: 0, 0) */
static inline void hll_speeds4(v4d hl, v4d ul, v4d cl, v4d hr, v4d ur, v4d cr, v4d *sl_out, v4d *sr_out)
{
    const v4d zero = vsplat(0.0), two = vsplat(2.0), half = vsplat(0.5);
    const v4i dl = hl <= zero, dr = hr <= zero;
    const v4d us = half * (ul + ur) + (cl - cr), cs = vmax(zero, half * (cl + cr) + vsplat(0.25) * (ul - ur));
    v4d sl = vmin(vmin(ul - cl, ur - cr), us - cs), sr = vmax(vmax(ul + cl, ur + cr), us + cs);
    sl = vsel(dr, ul - cl, sl), sr = vsel(dr, ul + two * cl, sr);
    sl = vsel(dl, ur - two * cr, sl), sr = vsel(dl, ur + cr, sr);
    *sl_out = vsel(dl & dr, zero, sl), *sr_out = vsel(dl & dr, zero, sr);
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
static inline v4d hydrostatic_pressure4(v4d ahf, v4d hf, v4d ahn, v4d hn, v4d dx, v4d dy, v4d dz, const double *g)
{
    const v4d zero = vsplat(0.0);
    const v4d P = ahf * hf + vsplat(g[0]) * dx + vsplat(g[1]) * dy + vsplat(g[2]) * dz;
    const v4i ok = (P > zero) & (ahn > zero);
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
    const v4d qo = vsel(so, hydrostatic_pressure4(aho, Ho, ahn, Hn, dx, dy, dz, s->c.g), po);
    const v4d qn = vsel(sn, hydrostatic_pressure4(ahn, Hn, aho, Ho, mx, my, mz, s->c.g), pn);
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
    const v4d L = {m->length[q[0]], m->length[q[1]], m->length[q[2]], m->length[q[3]]};
    const v4d out = L * vmax(zero, sr), in = L * vmax(zero, -sl);
    for (int k = 0; k < 4; ++k) {
        s->spd[2 * q[k]] = out[k];
        s->spd[2 * q[k] + 1] = in[k];
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

/* One forward-Euler stage with implicit friction: (H, M) -> (Ho, Mo). */
static gf_status stage(gf_surface *s, double dt, double *H, double *M, double *Ho, double *Mo, double weight)
{
    const gf_surface_mesh *m = &s->m;
    const gf_surface_config *c = &s->c;
    gf_status st;
    if ((st = exchange(s, H, 1)) || (st = exchange(s, M, 3)) || (st = exchange(s, s->a, 1)))
        return st;
    s->u_slow = dt * s->gmag;
    const double us2 = s->u_slow * s->u_slow;
    /* velocities, and the hydrostatic mode: every edge of the face static
     * (internal edges with both sides slow, walls, outflow edges; not inflow
     * edges) */
    unsigned char *slow = s->slow;
    const int order2 = c->order == 2;
    for (size_t i = 0; i < s->n_act_f; ++i) {
        const int f = s->act_f[i];
        double *u = s->u + 3 * f;
        velocity(s, H, M, f, u);
        slow[f] = (unsigned char)((dot3(u, u) < us2) | ((size_t)f < m->n_faces && H[f] > c->h_dry) << 1);
        s->stat[f] = 1;
    }
    if (order2) {
        gradients(s, H);
        if ((st = exchange(s, s->grad, 3 * NV)))
            return st;
    }
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
         * gradients() stores */
        const int plain = order2 && !se && kind == GF_EDGE_INTERNAL && (slow[o] & slow[n] & 2);
        s->sedge[e] = (unsigned char)(se | plain << 1);
        if (kind == GF_EDGE_INFLOW || (kind == GF_EDGE_INTERNAL && !se)) {
            s->stat[o] = 0;
            if (n >= 0)
                s->stat[n] = 0;
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
    double *badf = s->lvl; /* per face: marked this pass (scratch, exchanged; build_active's otherwise) */
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
            if ((st = global_min(s, v, 2)))
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
            memset(badf, 0, m->n_faces * sizeof *badf); /* only in a pass that marked faces somewhere */
            for (size_t i = 0; i < nbad; ++i)
                badf[badl[i]] = 1.0;
            if ((st = exchange(s, badf, 1)))
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
    /* boundary volumes of this stage */
    for (size_t i = 0; i < s->n_act_b; ++i) {
        const int e = s->act_b[i];
        s->edge_vol_step[e] += weight * dt * m->length[e] * s->fh[e];
    }
    const double gm = s->gmag;
    for (size_t i = 0; i < s->n_act_owned; ++i) {
        const int f = s->act_f[i];
        const double rA = 1.0 / m->area[f], h = H[f], *nf = m->normal + 3 * f;
        double hn = h - dt * rA * s->acc_h[f];
        if (hn < 0.0) {
            s->st.roundoff_faces++;
            s->st.roundoff_volume += -hn * m->area[f];
            hn = 0.0;
        }
        Ho[f] = hn;
        /* div F per unit area; p_b/rho from the normal projection, eq. (33) */
        const double *acc = s->acc_m + 3 * f;
        const double ndiv = dot3(acc, nf) * rA, npress = s->acc_pn[f] * rA;
        const int hs = s->stat[f]; /* hydrostatic mode: gravity along the surface is in the edge pressures */
        double pbr = -h * dot3(c->g, nf);
        if (c->centrifugal && !hs)
            pbr += ndiv - npress;
        if (c->lateral_feedback)
            pbr += npress;
        if (pbr < 0.0 || h <= c->h_dry)
            pbr = h > c->h_dry ? 0.0 : gmax(0.0, -h * dot3(c->g, nf));
        if (f < (int)m->n_faces)
            s->pb[f] = c->rho * pbr;
        double ms[3];
        for (int k = 0; k < 3; ++k)
            ms[k] = M[3 * f + k] + dt * ((hs ? 0.0 : h * c->g[k]) - acc[k] * rA);
        const double mn = dot3(ms, nf);
        for (int k = 0; k < 3; ++k)
            ms[k] -= mn * nf[k]; /* tangential part, eq. (35) */
        double *mo = Mo + 3 * f;
        const double gn = -dot3(c->g, nf);
        if (hn > c->h_dry) {
            const double Mag = sqrt(dot3(ms, ms));
            double speed = 0.0;
            if (Mag > 0.0) {
                const gf_friction_state fs = {hn, 0.0, c->rho * pbr, c->rho, gm};
                if ((st = gf_friction_implicit_speed_inline(&c->friction, &fs, Mag, dt, &speed)))
                    return st;
            }
            const double r = Mag > 0.0 ? hn * speed / Mag : 0.0;
            if (Mag > 0.0 && speed == 0.0)
                s->st.stopped_faces++;
            for (int k = 0; k < 3; ++k)
                mo[k] = ms[k] * r;
            s->a[f] = h > c->h_dry ? pbr / h : gmax(0.0, gn);
        } else {
            mo[0] = mo[1] = mo[2] = 0.0;
            s->a[f] = gmax(0.0, gn);
        }
    }
    return GF_SUCCESS;
}

/* The stage output's ghost entries (the owned active faces' are all written
 * by the stage; the faces outside the active set hold the state,
 * build_active) */
static void copy_ghosts(gf_surface *s, const double *h, const double *m, double *ho, double *mo)
{
    for (size_t i = s->n_act_owned; i < s->n_act_f; ++i) {
        const int f = s->act_f[i];
        ho[f] = h[f];
        mo[3 * f] = m[3 * f], mo[3 * f + 1] = m[3 * f + 1], mo[3 * f + 2] = m[3 * f + 2];
    }
}

/* One SSP-RK2 step; the state (h, mom) changes only on success. */
static gf_status step_once(gf_surface *s, double dt)
{
    gf_status st;
    /* the set of gf_surface_max_dt, unless the state changed since */
    if (!s->active_fresh && ((st = exchange(s, s->h, 1)) || (st = build_active(s))))
        return st;
    for (size_t i = 0; i < s->n_act_b; ++i)
        s->edge_vol_step[s->act_b[i]] = 0.0;
    for (size_t i = 0; i < s->n_act_f; ++i)
        s->a_save[s->act_f[i]] = s->a[s->act_f[i]];
    copy_ghosts(s, s->h, s->mom, s->h1, s->m1);
    if (!(st = stage(s, dt, s->h, s->mom, s->h1, s->m1, 0.5))) {
        copy_ghosts(s, s->h1, s->m1, s->h2, s->m2);
        st = stage(s, dt, s->h1, s->m1, s->h2, s->m2, 0.5);
    }
    if (st) {
        for (size_t i = 0; i < s->n_act_f; ++i)
            s->a[s->act_f[i]] = s->a_save[s->act_f[i]];
        return st;
    }
    int wet_changed = 0; /* a face became wet or dry */
    for (size_t i = 0; i < s->n_act_owned; ++i) {
        const int f = s->act_f[i];
        const double h0 = s->h[f], h1 = 0.5 * (h0 + s->h2[f]);
        wet_changed |= (h0 > 0.0) != (h1 > 0.0);
        s->h[f] = h1;
        for (int k = 0; k < 3; ++k)
            s->mom[3 * f + k] = 0.5 * (s->mom[3 * f + k] + s->m2[3 * f + k]);
    }
    for (size_t i = 0; i < s->n_act_b; ++i) { /* (an internal edge's volume stays 0) */
        const int e = s->act_b[i];
        s->edge_vol[e] += s->edge_vol_step[e];
    }
    /* The active set is a function of which faces are wet (h > 0): while
     * that set stays the same (on every rank), so does the active set, and
     * it is kept (build_active would rebuild it in the same order). */
    if (s->m.n_ghosts > 0 || s->minfn) {
        double v = wet_changed ? -1.0 : 0.0;
        if ((st = global_min(s, &v, 1)))
            return st;
        wet_changed = v < 0.0;
    }
    s->active_fresh = !wet_changed;
    s->st.steps++;
    s->st.face_updates += s->n_act_owned;
    s->st.active_faces = s->n_act_owned;
    return GF_SUCCESS;
}

/* A step whose stage would make a thickness negative even at first order
 * (the wave speeds grew within the step) is repeated as two half steps. */
static gf_status step_split(gf_surface *s, double dt, int depth)
{
    gf_status st = step_once(s, dt);
    if (st != GF_EPHYS || depth >= 6)
        return st;
    s->st.halved_steps++;
    if ((st = step_split(s, 0.5 * dt, depth + 1)))
        return st;
    return step_split(s, 0.5 * dt, depth + 1);
}

/* The halo of refined level l in a parallel run: its ghost sub-faces are
 * the neighbouring rank's sub-faces along the processor edges, 2^l per
 * coarse ghost in the order of gf_surface_mesh_refine, moved as one block
 * per processor edge by the coarse mesh's edge exchange. */
struct level_halo {
    gf_surface *coarse;
    const gf_surface_mesh *mesh;
    int l;
    double *send, *recv; /* 12 doubles per ghost sub-face (the gradients' 3 NV) */
};

static int level_exchange(void *ctx, double *field, int ncomp)
{
    struct level_halo *x = ctx;
    const gf_surface_mesh *m = x->mesh;
    const size_t n = m->n_faces;
    if (m->n_ghosts == 0)
        return 0;
    if (ncomp > 3 * NV || !x->coarse->xefn)
        return 1;
    for (size_t e = 0; e < m->n_edges; ++e) {
        const int nb = m->neighbour[e];
        if (nb >= 0 && (size_t)nb >= n)
            memcpy(x->send + ((size_t)nb - n) * (size_t)ncomp, field + (size_t)m->owner[e] * (size_t)ncomp,
                   (size_t)ncomp * sizeof *field);
    }
    if (x->coarse->xefn(x->coarse->xectx, x->send, x->recv, ncomp << x->l))
        return 1;
    memcpy(field + n * (size_t)ncomp, x->recv, m->n_ghosts * (size_t)ncomp * sizeof *field);
    return 0;
}

/* The start-up on refined meshes (gf_surface_config.startup_levels; see
 * granflow/surface.h).  Level l is the mesh refined l times; its faces map
 * to level l-1 through parent_face and to this mesh through froot, its edges
 * to this mesh's edges through eroot (-1 inside a face).  Level cl runs
 * until the fastest wave has travelled D / 2^(cl-1) and is then restricted to
 * level cl-1; level 1 ends at D on this mesh.  Between the caller's steps this mesh
 * holds the restriction of the running level (writes, peaks, volumes). */
struct gf_startup {
    int L, cl;
    double D;      /* the travel that ends level 1: 40 d */
    double travel; /* integral of the largest wave speed over the start-up's time */
    double tau;    /* time since the start-up began */
    gf_surface_refined *lev[4];
    gf_surface *sol[4];
    struct level_halo halo[4];
    int *froot[4], *eroot[4];
    double *base_vol;       /* this mesh's edge volumes when the start-up began */
    double *hc, *mc;        /* restriction scratch (finest size) */
    unsigned long steps, updates; /* of the finished levels */
    unsigned long counted;  /* face updates already added to this mesh's stats */
};

static void startup_free(gf_surface *s)
{
    struct gf_startup *u = s->su;
    if (!u)
        return;
    for (int l = 1; l <= 3; ++l) {
        gf_surface_free(u->sol[l]);
        gf_surface_refined_free(u->lev[l]);
        free(u->halo[l].send);
        free(u->halo[l].recv);
        free(u->froot[l]);
        free(u->eroot[l]);
    }
    free(u->base_vol), free(u->hc), free(u->mc);
    free(u);
    s->su = NULL;
}

/* The largest wave speed |u| + sqrt(a h) of the owned active faces, over
 * all ranks */
static gf_status max_wave_speed(gf_surface *s, gf_surface *g, double *w)
{
    double v = 0.0; /* -w */
    for (size_t i = 0; i < g->n_act_owned; ++i) {
        const int f = g->act_f[i];
        if (g->h[f] > g->c.h_dry) {
            double u[3];
            velocity(g, g->h, g->mom, f, u);
            v = gmin(v, -(sqrt(dot3(u, u)) + sqrt(g->a[f] * g->h[f])));
        }
    }
    const gf_status st = global_min(s, &v, 1);
    *w = -v;
    return st;
}

/* D = 40 d over all ranks, d the smallest sqrt(area) of a wet face (0 when
 * nothing is wet) */
static gf_status startup_length(gf_surface *s, double *D)
{
    double d = HUGE_VAL;
    for (size_t f = 0; f < s->m.n_faces; ++f)
        if (s->h[f] > s->c.h_dry)
            d = gmin(d, sqrt(s->m.area[f]));
    const gf_status st = global_min(s, &d, 1);
    *D = d < HUGE_VAL ? 40.0 * d : 0.0;
    return st;
}

/* Refine, set the finest state piecewise constant from this mesh's. */
static gf_status startup_begin(gf_surface *s, double D)
{
    struct gf_startup *u = calloc(1, sizeof *u);
    if (!u)
        return gf_fail(GF_ENOMEM, "surface scheme: out of memory for the start-up refinement");
    s->su = u;
    u->L = u->cl = s->c.startup_levels;
    u->D = D;
    gf_surface_config c = s->c;
    c.startup_levels = 0;
    gf_status st = GF_SUCCESS;
    for (int l = 1; l <= u->L && !st; ++l) {
        const gf_surface_mesh *parent = l == 1 ? &s->m : &u->lev[l - 1]->mesh;
        if ((st = gf_surface_mesh_refine(parent, &u->lev[l])))
            break;
        const gf_surface_mesh *mm = &u->lev[l]->mesh;
        u->froot[l] = malloc(mm->n_faces * sizeof(int));
        u->eroot[l] = malloc(mm->n_edges * sizeof(int));
        if (!u->froot[l] || !u->eroot[l]) {
            st = gf_fail(GF_ENOMEM, "surface scheme: out of memory for the start-up refinement");
            break;
        }
        for (size_t f = 0; f < mm->n_faces; ++f) {
            const int p = u->lev[l]->parent_face[f];
            u->froot[l][f] = l == 1 ? p : u->froot[l - 1][p];
        }
        for (size_t e = 0; e < mm->n_edges; ++e) {
            const int p = u->lev[l]->parent_edge[e];
            u->eroot[l][e] = p < 0 ? -1 : l == 1 ? p : u->eroot[l - 1][p];
        }
        if (mm->n_ghosts > 0) { /* the neighbours' sub-face geometry into the ghosts */
            struct level_halo *x = &u->halo[l];
            x->coarse = s, x->mesh = mm, x->l = l;
            x->send = malloc(3 * NV * mm->n_ghosts * sizeof *x->send);
            x->recv = malloc(3 * NV * mm->n_ghosts * sizeof *x->recv);
            if (!x->send || !x->recv) {
                st = gf_fail(GF_ENOMEM, "surface scheme: out of memory for the start-up refinement");
                break;
            }
            if (!s->xefn) {
                st = gf_fail(GF_EINVAL, "surface scheme: startup_levels = %d in a parallel run needs "
                                        "gf_surface_set_edge_exchange", u->L);
                break;
            }
            if (level_exchange(x, u->lev[l]->area_, 1) || level_exchange(x, u->lev[l]->centre_, 3) ||
                level_exchange(x, u->lev[l]->normal_, 3)) {
                st = gf_fail(GF_EINVAL, "surface scheme: the halo exchange of the refined mesh failed");
                break;
            }
        }
        if ((st = gf_surface_alloc(mm, &c, &u->sol[l])))
            break;
        if (mm->n_ghosts > 0)
            gf_surface_set_exchange(u->sol[l], level_exchange, &u->halo[l]);
        gf_surface_set_min(u->sol[l], s->minfn, s->minctx); /* the levels' positivity decisions */
    }
    if (st)
        return st;
    const size_t nfine = u->lev[u->L]->mesh.n_faces, ne = s->m.n_edges;
    u->hc = malloc(nfine * sizeof *u->hc);
    u->mc = malloc(3 * nfine * sizeof *u->mc);
    u->base_vol = malloc((ne + 1) * sizeof *u->base_vol);
    if (!u->hc || !u->mc || !u->base_vol)
        return gf_fail(GF_ENOMEM, "surface scheme: out of memory for the start-up refinement");
    memcpy(u->base_vol, s->edge_vol, ne * sizeof *u->base_vol);
    const int *root = u->froot[u->L];
    for (size_t f = 0; f < nfine; ++f) {
        u->hc[f] = s->h[root[f]];
        memcpy(u->mc + 3 * f, s->mom + 3 * root[f], 3 * sizeof *u->mc);
    }
    return gf_surface_set_state(u->sol[u->L], u->hc, u->mc);
}

/* Area-weighted means of level l's state on the faces of a coarser mesh
 * (map: level-l face -> face of that mesh) into u->hc, u->mc. */
static void startup_restrict(struct gf_startup *u, int l, const gf_surface_mesh *to, const int *map)
{
    const gf_surface_mesh *mm = &u->lev[l]->mesh;
    const double *hl = gf_surface_h(u->sol[l]), *ml = gf_surface_momentum(u->sol[l]);
    memset(u->hc, 0, to->n_faces * sizeof *u->hc);
    memset(u->mc, 0, 3 * to->n_faces * sizeof *u->mc);
    for (size_t f = 0; f < mm->n_faces; ++f) {
        const int p = map[f];
        const double A = mm->area[f];
        u->hc[p] += A * hl[f];
        for (int k = 0; k < 3; ++k)
            u->mc[3 * p + k] += A * ml[3 * f + k];
    }
    for (size_t f = 0; f < to->n_faces; ++f) {
        const double r = 1.0 / to->area[f];
        u->hc[f] *= r;
        u->mc[3 * f] *= r, u->mc[3 * f + 1] *= r, u->mc[3 * f + 2] *= r;
    }
}

/* Level l's statistics into the finished totals */
static void startup_fold(gf_surface *s, int l)
{
    struct gf_startup *u = s->su;
    gf_surface_stats ls;
    gf_surface_get_stats(u->sol[l], &ls);
    u->steps += ls.steps, u->updates += ls.face_updates;
    s->st.first_order_edges += ls.first_order_edges;
    s->st.stopped_faces += ls.stopped_faces;
    s->st.halved_steps += ls.halved_steps;
    s->st.roundoff_faces += ls.roundoff_faces;
    s->st.roundoff_volume += ls.roundoff_volume;
}

/* Advance the start-up by up to dt (it may end inside the step: *used is
 * the time it took), then put its state on this mesh. */
static gf_status startup_advance(gf_surface *s, double dt, double *used)
{
    struct gf_startup *u = s->su;
    gf_status st = GF_SUCCESS;
    const double t0 = u->tau, target = u->tau + dt, eps = 1e-12 * dt;
    /* inflow edges of the running and coarser levels: this step's state */
    for (int l = 1; l <= u->cl; ++l) {
        const gf_surface_mesh *mm = &u->lev[l]->mesh;
        for (size_t e = 0; e < mm->n_edges && !st; ++e)
            if (mm->kind[e] == GF_EDGE_INFLOW) {
                const double *b = s->inflow + 4 * u->eroot[l][e];
                st = gf_surface_set_inflow(u->sol[l], e, b[0], b + 1);
            }
    }
    if (st)
        return st;
    int finished = 0;
    while (u->tau < target - eps) {
        const int l = u->cl;
        const double Dl = u->D / (double)(1 << (l - 1));
        double w, dtl; /* max_dt first: it builds the active set max_wave_speed reads */
        if ((st = gf_surface_max_dt(u->sol[l], &dtl)) || (st = global_min(s, &dtl, 1)) ||
            (st = max_wave_speed(s, u->sol[l], &w)))
            return st;
        if (!(w > 0.0) || u->travel >= Dl) { /* this level is done (or nothing moves) */
            startup_fold(s, l);
            if (l == 1 || !(w > 0.0)) {
                finished = 1;
                break;
            }
            startup_restrict(u, l, &u->lev[l - 1]->mesh, u->lev[l]->parent_face);
            if ((st = gf_surface_set_state(u->sol[l - 1], u->hc, u->mc)))
                return st;
            u->cl = l - 1;
            continue;
        }
        /* land on the level's travel, and on the caller's step */
        dtl = gmin(dtl, (Dl - u->travel) / w * (1.0 + 1e-12));
        if (!(u->tau + dtl < target - eps))
            dtl = target - u->tau;
        if ((st = gf_surface_step(u->sol[l], dtl)))
            return st;
        u->tau = u->tau + dtl >= target - eps ? target : u->tau + dtl;
        u->travel += w * dtl;
    }
    *used = u->tau - t0;
    /* this mesh: the running (or last) level's state, boundary volumes of all */
    const int l = u->cl;
    startup_restrict(u, l, &s->m, u->froot[l]);
    memcpy(s->edge_vol, u->base_vol, s->m.n_edges * sizeof *s->edge_vol);
    for (int k = l; k <= u->L; ++k) {
        const gf_surface_mesh *mm = &u->lev[k]->mesh;
        const double *ev = gf_surface_edge_volume(u->sol[k]);
        for (size_t e = 0; e < mm->n_edges; ++e)
            if (mm->neighbour[e] < 0)
                s->edge_vol[u->eroot[k][e]] += ev[e];
    }
    gf_surface_stats ls;
    gf_surface_get_stats(u->sol[l], &ls);
    const unsigned long updates = u->updates + (finished ? 0 : ls.face_updates);
    s->st.startup_steps = u->steps + (finished ? 0 : ls.steps);
    s->st.startup_time = u->tau;
    s->st.face_updates += updates - u->counted;
    u->counted = updates;
    if (*used > 0.0)
        s->st.steps++;
    if ((st = load_state(s, u->hc, u->mc, NULL, 0)))
        return st;
    s->startup_pending = 0;
    if (finished)
        startup_free(s);
    /* the active set of the new state (peak fields, moments) */
    if ((st = build_active(s)))
        return st;
    s->st.active_faces = s->n_act_owned;
    return GF_SUCCESS;
}

/* A step while the start-up refinement is pending or running */
static gf_status startup_step(gf_surface *s, double dt)
{
    gf_status st;
    if (!s->su) {
        double D;
        if ((st = startup_length(s, &D)))
            return st;
        s->startup_pending = 0;
        if (!(D > 0.0))
            return step_split(s, dt, 0);
        if ((st = startup_begin(s, D))) {
            startup_free(s);
            return st;
        }
    }
    double used = 0.0;
    if ((st = startup_advance(s, dt, &used)))
        return st;
    /* the start-up ended inside the step: the rest on this mesh */
    return used < dt * (1.0 - 1e-12) ? step_split(s, dt - used, 0) : GF_SUCCESS;
}

gf_status gf_surface_step(gf_surface *s, double dt)
{
    if (!s || !(dt >= 0.0) || !isfinite(dt))
        return gf_fail(GF_EDOM, "surface scheme: time step %g (must be finite, >= 0)", dt);
    if (dt == 0.0)
        return GF_SUCCESS;
    if (s->startup_pending || s->su)
        return startup_step(s, dt);
    return step_split(s, dt, 0);
}

gf_status gf_surface_max_dt(gf_surface *s, double *dt)
{
    gf_status st;
    if ((st = exchange(s, s->h, 1)) || (st = exchange(s, s->mom, 3)) || (st = exchange(s, s->a, 1)) ||
        (!s->active_fresh && (st = build_active(s))))
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
        s->spd[2 * e] = m->length[e] * gmax(0.0, sr);
        s->spd[2 * e + 1] = m->length[e] * gmax(0.0, -sl);
    }
#ifdef __AVX__
    if (nq > 0) { /* the last internal edges, padded with the first (its rates written twice, alike) */
        for (int k = nq; k < 4; ++k)
            quad[k] = quad[0];
        edge_speeds4(s, quad);
    }
#endif
    /* per face, over its edges in mesh order (as accumulate) */
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

const double *gf_surface_h(const gf_surface *s) { return s->h; }
const double *gf_surface_momentum(const gf_surface *s) { return s->mom; }
const double *gf_surface_pb(const gf_surface *s) { return s->pb; }
const double *gf_surface_edge_volume(const gf_surface *s) { return s->edge_vol; }

void gf_surface_update_peaks(const gf_surface *s, double *h_peak, double *speed_peak)
{
    for (size_t i = 0; i < s->n_act_owned; ++i) {
        const int f = s->act_f[i];
        double u[3];
        velocity(s, s->h, s->mom, f, u);
        h_peak[f] = gmax(h_peak[f], s->h[f]);
        speed_peak[f] = gmax(speed_peak[f], sqrt(dot3(u, u)));
    }
}

void gf_surface_moments(const gf_surface *s, double out[4])
{
    out[0] = out[1] = out[2] = out[3] = 0.0;
    for (size_t i = 0; i < s->n_act_owned; ++i) {
        const int f = s->act_f[i];
        const double v = s->m.area[f] * s->h[f], *x = s->m.centre + 3 * f;
        out[0] += v, out[1] += v * x[0], out[2] += v * x[1], out[3] += v * x[2];
    }
}

double gf_surface_volume(const gf_surface *s)
{
    double v = 0.0;
    for (size_t f = 0; f < s->m.n_faces; ++f)
        v += s->m.area[f] * s->h[f];
    return v;
}

void gf_surface_get_stats(const gf_surface *s, gf_surface_stats *st) { *st = s->st; }
