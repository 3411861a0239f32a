/* Collision translation by a GJK ray cast (seed 002's query): the least tau
 * such that A translated by tau * d touches B.
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
#include "math/orient.h"
#include "math/vec3.h"
#include "narrow/feature.h"
#include "narrow/narrow.h"
#include "narrow/simplex.h"
#include "narrow/tolerance.h"

typedef struct tr_ctx {
    const px_convex *a, *b;
    const px_pose *t;
    double k;
    uint32_t start_a, start_b; /* climb starts (UINT32_MAX: direction table) */
} tr_ctx;

/* Point of M for the pair (ia, ib): b - T a, scaled. */
static inline px_vec3 tr_m(const tr_ctx *c, uint32_t ia, uint32_t ib) {
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
static inline int tr_solve(sx_simplex *s, px_vec3 x, const px_vec3 *m, px_vec3 *v) {
    for (int i = 0; i < s->n; ++i) s->p[i].w = pxi_sub(x, m[i]);
    int inside = 0;
    switch (s->n) {
    case 1: s->lam[0] = 1.0; break;
    case 2: pxi_sx_segment(s); break;
    case 3: pxi_sx_triangle(s); break;
    default: {
        sx_simplex t = *s;
        if (pxi_sx_tetra(&t) && t.margin > 0.0) {
            *s = t;
            inside = 1;
        } else {
            pxi_sx_flat_tetra(s);
        }
    }
    }
    *v = inside ? pxi_v(0, 0, 0) : sx_point_of(s);
    return inside;
}

/* The points m_i of the simplex (recomputed: s->p[i].w holds x - m_i). */
static inline void tr_points(const tr_ctx *c, const sx_simplex *s, px_vec3 *m) {
    for (int i = 0; i < s->n; ++i) m[i] = tr_m(c, s->p[i].ia, s->p[i].ib);
}

/* No hit: GJK on M projected onto the plane orthogonal to d. Support
 * directions stay in that plane, so M's support is the projection's. The
 * closest point v of the projection to the origin gives the separating
 * normal v / |v| (from A to B) and the gap |v|. */
static void tr_miss(tr_ctx *c, px_vec3 d, pxi_translation *out);

void pxi_ray_miss(const px_convex *a, const px_convex *b, const px_pose *t_ab, px_vec3 dir,
                  pxi_translation *out) {
    memset(out, 0, sizeof *out);
    tr_ctx c;
    c.a = a;
    c.b = b;
    c.t = t_ab;
    c.k = pxi_pair_unit(a, b, t_ab);
    c.start_a = c.start_b = UINT32_MAX;
    tr_miss(&c, dir, out);
}

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
        if (s.n == 2) pxi_sx_segment(&s);
        if (s.n == 3) pxi_sx_triangle(&s);
        if (s.n == 4) pxi_sx_flat_tetra(&s); /* coplanar points: never a real tetrahedron */
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
    if (!(len > 0.0) || !isfinite(len)) return;
    /* The certificate: the plane's points are the bodies' own supports along
     * the normal, A's highest and B's lowest, so every vertex of A lies below
     * point_a's plane and every vertex of B above point_b's by construction,
     * and the gap is what they leave. The simplex's weighted points are not
     * enough: on thin bodies (slabs of 1e-6) the final simplex keeps vertices
     * that are not extreme along the final normal, and its plane cut B by
     * 1.6e-4. Kept only when the supports still separate. */
    px_vec3 n = out->normal; /* B's frame, from A to B */
    uint32_t sa = pxi_support(c->a, pxi_rot_t(c->t->r, n), ia[0]), sb = pxi_support(c->b, pxi_neg(n), ib[0]);
    double gap = pxi_dot(n, pxi_sub(c->b->v[sb], pxi_xform(c->t, c->a->v[sa])));
    if (!(gap > 0.0)) {
        /* The normal is known only to eps span / gap: near a graze its
         * supports no longer separate. The gap stands; the plane is left to
         * the caller to refine (query.c). */
        out->quality |= PX_QUALITY_UNPROVEN;
        return;
    }
    out->pa = c->a->v[sa];
    out->pb = c->b->v[sb];
    out->gap = gap;
    out->fa = pxi_feature_of_vertices(c->a, &sa, 1, NULL);
    out->fb = pxi_feature_of_vertices(c->b, &sb, 1, NULL);
}

