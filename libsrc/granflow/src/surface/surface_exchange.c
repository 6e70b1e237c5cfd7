/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Mass exchange of the explicit surface scheme (granflow/surface.h,
 * gf_surface_set_mass_exchange): the pointwise updates of
 * granflow/mass_exchange.h (spec doc/theory/mass-exchange.md, §1-2)
 * applied once per step, after the SSP-RK2 combination, to the owned
 * active faces; the per-face fields and totals of spec §4. */
#include "surface_internal.h"
#include "surface_exchange.h"

#include <stdlib.h>

void gf_surface_exchange_free(gf_surface *s)
{
    if (!s->mx)
        return;
    free(s->mx->h_ent);
    free(s->mx->h_front);
    free(s->mx->res);
    free(s->mx->ent);
    free(s->mx->det);
    free(s->mx);
    s->mx = NULL;
}

gf_status gf_surface_set_mass_exchange(gf_surface *s, const gf_mass_exchange_config *cfg, const double *h_ent,
                                       const double *resistance)
{
    if (!s)
        return gf_fail(GF_EINVAL, "gf_surface_set_mass_exchange: null solver");
    gf_surface_exchange_free(s);
    if (!cfg || (!cfg->entrainment && !cfg->resistance))
        return GF_SUCCESS; /* simType null: off */
    gf_status st;
    if ((st = gf_mass_exchange_config_check(cfg)))
        return st;
    if (s->c.startup_levels > 0)
        return gf_fail(GF_EINVAL, "surface scheme: mass exchange with startup_levels = %d: the start-up's refined "
                                  "meshes carry no entrainable layer or resistance areas; set startup_levels 0",
                       s->c.startup_levels);
    if (cfg->entrainment && !h_ent)
        return gf_fail(GF_EINVAL, "surface scheme: entrainment is on but no entrainable depth field is given");
    if (cfg->resistance && !resistance)
        return gf_fail(GF_EINVAL, "surface scheme: resistance is on but no resistance field is given");
    const size_t nf = s->m.n_faces;
    for (size_t f = 0; f < nf; ++f) {
        if (h_ent && !(h_ent[f] >= 0.0 && isfinite(h_ent[f])))
            return gf_fail(isfinite(h_ent[f]) ? GF_EDOM : GF_ENONFINITE,
                           "surface scheme: entrainable depth %g m in face %zu (must be finite, >= 0)", h_ent[f], f);
        if (resistance && !(resistance[f] >= 0.0 && isfinite(resistance[f])))
            return gf_fail(isfinite(resistance[f]) ? GF_EDOM : GF_ENONFINITE,
                           "surface scheme: resistance factor %g in face %zu (must be finite, >= 0)", resistance[f],
                           f);
    }
    struct gf_surface_mx *x = calloc(1, sizeof *x);
    if (!x)
        return gf_fail(GF_ENOMEM, "surface scheme: out of memory for the mass exchange");
    s->mx = x;
    x->c = *cfg;
    x->h_ent = calloc(nf, sizeof *x->h_ent);
    x->h_front = calloc(nf, sizeof *x->h_front);
    x->ent = calloc(nf, sizeof *x->ent);
    x->det = calloc(nf, sizeof *x->det);
    x->res = cfg->resistance ? malloc(nf * sizeof *x->res) : NULL;
    if (!x->h_ent || !x->h_front || !x->ent || !x->det || (cfg->resistance && !x->res)) {
        gf_surface_exchange_free(s);
        return gf_fail(GF_ENOMEM, "surface scheme: out of memory for the mass exchange of %zu faces", nf);
    }
    if (cfg->entrainment) {
        memcpy(x->h_ent, h_ent, nf * sizeof *x->h_ent);
        memcpy(x->h_front, h_ent, nf * sizeof *x->h_front);
    }
    if (cfg->resistance)
        memcpy(x->res, resistance, nf * sizeof *x->res);
    return GF_SUCCESS;
}

