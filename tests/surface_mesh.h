/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Test and benchmark helper: a structured nx x ny quadrilateral surface mesh
 * on a developable surface (a plane, or a surface bent along x by an
 * inclination profile zeta(x)), flattened into gf_surface_mesh arrays.  The
 * surface is X(s, y) = (x(s), y, z(s)) with dx/ds = cos zeta, dz/ds =
 * -sin zeta (s the arc length, finite-area paper section 6.3), so every quad
 * is planar and the arc length is the 1D solvers' coordinate. */
#ifndef GF_TEST_SURFACE_MESH_H
#define GF_TEST_SURFACE_MESH_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "granflow/surface.h"

typedef struct strip_mesh {
    size_t nx, ny;
    double s0, s1, y0, y1;
    double *node;          /* (nx+1)(ny+1) x 3 */
    double *area, *centre, *normal, *length, *enormal, *ecentre, *epoints;
    int *owner, *neighbour, *kind;
    double *s_of_face;     /* arc-length coordinate of each face centre */
    int kinds[4];
    gf_surface_mesh m;
} strip_mesh;

typedef double (*strip_zeta_fn)(double s, void *ctx);

static inline void sm_sub(const double *a, const double *b, double *c)
{
    c[0] = a[0] - b[0], c[1] = a[1] - b[1], c[2] = a[2] - b[2];
}
static inline void sm_cross(const double *a, const double *b, double *c)
{
    c[0] = a[1] * b[2] - a[2] * b[1], c[1] = a[2] * b[0] - a[0] * b[2], c[2] = a[0] * b[1] - a[1] * b[0];
}
static inline double sm_norm(double *a)
{
    const double l = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    a[0] /= l, a[1] /= l, a[2] /= l;
    return l;
}

/* Edge e from node p to q with owner o (neighbour nb, kind kd): length,
 * midpoint and the unit normal t x nn (nn the mean normal of its faces),
 * oriented away from the owner's centre. */
static inline void sm_edge(struct strip_mesh *sm, size_t e, const double *p, const double *q, int o, int nb,
                           int kd)
{
    double nn[3];
    for (int k = 0; k < 3; ++k)
        nn[k] = sm->normal[3 * o + k] + (nb >= 0 ? sm->normal[3 * nb + k] : 0.0);
    double t[3], v[3], r[3];
    sm_sub(q, p, t);
    sm->length[e] = sm_norm(t);
    sm_cross(t, nn, v);
    sm_norm(v);
    for (int k = 0; k < 3; ++k)
        sm->ecentre[3 * e + k] = 0.5 * (p[k] + q[k]), r[k] = sm->ecentre[3 * e + k] - sm->centre[3 * o + k];
    if (v[0] * r[0] + v[1] * r[1] + v[2] * r[2] < 0)
        v[0] = -v[0], v[1] = -v[1], v[2] = -v[2];
    memcpy(sm->enormal + 3 * e, v, sizeof v);
    memcpy(sm->epoints + 6 * e, p, 3 * sizeof *p);
    memcpy(sm->epoints + 6 * e + 3, q, 3 * sizeof *q);
    sm->owner[e] = o, sm->neighbour[e] = nb, sm->kind[e] = kd;
}

/* Face and edge geometry from the nodes (planar-quad formulas: centre the
 * mean of the corners, normal and area from the diagonals; edges with the
 * mean normal of their faces). */
static inline void strip_geometry(strip_mesh *sm)
{
    const size_t nx = sm->nx, ny = sm->ny;
    const double s0 = sm->s0, ds = (sm->s1 - sm->s0) / (double)nx;
    const int *kinds = sm->kinds;
#define NODE(i, j) (sm->node + 3 * ((j) * (nx + 1) + (i)))
    for (size_t j = 0; j < ny; ++j)
        for (size_t i = 0; i < nx; ++i) {
            const size_t f = j * nx + i;
            const double *a = NODE(i, j), *b = NODE(i + 1, j), *c = NODE(i + 1, j + 1), *d = NODE(i, j + 1);
            double d1[3], d2[3], n[3];
            sm_sub(c, a, d1);
            sm_sub(d, b, d2);
            sm_cross(d1, d2, n);
            sm->area[f] = 0.5 * sm_norm(n);
            memcpy(sm->normal + 3 * f, n, sizeof n);
            for (int k = 0; k < 3; ++k)
                sm->centre[3 * f + k] = 0.25 * (a[k] + b[k] + c[k] + d[k]);
            sm->s_of_face[f] = s0 + ds * ((double)i + 0.5);
        }
    size_t e = 0;
    /* edges of constant s: between (i-1, j) and (i, j), from node (i, j) to (i, j+1) */
    for (size_t j = 0; j < ny; ++j)
        for (size_t i = 0; i <= nx; ++i, ++e) {
            const double *p = NODE(i, j), *q = NODE(i, j + 1);
            int o, nb, kd = GF_EDGE_INTERNAL;
            if (i == 0)
                o = (int)(j * nx), nb = -1, kd = kinds[0];
            else if (i == nx)
                o = (int)(j * nx + nx - 1), nb = -1, kd = kinds[1];
            else
                o = (int)(j * nx + i - 1), nb = (int)(j * nx + i);
            sm_edge(sm, e, p, q, o, nb, kd);
        }
    /* edges of constant y: between (i, j-1) and (i, j), from node (i, j) to (i+1, j) */
    for (size_t j = 0; j <= ny; ++j)
        for (size_t i = 0; i < nx; ++i, ++e) {
            const double *p = NODE(i, j), *q = NODE(i + 1, j);
            int o, nb, kd = GF_EDGE_INTERNAL;
            if (j == 0)
                o = (int)i, nb = -1, kd = kinds[2];
            else if (j == ny)
                o = (int)((ny - 1) * nx + i), nb = -1, kd = kinds[3];
            else
                o = (int)((j - 1) * nx + i), nb = (int)(j * nx + i);
            sm_edge(sm, e, p, q, o, nb, kd);
        }
#undef NODE
}

