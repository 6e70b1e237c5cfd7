/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Real terrain through GDAL/OGR (see granflow/terrain.h): GDAL's set-up and
 * the helpers the files of libgranflowTerrain share (terrain_internal.h), DEMs
 * and rasters read and written, the comparison of CRSs, the mesh grid on a DEM
 * and face values back on its pixels.  Vector files (OGR): terrain_vector.c;
 * outlines, lines, maps and contours: terrain_maps.c. */
#include "granflow/terrain.h"
#include "internal.h"
#include "terrain_internal.h"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

void gf_terrain_gdal_init(void)
{
    static int done = 0;
    if (!done) {
        GDALAllRegister();
        done = 1;
    }
}

/* GDAL's last error text, or a fixed one */
const char *gf_terrain_gdal_msg(void)
{
    const char *m = CPLGetLastErrorMsg();
    return (m && *m) ? m : "no detail from GDAL";
}

char *gf_terrain_dup_str(const char *s)
{
    const size_t n = strlen(s ? s : "") + 1;
    char *d = malloc(n);
    if (d)
        memcpy(d, s ? s : "", n);
    return d;
}

/*---------------------------------------------------------------- rasters --*/

gf_status gf_raster_read(const char *path, gf_raster *r)
{
    if (!path || !r)
        return gf_fail(GF_EINVAL, "gf_raster_read: null argument");
    memset(r, 0, sizeof *r);
    gf_terrain_gdal_init();
    if (access(path, R_OK) != 0)
        return gf_fail(GF_EIO, "DEM %s: no such file or not readable", path);
    CPLErrorReset();
    CPLPushErrorHandler(CPLQuietErrorHandler);
    GDALDatasetH ds = GDALOpenEx(path, GDAL_OF_RASTER | GDAL_OF_READONLY, NULL, NULL, NULL);
    CPLPopErrorHandler();
    if (!ds)
        return gf_fail(GF_EIO, "DEM %s: not a raster GDAL can read (%s)", path, gf_terrain_gdal_msg());
    gf_status st = GF_SUCCESS;
    double gt[6];
    GDALRasterBandH band = GDALGetRasterCount(ds) >= 1 ? GDALGetRasterBand(ds, 1) : NULL;
    if (!band) {
        st = gf_fail(GF_EIO, "DEM %s: has no raster band", path);
        goto done;
    }
    if (GDALGetGeoTransform(ds, gt) != CE_None) {
        st = gf_fail(GF_EDOM, "DEM %s: no georeferencing (no geotransform); a DEM needs its"
                              " origin and cell size", path);
        goto done;
    }
    if (gt[2] != 0.0 || gt[4] != 0.0) {
        st = gf_fail(GF_EDOM, "DEM %s: rotated grid (geotransform terms %g, %g); only north-up"
                              " grids are supported", path, gt[2], gt[4]);
        goto done;
    }
    if (!(gt[1] > 0.0) || !(gt[5] < 0.0)) {
        st = gf_fail(GF_EDOM, "DEM %s: cell size %g x %g; a north-up grid has dx > 0 and"
                              " dy < 0 in GDAL's convention", path, gt[1], gt[5]);
        goto done;
    }
    if (fabs(gt[1] + gt[5]) > 1e-9 * gt[1]) {
        st = gf_fail(GF_EDOM, "DEM %s: mixed cell sizes dx = %.10g, dy = %.10g; the cells must"
                              " be square", path, gt[1], -gt[5]);
        goto done;
    }
    r->nx = GDALGetRasterXSize(ds), r->ny = GDALGetRasterYSize(ds);
    if (r->nx < 2 || r->ny < 2) {
        st = gf_fail(GF_EDOM, "DEM %s: %d x %d cells; at least 2 x 2 are needed", path, r->nx, r->ny);
        goto done;
    }
    memcpy(r->gt, gt, sizeof gt);
    int has_nd = 0;
    const double nd = GDALGetRasterNoDataValue(band, &has_nd);
    r->nodata = has_nd ? nd : -9999.0;
    r->wkt = gf_terrain_dup_str(GDALGetProjectionRef(ds));
    r->z = malloc(sizeof(double) * (size_t)r->nx * (size_t)r->ny);
    if (!r->z || !r->wkt) {
        st = gf_fail(GF_ENOMEM, "DEM %s: out of memory for %d x %d cells", path, r->nx, r->ny);
        goto done;
    }
    if (GDALRasterIO(band, GF_Read, 0, 0, r->nx, r->ny, r->z, r->nx, r->ny, GDT_Float64, 0, 0) != CE_None) {
        st = gf_fail(GF_EIO, "DEM %s: reading the elevations failed (%s)", path, gf_terrain_gdal_msg());
        goto done;
    }
    const size_t n = (size_t)r->nx * (size_t)r->ny;
    for (size_t i = 0; i < n; ++i) {
        if ((has_nd && r->z[i] == nd) || isnan(r->z[i]))
            r->z[i] = NAN;
        else if (!isfinite(r->z[i])) {
            st = gf_fail(GF_ENONFINITE, "DEM %s: elevation %g at column %zu, row %zu is not finite",
                         path, r->z[i], i % (size_t)r->nx, i / (size_t)r->nx);
            goto done;
        } else
            ++r->n_valid;
    }
    if (r->n_valid == 0)
        st = gf_fail(GF_EDOM, "DEM %s: every cell is NODATA (%g)", path, r->nodata);
done:
    GDALClose(ds);
    if (st)
        gf_raster_free(r);
    return st;
}

