/* SPDX-License-Identifier: GPL-3.0-or-later */
#include "granflow/sh1d.h"
#include "granflow/exact.h"
#include "granflow/source.h"
#include "internal.h"
#include "sh1d_internal.h"

#include <gsl/gsl_integration.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void gf_sh1d_config_init(gf_sh1d_config *c)
{
    memset(c, 0, sizeof *c);
    c->n_cells = 256;
    c->x_min = 0.0;
    c->x_max = 30.0;
    c->epsilon = 1.0;
    c->g = 1.0;
    c->chi = 1.0;
    c->rho = 1.0;
    c->zeta = 0.0;
    c->topo = NULL;
    gf_earth_pressure_init(&c->earth_pressure, GF_EARTH_PRESSURE_ISOTROPIC, 0.0, 0.0);
    gf_friction_init(&c->friction, "none");
    c->bc_left = c->bc_right = GF_BC_TRANSMISSIVE;
    c->cfl = 0.0;
    c->dt_fixed = 0.0;
    c->h_eps = 1e-10;
    c->h_semi = 1e-6;
    c->degree = 2;
    c->limiter = GF_LIMITER_MOMENT;
    c->gamma = 0.5;
    c->tvb_m = 1.0;
    c->velocity_limiter = 1;
    c->scheme = 3;
    c->kinetic_order = 1;
    c->startup_levels = 0;
    c->moving_mesh = 0;
    c->riemann_start = 0.0;
}

const gf_sh1d_type *gf_sh1d_type_lookup(const char *name)
{
    if (!name)
        return NULL;
    if (strcmp(name, "rkdg") == 0)
        return gf_sh1d_rkdg;
    if (strcmp(name, "kinetic") == 0)
        return gf_sh1d_kinetic;
    return NULL;
}

const char *gf_sh1d_type_names(void) { return "rkdg, kinetic"; }

const char *gf_limiter_names(void) { return "none, minmod, moment"; }

int gf_limiter_lookup(const char *name)
{
    static const char *const names[] = {"none", "minmod", "moment"};
    for (int i = 0; name && i < 3; ++i)
        if (strcmp(name, names[i]) == 0)
            return i;
    return -1;
}

const char *gf_sh1d_type_name(const gf_sh1d_type *type) { return type ? type->name : "(null)"; }

