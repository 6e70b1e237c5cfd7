/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * granflow — back-calculation of an observed event (calibration): the
 * designs of parameter sets to run, the scores of a run against the
 * observation, a local refinement, and what the runs say about the
 * parameters (credible ranges, the trade-off between them, a ridge of equal
 * loss, an "unreachable" verdict).
 *
 * Model reference: doc/theory/calibration.md.  Everything here is a pure
 * function on arrays: a driver decides what to run from the designs, runs
 * the members (ensemble workers), and reduces what came back with the
 * scores and the analyses below.  No file is read or written.
 *
 * Coordinates.  The d varied parameters are handled in unit coordinates
 * u in [0, 1]^d (row-major arrays, one row of d per point); parameter j's
 * value is lo_j + (hi_j - lo_j) u_j.  Designs return unit coordinates; the
 * sensitivities are per unit of each parameter's range (so that they compare
 * across parameters of different units); the emulator reports its ridge in
 * parameter units from the ranges it is given.  The Latin hypercube design is
 * ensemble.h's gf_sample_latin_hypercube.
 *
 * Every function returns a gf_status; a refusal records its reason for
 * gf_error_detail() (granflow/status.h).
 */
#ifndef GRANFLOW_CALIBRATION_H
#define GRANFLOW_CALIBRATION_H

#include <stddef.h>
#include <stdint.h>

#include "granflow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------ */
/* Designs (theory section 1)                                          */
/* ------------------------------------------------------------------ */

/** Largest dimension of gf_design_sobol (GSL's Sobol generator). */
#define GF_SOBOL_MAX_DIM 40

/** Sobol design: n points of GSL's Sobol sequence (gsl_qrng_sobol: Antonov &
 *  Saleev's Gray-code construction with Bratley & Fox's direction numbers) in
 *  d dimensions, u [n d] in [0, 1)^d, after skipping the first `skip` points
 *  of the sequence.  GSL's sequence already leaves out the origin (its first
 *  point is (1/2, ..., 1/2)); the sequence is deterministic and not
 *  scrambled (no randomisation: the same n, d, skip give the same design).
 *  Refused (GF_EINVAL): n < 1, d < 1 or d > GF_SOBOL_MAX_DIM, u NULL. */
gf_status gf_design_sobol(size_t n, size_t d, size_t skip, double *u);

/** Morris's step on a p-level grid: Delta = p / (2 (p - 1)) (Morris 1991). */
double gf_morris_delta(size_t p);

/** Morris trajectories (Morris 1991, with the random base point, directions
 *  and order of the parameters): r trajectories of d + 1 points each, u [r (d + 1), d]
 *  (trajectory t's points are rows t (d + 1) .. t (d + 1) + d).  Each
 *  trajectory starts at a random base point on the p-level grid
 *  {0, 1/(p-1), ..., 1} and moves one parameter at a time, in a random order,
 *  by +-Delta (gf_morris_delta(p)), staying on the grid; consecutive points
 *  differ in exactly one coordinate.  p even, p >= 2; the random numbers
 *  from granflow's generator (ensemble.h) seeded by seed.  Refused
 *  (GF_EINVAL): r < 1, d < 1, p odd or < 2, u NULL. */
gf_status gf_design_morris(size_t r, size_t d, size_t p, uint64_t seed, double *u);

/** Elementary effects of Morris trajectories and their statistics.
 *  u [r (d + 1), d] the trajectories (gf_design_morris or any with one
 *  coordinate changed per step), y [r (d + 1), m] the m outputs (scores) of
 *  each point.  For output k and parameter j, each trajectory gives one
 *  effect EE = (y(next) - y(this)) / (u_j(next) - u_j(this)) at its step in
 *  j (per unit of the parameter's range); mu [m d] is their mean, mu_star
 *  [m d] the mean of their absolute values (Campolongo et al. 2007) and
 *  sigma [m d] their standard deviation (denominator r - 1), index k d + j.
 *  Refused: r < 2, d < 1, m < 1, a NULL array (GF_EINVAL); a step that
 *  changes no coordinate or more than one, or a trajectory that leaves a
 *  parameter unvaried (GF_EDOM); a value that is not finite (GF_ENONFINITE:
 *  a failed member is rerun or dropped by the caller, not averaged in). */
gf_status gf_morris_effects(size_t r, size_t d, const double *u, const double *y, size_t m,
                            double *mu, double *mu_star, double *sigma);

