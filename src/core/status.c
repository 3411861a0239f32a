/* Status names and the version (public). */
#include "proxima/base.h"

const char *px_status_string(px_status status) {
    switch (status) {
    case PX_OK: return "PX_OK";
    case PX_ERR_INVALID_ARGUMENT: return "PX_ERR_INVALID_ARGUMENT";
    case PX_ERR_NON_FINITE: return "PX_ERR_NON_FINITE";
    case PX_ERR_DEGENERATE: return "PX_ERR_DEGENERATE";
    case PX_ERR_INVALID_POSE: return "PX_ERR_INVALID_POSE";
    case PX_ERR_OUT_OF_MEMORY: return "PX_ERR_OUT_OF_MEMORY";
    case PX_ERR_IO: return "PX_ERR_IO";
    case PX_ERR_RANGE: return "PX_ERR_RANGE";
    case PX_ERR_INTERNAL: return "PX_ERR_INTERNAL";
    case PX_ERR_CANCELLED: return "PX_ERR_CANCELLED";
    }
    return "PX_ERR_UNKNOWN";
}

#define PXI_STR2(x) #x
#define PXI_STR(x) PXI_STR2(x)

uint32_t px_version(void) { return PX_VERSION; }

const char *px_version_string(void) {
    return PXI_STR(PX_VERSION_MAJOR) "." PXI_STR(PX_VERSION_MINOR) "." PXI_STR(PX_VERSION_PATCH);
}
