/// proxima: exact, fast proximity queries between rigid convex polytopes.
///
/// Umbrella header: the whole public API. C11, no global state except the
/// allocator hook. Geometry objects (`px_convex`) are immutable after
/// creation and may be shared between threads; everything a query changes
/// lives in small caller-owned caches.
///
/// Frames: every `px_convex` is described in its own local ("body") frame. A
/// `px_pose` maps body coordinates to world coordinates:
/// `p_world = R * p_body + t`. Query results are in the world frame unless a
/// name says otherwise.
#ifndef PROXIMA_PROXIMA_H
#define PROXIMA_PROXIMA_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define PX_VERSION_MAJOR 0
#define PX_VERSION_MINOR 1
#define PX_VERSION_PATCH 0

/* ------------------------------------------------------------------------- */
/* Status and errors                                                         */
/* ------------------------------------------------------------------------- */

/// Every fallible function returns one of these (or NULL plus a `px_error`).
typedef enum px_status {
    PX_OK = 0,
    PX_ERR_INVALID_ARGUMENT = 1, ///< NULL where not allowed, a count out of range
    PX_ERR_NON_FINITE = 2,       ///< NaN or Inf in coordinates, poses or options
    PX_ERR_DEGENERATE = 3,       ///< geometry with no 3-D hull (flat, collinear, one point)
    PX_ERR_INVALID_POSE = 4,     ///< rotation is not orthonormal with det +1 (within 1e-6)
    PX_ERR_OUT_OF_MEMORY = 5,    ///< the allocator returned NULL
    PX_ERR_IO = 6,               ///< a file could not be read or is malformed
    PX_ERR_INTERNAL = 7          ///< an invariant failed: a bug, please report it
} px_status;

/// Filled by functions that can fail. `message` is one human sentence that
/// names the input (file, argument) and what was wrong with it.
typedef struct px_error {
    px_status code;
    char message[256];
} px_error;

/// Short constant name of a status ("PX_ERR_DEGENERATE"); never NULL.
const char *px_status_string(px_status status);

/* ------------------------------------------------------------------------- */
/* Memory                                                                    */
/* ------------------------------------------------------------------------- */

/// One allocation hook pair for all memory proxima objects own. `alloc`
/// returns NULL on failure; `free` receives the size that was requested.
/// Queries never allocate.
typedef struct px_allocator {
    void *(*alloc)(void *user, size_t size);
    void (*free)(void *user, void *ptr, size_t size);
    void *user;
} px_allocator;

/// Installs `allocator` (copied) for all later allocations; NULL restores
/// malloc/free. Not thread-safe: call it before creating any object, and do
/// not free objects created under another allocator after switching.
void px_set_allocator(const px_allocator *allocator);

/* ------------------------------------------------------------------------- */
/* Math types                                                                */
/* ------------------------------------------------------------------------- */

typedef struct px_vec3 {
    double x, y, z;
} px_vec3;

/// Rigid transform body -> world: `p_world = R * p_body + t`, with `r` the
/// rotation matrix in row-major order (r[3*i + j] = R_ij).
typedef struct px_pose {
    double r[9];
    px_vec3 t;
} px_pose;

/// The identity pose.
px_pose px_pose_identity(void);

/// Pose from a row-major 3x3 rotation `r` and a translation `t`. The values
/// are copied unchecked; queries validate them (see `px_pose_check`).
px_pose px_pose_from_rt(const double r[9], const double t[3]);

/// Pose from a unit quaternion (w, x, y, z) and a translation. The quaternion
/// is normalised; a zero or non-finite quaternion gives a pose that
/// `px_pose_check` rejects.
px_pose px_pose_from_quat(const double q[4], const double t[3]);

/// PX_OK when every entry is finite and R is a proper rotation within 1e-6
/// (rows 0 and 1 orthonormal, row 2 = row 0 x row 1); otherwise PX_ERR_NON_FINITE or
/// PX_ERR_INVALID_POSE, with a message when `err` is not NULL.
px_status px_pose_check(const px_pose *pose, px_error *err);

