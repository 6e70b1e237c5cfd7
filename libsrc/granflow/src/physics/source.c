#include "granflow/source.h"

#include <math.h>

double gf_sh_beta(double epsilon, double k, double zeta) { return epsilon * k * cos(zeta); }

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

double gf_sh_normal_acceleration(double g, double zeta, double curv, double u)
{
    const double a = g * cos(zeta) + curv * u * u;
    return a > 0.0 ? a : 0.0;
}

double gf_sh_driving(double g, double zeta, double curv, double mu, double u)
{
    return gf_sh_moving_accel(g * sin(zeta), mu * gf_sh_normal_acceleration(g, zeta, curv, u), u);
}

double gf_sh_static_bound(double g, double zeta, double mu)
{
    return mu * gf_sh_normal_acceleration(g, zeta, 0.0, 0.0);
}

double gf_sh_static_source(double g, double zeta, double mu, double beta_dhdx)
{
    return gf_sh_clamp_static(g * sin(zeta), gf_sh_static_bound(g, zeta, mu), beta_dhdx);
}

int gf_sh_admissible(double g, double zeta, double mu, double beta_dhdx)
{
    return gf_sh_static_source(g, zeta, mu, beta_dhdx) == beta_dhdx;
}
