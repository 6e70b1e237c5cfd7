/* SPDX-License-Identifier: GPL-3.0-or-later */
/* libgranflowTerrain: DEMs, polygons, the mesh grid, rasters on the DEM's
 * grid (granflow/terrain.h).  The avaHelix DEM and release polygon come from
 * tutorials/avaHelix/Inputs (AvaFrame test data); the small cases are written
 * here. */
#include "../gf_test.h"

#include "granflow/terrain.h"

#include <gdal.h>
#include <ogr_api.h>
#include <ogr_srs_api.h>
#include <cpl_conv.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#ifndef GF_SOURCE_DIR
#error "GF_SOURCE_DIR must point at the granflow checkout"
#endif
#define HELIX GF_SOURCE_DIR "/tutorials/avaHelix/Inputs/DEM_HX_Topo.asc"
#define HELIX_REL GF_SOURCE_DIR "/tutorials/avaHelix/Inputs/REL/release1HX.shp"

#include "../gf_tmpdir.h"
GF_TMPDIR_FIXTURES("gf_terrain")

static void write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}


/* the avaHelix DEM as GDAL reports it: 1001 x 401 pixels of 5 m, lower-left
 * pixel centre (1000, -5000), no NODATA */
static void helix_dem_is_read_with_its_georeferencing(void **state)
{
    (void)state;
    gf_raster r;
    assert_int_equal(gf_raster_read(HELIX, &r), GF_SUCCESS);
    assert_int_equal(r.nx, 1001);
    assert_int_equal(r.ny, 401);
    assert_close(r.gt[1], 5.0, 0);
    assert_close(r.gt[5], -5.0, 0);
    double x, y;
    gf_raster_centre(&r, 0, r.ny - 1, &x, &y);
    assert_close(x, 1000.0, 1e-9);
    assert_close(y, -5000.0, 1e-9);
    assert_int_equal(r.n_valid, (size_t)1001 * 401);
    gf_raster_free(&r);
}

/* A 6 x 5 DEM with one NODATA pixel, written as ESRI ASCII */
static const char *small_dem(void)
{
    const char *p = tmp("small.asc");
    write_text(p, "ncols 6\nnrows 5\nxllcorner 100\nyllcorner 200\ncellsize 10\nNODATA_value -9999\n"
                  "1 2 3 4 5 6\n"
                  "2 3 4 5 6 7\n"
                  "3 4 -9999 6 7 8\n"
                  "4 5 6 7 8 9\n"
                  "5 6 7 8 9 10\n");
    return p;
}

static void rasters_round_trip_with_the_dem_header(void **state)
{
    (void)state;
    gf_raster dem;
    assert_int_equal(gf_raster_read(small_dem(), &dem), GF_SUCCESS);
    assert_int_equal(dem.n_valid, 29);
    assert_true(isnan(dem.z[2 * 6 + 2]));
    double v[30];
    for (int i = 0; i < 30; ++i)
        v[i] = i == 7 ? NAN : 0.1 * i + 1.0 / 3.0;
    const char *drivers[2] = {"AAIGrid", "GTiff"}, *names[2] = {"v.asc", "v.tif"};
    for (int d = 0; d < 2; ++d) {
        assert_int_equal(gf_raster_write(tmp(names[d]), drivers[d], &dem, v), GF_SUCCESS);
        gf_raster back;
        assert_int_equal(gf_raster_read(tmp(names[d]), &back), GF_SUCCESS);
        assert_int_equal(back.nx, 6);
        assert_int_equal(back.ny, 5);
        for (int k = 0; k < 6; ++k)
            assert_close(back.gt[k], dem.gt[k], 1e-9);
        assert_close(back.nodata, -9999, 0);
        for (int i = 0; i < 30; ++i) {
            if (i == 7)
                assert_true(isnan(back.z[i]));
            else
                assert_close(back.z[i], v[i], d == 0 ? 1e-7 * fabs(v[i]) : 0); /* GDAL reads ESRI ASCII as float32 */
        }
        gf_raster_free(&back);
    }
    assert_int_equal(gf_raster_write(tmp("v.png"), "PNG", &dem, v), GF_ENOTFOUND);
    gf_raster_free(&dem);
}

static void expect_refused(const char *path, gf_status want, const char *reason)
{
    gf_raster r;
    assert_int_equal(gf_raster_read(path, &r), want);
    const char *d = gf_error_detail();
    if (!strstr(d, path) || !strstr(d, reason))
        fail_msg("detail '%s' lacks the file %s or '%s'", d, path, reason);
    assert_null(r.z);
}

/* a missing file, a raster without georeferencing (a PGM image), mixed cell
 * sizes (ESRI's dx/dy header), only NODATA: refused naming the file */
static void bad_rasters_are_refused_naming_the_file(void **state)
{
    (void)state;
    expect_refused(tmp("missing.asc"), GF_EIO, "no such file");
    const char *pgm = tmp("image.pgm");
    FILE *f = fopen(pgm, "wb");
    assert_non_null(f);
    fputs("P5\n3 3\n255\n", f);
    fwrite("abcdefghi", 1, 9, f);
    fclose(f);
    expect_refused(pgm, GF_EDOM, "no georeferencing");
    const char *mixed = tmp("mixed.asc");
    write_text(mixed, "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ndx 5\ndy 10\nNODATA_value -9999\n1 2\n3 4\n");
    expect_refused(mixed, GF_EDOM, "mixed cell sizes");
    const char *empty = tmp("empty.asc");
    write_text(empty, "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 5\nNODATA_value -9999\n"
                      "-9999 -9999\n-9999 -9999\n");
    expect_refused(empty, GF_EDOM, "every cell is NODATA");
    const char *text = tmp("notes.txt");
    write_text(text, "not a raster\n");
    expect_refused(text, GF_EIO, "not a raster");
}

