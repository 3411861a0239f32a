/* Feature lookup on a polytope (internal). */
#ifndef PXI_FEATURE_H
#define PXI_FEATURE_H

#include <stdint.h>

#include <math.h>

#include "convex/convex.h"
#include "math/vec3.h"

/* 1 when f names a vertex, edge or face of c (type and index in range). */
static inline int pxi_feature_valid(const px_convex *c, px_feature f) {
    switch (f.type) {
    case PX_FEATURE_VERTEX: return f.index < c->nv;
    case PX_FEATURE_EDGE: return f.index < c->ne;
    case PX_FEATURE_FACE: return f.index < c->nf;
    default: return 0;
    }
}

/* How far p (c's frame) is from face f: its distance to the face plane, or
 * more when it lies outside the polygon (the largest violation of the
 * face's edge side planes). NaN for a NaN point. */
static inline double pxi_face_outside(const px_convex *c, uint32_t f, px_vec3 p) {
    const pxi_face *F = &c->f[f];
    double worst = fabs(pxi_dot(F->n, p) - F->d);
    for (uint32_t q = 0; q < F->count; ++q) {
        const pxi_edge *e = &c->e[c->f_edges[F->first + q]];
        px_vec3 side = e->left == f ? e->wl : e->wr;
        double out = -pxi_dot(pxi_sub(p, c->v[e->tail]), side);
        if (out > worst) worst = out;
    }
    return worst;
}

/* The smallest feature of `c` holding the given vertices (1-4 ids, repeats
 * allowed): the vertex, the edge joining two, or a face holding all.
 * Vertices on no common face (possible only within rounding of coplanar
 * faces): the face around them whose polygon holds the witness point `p`
 * (body frame; NULL: the vertex ids[0]). */
px_feature pxi_feature_of_vertices(const px_convex *c, const uint32_t *ids, int n, const px_vec3 *p);

/* The unit contact normal of a closest feature pair (B's frame, from A to
 * B), from the features' geometry where it defines one: a face's normal
 * (vertex-face, edge-face, face-anything), the cross product of two
 * non-parallel edges; else the direction `approx` (the closest points'
 * difference, whose direction near contact is only known to eps size /
 * distance). Oriented like `approx`. T_AB maps A's frame into B's. */
px_vec3 pxi_feature_normal(const px_convex *a, const px_convex *b, const px_pose *t_ab, px_feature fa,
                           px_feature fb, px_vec3 approx);

#endif
