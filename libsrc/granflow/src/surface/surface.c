/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Explicit finite-volume scheme on a surface mesh: see granflow/surface.h.
 * The core: configuration and mesh checks, edge frames, alloc/free, the
 * state, the SSP-RK2 step driver; the parts are listed in
 * surface_internal.h. */
#include "surface_internal.h"
#include "surface_active.h"
#include "surface_exchange.h"
#include "surface_flux.h"
#include "surface_halo.h"
#include "surface_recon.h"
#include "surface_source.h"
#include "surface_startup.h"

#include <limits.h>
#include <stdint.h>
#include <stdlib.h>

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

static void free_lines(double *p); /* the blocks of calloc_lines */

void gf_surface_free(gf_surface *s)
{
    if (!s)
        return;
    gf_surface_startup_free(s);
    gf_surface_exchange_free(s);
    free_lines(s->frame);
    free_lines(s->es);
    free_lines(s->eacc);
    void *bufs[] = {s->fe_start, s->fe,     s->h,    s->mom,    s->h1,     s->m1,
                    s->h2,       s->m2,     s->a,      s->u,      s->pb,       s->grad, s->acc_h,  s->acc_m,
                    s->acc_pn,   s->fh,     s->efmn, s->spd, s->ahyd, s->stat, s->slow, s->sedge, s->first, s->edge_vol,
                    s->edge_vol_step, s->inflow, s->mark_f, s->mark_e, s->mark_g, s->act_f, s->act_b, s->neg, s->defer,
                    s->act_e,    s->ring,     s->prev_f, s->a_save, s->inflow_edges, s->lvl,
                    s->fs_other, s->fs_nb, s->fs_geo, s->pface, s->send_f, s->geo_edge, s->geo_face,
                    s->len_own, s->eg.index};
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

static gf_status check_mesh(const gf_surface_mesh *m, const struct gf_edge_geo *g)
{
    const size_t nt = m->n_faces + m->n_ghosts;
    if (!m->area || !m->centre || !m->normal || !m->owner || !m->neighbour || !m->kind ||
        (g->index ? !g->points || !g->ends[0] || !g->ends[1] || !g->sn[0] || !g->sn[1]
                  : !m->length || !m->edge_normal || !m->edge_centre))
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
        double L, xe[3], nu[3];
        edge_geo(m, g, e, &L, xe, nu);
        if (!(L > 0.0) || !isfinite(L))
            return gf_fail(GF_EDOM, "surface mesh: edge %zu has length %g (must be > 0)", e, L);
        for (int j = 0; j < 3; ++j)
            if (!isfinite(nu[j]) || !isfinite(xe[j]))
                return gf_fail(GF_ENONFINITE, "surface mesh: edge %zu has non-finite geometry", e);
    }
    return GF_SUCCESS;
}

/* Edge e's vectors (EG doubles) into ge: L nu_e (the owner's Green–Gauss
 * weight), edge centre minus owner centre, minus neighbour centre (the
 * owner's on a boundary edge) */
static void edge_vectors_of(const gf_surface_mesh *m, size_t e, double L, const double *xe, const double *nue,
                            double *ge)
{
    const double *xo = m->centre + 3 * m->owner[e];
    const double *xn = m->neighbour[e] >= 0 ? m->centre + 3 * m->neighbour[e] : xo;
    for (int k = 0; k < 3; ++k) {
        ge[EG_LW + k] = L * nue[k];
        ge[EG_RO + k] = xe[k] - xo[k];
        ge[EG_RN + k] = xe[k] - xn[k];
    }
}

static void edge_vectors(const gf_surface_mesh *m, const struct gf_edge_geo *g, size_t e, double *ge)
{
    double L, xe[3], nue[3];
    edge_geo(m, g, e, &L, xe, nue);
    edge_vectors_of(m, e, L, xe, nue, ge);
}

