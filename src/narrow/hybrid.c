/* The Lin-Canny / GJK hybrid of seed 001 (shared/seeds/001: "a hybrid of
 * the Lin-Canny and GJK distance algorithms", INRIA / GRAVIR, sections 4-5).
 *
 * Sources: seed 001 (cached vertex sets on each body, closed-form local
 * distances, support updates of one body at a time, the stability check);
 * G. van den Bergen, "A fast and robust GJK implementation for collision
 * detection of convex objects", JGT 4(2), 1999 (relative duality-gap and
 * absolute termination); S. Cameron, "Enhancing GJK", ICRA 1997 (supports
 * by hill climbing from the previous vertex, which makes warm queries O(1));
 * D. Eberly, DistPointSegment / DistPointTriangle / DistSegmentSegment
 * (region-clamped local solutions, one division at the end).
 *
 * The idea. Each body keeps a small vertex set, FA on A and FB on B (1-3
 * vertices: a point, segment or triangle). The closest points of conv(FA)
 * and conv(FB) are computed in closed form; their difference v is a
 * candidate separating direction. A's vertex extreme along -v (or B's along
 * +v) either proves the answer optimal (the duality gap closes) or, added to
 * its body's set, strictly lowers the local distance. After each local solve
 * the sets shrink to the vertices that carry weight, so they stay a
 * point / segment / triangle per body with at most 4 vertices in all, like a
 * GJK simplex but on the bodies themselves instead of on A - B. Working on
 * the bodies keeps every difference local: no Minkowski-difference points
 * whose lengths are dominated by the offset between the bodies.
 *
 * Local solves take the best of well-conditioned candidates (endpoint on
 * segment, point projected inside a triangle, segment crossing a segment,
 * segment through a triangle, point inside a tetrahedron): each candidate is
 * a genuine pair of points of the two hulls, so the local distance never
 * undershoots the true one by more than rounding, and the candidate set is
 * complete (the minimum of a convex function on a product of simplices is
 * attained in the relative interior of some pair of faces).
 *
 * Two departures from the paper, both for rounding. A degenerate set is
 * not refused but solved through its lower-dimensional pieces (a sliver
 * triangle as its edges, a flat tetrahedron as its faces), so a vertex that
 * extends a segment still helps. And near contact the direction v is only
 * known to about eps span / |v|, so the neighbours of the support that are
 * extreme within that noise are offered too (see explore).
 *
 * Frames and scale. Everything runs in B's frame, relative to one point `o`
 * of B (a vertex of the first set) and multiplied by a power of two k that
 * brings the pair's span to [1, 2): exact, so a problem scaled by a power of
 * two takes the same steps and gives the same bits, and neither squares nor
 * triple products of lengths can overflow or underflow for bodies of 1e39
 * or 1e-23. Tolerances are relative to the scaled span.
 */
#include <float.h>
#include <math.h>
#include <string.h>

#include "convex/convex.h"
#include "math/orient.h"
#include "math/vec3.h"
#include "narrow/feature.h"
#include "narrow/narrow.h"
#include "narrow/tolerance.h"

/* van den Bergen's relative tolerance: stop when |v|^2 - v.(wA - wB) <=
 * REL_TOL^2 |v|^2. */
#define REL_TOL 1e-13
/* A duality gap below GAP_C eps |v| span is rounding noise: it cannot lower
 * the distance by more than the coordinates' own rounding. */
#define GAP_C 8.0
/* Two vertices closer than TAU span are one point for the stability check. */
#define TAU 0x1p-50
/* Triangles with |e0 x e1|^2 <= TAU_TRI2 |e0|^2 |e1|^2 are treated as their
 * edges (their plane is noise). */
#define TAU_TRI2 1e-24
/* Angular noise of v, in units of eps span / |v| (see explore). */
#define EXPLORE_C 8.0
/* Margin factor of the sign tests that prove intersection. */
#define CROSS_C 32.0

/* ------------------------------------------------------------------------ */
/* Local closest points.                                                     */
/* ------------------------------------------------------------------------ */

/* Result of a local solve between point sets P (np points) and Q (nq). */
typedef struct hy_local {
    double wp[4], wq[4]; /* barycentric weights of the closest points */
    px_vec3 cp, cq;      /* the closest points */
    double d2;           /* |cp - cq|^2 */
    int hit;             /* the hulls provably cross: the solids intersect */
} hy_local;

