/* px_translation against the brute-force half-space oracle (oracle_sat.h).
 *
 * Random pairs from a pool (hulls of 4 to 30 points, tetrahedra, boxes,
 * thin slabs) with A placed from deep overlap (answers tau < 0) to well
 * separated, and directions towards B, away from it (hits behind A) and at
 * random (misses), of lengths 1e-3 .. 1e3: >= 2,000 queries per run.
 * Every query:
 *   - hit/miss agrees with the oracle outside a 1e-9 * size band of grazing
 *     (size = |t_a - t_b| + R_A + R_B);
 *   - hit: tau * |d| within 1e-9 * size of the oracle; independently, A
 *     translated by tau d is touching (px_distance <= 1e-9 size) and by
 *     (tau - 1e-6 size / |d|) d it is separated (least tau); contact points
 *     coincide, the normal is unit and faces along d;
 *   - miss: the witness normal is unit and orthogonal to d, gap =
 *     normal . (point_b - point_a) > 0 and at least the oracle's separation,
 *     and by brute force every vertex of A is below point_a's plane and
 *     every vertex of B above point_b's.
 * Incremental: sequences of 100 small moves with a warm cache give the same
 * answers as cold queries. Bad inputs: zero, NaN and infinite directions,
 * lengths 1e-200 and 1e200 (tau scales), directions grazing faces of both
 * bodies, coincident bodies. */
#include <float.h>

#include "access.h"
#include "math/vec3.h"
#include "oracle_sat.h"
#include "px_gen.h"
#include "test_util.h"

typedef struct shape {
    px_convex *c;
    os_shape s;
    const char *kind;
} shape;

#define POOL 40
static shape g_pool[POOL];

typedef struct stats {
    long queries, hits, misses, band, negative_tau, failed, warm, oracle_hits, oracle_misses;
    double worst_tau, worst_touch, worst_gap, worst_warm, worst_normal;
    double time;
} stats;
static stats g_st;

/* |v| without overflow or underflow (directions of length 1e200, 1e-200). */
static double safe_len(px_vec3 v) {
    double m = fmax(fabs(v.x), fmax(fabs(v.y), fabs(v.z)));
    if (!(m > 0)) return 0;
    int e = ilogb(m);
    return ldexp(pxi_len(pxi_scale(v, ldexp(1.0, -e))), e);
}

static int make_shape(shape *out, const double *xyz, size_t n, const char *kind) {
    px_error err;
    out->kind = kind;
    out->c = px_convex_create(xyz, n, NULL, &err);
    CHECK(out->c != NULL, "hull failed: %s", err.message);
    if (!out->c) return -1;
    int r = os_shape_init(&out->s, out->c);
    CHECK(r == 0, "oracle shape init failed");
    return r;
}

static void free_shape(shape *s) {
    if (!s->c) return;
    os_shape_free(&s->s);
    px_convex_destroy(s->c);
    s->c = NULL;
}

static void build_pool(void) {
    pg_rng rng;
    pg_seed(&rng, 5005);
    double xyz[3 * 64];
    for (int i = 0; i < POOL; ++i) {
        double h = 0.5 * pg_range(&rng, 0.3, 2.0);
        switch (i % 5) {
        case 0:
        case 1: {
            size_t n = pg_log_int(&rng, 4, 30);
            if (n < 8) {
                pg_random_tetrahedron(&rng, h, xyz);
                n = 4;
            } else {
                pg_points_ball(&rng, n, h, xyz);
            }
            make_shape(&g_pool[i], xyz, n, n == 4 ? "tetra" : "hull");
            break;
        }
        case 2: {
            size_t n = 12 + pg_below(&rng, 19);
            pg_points_sphere(&rng, n, h, xyz);
            make_shape(&g_pool[i], xyz, n, "hull");
            break;
        }
        case 3:
            pg_box(h * pg_range(&rng, 0.1, 1), h * pg_range(&rng, 0.1, 1), h * pg_range(&rng, 0.1, 1), xyz);
            make_shape(&g_pool[i], xyz, 8, "box");
            break;
        default:
            if (pg_below(&rng, 2)) {
                pg_box(h, h * pg_range(&rng, 0.3, 1), h / 50, xyz);
                make_shape(&g_pool[i], xyz, 8, "slab box");
            } else {
                pg_points_in_box(&rng, 20, h, h, h / 50, xyz);
                make_shape(&g_pool[i], xyz, 20, "slab");
            }
            break;
        }
    }
}

