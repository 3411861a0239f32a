/* Lin-Canny closest features between two convex polytopes.
 *
 * Sources: M. Lin, "Efficient collision detection for animation and
 * robotics", PhD thesis, Berkeley 1993, chapter 3 (shared/seeds/000: the
 * closest-feature walk over Voronoi regions, blocks (5)-(23) for degenerate
 * edge-face and face-face pairs, the linear-time escape from local minima);
 * B. Mirtich, "V-Clip: fast and robust polyhedral collision detection", ACM
 * TOG 17(3) 1998 (the robust formulation used here: no face-face state, edge
 * clipping against face prisms, explicit penetration states).
 *
 * The idea. Every vertex, edge and face X owns a Voronoi region VR(X): the
 * points of space whose closest point on the polytope lies on X. For a
 * feature pair (X on A, Y on B) with closest points x, y: if x lies in VR(Y)
 * and y in VR(X), then x, y are the globally closest points (then the two
 * half-spaces through x and y normal to x - y separate A from B). Otherwise a
 * violated region plane names a neighbouring feature that is strictly closer,
 * or equally close and of lower dimension, so the walk cannot cycle in exact
 * arithmetic and, with motion coherence, takes O(1) steps per query.
 *
 * How the thesis' cases map onto the states here (docs/lin-canny.md has the
 * full table): point-vertex / point-edge / point-face applicability tests are
 * vertex_violation / edge_violation / face_violation; blocks (5)-(6), a
 * feature beneath a face, are the local-minimum scan in vertex_face; blocks
 * (7)-(23) (face-face, parallel or not, and edge-face) never need their own
 * state: as in V-Clip a face pair is demoted to an edge or vertex of one face,
 * and edge_face clips the edge against the face prism, which decides
 * "the edge cuts the prism", "its end lies above" and parallel edges in one
 * pass.
 *
 * Frames: body i's feature geometry is in its own frame; T[i] maps body i's
 * frame into the other body's. Only the points under test are transformed.
 */
#include <math.h>
#include <string.h>

#include "convex/convex.h"
#include "core/core.h"
#include "math/vec3.h"
#include "narrow/narrow.h"

#define NONE UINT32_MAX

enum { LC_CONTINUE, LC_DONE, LC_PENETRATION };

typedef struct lc_ctx {
    const px_convex *c[2];
    px_pose T[2];    /* T[0] = T_AB (A -> B), T[1] = T_BA (B -> A) */
    px_feature f[2]; /* current features */
    px_vec3 p[2];    /* at the end: closest (or witness) points, each in its own body frame */
    double dist;
} lc_ctx;

static inline px_vec3 to_other(const lc_ctx *x, int i, px_vec3 p) { return pxi_xform(&x->T[i], p); }
static inline px_vec3 dir_to_other(const lc_ctx *x, int i, px_vec3 d) { return pxi_rot(x->T[i].r, d); }

static inline px_feature feat(uint32_t type, uint32_t index) {
    px_feature f = {type, index};
    return f;
}

/* ---- Applicability tests: how far p lies outside a feature's region. ---- */
/* Each returns the largest violation (> 0: outside, across that plane) and
 * the neighbouring feature across the most violated plane (Lin; SWIFT
 * comments that stepping to the first violated plane is wrong). */

static double vertex_violation(const px_convex *c, uint32_t v, px_vec3 p, uint32_t *edge) {
    px_vec3 dp = pxi_sub(p, c->v[v]);
    double worst = 0.0;
    *edge = NONE;
    for (uint32_t k = c->v_first[v]; k < c->v_first[v + 1]; ++k) {
        const pxi_edge *E = &c->e[c->v_edges[k]];
        double s = pxi_dot(dp, E->u);
        if (E->tail != v) s = -s; /* u_out points away from v */
        if (s > worst) {
            worst = s;
            *edge = c->v_edges[k];
        }
    }
    return worst;
}

