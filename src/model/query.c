/* Model queries: distance, collision and tolerance verification between
 * sub-part hierarchy trees (M. Lin, Berkeley 1993, ch. 4). A depth-first
 * branch and bound over node pairs: each pair is bounded below by its
 * spheres, then by the exact distance of its hulls (Lin-Canny, tracked with
 * a per-node-pair cache), and pairs whose bound is not below the best leaf
 * distance found are pruned. Children are visited nearest first, so the
 * order is best-first along every path, and the previous query's best leaf
 * pair seeds the bound (temporal coherence).
 *
 * With a cache, a query also starts where the previous one stopped: the
 * front of node pairs it pruned or measured, each with its lower bound
 * (front tracking as in SWIFT++: S. Ehmann and M. Lin, "Accurate and fast
 * proximity queries between polyhedra using convex surface decomposition",
 * Eurographics 2001). Unlike SWIFT++, which tests every front pair again,
 * a stored bound is reused untested while B's motion since it was measured
 * cannot have closed it: first against a bound on any point's displacement
 * summed over queries (`drift`, as conservative advancement bounds motion),
 * then against the displacement of the pair's own node projected on the
 * axis of its gap. Only pairs that B actually closes on are measured again,
 * and descended if they must be (docs/model.md, "The front"). */
#include <float.h>
#include <stddef.h>
#include <math.h>
#include <string.h>

#include "convex/convex.h"
#include "core/core.h"
#include "model/model.h"
#include "narrow/narrow.h"

/* ---- The cache ---------------------------------------------------------- */

typedef struct mc_entry {
    uint32_t a, b; /* node ids; a == PXI_NONE: empty */
    px_pair_cache pc;
} mc_entry;

/* A node pair of the front. Its bound when measured, two ways:
 * - key: the bound plus the cache's drift then, so that key - drift bounds
 *   it now (one subtraction: the test that skips most entries);
 * - g along n: every point y of B's node and x of A's node had
 *   n . (y - x) >= g at the relative pose of query `stamp` (n a unit vector
 *   in A's frame; (0, 0, 0) when the bound has no axis). Moved by B's
 *   displacement since then, projected on n, this is a tighter bound than
 *   key - drift: motion across n does not close the gap. */
typedef struct mc_front {
    uint32_t a, b;
    uint64_t stamp;
    double key, g;
    px_vec3 n;
} mc_front;

/* The relative poses of the last MC_RING queries, for the entries' stamps. */
#define MC_RING 32

typedef struct mc_impl {
    uint64_t ida, idb; /* the models (or convex polytope) the cache serves: their uids */
    uint32_t best_a, best_b;
    uint32_t cap, count;
    mc_entry *table;
    /* The front: n_front entries, a cover of all leaf pairs when front_ok;
     * `next` collects what a query's expansions add to it. */
    mc_front *front, *next;
    uint32_t n_front, cap_front, n_next, cap_next;
    int front_ok;
    uint32_t cold_front; /* the front's size after the last cold descent */
    double drift;
    uint64_t stamp; /* queries that descended, this one included */
    px_pose ring[MC_RING];
    uint64_t ring_stamp[MC_RING];
    double ring_drift[MC_RING]; /* the drift at that query */
    px_allocator alloc;
    size_t bytes;
} mc_impl;

#define MC_DEFAULT_MAX_BYTES ((size_t)1 << 24)

void px_model_cache_release(px_model_cache *cache) {
    if (!cache) return;
    mc_impl *mc = cache->impl;
    if (mc) {
        px_allocator a = mc->alloc;
        pxi_free(&a, mc->table, (size_t)mc->cap * sizeof *mc->table);
        pxi_free(&a, mc->front, (size_t)mc->cap_front * sizeof *mc->front);
        pxi_free(&a, mc->next, (size_t)mc->cap_next * sizeof *mc->next);
        pxi_free(&a, mc, sizeof *mc);
    }
    cache->impl = NULL;
    cache->memory_bytes = 0;
}

static size_t cache_limit(const px_model_cache *cache) {
    return cache->max_bytes ? cache->max_bytes : MC_DEFAULT_MAX_BYTES;
}

/* The cache's state for models (a, b), created or reset as needed; NULL
 * when there is no cache or no memory for it (the query runs cold). */
static mc_impl *cache_open(px_model_cache *cache, const px_model *a, const px_model *b) {
    if (!cache) return NULL;
    mc_impl *mc = cache->impl;
    /* Identities, not addresses: a model built where a destroyed one was
     * must not inherit its front. */
    if (mc && (mc->ida != a->uid || mc->idb != b->uid)) {
        px_model_cache_release(cache);
        mc = NULL;
    }
    if (!mc) {
        px_allocator alloc;
        if (pxi_allocator_resolve(cache->allocator, &alloc, NULL) != PX_OK) return NULL;
        mc = sizeof *mc <= cache_limit(cache) ? pxi_alloc(&alloc, sizeof *mc) : NULL;
        if (!mc) {
            cache->cold_runs++; /* too small to hold even its header */
            return NULL;
        }
        memset(mc, 0, sizeof *mc);
        mc->alloc = alloc;
        mc->ida = a->uid;
        mc->idb = b->uid;
        mc->best_a = mc->best_b = PXI_NONE;
        mc->bytes = sizeof *mc;
        cache->impl = mc;
        cache->memory_bytes = mc->bytes;
    }
    return mc;
}

static uint32_t mc_hash(uint32_t a, uint32_t b, uint32_t cap) {
    uint64_t h = ((uint64_t)a * 0x9E3779B97F4A7C15ull) ^ ((uint64_t)b * 0xC2B2AE3D27D4EB4Full);
    return (uint32_t)(h >> 32) & (cap - 1);
}

static int mc_grow(px_model_cache *cache, mc_impl *mc) {
    uint32_t cap = mc->cap ? 2 * mc->cap : 64;
    size_t bytes = mc->bytes - (size_t)mc->cap * sizeof *mc->table + (size_t)cap * sizeof *mc->table;
    /* The old table is held until the new one is filled: both count
     * against the limit (review s30: the allocator saw 22 % more). */
    if (bytes + (size_t)mc->cap * sizeof *mc->table > cache_limit(cache) || cap > (1u << 30)) return 0;
    mc_entry *t = pxi_alloc_array(&mc->alloc, cap, sizeof *t);
    if (!t) return 0;
    for (uint32_t i = 0; i < cap; ++i) t[i].a = PXI_NONE;
    for (uint32_t i = 0; i < mc->cap; ++i) {
        if (mc->table[i].a == PXI_NONE) continue;
        uint32_t h = mc_hash(mc->table[i].a, mc->table[i].b, cap);
        while (t[h].a != PXI_NONE) h = (h + 1) & (cap - 1);
        t[h] = mc->table[i];
    }
    pxi_free(&mc->alloc, mc->table, (size_t)mc->cap * sizeof *mc->table);
    mc->table = t;
    mc->cap = cap;
    mc->bytes = bytes;
    cache->memory_bytes = bytes;
    return 1;
}

/* The pair cache of node pair (a, b), created zeroed on first use; NULL
 * when the cache is full or absent (the caller runs cold). */
