/* Brute-force distance and intersection oracle for the tests.
 *
 * Independent of the library's query code: it reads a px_convex only through
 * the public accessors (vertices, edges, face vertex lists), recomputes every
 * face plane itself (Newell's method on the face polygon), and evaluates the
 * distance as the minimum over ALL feature pairs:
 *   V-V, V-E, V-F (point to convex polygon), E-E (segment-segment); the
 *   distance between two disjoint convex polytopes is attained by a V-F,
 *   F-V or E-E pair (e.g. Ericson, "Real-Time Collision Detection", 2005,
 *   §5.1, §9.5; Lin 1993, thesis ch. 3), so the minimum is the distance.
 * Intersection (solids): the polytopes intersect iff a vertex of one lies in
 * the other (inside every face plane) or an edge of one crosses a face of
 * the other (E-F crossing). Bounding-sphere lower bounds prune pairs that
 * cannot improve the current minimum (the bounds are rigorous up to a
 * relative 1e-9 slack), which keeps 2,000-vertex hulls affordable.
 *
 * Everything is evaluated in one "common" frame chosen by the caller,
 * normally B's body frame with A mapped by T_AB = T_B^-1 T_A (the frame the
 * library works in). No function produces NaN or divides by zero.
 */
#ifndef PX_TESTS_ORACLE_H
#define PX_TESTS_ORACLE_H

#include <stdint.h>

#include "proxima/proxima.h"

typedef struct or_poly {
    uint32_t nv, ne, nf;
    px_vec3 *v;        /* vertices in the common frame */
    uint32_t *ev;      /* 2 * ne: edge endpoints */
    uint32_t *f_first; /* nf + 1 */
    uint32_t *f_vert;  /* face vertex ids, CCW seen from outside */
    px_vec3 *fn;       /* outward unit normals (Newell, oriented away from the centroid) */
    px_vec3 *fw;       /* unit Newell normals of the face loops as given (winding order) */
    double *fd;        /* plane offsets: fn . p = fd */
    px_vec3 *fc;       /* face centroid (bounding sphere centre) */
    double *fr;        /* face bounding sphere radius */
    px_vec3 *ec;       /* edge midpoints */
    double *er;        /* half edge lengths */
    px_vec3 center;    /* bounding sphere of the whole polytope */
    double radius;
    double body_radius;  /* max |v| in the body frame (R in the tolerances) */
    uint32_t degenerate; /* faces with no computable plane (collapsed by rounding): skipped */
    unsigned char *fdeg; /* per face: 1 = degenerate */
} or_poly;

/* Builds the oracle view of `c` with body -> common map `T` (NULL: identity).
 * Returns 0 on success (and on failure prints why and returns -1). */
int or_poly_init(or_poly *p, const px_convex *c, const px_pose *T);
/* Same from raw data: vertices (3*nv), faces as CCW vertex lists. Edges are
 * derived from the faces. */
int or_poly_init_raw(or_poly *p, const double *xyz, uint32_t nv, const uint32_t *f_first,
                     const uint32_t *f_vert, uint32_t nf);
void or_poly_free(or_poly *p);

/* Primitives. Each returns the distance and (when not NULL) the closest points. */
double or_pt_seg(px_vec3 p, px_vec3 a, px_vec3 b, px_vec3 *q);
double or_seg_seg(px_vec3 a0, px_vec3 a1, px_vec3 b0, px_vec3 b1, px_vec3 *pa, px_vec3 *pb);
double or_pt_face(px_vec3 p, const or_poly *P, uint32_t f, px_vec3 *q);
/* Segment to face polygon; 0 when the segment crosses or touches it. */
double or_seg_face(px_vec3 a0, px_vec3 a1, const or_poly *P, uint32_t f, px_vec3 *pa, px_vec3 *pq);
double or_face_face(const or_poly *A, uint32_t fa, const or_poly *B, uint32_t fb, px_vec3 *pa, px_vec3 *pb);

/* Distance between feature fa of A and feature fb of B (any of the nine
 * type combinations). Returns -1 for an invalid feature. */
double or_feature_distance(const or_poly *A, px_feature fa, const or_poly *B, px_feature fb);

/* Distance from point p to feature f of P (-1 for an invalid feature). */
double or_point_feature_distance(const or_poly *P, px_feature f, px_vec3 p);

/* max over faces of (n . p - d): <= 0 inside the polytope. */
double or_point_depth(const or_poly *P, px_vec3 p);

typedef struct or_result {
    double distance;   /* 0 when intersecting */
    int intersecting;  /* 1 if the solids share a point */
    double margin;     /* intersecting: how robust the witness is (0 = touching) */
    px_feature fa, fb; /* disjoint: a closest feature pair */
    px_vec3 pa, pb;    /* disjoint: closest points (common frame) */
} or_result;

/* Intersection test only (fills intersecting and margin). */
int or_intersect(const or_poly *A, const or_poly *B, double *margin);
/* Full brute force: intersection test, then min over all feature pairs. */
void or_distance(const or_poly *A, const or_poly *B, or_result *out);

#endif