static double edge_violation(const px_convex *c, uint32_t e, px_vec3 p, px_feature *nbr) {
    const pxi_edge *E = &c->e[e];
    px_vec3 dt = pxi_sub(p, c->v[E->tail]);
    double worst = 0.0, s;
    if ((s = -pxi_dot(dt, E->u)) > worst) worst = s, *nbr = feat(PX_FEATURE_VERTEX, E->tail);
    if ((s = pxi_dot(pxi_sub(p, c->v[E->head]), E->u)) > worst)
        worst = s, *nbr = feat(PX_FEATURE_VERTEX, E->head);
    if ((s = pxi_dot(dt, E->wl)) > worst) worst = s, *nbr = feat(PX_FEATURE_FACE, E->left);
    if ((s = pxi_dot(dt, E->wr)) > worst) worst = s, *nbr = feat(PX_FEATURE_FACE, E->right);
    return worst;
}

/* In-plane inward normal of face f along its boundary edge e. */
static inline px_vec3 face_side_normal(uint32_t f, const pxi_edge *E) { return E->left == f ? E->wl : E->wr; }

static double face_violation(const px_convex *c, uint32_t f, px_vec3 p, uint32_t *edge) {
    const pxi_face *F = &c->f[f];
    double worst = 0.0;
    *edge = NONE;
    for (uint32_t k = 0; k < F->count; ++k) {
        uint32_t e = c->f_edges[F->first + k];
        const pxi_edge *E = &c->e[e];
        double s = -pxi_dot(pxi_sub(p, c->v[E->tail]), face_side_normal(f, E));
        if (s > worst) {
            worst = s;
            *edge = e;
        }
    }
    return worst;
}

/* ---- Segment helpers. ---- */

static inline double clamp01(double x) { return x < 0.0 ? 0.0 : x > 1.0 ? 1.0 : x; }

/* Closest points of two segments (Ericson, Real-Time Collision Detection
 * §5.1.9, rewritten). Near-parallel pairs (relative 1e-14, REFERENCES §1.8)
 * take the middle of the projected overlap, so the point is interior to both
 * edges when they overlap and the region tests below see no false violation. */
void pxi_segment_closest(px_vec3 p0, px_vec3 p1, px_vec3 q0, px_vec3 q1, double *s_out, double *t_out) {
    px_vec3 d1 = pxi_sub(p1, p0), d2 = pxi_sub(q1, q0), r = pxi_sub(p0, q0);
    double a = pxi_dot(d1, d1), e = pxi_dot(d2, d2), f = pxi_dot(d2, r);
    double c = pxi_dot(d1, r), b = pxi_dot(d1, d2);
    double s, t;
    if (!(a > 0.0) || !(e > 0.0)) { /* degenerate segment: cannot happen on a valid hull */
        *s_out = 0.0;
        *t_out = e > 0.0 ? clamp01(f / e) : 0.0;
        return;
    }
    double denom = a * e - b * b;
    if (denom > 1e-14 * a * e) {
        s = clamp01((b * f - c * e) / denom);
    } else {
        /* Parallel: the interval of p-parameters covered by q's projection. */
        double s0 = -c / a, s1 = (b - c) / a;
        double lo = s0 < s1 ? s0 : s1, hi = s0 < s1 ? s1 : s0;
        if (lo < 0.0) lo = 0.0;
        if (hi > 1.0) hi = 1.0;
        s = lo <= hi ? 0.5 * (lo + hi) : (s0 + s1 < 1.0 ? 0.0 : 1.0);
    }
    t = (b * s + f) / e;
    if (t < 0.0) {
        t = 0.0;
        s = clamp01(-c / a);
    } else if (t > 1.0) {
        t = 1.0;
        s = clamp01((b - c) / a);
    }
    *s_out = s;
    *t_out = t;
}

static inline px_vec3 lerp(px_vec3 a, px_vec3 b, double s) { return pxi_madd(a, pxi_sub(b, a), s); }

/* ---- State handlers. i is the body of the first feature, j = 1 - i. ---- */

static int vertex_vertex(lc_ctx *x, int i) {
    int j = 1 - i;
    const px_convex *ci = x->c[i], *cj = x->c[j];
    uint32_t vi = x->f[i].index, vj = x->f[j].index, e;
    px_vec3 q = to_other(x, i, ci->v[vi]); /* vi in j's frame */
    if (vertex_violation(cj, vj, q, &e) > 0.0) {
        x->f[j] = feat(PX_FEATURE_EDGE, e);
        return LC_CONTINUE;
    }
    px_vec3 r = to_other(x, j, cj->v[vj]);
    if (vertex_violation(ci, vi, r, &e) > 0.0) {
        x->f[i] = feat(PX_FEATURE_EDGE, e);
        return LC_CONTINUE;
    }
    x->p[i] = ci->v[vi];
    x->p[j] = cj->v[vj];
    x->dist = pxi_len(pxi_sub(q, cj->v[vj]));
    return x->dist > 0.0 ? LC_DONE : LC_PENETRATION;
}

