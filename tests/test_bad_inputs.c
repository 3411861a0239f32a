/* Regression tests for sections A-C of shared/docs/BAD_INPUTS.md (items
 * 1-16): one named function per item, each citing the report it comes from
 * and asserting proxima's documented behaviour. Queries are checked with the
 * brute-force oracle (check.c) and, where it matters, CGAL's exact distance. */
#include <float.h>

#include "access.h"
#include "check.h"
#include "math/vec3.h"
#include "px_gen.h"
#include "test_util.h"

/* ----------------------------------------------------------------- helpers */

static px_convex *build(const double *xyz, size_t n, const char *what) {
    px_error err;
    memset(&err, 0, sizeof err);
    px_convex *c = px_convex_create(xyz, n, NULL, &err);
    CHECK(c != NULL, "%s: %s", what, err.message);
    if (c) CHECK(px_convex_validate(c, &err) == PX_OK, "%s: validate: %s", what, err.message);
    return c;
}

static px_status build_status(const double *xyz, size_t n, px_error *err) {
    memset(err, 0, sizeof *err);
    px_convex *c = px_convex_create(xyz, n, NULL, err);
    if (c) {
        px_status st = px_convex_validate(c, err);
        px_convex_destroy(c);
        return st == PX_OK ? PX_OK : PX_ERR_INTERNAL;
    }
    return err->code;
}

static px_pose pose_t(double x, double y, double z) {
    px_pose p = px_pose_identity();
    p.t = pxi_v(x, y, z);
    return p;
}

static int result_zero(const px_distance_result *r) {
    px_distance_result z;
    memset(&z, 0, sizeof z);
    return r->distance == 0 && !r->intersecting && r->diag.iterations == 0 && r->diag.fallbacks == 0 &&
           memcmp(&r->point_a, &z.point_a, sizeof z.point_a) == 0 &&
           memcmp(&r->point_b, &z.point_b, sizeof z.point_b) == 0 && r->feature_a.type == 0 &&
           r->feature_b.type == 0;
}

/* Query checked by the oracle at relative tolerance `rel`; returns fail bits. */
static int checked(const px_convex *a, const px_pose *pa, const px_convex *b, const px_pose *pb,
                   px_pair_cache *cache, double rel, const char *what, tc_report *rep) {
    tc_rel_tol = rel;
    tc_query_and_check(a, pa, b, pb, cache, rep);
    CHECK(rep->fail == 0, "%s: %s", what, rep->msg);
    CHECK(rep->res.diag.fallbacks == 0, "%s: %u fallbacks", what, rep->res.diag.fallbacks);
    return rep->fail;
}

/* Exact classification of the pair (CGAL on the doubles the library sees). */
static void check_exact(const px_convex *a, const px_pose *pa, const px_convex *b, const px_pose *pb,
                        const tc_report *rep, const char *what) {
    double d = 0;
    int zero = 0;
    if (tc_exact(a, pa, b, pb, &d, &zero) != 0) {
        CHECK(0, "%s: exact failed", what);
        return;
    }
    double tol = 64 * DBL_EPSILON * rep->scale;
    if (zero)
        CHECK(rep->res.intersecting || rep->res.distance <= tol, "%s: exact touching, library d=%.17g", what,
              rep->res.distance);
    else
        CHECK(fabs(rep->res.distance - d) <= tol && (d <= tol || !rep->res.intersecting),
              "%s: d=%.17g exact %.17g int %d", what, rep->res.distance, d, rep->res.intersecting);
}

static px_convex *unit_cube(double h) {
    double b[24];
    pg_box(h, h, h, b);
    return build(b, 8, "cube");
}

/* ============================================ A. non-finite and extreme numbers */

/* 1. NaN/Inf in setters and transforms: box2d rejects NaN, +Inf, -Inf in
 * every setter and leaves state unchanged (erincatto/box2d
 * test/test_invalid_input.c). Rule: validate every public float. */