static gf_status check_config(const gf_sh1d_config *c)
{
    gf_status st;
    if (c->n_cells < 4 || c->n_cells > 100000000)
        return gf_fail(GF_EDOM, "number of cells n_cells = %zu is outside [4, 1e8]", c->n_cells);
    if ((st = gf_check_range("x_min", c->x_min, -1e300, 1e300)) ||
        (st = gf_check_range("x_max", c->x_max, -1e300, 1e300)))
        return st;
    if (!(c->x_max > c->x_min))
        return gf_fail(GF_EDOM, "x_max = %g must exceed x_min = %g", c->x_max, c->x_min);
    if ((st = gf_check_range("epsilon (beta = epsilon K cos zeta)", c->epsilon, 1e-300, 1e300)) ||
        (st = gf_check_range("gravity scale g", c->g, 0.0, 1e300)) ||
        (st = gf_check_range("curvature factor chi", c->chi, -1e300, 1e300)) ||
        (st = gf_check_range("flow density rho", c->rho, 1e-300, 1e300)) ||
        (st = gf_check_range("inclination zeta [rad]", c->zeta, -0.5 * GF_PI + 1e-12,
                             0.5 * GF_PI - 1e-12)) ||
        (st = gf_check_range("cfl", c->cfl, 0.0, 1.0)) ||
        (st = gf_check_range("dt (fixed time step)", c->dt_fixed, 0.0, 1e300)) ||
        (st = gf_check_range("h_eps (dry threshold)", c->h_eps, 1e-300, 1.0)) ||
        (st = gf_check_range("h_semi (semi-wet threshold)", c->h_semi, c->h_eps, 1.0)) ||
        (st = gf_check_range("gamma (minmod)", c->gamma, 1e-12, 1.0)) ||
        (st = gf_check_range("tvb_m (TVB constant)", c->tvb_m, 0.0, 1e300)))
        return st;
    if ((int)c->limiter < 0 || (int)c->limiter > 2)
        return gf_fail(GF_EDOM, "limiter = %d is outside {0: none, 1: minmod, 2: moment}",
                       (int)c->limiter);
    if (c->degree < 0 || c->degree > 2)
        return gf_fail(GF_EDOM, "degree = %d is outside {0, 1, 2}", c->degree);
    if (c->scheme < 1 || c->scheme > 3)
        return gf_fail(GF_EDOM, "kinetic scheme = %d is outside {1, 2, 3}", c->scheme);
    if (c->kinetic_order < 1 || c->kinetic_order > 2)
        return gf_fail(GF_EDOM, "kinetic_order = %d is outside {1, 2}", c->kinetic_order);
    if (c->startup_levels < 0 || c->startup_levels > 5)
        return gf_fail(GF_EDOM, "startup_levels = %d is outside 0..5", c->startup_levels);
    if (c->startup_levels > 0 && (c->n_cells << c->startup_levels) > 100000000)
        return gf_fail(GF_EDOM, "startup_levels = %d needs %zu cells on the finest grid, more than 1e8",
                       c->startup_levels, c->n_cells << c->startup_levels);
    if ((st = gf_check_range("riemann_start (start time t_s)", c->riemann_start, 0.0, 1e300)))
        return st;
    if (c->riemann_start > 0.0 && c->startup_levels > 0)
        return gf_fail(GF_EINVAL, "riemann_start = %g and startup_levels = %d: the exact start replaces the "
                                  "start-up refinement; use one of them", c->riemann_start, c->startup_levels);
    if (c->riemann_start > 0.0 && c->bc_left == GF_BC_PERIODIC)
        return gf_fail(GF_EINVAL, "riemann_start = %g needs a dam on a dry bed, and a periodic domain has no "
                                  "ends; use a transmissive or wall boundary", c->riemann_start);
    if (c->riemann_start > 0.0 && c->topo)
        return gf_fail(GF_EINVAL, "riemann_start = %g needs a plane bed (constant zeta), where a dam's exact "
                                  "solution is known; this run has a topography", c->riemann_start);
    if ((c->bc_left == GF_BC_PERIODIC) != (c->bc_right == GF_BC_PERIODIC))
        return gf_fail(GF_EINVAL, "periodic boundaries must be periodic on both sides");
    if (c->moving_mesh != 0 && c->moving_mesh != 1)
        return gf_fail(GF_EDOM, "moving_mesh = %d is outside {0: fixed grid, 1: front tracking}", c->moving_mesh);
    if (c->moving_mesh && c->bc_left == GF_BC_PERIODIC)
        return gf_fail(GF_EINVAL, "moving_mesh = 1 needs a dry front, and a periodic domain has no ends; "
                                  "use a transmissive or wall boundary");
    if ((st = gf_friction_check(&c->friction)))
        return st;
    if (c->topo) {
        double lo, hi;
        gf_topography_range(c->topo, &lo, &hi);
        if (c->x_min < lo || c->x_max > hi)
            return gf_fail(GF_EDOM, "domain [%g, %g] is not inside the topography's range [%g, %g]",
                           c->x_min, c->x_max, lo, hi);
    }
    return GF_SUCCESS;
}

gf_status gf_sh1d_alloc(const gf_sh1d_type *type, const gf_sh1d_config *cfg, gf_sh1d **out)
{
    if (!type || !cfg || !out)
        return gf_fail(GF_EINVAL, "gf_sh1d_alloc: null argument");
    *out = NULL;
    gf_status st = check_config(cfg);
    if (st)
        return st;
    gf_sh1d *s = calloc(1, sizeof *s);
    if (!s)
        return gf_fail(GF_ENOMEM, "gf_sh1d_alloc: out of memory");
    s->type = type;
    s->cfg = *cfg;
    s->n = cfg->n_cells;
    s->dx = (cfg->x_max - cfg->x_min) / (double)cfg->n_cells;
    s->x0 = cfg->x_min;
    s->scratch = malloc(2 * s->n * sizeof *s->scratch);
    if (!s->scratch) {
        free(s);
        return gf_fail(GF_ENOMEM, "gf_sh1d_alloc: out of memory");
    }
    if ((st = type->init(s))) {
        free(s->scratch);
        free(s);
        return st;
    }
    *out = s;
    return GF_SUCCESS;
}

void gf_sh1d_free(gf_sh1d *s)
{
    if (!s)
        return;
    gf_sh1d_free(s->startup);
    s->type->free(s);
    free(s->scratch);
    free(s);
}

/* A solver like s on 2^m times the cells (fixed time step divided alike),
 * without start-up refinement of its own. */
static gf_status finer(const gf_sh1d *s, int m, gf_sh1d **out)
{
    gf_sh1d_config c = s->cfg;
    c.n_cells = s->n << m;
    c.dt_fixed = s->cfg.dt_fixed / (double)(1u << m);
    c.startup_levels = 0;
    return gf_sh1d_alloc(s->type, &c, out);
}

/* Waves of the initial state crossing about this many cells end the start-up. */
#define STARTUP_CELLS 40.0

/* One level down the start-up refinement: `fine` (2^m times s's cells)
 * restricted to a new grid of 2^(m-1) times s's cells, or to s itself for
 * m == 1, with fine's time and step count; *out is that grid.  `fine` is
 * left to the caller. */
