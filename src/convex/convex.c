/* Building px_convex from a point set: CGAL computes the hull (exact
 * predicates, exactly coplanar triangles merged into polygons; see
 * convexdecomp/pxcd.h), this file turns the polygons into the edge/face
 * structure with the Voronoi-region vectors of convex.h, and validates it.
 */
#include "convex/convex.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/core.h"
#include "math/orient.h"
#include "math/vec3.h"
#include "pxcd.h"

#define PXI_MAX_POINTS (1u << 26)
/* Accepted hull sizes (largest |stored coordinate|, about the body's
 * half-extent): every computation then runs at full relative precision
 * (bit-identical under power-of-two scaling of the input). Below, eps times
 * the size is subnormal and answers lose relative precision; above, sums of
 * a pair's sizes and distance approach overflow. Where the body sits does
 * not matter (it is stored relative to its own middle). */
#define PXI_MIN_SIZE 0x1p-1000
#define PXI_MAX_SIZE 0x1p1000

/* One directed boundary edge of a face, for pairing into undirected edges. */
typedef struct half {
    uint32_t lo, hi;  /* sorted vertex ids: the undirected key */
    uint32_t face;    /* face that traverses it */
    uint32_t slot;    /* position in f_verts / f_edges */
    uint32_t forward; /* 1 if the face traverses lo -> hi */
} half;

static int half_cmp(const void *pa, const void *pb) {
    const half *a = pa, *b = pb;
    if (a->lo != b->lo) return a->lo < b->lo ? -1 : 1;
    if (a->hi != b->hi) return a->hi < b->hi ? -1 : 1;
    return (int)a->forward - (int)b->forward;
}

static void *take(px_convex *c, size_t count, size_t size, int *ok) {
    void *p = pxi_alloc_array(&c->alloc, count, size);
    if (!p)
        *ok = 0;
    else
        c->bytes += count * size;
    return p;
}

void px_convex_destroy(px_convex *c) {
    if (!c) return;
    px_allocator a = c->alloc; /* c itself is freed last, with a copy */
    size_t h = 2 * (size_t)c->ne;
    pxi_free(&a, c->v, c->nv * sizeof *c->v);
    pxi_free(&a, c->v_first, (c->nv + 1) * sizeof *c->v_first);
    pxi_free(&a, c->v_edges, h * sizeof *c->v_edges);
    pxi_free(&a, c->v_adj, h * sizeof *c->v_adj);
    pxi_free(&a, c->e, c->ne * sizeof *c->e);
    pxi_free(&a, c->f, c->nf * sizeof *c->f);
    pxi_free(&a, c->f_verts, h * sizeof *c->f_verts);
    pxi_free(&a, c->f_edges, h * sizeof *c->f_edges);
    pxi_lut_destroy(c);
    pxi_free(&a, c, sizeof *c);
}

/* The area vector of a planar polygon (exact coplanarity came from CGAL):
 * the sum of its fan triangles' cross products from the first vertex, each
 * component an orient2d of the projected corners evaluated to full
 * relative precision (pxi_orient2d_value). Plain double products (Newell's
 * sum) lose a factor of the triangle's aspect: a sliver 1e-3 wide and 1
 * long got a normal tilted by ~1e-13 and Lin-Canny distances 200 eps off
 * beside it. The fan's terms have one sign for a convex polygon, so the
 * sum keeps that precision. Coordinates are first brought near unit scale
 * by a power of two (exact). */
static px_vec3 polygon_normal(const px_vec3 *v, const uint32_t *ids, uint32_t n) {
    double big = 0.0;
    for (uint32_t k = 0; k < n; ++k) big = pxi_max2(big, pxi_max_abs(v[ids[k]]));
    const double sc = pxi_unit_scale(big);
    const px_vec3 o = pxi_scale(v[ids[0]], sc);
    px_vec3 s = {0, 0, 0}, a = pxi_scale(v[ids[1]], sc);
    for (uint32_t k = 2; k < n; ++k) {
        px_vec3 b = pxi_scale(v[ids[k]], sc);
        s = pxi_add(s, pxi_tri_cross(o, a, b));
        a = b;
    }
    return s;
}

static px_vec3 unit(px_vec3 a) {
    /* Scale first so that tiny (1e-23) and huge (1e39) bodies normalise
     * without underflow or overflow of the squared length. */
    double m = pxi_max_abs(a);
    if (!(m > 0.0)) return a;
    /* 1 / m overflows for subnormal m: scale by a power of two there. */
    a = isfinite(1.0 / m) ? pxi_scale(a, 1.0 / m) : pxi_ldexp3(a, -ilogb(m));
    return pxi_scale(a, 1.0 / pxi_len(a));
}

/* Whether the plane of unit normal n through the polygon's mean holds
 * every vertex of the polygon within validate_local's tolerance. */
static int polygon_plane_ok(const px_vec3 *v, const uint32_t *ids, uint32_t n, px_vec3 nrm) {
    if (!(fabs(pxi_len(nrm) - 1.0) <= 1e-12)) return 0;
    double d = 0.0, big = 0.0;
    for (uint32_t k = 0; k < n; ++k) d += pxi_dot(nrm, v[ids[k]]), big = fmax(big, pxi_max_abs(v[ids[k]]));
    d /= n;
    for (uint32_t k = 0; k < n; ++k)
        if (!(fabs(pxi_dot(nrm, v[ids[k]]) - d) <= 1e-10 * big)) return 0;
    return 1;
}

static void inner_ball(px_convex *c);

