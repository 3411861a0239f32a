/// proxima/scene.h: many moving bodies, pairs scheduled by distance and
/// velocity (seed 000 §3.6; I-COLLIDE, Cohen, Lin, Manocha, Ponamgi, I3D
/// 1995).
///
/// A scene holds bodies (a model or a convex polytope, a pose, and bounds
/// on how fast it may move). Each step the caller sets the poses that
/// changed and the time; the scene finds every pair of bodies closer than
/// the report distance, with exact distances and witness points, and says
/// which pairs are in contact (closer than the margin) and which contacts
/// began or ended.
///
/// How only close pairs are checked:
/// - Broad phase: sweep-and-prune over boxes (axis-aligned in a fixed,
///   generic frame), kept sorted by insertion sort (coherence). Each box is fattened by the report
///   distance and by some slack, so a box is moved only when its body
///   leaves the fat box, and a pair whose boxes are apart is farther than
///   the report distance.
/// - Scheduler: a priority queue of the pairs whose boxes overlap, keyed by
///   the earliest time the pair could come within the report distance,
///   from its last distance and the two bodies' motion bounds. A pair is
///   measured only when it is due; a far pair costs nothing until then.
/// - Safety: the scene also measures how far each body actually moved (the
///   largest displacement of any of its points between poses). A body that
///   moved more than its bounds allow makes all its pairs due at once, and
///   a pair is never skipped while the actual motion could have closed its
///   gap. The guarantee is therefore independent of the declared bounds
///   (they decide only how often pairs are checked): at every step, every
///   pair closer than the report distance is reported. Poses whose matrix
///   is a little off a rotation (px_pose_check allows 1e-6) are allowed
///   for: the scene's bounds give way by the skew times the bodies' reach
///   (docs/scene.md, "The guarantee").
///
/// Distances are those of px_distance (convex bodies) and
/// px_model_distance (models): exact for exact leaves, a lower bound with a
/// certified upper bound for coarse leaves (the pair is reported and in
/// contact by its lower bound, so nothing is missed). Bodies are solids:
/// polytopes, convex pieces and the closed parts of triangle models; a body
/// inside another's closed part is at distance 0 (`contained`).
///
/// Determinism: bodies are numbered in order of creation (a removed body's
/// id is reused, smallest first); pairs are ordered by (body_a, body_b)
/// with body_a < body_b; the queue breaks ties by that order. The same
/// calls give the same reports in the same order on every run.
///
/// Memory grows with the bodies and the pairs whose boxes overlap, never
/// with all pairs; once warm, a step allocates only when that set grows
/// beyond what it held before, or when a model pair that came close again
/// rebuilds the node-pair cache it gave back while far. Not thread-safe: one scene per thread. The
/// models and polytopes bodies point to are shared, read only, and must
/// outlive the bodies.
#ifndef PROXIMA_SCENE_H
#define PROXIMA_SCENE_H

#include "proxima/base.h"
#include "proxima/convex.h"
#include "proxima/math.h"
#include "proxima/model.h"
#include "proxima/query.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct px_scene px_scene;

/// Options of a scene; zero-initialise, zero means default.
typedef struct px_scene_options {
    /// Allocator for everything the scene owns (NULL: malloc/free).
    const px_allocator *allocator;
    /// Contact margin (>= 0, finite, world units): a pair whose distance is
    /// at most this is in contact. 0: touching or intersecting only.
    double margin;
    /// Report distance (>= margin, finite; 0: the margin): every pair whose
    /// distance is at most this is reported each step with its distance and
    /// witness points. Larger values report more pairs and check them more
    /// often.
    double report_distance;
    /// Node-pair cache budget per model pair in bytes (0: 256 KiB), see
    /// px_model_cache.max_bytes.
    size_t model_cache_bytes;
    /// Threads a step may use to bring its due pairs up to date, the
    /// calling one included (0 or 1: the calling thread only; at most 64).
    /// The others are started by px_scene_create and wait between steps;
    /// they call the allocator (model pairs' caches), which must then be
    /// thread-safe. Reports, events and errors are the same for any number.
    /// Helpers run in the floating-point environment of the thread that
    /// created the scene; like the whole library, they expect
    /// round-to-nearest.
    uint32_t threads;
    uint32_t reserved[7]; ///< must be zero
} px_scene_options;

/// A new empty scene, or NULL with PX_ERR_INVALID_ARGUMENT (bad options) or
/// PX_ERR_OUT_OF_MEMORY in `err` (may be NULL).
PX_API px_scene *px_scene_create(const px_scene_options *options, px_error *err);