void gf_raster_free(gf_raster *r)
{
    if (!r)
        return;
    free(r->z);
    free(r->wkt);
    r->z = NULL, r->wkt = NULL;
}

void gf_raster_centre(const gf_raster *r, double col, double row, double *x, double *y)
{
    *x = r->gt[0] + (col + 0.5) * r->gt[1];
    *y = r->gt[3] + (row + 0.5) * r->gt[5];
}

/* An in-memory copy of grid with values (NAN -> NODATA) of type t and nb bands */
GDALDatasetH gf_terrain_mem_raster(const gf_raster *grid, int nx, int ny, int nb, GDALDataType t)
{
    GDALDriverH mem = GDALGetDriverByName("MEM");
    if (!mem)
        return NULL;
    GDALDatasetH ds = GDALCreate(mem, "", nx, ny, nb, t, NULL);
    if (ds && grid) {
        double gt[6];
        memcpy(gt, grid->gt, sizeof gt);
        GDALSetGeoTransform(ds, gt);
        if (grid->wkt && *grid->wkt)
            GDALSetProjection(ds, grid->wkt);
    }
    return ds;
}

gf_status gf_raster_write(const char *path, const char *driver, const gf_raster *grid,
                          const double *values)
{
    if (!path || !driver || !grid || !values)
        return gf_fail(GF_EINVAL, "gf_raster_write: null argument");
    gf_terrain_gdal_init();
    const int is_asc = strcmp(driver, "AAIGrid") == 0, is_tif = strcmp(driver, "GTiff") == 0;
    if (!is_asc && !is_tif)
        return gf_fail(GF_ENOTFOUND, "raster %s: driver %s; allowed AAIGrid or GTiff", path, driver);
    GDALDriverH drv = GDALGetDriverByName(driver);
    if (!drv)
        return gf_fail(GF_ENOTFOUND, "raster %s: GDAL has no %s driver", path, driver);
    const size_t n = (size_t)grid->nx * (size_t)grid->ny;
    double *buf = malloc(sizeof(double) * n);
    if (!buf)
        return gf_fail(GF_ENOMEM, "raster %s: out of memory", path);
    for (size_t i = 0; i < n; ++i)
        buf[i] = isfinite(values[i]) ? values[i] : grid->nodata;
    GDALDatasetH mem = gf_terrain_mem_raster(grid, grid->nx, grid->ny, 1, GDT_Float64);
    gf_status st = GF_SUCCESS;
    if (!mem) {
        st = gf_fail(GF_EIO, "raster %s: no in-memory dataset (%s)", path, gf_terrain_gdal_msg());
        goto done;
    }
    GDALRasterBandH b = GDALGetRasterBand(mem, 1);
    GDALSetRasterNoDataValue(b, grid->nodata);
    if (GDALRasterIO(b, GF_Write, 0, 0, grid->nx, grid->ny, buf, grid->nx, grid->ny, GDT_Float64, 0, 0)
        != CE_None) {
        st = gf_fail(GF_EIO, "raster %s: %s", path, gf_terrain_gdal_msg());
        goto done;
    }
    /* ESRI ASCII: 9 significant digits (float32 rasters are exact); GeoTIFF:
     * float64 */
    char *asc_opts[] = {"SIGNIFICANT_DIGITS=9", NULL};
    char *tif_opts[] = {"COMPRESS=DEFLATE", NULL};
    CPLErrorReset();
    CPLPushErrorHandler(CPLQuietErrorHandler);
    GDALDatasetH out = GDALCreateCopy(drv, path, mem, FALSE, is_asc ? asc_opts : tif_opts, NULL, NULL);
    CPLPopErrorHandler();
    if (!out)
        st = gf_fail(GF_EIO, "raster %s: GDAL cannot write it (%s)", path, gf_terrain_gdal_msg());
    else
        GDALClose(out);
done:
    if (mem)
        GDALClose(mem);
    free(buf);
    return st;
}

