/* px_mesh: triangle meshes with their part tree (include/proxima/mesh.h).
 *
 * Creation validates the whole description before allocating the object,
 * then copies everything into one block taken from the caller's allocator
 * (the mesh struct, coordinates, parts, nodes, triangles, names), so a mesh
 * is one allocation and one free. Two temporary arrays serve the checks:
 * the part ranges sorted (overlap test) and, per part, the work of the
 * closed-surface test below.
 *
 * Closed parts (BAD_INPUTS items 17 and 18). A part is closed when
 *   1. after joining its vertices at exactly equal positions (sort by
 *      (x, y, z), O(n log n); no tolerance, so nothing distinct is merged),
 *   2. no triangle is degenerate: its three corners are distinct after the
 *      join and not collinear (exact test, below), and
 *   3. every undirected edge is used by exactly two triangles, once in each
 *      direction (the sorted directed edges, O(t log t)).
 * Such a surface is an oriented 2-manifold without boundary, so its signed
 * volume sum(a . (b x c)) / 6 says which way it faces: a negative volume
 * means inside-out, and the part's triangles are reversed (corners 1 and 2
 * swapped) so that normals point out. The volume is taken about the part's
 * first vertex, which keeps its terms the size of the part, not of its
 * distance from the origin. A closed part of zero computed volume (two
 * coincident triangles of opposite winding) is left as it is.
 *
 * Collinearity is decided exactly (pxi_collinear, math/orient.c): the
 * triangle (a, b, c) is degenerate iff the orientations of its projections
 * on the xy, yz and zx planes are all 0, each by Shewchuk's orient2d
 * ("Adaptive precision floating-point arithmetic and fast robust geometric
 * predicates", 1997). Exact when every nonzero coordinate of a triangle is
 * at least 2^-400 of its largest.
 */
#include "proxima/mesh.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/core.h"
#include "math/orient.h"

#define PXI_MESH_MAX_COUNT (1ull << 31)

struct px_mesh {
    px_allocator alloc;
    size_t bytes; /* the whole block */
    uint32_t nv, nt, np, nn;
    double *xyz;
    uint32_t *tri;
    px_mesh_part *parts;
    px_mesh_node *nodes;
    px_mesh_info info;
};

/* ---- the closed-surface test ------------------------------------------ */

typedef struct pos_rec {
    double p[3];
    uint32_t index; /* vertex index within the part */
    uint32_t pad;
} pos_rec;

static int pos_cmp(const void *pa, const void *pb) {
    const pos_rec *a = pa, *b = pb;
    for (int k = 0; k < 3; ++k) {
        if (a->p[k] < b->p[k]) return -1;
        if (a->p[k] > b->p[k]) return 1;
    }
    return a->index < b->index ? -1 : a->index > b->index;
}

static int u64_cmp(const void *pa, const void *pb) {
    uint64_t a = *(const uint64_t *)pa, b = *(const uint64_t *)pb;
    return a < b ? -1 : a > b;
}

/* Work arrays for the largest part: recs and rep sized by vertices, keys by
 * 3 * triangles. */
typedef struct closed_work {
    pos_rec *recs;
    uint32_t *rep;
    uint64_t *keys;
} closed_work;

/* Whether part `p` of `m` is closed (file comment); reverses its triangles
 * when it is closed and inside-out. */
