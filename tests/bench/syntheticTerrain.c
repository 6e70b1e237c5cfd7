/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * syntheticTerrain — a SYNTHETIC alpine DEM for the regional scale bench
 * (tests/bench/run-regional, issue 52): not a real place.
 *
 *   gf_synthetic_terrain -out FILE.tif [-km W H] [-cell M] [-seed S] [-p90 DEG]
 *
 * The elevation is a ridged multifractal (Musgrave's ridged noise: sharp
 * ridges, rounded valley floors, the look of glacially shaped relief) over
 * a regional tilt:
 *
 *     z = 1500 m + A sum_o w_o (1 - |N(f_o x, f_o y)|)^2 + 0.03 x
 *
 * N a smooth value noise in [-1, 1] (a hashed lattice, quintic
 * interpolation), six octaves o from a wavelength of 3 km (f_o = 2^o / 3000
 * 1/m), weights w_o = 0.5^o normalised to 1.  The amplitude A is set so that
 * the 90th percentile of the slope (Horn's, libgranflow's gf_slope_aspect)
 * is -p90 degrees (default 45): alpine DEMs at 5 m have a mean slope near
 * 25-30 deg, 90 % of the cells below 45-50 deg, and a few per cent above 60
 * deg (Swiss Alps, swissALTI3D statistics as reported by Buehler et al.
 * 2018; Veitinger et al. 2016).  Prints the slope statistics it reaches
 * (mean, median, 90th and 99th percentiles, the share of 28-60 deg, the
 * release-area window) and writes a GeoTIFF (float64, a local metric grid
 * with no CRS: the file name and its metadata say SYNTHETIC).
 */
#define _GNU_SOURCE /* M_PI */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "granflow/regional.h"
#include "granflow/terrain.h"

static uint32_t seed_ = 1;

static double lattice(int64_t i, int64_t j)
{
    uint64_t h = (uint64_t)i * 0x9E3779B97F4A7C15ULL ^ (uint64_t)j * 0xC2B2AE3D27D4EB4FULL ^ (uint64_t)seed_ * 0x165667B19E3779F9ULL;
    h ^= h >> 31;
    h *= 0xBF58476D1CE4E5B9ULL;
    h ^= h >> 29;
    return (double)(h >> 11) / 9007199254740992.0 * 2.0 - 1.0;
}

static double fade(double t) { return t * t * t * (t * (t * 6 - 15) + 10); }

static double noise(double x, double y)
{
    const double fx = floor(x), fy = floor(y);
    const int64_t i = (int64_t)fx, j = (int64_t)fy;
    const double u = fade(x - fx), v = fade(y - fy);
    const double a = lattice(i, j), b = lattice(i + 1, j), c = lattice(i, j + 1), d = lattice(i + 1, j + 1);
    return (a + (b - a) * u) + ((c + (d - c) * u) - (a + (b - a) * u)) * v;
}

