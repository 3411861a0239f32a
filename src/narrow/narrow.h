/* Narrow phase on convex pairs (internal). */
#ifndef PXI_NARROW_H
#define PXI_NARROW_H

#include <stdint.h>

#include "convex/convex.h"

/* Result of the seeding / fallback GJK (frames: A's body frame for pa, B's
 * for pb; relative pose T_AB maps A's frame into B's). */
typedef struct pxi_gjk_result {
    double distance; /* |pa - pb| measured in B's frame; 0 when intersecting */
    px_vec3 pa, pb;  /* closest points, pa in A's frame, pb in B's frame */
    uint32_t va, vb; /* vertices of A and B carrying the largest weight */
    int intersecting;
    double inside_margin; /* intersecting: distance of the origin to the simplex boundary (0 if unknown) */
    uint32_t iterations;
} pxi_gjk_result;

/* GJK (Gilbert, Johnson, Keerthi 1988) with van den Bergen's termination,
 * on A (frame A) and B (frame B) with T_AB = A -> B. `rel_tol` is the relative
 * duality-gap tolerance: the loop stops when |v|^2 - v.w <= rel_tol^2 |v|^2.
 * Terminates on every input (iteration cap, NaN-safe conditions). */
void pxi_gjk(const px_convex *a, const px_convex *b, const px_pose *t_ab, double rel_tol,
             uint32_t max_iterations, pxi_gjk_result *out);

/* Segment-segment closest points: parameters s on [p0,p1] and t on [q0,q1]
 * (both in [0,1]). Parallel segments get the middle of their overlap. */
void pxi_segment_closest(px_vec3 p0, px_vec3 p1, px_vec3 q0, px_vec3 q1, double *s, double *t);

#endif
