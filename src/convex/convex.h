/* The convex polytope structure (internal layout of px_convex).
 *
 * Conventions (docs/lin-canny.md, shared REFERENCES §1.1):
 * - outward unit face normals n_f, face plane n_f . p = d_f;
 * - edge e runs tail -> head, u = unit(head - tail);
 * - the LEFT face L of e is the face whose counter-clockwise boundary (seen
 *   from outside) contains tail -> head; the RIGHT face R contains head -> tail;
 * - wl = n_L x u lies in L's plane and points into L; wr = u x n_R lies in R's
 *   plane and points into R. These are the FE constraint-plane normals.
 * Voronoi regions (all planes derived from stored vectors, nothing duplicated):
 * - VR(vertex v): (p - v) . u_out <= 0 for every incident edge leaving v;
 * - VR(edge e):   (p - t) . u >= 0, (p - h) . u <= 0, (p - t) . wl <= 0, (p - t) . wr <= 0;
 * - VR(face f):   (p - t_e) . w_{f,e} >= 0 for each boundary edge, n_f . p >= d_f.
 * Lower-dimensional pieces (dim < 3) use the same structure:
 * - a polygon (dim 2) is two-sided: faces 0 and 1 share every edge, with
 *   n_1 = -n_0 and d_1 = -d_0 exactly; each edge has one face on each side,
 *   so wl = n_L x u = u x n_R = wr and its region is the half-space outside
 *   the edge (both sides of the plane) between its two VE planes; vertices
 *   have degree 2. V - E + F = 2 still holds.
 * - a segment (dim 1) is 2 vertices and 1 edge (tail 0, head 1), no face:
 *   left = right = PXI_NO_FACE and wl = wr = 0, so the edge's region is the
 *   slab between its VE planes (the zero planes are never violated).
 * - a point (dim 0) is 1 vertex of degree 0: its region is all of space.
 */
#ifndef PXI_CONVEX_H
#define PXI_CONVEX_H

#include <stdint.h>

#include "proxima/convex.h"
#include "proxima/query.h"

/* A polygon turning by less than this (the sine of its exterior angle, about
 * its normal) at some vertex is a sliver whose normal and in-plane region
 * planes rounding decides: Lin-Canny's walk can cycle on them, and the
 * queries serve it from support functions alone (query.c's table). */
#define PXI_WALK_MIN_TURN 1e-9

/* The left and right face of a segment's edge (it has none). */
#define PXI_NO_FACE UINT32_MAX

typedef struct pxi_edge {
    uint32_t tail, head;  /* vertex ids */
    uint32_t left, right; /* face ids */
    px_vec3 u;            /* unit direction tail -> head */
    px_vec3 wl, wr;       /* in-plane inward normals of the left and right face */
} pxi_edge;

typedef struct pxi_face {
    px_vec3 n;             /* outward unit normal */
    double d;              /* plane offset: n . p = d */
    uint32_t first, count; /* boundary in f_verts / f_edges, CCW from outside */
} pxi_face;

/* Cube-map direction table (PhysX-style "Gauss map" lookup): for each of the
 * 6 cube faces a res x res grid of cells, each holding the vertex extreme in
 * the direction of the cell centre. A support query looks up its cell and
 * finishes by hill climbing, which is exact on a convex polytope. */
typedef struct pxi_lut {
    uint32_t res;
    uint32_t *cell; /* 6 * res * res vertex ids */
    /* Cells are indexed by the direction map[] * d (row-major 3x3), not by
     * d: map = diag(w) Q^T with Q the body's principal axes and w its
     * relative widths along them. For an ellipsoid-like body this spreads
     * its vertices evenly over the cells (its support along d is the
     * sphere point along map * d); without it, a thin body's flat sides
     * crowd thousands of vertices into a few cells and the climbs are long. */
    double map[9];
} pxi_lut;

struct px_convex {
    uint64_t uid; /* pxi_next_uid(): what a model cache recognises it by */
    uint32_t nv, ne, nf;
    uint32_t dim;      /* affine dimension: 3 solid, 2 polygon, 1 segment, 0 point */
    uint32_t walk_ok;  /* 1 when Lin-Canny can walk it: always, but for a polygon that turns by less
                          than PXI_WALK_MIN_TURN at a vertex (a sliver: its normal is rounding) */
    px_vec3 *v;        /* nv vertex positions, body frame minus origin */
    uint32_t *v_first; /* nv + 1: incident edges of v are v_edges[v_first[v] .. v_first[v+1]) */
    uint32_t *v_edges; /* 2 * ne incident edge ids */
    uint32_t *v_adj;   /* 2 * ne: v_adj[k] = the other end of v_edges[k] */
    pxi_edge *e;       /* ne */
    pxi_face *f;       /* nf */
    uint32_t *f_verts; /* 2 * ne: face boundary vertices, CCW */
    uint32_t *f_edges; /* 2 * ne: f_edges[first + k] joins f_verts[first + k] -> f_verts[first + k + 1 (mod
                          count)] */
    /* Everything is stored relative to `origin`, a point of the body frame:
     * body-frame point = stored point + origin. origin is 0 for a body near
     * its frame's origin; for a body far from it (coordinates at 1e14 times
     * its size) it is the body's middle, chosen so that every stored
     * coordinate v - origin is exact (Sterbenz). Then all rounding, and every
     * tolerance derived from coordinates, is relative to the body's size and
     * the distance between the bodies, not to where the point set sits. */
    px_vec3 origin;
    px_vec3 center;   /* mean of the vertices (an interior point), stored frame */
    double radius;    /* max |v - center| */
    double scale;     /* max |coordinate| of v, for relative tolerances */
    double reach;     /* radius + 4 max|center|: with twice max|t|, a cheap bound on a pair's size */
    double roundness; /* least / greatest width over 13 directions, in (0, 1]: 1 for a ball-like body */
    /* A ball inside the solid (stored frame; radius 0: none, as for a flat
     * body): two bodies whose inner balls overlap intersect, which the
     * scene uses to skip the query of a deeply overlapping pair. */
    px_vec3 inner_center;
    double inner_radius;
    pxi_lut lut;
    size_t bytes;       /* everything allocated for this polytope */
    px_allocator alloc; /* what allocated it, and frees it */
};

/* Vertex of `c` extreme along direction `d` (body frame): argmax v . d.
 * Starts at `start` (UINT32_MAX: from the lookup table) and hill-climbs over
 * the vertex graph with strict improvement only, so it terminates (also on
 * NaN, where no comparison succeeds). Exact up to ties. */
uint32_t pxi_support(const px_convex *c, px_vec3 d, uint32_t start);

/* Starting vertex for direction d from the lookup table (no climbing). */
uint32_t pxi_lut_lookup(const px_convex *c, px_vec3 d);

/* Builds the lookup table of `c` (called once by the constructor). */
px_status pxi_lut_build(px_convex *c, uint32_t res);
void pxi_lut_destroy(px_convex *c);

#endif
