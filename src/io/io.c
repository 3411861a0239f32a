/* Mesh files -> point sets and convex polytopes, through the Assimp C API.
 *
 * Design (shared REFERENCES §6):
 * - Import with no post-processing at all. A hull needs positions and nothing
 *   else, and the usual mesh clean-ups hurt here:
 *   JoinIdenticalVertices welds with an absolute tolerance of ~3e-6..1e-5
 *   file units (it merges distinct corners of small models),
 *   FindDegenerates deletes triangles of area < 1e-6 together with their
 *   vertices, and Triangulate is irrelevant to a point set. Duplicates are
 *   instead removed exactly (sort + unique), which loses nothing.
 *   ValidateDataStructure is not used either: it rejects point clouds
 *   ("Mesh contains no faces"), which are valid hull input. The few fields
 *   read here (node mesh indices, child pointers, mVertices) are checked.
 * - Walk the node tree, composing parent * local transforms in double
 *   precision, and emit every vertex of every mesh a node references
 *   (instanced meshes once per reference). Assimp positions are 32-bit
 *   floats; the float -> double conversion is exact.
 * - Assimp's last-error string is a process-global std::string written
 *   without a lock, so every call into Assimp (import, error copy, walk,
 *   release) runs under one mutex, and the message is copied at once.
 * - Scenes flagged AI_SCENE_FLAGS_INCOMPLETE are rejected.
 * - Before Assimp sees a file, precheck.c checks its type, its size and the
 *   counts its header declares (Assimp allocates by them), walks PLY and OFF
 *   bodies and COLLADA and glTF node graphs the way Assimp would, and the
 *   walk here stops at PX_IO_MAX_ELEMENTS vertices (instancing multiplies
 *   them).
 * - Assimp opens files through fs.c (aiImportFileEx with our aiFileIO): the
 *   mesh file must still be the one the precheck read, and every file the
 *   import opens, the mesh file's references too, is a regular file within
 *   the size limits. A refused open fails the import even where Assimp would
 *   have done without the file.
 */
#include "proxima/io.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <threads.h>

#include <assimp/cimport.h>
#include <assimp/scene.h>

#include "core/core.h"
#include "io/fs.h"
#include "io/precheck.h"

/* Node trees deeper than this are rejected (also catches cyclic graphs). */
#define PXI_IO_MAX_DEPTH 1024

/* The import lock, created once (call_once) on first use. If mtx_init fails
 * then, the failure is permanent: every later load fails too, with
 * PX_ERR_INTERNAL, rather than calling Assimp without the lock. */
static once_flag g_io_once = ONCE_FLAG_INIT;
static mtx_t g_io_mutex;
static int g_io_mutex_ok; /* written once, inside call_once */

/* call_once callback: creates the import mutex and records whether it could. */
static void io_mutex_init(void) { g_io_mutex_ok = (mtx_init(&g_io_mutex, mtx_plain) == thrd_success); }

/* Takes the import lock. On PX_OK the caller must call io_unlock; otherwise
 * the lock is not held and err names the file and the failure. */
static px_status io_lock(const char *path, px_error *err) {
    call_once(&g_io_once, io_mutex_init);
    if (!g_io_mutex_ok)
        return pxi_error(
            err, PX_ERR_INTERNAL,
            "cannot import mesh file '%s': the import mutex could not be created (mtx_init failed), "
            "and Assimp is not safe to call without it",
            path);
    if (mtx_lock(&g_io_mutex) != thrd_success)
        return pxi_error(err, PX_ERR_INTERNAL,
                         "cannot import mesh file '%s': locking the import mutex failed", path);
    return PX_OK;
}

/* Releases the lock taken by a successful io_lock. */
static void io_unlock(void) { mtx_unlock(&g_io_mutex); }

/* Affine map as a row-major 3x4 matrix [R | t]: p' = R p + t. */
typedef struct io_xform {
    double m[12];
} io_xform;

static io_xform xform_from_ai(const struct aiMatrix4x4 *a) {
    io_xform x = {{a->a1, a->a2, a->a3, a->a4, a->b1, a->b2, a->b3, a->b4, a->c1, a->c2, a->c3, a->c4}};
    return x;
}

