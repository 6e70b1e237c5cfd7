/* Real terrain through GDAL/OGR: see granflow/terrain.h. */
#include "granflow/terrain.h"
#include "granflow/path_analysis.h"
#include "granflow/constants.h"
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

void gf_terrain_gdal_init(void)
{
    static int done = 0;
    if (!done) {
        GDALAllRegister();
        done = 1;
    }
}

/* GDAL's last error text, or a fixed one */
static const char *gdal_msg(void)
{
    const char *m = CPLGetLastErrorMsg();
    return (m && *m) ? m : "no detail from GDAL";
}

static char *dup_str(const char *s)
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
        return gf_fail(GF_EIO, "DEM %s: not a raster GDAL can read (%s)", path, gdal_msg());
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
    r->wkt = dup_str(GDALGetProjectionRef(ds));
    r->z = malloc(sizeof(double) * (size_t)r->nx * (size_t)r->ny);
    if (!r->z || !r->wkt) {
        st = gf_fail(GF_ENOMEM, "DEM %s: out of memory for %d x %d cells", path, r->nx, r->ny);
        goto done;
    }
    if (GDALRasterIO(band, GF_Read, 0, 0, r->nx, r->ny, r->z, r->nx, r->ny, GDT_Float64, 0, 0) != CE_None) {
        st = gf_fail(GF_EIO, "DEM %s: reading the elevations failed (%s)", path, gdal_msg());
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
static GDALDatasetH mem_raster(const gf_raster *grid, int nx, int ny, int nb, GDALDataType t)
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
    GDALDatasetH mem = mem_raster(grid, grid->nx, grid->ny, 1, GDT_Float64);
    gf_status st = GF_SUCCESS;
    if (!mem) {
        st = gf_fail(GF_EIO, "raster %s: no in-memory dataset (%s)", path, gdal_msg());
        goto done;
    }
    GDALRasterBandH b = GDALGetRasterBand(mem, 1);
    GDALSetRasterNoDataValue(b, grid->nodata);
    if (GDALRasterIO(b, GF_Write, 0, 0, grid->nx, grid->ny, buf, grid->nx, grid->ny, GDT_Float64, 0, 0)
        != CE_None) {
        st = gf_fail(GF_EIO, "raster %s: %s", path, gdal_msg());
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
        st = gf_fail(GF_EIO, "raster %s: GDAL cannot write it (%s)", path, gdal_msg());
    else
        GDALClose(out);
done:
    if (mem)
        GDALClose(mem);
    free(buf);
    return st;
}

/*--------------------------------------------------------------- polygons --*/

typedef struct {
    double *d;
    size_t n, cap;
} dvec;
typedef struct {
    size_t *d;
    size_t n, cap;
} zvec;

/* room for one more element of size elem in the array *d of n of *cap */
static int grow(void **d, size_t n, size_t *cap, size_t elem)
{
    if (n < *cap)
        return 0;
    const size_t c = *cap ? 2 * *cap : 64;
    void *p = realloc(*d, c * elem);
    if (!p)
        return -1;
    *d = p, *cap = c;
    return 0;
}
static int dvec_push(dvec *v, double x)
{
    if (grow((void **)&v->d, v->n, &v->cap, sizeof *v->d))
        return -1;
    v->d[v->n++] = x;
    return 0;
}
static int zvec_push(zvec *v, size_t x)
{
    if (grow((void **)&v->d, v->n, &v->cap, sizeof *v->d))
        return -1;
    v->d[v->n++] = x;
    return 0;
}

/* Open a vector file (OGR) for reading; NULL with the failure in *st
 * (GF_EIO naming what and the file) */
GDALDatasetH gf_terrain_open_vector(const char *what, const char *path, gf_status *st)
{
    *st = GF_SUCCESS;
    if (access(path, R_OK) != 0) {
        *st = gf_fail(GF_EIO, "%s %s: no such file or not readable", what, path);
        return NULL;
    }
    CPLErrorReset();
    CPLPushErrorHandler(CPLQuietErrorHandler);
    GDALDatasetH ds = GDALOpenEx(path, GDAL_OF_VECTOR | GDAL_OF_READONLY, NULL, NULL, NULL);
    CPLPopErrorHandler();
    if (!ds)
        *st = gf_fail(GF_EIO, "%s %s: not a vector file OGR can read (%s)", what, path, gdal_msg());
    return ds;
}

/* Append polygon g (wkbPolygon) with value v */
static int add_polygon(OGRGeometryH g, double v, zvec *ring0, zvec *pt0, dvec *xy, dvec *val, dvec *box)
{
    const int nr = OGR_G_GetGeometryCount(g);
    if (nr < 1)
        return 0; /* empty polygon: nothing */
    if (zvec_push(ring0, pt0->n) || dvec_push(val, v))
        return -1;
    double b[4] = {HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (int r = 0; r < nr; ++r) {
        OGRGeometryH ring = OGR_G_GetGeometryRef(g, r);
        const int np = OGR_G_GetPointCount(ring);
        if (zvec_push(pt0, xy->n / 2))
            return -1;
        for (int i = 0; i < np; ++i) {
            const double x = OGR_G_GetX(ring, i), y = OGR_G_GetY(ring, i);
            if (dvec_push(xy, x) || dvec_push(xy, y))
                return -1;
            if (r == 0) {
                b[0] = fmin(b[0], x), b[1] = fmin(b[1], y);
                b[2] = fmax(b[2], x), b[3] = fmax(b[3], y);
            }
        }
    }
    for (int i = 0; i < 4; ++i)
        if (dvec_push(box, b[i]))
            return -1;
    return 0;
}

gf_status gf_polygons_read(const char *path, const char *attribute, double value, gf_polygons *p)
{
    if (!path || !p)
        return gf_fail(GF_EINVAL, "gf_polygons_read: null argument");
    memset(p, 0, sizeof *p);
    gf_terrain_gdal_init();
    if (!attribute && !(isfinite(value) && value >= 0.0))
        return gf_fail(GF_EDOM, "polygons %s: value %g must be finite and >= 0", path, value);
    gf_status opened;
    GDALDatasetH ds = gf_terrain_open_vector("polygons", path, &opened);
    if (!ds)
        return opened;
    gf_status st = GF_SUCCESS;
    zvec ring0 = {0}, pt0 = {0};
    dvec xy = {0}, val = {0}, box = {0};
    OGRLayerH L = GDALDatasetGetLayerCount(ds) > 0 ? GDALDatasetGetLayer(ds, 0) : NULL;
    if (!L) {
        st = gf_fail(GF_EDOM, "polygons %s: no layer", path);
        goto done;
    }
    OGRFeatureDefnH defn = OGR_L_GetLayerDefn(L);
    int fi = -1;
    if (attribute) {
        fi = OGR_FD_GetFieldIndex(defn, attribute);
        const OGRFieldType t = fi >= 0 ? OGR_Fld_GetType(OGR_FD_GetFieldDefn(defn, fi)) : OFTString;
        if (fi < 0 || (t != OFTReal && t != OFTInteger && t != OFTInteger64)) {
            char fields[256] = "";
            for (int i = 0; i < OGR_FD_GetFieldCount(defn); ++i) {
                const size_t l = strlen(fields);
                snprintf(fields + l, sizeof fields - l, "%s%s", i ? ", " : "",
                         OGR_Fld_GetNameRef(OGR_FD_GetFieldDefn(defn, i)));
            }
            st = gf_fail(GF_ENOTFOUND, "polygons %s: %s attribute '%s'; the numeric attributes"
                                       " to choose from are among: %s", path,
                         fi < 0 ? "no" : "non-numeric", attribute, fields[0] ? fields : "(none)");
            goto done;
        }
    }
    OGRSpatialReferenceH srs = OGR_L_GetSpatialRef(L);
    if (srs) {
        char *w = NULL;
        OSRExportToWkt(srs, &w);
        p->wkt = dup_str(w);
        CPLFree(w);
    } else
        p->wkt = dup_str("");
    OGR_L_ResetReading(L);
    OGRFeatureH f;
    while ((f = OGR_L_GetNextFeature(L)) != NULL) {
        const long fid = (long)OGR_F_GetFID(f);
        double v = value;
        if (fi >= 0) {
            if (!OGR_F_IsFieldSetAndNotNull(f, fi)) {
                st = gf_fail(GF_EDOM, "polygons %s: feature %ld has no %s value", path, fid, attribute);
                OGR_F_Destroy(f);
                goto done;
            }
            v = OGR_F_GetFieldAsDouble(f, fi);
            if (!isfinite(v) || v < 0.0) {
                st = gf_fail(GF_EDOM, "polygons %s: feature %ld has %s = %g; it must be finite"
                                      " and >= 0", path, fid, attribute, v);
                OGR_F_Destroy(f);
                goto done;
            }
        }
        OGRGeometryH g = OGR_F_GetGeometryRef(f);
        const OGRwkbGeometryType t = g ? wkbFlatten(OGR_G_GetGeometryType(g)) : wkbNone;
        int bad = 0;
        if (t == wkbPolygon)
            bad = add_polygon(g, v, &ring0, &pt0, &xy, &val, &box);
        else if (t == wkbMultiPolygon) {
            for (int k = 0; k < OGR_G_GetGeometryCount(g) && !bad; ++k)
                bad = add_polygon(OGR_G_GetGeometryRef(g, k), v, &ring0, &pt0, &xy, &val, &box);
        } else {
            st = gf_fail(GF_EDOM, "polygons %s: feature %ld is a %s, not a polygon", path, fid,
                         g ? OGRGeometryTypeToName(t) : "feature without geometry");
            OGR_F_Destroy(f);
            goto done;
        }
        OGR_F_Destroy(f);
        if (bad) {
            st = gf_fail(GF_ENOMEM, "polygons %s: out of memory", path);
            goto done;
        }
    }
    if (val.n == 0) {
        st = gf_fail(GF_EDOM, "polygons %s: no polygon in its first layer", path);
        goto done;
    }
    p->n = val.n;
    if (zvec_push(&ring0, pt0.n) || zvec_push(&pt0, xy.n / 2)) {
        st = gf_fail(GF_ENOMEM, "polygons %s: out of memory", path);
        goto done;
    }
    p->ring0 = ring0.d, p->pt0 = pt0.d, p->xy = xy.d, p->value = val.d, p->box = box.d;
    ring0.d = pt0.d = NULL, xy.d = val.d = box.d = NULL;
done:
    free(ring0.d), free(pt0.d), free(xy.d), free(val.d), free(box.d);
    GDALClose(ds);
    if (st)
        gf_polygons_free(p);
    return st;
}

void gf_polygons_free(gf_polygons *p)
{
    if (!p)
        return;
    free(p->ring0), free(p->pt0), free(p->xy), free(p->value), free(p->box), free(p->wkt);
    memset(p, 0, sizeof *p);
}

/* even-odd crossing count of the rings of polygon k */
static int inside(const gf_polygons *p, size_t k, double x, double y)
{
    const double *b = p->box + 4 * k;
    if (x < b[0] || x > b[2] || y < b[1] || y > b[3])
        return 0;
    int in = 0;
    for (size_t r = p->ring0[k]; r < p->ring0[k + 1]; ++r) {
        const size_t a = p->pt0[r], e = p->pt0[r + 1];
        for (size_t i = a, j = e - 1; i < e; j = i++) {
            const double xi = p->xy[2 * i], yi = p->xy[2 * i + 1];
            const double xj = p->xy[2 * j], yj = p->xy[2 * j + 1];
            if ((yi > y) != (yj > y) && x < xj + (y - yj) * (xi - xj) / (yi - yj))
                in = !in;
        }
    }
    return in;
}

long gf_polygons_locate(const gf_polygons *p, double x, double y)
{
    for (size_t k = p->n; k-- > 0;)
        if (inside(p, k, x, y))
            return (long)k;
    return -1;
}

double gf_polygons_area(const gf_polygons *p, size_t k)
{
    double area = 0.0;
    for (size_t r = p->ring0[k]; r < p->ring0[k + 1]; ++r) {
        const size_t a = p->pt0[r], e = p->pt0[r + 1];
        double s = 0.0;
        for (size_t i = a, j = e - 1; i < e; j = i++)
            s += p->xy[2 * j] * p->xy[2 * i + 1] - p->xy[2 * i] * p->xy[2 * j + 1];
        area += (r == p->ring0[k] ? 1.0 : -1.0) * fabs(0.5 * s);
    }
    return area;
}

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
    *mem = mem_raster(grid, grid->nx, grid->ny, 1, t);
    if (!*mem)
        return gf_fail(GF_EIO, "%s %s: %s", what, path, gdal_msg());
    *band = GDALGetRasterBand(*mem, 1);
    if (GDALRasterIO(*band, GF_Write, 0, 0, grid->nx, grid->ny, values, grid->nx, grid->ny, t, 0, 0) != CE_None)
        return gf_fail(GF_EIO, "%s %s: %s", what, path, gdal_msg());
    if (grid->wkt && *grid->wkt)
        *srs = geojson_srs(grid->wkt);
    GDALDriverH vdrv = GDALGetDriverByName("Memory"), gj = GDALGetDriverByName("GeoJSON");
    *vmem = vdrv ? GDALCreate(vdrv, "", 0, 0, 0, GDT_Unknown, NULL) : NULL;
    if (!*vmem || !gj)
        return gf_fail(GF_EIO, "%s %s: GDAL lacks the Memory or GeoJSON driver", what, path);
    *ml = GDALDatasetCreateLayer(*vmem, layer, *srs, gtype, NULL);
    return *ml ? GF_SUCCESS : gf_fail(GF_EIO, "%s %s: %s", what, path, gdal_msg());
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
    GDALRasterBandH b = NULL;
    OGRLayerH ml = NULL;
    OGRSpatialReferenceH srs = NULL;
    GDALDriverH gj = GDALGetDriverByName("GeoJSON");
    gf_status st = band_and_layer("outline", path, grid, mask, GDT_Byte, "mask", wkbPolygon, &mem, &b, &vmem, &ml, &srs);
    if (st)
        goto done;
    OGRFieldDefnH fd = OGR_Fld_Create("value", OFTInteger);
    OGR_L_CreateField(ml, fd, TRUE);
    OGR_Fld_Destroy(fd);
    /* the mask band as its own mask: only the affected pixels become polygons */
    if (GDALPolygonize(b, b, ml, 0, NULL, NULL, NULL) != CE_None) {
        st = gf_fail(GF_EIO, "outline %s: polygonize failed (%s)", path, gdal_msg());
        goto done;
    }
    unlink(path);
    CPLPushErrorHandler(CPLQuietErrorHandler);
    out = GDALCreate(gj, path, 0, 0, 0, GDT_Unknown, NULL);
    CPLPopErrorHandler();
    if (!out) {
        st = gf_fail(GF_EIO, "outline %s: GDAL cannot write it (%s)", path, gdal_msg());
        goto done;
    }
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
            st = gf_fail(GF_EIO, "outline %s: writing a polygon failed (%s)", path, gdal_msg());
            goto done;
        }
    }
