/* The API's contracts (issue 8, sections 3 and 6), each against an
 * independent answer:
 *   - version: run-time and header agree;
 *   - px_error on success is PX_OK with an empty message, on failure a
 *     sentence;
 *   - reserved option fields must be zero; lut_resolution above 256 is an
 *     error, not a silent clamp;
 *   - out-of-range accessors: PX_ERR_INVALID_ARGUMENT and zeroed outputs;
 *     in range they give back the input points and planes through them;
 *   - pose constructors: NULL arguments are errors, quaternions of norm
 *     1e-300 and 1e300 give the unit quaternion's rotation;
 *   - allocators: each polytope frees with the allocator it was created
 *     with, whatever other polytopes use (counted per allocator);
 *   - px_convex_bounds: the box against brute force over the vertices, the
 *     sphere enclosing every vertex;
 *   - px_translate: the default is the time of impact ahead (tau >= 0);
 *     PX_QUERY_BOTH_WAYS gives the least tau of either sign; both against
 *     closed forms on boxes;
 *   - px_intersect's result and diagnostics; the contact band stated in
 *     query.h, the same for every method (boxes at the band's edges). */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "proxima/proxima.h"
#include "test_util.h"

/* Box corners of half extents h, centred at c (24 doubles). */
static void box(double hx, double hy, double hz, double cx, double cy, double cz, double *xyz) {
    for (int i = 0; i < 8; ++i) {
        xyz[3 * i] = cx + ((i & 1) ? hx : -hx);
        xyz[3 * i + 1] = cy + ((i & 2) ? hy : -hy);
        xyz[3 * i + 2] = cz + ((i & 4) ? hz : -hz);
    }
}

static px_pose at(double x, double y, double z) {
    px_pose p = px_pose_identity();
    p.t.x = x, p.t.y = y, p.t.z = z;
    return p;
}

static void test_version_and_errors(void) {
    CHECK(px_version() == PX_VERSION, "px_version %u, header %d", px_version(), PX_VERSION);
    char want[32];
    snprintf(want, sizeof want, "%d.%d.%d", PX_VERSION_MAJOR, PX_VERSION_MINOR, PX_VERSION_PATCH);
    CHECK(strcmp(px_version_string(), want) == 0, "px_version_string %s, want %s", px_version_string(), want);
    for (int s = 0; s <= 8; ++s)
        CHECK(strncmp(px_status_string((px_status)s), "PX_", 3) == 0, "status %d has no name", s);
    double xyz[24];
    box(1, 1, 1, 0, 0, 0, xyz);
    px_error err;
    memset(&err, 0x5a, sizeof err); /* garbage before: success must clear it */
    px_convex *c = px_convex_create(xyz, 8, NULL, &err);
    CHECK(c && err.code == PX_OK && err.message[0] == '\0', "success leaves code %d, message '%.40s'",
          err.code, err.message);
    CHECK(px_convex_validate(c, &err) == PX_OK && err.code == PX_OK && err.message[0] == '\0',
          "validate success: code %d", err.code);
    px_convex_destroy(c);
    c = px_convex_create(xyz, 0, NULL, &err);
    CHECK(!c && err.code == PX_ERR_INVALID_ARGUMENT && strlen(err.message) > 10, "0 points: code %d '%s'",
          err.code, err.message);
    c = px_convex_create(xyz, 3, NULL, &err); /* a triangle: a flat piece (test_degenerate) */
    CHECK(c && err.code == PX_OK && px_convex_dimension(c) == 2, "3 points: code %d '%s'", err.code,
          err.message);
    px_convex_destroy(c);
    px_pose bad = px_pose_identity();
    bad.r[0] = 2;
    CHECK(px_pose_check(&bad, &err) == PX_ERR_INVALID_POSE && err.code == PX_ERR_INVALID_POSE, "bad pose");
    CHECK(px_pose_check(&bad, NULL) == PX_ERR_INVALID_POSE, "bad pose, NULL err");
}