/// Frees the scene and everything it owns (not the models or polytopes
/// its bodies point to); NULL is a no-op.
PX_API void px_scene_destroy(px_scene *scene);

/// Body flags (px_body_desc.flags).
typedef enum px_body_flags {
    /// The body never moves: px_scene_set_pose refuses it. A pair of two
    /// static bodies is measured once, when it first overlaps, and reported
    /// at every step from then on without being measured again.
    PX_BODY_STATIC = 1u
} px_body_flags;

/// A body. Exactly one of `model` and `convex` is set.
///
/// Motion bounds, in world units per unit of the scene's time (the time
/// passed to px_scene_step): the point `center` (body frame) moves at most
/// `max_speed`, and the body turns at most `max_angular_speed` radians
/// about it. Optional acceleration bounds (0: none) `max_accel` and
/// `max_angular_accel` tighten the schedule of pairs whose current speed is
/// known (px_scene_set_velocity). INFINITY is allowed for the speeds (the
/// body's pairs are checked at every step); a moving body with both speeds
/// 0 never moves: setting a pose that moves it counts as breaking its
/// bounds (handled safely, see the header comment).
///
/// Filters: bodies i and j are paired only when
/// (group_i & mask_j) != 0 and (group_j & mask_i) != 0, and the pair was
/// not excluded (px_scene_exclude_pair). Each of group and mask taken as
/// 0 means "all" (0xFFFFFFFF), so a mask of 0 cannot say "pair with
/// nothing": give such a body a group no mask has, or exclude its pairs.
typedef struct px_body_desc {
    const px_model *model;
    const px_convex *convex;
    px_pose pose;   ///< initial pose (body -> world)
    px_vec3 center; ///< body frame; PX_ERR_NON_FINITE if not finite, PX_ERR_RANGE beyond 2^250
    double max_speed;
    double max_angular_speed;
    double max_accel;
    double max_angular_accel;
    uint32_t group, mask;
    uint32_t flags;       ///< px_body_flags
    uint32_t reserved[3]; ///< must be zero
    void *user;           ///< returned by px_scene_body_user
} px_body_desc;

/// Adds a body; returns PX_OK and its id in *id (the smallest id free).
/// PX_ERR_INVALID_ARGUMENT for NULL arguments, no shape or two, negative
/// or NaN bounds, bad flags; the pose as px_pose_check; PX_ERR_RANGE for a
/// pose beyond 2^250. The body takes part from the next step on.
PX_API px_status px_scene_add_body(px_scene *scene, const px_body_desc *desc, uint32_t *id, px_error *err);

/// Removes a body; its contacts end (reported by the next step as ended
/// events), its pairs are freed and its exclusions forgotten: a body added
/// later under the same id is paired with every other (a contact then
/// begins anew). PX_ERR_INVALID_ARGUMENT for an unknown id;
/// PX_ERR_OUT_OF_MEMORY (nothing changes) when there is no room for the
/// ended events, never for a body without pairs (one added since the last
/// step).
PX_API px_status px_scene_remove_body(px_scene *scene, uint32_t id, px_error *err);

/// The body's user pointer (NULL for an unknown id).
PX_API void *px_scene_body_user(const px_scene *scene, uint32_t id);

/// Never pair bodies a and b (adjacent links of an arm, parts fixed to
/// each other); a current pair of them is dropped (a contact ends silently).
/// PX_ERR_INVALID_ARGUMENT for unknown ids or a == b.
PX_API px_status px_scene_exclude_pair(px_scene *scene, uint32_t a, uint32_t b, px_error *err);

/// Sets a body's pose for the next step. PX_ERR_INVALID_ARGUMENT for an
/// unknown or static body; the pose as px_pose_check; PX_ERR_RANGE beyond
/// 2^250. The pose may break the body's motion bounds (a teleport): the
/// next step measures it and checks the body's pairs at once.
PX_API px_status px_scene_set_pose(px_scene *scene, uint32_t id, const px_pose *pose, px_error *err);

/// Optionally, the body's current linear velocity of `center` and angular
/// speed (world units and radians per unit time), used with the
/// acceleration bounds: a pair's gap then closes at most as fast as
/// |v| + a t (never faster than the speed bounds allow). Values that break
/// the speed bounds are refused (PX_ERR_INVALID_ARGUMENT), as is a static
/// body (which px_scene_set_pose refuses too). The velocity is
/// forgotten at the next pose set without one.
PX_API px_status px_scene_set_velocity(px_scene *scene, uint32_t id, px_vec3 velocity, double angular_speed,
                                       px_error *err);

