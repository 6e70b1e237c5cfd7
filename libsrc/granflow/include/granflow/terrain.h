/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * granflow — real terrain: digital elevation models, release polygons and
 * georeferenced rasters, through GDAL/OGR (libgranflowTerrain).
 *
 * This is the only part of granflow that depends on GDAL; it is a library of
 * its own (libgranflowTerrain) so that libgranflow stays GSL-only.  Nothing
 * here parses a raster or a shapefile by hand: GDAL reads the DEM (any raster
 * format GDAL knows: ESRI ASCII grid, GeoTIFF, ...) and writes the rasters,
 * OGR reads the polygons (shapefile, GeoJSON, ...).
 *
 * Grids.  A DEM value is the elevation at its pixel centre (GDAL's pixel
 * corner geotransform plus half a pixel); the area mesh's nodes are the
 * centres of every k-th pixel (coarsening by k), and a mesh face is the quad
 * between four neighbouring nodes, all four valid (not NODATA) and, when a
 * crop is given, with its centre inside the crop.  Node (I, J) is pixel
 * (column c0 + k I, row r0 + k J); rows run as in the raster (north to south
 * for a north-up DEM).
 *
 * Errors name the file and what is wrong (gf_error_detail()).
 */
#ifndef GRANFLOW_TERRAIN_H
#define GRANFLOW_TERRAIN_H

#include <stddef.h>

#include "granflow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A single-band raster on a north-up grid with square pixels. */
typedef struct gf_raster {
    int nx, ny;       /* columns, rows */
    double gt[6];     /* GDAL geotransform: pixel corner (col, row) -> (gt0 + col gt1, gt3 + row gt5) */
    double nodata;    /* NODATA value of the source (-9999 when it had none) */
    char *wkt;        /* coordinate reference system as WKT ("" when the source had none) */
    double *z;        /* nx ny values, row-major; NAN where NODATA */
    size_t n_valid;   /* values that are not NODATA */
} gf_raster;

/* Read band 1 of a raster through GDAL.  Refused with GF_EIO/GF_EDOM and the
 * file's name: a file GDAL cannot open, no georeferencing (no geotransform),
 * a rotated grid, pixels that are not square (mixed cell sizes), only NODATA,
 * non-finite values. */
gf_status gf_raster_read(const char *path, gf_raster *r);
void gf_raster_free(gf_raster *r);

/* Georeferenced centre of pixel (col, row) (fractional indices allowed). */
void gf_raster_centre(const gf_raster *r, double col, double row, double *x, double *y);

/* Write values [nx ny] (NAN -> the grid's NODATA) on grid's size,
 * geotransform and CRS.  driver: "AAIGrid" (ESRI ASCII grid, 9 significant
 * digits, with a .prj when there is a CRS; GDAL reads it back as float32) or
 * "GTiff" (float64, deflate-compressed). */
gf_status gf_raster_write(const char *path, const char *driver, const gf_raster *grid,
                          const double *values);

/* Release (or crop) polygons: every polygon of every feature of the first
 * layer (a multipolygon gives its parts), exterior ring and holes, each with
 * a value. */
typedef struct gf_polygons {
    size_t n;          /* polygons */
    size_t *ring0;     /* [n+1] first ring of each polygon (ring ring0[p] is the exterior) */
    size_t *pt0;       /* [rings+1] first point of each ring */
    double *xy;        /* points, x y interleaved, rings closed or not */
    double *value;     /* [n] the attribute's (or the given) value */
    double *box;       /* [4n] xmin ymin xmax ymax of each polygon */
    char *wkt;         /* CRS of the layer ("" when none) */
} gf_polygons;

/* Read the polygons of the first layer of a vector file (shapefile,
 * GeoJSON, ... through OGR).  attribute: the numeric field giving each
 * polygon's value (refused when missing, with the fields there are, or when
 * a value is not finite or negative), or NULL to give every polygon
 * 'value'.  Refused: a file OGR cannot open, no polygon, a geometry that is
 * not a polygon. */
gf_status gf_polygons_read(const char *path, const char *attribute, double value,
                           gf_polygons *p);
void gf_polygons_free(gf_polygons *p);

/* Index of the last polygon containing (x, y) (holes excluded; a later
 * polygon overrides an earlier one), -1 when none (even-odd ray casting). */
long gf_polygons_locate(const gf_polygons *p, double x, double y);

/* Plane area of polygon k (exterior minus holes, shoelace formula). */
double gf_polygons_area(const gf_polygons *p, size_t k);

