/* px_convex construction (issue 3 §2, §4): every polytope built here is
 * validated (px_convex_validate) and compared with CGAL's hull of the same
 * points (pxcd_hull_compute): counts, vertex sets, Euler, and our own
 * independent checks of planes, convexity and edge/face incidence. Then
 * coplanar merging (cube with face centres and edge midpoints), degenerate
 * inputs with their documented statuses, memory per vertex, and the
 * allocator: leak count and failure injection at every allocation. */
#include <float.h>
#include <stdint.h>
#include <sys/resource.h>
#include <unistd.h>

#include "access.h"
#include "check.h"
#include "convex/convex.h" /* the inner ball (pxi), tested directly below */
#include "math/vec3.h"
#include "oracle.h"
#include "proxima/proxima.h"
#include "px_gen.h"
#include "pxcd.h"
#include "test_util.h"

/* ------------------------------------------------------ counting allocator */

typedef struct counting {
    long long calls;   /* successful + failed alloc calls */
    long long live;    /* live allocations */
    long long bytes;   /* live bytes */
    long long fail_at; /* fail the fail_at-th call (1-based); 0 = never */
    long long bad_free;
} counting;

#define HDR 16

static void *c_alloc(void *user, size_t size) {
    counting *c = user;
    c->calls++;
    if (c->fail_at && c->calls == c->fail_at) return NULL;
    unsigned char *p = malloc(size + HDR);
    if (!p) return NULL;
    memcpy(p, &size, sizeof size);
    c->live++;
    c->bytes += (long long)size;
    return p + HDR;
}

static void c_free(void *user, void *ptr, size_t size) {
    counting *c = user;
    if (!ptr) return;
    unsigned char *p = (unsigned char *)ptr - HDR;
    size_t stored;
    memcpy(&stored, p, sizeof stored);
    if (stored != size) c->bad_free++; /* free must receive the requested size */
    c->live--;
    c->bytes -= (long long)stored;
    free(p);
}

static counting g_count;
static px_allocator g_counting = {c_alloc, c_free, &g_count};
/* Options that route a polytope's allocations through the counter. */
static px_convex_options counting_options(void) {
    px_convex_options o;
    memset(&o, 0, sizeof o);
    o.allocator = &g_counting;
    return o;
}

/* ------------------------------------------------------- structure checks */

static int cmp_xyz(const void *a, const void *b) { return memcmp(a, b, 3 * sizeof(double)); }

static double g_max_bytes_per_vertex = 0, g_min_bytes_per_vertex = 1e300;
static long g_polytopes = 0;

