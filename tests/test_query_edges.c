/* Edge cases of the issue-4 queries found by a review of the code, one
 * function each, each reproduced from the reviewer's inputs:
 * - a warm px_translation whose cached hint misled its stall tests into a
 *   hit where the line misses (and random direction changes on one cache);
 * - px_intersect calling "intersecting" a pair separated by 1e-8 (boxes
 *   tilted by 1e-9..1e-4 rad near face contact);
 * - EPA's budget on deep overlaps of near-concentric round bodies: the
 *   answer must still separate the pair exactly when applied;
 * - A - B flat within rounding (thin plates): no point at the pose origins;
 * - subnormal and overflowing translation directions, poses whose relative
 *   transform overflows: a status, never NaN. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "access.h"
#include "math/vec3.h"
#include "narrow/narrow.h"
#include "oracle_sat.h"
#include "proxima/proxima.h"
#include "px_gen.h"
#include "test_util.h"

static px_convex *box_at(double cx, double cy, double cz, double hx, double hy, double hz) {
    double p[24];
    pg_box(hx, hy, hz, p);
    for (int i = 0; i < 8; ++i) p[3 * i] += cx, p[3 * i + 1] += cy, p[3 * i + 2] += cz;
    return px_convex_create(p, 8, NULL, NULL);
}

static px_pose at(double x, double y, double z) {
    px_pose p = px_pose_identity();
    p.t = pxi_v(x, y, z);
    return p;
}

/* Warm translation must agree with cold on hit/miss and tau, whatever the
 * cache saw before (the reviewer's pair, then random direction changes). */
static void test_warm_translation_hint(void) {
    px_convex *a = box_at(0, 0, 0, 1, 1, 1), *b = box_at(0, 0, 0, 1, 1, 1);
    px_pose pa = px_pose_identity(), pb = at(1.9623438693421853, 0.18832055771810283, 3.0350363747229396);
    px_vec3 d0 = {-0.35896571893865292, 0.62651439771320938, -0.6918260779161991};
    px_vec3 d1 = {-0.99359547034384488, 0.039608627144730291, -0.10582626312926095};
    px_pair_cache c;
    memset(&c, 0, sizeof c);
    px_translate_result r0, rw, rc;
    px_translate(a, &pa, b, &pb, d0, &tu_both_ways, &c, &r0);
    px_translate(a, &pa, b, &pb, d1, &tu_both_ways, &c, &rw);
    px_translate(a, &pa, b, &pb, d1, &tu_both_ways, NULL, &rc);
    CHECK(r0.hit && !rc.hit && !rw.hit && fabs(rw.gap - rc.gap) <= 1e-12,
          "reviewer's pair: first hit %d, warm hit %d gap %.17g, cold hit %d gap %.17g", r0.hit, rw.hit,
          rw.gap, rc.hit, rc.gap);
    /* Random directions on one cache, several pairs of small hulls. */
    pg_rng rng;
    pg_seed(&rng, 4242);
    double xyz[3 * 40];
    int bad = 0, n = 0;
    for (int pair = 0; pair < 20; ++pair) {
        pg_points_ball(&rng, 12 + pair, 1.0, xyz);
        px_convex *p = px_convex_create(xyz, (size_t)(12 + pair), NULL, NULL);
        pg_points_ball(&rng, 30 - pair, 0.7, xyz);
        px_convex *q = px_convex_create(xyz, (size_t)(30 - pair), NULL, NULL);
        if (!p || !q) continue;
        px_pose pp = pg_pose_random(&rng, 0.0), pq = pg_pose_random(&rng, 3.0);
        memset(&c, 0, sizeof c);
        for (int k = 0; k < tu_scaled(100); ++k, ++n) {
            px_vec3 d = pg_unit(&rng);
            px_translate_result w, cold;
            px_translate(p, &pp, q, &pq, d, &tu_both_ways, &c, &w);
            px_translate(p, &pp, q, &pq, d, &tu_both_ways, NULL, &cold);
            double size = pxi_len(pxi_sub(pp.t, pq.t)) + 2.0;
            int same = w.hit == cold.hit && (!w.hit || fabs(w.tau - cold.tau) <= 1e-9 * size) &&
                       (w.hit || fabs(w.gap - cold.gap) <= 1e-9 * size);
            if (!same && bad++ < 5)
                CHECK(0, "pair %d step %d: warm hit %d tau %.17g gap %.3g, cold hit %d tau %.17g gap %.3g",
                      pair, k, w.hit, w.tau, w.gap, cold.hit, cold.tau, cold.gap);
        }
        px_convex_destroy(p);
        px_convex_destroy(q);
    }
    CHECK(bad == 0, "%d of %d warm translations differ from cold", bad, n);
    px_convex_destroy(a);
    px_convex_destroy(b);
}

