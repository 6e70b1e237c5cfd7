/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The path analysis of peak rasters (granflow/path_analysis.h;
 * doc/theory/hazard-analysis.md sections 1-3) against closed forms: synthetic
 * DEMs and fields written with GDAL (GeoTIFF, float64) into a temporary
 * folder and read back as any raster is.
 *
 * The straight cases: a DEM of 151 x 61 pixels of h = 2 m, lower-left
 * corner (0, 0), pixel centres (1 + 2c, 1 + 2r) (r counted from the south),
 * and the path from (11, 61) east to (291, 61): its points s_i = 2i lie on
 * pixel centres (x = 11 + s), its cross-sections run north (l > 0 on the
 * left looking east), so every grid point is a pixel centre and every value
 * exact. */
#include "../gf_test.h"

#include "granflow/path_analysis.h"
#include "granflow/constants.h"
#include "granflow/terrain.h"

#include <cpl_conv.h>
#include <gdal.h>

#include <unistd.h>

#ifndef GF_SOURCE_DIR
#error "GF_SOURCE_DIR must point at the granflow checkout"
#endif

#include "../gf_tmpdir.h"
GF_TMPDIR_FIXTURES("gf_path")

enum { NX = 151, NY = 61 };
#define H 2.0

/* a raster of nx x ny pixels of cell, lower-left corner (x0, y0), with
 * values f(x, y) at the pixel centres (NAN -> NODATA), written with GDAL as
 * GeoTIFF and read back */
static void make_raster_on(const char *name, int nx, int ny, double x0, double y0, double cell,
                           double (*f)(double, double), gf_raster *out)
{
    gf_raster g = {0};
    g.nx = nx, g.ny = ny;
    const double gt[6] = {x0, cell, 0.0, y0 + ny * cell, 0.0, -cell};
    memcpy(g.gt, gt, sizeof gt);
    g.nodata = -9999.0;
    g.wkt = (char *)"";
    double *v = malloc(sizeof(double) * (size_t)nx * (size_t)ny);
    assert_non_null(v);
    for (int r = 0; r < ny; ++r)
        for (int c = 0; c < nx; ++c) {
            double x, y;
            gf_raster_centre(&g, c, r, &x, &y);
            v[(size_t)r * nx + c] = f(x, y);
        }
    const char *path = tmp(name);
    assert_int_equal(gf_raster_write(path, "GTiff", &g, v), GF_SUCCESS);
    free(v);
    assert_int_equal(gf_raster_read(path, out), GF_SUCCESS);
}

/* a raster on the test grid (nx x ny pixels of H, lower-left corner (0, 0)) */
static void make_raster(const char *name, int nx, int ny, double (*f)(double, double), gf_raster *out)
{
    make_raster_on(name, nx, ny, 0.0, 0.0, H, f, out);
}

static double plane(double x, double y) { (void)y; return 300.0 - 0.5 * x; }
/* the plane down to x = 151, flat beyond */
static double kinked(double x, double y) { return x < 151.0 ? plane(x, y) : plane(151.0, y); }

/* ppr: reached (> 1) for 51 <= x <= 201, |y - 61| <= 10, largest on the
 * path's line y = 61; shifted by dx along x */
static double shift_dx = 0.0;
static double block(double x, double y)
{
    const double d = fabs(y - 61.0);
    return x >= 51.0 + shift_dx - 1e-9 && x <= 201.0 + shift_dx + 1e-9 && d <= 10.0 + 1e-9 ? 10.0 - 0.1 * d : 0.0;
}
/* pfv: 0.1 x where the block is reached */
static double speed(double x, double y) { return block(x, y) > 1.0 ? 0.1 * x : 0.0; }

static const double straight[4] = {11.0, 61.0, 291.0, 61.0};

static void expect_detail(const char *a, const char *b)
{
    const char *d = gf_error_detail();
    if (!strstr(d, a) || (b && !strstr(d, b)))
        fail_msg("detail '%s' lacks '%s' or '%s'", d, a, b ? b : "");
}

/* Sections 1-2 on the inclined plane z = 300 - x/2: the grid has one point
 * per cell along s (141 over 280 m) and 21 across w = 40 m, cells of h^2;
 * the block reached from x = 51 to 201 gives sStart 40 m, sRunout 190 m at
 * (201, 61), deltaZ 75 m, deltaSXY 150 m, runout angle atan(1/2) =
 * 26.565 deg exactly; MMA 10 kPa, AMA 10 kPa; for pfv = x/10 MMA 20.1 and
 * AMA (5.1 + 20.1)/2 = 12.6 */
