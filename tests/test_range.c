/* The supported number range (proxima/convex.h, proxima/query.h,
 * docs/design.md): the range study's reproductions as a regression test.
 *
 * Before the fix (commit 230ea47) the study's sweep found 170 of 242 rows
 * wrong: boxes of half-size 1e-300 .. 1e300, subnormal sizes, body-frame
 * coordinates offset by 1e6 and 1e14 times the size, mixed sizes, a shared
 * rotation, and quaternions of norm 1e-300 .. 1e300 gave touching for
 * separated pairs, +inf or NaN distances with PX_OK, translations of the
 * wrong sign and polytopes that failed their own validation. The fix stores
 * bodies about their middle when they sit far from their frame's origin,
 * forms squares and products of lengths at a power-of-two scale, limits
 * hull sizes to [2^-1000, 2^1000] (PX_ERR_RANGE from px_convex_create) and
 * pair spans to 2^1021 (PX_ERR_RANGE from the queries), and decides touching
 * by one contact band (query.h).
 *
 * Parts:
 *   1. The sweep: two boxes at half-sizes 1e-320 .. 1e300, every query
 *      (three distance methods unsigned and signed, px_intersect,
 *      px_translate forward and both ways, px_convex_validate) against the
 *      closed-form answer. The acceptance rule is the contact band of
 *      query.h, band = 64 eps (R_A + R_B + |c_A - c_B|) from
 *      px_convex_bounds: a gap above the band must be reported separated at
 *      that distance, an overlap deeper than the band intersecting at that
 *      depth, each within max(1e-6 relative, band); inside the band touching
 *      and the small distance are both accepted. Sizes outside the range
 *      must give PX_ERR_RANGE with a message; a body built anyway must still
 *      give right answers (never a wrong answer with PX_OK, never NaN).
 *   2. px_pose_from_quat at quaternion norms 1e-308 .. 1e300.
 *   3. The range's edges: sizes just inside and outside [2^-1000, 2^1000],
 *      pair spans below and above 2^1021.
 *   4. px_translate's forward decision does not depend on the direction's
 *      length (found while writing this test; fixed with it).
 *   5. Scale covariance: random hull pairs and poses, the whole input scaled
 *      by 2^k; every length must be 2^k times the k = 0 output bit for bit
 *      (tau, flags, features and diagnostics the same, unit normals within
 *      4 eps) within the range, and PX_ERR_RANGE outside it.
 * Prints one line per wrong sweep row and the count ("N of M rows wrong"). */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "proxima/proxima.h"
#include "px_gen.h"
#include "test_util.h"

#define REL 1e-6

static int g_rows, g_rows_wrong, g_rows_band;

/* |v| without overflow or underflow (the test's own arithmetic must stay
 * finite at 1e300 and exact enough at 1e-300). */
static double len3(px_vec3 v) {
    double m = fmax(fabs(v.x), fmax(fabs(v.y), fabs(v.z)));
    if (!(m > 0.0) || !isfinite(m)) return m;
    double x = v.x / m, y = v.y / m, z = v.z / m;
    return m * sqrt(x * x + y * y + z * z);
}
static int finite3(px_vec3 v) { return isfinite(v.x) && isfinite(v.y) && isfinite(v.z); }
static px_vec3 sub3(px_vec3 a, px_vec3 b) {
    px_vec3 r = {a.x - b.x, a.y - b.y, a.z - b.z};
    return r;
}

/* px_convex_create with the floating-point traps on: CGAL's interval
 * filters raise FE_INVALID when they overflow (boxes of half-size 2^511 =
 * 6.7e153 and above) or meet subnormal coordinates, and used to kill a
 * caller that had traps on (SIGFPE) although the hull was right; the hull
 * computation now keeps the caller's floating-point environment. */
static int g_created;
static px_convex *create(const double *xyz, size_t n, px_error *err) {
    memset(err, 0, sizeof *err);
    feclearexcept(FE_ALL_EXCEPT);
    px_convex *c = px_convex_create(xyz, n, NULL, err);
    ++g_created;
    CHECK(!fetestexcept(FE_INVALID | FE_DIVBYZERO),
          "px_convex_create left a floating-point exception raised");
    return c;
}

/* The box [x0, x1] x [lo, hi]^2 (8 corners). */
static px_convex *box(double x0, double x1, double lo, double hi, px_error *err) {
    double p[24];
    for (int i = 0; i < 8; ++i) {
        p[3 * i] = (i & 1) ? x1 : x0;
        p[3 * i + 1] = (i & 2) ? hi : lo;
        p[3 * i + 2] = (i & 4) ? hi : lo;
    }
    return create(p, 8, err);
}

/* A box of half-size h has a hull size between h and 2h whatever its offset;
 * the sweep's sizes are either >= 1e-300 and <= 1e300 (inside
 * [2^-1000, 2^1000] = [9.3e-302, 1.07e301] by a margin) or <= 1e-308
 * (outside by a factor of 1e6), so the expectation does not depend on
 * which of the two the library calls the size. */
static int size_in_range(double h) { return h >= 0x1p-1000 && 2 * h <= 0x1p1000; }

static const char *const k_method[3] = {"Lin-Canny", "GJK", "hybrid"};