static px_pair_cache *mc_pair(px_model_cache *cache, mc_impl *mc, uint32_t a, uint32_t b) {
    if (!mc) return NULL;
    if (mc->cap) {
        uint32_t h = mc_hash(a, b, mc->cap);
        while (mc->table[h].a != PXI_NONE) {
            if (mc->table[h].a == a && mc->table[h].b == b) return &mc->table[h].pc;
            h = (h + 1) & (mc->cap - 1);
        }
    }
    if ((mc->count + 1) * 2 > mc->cap && !mc_grow(cache, mc)) {
        cache->cold_runs++;
        return NULL;
    }
    uint32_t h = mc_hash(a, b, mc->cap);
    while (mc->table[h].a != PXI_NONE) h = (h + 1) & (mc->cap - 1);
    mc->table[h].a = a;
    mc->table[h].b = b;
    memset(&mc->table[h].pc, 0, sizeof mc->table[h].pc);
    mc->count++;
    return &mc->table[h].pc;
}

/* ---- The descent -------------------------------------------------------- */

enum { Q_DISTANCE, Q_COLLIDE, Q_WITHIN };

typedef struct qctx {
    const px_model *a, *b;
    const px_pose *pa, *pb;
    px_pose t_ab; /* B's frame to A's frame */
    px_model_cache *cache;
    mc_impl *mc;
    int kind;
    double tol; /* Q_WITHIN */
    double ub;  /* best leaf distance so far (Q_DISTANCE) */
    int hit;    /* Q_COLLIDE / Q_WITHIN */
    uint32_t leaf_a, leaf_b, node_a, node_b;
    px_vec3 pt_a, pt_b; /* world */
    px_vec3 hint;       /* unit direction between the best witnesses, A's frame */
    int has_hint;
    double band; /* contact band of the roots (collide, within) */
    /* Poses a little off rotations (px_pose_check allows 1e-6): bounds
     * taken in A's frame and leaf distances taken in B's (a polytope's
     * query) differ by up to frel |d| + fpad; pruning allows for it. */
    double frel, fpad;
    double tie_pad; /* the tie window's part that does not scale with d (set_ub) */
    /* Q_DISTANCE keeps a bound lb when lb < keep_lt, set with ub (set_ub). */
    double keep_lt;
    px_feature fa, fb;
    uint32_t node_pairs, leaf_pairs;
    px_diagnostics diag;
    px_status status;
    int emit;        /* recording the new front into q->mc->next */
    int emit_failed; /* out of room: the new front is incomplete */
    double drift;    /* the cache's drift at this query */
    uint32_t ready;  /* bit k: ring slot k's motion below is filled */
    /* B's motion since ring slot k: rotation and translation differences,
     * the rotation difference's Frobenius norm and a rounding scale. Last
     * in the struct: start() zeroes only what comes before. */
    double dr[MC_RING][9], dr_norm[MC_RING], dscale[MC_RING];
    px_vec3 dt[MC_RING];
} qctx;

/* A lower bound and, where there is one, the unit axis n (A's frame, from
 * A's node to B's) with n . (y - x) >= g for the nodes' points; g <= lb. */
typedef struct qbound {
    double lb, g;
    px_vec3 n;
} qbound;

static qbound no_axis(double lb) { return (qbound){lb, lb, {0, 0, 0}}; }

static qbound larger(qbound x, qbound y) { return y.lb > x.lb ? y : x; }

/* A bound taken in A's frame, made good for distances taken in B's. */
static double frame_lb(const qctx *q, double lb) {
    return isfinite(lb) ? lb - q->frel * fabs(lb) - q->fpad : lb;
}

/* The best distance so far and keep()'s threshold for it. A bound lb is
 * kept when, lowered by the frames' allowance (frame_lb: lb < (ub + fpad) /
 * (1 - frel), raised by 8 eps for its rounding), it is below ub by more
 * than a tie window, 128 eps (ub + the models' reach + |t_ab|), which never
 * takes more than half of ub. Bounds and leaf distances of tied pairs (two
 * parallel faces: hundreds of triangle pairs at one distance) differ by
 * rounding only, and their order is the rounding's: without the window,
 * from a few dozen to every one of them was measured again at every query,
 * depending on the poses (two parallel grids of 1,152 triangles: 27 to
 * 12,768 leaf pairs a warm query; the Puma cell's exact wrist pair: 440
 * instead of 110 us a step). A pair pruned is then at least ub - window
 * away, so the answer is the minimum over leaf pairs to within the window,
 * and a pair at distance 0 is never pruned for a positive ub. */
static void set_ub(qctx *q, double ub) {
    q->ub = ub;
    if (!isfinite(ub)) {
        q->keep_lt = ub;
        return;
    }
    double allow = (q->fpad + q->frel * ub) / (1.0 - q->frel) * (1.0 + 8.0 * DBL_EPSILON);
    double tie = 128.0 * DBL_EPSILON * ub + q->tie_pad;
    q->keep_lt = pxi_max2(ub + allow - tie, 0.5 * ub);
}

static int is_leaf(const pxi_mnode *n) { return n->child[1] == PXI_NONE; }

/* The spheres' gap, along the line of centres. */
static qbound sphere_bound(const qctx *q, const pxi_mnode *na, const pxi_mnode *nb) {
    px_vec3 d = pxi_sub(pxi_xform(&q->t_ab, nb->center), na->center);
    double l = pxi_len(d);
    qbound r = {l - na->radius - nb->radius, 0.0, {0, 0, 0}};
    r.g = r.lb;
    if (l > 0.0) r.n = pxi_scale(d, 1.0 / l);
    return r;
}

/* Contact band of a pair of nodes (the convex query's formula, with the
 * nodes' spheres). */
static double node_band(const qctx *q, const pxi_mnode *na, const pxi_mnode *nb) {
    px_vec3 cb = pxi_xform(&q->t_ab, nb->center);
    return 64.0 * DBL_EPSILON * (na->radius + nb->radius + pxi_len(pxi_sub(cb, na->center)));
}

static void add_diag(qctx *q, const px_diagnostics *d) {
    q->diag.iterations += d->iterations;
    q->diag.fallbacks += d->fallbacks;
    q->diag.quality |= d->quality;
}

/* Exact distance between two hulls (convex leaves or inner nodes). start()
 * checked both poses, so the leaf queries skip px_pose_check. */
static int hull_distance(qctx *q, uint32_t ia, uint32_t ib, px_distance_result *r) {
    px_pair_cache *pc = mc_pair(q->cache, q->mc, ia, ib);
    px_status st = pxi_distance_checked(q->a->nodes[ia].hull, q->pa, q->b->nodes[ib].hull, q->pb, pc, r);
    if (st != PX_OK) {
        q->status = st;
        return 0;
    }
    add_diag(q, &r->diag);
    return 1;
}

static void tri_of(const px_model *m, uint32_t leaf, px_vec3 out[3]) {
    const uint32_t *t = m->tri + 3 * (size_t)m->leaves[leaf].tri;
    for (int k = 0; k < 3; ++k) out[k] = m->v[t[k]];
}

static void record(qctx *q, double d, uint32_t ia, uint32_t ib, px_vec3 pa, px_vec3 pb, px_feature fa,
                   px_feature fb) {
    uint32_t la = q->a->nodes[ia].child[0], lb = q->b->nodes[ib].child[0];
    set_ub(q, d);
    q->node_a = ia;
    q->node_b = ib;
    q->leaf_a = la;
    q->leaf_b = lb;
    q->pt_a = pa;
    q->pt_b = pb;
    px_vec3 u = pxi_rot_t(q->pa->r, pxi_sub(pb, pa));
    double ul = pxi_len(u);
    q->has_hint = ul > 0.0 && isfinite(ul);
    if (q->has_hint) q->hint = pxi_scale(u, 1.0 / ul);
    fa.piece = la;
    fb.piece = lb;
    q->fa = fa;
    q->fb = fb;
}