static px_status build_from_hull(px_convex *c, const pxcd_hull *h, int dim, px_error *err) {
    int ok = 1;
    size_t nhalf = h->face_offsets[h->face_count];
    /* What pxcd.h promises for each dimension: a closed polytope, a
     * two-sided polygon, a segment's two end points, one point. */
    int shape_ok = dim == 3   ? h->vertex_count >= 4 && h->face_count >= 4
                   : dim == 2 ? h->vertex_count >= 3 && h->face_count == 2 && nhalf == 2 * h->vertex_count
                   : dim == 1 ? h->vertex_count == 2 && h->face_count == 0
                              : dim == 0 && h->vertex_count == 1 && h->face_count == 0;
    if (!shape_ok || nhalf % 2 != 0 || nhalf / 2 > UINT32_MAX / 2)
        return pxi_error(err, PX_ERR_INTERNAL,
                         "hull from CGAL is not a closed polytope of dimension %d (V=%zu, F=%zu)", dim,
                         h->vertex_count, h->face_count);
    c->dim = (uint32_t)dim;
    c->nv = (uint32_t)h->vertex_count;
    c->nf = (uint32_t)h->face_count;
    c->ne = dim >= 2 ? (uint32_t)(nhalf / 2) : (uint32_t)dim; /* a segment: 1 edge, a point: none */
    size_t nh2 = 2 * (size_t)c->ne;                           /* == nhalf for dim >= 2 */
    c->v = take(c, c->nv, sizeof *c->v, &ok);
    c->f = take(c, c->nf, sizeof *c->f, &ok);
    c->e = take(c, c->ne, sizeof *c->e, &ok);
    c->f_verts = take(c, nh2, sizeof *c->f_verts, &ok);
    c->f_edges = take(c, nh2, sizeof *c->f_edges, &ok);
    c->v_first = take(c, (size_t)c->nv + 1, sizeof *c->v_first, &ok);
    c->v_edges = take(c, nh2, sizeof *c->v_edges, &ok);
    c->v_adj = take(c, nh2, sizeof *c->v_adj, &ok);
    half *hs = pxi_alloc_array(&c->alloc, nhalf, sizeof *hs);
    if (!ok || !hs) {
        pxi_free(&c->alloc, hs, nhalf * sizeof *hs);
        return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "out of memory building a polytope of %u vertices",
                         c->nv);
    }
    for (uint32_t i = 0; i < c->nv; ++i)
        c->v[i] = pxi_v(h->vertices[3 * i], h->vertices[3 * i + 1], h->vertices[3 * i + 2]);
    /* The stored origin (convex.h): per coordinate, the middle of the body's
     * range when the range lies on one side of 0 at least its own width
     * away (then lo/2 <= v, mid <= 2 lo for every v, so v - mid is exact,
     * Sterbenz); else 0, and the coordinate is stored as given (ordinary
     * bodies, near their frame's origin, keep their bits). Every tolerance is
     * then relative to the body's size, not to where its coordinates sit:
     * unit boxes at 1e14 get a contact band of 1e-14, not 1e-2. */
    double blo[3] = {INFINITY, INFINITY, INFINITY}, bhi[3] = {-INFINITY, -INFINITY, -INFINITY}, org[3];
    for (uint32_t i = 0; i < c->nv; ++i) {
        double p[3] = {c->v[i].x, c->v[i].y, c->v[i].z};
        for (int k = 0; k < 3; ++k) {
            if (p[k] < blo[k]) blo[k] = p[k];
            if (p[k] > bhi[k]) bhi[k] = p[k];
        }
    }
    for (int k = 0; k < 3; ++k) {
        double w = bhi[k] - blo[k];
        org[k] = (blo[k] >= w && blo[k] > 0.0) || (bhi[k] <= -w && bhi[k] < 0.0) ? blo[k] + 0.5 * w : 0.0;
    }
    c->origin = pxi_v(org[0], org[1], org[2]);
    for (uint32_t i = 0; i < c->nv; ++i) c->v[i] = pxi_sub(c->v[i], c->origin);
    if (nhalf) memcpy(c->f_verts, h->face_indices, nhalf * sizeof(uint32_t));
    if (dim == 1) c->f_verts[0] = 0, c->f_verts[1] = 1, c->f_edges[0] = c->f_edges[1] = 0; /* unused */

    /* Outward orientation is the contract of pxcd.h, but it costs O(F) to
     * make sure: the signed volume of the fans from an interior point must
     * be positive; if it is negative every loop is reversed. (A polygon has
     * both orientations, and no volume.) */
    px_vec3 mid = {0, 0, 0};
    double big = 0.0;
    for (uint32_t i = 0; i < c->nv; ++i) {
        double m = pxi_max_abs(c->v[i]);
        if (m > big) big = m;
    }
    /* Coordinates brought to unit size by a power of two (1 / big would
     * overflow for a subnormal big): triple products of raw coordinates
     * would overflow at 1e139 and underflow at 1e-23. */
    double inv = pxi_pow2_unit(big);
    for (uint32_t i = 0; i < c->nv; ++i) mid = pxi_add(mid, pxi_scale(c->v[i], inv / c->nv));
    /* Three times the volume as the sum over faces of the area vector
     * (accurate cross products, pxi_tri_cross) dotted with a vertex's offset
     * from the interior point: terms of one sign, so a needle 1e-10 wide
     * keeps its sign (the fans' triple products in plain double were noise
     * there, and every loop of half the needles came out reversed). */
    double vol = 0.0;
    for (uint32_t f = 0; f < c->nf; ++f) {
        const uint32_t *ids = c->f_verts + h->face_offsets[f];
        uint32_t n = (uint32_t)(h->face_offsets[f + 1] - h->face_offsets[f]);
        px_vec3 o = pxi_scale(c->v[ids[0]], inv), area = {0, 0, 0};
        for (uint32_t k = 1; k + 1 < n; ++k)
            area = pxi_add(area,
                           pxi_tri_cross(o, pxi_scale(c->v[ids[k]], inv), pxi_scale(c->v[ids[k + 1]], inv)));
        vol += pxi_dot(area, pxi_sub(o, mid));
    }
    if (vol < 0.0 && dim == 3) {
        for (uint32_t f = 0; f < c->nf; ++f) {
            uint32_t *ids = c->f_verts + h->face_offsets[f];
            uint32_t n = (uint32_t)(h->face_offsets[f + 1] - h->face_offsets[f]);
            for (uint32_t k = 0; k < n / 2; ++k) {
                uint32_t t = ids[k];
                ids[k] = ids[n - 1 - k];
                ids[n - 1 - k] = t;
            }
        }
    }

    /* Faces: boundary loops and planes. */
    for (uint32_t f = 0; f < c->nf; ++f) {
        uint32_t first = (uint32_t)h->face_offsets[f], n = (uint32_t)(h->face_offsets[f + 1] - first);
        pxi_face *F = &c->f[f];
        F->first = first;
        F->count = n;
        if (dim == 2 && f == 1) {
            /* The polygon's back: exactly the front's plane turned over. */
            F->n = pxi_neg(c->f[0].n);
            F->d = -c->f[0].d;
        } else {
            px_vec3 N = polygon_normal(c->v, c->f_verts + first, n);
            if (dim == 2 && !polygon_plane_ok(c->v, c->f_verts + first, n, unit(N))) {
                /* A sliver whose area is rounding (three points one ulp off
                 * a line): Newell's normal is noise, and its plane misses
                 * the vertices. The sliver lies within rounding of its
                 * longest edge, so a plane through that edge holds it (it
                 * turns by less than PXI_WALK_MIN_TURN: the queries serve
                 * it from supports alone, convex.h). */
                px_vec3 L = pxi_v(0, 0, 0);
                for (uint32_t k = 0; k < n; ++k) {
                    px_vec3 e = pxi_sub(c->v[c->f_verts[first + (k + 1) % n]], c->v[c->f_verts[first + k]]);
                    if (pxi_max_abs(e) > pxi_max_abs(L)) L = e;
                }
                L = unit(L);
                px_vec3 axis = fabs(L.x) <= fabs(L.y) && fabs(L.x) <= fabs(L.z) ? pxi_v(1, 0, 0)
                               : fabs(L.y) <= fabs(L.z)                         ? pxi_v(0, 1, 0)
                                                                                : pxi_v(0, 0, 1);
                N = pxi_cross(L, axis);
            }
            F->n = unit(N);
            double d = 0.0;
            for (uint32_t k = 0; k < n; ++k) d += pxi_dot(F->n, c->v[c->f_verts[first + k]]);
            F->d = d / n;
        }
        for (uint32_t k = 0; k < n; ++k) {
            uint32_t a = c->f_verts[first + k], b = c->f_verts[first + (k + 1) % n];
            half *x = &hs[first + k];
            x->lo = a < b ? a : b;
            x->hi = a < b ? b : a;
            x->face = f;
            x->slot = first + k;
            x->forward = a < b;
        }
    }
    /* Pair the two directed copies of every edge. Sorting makes the edge
     * numbering deterministic. */
    qsort(hs, nhalf, sizeof *hs, half_cmp);
    px_status st = PX_OK;
    for (size_t k = 0; k < nhalf; k += 2) {
        const half *bwd = &hs[k], *fwd = &hs[k + 1]; /* forward sorts last */
        if (bwd->lo != fwd->lo || bwd->hi != fwd->hi || bwd->forward || !fwd->forward) {
            st = pxi_error(err, PX_ERR_INTERNAL, "hull edge (%u,%u) is not shared by exactly two faces",
                           bwd->lo, bwd->hi);
            break;
        }
        uint32_t id = (uint32_t)(k / 2);
        pxi_edge *E = &c->e[id];
        E->tail = fwd->lo;
        E->head = fwd->hi;
        E->left = fwd->face; /* traverses tail -> head counter-clockwise */
        E->right = bwd->face;
        c->f_edges[fwd->slot] = id;
        c->f_edges[bwd->slot] = id;
        E->u = unit(pxi_sub(c->v[E->head], c->v[E->tail]));
        E->wl = unit(pxi_cross(c->f[E->left].n, E->u));
        E->wr = unit(pxi_cross(E->u, c->f[E->right].n));
    }
    pxi_free(&c->alloc, hs, nhalf * sizeof *hs);
    if (st != PX_OK) return st;
    if (dim == 1) {
        /* The segment's one edge: no face on either side, zero side planes. */
        pxi_edge *E = &c->e[0];
        E->tail = 0;
        E->head = 1;
        E->left = E->right = PXI_NO_FACE;
        E->u = unit(pxi_sub(c->v[1], c->v[0]));
        E->wl = E->wr = pxi_v(0, 0, 0);
    }

    /* Can Lin-Canny walk it? A polygon must turn clearly left about its
     * normal at every vertex (convex.h, PXI_WALK_MIN_TURN). */
    c->walk_ok = 1;
    if (dim == 2) {
        const pxi_face *F = &c->f[0];
        for (uint32_t k = 0; k < F->count; ++k) {
            const pxi_edge *E1 = &c->e[c->f_edges[F->first + k]];
            const pxi_edge *E2 = &c->e[c->f_edges[F->first + (k + 1) % F->count]];
            uint32_t b = c->f_verts[F->first + (k + 1) % F->count];
            px_vec3 u1 = E1->head == b ? E1->u : pxi_neg(E1->u), u2 = E2->tail == b ? E2->u : pxi_neg(E2->u);
            if (!(pxi_dot(pxi_cross(u1, u2), F->n) > PXI_WALK_MIN_TURN)) c->walk_ok = 0;
        }
    }

    /* Vertex -> incident edges (CSR). */
    memset(c->v_first, 0, ((size_t)c->nv + 1) * sizeof *c->v_first);
    for (uint32_t i = 0; i < c->ne; ++i) {
        c->v_first[c->e[i].tail + 1]++;
        c->v_first[c->e[i].head + 1]++;
    }
    for (uint32_t i = 0; i < c->nv; ++i) c->v_first[i + 1] += c->v_first[i];
    uint32_t *fill = pxi_alloc_array(&c->alloc, c->nv, sizeof *fill);
    if (!fill) return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "out of memory building vertex adjacency");
    memcpy(fill, c->v_first, c->nv * sizeof *fill);
    for (uint32_t i = 0; i < c->ne; ++i) {
        uint32_t t = c->e[i].tail, hd = c->e[i].head;
        c->v_edges[fill[t]] = i;
        c->v_adj[fill[t]++] = hd;
        c->v_edges[fill[hd]] = i;
        c->v_adj[fill[hd]++] = t;
    }
    pxi_free(&c->alloc, fill, c->nv * sizeof *fill);

    /* Centre (the mean of the vertices), radius about it, coordinate scale. */
    px_vec3 s = {0, 0, 0};
    double scale = 0.0;
    for (uint32_t i = 0; i < c->nv; ++i) {
        double m = pxi_max_abs(c->v[i]);
        if (m > scale) scale = m;
    }
    /* The mean of v / n: below about n DBL_MIN (bodies of 1e-306) the terms
     * are subnormal and lose bits, so there it is taken at unit scale. */
    int ce = pxi_len_ok(scale) || !(scale > 0.0) ? 0 : -ilogb(scale);
    for (uint32_t i = 0; i < c->nv; ++i) s = pxi_add(s, pxi_scale(pxi_ldexp3(c->v[i], ce), 1.0 / c->nv));
    s = pxi_ldexp3(s, -ce);
    c->center = s;
    double r2 = 0.0;
    for (uint32_t i = 0; i < c->nv; ++i) {
        double q = pxi_len_safe(pxi_sub(c->v[i], s));
        if (q > r2) r2 = q;
    }
    c->radius = r2;
    c->scale = scale;
    c->reach = r2 + 4.0 * pxi_max_abs(s);
    /* Widths along the 3 axes, 6 face diagonals and 4 body diagonals of a
     * cube: their ratio tells round bodies (where the line of centres is a
     * good cold-start guess) from thin ones (lin_canny.c). */
    static const double dirs[13][3] = {{1, 0, 0},  {0, 1, 0},  {0, 0, 1}, {1, 1, 0},  {1, -1, 0},
                                       {1, 0, 1},  {1, 0, -1}, {0, 1, 1}, {0, 1, -1}, {1, 1, 1},
                                       {1, 1, -1}, {1, -1, 1}, {-1, 1, 1}};
    double wmin = INFINITY, wmax = 0.0;
    for (int k = 0; k < 13; ++k) {
        px_vec3 d = unit(pxi_v(dirs[k][0], dirs[k][1], dirs[k][2]));
        double lo = INFINITY, hi = -INFINITY;
        for (uint32_t i = 0; i < c->nv; ++i) {
            double t = pxi_dot(d, pxi_sub(c->v[i], s));
            if (t < lo) lo = t;
            if (t > hi) hi = t;
        }
        if (hi - lo < wmin) wmin = hi - lo;
        if (hi - lo > wmax) wmax = hi - lo;
    }
    c->roundness = wmax > 0.0 ? wmin / wmax : 1.0;
    inner_ball(c);
    return PX_OK;
}

