/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Explicit surface scheme (granflow/surface.h) against exact solutions,
 * the 1D reference and the invariants it must keep. */
#include "../gf_test.h"
#include "../surface_mesh.h"

#include <stdio.h>

#include "granflow/constants.h"
#include "granflow/exact.h"
#include "granflow/surface.h"

static const int WALLS[4] = {GF_EDGE_WALL, GF_EDGE_WALL, GF_EDGE_WALL, GF_EDGE_WALL};

static double const_zeta(double s, void *ctx)
{
    (void)s;
    return *(double *)ctx;
}

/* inclined-to-horizontal transition, the curved-slope shape: 40 deg for
 * s < 10, blending to 10 deg over 10..20 */
static double curved_zeta(double s, void *ctx)
{
    (void)ctx;
    const double z0 = 40 * GF_DEG, z1 = 10 * GF_DEG;
    if (s <= 10.0)
        return z0;
    if (s >= 20.0)
        return z1;
    return z0 + (z1 - z0) * (s - 10.0) / 10.0;
}

static gf_surface *make_solver(strip_mesh *sm, const gf_surface_config *c)
{
    gf_surface *s = NULL;
    const gf_status st = gf_surface_alloc(&sm->m, c, &s);
    if (st)
        fail_msg("gf_surface_alloc: %s", gf_error_detail());
    return s;
}

static void coulomb(gf_surface_config *c, double delta_deg)
{
    assert_int_equal(gf_friction_init(&c->friction, "coulomb"), GF_SUCCESS);
    assert_int_equal(gf_friction_set(&c->friction, "mu", tan(delta_deg * GF_DEG)), GF_SUCCESS);
    assert_int_equal(gf_friction_set(&c->friction, "u0", 0.0), GF_SUCCESS);
}

/* A paraboloid pile of radius 2 m and height h0 centred at arc length sc
 * on the centre line: h = h0 (1 - r^2/4) (allocated, one value per face). */
static double *paraboloid(const strip_mesh *sm, double sc, double h0)
{
    double *h = calloc(sm->m.n_faces, sizeof *h);
    for (size_t f = 0; f < sm->m.n_faces; ++f) {
        const double ds = sm->s_of_face[f] - sc, y = sm->centre[3 * f + 1], r2 = ds * ds + y * y;
        h[f] = r2 < 4.0 ? h0 * (1.0 - r2 / 4.0) : 0.0;
    }
    return h;
}

static double lake_valley(double s, void *ctx)
{
    (void)ctx;
    return 30 * GF_DEG * tanh((10.0 - s) / 3.0);
}

/* a bowl with bumps: a doubly curved surface whose quads are not planar */
static double bumpy_bowl(double x, double y, void *ctx)
{
    (void)ctx;
    return (x - 10.0) * (x - 10.0) / 40.0 + y * y / 20.0 + 0.3 * sin(x / 1.5) * cos(y / 1.2);
}

/* Largest |h - h0| and |u| over the faces */
static void drift(const gf_surface *s, const double *h0, size_t nf, double *dh, double *umax)
{
    const double *h = gf_surface_h(s), *m = gf_surface_momentum(s);
    *dh = *umax = 0.0;
    for (size_t f = 0; f < nf; ++f) {
        *dh = fmax(*dh, fabs(h[f] - h0[f]));
        if (h[f] > 0.0)
            *umax = fmax(*umax, sqrt(m[3 * f] * m[3 * f] + m[3 * f + 1] * m[3 * f + 1] + m[3 * f + 2] * m[3 * f + 2]) / h[f]);
    }
}

/* A frictionless lake with a horizontal free surface (strip_lake) stays at
 * rest to round-off for 1000 steps at the largest stable step: on a 20 deg
 * plane with its shoreline on the slope, in a curved valley (30 deg down to
 * 30 deg up, two shorelines) and on the plane filled wall to wall (10 m
 * deep), and in a bumpy bowl (doubly curved, non-planar quads, an
 * irregular shoreline).  Bounds: |h - h0| <= 1e-12 h_max and |u| <= 1e-12 sqrt(g h_max)
 * (before the hydrostatic static edges: 0.04-0.1 m and up to 2 m/s).  The
 * same lake with its surface tilted by 2 cm over the strip must move
 * (|u| > 1e-3 m/s within 100 steps): the balance is not a frozen state. */
static void lake_at_rest_with_shorelines(void **state)
{
    (void)state;
    static const char *const names[4] = {"20 deg plane", "curved valley", "plane, wall to wall", "bumpy bowl"};
    for (int scene = 0; scene < 4; ++scene)
        for (size_t nx = 40; nx <= 80; nx *= 2) {
            double zeta = scene == 3 ? 0.0 : 20 * GF_DEG;
            const double w = scene == 3 ? 5.0 : 1.0;
            strip_mesh *sm = strip_mesh_new(nx, scene == 3 ? nx / 2 : 4, 0, 20, -w, w, scene == 1 ? lake_valley : const_zeta,
                                            &zeta, WALLS);
            if (scene == 3)
                strip_mesh_warp(sm, bumpy_bowl, NULL);
            gf_surface_config c;
            gf_surface_config_default(&c);
            const size_t nf = sm->m.n_faces;
            double *h0 = strip_lake(sm, scene == 2 ? 10.0 : 1.0), hmax = 0.0;
            for (size_t f = 0; f < nf; ++f)
                hmax = fmax(hmax, h0[f]);
            for (int tilt = 0; tilt < 2; ++tilt) {
                gf_surface *s = make_solver(sm, &c);
                double *h = malloc(nf * sizeof *h);
                for (size_t f = 0; f < nf; ++f)
                    h[f] = h0[f] > 0.0 ? h0[f] + (tilt ? 0.001 * sm->s_of_face[f] : 0.0) : 0.0;
                assert_int_equal(gf_surface_set_state(s, h, NULL), GF_SUCCESS);
                double dh, umax, t = 0.0, umoved = 0.0;
                for (int n = 0; n < (tilt ? 100 : 1000); ++n) {
                    double dt;
                    assert_int_equal(gf_surface_max_dt(s, &dt), GF_SUCCESS);
                    assert_int_equal(gf_surface_step(s, dt), GF_SUCCESS);
                    t += dt;
                    if (tilt) {
                        drift(s, h, nf, &dh, &umax);
                        umoved = fmax(umoved, umax);
                    }
                }
                drift(s, h, nf, &dh, &umax);
                if (tilt) {
                    printf("  lake, %s, %zu faces along: tilted by 2 cm, max |u| %.2e m/s within 100 steps\n",
                           names[scene], nx, umoved);
                    assert_true(umoved > 1e-3);
                } else {
                    printf("  lake, %s, %zu faces along, t = %.1f s (1000 steps): max|dh| %.1e m, max|u| %.1e m/s\n",
                           names[scene], nx, t, dh, umax);
                    gf_verify("lake at rest", "max abs dh / h_max", dh / hmax, "<=", 1e-12,
                              "lake with shorelines, %s, %zu faces along, 1000 steps", names[scene], nx);
                    assert_true(dh <= 1e-12 * hmax);
                    assert_true(umax <= 1e-12 * sqrt(9.81 * hmax));
                }
                gf_surface_free(s);
                free(h);
            }
            free(h0);
            strip_mesh_free(sm);
        }
}

/* A Coulomb pile (paraboloid cap, 0.4 m high, 2 m radius) on a 20 deg plane
 * and on the curved 40-to-10 deg transition, bed friction 45 deg: friction
 * holds every face, so the pile stays exactly at rest (|m| = 0, h unchanged
 * to 1e-12) for 400 steps at the largest stable step, with a kinetic energy
 * (gf_surface_kinetic_energy) of exactly 0 before and after. */
static void pile_at_rest_on_plane_and_curved_bed(void **state)
{
    (void)state;
    for (int curved = 0; curved < 2; ++curved) {
        double zeta = 20 * GF_DEG;
        strip_mesh *sm = strip_mesh_new(120, 40, 0, 30, -5, 5, curved ? curved_zeta : const_zeta, &zeta, WALLS);
        gf_surface_config c;
        gf_surface_config_default(&c);
        coulomb(&c, 45);
        gf_surface *s = make_solver(sm, &c);
        const size_t nf = sm->m.n_faces;
        double *h = paraboloid(sm, curved ? 15.0 : 10.0, 0.4);
        assert_int_equal(gf_surface_set_state(s, h, NULL), GF_SUCCESS);
        assert_true(gf_surface_kinetic_energy(s) == 0.0);
        double dmax = 0.0, mmax = 0.0;
        for (int n = 0; n < 400; ++n) {
            double dt;
            assert_int_equal(gf_surface_max_dt(s, &dt), GF_SUCCESS);
            assert_true(isfinite(dt));
            assert_int_equal(gf_surface_step(s, dt), GF_SUCCESS);
        }
        const double *hn = gf_surface_h(s), *m = gf_surface_momentum(s);
        for (size_t f = 0; f < nf; ++f) {
            dmax = fmax(dmax, fabs(hn[f] - h[f]));
            mmax = fmax(mmax, fabs(m[3 * f]) + fabs(m[3 * f + 1]) + fabs(m[3 * f + 2]));
        }
        const double e = gf_surface_kinetic_energy(s);
        printf("  pile on %s bed: max|dh| %.1e, max|m| %.1e, kinetic energy %.1e after 400 steps\n",
               curved ? "curved" : "20 deg", dmax, mmax, e);
        assert_true(dmax <= 1e-12);
        assert_true(mmax <= 1e-12);
        assert_true(e == 0.0); /* the end condition's "nothing moves" */
        gf_surface_free(s);
        strip_mesh_free(sm);
        free(h);
    }
}