static void bad_input_01_nan_inf_in_setters(void) {
    const double bad[3] = {NAN, INFINITY, -INFINITY};
    for (int b = 0; b < 3; ++b) {
        for (int pos = 0; pos < 24; pos += 7) { /* first point, middle, last */
            double box[24];
            pg_box(1, 2, 3, box);
            box[pos] = bad[b];
            px_error err;
            CHECK(build_status(box, 8, &err) == PX_ERR_NON_FINITE && err.message[0], "coordinate %d = %g: %s",
                  pos, bad[b], err.message);
        }
        px_pose p = px_pose_identity();
        p.r[4] = bad[b];
        px_error err;
        memset(&err, 0, sizeof err);
        CHECK(px_pose_check(&p, &err) == PX_ERR_NON_FINITE && err.message[0], "pose_check r = %g", bad[b]);
        p = pose_t(0, bad[b], 0);
        CHECK(px_pose_check(&p, NULL) == PX_ERR_NON_FINITE, "pose_check t = %g", bad[b]);
        double q[4] = {1, 0, bad[b], 0}, t[3] = {0, 0, 0};
        CHECK(px_pose_from_quat(q, t, &p) == PX_ERR_NON_FINITE && px_pose_check(&p, NULL) == PX_OK,
              "pose from quaternion with %g accepted (or not left as the identity)", bad[b]);
        double tb[3] = {0, bad[b], 0}, r[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
        CHECK(px_pose_from_rt(r, tb, &p) == PX_ERR_NON_FINITE, "pose from translation %g accepted", bad[b]);
    }
    double q0[4] = {0, 0, 0, 0}, t0[3] = {0, 0, 0};
    px_pose pz;
    CHECK(px_pose_from_quat(q0, t0, &pz) == PX_ERR_INVALID_ARGUMENT, "pose from a zero quaternion accepted");
    /* px_distance leaves the cache unchanged and zeroes the result. */
    px_convex *c = unit_cube(1);
    if (!c) return;
    px_pose a = px_pose_identity(), far = pose_t(4, 0, 0);
    px_pair_cache cache;
    memset(&cache, 0, sizeof cache);
    px_distance_result r;
    px_distance(c, &a, c, &far, NULL, &cache, &r);
    px_pair_cache saved = cache;
    for (int b = 0; b < 3; ++b) {
        px_pose bad_pose = pose_t(4, bad[b], 0);
        memset(&r, 0x5a, sizeof r);
        CHECK(px_distance(c, &a, c, &bad_pose, NULL, &cache, &r) == PX_ERR_NON_FINITE,
              "px_distance with t.y = %g", bad[b]);
        CHECK(result_zero(&r) && memcmp(&cache, &saved, sizeof cache) == 0, "result zeroed, cache unchanged");
    }
    px_convex_destroy(c);
}

/* 2. NaN inside GJK leads to an infinite loop (jrouwe/JoltPhysics #1383;
 * jrl-umi3218/sch-core #28, fix #29). Rule: NaN terminates loops; cap
 * iterations. Poses that are NaN only after arithmetic (huge but finite
 * entries whose products overflow) must still return. */
static void bad_input_02_nan_no_infinite_loop(void) {
    px_convex *c = unit_cube(1);
    if (!c) return;
    px_pose a = px_pose_identity();
    px_distance_result r;
    /* A quaternion with a NaN is refused, and a NaN rotation built by hand
     * is rejected by the query: no loop. */
    double q[4] = {NAN, 0, 0, 1}, t[3] = {3, 0, 0};
    px_pose pq;
    CHECK(px_pose_from_quat(q, t, &pq) == PX_ERR_NON_FINITE, "NaN quaternion accepted");
    for (int i = 0; i < 9; ++i) pq.r[i] = NAN;
    CHECK(px_distance(c, &a, c, &pq, NULL, NULL, &r) != PX_OK, "NaN rotation accepted");
    /* Far but finite: 1e150 apart (squares stay finite): answered. */
    px_pose far = pose_t(1e150, 0, 0);
    tc_report rep;
    checked(c, &a, c, &far, NULL, 64 * DBL_EPSILON, "1e150 apart", &rep);
    CHECK(rep.res.distance > 0 && !rep.res.intersecting, "1e150 apart: d=%g", rep.res.distance);
    px_convex_destroy(c);
}

/* 3. NaN witness points or contacts: fcl #293 (degenerate simplex,
 * NearestPointFromDegenerateSimplex), coal #636 (all-NaN contacts),
 * openGJK #56 (2D-in-3D). Rule: witnesses are always finite. */
static void bad_input_03_nan_witness_points(void) {
    double tri_prism[18] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1e-9, 1, 0, 1e-9, 0, 1, 1e-9}; /* near-2D */
    double seg_prism[24];
    pg_box(2, 1e-9, 1e-9, seg_prism); /* near-1D */
    px_convex *T = build(tri_prism, 6, "flat prism"), *S = build(seg_prism, 8, "needle box");
    px_convex *C = unit_cube(0.5);
    if (!T || !S || !C) return;
    pg_rng rng;
    pg_seed(&rng, 303);
    const px_convex *shapes[3] = {T, S, C};
    for (int i = 0; i < 300; ++i) {
        const px_convex *a = shapes[i % 3], *b = shapes[(i / 3) % 3];
        px_pose pb = pg_pose_random(&rng, 1), pa = pg_pose_random(&rng, 1);
        if (i % 5 == 0) pa = pb; /* coincident poses */
        tc_report rep;
        checked(a, &pa, b, &pb, NULL, 1e-12, "degenerate witness", &rep);
    }
    px_convex_destroy(T);
    px_convex_destroy(S);
    px_convex_destroy(C);
}

