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
 * pass. Edge-edge and the cone test of vertex-edge use the same clipping
 * (clip_against_edge, clip_against_vertex): better conditioned than testing
 * one closest point when edges are nearly parallel or a region is a wedge
 * thinner than rounding (docs/lin-canny.md, "Point tests and clipping").
 *
 * Frames: body i's feature geometry is in its own frame; T[i] maps body i's
 * frame into the other body's. Only the points under test are transformed.
 */
#include <float.h>
#include <math.h>
#include <string.h>
#ifdef PXI_TRACE_WALK
#include <stdio.h>
#endif

#include "convex/convex.h"
#include "core/core.h"
#include "math/orient.h"
#include "math/vec3.h"
#include "narrow/closest.h"
#include "narrow/feature.h"
#include "narrow/narrow.h"
#include "narrow/tolerance.h"

#define NONE UINT32_MAX

enum { LC_CONTINUE, LC_DONE, LC_PENETRATION };
/* lc_walk's other outcomes. */
enum { LC_REPEAT = -1, LC_OUT_OF_STEPS = -2 };

typedef struct lc_ctx {
    const px_convex *c[2];
    px_pose T[2];    /* T[0] = T_AB (A -> B), T[1] = T_BA (B -> A) */
    px_feature f[2]; /* current features */
    px_vec3 p[2];    /* at the end: closest (or witness) points, each in its own body frame */
    double dist;
    double tie; /* 0, or the relative margin of the tie-breaking mode (see noise()) */
    int band;   /* contact was decided within the rounding band, not proved */
} lc_ctx;

static inline px_vec3 to_other(const lc_ctx *x, int i, px_vec3 p) { return pxi_xform(&x->T[i], p); }
static inline px_vec3 dir_to_other(const lc_ctx *x, int i, px_vec3 d) { return pxi_rot(x->T[i].r, d); }

static inline px_feature feat(uint32_t type, uint32_t index) {
    px_feature f = {type, index, 0};
    return f;
}

/* ---- Applicability tests: how far p lies outside a feature's region. ---- */
/* Each returns the largest violation (> 0: outside, across that plane) and
 * the neighbouring feature across the most violated plane (Lin; SWIFT
 * comments that stepping to the first violated plane is wrong).
 *
 * Exact V-Clip compares with 0, and so does the first walk. But p was
 * transformed from the other body's frame and carries an error of a few ulps
 * of its coordinates, so a plane distance below 8 eps (|p| + |v|) (v a point
 * of the plane) is no evidence either way: exactly parallel edges and faces
 * (two copies of a body with the same orientation) then make the walk
 * alternate between a face and its boundary edge. When the walk revisits a
 * pair it is rerun from there in tie-breaking mode, where a violation must
 * exceed that margin (hysteresis, like I-COLLIDE's flared planes). The margin
 * is relative to the coordinates, so the walk stays scale-free. Tie-breaking
 * is not the default because a margin also accepts real but tiny violations,
 * and along nearly parallel edges (1e-9 rad) those add up to a visible error. */
static inline double noise(double k, px_vec3 p, px_vec3 v) { return k * (pxi_max_abs(p) + pxi_max_abs(v)); }

/* In-plane inward normal of face f along its boundary edge e. */
static inline px_vec3 face_side_normal(uint32_t f, const pxi_edge *E) { return E->left == f ? E->wl : E->wr; }

/* Two edges at a vertex this close to opposite (1 + u1 . u2 below it: an
 * angle within 4.5e-5 rad of 180 degrees) make it a point of a straight
 * stretch. A polygon corner is that flat only past 140,000 sides. */
#define LC_RIDGE_FLAT 0x1p-30

/* Whether edges k1, k2 of w's list (positions in v_edges) continue a
 * straight line through w. */
static inline int straight_at(const px_convex *c, uint32_t w, uint32_t k1, uint32_t k2) {
    const pxi_edge *Ea = &c->e[c->v_edges[k1]], *Eb = &c->e[c->v_edges[k2]];
    double d = pxi_dot(Ea->u, Eb->u);
    if ((Ea->tail == w) != (Eb->tail == w)) d = -d; /* both pointing away from w */
    return d < -1.0 + LC_RIDGE_FLAT;
}

/* A vertex of the exact hull can sit on a straight stretch of a face's
 * boundary (an input point 1e-19 off the line of its neighbours: the
 * face's angle there is 180 degrees within rounding). Its region is then
 * bounded, beside its edges' planes, by that face's side plane along the
 * stretch: its edges along the stretch, nearly opposite, say nothing about
 * a point p beyond that plane, on the face's side, which is closer to the
 * face's interior than to v (review s32: warm Lin-Canny stopped at such a
 * vertex facing an edge 380 times too far). Only edges nearly
 * perpendicular to dp = p - v (|dp . u| below 2^-14 |dp|) can make such a
 * pair when no edge plane is violated. Returns the face whose side plane p
 * lies beyond by more than `worst`, or NONE. */