static gf_status restrict_level(gf_sh1d *s, const gf_sh1d *fine, int m, gf_sh1d **out)
{
    gf_sh1d *to = s;
    gf_status st;
    if (m > 1 && (st = finer(s, m - 1, &to)))
        return st;
    if ((st = s->type->restrict_from(to, fine))) {
        if (to != s)
            gf_sh1d_free(to);
        return st;
    }
    to->t = fine->t;
    to->steps = fine->steps;
    to->outflow = fine->outflow;
    *out = to;
    return GF_SUCCESS;
}

gf_status gf_sh1d_project_cell(const gf_sh1d *s, gf_sh1d_initial_fn fn, void *ctx, double xc, double dx,
                               const double *xg, const double *wg, int ng, int M, double *hm, double *qm)
{
    /* the pieces' ends in the cell's xi: -1, the breakpoints inside, 1 */
    double e[6] = {-1.0};
    int ne = 1;
    for (int b = 0; b < s->nbreaks; ++b) {
        const double xi = (s->breaks[b] - xc) / (0.5 * dx);
        if (xi > -1.0 && xi < 1.0)
            e[ne++] = xi;
    }
    e[ne++] = 1.0;
    for (int i = 2; i < ne - 1; ++i) /* sort the (at most 4) inner ends */
        for (int j = i; j > 1 && e[j] < e[j - 1]; --j) {
            const double t = e[j];
            e[j] = e[j - 1];
            e[j - 1] = t;
        }
    for (int m = 0; m < M; ++m)
        hm[m] = qm[m] = 0.0;
    for (int p = 0; p + 1 < ne; ++p) {
        const double c = 0.5 * (e[p] + e[p + 1]), r = 0.5 * (e[p + 1] - e[p]); /* 0 and 1 for one piece */
        for (int g = 0; g < ng; ++g) {
            const double xi = c + r * xg[g], w = r * wg[g], x = xc + 0.5 * dx * xi;
            double h, u;
            fn(x, ctx, &h, &u);
            if (!isfinite(h) || !isfinite(u) || h < 0.0)
                return gf_fail(GF_EDOM, "initial data at x = %g: h = %g, u = %g (need finite values and h >= 0)",
                               x, h, u);
            for (int m = 0; m < M; ++m) {
                const double pm = gf_sh1d_legendre(m, xi);
                hm[m] += w * h * pm;
                qm[m] += w * h * u * pm;
            }
        }
    }
    return GF_SUCCESS;
}

double gf_sh1d_wet_end(gf_sh1d_initial_fn fn, void *ctx, double dry, double wet)
{
    for (int it = 0; it < 200; ++it) {
        const double mid = 0.5 * (dry + wet);
        if (mid == dry || mid == wet)
            break;
        double h, u;
        fn(mid, ctx, &h, &u);
        if (h > 0.0)
            wet = mid;
        else
            dry = mid;
    }
    return wet;
}

gf_status gf_sh1d_wet_interval(const gf_sh1d *s, gf_sh1d_initial_fn fn, void *ctx, double *xl, double *xr,
                               int *dry_l, int *dry_r)
{
    const double lo = s->cfg.x_min, hi = s->cfg.x_max;
    const size_t ns = 16 * s->n;
    size_t first = ns + 1, last = 0;
    for (size_t k = 0; k <= ns; ++k) {
        const double x = k == ns ? hi : lo + (hi - lo) * (double)k / (double)ns;
        double h, u;
        fn(x, ctx, &h, &u);
        if (!isfinite(h) || !isfinite(u) || h < 0.0)
            return gf_fail(GF_EDOM, "initial data at x = %g: h = %g, u = %g (need finite values and h >= 0)",
                           x, h, u);
        if (h > 0.0) {
            if (first > ns)
                first = k;
            last = k;
        }
    }
    if (first > ns)
        return gf_fail(GF_EDOM, "the initial data are dry at every sample of [%g, %g]", lo, hi);
    const double dxs = (hi - lo) / (double)ns;
    *dry_l = first > 0;
    *dry_r = last < ns;
    *xl = *dry_l ? gf_sh1d_wet_end(fn, ctx, lo + dxs * (double)(first - 1), lo + dxs * (double)first) : lo;
    *xr = *dry_r ? gf_sh1d_wet_end(fn, ctx, lo + dxs * (double)(last + 1), lo + dxs * (double)last) : hi;
    return GF_SUCCESS;
}

