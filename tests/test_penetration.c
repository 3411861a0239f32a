/* Signed distance (px_distance_ex with PX_QUERY_SIGNED, every method) and
 * px_intersect against the separating-axis oracle (oracle_sat.h).
 *
 * Seven shape pairs (small random hulls, tetrahedra, boxes, a thin slab, a
 * cylinder, a 200-vertex ellipsoid against a small hull), >= 1,000 random
 * overlapping poses each (PROXIMA_TEST_SCALE; a third under sanitizers).
 * On every pose and method:
 *   - depth within 1e-9 * size of the oracle (size = |t_a - t_b| + R_A + R_B);
 *   - |point_a - point_b| == |signed_distance|, point_b - point_a ==
 *     signed_distance * normal, normal unit and finite, point_a on A's
 *     boundary and point_b on B's (face-plane offsets);
 *   - B translated by depth (1 + 1e-9) + 1e-12 size along the normal is
 *     touching: px_distance <= 2e-9 size (the push overshoots by up to
 *     1e-9 size) and the oracle finds no overlap deeper than 1e-9 size; translated by depth (1 - 1e-6) it
 * still intersects;
 *   - separated poses: B moved by -(d/2) normal is at distance d/2;
 *   - px_intersect and the intersecting flag agree with the oracle outside a
 *     1e-9 * size band around touching.
 * Then the contact configurations of BAD_INPUTS.md section C: touching
 * faces, edges and vertices (depth 0), nested bodies, coincident identical
 * bodies, coinciding centres, touching after a rotation, a huge/tiny pair.
 * The oracle itself is cross-checked on a subset: pruned vs unpruned axes,
 * and its classification and depth against the brute-force distance oracle
 * (oracle.h). */
#include "access.h"
#include "math/vec3.h"
#include "oracle.h"
#include "oracle_sat.h"
#include "px_gen.h"
#include "test_util.h"

static const char *method_names[3] = {"lin-canny", "gjk", "hybrid"};

typedef struct stats {
    long poses, overlapping, separated, band, queries, failed;
    long intersect_checked;
    double worst_depth[3]; /* |depth - oracle| / size */
    double worst_touch;    /* px_distance after the push-out, / size */
    double worst_boundary; /* witness off its boundary, / size */
    double worst_sep;      /* |d(B moved) - d/2| / size */
    long fallbacks[3];
    double time[3];
} stats;
static stats g_st;

typedef struct shape {
    px_convex *c;
    os_shape s;
} shape;

static int make_shape(shape *out, const double *xyz, size_t n) {
    px_error err;
    out->c = px_convex_create(xyz, n, NULL, &err);
    CHECK(out->c != NULL, "hull failed: %s", err.message);
    if (!out->c) return -1;
    int r = os_shape_init(&out->s, out->c);
    CHECK(r == 0, "oracle shape init failed");
    return r;
}

static void free_shape(shape *s) {
    os_shape_free(&s->s);
    px_convex_destroy(s->c);
}

static double pair_size(const shape *a, const px_pose *pa, const shape *b, const px_pose *pb) {
    return pxi_len(pxi_sub(pa->t, pb->t)) + a->s.radius + b->s.radius;
}

static px_pose moved(const px_pose *p, px_vec3 dir, double s) {
    px_pose q = *p;
    q.t = pxi_madd(q.t, dir, s);
    return q;
}

/* All checks of one signed query against the oracle answer `o`. Returns the
 * number of failed checks (for the repro line). */
