/* Sub-part hierarchy trees (internal). See include/proxima/model.h. */
#ifndef PXI_MODEL_H
#define PXI_MODEL_H

#include <stdint.h>

#include "math/vec3.h"
#include "proxima/model.h"

#define PXI_NONE UINT32_MAX

/* Node flags. OVERSIZE: the subtree's hull had more than
 * PXI_HULL_MAX_VERTICES vertices and was not kept (nor is any ancestor's). */
#define PXI_NODE_OVERSIZE 1u

/* Triangle trees keep no hull of more vertices than this: a hull costs
 * ~450 bytes per vertex, and the hull of a large patch of a round surface
 * holds most of its vertices. */
#define PXI_HULL_MAX_VERTICES 256u

/* A tree node. Leaves have child[0] = leaf index and child[1] = PXI_NONE.
 * `hull` is the node's convex hull (for convex leaves: the piece itself), or
 * NULL where only the sphere bounds the subtree (triangle leaves, small
 * triangle subtrees, flat subtrees whose hull has no volume). */
typedef struct pxi_mnode {
    px_vec3 center; /* bounding sphere, body frame */
    double radius;
    uint32_t child[2];
    uint32_t box;   /* index into the model's boxes (inner nodes), PXI_NONE for leaves */
    uint32_t flags; /* PXI_NODE_* */
    px_convex *hull;
} pxi_mnode;

/* An oriented box bounding an inner node's subtree (body frame): centre,
 * orthonormal axes (rows of `axis`) along the principal directions of the
 * subtree's points, and half extents along them, rounded outward. Flat
 * patches get thin boxes, whose separating-axis bound stays tight where
 * spheres are not (two parallel plates). */
typedef struct pxi_box {
    px_vec3 center;
    double axis[9];
    px_vec3 half;
} pxi_box;

typedef struct pxi_mleaf {
    uint32_t part;
    uint32_t tri; /* triangle index into the model's copy, or PXI_NONE */
    double h, h_overlap;
} pxi_mleaf;

struct px_model {
    uint64_t uid;    /* pxi_next_uid(): what a cache recognises it by */
    uint32_t pieces; /* px_pieces */
    uint32_t n_nodes, n_leaves, n_hulls, depth;
    pxi_mnode *nodes; /* root is node 0 */
    pxi_box *boxes;   /* n_leaves - 1, one per inner node */
    pxi_mleaf *leaves;
    /* Triangle trees: the vertices and triangles (indices into v). */
    px_vec3 *v;
    uint32_t nv;
    uint32_t *tri; /* 3 per triangle */
    uint32_t nt;
    /* Solids for containment: one flag per triangle (1 when it belongs to a
     * closed part), and a representative vertex per connected piece of the
     * model (every piece of the model is tested for lying inside the other
     * model's solids). */
    uint8_t *tri_solid;
    uint32_t solid_parts;
    px_vec3 *reps;
    uint32_t n_reps;
    double max_h;
    px_vec3 lo, hi;
    size_t bytes;
    px_allocator alloc;
};

/* Models keep coordinates within 2^250 (boxes square them), and triangle
 * models span at least 2^-250 (closest points square edge lengths). */
#define PXI_MODEL_MAX_COORD 0x1p250
#define PXI_MODEL_MIN_SIZE 0x1p-250
px_status pxi_model_check_range(const double *xyz, size_t n, int triangles, px_error *err);

/* Builds a triangle tree (internal entry for the tests and
 * px_model_create_from_mesh): nv vertices, nt triangles, part[t] the part
 * of triangle t, closed[p] whether part p bounds a solid. */
px_model *pxi_model_from_triangles(const double *xyz, uint32_t nv, const uint32_t *tri, uint32_t nt,
                                   const uint32_t *part, const uint8_t *closed, uint32_t n_parts, int hulls,
                                   const px_allocator *alloc, px_error *err);

/* Certified bounds of a part hull or piece (reach.c): h over the hull's
 * boundary, h_overlap over the whole hull, of the distance to the part,
 * given as a triangle tree (built without hulls): to its triangles, or with
 * `solid` to the solid its closed triangles bound (0 inside; the tree needs
 * its solid flags). Refinement stops below `floor` (absolute; 0: refine to
 * 1 % of the largest distance seen). */
px_status pxi_part_reach(const px_allocator *alloc, const px_convex *hull, const px_model *tree, int solid,
                         double floor, double *h, double *h_overlap, px_error *err);

/* The same in a caller's scratch of at least
 * pxi_part_reach_scratch_bytes(pxi_part_reach_planes(hull)) bytes (the
 * largest over the hulls it serves), calling no
 * allocator (safe on a worker thread, one scratch per thread). `stop` (may
 * be NULL) is called with `stop_user` every thousand or so evaluations, on
 * the thread that computes; a nonzero return ends the computation with
 * PX_ERR_CANCELLED. The bounds do not depend on the thread. */
