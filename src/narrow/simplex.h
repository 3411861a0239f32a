/* Simplices of A - B (or of B - A for the translation ray cast) as vertex
 * pairs, and the GJK distance sub-algorithm on them (simplex.c). Shared by
 * GJK, EPA and the translation ray cast (internal). */
#ifndef PXI_SIMPLEX_H
#define PXI_SIMPLEX_H

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "convex/convex.h"
#include "math/vec3.h"
#include "narrow/tolerance.h"

typedef struct sx_point {
    px_vec3 w;       /* a - b in B's frame */
    uint32_t ia, ib; /* vertex ids on A and B */
} sx_point;

typedef struct sx_simplex {
    sx_point p[4];
    double lam[4];
    int n;
    double margin; /* origin inside: its least distance to a face plane */
} sx_simplex;

/* The point (T_AB a_ia - b_ib) k of A - B, with its vertex pair. */
static inline sx_point sx_pair_point(const px_convex *a, const px_convex *b, const px_pose *t_ab, double k,
                                     uint32_t ia, uint32_t ib) {
    sx_point p;
    p.ia = ia;
    p.ib = ib;
    p.w = pxi_scale(pxi_sub(pxi_xform(t_ab, a->v[ia]), b->v[ib]), k);
    return p;
}

/* Support calls a GJK-type loop may make on a pair: a safeguard far above
 * what polytopes need (their loops end on a repeated support). */
static inline uint32_t sx_iteration_cap(const px_convex *a, const px_convex *b) {
    return 64 + 4 * (uint32_t)ilogb((double)a->nv + b->nv + 1.0);
}

/* Closest point to the origin of the hull of s's points, by Voronoi-region
 * case analysis: keeps the points that carry weight, with their weights in
 * lam. Segment, triangle (a collinear one is solved as its longest side). */
void pxi_sx_segment(sx_simplex *s);
void pxi_sx_triangle(sx_simplex *s);
/* Tetrahedron: returns 1 when the origin is inside (or on) it, with
 * barycentric weights in lam and margin = its least distance to a face plane
 * (0 when the tetrahedron is too flat for its side tests); otherwise the
 * closest point over the faces the origin sees. */
int pxi_sx_tetra(sx_simplex *s);
/* Does the tetrahedron contain the origin with every side test certain? */
int pxi_sx_tetra_surely_contains(const sx_simplex *s);
/* The closest point over all four faces, without side tests (a tetrahedron
 * too flat for them). */
void pxi_sx_flat_tetra(sx_simplex *s);

static inline px_vec3 sx_point_of(const sx_simplex *s) {
    px_vec3 v = {0, 0, 0};
    for (int k = 0; k < s->n; ++k) v = pxi_madd(v, s->p[k].w, s->lam[k]);
    return v;
}

/* Is the vertex pair (ia, ib) already a point of the simplex? */
static inline int sx_has(const sx_simplex *s, uint32_t ia, uint32_t ib) {
    int dup = 0;
    for (int m = 0; m < s->n; ++m) dup |= s->p[m].ia == ia && s->p[m].ib == ib;
    return dup;
}

/* Index of the point of largest weight. */
static inline int sx_heaviest(const sx_simplex *s) {
    int big = 0;
    for (int m = 1; m < s->n; ++m)
        if (s->lam[m] > s->lam[big]) big = m;
    return big;
}

/* Witness points of a simplex of vertex pairs: its weights applied to A's
 * and B's vertices (each in its own body frame); the ids when not NULL. */
static inline void sx_witness(const sx_simplex *s, const px_convex *a, const px_convex *b, px_vec3 *pa,
                              px_vec3 *pb, uint32_t *ia, uint32_t *ib) {
    px_vec3 x = {0, 0, 0}, y = {0, 0, 0};
    for (int m = 0; m < s->n; ++m) {
        x = pxi_madd(x, a->v[s->p[m].ia], s->lam[m]);
        y = pxi_madd(y, b->v[s->p[m].ib], s->lam[m]);
        if (ia) ia[m] = s->p[m].ia;
        if (ib) ib[m] = s->p[m].ib;
    }
    *pa = x;
    *pb = y;
}

#endif
