/// proxima/mesh.h: triangle meshes with their part tree (an assembly).
///
/// A `px_mesh` owns vertices (doubles, in the mesh's root frame), triangles
/// (vertex index triples) and the file's part tree: nodes (a name, a parent)
/// and parts (one per node-mesh reference, with its own vertex and triangle
/// ranges, node transforms already applied). It is immutable after creation
/// and safe to share across threads; one `px_mesh_destroy` frees it all.
///
/// Meshes are made from arrays here (`px_mesh_create`, core library) or
/// loaded from files by `px_mesh_load` (proxima/io.h, library proxima-io).
/// Open, non-manifold and inconsistently oriented meshes are accepted; each
/// part records whether it is closed (a solid) or open (a surface).
#ifndef PROXIMA_MESH_H
#define PROXIMA_MESH_H

#include "proxima/base.h"
#include "proxima/math.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct px_mesh px_mesh;

/// A node of the part tree, as given to `px_mesh_create`.
typedef struct px_mesh_node_desc {
    const char *name;  ///< copied; NULL is stored as ""
    int32_t parent;    ///< index of the parent node, -1 for a root; must be below this node's index
    uint32_t reserved; ///< must be zero
} px_mesh_node_desc;

/// A part, as given to `px_mesh_create`: a contiguous range of vertices and
/// a contiguous range of triangles whose indices lie in that vertex range.
/// A part may have vertices and no triangles (a point set). The ranges of
/// different parts must not overlap; vertices and triangles outside every
/// part are kept (copied and checked) but belong to no part.
typedef struct px_mesh_part_desc {
    const char *name; ///< copied; NULL is stored as ""
    int32_t node;     ///< the node this part hangs from, -1 for none
    uint32_t first_vertex, vertex_count;
    uint32_t first_triangle, triangle_count;
    uint32_t reserved; ///< must be zero
} px_mesh_part_desc;

/// Everything `px_mesh_create` copies. Zero-initialise. With `part_count`
/// 0, the whole mesh is one part named "" and there are no nodes.
typedef struct px_mesh_desc {
    const double *xyz;         ///< 3 * vertex_count coordinates
    size_t vertex_count;       ///< at most 2^31
    const uint32_t *triangles; ///< 3 * triangle_count vertex indices (may be NULL when 0)
    size_t triangle_count;     ///< at most 2^31
    const px_mesh_part_desc *parts;
    uint32_t part_count;
    const px_mesh_node_desc *nodes;
    uint32_t node_count;
    /// Length in metres of one unit of the coordinates given here (before
    /// the scale option), 0 when unknown; finite and >= 0. Recorded, not
    /// applied. `px_mesh_load` sets 1 for COLLADA (Assimp 5.2 folds the
    /// file's `<unit meter>` into the root node's transform, so the
    /// coordinates come out in metres) and glTF (metres by its
    /// specification), 0 for the formats without units (STL, OBJ, PLY, OFF).
    double unit_metres;
    /// 1 when the coordinates passed through 32-bit floats on their way
    /// here (`px_mesh_load` through Assimp), 0 when they are as precise as
    /// their source. Recorded, not applied.
    uint32_t float_coordinates;
    uint32_t reserved[3]; ///< must be zero
} px_mesh_desc;

/// Options of mesh creation and loading; zero-initialise, zero = default.
typedef struct px_mesh_options {
    /// Allocator for everything the mesh owns (copied; NULL: malloc/free).
    const px_allocator *allocator;
    /// Every coordinate is multiplied by this (0 means 1). For unit-less
    /// formats: the Puma 560 STLs are in inches, scale 0.0254 gives metres.
    /// Must be finite and positive.
    double scale;
    uint32_t reserved[6]; ///< must be zero
} px_mesh_options;

