/* GJK: the distance method PX_METHOD_GJK, the boolean test, and the seed
 * and fallback of cold Lin-Canny walks. One loop (egjk_run) serves all three.
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
#include <float.h>
#include <math.h>
#include <string.h>

#include "convex/convex.h"
#include "math/vec3.h"
#include "narrow/closest.h"
#include "narrow/feature.h"
#include "narrow/narrow.h"
#include "narrow/simplex.h"
#include "narrow/tolerance.h"

/* One run on a pair: the power-of-two scale (pxi_pair_unit) and where
 * support climbs start.
 * Sources as above; the warm start from the previous simplex is Cameron's
 * (ICRA 1997, "Enhancing GJK") and van den Bergen's (JGT 1999, §5). */
typedef struct egjk {
    const px_convex *a, *b;
    const px_pose *t;
    double k;
    uint32_t start_a, start_b; /* UINT32_MAX: look up the direction table */
} egjk;

static void egjk_init(egjk *g, const px_convex *a, const px_convex *b, const px_pose *t_ab) {
    g->a = a;
    g->b = b;
    g->t = t_ab;
    g->k = pxi_pair_unit(a, b, t_ab);
    g->start_a = g->start_b = UINT32_MAX;
}

static sx_point egjk_point(const egjk *g, uint32_t ia, uint32_t ib) {
    return sx_pair_point(g->a, g->b, g->t, g->k, ia, ib);
}

/* Support of K = A - B along -v. Warm runs climb from the previous support
 * vertices (a few steps when the pose changed little); cold runs look up the
 * direction table each time, because early GJK directions jump across the
 * body and a climb from far away costs O(sqrt n) steps. */
static sx_point egjk_support(egjk *g, px_vec3 v) {
    uint32_t ia = pxi_support(g->a, pxi_rot_t(g->t->r, pxi_neg(v)), g->start_a);
    uint32_t ib = pxi_support(g->b, v, g->start_b);
    if (g->start_a != UINT32_MAX) g->start_a = ia, g->start_b = ib;
    return egjk_point(g, ia, ib);
}

/* Closest point of the simplex to the origin; 1 when the origin is inside a
 * tetrahedron. `robust` = 0 trusts the tetrahedron's side tests as they are
 * (the Lin-Canny seed, which checks the margin itself). */
static int egjk_solve(sx_simplex *s, int robust) {
    switch (s->n) {
    case 1: s->lam[0] = 1.0; return 0;
    case 2: pxi_sx_segment(s); return 0;
    case 3: pxi_sx_triangle(s); return 0;
    default: {
        if (!robust) return pxi_sx_tetra(s);
        /* Inside only when the tetrahedron is fat enough for its side tests.
         * Otherwise the closest point over all four faces: the side tests
         * that would skip faces decide on noise when the new point is within
         * rounding of the old triangle's plane (a 1e-12 dihedral angle), and
         * skipping the right face would stall GJK on the wrong facet. */
        sx_simplex t = *s;
        if (pxi_sx_tetra(&t) && (t.margin > 0.0 || pxi_sx_tetra_surely_contains(s))) {
            *s = t;
            return 1;
        }
        pxi_sx_flat_tetra(s);
        return 0;
    }
    }
}

/* What ends a run. */
typedef struct egjk_rules {
    double abs2;  /* |v|^2 at or below this (scaled units): contact; 0 = only exactly */
    double rel2;  /* van den Bergen's relative gap: stop when |v|^2 - v.w <= rel2 |v|^2 */
    uint32_t cap; /* support calls in the loop */
    int robust;   /* egjk_solve's mode */
} egjk_rules;

/* The GJK loop from a solved simplex s with closest point *v (|v|^2 in
 * *vv): add K's support along -v, re-solve, until the duality gap closes, a
 * support repeats, |v| stops shrinking (the round-off floor) or the origin
 * is enclosed. NaN fails every comparison and stops the loop. Returns 1
 * when the origin is inside K, 2 when |v| is within the contact band (or
 * NaN), 0 otherwise; *last_gap is
 * the last duality gap |v|^2 - v.w (the distance lies in
 * [(|v|^2 - gap) / |v|, |v|]). */
