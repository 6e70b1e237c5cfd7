/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The implicit friction update's speed (gf_friction_implicit_speed) as an
 * inline entry for the per-face kernels (the explicit surface scheme calls it
 * per face and stage): the argument test and the exact Coulomb law (u0 = 0)
 * inline, every other law out of line (friction_implicit.h, .c).  Calls only
 * down: friction_implicit.c does not include this header, and the public
 * out-of-line entry is friction_speed.c, above it.  Internal: not installed. */
#ifndef GRANFLOW_FRICTION_SPEED_H
#define GRANFLOW_FRICTION_SPEED_H

#include <math.h>

#include "granflow/friction.h"
#include "friction_implicit.h"

/* the arguments' ranges: one test on the hot path, the named check
 * (gf_friction_implicit_speed_fail) only on failure */
static inline int gf_friction_implicit_args_ok(const gf_friction_state *s, double M, double dt)
{
    return s->h >= 1e-300 && s->h < HUGE_VAL && M >= 0.0 && M < HUGE_VAL && dt >= 0.0 && dt < HUGE_VAL &&
           s->rho >= 1e-300 && s->rho < HUGE_VAL && s->g >= 0.0 && s->g < HUGE_VAL && isfinite(s->pb);
}

/* f and s not NULL, f initialised */
static inline gf_status gf_friction_implicit_speed_inline(const gf_friction *f, const gf_friction_state *s, double M,
                                                          double dt, double *speed)
{
    if (!gf_friction_implicit_args_ok(s, M, dt))
        return gf_friction_implicit_speed_fail(s, M, dt);
    /* Coulomb, u0 = 0: h s + dt mu p sign(s) = M, s = max(0, M - dt mu p) / h (stops exactly) */
    if (f->type == gf_friction_coulomb && f->p[1] == 0.0) {
        const double mp = gf_friction_coulomb_mp(f, s);
        *speed = M > dt * mp ? (M - dt * mp) / s->h : 0.0;
        return GF_SUCCESS;
    }
    return gf_friction_implicit_speed_laws(f, s, M, dt, speed);
}

#endif
