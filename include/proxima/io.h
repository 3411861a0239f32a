/// proxima/io.h: building polytopes from mesh files (Assimp). These
/// functions live in the separate library proxima-io (CMake target
/// proxima::io, pkg-config proxima-io), the only part of proxima that links
/// Assimp.
///
/// Any format Assimp 5 reads (OBJ, STL, PLY, OFF, COLLADA, glTF, FBX, ...)
/// can be turned into a convex polytope: the convex hull of every vertex of
/// every mesh in the file. Positions pass through Assimp as 32-bit floats
/// (about 7 significant digits); do not route precision-critical geometry
/// through files.
///
/// Frames and units: the node tree of the file is applied, so vertices are in
/// the file's root ("scene") frame. No unit conversion is made by proxima:
/// STL/OBJ/PLY/OFF have no units (the numbers in the file are used as they
/// are); for COLLADA, Assimp folds `<unit meter>` and the up-axis rotation
/// into the root node, so those come out in metres, Y up.
///
/// Thread safety: imports are serialised internally (Assimp's last-error
/// string is process-global); the functions may be called from any thread.
/// The lock is the library's only global state.
#ifndef PROXIMA_IO_H
#define PROXIMA_IO_H

#include <stddef.h>

#include "proxima/base.h"
#include "proxima/convex.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Convex hull of all vertices of all meshes in the file at `path`, with the
/// node transforms applied (the file's root frame; see the header comment for
/// units). A mesh referenced by several nodes contributes one copy per node.
/// Points, lines and faces all count; vertices no face uses count too.
/// `options` (may be NULL) is passed to `px_convex_create`.
///
/// Returns NULL and fills `err` (may be NULL) on:
/// - PX_ERR_INVALID_ARGUMENT: `path` NULL or empty;
/// - PX_ERR_IO: the file cannot be opened, Assimp cannot parse it or reports
///   an incomplete scene, the scene has no meshes or no vertices, or a vertex
///   (after the node transform) is NaN or infinite. The message names the file
///   and the problem (Assimp's own message is quoted when there is one);
/// - PX_ERR_DEGENERATE: the vertices have no 3-D hull (flat, collinear, one
///   point): the message names the file;
/// - PX_ERR_OUT_OF_MEMORY.
PX_API px_convex *px_convex_create_from_file(const char *path, const px_convex_options *options,
                                             px_error *err);

/// The distinct vertex positions of all meshes in the file at `path`, node
/// transforms applied (the frame `px_convex_create_from_file` uses). On
/// PX_OK, `*xyz` holds `3 * *count` doubles (x, y, z per point, exact
/// duplicates removed, order unspecified but deterministic), allocated with
/// `allocator` (NULL: malloc): release it with
/// `px_free_points(*xyz, *count, allocator)`, the same allocator.
/// On error `*xyz` is NULL, `*count` is 0, and the status is returned with
/// `err` (may be NULL) filled as for `px_convex_create_from_file` (PX_ERR_IO,
/// PX_ERR_INVALID_ARGUMENT for a NULL argument or an allocator without both
/// functions, PX_ERR_OUT_OF_MEMORY).
PX_API px_status px_load_points(const char *path, const px_allocator *allocator, double **xyz, size_t *count,
                                px_error *err);

/// Frees an array returned by `px_load_points`; `count` and `allocator`
/// must be the ones it was returned with. NULL is a no-op.
PX_API void px_free_points(double *xyz, size_t count, const px_allocator *allocator);

#ifdef __cplusplus
}
#endif

#endif /* PROXIMA_IO_H */