/* One row of the sweep. Layout (every gap representable whatever the scale):
 *   A: x in [o - 2 hA, o],          y, z in [o - hA, o + hA]
 *   B: x in [o + g, o + g + 2 hB],  y, z in [o - hB, o + hB]
 * pose_gap: B's points start at x = o instead and B's pose translation is
 * g along x (in B's rotation). rot: both poses share one rotation R and a
 * translation, so the relative pose is the identity only up to rounding.
 * Expected: distance g (> 0) or depth min(-g, 2 min(hA, hB)) (g < 0), from
 * the rounded coordinates. Translation: A moves along d = hB (1, 0.3, 0.2)
 * (rotated by R for rot): oblique, but the contact stays on the x faces, so
 * tau = g / hB for either sign (both ways), and the forward query gives it
 * for g > 0 and in_contact (tau = 0) for an overlap. */
static void run_row(const char *label, double hA, double hB, double g, double o, int pose_gap, int rot) {
    int fails0 = tu_fail_count;
    ++g_rows;
    double a0 = o - 2 * hA, a1 = o, b0 = pose_gap ? o : o + g, b1 = b0 + 2 * hB;
    px_error ea, eb;
    memset(&eb, 0, sizeof eb);
    px_convex *A = box(a0, a1, o - hA, o + hA, &ea);
    px_convex *B = A ? box(b0, b1, o - hB, o + hB, &eb) : NULL;
    if (!isfinite(o) || !isfinite(b1)) {
        /* The coordinates themselves overflow (1e300 x 1e14): not a range
         * question, the input is not finite. */
        CHECK(!A && ea.code == PX_ERR_NON_FINITE && ea.message[0], "%s: non-finite coordinates: %s '%s'",
              label, px_status_string(ea.code), ea.message);
        goto done;
    }
    if (!size_in_range(hA)) {
        CHECK(!A && ea.code == PX_ERR_RANGE && ea.message[0],
              "%s: A of half-size %g is outside the range: got %s '%s', want PX_ERR_RANGE", label, hA,
              px_status_string(ea.code), ea.message);
    } else {
        CHECK(A && ea.code == PX_OK, "%s: A: %s '%s'", label, px_status_string(ea.code), ea.message);
    }
    if (A && !size_in_range(hB)) {
        CHECK(!B && eb.code == PX_ERR_RANGE && eb.message[0],
              "%s: B of half-size %g is outside the range: got %s '%s', want PX_ERR_RANGE", label, hB,
              px_status_string(eb.code), eb.message);
    } else if (A) {
        CHECK(B && eb.code == PX_OK, "%s: B: %s '%s'", label, px_status_string(eb.code), eb.message);
    }
    if (!A || !B) goto done;
    /* Built (in range, or out of range and built anyway): the answers must
     * be right. */
    {
        px_error e;
        CHECK(px_convex_validate(A, &e) == PX_OK, "%s: validate A: %s", label, e.message);
        CHECK(px_convex_validate(B, &e) == PX_OK, "%s: validate B: %s", label, e.message);
    }
    px_pose pa = px_pose_identity(), pb = px_pose_identity();
    if (rot) {
        double q[4] = {0.9, 0.3, -0.2, 0.25}, t[3] = {0.5 * hA, -0.25 * hA, 0.125 * hA};
        CHECK(px_pose_from_quat(q, t, &pa) == PX_OK, "%s: pose", label);
        pb = pa;
    }
    if (pose_gap) {
        px_pose r = pb;
        r.t.x = r.t.y = r.t.z = 0;
        px_vec3 d = {g, 0, 0}, rd = px_pose_apply(&r, d);
        pb.t.x += rd.x, pb.t.y += rd.y, pb.t.z += rd.z;
    }
    double gap = pose_gap ? g : b0 - a1; /* exact: both near o (Sterbenz) */
    px_bounds ba, bb;
    CHECK(px_convex_bounds(A, &pa, &ba) == PX_OK && px_convex_bounds(B, &pb, &bb) == PX_OK, "%s: bounds",
          label);
    double band = 64 * DBL_EPSILON * (ba.radius + bb.radius + len3(sub3(ba.center, bb.center)));
    CHECK(isfinite(band), "%s: band %g from bounds", label, band);
    /* rot: R o is rounded in each pose, so the input fixes the relative pose
     * only to about eps |o| (0.02 s at o = 1e14 s); that much more is
     * allowed, on the decision and on the values. */
    double slack = rot ? 8 * DBL_EPSILON * fabs(o) : 0.0;
    double hmin = hA < hB ? hA : hB;
    double depth = gap < 0 ? (-gap < 2 * hmin ? -gap : 2 * hmin) : 0;
    int want = gap > band + slack ? 0 : gap < -(band + slack) ? 1 : -1; /* -1: either */
    if (want < 0) ++g_rows_band;
    double tol_d = fmax(REL * fabs(gap), band) + slack, tol_D = fmax(REL * depth, band) + slack;

    for (uint32_t m = 0; m < 3; ++m)
        for (int sgn = 0; sgn < 2; ++sgn) {
            px_query_options opt;
            memset(&opt, 0, sizeof opt);
            opt.method = m;
            opt.flags = sgn ? PX_QUERY_SIGNED : 0;
            px_distance_result r;
            px_status st = px_distance(A, &pa, B, &pb, &opt, NULL, &r);
            const char *sg = sgn ? " signed" : "";
            CHECK(st == PX_OK, "%s: %s%s: %s", label, k_method[m], sg, px_status_string(st));
            if (st != PX_OK) continue;
            int fin = isfinite(r.distance) && isfinite(r.signed_distance) && finite3(r.point_a) &&
                      finite3(r.point_b) && finite3(r.normal);
            CHECK(fin, "%s: %s%s: non-finite output with PX_OK: distance %g, signed %g", label, k_method[m],
                  sg, r.distance, r.signed_distance);
            if (!fin) continue;
            int ok;
            if (want == 0)
                ok = !r.intersecting && fabs(r.distance - gap) <= tol_d && r.signed_distance == r.distance;
            else if (want == 1)
                ok = r.intersecting && r.distance == 0.0 &&
                     (sgn ? fabs(-r.signed_distance - depth) <= tol_D : r.signed_distance == 0.0);
            else /* in the band: touching (at most the band deep), or the small distance */
                ok = r.intersecting
                         ? r.distance == 0.0 && (sgn ? r.signed_distance <= 0.0 && -r.signed_distance <= tol_D
                                                     : r.signed_distance == 0.0)
                         : fabs(r.distance - gap) <= tol_d && r.signed_distance == r.distance;
            CHECK(
                ok,
                "%s: %s%s: intersecting %d distance %.17g signed %.17g; want %s gap %.17g (depth %.17g, band "
                "%.3g)",
                label, k_method[m], sg, r.intersecting, r.distance, r.signed_distance,
                want == 0   ? "separated"
                : want == 1 ? "intersecting"
                            : "either (in the band)",
                gap, depth, band);
        }

    px_intersect_result ir;
    px_status st = px_intersect(A, &pa, B, &pb, NULL, NULL, &ir);
    CHECK(st == PX_OK, "%s: px_intersect: %s", label, px_status_string(st));
    if (st == PX_OK && want >= 0)
        CHECK(ir.intersecting == want, "%s: px_intersect says %d, want %d (gap %.17g)", label,
              ir.intersecting, want, gap);

    px_vec3 dir = {hB, 0.3 * hB, 0.2 * hB};
    if (rot) {
        px_pose r = pa;
        r.t.x = r.t.y = r.t.z = 0;
        dir = px_pose_apply(&r, dir);
    }
    for (int both = 0; both < 2; ++both) {
        px_query_options opt;
        memset(&opt, 0, sizeof opt);
        opt.flags = both ? PX_QUERY_BOTH_WAYS : 0;
        px_translate_result tr;
        const char *how = both ? "both ways" : "forward";
        st = px_translate(A, &pa, B, &pb, dir, &opt, NULL, &tr);
        CHECK(st == PX_OK, "%s: px_translate %s: %s", label, how, px_status_string(st));
        if (st != PX_OK) continue;
        int fin = isfinite(tr.tau) && finite3(tr.point_a) && finite3(tr.point_b) && finite3(tr.normal);
        CHECK(fin && tr.hit, "%s: px_translate %s: hit %d tau %g", label, how, tr.hit, tr.tau);
        if (!fin || !tr.hit) continue;
        /* |tau - g / hB| hB, without forming tau hB (1e300 x 1e300). */
        double err = fabs(tr.tau - gap / hB) * hB;
        int ok;
        if (both)
            ok = err <= tol_d;
        else if (want == 0)
            ok = !tr.in_contact && err <= tol_d;
        else if (want == 1)
            ok = tr.in_contact && tr.tau == 0.0;
        else
            ok = tr.in_contact ? tr.tau == 0.0 : tr.tau >= 0.0 && err <= tol_d;
        CHECK(ok, "%s: px_translate %s: in_contact %d tau %.17g, want %.17g", label, how, tr.in_contact,
              tr.tau, want == 1 && !both ? 0.0 : gap / hB);
    }
done:
    px_convex_destroy(A);
    px_convex_destroy(B);
    if (tu_fail_count != fails0) {
        ++g_rows_wrong;
        fprintf(stderr, "row wrong: %s\n", label);
    }
}