done:
    close_band_and_layer(out, vmem, mem, srs);
    free(mask);
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
        st = gf_fail(GF_EIO, "line %s: GDAL cannot write it (%s)", path, gdal_msg());
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
        st = gf_fail(GF_EIO, "line %s: writing the feature failed (%s)", path, gdal_msg());
    OGR_F_Destroy(f);
done:
    if (out)
        GDALClose(out);
    if (srs)
        OSRDestroySpatialReference(srs);
    return st;
}


/*------------------------------------------------------------------- dams --*/
/* mass-exchange specification, section 3 "Dams"; see granflow/terrain.h */

void gf_dam_free(gf_dam *d)
{
    if (!d)
        return;
    free(d->xyz);
    free(d->wkt);
    memset(d, 0, sizeof *d);
}

OGRFeatureH gf_terrain_first_feature(GDALDatasetH ds, const char *what, const char *path, gf_status *st)
{
    OGRLayerH L = GDALDatasetGetLayerCount(ds) > 0 ? GDALDatasetGetLayer(ds, 0) : NULL;
    OGRFeatureH f = NULL;
    if (L) {
        OGR_L_ResetReading(L);
        f = OGR_L_GetNextFeature(L);
    }
    if (!f)
        *st = gf_fail(GF_EDOM, "%s %s: no feature in its first layer", what, path);
    return f;
}

