/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Regional hazard indication (granflow/regional.h): terrain derivatives on
 * analytic surfaces, the release-area split of a ridge and a pyramid, the
 * Salm slope factor, alpha-beta on a parabolic profile, the D8 thalweg and
 * the merge of peak rasters, and the box of a release's cells and their
 * steepest-descent paths (gf_downslope_box). */
#include "../gf_test.h"

#include "granflow/constants.h"
#include "granflow/regional.h"

#define DEG GF_DEG

/* a north-up grid of nx x ny cells of size dx with z = f(x, y), x and y the
 * cell centres' coordinates relative to the grid's centre */
static gf_raster grid(int nx, int ny, double dx, double (*f)(double, double, const double *), const double *par)
{
    gf_raster r;
    memset(&r, 0, sizeof r);
    r.nx = nx;
    r.ny = ny;
    r.gt[0] = -0.5 * nx * dx;
    r.gt[1] = dx;
    r.gt[3] = 0.5 * ny * dx;
    r.gt[5] = -dx;
    r.nodata = -9999;
    r.wkt = (char *)"";
    r.z = malloc((size_t)nx * (size_t)ny * sizeof *r.z);
    assert_non_null(r.z);
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i)
            r.z[(size_t)j * (size_t)nx + (size_t)i] = f(r.gt[0] + (i + 0.5) * dx, r.gt[3] - (j + 0.5) * dx, par);
    r.n_valid = (size_t)nx * (size_t)ny;
    return r;
}

static double plane(double x, double y, const double *p) { return 1000 + p[0] * x + p[1] * y; }
static double cone(double x, double y, const double *p) { return 2000 - p[0] * hypot(x, y); }
static double ridge(double x, double y, const double *p) { (void)y; return 2000 - p[0] * fabs(x); }
static double pyramid(double x, double y, const double *p) { return 2000 - p[0] * fmax(fabs(x), fabs(y)); }

/* a plane z = a x + b y: Horn's slope atan(|grad z|) and the aspect of -grad z
 * (clockwise from north) at every interior cell, NAN on the border; a plane
 * has no roughness (VRM 0) */
static void plane_gives_its_slope_and_aspect(void **state)
{
    (void)state;
    const double cases[3][4] = {
        /* a, b, slope, aspect */
        {-tan(35 * DEG), 0, 35, 90},   /* falls to the east */
        {0, tan(28 * DEG), 28, 180},   /* rises to the north: faces south */
        {0.3, 0.4, atan(0.5) / DEG, atan2(-0.3, -0.4) / DEG + 360},
    };
    for (int k = 0; k < 3; ++k) {
        gf_raster r = grid(12, 9, 5, plane, cases[k]);
        double s[108], a[108], v[108];
        assert_int_equal(gf_slope_aspect(&r, s, a), GF_SUCCESS);
        assert_int_equal(gf_vrm(&r, 3, v, NULL), GF_SUCCESS);
        assert_true(isnan(s[0]) && isnan(a[11]) && isnan(s[107]));
        for (int j = 1; j < 8; ++j)
            for (int i = 1; i < 11; ++i) {
                assert_close(s[j * 12 + i], cases[k][2], 1e-9);
                assert_close(a[j * 12 + i], cases[k][3], 1e-9);
                assert_close(v[j * 12 + i], 0, 1e-12);
            }
        free(r.z);
    }
}

/* a cone z = H - tan(theta) r: plan curvature sin(theta) / r (> 0, flow
 * diverges), to 2 % at r >= 40 m on a 2 m grid; a ridge's flanks are planes
 * (no curvature), the ridge line itself rough (VRM > 0) */
static void cone_has_plan_curvature_sin_theta_over_r(void **state)
{
    (void)state;
    const double k = tan(35 * DEG);
    gf_raster r = grid(101, 101, 2, cone, &k);
    double *c = malloc(101 * 101 * sizeof *c);
    assert_int_equal(gf_plan_curvature(&r, c), GF_SUCCESS);
    for (int i = 70; i < 100; i += 7) {
        double x = r.gt[0] + (i + 0.5) * 2, y = r.gt[3] - (50 + 0.5) * 2;
        double rr = hypot(x, y), want = sin(35 * DEG) / rr;
        assert_true(fabs(c[50 * 101 + i] - want) <= 0.02 * want);
    }
    free(r.z);
    gf_raster q = grid(21, 21, 5, ridge, &k);
    double v[441];
    assert_int_equal(gf_plan_curvature(&q, c), GF_SUCCESS);
    assert_int_equal(gf_vrm(&q, 3, v, NULL), GF_SUCCESS);
    assert_close(c[10 * 21 + 5], 0, 1e-12);
    assert_close(v[10 * 21 + 5], 0, 1e-12);
    assert_true(v[10 * 21 + 10] > 0.05);
    free(q.z);
    free(c);
}

