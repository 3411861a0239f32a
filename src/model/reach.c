/* Certified bounds h of part hulls: how far a convex hull reaches outside
 * the triangles of the part it stands for.
 *
 * h bounds max dist(p, part) over the points p of the hull's boundary. The
 * boundary is triangulated (each hull face fanned) and the triangles are
 * refined best first. A triangle T = (v0, v1, v2) whose corners' nearest
 * points q0, q1, q2 lie on one and the same part triangle is bounded by
 * max d_k exactly: p = sum l_k v_k is within |sum l_k (v_k - q_k)| <=
 * max d_k of the point sum l_k q_k, which lies on that part triangle
 * (convex). Otherwise the distance being 1-Lipschitz, T is bounded by
 * dist(g) + max |v_k - g| at its centroid g. Faces of the hull that are
 * triangles of the part get bound 0 at once; others are split at the
 * midpoint of their longest edge until the largest bound left is within
 * 1 % of the largest distance seen (a lower bound of h) or a budget of
 * evaluations is spent; h is the largest bound left, certified either way.
 *
 * h_overlap bounds the same over the whole hull (inside too, used when two
 * pieces overlap), by cells of space refined the same way: a cell of
 * half-diagonal r whose centre is at distance f bounds f + r.
 *
 * Pieces of a closed part (approximate decomposition) are measured against
 * the part's solid instead: the distance is 0 inside it. That distance is
 * 1-Lipschitz too and at most the distance to the triangles, so the same
 * bounds hold with it (the same-triangle rule with the distances to the
 * triangles); a triangle or cell whose centre is inside and farther from
 * the triangles than its radius lies wholly inside (bound 0). Refinement
 * also stops once a bound is below `floor`, an absolute precision the
 * caller asks for (0 for part hulls).
 *
 * A cell misses the hull when its centre lies beyond one of the hull's
 * supporting planes by more than its radius: the face planes, and one
 * plane at each edge along the mean of its two faces' normals. Without the
 * edge planes a thin wedge (a plate whose rim faces are slivers nearly
 * parallel to it) kept every cell beside its rim: a cell there is within
 * the sliver's plane, only tilted by the plate's thickness, and the budget
 * ran out with the cells of a 1e-9 plate still a sixth of it wide (h 0.31
 * for a 0.02 tolerance).
 *
 * pxi_part_reach_in computes in a scratch buffer the caller gives (the
 * heap of triangles or cells and the hull's supporting planes) and calls no
 * allocator, so that the pieces of a decomposition can be certified on
 * worker threads, each with its own scratch (approx.c); the bounds depend
 * on the hull, the tree and `floor` alone, not on the thread. */
#include <float.h>
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "convex/convex.h"
#include "core/core.h"
#include "model/model.h"

double pxi_model_nearest(const px_model *m, px_vec3 p, double limit, uint32_t *tri) {
    uint32_t stack[128], top = 0;
    double best = limit;
    *tri = PXI_NONE;
    stack[top++] = 0;
    while (top > 0) {
        const pxi_mnode *n = &m->nodes[stack[--top]];
        if (pxi_len(pxi_sub(p, n->center)) - n->radius >= best) continue;
        if (n->child[1] == PXI_NONE) {
            const pxi_mleaf *leaf = &m->leaves[n->child[0]];
            const uint32_t *t = m->tri + 3 * (size_t)leaf->tri;
            px_vec3 tv[3] = {m->v[t[0]], m->v[t[1]], m->v[t[2]]};
            px_feature f;
            double d = pxi_len(pxi_sub(pxi_tri_closest(p, tv, &f), p));
            if (d < best) {
                best = d;
                *tri = leaf->tri;
            }
            continue;
        }
        /* Nearer child on top. */
        const pxi_mnode *c0 = &m->nodes[n->child[0]], *c1 = &m->nodes[n->child[1]];
        double d0 = pxi_len(pxi_sub(p, c0->center)) - c0->radius;
        double d1 = pxi_len(pxi_sub(p, c1->center)) - c1->radius;
        if (top + 2 > sizeof stack / sizeof stack[0]) return best; /* depth is bounded far below */
        if (d0 < d1) {
            stack[top++] = n->child[1];
            stack[top++] = n->child[0];
        } else {
            stack[top++] = n->child[0];
            stack[top++] = n->child[1];
        }
    }
    return best;
}

