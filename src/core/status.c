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

/* The header's version is the project's (CMakeLists.txt: the soname,
 * pkg-config and the CMake package config take theirs from it); 0.3.0
 * shipped with 0.2.0 in base.h, which px_version() could not catch. */
#ifdef PXI_PROJECT_VERSION
_Static_assert(PX_VERSION == (PXI_PROJECT_VERSION), "PX_VERSION_* in base.h differ from project(VERSION)");
#endif

uint32_t px_version(void) { return PX_VERSION; }

const char *px_version_string(void) {
    return PXI_STR(PX_VERSION_MAJOR) "." PXI_STR(PX_VERSION_MINOR) "." PXI_STR(PX_VERSION_PATCH);
}