static px_pose moved(const px_pose *p, px_vec3 d, double tau) {
    px_pose q = *p;
    q.t = pxi_madd(q.t, d, tau);
    return q;
}

/* One query checked against the oracle and by the distance test. Returns
 * the number of failed checks; *out receives the result. */
static int check_query(const shape *A, const px_pose *pa, const shape *B, const px_pose *pb, px_vec3 d,
                       px_pair_cache *cache, const char *what, long idx, px_translate_result *out) {
    int before = tu_fail_count;
    double size = pxi_len(pxi_sub(pa->t, pb->t)) + A->s.radius + B->s.radius, tol = 1e-9 * size;
    double dl = safe_len(d);
    px_translate_result r;
    double t0 = tu_now();
    px_status st = px_translate(A->c, pa, B->c, pb, d, &tu_both_ways, cache, &r);
    g_st.time += tu_now() - t0;
    g_st.queries++;
    if (out) *out = r;
    CHECK(st == PX_OK, "%s #%ld: status %s", what, idx, px_status_string(st));
    int fin = isfinite(r.tau) && isfinite(r.gap) && pxi_is_finite3(r.point_a) && pxi_is_finite3(r.point_b) &&
              pxi_is_finite3(r.normal);
    CHECK(fin, "%s #%ld: non-finite result", what, idx);
    if (st != PX_OK || !fin) return tu_fail_count - before;
    os_tr_result o;
    os_translation(&A->s, pa, &B->s, pb, d, &o);
    int decided = fabs(o.gap) > tol;
    if (!decided)
        g_st.band++;
    else if (o.hit)
        g_st.oracle_hits++;
    else
        g_st.oracle_misses++;
    if (decided) {
        /* Oracle self-consistency: the interval test and the projected
         * polygon test classify alike. */
        CHECK(o.hit == (o.gap < 0), "%s #%ld: oracle interval hit %d but perpendicular gap %.17g", what, idx,
              o.hit, o.gap);
        CHECK(r.hit == o.hit, "%s #%ld: hit %d, oracle %d (oracle gap %.3g, tau %.17g)", what, idx, r.hit,
              o.hit, o.gap, o.tau_min);
    }
    if (r.hit) {
        g_st.hits++;
        if (r.tau < 0) g_st.negative_tau++;
        if (decided && o.hit) {
            double e = fabs(r.tau - o.tau_min) * dl;
            if (e / size > g_st.worst_tau) g_st.worst_tau = e / size;
            CHECK(e <= tol, "%s #%ld: tau %.17g, oracle %.17g (err %.3g size)", what, idx, r.tau, o.tau_min,
                  e / size);
        }
        /* Independent of the oracle: touching at tau, separated just before. */
        px_pose pt = moved(pa, d, r.tau);
        px_distance_result dr;
        px_distance(A->c, &pt, B->c, pb, NULL, NULL, &dr);
        if (dr.distance / size > g_st.worst_touch) g_st.worst_touch = dr.distance / size;
        CHECK(dr.distance <= tol, "%s #%ld: A at tau %.17g is at distance %.3g (size %.3g)", what, idx, r.tau,
              dr.distance, size);
        if (decided) {
            px_pose pe = moved(pa, d, r.tau - 1e-6 * size / dl);
            px_distance(A->c, &pe, B->c, pb, NULL, NULL, &dr);
            CHECK(dr.distance > 0 && !dr.intersecting,
                  "%s #%ld: A at tau - 1e-6 size/|d| intersects: tau %.17g", what, idx, r.tau);
        }
        CHECK(pxi_len(pxi_sub(r.point_a, r.point_b)) <= tol, "%s #%ld: contact points %.3g apart", what, idx,
              pxi_len(pxi_sub(r.point_a, r.point_b)));
        double nl = pxi_len(r.normal);
        CHECK(fabs(nl - 1) <= 1e-12 && pxi_dot(r.normal, d) / dl >= -1e-9,
              "%s #%ld: contact normal |n| %.17g, n . d/|d| %.3g", what, idx, nl, pxi_dot(r.normal, d) / dl);
        /* The contact normal separates A at tau from B (brute force over
         * the vertices): the closest points' direction a rounding away from
         * contact had turned it by up to 1e-3 rad on cubes. */
        double wa = -1e300, wb = 1e300;
        for (uint32_t i = 0; i < A->s.nv; ++i) wa = fmax(wa, pxi_dot(r.normal, pxi_xform(&pt, A->s.v[i])));
        for (uint32_t i = 0; i < B->s.nv; ++i) wb = fmin(wb, pxi_dot(r.normal, pxi_xform(pb, B->s.v[i])));
        if ((wa - wb) / size > g_st.worst_normal) g_st.worst_normal = (wa - wb) / size;
        CHECK(wa - wb <= 256 * DBL_EPSILON * size,
              "%s #%ld: contact normal does not separate: overlap %.3g size", what, idx, (wa - wb) / size);
    } else {
        g_st.misses++;
        double nl = pxi_len(r.normal);
        double nd = pxi_dot(r.normal, pxi_scale(d, 1.0 / dl));
        CHECK(fabs(nl - 1) <= 1e-12 && fabs(nd) <= 1e-9, "%s #%ld: miss normal |n| %.17g, n . d/|d| %.3g",
              what, idx, nl, nd);
        double g = pxi_dot(r.normal, pxi_sub(r.point_b, r.point_a));
        CHECK(r.gap > 0 && fabs(g - r.gap) <= tol, "%s #%ld: gap %.17g, normal . (pb - pa) %.17g", what, idx,
              r.gap, g);
        if (decided && !o.hit) {
            /* The oracle's separation is a lower bound of the largest gap
             * (the closest points' gap). */
            if (o.gap - r.gap > g_st.worst_gap * size) g_st.worst_gap = (o.gap - r.gap) / size;
            CHECK(r.gap >= o.gap - tol, "%s #%ld: gap %.17g below the oracle's separation %.17g", what, idx,
                  r.gap, o.gap);
        }
        /* The witness by brute force over the vertices. */
        double ha = pxi_dot(r.normal, r.point_a), hb = pxi_dot(r.normal, r.point_b), wa = -1e300, wb = 1e300;
        for (uint32_t i = 0; i < A->s.nv; ++i) wa = fmax(wa, pxi_dot(r.normal, pxi_xform(pa, A->s.v[i])));
        for (uint32_t i = 0; i < B->s.nv; ++i) wb = fmin(wb, pxi_dot(r.normal, pxi_xform(pb, B->s.v[i])));
        CHECK(wa <= ha + tol && wb >= hb - tol, "%s #%ld: witness violated: A above by %.3g, B below by %.3g",
              what, idx, wa - ha, hb - wb);
    }
    int fails = tu_fail_count - before;
    if (fails) {
        g_st.failed++;
        if (g_st.failed <= 5)
            fprintf(stderr,
                    "  repro: %s #%ld A=%s B=%s d=(%.17g, %.17g, %.17g); oracle hit %d tau %.17g gap %.3g; "
                    "library hit %d tau %.17g gap %.3g\n",
                    what, idx, A->kind, B->kind, d.x, d.y, d.z, o.hit, o.tau_min, o.gap, r.hit, r.tau, r.gap);
    }
    return fails;
}