static void test_options(void) {
    double xyz[24];
    box(1, 1, 1, 0, 0, 0, xyz);
    px_error err;
    for (int i = 0; i < 5; ++i) {
        px_convex_options o;
        memset(&o, 0, sizeof o);
        o.reserved[i] = 1;
        px_convex *c = px_convex_create(xyz, 8, &o, &err);
        CHECK(!c && err.code == PX_ERR_INVALID_ARGUMENT && strstr(err.message, "reserved"),
              "convex reserved[%d]: code %d", i, err.code);
        px_convex_destroy(c);
    }
    px_convex_options o;
    memset(&o, 0, sizeof o);
    o.lut_resolution = 257;
    px_convex *c = px_convex_create(xyz, 8, &o, &err);
    CHECK(!c && err.code == PX_ERR_INVALID_ARGUMENT && strstr(err.message, "256"), "lut 257: code %d",
          err.code);
    o.lut_resolution = 256;
    c = px_convex_create(xyz, 8, &o, &err);
    CHECK(c != NULL, "lut 256: %s", err.message);
    px_allocator half = {NULL, NULL, NULL};
    o.lut_resolution = 0;
    o.allocator = &half;
    px_convex *d = px_convex_create(xyz, 8, &o, &err);
    CHECK(!d && err.code == PX_ERR_INVALID_ARGUMENT, "allocator without functions: code %d", err.code);

    /* Query options: reserved fields, unknown methods, flags of another query. */
    px_pose pa = at(0, 0, 0), pb = at(3, 0, 0);
    px_distance_result dr;
    px_intersect_result ir;
    px_translate_result tr;
    px_vec3 dir = {1, 0, 0};
    for (int i = 0; i < 6; ++i) {
        px_query_options q;
        memset(&q, 0, sizeof q);
        q.reserved[i] = 7;
        CHECK(px_distance(c, &pa, c, &pb, &q, NULL, &dr) == PX_ERR_INVALID_ARGUMENT, "distance reserved[%d]",
              i);
        CHECK(px_intersect(c, &pa, c, &pb, &q, NULL, &ir) == PX_ERR_INVALID_ARGUMENT,
              "intersect reserved[%d]", i);
        CHECK(px_translate(c, &pa, c, &pb, dir, &q, NULL, &tr) == PX_ERR_INVALID_ARGUMENT,
              "translate reserved[%d]", i);
    }
    px_query_options q;
    memset(&q, 0, sizeof q);
    q.method = 3;
    CHECK(px_distance(c, &pa, c, &pb, &q, NULL, &dr) == PX_ERR_INVALID_ARGUMENT, "method 3");
    q.method = 0;
    q.flags = PX_QUERY_BOTH_WAYS;
    CHECK(px_distance(c, &pa, c, &pb, &q, NULL, &dr) == PX_ERR_INVALID_ARGUMENT, "distance with BOTH_WAYS");
    CHECK(px_intersect(c, &pa, c, &pb, &q, NULL, &ir) == PX_ERR_INVALID_ARGUMENT, "intersect with a flag");
    q.flags = PX_QUERY_SIGNED;
    CHECK(px_translate(c, &pa, c, &pb, dir, &q, NULL, &tr) == PX_ERR_INVALID_ARGUMENT,
          "translate with SIGNED");
    CHECK(px_distance(c, &pa, c, &pb, &q, NULL, &dr) == PX_OK && dr.distance == 1.0, "signed ok: %g",
          dr.distance);
    px_convex_destroy(c);
}