/* ------------------------------------------------------------------ */
/* Scores of a run against an observation (theory section 2)            */
/* ------------------------------------------------------------------ */

/** The affected outline of a run compared with the observed one, on two
 *  co-registered rasters of n cells. */
typedef struct gf_outline_score {
    double tp, fp, fn;   /**< areas [m2]: both, simulated only, observed only */
    double jaccard;      /**< TP / (TP + FP + FN) */
    double tversky;      /**< TP / (TP + alpha FP + beta FN) (Tversky 1977) */
    size_t n_valid;      /**< cells counted (valid ones) */
} gf_outline_score;

/** Score the outline: a valid cell is simulated-affected when sim > threshold
 *  (NaN: not reached, the path analysis's convention) and observed-affected
 *  when observed[i] != 0; cells with valid[i] == 0 (NODATA in either raster)
 *  are left out (valid NULL: every cell counts).  Each cell counts
 *  cell_area.  alpha, beta >= 0 weigh the false positives and negatives in
 *  the Tversky index (alpha = beta = 1: Jaccard; 1/2: Dice); TP = 0 gives a
 *  Tversky index of 0.  Refused: n < 1, sim/observed/s NULL (GF_EINVAL);
 *  cell_area <= 0, alpha or beta < 0 (GF_EDOM); a non-finite threshold,
 *  cell_area, alpha, beta or an infinite sim value (GF_ENONFINITE); no valid
 *  observed-affected cell (GF_EDOM: there is nothing to compare with). */
gf_status gf_score_outline(size_t n, const double *sim, double threshold,
                           const unsigned char *observed, const unsigned char *valid,
                           double cell_area, double alpha, double beta, gf_outline_score *s);

/** Where the deposit RMSE is taken. */
typedef enum gf_rmse_region {
    GF_RMSE_UNION = 0,   /**< cells where either thickness exceeds the threshold */
    GF_RMSE_OBSERVED = 1 /**< cells where the observed thickness exceeds it */
} gf_rmse_region;

/** Deposit-thickness RMSE: sqrt(mean (sim - obs)^2) over the valid cells of
 *  the region (sim NaN: 0, not reached); *count the cells averaged.  Refused:
 *  n < 1, sim/obs/rmse NULL, an unknown region (GF_EINVAL); a non-finite
 *  threshold or obs value at a valid cell, an infinite sim value
 *  (GF_ENONFINITE); an empty region (GF_EDOM).  count may be NULL. */
gf_status gf_score_deposit_rmse(size_t n, const double *sim, const double *obs,
                                const unsigned char *valid, double threshold,
                                gf_rmse_region region, double *rmse, size_t *count);

/** Runout error along the path [m]: s_sim - s_obs (> 0: the run goes too
 *  far).  Refused (GF_ENONFINITE): a non-finite runout; err NULL (GF_EINVAL). */
gf_status gf_score_runout(double s_sim, double s_obs, double *err);

/** RMSE of two paired series (front positions [m] or speeds [m/s] at the
 *  same n times): sqrt(mean (sim_i - obs_i)^2).  Refused: n < 1, a NULL
 *  array (GF_EINVAL), a non-finite value (GF_ENONFINITE). */
gf_status gf_score_series_rmse(size_t n, const double *sim, const double *obs, double *rmse);

/** The front's position along the path at time t from an arrival-time map
 *  (theory section 2.6): the largest s of the n cells whose arrival time is
 *  finite and <= t and whose distance from the path |l| <= half_width, with
 *  s[i], l[i] the cell's coordinates along and across the path
 *  (gf_path_locate).  *s_front = NAN when no cell had arrived by t.  Cells
 *  with a NaN arrival (never reached, or off the mesh) are skipped.
 *  Refused: n < 1 or a NULL array (GF_EINVAL); a non-finite t or
 *  half_width <= 0 (GF_EDOM). */
gf_status gf_front_position(size_t n, const double *arrival, const double *s, const double *l,
                            double half_width, double t, double *s_front);

/** The front's speed along the path at time t [m/s]: the central difference
 *  (s_front(t + w) - s_front(t - w)) / 2w of gf_front_position, one-sided
 *  from t = 0 when t < w.  *speed = NAN when either position is NAN.
 *  Refused as gf_front_position, and w <= 0 or not finite (GF_EDOM). */
gf_status gf_front_speed(size_t n, const double *arrival, const double *s, const double *l,
                         double half_width, double t, double w, double *speed);

/** The scores of one run; NAN for a score that is not observed (left out of
 *  the loss). */
