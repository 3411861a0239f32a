/* GJK distance, used to seed cold Lin-Canny walks and as their fallback.
 *
 * Sources: E. Gilbert, D. Johnson, S. Keerthi, "A fast procedure for
 * computing the distance between complex objects in three-dimensional
 * space", IEEE J. Robotics & Automation 4(2), 1988; G. van den Bergen, "A
 * fast and robust GJK implementation for collision detection of convex
 * objects", JGT 4(2), 1999 (relative duality-gap termination, no-progress
 * exit); S. Cameron, "Enhancing GJK", ICRA 1997 (support by hill climbing).
 * The closest point of a simplex to the origin uses Voronoi-region case
 * analysis (C. Ericson, Real-Time Collision Detection, §5.1.5-5.1.6).
 *
 * Frames: everything is computed in B's frame; A's support points are
 * mapped by T_AB. The Minkowski difference is K = A - B, and the distance is
 * |v| for v the point of K closest to the origin.
 */
#include <math.h>
#include <string.h>

#include "convex/convex.h"
#include "math/vec3.h"
#include "narrow/narrow.h"

typedef struct sx_point {
    px_vec3 w;       /* a - b in B's frame */
    uint32_t ia, ib; /* vertex ids on A and B */
} sx_point;

typedef struct simplex {
    sx_point p[4];
    double lam[4];
    int n;
    double margin; /* origin inside: its least distance to a face plane */
} simplex;

/* Keep the points whose flag is set, with their weights. */
static void keep(simplex *s, const int *use, const double *lam) {
    simplex out;
    out.n = 0;
    for (int k = 0; k < s->n; ++k)
        if (use[k]) {
            out.p[out.n] = s->p[k];
            out.lam[out.n++] = lam[k];
        }
    *s = out;
}

static void closest_segment(simplex *s) {
    px_vec3 a = s->p[0].w, b = s->p[1].w, ab = pxi_sub(b, a);
    double den = pxi_dot(ab, ab), t = den > 0.0 ? -pxi_dot(a, ab) / den : 0.0;
    int use[2] = {1, 1};
    double lam[2];
    if (!(t > 0.0)) {
        use[1] = 0, lam[0] = 1.0;
    } else if (t >= 1.0) {
        use[0] = 0, lam[1] = 1.0;
    } else {
        lam[0] = 1.0 - t, lam[1] = t;
    }
    keep(s, use, lam);
}

static void closest_triangle(simplex *s) {
    px_vec3 a = s->p[0].w, b = s->p[1].w, c = s->p[2].w;
    px_vec3 ab = pxi_sub(b, a), ac = pxi_sub(c, a);
    double d1 = -pxi_dot(ab, a), d2 = -pxi_dot(ac, a);
    int use[3] = {0, 0, 0};
    double lam[3] = {0, 0, 0};
    if (d1 <= 0.0 && d2 <= 0.0) {
        use[0] = 1, lam[0] = 1;
        keep(s, use, lam);
        return;
    }
    double d3 = -pxi_dot(ab, b), d4 = -pxi_dot(ac, b);
    if (d3 >= 0.0 && d4 <= d3) {
        use[1] = 1, lam[1] = 1;
        keep(s, use, lam);
        return;
    }
    double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
        double v = d1 - d3 > 0.0 ? d1 / (d1 - d3) : 0.0; /* 0/0 on degenerate input */
        use[0] = use[1] = 1, lam[0] = 1 - v, lam[1] = v;
        keep(s, use, lam);
        return;
    }
    double d5 = -pxi_dot(ab, c), d6 = -pxi_dot(ac, c);
    if (d6 >= 0.0 && d5 <= d6) {
        use[2] = 1, lam[2] = 1;
        keep(s, use, lam);
        return;
    }
    double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
        double w = d2 - d6 > 0.0 ? d2 / (d2 - d6) : 0.0;
        use[0] = use[2] = 1, lam[0] = 1 - w, lam[2] = w;
        keep(s, use, lam);
        return;
    }
    double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
        double den = (d4 - d3) + (d5 - d6), w = den > 0.0 ? (d4 - d3) / den : 0.0;
        use[1] = use[2] = 1, lam[1] = 1 - w, lam[2] = w;
        keep(s, use, lam);
        return;
    }
    double sum = va + vb + vc;
    if (!(sum > 0.0)) { /* degenerate (collinear) triangle: keep its longest side */
        simplex e = *s;
        e.n = 2;
        closest_segment(&e);
        *s = e;
        return;
    }
    use[0] = use[1] = use[2] = 1;
    lam[1] = vb / sum, lam[2] = vc / sum, lam[0] = 1.0 - lam[1] - lam[2];
    keep(s, use, lam);
}

