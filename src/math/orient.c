/* Shewchuk's orient2d (math/orient.h): a filter, then the exact sum. */
#include "math/orient.h"

#include <float.h>
#include <math.h>

int pxi_orient2d_filter(double px, double py, double qx, double qy, double rx, double ry) {
    const double eps = 0.5 * DBL_EPSILON; /* Shewchuk's epsilon: half an ulp of 1 */
    /* In this order no operation is invalid (a caller's FE_INVALID trap
     * would fire): a difference beyond the range is refused before any
     * product of it (inf times 0), and products beyond the range before
     * their difference (inf - inf). */
    double a = px - rx, b = qy - ry, c = py - ry, d = qx - rx;
    if (!(fabs(a) <= DBL_MAX && fabs(b) <= DBL_MAX && fabs(c) <= DBL_MAX && fabs(d) <= DBL_MAX)) return 0;
    double l = a * b, r = c * d, sum = fabs(l) + fabs(r);
    if (!(sum > 0x1p-900 && sum < 0x1p900)) return 0;
    double det = l - r;
    if (fabs(det) > (3.0 + 16.0 * eps) * eps * sum) return det > 0 ? 1 : -1;
    return 0;
}

/* x + y == a + b exactly, x = fl(a + b) (Knuth's two-sum). */
static void two_sum(double a, double b, double *x, double *y) {
    double s = a + b, bv = s - a, av = s - bv;
    *x = s;
    *y = (a - av) + (b - bv);
}

/* x + y == a b exactly (the error by fma), unless it underflows. */
static void two_prod(double a, double b, double *x, double *y) {
    double p = a * b;
    *x = p;
    *y = fma(a, b, -p);
}

/* Adds b to the nonoverlapping expansion e[0..n) (increasing magnitude) in
 * place; returns the new length (at most n + 1; zeros dropped). */
static int grow(double *e, int n, double b) {
    double q = b;
    int m = 0;
    for (int i = 0; i < n; ++i) {
        double hh;
        two_sum(q, e[i], &q, &hh);
        if (hh != 0) e[m++] = hh;
    }
    if (q != 0) e[m++] = q;
    return m;
}

int pxi_orient2d_sign(double px, double py, double qx, double qy, double rx, double ry) {
    int s = pxi_orient2d_filter(px, py, qx, qy, rx, ry);
    if (s != 0) return s;
    /* Each difference as two terms, then the 16 products' terms summed. */
    double a[2], b[2], c[2], d[2];
    two_sum(px, -rx, &a[0], &a[1]);
    two_sum(qy, -ry, &b[0], &b[1]);
    two_sum(py, -ry, &c[0], &c[1]);
    two_sum(qx, -rx, &d[0], &d[1]);
    double e[17];
    int n = 0;
    for (int i = 0; i < 2; ++i) {
        for (int j = 0; j < 2; ++j) {
            double h, t;
            two_prod(a[i], b[j], &h, &t);
            n = grow(e, n, h);
            n = grow(e, n, t);
            two_prod(-c[i], d[j], &h, &t);
            n = grow(e, n, h);
            n = grow(e, n, t);
        }
    }
    if (n == 0) return 0;
    return e[n - 1] > 0 ? 1 : -1;
}

double pxi_orient2d_value(double px, double py, double qx, double qy, double rx, double ry) {
    /* The differences exactly (a = a0 + a1, ...), the products of their
     * leading terms exactly, and their difference exactly (s + se): what is
     * left, the error terms and the products with a trailing term, is
     * about eps times smaller, and its rounding is about eps^2 of |l| + |r|. */
    double a0, a1, b0, b1, c0, c1, d0, d1, l, le, r, re, s, se;
    two_sum(px, -rx, &a0, &a1);
    two_sum(qy, -ry, &b0, &b1);
    two_sum(py, -ry, &c0, &c1);
    two_sum(qx, -rx, &d0, &d1);
    two_prod(a0, b0, &l, &le);
    two_prod(c0, d0, &r, &re);
    two_sum(l, -r, &s, &se);
    double t = (se + (le - re)) + ((a0 * b1 + a1 * b0) - (c0 * d1 + c1 * d0)) + (a1 * b1 - c1 * d1);
    return s + t;
}

px_vec3 pxi_tri_cross(px_vec3 a, px_vec3 b, px_vec3 c) {
    return pxi_v(pxi_orient2d_value(b.y, b.z, c.y, c.z, a.y, a.z),
                 pxi_orient2d_value(b.z, b.x, c.z, c.x, a.z, a.x),
                 pxi_orient2d_value(b.x, b.y, c.x, c.y, a.x, a.y));
}

double pxi_unit_scale(double big) {
    if (!(big > 0x1p-100 && big < 0x1p100) && big > 0.0 && isfinite(big)) {
        /* Subnormal magnitudes would need more than 2^1023 (infinite). */
        int e = ilogb(big);
        return ldexp(1.0, e < -1023 ? 1023 : -e);
    }
    return 1.0;
}

int pxi_collinear(const double *a0, const double *b0, const double *c0) {
    double big = 0.0;
    for (int k = 0; k < 3; ++k) big = fmax(big, fmax(fabs(a0[k]), fmax(fabs(b0[k]), fabs(c0[k]))));
    double s = pxi_unit_scale(big), a[3], b[3], c[3];
    for (int k = 0; k < 3; ++k) a[k] = a0[k] * s, b[k] = b0[k] * s, c[k] = c0[k] * s;
    return pxi_orient2d_sign(a[0], a[1], b[0], b[1], c[0], c[1]) == 0 &&
           pxi_orient2d_sign(a[1], a[2], b[1], b[2], c[1], c[2]) == 0 &&
           pxi_orient2d_sign(a[2], a[0], b[2], b[0], c[2], c[0]) == 0;
}
