/* Allocation hooks and error reporting shared by every layer (internal). */
#ifndef PXI_CORE_H
#define PXI_CORE_H

#include <stddef.h>

#include "proxima/proxima.h"

/* All allocations of proxima objects go through these (px_set_allocator).
 * pxi_alloc_array checks count * size for overflow and returns NULL on it. */
void *pxi_alloc(size_t size);
void *pxi_alloc_array(size_t count, size_t size);
void pxi_free(void *ptr, size_t size);

/* Fills err (may be NULL) with code and a printf-style message; returns code. */
px_status pxi_error(px_error *err, px_status code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

#endif
