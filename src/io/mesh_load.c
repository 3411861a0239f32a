/* px_mesh_load: a mesh file -> px_mesh (triangles and the part tree),
 * through the checked import of import.c.
 *
 * Post-processing: none. Polygons of four or more corners are cut into
 * triangles here (polygon.c, on the full-precision coordinates), after the
 * raw scene was checked (face indices below the mesh's vertex count,
 * finite coordinates, polygons small enough: ear clipping costs up to the
 * square of a polygon's size). Assimp's aiProcess_Triangulate, used until
 * review s30, covers area outside concave polygons of five or more corners
 * in 5.2 (shared REFERENCES §6.2 named it). Every other step that would
 * help can delete small parts outright: Assimp 5.2 stores positions as
 * floats and its thresholds are absolute, in file units.
 * - JoinIdenticalVertices welds positions within ~3e-6..1e-5 (a 3e-5
 *   tetrahedron at coordinate 1000 collapsed to a point); px_mesh_create
 *   joins exactly equal positions instead, for its closed test only.
 * - FindDegenerates removes triangles of area < 1e-6 (a whole tetrahedron
 *   of edge 1e-6 vanished); px_mesh_create flags degenerate triangles
 *   exactly and keeps them (the part is then open).
 * - SortByPType with removal would drop point and line meshes, which are
 *   kept here as point-set parts; without it a mesh may mix primitives, and
 *   only its 3-index faces become triangles.
 * - ValidateDataStructure rejects meshes without faces (point clouds) and
 *   checks what is checked here anyway; PreTransformVertices flattens the
 *   tree; GenNormals, FixInfacingNormals and friends guess.
 *
 * Parts: one per node with meshes, holding all of them. Assimp's meshes
 * are material boundaries more than geometric ones: it splits a COLLADA
 * geometry into a mesh per <triangles> element, an OBJ object per
 * `usemtl`, a glTF mesh per primitive (the PUMA's link 3 comes as three
 * open pieces of one closed surface), and the pieces' names do not tell
 * (OBJ names the second piece after its material). What one node holds
 * moves as one body, so it is one part; a mesh that two nodes reference is
 * two parts.
 *
 * Coordinates: Assimp's floats, or, for plain OFF, ASCII STL, OBJ and PLY, the same
 * vertices read again at full precision by exact.c.
 *
 * The node tree is walked iteratively (BAD_INPUTS item 29: explicit stack,
 * depth cap PXI_IO_MAX_DEPTH), twice: once to count, once to fill. Nodes
 * are numbered in preorder, so a parent comes before its children. Each
 * node-mesh reference is one part, its vertices transformed by the node's
 * world matrix (parent * local, in doubles) into the root frame; under a
 * mirror (negative determinant) its triangles are reversed so that the
 * winding keeps facing the same side of the surface.
 */
#include "proxima/io.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "core/core.h"
#include "io/exact.h"
#include "io/import.h"
#include "io/polygon.h"

/* Polygons are triangulated by ear clipping and checked for crossing edges,
 * up to about n^2 steps for n corners (a 32,000-corner polygon took 5.5 s
 * in Assimp 5.2.5): files whose polygons of 5 or more corners sum to more
 * than this in n^2 are refused. */
#define PXI_IO_MAX_POLYGON_WORK (1ull << 28)

/* Longest node or mesh name kept (Assimp's aiString holds at most 1023). */
#define PXI_IO_NAME_MAX 1023

typedef struct load_ctx {
    const px_allocator *alloc;
    /* counts (pass 1) and cursors (pass 2) */
    size_t nv, nt, name_bytes;
    uint32_t np, nn;
    /* arrays, pxi_alloc'ed for pass 2 */
    double *xyz;
    uint32_t *tri;
    px_mesh_part_desc *parts;
    px_mesh_node_desc *nodes;
    char *names;
    size_t cap_v, cap_t, cap_names;
    uint32_t cap_p, cap_n;
    double unit_metres;
    uint32_t float_coordinates;
    /* full-precision positions (exact.c), or NULL: Assimp's floats */
    double *exact;
    size_t exact_count;
    size_t *mesh_first; /* where each scene mesh starts in `exact` */
    unsigned mesh_count;
    /* polygons of 4 or more corners (polygon.c): the most corners of one,
     * its corners' indices into xyz, the ear clipper's scratch */
    uint32_t max_corners, *corners;
    pxi_polygon_work poly;
} load_ctx;

