/* .pxm: models saved so that the build runs once.
 *
 * Layout (all integers and doubles little-endian):
 *   header (88 bytes): magic "PXMODEL\0", u32 version, u32 pieces,
 *     u32 n_leaves, nv, nt, n_reps, solid_parts, n_hull_vertices, f64 max_h,
 *     u64 payload_bytes, u64 checksum (FNV-1a, 64 bits, over the header's
 *     first 56 bytes and the payload),
 *     u32 reserved[6] = 0;
 *   payload:
 *     nodes (2 n_leaves - 1, preorder): u32 child0, child1 (child1 =
 *       0xffffffff for a leaf, child0 then its leaf index), u32 flags,
 *       u32 hull vertex count (0: no hull);
 *     leaves: u32 part, u32 triangle, f64 h, f64 h_overlap;
 *     vertices: nv x 3 f64; triangles: nt x 3 u32; solid flags: nt u8;
 *     representative points: n_reps x 3 f64;
 *     hull vertices: n_hull_vertices x 3 f64, node by node.
 * The reader checks every size against the bytes present before allocating,
 * the checksum, every index and the tree's shape, rebuilds each hull from
 * its vertices (px_convex_create) and checks that it holds its children
 * (their hull vertices, or the leaves' points), and recomputes the bounding
 * spheres from the points. What it cannot check without redoing the build
 * is a part's bound h: a file crafted to lie about h gives a wrong bracket
 * (never a wrong distance). */
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "convex/convex.h"
#include "core/core.h"
#include "model/model.h"

#define PXM_MAGIC "PXMODEL"
#define PXM_VERSION 1u
#define PXM_HEADER 88u
#define PXM_NODE 16u
#define PXM_LEAF 24u
#define FNV_SEED 0xcbf29ce484222325ull

/* ---- Byte helpers ------------------------------------------------------- */

typedef struct wbuf {
    unsigned char *p;
    size_t n, cap;
    int failed;
    const px_allocator *a;
} wbuf;

static void w_bytes(wbuf *w, const void *src, size_t n) {
    if (w->failed) return;
    if (w->n + n > w->cap) {
        size_t cap = w->cap ? w->cap : 4096;
        while (cap < w->n + n) cap *= 2;
        unsigned char *p = pxi_alloc(w->a, cap);
        if (!p) {
            w->failed = 1;
            return;
        }
        if (w->p) memcpy(p, w->p, w->n);
        pxi_free(w->a, w->p, w->cap);
        w->p = p;
        w->cap = cap;
    }
    memcpy(w->p + w->n, src, n);
    w->n += n;
}

static void w_u32(wbuf *w, uint32_t v) {
    unsigned char b[4] = {(unsigned char)v, (unsigned char)(v >> 8), (unsigned char)(v >> 16),
                          (unsigned char)(v >> 24)};
    w_bytes(w, b, 4);
}

static void w_u64(wbuf *w, uint64_t v) {
    w_u32(w, (uint32_t)v);
    w_u32(w, (uint32_t)(v >> 32));
}

static void w_f64(wbuf *w, double d) {
    uint64_t v;
    memcpy(&v, &d, 8);
    w_u64(w, v);
}

static void w_vec(wbuf *w, px_vec3 v) {
    w_f64(w, v.x);
    w_f64(w, v.y);
    w_f64(w, v.z);
}

