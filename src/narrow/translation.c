/* Collision translation (seed 002's query): the least tau such that A
 * translated by tau * d touches B.
 *
 * Sources: G. van den Bergen, "Ray casting against general convex objects
 * with application to continuous collision detection", 2004 (GJK ray cast;
 * also his book "Collision Detection in Interactive 3D Environments", §4.3.5);
 * the query and its incremental use are seed 002 (shared/seeds/002,
 * "collision translation", with a warm start from the previous solution). We use the ray cast rather than
 * seed 002's planar sections: it needs only support queries, which the polytope already answers in O(1)
 * amortised with the direction table and hill climbing, and it warm starts naturally from the previous
 * contact plane and simplex.
 *
 * The reduction. A + tau d meets B exactly when tau d lies in M = B - A
 * (points b - a). M is convex, so the taus form an interval, and the answer
 * is where the line {tau d} enters M. The ray starts at s = tau0 d, behind
 * M (tau0 below every m . d / d . d), and advances only to support planes
 * of M that separate the current point x from M: every tau passed over is
 * proved collision-free. It stops when x lies in the hull of support points
 * it keeps (a simplex of M), i.e. on M's boundary. If the line misses M,
 * the ray reaches a separating plane parallel to d; then a GJK on M
 * projected along d gives the witness: the plane through both bodies'
 * closest points, parallel to d, separates A + tau d from B for every tau.
 *
 * Precision: the final tau is recomputed from the plane of the final
 * simplex (tau = n.p0 / n.d), not accumulated from the start point, so it
 * does not inherit the rounding of tau0's offset.
 *
 * Frames: B's frame; d is given there, scaled to max-norm 1 by the caller.
 * Points of M are scaled by a power of two k (pair size about 1), as in GJK.
 */
#include <float.h>
#include <math.h>
#include <string.h>

#include "convex/convex.h"
#include "math/vec3.h"
#include "narrow/narrow.h"
#include "narrow/simplex.h"

typedef struct tr_ctx {
    const px_convex *a, *b;
    const px_pose *t;
    double k;
    uint32_t start_a, start_b; /* climb starts (UINT32_MAX: direction table) */
} tr_ctx;

/* Point of M for the pair (ia, ib): b - T a, scaled. */
static px_vec3 tr_m(const tr_ctx *c, uint32_t ia, uint32_t ib) {
    return pxi_scale(pxi_sub(c->b->v[ib], pxi_xform(c->t, c->a->v[ia])), c->k);
}

/* Support of M along u: B's vertex extreme along u, A's along -u. */
static sx_point tr_support(tr_ctx *c, px_vec3 u) {
    sx_point p;
    p.ib = pxi_support(c->b, u, c->start_b);
    p.ia = pxi_support(c->a, pxi_rot_t(c->t->r, pxi_neg(u)), c->start_a);
    /* Only the first support of a warm query climbs from the cached
     * vertices; later directions jump, and the direction table is the
     * cheaper start for them. */
    c->start_a = c->start_b = UINT32_MAX;
    p.w = tr_m(c, p.ia, p.ib);
    return p;
}

/* Closest point to the origin of the hull of { x - m_i }: fills s's
 * weights, keeps the points that carry weight, returns the point (v) and
 * 1 when x is inside a tetrahedron of the m_i. */
static int tr_solve(sx_simplex *s, px_vec3 x, const px_vec3 *m, px_vec3 *v) {
    for (int i = 0; i < s->n; ++i) s->p[i].w = pxi_sub(x, m[i]);
    int inside = 0;
    switch (s->n) {
    case 1: s->lam[0] = 1.0; break;
    case 2: sx_closest_segment(s); break;
    case 3: sx_closest_triangle(s); break;
    default: {
        sx_simplex t = *s;
        if (sx_closest_tetra(&t) && t.margin > 0.0) {
            *s = t;
            inside = 1;
        } else {
            sx_closest_flat_tetra(s);
        }
    }
    }
    *v = inside ? pxi_v(0, 0, 0) : sx_point_of(s);
    return inside;
}

/* The points m_i of the simplex (recomputed: s->p[i].w holds x - m_i). */
static void tr_points(const tr_ctx *c, const sx_simplex *s, px_vec3 *m) {
    for (int i = 0; i < s->n; ++i) m[i] = tr_m(c, s->p[i].ia, s->p[i].ib);
}

/* No hit: GJK on M projected onto the plane orthogonal to d. Support
 * directions stay in that plane, so M's support is the projection's. The
 * closest point v of the projection to the origin gives the separating
 * normal v / |v| (from A to B) and the gap |v|. */