typedef struct walk_entry {
    const struct aiNode *node;
    pxi_xform world;
    int32_t index;
    uint32_t next_child;
} walk_entry;

static size_t ai_len(const struct aiString *s) {
    size_t n = s->length < PXI_IO_NAME_MAX ? s->length : PXI_IO_NAME_MAX;
    for (size_t i = 0; i < n; ++i)
        if (!s->data[i]) return i;
    return n;
}

/* pxi_io_scene_fn, before Triangulate: every mesh present, face indices in
 * range, coordinates finite, polygon work bounded. */
static px_status check_raw(const char *path, const pxi_file_id *id, const struct aiScene *scene, void *vctx,
                           px_error *err) {
    load_ctx *c = vctx;
    if (id->off_dropped_faces)
        return pxi_error(
            err, PX_ERR_IO,
            "mesh file '%s': %llu of its faces have 10 or more vertices; Assimp 5.2 reads OFF faces "
            "of at most 9 and drops larger ones, whose triangles would be missing: split them",
            path, id->off_dropped_faces);
    unsigned long long work = 0;
    for (unsigned i = 0; i < scene->mNumMeshes; ++i) {
        const struct aiMesh *m = scene->mMeshes[i];
        if (!m || (m->mNumVertices && !m->mVertices) || (m->mNumFaces && !m->mFaces))
            return pxi_error(err, PX_ERR_IO, "mesh file '%s': mesh %u is missing its vertices or faces", path,
                             i);
        for (unsigned v = 0; v < m->mNumVertices; ++v) {
            const struct aiVector3D *p = &m->mVertices[v];
            if (!isfinite(p->x) || !isfinite(p->y) || !isfinite(p->z))
                return pxi_error(err, PX_ERR_IO,
                                 "mesh file '%s': vertex %u of mesh %u is NaN, infinite or beyond the 32-bit "
                                 "float range (|x| > 3.4e38) that Assimp reads every format in",
                                 path, v, i);
        }
        for (unsigned f = 0; f < m->mNumFaces; ++f) {
            const struct aiFace *face = &m->mFaces[f];
            if (face->mNumIndices && !face->mIndices)
                return pxi_error(err, PX_ERR_IO, "mesh file '%s': face %u of mesh %u has no indices", path, f,
                                 i);
            for (unsigned k = 0; k < face->mNumIndices; ++k) {
                if (face->mIndices[k] >= m->mNumVertices)
                    return pxi_error(err, PX_ERR_IO,
                                     "mesh file '%s': face %u of mesh %u uses vertex %u, but the mesh has %u "
                                     "vertices",
                                     path, f, i, face->mIndices[k], m->mNumVertices);
            }
            unsigned long long n = face->mNumIndices;
            if (n > c->max_corners) c->max_corners = (uint32_t)n;
            if (n >= 5) {
                work += n * n;
                if (work > PXI_IO_MAX_POLYGON_WORK)
                    return pxi_error(
                        err, PX_ERR_IO,
                        "mesh file '%s': its polygons are too large to triangulate (face %u of mesh "
                        "%u has %u corners; the squares of all polygon sizes may sum to %llu)",
                        path, f, i, face->mNumIndices, (unsigned long long)PXI_IO_MAX_POLYGON_WORK);
            }
        }
    }
    return PX_OK;
}

/* Counts (fill = 0) or writes (fill = 1) node `node`, the child of node
 * `parent`, at world transform `world`. */
