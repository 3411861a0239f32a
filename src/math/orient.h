/* Orientation of three points in a plane, and collinearity of three points
 * in space: J. R. Shewchuk, "Adaptive precision floating-point arithmetic
 * and fast robust geometric predicates" (Discrete Comput. Geom. 18, 1997),
 * orient2d. Used by the mesh's closed-surface test (a triangle whose
 * corners are collinear) and by px_convex_create (three points that are
 * surely a triangle skip CGAL's hull). */
#ifndef PXI_MATH_ORIENT_H
#define PXI_MATH_ORIENT_H

#include "math/vec3.h"

/* The sign of (px - rx)(qy - ry) - (py - ry)(qx - rx) when the
 * double-precision determinant decides it (Shewchuk's first stage: |det| >
 * (3 + 16 eps) eps (|l| + |r|), eps = 2^-53), else 0. Only products in the
 * normal range decide (the bound assumes no underflow nor overflow), so a
 * nonzero answer is always the exact sign. */
int pxi_orient2d_filter(double px, double py, double qx, double qy, double rx, double ry);

/* The exact sign, the determinant summed as an expansion where the filter
 * does not decide. Exact when every nonzero coordinate lies between 2^-400
 * and 2^400: the coordinates are then multiples of 2^-452, so are the
 * differences and their rounding errors, and every product's error term is
 * a normal number (fma computes it exactly). Far below that (coordinates
 * near 2^-489) a review found nonzero determinants taken for 0. */
int pxi_orient2d_sign(double px, double py, double qx, double qy, double rx, double ry);

/* The determinant itself, (px - rx)(qy - ry) - (py - ry)(qx - rx), to
 * within about eps of its value plus a few eps^2 of |l| + |r| (the two
 * products' sizes): full relative precision however much the products
 * cancel, down to triangles whose height is eps of their length (a
 * sliver's normal; plain double loses a factor |l| / |det|). Coordinates
 * should be near unit scale (pxi_unit_scale): the error terms underflow
 * below about 2^-900. */
double pxi_orient2d_value(double px, double py, double qx, double qy, double rx, double ry);

/* (b - a) x (c - a), each component a pxi_orient2d_value: the normal of
 * a sliver triangle to full relative precision (near unit scale). */
px_vec3 pxi_tri_cross(px_vec3 a, px_vec3 b, px_vec3 c);

/* Below this sin^2 of the angle between edges e0 and e1 (|e0 x e1|^2 over
 * |e0|^2 |e1|^2) a triangle is a sliver: plain products for its normal, and
 * for weights or region tests built on it, lose a factor of its aspect.
 * One threshold for every query that switches to pxi_tri_cross there. */
#define PXI_SLIVER 0x1p-16

/* Whether the triangle of edges e0 and e1, plain cross product n, is a
 * sliver. */
static inline int pxi_is_sliver(px_vec3 n, px_vec3 e0, px_vec3 e1) {
    return pxi_dot(n, n) < PXI_SLIVER * pxi_dot(e0, e0) * pxi_dot(e1, e1);
}

/* For the sliver paths of hot loops: the common path inlined, the rare
 * one out of line behind a cold branch (review s31: a non-inlined face
 * helper called eight times a tetrahedron step cost 12 % of a ray cast). */
#if defined(__GNUC__)
#define PXI_HOT_INLINE static inline __attribute__((always_inline))
#define PXI_COLD static __attribute__((noinline))
#define PXI_RARE(x) __builtin_expect(!!(x), 0)
#else
#define PXI_HOT_INLINE static inline
#define PXI_COLD static
#define PXI_RARE(x) (x)
#endif

/* (b - a) x (c - a): plain products, pxi_tri_cross for a sliver (GJK's
 * tetrahedron side tests, the ray cast's final plane). */
PXI_HOT_INLINE px_vec3 pxi_tri_normal(px_vec3 a, px_vec3 b, px_vec3 c) {
    px_vec3 ab = pxi_sub(b, a), ac = pxi_sub(c, a), n = pxi_cross(ab, ac);
    if (PXI_RARE(pxi_is_sliver(n, ab, ac))) n = pxi_tri_cross(a, b, c);
    return n;
}

/* A power of two that brings magnitudes up to `big` near 1, so that
 * products and cubes of coordinates neither overflow nor underflow (1 in
 * the usual range, 2^-100..2^100; at most 2^1023, which leaves subnormal
 * magnitudes near 2^-50). */
double pxi_unit_scale(double big);

/* 1 when the three points (xyz each) are collinear or two coincide:
 * every coordinate projection's orientation is 0. The points are first
 * scaled by a power of two that brings the largest magnitude near 1 (exact
 * but for coordinates that underflow far below the largest). Exact when
 * every nonzero coordinate is at least 2^-400 of the largest (see
 * pxi_orient2d_sign); far below that a triangle may be taken for
 * collinear. */
int pxi_collinear(const double *a, const double *b, const double *c);

#endif
