/* The GJK distance sub-algorithm: closest point of a simplex (1-4 points)
 * to the origin, by Voronoi-region case analysis (C. Ericson, Real-Time
 * Collision Detection, §5.1.5-5.1.6; the barycentric weights of the inside
 * case are ratios of signed volumes). Shared by GJK, EPA, the translation ray
 * cast and GJK's final polish. */
#include "narrow/simplex.h"

#include "math/orient.h"

#include <float.h>
#include <math.h>

/* Keep the points whose flag is set, with their weights. */
static inline void sx_keep(sx_simplex *s, const int *use, const double *lam) {
    sx_simplex out;
    out.n = 0;
    out.margin = s->margin;
    for (int k = 0; k < s->n; ++k)
        if (use[k]) {
            out.p[out.n] = s->p[k];
            out.lam[out.n++] = lam[k];
        }
    *s = out;
}

void pxi_sx_segment(sx_simplex *s) {
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
    sx_keep(s, use, lam);
}

/* A sliver triangle. Ericson's region tests and weights lose a factor of
 * the aspect (beside a 1 x 1e-6 side of a turned plate, GJK's distances
 * were 1e5 eps of the size off); here the normal N and the three
 * sub-triangles' areas against the origin's foot q are cross products to
 * full relative precision (pxi_tri_cross), whose dots with N do not cancel
 * (each is nearly parallel to N). When the foot falls outside after all,
 * the closest point is on an edge: the best of the three. Out of line: its
 * caller is GJK's hot triangle solve. */
PXI_COLD void sx_sliver(sx_simplex *s) {
    px_vec3 a = s->p[0].w, b = s->p[1].w, c = s->p[2].w, n = pxi_tri_cross(a, b, c);
    double nn = pxi_dot(n, n), h = (pxi_dot(n, a) + pxi_dot(n, b) + pxi_dot(n, c)) / 3.0;
    if (nn > 0.0 && isfinite(nn)) {
        px_vec3 q = pxi_scale(n, h / nn);
        double lam[3] = {pxi_dot(pxi_tri_cross(q, b, c), n), pxi_dot(pxi_tri_cross(a, q, c), n),
                         pxi_dot(pxi_tri_cross(a, b, q), n)};
        double sum = lam[0] + lam[1] + lam[2];
        if (lam[0] >= 0.0 && lam[1] >= 0.0 && lam[2] >= 0.0 && sum > 0.0) {
            int use[3] = {1, 1, 1};
            for (int k = 0; k < 3; ++k) lam[k] /= sum;
            sx_keep(s, use, lam);
            return;
        }
    }
    sx_simplex best = *s;
    double d2 = INFINITY;
    for (int e = 0; e < 3; ++e) {
        sx_simplex t = *s;
        t.n = 2;
        t.p[0] = s->p[e];
        t.p[1] = s->p[(e + 1) % 3];
        pxi_sx_segment(&t);
        double d = pxi_len2(sx_point_of(&t));
        if (d < d2) d2 = d, best = t;
    }
    *s = best;
}

void pxi_sx_triangle(sx_simplex *s) {
    px_vec3 a = s->p[0].w, b = s->p[1].w, c = s->p[2].w;
    px_vec3 ab = pxi_sub(b, a), ac = pxi_sub(c, a);
    if (PXI_RARE(pxi_is_sliver(pxi_cross(ab, ac), ab, ac))) {
        sx_sliver(s); /* the region tests below cancel too */
        return;
    }
    double d1 = -pxi_dot(ab, a), d2 = -pxi_dot(ac, a);
    int use[3] = {0, 0, 0};
    double lam[3] = {0, 0, 0};
    if (d1 <= 0.0 && d2 <= 0.0) {
        use[0] = 1, lam[0] = 1;
        sx_keep(s, use, lam);
        return;
    }
    double d3 = -pxi_dot(ab, b), d4 = -pxi_dot(ac, b);
    if (d3 >= 0.0 && d4 <= d3) {
        use[1] = 1, lam[1] = 1;
        sx_keep(s, use, lam);
        return;
    }
    double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
        double v = d1 - d3 > 0.0 ? d1 / (d1 - d3) : 0.0; /* 0/0 on degenerate input */
        use[0] = use[1] = 1, lam[0] = 1 - v, lam[1] = v;
        sx_keep(s, use, lam);
        return;
    }
    double d5 = -pxi_dot(ab, c), d6 = -pxi_dot(ac, c);
    if (d6 >= 0.0 && d5 <= d6) {
        use[2] = 1, lam[2] = 1;
        sx_keep(s, use, lam);
        return;
    }
    double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
        double w = d2 - d6 > 0.0 ? d2 / (d2 - d6) : 0.0;
        use[0] = use[2] = 1, lam[0] = 1 - w, lam[2] = w;
        sx_keep(s, use, lam);
        return;
    }
    double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
        double den = (d4 - d3) + (d5 - d6), w = den > 0.0 ? (d4 - d3) / den : 0.0;
        use[1] = use[2] = 1, lam[1] = 1 - w, lam[2] = w;
        sx_keep(s, use, lam);
        return;
    }
    double sum = va + vb + vc;
    if (!(sum > 0.0)) { /* degenerate (collinear) triangle: keep its longest side */
        sx_simplex e = *s;
        e.n = 2;
        pxi_sx_segment(&e);
        *s = e;
        return;
    }
    use[0] = use[1] = use[2] = 1;
    lam[1] = vb / sum, lam[2] = vc / sum, lam[0] = 1.0 - lam[1] - lam[2];
    sx_keep(s, use, lam);
}