/* A pile (paraboloid, 0.5 m high at 4 m) on a 35 deg plane in a closed box
 * (80 x 30 faces, walls), Coulomb bed friction 20 deg: it slides and
 * spreads.  Returns the solver; the mesh, configuration and initial h out. */
static gf_surface *sliding_pile(strip_mesh **sm, gf_surface_config *c, double **h)
{
    static double zeta = 35 * GF_DEG;
    *sm = strip_mesh_new(80, 30, 0, 20, -3.75, 3.75, const_zeta, &zeta, WALLS);
    gf_surface_config_default(c);
    coulomb(c, 20);
    gf_surface *s = make_solver(*sm, c);
    *h = paraboloid(*sm, 4.0, 0.5);
    assert_int_equal(gf_surface_set_state(s, *h, NULL), GF_SUCCESS);
    return s;
}

/* Volume in a closed box is conserved to 1e-12 while a pile slides and
 * spreads (35 deg plane, bed friction 20 deg, walls all round) and h >= 0. */
static void mass_conserved_in_a_closed_box(void **state)
{
    (void)state;
    strip_mesh *sm;
    gf_surface_config c;
    double *h;
    gf_surface *s = sliding_pile(&sm, &c, &h);
    const size_t nf = sm->m.n_faces;
    const double v0 = gf_surface_volume(s);
    double t = 0.0;
    assert_true(surface_advance(s, &t, 6.0) > 0);
    const double *hn = gf_surface_h(s);
    double hmin = HUGE_VAL;
    for (size_t f = 0; f < nf; ++f)
        hmin = fmin(hmin, hn[f]);
    gf_surface_stats st;
    gf_surface_get_stats(s, &st);
    const double rel = fabs(gf_surface_volume(s) - v0) / v0;
    printf("  closed box, t = 6: volume change %.1e relative, min h %.1e, %lu steps, %lu first-order edges, "
           "round-off volume %.1e\n", rel, hmin, st.steps, st.first_order_edges, st.roundoff_volume);
    gf_verify("initial volume", "relative volume change", rel, "<=", 1e-12, "sliding pile in a closed box, t = 6");
    assert_true(rel <= 1e-12);
    assert_true(hmin >= 0.0);
    assert_true(st.roundoff_volume <= 1e-13 * v0);
    gf_surface_free(s);
    strip_mesh_free(sm);
    free(h);
}

/* A renumbered mesh runs the same flow: the sliding pile (35 deg plane,
 * walls) on its faces in gf_surface_face_order's order (a permutation) and
 * the edges following their faces, against the mesh's own order, t = 3 s:
 * the same steps, h and momentum face by face the same bit for bit (each
 * face sums over its edges in the order of their centres, whatever their
 * numbers), the volume conserved to 1e-12. */
static int cmp_edge_key(const void *a, const void *b)
{
    const long long *x = a, *y = b;
    return (x[0] > y[0]) - (x[0] < y[0]);
}

static void renumbered_mesh_runs_the_same_flow(void **state)
{
    (void)state;
    strip_mesh *sm;
    gf_surface_config c;
    double *h;
    gf_surface *s = sliding_pile(&sm, &c, &h);
    const gf_surface_mesh *m = &sm->m;
    const size_t nf = m->n_faces, ne = m->n_edges;
    int *order = malloc(nf * sizeof *order), *inv = malloc(nf * sizeof *inv);
    assert_int_equal(gf_surface_face_order(nf, m->centre, order), GF_SUCCESS);
    for (size_t f = 0; f < nf; ++f)
        inv[f] = -1;
    for (size_t i = 0; i < nf; ++i) {
        assert_true(order[i] >= 0 && (size_t)order[i] < nf && inv[order[i]] < 0);
        inv[order[i]] = (int)i;
    }
    double *area = malloc(nf * sizeof *area), *centre = malloc(3 * nf * sizeof *centre),
           *normal = malloc(3 * nf * sizeof *normal), *h1 = malloc(nf * sizeof *h1);
    for (size_t i = 0; i < nf; ++i) {
        const int f = order[i];
        area[i] = m->area[f], h1[i] = h[f];
        memcpy(centre + 3 * i, m->centre + 3 * f, 3 * sizeof *centre);
        memcpy(normal + 3 * i, m->normal + 3 * f, 3 * sizeof *normal);
    }
    /* edges by their lower and higher face in the new numbering (boundary
     * edges: the face alone), orientation kept */
    long long *key = malloc(2 * ne * sizeof *key);
    for (size_t e = 0; e < ne; ++e) {
        const long long a = inv[m->owner[e]], b = m->neighbour[e] >= 0 ? inv[m->neighbour[e]] : (long long)nf;
        key[2 * e] = (a < b ? a : b) * (long long)(nf + 1) + (a < b ? b : a), key[2 * e + 1] = (long long)e;
    }
    qsort(key, ne, 2 * sizeof *key, cmp_edge_key);
    int *own = malloc(ne * sizeof *own), *nei = malloc(ne * sizeof *nei), *kind = malloc(ne * sizeof *kind);
    double *len = malloc(ne * sizeof *len), *en = malloc(3 * ne * sizeof *en), *ec = malloc(3 * ne * sizeof *ec);
    for (size_t i = 0; i < ne; ++i) {
        const size_t e = (size_t)key[2 * i + 1];
        own[i] = inv[m->owner[e]], nei[i] = m->neighbour[e] >= 0 ? inv[m->neighbour[e]] : -1;
        kind[i] = m->kind[e], len[i] = m->length[e];
        memcpy(en + 3 * i, m->edge_normal + 3 * e, 3 * sizeof *en);
        memcpy(ec + 3 * i, m->edge_centre + 3 * e, 3 * sizeof *ec);
    }
    const gf_surface_mesh rm = {nf, 0, ne, area, centre, normal, own, nei, kind, len, en, ec, NULL};
    gf_surface *r;
    assert_int_equal(gf_surface_alloc(&rm, &c, &r), GF_SUCCESS);
    assert_int_equal(gf_surface_set_state(r, h1, NULL), GF_SUCCESS);
    const double v0 = gf_surface_volume(r);
    double t = 0.0, tr = 0.0;
    const long n = surface_advance(s, &t, 3.0), nr = surface_advance(r, &tr, 3.0);
    assert_true(n > 0);
    assert_int_equal(n, nr);
    const double *ha = gf_surface_h(s), *hb = gf_surface_h(r), *ma = gf_surface_momentum(s),
                 *mb = gf_surface_momentum(r);
    double dh = 0.0, dm = 0.0, hx = 0.0, mx = 0.0;
    for (size_t i = 0; i < nf; ++i) {
        const int f = order[i];
        dh = fmax(dh, fabs(ha[f] - hb[i])), hx = fmax(hx, ha[f]);
        for (int k = 0; k < 3; ++k)
            dm = fmax(dm, fabs(ma[3 * f + k] - mb[3 * i + k])), mx = fmax(mx, fabs(ma[3 * f + k]));
    }
    const double rel = fabs(gf_surface_volume(r) - v0) / v0;
    printf("  renumbered sliding pile, t = 3 s, %ld steps: max |dh| %.2e (max h %.3f), max |dm| %.2e (max %.3f), "
           "volume change %.1e relative\n", n, dh, hx, dm, mx, rel);
    gf_verify("the run in the mesh's order", "max |h - h_renumbered| / max h", dh / hx, "<=", 1e-12,
              "sliding pile, faces in Hilbert order, t = 3 s");
    assert_true(dh == 0.0);
    assert_true(dm == 0.0);
    assert_true(rel <= 1e-12);
    gf_surface_free(r);
    gf_surface_free(s);
    void *p[] = {order, inv, area, centre, normal, h1, key, own, nei, kind, len, en, ec, h};
    for (size_t i = 0; i < sizeof p / sizeof p[0]; ++i)
        free(p[i]);
    strip_mesh_free(sm);
}

/* gf_surface_mesh_refine on the 35 deg strip and on the bumpy bowl (non-
 * planar quads): 4 sub-faces per quad, 2 per edge plus 4 per face new
 * edges; sub-face areas sum to the parent's to 1e-14 relative; every
 * sub-face is closed (sum over its edges of L nu, projected onto its tangent
 * plane, below 1e-12 of its perimeter on the planar strip, within 2% on the
 * bowl's warped quads) and each edge keeps its parent's kind; a second
 * refinement of the refined mesh works the same. */