static uint32_t part_closed(px_mesh *m, const px_mesh_part *p, closed_work *w) {
    if (p->triangle_count == 0) return 0;
    const double *xyz = m->xyz + 3 * (size_t)p->first_vertex;
    uint32_t *tri = m->tri + 3 * (size_t)p->first_triangle;
    uint32_t nv = p->vertex_count, nt = p->triangle_count, fv = p->first_vertex;
    for (uint32_t i = 0; i < nv; ++i) {
        memcpy(w->recs[i].p, xyz + 3 * (size_t)i, sizeof w->recs[i].p);
        w->recs[i].index = i;
        w->recs[i].pad = 0;
    }
    qsort(w->recs, nv, sizeof *w->recs, pos_cmp);
    for (uint32_t i = 0; i < nv; ++i) {
        const pos_rec *r = &w->recs[i];
        /* equal by value (-0.0 joins 0.0); equal positions are adjacent */
        const double *q = i > 0 ? w->recs[i - 1].p : NULL;
        int same = q && r->p[0] == q[0] && r->p[1] == q[1] && r->p[2] == q[2];
        w->rep[r->index] = same ? w->rep[w->recs[i - 1].index] : r->index;
    }
    for (uint32_t t = 0; t < nt; ++t) {
        uint32_t v[3];
        for (int k = 0; k < 3; ++k) v[k] = w->rep[tri[3 * (size_t)t + k] - fv];
        if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) return 0;
        if (pxi_collinear(xyz + 3 * (size_t)v[0], xyz + 3 * (size_t)v[1], xyz + 3 * (size_t)v[2])) return 0;
        for (int k = 0; k < 3; ++k) {
            uint64_t a = v[k], b = v[(k + 1) % 3];
            /* ids < 2^31: (lo << 33) | (hi << 1) | forward fits 64 bits */
            w->keys[3 * (size_t)t + k] = a < b ? (a << 33) | (b << 1) | 1u : (b << 33) | (a << 1);
        }
    }
    size_t nk = 3 * (size_t)nt;
    qsort(w->keys, nk, sizeof *w->keys, u64_cmp);
    for (size_t i = 0; i < nk; i += 2) {
        /* each undirected edge: exactly a backward and a forward use */
        if (i + 1 >= nk || (w->keys[i] & 1u) != 0 || w->keys[i + 1] != (w->keys[i] | 1u)) return 0;
        if (i + 2 < nk && (w->keys[i + 2] >> 1) == (w->keys[i] >> 1)) return 0;
    }
    double vol = 0;
    const double *o = xyz;
    /* Scaled by a power of two so that the cubes stay in range. */
    double big = 0.0;
    for (uint32_t t = 0; t < nt; ++t)
        for (int k = 0; k < 3; ++k) {
            const double *v = xyz + 3 * (size_t)(tri[3 * (size_t)t + k] - fv);
            big = fmax(big, fmax(fabs(v[0]), fmax(fabs(v[1]), fabs(v[2]))));
        }
    double sc = pxi_unit_scale(big);
    for (uint32_t t = 0; t < nt; ++t) {
        const double *a = xyz + 3 * (size_t)(tri[3 * (size_t)t] - fv);
        const double *b = xyz + 3 * (size_t)(tri[3 * (size_t)t + 1] - fv);
        const double *c = xyz + 3 * (size_t)(tri[3 * (size_t)t + 2] - fv);
        double ax = a[0] * sc - o[0] * sc, ay = a[1] * sc - o[1] * sc, az = a[2] * sc - o[2] * sc;
        double bx = b[0] * sc - o[0] * sc, by = b[1] * sc - o[1] * sc, bz = b[2] * sc - o[2] * sc;
        double cx = c[0] * sc - o[0] * sc, cy = c[1] * sc - o[1] * sc, cz = c[2] * sc - o[2] * sc;
        vol += ax * (by * cz - bz * cy) + ay * (bz * cx - bx * cz) + az * (bx * cy - by * cx);
    }
    if (vol < 0) {
        for (uint32_t t = 0; t < nt; ++t) {
            uint32_t s = tri[3 * (size_t)t + 1];
            tri[3 * (size_t)t + 1] = tri[3 * (size_t)t + 2];
            tri[3 * (size_t)t + 2] = s;
        }
    }
    return 1;
}

/* ---- validation -------------------------------------------------------- */

typedef struct range_rec {
    uint32_t first, count, part, pad;
} range_rec;

static int range_cmp(const void *pa, const void *pb) {
    const range_rec *a = pa, *b = pb;
    if (a->first != b->first) return a->first < b->first ? -1 : 1;
    return a->part < b->part ? -1 : a->part > b->part;
}

/* Checks that the non-empty ranges of the parts do not overlap; `which` 0:
 * vertices, 1: triangles. `tmp` holds part_count records. */
