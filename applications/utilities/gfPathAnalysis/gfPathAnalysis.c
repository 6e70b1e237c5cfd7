/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * gfPathAnalysis — the path analysis of peak rasters (hazard-analysis
 * specification, sections 1-3; AvaFrame's ana3AIMEC): runout along the
 * avalanche path, runout angle, the MMA/AMA indicators and, given a
 * reference run, the TP/FP/FN/TN areas in the runout area.  The computation
 * is libgranflowTerrain's (granflow/path_analysis.h); this program reads the
 * files, checks them, and writes CSV, a summary and gnuplot plots.
 *
 *   gfPathAnalysis -dem DEM -path LINE -ppr F [-pft F] [-pfv F] -out DIR
 *                  [-split POINT] [-field ppr|pft|pfv] [-threshold T]
 *                  [-width W] [-beta-angle DEG] [-ds-min M]
 *                  [-ref-ppr F] [-ref-pft F] [-ref-pfv F] [-name N] [-ref-name N]
 *                  [-plots yes|no]
 *   gfPathAnalysis -help | -keywords | -version
 */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "gf_csv.h"
#include "granflow/path_analysis.h"
#include "granflow/terrain.h"
#include "granflow/version.h"

#define NF 3
static const char *const field_name[NF] = {"ppr", "pft", "pfv"};
static const char *const field_unit[NF] = {"kPa", "m", "m/s"};
static const double field_threshold[NF] = {1.0, 0.1, 1.0};

/* the options: one table for parsing, -help and -keywords */
typedef struct option {
    const char *key, *type, *dflt, *allowed, *unit, *what;
} option;
static const option options[] = {
    {"-dem", "file", "required", "", "", "DEM (any raster GDAL reads); its cell size is the step of the (s, l) grid"},
    {"-path", "file", "required", "", "", "avalanche path: the first line of a vector file (Inputs/LINES/path_aimec.shp, GeoJSON), from the release down; turned round when drawn upwards"},
    {"-ppr", "file", "-", "", "kPa", "peak pressure raster (ESRI ASCII, GeoTIFF, ...)"},
    {"-pft", "file", "-", "", "m", "peak flow thickness raster"},
    {"-pfv", "file", "-", "", "m/s", "peak flow speed raster"},
    {"-out", "folder", "required", "", "", "output folder (made when missing)"},
    {"-split", "file", "-", "", "", "split point (Inputs/POINTS/splitPoint.shp): the runout area starts at the beta point below it"},
    {"-field", "choice", "ppr", "ppr, pft, pfv", "", "result type of the runout and the comparison (AvaFrame's runoutResType); its raster is required"},
    {"-threshold", "number", "1 (ppr), 0.1 (pft), 1 (pfv)", "finite", "field's", "reached: the field above this (thresholdValue)"},
    {"-width", "number", "600", "> 0", "m", "domain width w across the path (domainWidth)"},
    {"-beta-angle", "number", "10", "(0, 90)", "deg", "slope below which the runout area starts (startOfRunoutAreaAngle)"},
    {"-ds-min", "number", "30", ">= 0", "m", "the slope stays below the beta angle over at least this (dsMin)"},
    {"-ref-ppr", "file", "-", "", "kPa", "reference run's peak pressure raster"},
    {"-ref-pft", "file", "-", "", "m", "reference run's peak flow thickness raster"},
    {"-ref-pfv", "file", "-", "", "m/s", "reference run's peak flow speed raster"},
    {"-name", "string", "run", "", "", "name of the run in the CSV (simName)"},
    {"-ref-name", "string", "reference", "", "", "name of the reference run"},
    {"-plots", "choice", "yes", "yes, no", "", "draw the PNG plots with gnuplot"},
};
#define NOPT (sizeof options / sizeof options[0])

static void die(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "gfPathAnalysis: ");
    vfprintf(stderr, fmt, ap);
    fprintf(stderr, "\n");
    va_end(ap);
    exit(1);
}

