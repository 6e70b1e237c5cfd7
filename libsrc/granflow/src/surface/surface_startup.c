/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The start-up of the surface scheme on refined meshes
 * (gf_surface_config.startup_levels). */
#include "surface_internal.h"
#include "surface_active.h"
#include "surface_halo.h"
#include "surface_startup.h"

#include <stdlib.h>

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

void gf_surface_startup_free(gf_surface *s)
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
    const gf_status st = gf_surface_halo_min(s, &v, 1);
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
    const gf_status st = gf_surface_halo_min(s, &d, 1);
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
            if (gf_surface_level_exchange(x, u->lev[l]->area_, 1) ||
                gf_surface_level_exchange(x, u->lev[l]->centre_, 3) ||
                gf_surface_level_exchange(x, u->lev[l]->normal_, 3)) {
                st = gf_fail(GF_EINVAL, "surface scheme: the halo exchange of the refined mesh failed");
                break;
            }
        }
        if ((st = gf_surface_alloc(mm, &c, &u->sol[l])))
            break;
        if (mm->n_ghosts > 0)
            gf_surface_set_exchange(u->sol[l], gf_surface_level_exchange, &u->halo[l]);
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
        if ((st = gf_surface_max_dt(u->sol[l], &dtl)) || (st = gf_surface_halo_min(s, &dtl, 1)) ||
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
    if ((st = gf_surface_load_state(s, u->hc, u->mc, NULL, 0)))
        return st;
    s->startup_pending = 0;
    if (finished)
        gf_surface_startup_free(s);
    /* the active set of the new state (peak fields, moments) */
    if ((st = gf_surface_build_active(s)))
        return st;
    s->st.active_faces = s->n_act_owned;
    return GF_SUCCESS;
}

gf_status gf_surface_startup_step(gf_surface *s, double dt)
{
    gf_status st;
    if (!s->su) {
        double D;
        if ((st = startup_length(s, &D)))
            return st;
        s->startup_pending = 0;
        if (!(D > 0.0))
            return gf_surface_step_split(s, dt, 0);
        if ((st = startup_begin(s, D))) {
            gf_surface_startup_free(s);
            return st;
        }
    }
    double used = 0.0;
    if ((st = startup_advance(s, dt, &used)))
        return st;
    /* the start-up ended inside the step: the rest on this mesh */
    return used < dt * (1.0 - 1e-12) ? gf_surface_step_split(s, dt - used, 0) : GF_SUCCESS;
}

