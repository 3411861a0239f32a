/* Checks of a mesh file before Assimp reads it (BAD_INPUTS.md E.28).
 *
 * Assimp sizes its arrays by the counts a header declares, before it reads
 * the elements, and it allocates them with `new T[n]`, which constructs (so
 * touches) every element: a 45-byte OFF file declaring 2e9 vertices asks
 * for 24 GB (13 GB were committed before the process was killed), an ascii
 * PLY declaring 1e8 vertices with one vertex line loads as 1e8 vertices, and
 * a PLY header without end_header makes it loop forever (measured with
 * Debian bookworm's Assimp 5.2.5). So before the import, the declared
 * counts are compared with the size of the file, each element at the
 * smallest size its format allows, and the bodies of PLY and OFF files are
 * walked the way Assimp walks them (ply.c; off_walk below), and the node
 * graphs of COLLADA and glTF files are scanned (graph.c), and the nesting
 * of AC3D, FBX, OpenGEX and XML files (nest.c): a file refused
 * here cannot be a valid file of its format, would make Assimp 5.2 crash,
 * hang or read outside its buffers, or exceeds a documented limit (io.h).
 * Passing is no proof of validity: Assimp still parses the file.
 *
 * The file is opened once, without blocking (stat() first, then O_NONBLOCK),
 * and identified (device, inode, size, modification time): fs.c makes
 * Assimp's own opens of it find this same file. The first 64 KiB (the head)
 * are read for the headers; the walks stream through the rest.
 *
 * Which checks run. Assimp 5.2 picks the importer by the extension of the
 * file name when exactly one importer claims it; otherwise it asks each
 * importer whether it recognises the file's first bytes (for text formats,
 * BaseImporter::SearchFileHeaderForToken: the first 200 bytes, lowercased,
 * NUL bytes removed, searched for tokens). A check runs when the extension
 * names its format, or when the head matches a superset of that importer's
 * signature test, so every file Assimp could hand to the OFF, PLY, STL,
 * COLLADA or glTF importer is checked.
 *
 * What each Assimp 5.2 importer allocates from the header:
 * - OFF (OFFLoader.cpp): numVertices positions (with normals, colours and
 *   texture coordinates for the NOFF, COFF and STOFF variants) and numFaces
 *   faces, then it reads one line per vertex and per face.
 * - PLY (PlyParser.cpp, PlyLoader.cpp): per element, its declared number of
 *   records, ascii or binary; per list, its declared length (ply.c).
 * - STL (STLLoader.cpp): the file is binary when 84 + 50 n == file size, n
 *   being the 32-bit count at byte 80 and the arithmetic 32-bit (so a count
 *   that wraps passes); then 3 n positions and normals. A UTF-8 byte-order
 *   mark is removed from the buffer but not from the size that test uses.
 */
#define _POSIX_C_SOURCE 200809L /* stat, open(O_NONBLOCK), fstat, pread */

#include "io/precheck.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/core.h"
#include "io/scan.h"

#ifndef O_CLOEXEC
#define O_CLOEXEC 0
#endif

#define HEAD_BYTES PXI_IO_HEAD_BYTES /* bytes read to check a header */

#define sat_add pxi_sat_add
#define sat_mul pxi_sat_mul
#define lower pxi_lower
#define signature_has pxi_signature_has

/* 1 if the file starts with `s` (ASCII letters compared case-insensitively). */
static int starts_with_ci(const io_head *h, const char *s) {
    size_t n = strlen(s);
    if (h->len < n) return 0;
    for (size_t i = 0; i < n; ++i)
        if (lower(h->data[i]) != lower((unsigned char)s[i])) return 0;
    return 1;
}

/* 1 if the file starts with a UTF-8 byte-order mark (EF BB BF). */
static int has_utf8_bom(const io_head *h) {
    return h->len >= 3 && h->data[0] == 0xEF && h->data[1] == 0xBB && h->data[2] == 0xBF;
}

/* The PX_ERR_IO for a total of declared elements above PX_IO_MAX_ELEMENTS. */
static px_status err_too_many(const io_head *h, u64 total, px_error *err) {
    return pxi_error(err, PX_ERR_IO, "mesh file '%s' declares %llu elements, more than the limit of %llu",
                     h->path, total, (u64)PX_IO_MAX_ELEMENTS);
}

/* ------------------------------------------------------------------ OFF */

/* Assimp's OFF importer reads the file as one text buffer (TextFileToBuffer:
 * a UTF-8 byte-order mark dropped, a NUL appended). `off_text` is that
 * buffer as far as the head holds it; positions count from the text's
 * start, `skip` bytes into the file. */