static void usage(FILE *f)
{
    fprintf(f, "usage: gfPathAnalysis -dem DEM -path LINE -ppr F [-pft F] [-pfv F] -out DIR [options]\n"
               "       gfPathAnalysis -help | -keywords | -version\n\n"
               "The path analysis of peak rasters (hazard-analysis specification sections 1-3,\n"
               "AvaFrame's ana3AIMEC): the rasters on the path-following (s, l) grid, the\n"
               "cross-section maximum and mean along the path, the runout (sRunout, runoutAngle)\n"
               "of -field above -threshold, MMA/AMA (maxpprCrossMax, meanpprCrossMax, ...) and,\n"
               "with -ref-<field>, the TP/FP/FN/TN areas in the runout area.  Each raster is\n"
               "interpolated (bilinear) onto the (s, l) grid with its own georeferencing, so\n"
               "the rasters may lie on different grids (AvaFrame's remeshed 5 m rasters against\n"
               "granflow's on the DEM's); each must cover the path, and the grid points on the\n"
               "DEM a raster does not cover count as not reached (the summary says how many).\n"
               "Writes to DIR:\n"
               "pathAnalysis.csv (one row per run), pathProfile.csv (along s), pathGrid.csv\n"
               "(the (s, l) grid), summary.dat, and pathField.png, pathProfile.png,\n"
               "pathCompare.png (gnuplot).\n\noptions:\n");
    for (size_t k = 0; k < NOPT; ++k)
        fprintf(f, "  %-12s %-7s %s (default %s%s%s)\n", options[k].key, options[k].type, options[k].what,
                options[k].dflt, *options[k].unit ? "; unit " : "", options[k].unit);
}

static void print_keywords(void)
{
    printf("| option | type | default | allowed | unit | description |\n|---|---|---|---|---|---|\n");
    for (size_t k = 0; k < NOPT; ++k)
        printf("| `%s` | %s | %s | %s | %s | %s |\n", options[k].key, options[k].type, options[k].dflt,
               options[k].allowed, options[k].unit, options[k].what);
    printf("\n");
}

/* the values given, indexed like options[] */
static const char *given[NOPT];

static const char *opt(const char *key)
{
    for (size_t k = 0; k < NOPT; ++k)
        if (!strcmp(options[k].key, key))
            return given[k];
    return NULL;
}

static double num_opt(const char *key, double dflt, double lo, double hi, int open_lo, int open_hi)
{
    const char *v = opt(key);
    if (!v)
        return dflt;
    double x;
    if (!gf_parse_number(v, &x))
        die("%s '%s' is not a finite number", key, v);
    if ((open_lo ? !(x > lo) : !(x >= lo)) || (open_hi ? !(x < hi) : !(x <= hi)))
        die("%s %g outside %s%g, %g%s", key, x, open_lo ? "(" : "[", lo, hi, open_hi ? ")" : "]");
    return x;
}

static void read_raster(const char *key, const char *file, gf_raster *r)
{
    if (access(file, R_OK) != 0)
        die("%s %s: no such file or not readable", key, file);
    if (gf_raster_read(file, r) != GF_SUCCESS)
        die("%s: %s", key, gf_error_detail());
}

static void grid_text(const gf_raster *r, char *buf, size_t n)
{
    snprintf(buf, n, "%d x %d cells of %.10g m, corner (%.10g, %.10g)", r->nx, r->ny, r->gt[1], r->gt[0],
             r->gt[3] + r->ny * r->gt[5]);
}

static FILE *open_out(const char *dir, const char *name, char *path, size_t n)
{
    snprintf(path, n, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    if (!f)
        die("cannot write %s (%s)", path, strerror(errno));
    return f;
}

/* a number for the CSV (NaN where undefined: outside the raster, no
 * reference raster; gnuplot and pandas read it as such) */
static void csv_num(FILE *f, double v, int last)
{
    if (isnan(v))
        fprintf(f, "NaN%s", last ? "\n" : ",");
    else
        fprintf(f, "%.10g%s", v, last ? "\n" : ",");
}

typedef struct run {
    const char *name;
    int has[NF];
    gf_raster r[NF];
    double *a[NF];             /* on the (s, l) grid */
    double *cmax[NF], *cmean[NF];
    double mma[NF], ama[NF];
    gf_runout ro;
} run;

static void load_run(run *R, const char *name, const char *const keys[NF], const gf_path_grid *g)
{
    R->name = name;
    for (int f = 0; f < NF; ++f) {
        const char *file = opt(keys[f]);
        R->has[f] = file != NULL;
        if (!file)
            continue;
        read_raster(keys[f], file, &R->r[f]);
        const size_t N = g->ns * g->nl;
        R->a[f] = malloc(N * sizeof(double));
        R->cmax[f] = malloc(g->ns * sizeof(double));
        R->cmean[f] = malloc(g->ns * sizeof(double));
        if (!R->a[f] || !R->cmax[f] || !R->cmean[f])
            die("out of memory");
    }
}

static void free_run(run *R)
{
    for (int f = 0; f < NF; ++f)
        if (R->has[f]) {
            gf_raster_free(&R->r[f]);
            free(R->a[f]), free(R->cmax[f]), free(R->cmean[f]);
        }
}

static void analyse_run(run *R, const gf_path_grid *g, int field, double thr)
{
    for (int f = 0; f < NF; ++f)
        if (R->has[f]) {
            gf_path_sample(g, &R->r[f], R->a[f]);
            gf_path_profiles(g, R->a[f], R->cmax[f], R->cmean[f]);
        }
    if (gf_path_runout(g, R->a[field], thr, &R->ro) != GF_SUCCESS)
        die("%s, -field %s: %s", R->name, field_name[field], gf_error_detail());
    for (int f = 0; f < NF; ++f) {
        R->mma[f] = R->ama[f] = NAN;
        if (R->has[f])
            gf_path_indicators(g, R->cmax[f], &R->ro, &R->mma[f], &R->ama[f]);
    }
}

static int run_gnuplot(const char *dir, const char *name)
{
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "cd '%s' && gnuplot '%s' > '%s.log' 2>&1", dir, name, name);
    const int rc = system(cmd);
    if (rc != 0)
        fprintf(stderr, "gfPathAnalysis: warning: gnuplot failed on %s/%s (see %s/%s.log)\n", dir, name, dir,
                name);
    return rc;
}

