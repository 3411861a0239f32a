/* The public query entry points: argument checks, the relative transform,
 * dispatch to a method, and the conversion of body-frame answers to world
 * results. Every method answers through the same pxi_answer, so the result
 * conventions (docs/methods.md) are written once, here. */
#include <math.h>
#include <string.h>

#include "convex/convex.h"
#include "math/vec3.h"
#include "narrow/narrow.h"

/* Checks the arguments every query shares and computes T_AB. Poses far
 * apart (translations of opposite sign near 1e308) can overflow T_AB's
 * translation even though each pose is finite: PX_ERR_NON_FINITE. */
static px_status check_pair(const px_convex *a, const px_pose *pose_a, const px_convex *b,
                            const px_pose *pose_b, px_pose *t_ab) {
    if (!a || !b || !pose_a || !pose_b) return PX_ERR_INVALID_ARGUMENT;
    px_status st = px_pose_check(pose_a, NULL);
    if (st == PX_OK) st = px_pose_check(pose_b, NULL);
    if (st != PX_OK) return st;
    /* Checked before the rotation: inf times a zero matrix entry is NaN. */
    if (!pxi_is_finite3(pxi_sub(pose_a->t, pose_b->t))) return PX_ERR_NON_FINITE;
    *t_ab = pxi_relative(pose_a, pose_b);
    return pxi_is_finite3(t_ab->t) ? PX_OK : PX_ERR_NON_FINITE;
}

/* How far p is from face f: its distance to the face plane, or more when
 * it lies outside the polygon (the largest violation of the face's edge
 * side planes). */
static double outside_face(const px_convex *c, uint32_t f, px_vec3 p) {
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

px_feature pxi_feature_of_vertices(const px_convex *c, const uint32_t *ids, int n, const px_vec3 *p) {
    px_feature f = {PX_FEATURE_VERTEX, ids[0]};
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
                double out = outside_face(c, faces[s], *p);
                if (out < best) {
                    best = out;
                    f.type = PX_FEATURE_FACE;
                    f.index = faces[s];
                }
            }
        }
    return f;
}

static px_vec3 unit_or_zero(px_vec3 v) {
    double l = pxi_len(v);
    return l > 0.0 && isfinite(l) ? pxi_scale(v, 1.0 / l) : pxi_v(0, 0, 0);
}

px_status px_distance_ex(const px_convex *a, const px_pose *pose_a, const px_convex *b, const px_pose *pose_b,
                         const px_query_options *options, px_distance_cache *cache,
                         px_distance_result *result) {
    if (result) memset(result, 0, sizeof *result);
    if (!result) return PX_ERR_INVALID_ARGUMENT;
    uint32_t method = options ? options->method : PX_METHOD_LIN_CANNY;
    uint32_t flags = options ? options->flags : 0u;
    if (method > PX_METHOD_HYBRID || (flags & ~PX_QUERY_SIGNED)) return PX_ERR_INVALID_ARGUMENT;
    px_pose t_ab;
    px_status st = check_pair(a, pose_a, b, pose_b, &t_ab);
    if (st != PX_OK) return st;
    pxi_answer ans;
    memset(&ans, 0, sizeof ans);
    pxi_simplex_pairs simplex;
    simplex.n = 0;
    switch (method) {
    case PX_METHOD_GJK: pxi_gjk_distance(a, b, &t_ab, cache, &ans, &simplex); break;
    case PX_METHOD_HYBRID: pxi_hybrid(a, b, &t_ab, cache, &ans); break;
    default: pxi_lin_canny(a, b, &t_ab, cache, &ans); break;
    }
    result->distance = ans.distance;
    result->signed_distance = ans.distance;
    result->intersecting = ans.intersecting;
    result->feature_a = ans.fa;
    result->feature_b = ans.fb;
    result->iterations = ans.iterations;
    result->fallbacks = ans.fallbacks;
    result->point_a = pxi_xform(pose_a, ans.pa);
    if (!ans.intersecting) {
        result->point_b = pxi_xform(pose_b, ans.pb);
        result->normal = unit_or_zero(pxi_sub(result->point_b, result->point_a));
        return PX_OK;
    }
    /* Intersecting: one common point, reported once (the two frames' copies
     * differ by rounding, or by the noise band of contact detection). */
    result->point_b = result->point_a;
    result->distance = 0.0;
    result->signed_distance = 0.0;
    if (!(flags & PX_QUERY_SIGNED)) return PX_OK;
    pxi_penetration pen;
    pxi_epa(a, b, &t_ab, method == PX_METHOD_GJK ? &simplex : NULL, &pen);
    if (pen.flat) return PX_OK; /* A - B flat within rounding: touching, as reported */
    result->signed_distance = -pen.depth;
    result->point_a = pxi_xform(pose_a, pen.pa);
    result->point_b = pxi_xform(pose_b, pen.pb);
    result->normal = pen.depth > 0.0 ? pxi_rot(pose_b->r, pen.normal) : pxi_v(0, 0, 0);
    result->feature_a = pen.fa;
    result->feature_b = pen.fb;
    result->iterations += pen.iterations;
    result->fallbacks += (uint32_t)pen.fallback;
    return PX_OK;
}