/* Edge frame: n_e = (n_o + n_n)/|.|, nu orthogonalised against n_e, t = n_e x nu;
 * nu_L = t x n_o lies in the owner's plane (the rotation of nu about t).
 * Edge e's frame block (EF doubles) into fr and its vectors (EG) into ge. */
static gf_status edge_geometry(const gf_surface_mesh *m, const struct gf_edge_geo *g, size_t e, double *fr,
                               double *ge)
{
    double ne[3];
    const double *no = m->normal + 3 * m->owner[e];
    const double *nn = m->neighbour[e] >= 0 ? m->normal + 3 * m->neighbour[e] : no;
    for (int k = 0; k < 3; ++k)
        ne[k] = no[k] + nn[k];
    double *nu = fr + EF_NU, *t = fr + EF_T, *nul = fr + EF_NUL, *nur = fr + EF_NUR;
    double L, xe[3], nue[3];
    edge_geo(m, g, e, &L, xe, nue);
    memcpy(nu, nue, sizeof nue);
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
    edge_vectors_of(m, e, L, xe, nue, ge);
    fr[EF_L] = L;
    fr[EF_PO] = L * dot3(nu, no);
    fr[EF_PN] = L * dot3(nu, nn);
    return GF_SUCCESS;
}

/* Every edge's frame checked at the set-up (a degenerate mesh is refused
 * there, not in a step), into scratch: the per-edge and per-slot geometry
 * itself is written when a face first joins the active set
 * (gf_surface_geometry), so a run writes, and keeps resident, only the
 * geometry of the terrain its avalanche reaches. */
static gf_status check_frames(const gf_surface *s)
{
    double fr[EF], ge[EG];
    gf_status st;
    for (size_t e = 0; e < s->m.n_edges; ++e)
        if ((st = edge_geometry(&s->m, &s->eg, e, fr, ge)))
            return st;
    return GF_SUCCESS;
}

void gf_surface_geometry(gf_surface *s, const int *faces, size_t n)
{
    for (size_t i = 0; i < n; ++i) {
        const int f = faces[i];
        if (s->geo_face[f])
            continue;
        for (size_t j = s->fe_start[f]; j < s->fe_start[f + 1]; ++j) {
            const int e = s->fe[j];
            const double w = s->fs_nb[j] ? -1.0 : 1.0;
            double ge[EG];
            if (!s->geo_edge[e]) {
                (void)edge_geometry(&s->m, &s->eg, (size_t)e, s->frame + EF * e, ge); /* checked at the set-up */
                if (s->len_own)
                    s->len_own[e] = s->frame[EF * e + EF_L];
                s->geo_edge[e] = 1;
            } else
                edge_vectors(&s->m, &s->eg, (size_t)e, ge);
            double *sg = s->fs_geo + SG * j;
            for (int k = 0; k < 3; ++k) {
                sg[k] = w * ge[EG_LW + k];
                sg[3 + k] = ge[(s->fs_nb[j] ? EG_RN : EG_RO) + k];
            }
        }
        s->geo_face[f] = 1;
    }
}

/* n doubles, zeroed, on 64-byte boundaries: an edge's 8-double block of
 * gf_surface.es is then one cache line, not two.  From calloc, not
 * aligned_alloc and memset: calloc takes large blocks as fresh zero pages
 * from the system, which become resident only where they are first
 * written, so the per-edge scratch blocks (es, eacc) cost memory only along
 * the avalanche's path, and the set-up does not write them all; the block
 * starts after a pointer to calloc's own (free_lines). */
static double *calloc_lines(size_t n)
{
    const size_t bytes = (n * sizeof(double) + 63) / 64 * 64;
    char *raw = calloc(1, bytes + 64 + sizeof(void *));
    if (!raw)
        return NULL;
    char *p = raw + sizeof(void *);
    p += (64 - (uintptr_t)p % 64) % 64;
    memcpy(p - sizeof(void *), &raw, sizeof raw);
    return (double *)(void *)p;
}