static uint32_t straight_face_violation(const px_convex *c, uint32_t v, px_vec3 dp, double worst) {
    const double near2 = 0x1p-28 * pxi_len2(dp);
    uint32_t near[4], nn = 0;
    for (uint32_t k = c->v_first[v]; k < c->v_first[v + 1] && nn < 4; ++k) {
        double s = pxi_dot(dp, c->e[c->v_edges[k]].u);
        if (s * s <= near2) near[nn++] = k;
    }
    for (uint32_t a = 0; a < nn; ++a)
        for (uint32_t b = a + 1; b < nn; ++b) {
            if (!straight_at(c, v, near[a], near[b])) continue;
            const pxi_edge *Ea = &c->e[c->v_edges[near[a]]], *Eb = &c->e[c->v_edges[near[b]]];
            uint32_t f = Ea->left == Eb->left || Ea->left == Eb->right     ? Ea->left
                         : Ea->right == Eb->left || Ea->right == Eb->right ? Ea->right
                                                                           : NONE;
            if (f == NONE || f >= c->nf) continue;
            if (pxi_dot(dp, face_side_normal(f, Ea)) > worst) return f;
        }
    return NONE;
}

/* Is p outside vertex v's region: across one of its edge planes (*nbr that
 * edge), or beyond the side plane of a face whose boundary runs straight
 * through v (*nbr that face; straight_face_violation)? */
static int vertex_violation(double tie, const px_convex *c, uint32_t v, px_vec3 p, px_feature *nbr) {
    px_vec3 dp = pxi_sub(p, c->v[v]);
    double worst = noise(tie, p, c->v[v]);
    uint32_t edge = NONE;
    for (uint32_t k = c->v_first[v]; k < c->v_first[v + 1]; ++k) {
        const pxi_edge *E = &c->e[c->v_edges[k]];
        double s = pxi_dot(dp, E->u);
        if (E->tail != v) s = -s; /* u_out points away from v */
        if (s > worst) {
            worst = s;
            edge = c->v_edges[k];
        }
    }
    if (edge != NONE) {
        *nbr = feat(PX_FEATURE_EDGE, edge);
        return 1;
    }
    uint32_t f = straight_face_violation(c, v, dp, worst);
    if (f == NONE) return 0;
    *nbr = feat(PX_FEATURE_FACE, f);
    return 1;
}

static int edge_violation(double tie, const px_convex *c, uint32_t e, px_vec3 p, px_feature *nbr) {
    const pxi_edge *E = &c->e[e];
    px_vec3 dt = pxi_sub(p, c->v[E->tail]);
    double worst = noise(tie, p, c->v[E->tail]), s;
    nbr->type = PX_FEATURE_NONE;
    if ((s = -pxi_dot(dt, E->u)) > worst) worst = s, *nbr = feat(PX_FEATURE_VERTEX, E->tail);
    if ((s = pxi_dot(pxi_sub(p, c->v[E->head]), E->u)) > worst)
        worst = s, *nbr = feat(PX_FEATURE_VERTEX, E->head);
    if ((s = pxi_dot(dt, E->wl)) > worst) worst = s, *nbr = feat(PX_FEATURE_FACE, E->left);
    if ((s = pxi_dot(dt, E->wr)) > worst) worst = s, *nbr = feat(PX_FEATURE_FACE, E->right);
    return nbr->type != PX_FEATURE_NONE;
}

static int face_violation(double tie, const px_convex *c, uint32_t f, px_vec3 p, uint32_t *edge) {
    const pxi_face *F = &c->f[f];
    double worst = noise(tie, p, c->v[c->f_verts[F->first]]);
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
    return *edge != NONE;
}

static inline px_vec3 lerp(px_vec3 a, px_vec3 b, double s) { return pxi_madd(a, pxi_sub(b, a), s); }

/* Head of edge E of body i in the other body's frame, given its tail there:
 * tail plus the rotated edge vector, so that the edge keeps its own direction
 * and length exactly up to one rotation, whatever the translation. */
static inline px_vec3 edge_head_in_other(const lc_ctx *x, int i, const pxi_edge *E, px_vec3 tail_other) {
    const px_convex *c = x->c[i];
    return pxi_add(tail_other, dir_to_other(x, i, pxi_sub(c->v[E->head], c->v[E->tail])));
}

/* ---- State handlers. i is the body of the first feature, j = 1 - i. ---- */

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

/* A feature's Voronoi region lies outside its body, so a vertex q of body i
 * (in j's frame) beneath every face of j at the feature (the two faces of an
 * edge, those around a vertex) is not in it. The region's planes say so for
 * every feature but a flat one, whose faces are coplanar within rounding:
 * its side planes coincide and let through points on either side (a point
 * 5e-5 inside a thin piece was reported 5e-5 away). Then the thesis'
 * linear-time routine decides, as at a vertex-face local minimum. Returns
 * -1 when q is not beneath every face. */
static int beneath_faces(lc_ctx *x, int i, px_vec3 q, const uint32_t *fs,
                         uint32_t n) { /* x->p[i]: set by the caller */
    int j = 1 - i;
    const px_convex *cj = x->c[j];
    const double lim = PXI_LC_CONTACT * (pxi_max_abs(q) + cj->scale);
    for (uint32_t k = 0; k < n; ++k) {
        const pxi_face *F = &cj->f[fs[k]];
        if (!(pxi_dot(F->n, pxi_sub(q, cj->v[cj->f_verts[F->first]])) < -lim)) return -1;
    }
    double hb;
    uint32_t g = highest_face(cj, q, &hb);
    if (!(hb > lim)) {
        x->p[j] = q;
        x->dist = 0.0;
        x->band = !(hb < -lim);
        return LC_PENETRATION;
    }
    x->f[j] = feat(PX_FEATURE_FACE, g);
    return LC_CONTINUE;
}