typedef struct gf_scores {
    double runout_error; /**< s_sim - s_obs [m] */
    double tversky;      /**< Tversky index of the outline, in [0, 1] */
    double rmse;         /**< deposit-thickness RMSE [m] */
    double series_rmse;  /**< front position RMSE [m] */
    double speed_rmse;   /**< front speed RMSE [m/s] */
} gf_scores;

/** Weights and normalising scales of the loss. */
typedef struct gf_loss_weights {
    double runout, runout_scale; /**< weight; error scale [m] (e.g. the runout tolerance) */
    double outline;              /**< weight of 1 - Tversky */
    double rmse, rmse_scale;     /**< weight; thickness scale [m] */
    double series, series_scale; /**< weight; front position scale [m] */
    double speed, speed_scale;   /**< weight; front speed scale [m/s] */
} gf_loss_weights;

/** The weighted loss of normalised scores (theory section 2.5):
 *      L = sum_k w_k e_k / sum_k w_k
 *  over the scores that are observed (not NAN) and weighted (w_k > 0), with
 *  e_runout = |runout_error| / runout_scale, e_outline = 1 - tversky,
 *  e_rmse = rmse / rmse_scale, e_series = series_rmse / series_scale,
 *  e_speed = speed_rmse / speed_scale: 0 for
 *  a perfect match, 1 for an error of one scale or no overlap.  Refused:
 *  s/w/loss NULL (GF_EINVAL); a negative weight, a scale <= 0 or not finite
 *  of a weighted and observed term, tversky outside [0, 1], an RMSE < 0, no
 *  term both observed and weighted (GF_EDOM); a non-finite weight or an
 *  infinite score (GF_ENONFINITE). */
gf_status gf_loss(const gf_scores *s, const gf_loss_weights *w, double *loss);

/* ------------------------------------------------------------------ */
/* Local refinement (theory section 3)                                  */
/* ------------------------------------------------------------------ */

/** The loss of one parameter set u [d] in unit coordinates, written to
 *  *loss; in the calibration each call is an ensemble member.  A status
 *  other than GF_SUCCESS, or a loss that is not finite, stops the
 *  refinement (a member that failed can be given a large finite loss by the
 *  callback instead). */
typedef gf_status (*gf_objective)(const double *u, size_t d, void *ctx, double *loss);

/** Every evaluation of a refinement, in call order, and its best one. */
typedef struct gf_simplex_result {
    size_t d;
    size_t n_evals;    /**< evaluations made (<= max_evals) */
    double *u;         /**< [n_evals d] the points evaluated, in [0, 1]^d */
    double *loss;      /**< [n_evals] their losses */
    size_t best;       /**< index of the lowest loss */
    int converged;     /**< 1: the simplex's size fell below tol; 0: budget spent */
    size_t iterations; /**< simplex iterations */
} gf_simplex_result;

/** Nelder-Mead simplex minimisation (Nelder & Mead 1965; GSL's
 *  gsl_multimin_fminimizer_nmsimplex2) of f over the unit box from u0 [d]
 *  (inside [0, 1]^d), initial simplex steps `step` (unit coordinates, e.g.
 *  0.1) along each axis.  The box is kept by reflection: the simplex moves
 *  in R^d and f is called at the point folded into [0, 1]^d (each coordinate
 *  reflected at 0 and 1, a continuous map), so f is never called outside
 *  the box and a minimum on its boundary is reached.  Stops when the
 *  simplex's size (GSL's root-mean-square distance of its vertices from their centre,
 *  unit coordinates) is below tol, or after max_evals calls of f (then
 *  converged = 0; the best point so far is still the result).  The result's
 *  arrays are allocated here; free them with gf_simplex_result_free.
 *  Refused: d < 1, f/u0/res NULL, max_evals < d + 1 (GF_EINVAL); u0 outside
 *  [0, 1] or not finite, step not in (0, 1], tol not > 0 (GF_EDOM or
 *  GF_ENONFINITE); a callback's failure is returned as its status with the
 *  evaluations so far in res. */
gf_status gf_refine_simplex(gf_objective f, void *ctx, size_t d, const double *u0, double step,
                            double tol, size_t max_evals, gf_simplex_result *res);
void gf_simplex_result_free(gf_simplex_result *res);

/* ------------------------------------------------------------------ */
/* Uncertainty and identifiability (theory section 4)                   */
/* ------------------------------------------------------------------ */

