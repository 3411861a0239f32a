/* Penetration depth of intersecting convex polytopes by the Expanding
 * Polytope Algorithm.
 *
 * Sources: G. van den Bergen, "Proximity queries and penetration depth
 * computation on 3D game objects", GDC 2001, and his book "Collision
 * Detection in Interactive 3D Environments" (2004), §4.3.8 (EPA); S.
 * Cameron, "Enhancing GJK: computing minimum and penetration distances
 * between convex polyhedra", ICRA 1997 (penetration distance as the
 * distance from the origin to the boundary of A - B).
 *
 * The idea. For intersecting A and B the origin lies inside K = A - B, and
 * the penetration depth is the distance from the origin to K's boundary:
 * the shortest translation of B (by depth * n) after which the two only
 * touch. EPA keeps a polytope P inside K that contains the origin, made of
 * support points of K (vertex pairs). Each step takes P's face nearest the
 * origin, with outward normal n and offset d, and asks for K's support
 * point w along n. If n.w is d (within rounding), that face lies on K's
 * boundary and d is the depth: every other face of P is farther, and P is
 * inside K. Otherwise w is added and the faces it sees are replaced by a
 * cone from their horizon to w. On polytopes the support points are
 * vertices of K, so the loop ends after finitely many steps with the exact
 * facet.
 *
 * Robustness (fcl #346, #578, #390; libccd #7, #25): the start tetrahedron
 * is grown from whatever GJK ended with (a point, a segment or a triangle
 * through the origin when the bodies touch or sit exactly on top of each
 * other) by supports in directions orthogonal to it; faces are oriented by
 * an interior point, not by the origin, so a face through the origin
 * (touching bodies) still has a well-defined outward normal; the polytope
 * lives in fixed arrays (queries never allocate) and a full budget ends the
 * loop with the best bound so far, flagged as a fallback.
 */
#include <float.h>
#include <math.h>
#include <string.h>

#include "convex/convex.h"
#include "math/vec3.h"
#include "narrow/feature.h"
#include "narrow/narrow.h"
#include "narrow/simplex.h"
#include "narrow/tolerance.h"

#define EPA_MAX_V 192
#define EPA_MAX_F (2 * EPA_MAX_V)
#define EPA_MAX_H (3 * EPA_MAX_V)

typedef struct epa_face {
    int v[3];
    px_vec3 n; /* outward unit normal */
    double d;  /* n . p for p in the face: distance of the origin's plane */
    int alive;
} epa_face;

typedef struct epa {
    const px_convex *a, *b;
    const px_pose *t;
    double k;      /* power-of-two scale (as in GJK) */
    px_vec3 inner; /* a point strictly inside P */
    sx_point v[EPA_MAX_V];
    int nv;
    epa_face f[EPA_MAX_F];
    int nf;               /* slots in use (alive or dead) */
    int free_[EPA_MAX_F]; /* dead slots to reuse */
    int nfree;
} epa;

static sx_point epa_point(const epa *e, uint32_t ia, uint32_t ib) {
    return sx_pair_point(e->a, e->b, e->t, e->k, ia, ib);
}

/* Support of K along n (scaled frame): A extreme along n, B along -n.
 * `hint` (may be NULL) is a point of K near the answer, whose vertices start
 * the climbs: the closest face's vertex, a few steps from the support along
 * its normal. */
static sx_point epa_support(const epa *e, px_vec3 n, const sx_point *hint) {
    uint32_t ia = pxi_support(e->a, pxi_rot_t(e->t->r, n), hint ? hint->ia : UINT32_MAX);
    uint32_t ib = pxi_support(e->b, pxi_neg(n), hint ? hint->ib : UINT32_MAX);
    return epa_point(e, ia, ib);
}

/* Adds face (i, j, l) oriented away from the interior point, in a dead
 * slot if there is one. Returns its slot, or -1 when it is degenerate (no
 * normal) or the arrays are full. */
