/* Mesh files -> point sets and convex polytopes: conveniences on top of
 * px_mesh_load (mesh_load.c), which does the checked import, the node walk
 * and the checks of Assimp's scene.
 *
 * A hull needs positions only: px_load_points takes every vertex of every
 * part (all the vertices Assimp read, so PLY, OFF and glTF keep the ones no
 * face uses) and removes exact duplicates (sort + unique), which loses
 * nothing, where Assimp's JoinIdenticalVertices would weld with an absolute
 * tolerance of ~3e-6..1e-5 file units and merge distinct corners of small
 * models (shared REFERENCES §6). Assimp positions are 32-bit floats; the
 * float -> double conversion is exact.
 */
#include "proxima/io.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/core.h"

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
    px_mesh_options mo;
    memset(&mo, 0, sizeof mo);
    mo.allocator = &alloc;
    px_error inner;
    px_mesh *mesh = px_mesh_load(path, &mo, &inner);
    if (!mesh) {
        if (err) *err = inner;
        return inner.code;
    }
    size_t n = px_mesh_vertex_count(mesh), cap = n;
    double *pts = pxi_alloc_array(&alloc, cap, 3 * sizeof(double));
    if (!pts) {
        px_mesh_destroy(mesh);
        return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "out of memory reading mesh file '%s' (%zu vertices)",
                         path, n);
    }
    memcpy(pts, px_mesh_vertices(mesh), n * 3 * sizeof(double));
    px_mesh_destroy(mesh);

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