/* Random direction scaled to a log-uniform length in [1e-3, 1e3]. */
static px_vec3 scaled_dir(pg_rng *rng, px_vec3 v) {
    double l = pxi_len(v);
    if (!(l > 0)) v = pg_unit(rng), l = 1;
    return pxi_scale(v, pow(10.0, pg_range(rng, -3, 3)) / l);
}

static px_vec3 pick_direction(pg_rng *rng, const px_pose *pa, const px_pose *pb, double reach) {
    px_vec3 to_b = pxi_sub(pb->t, pa->t);
    px_vec3 noise = pxi_scale(pg_unit(rng), pg_range(rng, 0, 0.8) * reach);
    switch (pg_below(rng, 10)) {
    case 0:
    case 1:
    case 2:
    case 3: return scaled_dir(rng, pxi_add(to_b, noise)); /* towards B: mostly hits */
    case 4:
    case 5: return scaled_dir(rng, pxi_sub(noise, to_b)); /* away: hits behind A (tau < 0) */
    default: return scaled_dir(rng, pg_unit(rng));        /* random: hits and misses */
    }
}

static void test_random(int count) {
    pg_rng rng;
    pg_seed(&rng, 6006);
    for (int i = 0; i < count; ++i) {
        const shape *A = &g_pool[pg_below(&rng, POOL)], *B = &g_pool[pg_below(&rng, POOL)];
        if (!A->c || !B->c) continue;
        double reach = A->s.radius + B->s.radius;
        px_pose pb = pg_pose_random(&rng, 2.0), pa = pg_pose_random(&rng, 0);
        /* From deep overlap (f < 0.5) to well separated (f up to 2.5). */
        pa.t = pxi_add(pb.t, pxi_scale(pg_unit(&rng), pg_range(&rng, 0, 2.5) * reach));
        px_vec3 d = pick_direction(&rng, &pa, &pb, reach);
        px_pair_cache cache;
        memset(&cache, 0, sizeof cache);
        check_query(A, &pa, B, &pb, d, (i & 1) ? &cache : NULL, "random", i, NULL);
    }
}