/* Independent structural checks of `c` built from `xyz` (n points). */
static void check_polytope(const px_convex *c, const double *xyz, size_t n, const char *what) {
    px_error err;
    memset(&err, 0, sizeof err);
    px_status st = px_convex_validate(c, &err);
    CHECK(st == PX_OK, "%s: validate: %s", what, err.message);
    g_polytopes++;
    uint32_t V = px_convex_vertex_count(c), E = px_convex_edge_count(c), F = px_convex_face_count(c);
    CHECK((long)V - (long)E + (long)F == 2, "%s: Euler V=%u E=%u F=%u", what, V, E, F);

    /* CGAL's hull of the same points. */
    pxcd_hull *h = NULL;
    int dim = -1;
    char msg[256];
    CHECK(pxcd_hull_compute(xyz, n, &h, &dim, msg, sizeof msg) == PXCD_OK, "%s: pxcd hull: %s", what, msg);
    if (h) {
        size_t he = 0;
        for (size_t f = 0; f < h->face_count; ++f) he += h->face_offsets[f + 1] - h->face_offsets[f];
        CHECK(h->vertex_count == V && h->face_count == F && he == 2 * (size_t)E,
              "%s: counts V=%u E=%u F=%u, CGAL V=%zu E=%zu F=%zu", what, V, E, F, h->vertex_count, he / 2,
              h->face_count);
        /* Same vertex set (bitwise): sort both. */
        if (h->vertex_count == V) {
            double *a = malloc(3 * (size_t)V * sizeof *a), *b = malloc(3 * (size_t)V * sizeof *b);
            tc_vertices(c, a);
            memcpy(b, h->vertices, 3 * (size_t)V * sizeof *b);
            qsort(a, V, 3 * sizeof(double), cmp_xyz);
            qsort(b, V, 3 * sizeof(double), cmp_xyz);
            CHECK(memcmp(a, b, 3 * (size_t)V * sizeof *a) == 0, "%s: vertex set differs from CGAL's", what);
            free(a);
            free(b);
        }
        pxcd_hull_free(h);
    }

    /* Planes from the accessors vs the oracle's own (Newell) planes;
     * convexity; every edge used once in each direction by the faces. */
    or_poly P;
    if (or_poly_init(&P, c, NULL) != 0) {
        CHECK(0, "%s: oracle cannot read the polytope", what);
        return;
    }
    double scale = P.body_radius;
    int bad_plane = 0, nonconvex = 0, bad_incidence = 0, bad_winding = 0;
    for (uint32_t f = 0; f < F; ++f) {
        px_vec3 nrm;
        double d;
        if (!(px_convex_face(c, f, &nrm, &d, NULL) == PX_OK)) {
            bad_plane++;
            continue;
        }
        double dotn = nrm.x * P.fn[f].x + nrm.y * P.fn[f].y + nrm.z * P.fn[f].z;
        double len = sqrt(nrm.x * nrm.x + nrm.y * nrm.y + nrm.z * nrm.z);
        if (fabs(len - 1) > 1e-12 || dotn < 1 - 1e-12 || fabs(d - P.fd[f]) > 1e-12 * scale) bad_plane++;
        /* the face loop must be counter-clockwise seen from outside */
        if (P.fw[f].x * P.fn[f].x + P.fw[f].y * P.fn[f].y + P.fw[f].z * P.fn[f].z < 0) bad_winding++;
        for (uint32_t v = 0; v < V; ++v) {
            px_vec3 p = P.v[v];
            if (P.fn[f].x * p.x + P.fn[f].y * p.y + P.fn[f].z * p.z - P.fd[f] > 1e-12 * scale) nonconvex++;
        }
    }
    CHECK(bad_plane == 0, "%s: %d face planes disagree with the face polygons", what, bad_plane);
    CHECK(bad_winding == 0, "%s: %d faces listed clockwise (seen from outside)", what, bad_winding);
    CHECK(nonconvex == 0, "%s: %d vertex/face pairs violate convexity", what, nonconvex);
    CHECK((px_convex_face(c, F, NULL, NULL, NULL) == PX_OK) == 0 && ta_face_size(c, F) == 0,
          "%s: out of range face", what);
    {
        uint32_t ab[2];
        CHECK((px_convex_edge(c, E, ab) == PX_OK) == 0, "%s: out of range edge", what);
    }
    /* Directed edge use: +1 for tail->head, +2 for head->tail in a face.
     * Edges are looked up through per-vertex incidence lists. */
    unsigned char *use = calloc(E, 1);
    uint32_t *vfirst = calloc(V + 1, sizeof *vfirst), *vlist = calloc(2 * (size_t)E, sizeof *vlist);
    for (uint32_t e = 0; e < 2 * E; ++e) vfirst[P.ev[e] + 1]++;
    for (uint32_t v = 0; v < V; ++v) vfirst[v + 1] += vfirst[v];
    uint32_t *fill = calloc(V, sizeof *fill);
    for (uint32_t e = 0; e < 2 * E; ++e) vlist[vfirst[P.ev[e]] + fill[P.ev[e]]++] = e / 2;
    for (uint32_t f = 0; f < F; ++f) {
        uint32_t k = ta_face_size(c, f);
        for (uint32_t j = 0; j < k; ++j) {
            uint32_t a = ta_face_vertex(c, f, j), b = ta_face_vertex(c, f, (j + 1) % k);
            int found = 0;
            for (uint32_t q = vfirst[a]; q < vfirst[a + 1]; ++q) {
                uint32_t e = vlist[q];
                if (P.ev[2 * e] == a && P.ev[2 * e + 1] == b) use[e] += 1, found = 1;
                if (P.ev[2 * e] == b && P.ev[2 * e + 1] == a) use[e] += 2, found = 1;
            }
            if (!found) bad_incidence++;
        }
    }
    for (uint32_t e = 0; e < E; ++e)
        if (use[e] != 3) bad_incidence++;
    free(vfirst);
    free(vlist);
    free(fill);
    CHECK(bad_incidence == 0, "%s: %d edge/face incidence errors", what, bad_incidence);
    free(use);
    or_poly_free(&P);

    size_t bytes = px_convex_memory_bytes(c);
    double bpv = (double)bytes / V;
    CHECK(bytes > 0 && bpv < 1024, "%s: %zu bytes for %u vertices (%.0f per vertex)", what, bytes, V, bpv);
    if (bpv > g_max_bytes_per_vertex) g_max_bytes_per_vertex = bpv;
    if (bpv < g_min_bytes_per_vertex) g_min_bytes_per_vertex = bpv;
}

static px_convex *build_checked(const double *xyz, size_t n, const char *what) {
    px_error err;
    memset(&err, 0, sizeof err);
    px_convex *c = px_convex_create(xyz, n, NULL, &err);
    CHECK(c != NULL, "%s: px_convex_create failed: %s", what, err.message);
    if (c) check_polytope(c, xyz, n, what);
    return c;
}

/* --------------------------------------------------------------- the tests */

static void test_random_polytopes(int count) {
    pg_rng rng;
    pg_seed(&rng, 3001);
    double *xyz = malloc(3 * 2000 * sizeof *xyz);
    printf("  %-16s %6s %6s %6s %10s\n", "shape", "n", "V", "F", "bytes/V");
    for (int i = 0; i < count; ++i) {
        pg_kind kind = (pg_kind)(i % PG_KIND_COUNT);
        size_t n = i < PG_KIND_COUNT * 3 ? (size_t)(i < PG_KIND_COUNT       ? 8
                                                    : i < 2 * PG_KIND_COUNT ? 200
                                                                            : 2000)
                                         : pg_log_int(&rng, 4, 2000);
        if (n < 8) n = 8;
        double size = pow(10.0, pg_range(&rng, -3, 3));
        n = pg_shape(&rng, kind, n, size, xyz);
        char what[96];
        snprintf(what, sizeof what, "random #%d %s n=%zu size=%.3g", i, pg_kind_name(kind), n, size);
        px_convex *c = build_checked(xyz, n, what);
        if (c && (i % 37 == 0 || n >= 2000))
            printf("  %-16s %6zu %6u %6u %10.0f\n", pg_kind_name(kind), n, px_convex_vertex_count(c),
                   px_convex_face_count(c), (double)px_convex_memory_bytes(c) / px_convex_vertex_count(c));
        px_convex_destroy(c);
    }
    /* Exactly 4 vertices: tetrahedra at many scales. */
    for (int i = 0; i < 50; ++i) {
        double t[12];
        pg_random_tetrahedron(&rng, pow(10.0, pg_range(&rng, -20, 20)), t);
        px_convex *c = build_checked(t, 4, "tetrahedron");
        CHECK(c && px_convex_vertex_count(c) == 4 && px_convex_face_count(c) == 4, "tetra counts");
        px_convex_destroy(c);
    }
    free(xyz);
}