/* 4. A single NaN triangle poisons a BVH (LTplus-AG/ifc-lite #3561). Rule:
 * reject non-finite vertices at load time, naming the index. Subnormal and
 * signed-zero coordinates are finite and accepted. */
static void bad_input_04_single_nan_vertex(void) {
    pg_rng rng;
    pg_seed(&rng, 404);
    double *xyz = malloc(3 * 1000 * sizeof *xyz);
    pg_points_sphere(&rng, 1000, 1, xyz);
    xyz[3 * 537 + 1] = NAN;
    px_error err;
    CHECK(build_status(xyz, 1000, &err) == PX_ERR_NON_FINITE, "one NaN among 1000 points: %s",
          px_status_string(err.code));
    CHECK(strstr(err.message, "537") != NULL, "message does not name point 537: \"%s\"", err.message);
    /* Subnormals and -0.0 are fine (interior points). */
    xyz[3 * 537 + 1] = 0.0;
    xyz[3 * 10] = 4.9e-324, xyz[3 * 10 + 1] = -0.0, xyz[3 * 10 + 2] = -2.2e-310;
    CHECK(build_status(xyz, 1000, &err) == PX_OK, "subnormal coordinates rejected: %s", err.message);
    free(xyz);
}

/* 5. Unbounded iteration by default: libccd max_iterations = ULONG_MAX
 * (danfis/libccd src/ccd/ccd.h) gives the hangs of fcl #243, libccd #7 and
 * the box-box EPA loop of fcl #578. Rule: every query is bounded; we check
 * the iteration counter stays below 2 (V+E+F) of both bodies. */
static void bad_input_05_unbounded_iterations(void) {
    pg_rng rng;
    pg_seed(&rng, 505);
    double box[24], sph[3 * 400];
    pg_box(1, 1, 1, box);
    pg_points_sphere(&rng, 400, 1, sph);
    px_convex *B = build(box, 8, "box"), *S = build(sph, 400, "sphere");
    if (!B || !S) return;
    const px_convex *shapes[2] = {B, S};
    uint32_t worst = 0;
    for (int i = 0; i < 2000; ++i) {
        const px_convex *a = shapes[i & 1], *b = shapes[(i >> 1) & 1];
        px_pose pa = pg_pose_random(&rng, 0.3 + 2 * (i % 7) / 7.0), pb = pg_pose_random(&rng, 0.3);
        px_distance_result r;
        px_pair_cache cache;
        memset(&cache, 0, sizeof cache);
        CHECK(px_distance(a, &pa, b, &pb, NULL, &cache, &r) == PX_OK, "query %d", i);
        uint32_t cap = 2 * (px_convex_vertex_count(a) + px_convex_edge_count(a) + px_convex_face_count(a) +
                            px_convex_vertex_count(b) + px_convex_edge_count(b) + px_convex_face_count(b));
        CHECK(r.diag.iterations <= cap && r.diag.fallbacks == 0,
              "query %d: %u iterations (cap %u), %u fallbacks", i, r.diag.iterations, cap, r.diag.fallbacks);
        if (r.diag.iterations > worst) worst = r.diag.iterations;
    }
    printf("  5: 2000 box/sphere queries, max iterations %u\n", worst);
    px_convex_destroy(B);
    px_convex_destroy(S);
}

