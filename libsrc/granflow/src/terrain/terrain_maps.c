/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Real terrain through GDAL/OGR (see granflow/terrain.h): what is made from
 * rasters for the user: the outline of an area (GeoJSON polygons), a line as
 * GeoJSON, the outlines of classes (GeoPackage), the probability raster of an ensemble and its contour lines (the
 * maps themselves are drawn with GMT: gfReportMaps). */
#include "granflow/terrain.h"
#include "granflow/path_analysis.h"
#include "internal.h"
#include "terrain_internal.h"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal.h>
#include <gdal_alg.h>
#include <ogr_api.h>
#include <ogr_srs_api.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/*--------------------------------------------------------------- outline --*/

/* The CRS of a GeoJSON layer, x = easting */
static OGRSpatialReferenceH geojson_srs(const char *wkt)
{
    OGRSpatialReferenceH srs = OSRNewSpatialReference(wkt);
    if (srs)
        OSRSetAxisMappingStrategy(srs, OAMS_TRADITIONAL_GIS_ORDER);
    return srs;
}

/* GeoJSON is WGS 84 longitude/latitude (RFC 7946): a layer with a CRS is
 * reprojected to it on writing; one without (a synthetic terrain) keeps its
 * coordinates */
static char *rfc7946[] = {"RFC7946=YES", NULL};

/* The set-up GDAL's raster-to-vector algorithms share (gf_raster_outline,
 * gf_raster_contours): values (of type t) on grid in an in-memory band, an
 * in-memory layer of geometry type gtype for the algorithm to fill, and the
 * grid's CRS for GeoJSON (NULL without one).  Messages start with
 * "<what> <path>:".  Whatever was made is returned for the caller to close. */
static gf_status band_and_layer(const char *what, const char *path, const gf_raster *grid, void *values,
                                GDALDataType t, const char *layer, OGRwkbGeometryType gtype, GDALDatasetH *mem,
                                GDALRasterBandH *band, GDALDatasetH *vmem, OGRLayerH *ml, OGRSpatialReferenceH *srs)
{
    *mem = gf_terrain_mem_raster(grid, grid->nx, grid->ny, 1, t);
    if (!*mem)
        return gf_fail(GF_EIO, "%s %s: %s", what, path, gf_terrain_gdal_msg());
    *band = GDALGetRasterBand(*mem, 1);
    if (GDALRasterIO(*band, GF_Write, 0, 0, grid->nx, grid->ny, values, grid->nx, grid->ny, t, 0, 0) != CE_None)
        return gf_fail(GF_EIO, "%s %s: %s", what, path, gf_terrain_gdal_msg());
    if (grid->wkt && *grid->wkt)
        *srs = geojson_srs(grid->wkt);
    GDALDriverH vdrv = GDALGetDriverByName("Memory"), gj = GDALGetDriverByName("GeoJSON");
    *vmem = vdrv ? GDALCreate(vdrv, "", 0, 0, 0, GDT_Unknown, NULL) : NULL;
    if (!*vmem || !gj)
        return gf_fail(GF_EIO, "%s %s: GDAL lacks the Memory or GeoJSON driver", what, path);
    *ml = GDALDatasetCreateLayer(*vmem, layer, *srs, gtype, NULL);
    return *ml ? GF_SUCCESS : gf_fail(GF_EIO, "%s %s: %s", what, path, gf_terrain_gdal_msg());
}

/* Close what band_and_layer made and the output dataset (any may be NULL) */
static void close_band_and_layer(GDALDatasetH out, GDALDatasetH vmem, GDALDatasetH mem, OGRSpatialReferenceH srs)
{
    if (out)
        GDALClose(out);
    if (vmem)
        GDALClose(vmem);
    if (mem)
        GDALClose(mem);
    if (srs)
        OSRDestroySpatialReference(srs);
}