/** Kernel of the ABC's weights. */
typedef enum gf_abc_kernel {
    GF_ABC_UNIFORM = 0,     /**< every accepted point weight 1 */
    GF_ABC_EPANECHNIKOV = 1 /**< weight 1 - (L / epsilon)^2 (Beaumont et al. 2002) */
} gf_abc_kernel;

/** What the accepted points say about each parameter (unit coordinates). */
typedef struct gf_abc_result {
    size_t d, n;
    double epsilon;     /**< the acceptance loss: the loss's quantile-th quantile */
    size_t n_accepted;  /**< points with loss <= epsilon */
    double level;       /**< credible level of [lo, hi] */
    double *weight;     /**< [n] each point's weight (0: rejected), summing to 1 */
    double *mean;       /**< [d] weighted mean */
    double *lo, *median, *hi; /**< [d] weighted percentiles (1-level)/2, 1/2, (1+level)/2 */
    double *corr;       /**< [d d] weighted correlation between parameters (NAN for a
                             parameter without spread among the accepted) */
} gf_abc_result;

/** Rejection ABC on a design (Beaumont et al. 2002, without the regression
 *  adjustment): the loss L >= 0 plays the distance between simulated and
 *  observed; the points u [n d] whose loss is at most epsilon, the
 *  quantile-th quantile of the n losses (type 7, ensemble.h's
 *  gf_percentile; quantile in (0, 1]), are accepted, weighted by the kernel
 *  (Epanechnikov: 1 - (L/epsilon)^2; when epsilon = 0 or every accepted
 *  weight is 0 the accepted points weigh equally).  Each parameter's
 *  credible range [lo, hi] at `level` (e.g. 0.9) is the weighted
 *  percentiles of the accepted (theory section 4.1), with their weighted
 *  mean and median and the weighted correlation matrix.  Arrays allocated
 *  here; gf_abc_result_free frees them.  Refused: n < 2, d < 1, a NULL
 *  array (GF_EINVAL); quantile not in (0, 1], level not in (0, 1), a
 *  negative loss, an unknown kernel, fewer than 2 accepted points (GF_EDOM);
 *  a non-finite u or loss (GF_ENONFINITE). */
gf_status gf_abc_rejection(size_t n, size_t d, const double *u, const double *loss,
                           double quantile, gf_abc_kernel kernel, double level,
                           gf_abc_result *res);
void gf_abc_result_free(gf_abc_result *res);

/** Default fraction of the largest curvature below which a direction is a
 *  ridge (theory section 4.2). */
#define GF_RIDGE_FRACTION 0.01

/** A quadratic response surface of the loss around the best design point
 *  and what its Hessian says. */
typedef struct gf_emulator {
    size_t d;
    size_t n_fit;       /**< points fitted */
    double r2;          /**< coefficient of determination of the fit */
    double *center;     /**< [d] the best point (unit coordinates): the expansion's centre */
    double loss0;       /**< fitted loss at the centre */
    double *gradient;   /**< [d] fitted gradient at the centre (per unit coordinate) */
    double *hessian;    /**< [d d] fitted Hessian (unit coordinates) */
    double *curvature;  /**< [d] its eigenvalues, largest first */
    double *direction;  /**< [d d] row k: eigenvector k in unit coordinates (unit length) */
    double *direction_param; /**< [d d] row k: the same direction in parameter units,
                                  (hi - lo) * v_k normalised to unit length */
    int *ridge;         /**< [d] 1: curvature_k < fraction * curvature_0 (unconstrained) */
    size_t n_ridge;     /**< directions that are ridges */
    double *ridge_point;/**< [d] parameter units: the emulator's minimum across the
                             constrained directions, the ridge coordinates at the centre
                             (the emulator's minimum itself when n_ridge = 0) */
    double ridge_t_min, ridge_t_max; /**< along the first ridge direction (smallest
                             curvature) from ridge_point, the parameter-unit distances to the
                             box's faces (the ridge line's extent); 0 when n_ridge = 0, NAN
                             when the line misses the box */
} gf_emulator;