/* px_intersect near face contact with tiny tilts: must agree with the
 * distance query outside a 1e-12 band. */
static void test_intersect_near_contact(void) {
    px_convex *a = box_at(0, 0, 0, 1, 1, 1), *b = box_at(0, 0, 0, 1, 1, 1);
    int wrong = 0, n = 0;
    for (int e = 4; e <= 12; ++e)
        for (int k = 1; k <= 9; ++k)
            for (int gi = 6; gi <= 11; ++gi, ++n) {
                double ang = k * pow(10.0, -e), gap = pow(10.0, -gi);
                px_pose pa = px_pose_identity(), pb = px_pose_identity();
                pg_rot_axis_angle(pxi_v(0.6, 0.8, 0), ang, pb.r);
                pb.t = pxi_v(0.3, 0.2, 2.0);
                px_distance_result r;
                px_distance(a, &pa, b, &pb, NULL, NULL, &r);
                pb.t.z += gap - r.distance;
                px_distance(a, &pa, b, &pb, NULL, NULL, &r);
                px_intersect_result ir;
                px_intersect(a, &pa, b, &pb, NULL, NULL, &ir);
                int in = ir.intersecting;
                if (r.distance > 1e-12 && in != 0 && wrong++ < 5)
                    CHECK(0, "tilt %g gap %g: distance %.3g but px_intersect says %d", ang, gap, r.distance,
                          in);
            }
    CHECK(wrong == 0, "px_intersect wrong on %d of %d near-contact poses", wrong, n);
    px_convex_destroy(a);
    px_convex_destroy(b);
}

/* Deep overlap of near-concentric spheres of 500 and 1,000 vertices: even
 * when EPA's budget runs out, moving B by the depth along the normal must
 * leave the pair exactly touching, and the depth must be within 1 % of the
 * SAT oracle. The budget path must be taken at least once here, flagged
 * PX_QUALITY_DEPTH_BUDGET and counted as a fallback, and its depth (exact
 * along the normal it reports, by a translation query) can be no smaller
 * than the SAT minimum over all normals. */
static void test_epa_deep_round(void) {
    int budget_paths = 0;
    pg_rng rng;
    pg_seed(&rng, 1);
    static double xyz[3 * 1000];
    for (int n = 500; n <= 1000; n += 500) {
        pg_points_sphere(&rng, (size_t)n, 1.0, xyz);
        px_convex *s = px_convex_create(xyz, (size_t)n, NULL, NULL);
        os_shape sh;
        if (!s || os_shape_init(&sh, s) != 0) continue;
        for (int off = 0; off < 3; ++off) {
            px_pose pa = px_pose_identity(), pb = at(0.01 * off, 0.0, 0.0);
            os_pen_result orc;
            os_penetration(&sh, &pa, &sh, &pb, &orc);
            for (int m = 0; m < 3; ++m) {
                px_query_options o;
                memset(&o, 0, sizeof o);
                o.method = (uint32_t)m;
                o.flags = PX_QUERY_SIGNED;
                px_distance_result r;
                px_status st = px_distance(s, &pa, s, &pb, &o, NULL, &r);
                double depth = -r.signed_distance;
                px_pose moved = pb;
                moved.t = pxi_madd(pb.t, r.normal, depth * (1.0 + 1e-12));
                px_distance_result after;
                px_distance(s, &pa, s, &moved, NULL, NULL, &after);
                CHECK(
                    st == PX_OK && isfinite(depth) && fabs(depth - orc.depth) <= 1e-2 * orc.depth &&
                        after.distance <= 1e-9 && fabs(pxi_len(r.normal) - 1.0) <= 1e-12,
                    "sphere %d method %d offset %d: depth %.17g oracle %.17g (fallbacks %u), distance after "
                    "the move %.3g",
                    n, m, off, depth, orc.depth, r.diag.fallbacks, after.distance);
                if (r.diag.quality & PX_QUALITY_DEPTH_BUDGET) {
                    budget_paths++;
                    CHECK(r.diag.fallbacks >= 1 && depth >= orc.depth * (1.0 - 1e-12),
                          "sphere %d method %d offset %d: budget answer with %u fallbacks, depth %.17g below "
                          "the "
                          "SAT minimum %.17g",
                          n, m, off, r.diag.fallbacks, depth, orc.depth);
                } else {
                    CHECK(fabs(depth - orc.depth) <= 1e-9 * orc.depth,
                          "sphere %d method %d offset %d: exact answer %.17g, SAT %.17g", n, m, off, depth,
                          orc.depth);
                }
            }
        }
        os_shape_free(&sh);
        px_convex_destroy(s);
    }
    CHECK(budget_paths > 0, "EPA's budget path was never taken: the test no longer covers it");
    printf("  EPA budget path taken %d times, flagged and checked against SAT\n", budget_paths);
}