typedef struct off_text {
    const unsigned char *d;
    size_t n;   /* bytes of the text in the head */
    u64 total;  /* bytes of the text (the NUL at `total`) */
    u64 skip;   /* byte-order mark bytes */
    int beyond; /* a position past the head was needed */
} off_text;

static int off_at(off_text *t, u64 i) {
    if (i < t->n) return t->d[i];
    if (i >= t->total) return 0; /* the NUL Assimp appends */
    t->beyond = 1;
    return 0;
}

/* ParsingUtils' SkipSpacesAndLineEnd and SkipLine, and OFFLoader's
 * NextToken (blank space, then '#' comment lines). */
static void off_skip_blank(off_text *t, u64 *c) {
    int ch;
    while ((ch = off_at(t, *c)) == ' ' || ch == '\t' || ch == '\r' || ch == '\n') ++*c;
}
static void off_next_token(off_text *t, u64 *c) {
    off_skip_blank(t, c);
    int ch;
    while (*c < t->total + 1 && ((ch = off_at(t, *c)) == '#' || ch == '\n' || ch == '\r')) {
        while ((ch = off_at(t, *c)) != '\r' && ch != '\n' && ch != 0) ++*c;
        while ((ch = off_at(t, *c)) == '\r' || ch == '\n') ++*c;
        off_skip_blank(t, c);
    }
}

/* strtoul10: Assimp's value (32-bit, wrapping) and the saturated one. */
static unsigned off_strtoul10(off_text *t, u64 *c, u64 *sat) {
    unsigned v = 0;
    u64 s = 0;
    int ch;
    while ((ch = off_at(t, *c)) >= '0' && ch <= '9') {
        v = v * 10u + (unsigned)(ch - '0');
        s = sat_add(sat_mul(s, 10), (u64)(ch - '0'));
        ++*c;
    }
    if (sat) *sat = s;
    return v;
}

static int is_line_end(int c) { return c == '\r' || c == '\n' || c == '\0' || c == '\f'; }

#define OFF_LINE 4096 /* ParsingUtils' BufferSize: OFFImporter's char line[4096] */

/* ParsingUtils' GetNextLine on the stream: 0 at the end of the text (or an
 * embedded NUL). Returns -1 for a line of OFF_LINE bytes or more: Assimp
 * copies 4096 of them and writes its terminating NUL one past its stack
 * buffer. `line` gets the line, NUL-terminated. */
static int off_next_line(io_reader *r, unsigned char *line, size_t *len) {
    int c = pxi_rd_peek(r);
    if (c <= 0) return 0;
    size_t n = 0;
    while ((c = pxi_rd_peek(r)) > 0 && !is_line_end(c)) {
        if (n == OFF_LINE - 1) return -1;
        line[n++] = (unsigned char)c;
        r->at++;
    }
    line[n] = 0;
    while ((c = pxi_rd_peek(r)) > 0 && is_line_end(c)) r->at++;
    *len = n;
    return 1;
}

/* The vertex and face lines, as OFFImporter::InternReadFile reads them from
 * `start` (a text position): numVertices lines, then face lines until
 * numFaces were taken. Assimp's face loop has no bound of its own: a line
 * whose count is 0 or above 9 is skipped with --mesh->mNumFaces and without
 * advancing, so two such lines in a one-face file wrap mNumFaces to 2^32 - 1
 * over an array of one face, and ScenePreprocessor then reads far past it
 * (SIGSEGV: the review's c_c.off, "0\n0 "). Refused here: a face count
 * below 3, more skipped lines than faces (the wrap), a vertex index that is
 * not a number below numVertices (Assimp clamps those silently), fewer
 * indices than the count, a line of 4096 bytes or more, and a text that ends
 * before its vertices and faces (Assimp leaves the missing vertices at the
 * origin). Faces of 10 or more vertices are left to Assimp, which drops the
 * face (its vertices stay). */