static void mesh_refinement_geometry(void **state)
{
    (void)state;
    for (int bowl = 0; bowl < 2; ++bowl) {
        double zeta = 35 * GF_DEG;
        const int kinds[4] = {GF_EDGE_INFLOW, GF_EDGE_OUTFLOW, GF_EDGE_WALL, GF_EDGE_WALL};
        strip_mesh *sm = strip_mesh_new(12, 6, 0, 20, -5, 5, bowl ? NULL : const_zeta, &zeta, kinds);
        if (bowl)
            strip_mesh_warp(sm, bumpy_bowl, NULL);
        const gf_surface_mesh *in = &sm->m;
        gf_surface_refined *r[3] = {NULL, NULL, NULL};
        for (int l = 1; l <= 2; ++l) {
            const gf_surface_mesh *pm = l == 1 ? in : &r[1]->mesh;
            assert_int_equal(gf_surface_mesh_refine(pm, &r[l]), GF_SUCCESS);
            const gf_surface_mesh *m = &r[l]->mesh;
            assert_int_equal(m->n_faces, 4 * pm->n_faces);
            assert_int_equal(m->n_edges, 2 * pm->n_edges + 4 * pm->n_faces);
            double *sum = calloc(pm->n_faces, sizeof *sum), *close = calloc(3 * m->n_faces, sizeof *close),
                   *perim = calloc(m->n_faces, sizeof *perim), worst_area = 0.0, worst_close = 0.0;
            for (size_t f = 0; f < m->n_faces; ++f)
                sum[r[l]->parent_face[f]] += m->area[f];
            for (size_t f = 0; f < pm->n_faces; ++f)
                worst_area = fmax(worst_area, fabs(sum[f] - pm->area[f]) / pm->area[f]);
            for (size_t e = 0; e < m->n_edges; ++e) {
                const int pe = r[l]->parent_edge[e];
                assert_int_equal(m->kind[e], pe < 0 ? GF_EDGE_INTERNAL : pm->kind[pe]);
                for (int side = 0; side < 2; ++side) {
                    const int f = side ? m->neighbour[e] : m->owner[e];
                    if (f < 0)
                        continue;
                    for (int k = 0; k < 3; ++k)
                        close[3 * f + k] += (side ? -1.0 : 1.0) * m->length[e] * m->edge_normal[3 * e + k];
                    perim[f] += m->length[e];
                }
            }
            for (size_t f = 0; f < m->n_faces; ++f) {
                const double *n = m->normal + 3 * f, *c = close + 3 * f, cn = c[0] * n[0] + c[1] * n[1] + c[2] * n[2];
                const double t[3] = {c[0] - cn * n[0], c[1] - cn * n[1], c[2] - cn * n[2]};
                worst_close = fmax(worst_close, sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]) / perim[f]);
            }
            printf("  refinement %d of the %s: %zu faces, %zu edges, area sums %.1e, closure %.1e\n", l,
                   bowl ? "bumpy bowl" : "35 deg strip", m->n_faces, m->n_edges, worst_area, worst_close);
            assert_true(worst_area <= 1e-14);
            assert_true(worst_close <= (bowl ? 2e-2 : 1e-12));
            free(sum), free(close), free(perim);
        }
        gf_surface_refined_free(r[1]);
        gf_surface_refined_free(r[2]);
        strip_mesh_free(sm);
    }
    /* refused: no edge points, a face whose edges do not close */
    strip_mesh *sm = strip_mesh_new(4, 2, 0, 4, -1, 1, NULL, NULL, WALLS);
    gf_surface_mesh m = sm->m;
    gf_surface_refined *r = NULL;
    m.edge_points = NULL;
    assert_int_equal(gf_surface_mesh_refine(&m, &r), GF_EINVAL);
    printf("  refused: %s\n", gf_error_detail());
    sm->epoints[0] += 0.1;
    assert_int_equal(gf_surface_mesh_refine(&sm->m, &r), GF_EDOM);
    printf("  refused: %s\n", gf_error_detail());
    assert_null(r);
    strip_mesh_free(sm);
}

/* With the start-up refinement (startup_levels 1, 2, 3) a pile sliding in a
 * closed box keeps its volume to 1e-12, and one sliding out through an
 * outflow edge closes volume + outflow = initial to 1e-12 (the boundary
 * volumes of every refined level reach the mesh's edges); bad values are
 * refused naming the entry. */
static void startup_refinement_conserves_mass(void **state)
{
    (void)state;
    for (int outflow = 0; outflow < 2; ++outflow)
        for (int lv = 1; lv <= 3; ++lv) {
            static double zeta = 35 * GF_DEG;
            const int kinds[4] = {GF_EDGE_WALL, outflow ? GF_EDGE_OUTFLOW : GF_EDGE_WALL, GF_EDGE_WALL, GF_EDGE_WALL};
            strip_mesh *sm = strip_mesh_new(20, 6, 0, 10, -2.5, 2.5, const_zeta, &zeta, kinds);
            gf_surface_config c;
            gf_surface_config_default(&c);
            coulomb(&c, 20);
            c.startup_levels = lv;
            gf_surface *s = make_solver(sm, &c);
            double *h = paraboloid(sm, 7.0, 0.5);
            assert_int_equal(gf_surface_set_state(s, h, NULL), GF_SUCCESS);
            const double v0 = gf_surface_volume(s);
            double t = 0.0;
            assert_true(surface_advance(s, &t, 3.0) > 0);
            const double *ev = gf_surface_edge_volume(s);
            double out = 0.0;
            for (size_t e = 0; e < sm->m.n_edges; ++e)
                if (sm->m.neighbour[e] < 0)
                    out += ev[e];
            gf_surface_stats st;
            gf_surface_get_stats(s, &st);
            const double rel = fabs(gf_surface_volume(s) + out - v0) / v0;
            printf("  %s, startup_levels %d: %lu refined steps to t = %.3f s, outflow %.4f m3 of %.4f, "
                   "balance %.1e\n", outflow ? "outflow" : "closed box", lv, st.startup_steps, st.startup_time,
                   out, v0, rel);
            assert_true(rel <= 1e-12);
            assert_true(st.startup_steps > 0 && st.startup_time > 0.0);
            if (outflow)
                assert_true(out > 0.01 * v0);
            gf_surface_free(s);
            strip_mesh_free(sm);
            free(h);
        }
    strip_mesh *sm = strip_mesh_new(4, 2, 0, 4, -1, 1, NULL, NULL, WALLS);
    gf_surface_config c;
    gf_surface_config_default(&c);
    gf_surface *s = NULL;
    c.startup_levels = 4;
    assert_int_equal(gf_surface_alloc(&sm->m, &c, &s), GF_EDOM);
    printf("  refused: %s\n", gf_error_detail());
    c.startup_levels = 2;
    gf_surface_mesh m = sm->m;
    m.edge_points = NULL;
    assert_int_equal(gf_surface_alloc(&m, &c, &s), GF_EINVAL);
    printf("  refused: %s\n", gf_error_detail());
    assert_null(s);
    strip_mesh_free(sm);
}

/* Peak fields (hazard maps) follow every step: after a sliding pile (35 deg,
 * bed friction 20 deg) has moved, h_peak and speed_peak of every face equal
 * the maxima of h and |u| over all steps found by scanning every face, and
 * the faces the pile never reached keep 0. */
static void peak_fields_are_the_maxima_over_all_steps(void **state)
{
    (void)state;
    strip_mesh *sm;
    gf_surface_config c;
    double *h;
    gf_surface *s = sliding_pile(&sm, &c, &h);
    const size_t nf = sm->m.n_faces;
    double *hp = calloc(nf, sizeof *hp), *up = calloc(nf, sizeof *up);
    double *hs = calloc(nf, sizeof *hs), *us = calloc(nf, sizeof *us);
    double *ta = malloc(nf * sizeof *ta), *ts = malloc(nf * sizeof *ts);
    const double h_arrive = 0.01; /* the arrival thickness [m] */
    memcpy(hp, h, nf * sizeof *h);
    memcpy(hs, h, nf * sizeof *h);
    for (size_t f = 0; f < nf; ++f) ta[f] = ts[f] = h[f] >= h_arrive ? 0 : -1;
    double t = 0;
    for (int n = 0; n < 300; ++n) {
        double dt;
        assert_int_equal(gf_surface_max_dt(s, &dt), GF_SUCCESS);
        assert_int_equal(gf_surface_step(s, dt), GF_SUCCESS);
        t += dt;
        gf_surface_update_peaks(s, hp, up);
        gf_surface_update_arrival_mapped(s, NULL, t, h_arrive, ta);
        const double *hn = gf_surface_h(s), *m = gf_surface_momentum(s);
        for (size_t f = 0; f < nf; ++f) {
            if (ts[f] < 0 && hn[f] >= h_arrive) ts[f] = t;
            hs[f] = fmax(hs[f], hn[f]);
            if (hn[f] > c.h_dry)
                us[f] = fmax(us[f], sqrt(m[3 * f] * m[3 * f] + m[3 * f + 1] * m[3 * f + 1] +
                                         m[3 * f + 2] * m[3 * f + 2]) / hn[f]);
        }
    }
    size_t reached = 0;
    double umax = 0;
    for (size_t f = 0; f < nf; ++f) {
        assert_close(hp[f], hs[f], 0);
        assert_close(up[f], us[f], 1e-15 * (1 + us[f])); /* m/h against m (1/h) */
        /* the arrival time: the first step end with h >= h_arrive, every face
         * scanned (the kernel visits the active set only), -1 where never */
        assert_true(ta[f] == ts[f]);
        assert_true((ta[f] >= 0) == (hp[f] >= h_arrive));
        reached += hp[f] > 0;
        umax = fmax(umax, up[f]);
    }
    size_t arrived = 0;
    double tlast = 0;
    for (size_t f = 0; f < nf; ++f)
        if (ta[f] > 0) ++arrived, tlast = fmax(tlast, ta[f]);
    printf("  peaks: %zu of %zu faces reached, peak speed %.3f m/s; %zu reached %.2f m after the start,"
           " the last at %.3f s\n", reached, nf, umax, arrived, h_arrive, tlast);
    assert_true(reached > 0 && reached < nf);
    assert_true(arrived > 0 && tlast > 0 && tlast <= t);
    assert_true(umax > 1.0);
    gf_surface_free(s);
    strip_mesh_free(sm);
    free(h), free(hp), free(up), free(hs), free(us), free(ta), free(ts);
}

