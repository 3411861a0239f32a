/* Allocator hook and error helpers. */
#include "core/core.h"

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

/* The one piece of global state: the allocation hooks (documented in proxima.h). */
static px_allocator g_allocator = {default_alloc, default_free, NULL};

void px_set_allocator(const px_allocator *allocator) {
    if (allocator && allocator->alloc && allocator->free) {
        g_allocator = *allocator;
    } else {
        g_allocator.alloc = default_alloc;
        g_allocator.free = default_free;
        g_allocator.user = NULL;
    }
}

void *pxi_alloc(size_t size) {
    if (size == 0) size = 1;
    return g_allocator.alloc(g_allocator.user, size);
}

void *pxi_alloc_array(size_t count, size_t size) {
    if (size != 0 && count > SIZE_MAX / size) return NULL;
    return pxi_alloc(count * size);
}

void pxi_free(void *ptr, size_t size) {
    if (ptr) g_allocator.free(g_allocator.user, ptr, size == 0 ? 1 : size);
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

const char *px_status_string(px_status status) {
    switch (status) {
    case PX_OK: return "PX_OK";
    case PX_ERR_INVALID_ARGUMENT: return "PX_ERR_INVALID_ARGUMENT";
    case PX_ERR_NON_FINITE: return "PX_ERR_NON_FINITE";
    case PX_ERR_DEGENERATE: return "PX_ERR_DEGENERATE";
    case PX_ERR_INVALID_POSE: return "PX_ERR_INVALID_POSE";
    case PX_ERR_OUT_OF_MEMORY: return "PX_ERR_OUT_OF_MEMORY";
    case PX_ERR_IO: return "PX_ERR_IO";
    case PX_ERR_INTERNAL: return "PX_ERR_INTERNAL";
    }
    return "PX_ERR_UNKNOWN";
}