OGRGeometryH gf_terrain_single_line(OGRGeometryH g, OGRwkbGeometryType *t)
{
    *t = g ? wkbFlatten(OGR_G_GetGeometryType(g)) : wkbNone;
    if (*t == wkbMultiLineString && OGR_G_GetGeometryCount(g) == 1) {
        g = OGR_G_GetGeometryRef(g, 0);
        *t = wkbFlatten(OGR_G_GetGeometryType(g));
    }
    return g;
}

static int slope_ok(double s) { return isfinite(s) && s > 0.0 && s < 90.0; }

gf_status gf_dam_read(const char *path, const char *slope_attribute, double slope_default,
                      gf_dam *d)
{
    if (!path || !d)
        return gf_fail(GF_EINVAL, "gf_dam_read: null argument");
    memset(d, 0, sizeof *d);
    gf_terrain_gdal_init();
    gf_status opened;
    GDALDatasetH ds = gf_terrain_open_vector("dam", path, &opened);
    if (!ds)
        return opened;
    gf_status st = GF_SUCCESS;
    OGRFeatureH f = gf_terrain_first_feature(ds, "dam", path, &st);
    if (!f)
        goto done;
    OGRLayerH L = GDALDatasetGetLayer(ds, 0);
    const long fid = (long)OGR_F_GetFID(f);
    OGRwkbGeometryType t;
    OGRGeometryH g = gf_terrain_single_line(OGR_F_GetGeometryRef(f), &t);
    if (t != wkbLineString) {
        st = gf_fail(GF_EDOM, "dam %s: feature %ld is a %s, not a line (the dam's crown is one"
                              " 3D line)", path, fid,
                     g ? OGRGeometryTypeToName(t) : "feature without geometry");
        goto done;
    }
    const int np = OGR_G_GetPointCount(g);
    if (np < 2) {
        st = gf_fail(GF_EDOM, "dam %s: feature %ld has %d point(s); a crown line needs at least 2",
                     path, fid, np);
        goto done;
    }
    if (!OGR_G_Is3D(g)) {
        st = gf_fail(GF_EDOM, "dam %s: feature %ld is a 2D line without heights; the crown line"
                              " needs z (the crown's elevation) at each point (specification,"
                              " section 3)", path, fid);
        goto done;
    }
    double slope = slope_default;
    const char *from = "default";
    OGRFeatureDefnH defn = OGR_L_GetLayerDefn(L);
    const int fi = slope_attribute ? OGR_FD_GetFieldIndex(defn, slope_attribute) : -1;
    if (fi >= 0 && OGR_F_IsFieldSetAndNotNull(f, fi)) {
        const OGRFieldType ft = OGR_Fld_GetType(OGR_FD_GetFieldDefn(defn, fi));
        if (ft != OFTReal && ft != OFTInteger && ft != OFTInteger64) {
            st = gf_fail(GF_EDOM, "dam %s: attribute '%s' is not numeric", path, slope_attribute);
            goto done;
        }
        slope = OGR_F_GetFieldAsDouble(f, fi);
        from = slope_attribute;
    }
    if (isnan(slope)) {
        st = gf_fail(GF_EDOM, "dam %s: feature %ld has no wall slope (attribute '%s') and none"
                              " is given", path, fid, slope_attribute ? slope_attribute : "");
        goto done;
    }
    if (!slope_ok(slope)) {
        st = gf_fail(GF_EDOM, "dam %s: wall slope %g deg (%s) outside (0, 90) deg", path, slope,
                     from);
        goto done;
    }
    d->xyz = malloc(3 * (size_t)np * sizeof *d->xyz);
    if (!d->xyz) {
        st = gf_fail(GF_ENOMEM, "dam %s: out of memory", path);
        goto done;
    }
    for (int i = 0; i < np; ++i) {
        double *q = d->xyz + 3 * i;
        OGR_G_GetPoint(g, i, q, q + 1, q + 2);
        if (!isfinite(q[0]) || !isfinite(q[1]) || !isfinite(q[2])) {
            st = gf_fail(GF_EDOM, "dam %s: feature %ld, point %d has no finite height (%g %g %g);"
                                  " the crown line needs z at each point", path, fid, i, q[0],
                         q[1], q[2]);
            goto done;
        }
    }
    d->n = (size_t)np;
    d->slope = slope;
    OGRSpatialReferenceH srs = OGR_L_GetSpatialRef(L);
    char *w = NULL;
    if (srs)
        OSRExportToWkt(srs, &w);
    d->wkt = dup_str(w);
    CPLFree(w);
done:
    if (f)
        OGR_F_Destroy(f);
    GDALClose(ds);
    if (st)
        gf_dam_free(d);
    return st;
}