/* The Riemann start (config.riemann_start): the dams' exact solution at
 * t_s.  In the frame X = x - a t^2 / 2, U = u - a t that the source
 * accelerates uniformly (a = g sin zeta - sgn(u) tau / h, constant under
 * the conditions riemann_setup checks) the equations are homogeneous
 * (Mangeney, Heinrich & Roche 2000, Pure Appl. Geophys. 157; see
 * doc/theory/one-d-schemes.md: the transformation is checked by the incline tests
 * against Ritter's solution), and each dam's solution is Ritter's (the dry-bed
 * Riemann problem, gf_riemann) until the fans meet. */
typedef struct {
    gf_riemann dam[2]; /* left dam (dry on its left), right dam */
    int has[2];
    double hw, uw;     /* the wet interval's uniform state */
    double a, ts, mid; /* frame acceleration, start time, where the two dams' solutions meet */
    double edge[4];    /* the fans' edges at t_s (front and head of each dam), left to right */
    int nedge;
} riemann_start;

static void riemann_state(double x, void *ctx, double *h, double *u)
{
    const riemann_start *r = ctx;
    const double X = x - 0.5 * r->a * r->ts * r->ts;
    const int side = X >= r->mid;
    if (r->has[side])
        gf_riemann_sample(&r->dam[side], X, r->ts, h, u);
    else { /* no dam on this side: the wet interval reaches the domain's end */
        *h = r->hw;
        *u = r->uw;
    }
    *u = *h > 0.0 ? *u + r->a * r->ts : 0.0;
}

/* The initial data's dams, and whether their exact solution at t_s =
 * config.riemann_start is known (else the reason). */
