/* Allocators and errors (internal helpers; compiled into each shared
 * library that needs them, hidden there). */
#include "core/core.h"

#include <stdatomic.h>

#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void *default_alloc(void *user, size_t size) {
    (void)user;
    return malloc(size);
}
static void default_free(void *user, void *ptr, size_t size) {
    (void)user;
    (void)size;
    free(ptr);
}

px_status pxi_allocator_resolve(const px_allocator *user, px_allocator *out, px_error *err) {
    if (!user) {
        out->alloc = default_alloc;
        out->free = default_free;
        out->user = NULL;
        return PX_OK;
    }
    if (!user->alloc || !user->free)
        return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "allocator: both alloc and free must be set");
    *out = *user;
    return PX_OK;
}

void *pxi_alloc(const px_allocator *a, size_t size) { return a->alloc(a->user, size == 0 ? 1 : size); }

void *pxi_alloc_array(const px_allocator *a, size_t count, size_t size) {
    if (size != 0 && count > SIZE_MAX / size) return NULL;
    return pxi_alloc(a, count * size);
}

void pxi_free(const px_allocator *a, void *ptr, size_t size) {
    if (ptr) a->free(a->user, ptr, size == 0 ? 1 : size);
}

px_status pxi_error(px_error *err, px_status code, const char *fmt, ...) {
    if (err) {
        err->code = code;
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err->message, sizeof err->message, fmt, ap);
        va_end(ap);
    }
    return code;
}

uint64_t pxi_next_uid(void) {
    static _Atomic uint64_t last = 0;
    return atomic_fetch_add(&last, 1) + 1;
}
