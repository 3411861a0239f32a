/// proxima/query.h: proximity queries between two convex polytopes.
///
/// Three queries, one shape: (A, pose_a, B, pose_b, [direction], options,
/// cache, result), each returning a status.
///
/// | question                                   | call           |
/// |--------------------------------------------|----------------|
/// | how far apart, where, how deep?            | `px_distance`  |
/// | do they touch at all?                      | `px_intersect` |
/// | how far can A slide along d before it hits | `px_translate` |
///
/// Conventions for every result:
/// - World frame, unless a name says otherwise.
/// - A is the body that moves: `normal` points from A to B, and translating
///   A by `signed_distance * normal` (px_distance) or by `tau * direction`
///   (px_translate) brings the pair into touching contact.
/// - The contact band: touching counts as intersecting, and two bodies whose
///   distance is at most
///       band = 64 * DBL_EPSILON * (R_A + R_B + |c_A - c_B|)
///   are touching, where c and R are each polytope's centre and radius
///   (`px_convex_bounds`) and |c_A - c_B| the distance of the centres in
///   the world. Every method and query decides the same way outside the
///   band; answers decided inside it carry PX_QUALITY_CONTACT_BAND.
/// - Errors: on a non-OK status the result is zeroed and the cache is left
///   unchanged.
#ifndef PROXIMA_QUERY_H
#define PROXIMA_QUERY_H

#include "proxima/base.h"
#include "proxima/convex.h"
#include "proxima/math.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum px_feature_type {
    PX_FEATURE_NONE = 0,
    PX_FEATURE_VERTEX = 1,
    PX_FEATURE_EDGE = 2,
    PX_FEATURE_FACE = 3
} px_feature_type;

/// A vertex, edge or face of one piece of a body, by index. Convex queries
/// have one piece (`piece` = 0); queries on models made of many convex
/// pieces name the piece too.
typedef struct px_feature {
    uint32_t type; ///< a px_feature_type
    uint32_t index;
    uint32_t piece;
} px_feature;

/// Caller-owned coherence cache for one pair of polytopes (A, B), in that
/// order. Zero-initialise it: zero means "cold" (no previous answer). After
/// a query it holds what the next query of the same pair starts from: the
/// closest feature pair (Lin-Canny), the final simplex as vertex pairs (GJK,
/// translation), or two vertex sets (the hybrid). Entries out of range for
/// the polytopes given (a cache reused for another pair) are ignored and the
/// query runs cold. One cache may serve every method; keep one per query
/// kind for the best warm starts.
typedef struct px_pair_cache {
    px_feature feature_a;
    px_feature feature_b;
    uint32_t vertex_a[4], vertex_b[4];
    uint8_t simplex_count;
    uint8_t count_a, count_b;
    uint8_t unused_u8;
    uint32_t unused_u32;
    /// Last separating or contact direction (B's frame), a warm-start hint.
    double direction[3];
} px_pair_cache;

/// The distance algorithms. All answer the same query with the same result;
/// they differ in speed profile: Lin-Canny is the fastest tracked and on
/// round bodies, GJK and the hybrid need only support queries.
typedef enum px_method {
    /// Closest features by the walk of M. Lin's thesis (1993, ch. 3) in B.
    /// Mirtich's V-Clip formulation (ACM TOG 17(3), 1998). The default.
    PX_METHOD_LIN_CANNY = 0,
    /// GJK (Gilbert, Johnson, Keerthi 1988) enhanced as in S. Cameron (ICRA
    /// 1997): hill-climbing supports and a warm simplex.
    PX_METHOD_GJK = 1,
    /// The Lin-Canny/GJK hybrid of K. Sundaraj, A. d'Aulignac and E. Mazer
    /// (IROS 2000): cached vertex sets on each body, closed-form local
    /// distances, support updates of one body at a time.
    PX_METHOD_HYBRID = 2
} px_method;

/// Query flags (bits of px_query_options.flags).
typedef enum px_query_flags {
    /// px_distance: also compute the penetration depth of intersecting
    /// pairs (EPA), so that `signed_distance` is negative for them.
    PX_QUERY_SIGNED = 1u,
    /// px_translate: the least tau of either sign (where the line enters the
    /// set of touching translations: negative when A overlaps B or B is
    /// behind it), the collision translation of Carpin, Mirolo and Pagello
    /// (ICRA 2006). Without it, only tau >= 0 counts (the time of impact
    /// ahead).
    PX_QUERY_BOTH_WAYS = 2u
} px_query_flags;