/// World coordinates of a body-frame point.
px_vec3 px_pose_apply(const px_pose *pose, px_vec3 p_body);

/* ------------------------------------------------------------------------- */
/* Convex polytopes                                                          */
/* ------------------------------------------------------------------------- */

/// An immutable convex polytope in its body frame: vertices, edges and
/// polygonal faces (coplanar hull triangles merged) with full adjacency and
/// precomputed Voronoi-region planes. Safe to share across threads.
typedef struct px_convex px_convex;

/// Options for `px_convex_from_points`; zero-initialise, zero means default.
typedef struct px_convex_options {
    /// Resolution of the direction lookup table used for cold starts: the
    /// number of cells per cube face side. 0 = chosen from the vertex count.
    uint32_t lut_resolution;
    uint32_t reserved[7];
} px_convex_options;

/// Builds the convex hull of `count` points (`xyz` holds 3*count doubles,
/// body frame). The hull is computed by CGAL with exact predicates; only
/// extreme points become vertices; exactly coplanar hull triangles are merged
/// into polygonal faces.
///
/// Returns NULL and fills `err` (may be NULL) on:
/// - PX_ERR_INVALID_ARGUMENT: `xyz` NULL, or `count` 0 or above 2^26;
/// - PX_ERR_NON_FINITE: a NaN or infinite coordinate (index in the message);
/// - PX_ERR_DEGENERATE: fewer than 4 distinct points, or all points
///   collinear or coplanar (the message says which): the hull is not a solid;
/// - PX_ERR_OUT_OF_MEMORY.
/// `options` may be NULL.
px_convex *px_convex_from_points(const double *xyz, size_t count, const px_convex_options *options,
                                 px_error *err);

/// Frees a polytope; NULL is a no-op.
void px_convex_destroy(px_convex *convex);

/// Feature counts. Euler: V - E + F = 2.
uint32_t px_convex_vertex_count(const px_convex *convex);
uint32_t px_convex_edge_count(const px_convex *convex);
uint32_t px_convex_face_count(const px_convex *convex);

/// Vertex `i` in the body frame (i < vertex count; else a zero vector).
px_vec3 px_convex_vertex(const px_convex *convex, uint32_t i);

/// The two vertices of edge `e` (tail, head); returns 0 if `e` is out of range.
int px_convex_edge_vertices(const px_convex *convex, uint32_t e, uint32_t out[2]);

/// Number of vertices of face `f` (0 if out of range); its vertices in
/// counter-clockwise order seen from outside are `px_convex_face_vertex(f, k)`.
uint32_t px_convex_face_size(const px_convex *convex, uint32_t f);
uint32_t px_convex_face_vertex(const px_convex *convex, uint32_t f, uint32_t k);

/// Outward unit normal `n` and offset `d` of face `f` (plane n.p = d, body
/// frame); returns 0 if `f` is out of range.
int px_convex_face_plane(const px_convex *convex, uint32_t f, px_vec3 *n, double *d);

/// Bytes owned by the polytope (all arrays, planes and lookup table).
size_t px_convex_memory_bytes(const px_convex *convex);

/// Checks every structural invariant: Euler's formula, consistent
/// half-edge adjacency, outward unit normals, convexity (every vertex on or
/// below every face plane within a relative 1e-9), planar faces. PX_OK or
/// PX_ERR_INTERNAL with the first violation in `err`.
px_status px_convex_validate(const px_convex *convex, px_error *err);

/* ------------------------------------------------------------------------- */
/* Distance queries                                                          */
/* ------------------------------------------------------------------------- */

typedef enum px_feature_type {
    PX_FEATURE_NONE = 0,
    PX_FEATURE_VERTEX = 1,
    PX_FEATURE_EDGE = 2,
    PX_FEATURE_FACE = 3
} px_feature_type;

/// A vertex, edge or face of one polytope, by index.
typedef struct px_feature {
    uint32_t type; ///< a px_feature_type
    uint32_t index;
} px_feature;