static int vertex_edge(lc_ctx *x, int i) { /* vertex on i, edge on j */
    int j = 1 - i;
    const px_convex *ci = x->c[i], *cj = x->c[j];
    uint32_t v = x->f[i].index, e = x->f[j].index, ev;
    const pxi_edge *E = &cj->e[e];
    px_vec3 q = to_other(x, i, ci->v[v]);
    px_feature nbr;
    if (edge_violation(cj, e, q, &nbr) > 0.0) {
        x->f[j] = nbr;
        return LC_CONTINUE;
    }
    px_vec3 t = cj->v[E->tail], h = cj->v[E->head];
    px_vec3 d = pxi_sub(h, t);
    double lam = clamp01(pxi_dot(pxi_sub(q, t), d) / pxi_dot(d, d));
    px_vec3 y = lerp(t, h, lam);
    if (vertex_violation(ci, v, to_other(x, j, y), &ev) > 0.0) {
        x->f[i] = feat(PX_FEATURE_EDGE, ev);
        return LC_CONTINUE;
    }
    x->p[i] = ci->v[v];
    x->p[j] = y;
    x->dist = pxi_len(pxi_sub(q, y));
    return x->dist > 0.0 ? LC_DONE : LC_PENETRATION;
}

/* The thesis' "linear-time routine" (blocks (5), (6)): p (in j's frame) lies
 * beneath a face of j. The face of j with the greatest height of p is the
 * next candidate; if p is on or beneath every face plane, p is inside j. */
static uint32_t highest_face(const px_convex *c, px_vec3 p, double *height) {
    uint32_t best = 0;
    double hb = -INFINITY;
    for (uint32_t f = 0; f < c->nf; ++f) {
        double h = pxi_dot(c->f[f].n, p) - c->f[f].d;
        if (h > hb) {
            hb = h;
            best = f;
        }
    }
    *height = hb;
    return best;
}

static int vertex_face(lc_ctx *x, int i) { /* vertex on i, face on j */
    int j = 1 - i;
    const px_convex *ci = x->c[i], *cj = x->c[j];
    uint32_t v = x->f[i].index, f = x->f[j].index, e;
    const pxi_face *F = &cj->f[f];
    px_vec3 q = to_other(x, i, ci->v[v]);
    if (face_violation(cj, f, q, &e) > 0.0) {
        x->f[j] = feat(PX_FEATURE_EDGE, e);
        return LC_CONTINUE;
    }
    double h = pxi_dot(F->n, q) - F->d;
    x->p[i] = ci->v[v];
    if (h == 0.0) { /* the vertex lies on the face: touching */
        x->p[j] = q;
        x->dist = 0.0;
        return LC_PENETRATION;
    }
    /* Is the foot of the perpendicular in VR(v)? An edge at v along which
     * |height| decreases (h * n.u_out < 0) is closer to F (Mirtich §4). */
    px_vec3 n_i = dir_to_other(x, j, F->n);
    double worst = 0.0;
    uint32_t best_e = NONE;
    for (uint32_t k = ci->v_first[v]; k < ci->v_first[v + 1]; ++k) {
        const pxi_edge *E = &ci->e[ci->v_edges[k]];
        /* Signs only: h * (n.u) would underflow to 0 at tiny scales. */
        double g = pxi_dot(n_i, E->u);
        if (E->tail != v) g = -g;
        if (h < 0.0) g = -g;
        if (g < worst) {
            worst = g;
            best_e = ci->v_edges[k];
        }
    }
    if (best_e != NONE) {
        x->f[i] = feat(PX_FEATURE_EDGE, best_e);
        return LC_CONTINUE;
    }
    if (h > 0.0) {
        x->p[j] = pxi_madd(q, F->n, -h);
        x->dist = h;
        return LC_DONE;
    }
    /* Local minimum: v is beneath F inside its prism. */
    double hb;
    uint32_t g = highest_face(cj, q, &hb);
    if (!(hb > 0.0)) { /* inside or on every face plane (NaN also ends here) */
        x->p[j] = q;
        x->dist = 0.0;
        return LC_PENETRATION;
    }
    x->f[j] = feat(PX_FEATURE_FACE, g);
    return LC_CONTINUE;
}