/* Evaluation budgets: the boundary as a whole, one of its triangles, the
 * volume. */
enum { R_BUDGET = 200000, R_FACE_BUDGET = 20000, R_VOLUME_BUDGET = 40000, R_HEAP = R_VOLUME_BUDGET + 64 };

typedef struct rpoint {
    px_vec3 p;
    double d;  /* distance to the part (its solid, in solid mode) */
    double ds; /* distance to its triangles */
    uint32_t tri;
    int inside; /* solid mode: p lies inside the solid */
} rpoint;

typedef struct rtri {
    rpoint c[3];
    double ub;
} rtri;

typedef struct rcell {
    px_vec3 c, half;
    double ub;
    double ds; /* the centre's distance to the triangles */
    int side;  /* the centre inside the solid (1), outside (0), not tested (-1) */
    int in;    /* the cell lies wholly inside the hull */
} rcell;

/* A max-heap of fixed-size records keyed by their leading... ub field, kept
 * generic through a byte size and an offset. */
typedef struct rheap {
    unsigned char *data;
    size_t size, off;
    uint32_t n, cap;
} rheap;

static double rh_key(const rheap *h, uint32_t i) {
    double k;
    memcpy(&k, h->data + (size_t)i * h->size + h->off, sizeof k);
    return k;
}

static void rh_swap(rheap *h, uint32_t i, uint32_t j) {
    unsigned char tmp[sizeof(rtri) > sizeof(rcell) ? sizeof(rtri) : sizeof(rcell)];
    memcpy(tmp, h->data + (size_t)i * h->size, h->size);
    memcpy(h->data + (size_t)i * h->size, h->data + (size_t)j * h->size, h->size);
    memcpy(h->data + (size_t)j * h->size, tmp, h->size);
}

static int rh_push(rheap *h, const void *rec) {
    if (h->n == h->cap) return 0;
    uint32_t i = h->n++;
    memcpy(h->data + (size_t)i * h->size, rec, h->size);
    while (i > 0 && rh_key(h, (i - 1) / 2) < rh_key(h, i)) {
        rh_swap(h, i, (i - 1) / 2);
        i = (i - 1) / 2;
    }
    return 1;
}

static void rh_pop(rheap *h, void *rec) {
    memcpy(rec, h->data, h->size);
    h->n--;
    if (h->n == 0) return;
    memcpy(h->data, h->data + (size_t)h->n * h->size, h->size);
    uint32_t i = 0;
    for (;;) {
        uint32_t k = 2 * i + 1;
        if (k >= h->n) break;
        if (k + 1 < h->n && rh_key(h, k + 1) > rh_key(h, k)) ++k;
        if (rh_key(h, k) <= rh_key(h, i)) break;
        rh_swap(h, i, k);
        i = k;
    }
}

/* A supporting plane of the hull: n . p - off is the signed distance (body
 * frame); for faces as px_convex_face gives it. */
typedef struct rplane {
    px_vec3 n;
    double off;
} rplane;

typedef struct reach {
    const px_model *tree;
    int solid;    /* distances to the tree's solid (0 inside), not its triangles */
    double floor; /* bounds below this need no refinement */
    double known; /* largest distance seen at a point of the set */
    double bound; /* largest bound of the parts refined so far */
    uint32_t evals;
    const rplane *planes; /* the hull's supporting planes: faces, then edges */
    uint32_t n_planes;
    int (*stop)(void *); /* polled every R_POLL evaluations; nonzero stops */
    void *stop_user;
    int stopped;
    double slack; /* rounding of the distances: a few ulps of the hull's size */
} reach;