static int check_signed(const shape *A, const px_pose *pa, const shape *B, const px_pose *pb,
                        const os_pen_result *o, int method, const char *what, long idx) {
    int before = tu_fail_count;
    double size = pair_size(A, pa, B, pb), tol = 1e-9 * size;
    px_query_options opt;
    memset(&opt, 0, sizeof opt);
    opt.method = (uint32_t)method;
    opt.flags = PX_QUERY_SIGNED;
    px_distance_result r;
    double t0 = tu_now();
    px_status st = px_distance(A->c, pa, B->c, pb, &opt, NULL, &r);
    g_st.time[method] += tu_now() - t0;
    g_st.queries++;
    g_st.fallbacks[method] += r.diag.fallbacks;
    const char *mn = method_names[method];
    CHECK(st == PX_OK, "%s #%ld %s: status %s", what, idx, mn, px_status_string(st));
    int fin = isfinite(r.distance) && isfinite(r.signed_distance) && pxi_is_finite3(r.point_a) &&
              pxi_is_finite3(r.point_b) && pxi_is_finite3(r.normal);
    CHECK(fin, "%s #%ld %s: non-finite result", what, idx, mn);
    if (st != PX_OK || !fin) return tu_fail_count - before;
    double gap = pxi_len(pxi_sub(r.point_b, r.point_a));
    CHECK(fabs(gap - fabs(r.signed_distance)) <= tol, "%s #%ld %s: |pb - pa| = %.17g, signed %.17g", what,
          idx, mn, gap, r.signed_distance);
    if (fabs(o->depth) <= tol) {
        /* Touching band: the sign is not decided, the magnitude is. */
        CHECK(r.signed_distance >= -2 * tol, "%s #%ld %s: touching, signed %.17g (oracle %.3g)", what, idx,
              mn, r.signed_distance, o->depth);
        if (!o->separated)
            CHECK(r.signed_distance <= 2 * tol, "%s #%ld %s: touching, signed %.17g (oracle %.3g)", what, idx,
                  mn, r.signed_distance, o->depth);
        return tu_fail_count - before;
    }
    double nl = pxi_len(r.normal);
    CHECK(fabs(nl - 1) <= 1e-12, "%s #%ld %s: |normal| = %.17g", what, idx, mn, nl);
    if (!(nl > 0.5)) return tu_fail_count - before;
    px_vec3 resid = pxi_sub(pxi_sub(r.point_b, r.point_a), pxi_scale(r.normal, r.signed_distance));
    CHECK(pxi_len(resid) <= tol, "%s #%ld %s: pb - pa - signed * normal = %.3g", what, idx, mn,
          pxi_len(resid));
    if (o->separated) {
        double d = r.distance;
        CHECK(!r.intersecting && d > 0 && r.signed_distance == d,
              "%s #%ld %s: oracle separated by >= %.17g, library d %.17g signed %.17g intersecting %d", what,
              idx, mn, -o->depth, d, r.signed_distance, r.intersecting);
        /* The best separating axis bounds the distance from below. */
        CHECK(d >= -o->depth - tol, "%s #%ld %s: d %.17g < SAT separation %.17g", what, idx, mn, d,
              -o->depth);
        if (d > 0) {
            px_pose pb2 = moved(pb, r.normal, -0.5 * d);
            px_distance_result r2;
            px_distance(A->c, pa, B->c, &pb2, NULL, NULL, &r2);
            double e = fabs(r2.distance - 0.5 * d);
            if (e / size > g_st.worst_sep) g_st.worst_sep = e / size;
            CHECK(e <= tol, "%s #%ld %s: B moved by -d/2 normal: d %.17g, expected %.17g", what, idx, mn,
                  r2.distance, 0.5 * d);
        }
        return tu_fail_count - before;
    }
    /* Overlapping. */
    double depth = -r.signed_distance;
    CHECK(r.intersecting && r.distance == 0,
          "%s #%ld %s: oracle depth %.17g, library intersecting %d d %.17g", what, idx, mn, o->depth,
          r.intersecting, r.distance);
    double e = fabs(depth - o->depth);
    if (e / size > g_st.worst_depth[method]) g_st.worst_depth[method] = e / size;
    CHECK(e <= tol, "%s #%ld %s: depth %.17g, oracle %.17g (err %.3g size)", what, idx, mn, depth, o->depth,
          e / size);
    double ba = fabs(os_boundary_offset(&A->s, pa, r.point_a)),
           bb = fabs(os_boundary_offset(&B->s, pb, r.point_b));
    if (fmax(ba, bb) / size > g_st.worst_boundary) g_st.worst_boundary = fmax(ba, bb) / size;
    CHECK(ba <= tol && bb <= tol, "%s #%ld %s: witness off the boundary: A %.3g, B %.3g", what, idx, mn, ba,
          bb);
    if (!(depth > 0)) return tu_fail_count - before;
    /* Pushed out along the normal by the depth: touching. */
    px_pose pb_out = moved(pb, r.normal, depth * (1 + 1e-9) + 1e-12 * size);
    px_distance_result r2;
    px_distance(A->c, pa, B->c, &pb_out, NULL, NULL, &r2);
    if (r2.distance / size > g_st.worst_touch) g_st.worst_touch = r2.distance / size;
    os_pen_result o2;
    os_penetration(&A->s, pa, &B->s, &pb_out, &o2);
    /* 2 tol: the push itself overshoots by 1e-9 depth + 1e-12 size. */
    CHECK(r2.distance <= 2 * tol && o2.depth <= tol,
          "%s #%ld %s: pushed out by depth %.17g: distance %.3g, oracle overlap %.3g (size %.3g)", what, idx,
          mn, depth, r2.distance, o2.depth, size);
    if (depth * 1e-6 > 1e-10 * size) {
        px_pose pb_in = moved(pb, r.normal, depth * (1 - 1e-6));
        px_distance(A->c, pa, B->c, &pb_in, NULL, NULL, &r2);
        CHECK(r2.intersecting, "%s #%ld %s: pushed by depth (1 - 1e-6) no longer intersects: d %.3g", what,
              idx, mn, r2.distance);
    }
    return tu_fail_count - before;
}

