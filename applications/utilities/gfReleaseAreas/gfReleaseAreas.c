/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * gfReleaseAreas — every potential release area of a DEM, its scenario
 * release depth and an alpha-beta screening of its runout (issue 52;
 * doc/theory/regional.md).  A thin command on granflow/regional.h:
 *
 *   gfReleaseAreas -dem DEM [-slope MIN,MAX] [-minArea A] [-roughness VRM|none]
 *                  [-roughnessWindow N] [-curvature C] [-sectors N]
 *                  [-forest FILE] [-out DIR] [-format gpkg|shp]
 *                  [-d0 D0STAR [-gradient G -zref Z]] [-alphaBeta [-maxClimb H] [-maxFlat L]]
 *                  [-wind FROM[,HALF[,DMAX]]] [-compare REL]
 *   gfReleaseAreas -help | -version
 *
 * Writes DIR/releaseAreas.gpkg (or .shp): one polygon per area with id,
 * area_m2, slope_deg, altitude_m, aspect_deg (and d0_m with -d0);
 * DIR/releaseAreas.csv, the same table; DIR/releaseAreas_labels.tif, the
 * area of every cell (0: none); with -wind DIR/windShelter.tif (and each
 * area's mean in the table); with -alphaBeta DIR/alphaBeta.csv (the beta
 * point, alpha and the runout points of alpha and alpha -+ one standard
 * deviation of each area) and DIR/thalwegs.csv (each area's steepest-descent
 * thalweg from its highest cell).  Prints shell-readable lines (name=value):
 * releaseAreas, areaTotal_m2, seconds, and with -compare the fraction of the
 * given polygons' area that the release areas cover (overlap), the release
 * areas they touch (compareReleases) and those areas' total
 * (compareReleaseArea_m2).  A refused
 * input is named with its allowed range on stderr, exit 1 (2: a wrong
 * command line).
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include <cpl_error.h>

#include "granflow/regional.h"
#include "granflow/terrain.h"
#include "granflow/version.h"

static const char *prog = "gfReleaseAreas";

static void usage(FILE *f)
{
    fprintf(f,
            "usage: gfReleaseAreas -dem DEM [-slope MIN,MAX] [-minArea A] [-roughness VRM|none]\n"
            "                      [-roughnessWindow N] [-curvature C] [-sectors N] [-forest FILE]\n"
            "                      [-out DIR] [-format gpkg|shp] [-d0 D0STAR [-gradient G -zref Z]]\n"
            "                      [-alphaBeta [-maxClimb H] [-maxFlat L]] [-wind FROM[,HALF[,DMAX]]]\n"
            "                      [-compare REL]\n"
            "       gfReleaseAreas -help | -version\n\n"
            "The potential release areas of a DEM (doc/theory/regional.md): cells of slope\n"
            "in [MIN, MAX] deg (default 28,60; Horn's method), vector ruggedness (VRM, window\n"
            "-roughnessWindow cells, default 5) at most -roughness (default 0.05; none: no\n"
            "criterion), |plan curvature| at most -curvature 1/m (default: no criterion),\n"
            "outside the forest (-forest: polygons, or a raster on the DEM's grid, > 0 =\n"
            "forest), split into areas by -sectors aspect classes (default 8) and kept from\n"
            "-minArea m2 on (default 10000).  -d0: the release depth d0 = (D0STAR + G (z - Z))\n"
            "f(psi) (Salm et al. 1990) at each area's mean altitude z and slope psi; G in m\n"
            "per m (default 0), Z needed when G is not 0.  -alphaBeta: each area's thalweg,\n"
            "beta point and alpha runout (Lied and Bakkehoi 1980); the D8 thalweg walks\n"
            "through pits of the DEM up to -maxClimb m deep (default 5) and on along level\n"
            "ground for -maxFlat m without descending (default 1000).  -wind: the wind shelter\n"
            "index (Winstral et al. 2002) for a wind from FROM deg, a sector of -+HALF deg\n"
            "(default 30) within DMAX m (default 100): windShelter.tif and each area's mean\n"
            "(releaseAreas.csv, windshelter_deg).  -compare REL: the\n"
            "fraction of the polygons' area the release areas cover.\n\n"
            "Writes DIR/releaseAreas.gpkg (.shp), releaseAreas.csv, releaseAreas_labels.tif,\n"
            "and with -alphaBeta alphaBeta.csv and thalwegs.csv (DIR default .).\n");
}

