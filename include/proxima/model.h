/// proxima/model.h: non-convex models as sub-part hierarchy trees.
///
/// A `px_model` is a union of convex pieces (its leaves) arranged in a
/// binary tree whose inner nodes bound their subtree: the sub-part hierarchy
/// of M. Lin's thesis ("Efficient collision detection for animation and
/// robotics", Berkeley 1993, ch. 4). Leaves are of two kinds:
/// - exact: the mesh's own triangles (`PX_PIECES_TRIANGLES`), or convex
///   pieces given as point sets (`px_model_create_from_points`); distances
///   between such models are the exact distances of the geometry;
/// - coarse: one convex hull per part (`PX_PIECES_PARTS`). Each coarse leaf
///   carries a certified bound `h` on how far its hull reaches outside the
///   part it stands for, and distance results bracket the true distance of
///   the original meshes: [distance, distance + h_a + h_b].
///
/// Inner nodes hold the convex hull of their subtree (a `px_convex`, tracked
/// by Lin-Canny with a per-node-pair cache) and a bounding sphere. In
/// triangle trees, nodes of fewer than PX_MODEL_HULL_MIN_LEAVES triangles
/// keep only the sphere: a hull costs ~450 bytes per vertex, which a
/// triangle must not pay (docs/model.md).
///
/// Solids and surfaces: a part that is closed (px_mesh_part.closed) bounds a
/// solid, and a convex piece is a solid. Collision and tolerance queries
/// treat solids as filled: a model wholly inside another's solid
/// intersects it. An open part is a surface: only its triangles count.
/// Distances are always between the pieces themselves (surfaces for
/// triangle leaves): two disjoint triangle surfaces have a positive distance
/// even when one lies inside the other's solid, and the collision query is
/// the one that says they intersect.
///
/// Models are immutable after creation and safe to share across threads.
/// Queries allocate only through a caller-owned `px_model_cache` (its node
/// pair table). A triangle leaf met with a convex leaf is made a flat
/// px_convex for that pair, built on the stack (no allocation;
/// docs/model.md).
#ifndef PROXIMA_MODEL_H
#define PROXIMA_MODEL_H

#include "proxima/base.h"
#include "proxima/convex.h"
#include "proxima/math.h"
#include "proxima/mesh.h"
#include "proxima/query.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct px_model px_model;

/// In triangle trees, inner nodes with at least this many triangles below
/// them hold a convex hull; smaller ones only a bounding sphere.
#define PX_MODEL_HULL_MIN_LEAVES 128u

/// How a mesh becomes leaves.
typedef enum px_pieces {
    /// One convex hull per part of the mesh (coarse leaves with a bound h).
    PX_PIECES_PARTS = 0,
    /// One leaf per triangle (exact leaves, h = 0).
    PX_PIECES_TRIANGLES = 1,
    /// Pieces given as point sets (px_model_create_from_points), h = 0.
    PX_PIECES_POINTS = 2,
    /// Approximate convex decomposition: each part cut by planes into
    /// convex pieces whose hulls stay within `tolerance` of it (CGAL, in
    /// convexdecomp/), one leaf per piece with a certified bound h.
    PX_PIECES_APPROXIMATE = 3
} px_pieces;

/// Default and smallest tolerance of PX_PIECES_APPROXIMATE (relative to a
/// part's bounding-box diagonal; finer than the smallest, triangle leaves
/// are exact and cheaper).
#define PX_MODEL_DEFAULT_TOLERANCE 0.02
#define PX_MODEL_MIN_TOLERANCE 1e-4

/// Options of model creation; zero-initialise, zero means default.
typedef struct px_model_options {
    /// Allocator for everything the model owns (NULL: malloc/free).
    const px_allocator *allocator;
    /// px_model_create_from_mesh: a px_pieces value (PARTS, TRIANGLES or
    /// APPROXIMATE).
    uint32_t pieces;
    /// PX_PIECES_APPROXIMATE: threads the build may use, the calling one
    /// included (0 or 1: the calling thread only; at most 64 are used): the
    /// decomposition's candidate cuts and merges, then the certification
    /// of the pieces' bounds h, one piece per thread at a time. The model
    /// is the same bit for bit for any value. The other threads never call
    /// `allocator` (the hulls and each thread's scratch are allocated on
    /// the calling thread first) nor `progress`. Must be 0 otherwise.
    uint32_t threads;
    uint32_t reserved[4]; ///< must be zero
    /// PX_PIECES_APPROXIMATE: the largest distance a piece's hull may reach
    /// outside its part, relative to the part's bounding-box diagonal, in
    /// [PX_MODEL_MIN_TOLERANCE, 1] (0: PX_MODEL_DEFAULT_TOLERANCE). Must be
    /// 0 otherwise.
    double tolerance;
    /// PX_PIECES_APPROXIMATE: called from the building thread now and then
    /// with the fraction done, in [0, 1]; a nonzero return stops the build
    /// (PX_ERR_CANCELLED). May be NULL; must be NULL for other pieces.
    int (*progress)(void *user, double fraction);
    void *progress_user; ///< passed to `progress`
} px_model_options;