static px_status validate_local(const px_convex *c, px_error *err);

/* Depth of stored-frame point w in a solid: its least height below a face
 * plane (negative outside), and that face. */
static double depth_at(const px_convex *c, px_vec3 w, uint32_t *nearest) {
    double m = INFINITY;
    for (uint32_t f = 0; f < c->nf; ++f) {
        double h = c->f[f].d - pxi_dot(c->f[f].n, w);
        if (h < m) {
            m = h;
            *nearest = f;
        }
    }
    return m;
}

/* A lower bound on the depth of interior point w in the hull of the
 * vertices. A stored face plane is off the true facet's (through the
 * face's exactly coplanar vertices) by its rounding (before polygon_normal
 * was accurate, a sliver's tilted by up to 1e-11 rad). The nearest facet F of w
 * holds the foot p of w on its plane (were p outside F, the segment from w
 * to p would leave the hull through a nearer facet), and the difference
 * between the stored and the true plane function, affine, is at most its
 * largest value at F's vertices there (their residuals |n.v_k - d|, with
 * their rounding) and only grows from p to w (by s (1 - cos tilt), s the
 * depth). So the least over faces of the stored depth less the face's
 * largest residual is at most the true depth; a normal a few ulps off
 * unit length is left to the caller's margin. */
static double certified_depth(const px_convex *c, px_vec3 w) {
    double best = INFINITY;
    for (uint32_t f = 0; f < c->nf; ++f) {
        const pxi_face *F = &c->f[f];
        double e = 0.0, big = 0.0;
        for (uint32_t k = 0; k < F->count; ++k) {
            px_vec3 v = c->v[c->f_verts[F->first + k]];
            e = pxi_max2(e, fabs(pxi_dot(F->n, v) - F->d));
            big = pxi_max2(big, pxi_max_abs(v));
        }
        best = pxi_min2(best, F->d - pxi_dot(F->n, w) - (e + 16.0 * DBL_EPSILON * big));
    }
    return best;
}