/* wind shelter (Winstral et al. 2002): on level ground a wall 10 m high
 * across the grid shelters a cell d metres downwind by atan(10 / d) (north
 * wind, the wall to its north), leaves a cell upwind of it at 0 (level
 * ground in the sector) and one farther than dmax at 0 */
static double wall(double x, double y, const double *p)
{
    (void)x;
    return fabs(y - p[0]) < 2.5 ? 1010 : 1000;
}

static void wind_shelter_behind_a_wall(void **state)
{
    (void)state;
    const double yw = 0; /* the wall: the row of cell centres at y = 0 */
    gf_raster r = grid(21, 41, 5, wall, &yw);
    double *sx = malloc(21 * 41 * sizeof *sx);
    assert_int_equal(gf_wind_shelter(&r, 0, 30, 100, sx), GF_SUCCESS);
    /* the wall row: y = 102.5 - (j + 0.5) 5 = 0 at row 20 */
    int jw = 20;
    assert_close(r.z[jw * 21 + 10], 1010, 0);
    for (int k = 1; k <= 6; ++k)
        assert_close(sx[(jw + k) * 21 + 10], atan(10.0 / (5 * k)) / DEG, 1e-9);
    assert_close(sx[(jw - 3) * 21 + 10], 0, 1e-12);
    assert_int_equal(gf_wind_shelter(&r, 0, 30, 50, sx), GF_SUCCESS);
    assert_close(sx[(jw + 10) * 21 + 10], atan(10.0 / 50) / DEG, 1e-9);
    assert_close(sx[(jw + 11) * 21 + 10], 0, 1e-12);
    /* a south wind: the cells south of the wall are upwind of it */
    assert_int_equal(gf_wind_shelter(&r, 180, 30, 100, sx), GF_SUCCESS);
    assert_close(sx[(jw + 2) * 21 + 10], 0, 1e-12);
    assert_close(sx[(jw - 2) * 21 + 10], atan(10.0 / 10) / DEG, 1e-9);
    assert_int_equal(gf_wind_shelter(&r, 400, 30, 100, sx), GF_EDOM);
    assert_non_null(strstr(gf_error_detail(), "[0, 360]"));
    free(sx);
    free(r.z);
}

/* a symmetric ridge (35 deg flanks, north-south crest): two release areas,
 * the east and west flank, of equal area (the crest's three columns of
 * mixed aspect split between them), facing 90 and 270 deg; a forest on the
 * west flank leaves the east one; a 20 deg ridge has none */
static void ridge_splits_into_its_two_flanks(void **state)
{
    (void)state;
    double k = tan(35 * DEG);
    gf_raster r = grid(61, 40, 5, ridge, &k);
    gf_pra_params p;
    gf_pra_params_default(&p);
    p.roughness_max = NAN; /* the crest is a ridge line, not rough terrain */
    p.min_area = 2000;
    gf_pra_set s;
    assert_int_equal(gf_pra_delineate(&r, NULL, &p, &s), GF_SUCCESS);
    assert_int_equal(s.n, 2);
    /* interior cells 59 x 38, the crest column (slope 0 by symmetry) out */
    const double flank = 29 * 38 * 25.0;
    for (int a = 0; a < 2; ++a) {
        assert_close(s.pra[a].area_m2, flank, 1e-9);
        assert_close(s.pra[a].slope_deg, 35, 1e-9);
        assert_close(fabs(s.pra[a].aspect_deg - 180), 90, 1e-9);
    }
    gf_verify("analytic ridge", "flank area / expected", s.pra[0].area_m2 / flank, "=", 1, "35 deg ridge, 5 m grid");
    /* labels: one id per flank */
    assert_int_equal(s.label[20 * 61 + 5] + s.label[20 * 61 + 55], 3);
    assert_int_equal(s.label[20 * 61 + 30], 0);
    unsigned char *forest = calloc(61 * 40, 1);
    for (int j = 0; j < 40; ++j)
        for (int i = 0; i < 30; ++i)
            forest[j * 61 + i] = 1;
    gf_pra_set_free(&s);
    assert_int_equal(gf_pra_delineate(&r, forest, &p, &s), GF_SUCCESS);
    assert_int_equal(s.n, 1);
    assert_close(s.pra[0].aspect_deg, 90, 1e-9);
    gf_pra_set_free(&s);
    free(forest);
    free(r.z);
    k = tan(20 * DEG);
    r = grid(61, 40, 5, ridge, &k);
    assert_int_equal(gf_pra_delineate(&r, NULL, &p, &s), GF_SUCCESS);
    assert_int_equal(s.n, 0);
    gf_pra_set_free(&s);
    free(r.z);
}