void gf_raster_extent(const gf_raster *r, double box[4])
{
    box[0] = r->gt[0], box[2] = r->gt[0] + r->nx * r->gt[1];
    box[3] = r->gt[3], box[1] = r->gt[3] + r->ny * r->gt[5];
}

int gf_box_overlap(const double a[4], const double b[4])
{
    return a[0] <= b[2] && b[0] <= a[2] && a[1] <= b[3] && b[1] <= a[3];
}

/*------------------------------------------------------------------- CRS --*/

/* a PROJ string without its +towgs84=... term */
static void proj_without_shift(const char *p, char *out, size_t n)
{
    size_t k = 0;
    while (*p && k + 1 < n) {
        if (strncmp(p, "+towgs84=", 9) == 0) {
            while (*p && *p != ' ')
                ++p;
            while (*p == ' ')
                ++p;
            continue;
        }
        out[k++] = *p++;
    }
    out[k] = '\0';
}

int gf_crs_same(const char *wkt_a, const char *wkt_b)
{
    if (!wkt_a || !wkt_b || !*wkt_a || !*wkt_b)
        return -1;
    gf_terrain_gdal_init();
    CPLPushErrorHandler(CPLQuietErrorHandler);
    OGRSpatialReferenceH a = OSRNewSpatialReference(wkt_a), b = OSRNewSpatialReference(wkt_b);
    CPLPopErrorHandler();
    int same = (a && b) ? (OSRIsSame(a, b) ? 1 : 0) : -1;
    if (same == 0) {
        /* the same projection written differently (an EPSG definition with
         * its own axis order and datum shift against the ESRI .prj of the
         * same grid): the same PROJ string without +towgs84 */
        char *pa = NULL, *pb = NULL;
        CPLPushErrorHandler(CPLQuietErrorHandler);
        if (OSRExportToProj4(a, &pa) == OGRERR_NONE && OSRExportToProj4(b, &pb) == OGRERR_NONE && pa && pb) {
            char qa[1024], qb[1024];
            proj_without_shift(pa, qa, sizeof qa);
            proj_without_shift(pb, qb, sizeof qb);
            same = strcmp(qa, qb) == 0;
        }
        CPLPopErrorHandler();
        CPLFree(pa);
        CPLFree(pb);
    }
    if (a)
        OSRDestroySpatialReference(a);
    if (b)
        OSRDestroySpatialReference(b);
    return same;
}

