/* px_model_create_from_mesh: a mesh's parts become leaves as the options
 * say: triangles (build.c's triangle tree), one hull per part with its
 * certified bound (reach.c), or the pieces of an approximate decomposition
 * (approx.c). */
#include <math.h>
#include <string.h>

#include "convex/convex.h"
#include "core/core.h"
#include "model/model.h"

/* h and h_overlap of a part's hull: a scratch triangle tree of the part
 * (indices made local to its vertex range), measured by reach.c. */
static px_status part_bounds(const px_allocator *alloc, const px_convex *hull, const double *xyz,
                             const uint32_t *tri, const px_mesh_part *mp, double *h, double *h_overlap,
                             px_error *err) {
    *h = *h_overlap = 0.0;
    if (mp->triangle_count == 0) return PX_OK;
    size_t n = (size_t)mp->triangle_count * 3;
    uint32_t *local = pxi_alloc_array(alloc, n, sizeof *local);
    if (!local) return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_model: out of memory");
    for (size_t i = 0; i < n; ++i) local[i] = tri[3 * (size_t)mp->first_triangle + i] - mp->first_vertex;
    px_model *tree = pxi_model_from_triangles(xyz + 3 * (size_t)mp->first_vertex, mp->vertex_count, local,
                                              mp->triangle_count, NULL, NULL, 0, 0, alloc, err);
    pxi_free(alloc, local, n * sizeof *local);
    if (!tree) return err ? err->code : PX_ERR_OUT_OF_MEMORY;
    px_status st = pxi_part_reach(alloc, hull, tree, 0, 0.0, h, h_overlap, err);
    px_model_destroy(tree);
    return st;
}