/* a square pyramid (35 deg faces) splits along its four ridges into four
 * areas of a quarter each (to 1 %), facing N, E, S, W; the minimum area
 * drops them all when above a quarter */
static void pyramid_splits_into_four_faces(void **state)
{
    (void)state;
    const double k = tan(35 * DEG);
    gf_raster r = grid(81, 81, 2, pyramid, &k);
    gf_pra_params p;
    gf_pra_params_default(&p);
    p.roughness_max = NAN;
    p.min_area = 500;
    gf_pra_set s;
    assert_int_equal(gf_pra_delineate(&r, NULL, &p, &s), GF_SUCCESS);
    assert_int_equal(s.n, 4);
    /* interior cells but the two diagonals (157 cells: Horn's slope on a
     * crest cell is atan(tan 35 / sqrt 2) = 26.3 deg < 28), 4 m2 each */
    const double quarter = (79.0 * 79.0 - 157) * 4 / 4;
    double seen[4] = {0, 0, 0, 0};
    for (size_t a = 0; a < 4; ++a) {
        assert_true(fabs(s.pra[a].area_m2 / quarter - 1) < 0.01);
        int q = (int)floor(fmod(s.pra[a].aspect_deg + 45, 360) / 90);
        seen[q] = 1;
        assert_true(fabs(s.pra[a].aspect_deg - 90 * q) < 1 || fabs(s.pra[a].aspect_deg - 360) < 1);
    }
    assert_close(seen[0] + seen[1] + seen[2] + seen[3], 4, 0);
    gf_verify("analytic pyramid", "|face area / quarter - 1|", fabs(s.pra[0].area_m2 / quarter - 1), "<", 0.01,
              "35 deg square pyramid, 2 m grid");
    gf_pra_set_free(&s);
    p.min_area = 1.2 * quarter;
    assert_int_equal(gf_pra_delineate(&r, NULL, &p, &s), GF_SUCCESS);
    assert_int_equal(s.n, 0);
    gf_pra_set_free(&s);
    p.slope_min = 61;
    assert_int_equal(gf_pra_delineate(&r, NULL, &p, &s), GF_EDOM);
    assert_non_null(strstr(gf_error_detail(), "0 < min < max <= 90"));
    gf_pra_set_free(&s);
    free(r.z);
}

/* Salm, Burkard and Gubler (1990): f(psi) = 0.291 / (sin psi - 0.202 cos
 * psi); by hand f(28) = 0.291 / (0.469472 - 0.178355) = 0.99960 and f(45) =
 * 0.291 / (0.707107 x 0.798) = 0.51571; d0 = (1 m + 0.05 m / 100 m x 300 m)
 * f(45) = 1.15 x 0.51571 = 0.59306 m */