static int epa_add_face(epa *e, int i, int j, int l) {
    int slot;
    if (e->nfree > 0)
        slot = e->free_[--e->nfree];
    else if (e->nf < EPA_MAX_F)
        slot = e->nf++;
    else
        return -1;
    px_vec3 a = e->v[i].w, b = e->v[j].w, c = e->v[l].w;
    px_vec3 n = pxi_cross(pxi_sub(b, a), pxi_sub(c, a));
    double len = pxi_len(n);
    if (!(len > 0.0) || !isfinite(len)) {
        e->free_[e->nfree++] = slot;
        return -1;
    }
    n = pxi_scale(n, 1.0 / len);
    epa_face *F = &e->f[slot];
    if (pxi_dot(n, pxi_sub(a, e->inner)) < 0.0) {
        n = pxi_neg(n);
        F->v[0] = i, F->v[1] = l, F->v[2] = j;
    } else {
        F->v[0] = i, F->v[1] = j, F->v[2] = l;
    }
    F->n = n;
    /* Offset from the face's three points (the average is symmetric in them). */
    F->d = (pxi_dot(n, a) + pxi_dot(n, b) + pxi_dot(n, c)) / 3.0;
    F->alive = 1;
    return slot;
}

/* Width of K in direction u: the larger of its two supports, with which
 * point. Used to grow a flat start simplex into a tetrahedron. */
static sx_point epa_far_side(const epa *e, px_vec3 u, px_vec3 base) {
    sx_point p = epa_support(e, u, NULL), q = epa_support(e, pxi_neg(u), NULL);
    double hp = pxi_dot(u, pxi_sub(p.w, base)), hq = -pxi_dot(u, pxi_sub(q.w, base));
    return hp >= hq ? p : q;
}

/* Any unit vector orthogonal to u. */
static px_vec3 orthogonal(px_vec3 u) {
    px_vec3 t = fabs(u.x) < 0.57 ? pxi_v(1, 0, 0) : fabs(u.y) < 0.57 ? pxi_v(0, 1, 0) : pxi_v(0, 0, 1);
    px_vec3 o = pxi_cross(u, t);
    double l = pxi_len(o);
    return l > 0.0 ? pxi_scale(o, 1.0 / l) : pxi_v(1, 0, 0);
}

/* Grows the start simplex (1-4 points whose hull holds the origin, up to
 * rounding) to a tetrahedron of positive volume: each added point is K's
 * farthest support orthogonal to the current hull, so the origin stays in
 * the hull (on its boundary at worst). Returns 0 when K is flat within
 * rounding in some direction (impossible for solids; NaN input). */
static int epa_start(epa *e, const pxi_simplex_pairs *start) {
    e->nv = 0;
    if (start)
        for (int m = 0; m < start->n && m < 4; ++m) {
            if (start->ia[m] >= e->a->nv || start->ib[m] >= e->b->nv) continue;
            e->v[e->nv++] = epa_point(e, start->ia[m], start->ib[m]);
        }
    if (e->nv == 0)
        e->v[e->nv++] = epa_support(e, pxi_v(0.5773502691896258, 0.5773502588, 0.5773502794), NULL);
    double tiny = 1e-13; /* scaled units: the pair spans about 1 */
    /* A tetrahedron given by GJK is kept only if it has real volume. */
    if (e->nv == 4) {
        px_vec3 o = e->v[0].w;
        double vol = pxi_dot(pxi_sub(e->v[1].w, o), pxi_cross(pxi_sub(e->v[2].w, o), pxi_sub(e->v[3].w, o)));
        if (!(fabs(vol) > tiny * tiny * tiny)) e->nv = 3;
    }
    if (e->nv == 3) {
        px_vec3 o = e->v[0].w;
        px_vec3 n = pxi_cross(pxi_sub(e->v[1].w, o), pxi_sub(e->v[2].w, o));
        if (!(pxi_len(n) > tiny * tiny)) e->nv = 2;
    }
    if (e->nv == 2 && !(pxi_len(pxi_sub(e->v[1].w, e->v[0].w)) > tiny)) e->nv = 1;
    while (e->nv < 4) {
        px_vec3 o = e->v[0].w, u;
        if (e->nv == 1) {
            u = pxi_v(0.5773502691896258, 0.5773502588, 0.5773502794);
        } else if (e->nv == 2) {
            px_vec3 s = pxi_sub(e->v[1].w, o);
            u = orthogonal(pxi_scale(s, 1.0 / pxi_len(s)));
        } else {
            u = pxi_cross(pxi_sub(e->v[1].w, o), pxi_sub(e->v[2].w, o));
            u = pxi_scale(u, 1.0 / pxi_len(u));
        }
        sx_point p = epa_far_side(e, u, o);
        if (!(fabs(pxi_dot(u, pxi_sub(p.w, o))) > tiny)) {
            if (e->nv == 2) { /* the segment may be K's width: try the other normal */
                px_vec3 s = pxi_sub(e->v[1].w, o);
                u = pxi_cross(pxi_scale(s, 1.0 / pxi_len(s)), u);
                p = epa_far_side(e, u, o);
                if (!(fabs(pxi_dot(u, pxi_sub(p.w, o))) > tiny)) return 0;
            } else {
                return 0;
            }
        }
        e->v[e->nv++] = p;
    }
    e->inner = pxi_scale(pxi_add(pxi_add(e->v[0].w, e->v[1].w), pxi_add(e->v[2].w, e->v[3].w)), 0.25);
    e->nf = 0;
    e->nfree = 0;
    static const int tf[4][3] = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
    for (int k = 0; k < 4; ++k)
        if (epa_add_face(e, tf[k][0], tf[k][1], tf[k][2]) < 0) return 0;
    return 1;
}

