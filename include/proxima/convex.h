/// proxima/convex.h: convex polytopes.
///
/// A `px_convex` is an immutable convex polytope in its body frame:
/// vertices, edges and polygonal faces (exactly coplanar hull triangles
/// merged) with full adjacency and precomputed Voronoi-region planes (the
/// closest-feature structure of M. Lin's thesis, "Efficient collision
/// detection for animation and robotics", Berkeley 1993, ch. 3). Safe to
/// share across threads. Hulls are computed by CGAL's convex_hull_3 with
/// exact predicates.
///
/// Lower-dimensional pieces. A point set whose affine dimension (decided
/// exactly by CGAL on the input doubles) is below 3 gives a lower-dimensional
/// convex piece, which every query accepts like a solid
/// (`px_convex_dimension`):
///
/// | dimension | input | V, E, F | Euler |
/// |---|---|---|---|
/// | 3 | a solid | its hull | V - E + F = 2 |
/// | 2 | coplanar points (a triangle, a convex polygon) | n, n, 2 | V - E + F = 2 |
/// | 1 | collinear points (a segment) | 2, 1, 0 | V - E = 1 |
/// | 0 | one distinct point (repeated or not) | 1, 0, 0 | V = 1 |
///
/// A polygon is two-sided: faces 0 and 1 are the same polygon with
/// opposite normals (face 1's plane is face 0's turned over, exactly), each
/// listing the vertices counter-clockwise seen from its own side, and every
/// edge lies between them. A segment's edge runs from vertex 0 to vertex 1.
/// A sliver polygon whose area is rounding (three points one ulp off a
/// line) is accepted too: its plane is then one through its longest edge,
/// which holds it to within rounding, and the queries answer it from
/// support functions alone (docs/methods.md).
/// Points exactly collinear or coplanar count as such however they were
/// produced; points one ulp off a plane make a solid (a very thin one),
/// unless double precision cannot hold its planes: then points within 64
/// ulps of their coordinates' magnitude of one plane make the polygon of
/// their hull in that plane (a plate turned into place), of one line the
/// segment between the extreme two, of one point that point (see
/// PX_ERR_DEGENERATE below). The corners kept are input points.
/// Accessors: every accessor that takes an index returns PX_OK, or
/// PX_ERR_INVALID_ARGUMENT with its outputs zeroed when the polytope or an
/// output is NULL or the index is out of range. Counts of a NULL polytope
/// are 0.
#ifndef PROXIMA_CONVEX_H
#define PROXIMA_CONVEX_H

#include "proxima/base.h"
#include "proxima/math.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct px_convex px_convex;

/// Options of `px_convex_create`; zero-initialise, zero means default.
typedef struct px_convex_options {
    /// Allocator for everything the polytope owns (copied; NULL: malloc and
    /// free). Both functions must be set.
    const px_allocator *allocator;
    /// Resolution of the direction lookup table used for cold starts: cells
    /// per cube face side, 1 to 256. 0 = chosen from the vertex count.
    uint32_t lut_resolution;
    /// Must be zero (PX_ERR_INVALID_ARGUMENT otherwise): room for later options.
    uint32_t reserved[5];
} px_convex_options;

/// Builds the convex hull of `count` points (`xyz` holds 3*count doubles,
/// body frame). Only extreme points become vertices; exactly coplanar hull
/// triangles are merged into polygonal faces. The hull is stored about its
/// own centre, so that every tolerance is relative to the body's size, not
/// to where its coordinates sit.
///
/// Returns NULL and fills `err` (may be NULL) on:
/// - PX_ERR_INVALID_ARGUMENT: `xyz` NULL, `count` 0 or above 2^26, an
///   option out of range or a reserved field not zero;
/// - PX_ERR_NON_FINITE: a NaN or infinite coordinate (index in the message);
/// - PX_ERR_RANGE: coordinates outside the supported range (below);
/// - PX_ERR_DEGENERATE: the hull is a solid but double precision cannot
///   hold its planes (thinner than rounding, such as a slab 2^-1060 thick
///   at unit size, or a sliver tetrahedron); the message says which. Flat,
///   collinear and single-point input, sliver polygons included, is
///   accepted (above). Before refusing a solid, points closer than 2^-40 of
///   the points' extent (per coordinate, on a grid) are welded and the
///   hull is tried once more: near-duplicates a few ulps apart (cut points
///   computed twice, scans) make tiny faces whose normals are noise. The
///   hull then differs from the exact one by at most that distance. Points
///   that flat (above) are taken as a polygon, segment or point instead,
///   within 64 ulps of the exact hull;
/// - PX_ERR_OUT_OF_MEMORY.
/// On success `err->code` is PX_OK. `options` may be NULL.
PX_API px_convex *px_convex_create(const double *xyz, size_t count, const px_convex_options *options,
                                   px_error *err);

/// Frees a polytope with the allocator it was created with; NULL is a no-op.
PX_API void px_convex_destroy(px_convex *convex);

/// Feature counts. Euler: V - E + F = 2 for solids and polygons, V - E = 1
/// for segments and points (table above).
PX_API uint32_t px_convex_vertex_count(const px_convex *convex);
PX_API uint32_t px_convex_edge_count(const px_convex *convex);
PX_API uint32_t px_convex_face_count(const px_convex *convex);

/// Affine dimension of the piece: 3 (solid), 2 (polygon), 1 (segment) or
/// 0 (point); 0 for NULL.
PX_API uint32_t px_convex_dimension(const px_convex *convex);

/// Vertex `i` in the body frame.
PX_API px_status px_convex_vertex(const px_convex *convex, uint32_t i, px_vec3 *out);

/// The two vertices of edge `e` (tail, head).
PX_API px_status px_convex_edge(const px_convex *convex, uint32_t e, uint32_t out[2]);

/// Face `f`: outward unit normal `normal` and offset `offset` of its plane
/// (normal . p = offset, body frame) and its number of vertices. Any output
/// may be NULL.
PX_API px_status px_convex_face(const px_convex *convex, uint32_t f, px_vec3 *normal, double *offset,
                                uint32_t *vertex_count);

/// Vertex `k` of face `f`, counter-clockwise seen from outside.
PX_API px_status px_convex_face_vertex(const px_convex *convex, uint32_t f, uint32_t k, uint32_t *vertex);

/// World-frame bounds under a pose: the exact axis-aligned box of the
/// polytope (min, max) and an enclosing sphere (centre, radius) about its
/// centre, for broad phases.
typedef struct px_bounds {
    px_vec3 min, max;
    px_vec3 center;
    double radius;
} px_bounds;

/// Bounds of the polytope at `pose` (NULL: identity). PX_ERR_INVALID_ARGUMENT
/// for a NULL polytope or output; a bad pose as `px_pose_check`.
PX_API px_status px_convex_bounds(const px_convex *convex, const px_pose *pose, px_bounds *out);

/// Bytes owned by the polytope (all arrays, planes and lookup table).
PX_API size_t px_convex_memory_bytes(const px_convex *convex);

/// Checks every structural invariant: Euler's formula for the piece's
/// dimension (table above) and the vertex degrees it implies, consistent
/// half-edge adjacency, outward unit normals (a polygon: two faces, one the
/// other turned over), convexity (every vertex on or below every face plane
/// within a relative 1e-9; a polygon also turns left at every vertex and
/// keeps every vertex inside every edge), planar faces. PX_OK or
/// PX_ERR_INTERNAL with the first violation in `err`.
PX_API px_status px_convex_validate(const px_convex *convex, px_error *err);

#ifdef __cplusplus
}
#endif

#endif /* PROXIMA_CONVEX_H */
