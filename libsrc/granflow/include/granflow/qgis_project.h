/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * granflow — a QGIS project ("layer set") of a command's results: the
 * GeoTIFFs and GeoPackage layers a command wrote, styled and grouped, in one
 * QGIS 3 project file (.qgs, XML) that a user opens in QGIS (3.22, Debian
 * bookworm's, and later 3.x) to see them all at once.  Written as text, so
 * the commands do not depend on QGIS; the elements are those QGIS 3.22
 * itself writes (QgsProject::write) and reads back, reduced to what it
 * needs.  tests/foam/qgisProject checks a project of every style with
 * PyQGIS: read, every layer valid, the renderers, the groups, a rendering.
 */
#ifndef GRANFLOW_QGIS_PROJECT_H
#define GRANFLOW_QGIS_PROJECT_H

#include <stddef.h>

#include "granflow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* How a layer is drawn.  Colours are "#rrggbb" strings. */
typedef enum {
    GF_QGIS_HILLSHADE,    /* raster: hillshade of band 1 (azimuth 315, altitude 45), grey */
    GF_QGIS_RAMP,         /* raster band 1: interpolated colour ramp colors[0..ncolor-1] spread from vmin to vmax; values below vmin and nodata transparent; legend labels "%.3g unit" */
    GF_QGIS_CLASSES,      /* raster band 1 integer classes 1..nclass: paletted, class k colour colors[k-1], label labels[k-1]; 0 and nodata not drawn */
    GF_QGIS_OUTLINE,      /* vector polygons: no fill, outline `color`, `width` mm, dashed if `dashed` */
    GF_QGIS_FILL_CLASSES, /* vector polygons categorized on integer field `field` with values 1..nclass: fill colors[k-1] at 50 % opacity, darker outline, labels[k-1] */
    GF_QGIS_LINE,         /* vector lines: `color`, `width` mm, dashed if `dashed` */
    GF_QGIS_POINT_KINDS   /* vector points categorized on string field `field`: values[k] drawn with colors[k], shapes[k] ("circle", "square", "triangle", "diamond"), labels[k], k < nclass */
} gf_qgis_style;

/* One layer of the project.  RAMP: values above vmax are drawn in the last
 * colour (not hidden).  POINT_KINDS: markers of `width` mm if width > 0,
 * else 3 mm.  OUTLINE, LINE: width <= 0 gives QGIS's default 0.26 mm; a
 * NULL color is #202020. */
typedef struct {
    const char *group;   /* legend group (groups appear in order of first use; NULL: top level) */
    const char *name;    /* the layer's legend name */
    const char *source;  /* the file, relative to the project file's folder, or absolute */
    const char *layer;   /* a vector layer inside the file (e.g. a GeoPackage layer name); NULL for a raster */
    gf_qgis_style style;
    int visible;         /* checked in the legend */
    double vmin, vmax;   /* RAMP */
    const char *unit;    /* RAMP: legend unit */
    size_t nclass;       /* CLASSES, FILL_CLASSES, POINT_KINDS */
    const char *const *values;  /* POINT_KINDS: the string field's values */
    const char *const *labels;  /* CLASSES, FILL_CLASSES, POINT_KINDS */
    const char *const *colors;  /* "#rrggbb"; RAMP: ncolor of them (NULL: a default yellow-red-purple ramp) */
    size_t ncolor;              /* RAMP */
    const char *const *shapes;  /* POINT_KINDS */
    const char *field;          /* FILL_CLASSES, POINT_KINDS */
    const char *color;          /* OUTLINE, LINE */
    double width;               /* OUTLINE, LINE [mm] */
    int dashed;                 /* OUTLINE, LINE */
} gf_qgis_layer;

/* Writes a QGIS 3 project (.qgs XML) at path: title, the project CRS from crs_wkt (GDAL WKT of the rasters'
 * CRS; NULL or "" = no CRS, layers then unprojected), the initial view extent[4] = xmin, ymin, xmax, ymax,
 * and the n layers in legend order (first = top of the legend, drawn on top), grouped by .group.
 * Refused (GF_EINVAL, naming the layer and what is wrong): n == 0, a NULL name/source, an unknown style,
 * RAMP with vmax <= vmin or not finite, CLASSES/FILL_CLASSES/POINT_KINDS with nclass == 0 or missing
 * labels/colors/values/shapes, a colour that is not #rrggbb, an unknown shape. GF_EIO naming the path when it cannot be written.
 * Text is XML-escaped (& < > " ').
 *
 * A group's layers are listed together at the place of its first layer, in
 * their order; top-level layers keep their place.  RAMP: a cell of exactly
 * vmin is drawn (only cells below it are not).
 *
 * Every layer is declared in crs_wkt (QGIS takes a layer's CRS from the
 * project file, not from the file itself), so the files must be in that
 * CRS.  A relative source is written "./source", which QGIS resolves
 * against the project file's folder (relative paths are on), so the folder
 * can be moved as a whole.  A vector layer's source is "file|layername=layer"
 * (OGR provider; without .layer just the file, e.g. a shapefile).  Also
 * refused: extent NULL or not finite or empty, RAMP colors given with
 * ncolor < 2, FILL_CLASSES/POINT_KINDS without field, a raster style with a
 * .layer, a group or name "".
 * Numbers are written with printf: the C locale's decimal point is assumed
 * (as every C program has it unless it calls setlocale). */
gf_status gf_qgis_project_write(const char *path, const char *title, const char *crs_wkt, const double extent[4],
                                size_t n, const gf_qgis_layer *layers);

#ifdef __cplusplus
}
#endif

#endif
