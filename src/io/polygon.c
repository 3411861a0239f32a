/* Ear clipping of a mesh file's polygons (polygon.h).
 *
 * Every simple polygon of four or more corners has two ears: corners whose
 * triangle with their two neighbours lies inside it, no other corner in or
 * on it (G. H. Meisters, "Polygons have ears", Amer. Math. Monthly 82,
 * 1975). Cutting an ear leaves a simple polygon one corner smaller, so
 * cutting ears until three corners remain gives n - 2 triangles that tile
 * the polygon (the method as in D. Eberly, "Triangulation by ear
 * clipping", Geometric Tools, 2002: only reflex corners can block an ear,
 * and cutting one changes only its two neighbours).
 *
 * The polygon is projected on the coordinate plane its Newell normal (M.
 * Newell's sum of the edges' cross products) is most across, and every
 * decision is an exact orientation sign (Shewchuk's orient2d, math/orient.h)
 * of projected corners, which are the file's coordinates themselves: no
 * rounding decides whether a corner is convex or a point is inside. A
 * corner on the line of its neighbours is cut first (its triangle has no
 * area: a straight-through corner or the tip of a spike, either way on the
 * polygon's boundary). Corners at the same point as a corner of the
 * candidate ear (a polygon with a hole joined by a bridge visits them
 * twice) do not block it.
 */
#include "io/polygon.h"

#include <math.h>
#include <stddef.h>

#include "math/orient.h"

enum { CONVEX = 1, FLAT = 2, REFLEX = 3, GONE = 0 };

/* The corner's turn: CONVEX, FLAT or REFLEX, for a polygon turning counter-
 * clockwise in (u, v) when s = 1 (clockwise when s = -1). */
static unsigned char turn(const double *uv, uint32_t p, uint32_t i, uint32_t q, int s) {
    int o =
        pxi_orient2d_sign(uv[2 * p], uv[2 * p + 1], uv[2 * i], uv[2 * i + 1], uv[2 * q], uv[2 * q + 1]) * s;
    return o > 0 ? CONVEX : o < 0 ? REFLEX : FLAT;
}

static int same(const double *uv, uint32_t a, uint32_t b) {
    return uv[2 * a] == uv[2 * b] && uv[2 * a + 1] == uv[2 * b + 1];
}

/* 1 when corner i (convex, neighbours p and q) is an ear: no remaining
 * reflex or flat corner lies in or on triangle (p, i, q), apart from those
 * at the same point as one of its corners. */
static int is_ear(const pxi_polygon_work *w, uint32_t p, uint32_t i, uint32_t q, int s) {
    const double *uv = w->uv;
    for (uint32_t r = w->next[q]; r != p; r = w->next[r]) {
        if (w->state[r] == CONVEX || same(uv, r, p) || same(uv, r, i) || same(uv, r, q)) continue;
        const double ru = uv[2 * r], rv = uv[2 * r + 1];
        if (s * pxi_orient2d_sign(uv[2 * p], uv[2 * p + 1], uv[2 * i], uv[2 * i + 1], ru, rv) >= 0 &&
            s * pxi_orient2d_sign(uv[2 * i], uv[2 * i + 1], uv[2 * q], uv[2 * q + 1], ru, rv) >= 0 &&
            s * pxi_orient2d_sign(uv[2 * q], uv[2 * q + 1], uv[2 * p], uv[2 * p + 1], ru, rv) >= 0)
            return 0;
    }
    return 1;
}

/* Sign of orient2d(uv[a], uv[b], uv[c]). */
static int orient(const double *uv, uint32_t a, uint32_t b, uint32_t c) {
    return pxi_orient2d_sign(uv[2 * a], uv[2 * a + 1], uv[2 * b], uv[2 * b + 1], uv[2 * c], uv[2 * c + 1]);
}

/* 1 when two edges of the polygon that share no corner cross properly
 * (each edge's ends strictly on both sides of the other's line): the
 * polygon is not simple, and an ear clipping, which may still find ears,
 * would give triangles of no defined shape (a bow tie). Edges that touch
 * or overlap in line (a bridge to a hole, walked both ways) do not count.
 * O(n^2); the caller bounds the sum of n^2 over a file. */
static int crosses(const double *uv, uint32_t n) {
    for (uint32_t i = 0; i + 2 < n; ++i) {
        const uint32_t i1 = i + 1;
        for (uint32_t j = i + 2; j < n; ++j) {
            const uint32_t j1 = j + 1 < n ? j + 1 : 0;
            if (j1 == i) continue; /* adjacent through the last corner */
            if (orient(uv, i, i1, j) * orient(uv, i, i1, j1) < 0 &&
                orient(uv, j, j1, i) * orient(uv, j, j1, i1) < 0)
                return 1;
        }
    }
    return 0;
}

