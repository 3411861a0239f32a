/* Collision translation by conservative advancement with Lin-Canny: the
 * tracked (warm) path of the translation query, and the finish of a ray cast
 * that stopped at the rounding floor.
 *
 * Sources: seed 002 (shared/seeds/002, "collision translation", with a warm
 * start from the previous solution); conservative advancement as in B.
 * Mirtich, "Impulse-based dynamic simulation of rigid body systems", PhD
 * thesis, Berkeley 1996, ch. 2, with the Lin-Canny walk (lin_canny.c)
 * answering each distance. The only method this file calls is Lin-Canny.
 *
 * Frames: B's frame; d is given there. */
#include <float.h>
#include <math.h>
#include <string.h>

#include "convex/convex.h"
#include "math/vec3.h"
#include "narrow/closest.h"
#include "narrow/feature.h"
#include "narrow/narrow.h"
#include "narrow/tolerance.h"

/* Warm path: conservative advancement with Lin-Canny (seed 002's
 * incremental idea, with the distance walk doing the local search).
 *
 * 1. A lower bound: for any unit n with n.d < 0, the line enters the
 *    half-space {x : n.x <= h_M(n)}, which contains M, at
 *    tau = h_M(n) / (n.d) <= the answer. With n the previous contact normal
 *    (outward from M) this lands on or next to the new contact: M's support
 *    along n is two climbs from the cached vertices.
 * 2. From there, the closest points of A + tau d and B give a separating
 *    plane; moving A to it (tau += dist / (n.d), n from A to B) keeps tau a
 *    lower bound. When the closest features are a vertex-face or edge-edge
 *    pair (a facet of M) this step is exact, so small moves need one or two
 *    distance queries, each a warm walk of a few steps.
 * Returns 0 when it cannot conclude (no normal towards the motion, or slow
 * convergence on a curved part of M); the ray cast then answers. */
#define TR_LC_STEPS 12

/* After an advancement step: do the last closest features touch at the new
 * pose tt (A -> B)? For the pairs that make a facet of M (vertex-face,
 * face-vertex, edge-edge) this is a closed-form check, and a touching pair
 * proves contact; tau being a lower bound, it is the first contact. Sets
 * the contact points (pa in A's frame, pb in B's). 0: not known, ask
 * Lin-Canny. */
static int tr_features_touch(const px_convex *a, const px_convex *b, const px_pose *tt, px_feature fa,
                             px_feature fb, double tol, px_vec3 *pa, px_vec3 *pb) {
    if (fa.type == PX_FEATURE_VERTEX && fb.type == PX_FEATURE_FACE && fa.index < a->nv && fb.index < b->nf) {
        px_vec3 p = pxi_xform(tt, a->v[fa.index]);
        if (!(pxi_face_outside(b, fb.index, p) <= tol)) return 0;
        *pa = a->v[fa.index];
        *pb = p;
        return 1;
    }
    if (fa.type == PX_FEATURE_FACE && fb.type == PX_FEATURE_VERTEX && fa.index < a->nf && fb.index < b->nv) {
        px_vec3 p = pxi_xform_inv(tt, b->v[fb.index]);
        if (!(pxi_face_outside(a, fa.index, p) <= tol)) return 0;
        *pa = p;
        *pb = b->v[fb.index];
        return 1;
    }
    if (fa.type == PX_FEATURE_EDGE && fb.type == PX_FEATURE_EDGE && fa.index < a->ne && fb.index < b->ne) {
        const pxi_edge *ea = &a->e[fa.index], *eb = &b->e[fb.index];
        px_vec3 p0 = pxi_xform(tt, a->v[ea->tail]), p1 = pxi_xform(tt, a->v[ea->head]);
        px_vec3 q0 = b->v[eb->tail], q1 = b->v[eb->head];
        double u, w;
        pxi_segment_closest(p0, p1, q0, q1, &u, &w);
        px_vec3 x = pxi_madd(p0, pxi_sub(p1, p0), u), y = pxi_madd(q0, pxi_sub(q1, q0), w);
        if (!(pxi_len_safe(pxi_sub(x, y)) <= tol)) return 0;
        *pa = pxi_xform_inv(tt, x);
        *pb = y;
        return 1;
    }
    return 0;
}
pxi_outcome pxi_advance_warm(const px_convex *a, const px_convex *b, const px_pose *t_ab, px_vec3 d,
                             px_pair_cache *cache, pxi_translation *out) {
    px_vec3 nu = pxi_v(cache->direction[0], cache->direction[1], cache->direction[2]);
    double nl = pxi_len(nu);
    if (!(nl > 0.0) || !isfinite(nl)) return PXI_UNPROVEN;
    nu = pxi_scale(nu, 1.0 / nl);
    double nud = pxi_dot(nu, d);
    if (!(nud < -1e-3 * sqrt(pxi_dot(d, d)))) return PXI_UNPROVEN; /* grazing: the bound is useless */
    uint32_t ib = pxi_support(b, nu, cache->vertex_b[0]);
    uint32_t ia = pxi_support(a, pxi_rot_t(t_ab->r, pxi_neg(nu)), cache->vertex_a[0]);
    double h = pxi_dot(nu, pxi_sub(b->v[ib], pxi_xform(t_ab, a->v[ia])));
    double tau = h / nud;
    if (pxi_advance(a, b, t_ab, d, tau, pxi_neg(nu), cache->feature_a, cache->feature_b, out) != PXI_DONE)
        return PXI_UNPROVEN;
    out->iterations += 1;
    cache->feature_a = out->fa;
    cache->feature_b = out->fb;
    cache->direction[0] = -out->normal.x;
    cache->direction[1] = -out->normal.y;
    cache->direction[2] = -out->normal.z;
    cache->vertex_a[0] = ia;
    cache->vertex_b[0] = ib;
    if (cache->simplex_count == 0) cache->simplex_count = 1;
    return PXI_DONE;
}