/* tau from the final simplex: the line meets the simplex's plane (3
 * points), or its closest approach to the simplex's segment or point. */
static double tr_refine(const px_vec3 *m, int n, px_vec3 d, double tau) {
    double dd = pxi_dot(d, d);
    if (n == 3) {
        /* accurate for slivers (the simplex solver keeps a sliver triangle
         * whose plane holds x: plain products tilted its normal by eps over
         * the aspect, and tau by 1e-11 on a 1e-6 needle) */
        px_vec3 nn = pxi_tri_normal(m[0], m[1], m[2]);
        double nd = pxi_dot(nn, d);
        if (fabs(nd) > 1e-6 * pxi_len(nn) * sqrt(dd)) return pxi_dot(nn, m[0]) / nd;
        return tau;
    }
    if (n == 1) return pxi_dot(m[0], d) / dd;
    return tau;
}

/* The state of one ray cast: the ray x = (tau0 + lambda) d, the simplex of
 * support points of M kept so far, the current direction v (from the
 * simplex's closest point to x), and the last separating plane's normal. */
typedef struct ray {
    tr_ctx c;
    px_vec3 d;
    double dd;
    sx_simplex s;
    px_vec3 v, x, normal;
    double tau0, lambda;
    double y2; /* max |x - m|^2 over the simplex, at least 1 (scaled units) */
    uint32_t it, cap;
    const px_pair_cache *warm; /* the cache whose simplex is brought back after the first advance */
    int v_closest;             /* v is the closest point of a solved simplex (not a first guess) */
} ray;

/* What one step of the ray cast found. */
enum { RAY_GO, RAY_MISS, RAY_HIT, RAY_FLOOR };

static void ray_init(ray *r, const px_convex *a, const px_convex *b, const px_pose *t_ab, px_vec3 dir,
                     const px_pair_cache *cache) {
    r->c.a = a;
    r->c.b = b;
    r->c.t = t_ab;
    r->c.k = pxi_pair_unit(a, b, t_ab);
    r->c.start_a = r->c.start_b = UINT32_MAX;
    r->d = dir;
    r->dd = pxi_dot(dir, dir);
    r->s.n = 0;
    r->s.margin = 0.0;
    r->v = pxi_neg(dir);
    r->warm = NULL;
    int warm = cache && cache->simplex_count >= 1 && cache->simplex_count <= 3;
    for (int m = 0; warm && m < cache->simplex_count; ++m)
        warm = cache->vertex_a[m] < a->nv && cache->vertex_b[m] < b->nv;
    if (warm) {
        /* Warm start: the previous contact normal and simplex. */
        /* A unit hint (a caller's cache may hold any bits): its dot
         * products can neither overflow nor underflow. */
        px_vec3 n = pxi_unit_safe(pxi_v(cache->direction[0], cache->direction[1], cache->direction[2]));
        if (pxi_dot(n, dir) < 0.0) r->v = n;
        r->c.start_a = cache->vertex_a[0];
        r->c.start_b = cache->vertex_b[0];
        r->warm = cache;
    }
    /* Start behind M, below every m . d: M lies in the ball of radius
     * R_A + R_B around c_B - T c_A (no support query needed). */
    px_vec3 cm = pxi_scale(pxi_sub(b->center, pxi_xform(t_ab, a->center)), r->c.k);
    r->tau0 = (pxi_dot(cm, dir) - (a->radius + b->radius) * r->c.k * sqrt(r->dd)) / r->dd - 0.5 / r->dd;
    r->lambda = 0.0;
    r->x = pxi_scale(dir, r->tau0);
    r->normal = pxi_neg(dir);
    r->it = 0;
    r->cap = sx_iteration_cap(a, b);
    r->y2 = 1.0;
    r->v_closest = 0;
}