/* 6. Huge coordinate ranges: qhull fuzz mixing 1e139 and 1e-322
 * (qhull/qhull #166); GJK missing overlaps near 1000 in float
 * (RandyGaul/cute_headers #160); a fixed 1e-6 epsilon dropping a face at
 * 5 km (LTplus-AG/ifc-lite #2600). Rule: relative tolerances. */
static void bad_input_06_huge_coordinate_ranges(void) {
    /* qhull-style fuzz: a clear status or a valid hull, never a crash. */
    double fuzz[24] = {1e139,  0,      0, 0, 1e139,  0,      0,      0, 1e139,  1e-322, 1e-322, 1e-322,
                       -1e139, 1e-322, 0, 0, -1e139, 5e-323, 3e-322, 0, -1e139, 1e139,  1e139,  1e139};
    px_error err;
    px_status st = build_status(fuzz, 8, &err);
    CHECK(st == PX_OK || st == PX_ERR_DEGENERATE, "1e139 / 1e-322 fuzz: %s (%s)", px_status_string(st),
          err.message);
    /* Boxes at 5 km and 1e7 m from the origin, 1 mm apart / 1 mm overlapping. */
    px_convex *c = unit_cube(0.5);
    if (!c) return;
    const double offsets[3] = {5e3, 1e7, 1e12};
    for (int i = 0; i < 3; ++i) {
        for (int s = -1; s <= 1; s += 2) {
            double o = offsets[i];
            px_pose pa = pose_t(o, o, -o), pb = pose_t(o + 1 + s * 1e-3, o + 0.25, -o);
            tc_report rep;
            checked(c, &pa, c, &pb, NULL, 64 * DBL_EPSILON, "far from the origin", &rep);
            check_exact(c, &pa, c, &pb, &rep, "far from the origin");
            if (s < 0)
                CHECK(rep.res.intersecting, "overlap of 1 mm at %g m missed (d=%g)", o, rep.res.distance);
            else
                CHECK(!rep.res.intersecting && fabs(rep.res.distance - 1e-3) <= 4 * DBL_EPSILON * o,
                      "gap of 1 mm at %g m: d=%.17g", o, rep.res.distance);
        }
    }
    /* Hulls with coordinates of 1e139: distance relative to scale. */
    pg_rng rng;
    pg_seed(&rng, 606);
    double big[3 * 50];
    pg_points_sphere(&rng, 50, 1e139, big);
    px_convex *B = build(big, 50, "sphere of radius 1e139");
    if (B) {
        px_pose pa = px_pose_identity(), pb = pose_t(2.5e139, 0, 0);
        tc_report rep;
        checked(B, &pa, B, &pb, NULL, 1e-12, "1e139 spheres", &rep);
        check_exact(B, &pa, B, &pb, &rep, "1e139 spheres");
        px_convex_destroy(B);
    }
    px_convex_destroy(c);
}

/* 7. Tiny objects: a 0.005 m box vs a 0.01 m sphere missed in single
 * precision (bulletphysics/bullet3 #2579); Bullet's 0.04 margin
 * (jsk-ros-pkg/jsk_roseus #616). Rule: no absolute margins. */
static void bad_input_07_tiny_objects(void) {
    pg_rng rng;
    pg_seed(&rng, 707);
    double sph[3 * 100];
    for (int e = 0; e >= -12; e -= 3) {
        double s = pow(10.0, e);
        double box[24];
        pg_box(0.0025 * s, 0.0025 * s, 0.0025 * s, box);
        pg_points_sphere(&rng, 100, 0.005 * s, sph);
        px_convex *B = build(box, 8, "tiny box"), *S = build(sph, 100, "tiny sphere");
        if (!B || !S) return;
        for (int i = 0; i < 50; ++i) {
            px_pose pb = pg_pose_random(&rng, s);
            px_pose pa = pg_pose_random(&rng, 0);
            px_vec3 dir = pg_unit(&rng);
            pa.t = pxi_add(pb.t, pxi_scale(dir, s * 0.0075 * pg_range(&rng, 0.5, 1.5)));
            tc_report rep;
            checked(B, &pb, S, &pa, NULL, 1e-12, "tiny objects", &rep);
            check_exact(B, &pb, S, &pa, &rep, "tiny objects");
        }
        px_convex_destroy(B);
        px_convex_destroy(S);
    }
}

/* 8. Results that depend on the tolerance: a touching sphere-box pair is
 * colliding at GJK tolerance 1e-6 and not below 1e-10 (fcl #281); grossly
 * wrong distances near contact (coal #604); non-convergence as the
 * tolerance tightens (fcl #250). Rule: classification follows the exact
 * answer for the given doubles. */
