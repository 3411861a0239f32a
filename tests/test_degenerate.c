/* Lower-dimensional convex pieces (issue 9 §1): polygons, triangles,
 * segments and points, against each other and against solids, through
 * every query and every method.
 *
 * Oracles, all independent of src/ (they read a px_convex through the
 * public accessors only):
 *   - brute force over feature pairs: each piece is cut into simplices (a
 *     polygon into the triangles of a fan, a solid into the fans of its
 *     faces, a segment, a point) and the distance is the least distance of
 *     two simplices, 0 when a vertex of a piece lies inside a solid;
 *   - CGAL's exact Polytope_distance_d (check.h: tc_exact), which takes
 *     point sets of any dimension, on a subset of every shape pair;
 *   - a separating-axis oracle extended to flat pieces: the candidate axes
 *     are the face normals of both (a polygon's normal both ways), every
 *     edge-edge cross product, and for a segment or a point axes
 *     perpendicular to it (so that a flat A - B finds its own normal). The
 *     least support value h_{A-B}(n) over them is the penetration depth;
 *     over the same axes the line {tau d} enters B - A at
 *     max_{n.d<0} h_{B-A}(n) / (n.d) and leaves it at the min over n.d > 0
 *     (the translation oracle).
 * Per shape pair (ordered, 45 of them: 5 lower-dimensional kinds, a
 * 40-gon with a direction table among them, against 7 kinds) >= 1,000 random poses (PROXIMA_TEST_SCALE; fewer
 * under sanitizers), a quarter of them aligned (pieces in one plane, a polygon on a box's face plane) where
 * the degenerate contacts happen. On every pose: px_distance with each method, unsigned and signed,
 * px_intersect and px_translate (forward and both ways) along a random and an aimed direction.
 *
 * Then the construction itself: dimension, counts, Euler, validation,
 * bounds, exact duplicates, collinear points that are not exactly so, a
 * slab too thin for a solid. */
#include <float.h>

#include "check.h"
#include "pxcd.h"
#include "math/vec3.h"
#include "px_gen.h"
#include "test_util.h"

static const char *method_names[3] = {"lin-canny", "gjk", "hybrid"};

/* ---- A piece, read through the public accessors. ---- */

typedef struct piece {
    const char *name;
    px_convex *c;
    uint32_t dim, nv, ne, nf;
    px_vec3 *v;   /* body frame */
    uint32_t *ev; /* 2 * ne */
    /* simplices: triangles (3 ids) of the faces' fans, or for dim < 2 the
     * piece itself */
    uint32_t ntri;
    uint32_t *tri;
    px_vec3 *fn; /* body-frame face normals (accessor) */
    double *fd;
} piece;

static int piece_init(piece *p, const char *name, const double *xyz, size_t n) {
    memset(p, 0, sizeof *p);
    p->name = name;
    px_error err;
    p->c = px_convex_create(xyz, n, NULL, &err);
    CHECK(p->c != NULL, "%s: px_convex_create failed: %s", name, err.message);
    if (!p->c) return -1;
    p->dim = px_convex_dimension(p->c);
    p->nv = px_convex_vertex_count(p->c);
    p->ne = px_convex_edge_count(p->c);
    p->nf = px_convex_face_count(p->c);
    p->v = calloc(p->nv, sizeof *p->v);
    p->ev = calloc(2 * (size_t)p->ne + 1, sizeof *p->ev);
    p->fn = calloc(p->nf + 1, sizeof *p->fn);
    p->fd = calloc(p->nf + 1, sizeof *p->fd);
    for (uint32_t i = 0; i < p->nv; ++i) px_convex_vertex(p->c, i, &p->v[i]);
    for (uint32_t e = 0; e < p->ne; ++e) px_convex_edge(p->c, e, &p->ev[2 * e]);
    size_t cap = 0;
    for (uint32_t f = 0; f < p->nf; ++f) {
        uint32_t k;
        px_convex_face(p->c, f, &p->fn[f], &p->fd[f], &k);
        cap += k;
    }
    p->tri = calloc(3 * cap + 3, sizeof *p->tri);
    uint32_t nfan = p->dim == 2 ? 1 : p->nf; /* a polygon's two faces are one set */
    for (uint32_t f = 0; f < nfan; ++f) {
        uint32_t k, v0, v1, v2;
        px_convex_face(p->c, f, NULL, NULL, &k);
        px_convex_face_vertex(p->c, f, 0, &v0);
        for (uint32_t j = 1; j + 1 < k; ++j) {
            px_convex_face_vertex(p->c, f, j, &v1);
            px_convex_face_vertex(p->c, f, j + 1, &v2);
            p->tri[3 * p->ntri] = v0, p->tri[3 * p->ntri + 1] = v1, p->tri[3 * p->ntri + 2] = v2;
            p->ntri++;
        }
    }
    return 0;
}

static void piece_free(piece *p) {
    px_convex_destroy(p->c);
    free(p->v);
    free(p->ev);
    free(p->tri);
    free(p->fn);
    free(p->fd);
}

/* ---- Brute-force distance (world frame). ---- */

static px_vec3 xf(const px_pose *T, px_vec3 p) { return pxi_xform(T, p); }

/* Distance from p to triangle abc: the least of its three edges, and of
 * the plane when p's projection falls inside (sign tests about the normal).
 * Edges first: on a sliver, barycentric coordinates are ill conditioned
 * but the distances to its edges are not. */
static double pt_tri(px_vec3 p, px_vec3 a, px_vec3 b, px_vec3 c) {
    double d = fmin(or_pt_seg(p, a, b, NULL), fmin(or_pt_seg(p, b, c, NULL), or_pt_seg(p, c, a, NULL)));
    px_vec3 n = pxi_cross(pxi_sub(b, a), pxi_sub(c, a));
    double l = pxi_len(n);
    if (!(l > 0)) return d;
    n = pxi_scale(n, 1.0 / l);
    double s1 = pxi_dot(pxi_cross(pxi_sub(b, a), pxi_sub(p, a)), n);
    double s2 = pxi_dot(pxi_cross(pxi_sub(c, b), pxi_sub(p, b)), n);
    double s3 = pxi_dot(pxi_cross(pxi_sub(a, c), pxi_sub(p, c)), n);
    if (s1 >= 0 && s2 >= 0 && s3 >= 0) d = fmin(d, fabs(pxi_dot(pxi_sub(p, a), n)));
    return d;
}

/* 1 when segment pq crosses triangle abc transversally (strict signs). */
static int seg_crosses_tri(px_vec3 p, px_vec3 q, px_vec3 a, px_vec3 b, px_vec3 c) {
    px_vec3 n = pxi_cross(pxi_sub(b, a), pxi_sub(c, a));
    double hp = pxi_dot(n, pxi_sub(p, a)), hq = pxi_dot(n, pxi_sub(q, a));
    if (!((hp > 0 && hq < 0) || (hp < 0 && hq > 0))) return 0;
    px_vec3 x = pxi_add(p, pxi_scale(pxi_sub(q, p), hp / (hp - hq)));
    double s1 = pxi_dot(pxi_cross(pxi_sub(b, a), pxi_sub(x, a)), n);
    double s2 = pxi_dot(pxi_cross(pxi_sub(c, b), pxi_sub(x, b)), n);
    double s3 = pxi_dot(pxi_cross(pxi_sub(a, c), pxi_sub(x, c)), n);
    return (s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0);
}

/* A simplex: 1 to 3 world points. */
typedef struct simplex {
    int n;
    px_vec3 p[3];
    px_vec3 c; /* a bounding sphere, to prune pairs that cannot be closer */
    double r;
} simplex;

static void simplex_bound(simplex *s) {
    px_vec3 c = s->p[0];
    for (int i = 1; i < s->n; ++i) c = pxi_add(c, s->p[i]);
    s->c = pxi_scale(c, 1.0 / s->n);
    s->r = 0;
    for (int i = 0; i < s->n; ++i) s->r = fmax(s->r, pxi_len(pxi_sub(s->p[i], s->c)));
    s->r = s->r * (1 + 1e-9) + 1e-300;
}

static double pt_simplex(px_vec3 x, const simplex *s) {
    if (s->n == 1) return pxi_len(pxi_sub(x, s->p[0]));
    if (s->n == 2) return or_pt_seg(x, s->p[0], s->p[1], NULL);
    return pt_tri(x, s->p[0], s->p[1], s->p[2]);
}

static double simplex_distance(const simplex *s, const simplex *t) {
    double d = INFINITY;
    for (int i = 0; i < s->n; ++i) d = fmin(d, pt_simplex(s->p[i], t));
    for (int i = 0; i < t->n; ++i) d = fmin(d, pt_simplex(t->p[i], s));
    if (s->n >= 2 && t->n >= 2)
        for (int i = 0; i < (s->n == 3 ? 3 : 1); ++i)
            for (int j = 0; j < (t->n == 3 ? 3 : 1); ++j)
                d = fmin(
                    d, or_seg_seg(s->p[i], s->p[(i + 1) % s->n], t->p[j], t->p[(j + 1) % t->n], NULL, NULL));
    if (s->n == 3 && t->n >= 2)
        for (int j = 0; j < (t->n == 3 ? 3 : 1); ++j)
            if (seg_crosses_tri(t->p[j], t->p[(j + 1) % t->n], s->p[0], s->p[1], s->p[2])) d = 0.0;
    if (t->n == 3 && s->n >= 2)
        for (int i = 0; i < (s->n == 3 ? 3 : 1); ++i)
            if (seg_crosses_tri(s->p[i], s->p[(i + 1) % s->n], t->p[0], t->p[1], t->p[2])) d = 0.0;
    return d;
}

static int piece_simplices(const piece *p, const px_vec3 *w, simplex *out) {
    if (p->dim < 2) {
        out[0].n = (int)p->nv;
        for (uint32_t i = 0; i < p->nv; ++i) out[0].p[i] = w[i];
        simplex_bound(&out[0]);
        return 1;
    }
    for (uint32_t t = 0; t < p->ntri; ++t) {
        out[t].n = 3;
        for (int k = 0; k < 3; ++k) out[t].p[k] = w[p->tri[3 * t + k]];
        simplex_bound(&out[t]);
    }
    return (int)p->ntri;
}

/* max over faces of n . x - d (world): <= 0 inside a solid. */
static double solid_depth(const piece *p, const px_pose *pose, px_vec3 x) {
    px_vec3 q = pxi_sub(x, pose->t);
    q = pxi_rot_t(pose->r, q); /* body frame */
    double worst = -INFINITY;
    for (uint32_t f = 0; f < p->nf; ++f) worst = fmax(worst, pxi_dot(p->fn[f], q) - p->fd[f]);
    return worst;
}

