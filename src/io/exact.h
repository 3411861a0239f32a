/* Full-precision positions for the text formats whose vertex order in
 * Assimp's scene is known (internal to src/io). See exact.c. */
#ifndef PXI_IO_EXACT_H
#define PXI_IO_EXACT_H

#include <assimp/scene.h>

#include "io/precheck.h"
#include "proxima/io.h"

/* Reads the positions of the file at `path` (the one the precheck found as
 * `id`) again, in doubles, in the order of Assimp's scene: the vertices of
 * scene->mMeshes[0], then [1], ... On PX_OK, `*xyz` is either NULL (the
 * file is not plain OFF, ASCII STL, OBJ or PLY as exact.c reads them, or its numbers
 * disagree with Assimp's floats: keep those) or 3 * (the scene's vertex
 * count) doubles, pxi_alloc'ed, to free with pxi_free(alloc, *xyz,
 * *count * 3 * sizeof(double)). PX_ERR_OUT_OF_MEMORY otherwise. */
px_status pxi_io_exact_positions(const char *path, const pxi_file_id *id, const struct aiScene *scene,
                                 const px_allocator *alloc, double **xyz, size_t *count, px_error *err);

#endif
