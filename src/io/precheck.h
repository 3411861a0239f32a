/* Checks of a mesh file before Assimp reads it (internal to src/io). */
#ifndef PXI_IO_PRECHECK_H
#define PXI_IO_PRECHECK_H

#include "proxima/io.h"

/* What identifies the file that was checked: Assimp's later opens of the
 * same name must find this file (fs.c), not one put in its place. */
typedef struct pxi_file_id {
    unsigned long long dev, ino, size;
    long long mtime_sec, mtime_nsec;
    /* glTF: the triangles Assimp 5.2 must return, all its primitives being
     * triangle lists of known counts (~0: not known, or not glTF). Fewer
     * mean it dropped some: their indices were out of range. */
    unsigned long long gltf_triangles;
    /* OFF: the face lines of 10 or more vertices, which Assimp 5.2 drops
     * (their vertices stay): harmless for a hull of the points, a loss for
     * a mesh (px_mesh_load refuses them). */
    unsigned long long off_dropped_faces;
} pxi_file_id;

/* Checks the file at `path` (non-NULL, non-empty) before it is imported:
 * a regular, non-empty file of at most PX_IO_MAX_FILE_BYTES whose header
 * counts (OFF, PLY, binary STL) fit in its size and in PX_IO_MAX_ELEMENTS,
 * whose PLY or OFF body Assimp can read without the failures io.h lists, and
 * whose COLLADA or glTF node graph is acyclic and small enough, and whose
 * AC3D, FBX, OpenGEX or XML nesting Assimp's recursive readers can take;
 * see io.h for the rules and precheck.c, ply.c, graph.c and nest.c for why. Opens the file once
 * (without blocking: O_NONBLOCK, after stat() found a regular file) and
 * fills `id` with what identifies it. Streams through the file for PLY and
 * OFF (64 KiB and, for PLY, a 1 MiB cache at a time) and reads COLLADA and
 * glTF files whole. Returns PX_OK, or PX_ERR_IO (PX_ERR_OUT_OF_MEMORY if a
 * buffer cannot be allocated) with `err` (may be NULL) naming the file.
 * Thread-safe: touches no global state and does not call Assimp. */
px_status pxi_io_precheck(const char *path, const px_allocator *alloc, pxi_file_id *id, px_error *err);

/* The OBJ checks (obj.c) on the file `id` identifies, for a file Assimp
 * read as OBJ under another name (it picks an importer by the file's
 * content when the extension is none of its own: review s29 found a `.txt`
 * OBJ whose indented vertex line Assimp lost, with PX_OK). */
px_status pxi_io_check_as_obj(const char *path, const px_allocator *alloc, const pxi_file_id *id,
                              px_error *err);

#endif