static px_status visit(const char *path, const struct aiScene *scene, load_ctx *c, const struct aiNode *node,
                       int32_t parent, const pxi_xform *world, int fill, px_error *err) {
    if (c->nn >= PX_IO_MAX_ELEMENTS)
        return pxi_error(err, PX_ERR_IO, "mesh file '%s' has more than %llu nodes", path,
                         (unsigned long long)PX_IO_MAX_ELEMENTS);
    size_t node_len = ai_len(&node->mName);
    const char *node_name = NULL;
    if (fill) {
        char *name = c->names + c->name_bytes;
        memcpy(name, node->mName.data, node_len);
        name[node_len] = '\0';
        node_name = name;
        c->nodes[c->nn].name = name;
        c->nodes[c->nn].parent = parent;
        c->nodes[c->nn].reserved = 0;
    }
    c->name_bytes += node_len + 1;
    int32_t index = (int32_t)c->nn++;
    int mirror = pxi_xform_det(world) < 0;
    if (node->mNumMeshes && !node->mMeshes)
        return pxi_error(err, PX_ERR_IO, "mesh file '%s': node '%.*s' lists meshes without their indices",
                         path, (int)(node_len < 64 ? node_len : 64), node->mName.data);
    for (unsigned k = 0; k < node->mNumMeshes; ++k) {
        if (node->mMeshes[k] >= scene->mNumMeshes)
            return pxi_error(err, PX_ERR_IO,
                             "mesh file '%s': node '%.*s' references a mesh that does not exist", path,
                             (int)(node_len < 64 ? node_len : 64), node->mName.data);
    }
    if (node->mNumMeshes) {
        /* One part: all the node's meshes (file comment), named after the first. */
        const unsigned k = 0, end = node->mNumMeshes, mi = node->mMeshes[0];
        const struct aiMesh *first = scene->mMeshes[mi];
        size_t mesh_len = ai_len(&first->mName);
        size_t nv = 0, nt = 0;
        for (unsigned g = k; g < end; ++g) {
            const struct aiMesh *m = scene->mMeshes[node->mMeshes[g]];
            nv += m->mNumVertices;
            for (unsigned f = 0; f < m->mNumFaces; ++f)
                if (m->mFaces[f].mNumIndices >= 3) nt += m->mFaces[f].mNumIndices - 2;
            if (nv > PX_IO_MAX_ELEMENTS || nt > PX_IO_MAX_ELEMENTS) break;
        }
        if (nv > PX_IO_MAX_ELEMENTS - c->nv || nt > PX_IO_MAX_ELEMENTS - c->nt || c->np >= PX_IO_MAX_ELEMENTS)
            return pxi_error(
                err, PX_ERR_IO,
                "mesh file '%s' has more than %llu vertices, triangles or parts (a mesh counts once "
                "per node that uses it)",
                path, (unsigned long long)PX_IO_MAX_ELEMENTS);
        /* part name: "node/mesh", "node/#index" for a mesh without a name */
        char number[16];
        const char *mesh_name = first->mName.data;
        if (!mesh_len) {
            mesh_len = (size_t)snprintf(number, sizeof number, "#%u", mi);
            mesh_name = number;
        }
        if (fill) {
            char *name = c->names + c->name_bytes;
            memcpy(name, node->mName.data, node_len);
            name[node_len] = '/';
            memcpy(name + node_len + 1, mesh_name, mesh_len);
            name[node_len + 1 + mesh_len] = '\0';
            px_mesh_part_desc *p = &c->parts[c->np];
            memset(p, 0, sizeof *p);
            p->name = name;
            p->node = index;
            p->first_vertex = (uint32_t)c->nv;
            p->vertex_count = (uint32_t)nv;
            p->first_triangle = (uint32_t)c->nt;
            p->triangle_count = (uint32_t)nt;
            double *out = c->xyz + 3 * c->nv;
            uint32_t *t = c->tri + 3 * c->nt, base = (uint32_t)c->nv;
            for (unsigned g = k; g < end; ++g) {
                unsigned gi = node->mMeshes[g];
                const struct aiMesh *m = scene->mMeshes[gi];
                const double *exact = c->exact ? c->exact + 3 * c->mesh_first[gi] : NULL;
                for (unsigned v = 0; v < m->mNumVertices; ++v, out += 3) {
                    const struct aiVector3D *q = &m->mVertices[v];
                    if (exact)
                        pxi_xform_apply(world, exact[3 * v], exact[3 * v + 1], exact[3 * v + 2], out);
                    else
                        pxi_xform_apply(world, q->x, q->y, q->z, out);
                    if (!isfinite(out[0]) || !isfinite(out[1]) || !isfinite(out[2]))
                        return pxi_error(err, PX_ERR_IO,
                                         "mesh file '%s': vertex %u of mesh %u is NaN or infinite under the "
                                         "transform of node '%.64s'",
                                         path, v, gi, node_name);
                }
                for (unsigned f = 0; f < m->mNumFaces; ++f) {
                    const struct aiFace *face = &m->mFaces[f];
                    const uint32_t n = face->mNumIndices;
                    if (n < 3) continue; /* points and lines: not triangles */
                    if (n == 3) {
                        for (int j = 0; j < 3; ++j) t[j] = base + face->mIndices[j];
                    } else {
                        for (uint32_t j = 0; j < n; ++j) c->corners[j] = base + face->mIndices[j];
                        if (!pxi_polygon_triangulate(c->xyz, c->corners, n, &c->poly, t))
                            return pxi_error(err, PX_ERR_IO,
                                             "mesh file '%s': face %u of mesh %u, a polygon of %u corners, "
                                             "crosses itself (seen across its normal), so its triangles are "
                                             "not defined; split it into simple polygons or triangles",
                                             path, f, gi, n);
                    }
                    for (uint32_t j = 0; j < n - 2; ++j, t += 3)
                        if (mirror) {
                            uint32_t x = t[1];
                            t[1] = t[2];
                            t[2] = x;
                        }
                }
                base += m->mNumVertices;
            }
        }
        c->name_bytes += node_len + 1 + mesh_len + 1;
        c->nv += nv;
        c->nt += nt;
        c->np++;
    }
    return PX_OK;
}