/* Sequences of 100 small moves (A rotates and slides, B spins, the
 * direction turns slowly) with one warm cache: each answer equals the cold
 * one; every fifth step is also checked against the oracle. */
static void test_incremental(int sequences) {
    pg_rng rng;
    pg_seed(&rng, 6116);
    long idx = 0;
    for (int s = 0; s < sequences; ++s) {
        const shape *A = &g_pool[pg_below(&rng, POOL)], *B = &g_pool[pg_below(&rng, POOL)];
        if (!A->c || !B->c) continue;
        double reach = A->s.radius + B->s.radius;
        px_pose pb = pg_pose_random(&rng, 2.0), pa = pg_pose_random(&rng, 0);
        pa.t = pxi_add(pb.t, pxi_scale(pg_unit(&rng), pg_range(&rng, 0.3, 2.0) * reach));
        px_vec3 d = pick_direction(&rng, &pa, &pb, reach);
        px_vec3 step = pxi_scale(pg_unit(&rng), reach * pow(10.0, pg_range(&rng, -3, -1.5)));
        double ra[9], rb[9], rd[9];
        pg_rot_axis_angle(pg_unit(&rng), pg_range(&rng, 0.001, 0.05), ra);
        pg_rot_axis_angle(pg_unit(&rng), pg_range(&rng, 0.0, 0.02), rb);
        pg_rot_axis_angle(pg_unit(&rng), pg_range(&rng, 0.0, 0.02), rd);
        px_pair_cache cache;
        memset(&cache, 0, sizeof cache);
        for (int k = 0; k < 100; ++k, ++idx) {
            double size = pxi_len(pxi_sub(pa.t, pb.t)) + reach, tol = 1e-9 * size;
            px_translate_result warm, cold;
            if (k % 5 == 0) {
                check_query(A, &pa, B, &pb, d, &cache, "incremental", idx, &warm);
            } else {
                px_status st = px_translate(A->c, &pa, B->c, &pb, d, &tu_both_ways, &cache, &warm);
                g_st.queries++;
                CHECK(st == PX_OK, "incremental #%ld: status %s", idx, px_status_string(st));
            }
            px_status st = px_translate(A->c, &pa, B->c, &pb, d, &tu_both_ways, NULL, &cold);
            g_st.queries++;
            g_st.warm++;
            CHECK(st == PX_OK, "incremental cold #%ld: status %s", idx, px_status_string(st));
            double dl = pxi_len(d);
            if (warm.hit == cold.hit) {
                double e = warm.hit ? fabs(warm.tau - cold.tau) * dl : fabs(warm.gap - cold.gap);
                if (e / size > g_st.worst_warm) g_st.worst_warm = e / size;
                CHECK(e <= tol, "incremental #%ld: warm %s %.17g, cold %.17g", idx, warm.hit ? "tau" : "gap",
                      warm.hit ? warm.tau : warm.gap, cold.hit ? cold.tau : cold.gap);
            } else {
                /* Only a grazing line may be classified differently. */
                os_tr_result o;
                os_translation(&A->s, &pa, &B->s, &pb, d, &o);
                CHECK(fabs(o.gap) <= tol, "incremental #%ld: warm hit %d, cold hit %d, oracle gap %.3g", idx,
                      warm.hit, cold.hit, o.gap);
            }
            pg_mat_mul(ra, pa.r, pa.r);
            pg_rot_orthonormalize(pa.r);
            pa.t = pxi_add(pa.t, step);
            pg_mat_mul(rb, pb.r, pb.r);
            pg_rot_orthonormalize(pb.r);
            d = pxi_rot(rd, d);
        }
    }
}