static void salm_factor_matches_hand_values(void **state)
{
    (void)state;
    double f;
    assert_int_equal(gf_salm_slope_factor(28, &f), GF_SUCCESS);
    assert_close(f, 0.99960, 5e-6);
    assert_int_equal(gf_salm_slope_factor(45, &f), GF_SUCCESS);
    assert_close(f, 0.51571, 5e-6);
    double d0;
    assert_int_equal(gf_release_depth(1.0, 0.05 / 100, 2300, 2000, 45, &d0), GF_SUCCESS);
    assert_close(d0, 1.15 * 0.51571, 1e-5);
    gf_verify("Salm et al. 1990", "f(28 deg)", 0.99960, "=", 0.9996, "hand value");
    assert_int_equal(gf_salm_slope_factor(10, &f), GF_EDOM);
    assert_non_null(strstr(gf_error_detail(), "[15, 90]"));
    assert_int_equal(gf_release_depth(1.0, 0.01, 1000, 2000, 35, &d0), GF_EDOM);
    assert_non_null(strstr(gf_error_detail(), "negative"));
    assert_int_equal(gf_release_depth(NAN, 0, 1000, 2000, 35, &d0), GF_EDOM);
}

/* alpha-beta on the parabola z = z0 - b s + c s^2 (b = tan 40 deg, c = 5e-4
 * 1/m): the slope is 10 deg at s* = (b - tan 10) / (2c), beta = atan(b - c
 * s*), alpha = 0.96 beta - 1.4; the line from the top at alpha meets the
 * profile again at s = (b - tan alpha) / c (the same for alpha -+ 2.3) */
static void alpha_beta_on_parabola(void **state)
{
    (void)state;
    const double b = tan(40 * DEG), c = 5e-4, z0 = 2500;
    const size_t n = 3001;
    double *s = malloc(n * sizeof *s), *z = malloc(n * sizeof *z);
    for (size_t i = 0; i < n; ++i) {
        s[i] = 0.5 * (double)i;
        z[i] = z0 - b * s[i] + c * s[i] * s[i];
    }
    gf_alpha_beta_params p;
    gf_alpha_beta_params_default(&p);
    gf_alpha_beta ab;
    assert_int_equal(gf_alpha_beta_profile(n, s, z, &p, &ab), GF_SUCCESS);
    const double sstar = (b - tan(10 * DEG)) / (2 * c), beta = atan(b - c * sstar) / DEG;
    assert_close(ab.s_beta, sstar, 1e-6);
    assert_close(ab.beta, beta, 1e-4);
    assert_close(ab.alpha, 0.96 * beta - 1.4, 1e-4);
    const double a[3] = {ab.alpha, ab.alpha - 2.3, ab.alpha + 2.3};
    for (int m = 0; m < 3; ++m)
        assert_close(ab.s_alpha[m], (b - tan(a[m] * DEG)) / c, 0.05);
    assert_true(ab.s_alpha[1] > ab.s_alpha[0] && ab.s_alpha[0] > ab.s_alpha[2]);
    gf_verify("Lied and Bakkehoi 1980", "beta point error [m]", fabs(ab.s_beta - sstar), "<", 1e-6,
              "parabolic profile");
    /* a 10 m bench at 5 deg high on the profile is not the beta point */
    for (size_t i = 0; i < n; ++i) {
        const double t = s[i] <= 100 ? s[i] : s[i] <= 110 ? 100 : s[i] - 10;
        z[i] = z0 - b * t + c * t * t - tan(5 * DEG) * fmin(fmax(s[i] - 100, 0), 10);
    }
    assert_int_equal(gf_alpha_beta_profile(n, s, z, &p, &ab), GF_SUCCESS);
    assert_close(ab.s_beta, sstar + 10, 1e-6);
    /* a profile that never flattens */
    for (size_t i = 0; i < n; ++i)
        z[i] = z0 - s[i];
    assert_int_equal(gf_alpha_beta_profile(n, s, z, &p, &ab), GF_EDOM);
    assert_non_null(strstr(gf_error_detail(), "never falls below 10 deg"));
    free(s);
    free(z);
}

/* D8 thalweg: on a plane falling east it runs straight east to the border
 * in steps of the cell size; a pit ends it unless it is shallower than the
 * allowed climb (then it climbs out, reaches the border and follows its
 * level edge) */