static px_status off_walk(const io_head *h, const off_text *t, u64 start, unsigned nv, unsigned nf,
                          px_error *err) {
    io_reader *rd = h->rd;
    unsigned char *line = pxi_alloc(h->alloc, OFF_LINE);
    if (!line) return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "out of memory reading mesh file '%s'", h->path);
    px_status st = PX_OK;
    size_t len;
    int got = 1;
    pxi_rd_seek(rd, t->skip + start);
    unsigned i = 0;
    for (; i < nv && (got = off_next_line(rd, line, &len)) > 0; ++i) {
    }
    if (got < 0) goto long_line;
    if (rd->error) goto read_error;
    if (i < nv) {
        st = pxi_error(err, PX_ERR_IO,
                       "mesh file '%s' declares %u vertices but its text ends after %u vertex lines (Assimp "
                       "5.2 would put the others at the origin)",
                       h->path, nv, i);
        goto done;
    }
    unsigned faces = 0, skipped = 0;
    u64 lineno = 0;
    while (faces < nf) {
        got = off_next_line(rd, line, &len);
        if (got < 0) goto long_line;
        if (rd->error) goto read_error;
        if (!got) {
            /* Assimp stops here too; only the declared lines must exist
             * (after skipped ones it reads on past them). */
            if ((u64)faces + skipped < nf)
                st = pxi_error(err, PX_ERR_IO, "mesh file '%s' declares %u faces but its text ends after %u",
                               h->path, nf, faces + skipped);
            goto done;
        }
        ++lineno;
        size_t p = 0;
        while (line[p] == ' ' || line[p] == '\t') ++p;
        size_t q = p;
        unsigned count = 0;
        u64 count_sat = 0;
        for (; line[q] >= '0' && line[q] <= '9'; ++q) {
            count = count * 10u + (unsigned)(line[q] - '0');
            count_sat = sat_add(sat_mul(count_sat, 10), (u64)(line[q] - '0'));
        }
        if (count == 0 || count > 9) {
            /* Assimp skips the line: refused outright when the count is not
             * a count, or once the skips would wrap mNumFaces. */
            if (q == p || count_sat < 3) {
                st = pxi_error(err, PX_ERR_IO,
                               "mesh file '%s': face line %llu has %s vertices, and Assimp 5.2 mishandles "
                               "such faces (a face needs at least 3)",
                               h->path, lineno, q == p ? "no count of" : "0");
                goto done;
            }
            if (h->off_dropped_faces) ++*h->off_dropped_faces;
            if (++skipped > nf) {
                st = pxi_error(err, PX_ERR_IO,
                               "mesh file '%s': more face lines of 10 or more vertices than its %u faces "
                               "(Assimp 5.2 drops them and wraps its face count)",
                               h->path, nf);
                goto done;
            }
            continue;
        }
        if (count < 3) {
            st =
                pxi_error(err, PX_ERR_IO, "mesh file '%s': face %u has %u vertices (a face needs at least 3)",
                          h->path, faces, count);
            goto done;
        }
        p = q;
        for (unsigned m = 0; m < count; ++m) {
            while (line[p] == ' ' || line[p] == '\t') ++p;
            u64 idx = 0;
            size_t d = p;
            for (; line[p] >= '0' && line[p] <= '9'; ++p)
                idx = sat_add(sat_mul(idx, 10), (u64)(line[p] - '0'));
            if (p == d || idx >= nv) {
                st = pxi_error(
                    err, PX_ERR_IO,
                    "mesh file '%s': face %u has %s (a face lists %u indices below the %u vertices)", h->path,
                    faces, p == d ? "fewer vertex indices than its count" : "a vertex index out of range",
                    count, nv);
                goto done;
            }
        }
        ++faces;
    }
    /* A face line after the declared faces: Assimp 5.2 stops at the count
     * and drops it with the mesh it belongs to (review s32: "8 5 0" over 6
     * faces loaded open, with PX_OK). */
    for (;;) {
        got = off_next_line(rd, line, &len);
        if (got < 0) goto long_line;
        if (rd->error) goto read_error;
        if (!got) break;
        size_t p = 0;
        unsigned numbers = 0;
        while (line[p]) {
            while (line[p] == ' ' || line[p] == '\t' || line[p] == '\r') ++p;
            if (!(line[p] >= '0' && line[p] <= '9')) break;
            while (line[p] >= '0' && line[p] <= '9') ++p;
            ++numbers;
        }
        if (numbers >= 4 && !line[p]) {
            st =
                pxi_error(err, PX_ERR_IO,
                          "mesh file '%s' has a face line after the %u faces its header declares (Assimp 5.2 "
                          "would drop it)",
                          h->path, nf);
            goto done;
        }
    }
    goto done;
long_line:
    st = pxi_error(err, PX_ERR_IO,
                   "mesh file '%s' has a line of %d bytes or more (Assimp 5.2's OFF reader overflows its "
                   "line buffer)",
                   h->path, OFF_LINE);
    goto done;
read_error:
    st = pxi_rd_error(h, err);
done:
    pxi_free(h->alloc, line, OFF_LINE);
    return st;
}

/* OFF, parsed as OFFImporter::InternReadFile parses it: blank space and
 * comments, the keyword [ST][C][N][4][n]OFF (the letters are consumed even
 * when "OFF" does not follow; without "OFF" the file is headerless and must
 * go on with a digit; 'n': a dimension follows), then the vertex, face and
 * edge counts. Files Assimp refuses before allocating (no digit, a count of
 * 0, a dimension above 3, less than 8 bytes) are left to it. Then the size
 * check (a line takes at least one byte and a line break, so the bytes after
 * the vertex count must number at least 2 (V + F) - 1), the element limit,
 * and the walk over the vertex and face lines (off_walk). */