/* p * q (apply q first, then p); Assimp's parent * local order. */
static io_xform xform_mul(const io_xform *p, const io_xform *q) {
    io_xform r;
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

/* State of one walk over the node tree. Pass 1 (out == NULL) counts, pass 2
 * writes transformed points. */
typedef struct io_walk {
    const struct aiScene *scene;
    double *out;  /* 3 * capacity doubles, or NULL while counting */
    size_t count; /* points emitted (or counted) so far */
    size_t capacity;
    int too_deep;
    int bad_mesh_index;
    int too_many;         /* more than PX_IO_MAX_ELEMENTS vertices */
    int non_finite;       /* set on the first non-finite transformed vertex */
    size_t bad_vertex;    /* its index within its mesh */
    const char *bad_node; /* name of the node it belongs to */
} io_walk;

static void walk_node(io_walk *w, const struct aiNode *node, const io_xform *parent, int depth) {
    if (!node || w->too_deep || w->bad_mesh_index || w->too_many || w->non_finite) return;
    if (depth > PXI_IO_MAX_DEPTH) {
        w->too_deep = 1;
        return;
    }
    io_xform local = xform_from_ai(&node->mTransformation);
    io_xform world = xform_mul(parent, &local);
    for (unsigned k = 0; k < node->mNumMeshes && node->mMeshes; ++k) {
        unsigned mi = node->mMeshes[k];
        if (mi >= w->scene->mNumMeshes || !w->scene->mMeshes[mi]) {
            w->bad_mesh_index = 1;
            return;
        }
        const struct aiMesh *mesh = w->scene->mMeshes[mi];
        size_t nv = mesh->mVertices ? mesh->mNumVertices : 0;
        if (!w->out) {
            /* The cap also bounds 3 * count * sizeof(double) on 32-bit. */
            if (nv > PX_IO_MAX_ELEMENTS - w->count) {
                w->too_many = 1;
                return;
            }
            w->count += nv;
            continue;
        }
        const double *m = world.m;
        for (size_t i = 0; i < nv && w->count < w->capacity; ++i) {
            double x = mesh->mVertices[i].x, y = mesh->mVertices[i].y, z = mesh->mVertices[i].z;
            double px = m[0] * x + m[1] * y + m[2] * z + m[3];
            double py = m[4] * x + m[5] * y + m[6] * z + m[7];
            double pz = m[8] * x + m[9] * y + m[10] * z + m[11];
            if (!isfinite(px) || !isfinite(py) || !isfinite(pz)) {
                w->non_finite = 1;
                w->bad_vertex = i;
                w->bad_node = node->mName.data;
                return;
            }
            double *o = w->out + 3 * w->count++;
            o[0] = px;
            o[1] = py;
            o[2] = pz;
        }
    }
    if (!node->mChildren) return;
    for (unsigned c = 0; c < node->mNumChildren; ++c) walk_node(w, node->mChildren[c], &world, depth + 1);
}

static int cmp_point(const void *pa, const void *pb) {
    const double *a = pa, *b = pb;
    for (int k = 0; k < 3; ++k) {
        if (a[k] < b[k]) return -1;
        if (a[k] > b[k]) return 1;
    }
    return 0;
}

/* Sorts the (finite) points and removes exact duplicates; returns the new count. */
static size_t unique_points(double *xyz, size_t n) {
    if (n < 2) return n;
    qsort(xyz, n, 3 * sizeof(double), cmp_point);
    size_t m = 1;
    for (size_t i = 1; i < n; ++i) {
        const double *p = xyz + 3 * i, *q = xyz + 3 * (m - 1);
        if (p[0] == q[0] && p[1] == q[1] && p[2] == q[2]) continue;
        memmove(xyz + 3 * m, p, 3 * sizeof(double));
        ++m;
    }
    return m;
}

/* Imports the file (the one the precheck identified as `id`) and collects
 * all transformed vertices (with duplicates) into a pxi_alloc'ed array of
 * `*cap` points. Called with the io lock held. */
static px_status import_points_locked(const char *path, const pxi_file_id *id, const px_allocator *alloc,
                                      double **out, size_t *count, size_t *cap, px_error *err) {
    /* fs outlives the scene: the importer keeps it until aiReleaseImport. */
    pxi_io_fs fs;
    pxi_io_fs_init(&fs, path, id, alloc);
    const struct aiScene *scene = aiImportFileEx(path, 0, &fs.io);
    if (fs.refused) {
        /* Also after a success: Assimp goes on without a material library. */
        if (scene) aiReleaseImport(scene);
        pxi_io_fs_finish(&fs);
        return pxi_error(err, PX_ERR_IO, "cannot import mesh file '%s': %s", path, fs.message);
    }
    if (!scene) {
        pxi_io_fs_finish(&fs);
        char msg[160];
        const char *ai = aiGetErrorString();
        snprintf(msg, sizeof msg, "%s", ai && ai[0] ? ai : "unknown error");
        return pxi_error(err, PX_ERR_IO, "cannot import mesh file '%s': %s", path, msg);
    }
    px_status st = PX_OK;
    if (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) {
        st = pxi_error(err, PX_ERR_IO, "mesh file '%s' was imported incompletely (AI_SCENE_FLAGS_INCOMPLETE)",
                       path);
    } else if (scene->mNumMeshes == 0 || !scene->mMeshes) {
        st = pxi_error(err, PX_ERR_IO, "mesh file '%s' contains no meshes", path);
    } else if (!scene->mRootNode) {
        st = pxi_error(err, PX_ERR_IO, "mesh file '%s' has no root node", path);
    }
    if (st != PX_OK) {
        aiReleaseImport(scene);
        pxi_io_fs_finish(&fs);
        return st;
    }

    io_xform identity = {{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0}};
    io_walk w;
    memset(&w, 0, sizeof w);
    w.scene = scene;
    walk_node(&w, scene->mRootNode, &identity, 0);
    if (w.too_deep) {
        st = pxi_error(err, PX_ERR_IO, "mesh file '%s': node tree deeper than %d levels (or cyclic)", path,
                       PXI_IO_MAX_DEPTH);
    } else if (w.bad_mesh_index) {
        st = pxi_error(err, PX_ERR_IO, "mesh file '%s': a node references a mesh that does not exist", path);
    } else if (w.too_many) {
        st =
            pxi_error(err, PX_ERR_IO,
                      "mesh file '%s' has more than %llu vertices (a mesh counts once per node that uses it)",
                      path, (unsigned long long)PX_IO_MAX_ELEMENTS);
    } else if (w.count == 0) {
        st = pxi_error(err, PX_ERR_IO, "mesh file '%s' contains no vertices", path);
    }
    if (st != PX_OK) {
        aiReleaseImport(scene);
        pxi_io_fs_finish(&fs);
        return st;
    }

    size_t total = w.count;
    double *xyz = pxi_alloc_array(alloc, total, 3 * sizeof(double));
    if (!xyz) {
        aiReleaseImport(scene);
        pxi_io_fs_finish(&fs);
        return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "out of memory reading mesh file '%s' (%zu vertices)",
                         path, total);
    }
    w.out = xyz;
    w.capacity = total;
    w.count = 0;
    walk_node(&w, scene->mRootNode, &identity, 0);
    if (w.non_finite) {
        char node[64];
        snprintf(node, sizeof node, "%s", w.bad_node ? w.bad_node : "");
        st = pxi_error(err, PX_ERR_IO, "mesh file '%s': vertex %zu of node '%s' is NaN or infinite", path,
                       w.bad_vertex, node);
    }
    aiReleaseImport(scene);
    pxi_io_fs_finish(&fs);
    if (st != PX_OK) {
        pxi_free(alloc, xyz, total * 3 * sizeof(double));
        return st;
    }
    *out = xyz;
    *count = w.count;
    *cap = total;
    return PX_OK;
}

