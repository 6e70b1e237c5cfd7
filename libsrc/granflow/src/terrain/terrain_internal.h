/* Internal helpers shared by the files of libgranflowTerrain (terrain.c,
 * path_analysis.c): not installed, not part of the API. */
#ifndef GRANFLOW_TERRAIN_INTERNAL_H
#define GRANFLOW_TERRAIN_INTERNAL_H

#include <gdal.h>

#include "granflow/status.h"

/* GDALAllRegister once */
void gf_terrain_gdal_init(void);

/* Open a vector file (OGR) read-only; NULL with *st set (GF_EIO, the
 * message naming 'what' and the file) when it is missing or OGR cannot read
 * it. */
GDALDatasetH gf_terrain_open_vector(const char *what, const char *path, gf_status *st);

#endif