static const double k_scales[] = {1e-308, 1e-300, 1e-200, 1e-160, 1e-150, 1e-100,
                                  1,      1e100,  1e150,  1e160,  1e200,  1e300};
#define NSCALES (int)(sizeof k_scales / sizeof k_scales[0])
static const double k_gaps[] = {0.5, 2.0, -0.5}; /* times s; -0.5: overlap */

/* Equal boxes (half-size s), identity poses, gaps +0.5 s, +2 s, -0.5 s, the
 * body coordinates offset by 0, 1e6 s and 1e14 s. Before the fix:
 *   - s <= 1e-308 (subnormal sizes): Lin-Canny reported boxes 0.5 s and 2 s
 *     apart touching and GJK gave distance 0; the hybrid returned NaN with
 *     PX_OK (offset 0); the translation gave tau = 1.117 for 0.5; validate
 *     found non-unit face normals. Now PX_ERR_RANGE.
 *   - s = 1e-300 .. 1e-200: the same without the NaN: Lin-Canny touching,
 *     GJK distance 0, tau 1.226 for 0.5 (offset 0), non-unit normals.
 *   - s = 1e-160: Lin-Canny and GJK distances off by 5.6e-6 relative
 *     (4.99997e-161 for 5e-161); validate found inward face normals.
 *   - s = 1e-150 .. 1e150, offsets 0 and 1e6 s: right (the control rows).
 *   - s = 1e160 .. 1e300: Lin-Canny returned +inf for boxes one half-size
 *     apart (and two); the translation gave tau = -0.4425 for 0.5, 0.885
 *     for 2, -1.327 for -0.5; validate found inward normals.
 *   - offset 1e14 s, every s: unit boxes 0.5 apart at coordinates 1e14
 *     were reported touching by Lin-Canny, GJK and px_intersect (the
 *     contact band followed the coordinates, 16 eps x 1e14 = 0.02 s), the
 *     translation gave tau = -0.445 for 0.5, and the signed distance of
 *     the 0.5 s overlap was 0 for every method (the depth was lost).
 *   - s = 1e300 at offset 1e14 s: the coordinates overflow to inf
 *     (PX_ERR_NON_FINITE, before and after). */