static int vertex_vertex(lc_ctx *x, int i) {
    int j = 1 - i;
    const px_convex *ci = x->c[i], *cj = x->c[j];
    uint32_t vi = x->f[i].index, vj = x->f[j].index;
    px_vec3 q = to_other(x, i, ci->v[vi]); /* vi in j's frame */
    px_feature nbr;
    if (vertex_violation(x->tie, cj, vj, q, &nbr)) {
        x->f[j] = nbr;
        return LC_CONTINUE;
    }
    px_vec3 r = to_other(x, j, cj->v[vj]);
    if (vertex_violation(x->tie, ci, vi, r, &nbr)) {
        x->f[i] = nbr;
        return LC_CONTINUE;
    }
    /* Beneath every face around the other's vertex (a flat vertex): inside. */
    for (int side = 0; side < 2; ++side) {
        int a = side ? j : i, b = side ? i : j;
        const px_convex *cb = x->c[b];
        uint32_t vb = x->f[b].index, fs[64], n = 0;
        for (uint32_t k = cb->v_first[vb]; k < cb->v_first[vb + 1] && n + 2 <= 64; ++k) {
            const pxi_edge *E = &cb->e[cb->v_edges[k]];
            if (E->left < cb->nf) fs[n++] = E->left;
            if (E->right < cb->nf) fs[n++] = E->right;
        }
        if (n == 0 || cb->v_first[vb + 1] - cb->v_first[vb] > 32) continue;
        x->p[a] = x->c[a]->v[x->f[a].index];
        int st = beneath_faces(x, a, side ? to_other(x, j, cj->v[vj]) : q, fs, n);
        if (st >= 0) return st;
    }
    x->p[i] = ci->v[vi];
    x->p[j] = cj->v[vj];
    x->dist = pxi_len_safe(pxi_sub(q, cj->v[vj]));
    return x->dist > 0.0 ? LC_DONE : LC_PENETRATION;
}

/* dir without its component along unit u. On a VE plane P - v is normal
 * to u in exact arithmetic, so (P - v) . dir = (P - v) . perp(dir, u); the
 * left side multiplies the rounding error of P along u by |dir . u|, which
 * for nearly parallel edges is the whole of dir and swamps a true slope of
 * order angle^2. */
static inline px_vec3 perp(px_vec3 dir, px_vec3 u) { return pxi_madd(dir, u, -pxi_dot(dir, u)); }

/* A direction whose only use is the sign of (P - v) . dir, a product of two
 * lengths: brought to unit size by a power of two when that product would
 * overflow or underflow (bodies beyond 1e150 or below 1e-150); unchanged,
 * so the same bits, otherwise. */
static inline px_vec3 unit_scale_dir(px_vec3 dir) {
    double m = pxi_max_abs(dir);
    return pxi_len_ok(m) || !(m > 0.0) || !isfinite(m) ? dir : pxi_ldexp3(dir, -ilogb(m));
}

/* Mirtich's clipping of segment [p0, p1] (in v's body frame) against the
 * cone VR(v): 1 = v stays a candidate, 0 = move v to edge *edge, -1 =
 * compound exclusion (caller falls back to the closest-point test). The
 * derivative of |P - v| along the segment at a clip point is (P - v) . dir;
 * there P - v is normal to the clipping edge, so for a segment nearly
 * parallel to that edge the sign comes from the small angle between them,
 * far above rounding, where the foot-point test of Lin-Canny would compare
 * two quantities that differ only at second order. */
static int clip_against_vertex(const px_convex *c, uint32_t v, px_vec3 p0, px_vec3 p1, uint32_t *edge) {
    double lo = 0.0, hi = 1.0;
    uint32_t elo = NONE, ehi = NONE;
    px_vec3 d0 = pxi_sub(p0, c->v[v]), d1 = pxi_sub(p1, c->v[v]);
    for (uint32_t k = c->v_first[v]; k < c->v_first[v + 1]; ++k) {
        const pxi_edge *E = &c->e[c->v_edges[k]];
        double a = -pxi_dot(d0, E->u), b = -pxi_dot(d1, E->u); /* region side >= 0 */
        if (E->tail != v) a = -a, b = -b;
        if (a < 0.0 && b < 0.0) {
            *edge = c->v_edges[k];
            return 0;
        }
        if (a < 0.0) {
            double lam = a / (a - b);
            if (lam > lo) lo = lam, elo = c->v_edges[k];
        } else if (b < 0.0) {
            double lam = a / (a - b);
            if (lam < hi) hi = lam, ehi = c->v_edges[k];
        }
    }
    if (lo > hi) return -1;
    px_vec3 dir = unit_scale_dir(pxi_sub(p1, p0));
    if (elo != NONE && pxi_dot(lerp(d0, d1, lo), perp(dir, c->e[elo].u)) > 0.0) {
        *edge = elo;
        return 0;
    }
    if (ehi != NONE && pxi_dot(lerp(d0, d1, hi), perp(dir, c->e[ehi].u)) < 0.0) {
        *edge = ehi;
        return 0;
    }
    return 1;
}