/* A GeoJSON with a 10 x 10 square with a 2 x 2 hole (value 1.5) and a
 * multipolygon of two unit squares (value 0.5) that overlaps the first */
static const char *geojson(const char *extra_props)
{
    static char text[1024];
    snprintf(text, sizeof text,
             "{\"type\":\"FeatureCollection\",\"features\":["
             "{\"type\":\"Feature\",\"properties\":{\"thickness\":1.5%s},\"geometry\":{\"type\":\"Polygon\","
             "\"coordinates\":[[[0,0],[10,0],[10,10],[0,10],[0,0]],[[4,4],[6,4],[6,6],[4,6],[4,4]]]}},"
             "{\"type\":\"Feature\",\"properties\":{\"thickness\":0.5},\"geometry\":{\"type\":\"MultiPolygon\","
             "\"coordinates\":[[[[9,9],[11,9],[11,11],[9,11],[9,9]]],[[[20,0],[21,0],[21,1],[20,1],[20,0]]]]}}]}",
             extra_props);
    const char *p = tmp("rel.geojson");
    write_text(p, text);
    return p;
}

static void release_polygons_with_holes_parts_and_attributes(void **state)
{
    (void)state;
    gf_polygons p;
    assert_int_equal(gf_polygons_read(geojson(""), "thickness", 0, &p), GF_SUCCESS);
    assert_int_equal(p.n, 3);
    assert_close(gf_polygons_area(&p, 0), 96.0, 1e-12);
    assert_close(gf_polygons_area(&p, 1), 4.0, 1e-12);
    assert_close(gf_polygons_area(&p, 2), 1.0, 1e-12);
    assert_close(p.value[0], 1.5, 0);
    assert_close(p.value[1], 0.5, 0);
    assert_int_equal(gf_polygons_locate(&p, 2, 2), 0);
    assert_int_equal(gf_polygons_locate(&p, 5, 5), -1); /* the hole */
    assert_int_equal(gf_polygons_locate(&p, 9.5, 9.5), 1); /* the later one wins */
    assert_int_equal(gf_polygons_locate(&p, 20.5, 0.5), 2);
    assert_int_equal(gf_polygons_locate(&p, 15, 5), -1);
    gf_polygons_free(&p);
    /* a given value instead of an attribute */
    assert_int_equal(gf_polygons_read(geojson(""), NULL, 2.0, &p), GF_SUCCESS);
    assert_close(p.value[0], 2.0, 0);
    gf_polygons_free(&p);
    /* the shapefile of the avaHelix release: one polygon, thickness 1 m */
    assert_int_equal(gf_polygons_read(HELIX_REL, "thickness", 0, &p), GF_SUCCESS);
    assert_int_equal(p.n, 1);
    assert_close(p.value[0], 1.0, 0);
    assert_true(strstr(p.wkt, "Austria Lambert") != NULL);
    assert_int_equal(gf_crs_same(p.wkt, p.wkt), 1);
    assert_int_equal(gf_crs_same(p.wkt, ""), -1);
    {
        gf_polygons kot;
        assert_int_equal(gf_polygons_read(GF_SOURCE_DIR "/tutorials/avaKot/Inputs/REL/relKot.shp",
                                          "thickness", 0, &kot), GF_SUCCESS);
        /* both MGI / Austria Lambert */
        assert_int_equal(gf_crs_same(p.wkt, kot.wkt), 1);
        /* the same .prj read as a raster's CRS (GDAL's ESRI morphing: the
         * other axis order) against the shapefile's; against WGS 84 */
        const char *asc = tmp("kot.asc"), *prj = tmp("kot.prj");
        write_text(asc, "ncols 2\nnrows 2\nxllcorner 177000\nyllcorner 377000\ncellsize 5\n1 2\n3 4\n");
        char cmd[512];
        snprintf(cmd, sizeof cmd, "cp %s/tutorials/avaKot/Inputs/REL/relKot.prj %s", GF_SOURCE_DIR, prj);
        assert_int_equal(system(cmd), 0);
        gf_raster r;
        assert_int_equal(gf_raster_read(asc, &r), GF_SUCCESS);
        assert_true(strstr(r.wkt, "Austria Lambert") != NULL);
        assert_int_equal(gf_crs_same(r.wkt, kot.wkt), 1);
        assert_int_equal(gf_crs_same(r.wkt, "GEOGCS[\"WGS 84\",DATUM[\"WGS_1984\",SPHEROID[\"WGS 84\",6378137,298.257223563]],"
                                            "PRIMEM[\"Greenwich\",0],UNIT[\"degree\",0.0174532925199433]]"), 0);
        gf_raster_free(&r);
        gf_polygons_free(&kot);
    }
    assert_true(gf_polygons_area(&p, 0) > 3e4 && gf_polygons_area(&p, 0) < 8e4);
    gf_polygons_free(&p);
}

