/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * granflow — references and error measures of the field's standard analytic
 * tests for 2D dense-flow solvers (doc/theory/standard-tests.md):
 *
 *  1. similarity solution of a spreading cap on an inclined Coulomb plane
 *     (Hutter, Siegel, Savage & Nohguchi 1993, Acta Mech. 100, 37-68,
 *     doi:10.1007/BF01176861): the ODE for the stretching factors g(tau),
 *     f(tau), integrated with GSL's odeiv2 from a Taylor start;
 *  2. dam break on an inclined Coulomb plane (Faccanoni & Mangeney 2013,
 *     Int. J. Numer. Anal. Methods Geomech. 37(10), 1408-1433), 1D profile;
 *  3. flat-plane pile in marginal Coulomb equilibrium (exact: at rest);
 *  4. energy line: mass-averaged path against the alpha line z0 - mu s;
 *  5. rotation: the same release turned about the bowl's axis.
 *
 * Coordinates: x, y horizontal, the planes descend towards +x.  Thickness is
 * measured normal to the bed, velocities are Cartesian 3-vectors tangent to
 * the bed.  Errors follow the field's definitions: relative L2 and Lmax of a
 * scalar or of a 3-vector over a set of cells, NaN cells skipped, no
 * threshold inside the set.
 */
#ifndef GRANFLOW_STANDARD_TESTS_H
#define GRANFLOW_STANDARD_TESTS_H

#include <stddef.h>

#include "granflow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- 1. similarity solution ---------------------------------------------- */

typedef struct gf_simisol_params {
    double g;        /* gravity [m/s2], 9.81 */
    double zeta;     /* plane inclination [rad], 35 deg */
    double delta;    /* bed friction angle [rad], 25 deg */
    double H;        /* initial peak thickness [m], 4 */
    double Lx, Ly;   /* initial semi-axes along and across the slope [m], 80 */
    double Kx, Ky;   /* earth pressure coefficients (1, 1: isotropic) */
    /* Optional (not the standard test's setting): flag_earth = 1 replaces Kx
     * and Ky by the Savage-Hutter active/passive coefficients of the internal
     * friction angle phi [rad] (delta <= phi), chosen at every evaluation of
     * the ODE's right-hand side: Kx active where g' >= 0, Ky active where
     * f' >= 0 (Ky from the chosen Kx); the Taylor start uses both active. */
    int flag_earth;  /* 0: Kx, Ky as given (default) */
    double phi;      /* internal friction angle [rad], 25 deg; used only with flag_earth */
} gf_simisol_params;

/* The standard test's parameters (g 9.81, zeta 35 deg, delta 25 deg, H 4,
 * Lx = Ly = 80, Kx = Ky = 1). */
gf_simisol_params gf_simisol_default(void);

typedef struct gf_simisol gf_simisol;

/* Integrate the similarity ODE from the Taylor start (tau <= 0.1) up to
 * t_end [s] with GSL's adaptive integrator at relative tolerance rtol
 * (1e-10 for the reference).  Refuses non-finite or non-positive sizes,
 * delta >= zeta (the cap does not slide). */
gf_status gf_simisol_alloc(gf_simisol **out, const gf_simisol_params *p, double t_end,
                           double rtol);
void gf_simisol_free(gf_simisol *s);

/* g, g', f, f' (derivatives with respect to tau = t/sqrt(Lx/g)) at t in
 * [0, t_end]; dense output between the integrator's steps. */
gf_status gf_simisol_stretch(const gf_simisol *s, double t, double *gv, double *dg,
                             double *fv, double *df);

/* Thickness h [m] (normal to the bed) and Cartesian velocity vel[3] [m/s]
 * at the horizontal point (x, y) at time t (0 where h = 0).
 * The cross-slope velocity uses the field's scale V = sqrt(g Ly); the
 * balances of mass and cross-slope momentum hold with it only for Lx = Ly
 * (the standard test): the kinematic scale is Ly sqrt(g / Lx). */
gf_status gf_simisol_sample(const gf_simisol *s, double x, double y, double t, double *h,
                            double vel[3]);