static void test_coplanar_merging(void) {
    /* Cube corners + face centres + edge midpoints + body centre: 27 points. */
    double pts[27 * 3];
    int k = 0;
    for (int x = -1; x <= 1; ++x)
        for (int y = -1; y <= 1; ++y)
            for (int z = -1; z <= 1; ++z) pts[3 * k] = x, pts[3 * k + 1] = y, pts[3 * k + 2] = z, ++k;
    px_convex *c = build_checked(pts, 27, "cube 3x3x3 grid");
    if (c) {
        CHECK(px_convex_vertex_count(c) == 8 && px_convex_face_count(c) == 6 && px_convex_edge_count(c) == 12,
              "cube with face centres: V=%u E=%u F=%u", px_convex_vertex_count(c), px_convex_edge_count(c),
              px_convex_face_count(c));
        for (uint32_t f = 0; f < px_convex_face_count(c); ++f)
            CHECK(ta_face_size(c, f) == 4, "cube face %u has %u vertices", f, ta_face_size(c, f));
    }
    px_convex_destroy(c);
    /* Cylinder: the caps are single k-gons; k rectangles around. */
    for (size_t kk = 3; kk <= 200; kk = kk * 2 + 1) {
        double *cy = malloc(6 * kk * sizeof *cy);
        pg_cylinder(kk, 1.0, 0.5, cy);
        c = build_checked(cy, 2 * kk, "cylinder");
        CHECK(c && px_convex_face_count(c) == kk + 2 && px_convex_vertex_count(c) == 2 * kk,
              "cylinder k=%zu: F=%u", kk, c ? px_convex_face_count(c) : 0);
        px_convex_destroy(c);
        free(cy);
    }
    /* Box with many random points on its faces (dyadic, so exactly coplanar). */
    pg_rng rng;
    pg_seed(&rng, 77);
    double bp[3 * 208];
    pg_box(2, 1, 0.5, bp);
    for (int i = 8; i < 208; ++i) {
        int axis = (int)pg_below(&rng, 3), side = (int)pg_below(&rng, 2);
        double h[3] = {2, 1, 0.5};
        for (int j = 0; j < 3; ++j)
            bp[3 * i + j] = ldexp((double)pg_below(&rng, 1024), -10) * 2 * h[j] - h[j];
        bp[3 * i + axis] = side ? h[axis] : -h[axis];
    }
    c = build_checked(bp, 208, "box with face points");
    CHECK(c && px_convex_vertex_count(c) == 8 && px_convex_face_count(c) == 6, "box with face points merged");
    px_convex_destroy(c);
}

static int contains_ci(const char *s, const char *w) {
    for (; *s; ++s) {
        size_t i = 0;
        while (w[i] && s[i] && (s[i] | 32) == (w[i] | 32)) ++i;
        if (!w[i]) return 1;
    }
    return 0;
}

static void expect_status(const double *xyz, size_t n, px_status want, const char *word, const char *what) {
    px_error err;
    memset(&err, 0, sizeof err);
    px_convex *c = px_convex_create(xyz, n, NULL, &err);
    CHECK(c == NULL, "%s: expected failure", what);
    CHECK(err.code == want, "%s: status %s, expected %s (%s)", what, px_status_string(err.code),
          px_status_string(want), err.message);
    CHECK(err.message[0] != 0, "%s: empty message", what);
    if (word)
        CHECK(contains_ci(err.message, word), "%s: message \"%s\" does not say \"%s\"", what, err.message,
              word);
    px_convex_destroy(c);
    /* err may be NULL */
    c = px_convex_create(xyz, n, NULL, NULL);
    CHECK(c == NULL, "%s: expected failure with err NULL", what);
    px_convex_destroy(c);
}

/* A lower-dimensional piece: its dimension, counts and validity. */
static void expect_dimension(const double *xyz, size_t n, uint32_t dim, uint32_t nv, uint32_t ne, uint32_t nf,
                             const char *what) {
    px_error err;
    px_convex *c = px_convex_create(xyz, n, NULL, &err);
    CHECK(c && err.code == PX_OK, "%s: %s", what, err.message);
    CHECK(px_convex_dimension(c) == dim && px_convex_vertex_count(c) == nv && px_convex_edge_count(c) == ne &&
              px_convex_face_count(c) == nf,
          "%s: dimension %u, V %u E %u F %u", what, px_convex_dimension(c), px_convex_vertex_count(c),
          px_convex_edge_count(c), px_convex_face_count(c));
    CHECK(px_convex_validate(c, &err) == PX_OK, "%s: %s", what, err.message);
    px_convex_destroy(c);
}