/// One reported pair, in the world frame.
typedef struct px_scene_pair {
    uint32_t body_a, body_b; ///< body_a < body_b
    /// The pair's distance (px_distance / px_model_distance between a and
    /// b), and for coarse model leaves its certified upper bound (equal to
    /// distance otherwise).
    double distance, upper_bound;
    /// Witness points on a and on b. Intersecting bodies (distance 0): a
    /// point common to both, twice (for polytopes whose inner balls
    /// overlap, answered without a query, a point inside both).
    px_vec3 point_a, point_b;
    /// Leaves of each body realising the distance (0 for a convex body).
    uint32_t leaf_a, leaf_b;
    /// 1 when distance <= margin.
    uint32_t contact;
    /// Nonzero when one body lies inside a closed part of the other
    /// without touching its surface: bit 0 (1) when a piece of body_a lies
    /// inside body_b, bit 1 (2) when a piece of body_b lies inside body_a
    /// (both, for bodies of several pieces); bit 2 (4) with bit 0 when
    /// every piece of body_a lies inside body_b (all of it), bit 3 (8)
    /// with bit 1 when all of body_b lies inside body_a. Distance (and
    /// upper_bound) is then 0, as between solids, and the witness points
    /// are the closest points of the two surfaces.
    uint32_t contained;
} px_scene_pair;

/// A contact that began (distance came within the margin) or ended (the
/// pair moved beyond it, or a body was removed).
typedef struct px_scene_event {
    uint32_t body_a, body_b;
    uint32_t began; ///< 1: began, 0: ended
    uint32_t reserved;
} px_scene_event;

/// Statistics of the last step.
typedef struct px_scene_stats {
    uint32_t bodies; ///< bodies in the scene
    uint32_t moved;  ///< bodies whose pose or velocity was set since the step before (or whose velocity chain
                     ///< lapsed)
    uint32_t box_updates;     ///< bodies that left their fat box and were moved in the sweep
    uint32_t violations;      ///< bodies that moved more than their bounds allow
    uint64_t candidate_pairs; ///< pairs whose fat boxes overlap (queued)
    uint64_t pairs_due;       ///< pairs whose time came in this step (the close ones included)
    uint64_t pairs_checked;   ///< of those, pairs measured by a narrow-phase query (not those
                              ///< whose polytopes' inner balls overlap: intersecting, no query)
    uint64_t swaps;           ///< sweep-and-prune swaps in this step
    size_t memory_bytes;      ///< everything the scene owns now
} px_scene_stats;

/// Advances to `time` (>= the last step's time; the first step may use any
/// finite time): measures each moved body, updates the broad phase, and
/// checks every pair that is due. Afterwards px_scene_pairs and
/// px_scene_events hold this step's results. PX_ERR_OUT_OF_MEMORY leaves
/// the scene consistent: the next step sorts the broad phase anew and
/// finds every pair the failure could have lost. PX_ERR_INVALID_ARGUMENT for a
/// time that goes back or is not finite (the step is refused before it
/// starts: nothing changes, and the last step's results stay readable); a
/// query error (PX_ERR_RANGE for
/// bodies placed more than 2^250 apart) stops the step with the pair named
/// in `err`, and the next step checks again.
PX_API px_status px_scene_step(px_scene *scene, double time, px_error *err);

/// Every pair whose distance is at most the report distance, as measured
/// in the last step, in (body_a, body_b) order. The array stays valid
/// until the next call that changes the scene.
PX_API const px_scene_pair *px_scene_pairs(const px_scene *scene, size_t *count);

/// Contacts that began or ended in the last step, in (body_a, body_b)
/// order.
PX_API const px_scene_event *px_scene_events(const px_scene *scene, size_t *count);

/// Statistics of the last step.
PX_API px_status px_scene_get_stats(const px_scene *scene, px_scene_stats *out);

/// The smallest distance over all pairs of the scene (filters applied) at
/// the last step's poses (poses set since are not looked at; bodies
/// removed or added since are left out), with its pair, or PX_OK with body_a = body_b =
/// UINT32_MAX and distance INFINITY when no two bodies can be paired.
/// Exact: when no pair is within the report distance, the bodies' boxes
/// order the search and each pair is measured only if its boxes are closer
/// than the best distance found. Errors: PX_ERR_INVALID_ARGUMENT for NULL
/// arguments and before the scene's first step (there are no poses to
/// measure yet); a query's error, with the pair in `err` (PX_ERR_RANGE for
/// bodies placed more than 2^250 apart, as px_scene_step).
PX_API px_status px_scene_min_distance(px_scene *scene, px_scene_pair *out, px_error *err);

#ifdef __cplusplus
}
#endif

#endif /* PROXIMA_SCENE_H */