/* does segment a-b meet the box [x0, x1] x [y0, y1] (Liang-Barsky) */
static int segment_meets_box(const double *a, const double *b, double x0, double x1, double y0,
                             double y1)
{
    const double dx = b[0] - a[0], dy = b[1] - a[1];
    const double p[4] = {-dx, dx, -dy, dy};
    const double q[4] = {a[0] - x0, x1 - a[0], a[1] - y0, y1 - a[1]};
    double t0 = 0.0, t1 = 1.0;
    for (int k = 0; k < 4; ++k) {
        if (p[k] == 0.0) {
            if (q[k] < 0.0)
                return 0;
        } else {
            const double r = q[k] / p[k];
            if (p[k] < 0.0)
                t0 = r > t0 ? r : t0;
            else
                t1 = r < t1 ? r : t1;
            if (t0 > t1)
                return 0;
        }
    }
    return 1;
}

gf_status gf_dam_burn(gf_raster *dem, size_t n, const double *xyz, double slope,
                      size_t *n_raised, double *max_rise)
{
    if (!dem || !dem->z || (n && !xyz))
        return gf_fail(GF_EINVAL, "gf_dam_burn: null argument");
    if (n < 2)
        return gf_fail(GF_EDOM, "dam: %zu point(s); a crown line needs at least 2", n);
    if (!slope_ok(slope))
        return gf_fail(GF_EDOM, "dam: wall slope %g deg outside (0, 90) deg", slope);
    double bx0 = INFINITY, bx1 = -INFINITY, by0 = INFINITY, by1 = -INFINITY, zc = -INFINITY;
    for (size_t i = 0; i < n; ++i) {
        const double *q = xyz + 3 * i;
        if (!isfinite(q[0]) || !isfinite(q[1]) || !isfinite(q[2]))
            return gf_fail(GF_EDOM, "dam: point %zu (%g %g %g) is not finite; the crown line"
                                    " needs x, y and its height z at each point", i, q[0], q[1],
                           q[2]);
        bx0 = fmin(bx0, q[0]), bx1 = fmax(bx1, q[0]);
        by0 = fmin(by0, q[1]), by1 = fmax(by1, q[1]);
        zc = fmax(zc, q[2]);
    }
    const double ex0 = dem->gt[0], ex1 = dem->gt[0] + dem->nx * dem->gt[1];
    const double ey1 = dem->gt[3], ey0 = dem->gt[3] + dem->ny * dem->gt[5];
    int touches = 0;
    for (size_t i = 0; i + 1 < n && !touches; ++i)
        touches = segment_meets_box(xyz + 3 * i, xyz + 3 * i + 3, ex0, ex1, ey0, ey1);
    if (!touches)
        return gf_fail(GF_EDOM, "dam: the crown line (x %g .. %g, y %g .. %g) lies entirely"
                                " outside the DEM (x %g .. %g, y %g .. %g)", bx0, bx1, by0, by1,
                       ex0, ex1, ey0, ey1);
    const size_t npx = (size_t)dem->nx * (size_t)dem->ny;
    double zmin = INFINITY;
    for (size_t i = 0; i < npx; ++i)
        if (isfinite(dem->z[i]))
            zmin = fmin(zmin, dem->z[i]);
    const double tb = tan(slope * GF_DEG);
    /* no pixel farther than reach from the line is raised */
    const double reach = zc > zmin ? (zc - zmin) / tb + dem->gt[1] : 0.0;
    int c0 = (int)floor((bx0 - reach - dem->gt[0]) / dem->gt[1]);
    int c1 = (int)ceil((bx1 + reach - dem->gt[0]) / dem->gt[1]);
    int r0 = (int)floor((by1 + reach - dem->gt[3]) / dem->gt[5]);
    int r1 = (int)ceil((by0 - reach - dem->gt[3]) / dem->gt[5]);
    c0 = c0 < 0 ? 0 : c0, r0 = r0 < 0 ? 0 : r0;
    c1 = c1 > dem->nx - 1 ? dem->nx - 1 : c1, r1 = r1 > dem->ny - 1 ? dem->ny - 1 : r1;
    size_t raised = 0;
    double rise = 0.0;
    for (int r = r0; r <= r1; ++r)
        for (int c = c0; c <= c1; ++c) {
            double *z = dem->z + (size_t)r * dem->nx + c;
            if (!isfinite(*z))
                continue;
            double x, y;
            gf_raster_centre(dem, c, r, &x, &y);
            double best = INFINITY, zline = 0.0;
            for (size_t i = 0; i + 1 < n; ++i) {
                const double *a = xyz + 3 * i, *b = a + 3;
                const double ux = b[0] - a[0], uy = b[1] - a[1], L2 = ux * ux + uy * uy;
                double t = L2 > 0.0 ? ((x - a[0]) * ux + (y - a[1]) * uy) / L2 : 0.0;
                t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
                const double dx = x - a[0] - t * ux, dy = y - a[1] - t * uy;
                const double d2 = dx * dx + dy * dy;
                if (d2 < best)
                    best = d2, zline = a[2] + t * (b[2] - a[2]);
            }
            const double s = zline - tb * sqrt(best);
            if (s > *z) {
                rise = fmax(rise, s - *z);
                *z = s;
                ++raised;
            }
        }
    if (n_raised)
        *n_raised = raised;
    if (max_rise)
        *max_rise = rise;
    return GF_SUCCESS;
}

