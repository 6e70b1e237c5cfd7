/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Real terrain through GDAL/OGR (see granflow/terrain.h): vector files (OGR),
 * polygons with a value each, and dams (the crown line read, then burnt into
 * the DEM); the vector helpers path_analysis.c shares (terrain_internal.h). */
#include "granflow/terrain.h"
#include "granflow/constants.h"
#include "internal.h"
#include "terrain_internal.h"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal.h>
#include <ogr_api.h>
#include <ogr_srs_api.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

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
        *st = gf_fail(GF_EIO, "%s %s: not a vector file OGR can read (%s)", what, path, gf_terrain_gdal_msg());
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

/* Is field `field` of layer definition defn numeric (integer or real)?  The
 * refusals of gf_vector_field_numeric, naming path and the field. */
static gf_status numeric_field(OGRFeatureDefnH defn, const char *path, const char *field,
                               const char *need)
{
    if (!need)
        need = "a number";
    const int fi = OGR_FD_GetFieldIndex(defn, field);
    if (fi < 0) {
        char fields[512] = "";
        for (int i = 0; i < OGR_FD_GetFieldCount(defn); ++i) {
            OGRFieldDefnH d = OGR_FD_GetFieldDefn(defn, i);
            const OGRFieldType t = OGR_Fld_GetType(d);
            if (t != OFTReal && t != OFTInteger && t != OFTInteger64)
                continue;
            const size_t l = strlen(fields);
            snprintf(fields + l, sizeof fields - l, "%s%s", l ? ", " : "", OGR_Fld_GetNameRef(d));
        }
        return gf_fail(GF_ENOTFOUND, "%s: no attribute '%s'; %s is needed there (the numeric"
                                     " attributes of the file: %s)", path, field, need,
                       fields[0] ? fields : "none");
    }
    const OGRFieldType t = OGR_Fld_GetType(OGR_FD_GetFieldDefn(defn, fi));
    if (t == OFTReal || t == OFTInteger || t == OFTInteger64)
        return GF_SUCCESS;
    if (t == OFTString)
        return gf_fail(GF_EDOM, "field '%s' of %s is a text field (String); %s is needed", field,
                       path, need);
    return gf_fail(GF_EDOM, "field '%s' of %s is a %s field, not a number; %s is needed", field,
                   path, OGR_GetFieldTypeName(t), need);
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
        if ((st = numeric_field(defn, path, attribute, NULL)) != GF_SUCCESS)
            goto done;
        fi = OGR_FD_GetFieldIndex(defn, attribute);
    }
    OGRSpatialReferenceH srs = OGR_L_GetSpatialRef(L);
    if (srs) {
        char *w = NULL;
        OSRExportToWkt(srs, &w);
        p->wkt = gf_terrain_dup_str(w);
        CPLFree(w);
    } else
        p->wkt = gf_terrain_dup_str("");
    OGR_L_ResetReading(L);
    OGRFeatureH f;
    while ((f = OGR_L_GetNextFeature(L)) != NULL) {
        const long fid = (long)OGR_F_GetFID(f);
        double v = value;
        if (fi >= 0) {
            if (!OGR_F_IsFieldSetAndNotNull(f, fi)) {
                st = gf_fail(GF_EDOM, "polygons %s: feature %ld has no %s value (the field is empty"
                                      " there); give every polygon its value", path, fid, attribute);
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

/*------------------------------------------------------------------- dams --*/
/* doc/theory/mass-exchange.md, section 3 "Dams"; see granflow/terrain.h */

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
                              " needs z (the crown's elevation) at each point (doc/theory/mass-exchange.md,"
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
    d->wkt = gf_terrain_dup_str(w);
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

/*----------------------------------------------------- checks of inputs --*/

/* A vector file opened with its first layer (the layer the readers above
 * take); NULL with *st set when it cannot be opened or has no layer. */
static GDALDatasetH open_first_layer(const char *path, OGRLayerH *L, gf_status *st)
{
    gf_terrain_gdal_init();
    GDALDatasetH ds = gf_terrain_open_vector("vector file", path, st);
    if (!ds)
        return NULL;
    *L = GDALDatasetGetLayerCount(ds) > 0 ? GDALDatasetGetLayer(ds, 0) : NULL;
    if (!*L) {
        *st = gf_fail(GF_EDOM, "vector file %s: no layer", path);
        GDALClose(ds);
        return NULL;
    }
    *st = GF_SUCCESS;
    return ds;
}

gf_status gf_vector_crs(const char *path, char **wkt)
{
    if (!path || !wkt)
        return gf_fail(GF_EINVAL, "gf_vector_crs: null argument");
    *wkt = NULL;
    gf_status st;
    OGRLayerH L;
    GDALDatasetH ds = open_first_layer(path, &L, &st);
    if (!ds)
        return st;
    OGRSpatialReferenceH srs = OGR_L_GetSpatialRef(L);
    char *w = NULL;
    if (srs)
        OSRExportToWkt(srs, &w);
    *wkt = gf_terrain_dup_str(w);
    CPLFree(w);
    if (!*wkt)
        st = gf_fail(GF_ENOMEM, "vector file %s: out of memory", path);
    GDALClose(ds);
    return st;
}

gf_status gf_vector_field_numeric(const char *path, const char *field, const char *need)
{
    if (!path || !field)
        return gf_fail(GF_EINVAL, "gf_vector_field_numeric: null argument");
    gf_status st;
    OGRLayerH L;
    GDALDatasetH ds = open_first_layer(path, &L, &st);
    if (!ds)
        return st;
    st = numeric_field(OGR_L_GetLayerDefn(L), path, field, need);
    GDALClose(ds);
    return st;
}