static uint32_t r_u32(const unsigned char *p) {
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static uint64_t r_u64(const unsigned char *p) { return (uint64_t)r_u32(p) | (uint64_t)r_u32(p + 4) << 32; }

static double r_f64(const unsigned char *p) {
    uint64_t v = r_u64(p);
    double d;
    memcpy(&d, &v, 8);
    return d;
}

static px_vec3 r_vec(const unsigned char *p) { return pxi_v(r_f64(p), r_f64(p + 8), r_f64(p + 16)); }

static uint64_t fnv1a(uint64_t h, const unsigned char *p, size_t n) {
    for (size_t i = 0; i < n; ++i) {
        h ^= p[i];
        h *= 0x100000001b3ull;
    }
    return h;
}

/* ---- Writing ------------------------------------------------------------ */

static void write_payload(const px_model *m, wbuf *w, uint32_t *hull_vertices) {
    *hull_vertices = 0;
    for (uint32_t i = 0; i < m->n_nodes; ++i) {
        const pxi_mnode *n = &m->nodes[i];
        uint32_t hv = n->hull ? px_convex_vertex_count(n->hull) : 0;
        w_u32(w, n->child[0]);
        w_u32(w, n->child[1]);
        w_u32(w, n->flags);
        w_u32(w, hv);
        *hull_vertices += hv;
    }
    for (uint32_t i = 0; i < m->n_leaves; ++i) {
        w_u32(w, m->leaves[i].part);
        w_u32(w, m->leaves[i].tri);
        w_f64(w, m->leaves[i].h);
        w_f64(w, m->leaves[i].h_overlap);
    }
    for (uint32_t i = 0; i < m->nv; ++i) w_vec(w, m->v[i]);
    for (uint32_t i = 0; i < 3 * m->nt; ++i) w_u32(w, m->tri[i]);
    if (m->nt) w_bytes(w, m->tri_solid, m->nt);
    for (uint32_t i = 0; i < m->n_reps; ++i) w_vec(w, m->reps[i]);
    for (uint32_t i = 0; i < m->n_nodes; ++i) {
        const px_convex *h = m->nodes[i].hull;
        uint32_t hv = h ? px_convex_vertex_count(h) : 0;
        for (uint32_t k = 0; k < hv; ++k) {
            px_vec3 p;
            px_convex_vertex(h, k, &p);
            w_vec(w, p);
        }
    }
}

px_status px_model_save(const px_model *m, const char *path, px_error *err) {
    if (!m || !path || !*path)
        return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_model_save: NULL model or path");
    wbuf w = {NULL, 0, 0, 0, &m->alloc};
    uint32_t hull_vertices;
    write_payload(m, &w, &hull_vertices);
    if (w.failed) {
        pxi_free(&m->alloc, w.p, w.cap);
        return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_model_save: out of memory for '%s'", path);
    }
    wbuf h = {NULL, 0, 0, 0, &m->alloc};
    w_bytes(&h, PXM_MAGIC, 8);
    w_u32(&h, PXM_VERSION);
    w_u32(&h, m->pieces);
    w_u32(&h, m->n_leaves);
    w_u32(&h, m->nv);
    w_u32(&h, m->nt);
    w_u32(&h, m->n_reps);
    w_u32(&h, m->solid_parts);
    w_u32(&h, hull_vertices);
    w_f64(&h, m->max_h);
    w_u64(&h, w.n);
    w_u64(&h, h.failed ? 0 : fnv1a(fnv1a(FNV_SEED, h.p, 56), w.p, w.n));
    for (int i = 0; i < 6; ++i) w_u32(&h, 0);
    px_status st = PX_OK;
    if (h.failed) {
        st = pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_model_save: out of memory for '%s'", path);
    } else {
        FILE *f = fopen(path, "wb");
        if (!f) {
            st = pxi_error(err, PX_ERR_IO, "px_model_save: cannot create '%s': %s", path, strerror(errno));
        } else {
            int ok = fwrite(h.p, 1, h.n, f) == h.n && fwrite(w.p, 1, w.n, f) == w.n;
            ok = (fclose(f) == 0) && ok;
            if (!ok) st = pxi_error(err, PX_ERR_IO, "px_model_save: cannot write '%s'", path);
        }
    }
    pxi_free(&m->alloc, w.p, w.cap);
    pxi_free(&m->alloc, h.p, h.cap);
    if (st == PX_OK) pxi_error_clear(err);
    return st;
}

/* ---- Reading ------------------------------------------------------------ */

typedef struct reader {
    const char *name;
    px_error *err;
    px_status st;
} reader;

#define BAD(r, ...) ((r)->st = pxi_error((r)->err, PX_ERR_IO, __VA_ARGS__), (void)0)

/* Tolerance of the containment checks: a relative 1e-9 of the hull's size. */
static double hull_tol(const px_convex *h) {
    px_bounds bd;
    px_convex_bounds(h, NULL, &bd);
    return 1e-9 * (bd.radius + pxi_len(bd.center));
}

/* Is p inside hull h, within tol? */
static int inside(const px_convex *h, px_vec3 p, double tol) {
    uint32_t nf = px_convex_face_count(h);
    for (uint32_t f = 0; f < nf; ++f) {
        px_vec3 n;
        double off;
        px_convex_face(h, f, &n, &off, NULL);
        if (pxi_dot(n, p) - off > tol) return 0;
    }
    return 1;
}

/* Points of leaf `leaf`: a triangle's corners or a convex piece's vertices. */
static uint32_t leaf_points(const px_model *m, uint32_t node, px_vec3 *out, uint32_t cap) {
    const pxi_mnode *n = &m->nodes[node];
    const pxi_mleaf *leaf = &m->leaves[n->child[0]];
    if (leaf->tri != PXI_NONE) {
        for (int k = 0; k < 3; ++k) out[k] = m->v[m->tri[3 * (size_t)leaf->tri + k]];
        return 3;
    }
    uint32_t c = px_convex_vertex_count(n->hull);
    if (c > cap) c = cap; /* never: the caller sizes out for the largest leaf */
    for (uint32_t k = 0; k < c; ++k) px_convex_vertex(n->hull, k, &out[k]);
    return c;
}

/* Bounding spheres and hull containment, bottom up (children have larger
 * ids than their parent: preorder). */
static void finish_nodes(px_model *m, reader *r) {
    /* Box and radius per node from its subtree's points: each leaf's points
     * are pushed into every ancestor through a parent array. */
    uint32_t nn = m->n_nodes;
    uint32_t *parent = pxi_alloc_array(&m->alloc, nn, sizeof *parent);
    px_vec3 *lo = pxi_alloc_array(&m->alloc, nn, sizeof *lo),
            *hi = pxi_alloc_array(&m->alloc, nn, sizeof *hi);
    uint32_t cap = 3;
    for (uint32_t i = 0; i < nn; ++i)
        if (m->nodes[i].child[1] == PXI_NONE && m->nodes[i].hull &&
            px_convex_vertex_count(m->nodes[i].hull) > cap)
            cap = px_convex_vertex_count(m->nodes[i].hull);
    px_vec3 *pts = pxi_alloc_array(&m->alloc, cap, sizeof *pts);
    double *tol = pxi_alloc_array(&m->alloc, nn, sizeof *tol);
    if (!parent || !lo || !hi || !pts || !tol) {
        r->st = pxi_error(r->err, PX_ERR_OUT_OF_MEMORY, "px_model_load: out of memory for '%s'", r->name);
    } else {
        parent[0] = PXI_NONE;
        for (uint32_t i = 0; i < nn; ++i) {
            tol[i] = m->nodes[i].hull ? hull_tol(m->nodes[i].hull) : 0.0;
            lo[i] = pxi_v(INFINITY, INFINITY, INFINITY);
            hi[i] = pxi_v(-INFINITY, -INFINITY, -INFINITY);
            if (m->nodes[i].child[1] != PXI_NONE)
                parent[m->nodes[i].child[0]] = parent[m->nodes[i].child[1]] = i;
        }
        for (int pass = 0; pass < 2 && r->st == PX_OK; ++pass) {
            /* pass 0: boxes; pass 1: radii about the boxes' middles, and
             * every point inside every ancestor hull. */
            if (pass == 1)
                for (uint32_t i = 0; i < nn; ++i) {
                    m->nodes[i].center = pxi_scale(pxi_add(lo[i], hi[i]), 0.5);
                    m->nodes[i].radius = 0.0;
                }
            for (uint32_t i = 0; i < nn && r->st == PX_OK; ++i) {
                if (m->nodes[i].child[1] != PXI_NONE) continue;
                uint32_t np = leaf_points(m, i, pts, cap);
                for (uint32_t k = 0; k < np; ++k) {
                    px_vec3 p = pts[k];
                    for (uint32_t a = i; a != PXI_NONE; a = parent[a]) {
                        pxi_mnode *n = &m->nodes[a];
                        if (pass == 0) {
                            lo[a] = pxi_v(fmin(lo[a].x, p.x), fmin(lo[a].y, p.y), fmin(lo[a].z, p.z));
                            hi[a] = pxi_v(fmax(hi[a].x, p.x), fmax(hi[a].y, p.y), fmax(hi[a].z, p.z));
                        } else {
                            n->radius = fmax(n->radius, pxi_len(pxi_sub(p, n->center)));
                            if (n->hull && a != i && !inside(n->hull, p, tol[a])) {
                                BAD(r, "px_model_load: '%s': the hull of node %u does not hold its subtree",
                                    r->name, a);
                                break;
                            }
                        }
                    }
                }
            }
        }
        if (r->st == PX_OK) {
            for (uint32_t i = 0; i < nn; ++i)
                m->nodes[i].radius = m->nodes[i].radius * (1.0 + 4.0 * DBL_EPSILON) + 0x1p-1000;
            m->lo = lo[0];
            m->hi = hi[0];
        }
    }
    pxi_free(&m->alloc, parent, (size_t)nn * sizeof *parent);
    pxi_free(&m->alloc, lo, (size_t)nn * sizeof *lo);
    pxi_free(&m->alloc, hi, (size_t)nn * sizeof *hi);
    pxi_free(&m->alloc, pts, (size_t)cap * sizeof *pts);
    pxi_free(&m->alloc, tol, (size_t)nn * sizeof *tol);
}

/* The boxes of the inner nodes, fitted to their subtrees' points as the
 * build does. */
static void compute_boxes(px_model *m, reader *r) {
    uint32_t nl = m->n_leaves;
    if (nl < 2) return;
    m->boxes = pxi_alloc_array(&m->alloc, nl - 1, sizeof *m->boxes);
    uint32_t cap = 0;
    for (uint32_t i = 0; i < m->n_nodes; ++i)
        if (m->nodes[i].child[1] == PXI_NONE)
            cap += m->nodes[i].hull ? px_convex_vertex_count(m->nodes[i].hull) : 3;
    px_vec3 *pts = pxi_alloc_array(&m->alloc, cap, sizeof *pts);
    uint32_t *stack = pxi_alloc_array(&m->alloc, m->n_nodes, sizeof *stack);
    if (!m->boxes || !pts || !stack) {
        r->st = pxi_error(r->err, PX_ERR_OUT_OF_MEMORY, "px_model_load: out of memory for '%s'", r->name);
    } else {
        m->bytes += (size_t)(nl - 1) * sizeof *m->boxes;
        uint32_t next = 0;
        for (uint32_t i = 0; i < m->n_nodes; ++i) {
            if (m->nodes[i].child[1] == PXI_NONE) continue;
            uint32_t top = 0, n = 0;
            stack[top++] = i;
            while (top) {
                uint32_t k = stack[--top];
                if (m->nodes[k].child[1] != PXI_NONE) {
                    stack[top++] = m->nodes[k].child[0];
                    stack[top++] = m->nodes[k].child[1];
                } else {
                    n += leaf_points(m, k, pts + n, cap - n);
                }
            }
            m->nodes[i].box = next;
            pxi_box_fit(pts, n, &m->boxes[next++]);
        }
    }
    pxi_free(&m->alloc, pts, (size_t)cap * sizeof *pts);
    pxi_free(&m->alloc, stack, (size_t)m->n_nodes * sizeof *stack);
}

static int cmp_u32(const void *x, const void *y) {
    uint32_t a = *(const uint32_t *)x, b = *(const uint32_t *)y;
    return a < b ? -1 : a > b;
}

/* Solids and representative points are derived from the geometry, not
 * taken from the file: the closed flags are recomputed by px_mesh_create
 * over each part's triangles (its rule: exact join, every edge used twice
 * in opposite directions, no zero-area triangle, outward orientation), and
 * must match the file's; the representative points are recomputed. */
static void check_solids(px_model *m, reader *r) {
    /* Replace the file's representative points. */
    pxi_free(&m->alloc, m->reps, (size_t)m->n_reps * sizeof *m->reps);
    m->bytes -= (size_t)m->n_reps * sizeof *m->reps;
    m->reps = NULL;
    m->n_reps = 0;
    if (m->pieces != PX_PIECES_TRIANGLES) {
        px_convex **pieces = pxi_alloc_array(&m->alloc, m->n_leaves, sizeof *pieces);
        if (!pieces) {
            r->st = pxi_error(r->err, PX_ERR_OUT_OF_MEMORY, "px_model_load: out of memory for '%s'", r->name);
            return;
        }
        for (uint32_t i = 0; i < m->n_nodes; ++i)
            if (m->nodes[i].child[1] == PXI_NONE) pieces[m->nodes[i].child[0]] = m->nodes[i].hull;
        r->st = pxi_model_convex_reps(m, pieces, r->err);
        pxi_free(&m->alloc, pieces, (size_t)m->n_leaves * sizeof *pieces);
        return;
    }
    r->st = pxi_model_triangle_reps(m, r->err);
    if (r->st != PX_OK) return;
    /* Parts: contiguous triangle ranges (leaves are in the mesh's triangle
     * order) over disjoint vertex ranges, as px_mesh made them. */
    uint32_t nt = m->nt, np = 0;
    px_mesh_part_desc *parts = pxi_alloc_array(&m->alloc, nt, sizeof *parts);
    if (!parts) {
        r->st = pxi_error(r->err, PX_ERR_OUT_OF_MEMORY, "px_model_load: out of memory for '%s'", r->name);
        return;
    }
    memset(parts, 0, (size_t)nt * sizeof *parts);
    uint32_t prev = PXI_NONE - 1, solid_parts = 0;
    for (uint32_t t = 0; t < nt && r->st == PX_OK; ++t) {
        uint32_t part = m->leaves[t].part;
        if (part == PXI_NONE) {
            if (m->tri_solid[t])
                BAD(r, "px_model_load: '%s': triangle %u of no part is marked solid", r->name, t);
            prev = PXI_NONE;
            continue;
        }
        if (part != prev) {
            parts[np].first_triangle = t;
            parts[np].triangle_count = 0;
            parts[np].node = -1;
            parts[np].first_vertex = UINT32_MAX;
            parts[np].vertex_count = 0;
            parts[np].reserved = part; /* the part's id, while checking */
            ++np;
            prev = part;
        }
        px_mesh_part_desc *d = &parts[np - 1];
        d->triangle_count++;
        for (int k = 0; k < 3; ++k) {
            uint32_t v = m->tri[3 * (size_t)t + k];
            uint32_t end = d->first_vertex == UINT32_MAX ? 0 : d->first_vertex + d->vertex_count;
            if (d->first_vertex == UINT32_MAX) d->first_vertex = v, end = v + 1;
            if (v < d->first_vertex) d->first_vertex = v;
            if (v + 1 > end) end = v + 1;
            d->vertex_count = end - d->first_vertex;
        }
        if (m->tri_solid[t] != m->tri_solid[d->first_triangle])
            BAD(r, "px_model_load: '%s': part %u is partly solid", r->name, part);
    }
    /* Each part one run of triangles: no id twice among the runs. */
    uint32_t *ids = r->st == PX_OK && np ? pxi_alloc_array(&m->alloc, np, sizeof *ids) : NULL;
    if (r->st == PX_OK && np && !ids)
        r->st = pxi_error(r->err, PX_ERR_OUT_OF_MEMORY, "px_model_load: out of memory for '%s'", r->name);
    if (ids) {
        for (uint32_t i = 0; i < np; ++i) ids[i] = parts[i].reserved;
        qsort(ids, np, sizeof *ids, cmp_u32);
        for (uint32_t i = 1; i < np && r->st == PX_OK; ++i)
            if (ids[i] == ids[i - 1])
                BAD(r, "px_model_load: '%s': the triangles of part %u are not contiguous", r->name, ids[i]);
        pxi_free(&m->alloc, ids, (size_t)np * sizeof *ids);
    }
    px_mesh *mesh = NULL;
    if (r->st == PX_OK && np) {
        for (uint32_t i = 0; i < np; ++i) parts[i].reserved = 0;
        double *xyz = pxi_alloc_array(&m->alloc, (size_t)m->nv * 3, sizeof *xyz);
        if (!xyz) {
            r->st = pxi_error(r->err, PX_ERR_OUT_OF_MEMORY, "px_model_load: out of memory for '%s'", r->name);
        } else {
            for (uint32_t i = 0; i < m->nv; ++i)
                xyz[3 * i] = m->v[i].x, xyz[3 * i + 1] = m->v[i].y, xyz[3 * i + 2] = m->v[i].z;
            px_mesh_desc desc;
            memset(&desc, 0, sizeof desc);
            desc.xyz = xyz;
            desc.vertex_count = m->nv;
            desc.triangles = m->tri;
            desc.triangle_count = nt;
            desc.parts = parts;
            desc.part_count = np;
            px_mesh_options mo;
            memset(&mo, 0, sizeof mo);
            mo.allocator = &m->alloc;
            px_error e;
            mesh = px_mesh_create(&desc, &mo, &e);
            if (!mesh) BAD(r, "px_model_load: '%s': its triangles do not form parts: %s", r->name, e.message);
            pxi_free(&m->alloc, xyz, (size_t)m->nv * 3 * sizeof *xyz);
        }
    }
    for (uint32_t i = 0; mesh && i < np && r->st == PX_OK; ++i) {
        px_mesh_part mp;
        px_mesh_get_part(mesh, i, &mp);
        uint8_t flag = m->tri_solid[parts[i].first_triangle];
        if (flag != (mp.closed != 0))
            BAD(r, "px_model_load: '%s': a part is marked %s but its triangles are %s", r->name,
                flag ? "solid" : "open", mp.closed ? "closed" : "open");
        solid_parts += flag;
    }
    if (mesh && r->st == PX_OK &&
        memcmp(px_mesh_triangles(mesh), m->tri, (size_t)nt * 3 * sizeof *m->tri) != 0)
        BAD(r, "px_model_load: '%s': a closed part is inside out", r->name);
    if (r->st == PX_OK && solid_parts != m->solid_parts)
        BAD(r, "px_model_load: '%s': the header counts %u solid parts, the triangles %u", r->name,
            m->solid_parts, solid_parts);
    px_mesh_destroy(mesh);
    pxi_free(&m->alloc, parts, (size_t)nt * sizeof *parts);
}

static int finite3(px_vec3 v) { return isfinite(v.x) && isfinite(v.y) && isfinite(v.z); }

static px_model *load_memory(const unsigned char *d, size_t size, const px_model_options *options,
                             reader *r) {
    if (size < PXM_HEADER) {
        BAD(r, "px_model_load: '%s' is too short for a .pxm header (%zu bytes)", r->name, size);
        return NULL;
    }
    if (memcmp(d, PXM_MAGIC, 8) != 0) {
        BAD(r, "px_model_load: '%s' is not a .pxm file (bad magic)", r->name);
        return NULL;
    }
    uint32_t version = r_u32(d + 8);
    if (version != PXM_VERSION) {
        BAD(r, "px_model_load: '%s' is .pxm version %u; this library reads version %u", r->name, version,
            PXM_VERSION);
        return NULL;
    }
    uint32_t pieces = r_u32(d + 12), nl = r_u32(d + 16), nv = r_u32(d + 20), nt = r_u32(d + 24);
    uint32_t n_reps = r_u32(d + 28), solid_parts = r_u32(d + 32), nhv = r_u32(d + 36);
    double max_h = r_f64(d + 40);
    uint64_t payload = r_u64(d + 48), checksum = r_u64(d + 56);
    for (int i = 0; i < 6; ++i)
        if (r_u32(d + 64 + 4 * i)) {
            BAD(r, "px_model_load: '%s': reserved header field %d is not zero", r->name, i);
            return NULL;
        }
    if (pieces > PX_PIECES_APPROXIMATE || nl == 0 || nl > (1u << 30) || !(max_h >= 0.0) || !isfinite(max_h)) {
        BAD(r, "px_model_load: '%s': bad header (pieces %u, leaves %u)", r->name, pieces, nl);
        return NULL;
    }
    uint64_t nn = 2 * (uint64_t)nl - 1;
    uint64_t need = nn * PXM_NODE + (uint64_t)nl * PXM_LEAF + (uint64_t)nv * 24 + (uint64_t)nt * 13 +
                    (uint64_t)n_reps * 24 + (uint64_t)nhv * 24;
    if (payload != need || size - PXM_HEADER != payload) {
        BAD(r,
            "px_model_load: '%s': sizes do not match (payload %llu bytes, the header's counts need %llu, the "
            "file "
            "holds %zu)",
            r->name, (unsigned long long)payload, (unsigned long long)need, size - PXM_HEADER);
        return NULL;
    }
    const unsigned char *p = d + PXM_HEADER;
    if (fnv1a(fnv1a(FNV_SEED, d, 56), p, payload) != checksum) {
        BAD(r, "px_model_load: '%s': checksum mismatch (the file is damaged)", r->name);
        return NULL;
    }
    if ((pieces == PX_PIECES_TRIANGLES) != (nt > 0) || (pieces == PX_PIECES_TRIANGLES && nt != nl)) {
        BAD(r, "px_model_load: '%s': %u triangles for %u leaves of kind %u", r->name, nt, nl, pieces);
        return NULL;
    }
    px_allocator alloc;
    if (options) {
        for (size_t i = 0; i < sizeof options->reserved / sizeof options->reserved[0]; ++i)
            if (options->reserved[i] || options->pieces || options->tolerance != 0.0 || options->progress ||
                options->threads) {
                r->st =
                    pxi_error(r->err, PX_ERR_INVALID_ARGUMENT,
                              "px_model_load: options.reserved, pieces, tolerance, threads or progress set");
                return NULL;
            }
    }
    if ((r->st = pxi_allocator_resolve(options ? options->allocator : NULL, &alloc, r->err)) != PX_OK)
        return NULL;
    px_model *m = pxi_alloc(&alloc, sizeof *m);
    if (!m) {
        r->st = pxi_error(r->err, PX_ERR_OUT_OF_MEMORY, "px_model_load: out of memory for '%s'", r->name);
        return NULL;
    }
    memset(m, 0, sizeof *m);
    m->uid = pxi_next_uid();
    m->alloc = alloc;
    m->bytes = sizeof *m;
    m->pieces = pieces;
    m->max_h = max_h;
    m->solid_parts = solid_parts;
    m->nodes = pxi_alloc_array(&alloc, nn, sizeof *m->nodes);
    m->leaves = pxi_alloc_array(&alloc, nl, sizeof *m->leaves);
    m->v = nv ? pxi_alloc_array(&alloc, nv, sizeof *m->v) : NULL;
    m->tri = nt ? pxi_alloc_array(&alloc, (size_t)nt * 3, sizeof *m->tri) : NULL;
    m->tri_solid = nt ? pxi_alloc_array(&alloc, nt, 1) : NULL;
    m->reps = n_reps ? pxi_alloc_array(&alloc, n_reps, sizeof *m->reps) : NULL;
    if (!m->nodes || !m->leaves || (nv && !m->v) || (nt && (!m->tri || !m->tri_solid)) ||
        (n_reps && !m->reps)) {
        r->st = pxi_error(r->err, PX_ERR_OUT_OF_MEMORY, "px_model_load: out of memory for '%s'", r->name);
        pxi_free(&alloc, m->nodes, nn * sizeof *m->nodes);
        pxi_free(&alloc, m->leaves, (size_t)nl * sizeof *m->leaves);
        pxi_free(&alloc, m->v, (size_t)nv * sizeof *m->v);
        pxi_free(&alloc, m->tri, (size_t)nt * 3 * sizeof *m->tri);
        pxi_free(&alloc, m->tri_solid, nt);
        pxi_free(&alloc, m->reps, (size_t)n_reps * sizeof *m->reps);
        pxi_free(&alloc, m, sizeof *m);
        return NULL;
    }
    memset(m->nodes, 0, nn * sizeof *m->nodes);
    m->n_nodes = (uint32_t)nn;
    m->n_leaves = nl;
    m->nv = nv;
    m->nt = nt;
    m->n_reps = n_reps;
    m->bytes += nn * sizeof *m->nodes + (size_t)nl * sizeof *m->leaves + (size_t)nv * sizeof *m->v +
                (size_t)nt * 13 + (size_t)n_reps * sizeof *m->reps;
    /* Nodes: preorder, children after their parent, each node but the root
     * the child of exactly one node, each leaf index used once. */
    uint32_t *hv = pxi_alloc_array(&alloc, nn, sizeof *hv);
    uint8_t *seen = pxi_alloc_array(&alloc, nn + nl, 1);
    if (!hv || !seen)
        r->st = pxi_error(r->err, PX_ERR_OUT_OF_MEMORY, "px_model_load: out of memory for '%s'", r->name);
    if (seen) memset(seen, 0, nn + nl);
    uint64_t hv_total = 0;
    for (uint32_t i = 0; i < nn && r->st == PX_OK; ++i, p += PXM_NODE) {
        pxi_mnode *n = &m->nodes[i];
        n->child[0] = r_u32(p);
        n->child[1] = r_u32(p + 4);
        n->flags = r_u32(p + 8);
        hv[i] = r_u32(p + 12);
        hv_total += hv[i];
        if (n->flags & ~PXI_NODE_OVERSIZE)
            BAD(r, "px_model_load: '%s': node %u has unknown flags", r->name, i);
        if (n->child[1] == PXI_NONE) {
            if (n->child[0] >= nl || seen[nn + n->child[0]]++)
                BAD(r, "px_model_load: '%s': node %u names leaf %u twice or out of range", r->name, i,
                    n->child[0]);
            else if (pieces != PX_PIECES_TRIANGLES && hv[i] == 0)
                BAD(r, "px_model_load: '%s': convex leaf node %u has no hull", r->name, i);
            else if (pieces == PX_PIECES_TRIANGLES && hv[i] != 0)
                BAD(r, "px_model_load: '%s': triangle leaf node %u has a hull", r->name, i);
        } else {
            for (int k = 0; k < 2 && r->st == PX_OK; ++k) {
                uint32_t c = n->child[k];
                if (c <= i || c >= nn || seen[c]++)
                    BAD(r, "px_model_load: '%s': node %u has a bad child %u", r->name, i, c);
            }
        }
    }
    if (r->st == PX_OK && hv_total != nhv)
        BAD(r, "px_model_load: '%s': hull vertex counts do not add up", r->name);
    /* Depth first, before any work that grows with it: the builder's median
     * splits give ceil(log2 leaves) + 1 at most. */
    if (r->st == PX_OK) {
        uint32_t *depth = pxi_alloc_array(&alloc, nn, sizeof *depth);
        if (!depth) {
            r->st = pxi_error(r->err, PX_ERR_OUT_OF_MEMORY, "px_model_load: out of memory for '%s'", r->name);
        } else {
            depth[0] = 0;
            for (uint32_t i = 0; i < nn && r->st == PX_OK; ++i) {
                if (depth[i] > m->depth) m->depth = depth[i];
                if (depth[i] > 64)
                    BAD(r, "px_model_load: '%s': the tree is more than 64 levels deep", r->name);
                if (m->nodes[i].child[1] != PXI_NONE)
                    depth[m->nodes[i].child[0]] = depth[m->nodes[i].child[1]] = depth[i] + 1;
            }
            pxi_free(&alloc, depth, nn * sizeof *depth);
        }
    }
    for (uint32_t i = 0; i < nl && r->st == PX_OK; ++i, p += PXM_LEAF) {
        pxi_mleaf *l = &m->leaves[i];
        l->part = r_u32(p);
        l->tri = r_u32(p + 4);
        l->h = r_f64(p + 8);
        l->h_overlap = r_f64(p + 16);
        int tri_ok = pieces == PX_PIECES_TRIANGLES ? l->tri < nt : l->tri == PXI_NONE;
        if (!tri_ok || !(l->h >= 0.0) || !(l->h_overlap >= l->h) || !isfinite(l->h_overlap) ||
            l->h_overlap > max_h)
            BAD(r, "px_model_load: '%s': leaf %u is malformed", r->name, i);
    }
    for (uint32_t i = 0; i < nv && r->st == PX_OK; ++i, p += 24) {
        m->v[i] = r_vec(p);
        if (!finite3(m->v[i])) BAD(r, "px_model_load: '%s': vertex %u is not finite", r->name, i);
    }
    for (uint32_t i = 0; i < 3 * nt && r->st == PX_OK; ++i, p += 4) {
        m->tri[i] = r_u32(p);
        if (m->tri[i] >= nv)
            BAD(r, "px_model_load: '%s': triangle %u uses vertex %u of %u", r->name, i / 3, m->tri[i], nv);
    }
    if (r->st == PX_OK && nt) {
        memcpy(m->tri_solid, p, nt);
        p += nt;
        for (uint32_t i = 0; i < nt && r->st == PX_OK; ++i)
            if (m->tri_solid[i] > 1) BAD(r, "px_model_load: '%s': bad solid flag", r->name);
    }
    for (uint32_t i = 0; i < n_reps && r->st == PX_OK; ++i, p += 24) {
        m->reps[i] = r_vec(p);
        if (!finite3(m->reps[i])) BAD(r, "px_model_load: '%s': point %u is not finite", r->name, i);
    }
    /* Hulls, rebuilt from their vertices. */
    px_convex_options co;
    memset(&co, 0, sizeof co);
    co.allocator = &m->alloc;
    double *buf = NULL;
    size_t buf_cap = 0;
    for (uint32_t i = 0; i < nn && r->st == PX_OK; ++i) {
        if (!hv[i]) continue;
        if (3 * (size_t)hv[i] > buf_cap) {
            pxi_free(&alloc, buf, buf_cap * sizeof *buf);
            buf_cap = 3 * (size_t)hv[i];
            buf = pxi_alloc_array(&alloc, buf_cap, sizeof *buf);
            if (!buf) {
                buf_cap = 0;
                r->st =
                    pxi_error(r->err, PX_ERR_OUT_OF_MEMORY, "px_model_load: out of memory for '%s'", r->name);
                break;
            }
        }
        for (size_t k = 0; k < 3 * (size_t)hv[i]; ++k, p += 8) buf[k] = r_f64(p);
        px_error e;
        m->nodes[i].hull = px_convex_create(buf, hv[i], &co, &e);
        if (!m->nodes[i].hull) {
            BAD(r, "px_model_load: '%s': hull of node %u: %s", r->name, i, e.message);
        } else {
            m->bytes += px_convex_memory_bytes(m->nodes[i].hull);
            if (m->nodes[i].child[1] != PXI_NONE) m->n_hulls++;
        }
    }
    pxi_free(&alloc, buf, buf_cap * sizeof *buf);
    pxi_free(&alloc, hv, nn * sizeof *hv);
    pxi_free(&alloc, seen, nn + nl);
    for (uint32_t i = 0; i < nn; ++i) m->nodes[i].box = PXI_NONE;
    if (r->st == PX_OK) finish_nodes(m, r);
    if (r->st == PX_OK) compute_boxes(m, r);
    if (r->st == PX_OK) check_solids(m, r);
    if (r->st == PX_OK) {
        /* Depth, and the hull of every inner node holding its children's hulls. */
        for (uint32_t i = 0; i < nn && r->st == PX_OK; ++i) {
            const pxi_mnode *n = &m->nodes[i];
            if (n->child[1] == PXI_NONE || !n->hull) continue;
            for (int k = 0; k < 2 && r->st == PX_OK; ++k) {
                const px_convex *ch = m->nodes[n->child[k]].hull;
                uint32_t c = ch ? px_convex_vertex_count(ch) : 0;
                double t = c ? hull_tol(n->hull) : 0.0;
                for (uint32_t j = 0; j < c; ++j) {
                    px_vec3 q;
                    px_convex_vertex(ch, j, &q);
                    if (!inside(n->hull, q, t)) {
                        BAD(r, "px_model_load: '%s': the hull of node %u does not hold its children", r->name,
                            i);
                        break;
                    }
                }
            }
        }
    }
    if (r->st != PX_OK) {
        px_model_destroy(m);
        return NULL;
    }
    return m;
}

px_model *px_model_load_memory(const void *data, size_t size, const px_model_options *options,
                               px_error *err) {
    reader r = {"(memory)", err, PX_OK};
    if (!data) {
        pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_model_load_memory: data is NULL");
        return NULL;
    }
    px_model *m = load_memory(data, size, options, &r);
    if (m) pxi_error_clear(err);
    return m;
}

px_model *px_model_load(const char *path, const px_model_options *options, px_error *err) {
    if (!path || !*path) {
        pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_model_load: path is NULL or empty");
        return NULL;
    }
    struct stat sb;
    if (stat(path, &sb) != 0) {
        pxi_error(err, PX_ERR_IO, "px_model_load: cannot open '%s': %s", path, strerror(errno));
        return NULL;
    }
    if (!S_ISREG(sb.st_mode)) {
        pxi_error(err, PX_ERR_IO, "px_model_load: '%s' is not a regular file", path);
        return NULL;
    }
    if ((uint64_t)sb.st_size > PX_MODEL_MAX_FILE_BYTES) {
        pxi_error(err, PX_ERR_IO, "px_model_load: '%s' is larger than %llu bytes", path,
                  (unsigned long long)PX_MODEL_MAX_FILE_BYTES);
        return NULL;
    }
    px_allocator alloc;
    if (pxi_allocator_resolve(options ? options->allocator : NULL, &alloc, err) != PX_OK) return NULL;
    size_t size = (size_t)sb.st_size;
    unsigned char *buf = pxi_alloc(&alloc, size ? size : 1);
    if (!buf) {
        pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_model_load: out of memory for '%s'", path);
        return NULL;
    }
    FILE *f = fopen(path, "rb");
    px_model *m = NULL;
    if (!f) {
        pxi_error(err, PX_ERR_IO, "px_model_load: cannot open '%s': %s", path, strerror(errno));
    } else {
        size_t got = fread(buf, 1, size, f);
        int extra = fgetc(f) != EOF;
        fclose(f);
        if (got != size || extra) {
            pxi_error(err, PX_ERR_IO, "px_model_load: '%s' changed while it was read", path);
        } else {
            reader r = {path, err, PX_OK};
            m = load_memory(buf, size, options, &r);
            if (m) pxi_error_clear(err);
        }
    }
    pxi_free(&alloc, buf, size ? size : 1);
    return m;
}
