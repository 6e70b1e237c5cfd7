/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Single-core throughput of the explicit surface kernel (granflow/surface.h),
 * without OpenFOAM: a benchmark, not a test (nothing is asserted).
 *
 * Scenes, on the structured strip of tests/surface_mesh.h (walls all round):
 *   wet:   a 50 m x 50 m plane at 30 deg, 200 x 200 faces, covered everywhere
 *          (h = 1 m plus a Gaussian bump): every face is active;
 *   pile:  a 100 m x 100 m plane at 30 deg, 400 x 400 faces, a paraboloid pile
 *          of radius 10 m: the active set (wet faces and two rings) is
 *          6,600-8,500 faces, 4-5% of the mesh, so the rate shows what the
 *          dry part costs.
 * For orders 1 and 2 and the friction laws none, coulomb, mu_i, voellmy and
 * samosAT (all with u0 = 0, as the explicit scheme's cases set them), each
 * run makes 40 timed steps at the largest stable step, after one untimed
 * step (first touch of the buffers); the best of three runs is printed (the
 * machine is noisy):
 *   scene, order, friction, faces, active faces (last step), steps, CPU s,
 *   face-steps per CPU second (active faces summed over steps / CPU s).
 * A face-step is two SSP-RK2 stages: velocity, gradients and limiter (order
 * 2), HLL edge fluxes, the update with implicit friction, the step bound.
 *   gf_bench_surface [steps [scene order friction]]     CSV on stdout
 * (with scene, order and friction given, only that run: for profiling and
 * paired timings)
 */
#include "../surface_mesh.h"

#include <stdio.h>
#include <time.h>

#include "granflow/constants.h"
#include "granflow/status.h"
#include "granflow/surface.h"

static double const_zeta(double s, void *ctx)
{
    (void)s;
    return *(double *)ctx;
}

static void set_friction(gf_friction *f, const char *law)
{
    if (gf_friction_init(f, law)) {
        fprintf(stderr, "gf_bench_surface: %s\n", gf_error_detail());
        exit(1);
    }
    if (strcmp(law, "coulomb") == 0)
        gf_friction_set(f, "mu", tan(20 * GF_DEG));
    if (strcmp(law, "none") != 0) /* exact Coulomb part: the explicit scheme's setting */
        gf_friction_set(f, "u0", 0.0);
}

/* one run: returns CPU seconds; active faces summed over steps, last active */
static double run(const strip_mesh *sm, int pile, int order, const char *law, long steps,
                  unsigned long *updates, size_t *active)
{
    gf_surface_config c;
    gf_surface_config_default(&c);
    c.order = order;
    set_friction(&c.friction, law);
    gf_surface *s = NULL;
    if (gf_surface_alloc(&sm->m, &c, &s)) {
        fprintf(stderr, "gf_bench_surface: %s\n", gf_error_detail());
        exit(1);
    }
    const size_t nf = sm->m.n_faces;
    const double sc = 0.5 * (sm->s0 + sm->s1);
    double *h = malloc(nf * sizeof *h);
    for (size_t f = 0; f < nf; ++f) {
        const double ds = sm->s_of_face[f] - sc, y = sm->centre[3 * f + 1], r2 = ds * ds + y * y;
        h[f] = pile ? (r2 < 100.0 ? 2.0 * (1.0 - r2 / 100.0) : 0.0) : 1.0 + 0.5 * exp(-r2 / 20.0);
    }
    if (gf_surface_set_state(s, h, NULL)) {
        fprintf(stderr, "gf_bench_surface: %s\n", gf_error_detail());
        exit(1);
    }
    /* one untimed step first: it touches the freshly allocated buffers (page
     * faults, a few per cent of 40 steps) and builds the first active set
     * from a scan of the mesh; the timed steps are those of a long run */
    gf_surface_stats st0, st;
    clock_t t0 = 0;
    for (long n = 0; n <= steps; ++n) {
        if (n == 1) {
            gf_surface_get_stats(s, &st0);
            t0 = clock();
        }
        double dt;
        if (gf_surface_max_dt(s, &dt) || gf_surface_step(s, dt)) {
            fprintf(stderr, "gf_bench_surface: %s\n", gf_error_detail());
            exit(1);
        }
    }
    const double cpu = (double)(clock() - t0) / CLOCKS_PER_SEC;
    gf_surface_get_stats(s, &st);
    *updates = st.face_updates - st0.face_updates;
    *active = st.active_faces;
    gf_surface_free(s);
    free(h);
    return cpu;
}

int main(int argc, char **argv)
{
    char *end = NULL;
    const long steps = argc > 1 ? strtol(argv[1], &end, 10) : 40;
    const char *only_scene = argc == 5 ? argv[2] : NULL, *only_law = argc == 5 ? argv[4] : NULL;
    const int only_order = argc == 5 ? atoi(argv[3]) : 0;
    if ((argc != 1 && argc != 2 && argc != 5) || (argc > 1 && (end == argv[1] || *end != '\0')) || steps < 1 ||
        steps > 1000000 || (only_scene && strcmp(only_scene, "wet") && strcmp(only_scene, "pile")) ||
        (argc == 5 && only_order != 1 && only_order != 2)) {
        fprintf(stderr, "usage: gf_bench_surface [steps [scene order friction]]: steps an integer in 1..1000000 "
                        "(default 40), scene wet or pile, order 1 or 2, friction none, coulomb, mu_i, voellmy or "
                        "samosAT\n");
        return 1;
    }
    static const int walls[4] = {GF_EDGE_WALL, GF_EDGE_WALL, GF_EDGE_WALL, GF_EDGE_WALL};
    static const char *const laws[] = {"none", "coulomb", "mu_i", "voellmy", "samosAT"};
    double zeta = 30 * GF_DEG;
    printf("scene,order,friction,faces,active_faces,steps,cpu_s,face_steps_per_s\n");
    int ran = 0;
    for (int pile = 0; pile < 2; ++pile) {
        if (only_scene && strcmp(only_scene, pile ? "pile" : "wet"))
            continue;
        const size_t n = pile ? 400 : 200;
        const double half = pile ? 50.0 : 25.0;
        strip_mesh *sm = strip_mesh_new(n, n, 0, 2 * half, -half, half, const_zeta, &zeta, walls);
        for (int order = 1; order <= 2; ++order)
            for (size_t l = 0; l < sizeof laws / sizeof laws[0]; ++l) {
                if (only_scene && (order != only_order || strcmp(only_law, laws[l])))
                    continue;
                ran = 1;
                double best = HUGE_VAL;
                unsigned long updates = 0;
                size_t active = 0;
                for (int rep = 0; rep < 3; ++rep)
                    best = fmin(best, run(sm, pile, order, laws[l], steps, &updates, &active));
                printf("%s,%d,%s,%zu,%zu,%ld,%.3f,%.3e\n", pile ? "pile" : "wet", order, laws[l],
                       sm->m.n_faces, active, steps, best, (double)updates / fmax(best, 1e-9));
                fflush(stdout);
            }
        strip_mesh_free(sm);
    }
    if (!ran) {
        fprintf(stderr, "gf_bench_surface: no friction law named '%s'\n", only_law);
        return 1;
    }
    return 0;
}
