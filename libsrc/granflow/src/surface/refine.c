/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Uniform refinement of a surface mesh (granflow/surface.h,
 * gf_surface_mesh_refine): every face of k edges becomes k quadrilaterals,
 * each made of the face centre, the midpoints of two consecutive edges and
 * their common corner. */
#include "granflow/surface.h"
#include "internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static inline double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static inline void cross3(const double *a, const double *b, double *c)
{
    c[0] = a[1] * b[2] - a[2] * b[1], c[1] = a[2] * b[0] - a[0] * b[2], c[2] = a[0] * b[1] - a[1] * b[0];
}
static inline double norm3(const double *a) { return sqrt(dot3(a, a)); }

void gf_surface_refined_free(gf_surface_refined *r)
{
    if (!r)
        return;
    void *p[] = {r->area_, r->centre_, r->normal_, r->length_, r->enormal_, r->ecentre_, r->epoints_,
                 r->owner_, r->neighbour_, r->kind_, r->parent_face, r->parent_edge};
    for (size_t i = 0; i < sizeof p / sizeof p[0]; ++i)
        free(p[i]);
    free(r);
}

static int same_point(const double *a, const double *b, double tol)
{
    return fabs(a[0] - b[0]) <= tol && fabs(a[1] - b[1]) <= tol && fabs(a[2] - b[2]) <= tol;
}