static gf_status riemann_setup(const gf_sh1d *s, gf_sh1d_initial_fn fn, void *ctx, riemann_start *r)
{
    const gf_sh1d_config *c = &s->cfg;
    memset(r, 0, sizeof *r);
    double xl, xr;
    gf_status st = gf_sh1d_wet_interval(s, fn, ctx, &xl, &xr, &r->has[0], &r->has[1]);
    if (st)
        return st;
    if (!r->has[0] && !r->has[1])
        return gf_fail(GF_EDOM, "riemann_start: the initial data are wet on all of [%g, %g], so there is no "
                                "dam (a jump to a dry bed)", c->x_min, c->x_max);
    /* uniform and wet between the ends, at the same samples */
    const size_t ns = 16 * s->n;
    int seen = 0;
    double x0 = xl; /* the first sample's */
    for (size_t k = 0; k <= ns; ++k) {
        const double x = k == ns ? c->x_max : c->x_min + (c->x_max - c->x_min) * (double)k / (double)ns;
        if (x < xl || x > xr)
            continue;
        double h, u;
        fn(x, ctx, &h, &u);
        if (!seen) {
            seen = 1;
            x0 = x;
            r->hw = h;
            r->uw = u;
        }
        if (!(h > 0.0))
            return gf_fail(GF_EDOM, "riemann_start: the initial data are dry at x = %g between wet points; "
                                    "a Riemann start needs one wet interval", x);
        if (fabs(h - r->hw) > 1e-12 * r->hw || fabs(u - r->uw) > 1e-12 * (fabs(r->uw) + sqrt(r->hw)))
            return gf_fail(GF_EDOM, "riemann_start: the initial data are not uniform on the wet side: h = %g, "
                                    "u = %g at x = %g, h = %g, u = %g at x = %g; a dam's exact solution needs a "
                                    "uniform reservoir", h, u, x, r->hw, r->uw, x0);
    }
    /* the wave speed: beta with the coefficient of an expansion, which must
     * be the reservoir's at rest too */
    if (gf_earth_pressure_k(&c->earth_pressure, 1.0) != gf_earth_pressure_k(&c->earth_pressure, 0.0))
        return gf_fail(GF_EINVAL, "riemann_start: the earth-pressure coefficient differs between rest and "
                                  "expansion, so a dam's fan is not Ritter's; use isotropic earth pressure");
    const double beta = gf_sh1d_beta(s, c->zeta, 1.0), cw = sqrt(beta * r->hw);
    /* the velocities of the fans and the reservoir at t -> 0 */
    const double umin = r->has[0] ? r->uw - 2.0 * cw : r->uw, umax = r->has[1] ? r->uw + 2.0 * cw : r->uw;
    r->ts = c->riemann_start;
    const double lo = c->x_min, hi = c->x_max;
    /* the source's acceleration: g sin zeta, less friction tau / h in the
     * direction of motion, which must be one way for t in (0, t_s] and tau / h
     * the same at every depth and speed the solution takes */
    const double gs = c->g * sin(c->zeta);
    const double tau = gf_sh1d_friction(s, r->hw, umax, c->zeta, 0.0) / r->hw;
    r->a = gs;
    if (c->friction.type != gf_friction_none) {
        static const double hf[] = {1.0, 0.5, 0.1, 1e-3};
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 3; ++j) {
                const double uj = umin + (umax - umin) * 0.5 * j, hi_ = hf[i] * r->hw;
                const double ti = gf_sh1d_friction(s, hi_, uj, c->zeta, 0.0) / hi_;
                if (fabs(ti - tau) > 1e-12 * fabs(tau))
                    return gf_fail(GF_EINVAL, "riemann_start: the friction law '%s' gives tau/h = %g at h = %g, "
                                              "u = %g and %g at h = %g, u = %g; a dam's fan is self-similar "
                                              "only where tau/h depends on neither (no friction, or Coulomb "
                                              "with constant mu)", c->friction.type->name, ti, hi_, uj,
                                   tau, r->hw, umax);
            }
        const double ap = gs - tau, am = gs + tau; /* moving right, moving left */
        if (tau > 0.0) {
            if (umin >= 0.0 && umin + ap * r->ts > 0.0 && (umin > 0.0 || ap > 0.0))
                r->a = ap;
            else if (umax <= 0.0 && umax + am * r->ts < 0.0 && (umax < 0.0 || am < 0.0))
                r->a = am;
            else
                return gf_fail(GF_EINVAL, "riemann_start: with friction the flow must move one way until t_s = "
                                          "%g, but its velocities span [%g, %g] at t = 0 and the net "
                                          "accelerations are %g (moving right) and %g (moving left); friction "
                                          "holds the reservoir, or the fronts move apart", r->ts, umin, umax,
                               ap, am);
        }
    }
    /* the solution at t_s: fans that have not met, inside the domain, and a
     * reservoir that reaches a wall only at rest.  The fans' edges, in the
     * bed's frame: a left dam's front (u - 2c) and head (u + c), a right
     * dam's head (u - c) and front (u + 2c) */
    const double sh = 0.5 * r->a * r->ts * r->ts;
    if (r->has[0] && r->has[1] && !(xr - xl > 2.0 * cw * r->ts))
        return gf_fail(GF_EDOM, "riemann_start: the two dams' fans meet before t_s = %g (wet interval [%g, %g], "
                                "wave speed %g); use an earlier t_s", r->ts, xl, xr, cw);
    r->nedge = 0;
    if (r->has[0]) {
        r->edge[r->nedge++] = xl + sh + (r->uw - 2.0 * cw) * r->ts;
        r->edge[r->nedge++] = xl + sh + (r->uw + cw) * r->ts;
    }
    if (r->has[1]) {
        r->edge[r->nedge++] = xr + sh + (r->uw - cw) * r->ts;
        r->edge[r->nedge++] = xr + sh + (r->uw + 2.0 * cw) * r->ts;
    }
    const double ext_l = r->edge[0], ext_r = r->edge[r->nedge - 1];
    if (!(ext_l > lo) || !(ext_r < hi))
        return gf_fail(GF_EDOM, "riemann_start: at t_s = %g the dam's waves span [%g, %g], beyond the domain "
                                "[%g, %g]; use an earlier t_s or a longer domain", r->ts, ext_l, ext_r, lo, hi);
    for (int side = 0; side < 2; ++side)
        if (!r->has[side] && (side ? c->bc_right : c->bc_left) == GF_BC_WALL && (r->uw != 0.0 || r->a != 0.0))
            return gf_fail(GF_EINVAL, "riemann_start: the reservoir reaches the wall at x = %g and moves (u = %g, "
                                      "acceleration %g), so it does not stay uniform there; use a "
                                      "transmissive end", side ? hi : lo, r->uw, r->a);
    for (int side = 0; side < 2; ++side)
        if (r->has[side])
            gf_riemann_solve(&r->dam[side], beta, side ? r->hw : 0.0, side ? r->uw : 0.0, side ? 0.0 : r->hw,
                             side ? 0.0 : r->uw, side ? xr : xl);
    r->mid = r->has[0] && r->has[1] ? 0.5 * (xl + xr) : r->has[1] ? -HUGE_VAL : HUGE_VAL;
    return GF_SUCCESS;
}

