/* Sources and friction of the surface scheme: the face update of a stage
 * (mass, momentum with gravity and the basal pressure of eq. 33, then the
 * implicit friction update). */
#include "surface_internal.h"
#include "surface_source.h"
#include "friction_speed.h"

gf_status gf_surface_update_faces(gf_surface *s, double dt, const double *H, const double *M, double *Ho,
                                  double *Mo)
{
    const gf_surface_mesh *m = &s->m;
    const gf_surface_config *c = &s->c;
    gf_status st;
    const double gm = s->gmag;
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
            if (Mag > 0.0) {
                const gf_friction_state fs = {hn, 0.0, c->rho * pbr, c->rho, gm};
                if ((st = gf_friction_implicit_speed_inline(&c->friction, &fs, Mag, dt, &speed)))
                    return st;
            }
            const double r = Mag > 0.0 ? hn * speed / Mag : 0.0;
            if (Mag > 0.0 && speed == 0.0)
                s->st.stopped_faces++;
            for (int k = 0; k < 3; ++k)
                mo[k] = ms[k] * r;
            s->a[f] = h > c->h_dry ? pbr / h : gmax(0.0, gn);
        } else {
            mo[0] = mo[1] = mo[2] = 0.0;
            s->a[f] = gmax(0.0, gn);
        }
    }
    return GF_SUCCESS;
}