/* Evaluations between two calls of the stop hook (a few milliseconds). */
enum { R_POLL = 1024 };

/* Refinement goes on while a bound exceeds this. */
static double enough(const reach *r) { return pxi_max2(r->known * 1.01, r->floor); }

/* Evaluates p. `limit` (INFINITY: none) is a distance to the triangles
 * that p is known to be within: the search for the nearest one starts from
 * it. `side` (-1: unknown) is whether p is inside the solid, when known
 * without a ray cast. */
static rpoint eval_known(reach *r, px_vec3 p, double limit, int side) {
    rpoint out;
    out.p = p;
    out.ds = out.d = pxi_model_nearest(r->tree, p, limit, &out.tri);
    if (out.tri == PXI_NONE && limit < INFINITY)
        out.ds = out.d = pxi_model_nearest(r->tree, p, INFINITY, &out.tri);
    out.inside = 0;
    /* Near the triangles the distance to them is bound enough: the ray
     * cast is spent only where being inside matters. */
    if (r->solid && out.ds > 0.5 * r->floor && (side >= 0 ? side : pxi_model_point_inside(r->tree, p))) {
        out.d = 0.0;
        out.inside = 1;
    }
    r->evals++;
    if (r->stop && r->evals % R_POLL == 0 && r->stop(r->stop_user)) r->stopped = 1;
    return out;
}

static rpoint eval(reach *r, px_vec3 p) { return eval_known(r, p, INFINITY, -1); }

static void tri_bound(reach *r, rtri *t) {
    double same = INFINITY;
    if (t->c[0].tri == t->c[1].tri && t->c[1].tri == t->c[2].tri) {
        same = fmax(t->c[0].ds, fmax(t->c[1].ds, t->c[2].ds));
        if (!r->solid) {
            t->ub = same;
            return;
        }
    }
    px_vec3 g = pxi_scale(pxi_add(pxi_add(t->c[0].p, t->c[1].p), t->c[2].p), 1.0 / 3.0);
    double rad = 0.0;
    for (int k = 0; k < 3; ++k) rad = fmax(rad, pxi_len(pxi_sub(t->c[k].p, g)));
    rpoint pg = eval(r, g);
    r->known = fmax(r->known, pg.d);
    /* Inside, and the ball around g that holds the triangle misses the
     * surface: the whole triangle is inside. */
    t->ub = pg.inside && pg.ds > rad ? 0.0 : fmin(same, pg.d + rad);
}

/* Refines one triangle of the boundary best first, splitting the longest
 * edge at its midpoint (the two halves' diameters shrink even for the
 * slivers a fanned face is made of, where splitting in four keeps their
 * length); returns its bound. */
static double refine_triangle(reach *r, rheap *h, const rtri *t0, uint32_t budget) {
    h->n = 0;
    rh_push(h, t0);
    uint32_t start = r->evals;
    while (h->n > 0) {
        rtri t;
        rh_pop(h, &t);
        if (t.ub <= enough(r) || r->evals - start + 3 > budget || h->n + 2 > h->cap || r->stopped)
            return t.ub;
        int e = 0;
        double longest = -1.0;
        for (int k = 0; k < 3; ++k) {
            double l = pxi_len2(pxi_sub(t.c[(k + 1) % 3].p, t.c[k].p));
            if (l > longest) longest = l, e = k;
        }
        const rpoint a = t.c[e], b = t.c[(e + 1) % 3], c = t.c[(e + 2) % 3];
        rpoint m = eval(r, pxi_scale(pxi_add(a.p, b.p), 0.5));
        r->known = fmax(r->known, m.d);
        rtri kids[2] = {{{a, m, c}, 0}, {{m, b, c}, 0}};
        for (int k = 0; k < 2; ++k) {
            tri_bound(r, &kids[k]);
            rh_push(h, &kids[k]);
        }
    }
    return 0.0;
}

