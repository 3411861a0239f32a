/* What the checks of a mesh file share (internal to src/io): the file being
 * checked, a buffered reader over it, saturating arithmetic. */
#ifndef PXI_IO_SCAN_H
#define PXI_IO_SCAN_H

#include <stddef.h>

#include "proxima/io.h"

typedef unsigned long long u64;

/* Bytes of the head (the first bytes of the file, kept in memory). */
#define PXI_IO_HEAD_BYTES 65536

/* A buffered, forward-mostly reader over an open file descriptor (pread, so
 * its position is its own). Bytes past the size the file had when it was
 * checked are never read: a file that grows is read as it was. */
typedef struct io_reader {
    int fd;
    u64 size;           /* file size when checked */
    u64 base;           /* file offset of buf[0] */
    size_t len;         /* bytes valid in buf */
    size_t at;          /* next byte: buf[at] (at <= len) */
    unsigned char *buf; /* PXI_IO_READER_BYTES bytes */
    int error;          /* errno of a failed read, or -1 for a file that shrank */
} io_reader;

#define PXI_IO_READER_BYTES 65536

/* The file being checked: its name, size and first bytes, and a reader. */
typedef struct io_head {
    const char *path;
    char ext[16];              /* extension, lowercased, no dot; "" if none (or longer than 15) */
    u64 size;                  /* file size in bytes */
    const unsigned char *data; /* the first `len` bytes of the file */
    size_t len;                /* min(size, PXI_IO_HEAD_BYTES) */
    io_reader *rd;             /* the whole file, for the checks that stream over it */
    const px_allocator *alloc; /* for the checks' own buffers */
    u64 *gltf_triangles;       /* out (pxi_check_gltf): the triangles Assimp must return, ~0: unknown */
    u64 *off_dropped_faces;    /* out (OFF): face lines Assimp drops (10 or more vertices) */
} io_head;

/* a + b and a * b saturated at ULLONG_MAX: declared counts are untrusted. */
static inline u64 pxi_sat_add(u64 a, u64 b) { return a > ~0ull - b ? ~0ull : a + b; }
static inline u64 pxi_sat_mul(u64 a, u64 b) { return b && a > ~0ull / b ? ~0ull : a * b; }

/* ASCII tolower, independent of the locale. */
static inline int pxi_lower(int c) { return c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c; }

/* Moves the reader to file offset `off` (<= size). */
void pxi_rd_seek(io_reader *r, u64 off);

/* File offset of the next byte. */
static inline u64 pxi_rd_tell(const io_reader *r) { return r->base + r->at; }

/* Refills the buffer at the current position; returns the bytes now
 * available (0 at the end of the file or on an error, see r->error). */
size_t pxi_rd_fill(io_reader *r);

/* The next byte (advancing), or -1 at the end of the file or on an error. */
static inline int pxi_rd_get(io_reader *r) {
    if (r->at >= r->len && !pxi_rd_fill(r)) return -1;
    return r->buf[r->at++];
}

/* The next byte without advancing, or -1. */
static inline int pxi_rd_peek(io_reader *r) {
    if (r->at >= r->len && !pxi_rd_fill(r)) return -1;
    return r->buf[r->at];
}

/* Copies the next n bytes to out; returns 0 if the file ends first. */
int pxi_rd_read(io_reader *r, void *out, size_t n);

/* Skips n bytes; returns 0 (position unchanged) if fewer remain. */
int pxi_rd_skip(io_reader *r, u64 n);

/* The PX_ERR_IO for a read error of the reader (errno or a file that shrank
 * while it was checked). */
px_status pxi_rd_error(const io_head *h, px_error *err);

/* Reads the whole file into a buffer of size + 1 bytes (NUL-terminated),
 * allocated with h->alloc; release with pxi_free(h->alloc, *out, size + 1).
 * For the node-graph scans (Assimp's COLLADA and glTF importers hold the
 * whole document in memory too). */
px_status pxi_read_all(const io_head *h, unsigned char **out, px_error *err);

/* The checks of each format (ply.c, graph.c); PX_OK or PX_ERR_IO naming the
 * file. check_ply runs when the file may be a PLY file (see ply.c). */
px_status pxi_check_ply(const io_head *h, px_error *err);
px_status pxi_check_dae(const io_head *h, px_error *err);
px_status pxi_check_gltf(const io_head *h, px_error *err);

/* An ASCII STL file (Assimp's test: `solid` after spaces, not of binary STL
 * size) walked as Assimp 5.2 reads it (stl.c). */
px_status pxi_check_stl_ascii(const io_head *h, px_error *err);

/* An OBJ file read line by line as Assimp 5.2 reads it (obj.c): lines it
 * would skip or join, and objects it would mix up, are refused. */
px_status pxi_check_obj(const io_head *h, px_error *err);

/* Nesting depth of AC3D, FBX, OpenGEX and XML files, and BVH files refused (nest.c). */
px_status pxi_check_nesting(const io_head *h, px_error *err);

/* Assimp's signature test (BaseImporter::SearchFileHeaderForToken with its
 * default arguments): 1 if lowercase `token` occurs in the first 200 bytes,
 * lowercased, once the NUL bytes are removed (scan.c). */
int pxi_signature_has(const io_head *h, const char *token);

#endif
