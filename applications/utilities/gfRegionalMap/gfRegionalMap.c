/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * gfRegionalMap — every release area of a valley, for every scenario, run
 * on the ensemble workers and merged into regional hazard indication maps
 * (issue 52; doc/guide/regional.md, doc/theory/regional.md):
 *
 *   gfRegionalMap [-dict FILE] [-out DIR] [-np N] [-check] [-alphaBeta] CASE
 *   gfRegionalMap -slurm [-tasks T] [-np N] [-dict FILE] [-out DIR] [-alphaBeta] CASE
 *   gfRegionalMap -task K -tasks T [-np N] [-dict FILE] [-out DIR] CASE
 *   gfRegionalMap -collect [-dict FILE] [-out DIR] [-alphaBeta] CASE
 *   gfRegionalMap -help | -version
 *
 * CASE is a meshed terrain case whose system/controlDict sets the release
 * at the start (setFields (releaseDict);), e.g. tutorials/avaKot/run-coarse
 * after its Allrun -coarse.  The dictionary (default CASE/system/regionalDict):
 *
 *     releaseAreas      "PRA/releaseAreas.gpkg"; // polygons (OGR), relative to CASE or absolute
 *     idAttribute       id;           // integer field naming each release (default id)
 *     releases          (1 3 4);      // optional: only these ids (default: every polygon)
 *     slopeAttribute    slope_deg;    // mean slope [deg] (Salm scenarios; default slope_deg)
 *     altitudeAttribute altitude_m;   // mean altitude [m] (Salm scenarios; default altitude_m)
 *     gradient          0.0005;       // Salm: d0* change per m of altitude [m/m] (default 0)
 *     zRef              2000;         // Salm: altitude of d0* [m] (needed when a gradient is not 0)
 *     measured          normal;       // the depth normal to the terrain, or vertical (default normal)
 *     threshold         1;            // peak pressure [kPa] of a reached cell (count, area; default 1)
 *     zones             (1 10 30);    // peak pressure class limits [kPa], increasing (default (1 10 30))
 *     memberFiles       maps;         // maps: a member keeps its log, peak rasters (GeoTIFF), outline,
 *                                     // path, mass.csv, summary.dat; all: every file of its run (default maps)
 *     scenarios
 *     {
 *         small { d0Star 0.5; }                   // d0 = (d0* + gradient (z - zRef)) f(slope)
 *         large { d0Star 1.0; gradient 0; }       // gradient, zRef per scenario override the top's
 *         given { thicknessAttribute d0_m; factor 1.2; }  // the polygon's own depth x factor
 *     }
 *     clip                            // optional: each release on its own clipped mesh
 *     {
 *         buffer   300;    // [m] around the release and its paths, in [0, 100000] (default 300)
 *         reach    1000;   // [m] a path goes on along level ground this far, in [0, 100000] (1000)
 *         climb    5;      // [m] pits this deep are walked through, in [0, 100] (5)
 *         retries  2;      // runs again on a buffer x 2 (100 m from 0), in [0, 6] (2)
 *         keep     no;     // keep each clip's meshes after its release ran (default no)
 *     }
 *
 * gfReleaseAreas -d0 writes such polygons (id, slope_deg, altitude_m, d0_m);
 * any polygon file with an integer id and a thickness attribute will do.
 * Every release x scenario is a member: a copy of the case's template
 * (OUT/template: system/ and 0/ copied, the meshes linked; its controlDict
 * writes only the end time, peakFields and hazardMaps on, its pathAnalysis
 * removed), OUT/members/SCENARIO_rID/ with release.shp (that one polygon)
 * and a system/releaseDict 'polygons { file release.shp; value D; }'.  The
 * members run in N workers (faGranularFlowFoam -members -, the mesh loaded
 * once per worker; N default: the cores).  Each member's result is in its
 * folder (result): started again, the command reads every result and runs
 * only the members without one (a killed batch resumes; nothing runs twice).
 * A member whose depth is refused (Salm: d0* + gradient (z - zRef) < 0, a
 * slope outside [15, 90] deg; a depth <= 0) or whose run fails is listed
 * with its reason and the others go on.
 *
 * Writes, per scenario, OUT/SCENARIO/: pressurePeakMax.tif, hPeakMax.tif,
 * speedPeakMax.tif (each cell's largest peak over the scenario's members,
 * gf_merge_max), count.tif (the members whose peak pressure exceeds the
 * threshold there), releaseId.tif (the id of the member giving the largest
 * peak pressure, the first of equal ones; NODATA where no member reaches the
 * cell, peak pressure 0), zones.tif (0 below zones[0], k where the largest
 * peak pressure exceeds zones[k-1], NODATA outside the mesh); OUT/members.csv
 * (release, scenario, depth, status, seconds, affected area above the
 * threshold, largest peak pressure, reason) and OUT/summary.txt.  Prints
 * shell-readable lines name=value at the end (members, ran, resumed, failed,
 * seconds, secondsPerMember).  Exit status 0 when every member ran, 3 when
 * some failed (their maps merged without them), 1 on refused input (the file,
 * the key and its allowed range named), 2 on a wrong command line.
 *
 * -check reads the dictionary and the polygons and prints every member with
 * its depth, writing nothing.
 *
 * clip: each release runs on a mesh of its own part of the case's DEM
 * (doc/theory/regional.md, section 6): the box of its cells and of the
 * steepest-descent paths leaving them (gf_downslope_box: D8, pits up to climb
 * deep walked through, level ground followed for reach), widened by buffer
 * and aligned to the case's coarsened node grid, cut from the DEM
 * (OUT/clips/rID_bBUFFER/Inputs/clipDEM.tif: the region's pixels), meshed by
 * gfTerrainMesh with the case's coarsen and depth, and run on one worker for
 * all its scenarios; the cost grows with the releases, not with releases x
 * region.  Once they ran, the clip is removed (its log OUT/clips/rID_bBUFFER.log
 * stays; keep yes keeps it): the disk holds the members' results, not a mesh
 * per release.  The members' rasters are on their clip's grid; the merge places
 * them on the region's (the case's DEM: the same pixel size, an origin whole
 * pixels away, both checked); a DEM cell no clip holds is 0 (not reached).
 * A member whose flow reaches the outer faces of a clip side where the
 * region goes on and loses more than 1e-6 of its volume through the mesh's
 * boundary left its clip: it runs again on the buffer doubled (retries); if
 * it still does, members.csv says so in its reason (with outflow_m3,
 * volume_m3, clipBuffer_m) and summary.txt lists it (BOUNDARY), boundary=N.
 *
 * -slurm: DIR/slurm/array.sh (task K of T: -task K -tasks T, the members,
 * with clip the releases, whose index is K - 1 modulo T, those with a result
 * skipped) and DIR/slurm/collect.sh (-collect) written and submitted with
 * sbatch, the merge after the array (--dependency=afterany); T default: one
 * task per member (release) to run, at most 1000; -np N: the workers of a
 * task (--cpus-per-task).  Prints array=JOB, collect=JOB.  -collect reads
 * the results and merges (a member without a result is failed with its
 * reason); submitting again runs only what has no result.
 *
 * -alphaBeta: each release's steepest-descent thalweg from its highest cell
 * of the case's DEM (constant/terrainProperties dem; D8 through pits up to
 * 5 m deep, on along level ground for 1000 m, as gfReleaseAreas), its
 * alpha-beta runout (Lied and Bakkehoi 1980; gf_alpha_beta_profile's
 * defaults) and beside it each member's dynamic runout: the farthest
 * thalweg point whose peak pressure exceeds the threshold.  DIR/alphaBeta.csv
 * (release, scenario, status, z_top_m, beta_deg, alpha_deg, s_beta_m,
 * s_alpha_m, s_alpha_minus_sd_m, s_alpha_plus_sd_m, s_thalweg_m,
 * s_dynamic_m, dynamic_minus_alpha_m, reason; distances along the thalweg
 * from the top, horizontal; empty where there is none: s_alpha when the
 * alpha line meets no terrain before the thalweg ends, reason when the
 * release has a thalweg and alpha-beta); the releases' polygons in
 * DIR/releases/.
 */
#define _GNU_SOURCE
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <unistd.h>

#include <cpl_error.h>
#include <gdal.h>
#include <ogr_api.h>
#include <ogr_srs_api.h>

#include "gf_dict.h"
#include "gf_members.h"
#include "granflow/path_analysis.h"
#include "granflow/qgis_project.h"
#include "granflow/regional.h"
#include "granflow/terrain.h"
#include "granflow/version.h"
#include "granflow/workers.h"

#define MAXSCEN 32
#define MAXZONES 8

static const char *prog = "gfRegionalMap";

static void die(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "%s: ", prog);
    vfprintf(stderr, fmt, ap);
    fprintf(stderr, "\n");
    va_end(ap);
    exit(1);
}

static double now(void)
{
    struct timeval t;
    gettimeofday(&t, NULL);
    return (double)t.tv_sec + 1e-6 * (double)t.tv_usec;
}

/*---------------------------------------------------------------- the dictionary --*/

typedef struct scenario {
    char name[64];
    int salm;          /* 1: Salm's depth; 0: the polygon's attribute x factor */
    double d0star, gradient, zref, factor;
    char attr[64];
} scenario;

typedef struct config {
    const char *path;
    char *areas;        /* the polygon file (absolute) */
    char id_attr[64], slope_attr[64], alt_attr[64];
    long *only;         /* releases (ids), or NULL */
    size_t n_only;
    int vertical;
    int all_files;      /* memberFiles all: keep every file of a member's run */
    double threshold;
    double zones[MAXZONES];
    size_t n_zones;
    scenario s[MAXSCEN];
    size_t ns;
    /* clip { }: each release on its own clipped sub-domain */
    int clip;
    double buffer, reach, climb;
    long retries;
    int keep;           /* keep each clip's meshes after its release ran */
} config;

/* the dictionary is read with the typed readers of common/gf_dict.h, which
 * refuse a bad value naming the file, the line, the key and the range */

