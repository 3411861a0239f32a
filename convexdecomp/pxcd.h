/* pxcd: proxima's CGAL component behind a C ABI.
 *
 * This is the only place where CGAL is used (C++17, convexdecomp/). Nothing
 * outside convexdecomp/ knows CGAL exists. Two services:
 *   1. pxcd_hull_*: the convex hull of a point set (CGAL convex_hull_3 with
 *      the Exact_predicates_inexact_constructions kernel), returned as
 *      polygonal faces: hull triangles that are *exactly* coplanar (exact
 *      predicate) are merged into one convex polygon.
 *   2. pxcd_exact_distance: exact Euclidean distance between the convex hulls
 *      of two point sets (CGAL Polytope_distance_d with Homogeneous<Gmpzf>),
 *      used as ground truth by tests and benchmarks.
 *   3. pxcd_decompose: approximate convex decomposition of a triangle mesh
 *      (declared in pxcd_decomp.h, included at the end of this header).
 * No function throws or aborts: CGAL exceptions are caught and reported;
 * running out of memory (std::bad_alloc, recognised by its type) has its own
 * status.
 */
#ifndef PROXIMA_PXCD_H
#define PROXIMA_PXCD_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum pxcd_status {
    PXCD_OK = 0,
    PXCD_ERROR = 2,         /* bad argument, CGAL threw, or an internal check failed: see msg */
    PXCD_OUT_OF_MEMORY = 3, /* an allocation failed (std::bad_alloc) */
    PXCD_INVALID_INPUT = 4, /* pxcd_decompose only: bad argument or input, see msg */
    PXCD_CANCELLED = 5      /* pxcd_decompose only: the progress callback asked to stop */
} pxcd_status;

/* The hull, as polygons. Vertex ids index `vertices`; each face is a convex
 * polygon listed counter-clockwise seen from outside (outward orientation),
 * with no repeated vertex and no three consecutive vertices collinear.
 * Only extreme points are vertices (no point in the middle of an edge or
 * face). Every undirected edge belongs to exactly two faces, which use it in
 * opposite directions, and V - E + F = 2.
 * Lower-dimensional point sets (exact predicates decide): a polygon
 * (coplanar points) has two faces, its extreme points in order and the same
 * loop reversed (a two-sided polygon: every edge still belongs to exactly
 * two faces, and V - E + F = 2); a segment (collinear points) is its two end
 * points and no face; a point is one vertex and no face.
 * The output is canonical, hence deterministic: vertex i is the i-th distinct
 * extreme point in input order, with the coordinates (bit for bit) of its
 * first occurrence in the input; each face starts at its smallest vertex id
 * and faces are sorted by their first two ids.
 * Memory is owned by the pxcd_hull; free it with pxcd_hull_free. */
typedef struct pxcd_hull {
    size_t vertex_count;
    double *vertices; /* 3 * vertex_count, copied from the input */
    size_t face_count;
    size_t *face_offsets;   /* face_count + 1; face f = face_indices[offsets[f] .. offsets[f+1]) */
    uint32_t *face_indices; /* vertex ids, CCW from outside */
} pxcd_hull;

/* Computes the hull of `count` points (xyz: 3*count doubles, all finite:
 * the caller checks). On PXCD_OK *out is a new hull and *dimension the
 * affine dimension of the input (0 = one distinct point, 1 = collinear,
 * 2 = coplanar, 3 = a solid; decided with exact predicates). On PXCD_ERROR and PXCD_OUT_OF_MEMORY *out is
 * NULL and a sentence goes to msg (msg_len bytes, may be 0); count == 0 is
 * an error. `dimension` and `msg` may be NULL.
 * Time: ~1 s for 200k points in convex position. If the FPU's directed
 * rounding does not work (valgrind), an exact rational kernel is used
 * instead of CGAL's filtered one: same result, much slower. Reads no
 * environment variable and keeps no setting between calls. */
pxcd_status pxcd_hull_compute(const double *xyz, size_t count, pxcd_hull **out, int *dimension, char *msg,
                              size_t msg_len);

/* Flags of pxcd_hull_compute_ex. */
enum {
    /* Test only: compute with the exact rational kernel even where directed
     * rounding works, so that tests run the valgrind fallback natively. */
    PXCD_HULL_FORCE_EXACT_KERNEL = 1
};

/* Test only: pxcd_hull_compute with `flags`, a combination of PXCD_HULL_*
 * values (0: exactly pxcd_hull_compute). Unknown flags are PXCD_ERROR. */
pxcd_status pxcd_hull_compute_ex(const double *xyz, size_t count, unsigned flags, pxcd_hull **out,
                                 int *dimension, char *msg, size_t msg_len);

void pxcd_hull_free(pxcd_hull *hull);

/* Exact distance between conv(P) and conv(Q), P = p_xyz (np points),
 * Q = q_xyz (nq points), all in one common frame, all finite, np, nq >= 1.
 * Computed with CGAL::Polytope_distance_d over Homogeneous<Gmpzf> (exact)
 * and certified with its exact is_valid(). From the exact rational squared
 * distance, *distance is its square root and *squared_distance the value
 * itself, each correctly rounded to nearest double (via MPFR; no overflow or
 * underflow of intermediate parts, so right for any input scale; the squared
 * distance may underflow to 0 or be subnormal below ~1.5e-154, the distance
 * does not). *is_zero is 1 when the exact distance is 0 (touching or
 * intersecting). Optionally (realizing_p / realizing_q non-NULL, 3 doubles
 * each) returns the realizing points, each coordinate correctly rounded.
 * Any output pointer may be NULL. Outputs are written only on PXCD_OK;
 * otherwise PXCD_ERROR or PXCD_OUT_OF_MEMORY, with a sentence in msg.
 * Time: ~0.1 s for two 5k-vertex hulls, a few seconds for 200k points each. */
pxcd_status pxcd_exact_distance(const double *p_xyz, size_t np, const double *q_xyz, size_t nq,
                                double *distance, double *squared_distance, int *is_zero, double *realizing_p,
                                double *realizing_q, char *msg, size_t msg_len);

#ifdef __cplusplus
}
#endif

#include "pxcd_decomp.h"

#endif /* PROXIMA_PXCD_H */