gf_status gf_surface_mesh_refine(const gf_surface_mesh *in, gf_surface_refined **out)
{
    if (!in || !out)
        return gf_fail(GF_EINVAL, "gf_surface_mesh_refine: null argument");
    *out = NULL;
    if (!in->edge_points)
        return gf_fail(GF_EINVAL, "surface mesh refinement: the mesh has no edge_points (the end points of "
                                  "each edge are needed to split its faces)");
    const size_t nf = in->n_faces, ne = in->n_edges;
    /* face -> edges */
    size_t *start = calloc(nf + 1, sizeof *start);
    int *fe = malloc((2 * ne + 1) * sizeof *fe);
    gf_surface_refined *r = calloc(1, sizeof *r);
    if (!start || !fe || !r) {
        free(start), free(fe), free(r);
        return gf_fail(GF_ENOMEM, "surface mesh refinement: out of memory");
    }
    for (size_t e = 0; e < ne; ++e) {
        start[in->owner[e] + 1]++;
        if (in->neighbour[e] >= 0 && (size_t)in->neighbour[e] < nf) /* ghosts are not split */
            start[in->neighbour[e] + 1]++;
    }
    for (size_t f = 0; f < nf; ++f)
        start[f + 1] += start[f];
    {
        size_t *fill = calloc(nf, sizeof *fill);
        if (!fill) {
            free(start), free(fe), free(r);
            return gf_fail(GF_ENOMEM, "surface mesh refinement: out of memory");
        }
        for (size_t e = 0; e < ne; ++e) {
            fe[start[in->owner[e]] + fill[in->owner[e]]++] = (int)e;
            if (in->neighbour[e] >= 0 && (size_t)in->neighbour[e] < nf)
                fe[start[in->neighbour[e]] + fill[in->neighbour[e]]++] = (int)e;
        }
        free(fill);
    }
    /* sub-faces: one per edge of each face; sub-edges: two per edge plus
     * one per face edge (centre to midpoint) */
    const size_t nsf = start[nf], nse = 2 * ne + start[nf], ngh = 2 * in->n_ghosts, nst = nsf + ngh;
    r->area_ = malloc((nst + 1) * sizeof(double));
    r->centre_ = malloc(3 * (nst + 1) * sizeof(double));
    r->normal_ = malloc(3 * (nst + 1) * sizeof(double));
    r->parent_face = malloc(nsf * sizeof(int));
    r->length_ = malloc(nse * sizeof(double));
    r->enormal_ = malloc(3 * nse * sizeof(double));
    r->ecentre_ = malloc(3 * nse * sizeof(double));
    r->epoints_ = malloc(6 * nse * sizeof(double));
    r->owner_ = malloc(nse * sizeof(int));
    r->neighbour_ = malloc(nse * sizeof(int));
    r->kind_ = malloc(nse * sizeof(int));
    r->parent_edge = malloc(nse * sizeof(int));
    /* per face-edge slot: the cyclic position, and the sub-face at each end */
    int *slot_edge = malloc((nsf + 1) * sizeof(int));
    double *corner = malloc((3 * nsf + 1) * sizeof(double)); /* corner i: between slots i and i+1 */
    if (!r->area_ || !r->centre_ || !r->normal_ || !r->parent_face || !r->length_ ||
        !r->enormal_ || !r->ecentre_ || !r->epoints_ || !r->owner_ || !r->neighbour_ || !r->kind_ ||
        !r->parent_edge || !slot_edge || !corner) {
        free(start), free(fe), free(slot_edge), free(corner);
        gf_surface_refined_free(r);
        return gf_fail(GF_ENOMEM, "surface mesh refinement: out of memory for %zu sub-faces", nsf);
    }
    gf_status st = GF_SUCCESS;
    const double *P = in->edge_points;
    /* order each face's edges cyclically: slot i holds edge E_i, corner i is
     * the point E_i shares with E_{i+1} */
    for (size_t f = 0; f < nf && !st; ++f) {
        const size_t k = start[f + 1] - start[f], s0 = start[f];
        if (k < 3) {
            st = gf_fail(GF_EDOM, "surface mesh refinement: face %zu has %zu edges (need >= 3)", f, k);
            break;
        }
        int *used = calloc(k, sizeof *used);
        if (!used) {
            st = gf_fail(GF_ENOMEM, "surface mesh refinement: out of memory");
            break;
        }
        double tol = HUGE_VAL;
        for (size_t j = 0; j < k; ++j)
            tol = fmin(tol, in->length[fe[s0 + j]]);
        tol *= 1e-9;
        /* the cycle starts at the edge with the smallest centre (x, y, z),
         * not at the lowest edge number: the sub-faces, and the sums over
         * them (areas, restrictions), come in the same order however the
         * mesh is numbered or decomposed */
        for (size_t j = 1; j < k; ++j) {
            const double *x = in->edge_centre + 3 * fe[s0 + j], *y = in->edge_centre + 3 * fe[s0];
            int before = 0;
            for (int d = 0; d < 3; ++d)
                if (x[d] != y[d]) {
                    before = x[d] < y[d];
                    break;
                }
            if (before) {
                const int t = fe[s0];
                fe[s0] = fe[s0 + j], fe[s0 + j] = t;
            }
        }
        slot_edge[s0] = fe[s0];
        used[0] = 1;
        /* round the face from the first edge's larger end point (x, y, z),
         * whichever way the edge's points are stored */
        const double *p0 = P + 6 * fe[s0], *p1 = p0 + 3;
        for (int d = 0; d < 3; ++d)
            if (p0[d] != p1[d]) {
                if (p0[d] > p1[d]) {
                    const double *t = p0;
                    p0 = p1, p1 = t;
                }
                break;
            }
        const double *cur = p1;
        for (size_t i = 0; i < k; ++i) {
            memcpy(corner + 3 * (s0 + i), cur, 3 * sizeof(double));
            if (i + 1 == k) { /* the loop must close on the first edge's other point */
                if (!same_point(cur, p0, tol))
                    st = gf_fail(GF_EDOM, "surface mesh refinement: the edges of face %zu do not form a closed "
                                          "loop", f);
                break;
            }
            size_t found = k;
            for (size_t j = 0; j < k && found == k; ++j) {
                if (used[j])
                    continue;
                const double *q = P + 6 * fe[s0 + j];
                if (same_point(q, cur, tol))
                    found = j, cur = q + 3;
                else if (same_point(q + 3, cur, tol))
                    found = j, cur = q;
            }
            if (found == k) {
                st = gf_fail(GF_EDOM, "surface mesh refinement: the edges of face %zu do not form a closed loop", f);
                break;
            }
            used[found] = 1;
            slot_edge[s0 + i + 1] = fe[s0 + found];
        }
        free(used);
    }
    /* sub-face geometry: quad (C, M_i, V_i, M_{i+1}) as two triangles,
     * oriented along the parent's normal; areas scaled so that they sum to
     * the parent's exactly (mass-exact restriction and prolongation) */
    for (size_t f = 0; f < nf && !st; ++f) {
        const size_t k = start[f + 1] - start[f], s0 = start[f];
        const double *C = in->centre + 3 * f, *nf3 = in->normal + 3 * f;
        double sum = 0.0;
        for (size_t i = 0; i < k; ++i) {
            const int e1 = slot_edge[s0 + i], e2 = slot_edge[s0 + (i + 1) % k];
            const double *M1 = in->edge_centre + 3 * e1, *M2 = in->edge_centre + 3 * e2, *V = corner + 3 * (s0 + i);
            double a[3], b[3], c[3], t1[3], t2[3];
            for (int d = 0; d < 3; ++d)
                a[d] = M1[d] - C[d], b[d] = V[d] - C[d], c[d] = M2[d] - C[d];
            cross3(a, b, t1);
            cross3(b, c, t2);
            double nv[3] = {0.5 * (t1[0] + t2[0]), 0.5 * (t1[1] + t2[1]), 0.5 * (t1[2] + t2[2])};
            if (dot3(nv, nf3) < 0.0)
                nv[0] = -nv[0], nv[1] = -nv[1], nv[2] = -nv[2];
            const double A1 = 0.5 * norm3(t1), A2 = 0.5 * norm3(t2), An = norm3(nv);
            const size_t sf = s0 + i;
            if (!(A1 + A2 > 0.0) || !(An > 0.0)) {
                st = gf_fail(GF_EDOM, "surface mesh refinement: face %zu has a degenerate corner", f);
                break;
            }
            r->area_[sf] = A1 + A2;
            sum += A1 + A2;
            for (int d = 0; d < 3; ++d) {
                r->normal_[3 * sf + d] = nv[d] / An;
                r->centre_[3 * sf + d] =
                    (A1 * (C[d] + M1[d] + V[d]) + A2 * (C[d] + V[d] + M2[d])) / (3.0 * (A1 + A2));
            }
            r->parent_face[sf] = (int)f;
        }
        for (size_t i = 0; i < k && !st; ++i)
            r->area_[s0 + i] *= in->area[f] / sum;
    }
    /* ghost sub-faces: two per ghost (one per half of its processor edge),
     * the parent ghost's geometry until the caller fills the neighbour's */
    for (size_t j = 0; j < ngh; ++j) {
        const size_t g = nf + j / 2, sf = nsf + j;
        r->area_[sf] = 0.5 * in->area[g];
        memcpy(r->centre_ + 3 * sf, in->centre + 3 * g, 3 * sizeof(double));
        memcpy(r->normal_ + 3 * sf, in->normal + 3 * g, 3 * sizeof(double));
    }
    /* sub-edges: the two halves of every edge first (in edge order), then
     * the centre-to-midpoint edges inside each face */
    size_t se = 0;
    for (size_t e = 0; e < ne && !st; ++e) {
        const double *p0 = P + 6 * e, *p1 = p0 + 3, *M = in->edge_centre + 3 * e;
        const int o = in->owner[e], nb = in->neighbour[e];
        for (int half = 0; half < 2; ++half, ++se) {
            const double *end = half ? p1 : p0;
            /* the sub-face of face g whose corner is this half's end point */
            int sub[2] = {-1, -1};
            if (nb >= 0 && (size_t)nb >= nf) {
                /* a processor edge: the ghost sub-face of this half, numbered
                 * from the end point that is lexicographically smaller, the
                 * same on both ranks (identical coordinates) */
                const double *lo = p0;
                for (int d = 0; d < 3; ++d)
                    if (p0[d] != p1[d]) {
                        lo = p0[d] < p1[d] ? p0 : p1;
                        break;
                    }
                sub[1] = (int)(nsf + 2 * ((size_t)nb - nf) + (end == lo ? 0 : 1));
            }
            for (int side = 0; side < 2; ++side) {
                const int g = side ? nb : o;
                if (g < 0 || sub[side] >= 0)
                    continue;
                const size_t k = start[g + 1] - start[g], s0 = start[g];
                double tol = 1e-9 * in->length[e];
                for (size_t i = 0; i < k; ++i) {
                    const int e1 = slot_edge[s0 + i], e2 = slot_edge[s0 + (i + 1) % k];
                    if ((e1 == (int)e || e2 == (int)e) && same_point(corner + 3 * (s0 + i), end, tol)) {
                        sub[side] = (int)(s0 + i);
                        break;
                    }
                }
                if (sub[side] < 0)
                    st = gf_fail(GF_EDOM, "surface mesh refinement: edge %zu is not an edge of face %d", e, g);
            }
            r->owner_[se] = sub[0];
            r->neighbour_[se] = nb >= 0 ? sub[1] : -1;
            r->kind_[se] = in->kind[e];
            r->length_[se] = 0.5 * in->length[e];
            r->parent_edge[se] = (int)e;
            for (int d = 0; d < 3; ++d) {
                r->enormal_[3 * se + d] = in->edge_normal[3 * e + d];
                r->ecentre_[3 * se + d] = 0.5 * (end[d] + M[d]);
                r->epoints_[6 * se + d] = end[d];
                r->epoints_[6 * se + 3 + d] = M[d];
            }
        }
    }
    for (size_t f = 0; f < nf && !st; ++f) {
        const size_t k = start[f + 1] - start[f], s0 = start[f];
        const double *C = in->centre + 3 * f, *nf3 = in->normal + 3 * f;
        for (size_t i = 0; i < k; ++i, ++se) {
            /* edge C -> M(E_i) between the sub-faces of corners i-1 and i */
            const int e = slot_edge[s0 + i];
            const double *M = in->edge_centre + 3 * e;
            const size_t a = s0 + (i + k - 1) % k, b = s0 + i;
            double dir[3] = {M[0] - C[0], M[1] - C[1], M[2] - C[2]}, nu[3];
            const double L = norm3(dir);
            cross3(dir, nf3, nu);
            const double ln = norm3(nu);
            if (!(L > 0.0) || !(ln > 0.0)) {
                st = gf_fail(GF_EDOM, "surface mesh refinement: face %zu: an edge midpoint lies on its centre", f);
                break;
            }
            const double *ca = r->centre_ + 3 * a, *cb = r->centre_ + 3 * b;
            const double sg = (nu[0] * (cb[0] - ca[0]) + nu[1] * (cb[1] - ca[1]) + nu[2] * (cb[2] - ca[2])) < 0.0
                                  ? -1.0 : 1.0;
            r->owner_[se] = (int)a;
            r->neighbour_[se] = (int)b;
            r->kind_[se] = GF_EDGE_INTERNAL;
            r->length_[se] = L;
            r->parent_edge[se] = -1;
            for (int d = 0; d < 3; ++d) {
                r->enormal_[3 * se + d] = sg * nu[d] / ln;
                r->ecentre_[3 * se + d] = 0.5 * (C[d] + M[d]);
                r->epoints_[6 * se + d] = C[d];
                r->epoints_[6 * se + 3 + d] = M[d];
            }
        }
    }
    free(start), free(fe), free(slot_edge), free(corner);
    if (st) {
        gf_surface_refined_free(r);
        return st;
    }
    gf_surface_mesh m = {nsf, ngh, nse, r->area_, r->centre_, r->normal_, r->owner_, r->neighbour_,
                         r->kind_, r->length_, r->enormal_, r->ecentre_, r->epoints_};
    r->mesh = m;
    *out = r;
    return GF_SUCCESS;
}
