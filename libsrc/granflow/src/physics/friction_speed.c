/* SPDX-License-Identifier: GPL-3.0-or-later */
/* gf_friction_implicit_speed (granflow/friction.h): the argument checks
 * and friction_speed.h's inline entry, out of line for the library's
 * users.  Above friction_speed.h; nothing calls back up into it. */
#include "granflow/friction.h"
#include "internal.h"
#include "friction_speed.h"

gf_status gf_friction_implicit_speed(const gf_friction *f, const gf_friction_state *s, double M,
                                     double dt, double *speed)
{
    if (!f || !f->type || !s || !speed)
        return gf_fail(GF_EINVAL, "gf_friction_implicit_speed: null argument or uninitialised law");
    return gf_friction_implicit_speed_inline(f, s, M, dt, speed);
}