static px_status check_overlap(const px_mesh_desc *d, range_rec *tmp, int which, px_error *err) {
    uint32_t n = 0;
    for (uint32_t i = 0; i < d->part_count; ++i) {
        const px_mesh_part_desc *p = &d->parts[i];
        uint32_t first = which ? p->first_triangle : p->first_vertex;
        uint32_t count = which ? p->triangle_count : p->vertex_count;
        if (count == 0) continue;
        tmp[n].first = first;
        tmp[n].count = count;
        tmp[n].part = i;
        tmp[n].pad = 0;
        ++n;
    }
    qsort(tmp, n, sizeof *tmp, range_cmp);
    for (uint32_t i = 1; i < n; ++i) {
        if ((uint64_t)tmp[i - 1].first + tmp[i - 1].count > tmp[i].first) {
            uint32_t a = tmp[i - 1].part < tmp[i].part ? tmp[i - 1].part : tmp[i].part;
            uint32_t b = tmp[i - 1].part < tmp[i].part ? tmp[i].part : tmp[i - 1].part;
            return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_mesh_create: parts %u and %u share %s", a, b,
                             which ? "triangles" : "vertices");
        }
    }
    return PX_OK;
}

/* Everything mesh.h lists, except the overlap of parts (needs memory) and
 * check_part_triangles. */
static px_status check_desc(const px_mesh_desc *d, double scale, px_error *err) {
    for (int i = 0; i < 3; ++i)
        if (d->reserved[i])
            return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_mesh_create: desc.reserved[%d] is not zero",
                             i);
    if (d->vertex_count > PXI_MESH_MAX_COUNT || d->triangle_count > PXI_MESH_MAX_COUNT)
        return pxi_error(err, PX_ERR_INVALID_ARGUMENT,
                         "px_mesh_create: %zu vertices and %zu triangles: at most 2^31 of each",
                         d->vertex_count, d->triangle_count);
    if (d->part_count > PXI_MESH_MAX_COUNT || d->node_count > PXI_MESH_MAX_COUNT)
        return pxi_error(err, PX_ERR_INVALID_ARGUMENT,
                         "px_mesh_create: %u parts and %u nodes: at most 2^31 of each", d->part_count,
                         d->node_count);
    if ((d->vertex_count && !d->xyz) || (d->triangle_count && !d->triangles) ||
        (d->part_count && !d->parts) || (d->node_count && !d->nodes))
        return pxi_error(
            err, PX_ERR_INVALID_ARGUMENT,
            "px_mesh_create: an array is NULL while its count is not zero (xyz %zu, triangles %zu, "
            "parts %u, nodes %u)",
            d->vertex_count, d->triangle_count, d->part_count, d->node_count);
    if (d->float_coordinates > 1)
        return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_mesh_create: float_coordinates %u must be 0 or 1",
                         d->float_coordinates);
    if (!isfinite(d->unit_metres) || d->unit_metres < 0)
        return pxi_error(err, PX_ERR_INVALID_ARGUMENT,
                         "px_mesh_create: unit_metres %g must be finite and >= 0 (0: unknown)",
                         d->unit_metres);
    for (size_t i = 0; i < 3 * d->vertex_count; ++i) {
        double x = d->xyz[i];
        if (!isfinite(x))
            return pxi_error(err, PX_ERR_NON_FINITE,
                             "px_mesh_create: vertex %zu has a NaN or infinite coordinate", i / 3);
        if (!isfinite(x * scale))
            return pxi_error(err, PX_ERR_NON_FINITE,
                             "px_mesh_create: vertex %zu overflows to infinity when scaled by %g", i / 3,
                             scale);
    }
    for (size_t i = 0; i < 3 * d->triangle_count; ++i)
        if (d->triangles[i] >= d->vertex_count)
            return pxi_error(err, PX_ERR_INVALID_ARGUMENT,
                             "px_mesh_create: triangle %zu uses vertex %u, but there are %zu vertices", i / 3,
                             d->triangles[i], d->vertex_count);
    for (uint32_t i = 0; i < d->node_count; ++i) {
        const px_mesh_node_desc *n = &d->nodes[i];
        if (n->reserved)
            return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_mesh_create: node %u: reserved is not zero",
                             i);
        if (n->parent < -1 || (n->parent >= 0 && (uint32_t)n->parent >= i))
            return pxi_error(err, PX_ERR_INVALID_ARGUMENT,
                             "px_mesh_create: node %u has parent %d: it must be -1 or an earlier node", i,
                             (int)n->parent);
    }
    for (uint32_t i = 0; i < d->part_count; ++i) {
        const px_mesh_part_desc *p = &d->parts[i];
        if (p->reserved)
            return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_mesh_create: part %u: reserved is not zero",
                             i);
        if (p->node < -1 || (p->node >= 0 && (uint32_t)p->node >= d->node_count))
            return pxi_error(err, PX_ERR_INVALID_ARGUMENT,
                             "px_mesh_create: part %u hangs from node %d, but there are %u nodes", i,
                             (int)p->node, d->node_count);
        if ((uint64_t)p->first_vertex + p->vertex_count > d->vertex_count)
            return pxi_error(err, PX_ERR_INVALID_ARGUMENT,
                             "px_mesh_create: part %u: vertices %u + %u exceed the %zu vertices", i,
                             p->first_vertex, p->vertex_count, d->vertex_count);
        if ((uint64_t)p->first_triangle + p->triangle_count > d->triangle_count)
            return pxi_error(err, PX_ERR_INVALID_ARGUMENT,
                             "px_mesh_create: part %u: triangles %u + %u exceed the %zu triangles", i,
                             p->first_triangle, p->triangle_count, d->triangle_count);
    }
    return PX_OK;
}

