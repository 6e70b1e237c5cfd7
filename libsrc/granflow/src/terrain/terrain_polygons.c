/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The vector side of the regional analysis (granflow/regional.h): release
 * areas written as polygons with their attributes (GDAL's polygonize of the
 * label raster, OGR's GeoPackage or shapefile), and a polygon mask on a
 * grid. */
#include "granflow/regional.h"
#include "granflow/terrain.h"
#include "internal.h"
#include "terrain_internal.h"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal.h>
#include <gdal_alg.h>
#include <ogr_api.h>
#include <ogr_srs_api.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

void gf_polygons_mask(const gf_polygons *p, const gf_raster *grid, unsigned char *mask)
{
    for (int j = 0; j < grid->ny; ++j)
        for (int i = 0; i < grid->nx; ++i) {
            double x, y;
            gf_raster_centre(grid, i, j, &x, &y);
            mask[(size_t)j * (size_t)grid->nx + (size_t)i] = gf_polygons_locate(p, x, y) >= 0;
        }
}

gf_status gf_pra_write_polygons(const char *path, const char *driver, const gf_raster *grid,
                                const gf_pra_set *set, const double *d0)
{
    gf_terrain_gdal_init();
    if (!path || !driver || !grid || !set || !set->label || set->nx != grid->nx || set->ny != grid->ny)
        return gf_fail(GF_EINVAL, "release polygons %s: labels and grid must be given, of one size",
                       path ? path : "(no file)");
    GDALDriverH drv = GDALGetDriverByName(driver);
    if (!drv || (strcmp(driver, "GPKG") && strcmp(driver, "ESRI Shapefile")))
        return gf_fail(GF_EINVAL, "release polygons %s: driver '%s' (allowed: GPKG, ESRI Shapefile%s)", path, driver,
                       drv ? "" : "; GDAL lacks it");
    gf_status st = GF_SUCCESS;
    GDALDatasetH mem = NULL, vmem = NULL, out = NULL;
    OGRSpatialReferenceH srs = NULL;
    size_t nc = (size_t)grid->nx * (size_t)grid->ny;
    unsigned char *nz = malloc(nc);
    if (!nz)
        return gf_fail(GF_ENOMEM, "release polygons %s: %zu cells", path, nc);
    for (size_t c = 0; c < nc; ++c)
        nz[c] = set->label[c] > 0;
    mem = gf_terrain_mem_raster(grid, grid->nx, grid->ny, 2, GDT_Int32);
    if (!mem) {
        st = gf_fail(GF_EIO, "release polygons %s: %s", path, gf_terrain_gdal_msg());
        goto done;
    }
    GDALRasterBandH b = GDALGetRasterBand(mem, 1), m = GDALGetRasterBand(mem, 2);
    int *maskv = malloc(nc * sizeof *maskv);
    if (!maskv) {
        st = gf_fail(GF_ENOMEM, "release polygons %s: %zu cells", path, nc);
        goto done;
    }
    for (size_t c = 0; c < nc; ++c)
        maskv[c] = nz[c];
    CPLErr e1 = GDALRasterIO(b, GF_Write, 0, 0, grid->nx, grid->ny, set->label, grid->nx, grid->ny, GDT_Int32, 0, 0);
    CPLErr e2 = GDALRasterIO(m, GF_Write, 0, 0, grid->nx, grid->ny, maskv, grid->nx, grid->ny, GDT_Int32, 0, 0);
    free(maskv);
    if (e1 != CE_None || e2 != CE_None) {
        st = gf_fail(GF_EIO, "release polygons %s: %s", path, gf_terrain_gdal_msg());
        goto done;
    }
    if (grid->wkt && *grid->wkt) {
        srs = OSRNewSpatialReference(grid->wkt);
        if (srs)
            OSRSetAxisMappingStrategy(srs, OAMS_TRADITIONAL_GIS_ORDER);
    }
    GDALDriverH mdrv = GDALGetDriverByName("Memory");
    vmem = mdrv ? GDALCreate(mdrv, "", 0, 0, 0, GDT_Unknown, NULL) : NULL;
    if (!vmem) {
        st = gf_fail(GF_EIO, "release polygons %s: GDAL lacks the Memory driver", path);
        goto done;
    }
    OGRLayerH ml = GDALDatasetCreateLayer(vmem, "labels", srs, wkbPolygon, NULL);
    OGRFieldDefnH fd = OGR_Fld_Create("id", OFTInteger);
    OGR_L_CreateField(ml, fd, TRUE);
    OGR_Fld_Destroy(fd);
    if (GDALPolygonize(b, m, ml, 0, NULL, NULL, NULL) != CE_None) {
        st = gf_fail(GF_EIO, "release polygons %s: polygonize failed (%s)", path, gf_terrain_gdal_msg());
        goto done;
    }
    unlink(path);
    CPLPushErrorHandler(CPLQuietErrorHandler);
    out = GDALCreate(drv, path, 0, 0, 0, GDT_Unknown, NULL);
    CPLPopErrorHandler();
    if (!out) {
        st = gf_fail(GF_EIO, "release polygons %s: GDAL cannot write it (%s)", path, gf_terrain_gdal_msg());
        goto done;
    }
    OGRLayerH ol = GDALDatasetCreateLayer(out, "release_areas", srs, wkbMultiPolygon, NULL);
    if (!ol) {
        st = gf_fail(GF_EIO, "release polygons %s: cannot create its layer (%s)", path, gf_terrain_gdal_msg());
        goto done;
    }
    const char *names[6] = {"id", "area_m2", "slope_deg", "altitude_m", "aspect_deg", "d0_m"};
    int nf = d0 ? 6 : 5;
    for (int k = 0; k < nf; ++k) {
        OGRFieldDefnH f = OGR_Fld_Create(names[k], k ? OFTReal : OFTInteger);
        OGR_L_CreateField(ol, f, TRUE);
        OGR_Fld_Destroy(f);
    }
    /* one feature per area: its polygons (one, 4-connected) gathered */
    OGRGeometryH *geom = calloc(set->n + 1, sizeof *geom);
    if (!geom) {
        st = gf_fail(GF_ENOMEM, "release polygons %s: %zu areas", path, set->n);
        goto done;
    }
    OGR_L_ResetReading(ml);
    OGRFeatureH f;
    while ((f = OGR_L_GetNextFeature(ml)) != NULL) {
        int id = OGR_F_GetFieldAsInteger(f, 0);
        if (id >= 1 && (size_t)id <= set->n) {
            if (!geom[id])
                geom[id] = OGR_G_CreateGeometry(wkbMultiPolygon);
            OGR_G_AddGeometry(geom[id], OGR_F_GetGeometryRef(f));
        }
        OGR_F_Destroy(f);
    }
    const int tx = OGR_L_StartTransaction(ol) == OGRERR_NONE;
    for (size_t k = 0; k < set->n && !st; ++k) {
        const gf_pra *a = &set->pra[k];
        if (!geom[a->id])
            continue;
        OGRFeatureH g = OGR_F_Create(OGR_L_GetLayerDefn(ol));
        OGR_F_SetGeometry(g, geom[a->id]);
        OGR_F_SetFieldInteger(g, 0, a->id);
        OGR_F_SetFieldDouble(g, 1, a->area_m2);
        OGR_F_SetFieldDouble(g, 2, a->slope_deg);
        OGR_F_SetFieldDouble(g, 3, a->altitude_m);
        OGR_F_SetFieldDouble(g, 4, a->aspect_deg);
        if (d0)
            OGR_F_SetFieldDouble(g, 5, d0[k]);
        if (OGR_L_CreateFeature(ol, g) != OGRERR_NONE)
            st = gf_fail(GF_EIO, "release polygons %s: writing area %d failed (%s)", path, a->id, gf_terrain_gdal_msg());
        OGR_F_Destroy(g);
    }
    if (tx && OGR_L_CommitTransaction(ol) != OGRERR_NONE && !st)
        st = gf_fail(GF_EIO, "release polygons %s: writing the areas failed (%s)", path, gf_terrain_gdal_msg());
    for (size_t k = 0; k <= set->n; ++k)
        if (geom[k])
            OGR_G_DestroyGeometry(geom[k]);
    free(geom);
done:
    free(nz);
    if (out)
        GDALClose(out);
    if (vmem)
        GDALClose(vmem);
    if (mem)
        GDALClose(mem);
    if (srs)
        OSRDestroySpatialReference(srs);
    return st;
}