/* Do two CRS (WKT) describe the same coordinate system (GDAL's OSRIsSame,
 * or the same PROJ string apart from a datum shift +towgs84: an EPSG
 * definition and the ESRI .prj of the same projection agree)?  1 yes, 0 no,
 * -1 when either is empty or not understood. */
int gf_crs_same(const char *wkt_a, const char *wkt_b);

/* The checks of a case's inputs before anything runs (gfCheckInputs): the
 * CRS of a vector file, a numeric attribute, extents that overlap.  The
 * readers above check the rest (geometry types, values). */

/* The CRS of the first layer of a vector file (OGR) as WKT in *wkt
 * (malloc'd, free() it; "" when the layer has none).  Refused (GF_EIO,
 * GF_EDOM) naming the file: a file OGR cannot open, no layer. */
gf_status gf_vector_crs(const char *path, char **wkt);

/* Is the attribute (field) `field` of the first layer of a vector file
 * numeric (integer or real), as gf_polygons_read needs it?  need: what the
 * number is, for the message ("a number in metres"; NULL: "a number").
 * Refused naming the file and the field: GF_ENOTFOUND no such field (the
 * message lists the numeric fields there are), GF_EDOM a field of another
 * type, named ("field 'thickness' of rel.shp is a text field (String); a
 * number in metres is needed"); GF_EIO a file OGR cannot open. */
gf_status gf_vector_field_numeric(const char *path, const char *field, const char *need);

/* The extent of raster r's pixels (their outer edges): box = xmin ymin
 * xmax ymax. */
void gf_raster_extent(const gf_raster *r, double box[4]);

/* Do the boxes a and b (xmin ymin xmax ymax each) overlap, edges included?
 * 1 yes, 0 no (also when a coordinate is NAN). */
int gf_box_overlap(const double a[4], const double b[4]);

/* The node grid of an area mesh on a DEM (see the top of this file). */
typedef struct gf_terrain_grid {
    int c0, r0, k;        /* pixel of node (0, 0), coarsening */
    int ni, nj;           /* nodes along columns and rows */
    unsigned char *quad;  /* [(ni-1)(nj-1)], index I + (ni-1) J: 1 = a face of the mesh */
    size_t n_quads;       /* faces */
} gf_terrain_grid;

/* The mesh's grid on dem: coarsening k >= 1, optional crop box (xmin ymin
 * xmax ymax, georeferenced; NULL for none) and crop polygons (NULL for
 * none).  Refused when no face remains. */
gf_status gf_terrain_grid_make(const gf_raster *dem, int k, const double *box,
                               const gf_polygons *crop, gf_terrain_grid *g);
void gf_terrain_grid_free(gf_terrain_grid *g);

/* Georeferenced position (x, y, z) of node (I, J). */
void gf_terrain_node(const gf_raster *dem, const gf_terrain_grid *g, int I, int J, double xyz[3]);

/* Values at the faces of a mesh made by gf_terrain_grid_make (georeferenced
 * face centres xy [2n], areas [n], values [n]) onto every pixel of the DEM:
 * a node takes the area-weighted mean of its faces, a pixel between nodes
 * (k > 1) the bilinear interpolation in its face's quad, and pixels outside
 * the mesh NAN.  A face centre outside the grid is GF_EDOM naming it. */
gf_status gf_terrain_to_raster(const gf_raster *dem, const gf_terrain_grid *g, size_t n,
                               const double *xy, const double *area, const double *val,
                               double *out);

/* Outline of the pixels with values >= threshold (GDAL's polygonize):
 * GeoJSON polygons with their area [m2, in the grid's CRS]; returns the
 * affected area (pixels x pixel area) in *area when not NULL.  GeoJSON is
 * WGS 84 longitude/latitude (RFC 7946): with a CRS the polygons are
 * reprojected, without one they keep the grid's coordinates. */
gf_status gf_raster_outline(const char *path, const gf_raster *grid, const double *values,
                            double threshold, double *area);

/* The outlines of a class raster as a new GeoPackage (the file replaced),
 * one layer `layer` in the grid's CRS (none when the grid has none): each
 * 4-connected group of pixels of class k (cls a whole number 1..nclass;
 * 0, NAN and other values not drawn) is a polygon (holes kept) with fields
 * class (k), lower_UNIT = limits[k-1], upper_UNIT = limits[k] (empty for
 * the last class; limits holds nclass values, increasing) and area_m2 (its
 * area in the grid's CRS), UNIT the unit given (e.g. kPa); the number of
 * polygons in *n (may be NULL).  Used for the pressure zones of a hazard
 * indication map (gfRegionalMap).  Refused (GF_EINVAL): nclass 0, limits
 * not increasing or not finite, a unit or layer name that is not a plain
 * word (letters, digits, _); GF_EIO naming the file when GDAL cannot write
 * it. */