static void bad_input_08_tolerance_dependent(void) {
    pg_rng rng;
    pg_seed(&rng, 808);
    double sph[3 * 201];
    pg_points_sphere(&rng, 200, 1, sph);
    sph[600] = 0, sph[601] = 0, sph[602] = -1; /* exact south pole */
    px_convex *S = build(sph, 201, "sphere with pole");
    double box[24];
    pg_box(2, 2, 1, box);
    px_convex *B = build(box, 8, "box");
    if (!S || !B) return;
    px_pose pb = pose_t(0, 0, -1); /* box top at z = 0 */
    const double gaps[] = {0, 1e-16, 1e-14, 1e-12, 1e-10, 1e-8, 1e-6, -1e-16, -1e-12, -1e-6};
    for (size_t g = 0; g < sizeof gaps / sizeof gaps[0]; ++g) {
        px_pose ps = pose_t(0, 0, 1 + gaps[g]); /* pole at z = gaps[g] (rounded) */
        tc_report rep;
        checked(S, &ps, B, &pb, NULL, 64 * DBL_EPSILON, "sphere on box", &rep);
        check_exact(S, &ps, B, &pb, &rep, "sphere on box");
        if (gaps[g] == 0)
            CHECK(rep.res.intersecting || rep.res.distance == 0, "exact touching reported as d=%.17g",
                  rep.res.distance);
        if (gaps[g] >= 1e-12)
            CHECK(!rep.res.intersecting && fabs(rep.res.distance - gaps[g]) <= 1e-15,
                  "gap %g: d=%.17g (rounding of 1 + gap allows 1e-16)", gaps[g], rep.res.distance);
        if (gaps[g] <= -1e-12) CHECK(rep.res.intersecting, "overlap %g not detected", gaps[g]);
    }
    px_convex_destroy(S);
    px_convex_destroy(B);
}

/* ============================================ B. degenerate convex input */

/* 9. Flat or zero-volume point sets: "initial simplex is flat"
 * (google-deepmind/mujoco #3260); no hull for a flat mesh (bepu/bepuphysics2
 * #316); Jolt EResult::Degenerate. Rule: a status, never an assert. */
static void bad_input_09_flat_point_sets(void) {
    double quad[3 * 36];
    int k = 0;
    for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j, ++k)
            quad[3 * k] = i * 0.5, quad[3 * k + 1] = j * 0.25, quad[3 * k + 2] = 2.0;
    /* Issue 9: lower-dimensional pieces are accepted (a polygon, a
     * triangle, a segment), with their dimension; test_degenerate queries
     * them. */
    px_convex *c = px_convex_create(quad, 36, NULL, NULL);
    CHECK(c && px_convex_dimension(c) == 2 && px_convex_vertex_count(c) == 4, "planar grid: a rectangle");
    px_convex_destroy(c);
    double tri[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    c = px_convex_create(tri, 3, NULL, NULL);
    CHECK(c && px_convex_dimension(c) == 2 && px_convex_vertex_count(c) == 3, "single triangle");
    px_convex_destroy(c);
    double line[3 * 5] = {0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3, -1, -1, -1};
    c = px_convex_create(line, 5, NULL, NULL);
    CHECK(c && px_convex_dimension(c) == 1 && px_convex_vertex_count(c) == 2, "line: a segment");
    px_vec3 e0, e1;
    px_convex_vertex(c, 0, &e0);
    px_convex_vertex(c, 1, &e1);
    CHECK(e0.x == 3 && e1.x == -1, "line: the end points (3,3,3) and (-1,-1,-1) in input order");
    px_convex_destroy(c);
}

/* 10. Duplicate or near-duplicate points: Jolt TooFewPoints
 * (ConvexHullBuilderTest.cpp TestDegenerate); a hull crashing on duplicated
 * points (MeshInspector/MeshLib #5450). */
