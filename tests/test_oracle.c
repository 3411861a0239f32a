/* Unit test of the brute-force oracle (tests/oracle.c) itself, before it is
 * trusted to judge the library: closed-form primitive cases, then random
 * hull pairs against the exact distance of CGAL Polytope_distance_d
 * (pxcd_exact_distance, Homogeneous<Gmpzf>). Hulls come straight from
 * pxcd_hull_compute, so this test does not depend on px_convex. */
#include "oracle.h"
#include "px_gen.h"
#include "pxcd.h"
#include "test_util.h"

static px_vec3 P(double x, double y, double z) {
    px_vec3 p = {x, y, z};
    return p;
}

static double dist(px_vec3 a, px_vec3 b) {
    double x = a.x - b.x, y = a.y - b.y, z = a.z - b.z;
    return sqrt(x * x + y * y + z * z);
}

static void test_primitives(void) {
    /* point-segment */
    CHECK(or_pt_seg(P(0, 1, 0), P(-1, 0, 0), P(1, 0, 0), NULL) == 1.0, "interior projection");
    CHECK(or_pt_seg(P(4, 4, 0), P(-1, 0, 0), P(1, 0, 0), NULL) == 5.0, "beyond the head");
    CHECK(or_pt_seg(P(0, 2, 0), P(1, 1, 1), P(1, 1, 1), NULL) == sqrt(3.0), "zero-length segment");
    /* skew segments crossing at distance 1 */
    CHECK(or_seg_seg(P(-1, 0, 0), P(1, 0, 0), P(0, -1, 1), P(0, 1, 1), NULL, NULL) == 1.0, "skew");
    /* parallel, overlapping: distance 1 */
    CHECK(or_seg_seg(P(0, 0, 0), P(2, 0, 0), P(1, 1, 0), P(3, 1, 0), NULL, NULL) == 1.0, "parallel overlap");
    /* parallel, disjoint along the line */
    CHECK(fabs(or_seg_seg(P(0, 0, 0), P(1, 0, 0), P(4, 4, 0), P(5, 4, 0), NULL, NULL) - 5.0) < 1e-15,
          "parallel apart");
    /* nearly parallel (1e-9 rad) crossing in projection, height h */
    for (int k = 0; k < 4; ++k) {
        double a = 1e-9 * (k + 1), h = pow(10.0, -2.0 - 3.0 * k);
        double d =
            or_seg_seg(P(-1, 0, 0), P(1, 0, 0), P(-cos(a), -sin(a), h), P(cos(a), sin(a), h), NULL, NULL);
        CHECK(fabs(d - h) <= 1e-15, "near-parallel crossing: d=%.17g h=%.17g", d, h);
    }
    /* segments touching at a point */
    CHECK(or_seg_seg(P(0, 0, 0), P(1, 1, 1), P(1, 1, 1), P(2, 0, 0), NULL, NULL) == 0.0, "touching");

    /* A unit cube [0,1]^3 from raw faces. */
    static const double cube[24] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 0, 1, 1, 0, 1, 0, 1, 1, 1, 1, 1};
    static const uint32_t ff[7] = {0, 4, 8, 12, 16, 20, 24};
    static const uint32_t fv[24] = {
        0, 2, 3, 1, /* z = 0, normal -z */
        4, 5, 7, 6, /* z = 1 */
        0, 1, 5, 4, /* y = 0 */
        2, 6, 7, 3, /* y = 1 */
        0, 4, 6, 2, /* x = 0 */
        1, 3, 7, 5  /* x = 1 */
    };
    or_poly c;
    CHECK(or_poly_init_raw(&c, cube, 8, ff, fv, 6) == 0, "cube init");
    CHECK(c.ne == 12, "cube edges %u", c.ne);
    for (uint32_t f = 0; f < 6; ++f) {
        double s = c.fn[f].x + c.fn[f].y + c.fn[f].z;
        CHECK(fabs(fabs(s) - 1) == 0, "axis normal");
    }
    CHECK(or_point_depth(&c, P(0.5, 0.5, 0.5)) == -0.5, "centre depth");
    CHECK(or_point_depth(&c, P(0.5, 0.5, 3)) == 2.0, "above");
    CHECK(or_pt_face(P(0.5, 0.5, 3), &c, 1, NULL) == 2.0, "above top face");
    CHECK(or_pt_face(P(4, 5, 1), &c, 1, NULL) == 5.0, "beside the top face");
    CHECK(or_seg_face(P(0.5, 0.5, -1), P(0.5, 0.5, 2), &c, 1, NULL, NULL) == 0.0, "pierce");
    CHECK(or_seg_face(P(3, 0.5, 2), P(3, 0.5, 5), &c, 1, NULL, NULL) == sqrt(5.0), "segment beside");
    /* A second cube shifted by (0.25, 0.5, 1 + g): face-face gap g. */
    double cube2[24];
    for (int i = 0; i < 8; ++i) {
        cube2[3 * i] = cube[3 * i] + 0.25;
        cube2[3 * i + 1] = cube[3 * i + 1] + 0.5;
        cube2[3 * i + 2] = cube[3 * i + 2] + 1.125;
    }
    or_poly c2;
    CHECK(or_poly_init_raw(&c2, cube2, 8, ff, fv, 6) == 0, "cube2 init");
    or_result r;
    or_distance(&c2, &c, &r);
    CHECK(r.distance == 0.125 && !r.intersecting, "stacked cubes d=%.17g", r.distance);
    CHECK(or_face_face(&c2, 0, &c, 1, NULL, NULL) == 0.125, "face-face gap");
    /* Touching exactly: gap 0 -> intersecting with margin 0. */
    for (int i = 0; i < 8; ++i) cube2[3 * i + 2] -= 0.125;
    or_poly_free(&c2);
    CHECK(or_poly_init_raw(&c2, cube2, 8, ff, fv, 6) == 0, "cube2 init");
    or_distance(&c2, &c, &r);
    CHECK(r.intersecting && r.margin == 0 && r.distance == 0, "touching cubes");
    /* Overlapping: margin > 0. */
    for (int i = 0; i < 8; ++i) cube2[3 * i + 2] -= 0.5;
    or_poly_free(&c2);
    CHECK(or_poly_init_raw(&c2, cube2, 8, ff, fv, 6) == 0, "cube2 init");
    or_distance(&c2, &c, &r);
    CHECK(r.intersecting && r.margin > 0.2, "overlapping cubes margin %g", r.margin);
    /* One inside the other: small cube in the middle. */
    for (int i = 0; i < 24; ++i) cube2[i] = 0.4 + 0.2 * cube[i];
    or_poly_free(&c2);
    CHECK(or_poly_init_raw(&c2, cube2, 8, ff, fv, 6) == 0, "cube2 init");
    or_distance(&c2, &c, &r);
    CHECK(r.intersecting && fabs(r.margin - 0.4) < 1e-15, "contained cube, margin %g", r.margin);
    or_poly_free(&c2);
    or_poly_free(&c);
}

