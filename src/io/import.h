/* One checked, serialised Assimp import (internal to src/io), shared by
 * px_load_points (io.c) and px_mesh_load (mesh_load.c). See import.c. */
#ifndef PXI_IO_IMPORT_H
#define PXI_IO_IMPORT_H

#include <assimp/scene.h>

#include "io/precheck.h"
#include "proxima/io.h"

/* Node trees deeper than this are rejected (also catches cyclic graphs). */
#define PXI_IO_MAX_DEPTH 1024

/* Reads the imported scene of the file the precheck identified as `id`;
 * runs with the import lock held. Returns PX_OK
 * or an error with `err` filled (naming `path`). */
typedef px_status (*pxi_io_scene_fn)(const char *path, const pxi_file_id *id, const struct aiScene *scene,
                                     void *ctx, px_error *err);

/* Imports the file at `path` (non-NULL, non-empty) the checked way:
 * precheck.c first (outside the lock), then, under the import lock,
 * aiImportFileEx through fs.c with no post-processing; a refused file, a
 * failed or incomplete import, a scene without meshes or root node fail
 * with PX_ERR_IO naming the file (Assimp's message quoted). Then `check`
 * (may be NULL) reads the raw scene; if it succeeds and `post_flags` is not
 * 0, aiApplyPostProcessing(post_flags) runs (so that a post-process step
 * only ever sees a scene `check` accepted), and `use` reads the result.
 * The scene is released and the lock dropped before returning.
 * Returns PX_OK, PX_ERR_IO, PX_ERR_OUT_OF_MEMORY (precheck buffers),
 * PX_ERR_INTERNAL (no lock), or what a callback returned. */
px_status pxi_io_import(const char *path, const px_allocator *alloc, unsigned post_flags,
                        pxi_io_scene_fn check, pxi_io_scene_fn use, void *ctx, px_error *err);

/* The name of the Assimp importer that made `scene` (its
 * "SourceAsset_Format" metadata, e.g. "Wavefront Object Importer"), or
 * NULL when the scene does not say. */
const char *pxi_io_scene_format(const struct aiScene *scene);

/* Affine map as a row-major 3x4 matrix [R | t]: p' = R p + t, in doubles
 * (Assimp's float matrices convert exactly). */
typedef struct pxi_xform {
    double m[12];
} pxi_xform;

static inline pxi_xform pxi_xform_identity(void) {
    pxi_xform x = {{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0}};
    return x;
}

static inline pxi_xform pxi_xform_from_ai(const struct aiMatrix4x4 *a) {
    pxi_xform x = {{a->a1, a->a2, a->a3, a->a4, a->b1, a->b2, a->b3, a->b4, a->c1, a->c2, a->c3, a->c4}};
    return x;
}

/* p * q (apply q first, then p); Assimp's parent * local order. */
static inline pxi_xform pxi_xform_mul(const pxi_xform *p, const pxi_xform *q) {
    pxi_xform r;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 4; ++j) {
            double s =
                p->m[4 * i + 0] * q->m[j] + p->m[4 * i + 1] * q->m[4 + j] + p->m[4 * i + 2] * q->m[8 + j];
            if (j == 3) s += p->m[4 * i + 3];
            r.m[4 * i + j] = s;
        }
    }
    return r;
}

/* x' = R x + t for one point. */
static inline void pxi_xform_apply(const pxi_xform *x, double px, double py, double pz, double out[3]) {
    const double *m = x->m;
    out[0] = m[0] * px + m[1] * py + m[2] * pz + m[3];
    out[1] = m[4] * px + m[5] * py + m[6] * pz + m[7];
    out[2] = m[8] * px + m[9] * py + m[10] * pz + m[11];
}

/* Determinant of R: negative for a mirror (which reverses winding). */
static inline double pxi_xform_det(const pxi_xform *x) {
    const double *m = x->m;
    return m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8]) +
           m[2] * (m[4] * m[9] - m[5] * m[8]);
}

#endif
