/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Parallel runs of the surface scheme (surface_halo.c).  Private. */
#ifndef GRANFLOW_SURFACE_HALO_H
#define GRANFLOW_SURFACE_HALO_H

#include "surface_internal.h"

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

#pragma GCC visibility push(hidden) /* the library's own: not exported */
/* the ghost entries of field (ncomp per face) from their ranks (serial: nothing) */
gf_status gf_surface_halo_exchange(gf_surface *s, double *field, int ncomp);
/* v[0..n-1] to their minima over all ranks (serial: unchanged) */
gf_status gf_surface_halo_min(gf_surface *s, double *v, int n);
/* the exchange callback of a refined level (ctx: its struct level_halo):
 * the ghost sub-faces' entries by the coarse mesh's edge exchange */
int gf_surface_level_exchange(void *ctx, double *field, int ncomp);
#pragma GCC visibility pop

#endif
