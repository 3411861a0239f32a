/* Separating-axis oracles for penetration depth and collision translation
 * (tests only).
 *
 * Independent of src/: a px_convex is read only through the public
 * accessors (vertices, edges, face vertex lists); face normals are
 * recomputed here (Newell's method in the body frame, then rotated) and the
 * edge-face adjacency is rebuilt from the face loops.
 *
 * Both oracles rest on one fact: the facets of the Minkowski difference
 * K = A - B (world frame, points a - b) have outward normals among
 *   - the outward face normals of A,
 *   - the negated outward face normals of B,
 *   - +-(e_A x e_B) / |e_A x e_B| for an edge e_A of A and e_B of B whose
 *     Gauss-map arcs (the arc between the normals of an edge's two faces; for
 *     B the arcs of -B) cross (Minkowski sum facets; e.g. Ericson 2005 §5.5,
 *     Gregorius GDC 2013 "The Separating Axis Test between convex polyhedra").
 * The arc-crossing test only prunes: it is evaluated with a slack so it
 * keeps every real edge-edge facet (and a few extra axes). Extra axes are
 * harmless: for any unit n the support value h_K(n) = max a.n - min b.n is
 * an upper bound of the depth and a valid half-space of K. Edge pairs whose
 * cross product is below 1e-14 |e_A||e_B| are skipped: parallel edges make
 * no facet, and a nearly parallel pair makes a facet whose support value
 * differs from its neighbours' (which are kept) by O(angle * size).
 *
 * Support values are brute-force maxima over all vertices, evaluated in a
 * world frame shifted to the centre of the smaller body, so that rounding is
 * relative to the pair's size and not to its distance from the world origin.
 * No function produces NaN or divides by zero.
 */
#ifndef PX_TESTS_ORACLE_SAT_H
#define PX_TESTS_ORACLE_SAT_H

#include <stdint.h>

#include "proxima/proxima.h"

/* A polytope prepared once (body frame). */
typedef struct os_shape {
    const px_convex *c;
    uint32_t nv, ne, nf;
    px_vec3 *v;    /* body-frame vertices */
    px_vec3 *fn;   /* outward unit face normals (Newell, body frame) */
    double *fd;    /* face plane offsets fn . p = fd (mean over the face's vertices) */
    uint32_t *ev;  /* 2 * ne: edge endpoints */
    uint32_t *ef;  /* 2 * ne: the two faces of each edge */
    px_vec3 mean;  /* vertex mean (body frame) */
    double radius; /* max |v| (body frame) */
} os_shape;

/* Returns 0, or -1 (and prints why) when the face loops do not form a closed
 * 2-manifold or a face has no computable normal. */
int os_shape_init(os_shape *s, const px_convex *c);
void os_shape_free(os_shape *s);

/* Global switch (default 1): prune edge-edge axes by the Gauss-map arc test.
 * 0 = every edge pair (the plain brute force; used to cross-check). */
extern int os_prune;

typedef struct os_pen_result {
    /* min over the candidate axes n of h_K(n), K = A - B. Positive: the
     * penetration depth (B must move by depth along `normal` to touch A).
     * Negative: the pair is separated by at least -depth along `normal`
     * (the best separating axis; a lower bound of the distance). */
    double depth;
    px_vec3 normal; /* the minimising unit axis, world frame */
    int separated;  /* depth < 0 */
    uint32_t axes;  /* candidate axes evaluated */
    px_vec3 origin; /* the shifted frame's origin, world (diagnostics) */
} os_pen_result;

void os_penetration(const os_shape *a, const px_pose *pa, const os_shape *b, const px_pose *pb,
                    os_pen_result *out);

/* h_K(n) = max_a a.n - min_b b.n for a unit world direction n, K = A - B:
 * B translated by s n with s >= h_K(n) is at most touching A (the plane
 * orthogonal to n separates them). */
double os_support_diff(const os_shape *a, const px_pose *pa, const os_shape *b, const px_pose *pb, px_vec3 n);

/* Signed distance of the world point p to the boundary of s at pose:
 * max over faces of (n . p - offset); 0 on the boundary, < 0 inside. */
double os_boundary_offset(const os_shape *s, const px_pose *pose, px_vec3 p);

typedef struct os_tr_result {
    /* A at pose_a + tau * d touches B for tau in [tau_min, tau_max] (units
     * of the given d); hit when tau_min <= tau_max. tau_min is the answer. */
    int hit;
    double tau_min, tau_max;
    px_vec3 normal; /* hit: the facet normal of B - A realising tau_min (A -> B) */
    /* Separation of the line {tau d} from K' = B - A measured perpendicular
     * to d, over the projected edge normals n = +-(d x e)/|d x e| (e an edge
     * of A or B): max over them of min_b b.n - max_a a.n. Positive exactly
     * when no translation along d touches (the projection of K' is a convex
     * polygon whose edges are projections of edges of A or B); then it is a
     * lower bound of the true perpendicular gap (equal unless the closest
     * point of the projected polygon is one of its vertices). Negative on a
     * hit: minus the depth of the line inside K' (perpendicular). */
    double gap;
    px_vec3 gap_normal;
    uint32_t axes;
} os_tr_result;

void os_translation(const os_shape *a, const px_pose *pa, const os_shape *b, const px_pose *pb, px_vec3 d,
                    os_tr_result *out);

#endif
