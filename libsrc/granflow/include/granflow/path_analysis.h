/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * granflow — path analysis of peak rasters (libgranflowTerrain): the
 * path-following (s, l) coordinates, along-path profiles, runout, the MMA/AMA
 * indicators and the comparison of a run with a reference run.
 *
 * Model reference: doc/theory/hazard-analysis.md, sections 1-3 (after
 * AvaFrame's ana3AIMEC, Fischer 2013, NHESS 13, 1655).  The analysis works
 * on rasters (gf_raster, any format GDAL reads), so it reads any tool's peak
 * fields, not only granflow's; gf_path_analysis_run is the whole analysis with
 * its files, which the program gfPathAnalysis and faGranularFlowFoam
 * (controlDict pathAnalysis) call.
 *
 * Conventions (section 1).  The path is a polyline drawn from the release
 * down through the runout.  It is resampled at one point per cell size h of
 * the DEM: s_i = i h, i = 0 .. ns-1 (s_{ns-1} <= L, the path's horizontal
 * length; the last piece shorter than h is dropped), s the horizontal (x-y)
 * distance along the path from its first point.  Each point carries a
 * cross-section perpendicular to the path, along the bisector of the normals
 * of the two adjacent resampled segments (the one segment's normal at the
 * ends), sampled at h: l_j = (j - (nl-1)/2) h, j = 0 .. nl-1, nl = 2
 * floor(w / (2h)) + 1, l > 0 on the left of the path looking down it, w the
 * domain width (domainWidth, AvaFrame's default 600 m).  A grid point (i, j)
 * stands for the cell around it; its area is |dX/di x dX/dj| (centred
 * differences of the grid points, one-sided at the edges), h^2 on a straight
 * path and h (h - l dtheta) on a bend of angle dtheta per point.  Where the
 * cross-sections of a bend overlap (radius below w/2) cells are counted twice,
 * as in AvaFrame.
 *
 * Fields on the (s, l) grid: bilinear interpolation between pixel centres;
 * NAN outside the raster's pixel centres or where a pixel with a non-zero
 * weight is NODATA.  NAN counts as "not reached" and is left out of maxima and
 * means.  Each raster is sampled with its own georeferencing, so rasters on
 * different grids (another origin or cell size than the DEM's or each
 * other's, e.g. AvaFrame's remeshed 5 m rasters) are compared on the one
 * (s, l) grid, as AvaFrame's AIMEC does.
 */
#ifndef GRANFLOW_PATH_ANALYSIS_H
#define GRANFLOW_PATH_ANALYSIS_H

#include <stddef.h>

#include "granflow/status.h"
#include "granflow/terrain.h"

#ifdef __cplusplus
extern "C" {
#endif

/** The path-following grid (section 1). Grid arrays are
 *  [ns nl], index i nl + j (i along the path, j across). */
typedef struct gf_path_grid {
    size_t ns, nl;        /**< points along the path, across it */
    double h;             /**< step along and across [m]: the DEM's cell size */
    double width;         /**< domain width w [m] */
    double length;        /**< horizontal length of the given polyline [m] */
    int reversed;         /**< 1: the line was given from bottom to top and was turned round */
    double *s;            /**< [ns] horizontal distance from the path's first point [m] */
    double *l;            /**< [nl] distance across, > 0 on the left looking down the path [m] */
    double *xp, *yp, *zp; /**< [ns] path points and the DEM (bilinear) under them */
    double *nx, *ny;      /**< [ns] unit cross-section direction (towards l > 0) */
    double *x, *y;        /**< [ns nl] grid points */
    double *area;         /**< [ns nl] cell areas [m2] */
} gf_path_grid;

/** Build the (s, l) grid of a path (n >= 2 points, x y interleaved) on dem
 *  (section 1): cell size h = the DEM's, width w > 0 (at least one h).  A
 *  path whose last point is higher on the DEM than its first is turned round
 *  (reversed = 1), as AvaFrame does.  Refused (GF_EDOM, the reason and the
 *  point in the message): fewer than 2 distinct points, a non-finite
 *  coordinate, a width <= 0 or not finite, a path shorter than 2 h, a
 *  resampled path point outside the DEM's pixel centres or on NODATA (the
 *  path must lie inside the DEM, section 1). */
gf_status gf_path_grid_make(const gf_raster *dem, size_t n, const double *xy, double width,
                            gf_path_grid *g);
void gf_path_grid_free(gf_path_grid *g);

/** Bilinear value of raster r at the georeferenced point (x, y): NAN outside
 *  the square of pixel centres or when a pixel with a non-zero weight is
 *  NODATA (section 1). */
double gf_raster_bilinear(const gf_raster *r, double x, double y);

/** Does raster r cover the point (x, y): inside the square of its pixel
 *  centres (to 1e-9 of a cell), where gf_raster_bilinear interpolates?  1
 *  yes, 0 no (NODATA pixels count as covered). */
int gf_raster_covers(const gf_raster *r, double x, double y);

/** Do rasters a and b lie on one grid (size, origin and cell size to 1e-6 of
 *  a cell)?  1 yes, 0 no. */
int gf_raster_same_grid(const gf_raster *a, const gf_raster *b);

/** Field r on the grid (section 1): out[ns nl], bilinear interpolation of r
 *  at the grid points with r's own georeferencing (r need not lie on the
 *  DEM's grid or on another raster's), NAN outside r (gf_raster_covers). */
void gf_path_sample(const gf_path_grid *g, const gf_raster *r, double *out);

/** The part of the grid a raster does not cover (gf_raster_covers): the
 *  grid points outside its pixel centres, there NAN ("not reached") after
 *  gf_path_sample.  Only the grid points that raster `within` covers count
 *  (the DEM: the (s, l) grid reaches beyond a DEM narrower than the domain
 *  width); NULL: all of them. */
typedef struct gf_path_cover {
    size_t n_grid;                      /**< grid points counted (inside `within`) */
    size_t n_out;                       /**< of these, the points r does not cover */
    size_t n_path_out;                  /**< path points (xp, yp; l = 0) r does not cover */
    double path_s_min, path_s_max;      /**< their s range [m] (NAN when n_path_out = 0) */
    double area_out;                    /**< the n_out points' cell area [m2] */
    double s_min, s_max, l_min, l_max;  /**< their extent in s and l [m] (NAN when n_out = 0) */
} gf_path_cover;

void gf_path_coverage(const gf_path_grid *g, const gf_raster *r, const gf_raster *within,
                      gf_path_cover *c);

/** Along-path profiles of a field on the grid (section 2): cross_max[i] =
 *  max over l, cross_mean[i] = mean over l of the values that are not NAN
 *  (NAN when a whole section is NAN). */
void gf_path_profiles(const gf_path_grid *g, const double *a, double *cross_max,
                      double *cross_mean);

/** Runout of one field for a threshold (section 2). */
typedef struct gf_runout {
    size_t i_start, i_runout; /**< path indices of s_start and s_runout */
    double s_start;           /**< first s with A_max(s) > threshold [m] */
    double s_runout;          /**< last s with A_max(s) > threshold [m] (sRunout) */
    double x_runout, y_runout;/**< the grid point at s_runout where A is largest (xRunout, yRunout) */
    double l_runout;          /**< its l [m] */
    double z_start, z_runout; /**< z(s_start), z(s_runout) on the path (zRelease, zRunout) [m] */
    double delta_sxy;         /**< s_runout - s_start (deltaSXY) [m] */
    double delta_z;           /**< z_start - z_runout (deltaZ) [m] */
    double angle;             /**< runout (travel) angle atan(deltaZ / deltaSXY) [deg] (runoutAngle) */
} gf_runout;

/** Runout of field a (on g) for threshold: s_start, s_runout from its
 *  cross-section maximum (section 2).  Refused (GF_EDOM): no cross-section
 *  maximum above the threshold (the message gives the field's largest
 *  value), a threshold that is not finite. */
gf_status gf_path_runout(const gf_path_grid *g, const double *a, double threshold, gf_runout *r);

/** Indicators of a field (section 2): MMA = max over s of A_max(s)
 *  (AvaFrame's maxAcrossMax, e.g. MMPPR = maxpprCrossMax) and AMA = mean of
 *  A_max(s) over s_start <= s <= s_runout (meanAcrossMax), NAN values left
 *  out. */
void gf_path_indicators(const gf_path_grid *g, const double *cross_max, const gf_runout *r,
                        double *mma, double *ama);

/** The beta point (section 2, runout area): the first path point i at or
 *  below i_from (the split point snapped to the path, 0 without one) where
 *  the path's slope angle atan(-dz/ds) (centred differences of z(s)) is below
 *  angle_deg and stays below it for every point within ds_min downslope
 *  (AvaFrame: startOfRunoutAreaAngle 10 deg, dsMin 30 m).  Refused
 *  (GF_EDOM): no such point. */
gf_status gf_path_beta_point(const gf_path_grid *g, size_t i_from, double angle_deg,
                             double ds_min, size_t *i_beta);

/** Index of the path point nearest to (x, y) and its distance [m]. */
size_t gf_path_snap(const gf_path_grid *g, double x, double y, double *dist);

/** Areas of the comparison of run a with reference ref (section 3) over
 *  the runout area (grid rows i >= i_from), "reached" meaning > threshold
 *  (NAN is not reached): TP both, FP only a, FN only ref, TN neither [m2,
 *  sums of cell areas]; a_ref = TP + FN. */
typedef struct gf_path_areas {
    double tp, fp, fn, tn, a_ref;
} gf_path_areas;

void gf_path_compare(const gf_path_grid *g, const double *a, const double *ref, double threshold,
                     size_t i_from, gf_path_areas *ar);

/** Classification of each cell for the comparison map: 0 outside the
 *  runout area or NAN in both, 1 TP, 2 FP, 3 FN, 4 TN (out[ns nl]). */
void gf_path_compare_map(const gf_path_grid *g, const double *a, const double *ref,
                         double threshold, size_t i_from, unsigned char *out);

/** Read a path: the first line string of the first layer of a vector file
 *  (OGR: shapefile, GeoJSON; a multi line string of one part is that part),
 *  x y interleaved into *xy (malloc'ed, n points).  Refused (GF_EIO,
 *  GF_EDOM) naming the file: a file OGR cannot open, no feature, a geometry
 *  that is not a line, fewer than 2 points, a non-finite coordinate. */
gf_status gf_path_read(const char *path, size_t *n, double **xy);

/** Where a point (x, y) lies relative to a path of n >= 2 points (xy
 *  interleaved): the foot of the perpendicular on the nearest segment gives
 *  *s, the horizontal distance along the path from its first point to the
 *  foot, and *l, the signed distance from the path, positive to the left of
 *  the direction of travel (section 1's l).  Ties between segments go to the
 *  first.  Used to decompose a terrain case along its path (gfDecompose). */
void gf_path_locate(size_t n, const double *xy, double x, double y, double *s, double *l);

/** Read a point: the first point of the first layer of a vector file
 *  (OGR).  Refused like gf_path_read, and for a geometry that is not a point. */
gf_status gf_point_read(const char *path, double *x, double *y);

/*---------------------------------------------------------- the whole analysis --*/

/** An option of the whole path analysis (gf_path_analysis_run): gfPathAnalysis's
 *  command-line options, the rows of its -help and -keywords (doc/keywords.md). */
typedef struct gf_path_analysis_option {
    const char *key;     /**< "-dem", "-path", ... */
    const char *type;    /**< file, folder, choice, number, string */
    const char *dflt;    /**< "required", "-" (optional, none) or the default */
    const char *allowed; /**< allowed values ("" any) */
    const char *unit;
    const char *what;    /**< one-line description */
} gf_path_analysis_option;

/** The options (*n of them), in gfPathAnalysis's order. */
const gf_path_analysis_option *gf_path_analysis_options(size_t *n);

/** Where gf_path_analysis_run reads relative file names and sends its
 *  messages (every member may be 0/NULL). */
typedef struct gf_path_analysis_io {
    const char *base; /**< folder of relative file names (NULL: the working directory); the
                           messages and outputs name the files as given */
    void (*line)(void *ctx, const char *text);    /**< each line of the log (the summary, "wrote ..."), no newline */
    void (*warning)(void *ctx, const char *text); /**< a warning (gnuplot failed on a plot) */
    void (*error)(void *ctx, const char *text);   /**< the whole message of a failure, before the return */
    void *ctx;
} gf_path_analysis_io;

/** The whole path analysis of gfPathAnalysis (doc/guide/path-analysis.md):
 *  the options as n pairs kv[2 i] (the key, "-dem", ...) and kv[2 i + 1] (its
 *  value), checked; the DEM, the path (and split point) and the rasters read;
 *  the (s, l) grid, the runouts, indicators and the comparison with a
 *  reference run (the functions above); pathAnalysis.csv, pathProfile.csv,
 *  pathGrid.csv, summary.dat and (-plots yes) the gnuplot plots written into
 *  -out (made when missing).  The summary's lines and "wrote ..." go to
 *  io->line.  Any failure (an option missing or out of range, a file that
 *  cannot be read or written, a raster that does not cover the path, nothing
 *  above the threshold, ...) returns its status with the message of
 *  gfPathAnalysis (gf_error_detail, and whole to io->error); nothing exits.
 *  Reentrant apart from GDAL's own state (one call per thread at a time). */
gf_status gf_path_analysis_run(size_t n, const char *const *kv, const gf_path_analysis_io *io);

#ifdef __cplusplus
}
#endif

#endif