/* the settings the options give, checked */
typedef struct settings {
    int field;                  /* the result type of the runout and the comparison */
    double thr, width, beta, ds_min;
    int plots, has_ref;         /* -plots yes; a reference run given */
    const char *dir;            /* -out */
} settings;

static const char *const run_keys[NF] = {"-ppr", "-pft", "-pfv"};
static const char *const ref_keys[NF] = {"-ref-ppr", "-ref-pft", "-ref-pfv"};

/* everything read and computed */
typedef struct analysis {
    gf_raster dem;
    gf_path_grid g;
    run R, F;                   /* the run, the reference */
    size_t i_split, i_beta;     /* the split point and the beta point on the path */
    double split_dist;
    gf_path_areas ar;           /* the comparison in the runout area */
    char note[4 * NF][640];     /* rasters on another grid, grid points they do not cover */
    int n_note;
} analysis;

/* -help, -version, -keywords and the options given (into given[]): -1 to go
 * on, otherwise the exit status */
static int parse_options(int argc, char **argv)
{
    if (argc < 2 || !strcmp(argv[1], "-help") || !strcmp(argv[1], "--help") || !strcmp(argv[1], "-h")) {
        usage(argc < 2 ? stderr : stdout);
        return argc < 2 ? 2 : 0;
    }
    if (!strcmp(argv[1], "-version") || !strcmp(argv[1], "--version")) {
        printf("granflow %s (gfPathAnalysis)\n", gf_version());
        return 0;
    }
    if (!strcmp(argv[1], "-keywords") || !strcmp(argv[1], "--keywords")) {
        print_keywords();
        return 0;
    }
    for (int i = 1; i < argc; ++i) {
        size_t k = 0;
        while (k < NOPT && strcmp(options[k].key, argv[i]))
            ++k;
        if (k == NOPT) {
            fprintf(stderr, "gfPathAnalysis: unknown option '%s'; the options are:", argv[i]);
            for (size_t m = 0; m < NOPT; ++m)
                fprintf(stderr, " %s", options[m].key);
            fprintf(stderr, " (-help explains them)\n");
            return 1;
        }
        if (i + 1 >= argc)
            die("%s needs a value", argv[i]);
        if (given[k])
            die("%s given twice", argv[i]);
        given[k] = argv[++i];
    }
    return -1;
}

/* the values checked into S; the output folder made */
static void check_options(settings *S)
{
    for (size_t k = 0; k < NOPT; ++k)
        if (!strcmp(options[k].dflt, "required") && !given[k])
            die("%s is required (-help lists the options)", options[k].key);
    int field = 0;
    if (opt("-field")) {
        while (field < NF && strcmp(field_name[field], opt("-field")))
            ++field;
        if (field == NF)
            die("-field '%s': allowed ppr, pft, pfv", opt("-field"));
    }
    S->field = field;
    if (!opt(run_keys[field]))
        die("-field %s needs its raster %s", field_name[field], run_keys[field]);
    S->thr = num_opt("-threshold", field_threshold[field], -HUGE_VAL, HUGE_VAL, 0, 0);
    S->width = num_opt("-width", 600.0, 0.0, HUGE_VAL, 1, 1);
    S->beta = num_opt("-beta-angle", 10.0, 0.0, 90.0, 1, 1);
    S->ds_min = num_opt("-ds-min", 30.0, 0.0, HUGE_VAL, 0, 1);
    const char *plots = opt("-plots") ? opt("-plots") : "yes";
    if (strcmp(plots, "yes") && strcmp(plots, "no"))
        die("-plots '%s': allowed yes, no", plots);
    S->plots = !strcmp(plots, "yes");
    S->has_ref = 0;
    for (int f = 0; f < NF; ++f)
        S->has_ref |= opt(ref_keys[f]) != NULL;
    if (S->has_ref && !opt(ref_keys[field]))
        die("a comparison of -field %s needs the reference's raster %s", field_name[field], ref_keys[field]);
    S->dir = opt("-out");
    if (mkdir(S->dir, 0777) != 0 && errno != EEXIST)
        die("-out %s: cannot make the folder (%s)", S->dir, strerror(errno));
}