gf_status gf_sh1d_set_initial(gf_sh1d *s, gf_sh1d_initial_fn fn, void *ctx)
{
    if (!s || !fn)
        return gf_fail(GF_EINVAL, "gf_sh1d_set_initial: null argument");
    s->t = 0.0;
    s->steps = 0;
    s->outflow = 0.0;
    s->rejected = 0;
    s->startup_steps = 0;
    s->t_startup = 0.0;
    gf_sh1d_free(s->startup);
    s->startup = NULL;
    const int L = s->cfg.startup_levels;
    if (s->cfg.riemann_start > 0.0) {
        riemann_start r;
        gf_status st = riemann_setup(s, fn, ctx, &r);
        if (st)
            return st;
        /* the fans' edges, where the solution has kinks: the projection
         * splits its rule there, exact for the piecewise polynomial (Ritter's
         * h is quadratic in x, q cubic) */
        memcpy(s->breaks, r.edge, sizeof r.edge);
        s->nbreaks = r.nedge;
        st = s->type->set_initial(s, riemann_state, &r);
        s->nbreaks = 0;
        if (st)
            return st;
        s->t = r.ts;
        return GF_SUCCESS;
    }
    if (L == 0)
        return s->type->set_initial(s, fn, ctx);
    /* the finest grid starts from the initial data itself; its step bound
     * gives the fastest wave speed a (|u| + sqrt(beta h)), and the start-up
     * lasts until a dam-break fan (width 3 a t) spans STARTUP_CELLS cells
     * (or the scheme's own number, gf_sh1d_type.startup_cells) */
    gf_status st;
    if ((st = finer(s, L, &s->startup)) || (st = s->type->set_initial(s->startup, fn, ctx)))
        return st;
    /* this grid's initial state is the finest one's restricted, so that the
     * mass is the same to round-off on every grid of the start-up */
    const gf_sh1d *from = s->startup;
    gf_sh1d *tmp = NULL;
    for (int m = L; m >= 1 && !st; --m) {
        gf_sh1d *to = NULL;
        st = restrict_level(s, from, m, &to);
        gf_sh1d_free(tmp);
        tmp = to == s ? NULL : to;
        from = to;
    }
    gf_sh1d_free(tmp);
    if (st)
        return st;
    const double dtf = s->type->max_dt(s->startup);
    if (!(dtf > 0.0) || !isfinite(dtf)) { /* nothing moves: no start-up */
        gf_sh1d_free(s->startup);
        s->startup = NULL;
        return GF_SUCCESS;
    }
    /* the kinetic schemes' step bound is |u| + sqrt(2 beta h) (Theorem 3):
     * they report the wave speed itself, so that the start-up is as long on
     * every scheme */
    const double a = s->type->wave_speed ? s->type->wave_speed(s->startup) : s->startup->cfl * s->startup->dx / dtf;
    if (!(a > 0.0) || !isfinite(a)) {
        gf_sh1d_free(s->startup);
        s->startup = NULL;
        return GF_SUCCESS;
    }
    const double cells = s->type->startup_cells ? s->type->startup_cells(s) : STARTUP_CELLS;
    s->t_startup = cells * s->dx / (3.0 * a);
    return GF_SUCCESS;
}

/* The start-up refinement (config.startup_levels = L): the finest grid runs
 * to t_c / 2^(L-1), is restricted to the grid twice as coarse, which runs to
 * t_c / 2^(L-2), and so on; the grid of 2 times s's cells ends at t_c and is
 * restricted to s.  t_c = min(t_startup, dt_max). */
static gf_status startup(gf_sh1d *s, double dt_max)
{
    gf_sh1d *fine = s->startup;
    s->startup = NULL;
    const int L = s->cfg.startup_levels;
    const double tc = fmin(s->t_startup, dt_max);
    gf_status st = GF_SUCCESS;
    for (int m = L; m >= 1 && !st; --m) {
        const double t_end = tc / (double)(1u << (m - 1));
        const size_t before = fine->steps;
        if ((st = gf_sh1d_advance_to(fine, t_end)))
            break;
        s->startup_steps += fine->steps - before;
        gf_sh1d *coarse = NULL;
        st = restrict_level(s, fine, m, &coarse);
        gf_sh1d_free(fine);
        fine = coarse == s ? NULL : coarse;
    }
    gf_sh1d_free(fine);
    if (st) {
        char why[512];
        snprintf(why, sizeof why, "%s", gf_error_detail());
        return gf_fail(st, "%s: start-up refinement (startup_levels = %d): %s", s->type->name, L, why);
    }
    s->t = tc;
    s->steps = 1;
    s->t_startup = tc;
    return GF_SUCCESS;
}

static gf_status check_state(const gf_sh1d *s)
{
    double *h = s->scratch, *q = s->scratch + s->n;
    s->type->means(s, h, q);
    for (size_t i = 0; i < s->n; ++i)
        if (!isfinite(h[i]) || !isfinite(q[i]))
            return gf_fail(GF_ENONFINITE, "%s: solution not finite in cell %zu (x = %g) at t = %g "
                                          "after %zu steps",
                           s->type->name, i, gf_sh1d_cell_centre(s, i), s->t, s->steps);
    return GF_SUCCESS;
}