/* Plates whose Minkowski difference is flat within rounding: the signed
 * answer is "touching" with a common point on both bodies, not the pose
 * origins. */
static void test_flat_difference(void) {
    px_convex *a = box_at(1e6, 1e6, 1e6, 1, 1, 5e-8), *b = box_at(1e6 + 0.5, 1e6 + 0.3, 1e6, 1, 1, 5e-8);
    px_pose id = px_pose_identity();
    for (int m = 0; m < 3 && a && b; ++m) {
        px_query_options o;
        memset(&o, 0, sizeof o);
        o.method = (uint32_t)m;
        o.flags = PX_QUERY_SIGNED;
        px_distance_result r;
        px_status st = px_distance(a, &id, b, &id, &o, NULL, &r);
        px_vec3 resid = pxi_sub(pxi_sub(r.point_b, r.point_a), pxi_scale(r.normal, r.signed_distance));
        CHECK(st == PX_OK && r.intersecting && fabs(r.point_a.x - 1e6) < 2.0 &&
                  fabs(r.point_b.z - 1e6) < 1.0 && pxi_max_abs(resid) <= 1e-9,
              "plates, method %d: point_a (%.17g %.17g %.17g), signed %.3g", m, r.point_a.x, r.point_a.y,
              r.point_a.z, r.signed_distance);
    }
    px_convex_destroy(a);
    px_convex_destroy(b);
}

/* Directions of subnormal length, tau beyond the double range, and poses
 * whose relative transform overflows: statuses, no NaN. */
static void test_extreme_numbers(void) {
    px_convex *a = box_at(0, 0, 0, 1, 1, 1), *b = box_at(0, 0, 0, 1, 1, 1);
    px_pose pa = px_pose_identity(), pb = at(5, 0, 0), far = at(1e10, 0, 0);
    px_translate_result t;
    px_pose near = at(2.01, 0, 0); /* gap 0.01: tau = 1e308 along a direction of 1e-310 */
    px_status st = px_translate(a, &pa, b, &near, pxi_v(1e-310, 0, 0), &tu_both_ways, NULL, &t);
    CHECK(st == PX_OK && t.hit && isfinite(t.tau) && fabs(t.tau * 1e-310 - 0.01) <= 1e-12 &&
              pxi_is_finite3(t.point_a),
          "subnormal direction: status %d hit %d tau %g", st, t.hit, t.tau);
    st = px_translate(a, &pa, b, &pb, pxi_v(4.9e-324, 0, 0), &tu_both_ways, NULL, &t);
    CHECK(st == PX_ERR_NON_FINITE && t.hit == 0 && t.tau == 0.0,
          "smallest subnormal direction: tau overflows, status %d tau %g", st, t.tau);
    st = px_translate(a, &pa, b, &far, pxi_v(1e-300, 0, 0), &tu_both_ways, NULL, &t);
    CHECK(st == PX_ERR_NON_FINITE, "tau = 1e310: status %d tau %g", st, t.tau);
    px_pose p1 = at(1.5e308, 0, 0), p2 = at(-1.5e308, 0, 0);
    px_distance_result r;
    for (uint32_t m = 0; m < 3; ++m) {
        px_query_options o;
        memset(&o, 0, sizeof o);
        o.method = m;
        CHECK(px_distance(a, &p1, b, &p2, &o, NULL, &r) == PX_ERR_NON_FINITE && r.distance == 0.0,
              "poses +-1.5e308, method %u: T_AB overflows", m);
    }
    px_intersect_result ir;
    memset(&ir, 0x5a, sizeof ir);
    CHECK(px_intersect(a, &p1, b, &p2, NULL, NULL, &ir) == PX_ERR_NON_FINITE && ir.intersecting == 0,
          "px_intersect at +-1.5e308");
    CHECK(px_translate(a, &p1, b, &p2, pxi_v(1, 0, 0), &tu_both_ways, NULL, &t) == PX_ERR_NON_FINITE,
          "px_translation at +-1.5e308");
    px_convex_destroy(a);
    px_convex_destroy(b);
}