/* Each part's triangles use only the part's vertices (after the ranges
 * were found inside the arrays and disjoint). */
static px_status check_part_triangles(const px_mesh_desc *d, px_error *err) {
    for (uint32_t i = 0; i < d->part_count; ++i) {
        const px_mesh_part_desc *p = &d->parts[i];
        const uint32_t *t = d->triangles ? d->triangles + 3 * (size_t)p->first_triangle : NULL;
        for (size_t k = 0; k < 3 * (size_t)p->triangle_count; ++k) {
            if (t[k] < p->first_vertex || t[k] - p->first_vertex >= p->vertex_count)
                return pxi_error(err, PX_ERR_INVALID_ARGUMENT,
                                 "px_mesh_create: part %u: triangle %zu uses vertex %u, outside the part's "
                                 "vertices [%u, %u)",
                                 i, p->first_triangle + k / 3, t[k], p->first_vertex,
                                 p->first_vertex + p->vertex_count);
        }
    }
    return PX_OK;
}

static size_t name_bytes(const char *s) { return (s ? strlen(s) : 0) + 1; }

/* a += b, failing on overflow. */
static int add_size(size_t *a, size_t b) {
    if (b > SIZE_MAX - *a) return 0;
    *a += b;
    return 1;
}

/* a += count * size rounded up to 8 bytes, failing on overflow. */
static int add_array(size_t *a, size_t count, size_t size) {
    if (size && count > SIZE_MAX / size) return 0;
    size_t n = count * size;
    if (n > SIZE_MAX - 7) return 0;
    return add_size(a, (n + 7) & ~(size_t)7);
}

static char *put_name(char **cursor, const char *s) {
    char *out = *cursor;
    size_t n = name_bytes(s);
    if (s) memcpy(out, s, n - 1);
    out[n - 1] = '\0';
    *cursor += n;
    return out;
}

/* ---- public ------------------------------------------------------------ */

