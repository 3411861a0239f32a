/* Triangle geometry for exact triangle leaves: closest points between
 * triangles and the crossing test that detects intersecting ones.
 * Closest point on a triangle: the Voronoi-region walk of C. Ericson,
 * "Real-Time Collision Detection" (2005), section 5.1.5. Triangle-triangle
 * distance: the minimum over the 6 vertex-triangle and 9 edge-edge pairs,
 * which is exact for disjoint triangles (the closest pair of two disjoint
 * convex polygons involves a vertex or two edges, ibid. 5.1.9), and 0 when
 * an edge of one crosses the other. */
#include <float.h>
#include <math.h>

#include "model/model.h"
#include "narrow/closest.h"

static inline double max2(double a, double b) { return a > b ? a : b; }

static px_feature tri_feature(uint32_t type, uint32_t index) {
    px_feature f = {type, index, 0};
    return f;
}

/* Closest point on segment [a, b] to p, as a parameter in [0, 1]. */
static double segment_param(px_vec3 p, px_vec3 a, px_vec3 b) {
    px_vec3 ab = pxi_sub(b, a);
    double l2 = pxi_len2(ab);
    if (!(l2 > 0.0)) return 0.0;
    return pxi_clamp01(pxi_dot(pxi_sub(p, a), ab) / l2);
}

static px_vec3 edge_point(px_vec3 a, px_vec3 b, double s, uint32_t k, px_feature *f) {
    if (s <= 0.0) {
        *f = tri_feature(PX_FEATURE_VERTEX, k);
        return a;
    }
    if (s >= 1.0) {
        *f = tri_feature(PX_FEATURE_VERTEX, (k + 1) % 3);
        return b;
    }
    *f = tri_feature(PX_FEATURE_EDGE, k);
    return pxi_madd(a, pxi_sub(b, a), s);
}

/* Zero-area (or NaN-area) triangles: the closest point of its three edges. */
static px_vec3 closest_on_edges(px_vec3 p, const px_vec3 t[3], px_feature *feature) {
    px_vec3 best = t[0];
    double best_d2 = INFINITY;
    for (uint32_t k = 0; k < 3; ++k) {
        px_feature f;
        px_vec3 q = edge_point(t[k], t[(k + 1) % 3], segment_param(p, t[k], t[(k + 1) % 3]), k, &f);
        double d2 = pxi_len2(pxi_sub(p, q));
        if (d2 < best_d2) {
            best_d2 = d2;
            best = q;
            *feature = f;
        }
    }
    return best;
}

px_vec3 pxi_tri_closest(px_vec3 p, const px_vec3 t[3], px_feature *feature) {
    px_vec3 a = t[0], b = t[1], c = t[2];
    px_vec3 ab = pxi_sub(b, a), ac = pxi_sub(c, a), ap = pxi_sub(p, a);
    px_vec3 n = pxi_cross(ab, ac);
    double n2 = pxi_len2(n);
    /* A triangle whose area is lost to rounding against its edges has no
     * reliable interior region. */
    if (!(n2 > 1e-24 * pxi_len2(ab) * pxi_len2(ac))) return closest_on_edges(p, t, feature);
    double d1 = pxi_dot(ab, ap), d2 = pxi_dot(ac, ap);
    if (d1 <= 0.0 && d2 <= 0.0) {
        *feature = tri_feature(PX_FEATURE_VERTEX, 0);
        return a;
    }
    px_vec3 bp = pxi_sub(p, b);
    double d3 = pxi_dot(ab, bp), d4 = pxi_dot(ac, bp);
    if (d3 >= 0.0 && d4 <= d3) {
        *feature = tri_feature(PX_FEATURE_VERTEX, 1);
        return b;
    }
    double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return edge_point(a, b, segment_param(p, a, b), 0, feature);
    px_vec3 cp = pxi_sub(p, c);
    double d5 = pxi_dot(ab, cp), d6 = pxi_dot(ac, cp);
    if (d6 >= 0.0 && d5 <= d6) {
        *feature = tri_feature(PX_FEATURE_VERTEX, 2);
        return c;
    }
    double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return edge_point(c, a, segment_param(p, c, a), 2, feature);
    double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
        return edge_point(b, c, segment_param(p, b, c), 1, feature);
    /* Inside the face region: project onto the plane (more accurate than
     * the barycentric combination far from the origin of the frame). */
    *feature = tri_feature(PX_FEATURE_FACE, 0);
    return pxi_sub(p, pxi_scale(n, pxi_dot(ap, n) / n2));
}