/* Add w(x, y) to every node's height and recompute the geometry: a doubly
 * curved surface (its quads no longer planar); s_of_face stays the
 * unbent arc length. */
static inline void strip_mesh_warp(strip_mesh *sm, double (*w)(double x, double y, void *ctx), void *ctx)
{
    for (size_t i = 0; i < (sm->nx + 1) * (sm->ny + 1); ++i) {
        double *p = sm->node + 3 * i;
        p[2] += w(p[0], p[1], ctx);
    }
    strip_geometry(sm);
}

/* kinds: edges at s0, s1, y0, y1 */
static inline strip_mesh *strip_mesh_new(size_t nx, size_t ny, double s0, double s1, double y0, double y1,
                                         strip_zeta_fn zeta, void *ctx, const int kinds[4])
{
    strip_mesh *sm = calloc(1, sizeof *sm);
    sm->nx = nx, sm->ny = ny, sm->s0 = s0, sm->s1 = s1, sm->y0 = y0, sm->y1 = y1;
    const size_t nf = nx * ny, ne = (nx + 1) * ny + nx * (ny + 1);
    sm->node = malloc(3 * (nx + 1) * (ny + 1) * sizeof(double));
    /* centreline x(s), z(s) by the midpoint rule on 64 sub-steps per cell */
    double *xs = malloc((nx + 1) * sizeof(double)), *zs = malloc((nx + 1) * sizeof(double));
    xs[0] = zs[0] = 0.0;
    const double ds = (s1 - s0) / (double)nx;
    for (size_t i = 0; i < nx; ++i) {
        double x = xs[i], z = zs[i];
        for (int k = 0; k < 64; ++k) {
            const double s = s0 + ds * ((double)i + (k + 0.5) / 64.0), zt = zeta ? zeta(s, ctx) : 0.0;
            x += ds / 64.0 * cos(zt);
            z -= ds / 64.0 * sin(zt);
        }
        xs[i + 1] = x, zs[i + 1] = z;
    }
    for (size_t j = 0; j <= ny; ++j)
        for (size_t i = 0; i <= nx; ++i) {
            double *p = sm->node + 3 * (j * (nx + 1) + i);
            p[0] = xs[i], p[1] = y0 + (y1 - y0) * (double)j / (double)ny, p[2] = zs[i];
        }
    free(xs);
    free(zs);
    memcpy(sm->kinds, kinds, sizeof sm->kinds);
    sm->area = malloc(nf * sizeof(double));
    sm->centre = malloc(3 * nf * sizeof(double));
    sm->normal = malloc(3 * nf * sizeof(double));
    sm->s_of_face = malloc(nf * sizeof(double));
    sm->owner = malloc(ne * sizeof(int));
    sm->neighbour = malloc(ne * sizeof(int));
    sm->kind = malloc(ne * sizeof(int));
    sm->length = malloc(ne * sizeof(double));
    sm->enormal = malloc(3 * ne * sizeof(double));
    sm->ecentre = malloc(3 * ne * sizeof(double));
    sm->epoints = malloc(6 * ne * sizeof(double));
    strip_geometry(sm);
    gf_surface_mesh m = {nf, 0, ne, sm->area, sm->centre, sm->normal, sm->owner, sm->neighbour,
                         sm->kind, sm->length, sm->enormal, sm->ecentre, sm->epoints};
    sm->m = m;
    return sm;
}

static inline void strip_mesh_free(strip_mesh *sm)
{
    if (!sm)
        return;
    void *p[] = {sm->node, sm->area, sm->centre, sm->normal, sm->length, sm->enormal, sm->ecentre, sm->epoints,
                 sm->owner, sm->neighbour, sm->kind, sm->s_of_face};
    for (size_t i = 0; i < sizeof p / sizeof p[0]; ++i)
        free(p[i]);
    free(sm);
}

/* Advance to t_end with the largest stable steps; returns the step count,
 * or -1 on failure. */
static inline long surface_advance(gf_surface *s, double *t, double t_end)
{
    long n = 0;
    while (*t < t_end - 1e-14 * fabs(t_end)) {
        double dt;
        if (gf_surface_max_dt(s, &dt))
            return -1;
        if (dt > t_end - *t)
            dt = t_end - *t;
        if (gf_surface_step(s, dt))
            return -1;
        *t += dt;
        ++n;
    }
    return n;
}

/* A lake with a horizontal free surface eta = (lowest face centre) + depth:
 * h = (eta - z_f) / n_z,f, the normal thickness over each face's plane, so
 * that the basal pressure rho a h (a = -g.n, g vertical) is the hydrostatic
 * rho g (eta - z_f); 0 above the shoreline (allocated, one value per face). */
static inline double *strip_lake(const strip_mesh *sm, double depth)
{
    const size_t nf = sm->m.n_faces;
    double zmin = HUGE_VAL;
    for (size_t f = 0; f < nf; ++f)
        zmin = fmin(zmin, sm->centre[3 * f + 2]);
    double *h = malloc(nf * sizeof *h);
    for (size_t f = 0; f < nf; ++f) {
        const double d = zmin + depth - sm->centre[3 * f + 2];
        h[f] = d > 0.0 ? d / sm->normal[3 * f + 2] : 0.0;
    }
    return h;
}

#endif