/// Options of every query; zero-initialise, zero means default (Lin-Canny,
/// no flags). A query given a flag that is not its own, an unknown method or
/// a non-zero reserved field returns PX_ERR_INVALID_ARGUMENT.
typedef struct px_query_options {
    uint32_t method; ///< a px_method
    uint32_t flags;  ///< px_query_flags bits
    uint32_t reserved[6];
} px_query_options;

/// Why an answer is not exact (bits of px_diagnostics.quality).
typedef enum px_quality {
    /// Exact within a few DBL_EPSILON of the pair's size.
    PX_QUALITY_EXACT = 0,
    /// Reported touching because the distance lies within the contact band
    /// (see the header comment), not because an overlap was proved.
    PX_QUALITY_CONTACT_BAND = 1u,
    /// The penetration depth is exact along the normal given, which EPA
    /// found when its polytope budget (192 vertices) ran out; a smaller depth
    /// along another normal is possible (deep overlaps of finely tessellated
    /// round bodies).
    PX_QUALITY_DEPTH_BUDGET = 2u,
    /// Every method stopped without a proof and the last one's answer was
    /// taken: for distances a safeguard no test has triggered; for
    /// translations, a hit at the ray cast's rounding floor that neither
    /// advancement nor a distance check could confirm, or a miss whose
    /// witness plane could not be made exact (thin bodies, grazing lines).
    PX_QUALITY_UNPROVEN = 4u
} px_quality;

/// The diagnostic tail of every result.
typedef struct px_diagnostics {
    /// Steps of every method that ran: feature-pair changes (Lin-Canny),
    /// support calls (GJK, hybrid, ray cast), EPA expansions, advancement
    /// steps, seeds included.
    uint32_t iterations;
    /// Hand-offs to another method after one that should have concluded did
    /// not: Lin-Canny restarted from GJK after a rounding cycle, GJK finished
    /// by Lin-Canny when its duality gap stays open at the rounding floor,
    /// the hybrid out of rounds, EPA out of budget, a ray cast rerun or
    /// finished by advancement, px_intersect's slow path. Seeding a cold
    /// start and declining a warm fast path are not counted.
    uint32_t fallbacks;
    /// PX_QUALITY_EXACT (0), or px_quality bits saying why not.
    uint32_t quality;
    uint32_t reserved;
} px_diagnostics;

/// Result of `px_distance`.
typedef struct px_distance_result {
    /// Euclidean distance between the two solids; 0 when they intersect.
    double distance;
    /// `distance` for separated pairs; for intersecting pairs minus the
    /// penetration depth with PX_QUERY_SIGNED, else 0. A pair whose
    /// difference A - B is flat (two overlapping coplanar polygons, a point
    /// on a polygon, crossing segments: lower-dimensional pieces, convex.h)
    /// only touches: depth 0, normal 0 (docs/methods.md).
    double signed_distance;
    /// Closest points: |point_a - point_b| == distance. When the solids
    /// intersect both are one common point, except with PX_QUERY_SIGNED,
    /// where they are the deepest points: point_a on A's boundary, point_b
    /// on B's. In every case point_b - point_a == signed_distance * normal
    /// (up to rounding).
    px_vec3 point_a, point_b;
    /// Unit direction from A to B: (point_b - point_a) / distance for
    /// separated pairs; for intersecting pairs with PX_QUERY_SIGNED the
    /// direction along which A leaves B fastest, backwards: translating A by
    /// signed_distance * normal (= -depth * normal) makes the pair touch.
    /// Zero when unknown (touching, or intersecting without PX_QUERY_SIGNED).
    px_vec3 normal;
    /// The closest feature pair (on intersection: a witness pair).
    px_feature feature_a, feature_b;
    /// 1 when the solids share at least one point (touching or overlapping):
    /// solids, so one body inside the other counts.
    int intersecting;
    uint32_t unused;
    px_diagnostics diag;
} px_distance_result;