static void thalweg_follows_steepest_descent(void **state)
{
    (void)state;
    const double pe[2] = {-0.5, 0};
    gf_raster r = grid(30, 20, 5, plane, pe);
    double *p;
    size_t n;
    assert_int_equal(gf_thalweg_d8(&r, 3, 10, 0, 0, &p, &n), GF_SUCCESS);
    assert_int_equal(n, 27);
    assert_close(p[4 * (n - 1) + 3], 26 * 5.0, 1e-12);
    assert_close(p[4 * (n - 1) + 2] - p[2], -0.5 * 26 * 5, 1e-9);
    free(p);
    assert_int_equal(gf_thalweg_d8(&r, 30, 10, 0, 0, &p, &n), GF_EDOM);
    /* a pit 4 m deep (1.5 m below its lower neighbours) ends strict D8 there;
     * with max_climb 2 m the path climbs out and reaches the border */
    r.z[10 * 30 + 12] -= 4;
    assert_int_equal(gf_thalweg_d8(&r, 3, 10, 0, 0, &p, &n), GF_SUCCESS);
    assert_int_equal(n, 10);
    free(p);
    assert_int_equal(gf_thalweg_d8(&r, 3, 10, 2, 30, &p, &n), GF_SUCCESS);
    /* (then along the level border column until 30 m without a new low) */
    assert_int_equal(n, 27 + 7);
    assert_close(p[4 * 26], r.gt[0] + 29.5 * 5, 1e-9);
    assert_close(p[4 * (n - 1) + 2], p[4 * 26 + 2], 1e-9);
    for (size_t i = 1; i < n; ++i)
        assert_true(p[4 * i + 3] > p[4 * (i - 1) + 3]);
    free(p);
    assert_int_equal(gf_thalweg_d8(&r, 3, 10, 1, 50, &p, &n), GF_SUCCESS);
    assert_int_equal(n, 10);
    free(p);
    free(r.z);
}

/* ---- gf_downslope_box: the box of a release and its steepest-descent paths */

static double valley(double x, double y, const double *p) { (void)y; return 1000 + p[0] * fabs(x); }

/* the box of n cells (col, row pairs) of r; path_cells through *np */
static gf_status dbox(const gf_raster *r, size_t n, const int *cr, double climb, double flat, int box[4], size_t *np)
{
    size_t c[16];
    assert_true(n <= 16);
    for (size_t k = 0; k < n; ++k)
        c[k] = (size_t)cr[2 * k + 1] * (size_t)r->nx + (size_t)cr[2 * k];
    return gf_downslope_box(r, n, c, climb, flat, box, np);
}

#define assert_box(b, c0, r0, c1, r1)                                                                              \
    do {                                                                                                           \
        assert_int_equal((b)[0], (c0));                                                                            \
        assert_int_equal((b)[1], (r0));                                                                            \
        assert_int_equal((b)[2], (c1));                                                                            \
        assert_int_equal((b)[3], (r1));                                                                            \
    } while (0)

/* on a plane (cells of 5 m, 2.5 m lower each cell downslope) the path of one
 * cell runs straight downslope to the grid's border: falling south, from
 * (7, 2) down column 7 to row 19, a box one column wide and 18 cells on the
 * path; falling south-east (the diagonal drops 5 m in 7.07 m, steeper than
 * the 2.5 m in 5 m of a side), from (3, 2) diagonally to the bottom row at
 * (20, 19), then east along it (still 2.5 m a cell lower) to the corner
 * (29, 19): 18 + 9 cells.  Strict D8 (max_climb 0) ends there; with
 * max_climb 5 m and max_flat 0 the south path takes one level step along
 * the border row (west or east: either neighbour, the first is (6, 19))
 * and ends, its box then 2 columns wide */
static void downslope_box_runs_down_a_plane(void **state)
{
    (void)state;
    int box[4];
    size_t np = 0;
    const double ps[2] = {0, 0.5};
    gf_raster r = grid(30, 20, 5, plane, ps);
    const int a[2] = {7, 2};
    assert_int_equal(dbox(&r, 1, a, 0, 0, box, &np), GF_SUCCESS);
    assert_box(box, 7, 2, 7, 19);
    assert_int_equal(np, 18);
    /* max_flat 0 with a climb allowed: one step along the level border */
    assert_int_equal(dbox(&r, 1, a, 5, 0, box, &np), GF_SUCCESS);
    assert_box(box, 6, 2, 7, 19);
    assert_int_equal(np, 19);
    /* path_cells may be NULL */
    assert_int_equal(dbox(&r, 1, a, 0, 0, box, NULL), GF_SUCCESS);
    assert_box(box, 7, 2, 7, 19);
    free(r.z);
    const double pse[2] = {-0.5, 0.5};
    r = grid(30, 20, 5, plane, pse);
    const int b[2] = {3, 2};
    assert_int_equal(dbox(&r, 1, b, 0, 0, box, &np), GF_SUCCESS);
    assert_box(box, 3, 2, 29, 19);
    assert_int_equal(np, 18 + 9);
    free(r.z);
}