/* Builds an oracle polytope from the hull of points (common frame). */
static int hull_poly(const double *xyz, size_t n, or_poly *p, double **verts, size_t *nv) {
    pxcd_hull *h = NULL;
    int dim = -1;
    char msg[256];
    if (pxcd_hull_compute(xyz, n, &h, &dim, msg, sizeof msg) != PXCD_OK) return -1;
    uint32_t *ff = malloc((h->face_count + 1) * sizeof *ff);
    for (size_t f = 0; f <= h->face_count; ++f) ff[f] = (uint32_t)h->face_offsets[f];
    int rc = or_poly_init_raw(p, h->vertices, (uint32_t)h->vertex_count, ff, h->face_indices,
                              (uint32_t)h->face_count);
    *nv = h->vertex_count;
    *verts = malloc(3 * h->vertex_count * sizeof **verts);
    memcpy(*verts, h->vertices, 3 * h->vertex_count * sizeof **verts);
    free(ff);
    pxcd_hull_free(h);
    return rc;
}

static void test_random_vs_exact(int pairs) {
    pg_rng rng;
    pg_seed(&rng, 0x0ac1e5eedULL);
    double *pa = malloc(3 * 2000 * sizeof *pa), *pb = malloc(3 * 2000 * sizeof *pb);
    int compared = 0, band = 0, inter = 0;
    double worst = 0;
    for (int it = 0; it < pairs; ++it) {
        pg_kind ka = (pg_kind)pg_below(&rng, PG_KIND_COUNT), kb = (pg_kind)pg_below(&rng, PG_KIND_COUNT);
        size_t na = pg_log_int(&rng, 8, it % 50 == 0 ? 1000 : 40);
        size_t nb = pg_log_int(&rng, 8, 40);
        double sa = pg_range(&rng, 0.5, 2), sb = pg_range(&rng, 0.5, 2);
        na = pg_shape(&rng, ka, na, sa, pa);
        nb = pg_shape(&rng, kb, nb, sb, pb);
        /* Pose A relative to B (common frame = B's). */
        double r[9];
        pg_rot_random(&rng, r);
        px_vec3 dir = pg_unit(&rng);
        double gap = pg_range(&rng, 0.0, 1.2) * 0.5 * (sa + sb);
        for (size_t i = 0; i < na; ++i) {
            double x = pa[3 * i], y = pa[3 * i + 1], z = pa[3 * i + 2];
            pa[3 * i] = r[0] * x + r[1] * y + r[2] * z + gap * dir.x;
            pa[3 * i + 1] = r[3] * x + r[4] * y + r[5] * z + gap * dir.y;
            pa[3 * i + 2] = r[6] * x + r[7] * y + r[8] * z + gap * dir.z;
        }
        or_poly A, B;
        double *va = NULL, *vb = NULL;
        size_t nva = 0, nvb = 0;
        if (hull_poly(pa, na, &A, &va, &nva) != 0 || hull_poly(pb, nb, &B, &vb, &nvb) != 0) {
            CHECK(0, "hull of a random shape failed (pair %d)", it);
            continue;
        }
        or_result res;
        or_distance(&A, &B, &res);
        double ex = -1, ex2 = -1;
        int zero = -1;
        char msg[256];
        pxcd_status st = pxcd_exact_distance(va, nva, vb, nvb, &ex, &ex2, &zero, NULL, NULL, msg, sizeof msg);
        CHECK(st == PXCD_OK, "exact distance failed: %s", msg);
        double scale = gap + A.body_radius + B.body_radius;
        double tol = 1e-13 * scale;
        double err = fabs(res.distance - ex);
        if (err / scale > worst) worst = err / scale;
        CHECK(err <= tol, "pair %d (%s %zu, %s %zu): oracle %.17g exact %.17g", it, pg_kind_name(ka), na,
              pg_kind_name(kb), nb, res.distance, ex);
        /* Classification, outside the ambiguous band. */
        if (zero) {
            inter++;
            if (res.margin > tol)
                CHECK(res.intersecting, "pair %d: exact says intersecting", it);
            else
                band++;
        } else if (ex > tol) {
            CHECK(!res.intersecting, "pair %d: exact says disjoint (%.3g)", it, ex);
            /* Witnesses of the oracle. */
            CHECK(fabs(dist(res.pa, res.pb) - res.distance) <= tol, "oracle witness distance");
            CHECK(or_point_depth(&A, res.pa) <= tol && or_point_depth(&B, res.pb) <= tol,
                  "oracle witnesses on A, B");
            double fd = or_feature_distance(&A, res.fa, &B, res.fb);
            CHECK(fabs(fd - res.distance) <= tol, "oracle features realise d: %.17g vs %.17g", fd,
                  res.distance);
        } else {
            band++;
        }
        compared++;
        or_poly_free(&A);
        or_poly_free(&B);
        free(va);
        free(vb);
    }
    printf("oracle vs exact: %d pairs (%d intersecting, %d in the touching band), worst error/scale %.3g\n",
           compared, inter, band, worst);
    free(pa);
    free(pb);
}

int main(void) {
    tu_init("test_oracle");
    test_primitives();
    test_random_vs_exact(tu_scaled(400));
    return tu_finish();
}