static void bad_polygons_are_refused_naming_file_and_attribute(void **state)
{
    (void)state;
    gf_polygons p;
    assert_int_equal(gf_polygons_read(geojson(""), "depth", 0, &p), GF_ENOTFOUND);
    assert_true(strstr(gf_error_detail(), "depth") && strstr(gf_error_detail(), "thickness"));
    /* a text field: named as one, not as a missing value */
    assert_int_equal(gf_polygons_read(geojson(",\"name\":\"a\""), "name", 0, &p), GF_EDOM);
    assert_true(strstr(gf_error_detail(), "field 'name' of ") != NULL);
    assert_true(strstr(gf_error_detail(), "is a text field (String); a number is needed") != NULL);
    const char *neg = tmp("neg.geojson");
    write_text(neg, "{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\",\"properties\":"
                    "{\"thickness\":-1},\"geometry\":{\"type\":\"Polygon\",\"coordinates\":"
                    "[[[0,0],[1,0],[1,1],[0,0]]]}}]}");
    assert_int_equal(gf_polygons_read(neg, "thickness", 0, &p), GF_EDOM);
    assert_true(strstr(gf_error_detail(), neg) && strstr(gf_error_detail(), "-1"));
    const char *pt = tmp("point.geojson");
    write_text(pt, "{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\",\"properties\":"
                   "{\"thickness\":1},\"geometry\":{\"type\":\"Point\",\"coordinates\":[0,0]}}]}");
    assert_int_equal(gf_polygons_read(pt, "thickness", 0, &p), GF_EDOM);
    assert_true(strstr(gf_error_detail(), "not a polygon") != NULL);
    assert_int_equal(gf_polygons_read(tmp("none.shp"), "thickness", 0, &p), GF_EIO);
    assert_true(strstr(gf_error_detail(), "none.shp") != NULL);
    assert_int_equal(gf_polygons_read(geojson(""), NULL, -1.0, &p), GF_EDOM);
}

/* faces are the quads of four valid nodes: 5 x 4 quads of the small DEM
 * minus the 4 around its NODATA pixel; coarsening 2 and a crop box */
static void mesh_grid_skips_nodata_and_follows_the_crop(void **state)
{
    (void)state;
    gf_raster dem;
    assert_int_equal(gf_raster_read(small_dem(), &dem), GF_SUCCESS);
    gf_terrain_grid g;
    assert_int_equal(gf_terrain_grid_make(&dem, 1, NULL, NULL, &g), GF_SUCCESS);
    assert_int_equal(g.n_quads, 16);
    assert_int_equal(g.ni, 6);
    assert_int_equal(g.nj, 5);
    double xyz[3];
    gf_terrain_node(&dem, &g, 0, 4, xyz); /* lower-left pixel centre */
    assert_close(xyz[0], 105, 1e-12);
    assert_close(xyz[1], 205, 1e-12);
    assert_close(xyz[2], 5, 0);
    gf_terrain_grid_free(&g);
    /* k = 2: nodes at columns 0, 2, 4 and rows 0, 2, 4; all four quads
     * have the NODATA pixel (2, 2) as a corner: no face is left */
    assert_int_equal(gf_terrain_grid_make(&dem, 2, NULL, NULL, &g), GF_EDOM);
    assert_true(strstr(gf_error_detail(), "no cell") != NULL);
    const double box[4] = {100, 200, 128, 250}; /* quad centres with x <= 128 */
    assert_int_equal(gf_terrain_grid_make(&dem, 1, box, NULL, &g), GF_SUCCESS);
    assert_int_equal(g.n_quads, 2 * 4 - 2);
    assert_int_equal(g.c0, 0);
    gf_terrain_grid_free(&g);
    /* crop polygons: a triangle over the south-west corner keeps the faces
     * whose centres lie inside it */
    {
        const char *tri = tmp("crop.geojson");
        write_text(tri, "{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\",\"properties\":{},"
                        "\"geometry\":{\"type\":\"Polygon\",\"coordinates\":[[[100,200],[136,200],[100,236],[100,200]]]}}]}");
        gf_polygons crop;
        assert_int_equal(gf_polygons_read(tri, NULL, 1.0, &crop), GF_SUCCESS);
        assert_int_equal(gf_terrain_grid_make(&dem, 1, NULL, &crop, &g), GF_SUCCESS);
        /* quad centres (110 + 10 I, 240 - 10 J) are inside when
         * (x - 100) + (y - 200) < 36: (I, J) = (0, 3), (1, 3), (0, 2), none
         * next to the NODATA pixel */
        assert_int_equal(g.n_quads, 3);
        gf_terrain_grid_free(&g);
        gf_polygons_free(&crop);
    }
    const double nobox[4] = {0, 0, 10, 10};
    assert_int_equal(gf_terrain_grid_make(&dem, 1, nobox, NULL, &g), GF_EDOM);
    assert_int_equal(gf_terrain_grid_make(&dem, 5, NULL, NULL, &g), GF_EDOM);
    gf_raster_free(&dem);
}

/* Face values of a linear field a + b x + c y, mapped onto the DEM's pixels:
 * exact at interior nodes (the mean of four symmetric faces) and, with
 * coarsening, bilinear in between; NAN off the mesh */
