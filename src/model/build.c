/* Building sub-part hierarchy trees (M. Lin, "Efficient collision detection
 * for animation and robotics", Berkeley 1993, ch. 4: a hierarchy of convex
 * hulls over a union of convex pieces). The tree is built top down by
 * median splits along the longest axis of the leaf centroids' box, so that
 * nearby pieces are grouped and every node's hull stays tight (docs/model.md
 * says why this and not bottom-up merging); hulls are then computed bottom
 * up, each from its children's hull vertices. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "convex/convex.h"
#include "core/core.h"
#include "model/model.h"

typedef struct sort_key {
    double key;
    uint32_t leaf;
} sort_key;

typedef struct builder {
    px_model *m;
    px_convex **convex; /* per leaf, convex trees */
    px_vec3 *centroid;  /* per leaf */
    uint32_t *order;    /* leaves in tree order */
    sort_key *keys;
    px_vec3 *points; /* scratch for hull inputs */
    size_t points_cap;
    uint32_t next_node, next_box;
    int hulls; /* triangle trees: build inner hulls (0 for the scratch trees of part_reach) */
    px_error *err;
    px_status status;
} builder;

static int cmp_key(const void *x, const void *y) {
    const sort_key *a = x, *b = y;
    if (a->key < b->key) return -1;
    if (a->key > b->key) return 1;
    return a->leaf < b->leaf ? -1 : a->leaf > b->leaf;
}

static double coord(px_vec3 v, int axis) { return axis == 0 ? v.x : axis == 1 ? v.y : v.z; }

/* Makes room for `need` scratch points, keeping the first `n`. */
static int reserve(builder *b, size_t n, size_t need) {
    if (need <= b->points_cap) return 1;
    size_t cap = b->points_cap ? b->points_cap : 256;
    while (cap < need) cap *= 2;
    px_vec3 *p = pxi_alloc_array(&b->m->alloc, cap, sizeof *p);
    if (!p) return 0;
    if (b->points) memcpy(p, b->points, n * sizeof *p);
    pxi_free(&b->m->alloc, b->points, b->points_cap * sizeof *p);
    b->points = p;
    b->points_cap = cap;
    return 1;
}

/* Appends the points of leaf `leaf` (body frame) to the scratch array. */
static int push_leaf_points(builder *b, uint32_t leaf, size_t *n) {
    const px_model *m = b->m;
    uint32_t count = m->leaves[leaf].tri != PXI_NONE ? 3 : px_convex_vertex_count(b->convex[leaf]);
    if (!reserve(b, *n, *n + count)) return 0;
    if (m->leaves[leaf].tri != PXI_NONE) {
        const uint32_t *t = m->tri + 3 * (size_t)m->leaves[leaf].tri;
        for (int k = 0; k < 3; ++k) b->points[(*n)++] = m->v[t[k]];
    } else {
        for (uint32_t k = 0; k < count; ++k) px_convex_vertex(b->convex[leaf], k, &b->points[(*n)++]);
    }
    return 1;
}

/* Hull of `n` scratch points, or NULL with status PX_OK when they have no
 * volume (the node keeps its sphere only). */
static px_convex *hull_of_points(builder *b, size_t n) {
    px_convex_options o;
    memset(&o, 0, sizeof o);
    o.allocator = &b->m->alloc;
    px_error e;
    px_convex *c = px_convex_create(&b->points[0].x, n, &o, &e);
    if (!c && e.code != PX_ERR_DEGENERATE && e.code != PX_ERR_RANGE) {
        b->status = pxi_error(b->err, e.code, "px_model: hull of a tree node: %s", e.message);
    }
    return c;
}