static int egjk_run(egjk *g, sx_simplex *s, px_vec3 *v, double *vv, uint32_t *it, const egjk_rules *r,
                    double *last_gap) {
    for (uint32_t k = 0; k < r->cap; ++k) {
        if (!(*vv > r->abs2)) return 2; /* touching within the band (or NaN: stop) */
        ++*it;
        sx_point w = egjk_support(g, *v);
        double gap = *vv - pxi_dot(*v, w.w);
        *last_gap = gap;
        if (!(gap > r->rel2 * *vv)) return 0;
        if (sx_has(s, w.ia, w.ib)) return 0;
        sx_simplex prev = *s;
        s->lam[s->n] = 0.0;
        s->p[s->n++] = w;
        if (egjk_solve(s, r->robust)) return 1;
        px_vec3 nv = sx_point_of(s);
        double nvv = pxi_len2(nv);
        if (!(nvv < *vv)) { /* no progress: round-off floor reached */
            *s = prev;
            return 0;
        }
        *v = nv;
        *vv = nvv;
    }
    return 0;
}

/* Cold start: centre to centre; a fixed non-axis direction when the
 * centres coincide (fcl #346, libccd #25). */
static void egjk_cold(egjk *g, sx_simplex *s) {
    px_vec3 c = pxi_sub(pxi_xform(g->t, g->a->center), g->b->center);
    if (!(pxi_max_abs(c) > 0.0)) c = pxi_v(0.5773502691896258, 0.5773502588, 0.5773502794);
    s->n = 1;
    s->margin = 0.0;
    s->p[0] = egjk_support(g, c);
    s->lam[0] = 1.0;
}

/* The Lin-Canny seed and fallback: cold, always from the direction table,
 * contact only at exactly |v| = 0, the tetrahedron trusted as found (the
 * caller checks inside_margin). */
void pxi_gjk_seed_run(const px_convex *a, const px_convex *b, const px_pose *t_ab, double rel_tol,
                      uint32_t max_iterations, pxi_gjk_seed *out) {
    memset(out, 0, sizeof *out);
    egjk g;
    egjk_init(&g, a, b, t_ab);
    sx_simplex s;
    egjk_cold(&g, &s);
    px_vec3 v = s.p[0].w;
    double vv = pxi_len2(v);
    uint32_t it = 0;
    egjk_rules r = {0.0, rel_tol * rel_tol, max_iterations, 0};
    double gap = 0.0;
    int inside = egjk_run(&g, &s, &v, &vv, &it, &r, &gap) != 0;
    uint32_t ia[4], ib[4];
    sx_witness(&s, a, b, &out->pa, &out->pb, ia, ib);
    int big = sx_heaviest(&s);
    out->va = ia[big];
    out->vb = ib[big];
    out->intersecting = inside;
    out->distance = inside ? 0.0 : sqrt(vv) / g.k;
    out->inside_margin = inside && s.n == 4 ? s.margin / g.k : 0.0;
    out->iterations = it;
}

/* The cached simplex, if every id is in range for this pair. */
static int egjk_warm_simplex(const egjk *g, const px_pair_cache *cache, sx_simplex *s) {
    s->n = 0;
    s->margin = 0.0;
    if (!cache || cache->simplex_count == 0 || cache->simplex_count > 4) return 0;
    for (int m = 0; m < cache->simplex_count; ++m) {
        if (cache->vertex_a[m] >= g->a->nv || cache->vertex_b[m] >= g->b->nv) return 0;
        s->p[m] = egjk_point(g, cache->vertex_a[m], cache->vertex_b[m]);
        s->lam[m] = 0.0;
    }
    s->n = cache->simplex_count;
    return 1;
}

static void egjk_store(const sx_simplex *s, px_vec3 dir, px_pair_cache *cache) {
    if (!cache) return;
    cache->simplex_count = (uint8_t)s->n;
    for (int m = 0; m < s->n; ++m) {
        cache->vertex_a[m] = s->p[m].ia;
        cache->vertex_b[m] = s->p[m].ib;
    }
    cache->direction[0] = dir.x;
    cache->direction[1] = dir.y;
    cache->direction[2] = dir.z;
}