/* The internal policy hook a hierarchy will use (narrow.h, pxi_policy):
 * with accept_bound, GJK's unproven answer at the rounding floor comes back
 * as it is, flagged PX_QUALITY_UNPROVEN, with no fallback; its gap must
 * bracket the true distance (Lin-Canny's): d_true in [d - gap, d], up to
 * rounding. Without it the same pair is finished by Lin-Canny (one
 * fallback). Pairs: near-contact placements, where GJK's duality gap stays
 * open (about half of them). */
static void test_accept_bound_policy(void) {
    pg_rng rng;
    pg_seed(&rng, 777);
    double xyz[3 * 60];
    int unproven = 0;
    for (int i = 0; i < 400; ++i) {
        size_t na = pg_shape(&rng, (pg_kind)pg_below(&rng, PG_KIND_COUNT), 40, 1.0, xyz);
        px_convex *a = px_convex_create(xyz, na, NULL, NULL);
        size_t nb = pg_shape(&rng, (pg_kind)pg_below(&rng, PG_KIND_COUNT), 40, 1.0, xyz);
        px_convex *b = px_convex_create(xyz, nb, NULL, NULL);
        if (!a || !b) {
            px_convex_destroy(a);
            px_convex_destroy(b);
            continue;
        }
        px_pose pb = pg_pose_random(&rng, 1.0), pa = pg_pose_around(&rng, pb.t, 1.0);
        px_query_options sg;
        memset(&sg, 0, sizeof sg);
        sg.flags = PX_QUERY_SIGNED;
        px_distance_result r;
        px_distance(a, &pa, b, &pb, &sg, NULL, &r);
        double gap = pow(10.0, pg_range(&rng, -14.0, -9.0));
        pa.t = pxi_madd(pa.t, r.normal, r.signed_distance - gap);
        px_pose t_ab =
            pxi_relative(&pa, &pb); /* bodies near their frame origin: stored frames = body frames */
        pxi_policy pol;
        memset(&pol, 0, sizeof pol);
        pol.method = PX_METHOD_GJK;
        pol.accept_bound = 1;
        pxi_answer bound, full;
        uint32_t fb_bound = 0, fb_full = 0;
        pxi_distance_pair(a, b, &t_ab, &pol, NULL, &bound, NULL, &fb_bound);
        pol.accept_bound = 0;
        pxi_distance_pair(a, b, &t_ab, &pol, NULL, &full, NULL, &fb_full);
        pol.method = PX_METHOD_LIN_CANNY;
        pxi_answer lc;
        uint32_t fb_lc = 0;
        pxi_distance_pair(a, b, &t_ab, &pol, NULL, &lc, NULL, &fb_lc);
        if (bound.quality & PX_QUALITY_UNPROVEN) {
            unproven++;
            double noise = 64 * DBL_EPSILON * 4.0;
            CHECK(fb_bound == 0 && lc.distance <= bound.distance + noise &&
                      lc.distance >= bound.distance - bound.gap - noise,
                  "pair %d: unproven GJK %.17g with gap %.3g does not bracket Lin-Canny's %.17g", i,
                  bound.distance, bound.gap, lc.distance);
            CHECK(fb_full >= 1 && fabs(full.distance - lc.distance) <= noise &&
                      !(full.quality & PX_QUALITY_UNPROVEN),
                  "pair %d: the default policy gives %.17g (fallbacks %u), Lin-Canny %.17g", i, full.distance,
                  fb_full, lc.distance);
        } else {
            CHECK(fb_bound == 0 && bound.distance == full.distance, "pair %d: proven answers differ", i);
        }
        px_convex_destroy(a);
        px_convex_destroy(b);
    }
    CHECK(unproven > 10, "only %d unproven GJK answers: the test no longer covers the policy", unproven);
    printf("  accept_bound: %d unproven GJK answers bracket Lin-Canny's distance\n", unproven);
}

