/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * granflow — regional hazard indication (issue 52, doc/theory/regional.md):
 * the potential release areas (PRAs) of a whole DEM, their scenario release
 * depths, an alpha-beta screening of each one's runout, and the merge of the
 * peak rasters of many releases.
 *
 * Grids.  Everything works on a raster in memory, the gf_raster of
 * granflow/terrain.h (values row-major, NAN where NODATA, GDAL's north-up
 * geotransform with square pixels), so the rasters of any tool can be read
 * with gf_raster_read and the results written with gf_raster_write.  The
 * raster numerics (slope, roughness, curvature, delineation, the depth
 * formula, alpha-beta, the merge) are in libgranflow itself (GSL-only); the
 * two writers at the end (polygons, GDAL/OGR) are in libgranflowTerrain.
 *
 * Conventions.  Slope: Horn's (1981) third-order finite difference of the 3 x
 * 3 neighbourhood, in degrees from the horizontal.  Aspect: the direction the
 * slope faces (downslope), degrees clockwise from north (grid north, the
 * raster's +y), 0..360.  A cell on the raster's border or next to NODATA has
 * no 3 x 3 neighbourhood: its slope, aspect and curvature are NAN and it is
 * never part of a release area.  Areas are plane (map) areas in m^2.
 *
 * Errors name the parameter (or the file), its value and the allowed range
 * (gf_error_detail()).
 */
#ifndef GRANFLOW_REGIONAL_H
#define GRANFLOW_REGIONAL_H

#include <stddef.h>

#include "granflow/status.h"
#include "granflow/terrain.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- terrain derivatives -------------------------------------------- */

/* Slope [deg] and aspect [deg] of every cell of dem (Horn's method); either
 * output may be NULL.  Arrays of dem->nx * dem->ny.  Refused (GF_EINVAL): a
 * grid smaller than 3 x 3, a pixel size that is not finite and > 0. */
gf_status gf_slope_aspect(const gf_raster *dem, double *slope, double *aspect);

/* Vector ruggedness measure (Sappington, Longshore and Thompson 2007):
 * VRM = 1 - |sum of the unit surface normals| / N over a window of
 * window x window cells (odd, >= 3) centred on each cell, N the cells of
 * the window that have a normal; 0 for a plane, up to 1 for the roughest
 * terrain.  aspect_smooth (may be NULL): the aspect of the resultant normal,
 * the window's mean aspect [deg] (NAN on a flat window).  Refused: an even
 * window or one < 3 or larger than the grid. */
gf_status gf_vrm(const gf_raster *dem, int window, double *vrm, double *aspect_smooth);

/* Plan (horizontal) curvature [1/m] of every cell from the second-order
 * polynomial of the 3 x 3 neighbourhood (Zevenbergen and Thorne 1987; the
 * normal-section formula of Florinsky): positive on ridges and spurs (flow
 * diverges), negative in gullies (flow converges), NAN where the cell is
 * flat.  A cone of slope theta has sin(theta) / r at distance r from its
 * apex. */
gf_status gf_plan_curvature(const gf_raster *dem, double *curv);

/* Wind shelter index [deg] (Winstral, Elder and Davis 2002), in the sector
 * form of Veitinger et al. (2016): for each cell the largest elevation angle
 * atan((z_j - z_i) / d_ij) to the cells j within dmax [m] whose direction
 * lies within half_width_deg of where the wind comes from (wind_from_deg,
 * clockwise from north).  Positive: sheltered (higher terrain upwind, snow
 * is deposited), negative: exposed (snow is blown off).  NAN on NODATA and
 * where the sector holds no cell.  Refused: a direction outside [0, 360], a
 * half width outside (0, 180], dmax below the cell size or not finite. */
gf_status gf_wind_shelter(const gf_raster *dem, double wind_from_deg, double half_width_deg, double dmax,
                          double *sx);

/* ---- potential release areas ----------------------------------------- */

typedef struct gf_pra_params {
    double slope_min, slope_max; /* slope window [deg] (28, 60) */
    int roughness_window;        /* VRM window, cells (odd >= 3; 5) */
    double roughness_max;        /* largest VRM of a release cell (0.05); NAN: no criterion */
    double curvature_max;        /* largest |plan curvature| [1/m]; NAN: no criterion (default) */
    int aspect_sectors;          /* aspect classes splitting the areas (8: 45 deg each, centred on N) */
    double merge_sectors;        /* a small fragment merges into a neighbour at most this many sectors away (1) */
    double min_area;             /* smallest release area [m^2] (10000); smaller ones are dropped */
} gf_pra_params;

/* The defaults above. */
void gf_pra_params_default(gf_pra_params *p);

/* One release area. */
typedef struct gf_pra {
    int id;                 /* 1.. (its value in the label raster) */
    size_t cells;           /* cells of the area */
    double area_m2;         /* plane area */
    double slope_deg;       /* mean slope */
    double altitude_m;      /* mean altitude */
    double aspect_deg;      /* circular mean of the aspect (of the mean downslope direction) */
    double z_max;           /* highest cell's altitude */
    int top_col, top_row;   /* highest cell (where its thalweg starts) */
    double x, y;            /* centroid (georeferenced) */
} gf_pra;

typedef struct gf_pra_set {
    int nx, ny;
    int *label;   /* [nx ny] 0 outside every release area, else the id */
    size_t n;     /* release areas */
    gf_pra *pra;  /* [n], pra[k].id = k + 1, ordered by decreasing z_max */
} gf_pra_set;

/* Delineate the potential release areas of dem (doc/theory/regional.md,
 * section 1).  A cell is a candidate when it has a slope in
 * [slope_min, slope_max], a VRM <= roughness_max, |plan curvature| <=
 * curvature_max (when set) and is not excluded (excluded[c] != 0, e.g. a
 * forest mask; NULL for none).  Candidates are grouped into 4-connected
 * fragments of one aspect class (aspect_sectors classes of the window's
 * mean aspect), so that ridges and gullies, where the aspect turns, separate
 * areas; a fragment smaller than min_area merges into the neighbouring
 * fragment it shares the longest border with, when that one's class is at
 * most merge_sectors away (repeated until nothing merges); what is still
 * smaller than min_area is dropped.  Refused (GF_EDOM) naming the parameter
 * and its allowed range: slope window outside 0 < min < max <= 90, a
 * roughness window even or < 3, roughness_max outside [0, 1],
 * curvature_max <= 0, aspect_sectors outside [1, 36], min_area < 0 or not
 * finite.  *out is gf_pra_set_free'd by the caller (also after a failure). */
gf_status gf_pra_delineate(const gf_raster *dem, const unsigned char *excluded, const gf_pra_params *p,
                           gf_pra_set *out);
void gf_pra_set_free(gf_pra_set *s);

/* ---- scenario release depth (Salm, Burkard and Gubler 1990) ----------- */

/* The slope factor f(psi) = 0.291 / (sin psi - 0.202 cos psi), psi in
 * degrees (f(28 deg) = 1).  Refused (GF_EDOM, *f untouched) outside
 * [15, 90] degrees (the denominator vanishes at 11.4 deg). */
gf_status gf_salm_slope_factor(double psi_deg, double *f);

/* Release depth d0 = (d0star + gradient (z - z_ref)) f(psi) [m]: d0star the
 * reference depth (the 3-day snowfall increase) at z_ref [m], gradient its
 * change with altitude [m per m, e.g. 0.05 / 100].  Refused: d0star < 0 or
 * not finite, a non-finite gradient, z or z_ref, psi outside [15, 90], a
 * negative depth d0star + gradient (z - z_ref) (named, with the altitude). */
gf_status gf_release_depth(double d0star, double gradient, double z, double z_ref, double psi_deg,
                           double *d0);

/* ---- alpha-beta screening (Lied and Bakkehoi 1980) ------------------- */

typedef struct gf_alpha_beta_params {
    double k1, k2;        /* alpha = k1 beta + k2 [deg] (0.96, -1.4) */
    double sd;            /* standard deviation of alpha [deg] (2.3) */
    double beta_slope;    /* slope defining the beta point [deg] (10) */
    double ds_min;        /* the profile must stay below beta_slope over this horizontal length [m] (30) */
} gf_alpha_beta_params;

void gf_alpha_beta_params_default(gf_alpha_beta_params *p);

typedef struct gf_alpha_beta {
    double s_beta, z_beta;   /* the beta point (horizontal distance from the top, altitude) */
    double beta;             /* angle from the top to the beta point [deg] */
    double alpha;            /* k1 beta + k2 [deg] */
    double s_alpha[3];       /* runout of alpha, alpha - sd, alpha + sd: where the line
                                from the top at that angle meets the profile again;
                                NAN when the profile ends first */
    double z_alpha[3];
    size_t i_beta;           /* profile segment holding the beta point (s[i] <= s_beta <= s[i+1]) */
} gf_alpha_beta;

/* Alpha-beta on a profile of n >= 2 points: s [m] horizontal distance
 * along the thalweg from the top (strictly increasing), z [m].  The beta
 * point is the first point where the profile's slope falls below
 * beta_slope: the segment slopes atan(-dz/ds) are taken at the segments'
 * midpoints and the crossing is interpolated between them; a crossing is
 * accepted only when the mean slope over the following ds_min stays below
 * beta_slope (a short bench is not the runout zone).  Refused (GF_EDOM):
 * s not strictly increasing, a non-finite value, a profile that never
 * falls below beta_slope (named, with its length), parameters that are not
 * finite or k1 <= 0, sd < 0, beta_slope outside (0, 90). */
gf_status gf_alpha_beta_profile(size_t n, const double *s, const double *z, const gf_alpha_beta_params *p,
                                gf_alpha_beta *out);

/* The steepest-descent thalweg on dem from cell (col, row): D8, each step
 * to the neighbour of the steepest drop (drop / distance).  Where no
 * neighbour is lower (a pit or a flat of the DEM) the path goes on to the
 * lowest neighbour it has not visited as long as that stays within
 * max_climb [m] of the lowest point reached so far (a pit shallower than
 * max_climb is walked through, a level valley floor followed, ties keeping
 * the last step's direction; 0: strict D8, the path ends in the first pit),
 * and ends when it has gone max_flat [m] along the path without a new
 * lowest point (max_flat 0: at the first step that does not descend), at
 * the grid's border or NODATA.  On success *xyzs (malloc'd, free() it) holds *n points of x y z
 * s (s the horizontal distance from the start, strictly increasing).
 * Refused: a start outside the grid or on NODATA, max_climb or max_flat < 0
 * or not finite. */
gf_status gf_thalweg_d8(const gf_raster *dem, int col, int row, double max_climb, double max_flat, double **xyzs,
                       size_t *n);

/* ---- the clipped sub-domain of a release ------------------------------ */

/* The box of a release's sub-domain on dem, in pixels: box = col0 row0 col1
 * row1 (inclusive) of the n cells (indices row * nx + col; NODATA ones
 * skipped) and of the steepest-descent paths leaving them: from every cell
 * whose steepest lower neighbour is not a release cell (or that has none), the
 * walk of gf_thalweg_d8 (pits up to max_climb [m] walked through, level
 * ground followed for max_flat [m] without a new lowest point), ending also
 * where it meets an earlier path of the release that had as much of max_flat
 * left there (the box does not depend on the order of the cells).  The cost
 * is that of the release's cells and paths, not of the grid (no array of the
 * grid's size).  path_cells (may be NULL): the cells on the paths.  The
 * caller adds the buffer.  Refused (GF_EDOM): no valid cell, a cell outside
 * the grid, max_climb or max_flat < 0 or not finite; (GF_EINVAL) no DEM,
 * cells or box. */
gf_status gf_downslope_box(const gf_raster *dem, size_t n, const size_t *cells, double max_climb, double max_flat,
                           int box[4], size_t *path_cells);

/* ---- merge of many releases' peak rasters ----------------------------- */

/* Per cell c of ncell, over the m rasters fields[k] (NAN: not reached):
 * max[c] the largest value (NAN when every raster is NAN there), count[c]
 * how many rasters exceed threshold (strictly), who[c] the id ids[k] of the
 * raster holding the maximum (the first of equal ones; -1 where max is
 * NAN).  count and who may be NULL.  Refused: m < 1, a threshold that is not
 * finite. */
gf_status gf_merge_max(size_t m, size_t ncell, const double *const *fields, const long *ids, double threshold,
                       double *max, unsigned *count, long *who);

/* ---- writers (libgranflowTerrain, GDAL/OGR) -------------------------- */

/* The release areas of set on grid as polygons (GDAL's polygonize of the
 * labels, one feature per area, holes kept) in a vector file: driver
 * "GPKG" (GeoPackage) or "ESRI Shapefile", the grid's CRS, fields id,
 * area_m2, slope_deg, altitude_m, aspect_deg and, when d0 is given ([n],
 * NULL: not written), d0_m.  An existing file is replaced. */
gf_status gf_pra_write_polygons(const char *path, const char *driver, const gf_raster *grid,
                                const gf_pra_set *set, const double *d0);

/* A mask [nx ny] of grid's cells whose centre lies in one of the polygons
 * (1) or not (0), for the forest (resistance) areas. */
void gf_polygons_mask(const gf_polygons *p, const gf_raster *grid, unsigned char *mask);

#ifdef __cplusplus
}
#endif

#endif
