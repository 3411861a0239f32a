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
 * corner on the line of its neighbours is cut only when no convex ear is
 * left (its triangle has no area, which would leave a closed part open; it
 * lies on the polygon's boundary: a straight-through corner or the tip of
 * a spike). A corner at the same point as a corner of the
 * candidate ear (a polygon with a hole joined by a bridge, or a spike,
 * visits the point twice) blocks it only when one of its edges starts into
 * the ear.
 */
#include "io/polygon.h"

#include <math.h>
#include <stddef.h>

#include "math/orient.h"

enum { CONVEX = 1, FLAT = 2, REFLEX = 3, GONE = 0 };

/* Sign of orient2d(uv[a], uv[b], uv[c]). */
static int orient(const double *uv, uint32_t a, uint32_t b, uint32_t c) {
    return pxi_orient2d_sign(uv[2 * a], uv[2 * a + 1], uv[2 * b], uv[2 * b + 1], uv[2 * c], uv[2 * c + 1]);
}

/* s times the orientation of (a, b, c): > 0 when c is left of a -> b in
 * the polygon's winding. */
static int left(const double *uv, uint32_t a, uint32_t b, uint32_t c, int s) {
    return s * orient(uv, a, b, c);
}

/* The corner's turn: CONVEX, FLAT or REFLEX, for a polygon turning counter-
 * clockwise in (u, v) when s = 1 (clockwise when s = -1). */
static unsigned char turn(const double *uv, uint32_t p, uint32_t i, uint32_t q, int s) {
    const int o = left(uv, p, i, q, s);
    return o > 0 ? CONVEX : o < 0 ? REFLEX : FLAT;
}

static int same(const double *uv, uint32_t a, uint32_t b) {
    return uv[2 * a] == uv[2 * b] && uv[2 * a + 1] == uv[2 * b + 1];
}

/* 1 when an edge from a corner at the same point as triangle corner c
 * (its other end x) starts into the triangle: x strictly left of both
 * triangle edges at c, (a -> c) and (c -> b). */
static int enters(const double *uv, uint32_t a, uint32_t c, uint32_t b, uint32_t x, int s) {
    return left(uv, a, c, x, s) > 0 && left(uv, c, b, x, s) > 0;
}

/* 1 when corner i (convex, neighbours p and q) is an ear: no remaining
 * reflex or flat corner lies in or on triangle (p, i, q), and no corner at
 * the same point as one of the triangle's has an edge that starts into it
 * (a polygon that visits a point twice: a bridge to a hole, the foot of a
 * spike; review s30: a spike out of a corner and back let the triangle to
 * its tip cover what the spike leaves outside). */