static int edge_edge(lc_ctx *x, int i) {
    int j = 1 - i;
    const px_convex *ci = x->c[i], *cj = x->c[j];
    const pxi_edge *Ei = &ci->e[x->f[i].index], *Ej = &cj->e[x->f[j].index];
    px_vec3 p0 = to_other(x, i, ci->v[Ei->tail]), p1 = to_other(x, i, ci->v[Ei->head]);
    px_vec3 q0 = cj->v[Ej->tail], q1 = cj->v[Ej->head];
    double s, t;
    pxi_segment_closest(p0, p1, q0, q1, &s, &t);
    px_vec3 xp = lerp(p0, p1, s), yq = lerp(q0, q1, t);
    px_feature nbr;
    if (edge_violation(cj, x->f[j].index, xp, &nbr) > 0.0) {
        x->f[j] = nbr;
        return LC_CONTINUE;
    }
    if (edge_violation(ci, x->f[i].index, to_other(x, j, yq), &nbr) > 0.0) {
        x->f[i] = nbr;
        return LC_CONTINUE;
    }
    x->p[i] = lerp(ci->v[Ei->tail], ci->v[Ei->head], s);
    x->p[j] = yq;
    x->dist = pxi_len(pxi_sub(xp, yq));
    return x->dist > 0.0 ? LC_DONE : LC_PENETRATION;
}

/* Boundary feature of face f (body c) closest to segment [p0, p1] (c's
 * frame): an edge, or a vertex when the closest point is an edge end. */
static px_feature closest_boundary_feature(const px_convex *c, uint32_t f, px_vec3 p0, px_vec3 p1) {
    const pxi_face *F = &c->f[f];
    double best = INFINITY;
    px_feature out = feat(PX_FEATURE_EDGE, c->f_edges[F->first]);
    for (uint32_t k = 0; k < F->count; ++k) {
        uint32_t e = c->f_edges[F->first + k];
        const pxi_edge *E = &c->e[e];
        double s, t;
        pxi_segment_closest(p0, p1, c->v[E->tail], c->v[E->head], &s, &t);
        double d2 = pxi_len2(pxi_sub(lerp(p0, p1, s), lerp(c->v[E->tail], c->v[E->head], t)));
        if (d2 < best) {
            best = d2;
            out = t <= 0.0   ? feat(PX_FEATURE_VERTEX, E->tail)
                  : t >= 1.0 ? feat(PX_FEATURE_VERTEX, E->head)
                             : feat(PX_FEATURE_EDGE, e);
        }
    }
    return out;
}

