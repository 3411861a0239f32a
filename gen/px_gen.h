/* proxima_gen: the deterministic shape and motion generators shared by the
 * tests, the benchmarks and the thesis demo (examples/). A development aid,
 * not part of the library: it is not installed.
 *
 * Pure generators: they use only the public types of proxima.h (px_vec3,
 * px_pose), call nothing in the library and include nothing from src/. The
 * judges of the library's answers (the oracles and checks of tests/, the
 * demo's certificates) stay outside, independent of both.
 *
 * Two random streams, each kept bit for bit from where it came from, so that
 * the tests' results, the benchmarks' workloads and the demo's tables do not
 * move:
 *   pg_rng  xoshiro256** seeded through splitmix64 (Blackman and Vigna,
 *           "Scrambled linear pseudorandom number generators", 2018;
 *           public-domain reference code at prng.di.unimi.it, rewritten):
 *           the tests' stream (was tests/gen.c);
 *   pg_sm   a plain splitmix64 sequence (Steele, Lea and Flood, "Fast
 *           splittable pseudorandom number generators", 2014): the
 *           benchmarks' and the demo's stream (was bench/bench_common.h and
 *           the demo's rng_next).
 * Every stream is fixed by its seed, so a failing case is reproduced by its
 * seed and index. Where two consumers wrote the same formula with a
 * different rounding (a rotation matrix with or without renormalising the
 * quaternion, Rodrigues' formula grouped two ways), both are kept under
 * their own names and say who uses them.
 *
 * None of these functions produce NaN, Inf or divide by zero on valid
 * arguments (test builds trap FE_INVALID and FE_DIVBYZERO).
 *
 * Rotations are row-major 3x3 matrices (r[3*i + j] = R_ij), as in px_pose. */
#ifndef PX_GEN_H
#define PX_GEN_H

#include <stddef.h>
#include <stdint.h>

#include "proxima/proxima.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------------- */
/* The tests' stream: xoshiro256**                                           */
/* ------------------------------------------------------------------------- */

typedef struct pg_rng {
    uint64_t s[4];
} pg_rng;

void pg_seed(pg_rng *rng, uint64_t seed);
uint64_t pg_next(pg_rng *rng);
/* Uniform in (0, 1): never exactly 0 or 1 (safe for log). */
double pg_uniform(pg_rng *rng);
double pg_range(pg_rng *rng, double lo, double hi);
/* Uniform integer in [0, n), n > 0. */
uint32_t pg_below(pg_rng *rng, uint32_t n);
/* Log-uniform integer in [lo, hi]. */
uint32_t pg_log_int(pg_rng *rng, uint32_t lo, uint32_t hi);
/* Standard normal (Box-Muller). */
double pg_normal(pg_rng *rng);
/* Uniform unit vector (normalised Gaussian; a zero draw is redrawn). */
px_vec3 pg_unit(pg_rng *rng);

/* ------------------------------------------------------------------------- */
/* The benchmarks' and the demo's stream: splitmix64                         */
/* ------------------------------------------------------------------------- */

/* The state is the whole generator: `pg_sm rng = {seed};`. */
typedef struct pg_sm {
    uint64_t s;
} pg_sm;

uint64_t pg_sm_next(pg_sm *rng);
/* Uniform in [0, 1): the top 53 bits / 2^53. */
double pg_sm_uniform(pg_sm *rng);
/* Uniform unit vector: a point of the cube [-1, 1)^3 drawn x, y, z, kept if
 * 1e-6 < |p|^2 <= 1 (a point of the ball), then normalised. */
px_vec3 pg_sm_unit(pg_sm *rng);
/* A unit vector perpendicular to the unit vector u, uniformly at random. */
px_vec3 pg_sm_perpendicular(pg_sm *rng, px_vec3 u);

/* ------------------------------------------------------------------------- */
/* Point sets; `xyz` receives 3*n doubles                                     */
/* ------------------------------------------------------------------------- */

/* Uniform in the ball / on the sphere of the given radius (pg_unit). */
void pg_points_ball(pg_rng *rng, size_t n, double radius, double *xyz);
void pg_points_sphere(pg_rng *rng, size_t n, double radius, double *xyz);
/* On the ellipsoid surface with semi-axes a, b, c (x, y, z). */
void pg_points_ellipsoid(pg_rng *rng, size_t n, double a, double b, double c, double *xyz);
/* Uniform in the box [-hx,hx]x[-hy,hy]x[-hz,hz]. */
void pg_points_in_box(pg_rng *rng, size_t n, double hx, double hy, double hz, double *xyz);
/* On the sphere of the given radius from the splitmix64 stream (pg_sm_unit):
 * bench_hybrid's random polyhedra (seed 001 section 6). */
