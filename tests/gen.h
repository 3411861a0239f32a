/* Deterministic random geometry for the tests (test-only, not part of the
 * library).
 *
 * PRNG: xoshiro256** seeded through splitmix64 (Blackman and Vigna,
 * "Scrambled linear pseudorandom number generators", 2018; public-domain
 * reference code at prng.di.unimi.it, rewritten here). Every stream is fixed
 * by its seed, so a failing case is reproduced by its seed and index.
 *
 * None of these functions produce NaN, Inf or divide by zero (test builds
 * trap FE_INVALID and FE_DIVBYZERO).
 */
#ifndef PX_TESTS_GEN_H
#define PX_TESTS_GEN_H

#include <stddef.h>
#include <stdint.h>

#include "proxima/proxima.h"

typedef struct tg_rng {
    uint64_t s[4];
} tg_rng;

void tg_seed(tg_rng *rng, uint64_t seed);
uint64_t tg_next(tg_rng *rng);
/* Uniform in (0, 1): never exactly 0 or 1 (safe for log). */
double tg_uniform(tg_rng *rng);
double tg_range(tg_rng *rng, double lo, double hi);
/* Uniform integer in [0, n), n > 0. */
uint32_t tg_below(tg_rng *rng, uint32_t n);
/* Log-uniform integer in [lo, hi]. */
uint32_t tg_log_int(tg_rng *rng, uint32_t lo, uint32_t hi);
/* Standard normal (Box-Muller). */
double tg_normal(tg_rng *rng);
/* Uniform unit vector (normalised Gaussian; a zero draw is redrawn). */
px_vec3 tg_unit(tg_rng *rng);

/* Point sets; `xyz` receives 3*n doubles. */
void tg_points_ball(tg_rng *rng, size_t n, double radius, double *xyz);
void tg_points_sphere(tg_rng *rng, size_t n, double radius, double *xyz);
/* On the ellipsoid surface with semi-axes a, b, c (x, y, z). */
void tg_points_ellipsoid(tg_rng *rng, size_t n, double a, double b, double c, double *xyz);
/* Uniform in the box [-hx,hx]x[-hy,hy]x[-hz,hz]. */
void tg_points_in_box(tg_rng *rng, size_t n, double hx, double hy, double hz, double *xyz);
/* The 8 corners of a box of half extents hx, hy, hz centred at the origin. */
void tg_box(double hx, double hy, double hz, double xyz[24]);
/* Regular tetrahedron of edge `edge` centred at the origin. */
void tg_regular_tetrahedron(double edge, double xyz[12]);
/* Random tetrahedron with vertices on a sphere of radius r, with volume at
 * least 5% of the regular one. */
void tg_random_tetrahedron(tg_rng *rng, double r, double xyz[12]);
/* Cylinder around z: 2*k points (k around, two rings at +-half_height). */
void tg_cylinder(size_t k, double radius, double half_height, double *xyz);

/* A random convex shape, for the random suites. Kinds: */
typedef enum tg_kind {
    TG_BALL = 0,       /* points in a ball (hull vertices < n) */
    TG_SPHERE,         /* points on a sphere (all vertices) */
    TG_ELLIPSOID_THIN, /* on an ellipsoid 1:8:40 */
    TG_ELLIPSOID_RAND, /* on an ellipsoid with random semi-axes 1 .. 30 */
    TG_BOX,            /* random box (8 points) */
    TG_TETRA,          /* random tetrahedron */
    TG_CYLINDER,       /* cylinder with n/2 points around */
    TG_NEEDLE,         /* points in a cylinder of aspect 1:100 */
    TG_SLAB,           /* points in a box 1:50:50 */
    TG_KIND_COUNT
} tg_kind;

const char *tg_kind_name(tg_kind kind);
/* Writes up to `n` points (n >= 8) of a shape of kind `kind` and overall size
 * about `size` into xyz (room for 3*n doubles); returns the number written. */
size_t tg_shape(tg_rng *rng, tg_kind kind, size_t n, double size, double *xyz);

/* Rotations (row-major 3x3). */
void tg_quat_uniform(tg_rng *rng, double q[4]); /* (w, x, y, z), Shoemake 1992 */
void tg_rot_from_quat(const double q[4], double r[9]);
void tg_rot_axis_angle(px_vec3 axis, double angle, double r[9]); /* axis unit */
void tg_rot_random(tg_rng *rng, double r[9]);
void tg_mat_mul(const double a[9], const double b[9], double out[9]); /* out = a*b */
/* Re-orthonormalise a rotation (Gram-Schmidt on the rows). */
void tg_rot_orthonormalize(double r[9]);
/* Random pose: uniform rotation, translation uniform in [-tr, tr]^3. */
px_pose tg_pose_random(tg_rng *rng, double tr);

#endif