/* Gap between the projections of s and t on u (any length: divided by it),
 * kept in *best with its axis (unit, from s to t) when larger. */
static void axis_gap(const px_vec3 s[3], const px_vec3 t[3], px_vec3 u, qbound *best) {
    double s0 = pxi_dot(u, s[0]), s1 = pxi_dot(u, s[1]), s2 = pxi_dot(u, s[2]);
    double t0 = pxi_dot(u, t[0]), t1 = pxi_dot(u, t[1]), t2 = pxi_dot(u, t[2]);
    double slo = pxi_min2(s0, pxi_min2(s1, s2)), shi = pxi_max2(s0, pxi_max2(s1, s2));
    double tlo = pxi_min2(t0, pxi_min2(t1, t2)), thi = pxi_max2(t0, pxi_max2(t1, t2));
    double up = tlo - shi, down = slo - thi;
    double len = pxi_len(u);
    if (!(len > 0.0)) return;
    double gap = pxi_max2(up, down) / len;
    if (gap > best->lb) {
        best->lb = gap;
        best->n = pxi_scale(u, (up >= down ? 1.0 : -1.0) / len);
    }
}

/* The rounding margin of projection gaps between triangles s and t. */
static double tri_margin(const px_vec3 s[3], const px_vec3 t[3]) {
    /* The size of the coordinates and edges (|e| <= sqrt 3 |e|_inf, and 2
     * covers that without a square root). */
    double size = pxi_max_abs(s[0]) + pxi_max_abs(t[0]) +
                  2.0 * (pxi_max_abs(pxi_sub(s[1], s[0])) + pxi_max_abs(pxi_sub(s[2], s[0])) +
                         pxi_max_abs(pxi_sub(t[1], t[0])) + pxi_max_abs(pxi_sub(t[2], t[0])));
    return 64.0 * DBL_EPSILON * size;
}

/* A lower bound on the distance of two triangles (A's frame) from a few
 * separating axes, minus a rounding margin: the hint, and both normals. */
static qbound tri_gap(const px_vec3 s[3], const px_vec3 t[3], const px_vec3 *hint) {
    qbound g = {-INFINITY, 0.0, {0, 0, 0}};
    if (hint) axis_gap(s, t, *hint, &g);
    axis_gap(s, t, pxi_cross(pxi_sub(s[1], s[0]), pxi_sub(s[2], s[0])), &g);
    axis_gap(s, t, pxi_cross(pxi_sub(t[1], t[0]), pxi_sub(t[2], t[0])), &g);
    g.lb -= tri_margin(s, t);
    g.g = g.lb;
    return g;
}

/* The triangle feature of a feature of its px_convex copy (whose vertex
 * numbering is CGAL's): vertices matched by position. */
static px_feature triangle_feature(const px_convex *c, px_feature f, const px_vec3 t[3]) {
    px_feature out = {PX_FEATURE_FACE, 0, 0};
    if (f.type == PX_FEATURE_FACE || px_convex_dimension(c) < 2) return out;
    uint32_t ids[2] = {f.index, f.index};
    if (f.type == PX_FEATURE_EDGE) px_convex_edge(c, f.index, ids);
    uint32_t k[2] = {0, 0};
    for (int j = 0; j < 2; ++j) {
        px_vec3 p;
        px_convex_vertex(c, ids[j], &p);
        for (uint32_t m = 0; m < 3; ++m)
            if (p.x == t[m].x && p.y == t[m].y && p.z == t[m].z) k[j] = m;
    }
    if (f.type == PX_FEATURE_VERTEX) return (px_feature){PX_FEATURE_VERTEX, k[0], 0};
    /* Edge k joins vertices k and k + 1 (mod 3). */
    uint32_t e = (k[0] + 1) % 3 == k[1] ? k[0] : k[1];
    return (px_feature){PX_FEATURE_EDGE, e, 0};
}

/* A bump allocator over a buffer on the caller's stack, for the
 * short-lived px_convex of one triangle leaf (980 bytes in 12 blocks): the
 * leaf pair calls no allocator. What does not fit goes to `next` (the cache's
 * allocator, or malloc), and frees inside the buffer are nothing. */
typedef struct stack_arena {
    unsigned char *buf;
    size_t size, used;
    px_allocator next;
} stack_arena;

static void *arena_alloc(void *user, size_t size) {
    stack_arena *a = user;
    size_t at = (a->used + 15u) & ~(size_t)15u;
    if (at <= a->size && size <= a->size - at) {
        a->used = at + size;
        return a->buf + at;
    }
    return a->next.alloc(a->next.user, size);
}

static void arena_free(void *user, void *ptr, size_t size) {
    stack_arena *a = user;
    uintptr_t p = (uintptr_t)ptr, b = (uintptr_t)a->buf;
    if (p >= b && p < b + a->size) return;
    a->next.free(a->next.user, ptr, size);
}

/* A triangle leaf against a convex leaf: the triangle becomes a
 * (two-dimensional) px_convex for this pair (its hull built without CGAL,
 * in a buffer on the stack: no allocation), measured by px_distance, then
 * dropped; docs/model.md. Returns 0 with q->status set on error. */
static int mixed_pair(qctx *q, const pxi_mnode *na, const pxi_mnode *nb, double *d, px_vec3 *pa, px_vec3 *pb,
                      px_feature *fa, px_feature *fb) {
    int tri_is_a = na->hull == NULL;
    const px_model *tm = tri_is_a ? q->a : q->b;
    px_vec3 t[3];
    tri_of(tm, (tri_is_a ? na : nb)->child[0], t);
    double xyz[9];
    for (int k = 0; k < 3; ++k) xyz[3 * k] = t[k].x, xyz[3 * k + 1] = t[k].y, xyz[3 * k + 2] = t[k].z;
    _Alignas(16) unsigned char buf[2048];
    stack_arena arena = {buf, sizeof buf, 0, {NULL, NULL, NULL}};
    px_allocator via = {arena_alloc, arena_free, &arena};
    px_convex_options co;
    memset(&co, 0, sizeof co);
    if (pxi_allocator_resolve(q->cache ? q->cache->allocator : NULL, &arena.next, NULL) != PX_OK) {
        q->status = PX_ERR_INVALID_ARGUMENT;
        return 0;
    }
    co.allocator = &via;
    co.lut_resolution = 1;
    px_error e;
    px_convex *tc = px_convex_create(xyz, 3, &co, &e);
    if (!tc && e.code == PX_ERR_DEGENERATE) {
        /* A sliver too thin for its plane to be represented: measured as
         * its longest edge (the far corner lies within rounding of it). */
        int k = 0;
        double best = -1.0;
        for (int j = 0; j < 3; ++j) {
            double l = pxi_len2(pxi_sub(t[(j + 1) % 3], t[j]));
            if (l > best) best = l, k = j;
        }
        double seg[6] = {t[k].x, t[k].y, t[k].z, t[(k + 1) % 3].x, t[(k + 1) % 3].y, t[(k + 1) % 3].z};
        tc = px_convex_create(seg, 2, &co, &e);
        if (!tc && e.code == PX_ERR_DEGENERATE) tc = px_convex_create(seg, 1, &co, &e);
    }
    if (!tc) {
        q->status = e.code;
        return 0;
    }
    px_distance_result r;
    px_status st = tri_is_a ? pxi_distance_checked(tc, q->pa, nb->hull, q->pb, NULL, &r)
                            : pxi_distance_checked(na->hull, q->pa, tc, q->pb, NULL, &r);
    if (st == PX_OK) {
        add_diag(q, &r.diag);
        *d = r.intersecting ? 0.0 : r.distance;
        *pa = r.point_a;
        *pb = r.point_b;
        *fa = tri_is_a ? triangle_feature(tc, r.feature_a, t) : r.feature_a;
        *fb = tri_is_a ? r.feature_b : triangle_feature(tc, r.feature_b, t);
    } else {
        q->status = st;
    }
    px_convex_destroy(tc);
    return st == PX_OK;
}

