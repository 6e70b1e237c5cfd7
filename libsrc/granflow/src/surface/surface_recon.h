/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Reconstruction of the surface scheme (surface_recon.c), and the states
 * at an edge that the edge fluxes read: inline, for the flux pass.  Private. */
#ifndef GRANFLOW_SURFACE_RECON_H
#define GRANFLOW_SURFACE_RECON_H

#include "surface_internal.h"

#pragma GCC visibility push(hidden) /* the library's own: not exported */
/* The limited gradients of h and u of the owned active faces, and their
 * reconstructed states at their edges (gf_surface.es); order 2 only */
void gf_surface_gradients(gf_surface *s, const double *H);
#pragma GCC visibility pop

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
 * face's reconstruction as gf_surface_gradients() stored it, else side_state
 * with r = edge centre - face centre from the mesh (a ghost's, or a face
 * outside the active set's) */
static inline void edge_side(const gf_surface *s, const double *H, int f, int e, int side, int rec, double *h,
                             double *u)
{
    if (rec == 1 && (size_t)f < s->m.n_faces && s->mark_f[f] == s->stamp) {
        const double *q = s->es + 8 * e + 4 * side;
        *h = q[0];
        u[0] = q[1], u[1] = q[2], u[2] = q[3];
        return;
    }
    double r[3];
    if (rec == 1) {
        double L, xe[3];
        edge_geo(&s->m, &s->eg, (size_t)e, &L, xe, NULL);
        const double *xf = s->m.centre + 3 * f;
        r[0] = xe[0] - xf[0], r[1] = xe[1] - xf[1], r[2] = xe[2] - xf[2];
    }
    side_state(s, H, f, r, rec, h, u);
}

#endif