gf_status gf_class_outlines(const char *path, const char *layer, const gf_raster *grid, const double *cls,
                            size_t nclass, const double *limits, const char *unit, size_t *n);

/* A line (n >= 2 points, georeferenced x y z interleaved) as a GeoJSON
 * LineString feature, with a name and the numeric properties given
 * (keys[k] = values[k], nprops of them); reprojected to WGS 84 (RFC 7946)
 * from the CRS wkt, or as given when wkt is "". */
gf_status gf_line_geojson(const char *path, const char *wkt, size_t n, const double *xyz, const char *name,
                          size_t nprops, const char *const *keys, const double *values);

/* Dams (doc/theory/mass-exchange.md, section 3 "Dams"): a crown line, a
 * polyline of n >= 2 points (x y z interleaved, z the crown's absolute
 * elevation, as AvaFrame's Inputs/DAM lines carry it), and a wall slope
 * beta from the horizontal in (0, 90) degrees.  The dam surface at a point
 * at horizontal distance d from the line is z_c - tan(beta) d, z_c the
 * crown elevation (linear along the segment) at the nearest point of the
 * line; the DEM becomes the larger of the ground and that surface ("the DEM
 * raised to the crown height along it and falling off at slope beta on both
 * sides (the larger of the original and the dam surface)"), so the ends of
 * the line are rounded.  NODATA pixels stay NODATA. */
typedef struct gf_dam {
    size_t n;          /* points of the crown line */
    double *xyz;       /* [3n] x y z interleaved, z absolute elevation [m] */
    double slope;      /* wall slope beta [deg] */
    char *wkt;         /* CRS of the layer ("" when none) */
} gf_dam;

/* Read a dam from the first feature of the first layer of a vector file
 * (OGR: shapefile, GeoJSON): a line string with z (a multi line string
 * with one part is taken as that part), the wall slope from the numeric
 * attribute slope_attribute (AvaFrame: "slope") when the feature has it,
 * else slope_default (NAN: none).  Refused (GF_EIO, GF_EDOM), naming the
 * file: a file OGR cannot open, no feature, a geometry that is not a line,
 * a 2D line or a point without a finite z (the crown needs its height),
 * fewer than 2 points, no slope, a slope outside (0, 90) degrees. */
gf_status gf_dam_read(const char *path, const char *slope_attribute, double slope_default,
                      gf_dam *d);
void gf_dam_free(gf_dam *d);

/* Burn the dam (n points xyz, slope in degrees) into dem in place (see
 * gf_dam above).  n_raised (may be NULL): pixels raised; max_rise (may be
 * NULL): the largest rise [m].  Refused (GF_EDOM; the DEM untouched): fewer
 * than 2 points, a non-finite coordinate (a line without heights), a slope
 * outside (0, 90) degrees, a line that does not touch the DEM's extent. */
gf_status gf_dam_burn(gf_raster *dem, size_t n, const double *xyz, double slope,
                      size_t *n_raised, double *max_rise);

/* Probability map of an ensemble (doc/theory/hazard-analysis.md, section
 * 4): per pixel, the fraction of the n member rasters (paths; any raster
 * GDAL reads, on one grid) whose value exceeds threshold (strictly, e.g.
 * ppr > 1 kPa), 0..1.  A member's NODATA pixel counts as not reached; a
 * pixel NODATA in every member is NODATA (NAN).  On success out is the
 * first member's grid and CRS with z the probability (gf_raster_free it).
 * Refused, naming the file: a raster GDAL cannot read, members on different
 * grids (size, origin or pixel size), a threshold that is not finite. */
gf_status gf_probability_map(size_t n, const char *const *paths, double threshold, gf_raster *out);

/* Contour lines of values on grid at the nlev levels (GDAL's contour
 * generator; NAN pixels are left out): a GeoJSON file of line strings with
 * their level (WGS 84 as RFC 7946 asks when the grid has a CRS; NULL: not
 * written) and a plain text file of "x y level" rows, one block per line
 * (the grid's coordinates, for gnuplot; NULL: not written). */
gf_status gf_raster_contours(const char *geojson, const char *xy_path, const gf_raster *grid,
                             const double *values, size_t nlev, const double *levels);

#ifdef __cplusplus
}
#endif

#endif