/*------------------------------------------------------------------- map --*/

static void ramp(double t, double rgb[3])
{
    static const double stop[4][3] = {{1.0, 1.0, 0.55}, {1.0, 0.7, 0.0}, {0.85, 0.1, 0.1}, {0.4, 0.0, 0.45}};
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    const double s = 3.0 * t;
    const int i = s >= 3.0 ? 2 : (int)s;
    const double u = s - i;
    for (int c = 0; c < 3; ++c)
        rgb[c] = (1 - u) * stop[i][c] + u * stop[i + 1][c];
}

/* A 3 x 5 pixel font for the scale's numbers: digits, '.', '-', '+', 'e' */
static const char *glyph(char ch)
{
    switch (ch) {
    case '0': return "111101101101111";
    case '1': return "010110010010111";
    case '2': return "111001111100111";
    case '3': return "111001111001111";
    case '4': return "101101111001001";
    case '5': return "111100111001111";
    case '6': return "111100111101111";
    case '7': return "111001001001001";
    case '8': return "111101111101111";
    case '9': return "111101111001111";
    case '.': return "000000000000010";
    case '-': return "000000111000000";
    case '+': return "000010111010000";
    case 'e': return "000111111100111";
    default: return "000000000000000";
    }
}

static int text_width(const char *t, int fs) { return (int)strlen(t) * 4 * fs - fs; }

