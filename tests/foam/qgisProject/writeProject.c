/* SPDX-License-Identifier: GPL-3.0-or-later */
/* writeProject DIR: DIR/project.qgs through gf_qgis_project_write
 * (granflow/qgis_project.h) over the files the Alltest made in DIR: every
 * style once, in two groups (T30 and base) with a top-level layer between
 * them, the project CRS and the view those of DIR/dem.tif.  A second
 * project DIR/nocrs.qgs has no CRS.  Prints the library's reason and exits
 * 1 when it refuses. */
#include "granflow/qgis_project.h"
#include "granflow/terrain.h"

#include <stdio.h>

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: writeProject DIR\n");
        return 2;
    }
    char path[4096];
    gf_raster dem;
    snprintf(path, sizeof path, "%s/dem.tif", argv[1]);
    if (gf_raster_read(path, &dem)) {
        fprintf(stderr, "writeProject: %s\n", gf_error_detail());
        return 1;
    }
    /* the DEM's extent, from its north-up geotransform */
    const double extent[4] = {dem.gt[0], dem.gt[3] + dem.ny * dem.gt[5], dem.gt[0] + dem.nx * dem.gt[1], dem.gt[3]};
    static const char *const zone_labels[] = {"low & <1 kPa>", "medium", "high"};
    static const char *const zone_colors[] = {"#ffff00", "#0000ff", "#ff0000"};
    static const char *const ramp[] = {"#fff5b8", "#f67e2a", "#3d0f5c"};
    static const char *const kinds[] = {"release", "runout", "split"};
    static const char *const kind_labels[] = {"release point", "runout point", "split point"};
    static const char *const kind_colors[] = {"#00aa00", "#aa00aa", "#00aaaa"};
    static const char *const shapes[] = {"triangle", "diamond", "square"};
    const gf_qgis_layer layers[] = {
        {.group = "T30", .name = "peak pressure", .source = "T30/peak.tif", .style = GF_QGIS_RAMP, .visible = 1,
         .vmin = 5, .vmax = 15, .unit = "kPa", .colors = ramp, .ncolor = 3},
        {.group = "T30", .name = "zones \"T30\"", .source = "T30/zones.tif", .style = GF_QGIS_CLASSES, .visible = 1,
         .nclass = 3, .labels = zone_labels, .colors = zone_colors},
        {.group = "T30", .name = "release areas", .source = "vectors.gpkg", .layer = "areas",
         .style = GF_QGIS_FILL_CLASSES, .visible = 1, .nclass = 3, .labels = zone_labels, .colors = zone_colors,
         .field = "class"},
        {.group = "T30", .name = "outline", .source = "vectors.gpkg", .layer = "areas", .style = GF_QGIS_OUTLINE,
         .visible = 1, .color = "#202020", .width = 0.6, .dashed = 1},
        {.name = "DEM default ramp", .source = "dem.tif", .style = GF_QGIS_RAMP, .visible = 0, .vmin = 1300,
         .vmax = 2100, .unit = "m"},
        {.group = "base", .name = "paths", .source = "vectors.gpkg", .layer = "paths", .style = GF_QGIS_LINE,
         .visible = 1, .color = "#00ff00", .width = 0.8},
        {.group = "base", .name = "points", .source = "vectors.gpkg", .layer = "points",
         .style = GF_QGIS_POINT_KINDS, .visible = 1, .nclass = 3, .values = kinds, .labels = kind_labels,
         .colors = kind_colors, .shapes = shapes, .field = "kind"},
        {.group = "base", .name = "hillshade & <DEM>", .source = "dem.tif", .style = GF_QGIS_HILLSHADE, .visible = 1},
    };
    const size_t n = sizeof layers / sizeof *layers;
    snprintf(path, sizeof path, "%s/project.qgs", argv[1]);
    int rc = 0;
    if (gf_qgis_project_write(path, "granflow & <qgisProject>", dem.wkt, extent, n, layers)) {
        fprintf(stderr, "writeProject: %s\n", gf_error_detail());
        rc = 1;
    }
    snprintf(path, sizeof path, "%s/nocrs.qgs", argv[1]);
    if (!rc && gf_qgis_project_write(path, "no CRS", NULL, extent, n, layers)) {
        fprintf(stderr, "writeProject: %s\n", gf_error_detail());
        rc = 1;
    }
    gf_raster_free(&dem);
    return rc;
}