/* A large ball inside a solid, not the largest (that is a linear program,
 * the Chebyshev centre): from the vertices' mean, a few moves straight away
 * from the nearest face plane, each as far as the depth grows (the depth
 * along a line is concave, piecewise linear: bisection on the sign of its
 * slope). Its radius is then the certified depth of the centre (above),
 * lowered by the rounding of the unit normals and of the products (a few
 * ulps of the coordinates, and of the radius for the normals' length). At
 * most 4 x 24 + 2 passes over the faces. */
static void inner_ball(px_convex *c) {
    c->inner_center = c->center;
    c->inner_radius = 0.0;
    if (c->dim != 3 || !(c->scale > 0.0) || !pxi_len_ok(c->scale)) return;
    uint32_t f0 = 0;
    px_vec3 w = c->center;
    double rho = depth_at(c, w, &f0);
    for (int it = 0; it < 4 && rho > 0.0; ++it) {
        px_vec3 u = pxi_neg(c->f[f0].n);
        double lo = 0.0, hi = 2.0 * c->radius;
        for (int k = 0; k < 24; ++k) {
            double t = 0.5 * (lo + hi);
            uint32_t g = 0;
            depth_at(c, pxi_madd(w, u, t), &g);
            if (pxi_dot(c->f[g].n, u) < 0.0) /* the nearest plane recedes: deeper on */
                lo = t;
            else
                hi = t;
        }
        uint32_t g = 0;
        px_vec3 w2 = pxi_madd(w, u, lo);
        double r2 = depth_at(c, w2, &g);
        if (!(r2 > rho * (1.0 + 1e-3))) break;
        w = w2, rho = r2, f0 = g;
    }
    rho = certified_depth(c, w) - 256.0 * DBL_EPSILON * (c->scale + pxi_max_abs(w) + c->radius);
    if (!(rho > 1e-6 * c->radius)) return;
    c->inner_center = w;
    c->inner_radius = rho;
}

static uint32_t default_lut_resolution(uint32_t nv) {
    /* About four cells per vertex, between 2 and 256 cells per cube side:
     * at most 6*256*256*4 = 1.5 MiB, 8 bytes per vertex at 200k. A
     * support query then climbs one or two steps from its cell's vertex. Tiny
     * hulls climb from a fixed vertex instead (support.c). */
    if (nv < 24) return 0;
    uint32_t r = (uint32_t)sqrt(nv / 1.5);
    if (r < 2) r = 2;
    if (r > 256) r = 256;
    return r;
}

/* Checks the options; fills the allocator. */
static px_status check_options(const px_convex_options *o, px_allocator *alloc, px_error *err) {
    if (!o) return pxi_allocator_resolve(NULL, alloc, err);
    for (size_t i = 0; i < sizeof o->reserved / sizeof o->reserved[0]; ++i)
        if (o->reserved[i] != 0)
            return pxi_error(err, PX_ERR_INVALID_ARGUMENT,
                             "px_convex_create: options.reserved[%zu] is %u, must be zero", i,
                             o->reserved[i]);
    if (o->lut_resolution > 256)
        return pxi_error(err, PX_ERR_INVALID_ARGUMENT,
                         "px_convex_create: options.lut_resolution %u is above 256", o->lut_resolution);
    return pxi_allocator_resolve(o->allocator, alloc, err);
}

/* Points welded on a grid of cell w: points in one cell are kept once (the
 * first). Returns the count kept in out (3 doubles each, allocated). */
typedef struct weld_key {
    int64_t k[3];
    size_t i;
} weld_key;

static int weld_cmp(const void *pa, const void *pb) {
    const weld_key *a = pa, *b = pb;
    for (int j = 0; j < 3; ++j)
        if (a->k[j] != b->k[j]) return a->k[j] < b->k[j] ? -1 : 1;
    return a->i < b->i ? -1 : a->i > b->i;
}

static size_t weld_points(const px_allocator *alloc, const double *xyz, size_t count, double w,
                          double **out) {
    *out = NULL;
    weld_key *keys = pxi_alloc_array(alloc, count, sizeof *keys);
    double *kept = pxi_alloc_array(alloc, count, 3 * sizeof *kept);
    if (!keys || !kept) {
        pxi_free(alloc, keys, count * sizeof *keys);
        pxi_free(alloc, kept, count * 3 * sizeof *kept);
        return 0;
    }
    for (size_t i = 0; i < count; ++i) {
        for (int j = 0; j < 3; ++j) keys[i].k[j] = (int64_t)floor(xyz[3 * i + j] / w);
        keys[i].i = i;
    }
    qsort(keys, count, sizeof *keys, weld_cmp);
    size_t n = 0;
    for (size_t i = 0; i < count; ++i) {
        const int64_t *k = keys[i].k, *prev = i > 0 ? keys[i - 1].k : NULL;
        if (prev && k[0] == prev[0] && k[1] == prev[1] && k[2] == prev[2]) continue; /* same cell */
        memcpy(kept + 3 * n++, xyz + 3 * keys[i].i, 3 * sizeof *kept);
    }
    pxi_free(alloc, keys, count * sizeof *keys);
    *out = kept;
    return n;
}

static px_convex *convex_create(const double *xyz, size_t count, const px_convex_options *options, int weld,
                                px_error *err);