/* Scales and coefficients of the similarity ODE: T = sqrt(Lx/g),
 * U = sqrt(g Lx), V = sqrt(g Ly), A = sin zeta, C = cos zeta tan delta,
 * B = eps_x cos zeta Kx, D = (eps_y^2/eps_x) cos zeta Ky, E = (A - C)/A
 * (with flag_earth: B and D of the start, both coefficients active). */
typedef struct gf_simisol_coeffs {
    double T, U, V;
    double A, B, C, D, E;
} gf_simisol_coeffs;
void gf_simisol_coefficients(const gf_simisol *s, gf_simisol_coeffs *c);

/* Horizontal x of the centre of mass at time t >= 0 (y_c = 0):
 * Lx (A - C) tau^2 / 2 cos zeta; NaN for parameters gf_simisol_alloc
 * refuses. */
double gf_simisol_xc(const gf_simisol_params *p, double t);

/* The initial thickness h0(x, y) = H max(0, 1 - xi^2/Lx^2 - y^2/Ly^2),
 * xi = x / cos(zeta). */
double gf_simisol_h0(const gf_simisol_params *p, double x, double y);

/* ---- 2. dam break on an inclined Coulomb plane --------------------------- */

typedef struct gf_incdam {
    double g, phi, delta;   /* gravity, plane inclination, bed friction angle [rad] */
    double hL;              /* released thickness [m] */
    double x_back;          /* horizontal x of the release's rear edge [m] (< 0) */
    double gz, m0, cL;      /* g cos(phi), gz (tan phi - tan delta), sqrt(gz hL) */
} gf_incdam;

/* The standard test: phi 22 deg, delta 21 deg, hL 1 m, x_back -120 m. */
gf_status gf_incdam_init(gf_incdam *d, double g, double phi, double delta, double hL,
                         double x_back);

/* Along-slope profile at the horizontal position x (xi = x / cos phi, the
 * dam at 0) and time t >= 0: thickness h and downslope speed u.  As the
 * field's reference, the body h = hL, u = m0 t extends upstream without
 * end (the rear edge is not modelled): compare downstream of xmid only.
 * t <= 0 gives hL for x <= 0 (upstream of x_back too), 0 beyond. */
void gf_incdam_sample(const gf_incdam *d, double x, double t, double *h, double *u);

/* Horizontal x of the rarefaction fan's tail (the body/fan boundary,
 * xi = (m0 t/2 - cL) t) and of the front (xi = (2 cL + m0 t/2) t) at t >= 0. */
void gf_incdam_fan(const gf_incdam *d, double t, double *x_tail, double *x_front);

/* Horizontal x downstream of which the rear rarefaction (not part of the
 * exact solution) has no influence at time t: xmid(t) cos(phi). */
double gf_incdam_xmid(const gf_incdam *d, double t);

/* ---- 3. flat-plane pile --------------------------------------------------- */

/* h0(r) = min(H0, max(0, H0 - slope (r - r0))), r = sqrt(x^2 + y^2). */
double gf_flatpile_h0(double H0, double r0, double slope, double x, double y);

/* ---- error measures ------------------------------------------------------- */

typedef struct gf_error_norms {
    double l2, l2ref;       /* sqrt(w sum e), sqrt(w sum r) */
    double lmax, lmaxref;   /* max |a - n|, max |a| */
    double rel_l2, rel_lmax;/* l2 / l2ref, lmax / lmaxref (absolute where the reference is 0) */
    size_t n_used;          /* cells counted (NaN cells skipped) */
} gf_error_norms;

/* Scalar measure over n cells of weight w (csz^2 / cos theta).  As numpy's
 * nansum/nanmax, each sum skips its own NaN terms: a cell whose analytic
 * value is NaN leaves both sums, one whose numerical value is NaN only the
 * error's (n_used counts the error's cells).  GF_ENONFINITE for infinite
 * values or when every cell's error is NaN; GF_EINVAL for n = 0. */
gf_status gf_error_scalar(const double *analytic, const double *numeric, size_t n, double w,
                          gf_error_norms *out);

/* Vector measure over n cells, 3 components each (a[3 i + k]). */
gf_status gf_error_vector(const double *analytic, const double *numeric, size_t n, double w,
                          gf_error_norms *out);

/* Output grid size when a DEM of n0 cells of csz0 is computed at csz:
 * floor((n0 - 1) csz0 / csz) + 1 (the lower-left centre kept); 0 for
 * n0 = 0 or sizes that are not finite and positive. */