/* Returns 1 when the origin is inside (or on) the tetrahedron. */
static int closest_tetra(simplex *s) {
    static const int faces[4][4] = {{0, 1, 2, 3}, {0, 3, 1, 2}, {0, 2, 3, 1}, {1, 3, 2, 0}};
    double best = INFINITY;
    simplex best_s = *s;
    int any = 0;
    for (int k = 0; k < 4; ++k) {
        px_vec3 a = s->p[faces[k][0]].w, b = s->p[faces[k][1]].w, c = s->p[faces[k][2]].w;
        px_vec3 d = s->p[faces[k][3]].w;
        px_vec3 n = pxi_cross(pxi_sub(b, a), pxi_sub(c, a));
        double so = -pxi_dot(a, n), sd = pxi_dot(pxi_sub(d, a), n);
        if (!(so * sd < 0.0) && sd != 0.0) continue; /* origin on d's side of this face */
        simplex t;
        t.n = 3;
        t.p[0] = s->p[faces[k][0]], t.p[1] = s->p[faces[k][1]], t.p[2] = s->p[faces[k][2]];
        closest_triangle(&t);
        px_vec3 v = {0, 0, 0};
        for (int m = 0; m < t.n; ++m) v = pxi_madd(v, t.p[m].w, t.lam[m]);
        double d2 = pxi_len2(v);
        any = 1;
        if (d2 < best) best = d2, best_s = t;
    }
    if (!any) {
        /* Origin inside: its barycentric coordinates are ratios of signed
         * volumes (the origin replacing vertex k), so that sum lam_k w_k = 0
         * and the same weights give a common point of A and B. */
        px_vec3 w0 = s->p[0].w, w1 = s->p[1].w, w2 = s->p[2].w, w3 = s->p[3].w;
        double v0 = pxi_dot(w1, pxi_cross(w2, w3)), v1 = -pxi_dot(w0, pxi_cross(w2, w3));
        double v2 = pxi_dot(w0, pxi_cross(w1, w3)), v3 = -pxi_dot(w0, pxi_cross(w1, w2));
        double tot = v0 + v1 + v2 + v3;
        /* Trust the containment only for a tetrahedron of real volume: a
         * flat one (support points that coincide within rounding, as for a
         * 1e-6 body at 1e12) decides its side tests on noise. */
        double m = 0.0;
        for (int f = 0; f < 4; ++f)
            if (pxi_max_abs(s->p[f].w) > m) m = pxi_max_abs(s->p[f].w);
        int fat =
            fabs(tot) > 1e-9 * m * m * m && v0 / tot >= 0 && v1 / tot >= 0 && v2 / tot >= 0 && v3 / tot >= 0;
        s->margin = fat ? INFINITY : 0.0;
        for (int f = 0; f < 4; ++f) {
            px_vec3 a = s->p[faces[f][0]].w, b = s->p[faces[f][1]].w, c = s->p[faces[f][2]].w;
            px_vec3 n = pxi_cross(pxi_sub(b, a), pxi_sub(c, a));
            double len = pxi_len(n), dist = len > 0.0 ? fabs(pxi_dot(a, n)) / len : 0.0;
            if (fat && dist < s->margin) s->margin = dist;
        }
        if (tot != 0.0 && isfinite(tot)) {
            s->lam[0] = v0 / tot, s->lam[1] = v1 / tot, s->lam[2] = v2 / tot, s->lam[3] = v3 / tot;
        } else {
            s->lam[0] = s->lam[1] = s->lam[2] = s->lam[3] = 0.25;
        }
        return 1;
    }
    *s = best_s;
    return 0;
}

static px_vec3 simplex_point(const simplex *s) {
    px_vec3 v = {0, 0, 0};
    for (int k = 0; k < s->n; ++k) v = pxi_madd(v, s->p[k].w, s->lam[k]);
    return v;
}

/* Support of K = A - B in direction -v: A extreme along -v, B along +v.
 * Points of K are stored multiplied by `k`, a power of two that brings the
 * problem to unit scale: the simplex solver forms fourth powers of lengths,
 * which would overflow for bodies of 1e80 or underflow for bodies of 1e-80. */