/* Advances x to the support plane of M along v when that plane separates
 * x from M. A plane separates only if v.w clears v's rounding (an absolute
 * error of about eps max|x - m|): near contact between nearly coplanar
 * facets, |v| is 1e-10 and a noisy plane would push the ray past the entry
 * point. Returns 1 when x moved, -1 when the line misses M (v turned away
 * from the motion), 0 otherwise. */
static int ray_advance(ray *r, px_vec3 p) {
    px_vec3 w = pxi_sub(r->x, p);
    double vw = pxi_dot(r->v, w);
    if (!(vw > 16.0 * DBL_EPSILON * sqrt(r->y2) * pxi_len(w))) return 0;
    double vr = pxi_dot(r->v, r->d);
    if (!(vr < 0.0)) return -1;
    r->lambda -= vw / vr;
    r->x = pxi_scale(r->d, r->tau0 + r->lambda);
    r->normal = r->v;
    return 1;
}

/* Adds the support pair p to the simplex unless it is already there;
 * returns 1 when it was. After the first advance of a warm run (onto the
 * previous contact plane), the previous simplex comes back first: it is
 * made of points of M, so the ray's invariants hold whatever the pose
 * change was. */
static int ray_add(ray *r, const sx_point *p) {
    if (r->warm) {
        for (int m = 0; m < r->warm->simplex_count; ++m) {
            r->s.p[r->s.n].ia = r->warm->vertex_a[m];
            r->s.p[r->s.n].ib = r->warm->vertex_b[m];
            r->s.lam[r->s.n++] = 0.0;
        }
        r->warm = NULL;
    }
    int dup = sx_has(&r->s, p->ia, p->ib);
    if (!dup && r->s.n < 4) {
        r->s.p[r->s.n].ia = p->ia;
        r->s.p[r->s.n].ib = p->ib;
        r->s.lam[r->s.n++] = 0.0;
    }
    return dup;
}

/* One step: a support point, an advance, the simplex solved at x. */
static int ray_step(ray *r) {
    ++r->it;
    sx_point p = tr_support(&r->c, r->v);
    int advanced = ray_advance(r, p.w);
    if (advanced < 0) return RAY_MISS;
    int dup = ray_add(r, &p);
    px_vec3 mpts[4], nv;
    tr_points(&r->c, &r->s, mpts);
    int inside = tr_solve(&r->s, r->x, mpts, &nv);
    double vv = pxi_len2(nv);
    r->y2 = 1.0;
    for (int m = 0; m < r->s.n; ++m)
        if (pxi_len2(r->s.p[m].w) > r->y2) r->y2 = pxi_len2(r->s.p[m].w);
    /* van den Bergen's test: x within a relative 64 eps of the simplex
     * (the |x - m| are at least the pair's size, 1 here). */
    if (inside || !(vv > PXI_SUPPORT_NOISE * PXI_SUPPORT_NOISE * r->y2)) return RAY_HIT;
    /* The two stall exits hold only once v is the closest point of a solved
     * simplex (not the first direction, nor a warm hint). x did not move
     * and the simplex got no closer: the rounding floor, with x on M's
     * boundary. Or a support point already kept and no separating plane:
     * v.w >= |v|^2 would hold for it in exact arithmetic, so |v| is
     * rounding, and x is on M's boundary too. */
    if (r->v_closest && !advanced && (!(vv < pxi_len2(r->v)) || dup)) return RAY_FLOOR;
    r->v = nv;
    r->v_closest = 1;
    return RAY_GO;
}

/* The features of the simplex's vertex pairs, with the witnesses they give
 * at its current weights (pa in A's frame, pb in B's). */
