/*
 * granflowExact — libgranflow's exact solutions at given positions.
 *
 *   granflowExact riemann BETA H_L U_L H_R U_R X0 T  < positions
 *
 * Reads one x per line (or the first column of a CSV with a header) on
 * standard input and prints "x,h_exact,u_exact".  BETA = g for the
 * dimensional dam breaks (Stoker: H_R > 0, Ritter: H_R = 0), epsilon K cos
 * zeta for the dimensionless Savage–Hutter Riemann problem.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "granflow/exact.h"

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

int main(int argc, char **argv)
{
    if (argc != 9 || strcmp(argv[1], "riemann") != 0) {
        fprintf(stderr, "usage: granflowExact riemann BETA H_L U_L H_R U_R X0 T < positions\n");
        return 2;
    }
    static const char *names[] = {"BETA", "H_L", "U_L", "H_R", "U_R", "X0", "T"};
    double a[7];
    for (int i = 0; i < 7; ++i)
        a[i] = num(argv[i + 2], names[i]);
    gf_riemann rp;
    if (gf_riemann_solve(&rp, a[0], a[1], a[2], a[3], a[4], a[5]) != GF_SUCCESS) {
        fprintf(stderr, "granflowExact: %s\n", gf_error_detail());
        return 2;
    }
    char line[4096];
    printf("x,h_exact,u_exact\n");
    while (fgets(line, sizeof line, stdin)) {
        char *end;
        const double x = strtod(line, &end);
        if (end == line)
            continue; /* header or blank */
        double h, u;
        gf_riemann_sample(&rp, x, a[6], &h, &u);
        printf("%.12g,%.12g,%.12g\n", x, h, u);
    }
    return 0;
}
