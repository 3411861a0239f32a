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

/* One distance answer in body frames (pa in A's frame, pb in B's), shared
 * by every method; query.c turns it into a px_distance_result. */
typedef struct pxi_answer {
    double distance; /* 0 when intersecting */
    px_vec3 pa, pb;
    px_feature fa, fb;
    int intersecting;
    uint32_t iterations, fallbacks;
} pxi_answer;

/* Lin-Canny walk (lin_canny.c). `cache` may be NULL; updated on return. */
void pxi_lin_canny(const px_convex *a, const px_convex *b, const px_pose *t_ab, px_distance_cache *cache,
                   pxi_answer *out);

/* Enhanced GJK distance (gjk.c): warm start from the cache's simplex,
 * supports by direction table and hill climbing, van den Bergen's relative
 * and absolute termination. `cache` may be NULL; updated on return. When
 * `simplex_out` is not NULL it receives the final simplex (for EPA). */
typedef struct pxi_simplex_pairs {
    uint32_t ia[4], ib[4];
    int n;
} pxi_simplex_pairs;
void pxi_gjk_distance(const px_convex *a, const px_convex *b, const px_pose *t_ab, px_distance_cache *cache,
                      pxi_answer *out, pxi_simplex_pairs *simplex_out);

/* GJK boolean test with early exit on a separating axis (gjk.c). Returns 1
 * when the solids intersect (touching within rounding counts). */
int pxi_gjk_intersect(const px_convex *a, const px_convex *b, const px_pose *t_ab, px_distance_cache *cache,
                      uint32_t *iterations);

/* The Lin-Canny/GJK hybrid of seed 001 (hybrid.c). `cache` may be NULL;
 * its vertex_a[0..count_a) / vertex_b[0..count_b) sets are read and
 * updated. */
void pxi_hybrid(const px_convex *a, const px_convex *b, const px_pose *t_ab, px_distance_cache *cache,
                pxi_answer *out);

/* Penetration depth of an intersecting pair by EPA (epa.c), started from
 * `start` (a GJK simplex whose hull contains the origin; may be NULL or
 * lower-dimensional). Outputs in B's frame except pa (A's frame): depth >= 0,
 * unit normal n with pa - pb = depth * n (pa mapped into B's frame), i.e.
 * translating B by depth * n makes the pair touch. */
typedef struct pxi_penetration {
    double depth;
    px_vec3 normal; /* B's frame */
    px_vec3 pa, pb; /* A's frame, B's frame */
    px_feature fa, fb;
    uint32_t iterations;
    int fallback; /* 1 when the polytope budget ran out: the depth is then exact along EPA's
                     best normal (a translation query), not necessarily the least over all */
    int flat;     /* 1 when A - B is flat within rounding: no depth (touching within rounding) */
} pxi_penetration;
void pxi_epa(const px_convex *a, const px_convex *b, const px_pose *t_ab, const pxi_simplex_pairs *start,
             pxi_penetration *out);

/* Collision translation (translation.c), direction `dir` in B's frame
 * (not necessarily unit). Output frames: pa in A's frame at its original
 * pose (the caller adds tau * dir), pb and normal in B's frame. */
typedef struct pxi_translation {
    int hit;
    double tau;
    px_vec3 pa, pb, normal;
    double gap;
    px_feature fa, fb;
    uint32_t iterations;
} pxi_translation;
void pxi_translation_query(const px_convex *a, const px_convex *b, const px_pose *t_ab, px_vec3 dir,
                           px_distance_cache *cache, pxi_translation *out);

/* The smallest feature of `c` holding the given vertices (1-4 ids, repeats
 * allowed): the vertex, the edge joining two, or a face holding all.
 * Vertices on no common face (possible only within rounding of coplanar
 * faces): the face around them whose polygon holds the witness point `p`
 * (body frame; NULL: the vertex ids[0]). */
px_feature pxi_feature_of_vertices(const px_convex *c, const uint32_t *ids, int n, const px_vec3 *p);

#endif