/* Final polish of a separated answer: the distance between the convex hulls
 * of the final simplex's A vertices and B vertices (at most three each),
 * measured directly between those features (point-point, point-segment,
 * point-triangle, segment-segment) rather than from their Minkowski
 * differences. Both are the same number in exact arithmetic, but a simplex
 * of A - B spanned by two nearly parallel edges is a sliver whose normal, and
 * so |v|, carry an error of eps / sin(angle); the direct segment-segment
 * closest points do not (the local methods of seed 001). Also picks the
 * smallest vertex subsets that realise the distance, as the features. */
typedef struct polish_best {
    double d2;
    px_vec3 pa, pb; /* B's frame, relative to the origin point */
    uint32_t ia[3], ib[3];
    int na, nb;
} polish_best;

static void polish_consider(polish_best *best, px_vec3 pa, px_vec3 pb, const uint32_t *ia, int na,
                            const uint32_t *ib, int nb) {
    double d2 = pxi_len2(pxi_sub(pa, pb));
    if (!(d2 < best->d2)) return;
    best->d2 = d2;
    best->pa = pa;
    best->pb = pb;
    best->na = na;
    best->nb = nb;
    for (int k = 0; k < na; ++k) best->ia[k] = ia[k];
    for (int k = 0; k < nb; ++k) best->ib[k] = ib[k];
}

/* Point p against the hull of 1-3 points q (ids iq): the closest point and
 * the ids with non-zero weight. */
static void polish_point_set(polish_best *best, px_vec3 p, uint32_t ip, const px_vec3 *q, const uint32_t *iq,
                             int nq, int p_is_a) {
    sx_simplex t;
    t.n = nq;
    t.margin = 0.0;
    for (int k = 0; k < nq; ++k) {
        t.p[k].w = pxi_sub(q[k], p);
        t.p[k].ia = iq[k];
        t.p[k].ib = 0;
        t.lam[k] = 1.0;
    }
    if (nq == 2) pxi_sx_segment(&t);
    if (nq == 3) pxi_sx_triangle(&t);
    px_vec3 c = p;
    uint32_t ids[3];
    for (int k = 0; k < t.n; ++k) {
        c = pxi_madd(c, t.p[k].w, t.lam[k]);
        ids[k] = t.p[k].ia;
    }
    if (p_is_a)
        polish_consider(best, p, c, &ip, 1, ids, t.n);
    else
        polish_consider(best, c, p, ids, t.n, &ip, 1);
}

static int distinct_ids(const uint32_t *in, int n, uint32_t *out) {
    int m = 0;
    for (int k = 0; k < n; ++k) {
        int seen = 0;
        for (int j = 0; j < m; ++j) seen |= out[j] == in[k];
        if (!seen) out[m++] = in[k];
    }
    return m;
}