/* Measures a leaf pair; for Q_DISTANCE updates the best, for the boolean
 * queries sets hit. Returns a lower bound on the pair's distance (its
 * distance when measured; 0 on error, with q->status set); triangle pairs
 * with the axis of their best projection gap. */
static qbound leaf_pair(qctx *q, uint32_t ia, uint32_t ib) {
    const pxi_mnode *na = &q->a->nodes[ia], *nb = &q->b->nodes[ib];
    uint32_t la = na->child[0], lb = nb->child[0];
    q->leaf_pairs++;
    double d;
    px_vec3 pa, pb;
    px_feature fa, fb;
    qbound out = no_axis(0.0);
    if (na->hull && nb->hull) {
        px_distance_result r;
        if (!hull_distance(q, ia, ib, &r)) return out;
        d = r.distance;
        pa = r.point_a;
        pb = r.point_b;
        fa = r.feature_a;
        fb = r.feature_b;
        if (r.intersecting) d = 0.0;
    } else if (!na->hull && !nb->hull) {
        px_vec3 s[3], t[3];
        tri_of(q->a, la, s);
        tri_of(q->b, lb, t);
        for (int k = 0; k < 3; ++k) t[k] = pxi_xform(&q->t_ab, t[k]);
        /* A cheap bound first: the two triangles projected on the
         * direction between the best witnesses and on each one's normal. */
        out = tri_gap(s, t, q->has_hint ? &q->hint : NULL);
        if (q->kind == Q_DISTANCE
                ? !(out.lb < q->keep_lt)
                : frame_lb(q, out.lb) > (q->kind == Q_WITHIN ? q->tol : node_band(q, na, nb)))
            return out;
        d = pxi_tri_tri(s, t, &pa, &pb, &fa, &fb);
        /* The projection gap along the witnesses' direction: for the next
         * query's front (the distance itself has no axis one can trust
         * when the witnesses are only nearly the closest pair). */
        if (d > 0.0) {
            qbound w = {-INFINITY, 0.0, {0, 0, 0}};
            axis_gap(s, t, pxi_sub(pb, pa), &w);
            w.lb -= tri_margin(s, t);
            if (w.lb > out.g) out.g = w.lb, out.n = w.n;
        }
        pa = pxi_xform(q->pa, pa);
        pb = pxi_xform(q->pa, pb);
    } else {
        if (!mixed_pair(q, na, nb, &d, &pa, &pb, &fa, &fb)) return out;
    }
    out.lb = d;
    if (q->kind == Q_DISTANCE) {
        if (d < q->ub) record(q, d, ia, ib, pa, pb, fa, fb);
        return out;
    }
    double limit = q->kind == Q_COLLIDE ? node_band(q, na, nb) : q->tol;
    if (d <= limit) {
        q->hit = 1;
        record(q, d, ia, ib, pa, pb, fa, fb);
    }
    return out;
}

/* Lower bound of node pair (ia, ib) for pruning against `limit`: the
 * sphere bound, the boxes' (or a triangle's against a box), then the hull
 * distance when both nodes have hulls. The axis is the best gap's among
 * spheres and boxes (a hull distance has none). */
static qbound pair_bound(qctx *q, uint32_t ia, uint32_t ib, double limit) {
    const pxi_mnode *na = &q->a->nodes[ia], *nb = &q->b->nodes[ib];
    q->node_pairs++;
    qbound lb = sphere_bound(q, na, nb);
    if (lb.lb > limit) return lb;
    /* Boxes: inner nodes keep theirs; a triangle leaf against an inner node
     * is tested against the box directly (two triangles are measured). */
    const px_vec3 *hint = q->has_hint ? &q->hint : NULL;
    const pxi_box *ba = na->box != PXI_NONE ? &q->a->boxes[na->box] : NULL;
    const pxi_box *bb = nb->box != PXI_NONE ? &q->b->boxes[nb->box] : NULL;
    qbound bx = {-INFINITY, -INFINITY, {0, 0, 0}};
    if (ba && bb) {
        bx.lb = pxi_box_gap(ba, bb, &q->t_ab, hint, limit, &bx.n);
    } else if (!ba && bb && !na->hull) {
        px_vec3 t[3];
        tri_of(q->a, na->child[0], t);
        /* The axis points from B's box to A's triangle: turned round. */
        bx.lb = pxi_tri_box_gap(t, bb, &q->t_ab, hint, limit, &bx.n);
        bx.n = pxi_neg(bx.n);
    } else if (ba && !bb && !nb->hull) {
        px_vec3 t[3];
        tri_of(q->b, nb->child[0], t);
        for (int k = 0; k < 3; ++k) t[k] = pxi_xform(&q->t_ab, t[k]);
        bx.lb = pxi_tri_box_gap(t, ba, NULL, hint, limit, &bx.n);
    }
    bx.g = bx.lb;
    lb = larger(lb, bx);
    if (lb.lb > limit) return lb;
    if (!na->hull || !nb->hull) return lb;
    px_distance_result r;
    if (!hull_distance(q, ia, ib, &r)) return no_axis(INFINITY);
    lb.lb = r.intersecting ? 0.0 : pxi_max2(lb.lb, r.distance);
    return lb;
}

static double current_limit(const qctx *q) { return q->kind == Q_DISTANCE ? q->ub : q->tol; }

static int done(const qctx *q) {
    return q->status != PX_OK || (q->kind == Q_DISTANCE ? q->ub == 0.0 : q->hit);
}

/* Pruning: Q_DISTANCE keeps pairs whose bound is below the best; the
 * boolean queries pairs whose bound is at most the tolerance (plus the
 * contact band for collisions, so that touching pairs are not pruned). */
static int keep(const qctx *q, double lb) {
    if (q->kind == Q_DISTANCE) return lb < q->keep_lt;
    lb = frame_lb(q, lb);
    /* q->band: at least every node pair's band, computed once. */
    return lb <= current_limit(q) + q->band;
}

/* ---- The front ---------------------------------------------------------- */

/* Moves front array *arr (capacity *cap, its first `used` entries kept)
 * to a capacity of `want`, within the cache's limit; 0 when there is no
 * room (the array is left as it was). */