static int epa_closest_face(const epa *e) {
    int best = -1;
    for (int k = 0; k < e->nf; ++k)
        if (e->f[k].alive && (best < 0 || e->f[k].d < e->f[best].d)) best = k;
    return best;
}

/* Replaces the faces that see w by the cone from their horizon to w (the
 * new vertex e->nv - 1), and returns the slot of the face nearest the
 * origin afterwards (one pass finds both: survivors are compared while
 * visibility is tested, new faces as they are made). The face `seed` sees w
 * by construction, which keeps the visible set non-empty. Returns -1 when
 * the budget is exhausted or a new face is degenerate. */
static int epa_expand(epa *e, int seed) {
    int w = e->nv - 1, best = -1;
    px_vec3 pw = e->v[w].w;
    int horizon[EPA_MAX_H][2], nh = 0;
    for (int k = 0; k < e->nf; ++k) {
        epa_face *F = &e->f[k];
        if (!F->alive) continue;
        if (k != seed && !(pxi_dot(F->n, pw) - F->d > 0.0)) {
            if (best < 0 || F->d < e->f[best].d) best = k;
            continue;
        }
        F->alive = 0;
        e->free_[e->nfree++] = k;
        /* Each edge of a removed face: drop it if its twin was already
         * listed (both neighbours removed), else list it. */
        for (int m = 0; m < 3; ++m) {
            int i = F->v[m], j = F->v[(m + 1) % 3], found = -1;
            for (int h = 0; h < nh; ++h)
                if (horizon[h][0] == j && horizon[h][1] == i) found = h;
            if (found >= 0) {
                horizon[found][0] = horizon[nh - 1][0];
                horizon[found][1] = horizon[nh - 1][1];
                --nh;
            } else {
                if (nh >= EPA_MAX_H) return -1;
                horizon[nh][0] = i;
                horizon[nh][1] = j;
                ++nh;
            }
        }
    }
    for (int h = 0; h < nh; ++h) {
        int k = epa_add_face(e, horizon[h][0], horizon[h][1], w);
        if (k < 0) return -1;
        if (best < 0 || e->f[k].d < e->f[best].d) best = k;
    }
    return best;
}

/* Witness points: the origin's foot d n on the closest face plane, in
 * barycentric coordinates of the face that holds it, applied to the vertex
 * pairs. K's facet there may be a polygon that P splits into several
 * coplanar triangles with equal offsets: the foot lies in one of them, not
 * necessarily the first found, so every face within rounding of the least
 * offset is tried and the one nearest the foot wins. */