static uint32_t build_node(builder *b, uint32_t lo, uint32_t hi, uint32_t depth) {
    px_model *m = b->m;
    uint32_t id = b->next_node++;
    pxi_mnode *node = &m->nodes[id];
    node->box = PXI_NONE;
    node->flags = 0;
    node->hull = NULL;
    if (depth > m->depth) m->depth = depth;
    if (hi - lo == 1) {
        uint32_t leaf = b->order[lo];
        node->child[0] = leaf;
        node->child[1] = PXI_NONE;
        node->hull = b->convex ? b->convex[leaf] : NULL;
    } else {
        px_vec3 lo_c = b->centroid[b->order[lo]], hi_c = lo_c;
        for (uint32_t i = lo + 1; i < hi; ++i) {
            px_vec3 c = b->centroid[b->order[i]];
            lo_c = pxi_v(fmin(lo_c.x, c.x), fmin(lo_c.y, c.y), fmin(lo_c.z, c.z));
            hi_c = pxi_v(fmax(hi_c.x, c.x), fmax(hi_c.y, c.y), fmax(hi_c.z, c.z));
        }
        px_vec3 ext = pxi_sub(hi_c, lo_c);
        int axis = ext.x >= ext.y && ext.x >= ext.z ? 0 : ext.y >= ext.z ? 1 : 2;
        for (uint32_t i = lo; i < hi; ++i) {
            b->keys[i].key = coord(b->centroid[b->order[i]], axis);
            b->keys[i].leaf = b->order[i];
        }
        qsort(b->keys + lo, hi - lo, sizeof *b->keys, cmp_key);
        for (uint32_t i = lo; i < hi; ++i) b->order[i] = b->keys[i].leaf;
        uint32_t mid = lo + (hi - lo) / 2;
        uint32_t c0 = build_node(b, lo, mid, depth + 1);
        if (b->status != PX_OK) return id;
        uint32_t c1 = build_node(b, mid, hi, depth + 1);
        if (b->status != PX_OK) return id;
        node = &m->nodes[id];
        node->child[0] = c0;
        node->child[1] = c1;
    }
    /* Bounding sphere about the middle of the subtree's box. */
    size_t n = 0;
    for (uint32_t i = lo; i < hi; ++i) {
        if (!push_leaf_points(b, b->order[i], &n)) {
            b->status = pxi_error(b->err, PX_ERR_OUT_OF_MEMORY, "px_model: out of memory");
            return id;
        }
    }
    px_vec3 bl = b->points[0], bh = bl;
    for (size_t i = 1; i < n; ++i) {
        px_vec3 p = b->points[i];
        bl = pxi_v(fmin(bl.x, p.x), fmin(bl.y, p.y), fmin(bl.z, p.z));
        bh = pxi_v(fmax(bh.x, p.x), fmax(bh.y, p.y), fmax(bh.z, p.z));
    }
    px_vec3 c = pxi_scale(pxi_add(bl, bh), 0.5);
    double r = 0.0;
    for (size_t i = 0; i < n; ++i) r = fmax(r, pxi_len(pxi_sub(b->points[i], c)));
    node->center = c;
    if (hi - lo > 1) {
        node->box = b->next_box++;
        pxi_box_fit(b->points, n, &m->boxes[node->box]);
    }
    /* The radius is rounded up by a few ulps so that the sphere surely holds
     * every point. */
    node->radius = r * (1.0 + 4.0 * DBL_EPSILON) + 0x1p-1000;
    if (id == 0) {
        m->lo = bl;
        m->hi = bh;
    }
    int wants_hull = hi - lo > 1 && (b->convex || (b->hulls && hi - lo >= PX_MODEL_HULL_MIN_LEAVES));
    if (!b->convex && hi - lo > 1 &&
        ((m->nodes[node->child[0]].flags | m->nodes[node->child[1]].flags) & PXI_NODE_OVERSIZE)) {
        node->flags |= PXI_NODE_OVERSIZE;
        wants_hull = 0;
    }
    if (wants_hull) {
        /* From the children's hull vertices where they have hulls. */
        n = 0;
        int ok = 1;
        for (int k = 0; k < 2 && ok; ++k) {
            const pxi_mnode *ch = &m->nodes[node->child[k]];
            if (ch->hull) {
                uint32_t nv = px_convex_vertex_count(ch->hull);
                ok = reserve(b, n, n + nv);
                for (uint32_t j = 0; ok && j < nv; ++j) px_convex_vertex(ch->hull, j, &b->points[n++]);
            } else {
                uint32_t mid = lo + (hi - lo) / 2;
                uint32_t clo = k == 0 ? lo : mid, chi = k == 0 ? mid : hi;
                for (uint32_t i = clo; ok && i < chi; ++i) ok = push_leaf_points(b, b->order[i], &n);
            }
        }
        if (!ok) {
            b->status = pxi_error(b->err, PX_ERR_OUT_OF_MEMORY, "px_model: out of memory");
            return id;
        }
        node->hull = hull_of_points(b, n);
        if (node->hull && !b->convex && px_convex_vertex_count(node->hull) > PXI_HULL_MAX_VERTICES) {
            px_convex_destroy(node->hull);
            node->hull = NULL;
            node->flags |= PXI_NODE_OVERSIZE;
        }
        if (node->hull) m->n_hulls++;
    }
    return id;
}