/* the DEM, the path and its (s, l) grid, the rasters of the run and the
 * reference; each raster is sampled onto the (s, l) grid on its own
 * (gf_path_sample), so they may lie on different grids, but each must cover
 * the path; a raster on another grid than the -field's raster, and the grid
 * points on the DEM a raster does not cover, are noted in the summary */
static void read_inputs(const settings *S, analysis *A)
{
    read_raster("-dem", opt("-dem"), &A->dem);
    size_t np;
    double *pxy;
    if (gf_path_read(opt("-path"), &np, &pxy) != GF_SUCCESS)
        die("-path: %s", gf_error_detail());
    if (gf_path_grid_make(&A->dem, np, pxy, S->width, &A->g) != GF_SUCCESS)
        die("-path %s on -dem %s: %s", opt("-path"), opt("-dem"), gf_error_detail());
    free(pxy);
    load_run(&A->R, opt("-name") ? opt("-name") : "run", run_keys, &A->g);
    if (S->has_ref)
        load_run(&A->F, opt("-ref-name") ? opt("-ref-name") : "reference", ref_keys, &A->g);
    const gf_raster *grid0 = &A->R.r[S->field];
    const char *file0 = opt(run_keys[S->field]), *key0 = run_keys[S->field];
    char a[160], b[160];
    grid_text(grid0, a, sizeof a);
    A->n_note = 0;
    for (int w = 0; w < 2; ++w)
        for (int f = 0; f < NF; ++f) {
            const run *X = w ? &A->F : &A->R;
            if (!X->has[f])
                continue;
            const char *key = w ? ref_keys[f] : run_keys[f], *file = opt(key);
            grid_text(&X->r[f], b, sizeof b);
            gf_path_cover c;
            gf_path_coverage(&A->g, &X->r[f], &A->dem, &c);
            if (c.n_path_out)
                die("%s %s (%s) does not cover the path: %zu of its %zu points, s %.1f .. %.1f m, lie"
                    " outside the raster's pixel centres; every raster must cover the path (as the DEM"
                    " must)", key, file, b, c.n_path_out, A->g.ns, c.path_s_min, c.path_s_max);
            if (!gf_raster_same_grid(grid0, &X->r[f]))
                snprintf(A->note[A->n_note++], sizeof A->note[0],
                         "%s %s is on another grid (%s) than %s %s (%s); each raster is sampled onto the"
                         " (s, l) grid on its own (bilinear)", key, file, b, key0, file0, a);
            if (c.n_out)
                snprintf(A->note[A->n_note++], sizeof A->note[0],
                         "%s %s does not cover %zu of the %zu (s, l) grid points on the DEM (%.0f m2;"
                         " s %.1f .. %.1f m, l %.1f .. %.1f m): not reached there", key, file, c.n_out,
                         c.n_grid, c.area_out, c.s_min, c.s_max, c.l_min, c.l_max);
        }
}

/* the beta point below the split point, the runs' runouts and indicators,
 * the comparison */
static void analyse(const settings *S, analysis *A)
{
    A->i_split = 0, A->i_beta = 0;
    A->split_dist = NAN;
    double sx = NAN, sy = NAN;
    if (opt("-split")) {
        if (gf_point_read(opt("-split"), &sx, &sy) != GF_SUCCESS)
            die("-split: %s", gf_error_detail());
        A->i_split = gf_path_snap(&A->g, sx, sy, &A->split_dist);
        if (gf_path_beta_point(&A->g, A->i_split, S->beta, S->ds_min, &A->i_beta) != GF_SUCCESS)
            die("-split %s: %s", opt("-split"), gf_error_detail());
    }
    analyse_run(&A->R, &A->g, S->field, S->thr);
    if (S->has_ref) {
        analyse_run(&A->F, &A->g, S->field, S->thr);
        gf_path_compare(&A->g, A->R.a[S->field], A->F.a[S->field], S->thr, A->i_beta, &A->ar);
    }
}