static void bad_input_10_duplicate_points(void) {
    double box[24], rep[24 * 5];
    pg_box(1, 1, 1, box);
    for (int i = 0; i < 5; ++i) memcpy(rep + 24 * i, box, sizeof box);
    px_convex *c = build(rep, 40, "cube corners five times");
    CHECK(c && px_convex_vertex_count(c) == 8 && px_convex_face_count(c) == 6, "duplicated cube");
    px_convex_destroy(c);
    double dup[15] = {0, 0, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0, 1, 0};
    px_error err;
    CHECK(build_status(dup, 5, &err) == PX_OK, "3 distinct points (a triangle): %s",
          px_status_string(err.code));
    /* Near-duplicates: each corner of a tetrahedron with 10 copies perturbed by 1e-14. */
    pg_rng rng;
    pg_seed(&rng, 1010);
    double t[12], cloud[3 * 40];
    pg_regular_tetrahedron(1, t);
    for (int i = 0; i < 40; ++i)
        for (int j = 0; j < 3; ++j) cloud[3 * i + j] = t[3 * (i % 4) + j] + 1e-14 * pg_range(&rng, -1, 1);
    c = build(cloud, 40, "near-duplicate cloud");
    if (c) {
        px_convex *d = unit_cube(1);
        px_pose pa = px_pose_identity(), pb = pose_t(3, 0.2, 0.1);
        tc_report r;
        if (d) checked(c, &pa, d, &pb, NULL, 1e-12, "near-duplicate cloud vs cube", &r);
        px_convex_destroy(d);
    }
    px_convex_destroy(c);
}

/* 11. Nearly coplanar clusters: an inverted face and zero-area triangles
 * failing a convexity check (elalish/manifold #1785); quickhull without
 * robust predicates (tomilov/quickhull #14); Jolt TestHullEdgeCases. */
static void bad_input_11_nearly_coplanar_clusters(void) {
    pg_rng rng;
    pg_seed(&rng, 1111);
    px_convex *cube = unit_cube(0.5);
    for (int trial = 0; trial < 20; ++trial) {
        double pts[3 * 201];
        double eps = pow(10.0, -8 - (trial % 7));
        for (int i = 0; i < 200; ++i) {
            pts[3 * i] = pg_range(&rng, -1, 1);
            pts[3 * i + 1] = pg_range(&rng, -1, 1);
            pts[3 * i + 2] = 0.3 * pts[3 * i] - 0.2 * pts[3 * i + 1] + eps * pg_range(&rng, -1, 1);
        }
        pts[600] = 0.1, pts[601] = 0.2, pts[602] = (trial & 1) ? 1.0 : 1e-6; /* apex */
        px_convex *c = build(pts, 201, "nearly coplanar cluster");
        if (!c || !cube) continue;
        for (int q = 0; q < 20; ++q) {
            px_pose pa = pg_pose_random(&rng, 0), pb = pg_pose_random(&rng, 0);
            pb.t = pxi_scale(pg_unit(&rng), pg_range(&rng, 0.5, 2.5));
            tc_report rep;
            checked(c, &pa, cube, &pb, NULL, 1e-12, "nearly coplanar cluster", &rep);
        }
        px_convex_destroy(c);
    }
    px_convex_destroy(cube);
}

/* 12. Coplanar faces in Voronoi marching give degenerate edge regions (the
 * V-Clip UBC notes). Rule: merge coplanar faces at build time; the merged
 * model answers exactly like the plain one. */
static void bad_input_12_coplanar_faces_merged(void) {
    double plain[24], rich[3 * 26];
    pg_box(1, 1, 1, plain);
    memcpy(rich, plain, sizeof plain);
    int k = 8;
    for (int ax = 0; ax < 3; ++ax)
        for (int s = -1; s <= 1; s += 2, ++k) {
            rich[3 * k] = rich[3 * k + 1] = rich[3 * k + 2] = 0;
            rich[3 * k + ax] = s; /* face centres */
        }
    for (int i = 0; k < 26; ++i, ++k) { /* edge midpoints */
        int ax = i % 3;
        int s1 = (i / 3) & 1 ? 1 : -1, s2 = (i / 6) & 1 ? 1 : -1;
        rich[3 * k + ax] = 0, rich[3 * k + (ax + 1) % 3] = s1, rich[3 * k + (ax + 2) % 3] = s2;
    }
    px_convex *P = build(plain, 8, "plain cube"), *R = build(rich, 26, "cube with extra coplanar points");
    CHECK(R && px_convex_face_count(R) == 6 && px_convex_vertex_count(R) == 8, "coplanar faces merged");
    px_convex *T = unit_cube(0.3);
    if (!P || !R || !T) return;
    pg_rng rng;
    pg_seed(&rng, 1212);
    for (int i = 0; i < 500; ++i) {
        px_pose pa = pg_pose_random(&rng, 0), pb = pg_pose_random(&rng, 3);
        px_distance_result rp, rr;
        px_distance(P, &pa, T, &pb, NULL, NULL, &rp);
        tc_report rep;
        checked(R, &pa, T, &pb, NULL, 1e-12, "merged cube", &rep);
        rr = rep.res;
        CHECK(rp.distance == rr.distance && rp.intersecting == rr.intersecting,
              "merged and plain cube differ: %.17g vs %.17g", rr.distance, rp.distance);
    }
    px_convex_destroy(P);
    px_convex_destroy(R);
    px_convex_destroy(T);
}