/* The total kinetic energy (gf_surface_kinetic_energy, the end condition of
 * a run) is sum_f 1/2 A_f h_f |u_f|^2: a uniform layer 0.3 m thick moving
 * with one tangential velocity has exactly 1/2 h |u|^2 A_total (on the
 * 20 deg plane along the slope and across it; on the curved bed across it,
 * where y is tangential everywhere), before the first step and with the
 * active set built; while a pile slides, the value after every step is the
 * sum over all faces of h and momentum (the active set holds every wet
 * face).  (A pile at rest has 0: pile_at_rest_on_plane_and_curved_bed.) */
static void kinetic_energy_is_half_h_u2_area(void **state)
{
    (void)state;
    for (int curved = 0; curved < 2; ++curved) {
        double zeta = 20 * GF_DEG;
        strip_mesh *sm = strip_mesh_new(60, 20, 0, 30, -5, 5, curved ? curved_zeta : const_zeta, &zeta, WALLS);
        gf_surface_config c;
        gf_surface_config_default(&c);
        coulomb(&c, 30);
        gf_surface *s = make_solver(sm, &c);
        const size_t nf = sm->m.n_faces;
        const double h0 = 0.3;
        /* curved: across (y); plane: 2 m/s down the slope, 1.5 m/s across */
        const double u[3] = {curved ? 0.0 : 2.0 * cos(zeta), 1.5, curved ? 0.0 : -2.0 * sin(zeta)};
        double *h = malloc(nf * sizeof *h), *m = malloc(3 * nf * sizeof *m), area = 0.0;
        for (size_t f = 0; f < nf; ++f) {
            h[f] = h0, area += sm->area[f];
            for (int k = 0; k < 3; ++k)
                m[3 * f + k] = h0 * u[k];
        }
        const double exact = 0.5 * h0 * (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]) * area;
        assert_int_equal(gf_surface_set_state(s, h, m), GF_SUCCESS);
        const double e0 = gf_surface_kinetic_energy(s);
        double dt;
        assert_int_equal(gf_surface_max_dt(s, &dt), GF_SUCCESS); /* builds the active set */
        const double e1 = gf_surface_kinetic_energy(s);
        printf("  uniform layer on %s bed: E %.15g, 1/2 h |u|^2 A %.15g (relative %.1e)\n",
               curved ? "curved" : "20 deg", e1, exact, fabs(e1 / exact - 1));
        assert_close(e0, exact, 1e-13 * exact);
        assert_close(e1, exact, 1e-13 * exact);
        gf_surface_free(s);
        strip_mesh_free(sm);
        free(h), free(m);
    }
    /* a sliding pile: the active set's sum is the sum over every face */
    strip_mesh *sm;
    gf_surface_config c;
    double *h;
    gf_surface *s = sliding_pile(&sm, &c, &h);
    double worst = 0.0, peak = 0.0;
    for (int n = 0; n < 200; ++n) {
        double dt;
        assert_int_equal(gf_surface_max_dt(s, &dt), GF_SUCCESS);
        assert_int_equal(gf_surface_step(s, dt), GF_SUCCESS);
        const double *hn = gf_surface_h(s), *m = gf_surface_momentum(s);
        double all = 0.0;
        for (size_t f = 0; f < sm->m.n_faces; ++f)
            if (hn[f] > c.h_dry)
                all += 0.5 * sm->area[f] *
                       (m[3 * f] * m[3 * f] + m[3 * f + 1] * m[3 * f + 1] + m[3 * f + 2] * m[3 * f + 2]) / hn[f];
        const double e = gf_surface_kinetic_energy(s);
        worst = fmax(worst, fabs(e - all) / all);
        peak = fmax(peak, e);
    }
    printf("  sliding pile, 200 steps: E against the sum over all faces to %.1e relative, peak E %.3g m5/s2\n",
           worst, peak);
    assert_true(peak > 0.0);
    assert_true(worst <= 1e-13);
    gf_surface_free(s);
    strip_mesh_free(sm);
    free(h);
}

/* The faces still moving (gf_surface_moving_faces, the report at the end of
 * a run): on the 20 deg plane, a layer with a speed growing along the slope
 * by 0.1 m/s per column (0 .. 5.9 m/s; a diagonal component across) and
 * dry patches: the count of faces faster than 1 m/s, their volume sum A h,
 * the fastest face and its centre are those of a count over the arrays,
 * before the first step and with the active set built; a film at h_dry with
 * a large momentum is not counted (thinner films have no velocity);
 * "faster than" is strict (a face at exactly 1 m/s is not counted at 1 m/s,
 * is at 0.999); equal speeds give the lowest face; no wet face gives 0 faces
 * and face -1; while a pile slides, the kernel's active-set sums equal
 * gf_moving_faces_eval over every face of its h and momentum; a negative or
 * non-finite threshold is an error. */
/* the moving faces counted here, independently: n, volume, fastest speed and face */
static void expect_moving(size_t nf, const double *area, const double *h, const double *m, double h_dry,
                          double speed, size_t *n, double *vol, double *umax, long *fmax)
{
    *n = 0, *vol = 0.0, *umax = 0.0, *fmax = -1;
    for (size_t f = 0; f < nf; ++f) {
        if (!(h[f] > h_dry))
            continue;
        const double u = sqrt(m[3 * f] * m[3 * f] + m[3 * f + 1] * m[3 * f + 1] + m[3 * f + 2] * m[3 * f + 2]) / h[f];
        if (u > speed)
            ++*n, *vol += area[f] * h[f];
        if (*fmax < 0 || u > *umax)
            *umax = u, *fmax = (long)f;
    }
}

static void moving_faces_counted_and_located(void **state)
{
    (void)state;
    double zeta = 20 * GF_DEG;
    const size_t nx = 60, ny = 20;
    strip_mesh *sm = strip_mesh_new(nx, ny, 0, 30, -5, 5, const_zeta, &zeta, WALLS);
    gf_surface_config c;
    gf_surface_config_default(&c);
    coulomb(&c, 30);
    const size_t nf = sm->m.n_faces;
    const double down[3] = {cos(zeta), 0.0, -sin(zeta)}, across[3] = {0.0, 1.0, 0.0};
    double *h = malloc(nf * sizeof *h), *m = malloc(3 * nf * sizeof *m);
    for (size_t f = 0; f < nf; ++f) {
        const size_t i = f % nx, j = f / nx;
        const double a = 0.1 * (double)i, b = 0.05 * (double)j; /* |u| = sqrt(a^2 + b^2) */
        h[f] = (i + j) % 7 == 3 ? 0.0 : 0.2 + 0.01 * (double)j;
        if (i == nx - 1 && j == ny - 1)
            h[f] = 0.5 * c.h_dry; /* a film on the fastest column: not counted, whatever its momentum */
        for (int k = 0; k < 3; ++k)
            m[3 * f + k] = (h[f] > 0.0 ? h[f] : 1.0) * (a * down[k] + b * across[k]);
    }
    /* over the arrays as given: the film's momentum would make it the fastest */
    size_t n_exp;
    double vol_exp, umax;
    long fmax_exp;
    expect_moving(nf, sm->area, h, m, c.h_dry, 1.0, &n_exp, &vol_exp, &umax, &fmax_exp);
    assert_true(fmax_exp != (long)(nf - 1));
    gf_moving_faces ev;
    assert_int_equal(gf_moving_faces_eval(nf, sm->area, sm->centre, h, m, c.h_dry, 1.0, &ev), GF_SUCCESS);
    assert_int_equal(ev.n, n_exp);
    assert_close(ev.volume, vol_exp, 1e-13 * vol_exp);
    assert_true(ev.max_speed == umax && ev.max_face == fmax_exp);
    /* the kernel's state (its momentum projected onto the faces' planes) */
    for (int built = 0; built < 2; ++built) {
        gf_surface *s = make_solver(sm, &c);
        assert_int_equal(gf_surface_set_state(s, h, m), GF_SUCCESS);
        if (built) {
            double dt;
            assert_int_equal(gf_surface_max_dt(s, &dt), GF_SUCCESS); /* builds the active set */
        }
        expect_moving(nf, sm->area, gf_surface_h(s), gf_surface_momentum(s), c.h_dry, 1.0, &n_exp, &vol_exp, &umax,
                      &fmax_exp);
        gf_moving_faces mv;
        assert_int_equal(gf_surface_moving_faces(s, 1.0, &mv), GF_SUCCESS);
        printf("  layer, %s: %zu faces faster than 1 m/s (expected %zu), volume %.6g m3 (%.6g), fastest %.6g m/s at"
               " face %ld (%ld)\n",
               built ? "active set built" : "before the first step", mv.n, n_exp, mv.volume, vol_exp, mv.max_speed,
               mv.max_face, fmax_exp);
        assert_true(n_exp > 0 && n_exp < nf);
        assert_int_equal(mv.n, n_exp);
        assert_close(mv.volume, vol_exp, 1e-13 * vol_exp);
        assert_true(mv.max_speed == umax && mv.max_face == fmax_exp);
        for (int k = 0; k < 3; ++k)
            assert_true(mv.max_centre[k] == sm->centre[3 * fmax_exp + k]);
        gf_surface_free(s);
    }

    /* strict threshold, ties, nothing wet */
    for (size_t f = 0; f < nf; ++f) {
        h[f] = 0.5;
        for (int k = 0; k < 3; ++k)
            m[3 * f + k] = 0.5 * 0.25 * across[k];
    }
    const size_t f1 = 7 * nx + 13, f2 = 2 * nx + 40; /* the same largest speed, f2 < f1 */
    for (int k = 0; k < 3; ++k)
        m[3 * f1 + k] = m[3 * f2 + k] = 0.5 * across[k]; /* |u| = 1 m/s exactly */
    for (int built = 0; built < 2; ++built) {
        gf_surface *s = make_solver(sm, &c);
        assert_int_equal(gf_surface_set_state(s, h, m), GF_SUCCESS);
        if (built) {
            double dt;
            assert_int_equal(gf_surface_max_dt(s, &dt), GF_SUCCESS);
        }
        gf_moving_faces mv;
        assert_int_equal(gf_surface_moving_faces(s, 1.0, &mv), GF_SUCCESS);
        assert_int_equal(mv.n, 0);
        assert_true(mv.max_speed == 1.0);
        assert_int_equal(mv.max_face, (long)f2);
        assert_int_equal(gf_surface_moving_faces(s, 0.999, &mv), GF_SUCCESS);
        assert_int_equal(mv.n, 2);
        assert_close(mv.volume, 0.5 * (sm->area[f1] + sm->area[f2]), 1e-15);
        assert_int_equal(gf_surface_moving_faces(s, -0.1, &mv), GF_EDOM);
        assert_int_equal(gf_surface_moving_faces(s, NAN, &mv), GF_ENONFINITE);
        gf_surface_free(s);
    }
    memset(h, 0, nf * sizeof *h);
    gf_moving_faces mv;
    assert_int_equal(gf_moving_faces_eval(nf, sm->area, sm->centre, h, m, c.h_dry, 1.0, &mv), GF_SUCCESS);
    assert_true(mv.n == 0 && mv.volume == 0.0 && mv.max_speed == 0.0 && mv.max_face == -1);
    strip_mesh_free(sm);
    free(h), free(m);

    /* a sliding pile: the active set's sums are those over every face */
    double *h0;
    gf_surface *s = sliding_pile(&sm, &c, &h0);
    size_t seen = 0;
    for (int n = 0; n < 200; ++n) {
        double dt;
        assert_int_equal(gf_surface_max_dt(s, &dt), GF_SUCCESS);
        assert_int_equal(gf_surface_step(s, dt), GF_SUCCESS);
        if (n % 20 != 19)
            continue;
        gf_moving_faces a, b;
        assert_int_equal(gf_surface_moving_faces(s, 1.0, &a), GF_SUCCESS);
        assert_int_equal(gf_moving_faces_eval(sm->m.n_faces, sm->area, sm->centre, gf_surface_h(s),
                                              gf_surface_momentum(s), c.h_dry, 1.0, &b),
                         GF_SUCCESS);
        assert_int_equal(a.n, b.n);
        assert_close(a.volume, b.volume, 1e-13 * b.volume);
        assert_true(a.max_speed == b.max_speed && a.max_face == b.max_face);
        seen += a.n;
    }
    printf("  sliding pile, 200 steps: the active set's moving faces = the count over every face (%zu faces"
           " faster than 1 m/s over the 10 checks)\n", seen);
    assert_true(seen > 0);
    gf_surface_free(s);
    strip_mesh_free(sm);
    free(h0);
}