/* ---- Construction ------------------------------------------------------- */

px_model *pxi_model_alloc(const px_model_options *options, px_error *err, px_allocator *alloc) {
    if (options) {
        for (size_t i = 0; i < sizeof options->reserved / sizeof options->reserved[0]; ++i) {
            if (options->reserved[i]) {
                pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_model: options.reserved[%zu] is not zero", i);
                return NULL;
            }
        }
        if (options->pieces != PX_PIECES_APPROXIMATE &&
            (options->tolerance != 0.0 || options->progress || options->threads)) {
            pxi_error(err, PX_ERR_INVALID_ARGUMENT,
                      "px_model: options.tolerance, threads and progress are for PX_PIECES_APPROXIMATE only");
            return NULL;
        }
    }
    if (pxi_allocator_resolve(options ? options->allocator : NULL, alloc, err) != PX_OK) return NULL;
    px_model *m = pxi_alloc(alloc, sizeof *m);
    if (!m) {
        pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_model: out of memory");
        return NULL;
    }
    memset(m, 0, sizeof *m);
    m->uid = pxi_next_uid();
    m->alloc = *alloc;
    m->bytes = sizeof *m;
    return m;
}

void px_model_destroy(px_model *m) {
    if (!m) return;
    px_allocator a = m->alloc;
    if (m->nodes) {
        for (uint32_t i = 0; i < m->n_nodes; ++i) px_convex_destroy(m->nodes[i].hull);
    }
    pxi_free(&a, m->nodes, (size_t)m->n_nodes * sizeof *m->nodes);
    if (m->boxes) pxi_free(&a, m->boxes, (size_t)(m->n_leaves - 1) * sizeof *m->boxes);
    pxi_free(&a, m->leaves, (size_t)m->n_leaves * sizeof *m->leaves);
    pxi_free(&a, m->v, (size_t)m->nv * sizeof *m->v);
    pxi_free(&a, m->tri, (size_t)m->nt * 3 * sizeof *m->tri);
    pxi_free(&a, m->tri_solid, m->nt);
    pxi_free(&a, m->reps, (size_t)m->n_reps * sizeof *m->reps);
    pxi_free(&a, m, sizeof *m);
}

/* Builds the tree over m->n_leaves leaves (convex: the pieces of a convex
 * tree, NULL for triangles); takes ownership of the pieces. */
px_status pxi_model_build_tree(px_model *m, px_convex **convex, int hulls, px_error *err) {
    builder b;
    memset(&b, 0, sizeof b);
    b.m = m;
    b.convex = convex;
    b.hulls = hulls;
    b.err = err;
    b.status = PX_OK;
    uint32_t n = m->n_leaves;
    m->n_nodes = 2 * n - 1;
    m->nodes = pxi_alloc_array(&m->alloc, m->n_nodes, sizeof *m->nodes);
    /* Zeroed at once: px_model_destroy frees each node's hull, also when
     * an allocation below fails. */
    if (m->nodes) memset(m->nodes, 0, (size_t)m->n_nodes * sizeof *m->nodes);
    m->boxes = n > 1 ? pxi_alloc_array(&m->alloc, n - 1, sizeof *m->boxes) : NULL;
    b.centroid = pxi_alloc_array(&m->alloc, n, sizeof *b.centroid);
    b.order = pxi_alloc_array(&m->alloc, n, sizeof *b.order);
    b.keys = pxi_alloc_array(&m->alloc, n, sizeof *b.keys);
    if (!m->nodes || (n > 1 && !m->boxes) || !b.centroid || !b.order || !b.keys) {
        b.status = pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_model: out of memory");
    } else {
        for (uint32_t i = 0; i < n; ++i) {
            b.order[i] = i;
            size_t k = 0;
            if (!push_leaf_points(&b, i, &k)) {
                b.status = pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_model: out of memory");
                break;
            }
            px_vec3 s = pxi_v(0, 0, 0);
            for (size_t j = 0; j < k; ++j) s = pxi_add(s, b.points[j]);
            b.centroid[i] = pxi_scale(s, 1.0 / (double)k);
        }
        if (b.status == PX_OK) build_node(&b, 0, n, 0);
        if (b.status == PX_OK)
            m->bytes += (size_t)m->n_nodes * sizeof *m->nodes + (size_t)(n - 1) * sizeof *m->boxes;
    }
    /* Leaves own their pieces through the nodes; pieces not yet placed in a
     * node (an error part way) are freed here. */
    if (convex && b.status != PX_OK) {
        for (uint32_t i = 0; m->nodes && i < m->n_nodes; ++i) {
            if (m->nodes[i].child[1] == PXI_NONE && m->nodes[i].hull) m->nodes[i].hull = NULL;
        }
        for (uint32_t i = 0; i < n; ++i) px_convex_destroy(convex[i]);
    }
    for (uint32_t i = 0; b.status == PX_OK && i < m->n_nodes; ++i) {
        if (m->nodes[i].hull) m->bytes += px_convex_memory_bytes(m->nodes[i].hull);
    }
    pxi_free(&m->alloc, b.centroid, (size_t)n * sizeof *b.centroid);
    pxi_free(&m->alloc, b.order, (size_t)n * sizeof *b.order);
    pxi_free(&m->alloc, b.keys, (size_t)n * sizeof *b.keys);
    pxi_free(&m->alloc, b.points, b.points_cap * sizeof *b.points);
    return b.status;
}