/* Oracle, the three methods and px_intersect on one pose. */
static void check_pose(const shape *A, const px_pose *pa, const shape *B, const px_pose *pb, const char *what,
                       long idx) {
    os_pen_result o;
    os_penetration(&A->s, pa, &B->s, pb, &o);
    double size = pair_size(A, pa, B, pb), tol = 1e-9 * size;
    g_st.poses++;
    if (fabs(o.depth) <= tol)
        g_st.band++;
    else if (o.separated)
        g_st.separated++;
    else
        g_st.overlapping++;
    int fails = 0;
    for (int m = 0; m < 3; ++m) fails += check_signed(A, pa, B, pb, &o, m, what, idx);
    px_intersect_result ir;
    px_status st = px_intersect(A->c, pa, B->c, pb, NULL, NULL, &ir);
    int inter = ir.intersecting;
    CHECK(st == PX_OK, "%s #%ld: px_intersect status %s", what, idx, px_status_string(st));
    if (fabs(o.depth) > tol) {
        g_st.intersect_checked++;
        CHECK(inter == !o.separated, "%s #%ld: px_intersect %d, oracle depth %.17g", what, idx, inter,
              o.depth);
        fails += inter != !o.separated;
    }
    if (fails) {
        g_st.failed++;
        if (g_st.failed <= 5)
            fprintf(stderr, "  repro: %s #%ld oracle depth %.17g normal (%.17g, %.17g, %.17g)\n", what, idx,
                    o.depth, o.normal.x, o.normal.y, o.normal.z);
    }
}

/* Pose of A (pg_pose_around): random rotation, centre at B's plus `f` times
 * the sum of the radii in a random direction (f < ~0.7 overlaps for most
 * shapes). */
static px_pose place(pg_rng *rng, const px_pose *pb, double reach, double f) {
    return pg_pose_around(rng, pb->t, f * reach);
}

/* Cross-check of the oracle itself: pruned == unpruned axes; separated /
 * overlapping == the brute-force feature oracle; the oracle's own depth and
 * axis push B out (and no less does). */
