/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * granflow — mass exchange with the bed and with obstacles: entrainment
 * (erosion, ploughing), detrainment and increased friction in resistance
 * areas.  Model reference: doc/theory/mass-exchange.md (after AvaFrame
 * com1DFA; Tonnel et al. 2023, Geosci. Model Dev. 16, 7013), its section n
 * cited below as "spec §n".
 *
 * Everything here is pointwise, per face and time step: a solver calls
 * gf_mass_exchange_face_update (or the single processes below) where it
 * applies friction.  The explicit surface scheme does so once per step
 * (gf_surface_set_mass_exchange, granflow/surface.h).
 *
 * Units: masses in kg, masses per area q in kg/m^2, thicknesses in m
 * (the flow thickness h at the flow density rho, the entrainable layer's
 * depth h_ent at its own density rho_ent: q_ent = rho_ent h_ent).
 *
 *   process              per face and step Δt                     spec
 *   erosion (e_b > 0)    Δm = min(τ_b |u| / e_b · A Δt, q_ent A)    §1
 *   ploughing (e_b = 0)  Δm = min(q_front w |u| Δt, q_ent A),        §1
 *                        w = √A
 *   entrained snow       joins at rest: momentum kept, |u| scaled     §1
 *                        by m/(m + Δm); h grows by Δm/(ρ A)
 *   energy loss          ΔE = e_s A_ent + e_d Δm taken from ½ m|u|²  §1
 *   windows              |u| < v_min or h < h_min: detrainment;       §2
 *                        within both windows: increased friction;
 *                        |u| > v_max or h > h_max: nothing
 *   detrainment          Δm_det = min(K/|u| · A Δt, m), |u| kept      §2
 *   increased friction   m du/dt = -c_res ρ A |u|² u/|u|, implicit    §2
 */
#ifndef GRANFLOW_MASS_EXCHANGE_H
#define GRANFLOW_MASS_EXCHANGE_H

#include "granflow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Parameters (doc/theory/mass-exchange.md, sections 1 and 2), AvaFrame's defaults. */
typedef struct gf_mass_exchange_config {
    int entrainment;      /* 1: entrainment where the entrainable layer is > 0 (simType ent, entres) */
    int resistance;       /* 1: resistance areas act (simType res, entres) */
    int detrainment;      /* 1 (default): detrainment below the windows (spec §2); 0: no detrainment,
                           * the increased friction acts everywhere in a resistance area */
    double rho_ent;       /* density of the entrainable snow rho_ent, > 0 [kg/m^3] (100) */
    double h_ent;         /* entrainable thickness where an area gives none, >= 0 [m] (0.3); for the
                           * set-up tools: the kernels take the per-face field */
    double e_b;           /* specific erosion energy, >= 0 [J/kg] (5000); 0 selects ploughing */
    double e_s;           /* breaking energy per fracture area, >= 0 [J/m^2] (0; entShearResistance) */
    double e_d;           /* deformation energy per entrained mass, >= 0 [J/kg] (0; entDefResistance) */
    double K;             /* detrainment coefficient, >= 0 [Pa] (5; Feistl et al. 2014) */
    double c_res;         /* increased-friction coefficient, >= 0 [-] (0.01) */
    double v_min, v_max;  /* speed window of the resistance areas, 0 <= v_min <= v_max [m/s] (6, 40) */
    double h_min, h_max;  /* thickness window, 0 <= h_min <= h_max [m] (0.6, 10) */
} gf_mass_exchange_config;

/* AvaFrame's defaults (doc/theory/mass-exchange.md): simType null (entrainment, resistance 0),
 * detrainment 1, rho_ent 100 kg/m^3, h_ent 0.3 m, e_b 5000 J/kg, e_s 0,
 * e_d 0, K 5 Pa, c_res 0.01, v_min 6 m/s, v_max 40 m/s, h_min 0.6 m,
 * h_max 10 m. */