static void egjk_polish(const egjk *g, const sx_simplex *s, pxi_answer *out) {
    uint32_t all_a[4], all_b[4], ia[4], ib[4];
    for (int m = 0; m < s->n; ++m) all_a[m] = s->p[m].ia, all_b[m] = s->p[m].ib;
    int na = distinct_ids(all_a, s->n, ia), nb = distinct_ids(all_b, s->n, ib);
    if (na > 3 || nb > 3) return;
    /* Relative to one B vertex: the numbers stay as small as the features;
     * and times the pair's power of two k, so that the squared distances
     * neither overflow (bodies above 1e154) nor underflow (below 1e-154). */
    px_vec3 o = g->b->v[ib[0]], pa[3], pb[3];
    for (int k = 0; k < na; ++k) pa[k] = pxi_scale(pxi_sub(pxi_xform(g->t, g->a->v[ia[k]]), o), g->k);
    for (int k = 0; k < nb; ++k) pb[k] = pxi_scale(pxi_sub(g->b->v[ib[k]], o), g->k);
    polish_best best;
    best.d2 = INFINITY;
    for (int k = 0; k < na; ++k) polish_point_set(&best, pa[k], ia[k], pb, ib, nb, 1);
    for (int k = 0; k < nb; ++k) polish_point_set(&best, pb[k], ib[k], pa, ia, na, 0);
    for (int i = 0; i < na; ++i)
        for (int j = i + 1; j < na; ++j)
            for (int k = 0; k < nb; ++k)
                for (int l = k + 1; l < nb; ++l) {
                    double u, w;
                    pxi_segment_closest(pa[i], pa[j], pb[k], pb[l], &u, &w);
                    px_vec3 x = pxi_madd(pa[i], pxi_sub(pa[j], pa[i]), u);
                    px_vec3 y = pxi_madd(pb[k], pxi_sub(pb[l], pb[k]), w);
                    uint32_t sa[2] = {ia[i], ia[j]}, sb[2] = {ib[k], ib[l]};
                    int ma = u > 0.0 && u < 1.0 ? 2 : 1, mb = w > 0.0 && w < 1.0 ? 2 : 1;
                    if (ma == 1 && u >= 1.0) sa[0] = ia[j];
                    if (mb == 1 && w >= 1.0) sb[0] = ib[l];
                    polish_consider(&best, x, y, sa, ma, sb, mb);
                }
    if (!(best.d2 < INFINITY)) return;
    /* In exact arithmetic d <= |v|: accept it unless it is worse by more
     * than rounding (then the simplex was not what we think: keep |v|). */
    double d = sqrt(best.d2) / g->k,
           noise = 64.0 * DBL_EPSILON * (pxi_max_abs(o) + pxi_max_abs(g->t->t) + g->a->scale);
    if (!(d <= out->distance + noise)) return;
    out->distance = d;
    out->pa = pxi_xform_inv(g->t, pxi_add(pxi_scale(best.pa, 1.0 / g->k), o));
    out->pb = pxi_add(pxi_scale(best.pb, 1.0 / g->k), o);
    out->fa = pxi_feature_of_vertices(g->a, best.ia, best.na, &out->pa);
    out->fb = pxi_feature_of_vertices(g->b, best.ib, best.nb, &out->pb);
}

void pxi_gjk_distance(const px_convex *a, const px_convex *b, const px_pose *t_ab, px_pair_cache *cache,
                      pxi_answer *out, pxi_simplex_pairs *simplex_out) {
    memset(out, 0, sizeof *out);
    egjk g;
    egjk_init(&g, a, b, t_ab);
    sx_simplex s;
    int inside = 0;
    uint32_t it = 0, cap = sx_iteration_cap(a, b);
    if (egjk_warm_simplex(&g, cache, &s)) {
        g.start_a = s.p[0].ia;
        g.start_b = s.p[0].ib;
        inside = egjk_solve(&s, 1);
    } else {
        egjk_cold(&g, &s);
        ++it;
        --cap;
    }
    px_vec3 v = sx_point_of(&s);
    double vv = pxi_len2(v);
    egjk_rules r = {PXI_GJK_CONTACT * PXI_GJK_CONTACT, PXI_GJK_REL * PXI_GJK_REL, cap, 1};
    double gap = 0.0;
    if (!inside) inside = egjk_run(&g, &s, &v, &vv, &it, &r, &gap);
    uint32_t ia[4], ib[4];
    sx_witness(&s, a, b, &out->pa, &out->pb, ia, ib);
    out->intersecting = inside != 0;
    out->distance = inside ? 0.0 : sqrt(vv) / g.k;
    /* Intersecting: the simplex spans the overlap, not a feature; name the
     * vertices of largest weight (a witness pair, as the API says). */
    int big = sx_heaviest(&s);
    out->fa = inside ? pxi_feature_of_vertices(a, &ia[big], 1, NULL)
                     : pxi_feature_of_vertices(a, ia, s.n, &out->pa);
    out->fb = inside ? pxi_feature_of_vertices(b, &ib[big], 1, NULL)
                     : pxi_feature_of_vertices(b, ib, s.n, &out->pb);
    out->iterations = it;
    if (!inside) egjk_polish(&g, &s, out);
    out->outcome = PXI_DONE;
    if (inside == 2) out->quality = PX_QUALITY_CONTACT_BAND;
    if (!inside && !(gap <= PXI_GJK_OPEN_GAP * vv)) {
        /* The loop stopped on a repeat or at the round-off floor with the
         * duality gap still open: the lower bound (|v|^2 - gap) / |v| is
         * far below |v|, so separation is not proved. This happens within
         * about 1e-9 of the size of contact between nearly coplanar facets,
         * where v's direction is known only to eps / |v|. */
        out->outcome = PXI_UNPROVEN;
        out->gap = vv > 0.0 ? (gap / sqrt(vv)) / g.k : INFINITY;
    }
    egjk_store(&s, v, cache);
    if (cache) {
        cache->feature_a = out->fa;
        cache->feature_b = out->fb;
    }
    if (simplex_out) {
        simplex_out->n = s.n;
        for (int m = 0; m < s.n; ++m) simplex_out->ia[m] = ia[m], simplex_out->ib[m] = ib[m];
    }
}

