/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Edge fluxes of the surface scheme (surface_flux.c), and HLL's wave speed
 * bounds, which the step bound (surface_cfl.c) shares: inline.  Private. */
#ifndef GRANFLOW_SURFACE_FLUX_H
#define GRANFLOW_SURFACE_FLUX_H

#include "surface_internal.h"
#include "surface_simd.h"

#pragma GCC visibility push(hidden) /* the library's own: not exported */
/* One stage's edge fluxes from the stage state (thickness H, velocities
 * gf_surface.u, gradients, gf_surface.slow): each active edge classified
 * (gf_surface.sedge), the hydrostatic mode of the faces (gf_surface.stat),
 * the fluxes and their sums per owned active face (acc_h, acc_m, acc_pn);
 * a face whose thickness H - dt/A sum L fh would be below 0 has its edges
 * recomputed at first order (up to 3 passes); fails (GF_EPHYS) where that is
 * not enough, on every rank alike. */
gf_status gf_surface_edge_fluxes(gf_surface *s, const double *H, double dt, int order2);
#pragma GCC visibility pop

/* HLL speed bounds (sl, sr) of the first-order states across an edge, as in
 * hll(). */
static inline void hll_speeds(double hl, double ul, double cl, double hr, double ur, double cr, double *sl,
                              double *sr)
{
    if (hl <= 0.0 && hr <= 0.0) {
        *sl = *sr = 0.0;
    } else if (hl <= 0.0) {
        *sl = ur - 2.0 * cr;
        *sr = ur + cr;
    } else if (hr <= 0.0) {
        *sl = ul - cl;
        *sr = ul + 2.0 * cl;
    } else {
        /* written so that swapping the sides (ul, ur -> -ur, -ul) gives
         * exactly (-sr, -sl): a processor edge's two ranks agree bitwise */
        const double us = 0.5 * (ul + ur) + (cl - cr), cs = gmax(0.0, 0.5 * (cl + cr) + 0.25 * (ul - ur));
        *sl = gmin(gmin(ul - cl, ur - cr), us - cs);
        *sr = gmax(gmax(ul + cl, ur + cr), us + cs);
    }
}

#ifdef __AVX__
/* hll_speeds on four lanes: the same operations and cases, selected per
 * lane (both sides dry: 0, 0) */
static inline void hll_speeds4(v4d hl, v4d ul, v4d cl, v4d hr, v4d ur, v4d cr, v4d *sl_out, v4d *sr_out)
{
    const v4d zero = vsplat(0.0), two = vsplat(2.0), half = vsplat(0.5);
    const v4i dl = hl <= zero, dr = hr <= zero;
    const v4d us = half * (ul + ur) + (cl - cr), cs = vmax(zero, half * (cl + cr) + vsplat(0.25) * (ul - ur));
    v4d sl = vmin(vmin(ul - cl, ur - cr), us - cs), sr = vmax(vmax(ul + cl, ur + cr), us + cs);
    sl = vsel(dr, ul - cl, sl), sr = vsel(dr, ul + two * cl, sr);
    sl = vsel(dl, ur - two * cr, sl), sr = vsel(dl, ur + cr, sr);
    *sl_out = vsel(dl & dr, zero, sl), *sr_out = vsel(dl & dr, zero, sr);
}

#endif

#endif