/* ---- Findings of the issue-8 review, each reproduced. ---- */

/* A case file of the review (tests/data/review8): A's and B's vertices (hex
 * floats), their poses, a direction and a cache's raw bytes. */
static int load_case(const char *name, px_convex **a, px_pose *pa, px_convex **b, px_pose *pb, px_vec3 *dir,
                     px_pair_cache *cache) {
    char path[512];
    snprintf(path, sizeof path, "%s/%s", PX_TEST_DATA, name);
    FILE *f = fopen(path, "r");
    CHECK(f != NULL, "cannot open %s", path);
    if (!f) return 0;
    px_convex **cs[2] = {a, b};
    px_pose *ps[2] = {pa, pb};
    int ok = 1;
    for (int q = 0; q < 2 && ok; ++q) {
        unsigned n = 0;
        ok = fscanf(f, "%u", &n) == 1 && n > 0 && n < 100000;
        double *p = ok ? malloc(3 * sizeof *p * n) : NULL;
        for (unsigned i = 0; ok && i < 3 * n; ++i) ok = fscanf(f, "%la", &p[i]) == 1;
        *cs[q] = ok ? px_convex_create(p, n, NULL, NULL) : NULL;
        free(p);
        for (int i = 0; ok && i < 9; ++i) ok = fscanf(f, "%la", &ps[q]->r[i]) == 1;
        ok = ok && fscanf(f, "%la %la %la", &ps[q]->t.x, &ps[q]->t.y, &ps[q]->t.z) == 3;
    }
    ok = ok && fscanf(f, "%la %la %la", &dir->x, &dir->y, &dir->z) == 3;
    char hex[1024]; /* the width below must stay under its size */
    _Static_assert(2 * sizeof *cache < 1000, "a cache's hex string must fit the buffer");
    memset(cache, 0, sizeof *cache);
    if (ok && fscanf(f, "%1000s", hex) == 1 && strlen(hex) >= 2 * sizeof *cache) {
        unsigned char *bytes = (unsigned char *)cache;
        for (size_t i = 0; i < sizeof *cache; ++i) {
            unsigned v = 0;
            sscanf(hex + 2 * i, "%2x", &v);
            bytes[i] = (unsigned char)v;
        }
    }
    fclose(f);
    CHECK(ok && *a && *b, "case %s did not load", name);
    return ok && *a && *b;
}

/* The contact band of query.h, from the public bounds. */
static double band_of(const px_convex *a, const px_pose *pa, const px_convex *b, const px_pose *pb) {
    px_bounds ba, bb;
    px_convex_bounds(a, pa, &ba);
    px_convex_bounds(b, pb, &bb);
    return 64 * DBL_EPSILON * (ba.radius + bb.radius + pxi_len(pxi_sub(ba.center, bb.center)));
}

static px_pose translated(const px_pose *p, px_vec3 d, double tau) {
    px_pose q = *p;
    q.t = pxi_madd(q.t, d, tau);
    return q;
}

/* Thin bodies (slabs 1:1:1e-6, needles of radius 1e-5) where the ray cast
 * stopped at its rounding floor, advancement could not confirm, and its
 * unproven hit came back with PX_OK: cases 30, 84 and 338 are misses (the
 * line passes 1.7e-9, 9.5e-10 and 8.6 bands from B: exact distance along the
 * line, golden section), reported as hits at tau -1.35e-8, 4.3e-9, 1.8e-13;
 * case 304 stopped 4.9 bands short of contact (advancement accepted features
 * 16 bands apart as touching). Now: misses with a witness plane checked on
 * every vertex; the hit within the band and minimal. */