static int vertex_edge(lc_ctx *x, int i) { /* vertex on i, edge on j */
    int j = 1 - i;
    const px_convex *ci = x->c[i], *cj = x->c[j];
    uint32_t v = x->f[i].index, e = x->f[j].index, ev;
    const pxi_edge *E = &cj->e[e];
    px_vec3 q = to_other(x, i, ci->v[v]);
    px_feature nbr;
    if (edge_violation(x->tie, cj, e, q, &nbr)) {
        x->f[j] = nbr;
        return LC_CONTINUE;
    }
    px_vec3 t = cj->v[E->tail], h = cj->v[E->head];
    px_vec3 d = pxi_sub(h, t);
    px_vec3 qt = pxi_sub(q, t), ds = d;
    if (!pxi_len_ok(pxi_max_abs(d))) { /* |d|^2 overflows or underflows: the ratio at unit scale */
        int ex = -ilogb(pxi_max_abs(d));
        qt = pxi_ldexp3(qt, ex), ds = pxi_ldexp3(d, ex);
    }
    double lam = pxi_clamp01(pxi_dot(qt, ds) / pxi_dot(ds, ds));
    px_vec3 y = lerp(t, h, lam);
    int clip = x->tie == 0.0 ? -1 : 0;
    if (clip < 0) { /* exact mode: clip E against the cone of v (V-Clip) */
        px_vec3 r0 = to_other(x, j, t), r1 = edge_head_in_other(x, j, E, r0);
        clip = clip_against_vertex(ci, v, r0, r1, &ev);
        if (clip == 0) {
            x->f[i] = feat(PX_FEATURE_EDGE, ev);
            return LC_CONTINUE;
        }
    }
    if (clip < 0 || x->tie != 0.0) { /* closest-point test: tie-breaking mode, compound exclusion */
        if (vertex_violation(x->tie, ci, v, to_other(x, j, y), &nbr)) {
            x->f[i] = nbr;
            return LC_CONTINUE;
        }
    } else if (ci->v_first[v + 1] - ci->v_first[v] >= 3) {
        /* E crosses v's edge planes' cone: the side plane of a face running
         * straight through v may still cut it off (vertex_violation). */
        uint32_t f = straight_face_violation(ci, v, pxi_sub(to_other(x, j, y), ci->v[v]), 0.0);
        if (f != NONE) {
            x->f[i] = feat(PX_FEATURE_FACE, f);
            return LC_CONTINUE;
        }
    }
    if (cj->nf > 0 && E->left < cj->nf && E->right < cj->nf) {
        const uint32_t fs[2] = {E->left, E->right};
        x->p[i] = ci->v[v];
        int r = beneath_faces(x, i, q, fs, 2);
        if (r >= 0) return r;
    }
    x->p[i] = ci->v[v];
    x->p[j] = y;
    x->dist = pxi_len_safe(pxi_sub(q, y));
    return x->dist > 0.0 ? LC_DONE : LC_PENETRATION;
}

/* Height changes along the edges at v of body c, the height growing along
 * unit n (c's frame; signs only: h * (n.u) would underflow to 0 at tiny
 * scales): the edge that descends most steeply, or NONE. The positions in
 * v's edge list of up to eight edges level within rounding (an edge
 * parallel to F within rounding is no closer) go to level[], their number
 * to *nl. */
PXI_HOT_INLINE uint32_t steepest_descent(const px_convex *c, uint32_t v, px_vec3 n, uint32_t level[8],
                                         uint32_t *nl) {
    double worst = -4.0 * DBL_EPSILON;
    uint32_t best = NONE;
    *nl = 0;
    for (uint32_t k = c->v_first[v]; k < c->v_first[v + 1]; ++k) {
        const pxi_edge *E = &c->e[c->v_edges[k]];
        double g = pxi_dot(n, E->u);
        if (E->tail != v) g = -g;
        if (g < worst) {
            worst = g;
            best = c->v_edges[k];
        }
        if (!(fabs(g) > 4.0 * DBL_EPSILON) && *nl < 8) level[(*nl)++] = k;
    }
    return best;
}

#define LC_RIDGE_CAP 4096
#define LC_RIDGE_UNKNOWN (NONE - 1)
/* The first pair among w's level edges (positions level[0..nl)) that
 * continues a straight line through w, into *ka, *kb; 0 when none. */
static int straight_pair(const px_convex *c, uint32_t w, const uint32_t *level, uint32_t nl, uint32_t *ka,
                         uint32_t *kb) {
    for (uint32_t a = 0; a < nl; ++a)
        for (uint32_t b = a + 1; b < nl; ++b)
            if (straight_at(c, w, level[a], level[b])) {
                *ka = level[a], *kb = level[b];
                return 1;
            }
    return 0;
}

/* Vertex v has no edge that descends, but two level ones that continue a
 * straight line: v is a vertex of the exact hull on a straight stretch of a
 * face's boundary (an input point 1e-19 off the line of its neighbours: a
 * face angle of 180 degrees within rounding). If that stretch is level,
 * the descent into the face runs along no edge of v, and Lin-Canny stopped
 * there with the distance 16 % too large on a Puma link's hull (review
 * s32). The descent starts at the stretch's ends, corners of that face: so
 * the walk follows level edges that continue a straight line and returns
 * the first descending edge at a vertex it reaches, starting both ways from
 * v's straight pair (positions ka, kb in its edge list). (A corner of a face
 * parallel to F, a resting contact, has no straight pair, and the caller
 * does not come here.) Returns that edge, NONE (*end: the end of the
 * stretch, a corner, with fewer edges), or LC_RIDGE_UNKNOWN past 4096
 * vertices a way (the caller leaves the answer to another method). */