static int plain_name(const char *s)
{
    if (!*s) return 0;
    for (const char *p = s; *p; ++p)
        if (!((*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z') || (*p >= '0' && *p <= '9') || *p == '_' ||
              *p == '-'))
            return 0;
    return 1;
}

static void read_config(const char *path, const char *casedir, config *c)
{
    char err[2048];
    memset(c, 0, sizeof *c);
    c->path = path;
    gf_dict *D = gf_dict_read(path, err, sizeof err);
    if (!D) die("%s", err);
    const char *areas = gf_dict_word(D, "releaseAreas", NULL, 0);
    if (!areas) gf_dict_refuse(c->path, NULL, "releaseAreas", "required: the release polygons (\"file\", relative to the case or absolute)");
    if (areas[0] == '/') {
        c->areas = strdup(areas);
    } else {
        c->areas = gf_path(casedir, areas);
    }
    if (!gf_exists(c->areas)) gf_dict_refuse(c->path, gf_dict_find(D, "releaseAreas"), "releaseAreas", "%s: no such file", c->areas);
    char *real = realpath(c->areas, NULL);   /* named without ../ in the summary */
    if (real) free(c->areas), c->areas = real;
    snprintf(c->id_attr, sizeof c->id_attr, "%s", gf_dict_word(D, "idAttribute", "id", 63));
    snprintf(c->slope_attr, sizeof c->slope_attr, "%s", gf_dict_word(D, "slopeAttribute", "slope_deg", 63));
    snprintf(c->alt_attr, sizeof c->alt_attr, "%s", gf_dict_word(D, "altitudeAttribute", "altitude_m", 63));
    const gf_dict_entry *e = gf_dict_find(D, "releases");
    if (e) {
        double v[4096];
        c->n_only = gf_dict_numbers(e, c->path, "releases", v, 4096, 0, 2147483647.0);
        c->only = malloc(c->n_only * sizeof *c->only);
        for (size_t k = 0; k < c->n_only; ++k) {
            if (v[k] != floor(v[k])) gf_dict_refuse(c->path, e, "releases", "%g is not a whole number (an id)", v[k]);
            c->only[k] = (long)v[k];
        }
    }
    const char *m = gf_dict_word(D, "measured", "normal", 63);
    if (strcmp(m, "normal") && strcmp(m, "vertical"))
        gf_dict_refuse(c->path, gf_dict_find(D, "measured"), "measured", "'%s': allowed normal or vertical", m);
    c->vertical = strcmp(m, "vertical") == 0;
    const char *mf = gf_dict_word(D, "memberFiles", "maps", 63);
    if (strcmp(mf, "maps") && strcmp(mf, "all"))
        gf_dict_refuse(c->path, gf_dict_find(D, "memberFiles"), "memberFiles", "'%s': allowed maps or all", mf);
    c->all_files = strcmp(mf, "all") == 0;
    c->threshold = gf_dict_number(D, "threshold", 1, 1e-6, 1e6);
    e = gf_dict_find(D, "zones");
    if (e) {
        c->n_zones = gf_dict_numbers(e, c->path, "zones", c->zones, MAXZONES, 1e-6, 1e6);
        for (size_t k = 1; k < c->n_zones; ++k)
            if (!(c->zones[k] > c->zones[k - 1]))
                gf_dict_refuse(c->path, e, "zones", "%g after %g: the limits must increase", c->zones[k], c->zones[k - 1]);
    } else {
        c->n_zones = 3;
        c->zones[0] = 1, c->zones[1] = 10, c->zones[2] = 30;
    }
    const double gradient = gf_dict_number(D, "gradient", 0, -1, 1);
    const double zref = gf_dict_number(D, "zRef", 1e300, -500, 9000); /* 1e300: not given */
    e = gf_dict_find(D, "scenarios");
    if (!e) gf_dict_refuse(c->path, NULL, "scenarios", "required: a dictionary { NAME { d0Star D; } ... } of at least one scenario");
    if (!e->sub || e->sub->n == 0)
        gf_dict_refuse(c->path, e, "scenarios", "expected a dictionary { NAME { d0Star D; } ... } of at least one scenario");
    if (e->sub->n > MAXSCEN) gf_dict_refuse(c->path, e, "scenarios", "%zu scenarios: at most %d", e->sub->n, MAXSCEN);
    for (size_t k = 0; k < e->sub->n; ++k) {
        gf_dict_entry *se = &e->sub->e[k];
        se->used = 1;
        char full[256];
        snprintf(full, sizeof full, "scenarios/%s", se->key);
        if (!plain_name(se->key) || strlen(se->key) >= 48)
            gf_dict_refuse(c->path, se, full, "a scenario's name is a folder name: letters, digits, _ and -, at most 47 characters");
        if (!se->sub) gf_dict_refuse(c->path, se, full, "expected a dictionary { d0Star D; } or { thicknessAttribute NAME; }");
        for (size_t j = 0; j < k; ++j)
            if (strcmp(c->s[j].name, se->key) == 0) gf_dict_refuse(c->path, se, full, "a second scenario of this name");
        scenario *s = &c->s[c->ns++];
        snprintf(s->name, sizeof s->name, "%s", se->key);
        const gf_dict *sd = se->sub;
        const int has_d0 = gf_dict_find(sd, "d0Star") != NULL, has_attr = gf_dict_find(sd, "thicknessAttribute") != NULL;
        if (has_d0 == has_attr)
            gf_dict_refuse(c->path, se, full, "takes one of d0Star (Salm's depth [m], in [0, 20]) and thicknessAttribute (a field of the polygons)");
        if (has_d0) {
            s->salm = 1;
            s->d0star = gf_dict_number(sd, "d0Star", NAN, 0, 20);
            s->gradient = gf_dict_number(sd, "gradient", gradient, -1, 1);
            s->zref = gf_dict_number(sd, "zRef", zref, -500, 9000);
            if (s->zref == 1e300) {
                if (s->gradient != 0) gf_dict_refuse(c->path, se, full, "gradient %g needs zRef (the altitude of d0Star [m], in [-500, 9000])", s->gradient);
                s->zref = 0;
            }
        } else {
            snprintf(s->attr, sizeof s->attr, "%s", gf_dict_word(sd, "thicknessAttribute", NULL, 63));
            s->factor = gf_dict_number(sd, "factor", 1, 1e-6, 100);
        }
    }
    const gf_dict *cl = gf_dict_sub(D, "clip", 0);
    if (cl) {
        c->clip = 1;
        c->buffer = gf_dict_number(cl, "buffer", 300, 0, 100000);
        c->reach = gf_dict_number(cl, "reach", 1000, 0, 100000);
        c->climb = gf_dict_number(cl, "climb", 5, 0, 100);
        c->retries = gf_dict_whole(cl, "retries", 2, 0, 6);
        c->keep = gf_dict_bool(cl, "keep", 0);
    }
    const gf_dict *in = NULL;
    const gf_dict_entry *u = gf_dict_unused(D, &in);
    if (u) {
        char full[256];
        gf_dict_key_path(in, u->key, full, sizeof full);
        gf_dict_refuse(c->path, u, full,
            "unknown key (allowed: releaseAreas idAttribute releases slopeAttribute altitudeAttribute gradient zRef "
            "measured threshold zones memberFiles scenarios clip; a scenario: d0Star gradient zRef, or thicknessAttribute factor; "
            "clip: buffer reach climb retries keep)");
    }
    gf_dict_free(D);
}

/*---------------------------------------------------------------- the releases --*/

typedef struct release {
    long id;
    OGRGeometryH geom;
    double slope, alt;          /* NAN when the file has no such field */
    double attr[MAXSCEN];       /* the scenario's thickness attribute (NAN: none) */
} release;

typedef struct areas {
    size_t n;
    release *r;
    OGRSpatialReferenceH srs;   /* the layer's (may be NULL) */
} areas;

static int field_index(OGRFeatureDefnH def, const char *name)
{
    return OGR_FD_GetFieldIndex(def, name);
}

static void read_areas(const config *c, areas *A)
{
    memset(A, 0, sizeof *A);
    /* the fields: numeric, named with the ones there are when missing */
    char need[256];
    snprintf(need, sizeof need, "a whole number naming each release (%s idAttribute)", c->path);
    if (gf_vector_field_numeric(c->areas, c->id_attr, need)) die("%s", gf_error_detail());
    int any_salm = 0;
    for (size_t s = 0; s < c->ns; ++s) {
        if (c->s[s].salm) {
            any_salm = 1;
            continue;
        }
        char what[512];
        snprintf(what, sizeof what, "a depth in metres (%s scenarios/%s/thicknessAttribute)", c->path, c->s[s].name);
        if (gf_vector_field_numeric(c->areas, c->s[s].attr, what)) die("%s", gf_error_detail());
    }
    if (any_salm) {
        char what[512];
        snprintf(what, sizeof what, "the mean slope in degrees of each area, for Salm's depth (%s slopeAttribute)", c->path);
        if (gf_vector_field_numeric(c->areas, c->slope_attr, what)) die("%s", gf_error_detail());
        snprintf(what, sizeof what, "the mean altitude in metres of each area, for Salm's depth (%s altitudeAttribute)", c->path);
        if (gf_vector_field_numeric(c->areas, c->alt_attr, what)) die("%s", gf_error_detail());
    }
    GDALDatasetH ds = GDALOpenEx(c->areas, GDAL_OF_VECTOR | GDAL_OF_READONLY, NULL, NULL, NULL);
    if (!ds) die("%s (releaseAreas of %s): OGR cannot open it", c->areas, c->path);
    OGRLayerH L = GDALDatasetGetLayer(ds, 0);
    if (!L) die("%s (releaseAreas of %s): no layer", c->areas, c->path);
    OGRFeatureDefnH def = OGR_L_GetLayerDefn(L);
    const int fid = field_index(def, c->id_attr);
    const int fs = field_index(def, c->slope_attr), fa = field_index(def, c->alt_attr);
    int fattr[MAXSCEN];
    for (size_t s = 0; s < c->ns; ++s) fattr[s] = c->s[s].salm ? -1 : field_index(def, c->s[s].attr);
    OGRSpatialReferenceH srs = OGR_L_GetSpatialRef(L);
    if (srs) A->srs = OSRClone(srs);
    size_t cap = 0;
    OGRFeatureH f;
    OGR_L_ResetReading(L);
    while ((f = OGR_L_GetNextFeature(L))) {
        OGRGeometryH g = OGR_F_GetGeometryRef(f);
        const long fnum = (long)OGR_F_GetFID(f);
        if (!g || (wkbFlatten(OGR_G_GetGeometryType(g)) != wkbPolygon &&
                   wkbFlatten(OGR_G_GetGeometryType(g)) != wkbMultiPolygon))
            die("%s (releaseAreas of %s): feature %ld has no polygon", c->areas, c->path, fnum);
        if (!OGR_F_IsFieldSetAndNotNull(f, fid))
            die("%s (releaseAreas of %s): feature %ld has no %s (idAttribute)", c->areas, c->path, fnum, c->id_attr);
        const double idv = OGR_F_GetFieldAsDouble(f, fid);
        if (idv != floor(idv) || idv < 0 || idv > 2147483647.0)
            die("%s (releaseAreas of %s): feature %ld: %s %g is not a whole number in [0, 2147483647]", c->areas, c->path,
                fnum, c->id_attr, idv);
        const long id = (long)idv;
        int keep = !c->only;
        for (size_t k = 0; k < c->n_only; ++k) keep |= c->only[k] == id;
        if (keep) {
            for (size_t k = 0; k < A->n; ++k)
                if (A->r[k].id == id)
                    die("%s (releaseAreas of %s): %s %ld names two features (%s idAttribute: one id per release)",
                        c->areas, c->path, c->id_attr, id, c->path);
            if (A->n == cap) {
                cap = cap ? 2 * cap : 16;
                A->r = realloc(A->r, cap * sizeof *A->r);
                if (!A->r) die("out of memory");
            }
            release *r = &A->r[A->n++];
            r->id = id;
            r->geom = OGR_G_Clone(g);
            r->slope = fs >= 0 && OGR_F_IsFieldSetAndNotNull(f, fs) ? OGR_F_GetFieldAsDouble(f, fs) : NAN;
            r->alt = fa >= 0 && OGR_F_IsFieldSetAndNotNull(f, fa) ? OGR_F_GetFieldAsDouble(f, fa) : NAN;
            for (size_t s = 0; s < c->ns; ++s)
                r->attr[s] = fattr[s] >= 0 && OGR_F_IsFieldSetAndNotNull(f, fattr[s]) ? OGR_F_GetFieldAsDouble(f, fattr[s])
                                                                                     : NAN;
        }
        OGR_F_Destroy(f);
    }
    GDALClose(ds);
    for (size_t k = 0; k < c->n_only; ++k) {
        int found = 0;
        for (size_t j = 0; j < A->n; ++j) found |= A->r[j].id == c->only[k];
        if (!found)
            die("%s: releases: id %ld is not in %s (field %s)", c->path, c->only[k], c->areas, c->id_attr);
    }
    if (A->n == 0) die("%s (releaseAreas of %s): no release polygon", c->areas, c->path);
}

/* the depth of release r in scenario s; 0, or -1 with the reason */
static int depth(const config *c, const release *r, size_t s, double *d, char *why, size_t wsize)
{
    const scenario *sc = &c->s[s];
    *d = NAN;
    if (sc->salm) {
        if (isnan(r->slope) || isnan(r->alt)) {
            snprintf(why, wsize, "no %s or %s value for Salm's depth", c->slope_attr, c->alt_attr);
            return -1;
        }
        if (gf_release_depth(sc->d0star, sc->gradient, r->alt, sc->zref, r->slope, d)) {
            snprintf(why, wsize, "depth refused: %s", gf_error_detail());
            *d = NAN;
            return -1;
        }
    } else {
        if (isnan(r->attr[s])) {
            snprintf(why, wsize, "no %s value (thicknessAttribute)", sc->attr);
            return -1;
        }
        *d = r->attr[s] * sc->factor;
    }
    if (!(*d > 0) || !isfinite(*d) || *d > 100) {
        snprintf(why, wsize, "depth %g m outside the allowed range (0, 100] m", *d);
        return -1;
    }
    return 0;
}

/*---------------------------------------------------------------- the members --*/

typedef struct member {
    size_t rel, scen;
    double depth;
    int pre_failed;       /* the depth was refused: never run */
    char why[2048];
    /* the result */
    int done, ok, resumed;
    double seconds, affected, maxppr;
    /* clipped: the outflow through the mesh's boundary [m3], the release
     * volume [m3], the clip's buffer [m] and whether the clip is the whole DEM */
    double outflow, volume, buffer;
    int whole, edge;   /* edge: reached a clip side where the region goes on */
} member;

typedef struct job {
    const config *c;
    const areas *A;
    member *m;
    size_t nm;
    char *dir, *templ, *members;
    gf_workers *pool;
    pthread_mutex_t lock;
    size_t next, finished, total;
    double t0;
    /* clipped runs */
    gf_raster dem;           /* the case's DEM: the region's grid (case_dem) */
    char *dem_path;          /* its file */
    int coarsen;
    double depth_slab;
    char *casedir, *clips;
    size_t next_rel;
    /* a SLURM array task: task (1..ntasks) runs the members (clipped: the
     * releases) whose index is task - 1 modulo ntasks; 0: all */
    long task, ntasks;
} job;

static void member_dir(const job *j, const member *m, char *buf, size_t size)
{
    snprintf(buf, size, "%s/%s_r%ld", j->members, j->c->s[m->scen].name, j->A->r[m->rel].id);
}

/* result: "ok DEPTH SECONDS AREA MAXPPR" or "failed DEPTH SECONDS" and the
 * reason on the second line */
static int read_result(const char *md, member *m)
{
    char *f = gf_path(md, "result");
    FILE *in = fopen(f, "r");
    free(f);
    if (!in) return 0;
    char st[16] = "";
    double d, sec, a = NAN, p = NAN, of = NAN, vol = NAN, buf = NAN;
    int whole = 0, edge = 0;
    const int n =
        fscanf(in, "%15s %lf %lf %lf %lf %lf %lf %lf %d %d", st, &d, &sec, &a, &p, &of, &vol, &buf, &whole, &edge);
    m->outflow = NAN, m->volume = NAN, m->buffer = NAN, m->whole = 0, m->edge = 0;
    if (n == 10) m->outflow = of, m->volume = vol, m->buffer = buf, m->whole = whole, m->edge = edge;
    int okr = 0;
    if ((n == 5 || n == 10) && strcmp(st, "ok") == 0) {
        m->ok = 1, okr = 1;
    } else if (n >= 3 && strcmp(st, "failed") == 0) {
        m->ok = 0, okr = 1;
        int ch;
        while ((ch = fgetc(in)) != EOF && ch != '\n') {
        }
        if (!fgets(m->why, sizeof m->why, in)) m->why[0] = 0;
        m->why[strcspn(m->why, "\n")] = 0;
    }
    fclose(in);
    if (!okr) return 0;
    m->seconds = sec, m->affected = a, m->maxppr = p;
    m->done = 1, m->resumed = 1;
    return 1;
}

static void write_result(const char *md, const member *m)
{
    char *f = gf_path(md, "result"), *tmp = gf_path(md, "result.tmp");
    FILE *out = fopen(tmp, "w");
    if (!out) die("cannot write %s", tmp);
    if (m->ok)
        fprintf(out, "ok %.17g %.3f %.17g %.17g %.17g %.17g %.17g %d %d\n", m->depth, m->seconds, m->affected,
                m->maxppr, m->outflow, m->volume, m->buffer, m->whole, m->edge);
    else
        fprintf(out, "failed %.17g %.3f\n%s\n", m->depth, m->seconds, m->why);
    if (fclose(out) || rename(tmp, f)) die("cannot write %s", f);
    free(f), free(tmp);
}

/* the one polygon of release r as a shapefile (the layer's CRS: its .prj) */
static int write_release_shp(const areas *A, const release *r, const char *path, char *why, size_t wsize)
{
    GDALDriverH drv = GDALGetDriverByName("ESRI Shapefile");
    if (!drv) die("GDAL lacks the ESRI Shapefile driver");
    GDALDatasetH ds = GDALCreate(drv, path, 0, 0, 0, GDT_Unknown, NULL);
    if (!ds) {
        snprintf(why, wsize, "cannot write %s: %s", path, CPLGetLastErrorMsg());
        return -1;
    }
    OGRLayerH L = GDALDatasetCreateLayer(ds, "release", A->srs, wkbMultiPolygon, NULL);
    OGRFieldDefnH fd = OGR_Fld_Create("id", OFTInteger);
    int st = !L || OGR_L_CreateField(L, fd, 1) != OGRERR_NONE;
    OGR_Fld_Destroy(fd);
    if (!st) {
        OGRFeatureH f = OGR_F_Create(OGR_L_GetLayerDefn(L));
        OGR_F_SetFieldInteger(f, 0, (int)r->id);
        OGR_F_SetGeometry(f, r->geom);
        st = OGR_L_CreateFeature(L, f) != OGRERR_NONE;
        OGR_F_Destroy(f);
    }
    GDALClose(ds);
    if (st) snprintf(why, wsize, "cannot write %s: %s", path, CPLGetLastErrorMsg());
    return st ? -1 : 0;
}

static int make_member(const job *j, const char *templ, const member *m, const char *md, char *why, size_t wsize)
{
    if (gf_member_copy(templ, md, why, wsize)) return -1;
    char *shp = gf_path(md, "release.shp");
    const int st = write_release_shp(j->A, &j->A->r[m->rel], shp, why, wsize);
    if (st) {
        free(shp);
        return -1;
    }
    char *rd = gf_path(md, "system/releaseDict");
    FILE *out = fopen(rd, "w");
    if (!out) {
        snprintf(why, wsize, "cannot write %s", rd);
        free(rd), free(shp);
        return -1;
    }
    fprintf(out,
            "FoamFile { version 2.0; format ascii; class dictionary; location \"system\"; object releaseDict; }\n"
            "// gfRegionalMap: release %ld, scenario %s\n"
            "default 0;\n"
            "regions\n(\n    polygons\n    {\n        file      \"release.shp\";   // in the member's folder\n"
            "        value     %.17g;\n        measured  %s;\n    }\n);\n",
            j->A->r[m->rel].id, j->c->s[m->scen].name, m->depth, j->c->vertical ? "vertical" : "normal");
    const int bad = fclose(out);
    if (bad) snprintf(why, wsize, "cannot write %s", rd);
    free(rd), free(shp);
    return bad ? -1 : 0;
}

/* what a member that ran reached: the area above the threshold, the largest peak pressure */
static int score(const job *j, const char *md, member *m, char *why, size_t wsize)
{
    static const char *need[] = {"hPeak.tif", "speedPeak.tif"};
    char *hm = gf_path(md, "postProcessing/hazardMaps");
    for (size_t k = 0; k < 2; ++k) {
        char *f = gf_path(hm, need[k]);
        const int e = gf_exists(f);
        free(f);
        if (!e) {
            snprintf(why, wsize, "no postProcessing/hazardMaps/%s", need[k]);
            free(hm);
            return -1;
        }
    }
    char *ppr = gf_path(hm, "pressurePeak.tif");
    free(hm);
    gf_raster r;
    if (gf_raster_read(ppr, &r)) {
        snprintf(why, wsize, "no peak pressure raster (%s)", gf_error_detail());
        free(ppr);
        return -1;
    }
    free(ppr);
    const double cell = fabs(r.gt[1] * r.gt[5]);
    double a = 0, p = 0;
    for (size_t c = 0; c < (size_t)r.nx * (size_t)r.ny; ++c) {
        if (isnan(r.z[c])) continue;
        if (r.z[c] > j->c->threshold) a += cell;
        if (r.z[c] > p) p = r.z[c];
    }
    gf_raster_free(&r);
    m->affected = a, m->maxppr = p;
    return 0;
}

/* memberFiles maps: what a member's run wrote beyond what the merge, the
 * alpha-beta and a look at the run need goes (the start fields 0/, the
 * ASCII copies of the rasters with their .prj, the end thickness and
 * arrival-time rasters, the centre-of-mass series); kept: the log, the peak rasters (GeoTIFF), the
 * affected-area outline, the centre-of-mass path, mass.csv and summary.dat */
static void slim_member(const job *j, const char *md)
{
    if (j->c->all_files) return;
    char *zero = gf_path(md, "0"), *com = gf_path(md, "postProcessing/centreOfMass");
    char *rm[] = {"rm", "-rf", zero, com, NULL};
    gf_run(rm, NULL);
    free(zero), free(com);
    static const char *gone[] = {"hPeak.asc", "speedPeak.asc", "pressurePeak.asc", "thickness.asc", "thickness.tif",
                                 "arrivalTime.asc", "arrivalTime.tif", "hPeak.prj", "speedPeak.prj",
                                 "pressurePeak.prj", "thickness.prj", "arrivalTime.prj"};
    for (size_t k = 0; k < sizeof gone / sizeof gone[0]; ++k) {
        char rel[128];
        snprintf(rel, sizeof rel, "postProcessing/hazardMaps/%s", gone[k]);
        char *f = gf_path(md, rel);
        unlink(f);
        free(f);
    }
}

static void *runner(void *arg)
{
    job *j = arg;
    for (;;) {
        pthread_mutex_lock(&j->lock);
        size_t k = j->next;
        while (k < j->nm && j->m[k].done) ++k;
        j->next = k + 1;
        pthread_mutex_unlock(&j->lock);
        if (k >= j->nm) return NULL;
        member *m = &j->m[k];
        char md[4096], why[2048] = "";
        member_dir(j, m, md, sizeof md);
        const double t = now();
        int ok = 0;
        if (make_member(j, j->templ, m, md, why, sizeof why) == 0) {
            if (gf_workers_run(j->pool, md, &ok, why, sizeof why)) die("%s", gf_error_detail());
            if (ok && score(j, md, m, why, sizeof why)) ok = 0;
            gf_remove_times(md);
            slim_member(j, md);
        }
        m->ok = ok;
        m->seconds = now() - t;
        if (!ok) snprintf(m->why, sizeof m->why, "%s", why);
        for (char *p = m->why; *p; ++p)
            if (*p == '\n' || *p == '\r') *p = ' ';
        write_result(md, m);
        pthread_mutex_lock(&j->lock);
        m->done = 1;
        ++j->finished;
        if (ok)
            printf("member %-20s %3zu/%zu: depth %.3f m, %.1f s, affected %.0f m2, max %.1f kPa\n", strrchr(md, '/') + 1,
                   j->finished, j->total, m->depth, m->seconds, m->affected, m->maxppr);
        else
            printf("member %-20s %3zu/%zu: FAILED (%s)\n", strrchr(md, '/') + 1, j->finished, j->total, m->why);
        fflush(stdout);
        pthread_mutex_unlock(&j->lock);
    }
}

/*---------------------------------------------------------------- the merge --*/

static void write_tif(const char *dir, const char *name, const gf_raster *grid, const double *v)
{
    char *f = gf_path(dir, name);
    char *tmp = NULL;
    if (asprintf(&tmp, "%s.tmp.tif", f) < 0) die("out of memory");
    if (gf_raster_write(tmp, "GTiff", grid, v)) die("%s: %s", f, gf_error_detail());
    if (rename(tmp, f)) die("cannot write %s", f);
    free(f), free(tmp);
}

/* the merge's count.tif (releases reaching each cell), releaseId.tif (the
 * release of the cell's largest peak pressure) and zones.tif (the pressure
 * zone of the merged peak pressure mx), on grid */
static void write_counts(const char *outdir, const gf_raster *grid, size_t nc, const double *mx,
                         const unsigned *count, const long *who, const config *c)
{
    double *a = calloc(nc ? nc : 1, sizeof *a);
    if (!a) die("out of memory");
    for (size_t q = 0; q < nc; ++q) a[q] = isnan(mx[q]) ? NAN : (double)count[q];
    write_tif(outdir, "count.tif", grid, a);
    for (size_t q = 0; q < nc; ++q) a[q] = isnan(mx[q]) || !(mx[q] > 0) ? NAN : (double)who[q];
    write_tif(outdir, "releaseId.tif", grid, a);
    for (size_t q = 0; q < nc; ++q) {
        if (isnan(mx[q])) {
            a[q] = NAN;
            continue;
        }
        size_t z = 0;
        while (z < c->n_zones && mx[q] > c->zones[z]) ++z;
        a[q] = (double)z;
    }
    write_tif(outdir, "zones.tif", grid, a);
    free(a);
}


/* the scenario's merged maps; the members merged */
static size_t merge(const job *j, size_t s, char *outdir)
{
    const config *c = j->c;
    size_t n = 0;
    for (size_t k = 0; k < j->nm; ++k) n += j->m[k].scen == s && j->m[k].ok;
    if (n == 0) return 0;
    mkdir(outdir, 0755);
    static const char *field[] = {"pressurePeak", "hPeak", "speedPeak"};
    gf_raster grid;
    memset(&grid, 0, sizeof grid);
    for (size_t fi = 0; fi < 3; ++fi) {
        gf_raster *r = calloc(n, sizeof *r);
        const double **v = calloc(n, sizeof *v);
        long *ids = calloc(n, sizeof *ids);
        if (!r || !v || !ids) die("out of memory");
        size_t i = 0;
        for (size_t k = 0; k < j->nm; ++k) {
            const member *m = &j->m[k];
            if (m->scen != s || !m->ok) continue;
            char md[4096], rel[256];
            member_dir(j, m, md, sizeof md);
            snprintf(rel, sizeof rel, "postProcessing/hazardMaps/%s.tif", field[fi]);
            char *f = gf_path(md, rel);
            if (gf_raster_read(f, &r[i])) die("%s: %s", f, gf_error_detail());
            if (i > 0 && !gf_raster_same_grid(&r[i], &r[0])) die("%s: not on the grid of the scenario's other members", f);
            free(f);
            v[i] = r[i].z;
            ids[i] = j->A->r[m->rel].id;
            ++i;
        }
        const size_t nc = (size_t)r[0].nx * (size_t)r[0].ny;
        double *mx = malloc(nc * sizeof *mx);
        unsigned *count = fi == 0 ? malloc(nc * sizeof *count) : NULL;
        long *who = fi == 0 ? malloc(nc * sizeof *who) : NULL;
        if (!mx || (fi == 0 && (!count || !who))) die("out of memory");
        if (gf_merge_max(n, nc, v, ids, c->threshold, mx, count, who)) die("merge: %s", gf_error_detail());
        char name[64];
        snprintf(name, sizeof name, "%sMax.tif", field[fi]);
        write_tif(outdir, name, &r[0], mx);
        if (fi == 0) write_counts(outdir, &r[0], nc, mx, count, who, c);
        free(mx), free(count), free(who);
        for (size_t q = 0; q < n; ++q) gf_raster_free(&r[q]);
        free(r), free(v), free(ids);
    }
    return n;
}

/*---------------------------------------------------------------- -alphaBeta --*/

/* the DEM of the case (constant/terrainProperties dem, relative to the case) */
static void case_dem(job *j, const char *casedir)
{
    if (j->dem.z) return; /* read once: the clips, alpha-beta and the project use it */
    /* the value through foamDictionary, into a file of this process (array
     * tasks of one batch run at once) */
    char *tp = gf_path(casedir, "constant/terrainProperties"), *val = NULL;
    if (asprintf(&val, "%s/caseDEM.%ld.%ld", j->dir, (long)getpid(), j->task) < 0) die("out of memory");
    unlink(val);
    char *fd[] = {"foamDictionary", "-entry", "dem", "-value", tp, NULL};
    if (gf_run(fd, val)) die("no dem entry in %s (foamDictionary; the case's DEM)", tp);
    FILE *in = fopen(val, "r");
    char line[4096] = "";
    if (!in || !fgets(line, sizeof line, in)) die("no dem entry in %s (the case's DEM)", tp);
    fclose(in);
    unlink(val);
    line[strcspn(line, "\r\n")] = 0;
    char *b = line, *e = line + strlen(line);
    while (*b == '"' || *b == ' ') ++b;
    while (e > b && (e[-1] == '"' || e[-1] == ' ')) *--e = 0;
    char *path = b[0] == '/' ? strdup(b) : gf_path(casedir, b);
    if (gf_raster_read(path, &j->dem)) die("the case's DEM %s: %s", path, gf_error_detail());
    j->dem_path = path;
    free(tp), free(val);
}

/* a release's thalweg and alpha-beta (ok 0: why says what is missing) */
typedef struct ab_release {
    int ok;
    char why[1024];
    double *xyzs;   /* the thalweg: x y z s per point */
    size_t n;
    gf_alpha_beta ab;
} ab_release;

/* Each release's steepest-descent thalweg from its highest DEM cell, its
 * alpha-beta runout, and beside it each member's dynamic runout: the
 * farthest thalweg point where the member's peak pressure exceeds the
 * threshold (sdyn[k], NAN when none).  DIR/alphaBeta.csv.  Returns the
 * releases' thalwegs (ab_free). */
static ab_release *alpha_beta(const job *j, const gf_raster *dem, double *sdyn)
{
    const config *c = j->c;
    gf_alpha_beta_params p;
    gf_alpha_beta_params_default(&p);
    char *rd = gf_path(j->dir, "releases");
    mkdir(rd, 0755);
    char *csv = gf_path(j->dir, "alphaBeta.csv");
    FILE *o = fopen(csv, "w");
    if (!o) die("cannot write %s", csv);
    fprintf(o, "release,scenario,status,z_top_m,beta_deg,alpha_deg,s_beta_m,s_alpha_m,s_alpha_minus_sd_m,"
               "s_alpha_plus_sd_m,s_thalweg_m,s_dynamic_m,dynamic_minus_alpha_m,reason\n");
    unsigned char *mask = malloc((size_t)dem->nx * (size_t)dem->ny);
    ab_release *res = calloc(j->A->n, sizeof *res);
    if (!mask || !res) die("out of memory");
    size_t rows = 0;
    for (size_t k = 0; k < j->nm; ++k) sdyn[k] = NAN;
    for (size_t r = 0; r < j->A->n; ++r) {
        const release *R = &j->A->r[r];
        ab_release *T = &res[r];
        char name[64];
        snprintf(name, sizeof name, "r%ld.shp", R->id);
        char *shp = gf_path(rd, name);
        if (write_release_shp(j->A, R, shp, T->why, sizeof T->why)) die("%s", T->why);
        gf_polygons P;
        if (gf_polygons_read(shp, NULL, 1, &P)) die("%s: %s", shp, gf_error_detail());
        gf_polygons_mask(&P, dem, mask);
        gf_polygons_free(&P);
        free(shp);
        long top = -1;
        for (size_t q = 0; q < (size_t)dem->nx * (size_t)dem->ny; ++q)
            if (mask[q] && !isnan(dem->z[q]) && (top < 0 || dem->z[q] > dem->z[top])) top = (long)q;
        T->ok = top >= 0;
        if (!T->ok) snprintf(T->why, sizeof T->why, "no DEM cell in the polygon");
        if (T->ok && gf_thalweg_d8(dem, (int)(top % dem->nx), (int)(top / dem->nx), 5, 1000, &T->xyzs, &T->n)) {
            snprintf(T->why, sizeof T->why, "thalweg: %s", gf_error_detail());
            T->ok = 0;
        }
        const size_t n = T->n;
        double *s = NULL, *z = NULL;
        if (T->ok) {
            s = malloc(n * sizeof *s), z = malloc(n * sizeof *z);
            if (!s || !z) die("out of memory");
            for (size_t i = 0; i < n; ++i) z[i] = T->xyzs[4 * i + 2], s[i] = T->xyzs[4 * i + 3];
            if (gf_alpha_beta_profile(n, s, z, &p, &T->ab)) {
                snprintf(T->why, sizeof T->why, "alpha-beta: %s", gf_error_detail());
                T->ok = 0;
            }
        }
        const gf_alpha_beta ab = T->ab;
        for (size_t k = 0; k < j->nm; ++k) {
            const member *m = &j->m[k];
            if (m->rel != r) continue;
            fprintf(o, "%ld,%s,", R->id, c->s[m->scen].name);
            if (!T->ok) {
                fprintf(o, "%s,,,,,,,,,,,\"%s\"\n", m->ok ? "ok" : "failed", T->why);
                continue;
            }
            if (m->ok) {
                char md[4096];
                member_dir(j, m, md, sizeof md);
                char *f = gf_path(md, "postProcessing/hazardMaps/pressurePeak.tif");
                gf_raster pr;
                if (gf_raster_read(f, &pr)) die("%s: %s", f, gf_error_detail());
                free(f);
                sdyn[k] = 0;
                for (size_t i = 0; i < n; ++i) {
                    const double col = floor((T->xyzs[4 * i] - pr.gt[0]) / pr.gt[1]);
                    const double row = floor((T->xyzs[4 * i + 1] - pr.gt[3]) / pr.gt[5]);
                    if (col < 0 || row < 0 || col >= pr.nx || row >= pr.ny) continue;
                    const double v = pr.z[(size_t)row * (size_t)pr.nx + (size_t)col];
                    if (v > c->threshold) sdyn[k] = s[i];
                }
                gf_raster_free(&pr);
            }
            const double sd = sdyn[k];
            fprintf(o, "%s,%.2f,%.3f,%.3f,%.1f,", m->ok ? "ok" : "failed", z[0], ab.beta, ab.alpha, ab.s_beta);
            for (int q = 0; q < 3; ++q)
                isnan(ab.s_alpha[q]) ? fprintf(o, ",") : fprintf(o, "%.1f,", ab.s_alpha[q]);
            fprintf(o, "%.1f,", s[n - 1]);
            if (isnan(sd))
                fprintf(o, ",,\n");
            else if (isnan(ab.s_alpha[0]))
                fprintf(o, "%.1f,,\n", sd);
            else
                fprintf(o, "%.1f,%.1f,\n", sd, sd - ab.s_alpha[0]);
            ++rows;
        }
        if (T->ok && !isnan(ab.s_alpha[0]))
            printf("alphaBeta r%ld: beta %.2f deg, alpha %.2f deg, alpha runout s = %.0f m along the thalweg\n", R->id,
                   ab.beta, ab.alpha, ab.s_alpha[0]);
        else if (T->ok)
            printf("alphaBeta r%ld: beta %.2f deg, alpha %.2f deg, the alpha line meets no terrain before the "
                   "thalweg's end (%.0f m)\n",
                   R->id, ab.beta, ab.alpha, s[n - 1]);
        else
            printf("alphaBeta r%ld: %s\n", R->id, T->why);
        free(s), free(z);
    }
    if (fclose(o)) die("cannot write %s", csv);
    printf("alphaBeta=%s (%zu rows)\n", csv, rows);
    free(mask), free(rd), free(csv);
    return res;
}

static void ab_free(ab_release *res, size_t n)
{
    if (!res) return;
    for (size_t r = 0; r < n; ++r) free(res[r].xyzs);
    free(res);
}

/*---------------------------------------------------------------- the outlines --*/

static int leaked(const member *m);

/* an OGR field of name and type on layer L (die naming the file) */
static void add_field(OGRLayerH L, const char *name, OGRFieldType t, const char *path)
{
    OGRFieldDefnH d = OGR_Fld_Create(name, t);
    const OGRErr e = OGR_L_CreateField(L, d, TRUE);
    OGR_Fld_Destroy(d);
    if (e != OGRERR_NONE) die("%s: field %s: %s", path, name, CPLGetLastErrorMsg());
}

static void set_real(OGRFeatureH f, const char *name, double v)
{
    if (isfinite(v)) OGR_F_SetFieldDouble(f, OGR_F_GetFieldIndex(f, name), v);
}

static void put_feature(OGRLayerH L, OGRFeatureH f, const char *path)
{
    if (OGR_L_CreateFeature(L, f) != OGRERR_NONE) die("%s: %s", path, CPLGetLastErrorMsg());
    OGR_F_Destroy(f);
}

/* the point at distance s along a thalweg (x y z s per point) */
static void thalweg_point(const ab_release *T, double s, double *x, double *y)
{
    const double *q = T->xyzs;
    if (T->n < 2) {
        *x = q[0], *y = q[1];
        return;
    }
    size_t i = 1;
    while (i + 1 < T->n && q[4 * i + 3] < s) ++i;
    const double s0 = q[4 * (i - 1) + 3], s1 = q[4 * i + 3];
    const double w = s1 > s0 ? fmin(1.0, fmax(0.0, (s - s0) / (s1 - s0))) : 0.0;
    *x = q[4 * (i - 1)] + w * (q[4 * i] - q[4 * (i - 1)]);
    *y = q[4 * (i - 1) + 1] + w * (q[4 * i + 1] - q[4 * (i - 1) + 1]);
}

/* DIR/SCENARIO/outlines.gpkg: the pressure zones as polygons (zones:
 * class, lower_kPa, upper_kPa, area_m2; gf_class_outlines), the scenario's
 * releases (releases: the polygon, id, depth_m, status, affected_m2,
 * maxPressure_kPa, reason, and with alpha-beta beta_deg, alpha_deg,
 * s_alpha_m, s_dynamic_m, dynamic_minus_alpha_m) and with alpha-beta each
 * release's thalweg (thalwegs) and its runout points along it (runouts:
 * kind beta, alpha, alpha_minus_sd, alpha_plus_sd, dynamic; s_m the
 * distance along the thalweg) */
static void write_outlines(const job *j, size_t s, const char *outdir, const ab_release *abr, const double *sdyn)
{
    const config *c = j->c;
    char *zf = gf_path(outdir, "zones.tif"), *gp = gf_path(outdir, "outlines.gpkg"), *tmp = NULL;
    if (asprintf(&tmp, "%s.tmp.gpkg", gp) < 0) die("out of memory");
    gf_raster zr;
    if (gf_raster_read(zf, &zr)) die("%s: %s", zf, gf_error_detail());
    size_t nz = 0;
    if (gf_class_outlines(tmp, "zones", &zr, zr.z, c->n_zones, c->zones, "kPa", &nz)) die("%s", gf_error_detail());
    GDALDatasetH ds = GDALOpenEx(tmp, GDAL_OF_VECTOR | GDAL_OF_UPDATE, NULL, NULL, NULL);
    if (!ds) die("%s: %s", tmp, CPLGetLastErrorMsg());
    OGRSpatialReferenceH dsrs = NULL;
    if (zr.wkt && *zr.wkt) {
        dsrs = OSRNewSpatialReference(zr.wkt);
        if (dsrs) OSRSetAxisMappingStrategy(dsrs, OAMS_TRADITIONAL_GIS_ORDER);
    }
    /* the releases */
    OGRLayerH L = GDALDatasetCreateLayer(ds, "releases", j->A->srs, wkbMultiPolygon, NULL);
    if (!L) die("%s: layer releases: %s", tmp, CPLGetLastErrorMsg());
    add_field(L, "id", OFTInteger64, tmp);
    add_field(L, "depth_m", OFTReal, tmp);
    add_field(L, "status", OFTString, tmp);
    add_field(L, "affected_m2", OFTReal, tmp);
    add_field(L, "maxPressure_kPa", OFTReal, tmp);
    if (abr) {
        static const char *abf[] = {"beta_deg", "alpha_deg", "s_alpha_m", "s_dynamic_m", "dynamic_minus_alpha_m"};
        for (int q = 0; q < 5; ++q) add_field(L, abf[q], OFTReal, tmp);
    }
    add_field(L, "reason", OFTString, tmp);
    if (OGR_L_StartTransaction(L) != OGRERR_NONE) die("%s: %s", tmp, CPLGetLastErrorMsg());
    for (size_t k = 0; k < j->nm; ++k) {
        const member *m = &j->m[k];
        if (m->scen != s) continue;
        const release *R = &j->A->r[m->rel];
        OGRFeatureH f = OGR_F_Create(OGR_L_GetLayerDefn(L));
        OGRGeometryH g = OGR_G_ForceToMultiPolygon(OGR_G_Clone(R->geom));
        OGR_F_SetGeometryDirectly(f, g);
        OGR_F_SetFieldInteger64(f, OGR_F_GetFieldIndex(f, "id"), R->id);
        set_real(f, "depth_m", m->depth);
        const int boundary = m->ok && c->clip && leaked(m);
        OGR_F_SetFieldString(f, OGR_F_GetFieldIndex(f, "status"), !m->ok ? "failed" : boundary ? "boundary" : "ok");
        if (m->ok) set_real(f, "affected_m2", m->affected), set_real(f, "maxPressure_kPa", m->maxppr);
        if (!m->ok) OGR_F_SetFieldString(f, OGR_F_GetFieldIndex(f, "reason"), m->why);
        if (boundary) {
            char why[256];
            snprintf(why, sizeof why, "flow left through the clip's boundary: %.4g m3 of %.4g m3 (buffer %g m)",
                     m->outflow, m->volume, m->buffer);
            OGR_F_SetFieldString(f, OGR_F_GetFieldIndex(f, "reason"), why);
        }
        if (abr && abr[m->rel].ok) {
            const gf_alpha_beta *ab = &abr[m->rel].ab;
            set_real(f, "beta_deg", ab->beta), set_real(f, "alpha_deg", ab->alpha);
            set_real(f, "s_alpha_m", ab->s_alpha[0]), set_real(f, "s_dynamic_m", sdyn[k]);
            set_real(f, "dynamic_minus_alpha_m", sdyn[k] - ab->s_alpha[0]);
        }
        put_feature(L, f, tmp);
    }
    if (OGR_L_CommitTransaction(L) != OGRERR_NONE) die("%s: %s", tmp, CPLGetLastErrorMsg());
    size_t nth = 0, npt = 0;
    if (abr) {
        /* each release's thalweg and its runout points */
        OGRLayerH T = GDALDatasetCreateLayer(ds, "thalwegs", dsrs, wkbLineString, NULL);
        OGRLayerH P = T ? GDALDatasetCreateLayer(ds, "runouts", dsrs, wkbPoint, NULL) : NULL;
        if (!P) die("%s: layers thalwegs, runouts: %s", tmp, CPLGetLastErrorMsg());
        add_field(T, "id", OFTInteger64, tmp);
        add_field(T, "beta_deg", OFTReal, tmp);
        add_field(T, "alpha_deg", OFTReal, tmp);
        add_field(T, "s_thalweg_m", OFTReal, tmp);
        add_field(P, "id", OFTInteger64, tmp);
        add_field(P, "kind", OFTString, tmp);
        add_field(P, "s_m", OFTReal, tmp);
        if (OGR_L_StartTransaction(T) != OGRERR_NONE) die("%s: %s", tmp, CPLGetLastErrorMsg());
        for (size_t k = 0; k < j->nm; ++k) {
            const member *m = &j->m[k];
            const ab_release *A = &abr[m->rel];
            if (m->scen != s || !A->ok) continue;
            const long id = j->A->r[m->rel].id;
            OGRFeatureH f = OGR_F_Create(OGR_L_GetLayerDefn(T));
            OGRGeometryH g = OGR_G_CreateGeometry(wkbLineString);
            for (size_t i = 0; i < A->n; ++i) OGR_G_AddPoint_2D(g, A->xyzs[4 * i], A->xyzs[4 * i + 1]);
            OGR_F_SetGeometryDirectly(f, g);
            OGR_F_SetFieldInteger64(f, 0, id);
            set_real(f, "beta_deg", A->ab.beta), set_real(f, "alpha_deg", A->ab.alpha);
            set_real(f, "s_thalweg_m", A->xyzs[4 * (A->n - 1) + 3]);
            put_feature(T, f, tmp);
            ++nth;
            const char *kind[] = {"beta", "alpha", "alpha_minus_sd", "alpha_plus_sd", "dynamic"};
            const double at[] = {A->ab.s_beta, A->ab.s_alpha[0], A->ab.s_alpha[1], A->ab.s_alpha[2], sdyn[k]};
            for (int q = 0; q < 5; ++q) {
                if (!isfinite(at[q])) continue;
                double x, y;
                thalweg_point(A, at[q], &x, &y);
                OGRFeatureH pf = OGR_F_Create(OGR_L_GetLayerDefn(P));
                OGRGeometryH pg = OGR_G_CreateGeometry(wkbPoint);
                OGR_G_SetPoint_2D(pg, 0, x, y);
                OGR_F_SetGeometryDirectly(pf, pg);
                OGR_F_SetFieldInteger64(pf, 0, id);
                OGR_F_SetFieldString(pf, 1, kind[q]);
                OGR_F_SetFieldDouble(pf, 2, at[q]);
                put_feature(P, pf, tmp);
                ++npt;
            }
        }
        if (OGR_L_CommitTransaction(T) != OGRERR_NONE) die("%s: %s", tmp, CPLGetLastErrorMsg());
    }
    GDALClose(ds);
    if (dsrs) OSRDestroySpatialReference(dsrs);
    if (rename(tmp, gp)) die("cannot write %s", gp);
    printf("outlines %s: %zu zone polygons%s", gp, nz, abr ? "" : "\n");
    if (abr) printf(", %zu thalwegs, %zu runout points\n", nth, npt);
    gf_raster_free(&zr);
    free(zf), free(gp), free(tmp);
}

/*---------------------------------------------------------------- the QGIS project --*/

/* the largest value of a raster (0 when it has none above 0) */
static double raster_max(const char *dir, const char *name)
{
    char *f = gf_path(dir, name);
    gf_raster r;
    if (gf_raster_read(f, &r)) die("%s: %s", f, gf_error_detail());
    double mx = 0;
    for (size_t q = 0; q < (size_t)r.nx * (size_t)r.ny; ++q)
        if (r.z[q] > mx) mx = r.z[q];
    gf_raster_free(&r);
    free(f);
    return mx;
}

/* DIR/regional.qgs: a QGIS project of the batch, a legend group per merged
 * scenario (the first one shown): its runout points and thalwegs (with
 * alpha-beta), releases, pressure zones (raster shown, polygons hidden), the
 * largest peak pressure, thickness and speed, the releases reaching each
 * cell and the release of the largest pressure; under them the case's DEM
 * as a hillshade.  Paths relative to DIR (the folder can move), the DEM's
 * absolute. */
static void write_project(const job *j, const size_t *merged, int with_ab)
{
    const config *c = j->c;
    const gf_raster *dem = &j->dem;
    static const char *zone_colours[] = {"#ffdd00", "#1e6edc", "#d7191c", "#780050", "#3c0028",
                                         "#000000", "#000000", "#000000"};
    static const char *blues[] = {"#eff6fc", "#b9d6ee", "#6aaed6", "#2f7ebc", "#0b4d93"};
    static const char *kinds[] = {"dynamic", "alpha", "alpha_minus_sd", "alpha_plus_sd", "beta"};
    static const char *kind_labels[] = {"dynamic runout (along the thalweg)", "alpha runout (Lied and Bakkehoi 1980)",
                                        "alpha - 1 SD", "alpha + 1 SD", "beta point (10 deg)"};
    static const char *kind_colours[] = {"#e31a1c", "#ff8c00", "#202020", "#202020", "#ffffff"};
    static const char *kind_shapes[] = {"circle", "diamond", "square", "square", "triangle"};
    char zlab[MAXZONES][64];
    const char *zl[MAXZONES];
    for (size_t z = 0; z < c->n_zones; ++z) {
        if (z + 1 < c->n_zones)
            snprintf(zlab[z], sizeof zlab[z], "%g - %g kPa", c->zones[z], c->zones[z + 1]);
        else
            snprintf(zlab[z], sizeof zlab[z], ">= %g kPa", c->zones[z]);
        zl[z] = zlab[z];
    }
    gf_qgis_layer *L = calloc(10 * c->ns + 1, sizeof *L);
    char(*src)[320] = calloc(10 * c->ns + 1, sizeof *src);
    char(*nm)[160] = calloc(10 * c->ns + 1, sizeof *nm);
    if (!L || !src || !nm) die("out of memory");
    size_t n = 0, shown = 0;
    for (size_t s = 0; s < c->ns; ++s) {
        if (!merged[s]) continue;
        const char *S = c->s[s].name;
        const int vis = shown++ == 0;
        char *od = gf_path(j->dir, S);
#define ADD(style_, file_, layer_, name_)                                                                    \
    do {                                                                                                      \
        memset(&L[n], 0, sizeof L[n]);                                                                        \
        snprintf(src[n], sizeof src[n], "%s/%s", S, file_);                                                   \
        snprintf(nm[n], sizeof nm[n], "%s: %s", S, name_);                                                    \
        L[n].group = S, L[n].name = nm[n], L[n].source = src[n], L[n].layer = layer_, L[n].style = style_; \
    } while (0)
        if (with_ab) {
            ADD(GF_QGIS_POINT_KINDS, "outlines.gpkg", "runouts", "alpha-beta and dynamic runouts");
            L[n].visible = vis, L[n].field = "kind", L[n].nclass = 5, L[n].values = kinds, L[n].labels = kind_labels;
            L[n].colors = kind_colours, L[n].shapes = kind_shapes, ++n;
            ADD(GF_QGIS_LINE, "outlines.gpkg", "thalwegs", "thalwegs (steepest descent)");
            L[n].visible = vis, L[n].color = "#333333", L[n].width = 0.3, L[n].dashed = 1, ++n;
        }
        ADD(GF_QGIS_OUTLINE, "outlines.gpkg", "releases", "releases");
        L[n].visible = vis, L[n].color = "#202020", L[n].width = 0.5, ++n;
        ADD(GF_QGIS_FILL_CLASSES, "outlines.gpkg", "zones", "pressure zones (polygons)");
        L[n].field = "class", L[n].nclass = c->n_zones, L[n].labels = zl, L[n].colors = zone_colours, ++n;
        ADD(GF_QGIS_CLASSES, "zones.tif", NULL, "pressure zones");
        L[n].visible = vis, L[n].nclass = c->n_zones, L[n].labels = zl, L[n].colors = zone_colours, ++n;
        const struct {
            const char *file, *name, *unit;
            double vmin;
            int blue;
        } ramps[] = {{"pressurePeakMax.tif", "largest peak pressure", "kPa", c->threshold, 0},
                     {"hPeakMax.tif", "largest peak thickness", "m", 0.1, 0},
                     {"speedPeakMax.tif", "largest peak speed", "m/s", 1.0, 0},
                     {"count.tif", "releases reaching", "", 0.5, 1},
                     {"releaseId.tif", "release of the largest pressure", "id", 0.5, 1}};
        for (size_t q = 0; q < sizeof ramps / sizeof ramps[0]; ++q) {
            double mx = raster_max(od, ramps[q].file);
            if (!(mx > ramps[q].vmin)) mx = ramps[q].vmin + 1;
            ADD(GF_QGIS_RAMP, ramps[q].file, NULL, ramps[q].name);
            L[n].vmin = ramps[q].vmin, L[n].vmax = mx, L[n].unit = ramps[q].unit;
            if (ramps[q].blue) L[n].colors = blues, L[n].ncolor = 5;
            ++n;
        }
#undef ADD
        free(od);
    }
    memset(&L[n], 0, sizeof L[n]);
    L[n].name = "terrain (hillshade)", L[n].source = j->dem_path, L[n].style = GF_QGIS_HILLSHADE, L[n].visible = 1;
    ++n;
    const double ext[4] = {dem->gt[0], dem->gt[3] + dem->ny * dem->gt[5], dem->gt[0] + dem->nx * dem->gt[1], dem->gt[3]};
    char *qgs = gf_path(j->dir, "regional.qgs"), title[256];
    snprintf(title, sizeof title, "granflow regional hazard indication map (gfRegionalMap %s)", gf_version());
    if (gf_qgis_project_write(qgs, title, dem->wkt, ext, n, L)) die("%s", gf_error_detail());
    printf("project=%s (%zu layers)\n", qgs, n);
    free(qgs), free(L), free(src), free(nm);
}

/*---------------------------------------------------------------- clipped sub-domains --*/

static void make_template(const char *casedir, const char *templ);

/* the case's terrainDict: its coarsening and slab depth (a clip is meshed
 * with them); a crop or a dam is refused, since a clip's DEM is cut from the
 * case's DEM as it is */
static void clip_settings(job *j)
{
    char *td = gf_path(j->casedir, "system/terrainDict");
    char err[2048];
    gf_dict *D = gf_dict_read(td, err, sizeof err);
    if (!D) die("clip (%s): %s", j->c->path, err);
    j->coarsen = (int)gf_dict_whole(D, "coarsen", 1, 1, 1000);
    j->depth_slab = gf_dict_number(D, "depth", 10, 1e-6, 1e6);
    gf_dict_find(D, "dem");
    const gf_dict *in = NULL;
    const gf_dict_entry *u = gf_dict_unused(D, &in);
    if (u)
        die("%s:%d: %s: a clipped batch (clip in %s) meshes each release's part of the case's DEM with its dem, "
            "coarsen and depth only: remove clip from %s or %s from the case",
            td, u->line, u->key, j->c->path, j->c->path, u->key);
    gf_dict_free(D);
    free(td);
}

/* the clip box of release r with a buffer [m] on the region's DEM (pixels,
 * inclusive, its corner nodes on the case's coarsened node grid); 0, or -1
 * with the reason */
static int release_box(const job *j, size_t r, double buffer, int box[4], int *whole, char *why, size_t wsize)
{
    const gf_raster *dem = &j->dem;
    const release *R = &j->A->r[r];
    char name[64];
    snprintf(name, sizeof name, "r%ld.shp", R->id);
    char *rd = gf_path(j->clips, "releases");
    mkdir(rd, 0755);
    char *shp = gf_path(rd, name);
    free(rd);
    if (!gf_exists(shp) && write_release_shp(j->A, R, shp, why, wsize)) {
        free(shp);
        return -1;
    }
    gf_polygons P;
    if (gf_polygons_read(shp, NULL, 1, &P)) {
        snprintf(why, wsize, "%s: %s", shp, gf_error_detail());
        free(shp);
        return -1;
    }
    free(shp);
    OGREnvelope env;
    OGR_G_GetEnvelope(R->geom, &env);
    const double px = dem->gt[1], py = dem->gt[5];
    int c0 = (int)floor((env.MinX - dem->gt[0]) / px), c1 = (int)floor((env.MaxX - dem->gt[0]) / px);
    int r0 = (int)floor((env.MaxY - dem->gt[3]) / py), r1 = (int)floor((env.MinY - dem->gt[3]) / py);
    if (c0 < 0) c0 = 0;
    if (r0 < 0) r0 = 0;
    if (c1 > dem->nx - 1) c1 = dem->nx - 1;
    if (r1 > dem->ny - 1) r1 = dem->ny - 1;
    size_t n = 0;
    size_t *cells = NULL;
    if (c0 <= c1 && r0 <= r1) {
        gf_raster w = *dem;
        w.nx = c1 - c0 + 1, w.ny = r1 - r0 + 1;
        w.gt[0] = dem->gt[0] + c0 * px, w.gt[3] = dem->gt[3] + r0 * py;
        unsigned char *mask = malloc((size_t)w.nx * (size_t)w.ny);
        cells = malloc((size_t)w.nx * (size_t)w.ny * sizeof *cells);
        if (!mask || !cells) die("out of memory");
        gf_polygons_mask(&P, &w, mask);
        for (int jj = 0; jj < w.ny; ++jj)
            for (int ii = 0; ii < w.nx; ++ii) {
                const size_t c = (size_t)(r0 + jj) * (size_t)dem->nx + (size_t)(c0 + ii);
                if (mask[(size_t)jj * (size_t)w.nx + (size_t)ii] && isfinite(dem->z[c])) cells[n++] = c;
            }
        free(mask);
    }
    gf_polygons_free(&P);
    if (n == 0) {
        free(cells);
        snprintf(why, wsize, "no DEM cell in the polygon (clip)");
        return -1;
    }
    if (gf_downslope_box(dem, n, cells, j->c->climb, j->c->reach, box, NULL)) {
        snprintf(why, wsize, "clip: %s", gf_error_detail());
        free(cells);
        return -1;
    }
    free(cells);
    const int b = (int)ceil(buffer / px), k = j->coarsen;
    box[0] -= b, box[1] -= b, box[2] += b, box[3] += b;
    if (box[0] < 0) box[0] = 0;
    if (box[1] < 0) box[1] = 0;
    box[0] -= box[0] % k, box[1] -= box[1] % k;
    box[2] = box[0] + ((box[2] - box[0] + k - 1) / k) * k;
    box[3] = box[1] + ((box[3] - box[1] + k - 1) / k) * k;
    if (box[2] > dem->nx - 1) box[2] = dem->nx - 1;
    if (box[3] > dem->ny - 1) box[3] = dem->ny - 1;
    *whole = box[0] == 0 && box[1] == 0 && box[2] == dem->nx - 1 && box[3] == dem->ny - 1;
    return 0;
}

/* a field file of the case with its internalField uniform 0 of its class
 * (the release is set at the start; the list of the case's mesh would not
 * fit the clip's) and written in ascii: the header up to internalField and
 * the boundaryField after it kept */
static int uniform_field(const char *f)
{
    FILE *in = fopen(f, "rb");
    if (!in) return -1;
    fseek(in, 0, SEEK_END);
    const long size = ftell(in);
    fseek(in, 0, SEEK_SET);
    char *t = malloc((size_t)size + 1);
    if (!t || fread(t, 1, (size_t)size, in) != (size_t)size) {
        fclose(in), free(t);
        return -1;
    }
    fclose(in);
    t[size] = 0;
    char *fi = strstr(t, "internalField");
    /* the last boundaryField (a binary list may hold any bytes before it) */
    char *bf = NULL;
    for (long k = size - 13; k >= 0 && !bf; --k)
        if (memcmp(t + k, "boundaryField", 13) == 0) bf = t + k;
    if (!fi || !bf || bf < fi) {
        free(t);
        return -1;
    }
    *fi = 0;
    char *cl = strstr(t, "class");
    char cls[64] = "";
    if (cl) sscanf(cl + 5, " %63[A-Za-z]", cls);
    const char *v = strstr(cls, "Vector")   ? "uniform (0 0 0)"
                    : strstr(cls, "Tensor") ? "uniform (0 0 0 0 0 0 0 0 0)"
                                            : "uniform 0";
    char *bin = strstr(t, "binary");
    FILE *o = fopen(f, "wb");
    if (!o) {
        free(t);
        return -1;
    }
    if (bin) {
        fwrite(t, 1, (size_t)(bin - t), o);
        fprintf(o, "ascii; ");
        fputs(bin + 7, o);
    } else {
        fputs(t, o);
    }
    fprintf(o, "internalField   %s;\n\n", v);
    fputs(bf, o);
    const int st = fclose(o);
    free(t);
    return st ? -1 : 0;
}

/* the clip case cd of the region's DEM pixels box: its DEM cut (Inputs/clipDEM.tif, the
 * region's values and pixel grid), the case's system/, constant/ and 0/
 * (internal fields uniform), meshed by gfTerrainMesh; 0, or -1 with the reason */
static int make_clip(const job *j, const int box[4], const char *cd, char *why, size_t wsize)
{
    if (gf_exists(cd)) return 0;
    char *tmp = NULL, *log = NULL;
    if (asprintf(&tmp, "%s.tmp", cd) < 0 || asprintf(&log, "%s.log", cd) < 0) die("out of memory");
    char *rm[] = {"rm", "-rf", tmp, NULL};
    gf_run(rm, NULL);
    unlink(log);
    int st = -1;
    char *sys = gf_path(j->casedir, "system"), *zero = gf_path(j->casedir, "0"), *cons = gf_path(j->casedir, "constant");
    char *tcons = gf_path(tmp, "constant"), *demf = gf_path(tmp, "Inputs/clipDEM.tif"), *td = gf_path(tmp, "system/terrainDict");
    char *tzero = gf_path(tmp, "0"), *inp = gf_path(j->casedir, "Inputs"), *tinp = gf_path(tmp, "Inputs");
    if (mkdir(tmp, 0755) || mkdir(tcons, 0755)) {
        snprintf(why, wsize, "cannot make %s", tmp);
        goto out;
    }
    char *cp[] = {"cp", "-r", sys, zero, tmp, NULL};
    if (gf_run(cp, log)) {
        snprintf(why, wsize, "cannot copy the case's system/ and 0/ to %s (%s)", tmp, log);
        goto out;
    }
    /* Inputs/: the clip's DEM and links to the case's inputs (members link it) */
    if (mkdir(tinp, 0755)) {
        snprintf(why, wsize, "cannot make %s", tinp);
        goto out;
    }
    DIR *d = opendir(inp);
    struct dirent *de;
    while (d && (de = readdir(d))) {
        if (de->d_name[0] == '.' || !strcmp(de->d_name, "clipDEM.tif")) continue;
        char *f = gf_path(inp, de->d_name), *l = gf_path(tinp, de->d_name);
        const int e = symlink(f, l);
        free(f), free(l);
        if (e) {
            closedir(d);
            snprintf(why, wsize, "cannot link the case's Inputs/%s", de->d_name);
            goto out;
        }
    }
    if (d) closedir(d);
    d = opendir(cons);
    if (!d) {
        snprintf(why, wsize, "cannot read %s", cons);
        goto out;
    }
    int bad = 0;
    while (!bad && (de = readdir(d))) {
        if (de->d_name[0] == '.' || !strcmp(de->d_name, "polyMesh") || !strcmp(de->d_name, "faMesh") ||
            !strcmp(de->d_name, "terrainProperties") || !strcmp(de->d_name, "demWithDam.tif"))
            continue;
        char *f = gf_path(cons, de->d_name);
        char *c2[] = {"cp", "-r", f, tcons, NULL};
        bad = gf_run(c2, log);
        free(f);
    }
    closedir(d);
    if (bad) {
        snprintf(why, wsize, "cannot copy the case's constant/ (%s)", log);
        goto out;
    }
    {
        /* the area mesh's definition (gfTerrainMesh writes the area mesh from it) */
        char *fm = gf_path(cons, "faMesh/faMeshDefinition"), *tfm = gf_path(tcons, "faMesh");
        if (gf_exists(fm)) {
            mkdir(tfm, 0755);
            char *c3[] = {"cp", fm, tfm, NULL};
            bad = gf_run(c3, log);
        }
        free(fm), free(tfm);
        if (bad) {
            snprintf(why, wsize, "cannot copy the case's constant/faMesh/faMeshDefinition (%s)", log);
            goto out;
        }
    }
    /* the DEM cut: the same values, the pixel grid shifted by whole pixels */
    const gf_raster *R = &j->dem;
    gf_raster w = *R;
    w.nx = box[2] - box[0] + 1, w.ny = box[3] - box[1] + 1;
    w.gt[0] = R->gt[0] + box[0] * R->gt[1], w.gt[3] = R->gt[3] + box[1] * R->gt[5];
    double *z = malloc((size_t)w.nx * (size_t)w.ny * sizeof *z);
    if (!z) die("out of memory");
    for (int jj = 0; jj < w.ny; ++jj)
        memcpy(z + (size_t)jj * (size_t)w.nx, R->z + (size_t)(box[1] + jj) * (size_t)R->nx + (size_t)box[0],
               (size_t)w.nx * sizeof *z);
    w.z = z;
    const gf_status ws = gf_raster_write(demf, "GTiff", &w, z);
    free(z);
    if (ws) {
        snprintf(why, wsize, "%s: %s", demf, gf_error_detail());
        goto out;
    }
    FILE *o = fopen(td, "w");
    if (!o) {
        snprintf(why, wsize, "cannot write %s", td);
        goto out;
    }
    fprintf(o,
            "FoamFile { version 2.0; format ascii; class dictionary; location \"system\"; object terrainDict; }\n"
            "// gfRegionalMap clip: pixels %d..%d x %d..%d of the case's DEM\n"
            "dem      \"Inputs/clipDEM.tif\";\ncoarsen  %d;\ndepth    %.17g;\n",
            box[0], box[2], box[1], box[3], j->coarsen, j->depth_slab);
    if (fclose(o)) {
        snprintf(why, wsize, "cannot write %s", td);
        goto out;
    }
    if ((d = opendir(tzero))) {
        while (!bad && (de = readdir(d))) {
            if (de->d_name[0] == '.') continue;
            char *f = gf_path(tzero, de->d_name);
            bad = uniform_field(f);
            free(f);
        }
        closedir(d);
    }
    if (bad) {
        snprintf(why, wsize, "cannot make the clip's 0/ fields uniform (%s)", tzero);
        goto out;
    }
    char *tm[] = {"gfTerrainMesh", "-case", tmp, NULL};
    if (gf_run(tm, log)) {
        snprintf(why, wsize, "gfTerrainMesh failed on the clip (%s)", log);
        goto out;
    }
    char *fl = gf_path(tmp, "constant/faMesh/faceLabels");
    const int has = gf_exists(fl);
    free(fl);
    if (!has) {
        char *mf[] = {"makeFaMesh", "-case", tmp, NULL};
        if (gf_run(mf, log)) {
            snprintf(why, wsize, "makeFaMesh failed on the clip (%s)", log);
            goto out;
        }
    }
    if (rename(tmp, cd)) {
        snprintf(why, wsize, "cannot rename %s", tmp);
        goto out;
    }
    st = 0;
out:
    free(tmp), free(log), free(sys), free(zero), free(cons), free(tcons), free(demf), free(td), free(tzero);
    free(inp), free(tinp);
    return st;
}

/* the outflow through the mesh's boundary and the release volume [m3] of a
 * member that ran (its postProcessing/hazardMaps/mass.csv) */
static int member_outflow(const char *md, double *outflow, double *volume)
{
    char *f = gf_path(md, "postProcessing/hazardMaps/mass.csv");
    FILE *in = fopen(f, "r");
    free(f);
    if (!in) return -1;
    char line[1024];
    int iv = -1, io = -1, rows = 0;
    *outflow = NAN, *volume = NAN;
    while (fgets(line, sizeof line, in)) {
        char *save = NULL;
        int col = 0;
        for (char *t = strtok_r(line, ",\r\n", &save); t; t = strtok_r(NULL, ",\r\n", &save), ++col) {
            if (rows == 0) {
                if (!strcmp(t, "volume")) iv = col;
                if (!strcmp(t, "netOutflow")) io = col;
            } else {
                if (col == iv && rows == 1) *volume = atof(t);
                if (col == io) *outflow = atof(t);
            }
        }
        ++rows;
    }
    fclose(in);
    return iv < 0 || io < 0 || rows < 2 ? -1 : 0;
}

/* flow left through the clip's boundary: more than 1e-6 of the release left
 * the mesh and the flow reached a side of the clip where the region goes on
 * (flow leaving through the region's own border leaves the whole DEM's mesh
 * too) */
static int leaked(const member *m)
{
    return m->ok && !m->whole && m->edge && isfinite(m->outflow) && m->outflow > 1e-6 * m->volume;
}

/* did the member's flow (hPeak > 0) reach the clip's outer faces (k pixels
 * of its sides) on a side where the region's DEM goes on? */
static int reaches_clip_edge(const job *j, const char *md, const int box[4])
{
    char *f = gf_path(md, "postProcessing/hazardMaps/hPeak.tif");
    gf_raster r;
    const int bad = gf_raster_read(f, &r) != GF_SUCCESS;
    free(f);
    if (bad) return 1;
    const gf_raster *R = &j->dem;
    const int k = j->coarsen;
#define RVALID(cc, rr) ((cc) >= 0 && (rr) >= 0 && (cc) < R->nx && (rr) < R->ny && !isnan(R->z[(size_t)(rr) * (size_t)R->nx + (size_t)(cc)]))
    int hit = 0;
    for (int jj = 0; jj < r.ny && !hit; ++jj)
        for (int ii = 0; ii < r.nx && !hit; ++ii) {
            const double v = r.z[(size_t)jj * (size_t)r.nx + (size_t)ii];
            if (!(v > 0)) continue;
            const int gc = box[0] + ii, gr = box[1] + jj;
            if (ii <= k && RVALID(box[0] - 1, gr)) hit = 1;
            if (ii >= r.nx - 1 - k && RVALID(box[2] + 1, gr)) hit = 1;
            if (jj <= k && RVALID(gc, box[1] - 1)) hit = 1;
            if (jj >= r.ny - 1 - k && RVALID(gc, box[3] + 1)) hit = 1;
        }
#undef RVALID
    gf_raster_free(&r);
    return hit;
}

/* the buffer of a release's attempt a (0, 1, ... retries): doubled each time
 * (from 100 m when the first is 0) */
static double attempt_buffer(const config *c, long a)
{
    double b = c->buffer;
    for (long k = 0; k < a; ++k) b = b > 0 ? 2 * b : 100;
    return b;
}

/* every scenario of release r, on clips growing by doubling the buffer while
 * flow leaves through a clip's boundary (clip retries) */
static void run_release(job *j, size_t r)
{
    const config *c = j->c;
    const size_t nr = j->A->n;
    const long id = j->A->r[r].id;
    for (long attempt = 0; attempt <= c->retries; ++attempt) {
        const double buffer = attempt_buffer(c, attempt);
        size_t pending = 0;
        for (size_t s = 0; s < c->ns; ++s) {
            const member *m = &j->m[s * nr + r];
            if (m->pre_failed || (m->done && (!m->ok || !leaked(m)))) continue;
            if (m->done && m->buffer >= buffer) continue; /* ran on this clip (or a larger one) already */
            ++pending;
        }
        if (!pending) continue;
        char why[2048] = "", cd[4096];
        int box[4], whole = 0;
        int okc = release_box(j, r, buffer, box, &whole, why, sizeof why) == 0;
        snprintf(cd, sizeof cd, "%s/r%ld_b%g", j->clips, id, buffer);
        if (okc && make_clip(j, box, cd, why, sizeof why)) okc = 0;
        char *templ = gf_path(cd, "template");
        if (okc) make_template(cd, templ);
        gf_workers *pool = NULL;
        if (okc) {
            char *logfmt = gf_path(cd, "log.worker_%u");
            char *argvw[] = {"faGranularFlowFoam", "-case", cd, "-members", "-", NULL};
            if (gf_workers_start(1, argvw, logfmt, &pool)) die("workers: %s", gf_error_detail());
            free(logfmt);
        }
        for (size_t s = 0; s < c->ns; ++s) {
            member *m = &j->m[s * nr + r];
            if (m->pre_failed || (m->done && (!m->ok || !leaked(m)))) continue;
            if (m->done && m->buffer >= buffer) continue;
            const int rerun = m->done;
            char md[4096], mwhy[2048] = "";
            member_dir(j, m, md, sizeof md);
            const double t = now();
            int ok = 0;
            m->buffer = buffer, m->whole = whole, m->outflow = NAN, m->volume = NAN, m->edge = 0;
            if (!okc) {
                mkdir(md, 0755);
                snprintf(mwhy, sizeof mwhy, "%s", why);
            } else if (make_member(j, templ, m, md, mwhy, sizeof mwhy) == 0) {
                if (gf_workers_run(pool, md, &ok, mwhy, sizeof mwhy)) die("%s", gf_error_detail());
                if (ok && score(j, md, m, mwhy, sizeof mwhy)) ok = 0;
                if (ok && member_outflow(md, &m->outflow, &m->volume)) {
                    snprintf(mwhy, sizeof mwhy, "no mass balance (postProcessing/hazardMaps/mass.csv)");
                    ok = 0;
                }
                if (ok) m->edge = reaches_clip_edge(j, md, box);
                gf_remove_times(md);
                slim_member(j, md);
            }
            m->ok = ok;
            m->seconds = now() - t;
            m->why[0] = 0;
            if (!ok) snprintf(m->why, sizeof m->why, "%s", mwhy);
            for (char *p = m->why; *p; ++p)
                if (*p == '\n' || *p == '\r') *p = ' ';
            write_result(md, m);
            pthread_mutex_lock(&j->lock);
            m->done = 1;
            if (!rerun) ++j->finished;
            if (ok)
                printf("member %-20s %3zu/%zu: depth %.3f m, %.1f s, affected %.0f m2, max %.1f kPa; clip %dx%d "
                       "pixels (buffer %g m)%s\n",
                       strrchr(md, '/') + 1, j->finished, j->total, m->depth, m->seconds, m->affected, m->maxppr,
                       box[2] - box[0] + 1, box[3] - box[1] + 1, buffer,
                       leaked(m) ? ": flow left through the clip's boundary" : "");
            else
                printf("member %-20s %3zu/%zu: FAILED (%s)\n", strrchr(md, '/') + 1, j->finished, j->total, m->why);
            fflush(stdout);
            pthread_mutex_unlock(&j->lock);
        }
        if (pool && gf_workers_stop(pool)) fprintf(stderr, "%s: %s\n", prog, gf_error_detail());
        /* the clip's meshes are done with: every member of this attempt has
         * its result, and a retry runs on another buffer's clip (its log,
         * CLIPS/rID_bBUFFER.log, stays; a killed batch leaves the clip, and
         * resuming uses it) */
        if (okc && !c->keep) {
            char *rmc[] = {"rm", "-rf", cd, NULL};
            if (gf_run(rmc, NULL)) fprintf(stderr, "%s: cannot remove %s\n", prog, cd);
        }
        free(templ);
        if (!okc || whole) break;
    }
}

static void *clip_runner(void *arg)
{
    job *j = arg;
    for (;;) {
        pthread_mutex_lock(&j->lock);
        const size_t r = j->next_rel++;
        pthread_mutex_unlock(&j->lock);
        if (r >= j->A->n) return NULL;
        if (j->task && (long)(r % (size_t)j->ntasks) != j->task - 1) continue;
        run_release(j, r);
    }
}

/* the scenario's merged maps on the region's grid: each member's rasters (on
 * its clip's grid: the region's pixel size, its origin whole pixels away,
 * checked) folded in; cells of the region's DEM that no member's clip holds
 * are 0 (not reached); the members merged */
static size_t merge_clipped(const job *j, size_t s, char *outdir)
{
    const config *c = j->c;
    const gf_raster *R = &j->dem;
    size_t n = 0;
    for (size_t k = 0; k < j->nm; ++k) n += j->m[k].scen == s && j->m[k].ok;
    if (n == 0) return 0;
    mkdir(outdir, 0755);
    static const char *field[] = {"pressurePeak", "hPeak", "speedPeak"};
    const size_t nc = (size_t)R->nx * (size_t)R->ny;
    gf_raster grid = *R;
    for (size_t fi = 0; fi < 3; ++fi) {
        double *mx = malloc(nc * sizeof *mx);
        unsigned *count = calloc(nc, sizeof *count);
        long *who = malloc(nc * sizeof *who);
        if (!mx || !count || !who) die("out of memory");
        for (size_t q = 0; q < nc; ++q) mx[q] = NAN, who[q] = -1;
        for (size_t k = 0; k < j->nm; ++k) {
            const member *m = &j->m[k];
            if (m->scen != s || !m->ok) continue;
            char md[4096], rel[256];
            member_dir(j, m, md, sizeof md);
            snprintf(rel, sizeof rel, "postProcessing/hazardMaps/%s.tif", field[fi]);
            char *f = gf_path(md, rel);
            gf_raster r;
            if (gf_raster_read(f, &r)) die("%s: %s", f, gf_error_detail());
            if (fabs(r.gt[1] - R->gt[1]) > 1e-9 * fabs(R->gt[1]) || fabs(r.gt[5] - R->gt[5]) > 1e-9 * fabs(R->gt[5]))
                die("%s: pixel %g x %g m, the region's DEM's %g x %g m: not the region's grid", f, r.gt[1], r.gt[5],
                    R->gt[1], R->gt[5]);
            const double fc = (r.gt[0] - R->gt[0]) / R->gt[1], fr = (r.gt[3] - R->gt[3]) / R->gt[5];
            const long oc = lround(fc), orow = lround(fr);
            if (fabs(fc - (double)oc) > 1e-6 || fabs(fr - (double)orow) > 1e-6 || oc < 0 || orow < 0 ||
                oc + r.nx > R->nx || orow + r.ny > R->ny)
                die("%s: its origin is %.9g, %.9g pixels from the region's DEM's (%d x %d pixels there): not a "
                    "whole-pixel window of the region's grid",
                    f, fc, fr, r.nx, r.ny);
            grid.nodata = r.nodata;
            const long id = j->A->r[m->rel].id;
            for (int jj = 0; jj < r.ny; ++jj)
                for (int ii = 0; ii < r.nx; ++ii) {
                    const double v = r.z[(size_t)jj * (size_t)r.nx + (size_t)ii];
                    if (isnan(v)) continue;
                    const size_t q = (size_t)(orow + jj) * (size_t)R->nx + (size_t)(oc + ii);
                    if (isnan(mx[q]) || v > mx[q]) mx[q] = v, who[q] = id;
                    if (v > c->threshold) ++count[q];
                }
            gf_raster_free(&r);
            free(f);
        }
        for (size_t q = 0; q < nc; ++q)
            if (isnan(mx[q]) && !isnan(R->z[q])) mx[q] = 0;
        char name[64];
        snprintf(name, sizeof name, "%sMax.tif", field[fi]);
        write_tif(outdir, name, &grid, mx);
        if (fi == 0) write_counts(outdir, &grid, nc, mx, count, who, c);
        free(mx), free(count), free(who);
    }
    return n;
}

/*---------------------------------------------------------------- SLURM --*/

/* a shell word: 'text' (the paths are OpenFOAM-safe: no quote in them) */
static void sh_word(FILE *o, const char *s) { fprintf(o, "'%s'", s); }

/* -slurm: DIR/slurm/array.sh (task K of N: gfRegionalMap -task K -tasks N)
 * and DIR/slurm/collect.sh (gfRegionalMap -collect), submitted with sbatch,
 * the collecting job after the array (afterany) */
static void submit(const job *j, const char *dp, const char *casedir, long np, long ntasks, int with_ab)
{
    size_t units = 0;
    if (j->c->clip) {
        for (size_t r = 0; r < j->A->n; ++r) {
            int pending = 0;
            for (size_t s = 0; s < j->c->ns; ++s) pending |= !j->m[s * j->A->n + r].done;
            units += pending;
        }
    } else {
        for (size_t k = 0; k < j->nm; ++k) units += !j->m[k].done;
    }
    if (!ntasks) ntasks = units ? (long)(units < 1000 ? units : 1000) : 1;
    char *sd = gf_path(j->dir, "slurm");
    mkdir(sd, 0755);
    char *arr = gf_path(sd, "array.sh"), *col = gf_path(sd, "collect.sh");
    FILE *o = fopen(arr, "w");
    if (!o) die("cannot write %s", arr);
    fprintf(o, "#!/bin/bash\n# gfRegionalMap -slurm: array task K of %ld runs the %s whose index is K - 1 modulo %ld\n"
               "# (those with a result are not run again); then slurm/collect.sh merges\n#SBATCH --job-name=gfRegionalMap\n"
               "#SBATCH --cpus-per-task=%ld\nexec gfRegionalMap -task \"$SLURM_ARRAY_TASK_ID\" -tasks %ld -np %ld -dict ",
            ntasks, j->c->clip ? "releases (every scenario of each)" : "members", ntasks, np, ntasks, np);
    sh_word(o, dp), fprintf(o, " -out "), sh_word(o, j->dir), fprintf(o, " "), sh_word(o, casedir), fprintf(o, "\n");
    if (fclose(o)) die("cannot write %s", arr);
    o = fopen(col, "w");
    if (!o) die("cannot write %s", col);
    fprintf(o, "#!/bin/bash\n# gfRegionalMap -slurm: the merge when the array has ended\n#SBATCH --job-name=gfRegionalMap-collect\n"
               "exec gfRegionalMap -collect%s -dict ", with_ab ? " -alphaBeta" : "");
    sh_word(o, dp), fprintf(o, " -out "), sh_word(o, j->dir), fprintf(o, " "), sh_word(o, casedir), fprintf(o, "\n");
    if (fclose(o)) die("cannot write %s", col);
    chmod(arr, 0755), chmod(col, 0755);
    char range[64], outa[4200], outc[4200], dep[160];   /* "--dependency=afterany:" and a job id of up to 127 characters */
    snprintf(range, sizeof range, "--array=1-%ld", ntasks);
    snprintf(outa, sizeof outa, "--output=%s/task_%%a.out", sd);
    snprintf(outc, sizeof outc, "--output=%s/collect.out", sd);
    char *idf = gf_path(sd, "array.jobid"), *idc = gf_path(sd, "collect.jobid");
    /* (gf_run appends: a submission again into the folder reads its own ids,
     * and its merge waits for its own array) */
    unlink(idf), unlink(idc);
    char *sb1[] = {"sbatch", "--parsable", range, outa, arr, NULL};
    if (gf_run(sb1, idf)) die("sbatch %s failed (%s): the scripts are in %s", arr, idf, sd);
    char id1[128] = "";
    FILE *in = fopen(idf, "r");
    if (!in || !fgets(id1, sizeof id1, in)) die("sbatch gave no job id (%s)", idf);
    fclose(in);
    id1[strcspn(id1, ";\r\n")] = 0;
    snprintf(dep, sizeof dep, "--dependency=afterany:%s", id1);
    char *sb2[] = {"sbatch", "--parsable", dep, outc, col, NULL};
    if (gf_run(sb2, idc)) die("sbatch %s failed (%s)", col, idc);
    char id2[128] = "";
    in = fopen(idc, "r");
    if (!in || !fgets(id2, sizeof id2, in)) die("sbatch gave no job id (%s)", idc);
    fclose(in);
    id2[strcspn(id2, ";\r\n")] = 0;
    printf("gfRegionalMap -slurm: %zu %s to run in %ld array tasks: job %s (%s), then the merge: job %s (%s)\n"
           "array=%s\ncollect=%s\ntasks=%ld\n",
           units, j->c->clip ? "releases" : "members", ntasks, id1, arr, id2, col, id1, id2, ntasks);
    free(sd), free(arr), free(col), free(idf), free(idc);
}

/*---------------------------------------------------------------- main --*/

static void check_path(const char *what, const char *path)
{
    if (!gf_path_foam_safe(path))
        die("%s '%s': a blank or a quote in the path; OpenFOAM drops them from file names: move or rename it",
            what, path);
}

static void make_template(const char *casedir, const char *templ)
{
    if (gf_exists(templ)) return;
    char *tmp = NULL;
    if (asprintf(&tmp, "%s.tmp", templ) < 0) die("out of memory");
    char *rm[] = {"rm", "-rf", tmp, NULL};
    gf_run(rm, NULL);
    gf_case_controls ctl;
    char err[2048];
    if (gf_member_template(casedir, tmp, &ctl, err, sizeof err)) die("%s", err);
    if (!ctl.sets_release)
        die("%s/system/controlDict does not set the release at the start (setFields (releaseDict);): a member's "
            "release could not act",
            casedir);
    char *cd = gf_path(tmp, "system/controlDict");
    if (ctl.has_path_analysis) {
        /* the case's path is that of its own release, not of every release area */
        char *log = NULL;
        if (asprintf(&log, "%s.log", tmp) < 0) die("out of memory");
        char *fd[] = {"foamDictionary", "-entry", "pathAnalysis", "-remove", cd, NULL};
        if (gf_run(fd, log)) die("cannot remove pathAnalysis from %s (foamDictionary; %s)", cd, log);
        free(log);
    }
    char text[512];
    snprintf(text, sizeof text,
             "\n// gfRegionalMap: the members' controls\nwriteInterval %s;\npeakFields yes;\nhazardMaps yes;\n",
             ctl.end_time);
    if (gf_append(cd, text)) die("cannot write %s", cd);
    if (rename(tmp, templ)) die("cannot rename %s", tmp);
    free(tmp), free(cd);
}

static void free_all(config *c, areas *A, job *j, char *casereal, char *dp)
{
    for (size_t k = 0; k < A->n; ++k) OGR_G_DestroyGeometry(A->r[k].geom);
    free(A->r);
    if (A->srs) OSRRelease(A->srs);
    free(c->areas), free(c->only);
    free(j->m), free(j->dir), free(j->templ), free(j->members);
    free(j->clips);
    if (j->dem.z) gf_raster_free(&j->dem);
    free(j->dem_path);
    free(casereal), free(dp);
}

static void usage(int st)
{
    FILE *f = st ? stderr : stdout;
    fprintf(f,
            "usage: gfRegionalMap [-dict FILE] [-out DIR] [-np N] [-check] [-alphaBeta] CASE\n"
            "       gfRegionalMap -slurm [-tasks T] [-np N] [-dict FILE] [-out DIR] [-alphaBeta] CASE\n"
            "       gfRegionalMap -task K -tasks T [-np N] [-dict FILE] [-out DIR] CASE\n"
            "       gfRegionalMap -collect [-dict FILE] [-out DIR] [-alphaBeta] CASE\n"
            "       gfRegionalMap -help | -version\n\n"
            "Every release area x scenario of FILE (default CASE/system/regionalDict) run as\n"
            "a member of the meshed terrain case CASE on N ensemble workers (default: the\n"
            "cores), merged per scenario into DIR/SCENARIO/{pressurePeakMax,hPeakMax,\n"
            "speedPeakMax,count,releaseId,zones}.tif; DIR/members.csv, DIR/summary.txt\n"
            "(DIR default CASE-regional).  Started again, members with a result are read,\n"
            "not run.  -check: the dictionary and the polygons checked, each member's depth\n"
            "printed, nothing written.  -alphaBeta: each release's alpha-beta runout beside\n"
            "its members' dynamic runout along its thalweg (DIR/alphaBeta.csv).  -slurm: a job\n"
            "array of T tasks (-task K -tasks T each) and the merge after it (-collect), submitted\n"
            "with sbatch.  The dictionary's format (clip { buffer reach climb retries }: each\n"
            "release on its own clipped mesh): the header of\n"
            "applications/utilities/gfRegionalMap/gfRegionalMap.c, doc/guide/regional.md.\n");
    exit(st);
}

int main(int argc, char **argv)
{
    long np = sysconf(_SC_NPROCESSORS_ONLN);
    const char *dictp = NULL, *out = NULL, *casedir = NULL;
    int check_only = 0, with_ab = 0, slurm = 0, collect = 0, np_given = 0;
    long task = 0, ntasks = 0;
    for (int i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "-np") == 0 && i + 1 < argc) {
            double v;
            if (!gf_parse_number(argv[++i], &v) || v != floor(v) || v < 1 || v > 256)
                die("-np %s: a whole number in [1, 256]", argv[i]);
            np = (long)v;
            np_given = 1;
        } else if (strcmp(argv[i], "-dict") == 0 && i + 1 < argc) {
            dictp = argv[++i];
        } else if (strcmp(argv[i], "-out") == 0 && i + 1 < argc) {
            out = argv[++i];
        } else if (strcmp(argv[i], "-check") == 0) {
            check_only = 1;
        } else if (strcmp(argv[i], "-alphaBeta") == 0) {
            with_ab = 1;
        } else if (strcmp(argv[i], "-slurm") == 0) {
            slurm = 1;
        } else if (strcmp(argv[i], "-collect") == 0) {
            collect = 1;
        } else if ((strcmp(argv[i], "-task") == 0 || strcmp(argv[i], "-tasks") == 0) && i + 1 < argc) {
            double v;
            const int is_task = strcmp(argv[i], "-task") == 0;
            ++i;
            if (!gf_parse_number(argv[i], &v) || v != floor(v) || v < 1 || v > 100000)
                die("%s %s: a whole number in [1, 100000]", argv[i - 1], argv[i]);
            if (is_task)
                task = (long)v;
            else
                ntasks = (long)v;
        } else if (strcmp(argv[i], "-help") == 0 || strcmp(argv[i], "--help") == 0) {
            usage(0);
        } else if (strcmp(argv[i], "-version") == 0) {
            printf("%s %s\n", prog, gf_version());
            return 0;
        } else if (argv[i][0] == '-') {
            fprintf(stderr, "%s: unknown option %s\n", prog, argv[i]);
            usage(2);
        } else if (!casedir) {
            casedir = argv[i];
        } else {
            usage(2);
        }
    }
    if (!casedir) usage(2);
    if (slurm + collect + (task > 0) + check_only > 1) die("-slurm, -collect, -task and -check: one at a time");
    if (task && !ntasks) die("-task K needs -tasks N (the array's size)");
    if (task > ntasks) die("-task %ld: outside the array's 1..%ld (-tasks)", task, ntasks);
    char *casereal = realpath(casedir, NULL);
    if (!casereal) die("%s: %s", casedir, strerror(errno));
    {
        char *pm = gf_path(casereal, "constant/polyMesh");
        if (!gf_exists(pm)) die("%s: not a meshed case (no constant/polyMesh)", casereal);
        free(pm);
    }
    char *dp = dictp ? strdup(dictp) : gf_path(casereal, "system/regionalDict");
    if (!gf_exists(dp)) die("%s: no such dictionary (-dict FILE, default CASE/system/regionalDict)", dp);
    if (slurm && !np_given) np = 1; /* a task's workers: --cpus-per-task */
    if (slurm) {
        check_path("-dict", dp);
        char *a = realpath(dp, NULL);
        if (!a) die("%s: %s", dp, strerror(errno));
        free(dp);
        dp = a;
    }
    GDALAllRegister();
    CPLSetErrorHandler(CPLQuietErrorHandler);
    config c;
    read_config(dp, casereal, &c);
    areas A;
    read_areas(&c, &A);

    /* the members: release-major within each scenario, in the file's order */
    job j;
    memset(&j, 0, sizeof j);
    j.c = &c, j.A = &A;
    j.nm = c.ns * A.n;
    j.m = calloc(j.nm, sizeof *j.m);
    if (!j.m) die("out of memory");
    size_t nbad = 0;
    for (size_t s = 0; s < c.ns; ++s)
        for (size_t r = 0; r < A.n; ++r) {
            member *m = &j.m[s * A.n + r];
            m->rel = r, m->scen = s;
            if (depth(&c, &A.r[r], s, &m->depth, m->why, sizeof m->why)) m->pre_failed = 1, ++nbad;
        }
    if (check_only) {
        printf("gfRegionalMap -check: %s: %zu releases x %zu scenarios = %zu members (%zu refused)\n", dp, A.n, c.ns,
               j.nm, nbad);
        for (size_t k = 0; k < j.nm; ++k) {
            const member *m = &j.m[k];
            if (m->pre_failed)
                printf("  %s_r%ld: refused: %s\n", c.s[m->scen].name, A.r[m->rel].id, m->why);
            else
                printf("  %s_r%ld: depth %.3f m\n", c.s[m->scen].name, A.r[m->rel].id, m->depth);
        }
        free_all(&c, &A, &j, casereal, dp);
        return 0;
    }
    check_path("the case", casereal);
    if (out) {
        j.dir = strdup(out);
    } else if (asprintf(&j.dir, "%s-regional", casereal) < 0) {
        die("out of memory");
    }
    check_path("-out", j.dir);
    if (mkdir(j.dir, 0755) && errno != EEXIST) die("%s: cannot make the folder: %s", j.dir, strerror(errno));
    char *absdir = realpath(j.dir, NULL);
    if (!absdir) die("%s: %s", j.dir, strerror(errno));
    free(j.dir);
    j.dir = absdir;
    {
        /* the dictionary beside the results; another batch's folder is not mixed with this one */
        char *copy = gf_path(j.dir, "regionalDict");
        if (gf_exists(copy)) {
            char *cmp[] = {"cmp", "-s", dp, copy, NULL};
            if (gf_run(cmp, NULL) != 0)
                die("%s holds the results of another batch (its regionalDict differs from %s): give another -out, "
                    "or remove it to start again",
                    j.dir, dp);
        } else {
            char *cp[] = {"cp", dp, copy, NULL};
            if (gf_run(cp, NULL)) die("cannot write %s", copy);
        }
        free(copy);
    }
    j.templ = gf_path(j.dir, "template");
    j.members = gf_path(j.dir, "members");
    mkdir(j.members, 0755);
    if (!c.clip) make_template(casereal, j.templ);
    if (c.clip) {
        j.casedir = casereal;
        j.clips = gf_path(j.dir, "clips");
        mkdir(j.clips, 0755);
        case_dem(&j, casereal);
        clip_settings(&j);
    }

    /* the results there are; the refused depths are results too */
    size_t resumed = 0;
    int rerun_pending = 0;
    for (size_t k = 0; k < j.nm; ++k) {
        member *m = &j.m[k];
        char md[4096];
        member_dir(&j, m, md, sizeof md);
        if (m->pre_failed) {
            m->done = 1, m->ok = 0;
            continue;
        }
        const double d = m->depth;
        if (read_result(md, m)) {
            ++resumed;
            m->depth = d;
            if (c.clip && leaked(m) && m->buffer < attempt_buffer(&c, c.retries)) rerun_pending = 1;
        }
    }
    j.task = task, j.ntasks = ntasks;
    size_t others = 0;
    if (task)
        for (size_t k = 0; k < j.nm; ++k) {
            member *m = &j.m[k];
            const size_t unit = c.clip ? m->rel : k;
            if ((long)(unit % (size_t)ntasks) != task - 1 && !m->done) m->done = 1, ++others;
        }
    if (slurm) {
        submit(&j, dp, casereal, np, ntasks, with_ab);
        free_all(&c, &A, &j, casereal, dp);
        return 0;
    }
    j.total = j.nm;
    j.finished = resumed + nbad + others;
    size_t torun = j.nm - j.finished;
    if (collect) {
        /* the array's results: a member without one is failed, not run here */
        for (size_t k = 0; k < j.nm; ++k) {
            member *m = &j.m[k];
            if (m->done) continue;
            m->done = 1, m->ok = 0;
            snprintf(m->why, sizeof m->why,
                     "no result: its array task has not run it (gfRegionalMap -slurm again runs what has none)");
        }
        torun = 0, rerun_pending = 0;
    }
    printf("gfRegionalMap: %zu releases x %zu scenarios = %zu members: %zu resumed, %zu refused, %zu to run on %ld "
           "workers (%s)\n",
           A.n, c.ns, j.nm, resumed, nbad, torun, torun ? (np < (long)torun ? np : (long)torun) : 0L, j.dir);
    for (size_t k = 0; k < j.nm; ++k)
        if (j.m[k].pre_failed)
            printf("member %s_r%ld: FAILED (%s)\n", c.s[j.m[k].scen].name, A.r[j.m[k].rel].id, j.m[k].why);
    fflush(stdout);
    j.t0 = now();
    if (c.clip && (torun || rerun_pending)) {
        pthread_mutex_init(&j.lock, NULL);
        const size_t nw = (size_t)np < A.n ? (size_t)np : A.n;
        pthread_t *th = malloc(nw * sizeof *th);
        for (size_t t = 0; t < nw; ++t)
            if (pthread_create(&th[t], NULL, clip_runner, &j)) die("cannot start a thread");
        for (size_t t = 0; t < nw; ++t) pthread_join(th[t], NULL);
        free(th);
    } else if (torun && !c.clip) {
        const size_t nw = (size_t)np < torun ? (size_t)np : torun;
        char *logfmt = gf_path(j.dir, "log.worker_%u");
        char *argvw[] = {"faGranularFlowFoam", "-case", casereal, "-members", "-", NULL};
        if (gf_workers_start(nw, argvw, logfmt, &j.pool)) die("workers: %s", gf_error_detail());
        pthread_mutex_init(&j.lock, NULL);
        pthread_t *th = malloc(nw * sizeof *th);
        for (size_t t = 0; t < nw; ++t)
            if (pthread_create(&th[t], NULL, runner, &j)) die("cannot start a thread");
        for (size_t t = 0; t < nw; ++t) pthread_join(th[t], NULL);
        if (gf_workers_stop(j.pool)) fprintf(stderr, "%s: %s\n", prog, gf_error_detail());
        free(th), free(logfmt);
    }
    const double wall = now() - j.t0;
    if (task) {
        size_t mine = 0, bad_mine = 0;
        for (size_t k = 0; k < j.nm; ++k) {
            const member *m = &j.m[k];
            const size_t unit = c.clip ? m->rel : k;
            if ((long)(unit % (size_t)ntasks) != task - 1) continue;
            ++mine;
            bad_mine += !m->ok;
        }
        printf("task %ld of %ld: %zu members, %zu ran now, %zu failed; %.1f s (gfRegionalMap -collect merges)\n", task,
               ntasks, mine, torun, bad_mine, wall);
        free_all(&c, &A, &j, casereal, dp);
        return bad_mine ? 3 : 0;
    }

    /* the merge and the tables */
    size_t nfailed = 0, nran = 0;
    double sec_sum = 0;
    for (size_t k = 0; k < j.nm; ++k) {
        nfailed += !j.m[k].ok;
        if (j.m[k].ok) sec_sum += j.m[k].seconds, ++nran;
    }
    char *csv = gf_path(j.dir, "members.csv");
    FILE *o = fopen(csv, "w");
    if (!o) die("cannot write %s", csv);
    fprintf(o, "release,scenario,depth_m,status,seconds,affected_m2,maxPressure_kPa,reason%s\n",
            c.clip ? ",outflow_m3,volume_m3,clipBuffer_m" : "");
    size_t nleak = 0;
    for (size_t k = 0; k < j.nm; ++k) {
        const member *m = &j.m[k];
        fprintf(o, "%ld,%s,%.4f,%s,%.2f,", A.r[m->rel].id, c.s[m->scen].name, m->depth, m->ok ? "ok" : "failed",
                m->seconds);
        if (m->ok && c.clip && leaked(m)) {
            ++nleak;
            fprintf(o, "%.1f,%.3f,\"flow left through the clip's boundary: %.4g m3 of %.4g m3 with a %g m buffer "
                       "(clip buffer x 2^retries); its maps lack what went beyond\"",
                    m->affected, m->maxppr, m->outflow, m->volume, m->buffer);
        } else if (m->ok) {
            fprintf(o, "%.1f,%.3f,", m->affected, m->maxppr);
        } else {
            fprintf(o, ",,\"");
            for (const char *p = m->why; *p; ++p) fputc(*p == '"' ? '\'' : *p, o);
            fprintf(o, "\"");
        }
        if (c.clip) {
            if (m->ok)
                fprintf(o, ",%.6g,%.6g,%s", m->outflow, m->volume, m->whole ? "whole" : "");
            else
                fprintf(o, ",,,");
            if (m->ok && !m->whole) fprintf(o, "%g", m->buffer);
        }
        fprintf(o, "\n");
    }
    fclose(o);
    char *sum = gf_path(j.dir, "summary.txt");
    FILE *S = fopen(sum, "w");
    if (!S) die("cannot write %s", sum);
    fprintf(S, "gfRegionalMap %s: %s\nreleases %zu (%s, id %s), scenarios %zu, members %zu: %zu ok, %zu failed\n",
            gf_version(), dp, A.n, c.areas, c.id_attr, c.ns, j.nm, j.nm - nfailed, nfailed);
    fprintf(S, "threshold %g kPa; zones", c.threshold);
    for (size_t z = 0; z < c.n_zones; ++z) fprintf(S, " %g", c.zones[z]);
    fprintf(S, " kPa\n");
    size_t merged[MAXSCEN] = {0};
    for (size_t s = 0; s < c.ns; ++s) {
        char *od = gf_path(j.dir, c.s[s].name);
        const size_t nmg = c.clip ? merge_clipped(&j, s, od) : merge(&j, s, od);
        double amax = 0, pmax = 0;
        for (size_t k = 0; k < j.nm; ++k)
            if (j.m[k].scen == s && j.m[k].ok) {
                if (j.m[k].affected > amax) amax = j.m[k].affected;
                if (j.m[k].maxppr > pmax) pmax = j.m[k].maxppr;
            }
        fprintf(S, "scenario %s: %zu members merged into %s/ (largest affected area %.0f m2, largest peak pressure %.1f kPa)\n",
                c.s[s].name, nmg, c.s[s].name, amax, pmax);
        merged[s] = nmg;
        printf("scenario %s: %zu members merged (%s)\n", c.s[s].name, nmg, od);
        free(od);
    }
    for (size_t k = 0; k < j.nm; ++k)
        if (!j.m[k].ok)
            fprintf(S, "FAILED %s_r%ld: %s\n", c.s[j.m[k].scen].name, A.r[j.m[k].rel].id, j.m[k].why);
        else if (c.clip && leaked(&j.m[k]))
            fprintf(S, "BOUNDARY %s_r%ld: %.4g m3 of %.4g m3 left through the clip's boundary (buffer %g m)\n",
                    c.s[j.m[k].scen].name, A.r[j.m[k].rel].id, j.m[k].outflow, j.m[k].volume, j.m[k].buffer);
    if (c.clip) fprintf(S, "clip: buffer %g m, reach %g m, climb %g m, retries %ld\n", c.buffer, c.reach, c.climb, c.retries);
    fclose(S);
    /* alpha-beta beside the dynamic runouts, and the outlines */
    ab_release *abr = NULL;
    double *sdyn = NULL;
    case_dem(&j, casereal); /* (the clips' already) */
    if (with_ab) {
        sdyn = malloc(j.nm * sizeof *sdyn);
        if (!sdyn) die("out of memory");
        abr = alpha_beta(&j, &j.dem, sdyn);
    }
    for (size_t s = 0; s < c.ns; ++s) {
        if (!merged[s]) continue;
        char *od = gf_path(j.dir, c.s[s].name);
        write_outlines(&j, s, od, abr, sdyn);
        free(od);
    }
    ab_free(abr, A.n);
    free(sdyn);
    write_project(&j, merged, with_ab);
    const size_t ran_now = torun;
    printf("members=%zu\nran=%zu\nresumed=%zu\nfailed=%zu\nseconds=%.1f\nsecondsPerMember=%.2f\n", j.nm, ran_now,
           resumed, nfailed, wall, nran ? sec_sum / (double)nran : 0.0);
    if (c.clip) printf("boundary=%zu\n", nleak);
    free(csv), free(sum);
    free_all(&c, &A, &j, casereal, dp);
    return nfailed ? 3 : 0;
}