static void face_values_map_onto_the_dem_grid(void **state)
{
    (void)state;
    const int nx = 9, ny = 7;
    gf_raster dem = {.nx = nx, .ny = ny, .gt = {1000, 5, 0, 2000, 0, -5}, .nodata = -9999, .wkt = ""};
    double z[63];
    dem.z = z;
    for (int i = 0; i < nx * ny; ++i)
        z[i] = 0.1 * i;
    z[0] = NAN; /* the north-west corner */
    for (int k = 1; k <= 2; ++k) {
        gf_terrain_grid g;
        assert_int_equal(gf_terrain_grid_make(&dem, k, NULL, NULL, &g), GF_SUCCESS);
        assert_int_equal(g.n_quads, (size_t)((nx - 1) / k) * ((ny - 1) / k) - 1);
        double xy[96], area[48], val[48], out[63];
        size_t n = 0;
        for (int J = 0; J + 1 < g.nj; ++J)
            for (int I = 0; I + 1 < g.ni; ++I)
                if (g.quad[I + (g.ni - 1) * J]) {
                    double a[3], b[3];
                    gf_terrain_node(&dem, &g, I, J, a);
                    gf_terrain_node(&dem, &g, I + 1, J + 1, b);
                    xy[2 * n] = 0.5 * (a[0] + b[0]), xy[2 * n + 1] = 0.5 * (a[1] + b[1]);
                    area[n] = 25.0 * k * k;
                    val[n] = 3 + 0.5 * xy[2 * n] - 0.25 * xy[2 * n + 1];
                    ++n;
                }
        assert_int_equal(n, g.n_quads);
        assert_int_equal(gf_terrain_to_raster(&dem, &g, n, xy, area, val, out), GF_SUCCESS);
        for (int r = 0; r < ny; ++r)
            for (int c = 0; c < nx; ++c) {
                double x, y;
                gf_raster_centre(&dem, c, r, &x, &y);
                const double v = out[r * nx + c];
                /* the nodes on the mesh's boundary average fewer faces:
                 * exact in the quads of interior nodes only */
                const int on_edge = c < k || r < k || c > nx - 1 - k || r > ny - 1 - k;
                const int by_hole = c <= 2 * k && r <= 2 * k;
                if (c < k && r < k) /* inside the quad left out */
                    assert_true(isnan(v));
                else if (!on_edge && !by_hole)
                    assert_close(v, 3 + 0.5 * x - 0.25 * y, 1e-9);
                else
                    assert_true(isfinite(v));
            }
        /* a face that is not on the grid is refused */
        xy[0] = 0;
        assert_int_equal(gf_terrain_to_raster(&dem, &g, n, xy, area, val, out), GF_EDOM);
        gf_terrain_grid_free(&g);
    }
}

/* The outlines of a class raster (the pressure zones of a regional map) in
 * a GeoPackage: 4-connected groups by class, a ring keeping its hole, the
 * limits and areas counted by hand; refusals */
static void class_outlines_are_counted_by_hand(void **state)
{
    (void)state;
    gf_raster dem;
    assert_int_equal(gf_raster_read(small_dem(), &dem), GF_SUCCESS);
    assert_int_equal(dem.nx, 6);
    assert_int_equal(dem.ny, 5);
    /* a ring of class 1 around a class-2 pixel, a lone class-1 pixel (only
     * diagonal to the ring: another polygon), class 3 in a corner, class 2
     * in another, NAN and an out-of-range 7 not drawn */
    const double c[30] = {1, 1, 1, 0, 0, 3,   /* row 0 (north) */
                          1, 2, 1, 0, 0, 0,   /* row 1 */
                          1, 1, 1, 0, 0, 0,   /* row 2 */
                          0, 0, 0, 1, 0, 7,   /* row 3 */
                          NAN, 0, 0, 0, 0, 2}; /* row 4 */
    const double lim[3] = {1, 10, 30};
    size_t n = 0;
    assert_int_equal(gf_class_outlines(tmp("zones.gpkg"), "zones", &dem, c, 3, lim, "kPa", &n), GF_SUCCESS);
    assert_int_equal(n, 5);
    GDALDatasetH ds = GDALOpenEx(tmp("zones.gpkg"), GDAL_OF_VECTOR, NULL, NULL, NULL);
    assert_non_null(ds);
    OGRLayerH L = GDALDatasetGetLayerByName(ds, "zones");
    assert_non_null(L);
    assert_int_equal((int)OGR_L_GetFeatureCount(L, TRUE), 5);
    double area[4] = {0}, lower[4] = {0};
    int pieces[4] = {0}, holes = 0, upper_set[4] = {0};
    OGRFeatureH f;
    while ((f = OGR_L_GetNextFeature(L)) != NULL) {
        const int k = OGR_F_GetFieldAsInteger(f, OGR_F_GetFieldIndex(f, "class"));
        assert_true(k >= 1 && k <= 3);
        ++pieces[k];
        const double a = OGR_F_GetFieldAsDouble(f, OGR_F_GetFieldIndex(f, "area_m2"));
        assert_close(a, OGR_G_Area(OGR_F_GetGeometryRef(f)), 1e-9);
        area[k] += a;
        lower[k] = OGR_F_GetFieldAsDouble(f, OGR_F_GetFieldIndex(f, "lower_kPa"));
        upper_set[k] = OGR_F_IsFieldSetAndNotNull(f, OGR_F_GetFieldIndex(f, "upper_kPa"));
        if (k == 1 && a > 500) {
            holes = OGR_G_GetGeometryCount(OGR_F_GetGeometryRef(f)) - 1;
            assert_close(OGR_F_GetFieldAsDouble(f, OGR_F_GetFieldIndex(f, "upper_kPa")), 10, 0);
        }
        OGR_F_Destroy(f);
    }
    GDALClose(ds);
    assert_int_equal(pieces[1], 2);
    assert_int_equal(pieces[2], 2);
    assert_int_equal(pieces[3], 1);
    assert_close(area[1], 9 * 100.0, 1e-9); /* the ring's 8 pixels and the lone one, 10 m pixels */
    assert_close(area[2], 2 * 100.0, 1e-9);
    assert_close(area[3], 1 * 100.0, 1e-9);
    assert_int_equal(holes, 1);
    assert_close(lower[1], 1, 0);
    assert_close(lower[2], 10, 0);
    assert_close(lower[3], 30, 0);
    assert_true(upper_set[1] && upper_set[2] && !upper_set[3]);
    /* refusals */
    const double bad[3] = {1, 10, 10};
    assert_int_equal(gf_class_outlines(tmp("z.gpkg"), "zones", &dem, c, 3, bad, "kPa", NULL), GF_EINVAL);
    assert_non_null(strstr(gf_error_detail(), "limit 3"));
    assert_int_equal(gf_class_outlines(tmp("z.gpkg"), "zones", &dem, c, 0, lim, "kPa", NULL), GF_EINVAL);
    assert_int_equal(gf_class_outlines(tmp("z.gpkg"), "zo nes", &dem, c, 3, lim, "kPa", NULL), GF_EINVAL);
    assert_int_equal(gf_class_outlines("/nonexistent-dir/z.gpkg", "zones", &dem, c, 3, lim, "kPa", NULL), GF_EIO);
    assert_non_null(strstr(gf_error_detail(), "/nonexistent-dir/z.gpkg"));
    gf_raster_free(&dem);
}

