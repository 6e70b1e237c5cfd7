/*
 * Speed against error of the 1D solvers (a benchmark, not a test: nothing is
 * asserted).  Every scheme at six resolutions on
 *   riemann: kinetic paper's Riemann problem (epsilon = 0.4, h 1 | 0.5, t = 5),
 *            L1 error of h against the exact solution;
 *   smooth:  periodic 35 deg slope with Coulomb friction, t = 0.1 (the
 *            verification test's problem, limiter off for DG), L1 error
 *            against RKDG P2 on 2048 cells.
 * Prints: problem, scheme, N, L1 error, CPU seconds, cell updates per second
 * (cells x steps / CPU s; DG counts a three-stage step once).  CSV on stdout.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "granflow/granflow.h"
#include "granflow/sh1d.h"

#define PI 3.14159265358979323846

static void rp_init(double x, void *c, double *h, double *u)
{
    (void)c;
    *h = x <= 5.0 ? 1.0 : 0.5;
    *u = 0.0;
}
static void smooth_init(double x, void *c, double *h, double *u)
{
    (void)c;
    *h = 1 + 0.2 * sin(2 * PI * x);
    *u = 1 + 0.1 * cos(2 * PI * x);
}

static void configure(gf_sh1d_config *c, int problem, int variant, size_t n)
{
    gf_sh1d_config_init(c);
    c->n_cells = n;
    if (problem == 0) {
        c->x_min = 0;
        c->x_max = 10;
        c->epsilon = 0.4;
    } else {
        c->x_min = 0;
        c->x_max = 1;
        c->zeta = 35 * PI / 180;
        c->bc_left = c->bc_right = GF_BC_PERIODIC;
        c->limiter = 0;
        gf_friction_init(&c->friction, "coulomb");
        gf_friction_set(&c->friction, "mu", tan(PI / 6));
        gf_friction_set(&c->friction, "u0", 0.0);
    }
    if (variant < 3)
        c->scheme = variant + 1;
    else
        c->degree = variant - 3;
}

static gf_sh1d *run(int problem, int variant, size_t n, double *cpu)
{
    gf_sh1d_config c;
    configure(&c, problem, variant, n);
    gf_sh1d *s;
    if (gf_sh1d_alloc(variant < 3 ? gf_sh1d_kinetic : gf_sh1d_rkdg, &c, &s)) {
        fprintf(stderr, "bench1d: %s\n", gf_error_detail());
        exit(1);
    }
    gf_sh1d_set_initial(s, problem == 0 ? rp_init : smooth_init, NULL);
    const clock_t t0 = clock();
    if (gf_sh1d_advance_to(s, problem == 0 ? 5.0 : 0.1)) {
        fprintf(stderr, "bench1d: %s\n", gf_error_detail());
        exit(1);
    }
    *cpu = (double)(clock() - t0) / CLOCKS_PER_SEC;
    return s;
}

int main(void)
{
    static const char *names[6] = {"kinetic1", "kinetic2", "kinetic3", "rkdgP0", "rkdgP1", "rkdgP2"};
    gf_riemann ex;
    gf_riemann_solve(&ex, 0.4, 1.0, 0.0, 0.5, 0.0, 5.0);
    double cpu;
    gf_sh1d *ref = run(1, 5, 2048, &cpu);
    printf("problem,scheme,N,L1_error,cpu_s,cell_updates_per_s\n");
    for (int problem = 0; problem < 2; ++problem)
        for (int v = 0; v < 6; ++v)
            for (size_t n = 50; n <= 1600; n *= 2) {
                /* repeat short runs so that the CPU time is measurable */
                double total = 0;
                int reps = 0;
                gf_sh1d *s = NULL;
                do {
                    if (s)
                        gf_sh1d_free(s);
                    s = run(problem, v, n, &cpu);
                    total += cpu;
                    ++reps;
                } while (total < 0.05 && reps < 200);
                cpu = total / reps;
                const double e = problem == 0 ? gf_sh1d_l1_error_riemann(s, &ex, 5.0) : gf_sh1d_l1_difference(s, ref);
                printf("%s,%s,%zu,%.6e,%.6e,%.4e\n", problem == 0 ? "riemann" : "smooth", names[v], n, e,
                       cpu, (double)n * (double)gf_sh1d_steps(s) / fmax(cpu, 1e-9));
                gf_sh1d_free(s);
            }
    gf_sh1d_free(ref);
    return 0;
}