/* One representative point per connected piece, for containment tests:
 * triangles joined through vertices at exactly equal positions (a
 * union-find over vertex classes). */
typedef struct vkey {
    px_vec3 p;
    uint32_t i;
} vkey;

static int cmp_vkey(const void *x, const void *y) {
    const vkey *a = x, *b = y;
    if (a->p.x != b->p.x) return a->p.x < b->p.x ? -1 : 1;
    if (a->p.y != b->p.y) return a->p.y < b->p.y ? -1 : 1;
    if (a->p.z != b->p.z) return a->p.z < b->p.z ? -1 : 1;
    return a->i < b->i ? -1 : a->i > b->i;
}

static uint32_t uf_find(uint32_t *parent, uint32_t x) {
    while (parent[x] != x) {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    return x;
}

px_status pxi_model_triangle_reps(px_model *m, px_error *err) {
    uint32_t nv = m->nv;
    vkey *keys = pxi_alloc_array(&m->alloc, nv, sizeof *keys);
    uint32_t *parent = pxi_alloc_array(&m->alloc, nv, sizeof *parent);
    px_status st = PX_OK;
    if (!keys || !parent) {
        st = pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_model: out of memory");
    } else {
        for (uint32_t i = 0; i < nv; ++i) {
            keys[i].p = m->v[i];
            keys[i].i = i;
            parent[i] = i;
        }
        qsort(keys, nv, sizeof *keys, cmp_vkey);
        for (uint32_t i = 1; i < nv; ++i) {
            if (keys[i].p.x == keys[i - 1].p.x && keys[i].p.y == keys[i - 1].p.y &&
                keys[i].p.z == keys[i - 1].p.z)
                parent[uf_find(parent, keys[i].i)] = uf_find(parent, keys[i - 1].i);
        }
        for (uint32_t t = 0; t < m->nt; ++t) {
            uint32_t r0 = uf_find(parent, m->tri[3 * t]);
            for (int k = 1; k < 3; ++k) {
                uint32_t r = uf_find(parent, m->tri[3 * t + k]);
                if (r != r0) parent[r] = r0;
            }
        }
        /* Mark the roots of vertices used by triangles (keys[].i reused as
         * a flag array). */
        uint32_t count = 0;
        for (uint32_t i = 0; i < nv; ++i) keys[i].i = 0;
        for (uint32_t t = 0; t < m->nt; ++t) {
            uint32_t r = uf_find(parent, m->tri[3 * t]);
            if (!keys[r].i) {
                keys[r].i = 1;
                keys[r].p = m->v[m->tri[3 * t]];
                ++count;
            }
        }
        m->reps = pxi_alloc_array(&m->alloc, count, sizeof *m->reps);
        if (!m->reps) {
            st = pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_model: out of memory");
        } else {
            for (uint32_t i = 0; i < nv; ++i)
                if (keys[i].i) m->reps[m->n_reps++] = keys[i].p;
            m->bytes += (size_t)count * sizeof *m->reps;
        }
    }
    pxi_free(&m->alloc, keys, (size_t)nv * sizeof *keys);
    pxi_free(&m->alloc, parent, (size_t)nv * sizeof *parent);
    return st;
}

/* Convex trees: one representative vertex per piece. */
px_status pxi_model_convex_reps(px_model *m, px_convex **convex, px_error *err) {
    m->reps = pxi_alloc_array(&m->alloc, m->n_leaves, sizeof *m->reps);
    if (!m->reps) return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_model: out of memory");
    for (uint32_t i = 0; i < m->n_leaves; ++i) px_convex_vertex(convex[i], 0, &m->reps[i]);
    m->n_reps = m->n_leaves;
    m->bytes += (size_t)m->n_reps * sizeof *m->reps;
    return PX_OK;
}

px_model *pxi_model_finish(px_model *m, px_status st, px_error *err) {
    if (st != PX_OK) {
        px_model_destroy(m);
        return NULL;
    }
    pxi_error_clear(err);
    return m;
}

px_model *px_model_create_from_points(const double *xyz, const uint32_t *piece_end, uint32_t piece_count,
                                      const px_model_options *options, px_error *err) {
    if (!xyz || !piece_end || piece_count == 0) {
        pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_model_create_from_points: %s",
                  piece_count == 0 ? "no pieces" : "NULL array");
        return NULL;
    }
    if (options && options->pieces) {
        pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_model_create_from_points: options.pieces must be 0");
        return NULL;
    }
    if (piece_count > (1u << 30)) {
        pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_model_create_from_points: too many pieces (%u)",
                  piece_count);
        return NULL;
    }
    if (pxi_model_check_range(xyz, piece_end[piece_count - 1], 0, err) != PX_OK) return NULL;
    px_allocator alloc;
    px_model *m = pxi_model_alloc(options, err, &alloc);
    if (!m) return NULL;
    m->pieces = PX_PIECES_POINTS;
    m->n_leaves = piece_count;
    m->leaves = pxi_alloc_array(&alloc, piece_count, sizeof *m->leaves);
    px_convex **convex = pxi_alloc_array(&alloc, piece_count, sizeof *convex);
    px_status st = PX_OK;
    if (!m->leaves || !convex) {
        st = pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_model: out of memory");
    } else {
        m->bytes += (size_t)piece_count * sizeof *m->leaves;
        memset(convex, 0, (size_t)piece_count * sizeof *convex);
        px_convex_options co;
        memset(&co, 0, sizeof co);
        co.allocator = &m->alloc;
        uint32_t start = 0;
        for (uint32_t i = 0; i < piece_count && st == PX_OK; ++i) {
            if (piece_end[i] <= start) {
                st = pxi_error(err, PX_ERR_INVALID_ARGUMENT,
                               "px_model_create_from_points: piece %u is empty: piece_end[%u] = %u is not "
                               "above the piece's start %u (piece_end must increase)",
                               i, i, piece_end[i], start);
                break;
            }
            px_error e;
            convex[i] = px_convex_create(xyz + 3 * (size_t)start, piece_end[i] - start, &co, &e);
            if (!convex[i])
                st = pxi_error(err, e.code, "px_model_create_from_points: piece %u: %s", i, e.message);
            m->leaves[i].part = i;
            m->leaves[i].tri = PXI_NONE;
            m->leaves[i].h = m->leaves[i].h_overlap = 0.0;
            start = piece_end[i];
        }
        if (st == PX_OK) st = pxi_model_convex_reps(m, convex, err);
        if (st == PX_OK) {
            st = pxi_model_build_tree(m, convex, 1, err);
        } else {
            for (uint32_t i = 0; i < piece_count; ++i) px_convex_destroy(convex[i]);
        }
    }
    pxi_free(&alloc, convex, (size_t)piece_count * sizeof *convex);
    return pxi_model_finish(m, st, err);
}