/* One pass over the node tree (file comment). */
static px_status walk(const char *path, const struct aiScene *scene, load_ctx *c, walk_entry *stack, int fill,
                      px_error *err) {
    c->nv = c->nt = c->name_bytes = 0;
    c->np = c->nn = 0;
    pxi_xform identity = pxi_xform_identity(), local = pxi_xform_from_ai(&scene->mRootNode->mTransformation);
    stack[0].node = scene->mRootNode;
    stack[0].world = pxi_xform_mul(&identity, &local);
    stack[0].index = 0;
    stack[0].next_child = 0;
    px_status st = visit(path, scene, c, scene->mRootNode, -1, &stack[0].world, fill, err);
    int depth = 0;
    while (st == PX_OK && depth >= 0) {
        walk_entry *top = &stack[depth];
        const struct aiNode *node = top->node;
        if (!node->mChildren || top->next_child >= node->mNumChildren) {
            --depth;
            continue;
        }
        const struct aiNode *child = node->mChildren[top->next_child++];
        if (!child) return pxi_error(err, PX_ERR_IO, "mesh file '%s': a node has a missing child", path);
        if (depth + 1 > PXI_IO_MAX_DEPTH)
            return pxi_error(err, PX_ERR_IO, "mesh file '%s': node tree deeper than %d levels (or cyclic)",
                             path, PXI_IO_MAX_DEPTH);
        walk_entry *next = &stack[depth + 1];
        local = pxi_xform_from_ai(&child->mTransformation);
        next->node = child;
        next->world = pxi_xform_mul(&top->world, &local);
        next->index = (int32_t)c->nn;
        next->next_child = 0;
        st = visit(path, scene, c, child, top->index, &next->world, fill, err);
        ++depth;
    }
    return st;
}

static void free_exact(load_ctx *c) {
    pxi_free(c->alloc, c->exact, c->exact_count * 3 * sizeof(double));
    pxi_free(c->alloc, c->mesh_first, c->mesh_count * sizeof(size_t));
    c->exact = NULL;
    c->mesh_first = NULL;
}