static void test_accessors(void) {
    double xyz[24];
    box(1, 2, 3, 10, -20, 1e14, xyz); /* far from the origin: stored about its centre */
    px_error err;
    px_convex *c = px_convex_create(xyz, 8, NULL, &err);
    CHECK(c != NULL, "box: %s", err.message);
    if (!c) return;
    CHECK(px_convex_vertex_count(c) == 8 && px_convex_edge_count(c) == 12 && px_convex_face_count(c) == 6,
          "counts %u %u %u", px_convex_vertex_count(c), px_convex_edge_count(c), px_convex_face_count(c));
    /* Every vertex is an input point, bit for bit. */
    for (uint32_t i = 0; i < 8; ++i) {
        px_vec3 v;
        CHECK(px_convex_vertex(c, i, &v) == PX_OK, "vertex %u", i);
        int found = 0;
        for (int k = 0; k < 8; ++k)
            found |= v.x == xyz[3 * k] && v.y == xyz[3 * k + 1] && v.z == xyz[3 * k + 2];
        CHECK(found, "vertex %u (%.17g %.17g %.17g) is not an input point", i, v.x, v.y, v.z);
    }
    /* Every face plane passes through its vertices (body frame). */
    for (uint32_t f = 0; f < 6; ++f) {
        px_vec3 n;
        double d;
        uint32_t m;
        CHECK(px_convex_face(c, f, &n, &d, &m) == PX_OK && m == 4, "face %u", f);
        for (uint32_t k = 0; k < m; ++k) {
            uint32_t vi;
            px_vec3 v;
            CHECK(px_convex_face_vertex(c, f, k, &vi) == PX_OK && px_convex_vertex(c, vi, &v) == PX_OK, "fv");
            double h = n.x * v.x + n.y * v.y + n.z * v.z - d;
            CHECK(fabs(h) <= 1e-16 * 1e14 * 4, "face %u vertex %u off its plane by %g", f, vi, h);
        }
    }
    /* Out of range: an error and zeroed outputs, the same for every accessor. */
    px_vec3 v = {1, 1, 1};
    CHECK(px_convex_vertex(c, 8, &v) == PX_ERR_INVALID_ARGUMENT && v.x == 0 && v.y == 0 && v.z == 0,
          "vertex 8");
    uint32_t e2[2] = {5, 5};
    CHECK(px_convex_edge(c, 12, e2) == PX_ERR_INVALID_ARGUMENT && e2[0] == 0 && e2[1] == 0, "edge 12");
    px_vec3 n = {1, 1, 1};
    double d = 1;
    uint32_t m = 9, vi = 9;
    CHECK(px_convex_face(c, 6, &n, &d, &m) == PX_ERR_INVALID_ARGUMENT && n.x == 0 && d == 0 && m == 0,
          "face 6");
    CHECK(px_convex_face_vertex(c, 0, 4, &vi) == PX_ERR_INVALID_ARGUMENT && vi == 0, "face 0 vertex 4");
    CHECK(px_convex_face_vertex(c, 6, 0, &vi) == PX_ERR_INVALID_ARGUMENT, "face 6 vertex 0");
    CHECK(px_convex_vertex(NULL, 0, &v) == PX_ERR_INVALID_ARGUMENT, "NULL polytope");
    CHECK(px_convex_vertex(c, 0, NULL) == PX_ERR_INVALID_ARGUMENT, "NULL output");
    CHECK(px_convex_vertex_count(NULL) == 0 && px_convex_memory_bytes(NULL) == 0, "NULL counts");
    px_convex_destroy(c);
}