gf_status gf_sh1d_step(gf_sh1d *s, double dt_max)
{
    if (!s)
        return gf_fail(GF_EINVAL, "gf_sh1d_step: null solver");
    if (s->startup) {
        if (!(dt_max > 0.0))
            return gf_fail(GF_EDOM, "%s: invalid time step bound %g at t = %g", s->type->name, dt_max, s->t);
        gf_status st = startup(s, dt_max);
        return st ? st : check_state(s);
    }
    const double dt_cfl = s->type->max_dt(s);
    double dt = dt_cfl;
    if (s->cfg.dt_fixed > 0.0) {
        if (s->cfg.dt_fixed > dt_cfl * (1.0 + 1e-12))
            return gf_fail(GF_EDOM, "%s: fixed dt = %g exceeds the CFL bound %g at t = %g "
                                    "(Courant number %g); lower dt",
                           s->type->name, s->cfg.dt_fixed, dt_cfl, s->t, s->cfl);
        dt = s->cfg.dt_fixed;
    }
    /* land on the target instead of leaving a round-off sliver of a step */
    if (dt_max < dt * (1.0 + 1e-9))
        dt = dt_max;
    /* and a moving mesh's front on the domain's end */
    if (s->type->landing_dt) {
        const double dl = s->type->landing_dt(s);
        if (dl < dt)
            dt = dl;
    }
    if (!(dt > 0.0) || !isfinite(dt))
        return gf_fail(GF_ENONFINITE, "%s: invalid time step %g at t = %g", s->type->name, dt, s->t);
    gf_status st = s->type->step(s, dt);
    if (st)
        return st;
    s->t += dt;
    s->steps++;
    return check_state(s);
}

gf_status gf_sh1d_advance_to(gf_sh1d *s, double t)
{
    if (!s)
        return gf_fail(GF_EINVAL, "gf_sh1d_advance_to: null solver");
    while (s->t < t * (1.0 - 1e-14) && t - s->t > 1e-14) {
        gf_status st = gf_sh1d_step(s, t - s->t);
        if (st)
            return st;
    }
    return GF_SUCCESS;
}

double gf_sh1d_time(const gf_sh1d *s) { return s->t; }
size_t gf_sh1d_steps(const gf_sh1d *s) { return s->steps; }
size_t gf_sh1d_rejected_steps(const gf_sh1d *s) { return s->rejected; }
size_t gf_sh1d_startup_steps(const gf_sh1d *s) { return s->startup_steps; }
double gf_sh1d_startup_time(const gf_sh1d *s) { return s->startup ? 0.0 : s->t_startup; }
size_t gf_sh1d_n_cells(const gf_sh1d *s) { return s->n; }
double gf_sh1d_dx(const gf_sh1d *s) { return s->dx; }
double gf_sh1d_cell_centre(const gf_sh1d *s, size_t i)
{
    return s->x0 + ((double)i + 0.5) * s->dx;
}
void gf_sh1d_extent(const gf_sh1d *s, double *x_lo, double *x_hi)
{
    *x_lo = s->x0;
    *x_hi = s->cfg.moving_mesh ? s->x0 + (double)s->n * s->dx : s->cfg.x_max;
}
const gf_sh1d_config *gf_sh1d_get_config(const gf_sh1d *s) { return &s->cfg; }

void gf_sh1d_means(const gf_sh1d *s, double *h, double *u)
{
    s->type->means(s, h, u);
    for (size_t i = 0; i < s->n; ++i)
        u[i] = gf_sh1d_velocity(s, h[i], u[i]);
}

gf_status gf_sh1d_eval(const gf_sh1d *s, double x, double *h, double *u)
{
    if (!s || !h || !u)
        return gf_fail(GF_EINVAL, "gf_sh1d_eval: null argument");
    if (!(x >= s->cfg.x_min && x <= s->cfg.x_max))
        return gf_fail(GF_EDOM, "gf_sh1d_eval: x = %g outside the domain [%g, %g]", x,
                       s->cfg.x_min, s->cfg.x_max);
    double lo, hi;
    gf_sh1d_extent(s, &lo, &hi);
    if (x < lo || x > hi) { /* the moving mesh: beyond a front */
        *h = *u = 0.0;
        return GF_SUCCESS;
    }
    size_t i = (size_t)((x - lo) / s->dx);
    if (i >= s->n)
        i = s->n - 1;
    const double xi = 2.0 * (x - gf_sh1d_cell_centre(s, i)) / s->dx;
    double q;
    s->type->eval(s, i, xi, h, &q);
    *u = gf_sh1d_velocity(s, *h, q);
    return GF_SUCCESS;
}

double gf_sh1d_mass(const gf_sh1d *s)
{
    double *h = s->scratch, m = 0.0;
    s->type->means(s, h, h + s->n);
    for (size_t i = 0; i < s->n; ++i)
        m += h[i];
    return m * s->dx;
}

double gf_sh1d_outflow(const gf_sh1d *s) { return s->outflow; }

double gf_sh1d_min_depth(const gf_sh1d *s) { return s->type->min_depth(s); }

