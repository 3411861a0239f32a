/* Small inline vector and pose helpers used by every layer (internal). */
#ifndef PXI_VEC3_H
#define PXI_VEC3_H

#include <math.h>

#include "proxima/math.h"

static inline px_vec3 pxi_v(double x, double y, double z) {
    px_vec3 r = {x, y, z};
    return r;
}
static inline px_vec3 pxi_add(px_vec3 a, px_vec3 b) { return pxi_v(a.x + b.x, a.y + b.y, a.z + b.z); }
static inline px_vec3 pxi_sub(px_vec3 a, px_vec3 b) { return pxi_v(a.x - b.x, a.y - b.y, a.z - b.z); }
static inline px_vec3 pxi_scale(px_vec3 a, double s) { return pxi_v(a.x * s, a.y * s, a.z * s); }
static inline px_vec3 pxi_neg(px_vec3 a) { return pxi_v(-a.x, -a.y, -a.z); }
static inline double pxi_dot(px_vec3 a, px_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline px_vec3 pxi_cross(px_vec3 a, px_vec3 b) {
    return pxi_v(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static inline double pxi_len2(px_vec3 a) { return pxi_dot(a, a); }
static inline double pxi_len(px_vec3 a) { return sqrt(pxi_dot(a, a)); }
/* a + s * b */
static inline px_vec3 pxi_madd(px_vec3 a, px_vec3 b, double s) {
    return pxi_v(a.x + s * b.x, a.y + s * b.y, a.z + s * b.z);
}
/* min and max of two finite values (libm's fmin and fmax are calls on x86-64
 * without -ffinite-math-only; these compile to minsd and maxsd). */
static inline double pxi_min2(double a, double b) { return a < b ? a : b; }
static inline double pxi_max2(double a, double b) { return a > b ? a : b; }
/* The axis-aligned box [lo, hi] of n >= 1 points (3 doubles each). */
static inline void pxi_box3(const double *xyz, size_t n, px_vec3 *lo, px_vec3 *hi) {
    double l[3] = {xyz[0], xyz[1], xyz[2]}, h[3] = {xyz[0], xyz[1], xyz[2]};
    for (size_t i = 1; i < n; ++i)
        for (int j = 0; j < 3; ++j) {
            l[j] = pxi_min2(l[j], xyz[3 * i + j]);
            h[j] = pxi_max2(h[j], xyz[3 * i + j]);
        }
    *lo = (px_vec3){l[0], l[1], l[2]};
    *hi = (px_vec3){h[0], h[1], h[2]};
}
static inline double pxi_max_abs(px_vec3 a) {
    double m = fabs(a.x);
    if (fabs(a.y) > m) m = fabs(a.y);
    if (fabs(a.z) > m) m = fabs(a.z);
    return m;
}
static inline int pxi_is_finite3(px_vec3 a) { return isfinite(a.x) && isfinite(a.y) && isfinite(a.z); }

/* Scale-safe arithmetic. Squares and products of two lengths overflow above
 * about 1e154 and underflow below 1e-154; the helpers below keep the plain
 * formula (the same bits) in the safe range and work at a power-of-two scale
 * (exact) outside it. */

/* a * 2^e, exact unless the result leaves the normal range. */
static inline px_vec3 pxi_ldexp3(px_vec3 a, int e) {
    return pxi_v(ldexp(a.x, e), ldexp(a.y, e), ldexp(a.z, e));
}
/* Lengths whose squares are safe: max-abs in [2^-500, 2^500] (squares and
 * products of two such lengths stay normal and finite). */
static inline int pxi_len_ok(double m) { return m >= 0x1p-500 && m <= 0x1p500; }
/* |a| without overflow or underflow of the squares. */
static inline double pxi_len_safe(px_vec3 a) {
    double m = pxi_max_abs(a);
    if (pxi_len_ok(m)) return sqrt(a.x * a.x + a.y * a.y + a.z * a.z);
    if (!(m > 0.0) || !isfinite(m)) return m == m ? m : NAN;
    int e = ilogb(m);
    px_vec3 s = pxi_ldexp3(a, -e);
    return ldexp(sqrt(s.x * s.x + s.y * s.y + s.z * s.z), e);
}
/* a / |a| (zero vector for zero or non-finite a), scale-safe likewise. */
static inline px_vec3 pxi_unit_safe(px_vec3 a) {
    double m = pxi_max_abs(a);
    if (!(m > 0.0) || !isfinite(m)) return pxi_v(0, 0, 0);
    if (!pxi_len_ok(m)) a = pxi_ldexp3(a, -ilogb(m));
    double l = sqrt(a.x * a.x + a.y * a.y + a.z * a.z);
    return l > 0.0 && isfinite(l) ? pxi_v(a.x / l, a.y / l, a.z / l) : pxi_v(0, 0, 0);
}
/* The power of two k with m k in [1, 2), for m > 0 finite; clamped to the
 * double range (a subnormal m gets 2^1023, not inf). 1 otherwise. */
static inline double pxi_pow2_unit(double m) {
    if (!(m > 0.0) || !isfinite(m)) return 1.0;
    int e = -ilogb(m);
    return ldexp(1.0, e > 1023 ? 1023 : e);
}

/* R * p (rotation only), R row-major. */
static inline px_vec3 pxi_rot(const double r[9], px_vec3 p) {
    return pxi_v(r[0] * p.x + r[1] * p.y + r[2] * p.z, r[3] * p.x + r[4] * p.y + r[5] * p.z,
                 r[6] * p.x + r[7] * p.y + r[8] * p.z);
}
/* R^T * p */
static inline px_vec3 pxi_rot_t(const double r[9], px_vec3 p) {
    return pxi_v(r[0] * p.x + r[3] * p.y + r[6] * p.z, r[1] * p.x + r[4] * p.y + r[7] * p.z,
                 r[2] * p.x + r[5] * p.y + r[8] * p.z);
}
static inline px_vec3 pxi_xform(const px_pose *T, px_vec3 p) { return pxi_add(pxi_rot(T->r, p), T->t); }
/* T^-1 * p */
static inline px_vec3 pxi_xform_inv(const px_pose *T, px_vec3 p) { return pxi_rot_t(T->r, pxi_sub(p, T->t)); }

/* How far a rotation matrix's rows are from orthonormal and right-handed:
 * res = |r0|^2 - 1, |r1|^2 - 1, r0.r1 and r2 - r0 x r1 (3). px_pose_check
 * accepts a pose when all six are within PXI_POSE_TOL. */
#define PXI_POSE_TOL 1e-6
static inline int pxi_rotation_residuals(const double r[9], double res[6]) {
    res[0] = r[0] * r[0] + r[1] * r[1] + r[2] * r[2] - 1.0;
    res[1] = r[3] * r[3] + r[4] * r[4] + r[5] * r[5] - 1.0;
    res[2] = r[0] * r[3] + r[1] * r[4] + r[2] * r[5];
    res[3] = r[1] * r[5] - r[2] * r[4] - r[6];
    res[4] = r[2] * r[3] - r[0] * r[5] - r[7];
    res[5] = r[0] * r[4] - r[1] * r[3] - r[8];
    int ok = 1;
    for (int i = 0; i < 6; ++i) ok &= fabs(res[i]) <= PXI_POSE_TOL;
    return ok;
}

/* |R^T R - I| (Frobenius): how far a pose's matrix is from a rotation; it
 * bounds |R^T R - I| and |R R^T - I| in the 2-norm, so R stretches or
 * shrinks lengths by a factor within [sqrt(1 - skew), sqrt(1 + skew)]. */
static inline double pxi_skew(const double r[9]) {
    double f = 0.0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            double d = r[i] * r[j] + r[3 + i] * r[3 + j] + r[6 + i] * r[6 + j] - (i == j ? 1.0 : 0.0);
            f += d * d;
        }
    return sqrt(f);
}

/* px_pose_check's test (finite; rows orthonormal and right-handed within
 * PXI_POSE_TOL) and the pose's skew (pxi_skew) in one pass, for hot paths
 * that check a pose at every query: 0 when the pose fails (px_pose_check
 * then says why). The skew comes from the rows, the residuals' own terms:
 * |R R^T - I|_F = |R^T R - I|_F (R R^T - I = Q (R^T R - I) Q^T for the
 * polar factor Q, so both have the same singular values). */
static inline int pxi_pose_ok_skew(const px_pose *pose, double *sk) {
    const double *r = pose->r;
    for (int i = 0; i < 9; ++i)
        if (!isfinite(r[i])) return 0;
    if (!pxi_is_finite3(pose->t)) return 0;
    double res[6];
    if (!pxi_rotation_residuals(r, res)) return 0;
    double n2 = r[6] * r[6] + r[7] * r[7] + r[8] * r[8] - 1.0;
    double d02 = r[0] * r[6] + r[1] * r[7] + r[2] * r[8], d12 = r[3] * r[6] + r[4] * r[7] + r[5] * r[8];
    *sk = sqrt(res[0] * res[0] + res[1] * res[1] + n2 * n2 + 2.0 * (res[2] * res[2] + d02 * d02 + d12 * d12));
    return 1;
}

/* T_AB = T_B^-1 * T_A: maps A's body frame into B's. The translations are
 * subtracted first (exact when the bodies are close; REFERENCES §1.8, §7). */
static inline px_pose pxi_relative(const px_pose *ta, const px_pose *tb) {
    px_pose out;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            out.r[3 * i + j] =
                tb->r[i] * ta->r[j] + tb->r[3 + i] * ta->r[3 + j] + tb->r[6 + i] * ta->r[6 + j];
    out.t = pxi_rot_t(tb->r, pxi_sub(ta->t, tb->t));
    return out;
}

#endif