static void oracle_self_check(const shape *A, const px_pose *pa, const shape *B, const px_pose *pb,
                              long idx) {
    double size = pair_size(A, pa, B, pb), tol = 1e-9 * size;
    os_pen_result o, full;
    os_penetration(&A->s, pa, &B->s, pb, &o);
    os_prune = 0;
    os_penetration(&A->s, pa, &B->s, pb, &full);
    os_prune = 1;
    /* Overlapping: both are the exact depth. Separated: unpruned edge pairs
     * include non-facet axes that may separate better; only the class must
     * agree. */
    if (o.depth > 0 || full.depth > 0)
        CHECK(fabs(o.depth - full.depth) <= 1e-13 * size, "oracle #%ld: pruned %.17g, all axes %.17g", idx,
              o.depth, full.depth);
    else
        CHECK(o.separated && full.separated, "oracle #%ld: pruned %.17g, all axes %.17g", idx, o.depth,
              full.depth);
    or_poly oa, ob;
    if (or_poly_init(&oa, A->c, pa) != 0 || or_poly_init(&ob, B->c, pb) != 0) {
        CHECK(0, "oracle #%ld: or_poly_init failed", idx);
        return;
    }
    if (fabs(o.depth) > tol) {
        or_result r;
        or_distance(&oa, &ob, &r);
        CHECK(r.intersecting == !o.separated,
              "oracle #%ld: SAT depth %.17g, feature oracle intersecting %d d %.17g", idx, o.depth,
              r.intersecting, r.distance);
        if (o.separated)
            CHECK(r.distance >= -o.depth - tol, "oracle #%ld: distance %.17g < SAT separation %.17g", idx,
                  r.distance, -o.depth);
    }
    or_poly_free(&ob);
    if (!o.separated && o.depth > tol) {
        px_pose out = moved(pb, o.normal, o.depth + tol), in = moved(pb, o.normal, o.depth * (1 - 1e-6));
        or_poly_init(&ob, B->c, &out);
        CHECK(!or_intersect(&oa, &ob, NULL), "oracle #%ld: pushing out by its depth %.17g still intersects",
              idx, o.depth);
        or_poly_free(&ob);
        or_poly_init(&ob, B->c, &in);
        CHECK(or_intersect(&oa, &ob, NULL), "oracle #%ld: pushing out by 1 - 1e-6 of its depth separates",
              idx);
        or_poly_free(&ob);
    }
    or_poly_free(&oa);
}

typedef struct pair_def {
    const char *name;
    shape a, b;
} pair_def;

#define NPAIRS 7

static void build_pairs(pair_def *p) {
    pg_rng rng;
    pg_seed(&rng, 7007);
    double xyz[3 * 400], xyz2[3 * 400];
    p[0].name = "ball12 vs ball30";
    pg_points_ball(&rng, 12, 0.5, xyz);
    make_shape(&p[0].a, xyz, 12);
    pg_points_ball(&rng, 30, 0.7, xyz2);
    make_shape(&p[0].b, xyz2, 30);
    p[1].name = "tetra vs sphere40";
    pg_random_tetrahedron(&rng, 0.6, xyz);
    make_shape(&p[1].a, xyz, 4);
    pg_points_sphere(&rng, 40, 0.5, xyz2);
    make_shape(&p[1].b, xyz2, 40);
    p[2].name = "box vs box";
    pg_box(0.5, 0.5, 0.5, xyz);
    make_shape(&p[2].a, xyz, 8);
    pg_box(1.0, 0.25, 0.5, xyz2);
    make_shape(&p[2].b, xyz2, 8);
    p[3].name = "slab vs ball20";
    pg_box(1.0, 1.0, 0.02, xyz);
    make_shape(&p[3].a, xyz, 8);
    pg_points_ball(&rng, 20, 0.4, xyz2);
    make_shape(&p[3].b, xyz2, 20);
    p[4].name = "ellipsoid200 vs ball8";
    pg_points_ellipsoid(&rng, 200, 1.0, 0.6, 0.4, xyz);
    make_shape(&p[4].a, xyz, 200);
    pg_points_ball(&rng, 8, 0.25, xyz2);
    make_shape(&p[4].b, xyz2, 8);
    p[5].name = "cylinder24 vs box";
    pg_cylinder(12, 0.4, 0.6, xyz);
    make_shape(&p[5].a, xyz, 24);
    pg_box(0.3, 0.2, 0.1, xyz2);
    make_shape(&p[5].b, xyz2, 8);
    p[6].name = "tetra vs tetra";
    pg_random_tetrahedron(&rng, 0.5, xyz);
    make_shape(&p[6].a, xyz, 4);
    pg_random_tetrahedron(&rng, 0.4, xyz2);
    make_shape(&p[6].b, xyz2, 4);
}