static void sweep_equal(void) {
    const double offs[] = {0, 1e6, 1e14};
    const char *offname[] = {"0", "1e6s", "1e14s"};
    char label[128];
    for (int oi = 0; oi < 3; ++oi)
        for (int i = 0; i < NSCALES; ++i)
            for (int j = 0; j < 3; ++j) {
                double s = k_scales[i];
                snprintf(label, sizeof label, "s=%.0e g=%+.1fs off=%s", s, k_gaps[j], offname[oi]);
                run_row(label, s, s, k_gaps[j] * s, offs[oi] * s, 0, 0);
            }
}

/* Equal boxes 0.5 s apart, both poses one rotation R (unit quaternion
 * (0.9, 0.3, -0.2, 0.25) normalised) and translation (0.5, -0.25, 0.125) s,
 * offsets 0, 1e6 s, 1e14 s. Before the fix, as the identity rows: Lin-Canny
 * touching and GJK distance 0 for s <= 1e-200, tau 1.117 .. 1.457 for 0.5
 * (offset 0), distances off by 5.6e-6 relative at 1e-160, +inf from
 * Lin-Canny and tau -0.4425 at 1e160 .. 1e300; and at offset 1e14 s every s
 * was touching for Lin-Canny, GJK and px_intersect, with tau -0.41 .. -0.43
 * for 0.5. */
static void sweep_rotated(void) {
    const double offs[] = {0, 1e6, 1e14};
    const char *offname[] = {"0", "1e6s", "1e14s"};
    char label[128];
    for (int oi = 0; oi < 3; ++oi)
        for (int i = 0; i < NSCALES; ++i) {
            double s = k_scales[i];
            snprintf(label, sizeof label, "rot s=%.0e g=+0.5s off=%s", s, offname[oi]);
            run_row(label, s, s, 0.5 * s, offs[oi] * s, 0, 1);
        }
}

/* Equal boxes with their points about the origin and the gap (+0.5 s, +2 s,
 * -0.5 s) in B's pose translation. Before the fix: the hybrid returned NaN
 * with PX_OK on subnormal boxes (s = 1e-308); Lin-Canny touching and GJK
 * distance 0 up to s = 1e-200, tau 1.117 .. 2.444 where 0.5 or 2 was
 * right; distances off by 5.6e-6 relative at 1e-160; +inf from Lin-Canny
 * and tau -0.4425 at 1e160 .. 1e300; validate failing at both ends. */
static void sweep_pose_gap(void) {
    char label[128];
    for (int i = 0; i < NSCALES; ++i)
        for (int j = 0; j < 3; ++j) {
            double s = k_scales[i];
            snprintf(label, sizeof label, "pose s=%.0e g=%+.1fs", s, k_gaps[j]);
            run_row(label, s, s, k_gaps[j] * s, 0.0, 1, 0);
        }
}

/* Mixed sizes: a unit box and a box of half-size s, s apart (in B's pose),
 * either way round. Before the fix: the small box failed validation
 * (non-unit normals at s <= 1e-200, inward ones at 1e-160); with the large
 * box at 1e160 .. 1e300 Lin-Canny reported the pair touching and the
 * translation gave tau 0.4425 for 1 (0.4425 s for s). The gap is inside the
 * band for s <= 1e-100: both answers are accepted there. */
static void sweep_mixed(void) {
    char label[128];
    for (int i = 0; i < NSCALES; ++i) {
        double s = k_scales[i];
        snprintf(label, sizeof label, "mixed 1 vs s=%.0e g=s", s);
        run_row(label, 1.0, s, s, 0.0, 1, 0);
        snprintf(label, sizeof label, "mixed s=%.0e vs 1 g=s", s);
        run_row(label, s, 1.0, s, 0.0, 1, 0);
    }
}

/* Deeper subnormal sizes, s = 1e-310, 1e-315, 1e-320, gaps +0.5 s, +2 s,
 * -0.5 s, gap in the points or in B's pose. Before the fix: every distance
 * method called the separated pairs touching, the hybrid returned NaN with
 * PX_OK, the signed distance of the overlap was 0, the translation failed
 * with PX_ERR_NON_FINITE. Now PX_ERR_RANGE. */
static void sweep_subnormal(void) {
    const double sub[] = {1e-310, 1e-315, 1e-320};
    char label[128];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            double s = sub[i];
            snprintf(label, sizeof label, "s=%.0e g=%+.1fs off=0", s, k_gaps[j]);
            run_row(label, s, s, k_gaps[j] * s, 0.0, 0, 0);
            snprintf(label, sizeof label, "pose s=%.0e g=%+.1fs", s, k_gaps[j]);
            run_row(label, s, s, k_gaps[j] * s, 0.0, 1, 0);
        }
}

/* The hybrid's band at large offsets: gap 0.25 s at offset 1e14 s and 0.5 s
 * at 1e15 s, s = 1e-308, 1e-160, 1, 1e160. Before the fix every method,
 * the hybrid included, and px_intersect reported these pairs touching; the
 * translation gave tau -0.37 .. -0.68; Lin-Canny gave +inf at 1e160. */
static void sweep_far(void) {
    char label[128];
    for (int i = 0; i < NSCALES; i += 3) {
        double s = k_scales[i];
        snprintf(label, sizeof label, "s=%.0e g=+0.25s off=1e14s", s);
        run_row(label, s, s, 0.25 * s, 1e14 * s, 0, 0);
        snprintf(label, sizeof label, "s=%.0e g=+0.5s off=1e15s", s);
        run_row(label, s, s, 0.5 * s, 1e15 * s, 0, 0);
    }
}