static px_status check_off(const io_head *h, px_error *err) {
    off_text t;
    memset(&t, 0, sizeof t);
    if (h->len >= 2 &&
        ((h->data[0] == 0xFE && h->data[1] == 0xFF) || (h->data[0] == 0xFF && h->data[1] == 0xFE)))
        return pxi_error(err, PX_ERR_IO,
                         "mesh file '%s' starts with a UTF-16 byte-order mark, which Assimp 5.2's OFF reader "
                         "mishandles: save it as ASCII or UTF-8",
                         h->path);
    if (h->size < 8) return PX_OK; /* ConvertToUTF8: "File is too small" */
    t.skip = has_utf8_bom(h) ? 3 : 0;
    t.d = h->data + t.skip;
    t.n = h->len - (size_t)t.skip;
    t.total = h->size - t.skip;
    const u64 end = t.total + 1;
    u64 c = 0;
    off_next_token(&t, &c);
    int has_dim = 0;
    if (c + 2 < end && off_at(&t, c) == 'S' && off_at(&t, c + 1) == 'T') c += 2;
    if (c + 1 < end && off_at(&t, c) == 'C') ++c;
    if (c + 1 < end && off_at(&t, c) == 'N') ++c;
    if (c + 1 < end && off_at(&t, c) == '4') ++c;
    if (c + 1 < end && off_at(&t, c) == 'n') has_dim = 1, ++c;
    unsigned dims = 3;
    if (c + 3 < end && off_at(&t, c) == 'O' && off_at(&t, c + 1) == 'F' && off_at(&t, c + 2) == 'F') {
        c += 3;
        off_next_token(&t, &c);
    } else {
        /* Headerless: Assimp resets the dimension to 3 but still reads one
         * after an 'n'. */
        off_next_token(&t, &c);
        if (c + 1 >= end || off_at(&t, c) < '0' || off_at(&t, c) > '9') goto head_or_ok;
    }
    if (has_dim) {
        dims = off_strtoul10(&t, &c, NULL);
        off_next_token(&t, &c);
    }
    if (dims > 3) goto head_or_ok;
    off_next_token(&t, &c);
    u64 nv_sat, nf_sat;
    const unsigned nv = off_strtoul10(&t, &c, &nv_sat);
    const u64 after_nv = t.skip + c;
    off_next_token(&t, &c);
    const unsigned nf = off_strtoul10(&t, &c, &nf_sat);
    off_next_token(&t, &c);
    (void)off_strtoul10(&t, &c, NULL);
    off_next_token(&t, &c);
    if (t.beyond)
        return pxi_error(err, PX_ERR_IO,
                         "mesh file '%s': the OFF header does not end within its first %d bytes", h->path,
                         HEAD_BYTES);
    if (nv_sat == 0 || nf_sat == 0) return PX_OK; /* Assimp: "There are no valid vertices/faces" */
    const u64 avail = h->size - after_nv;
    if (sat_mul(2, nv_sat) - 1 > avail)
        return pxi_error(err, PX_ERR_IO,
                         "mesh file '%s' declares %llu vertices but has only %llu bytes "
                         "(an OFF vertex takes a line of at least 2 bytes)",
                         h->path, nv_sat, h->size);
    if (sat_mul(2, sat_add(nv_sat, nf_sat)) - 1 > avail)
        return pxi_error(err, PX_ERR_IO,
                         "mesh file '%s' declares %llu vertices and %llu faces but has only %llu bytes "
                         "(an OFF vertex or face takes a line of at least 2 bytes)",
                         h->path, nv_sat, nf_sat, h->size);
    if (sat_add(nv_sat, nf_sat) > PX_IO_MAX_ELEMENTS) return err_too_many(h, sat_add(nv_sat, nf_sat), err);
    return off_walk(h, &t, c, nv, nf, err);
head_or_ok:
    if (t.beyond)
        return pxi_error(err, PX_ERR_IO,
                         "mesh file '%s': the OFF header does not end within its first %d bytes", h->path,
                         HEAD_BYTES);
    return PX_OK;
}

/* ------------------------------------------------------------------ STL */

/* The little-endian 32-bit unsigned integer at b. */
static u64 read_u32le(const unsigned char *b) {
    return (u64)b[0] | (u64)b[1] << 8 | (u64)b[2] << 16 | (u64)b[3] << 24;
}

/* 1 if the head looks like ASCII STL: "solid" after blank space (and a
 * UTF-8 byte-order mark), and no control byte other than blank space in the
 * first 512 bytes. A binary STL's header may also start with "solid", but its
 * triangle count and coordinates hold NUL and control bytes. */