/* World vertices of a piece at a pose (w: nv). */
static void world_vertices(const piece *p, const px_pose *pose, px_vec3 *w) {
    for (uint32_t i = 0; i < p->nv; ++i) w[i] = xf(pose, p->v[i]);
}

enum { MAXV = 64, MAXT = 256 };

static double brute_distance(const piece *a, const px_pose *pa, const piece *b, const px_pose *pb) {
    px_vec3 wa[MAXV], wb[MAXV];
    world_vertices(a, pa, wa);
    world_vertices(b, pb, wb);
    if (a->dim == 3 && b->dim < 3)
        for (uint32_t i = 0; i < b->nv; ++i)
            if (solid_depth(a, pa, wb[i]) <= 0.0) return 0.0;
    if (b->dim == 3 && a->dim < 3)
        for (uint32_t i = 0; i < a->nv; ++i)
            if (solid_depth(b, pb, wa[i]) <= 0.0) return 0.0;
    static simplex sa[MAXT], sb[MAXT];
    int na = piece_simplices(a, wa, sa), nb = piece_simplices(b, wb, sb);
    double d = INFINITY;
    for (int i = 0; i < na; ++i)
        for (int j = 0; j < nb; ++j)
            if (pxi_len(pxi_sub(sa[i].c, sb[j].c)) - sa[i].r - sb[j].r <= d)
                d = fmin(d, simplex_distance(&sa[i], &sb[j]));
    return d;
}

/* Distance from the world point x to the piece (0 inside a solid). */
static double brute_point_distance(const piece *p, const px_pose *pose, px_vec3 x) {
    if (p->dim == 3 && solid_depth(p, pose, x) <= 0.0) return 0.0;
    px_vec3 w[MAXV];
    world_vertices(p, pose, w);
    static simplex s[MAXT];
    int n = piece_simplices(p, w, s);
    double d = INFINITY;
    for (int i = 0; i < n; ++i)
        if (pxi_len(pxi_sub(x, s[i].c)) - s[i].r <= d) d = fmin(d, pt_simplex(x, &s[i]));
    return d;
}

/* ---- Separating axes, extended to flat pieces. ---- */

typedef struct axes {
    int n;
    px_vec3 a[16384];
} axes;

static void add_axis(axes *x, px_vec3 n, double min_len) {
    double l = pxi_len(n);
    if (x->n + 2 > (int)(sizeof x->a / sizeof x->a[0])) {
        CHECK(0, "separating axes: more than %d", x->n);
        return;
    }
    if (!(l > min_len)) return;
    x->a[x->n++] = pxi_scale(n, 1.0 / l);
    x->a[x->n++] = pxi_scale(n, -1.0 / l);
}