/* The affected-area outline: pixels >= threshold, their area, the GeoJSON
 * polygons' areas summing to it; the PNG map has the DEM's size plus the
 * colour bar; a 3D line (the centre-of-mass path) as GeoJSON */
static void outline_and_map_are_written(void **state)
{
    (void)state;
    gf_raster dem;
    assert_int_equal(gf_raster_read(small_dem(), &dem), GF_SUCCESS);
    double v[30];
    size_t count = 0;
    for (int i = 0; i < 30; ++i) {
        v[i] = (i % 6 >= 3 && i / 6 >= 1) ? 0.5 + 0.01 * i : 0.0;
        count += v[i] >= 0.1;
    }
    v[0] = 0.2; /* a separate patch */
    double area;
    assert_int_equal(gf_raster_outline(tmp("outline.geojson"), &dem, v, 0.1, &area), GF_SUCCESS);
    assert_close(area, (count + 1) * 100.0, 1e-9);
    GDALDatasetH ds = GDALOpenEx(tmp("outline.geojson"), GDAL_OF_VECTOR, NULL, NULL, NULL);
    assert_non_null(ds);
    OGRLayerH L = GDALDatasetGetLayer(ds, 0);
    double sum = 0;
    int nf = 0;
    OGRFeatureH f;
    while ((f = OGR_L_GetNextFeature(L)) != NULL) {
        sum += OGR_F_GetFieldAsDouble(f, OGR_F_GetFieldIndex(f, "area_m2"));
        ++nf;
        OGR_F_Destroy(f);
    }
    GDALClose(ds);
    assert_int_equal(nf, 2);
    assert_close(sum, area, 1e-9);
    /* a 3D line with properties, read back by OGR */
    const double xyz[9] = {100, 200, 50, 130, 240, 20, 150, 250, 10};
    const char *keys[1] = {"length_m"};
    const double vals[1] = {42.5};
    assert_int_equal(gf_line_geojson(tmp("path.geojson"), "", 3, xyz, "path", 1, keys, vals), GF_SUCCESS);
    ds = GDALOpenEx(tmp("path.geojson"), GDAL_OF_VECTOR, NULL, NULL, NULL);
    assert_non_null(ds);
    L = GDALDatasetGetLayer(ds, 0);
    f = OGR_L_GetNextFeature(L);
    assert_non_null(f);
    assert_close(OGR_F_GetFieldAsDouble(f, OGR_F_GetFieldIndex(f, "length_m")), 42.5, 0);
    OGRGeometryH geom = OGR_F_GetGeometryRef(f);
    assert_int_equal(OGR_G_GetPointCount(geom), 3);
    assert_close(OGR_G_GetZ(geom, 1), 20, 0);
    assert_close(OGR_G_Length(geom), 50.0 + sqrt(500.0), 1e-12);
    OGR_F_Destroy(f);
    GDALClose(ds);
    assert_int_equal(gf_line_geojson(tmp("p1.geojson"), "", 1, xyz, "path", 0, NULL, NULL), GF_EDOM);
    gf_raster_free(&dem);
}

/* dem: a DEM of 41 x 41 pixels of 1 m, lower-left corner (0, 0), pixel
 * centres at (c + 0.5, 40.5 - r), elevation z0 + gx x, written to the ESRI
 * grid name in the test folder and read back */
static void plane_dem(const char *name, double z0, double gx, gf_raster *dem)
{
    const char *path = tmp(name);
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fprintf(f, "ncols 41\nnrows 41\nxllcorner 0\nyllcorner 0\ncellsize 1\nNODATA_value -9999\n");
    for (int r = 0; r < 41; ++r) {
        for (int c = 0; c < 41; ++c)
            fprintf(f, "%.17g ", z0 + gx * (c + 0.5));
        fputc('\n', f);
    }
    fclose(f);
    assert_int_equal(gf_raster_read(path, dem), GF_SUCCESS);
}

#define TAN60 1.7320508075688772