/* px_pose_from_quat with |q| = 1e-308 .. 1e300 (q = scale x (0.9, 0.3,
 * -0.2, 0.25)): the rotation of the unit quaternion within 1e-15. Before
 * the fix |q|^2 underflowed or overflowed: NaN rotations (PX_ERR_NON_FINITE
 * from px_pose_check) at 1e-200 and below and at 1e155 and above, a
 * rotation off by 2.6e-5 at 1e-160 (PX_ERR_INVALID_POSE) and by 3.4e-15 at
 * 1e-155. */
static void quat_rows(void) {
    const double qs[] = {1e-308, 1e-300, 1e-200, 1e-160, 1e-155, 1e-150,
                         1,      1e150,  1e155,  1e160,  1e200,  1e300};
    const double q1[4] = {0.9, 0.3, -0.2, 0.25}, t[3] = {0, 0, 0};
    px_pose ref;
    CHECK(px_pose_from_quat(q1, t, &ref) == PX_OK, "unit quaternion");
    for (size_t i = 0; i < sizeof qs / sizeof qs[0]; ++i) {
        int fails0 = tu_fail_count;
        ++g_rows;
        double s = qs[i], q[4] = {q1[0] * s, q1[1] * s, q1[2] * s, q1[3] * s};
        px_pose p;
        px_status st = px_pose_from_quat(q, t, &p);
        double err = 0;
        int fin = 1;
        for (int k = 0; k < 9; ++k) fin = fin && isfinite(p.r[k]);
        for (int k = 0; k < 9 && fin; ++k) err = fmax(err, fabs(p.r[k] - ref.r[k]));
        CHECK(st == PX_OK && fin && err < 1e-15 && px_pose_check(&p, NULL) == PX_OK,
              "quaternion of norm %g: %s, max |R - R(unit q)| = %.3g%s", s, px_status_string(st), err,
              fin ? "" : " (not finite)");
        if (tu_fail_count != fails0) {
            ++g_rows_wrong;
            fprintf(stderr, "row wrong: quat scale %g\n", s);
        }
    }
}

/* The range's edges with a margin either way (whichever extent the library
 * calls the size): boxes of half-size 2^-1000 and 2^999 are built, 2^-1002
 * and 2^1001 give PX_ERR_RANGE with a message. Pairs: unit boxes whose poses
 * are 2^1020 apart get the distance; 2^1022 apart (sizes plus distance
 * above 2^1021) get PX_ERR_RANGE from every query, with the result
 * zeroed. */
static void range_edges(void) {
    const double in[] = {0x1p-1000, 0x1p999}, out[] = {0x1p-1002, 0x1p1001};
    px_error err;
    for (int i = 0; i < 2; ++i) {
        px_convex *c = box(-in[i], in[i], -in[i], in[i], &err);
        CHECK(c && err.code == PX_OK, "half-size %a: %s '%s'", in[i], px_status_string(err.code),
              err.message);
        if (c) CHECK(px_convex_validate(c, &err) == PX_OK, "half-size %a: validate: %s", in[i], err.message);
        px_convex_destroy(c);
        c = box(-out[i], out[i], -out[i], out[i], &err);
        CHECK(!c && err.code == PX_ERR_RANGE && err.message[0], "half-size %a: %s '%s', want PX_ERR_RANGE",
              out[i], px_status_string(err.code), err.message);
        px_convex_destroy(c);
    }
    px_convex *u = box(-1, 1, -1, 1, &err);
    CHECK(u != NULL, "unit box");
    if (!u) return;
    for (int far = 0; far < 2; ++far) {
        double h = far ? 0x1p1021 : 0x1p1019; /* poses at -h and +h */
        px_pose pa = px_pose_identity(), pb = px_pose_identity();
        pa.t.x = -h, pb.t.x = h;
        px_status want = far ? PX_ERR_RANGE : PX_OK;
        double dist = 2 * h - 2; /* rounds to 2h */
        for (uint32_t m = 0; m < 3; ++m)
            for (int sgn = 0; sgn < 2; ++sgn) {
                px_query_options opt;
                memset(&opt, 0, sizeof opt);
                opt.method = m, opt.flags = sgn ? PX_QUERY_SIGNED : 0;
                px_distance_result r;
                px_status st = px_distance(u, &pa, u, &pb, &opt, NULL, &r);
                CHECK(st == want, "poses %a apart, %s: %s", 2 * h, k_method[m], px_status_string(st));
                if (st == PX_OK)
                    CHECK(!r.intersecting && fabs(r.distance - dist) <= 1e-12 * dist &&
                              r.signed_distance == r.distance,
                          "poses %a apart, %s: distance %a", 2 * h, k_method[m], r.distance);
                else
                    CHECK(r.distance == 0.0 && r.signed_distance == 0.0 && !r.intersecting,
                          "poses %a apart, %s: result not zeroed", 2 * h, k_method[m]);
            }
        px_intersect_result ir;
        px_status st = px_intersect(u, &pa, u, &pb, NULL, NULL, &ir);
        CHECK(st == want && !ir.intersecting, "poses %a apart: px_intersect %s %d", 2 * h,
              px_status_string(st), ir.intersecting);
        px_vec3 dir = {1, 0, 0};
        px_translate_result tr;
        st = px_translate(u, &pa, u, &pb, dir, NULL, NULL, &tr);
        CHECK(st == want && (far ? !tr.hit && tr.tau == 0.0 : tr.hit && fabs(tr.tau - dist) <= 1e-12 * dist),
              "poses %a apart: px_translate %s hit %d tau %a", 2 * h, px_status_string(st), tr.hit, tr.tau);
    }
    px_convex_destroy(u);
}