static void test_poses(void) {
    double r[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, t[3] = {1, 2, 3};
    px_pose p;
    CHECK(px_pose_from_rt(NULL, t, &p) == PX_ERR_INVALID_ARGUMENT, "from_rt NULL r");
    CHECK(px_pose_from_rt(r, NULL, &p) == PX_ERR_INVALID_ARGUMENT, "from_rt NULL t");
    CHECK(px_pose_from_rt(r, t, NULL) == PX_ERR_INVALID_ARGUMENT, "from_rt NULL out");
    CHECK(px_pose_from_rt(r, t, &p) == PX_OK && p.t.z == 3, "from_rt");
    double bad[9] = {1, 0, 0, 0, 1, 0, 0, 0, -1};
    CHECK(px_pose_from_rt(bad, t, &p) == PX_ERR_INVALID_POSE, "from_rt reflection");
    double q[4] = {0.5, 0.5, 0.5, 0.5}; /* 120 degrees about (1,1,1): x -> y -> z -> x */
    CHECK(px_pose_from_quat(NULL, t, &p) == PX_ERR_INVALID_ARGUMENT, "from_quat NULL q");
    CHECK(px_pose_from_quat(q, NULL, &p) == PX_ERR_INVALID_ARGUMENT, "from_quat NULL t");
    double zero[4] = {0, 0, 0, 0}, nanq[4] = {NAN, 0, 0, 1};
    CHECK(px_pose_from_quat(zero, t, &p) == PX_ERR_INVALID_ARGUMENT, "zero quaternion");
    tu_untrap_fp();
    CHECK(px_pose_from_quat(nanq, t, &p) == PX_ERR_NON_FINITE, "NaN quaternion");
    tu_trap_fp();
    px_pose ref;
    CHECK(px_pose_from_quat(q, t, &ref) == PX_OK, "unit quaternion");
    CHECK(fabs(ref.r[3] - 1.0) < 1e-15 && fabs(ref.r[0]) < 1e-15, "120 deg rotation maps x to y");
    const double scales[] = {1e-300, 1e-200, 1e-160, 1e160, 1e200, 1e300, 1e-310 /* subnormal */};
    for (size_t k = 0; k < sizeof scales / sizeof scales[0]; ++k) {
        double s = scales[k], qs[4] = {q[0] * s, q[1] * s, q[2] * s, q[3] * s};
        px_status st = px_pose_from_quat(qs, t, &p);
        int same = st == PX_OK;
        for (int i = 0; i < 9 && same; ++i) same = fabs(p.r[i] - ref.r[i]) <= 4 * DBL_EPSILON;
        CHECK(same && px_pose_check(&p, NULL) == PX_OK, "quaternion scaled by %g: %s", s,
              px_status_string(st));
    }
}

/* An allocator that counts its bytes. */
typedef struct counter {
    long live_bytes, allocs, frees;
} counter;
static void *count_alloc(void *user, size_t size) {
    counter *c = user;
    c->live_bytes += (long)size, c->allocs++;
    return malloc(size);
}
static void count_free(void *user, void *p, size_t size) {
    counter *c = user;
    c->live_bytes -= (long)size, c->frees++;
    free(p);
}

static void test_allocators(void) {
    counter ca = {0, 0, 0}, cb = {0, 0, 0};
    px_allocator aa = {count_alloc, count_free, &ca}, ab = {count_alloc, count_free, &cb};
    double xyz[3 * 64];
    for (int i = 0; i < 64; ++i) {
        double th = 0.7 * i, z = -1 + 2.0 * i / 63;
        xyz[3 * i] = cos(th) * sqrt(1 - z * z), xyz[3 * i + 1] = sin(th) * sqrt(1 - z * z),
                xyz[3 * i + 2] = z;
    }
    px_convex_options oa, ob;
    memset(&oa, 0, sizeof oa);
    memset(&ob, 0, sizeof ob);
    oa.allocator = &aa;
    ob.allocator = &ab;
    px_convex *a = px_convex_create(xyz, 64, &oa, NULL);
    px_convex *b = px_convex_create(xyz, 64, &ob, NULL);
    px_convex *m = px_convex_create(xyz, 64, NULL, NULL); /* malloc */
    CHECK(a && b && m, "three polytopes");
    CHECK(ca.live_bytes > 0 && cb.live_bytes > 0 && ca.live_bytes == cb.live_bytes, "live %ld %ld",
          ca.live_bytes, cb.live_bytes);
    CHECK((size_t)ca.live_bytes == px_convex_memory_bytes(a), "memory_bytes %zu, allocator saw %ld",
          px_convex_memory_bytes(a), ca.live_bytes);
    /* The option struct and its allocator go out of scope before destroy:
     * the polytope keeps its own copy. */
    memset(&oa, 0, sizeof oa);
    aa.alloc = NULL, aa.free = NULL;
    px_convex_destroy(b); /* frees with cb, not ca */
    CHECK(cb.live_bytes == 0 && cb.allocs == cb.frees && ca.live_bytes > 0, "b freed with its own: %ld %ld",
          cb.live_bytes, ca.live_bytes);
    px_convex_destroy(a);
    CHECK(ca.live_bytes == 0 && ca.allocs == ca.frees, "a freed with its own: %ld", ca.live_bytes);
    px_convex_destroy(m);
}

/* Brute-force world box of a polytope's vertices under a pose. */
static void brute_box(const px_convex *c, const px_pose *p, px_vec3 *lo, px_vec3 *hi) {
    *lo = (px_vec3){INFINITY, INFINITY, INFINITY};
    *hi = (px_vec3){-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t i = 0; i < px_convex_vertex_count(c); ++i) {
        px_vec3 v;
        px_convex_vertex(c, i, &v);
        px_vec3 w = px_pose_apply(p, v);
        lo->x = fmin(lo->x, w.x), lo->y = fmin(lo->y, w.y), lo->z = fmin(lo->z, w.z);
        hi->x = fmax(hi->x, w.x), hi->y = fmax(hi->y, w.y), hi->z = fmax(hi->z, w.z);
    }
}

static void test_bounds(void) {
    double xyz[3 * 200];
    uint64_t s = 42;
    for (int i = 0; i < 200; ++i)
        for (int k = 0; k < 3; ++k) {
            s = s * 6364136223846793005ULL + 1442695040888963407ULL;
            xyz[3 * i + k] = (double)(s >> 11) / 9007199254740992.0 * (k + 1) + 5.0 * k;
        }
    px_convex *c = px_convex_create(xyz, 200, NULL, NULL);
    CHECK(c != NULL, "cloud");
    double worst = 0;
    for (int trial = 0; trial < 200 && c; ++trial) {
        double q[4], t[3];
        for (int k = 0; k < 4; ++k) {
            s = s * 6364136223846793005ULL + 1442695040888963407ULL;
            q[k] = (double)(s >> 11) / 9007199254740992.0 - 0.5;
        }
        for (int k = 0; k < 3; ++k) t[k] = 10.0 * q[k] - 3.0;
        px_pose p;
        if (px_pose_from_quat(q, t, &p) != PX_OK) continue;
        px_bounds b;
        CHECK(px_convex_bounds(c, &p, &b) == PX_OK, "bounds status");
        px_vec3 lo, hi;
        brute_box(c, &p, &lo, &hi);
        worst = fmax(worst, fmax(fabs(b.min.x - lo.x), fmax(fabs(b.min.y - lo.y), fabs(b.min.z - lo.z))));
        worst = fmax(worst, fmax(fabs(b.max.x - hi.x), fmax(fabs(b.max.y - hi.y), fabs(b.max.z - hi.z))));
        for (uint32_t i = 0; i < px_convex_vertex_count(c); ++i) {
            px_vec3 v;
            px_convex_vertex(c, i, &v);
            px_vec3 w = px_pose_apply(&p, v);
            double dx = w.x - b.center.x, dy = w.y - b.center.y, dz = w.z - b.center.z;
            CHECK(sqrt(dx * dx + dy * dy + dz * dz) <= b.radius * (1 + 1e-14), "vertex %u outside the sphere",
                  i);
        }
    }
    CHECK(worst <= 1e-13, "box differs from brute force by %g", worst);
    px_bounds b;
    CHECK(px_convex_bounds(NULL, NULL, &b) == PX_ERR_INVALID_ARGUMENT, "NULL polytope");
    CHECK(px_convex_bounds(c, NULL, NULL) == PX_ERR_INVALID_ARGUMENT, "NULL output");
    CHECK(px_convex_bounds(c, NULL, &b) == PX_OK, "identity pose");
    px_convex_destroy(c);
}

/* Two unit cubes on the x axis; A moves along direction d. Closed forms. */
static void test_translate_modes(void) {
    double xyz[24];
    box(0.5, 0.5, 0.5, 0, 0, 0, xyz);
    px_convex *c = px_convex_create(xyz, 8, NULL, NULL);
    CHECK(c != NULL, "cube");
    if (!c) return;
    px_query_options both;
    memset(&both, 0, sizeof both);
    both.flags = PX_QUERY_BOTH_WAYS;
    px_translate_result r;
    px_vec3 towards = {1, 0, 0}, away = {-1, 0, 0}, aside = {0, 1, 0};
    px_pose pb = at(0, 0, 0);
    struct {
        double xa;      /* A's x */
        px_vec3 d;      /* direction */
        int hit_fwd;    /* default mode */
        double tau_fwd; /* default tau */
        int overlap;    /* default: in_contact at 0 */
        int hit_both;
        double tau_both;
    } cases[] = {
        {-3.0, towards, 1, 2.0, 0, 1, 2.0},            /* ahead: both modes agree */
        {-3.0, away, 0, 0.0, 0, 1, -4.0},              /* B behind A: no hit ahead; entry at -4 both ways */
        {-0.5, towards, 1, 0.0, 1, 1, -0.5},           /* in_contact by half */
        {-0.5, away, 1, 0.0, 1, 1, -1.5},              /* in_contact, moving out */
        {-3.0, aside, 0, 0.0, 0, 0, 0.0},              /* the line misses B */
        {-1.0, away, 1, 0.0, 1, 1, -2.0},              /* touching, moving away: in contact now */
        {-3.0, (px_vec3){4, 0, 0}, 1, 0.5, 0, 1, 0.5}, /* tau in units of the direction */
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k) {
        px_pose pa = at(cases[k].xa, 0.1, -0.05);
        CHECK(px_translate(c, &pa, c, &pb, cases[k].d, NULL, NULL, &r) == PX_OK, "case %zu status", k);
        CHECK(r.hit == cases[k].hit_fwd && fabs(r.tau - cases[k].tau_fwd) <= 1e-14 &&
                  r.in_contact == cases[k].overlap,
              "case %zu forward: hit %d tau %.17g in_contact %d", k, r.hit, r.tau, r.in_contact);
        if (r.hit) CHECK(r.tau >= 0.0, "case %zu: forward tau %g < 0", k, r.tau);
        if (!r.hit) {
            /* The witness plane: normal . d <= 0 and a positive gap, checked
             * against every vertex (A at every tau >= 0 stays below). */
            px_vec3 nn = r.normal, dd = cases[k].d;
            CHECK(nn.x * dd.x + nn.y * dd.y + nn.z * dd.z <= 1e-15, "case %zu: witness normal . d > 0", k);
            CHECK(r.gap > 0, "case %zu: gap %g", k, r.gap);
            for (int i = 0; i < 8; ++i) {
                px_vec3 v = {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]};
                px_vec3 wa = px_pose_apply(&pa, v), wb = px_pose_apply(&pb, v);
                double ha =
                    nn.x * (wa.x - r.point_a.x) + nn.y * (wa.y - r.point_a.y) + nn.z * (wa.z - r.point_a.z);
                double hb =
                    nn.x * (wb.x - r.point_b.x) + nn.y * (wb.y - r.point_b.y) + nn.z * (wb.z - r.point_b.z);
                CHECK(ha <= 1e-14 && hb >= -1e-14, "case %zu: witness plane cuts a body (%g, %g)", k, ha, hb);
            }
        }
        CHECK(px_translate(c, &pa, c, &pb, cases[k].d, &both, NULL, &r) == PX_OK, "case %zu both status", k);
        CHECK(r.hit == cases[k].hit_both && fabs(r.tau - cases[k].tau_both) <= 1e-14 && r.in_contact == 0,
              "case %zu both ways: hit %d tau %.17g", k, r.hit, r.tau);
    }
    px_convex_destroy(c);
}