static void tr_miss(tr_ctx *c, px_vec3 d, pxi_translation *out) {
    double dd = pxi_dot(d, d);
    sx_simplex s;
    s.n = 0;
    s.margin = 0.0;
    px_vec3 u = pxi_sub(c->b->center, pxi_xform(c->t, c->a->center));
    u = pxi_madd(u, d, -pxi_dot(u, d) / dd);
    if (!(pxi_len2(u) > 0.0)) {
        px_vec3 e = fabs(d.x) < 0.5 ? pxi_v(1, 0, 0) : pxi_v(0, 1, 0);
        u = pxi_cross(d, e);
    }
    /* v: current closest point of the projected simplex; start from the
     * support minimising u (the projection's point nearest along -u). */
    px_vec3 v = u;
    double vv = INFINITY;
    uint32_t it = 0;
    for (; it < 128; ++it) {
        sx_point w = tr_support(c, pxi_neg(v));
        w.w = pxi_madd(w.w, d, -pxi_dot(w.w, d) / dd);
        if (s.n > 0) {
            double gap = vv - pxi_dot(v, w.w);
            if (!(gap > 1e-24 * vv)) break;
            if (sx_has(&s, w.ia, w.ib)) break;
        }
        sx_simplex prev = s;
        s.lam[s.n] = 0.0;
        s.p[s.n++] = w;
        if (s.n == 1) s.lam[0] = 1.0;
        if (s.n == 2) sx_closest_segment(&s);
        if (s.n == 3) sx_closest_triangle(&s);
        if (s.n == 4) sx_closest_flat_tetra(&s); /* coplanar points: never a real tetrahedron */
        px_vec3 nv = sx_point_of(&s);
        double nvv = pxi_len2(nv);
        if (!(nvv < vv)) {
            if (prev.n > 0) s = prev;
            break;
        }
        v = nv;
        vv = nvv;
        if (!(vv > 0.0)) break;
    }
    out->iterations += it + 1;
    double len = sqrt(vv);
    uint32_t ia[4], ib[4];
    sx_witness(&s, c->a, c->b, &out->pa, &out->pb, ia, ib);
    out->hit = 0;
    out->tau = 0.0;
    out->gap = len > 0.0 && isfinite(len) ? len / c->k : 0.0;
    out->normal = len > 0.0 && isfinite(len) ? pxi_scale(v, 1.0 / len) : pxi_v(0, 0, 0);
    out->fa = pxi_feature_of_vertices(c->a, ia, s.n, &out->pa);
    out->fb = pxi_feature_of_vertices(c->b, ib, s.n, &out->pb);
}

/* tau from the final simplex: the line meets the simplex's plane (3
 * points), or its closest approach to the simplex's segment or point. */
static double tr_refine(const px_vec3 *m, int n, px_vec3 d, double tau) {
    double dd = pxi_dot(d, d);
    if (n == 3) {
        px_vec3 nn = pxi_cross(pxi_sub(m[1], m[0]), pxi_sub(m[2], m[0]));
        double nd = pxi_dot(nn, d);
        if (fabs(nd) > 1e-6 * pxi_len(nn) * sqrt(dd)) return pxi_dot(nn, m[0]) / nd;
        return tau;
    }
    if (n == 1) return pxi_dot(m[0], d) / dd;
    return tau;
}

static int tr_advance(const px_convex *a, const px_convex *b, const px_pose *t_ab, px_vec3 d, double tau,
                      px_vec3 n, px_feature fa, px_feature fb, pxi_translation *out);

