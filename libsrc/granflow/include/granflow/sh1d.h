/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * granflow — 1D Savage–Hutter solvers: common configuration and interface.
 *
 * Equations (rkdg paper eqs. 1-2; kinetic paper eqs. 1, 13), on a bed of
 * inclination zeta(x) and curvature kappa(x):
 *
 *   h_t + (hu)_x = 0,
 *   (hu)_t + (hu^2 + beta h^2/2)_x = h g sin(zeta) - tau_b/rho,
 *   beta = epsilon K cos(zeta),
 *   tau_b/rho = friction law at basal pressure p_b/rho = h max(0, g cos(zeta) + chi kappa u^2)
 *
 * Dimensionless Savage–Hutter: epsilon = H/L, g = 1, Coulomb friction
 * mu = tan(delta) with u0 = 0 gives h s(u) of rkdg eq. 2.  Dimensional form:
 * epsilon = g = 9.81 m/s^2, kappa in 1/m, any friction law (e.g. mu_i).
 *
 * A solver is an object made from a type (the gsl_odeiv2_step_type pattern):
 *   gf_sh1d_rkdg     — P0-P2 Runge–Kutta discontinuous Galerkin (dg1d.h)
 *   gf_sh1d_kinetic  — kinetic Schemes 1, 2, 3 (kinetic1d.h)
 *
 *   gf_sh1d_config c;  gf_sh1d_config_init(&c);  c.n_cells = 256; ...
 *   gf_sh1d *s;  gf_sh1d_alloc(gf_sh1d_rkdg, &c, &s);
 *   gf_sh1d_set_initial(s, pile, &params);
 *   gf_sh1d_advance_to(s, 12.0);
 *   gf_sh1d_means(s, h, u);  gf_sh1d_free(s);
 */
#ifndef GRANFLOW_SH1D_H
#define GRANFLOW_SH1D_H

#include <stddef.h>

#include "granflow/earth_pressure.h"
#include "granflow/exact.h"
#include "granflow/friction.h"
#include "granflow/status.h"
#include "granflow/topography.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum gf_bc {
    GF_BC_TRANSMISSIVE = 0, /* zero-gradient outflow */
    GF_BC_WALL = 1,         /* reflecting wall: u = 0 */
    GF_BC_PERIODIC = 2
} gf_bc;

/* RKDG slope limiters (applied to h and q after every stage) */
typedef enum gf_limiter {
    GF_LIMITER_NONE = 0,
    GF_LIMITER_MINMOD = 1, /* rkdg paper eq. 13: edge values against gamma times the
                              neighbour differences (TVB with tvb_m); P2 -> P1 where
                              it acts */
    GF_LIMITER_MOMENT = 2  /* hierarchical moment limiter (Krivodonova 2007): each mode
                              against the differences of the next lower mode of the
                              neighbours, highest first (TVB with tvb_m); the default */
} gf_limiter;

/* "none", "minmod", "moment"; -1 for any other name. */
int gf_limiter_lookup(const char *name);

/* "none, minmod, moment" — for error messages. */
const char *gf_limiter_names(void);