static int bad_option(const char *key, const char *value, const char *allowed)
{
    fprintf(stderr, "%s: %s %s: allowed %s\n", prog, key, value ? value : "(missing)", allowed);
    return 2;
}

static int number(const char *t, double *v)
{
    return t && gf_parse_number(t, v);
}

/* a raster on dem's grid, or polygons: the forest mask */
static int forest_mask(const char *path, const gf_raster *dem, unsigned char *mask)
{
    gf_raster f;
    CPLPushErrorHandler(CPLQuietErrorHandler);
    gf_status st = gf_raster_read(path, &f);
    CPLPopErrorHandler();
    if (st == GF_SUCCESS) {
        int same = f.nx == dem->nx && f.ny == dem->ny;
        for (int k = 0; k < 6 && same; ++k)
            same = fabs(f.gt[k] - dem->gt[k]) <= 1e-6 * fabs(dem->gt[1]);
        if (!same) {
            fprintf(stderr,
                    "%s: -forest %s: a raster of %d x %d cells at (%.3f, %.3f), cell %.4f m; allowed: the DEM's grid "
                    "(%d x %d cells at (%.3f, %.3f), cell %.4f m) (gdalwarp it onto the DEM, or give polygons)\n",
                    prog, path, f.nx, f.ny, f.gt[0], f.gt[3], f.gt[1], dem->nx, dem->ny, dem->gt[0], dem->gt[3],
                    dem->gt[1]);
            gf_raster_free(&f);
            return 0;
        }
        for (size_t c = 0; c < (size_t)dem->nx * (size_t)dem->ny; ++c)
            mask[c] = isfinite(f.z[c]) && f.z[c] > 0;
        gf_raster_free(&f);
        return 1;
    }
    gf_polygons p;
    if (gf_polygons_read(path, NULL, 1.0, &p) != GF_SUCCESS) {
        fprintf(stderr, "%s: -forest %s: neither a raster GDAL reads nor polygons: %s\n", prog, path,
                gf_error_detail());
        return 0;
    }
    gf_polygons_mask(&p, dem, mask);
    gf_polygons_free(&p);
    return 1;
}

/* x y of the thalweg (x y z s rows) at distance s */
static void thalweg_xy(const double *t, size_t n, double s, double *x, double *y)
{
    size_t i = 0;
    while (i + 2 < n && t[4 * (i + 1) + 3] < s)
        ++i;
    double s0 = t[4 * i + 3], s1 = t[4 * (i + 1) + 3];
    double u = s1 > s0 ? (s - s0) / (s1 - s0) : 0;
    u = u < 0 ? 0 : u > 1 ? 1 : u;
    *x = t[4 * i] + u * (t[4 * (i + 1)] - t[4 * i]);
    *y = t[4 * i + 1] + u * (t[4 * (i + 1) + 1] - t[4 * i + 1]);
}