/* Returns 1 when the origin is inside (or on) the tetrahedron. */
int pxi_sx_tetra(sx_simplex *s) {
    static const int faces[4][4] = {{0, 1, 2, 3}, {0, 3, 1, 2}, {0, 2, 3, 1}, {1, 3, 2, 0}};
    double best = INFINITY;
    sx_simplex best_s = *s;
    int any = 0;
    for (int k = 0; k < 4; ++k) {
        px_vec3 a = s->p[faces[k][0]].w, b = s->p[faces[k][1]].w, c = s->p[faces[k][2]].w;
        /* pxi_tri_normal: with plain products the side of the origin
         * against the 1 x 1e-7 side face of a plate was noise, and a
         * tetrahedron held the origin 1.7e-12 outside it (a ray cast's hit
         * 1.5e4 eps early) */
        px_vec3 d = s->p[faces[k][3]].w, n = pxi_tri_normal(a, b, c);
        double so = -pxi_dot(a, n), sd = pxi_dot(pxi_sub(d, a), n);
        if (!(so * sd < 0.0) && sd != 0.0) continue; /* origin on d's side of this face */
        sx_simplex t;
        t.n = 3;
        t.p[0] = s->p[faces[k][0]], t.p[1] = s->p[faces[k][1]], t.p[2] = s->p[faces[k][2]];
        pxi_sx_triangle(&t);
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
            px_vec3 n = pxi_tri_normal(a, b, c);
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

/* Does the tetrahedron contain the origin with every side test certain?
 * The four signed volumes with the origin replacing one vertex are triple
 * products of coordinates up to m, each with an error below about
 * 16 eps m^3; when all exceed 64 eps m^3 and share the total's sign, the
 * origin is inside however flat the tetrahedron is. (pxi_sx_tetra's own
 * test asks for a volume of 1e-9 m^3, which misses overlaps of 1e-10 between
 * nearly coplanar faces.) */
int pxi_sx_tetra_surely_contains(const sx_simplex *s) {
    px_vec3 w0 = s->p[0].w, w1 = s->p[1].w, w2 = s->p[2].w, w3 = s->p[3].w;
    double vol[4] = {pxi_dot(w1, pxi_cross(w2, w3)), -pxi_dot(w0, pxi_cross(w2, w3)),
                     pxi_dot(w0, pxi_cross(w1, w3)), -pxi_dot(w0, pxi_cross(w1, w2))};
    double m = 0.0;
    for (int f = 0; f < 4; ++f)
        if (pxi_max_abs(s->p[f].w) > m) m = pxi_max_abs(s->p[f].w);
    double noise = 64.0 * DBL_EPSILON * m * m * m, tot = vol[0] + vol[1] + vol[2] + vol[3];
    for (int f = 0; f < 4; ++f)
        if (!(fabs(vol[f]) > noise) || !(vol[f] * tot > 0.0)) return 0;
    return 1;
}

/* A tetrahedron too flat for its side tests (pxi_sx_tetra found the
 * origin inside but could not trust it, margin 0): the closest point over
 * its four faces, without side tests. */
void pxi_sx_flat_tetra(sx_simplex *s) {
    static const int faces[4][3] = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
    double best = INFINITY;
    sx_simplex best_s = *s;
    for (int k = 0; k < 4; ++k) {
        sx_simplex t;
        t.n = 3;
        t.margin = 0.0;
        for (int m = 0; m < 3; ++m) t.p[m] = s->p[faces[k][m]];
        pxi_sx_triangle(&t);
        px_vec3 v = {0, 0, 0};
        for (int m = 0; m < t.n; ++m) v = pxi_madd(v, t.p[m].w, t.lam[m]);
        double d2 = pxi_len2(v);
        if (d2 < best || k == 0) best = d2, best_s = t;
    }
    *s = best_s;
}
