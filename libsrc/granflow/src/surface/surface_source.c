/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Sources and friction of the surface scheme: the face update of a stage
 * (mass, momentum with gravity and the basal pressure of eq. 33, then the
 * implicit friction update). */
#include "surface_internal.h"
#include "surface_source.h"
#include "friction_speed.h"

/* samosAT's speeds (u0 = 0) wait in a queue of four faces and are taken
 * four at a time (gf_friction_implicit_speed_samosat4, each lane the scalar
 * result bit for bit): the per-face Newton iterations, the largest part of
 * a terrain step with samosAT, then share their divisions */
struct fq {
    int n, f[4];
    double h[4], pb[4], M[4], ms[4][3];
};

static void flush_queue(gf_surface *s, struct fq *q, double dt, double *Mo)
{
    if (q->n == 0)
        return;
    for (int k = q->n; k < 4; ++k) /* padding lanes: the first one's state, results unused */
        q->h[k] = q->h[0], q->pb[k] = q->pb[0], q->M[k] = q->M[0];
    double speed[4];
    gf_friction_implicit_speed_samosat4(&s->c.friction, q->h, q->pb, s->c.rho, q->M, dt, speed);
    for (int k = 0; k < q->n; ++k) {
        const double r = q->h[k] * speed[k] / q->M[k];
        if (speed[k] == 0.0)
            s->st.stopped_faces++;
        double *mo = Mo + 3 * q->f[k];
        for (int j = 0; j < 3; ++j)
            mo[j] = q->ms[k][j] * r;
    }
    q->n = 0;
}

gf_status gf_surface_update_faces(gf_surface *s, double dt, const double *H, const double *M, double *Ho,
                                  double *Mo)
{
    const gf_surface_mesh *m = &s->m;
    const gf_surface_config *c = &s->c;
    gf_status st;
    const double gm = s->gmag;
    const int lanes = gf_friction_samosat4(&c->friction);
    struct fq q = {0};
    for (size_t i = 0; i < s->n_act_owned; ++i) {
        const int f = s->act_f[i];
        const double rA = 1.0 / m->area[f], h = H[f], *nf = m->normal + 3 * f;
        double hn = h - dt * rA * s->acc_h[f];
        if (hn < 0.0) {
            s->st.roundoff_faces++;
            s->st.roundoff_volume += -hn * m->area[f];
            hn = 0.0;
        }
        Ho[f] = hn;
        /* div F per unit area; p_b/rho from the normal projection, eq. (33) */
        const double *acc = s->acc_m + 3 * f;
        const double ndiv = dot3(acc, nf) * rA, npress = s->acc_pn[f] * rA;
        const int hs = s->stat[f]; /* hydrostatic mode: gravity along the surface is in the edge pressures */
        double pbr = -h * dot3(c->g, nf);
        if (c->centrifugal && !hs)
            pbr += ndiv - npress;
        if (c->lateral_feedback)
            pbr += npress;
        if (pbr < 0.0 || h <= c->h_dry)
            pbr = h > c->h_dry ? 0.0 : gmax(0.0, -h * dot3(c->g, nf));
        if (f < (int)m->n_faces)
            s->pb[f] = c->rho * pbr;
        double ms[3];
        for (int k = 0; k < 3; ++k)
            ms[k] = M[3 * f + k] + dt * ((hs ? 0.0 : h * c->g[k]) - acc[k] * rA);
        const double mn = dot3(ms, nf);
        for (int k = 0; k < 3; ++k)
            ms[k] -= mn * nf[k]; /* tangential part, eq. (35) */
        double *mo = Mo + 3 * f;
        const double gn = -dot3(c->g, nf);
        if (hn > c->h_dry) {
            const double Mag = sqrt(dot3(ms, ms));
            double speed = 0.0;
            s->a[f] = h > c->h_dry ? pbr / h : gmax(0.0, gn);
            if (Mag > 0.0) {
                const gf_friction_state fs = {hn, 0.0, c->rho * pbr, c->rho, gm};
                if (lanes && gf_friction_implicit_args_ok(&fs, Mag, dt)) {
                    const int k = q.n++;
                    q.f[k] = f, q.h[k] = hn, q.pb[k] = fs.pb, q.M[k] = Mag;
                    memcpy(q.ms[k], ms, sizeof ms);
                    if (q.n == 4)
                        flush_queue(s, &q, dt, Mo);
                    continue;
                }
                if ((st = gf_friction_implicit_speed_inline(&c->friction, &fs, Mag, dt, &speed)))
                    return st;
            }
            const double r = Mag > 0.0 ? hn * speed / Mag : 0.0;
            if (Mag > 0.0 && speed == 0.0)
                s->st.stopped_faces++;
            for (int k = 0; k < 3; ++k)
                mo[k] = ms[k] * r;
        } else {
            mo[0] = mo[1] = mo[2] = 0.0;
            s->a[f] = gmax(0.0, gn);
        }
    }
    flush_queue(s, &q, dt, Mo);
    return GF_SUCCESS;
}