/* A restart: a second solver given the first one's h, momentum and normal
 * acceleration (gf_surface_restore) after 150 steps of a pile sliding onto the curved bed
 * (40 -> 10 deg, Coulomb 20 deg) continues it exactly: the next 150 steps at
 * the same time steps give the same h and momentum bit for bit. */
static void restart_continues_the_run_exactly(void **state)
{
    (void)state;
    strip_mesh *sm = strip_mesh_new(120, 30, 0, 30, -3.75, 3.75, curved_zeta, NULL, WALLS);
    gf_surface_config c;
    gf_surface_config_default(&c);
    coulomb(&c, 20);
    gf_surface *a = make_solver(sm, &c), *b = make_solver(sm, &c);
    const size_t nf = sm->m.n_faces;
    double *h = paraboloid(sm, 5.0, 0.5);
    assert_int_equal(gf_surface_set_state(a, h, NULL), GF_SUCCESS);
    for (int n = 0; n < 150; ++n) {
        double dt;
        assert_int_equal(gf_surface_max_dt(a, &dt), GF_SUCCESS);
        assert_int_equal(gf_surface_step(a, dt), GF_SUCCESS);
    }
    assert_int_equal(gf_surface_restore(b, gf_surface_h(a), gf_surface_momentum(a), gf_surface_normal_acceleration(a)),
                     GF_SUCCESS);
    double dmax = 0;
    for (int n = 0; n < 150; ++n) {
        double dta, dtb;
        assert_int_equal(gf_surface_max_dt(a, &dta), GF_SUCCESS);
        assert_int_equal(gf_surface_max_dt(b, &dtb), GF_SUCCESS);
        assert_true(dta == dtb);
        assert_int_equal(gf_surface_step(a, dta), GF_SUCCESS);
        assert_int_equal(gf_surface_step(b, dtb), GF_SUCCESS);
        const double *ha = gf_surface_h(a), *hb = gf_surface_h(b);
        const double *ma = gf_surface_momentum(a), *mb = gf_surface_momentum(b);
        for (size_t f = 0; f < nf; ++f) {
            dmax = fmax(dmax, fabs(ha[f] - hb[f]));
            for (int k = 0; k < 3; ++k)
                dmax = fmax(dmax, fabs(ma[3 * f + k] - mb[3 * f + k]));
        }
    }
    printf("  restart after 150 steps: max difference over the next 150 steps %.1e\n", dmax);
    gf_verify("uninterrupted run", "max difference", dmax, "=", 0.0, "restart after 150 steps, next 150 steps");
    assert_true(dmax == 0.0);
    /* a negative normal acceleration is refused */
    double *bad = calloc(nf, sizeof *bad);
    bad[3] = -1.0;
    assert_int_equal(gf_surface_restore(b, gf_surface_h(a), gf_surface_momentum(a), bad), GF_EDOM);
    free(bad);
    gf_surface_free(a);
    gf_surface_free(b);
    strip_mesh_free(sm);
    free(h);
}

/* Dam breaks on a dry bed along a strip (walls at the sides): frictionless
 * Ritter (g = 1, h0 = 1, dam at x = 6) and Coulomb on a 35 deg incline with
 * bed friction 30 deg (the reservoir enters at u = a t through the inflow
 * edge at x = 0); front (h = 1e-3 level) against the exact one at t = 5 and
 * L1(h). */
#define FRONT_LEVEL 1e-3
static double dam_front_from(int incline, int order, size_t n, double t0, int levels, double *travel, double *l1);
static double dam_front(int incline, int order, size_t n, double *travel, double *l1)
{
    return dam_front_from(incline, order, n, 0.0, 0, travel, l1);
}
/* the same from the exact solution's cell means at t0 > 0 (Ritter only): a
 * front that is already resolved, without the start-up of the dam break */
static double dam_front_from(int incline, int order, size_t n, double t0, int levels, double *travel, double *l1)
{
    double zeta = incline ? 35 * GF_DEG : 0.0;
    const int kinds[4] = {incline ? GF_EDGE_INFLOW : GF_EDGE_WALL, GF_EDGE_OUTFLOW, GF_EDGE_WALL, GF_EDGE_WALL};
    strip_mesh *sm = strip_mesh_new(n, 1, 0, 20, 0, 20.0 / (double)n, const_zeta, &zeta, kinds);
    gf_surface_config c;
    gf_surface_config_default(&c);
    c.g[2] = -1.0;
    c.order = order;
    c.h_dry = 1e-10;
    c.startup_levels = levels;
    const double a = incline ? sin(zeta) - tan(30 * GF_DEG) * cos(zeta) : 0.0;
    if (incline)
        coulomb(&c, 30);
    gf_surface *s = make_solver(sm, &c);
    double *h = calloc(n, sizeof *h), *q = calloc(3 * n, sizeof *q);
    const double x0 = 6.0;
    for (size_t f = 0; f < n; ++f)
        h[f] = sm->s_of_face[f] < x0 ? 1.0 : 0.0;
    if (t0 > 0.0) {
        assert_true(!incline);
        gf_riemann r0;
        assert_int_equal(gf_riemann_solve(&r0, 1.0, 1.0, 0.0, 0.0, 0.0, x0), GF_SUCCESS);
        const double d = 20.0 / (double)n;
        for (size_t f = 0; f < n; ++f) {
            h[f] = 0.0;
            for (int k = 0; k < 16; ++k) {
                double he, ue;
                gf_riemann_sample(&r0, sm->s_of_face[f] + d * ((k + 0.5) / 16.0 - 0.5), t0, &he, &ue);
                h[f] += he / 16.0, q[3 * f] += he * ue / 16.0;
            }
        }
    }
    assert_int_equal(gf_surface_set_state(s, h, q), GF_SUCCESS);
    free(q);
    const double T = 5.0, tdir[3] = {cos(zeta), 0.0, -sin(zeta)};
    double t = t0;
    while (t < T - 1e-12) {
        double dt;
        assert_int_equal(gf_surface_max_dt(s, &dt), GF_SUCCESS);
        dt = fmin(dt, T - t);
        if (incline) { /* exact state at x = 0 over the step: h = 1, u = a (t + dt/2) */
            const double ub = a * (t + 0.5 * dt), u[3] = {ub * tdir[0], 0.0, ub * tdir[2]};
            assert_int_equal(gf_surface_set_inflow(s, 0, 1.0, u), GF_SUCCESS);
        }
        assert_int_equal(gf_surface_step(s, dt), GF_SUCCESS);
        t += dt;
    }
    const double beta = cos(zeta), dx = 20.0 / (double)n;
    const double xe = x0 + 0.5 * a * T * T + (2.0 * sqrt(beta) - 3.0 * sqrt(beta * FRONT_LEVEL)) * T;
    *travel = (xe - x0) / dx;
    const double *hn = gf_surface_h(s);
    /* numerical front: last crossing of the level, linear between centres */
    double xf = 0.0;
    for (size_t f = 0; f + 1 < n; ++f)
        if (hn[f] >= FRONT_LEVEL && hn[f + 1] < FRONT_LEVEL)
            xf = sm->s_of_face[f] + dx * (hn[f] - FRONT_LEVEL) / (hn[f] - hn[f + 1]);
    gf_riemann rp;
    assert_int_equal(gf_riemann_solve(&rp, beta, 1.0, 0.0, 0.0, 0.0, x0), GF_SUCCESS);
    *l1 = 0.0;
    for (size_t f = 0; f < n; ++f) {
        double mean = 0.0;
        for (int k = 0; k < 8; ++k) {
            /* exact in the frame moving with 1/2 a t^2 */
            const double x = sm->s_of_face[f] + dx * ((k + 0.5) / 8.0 - 0.5) - 0.5 * a * T * T;
            double he, ue;
            gf_riemann_sample(&rp, x, T, &he, &ue);
            mean += he / 8.0;
        }
        *l1 += fabs(hn[f] - mean) * dx;
    }
    gf_surface_free(s);
    strip_mesh_free(sm);
    free(h);
    return (xf - xe) / dx;
}