/* Whether the file's first 512 bytes are text that starts (after blank
 * space) with `solid` in lower case (ascii 1) or in another case (ascii 2:
 * Assimp 5.2 compares case-sensitively and reads "SOLID" as binary). */
static int stl_text_kind(const io_head *h) {
    size_t p = has_utf8_bom(h) ? 3 : 0;
    for (size_t i = p; i < h->len && i < 512; ++i)
        if (h->data[i] < ' ' && !(h->data[i] >= '\t' && h->data[i] <= '\r')) return 0;
    while (p < h->len && (h->data[p] == ' ' || (h->data[p] >= '\t' && h->data[p] <= '\r'))) ++p;
    if (h->len - p < 5) return 0;
    if (memcmp(h->data + p, "solid", 5) == 0) return 1;
    for (int k = 0; k < 5; ++k)
        if (pxi_lower(h->data[p + k]) != "solid"[k]) return 0;
    return 2;
}

static int stl_is_ascii(const io_head *h) { return stl_text_kind(h) == 1; }

/* STL. Assimp reads a file as binary when (84 + 50 n) mod 2^32 equals its
 * size mod 2^32, n being the 32-bit count at byte 80 of its buffer (which
 * starts after a UTF-8 byte-order mark, while the size still includes it).
 * Such a file must then really hold n triangles: exactly 84 + 50 n bytes, no
 * byte-order mark, and 4 n (3 vertices and a face per triangle) within
 * PX_IO_MAX_ELEMENTS. Otherwise Assimp parses ASCII STL, which has no counts
 * and is walked as Assimp reads it (stl.c);
 * a `.stl` file (by_extension) must then be ASCII (stl_is_ascii), so that a
 * truncated or padded binary STL is reported as such instead of being parsed
 * as text. Files sniffed as STL get the binary checks, and the walk when
 * they start with `solid`: otherwise they may well be another format. */
static px_status check_stl(const io_head *h, int by_extension, px_error *err) {
    const size_t skip = has_utf8_bom(h) ? 3 : 0;
    if (h->size >= 84 && h->len >= 84 + skip) {
        const u64 n = read_u32le(h->data + 80 + skip);
        if (((84 + 50 * n) & 0xFFFFFFFFu) == (h->size & 0xFFFFFFFFu)) {
            if (skip)
                return pxi_error(err, PX_ERR_IO,
                                 "mesh file '%s': a binary STL that starts with a UTF-8 byte-order mark "
                                 "(Assimp 5.2 would read past its end)",
                                 h->path);
            if (84 + 50 * n != h->size)
                return pxi_error(
                    err, PX_ERR_IO,
                    "mesh file '%s' declares %llu triangles but has only %llu bytes (a binary STL of "
                    "that many has 84 + 50 * %llu = %llu)",
                    h->path, n, h->size, n, 84 + 50 * n);
            if (4 * n > PX_IO_MAX_ELEMENTS) return err_too_many(h, 4 * n, err);
            return PX_OK;
        }
    }
    /* A .stl file of text whose `solid` is not in lower case (and that is
     * no binary STL of the right size): Assimp 5.2 would not read it as
     * ASCII. (Another name picks another importer: an OBJ whose first line
     * is "Solid model ..." is an OBJ.) */
    if (by_extension && stl_text_kind(h) == 2)
        return pxi_error(err, PX_ERR_IO,
                         "mesh file '%s': an ASCII STL with keywords not in lower case ('SOLID', 'FACET'): "
                         "Assimp 5.2 reads them in lower case only; write them so",
                         h->path);
    if (!by_extension || stl_is_ascii(h)) {
        /* Text Assimp reads as ASCII STL: `solid` after spaces and tabs. */
        size_t p = skip;
        while (p < h->len && (h->data[p] == ' ' || h->data[p] == '\t')) ++p;
        if (h->len - p > 5 && memcmp(h->data + p, "solid", 5) == 0) return pxi_check_stl_ascii(h, err);
        return PX_OK;
    }
    if (h->size < 84)
        return pxi_error(
            err, PX_ERR_IO,
            "mesh file '%s' is neither ASCII STL nor binary STL (%llu bytes, less than the 84 of a "
            "binary STL header)",
            h->path, h->size);
    const u64 n = read_u32le(h->data + 80);
    if (skip && 84 + 50 * n == h->size)
        return pxi_error(err, PX_ERR_IO,
                         "mesh file '%s': a binary STL whose header starts with a UTF-8 byte-order mark "
                         "(Assimp 5.2 drops those 3 bytes and misreads the file)",
                         h->path);
    return pxi_error(err, PX_ERR_IO,
                     "mesh file '%s' is not ASCII STL, and as binary STL it declares %llu triangles, which "
                     "take 84 + 50 * %llu = %llu bytes, but has %llu bytes",
                     h->path, n, n, 84 + 50 * n, h->size);
}