gf_status gf_surface_exchange_step(gf_surface *s, double dt, int *dried)
{
    struct gf_surface_mx *x = s->mx;
    const gf_surface_config *c = &s->c;
    const double *area = s->m.area;
    double ve = 0.0, vd = 0.0, vs = 0.0, vr = 0.0;
    gf_status st;
    for (size_t i = 0; i < s->n_act_owned; ++i) {
        const int f = s->act_f[i];
        const double h = s->h[f], res = x->res ? x->res[f] : 0.0;
        if (!(h > 0.0) || (x->h_ent[f] == 0.0 && res == 0.0))
            continue; /* nothing to exchange */
        double u[3], *m = s->mom + 3 * f;
        velocity(s, s->h, s->mom, f, u);
        const double speed = sqrt(dot3(u, u));
        double tau_b = 0.0;
        if (x->h_ent[f] > 0.0 && speed > 0.0 && x->c.e_b > 0.0) {
            /* spec §1: τ_b of the friction law at the face's state */
            const gf_friction_state fs = {h, speed, s->pb[f], c->rho, s->gmag};
            gf_friction_result fr;
            if ((st = gf_friction_eval(&c->friction, &fs, &fr)))
                return gf_fail(st, "surface scheme: face %d: basal shear stress for erosion: %s", f,
                               gf_error_detail());
            tau_b = c->rho * fr.tau;
        }
        const gf_mass_exchange_face in = {h, speed, area[f], c->rho, tau_b, x->h_ent[f], x->h_front[f], res};
        gf_mass_exchange_result r;
        if ((st = gf_mass_exchange_face_update(&x->c, &in, dt, &r)))
            return gf_fail(st, "surface scheme: face %d: %s", f, gf_error_detail());
        s->h[f] = r.h;
        x->h_ent[f] = r.h_ent;
        if (r.h == 0.0) {
            m[0] = m[1] = m[2] = 0.0;
            s->a[f] = s->ahyd[f];
            *dried = 1;
        } else if (r.mom_factor != 1.0)
            m[0] *= r.mom_factor, m[1] *= r.mom_factor, m[2] *= r.mom_factor;
        x->ent[f] += r.entrained;
        x->det[f] += r.detrained;
        ve += area[f] * r.entrained;
        vd += area[f] * r.detrained;
        if (r.detrained > 0.0 && speed < x->c.v_min) { /* the speed window (spec §2) */
            vs += area[f] * r.detrained;
            if (speed == 0.0)
                vr += area[f] * r.detrained; /* at rest: K/|u| unbounded, the whole face */
        }
    }
    x->ent_step += ve;
    x->det_step += vd;
    x->ent_total += ve;
    x->det_total += vd;
    x->det_slow_step += vs;
    x->det_rest_step += vr;
    x->det_slow_total += vs;
    x->det_rest_total += vr;
    return GF_SUCCESS;
}

const double *gf_surface_entrainable_depth(const gf_surface *s) { return s->mx ? s->mx->h_ent : NULL; }
const double *gf_surface_entrained_depth(const gf_surface *s) { return s->mx ? s->mx->ent : NULL; }
const double *gf_surface_detrained_depth(const gf_surface *s) { return s->mx ? s->mx->det : NULL; }

void gf_surface_get_exchange(const gf_surface *s, gf_surface_exchange *out)
{
    memset(out, 0, sizeof *out);
    if (!s->mx)
        return;
    out->entrained_step = s->mx->ent_step;
    out->detrained_step = s->mx->det_step;
    out->entrained = s->mx->ent_total;
    out->detrained = s->mx->det_total;
    out->detrained_slow_step = s->mx->det_slow_step;
    out->detrained_rest_step = s->mx->det_rest_step;
    out->detrained_slow = s->mx->det_slow_total;
    out->detrained_rest = s->mx->det_rest_total;
}

gf_status gf_surface_restore_mass_exchange(gf_surface *s, const double *h_ent_left, const double *entrained,
                                           const double *detrained, const gf_surface_exchange *x)
{
    if (!s || !s->mx)
        return gf_fail(GF_EINVAL, "surface scheme: restoring the mass exchange: none is set "
                                  "(gf_surface_set_mass_exchange first)");
    struct gf_surface_mx *mx = s->mx;
    const size_t nf = s->m.n_faces;
    for (size_t f = 0; f < nf; ++f) {
        const double v[3] = {h_ent_left ? h_ent_left[f] : mx->h_ent[f], entrained ? entrained[f] : 0.0,
                             detrained ? detrained[f] : 0.0};
        static const char *const what[3] = {"entrainable depth left", "entrained depth", "detrained depth"};
        for (int k = 0; k < 3; ++k)
            if (!(v[k] >= 0.0) || !isfinite(v[k]))
                return gf_fail(isfinite(v[k]) ? GF_EDOM : GF_ENONFINITE,
                               "surface scheme: restoring the mass exchange: %s %g m in face %zu (must be finite, "
                               ">= 0)", what[k], v[k], f);
        if (v[0] > mx->h_front[f])
            return gf_fail(GF_EDOM, "surface scheme: restoring the mass exchange: entrainable depth left %g m in "
                                    "face %zu exceeds the layer set, %g m", v[0], f, mx->h_front[f]);
    }
    for (size_t f = 0; f < nf; ++f) {
        if (h_ent_left)
            mx->h_ent[f] = h_ent_left[f];
        mx->ent[f] = entrained ? entrained[f] : 0.0;
        mx->det[f] = detrained ? detrained[f] : 0.0;
    }
    mx->ent_step = mx->det_step = mx->det_slow_step = mx->det_rest_step = 0.0;
    mx->ent_total = x ? x->entrained : 0.0;
    mx->det_total = x ? x->detrained : 0.0;
    mx->det_slow_total = x ? x->detrained_slow : 0.0;
    mx->det_rest_total = x ? x->detrained_rest : 0.0;
    return GF_SUCCESS;
}
