/* The buffered reader the checks of a mesh file stream through (scan.h). */
#define _POSIX_C_SOURCE 200809L /* pread */

#include "io/scan.h"

#include <errno.h>
#include <string.h>
#include <unistd.h>

#include "core/core.h"

void pxi_rd_seek(io_reader *r, u64 off) {
    if (off > r->size) off = r->size;
    if (off >= r->base && off <= r->base + r->len) {
        r->at = (size_t)(off - r->base);
        return;
    }
    r->base = off;
    r->len = 0;
    r->at = 0;
}

size_t pxi_rd_fill(io_reader *r) {
    if (r->error) return 0;
    r->base += r->at;
    r->len = 0;
    r->at = 0;
    u64 left = r->size - r->base;
    size_t want = left < PXI_IO_READER_BYTES ? (size_t)left : PXI_IO_READER_BYTES;
    while (r->len < want) {
        ssize_t got = pread(r->fd, r->buf + r->len, want - r->len, (off_t)(r->base + r->len));
        if (got < 0 && errno == EINTR) continue;
        if (got <= 0) {
            /* A short file is reported, not read as a shorter one. */
            r->error = got < 0 ? errno : -1;
            r->len = 0;
            return 0;
        }
        r->len += (size_t)got;
    }
    return r->len;
}

int pxi_rd_read(io_reader *r, void *out, size_t n) {
    unsigned char *o = out;
    while (n) {
        if (r->at >= r->len && !pxi_rd_fill(r)) return 0;
        size_t k = r->len - r->at < n ? r->len - r->at : n;
        memcpy(o, r->buf + r->at, k);
        r->at += k;
        o += k;
        n -= k;
    }
    return 1;
}

int pxi_rd_skip(io_reader *r, u64 n) {
    u64 pos = pxi_rd_tell(r);
    if (n > r->size - pos) return 0;
    pxi_rd_seek(r, pos + n);
    return 1;
}

px_status pxi_rd_error(const io_head *h, px_error *err) {
    if (h->rd->error > 0)
        return pxi_error(err, PX_ERR_IO, "cannot read mesh file '%s': %s", h->path, strerror(h->rd->error));
    return pxi_error(err, PX_ERR_IO, "cannot read mesh file '%s': it became shorter while being read",
                     h->path);
}

px_status pxi_read_all(const io_head *h, unsigned char **out, px_error *err) {
    *out = NULL;
    if (h->size >= (u64)((size_t)-1)) /* 32-bit size_t */
        return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "out of memory reading mesh file '%s'", h->path);
    unsigned char *buf = pxi_alloc(h->alloc, (size_t)h->size + 1);
    if (!buf) return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "out of memory reading mesh file '%s'", h->path);
    pxi_rd_seek(h->rd, 0);
    if (!pxi_rd_read(h->rd, buf, (size_t)h->size)) {
        pxi_free(h->alloc, buf, (size_t)h->size + 1);
        return pxi_rd_error(h, err);
    }
    buf[h->size] = '\0';
    *out = buf;
    return PX_OK;
}

/* Assimp's signature test (SearchFileHeaderForToken with default arguments):
 * 1 if lowercase `token` occurs in the first 200 bytes, lowercased, once the
 * NUL bytes are removed. */
int pxi_signature_has(const io_head *h, const char *token) {
    char buf[200 + 1];
    size_t n = 0;
    for (size_t i = 0; i < h->len && i < 200; ++i)
        if (h->data[i]) buf[n++] = (char)pxi_lower(h->data[i]);
    buf[n] = '\0';
    return strstr(buf, token) != NULL;
}