static void test_random(pair_def *pairs, int want) {
    pg_rng rng;
    pg_seed(&rng, 8008);
    for (int k = 0; k < NPAIRS; ++k) {
        pair_def *P = &pairs[k];
        if (!P->a.c || !P->b.c) continue;
        double reach = P->a.s.radius + P->b.s.radius;
        long overl0 = g_st.overlapping, idx = 0;
        double t0 = tu_now();
        while (g_st.overlapping - overl0 < want && idx < 4L * want) {
            px_pose pb = pg_pose_random(&rng, 2.0);
            /* Mostly overlapping, a fifth reaching into separation. */
            double f = pg_below(&rng, 5) ? pg_range(&rng, 0.0, 0.6) : pg_range(&rng, 0.4, 1.2);
            px_pose pa = place(&rng, &pb, reach, f);
            check_pose(&P->a, &pa, &P->b, &pb, P->name, idx);
            if (idx < 40 && k != 4) oracle_self_check(&P->a, &pa, &P->b, &pb, idx);
            ++idx;
        }
        printf("  %-22s poses %5ld, overlapping %5ld (%.2f s)\n", P->name, idx, g_st.overlapping - overl0,
               tu_now() - t0);
        CHECK(g_st.overlapping - overl0 >= want, "%s: only %ld overlapping poses", P->name,
              g_st.overlapping - overl0);
    }
}

/* --- BAD_INPUTS.md section C --------------------------------------------- */

static px_pose pose_rt(const double r[9], double x, double y, double z) {
    double t[3] = {x, y, z};
    return ta_pose_rt(r, t);
}

/* Touching configurations: |signed| within rounding of 0, finite, PX_OK; the
 * oracle agrees (band), px_intersect says intersecting for exact contacts. */
static void check_touching(const shape *A, const px_pose *pa, const shape *B, const px_pose *pb,
                           const char *what, int exact) {
    double size = pair_size(A, pa, B, pb), tol = 1e-9 * size;
    os_pen_result o;
    os_penetration(&A->s, pa, &B->s, pb, &o);
    CHECK(fabs(o.depth) <= 1e-12 * size, "%s: oracle depth %.17g", what, o.depth);
    for (int m = 0; m < 3; ++m) {
        px_query_options opt = {(uint32_t)m, PX_QUERY_SIGNED, {0}};
        px_distance_result r;
        px_status st = px_distance(A->c, pa, B->c, pb, &opt, NULL, &r);
        CHECK(st == PX_OK && isfinite(r.signed_distance) && pxi_is_finite3(r.point_a) &&
                  pxi_is_finite3(r.point_b) && pxi_is_finite3(r.normal) && fabs(r.signed_distance) <= tol,
              "%s %s: status %s signed %.17g", what, method_names[m], px_status_string(st),
              r.signed_distance);
        if (exact)
            CHECK(r.intersecting && r.signed_distance == 0,
                  "%s %s: exact contact, intersecting %d signed %.17g", what, method_names[m], r.intersecting,
                  r.signed_distance);
    }
    px_intersect_result ir;
    px_status st = px_intersect(A->c, pa, B->c, pb, NULL, NULL, &ir);
    int inter = ir.intersecting;
    CHECK(st == PX_OK && (!exact || inter), "%s: px_intersect %d (exact contact %d)", what, inter, exact);
}