static void free_arrays(load_ctx *c) {
    pxi_free(c->alloc, c->xyz, c->cap_v * 3 * sizeof(double));
    pxi_free(c->alloc, c->tri, c->cap_t * 3 * sizeof(uint32_t));
    pxi_free(c->alloc, c->parts, c->cap_p * sizeof(px_mesh_part_desc));
    pxi_free(c->alloc, c->nodes, c->cap_n * sizeof(px_mesh_node_desc));
    pxi_free(c->alloc, c->names, c->cap_names);
    c->xyz = NULL;
    c->tri = NULL;
    c->parts = NULL;
    c->nodes = NULL;
    c->names = NULL;
}

/* The unit of the coordinates Assimp hands over (mesh.h, unit_metres). */
static double scene_unit(const struct aiScene *scene) {
    const char *format = pxi_io_scene_format(scene);
    /* COLLADA: Assimp 5.2 folds <unit meter> into the root node; glTF: metres */
    if (format && (strstr(format, "Collada") || strstr(format, "glTF"))) return 1.0;
    return 0.0;
}

/* The polygons' scratch, for max_corners corners. */
static int poly_alloc(load_ctx *c) {
    const uint32_t n = c->max_corners;
    c->corners = pxi_alloc_array(c->alloc, n, sizeof *c->corners);
    c->poly.prev = pxi_alloc_array(c->alloc, n, sizeof *c->poly.prev);
    c->poly.next = pxi_alloc_array(c->alloc, n, sizeof *c->poly.next);
    c->poly.state = pxi_alloc_array(c->alloc, n, 1);
    c->poly.uv = pxi_alloc_array(c->alloc, n, 2 * sizeof(double));
    c->poly.cap = n;
    return c->corners && c->poly.prev && c->poly.next && c->poly.state && c->poly.uv;
}

static void poly_free(load_ctx *c) {
    const uint32_t n = c->poly.cap;
    pxi_free(c->alloc, c->corners, (size_t)n * sizeof *c->corners);
    pxi_free(c->alloc, c->poly.prev, (size_t)n * sizeof *c->poly.prev);
    pxi_free(c->alloc, c->poly.next, (size_t)n * sizeof *c->poly.next);
    pxi_free(c->alloc, c->poly.state, n);
    pxi_free(c->alloc, c->poly.uv, (size_t)n * 2 * sizeof(double));
    c->corners = NULL;
    memset(&c->poly, 0, sizeof c->poly);
}

/* pxi_io_scene_fn, on the raw scene: the desc's arrays, polygons cut into
 * triangles by polygon.c. */