static int edge_face(lc_ctx *x, int i) { /* edge on i, face on j */
    int j = 1 - i;
    const px_convex *ci = x->c[i], *cj = x->c[j];
    const pxi_edge *Ei = &ci->e[x->f[i].index];
    uint32_t f = x->f[j].index;
    const pxi_face *F = &cj->f[f];
    px_vec3 p0 = to_other(x, i, ci->v[Ei->tail]), p1 = to_other(x, i, ci->v[Ei->head]);
    /* Clip the edge against the prism over F (Mirtich's clipEdge). */
    double lo = 0.0, hi = 1.0;
    uint32_t nlo = NONE, nhi = NONE;
    int excluded = 0;
    for (uint32_t k = 0; k < F->count && !excluded; ++k) {
        uint32_t e = cj->f_edges[F->first + k];
        const pxi_edge *E = &cj->e[e];
        px_vec3 w = face_side_normal(f, E), t = cj->v[E->tail];
        double a = pxi_dot(pxi_sub(p0, t), w), b = pxi_dot(pxi_sub(p1, t), w);
        if (a < 0.0 && b < 0.0) {
            excluded = 1;
        } else if (a < 0.0) {
            double lam = a / (a - b);
            if (lam > lo) lo = lam, nlo = e;
        } else if (b < 0.0) {
            double lam = a / (a - b);
            if (lam < hi) hi = lam, nhi = e;
        }
        if (lo > hi) excluded = 1;
    }
    if (excluded) {
        /* The edge misses the prism: the closest point of F to it lies on
         * F's boundary, so that boundary feature is as close and smaller. */
        x->f[j] = closest_boundary_feature(cj, f, p0, p1);
        return LC_CONTINUE;
    }
    px_vec3 plo = lerp(p0, p1, lo), phi = lerp(p0, p1, hi);
    double hl = pxi_dot(F->n, plo) - F->d, hh = pxi_dot(F->n, phi) - F->d;
    /* Sign tests, not products: a product of two tiny heights underflows. */
    if ((hl <= 0.0) != (hh <= 0.0) || hl == 0.0 || hh == 0.0 || !(hl == hl && hh == hh)) {
        /* The clipped edge meets the face plane inside the prism: the edge
         * pierces (or touches) the face. Witness: the crossing point. */
        double lam = hl != hh ? lo + (hi - lo) * (hl / (hl - hh)) : lo;
        if (!(lam >= lo && lam <= hi)) lam = lo;
        x->p[j] = lerp(p0, p1, lam);
        x->p[i] = lerp(ci->v[Ei->tail], ci->v[Ei->head], lam);
        x->dist = 0.0;
        return LC_PENETRATION;
    }
    /* Same side: |height| is linear along the clipped edge; follow its
     * decrease to the end of the clipped part. There the closest feature is
     * the prism side that clipped it, or the edge's own endpoint. */
    double slope = pxi_dot(F->n, pxi_sub(p1, p0));
    if (slope != 0.0 && (hl > 0.0) == (slope > 0.0)) {
        if (nlo != NONE)
            x->f[j] = feat(PX_FEATURE_EDGE, nlo);
        else
            x->f[i] = feat(PX_FEATURE_VERTEX, Ei->tail);
    } else {
        if (nhi != NONE)
            x->f[j] = feat(PX_FEATURE_EDGE, nhi);
        else
            x->f[i] = feat(PX_FEATURE_VERTEX, Ei->head);
    }
    return LC_CONTINUE;
}

/* One step of the walk on the current pair. */
static int lc_step(lc_ctx *x) {
    uint32_t ta = x->f[0].type, tb = x->f[1].type;
    if (ta == PX_FEATURE_FACE && tb == PX_FEATURE_FACE) {
        /* No face-face state (V-Clip): demote A's face to one of its vertices. */
        x->f[0] = feat(PX_FEATURE_VERTEX, x->c[0]->f_verts[x->c[0]->f[x->f[0].index].first]);
        return LC_CONTINUE;
    }
    int i = ta <= tb ? 0 : 1; /* body with the lower-dimensional feature */
    uint32_t lo = ta <= tb ? ta : tb, hi = ta <= tb ? tb : ta;
    if (lo == PX_FEATURE_VERTEX) {
        if (hi == PX_FEATURE_VERTEX) return vertex_vertex(x, 0);
        if (hi == PX_FEATURE_EDGE) return vertex_edge(x, i);
        return vertex_face(x, i);
    }
    if (hi == PX_FEATURE_EDGE) return edge_edge(x, 0);
    return edge_face(x, i);
}

static int feature_valid(const px_convex *c, px_feature f) {
    switch (f.type) {
    case PX_FEATURE_VERTEX: return f.index < c->nv;
    case PX_FEATURE_EDGE: return f.index < c->ne;
    case PX_FEATURE_FACE: return f.index < c->nf;
    default: return 0;
    }
}

/* Runs the walk from x->f. Returns the final state, or -1 when it revisited
 * a recent pair (a floating-point cycle) or ran out of steps. */
static int lc_walk(lc_ctx *x, uint32_t max_steps, uint32_t *iterations) {
    px_feature ring[2][8];
    memset(ring, 0xff, sizeof ring);
    for (uint32_t step = 0; step < max_steps; ++step) {
        int r = lc_step(x);
        if (r != LC_CONTINUE) return r;
        ++*iterations;
        /* In exact arithmetic no pair repeats (the distance never grows, and
         * at equal distance the dimension drops). A repeat is round-off. */
        for (int k = 0; k < 8; ++k)
            if (ring[0][k].type == x->f[0].type && ring[0][k].index == x->f[0].index &&
                ring[1][k].type == x->f[1].type && ring[1][k].index == x->f[1].index)
                return -1;
        ring[0][step & 7] = x->f[0];
        ring[1][step & 7] = x->f[1];
    }
    return -1;
}

