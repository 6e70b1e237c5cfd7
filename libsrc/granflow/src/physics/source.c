#include "granflow/source.h"

#include <math.h>

double gf_sh_normal_acceleration(double g, double zeta, double curv, double u)
{
    const double a = g * cos(zeta) + curv * u * u;
    return a > 0.0 ? a : 0.0;
}

double gf_sh_driving(double g, double zeta, double curv, double mu, double u)
{
    const double gravity = g * sin(zeta);
    if (u == 0.0)
        return gravity;
    const double sgn = u > 0.0 ? 1.0 : -1.0;
    return gravity - sgn * mu * gf_sh_normal_acceleration(g, zeta, curv, u); /* eq. (2) */
}

double gf_sh_static_bound(double g, double zeta, double mu)
{
    return mu * gf_sh_normal_acceleration(g, zeta, 0.0, 0.0);
}

double gf_sh_static_source(double g, double zeta, double mu, double beta_dhdx)
{
    const double gs = g * sin(zeta), r = gf_sh_static_bound(g, zeta, mu);
    return fmin(gs + r, fmax(beta_dhdx, gs - r));
}

int gf_sh_admissible(double g, double zeta, double mu, double beta_dhdx)
{
    return gf_sh_static_source(g, zeta, mu, beta_dhdx) == beta_dhdx;
}