static void test_bad_inputs(void) {
    pg_rng rng;
    pg_seed(&rng, 9009);
    double xyz[3 * 64], I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    shape cube, big, small, hull, slab;
    pg_box(0.5, 0.5, 0.5, xyz);
    make_shape(&cube, xyz, 8);
    pg_box(1.0, 1.0, 1.0, xyz);
    make_shape(&big, xyz, 8);
    pg_points_ball(&rng, 20, 0.1, xyz);
    make_shape(&small, xyz, 20);
    pg_points_sphere(&rng, 30, 0.6, xyz);
    make_shape(&hull, xyz, 30);
    pg_box(0.8, 0.6, 0.01, xyz);
    make_shape(&slab, xyz, 8);
    long before = tu_fail_count;

    /* 14: touching faces, edges, vertices (exact coordinates). */
    px_pose p0 = pose_rt(I, 0, 0, 0);
    px_pose pf = pose_rt(I, 1, 0, 0), pe = pose_rt(I, 1, 1, 0), pv = pose_rt(I, 1, 1, 1);
    px_pose pf2 = pose_rt(I, 1, 0.3, -0.2); /* partial face overlap */
    check_touching(&cube, &p0, &cube, &pf, "touching faces", 1);
    check_touching(&cube, &p0, &cube, &pf2, "touching offset faces", 1);
    check_touching(&cube, &p0, &cube, &pe, "touching edges", 1);
    check_touching(&cube, &p0, &cube, &pv, "touching vertices", 1);
    /* Crossed edges: A turned 45 degrees about x, B about y, stacked. */
    double rx[9], ry[9];
    pg_rot_axis_angle(pxi_v(1, 0, 0), M_PI / 4, rx);
    pg_rot_axis_angle(pxi_v(0, 1, 0), M_PI / 4, ry);
    px_pose pcx = pose_rt(rx, 0, 0, 0), pcy = pose_rt(ry, 0.1, -0.2, sqrt(2.0));
    check_touching(&cube, &pcx, &cube, &pcy, "touching crossed edges", 0);
    /* Touching after a rotation: same random rotation, B one face further. */
    for (int i = 0; i < 20; ++i) {
        px_pose pa = pg_pose_random(&rng, 3.0), pb = pa;
        px_vec3 off = pxi_v(1.0, pg_range(&rng, -0.5, 0.5), pg_range(&rng, -0.5, 0.5));
        pb.t = pxi_add(pa.t, pxi_rot(pa.r, off));
        check_touching(&cube, &pa, &cube, &pb, "touching after rotation", 0);
    }
    /* Nested: a small hull strictly inside the big box; coinciding centres. */
    for (int i = 0; i < 30; ++i) {
        px_pose pb = pg_pose_random(&rng, 1.0);
        px_pose pa = pg_pose_random(&rng, 0);
        pa.t = pxi_add(pb.t, pxi_rot(pb.r, pxi_v(pg_range(&rng, -0.8, 0.8), pg_range(&rng, -0.8, 0.8),
                                                 pg_range(&rng, -0.8, 0.8))));
        check_pose(&small, &pa, &big, &pb, "nested small in big", i);
        check_pose(&big, &pb, &small, &pa, "nested big around small", i);
        px_pose pc = pg_pose_random(&rng, 0);
        pc.t = pb.t;
        check_pose(&hull, &pc, &cube, &pb, "coinciding centres", i);
        check_pose(&slab, &pc, &hull, &pb, "coinciding centres slab", i);
    }
    /* 13: coincident identical bodies (same shape, same pose): must return,
     * with the oracle's depth (the least width of A - A). */
    const shape *same[4] = {&cube, &hull, &slab, &small};
    for (int i = 0; i < 4; ++i) {
        px_pose p = pg_pose_random(&rng, 2.0);
        double t0 = tu_now();
        check_pose(same[i], &p, same[i], &p, "coincident", i);
        CHECK(tu_now() - t0 < 5.0, "coincident #%d took %.2f s", i, tu_now() - t0);
        px_pose q = pose_rt(I, 0, 0, 0);
        check_pose(same[i], &q, same[i], &q, "coincident identity", i);
    }
    /* Huge/tiny pair: a 1e-3 box half inside a face of a 1e3 box, and the
     * same pair at random rotations; then both bodies tiny, both huge. */
    shape huge, tiny;
    pg_box(1e3, 1e3, 1e3, xyz);
    make_shape(&huge, xyz, 8);
    pg_box(1e-3, 1e-3, 1e-3, xyz);
    make_shape(&tiny, xyz, 8);
    px_pose ph = pose_rt(I, 0, 0, 0), pt = pose_rt(I, 1e3, 0.5, -0.25);
    check_pose(&tiny, &pt, &huge, &ph, "tiny on huge face", 0);
    check_pose(&huge, &ph, &tiny, &pt, "huge under tiny", 0);
    for (int i = 0; i < 20; ++i) {
        px_pose pa = pg_pose_random(&rng, 0), pb = pg_pose_random(&rng, 0);
        pa.t = pxi_scale(pg_unit(&rng), pg_range(&rng, 0, 1.5e-3));
        check_pose(&tiny, &pa, &tiny, &pb, "tiny pair", i);
        pa.t = pxi_scale(pg_unit(&rng), pg_range(&rng, 0, 1.5e3));
        check_pose(&huge, &pa, &huge, &pb, "huge pair", i);
        pa.t = pxi_add(pb.t, pxi_rot(pb.r, pxi_v(1e3 - 1e-3 * pg_range(&rng, 0, 2), 0.1 * i, -5.0 * i)));
        check_pose(&tiny, &pa, &huge, &pb, "tiny at huge face", i);
    }
    printf("  section C cases: %ld failed checks\n", (long)(tu_fail_count - before));
    free_shape(&huge);
    free_shape(&tiny);
    free_shape(&cube);
    free_shape(&big);
    free_shape(&small);
    free_shape(&hull);
    free_shape(&slab);
}