/* px_translate's direction may have any non-zero length; tau is in units of
 * it. Unit cubes (identity poses) at gaps 0.25 and 0.9 bands (touching for
 * px_distance: query.h's band is 64 eps (sqrt3 + 1) here), 4 bands and 0.5,
 * forward along (2^j, 0, 0), j = -40 .. 40: in_contact must be what
 * px_distance decides (query.h, px_translate_result.in_contact) for every
 * j, and tau 2^j the same bits for every j. Found while writing this test
 * (main at a35985f, fixed in src/narrow/query.c with it): the forward
 * query compared the distance travelled and the gap now, both lengths,
 * with the band after scaling them by 2^-ilogb|d|, so for |d| < 1 pairs
 * inside the band got in_contact 0 and tau > 0 while px_distance calls
 * them touching, and for |d| >= 2 every hit also ran the distance query at
 * tau = 0 (same answers, more iterations: part 5 saw the diagnostics of
 * the forward translation change with 2^k). */
static void translate_direction_length(void) {
    const double band = 64 * DBL_EPSILON * (sqrt(3.0) + 1.0);
    const double gaps[] = {0.25 * band, 0.9 * band, 4 * band, 0.5};
    px_error err;
    px_convex *a = box(-1, 0, -0.5, 0.5, &err);
    px_pose p = px_pose_identity();
    for (int g = 0; g < 4; ++g) {
        px_convex *b = box(gaps[g], gaps[g] + 1, -0.5, 0.5, &err);
        CHECK(a && b, "cubes");
        if (!a || !b) {
            px_convex_destroy(b);
            continue;
        }
        double gap = gaps[g]; /* exact: the boxes' x faces are at 0 and gap */
        px_distance_result r;
        CHECK(px_distance(a, &p, b, &p, NULL, NULL, &r) == PX_OK, "distance");
        CHECK(r.intersecting == (gap <= band), "gap %.3g (band %.3g): px_distance intersecting %d", gap, band,
              r.intersecting);
        px_vec3 d1 = {1, 0, 0};
        px_translate_result ref;
        CHECK(px_translate(a, &p, b, &p, d1, NULL, NULL, &ref) == PX_OK && ref.hit, "gap %.3g, |d| = 1", gap);
        CHECK(ref.in_contact == r.intersecting && (ref.in_contact ? ref.tau == 0.0 : ref.tau > 0.0),
              "gap %.3g (band %.3g), |d| = 1: in_contact %d tau %.3g, but px_distance says intersecting %d",
              gap, band, ref.in_contact, ref.tau, r.intersecting);
        for (int j = -40; j <= 40; j += 8) {
            if (j == 0) continue;
            px_vec3 d = {ldexp(1.0, j), 0, 0};
            px_translate_result t;
            px_status st = px_translate(a, &p, b, &p, d, NULL, NULL, &t);
            CHECK(st == PX_OK && t.hit, "gap %.3g, |d| = 2^%d: %s hit %d", gap, j, px_status_string(st),
                  t.hit);
            CHECK(t.in_contact == ref.in_contact && ldexp(t.tau, j) == ref.tau,
                  "gap %.3g (band %.3g), |d| = 2^%d: in_contact %d, tau |d| %.17g; at |d| = 1: %d, %.17g",
                  gap, band, j, t.in_contact, ldexp(t.tau, j), ref.in_contact, ref.tau);
        }
        px_convex_destroy(b);
    }
    px_convex_destroy(a);
}

/* ---- Scale covariance. ---- */

#define NV 200
/* Queries: 0-5 distance (Lin-Canny, GJK, hybrid; unsigned, signed), 6
 * px_intersect, 7 px_translate forward along d, 8 both ways along d, 9
 * forward along -d. */
#define NQ 10
static const char *const k_query[NQ] = {
    "Lin-Canny",     "Lin-Canny signed", "GJK",          "GJK signed",          "hybrid",
    "hybrid signed", "intersect",        "translate +d", "translate both ways", "translate -d"};
typedef struct outputs {
    px_status st[NQ];
    int flag[NQ], contact[NQ];
    double len[NQ][8]; /* lengths, 2^k times: distances, gap, points */
    double tau[NQ];    /* scale-free (the direction is scaled too) */
    px_vec3 normal[NQ];
    px_feature fa[NQ], fb[NQ];
    px_diagnostics diag[NQ];
} outputs;