static void straight_path_on_a_plane_gives_the_exact_runout_and_angle(void **state)
{
    (void)state;
    gf_raster dem, ppr, pfv;
    make_raster("plane.tif", NX, NY, plane, &dem);
    shift_dx = 0.0;
    make_raster("ppr.tif", NX, NY, block, &ppr);
    make_raster("pfv.tif", NX, NY, speed, &pfv);
    gf_path_grid g;
    assert_int_equal(gf_path_grid_make(&dem, 2, straight, 40.0, &g), GF_SUCCESS);
    assert_int_equal(g.ns, 141);
    assert_int_equal(g.nl, 21);
    assert_int_equal(g.reversed, 0);
    assert_close(g.s[140], 280.0, 1e-12);
    assert_close(g.l[0], -20.0, 1e-12);
    for (size_t i = 0; i < g.ns; ++i) {
        assert_close(g.xp[i], 11.0 + 2.0 * i, 1e-9);
        assert_close(g.zp[i], plane(g.xp[i], 61.0), 1e-9);
        assert_close(g.nx[i], 0.0, 1e-15);
        assert_close(g.ny[i], 1.0, 1e-15);
        for (size_t j = 0; j < g.nl; ++j)
            assert_close(g.area[i * g.nl + j], H * H, 1e-9);
    }
    const size_t N = g.ns * g.nl;
    double *a = malloc(N * sizeof *a), *v = malloc(N * sizeof *v);
    double cmax[141], cmean[141];
    gf_path_sample(&g, &ppr, a);
    gf_path_sample(&g, &pfv, v);
    gf_path_profiles(&g, a, cmax, cmean);
    assert_close(cmax[20], 10.0, 1e-12);           /* x = 51 */
    assert_close(cmean[20], (11 * 10.0 - 0.1 * 2 * (2 + 4 + 6 + 8 + 10)) / 21.0, 1e-12);
    assert_close(cmax[19], 0.0, 0);
    gf_runout r;
    assert_int_equal(gf_path_runout(&g, a, 1.0, &r), GF_SUCCESS);
    assert_close(r.s_start, 40.0, 1e-9);
    assert_close(r.s_runout, 190.0, 1e-9);
    assert_close(r.x_runout, 201.0, 1e-9);
    assert_close(r.y_runout, 61.0, 1e-9);
    assert_close(r.delta_sxy, 150.0, 1e-9);
    assert_close(r.delta_z, 75.0, 1e-9);
    assert_close(r.angle, atan(0.5) * 180.0 / GF_PI, 1e-9);
    double mma, ama;
    gf_path_indicators(&g, cmax, &r, &mma, &ama);
    assert_close(mma, 10.0, 1e-12);
    assert_close(ama, 10.0, 1e-12);
    gf_path_profiles(&g, v, cmax, cmean);
    gf_path_indicators(&g, cmax, &r, &mma, &ama);
    assert_close(mma, 20.1, 1e-9);
    assert_close(ama, 12.6, 1e-9);
    /* nothing above 20 kPa: refused with the largest value */
    assert_int_equal(gf_path_runout(&g, a, 20.0, &r), GF_EDOM);
    expect_detail("threshold 20", "the largest is 10");
    free(a), free(v);
    gf_path_grid_free(&g);

    /* the path drawn upwards is turned round; off the pixel centres (the
     * line y = 60, vertices at x = 10 and 290) the block's edge x = 201 is
     * interpolated to 10 -> 0 at x = 203: ppr > 1 up to x = 202.8, the last
     * grid point x = 202 (s = 192), within one cell of the edge */
    const double up[4] = {290.0, 60.0, 10.0, 60.0};
    assert_int_equal(gf_path_grid_make(&dem, 2, up, 40.0, &g), GF_SUCCESS);
    assert_int_equal(g.reversed, 1);
    assert_close(g.xp[0], 10.0, 1e-12);
    a = malloc(g.ns * g.nl * sizeof *a);
    gf_path_sample(&g, &ppr, a);
    assert_int_equal(gf_path_runout(&g, a, 1.0, &r), GF_SUCCESS);
    assert_close(r.s_runout, 192.0, 1e-9);
    assert_close(r.s_start, 40.0, 1e-9); /* x = 50: the first grid point past x = 49.2 */
    assert_true(fabs(r.x_runout - 201.0) <= H);
    free(a);
    gf_path_grid_free(&g);
    gf_raster_free(&dem), gf_raster_free(&ppr), gf_raster_free(&pfv);
}

/* Section 1 on a circular arc of radius R = 100 m about (151, 151), a
 * quarter circle from the north (theta = 90 deg) clockwise to the east,
 * given as 2001 vertices: the points lie on the circle at theta = 90 deg -
 * s/R (s = R theta), the cross-sections are radial (l > 0 on the left
 * of the clockwise path: outwards, radius R + l), cell areas h^2 (R + l)/R;
 * a field reached
 * for theta >= 30 deg has sRunout = R (60 deg) within one cell */
static double bowl(double x, double y) { return 1000.0 - 0.2 * x - 0.1 * y; }
static double arc_field(double x, double y)
{
    const double th = atan2(y - 151.0, x - 151.0), r = hypot(x - 151.0, y - 151.0);
    return th >= GF_PI / 6.0 && fabs(r - 100.0) <= 20.0 ? 5.0 : 0.0;
}