/* ------------------------------------------------ unchecked formats */

/* Importers of Assimp 5.2 that size arrays by counts written in the body of
 * the file, anywhere, any number of times, so that no check of a header can
 * bound them (measured: 100 to 300-byte files declaring 1e8 vertices commit
 * 1.1 to 1.5 GB): DirectX X ("Mesh { n;", also MeshNormals and others), ASE
 * ("*MESH_NUMVERTEX n"), MD5 ("numverts n"), NFF ("pp n") and Caligari COB
 * ("World Vertices n"). They are refused by extension, and X, ASE and MD5
 * also by the signature Assimp would detect them by (NFF and COB are
 * recognised by extension only). */
static const struct {
    const char *ext;
    const char *format;
} k_unchecked[] = {{"x", "DirectX"},        {"ase", "ASE"},         {"ask", "ASE"}, {"md5mesh", "MD5"},
                   {"md5anim", "MD5"},      {"md5camera", "MD5"},   {"nff", "NFF"}, {"enff", "NFF"},
                   {"cob", "Caligari COB"}, {"scn", "Caligari COB"}};

/* 1 if the file ends like a ZIP archive: minizip's unzOpen (behind Assimp's
 * ZipArchiveIOSystem) looks for the end-of-central-directory signature
 * PK 05 06 in the last 64 KiB + 22 bytes, wherever the archive starts.
 * -1 when out of memory. */
static int zip_tail(const io_head *h) {
    const u64 span = 65536 + 22;
    u64 n = h->size < span ? h->size : span;
    unsigned char *tail = pxi_alloc(h->alloc, (size_t)n);
    int found = 0;
    if (!tail) return -1;
    pxi_rd_seek(h->rd, h->size - n);
    if (pxi_rd_read(h->rd, tail, (size_t)n))
        for (size_t i = 0; i + 4 <= n && !found; ++i)
            found = tail[i] == 'P' && tail[i + 1] == 'K' && tail[i + 2] == 5 && tail[i + 3] == 6;
    pxi_free(h->alloc, tail, (size_t)n);
    return found;
}

/* Refuses the formats of k_unchecked, and files starting with 00 00 FE FF or
 * FE FF 00 00: Assimp 5.2's BaseImporter::ConvertToUTF8 (used by most text
 * importers) takes them for UTF-32 byte-order marks and then swaps or reads
 * bytes past the end of its buffer (seen with valgrind). */
static px_status check_unchecked(const io_head *h, px_error *err) {
    const char *format = NULL;
    for (size_t i = 0; i < sizeof k_unchecked / sizeof k_unchecked[0] && !format; ++i)
        if (strcmp(h->ext, k_unchecked[i].ext) == 0) format = k_unchecked[i].format;
    if (!format && starts_with_ci(h, "xof ")) format = "DirectX";
    if (!format && signature_has(h, "*3dsmax_asciiexport")) format = "ASE";
    if (!format && signature_has(h, "md5version")) format = "MD5";
    /* ZIP containers: Assimp's COLLADA importer reads any archive with a
     * .dae in it (also under .dae, or another name no importer claims), 3MF,
     * Quake 3 BSP and IFC ones theirs; the files inside, inflated to the
     * sizes the archive declares, are never seen here. */
    static const char *const zip_exts[] = {"zae", "3mf", "pk3", "ifczip"};
    int zip = 0;
    for (size_t i = 0; i < sizeof zip_exts / sizeof zip_exts[0]; ++i) zip |= strcmp(h->ext, zip_exts[i]) == 0;
    static const char *const plain_exts[] = {"obj", "stl", "ply", "off", "gltf", "glb", "fbx"};
    int plain = 0;
    for (size_t i = 0; i < sizeof plain_exts / sizeof plain_exts[0]; ++i)
        plain |= strcmp(h->ext, plain_exts[i]) == 0;
    if (!format && !zip && h->len >= 4 && memcmp(h->data, "PK\x03\x04", 4) == 0) zip = 1;
    if (!format && !zip && !plain && (zip = zip_tail(h)) < 0)
        return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "mesh file '%s': out of memory reading its last 64 KiB",
                         h->path);
    if (h->rd->error) return pxi_rd_error(h, err);
    if (!format && zip)
        return pxi_error(err, PX_ERR_IO,
                         "mesh file '%s' is a ZIP archive (ZAE, 3MF, ...), which is not accepted: the files "
                         "Assimp 5.2 would inflate from it cannot be checked; extract the model",
                         h->path);
    if (format)
        return pxi_error(
            err, PX_ERR_IO,
            "mesh file '%s': %s files are not accepted (Assimp 5.2 sizes arrays by counts in them "
            "without checking them against the file): convert it to OBJ, PLY, STL or glTF",
            h->path, format);
    static const unsigned char utf32_be[4] = {0, 0, 0xFE, 0xFF}, utf32_le[4] = {0xFE, 0xFF, 0, 0};
    if (h->len >= 4 && (memcmp(h->data, utf32_be, 4) == 0 || memcmp(h->data, utf32_le, 4) == 0))
        return pxi_error(err, PX_ERR_IO,
                         "mesh file '%s' starts with what Assimp 5.2 takes for a UTF-32 byte-order mark "
                         "(it then reads past its buffer): save it as ASCII or UTF-8",
                         h->path);
    return PX_OK;
}