static int front_grow(qctx *q, mc_front **arr, uint32_t *cap, uint32_t used, size_t want) {
    mc_impl *mc = q->mc;
    size_t bytes = mc->bytes + (want - *cap) * sizeof **arr;
    /* The old array is held until it is copied (see mc_grow). */
    mc_front *nf = bytes + (size_t)*cap * sizeof **arr <= cache_limit(q->cache) && want < ((size_t)1 << 26)
                       ? pxi_alloc_array(&mc->alloc, want, sizeof *nf)
                       : NULL;
    if (!nf) return 0;
    if (used) memcpy(nf, *arr, (size_t)used * sizeof *nf);
    pxi_free(&mc->alloc, *arr, (size_t)*cap * sizeof **arr);
    *arr = nf;
    *cap = (uint32_t)want;
    mc->bytes = bytes;
    q->cache->memory_bytes = bytes;
    return 1;
}

/* Pair (a, b) with bound lb, as a front entry measured at this query. */
static mc_front front_entry(const qctx *q, uint32_t a, uint32_t b, qbound lb) {
    return (mc_front){a, b, q->mc->stamp, lb.lb + q->drift, lb.g, lb.n};
}

/* Appends an entry to `next`, growing it within the cache's limit. */
static void emit_entry(qctx *q, mc_front f) {
    if (!q->emit) return;
    mc_impl *mc = q->mc;
    if (mc->n_next == mc->cap_next &&
        !front_grow(q, &mc->next, &mc->cap_next, mc->n_next, mc->cap_next ? 2 * (size_t)mc->cap_next : 256)) {
        q->emit = 0;
        q->emit_failed = 1;
        return;
    }
    mc->next[mc->n_next++] = f;
}

/* A pair pruned or measured at this query with bound lb. */
static void emit(qctx *q, uint32_t a, uint32_t b, qbound lb) {
    if (q->emit) emit_entry(q, front_entry(q, a, b, lb));
}

/* What a stored key still guarantees: key - drift, less the rounding of
 * the two sums (a few ulps of their size). */
static double front_bound(const qctx *q, double key) {
    return key - q->drift - 4.0 * DBL_EPSILON * (fabs(key) + q->drift);
}

/* A key above which an entry is pruned by its key alone: keep(q,
 * front_bound(q, key)) is then surely false, with a margin far above the
 * rounding of both (so the full test is needed only below it). The limit
 * only falls during a query (a better distance lowers keep_lt), so a
 * threshold taken at its start stays safe. */
static double prune_key(const qctx *q) {
    /* The least front bound that prunes: keep_lt, or for the boolean
     * queries the limit raised by the frames' allowance. */
    double t = q->kind == Q_DISTANCE ? q->keep_lt : (current_limit(q) + q->band + q->fpad) / (1.0 - q->frel);
    if (!(t >= 0.0) || !isfinite(t)) return INFINITY;
    /* front_bound(key) >= key (1 - 8 eps) - drift (1 + 8 eps) for key >= 0. */
    double k = (t + q->drift * (1.0 + 8.0 * DBL_EPSILON)) / (1.0 - 8.0 * DBL_EPSILON);
    k = k * (1.0 + 64.0 * DBL_EPSILON) + 0x1p-1000;
    return isfinite(k) ? k : INFINITY;
}

/* B's motion since ring slot k, computed on first use in this query. */
static void ring_motion(qctx *q, uint32_t k) {
    if (q->ready & (1u << k)) return;
    const px_pose *t0 = &q->mc->ring[k], *t1 = &q->t_ab;
    double f2 = 0.0;
    for (int i = 0; i < 9; ++i) q->dr[k][i] = t1->r[i] - t0->r[i], f2 += q->dr[k][i] * q->dr[k][i];
    q->dr_norm[k] = sqrt(f2) * (1.0 + 1e-12);
    q->dt[k] = pxi_sub(t1->t, t0->t);
    /* Every node's |c| + r is below |c_root| + 3 r_root (its points lie in
     * the root's sphere, so its centre does and its radius is at most the
     * root's diameter). */
    const pxi_mnode *root = &q->b->nodes[0];
    q->dscale[k] =
        pxi_max_abs(t0->t) + pxi_max_abs(t1->t) + 2.0 * (pxi_max_abs(root->center) + 3.0 * root->radius);
    q->ready |= 1u << k;
}

static int has_axis(const mc_front *f) { return f->n.x != 0.0 || f->n.y != 0.0 || f->n.z != 0.0; }

/* Bounds, at this query, on entry f measured at an earlier one still in
 * the ring (0 when its pose has left the ring). Since then B's node
 * (sphere c, r) has moved by m = dR c + dt, give or take |dR| r: the gap
 * along f's axis has closed by at most (dR c + dt) . n + |dR| r, and the
 * distance by at most |dR c + dt| + |dR| r. The first is tried first (no
 * square root); out->g is the moved gap along f->n (-inf without axis). */
static int moved_bound(qctx *q, const mc_front *f, qbound *out) {
    uint32_t k = (uint32_t)(f->stamp % MC_RING);
    if (q->mc->ring_stamp[k] != f->stamp) return 0;
    ring_motion(q, k);
    const pxi_mnode *nb = &q->b->nodes[f->b];
    px_vec3 m = pxi_add(pxi_rot(q->dr[k], nb->center), q->dt[k]);
    double turn = q->dr_norm[k] * nb->radius;
    double lb_then = f->key - q->mc->ring_drift[k];
    double slack = 32.0 * DBL_EPSILON * (fabs(f->key) + q->mc->ring_drift[k] + fabs(f->g) + q->dscale[k]);
    *out = (qbound){-INFINITY, -INFINITY, f->n};
    if (has_axis(f)) {
        out->g = f->g + pxi_dot(f->n, m) - turn - slack;
        out->lb = out->g;
        if (!keep(q, out->lb)) return 1;
    }
    out->lb = pxi_max2(out->lb, lb_then - pxi_len(m) - turn - slack);
    return 1;
}

/* A leaf pair: its spheres, then, if they do not prune it, the pair
 * itself; either way it joins the new front. */
static void visit_leaves(qctx *q, uint32_t a, uint32_t b) {
    qbound lb = sphere_bound(q, &q->a->nodes[a], &q->b->nodes[b]);
    if (keep(q, lb.lb)) lb = larger(lb, leaf_pair(q, a, b));
    emit(q, a, b, lb);
}

/* Node pair (a0, b0) measured afresh and, where its bound is within the
 * limit, descended depth first, nearest child pair first. Every pair where
 * the descent stops (pruned, or a leaf pair measured) joins the new front,
 * as do the pairs left unvisited when the query ends early (with their
 * parent's bound, which holds for them). */