/*------------------------------------------------------------ mesh grid --*/

gf_status gf_terrain_grid_make(const gf_raster *dem, int k, const double *box,
                               const gf_polygons *crop, gf_terrain_grid *g)
{
    if (!dem || !g || !dem->z)
        return gf_fail(GF_EINVAL, "gf_terrain_grid_make: null argument");
    memset(g, 0, sizeof *g);
    const int kmax = (dem->nx < dem->ny ? dem->nx : dem->ny) - 1;
    if (k < 1 || k > kmax)
        return gf_fail(GF_EDOM, "coarsening %d is outside the allowed range [1, %d] for a %d x %d DEM",
                       k, kmax, dem->nx, dem->ny);
    if (box && !(box[0] < box[2] && box[1] < box[3]))
        return gf_fail(GF_EDOM, "crop box (%g %g %g %g): needs xmin < xmax and ymin < ymax",
                       box[0], box[1], box[2], box[3]);
    const int ni = (dem->nx - 1) / k + 1, nj = (dem->ny - 1) / k + 1;
    unsigned char *q = calloc((size_t)(ni - 1) * (size_t)(nj - 1), 1);
    if (!q)
        return gf_fail(GF_ENOMEM, "terrain grid: out of memory");
    int imin = ni, imax = -1, jmin = nj, jmax = -1;
    for (int J = 0; J + 1 < nj; ++J)
        for (int I = 0; I + 1 < ni; ++I) {
            const int c = I * k, r = J * k;
            const double *z = dem->z;
            const size_t nx = (size_t)dem->nx;
            if (isnan(z[r * nx + c]) || isnan(z[r * nx + c + k]) || isnan(z[(r + k) * nx + c]) ||
                isnan(z[(r + k) * nx + c + k]))
                continue;
            double x, y;
            gf_raster_centre(dem, c + 0.5 * k, r + 0.5 * k, &x, &y);
            if (box && (x < box[0] || x > box[2] || y < box[1] || y > box[3]))
                continue;
            if (crop && gf_polygons_locate(crop, x, y) < 0)
                continue;
            q[I + (size_t)(ni - 1) * J] = 1;
            imin = I < imin ? I : imin, imax = I > imax ? I : imax;
            jmin = J < jmin ? J : jmin, jmax = J > jmax ? J : jmax;
        }
    if (imax < 0) {
        free(q);
        return gf_fail(GF_EDOM, "terrain grid: no cell of the DEM is left (every cell touches"
                                " NODATA or lies outside the crop)");
    }
    /* the bounding range of the faces */
    g->k = k, g->c0 = imin * k, g->r0 = jmin * k;
    g->ni = imax - imin + 2, g->nj = jmax - jmin + 2;
    g->quad = calloc((size_t)(g->ni - 1) * (size_t)(g->nj - 1), 1);
    if (!g->quad) {
        free(q);
        return gf_fail(GF_ENOMEM, "terrain grid: out of memory");
    }
    for (int J = jmin; J <= jmax; ++J)
        for (int I = imin; I <= imax; ++I)
            if (q[I + (size_t)(ni - 1) * J]) {
                g->quad[(I - imin) + (size_t)(g->ni - 1) * (J - jmin)] = 1;
                ++g->n_quads;
            }
    free(q);
    return GF_SUCCESS;
}

void gf_terrain_grid_free(gf_terrain_grid *g)
{
    if (g) {
        free(g->quad);
        g->quad = NULL;
    }
}

void gf_terrain_node(const gf_raster *dem, const gf_terrain_grid *g, int I, int J, double xyz[3])
{
    const int c = g->c0 + g->k * I, r = g->r0 + g->k * J;
    gf_raster_centre(dem, c, r, xyz, xyz + 1);
    xyz[2] = dem->z[(size_t)r * (size_t)dem->nx + (size_t)c];
}

