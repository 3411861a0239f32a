/* Features of a polytope: validity, the smallest feature holding a set of
 * vertices, and how far a point lies outside a face (shared by every
 * method). */
#include "narrow/feature.h"

#include <math.h>

#include "math/vec3.h"

px_feature pxi_feature_of_vertices(const px_convex *c, const uint32_t *ids, int n, const px_vec3 *p) {
    px_feature f = {PX_FEATURE_VERTEX, ids[0], 0};
    uint32_t u[4] = {ids[0], ids[0], ids[0], ids[0]};
    int m = 0;
    for (int k = 0; k < n; ++k) {
        int seen = 0;
        for (int j = 0; j < m; ++j) seen |= u[j] == ids[k];
        if (!seen) u[m++] = ids[k];
    }
    if (m == 1) return f;
    uint32_t v = u[0];
    if (m == 2) /* the edge joining them, before any face holding both */
        for (uint32_t k = c->v_first[v]; k < c->v_first[v + 1]; ++k)
            if (c->v_adj[k] == u[1]) {
                f.type = PX_FEATURE_EDGE;
                f.index = c->v_edges[k];
                return f;
            }
    for (uint32_t k = c->v_first[v]; k < c->v_first[v + 1]; ++k) {
        const pxi_edge *e = &c->e[c->v_edges[k]];
        /* A face holding all of them is a face of an edge incident to v. */
        uint32_t faces[2] = {e->left, e->right};
        for (int s = 0; s < 2; ++s) {
            const pxi_face *F = &c->f[faces[s]];
            int all = 1;
            for (int j = 1; j < m && all; ++j) {
                int in = 0;
                for (uint32_t q = 0; q < F->count && !in; ++q) in = c->f_verts[F->first + q] == u[j];
                all = in;
            }
            if (all) {
                f.type = PX_FEATURE_FACE;
                f.index = faces[s];
                return f;
            }
        }
    }
    if (!p) return f;
    /* On no common face: the vertices lie on faces within rounding of
     * coplanar. The witness p then lies on one of the faces around them:
     * the one whose polygon it is least outside of. */
    double best = INFINITY;
    for (int j = 0; j < m; ++j)
        for (uint32_t k = c->v_first[u[j]]; k < c->v_first[u[j] + 1]; ++k) {
            const pxi_edge *e = &c->e[c->v_edges[k]];
            uint32_t faces[2] = {e->left, e->right};
            for (int s = 0; s < 2; ++s) {
                double out = pxi_face_outside(c, faces[s], *p);
                if (out < best) {
                    best = out;
                    f.type = PX_FEATURE_FACE;
                    f.index = faces[s];
                }
            }
        }
    return f;
}

px_vec3 pxi_feature_normal(const px_convex *a, const px_convex *b, const px_pose *t_ab, px_feature fa,
                           px_feature fb, px_vec3 approx) {
    px_vec3 n = approx;
    if (fb.type == PX_FEATURE_FACE && fb.index < b->nf) {
        n = pxi_neg(b->f[fb.index].n); /* B's outward normal points from B to A */
    } else if (fa.type == PX_FEATURE_FACE && fa.index < a->nf) {
        n = pxi_rot(t_ab->r, a->f[fa.index].n);
    } else if (fa.type == PX_FEATURE_EDGE && fb.type == PX_FEATURE_EDGE && fa.index < a->ne &&
               fb.index < b->ne) {
        px_vec3 c = pxi_cross(pxi_rot(t_ab->r, a->e[fa.index].u), b->e[fb.index].u);
        if (pxi_len(c) > 1e-6) n = c; /* parallel edges define no normal */
    }
    n = pxi_unit_safe(n);
    return pxi_dot(n, approx) < 0.0 ? pxi_neg(n) : n;
}