/* Whether three points are certainly not collinear: the orientation of
 * their projection on some coordinate plane is nonzero beyond the error
 * bound of its floating-point evaluation (pxi_orient2d_filter, Shewchuk's
 * orient2d first stage). 0 when no projection decides (nearly or exactly
 * collinear, or products outside the normal range): CGAL's exact
 * predicates decide then. */
static int surely_a_triangle(const double *p) {
    static const int axes[3][2] = {{1, 2}, {2, 0}, {0, 1}};
    for (int k = 0; k < 3; ++k) {
        int i = axes[k][0], j = axes[k][1];
        if (pxi_orient2d_filter(p[i], p[j], p[3 + i], p[3 + j], p[6 + i], p[6 + j]) != 0) return 1;
    }
    return 0;
}

/* The hull of a triangle, as pxcd_hull_compute gives it (vertices in input
 * order, faces (0, 1, 2) and (0, 2, 1): each starts at its smallest id,
 * sorted by their first two), built without CGAL: a model's triangle
 * leaves become px_convex copies one query at a time (model/query.c), and
 * CGAL would allocate outside the caller's allocator. */
typedef struct tri_hull {
    pxcd_hull h;
    double v[9];
    size_t offsets[3];
    uint32_t ids[6];
} tri_hull;

static void tri_hull_init(tri_hull *t, const double *xyz) {
    memcpy(t->v, xyz, sizeof t->v);
    static const uint32_t ids[6] = {0, 1, 2, 0, 2, 1};
    memcpy(t->ids, ids, sizeof ids);
    t->offsets[0] = 0, t->offsets[1] = 3, t->offsets[2] = 6;
    t->h = (pxcd_hull){3, t->v, 2, t->offsets, t->ids};
}

/* Frees a hull from pxcd_hull_compute (not the local triangle's). */
static void hull_release(pxcd_hull *h, const tri_hull *local) {
    if (h != &local->h) pxcd_hull_free(h);
}

/* A polygon for points that are flat to within rounding but that CGAL's
 * exact predicates call a solid: a plate whose corners were turned into
 * place (a unit square under a random rotation is off its plane by ~1e-16,
 * and 63 % of them were refused as too thin for double precision, review
 * s29). The plane: a, the point b farthest from it, the point c farthest
 * from the line ab. Taken when every point is within 64 ulps of the
 * coordinates' magnitude of it (the rounding of a turn, and below the
 * queries' contact band); the hull is then the 2D hull of the points'
 * coordinates in the plane (CGAL, exact on those), its corners the input
 * points themselves. Likewise points within that of the line ab (a rod
 * turned into place: 977 of 1000 five-point ones were refused) make the
 * segment between the two extreme ones along it, and points within that
 * of a make a point. */
typedef struct flat_hull {
    pxcd_hull h;
    int dim;
    size_t n, offsets[3];
    double *v;     /* 3 n */
    uint32_t *ids; /* 2 n: the ring, then the ring reversed */
} flat_hull;

static void flat_hull_free(flat_hull *f, const px_allocator *alloc) {
    pxi_free(alloc, f->v, f->n * 3 * sizeof *f->v);
    pxi_free(alloc, f->ids, f->n * 2 * sizeof *f->ids);
    f->v = NULL, f->ids = NULL, f->n = 0;
}

/* A point's coordinates in the plane, and its index: sorted, so that each
 * corner of the 2D hull finds its input point in log time (a flat disc of
 * 100,000 points has as many corners). */
typedef struct plane_point {
    double x, y;
    size_t i;
} plane_point;

static int cmp_plane_point(const void *a, const void *b) {
    const plane_point *p = a, *q = b;
    if (p->x != q->x) return p->x < q->x ? -1 : 1;
    if (p->y != q->y) return p->y < q->y ? -1 : 1;
    return (p->i > q->i) - (p->i < q->i);
}

/* 1: f holds the polygon; 0: the points are not that flat (or no plane);
 * -1: out of memory. */
static int flat_hull_build(const double *xyz, size_t count, const px_allocator *alloc, flat_hull *f) {
    memset(f, 0, sizeof *f);
#define P(i) pxi_v(xyz[3 * (i)], xyz[3 * (i) + 1], xyz[3 * (i) + 2])
    const px_vec3 a = P(0);
    size_t ib = 0, ic = 0;
    double best = 0.0;
    for (size_t i = 1; i < count; ++i) {
        double d = pxi_len2(pxi_sub(P(i), a));
        if (d > best) best = d, ib = i;
    }
    const px_vec3 ab = pxi_sub(P(ib), a);
    best = 0.0;
    for (size_t i = 1; i < count; ++i) {
        double d = pxi_len2(pxi_cross(pxi_sub(P(i), a), ab));
        if (d > best) best = d, ic = i;
    }
    px_vec3 n = pxi_cross(ab, pxi_sub(P(ic), a));
    const double ln = pxi_len(n), lab = pxi_len(ab);
    double mag = lab;
    for (size_t i = 0; i < count; ++i) mag = pxi_max2(mag, pxi_max_abs(P(i)));
    const double tol = 64.0 * DBL_EPSILON * mag;
    if (!isfinite(ln) || !isfinite(lab) || !(tol < INFINITY)) return 0;
    if (!(lab > tol) || !(ln / lab > tol)) {
        /* A point, or a segment between the extremes along ab. */
        size_t lo = 0, hi = 0;
        double tlo = 0.0, thi = 0.0;
        for (size_t i = 0; lab > 0.0 && i < count; ++i) {
            const double t = pxi_dot(ab, pxi_sub(P(i), a));
            if (t < tlo) tlo = t, lo = i;
            if (t > thi) thi = t, hi = i;
        }
        for (size_t i = 0; lab > tol && i < count; ++i)
            if (!(pxi_len(pxi_cross(pxi_sub(P(i), a), ab)) / lab <= tol)) return 0;
        f->dim = lab > tol ? 1 : 0;
        f->n = (size_t)f->dim + 1;
        f->v = pxi_alloc_array(alloc, f->n, 3 * sizeof *f->v);
        f->ids = f->v ? pxi_alloc_array(alloc, f->n, 2 * sizeof *f->ids) : NULL;
        if (!f->ids) {
            flat_hull_free(f, alloc);
            return -1;
        }
        memcpy(f->v, xyz + 3 * (f->dim ? lo : 0), 3 * sizeof *f->v);
        if (f->dim) memcpy(f->v + 3, xyz + 3 * hi, 3 * sizeof *f->v);
        f->offsets[0] = 0;
        f->h = (pxcd_hull){f->n, f->v, 0, f->offsets, f->ids};
        return 1;
    }
    n = pxi_scale(n, 1.0 / ln);
    const px_vec3 u = pxi_scale(ab, 1.0 / lab), w = pxi_cross(n, u);
    double off = 0.0;
    for (size_t i = 0; i < count; ++i) off = pxi_max2(off, fabs(pxi_dot(n, pxi_sub(P(i), a))));
    if (!(off <= tol)) return 0;
    double *q = pxi_alloc_array(alloc, count, 3 * sizeof *q);
    if (!q) return -1;
    for (size_t i = 0; i < count; ++i) {
        const px_vec3 d = pxi_sub(P(i), a);
        q[3 * i] = pxi_dot(u, d), q[3 * i + 1] = pxi_dot(w, d), q[3 * i + 2] = 0.0;
    }
    pxcd_hull *h = NULL;
    int dim = 0, r = 0;
    const pxcd_status hs = pxcd_hull_compute(q, count, &h, &dim, NULL, 0);
    if (hs == PXCD_OUT_OF_MEMORY) r = -1;
    if (hs == PXCD_OK && h && dim == 2 && h->face_count == 2 && h->face_offsets[1] == h->vertex_count &&
        h->face_offsets[2] == 2 * h->vertex_count) {
        f->n = h->vertex_count;
        f->v = pxi_alloc_array(alloc, f->n, 3 * sizeof *f->v);
        f->ids = f->v ? pxi_alloc_array(alloc, f->n, 2 * sizeof *f->ids) : NULL;
        plane_point *pp = f->ids ? pxi_alloc_array(alloc, count, sizeof *pp) : NULL;
        r = pp ? 1 : -1;
        for (size_t i = 0; pp && i < count; ++i) pp[i] = (plane_point){q[3 * i], q[3 * i + 1], i};
        if (pp) qsort(pp, count, sizeof *pp, cmp_plane_point);
        /* Each corner back to an input point with its plane coordinates. */
        for (size_t k = 0; r == 1 && k < f->n; ++k) {
            const plane_point key = {h->vertices[3 * k], h->vertices[3 * k + 1], 0};
            size_t lo = 0, hi = count;
            while (lo < hi) {
                const size_t mid = lo + (hi - lo) / 2;
                if (cmp_plane_point(&pp[mid], &key) < 0)
                    lo = mid + 1;
                else
                    hi = mid;
            }
            if (lo == count || pp[lo].x != key.x || pp[lo].y != key.y)
                r = 0;
            else
                memcpy(f->v + 3 * k, xyz + 3 * pp[lo].i, 3 * sizeof *f->v);
        }
        pxi_free(alloc, pp, count * sizeof *pp);
        if (r == 1) {
            f->dim = 2;
            memcpy(f->ids, h->face_indices, f->n * 2 * sizeof *f->ids);
            f->offsets[0] = 0, f->offsets[1] = f->n, f->offsets[2] = 2 * f->n;
            f->h = (pxcd_hull){f->n, f->v, 2, f->offsets, f->ids};
        } else {
            flat_hull_free(f, alloc);
        }
    }
    pxcd_hull_free(h);
    pxi_free(alloc, q, count * 3 * sizeof *q);
    return r;
#undef P
}