/* Closest point of segment [q0, q1] to p (Eberly's DistPointSegment: clamp
 * first, divide only in the interior case, where 0 < t0 < |m|^2). */
static px_vec3 pt_seg(px_vec3 p, px_vec3 q0, px_vec3 q1, double *w) {
    px_vec3 m = pxi_sub(q1, q0);
    double t0 = pxi_dot(m, pxi_sub(p, q0));
    if (!(t0 > 0.0)) {
        w[0] = 1.0, w[1] = 0.0;
        return q0;
    }
    double mm = pxi_dot(m, m);
    if (t0 >= mm) {
        w[0] = 0.0, w[1] = 1.0;
        return q1;
    }
    double t = t0 / mm;
    w[0] = 1.0 - t, w[1] = t;
    return pxi_madd(q0, m, t);
}

/* Unnormalised barycentric coordinates of the projection of p onto the
 * plane of triangle q (normal n): lam[i] = ((q_k - q_j) x (p - q_j)) . n for
 * the cyclic (i, j, k). Each is measured from a vertex of the opposite edge,
 * so its error is eps |p - q_j| L |n| (not eps |p|^2 |n|). */
static void tri_lambdas(px_vec3 p, const px_vec3 *q, px_vec3 n, double *lam) {
    for (int i = 0; i < 3; ++i) {
        px_vec3 qj = q[(i + 1) % 3], qk = q[(i + 2) % 3];
        lam[i] = pxi_dot(pxi_cross(pxi_sub(qk, qj), pxi_sub(p, qj)), n);
    }
}

/* tri_lambdas from cross products to full relative precision. */
static void tri_lambdas_accurate(px_vec3 p, const px_vec3 *q, px_vec3 n, double *lam) {
    for (int i = 0; i < 3; ++i) lam[i] = pxi_dot(pxi_tri_cross(q[(i + 1) % 3], q[(i + 2) % 3], p), n);
}

/* The plane of a triangle is trusted only when its normal is not noise. */
static int tri_normal(const px_vec3 *q, px_vec3 *n) {
    px_vec3 e0 = pxi_sub(q[1], q[0]), e1 = pxi_sub(q[2], q[0]);
    *n = pxi_cross(e0, e1);
    double nn = pxi_dot(*n, *n);
    return nn > TAU_TRI2 * pxi_dot(e0, e0) * pxi_dot(e1, e1) && nn > 0.0;
}

/* Closest point of triangle q to p: the projection when it falls inside
 * (weights from the cross-product form of Eberly's s, t, which is better
 * conditioned than the a c - b^2 form), else the best of the three edges. */
static px_vec3 pt_tri(px_vec3 p, const px_vec3 *q, double *w, double *d2) {
    px_vec3 n;
    if (tri_normal(q, &n)) {
        double lam[3];
        px_vec3 e0 = pxi_sub(q[1], q[0]), e1 = pxi_sub(q[2], q[0]);
        if (pxi_is_sliver(n, e0, e1)) {
            /* A sliver: the normal and the weights from cross products to
             * full relative precision (pxi_tri_cross). In plain double both
             * lose a factor of the aspect (beside a 1 x 1e-8 side of a
             * turned plate, distances 500 eps of the span off). */
            n = pxi_tri_cross(q[0], q[1], q[2]);
            tri_lambdas_accurate(p, q, n, lam);
        } else {
            tri_lambdas(p, q, n, lam);
        }
        double sum = lam[0] + lam[1] + lam[2]; /* |n|^2 up to rounding */
        if (lam[0] >= 0.0 && lam[1] >= 0.0 && lam[2] >= 0.0 && sum > 0.0) {
            for (int i = 0; i < 3; ++i) w[i] = lam[i] / sum;
            px_vec3 c = pxi_madd(pxi_madd(q[0], pxi_sub(q[1], q[0]), w[1]), pxi_sub(q[2], q[0]), w[2]);
            *d2 = pxi_len2(pxi_sub(p, c));
            return c;
        }
    }
    px_vec3 best = q[0];
    *d2 = INFINITY;
    w[0] = 1.0, w[1] = w[2] = 0.0;
    for (int e = 0; e < 3; ++e) {
        int i = e, j = (e + 1) % 3;
        double we[2];
        px_vec3 c = pt_seg(p, q[i], q[j], we);
        double d = pxi_len2(pxi_sub(p, c));
        if (d < *d2) {
            *d2 = d, best = c;
            w[0] = w[1] = w[2] = 0.0;
            w[i] = we[0], w[j] = we[1];
        }
    }
    return best;
}