/// Caller-owned coherence cache for one pair of polytopes (A, B), in that
/// order. Zero-initialise it: zero means "cold" (no previous answer). After a
/// query it holds what the next query of the same pair starts from: the
/// closest feature pair (Lin-Canny), the final simplex as vertex pairs
/// (GJK, translation), or the two cached vertex sets (hybrid). Entries out of
/// range for the polytopes given (a cache reused for another pair) are
/// ignored and the query runs cold. One cache may serve every method, but a
/// cache shared between distance and translation queries of the same pair
/// warm-starts each from the other's answer, which is slower than keeping
/// one cache per query kind.
typedef struct px_distance_cache {
    px_feature feature_a;
    px_feature feature_b;
    /// GJK / translation: simplex vertex pairs (vertex_a[k], vertex_b[k]),
    /// k < simplex_count. Hybrid: vertex_a[0 .. count_a) and
    /// vertex_b[0 .. count_b) are the cached vertex sets of A and B.
    uint32_t vertex_a[4], vertex_b[4];
    uint8_t simplex_count;
    uint8_t count_a, count_b;
    uint8_t reserved_u8;
    /// Last separating or contact direction (B's frame), a warm-start hint.
    double direction[3];
} px_distance_cache;

/// The distance algorithms. All answer the same query with the same result
/// struct; they differ in speed profile (see docs/methods.md).
typedef enum px_method {
    /// Lin-Canny closest features in the V-Clip formulation (default).
    PX_METHOD_LIN_CANNY = 0,
    /// Enhanced GJK (Cameron 1997): hill-climbing supports, warm simplex.
    PX_METHOD_GJK = 1,
    /// The Lin-Canny/GJK hybrid of seed 001: cached vertex sets on each
    /// body, closed-form local distances, one-body support updates.
    PX_METHOD_HYBRID = 2
} px_method;

/// Query flags.
enum {
    /// Also compute the penetration depth of intersecting pairs (EPA), so
    /// that `signed_distance` is negative for them.
    PX_QUERY_SIGNED = 1u
};

/// Options of `px_distance_ex`; zero-initialise, zero means default
/// (Lin-Canny, unsigned).
typedef struct px_query_options {
    uint32_t method; ///< a px_method
    uint32_t flags;  ///< PX_QUERY_* bits
    uint32_t reserved[6];
} px_query_options;

/// Result of `px_distance` and `px_distance_ex`.
typedef struct px_distance_result {
    /// Euclidean distance between the two solids; 0 when they intersect.
    double distance;
    /// `distance` for separated pairs; for intersecting pairs minus the
    /// penetration depth when PX_QUERY_SIGNED was asked, else 0.
    double signed_distance;
    /// Closest points, world frame: |point_a - point_b| == distance. When the
    /// solids intersect both are one common point of A and B, except with
    /// PX_QUERY_SIGNED, where they are the deepest points: point_a on A's
    /// boundary, point_b on B's. In every case
    /// point_b - point_a == signed_distance * normal (up to rounding).
    px_vec3 point_a, point_b;
    /// Unit direction, world frame, in which B moves away from A: for
    /// separated pairs (point_b - point_a) / distance; with PX_QUERY_SIGNED
    /// and intersecting pairs, translating B by depth * normal (depth =
    /// -signed_distance) makes the pair touch. Zero when unknown (touching,
    /// or intersecting without PX_QUERY_SIGNED).
    px_vec3 normal;
    /// The closest feature pair (on intersection: a witness pair).
    px_feature feature_a, feature_b;
    /// 1 when the solids share at least one point (touching or overlapping):
    /// solids, so one body inside the other counts.
    int intersecting;
    /// Method steps: feature-pair changes (Lin-Canny), support calls (GJK,
    /// hybrid), plus EPA expansions when signed.
    uint32_t iterations;
    /// Number of times a safeguard (cycle detector or step cap) had to
    /// restart from a slower exhaustive method. Expected 0.
    uint32_t fallbacks;
} px_distance_result;