static double dam_l1_first[2];

/* order 2 beats order 1 fivefold in L1 at N = 800 */
/* Where the dam break's front lag comes from: started from the exact
 * Ritter solution at t0 = 0.5 s (a front resolved over 10-40 cells), the
 * order-2 front at t = 5 is within 3 cells at N = 200, 400, 800 (measured
 * -1.55, -0.49, -0.10) and its error falls faster than first order; the dam
 * break from t = 0 lags 7-8 cells (dry_fronts_against_exact): a shift made
 * in its first steps, while the discontinuity is unresolved. */
static void resolved_front_within_three_cells(void **state)
{
    (void)state;
    const size_t ns[] = {200, 400, 800};
    double err[3], l1, travel;
    printf("  Ritter, order 2, from the exact solution at t0 = 0.5 s: front error in cells at t = 5:");
    for (int k = 0; k < 3; ++k) {
        err[k] = dam_front_from(0, 2, ns[k], 0.5, 0, &travel, &l1);
        printf(" N=%zu %+.2f (%.0f cells travelled);", ns[k], err[k], travel);
    }
    printf("\n");
    for (int k = 0; k < 3; ++k) {
        gf_verify("exact front", "front error in cells (abs)", fabs(err[k]), "<=", 3.0,
                  "Ritter from its exact state at t0 = 0.5 s, order 2, N = %zu, t = 5", ns[k]);
        assert_true(fabs(err[k]) <= 3.0);
    }
    /* the absolute error (cells x dx) falls faster than first order: by
     * more than 4 over the two doublings (measured 60x) */
    const double e0 = fabs(err[0]) * 20.0 / (double)ns[0], e2 = fabs(err[2]) * 20.0 / (double)ns[2];
    assert_true(e2 < 0.25 * e0);
}

static void dry_fronts_against_exact(void **state)
{
    (void)state;
    const size_t ns[] = {100, 200, 400, 800};
    for (int incline = 0; incline < 2; ++incline)
        for (int order = 1; order <= 2; ++order) {
            double err[4], l1[4], travel[4];
            printf("  %s, order %d, t = 5: front error in cells (travel), L1(h):", incline ? "Coulomb incline" : "Ritter",
                   order);
            for (int k = 0; k < 4; ++k) {
                err[k] = dam_front(incline, order, ns[k], &travel[k], &l1[k]);
                printf(" N=%zu %+.2f (%.0f) %.1e;", ns[k], err[k], travel[k], l1[k]);
            }
            printf("\n");
            /* L1 converges at first order or better (a dry front and a
             * kink); the front error in cells at N = 400 and 800 (190 and
             * 380 cells of travel).  Measured: Ritter order 2 -8.3, -6.9;
             * incline order 2 see the output.  The 3-cell target is
             * not met: the lag is a start-up shift of the unresolved dam
             * (resolved_front_within_three_cells). */
            assert_true(l1[3] < 0.7 * l1[2] && l1[2] < 0.7 * l1[1]);
            if (order == 2) {
                gf_verify("exact front", "front error in cells (abs)", fabs(err[3]), "<=", 8.0,
                          "%s, order 2, N = 800, t = 5", incline ? "Coulomb incline" : "Ritter");
                gf_verify("exact solution", "L1(h)", l1[3], "<", 0.2 * dam_l1_first[incline],
                          "%s, order 2, N = 800, t = 5 (bound: 0.2 x order 1's)", incline ? "Coulomb incline" : "Ritter");
                assert_true(fabs(err[2]) <= 9.5 && fabs(err[3]) <= 8.0);
                assert_true(l1[3] < 0.2 * dam_l1_first[incline]);
            } else
                dam_l1_first[incline] = l1[3];
        }
}

/* The start-up refinement (startup_levels = 2: the first phase, until the
 * front has crossed about 40 faces, on meshes refined twice and once) takes
 * away the start-up lag of dry_fronts_against_exact: order 2, Ritter and
 * the Coulomb incline, fronts within 3 cells at N = 200, 400, 800 (95 to
 * 395 cells of travel; measured Ritter -2.19, -1.83, -1.40), the front
 * error in metres falling at first order or better (by more than 4 over
 * the two doublings), L1(h) at most half of the run without (N = 200,
 * 400; measured a quarter to a third). */
static void startup_refinement_fronts_within_three_cells(void **state)
{
    (void)state;
    const size_t ns[] = {200, 400, 800};
    for (int incline = 0; incline < 2; ++incline) {
        double err[3], l1[3], l10 = 0.0, travel;
        printf("  %s, order 2, startup_levels 2, t = 5: front error in cells, L1(h) (without):",
               incline ? "Coulomb incline" : "Ritter");
        for (int k = 0; k < 3; ++k) {
            err[k] = dam_front_from(incline, 2, ns[k], 0.0, 2, &travel, &l1[k]);
            if (k < 2) /* the runs without: dry_fronts_against_exact's (N = 800: 6.2e-3) */
                dam_front_from(incline, 2, ns[k], 0.0, 0, &travel, &l10);
            printf(k < 2 ? " N=%zu %+.2f, %.1e (%.1e);" : " N=%zu %+.2f, %.1e;", ns[k], err[k], l1[k], l10);
            gf_verify("exact front", "front error in cells (abs)", fabs(err[k]), "<=", 3.0,
                      "%s, order 2, startup_levels 2, N = %zu, t = 5", incline ? "Coulomb incline" : "Ritter", ns[k]);
            assert_true(fabs(err[k]) <= 3.0);
            if (k < 2)
                assert_true(l1[k] <= 0.5 * l10);
        }
        printf("\n");
        assert_true(fabs(err[2]) * 20.0 / 800.0 < 0.25 * fabs(err[0]) * 20.0 / 200.0);
    }
}

/* gf_surface_alloc_edges: the edges' length, centre and unit normal computed
 * by the kernel from the points, each edge's end points and the surface's
 * normal at the edge.  The fixture feeds it a strip mesh's nodes as the
 * points, the surface normal at an edge as the bridge's edgeAreaNormals
 * would (the mean of the adjacent faces' normals, normalised; the owner's on
 * a boundary edge), the internal edges as entries of the arrays [0] in
 * reverse order and the boundary edges as entries of the arrays [1]
 * (index -1 - i), every third edge with its end points swapped (its normal
 * must still point away from the owner).  len, en and ec hold the
 * documented formula computed here, independently of the kernel:
 * d = p_end - p_start, length |d|, centre (p_start + p_end)/2, normal
 * d x n_e turned away from the owner's centre, scaled to the length,
 * divided by it. */
struct eg_fixture {
    strip_mesh *sm;
    int *index, *ends0, *ends1, *pe; /* pe: each edge's start and end point */
    double *sn0, *sn1, *sn;         /* sn: each edge's surface normal */
    double *len, *en, *ec;
    size_t n0, n1;
    gf_surface_edge_geometry eg;
};