static void zero_result(px_distance_result *r) {
    if (r) memset(r, 0, sizeof *r);
}

px_status px_distance(const px_convex *a, const px_pose *pose_a, const px_convex *b, const px_pose *pose_b,
                      px_distance_cache *cache, px_distance_result *result) {
    zero_result(result);
    if (!a || !b || !pose_a || !pose_b || !result) return PX_ERR_INVALID_ARGUMENT;
    px_status st = px_pose_check(pose_a, NULL);
    if (st == PX_OK) st = px_pose_check(pose_b, NULL);
    if (st != PX_OK) return st;

    lc_ctx x;
    x.c[0] = a;
    x.c[1] = b;
    x.T[0] = pxi_relative(pose_a, pose_b);
    /* T_BA = T_AB^-1 = (R^T, -R^T t), cheaper than a second product. */
    for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 3; ++k) x.T[1].r[3 * r + k] = x.T[0].r[3 * k + r];
    x.T[1].t = pxi_neg(pxi_rot_t(x.T[0].r, x.T[0].t));
    x.dist = 0.0;
    x.p[0] = x.p[1] = pxi_v(0, 0, 0);

    int warm = cache && feature_valid(a, cache->feature_a) && feature_valid(b, cache->feature_b);
    if (warm) {
        x.f[0] = cache->feature_a;
        x.f[1] = cache->feature_b;
    } else {
        /* Cold start: GJK to a loose tolerance finds vertices near the
         * closest points in O(log n)-ish support calls (direction table plus
         * hill climbing), so the walk starts close to its goal. */
        pxi_gjk_result g;
        pxi_gjk(a, b, &x.T[0], 1e-3, 64, &g);
        x.f[0] = feat(PX_FEATURE_VERTEX, g.va);
        x.f[1] = feat(PX_FEATURE_VERTEX, g.vb);
        if (g.intersecting) {
            /* The origin lies in a simplex of A - B: the solids overlap, and
             * the barycentric combination is a common point. Walking to a
             * penetration witness from here would cost O(n) for nothing. */
            result->intersecting = 1;
            result->point_a = pxi_xform(pose_a, g.pa);
            result->point_b = pxi_xform(pose_b, g.pb);
            result->feature_a = x.f[0];
            result->feature_b = x.f[1];
            if (cache) {
                cache->feature_a = x.f[0];
                cache->feature_b = x.f[1];
            }
            return PX_OK;
        }
    }
    uint64_t total = (uint64_t)a->nv + a->ne + a->nf + b->nv + b->ne + b->nf;
    uint32_t cap = total > 100000000u ? 400000000u : (uint32_t)(4 * total + 64);
    uint32_t iterations = 0, fallbacks = 0;
    int r = lc_walk(&x, cap, &iterations);
    if (r < 0) {
        /* Safeguard: restart once from GJK's answer at full precision. */
        ++fallbacks;
        pxi_gjk_result g;
        pxi_gjk(a, b, &x.T[0], 1e-12, 256, &g);
        x.f[0] = feat(PX_FEATURE_VERTEX, g.va);
        x.f[1] = feat(PX_FEATURE_VERTEX, g.vb);
        r = lc_walk(&x, cap, &iterations);
        if (r < 0) {
            /* Still cycling: GJK's own answer is the result. */
            ++fallbacks;
            x.p[0] = g.pa;
            x.p[1] = g.pb;
            x.dist = g.distance;
            r = g.intersecting ? LC_PENETRATION : LC_DONE;
        }
    }
    result->distance = r == LC_PENETRATION ? 0.0 : x.dist;
    result->intersecting = r == LC_PENETRATION;
    result->point_a = pxi_xform(pose_a, x.p[0]);
    result->point_b = pxi_xform(pose_b, x.p[1]);
    result->feature_a = x.f[0];
    result->feature_b = x.f[1];
    result->iterations = iterations;
    result->fallbacks = fallbacks;
    if (cache) {
        cache->feature_a = x.f[0];
        cache->feature_b = x.f[1];
    }
    return PX_OK;
}