static void test_degenerate_inputs(void) {
    static const double tet[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    expect_status(NULL, 4, PX_ERR_INVALID_ARGUMENT, NULL, "NULL points");
    expect_status(tet, 0, PX_ERR_INVALID_ARGUMENT, NULL, "count 0");
    expect_status(tet, ((size_t)1 << 26) + 1, PX_ERR_INVALID_ARGUMENT, NULL, "count above 2^26");
    /* Fewer than 4 points, duplicates, collinear and coplanar sets are
     * lower-dimensional pieces now (test_degenerate has the queries). */
    expect_dimension(tet, 1, 0, 1, 0, 0, "1 point");
    expect_dimension(tet, 2, 1, 2, 1, 0, "2 points");
    expect_dimension(tet, 3, 2, 3, 3, 2, "3 points");
    double dup[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 0, 0};
    expect_dimension(dup, 4, 2, 3, 3, 2, "4 points, one duplicated");
    double rep[30];
    for (int i = 0; i < 30; ++i) rep[i] = (i % 3 == 0) ? 0.5 : -2.25;
    expect_dimension(rep, 10, 0, 1, 0, 0, "one point repeated 10 times");
    double col[60];
    for (int i = 0; i < 20; ++i) col[3 * i] = i, col[3 * i + 1] = 2.0 * i, col[3 * i + 2] = -3.0 * i;
    expect_dimension(col, 20, 1, 2, 1, 0, "collinear points");
    double pl[300];
    pg_rng rng;
    pg_seed(&rng, 5);
    for (int i = 0; i < 100; ++i) {
        double x = (double)pg_below(&rng, 1000), y = (double)pg_below(&rng, 1000);
        pl[3 * i] = x, pl[3 * i + 1] = y, pl[3 * i + 2] = 3 * x - 2 * y + 7; /* exact, tilted plane */
    }
    px_convex *flat = px_convex_create(pl, 100, NULL, NULL);
    CHECK(flat && px_convex_dimension(flat) == 2 && px_convex_face_count(flat) == 2 &&
              px_convex_validate(flat, NULL) == PX_OK,
          "coplanar points: a valid polygon");
    px_convex_destroy(flat);
    /* Non-finite coordinates, at index 5 of 8 (box corners). */
    const double bad[3] = {NAN, INFINITY, -INFINITY};
    const char *names[3] = {"NaN", "+Inf", "-Inf"};
    for (int b = 0; b < 3; ++b)
        for (int comp = 0; comp < 3; ++comp) {
            double box[24];
            pg_box(1, 1, 1, box);
            box[3 * 5 + comp] = bad[b];
            char what[64];
            snprintf(what, sizeof what, "%s coordinate (point 5, component %d)", names[b], comp);
            expect_status(box, 8, PX_ERR_NON_FINITE, "5", what);
        }
    /* Accessors on NULL / out of range do not crash. */
    px_convex_destroy(NULL);
    px_error err;
    CHECK(px_convex_validate(NULL, &err) != PX_OK, "validate(NULL)");
}

/* Leak check and failure injection at every allocation of a build (and of
 * queries, which must not allocate at all). */
static void test_allocator(void) {
    pg_rng rng;
    pg_seed(&rng, 99);
    double xyz[3 * 300];
    pg_points_sphere(&rng, 300, 1.0, xyz);
    double box[24];
    pg_box(0.5, 0.25, 2, box);

    memset(&g_count, 0, sizeof g_count);
    px_convex_options opt = counting_options();
    px_convex *a = px_convex_create(xyz, 300, &opt, NULL);
    long long calls_a = g_count.calls;
    px_convex *b = px_convex_create(box, 8, &opt, NULL);
    long long calls_b = g_count.calls - calls_a;
    CHECK(a && b, "builds under the counting allocator");
    CHECK(g_count.live > 0 && g_count.bytes > 0, "allocations went through the hook (%lld live)",
          g_count.live);
    if (a) {
        CHECK((long long)px_convex_memory_bytes(a) >= g_count.bytes / 4,
              "memory_bytes %zu vs %lld bytes allocated", px_convex_memory_bytes(a), g_count.bytes);
    }
    /* Queries do not allocate. */
    long long before = g_count.calls;
    px_pair_cache cache;
    memset(&cache, 0, sizeof cache);
    for (int i = 0; i < 50 && a && b; ++i) {
        px_pose pa = pg_pose_random(&rng, 2), pb = pg_pose_random(&rng, 2);
        px_distance_result res;
        px_distance(a, &pa, b, &pb, NULL, &cache, &res);
    }
    CHECK(g_count.calls == before, "px_distance allocated %lld times", g_count.calls - before);
    px_convex_destroy(a);
    px_convex_destroy(b);
    CHECK(g_count.live == 0 && g_count.bytes == 0, "leak: %lld allocations, %lld bytes live", g_count.live,
          g_count.bytes);
    CHECK(g_count.bad_free == 0, "%lld frees with a size different from the allocation", g_count.bad_free);
    printf("  allocations per build: %lld (300-point sphere), %lld (box)\n", calls_a, calls_b);

    /* Failure injection: fail the k-th call, for every k. */
    int injected = 0;
    for (int which = 0; which < 2; ++which) {
        const double *p = which ? box : xyz;
        size_t n = which ? 8 : 300;
        long long total = which ? calls_b : calls_a;
        for (long long k = 1; k <= total; ++k) {
            memset(&g_count, 0, sizeof g_count);
            g_count.fail_at = k;
            px_error err;
            memset(&err, 0, sizeof err);
            px_convex *c = px_convex_create(p, n, &opt, &err);
            CHECK(c == NULL && err.code == PX_ERR_OUT_OF_MEMORY,
                  "failing allocation %lld of %lld: got %s (%s)", k, total,
                  c ? "a polytope" : px_status_string(err.code), err.message);
            CHECK(err.message[0] != 0, "OOM message empty");
            px_convex_destroy(c);
            CHECK(g_count.live == 0 && g_count.bytes == 0, "leak after failing allocation %lld: %lld live", k,
                  g_count.live);
            injected++;
        }
    }
    printf("  failure injection: %d builds with one failing allocation\n", injected);
}

/* Regression: when the hull computation ran out of memory,
 * px_convex_from_points told it by searching CGAL's message for "memory";
 * now pxcd reports PXCD_OUT_OF_MEMORY (std::bad_alloc, by type) and this
 * must become PX_ERR_OUT_OF_MEMORY. Configuration: the address space is
 * capped (RLIMIT_AS, soft limit only) at the process's current size plus
 * 32 MiB, then a polytope is built from 4M points (96 MiB): CGAL's first
 * copy of them cannot be allocated. Skipped under AddressSanitizer, whose
 * shadow memory needs an unlimited address space. */
static void test_out_of_memory(void) {
    if (tu_sanitized()) return;
    const size_t n = (size_t)4 << 20;
    double *xyz = malloc(3 * n * sizeof *xyz);
    CHECK(xyz != NULL, "input");
    if (!xyz) return;
    for (size_t i = 0; i < 3 * n; ++i) xyz[i] = (double)(i % 1013);
    long vm_pages = 0;
    FILE *f = fopen("/proc/self/statm", "r");
    if (f) {
        if (fscanf(f, "%ld", &vm_pages) != 1) vm_pages = 0;
        fclose(f);
    }
    struct rlimit old, lim;
    if (vm_pages <= 0 || getrlimit(RLIMIT_AS, &old) != 0) {
        printf("  out-of-memory test skipped: no /proc/self/statm or RLIMIT_AS\n");
        free(xyz);
        return;
    }
    lim = old;
    lim.rlim_cur = (rlim_t)vm_pages * (rlim_t)sysconf(_SC_PAGESIZE) + ((rlim_t)32 << 20);
    if (old.rlim_cur != RLIM_INFINITY && lim.rlim_cur > old.rlim_cur) lim.rlim_cur = old.rlim_cur;
    px_error err;
    memset(&err, 0, sizeof err);
    px_convex *c = NULL;
    int limited = setrlimit(RLIMIT_AS, &lim) == 0;
    if (limited) {
        c = px_convex_create(xyz, n, NULL, &err);
        setrlimit(RLIMIT_AS, &old);
    }
    CHECK(limited, "setrlimit");
    CHECK(c == NULL && err.code == PX_ERR_OUT_OF_MEMORY, "4M points under a 32 MiB margin: %s: %s",
          px_status_string(err.code), err.message);
    px_convex_destroy(c);
    free(xyz);
}

/* Points whose extent overflows are refused as out of range before any
 * plane is computed (FE_INVALID is trapped here); near-duplicates a few ulps
 * apart, which make faces of noise, are welded and accepted. */
static void test_extent_and_weld(void) {
    const double huge[12] = {-1e308, -1e308, -1e308, 1e308,  -1e308, -1e308,
                             -1e308, 1e308,  -1e308, -1e308, -1e308, 1e308};
    px_error e;
    px_convex *c = px_convex_create(huge, 4, NULL, &e);
    CHECK(c == NULL && e.code == PX_ERR_RANGE, "extent 2e308: %s", e.message);
    /* A torus piece cut out of a mesh: 59 points, nine pairs 1e-16 apart
     * (tests/data/near_duplicates.txt). */
    FILE *f = fopen(PX_TEST_DATA "/../near_duplicates.txt", "r");
    CHECK(f != NULL, "near_duplicates.txt");
    if (!f) return;
    double xyz[3 * 64];
    size_t n = 0;
    while (n < 64 && fscanf(f, "%lf %lf %lf", &xyz[3 * n], &xyz[3 * n + 1], &xyz[3 * n + 2]) == 3) ++n;
    fclose(f);
    c = px_convex_create(xyz, n, NULL, &e);
    CHECK(n == 59 && c != NULL, "near-duplicates: %zu points: %s", n, e.message);
    if (c) {
        /* Every input point lies within the weld distance of the hull. */
        double worst = 0.0;
        for (size_t i = 0; i < n; ++i) {
            px_convex *p = px_convex_create(xyz + 3 * i, 1, NULL, &e);
            px_distance_result r;
            px_pose id = px_pose_identity();
            if (p && px_distance(p, &id, c, &id, NULL, NULL, &r) == PX_OK && !r.intersecting)
                worst = r.distance > worst ? r.distance : worst;
            px_convex_destroy(p);
        }
        CHECK(worst <= 0x1p-39, "near-duplicates: a point %.3g outside the welded hull", worst);
    }
    px_convex_destroy(c);
}

/* A point 5.08e-5 inside a thin piece whose faces are coplanar within
 * rounding at the edge nearest to it (tests/data/lin_canny_inside_point.txt,
 * from a decomposed 1e-4-thick shell): every method finds it inside, from
 * either side and warm. Lin-Canny used to end at that flat edge and answer
 * 5.08e-5. */
static void test_inside_flat_edge(void) {
    FILE *f = fopen(PX_TEST_DATA "/../lin_canny_inside_point.txt", "r");
    CHECK(f != NULL, "lin_canny_inside_point.txt");
    if (!f) return;
    double xyz[3 * 32];
    int n = 0;
    char line[512];
    while (n < 32 && fgets(line, sizeof line, f))
        if (line[0] != '#' && sscanf(line, "%la %la %la", &xyz[3 * n], &xyz[3 * n + 1], &xyz[3 * n + 2]) == 3)
            ++n;
    fclose(f);
    px_error e;
    px_convex *c = n == 24 ? px_convex_create(xyz, 23, NULL, &e) : NULL;
    px_convex *p = n == 24 ? px_convex_create(xyz + 69, 1, NULL, &e) : NULL;
    CHECK(c && p, "inside point: %d rows: %s", n, e.message);
    const px_method methods[3] = {PX_METHOD_LIN_CANNY, PX_METHOD_GJK, PX_METHOD_HYBRID};
    for (int m = 0; c && p && m < 3; ++m) {
        px_query_options o;
        memset(&o, 0, sizeof o);
        o.method = methods[m];
        px_pose id = px_pose_identity();
        px_pair_cache cache = {0};
        for (int k = 0; k < 4; ++k) {
            px_distance_result r;
            int ok = (k & 1 ? px_distance(p, &id, c, &id, &o, &cache, &r)
                            : px_distance(c, &id, p, &id, &o, &cache, &r)) == PX_OK &&
                     r.intersecting && r.distance == 0.0;
            CHECK(ok, "inside point, method %d, call %d: distance %.3g, intersecting %d", m, k, r.distance,
                  r.intersecting);
            if (k == 1) memset(&cache, 0, sizeof cache);
        }
    }
    px_convex_destroy(c);
    px_convex_destroy(p);
}

/* A triangle (three points not certainly collinear under a floating-point
 * filter) is built without CGAL; the same points with the first repeated
 * go through CGAL: the two polytopes must be the same bit for bit (vertices,
 * edges, faces, size), as must a distance query on each, and both must be
 * refused or accepted together. Random triangles at sizes 2^-30..2^30,
 * offsets up to 2^80, nearly collinear (1e-14 off the line), slivers,
 * on an axis plane, and a corner 2^-40 of an edge along it. */
static void test_triangle_without_cgal(int count) {
    pg_rng rng;
    pg_seed(&rng, 3011);
    int compared = 0, refused = 0;
    for (int it = 0; it < count; ++it) {
        double p[12];
        double sc = ldexp(1.0, (int)pg_range(&rng, -30, 30));
        double off = pg_uniform(&rng) < 0.3 ? ldexp(1.0, (int)pg_range(&rng, 0, 80)) : 0.0;
        for (int i = 0; i < 9; ++i) p[i] = off + sc * (pg_uniform(&rng) - 0.5);
        int kind = it % 5;
        for (int k = 0; k < 3; ++k) {
            if (kind == 1) p[6 + k] = p[k] + 0.5 * (p[3 + k] - p[k]) + sc * 1e-14 * (pg_uniform(&rng) - 0.5);
            if (kind == 2) p[6 + k] = p[3 + k] + sc * 1e-9 * (pg_uniform(&rng) - 0.5);
            if (kind == 4) p[6 + k] = p[k] + 0x1p-40 * (p[3 + k] - p[k]);
        }
        if (kind == 3) p[2] = p[5] = p[8] = off;
        memcpy(p + 9, p, 3 * sizeof *p);
        px_error e3, e4;
        px_convex *a = px_convex_create(p, 3, NULL, &e3), *b = px_convex_create(p, 4, NULL, &e4);
        CHECK(!a == !b, "triangle %d (kind %d): %s without CGAL, %s with it", it, kind,
              a ? "built" : e3.message, b ? "built" : e4.message);
        if (a && b) {
            compared++;
            int same = px_convex_vertex_count(a) == px_convex_vertex_count(b) &&
                       px_convex_edge_count(a) == px_convex_edge_count(b) &&
                       px_convex_face_count(a) == px_convex_face_count(b) &&
                       px_convex_dimension(a) == px_convex_dimension(b) &&
                       px_convex_memory_bytes(a) == px_convex_memory_bytes(b);
            for (uint32_t i = 0; same && i < px_convex_vertex_count(a); ++i) {
                px_vec3 x, y;
                px_convex_vertex(a, i, &x);
                px_convex_vertex(b, i, &y);
                same = !memcmp(&x, &y, sizeof x);
            }
            for (uint32_t i = 0; same && i < px_convex_edge_count(a); ++i) {
                uint32_t x[2], y[2];
                px_convex_edge(a, i, x);
                px_convex_edge(b, i, y);
                same = !memcmp(x, y, sizeof x);
            }
            for (uint32_t i = 0; same && i < px_convex_face_count(a); ++i) {
                px_vec3 x, y;
                double dx, dy;
                uint32_t cx, cy;
                px_convex_face(a, i, &x, &dx, &cx);
                px_convex_face(b, i, &y, &dy, &cy);
                same = !memcmp(&x, &y, sizeof x) && dx == dy && cx == cy;
            }
            px_pose ia = px_pose_identity(), tb = ia;
            tb.t = (px_vec3){sc, 0.3 * sc, -0.2 * sc};
            px_distance_result ra, rb;
            same = same && px_distance(a, &ia, a, &tb, NULL, NULL, &ra) == PX_OK &&
                   px_distance(b, &ia, b, &tb, NULL, NULL, &rb) == PX_OK && ra.distance == rb.distance &&
                   !memcmp(&ra.point_a, &rb.point_a, sizeof ra.point_a) &&
                   !memcmp(&ra.point_b, &rb.point_b, sizeof ra.point_b);
            CHECK(same, "triangle %d (kind %d): built without CGAL, it differs from CGAL's", it, kind);
        } else {
            refused++;
        }
        px_convex_destroy(a);
        px_convex_destroy(b);
    }
    printf("  triangles without CGAL: %d equal to CGAL's, %d refused by both\n", compared, refused);
}

/* The inner ball each solid keeps (the scene's test for deeply overlapping
 * pairs) must lie inside the hull of the vertices. Oracle, from the vertices
 * alone (not the face planes' offsets the ball was computed from): a ball
 * (c, r) is inside a convex set iff every direction u has support
 * h(u) >= u.c + r; the tight directions are the true facet normals, here the
 * stored ones (near the true ones but on slivers: the needles below take
 * them in long double) and 2,000 random ones. Also: the ball is not tiny on
 * sphere hulls and boxes (a radius of 0 would pass the first test), and flat
 * bodies have none. */
static void test_inner_ball(void) {
    pg_rng rng;
    pg_seed(&rng, 3101);
    double *xyz = malloc(3 * 600 * sizeof *xyz);
    double worst = INFINITY, least_round = INFINITY;
    int bodies = 0;
    for (int i = 0; i < tu_scaled(180); ++i) {
        pg_kind kind = (pg_kind)(i % PG_KIND_COUNT);
        size_t n =
            pg_shape(&rng, kind, (size_t)pg_log_int(&rng, 8, 600), pow(10.0, pg_range(&rng, -6, 6)), xyz);
        /* Far from the origin now and then: stored coordinates are then
         * relative to an origin in the body. */
        double shift = i % 3 == 0 ? 1e7 * pg_range(&rng, -1, 1) : 0.0;
        for (size_t k = 0; k < 3 * n; ++k) xyz[k] += shift;
        px_convex *c = px_convex_create(xyz, n, NULL, NULL);
        if (!c) continue;
        ++bodies;
        /* In the stored frame (body frame minus the origin), where the ball
         * is kept: adding the origin back rounds by an ulp of it. */
        px_vec3 ic = c->inner_center;
        double r = c->inner_radius, half_width = INFINITY;
        CHECK(r >= 0.0 && r <= c->radius, "inner ball #%d (%s): radius %g of %g", i, pg_kind_name(kind), r,
              c->radius);
        double slack = INFINITY;
        for (uint32_t f = 0; f < c->nf + 2000; ++f) {
            px_vec3 u = f < c->nf ? c->f[f].n : pg_unit(&rng);
            double h = -INFINITY, l = INFINITY;
            for (uint32_t v = 0; v < c->nv; ++v) {
                double t = pxi_dot(u, pxi_sub(c->v[v], ic));
                h = t > h ? t : h;
                l = t < l ? t : l;
            }
            if (h - r < slack) slack = h - r;
            if (f < c->nf && 0.5 * (h - l) < half_width) half_width = 0.5 * (h - l);
        }
        if (r > 0.0) {
            /* Positive up to the rounding of the products above. */
            double noise = 8.0 * DBL_EPSILON * (c->scale + c->radius);
            CHECK(slack >= -noise, "inner ball #%d (%s, n=%zu): sticks out by %g (radius %g)", i,
                  pg_kind_name(kind), n, -slack, r);
            if (slack / c->radius < worst) worst = slack / c->radius;
        }
        /* Boxes and points on a sphere: at least half of the half-width
         * across the faces (for a box the largest possible, reached at its
         * centre, the vertices' mean). */
        if (kind == PG_SPHERE || kind == PG_BOX) {
            CHECK(r >= 0.5 * half_width, "inner ball #%d (%s): radius %g, half-width %g", i,
                  pg_kind_name(kind), r, half_width);
            if (r / half_width < least_round) least_round = r / half_width;
        }
        px_convex_destroy(c);
    }
    /* Needles 1e-4.5 to 1e-6 wide (8 random points, turned): their sliver
     * faces' stored planes tilt by up to 1e-11 rad, far above rounding, and
     * a ball from the stored planes alone stuck out by 4e-12 (a review's
     * finding). The oracle's directions are the faces' normals from the
     * vertices in long double, near the true facets' normals. */
    int needles = 0, with_ball = 0;
    for (int i = 0; i < tu_scaled(3000); ++i) {
        double b = pow(10.0, -pg_range(&rng, 4.5, 6)), q[4], rot[9], p[24];
        for (int k = 0; k < 8; ++k)
            xyz[3 * k] = pg_range(&rng, -b, b), xyz[3 * k + 1] = pg_range(&rng, -b, b),
                    xyz[3 * k + 2] = pg_range(&rng, -1, 1);
        pg_quat_uniform(&rng, q);
        pg_rot_from_quat(q, rot);
        for (int k = 0; k < 8; ++k) {
            px_vec3 v = pg_rot_apply(rot, pxi_v(xyz[3 * k], xyz[3 * k + 1], xyz[3 * k + 2]));
            p[3 * k] = v.x, p[3 * k + 1] = v.y, p[3 * k + 2] = v.z;
        }
        px_convex *nd = px_convex_create(p, 8, NULL, NULL);
        if (!nd) continue;
        ++needles;
        if (nd->inner_radius > 0.0) {
            ++with_ball;
            const px_vec3 w = nd->inner_center;
            double out = -INFINITY;
            for (uint32_t f = 0; f < nd->nf; ++f) {
                const uint32_t *ids = nd->f_verts + nd->f[f].first;
                const px_vec3 o = nd->v[ids[0]];
                long double sx = 0, sy = 0, sz = 0;
                for (uint32_t k = 0; k < nd->f[f].count; ++k) {
                    px_vec3 A = nd->v[ids[k]], B = nd->v[ids[(k + 1) % nd->f[f].count]];
                    long double ax = (long double)A.x - o.x, ay = (long double)A.y - o.y,
                                az = (long double)A.z - o.z;
                    long double bx = (long double)B.x - o.x, by = (long double)B.y - o.y,
                                bz = (long double)B.z - o.z;
                    sx += (ay - by) * (az + bz), sy += (az - bz) * (ax + bx), sz += (ax - bx) * (ay + by);
                }
                long double l = sqrtl(sx * sx + sy * sy + sz * sz), h = -INFINITY;
                if (!(l > 0)) continue;
                sx /= l, sy /= l, sz /= l;
                for (uint32_t v = 0; v < nd->nv; ++v) {
                    long double t =
                        sx * (nd->v[v].x - w.x) + sy * (nd->v[v].y - w.y) + sz * (nd->v[v].z - w.z);
                    if (t > h) h = t;
                }
                if ((double)(nd->inner_radius - h) > out) out = (double)(nd->inner_radius - h);
            }
            CHECK(out <= 8.0 * DBL_EPSILON * nd->scale,
                  "needle #%d (width %.3g): the inner ball sticks out by %g", i, b, out);
        }
        px_convex_destroy(nd);
    }
    printf("  needles: %d, %d with an inner ball, none sticking out\n", needles, with_ball);
    /* A unit cube: the inscribed ball is radius 1/2 at the centre. A
     * cone over a fine base (the vertices' mean sits near the base): the
     * search moves up. */
    double cube[24];
    pg_box(0.5, 0.5, 0.5, cube);
    px_convex *c = px_convex_create(cube, 8, NULL, NULL);
    CHECK(c && fabs(c->inner_radius - 0.5) < 1e-9, "cube: inner radius %g", c ? c->inner_radius : -1.0);
    px_convex_destroy(c);
    /* At every scale the library takes (a bound that squared areas lost
     * the ball below 2^-270). */
    for (int k = -480; k <= 480; k += 120) {
        double h = ldexp(1.0, k), box[24];
        pg_box(h, h, h, box);
        c = px_convex_create(box, 8, NULL, NULL);
        CHECK(c && fabs(c->inner_radius / h - 1.0) < 1e-9, "cube of half-side 2^%d: inner radius %g", k,
              c ? c->inner_radius / h : -1.0);
        px_convex_destroy(c);
    }
    size_t nb = 0;
    for (int k = 0; k < 200; ++k, ++nb) {
        xyz[3 * nb] = cos(2 * M_PI * k / 200), xyz[3 * nb + 1] = sin(2 * M_PI * k / 200), xyz[3 * nb + 2] = 0;
    }
    xyz[3 * nb] = 0, xyz[3 * nb + 1] = 0, xyz[3 * nb + 2] = 3, ++nb;
    c = px_convex_create(xyz, nb, NULL, NULL);
    /* The cone's inscribed ball: radius 3 / (1 + sqrt 10) = 0.72 about
     * (0, 0, 0.72); from the mean (height 3 / 201) straight up. */
    CHECK(c && c->inner_radius > 0.6, "cone: inner radius %g (best 0.72)", c ? c->inner_radius : -1.0);
    px_convex_destroy(c);
    /* Flat: a square has no inner ball. */
    double sq[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    c = px_convex_create(sq, 4, NULL, NULL);
    CHECK(c && c->inner_radius == 0.0, "square: inner radius %g", c ? c->inner_radius : -1.0);
    px_convex_destroy(c);
    printf(
        "  inner balls: %d bodies, least slack %.3g of the radius; boxes and spheres: at least %.2f of the "
        "half-width\n",
        bodies, worst, least_round);
    free(xyz);
}

int main(void) {
    tu_init("test_convex");
    test_inner_ball();
    test_triangle_without_cgal(tu_scaled(20000));
    test_inside_flat_edge();
    test_extent_and_weld();
    double t0 = tu_now();
    test_coplanar_merging();
    test_degenerate_inputs();
    test_random_polytopes(tu_scaled(300));
    test_allocator();
    test_out_of_memory();
    printf("  %ld polytopes validated; bytes per vertex: min %.0f, max %.0f (limit 1024); %.2f s\n",
           g_polytopes, g_min_bytes_per_vertex, g_max_bytes_per_vertex, tu_now() - t0);
    return tu_finish();
}