static void circular_arc_path_has_s_equal_r_theta(void **state)
{
    (void)state;
    gf_raster dem, f;
    make_raster("bowl.tif", 151, 151, bowl, &dem);
    make_raster("arc.tif", 151, 151, arc_field, &f);
    enum { NV = 2001 };
    static double xy[2 * NV];
    const double R = 100.0;
    for (int k = 0; k < NV; ++k) {
        const double th = GF_PI / 2.0 * (1.0 - (double)k / (NV - 1));
        xy[2 * k] = 151.0 + R * cos(th), xy[2 * k + 1] = 151.0 + R * sin(th);
    }
    gf_path_grid g;
    assert_int_equal(gf_path_grid_make(&dem, NV, xy, 40.0, &g), GF_SUCCESS);
    assert_int_equal(g.reversed, 0); /* z falls from (151, 251) to (251, 151) */
    assert_close(g.length, R * GF_PI / 2.0, 1e-5);
    assert_int_equal(g.ns, (size_t)floor(R * GF_PI / 2.0 / H) + 1);
    for (size_t i = 0; i < g.ns; ++i) {
        const double th = GF_PI / 2.0 - g.s[i] / R;
        assert_close(g.xp[i], 151.0 + R * cos(th), 1e-4);
        assert_close(g.yp[i], 151.0 + R * sin(th), 1e-4);
        for (size_t j = 0; j < g.nl && i > 0 && i + 1 < g.ns; ++j) {
            const size_t k = i * g.nl + j;
            /* clockwise: the left is outwards, radius R + l (at the two ends
             * the one segment's normal is half a step off the radius) */
            const double rad = hypot(g.x[k] - 151.0, g.y[k] - 151.0);
            assert_close(rad, R + g.l[j], 1e-4);
            assert_close(atan2(g.y[k] - 151.0, g.x[k] - 151.0), th, 1e-6);
            if (i > 1 && i + 2 < g.ns) /* the centred differences use the ends' sections */
                assert_close(g.area[k], H * H * (R + g.l[j]) / R, 1e-3 * H * H);
        }
    }
    double *a = malloc(g.ns * g.nl * sizeof *a);
    gf_path_sample(&g, &f, a);
    gf_runout r;
    assert_int_equal(gf_path_runout(&g, a, 1.0, &r), GF_SUCCESS);
    assert_close(r.s_start, 0.0, 0);
    assert_true(fabs(r.s_runout - R * GF_PI / 3.0) <= H);
    free(a);
    gf_path_grid_free(&g);
    gf_raster_free(&dem), gf_raster_free(&f);
}

/* NODATA: a field NODATA for x > 231 (beyond the runout) and in the pixel
 * (101, 71): NAN at grid points on it and between it and its neighbours,
 * left out of the cross-section maximum and mean; the runout is the same.
 * A DEM with NODATA under the path is refused naming the point. */
static double holed(double x, double y)
{
    if (x > 231.0 || (fabs(x - 101.0) < 1e-9 && fabs(y - 71.0) < 1e-9))
        return NAN;
    return block(x, y);
}
static double holed_dem(double x, double y) { return fabs(x - 151.0) < 1.5 && fabs(y - 61.0) < 1.5 ? NAN : plane(x, y); }

static void nodata_is_nan_and_not_reached(void **state)
{
    (void)state;
    gf_raster dem, f, bad;
    make_raster("plane.tif", NX, NY, plane, &dem);
    shift_dx = 0.0;
    make_raster("holed.tif", NX, NY, holed, &f);
    assert_true(isnan(gf_raster_bilinear(&f, 101.0, 71.0)));
    assert_true(isnan(gf_raster_bilinear(&f, 100.0, 70.0)));   /* weight on the hole */
    assert_close(gf_raster_bilinear(&f, 99.0, 71.0), 9.0, 1e-12); /* the neighbour, exactly */
    assert_true(isnan(gf_raster_bilinear(&f, 0.5, 30.0)));     /* outside the pixel centres */
    gf_path_grid g;
    assert_int_equal(gf_path_grid_make(&dem, 2, straight, 40.0, &g), GF_SUCCESS);
    double *a = malloc(g.ns * g.nl * sizeof *a);
    double cmax[141], cmean[141];
    gf_path_sample(&g, &f, a);
    const size_t i101 = 45; /* x = 101 */
    assert_true(isnan(a[i101 * g.nl + 15])); /* l = 10: y = 71 */
    gf_path_profiles(&g, a, cmax, cmean);
    assert_close(cmax[i101], 10.0, 1e-12);
    /* 20 valid values: 10 - 0.1 |l|, |l| <= 10 without l = 10 (9.0) */
    assert_close(cmean[i101], (11 * 10.0 - 0.1 * 2 * (2 + 4 + 6 + 8 + 10) - 9.0) / 20.0, 1e-12);
    assert_true(isnan(cmax[140]) && isnan(cmean[140])); /* x = 291: all NODATA */
    gf_runout r;
    assert_int_equal(gf_path_runout(&g, a, 1.0, &r), GF_SUCCESS);
    assert_close(r.s_runout, 190.0, 1e-9);
    free(a);
    gf_path_grid_free(&g);
    make_raster("holeddem.tif", NX, NY, holed_dem, &bad);
    assert_int_equal(gf_path_grid_make(&bad, 2, straight, 40.0, &g), GF_EDOM);
    expect_detail("NODATA", "140.0 m along it");
    assert_null(g.s);
    gf_raster_free(&bad), gf_raster_free(&dem), gf_raster_free(&f);
}

