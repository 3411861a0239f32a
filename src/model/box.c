/* Oriented bounding boxes of tree nodes and the separating-axis lower bound
 * on their distance (S. Gottschalk, M. Lin, D. Manocha, "OBBTree: a
 * hierarchical structure for rapid interference detection", SIGGRAPH
 * 1996: axes from the covariance of the points, the 15-axis test). Here the
 * test's gap is used as a distance bound: projections onto a unit axis are
 * 1-Lipschitz, so the gap between two projected intervals never exceeds
 * the distance of the boxes. */
#include <float.h>
#include <math.h>

#include "model/model.h"

/* max without libm's NaN rules (the call is not inlined); the bounds are
 * finite. */

/* Eigenvectors of a symmetric 3x3 matrix by cyclic Jacobi rotations (rows
 * of v). */
static void jacobi3(double a[9], double v[9]) {
    for (int i = 0; i < 9; ++i) v[i] = (i % 4 == 0) ? 1.0 : 0.0;
    for (int sweep = 0; sweep < 32; ++sweep) {
        double off = a[1] * a[1] + a[2] * a[2] + a[5] * a[5];
        if (!(off > 1e-30 * (a[0] * a[0] + a[4] * a[4] + a[8] * a[8]))) break;
        for (int p = 0; p < 2; ++p)
            for (int q = p + 1; q < 3; ++q) {
                double apq = a[3 * p + q];
                if (apq == 0.0) continue;
                double theta = (a[3 * q + q] - a[3 * p + p]) / (2.0 * apq);
                double t = (theta >= 0 ? 1.0 : -1.0) / (fabs(theta) + sqrt(theta * theta + 1.0));
                double c = 1.0 / sqrt(t * t + 1.0), s = t * c;
                /* a = J^T a J on rows/columns p, q. */
                for (int k = 0; k < 3; ++k) {
                    double akp = a[3 * k + p], akq = a[3 * k + q];
                    a[3 * k + p] = c * akp - s * akq;
                    a[3 * k + q] = s * akp + c * akq;
                }
                for (int k = 0; k < 3; ++k) {
                    double apk = a[3 * p + k], aqk = a[3 * q + k];
                    a[3 * p + k] = c * apk - s * aqk;
                    a[3 * q + k] = s * apk + c * aqk;
                }
                for (int k = 0; k < 3; ++k) {
                    double vpk = v[3 * p + k], vqk = v[3 * q + k];
                    v[3 * p + k] = c * vpk - s * vqk;
                    v[3 * q + k] = s * vpk + c * vqk;
                }
            }
    }
}

void pxi_box_fit(const px_vec3 *p, size_t n, pxi_box *out) {
    px_vec3 mean = pxi_v(0, 0, 0);
    for (size_t i = 0; i < n; ++i) mean = pxi_add(mean, p[i]);
    mean = pxi_scale(mean, 1.0 / (double)n);
    double c[9] = {0};
    for (size_t i = 0; i < n; ++i) {
        px_vec3 d = pxi_sub(p[i], mean);
        c[0] += d.x * d.x, c[1] += d.x * d.y, c[2] += d.x * d.z;
        c[4] += d.y * d.y, c[5] += d.y * d.z, c[8] += d.z * d.z;
    }
    c[3] = c[1], c[6] = c[2], c[7] = c[5];
    double v[9];
    jacobi3(c, v);
    /* Orthonormalise (the third axis as the cross product keeps the frame
     * right-handed and exactly orthogonal up to rounding). */
    px_vec3 a0 = pxi_unit_safe(pxi_v(v[0], v[1], v[2]));
    px_vec3 a1 = pxi_v(v[3], v[4], v[5]);
    a1 = pxi_unit_safe(pxi_sub(a1, pxi_scale(a0, pxi_dot(a0, a1))));
    px_vec3 a2 = pxi_unit_safe(pxi_cross(a0, a1));
    if (!pxi_is_finite3(a0) || !pxi_is_finite3(a1) || !pxi_is_finite3(a2) || pxi_len2(a0) < 0.5 ||
        pxi_len2(a1) < 0.5 || pxi_len2(a2) < 0.5) {
        a0 = pxi_v(1, 0, 0), a1 = pxi_v(0, 1, 0), a2 = pxi_v(0, 0, 1);
    }
    px_vec3 ax[3] = {a0, a1, a2};
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    double reach = 0.0;
    for (size_t i = 0; i < n; ++i) {
        px_vec3 d = pxi_sub(p[i], mean);
        reach = fmax(reach, pxi_max_abs(d));
        for (int k = 0; k < 3; ++k) {
            double t = pxi_dot(ax[k], d);
            lo[k] = fmin(lo[k], t);
            hi[k] = fmax(hi[k], t);
        }
    }
    /* Outward rounding: the projections' and the centre's errors are a few
     * ulps of the points' spread and of the centre's size. */
    double pad = 16.0 * DBL_EPSILON * (4.0 * reach + pxi_max_abs(mean)) + 0x1p-1000;
    px_vec3 center = mean;
    double half[3];
    for (int k = 0; k < 3; ++k) {
        center = pxi_madd(center, ax[k], 0.5 * (lo[k] + hi[k]));
        half[k] = 0.5 * (hi[k] - lo[k]) + pad;
    }
    out->center = center;
    for (int k = 0; k < 3; ++k) {
        out->axis[3 * k] = ax[k].x;
        out->axis[3 * k + 1] = ax[k].y;
        out->axis[3 * k + 2] = ax[k].z;
    }
    out->half = pxi_v(half[0], half[1], half[2]);
}

