/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The active set of the surface scheme: wet faces and two rings of
 * neighbours, and their edges; dry terrain costs nothing. */
#include "surface_internal.h"
#include "surface_active.h"
#include "surface_halo.h"

#include <stdlib.h>

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

gf_status gf_surface_build_active(gf_surface *s)
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
         * order as the full scan lists them (the previous set's owned faces
         * are sorted, below; sort_faces then only checks), so a step costs
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
        if (s->send_f) /* only what the exchange sends (gf_surface_set_send_faces) */
            for (size_t i = 0; i < s->n_send; ++i) {
                const int f = s->send_f[i];
                lvl[f] = s->mark_g[f] == st ? 1.0 : 3.0;
            }
        else
            for (size_t f = 0; f < nf; ++f)
                lvl[f] = s->mark_g[f] == st ? 1.0 : 3.0;
        gf_status x = gf_surface_halo_exchange(s, lvl, 1);
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
    /* The owned active faces in increasing order (the wet ones are, the
     * rings are merged in; s->neg is free scratch here): the passes over
     * them, and over their edges (listed in this order below), then walk
     * the arrays forwards instead of returning for the rings.  avaHelix:
     * the time loop 0.96 of its CPU time (farm-bench, paired runs). */
    sort_faces(s->act_f, s->n_act_f, s->neg);
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
        if ((size_t)f >= nf || s->pface[f]) /* the only gradients written (the halo's) */
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
    /* the geometry the passes read: of the active faces and their edges */
    gf_surface_geometry(s, s->act_f, s->n_act_f);
    s->n_act_b = 0;
    for (size_t i = 0; i < s->n_act_e; ++i)
        if (s->m.neighbour[s->act_e[i]] < 0)
            s->act_b[s->n_act_b++] = s->act_e[i];
    s->active_fresh = 1;
    return GF_SUCCESS;
}