/* The hull's faces fanned into triangles, each refined with a share of the
 * budget proportional to what it needs at a resolution of 1 % of the
 * hull's size: its area, plus its longest edge times that resolution (a
 * sliver needs as many steps as its length, whatever its area). */
static double boundary_reach(reach *r, const px_convex *hull, rheap *h) {
    uint32_t nf = px_convex_face_count(hull);
    double total_area = 0.0;
    px_bounds bd;
    px_convex_bounds(hull, NULL, &bd);
    const double res = 0.01 * bd.radius;
    for (int pass = 0; pass < 2; ++pass) {
        for (uint32_t f = 0; f < nf && !r->stopped; ++f) {
            uint32_t count, v0;
            px_convex_face(hull, f, NULL, NULL, &count);
            px_convex_face_vertex(hull, f, 0, &v0);
            px_vec3 p0;
            px_convex_vertex(hull, v0, &p0);
            rpoint c0 = {p0, 0.0, 0.0, PXI_NONE, 0};
            if (pass == 1) {
                c0 = eval(r, p0);
                r->known = fmax(r->known, c0.d);
            }
            for (uint32_t k = 1; k + 1 < count; ++k) {
                uint32_t v1, v2;
                px_convex_face_vertex(hull, f, k, &v1);
                px_convex_face_vertex(hull, f, k + 1, &v2);
                px_vec3 p1, p2;
                px_convex_vertex(hull, v1, &p1);
                px_convex_vertex(hull, v2, &p2);
                double area = 0.5 * pxi_len(pxi_cross(pxi_sub(p1, p0), pxi_sub(p2, p0)));
                double edge = sqrt(fmax(pxi_len2(pxi_sub(p1, p0)),
                                        fmax(pxi_len2(pxi_sub(p2, p1)), pxi_len2(pxi_sub(p0, p2)))));
                area += edge * res;
                if (pass == 0) {
                    total_area += area;
                    continue;
                }
                rtri t;
                t.c[0] = c0;
                t.c[1] = eval(r, p1);
                t.c[2] = eval(r, p2);
                r->known = fmax(r->known, fmax(t.c[1].d, t.c[2].d));
                tri_bound(r, &t);
                double share = total_area > 0.0 ? area / total_area : 1.0;
                uint32_t budget = (uint32_t)fmin((double)R_FACE_BUDGET, fmax(8.0, share * R_BUDGET));
                r->bound = fmax(r->bound, refine_triangle(r, h, &t, budget));
            }
        }
    }
    return fmax(r->bound, r->known);
}

/* The largest signed distance of p to the hull's supporting planes, or any value
 * above `above` once one exceeds it (the caller only asks whether it
 * does). */
static double plane_max(const reach *r, px_vec3 p, double above) {
    double worst = -INFINITY;
    for (uint32_t f = 0; f < r->n_planes; ++f) {
        double s = pxi_dot(r->planes[f].n, p) - r->planes[f].off;
        if (s > worst) {
            worst = s;
            if (worst > above) break;
        }
    }
    return worst;
}

/* Pushes the cell of centre c and half extents `half`, a child of `parent`
 * (NULL for none). The child lies in the parent, so in the hull when the
 * parent does. The child's centre lies within |half| of the parent's:
 * its distance to the triangles is at most the parent's plus |half|, and
 * when the parent's is larger than |half| (less a rounding slack) the
 * segment between the centres meets no triangle, so the child's centre is
 * on the same side of the solid's surface. */