/// Distance between convex A at `pose_a` and convex B at `pose_b` by the
/// Lin-Canny closest-feature walk (in the V-Clip formulation; see
/// docs/lin-canny.md). Only the relative transform T_AB = T_B^-1 T_A is
/// used. `cache` may be NULL (always cold). On error the result is zeroed,
/// the cache is left unchanged, and the status is returned
/// (PX_ERR_INVALID_ARGUMENT for NULL polytopes, poses or result;
/// PX_ERR_NON_FINITE / PX_ERR_INVALID_POSE for a bad pose, and
/// PX_ERR_NON_FINITE when the two poses are so far apart that T_AB
/// overflows).
px_status px_distance(const px_convex *a, const px_pose *pose_a, const px_convex *b, const px_pose *pose_b,
                      px_distance_cache *cache, px_distance_result *result);

/// Distance by the method and flags in `options` (NULL: Lin-Canny,
/// unsigned; same as `px_distance`). PX_ERR_INVALID_ARGUMENT for an unknown
/// method or flag; otherwise as `px_distance`.
px_status px_distance_ex(const px_convex *a, const px_pose *pose_a, const px_convex *b, const px_pose *pose_b,
                         const px_query_options *options, px_distance_cache *cache,
                         px_distance_result *result);

/// Boolean intersection test by GJK with early exit on the first separating
/// axis found (touching counts as intersecting, within rounding). `cache`
/// may be NULL; a warm cache usually answers in one or two supports.
px_status px_intersect(const px_convex *a, const px_pose *pose_a, const px_convex *b, const px_pose *pose_b,
                       px_distance_cache *cache, int *intersecting);

/* ------------------------------------------------------------------------- */
/* Collision translation                                                     */
/* ------------------------------------------------------------------------- */

/// Result of `px_translation`.
typedef struct px_translation_result {
    /// 1 when some translation of A along the direction makes it touch B.
    int hit;
    /// hit: the least tau (negative allowed) such that A translated by
    /// tau * direction touches B. 0 when no hit.
    double tau;
    /// hit: the contact points at tau, world frame, point_a on A translated
    /// by tau * direction (so point_a == point_b up to rounding).
    /// No hit: the closest points of A and B measured perpendicular to the
    /// direction; they witness separation for every tau (see `normal`).
    px_vec3 point_a, point_b;
    /// hit: the unit contact normal at tau, pointing from A to B
    /// (normal . direction > 0 unless the contact is grazing).
    /// No hit: a unit normal perpendicular to the direction with
    /// normal . x <= normal . point_a for all x in A and
    /// normal . y >= normal . point_b for all y in B, and
    /// normal . (point_b - point_a) = gap > 0: no translation along the
    /// direction closes that gap.
    px_vec3 normal;
    double gap;
    /// hit: the contact feature pair (vertex, edge or face of each body).
    px_feature feature_a, feature_b;
    uint32_t iterations;
} px_translation_result;

/// Collision translation (seed 002): A at `pose_a` moves along the world
/// direction `direction` (any non-zero length; tau is in units of it), B
/// stays at `pose_b`. Computed by a GJK ray cast against the Minkowski
/// difference (van den Bergen 2004) with exact refinement on the final
/// facet; `cache` (may be NULL) warm-starts it from the previous answer of
/// the same pair. PX_ERR_INVALID_ARGUMENT for a zero or NULL direction,
/// PX_ERR_NON_FINITE for a non-finite one, or when tau itself overflows (a
/// direction so short that the answer exceeds the double range); bad poses
/// as `px_distance`.
px_status px_translation(const px_convex *a, const px_pose *pose_a, const px_convex *b, const px_pose *pose_b,
                         px_vec3 direction, px_distance_cache *cache, px_translation_result *result);

#ifdef __cplusplus
}
#endif

/* File loading (Assimp): px_convex_from_file, px_mesh_points_from_file. */
#include "proxima/io.h"

#endif /* PROXIMA_PROXIMA_H */