PXI_NOINLINE static uint32_t ridge_descent(const px_convex *c, uint32_t v, px_vec3 n, uint32_t ka,
                                           uint32_t kb, uint32_t *end) {
    uint32_t level[8], nl;
    *end = NONE;
    /* Both ways along the stretch, one vertex at a time: at each, a
     * descending edge ends the walk; else the level edge continuing the
     * line from the one it came by leads on, and without one the vertex is
     * the stretch's end (a corner). */
    for (int side = 0; side < 2; ++side) {
        uint32_t prev = v, cur = c->v_adj[side ? kb : ka], steps = 0;
        for (;; ++steps) {
            if (steps == LC_RIDGE_CAP) return LC_RIDGE_UNKNOWN;
            uint32_t e = steepest_descent(c, cur, n, level, &nl);
            if (e != NONE) return e;
            uint32_t back = NONE, next = NONE;
            for (uint32_t a = 0; a < nl; ++a)
                if (c->v_adj[level[a]] == prev) back = level[a];
            for (uint32_t a = 0; back != NONE && a < nl && next == NONE; ++a)
                if (level[a] != back && straight_at(c, cur, back, level[a])) next = c->v_adj[level[a]];
            if (next == NONE || next == v) break;
            prev = cur;
            cur = next;
        }
        /* of the two ends, the one with fewer edges (cheaper to test) */
        if (*end == NONE || c->v_first[cur + 1] - c->v_first[cur] < c->v_first[*end + 1] - c->v_first[*end])
            *end = cur;
    }
    return NONE;
}