void pg_sm_points_sphere(pg_sm *rng, size_t n, double radius, double *xyz);
/* n points of a golden-spiral (Fibonacci) lattice on the unit sphere, mapped
 * to the ellipsoid with semi-axes a, b, c: bench_convex's bodies (seed 002).
 * Points on a strictly convex surface are all extreme, so (up to rounding)
 * every point is a hull vertex. */
void pg_points_fibonacci_ellipsoid(size_t n, double a, double b, double c, double *xyz);

/* The 8 corners of a box of half extents hx, hy, hz centred at the origin
 * (corner i has +hx when bit 0 of i is set, +hy for bit 1, +hz for bit 2). */
void pg_box(double hx, double hy, double hz, double xyz[24]);
/* Regular tetrahedron of edge `edge` centred at the origin. */
void pg_regular_tetrahedron(double edge, double xyz[12]);
/* Random tetrahedron with vertices on a sphere of radius r, with volume at
 * least 5% of the regular one. */
void pg_random_tetrahedron(pg_rng *rng, double r, double xyz[12]);
/* Cylinder around z: 2*k points (k around, two rings at +-half_height),
 * ordered bottom, top for each angle 2 pi i / k. */
void pg_cylinder(size_t k, double radius, double half_height, double *xyz);
/* Prism / cone / frustum around z: an n-gon of radius r0 at z = -h/2, then
 * one of radius r1 at z = +h/2 (r1 = 0: a cone with its apex at the top), the
 * demo's primitives (seed 000 Table 3.1). Returns the number of points,
 * n + (r1 > 0 ? n : 1); with xyz NULL it only counts. */
size_t pg_frustum(int n, double r0, double r1, double h, double *xyz);
/* Polygonised (latitude-longitude) sphere of radius r: the two poles, then
 * nlat - 1 rings of nlon points (seed 000 Fig. 3.12). Returns the number of
 * points, 2 + (nlat - 1) * nlon; with xyz NULL it only counts. */
size_t pg_sphere_latlong(int nlat, int nlon, double r, double *xyz);

/* A random convex shape, for the random test suites. Kinds: */
typedef enum pg_kind {
    PG_BALL = 0,       /* points in a ball (hull vertices < n) */
    PG_SPHERE,         /* points on a sphere (all vertices) */
    PG_ELLIPSOID_THIN, /* on an ellipsoid 1:8:40 */
    PG_ELLIPSOID_RAND, /* on an ellipsoid with random semi-axes 1 .. 30 */
    PG_BOX,            /* random box (8 points) */
    PG_TETRA,          /* random tetrahedron */
    PG_CYLINDER,       /* cylinder with n/2 points around */
    PG_NEEDLE,         /* points in a cylinder of aspect 1:100 */
    PG_SLAB,           /* points in a box 1:50:50 */
    PG_KIND_COUNT
} pg_kind;

const char *pg_kind_name(pg_kind kind);
/* Writes up to `n` points (n >= 8) of a shape of kind `kind` and overall size
 * about `size` into xyz (room for 3*n doubles); returns the number written. */
size_t pg_shape(pg_rng *rng, pg_kind kind, size_t n, double size, double *xyz);

/* ------------------------------------------------------------------------- */
/* Rotations                                                                 */
/* ------------------------------------------------------------------------- */

/* Unit quaternion (w, x, y, z) of a uniformly distributed rotation from three
 * uniforms in [0, 1], drawn u1, u2, u3 (Shoemake, "Uniform random
 * rotations", Graphics Gems III, 1992). */
void pg_quat_shoemake(double u1, double u2, double u3, double q[4]);
/* pg_quat_shoemake on the tests' stream. */
void pg_quat_uniform(pg_rng *rng, double q[4]);
/* Rotation of the quaternion q (w, x, y, z) normalised first (the tests'). */
void pg_rot_from_quat(const double q[4], double r[9]);
/* Rotation of q taken as a unit quaternion, not renormalised (the
 * benchmarks'). */
void pg_rot_from_unit_quat(const double q[4], double r[9]);
/* Rotation by `angle` about the unit axis, through the quaternion (the
 * tests'). */
void pg_rot_axis_angle(px_vec3 axis, double angle, double r[9]);
/* Rotation by `angle` about the unit axis u by Rodrigues' formula
 * R = c I + s [u]x + (1 - c) u u^T with the products grouped (u_i u_j)(1 - c)
 * (the demo's). */
