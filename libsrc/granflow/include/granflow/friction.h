/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * granflow — basal friction laws, selected by name from a table of types
 * (the gsl_odeiv2_step_type pattern).
 *
 * Every law gives, for a local state (thickness h, speed |u|, basal pressure
 * p_b), the basal shear per unit density tau = |tau_b|/rho [m^2/s^2] and its
 * implicit coefficient nu [m/s] with
 *
 *     tau_b / rho = nu * u        (finite-area paper eq. 60),
 *
 * so that a solver can treat friction implicitly: the update
 * u_new = u / (1 + dt nu / h) never reverses the velocity.
 *
 *   name      tau_b/rho                                  parameters (default)
 *   coulomb   mu p_b/rho |u|/(|u|+u0)                    mu (0.5), u0 (0)
 *   mu_i      mu(I_b) p_b/rho |u|/(|u|+u0), eqs. 24-26   mu_s (0.38), mu_2 (0.65),
 *             mu = mu_s + (mu_2-mu_s)/(I_0/I_b + 1)       I_0 (0.3), d (0.005 m),
 *             I_b = 5/2 |u| d/(h sqrt(p_b/rho_p))         rho_p (2500 kg/m^3),
 *                                                         u0 (1e-4 m/s)  [Table 1]
 *   voellmy   mu p_b/rho |u|/(|u|+u0) + g|u|^2/xi        mu (0.2), xi (1000 m/s^2),
 *                                                         u0 (1e-4 m/s)
 *   chezy     g |u|^2 / C^2, eq. 71                      C (40 m^0.5/s)
 *   samosAT   (tau0 + mu (1 + Rs0/(Rs0+Rs)) p_b)/rho     mu (0.155), tau0 (0 Pa), Rs0 (0.222),
 *             x |u|/(|u|+u0) + u^2/(ln(h/R)/kappa + B)^2  kappa (0.43), R (0.05 m), B (4.13),
 *             Rs = rho u^2/(p_b + 0.001 Pa); ln(h/R) = 0  u0 (1e-4 m/s)   [AvaFrame com1DFA;
 *             for h < R (Sampl 2007)                     doc/theory/friction.md]
 *   none      0
 *
 * u0 regularises |u|/|u| near rest (paper eq. 24).  With u0 = 0 (exact
 * Coulomb, as in the Savage–Hutter papers) tau at rest is the static bound
 * mu p_b/rho and nu is +INFINITY.  A negative p_b (lift-off) gives no
 * Coulomb-type friction.
 */
#ifndef GRANFLOW_FRICTION_H
#define GRANFLOW_FRICTION_H

#include <stddef.h>

#include "granflow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define GF_FRICTION_MAX_PARAMS 8

/* One coefficient of a friction law: its name, unit, documented default and
 * the closed range of accepted values. */
typedef struct gf_friction_param {
    const char *name;
    const char *unit;
    const char *description;
    double default_value;
    double min;
    double max;
} gf_friction_param;

/* Local state at which friction is evaluated (SI units when dimensional). */
typedef struct gf_friction_state {
    double h;      /* flow thickness, >= 0 */
    double speed;  /* |u|, >= 0 */
    double pb;     /* basal pressure p_b [Pa]; <= 0 means no contact */
    double rho;    /* flow (bulk) density, > 0 */
    double g;      /* gravitational acceleration magnitude, >= 0 */
} gf_friction_state;

typedef struct gf_friction_result {
    double tau;  /* |tau_b| / rho */
    double nu;   /* implicit coefficient: tau_b/rho = nu u */
    double mu;   /* effective friction coefficient tau/(p_b/rho), 0 if p_b <= 0 */
} gf_friction_result;

typedef struct gf_friction_type {
    const char *name;
    const char *description;
    size_t n_params;
    const gf_friction_param *params;
    /* Cross-parameter checks (e.g. mu_2 >= mu_s); NULL when none. */
    gf_status (*check)(const double *p);
    void (*eval)(const double *p, const gf_friction_state *s, gf_friction_result *r);
} gf_friction_type;

extern const gf_friction_type *const gf_friction_coulomb;
extern const gf_friction_type *const gf_friction_mu_i;
extern const gf_friction_type *const gf_friction_voellmy;
extern const gf_friction_type *const gf_friction_chezy;
extern const gf_friction_type *const gf_friction_samosat;
extern const gf_friction_type *const gf_friction_none;

/* A friction law with its coefficients. */
typedef struct gf_friction {
    const gf_friction_type *type;
    double p[GF_FRICTION_MAX_PARAMS];
} gf_friction;

/* NULL-terminated table of all laws. */
const gf_friction_type *const *gf_friction_types(void);

/* "coulomb, mu_i, voellmy, chezy, samosAT, none" — for error messages. */
const char *gf_friction_names(void);

/* Type by name; NULL when unknown. */
const gf_friction_type *gf_friction_lookup(const char *name);

/* Initialise law `name` with its default coefficients.  GF_ENOTFOUND (detail
 * lists the valid names) for an unknown name. */
gf_status gf_friction_init(gf_friction *f, const char *name);

/* Set coefficient `key`.  GF_ENOTFOUND for a key the law does not have
 * (detail lists its keys), GF_EDOM / GF_ENONFINITE for a value outside the
 * documented range (detail names key, value and range). */
gf_status gf_friction_set(gf_friction *f, const char *key, double value);

/* Value of coefficient `key` in *value. */
gf_status gf_friction_get(const gf_friction *f, const char *key, double *value);