/* The GJK ray cast (cold, or when the warm path gives up). */
static void tr_raycast(const px_convex *a, const px_convex *b, const px_pose *t_ab, px_vec3 dir,
                       px_distance_cache *cache, pxi_translation *out) {
    tr_ctx c;
    c.a = a;
    c.b = b;
    c.t = t_ab;
    c.k = sx_pair_scale(a, b, t_ab);
    c.start_a = c.start_b = UINT32_MAX;
    px_vec3 d = dir;
    double dd = pxi_dot(d, d);

    /* Warm start: the previous contact normal and simplex. */
    sx_simplex s;
    s.n = 0;
    s.margin = 0.0;
    px_vec3 v = pxi_neg(d), mpts[4];
    int warm = cache && cache->simplex_count >= 1 && cache->simplex_count <= 3;
    for (int m = 0; warm && m < cache->simplex_count; ++m)
        warm = cache->vertex_a[m] < a->nv && cache->vertex_b[m] < b->nv;
    if (warm) {
        px_vec3 n = pxi_v(cache->direction[0], cache->direction[1], cache->direction[2]);
        if (pxi_is_finite3(n) && pxi_dot(n, d) < 0.0) v = n;
        c.start_a = cache->vertex_a[0];
        c.start_b = cache->vertex_b[0];
    }
    /* Start behind M, below every m . d: M lies in the ball of radius
     * R_A + R_B around c_B - T c_A (no support query needed). */
    px_vec3 cm = pxi_scale(pxi_sub(b->center, pxi_xform(t_ab, a->center)), c.k);
    double tau0 = (pxi_dot(cm, d) - (a->radius + b->radius) * c.k * sqrt(dd)) / dd - 0.5 / dd;
    double lambda = 0.0; /* x = (tau0 + lambda) d */
    px_vec3 x = pxi_scale(d, tau0);
    px_vec3 normal = pxi_neg(d);
    int hit = 0;
    uint32_t it = 0;
    const double eps2 = (64.0 * DBL_EPSILON) * (64.0 * DBL_EPSILON);
    uint32_t cap = sx_iteration_cap(a, b);
    int seeded = !warm, certain = 0, v_closest = 0, capped = 1;
    double y2 = 1.0;
    while (it < cap) {
        ++it;
        sx_point p = tr_support(&c, v);
        px_vec3 w = pxi_sub(x, p.w);
        double vw = pxi_dot(v, w);
        /* A plane separates only if v.w clears v's rounding (an absolute
         * error of about eps max|x - m|): near contact between nearly
         * coplanar facets, |v| is 1e-10 and a noisy plane would push the
         * ray past the entry point. */
        int advanced = vw > 16.0 * DBL_EPSILON * sqrt(y2) * pxi_len(w);
        if (advanced) {
            double vr = pxi_dot(v, d);
            if (!(vr < 0.0)) break; /* the line misses M */
            lambda -= vw / vr;
            x = pxi_scale(d, tau0 + lambda);
            normal = v;
        }
        /* Warm: after the first advance (onto the previous contact plane),
         * bring back the previous simplex; it is made of points of M, so the
         * ray's invariants hold whatever the pose change was. */
        if (!seeded) {
            seeded = 1;
            for (int m = 0; m < cache->simplex_count; ++m) {
                s.p[s.n].ia = cache->vertex_a[m];
                s.p[s.n].ib = cache->vertex_b[m];
                s.lam[s.n++] = 0.0;
            }
        }
        int dup = sx_has(&s, p.ia, p.ib);
        if (!dup && s.n < 4) {
            s.p[s.n].ia = p.ia;
            s.p[s.n].ib = p.ib;
            s.lam[s.n++] = 0.0;
        }
        tr_points(&c, &s, mpts);
        px_vec3 nv;
        int inside = tr_solve(&s, x, mpts, &nv);
        double vv = pxi_len2(nv);
        y2 = 1.0;
        for (int m = 0; m < s.n; ++m)
            if (pxi_len2(s.p[m].w) > y2) y2 = pxi_len2(s.p[m].w);
        /* van den Bergen's test: x within a relative 64 eps of the simplex
         * (the |x - m| are at least the pair's size, 1 here). */
        if (inside || !(vv > eps2 * y2)) {
            hit = 1;
            certain = 1;
            break;
        }
        /* The two stall exits below hold only once v is the closest point
         * of a solved simplex (not the first direction, nor a warm hint). */
        if (v_closest && !advanced && !(vv < pxi_len2(v))) {
            /* x did not move and the simplex got no closer: the rounding
             * floor, with x on M's boundary. */
            hit = 1;
            break;
        }
        if (v_closest && dup && !advanced) {
            /* A support point already kept, and no separating plane: v.w >=
             * |v|^2 would hold for it in exact arithmetic, so |v| is
             * rounding. x is on M's boundary. */
            hit = 1;
            break;
        }
        v = nv;
        v_closest = 1;
    }
    if (hit || it < cap) capped = 0;
    if (warm && (capped || (hit && !certain))) {
        /* A warm run that did not converge cleanly (a stale hint can mislead
         * the stall tests): the answer comes from a cold run instead. */
        cache->simplex_count = 0;
        memset(out, 0, sizeof *out);
        tr_raycast(a, b, t_ab, dir, NULL, out);
        out->iterations += it;
        return;
    }
    out->iterations = it;
    if (!hit) {
        tr_miss(&c, d, out);
        if (cache) cache->simplex_count = 0;
        return;
    }
    tr_points(&c, &s, mpts);
    if (!certain) {
        /* Stopped at the rounding floor, x within |v| of M but not in the
         * simplex: x is a proved lower bound, and conservative advancement
         * with Lin-Canny (exact there) finishes from it. */
        uint32_t ia[4], ib[4];
        px_vec3 pa, pb;
        sx_witness(&s, a, b, &pa, &pb, ia, ib);
        px_feature fa = pxi_feature_of_vertices(a, ia, s.n, &pa),
                   fb = pxi_feature_of_vertices(b, ib, s.n, &pb);
        double nl = pxi_len(normal);
        px_vec3 n = nl > 0.0 ? pxi_scale(normal, -1.0 / nl) : pxi_v(0, 0, 0);
        if (tr_advance(a, b, t_ab, d, (tau0 + lambda) / c.k, n, fa, fb, out)) {
            out->iterations += it;
            if (cache) {
                cache->simplex_count = (uint8_t)(s.n < 4 ? s.n : 3);
                for (int m = 0; m < cache->simplex_count; ++m) {
                    cache->vertex_a[m] = s.p[m].ia;
                    cache->vertex_b[m] = s.p[m].ib;
                }
                cache->direction[0] = -out->normal.x;
                cache->direction[1] = -out->normal.y;
                cache->direction[2] = -out->normal.z;
                cache->feature_a = out->fa;
                cache->feature_b = out->fb;
            }
            return;
        }
        out->iterations = it;
    }
    double tau = tr_refine(mpts, s.n, d, tau0 + lambda);
    /* Contact points from the final simplex's weights at x = tau d. */
    x = pxi_scale(d, tau);
    px_vec3 nv;
    tr_solve(&s, x, mpts, &nv);
    px_vec3 pa, pb;
    uint32_t ia[4], ib[4];
    sx_witness(&s, a, b, &pa, &pb, ia, ib);
    double nl = pxi_len(normal);
    out->hit = 1;
    out->tau = tau / c.k; /* M was scaled by k */
    out->pa = pa;
    out->pb = pb;
    out->normal = nl > 0.0 ? pxi_scale(normal, -1.0 / nl) : pxi_v(0, 0, 0);
    out->fa = pxi_feature_of_vertices(a, ia, s.n, &out->pa);
    out->fb = pxi_feature_of_vertices(b, ib, s.n, &out->pb);
    if (cache) {
        cache->simplex_count = (uint8_t)(s.n < 4 ? s.n : 3);
        for (int m = 0; m < cache->simplex_count; ++m) {
            cache->vertex_a[m] = s.p[m].ia;
            cache->vertex_b[m] = s.p[m].ib;
        }
        if (nl > 0.0) {
            cache->direction[0] = normal.x / nl;
            cache->direction[1] = normal.y / nl;
            cache->direction[2] = normal.z / nl;
        }
        cache->feature_a = out->fa;
        cache->feature_b = out->fb;
    }
}

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

