/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Internal helpers shared by the files of libgranflowTerrain
 * (terrain_raster.c, terrain_vector.c, terrain_maps.c, path_analysis.c): not
 * installed, not part of the API. */
#ifndef GRANFLOW_TERRAIN_INTERNAL_H
#define GRANFLOW_TERRAIN_INTERNAL_H

#include <gdal.h>
#include <ogr_api.h>

#include "granflow/status.h"
#include "granflow/terrain.h"

/* GDALAllRegister once */
void gf_terrain_gdal_init(void);

/* GDAL's last error text, or a fixed one */
const char *gf_terrain_gdal_msg(void);

/* A malloc'd copy of s ("" for NULL); NULL when out of memory */
char *gf_terrain_dup_str(const char *s);

/* An in-memory (MEM) dataset of nx x ny pixels, nb bands of type t, with the
 * geotransform and CRS of grid (none for grid NULL); NULL without the MEM
 * driver */
GDALDatasetH gf_terrain_mem_raster(const gf_raster *grid, int nx, int ny, int nb, GDALDataType t);

/* Open a vector file (OGR) read-only; NULL with *st set (GF_EIO, the
 * message naming 'what' and the file) when it is missing or OGR cannot read
 * it. */
GDALDatasetH gf_terrain_open_vector(const char *what, const char *path, gf_status *st);

/* The first feature of the first layer of ds (OGR_F_Destroy it); NULL with
 * *st set (GF_EDOM, "<what> <path>: no feature in its first layer") when
 * there is none. */
OGRFeatureH gf_terrain_first_feature(GDALDatasetH ds, const char *what, const char *path, gf_status *st);

/* A line geometry as one line string: a multi line string of one part is
 * taken as that part.  Returns the geometry and its flattened type in *t
 * (wkbNone for no geometry); the caller checks *t == wkbLineString. */
OGRGeometryH gf_terrain_single_line(OGRGeometryH g, OGRwkbGeometryType *t);

#endif
