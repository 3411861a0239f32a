/* Standalone test of the pxcd C ABI (convexdecomp/pxcd.h).
 *
 *   test_pxcd          run the tests; exit status 0 iff all pass
 *   test_pxcd --bench  also time a 200k-point ellipsoid hull and the exact
 *                      distance between two 5k-vertex hulls
 *
 * Hull checks used throughout (check_hull): the combinatorics promised by
 * pxcd.h (ids in range, no repeated vertex in a face, every undirected edge
 * in exactly two faces with opposite directions, Euler V - E + F = 2),
 * vertices bit-identical to some input point, outward CCW faces (Newell
 * normal points away from the vertex centroid) and all input points on the
 * inner side of every face plane (up to a rounding tolerance). For small
 * integer inputs the geometry is checked exactly: every face is planar,
 * strictly convex at every corner (so every vertex is extreme) and no input
 * point is strictly outside any face.
 */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */

#include "pxcd.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define PI 3.14159265358979323846

static int g_passed = 0, g_failed = 0;

#define CHECK(cond, ...)                                                        \
    do {                                                                        \
        if (cond) {                                                             \
            ++g_passed;                                                         \
        } else {                                                                \
            ++g_failed;                                                         \
            printf("FAIL %s:%d: %s: ", __FILE__, __LINE__, #cond);              \
            printf(__VA_ARGS__);                                                \
            printf("\n");                                                       \
        }                                                                       \
    } while (0)

/* ---------- small helpers ---------- */

static uint64_t g_rng = 0x9E3779B97F4A7C15ull;
static double rnd01(void) { /* xorshift64*, uniform in [0,1) */
    g_rng ^= g_rng >> 12;
    g_rng ^= g_rng << 25;
    g_rng ^= g_rng >> 27;
    return (double)((g_rng * 0x2545F4914F6CDD1Dull) >> 11) * 0x1.0p-53;
}

static double now_seconds(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void shuffle_points(double *xyz, size_t n) {
    for (size_t i = n; i > 1; --i) {
        size_t j = (size_t)(rnd01() * (double)i);
        for (int k = 0; k < 3; ++k) {
            double t = xyz[3 * (i - 1) + k];
            xyz[3 * (i - 1) + k] = xyz[3 * j + k];
            xyz[3 * j + k] = t;
        }
    }
}

static size_t edge_count(const pxcd_hull *h) { return h->face_offsets[h->face_count] / 2; }

static int cmp_u64(const void *a, const void *b) {
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

/* Returns 1 if the hull passes all generic checks (reports failures). When
 * exact_ints is set the input coordinates are small integers and the
 * geometric checks are exact. */
static int check_hull(const pxcd_hull *h, const double *xyz, size_t n, int exact_ints) {
    int ok = 1;
    const size_t V = h->vertex_count, F = h->face_count, NI = h->face_offsets[F];
    if (h->face_offsets[0] != 0 || NI % 2 != 0 || V < 4 || F < 4) {
        printf("  bad sizes V=%zu F=%zu indices=%zu\n", V, F, NI);
        return 0;
    }
    /* Combinatorics. */
    uint64_t *keys = malloc(NI * sizeof *keys);
    size_t *stamp = malloc(V * sizeof *stamp);
    char *used = calloc(V, 1);
    for (size_t v = 0; v < V; ++v) stamp[v] = (size_t)-1;
    for (size_t f = 0; f < F && ok; ++f) {
        size_t b = h->face_offsets[f], e = h->face_offsets[f + 1];
        if (e < b + 3) { printf("  face %zu has %zu vertices\n", f, e - b); ok = 0; break; }
        for (size_t i = b; i < e; ++i) {
            uint64_t u = h->face_indices[i], w = h->face_indices[i + 1 < e ? i + 1 : b];
            if (u >= V) { printf("  id out of range\n"); ok = 0; break; }
            if (stamp[u] == f) { printf("  face %zu repeats vertex %u\n", f, (unsigned)u); ok = 0; break; }
            stamp[u] = f;
            used[u] = 1;
            uint64_t lo = u < w ? u : w, hi = u < w ? w : u;
            keys[i] = (lo << 33) | (hi << 1) | (u < w ? 0u : 1u);
        }
    }
    if (ok) {
        qsort(keys, NI, sizeof *keys, cmp_u64);
        for (size_t i = 0; i < NI; i += 2)
            if ((keys[i] & 1u) || keys[i + 1] != (keys[i] | 1u) ||
                (i + 2 < NI && (keys[i + 2] >> 1) == (keys[i] >> 1))) {
                printf("  edges not paired with opposite directions\n");
                ok = 0;
                break;
            }
        for (size_t v = 0; v < V && ok; ++v)
            if (!used[v]) { printf("  vertex %zu unused\n", v); ok = 0; }
        if (ok && V + F != NI / 2 + 2) { printf("  Euler fails: V=%zu E=%zu F=%zu\n", V, NI / 2, F); ok = 0; }
    }
    free(keys);
    free(stamp);
    free(used);
    if (!ok) return 0;

    /* Vertices are bit-identical copies of input points. */
    for (size_t v = 0; v < V && ok; ++v) {
        int found = 0;
        for (size_t i = 0; i < n && !found; ++i)
            found = memcmp(&h->vertices[3 * v], &xyz[3 * i], 3 * sizeof(double)) == 0;
        if (!found) { printf("  vertex %zu is not an input point\n", v); ok = 0; }
    }

    /* Geometry: outward orientation, points inside. */
    double c[3] = {0, 0, 0}, scale = 0;
    for (size_t v = 0; v < V; ++v)
        for (int k = 0; k < 3; ++k) {
            c[k] += h->vertices[3 * v + k] / (double)V;
            if (fabs(h->vertices[3 * v + k]) > scale) scale = fabs(h->vertices[3 * v + k]);
        }
    for (size_t f = 0; f < F && ok; ++f) {
        size_t b = h->face_offsets[f], e = h->face_offsets[f + 1], m = e - b;
        const double *p0 = &h->vertices[3 * h->face_indices[b]];
        double nrm[3] = {0, 0, 0};
        for (size_t i = 0; i < m; ++i) { /* Newell normal */
            const double *p = &h->vertices[3 * h->face_indices[b + i]];
            const double *q = &h->vertices[3 * h->face_indices[b + (i + 1) % m]];
            nrm[0] += (p[1] - q[1]) * (p[2] + q[2]);
            nrm[1] += (p[2] - q[2]) * (p[0] + q[0]);
            nrm[2] += (p[0] - q[0]) * (p[1] + q[1]);
        }
        double len = sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
        double out = nrm[0] * (p0[0] - c[0]) + nrm[1] * (p0[1] - c[1]) + nrm[2] * (p0[2] - c[2]);
        if (!(len > 0 && out > 0)) { printf("  face %zu not outward\n", f); ok = 0; break; }
        if (exact_ints) {
            /* With small integers all products below are exact doubles. */
            for (size_t i = 0; i < m && ok; ++i) {
                const double *p = &h->vertices[3 * h->face_indices[b + (i + m - 1) % m]];
                const double *q = &h->vertices[3 * h->face_indices[b + i]];
                const double *r = &h->vertices[3 * h->face_indices[b + (i + 1) % m]];
                double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
                double w[3] = {r[0] - q[0], r[1] - q[1], r[2] - q[2]};
                double x[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2],
                               u[0] * w[1] - u[1] * w[0]};
                double turn = x[0] * nrm[0] + x[1] * nrm[1] + x[2] * nrm[2];
                double off = nrm[0] * (q[0] - p0[0]) + nrm[1] * (q[1] - p0[1]) + nrm[2] * (q[2] - p0[2]);
                if (off != 0) { printf("  face %zu not planar\n", f); ok = 0; }
                else if (!(turn > 0)) { printf("  face %zu not strictly convex at corner %zu\n", f, i); ok = 0; }
            }
        }
        double tol = exact_ints ? 0.0 : 1e-12 * len * scale;
        for (size_t i = 0; i < n && ok; ++i) {
            const double *p = &xyz[3 * i];
            double s = nrm[0] * (p[0] - p0[0]) + nrm[1] * (p[1] - p0[1]) + nrm[2] * (p[2] - p0[2]);
            if (s > tol) { printf("  input point %zu outside face %zu (%g)\n", i, f, s); ok = 0; }
        }
    }
    return ok;
}

static pxcd_hull *hull_of(const double *xyz, size_t n, pxcd_status *st, int *dim) {
    char msg[256] = "";
    pxcd_hull *h = NULL;
    *dim = -1;
    *st = pxcd_hull_compute(xyz, n, &h, dim, msg, sizeof msg);
    if (*st == PXCD_ERROR) printf("  pxcd_hull_compute error: %s\n", msg);
    return h;
}

/* ---------- hull tests ---------- */

static void test_cube_with_extras(void) {
    /* Corners, face centres, edge midpoints and the centre of [-1,1]^3: the
     * 27 points of the {-1,0,1}^3 grid. Only the corners are extreme. */
    double xyz[27 * 3];
    size_t n = 0;
    for (int x = -1; x <= 1; ++x)
        for (int y = -1; y <= 1; ++y)
            for (int z = -1; z <= 1; ++z) {
                xyz[3 * n] = x, xyz[3 * n + 1] = y, xyz[3 * n + 2] = z;
                ++n;
            }
    for (int round = 0; round < 20; ++round) { /* several input orders */
        if (round > 0) shuffle_points(xyz, n);
        pxcd_status st;
        int dim;
        pxcd_hull *h = hull_of(xyz, n, &st, &dim);
        CHECK(st == PXCD_OK && h, "status %d", (int)st);
        if (!h) continue;
        CHECK(h->vertex_count == 8 && h->face_count == 6 && edge_count(h) == 12,
              "V=%zu F=%zu E=%zu", h->vertex_count, h->face_count, edge_count(h));
        int quads = 1;
        for (size_t f = 0; f < h->face_count; ++f)
            quads &= h->face_offsets[f + 1] - h->face_offsets[f] == 4;
        CHECK(quads, "not all faces are quads");
        int corners = 1;
        for (size_t i = 0; i < 3 * h->vertex_count; ++i)
            corners &= fabs(h->vertices[i]) == 1.0;
        CHECK(corners, "a hull vertex is not a cube corner");
        CHECK(dim == 3, "dim=%d", dim);
        CHECK(check_hull(h, xyz, n, 1), "cube hull checks");
        pxcd_hull_free(h);
    }
}

static void test_tetrahedron(void) {
    double xyz[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0.1, 0.1, 0.1};
    pxcd_status st;
    int dim;
    pxcd_hull *h = hull_of(xyz, 5, &st, &dim);
    CHECK(st == PXCD_OK && h, "status %d", (int)st);
    if (!h) return;
    CHECK(h->vertex_count == 4 && h->face_count == 4 && edge_count(h) == 6,
          "V=%zu F=%zu E=%zu", h->vertex_count, h->face_count, edge_count(h));
    CHECK(check_hull(h, xyz, 5, 0), "tetrahedron hull checks");
    pxcd_hull_free(h);
}

static void test_sphere(size_t n) {
    double *xyz = malloc(3 * n * sizeof *xyz);
    for (size_t i = 0; i < n; ++i) {
        double z = 2 * rnd01() - 1, t = 2 * PI * rnd01(), r = sqrt(1 - z * z);
        xyz[3 * i] = r * cos(t), xyz[3 * i + 1] = r * sin(t), xyz[3 * i + 2] = z;
    }
    pxcd_status st;
    int dim;
    pxcd_hull *h = hull_of(xyz, n, &st, &dim);
    CHECK(st == PXCD_OK && h, "status %d", (int)st);
    if (h) {
        /* Rounded points are not exactly on the sphere, but with this few
         * points essentially all are extreme and in general position. */
        CHECK(h->vertex_count > n * 9 / 10 && h->vertex_count <= n, "V=%zu of %zu", h->vertex_count, n);
        CHECK(check_hull(h, xyz, n, 0), "sphere hull checks");
        /* Deterministic: same input, same output. */
        pxcd_hull *g = hull_of(xyz, n, &st, &dim);
        CHECK(g && g->vertex_count == h->vertex_count && g->face_count == h->face_count &&
                  memcmp(g->vertices, h->vertices, 3 * h->vertex_count * sizeof(double)) == 0 &&
                  memcmp(g->face_offsets, h->face_offsets, (h->face_count + 1) * sizeof(size_t)) == 0 &&
                  memcmp(g->face_indices, h->face_indices,
                         h->face_offsets[h->face_count] * sizeof(uint32_t)) == 0,
              "hull not deterministic");
        pxcd_hull_free(g);
        pxcd_hull_free(h);
    }
    free(xyz);
}

/* Points on the 12 edges (and faces) of a box, random order: many collinear
 * and coplanar non-extreme points, the case that makes quickhull keep
 * non-extreme vertices. */
static void test_box_edges(void) {
    enum { K = 9 };
    const double size[3] = {8, 8, 4}; /* box [0,8]x[0,8]x[0,4] */
    double xyz[3 * (12 * K + 6 * K * K)];
    size_t n = 0;
    for (int axis = 0; axis < 3; ++axis)
        for (int s1 = 0; s1 < 2; ++s1)
            for (int s2 = 0; s2 < 2; ++s2)
                for (int k = 0; k < K; ++k) {
                    const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
                    double p[3];
                    p[axis] = k * size[axis] / (K - 1);
                    p[a1] = s1 ? size[a1] : 0;
                    p[a2] = s2 ? size[a2] : 0;
                    memcpy(&xyz[3 * n++], p, sizeof p);
                }
    const size_t n_edges = n;
    for (int axis = 0; axis < 3; ++axis) /* plus grids on the six faces */
        for (int s = 0; s < 2; ++s)
            for (int a = 0; a < K; ++a)
                for (int b = 0; b < K; ++b) {
                    const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
                    double p[3];
                    p[axis] = s ? size[axis] : 0;
                    p[a1] = a * size[a1] / (K - 1);
                    p[a2] = b * size[a2] / (K - 1);
                    memcpy(&xyz[3 * n++], p, sizeof p);
                }
    for (int round = 0; round < 30; ++round) {
        size_t m = round % 2 ? n : n_edges;
        shuffle_points(xyz, m);
        pxcd_status st;
        int dim;
        pxcd_hull *h = hull_of(xyz, m, &st, &dim);
        CHECK(st == PXCD_OK && h, "status %d", (int)st);
        if (!h) continue;
        CHECK(h->vertex_count == 8 && h->face_count == 6 && edge_count(h) == 12,
              "round %d: V=%zu F=%zu E=%zu", round, h->vertex_count, h->face_count, edge_count(h));
        CHECK(check_hull(h, xyz, m, 1), "box hull checks");
        pxcd_hull_free(h);
    }
}

/* Random small-integer points: heavy coplanarity, exact checks. */
static void test_random_lattice(void) {
    enum { N = 400 };
    double xyz[3 * N];
    for (int round = 0; round < 40; ++round) {
        int range = 2 + round % 6;
        for (size_t i = 0; i < 3 * N; ++i) xyz[i] = floor(rnd01() * (range + 1)) - range / 2;
        size_t n = 8 + (size_t)(rnd01() * (N - 8));
        pxcd_status st;
        int dim;
        pxcd_hull *h = hull_of(xyz, n, &st, &dim);
        CHECK(st == PXCD_OK && h, "status %d", (int)st);
        if (!h) continue;
        CHECK(check_hull(h, xyz, n, 1), "lattice round %d (range %d, n %zu)", round, range, n);
        pxcd_hull_free(h);
    }
    /* Octahedron with its lattice interior: 6 vertices, 8 triangles. */
    size_t n = 0;
    double oct[3 * 7 * 7 * 7];
    for (int x = -3; x <= 3; ++x)
        for (int y = -3; y <= 3; ++y)
            for (int z = -3; z <= 3; ++z)
                if (abs(x) + abs(y) + abs(z) <= 3) {
                    oct[3 * n] = x, oct[3 * n + 1] = y, oct[3 * n + 2] = z;
                    ++n;
                }
    shuffle_points(oct, n);
    pxcd_status st;
    int dim;
    pxcd_hull *h = hull_of(oct, n, &st, &dim);
    CHECK(st == PXCD_OK && h && h->vertex_count == 6 && h->face_count == 8,
          "octahedron: V=%zu F=%zu", h ? h->vertex_count : 0, h ? h->face_count : 0);
    if (h) CHECK(check_hull(h, oct, n, 1), "octahedron hull checks");
    pxcd_hull_free(h);
}

static void test_degenerate(void) {
    pxcd_status st;
    int dim;
    pxcd_hull *h;
    double one[] = {1.5, -2, 3};
    h = hull_of(one, 1, &st, &dim);
    CHECK(st == PXCD_DEGENERATE && dim == 0 && !h, "single point: st=%d dim=%d", (int)st, dim);

    double same[5 * 3];
    for (int i = 0; i < 5; ++i) memcpy(&same[3 * i], one, sizeof one);
    h = hull_of(same, 5, &st, &dim);
    CHECK(st == PXCD_DEGENERATE && dim == 0 && !h, "repeated point: st=%d dim=%d", (int)st, dim);

    double line[6 * 3];
    for (int i = 0; i < 6; ++i) line[3 * i] = 1 + i, line[3 * i + 1] = 2 + 2 * i, line[3 * i + 2] = -3 * i;
    memcpy(&line[3 * 5], &line[0], 3 * sizeof(double)); /* duplicates too */
    h = hull_of(line, 6, &st, &dim);
    CHECK(st == PXCD_DEGENERATE && dim == 1 && !h, "collinear: st=%d dim=%d", (int)st, dim);

    double plane[50 * 3];
    for (int i = 0; i < 50; ++i) {
        double a = floor(rnd01() * 100), b = floor(rnd01() * 100);
        plane[3 * i] = a, plane[3 * i + 1] = b, plane[3 * i + 2] = 3 * a - 2 * b + 7;
    }
    h = hull_of(plane, 50, &st, &dim);
    CHECK(st == PXCD_DEGENERATE && dim == 2 && !h, "coplanar: st=%d dim=%d", (int)st, dim);

    /* Almost coplanar: one point off the plane by one ulp is 3D. */
    plane[3 * 49 + 2] = nextafter(plane[3 * 49 + 2], INFINITY);
    h = hull_of(plane, 50, &st, &dim);
    CHECK(st == PXCD_OK && dim == 3 && h, "nearly coplanar: st=%d dim=%d", (int)st, dim);
    if (h) CHECK(check_hull(h, plane, 50, 0), "nearly coplanar hull checks");
    pxcd_hull_free(h);

    char msg[128] = "";
    h = (pxcd_hull *)1;
    st = pxcd_hull_compute(one, 0, &h, &dim, msg, sizeof msg);
    CHECK(st == PXCD_ERROR && h == NULL && msg[0] != 0, "empty input: st=%d", (int)st);
    pxcd_hull_free(NULL);
}

/* ---------- exact distance tests ---------- */

static void tetra(double s, double z0, int up, double out[12]) {
    /* Right-angle tetrahedron with a face in the plane z = z0 and apex at
     * z0 + s (up) or z0 - s (down). */
    double v[12] = {0, 0, z0, s, 0, z0, 0, s, z0, 0, 0, up ? z0 + s : z0 - s};
    memcpy(out, v, sizeof v);
}

static void test_distance_scales(void) {
    const double scales[] = {1e-23, 1e-150, 1e150, 1e-170, 1.0, 3.0e-7, 7.0e100};
    for (size_t i = 0; i < sizeof scales / sizeof scales[0]; ++i) {
        double s = scales[i], P[12], Q[12];
        tetra(s, 0, 0, P);     /* below z = 0 */
        tetra(s, s, 1, Q);     /* above z = s: exact gap s */
        double d = -1, d2 = -1, rp[3], rq[3];
        int zero = -1;
        char msg[256] = "";
        pxcd_status st = pxcd_exact_distance(P, 4, Q, 4, &d, &d2, &zero, rp, rq, msg, sizeof msg);
        CHECK(st == PXCD_OK, "s=%g: %s", s, msg);
        /* The exact distance is s, a double, so the correctly rounded
         * result is exactly s. */
        CHECK(d == s && zero == 0, "s=%g: d=%.17g zero=%d", s, d, zero);
        double s2 = s * s; /* correctly rounded by IEEE, incl. underflow */
        CHECK(d2 == s2, "s=%g: d2=%.17g expected %.17g", s, d2, s2);
        CHECK(rp[2] == 0 && rq[2] == s && fabs(rp[0] - rq[0]) <= 0 && fabs(rp[1] - rq[1]) <= 0,
              "s=%g: realizing points (%g %g %g) (%g %g %g)", s, rp[0], rp[1], rp[2], rq[0], rq[1], rq[2]);
    }
    /* A distance that is not a double: gap sqrt(2)*s between a point and an
     * edge; checks correct rounding of an irrational result at extreme scales. */
    const double scales2[] = {1e-170, 1e-23, 1.0, 1e150};
    for (size_t i = 0; i < sizeof scales2 / sizeof scales2[0]; ++i) {
        double s = scales2[i];
        double P[] = {0, 0, 0};
        double Q[] = {s, s, 0, s, s, s}; /* segment x=y=s, distance s*sqrt(2) */
        double d = -1;
        int zero = -1;
        char msg[256] = "";
        pxcd_status st = pxcd_exact_distance(P, 1, Q, 2, &d, NULL, &zero, NULL, NULL, msg, sizeof msg);
        double expect = sqrt(2.0) * s; /* not necessarily correctly rounded */
        CHECK(st == PXCD_OK && zero == 0 && fabs(d - expect) <= 2 * (nextafter(expect, INFINITY) - expect),
              "s=%g: d=%.17g expected ~%.17g (%s)", s, d, expect, msg);
    }
}

static void unit_cube(double x0, double out[24]) {
    for (int i = 0; i < 8; ++i) {
        out[3 * i] = x0 + (i & 1), out[3 * i + 1] = (i >> 1) & 1, out[3 * i + 2] = (i >> 2) & 1;
    }
}

static void test_distance_cubes(void) {
    double A[24], B[24];
    unit_cube(0, A);
    unit_cube(1.5, B);
    double d = -1, d2 = -1, rp[3], rq[3];
    int zero = -1;
    char msg[256] = "";
    pxcd_status st = pxcd_exact_distance(A, 8, B, 8, &d, &d2, &zero, rp, rq, msg, sizeof msg);
    CHECK(st == PXCD_OK && d == 0.5 && d2 == 0.25 && zero == 0, "gap cubes: st=%d d=%g d2=%g zero=%d %s",
          (int)st, d, d2, zero, msg);
    CHECK(rp[0] == 1 && rq[0] == 1.5 && rp[1] == rq[1] && rp[2] == rq[2] && rp[1] >= 0 && rp[1] <= 1 &&
              rp[2] >= 0 && rp[2] <= 1,
          "gap cubes realizing points (%g %g %g) (%g %g %g)", rp[0], rp[1], rp[2], rq[0], rq[1], rq[2]);

    unit_cube(1, B); /* touching along a face */
    st = pxcd_exact_distance(A, 8, B, 8, &d, &d2, &zero, NULL, NULL, msg, sizeof msg);
    CHECK(st == PXCD_OK && zero == 1 && d == 0 && d2 == 0, "touching cubes: d=%g zero=%d", d, zero);

    unit_cube(0.25, B); /* overlapping */
    st = pxcd_exact_distance(A, 8, B, 8, &d, &d2, &zero, NULL, NULL, msg, sizeof msg);
    CHECK(st == PXCD_OK && zero == 1 && d == 0, "overlapping cubes: d=%g zero=%d", d, zero);

    /* A gap of one ulp at 1: tiny but not zero. */
    unit_cube(nextafter(1.0, 2.0), B);
    st = pxcd_exact_distance(A, 8, B, 8, &d, &d2, &zero, NULL, NULL, msg, sizeof msg);
    CHECK(st == PXCD_OK && zero == 0 && d == 0x1.0p-52, "one-ulp gap: d=%a zero=%d", d, zero);

    st = pxcd_exact_distance(A, 0, B, 8, &d, &d2, &zero, NULL, NULL, msg, sizeof msg);
    CHECK(st == PXCD_ERROR && msg[0] != 0, "empty P: st=%d", (int)st);
}

/* ---------- benchmark ---------- */

static double *ellipsoid(size_t n, double a, double b, double c, double cx) {
    double *xyz = malloc(3 * n * sizeof *xyz);
    for (size_t i = 0; i < n; ++i) {
        double z = 2 * rnd01() - 1, t = 2 * PI * rnd01(), r = sqrt(1 - z * z);
        xyz[3 * i] = cx + a * r * cos(t), xyz[3 * i + 1] = b * r * sin(t), xyz[3 * i + 2] = c * z;
    }
    return xyz;
}

static void bench(void) {
    const size_t n = 200000;
    double *xyz = ellipsoid(n, 3, 2, 1, 0);
    pxcd_status st;
    int dim;
    double t0 = now_seconds();
    pxcd_hull *h = hull_of(xyz, n, &st, &dim);
    double t1 = now_seconds();
    printf("bench: hull of %zu ellipsoid points: %.3f s, V=%zu F=%zu\n", n, t1 - t0,
           h ? h->vertex_count : 0, h ? h->face_count : 0);
    pxcd_hull_free(h);
    free(xyz);

    /* Two hulls of 5k vertices each (ellipsoids, gap ~0.5 along x). */
    const size_t m = 5000;
    double *P = ellipsoid(m, 1, 1.5, 2, 0), *Q = ellipsoid(m, 2, 1, 1, 3.5);
    pxcd_hull *hp = hull_of(P, m, &st, &dim), *hq = hull_of(Q, m, &st, &dim);
    if (hp && hq) {
        double d = 0, rp[3], rq[3];
        int zero = 0;
        char msg[256] = "";
        t0 = now_seconds();
        st = pxcd_exact_distance(hp->vertices, hp->vertex_count, hq->vertices, hq->vertex_count, &d,
                                 NULL, &zero, rp, rq, msg, sizeof msg);
        t1 = now_seconds();
        printf("bench: exact distance %zu x %zu vertices: %.3f s, d=%.17g st=%d %s\n", hp->vertex_count,
               hq->vertex_count, t1 - t0, d, (int)st, msg);
    }
    pxcd_hull_free(hp);
    pxcd_hull_free(hq);
    free(P);
    free(Q);
}

int main(int argc, char **argv) {
    test_cube_with_extras();
    test_tetrahedron();
    test_sphere(2000);
    test_box_edges();
    test_random_lattice();
    test_degenerate();
    test_distance_scales();
    test_distance_cubes();
    if (argc > 1 && strcmp(argv[1], "--bench") == 0) bench();
    printf("%d passed, %d failed\n", g_passed, g_failed);
    return g_failed == 0 ? 0 : 1;
}
