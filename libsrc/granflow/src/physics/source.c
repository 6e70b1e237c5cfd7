/* SPDX-License-Identifier: GPL-3.0-or-later */
#include "granflow/source.h"
#include "granflow/friction.h"

#include <math.h>

double gf_sh_beta_c(double epsilon, double k, double cos_zeta) { return epsilon * k * cos_zeta; }
double gf_sh_beta(double epsilon, double k, double zeta) { return gf_sh_beta_c(epsilon, k, cos(zeta)); }

double gf_sh_moving_accel(double g_sin_zeta, double r, double u)
{
    if (u == 0.0)
        return g_sin_zeta;
    return u > 0.0 ? g_sin_zeta - r : g_sin_zeta + r; /* eq. (2) */
}

double gf_sh_clamp_static(double g_sin_zeta, double r, double beta_dhdx)
{
    return fmin(g_sin_zeta + r, fmax(beta_dhdx, g_sin_zeta - r));
}

double gf_sh_normal_acceleration_c(double g, double cos_zeta, double curv, double u)
{
    const double a = g * cos_zeta + curv * u * u;
    return a > 0.0 ? a : 0.0;
}

double gf_sh_normal_acceleration(double g, double zeta, double curv, double u)
{
    return gf_sh_normal_acceleration_c(g, cos(zeta), curv, u);
}

double gf_sh_driving(double g, double zeta, double curv, double mu, double u)
{
    return gf_sh_moving_accel(g * sin(zeta), mu * gf_sh_normal_acceleration(g, zeta, curv, u), u);
}

double gf_sh_static_bound(double g, double zeta, double mu)
{
    /* the Coulomb law's static bound (friction.c, its one home) per unit
     * thickness and density: p_b/rho = h max(0, g cos zeta) with h = 1 */
    gf_friction f;
    double tau;
    const gf_friction_state st = {1.0, 0.0, gf_sh_normal_acceleration(g, zeta, 0.0, 0.0), 1.0, fabs(g)};
    if (gf_friction_init(&f, "coulomb") || gf_friction_set(&f, "mu", mu) ||
        gf_friction_static_bound(&f, &st, &tau))
        return NAN; /* mu outside [0, 10] or a non-finite state */
    return tau;
}

double gf_sh_static_source(double g, double zeta, double mu, double beta_dhdx)
{
    return gf_sh_clamp_static(g * sin(zeta), gf_sh_static_bound(g, zeta, mu), beta_dhdx);
}

int gf_sh_admissible(double g, double zeta, double mu, double beta_dhdx)
{
    return gf_sh_static_source(g, zeta, mu, beta_dhdx) == beta_dhdx;
}

double gf_dynamic_pressure(double rho, double u) { return rho * u * u; }