static px_pose pose_at(double x, double y, double z) {
    px_pose p = px_pose_identity();
    p.t = pxi_v(x, y, z);
    return p;
}

static void test_bad_inputs(void) {
    long before = tu_fail_count;
    pg_rng rng;
    pg_seed(&rng, 6226);
    double xyz[3 * 32];
    shape box, hull;
    pg_box(1, 1, 1, xyz);
    make_shape(&box, xyz, 8, "box");
    pg_points_sphere(&rng, 24, 0.8, xyz);
    make_shape(&hull, xyz, 24, "hull");
    px_pose pa = pose_at(-5, 0.2, 0.1), pb = pose_at(0, 0, 0);
    px_translate_result r;
    px_pair_cache cache;
    memset(&cache, 0, sizeof cache);

    /* Invalid directions: status, and the cache untouched. */
    px_pair_cache c0 = cache;
    px_status st = px_translate(box.c, &pa, box.c, &pb, pxi_v(0, 0, 0), &tu_both_ways, &cache, &r);
    CHECK(st == PX_ERR_INVALID_ARGUMENT, "zero direction: %s", px_status_string(st));
    st = px_translate(box.c, &pa, box.c, &pb, pxi_v(-0.0, 0.0, -0.0), &tu_both_ways, &cache, &r);
    CHECK(st == PX_ERR_INVALID_ARGUMENT, "negative zero direction: %s", px_status_string(st));
    st = px_translate(box.c, &pa, box.c, &pb, pxi_v(1, NAN, 0), &tu_both_ways, &cache, &r);
    CHECK(st == PX_ERR_NON_FINITE, "NaN direction: %s", px_status_string(st));
    st = px_translate(box.c, &pa, box.c, &pb, pxi_v(INFINITY, 0, 0), &tu_both_ways, &cache, &r);
    CHECK(st == PX_ERR_NON_FINITE, "infinite direction: %s", px_status_string(st));
    st = px_translate(box.c, &pa, box.c, &pb, pxi_v(1, 0, 0), &tu_both_ways, &cache, NULL);
    CHECK(st == PX_ERR_INVALID_ARGUMENT, "NULL result: %s", px_status_string(st));
    CHECK(memcmp(&c0, &cache, sizeof cache) == 0, "a failed query changed the cache");

    /* Direction lengths 1e-200 .. 1e200: tau scales as 1 / |d| (tau d is the
     * same translation). */
    const double lens[] = {1e-200, 1e-100, 1e-3, 1.0, 7.5, 1e100, 1e200};
    for (int k = 0; k < 10; ++k) {
        px_pose qa = pg_pose_random(&rng, 0), qb = pg_pose_random(&rng, 1.0);
        qa.t = pxi_add(qb.t, pxi_scale(pg_unit(&rng), pg_range(&rng, 0, 4)));
        px_vec3 u = pxi_add(pxi_sub(qb.t, qa.t), pxi_scale(pg_unit(&rng), 0.5));
        u = pxi_scale(u, 1.0 / pxi_len(u));
        px_translate_result r1;
        check_query(&hull, &qa, &box, &qb, u, NULL, "unit direction", k, &r1);
        double size = pxi_len(pxi_sub(qa.t, qb.t)) + hull.s.radius + box.s.radius;
        for (size_t j = 0; j < sizeof lens / sizeof lens[0]; ++j) {
            px_vec3 d = pxi_scale(u, lens[j]);
            px_translate_result rk;
            check_query(&hull, &qa, &box, &qb, d, NULL, "scaled direction", (long)(10 * k + (int)j), &rk);
            CHECK(rk.hit == r1.hit && (!r1.hit || fabs(rk.tau * lens[j] - r1.tau) <= 1e-9 * size),
                  "length %.0e: hit %d tau*|d| %.17g, unit: hit %d tau %.17g", lens[j], rk.hit,
                  rk.tau * lens[j], r1.hit, r1.tau);
        }
    }

    /* Grazing: the direction is parallel to a face of both boxes. A slides
     * along x over B's top face: exactly touching (hit at tau 3, the x
     * extents meet), slightly overlapping in z (hit at 3), clearly above
     * (miss, gap 0.5, normal -z). */
    px_pose g0 = pose_at(-5, 0.3, 2), g1 = pose_at(-5, 0.3, 1.999), g2 = pose_at(-5, 0.3, 2.5);
    px_vec3 dx = pxi_v(1, 0, 0);
    check_query(&box, &g0, &box, &pb, dx, NULL, "grazing touching", 0, &r);
    CHECK(r.hit && fabs(r.tau - 3) <= 1e-12, "grazing touching: hit %d tau %.17g (expected 3)", r.hit, r.tau);
    check_query(&box, &g1, &box, &pb, dx, NULL, "grazing overlap", 0, &r);
    CHECK(r.hit && fabs(r.tau - 3) <= 1e-12, "grazing overlap: hit %d tau %.17g (expected 3)", r.hit, r.tau);
    check_query(&box, &g2, &box, &pb, dx, NULL, "grazing miss", 0, &r);
    CHECK(!r.hit && fabs(r.gap - 0.5) <= 1e-12 && fabs(r.normal.z + 1) <= 1e-12,
          "grazing miss: hit %d gap %.17g normal (%.3g, %.3g, %.3g)", r.hit, r.gap, r.normal.x, r.normal.y,
          r.normal.z);
    check_query(&box, &g0, &box, &pb, pxi_v(-1e-200, 0, 0), NULL, "grazing backwards", 0, &r);
    CHECK(r.hit && fabs(r.tau * 1e-200 + 7) <= 1e-12,
          "grazing backwards: hit %d tau * 1e-200 %.17g (expected -7)", r.hit, r.tau * 1e-200);
    /* The same under random rigid motions of the whole scene: rounding may
     * decide touching either way, but a hit must be at tau 3 and a miss must
     * have a rounding-sized gap. */
    for (int k = 0; k < 20; ++k) {
        px_pose g = pg_pose_random(&rng, 3.0), qa = g0, qb = pb;
        pg_mat_mul(g.r, g0.r, qa.r);
        pg_mat_mul(g.r, pb.r, qb.r);
        qa.t = pxi_xform(&g, g0.t);
        qb.t = pxi_xform(&g, pb.t);
        px_vec3 d = pxi_rot(g.r, dx);
        check_query(&box, &qa, &box, &qb, d, NULL, "grazing rotated", k, &r);
        CHECK(r.hit ? fabs(r.tau - 3) <= 1e-9 : r.gap <= 1e-9,
              "grazing rotated #%d: hit %d tau %.17g gap %.3g", k, r.hit, r.tau, r.gap);
    }

    /* Coincident bodies: the same shape at the same pose; every direction
     * hits, with tau < 0 (A must move back to just touch). */
    const shape *same[2] = {&box, &hull};
    for (int k = 0; k < 20; ++k) {
        const shape *S = same[k & 1];
        px_pose p = pg_pose_random(&rng, 2.0);
        check_query(S, &p, S, &p, scaled_dir(&rng, pg_unit(&rng)), NULL, "coincident", k, &r);
        CHECK(r.hit && r.tau < 0, "coincident #%d: hit %d tau %.17g", k, r.hit, r.tau);
    }
    printf("  bad inputs: %ld failed checks\n", (long)(tu_fail_count - before));
    free_shape(&box);
    free_shape(&hull);
}