/* Projection radius of a box (axes ax[], half extents h[]) on u. */
static inline double box_radius(const px_vec3 ax[3], const double h[3], px_vec3 u) {
    return h[0] * fabs(pxi_dot(ax[0], u)) + h[1] * fabs(pxi_dot(ax[1], u)) + h[2] * fabs(pxi_dot(ax[2], u));
}

/* Keeps the larger of (best, its axis id and sign) and (g, id, sign); the
 * axis itself is built once at the end. */
static inline void take(double *best, int *id, double *sign, double g, int gid, double gsign) {
    if (g > *best) {
        *best = g;
        *id = gid;
        *sign = gsign;
    }
}

static inline double sgn(double x) { return x < 0.0 ? -1.0 : 1.0; }

enum { AX_NONE = -1, AX_HINT = 0, AX_CENTRES = 1, AX_A = 2, AX_B = 5, AX_CROSS = 8 };

double pxi_box_gap(const pxi_box *a, const pxi_box *b, const px_pose *t_ab, const px_vec3 *hint, double limit,
                   px_vec3 *axis_out) {
    /* B's axes and centre in A's frame. */
    px_vec3 d = pxi_sub(pxi_xform(t_ab, b->center), a->center);
    px_vec3 aa[3], ba[3];
    for (int k = 0; k < 3; ++k) {
        aa[k] = pxi_v(a->axis[3 * k], a->axis[3 * k + 1], a->axis[3 * k + 2]);
        ba[k] = pxi_rot(t_ab->r, pxi_v(b->axis[3 * k], b->axis[3 * k + 1], b->axis[3 * k + 2]));
    }
    double ha[3] = {a->half.x, a->half.y, a->half.z}, hb[3] = {b->half.x, b->half.y, b->half.z};
    /* Rounding of every gap: a few ulps of the sizes involved (divided by
     * the axis length for the cross products). */
    double dl = pxi_len(d);
    double margin = 64.0 * DBL_EPSILON * (dl + ha[0] + ha[1] + ha[2] + hb[0] + hb[1] + hb[2]);
    double best = -INFINITY, sign = 1.0;
    int id = AX_NONE;
    double r[3][3], ar[3][3], t[3];
    /* Cheapest and most often decisive first, each returning as soon as
     * the bound exceeds `limit`: the caller's hint (the direction between
     * the closest points found so far, which sees two parallel surfaces
     * facing each other), then the line of centres (boxes lying
     * diagonally from each other). */
    if (hint) {
        double dh = pxi_dot(d, *hint);
        take(&best, &id, &sign, fabs(dh) - box_radius(aa, ha, *hint) - box_radius(ba, hb, *hint) - margin,
             AX_HINT, sgn(dh));
        if (best > limit) goto out;
    }
    if (dl > 0.0) {
        px_vec3 u = pxi_scale(d, 1.0 / dl);
        take(&best, &id, &sign, dl - box_radius(aa, ha, u) - box_radius(ba, hb, u) - margin, AX_CENTRES, 1.0);
        if (best > limit) goto out;
    }
    /* The 15 axes of the separating-axis test, in A's box basis. */
    for (int i = 0; i < 3; ++i) {
        t[i] = pxi_dot(aa[i], d);
        for (int j = 0; j < 3; ++j) {
            r[i][j] = pxi_dot(aa[i], ba[j]);
            ar[i][j] = fabs(r[i][j]);
        }
    }
    for (int i = 0; i < 3; ++i)
        take(&best, &id, &sign,
             fabs(t[i]) - ha[i] - (hb[0] * ar[i][0] + hb[1] * ar[i][1] + hb[2] * ar[i][2]) - margin, AX_A + i,
             sgn(t[i]));
    if (best > limit) goto out;
    for (int j = 0; j < 3; ++j) {
        double tb = t[0] * r[0][j] + t[1] * r[1][j] + t[2] * r[2][j];
        take(&best, &id, &sign,
             fabs(tb) - (ha[0] * ar[0][j] + ha[1] * ar[1][j] + ha[2] * ar[2][j]) - hb[j] - margin, AX_B + j,
             sgn(tb));
    }
    if (best > limit) goto out;
    /* Cross products A_i x B_j, in A's basis c = r_i1j e_i2 - r_i2j e_i1
     * (B_j's coordinates are r_.j). Every term is taken from c itself: its
     * length from its two coordinates, B's radius from B's axes' own
     * coordinates (c . r_.m, 0 for m = j up to rounding). The textbook
     * shortcuts, |c| = sqrt(1 - r_ij^2) and B's radius by the identities
     * of an orthonormal B, hold only for exact rotations: with B's axes
     * off by d (rounding, or a pose's skew) they err by about d / |c|^2,
     * and for nearly parallel axes the bound came out too large, so the
     * query pruned the nearest pair (6.8e-10 off with exact quaternion
     * poses, 2.1e-4 with float-rounded ones, 9 % at a skew of 1e-6; a
     * review's finding). Along any direction the gap is a lower bound, so
     * c need not be A_i x B_j exactly, only the terms must be c's. Nearly
     * parallel pairs are skipped (the face axes cover them). */
    for (int i = 0; i < 3; ++i) {
        int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
        for (int j = 0; j < 3; ++j) {
            double c1 = r[i1][j], c2 = r[i2][j]; /* c = c1 e_i2 - c2 e_i1 */
            double len2 = c1 * c1 + c2 * c2;
            if (!(len2 > 1e-6)) continue;
            double ra = ha[i1] * fabs(c2) + ha[i2] * fabs(c1);
            double rb = 0.0;
            for (int m = 0; m < 3; ++m) rb += hb[m] * fabs(c1 * r[i2][m] - c2 * r[i1][m]);
            double ts = t[i2] * c1 - t[i1] * c2; /* d . c */
            take(&best, &id, &sign, (fabs(ts) - ra - rb - margin) / sqrt(len2), AX_CROSS + 3 * i + j,
                 sgn(ts));
        }
    }
out:
    if (axis_out) {
        px_vec3 u = pxi_v(0, 0, 0);
        if (id == AX_HINT)
            u = *hint;
        else if (id == AX_CENTRES)
            u = pxi_scale(d, 1.0 / dl);
        else if (id >= AX_A && id < AX_B)
            u = aa[id - AX_A];
        else if (id >= AX_B && id < AX_CROSS)
            u = ba[id - AX_B];
        else if (id >= AX_CROSS) {
            int i = (id - AX_CROSS) / 3, j = (id - AX_CROSS) % 3, i1 = (i + 1) % 3, i2 = (i + 2) % 3;
            double c1 = r[i1][j], c2 = r[i2][j];
            u = pxi_scale(pxi_sub(pxi_scale(aa[i2], c1), pxi_scale(aa[i1], c2)),
                          1.0 / sqrt(c1 * c1 + c2 * c2));
        }
        *axis_out = pxi_scale(u, sign);
    }
    return best;
}