static void ray_features(const ray *r, px_vec3 *pa, px_vec3 *pb, px_feature *fa, px_feature *fb) {
    uint32_t ia[4], ib[4];
    sx_witness(&r->s, r->c.a, r->c.b, pa, pb, ia, ib);
    *fa = pxi_feature_of_vertices(r->c.a, ia, r->s.n, pa);
    *fb = pxi_feature_of_vertices(r->c.b, ib, r->s.n, pb);
}

/* The hit from the final simplex: tau recomputed from its plane, contact
 * points from its weights at x = tau d. */
static void ray_hit(ray *r, pxi_translation *out) {
    px_vec3 mpts[4], nv;
    tr_points(&r->c, &r->s, mpts);
    double tau = tr_refine(mpts, r->s.n, r->d, r->tau0 + r->lambda);
    tr_solve(&r->s, pxi_scale(r->d, tau), mpts, &nv);
    double nl = pxi_len(r->normal);
    out->hit = 1;
    out->tau = tau / r->c.k; /* M was scaled by k */
    out->normal = nl > 0.0 ? pxi_scale(r->normal, -1.0 / nl) : pxi_v(0, 0, 0);
    ray_features(r, &out->pa, &out->pb, &out->fa, &out->fb);
}

/* The cache after a hit: the simplex (a tetrahedron keeps a face), the
 * plane normal (towards A), the features. */
static void ray_store(const ray *r, px_pair_cache *cache, const pxi_translation *out) {
    if (!cache) return;
    cache->simplex_count = (uint8_t)(r->s.n < 4 ? r->s.n : 3);
    for (int m = 0; m < cache->simplex_count; ++m) {
        cache->vertex_a[m] = r->s.p[m].ia;
        cache->vertex_b[m] = r->s.p[m].ib;
    }
    double nl = pxi_len(r->normal);
    if (nl > 0.0) {
        cache->direction[0] = r->normal.x / nl;
        cache->direction[1] = r->normal.y / nl;
        cache->direction[2] = r->normal.z / nl;
    }
    cache->feature_a = out->fa;
    cache->feature_b = out->fb;
}

pxi_outcome pxi_raycast(const px_convex *a, const px_convex *b, const px_pose *t_ab, px_vec3 dir,
                        px_pair_cache *cache, pxi_translation *out, pxi_ray_bound *bound) {
    memset(out, 0, sizeof *out);
    ray r;
    ray_init(&r, a, b, t_ab, dir, cache);
    int warm = r.warm != NULL, state = RAY_GO;
    while (state == RAY_GO && r.it < r.cap) state = ray_step(&r);
    out->iterations = r.it;
    int hit = state == RAY_HIT || state == RAY_FLOOR, capped = !hit && r.it >= r.cap;
    if (warm && (capped || state == RAY_FLOOR)) {
        /* A warm run that did not converge cleanly (a stale hint can mislead
         * the stall tests): the caller reruns cold. */
        cache->simplex_count = 0;
        return PXI_OUT_OF_STEPS;
    }
    if (!hit) {
        tr_miss(&r.c, r.d, out);
        if (cache) cache->simplex_count = 0;
        return PXI_DONE;
    }
    if (state == RAY_FLOOR) {
        /* Stopped at the rounding floor, x within |v| of M but not in the
         * simplex: x is a proved lower bound, from which conservative
         * advancement (exact there) can finish. */
        double nl = pxi_len(r.normal);
        px_vec3 pa, pb;
        bound->tau = (r.tau0 + r.lambda) / r.c.k;
        bound->normal = nl > 0.0 ? pxi_scale(r.normal, -1.0 / nl) : pxi_v(0, 0, 0);
        ray_features(&r, &pa, &pb, &bound->fa, &bound->fb);
        bound->simplex.n = r.s.n < 4 ? r.s.n : 3;
        for (int m = 0; m < bound->simplex.n; ++m)
            bound->simplex.ia[m] = r.s.p[m].ia, bound->simplex.ib[m] = r.s.p[m].ib;
    }
    ray_hit(&r, out);
    ray_store(&r, cache, out);
    return state == RAY_HIT ? PXI_DONE : PXI_UNPROVEN;
}
