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
 * smallest size its format allows, and the bodies of PLY files are walked
 * the way Assimp walks them (ply.c): a file refused here cannot be a valid
 * file of its format, would make Assimp 5.2 hang or read outside its
 * buffers, or exceeds a documented limit (io.h).
 * Passing is no proof of validity: Assimp still parses the file.
 *
 * The file is opened once, without blocking (stat() first, then O_NONBLOCK),
 * and identified (device, inode, size, modification time): fs.c makes
 * Assimp's own opens of it find this same file. The first 64 KiB (the head)
 * are read for the headers; the PLY walk streams through the rest.
 *
 * Which checks run. Assimp 5.2 picks the importer by the extension of the
 * file name when exactly one importer claims it; otherwise it asks each
 * importer whether it recognises the file's first bytes (for text formats,
 * BaseImporter::SearchFileHeaderForToken: the first 200 bytes, lowercased,
 * NUL bytes removed, searched for tokens). A check runs when the extension
 * names its format, or when the head matches a superset of that importer's
 * signature test, so every file Assimp could hand to the OFF, PLY or STL
 * importer is checked.
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
#define SIGNATURE_BYTES 200          /* what Assimp's SearchFileHeaderForToken reads */

#define sat_add pxi_sat_add
#define sat_mul pxi_sat_mul
#define lower pxi_lower

/* 1 if the file starts with `s` (ASCII letters compared case-insensitively). */
static int starts_with_ci(const io_head *h, const char *s) {
    size_t n = strlen(s);
    if (h->len < n) return 0;
    for (size_t i = 0; i < n; ++i)
        if (lower(h->data[i]) != lower((unsigned char)s[i])) return 0;
    return 1;
}

/* Assimp's signature test (SearchFileHeaderForToken with default arguments):
 * 1 if lowercase `token` occurs in the first 200 bytes, lowercased, once the
 * NUL bytes are removed. */
static int signature_has(const io_head *h, const char *token) {
    char buf[SIGNATURE_BYTES + 1];
    size_t n = 0;
    for (size_t i = 0; i < h->len && i < SIGNATURE_BYTES; ++i)
        if (h->data[i]) buf[n++] = (char)lower(h->data[i]);
    buf[n] = '\0';
    return strstr(buf, token) != NULL;
}

/* 1 if the file starts with a UTF-8 byte-order mark (EF BB BF). */
static int has_utf8_bom(const io_head *h) {
    return h->len >= 3 && h->data[0] == 0xEF && h->data[1] == 0xBB && h->data[2] == 0xBF;
}

/* Reads the decimal digits at data[*pos] on (none: 0), saturating, like
 * Assimp's strtoul10 but without its 32-bit wrap-around; advances *pos. */
static u64 read_count(const io_head *h, size_t *pos) {
    u64 v = 0;
    size_t i = *pos;
    for (; i < h->len && h->data[i] >= '0' && h->data[i] <= '9'; ++i)
        v = sat_add(sat_mul(v, 10), (u64)(h->data[i] - '0'));
    *pos = i;
    return v;
}

/* The PX_ERR_IO for a total of declared elements above PX_IO_MAX_ELEMENTS. */
static px_status err_too_many(const io_head *h, u64 total, px_error *err) {
    return pxi_error(err, PX_ERR_IO, "mesh file '%s' declares %llu elements, more than the limit of %llu",
                     h->path, total, (u64)PX_IO_MAX_ELEMENTS);
}

/* ------------------------------------------------------------------ OFF */

/* Skips what Assimp's OFF NextToken skips: blank space and '#' comment
 * lines. Every byte up to ' ' counts as blank here (a superset of Assimp's
 * set), so the digits found next are the ones Assimp reads, or Assimp reads
 * none (count 0: it refuses the file). */
static void off_skip(const io_head *h, size_t *pos) {
    size_t i = *pos;
    for (;;) {
        while (i < h->len && h->data[i] <= ' ') ++i;
        if (i >= h->len || h->data[i] != '#') break;
        while (i < h->len && h->data[i] != '\n' && h->data[i] != '\r') ++i;
    }
    *pos = i;
}

/* OFF: optional blank space and comments, the keyword [ST][C][N][4][n]OFF
 * ('n': a dimension follows; a headerless file, accepted by extension, has
 * none), then the vertex, face and edge counts, then one line per vertex and
 * per face. A line takes at least one byte and a line break, so the bytes
 * after the vertex count must number at least 2 (V + F) - 1. Files sniffed as
 * OFF (by_extension 0) that are not OFF are left to Assimp, which refuses them
 * before allocating, as it does a zero count. */