double pxi_tri_box_gap(const px_vec3 t[3], const pxi_box *b, const px_pose *t_box, const px_vec3 *hint,
                       double limit, px_vec3 *axis_out) {
    px_vec3 c = t_box ? pxi_xform(t_box, b->center) : b->center;
    px_vec3 ax[3];
    for (int k = 0; k < 3; ++k) {
        px_vec3 a = pxi_v(b->axis[3 * k], b->axis[3 * k + 1], b->axis[3 * k + 2]);
        ax[k] = t_box ? pxi_rot(t_box->r, a) : a;
    }
    double h[3] = {b->half.x, b->half.y, b->half.z};
    px_vec3 e1 = pxi_sub(t[1], t[0]), e2 = pxi_sub(t[2], t[0]);
    px_vec3 d0 = pxi_sub(t[0], c);
    double margin = 64.0 * DBL_EPSILON * (pxi_len(d0) + pxi_len(e1) + pxi_len(e2) + h[0] + h[1] + h[2]);
    double best = -INFINITY, sign = 1.0;
    px_vec3 axis = pxi_v(0, 0, 0);
    double axis_len = 1.0;
    /* On an axis u of length unit_len: the triangle's interval against the
     * box's; the oriented axis points from the box to the triangle. */
#define PXI_TRI_AXIS(u, unit_len)                                                                            \
    do {                                                                                                     \
        double p0 = pxi_dot(d0, u), p1 = p0 + pxi_dot(e1, u), p2 = p0 + pxi_dot(e2, u);                      \
        double lo = pxi_min2(p0, pxi_min2(p1, p2)), hi = pxi_max2(p0, pxi_max2(p1, p2)),                     \
               rr = box_radius(ax, h, u);                                                                    \
        double above = lo - rr, below = -rr - hi;                                                            \
        double g = (pxi_max2(above, below) - margin) / (unit_len);                                           \
        if (g > best) best = g, axis = (u), axis_len = (unit_len), sign = above >= below ? 1.0 : -1.0;       \
        if (best > limit) goto out;                                                                          \
    } while (0)
    if (hint) PXI_TRI_AXIS(*hint, 1.0);
    for (int k = 0; k < 3; ++k) PXI_TRI_AXIS(ax[k], 1.0);
    px_vec3 n = pxi_cross(e1, e2);
    double nl = pxi_len(n);
    if (nl > 0.0) PXI_TRI_AXIS(n, nl);
#undef PXI_TRI_AXIS
out:
    if (axis_out) *axis_out = pxi_scale(axis, sign / axis_len);
    return best;
}