/* a V valley z = 1000 + 0.5 |x| (31 x 21 cells of 5 m, its level floor the
 * column 15, x = 0): from (25, 10) on its flank the path runs west down to
 * the floor (15, 10), 11 cells; strict D8 ends there.  With max_climb 1 m
 * (the flanks' cells next to the floor are 2.5 m higher) it follows the
 * level floor (north: the first level neighbour, then keeping its
 * direction) until it has gone more than max_flat without a new lowest
 * point: k steps of 5 m with 5 k > max_flat, k = 3 for 12 m (rows 9..7) and
 * 7 for 30 m (rows 9..3); a max_flat longer than the floor ends at the
 * grid's border (row 0, 10 steps) */
static void downslope_box_follows_a_valley_floor(void **state)
{
    (void)state;
    int box[4];
    size_t np = 0;
    const double pv[1] = {0.5};
    gf_raster r = grid(31, 21, 5, valley, pv);
    const int a[2] = {25, 10};
    assert_int_equal(dbox(&r, 1, a, 0, 1000, box, &np), GF_SUCCESS);
    assert_box(box, 15, 10, 25, 10);
    assert_int_equal(np, 11);
    assert_int_equal(dbox(&r, 1, a, 1, 12, box, &np), GF_SUCCESS);
    assert_box(box, 15, 10 - 3, 25, 10);
    assert_int_equal(np, 11 + 3);
    assert_int_equal(dbox(&r, 1, a, 1, 30, box, &np), GF_SUCCESS);
    assert_box(box, 15, 10 - 7, 25, 10);
    assert_int_equal(np, 11 + 7);
    assert_int_equal(dbox(&r, 1, a, 1, 1000, box, &np), GF_SUCCESS);
    assert_box(box, 15, 0, 25, 10);
    assert_int_equal(np, 11 + 10);
    free(r.z);
}

/* a pit on a plane falling east (2.5 m a cell): cell (12, 10) lowered by
 * 4 m lies 1.5 m below its lowest neighbours (13, 9..11).  From (3, 10):
 * with max_climb 1 m the path ends in the pit (the box cols 3..12, 10
 * cells); with 2 m it climbs out eastwards (the level neighbours: the one
 * in its direction, (13, 10), 5 m without a new lowest point, within
 * max_flat 5 m), descends to the border column 29 (new lowest points all
 * the way) and there follows the level border north for 5 m and one step
 * more (rows 9 and 8): 27 + 2 cells, rows 8..10 */
static void downslope_box_walks_through_shallow_pits(void **state)
{
    (void)state;
    int box[4];
    size_t np = 0;
    const double pe[2] = {-0.5, 0};
    gf_raster r = grid(30, 20, 5, plane, pe);
    r.z[10 * 30 + 12] -= 4;
    const int a[2] = {3, 10};
    assert_int_equal(dbox(&r, 1, a, 1, 5, box, &np), GF_SUCCESS);
    assert_box(box, 3, 10, 12, 10);
    assert_int_equal(np, 10);
    assert_int_equal(dbox(&r, 1, a, 2, 5, box, &np), GF_SUCCESS);
    assert_box(box, 3, 8, 29, 10);
    assert_int_equal(np, 27 + 2);
    /* strict D8 stops in the pit whatever max_flat */
    assert_int_equal(dbox(&r, 1, a, 0, 100, box, &np), GF_SUCCESS);
    assert_box(box, 3, 10, 12, 10);
    assert_int_equal(np, 10);
    free(r.z);
}

