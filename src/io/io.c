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
 * - The import itself (prechecks, the lock, Assimp's file system, the scene
 *   checks) is import.c's, shared with px_mesh_load; the walk here stops at
 *   PX_IO_MAX_ELEMENTS vertices (instancing multiplies them).
 */
#include "proxima/io.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <assimp/cimport.h>
#include <assimp/scene.h>

#include "core/core.h"
#include "io/import.h"

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

static void walk_node(io_walk *w, const struct aiNode *node, const pxi_xform *parent, int depth) {
    if (!node || w->too_deep || w->bad_mesh_index || w->too_many || w->non_finite) return;
    if (depth > PXI_IO_MAX_DEPTH) {
        w->too_deep = 1;
        return;
    }
    pxi_xform local = pxi_xform_from_ai(&node->mTransformation);
    pxi_xform world = pxi_xform_mul(parent, &local);
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

/* What the walk hands back to px_load_points. */
typedef struct points_ctx {
    const px_allocator *alloc;
    double *xyz; /* 3 * cap doubles, pxi_alloc'ed */
    size_t count, cap;
} points_ctx;

/* pxi_io_scene_fn: collects all transformed vertices (with duplicates). */
static px_status collect_points(const char *path, const struct aiScene *scene, void *vctx, px_error *err) {
    points_ctx *ctx = vctx;
    pxi_xform identity = pxi_xform_identity();
    io_walk w;
    memset(&w, 0, sizeof w);
    w.scene = scene;
    walk_node(&w, scene->mRootNode, &identity, 0);
    if (w.too_deep)
        return pxi_error(err, PX_ERR_IO, "mesh file '%s': node tree deeper than %d levels (or cyclic)", path,
                         PXI_IO_MAX_DEPTH);
    if (w.bad_mesh_index)
        return pxi_error(err, PX_ERR_IO, "mesh file '%s': a node references a mesh that does not exist",
                         path);
    if (w.too_many)
        return pxi_error(
            err, PX_ERR_IO,
            "mesh file '%s' has more than %llu vertices (a mesh counts once per node that uses it)", path,
            (unsigned long long)PX_IO_MAX_ELEMENTS);
    if (w.count == 0) return pxi_error(err, PX_ERR_IO, "mesh file '%s' contains no vertices", path);

    size_t total = w.count;
    double *xyz = pxi_alloc_array(ctx->alloc, total, 3 * sizeof(double));
    if (!xyz)
        return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "out of memory reading mesh file '%s' (%zu vertices)",
                         path, total);
    w.out = xyz;
    w.capacity = total;
    w.count = 0;
    walk_node(&w, scene->mRootNode, &identity, 0);
    if (w.non_finite) {
        char node[64];
        snprintf(node, sizeof node, "%s", w.bad_node ? w.bad_node : "");
        pxi_free(ctx->alloc, xyz, total * 3 * sizeof(double));
        return pxi_error(err, PX_ERR_IO, "mesh file '%s': vertex %zu of node '%s' is NaN or infinite", path,
                         w.bad_vertex, node);
    }
    ctx->xyz = xyz;
    ctx->count = w.count;
    ctx->cap = total;
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
    points_ctx ctx = {&alloc, NULL, 0, 0};
    px_status st = pxi_io_import(path, &alloc, 0, NULL, collect_points, &ctx, err);
    if (st != PX_OK) return st;
    double *pts = ctx.xyz;
    size_t n = ctx.count, cap = ctx.cap;

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
