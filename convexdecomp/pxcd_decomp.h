/* pxcd_decompose: approximate convex decomposition of a triangle mesh
 * (issue 10, section 1), behind a C ABI. Included by pxcd.h; do not include
 * it alone (it uses pxcd_status from there).
 *
 * Method (convexdecomp/decompose.cpp has the details and the sources: CoACD,
 * Wei et al., SIGGRAPH 2022; V-HACD 4): recursive axis-aligned plane cuts
 * chosen greedily to minimise the worst sampled concavity of the two halves,
 * then a greedy merge pass, then every piece is re-hulled.
 *
 * Concavity of a piece (the decomposer's own, sampled, UNCERTIFIED measure):
 * the largest distance from sample points of the piece's convex hull
 * boundary to the piece's own surface (the input triangles clipped to the
 * piece, plus the cut caps when the input is closed). It is at least the
 * distance from those points to the whole part (to its solid when closed,
 * to its triangles when open), up to sampling. Callers that need a bound
 * must certify it themselves (src/model/reach.c).
 *
 * What "inside" means:
 *   - Closed input (every undirected edge, after merging vertices with
 *     bit-identical coordinates, is used by an even number of triangles;
 *     orientation is irrelevant): the part is the solid bounded by the
 *     triangles (even-odd rule). Cuts close each half with a cap (the
 *     cross-section, even-odd), so the pieces partition the solid and the
 *     union of the piece hulls covers it (up to rounding of the cut points,
 *     ~1e-15 of the diagonal).
 *   - Open input (anything else, including non-manifold edges used 3 times,
 *     holes, single sheets): the part is its triangles only. No caps; every
 *     input triangle lies in the union of the piece hulls (each triangle is
 *     split among the pieces it crosses), and each hull stays within the
 *     tolerance (sampled) of the triangles.
 *
 * Deterministic: the same input and options give the same pieces bit for
 * bit, whatever `threads` is (candidate cuts and merge pairs are evaluated
 * in parallel batches and reduced in a fixed order). No global state, no
 * environment variable; safe to call from several threads at once.
 * The coordinates are not transformed: the tolerance is scaled by the
 * diagonal instead, so hull vertices that are input vertices are bit-equal
 * to them (except that -0.0 becomes +0.0).
 */
#ifndef PROXIMA_PXCD_DECOMP_H
#define PROXIMA_PXCD_DECOMP_H

#ifndef PROXIMA_PXCD_H
#error "include pxcd.h, not pxcd_decomp.h"
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* Stages reported to the progress callback. Fractions go from 0 to 1
 * within a stage (roughly: cutting reports the share of the input's area
 * already in accepted pieces), stages come in this order. */
enum {
    PXCD_STAGE_CUT = 1,   /* recursive cutting */
    PXCD_STAGE_MERGE = 2, /* merge pass */
    PXCD_STAGE_HULL = 3   /* final hulls */
};

/* Options. Zero-initialise, then set `tolerance`; zero means default for
 * every other field. */
typedef struct pxcd_decomp_options {
    /* Target concavity, relative to the input's bounding-box diagonal (e.g.
     * 0.02). Required: finite and > 0. Values >= 1 give one piece per
     * connected component. */
    double tolerance;
    /* Safety cap on the number of pieces during cutting (0 = 4096). When it
     * is reached, pieces still above the tolerance are kept as they are
     * (their concavity then exceeds the tolerance; see `pieces_over`). The
     * count can exceed it when the input has more connected components, or
     * by a few when the last cut splits a piece into several components. */
    unsigned max_pieces;
    /* 0 or 1 = the calling thread only; n > 1 = up to n threads (capped at
     * 64) for candidate evaluation. Any value gives the same output. */
    unsigned threads;
    /* Called from the calling thread now and then with a PXCD_STAGE_* value
     * and a fraction in [0, 1]; a nonzero return cancels (PXCD_CANCELLED).
     * May be NULL. */
    int (*progress)(void *user, int stage, double fraction);
    void *user;
    unsigned reserved[4]; /* must be zero (PXCD_INVALID_INPUT otherwise) */
} pxcd_decomp_options;

/* One convex piece: the extreme points of the piece, i.e. the vertices of
 * its convex hull (CGAL convex_hull_3, exact predicates), sorted
 * lexicographically by (x, y, z). A piece may be flat (coplanar points),
 * a segment (2 points) or a point (1 point). */
typedef struct pxcd_decomp_piece {
    size_t vertex_count;
    double *vertices; /* 3 * vertex_count, input frame and units */
    /* The decomposer's sampled concavity estimate of this piece, in input
     * units (not relative), NOT a certified bound. */
    double concavity;
} pxcd_decomp_piece;

typedef struct pxcd_decomp_result {
    size_t piece_count;
    pxcd_decomp_piece *pieces;
    double diagonal;    /* bounding-box diagonal of the input vertices used by triangles */
    int closed;         /* 1: input treated as closed (solid, with caps); 0: open (surface) */
    size_t pieces_over; /* pieces whose estimate exceeds tolerance * diagonal (caps hit) */
    size_t cuts;        /* number of plane cuts performed */
    size_t merges;      /* number of merges performed */
} pxcd_decomp_result;

/* Decomposes the triangle mesh (xyz: 3 * n_vertices doubles; tri:
 * 3 * n_triangles vertex ids < n_vertices). Vertices not used by any
 * triangle are ignored. Triangles may be degenerate, duplicated,
 * inconsistently oriented, non-manifold or self-intersecting (the result is
 * then still a cover of the triangles, but concavities are measured against
 * whatever surface they form).
 * Returns PXCD_OK and a new result in *out (free with pxcd_decomp_free), or:
 *   PXCD_INVALID_INPUT  a NULL pointer, n_triangles == 0, n_vertices == 0 or
 *                       > UINT32_MAX, an id out of range, a non-finite
 *                       coordinate (of a used vertex), tolerance not finite
 *                       or <= 0, a nonzero reserved field;
 *   PXCD_CANCELLED      the progress callback returned nonzero;
 *   PXCD_OUT_OF_MEMORY  an allocation failed;
 *   PXCD_ERROR          CGAL threw or an internal check failed.
 * On any status but PXCD_OK *out is NULL (when out is not NULL), everything
 * allocated is freed, and a sentence goes to msg (msg_len bytes, may be 0;
 * msg may be NULL). */
pxcd_status pxcd_decompose(const double *xyz, size_t n_vertices, const uint32_t *tri, size_t n_triangles,
                           const pxcd_decomp_options *opt, pxcd_decomp_result **out, char *msg,
                           size_t msg_len);

/* Frees a result of pxcd_decompose; NULL is allowed. */
void pxcd_decomp_free(pxcd_decomp_result *result);

#ifdef __cplusplus
}
#endif

#endif /* PROXIMA_PXCD_DECOMP_H */