/* A path leaving the DEM (a vertex at x = 400, beyond the last pixel centre
 * 301), too short, one point, a zero width: refused with the reason */
static void path_leaving_the_dem_is_refused(void **state)
{
    (void)state;
    gf_raster dem;
    make_raster("plane.tif", NX, NY, plane, &dem);
    gf_path_grid g;
    const double off[6] = {11.0, 61.0, 291.0, 61.0, 400.0, 61.0};
    assert_int_equal(gf_path_grid_make(&dem, 3, off, 40.0, &g), GF_EDOM);
    expect_detail("vertex 2 at (400.00, 61.00): outside the DEM", "pixel centres x 1.00 .. 301.00");
    assert_null(g.s);
    const double shrt[4] = {11.0, 61.0, 13.0, 61.0};
    assert_int_equal(gf_path_grid_make(&dem, 2, shrt, 40.0, &g), GF_EDOM);
    expect_detail("at least two cell sizes", NULL);
    assert_int_equal(gf_path_grid_make(&dem, 1, straight, 40.0, &g), GF_EDOM);
    expect_detail("at least 2", NULL);
    assert_int_equal(gf_path_grid_make(&dem, 2, straight, 0.0, &g), GF_EDOM);
    expect_detail("domain width 0", NULL);
    gf_raster_free(&dem);
}

/* Section 3: the run is the reference shifted 10 m (5 cells) down the
 * path.  Over the whole grid: TP = 71 sections x 11 cells x 4 m2 = 3124,
 * FP = FN = 5 x 11 x 4 = 220, TN = 141 x 21 x 4 - 3564 = 8280, A_ref =
 * 3344; from x = 101 (i = 45) on: TP 2244, FN 0, FP 220.  Identical runs:
 * TP / A_ref = 1, FP = FN = 0.  Rasters on another grid are told apart. */
static void shifted_runs_give_the_known_tp_fp_fn_areas(void **state)
{
    (void)state;
    gf_raster dem, ref, run, other;
    make_raster("plane.tif", NX, NY, plane, &dem);
    shift_dx = 0.0;
    make_raster("ref.tif", NX, NY, block, &ref);
    shift_dx = 10.0;
    make_raster("run.tif", NX, NY, block, &run);
    shift_dx = 0.0;
    gf_path_grid g;
    assert_int_equal(gf_path_grid_make(&dem, 2, straight, 40.0, &g), GF_SUCCESS);
    const size_t N = g.ns * g.nl;
    double *a = malloc(N * sizeof *a), *b = malloc(N * sizeof *b);
    gf_path_sample(&g, &run, a);
    gf_path_sample(&g, &ref, b);
    gf_path_areas ar;
    gf_path_compare(&g, a, b, 1.0, 0, &ar);
    assert_close(ar.tp, 3124.0, 1e-9);
    assert_close(ar.fp, 220.0, 1e-9);
    assert_close(ar.fn, 220.0, 1e-9);
    assert_close(ar.tn, 8280.0, 1e-9);
    assert_close(ar.a_ref, 3344.0, 1e-9);
    gf_path_compare(&g, a, b, 1.0, 45, &ar);
    assert_close(ar.tp, 2244.0, 1e-9);
    assert_close(ar.fn, 0.0, 0);
    assert_close(ar.fp, 220.0, 1e-9);
    unsigned char *cls = malloc(N);
    gf_path_compare_map(&g, a, b, 1.0, 45, cls);
    assert_int_equal(cls[44 * g.nl + 10], 0);     /* above the runout area */
    assert_int_equal(cls[45 * g.nl + 10], 1);     /* x = 101 on the path: TP */
    assert_int_equal(cls[(size_t)100 * g.nl + 10], 2); /* x = 211: FP */
    assert_int_equal(cls[45 * g.nl + 0], 4);      /* l = -20: TN */
    gf_path_compare_map(&g, a, b, 1.0, 0, cls);
    assert_int_equal(cls[20 * g.nl + 10], 3);     /* x = 51: FN */
    gf_runout ra, rb;
    assert_int_equal(gf_path_runout(&g, a, 1.0, &ra), GF_SUCCESS);
    assert_int_equal(gf_path_runout(&g, b, 1.0, &rb), GF_SUCCESS);
    assert_close(ra.s_runout - rb.s_runout, 10.0, 1e-9);
    /* identical runs */
    gf_path_compare(&g, b, b, 1.0, 0, &ar);
    assert_close(ar.tp / ar.a_ref, 1.0, 1e-15);
    assert_close(ar.fp, 0.0, 0);
    assert_close(ar.fn, 0.0, 0);
    /* grids */
    assert_int_equal(gf_raster_same_grid(&ref, &run), 1);
    make_raster("other.tif", NX + 1, NY, block, &other);
    assert_int_equal(gf_raster_same_grid(&ref, &other), 0);
    other.nx = NX, other.gt[0] += 1.0;
    assert_int_equal(gf_raster_same_grid(&ref, &other), 0);
    free(a), free(b), free(cls);
    gf_path_grid_free(&g);
    gf_raster_free(&dem), gf_raster_free(&ref), gf_raster_free(&run), gf_raster_free(&other);
}