/* black text with its top-left corner at (x, y), pixels scaled by fs */
static void draw_text(unsigned char *img, int nx, int H, int x, int y, const char *t, int fs)
{
    const size_t np = (size_t)nx * (size_t)H;
    for (; *t; ++t, x += 4 * fs) {
        const char *g = glyph(*t);
        for (int r = 0; r < 5 * fs; ++r)
            for (int c = 0; c < 3 * fs; ++c)
                if (g[(r / fs) * 3 + c / fs] == '1' && x + c >= 0 && x + c < nx && y + r < H)
                    for (int k = 0; k < 3; ++k)
                        img[k * np + (size_t)(y + r) * nx + (x + c)] = 0;
    }
}

gf_status gf_raster_png(const char *path, const gf_raster *dem, const double *values,
                        double vmin, double vmax)
{
    gf_terrain_gdal_init();
    if (!(vmax > vmin) || !isfinite(vmin) || !isfinite(vmax))
        return gf_fail(GF_EDOM, "map %s: colour range [%g, %g] is empty or not finite", path, vmin, vmax);
    /* below the map: the colour bar, then vmin and vmax at its ends */
    const int nx = dem->nx, ny = dem->ny, bar = ny / 40 + 4, fs = nx >= 300 ? 2 : 1;
    const int H = ny + 2 + bar + 3 + 5 * fs + 2;
    const size_t np = (size_t)nx * (size_t)H;
    unsigned char *img = malloc(3 * np);
    if (!img)
        return gf_fail(GF_ENOMEM, "map %s: out of memory", path);
    const double d = dem->gt[1], deg = acos(-1.0) / 180.0;
    const double alt = 45 * deg, az = 315 * deg;
    const double L[3] = {cos(alt) * sin(az), cos(alt) * cos(az), sin(alt)};
    const double *z = dem->z;
    /* contour lines: about ten over the elevation range, at 1, 2 or 5 x 10^n m */
    double zlo = HUGE_VAL, zhi = -HUGE_VAL;
    for (size_t i = 0; i < (size_t)nx * ny; ++i)
        if (!isnan(z[i]))
            zlo = fmin(zlo, z[i]), zhi = fmax(zhi, z[i]);
    double dz = pow(10.0, floor(log10(fmax(zhi - zlo, 1e-3) / 10.0)));
    dz *= (zhi - zlo) / dz > 50 ? 5 : (zhi - zlo) / dz > 20 ? 2 : 1;
    for (int r = 0; r < ny; ++r)
        for (int c = 0; c < nx; ++c) {
            const size_t i = (size_t)r * nx + c;
            double rgb[3] = {1, 1, 1};
            if (!isnan(z[i])) {
                /* one-sided differences next to the edge or NODATA */
                const int cl = c > 0 && !isnan(z[i - 1]) ? c - 1 : c, cr = c + 1 < nx && !isnan(z[i + 1]) ? c + 1 : c;
                const int ru = r > 0 && !isnan(z[i - nx]) ? r - 1 : r, rd = r + 1 < ny && !isnan(z[i + nx]) ? r + 1 : r;
                const double zx = cr > cl ? (z[(size_t)r * nx + cr] - z[(size_t)r * nx + cl]) / ((cr - cl) * d) : 0;
                /* rows run southwards: north is towards smaller r */
                const double zy = rd > ru ? (z[(size_t)ru * nx + c] - z[(size_t)rd * nx + c]) / ((rd - ru) * d) : 0;
                const double nl = sqrt(zx * zx + zy * zy + 1);
                double shade = (-zx * L[0] - zy * L[1] + L[2]) / nl;
                shade = shade < 0 ? 0 : shade;
                double grey = 0.25 + 0.75 * shade;
                /* a contour between this pixel and its east or south neighbour */
                const double band = floor(z[i] / dz);
                if ((c + 1 < nx && !isnan(z[i + 1]) && floor(z[i + 1] / dz) != band) ||
                    (r + 1 < ny && !isnan(z[i + nx]) && floor(z[i + nx] / dz) != band))
                    grey *= 0.7;
                rgb[0] = rgb[1] = rgb[2] = grey;
                if (isfinite(values[i]) && values[i] >= vmin) {
                    double col[3];
                    ramp((values[i] - vmin) / (vmax - vmin), col);
                    for (int k = 0; k < 3; ++k)
                        rgb[k] = col[k] * (0.45 + 0.55 * shade);
                }
            }
            for (int k = 0; k < 3; ++k)
                img[k * np + i] = (unsigned char)lround(255 * rgb[k]);
        }
    for (int r = ny; r < H; ++r)
        for (int c = 0; c < nx; ++c) {
            double col[3] = {1, 1, 1};
            if (r >= ny + 2 && r < ny + 2 + bar)
                ramp((double)c / (nx - 1), col);
            for (int k = 0; k < 3; ++k)
                img[k * np + (size_t)r * nx + c] = (unsigned char)lround(255 * col[k]);
        }
    char lo[32], hi[32];
    snprintf(lo, sizeof lo, "%.3g", vmin);
    snprintf(hi, sizeof hi, "%.3g", vmax);
    const int ty = ny + 2 + bar + 3;
    draw_text(img, nx, H, 1, ty, lo, fs);
    draw_text(img, nx, H, nx - 1 - text_width(hi, fs), ty, hi, fs);
    gf_status st = GF_SUCCESS;
    GDALDatasetH mem = mem_raster(NULL, nx, H, 3, GDT_Byte), out = NULL;
    GDALDriverH png = GDALGetDriverByName("PNG");
    if (!mem || !png) {
        st = gf_fail(GF_EIO, "map %s: GDAL lacks the MEM or PNG driver", path);
        goto done;
    }
    if (GDALDatasetRasterIO(mem, GF_Write, 0, 0, nx, H, img, nx, H, GDT_Byte, 3, NULL, 0, 0, 0) != CE_None) {
        st = gf_fail(GF_EIO, "map %s: %s", path, gdal_msg());
        goto done;
    }
    CPLPushErrorHandler(CPLQuietErrorHandler);
    out = GDALCreateCopy(png, path, mem, FALSE, NULL, NULL, NULL);
    CPLPopErrorHandler();
    if (!out)
        st = gf_fail(GF_EIO, "map %s: GDAL cannot write it (%s)", path, gdal_msg());
done:
    if (out)
        GDALClose(out);
    if (mem)
        GDALClose(mem);
    free(img);
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
            char why[512];
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
        st = gf_fail(GF_EIO, "contours %s: contouring failed (%s)", what, gdal_msg());
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
            st = gf_fail(GF_EIO, "contours %s: GDAL cannot write it (%s)", geojson, gdal_msg());
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
                st = gf_fail(GF_EIO, "contours %s: writing a line failed (%s)", geojson, gdal_msg());
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