typedef struct gf_sh1d_config {
    size_t n_cells;          /* number of cells N, >= 4 */
    double x_min, x_max;     /* domain */
    double epsilon;          /* beta = epsilon K cos(zeta) */
    double g;                /* gravity scale of the source: 1 or 9.81 */
    double chi;              /* curvature factor chi of rkdg eq. 2 (1) */
    double rho;              /* flow density: p_b = rho h (g cos zeta + chi kappa u^2) for
                                laws that use p_b itself (mu_i's inertial number, eq. 26);
                                1 in the dimensionless form */
    double zeta;             /* constant inclination [rad] when topo is NULL */
    const gf_topography *topo; /* variable zeta(x), kappa(x); not owned; or NULL */
    gf_earth_pressure earth_pressure;
    gf_friction friction;
    gf_bc bc_left, bc_right;
    double cfl;              /* Courant number; 0 = the scheme's default */
    double dt_fixed;         /* > 0: fixed step, rejected if it breaks the CFL bound */
    double h_eps;            /* dry threshold (rkdg: 1e-10) */
    double h_semi;           /* semi-wet threshold (rkdg: 1e-6) */
    /* RKDG */
    int degree;              /* polynomial degree k: 0, 1, 2 */
    gf_limiter limiter;      /* default GF_LIMITER_MOMENT */
    double gamma;            /* gamma of GF_LIMITER_MINMOD (rkdg paper: 0.5) */
    double tvb_m;            /* TVB constant M (default 1): a mode is not limited where
                                |value| <= M dx^2, which spares smooth extrema; 0 = strict
                                (the rkdg paper's minmod) */
    int velocity_limiter;    /* 1 (default): point velocities q/h within the range of the
                                mean velocities of the cell and its wet neighbours */
    /* kinetic */
    int scheme;              /* 1, 2 or 3 (kinetic paper section 3) */
    int kinetic_order;       /* 1 (default): the paper's first-order schemes; 2: minmod-limited
                                linear reconstruction of h and u with Heun's method (the
                                higher-order method the paper leaves to future work,
                                section 6), Courant number 0.45 by default; Schemes 1 and 3
                                (Scheme 2 reconstructs nothing); interfaces between two
                                slow cells keep the cell means, so rest is kept as at
                                order 1 */
    /* both */
    int startup_levels;      /* start-up refinement L in 0..5 (0, the default: off).  The
                                first phase, until the waves of the initial state have
                                crossed about 40 cells (kinetic_order 2: 60), is computed on grids 2^L, ..., 2
                                times finer and restricted to this one, mass-exactly:
                                the first steps of discontinuous initial data (a dam
                                break on a dry bed) are resolved instead of smeared
                                over a few cells, whose error a dry front keeps (issue
                                11).  It is taken by the first gf_sh1d_step. */
    /* RKDG */
    int moving_mesh;         /* 0 (default): the fixed grid of n_cells on [x_min, x_max].
                                1: front tracking.  The n_cells cells span the wet interval
                                of the initial data; an end of it inside the domain is a
                                dry front, whose node moves at the speed of the wet/dry
                                Riemann fan's edge, u + 2 sqrt(beta h) of the end cell's
                                trace (u - 2 sqrt(beta h) at a left front), and stands while
                                friction holds that cell at rest; the nodes between move in
                                proportion.  The equations in ALE form: fluxes relative to
                                the mesh velocity, none through a front node (mass kept to
                                round-off).  A front's kink or jump then sits on a node
                                instead of inside a cell.  A front that reaches the domain's
                                end lands on it (the step is shortened to do so) and from
                                then on is a fixed node with bc_left / bc_right (wall: the
                                flow is reflected; transmissive: it leaves); not with
                                periodic boundaries.  With startup_levels the finer
                                grids span the same interval, and each hands its nodes on. */
    /* both */
    double riemann_start;    /* 0 (default): the run starts at t = 0 from the initial data.
                                t_s > 0: a dam on a dry bed starts at t_s from its exact
                                solution (gf_sh1d_time is then t_s).  The initial data
                                must be one wet interval of uniform depth and velocity,
                                with a jump to a dry bed at one end or both (a dam), on a
                                plane (no topography), with no friction or a friction
                                whose tau/h depends on neither h nor u (Coulomb with
                                constant mu) and the flow moving one way, and an
                                earth-pressure coefficient that is the same at rest and in
                                expansion.  Then, until the fans meet or reach a boundary,
                                the exact solution is Ritter's fan of each dam (the
                                homogeneous dry-bed Riemann problem) in the frame that the
                                source accelerates uniformly (Mangeney, Heinrich & Roche
                                2000).
                                Instead of the start-up refinement (not with
                                startup_levels), and without a start-up error: a dam
                                break's first steps, while its fan spans a few cells,
                                otherwise set its error at every later time, at first
                                order for every degree (issue 11).  With t_s the same on
                                every grid the error converges at the scheme's order
                                after t_s.  Data that do not meet these conditions, and a
                                t_s at which the fans have met or reached the domain's
                                end, are refused with the reason. */
} gf_sh1d_config;

/* Defaults: k = 2 with the moment limiter and the velocity bound, the rkdg
 * paper's gamma = 0.5 (for the minmod limiter), h_eps = 1e-10,
 * h_semi = 1e-6, Scheme 3, epsilon = g = chi = 1, zeta = 0, isotropic
 * earth pressure, no friction, transmissive boundaries, N = 256 on [0, 30]. */