/* doc/theory/mass-exchange.md, section 3: on flat ground at 100 m, a straight crown line
 * x = 20.5 at elevation 105 (H = 5 m above ground), wall slope 60 deg:
 * exactly 105 on the line, 105 - tan(60) d at distance d = 1, 2, the ground
 * from d = 3 (105 - 3 tan 60 < 100) on; a short line has rounded ends */
static void dam_on_flat_ground_has_the_crown_height_and_the_wall_slope(void **state)
{
    (void)state;
    gf_raster dem;
    plane_dem("flat.asc", 100.0, 0.0, &dem);
    const double line[6] = {20.5, -5.0, 105.0, 20.5, 46.0, 105.0};
    size_t raised = 0;
    double rise = 0;
    assert_int_equal(gf_dam_burn(&dem, 2, line, 60.0, &raised, &rise), GF_SUCCESS);
    assert_int_equal(raised, 41 * 5);
    assert_close(rise, 5.0, 1e-12);
    for (int r = 0; r < 41; ++r)
        for (int c = 0; c < 41; ++c) {
            const int d = abs(c - 20);
            const double want = d <= 2 ? 105.0 - TAN60 * d : 100.0;
            assert_close(dem.z[r * 41 + c], want, 1e-12);
        }
    gf_raster_free(&dem);
    /* a short line (20.5, 10.5) - (20.5, 30.5): beyond its north end the
     * nearest point is the end; pixel (21.5, 32.5) is sqrt(5) from it */
    plane_dem("flat.asc", 100.0, 0.0, &dem);
    const double shrt[6] = {20.5, 10.5, 105.0, 20.5, 30.5, 105.0};
    assert_int_equal(gf_dam_burn(&dem, 2, shrt, 60.0, NULL, NULL), GF_SUCCESS);
    assert_close(dem.z[(40 - 32) * 41 + 21], 105.0 - TAN60 * sqrt(5.0), 1e-12);
    assert_close(dem.z[(40 - 30) * 41 + 20], 105.0, 1e-12);
    assert_close(dem.z[(40 - 34) * 41 + 20], 100.0, 0); /* 4 m beyond the end */
    gf_raster_free(&dem);
}

/* sloping ground z = 100 + 0.25 x (exact in float32, as GDAL reads the
 * ESRI grid) and a crown rising along the line
 * z_c(y) = 110 + 0.1 (y + 5), slope 45 deg: every pixel is
 * max(ground, z_c(y) - |x - 20.5|) */
static void dam_on_sloping_ground_follows_the_crown_elevation(void **state)
{
    (void)state;
    gf_raster dem;
    plane_dem("plane.asc", 100.0, 0.25, &dem);
    const double line[9] = {20.5, -5.0, 110.0, 20.5, 20.0, 112.5, 20.5, 46.0, 115.1};
    size_t raised = 0;
    double rise = 0;
    assert_int_equal(gf_dam_burn(&dem, 3, line, 45.0, &raised, &rise), GF_SUCCESS);
    size_t want_raised = 0;
    double want_rise = 0;
    for (int r = 0; r < 41; ++r)
        for (int c = 0; c < 41; ++c) {
            const double x = c + 0.5, y = 40.5 - r, ground = 100.0 + 0.25 * x;
            const double dam = 110.0 + 0.1 * (y + 5.0) - fabs(x - 20.5);
            if (dam > ground)
                ++want_raised, want_rise = fmax(want_rise, dam - ground);
            assert_close(dem.z[r * 41 + c], fmax(ground, dam), 1e-9);
        }
    assert_int_equal(raised, want_raised);
    assert_close(rise, want_rise, 1e-9);
    assert_close(rise, 110.0 + 0.1 * 45.5 - (100.0 + 0.25 * 20.5), 1e-9); /* the line's top end */
    gf_raster_free(&dem);
}

static void write_line(const char *path, const char *props, const char *coords)
{
    char text[512];
    snprintf(text, sizeof text,
             "{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\",\"properties\":"
             "{%s},\"geometry\":{\"type\":\"LineString\",\"coordinates\":%s}}]}", props, coords);
    write_text(path, text);
}

static void expect_detail(const char *a, const char *b)
{
    const char *d = gf_error_detail();
    if (!strstr(d, a) || (b && !strstr(d, b)))
        fail_msg("detail '%s' lacks '%s' or '%s'", d, a, b ? b : "");
}

/* no heights (2D line, non-finite z), fewer than 2 points, wall slopes 0,
 * 90 and 95 deg, a line off the DEM, no slope: refused with the reason; a
 * refused burn leaves the DEM as it was */