px_model *px_model_create_from_mesh(const px_mesh *mesh, const px_model_options *options, px_error *err) {
    if (!mesh) {
        pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_model_create_from_mesh: mesh is NULL");
        return NULL;
    }
    for (size_t i = 0; options && i < sizeof options->reserved / sizeof options->reserved[0]; ++i) {
        if (options->reserved[i]) {
            pxi_error(err, PX_ERR_INVALID_ARGUMENT,
                      "px_model_create_from_mesh: options.reserved[%zu] is not zero", i);
            return NULL;
        }
    }
    uint32_t pieces = options ? options->pieces : PX_PIECES_PARTS;
    if (pieces != PX_PIECES_PARTS && pieces != PX_PIECES_TRIANGLES && pieces != PX_PIECES_APPROXIMATE) {
        pxi_error(err, PX_ERR_INVALID_ARGUMENT,
                  "px_model_create_from_mesh: options.pieces %u is not PARTS, TRIANGLES or APPROXIMATE",
                  pieces);
        return NULL;
    }
    if (options && pieces != PX_PIECES_APPROXIMATE &&
        (options->tolerance != 0.0 || options->progress || options->threads)) {
        pxi_error(err, PX_ERR_INVALID_ARGUMENT,
                  "px_model_create_from_mesh: options.tolerance, threads and "
                  "progress are for PX_PIECES_APPROXIMATE only");
        return NULL;
    }
    uint32_t np = px_mesh_part_count(mesh), nv = px_mesh_vertex_count(mesh),
             nt = px_mesh_triangle_count(mesh);
    const double *xyz = px_mesh_vertices(mesh);
    const uint32_t *tri = px_mesh_triangles(mesh);
    if (np == 0 || nv == 0) {
        pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_model_create_from_mesh: the mesh is empty");
        return NULL;
    }
    px_allocator alloc;
    if (pxi_allocator_resolve(options ? options->allocator : NULL, &alloc, err) != PX_OK) return NULL;
    if (pieces == PX_PIECES_TRIANGLES) {
        uint32_t *part = pxi_alloc_array(&alloc, nt ? nt : 1, sizeof *part);
        uint8_t *closed = pxi_alloc_array(&alloc, np, 1);
        px_model *m = NULL;
        if (!part || !closed) {
            pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_model: out of memory");
        } else {
            int ok = 1;
            /* Triangles outside every part (px_mesh_create allows them) are
             * leaves of no part: surfaces, never solid. */
            for (uint32_t t = 0; t < nt; ++t) part[t] = PXI_NONE;
            for (uint32_t p = 0; p < np && ok; ++p) {
                px_mesh_part mp;
                px_mesh_get_part(mesh, p, &mp);
                closed[p] = (uint8_t)(mp.closed != 0);
                if (mp.triangle_count == 0) {
                    pxi_error(err, PX_ERR_INVALID_ARGUMENT,
                              "px_model_create_from_mesh: part %u ('%s') has no triangles; build it with "
                              "PX_PIECES_PARTS",
                              p, mp.name);
                    ok = 0;
                }
                for (uint32_t t = 0; t < mp.triangle_count; ++t) part[mp.first_triangle + t] = p;
            }
            if (ok) m = pxi_model_from_triangles(xyz, nv, tri, nt, part, closed, np, 1, &alloc, err);
        }
        pxi_free(&alloc, part, (size_t)(nt ? nt : 1) * sizeof *part);
        pxi_free(&alloc, closed, np);
        return m;
    }
    /* One hull per part, or pieces of parts: every triangle must belong to
     * a part, or the model would not stand for it. */
    uint64_t covered = 0;
    for (uint32_t p = 0; p < np; ++p) {
        px_mesh_part mp;
        px_mesh_get_part(mesh, p, &mp);
        covered += mp.triangle_count;
    }
    if (covered != nt) {
        pxi_error(
            err, PX_ERR_INVALID_ARGUMENT,
            "px_model_create_from_mesh: %llu of the mesh's %u triangles belong to no part; %s needs every "
            "triangle in a part",
            (unsigned long long)(nt - covered), nt,
            pieces == PX_PIECES_PARTS ? "PX_PIECES_PARTS" : "PX_PIECES_APPROXIMATE");
        return NULL;
    }
    px_model *m = pxi_model_alloc(options, err, &alloc);
    if (!m) return NULL;
    if (pieces == PX_PIECES_APPROXIMATE) {
        m->pieces = PX_PIECES_APPROXIMATE;
        px_convex **convex = NULL;
        px_status st = pxi_model_approximate(m, mesh, options, &convex, err);
        uint32_t n = m->n_leaves;
        if (st == PX_OK) st = pxi_model_convex_reps(m, convex, err);
        if (st == PX_OK) {
            st = pxi_model_build_tree(m, convex, 1, err);
        } else {
            for (uint32_t i = 0; i < n; ++i) px_convex_destroy(convex[i]);
        }
        pxi_free(&alloc, convex, (size_t)n * sizeof *convex);
        return pxi_model_finish(m, st, err);
    }
    m->pieces = PX_PIECES_PARTS;
    m->n_leaves = np;
    m->leaves = pxi_alloc_array(&alloc, np, sizeof *m->leaves);
    px_convex **convex = pxi_alloc_array(&alloc, np, sizeof *convex);
    px_status st = PX_OK;
    if (!m->leaves || !convex) {
        st = pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_model: out of memory");
    } else {
        m->bytes += (size_t)np * sizeof *m->leaves;
        memset(convex, 0, (size_t)np * sizeof *convex);
        px_convex_options co;
        memset(&co, 0, sizeof co);
        co.allocator = &m->alloc;
        for (uint32_t p = 0; p < np && st == PX_OK; ++p) {
            px_mesh_part mp;
            px_mesh_get_part(mesh, p, &mp);
            px_error e;
            convex[p] = px_convex_create(xyz + 3 * (size_t)mp.first_vertex, mp.vertex_count, &co, &e);
            if (!convex[p]) {
                st = pxi_error(err, e.code, "px_model_create_from_mesh: part %u ('%s'): %s", p, mp.name,
                               e.message);
                break;
            }
            m->leaves[p].part = p;
            m->leaves[p].tri = PXI_NONE;
            st = part_bounds(&alloc, convex[p], xyz, tri, &mp, &m->leaves[p].h, &m->leaves[p].h_overlap, err);
            m->max_h = fmax(m->max_h, m->leaves[p].h_overlap);
        }
        if (st == PX_OK) st = pxi_model_convex_reps(m, convex, err);
        if (st == PX_OK) {
            st = pxi_model_build_tree(m, convex, 1, err);
        } else {
            for (uint32_t i = 0; i < np; ++i) px_convex_destroy(convex[i]);
        }
    }
    pxi_free(&alloc, convex, (size_t)np * sizeof *convex);
    return pxi_model_finish(m, st, err);
}
