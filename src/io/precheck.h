/* Checks of a mesh file before Assimp reads it (internal to src/io). */
#ifndef PXI_IO_PRECHECK_H
#define PXI_IO_PRECHECK_H

#include "proxima/io.h"

/* Checks the file at `path` (non-NULL, non-empty) before it is imported:
 * a regular, non-empty file of at most PX_IO_MAX_FILE_BYTES whose header
 * counts (OFF, PLY, binary STL) fit in its size and in PX_IO_MAX_ELEMENTS;
 * see io.h for the rules and precheck.c for why. Reads at most the first
 * 64 KiB. Returns PX_OK, or PX_ERR_IO (PX_ERR_OUT_OF_MEMORY if the buffer for
 * the head cannot be allocated) with `err` (may be NULL) naming the file.
 * Thread-safe: touches no global state and does not call Assimp. */
px_status pxi_io_precheck(const char *path, const px_allocator *alloc, px_error *err);

#endif
