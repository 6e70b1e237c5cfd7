/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Lake at rest under the explicit surface scheme (granflow/surface.h): a
 * diagnostic, not a test (nothing is asserted; test_surface's
 * lake_at_rest_with_shorelines asserts it to 1e-12).  It prints how far a
 * frictionless lake drifts: round-off only, since the static edges keep the
 * basal pressure hydrostatic (surface.h).
 *
 * On the structured strip of tests/surface_mesh.h (20 m along the slope,
 * 4 faces across, walls all round), no friction, a lake with a horizontal
 * free surface: h = (eta - z_f) / n_z,f, the normal thickness of a
 * horizontal surface over each face's plane (strip_lake: the basal
 * pressure is rho g (eta - z_f)).  Scenes:
 *   plane:  a 20 deg plane, the lake 1 m deep (vertically) at the low wall,
 *           its shoreline on the slope;
 *   valley: 30 deg down to 30 deg up (zeta = 30 deg tanh((10 - s)/3)), the
 *           lake 1 m deep at the bottom, two shorelines;
 *   full:   the 20 deg plane filled wall to wall (10 m deep at the low wall),
 *           no shoreline.
 * For 40, 80 and 160 faces along the slope, 2000 steps at the largest stable
 * step; prints scene, faces along the slope, time reached, max |h - h0|, max
 * speed and the mass-weighted mean speed (faces with h > 1e-6 m).  A
 * well-balanced scheme keeps all three at round-off.
 *   gf_lake_at_rest      CSV on stdout
 */
#include "../surface_mesh.h"

#include <stdio.h>

#include "granflow/constants.h"
#include "granflow/status.h"
#include "granflow/surface.h"

static double plane(double s, void *ctx)
{
    (void)s;
    (void)ctx;
    return 20 * GF_DEG;
}

static double valley(double s, void *ctx)
{
    (void)ctx;
    return 30 * GF_DEG * tanh((10.0 - s) / 3.0);
}

int main(void)
{
    static const int walls[4] = {GF_EDGE_WALL, GF_EDGE_WALL, GF_EDGE_WALL, GF_EDGE_WALL};
    static const char *const names[3] = {"plane", "valley", "full"};
    printf("scene,faces_along,t_s,max_dh_m,max_speed_m_s,mean_speed_m_s\n");
    for (int scene = 0; scene < 3; ++scene)
        for (size_t nx = 40; nx <= 160; nx *= 2) {
            strip_mesh *sm = strip_mesh_new(nx, 4, 0, 20, -1, 1, scene == 1 ? valley : plane, NULL, walls);
            gf_surface_config c;
            gf_surface_config_default(&c);
            gf_surface *s = NULL;
            if (gf_surface_alloc(&sm->m, &c, &s)) {
                fprintf(stderr, "gf_lake_at_rest: %s\n", gf_error_detail());
                return 1;
            }
            const size_t nf = sm->m.n_faces;
            double *h0 = strip_lake(sm, scene == 2 ? 10.0 : 1.0);
            if (gf_surface_set_state(s, h0, NULL)) {
                fprintf(stderr, "gf_lake_at_rest: %s\n", gf_error_detail());
                return 1;
            }
            double t = 0.0;
            for (int n = 0; n < 2000; ++n) {
                double dt;
                if (gf_surface_max_dt(s, &dt) || gf_surface_step(s, dt)) {
                    fprintf(stderr, "gf_lake_at_rest: %s\n", gf_error_detail());
                    return 1;
                }
                t += dt;
            }
            const double *h = gf_surface_h(s), *m = gf_surface_momentum(s);
            double dh = 0.0, umax = 0.0, mom = 0.0, mass = 0.0;
            for (size_t f = 0; f < nf; ++f) {
                dh = fmax(dh, fabs(h[f] - h0[f]));
                if (h[f] > 1e-6) {
                    const double p = sqrt(m[3 * f] * m[3 * f] + m[3 * f + 1] * m[3 * f + 1] + m[3 * f + 2] * m[3 * f + 2]);
                    umax = fmax(umax, p / h[f]);
                    mom += p * sm->m.area[f];
                    mass += h[f] * sm->m.area[f];
                }
            }
            printf("%s,%zu,%.2f,%.3e,%.3e,%.3e\n", names[scene], nx, t, dh, umax, mom / mass);
            gf_surface_free(s);
            strip_mesh_free(sm);
            free(h0);
        }
    return 0;
}
