/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The total kinetic energy of the owned faces (gf_surface_kinetic_energy):
 * the end condition of a run (the flow has stopped when it falls below a
 * fraction of its running peak, as AvaFrame ends its runs); the faces still
 * moving when a run ends (gf_surface_moving_faces, gf_moving_faces_eval). */
#include "surface_internal.h"
#include "granflow/standard_tests.h"

double gf_surface_kinetic_energy(const gf_surface *s)
{
    /* E_f = 1/2 A_f |m_f|^2 / h_f = 1/2 A_f h_f |u_f|^2 with the kernel's
     * velocity (velocity(): 0 where h <= h_dry, as the stages and the peak
     * speeds take it) */
    double e = 0.0;
    const double hd = s->c.h_dry;
    if (s->scan_all) { /* a state loaded and no step since: the active set is not built */
        for (size_t f = 0; f < s->m.n_faces; ++f)
            if (s->h[f] > hd) {
                const double *m = s->mom + 3 * f;
                e += s->m.area[f] * dot3(m, m) / s->h[f];
            }
        return 0.5 * e;
    }
    /* after a step every owned face with h > 0 is in the active set (its
     * owned part, act_f[0, n_act_owned)): the others are dry */
    for (size_t i = 0; i < s->n_act_owned; ++i) {
        const int f = s->act_f[i];
        if (s->h[f] > hd) {
            const double *m = s->mom + 3 * f;
            e += s->m.area[f] * dot3(m, m) / s->h[f];
        }
    }
    return 0.5 * e;
}

void gf_surface_path_moments(const gf_surface *s, double out[6])
{
    /* every owned face before the first step (the active set is not built),
     * the active set's owned part after it (the other faces are dry) */
    if (s->scan_all)
        gf_path_moments(s->m.n_faces, NULL, s->m.area, s->m.centre, s->h, s->mom, s->c.h_dry, s->c.g, out);
    else
        gf_path_moments(s->n_act_owned, s->act_f, s->m.area, s->m.centre, s->h, s->mom, s->c.h_dry, s->c.g,
                        out);
}

/* one face into the moving-face sums (h > h_dry) */
static void moving_face(gf_moving_faces *o, long f, double area, const double *centre, double h, const double *m,
                        double speed)
{
    const double u = sqrt(dot3(m, m)) / h;
    if (u > speed) {
        ++o->n;
        o->volume += area * h;
    }
    if (u > o->max_speed || o->max_face < 0) {
        o->max_speed = u;
        o->max_face = f;
        memcpy(o->max_centre, centre, sizeof o->max_centre);
    }
}

static gf_status moving_faces_args(double h_dry, double speed, const gf_moving_faces *out)
{
    if (!out)
        return gf_fail(GF_EINVAL, "moving faces: null output");
    if (!isfinite(speed) || !isfinite(h_dry))
        return gf_fail(GF_ENONFINITE, "moving faces: speed %g m/s, h_dry %g m: must be finite", speed, h_dry);
    if (speed < 0.0)
        return gf_fail(GF_EDOM, "moving faces: speed threshold %g m/s: allowed >= 0", speed);
    if (h_dry < 0.0)
        return gf_fail(GF_EDOM, "moving faces: h_dry %g m: allowed >= 0", h_dry);
    return GF_SUCCESS;
}

static void moving_faces_zero(gf_moving_faces *out)
{
    memset(out, 0, sizeof *out);
    out->max_face = -1;
}

gf_status gf_moving_faces_eval(size_t n, const double *area, const double *centre, const double *h,
                               const double *m, double h_dry, double speed, gf_moving_faces *out)
{
    const gf_status st = moving_faces_args(h_dry, speed, out);
    if (st != GF_SUCCESS)
        return st;
    if (n > 0 && (!area || !centre || !h || !m))
        return gf_fail(GF_EINVAL, "moving faces: null array for %zu faces", n);
    moving_faces_zero(out);
    for (size_t f = 0; f < n; ++f)
        if (h[f] > h_dry)
            moving_face(out, (long)f, area[f], centre + 3 * f, h[f], m + 3 * f, speed);
    return GF_SUCCESS;
}

gf_status gf_surface_moving_faces(const gf_surface *s, double speed, gf_moving_faces *out)
{
    if (!s)
        return gf_fail(GF_EINVAL, "gf_surface_moving_faces: null solver");
    const double hd = s->c.h_dry;
    if (s->scan_all) /* a state loaded and no step since: the active set is not built */
        return gf_moving_faces_eval(s->m.n_faces, s->m.area, s->m.centre, s->h, s->mom, hd, speed, out);
    const gf_status st = moving_faces_args(hd, speed, out);
    if (st != GF_SUCCESS)
        return st;
    moving_faces_zero(out);
    /* the active set's owned part holds every owned face with h > 0; its
     * order is not the face order: the fastest face is the lowest index
     * among equal speeds */
    for (size_t i = 0; i < s->n_act_owned; ++i) {
        const int f = s->act_f[i];
        if (s->h[f] > hd) {
            const double *m = s->mom + 3 * f;
            const double u = sqrt(dot3(m, m)) / s->h[f];
            if (u == out->max_speed && out->max_face >= 0 && f < out->max_face) {
                out->max_face = f;
                memcpy(out->max_centre, s->m.centre + 3 * (size_t)f, sizeof out->max_centre);
            }
            moving_face(out, f, s->m.area[f], s->m.centre + 3 * (size_t)f, s->h[f], m, speed);
        }
    }
    return GF_SUCCESS;
}
