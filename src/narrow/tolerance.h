/* Tolerance bands of the narrow phase and the one definition of a pair's
 * scale (internal).
 *
 * Every threshold below is either relative to the pair's scale (the span
 * S = scale_A + scale_B + max|t_AB|, body coordinates' magnitude included) or
 * to the coordinates of the points under test. None is absolute: a problem
 * scaled by a power of two takes the same decisions (REFERENCES §1.8).
 *
 * The methods work either in the pair's power-of-two units (points of A - B
 * multiplied by pxi_pair_unit, so S lies in [1, 2): GJK, EPA, the hybrid,
 * translation) or in B's body frame as it is (Lin-Canny, whose region tests
 * are linear in the coordinates). A band "in scaled units" is a multiple of
 * eps in the former; "of the coordinates" is a multiple of eps times the
 * max-norm of the points compared.
 */
#ifndef PXI_TOLERANCE_H
#define PXI_TOLERANCE_H

#include <float.h>
#include <math.h>

#include "convex/convex.h"
#include "math/vec3.h"

/* Keeps a rarely taken path out of its caller, whose common path then
 * needs fewer registers saved and a smaller stack frame. */
#if defined(__GNUC__)
#define PXI_NOINLINE __attribute__((noinline))
#else
#define PXI_NOINLINE
#endif

/* ---- The pair's scale. ---- */

/* Every polytope is stored relative to its own middle when it sits far from
 * its frame's origin (convex.h), so a pair's scale is made of the bodies'
 * sizes and the distance between them, never of where their body-frame
 * coordinates sit. */

/* The size of the pair, R_A + R_B + |c_A - c_B| (radii about the centres,
 * the distance of the centres): what the contact band is relative to
 * (stated in proxima/query.h). */
static inline double pxi_pair_size(const px_convex *a, const px_convex *b, const px_pose *t_ab) {
    return a->radius + b->radius + pxi_len_safe(pxi_sub(pxi_xform(t_ab, a->center), b->center));
}

/* A cheap bound on the size, >= pxi_pair_size (|v| <= 2 max|v|, reach =
 * R + 4 max|center|, convex.h): a
 * distance above the band of this bound is outside the band, without a
 * square root. */
static inline double pxi_pair_size_bound(const px_convex *a, const px_convex *b, const px_pose *t_ab) {
    return a->reach + b->reach + 2.0 * pxi_max_abs(t_ab->t);
}

/* S = scale_A + scale_B + max|t_AB| (<= the size): every coordinate of
 * either body, mapped into B's frame, is below it. */
static inline double pxi_pair_span(const px_convex *a, const px_convex *b, const px_pose *t_ab) {
    return a->scale + b->scale + pxi_max_abs(t_ab->t);
}

/* The power of two k with k S in [1, 2): points of A - B are stored times k,
 * because the simplex solvers form fourth powers of lengths, which would
 * overflow for bodies of 1e80 or underflow for bodies of 1e-80. Exact, so
 * scaled runs see the same bits. 1 when S is 0 or not finite. */
static inline double pxi_pair_unit(const px_convex *a, const px_convex *b, const px_pose *t_ab) {
    return pxi_pow2_unit(pxi_pair_span(a, b, t_ab)); /* clamped: 2^-ilogb is inf for a subnormal span */
}

/* ---- Contact bands: "touching counts as intersecting". ---- */

/* The band every query honours: distance <= PXI_CONTACT_BAND * size is
 * touching (query.c applies it to every answer; each method's own band
 * below lies inside it). */
#define PXI_CONTACT_BAND (64.0 * DBL_EPSILON)

/* GJK family (scaled units, S in [1, 2)): |v| at or below this is contact. */
#define PXI_GJK_CONTACT (32.0 * DBL_EPSILON)
/* Hybrid: distance below this many eps times the scaled span is contact
 * (seed 001's absolute error Ae). */
#define PXI_HYBRID_CONTACT 8.0
/* Lin-Canny: a height, or a distance between closest points, within this
 * many eps of the coordinates compared is contact (their own rounding). */
#define PXI_LC_CONTACT (16.0 * DBL_EPSILON)

/* ---- Rounding of a point mapped between frames. ---- */

/* Lin-Canny's tie-breaking margin: a region-plane violation must exceed this
 * many eps of the coordinates in the second walk (docs/lin-canny.md). */
#define PXI_LC_TIE (8.0 * DBL_EPSILON)
/* A signed plane distance or support gap this many eps of the pair's scaled
 * size decides nothing (EPA's "on K's boundary", translation's contact). */
#define PXI_SUPPORT_NOISE (64.0 * DBL_EPSILON)

/* ---- Convergence. ---- */

/* GJK's relative duality gap: |v|^2 - v.w <= REL^2 |v|^2 bounds the relative
 * error of |v| by REL^2. On polytopes the loop nearly always ends earlier,
 * when the support repeats a simplex point. */
#define PXI_GJK_REL 1e-8
/* A GJK answer whose last duality gap exceeds this fraction of |v|^2 has not
 * proved separation: the lower bound (|v|^2 - gap) / |v| is far below |v|. */
#define PXI_GJK_OPEN_GAP 1e-6

#endif
