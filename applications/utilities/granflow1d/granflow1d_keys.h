/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * granflow1d_keys.h — the keys of granflow1d's case files, one row each:
 * section, key, type, default, allowed range or choices, unit, what it
 * applies to and a one-line description.  granflow1d reads every key
 * through its row (default, range; a key of no row is an error naming it)
 * and prints the rows as Markdown with --keywords (doc/keywords.md via
 * doc/make-keywords), so the reference is the code's.  The [friction]
 * section's keys are the coefficients of the law, printed from
 * libgranflow's table of laws (granflow/friction.h).
 *
 * type: number (a real), integer, choice (one of `allowed`, "a | b"), name
 * (a name the library looks up: method, limiter, friction law), string, list.
 * default: the value as a case file would give it; for number and integer
 * rows gf_parse_number of it is the default, unless the reading code
 * computes one (documented in the text, e.g. "(x_min + x_max)/2");
 * "required" / "-" (optional, none).
 * Papers: RKDG = rkdg-savage-hutter-1d.md, KIN = kinetic-scheme-savage-hutter-1d.md.
 */
#ifndef GRANFLOW1D_KEYS_H
#define GRANFLOW1D_KEYS_H

typedef struct gf1d_key {
    const char *section, *key, *type, *deflt;
    double lo, hi;          /* number, integer: the allowed closed range */
    const char *allowed;    /* choice: "a | b"; others: NULL (from lo, hi) */
    const char *unit, *applies, *description;
} gf1d_key;

#define ANY -1e300, 1e300
#define POS 1e-300, 1e300   /* > 0 */
#define NONNEG 0.0, 1e300   /* >= 0 */
#define NORANGE 0.0, 0.0