/* ============================================ C. contact configurations */

/* 13. Identical or co-centred bodies: signed distance of co-centred spheres
 * never returns (fcl #346); a zero initial direction hides identical boxes
 * (rustgd/collision-rs #51, pull #52); Bullet skips co-centric spheres. */
static void bad_input_13_identical_cocentred(void) {
    pg_rng rng;
    pg_seed(&rng, 1313);
    double sph[3 * 300];
    pg_points_sphere(&rng, 300, 1, sph);
    px_convex *S = build(sph, 300, "sphere");
    for (int i = 0; i < 3 * 300; ++i) sph[i] *= 0.25;
    px_convex *s = build(sph, 300, "small sphere");
    px_convex *B = unit_cube(1);
    if (!S || !s || !B) return;
    for (int i = 0; i < 50; ++i) {
        px_pose p = pg_pose_random(&rng, 10), q = pg_pose_random(&rng, 0);
        q.t = p.t; /* co-centred, different orientation */
        const px_convex *pairs[4][2] = {{S, S}, {B, B}, {S, s}, {s, B}};
        for (int k = 0; k < 4; ++k) {
            tc_report rep;
            checked(pairs[k][0], &p, pairs[k][1], k == 1 && i & 1 ? &p : &q, NULL, 1e-12, "co-centred", &rep);
            CHECK(rep.res.intersecting && rep.res.distance == 0, "co-centred pair %d not intersecting", k);
        }
    }
    px_convex_destroy(S);
    px_convex_destroy(s);
    px_convex_destroy(B);
}

/* 14. Touching or kissing faces: GJK "touching" vs EPA "separated" and FCL
 * throws (fcl #495); "origin outside polytope" (fcl #390, #319); identical
 * boxes touching along one axis not detected (felipeek/raw-physics #6). */
static void bad_input_14_touching_faces(void) {
    px_convex *B = unit_cube(0.5);
    if (!B) return;
    px_pose a = px_pose_identity();
    for (int ax = 0; ax < 3; ++ax)
        for (int s = -1; s <= 1; s += 2) {
            double t[3] = {0.1, -0.2, 0.3};
            t[ax] = s * 1.0;
            px_pose pb = pose_t(t[0], t[1], t[2]);
            tc_report rep;
            checked(B, &a, B, &pb, NULL, 1e-12, "touching boxes", &rep);
            CHECK(rep.res.intersecting || rep.res.distance == 0, "axis %d: touching boxes d=%.17g", ax,
                  rep.res.distance);
            /* one ulp apart / one ulp overlapping */
            t[ax] = nextafter(t[ax], s * 2.0);
            pb = pose_t(t[0], t[1], t[2]);
            checked(B, &a, B, &pb, NULL, 1e-12, "boxes one ulp apart", &rep);
            check_exact(B, &a, B, &pb, &rep, "boxes one ulp apart");
            t[ax] = nextafter(nextafter(t[ax], 0.0), 0.0);
            pb = pose_t(t[0], t[1], t[2]);
            checked(B, &a, B, &pb, NULL, 1e-12, "boxes one ulp overlapping", &rep);
            check_exact(B, &a, B, &pb, &rep, "boxes one ulp overlapping");
        }
    px_convex_destroy(B);
}

/* 15. Overlap misreported as separation by rounding: intersecting polygons
 * reported 0.51 apart (MattiaMontanari/openGJK #3); nearly identical
 * triangles failing the intersection test (kroitor/gjk.c pull #5). */