/* Keeps candidate (cp, cq, weights) in r when it is strictly closer. */
static void offer(hy_local *r, px_vec3 cp, px_vec3 cq, const double *wp, int np, const double *wq, int nq) {
    double d2 = pxi_len2(pxi_sub(cp, cq));
    if (!(d2 < r->d2)) return;
    r->d2 = d2, r->cp = cp, r->cq = cq;
    for (int i = 0; i < np; ++i) r->wp[i] = wp[i];
    for (int i = 0; i < nq; ++i) r->wq[i] = wq[i];
}

/* Segment-segment: the four endpoint-to-segment candidates, then the
 * crossing of the two lines when it lies inside both. The crossing's s comes
 * from the cross-product form (relative error eps / sin(angle), where
 * a c - b^2 would give eps / sin^2) and t from projecting the point at s, so
 * the pair stays consistent even for nearly parallel segments. Endpoint
 * candidates come first: on ties (parallel overlap) the smaller set wins. */
static void seg_seg(const px_vec3 *p, const px_vec3 *q, hy_local *r) {
    r->d2 = INFINITY;
    double w2[2], one[2] = {1.0, 0.0}, other[2] = {0.0, 1.0};
    for (int i = 0; i < 2; ++i) {
        px_vec3 c = pt_seg(p[i], q[0], q[1], w2);
        offer(r, p[i], c, i ? other : one, 2, w2, 2);
        c = pt_seg(q[i], p[0], p[1], w2);
        offer(r, c, q[i], w2, 2, i ? other : one, 2);
    }
    px_vec3 m0 = pxi_sub(p[1], p[0]), m1 = pxi_sub(q[1], q[0]), n = pxi_cross(m0, m1);
    double nn = pxi_dot(n, n), a = pxi_dot(m0, m0), c = pxi_dot(m1, m1);
    if (!(nn > TAU_TRI2 * a * c && nn > 0.0)) return;
    double s = pxi_dot(pxi_cross(pxi_sub(q[0], p[0]), m1), n);
    if (!(s > 0.0 && s < nn)) return;
    s /= nn;
    px_vec3 cp = pxi_madd(p[0], m0, s);
    double t = pxi_dot(m1, pxi_sub(cp, q[0]));
    if (!(t > 0.0 && t < c)) return;
    t /= c;
    double wp[2] = {1.0 - s, s}, wq[2] = {1.0 - t, t};
    offer(r, cp, pxi_madd(q[0], m1, t), wp, 2, wq, 2);
}

/* Noise bound of a triple product of vectors with these max-abs sizes. */
static double triple_noise(double x, double y, double z) { return CROSS_C * DBL_EPSILON * x * y * z; }

/* Does segment p cross triangle q (proved with margins against rounding)?
 * Then fills r with the crossing point. */
static int seg_through_tri(const px_vec3 *p, const px_vec3 *q, hy_local *r) {
    px_vec3 n;
    if (!tri_normal(q, &n)) return 0;
    px_vec3 e0 = pxi_sub(q[1], q[0]), e1 = pxi_sub(q[2], q[0]);
    /* A sliver's plain normal tilts by eps over its aspect, and the plane
     * through q[0] then misses its other corners by far more than the
     * sliver is wide (review s31: two needles 2.4e-10 apart were taken for
     * crossing): the accurate one. */
    const int sliver = pxi_is_sliver(n, e0, e1);
    if (sliver) n = pxi_tri_cross(q[0], q[1], q[2]);
    px_vec3 r0 = pxi_sub(p[0], q[0]), r1 = pxi_sub(p[1], q[0]);
    double s0 = pxi_dot(n, r0), s1 = pxi_dot(n, r1), ee = pxi_max_abs(e0) * pxi_max_abs(e1);
    if (!(fabs(s0) > triple_noise(ee, pxi_max_abs(r0), 1.0)) ||
        !(fabs(s1) > triple_noise(ee, pxi_max_abs(r1), 1.0)) || (s0 > 0.0) == (s1 > 0.0))
        return 0;
    double u = s0 / (s0 - s1); /* opposite signs: the denominator is not 0 */
    px_vec3 x = pxi_madd(p[0], pxi_sub(p[1], p[0]), u);
    double lam[3], len = pxi_max_abs(e0) > pxi_max_abs(e1) ? pxi_max_abs(e0) : pxi_max_abs(e1);
    if (sliver)
        tri_lambdas_accurate(x, q, n, lam);
    else
        tri_lambdas(x, q, n, lam);
    double noise = triple_noise(len, len + pxi_max_abs(pxi_sub(x, q[0])), pxi_max_abs(n));
    if (!(lam[0] > noise && lam[1] > noise && lam[2] > noise)) return 0;
    double sum = lam[0] + lam[1] + lam[2];
    r->wp[0] = 1.0 - u, r->wp[1] = u;
    for (int i = 0; i < 3; ++i) r->wq[i] = lam[i] / sum;
    r->cp = r->cq = x;
    r->d2 = 0.0;
    r->hit = 1;
    return 1;
}