/* One pair, every query: distance with each method, px_intersect and the
 * forward translation along -x agree on touching or not. */
static void check_pair_agrees(const px_convex *a, const px_convex *b, double gap, int want,
                              const char *what) {
    px_pose pa = px_pose_identity(), pb = px_pose_identity();
    for (uint32_t m = 0; m < 3; ++m) {
        px_query_options q;
        memset(&q, 0, sizeof q);
        q.method = m;
        px_distance_result r;
        CHECK(px_distance(a, &pa, b, &pb, &q, NULL, &r) == PX_OK, "%s: distance status", what);
        CHECK(r.intersecting == want, "%s method %u: intersecting %d (distance %.17g)", what, m,
              r.intersecting, r.distance);
        if (!want)
            CHECK(fabs(r.distance - gap) <= 8 * DBL_EPSILON * (4 + gap),
                  "%s method %u: distance %.17g, want %.17g", what, m, r.distance, gap);
        if (want && gap > 0)
            CHECK(r.diag.quality & PX_QUALITY_CONTACT_BAND, "%s method %u: band answer without its flag",
                  what, m);
    }
    px_intersect_result ir;
    CHECK(px_intersect(a, &pa, b, &pb, NULL, NULL, &ir) == PX_OK, "%s: intersect status", what);
    CHECK(ir.intersecting == want, "%s: px_intersect %d", what, ir.intersecting);
    px_translate_result tr;
    px_vec3 dir = {-1, 0, 0};
    CHECK(px_translate(a, &pa, b, &pb, dir, NULL, NULL, &tr) == PX_OK && tr.hit, "%s: translate", what);
    CHECK(want ? tr.tau == 0.0 : fabs(tr.tau - gap) <= 8 * DBL_EPSILON * (4 + gap),
          "%s: tau %.17g, want %.17g", what, tr.tau, want ? 0.0 : gap);
}