/* Rasters on different grids (AvaFrame's remeshed 5 m rasters against
 * granflow's on the DEM's grid): each is sampled onto the (s, l) grid with
 * its own georeferencing.  A bent path (21, 101) -> (151, 71) -> (281, 31)
 * with a domain width of 60 m on the plane DEM (grid A: 2 m, corner (0,
 * 0)), so the grid points fall between pixel centres and the first
 * cross-sections leave the DEM (y > 121); grid B: 3 m cells, corner (-4.3,
 * -2.7), 104 x 46 pixels, covering all of the (s, l) grid; grid C: 2.5 m
 * cells, corner (100.2, -1.1), covering the DEM only from x = 101.45 (its
 * first pixel centre) on.
 *  * a linear field given on A and on B: bilinear interpolation is exact for
 *    it, so both samples equal the field to 1e-9 at every grid point on A,
 *    B's also beyond the DEM (A's are NAN there);
 *  * C misses the path points with x < 101.45 and the grid points there
 *    (gf_path_coverage counts them; its samples are NAN there);
 *  * the comparison of a paraboloid cap f = 10 - r^2 / (2 R), R = 50 m,
 *    threshold 1 (a disc of radius 30 m) with the cap shifted 10 m east:
 *    the bilinear error of f is at most (h^2 / 8)(f_xx + f_yy) = h^2 / (4R)
 *    (0.02 on A, 0.045 on B), so a cell changes class between the one-grid
 *    comparison (run and reference on A) and the two-grid one (the
 *    reference on B) only where the exact run or reference value lies
 *    within that bound of the threshold; TP, FP and FN agree to those
 *    cells' area (under 3 % of A_ref), and with the exact classes.  The
 *    cap against itself on the other grid: FP and FN only in those cells. */
static double lin(double x, double y) { return 7.0 + 0.25 * x - 0.4 * y; }
static double cap_x = 0.0;
static double cap(double x, double y)
{
    const double dx = x - cap_x, dy = y - 51.0;
    return 10.0 - (dx * dx + dy * dy) / 100.0;
}