int pxi_segment_crosses_tri(px_vec3 p, px_vec3 q, const px_vec3 t[3]) {
    px_vec3 n = pxi_cross(pxi_sub(t[1], t[0]), pxi_sub(t[2], t[0]));
    double dp = pxi_dot(n, pxi_sub(p, t[0])), dq = pxi_dot(n, pxi_sub(q, t[0]));
    if ((dp > 0.0 && dq > 0.0) || (dp < 0.0 && dq < 0.0) || dp == dq) return 0;
    px_vec3 x = pxi_madd(p, pxi_sub(q, p), dp / (dp - dq));
    /* Inside when x is on the inner side of all three edges (seen along n). */
    for (int k = 0; k < 3; ++k) {
        px_vec3 e = pxi_sub(t[(k + 1) % 3], t[k]);
        if (pxi_dot(pxi_cross(e, pxi_sub(x, t[k])), n) < 0.0) return 0;
    }
    return 1;
}

/* All three values strictly of one sign. */
static int one_side(const double d[3]) {
    return (d[0] > 0.0 && d[1] > 0.0 && d[2] > 0.0) || (d[0] < 0.0 && d[1] < 0.0 && d[2] < 0.0);
}

/* The vertex-face certificate: triangle `other` lies strictly on one side
 * of triangle f's plane (normal n = (f1 - f0) x (f2 - f0), signed distances
 * times |n| in d[]); its vertex nearest the plane, projected on it, lands
 * inside f. Writes the pair (f's point first when f_is_t is 0, else
 * other's first) and returns 1; 0 when the certificate does not apply. */
static int vertex_face(const px_vec3 f[3], px_vec3 n, const double d[3], const px_vec3 other[3], int f_is_t,
                       px_vec3 *ps, px_vec3 *pt, px_feature *fs, px_feature *ft) {
    double n2 = pxi_len2(n);
    px_vec3 e1 = pxi_sub(f[1], f[0]), e2 = pxi_sub(f[2], f[0]);
    if (!(n2 > 1e-24 * pxi_len2(e1) * pxi_len2(e2))) return 0;
    uint32_t k = 0;
    for (uint32_t m = 1; m < 3; ++m)
        if (fabs(d[m]) < fabs(d[k])) k = m;
    px_vec3 q = pxi_sub(other[k], pxi_scale(n, d[k] / n2));
    for (int m = 0; m < 3; ++m)
        if (pxi_dot(pxi_cross(pxi_sub(f[(m + 1) % 3], f[m]), pxi_sub(q, f[m])), n) < 0.0) return 0;
    px_feature face = tri_feature(PX_FEATURE_FACE, 0), vertex = tri_feature(PX_FEATURE_VERTEX, k);
    if (!f_is_t) {
        *ps = q, *pt = other[k], *fs = face, *ft = vertex;
    } else {
        *ps = other[k], *pt = q, *fs = vertex, *ft = face;
    }
    return 1;
}

/* Whether the pair p (on s), q (on t) is the closest pair to within
 * rounding. With u = (q - p) / |q - p|, let hs be how far s reaches past p
 * along u (the largest (x - p) . u over its corners) and ht how far t
 * reaches back past q: every x in s and y in t then have (y - x) . u >=
 * |q - p| - hs - ht, so |q - p| exceeds the distance by at most hs + ht
 * (E. Larsen's slab argument in PQP's TriDist, which tests only the third
 * corners with no margin). Accepted when hs + ht is within a few ulps of
 * the coordinates: all six corners are tested, since near-parallel or
 * degenerate edges leave p short of its edge's closest point. */