static void test_review_thin_translation(void) {
    const char *names[4] = {"case_translate_30.txt", "case_translate_84.txt", "case_translate_338.txt",
                            "case_translate_304.txt"};
    for (int k = 0; k < 4; ++k) {
        px_convex *a = NULL, *b = NULL;
        px_pose pa, pb;
        px_vec3 d;
        px_pair_cache cache;
        if (!load_case(names[k], &a, &pa, &b, &pb, &d, &cache)) {
            px_convex_destroy(a);
            px_convex_destroy(b);
            continue;
        }
        double band = band_of(a, &pa, b, &pb);
        for (int mode = 0; mode < 2; ++mode) {
            px_translate_result t;
            px_status st = px_translate(a, &pa, b, &pb, d, mode ? &tu_both_ways : NULL, NULL, &t);
            CHECK(st == PX_OK, "%s mode %d: %s", names[k], mode, px_status_string(st));
            if (k < 3) {
                CHECK(!t.hit && t.gap > band,
                      "%s mode %d: hit %d tau %.3g gap %.3g (a miss by more than the band)", names[k], mode,
                      t.hit, t.tau, t.gap);
                for (uint32_t i = 0; i < px_convex_vertex_count(a); ++i) {
                    px_vec3 w = px_pose_apply(&pa, ta_vertex(a, i));
                    CHECK(pxi_dot(t.normal, pxi_sub(w, t.point_a)) <= 8 * band,
                          "%s: A vertex %u above the witness", names[k], i);
                }
                for (uint32_t i = 0; i < px_convex_vertex_count(b); ++i) {
                    px_vec3 w = px_pose_apply(&pb, ta_vertex(b, i));
                    double h = pxi_dot(t.normal, pxi_sub(w, t.point_b));
                    CHECK(h >= -8 * band,
                          "%s mode %d: B vertex %u below the witness by %.3g (band %.3g, gap %.3g)", names[k],
                          mode, i, -h, band, t.gap);
                }
            } else {
                px_distance_result at, before;
                px_pose moved = translated(&pa, d, t.tau),
                        early = translated(&pa, d, t.tau - 100 * band / pxi_len(d));
                px_distance(a, &moved, b, &pb, NULL, NULL, &at);
                px_distance(a, &early, b, &pb, NULL, NULL, &before);
                CHECK(t.hit && at.intersecting && !before.intersecting,
                      "%s mode %d: hit %d, touching at tau %d, separated 100 bands before %d", names[k], mode,
                      t.hit, at.intersecting, !before.intersecting);
            }
        }
        px_convex_destroy(a);
        px_convex_destroy(b);
    }
}

/* A cache whose direction hint is (1e200, -0.2352, 1.8e308): the ray cast
 * took it as its first direction, its dot products overflowed, and tau came
 * out 2.228 where contact is at 0.5245. Warm must equal cold. */
static void test_review_cache_hint(void) {
    px_convex *a = NULL, *b = NULL;
    px_pose pa, pb;
    px_vec3 d;
    px_pair_cache cache;
    if (!load_case("cachecase_1.txt", &a, &pa, &b, &pb, &d, &cache)) {
        px_convex_destroy(a);
        px_convex_destroy(b);
        return;
    }
    for (int mode = 0; mode < 2; ++mode) {
        px_translate_result cold, warm;
        px_pair_cache c = cache;
        px_translate(a, &pa, b, &pb, d, mode ? &tu_both_ways : NULL, NULL, &cold);
        px_status st = px_translate(a, &pa, b, &pb, d, mode ? &tu_both_ways : NULL, &c, &warm);
        CHECK(st == PX_OK && warm.hit == cold.hit &&
                  fabs(warm.tau - cold.tau) <= 1e-12 * (1 + fabs(cold.tau)),
              "cache hint, mode %d: warm tau %.17g, cold %.17g", mode, warm.tau, cold.tau);
    }
    px_convex_destroy(a);
    px_convex_destroy(b);
}

/* A body whose points sit at 2^40 in its own frame, posed back by -2^40
 * next to a unit cube: the relative translation rounded t_A - t_B at
 * ulp(2^40) before the centres' offset cancelled it, so gaps below 1.2e-4
 * came out 0 (touching) and larger ones off by up to 1.2e-4. */