/// A model from convex pieces given as point sets, the seed's "union of
/// convex polyhedra": piece i is the convex hull of points
/// [piece_end[i-1], piece_end[i]) of `xyz` (3 doubles each; piece_end[-1]
/// is 0). Errors as `px_convex_create` for each piece (the message names the
/// piece), PX_ERR_INVALID_ARGUMENT for NULL arrays, zero pieces or ends
/// that decrease, PX_ERR_RANGE for a coordinate beyond 2^250.
PX_API px_model *px_model_create_from_points(const double *xyz, const uint32_t *piece_end,
                                             uint32_t piece_count, const px_model_options *options,
                                             px_error *err);

/// A model from a mesh, with leaves as `options->pieces` says. Parts without
/// triangles become point-set pieces (h = 0). The mesh may be destroyed
/// afterwards. PX_ERR_DEGENERATE names a part whose hull cannot be built;
/// PX_ERR_INVALID_ARGUMENT for a part without triangles with
/// PX_PIECES_TRIANGLES, or triangles of no part with PX_PIECES_PARTS;
/// PX_ERR_RANGE for a coordinate beyond 2^250 or triangles spanning less
/// than 2^-250.
PX_API px_model *px_model_create_from_mesh(const px_mesh *mesh, const px_model_options *options,
                                           px_error *err);

/// Frees the model with its allocator; NULL is a no-op.
PX_API void px_model_destroy(px_model *model);

/// Facts about a model.
typedef struct px_model_info {
    uint32_t pieces;      ///< px_pieces
    uint32_t leaves;      ///< leaf count
    uint32_t nodes;       ///< node count, leaves included (2 * leaves - 1)
    uint32_t hull_nodes;  ///< inner nodes holding a hull
    uint32_t depth;       ///< longest root-to-leaf path, in edges
    uint32_t solid;       ///< 1 when every leaf stands for a solid (closed parts, convex pieces)
    uint32_t solid_parts; ///< closed parts (triangle trees) whose inside counts in collisions
    uint32_t reserved;
    double max_h; ///< largest leaf bound h_overlap, which is at least h (px_model_leaf; 0 for exact leaves)
    px_vec3 min, max;    ///< axis-aligned box of the model (body frame)
    size_t memory_bytes; ///< everything the model owns
} px_model_info;

PX_API px_status px_model_get_info(const px_model *model, px_model_info *out);

/// Leaf `i`: the part it came from (the piece index for point sets), its
/// bounds, and for triangle leaves the triangle's index in the mesh.
/// For a part hull, `h` bounds the distance from any point of the hull's
/// boundary to the part's triangles, and `h_overlap` from any point of the
/// hull, inside included (used when two pieces overlap). Both are
/// certified: the largest distance found at the centres of a grid of cells
/// covering the hull, plus each cell's half-diagonal (the distance to a set
/// is 1-Lipschitz), refined where it matters. 0 for exact leaves and for
/// parts without triangles (a point set stands for its hull).
typedef struct px_model_leaf {
    uint32_t part;     ///< UINT32_MAX for a triangle that belongs to no part of its mesh
    uint32_t triangle; ///< UINT32_MAX for convex leaves
    double h;
    double h_overlap;
} px_model_leaf;

PX_API px_status px_model_get_leaf(const px_model *model, uint32_t i, px_model_leaf *out);

/// Largest .pxm file px_model_load reads (4 GiB).
#define PX_MODEL_MAX_FILE_BYTES (1ull << 32)

/// Saves a model to `path` in proxima's versioned binary format (.pxm), so
/// that the build runs once. PX_ERR_IO (naming the file) when it cannot be
/// written.
PX_API px_status px_model_save(const px_model *model, const char *path, px_error *err);

/// Loads a model saved by px_model_save (`options` as for creation: the
/// allocator; `pieces` must be 0). The reader checks the magic, version,
/// every size against the bytes present (before allocating), a checksum of
/// the whole payload, every index and the tree's shape; it rebuilds each
/// hull from its stored vertices and checks that every hull holds its
/// subtree, and recomputes the bounding spheres. A damaged or foreign file
/// gets PX_ERR_IO naming the file and the problem. Not checked: a part's
/// bound h (recomputing it is the build's cost); a file crafted to lie
/// about h gives a wrong bracket, never a wrong distance. A loaded model
/// answers every query as the saved one did (hulls are rebuilt from the
/// same vertices; their feature numbering may differ).
PX_API px_model *px_model_load(const char *path, const px_model_options *options, px_error *err);

/// The same from `size` bytes in memory (messages name "(memory)").
PX_API px_model *px_model_load_memory(const void *data, size_t size, const px_model_options *options,
                                      px_error *err);