static int edge_certified(const px_vec3 s[3], const px_vec3 t[3], px_vec3 p, px_vec3 q, px_vec3 v,
                          double d2) {
    double l = sqrt(d2);
    if (!(l > 0.0)) return 0;
    double hs = -INFINITY, ht = -INFINITY, reach = 0.0;
    for (int k = 0; k < 3; ++k) {
        px_vec3 a = pxi_sub(s[k], p), b = pxi_sub(t[k], q);
        hs = max2(hs, pxi_dot(a, v));
        ht = max2(ht, -pxi_dot(b, v));
        reach = max2(reach, max2(pxi_max_abs(a), pxi_max_abs(b)));
    }
    double size = reach + pxi_max_abs(p) + pxi_max_abs(q);
    return (hs + ht) / l <= 16.0 * DBL_EPSILON * size;
}

/* Twice the signed area of 2D triangle abc. */
static double orient2(const double a[2], const double b[2], const double c[2]) {
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

static int on_segment2(const double a[2], const double b[2], const double p[2]) {
    return p[0] >= fmin(a[0], b[0]) && p[0] <= fmax(a[0], b[0]) && p[1] >= fmin(a[1], b[1]) &&
           p[1] <= fmax(a[1], b[1]);
}

/* p in triangle t (edges included); never for a triangle of no area, whose
 * orientations would all be 0 (its edges are tested on their own). */
static int inside2(const double t[3][2], const double p[2]) {
    if (orient2(t[0], t[1], t[2]) == 0.0) return 0;
    double o0 = orient2(t[0], t[1], p), o1 = orient2(t[1], t[2], p), o2 = orient2(t[2], t[0], p);
    return (o0 >= 0.0 && o1 >= 0.0 && o2 >= 0.0) || (o0 <= 0.0 && o1 <= 0.0 && o2 <= 0.0);
}

/* Exactly coplanar triangles (every corner's computed distance to the
 * other's plane is 0: faces on one axis-aligned plane, the common case of
 * parts that touch by design) meet when, projected on the two axes other
 * than the normal n's largest, an edge of one meets an edge of the other
 * or a corner of one lies in the other. tri_tri_local's crossing tests
 * cannot see it (no edge leaves the plane), and the edge pairs' closest
 * points would measure a rounding-sized gap. Writes a common point; 1 when
 * they meet. */
static int coplanar_meet(const px_vec3 s[3], const px_vec3 t[3], px_vec3 n, px_vec3 *x, px_feature *fs,
                         px_feature *ft) {
    double ax = fabs(n.x), ay = fabs(n.y), az = fabs(n.z);
    if (!(ax > 0.0 || ay > 0.0 || az > 0.0)) return 0;
    int drop = ax >= ay && ax >= az ? 0 : ay >= az ? 1 : 2; /* the axis projected away */
    int u = drop == 0 ? 1 : 0, v = drop == 2 ? 1 : 2;
    double s2[3][2], t2[3][2];
    for (int k = 0; k < 3; ++k) {
        const double *ps = &s[k].x, *pt = &t[k].x;
        s2[k][0] = ps[u], s2[k][1] = ps[v], t2[k][0] = pt[u], t2[k][1] = pt[v];
    }
    for (int i = 0; i < 3; ++i) {
        const double *a = s2[i], *b = s2[(i + 1) % 3];
        for (int j = 0; j < 3; ++j) {
            const double *c = t2[j], *d = t2[(j + 1) % 3];
            double d1 = orient2(c, d, a), d2 = orient2(c, d, b), d3 = orient2(a, b, c), d4 = orient2(a, b, d);
            int proper = ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0)) &&
                         ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0));
            if (proper) {
                *x = pxi_madd(s[i], pxi_sub(s[(i + 1) % 3], s[i]), d1 / (d1 - d2));
                *fs = tri_feature(PX_FEATURE_EDGE, (uint32_t)i);
                *ft = tri_feature(PX_FEATURE_EDGE, (uint32_t)j);
                return 1;
            }
        }
    }
    for (int k = 0; k < 3; ++k) {
        if (inside2(t2, s2[k])) {
            *x = s[k];
            *fs = tri_feature(PX_FEATURE_VERTEX, (uint32_t)k);
            *ft = tri_feature(PX_FEATURE_FACE, 0);
            return 1;
        }
        if (inside2(s2, t2[k])) {
            *x = t[k];
            *fs = tri_feature(PX_FEATURE_FACE, 0);
            *ft = tri_feature(PX_FEATURE_VERTEX, (uint32_t)k);
            return 1;
        }
    }
    /* A corner on the other's edge where that triangle has no area (with
     * an area, inside2 above takes edges in). */
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            const double *a = s2[i], *b = s2[(i + 1) % 3], *c = t2[j], *d = t2[(j + 1) % 3];
            if (orient2(a, b, c) == 0.0 && on_segment2(a, b, c)) {
                *x = t[j];
                *fs = tri_feature(PX_FEATURE_EDGE, (uint32_t)i);
                *ft = tri_feature(PX_FEATURE_VERTEX, (uint32_t)j);
                return 1;
            }
            if (orient2(c, d, a) == 0.0 && on_segment2(c, d, a)) {
                *x = s[i];
                *fs = tri_feature(PX_FEATURE_VERTEX, (uint32_t)i);
                *ft = tri_feature(PX_FEATURE_EDGE, (uint32_t)j);
                return 1;
            }
        }
    return 0;
}

