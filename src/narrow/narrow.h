/* Narrow phase on convex pairs (internal): the methods and what they return.
 *
 * Layout (an arrow only points down; tests/check_layers.sh checks it):
 *   primitives   tolerance.h, simplex.c, closest.c, feature.c
 *   methods      lin_canny.c, gjk.c, hybrid.c, epa.c, raycast.c
 *   derived      advance.c (conservative advancement, on Lin-Canny)
 *   policy       query.c: the public entry points and the fallback table,
 *                the only file that calls more than one method.
 *
 * Every method runs alone, on A in its body frame mapped into B's by T_AB,
 * and reports an outcome with its best answer; it never calls another
 * method. What happens after an unproven answer is query.c's decision.
 */
#ifndef PXI_NARROW_H
#define PXI_NARROW_H

#include <stdint.h>

#include "convex/convex.h"
#include "proxima/query.h"

/* How a method ended. */
typedef enum pxi_outcome {
    PXI_DONE = 0,        /* proved, within the bands of tolerance.h */
    PXI_UNPROVEN = 1,    /* stopped without a proof (a rounding floor, a cycle) */
    PXI_OUT_OF_STEPS = 2 /* its step budget ran out */
} pxi_outcome;

/* One distance answer in body frames (pa in A's frame, pb in B's), shared
 * by every distance method; query.c turns it into a public result. */
typedef struct pxi_answer {
    double distance; /* 0 when intersecting */
    px_vec3 pa, pb;
    px_feature fa, fb;
    int intersecting;
    uint32_t iterations;
    pxi_outcome outcome;
    double gap;       /* PXI_UNPROVEN (GJK): the true distance is at least distance - gap */
    uint32_t quality; /* px_quality bits (0: exact) */
} pxi_answer;

/* ---- Lin-Canny (lin_canny.c). ---- */

/* Where a walk starts. A zero start is cold: the vertices extreme along the
 * line of centres. */
typedef struct pxi_lc_start {
    px_feature fa, fb; /* start pair (type PX_FEATURE_NONE: cold) */
    uint32_t budget;   /* steps of the first walk when it starts cold; 0 = the safeguard cap */
    int tie;           /* 1: in tie-breaking mode from the start */
} pxi_lc_start;

/* The closest-feature walk from `start`. A walk that revisits a pair (a
 * rounding cycle) continues in tie-breaking mode. Outcomes: PXI_DONE;
 * PXI_OUT_OF_STEPS when a first walk with a budget below the cap ran out (a
 * cold start that needs a seed); PXI_UNPROVEN when it still cycles. fa, fb
 * always hold the last pair. */
void pxi_lin_canny(const px_convex *a, const px_convex *b, const px_pose *t_ab, const pxi_lc_start *start,
                   pxi_answer *out);

/* px_distance with default options for poses that passed px_pose_check
 * already (a scene checks each pose once, when it is set, instead of at
 * every query). */
px_status pxi_distance_checked(const px_convex *a, const px_pose *pose_a, const px_convex *b,
                               const px_pose *pose_b, px_pair_cache *cache, px_distance_result *result);

/* Steps of the cold line-of-centres walk before a seed is asked for, and
 * whether the pair is round enough for that start (thin bodies go straight
 * to a GJK seed: from the line of centres a 1:8:40 ellipsoid takes tens of
 * steps). */
#define PXI_LC_COLD_BUDGET 12
/* Bodies with px_convex.roundness below this (a width ratio over 13
 * directions) do not start from the line of centres. */
#define PXI_LC_COLD_ROUND 0.5
static inline int pxi_lc_line_of_centres_ok(const px_convex *a, const px_convex *b) {
    return a->roundness >= PXI_LC_COLD_ROUND && b->roundness >= PXI_LC_COLD_ROUND;
}

/* ---- GJK (gjk.c). ---- */

/* A simplex of A - B as vertex pairs (for EPA's start). */
typedef struct pxi_simplex_pairs {
    uint32_t ia[4], ib[4];
    int n;
} pxi_simplex_pairs;

/* Cold GJK to a relative tolerance, used as a seed: closest points, the
 * vertices carrying the largest weight, and when the origin is enclosed by
 * a tetrahedron its margin to the tetrahedron's faces (0 if unknown).
 * Frames: pa in A's, pb in B's. */
typedef struct pxi_gjk_seed {
    double distance;
    px_vec3 pa, pb;
    uint32_t va, vb;
    int intersecting;
    double inside_margin;
    uint32_t iterations;
} pxi_gjk_seed;
void pxi_gjk_seed_run(const px_convex *a, const px_convex *b, const px_pose *t_ab, double rel_tol,
                      uint32_t max_iterations, pxi_gjk_seed *out);

/* Enhanced GJK distance: warm start from the cache's simplex, supports by
 * direction table and hill climbing, van den Bergen's relative and absolute
 * termination, a direct polish of the final features. PXI_UNPROVEN (with
 * gap) when it stopped on a repeat or the rounding floor with the duality
 * gap open. `cache` (may be NULL) receives the simplex, direction and
 * features; `simplex_out` (may be NULL) the final simplex. */
void pxi_gjk_distance(const px_convex *a, const px_convex *b, const px_pose *t_ab, px_pair_cache *cache,
                      pxi_answer *out, pxi_simplex_pairs *simplex_out);

/* Boolean GJK with early exit on a separating axis. PXI_DONE with
 * *intersecting set when proved either way, else PXI_UNPROVEN. */