size_t gf_output_grid_cells(size_t n0, double csz0, double csz);

/* ---- 4. energy line --------------------------------------------------------- */

typedef struct gf_energy_line {
    double gamma;        /* runout angle of the simulation [rad] */
    double s_alpha;      /* intersection with the alpha line [m] */
    double z_alpha;      /* its elevation [m] */
    double err_s;        /* s_end - s_alpha [m] (positive: overshoot) */
    double err_z;        /* z_end - z_alpha [m] */
    double err_angle;    /* gamma - alpha [rad] */
    double rmse_v;       /* sqrt(mean((z + v2/(2g) - (z0 - mu s))^2)) [m] */
    int extrapolated;    /* 1 when the intersection needed the extrapolation */
} gf_energy_line;

/* From n >= 2 mass-averaged points (s[k], z[k], v2[k]) at the saved times
 * (k = 0 at t = 0), friction mu, gravity g, cell size csz (the fit of the
 * extrapolation uses the points within 4 csz of the end).
 * The alpha line is z[0] - mu s.  The intersection is the last sign change
 * of z - (z[0] - mu s); when that is only the trivial one at the start (the
 * run stopped short, below the line: err_s < 0), the path is extended by
 * one point at (1 + k) s_end, z_end + k p s_end, k = 1, 2, 3, p the
 * least-squares slope of the points with s_end - s < 4 csz.  GF_ENOCONV
 * when even k = 3 meets no line (gamma and rmse_v are set, the
 * intersection's fields NaN); GF_EDOM when the path did not move forward
 * or the extrapolation has fewer than two distinct s to fit. */
gf_status gf_energy_line_analyse(const double *s, const double *z, const double *v2, size_t n,
                                 double mu, double g, double csz, gf_energy_line *out);

/* The mass-weighted sums of the energy-line test over faces (section 4 of
 * doc/theory/standard-tests.md), the faces listed in faces[0, n) or, with
 * faces NULL, faces 0..n-1; a face counts where h > 0, its speed only where
 * h > h_dry (a thinner film has no velocity in the kernel):
 *   out[0] = sum A h                 (volume; times rho: the mass)
 *   out[1..3] = sum A h x            (x the face centre: the centre of mass)
 *   out[4] = sum A |m|^2 / h         (= sum A h |u|^2, m = h u)
 *   out[5] = sum A |m - (m.e) e|     (= sum A h |u_hor|, e = g/|g|)
 * out[5] is the rate of change of sum A h sigma for the path-length tracer
 * d(h sigma)/dt + div(h sigma u) = h |u_hor| (the flux sums to 0 over a
 * closed domain), so with the mass constant the mass-averaged path length
 * is s(t) = (integral_0^t out[5] dt) / out[0]: the tracer's mean without the
 * tracer.  area [.], centre [3 .], h [.], mom [3 .] indexed by face; g any
 * non-zero gravity vector. */
void gf_path_moments(size_t n, const int *faces, const double *area, const double *centre,
                     const double *h, const double *mom, double h_dry, const double g[3], double out[6]);

/* ---- 5. rotation -------------------------------------------------------------- */

/* Rotate a run back onto the reference's orientation: the run was released
 * at the reference's position rotated clockwise by angle [deg] about
 * (cx, cy), so out(p) = v(R p), R the clockwise rotation by angle about
 * (cx, cy), bilinear between the four cell centres around R p.  Grid: nx
 * columns, ny rows, row-major, GDAL's north-up geotransform gt (cell
 * (col, row) centred at gt[0] + (col + 1/2) gt[1], gt[3] + (row + 1/2) gt[5];
 * gt[2] = gt[4] = 0).  out is NaN where R p falls outside the cell centres
 * or one of its four values with a non-zero weight is NaN ("points
 * outside get no value").
 * GF_EINVAL for null pointers or an empty grid, GF_EDOM for a rotated or
 * degenerate geotransform or a non-finite angle. */
gf_status gf_grid_rotate_back(int nx, int ny, const double gt[6], const double *v, double angle_deg, double cx,
                              double cy, double *out);

#ifdef __cplusplus
}
#endif

#endif /* GRANFLOW_STANDARD_TESTS_H */