gf_status gf_terrain_to_raster(const gf_raster *dem, const gf_terrain_grid *g, size_t n,
                               const double *xy, const double *area, const double *val,
                               double *out)
{
    const size_t nq = (size_t)(g->ni - 1) * (size_t)(g->nj - 1);
    const size_t nn = (size_t)g->ni * (size_t)g->nj;
    double *sum = calloc(2 * nn, sizeof(double));
    unsigned char *seen = calloc(nq, 1);
    gf_status st = GF_SUCCESS;
    if (!sum || !seen) {
        st = gf_fail(GF_ENOMEM, "terrain raster: out of memory");
        goto done;
    }
    double *w = sum + nn;
    const double k = g->k;
    for (size_t f = 0; f < n; ++f) {
        const double col = (xy[2 * f] - dem->gt[0]) / dem->gt[1] - 0.5;
        const double row = (xy[2 * f + 1] - dem->gt[3]) / dem->gt[5] - 0.5;
        const double fi = floor((col - g->c0) / k), fj = floor((row - g->r0) / k);
        if (!(fi >= 0 && fi < g->ni - 1 && fj >= 0 && fj < g->nj - 1) ||
            !g->quad[(size_t)fi + (size_t)(g->ni - 1) * (size_t)fj] ||
            seen[(size_t)fi + (size_t)(g->ni - 1) * (size_t)fj]) {
            st = gf_fail(GF_EDOM, "terrain raster: face %zu (centre %.3f %.3f) is not on a face of"
                                  " the terrain grid, or shares it with another face: the mesh was"
                                  " not made from this DEM with this coarsening and crop",
                         f, xy[2 * f], xy[2 * f + 1]);
            goto done;
        }
        const int I = (int)fi, J = (int)fj;
        seen[I + (size_t)(g->ni - 1) * J] = 1;
        if (!isfinite(val[f]) || !(area[f] > 0)) {
            st = gf_fail(GF_ENONFINITE, "terrain raster: face %zu has value %g, area %g", f, val[f], area[f]);
            goto done;
        }
        for (int b = 0; b < 4; ++b) {
            const size_t node = (size_t)(I + (b & 1)) + (size_t)g->ni * (size_t)(J + (b >> 1));
            sum[node] += area[f] * val[f];
            w[node] += area[f];
        }
    }
    for (size_t i = 0; i < nn; ++i)
        sum[i] = w[i] > 0 ? sum[i] / w[i] : NAN;
    for (int r = 0; r < dem->ny; ++r)
        for (int c = 0; c < dem->nx; ++c) {
            double v = NAN;
            const double a = (c - g->c0) / k, b = (r - g->r0) / k;
            const int I = (int)floor(a), J = (int)floor(b);
            /* the quads that contain the pixel (two or four when it lies on a
             * grid line): the first face among them */
            for (int dj = 0; dj <= (b == J && J > 0) && isnan(v); ++dj)
                for (int di = 0; di <= (a == I && I > 0) && isnan(v); ++di) {
                    const int qi = I - di, qj = J - dj;
                    if (qi < 0 || qj < 0 || qi >= g->ni - 1 || qj >= g->nj - 1 ||
                        !seen[qi + (size_t)(g->ni - 1) * qj])
                        continue;
                    const double s = a - qi, t = b - qj;
                    const double *v0 = sum + qi + (size_t)g->ni * qj;
                    v = (1 - s) * (1 - t) * v0[0] + s * (1 - t) * v0[1] + (1 - s) * t * v0[g->ni] +
                        s * t * v0[g->ni + 1];
                }
            /* a pixel on the mesh's last row or column of nodes */
            if (isnan(v) && a == I && b == J && I >= 0 && J >= 0 && I < g->ni && J < g->nj)
                v = sum[I + (size_t)g->ni * J];
            out[(size_t)r * (size_t)dem->nx + (size_t)c] = v;
        }
done:
    free(sum);
    free(seen);
    return st;
}
