/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Mass exchange of the surface scheme (surface_exchange.c).  Private. */
#ifndef GRANFLOW_SURFACE_EXCHANGE_H
#define GRANFLOW_SURFACE_EXCHANGE_H

#include "surface_internal.h"

#pragma GCC visibility push(hidden) /* the library's own: not exported */
/* The mass exchange of one step of length dt on the owned active faces'
 * state (s->h, s->mom after the SSP-RK2 combination; every other owned
 * face is dry): gf_mass_exchange_face_update per face, τ_b from the
 * friction law at the face's state and the last stage's p_b, the momentum
 * scaled (its direction kept), the entrained and detrained thickness added
 * to the per-face fields and their volumes to the totals.  *dried is set to
 * 1 when detrainment took a face's whole thickness (the active set
 * changes).  Errors name the face. */
gf_status gf_surface_exchange_step(gf_surface *s, double dt, int *dried);
void gf_surface_exchange_free(gf_surface *s);
#pragma GCC visibility pop

#endif