/* several cells: the box is the union of their boxes.  On the plane falling
 * east two cells (3, 4) and (5, 15) run to column 29 each: rows 4..15,
 * 27 + 25 cells on the paths.  A block of 3 x 3 cells (cols 3..5, rows
 * 9..11): only the east column's cells start a path (the others' steepest
 * neighbour is a release cell), 3 paths of 25 cells, the block's other 6
 * cells on none.  In the valley, cells on both flanks (25, 10) and (5, 10)
 * meet on the floor (15, 10): one floor walk (3 cells for max_flat 12 m),
 * 11 + 3 + 10 cells (the second path ends where it meets the first, in
 * either order: it arrives with more of max_flat used).  A NODATA cell of
 * the release is skipped. */
static void downslope_box_of_several_cells_is_the_union(void **state)
{
    (void)state;
    int box[4];
    size_t np = 0;
    const double pe[2] = {-0.5, 0};
    gf_raster r = grid(30, 20, 5, plane, pe);
    const int two[4] = {3, 4, 5, 15};
    assert_int_equal(dbox(&r, 2, two, 0, 0, box, &np), GF_SUCCESS);
    assert_box(box, 3, 4, 29, 15);
    assert_int_equal(np, 27 + 25);
    int block[18];
    for (int k = 0; k < 9; ++k)
        block[2 * k] = 3 + k % 3, block[2 * k + 1] = 9 + k / 3;
    assert_int_equal(dbox(&r, 9, block, 0, 0, box, &np), GF_SUCCESS);
    assert_box(box, 3, 9, 29, 11);
    assert_int_equal(np, 3 * 25);
    /* a NODATA cell, (1, 2), is no part of the box */
    r.z[2 * 30 + 1] = NAN;
    const int withnan[4] = {1, 2, 5, 15};
    assert_int_equal(dbox(&r, 2, withnan, 0, 0, box, &np), GF_SUCCESS);
    assert_box(box, 5, 15, 29, 15);
    assert_int_equal(np, 25);
    free(r.z);
    const double pv[1] = {0.5};
    r = grid(31, 21, 5, valley, pv);
    const int flanks[4] = {25, 10, 5, 10}, flanks2[4] = {5, 10, 25, 10};
    assert_int_equal(dbox(&r, 2, flanks, 1, 12, box, &np), GF_SUCCESS);
    assert_box(box, 5, 7, 25, 10);
    assert_int_equal(np, 11 + 3 + 10);
    assert_int_equal(dbox(&r, 2, flanks2, 1, 12, box, &np), GF_SUCCESS);
    assert_box(box, 5, 7, 25, 10);
    assert_int_equal(np, 11 + 3 + 10);
    /* two cells of one flank, (25, 10) and (25, 8): their floor walks
     * (max_flat 12 m) reach rows 7 and 5; the second path goes on where it
     * meets the first with more of max_flat left, so the box is rows 5..10
     * in either order: 11 + 3 cells of the one, 10 + 2 more of the other */
    const int same[4] = {25, 10, 25, 8}, same2[4] = {25, 8, 25, 10};
    assert_int_equal(dbox(&r, 2, same, 1, 12, box, &np), GF_SUCCESS);
    assert_box(box, 15, 5, 25, 10);
    assert_int_equal(np, 11 + 3 + 10 + 2);
    assert_int_equal(dbox(&r, 2, same2, 1, 12, box, &np), GF_SUCCESS);
    assert_box(box, 15, 5, 25, 10);
    assert_int_equal(np, 11 + 3 + 10 + 2);
    free(r.z);
}

/* refused: no cell (n 0) or none with a DEM value and a cell outside the
 * grid (GF_EDOM: "no valid cell, a cell outside the grid"), max_climb or
 * max_flat negative or not finite (GF_EDOM), no DEM, no cells for n > 0 or
 * no box (GF_EINVAL: a null pointer) */
