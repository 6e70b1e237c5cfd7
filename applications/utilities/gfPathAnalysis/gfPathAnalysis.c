/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * gfPathAnalysis — the path analysis of peak rasters (doc/theory/hazard-analysis.md,
 * sections 1-3; AvaFrame's ana3AIMEC): runout along the
 * avalanche path, runout angle, the MMA/AMA indicators and, given a
 * reference run, the TP/FP/FN/TN areas in the runout area.  The computation
 * and its files are libgranflowTerrain's (gf_path_analysis_run,
 * granflow/path_analysis.h), which faGranularFlowFoam calls at the end of a
 * run too (controlDict pathAnalysis); this program parses the command line
 * into its options and prints its messages.
 *
 *   gfPathAnalysis -dem DEM -path LINE -ppr F [-pft F] [-pfv F] -out DIR
 *                  [-split POINT] [-field ppr|pft|pfv] [-threshold T]
 *                  [-width W] [-beta-angle DEG] [-ds-min M]
 *                  [-ref-ppr F] [-ref-pft F] [-ref-pfv F] [-name N] [-ref-name N]
 *                  [-plots yes|no]
 *   gfPathAnalysis -help | -keywords | -version
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "granflow/path_analysis.h"
#include "granflow/version.h"

static void usage(FILE *f)
{
    size_t n;
    const gf_path_analysis_option *o = gf_path_analysis_options(&n);
    fprintf(f, "usage: gfPathAnalysis -dem DEM -path LINE -ppr F [-pft F] [-pfv F] -out DIR [options]\n"
               "       gfPathAnalysis -help | -keywords | -version\n\n"
               "The path analysis of peak rasters (doc/theory/hazard-analysis.md, sections 1-3,\n"
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
               "pathCompare.png (one gnuplot process; the .gp scripts, pathField.dat and gnuplot.log\n"
               "stay beside them).\n\noptions:\n");
    for (size_t k = 0; k < n; ++k)
        fprintf(f, "  %-12s %-7s %s (default %s%s%s)\n", o[k].key, o[k].type, o[k].what,
                o[k].dflt, *o[k].unit ? "; unit " : "", o[k].unit);
}

static void print_keywords(void)
{
    size_t n;
    const gf_path_analysis_option *o = gf_path_analysis_options(&n);
    printf("| option | type | default | allowed | unit | description |\n|---|---|---|---|---|---|\n");
    for (size_t k = 0; k < n; ++k)
        printf("| `%s` | %s | %s | %s | %s | %s |\n", o[k].key, o[k].type, o[k].dflt,
               o[k].allowed, o[k].unit, o[k].what);
    printf("\n");
}

static void say(void *ctx, const char *text)
{
    (void)ctx;
    printf("%s\n", text);
}

static void warn(void *ctx, const char *text)
{
    (void)ctx;
    fprintf(stderr, "gfPathAnalysis: warning: %s\n", text);
}

static void error(void *ctx, const char *text)
{
    (void)ctx;
    fprintf(stderr, "gfPathAnalysis: %s\n", text);
}

int main(int argc, char **argv)
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
    /* the options as key/value pairs, in the order given: an unknown one is
     * refused with the list, one without a value or given twice here too */
    size_t nopt;
    const gf_path_analysis_option *o = gf_path_analysis_options(&nopt);
    const char **kv = malloc((size_t)argc * sizeof *kv);
    char *seen = calloc(nopt, 1);
    if (!kv || !seen) {
        fprintf(stderr, "gfPathAnalysis: out of memory\n");
        return 1;
    }
    size_t n = 0;
    for (int i = 1; i < argc; ++i) {
        size_t k = 0;
        while (k < nopt && strcmp(o[k].key, argv[i]))
            ++k;
        const char *why = NULL;
        if (k == nopt) {
            fprintf(stderr, "gfPathAnalysis: unknown option '%s'; the options are:", argv[i]);
            for (size_t m = 0; m < nopt; ++m)
                fprintf(stderr, " %s", o[m].key);
            fprintf(stderr, " (-help explains them)\n");
        } else if (i + 1 >= argc)
            why = "needs a value";
        else if (seen[k])
            why = "given twice";
        if (k == nopt || why) {
            if (why)
                fprintf(stderr, "gfPathAnalysis: %s %s\n", argv[i], why);
            free(kv), free(seen);
            return 1;
        }
        seen[k] = 1;
        kv[2 * n] = argv[i];
        kv[2 * n + 1] = argv[++i];
        ++n;
    }
    free(seen);
    const gf_path_analysis_io io = {NULL, say, warn, error, NULL};
    const gf_status st = gf_path_analysis_run(n, kv, &io);
    free(kv);
    return st == GF_SUCCESS ? 0 : 1;
}