static void test_review_far_pose_cancel(void) {
    double o = 0x1p40, pts[24], unit[24];
    for (int i = 0; i < 8; ++i)
        for (int k = 0; k < 3; ++k) pts[3 * i + k] = o + ((i >> k) & 1), unit[3 * i + k] = (i >> k) & 1;
    px_convex *a = px_convex_create(pts, 8, NULL, NULL), *b = px_convex_create(unit, 8, NULL, NULL);
    CHECK(a && b, "cubes");
    const double gaps[4] = {0x1p-30, 0x1p-14, 0x1p-13, 1e-3};
    for (int g = 0; g < 4 && a && b; ++g) {
        px_pose pa = at(-o, -o, -o), pb = at(1.0 + gaps[g], 0, 0);
        for (uint32_t m = 0; m < 3; ++m) {
            px_query_options q;
            memset(&q, 0, sizeof q);
            q.method = m;
            px_distance_result r;
            px_distance(a, &pa, b, &pb, &q, NULL, &r);
            CHECK(!r.intersecting && fabs(r.distance - gaps[g]) <= 4 * DBL_EPSILON * 4,
                  "far pose, gap %g, method %u: distance %.17g", gaps[g], m, r.distance);
        }
        px_translate_result t;
        px_translate(a, &pa, b, &pb, pxi_v(1, 0, 0), NULL, NULL, &t);
        CHECK(t.hit && fabs(t.tau - gaps[g]) <= 16 * DBL_EPSILON, "far pose, gap %g: tau %.17g", gaps[g],
              t.tau);
    }
    px_convex_destroy(a);
    px_convex_destroy(b);
}

/* Cubes 2^-46 (0.36 band) apart slide along their touching faces: the
 * distance query says touching, and the forward translation said "no hit,
 * not in contact" (its check at tau = 0 ran only on hits). */
static void test_review_parallel_slide(void) {
    double unit[24];
    for (int i = 0; i < 8; ++i)
        for (int k = 0; k < 3; ++k) unit[3 * i + k] = (i >> k) & 1;
    px_convex *c = px_convex_create(unit, 8, NULL, NULL);
    if (!c) return;
    px_pose pa = px_pose_identity(), pb = at(1.0 + 0x1p-46, 0, 0);
    const px_vec3 dirs[3] = {{0, 1, 0}, {0, 0, -1}, {0, 1, 1}};
    for (int i = 0; i < 3; ++i) {
        px_translate_result t;
        px_translate(c, &pa, c, &pb, dirs[i], NULL, NULL, &t);
        CHECK(t.hit && t.in_contact && t.tau == 0.0, "slide %d: hit %d in_contact %d", i, t.hit,
              t.in_contact);
    }
    px_convex_destroy(c);
}

/* Sliver and subnormal-thickness hulls: exactly solids for CGAL, but with
 * face planes double precision cannot hold (a zero or inward "unit" normal,
 * side normals 0.79999 for 0.8 on a slab 2^-1060 thick, on which Lin-Canny
 * answered 0.049989 for 0.05). Refused with PX_ERR_DEGENERATE. */
static void test_review_thin_hulls(void) {
    double sliver[12] = {0, 0, 0, 0, 2.28e-41, 0, 2.59e-9, 4.3e-5, 4.3e-5, 1, 0, 0};
    double slab[24];
    for (int i = 0; i < 8; ++i)
        slab[3 * i] = (i & 1), slab[3 * i + 1] = (i & 2) ? 1 : 0, slab[3 * i + 2] = (i & 4) ? 0x1p-1060 : 0;
    const double *sets[2] = {sliver, slab};
    size_t counts[2] = {4, 8};
    for (int k = 0; k < 2; ++k) {
        px_error err;
        tu_untrap_fp(); /* the subnormal slab's own arithmetic */
        px_convex *c = px_convex_create(sets[k], counts[k], NULL, &err);
        tu_trap_fp();
        CHECK(c == NULL ? err.code == PX_ERR_DEGENERATE : px_convex_validate(c, NULL) == PX_OK,
              "thin hull %d: accepted but invalid, or refused with %s (%s)", k, px_status_string(err.code),
              err.message);
        px_convex_destroy(c);
    }
}

int main(void) {
    tu_init("test_query_edges");
    test_review_thin_translation();
    test_review_cache_hint();
    test_review_far_pose_cancel();
    test_review_parallel_slide();
    test_review_thin_hulls();
    test_accept_bound_policy();
    test_warm_translation_hint();
    test_intersect_near_contact();
    test_epa_deep_round();
    test_flat_difference();
    test_extreme_numbers();
    return tu_finish();
}