/* pathAnalysis.csv: one row per run */
static void write_analysis_csv(const settings *S, const analysis *A)
{
    const gf_path_grid *g = &A->g;
    const int field = S->field, has_ref = S->has_ref;
    char path[1200];
    FILE *c = open_out(S->dir, "pathAnalysis.csv", path, sizeof path);
    fprintf(c, "simName,resType,thresholdValue,domainWidth,sStart,sRunout,xRunout,yRunout,lRunout,"
               "zRelease,zRunout,deltaSXY,deltaZ,runoutAngle");
    for (int f = 0; f < NF; ++f)
        fprintf(c, ",max%sCrossMax,mean%sCrossMax", field_name[f], field_name[f]);
    fprintf(c, ",sBeta,xBeta,yBeta");
    if (has_ref) {
        fprintf(c, ",TP,FP,FN,TN,Aref,TPnorm,FPnorm,FNnorm,TNnorm,sRunoutDiff,runoutAngleDiff");
        for (int f = 0; f < NF; ++f)
            fprintf(c, ",max%sCrossMaxDiff", field_name[f]);
    }
    fprintf(c, "\n");
    for (int w = 0; w < 1 + has_ref; ++w) {
        const run *X = w ? &A->F : &A->R;
        const gf_runout *o = &X->ro;
        fprintf(c, "%s,%s,", X->name, field_name[field]);
        const double v[] = {S->thr, S->width, o->s_start, o->s_runout, o->x_runout, o->y_runout, o->l_runout,
                            o->z_start, o->z_runout, o->delta_sxy, o->delta_z, o->angle};
        for (size_t k = 0; k < sizeof v / sizeof v[0]; ++k)
            csv_num(c, v[k], 0);
        for (int f = 0; f < NF; ++f)
            csv_num(c, X->mma[f], 0), csv_num(c, X->ama[f], 0);
        const int b = opt("-split") != NULL;
        csv_num(c, b ? g->s[A->i_beta] : NAN, 0);
        csv_num(c, b ? g->xp[A->i_beta] : NAN, 0);
        csv_num(c, b ? g->yp[A->i_beta] : NAN, !has_ref);
        if (has_ref) {
            gf_path_areas q = A->ar;
            if (w) /* the reference against itself */
                gf_path_compare(g, A->F.a[field], A->F.a[field], S->thr, A->i_beta, &q);
            const double Aref = q.a_ref > 0.0 ? q.a_ref : NAN;
            const double u[] = {q.tp, q.fp, q.fn, q.tn, q.a_ref, q.tp / Aref, q.fp / Aref, q.fn / Aref, q.tn / Aref,
                                X->ro.s_runout - A->F.ro.s_runout, X->ro.angle - A->F.ro.angle};
            for (size_t k = 0; k < sizeof u / sizeof u[0]; ++k)
                csv_num(c, u[k], 0);
            for (int f = 0; f < NF; ++f)
                csv_num(c, X->mma[f] - A->F.mma[f], f == NF - 1);
        }
    }
    fclose(c);
}

/* pathProfile.csv: along s */
static void write_profile_csv(const settings *S, const analysis *A)
{
    const gf_path_grid *g = &A->g;
    char path[1200];
    FILE *p = open_out(S->dir, "pathProfile.csv", path, sizeof path);
    fprintf(p, "s,x,y,z");
    for (int w = 0; w < 1 + S->has_ref; ++w)
        for (int f = 0; f < NF; ++f)
            if ((w ? A->F.has : A->R.has)[f])
                fprintf(p, ",%s%sCrossMax,%s%sCrossMean", w ? "ref" : "", field_name[f], w ? "ref" : "",
                        field_name[f]);
    fprintf(p, "\n");
    for (size_t i = 0; i < g->ns; ++i) {
        fprintf(p, "%.10g,%.10g,%.10g,%.10g", g->s[i], g->xp[i], g->yp[i], g->zp[i]);
        for (int w = 0; w < 1 + S->has_ref; ++w) {
            const run *X = w ? &A->F : &A->R;
            for (int f = 0; f < NF; ++f)
                if (X->has[f]) {
                    fprintf(p, isnan(X->cmax[f][i]) ? ",NaN" : ",%.10g", X->cmax[f][i]);
                    fprintf(p, isnan(X->cmean[f][i]) ? ",NaN" : ",%.10g", X->cmean[f][i]);
                }
        }
        fprintf(p, "\n");
    }
    fclose(p);
}

/* pathGrid.csv: the (s, l) grid, blank line between sections (gnuplot) */
static void write_grid_csv(const settings *S, const analysis *A)
{
    const gf_path_grid *g = &A->g;
    const run *R = &A->R, *F = &A->F;
    const int field = S->field, has_ref = S->has_ref;
    unsigned char *cls = NULL;
    if (has_ref) {
        cls = malloc(g->ns * g->nl);
        if (!cls)
            die("out of memory");
        gf_path_compare_map(g, R->a[field], F->a[field], S->thr, A->i_beta, cls);
    }
    char path[1200];
    FILE *q = open_out(S->dir, "pathGrid.csv", path, sizeof path);
    fprintf(q, "s,l,x,y,area");
    for (int f = 0; f < NF; ++f)
        if (R->has[f])
            fprintf(q, ",%s", field_name[f]);
    if (has_ref)
        fprintf(q, ",ref%s,class", field_name[field]);
    fprintf(q, "\n");
    for (size_t i = 0; i < g->ns; ++i) {
        for (size_t j = 0; j < g->nl; ++j) {
            const size_t k = i * g->nl + j;
            fprintf(q, "%.10g,%.10g,%.10g,%.10g,%.8g", g->s[i], g->l[j], g->x[k], g->y[k], g->area[k]);
            for (int f = 0; f < NF; ++f)
                if (R->has[f]) {
                    fprintf(q, isnan(R->a[f][k]) ? ",NaN" : ",%.8g", R->a[f][k]);
                }
            if (has_ref) {
                fprintf(q, isnan(F->a[field][k]) ? ",NaN" : ",%.8g", F->a[field][k]);
                fprintf(q, ",%d", cls[k]);
            }
            fprintf(q, "\n");
        }
        fprintf(q, "\n");
    }
    fclose(q);
    free(cls);
}