void gf_mass_exchange_config_default(gf_mass_exchange_config *c);

/* AvaFrame's simType switch (spec §2, last paragraph): "null" (neither),
 * "ent" (entrainment), "res" (resistance), "entres" (both): sets
 * c->entrainment and c->resistance.  GF_ENOTFOUND (the detail lists the
 * four names) for any other name. */
gf_status gf_mass_exchange_simtype(gf_mass_exchange_config *c, const char *name);

/* Check every parameter: finite, inside its range above (a negative e_b,
 * e_s, e_d, K, c_res or h_ent, a density <= 0, switches other than 0/1),
 * and the windows not inverted (v_min <= v_max, h_min <= h_max).  GF_EDOM,
 * GF_ENONFINITE or GF_EINVAL; gf_error_detail() names the parameter, its
 * value and the range. */
gf_status gf_mass_exchange_config_check(const gf_mass_exchange_config *c);

/* Erosion mass rate per area ṁ = τ_b |u| / e_b [kg/(m^2 s)] (spec §1,
 * erosion), τ_b >= 0 the basal shear stress of the friction law [Pa];
 * 0 when e_b = 0 (ploughing) or |u| = 0. */
double gf_erosion_rate(const gf_mass_exchange_config *c, double tau_b, double speed);

/* Mass Δm [kg] that one face of area A takes from its entrainable layer in
 * a step dt (spec §1):
 *   erosion (e_b > 0):   Δm = min(ṁ A dt, q_ent A), ṁ = gf_erosion_rate;
 *   ploughing (e_b = 0): Δm = min(q_front w |u| dt, q_ent A), w = √A the
 *                        width of the face across the flow.
 * q_ent = rho_ent h_ent >= 0 is the layer left on the face [kg/m^2];
 * q_front >= q_ent the intact layer the front meets: the layer as set at the
 * start (a face's layer is taken strip by strip as the front sweeps across,
 * so the strip ahead is intact; with q_front = q_ent the spec's formula is
 * taken literally).  A front at constant |u| clears a face in √A/|u|,
 * taking exactly the swept layer q_front √A |u| t until then.  Arguments
 * are not checked (gf_mass_exchange_face_update does). */
double gf_entrainment_mass(const gf_mass_exchange_config *c, double tau_b, double speed, double area, double dt,
                           double q_ent, double q_front);

/* Speed after entrainment of dm >= 0 [kg] into a face of mass m > 0 [kg]
 * moving at |u| (spec §1): the entrained snow is at rest, so the momentum
 * is kept, |u| m/(m + dm); then the energy loss ΔE = e_s a_ent + e_d dm
 * (a_ent the fracture area [m^2]: A for erosion, the swept area dm/q_front
 * for ploughing) is taken from the kinetic energy ½ (m + dm) |u'|^2: the
 * speed scaled by √(1 - ΔE/(½ (m + dm)|u'|^2)), floored at 0.  With e_s =
 * e_d = 0 (the defaults) only the first factor.  (The e_s term is per step,
 * as in AvaFrame: it depends on the step for erosion.) */
double gf_entrainment_speed(const gf_mass_exchange_config *c, double m, double dm, double a_ent, double speed);

/* Which process of a resistance area acts on a face of thickness h and
 * speed |u| (spec §2). */
typedef enum gf_resistance_process {
    GF_RESISTANCE_NONE = 0,   /* |u| > v_max or h > h_max: the obstacles are overrun */
    GF_RESISTANCE_DETRAIN,    /* |u| < v_min or h < h_min: detrainment only */
    GF_RESISTANCE_FRICTION    /* within [v_min, v_max] and [h_min, h_max]: increased friction only */
} gf_resistance_process;

/* The windows of spec §2: DETRAIN when |u| < v_min or h < h_min (tested
 * first), NONE when |u| > v_max or h > h_max, FRICTION otherwise; with
 * c->detrainment = 0 FRICTION everywhere (spec §2: "with detrainment
 * switched off the increased friction applies everywhere in the area"). */