static int push_cell(reach *r, rheap *h, px_vec3 c, px_vec3 half, const rcell *parent) {
    /* A cell inside the hull holds its children: no plane to test. */
    double rad = pxi_len(half), pm = parent && parent->in ? -INFINITY : plane_max(r, c, rad);
    if (pm > rad) return 1; /* the cell misses the hull */
    double limit = INFINITY;
    int side = -1;
    if (parent) {
        limit = (parent->ds + rad) * (1.0 + 16.0 * DBL_EPSILON) + r->slack;
        if (parent->side >= 0 && parent->ds > rad + r->slack) side = parent->side;
    }
    rpoint e = eval_known(r, c, limit, side);
    if (pm <= 0.0) r->known = pxi_max2(r->known, e.d);
    /* The side is known where it was tested (or inherited): solid mode,
     * and the centre farther from the triangles than half the floor. */
    int known_side = r->solid && e.ds > 0.5 * r->floor ? e.inside : -1;
    rcell cell = {c,    half,       e.inside && e.ds > rad ? 0.0 : e.d + rad,
                  e.ds, known_side, pm < -(rad + r->slack)};
    return rh_push(h, &cell);
}

static double volume_reach(reach *r, const px_convex *hull, rheap *h) {
    uint32_t nv = px_convex_vertex_count(hull);
    px_vec3 lo, hi;
    px_convex_vertex(hull, 0, &lo);
    hi = lo;
    for (uint32_t i = 1; i < nv; ++i) {
        px_vec3 p;
        px_convex_vertex(hull, i, &p);
        lo = pxi_v(fmin(lo.x, p.x), fmin(lo.y, p.y), fmin(lo.z, p.z));
        hi = pxi_v(fmax(hi.x, p.x), fmax(hi.y, p.y), fmax(hi.z, p.z));
    }
    const int k0 = 4;
    px_vec3 half = pxi_scale(pxi_sub(hi, lo), 0.5 / k0);
    for (int i = 0; i < k0; ++i)
        for (int j = 0; j < k0; ++j)
            for (int k = 0; k < k0; ++k) {
                px_vec3 c = pxi_v(lo.x + (2 * i + 1) * half.x, lo.y + (2 * j + 1) * half.y,
                                  lo.z + (2 * k + 1) * half.z);
                if (!push_cell(r, h, c, half, NULL)) return INFINITY;
            }
    while (h->n > 0) {
        rcell cell;
        rh_pop(h, &cell);
        if (cell.ub <= enough(r) || r->evals + 8 > R_VOLUME_BUDGET || h->n + 8 > h->cap || r->stopped)
            return fmax(cell.ub, r->known);
        px_vec3 hh = pxi_scale(cell.half, 0.5);
        for (int s = 0; s < 8; ++s) {
            px_vec3 c = pxi_v(cell.c.x + ((s & 1) ? hh.x : -hh.x), cell.c.y + ((s & 2) ? hh.y : -hh.y),
                              cell.c.z + ((s & 4) ? hh.z : -hh.z));
            push_cell(r, h, c, hh, &cell);
        }
    }
    return r->known;
}

enum { R_REC = sizeof(rtri) > sizeof(rcell) ? sizeof(rtri) : sizeof(rcell) };

uint32_t pxi_part_reach_planes(const px_convex *hull) { return hull->nf + hull->ne; }

size_t pxi_part_reach_scratch_bytes(uint32_t max_planes) {
    return (size_t)R_HEAP * R_REC + (size_t)max_planes * sizeof(rplane);
}

/* The hull's face planes, then a plane at each edge whose faces are not
 * opposite (a polygon's rim): normal the mean of theirs, a direction in
 * the edge's normal cone, through the hull's extreme vertex along it (the
 * support, hill climbing from the edge's tail: exact on a convex polytope,
 * so the plane supports the hull even where rounding tilts the mean out of
 * the cone). Returns the count. */
static uint32_t supporting_planes(const px_convex *hull, rplane *planes) {
    uint32_t k = 0;
    for (uint32_t f = 0; f < hull->nf; ++f, ++k) px_convex_face(hull, f, &planes[k].n, &planes[k].off, NULL);
    for (uint32_t e = 0; e < hull->ne; ++e) {
        const pxi_edge *E = &hull->e[e];
        if (E->left >= hull->nf || E->right >= hull->nf) continue; /* a segment's edge has no faces */
        px_vec3 u = pxi_add(hull->f[E->left].n, hull->f[E->right].n);
        double m = pxi_max_abs(u);
        if (!(m > 0x1p-500)) continue;
        u = pxi_scale(u, 1.0 / m);
        u = pxi_scale(u, 1.0 / pxi_len(u));
        planes[k].n = u;
        planes[k].off = pxi_dot(u, hull->v[pxi_support(hull, u, E->tail)]) + pxi_dot(u, hull->origin);
        ++k;
    }
    return k;
}