/* the summary, printed and written to summary.dat */
static void print_summary(const settings *S, const analysis *A)
{
    const gf_path_grid *g = &A->g;
    const gf_path_areas *ar = &A->ar;
    const int field = S->field;
    const double thr = S->thr;
    char path[1200];
    FILE *s = open_out(S->dir, "summary.dat", path, sizeof path);
    char line[1024];
#define SAY(...)                                   \
    do {                                           \
        snprintf(line, sizeof line, __VA_ARGS__); \
        printf("%s\n", line);                      \
        fprintf(s, "%s\n", line);                  \
    } while (0)
    SAY("path %s: %.1f m long (horizontal), %zu points every %.4g m%s; domain width %g m (%zu points across)",
        opt("-path"), g->length, g->ns, g->h, g->reversed ? ", turned round (it was drawn upwards)" : "",
        g->width, g->nl);
    if (opt("-split"))
        SAY("split point snapped to s = %.1f m (%.1f m off the path); beta point (slope < %g deg over"
            " %g m): s = %.1f m, z = %.1f m",
            g->s[A->i_split], A->split_dist, S->beta, S->ds_min, g->s[A->i_beta], g->zp[A->i_beta]);
    for (int k = 0; k < A->n_note; ++k)
        SAY("%s", A->note[k]);
    for (int w = 0; w < 1 + S->has_ref; ++w) {
        const run *X = w ? &A->F : &A->R;
        const gf_runout *o = &X->ro;
        SAY("%s: runout of %s > %g %s: sStart %.1f m, sRunout %.1f m at (%.1f, %.1f), deltaSXY %.1f m,"
            " deltaZ %.1f m, runout angle %.2f deg",
            X->name, field_name[field], thr, field_unit[field], o->s_start, o->s_runout, o->x_runout,
            o->y_runout, o->delta_sxy, o->delta_z, o->angle);
        for (int f = 0; f < NF; ++f)
            if (X->has[f])
                SAY("%s: MM%s %.4g %s, AM%s %.4g %s", X->name, f == 0 ? "PPR" : (f == 1 ? "PFT" : "PFV"),
                    X->mma[f], field_unit[f], f == 0 ? "PPR" : (f == 1 ? "PFT" : "PFV"), X->ama[f],
                    field_unit[f]);
    }
    if (S->has_ref)
        SAY("comparison in the runout area (s >= %.1f m), %s > %g: TP %.0f m2, FP %.0f m2, FN %.0f m2,"
            " TN %.0f m2; over A_ref = %.0f m2: TP %.4f, FP %.4f, FN %.4f; sRunout difference %.1f m",
            g->s[A->i_beta], field_name[field], thr, ar->tp, ar->fp, ar->fn, ar->tn, ar->a_ref,
            ar->a_ref > 0 ? ar->tp / ar->a_ref : NAN, ar->a_ref > 0 ? ar->fp / ar->a_ref : NAN,
            ar->a_ref > 0 ? ar->fn / ar->a_ref : NAN, A->R.ro.s_runout - A->F.ro.s_runout);
#undef SAY
    fclose(s);
}