gf_resistance_process gf_resistance_window(const gf_mass_exchange_config *c, double speed, double h);

/* Detrained mass of a face of mass m [kg] and area A in a step dt (spec §2):
 * Δm_det = min(K/|u| A dt, m); the whole mass when |u| = 0 (and K > 0;
 * K = 0 or dt = 0 detrains nothing, at rest too).  The remaining
 * flow keeps its velocity (the deposited snow is stopped by the
 * obstacles). */
double gf_detrainment_mass(const gf_mass_exchange_config *c, double speed, double m, double area, double dt);

/* Speed after the increased friction of spec §2 over a step dt, implicit
 * like the friction laws (gf_friction_implicit_speed): the basal force
 * F_res = -c ρ A |u|^2 u/|u| gives, per unit area and density,
 * h d|u|/dt = -c |u|^2; backward Euler h s + dt c s^2 = h |u| has the root
 *   s = 2 |u| / (1 + √(1 + 4 c dt |u| / h)),
 * which slows the face but never reverses or stops it, for any dt
 * (unconditionally stable); c = c_res times the face's resistance factor.
 * h > 0; returns |u| when c = 0 or dt = 0. */
double gf_resistance_speed(double c, double h, double speed, double dt);

/* One face's state for gf_mass_exchange_face_update. */
typedef struct gf_mass_exchange_face {
    double h;           /* flow thickness [m], >= 0 */
    double speed;       /* |u| [m/s], >= 0 */
    double area;        /* face area A [m^2], > 0 */
    double rho;         /* flow density [kg/m^3], > 0 */
    double tau_b;       /* basal shear stress of the friction law at this state [Pa], >= 0 */
    double h_ent;       /* entrainable depth left on the face [m] (at rho_ent), >= 0 */
    double h_front;     /* intact layer depth ahead of the front (ploughing), >= h_ent [m] */
    double resistance;  /* 0 outside resistance areas, > 0 inside: the factor on c_res */
} gf_mass_exchange_face;

typedef struct gf_mass_exchange_result {
    double h;           /* new flow thickness [m] (0 exactly when detrainment takes all) */
    double speed;       /* new |u| [m/s] */
    double mom_factor;  /* new momentum h|u| over the old (the direction is kept): 1 exactly for
                         * entrainment without energy loss (spec §1), h_new/h_old for detrainment */
    double h_ent;       /* entrainable depth left [m] (0 exactly when the layer runs out, never < 0) */
    double entrained;   /* flow thickness gained, the actual difference of h [m] (Δm/(ρ A)) */
    double detrained;   /* flow thickness lost, the actual difference of h [m] (Δm_det/(ρ A)) */
    gf_resistance_process process; /* the resistance process that acted (NONE outside areas) */
} gf_mass_exchange_result;

/* One face's mass exchange over a step dt (spec §1, §2): the resistance
 * window is chosen from the state on entry (h, |u|); then entrainment
 * (c->entrainment, h_ent > 0, |u| > 0, h > 0: gf_entrainment_mass,
 * gf_entrainment_speed; the layer decreases by Δm/(rho_ent A) and never
 * below 0), then, in a resistance area (c->resistance, resistance > 0),
 * detrainment (gf_detrainment_mass: h decreases by Δm_det/(ρ A), to 0
 * exactly when it takes all) or the increased friction (gf_resistance_speed
 * with c = c_res resistance, at the thickness after entrainment).  The
 * configuration must have passed gf_mass_exchange_config_check.  GF_EDOM /
 * GF_ENONFINITE (the detail names the quantity) for a state outside the
 * ranges above or a negative or non-finite dt. */
gf_status gf_mass_exchange_face_update(const gf_mass_exchange_config *c, const gf_mass_exchange_face *f, double dt,
                                       gf_mass_exchange_result *r);

#ifdef __cplusplus
}
#endif

#endif
