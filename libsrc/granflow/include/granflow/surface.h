/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * granflow — explicit high-resolution finite-volume scheme for the
 * Rauter–Tuković model on a curved surface mesh (finite-area paper eqs. 30,
 * 33 and 35), on plain arrays of faces and edges.
 *
 * State per face: thickness h (measured normal to the surface) and the
 * depth-integrated momentum m = h u as a 3D Cartesian vector kept tangential
 * to the face (eq. 28).  One step of length dt is SSP-RK2 (Heun):
 *
 *   U1 = F(U0),  U(t+dt) = (U0 + F(U1)) / 2,
 *
 * where F is one forward-Euler stage followed by the pointwise implicit
 * friction update:
 *
 *  1. reconstruction: Green–Gauss gradients of h and of the three Cartesian
 *     velocity components, Barth–Jespersen limited (h at an edge stays within
 *     the values of the face and its neighbours, so it is >= 0; velocity
 *     within its wet neighbours'); order = 1 switches it off;
 *  2. edge fluxes in the edge frame (nu edge normal in the surface, n_e
 *     surface normal, t_e = n_e x nu): each side's velocity is rotated from
 *     its face's tangent plane into the edge plane about t_e, then HLL with
 *     Einfeldt speeds and Toro's dry-bed speeds (a front moves at u + 2c)
 *     for mass h u_nu, normal momentum h u_nu^2 + h p_b/(2 rho) (eq. 35's
 *     lateral pressure with p_b = rho a h) and tangential momentum
 *     h u_nu u_t.  A static edge, both sides slow (|u| < dt |g|, at rest
 *     included; a dry face has u = 0), carries only the donor flux of its
 *     mean normal velocity (the kinetic paper's Scheme 3 idea: zero at rest,
 *     no creep through HLL's mass diffusion) and each side feels a pressure
 *     of its own.  A face whose edges are all static (or walls) is in the
 *     hydrostatic mode: it feels a_f h_f (h_N - h_N^eq) / 2 at each edge,
 *     h_N^eq = max(0, a_f h_f + g.(x_N - x_f)) / a_N the neighbour thickness
 *     that continues its basal pressure hydrostatically (a = -g.n), nothing
 *     at walls, and no pointwise gravity: a lake whose basal pressure is
 *     rho g (eta - z) for one free-surface height eta stays at rest to
 *     round-off on any surface, with shorelines and walls (well-balanced),
 *     and a pile that friction holds stays exactly at rest (kinetic paper,
 *     Def. 1, in 2D); summed over a face the force is -A h (grad(a h) -
 *     g_s), first order.  Other faces feel a_f h_f h_N / 2 at their static
 *     edges (A a_f h_f grad h, Green–Gauss) plus pointwise gravity.  (The
 *     model's pressure term grad(a h^2/2) = a h grad h + h^2 grad a / 2:
 *     where a varies along a curved bed a horizontal lake is not exactly at
 *     rest in it; the static faces take the hydrostatic state instead.)
 *     On a wet/dry edge the face values are used (no
 *     reconstruction), so the limiter cannot cut a front's tip to zero.
 *     Boundary edges: wall (mirror state, zero mass flux),
 *     outflow (one-way: the interior state leaves, nothing enters), inflow
 *     (prescribed h and u: the flux of that state);
 *  3. face update: m* = m + dt (-div F + h g), projected onto the face's
 *     tangent plane; the normal part removed is the basal reaction, eq. (33):
 *       p_b/rho = n . div F_adv [centrifugal]
 *               + n . div F_press [lateral feedback] - h n . g,
 *     clipped at 0 (lift-off), and a = p_b/(rho h) enters the next stage's
 *     pressure flux;
 *  4. friction: gf_friction_implicit_speed per face (exact Coulomb stopping:
 *     a face whose driving force friction can hold stops within the stage).
 *
 * With gf_surface_set_mass_exchange, entrainment, detrainment and the
 * increased friction of resistance areas follow each step (below).
 *
 * Positivity: with Co <= 0.5 (Co = dt sum_e L_e s_e / (2 A), s_e the HLL
 * wave speed leaving the face through edge e, of the first-order states)
 * the first-order update keeps h >= 0; a face that the
 * reconstructed fluxes would drive negative has its edges recomputed at
 * first order (counted).  Mass: every edge flux leaves one face and enters
 * the other, so the volume changes only through boundary edges, whose
 * fluxes are accumulated per edge (gf_surface_edge_volume).
 *
 * Active set: faces with h > 0, the owners of inflow edges that bring
 * material, and two rings of neighbours (the first ring exchanged between
 * ranks); only those faces and their edges are computed, so dry terrain
 * costs a scan.
 *
 * Parallel: faces n_faces .. n_faces+n_ghosts-1 are halo copies of other
 * ranks' faces (one per processor edge); the caller's exchange callback
 * fills their entries of a field before the kernel reads them.
 */
#ifndef GRANFLOW_SURFACE_H
#define GRANFLOW_SURFACE_H

#include <stddef.h>

#include "granflow/friction.h"
#include "granflow/mass_exchange.h"
#include "granflow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum gf_edge_kind {
    GF_EDGE_INTERNAL = 0, /* owner and neighbour faces (neighbour may be a ghost) */
    GF_EDGE_WALL,         /* impermeable, slip; also symmetry planes */
    GF_EDGE_OUTFLOW,      /* one-way: material leaves, nothing enters */
    GF_EDGE_INFLOW        /* prescribed thickness and velocity (gf_surface_set_inflow) */
} gf_edge_kind;

/* Geometry of a surface mesh; arrays are read, not copied, and must outlive
 * the solver.  Vectors are 3 consecutive doubles. */
typedef struct gf_surface_mesh {
    size_t n_faces;          /* owned faces */
    size_t n_ghosts;         /* halo faces, indices n_faces .. n_faces+n_ghosts-1 */
    size_t n_edges;
    const double *area;      /* [n_faces+n_ghosts] face areas */
    const double *centre;    /* [3(n_faces+n_ghosts)] face centres */
    const double *normal;    /* [3(n_faces+n_ghosts)] unit face normals (away from the bed) */
    const int *owner;        /* [n_edges] owner face */
    const int *neighbour;    /* [n_edges] neighbour face (or ghost); -1 on boundary edges */
    const int *kind;         /* [n_edges] gf_edge_kind */
    const double *length;    /* [n_edges] edge lengths */
    const double *edge_normal; /* [3 n_edges] unit normal in the surface, owner -> out */
    const double *edge_centre; /* [3 n_edges] edge midpoints */
    const double *edge_points; /* [6 n_edges] the two end points of each edge, or NULL
                                * (needed by gf_surface_mesh_refine and startup_levels) */
} gf_surface_mesh;

typedef struct gf_surface_config {
    double g[3];              /* gravity vector [m/s^2] */
    double rho;               /* density, > 0 [kg/m^3] */
    double h_dry;             /* thickness below which a face has no velocity, > 0 [m] */
    double courant;           /* Co of the time step, (0, 0.5] for positivity */
    int order;                /* 1 (first order) or 2 (limited linear reconstruction) */
    int centrifugal;          /* p_b includes n . div(h u u) (eq. 33, first term) */
    int lateral_feedback;     /* p_b includes n . div of the lateral pressure (eq. 33, third) */
    gf_friction friction;     /* basal friction law (gf_friction_init) */
    int startup_levels;       /* 0..3: start-up refinement (below) */
} gf_surface_config;

/* Defaults: g = (0, 0, -9.81), rho 1000, h_dry 1e-6, Co 0.5, order 2,
 * centrifugal and lateral feedback on, friction none, startup_levels 0.
 *
 * Start-up refinement (startup_levels = L > 0; meshes with edge_points; in
 * parallel with gf_surface_set_edge_exchange and gf_surface_set_min): a dam
 * break or release edge is a discontinuity that spans one face, and while
 * its waves are unresolved the scheme builds a front lag that it never
 * makes up (7-8 faces on Ritter's dam break at 200-800 faces).  With L > 0
 * the first phase of flow after gf_surface_set_state runs on meshes refined
 * L, L-1, .., 1 times (gf_surface_mesh_refine: 4^L faces per
 * quadrilateral).  The state is carried down piecewise constant; the phase
 * is measured by the travel of the fastest wave, the integral over time of
 * the largest |u| + sqrt(a h) over the faces: the finest mesh runs until
 * that is D / 2^(L-1), each coarser one to twice the travel of the finer
 * one, each restricted to the next by area-weighted means (mass to
 * round-off), the last onto this mesh at D = 40 d (d the smallest
 * sqrt(area) of a wet face at the start), or when nothing moves.  The
 * caller's steps stay this mesh's (gf_surface_max_dt of the restricted
 * state; inflow states are passed down each step); between them this mesh
 * holds the restriction of the running level, and boundary volumes of every
 * level reach its edges.  The peak fields see the state at the end of each
 * step; a restart (gf_surface_restore) taken inside the phase continues on
 * this mesh.  Work: at most 8 (L = 1), 36 (L = 2) or 148 (L = 3) times that
 * of this mesh over the phase (level l: 4^l faces, 2^l steps; fewer where
 * faces are dry).  Measured (order 2, fronts at h = 1e-3, t = 5, 95-395
 * cells of travel): Ritter -7.6 / -8.0 / -6.8 cells at N = 200 / 400 / 800
 * without, -2.2 / -1.8 / -1.4 with L = 2. */
void gf_surface_config_default(gf_surface_config *c);

typedef struct gf_surface gf_surface;

/* Fill the ghost entries (indices n_faces ..) of a field with ncomp
 * components per face from the neighbouring ranks; 0 on success. */
typedef int (*gf_surface_exchange_fn)(void *ctx, double *field, int ncomp);

/* A face order that keeps neighbouring faces together in memory: order[i]
 * (i = 0 .. n-1) is the face that comes i-th along a Hilbert curve through
 * the face centres ([3n]), projected onto the plane of the two coordinate
 * axes with the largest extent (a terrain's x and y); equal keys in face
 * order.  The kernel works only on the active set (wet faces and two
 * rings): numbered in this order, those faces and their edges are a few
 * runs of consecutive entries, so a step reads whole cache lines and pages
 * of its arrays and touches (makes resident) few others.  A caller numbers
 * its faces by it before building gf_surface_mesh (face order[i] becomes
 * face i, and the edges follow their faces) and maps its fields in and out.
 * The kernel sums over a face's edges in the order of the edge centres, not
 * of the edge numbers, so the state is the same bit for bit in any
 * numbering (sums over faces, such as gf_surface_volume, to round-off).
 * Errors: a non-finite centre. */
gf_status gf_surface_face_order(size_t n, const double *centre, int *order);

/* Check the mesh (finite geometry, unit normals, index ranges, kinds) and
 * the configuration; errors name the entry. */
gf_status gf_surface_alloc(const gf_surface_mesh *mesh, const gf_surface_config *cfg,
                           gf_surface **out);
void gf_surface_free(gf_surface *s);

/* The edges' length, centre and normal computed by the scheme from the
 * mesh's points instead of read from the mesh's length, edge_normal and
 * edge_centre (which may then be NULL), as an OpenFOAM area mesh defines
 * them (its magLe, edgeCentres and Le, which it would otherwise compute and
 * keep for every edge): with d = p_end - p_start, the length |d|, the
 * centre (p_start + p_end)/2, the normal d x n_e (n_e the surface's unit
 * normal at the edge) turned away from the owner's centre (the side of the
 * edge centre where (d x n_e) . (x_owner - centre) < 0), scaled to the
 * length, divided by it.  The scheme computes an edge's geometry when it
 * needs it (the set-up checks, the order of a face's edges, an edge's first
 * step in the active set), so a caller keeps no per-edge geometry, and the
 * results equal those of the mesh with the same values in its arrays, bit
 * for bit.  Edge e of the mesh is entry i = index[e] of the arrays [0] when
 * i >= 0, entry -1 - i of the arrays [1] when i < 0 (OpenFOAM keeps the
 * boundary edges' normals per patch).  points, ends and surface_normal must
 * outlive the scheme; index is copied.  Not with startup_levels > 0 (the
 * refined meshes are built from the mesh's own arrays). */
typedef struct gf_surface_edge_geometry {
    const int *index;                 /* [n_edges] */
    const double *points;             /* 3 per point */
    const int *ends[2];               /* 2 per entry: the edge's start and end point */
    const double *surface_normal[2];  /* 3 per entry: the surface's unit normal at the edge */
} gf_surface_edge_geometry;

/* gf_surface_alloc with the edges' geometry from eg (NULL: the mesh's) */
gf_status gf_surface_alloc_edges(const gf_surface_mesh *mesh, const gf_surface_edge_geometry *eg,
                                 const gf_surface_config *cfg, gf_surface **out);

/* Halo exchange used by every stage (NULL: serial, no ghosts allowed). */
void gf_surface_set_exchange(gf_surface *s, gf_surface_exchange_fn fn, void *ctx);

/* Optional, with an exchange: the owned faces whose values the exchange
 * sends (the faces next to processor boundaries; n of them, copied).  The
 * scheme then prepares only those faces' entries of its scratch fields
 * before an exchange (the active set's ring levels, the positivity marks)
 * instead of every owned face's, so that a step's cost on a rank follows
 * its active faces, as in a serial run.  The results are the same either
 * way.  Refused: a face index outside the owned faces. */
gf_status gf_surface_set_send_faces(gf_surface *s, size_t n, const int *faces);

/* Exchange of blocks per processor edge: send and recv hold ncomp doubles
 * per ghost g (the processor edge of ghost g): send this rank's block, recv
 * the neighbouring rank's block for the same edge; 0 on success.  Needed by
 * startup_levels > 0 in a parallel run (the refined meshes' halos). */
typedef int (*gf_surface_edge_exchange_fn)(void *ctx, const double *send, double *recv, int ncomp);
void gf_surface_set_edge_exchange(gf_surface *s, gf_surface_edge_exchange_fn fn, void *ctx);

/* Global minimum over all ranks of each of v[0..n-1], in place; 0 on
 * success.  Needed by every parallel run (ghost faces): the ranks agree on
 * the positivity fallback of each stage (which faces' edges are recomputed
 * at first order, whether the step is halved), on the scale of its
 * tolerance, and with startup_levels > 0 on the start-up's length and the
 * refined meshes' steps.  With it a decomposed run takes the serial run's
 * decisions, and its state equals the serial one bit for bit (each face
 * sums over its edges in the order of their centres, which a processor
 * edge shares with the serial one). */
typedef int (*gf_surface_min_fn)(void *ctx, double *v, int n);
void gf_surface_set_min(gf_surface *s, gf_surface_min_fn fn, void *ctx);

/* Uniform refinement: each face of k edges becomes k quadrilaterals (face
 * centre, the midpoints of two consecutive edges and their common corner);
 * each edge becomes two, keeping its kind, normal and parent; new edges join
 * the centre to each midpoint.  Sub-face areas are scaled to sum to the
 * parent's exactly.  Ghost faces are not split: each becomes two ghost
 * sub-faces, one per half of its processor edge, numbered from the half at
 * the lexicographically smaller end point (the same on both ranks), with
 * the parent ghost's geometry until the caller fills in the neighbouring
 * rank's (the start-up does, through gf_surface_set_edge_exchange).  Needs
 * edge_points; errors name the face or edge. */
typedef struct gf_surface_refined {
    gf_surface_mesh mesh;  /* the refined mesh (arrays owned by this struct) */
    int *parent_face;      /* [mesh.n_faces] face of the input mesh (its sub-faces are consecutive) */
    int *parent_edge;      /* [mesh.n_edges] edge of the input mesh, -1 inside a face */
    double *area_, *centre_, *normal_, *length_, *enormal_, *ecentre_, *epoints_; /* storage */
    int *owner_, *neighbour_, *kind_;
} gf_surface_refined;

gf_status gf_surface_mesh_refine(const gf_surface_mesh *in, gf_surface_refined **out);
void gf_surface_refined_free(gf_surface_refined *r);

/* Initial state of the owned faces: h [n_faces] >= 0 and finite, m
 * [3 n_faces] or NULL for rest; m is projected onto the tangent planes and
 * set to 0 where h <= h_dry.  Errors name the face. */
gf_status gf_surface_set_state(gf_surface *s, const double *h, const double *m);

/* The normal acceleration a = p_b/(rho h) [m/s^2] of each face that the next
 * stage's pressure and wave speeds use ([n_faces+n_ghosts]; hydrostatic
 * -g.n after gf_surface_set_state, then eq. 33's value of the last stage). */
const double *gf_surface_normal_acceleration(const gf_surface *s);

/* A restart: the state exactly as this scheme had it - h, the momentum
 * (gf_surface_momentum, kept as given, also on faces with h <= h_dry) and
 * the normal acceleration - so that the run continues bit for bit as the
 * uninterrupted one (same time steps given).  Errors name the face. */
gf_status gf_surface_restore(gf_surface *s, const double *h, const double *m, const double *a);

/* Prescribed state of an inflow edge: thickness h >= 0 and velocity u (3D,
 * projected onto the owner's tangent plane). */
gf_status gf_surface_set_inflow(gf_surface *s, size_t edge, double h, const double u[3]);

/* Largest stable step for the configured Courant number (HUGE_VAL when
 * nothing moves and no wave can start: an empty domain). */
gf_status gf_surface_max_dt(gf_surface *s, double *dt);

/* Advance by dt.  A step that would make a thickness negative even with
 * first-order fluxes is repeated as two half steps (counted; up to 6
 * levels); GF_EPHYS naming the face if that is not enough. */
gf_status gf_surface_step(gf_surface *s, double dt);

const double *gf_surface_h(const gf_surface *s);        /* [n_faces+n_ghosts] */
const double *gf_surface_momentum(const gf_surface *s); /* [3(n_faces+n_ghosts)] */
const double *gf_surface_pb(const gf_surface *s);       /* [n_faces] basal pressure [Pa] */
/* Cumulative volume that left through each edge (negative: entered), from
 * the owner's side; meaningful for boundary edges. */
const double *gf_surface_edge_volume(const gf_surface *s);

/* Peak fields over time, for hazard maps: h_peak[f] = max(h_peak[f], h_f)
 * and speed_peak[f] = max(speed_peak[f], |u_f|) over the owned faces of the
 * last step's active set (every face that is or was wet in it; the others
 * have h = 0 and cannot raise a peak).  Caller-owned arrays [n_faces];
 * call after each gf_surface_step. */
void gf_surface_update_peaks(const gf_surface *s, double *h_peak, double *speed_peak);
/* The same into arrays in the caller's numbering: kernel face f's peaks go
 * to entry map[f] (a caller that numbered its faces by
 * gf_surface_face_order passes that order); map NULL: entry f. */
void gf_surface_update_peaks_mapped(const gf_surface *s, const int *map, double *h_peak, double *speed_peak);
/* Arrival time, for front observations (radar, video): arrival[map[f]] = t
 * for each owned face of the last step's active set whose thickness reaches
 * h_min for the first time (arrival < 0: not reached yet; the caller fills
 * the array with -1 at the start).  t is the time at the end of the step,
 * so an arrival is late by at most one step.  map NULL: entry f. */
void gf_surface_update_arrival_mapped(const gf_surface *s, const int *map, double t, double h_min,
                                      double *arrival);

/* First moments of the owned faces' volume for the centre of mass:
 * out[0] = sum A h, out[1..3] = sum A h x_f (face centres), over the active
 * set (the other faces are dry). */
void gf_surface_moments(const gf_surface *s, double out[4]);

/* The energy-line sums of gf_path_moments (granflow/standard_tests.h) over
 * the owned faces with the kernel's state and gravity: volume, its first
 * moments, sum A h |u|^2 and sum A h |u_hor|; valid before the first step
 * too. */
void gf_surface_path_moments(const gf_surface *s, double out[6]);

/* Volume sum_f A_f h_f of the owned faces: after a step over the active
 * set (the other faces are dry), before the first over every owned face. */
double gf_surface_volume(const gf_surface *s);

/* Mass exchange with the bed and obstacles (granflow/mass_exchange.h;
 * model reference doc/theory/mass-exchange.md): entrainment where
 * h_ent[f] > 0, detrainment or increased friction where resistance[f] > 0,
 * per owned face, switched by cfg->entrainment and cfg->resistance (a NULL
 * cfg, or both switches 0 - simType null - turns it off: the scheme is then
 * exactly the one without it, at the cost of one test per step).
 *   h_ent       [n_faces] entrainable depth [m] at cfg->rho_ent, >= 0 (the
 *               polygons' thickness; 0 outside entrainment areas); needed
 *               when cfg->entrainment;
 *   resistance  [n_faces] 0 outside resistance areas, > 0 inside: the factor
 *               on cfg->c_res (1: the configured coefficient); needed when
 *               cfg->resistance.
 * Both fields and the configuration are copied (the caller's arrays can go);
 * a call replaces the previous exchange and zeroes the entrained and
 * detrained fields and totals.  Errors (the detail names the parameter or
 * face): the configuration's (gf_mass_exchange_config_check), a missing
 * field, a negative or non-finite entry, startup_levels > 0 (the start-up's
 * refined meshes carry no layer: refused).
 *
 * When: once per step, after the SSP-RK2 combination (Lie splitting), where
 * the explicit part and the friction of both stages are done:
 * gf_mass_exchange_face_update on each owned wet face, with |u| and h of
 * the step's result, τ_b the friction law's at that state and the last
 * stage's p_b.  Why not per stage like the friction: SSP-RK2's final
 * average (U0 + U2)/2 of a per-stage exchange would halve a layer that runs
 * out in each step instead of taking it (0.5 q_ent left, then 0.25, ...),
 * and its detrainment would never empty a face; once per step the layer
 * reaches 0 exactly and a face detrains to 0 exactly.  The step stays SSP
 * (the exchange is a pointwise map that keeps h >= 0 and h_ent >= 0 for
 * any dt) and the mass balance exact: the volume that a face gains or
 * loses is the actual difference of its h, counted as it is applied.  Time
 * accuracy is first order for the exchange terms, as for the scheme's
 * implicit friction: the SSP-RK2 average of two implicit stages is first
 * order too (for h du/dt = -c u^2 its per-step error is 1.5 (c u dt/h)^2 u
 * against 0.5 for one backward-Euler step).
 *
 * Mass balance, in volumes at the flow density (mass = rho volume; summed
 * over the ranks in parallel, each rank counting its owned faces):
 *   gf_surface_volume + outflow - inflow - entrained + detrained = initial
 * to round-off, outflow and inflow from gf_surface_edge_volume. */
gf_status gf_surface_set_mass_exchange(gf_surface *s, const gf_mass_exchange_config *cfg, const double *h_ent,
                                       const double *resistance);

/* The entrainable depth left on each owned face [n_faces] [m] (at rho_ent;
 * never negative), or NULL without mass exchange. */
const double *gf_surface_entrainable_depth(const gf_surface *s);
/* Cumulative flow thickness [m] (at the flow density rho) that each owned
 * face gained by entrainment / lost by detrainment [n_faces]: the
 * entrained-depth and detrained-depth rasters of doc/theory/mass-exchange.md, section 4 (mass per
 * area: rho times it); NULL without mass exchange. */
const double *gf_surface_entrained_depth(const gf_surface *s);
const double *gf_surface_detrained_depth(const gf_surface *s);

/* Exchanged volumes [m^3] of this rank's owned faces at the flow density
 * (mass: rho times them): of the last gf_surface_step and since
 * gf_surface_set_mass_exchange (doc/theory/mass-exchange.md, section 4's mass time series); all 0
 * without mass exchange.  Of the detrained volume, the part taken in the
 * speed window (|u| < v_min: the rate K/|u| of doc/theory/mass-exchange.md, section 2) and of that
 * the part taken at rest (|u| = 0, where the rate is unbounded and the whole
 * face goes); the rest was faster than v_min and thinner than h_min.
 * AvaFrame's com1DFA detrains nothing at rest (doc/guide/avaframe-comparison.md). */
typedef struct gf_surface_exchange {
    double entrained_step, detrained_step;
    double entrained, detrained;
    double detrained_slow_step, detrained_rest_step; /* of detrained_step: |u| < v_min; |u| = 0 */
    double detrained_slow, detrained_rest;           /* of detrained: likewise */
} gf_surface_exchange;
void gf_surface_get_exchange(const gf_surface *s, gf_surface_exchange *x);

/* A restart of the mass exchange: after gf_surface_set_mass_exchange with
 * the layer as it was set at the start (the intact layer ploughing fronts
 * meet), the state of a run as these accessors gave it - the entrainable
 * depth left [n_faces] (each <= the layer set), the cumulative entrained
 * and detrained depths [n_faces] (or NULL: 0) and the totals x (or NULL: 0;
 * the last step's volumes are not restored) - so that, with
 * gf_surface_restore, the run continues bit for bit.  Errors (the detail
 * names the face): no mass exchange set, a negative or non-finite entry, a
 * layer left above the one set. */
gf_status gf_surface_restore_mass_exchange(gf_surface *s, const double *h_ent_left, const double *entrained,
                                           const double *detrained, const gf_surface_exchange *x);

typedef struct gf_surface_stats {
    unsigned long steps;
    unsigned long face_updates;     /* active faces summed over steps */
    unsigned long first_order_edges; /* edges recomputed at first order for positivity */
    unsigned long stopped_faces;    /* faces brought to rest by friction in a stage */
    unsigned long halved_steps;     /* steps repeated as two halves (positivity) */
    unsigned long roundoff_faces;   /* faces whose h came out in (-1e-13 h_scale, 0): set to 0 */
    double roundoff_volume;         /* volume added by those (<= 1e-13 of the volume) */
    size_t active_faces;            /* of the last step */
    unsigned long startup_steps;    /* steps on the refined meshes of the start-up (startup_levels) */
    double startup_time;            /* the time they covered (0: none) */
} gf_surface_stats;

void gf_surface_get_stats(const gf_surface *s, gf_surface_stats *st);

/* Total kinetic energy per unit density of the owned faces [m^5/s^2]:
 * sum_f 1/2 A_f |m_f|^2 / h_f = sum_f 1/2 A_f h_f |u_f|^2, m the momentum
 * h u (gf_surface_momentum), over the faces with h > h_dry (thinner films
 * have no velocity in the scheme); times rho it is in joules.  A pile at
 * rest has 0.  Cheap: the active set after a step (every owned face of a
 * loaded state before the first).  In parallel, sum over the ranks.  An end
 * condition: the flow has stopped when E falls below a fraction of its
 * running peak (AvaFrame: 1 %). */
double gf_surface_kinetic_energy(const gf_surface *s);

/* The faces still moving (the report at the end of a run, when the stop
 * criterion on the kinetic energy has ended it or endTime has): over the
 * faces with h > h_dry (thinner films have no velocity in the scheme), with
 * |u| = |m|/h,
 *   n, volume        how many are faster than `speed` (|u| > speed) and
 *                    their volume sum A h [m^3];
 *   max_speed,       the largest |u| of them all [m/s] (the fastest wet
 *   max_face,        face, faster than `speed` or not), its face (the first
 *   max_centre       of equal speeds in face order) and centre; 0, -1 and
 *                    (0, 0, 0) when no face is wet.
 * In parallel, sum n and volume over the ranks and take the fastest face of
 * the rank with the largest max_speed. */
typedef struct gf_moving_faces {
    size_t n;
    double volume;
    double max_speed;
    long max_face;
    double max_centre[3];
} gf_moving_faces;

/* gf_moving_faces of the arrays of n faces: area [n], centre [3n], h [n],
 * momentum m = h u [3n] (the implicit scheme's fields give h Us), h_dry the
 * dry threshold.  GF_EDOM / GF_ENONFINITE (detail names the argument) for a
 * speed or h_dry < 0 or not finite, GF_EINVAL for a null array with n > 0. */
gf_status gf_moving_faces_eval(size_t n, const double *area, const double *centre, const double *h,
                               const double *m, double h_dry, double speed, gf_moving_faces *out);

/* gf_moving_faces of the owned faces with the kernel's state and h_dry
 * (the active set after a step, every owned face before the first: the other
 * faces are dry); the same errors. */
gf_status gf_surface_moving_faces(const gf_surface *s, double speed, gf_moving_faces *out);

#ifdef __cplusplus
}
#endif

#endif