/* pathField.png: the field in path coordinates (s, l) */
static void plot_field(const settings *S, const analysis *A, int before)
{
    const gf_path_grid *g = &A->g;
    const run *R = &A->R;
    const int field = S->field;
    const double thr = S->thr;
    const int col = 6 + before; /* the field's column in pathGrid.csv */
    double vmax = R->mma[field] > thr ? R->mma[field] : thr * 2;
    char path[1200];
    FILE *gp = open_out(S->dir, "pathField.gp", path, sizeof path);
    fprintf(gp, "set datafile separator ','\n"
                "set terminal pngcairo size 700,900 font ',10' noenhanced\nset output 'pathField.png'\n"
                "set title \"%s: peak %s in path coordinates (s, l)\"\n"
                "set xlabel 'l [m] (> 0: left looking down the path)'\nset ylabel 's [m]'\n"
                "set cblabel '%s [%s]'\nset cbrange [0:%g]\n"
                "set palette defined (0 '#ffffcc', 0.3 '#fd8d3c', 0.7 '#e31a1c', 1 '#54278f')\n"
                "set yrange [%g:%g] reverse\nset xrange [%g:%g]\nset key outside bottom\n"
                "set arrow from %g,%g to %g,%g nohead lw 2 lc rgb 'black' front\n"
                "set label 'sRunout %.0f m' at %g,%g offset 0,-0.7 front\n"
                "set arrow from %g,%g to %g,%g nohead dt 2 lc rgb 'black' front\n"
                "set label 'sStart %.0f m' at %g,%g offset 0,0.7 front\n",
            R->name, field_name[field], field_name[field], field_unit[field], vmax, g->s[0], g->s[g->ns - 1],
            g->l[0], g->l[g->nl - 1], g->l[0], R->ro.s_runout, g->l[g->nl - 1], R->ro.s_runout, R->ro.s_runout,
            g->l[0], R->ro.s_runout, g->l[0], R->ro.s_start, g->l[g->nl - 1], R->ro.s_start, R->ro.s_start,
            g->l[0], R->ro.s_start);
    if (opt("-split"))
        fprintf(gp, "set arrow from %g,%g to %g,%g nohead dt 3 lw 2 lc rgb 'blue' front\n"
                    "set label 'beta point (%g deg)' at %g,%g offset 0,-0.7 right tc rgb 'blue' front\n",
                g->l[0], g->s[A->i_beta], g->l[g->nl - 1], g->s[A->i_beta], S->beta, g->l[g->nl - 1],
                g->s[A->i_beta]);
    fprintf(gp, "set arrow from 0,%g to 0,%g nohead dt 3 lc rgb 'blue' front\n"
                "set object circle at %g,%g size %g fs empty border lc rgb 'black' lw 2 front\n"
                "plot 'pathGrid.csv' skip 1 using 2:1:($%d > %g ? $%d : NaN) with image notitle\n",
            g->s[0], g->s[g->ns - 1], R->ro.l_runout, R->ro.s_runout, 3.0 * g->h, col, 0.01 * thr, col);
    fclose(gp);
    run_gnuplot(S->dir, "pathField.gp");
}

/* pathProfile.png: the cross-section maximum and mean along the path */
static void plot_profile(const settings *S, const analysis *A, int before)
{
    const gf_path_grid *g = &A->g;
    const run *R = &A->R, *F = &A->F;
    const int field = S->field;
    const double thr = S->thr;
    const int pc = 5 + 2 * before; /* its cross max in pathProfile.csv */
    char path[1200];
    FILE *gp = open_out(S->dir, "pathProfile.gp", path, sizeof path);
    fprintf(gp, "set datafile separator ','\n"
                "set terminal pngcairo size 1000,500 font ',10' noenhanced\nset output 'pathProfile.png'\n"
                "set title \"%s: cross-section maximum and mean of %s along the path; runout angle %.1f deg\"\n"
                "set xlabel 's [m]'\nset ylabel '%s [%s]'\nset y2label 'z [m]'\nset ytics nomirror\n"
                "set y2tics\nset grid\nset key top right\n"
                "set arrow from %g, graph 0 to %g, graph 1 nohead dt 2 lc rgb 'black'\n"
                "set arrow from %g, graph 0 to %g, graph 1 nohead lw 2 lc rgb 'black'\n"
                "set label 'sStart' at %g, graph 0.95 offset 0.5,0\n"
                "set label 'sRunout %.0f m' at %g, graph 0.95 offset 0.5,0\n",
            R->name, field_name[field], R->ro.angle, field_name[field], field_unit[field], R->ro.s_start,
            R->ro.s_start, R->ro.s_runout, R->ro.s_runout, R->ro.s_start, R->ro.s_runout, R->ro.s_runout);
    if (opt("-split"))
        fprintf(gp, "set arrow from %g, graph 0 to %g, graph 1 nohead dt 3 lw 2 lc rgb 'blue'\n"
                    "set label 'beta' at %g, graph 0.05 offset 0.5,0 tc rgb 'blue'\n",
                g->s[A->i_beta], g->s[A->i_beta], g->s[A->i_beta]);
    fprintf(gp, "plot 'pathProfile.csv' skip 1 using 1:%d with lines lw 2 lc rgb '#e31a1c' title '%s cross max',"
                " '' skip 1 using 1:%d with lines lc rgb '#fd8d3c' title '%s cross mean',"
                " %g with lines dt 2 lc rgb 'gray40' title 'threshold %g %s',"
                " '' skip 1 using 1:4 axes x1y2 with lines lc rgb 'black' title 'z(s)',",
            pc, field_name[field], pc + 1, field_name[field], thr, thr, field_unit[field]);
    if (S->has_ref) {
        /* the reference's cross max: after the run's columns */
        int rc = 5;
        for (int f = 0; f < NF; ++f)
            rc += 2 * R->has[f];
        for (int f = 0; f < field; ++f)
            rc += 2 * F->has[f];
        fprintf(gp, " '' skip 1 using 1:%d with lines lw 2 dt 2 lc rgb '#3182bd' title '%s cross max (%s)',",
                rc, field_name[field], F->name);
    }
    /* the travel-angle line from (sStart, zRelease) to (sRunout, zRunout) on the z axis */
    fprintf(gp, " '-' using 1:2 axes x1y2 with linespoints pt 7 dt 4 lc rgb 'black' title 'runout angle %.1f deg'\n"
                "%.10g,%.10g\n%.10g,%.10g\ne\n",
            R->ro.angle, R->ro.s_start, R->ro.z_start, R->ro.s_runout, R->ro.z_runout);
    fclose(gp);
    run_gnuplot(S->dir, "pathProfile.gp");
}

