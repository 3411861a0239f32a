/* The file system Assimp reads through during one import (internal to
 * src/io): Assimp's C API aiFileIO, so that every file an import opens (the
 * mesh file, and the files it references: glTF buffers, OBJ material
 * libraries, ...) passes the same rules. See fs.c. */
#ifndef PXI_IO_FS_H
#define PXI_IO_FS_H

#include <assimp/cfileio.h>

#include "io/precheck.h"
#include "proxima/io.h"

/* One import's file system. `io` is what aiImportFileEx gets; it must stay
 * valid until aiReleaseImport (the importer keeps it). */
typedef struct pxi_io_fs {
    struct aiFileIO io;
    const char *path; /* the mesh file, for messages */
    const px_allocator *alloc;
    pxi_file_id main;           /* the mesh file as the precheck found it */
    unsigned long long charged; /* bytes counted against PX_IO_MAX_IMPORT_BYTES */
    int main_charged;
    int refused;       /* an open or a read was refused: the import fails */
    int out_of_memory; /* ... and the first refusal was an allocation failing */
    void *open_files;  /* the openings not closed yet (a list, fs.c) */
    char message[480]; /* the first refusal: "'name' was refused: why" */
} pxi_io_fs;

/* Sets up `fs` for importing `path`, whose precheck found `main`. */
void pxi_io_fs_init(pxi_io_fs *fs, const char *path, const pxi_file_id *main, const px_allocator *alloc);

/* Closes the files Assimp left open. Call once the importer is gone: after
 * aiReleaseImport, or after aiImportFileEx returned NULL. */
void pxi_io_fs_finish(pxi_io_fs *fs);

#endif