pxi_outcome pxi_gjk_intersect(const px_convex *a, const px_convex *b, const px_pose *t_ab,
                              px_pair_cache *cache, int *intersecting, uint32_t *iterations,
                              uint32_t *quality);

/* ---- The Lin-Canny/GJK hybrid of seed 001 (hybrid.c). ---- */

/* PXI_DONE, or PXI_OUT_OF_STEPS when its rounds ran out (a safeguard).
 * `cache` (may be NULL): its vertex sets are read and updated. */
void pxi_hybrid(const px_convex *a, const px_convex *b, const px_pose *t_ab, px_pair_cache *cache,
                pxi_answer *out);

/* ---- Penetration depth by EPA (epa.c). ---- */

/* Outputs in B's frame except pa (A's frame): depth >= 0, unit normal n with
 * pa - pb = depth * n (pa mapped into B's frame), so translating B by
 * depth * n makes the pair touch. */
typedef struct pxi_penetration {
    double depth;
    px_vec3 normal; /* B's frame */
    px_vec3 pa, pb; /* A's frame, B's frame */
    px_feature fa, fb;
    uint32_t iterations;
    pxi_outcome outcome; /* PXI_OUT_OF_STEPS: budget ran out; normal is the best one seen and depth is
                            its support bound; PXI_UNPROVEN: a degenerate cone, the last good face */
    int flat;            /* 1 when A - B is flat within rounding: no depth (touching within rounding) */
} pxi_penetration;

/* EPA from `start`, a GJK simplex whose hull holds the origin (4 points;
 * fewer are grown to a tetrahedron). */
void pxi_epa(const px_convex *a, const px_convex *b, const px_pose *t_ab, const pxi_simplex_pairs *start,
             pxi_penetration *out);

/* ---- Collision translation: ray cast (raycast.c), advancement (advance.c). ---- */

/* Direction `dir` in B's frame (not necessarily unit). Frames: pa in A's
 * frame at its original pose (the caller adds tau * dir), pb and normal in
 * B's frame. */
typedef struct pxi_translation {
    int hit;
    double tau;
    px_vec3 pa, pb, normal;
    double gap;
    px_feature fa, fb;
    uint32_t iterations;
    uint32_t quality; /* px_quality bits */
} pxi_translation;

/* What the ray cast leaves for the caller when it stopped at the rounding
 * floor (PXI_UNPROVEN): a proved lower bound on tau, the plane normal there
 * (from A to B) and the features of its simplex. */
typedef struct pxi_ray_bound {
    double tau;
    px_vec3 normal;
    px_feature fa, fb;
    pxi_simplex_pairs simplex; /* at most 3 pairs: what a warm cache keeps */
} pxi_ray_bound;

/* The GJK ray cast against B - A (van den Bergen 2004). `cache` (may be
 * NULL) warm-starts it and receives its final simplex and normal.
 * PXI_DONE: a certain hit or a miss, in out. PXI_UNPROVEN: a hit at the
 * rounding floor: out holds the hit refined from the final simplex, *bound
 * the lower bound to finish from. PXI_OUT_OF_STEPS: a warm run that did not
 * converge cleanly (a stale hint): out is not set, the caller reruns cold. */
pxi_outcome pxi_raycast(const px_convex *a, const px_convex *b, const px_pose *t_ab, px_vec3 dir,
                        px_pair_cache *cache, pxi_translation *out, pxi_ray_bound *bound);

/* The closest approach of the line {tau dir} to B - A, measured
 * perpendicular to dir (a GJK on the projection along dir): out->gap is
 * the gap no translation along dir closes, with its witness plane (hit 0). */
void pxi_ray_miss(const px_convex *a, const px_convex *b, const px_pose *t_ab, px_vec3 dir,
                  pxi_translation *out);

/* Conservative advancement with Lin-Canny from tau, a proved lower bound
 * (A + tau d does not overlap B); n is the normal to report if the first
 * query already touches, (fa, fb) the features the walks start from.
 * PXI_DONE with the hit in out, or PXI_UNPROVEN when it cannot conclude (a
 * normal turning away from the motion, slow convergence on a curved part of
 * B - A). */
pxi_outcome pxi_advance(const px_convex *a, const px_convex *b, const px_pose *t_ab, px_vec3 d, double tau,
                        px_vec3 n, px_feature fa, px_feature fb, pxi_translation *out);

/* The warm start of a tracked translation: a lower bound from the cached
 * contact normal, then pxi_advance; updates the cache on PXI_DONE. */
pxi_outcome pxi_advance_warm(const px_convex *a, const px_convex *b, const px_pose *t_ab, px_vec3 d,
                             px_pair_cache *cache, pxi_translation *out);

/* ---- Policy (query.c). ---- */

/* How query.c may finish an unproven answer. */
typedef struct pxi_policy {
    uint32_t method;  /* px_method */
    int signed_depth; /* also the penetration depth (EPA) of intersecting pairs */
    int accept_bound; /* stop at the first unproven answer and flag it approximate */
} pxi_policy;

/* The distance of a pair under a policy (T_AB already checked). */
void pxi_distance_pair(const px_convex *a, const px_convex *b, const px_pose *t_ab, const pxi_policy *policy,
                       px_pair_cache *cache, pxi_answer *out, pxi_penetration *pen, uint32_t *fallbacks);

/* The collision translation of a pair (dir in B's frame, scaled to max-norm
 * in [1, 2)). */
void pxi_translation_query(const px_convex *a, const px_convex *b, const px_pose *t_ab, px_vec3 dir,
                           px_pair_cache *cache, pxi_translation *out, uint32_t *fallbacks);

#endif