px_mesh *px_mesh_create(const px_mesh_desc *desc, const px_mesh_options *options, px_error *err) {
    pxi_error_clear(err);
    if (!desc) {
        pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_mesh_create: desc is NULL");
        return NULL;
    }
    px_mesh_options opt;
    memset(&opt, 0, sizeof opt);
    if (options) opt = *options;
    for (int i = 0; i < 6; ++i) {
        if (opt.reserved[i]) {
            pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_mesh_create: options.reserved[%d] is not zero", i);
            return NULL;
        }
    }
    double scale = opt.scale == 0 ? 1.0 : opt.scale;
    if (!isfinite(scale) || scale <= 0) { /* isfinite first: no comparison with a NaN */
        pxi_error(err, PX_ERR_INVALID_ARGUMENT,
                  "px_mesh_create: options.scale %g must be finite and positive", opt.scale);
        return NULL;
    }
    px_allocator alloc;
    if (pxi_allocator_resolve(opt.allocator, &alloc, err) != PX_OK) return NULL;
    if (check_desc(desc, scale, err) != PX_OK) return NULL;

    uint32_t nv = (uint32_t)desc->vertex_count, nt = (uint32_t)desc->triangle_count;
    uint32_t np = desc->part_count ? desc->part_count : 1, nn = desc->node_count;

    /* the overlap of parts, and the closed test's work, in temporaries */
    if (desc->part_count > 1) {
        range_rec *tmp = pxi_alloc_array(&alloc, desc->part_count, sizeof *tmp);
        if (!tmp) {
            pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_mesh_create: out of memory checking %u parts",
                      desc->part_count);
            return NULL;
        }
        px_status st = check_overlap(desc, tmp, 0, err);
        if (st == PX_OK) st = check_overlap(desc, tmp, 1, err);
        pxi_free(&alloc, tmp, desc->part_count * sizeof *tmp);
        if (st != PX_OK) return NULL;
    }
    if (check_part_triangles(desc, err) != PX_OK) return NULL;

    size_t bytes = 0;
    int ok = add_array(&bytes, 1, sizeof(px_mesh)) && add_array(&bytes, 3 * (size_t)nv, sizeof(double)) &&
             add_array(&bytes, np, sizeof(px_mesh_part)) && add_array(&bytes, nn, sizeof(px_mesh_node)) &&
             add_array(&bytes, 3 * (size_t)nt, sizeof(uint32_t));
    for (uint32_t i = 0; ok && i < desc->part_count; ++i)
        ok = add_size(&bytes, name_bytes(desc->parts[i].name));
    for (uint32_t i = 0; ok && i < nn; ++i) ok = add_size(&bytes, name_bytes(desc->nodes[i].name));
    if (ok && !desc->part_count) ok = add_size(&bytes, 1);
    if (!ok) {
        pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_mesh_create: the mesh's size overflows");
        return NULL;
    }
    unsigned char *block = pxi_alloc(&alloc, bytes);
    if (!block) {
        pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_mesh_create: out of memory (%zu bytes)", bytes);
        return NULL;
    }
    px_mesh *m = (px_mesh *)block;
    memset(m, 0, sizeof *m);
    m->alloc = alloc;
    m->bytes = bytes;
    m->nv = nv;
    m->nt = nt;
    m->np = np;
    m->nn = nn;
    size_t at = 0;
    add_array(&at, 1, sizeof(px_mesh));
    m->xyz = (double *)(block + at);
    add_array(&at, 3 * (size_t)nv, sizeof(double));
    m->parts = (px_mesh_part *)(block + at);
    add_array(&at, np, sizeof(px_mesh_part));
    m->nodes = (px_mesh_node *)(block + at);
    add_array(&at, nn, sizeof(px_mesh_node));
    m->tri = (uint32_t *)(block + at);
    add_array(&at, 3 * (size_t)nt, sizeof(uint32_t));
    char *names = (char *)(block + at);

    for (size_t i = 0; i < 3 * (size_t)nv; ++i) m->xyz[i] = desc->xyz[i] * scale;
    if (nt) memcpy(m->tri, desc->triangles, 3 * (size_t)nt * sizeof(uint32_t));
    for (uint32_t i = 0; i < nn; ++i) {
        m->nodes[i].name = put_name(&names, desc->nodes[i].name);
        m->nodes[i].parent = desc->nodes[i].parent;
    }
    if (desc->part_count) {
        for (uint32_t i = 0; i < np; ++i) {
            const px_mesh_part_desc *p = &desc->parts[i];
            px_mesh_part *q = &m->parts[i];
            q->name = put_name(&names, p->name);
            q->node = p->node;
            q->first_vertex = p->first_vertex;
            q->vertex_count = p->vertex_count;
            q->first_triangle = p->first_triangle;
            q->triangle_count = p->triangle_count;
            q->closed = 0;
        }
    } else {
        px_mesh_part *q = &m->parts[0];
        q->name = put_name(&names, NULL);
        q->node = -1;
        q->first_vertex = 0;
        q->vertex_count = nv;
        q->first_triangle = 0;
        q->triangle_count = nt;
        q->closed = 0;
    }

    /* closed parts: work arrays sized for the largest part with triangles */
    uint32_t max_v = 0, max_t = 0;
    for (uint32_t i = 0; i < np; ++i) {
        if (!m->parts[i].triangle_count) continue;
        if (m->parts[i].vertex_count > max_v) max_v = m->parts[i].vertex_count;
        if (m->parts[i].triangle_count > max_t) max_t = m->parts[i].triangle_count;
    }
    if (max_t) {
        closed_work w;
        w.recs = pxi_alloc_array(&alloc, max_v, sizeof *w.recs);
        w.rep = w.recs ? pxi_alloc_array(&alloc, max_v, sizeof *w.rep) : NULL;
        w.keys = w.rep ? pxi_alloc_array(&alloc, 3 * (size_t)max_t, sizeof *w.keys) : NULL;
        if (!w.keys) {
            pxi_free(&alloc, w.rep, max_v * sizeof *w.rep);
            pxi_free(&alloc, w.recs, max_v * sizeof *w.recs);
            pxi_free(&alloc, block, bytes);
            pxi_error(err, PX_ERR_OUT_OF_MEMORY,
                      "px_mesh_create: out of memory checking which parts are closed (%u vertices, %u "
                      "triangles)",
                      max_v, max_t);
            return NULL;
        }
        for (uint32_t i = 0; i < np; ++i) m->parts[i].closed = part_closed(m, &m->parts[i], &w);
        pxi_free(&alloc, w.keys, 3 * (size_t)max_t * sizeof *w.keys);
        pxi_free(&alloc, w.rep, max_v * sizeof *w.rep);
        pxi_free(&alloc, w.recs, max_v * sizeof *w.recs);
    }

    px_mesh_info *info = &m->info;
    for (uint32_t i = 0; i < np; ++i) info->closed_parts += m->parts[i].closed;
    info->unit_metres = desc->unit_metres;
    info->float_coordinates = desc->float_coordinates;
    info->scale = scale;
    if (nv) {
        double lo[3] = {m->xyz[0], m->xyz[1], m->xyz[2]}, hi[3] = {lo[0], lo[1], lo[2]};
        for (size_t i = 1; i < nv; ++i) {
            for (int k = 0; k < 3; ++k) {
                double x = m->xyz[3 * i + k];
                if (x < lo[k]) lo[k] = x;
                if (x > hi[k]) hi[k] = x;
            }
        }
        info->min = (px_vec3){lo[0], lo[1], lo[2]};
        info->max = (px_vec3){hi[0], hi[1], hi[2]};
    }
    return m;
}

