/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The whole path analysis of peak rasters (gf_path_analysis_run, see
 * granflow/path_analysis.h): the options checked, the DEM, the path and the
 * rasters read, the analysis of path_analysis.c, and the CSV, the summary
 * and the gnuplot plots written.  The code of the program gfPathAnalysis,
 * which parses its command line into the options and prints the messages,
 * and of faGranularFlowFoam's path analysis at the end of a run (controlDict
 * pathAnalysis): one implementation, the same files byte for byte.  Every
 * failure returns a status with the message (never exits). */
#include "granflow/path_analysis.h"
#include "internal.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define NF 3
static const char *const field_name[NF] = {"ppr", "pft", "pfv"};
static const char *const field_unit[NF] = {"kPa", "m", "m/s"};
static const double field_threshold[NF] = {1.0, 0.1, 1.0};

/* the options: one table for the checks, gfPathAnalysis's -help and -keywords */
static const gf_path_analysis_option options[] = {
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

const gf_path_analysis_option *gf_path_analysis_options(size_t *n)
{
    if (n)
        *n = NOPT;
    return options;
}

/* a file name of the options: longer ones are refused */
#define PATHMAX 4352

typedef struct run {
    const char *name;
    int has[NF];
    gf_raster r[NF];
    double *a[NF];             /* on the (s, l) grid */
    double *cmax[NF], *cmean[NF];
    double mma[NF], ama[NF];
    gf_runout ro;
} run;

/* the settings the options give, checked */
typedef struct settings {
    int field;                  /* the result type of the runout and the comparison */
    double thr, width, beta, ds_min;
    int plots, has_ref;         /* -plots yes; a reference run given */
    const char *dir;            /* -out, as given */
    char dir_path[PATHMAX];     /* -out in the base folder */
} settings;

/* everything read and computed */
typedef struct analysis {
    gf_raster dem;
    gf_path_grid g;
    run R, F;                   /* the run, the reference */
    size_t i_split, i_beta;     /* the split point and the beta point on the path */
    double split_dist;
    gf_path_areas ar;           /* the comparison in the runout area */
    char note[4 * NF][2 * PATHMAX + 640]; /* rasters on another grid, grid points they do not cover
                                          (two file names of any length a line) */
    int n_note;
} analysis;

/* one call: the values given (indexed like options[]) and where messages go */
typedef struct call {
    const char *given[NOPT];
    const gf_path_analysis_io *io;
} call;

static const char *const run_keys[NF] = {"-ppr", "-pft", "-pfv"};
static const char *const ref_keys[NF] = {"-ref-ppr", "-ref-pft", "-ref-pfv"};

/* the failure: its whole message to io->error, the status with the message
 * (gf_error_detail, which keeps its first 511 characters) */
#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
static gf_status fail(const call *C, gf_status st, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    const int n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    char *msg = n >= 0 ? malloc((size_t)n + 1) : NULL;
    if (!msg) {
        if (C->io && C->io->error)
            C->io->error(C->io->ctx, "out of memory");
        return gf_fail(GF_ENOMEM, "out of memory");
    }
    va_start(ap, fmt);
    vsnprintf(msg, (size_t)n + 1, fmt, ap);
    va_end(ap);
    if (C->io && C->io->error)
        C->io->error(C->io->ctx, msg);
    gf_fail(st, "%s", msg);
    free(msg);
    return st;
}

#define TRY(expr)                           \
    do {                                    \
        const gf_status st_ = (expr);       \
        if (st_ != GF_SUCCESS)              \
            return st_;                     \
    } while (0)

static void say(const call *C, const char *line)
{
    if (C->io && C->io->line)
        C->io->line(C->io->ctx, line);
}

static const char *opt(const call *C, const char *key)
{
    for (size_t k = 0; k < NOPT; ++k)
        if (!strcmp(options[k].key, key))
            return C->given[k];
    return NULL;
}

/* a file of the options where it is: in the base folder unless absolute */
static gf_status where(const call *C, const char *key, const char *file, char *path)
{
    const char *base = C->io ? C->io->base : NULL;
    const int n = (!base || !*base || file[0] == '/') ? snprintf(path, PATHMAX, "%s", file)
                                                      : snprintf(path, PATHMAX, "%s/%s", base, file);
    if (n < 0 || n >= PATHMAX)
        return fail(C, GF_EINVAL, "%s %s: the file name is too long", key, file);
    return GF_SUCCESS;
}

static gf_status num_opt(const call *C, const char *key, double dflt, double lo, double hi, int open_lo,
                         int open_hi, double *x)
{
    const char *v = opt(C, key);
    *x = dflt;
    if (!v)
        return GF_SUCCESS;
    if (!gf_parse_number(v, x))
        return fail(C, GF_EDOM, "%s '%s' is not a finite number", key, v);
    if ((open_lo ? !(*x > lo) : !(*x >= lo)) || (open_hi ? !(*x < hi) : !(*x <= hi)))
        return fail(C, GF_EDOM, "%s %g outside %s%g, %g%s", key, *x, open_lo ? "(" : "[", lo, hi,
                    open_hi ? ")" : "]");
    return GF_SUCCESS;
}

static gf_status read_raster(const call *C, const char *key, const char *file, gf_raster *r)
{
    char path[PATHMAX];
    TRY(where(C, key, file, path));
    if (access(path, R_OK) != 0)
        return fail(C, GF_EIO, "%s %s: no such file or not readable", key, file);
    if (gf_raster_read(path, r) != GF_SUCCESS)
        return fail(C, GF_EIO, "%s: %s", key, gf_error_detail());
    return GF_SUCCESS;
}

static void grid_text(const gf_raster *r, char *buf, size_t n)
{
    snprintf(buf, n, "%d x %d cells of %.10g m, corner (%.10g, %.10g)", r->nx, r->ny, r->gt[1], r->gt[0],
             r->gt[3] + r->ny * r->gt[5]);
}

static gf_status open_out(const call *C, const settings *S, const char *name, FILE **f)
{
    char path[PATHMAX + 64];
    snprintf(path, sizeof path, "%s/%s", S->dir_path, name);
    *f = fopen(path, "w");
    if (!*f) {
        const int e = errno;
        char shown[PATHMAX + 64];
        snprintf(shown, sizeof shown, "%s/%s", S->dir, name);
        return fail(C, GF_EIO, "cannot write %s (%s)", shown, strerror(e));
    }
    return GF_SUCCESS;
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

static gf_status load_run(const call *C, run *R, const char *name, const char *const keys[NF],
                          const gf_path_grid *g)
{
    R->name = name;
    for (int f = 0; f < NF; ++f) {
        const char *file = opt(C, keys[f]);
        if (!file)
            continue;
        TRY(read_raster(C, keys[f], file, &R->r[f]));
        R->has[f] = 1;
        const size_t N = g->ns * g->nl;
        R->a[f] = malloc(N * sizeof(double));
        R->cmax[f] = malloc(g->ns * sizeof(double));
        R->cmean[f] = malloc(g->ns * sizeof(double));
        if (!R->a[f] || !R->cmax[f] || !R->cmean[f])
            return fail(C, GF_ENOMEM, "out of memory");
    }
    return GF_SUCCESS;
}

static void free_run(run *R)
{
    for (int f = 0; f < NF; ++f)
        if (R->has[f]) {
            gf_raster_free(&R->r[f]);
            free(R->a[f]), free(R->cmax[f]), free(R->cmean[f]);
        }
}

static gf_status analyse_run(const call *C, run *R, const gf_path_grid *g, int field, double thr)
{
    for (int f = 0; f < NF; ++f)
        if (R->has[f]) {
            gf_path_sample(g, &R->r[f], R->a[f]);
            gf_path_profiles(g, R->a[f], R->cmax[f], R->cmean[f]);
        }
    if (gf_path_runout(g, R->a[field], thr, &R->ro) != GF_SUCCESS)
        return fail(C, GF_EDOM, "%s, -field %s: %s", R->name, field_name[field], gf_error_detail());
    for (int f = 0; f < NF; ++f) {
        R->mma[f] = R->ama[f] = NAN;
        if (R->has[f])
            gf_path_indicators(g, R->cmax[f], &R->ro, &R->mma[f], &R->ama[f]);
    }
    return GF_SUCCESS;
}

/* the plot scripts written, in one gnuplot process (cd to the folder: the
 * scripts name their files relatively, so they rerun alone there); each
 * script starts with 'reset', so that one's settings do not reach the next.
 * One process for all of them: a gnuplot start (pngcairo) is about 0.09 s of
 * CPU; its log is gnuplot.log */
static void run_gnuplot(const call *C, const settings *S, const char *names)
{
    /* the folder single-quoted for the shell, a quote in it as '\'' (a
     * folder may be named "Lawinen d'Hérens") */
    char quoted[4 * PATHMAX], cmd[5 * PATHMAX];
    size_t q = 0;
    for (const char *p = S->dir_path; *p && q + 5 < sizeof quoted; ++p) {
        if (*p == '\'') {
            memcpy(quoted + q, "'\\''", 4);
            q += 4;
        } else
            quoted[q++] = *p;
    }
    quoted[q] = '\0';
    snprintf(cmd, sizeof cmd, "cd '%s' && gnuplot %s > gnuplot.log 2>&1", quoted, names);
    const int rc = system(cmd);
    if (rc != 0 && C->io && C->io->warning) {
        char msg[2 * PATHMAX];
        snprintf(msg, sizeof msg, "gnuplot failed on %s/{%s} (see %s/gnuplot.log)", S->dir, names, S->dir);
        C->io->warning(C->io->ctx, msg);
    }
}

/* the values checked into S; the output folder made */
static gf_status check_options(const call *C, settings *S)
{
    for (size_t k = 0; k < NOPT; ++k)
        if (!strcmp(options[k].dflt, "required") && !C->given[k])
            return fail(C, GF_EINVAL, "%s is required (-help lists the options)", options[k].key);
    int field = 0;
    if (opt(C, "-field")) {
        while (field < NF && strcmp(field_name[field], opt(C, "-field")))
            ++field;
        if (field == NF)
            return fail(C, GF_EINVAL, "-field '%s': allowed ppr, pft, pfv", opt(C, "-field"));
    }
    S->field = field;
    if (!opt(C, run_keys[field]))
        return fail(C, GF_EINVAL, "-field %s needs its raster %s", field_name[field], run_keys[field]);
    TRY(num_opt(C, "-threshold", field_threshold[field], -HUGE_VAL, HUGE_VAL, 0, 0, &S->thr));
    TRY(num_opt(C, "-width", 600.0, 0.0, HUGE_VAL, 1, 1, &S->width));
    TRY(num_opt(C, "-beta-angle", 10.0, 0.0, 90.0, 1, 1, &S->beta));
    TRY(num_opt(C, "-ds-min", 30.0, 0.0, HUGE_VAL, 0, 1, &S->ds_min));
    const char *plots = opt(C, "-plots") ? opt(C, "-plots") : "yes";
    if (strcmp(plots, "yes") && strcmp(plots, "no"))
        return fail(C, GF_EINVAL, "-plots '%s': allowed yes, no", plots);
    S->plots = !strcmp(plots, "yes");
    S->has_ref = 0;
    for (int f = 0; f < NF; ++f)
        S->has_ref |= opt(C, ref_keys[f]) != NULL;
    if (S->has_ref && !opt(C, ref_keys[field]))
        return fail(C, GF_EINVAL, "a comparison of -field %s needs the reference's raster %s", field_name[field],
                    ref_keys[field]);
    S->dir = opt(C, "-out");
    TRY(where(C, "-out", S->dir, S->dir_path));
    if (mkdir(S->dir_path, 0777) != 0 && errno != EEXIST) {
        const int e = errno;
        return fail(C, GF_EIO, "-out %s: cannot make the folder (%s)", S->dir, strerror(e));
    }
    return GF_SUCCESS;
}

/* the DEM, the path and its (s, l) grid, the rasters of the run and the
 * reference; each raster is sampled onto the (s, l) grid on its own
 * (gf_path_sample), so they may lie on different grids, but each must cover
 * the path; a raster on another grid than the -field's raster, and the grid
 * points on the DEM a raster does not cover, are noted in the summary */
static gf_status read_inputs(const call *C, const settings *S, analysis *A)
{
    TRY(read_raster(C, "-dem", opt(C, "-dem"), &A->dem));
    size_t np;
    double *pxy = NULL;
    char path[PATHMAX];
    TRY(where(C, "-path", opt(C, "-path"), path));
    if (gf_path_read(path, &np, &pxy) != GF_SUCCESS)
        return fail(C, GF_EIO, "-path: %s", gf_error_detail());
    const gf_status st = gf_path_grid_make(&A->dem, np, pxy, S->width, &A->g);
    free(pxy);
    if (st != GF_SUCCESS)
        return fail(C, st, "-path %s on -dem %s: %s", opt(C, "-path"), opt(C, "-dem"), gf_error_detail());
    TRY(load_run(C, &A->R, opt(C, "-name") ? opt(C, "-name") : "run", run_keys, &A->g));
    if (S->has_ref)
        TRY(load_run(C, &A->F, opt(C, "-ref-name") ? opt(C, "-ref-name") : "reference", ref_keys, &A->g));
    const gf_raster *grid0 = &A->R.r[S->field];
    const char *file0 = opt(C, run_keys[S->field]), *key0 = run_keys[S->field];
    char a[160], b[160];
    grid_text(grid0, a, sizeof a);
    A->n_note = 0;
    for (int w = 0; w < 2; ++w)
        for (int f = 0; f < NF; ++f) {
            const run *X = w ? &A->F : &A->R;
            if (!X->has[f])
                continue;
            const char *key = w ? ref_keys[f] : run_keys[f], *file = opt(C, key);
            grid_text(&X->r[f], b, sizeof b);
            gf_path_cover c;
            gf_path_coverage(&A->g, &X->r[f], &A->dem, &c);
            if (c.n_path_out)
                return fail(C, GF_EDOM,
                            "%s %s (%s) does not cover the path: %zu of its %zu points, s %.1f .. %.1f m, lie"
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
    return GF_SUCCESS;
}

/* the beta point below the split point, the runs' runouts and indicators,
 * the comparison */
static gf_status analyse(const call *C, const settings *S, analysis *A)
{
    A->i_split = 0, A->i_beta = 0;
    A->split_dist = NAN;
    double sx = NAN, sy = NAN;
    if (opt(C, "-split")) {
        char path[PATHMAX];
        TRY(where(C, "-split", opt(C, "-split"), path));
        if (gf_point_read(path, &sx, &sy) != GF_SUCCESS)
            return fail(C, GF_EIO, "-split: %s", gf_error_detail());
        A->i_split = gf_path_snap(&A->g, sx, sy, &A->split_dist);
        if (gf_path_beta_point(&A->g, A->i_split, S->beta, S->ds_min, &A->i_beta) != GF_SUCCESS)
            return fail(C, GF_EDOM, "-split %s: %s", opt(C, "-split"), gf_error_detail());
    }
    TRY(analyse_run(C, &A->R, &A->g, S->field, S->thr));
    if (S->has_ref) {
        TRY(analyse_run(C, &A->F, &A->g, S->field, S->thr));
        gf_path_compare(&A->g, A->R.a[S->field], A->F.a[S->field], S->thr, A->i_beta, &A->ar);
    }
    return GF_SUCCESS;
}

/* pathAnalysis.csv: one row per run */
static gf_status write_analysis_csv(const call *C, const settings *S, const analysis *A)
{
    const gf_path_grid *g = &A->g;
    const int field = S->field, has_ref = S->has_ref;
    FILE *c;
    TRY(open_out(C, S, "pathAnalysis.csv", &c));
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
        const int b = opt(C, "-split") != NULL;
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
    return GF_SUCCESS;
}

/* pathProfile.csv: along s */
static gf_status write_profile_csv(const call *C, const settings *S, const analysis *A)
{
    const gf_path_grid *g = &A->g;
    FILE *p;
    TRY(open_out(C, S, "pathProfile.csv", &p));
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
    return GF_SUCCESS;
}

/* pathGrid.csv: the (s, l) grid, blank line between sections (gnuplot) */
static gf_status write_grid_csv(const call *C, const settings *S, const analysis *A)
{
    const gf_path_grid *g = &A->g;
    const run *R = &A->R, *F = &A->F;
    const int field = S->field, has_ref = S->has_ref;
    unsigned char *cls = NULL;
    if (has_ref) {
        cls = malloc(g->ns * g->nl);
        if (!cls)
            return fail(C, GF_ENOMEM, "out of memory");
        gf_path_compare_map(g, R->a[field], F->a[field], S->thr, A->i_beta, cls);
    }
    FILE *q;
    const gf_status st = open_out(C, S, "pathGrid.csv", &q);
    if (st != GF_SUCCESS) {
        free(cls);
        return st;
    }
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
    return GF_SUCCESS;
}

/* the summary, printed and written to summary.dat */
static gf_status print_summary(const call *C, const settings *S, const analysis *A)
{
    const gf_path_grid *g = &A->g;
    const gf_path_areas *ar = &A->ar;
    const int field = S->field;
    const double thr = S->thr;
    FILE *s;
    TRY(open_out(C, S, "summary.dat", &s));
    char line[3 * PATHMAX]; /* a line names up to two files (the notes) */
#define SAY(...)                                   \
    do {                                           \
        snprintf(line, sizeof line, __VA_ARGS__); \
        say(C, line);                              \
        fprintf(s, "%s\n", line);                  \
    } while (0)
    SAY("path %s: %.1f m long (horizontal), %zu points every %.4g m%s; domain width %g m (%zu points across)",
        opt(C, "-path"), g->length, g->ns, g->h, g->reversed ? ", turned round (it was drawn upwards)" : "",
        g->width, g->nl);
    if (opt(C, "-split"))
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
    return GF_SUCCESS;
}

/* pathField.png: the field in path coordinates (s, l) */
static gf_status plot_field(const call *C, const settings *S, const analysis *A)
{
    const gf_path_grid *g = &A->g;
    const run *R = &A->R;
    const int field = S->field;
    const double thr = S->thr;
    double vmax = R->mma[field] > thr ? R->mma[field] : thr * 2;
    /* the plotted values in pathField.dat (l, s, the field where it is above
     * 1 % of the threshold, else NaN: not drawn): gnuplot reads these three
     * columns in a third of the time it took for pathGrid.csv's columns with
     * the masking expression (0.12 against 0.34 s on avaKot, the same PNG
     * byte for byte) */
    FILE *dat;
    TRY(open_out(C, S, "pathField.dat", &dat));
    for (size_t i = 0; i < g->ns; ++i) {
        for (size_t j = 0; j < g->nl; ++j) {
            const double v = R->a[field][i * g->nl + j];
            fprintf(dat, "%.10g %.10g ", g->l[j], g->s[i]);
            fprintf(dat, !isnan(v) && v > 0.01 * thr ? "%.8g\n" : "NaN\n", v);
        }
        fprintf(dat, "\n");
    }
    if (fclose(dat) != 0)
        return fail(C, GF_EIO, "%s/pathField.dat: cannot write it", S->dir);
    FILE *gp;
    TRY(open_out(C, S, "pathField.gp", &gp));
    fprintf(gp, "reset\n"
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
    if (opt(C, "-split"))
        fprintf(gp, "set arrow from %g,%g to %g,%g nohead dt 3 lw 2 lc rgb 'blue' front\n"
                    "set label 'beta point (%g deg)' at %g,%g offset 0,-0.7 right tc rgb 'blue' front\n",
                g->l[0], g->s[A->i_beta], g->l[g->nl - 1], g->s[A->i_beta], S->beta, g->l[g->nl - 1],
                g->s[A->i_beta]);
    fprintf(gp, "set arrow from 0,%g to 0,%g nohead dt 3 lc rgb 'blue' front\n"
                "set object circle at %g,%g size %g fs empty border lc rgb 'black' lw 2 front\n"
                "plot 'pathField.dat' using 1:2:3 with image notitle\n",
            g->s[0], g->s[g->ns - 1], R->ro.l_runout, R->ro.s_runout, 3.0 * g->h);
    fclose(gp);
    return GF_SUCCESS;
}

/* pathProfile.png: the cross-section maximum and mean along the path */
static gf_status plot_profile(const call *C, const settings *S, const analysis *A, int before)
{
    const gf_path_grid *g = &A->g;
    const run *R = &A->R, *F = &A->F;
    const int field = S->field;
    const double thr = S->thr;
    const int pc = 5 + 2 * before; /* its cross max in pathProfile.csv */
    FILE *gp;
    TRY(open_out(C, S, "pathProfile.gp", &gp));
    fprintf(gp, "reset\nset datafile separator ','\n"
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
    if (opt(C, "-split"))
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
    return GF_SUCCESS;
}

/* pathCompare.png: TP, FP, FN, TN in the runout area */
static gf_status plot_compare(const call *C, const settings *S, const analysis *A)
{
    const gf_path_grid *g = &A->g;
    const gf_path_areas *ar = &A->ar;
    const run *R = &A->R, *F = &A->F;
    const int field = S->field;
    const int cc = 6 + R->has[0] + R->has[1] + R->has[2] + 1;
    FILE *gp;
    TRY(open_out(C, S, "pathCompare.gp", &gp));
    fprintf(gp, "reset\nset datafile separator ','\n"
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
    return GF_SUCCESS;
}

/* the gnuplot plots */
static gf_status write_plots(const call *C, const settings *S, const analysis *A)
{
    int before = 0; /* rasters of the run before the field's */
    for (int f = 0; f < S->field; ++f)
        before += A->R.has[f];
    TRY(plot_field(C, S, A));
    TRY(plot_profile(C, S, A, before));
    if (S->has_ref)
        TRY(plot_compare(C, S, A));
    run_gnuplot(C, S, S->has_ref ? "pathField.gp pathProfile.gp pathCompare.gp" : "pathField.gp pathProfile.gp");
    return GF_SUCCESS;
}

/* the options as pairs, checked into C->given */
static gf_status take_options(call *C, size_t n, const char *const *kv)
{
    for (size_t i = 0; i < n; ++i) {
        const char *key = kv[2 * i], *value = kv[2 * i + 1];
        size_t k = 0;
        while (k < NOPT && (!key || strcmp(options[k].key, key)))
            ++k;
        if (k == NOPT)
            return fail(C, GF_ENOTFOUND, "unknown option '%s' (gfPathAnalysis -help lists the options)",
                        key ? key : "(null)");
        if (!value)
            return fail(C, GF_EINVAL, "%s needs a value", key);
        if (C->given[k])
            return fail(C, GF_EINVAL, "%s given twice", key);
        C->given[k] = value;
    }
    return GF_SUCCESS;
}

static gf_status analysis_run(call *C, size_t n, const char *const *kv, settings *S, analysis *A)
{
    TRY(take_options(C, n, kv));
    TRY(check_options(C, S));
    TRY(read_inputs(C, S, A));
    TRY(analyse(C, S, A));
    TRY(write_analysis_csv(C, S, A));
    TRY(write_profile_csv(C, S, A));
    TRY(write_grid_csv(C, S, A));
    TRY(print_summary(C, S, A));
    if (S->plots)
        TRY(write_plots(C, S, A));
    const size_t m = strlen(S->dir) + 128;
    char *line = malloc(m);
    if (!line)
        return fail(C, GF_ENOMEM, "out of memory");
    snprintf(line, m, "wrote %s/{pathAnalysis.csv,pathProfile.csv,pathGrid.csv,summary.dat%s}", S->dir,
             !S->plots ? "" : (S->has_ref ? ",pathField.dat,pathField.png,pathProfile.png,pathCompare.png"
                                          : ",pathField.dat,pathField.png,pathProfile.png"));
    say(C, line);
    free(line);
    return GF_SUCCESS;
}

gf_status gf_path_analysis_run(size_t n, const char *const *kv, const gf_path_analysis_io *io)
{
    if (n && !kv)
        return gf_fail(GF_EINVAL, "gf_path_analysis_run: no options");
    call *C = calloc(1, sizeof *C);
    settings *S = calloc(1, sizeof *S);
    analysis *A = calloc(1, sizeof *A);
    gf_status st = GF_ENOMEM;
    if (!C || !S || !A)
        st = gf_fail(GF_ENOMEM, "out of memory");
    else {
        C->io = io;
        st = analysis_run(C, n, kv, S, A);
        free_run(&A->R);
        free_run(&A->F);
        gf_path_grid_free(&A->g);
        gf_raster_free(&A->dem);
    }
    free(A), free(S), free(C);
    return st;
}