static void eg_fixture_init(struct eg_fixture *x, strip_mesh *sm)
{
    const gf_surface_mesh *m = &sm->m;
    const size_t ne = m->n_edges, nx = sm->nx, ny = sm->ny;
    x->sm = sm;
    x->index = malloc(ne * sizeof *x->index);
    x->pe = malloc(2 * ne * sizeof *x->pe);
    x->ends0 = malloc(2 * ne * sizeof *x->ends0);
    x->ends1 = malloc(2 * ne * sizeof *x->ends1);
    x->sn = malloc(3 * ne * sizeof *x->sn);
    x->sn0 = malloc(3 * ne * sizeof *x->sn0);
    x->sn1 = malloc(3 * ne * sizeof *x->sn1);
    x->len = malloc(ne * sizeof *x->len);
    x->en = malloc(3 * ne * sizeof *x->en);
    x->ec = malloc(3 * ne * sizeof *x->ec);
    assert_non_null(x->ec);
    /* the end points in strip_geometry's edge order: edges of constant s
     * from node (i, j) to (i, j+1), then of constant y from (i, j) to (i+1, j) */
    size_t e = 0;
    for (size_t j = 0; j < ny; ++j)
        for (size_t i = 0; i <= nx; ++i, ++e)
            x->pe[2 * e] = (int)(j * (nx + 1) + i), x->pe[2 * e + 1] = (int)((j + 1) * (nx + 1) + i);
    for (size_t j = 0; j <= ny; ++j)
        for (size_t i = 0; i < nx; ++i, ++e)
            x->pe[2 * e] = (int)(j * (nx + 1) + i), x->pe[2 * e + 1] = (int)(j * (nx + 1) + i + 1);
    assert_int_equal(e, ne);
    size_t n_int = 0;
    for (e = 0; e < ne; ++e) {
        /* the mesh's own end points are these nodes */
        assert_memory_equal(sm->epoints + 6 * e, sm->node + 3 * x->pe[2 * e], 3 * sizeof(double));
        assert_memory_equal(sm->epoints + 6 * e + 3, sm->node + 3 * x->pe[2 * e + 1], 3 * sizeof(double));
        n_int += m->neighbour[e] >= 0;
        if (e % 3 == 1) {
            const int p = x->pe[2 * e];
            x->pe[2 * e] = x->pe[2 * e + 1], x->pe[2 * e + 1] = p;
        }
        const double *no = m->normal + 3 * m->owner[e];
        const double *nn = m->neighbour[e] >= 0 ? m->normal + 3 * m->neighbour[e] : no;
        double *n = x->sn + 3 * e;
        for (int k = 0; k < 3; ++k)
            n[k] = no[k] + nn[k];
        const double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (int k = 0; k < 3; ++k)
            n[k] /= l;
    }
    assert_true(n_int > 0 && n_int < ne);
    x->n0 = x->n1 = 0;
    for (e = 0; e < ne; ++e) {
        int *ends;
        double *sn;
        if (m->neighbour[e] >= 0) {
            const size_t i = n_int - 1 - x->n0++; /* reverse order */
            x->index[e] = (int)i, ends = x->ends0 + 2 * i, sn = x->sn0 + 3 * i;
        } else {
            const size_t i = x->n1++;
            x->index[e] = -1 - (int)i, ends = x->ends1 + 2 * i, sn = x->sn1 + 3 * i;
        }
        memcpy(ends, x->pe + 2 * e, 2 * sizeof *ends);
        memcpy(sn, x->sn + 3 * e, 3 * sizeof *sn);
    }
    assert_int_equal(x->n0, n_int);
    gf_surface_edge_geometry eg = {x->index, sm->node, {x->ends0, x->ends1}, {x->sn0, x->sn1}};
    x->eg = eg;
    /* the documented formula */
    for (e = 0; e < ne; ++e) {
        const double *a = sm->node + 3 * x->pe[2 * e], *b = sm->node + 3 * x->pe[2 * e + 1], *n = x->sn + 3 * e;
        const double *xo = m->centre + 3 * m->owner[e];
        double d[3], v[3], *c = x->ec + 3 * e, *nu = x->en + 3 * e;
        for (int k = 0; k < 3; ++k)
            d[k] = b[k] - a[k], c[k] = (a[k] + b[k]) / 2;
        const double l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        x->len[e] = l;
        sm_cross(d, n, v);
        if (v[0] * (xo[0] - c[0]) + v[1] * (xo[1] - c[1]) + v[2] * (xo[2] - c[2]) >= 0.0)
            v[0] = -v[0], v[1] = -v[1], v[2] = -v[2];
        const double vm = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        for (int k = 0; k < 3; ++k)
            nu[k] = v[k] * (l / vm) / l;
    }
}

static void eg_fixture_free(struct eg_fixture *x)
{
    void *p[] = {x->index, x->ends0, x->ends1, x->pe, x->sn0, x->sn1, x->sn, x->len, x->en, x->ec};
    for (size_t i = 0; i < sizeof p / sizeof p[0]; ++i)
        free(p[i]);
}

/* the two scenes: a pile (0.5 m high) sliding down the curved slope (40 deg
 * to 10 deg, 80 x 30 faces, walls all round; Coulomb 20 deg) from s = 5,
 * and a pile (0.6 m) sliding into the bumpy bowl (non-planar quads, 40 x 20
 * faces, walls; Coulomb 15 deg) from x = 4 */
static strip_mesh *eg_scene(int bowl, gf_surface_config *c, double **h)
{
    strip_mesh *sm = bowl ? strip_mesh_new(40, 20, 0, 20, -5, 5, NULL, NULL, WALLS)
                          : strip_mesh_new(80, 30, 0, 30, -3.75, 3.75, curved_zeta, NULL, WALLS);
    if (bowl)
        strip_mesh_warp(sm, bumpy_bowl, NULL);
    gf_surface_config_default(c);
    coulomb(c, bowl ? 15 : 20);
    *h = paraboloid(sm, bowl ? 4.0 : 5.0, bowl ? 0.6 : 0.5);
    return sm;
}

static gf_surface *eg_run(const gf_surface_mesh *m, const gf_surface_edge_geometry *eg, const gf_surface_config *c,
                          const double *h, double t_end, long *steps, double *rel_volume)
{
    gf_surface *s = NULL;
    if (gf_surface_alloc_edges(m, eg, c, &s))
        fail_msg("gf_surface_alloc_edges (%s): %s", eg ? "edge geometry" : "NULL", gf_error_detail());
    assert_int_equal(gf_surface_set_state(s, h, NULL), GF_SUCCESS);
    const double v0 = gf_surface_volume(s);
    double t = 0.0;
    *steps = surface_advance(s, &t, t_end);
    assert_true(*steps > 0 || t_end == 0.0);
    *rel_volume = fabs(gf_surface_volume(s) - v0) / v0;
    return s;
}

/* gf_surface_alloc_edges equals gf_surface_alloc bit for bit when the mesh's
 * length, edge_normal and edge_centre hold the documented formula's values
 * (the fixture's, computed here): on the curved slope and in the bumpy bowl
 * the same steps to t = 3 s and h, momentum, basal pressure and edge
 * volumes identical (memcmp), with the mesh's arrays NULL and with them
 * filled with NaN (never read), the volume conserved to 1e-12.  Both index
 * signs are used (internal edges in [0], boundary edges in [1]) and every
 * third edge has its end points swapped. */
static void edge_geometry_from_points_equals_mesh_arrays(void **state)
{
    (void)state;
    for (int bowl = 0; bowl < 2; ++bowl) {
        gf_surface_config c;
        double *h;
        strip_mesh *sm = eg_scene(bowl, &c, &h);
        struct eg_fixture x;
        eg_fixture_init(&x, sm);
        const size_t nf = sm->m.n_faces, ne = sm->m.n_edges;
        gf_surface_mesh ma = sm->m, mb = sm->m, mc = sm->m;
        ma.length = x.len, ma.edge_normal = x.en, ma.edge_centre = x.ec;
        mb.length = mb.edge_normal = mb.edge_centre = NULL;
        double *nan = malloc(3 * ne * sizeof *nan);
        for (size_t i = 0; i < 3 * ne; ++i)
            nan[i] = NAN;
        mc.length = mc.edge_normal = mc.edge_centre = nan;
        long na, nb, nc;
        double ra, rb, rc;
        gf_surface *a = eg_run(&ma, NULL, &c, h, 3.0, &na, &ra);
        gf_surface *b = eg_run(&mb, &x.eg, &c, h, 3.0, &nb, &rb);
        gf_surface *cc = eg_run(&mc, &x.eg, &c, h, 3.0, &nc, &rc);
        const double *ha = gf_surface_h(a), *ma_ = gf_surface_momentum(a);
        double hmax = 0.0;
        for (size_t f = 0; f < nf; ++f)
            hmax = fmax(hmax, ha[f]);
        printf("  %s, t = 3 s: %ld / %ld / %ld steps, max h %.3f, volume change %.1e / %.1e / %.1e relative, "
               "%zu edges in [0], %zu in [1]\n", bowl ? "bumpy bowl" : "curved slope", na, nb, nc, hmax, ra, rb, rc,
               x.n0, x.n1);
        assert_int_equal(nb, na);
        assert_int_equal(nc, na);
        gf_surface *r[2] = {b, cc};
        for (int k = 0; k < 2; ++k) {
            assert_memory_equal(gf_surface_h(r[k]), ha, nf * sizeof(double));
            assert_memory_equal(gf_surface_momentum(r[k]), ma_, 3 * nf * sizeof(double));
            assert_memory_equal(gf_surface_pb(r[k]), gf_surface_pb(a), nf * sizeof(double));
            assert_memory_equal(gf_surface_edge_volume(r[k]), gf_surface_edge_volume(a), ne * sizeof(double));
        }
        gf_verify("gf_surface_alloc with the formula in the mesh's arrays", "relative volume change", rb, "<=", 1e-12,
                  "%s, edges from points, t = 3 s", bowl ? "pile in a bumpy bowl" : "pile on the curved slope");
        assert_true(ra <= 1e-12 && rb <= 1e-12 && rc <= 1e-12);
        assert_true(hmax > 0.05); /* the pile moved and spread, but is there */
        gf_surface_free(a);
        gf_surface_free(b);
        gf_surface_free(cc);
        free(nan);
        eg_fixture_free(&x);
        strip_mesh_free(sm);
        free(h);
    }
}

