/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The implicit friction update's out-of-line parts (friction_implicit.c),
 * and the primitive that they and the inline entry (friction_speed.h) both
 * use.  Depends only on granflow/friction.h; the inline entry sits above
 * it.  Internal: not installed. */
#ifndef GRANFLOW_FRICTION_IMPLICIT_H
#define GRANFLOW_FRICTION_IMPLICIT_H

#include "granflow/friction.h"

/* the named failure for arguments outside their ranges */
gf_status gf_friction_implicit_speed_fail(const gf_friction_state *s, double M, double dt);
/* every law and setting but Coulomb with u0 = 0; arguments already checked */
gf_status gf_friction_implicit_speed_laws(const gf_friction *f, const gf_friction_state *s, double M, double dt,
                                          double *speed);

/* samosAT with u0 = 0, whose speeds gf_friction_implicit_speed_samosat4
 * gives four at a time */
static inline int gf_friction_samosat4(const gf_friction *f)
{
    return f->type == gf_friction_samosat && f->p[6] == 0.0;
}
/* The speeds of four states at once (h[k], pb[k], M[k]; rho, g and dt
 * common; arguments checked, gf_friction_samosat4(f)): each lane the value
 * gf_friction_implicit_speed_laws gives for it, bit for bit */
void gf_friction_implicit_speed_samosat4(const gf_friction *f, const double h[4], const double pb[4], double rho,
                                         const double M[4], double dt, double speed[4]);

/* mu p_b / rho of the Coulomb law (0 without contact) */
static inline double gf_friction_coulomb_mp(const gf_friction *f, const gf_friction_state *s)
{
    return s->pb > 0.0 ? f->p[0] * s->pb / s->rho : 0.0;
}

#endif