/// Copies a mesh from arrays, multiplying every coordinate by the scale
/// option, and finds which parts are closed (`px_mesh_part.closed`). A
/// closed part whose signed volume is negative (inside out: its triangles
/// wound clockwise seen from outside) has its triangles reversed (corners
/// 1 and 2 swapped), so that every closed part's normals, by the
/// right-hand rule, point out of the solid (the part's total decides: of
/// separate shells wound against each other, the smaller keeps facing in;
/// docs/io.md); open parts keep their winding.
/// Cost: O(n log n) in the vertices and triangles (sorts), plus temporary
/// memory of about 36 bytes per vertex and 24 per triangle of the largest
/// part, freed before returning.
///
/// Returns NULL and fills `err` (may be NULL) on
/// PX_ERR_INVALID_ARGUMENT (NULL arrays with non-zero counts, an index out
/// of range, a part whose triangles use vertices outside its range, parts
/// that overlap, a node whose parent is not an earlier node, a reserved
/// field not zero, a bad scale or unit, more than 2^31 vertices, triangles,
/// parts or nodes, an allocator without both functions), PX_ERR_NON_FINITE
/// (a NaN or infinite coordinate, or one the scale makes infinite; vertex
/// index in the message), PX_ERR_OUT_OF_MEMORY (the allocator failed, or
/// the mesh's size overflows size_t).
PX_API px_mesh *px_mesh_create(const px_mesh_desc *desc, const px_mesh_options *options, px_error *err);

/// Frees the mesh with the allocator it was created with; NULL is a no-op.
PX_API void px_mesh_destroy(px_mesh *mesh);

/// Counts; 0 for a NULL mesh.
PX_API uint32_t px_mesh_vertex_count(const px_mesh *mesh);
PX_API uint32_t px_mesh_triangle_count(const px_mesh *mesh);
PX_API uint32_t px_mesh_part_count(const px_mesh *mesh);
PX_API uint32_t px_mesh_node_count(const px_mesh *mesh);

/// The arrays, owned by the mesh: 3 * vertex_count doubles (scale applied),
/// 3 * triangle_count indices. NULL for a NULL or empty mesh.
PX_API const double *px_mesh_vertices(const px_mesh *mesh);
PX_API const uint32_t *px_mesh_triangles(const px_mesh *mesh);

/// A part as stored: the desc's fields plus what creation measured.
typedef struct px_mesh_part {
    const char *name; ///< owned by the mesh, never NULL
    int32_t node;
    uint32_t first_vertex, vertex_count;
    uint32_t first_triangle, triangle_count;
    /// 1 when the part is a closed surface: after joining vertices at
    /// exactly equal positions (no tolerance), every edge is used by exactly
    /// two triangles, once in each direction, and no triangle is degenerate
    /// (two equal corners, or three collinear ones: decided exactly, each
    /// triangle scaled by a power of two first; coordinates more than 2^900
    /// below the triangle's largest may round to zero there). Such a part bounds a
    /// solid, and its triangles face out (see `px_mesh_create`). 0: an
    /// open, non-manifold or inconsistently wound surface, or a point set.
    uint32_t closed;
} px_mesh_part;

/// A node as stored.
typedef struct px_mesh_node {
    const char *name; ///< owned by the mesh, never NULL
    int32_t parent;
} px_mesh_node;

/// Part `i` / node `i` (named `get` because `px_mesh_part` and
/// `px_mesh_node` are the types). PX_ERR_INVALID_ARGUMENT with the output
/// zeroed for a NULL mesh or output or an index out of range.
PX_API px_status px_mesh_get_part(const px_mesh *mesh, uint32_t i, px_mesh_part *out);
PX_API px_status px_mesh_get_node(const px_mesh *mesh, uint32_t i, px_mesh_node *out);

/// Whole-mesh facts.
typedef struct px_mesh_info {
    px_vec3 min, max;   ///< axis-aligned box of all vertices (zero when empty)
    double unit_metres; ///< as given or read (0: unknown), times nothing: the scale option is not folded in
    double scale;       ///< the scale option that was applied (1 by default)
    uint32_t closed_parts; ///< parts with `closed` = 1
    /// As given in the desc: 1 when the coordinates passed through 32-bit
    /// floats (about 7 significant digits; docs/io.md has the cost).
    uint32_t float_coordinates;
} px_mesh_info;

PX_API px_status px_mesh_get_info(const px_mesh *mesh, px_mesh_info *out);

/// Bytes the mesh owns.
PX_API size_t px_mesh_memory_bytes(const px_mesh *mesh);

#ifdef __cplusplus
}
#endif

#endif /* PROXIMA_MESH_H */
