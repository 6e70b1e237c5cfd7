/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The active set of the surface scheme (surface_active.c).  Private. */
#ifndef GRANFLOW_SURFACE_ACTIVE_H
#define GRANFLOW_SURFACE_ACTIVE_H

#include "surface_internal.h"

#pragma GCC visibility push(hidden) /* the library's own: not exported */
/* Active set: faces with h > 0 (owned and ghost) and two rings of
 * neighbours; their edges.  act_f lists owned faces first (n_act_owned).
 * In parallel the first ring is exchanged before the second is grown, so
 * that a face whose first-ring neighbour lies on another rank is active as
 * it is in serial. */
gf_status gf_surface_build_active(gf_surface *s);
#pragma GCC visibility pop

#endif