static void free_lines(double *p)
{
    if (!p)
        return;
    void *raw;
    memcpy(&raw, (char *)p - sizeof(void *), sizeof raw);
    free(raw);
}

/* edge a before edge b in a face's list: by centre (x, y, z), then number */
static int edge_before(const gf_surface_mesh *m, const struct gf_edge_geo *g, int a, int b)
{
    double la, lb, x[3], y[3];
    edge_geo(m, g, (size_t)a, &la, x, NULL);
    edge_geo(m, g, (size_t)b, &lb, y, NULL);
    for (int k = 0; k < 3; ++k)
        if (x[k] != y[k])
            return x[k] < y[k];
    return a < b;
}

gf_status gf_surface_alloc(const gf_surface_mesh *mesh, const gf_surface_config *cfg, gf_surface **out)
{
    return gf_surface_alloc_edges(mesh, NULL, cfg, out);
}

gf_status gf_surface_alloc_edges(const gf_surface_mesh *mesh, const gf_surface_edge_geometry *eg,
                                 const gf_surface_config *cfg, gf_surface **out)
{
    if (!mesh || !cfg || !out)
        return gf_fail(GF_EINVAL, "gf_surface_alloc: null argument");
    *out = NULL;
    gf_status st;
    struct gf_edge_geo g = {NULL, NULL, {NULL, NULL}, {NULL, NULL}};
    if (eg) {
        if (!eg->index)
            return gf_fail(GF_EINVAL, "gf_surface_alloc_edges: no edge index");
        if (cfg->startup_levels > 0)
            return gf_fail(GF_EINVAL, "surface scheme: startup_levels = %d needs the mesh's own edge arrays (not "
                                      "gf_surface_alloc_edges)", cfg->startup_levels);
        const void *arg[] = {eg->points, eg->ends[0], eg->ends[1], eg->surface_normal[0], eg->surface_normal[1]};
        static const char *const arg_name[] = {"points", "ends[0]", "ends[1]", "surface_normal[0]",
                                               "surface_normal[1]"};
        for (int k = 0; k < 5; ++k)
            if (!arg[k])
                return gf_fail(GF_EINVAL, "gf_surface_alloc_edges: no edge geometry %s (NULL)", arg_name[k]);
        g.index = (int *)(uintptr_t)eg->index; /* the caller's until copied below */
        g.points = eg->points;
        for (int k = 0; k < 2; ++k)
            g.ends[k] = eg->ends[k], g.sn[k] = eg->surface_normal[k];
    }
    if ((st = check_config(cfg)) || (st = check_mesh(mesh, &g)))
        return st;
    if (cfg->startup_levels > 0 && !mesh->edge_points)
        return gf_fail(GF_EINVAL, "surface scheme: startup_levels = %d needs the mesh's edge_points (the end "
                                  "points of each edge)", cfg->startup_levels);
    if (mesh->n_edges > (size_t)INT_MAX / 8) /* the per-slot offsets into gf_surface.es are int */
        return gf_fail(GF_EDOM, "surface mesh: %zu edges, at most %d allowed", mesh->n_edges, INT_MAX / 8);
    gf_surface *s = calloc(1, sizeof *s);
    if (!s)
        return gf_fail(GF_ENOMEM, "surface scheme: out of memory");
    s->scan_all = 1; /* (and after every gf_surface_load_state) */
    s->m = *mesh;
    s->eg = g;
    s->eg.index = NULL;
    s->len = mesh->length;
    s->c = *cfg;
    s->gmag = sqrt(dot3(cfg->g, cfg->g));
    const size_t nt = s->nt = mesh->n_faces + mesh->n_ghosts, ne = mesh->n_edges, nf = mesh->n_faces;
    s->fe_start = calloc(nt + 1, sizeof *s->fe_start);
    s->fe = malloc((2 * ne + 1) * sizeof *s->fe);
    s->frame = calloc_lines(EF * ne + 1);
    s->geo_edge = calloc(ne + 1, 1);
    s->geo_face = calloc(nt + 1, 1);
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
    if (!s->fe_start || !s->fe || !s->frame || !s->geo_edge || !s->geo_face || !s->mom || !s->m1 || !s->m2 || !s->u || !s->h || !s->h1 || !s->h2 ||
        !s->a || !s->pb || !s->grad || !s->es || !s->acc_h || !s->acc_m || !s->acc_pn || !s->fh || !s->eacc || !s->efmn || !s->spd || !s->ahyd || !s->stat || !s->slow || !s->sedge ||
        !s->first || !s->edge_vol || !s->edge_vol_step || !s->inflow || !s->mark_f || !s->mark_g ||
        !s->mark_e || !s->act_f || !s->ring || !s->act_e || !s->act_b || !s->neg || !s->defer || !s->prev_f || !s->a_save || !s->lvl) {
        gf_surface_free(s);
        return gf_fail(GF_ENOMEM, "surface scheme: out of memory for %zu faces", nt);
    }
    s->inflow_edges = malloc((ne + 1) * sizeof *s->inflow_edges);
    if (g.index) { /* the index copied; the lengths written with the frames */
        s->eg.index = malloc((ne + 1) * sizeof *s->eg.index);
        s->len = s->len_own = calloc(ne + 1, sizeof *s->len_own);
        if (s->eg.index)
            memcpy(s->eg.index, g.index, ne * sizeof *s->eg.index);
    }
    if (!s->inflow_edges || (g.index && (!s->eg.index || !s->len_own))) {
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
    /* Each face's edges in the order of their centres (x, then y, then z;
     * equal centres by edge number), not of the edge numbers: the sums over
     * a face's edges (gradients, fluxes, the step bound) are then made in
     * the same order however the faces and edges are numbered, so a mesh
     * renumbered (gf_surface_face_order) or decomposed, whose processor
     * edges have the same centres on both sides, gives the same results bit
     * for bit. */
    for (size_t f = 0; f < nt; ++f)
        for (size_t j = s->fe_start[f] + 1; j < s->fe_start[f + 1]; ++j) {
            const int e = s->fe[j];
            size_t i = j;
            while (i > s->fe_start[f] && edge_before(&s->m, &s->eg, e, s->fe[i - 1])) {
                s->fe[i] = s->fe[i - 1];
                --i;
            }
            s->fe[i] = e;
        }
    const size_t ns = s->fe_start[nt];
    s->fs_other = malloc((ns + 1) * sizeof *s->fs_other);
    s->fs_nb = malloc(ns + 1);
    s->fs_geo = calloc(SG * ns + 1, sizeof *s->fs_geo);
    s->pface = calloc(nf + 1, 1);
    if (!s->fs_other || !s->fs_nb || !s->fs_geo || !s->pface) {
        gf_surface_free(s);
        return gf_fail(GF_ENOMEM, "surface scheme: out of memory");
    }
    for (size_t f = 0; f < nt; ++f)
        for (size_t j = s->fe_start[f]; j < s->fe_start[f + 1]; ++j) {
            const int e = s->fe[j], isown = mesh->owner[e] == (int)f;
            s->fs_other[j] = isown ? mesh->neighbour[e] : mesh->owner[e];
            s->fs_nb[j] = (unsigned char)!isown;
            if (f < nf && s->fs_other[j] >= (int)nf)
                s->pface[f] = 1;
        }
    for (size_t f = 0; f < nt; ++f) {
        const double gn = -dot3(cfg->g, mesh->normal + 3 * f);
        s->a[f] = s->ahyd[f] = gn > 0.0 ? gn : 0.0;
    }
    if ((st = check_frames(s))) {
        gf_surface_free(s);
        return st;
    }
    *out = s;
    return GF_SUCCESS;
}

/* *p = v, written only where it changes (bit for bit: -0.0 replaces 0.0):
 * the state arrays come from calloc, whose zero pages become resident only
 * where they are written, and a terrain is mostly dry */
static inline void store(double *p, double v)
{
    if (memcmp(p, &v, sizeof v))
        *p = v;
}

gf_status gf_surface_load_state(gf_surface *s, const double *h, const double *mom, const double *a, int exact)
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
        /* each entry written only where it changes (store()): the arrays
         * come from calloc, and the dry faces' zero pages stay unwritten,
         * not resident */
        store(s->h + f, h[f]);
        s->h_scale = gmax(s->h_scale, h[f]);
        double m[3];
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
            store(s->a + f, a[f]);
        } else {
            const double mn = dot3(m, n);
            for (int k = 0; k < 3; ++k)
                m[k] = h[f] > s->c.h_dry ? m[k] - mn * n[k] : 0.0;
            store(s->a + f, s->ahyd[f]);
        }
        for (int k = 0; k < 3; ++k)
            store(s->mom + 3 * f + k, m[k]);
    }
    gf_status st;
    double hs = -s->h_scale; /* the positivity tolerance's scale: the same on every rank */
    if ((st = gf_surface_halo_min(s, &hs, 1)))
        return st;
    s->h_scale = -hs;
    if ((st = gf_surface_halo_exchange(s, s->h, 1)) || (st = gf_surface_halo_exchange(s, s->mom, 3)) ||
        (st = gf_surface_halo_exchange(s, s->a, 1)))
        return st;
    /* stage buffers equal to the state everywhere (as for faces that leave
     * the active set): a neighbour outside the set reads true values */
    for (size_t f = 0; f < s->nt; ++f) {
        store(s->h1 + f, s->h[f]);
        store(s->h2 + f, s->h[f]);
        for (int k = 0; k < 3; ++k) {
            store(s->m1 + 3 * f + k, s->mom[3 * f + k]);
            store(s->m2 + 3 * f + k, s->mom[3 * f + k]);
        }
    }
    return GF_SUCCESS;
}