static void bad_dams_are_refused_with_the_reason(void **state)
{
    (void)state;
    gf_raster dem;
    plane_dem("flat.asc", 100.0, 0.0, &dem);
    const double ok[6] = {20.5, -5.0, 105.0, 20.5, 46.0, 105.0};
    assert_int_equal(gf_dam_burn(&dem, 1, ok, 60.0, NULL, NULL), GF_EDOM);
    expect_detail("at least 2", NULL);
    const double slopes[3] = {0.0, 90.0, 95.0};
    for (int k = 0; k < 3; ++k) {
        assert_int_equal(gf_dam_burn(&dem, 2, ok, slopes[k], NULL, NULL), GF_EDOM);
        expect_detail("outside (0, 90)", NULL);
    }
    const double noz[6] = {20.5, -5.0, NAN, 20.5, 46.0, NAN};
    assert_int_equal(gf_dam_burn(&dem, 2, noz, 60.0, NULL, NULL), GF_EDOM);
    expect_detail("height", NULL);
    const double off[6] = {50.0, -5.0, 105.0, 60.0, 46.0, 105.0};
    assert_int_equal(gf_dam_burn(&dem, 2, off, 60.0, NULL, NULL), GF_EDOM);
    expect_detail("outside the DEM", NULL);
    for (size_t i = 0; i < 41 * 41; ++i)
        assert_close(dem.z[i], 100.0, 0);
    /* a segment crossing the DEM with both ends outside is on it */
    const double across[6] = {-10.0, 20.0, 105.0, 50.0, 20.0, 105.0};
    assert_int_equal(gf_dam_burn(&dem, 2, across, 60.0, NULL, NULL), GF_SUCCESS);
    gf_raster_free(&dem);

    gf_dam d;
    const char *p2 = tmp("dam2d.geojson");
    write_line(p2, "\"slope\":60", "[[0,0],[10,0]]");
    assert_int_equal(gf_dam_read(p2, "slope", NAN, &d), GF_EDOM);
    expect_detail(p2, "without heights");
    assert_null(d.xyz);
    const char *steep = tmp("dam95.geojson");
    write_line(steep, "\"slope\":95", "[[0,0,5],[10,0,5]]");
    assert_int_equal(gf_dam_read(steep, "slope", NAN, &d), GF_EDOM);
    expect_detail(steep, "95 deg (slope) outside (0, 90)");
    const char *flat = tmp("dam0.geojson");
    write_line(flat, "\"slope\":0", "[[0,0,5],[10,0,5]]");
    assert_int_equal(gf_dam_read(flat, "slope", NAN, &d), GF_EDOM);
    expect_detail(flat, "outside (0, 90)");
    const char *none = tmp("damnone.geojson");
    write_line(none, "\"name\":\"x\"", "[[0,0,5],[10,0,5]]");
    assert_int_equal(gf_dam_read(none, "slope", NAN, &d), GF_EDOM);
    expect_detail(none, "no wall slope");
    assert_int_equal(gf_dam_read(none, "slope", 90.0, &d), GF_EDOM);
    expect_detail(none, "90 deg (default) outside (0, 90)");
    /* without the attribute the given slope; a polygon is not a line */
    assert_int_equal(gf_dam_read(none, "slope", 30.0, &d), GF_SUCCESS);
    assert_int_equal(d.n, 2);
    assert_close(d.slope, 30.0, 0);
    assert_close(d.xyz[5], 5.0, 0);
    gf_dam_free(&d);
    assert_int_equal(gf_dam_read(geojson(""), "slope", 30.0, &d), GF_EDOM);
    expect_detail("not a line", NULL);
    assert_int_equal(gf_dam_read(tmp("nodam.shp"), "slope", 30.0, &d), GF_EIO);
    expect_detail("nodam.shp", NULL);
}

/* avaKot's dam (AvaFrame Inputs/DAM/dam.shp): a 3D line of 6 points with
 * absolute crown elevations 1184 .. 1079 m, slope 60 deg; burned into the
 * avaKot DEM it raises the ground by 5-15 m (the crown is 8.6-9.8 m above
 * the ground at its points) */
static void avakot_dam_is_read_and_burned(void **state)
{
    (void)state;
    gf_dam d;
    assert_int_equal(gf_dam_read(GF_SOURCE_DIR "/tutorials/avaKot/Inputs/DAM/dam.shp", "slope",
                                 NAN, &d), GF_SUCCESS);
    assert_int_equal(d.n, 6);
    assert_close(d.slope, 60.0, 0);
    assert_close(d.xyz[2], 1184.0, 0);
    assert_close(d.xyz[17], 1079.0, 0);
    assert_true(strstr(d.wkt, "Austria Lambert") != NULL);
    gf_raster dem;
    assert_int_equal(gf_raster_read(GF_SOURCE_DIR "/tutorials/avaKot/Inputs/avaKot.asc", &dem),
                     GF_SUCCESS);
    size_t raised = 0;
    double rise = 0;
    assert_int_equal(gf_dam_burn(&dem, d.n, d.xyz, d.slope, &raised, &rise), GF_SUCCESS);
    assert_true(raised > 100 && raised < 2000);
    assert_true(rise > 5.0 && rise < 15.0);
    gf_raster_free(&dem);
    gf_dam_free(&d);
}

/* The checks of a case's inputs (gfCheckInputs): a vector file's CRS, a
 * numeric attribute, extents that overlap */