/* The formula is the mesh's geometry: the fixture's lengths and centres
 * equal surface_mesh.h's own (sm_edge: the unit tangent times the
 * unnormalised mean face normal, normalised: other operations, other
 * rounding) exactly and its normals within 1e-15, and the run with the
 * kernel's own geometry (gf_surface_alloc_edges) against the run with
 * sm_edge's arrays, on the curved slope and in the bumpy bowl, takes the
 * same steps and agrees to 1e-14 of max h and max |momentum| at t = 1 s
 * (measured 1e-16 to 4e-16), to 1e-9 at t = 3 s: the 1-ulp differences in
 * the normals grow at the curved slope's moving front (the limiters' and
 * the dry threshold's switches; measured 1e-16, 2e-13, 9e-14 at t = 1, 2,
 * 3 s there, 1e-11 at t = 3 s run without the stops at 0.25 .. 2 s; below
 * 4e-15 in the bowl). */
static void edge_geometry_from_points_agrees_with_mesh_geometry(void **state)
{
    (void)state;
    for (int bowl = 0; bowl < 2; ++bowl) {
        gf_surface_config c;
        double *h;
        strip_mesh *sm = eg_scene(bowl, &c, &h);
        struct eg_fixture x;
        eg_fixture_init(&x, sm);
        const size_t nf = sm->m.n_faces, ne = sm->m.n_edges;
        double dl = 0.0, dc = 0.0, dn = 0.0;
        for (size_t e = 0; e < ne; ++e) {
            dl = fmax(dl, fabs(x.len[e] - sm->length[e]) / sm->length[e]);
            for (int k = 0; k < 3; ++k) {
                dc = fmax(dc, fabs(x.ec[3 * e + k] - sm->ecentre[3 * e + k]));
                dn = fmax(dn, fabs(x.en[3 * e + k] - sm->enormal[3 * e + k]));
            }
        }
        gf_surface_mesh mb = sm->m;
        mb.length = mb.edge_normal = mb.edge_centre = NULL;
        long na = 0, nb = 0;
        double ra, rb, hx = 0.0, mx = 0.0, dh = 0.0, dm = 0.0;
        gf_surface *a = eg_run(&sm->m, NULL, &c, h, 0.0, &na, &ra);
        gf_surface *b = eg_run(&mb, &x.eg, &c, h, 0.0, &nb, &rb);
        const double v0 = gf_surface_volume(b);
        double ta = 0.0, tb = 0.0;
        static const double t_out[] = {0.25, 0.5, 1.0, 2.0, 3.0};
        double dh1 = 0.0, dm1 = 0.0;
        for (size_t q = 0; q < sizeof t_out / sizeof t_out[0]; ++q) {
            const double t_end = t_out[q];
            na += surface_advance(a, &ta, t_end), nb += surface_advance(b, &tb, t_end);
            const double *ha = gf_surface_h(a), *hb = gf_surface_h(b), *pa = gf_surface_momentum(a),
                         *pb = gf_surface_momentum(b);
            hx = mx = dh = dm = 0.0;
            for (size_t f = 0; f < nf; ++f) {
                hx = fmax(hx, ha[f]), dh = fmax(dh, fabs(ha[f] - hb[f]));
                for (int k = 0; k < 3; ++k)
                    mx = fmax(mx, fabs(pa[3 * f + k])), dm = fmax(dm, fabs(pa[3 * f + k] - pb[3 * f + k]));
            }
            printf("    t = %.2f: %ld / %ld steps, max |dh| / max h %.1e, max |dm| / max |m| %.1e\n", t_end, na, nb,
                   dh / hx, dm / mx);
            assert_int_equal(na, nb);
            if (t_end == 1.0)
                dh1 = dh / hx, dm1 = dm / mx;
        }
        rb = fabs(gf_surface_volume(b) - v0) / v0;
        printf("  %s: geometry differences: length %.1e relative, centre %.1e m, normal %.1e; t = 3 s, %ld / %ld "
               "steps: max |dh| %.1e (max h %.3f), max |dm| %.1e (max %.3f), volume change %.1e\n",
               bowl ? "bumpy bowl" : "curved slope", dl, dc, dn, na, nb, dh, hx, dm, mx, rb);
        gf_verify("the mesh's own edge geometry (sm_edge)", "max |h - h_edges| / max h", dh1, "<=", 1e-14,
                  "%s, edges from points, t = 1 s", bowl ? "pile in a bumpy bowl" : "pile on the curved slope");
        assert_true(dl == 0.0 && dc == 0.0);
        assert_true(dn <= 1e-15);
        assert_true(dh1 <= 1e-14 && dm1 <= 1e-14);
        assert_true(dh <= 1e-9 * hx && dm <= 1e-9 * mx);
        assert_true(rb <= 1e-12);
        gf_surface_free(a);
        gf_surface_free(b);
        eg_fixture_free(&x);
        strip_mesh_free(sm);
        free(h);
    }
}

/* gf_surface_alloc_edges refuses, with an error naming the cause and no
 * scheme: startup_levels > 0 (the refined meshes need the mesh's arrays),
 * no index, each missing array of the edge geometry (named), an edge whose
 * end points coincide (length 0) and an edge whose surface normal lies along
 * it (d x n_e = 0: no edge normal), each named by its edge number. */
static void edge_geometry_from_points_refusals(void **state)
{
    (void)state;
    double zeta = 20 * GF_DEG;
    strip_mesh *sm = strip_mesh_new(6, 4, 0, 6, -2, 2, const_zeta, &zeta, WALLS);
    struct eg_fixture x;
    eg_fixture_init(&x, sm);
    gf_surface_mesh m = sm->m;
    m.length = m.edge_normal = m.edge_centre = NULL;
    gf_surface_config c;
    gf_surface_config_default(&c);
    gf_surface *s = NULL;
    assert_int_equal(gf_surface_alloc_edges(&m, &x.eg, &c, &s), GF_SUCCESS); /* the baseline is accepted */
    gf_surface_free(s);
    struct {
        const char *what, *expect;
    } cases[] = {{"startup_levels = 2", "startup_levels"},
                 {"index NULL", "index"},
                 {"points NULL", "points"},
                 {"ends[0] NULL", "ends[0]"},
                 {"ends[1] NULL", "ends[1]"},
                 {"surface_normal[0] NULL", "surface_normal[0]"},
                 {"surface_normal[1] NULL", "surface_normal[1]"},
                 {"edge 8's end points equal", "edge 8"},
                 {"edge 8's surface normal along it", "edge 8"}};
    const int i8 = x.index[8];
    assert_true(i8 >= 0); /* an internal edge: arrays [0] */
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        gf_surface_edge_geometry eg = x.eg;
        gf_surface_config ci = c;
        int ends[2 * 64];
        double sn[3 * 64];
        assert_true(x.n0 <= 64);
        memcpy(ends, x.ends0, 2 * x.n0 * sizeof *ends);
        memcpy(sn, x.sn0, 3 * x.n0 * sizeof *sn);
        switch (i) {
        case 0: ci.startup_levels = 2; break;
        case 1: eg.index = NULL; break;
        case 2: eg.points = NULL; break;
        case 3: eg.ends[0] = NULL; break;
        case 4: eg.ends[1] = NULL; break;
        case 5: eg.surface_normal[0] = NULL; break;
        case 6: eg.surface_normal[1] = NULL; break;
        case 7:
            ends[2 * i8 + 1] = ends[2 * i8];
            eg.ends[0] = ends;
            break;
        default: {
            const double *a = sm->node + 3 * ends[2 * i8], *b = sm->node + 3 * ends[2 * i8 + 1];
            double d[3];
            sm_sub(b, a, d);
            sm_norm(d);
            memcpy(sn + 3 * i8, d, sizeof d);
            eg.surface_normal[0] = sn;
        }
        }
        s = (gf_surface *)&s; /* must be reset to NULL */
        const gf_status st = gf_surface_alloc_edges(&m, &eg, &ci, &s);
        const char *detail = gf_error_detail();
        printf("  %s: status %d, \"%s\"\n", cases[i].what, (int)st, detail ? detail : "(none)");
        assert_int_not_equal(st, GF_SUCCESS);
        assert_null(s);
        assert_non_null(detail);
        if (!strstr(detail, cases[i].expect))
            fail_msg("%s: the error \"%s\" does not name %s", cases[i].what, detail, cases[i].expect);
    }
    eg_fixture_free(&x);
    strip_mesh_free(sm);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(pile_at_rest_on_plane_and_curved_bed),
        cmocka_unit_test(lake_at_rest_with_shorelines),
        cmocka_unit_test(mass_conserved_in_a_closed_box),
        cmocka_unit_test(renumbered_mesh_runs_the_same_flow),
        cmocka_unit_test(peak_fields_are_the_maxima_over_all_steps),
        cmocka_unit_test(kinetic_energy_is_half_h_u2_area),
        cmocka_unit_test(moving_faces_counted_and_located),
        cmocka_unit_test(restart_continues_the_run_exactly),
        cmocka_unit_test(dry_fronts_against_exact),
        cmocka_unit_test(resolved_front_within_three_cells),
        cmocka_unit_test(startup_refinement_fronts_within_three_cells),
        cmocka_unit_test(mesh_refinement_geometry),
        cmocka_unit_test(startup_refinement_conserves_mass),
        cmocka_unit_test(edge_geometry_from_points_equals_mesh_arrays),
        cmocka_unit_test(edge_geometry_from_points_agrees_with_mesh_geometry),
        cmocka_unit_test(edge_geometry_from_points_refusals),
    };
    return gf_run_tests("surface_verification", tests, NULL, NULL);
}