static int vertex_face(lc_ctx *x, int i) { /* vertex on i, face on j */
    int j = 1 - i;
    const px_convex *ci = x->c[i], *cj = x->c[j];
    uint32_t v = x->f[i].index, f = x->f[j].index, e;
    const pxi_face *F = &cj->f[f];
    px_vec3 q = to_other(x, i, ci->v[v]);
    if (face_violation(x->tie, cj, f, q, &e)) {
        x->f[j] = feat(PX_FEATURE_EDGE, e);
        return LC_CONTINUE;
    }
    /* Height measured from a vertex of the face, not from the origin: the
     * rounding error then scales with the body, not with its position. */
    const px_vec3 f0 = cj->v[cj->f_verts[F->first]];
    double h = pxi_dot(F->n, pxi_sub(q, f0));
    x->p[i] = ci->v[v];
    if (fabs(h) <= PXI_LC_CONTACT * (pxi_max_abs(q) + cj->scale)) {
        /* The vertex lies on the face plane up to the rounding of q: contact. */
        x->p[j] = q;
        x->dist = 0.0;
        x->band = 1;
        return LC_PENETRATION;
    }
    /* Is the foot of the perpendicular in VR(v)? An edge at v along which
     * |height| decreases (h * n.u_out < 0) is closer to F (Mirtich §4). */
    px_vec3 n_i = dir_to_other(x, j, F->n);
    if (h < 0.0) n_i = pxi_neg(n_i);
    uint32_t level[8], nl;
    uint32_t best_e = steepest_descent(ci, v, n_i, level, &nl);
    /* Two edges level with F within rounding that continue a straight line:
     * v sits on a straight stretch of a face's boundary, whose descent may
     * run inside the face, along no edge of v (see ridge_descent). */
    uint32_t ka, kb;
    if (best_e == NONE && nl >= 2 && straight_pair(ci, v, level, nl, &ka, &kb)) {
        uint32_t end;
        best_e = ridge_descent(ci, v, n_i, ka, kb, &end);
        if (best_e == LC_RIDGE_UNKNOWN) return LC_OUT_OF_STEPS;
        if (best_e == NONE && end != NONE) {
            /* The stretch is level and nothing descends from it (it lies on
             * a face parallel to F): its end, a corner, is as close, and a
             * tracked query kept there does not walk the stretch again
             * (review s32: 60 vertices walked at every query, 24x slower). */
            x->f[i] = feat(PX_FEATURE_VERTEX, end);
            return LC_CONTINUE;
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
    /* Inside or on every face plane, up to the rounding of q (NaN also ends
     * here): a vertex lying on the other body's surface is contact. */
    if (!(hb > PXI_LC_CONTACT * (pxi_max_abs(q) + cj->scale))) {
        x->p[j] = q;
        x->dist = 0.0;
        x->band = !(hb < -PXI_LC_CONTACT * (pxi_max_abs(q) + cj->scale)); /* inside by less than noise */
        return LC_PENETRATION;
    }
    x->f[j] = feat(PX_FEATURE_FACE, g);
    return LC_CONTINUE;
}

/* Mirtich's clipping test of segment [p0, p1] (in the frame of edge e's
 * body) against VR(e). Returns 1 if e is still a candidate for the segment,
 * else 0 with *nbr the neighbour of e to move to:
 * - the segment lies wholly beyond one region plane: that plane's neighbour
 *   ("simple exclusion");
 * - otherwise, on the part of the segment inside the region, the distance to
 *   e's line grows as the segment leaves the region at lo (or shrinks as it
 *   leaves at hi): the neighbour across that plane is closer. The sign of
 *   the derivative is (P - Q) . (p1 - p0), Q the foot of P on e's line.
 * Compared with testing one closest point against the region, this decides
 * from the whole edge, which matters when e's region is a wedge thinner than
 * rounding (faces meeting at a dihedral of 1e-12): then the segment leaves it
 * at once and the derivative still says which side is closer.
 * Returns -1 on a compound exclusion (two planes cut the segment off from
 * both ends); the caller then falls back to the closest-point test. */
/* Sign of the derivative of the distance from P (moving along dir) to the
 * line of edge E, at a point P where the segment crosses region plane k of
 * E (0 tail, 1 head, 2 left face, 3 right face). On a VE plane the foot of P
 * is that endpoint: (P - v) . dir. On an FE plane P - foot is normal to the
 * face, so the derivative is (height of P above the face) * (n . dir): the
 * same sign as (P - foot) . dir, but computed without the in-plane part of
 * P - foot, which is zero in exact arithmetic and pure rounding noise in
 * doubles (it would swamp a true slope of 1e-17 where faces meet at 1e-12). */
static double edge_slope(const px_convex *c, const pxi_edge *E, int k, px_vec3 P, px_vec3 dir) {
    if (k < 2) return pxi_dot(pxi_sub(P, c->v[k == 0 ? E->tail : E->head]), perp(dir, E->u));
    px_vec3 n = c->f[k == 2 ? E->left : E->right].n;
    double h = pxi_dot(pxi_sub(P, c->v[E->tail]), n), s = pxi_dot(n, dir);
    return (h > 0.0) == (s > 0.0) ? (h == 0.0 || s == 0.0 ? 0.0 : 1.0) : -1.0;
}

static int clip_against_edge(const px_convex *c, uint32_t e, px_vec3 p0, px_vec3 p1, px_feature *nbr) {
    const pxi_edge *E = &c->e[e];
    px_vec3 t = c->v[E->tail], h = c->v[E->head];
    px_vec3 d0 = pxi_sub(p0, t), d1 = pxi_sub(p1, t);
    /* Region side is >= 0 for each plane. */
    double a[4] = {pxi_dot(d0, E->u), pxi_dot(pxi_sub(h, p0), E->u), -pxi_dot(d0, E->wl),
                   -pxi_dot(d0, E->wr)};
    double b[4] = {pxi_dot(d1, E->u), pxi_dot(pxi_sub(h, p1), E->u), -pxi_dot(d1, E->wl),
                   -pxi_dot(d1, E->wr)};
    px_feature n[4] = {feat(PX_FEATURE_VERTEX, E->tail), feat(PX_FEATURE_VERTEX, E->head),
                       feat(PX_FEATURE_FACE, E->left), feat(PX_FEATURE_FACE, E->right)};
    double lo = 0.0, hi = 1.0;
    int nlo = -1, nhi = -1;
    for (int k = 0; k < 4; ++k) {
        if (a[k] < 0.0 && b[k] < 0.0) {
            *nbr = n[k];
            return 0;
        }
        if (a[k] < 0.0) {
            double lam = a[k] / (a[k] - b[k]);
            if (lam > lo) lo = lam, nlo = k;
        } else if (b[k] < 0.0) {
            double lam = a[k] / (a[k] - b[k]);
            if (lam < hi) hi = lam, nhi = k;
        }
    }
    if (lo > hi) return -1;
    px_vec3 dir = unit_scale_dir(pxi_sub(p1, p0));
    if (nlo >= 0 && edge_slope(c, E, nlo, lerp(p0, p1, lo), dir) > 0.0) {
        *nbr = n[nlo];
        return 0;
    }
    if (nhi >= 0 && edge_slope(c, E, nhi, lerp(p0, p1, hi), dir) < 0.0) {
        *nbr = n[nhi];
        return 0;
    }
    return 1;
}

static int edge_edge(lc_ctx *x, int i) {
    int j = 1 - i;
    const px_convex *ci = x->c[i], *cj = x->c[j];
    const pxi_edge *Ei = &ci->e[x->f[i].index], *Ej = &cj->e[x->f[j].index];
    px_vec3 p0 = to_other(x, i, ci->v[Ei->tail]), p1 = edge_head_in_other(x, i, Ei, p0);
    px_vec3 q0 = cj->v[Ej->tail], q1 = cj->v[Ej->head];
    px_feature nbr;
    int compound = 0;
    if (x->tie == 0.0) { /* exact mode: V-Clip's clipping tests, each edge against the other's region */
        int r = clip_against_edge(cj, x->f[j].index, p0, p1, &nbr);
        if (r == 0) {
            x->f[j] = nbr;
            return LC_CONTINUE;
        }
        px_vec3 r0 = to_other(x, j, q0), r1 = edge_head_in_other(x, j, Ej, r0);
        int r2 = clip_against_edge(ci, x->f[i].index, r0, r1, &nbr);
        if (r2 == 0) {
            x->f[i] = nbr;
            return LC_CONTINUE;
        }
        compound = r < 0 || r2 < 0;
    }
    double s, t;
    pxi_segment_closest(p0, p1, q0, q1, &s, &t);
    px_vec3 xp = lerp(p0, p1, s), yq = lerp(q0, q1, t);
    if (compound || x->tie != 0.0) {
        /* Closest-point tests (Lin-Canny proper), also the tie-breaking mode. */
        if (edge_violation(x->tie, cj, x->f[j].index, xp, &nbr)) {
            x->f[j] = nbr;
            return LC_CONTINUE;
        }
        if (edge_violation(x->tie, ci, x->f[i].index, to_other(x, j, yq), &nbr)) {
            x->f[i] = nbr;
            return LC_CONTINUE;
        }
    }
    x->p[i] = lerp(ci->v[Ei->tail], ci->v[Ei->head], s);
    x->p[j] = yq;
    x->dist = pxi_len_safe(pxi_sub(xp, yq));
    return x->dist > 0.0 ? LC_DONE : LC_PENETRATION;
}

/* Boundary feature of face f (body c) closest to segment [p0, p1] (c's
 * frame): an edge, or a vertex when the closest point is an edge end. */
static px_feature closest_boundary_feature(const px_convex *c, uint32_t f, px_vec3 p0, px_vec3 p1) {
    const pxi_face *F = &c->f[f];
    double best = INFINITY;
    px_feature out = feat(PX_FEATURE_EDGE, c->f_edges[F->first]);
    /* Squared distances compared at unit scale when they would overflow or
     * underflow (k = 1, the plain squares, in the safe range). */
    double m = c->scale + pxi_max_abs(p0) + pxi_max_abs(p1), ks = pxi_len_ok(m) ? 1.0 : pxi_pow2_unit(m);
    for (uint32_t k = 0; k < F->count; ++k) {
        uint32_t e = c->f_edges[F->first + k];
        const pxi_edge *E = &c->e[e];
        double s, t;
        pxi_segment_closest(p0, p1, c->v[E->tail], c->v[E->head], &s, &t);
        double d2 = pxi_len2(pxi_scale(pxi_sub(lerp(p0, p1, s), lerp(c->v[E->tail], c->v[E->head], t)), ks));
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
    px_vec3 p0 = to_other(x, i, ci->v[Ei->tail]), p1 = edge_head_in_other(x, i, Ei, p0);
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
    const px_vec3 f0 = cj->v[cj->f_verts[F->first]];
    double hl = pxi_dot(F->n, pxi_sub(plo, f0)), hh = pxi_dot(F->n, pxi_sub(phi, f0));
    /* Sign tests, not products: a product of two tiny heights underflows.
     * A height within the rounding of the points is contact, as in
     * vertex_face (deciding its sign here and there independently would let
     * the two states undo each other). */
    double hnoise = PXI_LC_CONTACT * (pxi_max_abs(plo) + pxi_max_abs(phi) + cj->scale);
    if (fabs(hl) <= hnoise || fabs(hh) <= hnoise || (hl <= 0.0) != (hh <= 0.0) || hl == 0.0 || hh == 0.0 ||
        !(hl == hl && hh == hh)) {
        /* The clipped edge meets the face plane inside the prism: the edge
         * pierces (or touches) the face. Witness: the crossing point. */
        double lam;
        if ((hl < 0.0) != (hh < 0.0) && hl != hh) { /* a real crossing */
            lam = lo + (hi - lo) * (hl / (hl - hh));
            if (!(lam >= lo)) lam = lo;
            if (!(lam <= hi)) lam = hi;
        } else { /* an end within rounding of the plane: that end */
            lam = fabs(hl) <= fabs(hh) ? lo : hi;
        }
        x->p[j] = lerp(p0, p1, lam);
        x->p[i] = lerp(ci->v[Ei->tail], ci->v[Ei->head], lam);
        x->dist = 0.0;
        x->band = fabs(hl) <= hnoise || fabs(hh) <= hnoise; /* an end on the plane within rounding */
        return LC_PENETRATION;
    }
    /* Same side: |height| is linear along the clipped edge; follow its
     * decrease to the end of the clipped part. There the closest feature is
     * the prism side that clipped it, or the edge's own endpoint. */
    /* The slope from the rotated direction alone: a difference of two
     * translated points loses the edge's direction when the translation is
     * large next to the edge (a 1e-6 edge at 1e12: all rounding). */
    double slope = pxi_dot(F->n, dir_to_other(x, i, Ei->u));
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

/* Runs the walk from x->f. Returns the final state, LC_REPEAT when it
 * revisited a recent pair (a floating-point cycle), or LC_OUT_OF_STEPS. */
static int lc_walk(lc_ctx *x, uint32_t max_steps, uint32_t *iterations) {
    px_feature ring[2][8];
    memset(ring, 0xff, sizeof ring);
    for (uint32_t step = 0; step < max_steps; ++step) {
        int r = lc_step(x);
#ifdef PXI_TRACE_WALK
        fprintf(stderr, "step %u: r=%d A %u:%u B %u:%u\n", step, r, x->f[0].type, x->f[0].index, x->f[1].type,
                x->f[1].index);
#endif
        if (r != LC_CONTINUE) return r;
        ++*iterations;
        /* In exact arithmetic no pair repeats (the distance never grows, and
         * at equal distance the dimension drops). A repeat is round-off. */
        for (int k = 0; k < 8; ++k)
            if (ring[0][k].type == x->f[0].type && ring[0][k].index == x->f[0].index &&
                ring[1][k].type == x->f[1].type && ring[1][k].index == x->f[1].index)
                return LC_REPEAT;
        ring[0][step & 7] = x->f[0];
        ring[1][step & 7] = x->f[1];
    }
    return LC_OUT_OF_STEPS;
}

/* A terminal pair proves separation only if its tests were decided beyond
 * rounding. Near contact that can fail: two copies of one body at one pose
 * end at a vertex pair, or a vertex on a face, with d ~ 1e-16 although the
 * solids overlap completely. Two checks, both only in that rare band:
 * - a distance within the rounding noise of the coordinates is contact;
 * - where the pair has a face, its normal (exact, unlike the direction
 *   between two nearly coincident points) gives a separating-plane test:
 *   B's highest and A's lowest vertex along it, by support queries. If they
 *   overlap by more than the noise, the solids intersect.
 * Returns 1 when the pair is really contact. */
static int contact_within_rounding(lc_ctx *x) {
    const px_convex *a = x->c[0], *b = x->c[1];
    px_vec3 pa = pxi_xform(&x->T[0], x->p[0]);
    double noise_d = PXI_LC_CONTACT * (pxi_max_abs(pa) + pxi_max_abs(x->p[1]));
    if (x->dist <= noise_d) {
        x->band = 1;
        return 1;
    }
    if (x->dist > 1e-8 * pxi_pair_size_bound(a, b, &x->T[0]))
        return 0; /* cheap first: the bound >= the size */
    double span = pxi_pair_size(a, b, &x->T[0]);
    if (x->dist > 1e-8 * span) return 0;
    px_vec3 n; /* B -> A, B's frame */
    if (x->f[1].type == PX_FEATURE_FACE)
        n = b->f[x->f[1].index].n;
    else if (x->f[0].type == PX_FEATURE_FACE)
        n = pxi_neg(pxi_rot(x->T[0].r, a->f[x->f[0].index].n));
    else
        return 0;
    uint32_t vb = pxi_support(b, n, UINT32_MAX);
    uint32_t va = pxi_support(a, pxi_rot_t(x->T[0].r, pxi_neg(n)), UINT32_MAX);
    double gap = pxi_dot(n, pxi_xform(&x->T[0], a->v[va])) - pxi_dot(n, b->v[vb]);
    return gap < -64.0 * DBL_EPSILON * span;
}

void pxi_lin_canny(const px_convex *a, const px_convex *b, const px_pose *t_ab, const pxi_lc_start *start,
                   pxi_answer *out) {
    lc_ctx x;
    x.c[0] = a;
    x.c[1] = b;
    x.T[0] = *t_ab;
    /* T_BA = T_AB^-1 = (R^T, -R^T t), cheaper than a second product. */
    for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 3; ++k) x.T[1].r[3 * r + k] = x.T[0].r[3 * k + r];
    x.T[1].t = pxi_neg(pxi_rot_t(x.T[0].r, x.T[0].t));
    x.dist = 0.0;
    x.p[0] = x.p[1] = pxi_v(0, 0, 0);
    x.band = 0;
    x.tie = start->tie ? PXI_LC_TIE : 0.0;

    uint64_t total = (uint64_t)a->nv + a->ne + a->nf + b->nv + b->ne + b->nf;
    uint32_t cap = total > 100000000u ? 400000000u : (uint32_t)(4 * total + 64);
    int warm = pxi_feature_valid(a, start->fa) && pxi_feature_valid(b, start->fb);
    if (warm) {
        x.f[0] = start->fa;
        x.f[1] = start->fb;
    } else {
        /* Cold: the vertices extreme along the line of centres; on round
         * bodies about 4 steps from the answer. */
        px_vec3 ab = pxi_sub(b->center, pxi_xform(&x.T[0], a->center)); /* B's frame */
        x.f[0] = feat(PX_FEATURE_VERTEX, pxi_support(a, pxi_rot_t(x.T[0].r, ab), UINT32_MAX));
        x.f[1] = feat(PX_FEATURE_VERTEX, pxi_support(b, pxi_neg(ab), UINT32_MAX));
    }
    uint32_t budget = !warm && start->budget > 0 && start->budget < cap ? start->budget : cap, iterations = 0;
    int r = lc_walk(&x, budget, &iterations);
    out->outcome = PXI_DONE;
    if (r == LC_OUT_OF_STEPS && budget < cap) {
        out->outcome = PXI_OUT_OF_STEPS; /* a budgeted cold walk: the caller seeds it */
    } else if (r < 0 && x.tie == 0.0) {
        /* A revisited pair: round-off ties between neighbouring regions.
         * Continue from there with tie-breaking margins (see noise()). */
        x.tie = PXI_LC_TIE;
        r = lc_walk(&x, cap, &iterations);
    }
    if (out->outcome == PXI_DONE && r < 0) out->outcome = PXI_UNPROVEN; /* still cycling */
    out->fa = x.f[0];
    out->fb = x.f[1];
    out->iterations = iterations;
    out->gap = 0.0;
    out->quality = 0;
    if (out->outcome != PXI_DONE) {
        out->distance = 0.0;
        out->intersecting = 0;
        out->pa = out->pb = pxi_v(0, 0, 0);
        return;
    }
    if (r == LC_DONE && contact_within_rounding(&x)) r = LC_PENETRATION;
    out->distance = r == LC_PENETRATION ? 0.0 : x.dist;
    out->intersecting = r == LC_PENETRATION;
    out->quality = out->intersecting && x.band ? PX_QUALITY_CONTACT_BAND : 0u;
    out->pa = x.p[0];
    out->pb = x.p[1];
}