uint32_t pxi_part_reach_planes(const px_convex *hull);
size_t pxi_part_reach_scratch_bytes(uint32_t max_planes);
px_status pxi_part_reach_in(void *scratch, size_t scratch_bytes, const px_convex *hull, const px_model *tree,
                            int solid, double floor, int (*stop)(void *), void *stop_user, double *h,
                            double *h_overlap, px_error *err);

/* The builder's steps (build.c), shared with from_mesh.c and approx.c: a
 * model with its options checked; the tree over m->n_leaves leaves
 * (`convex`: their hulls, taken over, or NULL for triangles); the model or
 * NULL (freed) by status. */
px_model *pxi_model_alloc(const px_model_options *options, px_error *err, px_allocator *alloc);
px_status pxi_model_build_tree(px_model *m, px_convex **convex, int hulls, px_error *err);
px_model *pxi_model_finish(px_model *m, px_status st, px_error *err);

/* Approximate decomposition (approx.c): the leaves, hulls and bounds of a
 * PX_PIECES_APPROXIMATE model of `mesh`, into m (m->leaves, m->n_leaves)
 * and *convex (one hull per leaf, owned by the caller until the tree takes
 * them). */
px_status pxi_model_approximate(px_model *m, const px_mesh *mesh, const px_model_options *options,
                                px_convex ***convex, px_error *err);

/* Distance from p (body frame) to the nearest triangle of a triangle tree,
 * at most `limit` (returns `limit` when none is nearer); *tri gets the
 * triangle (PXI_NONE when none is nearer than limit). */
double pxi_model_nearest(const px_model *m, px_vec3 p, double limit, uint32_t *tri);

/* The representative points of a model (one per connected piece of a
 * triangle model, one vertex per convex piece; build.c): m->reps, counted in
 * m->bytes. For convex models `convex` lists the leaves' pieces. */
px_status pxi_model_triangle_reps(px_model *m, px_error *err);
px_status pxi_model_convex_reps(px_model *m, px_convex **convex, px_error *err);

/* Triangle geometry (tri.c). Closest point of triangle (a, b, c) to p,
 * with the feature realising it (vertex k, edge k from vertex k to k+1, or
 * face 0). Zero-area triangles are treated as their edges. */
px_vec3 pxi_tri_closest(px_vec3 p, const px_vec3 t[3], px_feature *feature);

/* Distance between triangles s and t with closest points and features;
 * 0 with a common point when they intersect. */
double pxi_tri_tri(const px_vec3 s[3], const px_vec3 t[3], px_vec3 *ps, px_vec3 *pt, px_feature *fs,
                   px_feature *ft);

/* 1 when the segment [p, q] crosses the triangle (proper crossing of the
 * plane inside the triangle); coplanar contact is left to the distances. */
int pxi_segment_crosses_tri(px_vec3 p, px_vec3 q, const px_vec3 t[3]);

/* Computes the box of `n` points (box.c). */
void pxi_box_fit(const px_vec3 *p, size_t n, pxi_box *out);

/* A lower bound on the distance between box a (frame A) and box b (frame
 * B, mapped into A by t_ab): the largest gap of the separating-axis test
 * over the 15 axes, the line of centres and `hint` (a unit vector in A's
 * frame, or NULL), minus a rounding margin; <= 0 when they may overlap;
 * a value above `limit` may be returned before every axis is tried. */
double pxi_box_gap(const pxi_box *a, const pxi_box *b, const px_pose *t_ab, const px_vec3 *hint, double limit,
                   px_vec3 *axis);

/* The same between triangle t (A's frame) and box b (its frame mapped into
 * A's by t_box; NULL: already in A's) over the box's axes, the triangle's
 * normal and the hint. Both return as soon as the bound exceeds `limit`.
 * `axis` (may be NULL) receives the unit axis of the returned gap, pointing
 * from the first set to the second (pxi_box_gap: from a to b;
 * pxi_tri_box_gap: from the box to the triangle), so that every point y of
 * the second and x of the first have axis . (y - x) >= the gap, up to the
 * margin already taken off; (0, 0, 0) when no axis was tried. */
double pxi_tri_box_gap(const px_vec3 t[3], const pxi_box *b, const px_pose *t_box, const px_vec3 *hint,
                       double limit, px_vec3 *axis);

/* Ray parity: 1 when p lies inside the solid bounded by the model's closed
 * parts, 0 outside, found by casting rays and counting crossings with the
 * closed triangles; a ray that grazes an edge or vertex is cast again in
 * another direction. */
int pxi_model_point_inside(const px_model *m, px_vec3 p);

#endif
