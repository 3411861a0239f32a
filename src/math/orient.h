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