double gf_sh1d_max_speed(const gf_sh1d *s)
{
    double *h = s->scratch, m = 0.0;
    gf_sh1d_means(s, h, h + s->n);
    for (size_t i = 0; i < s->n; ++i)
        m = fmax(m, fabs(h[s->n + i]));
    return m;
}

void gf_sh1d_bed(const gf_sh1d *s, double x, double *zeta, double *kappa)
{
    if (s->cfg.topo) {
        /* range checked at alloc; ghost points slightly outside are clamped */
        double lo, hi;
        gf_topography_range(s->cfg.topo, &lo, &hi);
        gf_topography_eval(s->cfg.topo, fmin(fmax(x, lo), hi), zeta, kappa);
    } else {
        *zeta = s->cfg.zeta;
        *kappa = 0.0;
    }
}

double gf_sh1d_beta(const gf_sh1d *s, double zeta, double dudx)
{
    return gf_sh_beta(s->cfg.epsilon, gf_earth_pressure_k(&s->cfg.earth_pressure, dudx), zeta);
}

double gf_sh1d_friction(const gf_sh1d *s, double h, double u, double zeta, double kappa)
{
    return gf_sh1d_friction_c(s, h, u, cos(zeta), kappa);
}

double gf_sh1d_friction_c(const gf_sh1d *s, double h, double u, double cos_zeta, double kappa)
{
    if (h <= s->cfg.h_eps || s->cfg.friction.type == gf_friction_none)
        return 0.0;
    const double n = gf_sh_normal_acceleration_c(s->cfg.g, cos_zeta, s->cfg.chi * kappa, u);
    const gf_friction_state st = {h, fabs(u), s->cfg.rho * h * n, s->cfg.rho, s->cfg.g};
    gf_friction_result r;
    if (gf_friction_eval(&s->cfg.friction, &st, &r) != GF_SUCCESS)
        return NAN; /* caught by the finiteness check of the step */
    return r.tau;
}

double gf_sh1d_static_friction(const gf_sh1d *s, double h, double zeta)
{
    if (h <= s->cfg.h_eps)
        return 0.0;
    const double n = gf_sh_normal_acceleration(s->cfg.g, zeta, 0.0, 0.0);
    const gf_friction_state st = {h, 0.0, s->cfg.rho * h * n, s->cfg.rho, s->cfg.g};
    double tau;
    if (gf_friction_static_bound(&s->cfg.friction, &st, &tau) != GF_SUCCESS)
        return NAN;
    return tau;
}

/* The cells a step can change (sh1d_internal.h): a cell whose values and
 * whose neighbours' values are all exactly 0 (dry, at rest) gets no flux,
 * source or friction from either scheme and stays exactly 0, and each stage
 * (three at most) wets at most one more cell on each side: fluxes cross one
 * interface, the limiters only shrink slopes.  So the cells within
 * ACTIVE_MARGIN of one that is not 0 are all a step needs to compute; the
 * others keep every bit.  Periodic boundaries: every cell. */
#define ACTIVE_MARGIN 4
void gf_sh1d_active_range(const gf_sh1d *s, const double *h, const double *q, size_t stride, size_t *lo,
                          size_t *hi)
{
    const size_t n = s->n;
    *lo = 1, *hi = n;
    if (s->cfg.bc_left == GF_BC_PERIODIC || s->cfg.bc_right == GF_BC_PERIODIC)
        return;
    size_t first = 0, last = 0;
    for (size_t c = 1; c <= n && !first; ++c)
        for (size_t m = 0; m < stride; ++m)
            if (h[c * stride + m] != 0.0 || q[c * stride + m] != 0.0) {
                first = c;
                break;
            }
    if (!first) { /* all dry: nothing to compute */
        *hi = 0;
        return;
    }
    for (size_t c = n; c >= first && !last; --c)
        for (size_t m = 0; m < stride; ++m)
            if (h[c * stride + m] != 0.0 || q[c * stride + m] != 0.0) {
                last = c;
                break;
            }
    *lo = first > ACTIVE_MARGIN ? first - ACTIVE_MARGIN : 1;
    *hi = last + ACTIVE_MARGIN < n ? last + ACTIVE_MARGIN : n;
}

gf_status gf_gauss_legendre5(double x[5], double w[5])
{
    gsl_integration_glfixed_table *t = gsl_integration_glfixed_table_alloc(5);
    if (!t)
        return gf_fail(GF_ENOMEM, "Gauss-Legendre table: out of memory");
    for (size_t i = 0; i < 5; ++i)
        gsl_integration_glfixed_point(-1.0, 1.0, i, &x[i], &w[i], t);
    gsl_integration_glfixed_table_free(t);
    return GF_SUCCESS;
}
