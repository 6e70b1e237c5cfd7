/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Sources and friction of the surface scheme (surface_source.c).  Private. */
#ifndef GRANFLOW_SURFACE_SOURCE_H
#define GRANFLOW_SURFACE_SOURCE_H

#include "surface_internal.h"

#pragma GCC visibility push(hidden) /* the library's own: not exported */
/* The owned active faces' update of a stage from (H, M) and the summed
 * edge fluxes (gf_surface_edge_fluxes) into (Ho, Mo): h (a round-off
 * negative thickness clipped and counted), p_b/rho from the normal
 * projection (eq. 33) into gf_surface.pb and the normal acceleration
 * gf_surface.a, m + dt (h g - div F) projected onto the tangent plane
 * (eq. 35; no pointwise gravity in the hydrostatic mode), then the implicit
 * friction update (gf_friction_implicit_speed: exact Coulomb stopping). */
gf_status gf_surface_update_faces(gf_surface *s, double dt, const double *H, const double *M, double *Ho,
                                  double *Mo);
#pragma GCC visibility pop

#endif