/* values (of type t, 0 where nothing is) on grid polygonized by GDAL: each
 * 4-connected group of pixels of one non-zero value a polygon of an
 * in-memory layer *ml (its value in field 0), and the output dataset *out
 * made at path by the driver drv (the file replaced); what made it is
 * returned for close_band_and_layer */
static gf_status polygonize_into(const char *what, const char *path, const gf_raster *grid, void *values,
                                 GDALDataType t, GDALDriverH drv, GDALDatasetH *mem, GDALDatasetH *vmem, OGRLayerH *ml,
                                 OGRSpatialReferenceH *srs, GDALDatasetH *out)
{
    GDALRasterBandH b = NULL;
    gf_status st = band_and_layer(what, path, grid, values, t, "polygons", wkbPolygon, mem, &b, vmem, ml, srs);
    if (st)
        return st;
    OGRFieldDefnH fd = OGR_Fld_Create("value", OFTInteger);
    OGR_L_CreateField(*ml, fd, TRUE);
    OGR_Fld_Destroy(fd);
    /* the band as its own mask: 0 makes no polygon */
    if (GDALPolygonize(b, b, *ml, 0, NULL, NULL, NULL) != CE_None)
        return gf_fail(GF_EIO, "%s %s: polygonize failed (%s)", what, path, gf_terrain_gdal_msg());
    unlink(path);
    CPLPushErrorHandler(CPLQuietErrorHandler);
    *out = GDALCreate(drv, path, 0, 0, 0, GDT_Unknown, NULL);
    CPLPopErrorHandler();
    return *out ? GF_SUCCESS : gf_fail(GF_EIO, "%s %s: GDAL cannot write it (%s)", what, path, gf_terrain_gdal_msg());
}

gf_status gf_raster_outline(const char *path, const gf_raster *grid, const double *values,
                            double threshold, double *area)
{
    gf_terrain_gdal_init();
    if (!(isfinite(threshold) && threshold > 0))
        return gf_fail(GF_EDOM, "outline %s: threshold %g must be finite and > 0", path, threshold);
    const size_t n = (size_t)grid->nx * (size_t)grid->ny;
    unsigned char *mask = malloc(n);
    if (!mask)
        return gf_fail(GF_ENOMEM, "outline %s: out of memory", path);
    size_t count = 0;
    for (size_t i = 0; i < n; ++i)
        count += (mask[i] = isfinite(values[i]) && values[i] >= threshold);
    if (area)
        *area = (double)count * grid->gt[1] * -grid->gt[5];
    GDALDatasetH mem = NULL, vmem = NULL, out = NULL;
    OGRLayerH ml = NULL;
    OGRSpatialReferenceH srs = NULL;
    GDALDriverH gj = GDALGetDriverByName("GeoJSON");
    /* only the affected pixels become polygons */
    gf_status st = gj ? polygonize_into("outline", path, grid, mask, GDT_Byte, gj, &mem, &vmem, &ml, &srs, &out)
                      : gf_fail(GF_EIO, "outline %s: GDAL lacks the GeoJSON driver", path);
    if (st)
        goto done;
    OGRLayerH ol = GDALDatasetCreateLayer(out, "affected_area", srs, wkbPolygon, srs ? rfc7946 : NULL);
    OGRFieldDefnH fa = OGR_Fld_Create("area_m2", OFTReal);
    OGRFieldDefnH ft = OGR_Fld_Create("threshold", OFTReal);
    OGR_L_CreateField(ol, fa, TRUE);
    OGR_L_CreateField(ol, ft, TRUE);
    OGR_Fld_Destroy(fa);
    OGR_Fld_Destroy(ft);
    OGR_L_ResetReading(ml);
    OGRFeatureH f;
    while ((f = OGR_L_GetNextFeature(ml)) != NULL) {
        OGRFeatureH g = OGR_F_Create(OGR_L_GetLayerDefn(ol));
        OGRGeometryH geom = OGR_F_GetGeometryRef(f);
        OGR_F_SetGeometry(g, geom);
        OGR_F_SetFieldDouble(g, 0, OGR_G_Area(geom));
        OGR_F_SetFieldDouble(g, 1, threshold);
        const OGRErr e = OGR_L_CreateFeature(ol, g);
        OGR_F_Destroy(g);
        OGR_F_Destroy(f);
        if (e != OGRERR_NONE) {
            st = gf_fail(GF_EIO, "outline %s: writing a polygon failed (%s)", path, gf_terrain_gdal_msg());
            goto done;
        }
    }
done:
    close_band_and_layer(out, vmem, mem, srs);
    free(mask);
    return st;
}