static px_status check_off(const io_head *h, int by_extension, px_error *err) {
    const unsigned char *d = h->data;
    const size_t n = h->len;
    size_t p = has_utf8_bom(h) ? 3 : 0; /* Assimp's TextFileToBuffer drops it */
    off_skip(h, &p);
    /* Assimp consumes these letters even when "OFF" does not follow. */
    int has_dim = 0;
    if (p + 2 < n && d[p] == 'S' && d[p + 1] == 'T') p += 2;
    if (p + 1 < n && d[p] == 'C') ++p;
    if (p + 1 < n && d[p] == 'N') ++p;
    if (p + 1 < n && d[p] == '4') ++p;
    if (p + 1 < n && d[p] == 'n') {
        has_dim = 1;
        ++p;
    }
    if (p + 3 <= n && memcmp(d + p, "OFF", 3) == 0)
        p += 3;
    else if (!by_extension)
        return PX_OK;
    off_skip(h, &p);
    if (has_dim) {
        (void)read_count(h, &p);
        off_skip(h, &p);
    }
    const u64 nv = read_count(h, &p);
    const size_t after_nv = p;
    off_skip(h, &p);
    const u64 nf = read_count(h, &p);
    if (p >= n && n < h->size)
        return pxi_error(err, PX_ERR_IO,
                         "mesh file '%s': the OFF header does not end within its first %d bytes", h->path,
                         HEAD_BYTES);
    if (nv == 0 || nf == 0) return PX_OK;
    const u64 avail = h->size - after_nv;
    if (sat_mul(2, nv) - 1 > avail)
        return pxi_error(err, PX_ERR_IO,
                         "mesh file '%s' declares %llu vertices but has only %llu bytes "
                         "(an OFF vertex takes a line of at least 2 bytes)",
                         h->path, nv, h->size);
    if (sat_mul(2, sat_add(nv, nf)) - 1 > avail)
        return pxi_error(err, PX_ERR_IO,
                         "mesh file '%s' declares %llu vertices and %llu faces but has only %llu bytes "
                         "(an OFF vertex or face takes a line of at least 2 bytes)",
                         h->path, nv, nf, h->size);
    if (sat_add(nv, nf) > PX_IO_MAX_ELEMENTS) return err_too_many(h, sat_add(nv, nf), err);
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
static int stl_is_ascii(const io_head *h) {
    size_t p = has_utf8_bom(h) ? 3 : 0;
    for (size_t i = p; i < h->len && i < 512; ++i)
        if (h->data[i] < ' ' && !(h->data[i] >= '\t' && h->data[i] <= '\r')) return 0;
    while (p < h->len && (h->data[p] == ' ' || (h->data[p] >= '\t' && h->data[p] <= '\r'))) ++p;
    return h->len - p >= 5 && memcmp(h->data + p, "solid", 5) == 0;
}

/* STL. Assimp reads a file as binary when (84 + 50 n) mod 2^32 equals its
 * size mod 2^32, n being the 32-bit count at byte 80 of its buffer (which
 * starts after a UTF-8 byte-order mark, while the size still includes it).
 * Such a file must then really hold n triangles: exactly 84 + 50 n bytes, no
 * byte-order mark, and 4 n (3 vertices and a face per triangle) within
 * PX_IO_MAX_ELEMENTS. Otherwise Assimp parses ASCII STL, which has no counts;
 * a `.stl` file (by_extension) must then be ASCII (stl_is_ascii), so that a
 * truncated or padded binary STL is reported as such instead of being parsed
 * as text. Files sniffed as STL get only the binary checks: they may well be
 * another format. */
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
    if (!by_extension || stl_is_ascii(h)) return PX_OK;
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
/* Runs the checks of every format Assimp could read the file as. */
static px_status check_formats(const io_head *h, px_error *err) {
    const int off = strcmp(h->ext, "off") == 0, ply = strcmp(h->ext, "ply") == 0,
              stl = strcmp(h->ext, "stl") == 0;
    px_status st = check_unchecked(h, err);
    if (st == PX_OK && (off || starts_with_ci(h, "off"))) st = check_off(h, off, err);
    /* PLYImporter::CanRead: "ply" anywhere in the signature bytes. */
    if (st == PX_OK && (ply || signature_has(h, "ply"))) st = pxi_check_ply(h, err);
    if (st == PX_OK && (stl || signature_has(h, "solid") || signature_has(h, "stl")))
        st = check_stl(h, stl, err);
    return st;
}

px_status pxi_io_precheck(const char *path, const px_allocator *alloc, pxi_file_id *id, px_error *err) {
    /* stat() first: open() of a FIFO would block (O_NONBLOCK below covers one
     * put in its place meanwhile), and a device has no size. */
    struct stat sb, fsb;
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
            st = check_formats(&h, err);
        }
    }
    if (head) pxi_free(alloc, head, h.len);
    if (rd.buf) pxi_free(alloc, rd.buf, PXI_IO_READER_BYTES);
    close(fd);
    return st;
}