px_convex *px_convex_create(const double *xyz, size_t count, const px_convex_options *options,
                            px_error *err) {
    return convex_create(xyz, count, options, 1, err);
}

static px_convex *convex_create(const double *xyz, size_t count, const px_convex_options *options, int weld,
                                px_error *err) {
    pxi_error_clear(err);
    px_allocator alloc;
    if (check_options(options, &alloc, err) != PX_OK) return NULL;
    if (!xyz) {
        pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_convex_create: points array is NULL");
        return NULL;
    }
    if (count == 0 || count > PXI_MAX_POINTS) {
        pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_convex_create: point count %zu is outside 1..%u", count,
                  PXI_MAX_POINTS);
        return NULL;
    }
    for (size_t i = 0; i < 3 * count; ++i)
        if (!isfinite(xyz[i])) {
            pxi_error(err, PX_ERR_NON_FINITE, "px_convex_create: point %zu has a non-finite coordinate %c",
                      i / 3, "xyz"[i % 3]);
            return NULL;
        }
    /* An extent that overflows is out of range before any plane is
     * computed from it (the hull's own size check comes later). */
    px_vec3 lo, hi;
    pxi_box3(xyz, count, &lo, &hi);
    const px_vec3 span = pxi_sub(hi, lo);
    for (int j = 0; j < 3; ++j) {
        if (!isfinite(j == 0 ? span.x : j == 1 ? span.y : span.z)) {
            pxi_error(err, PX_ERR_RANGE,
                      "px_convex_create: the points span more than the doubles hold along %c (the supported "
                      "size is 2^-1000 .. 2^1000)",
                      "xyz"[j]);
            return NULL;
        }
    }
    pxcd_hull *hull = NULL;
    int dim = 3;
    char msg[200] = {0};
    tri_hull tri;
    pxcd_status hs = PXCD_OK;
    if (count == 3 && surely_a_triangle(xyz)) {
        tri_hull_init(&tri, xyz);
        hull = &tri.h;
        dim = 2;
    } else {
        hs = pxcd_hull_compute(xyz, count, &hull, &dim, msg, sizeof msg);
    }
    if (hs == PXCD_OUT_OF_MEMORY) {
        pxi_error(err, PX_ERR_OUT_OF_MEMORY,
                  "px_convex_create: out of memory computing the hull of %zu points", count);
        return NULL;
    }
    if (hs != PXCD_OK || !hull || dim < 0 || dim > 3) {
        hull_release(hull, &tri);
        pxi_error(err, PX_ERR_INTERNAL, "px_convex_create: hull computation failed: %s", msg);
        return NULL;
    }
    px_convex *c = pxi_alloc(&alloc, sizeof *c);
    if (!c) {
        hull_release(hull, &tri);
        pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_convex_create: out of memory");
        return NULL;
    }
    memset(c, 0, sizeof *c);
    c->uid = pxi_next_uid();
    c->alloc = alloc;
    c->bytes = sizeof *c;
    px_status st = build_from_hull(c, hull, dim, err);
    hull_release(hull, &tri);
    /* A point has no size (it is stored as its own origin): any finite
     * point is in range. */
    if (st == PX_OK && c->dim > 0 && !(c->scale >= PXI_MIN_SIZE && c->scale <= PXI_MAX_SIZE))
        st = pxi_error(err, PX_ERR_RANGE,
                       "px_convex_create: the hull's size %.3g is outside the supported range [%.3g, %.3g] "
                       "(2^-1000 .. 2^1000; where the points sit in the double range does not matter)",
                       c->scale, PXI_MIN_SIZE, PXI_MAX_SIZE);
    if (st == PX_OK && validate_local(c, NULL) != PX_OK) {
        /* Exactly a solid (CGAL's predicates), but with a face whose plane
         * double precision cannot represent: a sliver too thin for its
         * normal, a slab 2^-1060 thick whose subnormal coordinates carry too
         * few bits (its side normals came out 0.79999 for 0.8), faces meeting
         * at an angle below rounding. Refused rather than answered on wrong
         * planes. (Polygons do not get here: a sliver polygon takes a plane
         * through its longest edge, in build_from_hull.) */
        static const char *what[] = {"a point", "a segment", "a polygon", "a solid"};
        px_error why;
        validate_local(c, &why);
        if (weld && c->dim == 3) {
            /* Often the cause is points a few ulps apart (cut points
             * computed twice, scans): their tiny faces have normals of
             * noise. Welded within 2^-40 of the points' extent (the hull
             * moves by at most that), the set is tried once more. */
            double w = ldexp(pxi_max2(span.x, pxi_max2(span.y, span.z)), -40);
            double *kept = NULL;
            size_t n = isfinite(w) && w > 0.0 && pxi_max_abs(lo) / w < 0x1p60 && pxi_max_abs(hi) / w < 0x1p60
                           ? weld_points(&alloc, xyz, count, w, &kept)
                           : 0;
            if (kept && n < count) {
                px_convex_destroy(c);
                px_convex *again = convex_create(kept, n, options, 0, err);
                pxi_free(&alloc, kept, count * 3 * sizeof *kept);
                return again;
            }
            pxi_free(&alloc, kept, count * 3 * sizeof *kept);
        }
        flat_hull fh;
        const int flat = c->dim >= 2 ? flat_hull_build(xyz, count, &alloc, &fh) : 0;
        px_convex *p = flat > 0 ? pxi_alloc(&alloc, sizeof *p) : NULL;
        const int oom = flat < 0 || (flat > 0 && !p);
        if (p) {
            memset(p, 0, sizeof *p);
            p->uid = pxi_next_uid();
            p->alloc = alloc;
            p->bytes = sizeof *p;
            if ((uint32_t)fh.dim < c->dim && build_from_hull(p, &fh.h, fh.dim, NULL) == PX_OK &&
                validate_local(p, NULL) == PX_OK) {
                px_convex_destroy(c);
                c = p;
            } else {
                px_convex_destroy(p);
                p = NULL;
            }
        }
        if (flat > 0) flat_hull_free(&fh, &alloc);
        if (oom)
            st = pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_convex_create: out of memory");
        else if (!p)
            st = pxi_error(err, PX_ERR_DEGENERATE,
                           "px_convex_create: the hull is %s but too thin for double precision (%s)",
                           what[c->dim <= 3 ? c->dim : 3], why.message);
    }
    if (st == PX_OK) {
        uint32_t res =
            options && options->lut_resolution ? options->lut_resolution : default_lut_resolution(c->nv);
        st = pxi_lut_build(c, res);
        if (st != PX_OK) pxi_error(err, st, "px_convex_create: out of memory for the direction table");
    }
    if (st != PX_OK) {
        px_convex_destroy(c);
        return NULL;
    }
    return c;
}