/* Compressed files Assimp 5.2 inflates whole into memory before reading
 * them, with no bound but the memory it gets: XGL's importer a .zgl file
 * (raw deflate), the Blender importer a gzip stream (a 3 MB .blend of
 * 3 GiB of zeros, and a 3 MB .zgl, ended in std::bad_alloc after 1 GB,
 * under a 2 GiB address-space limit). The size they inflate to is not
 * written anywhere reliable (gzip's trailer holds it modulo 2^32, unchecked),
 * so they are refused. */
static px_status check_compressed(const io_head *h, px_error *err) {
    if (strcmp(h->ext, "zgl") == 0)
        return pxi_error(err, PX_ERR_IO,
                         "mesh file '%s': ZGL (compressed XGL) files are not accepted (Assimp 5.2 inflates "
                         "them whole, unchecked): decompress it to .xgl",
                         h->path);
    const int gzip = h->len >= 2 && h->data[0] == 0x1F && h->data[1] == 0x8B;
    if (gzip && (strcmp(h->ext, "blend") == 0 || signature_has(h, "blender")))
        return pxi_error(err, PX_ERR_IO,
                         "mesh file '%s': compressed (gzip) Blender files are not accepted (Assimp 5.2 "
                         "inflates them whole, unchecked): save it uncompressed",
                         h->path);
    return PX_OK;
}

/* ---------------------------------------------------------------- entry */

/* Lowercased extension of the file name in `path` (after the last '.' of
 * the last path component), or "" if there is none or it is too long. */
static void file_extension(const char *path, char *ext, size_t size) {
    const char *name = path;
    for (const char *c = path; *c; ++c)
        if (*c == '/' || *c == '\\') name = c + 1;
    const char *dot = strrchr(name, '.');
    ext[0] = '\0';
    if (!dot || strlen(dot + 1) >= size) return;
    size_t i = 0;
    for (const char *c = dot + 1; *c; ++c) ext[i++] = (char)lower((unsigned char)*c);
    ext[i] = '\0';
}

/* Runs the checks of every format Assimp could read the file as. */
static px_status check_formats(const io_head *h, px_error *err) {
    const int off = strcmp(h->ext, "off") == 0, ply = strcmp(h->ext, "ply") == 0,
              stl = strcmp(h->ext, "stl") == 0, dae = strcmp(h->ext, "dae") == 0,
              gltf = strcmp(h->ext, "gltf") == 0 || strcmp(h->ext, "glb") == 0;
    px_status st = check_unchecked(h, err);
    if (st == PX_OK) st = check_compressed(h, err);
    if (st == PX_OK && (off || starts_with_ci(h, "off"))) st = check_off(h, err);
    if (st == PX_OK && strcmp(h->ext, "obj") == 0) st = pxi_check_obj(h, err);
    /* PLYImporter::CanRead: "ply" anywhere in the signature bytes. */
    if (st == PX_OK && (ply || signature_has(h, "ply"))) st = pxi_check_ply(h, err);
    if (st == PX_OK && (stl || signature_has(h, "solid") || signature_has(h, "stl")))
        st = check_stl(h, stl, err);
    /* ColladaLoader::CanRead: "<collada" in the signature bytes. */
    if (st == PX_OK && (dae || signature_has(h, "<collada"))) st = pxi_check_dae(h, err);
    /* glTF: by name, "glTF" binary magic, or JSON with an "asset" member. */
    /* glTF: by name, by the binary magic, or any JSON object (the glTF
     * importers' signature test parses the whole document). */
    size_t b = has_utf8_bom(h) ? 3 : 0;
    while (b < h->len &&
           (h->data[b] == ' ' || h->data[b] == '\t' || h->data[b] == '\n' || h->data[b] == '\r'))
        ++b;
    if (st == PX_OK && (gltf || starts_with_ci(h, "gltf") || (b < h->len && h->data[b] == '{')))
        st = pxi_check_gltf(h, err);
    /* AC3D, FBX, OpenGEX and XML nesting; BVH refused (nest.c). */
    if (st == PX_OK) st = pxi_check_nesting(h, err);
    return st;
}

