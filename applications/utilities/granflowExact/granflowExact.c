/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * granflowExact — libgranflow's exact solutions at given positions.
 *
 *   granflowExact riemann BETA H_L U_L H_R U_R X0 T  < positions
 *   granflowExact dressler G H_L C X0 T                < positions
 *   granflowExact chute ZETA0 ZETA1 X1 X2              < arc lengths
 *   granflowExact table PROFILE.csv                     < arc lengths
 *   granflowExact simisol T
 *   granflowExact incdam T
 *   granflowExact --version
 *
 * Reads one x per line (or the first column of a CSV with a header) on
 * standard input and prints "x,h_exact,u_exact".  BETA = g for the
 * dimensional dam breaks (Stoker: H_R > 0, Ritter: H_R = 0), epsilon K cos
 * zeta for the dimensionless Savage–Hutter Riemann problem.  dressler:
 * Dressler's dry dam break with Chezy coefficient C (first-order expansion
 * with a friction-dominated tip, exact.h); its tip and front positions are
 * printed to standard error.  chute: libgranflow's chute topography
 * (topography.h: zeta0 up to x1, linear to zeta1 at x2, angles in degrees;
 * the finite-area paper's eq. 74 is 35 10 17.5 21.5): prints
 * "s,X,Z,zeta" - the bed position with X = Z = 0 at s = 0 and the
 * inclination in radians - for the mesh generators of the tutorials.
 * table: the same for a tabulated profile (CSV with a header line, columns
 * x and zeta in degrees, x strictly increasing; libgranflow's cubic spline).
 * simisol and incdam print the references of two standard tests at time T
 * [s] (standard_tests.h, the standard parameters), reading no input:
 * simisol, the similarity solution of Hutter et al. (1993), prints
 * "t,g,dg,f,df,h_peak,x_c" - the stretching factors, their derivatives in
 * tau = t/sqrt(Lx/g), the peak thickness H/(f g) [m] and the horizontal
 * centre of mass [m]; incdam, the dam break on an inclined plane of
 * Faccanoni & Mangeney (2013), prints "t,x_tail,x_front,x_mid" - the
 * horizontal x [m] of the body/fan boundary, of the front and of xmid,
 * downstream of which the rear edge has no influence.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gf_csv.h"
#include "granflow/constants.h"
#include "granflow/exact.h"
#include "granflow/standard_tests.h"
#include "granflow/topography.h"
#include "granflow/version.h"

static double num(const char *s, const char *what)
{
    char *end;
    const double v = strtod(s, &end);
    if (end == s || *end) {
        fprintf(stderr, "granflowExact: %s = '%s' is not a number\n", what, s);
        exit(2);
    }
    return v;
}

static void usage(void)
{
    fprintf(stderr, "usage: granflowExact riemann BETA H_L U_L H_R U_R X0 T < positions\n"
                    "       granflowExact dressler G H_L C X0 T < positions\n"
                    "       granflowExact chute ZETA0 ZETA1 X1 X2 < arc lengths\n"
                    "       granflowExact table PROFILE.csv < arc lengths\n"
                    "       granflowExact simisol T\n"
                    "       granflowExact incdam T\n");
    exit(2);
}

/* The next position on standard input: the leading number of a line (the
 * first column of a CSV); lines without one (a header, blanks) are skipped.
 * 0 at the end of the input. */
static int next_position(double *x)
{
    char line[4096];
    while (fgets(line, sizeof line, stdin)) {
        char *end;
        *x = strtod(line, &end);
        if (end != line)
            return 1;
    }
    return 0;
}

/* A tabulated profile (CSV columns x, zeta in degrees; the shared strict
 * parser gf_csv.h); exits with its message on bad input. */
static gf_topography *read_table(const char *path)
{
    const double deg = 3.14159265358979323846 / 180.0;
    static const char *const cols[] = {"x", "zeta"};
    static const int nonneg[] = {0, 0};
    double *col[2];
    size_t n;
    char err[1024];
    if (gf_csv_read(path, cols, nonneg, 2, col, &n, err, sizeof err)) {
        fprintf(stderr, "granflowExact: %s\n", err);
        exit(2);
    }
    for (size_t i = 0; i < n; ++i)
        col[1][i] *= deg;
    gf_topography *t;
    if (gf_topography_tabulated_alloc(col[0], col[1], n, &t) != GF_SUCCESS) {
        fprintf(stderr, "granflowExact: profile '%s': %s\n", path, gf_error_detail());
        exit(2);
    }
    free(col[0]);
    free(col[1]);
    return t;
}

/* the bed of a chute (argv: chute ZETA0 ZETA1 X1 X2) or of a tabulated
 * profile (argv: table FILE) at every arc length read from stdin */
static int chute(char **argv)
{
    const double deg = 3.14159265358979323846 / 180.0;
    gf_topography *t;
    if (strcmp(argv[1], "table") == 0)
        t = read_table(argv[2]);
    else if (gf_topography_chute_alloc(num(argv[2], "ZETA0") * deg, num(argv[3], "ZETA1") * deg, num(argv[4], "X1"),
                                       num(argv[5], "X2"), &t) != GF_SUCCESS) {
        fprintf(stderr, "granflowExact: %s\n", gf_error_detail());
        return 2;
    }
    double lo, hi;
    gf_topography_range(t, &lo, &hi);
    (void)hi;
    double X0, Z0;
    gf_topography_position(t, lo > 0.0 ? lo : 0.0, &X0, &Z0);
    printf("s,X,Z,zeta\n");
    double x;
    while (next_position(&x)) {
        double X, Z, zeta, kappa;
        if (gf_topography_position(t, x, &X, &Z) != GF_SUCCESS || gf_topography_eval(t, x, &zeta, &kappa) != GF_SUCCESS) {
            fprintf(stderr, "granflowExact: %s\n", gf_error_detail());
            gf_topography_free(t);
            return 2;
        }
        printf("%.12g,%.12g,%.12g,%.15g\n", x, X - X0, Z - Z0, zeta);
    }
    gf_topography_free(t);
    return 0;
}

/* the references of the standard tests at time T (argv: simisol|incdam T) */
static int standard_test(char **argv)
{
    const double t = num(argv[2], "T");
    if (!(t >= 0.0) || !isfinite(t)) {
        fprintf(stderr, "granflowExact: T = %g must be finite and >= 0\n", t);
        return 2;
    }
    if (strcmp(argv[1], "simisol") == 0) {
        const gf_simisol_params p = gf_simisol_default();
        gf_simisol *s;
        double g, dg, f, df;
        if (gf_simisol_alloc(&s, &p, t, 1e-10) != GF_SUCCESS ||
            gf_simisol_stretch(s, t, &g, &dg, &f, &df) != GF_SUCCESS) {
            fprintf(stderr, "granflowExact: %s\n", gf_error_detail());
            return 2;
        }
        gf_simisol_free(s);
        printf("t,g,dg,f,df,h_peak,x_c\n%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g\n", t, g, dg, f,
               df, p.H / (f * g), gf_simisol_xc(&p, t));
        return 0;
    }
    gf_incdam d;
    if (gf_incdam_init(&d, 9.81, 22.0 * GF_DEG, 21.0 * GF_DEG, 1.0, -120.0) != GF_SUCCESS) {
        fprintf(stderr, "granflowExact: %s\n", gf_error_detail());
        return 2;
    }
    double x_tail, x_front;
    gf_incdam_fan(&d, t, &x_tail, &x_front);
    printf("t,x_tail,x_front,x_mid\n%.12g,%.12g,%.12g,%.12g\n", t, x_tail, x_front,
           gf_incdam_xmid(&d, t));
    return 0;
}

int main(int argc, char **argv)
{
    if (argc > 1 && (!strcmp(argv[1], "--version") || !strcmp(argv[1], "-version"))) {
        printf("granflow %s (granflowExact)\n", gf_version());
        return 0;
    }
    if ((argc == 6 && strcmp(argv[1], "chute") == 0) || (argc == 3 && strcmp(argv[1], "table") == 0))
        return chute(argv);
    if (argc == 3 && (strcmp(argv[1], "simisol") == 0 || strcmp(argv[1], "incdam") == 0))
        return standard_test(argv);
    static const char *rnames[] = {"BETA", "H_L", "U_L", "H_R", "U_R", "X0", "T"};
    static const char *dnames[] = {"G", "H_L", "C", "X0", "T"};
    const int riemann = argc == 9 && strcmp(argv[1], "riemann") == 0;
    const int dressler = argc == 7 && strcmp(argv[1], "dressler") == 0;
    if (!riemann && !dressler)
        usage();
    double a[7];
    for (int i = 0; i < argc - 2; ++i)
        a[i] = num(argv[i + 2], riemann ? rnames[i] : dnames[i]);
    gf_riemann rp;
    gf_dressler dp;
    double t;
    if (riemann) {
        t = a[6];
        if (gf_riemann_solve(&rp, a[0], a[1], a[2], a[3], a[4], a[5]) != GF_SUCCESS) {
            fprintf(stderr, "granflowExact: %s\n", gf_error_detail());
            return 2;
        }
    } else {
        t = a[4];
        if (gf_dressler_init(&dp, a[0], a[1], a[2], a[3]) != GF_SUCCESS ||
            gf_dressler_at(&dp, t) != GF_SUCCESS) {
            fprintf(stderr, "granflowExact: %s\n", gf_error_detail());
            return 2;
        }
        fprintf(stderr, "Dressler t = %g: tip x = %.6g (u = %.6g m/s, h = %.6g m), front x = %.6g\n",
                t, dp.x_tip, dp.u_tip, dp.h_tip, dp.x_front);
    }
    printf("x,h_exact,u_exact\n");
    double x;
    while (next_position(&x)) {
        double h, u;
        if (riemann)
            gf_riemann_sample(&rp, x, t, &h, &u);
        else
            gf_dressler_sample(&dp, x, t, &h, &u); /* t checked by gf_dressler_at above */
        printf("%.12g,%.12g,%.12g\n", x, h, u);
    }
    return 0;
}