static void run_queries(const px_convex *A, const px_convex *B, const px_pose *pa, const px_pose *pb,
                        px_vec3 dir, outputs *o) {
    memset(o, 0, sizeof *o);
    for (uint32_t m = 0; m < 3; ++m)
        for (int sg = 0; sg < 2; ++sg) {
            px_query_options opt;
            memset(&opt, 0, sizeof opt);
            opt.method = m, opt.flags = sg ? PX_QUERY_SIGNED : 0;
            px_distance_result r;
            int q = 2 * (int)m + sg;
            o->st[q] = px_distance(A, pa, B, pb, &opt, NULL, &r);
            o->flag[q] = r.intersecting;
            double v[8] = {r.distance,  r.signed_distance, r.point_a.x, r.point_a.y,
                           r.point_a.z, r.point_b.x,       r.point_b.y, r.point_b.z};
            memcpy(o->len[q], v, sizeof v);
            o->normal[q] = r.normal, o->fa[q] = r.feature_a, o->fb[q] = r.feature_b, o->diag[q] = r.diag;
        }
    px_intersect_result ir;
    o->st[6] = px_intersect(A, pa, B, pb, NULL, NULL, &ir);
    o->flag[6] = ir.intersecting, o->diag[6] = ir.diag;
    for (int k = 0; k < 3; ++k) {
        px_query_options opt;
        memset(&opt, 0, sizeof opt);
        opt.flags = k == 1 ? PX_QUERY_BOTH_WAYS : 0;
        px_vec3 d = dir;
        if (k == 2) d.x = -d.x, d.y = -d.y, d.z = -d.z;
        px_translate_result t;
        int q = 7 + k;
        o->st[q] = px_translate(A, pa, B, pb, d, &opt, NULL, &t);
        o->flag[q] = t.hit, o->contact[q] = t.in_contact, o->tau[q] = t.tau;
        double v[8] = {t.gap,       0,           t.point_a.x, t.point_a.y,
                       t.point_a.z, t.point_b.x, t.point_b.y, t.point_b.z};
        memcpy(o->len[q], v, sizeof v);
        o->normal[q] = t.normal, o->fa[q] = t.feature_a, o->fb[q] = t.feature_b, o->diag[q] = t.diag;
    }
}

static int same_feature(px_feature a, px_feature b) {
    return a.type == b.type && a.index == b.index && a.piece == b.piece;
}

/* Compares one scaled run with the reference (k = 0) and counts the
 * difference of the unit normals. */
static void compare_scaled(int p, int k, const outputs *res, const outputs *ref, double *worst_normal) {
    for (int q = 0; q < NQ; ++q) {
        const char *qn = k_query[q];
        CHECK(res->st[q] == ref->st[q] && res->flag[q] == ref->flag[q] && res->contact[q] == ref->contact[q],
              "pair %d k %d %s: status %s flag %d in_contact %d, at k = 0 %s %d %d", p, k, qn,
              px_status_string(res->st[q]), res->flag[q], res->contact[q], px_status_string(ref->st[q]),
              ref->flag[q], ref->contact[q]);
        for (int i = 0; i < 8; ++i)
            CHECK(res->len[q][i] == ldexp(ref->len[q][i], k),
                  "pair %d k %d %s: length %d is %a, 2^k x k = 0: %a", p, k, qn, i, res->len[q][i],
                  ldexp(ref->len[q][i], k));
        CHECK(res->tau[q] == ref->tau[q], "pair %d k %d %s: tau %a, at k = 0 %a", p, k, qn, res->tau[q],
              ref->tau[q]);
        double dn =
            fmax(fabs(res->normal[q].x - ref->normal[q].x),
                 fmax(fabs(res->normal[q].y - ref->normal[q].y), fabs(res->normal[q].z - ref->normal[q].z)));
        if (dn > *worst_normal) *worst_normal = dn;
        CHECK(dn <= 4 * DBL_EPSILON, "pair %d k %d %s: normal differs from k = 0 by %.3g", p, k, qn, dn);
        CHECK(same_feature(res->fa[q], ref->fa[q]) && same_feature(res->fb[q], ref->fb[q]),
              "pair %d k %d %s: features (%u %u) (%u %u), at k = 0 (%u %u) (%u %u)", p, k, qn,
              res->fa[q].type, res->fa[q].index, res->fb[q].type, res->fb[q].index, ref->fa[q].type,
              ref->fa[q].index, ref->fb[q].type, ref->fb[q].index);
        CHECK(res->diag[q].iterations == ref->diag[q].iterations &&
                  res->diag[q].fallbacks == ref->diag[q].fallbacks &&
                  res->diag[q].quality == ref->diag[q].quality,
              "pair %d k %d %s: diagnostics (iterations %u, fallbacks %u, quality %u), at k = 0 (%u, %u, %u)",
              p, k, qn, res->diag[q].iterations, res->diag[q].fallbacks, res->diag[q].quality,
              ref->diag[q].iterations, ref->diag[q].fallbacks, ref->diag[q].quality);
    }
}

/* Random round (200-point) and thin (40-point) ellipsoid hulls about their
 * frame's origin (gen/px_gen.h, a fixed seed), random rotations, separations 0.05 .. 2.5 (overlaps
 * included), the whole input (points, translations, direction) scaled by
 * 2^k, exactly. Within the range every length is 2^k times the k = 0
 * output bit for bit, tau, flags, features and diagnostics are the same,
 * and unit normals agree within 4 eps (normalising at a power-of-two scale,
 * outside [2^-500, 2^500], rounds differently from the direct division: up
 * to a few ulps, seen at |k| >= 520). Outside the range px_convex_create
 * says PX_ERR_RANGE. Before the fix (the study's scalecov, 40 pairs): at
 * k >= 520 Lin-Canny's answers differed on every pair and GJK's, the
 * hybrid's and the translation's on many, with wrong flags and values
 * beyond 1e-9 of the size; likewise at k <= -520; validate failed on every
 * pair at |k| >= 520; nothing was rejected. */
