/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Parallel runs of the surface scheme: the caller's halo exchange and
 * global-minimum callbacks, and the halos of the refined start-up levels. */
#include "surface_internal.h"

#include <stdlib.h>
#include <string.h>
#include "surface_halo.h"

void gf_surface_set_min(gf_surface *s, gf_surface_min_fn fn, void *ctx)
{
    s->minfn = fn;
    s->minctx = ctx;
}

gf_status gf_surface_halo_min(gf_surface *s, double *v, int n)
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

gf_status gf_surface_set_send_faces(gf_surface *s, size_t n, const int *faces)
{
    if (!s || (n > 0 && !faces))
        return gf_fail(GF_EINVAL, "gf_surface_set_send_faces: null argument");
    for (size_t i = 0; i < n; ++i)
        if (faces[i] < 0 || (size_t)faces[i] >= s->m.n_faces)
            return gf_fail(GF_EDOM, "gf_surface_set_send_faces: face %d (entry %zu) is not an owned face (0 .. %zu)",
                           faces[i], i, s->m.n_faces - 1);
    int *copy = malloc((n + 1) * sizeof *copy);
    if (!copy)
        return gf_fail(GF_ENOMEM, "gf_surface_set_send_faces: %zu faces", n);
    memcpy(copy, faces, n * sizeof *copy);
    free(s->send_f);
    s->send_f = copy;
    s->n_send = n;
    return GF_SUCCESS;
}

gf_status gf_surface_halo_exchange(gf_surface *s, double *field, int ncomp)
{
    if (s->m.n_ghosts == 0)
        return GF_SUCCESS;
    if (!s->xfn)
        return gf_fail(GF_EINVAL, "surface scheme: %zu ghost faces but no exchange callback", s->m.n_ghosts);
    if (s->xfn(s->xctx, field, ncomp))
        return gf_fail(GF_EIO, "surface scheme: halo exchange failed");
    return GF_SUCCESS;
}

int gf_surface_level_exchange(void *ctx, double *field, int ncomp)
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