static void rasters_on_different_grids_are_sampled_each_on_its_own(void **state)
{
    (void)state;
    gf_raster dem, la, lb, lc, run_a, ref_a, ref_b, run_b;
    make_raster("plane.tif", NX, NY, plane, &dem);
    const double bent[6] = {21.0, 101.0, 151.0, 71.0, 281.0, 31.0};
    gf_path_grid g;
    assert_int_equal(gf_path_grid_make(&dem, 3, bent, 60.0, &g), GF_SUCCESS);
    const size_t N = g.ns * g.nl;
    make_raster("lin_a.tif", NX, NY, lin, &la);
    make_raster_on("lin_b.tif", 104, 46, -4.3, -2.7, 3.0, lin, &lb);
    make_raster_on("lin_c.tif", 82, 50, 100.2, -1.1, 2.5, lin, &lc);
    assert_int_equal(gf_raster_same_grid(&la, &lb), 0);
    double *a = malloc(N * sizeof *a), *b = malloc(N * sizeof *b), *c = malloc(N * sizeof *c);
    gf_path_sample(&g, &la, a);
    gf_path_sample(&g, &lb, b);
    gf_path_sample(&g, &lc, c);
    size_t on_dem = 0, off_a = 0;
    for (size_t k = 0; k < N; ++k) {
        const double exact = lin(g.x[k], g.y[k]);
        assert_close(b[k], exact, 1e-9); /* B covers the whole grid */
        if (gf_raster_covers(&dem, g.x[k], g.y[k])) {
            ++on_dem;
            assert_close(a[k], exact, 1e-9);
        } else {
            ++off_a;
            assert_true(isnan(a[k]));
        }
        if (gf_raster_covers(&lc, g.x[k], g.y[k]))
            assert_close(c[k], exact, 1e-9);
        else
            assert_true(isnan(c[k]) && g.x[k] < 101.45 + 1e-6);
    }
    assert_true(on_dem > N / 2 && off_a > 0); /* the ends' cross-sections leave the DEM */
    gf_path_cover cv;
    gf_path_coverage(&g, &lb, &dem, &cv);
    assert_int_equal(cv.n_grid, on_dem);
    assert_int_equal(cv.n_out, 0);
    assert_int_equal(cv.n_path_out, 0);
    assert_true(isnan(cv.s_min) && isnan(cv.path_s_min));
    gf_path_coverage(&g, &la, NULL, &cv);
    assert_int_equal(cv.n_grid, N);
    assert_int_equal(cv.n_out, off_a);
    gf_path_coverage(&g, &lc, &dem, &cv);
    size_t path_out = 0, grid_out = 0;
    double area_out = 0.0, s_last = -1.0;
    for (size_t i = 0; i < g.ns; ++i) {
        if (g.xp[i] < 101.45 - 1e-9)
            ++path_out, s_last = g.s[i];
        for (size_t j = 0; j < g.nl; ++j) {
            const size_t k = i * g.nl + j;
            if (gf_raster_covers(&dem, g.x[k], g.y[k]) && g.x[k] < 101.45 - 1e-9)
                ++grid_out, area_out += g.area[k];
        }
    }
    assert_true(path_out > 0);
    assert_int_equal(cv.n_path_out, path_out);
    assert_close(cv.path_s_min, 0.0, 0);
    assert_close(cv.path_s_max, s_last, 0);
    assert_int_equal(cv.n_out, grid_out);
    assert_close(cv.area_out, area_out, 1e-6);
    assert_close(cv.s_min, 0.0, 0);

    /* the comparison: the cap on the path's second leg (216, 51), the
     * reference 10 m west of the run */
    cap_x = 226.0;
    make_raster("cap_run_a.tif", NX, NY, cap, &run_a);
    make_raster_on("cap_run_b.tif", 104, 46, -4.3, -2.7, 3.0, cap, &run_b);
    cap_x = 216.0;
    make_raster("cap_ref_a.tif", NX, NY, cap, &ref_a);
    make_raster_on("cap_ref_b.tif", 104, 46, -4.3, -2.7, 3.0, cap, &ref_b);
    double *ra = malloc(N * sizeof *ra), *fa = malloc(N * sizeof *fa), *fb = malloc(N * sizeof *fb),
           *rb = malloc(N * sizeof *rb);
    gf_path_sample(&g, &run_a, ra);
    gf_path_sample(&g, &run_b, rb);
    gf_path_sample(&g, &ref_a, fa);
    gf_path_sample(&g, &ref_b, fb);
    const double thr = 1.0, err_a = H * H / 200.0 + 1e-9, err_b = 3.0 * 3.0 / 200.0 + 1e-9;
    gf_path_areas one, two, exact = {0}, self;
    gf_path_compare(&g, ra, fa, thr, 0, &one);
    gf_path_compare(&g, ra, fb, thr, 0, &two);
    gf_path_compare(&g, ra, rb, thr, 0, &self);
    double near = 0.0, near_self = 0.0; /* the cells whose class the resampling may change */
    for (size_t k = 0; k < N; ++k) {
        cap_x = 226.0;
        const double er = cap(g.x[k], g.y[k]);
        cap_x = 216.0;
        const double ef = cap(g.x[k], g.y[k]);
        const int in_r = er > thr, in_f = ef > thr;
        exact.tp += in_r && in_f ? g.area[k] : 0.0;
        exact.fp += in_r && !in_f ? g.area[k] : 0.0;
        exact.fn += !in_r && in_f ? g.area[k] : 0.0;
        if (fabs(er - thr) <= err_a || fabs(ef - thr) <= err_b)
            near += g.area[k];
        if (fabs(er - thr) <= err_b)
            near_self += g.area[k];
    }
    exact.a_ref = exact.tp + exact.fn;
    assert_true(exact.tp > 1000.0 && exact.fp > 100.0 && exact.fn > 100.0);
    assert_true(near < 0.03 * exact.a_ref);
    assert_true(fabs(two.tp - one.tp) <= near && fabs(two.fp - one.fp) <= near &&
                fabs(two.fn - one.fn) <= near);
    assert_true(fabs(two.tp - exact.tp) <= near && fabs(two.fp - exact.fp) <= near &&
                fabs(two.fn - exact.fn) <= near);
    assert_true(fabs(one.tp - exact.tp) <= near && fabs(one.fp - exact.fp) <= near &&
                fabs(one.fn - exact.fn) <= near);
    assert_true(self.fp + self.fn <= near_self && self.tp >= self.a_ref - near_self);
    free(a), free(b), free(c), free(ra), free(fa), free(fb), free(rb);
    gf_path_grid_free(&g);
    gf_raster_free(&dem), gf_raster_free(&la), gf_raster_free(&lb), gf_raster_free(&lc);
    gf_raster_free(&run_a), gf_raster_free(&ref_a), gf_raster_free(&ref_b), gf_raster_free(&run_b);
}

/* Section 2, runout area: on the plane that turns flat at x = 151, the
 * slope (centred differences) at x = 151 is atan(1/4) = 14 deg and 0 from
 * x = 153 on: the beta point below a split point at x = 101 is x = 153 (s =
 * 142 m); a split point already on the flat is its own beta point; with
 * dsMin longer than the flat part, or on the plane alone, there is none */