/** Fit L(u) ~ c + g.(u - u*) + 1/2 (u - u*)' H (u - u*) by linear least squares
 *  (gsl_multifit_linear) to the n_fit design points nearest (Euclidean, unit
 *  coordinates) to the best one u* (n_fit = 0: all n points; at least the
 *  1 + d + d (d + 1)/2 coefficients), and decompose H (gsl_eigen_symmv).  A
 *  direction whose curvature is below `fraction` (0 < fraction < 1; e.g.
 *  GF_RIDGE_FRACTION) of the largest is a ridge: along it the loss changes
 *  less than fraction as much as along the best-constrained direction, the
 *  parameters the observation cannot tell apart.  lo, hi [d] the ranges
 *  (hi > lo) for the parameter-unit results.  Arrays allocated here;
 *  gf_emulator_free frees them.  Refused: d < 1, a NULL array (GF_EINVAL);
 *  fewer points than coefficients, n_fit > n, fraction outside (0, 1),
 *  hi <= lo, a largest curvature <= 0 (no minimum near the best point),
 *  a singular fit (points on a lower-dimensional set) (GF_EDOM); a
 *  non-finite value (GF_ENONFINITE). */
gf_status gf_emulator_fit(size_t n, size_t d, const double *u, const double *loss, size_t n_fit,
                          const double *lo, const double *hi, double fraction, gf_emulator *em);
void gf_emulator_free(gf_emulator *em);

/** The fitted quadratic at u [d] (unit coordinates): loss0 + g.(u - u*) +
 *  1/2 (u - u*)' H (u - u*), for the loss picture over a pair of parameters.
 *  NAN when em or u is NULL or em holds no fit. */
double gf_emulator_eval(const gf_emulator *em, const double *u);

/** The verdict on an observation. */
typedef enum gf_verdict {
    GF_REACHABLE = 0,  /**< some evaluation meets every criterion */
    GF_UNREACHABLE = 1 /**< none does: no parameter set in the ranges reproduces the event */
} gf_verdict;

/** Criteria an evaluation must meet to reproduce the observation; NAN: not
 *  used. */
typedef struct gf_reach_criteria {
    double max_loss;         /**< loss <= max_loss */
    double min_jaccard;      /**< outline Jaccard >= min_jaccard */
    double runout_tolerance; /**< |runout error| <= runout_tolerance [m] */
} gf_reach_criteria;

typedef struct gf_reach_result {
    gf_verdict verdict;
    size_t best;       /**< the evaluation of lowest loss */
    size_t n_meeting;  /**< evaluations meeting every criterion */
    char reason[256];  /**< one line: which criterion the best evaluation misses, or
                            how many meet them */
} gf_reach_result;

/** The reachability verdict over every evaluation made (design and
 *  refinement): reachable when at least one evaluation meets every criterion
 *  given, unreachable otherwise — never a silent best guess.  loss [n]
 *  required; jaccard [n] and runout_error [n] may be NULL when their
 *  criterion is NAN.  Refused: n < 1, loss/c/res NULL, a criterion's array
 *  NULL, no criterion given (GF_EINVAL); a negative runout tolerance
 *  (GF_EDOM); an infinite criterion or a non-finite value of a used array
 *  (GF_ENONFINITE). */
gf_status gf_reach_verdict(size_t n, const double *loss, const double *jaccard,
                           const double *runout_error, const gf_reach_criteria *c,
                           gf_reach_result *res);


/* ------------------------------------------------------------------ */
/* The calibration's runs (theory section 5)                           */
/* ------------------------------------------------------------------ */

/** What one evaluation (an ensemble member) gave. */
typedef struct gf_calib_eval {
    int ok;            /**< 1: the member ran and was scored; 0: it failed */
    double loss;       /**< gf_loss of its scores (NAN when it failed) */
    gf_scores scores;  /**< runout error, Tversky, RMSE, series RMSE (NAN: not observed) */
    double jaccard;    /**< the outline's Jaccard index (NAN: no outline observed) */
    int accepted;      /**< 1: it reproduces the observation within its tolerance (the
                            caller's criteria, e.g. gf_reach_criteria's) */
} gf_calib_eval;

/** The evaluation of parameter set `index` at u [d] (unit coordinates),
 *  written to *out.  Called from several threads at once (plan.threads):
 *  it must be thread-safe.  The index is deterministic (the same plan gives
 *  the same index to the same point), so that a driver can keep the results
 *  of a stopped calibration and return them again instead of running the
 *  member twice.  A member that failed is out->ok = 0 with GF_SUCCESS; a
 *  status other than GF_SUCCESS stops the calibration. */
typedef gf_status (*gf_calib_evaluate)(size_t index, const double *u, size_t d, void *ctx,
                                       gf_calib_eval *out);

/** The plan: a space-filling design, Morris trajectories on top of it (the
 *  sensitivities), simplex refinements from the best design points, then
 *  an exploration of the region that reproduces the observation (a Sobol
 *  design in the box around the accepted evaluations, widened: the second
 *  population of a sequential ABC, so that the ranges come from runs that
 *  sample the accepted region and not only the refinements' paths). */
