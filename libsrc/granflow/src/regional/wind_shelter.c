/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The wind shelter index of Winstral, Elder and Davis (2002) in the sector
 * form Veitinger et al. (2016) use for release-area scenarios
 * (granflow/regional.h; doc/theory/regional.md, section 1.1). */
#include "granflow/regional.h"
#include "internal.h"

#include <math.h>

gf_status gf_wind_shelter(const gf_raster *dem, double wind_from_deg, double half_width_deg, double dmax,
                          double *sx)
{
    if (!dem || !dem->z || !sx || dem->nx < 1 || dem->ny < 1)
        return gf_fail(GF_EINVAL, "wind shelter: no DEM or output given");
    if (!(isfinite(wind_from_deg) && wind_from_deg >= 0 && wind_from_deg <= 360))
        return gf_fail(GF_EDOM, "wind shelter: wind direction %g deg must be in [0, 360]", wind_from_deg);
    if (!(half_width_deg > 0 && half_width_deg <= 180))
        return gf_fail(GF_EDOM, "wind shelter: sector half width %g deg must be in (0, 180]", half_width_deg);
    double L = fabs(dem->gt[1]);
    if (!(L > 0 && isfinite(L)) || !(dmax >= L && isfinite(dmax)))
        return gf_fail(GF_EDOM, "wind shelter: search distance %g m must be finite and at least the cell size %g m",
                       dmax, L);
    int r = (int)floor(dmax / L);
    double sxs = dem->gt[1] > 0 ? 1.0 : -1.0, sys = dem->gt[5] < 0 ? 1.0 : -1.0;
    double cw = cos(half_width_deg * GF_DEG);
    /* unit vector towards where the wind comes from (east, north) */
    double ue = sin(wind_from_deg * GF_DEG), un = cos(wind_from_deg * GF_DEG);
    for (int j = 0; j < dem->ny; ++j)
        for (int i = 0; i < dem->nx; ++i) {
            size_t c = (size_t)j * (size_t)dem->nx + (size_t)i;
            double z0 = dem->z[c], best = -INFINITY;
            if (!isfinite(z0)) {
                sx[c] = NAN;
                continue;
            }
            for (int b = -r; b <= r; ++b)
                for (int a = -r; a <= r; ++a) {
                    int ii = i + a, jj = j + b;
                    if ((!a && !b) || ii < 0 || jj < 0 || ii >= dem->nx || jj >= dem->ny)
                        continue;
                    double e = sxs * a * L, n = -sys * b * L, d = hypot(e, n);
                    if (d > dmax || (e * ue + n * un) < cw * d)
                        continue;
                    double z = dem->z[(size_t)jj * (size_t)dem->nx + (size_t)ii];
                    if (!isfinite(z))
                        continue;
                    double ang = atan((z - z0) / d);
                    if (ang > best)
                        best = ang;
                }
            sx[c] = isfinite(best) ? best / GF_DEG : NAN;
        }
    return GF_SUCCESS;
}