/* Check all coefficients, including relations between them. */
gf_status gf_friction_check(const gf_friction *f);

/* Evaluate the law.  GF_ENONFINITE / GF_EDOM for a non-finite or negative
 * thickness, speed, density or gravity. */
gf_status gf_friction_eval(const gf_friction *f, const gf_friction_state *s,
                           gf_friction_result *r);

/* Coulomb static bound: the largest basal shear per unit density tau_s =
 * |tau_b|/rho the law can exert on material at rest, i.e. tau as |u| -> 0+ with
 * the regularisation u0 set to zero (finite-area paper eqs. 24-26 at I_b = 0):
 * mu_s p_b/rho for mu_i, mu p_b/rho for coulomb and voellmy, 0 for chezy and
 * none, 0 where p_b <= 0.  s->speed is not used.  A solver holds material at
 * rest where the tangential driving force per unit area (per unit density)
 * does not exceed tau_s (Coulomb's static condition; kinetic paper Def. 1 in
 * 1D).  Same argument checks as gf_friction_eval. */
gf_status gf_friction_static_bound(const gf_friction *f, const gf_friction_state *s,
                                   double *tau_s);

/* Explicit friction step that never reverses the motion: the velocity
 * component u reduced in magnitude by decel_dt >= 0 (deceleration times time
 * step), stopping at zero: sgn(u) max(0, |u| - decel_dt). */
double gf_friction_decelerate(double u, double decel_dt);

/* Pointwise implicit friction update (the explicit finite-area scheme's
 * friction step, and exact Coulomb stopping).  Given the trial momentum
 * magnitude M = |h u*| >= 0 per unit area after the explicit part of a step
 * of length dt >= 0, find the new speed s >= 0 with
 *
 *     h s + dt tau(s) = M                          (backward Euler in |u|),
 *
 * tau = |tau_b|/rho of the law at the state s->h, s->pb, s->rho, s->g (the
 * direction of motion is kept: friction never reverses it).  When the law at
 * rest can hold the trial momentum, dt tau(0) >= M, the face stops: *speed =
 * 0 exactly (Coulomb's static condition; with u0 = 0 tau(0) is the static
 * bound mu p_b/rho, with u0 > 0 it is 0 and material only creeps to rest).
 * For a tau non-decreasing in s the root is unique (all laws but samosAT,
 * whose Coulomb factor falls with speed: then a root in [0, M/h] is taken,
 * unique where h/dt exceeds the factor's fall); coulomb
 * (any u0), mu_i and voellmy with u0 = 0 are solved in closed form, samosAT
 * with u0 = 0 by Newton kept inside the root's bracket (started from the
 * root with its Coulomb factor frozen at speed M/h), the others by
 * Illinois regula falsi with bisection steps, to 1e-14 relative.  s->speed is not
 * used.  GF_EDOM / GF_ENONFINITE for a negative or non-finite M, dt or state;
 * h must be > 0. */
gf_status gf_friction_implicit_speed(const gf_friction *f, const gf_friction_state *s, double M,
                                     double dt, double *speed);

/* ---- samosATAuto: AvaFrame com1DFA's samosAT set by release volume ------------
 *
 * com1DFA's frictModel samosATAuto (com1DFACfg.ini volClassSmall 25000,
 * volClassMedium 60000; checkCfg.checkCfgFrictionModel) takes, for the
 * release volume V,
 *
 *     V <  25,000 m^3            samosATSmall    mu 0.22
 *     25,000 <= V < 60,000 m^3   samosATMedium   mu 0.17
 *     V >= 60,000 m^3            samosAT         mu 0.155 (the standard set)
 *
 * with tau0 0 Pa, Rs0 0.222, kappa 0.43, R 0.05 m and B 4.13 in all three.
 * V is the volume on the terrain (com1DFA.fetchRelVolume: each DEM cell in
 * the release polygons, its thickness, measured normal to the slope, times
 * its true inclined area, summed; with secondary release areas their volume
 * added), not the plan area times the thickness.  (com1DFA's code tests
 * V > volClassMedium for the standard set and so leaves V = 60,000 m^3
 * exactly unset; its documentation's V >= 60,000 m^3 is taken here.) */
#define GF_SAMOSAT_VOL_SMALL 25000.0  /* [m^3] below: samosATSmall */
#define GF_SAMOSAT_VOL_MEDIUM 60000.0 /* [m^3] below: samosATMedium; from it on: samosAT */

/* One of AvaFrame's samosAT coefficient sets. */
typedef struct gf_samosat_set {
    const char *name; /* "samosATSmall", "samosATMedium", "samosAT" */
    double mu, tau0, Rs0, kappa, R, B;
} gf_samosat_set;

/* The three sets, small, medium, standard (NULL-terminated by name). */
const gf_samosat_set *gf_samosat_sets(void);

/* The set samosATAuto takes for release volume V [m^3] in *set.  GF_EDOM
 * for V <= 0 (no release volume: nothing to choose by), GF_ENONFINITE for a
 * V that is not finite. */
gf_status gf_samosat_auto(double volume, const gf_samosat_set **set);

/* Initialise f as law samosAT with the coefficients of set (u0 the law's
 * default, 1e-4 m/s; gf_friction_set changes it). */
gf_status gf_friction_init_samosat_set(gf_friction *f, const gf_samosat_set *set);

#ifdef __cplusplus
}
#endif

#endif