static const gf1d_key gf1d_keys[] = {
    /* [model] */
    {"model", "epsilon", "number", "1", POS, NULL, "", "",
     "aspect ratio H/L of the Savage-Hutter scaling: beta = epsilon K cos(zeta) (RKDG eq. 2); g for dimensional runs"},
    {"model", "g", "number", "1", NONNEG, NULL, "", "", "gravity scale of the source terms: 1 (dimensionless) or 9.81"},
    {"model", "chi", "number", "1", ANY, NULL, "", "", "curvature factor chi of the basal pressure (RKDG eq. 2)"},
    {"model", "rho", "number", "1", 1e-6, 1e6, NULL, "kg/m3", "",
     "flow density: basal pressure p_b = rho h (g cos zeta + chi kappa u^2), used by mu_i's inertial number"},
    {"model", "earth_pressure", "choice", "isotropic", NORANGE, "isotropic | savageHutter", "", "",
     "earth-pressure coefficient K: 1, or K_act/K_pass from phi and delta (RKDG eq. 4)"},
    {"model", "phi", "number", "-", 0.0, 90.0, NULL, "deg", "savageHutter", "internal friction angle"},
    {"model", "delta", "number", "-", 0.0, 90.0, NULL, "deg", "savageHutter, coulomb",
     "bed friction angle (coulomb: mu = tan(delta) unless [friction] mu is given)"},
    {"model", "friction", "name", "none", NORANGE, NULL, "", "",
     "basal friction law of libgranflow; its coefficients in [friction]"},
    /* [topography] */
    {"topography", "type", "choice", "flat", NORANGE, "flat | chute | tabulated", "", "",
     "flat: constant inclination; chute: zeta0 up to x1, linear to zeta1 at x2 (FA eq. 74); tabulated: a CSV"},
    {"topography", "zeta", "number", "0", -89.9, 89.9, NULL, "deg", "flat", "inclination of the bed"},
    {"topography", "zeta0", "number", "required", -89.9, 89.9, NULL, "deg", "chute", "inclination up to x1"},
    {"topography", "zeta1", "number", "0", -89.9, 89.9, NULL, "deg", "chute", "inclination from x2 on"},
    {"topography", "x1", "number", "17.5", ANY, NULL, "", "chute", "start of the transition"},
    {"topography", "x2", "number", "21.5", ANY, NULL, "", "chute", "end of the transition"},
    {"topography", "file", "string", "required", NORANGE, NULL, "", "tabulated",
     "CSV with columns x, zeta (deg), x increasing (cubic spline)"},
    /* [domain] */
    {"domain", "x_min", "number", "0", ANY, NULL, "", "", "left end of the domain"},
    {"domain", "x_max", "number", "30", ANY, NULL, "", "", "right end of the domain"},
    {"domain", "cells", "integer", "256", 4, 100000000, NULL, "", "", "number of cells"},
    {"domain", "bc_left", "choice", "transmissive", NORANGE, "transmissive | wall | periodic", "", "",
     "boundary condition at x_min"},
    {"domain", "bc_right", "choice", "transmissive", NORANGE, "transmissive | wall | periodic", "", "",
     "boundary condition at x_max"},
    /* [initial] */
    {"initial", "shape", "choice", "dam", NORANGE, "dam | box | semicircle | parabola | sinusoid | file | cap", "",
     "", "initial profile (sinusoid: KIN section 4, fifth test)"},
    {"initial", "x0", "number", "(x_min + x_max)/2", ANY, NULL, "", "dam, semicircle, parabola, cap",
     "position of the dam or centre"},
    {"initial", "h_left", "number", "1", NONNEG, NULL, "", "dam", "depth left of x0"},
    {"initial", "h_right", "number", "0", NONNEG, NULL, "", "dam", "depth right of x0"},
    {"initial", "u_left", "number", "0", ANY, NULL, "", "dam", "velocity left of x0"},
    {"initial", "u_right", "number", "0", ANY, NULL, "", "dam", "velocity right of x0"},
    {"initial", "x1", "number", "x_min", ANY, NULL, "", "box", "left end of the box"},
    {"initial", "x2", "number", "x_max", ANY, NULL, "", "box", "right end of the box"},
    {"initial", "h_in", "number", "1", NONNEG, NULL, "", "box", "depth inside the box"},
    {"initial", "h_out", "number", "0", NONNEG, NULL, "", "box", "depth outside the box"},
    {"initial", "radius", "number", "1", NONNEG, NULL, "", "semicircle, cap", "radius"},
    {"initial", "K", "number", "1", NONNEG, NULL, "", "parabola", "h = max(K/10, K - l (x - x0)^2)"},
    {"initial", "l", "number", "4", NONNEG, NULL, "", "parabola", "curvature of the parabola"},
    {"initial", "depth", "number", "0", ANY, NULL, "", "cap",
     "h = max(0, sqrt(r^2 - (x - x0)^2) - depth): a sphere's or cylinder's cap"},
    {"initial", "file", "string", "required", NORANGE, NULL, "", "file", "CSV with columns x, h, u (at least 2 rows)"},
    /* [solver] */
    {"solver", "method", "name", "rkdg", NORANGE, NULL, "", "", "rkdg (RKDG paper) or kinetic (KIN paper)"},
    {"solver", "degree", "integer", "2", 0, 2, NULL, "", "rkdg", "polynomial degree of the DG space"},
    {"solver", "scheme", "integer", "3", 1, 3, NULL, "", "kinetic", "kinetic scheme 1, 2 or 3 (the coupled one)"},
    {"solver", "kinetic_order", "integer", "1", 1, 2, NULL, "", "kinetic",
     "2: reconstruction and Heun (schemes 1 and 3)"},
    {"solver", "cfl", "number", "0", 0.0, 1.0, NULL, "", "", "Courant number; 0: the scheme's default"},
    {"solver", "dt", "number", "0", NONNEG, NULL, "", "", "> 0: fixed time step (rejected if it breaks the CFL bound)"},
    {"solver", "limiter", "name", "moment", NORANGE, NULL, "", "rkdg",
     "moment (Krivodonova), minmod (RKDG eq. 13 with gamma) or none"},
    {"solver", "velocity_limiter", "choice", "on", NORANGE, "off | on", "", "rkdg", "limit the velocity too"},
    {"solver", "gamma", "number", "0.5", 1e-12, 1.0, NULL, "", "rkdg", "gamma of the minmod limiter (RKDG eq. 13)"},
    {"solver", "tvb_m", "number", "0 for minmod, 1 for moment", NONNEG, NULL, "", "rkdg", "TVB constant M"},
    {"solver", "h_eps", "number", "1e-10", 1e-300, 1.0, NULL, "", "", "dry threshold"},
    {"solver", "h_semi", "number", "1e-6", 1e-300, 1.0, NULL, "", "", "semi-wet threshold (RKDG wet/semi-wet/dry)"},
    {"solver", "startup_levels", "integer", "0", 0, 5, NULL, "", "",
     "the first phase on grids 2^L..2 times finer (discontinuous initial data)"},
    {"solver", "moving_mesh", "choice", "off", NORANGE, "off | on", "", "rkdg",
     "front tracking: the cells span the wet interval, the dry-front nodes move with the fronts"},
    {"solver", "riemann_start", "number", "0", NONNEG, NULL, "", "",
     "t_s > 0: a uniform dam on a dry plane starts at t_s from its exact solution"},
    /* [output] */
    {"output", "times", "list", "required", NORANGE, NULL, "", "", "output times, increasing (space or comma separated)"},
    {"output", "dir", "string", ".", NORANGE, NULL, "", "", "folder of the output files"},
    {"output", "name", "string", "case file stem", NORANGE, NULL, "", "", "stem of the output files"},
    {"output", "plot", "choice", "no", NORANGE, "no | yes", "", "", "draw NAME.png with gnuplot"},
    {"output", "exact", "choice", "no", NORANGE, "no | riemann | dressler", "", "",
     "exact columns: riemann for a dam, dressler for a dam on a dry bed with chezy friction"},
    {"output", "front_h", "number", "1e-3", NONNEG, NULL, "", "", "depth that defines the front and tail"},
    {"output", "every", "number", "0", NONNEG, NULL, "", "", "> 0: a summary line every this much time"},
};

#undef ANY
#undef POS
#undef NONNEG
#undef NORANGE

#endif