px_status px_load_points(const char *path, const px_allocator *allocator, double **xyz, size_t *count,
                         px_error *err) {
    pxi_error_clear(err);
    if (xyz) *xyz = NULL;
    if (count) *count = 0;
    if (!path || !path[0] || !xyz || !count) {
        return pxi_error(err, PX_ERR_INVALID_ARGUMENT,
                         "px_load_points: path, xyz and count must be non-NULL (and path non-empty)");
    }
    px_allocator alloc;
    px_status ast = pxi_allocator_resolve(allocator, &alloc, err);
    if (ast != PX_OK) return ast;
    /* Readability, size and header counts first (precheck.c): Assimp's message
     * for a missing file omits why, and Assimp allocates by declared counts. */
    pxi_file_id id;
    px_status pre = pxi_io_precheck(path, &alloc, &id, err);
    if (pre != PX_OK) return pre;

    double *pts = NULL;
    size_t n = 0, cap = 0;
    px_status st = io_lock(path, err);
    if (st != PX_OK) return st;
    st = import_points_locked(path, &id, &alloc, &pts, &n, &cap, err);
    io_unlock();
    if (st != PX_OK) return st;

    size_t m = unique_points(pts, n);
    if (m != cap) {
        /* Shrink to the exact size so px_free_points(xyz, count) frees what was allocated. */
        double *small = pxi_alloc_array(&alloc, m, 3 * sizeof(double));
        if (!small) {
            pxi_free(&alloc, pts, cap * 3 * sizeof(double));
            return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "out of memory reading mesh file '%s'", path);
        }
        memcpy(small, pts, m * 3 * sizeof(double));
        pxi_free(&alloc, pts, cap * 3 * sizeof(double));
        pts = small;
    }
    *xyz = pts;
    *count = m;
    if (err) {
        err->code = PX_OK;
        err->message[0] = '\0';
    }
    return PX_OK;
}

void px_free_points(double *xyz, size_t count, const px_allocator *allocator) {
    px_allocator alloc;
    if (!xyz || pxi_allocator_resolve(allocator, &alloc, NULL) != PX_OK) return;
    pxi_free(&alloc, xyz, count * 3 * sizeof(double));
}

px_convex *px_convex_create_from_file(const char *path, const px_convex_options *options, px_error *err) {
    pxi_error_clear(err);
    if (!path || !path[0]) {
        pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_convex_create_from_file: path is NULL or empty");
        return NULL;
    }
    /* The points are temporary: malloc'ed whatever the polytope's allocator. */
    double *xyz = NULL;
    size_t n = 0;
    if (px_load_points(path, NULL, &xyz, &n, err) != PX_OK) return NULL;
    px_error inner;
    memset(&inner, 0, sizeof inner);
    px_convex *c = px_convex_create(xyz, n, options, &inner);
    px_free_points(xyz, n, NULL);
    if (!c) {
        /* Keep the code, name the file. */
        char msg[sizeof inner.message];
        memcpy(msg, inner.message, sizeof msg);
        msg[sizeof msg - 1] = '\0';
        pxi_error(err, inner.code, "mesh file '%s' (%zu distinct vertices): %s", path, n, msg);
        return NULL;
    }
    if (err) {
        err->code = PX_OK;
        err->message[0] = '\0';
    }
    return c;
}