/* Segment-triangle (seed 001 reduces it to the pairs above): a crossing
 * proves intersection; otherwise the best of the endpoints against the
 * triangle and the segment against each edge. */
static void seg_tri(const px_vec3 *p, const px_vec3 *q, hy_local *r) {
    r->d2 = INFINITY;
    if (seg_through_tri(p, q, r)) return;
    double wq[3], one[2] = {1.0, 0.0}, other[2] = {0.0, 1.0};
    for (int i = 0; i < 2; ++i) {
        double d2;
        px_vec3 c = pt_tri(p[i], q, wq, &d2);
        offer(r, p[i], c, i ? other : one, 2, wq, 3);
    }
    for (int e = 0; e < 3; ++e) {
        int i = e, j = (e + 1) % 3;
        px_vec3 edge[2] = {q[i], q[j]};
        hy_local s;
        seg_seg(p, edge, &s);
        double w3[3] = {0.0, 0.0, 0.0};
        w3[i] = s.wq[0], w3[j] = s.wq[1];
        offer(r, s.cp, s.cq, s.wp, 2, w3, 3);
    }
}

/* Point-tetrahedron: p inside (all four sub-volumes of the sign of the
 * whole, each beyond its rounding noise) proves intersection; otherwise the
 * best face. */
static void pt_tet(px_vec3 p, const px_vec3 *q, hy_local *r) {
    px_vec3 y[4];
    double m[4];
    for (int i = 0; i < 4; ++i) y[i] = pxi_sub(q[i], p), m[i] = pxi_max_abs(y[i]);
    double v[4] = {pxi_dot(y[1], pxi_cross(y[2], y[3])), -pxi_dot(y[0], pxi_cross(y[2], y[3])),
                   pxi_dot(y[0], pxi_cross(y[1], y[3])), -pxi_dot(y[0], pxi_cross(y[1], y[2]))};
    double sign = v[0] + v[1] + v[2] + v[3] > 0.0 ? 1.0 : -1.0;
    int inside = 1;
    for (int i = 0; i < 4 && inside; ++i) {
        double x = 1.0;
        for (int j = 0; j < 4; ++j) x *= j == i ? 1.0 : m[j];
        inside = sign * v[i] > triple_noise(x, 1.0, 1.0);
    }
    if (inside) {
        double tot = v[0] + v[1] + v[2] + v[3]; /* all of one sign and non-zero */
        r->wp[0] = 1.0;
        for (int i = 0; i < 4; ++i) r->wq[i] = v[i] / tot;
        r->cp = r->cq = p;
        r->d2 = 0.0;
        r->hit = 1;
        return;
    }
    static const int faces[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
    r->d2 = INFINITY;
    double one = 1.0;
    for (int f = 0; f < 4; ++f) {
        px_vec3 t[3] = {q[faces[f][0]], q[faces[f][1]], q[faces[f][2]]};
        double w3[3], w4[4] = {0.0, 0.0, 0.0, 0.0}, d2;
        px_vec3 c = pt_tri(p, t, w3, &d2);
        for (int i = 0; i < 3; ++i) w4[faces[f][i]] = w3[i];
        offer(r, p, c, &one, 1, w4, 4);
    }
}

/* Closest points of conv(p) and conv(q) with np <= nq, np + nq <= 5. */
static void solve_sorted(const px_vec3 *p, int np, const px_vec3 *q, int nq, hy_local *r) {
    r->hit = 0;
    if (np == 1) {
        r->wp[0] = 1.0;
        r->cp = p[0];
        if (nq == 1) {
            r->wq[0] = 1.0, r->cq = q[0];
        } else if (nq == 2) {
            r->cq = pt_seg(p[0], q[0], q[1], r->wq);
        } else if (nq == 3) {
            double d2;
            r->cq = pt_tri(p[0], q, r->wq, &d2);
        } else {
            pt_tet(p[0], q, r);
            return;
        }
        r->d2 = pxi_len2(pxi_sub(r->cp, r->cq));
    } else if (nq == 2) {
        seg_seg(p, q, r);
    } else {
        seg_tri(p, q, r);
    }
}

/* Closest points of conv(FA) and conv(FB); wp / cp belong to A. */
static void solve(const px_vec3 *pa, int na, const px_vec3 *pb, int nb, hy_local *r) {
    if (na <= nb) {
        solve_sorted(pa, na, pb, nb, r);
        return;
    }
    hy_local s;
    solve_sorted(pb, nb, pa, na, &s);
    *r = s;
    memcpy(r->wp, s.wq, sizeof r->wp);
    memcpy(r->wq, s.wp, sizeof r->wq);
    r->cp = s.cq, r->cq = s.cp;
}

/* ------------------------------------------------------------------------ */
/* The walk.                                                                 */
/* ------------------------------------------------------------------------ */

/* One body's vertex set: ids, scaled local coordinates, weights. */
typedef struct hy_set {
    uint32_t id[4];
    px_vec3 p[4];
    double w[4];
    int n;
} hy_set;

typedef struct hy_ctx {
    const px_convex *c[2]; /* A, B */
    const px_pose *t_ab;
    px_vec3 o;   /* origin of the local coordinates (B's frame) */
    px_vec3 to;  /* t_AB - o */
    double k;    /* power-of-two scale */
    double span; /* scaled size of the problem, in [1, 2) */
    hy_set s[2];
    px_vec3 c2[2];      /* current closest points (scaled local coordinates) */
    double vv;          /* |c2[0] - c2[1]|^2 */
    px_feature hint[2]; /* the cached features (type NONE when cold) */
    uint32_t iterations;
} hy_ctx;

/* Scaled local coordinates of vertex `id` of body `i`. */
static px_vec3 local_point(const hy_ctx *x, int i, uint32_t id) {
    if (i == 0) return pxi_scale(pxi_add(pxi_rot(x->t_ab->r, x->c[0]->v[id]), x->to), x->k);
    return pxi_scale(pxi_sub(x->c[1]->v[id], x->o), x->k);
}

/* Vertex of body i extreme along its side of v (A: -v, B: +v), by hill
 * climbing from `start` (UINT32_MAX: from the direction table). */
static uint32_t support(hy_ctx *x, int i, px_vec3 v, uint32_t start) {
    x->iterations++;
    if (i == 0) return pxi_support(x->c[0], pxi_rot_t(x->t_ab->r, pxi_neg(v)), start);
    return pxi_support(x->c[1], v, start);
}

/* Keeps the vertices of a set that carry weight in the local solution. */
static void reduce(hy_set *s, const double *w) {
    hy_set out;
    out.n = 0;
    for (int i = 0; i < s->n; ++i)
        if (w[i] > 0.0) {
            out.id[out.n] = s->id[i], out.p[out.n] = s->p[i], out.w[out.n++] = w[i];
        }
    if (out.n == 0) { /* cannot happen (weights sum to 1); keep one vertex */
        out.id[0] = s->id[0], out.p[0] = s->p[0], out.w[0] = 1.0, out.n = 1;
    }
    *s = out;
}

/* The set vertex with the largest weight: the hill-climbing start. */
static uint32_t heaviest(const hy_set *s) {
    int best = 0;
    for (int i = 1; i < s->n; ++i)
        if (s->w[i] > s->w[best]) best = i;
    return s->id[best];
}

/* Seed 001's stability check: a vertex already in the set, or closer than
 * TAU span to one of its vertices, would only add a degenerate edge. */
static int stable_to_add(const hy_ctx *x, const hy_set *s, uint32_t id, px_vec3 p) {
    double lim = TAU * x->span;
    for (int i = 0; i < s->n; ++i)
        if (s->id[i] == id || pxi_max_abs(pxi_sub(s->p[i], p)) <= lim) return 0;
    return 1;
}

enum { HY_MOVED, HY_STUCK, HY_HIT };

/* Tries to add body i's support vertex (id, p) to its set: kept only when
 * the local distance strictly decreases. */
static int try_add(hy_ctx *x, int i, uint32_t id, px_vec3 p, hy_local *r) {
    hy_set t = x->s[i];
    t.id[t.n] = id, t.p[t.n++] = p;
    const hy_set *sa = i == 0 ? &t : &x->s[0], *sb = i == 1 ? &t : &x->s[1];
    solve(sa->p, sa->n, sb->p, sb->n, r);
    if (r->hit) {
        x->s[i] = t;
        return HY_HIT;
    }
    if (!(r->d2 < x->vv)) return HY_STUCK;
    x->s[i] = t;
    return HY_MOVED;
}

/* Applies a local solution: closest points, distance, reduced sets. */
static void accept(hy_ctx *x, const hy_local *r) {
    x->c2[0] = r->cp, x->c2[1] = r->cq;
    x->vv = r->d2;
    reduce(&x->s[0], r->wp);
    reduce(&x->s[1], r->wq);
}

/* Near-extreme neighbours. v's direction is known only to about
 * eps span / |v| (both closest points carry rounding of the coordinates), so
 * near contact the support can miss a vertex that still lowers the distance
 * by more than the tolerance: with two nearly parallel edges 2.6e-7 apart,
 * the vertex-edge pair is 2e-11 worse than the edge-edge pair, while the
 * support cannot tell the two ends of the edge apart. The neighbours of the
 * set and of the support that are extreme within that noise are offered
 * too; the local distance decides, as for the support itself. */
static int explore(hy_ctx *x, int i, px_vec3 v, uint32_t sid, px_vec3 sp, hy_local *r) {
    const px_convex *c = x->c[i];
    /* The test runs in the body's own frame (no mapping per neighbour):
     * d has the length of v, and body-frame lengths times k are local ones. */
    px_vec3 d = i == 0 ? pxi_rot_t(x->t_ab->r, pxi_neg(v)) : v;
    px_vec3 vs = c->v[sid];
    double top = pxi_dot(d, vs), len = sqrt(x->vv), e = DBL_EPSILON * x->span;
    /* Near-extreme vertices are joined to the support by near-extreme edges
     * (a level set of a linear function on a polytope is connected), so its
     * ring is searched; the set's rings too when the support is elsewhere. */
    uint32_t roots[4] = {sid, 0, 0, 0};
    int nr = 1;
    if (stable_to_add(x, &x->s[i], sid, sp))
        for (int q = 0; q < x->s[i].n; ++q) roots[nr++] = x->s[i].id[q];
    for (int q = 0; q < nr; ++q)
        for (uint32_t k = c->v_first[roots[q]]; k < c->v_first[roots[q] + 1]; ++k) {
            uint32_t y = c->v_adj[k];
            /* angular noise (EXPLORE_C eps span / |v|) times |v| |y - s|, plus
             * the rounding of the two dot products */
            double band = e * (EXPLORE_C * x->k * pxi_max_abs(pxi_sub(c->v[y], vs)) + 4.0 * len);
            if (!(x->k * (pxi_dot(d, c->v[y]) - top) >= -band)) continue;
            px_vec3 py = local_point(x, i, y);
            if (!stable_to_add(x, &x->s[i], y, py)) continue;
            int st = try_add(x, i, y, py, r);
            if (st != HY_STUCK) return st;
        }
    return HY_STUCK;
}

/* One round: body `first`, then the other, offer their support vertices.
 * Returns HY_MOVED when one body improved the distance, HY_HIT on proved
 * intersection, HY_STUCK when neither can (converged). */
static int round_step(hy_ctx *x, int first, hy_local *r) {
    px_vec3 v = pxi_sub(x->c2[0], x->c2[1]);
    double len = sqrt(x->vv);
    double thr = REL_TOL * REL_TOL * x->vv + GAP_C * DBL_EPSILON * len * x->span;
    for (int a = 0; a < 2; ++a) {
        int i = first ^ a;
        uint32_t id = support(x, i, v, heaviest(&x->s[i]));
        px_vec3 p = local_point(x, i, id);
        /* This body's share of the duality gap |v|^2 - v.(wA - wB). */
        double g = i == 0 ? pxi_dot(v, pxi_sub(x->c2[0], p)) : pxi_dot(v, pxi_sub(p, x->c2[1]));
        int st = HY_STUCK;
        if (g > thr && stable_to_add(x, &x->s[i], id, p)) st = try_add(x, i, id, p, r);
        if (st != HY_STUCK) return st;
        st = explore(x, i, v, id, p, r);
        if (st != HY_STUCK) return st;
    }
    return HY_STUCK;
}

/* Reads the cached sets; 0 when absent or out of range (cold). */
static int load_cache(hy_ctx *x, const px_pair_cache *cache) {
    if (!cache) return 0;
    uint32_t n[2] = {cache->count_a, cache->count_b};
    const uint32_t *ids[2] = {cache->vertex_a, cache->vertex_b};
    for (int i = 0; i < 2; ++i) {
        if (n[i] < 1 || n[i] > 3) return 0;
        x->s[i].n = 0;
        for (uint32_t k = 0; k < n[i]; ++k) {
            if (ids[i][k] >= x->c[i]->nv) return 0;
            int dup = 0;
            for (int j = 0; j < x->s[i].n; ++j) dup |= x->s[i].id[j] == ids[i][k];
            if (!dup) x->s[i].id[x->s[i].n++] = ids[i][k];
        }
    }
    /* The local solvers take at most 5 vertices: a hand-made 3 + 3 keeps 2 on B. */
    if (x->s[0].n + x->s[1].n > 5) x->s[1].n = 2;
    x->hint[0] = cache->feature_a;
    x->hint[1] = cache->feature_b;
    return 1;
}

static void store_cache(const hy_ctx *x, px_pair_cache *cache, const pxi_answer *out) {
    if (!cache) return;
    uint8_t *n[2] = {&cache->count_a, &cache->count_b};
    uint32_t *ids[2] = {cache->vertex_a, cache->vertex_b};
    for (int i = 0; i < 2; ++i) {
        int m = x->s[i].n < 3 ? x->s[i].n : 3; /* a tetrahedron (intersection) keeps a face */
        for (int k = 0; k < m; ++k) ids[i][k] = x->s[i].id[k];
        *n[i] = (uint8_t)m;
    }
    cache->feature_a = out->fa;
    cache->feature_b = out->fb;
}

/* Witness of body i in its own frame from the weights of its set. */
static px_vec3 witness(const hy_ctx *x, int i) {
    const hy_set *s = &x->s[i];
    const px_vec3 *v = x->c[i]->v;
    px_vec3 base = v[s->id[0]], p = base;
    for (int k = 1; k < s->n; ++k) p = pxi_madd(p, pxi_sub(v[s->id[k]], base), s->w[k]);
    return p;
}

/* Whether feature f is exactly the smallest feature holding the set (the
 * edge joining two vertices, a face holding three): then it can be reused
 * from the cache without the search of pxi_feature_of_vertices. */
static int feature_holds(const px_convex *c, px_feature f, const hy_set *s) {
    if (s->n == 2 && f.type == PX_FEATURE_EDGE && f.index < c->ne) {
        const pxi_edge *e = &c->e[f.index];
        return (e->tail == s->id[0] && e->head == s->id[1]) || (e->tail == s->id[1] && e->head == s->id[0]);
    }
    if (s->n != 3 || f.type != PX_FEATURE_FACE || f.index >= c->nf) return 0;
    const pxi_face *F = &c->f[f.index];
    int found = 0;
    for (uint32_t q = 0; q < F->count; ++q) {
        uint32_t w = c->f_verts[F->first + q];
        found += w == s->id[0] || w == s->id[1] || w == s->id[2];
    }
    return found == 3; /* two distinct faces never share three vertices */
}

static px_feature feature_of(const hy_ctx *x, int i, const px_vec3 *p) {
    const hy_set *s = &x->s[i];
    if (s->n == 1 || s->n == 4) { /* a tetrahedron that proved intersection: no feature holds it */
        px_feature f = {PX_FEATURE_VERTEX, heaviest(s), 0};
        return f;
    }
    if (x->hint[i].type != PX_FEATURE_NONE && feature_holds(x->c[i], x->hint[i], s)) return x->hint[i];
    if (s->n == 2) { /* the edge joining them, when there is one */
        const px_convex *c = x->c[i];
        for (uint32_t k = c->v_first[s->id[0]]; k < c->v_first[s->id[0] + 1]; ++k)
            if (c->v_adj[k] == s->id[1]) {
                px_feature f = {PX_FEATURE_EDGE, c->v_edges[k], 0};
                return f;
            }
    }
    return pxi_feature_of_vertices(x->c[i], s->id, s->n, p);
}

static void finish(const hy_ctx *x, int intersecting, pxi_answer *out) {
    out->intersecting = intersecting;
    out->distance = intersecting ? 0.0 : sqrt(x->vv) / x->k;
    out->pa = witness(x, 0);
    out->pb = witness(x, 1);
    out->fa = feature_of(x, 0, &out->pa);
    out->fb = feature_of(x, 1, &out->pb);
    out->iterations = x->iterations;
}

/* Sets up the frame: origin o = B's first vertex, scale k. */
static void setup_frame(hy_ctx *x) {
    const px_pose *t = x->t_ab;
    x->k = pxi_pair_unit(x->c[0], x->c[1], t);
    x->span = pxi_pair_span(x->c[0], x->c[1], t) * x->k;
    x->o = x->c[1]->v[x->s[1].id[0]];
    x->to = pxi_sub(t->t, x->o);
    for (int i = 0; i < 2; ++i)
        for (int k = 0; k < x->s[i].n; ++k) x->s[i].p[k] = local_point(x, i, x->s[i].id[k]);
}

/* Cold start: the supports along the line of centres (a fixed skew
 * direction when the centres coincide). */
static void cold_start(hy_ctx *x) {
    px_vec3 d = pxi_sub(pxi_xform(x->t_ab, x->c[0]->center), x->c[1]->center);
    if (!(pxi_max_abs(d) > 0.0)) d = pxi_v(0.5773502691896258, 0.5773502588, 0.5773502794);
    for (int i = 0; i < 2; ++i) {
        x->s[i].n = 1;
        x->s[i].id[0] = support(x, i, d, UINT32_MAX);
    }
}

static uint32_t round_cap(const px_convex *a, const px_convex *b) {
    uint32_t n = a->nv + b->nv, lg = 0;
    while (n > 1) n >>= 1, ++lg;
    return 64 + 4 * lg;
}

void pxi_hybrid(const px_convex *a, const px_convex *b, const px_pose *t_ab, px_pair_cache *cache,
                pxi_answer *out) {
    memset(out, 0, sizeof *out);
    hy_ctx x;
    memset(&x, 0, sizeof x);
    x.c[0] = a, x.c[1] = b;
    x.t_ab = t_ab;
    if (!load_cache(&x, cache)) cold_start(&x);
    setup_frame(&x);

    hy_local r;
    solve(x.s[0].p, x.s[0].n, x.s[1].p, x.s[1].n, &r);
    int state = r.hit ? HY_HIT : HY_MOVED;
    if (!r.hit) accept(&x, &r);
    double abs_tol = PXI_HYBRID_CONTACT * DBL_EPSILON * x.span;
    uint32_t cap = round_cap(a, b), rounds = 0;
    int turn = 0; /* seed 001: one body per update, alternating */
    while (state == HY_MOVED && rounds < cap) {
        if (x.vv <= abs_tol * abs_tol) break; /* contact */
        ++rounds;
        state = round_step(&x, turn, &r);
        if (state == HY_MOVED) {
            accept(&x, &r);
            turn ^= 1;
        }
    }
    if (state == HY_HIT) {
        /* Intersection proved by the sets (kept unreduced: a crossing). */
        for (int i = 0; i < 2; ++i)
            for (int k = 0; k < x.s[i].n; ++k) x.s[i].w[k] = i == 0 ? r.wp[k] : r.wq[k];
        x.vv = 0.0;
        finish(&x, 1, out);
    } else if (state == HY_MOVED && x.vv > abs_tol * abs_tol) {
        /* Out of rounds: a safeguard that should never trigger. */
        finish(&x, 0, out);
        out->outcome = PXI_OUT_OF_STEPS;
    } else {
        int band = x.vv <= abs_tol * abs_tol;
        finish(&x, band, out);
        if (band) out->quality = PX_QUALITY_CONTACT_BAND;
    }
    store_cache(&x, cache, out);
}
