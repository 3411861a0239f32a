/* Allocation and error helpers shared by every layer (internal). */
#ifndef PXI_CORE_H
#define PXI_CORE_H

#include <stddef.h>

#include "proxima/base.h"

/* The allocator an object uses: the caller's (validated) or malloc/free.
 * Returns PX_ERR_INVALID_ARGUMENT (with a message in err) when the caller's
 * lacks a function. */
px_status pxi_allocator_resolve(const px_allocator *user, px_allocator *out, px_error *err);

/* Allocations through an allocator. pxi_alloc_array checks count * size for
 * overflow and returns NULL on it. A size of 0 allocates 1 byte. */
void *pxi_alloc(const px_allocator *a, size_t size);
void *pxi_alloc_array(const px_allocator *a, size_t count, size_t size);
void pxi_free(const px_allocator *a, void *ptr, size_t size);

/* A number never handed out before in this process (1, 2, ...): the
 * identity of a polytope or model, which its address is not (a new one may
 * be built where a destroyed one was). Thread-safe. */
uint64_t pxi_next_uid(void);

/* Fills err (may be NULL) with code and a printf-style message; returns code. */
px_status pxi_error(px_error *err, px_status code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* The success state of an error: PX_OK and an empty message. */
static inline void pxi_error_clear(px_error *err) {
    if (!err) return;
    err->code = PX_OK;
    err->message[0] = '\0';
}

#endif