void gf_sh1d_config_init(gf_sh1d_config *c);

typedef struct gf_sh1d_type gf_sh1d_type;
typedef struct gf_sh1d gf_sh1d;

extern const gf_sh1d_type *const gf_sh1d_rkdg;
extern const gf_sh1d_type *const gf_sh1d_kinetic;

/* "rkdg" or "kinetic"; NULL otherwise. */
const gf_sh1d_type *gf_sh1d_type_lookup(const char *name);

/* "rkdg, kinetic" — for error messages. */
const char *gf_sh1d_type_names(void);
const char *gf_sh1d_type_name(const gf_sh1d_type *type);

/* Initial data: depth and velocity at x. */
typedef void (*gf_sh1d_initial_fn)(double x, void *ctx, double *h, double *u);

/* Check the configuration and make a solver. */
gf_status gf_sh1d_alloc(const gf_sh1d_type *type, const gf_sh1d_config *cfg, gf_sh1d **out);
void gf_sh1d_free(gf_sh1d *s);

/* Project the initial data (Gauss quadrature; rkdg eq. 8) and set t = 0.
 * Negative or non-finite depths are an error. */
gf_status gf_sh1d_set_initial(gf_sh1d *s, gf_sh1d_initial_fn fn, void *ctx);

/* One time step of at most dt_max (the CFL step, or dt_fixed).
 * GF_ENONFINITE if the solution stops being finite, GF_EDOM if dt_fixed
 * breaks the CFL bound. */
gf_status gf_sh1d_step(gf_sh1d *s, double dt_max);

/* Steps until time t (the last step shortened to land on t). */
gf_status gf_sh1d_advance_to(gf_sh1d *s, double t);

double gf_sh1d_time(const gf_sh1d *s);
size_t gf_sh1d_steps(const gf_sh1d *s);
/* Steps (or half steps) that were repeated as two halves because a stage
 * would have made a mean depth negative (RKDG; 0 for the kinetic schemes). */
size_t gf_sh1d_rejected_steps(const gf_sh1d *s);
/* Steps of the start-up refinement's finer grids (config.startup_levels),
 * summed over its levels; 0 without it. */
size_t gf_sh1d_startup_steps(const gf_sh1d *s);
/* The time the start-up refinement ends at (0 without it or before the
 * first step). */
double gf_sh1d_startup_time(const gf_sh1d *s);
size_t gf_sh1d_n_cells(const gf_sh1d *s);
double gf_sh1d_dx(const gf_sh1d *s);
double gf_sh1d_cell_centre(const gf_sh1d *s, size_t i);
const gf_sh1d_config *gf_sh1d_get_config(const gf_sh1d *s);

/* The grid's ends: [x_min, x_max] on the fixed grid; the moving mesh's current
 * nodes (moving_mesh = 1).  Outside them the solution is dry. */
void gf_sh1d_extent(const gf_sh1d *s, double *x_lo, double *x_hi);

/* Cell means of h and u (u = q/h, 0 where dry); arrays of n_cells. */
void gf_sh1d_means(const gf_sh1d *s, double *h, double *u);

/* Point values of the numerical solution at x (the DG polynomial; the cell
 * value for the kinetic schemes). */
gf_status gf_sh1d_eval(const gf_sh1d *s, double x, double *h, double *u);

/* Total mass: sum of cell means times dx. */
double gf_sh1d_mass(const gf_sh1d *s);

/* The mass that has left through the domain's ends since the initial state
 * (gf_sh1d_set_initial; inflow counts negative): the boundary fluxes of
 * every step, combined with the time integrator's stage weights, so that
 * gf_sh1d_mass + gf_sh1d_outflow is the initial mass to round-off with any
 * boundary condition (0 between walls, with periodic ends, and where the
 * moving mesh's fronts have not reached an end). */
double gf_sh1d_outflow(const gf_sh1d *s);

/* Smallest depth over all quadrature and interface points. */
double gf_sh1d_min_depth(const gf_sh1d *s);

/* Largest |u| over the cell means. */
double gf_sh1d_max_speed(const gf_sh1d *s);

#ifdef __cplusplus
}
#endif

#endif
