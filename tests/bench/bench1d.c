/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Speed against error of the 1D solvers (a benchmark, not a test: nothing is
 * asserted).  Every scheme at six resolutions on
 *   riemann: kinetic paper's Riemann problem (epsilon = 0.4, h 1 | 0.5, t = 5),
 *            L1 error of h against the exact solution;
 *   smooth:  periodic 35 deg slope with Coulomb friction, t = 0.1 (the
 *            verification test's problem, limiter off for DG), L1 error
 *            against RKDG P2 on 2048 cells;
 *   smoothlim: the same with the default limiters on (moment, TVB M = 1,
 *            velocity bound);
 *   ritter:  dam break on a dry flat bed (h 1 | 0 at x = 6 on [0, 20], beta = 1,
 *            wall at x = 0), t = 5: L1 error of h against the exact solution
 *            and the front error (the h = 1e-3 level of the cell means) in cells;
 *   incline: the same dam on a 35 deg slope with Coulomb friction tan 30 deg
 *            (mu constant, u0 = 0; transmissive at x = 0): u > 0 everywhere,
 *            so the exact solution is Ritter's with beta = cos 35 deg in the
 *            frame accelerating at sin 35 - tan 30 cos 35; t = 5: the same
 *            two errors;
 *   cap:     spreading parabolic cap (h0 = 1, l0 = 2, beta = 1) on [-15, 15],
 *            t = 5: the same two errors.
 * The kinetic Schemes 1 and 3 also run with kinetic_order 2 ("o2").  The
 * three dry-front problems also run with the start-up refinement
 * (startup_levels = 3: kinetic 3 at orders 1 and 2 and RKDG P0-P2, "+s3";
 * 5: RKDG P1, P2 and kinetic 3 order 2, "+s5"); its finer grids' CPU time is
 * included, their steps are not counted as cell updates.  RKDG P1 and P2 also on
 * the moving mesh (moving_mesh = 1, "+m"; with 3 and 5 start-up levels,
 * "+m+s3", "+m+s5"), whose L1 error adds the exact depth beyond its ends.
 * The dam breaks also with the Riemann start at t_s = 0.2 (riemann_start:
 * the exact solution up to t_s), RKDG P1 and P2 on the fixed grid ("+r") and
 * the moving mesh ("+m+r", up to N = 3200); the CPU time is from t_s.
 * Prints: problem, scheme, N, L1 error, CPU seconds, cell updates per second
 * (cells x steps / CPU s; DG counts a three-stage step once), front error in
 * cells (nan without a dry front).  CSV on stdout.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "granflow/granflow.h"
#include "granflow/sh1d.h"
#include "granflow/verification.h"


static void rp_init(double x, void *c, double *h, double *u)
{
    (void)c;
    *h = x <= 5.0 ? 1.0 : 0.5;
    *u = 0.0;
}
static void smooth_init(double x, void *c, double *h, double *u)
{
    (void)c;
    *h = 1 + 0.2 * sin(2 * GF_PI * x);
    *u = 1 + 0.1 * cos(2 * GF_PI * x);
}

enum { RIEMANN, SMOOTH, SMOOTHLIM, RITTER, INCLINE, CAP, NPROBLEMS };
static const char *const problem_names[NPROBLEMS] = {"riemann", "smooth", "smoothlim", "ritter", "incline", "cap"};
static const double INCLINE_ZETA = 35 * GF_PI / 180, INCLINE_DELTA = 30 * GF_PI / 180;
#define DRY_FRONT(p) ((p) == RITTER || (p) == INCLINE || (p) == CAP)
static gf_spreading_cap cap;

static void dam_init(double x, void *c, double *h, double *u)
{
    (void)c;
    *h = x <= 6.0 ? 1.0 : 0.0;
    *u = 0.0;
}
static void cap_init(double x, void *c, double *h, double *u)
{
    (void)c;
    gf_spreading_cap_sample(&cap, x, 0.0, h, u);
}

/* the configurations: the kinetic schemes (order 1, the paper's; order 2,
 * the reconstruction with Heun's method) and RKDG P0-P2, without and with
 * the start-up refinement (+s3: startup_levels 3, +s5: 5); the start-up
 * variants run on the dry-front problems only */
struct variant {
    const char *name;
    int kinetic, scheme_or_degree, order, levels, moving, riemann;
};
static const struct variant variants[] = {
    {"kinetic1", 1, 1, 1, 0, 0, 0},         {"kinetic2", 1, 2, 1, 0, 0, 0},         {"kinetic3", 1, 3, 1, 0, 0, 0},
    {"rkdgP0", 0, 0, 0, 0, 0, 0},           {"rkdgP1", 0, 1, 0, 0, 0, 0},           {"rkdgP2", 0, 2, 0, 0, 0, 0},
    {"kinetic1o2", 1, 1, 2, 0, 0, 0},       {"kinetic3o2", 1, 3, 2, 0, 0, 0},       {"kinetic3+s3", 1, 3, 1, 3, 0, 0},
    {"rkdgP0+s3", 0, 0, 0, 3, 0, 0},        {"rkdgP1+s3", 0, 1, 0, 3, 0, 0},        {"rkdgP2+s3", 0, 2, 0, 3, 0, 0},
    {"kinetic3o2+s3", 1, 3, 2, 3, 0, 0},    {"rkdgP1+s5", 0, 1, 0, 5, 0, 0},        {"rkdgP2+s5", 0, 2, 0, 5, 0, 0},
    {"kinetic3o2+s5", 1, 3, 2, 5, 0, 0},    {"rkdgP1+m", 0, 1, 0, 0, 1, 0},      {"rkdgP2+m", 0, 2, 0, 0, 1, 0},
    {"rkdgP1+m+s3", 0, 1, 0, 3, 1, 0},   {"rkdgP2+m+s3", 0, 2, 0, 3, 1, 0},   {"rkdgP1+m+s5", 0, 1, 0, 5, 1, 0},
    {"rkdgP2+m+s5", 0, 2, 0, 5, 1, 0},   {"rkdgP1+r", 0, 1, 0, 0, 0, 1},   {"rkdgP2+r", 0, 2, 0, 0, 0, 1},
    {"rkdgP1+m+r", 0, 1, 0, 0, 1, 1}, {"rkdgP2+m+r", 0, 2, 0, 0, 1, 1},
};
/* the Riemann start's time (riemann_start, "+r"; the dam breaks only) */
#define RIEMANN_START 0.2
#define NVARIANTS ((int)(sizeof variants / sizeof variants[0]))

static void configure(gf_sh1d_config *c, int problem, int variant, size_t n)
{
    gf_sh1d_config_init(c);
    c->n_cells = n;
    if (problem == RITTER) {
        c->x_min = 0;
        c->x_max = 20;
        c->bc_left = GF_BC_WALL;
    } else if (problem == INCLINE) {
        c->x_min = 0;
        c->x_max = 20;
        c->zeta = INCLINE_ZETA;
        gf_friction_init(&c->friction, "coulomb");
        gf_friction_set(&c->friction, "mu", tan(INCLINE_DELTA));
        gf_friction_set(&c->friction, "u0", 0.0);
    } else if (problem == CAP) {
        c->x_min = -15;
        c->x_max = 15;
    } else if (problem == RIEMANN) {
        c->x_min = 0;
        c->x_max = 10;
        c->epsilon = 0.4;
    } else {
        c->x_min = 0;
        c->x_max = 1;
        c->zeta = 35 * GF_PI / 180;
        c->bc_left = c->bc_right = GF_BC_PERIODIC;
        if (problem == SMOOTH) {
            c->limiter = GF_LIMITER_NONE;
            c->velocity_limiter = 0;
        }
        gf_friction_init(&c->friction, "coulomb");
        gf_friction_set(&c->friction, "mu", tan(GF_PI / 6));
        gf_friction_set(&c->friction, "u0", 0.0);
    }
    const struct variant *v = &variants[variant];
    if (v->kinetic)
        c->scheme = v->scheme_or_degree, c->kinetic_order = v->order;
    else
        c->degree = v->scheme_or_degree;
    c->startup_levels = v->levels;
    c->moving_mesh = v->moving;
    c->riemann_start = v->riemann ? RIEMANN_START : 0.0;
}

static gf_sh1d *run(int problem, int variant, size_t n, double *cpu)
{
    gf_sh1d_config c;
    configure(&c, problem, variant, n);
    gf_sh1d *s;
    if (gf_sh1d_alloc(variants[variant].kinetic ? gf_sh1d_kinetic : gf_sh1d_rkdg, &c, &s)) {
        fprintf(stderr, "bench1d: %s\n", gf_error_detail());
        exit(1);
    }
    static const gf_sh1d_initial_fn init[NPROBLEMS] = {rp_init, smooth_init, smooth_init, dam_init,
                                                        dam_init, cap_init};
    gf_sh1d_set_initial(s, init[problem], NULL);
    const clock_t t0 = clock();
    if (gf_sh1d_advance_to(s, problem == SMOOTH || problem == SMOOTHLIM ? 0.1 : 5.0)) {
        fprintf(stderr, "bench1d: %s\n", gf_error_detail());
        exit(1);
    }
    *cpu = (double)(clock() - t0) / CLOCKS_PER_SEC;
    return s;
}

/* last crossing of h = 1e-3 by the cell means, linear between centres (on
 * the moving mesh, between the last centre and the front node, h = 0 there) */
static double front_of(const gf_sh1d *s, const double *h)
{
    const size_t n = gf_sh1d_n_cells(s);
    double lo, hi;
    gf_sh1d_extent(s, &lo, &hi);
    if (h[n - 1] >= 1e-3)
        return gf_sh1d_cell_centre(s, n - 1) + (h[n - 1] - 1e-3) / h[n - 1] * (hi - gf_sh1d_cell_centre(s, n - 1));
    for (size_t i = n - 1; i > 0; --i)
        if (h[i - 1] >= 1e-3 && h[i] < 1e-3)
            return gf_sh1d_cell_centre(s, i - 1) + (h[i - 1] - 1e-3) / (h[i - 1] - h[i]) * gf_sh1d_dx(s);
    return NAN;
}

/* the exact depth of a dry-front problem at (x, t); a: the incline frame's
 * acceleration */
struct exact_at { int problem; const gf_riemann *rp; double a, t; };
static double exact_depth(double x, void *ctx)
{
    const struct exact_at *e = ctx;
    double h, u;
    if (e->problem == CAP)
        gf_spreading_cap_sample(&cap, x, e->t, &h, &u);
    else
        gf_riemann_sample(e->rp, x - 0.5 * e->a * e->t * e->t, e->t, &h, &u);
    return h;
}

/* L1 error of the cell means against the exact cell means (16 samples) and the
 * front error in cells, for the dry-front problems */
static double dry_front_errors(const gf_sh1d *s, int problem, const gf_riemann *ritter,
                               const gf_riemann *incline, double *front)
{
    /* the incline: Ritter with beta = cos zeta in the frame accelerating at a */
    const double a = problem == INCLINE ? sin(INCLINE_ZETA) - tan(INCLINE_DELTA) * cos(INCLINE_ZETA) : 0.0;
    const double beta = problem == INCLINE ? cos(INCLINE_ZETA) : 1.0;
    const size_t n = gf_sh1d_n_cells(s);
    const double dx = gf_sh1d_dx(s), t = 5.0;
    struct exact_at at = {problem, problem == INCLINE ? incline : ritter, a, t};
    double *h = malloc(2 * n * sizeof *h), e = 0.0;
    gf_sh1d_means(s, h, h + n);
    for (size_t i = 0; i < n; ++i) {
        double mean = 0.0;
        for (int k = 0; k < 16; ++k)
            mean += exact_depth(gf_sh1d_cell_centre(s, i) + dx * ((k + 0.5) / 16.0 - 0.5), &at) / 16.0;
        e += fabs(h[i] - mean) * dx;
    }
    /* the moving mesh: the exact depth beyond its ends */
    e += gf_sh1d_depth_beyond(s, exact_depth, &at, 20000);
    double xe;
    if (problem == CAP) {
        double lam, dlam;
        gf_spreading_cap_stretch(&cap, t, &lam, &dlam);
        xe = lam * cap.l0 * sqrt(1.0 - 1e-3 * lam / cap.h0);
    } else {
        /* Ritter's h = 1e-3 level */
        xe = 6.0 + 0.5 * a * t * t + (2.0 * sqrt(beta) - 3.0 * sqrt(beta * 1e-3)) * t;
    }
    *front = (front_of(s, h) - xe) / dx;
    free(h);
    return e;
}

int main(void)
{
    gf_riemann ex, ritter, incline;
    gf_riemann_solve(&ex, 0.4, 1.0, 0.0, 0.5, 0.0, 5.0);
    gf_riemann_solve(&ritter, 1.0, 1.0, 0.0, 0.0, 0.0, 6.0);
    gf_riemann_solve(&incline, cos(INCLINE_ZETA), 1.0, 0.0, 0.0, 0.0, 6.0);
    gf_spreading_cap_init(&cap, 1.0, 1.0, 2.0, 0.0);
    double cpu;
    gf_sh1d *ref = run(SMOOTH, 5, 2048, &cpu);
    printf("problem,scheme,N,L1_error,cpu_s,cell_updates_per_s,front_error_cells\n");
    for (int problem = 0; problem < NPROBLEMS; ++problem)
        for (int v = 0; v < NVARIANTS; ++v)
            for (size_t n = 50; n <= (variants[v].riemann && variants[v].moving ? 3200u : 1600u); n *= 2) {
                if ((variants[v].levels > 0 || variants[v].moving) && !DRY_FRONT(problem))
                    continue;
                if (variants[v].riemann && problem != RITTER && problem != INCLINE)
                    continue; /* a dam on a dry bed */
                const char *only = getenv("GF_BENCH1D_ONLY"); /* "problem/variant", for a quick look */
                char key[64];
                snprintf(key, sizeof key, "%s/%s", problem_names[problem], variants[v].name);
                if (only && !strstr(key, only))
                    continue;
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
                double e, front = NAN;
                if (problem == RIEMANN)
                    e = gf_sh1d_l1_error_riemann(s, &ex, 5.0);
                else if (problem == SMOOTH || problem == SMOOTHLIM)
                    e = gf_sh1d_l1_difference(s, ref);
                else
                    e = dry_front_errors(s, problem, &ritter, &incline, &front);
                printf("%s,%s,%zu,%.6e,%.6e,%.4e,%.3f\n", problem_names[problem], variants[v].name, n, e, cpu,
                       (double)n * (double)gf_sh1d_steps(s) / fmax(cpu, 1e-9), front);
                gf_sh1d_free(s);
            }
    gf_sh1d_free(ref);
    return 0;
}