pxi_outcome pxi_advance(const px_convex *a, const px_convex *b, const px_pose *t_ab, px_vec3 d, double tau,
                        px_vec3 n, px_feature fa, px_feature fb, pxi_translation *out) {
    memset(out, 0, sizeof *out);
    double tol = PXI_SUPPORT_NOISE * pxi_pair_span(a, b, t_ab);
    pxi_lc_start start;
    memset(&start, 0, sizeof start);
    start.fa = fa;
    start.fb = fb;
    pxi_answer ans;
    uint32_t steps = 0;
    for (;;) {
        if (steps >= TR_LC_STEPS) return PXI_UNPROVEN;
        px_pose tt = *t_ab;
        tt.t = pxi_madd(tt.t, d, tau);
        pxi_lin_canny(a, b, &tt, &start, &ans);
        ++steps;
        if (ans.outcome != PXI_DONE) return PXI_UNPROVEN; /* the walk cycles: the ray cast decides */
        start.fa = ans.fa;
        start.fb = ans.fb;
        if (ans.intersecting) break;
        px_vec3 gap = pxi_sub(ans.pb, pxi_xform(&tt, ans.pa));
        double gl = pxi_len_safe(gap);
        if (!(gl > 0.0)) break;
        px_vec3 ng = pxi_len_ok(gl) ? pxi_scale(gap, 1.0 / gl) : pxi_unit_safe(gap);
        double nd = pxi_dot(ng, d);
        if (!(nd > 1e-3 * sqrt(pxi_dot(d, d)))) return PXI_UNPROVEN; /* may miss: the ray cast decides */
        tau += ans.distance / nd;
        /* Within rounding: that last step closes it. The gap's direction is
         * then noise (1e-13 apart, it turned a cube's contact normal by
         * 1e-3): the last normal stands (the separating plane of the step
         * that brought A here, or the ray cast's), refined by the features
         * below. */
        if (!(ans.distance > tol)) break;
        n = ng;
        /* The same features touching at the new tau settle it without
         * another walk (exact for the facet pairs of M). */
        tt.t = pxi_madd(t_ab->t, d, tau);
        px_vec3 ca, cb;
        if (tr_features_touch(a, b, &tt, ans.fa, ans.fb, tol, &ca, &cb)) {
            ans.pa = ca;
            ans.pb = cb;
            break;
        }
    }
    out->hit = 1;
    out->tau = tau;
    out->pa = ans.pa;
    out->pb = ans.pb;
    /* A facet of M (vertex-face, edge-edge) in contact has its own normal,
     * exact; other contacts keep the separating plane's. */
    out->normal = ans.intersecting ? n : pxi_feature_normal(a, b, t_ab, ans.fa, ans.fb, n);
    out->fa = ans.fa;
    out->fb = ans.fb;
    out->iterations = steps;
    return PXI_DONE;
}