static void expand(qctx *q, uint32_t a0, uint32_t b0) {
    typedef struct {
        uint32_t a, b;
        qbound lb;
    } spair;
    spair stack[512];
    uint32_t top = 0;
    const px_model *a = q->a, *b = q->b;
    if (is_leaf(&a->nodes[a0]) && is_leaf(&b->nodes[b0])) {
        visit_leaves(q, a0, b0);
        return;
    }
    qbound lb0 = pair_bound(q, a0, b0, current_limit(q));
    if (!keep(q, lb0.lb)) {
        emit(q, a0, b0, lb0);
        return;
    }
    stack[top++] = (spair){a0, b0, lb0};
    while (top > 0) {
        spair e = stack[--top];
        if (done(q) || !keep(q, e.lb.lb)) {
            emit(q, e.a, e.b, e.lb);
            continue;
        }
        const pxi_mnode *na = &a->nodes[e.a], *nb = &b->nodes[e.b];
        /* Both nodes split when both are inner (four child pairs, a level
         * of each tree per step), else the inner one. */
        uint32_t ca_list[2] = {e.a, e.a}, cb_list[2] = {e.b, e.b}, nca = 1, ncb = 1;
        if (!is_leaf(na)) ca_list[0] = na->child[0], ca_list[1] = na->child[1], nca = 2;
        if (!is_leaf(nb)) cb_list[0] = nb->child[0], cb_list[1] = nb->child[1], ncb = 2;
        spair kids[4];
        uint32_t nk = 0;
        for (uint32_t i = 0; i < nca; ++i) {
            for (uint32_t j = 0; j < ncb; ++j) {
                uint32_t ca = ca_list[i], cb = cb_list[j];
                if (done(q)) {
                    emit(q, ca, cb, e.lb);
                    continue;
                }
                if (is_leaf(&a->nodes[ca]) && is_leaf(&b->nodes[cb])) {
                    visit_leaves(q, ca, cb);
                    continue;
                }
                qbound lb = pair_bound(q, ca, cb, current_limit(q));
                if (keep(q, lb.lb))
                    kids[nk++] = (spair){ca, cb, lb};
                else
                    emit(q, ca, cb, lb);
            }
        }
        /* Farthest pushed first, so the nearest is taken next. */
        for (uint32_t i = 1; i < nk; ++i)
            for (uint32_t j = i; j > 0 && kids[j - 1].lb.lb < kids[j].lb.lb; --j) {
                spair t = kids[j];
                kids[j] = kids[j - 1];
                kids[j - 1] = t;
            }
        for (uint32_t k = 0; k < nk; ++k) {
            if (top == sizeof stack / sizeof stack[0]) {
                q->status = PX_ERR_INTERNAL;
                return;
            }
            stack[top++] = kids[k];
        }
    }
}

/* A bound on how far any point of B has moved in A's frame since the query
 * in ring slot k (the previous one): |(R1 - R0) c + t1 - t0| + |R1 - R0| r
 * over B's root sphere (c, r), the Frobenius norm bounding the rotation's,
 * with a rounding margin. The motion is ring_motion's, which the front's
 * entries from that query use too. */
static double motion_bound(qctx *q, uint32_t k) {
    ring_motion(q, k);
    const pxi_mnode *root = &q->b->nodes[0];
    px_vec3 c = root->center;
    px_vec3 m = pxi_add(pxi_rot(q->dr[k], c), q->dt[k]);
    double size = pxi_len(c) + root->radius + pxi_len(q->mc->ring[k].t) + pxi_len(q->t_ab.t);
    return pxi_len(m) * (1.0 + 1e-12) + q->dr_norm[k] * root->radius + 16.0 * DBL_EPSILON * size;
}

/* The descent: from the previous front when the cache holds a usable one,
 * else from the roots. The new front replaces the old when complete. */
static void descend(qctx *q) {
    mc_impl *mc = q->mc;
    if (!mc) {
        expand(q, 0, 0);
        return;
    }
    double reach = q->a->nodes[0].radius + q->b->nodes[0].radius;
    /* A front is only ever left by a descent, whose pose is in the ring. */
    int warm = mc->front_ok;
    if (warm) {
        mc->drift += motion_bound(q, (uint32_t)(mc->stamp % MC_RING));
        /* Cold again when the front has outgrown its last cold size by
         * half (a front only ever splits: past that, reading it costs more
         * than a fresh descent's coarser front saves; 1.5 gave the lowest
         * mean time per pose on the benchmark's approaches, against 1, 1.25,
         * 2 and 4), or when B has moved about as far as the models reach
         * (the stored bounds say little then, and the sums would lose
         * precision). */
        if (!(mc->drift <= 0.5 * reach) || 2 * (uint64_t)mc->n_front > 3 * (uint64_t)mc->cold_front + 512)
            warm = 0;
    }
    if (!warm) mc->drift = 0.0;
    /* This query's pose joins the ring, for the entries it writes. */
    mc->stamp++;
    uint32_t slot = (uint32_t)(mc->stamp % MC_RING);
    mc->ring[slot] = q->t_ab;
    mc->ring_stamp[slot] = mc->stamp;
    mc->ring_drift[slot] = mc->drift;
    q->drift = mc->drift;
    q->emit = 1;
    q->emit_failed = 0;
    mc->n_next = 0;
    /* The old front is rewritten in place (entries kept or rebased move
     * down over the expanded ones); what expansions emit collects in
     * `next` and is appended at the end. */
    uint32_t w = 0;
    if (warm) {
        uint32_t n = mc->n_front;
        const double kt = prune_key(q);
        for (uint32_t i = 0; i < n; ++i) {
            /* Entries pruned by their key stay as they are (moved down
             * over expanded ones, if any). */
            if (mc->front[i].key > kt) {
                if (w != i) mc->front[w] = mc->front[i];
                w++;
                continue;
            }
            mc_front f = mc->front[i];
            if (done(q) || !keep(q, front_bound(q, f.key))) {
                mc->front[w++] = f;
                continue;
            }
            /* The tighter bounds from B's motion since f was measured: if
             * they still prune, f is kept, rebased on this query. */
            qbound lb;
            if (moved_bound(q, &f, &lb) && !keep(q, lb.lb)) {
                mc->front[w++] = front_entry(q, f.a, f.b, lb);
                continue;
            }
            expand(q, f.a, f.b);
        }
    } else {
        expand(q, 0, 0);
    }
    /* Room for the appended entries, within the cache's limit. */
    size_t need = (size_t)w + mc->n_next;
    if (!q->emit_failed && q->status == PX_OK && need > mc->cap_front &&
        !front_grow(q, &mc->front, &mc->cap_front, w, need + need / 2 + 256))
        q->emit_failed = 1;
    if (q->emit_failed || q->status != PX_OK) {
        if (q->emit_failed) q->cache->cold_runs++;
        mc->front_ok = 0;
        mc->n_front = 0;
        mc->n_next = 0;
        return;
    }
    if (mc->n_next) memcpy(mc->front + w, mc->next, (size_t)mc->n_next * sizeof *mc->front);
    mc->n_front = w + mc->n_next;
    mc->n_next = 0;
    mc->front_ok = 1;
    if (!warm) mc->cold_front = mc->n_front;
}

/* ---- Containment -------------------------------------------------------- */

/* Directions for the ray casts: fixed, irrational-looking, not along axes,
 * so that rays rarely graze the edges of axis-aligned CAD geometry. */
static const double ray_dirs[8][3] = {
    {0.5773502691896258, 0.5773502691896257, 0.5773502691896259},
    {-0.3162277660168379, 0.8944271909999159, 0.3162277660168380},
    {0.8017837257372732, -0.2672612419124244, 0.5345224838248488},
    {-0.6666666666666666, -0.3333333333333333, 0.6666666666666667},
    {0.2182178902359924, 0.4364357804719848, -0.8728715609439696},
    {-0.5345224838248488, 0.8017837257372732, -0.2672612419124244},
    {0.9128709291752769, 0.3651483716701107, -0.1825741858350554},
    {-0.1690308509457033, -0.5070925528371099, -0.8451542547285166},
};

typedef struct ray_state {
    px_vec3 o, d;
    int winding;
    int grazed;
} ray_state;

/* Moller-Trumbore with a margin: a hit too close to an edge or vertex of
 * the triangle, or a ray nearly in its plane, marks the ray as grazing. */