/*--------------------------------------------------------- class outlines --*/

static int plain_word(const char *s)
{
    if (!s || !*s || strlen(s) > 48)
        return 0;
    for (; *s; ++s)
        if (!((*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z') || (*s >= '0' && *s <= '9') || *s == '_'))
            return 0;
    return 1;
}

gf_status gf_class_outlines(const char *path, const char *layer, const gf_raster *grid, const double *cls,
                            size_t nclass, const double *limits, const char *unit, size_t *n)
{
    gf_terrain_gdal_init();
    if (!path || !grid || !cls || !limits)
        return gf_fail(GF_EINVAL, "class outlines %s: a grid, its classes and the limits must be given",
                       path ? path : "(no file)");
    if (nclass == 0 || nclass > 1000)
        return gf_fail(GF_EINVAL, "class outlines %s: %zu classes (allowed: 1 to 1000)", path, nclass);
    for (size_t k = 0; k < nclass; ++k)
        if (!isfinite(limits[k]) || (k > 0 && !(limits[k] > limits[k - 1])))
            return gf_fail(GF_EINVAL, "class outlines %s: limit %zu (%g) must be finite and above the one before", path,
                           k + 1, limits[k]);
    if (!plain_word(layer) || !plain_word(unit))
        return gf_fail(GF_EINVAL, "class outlines %s: layer '%s' and unit '%s' must be plain words (letters, digits, _)",
                       path, layer ? layer : "", unit ? unit : "");
    GDALDriverH gp = GDALGetDriverByName("GPKG");
    if (!gp)
        return gf_fail(GF_EIO, "class outlines %s: GDAL lacks the GPKG driver", path);
    const size_t nc = (size_t)grid->nx * (size_t)grid->ny;
    int *v = malloc(nc * sizeof *v);
    if (!v)
        return gf_fail(GF_ENOMEM, "class outlines %s: %zu cells", path, nc);
    for (size_t i = 0; i < nc; ++i) {
        const double c = cls[i];
        v[i] = isfinite(c) && c >= 1 && c <= (double)nclass && c == floor(c) ? (int)c : 0;
    }
    GDALDatasetH mem = NULL, vmem = NULL, out = NULL;
    OGRLayerH ml = NULL;
    OGRSpatialReferenceH srs = NULL;
    size_t count = 0;
    /* class 0 makes no polygon */
    gf_status st = polygonize_into("class outlines", path, grid, v, GDT_Int32, gp, &mem, &vmem, &ml, &srs, &out);
    if (st)
        goto done;
    OGRLayerH ol = GDALDatasetCreateLayer(out, layer, srs, wkbPolygon, NULL);
    if (!ol) {
        st = gf_fail(GF_EIO, "class outlines %s: GDAL cannot write it (%s)", path, gf_terrain_gdal_msg());
        goto done;
    }
    char lo[64], hi[64];
    snprintf(lo, sizeof lo, "lower_%s", unit);
    snprintf(hi, sizeof hi, "upper_%s", unit);
    const char *names[] = {"class", lo, hi, "area_m2"};
    const OGRFieldType types[] = {OFTInteger, OFTReal, OFTReal, OFTReal};
    for (int f = 0; f < 4; ++f) {
        OGRFieldDefnH d = OGR_Fld_Create(names[f], types[f]);
        const OGRErr e = OGR_L_CreateField(ol, d, TRUE);
        OGR_Fld_Destroy(d);
        if (e != OGRERR_NONE) {
            st = gf_fail(GF_EIO, "class outlines %s: field %s (%s)", path, names[f], gf_terrain_gdal_msg());
            goto done;
        }
    }
    if (OGR_L_StartTransaction(ol) != OGRERR_NONE) {
        st = gf_fail(GF_EIO, "class outlines %s: %s", path, gf_terrain_gdal_msg());
        goto done;
    }
    OGR_L_ResetReading(ml);
    OGRFeatureH f;
    while ((f = OGR_L_GetNextFeature(ml)) != NULL) {
        const int k = OGR_F_GetFieldAsInteger(f, 0);
        OGRFeatureH g = OGR_F_Create(OGR_L_GetLayerDefn(ol));
        OGRGeometryH geom = OGR_F_GetGeometryRef(f);
        OGR_F_SetGeometry(g, geom);
        OGR_F_SetFieldInteger(g, 0, k);
        OGR_F_SetFieldDouble(g, 1, limits[k - 1]);
        if ((size_t)k < nclass)
            OGR_F_SetFieldDouble(g, 2, limits[k]);
        OGR_F_SetFieldDouble(g, 3, OGR_G_Area(geom));
        const OGRErr e = OGR_L_CreateFeature(ol, g);
        OGR_F_Destroy(g);
        OGR_F_Destroy(f);
        if (e != OGRERR_NONE) {
            st = gf_fail(GF_EIO, "class outlines %s: writing a polygon failed (%s)", path, gf_terrain_gdal_msg());
            goto done;
        }
        ++count;
    }
    if (OGR_L_CommitTransaction(ol) != OGRERR_NONE)
        st = gf_fail(GF_EIO, "class outlines %s: %s", path, gf_terrain_gdal_msg());
done:
    close_band_and_layer(out, vmem, mem, srs);
    free(v);
    if (n)
        *n = count;
    return st;
}

gf_status gf_line_geojson(const char *path, const char *wkt, size_t n, const double *xyz, const char *name,
                          size_t nprops, const char *const *keys, const double *values)
{
    gf_terrain_gdal_init();
    if (n < 2)
        return gf_fail(GF_EDOM, "line %s: %zu points; a line needs at least 2", path, n);
    GDALDriverH gj = GDALGetDriverByName("GeoJSON");
    if (!gj)
        return gf_fail(GF_EIO, "line %s: GDAL lacks the GeoJSON driver", path);
    OGRSpatialReferenceH srs = NULL;
    if (wkt && *wkt)
        srs = geojson_srs(wkt);
    unlink(path);
    CPLPushErrorHandler(CPLQuietErrorHandler);
    GDALDatasetH out = GDALCreate(gj, path, 0, 0, 0, GDT_Unknown, NULL);
    CPLPopErrorHandler();
    gf_status st = GF_SUCCESS;
    if (!out) {
        st = gf_fail(GF_EIO, "line %s: GDAL cannot write it (%s)", path, gf_terrain_gdal_msg());
        goto done;
    }
    OGRLayerH L = GDALDatasetCreateLayer(out, name, srs, wkbLineString25D, srs ? rfc7946 : NULL);
    OGRFieldDefnH fn = OGR_Fld_Create("name", OFTString);
    OGR_L_CreateField(L, fn, TRUE);
    OGR_Fld_Destroy(fn);
    for (size_t k = 0; k < nprops; ++k) {
        OGRFieldDefnH fd = OGR_Fld_Create(keys[k], OFTReal);
        OGR_L_CreateField(L, fd, TRUE);
        OGR_Fld_Destroy(fd);
    }
    OGRFeatureH f = OGR_F_Create(OGR_L_GetLayerDefn(L));
    OGR_F_SetFieldString(f, 0, name);
    for (size_t k = 0; k < nprops; ++k)
        OGR_F_SetFieldDouble(f, (int)k + 1, values[k]);
    OGRGeometryH g = OGR_G_CreateGeometry(wkbLineString25D);
    for (size_t i = 0; i < n; ++i)
        OGR_G_AddPoint(g, xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
    OGR_F_SetGeometryDirectly(f, g);
    if (OGR_L_CreateFeature(L, f) != OGRERR_NONE)
        st = gf_fail(GF_EIO, "line %s: writing the feature failed (%s)", path, gf_terrain_gdal_msg());
    OGR_F_Destroy(f);
done:
    if (out)
        GDALClose(out);
    if (srs)
        OSRDestroySpatialReference(srs);
    return st;
}

/*------------------------------------------------------ probability maps --*/

gf_status gf_probability_map(size_t n, const char *const *paths, double threshold, gf_raster *out)
{
    if (!out)
        return gf_fail(GF_EINVAL, "probability map: null argument");
    memset(out, 0, sizeof *out);
    if (n < 1 || !paths)
        return gf_fail(GF_EINVAL, "probability map: no member rasters (n = %zu)", n);
    if (!isfinite(threshold))
        return gf_fail(GF_ENONFINITE, "probability map: threshold %g is not a finite number", threshold);
    gf_status st = GF_SUCCESS;
    unsigned *count = NULL;
    unsigned char *seen = NULL;
    for (size_t m = 0; m < n; ++m) {
        gf_raster r;
        if ((st = gf_raster_read(paths[m], &r))) {
            char why[GF_DETAIL_MAX];
            snprintf(why, sizeof why, "%s", gf_error_detail());
            st = gf_fail(st, "probability map: member %zu of %zu: %s", m + 1, n, why);
            break;
        }
        const size_t np = (size_t)r.nx * (size_t)r.ny;
        if (m == 0) {
            *out = r;   /* the grid and CRS of the first member; z becomes the probability */
            count = calloc(np, sizeof *count);
            seen = calloc(np, 1);
            if (!count || !seen) {
                st = gf_fail(GF_ENOMEM, "probability map: out of memory for %d x %d cells", r.nx, r.ny);
                break;
            }
        } else if (!gf_raster_same_grid(out, &r)) {
            st = gf_fail(GF_EDOM,
                         "probability map: raster %s (member %zu) is %d x %d cells, origin (%.10g, %.10g),"
                         " pixel %.10g; the first member %s is %d x %d, origin (%.10g, %.10g), pixel %.10g:"
                         " every member must be on one grid",
                         paths[m], m + 1, r.nx, r.ny, r.gt[0], r.gt[3], r.gt[1], paths[0], out->nx, out->ny,
                         out->gt[0], out->gt[3], out->gt[1]);
            gf_raster_free(&r);
            break;
        }
        for (size_t i = 0; i < np; ++i) {
            if (isnan(r.z[i]))
                continue;
            seen[i] = 1;
            count[i] += r.z[i] > threshold;
        }
        if (m > 0)
            gf_raster_free(&r);
    }
    if (!st) {
        const size_t np = (size_t)out->nx * (size_t)out->ny;
        out->n_valid = 0;
        for (size_t i = 0; i < np; ++i) {
            out->z[i] = seen[i] ? (double)count[i] / (double)n : NAN;
            out->n_valid += seen[i];
        }
    } else
        gf_raster_free(out);
    free(count);
    free(seen);
    return st;
}

gf_status gf_raster_contours(const char *geojson, const char *xy_path, const gf_raster *grid,
                             const double *values, size_t nlev, const double *levels)
{
    gf_terrain_gdal_init();
    if (!grid || !values || nlev < 1 || !levels)
        return gf_fail(GF_EINVAL, "contours: no grid, values or levels");
    for (size_t k = 0; k < nlev; ++k)
        if (!isfinite(levels[k]))
            return gf_fail(GF_ENONFINITE, "contours: level %zu is %g, not a finite number", k, levels[k]);
    const size_t np = (size_t)grid->nx * (size_t)grid->ny;
    const double nd = -9999.0;
    double *v = malloc(np * sizeof *v);
    if (!v)
        return gf_fail(GF_ENOMEM, "contours: out of memory");
    for (size_t i = 0; i < np; ++i)
        v[i] = isnan(values[i]) ? nd : values[i];
    GDALDatasetH mem = NULL, vmem = NULL, out = NULL;
    GDALRasterBandH b = NULL;
    OGRLayerH ml = NULL;
    OGRSpatialReferenceH srs = NULL;
    FILE *xy = NULL;
    const char *what = geojson ? geojson : xy_path ? xy_path : "(none)";
    GDALDriverH gj = GDALGetDriverByName("GeoJSON");
    gf_status st = band_and_layer("contours", what, grid, v, GDT_Float64, "contours", wkbLineString, &mem, &b, &vmem,
                                  &ml, &srs);
    if (st)
        goto done;
    OGRFieldDefnH fid = OGR_Fld_Create("id", OFTInteger), fl = OGR_Fld_Create("level", OFTReal);
    OGR_L_CreateField(ml, fid, TRUE);
    OGR_L_CreateField(ml, fl, TRUE);
    OGR_Fld_Destroy(fid);
    OGR_Fld_Destroy(fl);
    if (GDALContourGenerate(b, 0.0, 0.0, (int)nlev, (double *)levels, TRUE, nd, ml, 0, 1, NULL, NULL) != CE_None) {
        st = gf_fail(GF_EIO, "contours %s: contouring failed (%s)", what, gf_terrain_gdal_msg());
        goto done;
    }
    if (xy_path && !(xy = fopen(xy_path, "w"))) {
        st = gf_fail(GF_EIO, "contours %s: cannot write it", xy_path);
        goto done;
    }
    if (xy)
        fprintf(xy, "# contour lines: x y level (the grid's coordinates), one block per line\n");
    OGRLayerH ol = NULL;
    if (geojson) {
        unlink(geojson);
        CPLPushErrorHandler(CPLQuietErrorHandler);
        out = GDALCreate(gj, geojson, 0, 0, 0, GDT_Unknown, NULL);
        CPLPopErrorHandler();
        if (!out) {
            st = gf_fail(GF_EIO, "contours %s: GDAL cannot write it (%s)", geojson, gf_terrain_gdal_msg());
            goto done;
        }
        ol = GDALDatasetCreateLayer(out, "contours", srs, wkbLineString, srs ? rfc7946 : NULL);
        OGRFieldDefnH f1 = OGR_Fld_Create("level", OFTReal);
        OGR_L_CreateField(ol, f1, TRUE);
        OGR_Fld_Destroy(f1);
    }
    OGR_L_ResetReading(ml);
    OGRFeatureH f;
    while ((f = OGR_L_GetNextFeature(ml)) != NULL) {
        OGRGeometryH geom = OGR_F_GetGeometryRef(f);
        const double level = OGR_F_GetFieldAsDouble(f, 1);
        if (xy && geom) {
            const int npt = OGR_G_GetPointCount(geom);
            for (int i = 0; i < npt; ++i)
                fprintf(xy, "%.3f %.3f %.6g\n", OGR_G_GetX(geom, i), OGR_G_GetY(geom, i), level);
            fprintf(xy, "\n");
        }
        if (ol) {
            OGRFeatureH g = OGR_F_Create(OGR_L_GetLayerDefn(ol));
            OGR_F_SetGeometry(g, geom);
            OGR_F_SetFieldDouble(g, 0, level);
            const OGRErr e = OGR_L_CreateFeature(ol, g);
            OGR_F_Destroy(g);
            if (e != OGRERR_NONE) {
                OGR_F_Destroy(f);
                st = gf_fail(GF_EIO, "contours %s: writing a line failed (%s)", geojson, gf_terrain_gdal_msg());
                goto done;
            }
        }
        OGR_F_Destroy(f);
    }
done:
    if (xy && fclose(xy) != 0 && !st)
        st = gf_fail(GF_EIO, "contours %s: writing failed", xy_path);
    close_band_and_layer(out, vmem, mem, srs);
    free(v);
    return st;
}