int main(void) {
    tu_init("test_translation");
    double t0 = tu_now();
    build_pool();
    int count = tu_scaled(tu_sanitized() ? 1000 : 2500), seq = tu_scaled(tu_sanitized() ? 8 : 20);
    test_random(count);
    long random_queries = g_st.queries;
    test_incremental(seq);
    test_bad_inputs();
    for (int i = 0; i < POOL; ++i) free_shape(&g_pool[i]);
    printf(
        "  queries %ld (random %ld, incremental %d x 100 warm + cold), hits %ld (tau < 0: %ld), misses %ld, "
        "grazing band %ld, failed %ld\n",
        g_st.queries, random_queries, seq, g_st.hits, g_st.negative_tau, g_st.misses, g_st.band, g_st.failed);
    printf(
        "  worst / size: |tau - oracle| |d| %.3g, distance at tau %.3g, gap below oracle %.3g, warm vs cold "
        "%.3g, contact normal overlap %.3g\n",
        g_st.worst_tau, g_st.worst_touch, g_st.worst_gap, g_st.worst_warm, g_st.worst_normal);
    printf("  time: px_translation %.3f s, total %.2f s\n", g_st.time, tu_now() - t0);
    CHECK(tu_scale() < 1 || g_st.queries >= 2000, "only %ld queries", g_st.queries);
    return tu_finish();
}