static int cmp(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int main(int argc, char **argv)
{
    const char *out = NULL;
    double w = 10, h = 10, cell = 5, p90 = 45;
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "-out") && i + 1 < argc) out = argv[++i];
        else if (!strcmp(argv[i], "-km") && i + 2 < argc) w = atof(argv[++i]), h = atof(argv[++i]);
        else if (!strcmp(argv[i], "-cell") && i + 1 < argc) cell = atof(argv[++i]);
        else if (!strcmp(argv[i], "-seed") && i + 1 < argc) seed_ = (uint32_t)atol(argv[++i]);
        else if (!strcmp(argv[i], "-p90") && i + 1 < argc) p90 = atof(argv[++i]);
        else {
            fprintf(stderr, "usage: gf_synthetic_terrain -out FILE.tif [-km W H] [-cell M] [-seed S] [-p90 DEG]\n");
            return 2;
        }
    }
    if (!out || !(w > 0 && h > 0 && cell > 0 && p90 > 5 && p90 < 80)) {
        fprintf(stderr, "gf_synthetic_terrain: -out FILE.tif, -km > 0, -cell > 0, -p90 in (5, 80) needed\n");
        return 2;
    }
    gf_raster g;
    memset(&g, 0, sizeof g);
    g.nx = (int)lround(w * 1000 / cell), g.ny = (int)lround(h * 1000 / cell);
    g.gt[0] = 600000, g.gt[1] = cell, g.gt[3] = 200000 + g.ny * cell, g.gt[5] = -cell;
    g.nodata = -9999;
    g.wkt = (char *)"";
    const size_t n = (size_t)g.nx * (size_t)g.ny;
    double *r = malloc(n * sizeof *r), *z = malloc(n * sizeof *z), *s = malloc(n * sizeof *s);
    if (!r || !z || !s) return 1;
    double wsum = 0;
    for (int o = 0; o < 6; ++o) wsum += pow(0.5, o);
    for (int jj = 0; jj < g.ny; ++jj)
        for (int ii = 0; ii < g.nx; ++ii) {
            const double x = ii * cell, y = (g.ny - 1 - jj) * cell;
            double v = 0;
            for (int o = 0; o < 6; ++o) {
                const double f = pow(2, o) / 3000.0, q = 1 - fabs(noise(f * x + 17.3 * o, f * y - 7.1 * o));
                v += pow(0.5, o) * q * q;
            }
            r[(size_t)jj * (size_t)g.nx + (size_t)ii] = v / wsum;
        }
    /* the amplitude: tan(slope) scales with it; two passes make the 90th percentile p90 */
    double amp = 1000;
    double st[5] = {0};
    for (int pass = 0; pass < 2; ++pass) {
        for (int jj = 0; jj < g.ny; ++jj)
            for (int ii = 0; ii < g.nx; ++ii) {
                const size_t c = (size_t)jj * (size_t)g.nx + (size_t)ii;
                z[c] = 1500 + amp * r[c] + 0.03 * ii * cell;
            }
        g.z = z;
        if (gf_slope_aspect(&g, s, NULL)) return 1;
        size_t m = 0;
        double mean = 0, pra = 0;
        for (size_t c = 0; c < n; ++c)
            if (isfinite(s[c])) {
                mean += s[c];
                pra += s[c] >= 28 && s[c] <= 60;
                s[m++] = s[c];
            }
        qsort(s, m, sizeof *s, cmp);
        st[0] = mean / (double)m, st[1] = s[m / 2], st[2] = s[(size_t)(0.9 * (double)m)], st[3] = s[(size_t)(0.99 * (double)m)];
        st[4] = pra / (double)m;
        if (pass == 0) amp *= tan(p90 * M_PI / 180) / tan(st[2] * M_PI / 180);
    }
    double zmin = INFINITY, zmax = -INFINITY;
    for (size_t c = 0; c < n; ++c) zmin = fmin(zmin, z[c]), zmax = fmax(zmax, z[c]);
    if (gf_raster_write(out, "GTiff", &g, z)) {
        fprintf(stderr, "gf_synthetic_terrain: %s: %s\n", out, gf_error_detail());
        return 1;
    }
    printf("SYNTHETIC terrain %s: %d x %d cells of %g m (%.1f km2), seed %u, ridged multifractal amplitude %.0f m, "
           "elevation %.0f .. %.0f m\n",
           out, g.nx, g.ny, cell, (double)n * cell * cell / 1e6, seed_, amp, zmin, zmax);
    printf("slope: mean %.1f deg, median %.1f, 90th percentile %.1f, 99th %.1f; %.1f %% of the cells in 28-60 deg\n", st[0],
           st[1], st[2], st[3], 100 * st[4]);
    printf("synthetic_km2=%.2f\nslope_mean=%.2f\nslope_p90=%.2f\nslope_p99=%.2f\nshare_28_60=%.4f\n",
           (double)n * cell * cell / 1e6, st[0], st[2], st[3], st[4]);
    free(r), free(z), free(s);
    return 0;
}