gf_status gf_surface_set_state(gf_surface *s, const double *h, const double *mom)
{
    gf_surface_startup_free(s);
    return gf_surface_load_state(s, h, mom, NULL, 0);
}

gf_status gf_surface_restore(gf_surface *s, const double *h, const double *mom, const double *a)
{
    if (!h || !mom || !a)
        return gf_fail(GF_EINVAL, "gf_surface_restore: h, momentum and normal acceleration are all needed");
    gf_surface_startup_free(s);
    return gf_surface_load_state(s, h, mom, a, 1);
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

/* One forward-Euler stage with implicit friction: (H, M) -> (Ho, Mo). */
static gf_status stage(gf_surface *s, double dt, double *H, double *M, double *Ho, double *Mo, double weight)
{
    const gf_surface_mesh *m = &s->m;
    const gf_surface_config *c = &s->c;
    gf_status st;
    if ((st = gf_surface_halo_exchange(s, H, 1)) || (st = gf_surface_halo_exchange(s, M, 3)) ||
        (st = gf_surface_halo_exchange(s, s->a, 1)))
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
        gf_surface_gradients(s, H);
        if ((st = gf_surface_halo_exchange(s, s->grad, 3 * NV)))
            return st;
    }
    if ((st = gf_surface_edge_fluxes(s, H, dt, order2)))
        return st;
    /* boundary volumes of this stage */
    for (size_t i = 0; i < s->n_act_b; ++i) {
        const int e = s->act_b[i];
        s->edge_vol_step[e] += weight * dt * s->len[e] * s->fh[e];
    }
    return gf_surface_update_faces(s, dt, H, M, Ho, Mo);
}

