/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * gfCheckInputs — every input of a terrain case checked at once, in one
 * process, before anything runs (gfRunCase calls it; doc/guide/own-case.md).
 * The checks are libgranflowTerrain's readers and checks (granflow/terrain.h,
 * granflow/path_analysis.h), the ones the meshing, the solver and the path
 * analysis run later, so an input that passes here is read there:
 *
 *   the DEM: a raster GDAL reads, north-up with square cells, with a
 *     coordinate reference system (CRS);
 *   each vector file: readable, with a CRS, the DEM's (gf_crs_same);
 *   the release (and the entrainment areas): polygons, a numeric thickness
 *     attribute with a finite value >= 0 on every feature, each polygon on
 *     the DEM's extent; the resistance areas: polygons on the DEM;
 *   the dam: a 3D crown line with its wall slope that touches the DEM (it is
 *     burnt into the DEM here as gfTerrainMesh burns it, and the path is
 *     checked on that DEM);
 *   the path: a line whose resampled points all lie on the DEM, off NODATA
 *     (the path analysis's own grid, gf_path_grid_make);
 *   the split point: a point on the DEM, with a beta point below it on the
 *     path (the path analysis's defaults).
 *
 *   gfCheckInputs -dem FILE [-release FILE] [-attribute NAME] [-ent FILE]
 *                 [-res FILE] [-dam FILE] [-path FILE] [-split FILE]
 *   gfCheckInputs -help | -version
 *
 * Prints, when every check passes, shell-readable lines (name=value): demCell
 * (the DEM's cell size [m]), demSize (columns x rows), releasePolygons.
 * Otherwise each refusal on its own line on stderr, naming the file, the
 * problem and the fix, and exits with 1 (2: a wrong command line).
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cpl_error.h>
#include <ogr_srs_api.h>

#include "granflow/path_analysis.h"
#include "granflow/terrain.h"
#include "granflow/version.h"

static const char *prog = "gfCheckInputs";
static int refusals = 0;

static void refuse(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;
static void refuse(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "%s: ", prog);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
    ++refusals;
}

static void usage(FILE *f)
{
    fprintf(f,
            "usage: gfCheckInputs -dem FILE [-release FILE] [-attribute NAME] [-ent FILE]\n"
            "                     [-res FILE] [-dam FILE] [-path FILE] [-split FILE]\n"
            "       gfCheckInputs -help | -version\n\n"
            "Checks every input of a terrain case at once, before anything runs (gfRunCase\n"
            "calls it): the DEM has a CRS; every vector file has the DEM's CRS; the release\n"
            "(-release) and the entrainment areas (-ent) are polygons with a numeric\n"
            "attribute -attribute (default thickness, in metres), on the DEM; the resistance\n"
            "areas (-res) are polygons on the DEM; the dam (-dam) is a 3D crown line with\n"
            "its wall slope (attribute slope) that touches the DEM; the path (-path) lies on\n"
            "the DEM, off its NODATA; the split point (-split) lies on the DEM with a beta\n"
            "point below it on the path.  The checks are those of the meshing, the solver\n"
            "and the path analysis (libgranflowTerrain).\n\n"
            "Prints demCell=<the DEM's cell size, m>, demSize=<columns>x<rows> and\n"
            "releasePolygons=<n> when every input passes; otherwise each problem on its own\n"
            "line (the file, what is wrong, the fix) and exits with 1.  Guide:\n"
            "doc/guide/own-case.md, doc/guide/troubleshooting.md.\n");
}

/* a CRS's name for a message */
static void crs_name(const char *wkt, char *out, size_t n)
{
    CPLPushErrorHandler(CPLQuietErrorHandler);
    OGRSpatialReferenceH s = OSRNewSpatialReference(wkt);
    const char *name = s ? OSRGetName(s) : NULL;
    snprintf(out, n, "%s", name && *name ? name : "an unnamed CRS");
    if (s)
        OSRDestroySpatialReference(s);
    CPLPopErrorHandler();
}

/* how to name the DEM's CRS in a command: its .prj when there is one */
static void dem_crs_ref(const char *dem, char *out, size_t n)
{
    char prj[4096];
    snprintf(prj, sizeof prj, "%s", dem);
    char *dot = strrchr(prj, '.');
    char *slash = strrchr(prj, '/');
    if (dot && (!slash || dot > slash) && (size_t)(dot - prj) + 5 < sizeof prj) {
        strcpy(dot, ".prj");
        if (access(prj, R_OK) == 0) {
            snprintf(out, n, "%s", prj);
            return;
        }
    }
    snprintf(out, n, "%s", dem);
}

/* the DEM as read, its extent and CRS */
typedef struct {
    const char *path;
    gf_raster r;
    double box[4];
    int has_crs;
} dem_info;

/* a vector file's CRS: present and the DEM's; 0 when it fails */
static int check_crs(const dem_info *dem, const char *path, const char *what)
{
    char *wkt = NULL;
    if (gf_vector_crs(path, &wkt) != GF_SUCCESS) {
        refuse("%s", gf_error_detail());
        return 0;
    }
    int ok = 1;
    char ref[4200];
    dem_crs_ref(dem->path, ref, sizeof ref);
    if (!*wkt) {
        refuse("%s: no coordinate reference system (its .prj is missing): the %s needs the"
               " DEM's CRS; when its coordinates are the DEM's, assign it (ogr2ogr -a_srs %s"
               " OUT.shp %s)", path, what, ref, path);
        ok = 0;
    } else if (dem->has_crs && gf_crs_same(wkt, dem->r.wkt) == 0) {
        char a[256], b[256];
        crs_name(wkt, a, sizeof a);
        crs_name(dem->r.wkt, b, sizeof b);
        refuse("%s: in another CRS (%s) than the DEM %s (%s); reproject it (ogr2ogr -t_srs %s"
               " OUT.shp %s)", path, a, dem->path, b, ref, path);
        ok = 0;
    }
    free(wkt);
    return ok;
}

/* polygons (release, entrainment, resistance): read as the solver reads
 * them, each on the DEM's extent; the number of polygons (0 when refused) */
static size_t check_polygons(const dem_info *dem, const char *path, const char *attribute,
                             const char *what, const char *hint)
{
    if (attribute && gf_vector_field_numeric(path, attribute, "a number in metres") != GF_SUCCESS) {
        refuse("%s; %s", gf_error_detail(), hint);
        return 0;
    }
    gf_polygons p;
    if (gf_polygons_read(path, attribute, 1.0, &p) != GF_SUCCESS) {
        refuse("%s; %s", gf_error_detail(), hint);
        return 0;
    }
    const size_t n = p.n;
    for (size_t k = 0; k < p.n; ++k) {
        const double *b = p.box + 4 * k;
        if (!gf_box_overlap(b, dem->box)) {
            refuse("%s: %s polygon %zu (x %.1f .. %.1f, y %.1f .. %.1f) lies outside the DEM %s"
                   " (x %.1f .. %.1f, y %.1f .. %.1f): draw it on this terrain (polygons of"
                   " another terrain, or coordinates in another CRS without a .prj?)",
                   path, what, k, b[0], b[2], b[1], b[3], dem->path, dem->box[0], dem->box[2],
                   dem->box[1], dem->box[3]);
            gf_polygons_free(&p);
            return 0;
        }
    }
    gf_polygons_free(&p);
    return n;
}

/* a default of the path analysis's options (its one table) */
static double path_default(const char *key)
{
    size_t n;
    const gf_path_analysis_option *o = gf_path_analysis_options(&n);
    double v = NAN;
    for (size_t k = 0; k < n; ++k)
        if (!strcmp(o[k].key, key) && gf_parse_number(o[k].dflt, &v))
            return v;
    return NAN;
}

int main(int argc, char **argv)
{
    const char *dem_path = NULL, *rel = NULL, *attr = "thickness", *ent = NULL, *res = NULL;
    const char *dam = NULL, *path = NULL, *split = NULL;
    struct {
        const char *key;
        const char **value;
    } opts[] = {{"-dem", &dem_path}, {"-release", &rel}, {"-attribute", &attr}, {"-ent", &ent},
                {"-res", &res},      {"-dam", &dam},     {"-path", &path},      {"-split", &split}};
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "-help") || !strcmp(argv[i], "-h") || !strcmp(argv[i], "--help")) {
            usage(stdout);
            return 0;
        }
        if (!strcmp(argv[i], "-version") || !strcmp(argv[i], "--version")) {
            printf("granflow %s (gfCheckInputs)\n", gf_version());
            return 0;
        }
        size_t k = 0;
        while (k < sizeof opts / sizeof opts[0] && strcmp(argv[i], opts[k].key))
            ++k;
        if (k == sizeof opts / sizeof opts[0]) {
            fprintf(stderr, "%s: unknown option '%s' (gfCheckInputs -help)\n", prog, argv[i]);
            return 2;
        }
        if (i + 1 >= argc || !*argv[i + 1]) {
            fprintf(stderr, "%s: option %s needs a value\n", prog, argv[i]);
            return 2;
        }
        *opts[k].value = argv[++i];
    }
    if (!dem_path) {
        usage(stderr);
        return 2;
    }

    /* the DEM, read as gfTerrainMesh reads it */
    dem_info dem = {.path = dem_path};
    if (gf_raster_read(dem_path, &dem.r) != GF_SUCCESS) {
        refuse("%s", gf_error_detail());
        return 1;
    }
    gf_raster_extent(&dem.r, dem.box);
    dem.has_crs = dem.r.wkt && *dem.r.wkt;
    if (!dem.has_crs)
        refuse("%s: the DEM has no coordinate reference system (add its .prj, or set one:"
               " gdal_edit.py -a_srs EPSG:...)", dem_path);

    /* the release and the mass exchange's polygons */
    size_t n_rel = 0;
    if (rel && check_crs(&dem, rel, "release"))
        n_rel = check_polygons(&dem, rel, attr, "release",
                               "the release areas are polygons with their thickness [m] in an"
                               " attribute (doc/guide/own-case.md)");
    if (ent && check_crs(&dem, ent, "entrainment areas"))
        check_polygons(&dem, ent, attr, "entrainment",
                       "the entrainment areas are polygons with the thickness [m] of the"
                       " entrainable layer in an attribute (doc/guide/terrain-case.md)");
    if (res && check_crs(&dem, res, "resistance areas"))
        check_polygons(&dem, res, NULL, "resistance",
                       "the resistance areas (forests) are polygons (doc/guide/terrain-case.md)");

    /* the dam, burnt into the DEM as gfTerrainMesh burns it (the path
     * analysis of such a run reads that DEM) */
    if (dam && check_crs(&dem, dam, "dam")) {
        gf_dam d;
        if (gf_dam_read(dam, "slope", NAN, &d) != GF_SUCCESS)
            refuse("%s; the dam is its crown as one 3D line with the wall slope in the attribute"
                   " 'slope' (doc/guide/terrain-case.md)", gf_error_detail());
        else {
            if (gf_dam_burn(&dem.r, d.n, d.xyz, d.slope, NULL, NULL) != GF_SUCCESS)
                refuse("%s: %s: draw the dam on this terrain (a line of another terrain, or in"
                       " another CRS without a .prj?)", dam, gf_error_detail());
            gf_dam_free(&d);
        }
    }

    /* the path and the split point, on the path analysis's own grid */
    size_t np = 0;
    double *xy = NULL;
    gf_path_grid g = {0};
    int have_grid = 0;
    if (path && check_crs(&dem, path, "path")) {
        if (gf_path_read(path, &np, &xy) != GF_SUCCESS)
            refuse("%s; see doc/guide/path-analysis.md", gf_error_detail());
        else if (gf_path_grid_make(&dem.r, np, xy, path_default("-width"), &g) != GF_SUCCESS)
            refuse("%s: %s: the path analysis needs the path on this DEM (a path of another"
                   " terrain?); draw it on this DEM, or remove it to run without the path analysis"
                   " (doc/guide/path-analysis.md)", path, gf_error_detail());
        else
            have_grid = 1;
    }
    if (split && check_crs(&dem, split, "split point")) {
        double x, y;
        if (!path)
            refuse("%s: a split point needs the avalanche path (Inputs/LINES/path_aimec.shp);"
                   " add the path or remove the split point", split);
        else if (gf_point_read(split, &x, &y) != GF_SUCCESS)
            refuse("%s; the split point is one point on the path, below the release"
                   " (doc/guide/path-analysis.md)", gf_error_detail());
        else if (!gf_raster_covers(&dem.r, x, y))
            refuse("%s: the split point (%.1f, %.1f) lies outside the DEM %s (x %.1f .. %.1f,"
                   " y %.1f .. %.1f): place it on this terrain's path, or remove it",
                   split, x, y, dem_path, dem.box[0], dem.box[2], dem.box[1], dem.box[3]);
        else if (have_grid) {
            double dist;
            size_t i_beta;
            const size_t i_split = gf_path_snap(&g, x, y, &dist);
            if (gf_path_beta_point(&g, i_split, path_default("-beta-angle"),
                                   path_default("-ds-min"), &i_beta) != GF_SUCCESS)
                refuse("%s: %s: the runout area starts at the beta point below the split point;"
                       " place the split point higher up the path (doc/guide/path-analysis.md)",
                       split, gf_error_detail());
        }
    }
    gf_path_grid_free(&g);
    free(xy);

    if (refusals == 0) {
        printf("demCell=%.15g\ndemSize=%dx%d\n", dem.r.gt[1], dem.r.nx, dem.r.ny);
        if (rel)
            printf("releasePolygons=%zu\n", n_rel);
    }
    gf_raster_free(&dem.r);
    return refusals ? 1 : 0;
}