void pg_rot_rodrigues(px_vec3 u, double angle, double r[9]);
/* r = rot(u, angle) r, with rot(u, angle) by Rodrigues' formula grouped
 * ((1 - c) u_i) u_j (the benchmarks' step of a constant angular velocity).
 * Same rotation as pg_rot_rodrigues, rounded differently. */
void pg_rot_turn(px_vec3 u, double angle, double r[9]);
/* Uniform random rotation (Shoemake): the tests' (pg_rot_from_quat) and the
 * benchmarks' (pg_sm_uniform, pg_rot_from_unit_quat). */
void pg_rot_random(pg_rng *rng, double r[9]);
void pg_sm_rot_random(pg_sm *rng, double r[9]);
void pg_mat_mul(const double a[9], const double b[9], double out[9]); /* out = a*b; out may alias */
/* Re-orthonormalise a rotation (Gram-Schmidt on the rows). */
void pg_rot_orthonormalize(double r[9]);
/* R p. */
px_vec3 pg_rot_apply(const double r[9], px_vec3 p);
/* URDF's fixed-axis roll, pitch, yaw: R = Rz(yaw) Ry(pitch) Rx(roll), the
 * products grouped as src/io/urdf.c groups them (bit for bit its matrix). */
void pg_rot_rpy(double roll, double pitch, double yaw, double r[9]);

/* ------------------------------------------------------------------------- */
/* Poses                                                                     */
/* ------------------------------------------------------------------------- */

/* Random pose: uniform rotation, translation uniform in [-tr, tr]^3. */
px_pose pg_pose_random(pg_rng *rng, double tr);
/* Random pose near a point: pg_pose_random(rng, 0), then the origin moved to
 * centre + dist * pg_unit(rng). */
px_pose pg_pose_around(pg_rng *rng, px_vec3 centre, double dist);
/* Pose with rotation r that puts the body-frame point `body_centre` at the
 * world point `at` (t = at - R body_centre). */
px_pose pg_pose_centred(const double r[9], px_vec3 body_centre, px_vec3 at);

/* ------------------------------------------------------------------------- */
/* Motions: pose sequences of the demo and the benchmarks                    */
/* ------------------------------------------------------------------------- */

/* Relative rotation at a constant rate (seed 000 section 3.5; the demo's
 * (a)-(c)). Both bodies spin about the same world axis through their own
 * centres, A by +k theta / 2 and B by -k theta / 2 at step k (Rodrigues), so
 * R_B^T R_A turns by exactly theta per step. A's centre stays at the origin,
 * B's is at (separation, 0, 0) plus a displacement of amplitude disp_amp,
 * (sin 1.3s, 0.5 sin(0.7s + 1), 0.5 sin(1.1s + 2)) with s = k theta: its
 * phase follows the rotation, so it scales with theta. */
typedef struct pg_spin {
    px_vec3 axis;      /* unit */
    double theta;      /* relative rotation per step, radians */
    double separation; /* distance between the centres before displacement */
    double disp_amp;   /* displacement amplitude (0: none) */
} pg_spin;

/* Step k; centre_a and centre_b are the bodies' centres in their own frames. */
void pg_spin_poses(const pg_spin *m, px_vec3 centre_a, px_vec3 centre_b, int k, px_pose *pa, px_pose *pb);

/* Approach, contact, overlap and separation (the demo's (d)-(g)). Step k of
 * n, phi the relative rotation accumulated so far (the sum of
 * pg_swing_step(j) for j < k): A turns by +phi/2 and B by -phi/2 about the
 * axis (Rodrigues), B also by the fixed r0 first (so that two copies of one
 * hull do not meet mirror-aligned). A's centre stays at the origin; B's is
 * f(k) size along x, with f = 0.75 + 0.4 cos(4 pi k / n) swinging twice from
 * 1.15 (apart for size = R_A + R_B) to 0.35 (deep overlap) and back, plus a
 * sideways wobble of 8% of size. */
typedef struct pg_swing {
    px_vec3 axis;
    double size;
    double r0[9];
} pg_swing;

/* Step angle of the swing: 1 to 5 degrees, varying smoothly with k. */
double pg_swing_step(int k);
void pg_swing_poses(const pg_swing *m, px_vec3 centre_a, px_vec3 centre_b, int k, int n, double phi,
                    px_pose *pa, px_pose *pb);

/* Point k of n evenly spaced on the circle of the given radius about the
 * origin in the plane of the orthonormal u, v: radius (cos phi u + sin phi v),
 * phi = 2 pi k / n (bench_hybrid's translation path, seed 001 section 6). */
px_vec3 pg_circle_point(px_vec3 u, px_vec3 v, double radius, size_t k, size_t n);

#ifdef __cplusplus
}
#endif

#endif