/* The stage output's ghost entries (the owned active faces' are all written
 * by the stage; the faces outside the active set hold the state,
 * gf_surface_build_active) */
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
    if (!s->active_fresh && ((st = gf_surface_halo_exchange(s, s->h, 1)) || (st = gf_surface_build_active(s))))
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
    /* mass exchange (granflow/mass_exchange.h) once per step, on the step's
     * result: Lie splitting of the pointwise exchange from the SSP-RK2
     * step (gf_surface_set_mass_exchange) */
    if (s->mx && (st = gf_surface_exchange_step(s, dt, &wet_changed)))
        return st;
    /* The active set is a function of which faces are wet (h > 0): while
     * that set stays the same (on every rank), so does the active set, and
     * it is kept (gf_surface_build_active would rebuild it in the same order). */
    if (s->m.n_ghosts > 0 || s->minfn) {
        double v = wet_changed ? -1.0 : 0.0;
        if ((st = gf_surface_halo_min(s, &v, 1)))
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
 * (the wave speeds grew within the step) is repeated as two half steps
 * (surface_internal.h). */
gf_status gf_surface_step_split(gf_surface *s, double dt, int depth)
{
    gf_status st = step_once(s, dt);
    if (st != GF_EPHYS || depth >= 6)
        return st;
    s->st.halved_steps++;
    if ((st = gf_surface_step_split(s, 0.5 * dt, depth + 1)))
        return st;
    return gf_surface_step_split(s, 0.5 * dt, depth + 1);
}

gf_status gf_surface_step(gf_surface *s, double dt)
{
    if (!s || !(dt >= 0.0) || !isfinite(dt))
        return gf_fail(GF_EDOM, "surface scheme: time step %g (must be finite, >= 0)", dt);
    if (dt == 0.0)
        return GF_SUCCESS;
    if (s->mx)
        s->mx->ent_step = s->mx->det_step = s->mx->det_slow_step = s->mx->det_rest_step = 0.0;
    if (s->startup_pending || s->su)
        return gf_surface_startup_step(s, dt);
    return gf_surface_step_split(s, dt, 0);
}

const double *gf_surface_h(const gf_surface *s) { return s->h; }
const double *gf_surface_momentum(const gf_surface *s) { return s->mom; }
const double *gf_surface_pb(const gf_surface *s) { return s->pb; }
const double *gf_surface_edge_volume(const gf_surface *s) { return s->edge_vol; }

void gf_surface_update_peaks_mapped(const gf_surface *s, const int *map, double *h_peak, double *speed_peak)
{
    for (size_t i = 0; i < s->n_act_owned; ++i) {
        const int f = s->act_f[i], p = map ? map[f] : f;
        double u[3];
        velocity(s, s->h, s->mom, f, u);
        h_peak[p] = gmax(h_peak[p], s->h[f]);
        speed_peak[p] = gmax(speed_peak[p], sqrt(dot3(u, u)));
    }
}

void gf_surface_update_arrival_mapped(const gf_surface *s, const int *map, double t, double h_min,
                                      double *arrival)
{
    for (size_t i = 0; i < s->n_act_owned; ++i) {
        const int f = s->act_f[i], p = map ? map[f] : f;
        if (arrival[p] < 0 && s->h[f] >= h_min) arrival[p] = t;
    }
}

void gf_surface_update_peaks(const gf_surface *s, double *h_peak, double *speed_peak)
{
    gf_surface_update_peaks_mapped(s, NULL, h_peak, speed_peak);
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
    if (s->scan_all) { /* a state loaded and no step since: the active set is not built */
        for (size_t f = 0; f < s->m.n_faces; ++f)
            v += s->m.area[f] * s->h[f];
        return v;
    }
    /* after a step every owned face with h > 0 is in the active set's owned
     * part, act_f[0, n_act_owned); the other faces are dry (h = 0), so the
     * dry part of the mesh costs nothing.  They are in increasing order
     * (gf_surface_build_active): the sum is the scan over every face's. */
    for (size_t i = 0; i < s->n_act_owned; ++i) {
        const int f = s->act_f[i];
        v += s->m.area[f] * s->h[f];
    }
    return v;
}

void gf_surface_get_stats(const gf_surface *s, gf_surface_stats *st) { *st = s->st; }
