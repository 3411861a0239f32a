/* Closest points between segments (shared by Lin-Canny, GJK's polish and
 * collision translation). */
#include "narrow/closest.h"

#include <math.h>

/* Closest points of two segments (Ericson, Real-Time Collision Detection
 * §5.1.9, rewritten). The closed form divides by a e - b^2 = |d1|^2 |d2|^2
 * sin^2(angle); its parameters carry an error of about eps / sin^2, harmless
 * where the minimum is well defined. For nearly parallel segments (sin^2 below
 * 1e-6) the distance is nearly constant along the overlap and the closed form
 * is noise, so the answer is the best of well-conditioned candidates: the four
 * endpoint-to-segment projections, plus the closed form if it lands inside
 * both segments. Each candidate is a real pair of points, so the minimum is
 * never below the true distance and misses it by at most second order. */
static double seg_dist2(px_vec3 d1, px_vec3 d2, px_vec3 r, double s, double t) {
    /* |p0 + s d1 - (q0 + t d2)|^2 with r = p0 - q0 */
    return pxi_len2(pxi_sub(pxi_madd(r, d1, s), pxi_scale(d2, t)));
}

void pxi_segment_closest(px_vec3 p0, px_vec3 p1, px_vec3 q0, px_vec3 q1, double *s_out, double *t_out) {
    px_vec3 d1 = pxi_sub(p1, p0), d2 = pxi_sub(q1, q0), r = pxi_sub(p0, q0);
    /* Work at unit scale (a power of two, so exactly): a * e below is a
     * fourth power of lengths and would overflow at 1e80 or underflow at
     * 1e-80; the parameters s, t do not depend on the scale. */
    double m = pxi_max_abs(d1);
    if (pxi_max_abs(d2) > m) m = pxi_max_abs(d2);
    if (pxi_max_abs(r) > m) m = pxi_max_abs(r);
    /* Lengths between 2^-100 and 2^100 keep their fourth powers in range
     * as they are (and scaling by a power of two would change no bit):
     * only the others pay for ilogb and the scaling. */
    if (m > 0.0 && isfinite(m) && !(m >= 0x1p-100 && m <= 0x1p100)) {
        double k = pxi_pow2_unit(m); /* clamped: 2^-ilogb(m) is inf for subnormal m */
        d1 = pxi_scale(d1, k), d2 = pxi_scale(d2, k), r = pxi_scale(r, k);
    }
    double a = pxi_dot(d1, d1), e = pxi_dot(d2, d2), f = pxi_dot(d2, r);
    double c = pxi_dot(d1, r), b = pxi_dot(d1, d2);
    double s, t;
    if (!(a > 0.0) || !(e > 0.0)) { /* degenerate segment: cannot happen on a valid hull */
        *s_out = 0.0;
        *t_out = e > 0.0 ? pxi_clamp01(f / e) : 0.0;
        return;
    }
    double denom = a * e - b * b;
    if (denom > 1e-6 * a * e) {
        s = pxi_clamp01((b * f - c * e) / denom);
        t = (b * s + f) / e;
        if (t < 0.0) {
            t = 0.0;
            s = pxi_clamp01(-c / a);
        } else if (t > 1.0) {
            t = 1.0;
            s = pxi_clamp01((b - c) / a);
        }
        *s_out = s;
        *t_out = t;
        return;
    }
    /* Nearly parallel. Candidates: endpoints of one against the other. */
    double cs[7], ct[7];
    int n = 0;
    cs[n] = 0.0, ct[n++] = pxi_clamp01(f / e);       /* p0 on q */
    cs[n] = 1.0, ct[n++] = pxi_clamp01((b + f) / e); /* p1 on q */
    cs[n] = pxi_clamp01(-c / a), ct[n++] = 0.0;      /* q0 on p */
    cs[n] = pxi_clamp01((b - c) / a), ct[n++] = 1.0; /* q1 on p */
    /* The crossing of the two lines, from the cross product: a e - b^2
     * cancels catastrophically at small angles (sin^2 1e-9 = 1e-18 < eps),
     * |d1 x d2|^2 keeps relative precision eps / sin. */
    px_vec3 cr = pxi_cross(d1, d2), qp = pxi_neg(r);
    double den2 = pxi_dot(cr, cr);
    if (den2 > 0.0) {
        double si = pxi_dot(pxi_cross(qp, d2), cr) / den2, ti = pxi_dot(pxi_cross(qp, d1), cr) / den2;
        if (si >= 0.0 && si <= 1.0 && ti >= 0.0 && ti <= 1.0) {
            cs[n] = si, ct[n++] = ti;
            /* si and ti each carry an error of about eps / sin along their
             * line, and the two do not cancel: the pair is far apart by
             * that much. The point at si projected on q (and ti's on p) is
             * off by only that error times sin. */
            cs[n] = si, ct[n++] = pxi_clamp01((b * si + f) / e);
            cs[n] = pxi_clamp01((b * ti - c) / a), ct[n++] = ti;
        }
    }
    double best = INFINITY;
    s = t = 0.0;
    for (int k = 0; k < n; ++k) {
        double d = seg_dist2(d1, d2, r, cs[k], ct[k]);
        if (d < best) best = d, s = cs[k], t = ct[k];
    }
    /* Exactly parallel with overlap: every overlap point is closest; prefer
     * the middle of the overlap so that both points are edge interiors and
     * the region tests see no false violation at a shared endpoint plane. */
    if (den2 <= 1e-30 * a * e) {
        double s0 = -c / a, s1 = (b - c) / a;
        double lo = s0 < s1 ? s0 : s1, hi = s0 < s1 ? s1 : s0;
        if (lo < 0.0) lo = 0.0;
        if (hi > 1.0) hi = 1.0;
        if (lo < hi) {
            double sm = 0.5 * (lo + hi), tm = pxi_clamp01((b * sm + f) / e);
            if (seg_dist2(d1, d2, r, sm, tm) <= best) s = sm, t = tm;
        }
    }
    *s_out = s;
    *t_out = t;
}