px_status pxi_model_check_range(const double *xyz, size_t n, int triangles, px_error *err) {
    double big = 0.0, lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < 3 * n; ++i) {
        big = fmax(big, fabs(xyz[i]));
        lo[i % 3] = fmin(lo[i % 3], xyz[i]);
        hi[i % 3] = fmax(hi[i % 3], xyz[i]);
    }
    double size = n ? fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2])) : 0.0;
    if (!(big <= PXI_MODEL_MAX_COORD))
        return pxi_error(err, PX_ERR_RANGE,
                         "px_model: a coordinate of magnitude %.3g is beyond the models' range 2^250", big);
    if (triangles && size > 0.0 && size < PXI_MODEL_MIN_SIZE)
        return pxi_error(
            err, PX_ERR_RANGE,
            "px_model: the triangles span %.3g, below the triangle models' range 2^-250 (their closest "
            "points square lengths)",
            size);
    return PX_OK;
}

/* Copies vertices and triangles into the model (body frame = mesh frame). */
static px_status copy_triangles(px_model *m, const double *xyz, uint32_t nv, const uint32_t *tri, uint32_t nt,
                                px_error *err) {
    m->v = pxi_alloc_array(&m->alloc, nv, sizeof *m->v);
    m->tri = pxi_alloc_array(&m->alloc, (size_t)nt * 3, sizeof *m->tri);
    m->tri_solid = pxi_alloc_array(&m->alloc, nt, 1);
    if (!m->v || !m->tri || !m->tri_solid) {
        pxi_free(&m->alloc, m->v, (size_t)nv * sizeof *m->v);
        pxi_free(&m->alloc, m->tri, (size_t)nt * 3 * sizeof *m->tri);
        pxi_free(&m->alloc, m->tri_solid, nt);
        m->v = NULL;
        m->tri = NULL;
        m->tri_solid = NULL;
        return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_model: out of memory");
    }
    m->nv = nv;
    m->nt = nt;
    for (uint32_t i = 0; i < nv; ++i) m->v[i] = pxi_v(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
    memcpy(m->tri, tri, (size_t)nt * 3 * sizeof *tri);
    memset(m->tri_solid, 0, nt);
    m->bytes += (size_t)nv * sizeof *m->v + (size_t)nt * (3 * sizeof *tri + 1);
    return PX_OK;
}

px_model *pxi_model_from_triangles(const double *xyz, uint32_t nv, const uint32_t *tri, uint32_t nt,
                                   const uint32_t *part, const uint8_t *closed, uint32_t n_parts, int hulls,
                                   const px_allocator *alloc_in, px_error *err) {
    px_model_options o;
    memset(&o, 0, sizeof o);
    o.allocator = alloc_in;
    px_allocator alloc;
    px_model *m = pxi_model_alloc(&o, err, &alloc);
    if (!m) return NULL;
    m->pieces = PX_PIECES_TRIANGLES;
    px_status st = pxi_model_check_range(xyz, nv, 1, err);
    if (st == PX_OK) st = copy_triangles(m, xyz, nv, tri, nt, err);
    if (st == PX_OK) {
        m->n_leaves = nt;
        m->leaves = pxi_alloc_array(&alloc, nt, sizeof *m->leaves);
        if (!m->leaves) st = pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_model: out of memory");
    }
    if (st == PX_OK) {
        m->bytes += (size_t)nt * sizeof *m->leaves;
        for (uint32_t t = 0; t < nt; ++t) {
            m->leaves[t].part = part ? part[t] : 0;
            m->leaves[t].tri = t;
            m->leaves[t].h = m->leaves[t].h_overlap = 0.0;
            m->tri_solid[t] = closed && part && part[t] < n_parts ? closed[part[t]] : 0;
        }
        for (uint32_t p = 0; closed && p < n_parts; ++p) m->solid_parts += closed[p] != 0;
        st = pxi_model_triangle_reps(m, err);
    }
    if (st == PX_OK) st = pxi_model_build_tree(m, NULL, hulls, err);
    return pxi_model_finish(m, st, err);
}

/* ---- Accessors ---------------------------------------------------------- */

px_status px_model_get_info(const px_model *m, px_model_info *out) {
    if (out) memset(out, 0, sizeof *out);
    if (!m || !out) return PX_ERR_INVALID_ARGUMENT;
    out->pieces = m->pieces;
    out->leaves = m->n_leaves;
    out->nodes = m->n_nodes;
    out->hull_nodes = m->n_hulls;
    out->depth = m->depth;
    out->solid_parts = m->solid_parts;
    out->solid = m->pieces != PX_PIECES_TRIANGLES;
    if (m->pieces == PX_PIECES_TRIANGLES) {
        out->solid = 1;
        for (uint32_t t = 0; t < m->nt; ++t) out->solid &= m->tri_solid[t];
    }
    out->max_h = m->max_h;
    out->min = m->lo;
    out->max = m->hi;
    out->memory_bytes = m->bytes;
    return PX_OK;
}

px_status px_model_get_leaf(const px_model *m, uint32_t i, px_model_leaf *out) {
    if (out) memset(out, 0, sizeof *out);
    if (!m || !out || i >= m->n_leaves) return PX_ERR_INVALID_ARGUMENT;
    out->part = m->leaves[i].part;
    out->triangle = m->leaves[i].tri;
    out->h = m->leaves[i].h;
    out->h_overlap = m->leaves[i].h_overlap;
    return PX_OK;
}