/// Caller-owned coherence cache for one pair of models (A, B), in that
/// order. Zero-initialise it: zero means cold. It keeps the last best (or
/// hitting) leaf pair, one small Lin-Canny cache per node pair a query
/// visited, and the front of node pairs where the last query's descent
/// stopped, each with its lower bound: the next query re-measures only the
/// pairs that B's motion since could have brought within reach (front
/// tracking; docs/model.md). Everything is allocated on first use through
/// `allocator` (NULL: malloc) up to `max_bytes` (0: 16 MiB), the moment
/// a table grows (old and new copy) included; when full, further node
/// pairs, or the whole front, run cold (counted in `cold_runs`). Release it with px_model_cache_release. A
/// cache used with another pair of models is reset: every model and polytope carries an identity of its own,
/// so one built where a destroyed one was is another. One cache may serve distance, collide and within
/// queries of its pair.
typedef struct px_model_cache {
    const px_allocator *allocator;
    size_t max_bytes;
    /// Read-only statistics.
    size_t memory_bytes;
    uint64_t cold_runs;
    /// Private.
    void *impl;
} px_model_cache;

/// Frees what the cache holds and zeroes its private state (the allocator
/// and max_bytes are kept). NULL is a no-op.
PX_API void px_model_cache_release(px_model_cache *cache);

/// Result of px_model_distance.
typedef struct px_model_distance_result {
    /// Minimum distance over leaf pairs (pieces as solids for convex
    /// leaves, triangles for triangle leaves); 0 when two pieces touch.
    /// Leaf pairs tied with the best to within 128 eps (distance + the
    /// models' reach + the distance between their frames) may be pruned
    /// (docs/model.md, "Ties"), so the answer is that minimum to within
    /// this window, whatever the cache holds.
    double distance;
    /// distance + h_a + h_b of the leaves realising it (h_overlap when the
    /// distance is 0): with coarse leaves, the distance of the original
    /// meshes' triangles lies in [distance, upper_bound]. Equal to distance
    /// for exact leaves.
    double upper_bound;
    /// Closest points in the world frame.
    px_vec3 point_a, point_b;
    /// The leaves realising the distance, and their features (`piece` holds
    /// the leaf index; for triangle leaves, vertex k / edge k (vertices k,
    /// k+1) / face 0 of the triangle).
    uint32_t leaf_a, leaf_b;
    px_feature feature_a, feature_b;
    /// Node pairs bounded and leaf pairs measured by this query.
    uint32_t node_pairs, leaf_pairs;
    px_diagnostics diag;
} px_model_distance_result;

/// Distance between model A at pose_a and model B at pose_b: best-first
/// descent with hull distances as lower bounds (seed 000 ch. 4), started
/// from the cache's previous best pair. `cache` may be NULL (cold).
/// PX_ERR_INVALID_ARGUMENT for NULL models, poses or result; a bad pose as
/// px_pose_check; PX_ERR_RANGE when the models are placed more than 2^250
/// apart.
PX_API px_status px_model_distance(const px_model *a, const px_pose *pose_a, const px_model *b,
                                   const px_pose *pose_b, px_model_cache *cache,
                                   px_model_distance_result *out);

/// Result of px_model_collide and px_model_within.
typedef struct px_model_collide_result {
    /// 1 when the models intersect (collide) or are at most the tolerance
    /// apart (within); 0 otherwise.
    int hit;
    /// 1 when the hit is a containment: a piece of one model lies inside a
    /// solid of the other without touching its surface.
    int contained;
    /// A leaf pair that proves the hit (UINT32_MAX for containment or none).
    uint32_t leaf_a, leaf_b;
    uint32_t node_pairs, leaf_pairs;
    px_diagnostics diag;
} px_model_collide_result;

/// Boolean collision with early exit, solids counted as filled.
PX_API px_status px_model_collide(const px_model *a, const px_pose *pose_a, const px_model *b,
                                  const px_pose *pose_b, px_model_cache *cache, px_model_collide_result *out);

/// Tolerance verification: are the models at most `tolerance` (>= 0,
/// finite) apart (a distance equal to it is a hit, as the scene's margin
/// is)? Prunes every node pair farther than it; solids as in collide.
PX_API px_status px_model_within(const px_model *a, const px_pose *pose_a, const px_model *b,
                                 const px_pose *pose_b, double tolerance, px_model_cache *cache,
                                 px_model_collide_result *out);

/// Model A against one convex polytope B: the same queries, B seen as a
/// model of one leaf (leaf_b is 0).
PX_API px_status px_model_distance_convex(const px_model *a, const px_pose *pose_a, const px_convex *b,
                                          const px_pose *pose_b, px_model_cache *cache,
                                          px_model_distance_result *out);
PX_API px_status px_model_collide_convex(const px_model *a, const px_pose *pose_a, const px_convex *b,
                                         const px_pose *pose_b, px_model_cache *cache,
                                         px_model_collide_result *out);

#ifdef __cplusplus
}
#endif

#endif /* PROXIMA_MODEL_H */