static double tri_tri_local(const px_vec3 s[3], const px_vec3 t[3], px_vec3 *ps, px_vec3 *pt, px_feature *fs,
                            px_feature *ft) {
    /* An edge of one crossing the other: they intersect. An edge of s
     * cannot cross t when s lies strictly on one side of t's plane (the
     * crossing test's own first step, done once for the three edges), and
     * likewise for t's edges. Each side is decided by its own plane only:
     * a sliver's normal is rounding noise, and its edges must still be
     * tried against the other's plane. */
    px_vec3 ns = pxi_cross(pxi_sub(s[1], s[0]), pxi_sub(s[2], s[0]));
    px_vec3 nt = pxi_cross(pxi_sub(t[1], t[0]), pxi_sub(t[2], t[0]));
    double ds[3], dt[3];
    for (int k = 0; k < 3; ++k)
        ds[k] = pxi_dot(nt, pxi_sub(s[k], t[0])), dt[k] = pxi_dot(ns, pxi_sub(t[k], s[0]));
    int s_apart = one_side(ds), t_apart = one_side(dt);
    if (ds[0] == 0.0 && ds[1] == 0.0 && ds[2] == 0.0 && dt[0] == 0.0 && dt[1] == 0.0 && dt[2] == 0.0) {
        px_vec3 n = pxi_max_abs(ns) >= pxi_max_abs(nt) ? ns : nt;
        if (coplanar_meet(s, t, n, ps, fs, ft)) {
            *pt = *ps;
            return 0.0;
        }
    }
    if (!s_apart || !t_apart) {
        for (int k = 0; k < 3; ++k) {
            if (!s_apart && pxi_segment_crosses_tri(s[k], s[(k + 1) % 3], t)) {
                double dp = ds[k], dq = ds[(k + 1) % 3];
                *ps = *pt = pxi_madd(s[k], pxi_sub(s[(k + 1) % 3], s[k]), dp / (dp - dq));
                *fs = tri_feature(PX_FEATURE_EDGE, (uint32_t)k);
                *ft = tri_feature(PX_FEATURE_FACE, 0);
                return 0.0;
            }
            if (!t_apart && pxi_segment_crosses_tri(t[k], t[(k + 1) % 3], s)) {
                double dp = dt[k], dq = dt[(k + 1) % 3];
                *ps = *pt = pxi_madd(t[k], pxi_sub(t[(k + 1) % 3], t[k]), dp / (dp - dq));
                *fs = tri_feature(PX_FEATURE_FACE, 0);
                *ft = tri_feature(PX_FEATURE_EDGE, (uint32_t)k);
                return 0.0;
            }
        }
    }
    /* Cheap certificates first (E. Larsen's argument in PQP's TriDist). If t
     * lies strictly on one side of s's plane and its vertex nearest that
     * plane projects inside s, that vertex and its projection are the
     * closest pair (all of t is at least that far from the plane, and s
     * lies in it); likewise with the roles swapped. A triangle whose normal
     * is lost to rounding gives no certificate. */
    if (t_apart && vertex_face(s, ns, dt, t, 0, ps, pt, fs, ft)) return pxi_len(pxi_sub(*pt, *ps));
    if (s_apart && vertex_face(t, nt, ds, s, 1, ps, pt, fs, ft)) return pxi_len(pxi_sub(*pt, *ps));
    /* Squared distances compared; one square root at the end. An edge
     * pair (p, q) ends the search when it is certified to within rounding:
     * edge_certified below. */
    double best = INFINITY;
    for (uint32_t i = 0; i < 3; ++i) {
        for (uint32_t j = 0; j < 3; ++j) {
            double a, b;
            pxi_segment_closest(s[i], s[(i + 1) % 3], t[j], t[(j + 1) % 3], &a, &b);
            px_feature fa, fb;
            px_vec3 p = edge_point(s[i], s[(i + 1) % 3], a, i, &fa);
            px_vec3 q = edge_point(t[j], t[(j + 1) % 3], b, j, &fb);
            px_vec3 v = pxi_sub(q, p);
            double d = pxi_len2(v);
            if (d < best) {
                best = d;
                *ps = p;
                *pt = q;
                *fs = fa;
                *ft = fb;
                if (edge_certified(s, t, p, q, v, d)) return sqrt(best);
            }
        }
    }
    for (uint32_t k = 0; k < 3; ++k) {
        px_feature f;
        px_vec3 q = pxi_tri_closest(s[k], t, &f);
        double d = pxi_len2(pxi_sub(q, s[k]));
        if (d < best) {
            best = d;
            *ps = s[k];
            *pt = q;
            *fs = tri_feature(PX_FEATURE_VERTEX, k);
            *ft = f;
        }
        q = pxi_tri_closest(t[k], s, &f);
        d = pxi_len2(pxi_sub(q, t[k]));
        if (d < best) {
            best = d;
            *ps = q;
            *pt = t[k];
            *fs = f;
            *ft = tri_feature(PX_FEATURE_VERTEX, k);
        }
    }
    return sqrt(best);
}

/* Measured about s[0]: the differences of nearby coordinates are exact, so
 * the rounding of every step above is a few ulps of the two triangles'
 * extent and distance, not of their place. Measured where they sit, two
 * slivers 1e-10 across at 4e4 came out 1.8e-10 apart (an edge pair
 * certified within ulps of 4e4) instead of 3.1e-14 (the fourth review). */
double pxi_tri_tri(const px_vec3 s[3], const px_vec3 t[3], px_vec3 *ps, px_vec3 *pt, px_feature *fs,
                   px_feature *ft) {
    px_vec3 o = s[0], ls[3], lt[3];
    for (int k = 0; k < 3; ++k) ls[k] = pxi_sub(s[k], o), lt[k] = pxi_sub(t[k], o);
    double d = tri_tri_local(ls, lt, ps, pt, fs, ft);
    *ps = pxi_add(*ps, o);
    *pt = pxi_add(*pt, o);
    return d;
}
