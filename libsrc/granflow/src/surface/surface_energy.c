/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The total kinetic energy of the owned faces (gf_surface_kinetic_energy):
 * the end condition of a run (the flow has stopped when it falls below a
 * fraction of its running peak, as AvaFrame ends its runs). */
#include "surface_internal.h"

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