px_status px_distance(const px_convex *a, const px_pose *pose_a, const px_convex *b, const px_pose *pose_b,
                      px_distance_cache *cache, px_distance_result *result) {
    return px_distance_ex(a, pose_a, b, pose_b, NULL, cache, result);
}

px_status px_intersect(const px_convex *a, const px_pose *pose_a, const px_convex *b, const px_pose *pose_b,
                       px_distance_cache *cache, int *intersecting) {
    if (intersecting) *intersecting = 0;
    if (!intersecting) return PX_ERR_INVALID_ARGUMENT;
    px_pose t_ab;
    px_status st = check_pair(a, pose_a, b, pose_b, &t_ab);
    if (st != PX_OK) return st;
    uint32_t it = 0;
    *intersecting = pxi_gjk_intersect(a, b, &t_ab, cache, &it);
    return PX_OK;
}

px_status px_translation(const px_convex *a, const px_pose *pose_a, const px_convex *b, const px_pose *pose_b,
                         px_vec3 direction, px_distance_cache *cache, px_translation_result *result) {
    if (result) memset(result, 0, sizeof *result);
    if (!result) return PX_ERR_INVALID_ARGUMENT;
    if (!pxi_is_finite3(direction)) return PX_ERR_NON_FINITE;
    if (!(pxi_max_abs(direction) > 0.0)) return PX_ERR_INVALID_ARGUMENT;
    px_pose t_ab;
    px_status st = check_pair(a, pose_a, b, pose_b, &t_ab);
    if (st != PX_OK) return st;
    /* Scale the direction by 2^-e to max-norm in [1, 2) (exact, also for
     * subnormal lengths), so that its squared length can neither overflow
     * nor underflow; tau is rescaled at the end. */
    int e = ilogb(pxi_max_abs(direction));
    px_vec3 ds = pxi_v(ldexp(direction.x, -e), ldexp(direction.y, -e), ldexp(direction.z, -e));
    px_vec3 dir_b = pxi_rot_t(pose_b->r, ds);
    pxi_translation tr;
    pxi_translation_query(a, b, &t_ab, dir_b, cache, &tr);
    double tau = ldexp(tr.tau, -e);
    if (!isfinite(tau)) return PX_ERR_NON_FINITE; /* a direction so short that tau overflows */
    result->hit = tr.hit;
    result->tau = tau;
    result->iterations = tr.iterations;
    result->feature_a = tr.fa;
    result->feature_b = tr.fb;
    result->normal = pxi_rot(pose_b->r, tr.normal);
    result->gap = tr.gap;
    px_vec3 pa = pxi_xform(pose_a, tr.pa);
    if (tr.hit) pa = pxi_madd(pa, ds, tr.tau); /* tau * direction, without overflow */
    result->point_a = pa;
    result->point_b = pxi_xform(pose_b, tr.pb);
    return PX_OK;
}