/// Distance between convex A at `pose_a` and convex B at `pose_b`, by the
/// method in `options` (NULL: Lin-Canny, unsigned). Only the relative
/// transform T_B^-1 T_A is used. `cache` may be NULL (always cold).
/// Statuses: PX_ERR_INVALID_ARGUMENT for NULL polytopes, poses or result,
/// or bad options; PX_ERR_NON_FINITE / PX_ERR_INVALID_POSE for a bad pose,
/// and PX_ERR_NON_FINITE when the two poses are so far apart that the
/// relative transform overflows.
PX_API px_status px_distance(const px_convex *a, const px_pose *pose_a, const px_convex *b,
                             const px_pose *pose_b, const px_query_options *options, px_pair_cache *cache,
                             px_distance_result *result);

/// Result of `px_intersect`.
typedef struct px_intersect_result {
    /// 1 when the solids share at least one point (touching counts).
    int intersecting;
    uint32_t unused;
    px_diagnostics diag;
} px_intersect_result;

/// Boolean intersection test: GJK with an early exit at the first
/// separating axis that clears the contact band, or at a simplex that
/// encloses the origin. A warm cache usually answers in one or two
/// supports. Slow path: when GJK stops at the rounding floor without a proof
/// either way (contact between nearly coplanar facets, within about 1e-9 of
/// the size), the distance query decides, by `options->method`; this
/// counts as a fallback. `options` may be NULL; no flags apply. Statuses as
/// `px_distance`.
PX_API px_status px_intersect(const px_convex *a, const px_pose *pose_a, const px_convex *b,
                              const px_pose *pose_b, const px_query_options *options, px_pair_cache *cache,
                              px_intersect_result *result);

/// Result of `px_translate`.
typedef struct px_translate_result {
    /// 1 when some translation of A along the direction (tau >= 0 unless
    /// PX_QUERY_BOTH_WAYS) makes it touch B.
    int hit;
    /// Without PX_QUERY_BOTH_WAYS: 1 when A already touches or overlaps B at
    /// tau = 0 (within the contact band, as px_distance decides); then
    /// hit = 1, tau = 0, point_a == point_b is a common point and normal is
    /// zero.
    int in_contact;
    /// hit: the least such tau. 0 when no hit.
    double tau;
    /// hit: the contact points at tau, point_a on A translated by
    /// tau * direction (so point_a == point_b up to rounding).
    /// No hit: the points of a plane that separates A + tau * direction from
    /// B for every tau considered (see `normal`): A's highest and B's lowest
    /// vertex along the normal, so the plane's claim holds by construction.
    px_vec3 point_a, point_b;
    /// hit: the unit contact normal at tau, from A to B (normal . direction
    /// > 0 unless the contact is grazing): the plane through point_b with
    /// this normal has A (moved by tau) below it and B above it, to within
    /// the contact band.
    /// No hit: a unit normal with normal . direction <= 0 (= 0 when the line
    /// misses B entirely), normal . x <= normal . point_a for all x in A,
    /// normal . y >= normal . point_b for all y in B, and
    /// gap = normal . (point_b - point_a) > 0: no translation considered
    /// closes that gap.
    px_vec3 normal;
    double gap;
    /// hit: the contact feature pair.
    px_feature feature_a, feature_b;
    px_diagnostics diag;
} px_translate_result;

/// Collision translation: A at `pose_a` moves along the world direction
/// `direction` (any non-zero length; tau is in units of it), B stays at
/// `pose_b`. By default the time of impact ahead (tau >= 0); with
/// PX_QUERY_BOTH_WAYS the least tau of either sign. Computed by a GJK ray
/// cast against the Minkowski difference (G. van den Bergen, "Ray casting
/// against general convex objects", 2004) with exact refinement on the final
/// facet, and by conservative advancement with Lin-Canny from a warm
/// `cache` (may be NULL). PX_ERR_INVALID_ARGUMENT for a zero or NULL
/// direction or bad options, PX_ERR_NON_FINITE for a non-finite direction or
/// when tau itself overflows (a direction so short that the answer exceeds
/// the double range); bad poses as `px_distance`.
PX_API px_status px_translate(const px_convex *a, const px_pose *pose_a, const px_convex *b,
                              const px_pose *pose_b, px_vec3 direction, const px_query_options *options,
                              px_pair_cache *cache, px_translate_result *result);

#ifdef __cplusplus
}
#endif

#endif /* PROXIMA_QUERY_H */