static void beta_point_is_where_the_slope_stays_below_ten_degrees(void **state)
{
    (void)state;
    gf_raster dem, pl;
    make_raster("kinked.tif", NX, NY, kinked, &dem);
    gf_path_grid g;
    assert_int_equal(gf_path_grid_make(&dem, 2, straight, 40.0, &g), GF_SUCCESS);
    double d;
    const size_t isplit = gf_path_snap(&g, 101.3, 70.0, &d);
    assert_int_equal(isplit, 45);
    assert_close(d, hypot(0.3, 9.0), 1e-9);
    size_t ib = 0;
    assert_int_equal(gf_path_beta_point(&g, isplit, 10.0, 30.0, &ib), GF_SUCCESS);
    assert_close(g.s[ib], 142.0, 1e-9);
    assert_int_equal(gf_path_beta_point(&g, 80, 10.0, 30.0, &ib), GF_SUCCESS);
    assert_int_equal(ib, 80);
    /* the flat part is 291 - 153 = 138 m long */
    assert_int_equal(gf_path_beta_point(&g, isplit, 10.0, 140.0, &ib), GF_EDOM);
    expect_detail("below 10 deg for 140 m", NULL);
    gf_path_grid_free(&g);
    make_raster("plane.tif", NX, NY, plane, &pl);
    assert_int_equal(gf_path_grid_make(&pl, 2, straight, 40.0, &g), GF_SUCCESS);
    assert_int_equal(gf_path_beta_point(&g, 0, 10.0, 30.0, &ib), GF_EDOM);
    /* steeper threshold than the plane (26.6 deg): its first point */
    assert_int_equal(gf_path_beta_point(&g, 0, 30.0, 30.0, &ib), GF_SUCCESS);
    assert_int_equal(ib, 0);
    gf_path_grid_free(&g);
    gf_raster_free(&dem), gf_raster_free(&pl);
}

/* Paths and points through OGR: AvaFrame's avaKot path (14 vertices) and
 * split point; a GeoJSON polygon is not a path, a line is not a point, a
 * missing file is refused naming it */
static void paths_and_points_are_read_through_ogr(void **state)
{
    (void)state;
    size_t n;
    double *xy;
    assert_int_equal(gf_path_read(GF_SOURCE_DIR "/tutorials/avaKot/Inputs/LINES/path_aimec.shp", &n, &xy),
                     GF_SUCCESS);
    assert_int_equal(n, 14);
    assert_close(xy[0], 177853.293296122, 1e-6);
    assert_close(xy[27], 378531.456174702, 1e-6);
    free(xy);
    double x, y;
    assert_int_equal(gf_point_read(GF_SOURCE_DIR "/tutorials/avaKot/Inputs/POINTS/splitPoint.shp", &x, &y),
                     GF_SUCCESS);
    assert_close(x, 178342.713179185, 1e-6);
    assert_close(y, 377698.857655861, 1e-6);
    const char *poly = tmp("poly.geojson");
    FILE *f = fopen(poly, "w");
    assert_non_null(f);
    fputs("{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\",\"properties\":{},"
          "\"geometry\":{\"type\":\"Polygon\",\"coordinates\":[[[0,0],[1,0],[1,1],[0,0]]]}}]}", f);
    fclose(f);
    assert_int_equal(gf_path_read(poly, &n, &xy), GF_EDOM);
    expect_detail(poly, "not a line");
    assert_null(xy);
    const char *line = tmp("line.geojson");
    f = fopen(line, "w");
    assert_non_null(f);
    fputs("{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\",\"properties\":{},"
          "\"geometry\":{\"type\":\"LineString\",\"coordinates\":[[0,0],[10,5]]}}]}", f);
    fclose(f);
    assert_int_equal(gf_path_read(line, &n, &xy), GF_SUCCESS);
    assert_int_equal(n, 2);
    free(xy);
    assert_int_equal(gf_point_read(line, &x, &y), GF_EDOM);
    expect_detail(line, "not a point");
    assert_int_equal(gf_path_read(tmp("nopath.shp"), &n, &xy), GF_EIO);
    expect_detail("nopath.shp", "no such file");
}

/* gf_path_locate: on an L-shaped path (0,0) -> (10,0) -> (10,10) a point
 * left of the first leg, right of the second, beyond the end, and at the
 * corner's outside */
static void points_are_located_along_and_across_the_path(void **state)
{
    (void)state;
    const double xy[6] = {0, 0, 10, 0, 10, 10};
    double s, l;
    gf_path_locate(3, xy, 4, 3, &s, &l);
    assert_close(s, 4, 1e-12);
    assert_close(l, 3, 1e-12); /* left of +x */
    gf_path_locate(3, xy, 12, 6, &s, &l);
    assert_close(s, 16, 1e-12);
    assert_close(l, -2, 1e-12); /* right of +y */
    gf_path_locate(3, xy, 10, 13, &s, &l);
    assert_close(s, 20, 1e-12);
    assert_close(l, 3, 1e-12); /* beyond the end: distance to the end point, on the left side */
    gf_path_locate(3, xy, 13, -4, &s, &l);
    assert_close(s, 10, 1e-12);
    assert_close(l, -5, 1e-12); /* the corner, from outside (right of the first leg) */
}

/* The whole analysis (gf_path_analysis_run, gfPathAnalysis's and the
 * solver's): the straight path as a GeoJSON line, relative file names in the
 * base folder; the files written and the summary through the line callback
 * (sRunout 190 m as above); failures return their status and whole message
 * to the error callback, call after call in one process (nothing exits) */