/* pathCompare.png: TP, FP, FN, TN in the runout area */
static void plot_compare(const settings *S, const analysis *A)
{
    const gf_path_grid *g = &A->g;
    const gf_path_areas *ar = &A->ar;
    const run *R = &A->R, *F = &A->F;
    const int field = S->field;
    const int cc = 6 + R->has[0] + R->has[1] + R->has[2] + 1;
    char path[1200];
    FILE *gp = open_out(S->dir, "pathCompare.gp", path, sizeof path);
    fprintf(gp, "set datafile separator ','\n"
                "set terminal pngcairo size 700,900 font ',10' noenhanced\nset output 'pathCompare.png'\n"
                "set title \"%s against %s: %s > %g %s in the runout area\\nTP %.3f, FP %.3f, FN %.3f of A_ref = %.0f m2\"\n"
                "set xlabel 'l [m]'\nset ylabel 's [m]'\nset yrange [%g:%g] reverse\nset xrange [%g:%g]\n"
                "set cbrange [0.5:4.5]\nset cbtics ('TP' 1, 'FP' 2, 'FN' 3, 'TN' 4)\n"
                "set palette defined (0.5 '#1a9850', 1.5 '#1a9850', 1.5 '#d73027', 2.5 '#d73027',"
                " 2.5 '#4575b4', 3.5 '#4575b4', 3.5 '#f0f0f0', 4.5 '#f0f0f0')\n"
                "set arrow from %g,%g to %g,%g nohead dt 3 lw 2 lc rgb 'black' front\n"
                "set key outside bottom\n"
                "plot 'pathGrid.csv' skip 1 using 2:1:($%d > 0 ? $%d : NaN) with image notitle\n",
            R->name, F->name, field_name[field], S->thr, field_unit[field],
            ar->a_ref > 0 ? ar->tp / ar->a_ref : NAN, ar->a_ref > 0 ? ar->fp / ar->a_ref : NAN,
            ar->a_ref > 0 ? ar->fn / ar->a_ref : NAN, ar->a_ref, fmax(g->s[0], g->s[A->i_beta] - 50.0),
            g->s[g->ns - 1], g->l[0], g->l[g->nl - 1], g->l[0], g->s[A->i_beta], g->l[g->nl - 1], g->s[A->i_beta],
            cc, cc);
    fclose(gp);
    run_gnuplot(S->dir, "pathCompare.gp");
}

/* the gnuplot plots */
static void write_plots(const settings *S, const analysis *A)
{
    int before = 0; /* rasters of the run before the field's */
    for (int f = 0; f < S->field; ++f)
        before += A->R.has[f];
    plot_field(S, A, before);
    plot_profile(S, A, before);
    if (S->has_ref)
        plot_compare(S, A);
}

int main(int argc, char **argv)
{
    const int rc = parse_options(argc, argv);
    if (rc >= 0)
        return rc;
    settings S;
    check_options(&S);
    analysis A = {0};
    read_inputs(&S, &A);
    analyse(&S, &A);
    write_analysis_csv(&S, &A);
    write_profile_csv(&S, &A);
    write_grid_csv(&S, &A);
    print_summary(&S, &A);
    if (S.plots)
        write_plots(&S, &A);
    printf("wrote %s/{pathAnalysis.csv,pathProfile.csv,pathGrid.csv,summary.dat%s}\n", S.dir,
           !S.plots ? "" : (S.has_ref ? ",pathField.png,pathProfile.png,pathCompare.png"
                                      : ",pathField.png,pathProfile.png"));
    free_run(&A.R);
    free_run(&A.F);
    gf_path_grid_free(&A.g);
    gf_raster_free(&A.dem);
    return 0;
}