static sx_point support(const px_convex *a, const px_convex *b, const px_pose *t_ab, px_vec3 v, double k) {
    /* Always from the direction table: climbing from the previous support
     * vertex is slower on large hulls, where early GJK directions jump. */
    sx_point p;
    p.ia = pxi_support(a, pxi_rot_t(t_ab->r, pxi_neg(v)), UINT32_MAX);
    p.ib = pxi_support(b, v, UINT32_MAX);
    p.w = pxi_scale(pxi_sub(pxi_xform(t_ab, a->v[p.ia]), b->v[p.ib]), k);
    return p;
}

void pxi_gjk(const px_convex *a, const px_convex *b, const px_pose *t_ab, double rel_tol,
             uint32_t max_iterations, pxi_gjk_result *out) {
    memset(out, 0, sizeof *out);
    simplex s;
    double span = a->scale + b->scale + pxi_max_abs(t_ab->t);
    double k = span > 0.0 && isfinite(span) ? ldexp(1.0, -ilogb(span)) : 1.0;
    /* First direction: centre to centre; a fixed non-axis direction when the
     * centres coincide (fcl #346, libccd #25). */
    px_vec3 v = pxi_sub(pxi_xform(t_ab, a->center), b->center);
    if (!(pxi_len2(v) > 0.0)) v = pxi_v(0.5773502691896258, 0.5773502588, 0.5773502794);
    s.n = 1;
    s.margin = 0.0;
    s.p[0] = support(a, b, t_ab, v, k);
    s.lam[0] = 1.0;
    v = s.p[0].w;
    double vv = pxi_len2(v), rel2 = rel_tol * rel_tol;
    int inside = 0;
    uint32_t it = 0;
    while (it < max_iterations) {
        if (!(vv > 0.0)) { /* origin on K: touching (or NaN: stop) */
            inside = 1;
            break;
        }
        ++it;
        sx_point w = support(a, b, t_ab, v, k);
        /* van den Bergen: stop when the duality gap |v|^2 - v.w is small
         * relative to |v|^2. Written so that NaN stops the loop. */
        double gap = vv - pxi_dot(v, w.w);
        if (!(gap > rel2 * vv)) break;
        int dup = 0;
        for (int m = 0; m < s.n; ++m)
            if (s.p[m].ia == w.ia && s.p[m].ib == w.ib) dup = 1;
        if (dup) break;
        simplex prev = s;
        s.lam[s.n] = 0.0;
        s.p[s.n++] = w;
        if (s.n == 2)
            closest_segment(&s);
        else if (s.n == 3)
            closest_triangle(&s);
        else if (closest_tetra(&s)) {
            inside = 1;
            break;
        }
        px_vec3 nv = simplex_point(&s);
        double nvv = pxi_len2(nv);
        if (!(nvv < vv)) { /* no progress: round-off floor reached */
            s = prev;
            break;
        }
        v = nv;
        vv = nvv;
    }
    /* Witnesses from the barycentric weights of the final simplex. */
    px_vec3 pa = {0, 0, 0}, pb = {0, 0, 0};
    double big = -1.0;
    for (int m = 0; m < s.n; ++m) {
        pa = pxi_madd(pa, a->v[s.p[m].ia], s.lam[m]);
        pb = pxi_madd(pb, b->v[s.p[m].ib], s.lam[m]);
        if (s.lam[m] > big) {
            big = s.lam[m];
            out->va = s.p[m].ia;
            out->vb = s.p[m].ib;
        }
    }
    out->pa = pa;
    out->pb = pb;
    out->intersecting = inside;
    out->distance = inside ? 0.0 : sqrt(vv) / k;
    out->inside_margin = inside && s.n == 4 ? s.margin / k : 0.0;
    out->iterations = it;
}

/* PLACEHOLDER until the enhanced GJK lands. */
void pxi_gjk_distance(const px_convex *a, const px_convex *b, const px_pose *t_ab, px_distance_cache *cache,
                      pxi_answer *out, pxi_simplex_pairs *simplex_out) {
    (void)cache;
    pxi_gjk_result g;
    pxi_gjk(a, b, t_ab, 1e-12, 256, &g);
    memset(out, 0, sizeof *out);
    out->distance = g.distance;
    out->pa = g.pa;
    out->pb = g.pb;
    out->intersecting = g.intersecting;
    out->fa.type = out->fb.type = PX_FEATURE_VERTEX;
    out->fa.index = g.va;
    out->fb.index = g.vb;
    if (simplex_out) simplex_out->n = 0;
}

int pxi_gjk_intersect(const px_convex *a, const px_convex *b, const px_pose *t_ab, px_distance_cache *cache,
                      uint32_t *iterations) {
    pxi_answer ans;
    pxi_gjk_distance(a, b, t_ab, cache, &ans, NULL);
    *iterations = 0;
    return ans.intersecting;
}
