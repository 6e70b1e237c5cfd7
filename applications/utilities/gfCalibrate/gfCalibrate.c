/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * gfCalibrate — back-calculate an observed event: the parameters (friction
 * coefficients, the release thickness, any dictionary entry) whose runs
 * reproduce an observed outline, runout, deposit and front (positions and
 * speeds at given times: radar, video), with what the
 * observation does and does not constrain (doc/theory/calibration.md,
 * doc/guide/back-calculation.md).
 *
 *   gfCalibrate [-np N] [-dict FILE] [-out DIR] CASE
 *   gfCalibrate -check [-dict FILE] CASE
 *   gfCalibrate -run "V1 ... Vd" [-dict FILE] -out DIR CASE
 *   gfCalibrate -observe RUN OUTDIR [-threshold KPA] [-shift CELLS] [-runoutShift M]
 *   gfCalibrate -version | -help
 *
 * CASE is a terrain case that has been meshed and released (a tutorial's
 * run folder).  FILE (default CASE/system/calibrationDict) names the
 * parameters and their ranges, the observations and the scores' weights;
 * every key is checked (an unknown one is refused).  The calibration runs
 * libgranflow's gf_calibrate_run: a Sobol design and Morris trajectories,
 * then simplex refinements from the best points, every evaluation a member
 * folder DIR/evals/eval_NNNN run by N ensemble workers (faGranularFlowFoam
 * -members -: the meshes loaded once per worker, granflow/workers.h).  A
 * calibration that stops (killed, a machine down) resumes: run the same
 * command again; every evaluation whose result is in its folder is read,
 * not run again.  Output in DIR (default CASE-calibration):
 *   evaluations.csv  every evaluation: its parameters, status, loss, scores, folder
 *   summary.txt      the verdict, the best set, the credible ranges, the
 *                    ridge, the sensitivities, the evaluations per minute
 *   parameters.csv   per parameter: best, credible range, design range
 *   best/            the best evaluation's case (its results, ready to run again),
 *                    with its report maps and the observed outline and
 *                    runout point drawn on them (postProcessing/hazardMaps/report/)
 *   loss_A_B.png     the loss over each pair of parameters with the ridge
 *   bestOutline.tif  the best run against the observation per pixel:
 *                    1 both affected, 2 simulated only, 3 observed only
 * The exit status is 0 when the observation is reached, 3 when no
 * evaluation reproduces it (unreachable: reported, never a silent best
 * guess), 1 or 2 on errors.
 *
 * -check reads the dictionary and the observations, checks them and the
 * parameters' entries in the case, and ends (exit status 0) without
 * writing anything.  A case or output path with a blank or a quote is
 * refused (OpenFOAM drops them from file names).
 *
 * -run makes one run of CASE in DIR (its own solver process) with the
 * dictionary's parameters at the values given, in the dictionary's order
 * (the "event" of a twin experiment: gfCalibrate -run "0.20 1.15" -out
 * EVENT CASE, then -observe EVENT); the dictionary's observations are not
 * read.
 *
 * -observe makes the observations of a run (a twin experiment, or a
 * documented event re-made from a run): RUN's peak pressure above the
 * threshold (default 1 kPa) as an outline shapefile (outline.shp, the DEM's
 * CRS), the runout point (runout.shp: pathAnalysis's xRunout, yRunout) and
 * the deposit (deposit.tif: the thickness at the run's end) and the front
 * (front.csv: time,x,y,speed at 6 times evenly spread until the front has
 * done 99 % of its travel along the path, or at -frontTimes "T1 T2 ..."; the front is the
 * furthest cell along the path the arrival-time map has reached by then,
 * the speed its central difference over 2 s); -shift moves the outline by
 * CELLS pixels east, -runoutShift moves the runout point by M metres along
 * the path (noise on the observation).
 */
#define _GNU_SOURCE
#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <time.h>
#include <unistd.h>

#include <gdal.h>
#include <gdal_alg.h>
#include <ogr_api.h>
#include <ogr_srs_api.h>

#include "gf_dict.h"
#include "gf_members.h"
#include "granflow/calibration.h"
#include "granflow/path_analysis.h"
#include "granflow/terrain.h"
#include "granflow/version.h"
#include "granflow/workers.h"

#define MAXP 16

static const char *prog = "gfCalibrate";

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

static char *cat(const char *a, const char *b) { return gf_path(a, b); }
#define run_prog gf_run
#define exists gf_exists

static double now(void)
{
    struct timeval t;
    gettimeofday(&t, NULL);
    return (double)t.tv_sec + 1e-6 * (double)t.tv_usec;
}

/*---------------------------------------------------------------- the dictionary --*/

typedef struct param {
    char name[64];
    int release;         /* 1: the release thickness factor (releaseDict factor) */
    char file[512];      /* the dictionary, relative to the case */
    char entry[512];     /* a/b/c */
    double lo, hi;
} param;

typedef struct config {
    const char *path;
    param p[MAXP];
    size_t d;
    char *outline, *runout_point, *deposit, *front;
    double runout_s;     /* NAN: not given as a number */
    double threshold, alpha, beta, deposit_threshold;
    double front_window; /* s: the front speed's central difference */
    gf_loss_weights w;
    gf_calib_plan plan;
    double runout_tol, min_jaccard, front_tol, speed_tol;
} config;

/* the half width of the path's corridor [m]: the path analysis's (a runout
 * point or a front point further from the path is refused) */
#define HALF_WIDTH 300.0

static void read_config(const char *path, config *c)
{
    char err[2048];
    memset(c, 0, sizeof *c);
    c->path = path;
    gf_dict *D = gf_dict_read(path, err, sizeof err);
    if (!D) die("%s", err);

    const gf_dict *P = gf_dict_sub(D, "parameters", 1);
    for (size_t k = 0; k < P->n; ++k) {
        gf_dict_entry *e = &P->e[k];
        e->used = 1;
        if (!e->sub) gf_dict_refuse(c->path, e, e->key, "a parameter is a dictionary { file F; entry E; range (lo hi); } or "
                                       "{ release factor; range (lo hi); }");
        if (c->d == MAXP) gf_dict_refuse(c->path, e, e->key, "more than %d parameters", MAXP);
        param *p = &c->p[c->d++];
        snprintf(p->name, sizeof p->name, "%s", e->key);
        const gf_dict *s = e->sub;
        const char *rel = gf_dict_word(s, "release", NULL, 0);
        if (rel) {
            if (strcmp(rel, "factor") != 0) gf_dict_refuse(c->path, gf_dict_find(s, "release"), "release", "'%s': allowed: factor", rel);
            p->release = 1;
        } else {
            const char *f = gf_dict_word(s, "file", NULL, 0), *en = gf_dict_word(s, "entry", NULL, 0);
            if (!f || !en)
                gf_dict_refuse(c->path, e, e->key, "needs file (a dictionary of the case, e.g. constant/granularProperties) and "
                                  "entry (e.g. samosATCoeffs/mu), or release factor");
            if (f[0] == '/' || strstr(f, "..")) gf_dict_refuse(c->path, gf_dict_find(s, "file"), "file", "'%s': a path inside the case", f);
            if (strcmp(f, "system/controlDict") == 0)
                gf_dict_refuse(c->path, gf_dict_find(s, "file"), "file", "the run's controls are not calibrated");
            snprintf(p->file, sizeof p->file, "%s", f);
            snprintf(p->entry, sizeof p->entry, "%s", en);
        }
        const gf_dict_entry *r = gf_dict_find(s, "range");
        if (!r || r->sub || r->ntok != 4 || strcmp(r->tok[0], "(") || strcmp(r->tok[3], ")") ||
            !gf_parse_number(r->tok[1], &p->lo) || !gf_parse_number(r->tok[2], &p->hi) || !(p->hi > p->lo) ||
            !isfinite(p->lo) || !isfinite(p->hi))
            gf_dict_refuse(c->path, r ? r : e, e->key, "range: expected (lo hi) with lo < hi, finite");
        if (p->release && !(p->lo >= 0 && p->hi <= 100))
            gf_dict_refuse(c->path, r, e->key, "a release factor's range lies in [0, 100]");
    }
    if (c->d == 0) gf_dict_refuse(c->path, NULL, "parameters", "no parameter to calibrate");

    const gf_dict *O = gf_dict_sub(D, "observations", 1);
    const char *w;
    c->runout_s = NAN;
    if ((w = gf_dict_word(O, "outline", NULL, 0))) c->outline = strdup(w);
    if ((w = gf_dict_word(O, "runoutPoint", NULL, 0))) c->runout_point = strdup(w);
    if (gf_dict_find(O, "runout")) c->runout_s = gf_dict_number(O, "runout", NAN, 0, 1e6);
    if ((w = gf_dict_word(O, "deposit", NULL, 0))) c->deposit = strdup(w);
    if ((w = gf_dict_word(O, "front", NULL, 0))) c->front = strdup(w);
    if (c->runout_point && !isnan(c->runout_s))
        gf_dict_refuse(c->path, gf_dict_find(O, "runout"), "observations", "give runoutPoint or runout, not both");
    if (!c->outline && !c->runout_point && isnan(c->runout_s) && !c->deposit && !c->front)
        gf_dict_refuse(c->path, NULL, "observations", "none given: outline, runoutPoint or runout, deposit, front");

    const gf_dict *S = gf_dict_sub(D, "scores", 0);
    gf_dict empty = {path, (char *)"scores", NULL, 0};
    if (!S) S = &empty;
    c->threshold = gf_dict_number(S, "threshold", 1, 0, 1e6);
    c->alpha = gf_dict_number(S, "tverskyAlpha", 1, 0, 100);
    c->beta = gf_dict_number(S, "tverskyBeta", 1, 0, 100);
    c->w.runout = gf_dict_number(S, "runoutWeight", 1, 0, 1e6);
    c->w.runout_scale = gf_dict_number(S, "runoutScale", 20, 1e-9, 1e6);
    c->w.outline = gf_dict_number(S, "outlineWeight", 1, 0, 1e6);
    c->w.rmse = gf_dict_number(S, "depositWeight", 1, 0, 1e6);
    c->w.rmse_scale = gf_dict_number(S, "depositScale", 0.5, 1e-9, 1e6);
    c->deposit_threshold = gf_dict_number(S, "depositThreshold", 0.01, 0, 1e3);
    c->w.series = gf_dict_number(S, "frontWeight", 1, 0, 1e6);
    c->w.series_scale = gf_dict_number(S, "frontScale", 20, 1e-9, 1e6);
    c->w.speed = gf_dict_number(S, "frontSpeedWeight", 1, 0, 1e6);
    c->w.speed_scale = gf_dict_number(S, "frontSpeedScale", 2, 1e-9, 1e6);
    c->front_window = gf_dict_number(S, "frontSpeedWindow", 2, 1e-6, 1e4);

    const gf_dict *G = gf_dict_sub(D, "design", 0);
    gf_dict emptyG = {path, (char *)"design", NULL, 0};
    if (!G) G = &emptyG;
    c->plan.d = c->d;
    c->plan.n_sobol = (size_t)gf_dict_whole(G, "sobol", 8 * (double)c->d + 8, 1, 1e5);
    c->plan.morris_r = (size_t)gf_dict_whole(G, "morrisTrajectories", 4, 0, 1e4);
    if (c->plan.morris_r == 1) gf_dict_refuse(c->path, gf_dict_find(G, "morrisTrajectories"), "design/morrisTrajectories", "0 or >= 2");
    c->plan.morris_p = (size_t)gf_dict_whole(G, "morrisLevels", 4, 2, 100);
    if (c->plan.morris_p % 2) gf_dict_refuse(c->path, gf_dict_find(G, "morrisLevels"), "design/morrisLevels", "an even number");
    c->plan.seed = (size_t)gf_dict_whole(G, "seed", 1, 0, 4e9);

    const gf_dict *R = gf_dict_sub(D, "refinement", 0);
    gf_dict emptyR = {path, (char *)"refinement", NULL, 0};
    if (!R) R = &emptyR;
    c->plan.n_starts = (size_t)gf_dict_whole(R, "starts", 2, 0, 100);
    c->plan.refine_evals = (size_t)gf_dict_whole(R, "evaluations", 10 * (double)c->d + 5, (double)c->d + 1, 1e5);
    c->plan.step = gf_dict_number(R, "step", 0.1, 1e-6, 1);
    c->plan.tol = gf_dict_number(R, "tolerance", 0.01, 1e-9, 1);
    c->plan.failed_loss = 10;

    const gf_dict *X = gf_dict_sub(D, "exploration", 0);
    gf_dict emptyX = {path, (char *)"exploration", NULL, 0};
    if (!X) X = &emptyX;
    c->plan.n_explore = (size_t)gf_dict_whole(X, "points", 8 * (double)c->d, 0, 1e5);
    c->plan.explore_rounds = (size_t)gf_dict_whole(X, "rounds", 3, 1, 100);
    c->plan.explore_margin = gf_dict_number(X, "margin", 0.5, 0, 10);

    const gf_dict *A = gf_dict_sub(D, "acceptance", 0);
    gf_dict emptyA = {path, (char *)"acceptance", NULL, 0};
    if (!A) A = &emptyA;
    c->runout_tol = gf_dict_number(A, "runoutTolerance", c->w.runout_scale, 0, 1e6);
    c->min_jaccard = gf_dict_number(A, "minJaccard", 0.8, 0, 1);
    c->front_tol = gf_dict_number(A, "frontTolerance", c->w.series_scale, 0, 1e6);
    c->speed_tol = gf_dict_number(A, "frontSpeedTolerance", c->w.speed_scale, 0, 1e6);

    const gf_dict *in = NULL;
    const gf_dict_entry *u = gf_dict_unused(D, &in);
    if (u)
        gf_dict_refuse(c->path, u, u->key, "unknown key%s%s (allowed: parameters, observations { outline runoutPoint runout deposit "
                          "front }, scores { threshold tverskyAlpha tverskyBeta runoutWeight runoutScale outlineWeight "
                          "depositWeight depositScale depositThreshold frontWeight frontScale frontSpeedWeight "
                          "frontSpeedScale frontSpeedWindow }, design { sobol morrisTrajectories "
                          "morrisLevels seed }, refinement { starts evaluations step tolerance }, exploration { points rounds margin }, acceptance { "
                          "runoutTolerance minJaccard frontTolerance frontSpeedTolerance })",
            in && *in->name ? " in " : "", in && *in->name ? in->name : "");
    gf_dict_free(D);
}

/*---------------------------------------------------------------- the observation --*/

typedef struct observation {
    gf_raster dem;            /* the DEM's grid */
    unsigned char *mask;      /* observed affected (outline) or NULL */
    unsigned char *valid;     /* cells counted */
    double cell_area;
    double s_runout;          /* NAN: not observed */
    double *deposit;          /* NULL: not observed */
    size_t npath;
    double *path;             /* the case's path (xy) */
    size_t nfront;            /* observed front points (0: none) */
    double *ft, *fs, *fv;     /* their times [s], positions along the path [m], speeds [m/s] (NAN: none) */
    size_t nspeed;            /* the points with a speed */
    double *cs, *cl;          /* every DEM cell's s and l along the path (with a front) */
} observation;

/* the value of a one-word entry of a case dictionary (NULL when absent) */
static char *case_word(const char *file, const char *key)
{
    char err[1024];
    gf_dict *d = gf_dict_read(file, err, sizeof err);
    if (!d) die("%s", err);
    gf_dict_entry *e = gf_dict_find(d, key);
    char *r = e && !e->sub && e->ntok == 1 ? strdup(e->tok[0]) : NULL;
    gf_dict_free(d);
    return r;
}

static void crs_check(const char *what, const char *file, const char *wkt, const observation *o, const char *dem)
{
    const int same = gf_crs_same(wkt, o->dem.wkt);
    if (same == 0) die("observations/%s %s: its CRS is not the DEM's (%s): reproject it to the DEM's CRS", what, file, dem);
    if (same < 0 && *wkt && *o->dem.wkt)
        die("observations/%s %s: its CRS is not understood (GDAL), the DEM's is", what, file);
}

/* every cell centre's coordinates along (*s) and across (*l) the path of np
 * points xy (gf_path_locate), arrays of the grid's size */
static void cell_path_coords(const gf_raster *g, size_t np, const double *xy, double **s, double **l)
{
    const size_t n = (size_t)g->nx * (size_t)g->ny;
    *s = malloc(n * sizeof **s);
    *l = malloc(n * sizeof **l);
    if (!*s || !*l) die("out of memory");
    for (int r = 0; r < g->ny; ++r)
        for (int q = 0; q < g->nx; ++q) {
            double x, y;
            const size_t i = (size_t)r * (size_t)g->nx + (size_t)q;
            gf_raster_centre(g, q, r, &x, &y);
            gf_path_locate(np, xy, x, y, &(*s)[i], &(*l)[i]);
        }
}

/* the observed front: a CSV file with the header time,x,y or
 * time,x,y,speed (an empty speed: none at that time), one row per
 * observation, the points in the DEM's coordinates; each point's position
 * along the case's path (pf); and every DEM cell's s and l, for the
 * simulated front (gf_front_position) */
static void read_front(const char *casedir, const config *c, observation *o, const char *pf)
{
    char *f = c->front[0] == '/' ? strdup(c->front) : cat(casedir, c->front);
    FILE *in = fopen(f, "r");
    if (!in) die("observations/front %s: cannot open it (%s)", f, strerror(errno));
    char line[1024];
    if (!fgets(line, sizeof line, in)) die("observations/front %s: empty (expected the header time,x,y[,speed])", f);
    line[strcspn(line, "\r\n")] = '\0';
    int has_speed = 0;
    if (strcmp(line, "time,x,y,speed") == 0)
        has_speed = 1;
    else if (strcmp(line, "time,x,y") != 0)
        die("observations/front %s: header '%s': expected time,x,y or time,x,y,speed (time in s from the release, x "
            "and y in the DEM's coordinates, speed in m/s)", f, line);
    size_t cap = 0, row = 1;
    while (fgets(line, sizeof line, in)) {
        ++row;
        line[strcspn(line, "\r\n")] = '\0';
        if (!line[0]) continue;
        char *field[5] = {0};
        int nf = 0;
        for (char *p = line; nf < 5;) {
            field[nf++] = p;
            char *comma = strchr(p, ',');
            if (!comma) break;
            *comma = '\0';
            p = comma + 1;
        }
        if (nf != 3 + has_speed)
            die("observations/front %s, line %zu: %d fields, expected %d (%s)", f, row, nf, 3 + has_speed,
                has_speed ? "time,x,y,speed" : "time,x,y");
        double v[4] = {NAN, NAN, NAN, NAN};
        for (int j = 0; j < nf; ++j) {
            if (j == 3 && !field[j][0]) continue; /* no speed at this time */
            if (!gf_parse_number(field[j], &v[j]) || !isfinite(v[j]))
                die("observations/front %s, line %zu: '%s' is not a number", f, row, field[j]);
        }
        if (v[0] < 0) die("observations/front %s, line %zu: time %g s: allowed >= 0 (from the release)", f, row, v[0]);
        if (!isnan(v[3]) && v[3] < 0) die("observations/front %s, line %zu: speed %g m/s: allowed >= 0", f, row, v[3]);
        if (!gf_raster_covers(&o->dem, v[1], v[2]))
            die("observations/front %s, line %zu: (%.1f, %.1f) lies outside the DEM", f, row, v[1], v[2]);
        double sp, l;
        gf_path_locate(o->npath, o->path, v[1], v[2], &sp, &l);
        if (fabs(l) > HALF_WIDTH)
            die("observations/front %s, line %zu: (%.1f, %.1f) lies %.0f m from the path %s (at most %.0f m: the "
                "path analysis's half width)", f, row, v[1], v[2], fabs(l), pf, HALF_WIDTH);
        if (o->nfront == cap) {
            cap = cap ? 2 * cap : 16;
            o->ft = realloc(o->ft, cap * sizeof *o->ft);
            o->fs = realloc(o->fs, cap * sizeof *o->fs);
            o->fv = realloc(o->fv, cap * sizeof *o->fv);
            if (!o->ft || !o->fs || !o->fv) die("out of memory");
        }
        o->ft[o->nfront] = v[0], o->fs[o->nfront] = sp, o->fv[o->nfront] = v[3];
        o->nspeed += !isnan(v[3]);
        ++o->nfront;
    }
    fclose(in);
    if (o->nfront == 0) die("observations/front %s: no observation after the header", f);
    cell_path_coords(&o->dem, o->npath, o->path, &o->cs, &o->cl);
    printf("observed front %s: %zu positions (%zu with a speed), %.1f to %.1f s\n", c->front, o->nfront, o->nspeed,
           o->ft[0], o->ft[o->nfront - 1]);
    free(f);
}

static void read_observation(const char *casedir, const config *c, observation *o)
{
    memset(o, 0, sizeof *o);
    o->s_runout = NAN;
    char *td = cat(casedir, "system/terrainDict");
    char *demrel = case_word(td, "dem");
    if (!demrel) die("%s: no dem entry: CASE must be a terrain case (gfTerrainMesh)", td);
    char *dem = cat(casedir, "constant/demWithDam.tif");
    if (!exists(dem)) {
        free(dem);
        dem = demrel[0] == '/' ? strdup(demrel) : cat(casedir, demrel);
    }
    if (gf_raster_read(dem, &o->dem)) die("DEM %s: %s", dem, gf_error_detail());
    const size_t n = (size_t)o->dem.nx * (size_t)o->dem.ny;
    o->cell_area = fabs(o->dem.gt[1] * o->dem.gt[5]);
    o->valid = malloc(n);
    if (!o->valid) die("out of memory");
    for (size_t i = 0; i < n; ++i) o->valid[i] = !isnan(o->dem.z[i]);

    if (c->outline) {
        char *f = c->outline[0] == '/' ? strdup(c->outline) : cat(casedir, c->outline);
        gf_polygons P;
        if (gf_polygons_read(f, NULL, 1, &P)) die("observations/outline %s: %s", f, gf_error_detail());
        crs_check("outline", f, P.wkt, o, dem);
        o->mask = calloc(n, 1);
        if (!o->mask) die("out of memory");
        size_t inside = 0;
        for (int r = 0; r < o->dem.ny; ++r)
            for (int q = 0; q < o->dem.nx; ++q) {
                double x, y;
                gf_raster_centre(&o->dem, q, r, &x, &y);
                const size_t i = (size_t)r * (size_t)o->dem.nx + (size_t)q;
                o->mask[i] = gf_polygons_locate(&P, x, y) >= 0;
                inside += o->mask[i] && o->valid[i];
            }
        gf_polygons_free(&P);
        if (inside == 0) die("observations/outline %s: no pixel centre of the DEM %s lies inside it", f, dem);
        printf("observed outline %s: %zu pixels, %.0f m2\n", c->outline, inside, (double)inside * o->cell_area);
        free(f);
    }
    if (c->runout_point || !isnan(c->runout_s) || c->front) {
        char *pf = cat(casedir, "Inputs/LINES/path_aimec.shp");
        if (!exists(pf))
            die("observations: a runout or a front needs the case's path %s (measured along it)", pf);
        if (gf_path_read(pf, &o->npath, &o->path)) die("path %s: %s", pf, gf_error_detail());
        if (c->runout_point) {
            char *f = c->runout_point[0] == '/' ? strdup(c->runout_point) : cat(casedir, c->runout_point);
            char *wkt = NULL;
            if (gf_vector_crs(f, &wkt)) die("observations/runoutPoint %s: %s", f, gf_error_detail());
            crs_check("runoutPoint", f, wkt, o, dem);
            free(wkt);
            double x, y, l;
            if (gf_point_read(f, &x, &y)) die("observations/runoutPoint %s: %s", f, gf_error_detail());
            gf_path_locate(o->npath, o->path, x, y, &o->s_runout, &l);
            if (fabs(l) > 300)
                die("observations/runoutPoint %s: (%.1f, %.1f) lies %.0f m from the path %s (at most 300 m: the "
                    "path analysis's half width)",
                    f, x, y, fabs(l), pf);
            printf("observed runout point %s: s = %.1f m along the path (%.1f m %s of it)\n", c->runout_point,
                   o->s_runout, fabs(l), l > 0 ? "left" : "right");
            free(f);
        } else if (!isnan(c->runout_s)) {
            o->s_runout = c->runout_s;
            printf("observed runout: s = %.1f m along the path\n", o->s_runout);
        }
        if (c->front) read_front(casedir, c, o, pf);
        free(pf);
    }
    if (c->deposit) {
        char *f = c->deposit[0] == '/' ? strdup(c->deposit) : cat(casedir, c->deposit);
        gf_raster r;
        if (gf_raster_read(f, &r)) die("observations/deposit %s: %s", f, gf_error_detail());
        crs_check("deposit", f, r.wkt, o, dem);
        if (!gf_raster_same_grid(&r, &o->dem))
            die("observations/deposit %s: not on the DEM's grid (%s: %d x %d pixels of %g m): resample it "
                "(gdalwarp -te/-tr)", f, dem, o->dem.nx, o->dem.ny, o->dem.gt[1]);
        o->deposit = r.z;
        r.z = NULL;
        gf_raster_free(&r);
        for (size_t i = 0; i < n; ++i)
            if (isnan(o->deposit[i])) o->valid[i] = 0;
        free(f);
    }
    free(td);
    free(demrel);
    free(dem);
}

/*------------------------------------------------------------------- the members --*/

typedef struct calib {
    const config *c;
    const observation *o;
    const char *casedir;
    char *dir, *evals, *templ;
    gf_workers *pool;
    pthread_mutex_t lock;
    size_t done, ran, resumed;
    double t0;
} calib;

static void member_name(const calib *k, size_t index, char *buf, size_t size)
{
    snprintf(buf, size, "%s/eval_%04zu", k->evals, index);
}

#define append gf_append

static double value(const param *p, double u) { return p->lo + (p->hi - p->lo) * u; }

/* the first number of a CSV column */
static double csv_value(const char *file, const char *col)
{
    FILE *f = fopen(file, "r");
    if (!f) return NAN;
    char *h = NULL, *r = NULL;
    size_t hc = 0, rc = 0;
    double v = NAN;
    if (getline(&h, &hc, f) > 0 && getline(&r, &rc, f) > 0) {
        int k = -1, i = 0;
        char *s1 = NULL, *s2 = NULL;
        for (char *t = strtok_r(h, ",\n", &s1); t; t = strtok_r(NULL, ",\n", &s1), ++i)
            if (strcmp(t, col) == 0) k = i;
        i = 0;
        for (char *t = strtok_r(r, ",\n", &s2); t; t = strtok_r(NULL, ",\n", &s2), ++i)
            if (i == k && !gf_parse_number(t, &v)) v = NAN;
    }
    free(h);
    free(r);
    fclose(f);
    return v;
}

/* the scores of a member that ran (0), or -1 with the reason */
/* a member's hazard-map raster NAME (postProcessing/hazardMaps/NAME.tif) on
 * the DEM's grid into *r; -1 and the reason in why (what: its name in the
 * message, hint: how to get it) */
static int member_raster(const char *m, const char *name, const char *what, const char *hint,
                         const observation *o, gf_raster *r, char *why, size_t wsize)
{
    char rel[256];
    snprintf(rel, sizeof rel, "postProcessing/hazardMaps/%s.tif", name);
    char *f = cat(m, rel);
    const gf_status st = gf_raster_read(f, r);
    free(f);
    if (st) {
        snprintf(why, wsize, "no %s raster (%s%s)", what, gf_error_detail(), hint);
        return -1;
    }
    if (!gf_raster_same_grid(r, &o->dem)) {
        gf_raster_free(r);
        snprintf(why, wsize, "its %s raster is not on the DEM's grid", what);
        return -1;
    }
    return 0;
}

static int score(calib *k, const char *m, gf_calib_eval *e, char *why, size_t wsize)
{
    const config *c = k->c;
    const observation *o = k->o;
    const size_t n = (size_t)o->dem.nx * (size_t)o->dem.ny;
    e->scores = (gf_scores){NAN, NAN, NAN, NAN, NAN};
    e->jaccard = NAN;
    gf_raster r;
    if (member_raster(m, "pressurePeak", "peak pressure", "", o, &r, why, wsize)) return -1;
    if (o->mask) {
        gf_outline_score s;
        if (gf_score_outline(n, r.z, c->threshold, o->mask, o->valid, o->cell_area, c->alpha, c->beta, &s)) {
            snprintf(why, wsize, "outline score: %s", gf_error_detail());
            gf_raster_free(&r);
            return -1;
        }
        e->scores.tversky = s.tversky;
        e->jaccard = s.tp + s.fp + s.fn > 0 ? s.tp / (s.tp + s.fp + s.fn) : 0;
    }
    gf_raster_free(&r);
    if (!isnan(o->s_runout)) {
        char *pa = cat(m, "postProcessing/pathAnalysis/pathAnalysis.csv");
        double s = exists(pa) ? csv_value(pa, "sRunout") : NAN;
        if (!exists(pa)) s = 0; /* the path analysis found no cross-section above its
                                 * threshold: the run reaches nothing along the path */
        free(pa);
        if (isnan(s)) {
            snprintf(why, wsize, "no sRunout in postProcessing/pathAnalysis/pathAnalysis.csv");
            return -1;
        }
        gf_score_runout(s, o->s_runout, &e->scores.runout_error);
    }
    if (o->deposit) {
        gf_raster t;
        if (member_raster(m, "thickness", "thickness", "", o, &t, why, wsize)) return -1;
        double rmse = NAN;
        if (gf_score_deposit_rmse(n, t.z, o->deposit, o->valid, c->deposit_threshold, GF_RMSE_UNION, &rmse, NULL)) {
            snprintf(why, wsize, "deposit score: %s", gf_error_detail());
            gf_raster_free(&t);
            return -1;
        }
        gf_raster_free(&t);
        e->scores.rmse = rmse;
    }
    if (o->nfront) {
        gf_raster a;
        if (member_raster(m, "arrivalTime", "arrival-time", "; controlDict peakFields yes", o, &a, why, wsize))
            return -1;
        double *sim = malloc(2 * o->nfront * sizeof *sim), *obs = sim ? sim + o->nfront : NULL;
        size_t nv = 0;
        int st = sim ? 0 : -1;
        for (size_t i = 0; i < o->nfront && !st; ++i) {
            if (gf_front_position(n, a.z, o->cs, o->cl, HALF_WIDTH, o->ft[i], &sim[i])) st = -1;
            else if (isnan(sim[i])) {
                snprintf(why, wsize, "front: no cell reached by %g s", o->ft[i]);
                st = -2;
            }
        }
        if (!st && gf_score_series_rmse(o->nfront, sim, o->fs, &e->scores.series_rmse)) st = -1;
        for (size_t i = 0; i < o->nfront && !st; ++i) {
            if (isnan(o->fv[i])) continue;
            if (gf_front_speed(n, a.z, o->cs, o->cl, HALF_WIDTH, o->ft[i], c->front_window, &sim[nv])) st = -1;
            obs[nv++] = o->fv[i];
        }
        if (!st && nv && gf_score_series_rmse(nv, sim, obs, &e->scores.speed_rmse)) st = -1;
        gf_raster_free(&a);
        free(sim);
        if (st) {
            if (st == -1) snprintf(why, wsize, "front score: %s", gf_error_detail());
            return -1;
        }
    }
    if (gf_loss(&e->scores, &c->w, &e->loss)) {
        snprintf(why, wsize, "loss: %s", gf_error_detail());
        return -1;
    }
    e->ok = 1;
    return 0;
}

/* the result file of a member: "u_1 .. u_d ok loss runout tversky rmse
 * jaccard front speed" (an earlier version's file without the front's two
 * values is read as not observed) */
static int read_result(const char *m, const double *u, size_t d, gf_calib_eval *e)
{
    char *f = cat(m, "result");
    FILE *in = fopen(f, "r");
    free(f);
    if (!in) return 0;
    double v[MAXP + 8];
    int ok = 1;
    size_t got = 0;
    for (size_t j = 0; j < d + 8 && ok; ++j) {
        char t[64];
        const int r = fscanf(in, "%63s", t);
        if (r != 1 && j == d + 6) break; /* the earlier format */
        ok = r == 1 && (gf_parse_number(t, &v[j]) || (strcmp(t, "nan") == 0 && (v[j] = NAN, 1)));
        got += ok;
    }
    fclose(in);
    if (!ok || got < d + 6) return 0;
    if (got < d + 8) v[d + 6] = v[d + 7] = NAN;
    for (size_t j = 0; j < d; ++j)
        if (fabs(v[j] - u[j]) > 1e-12) return 0; /* another point: run it */
    e->ok = v[d] == 1;
    e->loss = v[d + 1];
    e->scores = (gf_scores){v[d + 2], v[d + 3], v[d + 4], v[d + 6], v[d + 7]};
    e->jaccard = v[d + 5];
    return 1;
}

static void write_result(const char *m, const double *u, size_t d, const gf_calib_eval *e)
{
    char *f = cat(m, "result");
    FILE *out = fopen(f, "w");
    if (!out) die("%s: cannot write", f);
    for (size_t j = 0; j < d; ++j) fprintf(out, "%.17g ", u[j]);
    fprintf(out, "%d %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", e->ok, e->loss, e->scores.runout_error,
            e->scores.tversky, e->scores.rmse, e->jaccard, e->scores.series_rmse, e->scores.speed_rmse);
    fclose(out);
    free(f);
}

static const char *phase_name(int phase)
{
    return phase == GF_PHASE_SOBOL    ? "design"
           : phase == GF_PHASE_MORRIS ? "morris"
           : phase == GF_PHASE_REFINE ? "refine"
                                      : "explore";
}

static size_t n_design(const calib *k)
{
    return k->c->plan.n_sobol + (k->c->plan.morris_r ? k->c->plan.morris_r * (k->c->d + 1) : 0);
}

/* a member folder m: the template's copy with the parameters' values x
 * [d] written into its dictionaries; 0, or 1 with the reason */
static int make_member(const calib *k, const char *m, const double *x, char *why, size_t wsize)
{
    const config *c = k->c;
    if (gf_member_copy(k->templ, m, why, wsize)) die("%s", why);
    for (size_t j = 0; j < c->d; ++j) {
        const param *p = &c->p[j];
        char text[2048], *file;
        if (p->release) {
            snprintf(text, sizeof text, "\n// gfCalibrate\nfactor %.17g;\n", x[j]);
            file = cat(m, "system/releaseDict");
        } else {
            gf_override_text(p->entry, x[j], text, sizeof text);
            file = cat(m, p->file);
        }
        const int r = append(file, text);
        if (r) snprintf(why, wsize, "cannot write %s", file);
        free(file);
        if (r) return 1;
    }
    return 0;
}

/* does an evaluation reproduce the observation (the acceptance criteria)? */
static int meets(const calib *k, const gf_calib_eval *e)
{
    const config *c = k->c;
    if (!e->ok) return 0;
    if (k->o->mask && !(e->jaccard >= c->min_jaccard)) return 0;
    if (!isnan(k->o->s_runout) && !(fabs(e->scores.runout_error) <= c->runout_tol)) return 0;
    if (k->o->nfront && !(e->scores.series_rmse <= c->front_tol)) return 0;
    if (k->o->nspeed && !(e->scores.speed_rmse <= c->speed_tol)) return 0;
    if (!k->o->mask && isnan(k->o->s_runout) && !k->o->nfront && !(e->loss <= 1))
        return 0; /* the deposit alone: within its scale */
    return 1;
}

static gf_status evaluate(size_t index, const double *u, size_t d, void *ctx, gf_calib_eval *e)
{
    calib *k = ctx;
    const config *c = k->c;
    char m[4096], why[2048] = "";
    member_name(k, index, m, sizeof m);
    int resumed = read_result(m, u, d, e);
    if (!resumed) {
        double x[MAXP];
        for (size_t j = 0; j < d; ++j) x[j] = value(&c->p[j], u[j]);
        const int bad = make_member(k, m, x, why, sizeof why);
        int ok = 0;
        if (!bad && gf_workers_run(k->pool, m, &ok, why, sizeof why)) die("%s", gf_error_detail());
        *e = (gf_calib_eval){0, NAN, {NAN, NAN, NAN, NAN, NAN}, NAN, 0};
        if (ok && score(k, m, e, why, sizeof why) != 0) e->ok = 0;
        gf_remove_times(m); /* keep the logs, rasters and tables; the fields go */
        write_result(m, u, d, e);
        if (!e->ok) {
            char *f = cat(m, "failure");
            FILE *out = fopen(f, "w");
            if (out) {
                fprintf(out, "%s\n", why);
                fclose(out);
            }
            free(f);
        }
    }
    e->accepted = meets(k, e);
    pthread_mutex_lock(&k->lock);
    ++k->done;
    resumed ? ++k->resumed : ++k->ran;
    printf("eval %4zu %-7s", index,
           index < n_design(k)                               ? (index < c->plan.n_sobol ? "design" : "morris")
           : index < gf_calib_explore_index(&c->plan, 0) ? "refine"
                                                             : "explore");
    for (size_t j = 0; j < d; ++j) printf(" %s %-8.4g", c->p[j].name, value(&c->p[j], u[j]));
    if (e->ok) {
        printf(": loss %.4f", e->loss);
        if (!isnan(e->scores.runout_error)) printf(", runout %+.1f m", e->scores.runout_error);
        if (!isnan(e->jaccard)) printf(", Jaccard %.3f", e->jaccard);
        if (!isnan(e->scores.rmse)) printf(", deposit RMSE %.3f m", e->scores.rmse);
        if (!isnan(e->scores.series_rmse)) printf(", front RMSE %.1f m", e->scores.series_rmse);
        if (!isnan(e->scores.speed_rmse)) printf(", front speed RMSE %.2f m/s", e->scores.speed_rmse);
    } else {
        char *f = cat(m, "failure");
        FILE *in = fopen(f, "r");
        char line[512] = "";
        if (in) {
            if (!fgets(line, sizeof line, in)) line[0] = '\0';
            fclose(in);
        }
        line[strcspn(line, "\n")] = '\0';
        printf(": FAILED: %s", line);
        free(f);
    }
    printf("%s\n", resumed ? " (resumed)" : "");
    fflush(stdout);
    pthread_mutex_unlock(&k->lock);
    return GF_SUCCESS;
}

/* every parameter's entry must exist in the case's dictionary (a typo is
 * refused, not ignored): checked before anything is written */
static void check_entries(const char *casedir, const config *c)
{
    for (size_t j = 0; j < c->d; ++j) {
        if (c->p[j].release) continue;
        char *f = cat(casedir, c->p[j].file);
        char *entry = strdup(c->p[j].entry);
        char *fd[] = {"foamDictionary", "-entry", entry, "-value", f, NULL};
        char *log = NULL;
        if (asprintf(&log, "/tmp/gfCalibrate-check.%ld", (long)getpid()) < 0) die("out of memory");
        const int bad = !exists(f) || run_prog(fd, log) != 0;
        unlink(log);
        if (bad) die("parameter %s: %s has no entry %s (%s)", c->p[j].name, c->p[j].file, c->p[j].entry, c->path);
        free(f), free(log), free(entry);
    }
}

/* a folder name the OpenFOAM runs can take: OpenFOAM v1912 drops blanks and
 * quotes from file names (fileName::stripInvalid) */
static void check_path(const char *what, const char *path)
{
    if (!gf_path_foam_safe(path))
        die("%s '%s': a blank or a quote in the path; OpenFOAM drops them from file names: move or rename it",
            what, path);
}

/* the template: the case's system/, 0/ and constant/ (meshes linked), its
 * controls set for members */
static void make_template(calib *k)
{
    const config *c = k->c;
    if (exists(k->templ)) return;
    char *tmp = NULL;
    if (asprintf(&tmp, "%s.tmp", k->templ) < 0) die("out of memory");
    char *rm[] = {"rm", "-rf", tmp, NULL};
    run_prog(rm, NULL);
    gf_case_controls ctl;
    char err[2048];
    if (gf_member_template(k->casedir, tmp, &ctl, err, sizeof err)) die("%s", err);
    const int release_set = ctl.sets_release, has_pa = ctl.has_path_analysis;
    char *cd = cat(tmp, "system/controlDict");
    for (size_t j = 0; j < c->d; ++j)
        if (c->p[j].release && !release_set)
            die("parameter %s (release factor): the case's system/controlDict does not set the release at the start "
                "(setFields (releaseDict);), so a release factor cannot act",
                c->p[j].name);
    char text[4096];
    snprintf(text, sizeof text,
             "\n// gfCalibrate: the members' controls\nwriteInterval %s;\npeakFields yes;\nhazardMaps yes;\n%s\n",
             ctl.end_time,
             has_pa ? "pathAnalysis { plots no; }"
                    : (!isnan(k->o->s_runout) ? "pathAnalysis { path \"Inputs/LINES/path_aimec.shp\"; plots no; }" : ""));
    if (append(cd, text)) die("cannot write %s", cd);
    if (rename(tmp, k->templ)) die("cannot rename %s", tmp);
    free(tmp), free(cd);
}

/*-------------------------------------------------------------------- -observe --*/

static void write_point_shp(const char *path, const char *wkt, double x, double y)
{
    GDALDriverH drv = GDALGetDriverByName("ESRI Shapefile");
    if (!drv) die("GDAL lacks the ESRI Shapefile driver");
    GDALDatasetH ds = GDALCreate(drv, path, 0, 0, 0, GDT_Unknown, NULL);
    if (!ds) die("%s: cannot write", path);
    OGRSpatialReferenceH srs = *wkt ? OSRNewSpatialReference(wkt) : NULL;
    OGRLayerH L = GDALDatasetCreateLayer(ds, "runout", srs, wkbPoint, NULL);
    OGRFeatureH f = OGR_F_Create(OGR_L_GetLayerDefn(L));
    OGRGeometryH g = OGR_G_CreateGeometry(wkbPoint);
    OGR_G_SetPoint_2D(g, 0, x, y);
    OGR_F_SetGeometryDirectly(f, g);
    if (OGR_L_CreateFeature(L, f) != OGRERR_NONE) die("%s: cannot write the point", path);
    OGR_F_Destroy(f);
    if (srs) OSRDestroySpatialReference(srs);
    GDALClose(ds);
}

static void write_outline_shp(const char *path, const gf_raster *grid, const unsigned char *mask)
{
    GDALDriverH mem = GDALGetDriverByName("MEM"), drv = GDALGetDriverByName("ESRI Shapefile");
    if (!mem || !drv) die("GDAL lacks the MEM or ESRI Shapefile driver");
    GDALDatasetH r = GDALCreate(mem, "", grid->nx, grid->ny, 1, GDT_Byte, NULL);
    GDALSetGeoTransform(r, (double *)grid->gt);
    GDALRasterBandH b = GDALGetRasterBand(r, 1);
    if (GDALRasterIO(b, GF_Write, 0, 0, grid->nx, grid->ny, (void *)mask, grid->nx, grid->ny, GDT_Byte, 0, 0) != CE_None)
        die("outline: cannot fill the mask");
    GDALDatasetH ds = GDALCreate(drv, path, 0, 0, 0, GDT_Unknown, NULL);
    if (!ds) die("%s: cannot write", path);
    OGRSpatialReferenceH srs = *grid->wkt ? OSRNewSpatialReference(grid->wkt) : NULL;
    OGRLayerH L = GDALDatasetCreateLayer(ds, "outline", srs, wkbPolygon, NULL);
    OGRFieldDefnH fd = OGR_Fld_Create("affected", OFTInteger);
    OGR_L_CreateField(L, fd, 1);
    OGR_Fld_Destroy(fd);
    /* the mask band as its own mask: only the affected pixels become polygons */
    if (GDALPolygonize(b, b, L, 0, NULL, NULL, NULL) != CE_None) die("%s: GDALPolygonize failed", path);
    if (srs) OSRDestroySpatialReference(srs);
    GDALClose(ds);
    GDALClose(r);
}

/* -observe's front.csv: the run's front (gf_front_position on its
 * arrival-time map) at the times given ("T1 T2 ...") or at 6 times evenly
 * spread over the front's travel, the point the furthest reached cell's
 * centre, the speed the central difference over 2 s */
static void observe_front(const char *run, const char *out, const char *times)
{
    char *at = cat(run, "postProcessing/hazardMaps/arrivalTime.tif");
    gf_raster a;
    if (gf_raster_read(at, &a)) {
        if (times) die("-frontTimes: %s: %s (a run with peakFields yes)", at, gf_error_detail());
        printf("front: no arrival-time raster %s: no front.csv\n", at);
        free(at);
        return;
    }
    char *pf = cat(run, "Inputs/LINES/path_aimec.shp");
    size_t np;
    double *xy;
    if (gf_path_read(pf, &np, &xy)) die("%s: %s", pf, gf_error_detail());
    const size_t n = (size_t)a.nx * (size_t)a.ny;
    double *cs, *cl, tmax = 0;
    cell_path_coords(&a, np, xy, &cs, &cl);
    for (size_t i = 0; i < n; ++i)
        if (isfinite(a.z[i]) && fabs(cl[i]) <= HALF_WIDTH) tmax = fmax(tmax, a.z[i]);
    double t[64];
    size_t nt = 0;
    if (times) {
        char *copy = strdup(times), *save = NULL;
        for (char *w = strtok_r(copy, " ,", &save); w; w = strtok_r(NULL, " ,", &save)) {
            if (nt == 64) die("-frontTimes: at most 64 times");
            if (!gf_parse_number(w, &t[nt]) || !(t[nt] >= 0 && t[nt] <= 1e6)) die("-frontTimes: '%s': seconds in [0, 1e6]", w);
            ++nt;
        }
        free(copy);
        if (!nt) die("-frontTimes '%s': no time", times);
    } else {
        /* the time the front has done 99 % of its travel along the path,
         * split in 6 (the last of them at that time) */
        double s0, s1, t99 = tmax;
        if (gf_front_position(n, a.z, cs, cl, HALF_WIDTH, 0, &s0) ||
            gf_front_position(n, a.z, cs, cl, HALF_WIDTH, tmax, &s1))
            die("front: %s", gf_error_detail());
        if (isnan(s0) || isnan(s1)) die("front: %s has no arrival at 0 s within %g m of the path", at, HALF_WIDTH);
        for (size_t i = 0; i < n; ++i)
            if (isfinite(a.z[i]) && fabs(cl[i]) <= HALF_WIDTH && cs[i] >= s0 + 0.99 * (s1 - s0)) t99 = fmin(t99, a.z[i]);
        for (nt = 0; nt < 6; ++nt) t[nt] = round(10.0 * (double)(nt + 1) * t99 / 6.0) / 10.0;
    }
    char *csv = cat(out, "front.csv");
    FILE *f = fopen(csv, "w");
    if (!f) die("%s: cannot write", csv);
    fprintf(f, "time,x,y,speed\n");
    for (size_t k = 0; k < nt; ++k) {
        double sf, v;
        if (gf_front_position(n, a.z, cs, cl, HALF_WIDTH, t[k], &sf) ||
            gf_front_speed(n, a.z, cs, cl, HALF_WIDTH, t[k], 2.0, &v))
            die("front: %s", gf_error_detail());
        if (isnan(sf)) die("front: nothing reached by %g s in %s", t[k], at);
        size_t best = n;
        for (size_t i = 0; i < n && best == n; ++i)
            if (isfinite(a.z[i]) && a.z[i] <= t[k] && fabs(cl[i]) <= HALF_WIDTH && cs[i] == sf) best = i;
        double x, y;
        gf_raster_centre(&a, (int)(best % (size_t)a.nx), (int)(best / (size_t)a.nx), &x, &y);
        fprintf(f, "%.10g,%.3f,%.3f,%.4f\n", t[k], x, y, v);
    }
    fclose(f);
    printf("front %s: %zu positions and speeds along the path, %g to %g s (the last arrival within %g m of the path at "
           "%.1f s)\n", csv, nt, t[0], t[nt - 1], HALF_WIDTH, tmax);
    gf_raster_free(&a);
    free(at), free(pf), free(xy), free(cs), free(cl), free(csv);
}

static int observe(int argc, char **argv)
{
    const char *run = NULL, *out = NULL, *front_times = NULL;
    double threshold = 1, shift = 0, rshift = 0;
    for (int i = 2; i < argc; ++i) {
        if (strcmp(argv[i], "-threshold") == 0 && i + 1 < argc) {
            if (!gf_parse_number(argv[++i], &threshold) || !(threshold >= 0)) die("-threshold %s: a number >= 0 [kPa]", argv[i]);
        } else if (strcmp(argv[i], "-shift") == 0 && i + 1 < argc) {
            if (!gf_parse_number(argv[++i], &shift) || shift != floor(shift) || fabs(shift) > 1000)
                die("-shift %s: a whole number of pixels in [-1000, 1000]", argv[i]);
        } else if (strcmp(argv[i], "-frontTimes") == 0 && i + 1 < argc) {
            front_times = argv[++i];
        } else if (strcmp(argv[i], "-runoutShift") == 0 && i + 1 < argc) {
            if (!gf_parse_number(argv[++i], &rshift) || fabs(rshift) > 1e5) die("-runoutShift %s: metres in [-1e5, 1e5]", argv[i]);
        } else if (!run) {
            run = argv[i];
        } else if (!out) {
            out = argv[i];
        } else {
            die("-observe: unexpected argument %s", argv[i]);
        }
    }
    if (!run || !out)
        die("usage: gfCalibrate -observe RUN OUTDIR [-threshold KPA] [-shift CELLS] [-runoutShift M] [-frontTimes \"T1 "
            "T2 ...\"]");
    GDALAllRegister();
    mkdir(out, 0755);
    char *ppr = cat(run, "postProcessing/hazardMaps/pressurePeak.tif");
    gf_raster r;
    if (gf_raster_read(ppr, &r)) die("%s: %s (run the case with hazardMaps yes)", ppr, gf_error_detail());
    const size_t n = (size_t)r.nx * (size_t)r.ny;
    unsigned char *mask = calloc(n, 1);
    size_t count = 0;
    const long s = (long)shift;
    for (long row = 0; row < r.ny; ++row)
        for (long q = 0; q < r.nx; ++q) {
            const long from = q - s;
            if (from < 0 || from >= r.nx) continue;
            const double v = r.z[(size_t)row * (size_t)r.nx + (size_t)from];
            mask[(size_t)row * (size_t)r.nx + (size_t)q] = v > threshold;
            count += v > threshold;
        }
    if (count == 0) die("%s: no pixel above %g kPa: nothing observed", ppr, threshold);
    char *shp = cat(out, "outline.shp");
    write_outline_shp(shp, &r, mask);
    printf("outline %s: %zu pixels above %g kPa%s\n", shp, count, threshold, s ? " (shifted)" : "");
    char *pa = cat(run, "postProcessing/pathAnalysis/pathAnalysis.csv");
    double sr = csv_value(pa, "sRunout"), x = csv_value(pa, "xRunout"), y = csv_value(pa, "yRunout");
    if (isnan(x) || isnan(y)) die("%s: no xRunout, yRunout (run the path analysis)", pa);
    if (rshift != 0) {
        char *pf = cat(run, "Inputs/LINES/path_aimec.shp");
        size_t np;
        double *xy;
        if (gf_path_read(pf, &np, &xy)) die("%s: %s", pf, gf_error_detail());
        /* move the point by rshift along the path's direction there */
        double s0, l;
        gf_path_locate(np, xy, x, y, &s0, &l);
        double acc = 0;
        for (size_t i = 0; i + 1 < np; ++i) {
            const double dx = xy[2 * i + 2] - xy[2 * i], dy = xy[2 * i + 3] - xy[2 * i + 1], len = hypot(dx, dy);
            if (acc + len >= s0 || i + 2 == np) {
                x += rshift * dx / len;
                y += rshift * dy / len;
                break;
            }
            acc += len;
        }
        free(xy);
        free(pf);
    }
    char *pt = cat(out, "runout.shp");
    write_point_shp(pt, r.wkt, x, y);
    printf("runout point %s: (%.2f, %.2f), the run's sRunout %.2f m%s\n", pt, x, y, sr, rshift != 0 ? " (moved)" : "");
    char *th = cat(run, "postProcessing/hazardMaps/thickness.tif");
    gf_raster t;
    if (gf_raster_read(th, &t) == GF_SUCCESS) {
        char *dep = cat(out, "deposit.tif");
        if (gf_raster_write(dep, "GTiff", &t, t.z)) die("%s: %s", dep, gf_error_detail());
        printf("deposit %s: the thickness at the run's end\n", dep);
        gf_raster_free(&t);
        free(dep);
    }
    observe_front(run, out, front_times);
    gf_raster_free(&r);
    free(mask), free(ppr), free(shp), free(pa), free(pt), free(th);
    return 0;
}

/*--------------------------------------------------------------------- analysis --*/

static void write_outline_comparison(const calib *k, const char *m, const char *out)
{
    const observation *o = k->o;
    if (!o->mask) return;
    char *ppr = cat(m, "postProcessing/hazardMaps/pressurePeak.tif");
    gf_raster r;
    if (gf_raster_read(ppr, &r)) {
        free(ppr);
        return;
    }
    const size_t n = (size_t)r.nx * (size_t)r.ny;
    double *cls = malloc(n * sizeof *cls);
    for (size_t i = 0; i < n; ++i) {
        const int s = r.z[i] > k->c->threshold, ob = o->mask[i];
        cls[i] = !o->valid[i] || (!s && !ob) ? NAN : s && ob ? 1 : s ? 2 : 3;
    }
    if (gf_raster_write(out, "GTiff", &r, cls)) fprintf(stderr, "%s: %s\n", prog, gf_error_detail());
    free(cls);
    gf_raster_free(&r);
    free(ppr);
}

/* the loss over a pair of parameters: the evaluations, the emulator's
 * contours, the ridge and the accepted points (gnuplot) */
static void loss_picture(const calib *k, const gf_calib_run *run, const int *accepted, const gf_emulator *em,
                         int have_em, size_t a, size_t b, size_t best)
{
    const config *c = k->c;
    const size_t d = run->d;
    char name[256];
    snprintf(name, sizeof name, "loss_%s_%s", c->p[a].name, c->p[b].name);
    char *dat = NULL, *gp = NULL, *png = NULL, *grid = NULL;
    if (asprintf(&dat, "%s/%s.dat", k->dir, name) < 0 || asprintf(&gp, "%s/%s.gp", k->dir, name) < 0 ||
        asprintf(&png, "%s/%s.png", k->dir, name) < 0 || asprintf(&grid, "%s/%s.grid", k->dir, name) < 0)
        die("out of memory");
    FILE *f = fopen(dat, "w");
    if (!f) return;
    for (size_t i = 0; i < run->n; ++i)
        if (run->ev[i].ok)
            fprintf(f, "%.9g %.9g %.9g %d\n", value(&c->p[a], run->u[i * d + a]), value(&c->p[b], run->u[i * d + b]),
                    run->ev[i].loss, accepted[i]);
    fclose(f);
    /* the emulator's contours where it is a bowl around the best point (every
     * curvature > 0) that fits the loss (R2 >= 0.95); a saddle or a poor fit
     * says the loss has a curved valley or several, which the evaluations
     * show better */
    int bowl = have_em && em->r2 >= 0.95; /* a fit that describes the loss */
    for (size_t kk = 0; have_em && kk < d; ++kk) bowl &= em->curvature[kk] > 0;
    int contours = 0;
    if (bowl) {
        FILE *g = fopen(grid, "w");
        if (g) {
            double *u = malloc(d * sizeof *u);
            for (int i = 0; i <= 60; ++i) {
                for (int j = 0; j <= 60; ++j) {
                    memcpy(u, run->u + best * d, d * sizeof *u);
                    u[a] = i / 60.0;
                    u[b] = j / 60.0;
                    fprintf(g, "%.9g %.9g %.9g\n", value(&c->p[a], u[a]), value(&c->p[b], u[b]), gf_emulator_eval(em, u));
                }
                fprintf(g, "\n");
            }
            free(u);
            fclose(g);
            contours = 1;
        }
    }
    f = fopen(gp, "w");
    if (!f) return;
    fprintf(f,
            "set terminal pngcairo size 900,760 font ',11'\nset output '%s'\n"
            "set xlabel '%s'\nset ylabel '%s'\nset xrange [%g:%g]\nset yrange [%g:%g]\n"
            "set title 'loss over %s and %s (others at the best set)'\nset key outside bottom center horizontal\n"
            "set cblabel 'loss'\nset palette rgb 33,13,10\n",
            png, c->p[a].name, c->p[b].name, c->p[a].lo, c->p[a].hi, c->p[b].lo, c->p[b].hi, c->p[a].name,
            c->p[b].name);
    if (contours) {
        fprintf(f, "set contour base\nunset surface\nset view map\nset cntrparam levels auto 8\n"
                   "set table '%s.cnt'\nsplot '%s' using 1:2:3 notitle\nunset table\nunset contour\n",
                gp, grid);
    }
    fprintf(f, "plot ");
    if (contours) fprintf(f, "'%s.cnt' using 1:2 with lines lc rgb '#888888' title 'emulator contours', ", gp);
    fprintf(f, "'%s' using 1:2:3 with points pt 7 ps 1 lc palette title 'evaluations', "
               "'' using ($4 > 0 ? $1 : 1/0):2 with points pt 6 ps 2 lc rgb 'black' title 'reproduce the observation', "
               "'-' using 1:2 with points pt 3 ps 3 lw 2 lc rgb 'red' title 'best'",
            dat);
    int ridge = have_em && em->n_ridge > 0 && isfinite(em->ridge_t_min) && isfinite(em->ridge_t_max);
    if (ridge) fprintf(f, ", '-' using 1:2 with lines lw 2 dt 2 lc rgb 'blue' title 'ridge (equal loss)'");
    fprintf(f, "\n%.9g %.9g\ne\n", value(&c->p[a], run->u[best * d + a]), value(&c->p[b], run->u[best * d + b]));
    if (ridge) {
        /* the ridge line: ridge_point + t direction_param[smallest curvature] */
        const size_t kk = d - 1;
        for (int s = 0; s <= 1; ++s) {
            const double t = s ? em->ridge_t_max : em->ridge_t_min;
            fprintf(f, "%.9g %.9g\n", em->ridge_point[a] + t * em->direction_param[kk * d + a],
                    em->ridge_point[b] + t * em->direction_param[kk * d + b]);
        }
        fprintf(f, "e\n");
    }
    fclose(f);
    char *argv[] = {"gnuplot", gp, NULL};
    char *log = cat(k->dir, "log.gnuplot");
    if (run_prog(argv, log) != 0) fprintf(stderr, "%s: gnuplot %s failed (%s)\n", prog, gp, log);
    free(log), free(dat), free(gp), free(png), free(grid);
}

static int analyse(calib *k, const gf_calib_run *run, double wall)
{
    const config *c = k->c;
    const size_t d = run->d, n = run->n;
    char *csv = cat(k->dir, "evaluations.csv");
    FILE *f = fopen(csv, "w");
    if (!f) die("%s: cannot write", csv);
    fprintf(f, "evaluation,phase,refinement");
    for (size_t j = 0; j < d; ++j) fprintf(f, ",%s", c->p[j].name);
    fprintf(f, ",status,loss,runoutError_m,jaccard,tversky,depositRmse_m,frontRmse_m,frontSpeedRmse_m_s,member\n");
    size_t nok = 0, nfail = 0, nused = 0, best = (size_t)-1;
    for (size_t i = 0; i < n; ++i) {
        char m[4096];
        member_name(k, i, m, sizeof m);
        char *res = cat(m, "result");
        const int ran = exists(res);
        free(res);
        if (!ran) continue; /* a refinement that stopped early leaves its indices unused */
        ++nused;
        const gf_calib_eval *e = &run->ev[i];
        e->ok ? ++nok : ++nfail;
        if (e->ok && (best == (size_t)-1 || e->loss < run->ev[best].loss)) best = i;
        fprintf(f, "%zu,%s,%d", i, phase_name(run->phase[i]), run->start[i]);
        for (size_t j = 0; j < d; ++j) fprintf(f, ",%.9g", value(&c->p[j], run->u[i * d + j]));
        fprintf(f, ",%s,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,evals/eval_%04zu\n", e->ok ? "ok" : "failed", e->loss,
                e->scores.runout_error, e->jaccard, e->scores.tversky, e->scores.rmse, e->scores.series_rmse,
                e->scores.speed_rmse, i);
    }
    fclose(f);
    if (best == (size_t)-1) die("every evaluation failed (their folders: %s)", k->evals);

    /* the verdict, and the evaluations that reproduce the observation */
    double *loss = malloc(nused * sizeof *loss), *jac = malloc(nused * sizeof *jac), *rerr = malloc(nused * sizeof *rerr);
    size_t *idx = malloc(nused * sizeof *idx);
    size_t m = 0;
    for (size_t i = 0; i < n; ++i)
        if (run->ev[i].ok) {
            idx[m] = i;
            loss[m] = run->ev[i].loss;
            jac[m] = run->ev[i].jaccard;
            rerr[m] = run->ev[i].scores.runout_error;
            ++m;
        }
    gf_reach_criteria crit = {NAN, k->o->mask ? c->min_jaccard : NAN, !isnan(k->o->s_runout) ? c->runout_tol : NAN};
    if (!k->o->mask && isnan(k->o->s_runout)) crit.max_loss = 1; /* the deposit (or front) only: within one scale */
    gf_reach_result verdict;
    if (gf_reach_verdict(m, loss, k->o->mask ? jac : NULL, isnan(k->o->s_runout) ? NULL : rerr, &crit, &verdict))
        die("verdict: %s", gf_error_detail());
    if (k->o->nfront) {
        /* the front's tolerances too (meets): the evaluations that meet
         * every criterion, and the best front of them all */
        size_t nmeet = 0, bf = idx[0];
        for (size_t q = 0; q < m; ++q) {
            nmeet += run->ev[idx[q]].accepted != 0;
            if (run->ev[idx[q]].scores.series_rmse < run->ev[bf].scores.series_rmse) bf = idx[q];
        }
        const int others_met = verdict.verdict == GF_REACHABLE;
        verdict.n_meeting = nmeet;
        verdict.verdict = nmeet ? GF_REACHABLE : GF_UNREACHABLE;
        if (nmeet)
            snprintf(verdict.reason, sizeof verdict.reason, "reachable: %zu of %zu evaluations meet every criterion",
                     nmeet, m);
        else if (!others_met && run->ev[bf].scores.series_rmse <= c->front_tol &&
                 !(run->ev[bf].scores.speed_rmse > c->speed_tol))
            ; /* the front is met: the other criteria's reason stands */
        else
            snprintf(verdict.reason, sizeof verdict.reason,
                     "unreachable: none of %zu evaluations meets every criterion; the best front (evaluation %zu): "
                     "position RMSE %.1f m (tolerance %g m), speed RMSE %.2f m/s (tolerance %g m/s)",
                     m, bf, run->ev[bf].scores.series_rmse, c->front_tol, run->ev[bf].scores.speed_rmse, c->speed_tol);
    }
    int *accepted = calloc(n, sizeof *accepted);
    double lo[MAXP], hi[MAXP];
    size_t nacc = 0;
    for (size_t j = 0; j < d; ++j) lo[j] = INFINITY, hi[j] = -INFINITY;
    for (size_t q = 0; q < m; ++q) {
        if (!run->ev[idx[q]].accepted) continue; /* the criteria of the verdict (meets) */
        accepted[idx[q]] = 1;
        ++nacc;
        for (size_t j = 0; j < d; ++j) {
            const double v = value(&c->p[j], run->u[idx[q] * d + j]);
            lo[j] = fmin(lo[j], v);
            hi[j] = fmax(hi[j], v);
        }
    }

    /* the emulator around the best point: the ridge */
    gf_emulator em;
    memset(&em, 0, sizeof em);
    const size_t ncoef = 1 + d + d * (d + 1) / 2;
    double *uu = malloc(m * d * sizeof *uu), plo[MAXP], phi[MAXP];
    for (size_t q = 0; q < m; ++q) memcpy(uu + q * d, run->u + idx[q] * d, d * sizeof *uu);
    for (size_t j = 0; j < d; ++j) plo[j] = c->p[j].lo, phi[j] = c->p[j].hi;
    size_t nfit = 3 * ncoef > 12 ? 3 * ncoef : 12;
    if (nfit > m) nfit = m;
    int have_em = m >= ncoef + 1 && gf_emulator_fit(m, d, uu, loss, nfit, plo, phi, GF_RIDGE_FRACTION, &em) == GF_SUCCESS;
    char emwhy[512] = "";
    if (!have_em) snprintf(emwhy, sizeof emwhy, "%s", m < ncoef + 1 ? "too few evaluations" : gf_error_detail());

    /* Morris sensitivities of the loss, the runout error and the outline */
    /* (and the front's position and speed RMSE when a front is observed) */
    enum { NY = 5 };
    double mu_star[NY * MAXP], sigma[NY * MAXP], mu[NY * MAXP];
    int have_morris = 0;
    if (run->n_morris) {
        const size_t r = run->n_morris / (d + 1);
        double *y = malloc(run->n_morris * NY * sizeof *y);
        int all_ok = 1;
        for (size_t i = 0; i < run->n_morris; ++i) {
            const gf_calib_eval *e = &run->ev[run->n_sobol + i];
            all_ok &= e->ok;
            y[NY * i] = e->loss;
            y[NY * i + 1] = isnan(e->scores.runout_error) ? 0 : e->scores.runout_error;
            y[NY * i + 2] = isnan(e->jaccard) ? 0 : 1 - e->jaccard;
            y[NY * i + 3] = isnan(e->scores.series_rmse) ? 0 : e->scores.series_rmse;
            y[NY * i + 4] = isnan(e->scores.speed_rmse) ? 0 : e->scores.speed_rmse;
        }
        have_morris = all_ok && gf_morris_effects(r, d, run->u + run->n_sobol * d, y, NY, mu, mu_star, sigma) == GF_SUCCESS;
        free(y);
    }

    /* best/: the best evaluation's case */
    char bm[4096];
    member_name(k, best, bm, sizeof bm);
    char *bestdir = cat(k->dir, "best");
    char *rm[] = {"rm", "-rf", bestdir, NULL}, *cp[] = {"cp", "-a", bm, bestdir, NULL};
    run_prog(rm, NULL);
    if (run_prog(cp, NULL)) fprintf(stderr, "%s: cannot copy %s to %s\n", prog, bm, bestdir);
    char *cmp = cat(k->dir, "bestOutline.tif");
    write_outline_comparison(k, bm, cmp);
    /* the best run's report maps with the observed outline and runout point
     * (gfReportMaps -observed): best/postProcessing/hazardMaps/report/ */
    {
        char *obs = NULL, *olp = NULL, *ptp = NULL;
        if (c->outline) olp = c->outline[0] == '/' ? strdup(c->outline) : cat(k->casedir, c->outline);
        if (c->runout_point) ptp = c->runout_point[0] == '/' ? strdup(c->runout_point) : cat(k->casedir, c->runout_point);
        if (asprintf(&obs, "%s,%s", olp ? olp : "", ptp ? ptp : "") < 0) die("out of memory");
        char *log = cat(k->dir, "log.gfReportMaps");
        char *rmaps[8];
        int a = 0;
        rmaps[a++] = "gfReportMaps";
        if (olp || ptp) {
            rmaps[a++] = "-observed";
            rmaps[a++] = obs;
        }
        rmaps[a++] = "-title";
        rmaps[a++] = "best run of the back-calculation";
        rmaps[a++] = bestdir;
        rmaps[a] = NULL;
        unlink(log);
        if (run_prog(rmaps, log) != 0)
            fprintf(stderr, "%s: the best run's report maps failed (%s); its rasters are in %s\n", prog, log, bestdir);
        free(obs), free(olp), free(ptp), free(log);
    }

    for (size_t a = 0; a < d; ++a)
        for (size_t b = a + 1; b < d; ++b) loss_picture(k, run, accepted, &em, have_em, a, b, best);

    /* parameters.csv and summary.txt */
    char *pc = cat(k->dir, "parameters.csv");
    f = fopen(pc, "w");
    if (!f) die("%s: cannot write", pc);
    fprintf(f, "parameter,best,acceptedMin,acceptedMax,rangeMin,rangeMax,identifiable\n");
    int ridge_param[MAXP] = {0};
    if (have_em && em.n_ridge > 0)
        for (size_t kk = 0; kk < d; ++kk)
            if (em.ridge[kk])
                for (size_t j = 0; j < d; ++j) ridge_param[j] |= fabs(em.direction[kk * d + j]) > 0.3;
    /* the trade-off among the runs that reproduce the observation: their
     * correlation per pair of parameters (|r| >= 0.7: raising one and
     * moving the other with it reproduces the event as well) */
    double corr[MAXP * MAXP];
    int tradeoff[MAXP];
    for (size_t j = 0; j < d; ++j) tradeoff[j] = -1;
    for (size_t a = 0; a < d; ++a)
        for (size_t b = 0; b < d; ++b) {
            double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
            for (size_t i = 0; i < n; ++i) {
                if (!accepted[i]) continue;
                const double x = run->u[i * d + a], y = run->u[i * d + b];
                sa += x, sb += y, saa += x * x, sbb += y * y, sab += x * y;
            }
            const double na = (double)nacc, va = saa - sa * sa / na, vb = sbb - sb * sb / na;
            corr[a * d + b] = nacc >= 3 && va > 0 && vb > 0 ? (sab - sa * sb / na) / sqrt(va * vb) : NAN;
            if (a != b && fabs(corr[a * d + b]) >= 0.7 && tradeoff[a] < 0) tradeoff[a] = (int)b;
        }
    const char *ident[MAXP];
    for (size_t j = 0; j < d; ++j) ident[j] = ridge_param[j] ? "ridge" : tradeoff[j] >= 0 ? "tradeoff" : "yes";
    for (size_t j = 0; j < d; ++j)
        fprintf(f, "%s,%.9g,%.9g,%.9g,%.9g,%.9g,%s\n", c->p[j].name, value(&c->p[j], run->u[best * d + j]),
                nacc ? lo[j] : NAN, nacc ? hi[j] : NAN, c->p[j].lo, c->p[j].hi, ident[j]);
    fclose(f);

    char *sp = cat(k->dir, "summary.txt");
    f = fopen(sp, "w");
    if (!f) die("%s: cannot write", sp);
    for (int pass = 0; pass < 2; ++pass) {
        FILE *o = pass ? stdout : f;
        fprintf(o, "gfCalibrate %s: %s\n", GF_VERSION_STRING, k->casedir);
        fprintf(o, "evaluations: %zu (%zu ok, %zu failed; %zu run now, %zu read from an earlier run) in %.1f s wall "
                   "on %zu workers",
                nused, nok, nfail, k->ran, k->resumed, wall, k->c->plan.threads);
        if (k->ran > 0) fprintf(o, ": %.1f evaluations per minute", 60.0 * (double)k->ran / wall);
        fprintf(o, "\n");
        fprintf(o, "verdict: %s: %s\n", verdict.verdict == GF_REACHABLE ? "REACHABLE" : "UNREACHABLE", verdict.reason);
        const gf_calib_eval *b = &run->ev[best];
        fprintf(o, "best evaluation %zu (%s): loss %.4f", best, phase_name(run->phase[best]), b->loss);
        if (!isnan(b->scores.runout_error)) fprintf(o, ", runout error %+.1f m", b->scores.runout_error);
        if (!isnan(b->jaccard)) fprintf(o, ", Jaccard %.3f, Tversky %.3f", b->jaccard, b->scores.tversky);
        if (!isnan(b->scores.rmse)) fprintf(o, ", deposit RMSE %.3f m", b->scores.rmse);
        if (!isnan(b->scores.series_rmse)) fprintf(o, ", front RMSE %.1f m", b->scores.series_rmse);
        if (!isnan(b->scores.speed_rmse)) fprintf(o, ", front speed RMSE %.2f m/s", b->scores.speed_rmse);
        fprintf(o, "\n\n%-16s %12s %27s %25s %s\n", "parameter", "best", "reproduce the observation", "design range",
                "constrained");
        for (size_t j = 0; j < d; ++j) {
            char acc[64] = "none";
            if (nacc) snprintf(acc, sizeof acc, "%.4g .. %.4g", lo[j], hi[j]);
            char con[160] = "yes";
            if (ridge_param[j])
                snprintf(con, sizeof con, "no: on a ridge");
            else if (tradeoff[j] >= 0)
                snprintf(con, sizeof con, "with %s (r = %+.2f)", c->p[tradeoff[j]].name, corr[j * d + (size_t)tradeoff[j]]);
            fprintf(o, "%-16s %12.5g %27s %12.4g .. %-10.4g %s\n", c->p[j].name, value(&c->p[j], run->u[best * d + j]),
                    acc, c->p[j].lo, c->p[j].hi, con);
        }
        for (size_t a2 = 0; a2 < d; ++a2)
            for (size_t b2 = a2 + 1; b2 < d; ++b2)
                if (fabs(corr[a2 * d + b2]) >= 0.7)
                    fprintf(o, "trade-off: %s and %s correlate with r = %+.2f among the runs that reproduce the "
                               "observation: %s one with the other reproduces the event as well; the observation "
                               "constrains their combination, not each\n",
                            c->p[a2].name, c->p[b2].name, corr[a2 * d + b2], corr[a2 * d + b2] > 0 ? "raising" : "lowering");
        {
            char crit_text[512] = "";
            size_t len = 0;
            if (k->o->mask) len += (size_t)snprintf(crit_text + len, sizeof crit_text - len, ", Jaccard >= %g", c->min_jaccard);
            if (!isnan(k->o->s_runout))
                len += (size_t)snprintf(crit_text + len, sizeof crit_text - len, ", |runout error| <= %g m", c->runout_tol);
            if (k->o->nfront)
                len += (size_t)snprintf(crit_text + len, sizeof crit_text - len, ", front RMSE <= %g m", c->front_tol);
            if (k->o->nspeed)
                len += (size_t)snprintf(crit_text + len, sizeof crit_text - len, ", front speed RMSE <= %g m/s",
                                        c->speed_tol);
            if (!k->o->mask && isnan(k->o->s_runout) && !k->o->nfront)
                len += (size_t)snprintf(crit_text + len, sizeof crit_text - len, ", loss <= 1");
            fprintf(o, "(%zu evaluations reproduce the observation: %s; the range is theirs)\n", nacc,
                    len > 2 ? crit_text + 2 : "");
        }
        if (have_em) {
            fprintf(o, "\nemulator (quadratic, %zu evaluations nearest the best, R2 %.3f): curvatures", em.n_fit, em.r2);
            for (size_t kk = 0; kk < d; ++kk) fprintf(o, " %.4g", em.curvature[kk]);
            fprintf(o, "\n");
            if (em.curvature[d - 1] <= 0)
                fprintf(o, "the quadratic is not a bowl around the best point (a curvature <= 0): the loss has a "
                           "curved valley or several; the evaluations that reproduce the observation (above, and the "
                           "loss pictures) are the answer\n");
            if (em.n_ridge) {
                fprintf(o, "ridge: %zu direction%s of equal loss (curvature < %g of the largest); along",
                        em.n_ridge, em.n_ridge > 1 ? "s" : "", GF_RIDGE_FRACTION);
                const size_t kk = d - 1;
                for (size_t j = 0; j < d; ++j) fprintf(o, " %s %+.4g", c->p[j].name, em.direction_param[kk * d + j]);
                fprintf(o, " per unit step through");
                for (size_t j = 0; j < d; ++j) fprintf(o, " %s %.4g", c->p[j].name, em.ridge_point[j]);
                fprintf(o, ": the observation cannot tell these parameters apart\n");
            } else {
                fprintf(o, "no ridge: every direction is constrained\n");
            }
        } else {
            fprintf(o, "\nemulator: not fitted (%s)\n", emwhy);
        }
        if (have_morris) {
            fprintf(o, "\nsensitivity (Morris mu*, per unit of each range, %zu trajectories):\n%-16s %10s %14s %12s",
                    run->n_morris / (d + 1), "parameter", "loss", "runout [m]", "1 - Jaccard");
            if (k->o->nfront) fprintf(o, " %14s %18s", "front RMSE [m]", "front speed [m/s]");
            fprintf(o, "\n");
            for (size_t j = 0; j < d; ++j) {
                fprintf(o, "%-16s %10.4g %14.4g %12.4g", c->p[j].name, mu_star[j], mu_star[d + j], mu_star[2 * d + j]);
                if (k->o->nfront) fprintf(o, " %14.4g %18.4g", mu_star[3 * d + j], mu_star[4 * d + j]);
                fprintf(o, "\n");
            }
        } else if (run->n_morris) {
            fprintf(o, "\nsensitivity: not computed (a Morris member failed)\n");
        }
        fprintf(o, "\noutputs (in the output folder): evaluations.csv, parameters.csv, best/, bestOutline.tif, "
                   "loss_*.png; the best run's maps with the observation: best/postProcessing/hazardMaps/report/\n");
    }
    fclose(f);
    free(loss), free(jac), free(rerr), free(idx), free(accepted), free(uu), free(csv), free(bestdir), free(cmp),
        free(pc), free(sp);
    if (have_em) gf_emulator_free(&em);
    return verdict.verdict == GF_REACHABLE ? 0 : 3;
}

/* -run "V1 ... Vd": one run of the case with the parameters at these values
 * (their order: the dictionary's), in the folder out, by its own solver
 * process (a twin experiment's "event", or a set to look at) */
static int run_one(const char *casedir, const config *c, const char *values, const char *out)
{
    double x[MAXP];
    size_t n = 0;
    char *buf = strdup(values), *save = NULL;
    for (char *t = strtok_r(buf, " ,", &save); t; t = strtok_r(NULL, " ,", &save)) {
        if (n == c->d) die("-run \"%s\": more values than the %zu parameters of %s", values, c->d, c->path);
        if (!gf_parse_number(t, &x[n]) || !isfinite(x[n])) die("-run: '%s' is not a number", t);
        ++n;
    }
    free(buf);
    if (n != c->d) die("-run \"%s\": %zu values for the %zu parameters of %s (in its order)", values, n, c->d, c->path);
    observation none;
    memset(&none, 0, sizeof none);
    none.s_runout = NAN;
    calib k;
    memset(&k, 0, sizeof k);
    k.c = c;
    k.o = &none;
    k.casedir = casedir;
    if (asprintf(&k.templ, "%s.template", out) < 0) die("out of memory");
    char *rm[] = {"rm", "-rf", k.templ, NULL};
    run_prog(rm, NULL);
    make_template(&k);
    char why[2048] = "";
    if (make_member(&k, out, x, why, sizeof why)) die("%s", why);
    run_prog(rm, NULL);
    printf("gfCalibrate -run: %s with", out);
    for (size_t j = 0; j < c->d; ++j) printf(" %s %.9g", c->p[j].name, x[j]);
    printf("\n");
    char *log = cat(out, "log.faGranularFlowFoam");
    char *sv[] = {"faGranularFlowFoam", "-case", (char *)out, NULL};
    const int st = run_prog(sv, log);
    if (st) die("faGranularFlowFoam -case %s failed (exit status %d; %s)", out, st, log);
    free(log);
    free(k.templ);
    return 0;
}

/*------------------------------------------------------------------------- main --*/

static void usage(int st)
{
    fprintf(st ? stderr : stdout,
            "usage: gfCalibrate [-np N] [-dict FILE] [-out DIR] CASE\n"
            "       gfCalibrate -check [-dict FILE] CASE\n"
            "       gfCalibrate -run \"V1 ... Vd\" [-dict FILE] -out DIR CASE\n"
            "       gfCalibrate -observe RUN OUTDIR [-threshold KPA] [-shift CELLS] [-runoutShift M]\n"
            "       gfCalibrate -version\n"
            "Back-calculates the parameters of system/calibrationDict from the observations there\n"
            "(doc/guide/back-calculation.md); exit status 3 when the observation is unreachable.\n");
    exit(st);
}

int main(int argc, char **argv)
{
    if (argc > 1 && strcmp(argv[1], "-version") == 0) {
        printf("%s\n", GF_VERSION_STRING);
        return 0;
    }
    if (argc > 1 && (strcmp(argv[1], "-help") == 0 || strcmp(argv[1], "--help") == 0)) usage(0);
    if (argc > 1 && strcmp(argv[1], "-observe") == 0) return observe(argc, argv);
    long np = sysconf(_SC_NPROCESSORS_ONLN);
    const char *dictp = NULL, *out = NULL, *casedir = NULL, *runvalues = NULL;
    int check_only = 0;
    for (int i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "-np") == 0 && i + 1 < argc) {
            double v;
            if (!gf_parse_number(argv[++i], &v) || v != floor(v) || v < 1 || v > 256) die("-np %s: a whole number in [1, 256]", argv[i]);
            np = (long)v;
        } else if (strcmp(argv[i], "-dict") == 0 && i + 1 < argc) {
            dictp = argv[++i];
        } else if (strcmp(argv[i], "-out") == 0 && i + 1 < argc) {
            out = argv[++i];
        } else if (strcmp(argv[i], "-check") == 0) {
            check_only = 1;
        } else if (strcmp(argv[i], "-run") == 0 && i + 1 < argc) {
            runvalues = argv[++i];
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
    if (runvalues && !out) die("-run needs -out DIR: the run's folder");
    char *casereal = realpath(casedir, NULL);
    if (!casereal) die("%s: %s", casedir, strerror(errno));
    char *dp = dictp ? strdup(dictp) : cat(casereal, "system/calibrationDict");
    config c;
    read_config(dp, &c);
    check_path("the case", casereal);
    if (out) check_path("-out", out);
    check_entries(casereal, &c);
    GDALAllRegister();
    observation o;
    if (runvalues) return run_one(casereal, &c, runvalues, out);
    read_observation(casereal, &c, &o);
    if (check_only) {
        printf("gfCalibrate -check: %s and its observations are valid for %s\n", dp, casereal);
        return 0;
    }

    calib k;
    memset(&k, 0, sizeof k);
    k.c = &c;
    k.o = &o;
    k.casedir = casereal;
    if (out) {
        k.dir = strdup(out);
    } else if (asprintf(&k.dir, "%s-calibration", casereal) < 0) {
        die("out of memory");
    }
    if (mkdir(k.dir, 0755) && errno != EEXIST) die("%s: cannot make the folder: %s", k.dir, strerror(errno));
    char *absdir = realpath(k.dir, NULL);
    if (!absdir) die("%s: %s", k.dir, strerror(errno));
    free(k.dir);
    k.dir = absdir;
    k.evals = cat(k.dir, "evals");
    k.templ = cat(k.dir, "template");
    mkdir(k.evals, 0755);
    /* the dictionary beside the results (a record of what ran); a folder
     * that holds another calibration's results is not mixed with this one */
    {
        char *copy = cat(k.dir, "calibrationDict");
        if (exists(copy)) {
            char *cmp[] = {"cmp", "-s", dp, copy, NULL};
            if (run_prog(cmp, NULL) != 0)
                die("%s holds the results of another calibration (its calibrationDict differs from %s): give "
                    "another -out, or remove it to start again",
                    k.dir, dp);
        } else {
            char *cp[] = {"cp", dp, copy, NULL};
            if (run_prog(cp, NULL)) die("cannot write %s", copy);
        }
        free(copy);
    }
    make_template(&k);
    c.plan.threads = (size_t)np;
    char *logfmt = cat(k.dir, "log.worker_%u");
    char *argvw[] = {"faGranularFlowFoam", "-case", casereal, "-members", "-", NULL};
    printf("gfCalibrate: %zu parameters, %zu design points + %zu Morris + %zu refinements x %zu + %zu exploration "
           "rounds x %zu = %zu evaluations at most, on %ld workers (%s)\n",
           c.d, c.plan.n_sobol, c.plan.morris_r * (c.d + 1), c.plan.n_starts, c.plan.refine_evals,
           c.plan.explore_rounds, c.plan.n_explore,
           gf_calib_explore_index(&c.plan, c.plan.explore_rounds * c.plan.n_explore), np, k.dir);
    fflush(stdout);
    if (gf_workers_start((size_t)np, argvw, logfmt, &k.pool)) die("workers: %s", gf_error_detail());
    pthread_mutex_init(&k.lock, NULL);
    k.t0 = now();
    gf_calib_run run;
    const gf_status st = gf_calibrate_run(&c.plan, evaluate, &k, &run);
    const double wall = now() - k.t0;
    if (st) die("calibration: %s", gf_error_detail());
    if (gf_workers_stop(k.pool)) fprintf(stderr, "%s: %s\n", prog, gf_error_detail());
    const int verdict = analyse(&k, &run, wall);
    gf_calib_run_free(&run);
    return verdict;
}