px_status pxi_part_reach_in(void *scratch, size_t scratch_bytes, const px_convex *hull, const px_model *tree,
                            int solid, double floor, int (*stop)(void *), void *stop_user, double *h,
                            double *h_overlap, px_error *err) {
    *h = *h_overlap = 0.0;
    if (!scratch || scratch_bytes < pxi_part_reach_scratch_bytes(pxi_part_reach_planes(hull)))
        return pxi_error(err, PX_ERR_INTERNAL, "px_model: reach scratch too small");
    rheap heap = {scratch, sizeof(rtri), offsetof(rtri, ub), 0, R_HEAP};
    rplane *planes = (rplane *)((unsigned char *)scratch + (size_t)R_HEAP * R_REC);
    const uint32_t n_planes = supporting_planes(hull, planes);
    /* Rounding of the nearest points: a few ulps of the hull's size. */
    px_bounds bd;
    px_convex_bounds(hull, NULL, &bd);
    double slack = 16.0 * DBL_EPSILON * (bd.radius + pxi_len(bd.center));
    reach r;
    memset(&r, 0, sizeof r);
    r.tree = tree;
    r.solid = solid && tree->solid_parts > 0;
    r.floor = floor > 0.0 ? floor : 0.0;
    r.planes = planes;
    r.n_planes = n_planes;
    r.stop = stop;
    r.stop_user = stop_user;
    r.slack = slack;
    if (r.solid) {
        /* Against a solid the cells of space bound the boundary too (it
         * lies in the hull), and they stay fat where the fanned faces of a
         * large cut cap are slivers that refinement cannot shrink within
         * its budget; cells inside the solid cost one evaluation. */
        heap.size = sizeof(rcell);
        heap.off = offsetof(rcell, ub);
        *h = *h_overlap = volume_reach(&r, hull, &heap) * (1.0 + 16.0 * DBL_EPSILON) + slack;
    } else {
        *h = boundary_reach(&r, hull, &heap) * (1.0 + 16.0 * DBL_EPSILON) + slack;
        if (px_convex_dimension(hull) < 3) {
            /* A polygon, segment or point is its own boundary. */
            *h_overlap = *h;
        } else if (!r.stopped) {
            heap.n = 0;
            heap.size = sizeof(rcell);
            heap.off = offsetof(rcell, ub);
            r.evals = 0;
            *h_overlap = fmax(*h, volume_reach(&r, hull, &heap) * (1.0 + 16.0 * DBL_EPSILON) + slack);
        }
    }
    if (r.stopped) {
        *h = *h_overlap = 0.0;
        return pxi_error(err, PX_ERR_CANCELLED, "px_model: bound h stopped (cancelled)");
    }
    if (!isfinite(*h) || !isfinite(*h_overlap))
        return pxi_error(err, PX_ERR_INTERNAL, "px_model: %s bound h did not converge",
                         solid ? "piece" : "part");
    return PX_OK;
}

px_status pxi_part_reach(const px_allocator *alloc, const px_convex *hull, const px_model *tree, int solid,
                         double floor, double *h, double *h_overlap, px_error *err) {
    *h = *h_overlap = 0.0;
    size_t bytes = pxi_part_reach_scratch_bytes(pxi_part_reach_planes(hull));
    void *scratch = pxi_alloc(alloc, bytes);
    if (!scratch) return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_model: out of memory");
    px_status st = pxi_part_reach_in(scratch, bytes, hull, tree, solid, floor, NULL, NULL, h, h_overlap, err);
    pxi_free(alloc, scratch, bytes);
    return st;
}
