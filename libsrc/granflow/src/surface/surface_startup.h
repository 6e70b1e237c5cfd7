/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The start-up on refined meshes (surface_startup.c).  Private. */
#ifndef GRANFLOW_SURFACE_STARTUP_H
#define GRANFLOW_SURFACE_STARTUP_H

#include "surface_internal.h"

#pragma GCC visibility push(hidden) /* the library's own: not exported */
/* A step while the start-up refinement is pending or running */
gf_status gf_surface_startup_step(gf_surface *s, double dt);
/* End the running start-up, if any (its levels freed) */
void gf_surface_startup_free(gf_surface *s);
#pragma GCC visibility pop

#endif