static void ray_triangle(ray_state *r, const px_vec3 t[3]) {
    px_vec3 e1 = pxi_sub(t[1], t[0]), e2 = pxi_sub(t[2], t[0]);
    px_vec3 p = pxi_cross(r->d, e2);
    double det = pxi_dot(e1, p);
    double scale = pxi_len(e1) * pxi_len(e2);
    if (!(scale > 0.0)) return; /* a zero-area triangle bounds nothing */
    const double margin = 1e-9;
    if (fabs(det) <= margin * scale) {
        /* The ray runs (nearly) in the triangle's plane: grazing if it
         * passes near it at all. */
        px_vec3 n = pxi_cross(e1, e2);
        double off = pxi_dot(n, pxi_sub(r->o, t[0]));
        if (fabs(off) <= margin * scale * (1.0 + pxi_len(pxi_sub(r->o, t[0])))) r->grazed = 1;
        return;
    }
    double inv = 1.0 / det;
    px_vec3 s = pxi_sub(r->o, t[0]);
    double u = pxi_dot(s, p) * inv;
    px_vec3 qv = pxi_cross(s, e1);
    double v = pxi_dot(r->d, qv) * inv;
    double tt = pxi_dot(e2, qv) * inv;
    double w = 1.0 - u - v;
    if (u < -margin || v < -margin || w < -margin || tt < 0.0) return;
    if (u < margin || v < margin || w < margin) {
        r->grazed = 1;
        return;
    }
    /* Exits through an outward face count +1, entries -1. */
    r->winding += det > 0.0 ? 1 : -1;
}

static void ray_walk(const px_model *m, uint32_t id, ray_state *r) {
    const pxi_mnode *n = &m->nodes[id];
    px_vec3 oc = pxi_sub(n->center, r->o);
    double along = pxi_dot(oc, r->d);
    if (along < -n->radius) return;
    if (pxi_len2(pxi_sub(oc, pxi_scale(r->d, along))) > n->radius * n->radius * (1.0 + 1e-12)) return;
    if (is_leaf(n)) {
        uint32_t leaf = n->child[0];
        if (m->leaves[leaf].tri == PXI_NONE || !m->tri_solid[m->leaves[leaf].tri]) return;
        px_vec3 t[3];
        tri_of(m, leaf, t);
        ray_triangle(r, t);
        return;
    }
    ray_walk(m, n->child[0], r);
    if (!r->grazed) ray_walk(m, n->child[1], r);
}

/* Generalised winding number of the closed triangles about p: the sum of
 * their signed solid angles over 4 pi (A. Van Oosterom and J. Strackee,
 * "The solid angle of a plane triangle", IEEE Trans. Biomed. Eng. 30(2),
 * 1983). 1 inside a closed outward surface, 0 outside; O(triangles). */
static double winding_number(const px_model *m, px_vec3 p) {
    double total = 0.0;
    for (uint32_t t = 0; t < m->nt; ++t) {
        if (!m->tri_solid[t]) continue;
        const uint32_t *v = m->tri + 3 * (size_t)t;
        px_vec3 a = pxi_sub(m->v[v[0]], p), b = pxi_sub(m->v[v[1]], p), c = pxi_sub(m->v[v[2]], p);
        double la = pxi_len(a), lb = pxi_len(b), lc = pxi_len(c);
        double num = pxi_dot(a, pxi_cross(b, c));
        double den = la * lb * lc + pxi_dot(a, b) * lc + pxi_dot(b, c) * la + pxi_dot(c, a) * lb;
        total += 2.0 * atan2(num, den);
    }
    return total / (4.0 * 3.14159265358979323846);
}

int pxi_model_point_inside(const px_model *m, px_vec3 p) {
    if (m->pieces != PX_PIECES_TRIANGLES || m->solid_parts == 0) return 0;
    if (p.x < m->lo.x || p.y < m->lo.y || p.z < m->lo.z || p.x > m->hi.x || p.y > m->hi.y || p.z > m->hi.z)
        return 0;
    ray_state r;
    for (int k = 0; k < 8; ++k) {
        r.o = p;
        r.d = pxi_v(ray_dirs[k][0], ray_dirs[k][1], ray_dirs[k][2]);
        r.winding = 0;
        r.grazed = 0;
        ray_walk(m, 0, &r);
        if (!r.grazed) return r.winding != 0;
    }
    /* Every ray grazed an edge or vertex (a point on a symmetry plane of a
     * finely tessellated part, say): the winding number by solid angles
     * decides, which has no special directions (nonzero, as the rays':
     * a shell wound against the rest of its part counts -1). */
    return fabs(winding_number(m, p)) > 0.5;
}

/* A piece of `in` lying inside a solid of `out` (poses: world). */
static int contained(const qctx *q, const px_model *in, const px_pose *pose_in, const px_model *out,
                     const px_pose *pose_out) {
    if (out->pieces != PX_PIECES_TRIANGLES || out->solid_parts == 0) return 0;
    for (uint32_t i = 0; i < in->n_reps; ++i) {
        px_vec3 w = pxi_xform(pose_in, in->reps[i]);
        if (pxi_model_point_inside(out, pxi_xform_inv(pose_out, w))) return 1;
    }
    (void)q;
    return 0;
}

/* ---- Entry points ------------------------------------------------------- */

static px_status start(qctx *q, const px_model *a, const px_pose *pa, const px_model *b, const px_pose *pb,
                       px_model_cache *cache, int kind) {
    memset(q, 0, offsetof(qctx, dr));
    if (!a || !b || !pa || !pb) return PX_ERR_INVALID_ARGUMENT;
    double ka, kb;
    if (!pxi_pose_ok_skew(pa, &ka) || !pxi_pose_ok_skew(pb, &kb)) {
        px_status st = px_pose_check(pa, NULL);
        if (st == PX_OK) st = px_pose_check(pb, NULL);
        /* Not reached: pxi_pose_ok_skew refuses only what px_pose_check refuses. */
        return st != PX_OK ? st : PX_ERR_INTERNAL;
    }
    q->a = a;
    q->b = b;
    q->pa = pa;
    q->pb = pb;
    q->t_ab = pxi_relative(pb, pa);
    if (!pxi_is_finite3(q->t_ab.t)) return PX_ERR_NON_FINITE;
    /* With R^T R = I + E, |E| <= k, a distance measured in one body's
     * frame and in the other's differ by at most about 2k (|d| + the
     * bodies' reach from their origins) (docs/scene.md derives it for the
     * world frame). Exact rotations: k ~ 1e-16, a pad of ulps, which the
     * tie window covers (set_ub). */
    double k = ka + kb + 8.0 * DBL_EPSILON;
    double reach = pxi_len(a->nodes[0].center) + 3.0 * a->nodes[0].radius + pxi_len(b->nodes[0].center) +
                   3.0 * b->nodes[0].radius;
    q->frel = 4.0 * k;
    q->fpad = 2.0 * k * reach;
    q->tie_pad = 128.0 * DBL_EPSILON * (reach + pxi_len(q->t_ab.t));
    /* Both models in A's frame stay within the models' range. */
    if (!(pxi_max_abs(q->t_ab.t) <= PXI_MODEL_MAX_COORD)) return PX_ERR_RANGE;
    q->cache = cache;
    q->mc = cache_open(cache, a, b);
    q->kind = kind;
    /* Twice the roots' band: every node pair's band is below it (the centres
     * lie in their ancestors' spheres). */
    q->band = 2.0 * node_band(q, &a->nodes[0], &b->nodes[0]);
    set_ub(q, INFINITY);
    q->leaf_a = q->leaf_b = PXI_NONE;
    q->status = PX_OK;
    return PX_OK;
}