int pxi_polygon_triangulate(const double *xyz, const uint32_t *idx, uint32_t n, pxi_polygon_work *w,
                            uint32_t *out) {
    /* Newell's normal, about the first corner (smaller products). */
    const double *o = xyz + 3 * (size_t)idx[0];
    double nrm[3] = {0, 0, 0};
    for (uint32_t k = 0; k < n; ++k) {
        const double *a = xyz + 3 * (size_t)idx[k], *b = xyz + 3 * (size_t)idx[k + 1 < n ? k + 1 : 0];
        const double ax = a[0] - o[0], ay = a[1] - o[1], az = a[2] - o[2];
        const double bx = b[0] - o[0], by = b[1] - o[1], bz = b[2] - o[2];
        nrm[0] += ay * bz - az * by;
        nrm[1] += az * bx - ax * bz;
        nrm[2] += ax * by - ay * bx;
    }
    int drop = 2;
    if (fabs(nrm[0]) > fabs(nrm[drop])) drop = 0;
    if (fabs(nrm[1]) > fabs(nrm[drop])) drop = 1;
    const int cu = (drop + 1) % 3, cv = (drop + 2) % 3; /* (u, v, drop) is right-handed */
    double *uv = w->uv;
    for (uint32_t k = 0; k < n; ++k) {
        uv[2 * k] = xyz[3 * (size_t)idx[k] + cu];
        uv[2 * k + 1] = xyz[3 * (size_t)idx[k] + cv];
    }
    /* The winding in (u, v), exactly: the turn at the lowest corner (of
     * least u, then v), which is convex for a simple polygon; Newell's
     * sign where that corner does not turn (a neighbour at the same point
     * or in line); 0 when neither says: no area, a fan of flat triangles. */
    uint32_t m = 0;
    for (uint32_t k = 1; k < n; ++k)
        if (uv[2 * k] < uv[2 * m] || (uv[2 * k] == uv[2 * m] && uv[2 * k + 1] < uv[2 * m + 1])) m = k;
    const uint32_t mp = m ? m - 1 : n - 1, mq = m + 1 < n ? m + 1 : 0;
    int s =
        pxi_orient2d_sign(uv[2 * mp], uv[2 * mp + 1], uv[2 * m], uv[2 * m + 1], uv[2 * mq], uv[2 * mq + 1]);
    if (s == 0) s = nrm[drop] > 0 ? 1 : nrm[drop] < 0 ? -1 : 0;
    uint32_t t = 0;
    if (s == 0) {
        for (uint32_t k = 1; k + 1 < n; ++k, ++t) {
            out[3 * t] = idx[0];
            out[3 * t + 1] = idx[k];
            out[3 * t + 2] = idx[k + 1];
        }
        return 1;
    }
    if (crosses(uv, n)) return 0;
    for (uint32_t k = 0; k < n; ++k) {
        w->prev[k] = k ? k - 1 : n - 1;
        w->next[k] = k + 1 < n ? k + 1 : 0;
    }
    for (uint32_t k = 0; k < n; ++k) w->state[k] = turn(uv, w->prev[k], k, w->next[k], s);
    /* From corner 1: a convex quad is cut along 0-2, as Assimp cuts it. */
    uint32_t left = n, i = 1, misses = 0;
    while (left > 3) {
        const uint32_t p = w->prev[i], q = w->next[i];
        const int ear = w->state[i] == FLAT || (w->state[i] == CONVEX && is_ear(w, p, i, q, s));
        if (!ear) {
            if (++misses >= left) return 0; /* a whole turn without an ear */
            i = q;
            continue;
        }
        out[3 * t] = idx[p];
        out[3 * t + 1] = idx[i];
        out[3 * t + 2] = idx[q];
        ++t;
        w->next[p] = q;
        w->prev[q] = p;
        w->state[i] = GONE;
        --left;
        w->state[p] = turn(uv, w->prev[p], p, q, s);
        w->state[q] = turn(uv, p, q, w->next[q], s);
        misses = 0;
        /* p's triangle changed: it may be an ear now (a flat one first). */
        i = w->state[p] == FLAT ? p : q;
    }
    out[3 * t] = idx[w->prev[i]];
    out[3 * t + 1] = idx[i];
    out[3 * t + 2] = idx[w->next[i]];
    return 1;
}
