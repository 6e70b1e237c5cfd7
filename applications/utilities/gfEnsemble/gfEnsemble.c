/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * gfEnsemble — the numerical steps of an ensemble of runs (doc/theory/hazard-analysis.md,
 * section 4); the driver gfRunEnsemble calls them.
 *
 *   gfEnsemble sample latinHypercube N D SEED
 *   gfEnsemble sample oneAtATime STEPS D
 *       the members' unit coordinates u in [0, 1), one member per line:
 *       "member u_1 ... u_D" (libgranflow's gf_sample_latin_hypercube,
 *       gf_sample_one_at_a_time; the seed makes the sample reproducible on
 *       every machine)
 *   gfEnsemble probability [-dem DEM] [-levels L1,L2,...] THRESHOLD OUTDIR RASTER...
 *       the fraction of the rasters (one per successful member, on one
 *       grid) above THRESHOLD per pixel (gf_probability_map): OUTDIR/
 *       probability.tif and .asc (0..1 on the rasters' grid), its contour
 *       lines at the levels (default 0.05,0.5,0.95) as contours.geojson and
 *       contours.xy (x y level, for gnuplot); -dem checks that the rasters
 *       are on the DEM's grid (gfRunEnsemble draws the map with gfReportMaps)
 *   gfEnsemble percentiles P1,P2,... < values
 *       percentiles of the numbers on standard input (one per line; "nan"
 *       or "failed" lines are counted and left out): "n N failed F" and
 *       "pP VALUE" per percentile (gf_percentile, type 7: p50 the median)
 *   gfEnsemble -version
 * Errors name the file or argument and exit 2.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "gf_csv.h"
#include "granflow/ensemble.h"
#include "granflow/terrain.h"
#include "granflow/version.h"

static void usage(void)
{
    fprintf(stderr,
            "usage: gfEnsemble sample latinHypercube N D SEED\n"
            "       gfEnsemble sample oneAtATime STEPS D\n"
            "       gfEnsemble probability [-dem DEM] [-levels L1,L2,...] THRESHOLD OUTDIR RASTER...\n"
            "       gfEnsemble percentiles P1,P2,... < values\n"
            "       gfEnsemble -version\n");
    exit(2);
}

static void fail(const char *what)
{
    fprintf(stderr, "gfEnsemble: %s: %s\n", what, gf_error_detail());
    exit(2);
}

static double num(const char *s, const char *what)
{
    double v;
    if (!gf_parse_number(s, &v)) {
        fprintf(stderr, "gfEnsemble: %s = '%s' is not a number\n", what, s);
        exit(2);
    }
    return v;
}

static size_t count(const char *s, const char *what, double lo)
{
    const double v = num(s, what);
    if (v != floor(v) || v < lo || v > 1e6) {
        fprintf(stderr, "gfEnsemble: %s = %s must be a whole number in [%g, 1e6]\n", what, s, lo);
        exit(2);
    }
    return (size_t)v;
}

/* a comma-separated list of numbers */
static size_t list(const char *s, const char *what, double *out, size_t max)
{
    size_t n = 0;
    char buf[1024];
    snprintf(buf, sizeof buf, "%s", s);
    for (char *save = NULL, *t = strtok_r(buf, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
        if (n == max) {
            fprintf(stderr, "gfEnsemble: %s: more than %zu values\n", what, max);
            exit(2);
        }
        out[n++] = num(t, what);
    }
    if (n == 0) {
        fprintf(stderr, "gfEnsemble: %s: no value\n", what);
        exit(2);
    }
    return n;
}

static int sample(int argc, char **argv)
{
    if (argc < 1)
        usage();
    size_t n, d;
    double *u;
    if (!strcmp(argv[0], "latinHypercube")) {
        if (argc != 4)
            usage();
        n = count(argv[1], "members N", 1), d = count(argv[2], "inputs D", 1);
        const double seed = num(argv[3], "SEED");
        if (seed < 0 || seed != floor(seed) || seed > 9007199254740992.0) {
            fprintf(stderr, "gfEnsemble: SEED = %s must be a whole number in [0, 2^53]\n", argv[3]);
            exit(2);
        }
        if (!(u = malloc(n * d * sizeof *u)))
            return 2;
        if (gf_sample_latin_hypercube(n, d, (uint64_t)seed, u))
            fail("sample latinHypercube");
    } else if (!strcmp(argv[0], "oneAtATime")) {
        if (argc != 3)
            usage();
        const size_t steps = count(argv[1], "STEPS", 2);
        d = count(argv[2], "inputs D", 1), n = steps * d;
        if (!(u = malloc(n * d * sizeof *u)))
            return 2;
        if (gf_sample_one_at_a_time(steps, d, u))
            fail("sample oneAtATime");
    } else {
        fprintf(stderr, "gfEnsemble: sample method '%s': latinHypercube or oneAtATime\n", argv[0]);
        exit(2);
    }
    for (size_t i = 0; i < n; ++i) {
        printf("%zu", i + 1);
        for (size_t j = 0; j < d; ++j)
            printf(" %.17g", u[i * d + j]);
        printf("\n");
    }
    free(u);
    return 0;
}

static int probability(int argc, char **argv)
{
    const char *dem = NULL;
    double levels[16] = {0.05, 0.5, 0.95};
    size_t nlev = 3;
    int a = 0;
    for (; a < argc && argv[a][0] == '-'; a += 2) {
        if (a + 1 >= argc)
            usage();
        if (!strcmp(argv[a], "-dem"))
            dem = argv[a + 1];
        else if (!strcmp(argv[a], "-levels")) {
            nlev = list(argv[a + 1], "-levels", levels, 16);
            for (size_t k = 0; k < nlev; ++k)
                if (!(levels[k] > 0 && levels[k] <= 1)) {
                    fprintf(stderr, "gfEnsemble: -levels: %g is outside (0, 1]\n", levels[k]);
                    exit(2);
                }
        } else {
            fprintf(stderr, "gfEnsemble: probability: unknown option %s (-dem, -levels)\n", argv[a]);
            exit(2);
        }
    }
    if (argc - a < 3)
        usage();
    const double threshold = num(argv[a], "THRESHOLD");
    const char *dir = argv[a + 1];
    const size_t n = (size_t)(argc - a - 2);
    if (mkdir(dir, 0777) != 0) {
        struct stat sb;
        if (stat(dir, &sb) != 0 || !S_ISDIR(sb.st_mode)) {
            fprintf(stderr, "gfEnsemble: cannot create the output folder %s\n", dir);
            exit(2);
        }
    }
    gf_raster p;
    if (gf_probability_map(n, (const char *const *)(argv + a + 2), threshold, &p))
        fail("probability");
    char path[4096];
    snprintf(path, sizeof path, "%s/probability.tif", dir);
    if (gf_raster_write(path, "GTiff", &p, p.z))
        fail(path);
    snprintf(path, sizeof path, "%s/probability.asc", dir);
    if (gf_raster_write(path, "AAIGrid", &p, p.z))
        fail(path);
    char gj[4096];
    snprintf(gj, sizeof gj, "%s/contours.geojson", dir);
    snprintf(path, sizeof path, "%s/contours.xy", dir);
    if (gf_raster_contours(gj, path, &p, p.z, nlev, levels))
        fail(gj);
    /* pixels with each level reached, and the area */
    const size_t np = (size_t)p.nx * (size_t)p.ny;
    const double cell = p.gt[1] * -p.gt[5];
    printf("probability of exceeding %g over %zu members: %s/probability.tif\n", threshold, n, dir);
    for (size_t k = 0; k < nlev; ++k) {
        size_t c = 0;
        for (size_t i = 0; i < np; ++i)
            c += p.z[i] >= levels[k];
        printf("area with probability >= %g: %.6g m2\n", levels[k], (double)c * cell);
    }
    if (dem) {
        gf_raster d;
        if (gf_raster_read(dem, &d))
            fail(dem);
        if (d.nx != p.nx || d.ny != p.ny) {
            fprintf(stderr, "gfEnsemble: -dem %s is %d x %d cells, the members' rasters %d x %d\n", dem, d.nx, d.ny,
                    p.nx, p.ny);
            exit(2);
        }
        gf_raster_free(&d);
    }
    gf_raster_free(&p);
    return 0;
}

static int percentiles(int argc, char **argv)
{
    if (argc != 1)
        usage();
    double ps[32];
    const size_t np = list(argv[0], "percentiles", ps, 32);
    size_t n = 0, cap = 64, failed = 0;
    double *x = malloc(cap * sizeof *x);
    char line[4096];
    while (x && fgets(line, sizeof line, stdin)) {
        line[strcspn(line, "\r\n")] = 0;
        const char *t = line + strspn(line, " \t");
        if (!*t || *t == '#')
            continue;
        double v;
        if (!strcmp(t, "nan") || !strcmp(t, "failed")) {
            ++failed;
            continue;
        }
        if (!gf_parse_number(t, &v)) {
            fprintf(stderr, "gfEnsemble: percentiles: '%s' on standard input is not a number\n", t);
            exit(2);
        }
        if (n == cap && !(x = realloc(x, (cap *= 2) * sizeof *x)))
            break;
        x[n++] = v;
    }
    if (!x)
        return 2;
    printf("n %zu failed %zu\n", n, failed);
    for (size_t k = 0; k < np; ++k) {
        double v;
        if (gf_percentile(x, n, ps[k], &v))
            fail("percentiles");
        printf("p%g %.10g\n", ps[k], v);
    }
    free(x);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc >= 2 && (!strcmp(argv[1], "-version") || !strcmp(argv[1], "--version"))) {
        printf("gfEnsemble (granflow) %s\n", gf_version());
        return 0;
    }
    if (argc < 2)
        usage();
    if (!strcmp(argv[1], "sample"))
        return sample(argc - 2, argv + 2);
    if (!strcmp(argv[1], "probability"))
        return probability(argc - 2, argv + 2);
    if (!strcmp(argv[1], "percentiles"))
        return percentiles(argc - 2, argv + 2);
    usage();
    return 2;
}
