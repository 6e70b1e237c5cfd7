/* SPDX-License-Identifier: GPL-3.0-or-later */
#include "granflow/earth_pressure.h"
#include "internal.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

gf_status gf_earth_pressure_coefficients(double phi, double delta,
                                         double *k_act, double *k_pass)
{
    gf_status st;
    if (!k_act || !k_pass)
        return gf_fail(GF_EINVAL, "gf_earth_pressure_coefficients: null output pointer");
    if ((st = gf_check_range("internal friction angle phi [rad]", phi, 1e-12, 0.5 * GF_PI - 1e-12)))
        return st;
    if ((st = gf_check_range("bed friction angle delta [rad]", delta, 0.0, 0.5 * GF_PI - 1e-12)))
        return st;
    if (delta > phi)
        return gf_fail(GF_EPHYS,
                       "bed friction angle delta = %g deg exceeds internal friction angle "
                       "phi = %g deg: 1 - cos^2(phi)/cos^2(delta) < 0, so K_act and K_pass "
                       "are complex (doc/theory/savage-hutter.md, section 3); require delta <= phi",
                       delta * GF_RAD2DEG, phi * GF_RAD2DEG);
    const double cphi = cos(phi), cdel = cos(delta);
    double arg = 1.0 - (cphi * cphi) / (cdel * cdel);
    if (arg < 0.0) /* delta == phi up to rounding */
        arg = 0.0;
    const double sec2 = 1.0 / (cphi * cphi);
    *k_act = 2.0 * sec2 * (1.0 - sqrt(arg)) - 1.0;
    *k_pass = 2.0 * sec2 * (1.0 + sqrt(arg)) - 1.0;
    return GF_SUCCESS;
}

gf_status gf_earth_pressure_init(gf_earth_pressure *ep, gf_earth_pressure_model model,
                                 double phi, double delta)
{
    if (!ep)
        return gf_fail(GF_EINVAL, "gf_earth_pressure_init: null model pointer");
    switch (model) {
    case GF_EARTH_PRESSURE_ISOTROPIC:
        ep->model = model;
        ep->k_act = ep->k_pass = 1.0;
        return GF_SUCCESS;
    case GF_EARTH_PRESSURE_SAVAGE_HUTTER: {
        double ka, kp;
        gf_status st = gf_earth_pressure_coefficients(phi, delta, &ka, &kp);
        if (st)
            return st;
        ep->model = model;
        ep->k_act = ka;
        ep->k_pass = kp;
        return GF_SUCCESS;
    }
    }
    return gf_fail(GF_EINVAL, "gf_earth_pressure_init: unknown model code %d", (int)model);
}

gf_status gf_earth_pressure_model_from_name(const char *name, gf_earth_pressure_model *model)
{
    if (!name || !model)
        return gf_fail(GF_EINVAL, "gf_earth_pressure_model_from_name: null argument");
    if (strcmp(name, "isotropic") == 0) {
        *model = GF_EARTH_PRESSURE_ISOTROPIC;
        return GF_SUCCESS;
    }
    if (strcmp(name, "savageHutter") == 0) {
        *model = GF_EARTH_PRESSURE_SAVAGE_HUTTER;
        return GF_SUCCESS;
    }
    return gf_fail(GF_ENOTFOUND,
                   "unknown earth-pressure model '%s'; valid names: isotropic, savageHutter",
                   name);
}

double gf_earth_pressure_k(const gf_earth_pressure *ep, double dudx)
{
    return dudx >= 0.0 ? ep->k_act : ep->k_pass;
}