typedef struct gf_calib_plan {
    size_t d;            /**< parameters (1 .. GF_SOBOL_MAX_DIM) */
    size_t n_sobol;      /**< Sobol design points (>= 1) */
    size_t morris_r;     /**< Morris trajectories (0: none; else >= 2) */
    size_t morris_p;     /**< Morris grid levels (even >= 2) */
    uint64_t seed;       /**< Morris's random numbers */
    size_t n_starts;     /**< refinements (0: none), from the n_starts best design points */
    size_t refine_evals; /**< evaluations per refinement (>= d + 1) */
    double step, tol;    /**< the simplex's initial step and size tolerance (unit coordinates) */
    double failed_loss;  /**< the loss a failed member counts in a refinement (> 0, finite) */
    size_t n_explore;    /**< exploration points per round (0: none) */
    size_t explore_rounds; /**< exploration rounds (>= 1 when n_explore > 0): each round's box from
                              every accepted evaluation so far; the rounds end early when a round
                              widens the box by less than tol in every parameter */
    double explore_margin; /**< the box around the accepted evaluations widened by this fraction of
                              its width on each side (>= 0), and by at least 2 step; clipped to
                              [0, 1]; around the best evaluation when none is accepted */
    size_t threads;      /**< evaluations at once (>= 1; one per worker) */
} gf_calib_plan;

/** Where an evaluation comes from. */
typedef enum gf_calib_phase {
    GF_PHASE_SOBOL = 0,
    GF_PHASE_MORRIS = 1,
    GF_PHASE_REFINE = 2,
    GF_PHASE_EXPLORE = 3
} gf_calib_phase;

/** Every evaluation of a calibration, by index. */
typedef struct gf_calib_run {
    size_t d, n;         /**< parameters; evaluations (index 0 .. n - 1) */
    double *u;           /**< [n d] unit coordinates */
    gf_calib_eval *ev;   /**< [n] */
    int *phase;          /**< [n] gf_calib_phase */
    int *start;          /**< [n] the refinement an evaluation belongs to (-1: the design) */
    size_t n_sobol, n_morris; /**< the design's parts: indices [0, n_sobol), then n_morris */
    int *converged;      /**< [n_starts] each refinement: 1 converged, 0 budget spent */
    size_t n_starts;
    size_t n_explore;    /**< the exploration: the last explore_rounds n_explore indices (a
                              round that did not run leaves its indices unused, ok = 0) */
    size_t explore_rounds; /**< rounds run */
    double explore_box[2 * GF_SOBOL_MAX_DIM]; /**< its box (unit coordinates): lo_j at [j], hi_j at
                                                [GF_SOBOL_MAX_DIM + j] */
} gf_calib_run;

/** Index of evaluation j of refinement k: n_sobol + n_morris + k refine_evals + j;
 *  exploration point j: n_sobol + n_morris + n_starts refine_evals + j. */
size_t gf_calib_refine_index(const gf_calib_plan *plan, size_t k, size_t j);
size_t gf_calib_explore_index(const gf_calib_plan *plan, size_t j); /* j over all rounds: r n_explore + i */

/** Run a calibration: the design's points (Sobol, then Morris trajectories,
 *  plan.threads at a time), then plan.n_starts simplex refinements
 *  (gf_refine_simplex) from the best successful design points (those
 *  farther than 2 tol from a start already taken, so that they explore
 *  different places), each refinement in its own thread, plan.threads at a
 *  time, then the exploration's points (plan.threads at a time).  Indices
 *  are deterministic (gf_calib_refine_index); a refinement
 *  that stops before its budget leaves its remaining indices unused (ok =
 *  0, loss NAN, phase GF_PHASE_REFINE, start k).  The arrays are allocated
 *  here; gf_calib_run_free frees them.  Refused: a NULL argument, a plan
 *  outside the ranges above (GF_EINVAL, GF_EDOM); the first evaluation that
 *  returns an error stops every thread and is returned (the evaluations made
 *  are in run); no successful design point to start a refinement from
 *  (GF_EDOM: every member failed). */
gf_status gf_calibrate_run(const gf_calib_plan *plan, gf_calib_evaluate f, void *ctx, gf_calib_run *run);
void gf_calib_run_free(gf_calib_run *run);

#ifdef __cplusplus
}
#endif

#endif