static int alpha_beta(const char *dir, const gf_raster *dem, const gf_pra_set *set, double max_climb,
                      double max_flat)
{
    char path[4096], tpath[4096];
    snprintf(path, sizeof path, "%s/alphaBeta.csv", dir);
    snprintf(tpath, sizeof tpath, "%s/thalwegs.csv", dir);
    FILE *f = fopen(path, "w"), *t = fopen(tpath, "w");
    if (!f || !t) {
        fprintf(stderr, "%s: cannot write %s: %s\n", prog, !f ? path : tpath, strerror(errno));
        if (f)
            fclose(f);
        if (t)
            fclose(t);
        return 0;
    }
    gf_alpha_beta_params p;
    gf_alpha_beta_params_default(&p);
    fprintf(f, "# alpha-beta (Lied and Bakkehoi 1980): alpha = %g beta %+g deg, SD %g deg; beta point where the "
               "thalweg's slope first falls below %g deg (staying below over %g m); s horizontal distance from the "
               "area's highest cell along its D8 thalweg\n",
            p.k1, p.k2, p.sd, p.beta_slope, p.ds_min);
    fprintf(f, "id,x_top,y_top,z_top,thalweg_m,beta_deg,alpha_deg,sd_deg,s_beta,x_beta,y_beta,z_beta,"
               "s_alpha,x_alpha,y_alpha,z_alpha,s_alpha_minus_sd,x_alpha_minus_sd,y_alpha_minus_sd,z_alpha_minus_sd,"
               "s_alpha_plus_sd,x_alpha_plus_sd,y_alpha_plus_sd,z_alpha_plus_sd,note\n");
    fprintf(t, "id,s,x,y,z\n");
    size_t screened = 0;
    for (size_t k = 0; k < set->n; ++k) {
        const gf_pra *a = &set->pra[k];
        double *th = NULL;
        size_t n = 0;
        if (gf_thalweg_d8(dem, a->top_col, a->top_row, max_climb, max_flat, &th, &n) != GF_SUCCESS) {
            fprintf(stderr, "%s: release area %d: %s\n", prog, a->id, gf_error_detail());
            continue;
        }
        for (size_t i = 0; i < n; ++i)
            fprintf(t, "%d,%.3f,%.3f,%.3f,%.3f\n", a->id, th[4 * i + 3], th[4 * i], th[4 * i + 1], th[4 * i + 2]);
        double *s = malloc(n * sizeof *s), *z = malloc(n * sizeof *z);
        if (!s || !z) {
            free(s);
            free(z);
            free(th);
            fclose(f);
            fclose(t);
            fprintf(stderr, "%s: out of memory\n", prog);
            return 0;
        }
        for (size_t i = 0; i < n; ++i) {
            s[i] = th[4 * i + 3];
            z[i] = th[4 * i + 2];
        }
        gf_alpha_beta ab;
        fprintf(f, "%d,%.3f,%.3f,%.3f,%.3f", a->id, th[0], th[1], th[2], th[4 * (n - 1) + 3]);
        if (n < 2 || gf_alpha_beta_profile(n, s, z, &p, &ab) != GF_SUCCESS) {
            const char *why = n < 2 ? "the highest cell is a pit" : gf_error_detail();
            fprintf(f, ",,,,,,,,,,,,,,,,,,,,\"%s\"\n", why);
        } else {
            double x, y;
            thalweg_xy(th, n, ab.s_beta, &x, &y);
            fprintf(f, ",%.4f,%.4f,%.2f,%.3f,%.3f,%.3f,%.3f", ab.beta, ab.alpha, p.sd, ab.s_beta, x, y, ab.z_beta);
            int reached = 1;
            for (int m = 0; m < 3; ++m) {
                if (isnan(ab.s_alpha[m])) {
                    fprintf(f, ",,,,");
                    reached = 0;
                    continue;
                }
                thalweg_xy(th, n, ab.s_alpha[m], &x, &y);
                fprintf(f, ",%.3f,%.3f,%.3f,%.3f", ab.s_alpha[m], x, y, ab.z_alpha[m]);
            }
            fprintf(f, ",%s\n", reached ? "" : "\"the thalweg ends (pit or DEM border) before an alpha line meets it\"");
            ++screened;
        }
        free(s);
        free(z);
        free(th);
    }
    int ok = !ferror(f) && !ferror(t);
    ok = !fclose(f) && ok;
    ok = !fclose(t) && ok;
    if (!ok) {
        fprintf(stderr, "%s: cannot write %s or %s\n", prog, path, tpath);
        return 0;
    }
    printf("alphaBetaScreened=%zu\n", screened);
    return 1;
}