static void bad_input_15_overlap_by_rounding(void) {
    pg_rng rng;
    pg_seed(&rng, 1515);
    for (int i = 0; i < 200; ++i) {
        double tri[9], prism[18], prism2[18];
        pg_points_sphere(&rng, 3, 1, tri);
        for (int v = 0; v < 3; ++v)
            for (int j = 0; j < 3; ++j) {
                prism[3 * v + j] = tri[3 * v + j];
                prism[9 + 3 * v + j] = tri[3 * v + j] + (j == 2 ? 1e-3 : 0);
                double jit = 1e-12 * pg_range(&rng, -1, 1);
                prism2[3 * v + j] = prism[3 * v + j] + jit;
                prism2[9 + 3 * v + j] = prism[9 + 3 * v + j] + jit;
            }
        px_convex *A = build(prism, 6, "thin prism"), *B = build(prism2, 6, "jittered prism");
        if (!A || !B) continue;
        px_pose p = pg_pose_random(&rng, 1);
        tc_report rep;
        checked(A, &p, B, &p, NULL, 1e-12, "nearly identical prisms", &rep);
        CHECK(rep.res.intersecting, "nearly identical prisms reported %.3g apart", rep.res.distance);
        px_convex_destroy(A);
        px_convex_destroy(B);
    }
}

/* 16. Deep penetration and thin shapes: EPA under-reports depth and
 * misreports on thin meshes (MuJoCo box fuzz test header). Aspect-ratio
 * sweep (needles, slabs), crossing deeply and separated. */
static void bad_input_16_deep_penetration_thin(void) {
    pg_rng rng;
    pg_seed(&rng, 1616);
    for (int e = 0; e <= 4; ++e) {
        double asp = pow(10.0, e);
        double needle[24], slab[24];
        pg_box(1, 1 / asp, 1 / asp, needle);
        pg_box(1, 1, 1 / asp, slab);
        px_convex *N = build(needle, 8, "needle"), *S = build(slab, 8, "slab");
        if (!N || !S) return;
        for (int i = 0; i < 60; ++i) {
            px_pose pa = pg_pose_random(&rng, 0), pb = pg_pose_random(&rng, 0);
            pb.t = pxi_scale(pg_unit(&rng), (i % 3 == 0) ? 0.0 : pg_range(&rng, 0.0, 2.5));
            const px_convex *x = (i & 1) ? N : S, *y = (i & 2) ? N : S;
            tc_report rep;
            checked(x, &pa, y, &pb, NULL, 1e-12, "thin shapes", &rep);
            if (i % 3 == 0)
                CHECK(rep.res.intersecting, "co-centred thin shapes (aspect %g) not intersecting", asp);
        }
        px_convex_destroy(N);
        px_convex_destroy(S);
    }
}

int main(void) {
    tu_init("test_bad_inputs");
    struct {
        const char *name;
        void (*fn)(void);
    } items[] = {
        {"01 nan_inf_in_setters", bad_input_01_nan_inf_in_setters},
        {"02 nan_no_infinite_loop", bad_input_02_nan_no_infinite_loop},
        {"03 nan_witness_points", bad_input_03_nan_witness_points},
        {"04 single_nan_vertex", bad_input_04_single_nan_vertex},
        {"05 unbounded_iterations", bad_input_05_unbounded_iterations},
        {"06 huge_coordinate_ranges", bad_input_06_huge_coordinate_ranges},
        {"07 tiny_objects", bad_input_07_tiny_objects},
        {"08 tolerance_dependent", bad_input_08_tolerance_dependent},
        {"09 flat_point_sets", bad_input_09_flat_point_sets},
        {"10 duplicate_points", bad_input_10_duplicate_points},
        {"11 nearly_coplanar_clusters", bad_input_11_nearly_coplanar_clusters},
        {"12 coplanar_faces_merged", bad_input_12_coplanar_faces_merged},
        {"13 identical_cocentred", bad_input_13_identical_cocentred},
        {"14 touching_faces", bad_input_14_touching_faces},
        {"15 overlap_by_rounding", bad_input_15_overlap_by_rounding},
        {"16 deep_penetration_thin", bad_input_16_deep_penetration_thin},
    };
    for (size_t i = 0; i < sizeof items / sizeof items[0]; ++i) {
        int before = tu_fail_count;
        double t0 = tu_now();
        items[i].fn();
        printf("  item %-28s %s (%.2f s)\n", items[i].name, tu_fail_count == before ? "ok" : "FAILED",
               tu_now() - t0);
    }
    return tu_finish();
}