/* The precheck (obj_again 0: *id is filled), or the OBJ checks alone on
 * the file *id identifies (obj_again 1). */
static px_status precheck(const char *path, const px_allocator *alloc, pxi_file_id *id, int obj_again,
                          px_error *err) {
    /* stat() first: open() of a FIFO would block (O_NONBLOCK below covers one
     * put in its place meanwhile), and a device has no size. */
    struct stat sb, fsb;
    const pxi_file_id expect = *id;
    memset(id, 0, sizeof *id);
    if (stat(path, &sb) != 0) {
        int e = errno;
        return pxi_error(err, PX_ERR_IO, "cannot open mesh file '%s': %s", path, strerror(e));
    }
    if (S_ISDIR(sb.st_mode))
        return pxi_error(err, PX_ERR_IO, "cannot read mesh file '%s': %s", path, strerror(EISDIR));
    if (!S_ISREG(sb.st_mode))
        return pxi_error(err, PX_ERR_IO, "mesh file '%s' is not a regular file (a device, pipe or socket)",
                         path);
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        int e = errno;
        return pxi_error(err, PX_ERR_IO, "cannot open mesh file '%s': %s", path, strerror(e));
    }
    if (fstat(fd, &fsb) != 0 || !S_ISREG(fsb.st_mode) || fsb.st_dev != sb.st_dev || fsb.st_ino != sb.st_ino) {
        close(fd);
        return pxi_error(err, PX_ERR_IO, "mesh file '%s' was replaced while being opened", path);
    }
    io_head h;
    memset(&h, 0, sizeof h);
    id->gltf_triangles = ~0ull;
    h.gltf_triangles = &id->gltf_triangles;
    id->off_dropped_faces = 0;
    h.off_dropped_faces = &id->off_dropped_faces;
    h.path = path;
    h.size = (u64)fsb.st_size;
    h.alloc = alloc;
    file_extension(path, h.ext, sizeof h.ext);
    if (h.size == 0) {
        close(fd);
        return pxi_error(err, PX_ERR_IO, "mesh file '%s' is empty", path);
    }
    if (h.size > PX_IO_MAX_FILE_BYTES) {
        close(fd);
        return pxi_error(err, PX_ERR_IO, "mesh file '%s' has %llu bytes, more than the limit of %llu", path,
                         h.size, (u64)PX_IO_MAX_FILE_BYTES);
    }
    id->dev = (u64)fsb.st_dev;
    id->ino = (u64)fsb.st_ino;
    id->size = h.size;
    id->mtime_sec = (long long)fsb.st_mtim.tv_sec;
    id->mtime_nsec = (long long)fsb.st_mtim.tv_nsec;
    if (obj_again) {
        const int same = id->dev == expect.dev && id->ino == expect.ino && id->size == expect.size &&
                         id->mtime_sec == expect.mtime_sec && id->mtime_nsec == expect.mtime_nsec;
        *id = expect;
        if (!same) {
            close(fd);
            return pxi_error(err, PX_ERR_IO, "mesh file '%s' changed while it was read", path);
        }
    }
    io_reader rd;
    memset(&rd, 0, sizeof rd);
    rd.fd = fd;
    rd.size = h.size;
    rd.buf = pxi_alloc(alloc, PXI_IO_READER_BYTES);
    h.len = h.size < HEAD_BYTES ? (size_t)h.size : HEAD_BYTES;
    unsigned char *head = pxi_alloc(alloc, h.len);
    px_status st = PX_OK;
    if (!rd.buf || !head) {
        st = pxi_error(err, PX_ERR_OUT_OF_MEMORY, "out of memory reading mesh file '%s'", path);
    } else {
        h.rd = &rd;
        if (!pxi_rd_read(&rd, head, h.len)) {
            st = pxi_rd_error(&h, err);
        } else {
            h.data = head;
            st = obj_again ? pxi_check_obj(&h, err) : check_formats(&h, err);
        }
    }
    if (head) pxi_free(alloc, head, h.len);
    if (rd.buf) pxi_free(alloc, rd.buf, PXI_IO_READER_BYTES);
    close(fd);
    return st;
}

px_status pxi_io_precheck(const char *path, const px_allocator *alloc, pxi_file_id *id, px_error *err) {
    memset(id, 0, sizeof *id);
    return precheck(path, alloc, id, 0, err);
}

px_status pxi_io_check_as_obj(const char *path, const px_allocator *alloc, const pxi_file_id *id,
                              px_error *err) {
    pxi_file_id again = *id;
    return precheck(path, alloc, &again, 1, err);
}