static int is_ear(const pxi_polygon_work *w, uint32_t p, uint32_t i, uint32_t q, int s) {
    const double *uv = w->uv;
    for (uint32_t r = w->next[q]; r != p; r = w->next[r]) {
        const uint32_t a = w->prev[r], b = w->next[r];
        if (same(uv, r, p)) {
            if (enters(uv, q, p, i, a, s) || enters(uv, q, p, i, b, s)) return 0;
            continue;
        }
        if (same(uv, r, i)) {
            if (enters(uv, p, i, q, a, s) || enters(uv, p, i, q, b, s)) return 0;
            continue;
        }
        if (same(uv, r, q)) {
            if (enters(uv, i, q, p, a, s) || enters(uv, i, q, p, b, s)) return 0;
            continue;
        }
        if (w->state[r] == CONVEX) continue;
        if (left(uv, p, i, r, s) >= 0 && left(uv, i, q, r, s) >= 0 && left(uv, q, p, r, s) >= 0) return 0;
    }
    /* Last, the ear must lie inside what is left: its centre's winding
     * number about the remaining corners is not 0. Only a polygon that
     * visits a point twice can fail here (what is left of an antenna and
     * its foot has no inside; helper-49). */
    const double cu = (uv[2 * p] + uv[2 * i] + uv[2 * q]) / 3.0,
                 cv = (uv[2 * p + 1] + uv[2 * i + 1] + uv[2 * q + 1]) / 3.0;
    int wn = 0;
    uint32_t a = p;
    do {
        const uint32_t b = w->next[a];
        const double au = uv[2 * a], av = uv[2 * a + 1], bu = uv[2 * b], bv = uv[2 * b + 1];
        const int o = pxi_orient2d_sign(au, av, bu, bv, cu, cv);
        if (av <= cv && bv > cv && o > 0) ++wn;
        if (av > cv && bv <= cv && o < 0) --wn;
        a = b;
    } while (a != p);
    return wn != 0;
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

/* Cuts ears off the polygon wound as s says (polygon.h's work arrays
 * hold its projected corners). 1 when done; 0 when a whole turn finds no
 * ear. */
static int clip(pxi_polygon_work *w, const uint32_t *idx, uint32_t n, int s, uint32_t *out) {
    const double *uv = w->uv;
    uint32_t t = 0;
    for (uint32_t k = 0; k < n; ++k) {
        w->prev[k] = k ? k - 1 : n - 1;
        w->next[k] = k + 1 < n ? k + 1 : 0;
    }
    for (uint32_t k = 0; k < n; ++k) w->state[k] = turn(uv, w->prev[k], k, w->next[k], s);
    /* From corner 1: a convex quad is cut along 0-2, as Assimp cuts it.
     * Convex ears first: a corner in line with its neighbours is cut only
     * when a whole turn finds no convex ear, because its triangle has no
     * area, and a part with such a triangle is not closed (helper-49: a
     * cube with a corner on an edge, shared by both faces, lost its
     * inside). */
    uint32_t remaining = n, i = 1, misses = 0;
    int flat_ok = 0;
    while (remaining > 3) {
        const uint32_t p = w->prev[i], q = w->next[i];
        const int ear = (flat_ok && w->state[i] == FLAT) || (w->state[i] == CONVEX && is_ear(w, p, i, q, s));
        if (!ear) {
            if (++misses >= remaining) {
                if (flat_ok) return 0; /* a whole turn without an ear */
                flat_ok = 1;
                misses = 0;
            }
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
        --remaining;
        w->state[p] = turn(uv, w->prev[p], p, q, s);
        w->state[q] = turn(uv, p, q, w->next[q], s);
        misses = 0;
        flat_ok = 0;
        i = p; /* p's triangle changed: it may be an ear now */
    }
    out[3 * t] = idx[w->prev[i]];
    out[3 * t + 1] = idx[i];
    out[3 * t + 2] = idx[w->next[i]];
    return 1;
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
    if (nrm[0] == 0 && nrm[1] == 0 && nrm[2] == 0) {
        /* No area (a bow tie's lobes cancel, or every corner on a line):
         * the plane across the axis the corners spread least along, so
         * that crossing edges still show. */
        double lo[3], hi[3];
        for (int c = 0; c < 3; ++c) lo[c] = hi[c] = o[c];
        for (uint32_t k = 1; k < n; ++k)
            for (int c = 0; c < 3; ++c) {
                const double x = xyz[3 * (size_t)idx[k] + c];
                lo[c] = x < lo[c] ? x : lo[c];
                hi[c] = x > hi[c] ? x : hi[c];
            }
        drop = 0;
        for (int c = 1; c < 3; ++c)
            if (hi[c] - lo[c] < hi[drop] - lo[drop]) drop = c;
    }
    const int cu = (drop + 1) % 3, cv = (drop + 2) % 3; /* (u, v, drop) is right-handed */
    double *uv = w->uv;
    for (uint32_t k = 0; k < n; ++k) {
        uv[2 * k] = xyz[3 * (size_t)idx[k] + cu];
        uv[2 * k + 1] = xyz[3 * (size_t)idx[k] + cv];
    }
    /* The winding in (u, v): the sign of Newell's normal across it, which
     * rounding cannot turn unless the polygon's area is rounding itself;
     * then the turn at the lowest corner (least u, then v), convex for a
     * simple polygon that visits it once; if neither says, the polygon has
     * no area: a fan of flat triangles. */
    int s = nrm[drop] > 0 ? 1 : nrm[drop] < 0 ? -1 : 0;
    if (s == 0) {
        uint32_t m = 0;
        for (uint32_t k = 1; k < n; ++k)
            if (uv[2 * k] < uv[2 * m] || (uv[2 * k] == uv[2 * m] && uv[2 * k + 1] < uv[2 * m + 1])) m = k;
        s = orient(uv, m ? m - 1 : n - 1, m, m + 1 < n ? m + 1 : 0);
    }
    /* Crossing edges first: a bow tie's lobes cancel, so it may have no
     * area (helper-49) and would pass for a fan. */
    if (crosses(uv, n)) return 0;
    if (s == 0) {
        for (uint32_t k = 1; k + 1 < n; ++k) {
            out[3 * (k - 1)] = idx[0];
            out[3 * (k - 1) + 1] = idx[k];
            out[3 * (k - 1) + 2] = idx[k + 1];
        }
        return 1;
    }
    /* A polygon of rounding's area may have its winding wrong: the other
     * one is tried before giving up. */
    return clip(w, idx, n, s, out) || clip(w, idx, n, -s, out);
}