static void collect_axes(const piece *a, const px_pose *pa, const piece *b, const px_pose *pb, axes *x) {
    x->n = 0;
    const piece *ps[2] = {a, b};
    const px_pose *qs[2] = {pa, pb};
    static const px_vec3 ex[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (int s = 0; s < 2; ++s) {
        const piece *p = ps[s];
        for (uint32_t f = 0; f < p->nf; ++f) add_axis(x, pxi_rot(qs[s]->r, p->fn[f]), 0.5);
        if (p->dim == 1) { /* perpendicular to the segment */
            px_vec3 u = pxi_rot(qs[s]->r, pxi_sub(p->v[1], p->v[0]));
            for (int k = 0; k < 3; ++k) add_axis(x, pxi_cross(u, ex[k]), 1e-3 * pxi_len(u));
        }
        if (p->dim == 0)
            for (int k = 0; k < 3; ++k) add_axis(x, ex[k], 0.5);
    }
    for (uint32_t i = 0; i < a->ne; ++i) {
        px_vec3 ua = pxi_rot(pa->r, pxi_sub(a->v[a->ev[2 * i + 1]], a->v[a->ev[2 * i]]));
        for (uint32_t j = 0; j < b->ne; ++j) {
            px_vec3 ub = pxi_rot(pb->r, pxi_sub(b->v[b->ev[2 * j + 1]], b->v[b->ev[2 * j]]));
            add_axis(x, pxi_cross(ua, ub), 1e-14 * pxi_len(ua) * pxi_len(ub));
        }
    }
}

/* h_{A-B}(n) = max_a a.n - min_b b.n, measured from `o` (a point near the pair). */
static double support_diff(const piece *a, const px_vec3 *wa, const piece *b, const px_vec3 *wb, px_vec3 n,
                           px_vec3 o) {
    double ha = -INFINITY, lb = INFINITY;
    for (uint32_t i = 0; i < a->nv; ++i) ha = fmax(ha, pxi_dot(pxi_sub(wa[i], o), n));
    for (uint32_t i = 0; i < b->nv; ++i) lb = fmin(lb, pxi_dot(pxi_sub(wb[i], o), n));
    return ha - lb;
}

/* Least h_{A-B} over the axes: the depth when positive. */
static double sat_depth(const piece *a, const px_pose *pa, const piece *b, const px_pose *pb,
                        px_vec3 *best_n) {
    static axes x;
    collect_axes(a, pa, b, pb, &x);
    px_vec3 wa[MAXV], wb[MAXV];
    world_vertices(a, pa, wa);
    world_vertices(b, pb, wb);
    double best = INFINITY;
    for (int k = 0; k < x.n; ++k) {
        double h = support_diff(a, wa, b, wb, x.a[k], pb->t);
        if (h < best) best = h, *best_n = x.a[k];
    }
    return best;
}

/* The interval of tau over which A + tau d meets B (B - A over the axes):
 * [lo, hi], empty when lo > hi. `slack` receives the least |n.d| used
 * relative to |d| (grazing lines are skipped by the caller). */
static void sat_translation(const piece *a, const px_pose *pa, const piece *b, const px_pose *pb, px_vec3 d,
                            double *lo, double *hi, double *parallel_gap) {
    static axes x;
    collect_axes(a, pa, b, pb, &x);
    px_vec3 wa[MAXV], wb[MAXV];
    world_vertices(a, pa, wa);
    world_vertices(b, pb, wb);
    *lo = -INFINITY;
    *hi = INFINITY;
    *parallel_gap = -INFINITY;
    double dl = pxi_len(d);
    for (int k = 0; k < x.n; ++k) {
        px_vec3 n = x.a[k];
        double h = support_diff(b, wb, a, wa, n, pb->t); /* h_{B-A}(n) */
        double nd = pxi_dot(n, d);
        if (fabs(nd) <= 1e-12 * dl) {
            *parallel_gap = fmax(*parallel_gap, -h);
            if (h < 0) *lo = INFINITY; /* the line misses */
        } else if (nd < 0) {
            *lo = fmax(*lo, h / nd);
        } else {
            *hi = fmin(*hi, h / nd);
        }
    }
}

/* ---- Shapes. All lower-dimensional ones lie in z = 0 of their body
 * frame (so that poses turning about z and moving in z = 0 keep two of
 * them in one plane), the segment along a line of that plane. ---- */

enum { K_TRI, K_POLY, K_BIGPOLY, K_SEG, K_PT, K_BOX, K_HULL, K_COUNT };
static const char *kind_names[K_COUNT] = {"triangle", "polygon", "40-gon", "segment", "point", "box", "hull"};

static int make_kind(piece *p, int kind, pg_rng *rng) {
    double xyz[3 * 64];
    size_t n = 0;
    switch (kind) {
    case K_TRI:
        for (int i = 0; i < 3; ++i) xyz[3 * i] = pg_range(rng, -1, 1), xyz[3 * i + 1] = pg_range(rng, -1, 1);
        for (int i = 0; i < 3; ++i) xyz[3 * i + 2] = 0;
        n = 3;
        break;
    case K_POLY: /* points of a disc, some inside: the polygon of the extreme ones */
        n = 20;
        for (size_t i = 0; i < n; ++i) {
            double t = pg_range(rng, 0, 2 * M_PI), r = i < 12 ? 1.0 : pg_range(rng, 0, 1);
            xyz[3 * i] = r * cos(t), xyz[3 * i + 1] = 0.7 * r * sin(t), xyz[3 * i + 2] = 0;
        }
        break;
    case K_BIGPOLY: /* 40 points of an ellipse: a polygon with a direction table (>= 24 vertices) */
        n = 40;
        for (size_t i = 0; i < n; ++i) {
            double t = 2 * M_PI * ((double)i + pg_range(rng, 0, 0.5)) / (double)n;
            xyz[3 * i] = cos(t), xyz[3 * i + 1] = 0.4 * sin(t), xyz[3 * i + 2] = 0;
        }
        break;
    case K_SEG: { /* collinear exactly: small integers along (3, 1, 0) */
        n = 6;
        for (size_t i = 0; i < n; ++i) {
            double k = (double)pg_below(rng, 9) - 4;
            xyz[3 * i] = 0.25 * (3 * k + 1), xyz[3 * i + 1] = 0.25 * (k - 2), xyz[3 * i + 2] = 0;
        }
        xyz[0] = 0.25 * (3 * -4 + 1), xyz[1] = 0.25 * (-4 - 2); /* both ends present */
        xyz[3] = 0.25 * (3 * 4 + 1), xyz[4] = 0.25 * (4 - 2);
        break;
    }
    case K_PT:
        n = 3; /* one point, repeated */
        for (size_t i = 0; i < n; ++i) xyz[3 * i] = 0.125, xyz[3 * i + 1] = -0.25, xyz[3 * i + 2] = 0;
        break;
    case K_BOX:
        pg_box(0.6, 0.4, 0.5, xyz);
        n = 8;
        break;
    default:
        n = 30;
        pg_points_ball(rng, n, 0.8, xyz);
        break;
    }
    return piece_init(p, kind_names[kind], xyz, n);
}

/* ---- The pose loop. ---- */

typedef struct stats {
    long poses, queries, exact_checked, pen_checked, tr_checked, intersect_checked;
    double worst_brute[3], worst_exact[3], worst_depth[3], worst_tau;
    long fallbacks[3];
} stats;
static stats g;

static double rel(double err, double size) { return err / size; }

/* Pose of B: random, or aligned with A (same plane; for a solid, a face
 * plane z = 0.5 of the box against the pieces' plane z = 0). */
static void make_poses(pg_rng *rng, const piece *a, const piece *b, int aligned, px_pose *pa, px_pose *pb) {
    double span = 1.2;
    if (!aligned) {
        *pa = pg_pose_random(rng, 0.5);
        *pb = pg_pose_random(rng, span);
        return;
    }
    double ra[9], rb[9];
    pg_rot_axis_angle(pxi_v(0, 0, 1), pg_range(rng, 0, 2 * M_PI), ra);
    pg_rot_axis_angle(pxi_v(0, 0, 1), pg_range(rng, 0, 2 * M_PI), rb);
    px_vec3 ta = pxi_v(pg_range(rng, -0.3, 0.3), pg_range(rng, -0.3, 0.3), 0);
    px_vec3 tb = pxi_v(pg_range(rng, -span, span), pg_range(rng, -span, span), 0);
    /* a box B rests on A's plane with its face z = -0.5 (or A's on B's) */
    if (b->dim == 3) tb.z = 0.5;
    if (a->dim == 3) ta.z = -0.5;
    memcpy(pa->r, ra, sizeof ra);
    memcpy(pb->r, rb, sizeof rb);
    pa->t = ta;
    pb->t = tb;
    (void)a;
}

static void check_pose(const piece *a, const piece *b, const px_pose *pa, const px_pose *pb, pg_rng *rng,
                       int exact, px_pair_cache caches[3]) {
    double size = tc_scale(a->c, pa, b->c, pb);
    double tol = 1e-12 * size; /* classification band around touching */
    double bd = brute_distance(a, pa, b, pb);
    double ed = -1.0;
    int ez = 0;
    if (exact) {
        CHECK(tc_exact(a->c, pa, b->c, pb, &ed, &ez) == 0, "exact oracle failed");
        g.exact_checked++;
    }
    px_vec3 sat_n = {0, 0, 0};
    double depth = bd <= tol ? sat_depth(a, pa, b, pb, &sat_n) : 0.0;
    g.poses++;
    for (int m = 0; m < 3; ++m) {
        px_query_options opt = {0};
        opt.method = (uint32_t)m;
        for (int sgn = 0; sgn < 2; ++sgn) {
            opt.flags = sgn ? PX_QUERY_SIGNED : 0;
            px_distance_result r;
            px_pair_cache *cache = (g.poses & 1) ? &caches[m] : NULL; /* warm from a stale pair or cold */
            px_status st = px_distance(a->c, pa, b->c, pb, &opt, cache, &r);
            g.queries++;
            g.fallbacks[m] += r.diag.fallbacks;
            if (getenv("PROXIMA_TEST_DEBUG") && r.diag.fallbacks)
                fprintf(stderr, "fallback %s/%s %s%s: d %.3g brute %.3g intersecting %d quality %u\n",
                        a->name, b->name, method_names[m], sgn ? " signed" : "", r.distance, bd,
                        r.intersecting, r.diag.quality);
            CHECK(st == PX_OK, "%s/%s %s: status %s", a->name, b->name, method_names[m],
                  px_status_string(st));
            if (st != PX_OK) continue;
            CHECK(isfinite(r.distance) && isfinite(r.signed_distance) && pxi_is_finite3(r.point_a) &&
                      pxi_is_finite3(r.point_b) && pxi_is_finite3(r.normal),
                  "%s/%s %s: non-finite result", a->name, b->name, method_names[m]);
            double e = fabs(r.distance - bd);
            if (rel(e, size) > g.worst_brute[m]) g.worst_brute[m] = rel(e, size);
            CHECK(e <= tol, "%s/%s %s%s: distance %.17g, brute force %.17g (size %.3g)", a->name, b->name,
                  method_names[m], sgn ? " signed" : "", r.distance, bd, size);
            if (exact) {
                double ee = fabs(r.distance - ed);
                if (rel(ee, size) > g.worst_exact[m]) g.worst_exact[m] = rel(ee, size);
                CHECK(ee <= 64 * DBL_EPSILON * size || (ez && r.intersecting),
                      "%s/%s %s: distance %.17g, exact %.17g", a->name, b->name, method_names[m], r.distance,
                      ed);
            }
            if (bd > 2 * tol || bd == 0.0)
                CHECK(r.intersecting == (bd <= tol), "%s/%s %s: intersecting %d, brute distance %.3g",
                      a->name, b->name, method_names[m], r.intersecting, bd);
            if (!r.intersecting) {
                double w = pxi_len(pxi_sub(r.point_b, r.point_a));
                CHECK(fabs(w - r.distance) <= tol, "%s/%s %s: witnesses %.17g apart, distance %.17g", a->name,
                      b->name, method_names[m], w, r.distance);
                /* the witnesses lie on their pieces */
                double ona = fabs(brute_point_distance(a, pa, r.point_a)),
                       onb = fabs(brute_point_distance(b, pb, r.point_b));
                CHECK(ona <= tol && onb <= tol, "%s/%s %s: witnesses off their pieces by %.3g, %.3g", a->name,
                      b->name, method_names[m], ona, onb);
                if (getenv("PROXIMA_TEST_DEBUG") && !(ona <= tol && onb <= tol)) {
                    for (uint32_t i = 0; i < a->nv; ++i) {
                        px_vec3 wv = xf(pa, a->v[i]);
                        fprintf(stderr, "  A v%u %.17g %.17g %.17g\n", i, wv.x, wv.y, wv.z);
                    }
                    fprintf(stderr, "  pa %.17g %.17g %.17g  d %.17g fa %u:%u fb %u:%u\n", r.point_a.x,
                            r.point_a.y, r.point_a.z, r.distance, r.feature_a.type, r.feature_a.index,
                            r.feature_b.type, r.feature_b.index);
                }
            }
            if (sgn && r.intersecting && bd <= tol) {
                g.pen_checked++;
                double dd = fabs(-r.signed_distance - depth);
                if (rel(dd, size) > g.worst_depth[m]) g.worst_depth[m] = rel(dd, size);
                CHECK(dd <= 1e-9 * size, "%s/%s %s: depth %.17g, separating axes %.17g", a->name, b->name,
                      method_names[m], -r.signed_distance, depth);
                if (r.signed_distance < 0) {
                    /* moving A by signed_distance * normal makes the pair touch */
                    px_pose moved = *pa;
                    moved.t = pxi_madd(moved.t, r.normal, r.signed_distance * (1 + 1e-9) - 1e-12 * size);
                    double after = brute_distance(a, &moved, b, pb);
                    CHECK(after <= 2e-9 * size, "%s/%s %s: pushed out by the depth, %.3g apart", a->name,
                          b->name, method_names[m], after);
                    px_vec3 nn;
                    double left = m == 0 ? sat_depth(a, &moved, b, pb, &nn) : 0.0; /* once per pose */
                    CHECK(left <= 2e-9 * size, "%s/%s %s: pushed out by the depth, still %.3g deep", a->name,
                          b->name, method_names[m], left);
                }
            }
        }
        /* px_intersect by this method */
        px_query_options io = {0};
        io.method = (uint32_t)m;
        px_intersect_result ir;
        px_status st = px_intersect(a->c, pa, b->c, pb, &io, NULL, &ir);
        CHECK(st == PX_OK, "intersect status %s", px_status_string(st));
        if (bd > 2 * tol || bd == 0.0) {
            g.intersect_checked++;
            CHECK(ir.intersecting == (bd <= tol), "%s/%s %s: px_intersect %d, brute distance %.3g", a->name,
                  b->name, method_names[m], ir.intersecting, bd);
        }
    }
    /* Translation: a random direction and one aimed from A at B. */
    for (int k = 0; k < 2; ++k) {
        px_vec3 d = k == 0 ? pg_unit(rng) : pxi_add(pxi_sub(pb->t, pa->t), pxi_scale(pg_unit(rng), 0.3));
        if (!(pxi_len(d) > 1e-3)) continue;
        double lo, hi, pgap;
        sat_translation(a, pa, b, pb, d, &lo, &hi, &pgap);
        for (int both = 0; both < 2; ++both) {
            px_query_options to = {0};
            to.flags = both ? PX_QUERY_BOTH_WAYS : 0;
            px_translate_result tr;
            px_status st = px_translate(a->c, pa, b->c, pb, d, &to, NULL, &tr);
            CHECK(st == PX_OK, "translate status %s", px_status_string(st));
            if (st != PX_OK) continue;
            double dl = pxi_len(d), ttol = 1e-9 * size / dl;
            /* the oracle's answer, where it is clear of ties */
            int oracle_hit = lo <= hi;
            double want = both ? lo : (hi < 0 ? INFINITY : fmax(lo, 0.0));
            if (!both && hi < 0) oracle_hit = 0;
            int clear =
                fabs(hi - lo) > 4 * ttol && (both || fabs(hi) > 4 * ttol) && isfinite(lo) == isfinite(hi);
            if (clear && lo <= hi) {
                g.tr_checked++;
                CHECK(tr.hit == oracle_hit, "%s/%s translate%s: hit %d, oracle [%.17g, %.17g]", a->name,
                      b->name, both ? " both ways" : "", tr.hit, lo, hi);
                if (tr.hit && oracle_hit) {
                    double e = fabs(tr.tau - want) * dl;
                    if (rel(e, size) > g.worst_tau) g.worst_tau = rel(e, size);
                    CHECK(e <= 1e-9 * size, "%s/%s translate%s: tau %.17g, oracle %.17g", a->name, b->name,
                          both ? " both ways" : "", tr.tau, want);
                }
            } else if (clear && lo > hi + 4 * ttol) {
                g.tr_checked++;
                CHECK(!tr.hit, "%s/%s translate%s: hit at %.17g, oracle misses [%.17g, %.17g]", a->name,
                      b->name, both ? " both ways" : "", tr.tau, lo, hi);
            }
            if (tr.hit) {
                /* the distance check: touching at tau, apart a little before */
                px_pose at = *pa;
                at.t = pxi_madd(at.t, d, tr.tau);
                double d_at = brute_distance(a, &at, b, pb);
                CHECK(d_at <= 1e-9 * size, "%s/%s translate: %.3g apart at tau", a->name, b->name, d_at);
                double back = 1e-6 * size / dl;
                if (!tr.in_contact && tr.tau > 2 * back) {
                    px_pose before = *pa;
                    before.t = pxi_madd(before.t, d, tr.tau - back);
                    double d_before = brute_distance(a, &before, b, pb);
                    CHECK(
                        d_before > 0.0 || lo >= hi - 4 * ttol,
                        "%s/%s translate%s: touching before tau %.17g (oracle [%.17g, %.17g], in contact %d, "
                        "d %g %g %g)",
                        a->name, b->name, both ? " both ways" : "", tr.tau, lo, hi, tr.in_contact, d.x, d.y,
                        d.z);
                }
            } else if (!tr.in_contact) {
                /* the miss certificate: A below the plane, B above it */
                px_vec3 wa[MAXV], wb[MAXV];
                world_vertices(a, pa, wa);
                world_vertices(b, pb, wb);
                double worst = -INFINITY;
                for (uint32_t i = 0; i < a->nv; ++i)
                    worst = fmax(worst, pxi_dot(tr.normal, pxi_sub(wa[i], tr.point_a)));
                for (uint32_t i = 0; i < b->nv; ++i)
                    worst = fmax(worst, -pxi_dot(tr.normal, pxi_sub(wb[i], tr.point_b)));
                /* n . d <= 0 up to the rounding of a normal made orthogonal
                 * to d (test_translation's 1e-9) */
                CHECK(tr.gap > 0 && worst <= 1e-12 * size && pxi_dot(tr.normal, d) <= 1e-9 * dl,
                      "%s/%s translate%s: miss certificate gap %.3g, worst %.3g, n.d %.3g, quality %u, "
                      "oracle [%.17g, "
                      "%.17g]",
                      a->name, b->name, both ? " both ways" : "", tr.gap, worst, pxi_dot(tr.normal, d),
                      tr.diag.quality, lo, hi);
            }
        }
    }
}

static void test_pairs(void) {
    int poses = tu_scaled(tu_sanitized() ? 150 : 1000);
    int exact_every = tu_sanitized() ? 50 : 10;
    pg_rng rng;
    pg_seed(&rng, 9001);
    double t0 = tu_now();
    int pairs = 0;
    for (int ka = 0; ka < K_COUNT; ++ka)
        for (int kb = 0; kb < K_COUNT; ++kb) {
            if (ka >= K_BOX && kb >= K_BOX) continue; /* solid pairs: the other suites */
            pairs++;
            px_pair_cache caches[3];
            memset(caches, 0, sizeof caches);
            for (int i = 0; i < poses; ++i) {
                piece a, b;
                if (make_kind(&a, ka, &rng) || make_kind(&b, kb, &rng)) return;
                px_pose pa, pb;
                make_poses(&rng, &a, &b, i % 4 == 3, &pa, &pb);
                check_pose(&a, &b, &pa, &pb, &rng, i % exact_every == 0, caches);
                piece_free(&a);
                piece_free(&b);
            }
        }
    printf("  %d shape pairs x %d poses: %ld poses, %ld distance queries, %ld exact, %ld depths, %ld "
           "intersects, %ld translations checked (%.1f s)\n",
           pairs, poses, g.poses, g.queries, g.exact_checked, g.pen_checked, g.intersect_checked,
           g.tr_checked, tu_now() - t0);
    for (int m = 0; m < 3; ++m)
        printf(
            "  %-9s worst |d - brute| %.2g S, |d - exact| %.2g eps S, |depth - SAT| %.2g S, fallbacks %ld\n",
            method_names[m], g.worst_brute[m], g.worst_exact[m] / DBL_EPSILON, g.worst_depth[m],
            g.fallbacks[m]);
    printf("  translation worst |tau - oracle| %.2g S\n", g.worst_tau);
}

/* ---- Fixed configurations where lower-dimensional contacts happen. ---- */

static px_pose pose_at(double x, double y, double z) {
    px_pose p = px_pose_identity();
    p.t = pxi_v(x, y, z);
    return p;
}

/* One fixed pair through every oracle of check_pose, plus the answers
 * known in closed form: the distance (< 0: do not check), and for an
 * overlapping pair whose A - B is flat, signed distance 0 with the pair
 * touching. */
static void special(const char *what, const double *xa, size_t na, const double *xb, size_t nb, px_pose pa,
                    px_pose pb, double want_d, int flat_overlap) {
    piece a, b;
    if (piece_init(&a, what, xa, na) || piece_init(&b, what, xb, nb)) return;
    pg_rng rng;
    pg_seed(&rng, 77);
    px_pair_cache caches[3];
    memset(caches, 0, sizeof caches);
    check_pose(&a, &b, &pa, &pb, &rng, 1, caches);
    for (int m = 0; m < 3; ++m) {
        px_query_options opt = {0};
        opt.method = (uint32_t)m;
        opt.flags = PX_QUERY_SIGNED;
        px_distance_result r;
        px_distance(a.c, &pa, b.c, &pb, &opt, NULL, &r);
        if (want_d >= 0)
            CHECK(fabs(r.distance - want_d) <= 1e-15 * (1 + want_d), "%s %s: distance %.17g, want %.17g",
                  what, method_names[m], r.distance, want_d);
        if (flat_overlap)
            CHECK(r.intersecting && r.signed_distance == 0.0 && pxi_max_abs(r.normal) == 0.0 &&
                      pxi_len(pxi_sub(r.point_a, r.point_b)) == 0.0,
                  "%s %s: flat overlap gives intersecting %d, signed distance %.3g, normal %g %g %g", what,
                  method_names[m], r.intersecting, r.signed_distance, r.normal.x, r.normal.y, r.normal.z);
    }
    piece_free(&a);
    piece_free(&b);
}

static void test_special(void) {
    const double tri[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const double tri2[9] = {0.5, 0.5, 0, 1.5, 0.5, 0, 0.5, 1.5, 0};
    const double seg[6] = {-1, 0, 0, 1, 0, 0};
    const double segz[6] = {0, 0, -1, 0, 0, 1};
    const double pt[3] = {0.25, 0.25, 0};
    double box[24];
    pg_box(0.6, 0.4, 0.5, box);
    px_pose id = px_pose_identity();
    /* coplanar overlaps: A - B flat, depth 0 */
    special("triangle on itself", tri, 3, tri, 3, id, id, 0, 1);
    special("coplanar overlapping triangles", tri, 3, tri2, 3, id, id, 0, 1);
    special("coplanar triangles sharing a vertex", tri, 3, tri2, 3, id, pose_at(0.5, -0.5, 0), 0, 1);
    special("coplanar triangles apart", tri, 3, tri, 3, id, pose_at(1.5, 0, 0), 0.5, 0);
    special("point in a triangle", pt, 1, tri, 3, id, id, 0, 1);
    special("point above a triangle", pt, 1, tri, 3, pose_at(0, 0, 0.75), id, 0.75, 0);
    special("point on a segment", pt, 1, seg, 2, id, pose_at(0, 0.25, 0), 0, 1);
    special("point on itself", pt, 1, pt, 1, id, id, 0, 1);
    special("two points", pt, 1, pt, 1, id, pose_at(3, 4, 0), 5, 0);
    special("collinear segments overlapping", seg, 2, seg, 2, id, pose_at(1.5, 0, 0), 0, 1);
    special("collinear segments end to end", seg, 2, seg, 2, id, pose_at(2, 0, 0), 0, 1);
    special("collinear segments apart", seg, 2, seg, 2, id, pose_at(2.5, 0, 0), 0.5, 0);
    special("parallel segments", seg, 2, seg, 2, id, pose_at(0.5, 0.75, 0), 0.75, 0);
    special("crossing segments", seg, 2, segz, 2, id, id, 0, 1);
    special("skew segments", seg, 2, segz, 2, id, pose_at(0, 0.5, 0), 0.5, 0);
    special("segment in a triangle's plane across it", seg, 2, tri, 3, pose_at(0.3, 0.2, 0), id, 0, 1);
    special("segment through a triangle", segz, 2, tri, 3, pose_at(0.2, 0.2, 0), id, 0, 0);
    special("segment along a triangle's edge", seg, 2, tri, 3, pose_at(0.5, 0, 0), id, 0, 1);
    special("point inside a box", pt, 1, box, 8, id, id, 0, 0);
    special("point on a box face", pt, 1, box, 8, pose_at(0, 0, 0.5), id, 0, 0);
    special("point at a box corner", pt, 1, box, 8, pose_at(0.6 - 0.25, 0.4 - 0.25, 0.5), id, 0, 0);
    special("triangle resting on a box", tri, 3, box, 8, pose_at(-0.2, -0.2, 0.5), id, 0, 0);
    special("triangle above a box", tri, 3, box, 8, pose_at(-0.2, -0.2, 0.875), id, 0.375, 0);
    special("triangle through a box", tri, 3, box, 8, pose_at(-0.2, -0.2, 0.25), id, 0, 0);
    special("segment inside a box", seg, 2, box, 8, pose_at(0, 0, 0.125), pose_at(0, 0, 0), 0, 0);
    special("segment through a box", segz, 2, box, 8, id, id, 0, 0);
    special("segment along a box edge", seg, 2, box, 8, pose_at(0, 0.4, 0.5), id, 0, 0);
    special("box on a triangle", box, 8, tri, 3, pose_at(0.1, 0.1, 0.5), id, 0, 0);
    /* overlapping triangles crossing at small angles: A - B is a solid
     * thinner and thinner, its depth shrinking with the angle (separating
     * axes check it; at 1e-14 rad it is flat within rounding: depth 0) */
    static const double tilts[4] = {1e-2, 1e-6, 1e-10, 1e-14};
    for (int k = 0; k < 4; ++k) {
        px_pose tilted = pose_at(-0.1, -0.1, 0);
        pg_rot_axis_angle(pxi_v(1, 1, 0), tilts[k], tilted.r);
        special("triangles crossing at a small angle", tri, 3, tri2, 3, id, tilted, 0, 0);
    }
}

/* Construction: dimension, Euler, validation, bounds, and the inputs at
 * the edge of flatness. */
static void test_construction(void) {
    pg_rng rng;
    pg_seed(&rng, 4242);
    for (int kind = K_TRI; kind <= K_PT; ++kind)
        for (int i = 0; i < 20; ++i) {
            piece p;
            if (make_kind(&p, kind, &rng)) return;
            static const uint32_t want_dim[5] = {2, 2, 2, 1, 0};
            CHECK(p.dim == want_dim[kind], "%s: dimension %u", p.name, p.dim);
            long euler = (long)p.nv - (long)p.ne + (long)p.nf;
            CHECK(euler == (p.dim >= 2 ? 2 : 1), "%s: V - E + F = %ld", p.name, euler);
            px_error err;
            CHECK(px_convex_validate(p.c, &err) == PX_OK, "%s: %s", p.name, err.message);
            /* bounds against the world vertices */
            px_pose pose = pg_pose_random(&rng, 3);
            px_bounds bb;
            CHECK(px_convex_bounds(p.c, &pose, &bb) == PX_OK, "%s: bounds", p.name);
            px_vec3 lo = {INFINITY, INFINITY, INFINITY}, hi = {-INFINITY, -INFINITY, -INFINITY};
            double r = 0;
            for (uint32_t k = 0; k < p.nv; ++k) {
                px_vec3 w = xf(&pose, p.v[k]);
                lo = pxi_v(fmin(lo.x, w.x), fmin(lo.y, w.y), fmin(lo.z, w.z));
                hi = pxi_v(fmax(hi.x, w.x), fmax(hi.y, w.y), fmax(hi.z, w.z));
                r = fmax(r, pxi_len(pxi_sub(w, bb.center)));
            }
            CHECK(pxi_max_abs(pxi_sub(lo, bb.min)) <= 1e-15 * 4 &&
                      pxi_max_abs(pxi_sub(hi, bb.max)) <= 1e-15 * 4 && r <= bb.radius * (1 + 1e-12) + 1e-15,
                  "%s: bounds off", p.name);
            if (p.dim == 2) {
                px_vec3 n0, n1;
                double d0, d1;
                px_convex_face(p.c, 0, &n0, &d0, NULL);
                px_convex_face(p.c, 1, &n1, &d1, NULL);
                CHECK(n0.x == -n1.x && n0.y == -n1.y && n0.z == -n1.z && d0 == -d1,
                      "%s: the two faces are not one plane turned over", p.name);
            }
            piece_free(&p);
        }
    /* exact duplicates: a triangle given 4 times over is a triangle */
    double dup[36];
    const double tri[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    for (int k = 0; k < 4; ++k) memcpy(dup + 9 * k, tri, sizeof tri);
    px_convex *c = px_convex_create(dup, 12, NULL, NULL);
    CHECK(c && px_convex_dimension(c) == 2 && px_convex_vertex_count(c) == 3, "triangle four times");
    px_convex_destroy(c);
    /* collinear but for one ulp: CGAL says a (sliver) triangle, and its
     * distances still agree with brute force and the exact oracle */
    double sliver[9] = {0, 0, 0, 1, 1, 1, 2, 2, nextafter(2.0, 3.0)};
    piece s;
    if (piece_init(&s, "one-ulp sliver", sliver, 3) == 0) {
        CHECK(s.dim == 2, "one-ulp sliver: dimension %u", s.dim);
        piece bx;
        double box[24];
        pg_box(0.6, 0.4, 0.5, box);
        if (piece_init(&bx, "box", box, 8) == 0) {
            px_pair_cache caches[3];
            memset(caches, 0, sizeof caches);
            for (int i = 0; i < 200; ++i) {
                px_pose pa = pg_pose_random(&rng, 0.5), pb = pg_pose_random(&rng, 2.0);
                check_pose(&s, &bx, &pa, &pb, &rng, i % 10 == 0, caches);
                check_pose(&bx, &s, &pb, &pa, &rng, 0, caches);
            }
            piece_free(&bx);
        }
        piece_free(&s);
    }
    /* random slivers: the third point on the line of the first two, then
     * one coordinate moved by an ulp. CGAL says a segment or a triangle;
     * either is built (never refused) and answers right. */
    int built = 0;
    for (int i = 0; i < 100; ++i) {
        double sl[9];
        for (int k = 0; k < 6; ++k) sl[k] = pg_range(&rng, -1, 1);
        double t = pg_range(&rng, 0.1, 0.9);
        for (int k = 0; k < 3; ++k) sl[6 + k] = sl[k] + t * (sl[3 + k] - sl[k]);
        int which = (int)pg_below(&rng, 3);
        sl[6 + which] = nextafter(sl[6 + which], pg_below(&rng, 2) ? 2.0 : -2.0);
        piece q;
        px_error e2;
        px_convex *cq = px_convex_create(sl, 3, NULL, &e2);
        CHECK(cq != NULL, "sliver %d refused: %s", i, e2.message);
        px_convex_destroy(cq);
        if (!cq || piece_init(&q, "random sliver", sl, 3)) continue;
        built++;
        CHECK(px_convex_validate(q.c, &e2) == PX_OK, "sliver %d: %s", i, e2.message);
        piece bx;
        double box2[24];
        pg_box(0.6, 0.4, 0.5, box2);
        if (piece_init(&bx, "box", box2, 8) == 0) {
            px_pair_cache caches[3];
            memset(caches, 0, sizeof caches);
            for (int k = 0; k < 10; ++k) {
                px_pose pa = pg_pose_random(&rng, 0.5), pb = pg_pose_random(&rng, 2.0);
                check_pose(&q, &bx, &pa, &pb, &rng, k == 0, caches);
            }
            piece_free(&bx);
        }
        piece_free(&q);
    }
    CHECK(built == 100, "slivers built: %d of 100", built);
    /* a slab thinner than double precision resolves: its two sides round
     * to one plane, so the input is coplanar and the piece a polygon */
    double slab[24];
    for (int i = 0; i < 8; ++i)
        slab[3 * i] = (i & 1), slab[3 * i + 1] = (i & 2) ? 1 : 0, slab[3 * i + 2] = (i & 4) ? 1 + 1e-17 : 1;
    c = px_convex_create(slab, 8, NULL, NULL);
    CHECK(c && px_convex_dimension(c) == 2 && px_convex_vertex_count(c) == 4, "slab 1e-17 thick: a square");
    px_convex_destroy(c);
    /* a point anywhere in the double range has no size: accepted */
    const double far[3] = {1e300, -1e300, 5};
    c = px_convex_create(far, 1, NULL, NULL);
    px_vec3 v;
    CHECK(c && px_convex_dimension(c) == 0 && px_convex_vertex(c, 0, &v) == PX_OK && v.x == 1e300 &&
              v.y == -1e300,
          "a point at 1e300");
    px_convex_destroy(c);
    /* a segment shorter than the supported range: PX_ERR_RANGE */
    const double tiny[6] = {0, 0, 0, 1e-310, 0, 0};
    px_error err;
    tu_untrap_fp();
    c = px_convex_create(tiny, 2, NULL, &err);
    tu_trap_fp();
    CHECK(!c && err.code == PX_ERR_RANGE, "a 1e-310 segment: %s", px_status_string(err.code));
}

/* Near contact: from a random separated pose, B moved along the closest
 * points' direction until the gap is size * 10^-k (k = 16, 14, .., 2) or
 * exactly closed; every method against the exact distance, and the
 * intersecting flags (px_distance, px_intersect) against it outside the
 * contact band. */
static void test_near_contact(void) {
    int poses = tu_scaled(tu_sanitized() ? 2 : 12);
    pg_rng rng;
    pg_seed(&rng, 9002);
    long checked = 0;
    double worst[3] = {0, 0, 0};
    for (int ka = K_TRI; ka <= K_PT; ++ka)
        for (int kb = 0; kb < K_COUNT; ++kb)
            for (int i = 0; i < poses; ++i) {
                piece a, b;
                if (make_kind(&a, ka, &rng) || make_kind(&b, kb, &rng)) return;
                px_pose pa = pg_pose_random(&rng, 0.5), pb = pg_pose_random(&rng, 2.5);
                px_distance_result r0;
                px_distance(a.c, &pa, b.c, &pb, NULL, NULL, &r0);
                if (!r0.intersecting && r0.distance > 0) {
                    px_vec3 n = pxi_scale(pxi_sub(r0.point_b, r0.point_a), 1.0 / r0.distance);
                    for (int k = 16; k >= 0; k -= 2) {
                        double size = tc_scale(a.c, &pa, b.c, &pb);
                        double gap = k == 0 ? 0.0 : size * pow(10.0, -k);
                        px_pose q = pb;
                        q.t = pxi_madd(pb.t, n, gap - r0.distance);
                        double ed;
                        int ez;
                        if (tc_exact(a.c, &pa, b.c, &q, &ed, &ez) != 0) continue;
                        double s2 = tc_scale(a.c, &pa, b.c, &q);
                        /* the contact band of query.h, from the bounds' centres and radii */
                        px_bounds ba, bb;
                        px_convex_bounds(a.c, &pa, &ba);
                        px_convex_bounds(b.c, &q, &bb);
                        double band = 64 * DBL_EPSILON *
                                      (ba.radius + bb.radius + pxi_len(pxi_sub(ba.center, bb.center)));
                        checked++;
                        for (int m = 0; m < 3; ++m) {
                            px_query_options opt = {0};
                            opt.method = (uint32_t)m;
                            px_distance_result r;
                            px_distance(a.c, &pa, b.c, &q, &opt, NULL, &r);
                            double e = fabs(r.distance - ed) / s2;
                            if (e > worst[m] && !(r.intersecting && ed <= band)) worst[m] = e;
                            CHECK(fabs(r.distance - ed) <= 64 * DBL_EPSILON * s2 ||
                                      (r.intersecting && ed <= band),
                                  "%s/%s %s near contact 1e-%d: distance %.17g, exact %.17g", a.name, b.name,
                                  method_names[m], k, r.distance, ed);
                            px_intersect_result ir;
                            px_intersect(a.c, &pa, b.c, &q, &opt, NULL, &ir);
                            if (ez || ed > 2 * band)
                                CHECK(r.intersecting == ez && ir.intersecting == ez,
                                      "%s/%s %s near contact 1e-%d: intersecting %d / %d, exact %.3g", a.name,
                                      b.name, method_names[m], k, r.intersecting, ir.intersecting, ed);
                        }
                    }
                }
                piece_free(&a);
                piece_free(&b);
            }
    printf("  near contact: %ld poses against the exact distance, worst |d - exact| %.2g / %.2g / %.2g eps S "
           "(lin-canny / gjk / hybrid)\n",
           checked, worst[0] / DBL_EPSILON, worst[1] / DBL_EPSILON, worst[2] / DBL_EPSILON);
}

/* Tracked motion: B moves by small steps (a hundredth of its size, a
 * hundredth of a radian) with one cache per method; every answer against
 * brute force. */
static void test_motion(void) {
    int seqs = tu_scaled(tu_sanitized() ? 1 : 4), steps = 40;
    pg_rng rng;
    pg_seed(&rng, 9003);
    long queries = 0, fallbacks[3] = {0, 0, 0};
    for (int ka = K_TRI; ka <= K_PT; ++ka)
        for (int kb = 0; kb < K_COUNT; ++kb)
            for (int sq = 0; sq < seqs; ++sq) {
                piece a, b;
                if (make_kind(&a, ka, &rng) || make_kind(&b, kb, &rng)) return;
                px_pose pa = pg_pose_random(&rng, 0.3), pb = pg_pose_random(&rng, 1.5);
                px_pair_cache caches[3];
                memset(caches, 0, sizeof caches);
                px_vec3 drift = pxi_scale(pg_unit(&rng), 0.01);
                for (int st = 0; st < steps; ++st) {
                    double turn[9];
                    pg_rot_axis_angle(pg_unit(&rng), 0.01, turn);
                    pg_mat_mul(turn, pb.r, pb.r);
                    pb.t = pxi_add(pb.t, drift);
                    if (pxi_len(pxi_sub(pb.t, pa.t)) > 2.5) drift = pxi_neg(drift);
                    double bd = brute_distance(&a, &pa, &b, &pb), size = tc_scale(a.c, &pa, b.c, &pb);
                    for (int m = 0; m < 3; ++m) {
                        px_query_options opt = {0};
                        opt.method = (uint32_t)m;
                        px_distance_result r;
                        px_distance(a.c, &pa, b.c, &pb, &opt, &caches[m], &r);
                        queries++;
                        fallbacks[m] += r.diag.fallbacks;
                        CHECK(fabs(r.distance - bd) <= 1e-12 * size,
                              "%s/%s %s tracked step %d: %.17g, brute %.17g", a.name, b.name, method_names[m],
                              st, r.distance, bd);
                    }
                }
                piece_free(&a);
                piece_free(&b);
            }
    printf("  tracked: %ld queries, fallbacks %ld / %ld / %ld\n", queries, fallbacks[0], fallbacks[1],
           fallbacks[2]);
}

/* The contact band (query.h) with a point above a triangle: a gap of a
 * quarter band is touching (flagged), four bands apart is not; the same
 * for every method, px_intersect and the forward translation. */
static void test_band(void) {
    const double tri[9] = {-1, -1, 0, 1, -1, 0, 0, 1, 0};
    const double pt[3] = {0, 0, 0};
    px_convex *t = px_convex_create(tri, 3, NULL, NULL), *p = px_convex_create(pt, 1, NULL, NULL);
    CHECK(t && p, "band pieces");
    if (!t || !p) return;
    px_pose pt_pose = px_pose_identity(), tri_pose = px_pose_identity();
    for (int far = 0; far < 2; ++far) {
        px_bounds ba, bb;
        pt_pose.t = pxi_v(0, 0, 0.5);
        px_convex_bounds(p, &pt_pose, &ba);
        px_convex_bounds(t, &tri_pose, &bb);
        double band = 64 * DBL_EPSILON * (ba.radius + bb.radius + pxi_len(pxi_sub(ba.center, bb.center)));
        double h = far ? 4 * band : 0.25 * band;
        pt_pose.t = pxi_v(0, 0, h);
        for (int m = 0; m < 3; ++m) {
            px_query_options opt = {0};
            opt.method = (uint32_t)m;
            px_distance_result r;
            px_distance(p, &pt_pose, t, &tri_pose, &opt, NULL, &r);
            CHECK(r.intersecting == !far && (far || (r.diag.quality & PX_QUALITY_CONTACT_BAND)) &&
                      (!far || fabs(r.distance - h) <= 1e-15 * h),
                  "band %s at %s: intersecting %d, distance %.3g, quality %u", method_names[m],
                  far ? "4 bands" : "band/4", r.intersecting, r.distance, r.diag.quality);
            px_intersect_result ir;
            px_intersect(p, &pt_pose, t, &tri_pose, &opt, NULL, &ir);
            CHECK(ir.intersecting == !far, "band %s: px_intersect %d at %s", method_names[m], ir.intersecting,
                  far ? "4 bands" : "band/4");
        }
        px_translate_result tr;
        px_translate(p, &pt_pose, t, &tri_pose, pxi_v(1, 0, 0), NULL, NULL, &tr);
        CHECK(tr.in_contact == !far, "band: translation in contact %d at %s", tr.in_contact,
              far ? "4 bands" : "band/4");
    }
    px_convex_destroy(t);
    px_convex_destroy(p);
}

/* Scale: every coordinate and translation times 2^k (|k| up to 900),
 * with the bodies' coordinates also offset by 2^40 of their size: the
 * distances and tau scale bit for bit, as for solids (test_range). */
static void scaled_xyz(const piece *p, double f, px_vec3 off, double *xyz) {
    for (uint32_t i = 0; i < p->nv; ++i) {
        xyz[3 * i] = (p->v[i].x + off.x) * f;
        xyz[3 * i + 1] = (p->v[i].y + off.y) * f;
        xyz[3 * i + 2] = (p->v[i].z + off.z) * f;
    }
}

static void test_scale(void) {
    pg_rng rng;
    pg_seed(&rng, 9004);
    static const int ks[4] = {-900, -300, 300, 900};
    long compared = 0;
    for (int ka = K_TRI; ka <= K_PT; ++ka)
        for (int kb = 0; kb < K_COUNT; ++kb)
            for (int i = 0; i < 3; ++i) {
                piece a, b;
                if (make_kind(&a, ka, &rng) || make_kind(&b, kb, &rng)) return;
                px_pose pa = pg_pose_random(&rng, 0.5), pb = pg_pose_random(&rng, 2.0);
                px_vec3 off = i == 2 ? pxi_v(0x1p40, -0x1p40, 0x1p39) : pxi_v(0, 0, 0);
                double xa[3 * MAXV], xb[3 * MAXV];
                px_distance_result r1[3];
                px_translate_result t1;
                memset(&t1, 0, sizeof t1);
                memset(r1, 0, sizeof r1);
                px_vec3 dir = pxi_sub(pb.t, pa.t);
                /* unscaled, with the same offset (the offset is moved back by the pose) */
                for (int pass = 0; pass < 5; ++pass) {
                    double f = pass == 0 ? 1.0 : ldexp(1.0, ks[pass - 1]);
                    scaled_xyz(&a, f, off, xa);
                    scaled_xyz(&b, f, off, xb);
                    px_convex *ca = px_convex_create(xa, a.nv, NULL, NULL),
                              *cb = px_convex_create(xb, b.nv, NULL, NULL);
                    CHECK(ca && cb, "scale 2^%d: pieces not built", pass ? ks[pass - 1] : 0);
                    if (ca && cb) {
                        px_pose qa = pa, qb = pb;
                        /* the offset o is undone by the pose: t' = f (t - R o) */
                        qa.t = pxi_scale(pxi_sub(pa.t, pxi_rot(pa.r, off)), f);
                        qb.t = pxi_scale(pxi_sub(pb.t, pxi_rot(pb.r, off)), f);
                        for (int m = 0; m < 3; ++m) {
                            px_query_options opt = {0};
                            opt.method = (uint32_t)m;
                            opt.flags = PX_QUERY_SIGNED;
                            px_distance_result r;
                            px_distance(ca, &qa, cb, &qb, &opt, NULL, &r);
                            if (pass == 0) {
                                r1[m] = r;
                            } else {
                                compared++;
                                CHECK(r.distance == ldexp(r1[m].distance, ks[pass - 1]) &&
                                          r.signed_distance == ldexp(r1[m].signed_distance, ks[pass - 1]) &&
                                          r.intersecting == r1[m].intersecting,
                                      "%s/%s %s at 2^%d: distance %.17g, unscaled %.17g", a.name, b.name,
                                      method_names[m], ks[pass - 1], ldexp(r.distance, -ks[pass - 1]),
                                      r1[m].distance);
                            }
                        }
                        px_translate_result t;
                        px_translate(ca, &qa, cb, &qb, dir, NULL, NULL, &t);
                        if (pass == 0)
                            t1 = t;
                        else
                            CHECK(t.hit == t1.hit && t.tau == ldexp(t1.tau, ks[pass - 1]),
                                  "%s/%s translate at 2^%d: hit %d tau %.17g, unscaled %d %.17g", a.name,
                                  b.name, ks[pass - 1], t.hit, ldexp(t.tau, -ks[pass - 1]), t1.hit, t1.tau);
                    }
                    px_convex_destroy(ca);
                    px_convex_destroy(cb);
                }
                piece_free(&a);
                piece_free(&b);
            }
    printf("  scale: %ld answers at 2^-900..2^900 compared bit for bit with the unscaled ones\n", compared);
}

/* Plates turned into place (review s29): k points of a convex polygon in
 * the xy plane, turned by a random rotation and moved by up to 1e3, are
 * off their plane by rounding, and CGAL's exact predicates call most of
 * them a solid too thin for double precision (629 of 1000 unit squares were
 * refused). Every one must now be accepted (a polygon, or a solid when its
 * planes hold), and its distance to a box placed across, at and near its
 * plane must be the exact distance between the input points' hull and the
 * box (CGAL's Polytope_distance_d, on the points as given), with every
 * method, to within 1e-12 of the pair's size and place. */
static void test_turned_plates(void) {
    pg_rng rng;
    pg_seed(&rng, 0x91a7e5);
    const double cube[24] = {-0.3, -0.3, -0.3, 0.3, -0.3, -0.3, -0.3, 0.3, -0.3, 0.3, 0.3, -0.3,
                             -0.3, -0.3, 0.3,  0.3, -0.3, 0.3,  -0.3, 0.3, 0.3,  0.3, 0.3, 0.3};
    px_convex *box = px_convex_create(cube, 8, NULL, NULL);
    const int n_plates = tu_scaled(600);
    int refused = 0, polygons = 0, segments = 0, worst_at = -1;
    double worst = 0;
    for (int it = 0; it < n_plates; ++it) {
        /* every fourth a rod: 3 to 7 points along x */
        const int rod = it % 4 == 3, k = rod ? 3 + it % 5 : 3 + it % 10;
        double local[36], xyz[36], r[9];
        for (int i = 0; i < k; ++i) {
            const double phi = 2 * M_PI * (i + 0.4 * pg_uniform(&rng)) / k;
            local[3 * i] = rod ? pg_range(&rng, -1, 1) : cos(phi), local[3 * i + 1] = rod ? 0 : sin(phi);
            local[3 * i + 2] = 0;
        }
        pg_rot_random(&rng, r);
        static const double offsets[3] = {0, 1, 1e3};
        const double off = offsets[it % 3];
        const px_vec3 t = {pg_range(&rng, -off, off), pg_range(&rng, -off, off), pg_range(&rng, -off, off)};
        for (int i = 0; i < k; ++i) {
            const px_vec3 p = pxi_add(pg_rot_apply(r, pxi_v(local[3 * i], local[3 * i + 1], 0)), t);
            xyz[3 * i] = p.x, xyz[3 * i + 1] = p.y, xyz[3 * i + 2] = p.z;
        }
        px_error err;
        px_convex *plate = px_convex_create(xyz, (size_t)k, NULL, &err);
        if (!plate) {
            if (refused++ < 3)
                CHECK(0, "plate %d (%d corners, offset %g) refused: %s", it, k, off, err.message);
            continue;
        }
        polygons += px_convex_dimension(plate) == 2;
        segments += px_convex_dimension(plate) == 1;
        /* The box's centre over a point of the plate, at a height along the
         * plate's normal: across it, touching it, or just above. */
        static const double heights[5] = {0.0, 0.3, 0.3 + 1e-9, 0.31, 0.8};
        const px_vec3 normal = pg_rot_apply(r, pxi_v(0, 0, 1));
        const px_vec3 over =
            pxi_add(pg_rot_apply(r, pxi_v(pg_range(&rng, -0.5, 0.5), pg_range(&rng, -0.5, 0.5), 0)), t);
        px_pose pb;
        pg_rot_random(&rng, r);
        if (it % 2) memcpy(r, (double[9]){1, 0, 0, 0, 1, 0, 0, 0, 1}, sizeof r);
        pb = pg_pose_centred(r, pxi_v(0, 0, 0), pxi_add(over, pxi_scale(normal, heights[it % 5])));
        const px_pose pa = px_pose_identity();
        double boxw[24];
        for (int i = 0; i < 8; ++i) {
            const px_vec3 p = pxi_xform(&pb, pxi_v(cube[3 * i], cube[3 * i + 1], cube[3 * i + 2]));
            boxw[3 * i] = p.x, boxw[3 * i + 1] = p.y, boxw[3 * i + 2] = p.z;
        }
        double exact, exact2;
        int zero;
        char msg[200];
        if (pxcd_exact_distance(xyz, (size_t)k, boxw, 8, &exact, &exact2, &zero, NULL, NULL, msg,
                                sizeof msg) != PXCD_OK) {
            CHECK(0, "exact oracle: %s", msg);
            px_convex_destroy(plate);
            continue;
        }
        const double size = 1 + 0.3 * sqrt(3.0) + pxi_max_abs(t) + exact;
        for (int m = 0; m < 3; ++m) {
            px_query_options o = {0};
            o.method = m == 0 ? PX_METHOD_LIN_CANNY : m == 1 ? PX_METHOD_GJK : PX_METHOD_HYBRID;
            px_distance_result res;
            CHECK(px_distance(plate, &pa, box, &pb, &o, NULL, &res) == PX_OK, "distance");
            const double e = fabs(res.distance - exact) / size;
            if (e > worst) worst = e, worst_at = it;
        }
        px_convex_destroy(plate);
    }
    printf(
        "turned plates and rods: %d of %d polygons, %d segments, %d refused; distance off the exact by up to "
        "%.3g of size (plate %d)\n",
        polygons, n_plates, segments, refused, worst, worst_at);
    CHECK(refused == 0, "%d of %d turned plates refused", refused, n_plates);
    CHECK(worst <= 1e-12, "a turned plate's distance off the exact by %.3g of the size (plate %d)", worst,
          worst_at);
    px_convex_destroy(box);
}

/* Review s31's two needles 1e-6 wide, turned (hex: the exact doubles), each
 * with a tetrahedron: px_translate along Lin-Canny's normal hit 8e4 eps too
 * early and 3.8e3 eps too late (the ray cast's final plane was a sliver's). */
static const double needle_pairs[2][2][24] = {
    {{-0x1.f9427b2fb1507p-2, -0x1.0fbb29f58bd7bp-5, -0x1.2e1228721904bp-4, -0x1.f942808e92287p-2,
      -0x1.0fb914f14a9f3p-5, -0x1.2e1210954d6d8p-4, -0x1.f942849e1f905p-2, -0x1.0fbb5f64984b5p-5,
      -0x1.2e1120054b1p-4,   -0x1.f94289fd00685p-2, -0x1.0fb94a605712dp-5, -0x1.2e1108287f78dp-4,
      0x1.f94289fd00685p-2,  0x1.0fb94a605712dp-5,  0x1.2e1108287f78dp-4,  0x1.f942849e1f905p-2,
      0x1.0fbb5f64984b5p-5,  0x1.2e1120054b1p-4,    0x1.f942808e92287p-2,  0x1.0fb914f14a9f3p-5,
      0x1.2e1210954d6d8p-4,  0x1.f9427b2fb1507p-2,  0x1.0fbb29f58bd7bp-5,  0x1.2e1228721904bp-4},
     {-0x1.2197d7a55656ep-1, 0x1.ae95379ce64aep-6, -0x1.6ec35df04504p-3, -0x1.5ffb742474cccp-1,
      -0x1.f08e4ff2b3e21p-4, -0x1.1b385bf776f96p-3, -0x1.57490867c90f4p-1, 0x1.d8a65a1a8ef0cp-6,
      -0x1.c93d663ce25f8p-7, -0x1.0becb031642a1p-1, -0x1.930180f7774f6p-4, -0x1.19ae72d88fcf4p-5}},
    {{0x1.114a8ac0968a3p-2,  -0x1.b0d34e38a5c87p-2, -0x1.5bbf2b51d5aa7p-7, 0x1.114a95fd5c1bep-2,
      -0x1.b0d3457aad64fp-2, -0x1.5bc75deb37e7dp-7, 0x1.114a532077e7ep-2,  -0x1.b0d370fcf58ebp-2,
      -0x1.5bc0f0a129f83p-7, 0x1.114a5e5d3d799p-2,  -0x1.b0d3683efd2b3p-2, -0x1.5bc9233a8c359p-7,
      -0x1.114a5e5d3d799p-2, 0x1.b0d3683efd2b3p-2,  0x1.5bc9233a8c359p-7,  -0x1.114a532077e7ep-2,
      0x1.b0d370fcf58ebp-2,  0x1.5bc0f0a129f83p-7,  -0x1.114a95fd5c1bep-2, 0x1.b0d3457aad64fp-2,
      0x1.5bc75deb37e7dp-7,  -0x1.114a8ac0968a3p-2, 0x1.b0d34e38a5c87p-2,  0x1.5bbf2b51d5aa7p-7},
     {0x1.b7e6797c16e0bp-2, -0x1.37ced847a58a2p-1, 0x1.876b1952f8202p-5, 0x1.8c23bf6e4b31ap-2,
      -0x1.c55e54d65fbf3p-2, -0x1.3ad1205d1b122p-5, 0x1.fde65e009bdap-3, -0x1.165481d11600ap-1,
      0x1.94aec1014d388p-5, 0x1.4dfac62f4b2bdp-2, -0x1.3793a0c3f6baap-1, -0x1.d34a678a26ce4p-4}},
};

/* Review s31's two needles 1e-9 wide, 2.36e-10 apart (CGAL): the hybrid's
 * segment-through-triangle test took them for crossing (a sliver's plain
 * normal). */
static const double needles_apart[2][24] = {
    {-0x1.2f7f76001c0eep-4, 0x1.f9e16de2ece68p-2,  0x1.5b9278f44e80bp-6,  -0x1.2f7f7611ea829p-4,
     0x1.f9e16de18c327p-2,  0x1.5b9279fce1295p-6,  -0x1.2f7f7641b233bp-4, 0x1.f9e16de0a9edfp-2,
     0x1.5b9278aaaa56bp-6,  -0x1.2f7f765380a76p-4, 0x1.f9e16ddf4939ep-2,  0x1.5b9279b33cff5p-6,
     0x1.2f7f765380a76p-4,  -0x1.f9e16ddf4939ep-2, -0x1.5b9279b33cff5p-6, 0x1.2f7f7641b233bp-4,
     -0x1.f9e16de0a9edfp-2, -0x1.5b9278aaaa56bp-6, 0x1.2f7f7611ea829p-4,  -0x1.f9e16de18c327p-2,
     -0x1.5b9279fce1295p-6, 0x1.2f7f76001c0eep-4,  -0x1.f9e16de2ece68p-2, -0x1.5b9278f44e80bp-6},
    {0x1.3793a2d7e5b3p-3,   -0x1.9435bbe38992ap-2, -0x1.b01ac7dcef006p-6, 0x1.3793a2d064a12p-3,
     -0x1.9435bbe6b267p-2,  -0x1.b01ac8087ccfbp-6, 0x1.3793a2d47d80dp-3,  -0x1.9435bbe5b7f28p-2,
     -0x1.b01ac78edbe2bp-6, 0x1.3793a2ccfc6eep-3,  -0x1.9435bbe8e0c7p-2,  -0x1.b01ac7ba69b21p-6,
     -0x1.1c6aac1f5c364p-4, -0x1.40d0df315f9dap-3, 0x1.6168f1bc5a2a4p-9,  -0x1.1c6aac2e5e5a2p-4,
     -0x1.40d0df37b1468p-3, 0x1.6168f05febafcp-9,  -0x1.1c6aac262c9adp-4, -0x1.40d0df35bc5d7p-3,
     0x1.6168f42cf3174p-9,  -0x1.1c6aac352ebeap-4, -0x1.40d0df3c0e066p-3, 0x1.6168f2d0849bcp-9}};

/* Review s31's needles 1e-9 wide and a direction along which, both ways,
 * the ray cast stopped at its rounding floor and its refined plane put the
 * entry 2.9e-7 late (0.8 of the width along the normal); CGAL's touching
 * interval starts at -1.8487188653253122e-06. */
static const double needles_both[2][24] = {
    {-0x1.46a9ed3b1f005p-5, 0x1.4e0a5d751ab0ep-2,  -0x1.81de0b61829c8p-2, -0x1.46a9edadbb0fep-5,
     0x1.4e0a5d7b786c1p-2,  -0x1.81de0b5a7bac6p-2, -0x1.46a9ed862e48ep-5, 0x1.4e0a5d69bf373p-2,
     -0x1.81de0b6a59672p-2, -0x1.46a9edf8ca587p-5, 0x1.4e0a5d701cf26p-2,  -0x1.81de0b635277p-2,
     0x1.46a9edf8ca587p-5,  -0x1.4e0a5d701cf26p-2, 0x1.81de0b635277p-2,   0x1.46a9ed862e48ep-5,
     -0x1.4e0a5d69bf373p-2, 0x1.81de0b6a59672p-2,  0x1.46a9edadbb0fep-5,  -0x1.4e0a5d7b786c1p-2,
     0x1.81de0b5a7bac6p-2,  0x1.46a9ed3b1f005p-5,  -0x1.4e0a5d751ab0ep-2, 0x1.81de0b61829c8p-2},
    {-0x1.8efb958eeef1ep-3, 0x1.490a043579c89p-3,  -0x1.671ca47a3b00ep-3, -0x1.8efb958d0ba5ap-3,
     0x1.490a042bd444p-3,   -0x1.671ca4732ceefp-3, -0x1.8efb958fd3d67p-3, 0x1.490a042e3d41ep-3,
     -0x1.671ca483e2caep-3, -0x1.8efb958df08a3p-3, 0x1.490a042497bd5p-3,  -0x1.671ca47cd4b8ep-3,
     0x1.375c7867138a2p-3,  0x1.83c3318670317p-3,  -0x1.d4e70c423cb61p-3, 0x1.375c7868f6d67p-3,
     0x1.83c3317ccaacdp-3,  -0x1.d4e70c3b2ea42p-3, 0x1.375c78662ea59p-3,  0x1.83c3317f33aacp-3,
     -0x1.d4e70c4be4801p-3, 0x1.375c786811f1dp-3,  0x1.83c331758e262p-3,  -0x1.d4e70c44d66e2p-3}};
static const double needles_both_dir[3] = {-0x1.fddb1a874d92fp-3, 0x1.389398cc012bbp+0,
                                           -0x1.67fb1d40aa7c2p+0};

static void test_needle_translations(void) {
    double worst = 0;
    for (int c = 0; c < 2; ++c) {
        const double *p = needle_pairs[c][0], *q = needle_pairs[c][1];
        px_convex *a = px_convex_create(p, 8, NULL, NULL), *b = px_convex_create(q, 4, NULL, NULL);
        double exact;
        int zero;
        char msg[200];
        CHECK(a && b &&
                  pxcd_exact_distance(p, 8, q, 4, &exact, NULL, &zero, NULL, NULL, msg, sizeof msg) ==
                      PXCD_OK,
              "needle pair %d", c);
        if (a && b) {
            const px_pose id = px_pose_identity();
            px_distance_result d;
            CHECK(px_distance(a, &id, b, &id, NULL, NULL, &d) == PX_OK, "distance");
            for (int m = 0; m < 3; ++m) {
                px_query_options o = {0};
                o.method = (uint32_t)m;
                px_translate_result tr;
                CHECK(px_translate(a, &id, b, &id, d.normal, &o, NULL, &tr) == PX_OK && tr.hit, "translate");
                worst = fmax(worst, fabs(tr.tau - exact) / (DBL_EPSILON * 1.0));
            }
        }
        px_convex_destroy(a);
        px_convex_destroy(b);
    }
    px_convex *a = px_convex_create(needles_apart[0], 8, NULL, NULL),
              *b = px_convex_create(needles_apart[1], 8, NULL, NULL);
    double exact;
    int zero;
    char msg[200];
    CHECK(a && b &&
              pxcd_exact_distance(needles_apart[0], 8, needles_apart[1], 8, &exact, NULL, &zero, NULL, NULL,
                                  msg, sizeof msg) == PXCD_OK,
          "needles apart");
    for (int m = 0; a && b && m < 3; ++m) {
        const px_pose id = px_pose_identity();
        px_query_options o = {0};
        o.method = (uint32_t)m;
        px_distance_result d;
        px_intersect_result x;
        CHECK(px_distance(a, &id, b, &id, &o, NULL, &d) == PX_OK && !d.intersecting &&
                  fabs(d.distance - exact) <= 8 * DBL_EPSILON,
              "needles apart, method %d: distance %.17g (exact %.17g), intersecting %d", m, d.distance, exact,
              d.intersecting);
        CHECK(px_intersect(a, &id, b, &id, &o, NULL, &x) == PX_OK && !x.intersecting,
              "needles apart, method %d: px_intersect says they meet", m);
    }
    px_convex_destroy(a);
    px_convex_destroy(b);
    a = px_convex_create(needles_both[0], 8, NULL, NULL),
    b = px_convex_create(needles_both[1], 8, NULL, NULL);
    const px_vec3 dir = {needles_both_dir[0], needles_both_dir[1], needles_both_dir[2]};
    /* from where it starts, and from 1e3 back along the line (review s31:
     * the band of the start pose, which counts the distance, put the entry
     * 2e3 bands early) */
    for (int k = 0; a && b && k < 6; ++k) {
        const int m = k % 3;
        const double back = k < 3 ? 0.0 : 1e3;
        const px_pose id = px_pose_identity();
        px_pose pa = id;
        pa.t = pxi_scale(dir, -back);
        px_query_options o = {0};
        o.method = (uint32_t)m;
        o.flags = PX_QUERY_BOTH_WAYS;
        px_translate_result tr;
        CHECK(px_translate(a, &pa, b, &id, dir, &o, NULL, &tr) == PX_OK && tr.hit, "needles both ways");
        /* (1e3 back, the moved points carry rounding of 1e-13: 32 eps of the
         * shift is the allowance; the bug was 2.7e-11) */
        const double tau = tr.tau - back, allow = back > 0.0 ? 32 * DBL_EPSILON * back : 256 * DBL_EPSILON;
        double moved[24];
        for (int i = 0; i < 8; ++i) {
            moved[3 * i] = needles_both[0][3 * i] + tau * dir.x;
            moved[3 * i + 1] = needles_both[0][3 * i + 1] + tau * dir.y;
            moved[3 * i + 2] = needles_both[0][3 * i + 2] + tau * dir.z;
        }
        CHECK(pxcd_exact_distance(moved, 8, needles_both[1], 8, &exact, NULL, &zero, NULL, NULL, msg,
                                  sizeof msg) == PXCD_OK &&
                  exact <= allow && tau <= -1.8487188653253122e-06 + 1e-9,
              "needles both ways, method %d, from %g back: tau %.17g (the interval starts at "
              "-1.8487188653253122e-06), %.3g apart there",
              m, back, tau, exact);
    }
    px_convex_destroy(a);
    px_convex_destroy(b);
    printf("review s31's needles: time of impact off the distance by up to %.3g eps\n", worst);
    CHECK(worst <= 16, "a needle's time of impact off the exact distance by %.3g eps", worst);
}

/* Solid plates 1 x 1 x t turned into place (t = 1e-3 .. 1e-7): their
 * side faces are slivers of aspect t. Before the normals came from
 * accurate cross products (convex.c polygon_normal, simplex.c sx_sliver,
 * hybrid.c pt_tri), 40 % of the plates at 1e-5 were refused as too thin
 * (a reflex edge from a tilted normal), and beside a side face Lin-Canny
 * was 200 eps of the size off at 1e-3 and 1e4 at 1e-5, GJK 1e5 at 1e-6. A
 * tetrahedron's apex is put beside a side face (in its plane, or just off
 * it) at a gap up to 0.02; every method must give the exact distance
 * between the input points' hulls (CGAL) to within 8 eps of the size, and
 * A translated along each method's normal must touch B at tau = that
 * distance within 256 eps (review s31: the ray cast's final plane was a
 * sliver's, 8e4 eps off on a needle, test_needle_translations; and a
 * tetrahedron's side test against a sliver face held the origin inside
 * 1.7e-12 outside it, 2.3e4 eps early on a slab). Needles t x 1 x t the same (review s31: half of
 * those 1e-9 thick and below were refused, every face inward, from a
 * volume summed in plain double). */
static void test_turned_slabs(void) {
    pg_rng rng;
    pg_seed(&rng, 0x5eab1e);
    static const double thick[5] = {1e-3, 1e-4, 1e-5, 1e-6, 1e-7};
    const int per = tu_scaled(120);
    int refused = 0, worst_at = -1, worst_tau_at[2] = {-1, -1};
    double worst = 0, worst_tau[2] = {0, 0}; /* slabs, needles */
    for (int it = 0; it < 10 * per; ++it) {
        const double t = thick[it % 5];
        const int needle = it % 10 >= 5; /* t x 1 x t, its long side faces x = +-t/2 */
        double r[9], p[24], q[12];
        pg_rot_random(&rng, r);
        for (int i = 0; i < 8; ++i) {
            const double x = needle ? 0.5 * t : 0.5;
            const px_vec3 w =
                pg_rot_apply(r, pxi_v(i & 1 ? x : -x, i & 2 ? 0.5 : -0.5, i & 4 ? 0.5 * t : -0.5 * t));
            p[3 * i] = w.x, p[3 * i + 1] = w.y, p[3 * i + 2] = w.z;
        }
        const double y0 = pg_range(&rng, -0.5, 0.5), gap = pg_range(&rng, 0, 0.02),
                     z0 = it % 3 == 0 ? 0 : pg_range(&rng, -1.5 * t, 1.5 * t);
        const px_vec3 tet[4] = {{0.5 + gap, y0, z0},
                                {0.8 + gap, y0 + 0.1, z0 + 0.1},
                                {0.8 + gap, y0 - 0.1, z0 + 0.1},
                                {0.8 + gap, y0, z0 - 0.1}};
        for (int i = 0; i < 4; ++i) {
            const px_vec3 w = pg_rot_apply(r, tet[i]);
            q[3 * i] = w.x, q[3 * i + 1] = w.y, q[3 * i + 2] = w.z;
        }
        px_error err;
        px_convex *a = px_convex_create(p, 8, NULL, &err), *b = px_convex_create(q, 4, NULL, NULL);
        if (!a || !b) {
            if (refused++ < 3)
                CHECK(0, "slab %d (t %g) refused: %s", it, t, a ? "(the tetrahedron)" : err.message);
            px_convex_destroy(a);
            px_convex_destroy(b);
            continue;
        }
        double exact;
        int zero;
        char msg[200];
        if (pxcd_exact_distance(p, 8, q, 4, &exact, NULL, &zero, NULL, NULL, msg, sizeof msg) != PXCD_OK) {
            CHECK(0, "exact oracle: %s", msg);
        } else {
            const px_pose id = px_pose_identity();
            double size = 0;
            for (int i = 0; i < 24; ++i) size = fmax(size, fabs(p[i]));
            for (int i = 0; i < 12; ++i) size = fmax(size, fabs(q[i]));
            for (int m = 0; m < 3; ++m) {
                px_query_options o = {0};
                o.method = m == 0 ? PX_METHOD_LIN_CANNY : m == 1 ? PX_METHOD_GJK : PX_METHOD_HYBRID;
                px_distance_result res;
                CHECK(px_distance(a, &id, b, &id, &o, NULL, &res) == PX_OK, "distance");
                const double e = fabs(res.distance - exact) / (DBL_EPSILON * size);
                if (e > worst) worst = e, worst_at = it;
                /* A moved along the normal touches B after the distance:
                 * the ray cast's final plane is a sliver's (tr_refine) */
                px_translate_result tr;
                CHECK(px_translate(a, &id, b, &id, res.normal, &o, NULL, &tr) == PX_OK && tr.hit,
                      "translate");
                const double et = fabs(tr.tau - exact) / (DBL_EPSILON * size);
                if (et > worst_tau[needle]) worst_tau[needle] = et, worst_tau_at[needle] = it;
            }
        }
        px_convex_destroy(a);
        px_convex_destroy(b);
    }
    printf(
        "turned slabs and needles 1e-3..1e-7 thick: %d refused of %d; distance off the exact by up to %.2g "
        "eps of the size (%d), time of impact along the normal by %.3g (slab %d) and %.3g (needle %d)\n",
        refused, 10 * per, worst, worst_at, worst_tau[0], worst_tau_at[0], worst_tau[1], worst_tau_at[1]);
    CHECK(refused == 0, "%d turned slabs refused", refused);
    CHECK(worst <= 8, "a turned slab's distance off the exact by %.3g eps of the size (slab %d)", worst,
          worst_at);
    CHECK(fmax(worst_tau[0], worst_tau[1]) <= 256,
          "a turned slab's or needle's time of impact off the exact "
          "distance by %.3g / %.3g eps (%d / %d)",
          worst_tau[0], worst_tau[1], worst_tau_at[0], worst_tau_at[1]);
}

int main(void) {
    tu_init("test_degenerate");
    test_construction();
    test_special();
    test_band();
    test_scale();
    test_motion();
    test_near_contact();
    test_pairs();
    test_turned_plates();
    test_turned_slabs();
    test_needle_translations();
    return tu_finish();
}
