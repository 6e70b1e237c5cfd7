/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * granflow — earth-pressure coefficient K of the Savage–Hutter model.
 *
 * K = p_xx / p_zz relates the down-slope normal stress to the bed-normal one.
 * Savage–Hutter (Mohr–Coulomb, rkdg paper section 2, the equation under (1)):
 *
 *   K_act/pass = 2 sec^2(phi) (1 -/+ sqrt(1 - cos^2(phi) sec^2(delta))) - 1,
 *
 * active (-) where the flow extends (du/dx >= 0), passive (+) where it
 * contracts (du/dx < 0).  phi is the internal and delta the bed friction
 * angle.  The square root is real only for delta <= phi: a bed friction angle
 * above the internal one is physically impossible in this model and rejected.
 *
 * The isotropic choice K = 1 is the finite-area paper's (section 2.1, after
 * eq. 10: shearing over the whole thickness gives a nearly isotropic stress).
 * Angles are in radians.
 */
#ifndef GRANFLOW_EARTH_PRESSURE_H
#define GRANFLOW_EARTH_PRESSURE_H

#include "granflow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum gf_earth_pressure_model {
    GF_EARTH_PRESSURE_ISOTROPIC = 0,     /* K = 1 */
    GF_EARTH_PRESSURE_SAVAGE_HUTTER = 1  /* K_act / K_pass from phi, delta */
} gf_earth_pressure_model;

typedef struct gf_earth_pressure {
    gf_earth_pressure_model model;
    double k_act;   /* K where du/dx >= 0 */
    double k_pass;  /* K where du/dx <  0 */
} gf_earth_pressure;

/* K_act and K_pass for internal friction angle phi in (0, pi/2) and bed
 * friction angle delta in [0, phi].  GF_EPHYS when delta > phi (complex K),
 * GF_EDOM / GF_ENONFINITE for angles out of range.  rkdg paper, section 2. */
gf_status gf_earth_pressure_coefficients(double phi, double delta,
                                         double *k_act, double *k_pass);

/* Initialise a model.  For GF_EARTH_PRESSURE_ISOTROPIC phi and delta are not
 * used (K_act = K_pass = 1); for GF_EARTH_PRESSURE_SAVAGE_HUTTER they are
 * checked as in gf_earth_pressure_coefficients(). */
gf_status gf_earth_pressure_init(gf_earth_pressure *ep,
                                 gf_earth_pressure_model model,
                                 double phi, double delta);

/* Model from its name: "isotropic" or "savageHutter".  GF_ENOTFOUND with
 * the valid names in the detail message otherwise. */
gf_status gf_earth_pressure_model_from_name(const char *name,
                                            gf_earth_pressure_model *model);

/* K for the local stretching rate du/dx: K_act if du/dx >= 0, else K_pass
 * (rkdg paper, section 2). */
double gf_earth_pressure_k(const gf_earth_pressure *ep, double dudx);

#ifdef __cplusplus
}
#endif

#endif
