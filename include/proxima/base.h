/// proxima/base.h: what every part of the API shares: the export macro,
/// the version, statuses and errors, and the allocator.
///
/// Global state: the library keeps none, except one mutex that serialises
/// file imports (Assimp's error string is process-global; see io.h).
#ifndef PROXIMA_BASE_H
#define PROXIMA_BASE_H

#include <stddef.h>
#include <stdint.h>

/// Marks the library's exported symbols; everything else is hidden.
#if defined(_WIN32)
#if defined(PX_BUILDING_LIBRARY)
#define PX_API __declspec(dllexport)
#else
#define PX_API
#endif
#elif defined(__GNUC__) || defined(__clang__)
#define PX_API __attribute__((visibility("default")))
#else
#define PX_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

#define PX_VERSION_MAJOR 0
#define PX_VERSION_MINOR 3
#define PX_VERSION_PATCH 0
/// The version the headers describe, as one number (major, minor and patch
/// in 8 bits each). Compare it with `px_version()` to detect a header and
/// library mismatch.
#define PX_VERSION ((PX_VERSION_MAJOR << 16) | (PX_VERSION_MINOR << 8) | PX_VERSION_PATCH)

/// The version of the library linked at run time, encoded as PX_VERSION.
PX_API uint32_t px_version(void);

/// The same as "major.minor.patch"; never NULL.
PX_API const char *px_version_string(void);

/// Every fallible function returns one of these (or NULL plus a `px_error`).
typedef enum px_status {
    PX_OK = 0,
    PX_ERR_INVALID_ARGUMENT = 1, ///< NULL where not allowed, an index, count or option out of range
    PX_ERR_NON_FINITE = 2,       ///< NaN or Inf in coordinates, poses or directions
    PX_ERR_DEGENERATE = 3,       ///< geometry with no 3-D hull (flat, collinear, one point)
    PX_ERR_INVALID_POSE = 4,     ///< rotation is not orthonormal with det +1 (within 1e-6)
    PX_ERR_OUT_OF_MEMORY = 5,    ///< the allocator returned NULL, or a size overflowed
    PX_ERR_IO = 6,               ///< a file could not be read or is malformed
    PX_ERR_RANGE = 7,            ///< a number outside the supported range (see proxima/convex.h)
    PX_ERR_INTERNAL = 8,         ///< an invariant failed: a bug, please report it
    PX_ERR_CANCELLED = 9         ///< a progress callback asked to stop (long builds)
} px_status;

/// Filled by functions that can fail. On success `code` is PX_OK and
/// `message` is the empty string; on failure `message` is one human sentence
/// that names the input (file, argument) and what was wrong with it.
typedef struct px_error {
    px_status code;
    char message[256];
} px_error;

/// Short constant name of a status ("PX_ERR_DEGENERATE"); never NULL.
PX_API const char *px_status_string(px_status status);

/// An allocator. `alloc` returns NULL on failure; `free` receives the size
/// that was requested. Objects take one in their options, keep a copy, and
/// free everything they own with it; NULL means malloc and free. Queries
/// never allocate.
typedef struct px_allocator {
    void *(*alloc)(void *user, size_t size);
    void (*free)(void *user, void *ptr, size_t size);
    void *user;
} px_allocator;

#ifdef __cplusplus
}
#endif

#endif /* PROXIMA_BASE_H */