/* Measures the cache's previous best (distance) or hitting (boolean) leaf
 * pair first: its distance bounds the search, or its hit ends it. */
static void seed(qctx *q) {
    if (q->mc && q->mc->best_a < q->a->n_nodes && q->mc->best_b < q->b->n_nodes &&
        is_leaf(&q->a->nodes[q->mc->best_a]) && is_leaf(&q->b->nodes[q->mc->best_b])) {
        leaf_pair(q, q->mc->best_a, q->mc->best_b);
    }
}

static px_status run_distance(qctx *q, px_model_distance_result *out) {
    seed(q);
    if (q->status == PX_OK && q->ub > 0.0) descend(q);
    if (q->status != PX_OK) return q->status;
    if (q->leaf_a == PXI_NONE) return PX_ERR_INTERNAL;
    /* The best pair's node ids, for the next query's seed. */
    if (q->mc) {
        q->mc->best_a = q->node_a;
        q->mc->best_b = q->node_b;
    }
    out->distance = q->ub;
    const pxi_mleaf *la = &q->a->leaves[q->leaf_a], *lb = &q->b->leaves[q->leaf_b];
    out->upper_bound = q->ub + (q->ub > 0.0 ? la->h + lb->h : la->h_overlap + lb->h_overlap);
    out->point_a = q->pt_a;
    out->point_b = q->pt_b;
    out->leaf_a = q->leaf_a;
    out->leaf_b = q->leaf_b;
    out->feature_a = q->fa;
    out->feature_b = q->fb;
    out->node_pairs = q->node_pairs;
    out->leaf_pairs = q->leaf_pairs;
    out->diag = q->diag;
    return PX_OK;
}

static px_status run_boolean(qctx *q, px_model_collide_result *out) {
    seed(q);
    if (q->status == PX_OK && !q->hit) descend(q);
    if (q->status != PX_OK) return q->status;
    out->leaf_a = out->leaf_b = PXI_NONE;
    if (q->hit) {
        if (q->mc) {
            q->mc->best_a = q->node_a;
            q->mc->best_b = q->node_b;
        }
        out->hit = 1;
        out->leaf_a = q->leaf_a;
        out->leaf_b = q->leaf_b;
    } else if (contained(q, q->b, q->pb, q->a, q->pa) || contained(q, q->a, q->pa, q->b, q->pb)) {
        out->hit = 1;
        out->contained = 1;
    }
    out->node_pairs = q->node_pairs;
    out->leaf_pairs = q->leaf_pairs;
    out->diag = q->diag;
    return PX_OK;
}

static px_status model_distance(const px_model *a, const px_pose *pose_a, const px_model *b,
                                const px_pose *pose_b, px_model_cache *cache, px_model_distance_result *out) {
    if (out) memset(out, 0, sizeof *out);
    if (!out) return PX_ERR_INVALID_ARGUMENT;
    qctx q;
    px_status st = start(&q, a, pose_a, b, pose_b, cache, Q_DISTANCE);
    if (st == PX_OK) st = run_distance(&q, out);
    if (st != PX_OK) memset(out, 0, sizeof *out);
    return st;
}

/* Collide (kind Q_COLLIDE) and within (Q_WITHIN, `tol`): one descent. */
static px_status model_boolean(const px_model *a, const px_pose *pose_a, const px_model *b,
                               const px_pose *pose_b, px_model_cache *cache, px_model_collide_result *out,
                               int kind, double tol) {
    if (out) memset(out, 0, sizeof *out);
    if (!out) return PX_ERR_INVALID_ARGUMENT;
    qctx q;
    px_status st = start(&q, a, pose_a, b, pose_b, cache, kind);
    q.tol = tol;
    if (st == PX_OK) st = run_boolean(&q, out);
    if (st != PX_OK) memset(out, 0, sizeof *out);
    return st;
}

px_status px_model_distance(const px_model *a, const px_pose *pose_a, const px_model *b,
                            const px_pose *pose_b, px_model_cache *cache, px_model_distance_result *out) {
    return model_distance(a, pose_a, b, pose_b, cache, out);
}

px_status px_model_collide(const px_model *a, const px_pose *pose_a, const px_model *b, const px_pose *pose_b,
                           px_model_cache *cache, px_model_collide_result *out) {
    return model_boolean(a, pose_a, b, pose_b, cache, out, Q_COLLIDE, 0.0);
}

px_status px_model_within(const px_model *a, const px_pose *pose_a, const px_model *b, const px_pose *pose_b,
                          double tolerance, px_model_cache *cache, px_model_collide_result *out) {
    if (out) memset(out, 0, sizeof *out);
    if (!isfinite(tolerance) || tolerance < 0.0) return PX_ERR_INVALID_ARGUMENT;
    return model_boolean(a, pose_a, b, pose_b, cache, out, Q_WITHIN, tolerance);
}

/* A convex polytope seen as a model of one leaf, without allocating. */
typedef struct convex_view {
    px_model m;
    pxi_mnode node;
    pxi_mleaf leaf;
    px_vec3 rep;
} convex_view;

static px_status view_convex(convex_view *v, const px_convex *c) {
    if (!c) return PX_ERR_INVALID_ARGUMENT;
    memset(v, 0, sizeof *v);
    px_bounds bd;
    px_status st = px_convex_bounds(c, NULL, &bd);
    if (st != PX_OK) return st;
    v->node.center = bd.center;
    v->node.radius = bd.radius * (1.0 + 4.0 * DBL_EPSILON);
    v->node.child[0] = 0;
    v->node.child[1] = PXI_NONE;
    v->node.box = PXI_NONE;
    v->node.hull = (px_convex *)c;
    v->leaf.tri = PXI_NONE;
    px_convex_vertex(c, 0, &v->rep);
    v->m.uid = c->uid; /* the cache knows the view by its polytope */
    v->m.pieces = PX_PIECES_POINTS;
    v->m.n_nodes = v->m.n_leaves = 1;
    v->m.nodes = &v->node;
    v->m.leaves = &v->leaf;
    v->m.reps = &v->rep;
    v->m.n_reps = 1;
    v->m.lo = bd.min;
    v->m.hi = bd.max;
    return PX_OK;
}

px_status px_model_distance_convex(const px_model *a, const px_pose *pose_a, const px_convex *b,
                                   const px_pose *pose_b, px_model_cache *cache,
                                   px_model_distance_result *out) {
    if (out) memset(out, 0, sizeof *out);
    convex_view v;
    if (!out || view_convex(&v, b) != PX_OK) return PX_ERR_INVALID_ARGUMENT;
    return model_distance(a, pose_a, &v.m, pose_b, cache, out);
}

px_status px_model_collide_convex(const px_model *a, const px_pose *pose_a, const px_convex *b,
                                  const px_pose *pose_b, px_model_cache *cache,
                                  px_model_collide_result *out) {
    if (out) memset(out, 0, sizeof *out);
    convex_view v;
    if (!out || view_convex(&v, b) != PX_OK) return PX_ERR_INVALID_ARGUMENT;
    return model_boolean(a, pose_a, &v.m, pose_b, cache, out, Q_COLLIDE, 0.0);
}