static void downslope_box_refusals(void **state)
{
    (void)state;
    int box[4];
    size_t np = 0;
    const double pe[2] = {-0.5, 0};
    gf_raster r = grid(30, 20, 5, plane, pe);
    const size_t ok = 10 * 30 + 3, out = 30 * 20, two[2] = {10 * 30 + 3, 30 * 20};
    assert_int_equal(gf_downslope_box(&r, 0, NULL, 0, 0, box, &np), GF_EDOM);
    assert_int_equal(gf_downslope_box(&r, 0, &ok, 0, 0, box, &np), GF_EDOM);
    assert_int_equal(gf_downslope_box(&r, 1, &out, 0, 0, box, &np), GF_EDOM);
    assert_non_null(strstr(gf_error_detail(), "600"));
    assert_int_equal(gf_downslope_box(&r, 2, two, 0, 0, box, &np), GF_EDOM);
    assert_int_equal(gf_downslope_box(&r, 1, &ok, -1, 0, box, &np), GF_EDOM);
    assert_non_null(strstr(gf_error_detail(), "max_climb"));
    assert_int_equal(gf_downslope_box(&r, 1, &ok, 0, -1, box, &np), GF_EDOM);
    assert_int_equal(gf_downslope_box(&r, 1, &ok, NAN, 0, box, &np), GF_EDOM);
    assert_int_equal(gf_downslope_box(&r, 1, &ok, 0, INFINITY, box, &np), GF_EDOM);
    assert_int_equal(gf_downslope_box(&r, 1, &ok, 0, 0, NULL, &np), GF_EINVAL);
    assert_int_equal(gf_downslope_box(&r, 1, NULL, 0, 0, box, &np), GF_EINVAL);
    assert_int_equal(gf_downslope_box(NULL, 1, &ok, 0, 0, box, &np), GF_EINVAL);
    r.z[ok] = NAN;
    assert_int_equal(gf_downslope_box(&r, 1, &ok, 0, 0, box, &np), GF_EDOM);
    /* the refusals left the DEM as it was: a valid cell still works */
    const size_t c = 4 * 30 + 3;
    assert_int_equal(gf_downslope_box(&r, 1, &c, 0, 0, box, &np), GF_SUCCESS);
    assert_box(box, 3, 4, 29, 4);
    assert_int_equal(np, 27);
    free(r.z);
}

/* the merge of three rasters equals the cell-by-cell maximum, the count of
 * values above the threshold and the id of the maximum; NAN is not reached */
static void merge_is_cellwise_max(void **state)
{
    (void)state;
    enum { N = 1000 };
    double *f[3];
    const long ids[3] = {7, 11, 42};
    srand(52);
    for (int k = 0; k < 3; ++k) {
        f[k] = malloc(N * sizeof *f[k]);
        for (int c = 0; c < N; ++c)
            f[k][c] = rand() % 5 == 0 ? NAN : 100.0 * rand() / RAND_MAX;
    }
    double mx[N];
    unsigned cnt[N];
    long who[N];
    assert_int_equal(gf_merge_max(3, N, (const double *const *)f, ids, 50, mx, cnt, who), GF_SUCCESS);
    for (int c = 0; c < N; ++c) {
        double m = NAN;
        long w = -1;
        unsigned n = 0;
        for (int k = 0; k < 3; ++k)
            if (!isnan(f[k][c])) {
                if (isnan(m) || f[k][c] > m) {
                    m = f[k][c];
                    w = ids[k];
                }
                n += f[k][c] > 50;
            }
        if (isnan(m))
            assert_true(isnan(mx[c]));
        else
            assert_close(mx[c], m, 0);
        assert_int_equal(cnt[c], n);
        assert_int_equal(who[c], w);
    }
    assert_int_equal(gf_merge_max(3, N, (const double *const *)f, ids, NAN, mx, cnt, who), GF_EDOM);
    for (int k = 0; k < 3; ++k)
        free(f[k]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(plane_gives_its_slope_and_aspect),
        cmocka_unit_test(cone_has_plan_curvature_sin_theta_over_r),
        cmocka_unit_test(wind_shelter_behind_a_wall),
        cmocka_unit_test(ridge_splits_into_its_two_flanks),
        cmocka_unit_test(pyramid_splits_into_four_faces),
        cmocka_unit_test(salm_factor_matches_hand_values),
        cmocka_unit_test(alpha_beta_on_parabola),
        cmocka_unit_test(thalweg_follows_steepest_descent),
        cmocka_unit_test(downslope_box_runs_down_a_plane),
        cmocka_unit_test(downslope_box_follows_a_valley_floor),
        cmocka_unit_test(downslope_box_walks_through_shallow_pits),
        cmocka_unit_test(downslope_box_of_several_cells_is_the_union),
        cmocka_unit_test(downslope_box_refusals),
        cmocka_unit_test(merge_is_cellwise_max),
    };
    return gf_run_tests("regional", tests, NULL, NULL);
}