typedef struct { int lines, errors; char last[1024]; } pa_log;
static void pa_line(void *ctx, const char *t)
{
    pa_log *L = ctx;
    ++L->lines;
    snprintf(L->last, sizeof L->last, "%s", t);
}
static void pa_error(void *ctx, const char *t)
{
    pa_log *L = ctx;
    ++L->errors;
    snprintf(L->last, sizeof L->last, "%s", t);
}

static void whole_analysis_writes_its_files_and_returns_its_errors(void **state)
{
    (void)state;
    gf_raster dem, ppr;
    make_raster("plane.tif", NX, NY, plane, &dem);
    shift_dx = 0.0;
    make_raster("ppr.tif", NX, NY, block, &ppr);
    gf_raster_free(&dem), gf_raster_free(&ppr);
    FILE *f = fopen(tmp("path.geojson"), "w");
    assert_non_null(f);
    fputs("{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\",\"properties\":{},"
          "\"geometry\":{\"type\":\"LineString\",\"coordinates\":[[11,61],[291,61]]}}]}", f);
    fclose(f);
    size_t nopt;
    const gf_path_analysis_option *o = gf_path_analysis_options(&nopt);
    assert_int_equal(nopt, 18);
    assert_string_equal(o[0].key, "-dem");
    pa_log L = {0};
    const gf_path_analysis_io io = {tmpdir, pa_line, NULL, pa_error, &L};
    const char *ok[] = {"-dem", "plane.tif", "-path", "path.geojson", "-ppr", "ppr.tif", "-width", "40",
                        "-plots", "no", "-out", "pa"};
    assert_int_equal(gf_path_analysis_run(6, ok, &io), GF_SUCCESS);
    assert_int_equal(L.errors, 0);
    assert_int_equal(L.lines, 4);   /* path, runout, MMPPR; "wrote" */
    assert_string_equal(L.last, "wrote pa/{pathAnalysis.csv,pathProfile.csv,pathGrid.csv,summary.dat}");
    f = fopen(tmp("pa/pathAnalysis.csv"), "r");
    assert_non_null(f);
    char head[512], row[512];
    assert_non_null(fgets(head, sizeof head, f));
    assert_non_null(fgets(row, sizeof row, f));
    fclose(f);
    assert_non_null(strstr(row, "run,ppr,1,40,40,190,"));
    assert_int_equal(access(tmp("pa/summary.dat"), R_OK), 0);
    /* failures, one after the other */
    const char *none[] = {"-path", "path.geojson"};
    assert_int_equal(gf_path_analysis_run(1, none, &io), GF_EINVAL);
    assert_string_equal(L.last, "-dem is required (-help lists the options)");
    expect_detail("-dem is required", NULL);
    const char *high[] = {"-dem", "plane.tif", "-path", "path.geojson", "-ppr", "ppr.tif", "-width", "40",
                          "-threshold", "100", "-out", "pa"};
    assert_int_equal(gf_path_analysis_run(6, high, &io), GF_EDOM);
    assert_non_null(strstr(L.last, "run, -field ppr: "));
    assert_non_null(strstr(L.last, "exceeds the threshold 100"));
    const char *missing[] = {"-dem", "plane.tif", "-path", "path.geojson", "-ppr", "nope.tif", "-out", "pa"};
    assert_int_equal(gf_path_analysis_run(4, missing, &io), GF_EIO);
    assert_string_equal(L.last, "-ppr nope.tif: no such file or not readable");
    const char *twice[] = {"-dem", "plane.tif", "-dem", "plane.tif"};
    assert_int_equal(gf_path_analysis_run(2, twice, &io), GF_EINVAL);
    assert_string_equal(L.last, "-dem given twice");
    const char *unknown[] = {"-speed", "1"};
    assert_int_equal(gf_path_analysis_run(1, unknown, &io), GF_ENOTFOUND);
    assert_int_equal(L.errors, 5);
    /* without callbacks: the status and gf_error_detail only */
    assert_int_equal(gf_path_analysis_run(1, none, NULL), GF_EINVAL);
    expect_detail("-dem is required", NULL);
}

int main(void)
{
    CPLSetConfigOption("CPL_LOG", "/dev/null");
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(points_are_located_along_and_across_the_path),
        cmocka_unit_test(straight_path_on_a_plane_gives_the_exact_runout_and_angle),
        cmocka_unit_test(circular_arc_path_has_s_equal_r_theta),
        cmocka_unit_test(nodata_is_nan_and_not_reached),
        cmocka_unit_test(path_leaving_the_dem_is_refused),
        cmocka_unit_test(shifted_runs_give_the_known_tp_fp_fn_areas),
        cmocka_unit_test(rasters_on_different_grids_are_sampled_each_on_its_own),
        cmocka_unit_test(beta_point_is_where_the_slope_stays_below_ten_degrees),
        cmocka_unit_test(paths_and_points_are_read_through_ogr),
        cmocka_unit_test(whole_analysis_writes_its_files_and_returns_its_errors),
    };
    const int rc = gf_run_tests("tests", tests, setup, teardown);
    GDALDestroyDriverManager();
    return rc;
}