static void input_checks_name_the_crs_the_field_type_and_the_overlap(void **state)
{
    (void)state;
    /* the CRS of the avaHelix release (MGI / Austria Lambert) and of a
     * GeoJSON without one (RFC 7946: WGS 84, which OGR reports) */
    char *wkt = NULL;
    assert_int_equal(gf_vector_crs(HELIX_REL, &wkt), GF_SUCCESS);
    assert_true(strstr(wkt, "Austria Lambert") != NULL);
    gf_raster dem;
    assert_int_equal(gf_raster_read(HELIX, &dem), GF_SUCCESS);
    assert_int_equal(gf_crs_same(wkt, dem.wkt), 1);
    free(wkt);
    const char *shp = tmp("nocrs.csv");
    write_text(shp, "id,thickness,WKT\n1,1.5,\"POLYGON ((0 0,1 0,1 1,0 0))\"\n");
    assert_int_equal(gf_vector_crs(shp, &wkt), GF_SUCCESS);
    assert_string_equal(wkt, "");
    free(wkt);
    /* the ESRI .prj of avaKot's release against EPSG's definition of the
     * same projection (MGI / Austria Lambert, EPSG:31287), which carries
     * another datum shift (TOWGS84): the same CRS; against UTM 32N: not */
    assert_int_equal(gf_vector_crs(GF_SOURCE_DIR "/tutorials/avaKot/Inputs/REL/relKot.shp", &wkt), GF_SUCCESS);
    for (int epsg = 31287; epsg; epsg = epsg == 31287 ? 32632 : 0) {
        OGRSpatialReferenceH e = OSRNewSpatialReference(NULL);
        assert_int_equal(OSRImportFromEPSG(e, epsg), OGRERR_NONE);
        char *ew = NULL;
        OSRExportToWkt(e, &ew);
        assert_int_equal(gf_crs_same(wkt, ew), epsg == 31287 ? 1 : 0);
        CPLFree(ew);
        OSRDestroySpatialReference(e);
    }
    free(wkt);
    assert_int_equal(gf_vector_crs(tmp("missing.shp"), &wkt), GF_EIO);
    assert_true(strstr(gf_error_detail(), "missing.shp") != NULL);
    assert_null(wkt);

    /* a numeric attribute: real and integer pass; a text field is named as
     * one with the number needed; a missing one lists the numeric fields */
    const char *p = geojson(",\"name\":\"a\",\"n\":3");
    assert_int_equal(gf_vector_field_numeric(p, "thickness", "a number in metres"), GF_SUCCESS);
    assert_int_equal(gf_vector_field_numeric(p, "n", NULL), GF_SUCCESS);
    assert_int_equal(gf_vector_field_numeric(p, "name", "a number in metres"), GF_EDOM);
    char expect[512];
    snprintf(expect, sizeof expect, "field 'name' of %s is a text field (String); a number in metres"
                                    " is needed", p);
    assert_string_equal(gf_error_detail(), expect);
    assert_int_equal(gf_vector_field_numeric(p, "depth", NULL), GF_ENOTFOUND);
    assert_true(strstr(gf_error_detail(), p) && strstr(gf_error_detail(), "'depth'"));
    assert_true(strstr(gf_error_detail(), "thickness, n") != NULL);
    assert_null(strstr(gf_error_detail(), "name"));
    assert_int_equal(gf_vector_field_numeric(tmp("missing.shp"), "thickness", NULL), GF_EIO);

    /* extents: the avaHelix DEM's pixels (centres 1000 .. 6000, -5000 ..
     * -3000, 5 m) reach half a pixel beyond its centres */
    double box[4];
    gf_raster_extent(&dem, box);
    assert_close(box[0], 997.5, 1e-9);
    assert_close(box[1], -5002.5, 1e-9);
    assert_close(box[2], 6002.5, 1e-9);
    assert_close(box[3], -2997.5, 1e-9);
    const double inside[4] = {2000, -4000, 2100, -3900}, across[4] = {6000, -3000, 7000, -2000};
    const double edge[4] = {6002.5, -3000, 7000, -2000}, beyond[4] = {6002.6, -4000, 7000, -3900};
    const double nan_box[4] = {NAN, -4000, 2100, -3900};
    assert_int_equal(gf_box_overlap(inside, box), 1);
    assert_int_equal(gf_box_overlap(box, inside), 1);
    assert_int_equal(gf_box_overlap(across, box), 1);
    assert_int_equal(gf_box_overlap(edge, box), 1);
    assert_int_equal(gf_box_overlap(beyond, box), 0);
    assert_int_equal(gf_box_overlap(box, beyond), 0);
    assert_int_equal(gf_box_overlap(nan_box, box), 0);
    /* the avaHelix release lies on its DEM */
    gf_polygons rel;
    assert_int_equal(gf_polygons_read(HELIX_REL, "thickness", 0, &rel), GF_SUCCESS);
    assert_int_equal(gf_box_overlap(rel.box, box), 1);
    gf_polygons_free(&rel);
    gf_raster_free(&dem);
}

int main(void)
{
    CPLSetConfigOption("CPL_LOG", "/dev/null");
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(helix_dem_is_read_with_its_georeferencing),
        cmocka_unit_test(rasters_round_trip_with_the_dem_header),
        cmocka_unit_test(bad_rasters_are_refused_naming_the_file),
        cmocka_unit_test(release_polygons_with_holes_parts_and_attributes),
        cmocka_unit_test(bad_polygons_are_refused_naming_file_and_attribute),
        cmocka_unit_test(mesh_grid_skips_nodata_and_follows_the_crop),
        cmocka_unit_test(face_values_map_onto_the_dem_grid),
        cmocka_unit_test(outline_and_map_are_written),
        cmocka_unit_test(class_outlines_are_counted_by_hand),
        cmocka_unit_test(dam_on_flat_ground_has_the_crown_height_and_the_wall_slope),
        cmocka_unit_test(dam_on_sloping_ground_follows_the_crown_elevation),
        cmocka_unit_test(bad_dams_are_refused_with_the_reason),
        cmocka_unit_test(avakot_dam_is_read_and_burned),
        cmocka_unit_test(input_checks_name_the_crs_the_field_type_and_the_overlap),
    };
    const int rc = gf_run_tests("tests", tests, setup, teardown);
    GDALDestroyDriverManager();
    return rc;
}