int main(void) {
    tu_init("test_penetration");
    double t0 = tu_now();
    pair_def pairs[NPAIRS];
    memset(pairs, 0, sizeof pairs);
    build_pairs(pairs);
    int want = tu_scaled(tu_sanitized() ? 300 : 1000);
    test_random(pairs, want);
    test_bad_inputs();
    for (int k = 0; k < NPAIRS; ++k) {
        if (pairs[k].a.c) free_shape(&pairs[k].a);
        if (pairs[k].b.c) free_shape(&pairs[k].b);
    }
    printf(
        "  poses %ld (overlapping %ld, separated %ld, touching band %ld), signed queries %ld, failed poses "
        "%ld\n",
        g_st.poses, g_st.overlapping, g_st.separated, g_st.band, g_st.queries, g_st.failed);
    for (int m = 0; m < 3; ++m)
        printf("  %-9s worst |depth - oracle| / size %.3g, fallbacks %ld, time %.2f s\n", method_names[m],
               g_st.worst_depth[m], g_st.fallbacks[m], g_st.time[m]);
    printf("  worst: push-out distance / size %.3g, witness off boundary / size %.3g, -d/2 move / size %.3g; "
           "px_intersect checked %ld\n",
           g_st.worst_touch, g_st.worst_boundary, g_st.worst_sep, g_st.intersect_checked);
    printf("  time %.2f s\n", tu_now() - t0);
    return tu_finish();
}