uint32_t px_convex_vertex_count(const px_convex *c) { return c ? c->nv : 0; }
uint32_t px_convex_edge_count(const px_convex *c) { return c ? c->ne : 0; }
uint32_t px_convex_face_count(const px_convex *c) { return c ? c->nf : 0; }
uint32_t px_convex_dimension(const px_convex *c) { return c ? c->dim : 0; }
size_t px_convex_memory_bytes(const px_convex *c) { return c ? c->bytes : 0; }

px_status px_convex_vertex(const px_convex *c, uint32_t i, px_vec3 *out) {
    if (out) *out = pxi_v(0, 0, 0);
    if (!c || !out || i >= c->nv) return PX_ERR_INVALID_ARGUMENT;
    *out = pxi_add(c->v[i], c->origin);
    return PX_OK;
}

px_status px_convex_edge(const px_convex *c, uint32_t e, uint32_t out[2]) {
    if (out) out[0] = out[1] = 0;
    if (!c || !out || e >= c->ne) return PX_ERR_INVALID_ARGUMENT;
    out[0] = c->e[e].tail;
    out[1] = c->e[e].head;
    return PX_OK;
}

px_status px_convex_face(const px_convex *c, uint32_t f, px_vec3 *normal, double *offset,
                         uint32_t *vertex_count) {
    if (normal) *normal = pxi_v(0, 0, 0);
    if (offset) *offset = 0.0;
    if (vertex_count) *vertex_count = 0;
    if (!c || f >= c->nf) return PX_ERR_INVALID_ARGUMENT;
    if (normal) *normal = c->f[f].n;
    if (offset) *offset = c->f[f].d + pxi_dot(c->f[f].n, c->origin); /* the body frame's plane */
    if (vertex_count) *vertex_count = c->f[f].count;
    return PX_OK;
}

px_status px_convex_face_vertex(const px_convex *c, uint32_t f, uint32_t k, uint32_t *vertex) {
    if (vertex) *vertex = 0;
    if (!c || !vertex || f >= c->nf || k >= c->f[f].count) return PX_ERR_INVALID_ARGUMENT;
    *vertex = c->f_verts[c->f[f].first + k];
    return PX_OK;
}

px_status px_convex_bounds(const px_convex *c, const px_pose *pose, px_bounds *out) {
    if (out) memset(out, 0, sizeof *out);
    if (!c || !out) return PX_ERR_INVALID_ARGUMENT;
    px_pose id = px_pose_identity();
    if (!pose) pose = &id;
    px_status st = px_pose_check(pose, NULL);
    if (st != PX_OK) return st;
    /* The box is exact: along each world axis, the extreme vertex (a support
     * query in the body frame along that axis's row of R). */
    double lo[3], hi[3], t[3] = {pose->t.x, pose->t.y, pose->t.z};
    for (int i = 0; i < 3; ++i) {
        px_vec3 axis = pxi_v(pose->r[3 * i], pose->r[3 * i + 1], pose->r[3 * i + 2]);
        uint32_t vmax = pxi_support(c, axis, UINT32_MAX), vmin = pxi_support(c, pxi_neg(axis), UINT32_MAX);
        /* world coordinate i of a body point p: row i of R times p, plus t_i */
        double at = pxi_dot(axis, c->origin) + t[i]; /* world coordinate i of the stored origin */
        hi[i] = pxi_dot(axis, c->v[vmax]) + at;
        lo[i] = pxi_dot(axis, c->v[vmin]) + at;
    }
    out->min = pxi_v(lo[0], lo[1], lo[2]);
    out->max = pxi_v(hi[0], hi[1], hi[2]);
    out->center = pxi_xform(pose, pxi_add(c->center, c->origin));
    out->radius = c->radius;
    if (!pxi_is_finite3(out->min) || !pxi_is_finite3(out->max) || !pxi_is_finite3(out->center)) {
        memset(out, 0, sizeof *out);
        return PX_ERR_NON_FINITE; /* a pose so far out that the world coordinates overflow */
    }
    return PX_OK;
}

/* Structural validation. Convexity is checked locally at every edge (the
 * dihedral turns outward) on all hulls; a closed, connected, locally convex
 * polyhedral surface bounds a convex body (van Heijenoort 1952). The global
 * vertex-below-every-plane test runs too when V*F is small enough. */
/* The checks that cost O(V + E + F): Euler, face loops against edge
 * adjacency, unit outward normals, planar faces, convex dihedrals, vertex
 * adjacency. px_convex_create runs them on every polytope it builds. */