void px_mesh_destroy(px_mesh *mesh) {
    if (!mesh) return;
    px_allocator a = mesh->alloc;
    pxi_free(&a, mesh, mesh->bytes);
}

uint32_t px_mesh_vertex_count(const px_mesh *mesh) { return mesh ? mesh->nv : 0; }
uint32_t px_mesh_triangle_count(const px_mesh *mesh) { return mesh ? mesh->nt : 0; }
uint32_t px_mesh_part_count(const px_mesh *mesh) { return mesh ? mesh->np : 0; }
uint32_t px_mesh_node_count(const px_mesh *mesh) { return mesh ? mesh->nn : 0; }

const double *px_mesh_vertices(const px_mesh *mesh) { return mesh && mesh->nv ? mesh->xyz : NULL; }
const uint32_t *px_mesh_triangles(const px_mesh *mesh) { return mesh && mesh->nt ? mesh->tri : NULL; }

px_status px_mesh_get_part(const px_mesh *mesh, uint32_t i, px_mesh_part *out) {
    if (out) memset(out, 0, sizeof *out);
    if (!mesh || !out || i >= mesh->np) return PX_ERR_INVALID_ARGUMENT;
    *out = mesh->parts[i];
    return PX_OK;
}

px_status px_mesh_get_node(const px_mesh *mesh, uint32_t i, px_mesh_node *out) {
    if (out) memset(out, 0, sizeof *out);
    if (!mesh || !out || i >= mesh->nn) return PX_ERR_INVALID_ARGUMENT;
    *out = mesh->nodes[i];
    return PX_OK;
}

px_status px_mesh_get_info(const px_mesh *mesh, px_mesh_info *out) {
    if (out) memset(out, 0, sizeof *out);
    if (!mesh || !out) return PX_ERR_INVALID_ARGUMENT;
    *out = mesh->info;
    return PX_OK;
}

size_t px_mesh_memory_bytes(const px_mesh *mesh) { return mesh ? mesh->bytes : 0; }