/* Boolean GJK: stops at the first direction v whose support plane leaves
 * the origin outside K (a separating axis: v.w > 0 for the support w of K
 * along -v), or when the simplex encloses the origin. A warm cache first
 * tries the previous separating direction: one support pair when the pair
 * is still separated along it. */
pxi_outcome pxi_gjk_intersect(const px_convex *a, const px_convex *b, const px_pose *t_ab,
                              px_pair_cache *cache, int *intersecting, uint32_t *iterations,
                              uint32_t *quality) {
    egjk g;
    egjk_init(&g, a, b, t_ab);
    sx_simplex s;
    px_vec3 v = pxi_sub(pxi_xform(t_ab, a->center), b->center);
    if (cache) {
        /* the last separating direction, made unit (a cache may hold any bits) */
        px_vec3 d = pxi_unit_safe(pxi_v(cache->direction[0], cache->direction[1], cache->direction[2]));
        if (pxi_max_abs(d) > 0.0) v = d;
        if (egjk_warm_simplex(&g, cache, &s)) { /* its vertices only seed the climbs */
            g.start_a = s.p[0].ia;
            g.start_b = s.p[0].ib;
        }
    }
    s.n = 0;
    s.margin = 0.0;
    if (!(pxi_max_abs(v) > 0.0)) v = pxi_v(0.5773502691896258, 0.5773502588, 0.5773502794);
    if (!pxi_len_ok(pxi_max_abs(v))) v = pxi_scale(v, g.k); /* |v|^2 below would overflow or underflow */
    uint32_t cap = sx_iteration_cap(a, b), it = 0;
    int hit = -1; /* -1: not proved either way yet */
    double vv = pxi_len2(v);
    /* The contact band of every query (tolerance.h), in scaled units. */
    double band = PXI_CONTACT_BAND * pxi_pair_size(a, b, t_ab) * g.k;
    while (it < cap) {
        ++it;
        sx_point w = egjk_support(&g, v);
        /* A separating axis only if the gap it proves clears the contact
         * band (touching within rounding counts as intersecting). */
        if (pxi_dot(v, w.w) > band * sqrt(vv)) {
            hit = 0;
            break;
        }
        if (sx_has(&s, w.ia, w.ib)) break; /* repeat without a separating axis: not proved */
        s.lam[s.n] = 0.0;
        s.p[s.n++] = w;
        if (egjk_solve(&s, 1)) {
            hit = 1;
            break;
        }
        px_vec3 nv = sx_point_of(&s);
        double nvv = pxi_len2(nv);
        if (!(nvv > band * band)) { /* within the contact band */
            hit = 1;
            *quality |= PX_QUALITY_CONTACT_BAND;
            break;
        }
        if (s.n > 1 && !(nvv < vv)) break; /* round-off floor: not proved */
        v = nv;
        vv = nvv;
    }
    egjk_store(&s, v, cache);
    if (iterations) *iterations = it;
    *intersecting = hit > 0;
    /* Stopped without a proof (a repeat, the round-off floor or the cap,
     * near contact between nearly coplanar facets): the caller decides. */
    return hit >= 0 ? PXI_DONE : PXI_UNPROVEN;
}