static void epa_witness(const epa *e, int best, double tol, pxi_penetration *out) {
    px_vec3 foot = pxi_scale(e->f[best].n, e->f[best].d);
    sx_simplex win;
    win.n = 0;
    double win_off = INFINITY;
    for (int pass = 0; pass < 2; ++pass)
        for (int k = 0; k < e->nf; ++k) {
            const epa_face *F = &e->f[k];
            /* pass 0: the closest face itself; pass 1: its coplanar rivals */
            if (pass == 0 ? k != best : (k == best || !F->alive || !(F->d - e->f[best].d <= tol))) continue;
            sx_simplex s;
            s.n = 3;
            s.margin = 0.0;
            for (int m = 0; m < 3; ++m) {
                s.p[m] = e->v[F->v[m]];
                s.p[m].w = pxi_sub(s.p[m].w, foot);
                s.lam[m] = 0.0;
            }
            pxi_sx_triangle(&s);
            double off = pxi_len2(sx_point_of(&s));
            if (pass == 0 || off < win_off) win_off = off, win = s;
        }
    uint32_t ia[4], ib[4];
    sx_witness(&win, e->a, e->b, &out->pa, &out->pb, ia, ib);
    out->fa = pxi_feature_of_vertices(e->a, ia, win.n, &out->pa);
    out->fb = pxi_feature_of_vertices(e->b, ib, win.n, &out->pb);
}

void pxi_epa(const px_convex *a, const px_convex *b, const px_pose *t_ab, const pxi_simplex_pairs *start,
             pxi_penetration *out) {
    memset(out, 0, sizeof *out);
    epa e; /* about 32 KB of stack: queries never allocate */
    e.a = a;
    e.b = b;
    e.t = t_ab;
    e.k = pxi_pair_unit(a, b, t_ab);
    if (!epa_start(&e, start)) { /* flat within rounding: touching, no depth */
        out->flat = 1;
        return;
    }
    /* Rounding band of a support value: n.w - d within it means "on K's
     * boundary". Relative to the pair's size (1 here), like GJK's. */
    const double tol = PXI_SUPPORT_NOISE;
    int best = epa_closest_face(&e);
    uint32_t it = 0;
    /* The least support value seen, h_K(n) along a face normal n: an upper
     * bound on the depth along a direction that really separates, kept for
     * the case the budget runs out. */
    double best_h = INFINITY;
    px_vec3 best_n = {0, 0, 0};
    uint32_t best_ia = 0, best_ib = 0;
    while (best >= 0) {
        epa_face *F = &e.f[best];
        sx_point w = epa_support(&e, F->n, &e.v[F->v[0]]);
        ++it;
        if (pxi_dot(F->n, w.w) < best_h)
            best_h = pxi_dot(F->n, w.w), best_n = F->n, best_ia = w.ia, best_ib = w.ib;
        if (!(pxi_dot(F->n, w.w) - F->d > tol)) break; /* F is on K's boundary */
        int dup = 0;
        for (int m = 0; m < e.nv && !dup; ++m) dup = e.v[m].ia == w.ia && e.v[m].ib == w.ib;
        if (dup) break;
        if (e.nv >= EPA_MAX_V) {
            /* Deep overlap of finely tessellated round bodies. The support
             * value over-estimates the depth along best_n; the caller may take
             * the exact depth along it (a translation query). */
            out->outcome = PXI_OUT_OF_STEPS;
            out->iterations = it;
            out->depth = best_h > 0.0 ? best_h / e.k : 0.0;
            out->normal = best_n;
            out->pa = a->v[best_ia];
            out->pb = pxi_madd(pxi_xform(t_ab, out->pa), best_n, -out->depth);
            out->fa = pxi_feature_of_vertices(a, &best_ia, 1, NULL);
            out->fb = pxi_feature_of_vertices(b, &best_ib, 1, NULL);
            return;
        }
        e.v[e.nv++] = w;
        epa_face keep = *F;
        int next = epa_expand(&e, best);
        if (next < 0) {
            /* Degenerate cone or full arrays: report the last good face. */
            out->outcome = PXI_UNPROVEN;
            e.f[0] = keep;
            e.nf = 1;
            best = 0;
            break;
        }
        best = next;
    }
    out->iterations = it;
    if (best < 0) return;
    const epa_face *F = &e.f[best];
    out->depth = F->d > 0.0 ? F->d / e.k : 0.0;
    out->normal = F->n;
    epa_witness(&e, best, tol, out);
}