/* Is p (face f's frame) on face f: within tol of its plane and inside its
 * polygon (edge side planes, with the same slack)? */
static int tr_on_face(const px_convex *c, uint32_t f, px_vec3 p, double tol) {
    const pxi_face *F = &c->f[f];
    if (!(fabs(pxi_dot(F->n, p) - F->d) <= tol)) return 0;
    for (uint32_t q = 0; q < F->count; ++q) {
        const pxi_edge *e = &c->e[c->f_edges[F->first + q]];
        px_vec3 side = e->left == f ? e->wl : e->wr;
        if (pxi_dot(pxi_sub(p, c->v[e->tail]), side) < -tol) return 0;
    }
    return 1;
}

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
        if (!tr_on_face(b, fb.index, p, tol)) return 0;
        *pa = a->v[fa.index];
        *pb = p;
        return 1;
    }
    if (fa.type == PX_FEATURE_FACE && fb.type == PX_FEATURE_VERTEX && fa.index < a->nf && fb.index < b->nv) {
        px_vec3 p = pxi_xform_inv(tt, b->v[fb.index]);
        if (!tr_on_face(a, fa.index, p, tol)) return 0;
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
        if (!(pxi_len(pxi_sub(x, y)) <= tol)) return 0;
        *pa = pxi_xform_inv(tt, x);
        *pb = y;
        return 1;
    }
    return 0;
}
static int tr_warm_lc(const px_convex *a, const px_convex *b, const px_pose *t_ab, px_vec3 d,
                      px_distance_cache *cache, pxi_translation *out) {
    px_vec3 nu = pxi_v(cache->direction[0], cache->direction[1], cache->direction[2]);
    double nl = pxi_len(nu);
    if (!(nl > 0.0) || !isfinite(nl)) return 0;
    nu = pxi_scale(nu, 1.0 / nl);
    double nud = pxi_dot(nu, d);
    if (!(nud < -1e-3 * sqrt(pxi_dot(d, d)))) return 0; /* grazing: the bound is useless */
    uint32_t ib = pxi_support(b, nu, cache->vertex_b[0]);
    uint32_t ia = pxi_support(a, pxi_rot_t(t_ab->r, pxi_neg(nu)), cache->vertex_a[0]);
    double h = pxi_dot(nu, pxi_sub(b->v[ib], pxi_xform(t_ab, a->v[ia])));
    double tau = h / nud;
    if (!tr_advance(a, b, t_ab, d, tau, pxi_neg(nu), cache->feature_a, cache->feature_b, out)) return 0;
    out->iterations += 1;
    cache->feature_a = out->fa;
    cache->feature_b = out->fb;
    cache->direction[0] = -out->normal.x;
    cache->direction[1] = -out->normal.y;
    cache->direction[2] = -out->normal.z;
    cache->vertex_a[0] = ia;
    cache->vertex_b[0] = ib;
    if (cache->simplex_count == 0) cache->simplex_count = 1;
    return 1;
}