static px_status validate_local(const px_convex *c, px_error *err) {
    /* Euler per dimension: V - E + F = 2 for a solid and for a two-sided
     * polygon, a segment is V = 2, E = 1, a point V = 1. */
    static const uint32_t degree_lo[4] = {0, 1, 2, 3}, degree_hi[4] = {0, 1, 2, UINT32_MAX};
    uint32_t dim = c->dim;
    int counts_ok = dim == 3   ? c->nf >= 4
                    : dim == 2 ? c->nf == 2 && c->ne == c->nv && c->nv >= 3
                    : dim == 1 ? c->nv == 2 && c->ne == 1 && c->nf == 0
                               : dim == 0 && c->nv == 1 && c->ne == 0 && c->nf == 0;
    if (!counts_ok || (int64_t)c->nv - (int64_t)c->ne + (int64_t)c->nf != (dim >= 2 ? 2 : 1))
        return pxi_error(err, PX_ERR_INTERNAL, "Euler's formula fails for dimension %u: V=%u E=%u F=%u", dim,
                         c->nv, c->ne, c->nf);
    double tol = 1e-9 * (c->scale > 0 ? c->scale : 1.0);
    for (uint32_t f = 0; f < c->nf; ++f) {
        const pxi_face *F = &c->f[f];
        if (F->count < 3) return pxi_error(err, PX_ERR_INTERNAL, "face %u has %u vertices", f, F->count);
        if (fabs(pxi_len(F->n) - 1.0) > 1e-12)
            return pxi_error(err, PX_ERR_INTERNAL, "face %u normal not unit", f);
        for (uint32_t k = 0; k < F->count; ++k) {
            uint32_t a = c->f_verts[F->first + k], b = c->f_verts[F->first + (k + 1) % F->count];
            const pxi_edge *E = &c->e[c->f_edges[F->first + k]];
            int left = E->tail == a && E->head == b && E->left == f;
            int right = E->tail == b && E->head == a && E->right == f;
            if (!left && !right)
                return pxi_error(err, PX_ERR_INTERNAL,
                                 "face %u boundary %u->%u disagrees with edge adjacency", f, a, b);
            if (fabs(pxi_dot(F->n, c->v[a]) - F->d) > tol)
                return pxi_error(err, PX_ERR_INTERNAL, "face %u is not planar at vertex %u", f, a);
            if (dim == 2) {
                /* A polygon is convex where its boundary turns left about
                 * its normal at every vertex (the dihedral test below is
                 * void: its two faces are one plane). */
                const pxi_edge *E2 = &c->e[c->f_edges[F->first + (k + 1) % F->count]];
                px_vec3 u1 = left ? E->u : pxi_neg(E->u), u2 = E2->tail == b ? E2->u : pxi_neg(E2->u);
                double turn = pxi_dot(pxi_cross(u1, u2), F->n);
                if (turn < -1e-12)
                    return pxi_error(err, PX_ERR_INTERNAL, "polygon face %u turns right at vertex %u (%.3g)",
                                     f, b, turn);
            }
        }
        /* Outward: the centre lies strictly below every face plane (a
         * polygon: on its plane, the back face the front turned over). */
        if (dim == 3 && !(pxi_dot(F->n, c->center) < F->d))
            return pxi_error(err, PX_ERR_INTERNAL, "face %u normal points inward", f);
    }
    if (dim == 2 &&
        (c->f[1].n.x != -c->f[0].n.x || c->f[1].n.y != -c->f[0].n.y || c->f[1].n.z != -c->f[0].n.z ||
         c->f[1].d != -c->f[0].d || !(fabs(pxi_dot(c->f[0].n, c->center) - c->f[0].d) <= tol)))
        return pxi_error(err, PX_ERR_INTERNAL, "the polygon's two faces are not one plane turned over");
    for (uint32_t i = 0; i < c->ne; ++i) {
        const pxi_edge *E = &c->e[i];
        if (E->tail >= c->nv || E->head >= c->nv || E->tail == E->head)
            return pxi_error(err, PX_ERR_INTERNAL, "edge %u has invalid adjacency", i);
        if (!(fabs(pxi_len(E->u) - 1.0) <= 1e-12))
            return pxi_error(err, PX_ERR_INTERNAL, "edge %u direction not unit", i);
        if (dim == 1) {
            if (E->left != PXI_NO_FACE || E->right != PXI_NO_FACE || pxi_max_abs(E->wl) != 0.0 ||
                pxi_max_abs(E->wr) != 0.0)
                return pxi_error(err, PX_ERR_INTERNAL, "the segment's edge has a face");
            continue;
        }
        if (E->left >= c->nf || E->right >= c->nf || E->left == E->right)
            return pxi_error(err, PX_ERR_INTERNAL, "edge %u has invalid adjacency", i);
        /* Convex dihedral: (n_L x n_R) . u >= 0 (REFERENCES §1.8). */
        double turn = pxi_dot(pxi_cross(c->f[E->left].n, c->f[E->right].n), E->u);
        if (turn < -1e-12) return pxi_error(err, PX_ERR_INTERNAL, "edge %u is reflex (%.3g)", i, turn);
    }
    for (uint32_t v = 0; v < c->nv; ++v) {
        uint32_t deg = c->v_first[v + 1] - c->v_first[v];
        if (deg < degree_lo[dim] || deg > degree_hi[dim])
            return pxi_error(err, PX_ERR_INTERNAL, "vertex %u has degree %u", v, deg);
        for (uint32_t k = c->v_first[v]; k < c->v_first[v + 1]; ++k) {
            const pxi_edge *E = &c->e[c->v_edges[k]];
            if ((E->tail != v || E->head != c->v_adj[k]) && (E->head != v || E->tail != c->v_adj[k]))
                return pxi_error(err, PX_ERR_INTERNAL, "vertex %u adjacency disagrees with edge %u", v,
                                 c->v_edges[k]);
        }
    }
    return PX_OK;
}

px_status px_convex_validate(const px_convex *c, px_error *err) {
    pxi_error_clear(err);
    if (!c) return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "polytope is NULL");
    px_status st = validate_local(c, err);
    if (st != PX_OK) return st;
    double tol = 1e-9 * (c->scale > 0 ? c->scale : 1.0);
    if ((uint64_t)c->nv * c->nf <= 4000000u) {
        for (uint32_t f = 0; f < c->nf; ++f)
            for (uint32_t v = 0; v < c->nv; ++v)
                if (pxi_dot(c->f[f].n, c->v[v]) - c->f[f].d > tol)
                    return pxi_error(err, PX_ERR_INTERNAL, "vertex %u lies above face %u: not convex", v, f);
    }
    if (c->dim == 2 && (uint64_t)c->nv * c->ne <= 4000000u) {
        /* In the polygon's plane: every vertex on the inner side of every
         * edge (wl points into the polygon). */
        for (uint32_t i = 0; i < c->ne; ++i)
            for (uint32_t v = 0; v < c->nv; ++v)
                if (pxi_dot(pxi_sub(c->v[v], c->v[c->e[i].tail]), c->e[i].wl) < -tol)
                    return pxi_error(err, PX_ERR_INTERNAL, "vertex %u lies outside edge %u: not convex", v,
                                     i);
    }
    return PX_OK;
}