static void scale_covariance(void) {
    static const int ks[] = {0,   -1010, -990, -960, -700, -520, -480, -100,
                             100, 480,   520,  700,  960,  1000, 1010};
    const int nk = (int)(sizeof ks / sizeof ks[0]);
    const int pairs = tu_sanitized() ? 4 : tu_scaled(16);
    static double pts_a[3 * NV], pts_b[3 * NV], sa[3 * NV], sb[3 * NV];
    long compared = 0, rejected = 0;
    double worst_normal = 0;
    pg_rng rng;
    pg_seed(&rng, 0x72616e6765ull); /* "range" */
    for (int p = 0; p < pairs; ++p) {
        int na = p % 2 ? 40 : NV, nb = p % 3 ? NV : 40;
        if (p % 2)
            pg_points_ellipsoid(&rng, (size_t)na, 1, 0.2, 0.05, pts_a);
        else
            pg_points_ellipsoid(&rng, (size_t)na, 1, 1, 1, pts_a);
        if (p % 3)
            pg_points_ellipsoid(&rng, (size_t)nb, 1, 1, 0.8, pts_b);
        else
            pg_points_ellipsoid(&rng, (size_t)nb, 1, 0.125, 0.5, pts_b);
        /* The hulls' sizes: max |coordinate| (centred on the origin, so
         * stored at origin 0); the k list assumes them in [0.5, 1]. */
        double ma = 0, mb = 0;
        for (int i = 0; i < 3 * na; ++i) ma = fmax(ma, fabs(pts_a[i]));
        for (int i = 0; i < 3 * nb; ++i) mb = fmax(mb, fabs(pts_b[i]));
        CHECK(ma >= 0.5 && ma <= 1 && mb >= 0.5 && mb <= 1, "pair %d: sizes %g, %g", p, ma, mb);
        double qa[4], qb[4], ta[3], tb[3];
        pg_quat_uniform(&rng, qa), pg_quat_uniform(&rng, qb);
        double sep = (p % 4 == 0) ? 0.3 : (p % 4 == 1) ? 1.2 : (p % 4 == 2) ? 2.5 : 0.05;
        for (int i = 0; i < 3; ++i) ta[i] = pg_range(&rng, -2, 2);
        px_vec3 u = pg_unit(&rng); /* B's centre from A's */
        tb[0] = ta[0] + sep * u.x, tb[1] = ta[1] + sep * u.y, tb[2] = ta[2] + sep * u.z;
        px_vec3 dir0 = {-u.x + 0.1, -u.y, -u.z + 0.05}; /* away from B: -dir0 approaches it */
        outputs ref, res;
        int have_ref = 0;
        for (int j = 0; j < nk; ++j) { /* ks[0] = 0: the reference first */
            int k = ks[j];
            for (int i = 0; i < 3 * na; ++i) sa[i] = ldexp(pts_a[i], k);
            for (int i = 0; i < 3 * nb; ++i) sb[i] = ldexp(pts_b[i], k);
            double tas[3], tbs[3];
            for (int i = 0; i < 3; ++i) tas[i] = ldexp(ta[i], k), tbs[i] = ldexp(tb[i], k);
            px_pose pa, pb;
            CHECK(px_pose_from_quat(qa, tas, &pa) == PX_OK && px_pose_from_quat(qb, tbs, &pb) == PX_OK,
                  "pair %d k %d: poses", p, k);
            px_error ea, eb;
            px_convex *A = create(sa, (size_t)na, &ea), *B = create(sb, (size_t)nb, &eb);
            int in_a = ldexp(ma, k) >= 0x1p-1000 && ldexp(ma, k) <= 0x1p1000;
            int in_b = ldexp(mb, k) >= 0x1p-1000 && ldexp(mb, k) <= 0x1p1000;
            CHECK(in_a ? A != NULL : !A && ea.code == PX_ERR_RANGE && ea.message[0],
                  "pair %d k %d: A (size %a): %s '%s'", p, k, ldexp(ma, k), px_status_string(ea.code),
                  ea.message);
            CHECK(in_b ? B != NULL : !B && eb.code == PX_ERR_RANGE && eb.message[0],
                  "pair %d k %d: B (size %a): %s '%s'", p, k, ldexp(mb, k), px_status_string(eb.code),
                  eb.message);
            if (!in_a || !in_b) ++rejected;
            if (A && B) {
                px_vec3 dir = {ldexp(dir0.x, k), ldexp(dir0.y, k), ldexp(dir0.z, k)};
                run_queries(A, B, &pa, &pb, dir, k == 0 ? &ref : &res);
                CHECK(px_convex_validate(A, NULL) == PX_OK && px_convex_validate(B, NULL) == PX_OK,
                      "pair %d k %d: validate", p, k);
                if (k == 0) {
                    have_ref = 1;
                    for (int q = 0; q < NQ; ++q)
                        CHECK(ref.st[q] == PX_OK, "pair %d k 0 %s: %s", p, k_query[q],
                              px_status_string(ref.st[q]));
                } else if (have_ref) {
                    ++compared;
                    compare_scaled(p, k, &res, &ref, &worst_normal);
                }
            }
            px_convex_destroy(A);
            px_convex_destroy(B);
        }
    }
    printf("scale covariance: %d pairs, %ld scaled runs compared with k = 0 (largest normal difference "
           "%.3g), %ld "
           "rejected as out of range\n",
           pairs, compared, worst_normal, rejected);
}

int main(void) {
    tu_init("test_range");
    double t0 = tu_now();
    sweep_equal();
    sweep_rotated();
    sweep_pose_gap();
    sweep_mixed();
    sweep_subnormal();
    sweep_far();
    quat_rows();
    printf("range sweep: %d of %d rows wrong (%d rows with the gap inside the contact band)\n", g_rows_wrong,
           g_rows, g_rows_band);
    range_edges();
    translate_direction_length();
    scale_covariance();
    printf("%d polytopes built with the floating-point traps on\n", g_created);
    printf("time %.1f s\n", tu_now() - t0);
    return tu_finish();
}