int main(int argc, char **argv)
{
    const char *dem_path = NULL, *forest = NULL, *out = ".", *format = "gpkg", *compare = NULL;
    gf_pra_params p;
    gf_pra_params_default(&p);
    double d0star = NAN, gradient = 0, zref = NAN;
    int do_ab = 0;
    double max_climb = 5, max_flat = 1000;
    double wind[3] = {NAN, 30, 100}; /* from, half width [deg], search distance [m] */
    for (int i = 1; i < argc; ++i) {
        const char *k = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        double x;
        if (!strcmp(k, "-help") || !strcmp(k, "-h")) {
            usage(stdout);
            return 0;
        } else if (!strcmp(k, "-version")) {
            printf("%s %s\n", prog, GF_VERSION_STRING);
            return 0;
        } else if (!strcmp(k, "-alphaBeta")) {
            do_ab = 1;
            continue;
        } else if (!v) {
            fprintf(stderr, "%s: %s needs a value\n", prog, k);
            usage(stderr);
            return 2;
        } else if (!strcmp(k, "-dem")) {
            dem_path = v;
        } else if (!strcmp(k, "-forest")) {
            forest = v;
        } else if (!strcmp(k, "-out")) {
            out = v;
        } else if (!strcmp(k, "-compare")) {
            compare = v;
        } else if (!strcmp(k, "-format")) {
            if (strcmp(v, "gpkg") && strcmp(v, "shp"))
                return bad_option(k, v, "gpkg or shp");
            format = v;
        } else if (!strcmp(k, "-slope")) {
            char a[64], b[64];
            const char *comma = strchr(v, ',');
            if (!comma || (size_t)(comma - v) >= sizeof a || strlen(comma + 1) >= sizeof b)
                return bad_option(k, v, "MIN,MAX in degrees with 0 < MIN < MAX <= 90 (e.g. 28,60)");
            memcpy(a, v, (size_t)(comma - v));
            a[comma - v] = 0;
            strcpy(b, comma + 1);
            if (!number(a, &p.slope_min) || !number(b, &p.slope_max) || !(p.slope_min > 0) ||
                !(p.slope_min < p.slope_max) || !(p.slope_max <= 90))
                return bad_option(k, v, "MIN,MAX in degrees with 0 < MIN < MAX <= 90 (e.g. 28,60)");
        } else if (!strcmp(k, "-minArea")) {
            if (!number(v, &p.min_area) || p.min_area < 0)
                return bad_option(k, v, "an area in m2 >= 0");
        } else if (!strcmp(k, "-roughness")) {
            if (!strcmp(v, "none"))
                p.roughness_max = NAN;
            else if (!number(v, &p.roughness_max) || p.roughness_max < 0 || p.roughness_max > 1)
                return bad_option(k, v, "a VRM in [0, 1] or none");
        } else if (!strcmp(k, "-roughnessWindow")) {
            if (!number(v, &x) || x < 3 || x > 101 || x != floor(x) || fmod(x, 2) != 1)
                return bad_option(k, v, "an odd number of cells in [3, 101]");
            p.roughness_window = (int)x;
        } else if (!strcmp(k, "-curvature")) {
            if (!number(v, &p.curvature_max) || !(p.curvature_max > 0))
                return bad_option(k, v, "a plan curvature in 1/m > 0");
        } else if (!strcmp(k, "-sectors")) {
            if (!number(v, &x) || x < 1 || x > 36 || x != floor(x))
                return bad_option(k, v, "a whole number of aspect classes in [1, 36]");
            p.aspect_sectors = (int)x;
        } else if (!strcmp(k, "-d0")) {
            if (!number(v, &d0star) || d0star < 0)
                return bad_option(k, v, "a depth in m >= 0");
        } else if (!strcmp(k, "-gradient")) {
            if (!number(v, &gradient))
                return bad_option(k, v, "a finite change of d0 with altitude, m per m (e.g. 0.0005)");
        } else if (!strcmp(k, "-maxClimb")) {
            if (!number(v, &max_climb) || max_climb < 0)
                return bad_option(k, v, "a height in m >= 0 (0: the thalweg ends in the first pit)");
        } else if (!strcmp(k, "-wind")) {
            char buf[256];
            snprintf(buf, sizeof buf, "%s", v);
            int nw = 0, okw = strlen(v) < sizeof buf;
            for (char *save = NULL, *tok = strtok_r(buf, ",", &save); tok && okw; tok = strtok_r(NULL, ",", &save))
                okw = nw < 3 && number(tok, &wind[nw++]);
            if (!okw || nw < 1 || !(wind[0] >= 0 && wind[0] <= 360) || !(wind[1] > 0 && wind[1] <= 180) ||
                !(wind[2] > 0))
                return bad_option(k, v,
                                  "FROM[,HALF[,DMAX]]: the direction the wind comes from in [0, 360] deg, the "
                                  "sector's half width in (0, 180] deg (30), the search distance in m > 0 (100)");
        } else if (!strcmp(k, "-maxFlat")) {
            if (!number(v, &max_flat) || max_flat < 0)
                return bad_option(k, v, "a length in m >= 0 (0: the thalweg ends where it stops descending)");
        } else if (!strcmp(k, "-zref")) {
            if (!number(v, &zref))
                return bad_option(k, v, "a finite reference altitude in m");
        } else {
            fprintf(stderr, "%s: unknown option %s\n", prog, k);
            usage(stderr);
            return 2;
        }
        ++i;
    }
    if (!dem_path) {
        fprintf(stderr, "%s: -dem is required\n", prog);
        usage(stderr);
        return 2;
    }
    if (gradient != 0 && isnan(d0star))
        return bad_option("-gradient", "given", "only with -d0");
    if (gradient != 0 && isnan(zref))
        return bad_option("-zref", NULL, "a reference altitude in m when -gradient is not 0");
    if (isnan(zref))
        zref = 0;

    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    gf_raster dem;
    if (gf_raster_read(dem_path, &dem) != GF_SUCCESS) {
        fprintf(stderr, "%s: -dem %s: %s\n", prog, dem_path, gf_error_detail());
        return 1;
    }
    if (mkdir(out, 0777) && errno != EEXIST) {
        fprintf(stderr, "%s: -out %s: cannot create it: %s\n", prog, out, strerror(errno));
        gf_raster_free(&dem);
        return 1;
    }
    size_t nc = (size_t)dem.nx * (size_t)dem.ny;
    unsigned char *mask = NULL;
    int rc = 1;
    gf_pra_set set = {0};
    double *d0 = NULL, *lab = NULL;
    if (forest) {
        mask = malloc(nc);
        if (!mask || !forest_mask(forest, &dem, mask))
            goto done;
    }
    if (gf_pra_delineate(&dem, mask, &p, &set) != GF_SUCCESS) {
        fprintf(stderr, "%s: -dem %s: %s\n", prog, dem_path, gf_error_detail());
        goto done;
    }
    if (!isnan(d0star)) {
        d0 = malloc((set.n + 1) * sizeof *d0);
        if (!d0)
            goto done;
        for (size_t k = 0; k < set.n; ++k)
            if (gf_release_depth(d0star, gradient, set.pra[k].altitude_m, zref, set.pra[k].slope_deg, d0 + k) !=
                GF_SUCCESS) {
                fprintf(stderr, "%s: release area %d (-d0 %g -gradient %g -zref %g): %s\n", prog, set.pra[k].id,
                        d0star, gradient, zref, gf_error_detail());
                goto done;
            }
    }
    char path[4096];
    snprintf(path, sizeof path, "%s/releaseAreas.%s", out, format);
    if (gf_pra_write_polygons(path, strcmp(format, "shp") ? "GPKG" : "ESRI Shapefile", &dem, &set, d0) !=
        GF_SUCCESS) {
        fprintf(stderr, "%s: %s\n", prog, gf_error_detail());
        goto done;
    }
    lab = malloc(nc * sizeof *lab);
    if (!lab)
        goto done;
    for (size_t c = 0; c < nc; ++c)
        lab[c] = set.label[c];
    snprintf(path, sizeof path, "%s/releaseAreas_labels.tif", out);
    if (gf_raster_write(path, "GTiff", &dem, lab) != GF_SUCCESS) {
        fprintf(stderr, "%s: %s\n", prog, gf_error_detail());
        goto done;
    }
    snprintf(path, sizeof path, "%s/releaseAreas.csv", out);
    FILE *f = fopen(path, "w");
    if (!f) {
        fprintf(stderr, "%s: cannot write %s: %s\n", prog, path, strerror(errno));
        goto done;
    }
    double *ws = NULL, *ws_mean = NULL;
    if (!isnan(wind[0])) {
        ws = malloc(nc * sizeof *ws);
        ws_mean = calloc(set.n + 1, sizeof *ws_mean);
        size_t *cnt = calloc(set.n + 1, sizeof *cnt);
        if (!ws || !ws_mean || !cnt || gf_wind_shelter(&dem, wind[0], wind[1], wind[2], ws) != GF_SUCCESS) {
            fprintf(stderr, "%s: -wind %g,%g,%g: %s\n", prog, wind[0], wind[1], wind[2],
                    ws && ws_mean && cnt ? gf_error_detail() : "out of memory");
            free(cnt);
            fclose(f);
            free(ws);
            free(ws_mean);
            goto done;
        }
        for (size_t c = 0; c < nc; ++c)
            if (set.label[c] > 0 && isfinite(ws[c])) {
                ws_mean[set.label[c]] += ws[c];
                ++cnt[set.label[c]];
            }
        for (size_t k = 1; k <= set.n; ++k)
            ws_mean[k] = cnt[k] ? ws_mean[k] / (double)cnt[k] : NAN;
        free(cnt);
        char wpath[4096];
        snprintf(wpath, sizeof wpath, "%s/windShelter.tif", out);
        if (gf_raster_write(wpath, "GTiff", &dem, ws) != GF_SUCCESS) {
            fprintf(stderr, "%s: %s\n", prog, gf_error_detail());
            fclose(f);
            free(ws);
            free(ws_mean);
            goto done;
        }
        free(ws);
    }
    fprintf(f, "id,area_m2,slope_deg,altitude_m,aspect_deg,z_max,x_top,y_top,x_centroid,y_centroid%s%s\n",
            d0 ? ",d0_m" : "", ws_mean ? ",windshelter_deg" : "");
    double total = 0;
    for (size_t k = 0; k < set.n; ++k) {
        const gf_pra *a = &set.pra[k];
        double xt, yt;
        gf_raster_centre(&dem, a->top_col, a->top_row, &xt, &yt);
        fprintf(f, "%d,%.1f,%.2f,%.1f,%.1f,%.2f,%.3f,%.3f,%.3f,%.3f", a->id, a->area_m2, a->slope_deg, a->altitude_m,
                a->aspect_deg, a->z_max, xt, yt, a->x, a->y);
        if (d0)
            fprintf(f, ",%.3f", d0[k]);
        if (ws_mean) {
            if (isfinite(ws_mean[a->id]))
                fprintf(f, ",%.2f", ws_mean[a->id]);
            else
                fputc(',', f);
        }
        fputc('\n', f);
        total += a->area_m2;
    }
    free(ws_mean);
    if (fclose(f)) {
        fprintf(stderr, "%s: cannot write %s\n", prog, path);
        goto done;
    }
    printf("releaseAreas=%zu\nareaTotal_m2=%.0f\n", set.n, total);
    if (do_ab && !alpha_beta(out, &dem, &set, max_climb, max_flat))
        goto done;
    if (compare) {
        gf_polygons rel;
        if (gf_polygons_read(compare, NULL, 1.0, &rel) != GF_SUCCESS) {
            fprintf(stderr, "%s: -compare %s: %s\n", prog, compare, gf_error_detail());
            goto done;
        }
        unsigned char *in = malloc(nc);
        if (!in) {
            gf_polygons_free(&rel);
            goto done;
        }
        gf_polygons_mask(&rel, &dem, in);
        size_t cells = 0, covered = 0;
        unsigned char *hit = calloc(set.n + 1, 1);
        if (!hit) {
            free(in);
            gf_polygons_free(&rel);
            goto done;
        }
        for (size_t c = 0; c < nc; ++c)
            if (in[c]) {
                ++cells;
                covered += set.label[c] > 0;
                hit[set.label[c]] = 1;
            }
        free(in);
        /* the release areas the polygons touch, and their area */
        double touched = 0;
        printf("compareReleases=");
        for (size_t k = 0, first = 1; k < set.n; ++k)
            if (hit[set.pra[k].id]) {
                printf("%s%d", first ? "" : ",", set.pra[k].id);
                touched += set.pra[k].area_m2;
                first = 0;
            }
        printf("\ncompareReleaseArea_m2=%.0f\n", touched);
        free(hit);
        gf_polygons_free(&rel);
        if (!cells) {
            fprintf(stderr, "%s: -compare %s: no cell centre of the DEM lies in its polygons\n", prog, compare);
            goto done;
        }
        printf("compareArea_m2=%.0f\noverlap=%.4f\n", (double)cells * fabs(dem.gt[1] * dem.gt[5]),
               (double)covered / (double)cells);
    }
    clock_gettime(CLOCK_MONOTONIC, &t1);
    printf("seconds=%.2f\n", (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec));
    rc = 0;
done:
    free(mask);
    free(d0);
    free(lab);
    gf_pra_set_free(&set);
    gf_raster_free(&dem);
    return rc;
}