/* The contact band of query.h, the same for every query: unit cubes whose
 * body coordinates sit at 0, 1e6 and 1e14 (identity poses), 0.5 and 1e-3
 * apart, are separated by exactly that for every query (the band used to
 * follow the coordinates: 16 eps x 1e14 = 0.02 made some methods call 1e-3
 * touching); at 0.25 band apart they touch for every query, at 4 bands they
 * are separated. */
static void test_band(void) {
    const double offsets[] = {0.0, 1e6, 1e14};
    for (size_t o = 0; o < 3; ++o) {
        double off = offsets[o], xyz_b[24];
        box(0.5, 0.5, 0.5, off, off, off, xyz_b);
        px_convex *b = px_convex_create(xyz_b, 8, NULL, NULL);
        const double gaps[] = {0.5, 1e-3, -1, -2};
        for (size_t g = 0; g < 4; ++g) {
            double centres = 1.0, band = 64 * DBL_EPSILON * (sqrt(3.0) + centres);
            double gap = gaps[g] > 0 ? gaps[g] : gaps[g] == -1 ? 0.25 * band : 4 * band;
            if (gaps[g] < 0 && off != 0.0)
                continue; /* gaps below the coordinates' ulp are not representable */
            double xyz_a[24];
            box(0.5, 0.5, 0.5, off + 1.0 + gap, off, off, xyz_a);
            /* The gap the coordinates hold (1e-3 is lost at 1e14, where the
             * ulp is 0.016): A's least x minus B's greatest, exact. */
            gap = xyz_a[0] - xyz_b[3];
            px_convex *a = px_convex_create(xyz_a, 8, NULL, NULL);
            CHECK(a && b, "boxes");
            char what[96];
            snprintf(what, sizeof what, "cubes at %g, gap %g", off, gap);
            if (a && b) check_pair_agrees(a, b, gap, gap <= band, what);
            px_convex_destroy(a);
        }
        px_convex_destroy(b);
    }
}

int main(void) {
    tu_init("test_api");
    test_version_and_errors();
    test_options();
    test_accessors();
    test_poses();
    test_allocators();
    test_bounds();
    test_translate_modes();
    test_band();
    return tu_finish();
}