/* Conservative advancement from tau, a proved lower bound (A + tau d does
 * not overlap B): the closest points give a separating plane, and moving A
 * to it keeps tau a lower bound; n is the normal to report if the first
 * query already touches, (fa, fb) the features Lin-Canny starts from.
 * Returns 0 when it cannot conclude (a normal turning away from the motion,
 * or slow convergence on a curved part of M). */
static int tr_advance(const px_convex *a, const px_convex *b, const px_pose *t_ab, px_vec3 d, double tau,
                      px_vec3 n, px_feature fa, px_feature fb, pxi_translation *out) {
    double span = a->scale + b->scale + pxi_max_abs(t_ab->t);
    double tol = 64.0 * DBL_EPSILON * span;
    px_distance_cache lc;
    memset(&lc, 0, sizeof lc);
    lc.feature_a = fa;
    lc.feature_b = fb;
    pxi_answer ans;
    uint32_t steps = 0;
    for (;;) {
        if (steps >= TR_LC_STEPS) return 0;
        px_pose tt = *t_ab;
        tt.t = pxi_madd(tt.t, d, tau);
        pxi_lin_canny(a, b, &tt, &lc, &ans);
        ++steps;
        if (ans.intersecting) break;
        px_vec3 gap = pxi_sub(ans.pb, pxi_xform(&tt, ans.pa));
        double gl = pxi_len(gap);
        if (!(gl > 0.0)) break;
        n = pxi_scale(gap, 1.0 / gl);
        double nd = pxi_dot(n, d);
        if (!(nd > 1e-3 * sqrt(pxi_dot(d, d)))) return 0; /* may miss: the ray cast decides */
        tau += ans.distance / nd;
        if (!(ans.distance > tol)) break; /* within rounding: that last step closes it */
        /* The same features touching at the new tau settle it without
         * another walk (exact for the facet pairs of M). */
        tt.t = pxi_madd(t_ab->t, d, tau);
        px_vec3 ca, cb;
        if (tr_features_touch(a, b, &tt, ans.fa, ans.fb, 16.0 * tol, &ca, &cb)) {
            ans.pa = ca;
            ans.pb = cb;
            break;
        }
    }
    out->hit = 1;
    out->tau = tau;
    out->pa = ans.pa;
    out->pb = ans.pb;
    out->normal = n;
    out->fa = ans.fa;
    out->fb = ans.fb;
    out->iterations = steps;
    return 1;
}

void pxi_translation_query(const px_convex *a, const px_convex *b, const px_pose *t_ab, px_vec3 dir,
                           px_distance_cache *cache, pxi_translation *out) {
    memset(out, 0, sizeof *out);
    int warm = cache && cache->simplex_count >= 1 && cache->simplex_count <= 3 &&
               cache->vertex_a[0] < a->nv && cache->vertex_b[0] < b->nv &&
               cache->feature_a.type >= PX_FEATURE_VERTEX && cache->feature_b.type >= PX_FEATURE_VERTEX;
    if (warm && tr_warm_lc(a, b, t_ab, dir, cache, out)) return;
    memset(out, 0, sizeof *out);
    tr_raycast(a, b, t_ab, dir, cache, out);
}