static px_status build(const char *path, const pxi_file_id *id, const struct aiScene *scene, void *vctx,
                       px_error *err) {
    load_ctx *c = vctx;
    walk_entry *stack = pxi_alloc_array(c->alloc, PXI_IO_MAX_DEPTH + 1, sizeof *stack);
    if (!stack) return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "out of memory reading mesh file '%s'", path);
    px_status st = walk(path, scene, c, stack, 0, err);
    if (st == PX_OK && c->nv == 0)
        st = pxi_error(err, PX_ERR_IO, "mesh file '%s' contains no vertices", path);
    if (st == PX_OK) {
        c->cap_v = c->nv;
        c->cap_t = c->nt;
        c->cap_p = c->np;
        c->cap_n = c->nn;
        c->cap_names = c->name_bytes;
        c->xyz = pxi_alloc_array(c->alloc, c->cap_v, 3 * sizeof(double));
        c->tri = c->xyz ? pxi_alloc_array(c->alloc, c->cap_t, 3 * sizeof(uint32_t)) : NULL;
        c->parts = c->tri ? pxi_alloc_array(c->alloc, c->cap_p, sizeof(px_mesh_part_desc)) : NULL;
        c->nodes = c->parts ? pxi_alloc_array(c->alloc, c->cap_n, sizeof(px_mesh_node_desc)) : NULL;
        c->names = c->nodes ? pxi_alloc(c->alloc, c->cap_names) : NULL;
        if (c->names && c->max_corners > 3 && !poly_alloc(c)) {
            pxi_free(c->alloc, c->names, c->cap_names);
            c->names = NULL;
        }
        if (!c->names)
            st = pxi_error(err, PX_ERR_OUT_OF_MEMORY,
                           "out of memory reading mesh file '%s' (%zu vertices, %zu triangles)", path,
                           c->cap_v, c->cap_t);
    }
    if (st == PX_OK) st = pxi_io_exact_positions(path, id, scene, c->alloc, &c->exact, &c->exact_count, err);
    if (st == PX_OK && c->exact) {
        c->mesh_count = scene->mNumMeshes;
        c->mesh_first = pxi_alloc_array(c->alloc, c->mesh_count, sizeof(size_t));
        if (!c->mesh_first)
            st = pxi_error(err, PX_ERR_OUT_OF_MEMORY, "out of memory reading mesh file '%s'", path);
        size_t at = 0;
        for (unsigned i = 0; st == PX_OK && i < c->mesh_count; ++i) {
            c->mesh_first[i] = at;
            at += scene->mMeshes[i]->mNumVertices;
        }
    }
    if (st == PX_OK) st = walk(path, scene, c, stack, 1, err);
    pxi_free(c->alloc, stack, (PXI_IO_MAX_DEPTH + 1) * sizeof *stack);
    poly_free(c);
    int exact = c->exact != NULL;
    free_exact(c);
    if (st != PX_OK) {
        free_arrays(c);
        return st;
    }
    c->float_coordinates = !exact;
    c->unit_metres = scene_unit(scene);
    return PX_OK;
}

px_mesh *px_mesh_load(const char *path, const px_mesh_options *options, px_error *err) {
    pxi_error_clear(err);
    if (!path || !path[0]) {
        pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_mesh_load: path is NULL or empty");
        return NULL;
    }
    /* The options are checked again by px_mesh_create; here so that a bad
     * option is reported before the file is read, as an argument error. */
    px_mesh_options opt;
    memset(&opt, 0, sizeof opt);
    if (options) opt = *options;
    for (int i = 0; i < 6; ++i) {
        if (opt.reserved[i]) {
            pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_mesh_load: options.reserved[%d] is not zero", i);
            return NULL;
        }
    }
    if (!isfinite(opt.scale) || opt.scale < 0) {
        pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_mesh_load: options.scale %g must be finite and positive",
                  opt.scale);
        return NULL;
    }
    px_allocator alloc;
    if (pxi_allocator_resolve(opt.allocator, &alloc, err) != PX_OK) return NULL;

    load_ctx c;
    memset(&c, 0, sizeof c);
    c.alloc = &alloc;
    if (pxi_io_import(path, &alloc, 0, check_raw, build, &c, err) != PX_OK) return NULL;

    px_mesh_desc d;
    memset(&d, 0, sizeof d);
    d.xyz = c.xyz;
    d.vertex_count = c.nv;
    d.triangles = c.tri;
    d.triangle_count = c.nt;
    d.parts = c.parts;
    d.part_count = c.np;
    d.nodes = c.nodes;
    d.node_count = c.nn;
    d.unit_metres = c.unit_metres;
    d.float_coordinates = c.float_coordinates;
    px_error inner;
    memset(&inner, 0, sizeof inner);
    px_mesh *mesh = px_mesh_create(&d, options, &inner);
    free_arrays(&c);
    if (!mesh) {
        /* Keep out of memory as it is; anything else is the file's fault
         * (a coordinate the scale makes infinite, ...). */
        char msg[sizeof inner.message];
        memcpy(msg, inner.message, sizeof msg);
        msg[sizeof msg - 1] = '\0';
        pxi_error(err, inner.code == PX_ERR_OUT_OF_MEMORY ? PX_ERR_OUT_OF_MEMORY : PX_ERR_IO,
                  "mesh file '%s': %s", path, msg);
        return NULL;
    }
    return mesh;
}
