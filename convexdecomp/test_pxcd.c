/* Standalone test of the pxcd C ABI (convexdecomp/pxcd.h).
 *
 *   test_pxcd                 run the tests; exit status 0 iff all pass
 *   test_pxcd --exact-kernel  the same, every hull computed with the exact
 *                             rational kernel (PXCD_HULL_FORCE_EXACT_KERNEL,
 *                             the fallback used under valgrind)
 *   test_pxcd --bench         also time a 200k-point ellipsoid hull and the
 *                             exact distance between two 5k-vertex hulls
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
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>

/* AddressSanitizer (PROXIMA_SANITIZE) cannot run under an address-space limit. */
#if defined(__SANITIZE_ADDRESS__)
#define PXCD_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define PXCD_TEST_ASAN 1
#endif
#endif
#ifndef PXCD_TEST_ASAN
#define PXCD_TEST_ASAN 0
#endif

#define PI 3.14159265358979323846

static int g_passed = 0, g_failed = 0;

#define CHECK(cond, ...)                                                                                     \
    do {                                                                                                     \
        if (cond) {                                                                                          \
            ++g_passed;                                                                                      \
        } else {                                                                                             \
            ++g_failed;                                                                                      \
            printf("FAIL %s:%d: %s: ", __FILE__, __LINE__, #cond);                                           \
            printf(__VA_ARGS__);                                                                             \
            printf("\n");                                                                                    \
        }                                                                                                    \
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

static double cpu_seconds(void) { return (double)clock() / CLOCKS_PER_SEC; }

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

/* How check_hull checks the geometry. */
enum {
    GEOM_FLOAT = 0, /* floating point, with a tolerance */
    GEOM_EXACT = 1, /* inputs are small integers or halves: exact checks */
    GEOM_NONE = 2   /* ill-conditioned (nearly flat) hull: no geometry */
};

/* Returns 1 if the hull passes all checks (and prints why not). */
static int check_hull(const pxcd_hull *h, const double *xyz, size_t n, int geom) {
    const int exact_ints = geom == GEOM_EXACT;
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
        if (e < b + 3) {
            printf("  face %zu has %zu vertices\n", f, e - b);
            ok = 0;
            break;
        }
        for (size_t i = b; i < e; ++i) {
            uint64_t u = h->face_indices[i], w = h->face_indices[i + 1 < e ? i + 1 : b];
            if (u >= V) {
                printf("  id out of range\n");
                ok = 0;
                break;
            }
            if (stamp[u] == f) {
                printf("  face %zu repeats vertex %u\n", f, (unsigned)u);
                ok = 0;
                break;
            }
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
            if (!used[v]) {
                printf("  vertex %zu unused\n", v);
                ok = 0;
            }
        if (ok && V + F != NI / 2 + 2) {
            printf("  Euler fails: V=%zu E=%zu F=%zu\n", V, NI / 2, F);
            ok = 0;
        }
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
        if (!found) {
            printf("  vertex %zu is not an input point\n", v);
            ok = 0;
        }
    }

    if (!ok || geom == GEOM_NONE) return ok;

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
        if (!(len > 0 && out > 0)) {
            printf("  face %zu not outward\n", f);
            ok = 0;
            break;
        }
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
                if (off != 0) {
                    printf("  face %zu not planar\n", f);
                    ok = 0;
                } else if (!(turn > 0)) {
                    printf("  face %zu not strictly convex at corner %zu\n", f, i);
                    ok = 0;
                }
            }
        }
        double tol = exact_ints ? 0.0 : 1e-12 * len * scale;
        for (size_t i = 0; i < n && ok; ++i) {
            const double *p = &xyz[3 * i];
            double s = nrm[0] * (p[0] - p0[0]) + nrm[1] * (p[1] - p0[1]) + nrm[2] * (p[2] - p0[2]);
            if (s > tol) {
                printf("  input point %zu outside face %zu (%g)\n", i, f, s);
                ok = 0;
            }
        }
    }
    return ok;
}

/* Flags of every hull computed by the tests (--exact-kernel). */
static unsigned g_hull_flags = 0;

static pxcd_hull *hull_of(const double *xyz, size_t n, pxcd_status *st, int *dim) {
    char msg[256] = "";
    pxcd_hull *h = NULL;
    *dim = -1;
    *st = pxcd_hull_compute_ex(xyz, n, g_hull_flags, &h, dim, msg, sizeof msg);
    if (*st == PXCD_ERROR || *st == PXCD_OUT_OF_MEMORY) printf("  pxcd_hull_compute error: %s\n", msg);
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
        CHECK(h->vertex_count == 8 && h->face_count == 6 && edge_count(h) == 12, "V=%zu F=%zu E=%zu",
              h->vertex_count, h->face_count, edge_count(h));
        int quads = 1;
        for (size_t f = 0; f < h->face_count; ++f) quads &= h->face_offsets[f + 1] - h->face_offsets[f] == 4;
        CHECK(quads, "not all faces are quads");
        int corners = 1;
        for (size_t i = 0; i < 3 * h->vertex_count; ++i) corners &= fabs(h->vertices[i]) == 1.0;
        CHECK(corners, "a hull vertex is not a cube corner");
        CHECK(dim == 3, "dim=%d", dim);
        CHECK(check_hull(h, xyz, n, GEOM_EXACT), "cube hull checks");
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
    CHECK(h->vertex_count == 4 && h->face_count == 4 && edge_count(h) == 6, "V=%zu F=%zu E=%zu",
          h->vertex_count, h->face_count, edge_count(h));
    CHECK(check_hull(h, xyz, 5, GEOM_FLOAT), "tetrahedron hull checks");
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
        CHECK(check_hull(h, xyz, n, GEOM_FLOAT), "sphere hull checks");
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
    double *pts = malloc(sizeof xyz);
    for (int round = 0; round < 30; ++round) {
        /* Even rounds: edge points only; odd rounds: edges and faces. */
        size_t m = round % 2 ? n : n_edges;
        memcpy(pts, xyz, m * 3 * sizeof(double));
        shuffle_points(pts, m);
        pxcd_status st;
        int dim;
        pxcd_hull *h = hull_of(pts, m, &st, &dim);
        CHECK(st == PXCD_OK && h, "status %d", (int)st);
        if (!h) continue;
        CHECK(h->vertex_count == 8 && h->face_count == 6 && edge_count(h) == 12,
              "round %d: V=%zu F=%zu E=%zu", round, h->vertex_count, h->face_count, edge_count(h));
        CHECK(check_hull(h, pts, m, GEOM_EXACT), "box hull checks");
        pxcd_hull_free(h);
    }
    free(pts);
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
        CHECK(check_hull(h, xyz, n, GEOM_EXACT), "lattice round %d (range %d, n %zu)", round, range, n);
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
    CHECK(st == PXCD_OK && h && h->vertex_count == 6 && h->face_count == 8, "octahedron: V=%zu F=%zu",
          h ? h->vertex_count : 0, h ? h->face_count : 0);
    if (h) CHECK(check_hull(h, oct, n, GEOM_EXACT), "octahedron hull checks");
    pxcd_hull_free(h);
}

/* The 27-point cube grid scaled to extreme magnitudes and offset: the
 * predicates overflow/underflow the filters and must fall back to exact
 * arithmetic. Also signed zeros: the vertex keeps its first occurrence's
 * bits. */
static void test_hull_scales(void) {
    const double scales[] = {1e-300, 1e-150, 1e150, 1e300};
    double xyz[27 * 3];
    for (size_t k = 0; k < sizeof scales / sizeof scales[0]; ++k) {
        double s = scales[k];
        size_t n = 0;
        for (int x = -1; x <= 1; ++x)
            for (int y = -1; y <= 1; ++y)
                for (int z = -1; z <= 1; ++z) {
                    xyz[3 * n] = x * s + 3 * s, xyz[3 * n + 1] = y * s, xyz[3 * n + 2] = z * s - 5 * s;
                    ++n;
                }
        shuffle_points(xyz, n);
        pxcd_status st;
        int dim;
        pxcd_hull *h = hull_of(xyz, n, &st, &dim);
        CHECK(st == PXCD_OK && h && h->vertex_count == 8 && h->face_count == 6, "scale %g: st=%d V=%zu F=%zu",
              s, (int)st, h ? h->vertex_count : 0, h ? h->face_count : 0);
        if (h) CHECK(check_hull(h, xyz, n, GEOM_NONE), "scale %g hull checks", s);
        pxcd_hull_free(h);
    }

    /* Unit cube corners; the origin comes first as (-0, 0, -0), later as
     * (0, 0, 0) and (0, -0, 0). */
    double cube[11 * 3] = {-0.0, 0, -0.0, 1, 0, 0, 0, 1, 0, 1, 1,   0,   0,   0, 1,    1, 0,
                           1,    0, 1,    1, 1, 1, 1, 0, 0, 0, 0.5, 0.5, 0.5, 0, -0.0, 0};
    pxcd_status st;
    int dim;
    pxcd_hull *h = hull_of(cube, 11, &st, &dim);
    CHECK(st == PXCD_OK && h && h->vertex_count == 8 && h->face_count == 6, "signed-zero cube");
    if (h) {
        /* Vertex 0 is the first input point, with its bits. */
        CHECK(memcmp(&h->vertices[0], &cube[0], 3 * sizeof(double)) == 0 && signbit(h->vertices[0]) &&
                  signbit(h->vertices[2]) && !signbit(h->vertices[1]),
              "signed zeros not preserved: (%g %g %g)", h->vertices[0], h->vertices[1], h->vertices[2]);
        /* Vertices come in input order: vertex i is input point i here. */
        CHECK(memcmp(h->vertices, cube, 24 * sizeof(double)) == 0, "vertices not in input order");
        /* Faces start at their smallest id and are sorted. */
        int canonical = 1;
        for (size_t f = 0; f < h->face_count; ++f) {
            const uint32_t *p = &h->face_indices[h->face_offsets[f]];
            size_t m = h->face_offsets[f + 1] - h->face_offsets[f];
            for (size_t i = 1; i < m; ++i) canonical &= p[0] < p[i];
            if (f > 0) {
                const uint32_t *q = &h->face_indices[h->face_offsets[f - 1]];
                canonical &= q[0] < p[0] || (q[0] == p[0] && q[1] < p[1]);
            }
        }
        CHECK(canonical, "faces not canonical");
        CHECK(check_hull(h, cube, 11, GEOM_EXACT), "signed-zero cube hull checks");
    }
    pxcd_hull_free(h);
}

static void test_degenerate(void) {
    pxcd_status st;
    int dim;
    pxcd_hull *h;
    double one[] = {1.5, -2, 3};
    h = hull_of(one, 1, &st, &dim);
    CHECK(st == PXCD_OK && dim == 0 && h && h->vertex_count == 1 && h->face_count == 0 &&
              memcmp(h->vertices, one, sizeof one) == 0,
          "single point: st=%d dim=%d", (int)st, dim);
    pxcd_hull_free(h);

    double same[5 * 3];
    for (int i = 0; i < 5; ++i) memcpy(&same[3 * i], one, sizeof one);
    h = hull_of(same, 5, &st, &dim);
    CHECK(st == PXCD_OK && dim == 0 && h && h->vertex_count == 1, "repeated point: st=%d dim=%d", (int)st,
          dim);
    pxcd_hull_free(h);

    double line[6 * 3];
    for (int i = 0; i < 6; ++i) line[3 * i] = 1 + i, line[3 * i + 1] = 2 + 2 * i, line[3 * i + 2] = -3 * i;
    memcpy(&line[3 * 5], &line[0], 3 * sizeof(double)); /* duplicates too */
    h = hull_of(line, 6, &st, &dim);
    /* The end points (1,2,0) and (5,10,-12), in input order, no face. */
    CHECK(st == PXCD_OK && dim == 1 && h && h->vertex_count == 2 && h->face_count == 0 &&
              memcmp(h->vertices, &line[0], 3 * sizeof(double)) == 0 &&
              memcmp(h->vertices + 3, &line[3 * 4], 3 * sizeof(double)) == 0,
          "collinear: st=%d dim=%d", (int)st, dim);
    pxcd_hull_free(h);

    double plane[50 * 3];
    for (int i = 0; i < 50; ++i) {
        double a = floor(rnd01() * 100), b = floor(rnd01() * 100);
        plane[3 * i] = a, plane[3 * i + 1] = b, plane[3 * i + 2] = 3 * a - 2 * b + 7;
    }
    h = hull_of(plane, 50, &st, &dim);
    /* A two-sided polygon: two loops, one the other reversed, every vertex
     * an input point, every input point inside or on it (checked in the
     * lattice's plane coordinates (a, b), which the plane maps one to one). */
    int poly_ok = st == PXCD_OK && dim == 2 && h && h->face_count == 2 && h->vertex_count >= 3;
    if (poly_ok) {
        size_t n = h->vertex_count;
        const uint32_t *f0 = h->face_indices, *f1 = h->face_indices + h->face_offsets[1];
        poly_ok = h->face_offsets[1] == n && h->face_offsets[2] == 2 * n && f0[0] == 0 && f1[0] == 0;
        for (size_t k = 1; k < n && poly_ok; ++k) poly_ok = f1[k] == f0[n - k];
        double area = 0.0;
        for (size_t k = 0; k < n; ++k) {
            const double *p = h->vertices + 3 * f0[k], *q = h->vertices + 3 * f0[(k + 1) % n];
            area += p[0] * q[1] - q[0] * p[1];
        }
        for (int i = 0; i < 50 && poly_ok; ++i)
            for (size_t k = 0; k < n && poly_ok; ++k) {
                const double *p = h->vertices + 3 * f0[k], *q = h->vertices + 3 * f0[(k + 1) % n];
                double o = (q[0] - p[0]) * (plane[3 * i + 1] - p[1]) - (q[1] - p[1]) * (plane[3 * i] - p[0]);
                poly_ok = area > 0 ? o >= 0 : o <= 0; /* small integers: exact */
            }
    }
    CHECK(poly_ok, "coplanar: st=%d dim=%d", (int)st, dim);
    pxcd_hull_free(h);

    /* Almost coplanar: one point off the plane by one ulp is 3D. */
    plane[3 * 49 + 2] = nextafter(plane[3 * 49 + 2], INFINITY);
    h = hull_of(plane, 50, &st, &dim);
    CHECK(st == PXCD_OK && dim == 3 && h, "nearly coplanar: st=%d dim=%d", (int)st, dim);
    if (h) CHECK(check_hull(h, plane, 50, GEOM_NONE), "nearly coplanar hull checks");
    pxcd_hull_free(h);

    char msg[128] = "";
    h = (pxcd_hull *)1;
    st = pxcd_hull_compute(one, 0, &h, &dim, msg, sizeof msg);
    CHECK(st == PXCD_ERROR && h == NULL && msg[0] != 0, "empty input: st=%d", (int)st);
    pxcd_hull_free(NULL);
}

/* pxcd_hull_compute_ex: both kernels give the same hull, bit for bit (the
 * output is canonical), and unknown flags are refused. Regression for the
 * test-only switch, which was the environment variable
 * PXCD_HULL_EXACT_KERNEL read by the library itself. */
static void test_kernel_flag(void) {
    enum { N = 400 };
    double xyz[3 * N];
    for (size_t i = 0; i < N; ++i) { /* small integers: many coplanar points */
        for (int k = 0; k < 3; ++k) xyz[3 * i + k] = floor(rnd01() * 9);
    }
    char msg[256] = "";
    pxcd_hull *fast = NULL, *exact = NULL;
    int dim_fast = -1, dim_exact = -1;
    pxcd_status s1 = pxcd_hull_compute_ex(xyz, N, 0, &fast, &dim_fast, msg, sizeof msg);
    pxcd_status s2 =
        pxcd_hull_compute_ex(xyz, N, PXCD_HULL_FORCE_EXACT_KERNEL, &exact, &dim_exact, msg, sizeof msg);
    CHECK(s1 == PXCD_OK && s2 == PXCD_OK && fast && exact, "kernels: %d %d %s", (int)s1, (int)s2, msg);
    if (fast && exact)
        CHECK(fast->vertex_count == exact->vertex_count && fast->face_count == exact->face_count &&
                  memcmp(fast->vertices, exact->vertices, 3 * fast->vertex_count * sizeof(double)) == 0 &&
                  memcmp(fast->face_offsets, exact->face_offsets, (fast->face_count + 1) * sizeof(size_t)) ==
                      0 &&
                  memcmp(fast->face_indices, exact->face_indices,
                         fast->face_offsets[fast->face_count] * sizeof(uint32_t)) == 0,
              "the two kernels give different hulls");
    pxcd_hull_free(fast);
    pxcd_hull_free(exact);
    pxcd_hull *h = (pxcd_hull *)1;
    msg[0] = '\0';
    CHECK(pxcd_hull_compute_ex(xyz, N, 2, &h, NULL, msg, sizeof msg) == PXCD_ERROR && h == NULL && msg[0],
          "unknown flag accepted");
}

/* Regression: out of memory is its own status, PXCD_OUT_OF_MEMORY, told by
 * the exception's type (std::bad_alloc); callers used to search the message
 * for "memory". Configuration: the address space is capped (RLIMIT_AS, soft
 * limit only) at the process's current size plus 32 MiB, then the hull of 4M
 * points is asked for: CGAL's first copy of them (96 MiB or more) cannot be
 * allocated. Skipped under AddressSanitizer. pxcd_exact_distance is not
 * tested this way: GMP aborts the process when its own allocations fail. */
static void test_out_of_memory(void) {
    if (PXCD_TEST_ASAN) return;
    const size_t n = (size_t)4 << 20;
    double *xyz = malloc(3 * n * sizeof *xyz);
    if (!xyz) {
        CHECK(0, "cannot allocate the input");
        return;
    }
    for (size_t i = 0; i < 3 * n; ++i) xyz[i] = (double)(i % 1013);
    long vm_pages = 0;
    FILE *f = fopen("/proc/self/statm", "r");
    if (f) {
        if (fscanf(f, "%ld", &vm_pages) != 1) vm_pages = 0;
        fclose(f);
    }
    struct rlimit old, lim;
    if (vm_pages <= 0 || getrlimit(RLIMIT_AS, &old) != 0) {
        printf("out-of-memory test skipped: no /proc/self/statm or RLIMIT_AS\n");
        free(xyz);
        return;
    }
    lim = old;
    lim.rlim_cur = (rlim_t)vm_pages * (rlim_t)sysconf(_SC_PAGESIZE) + ((rlim_t)32 << 20);
    if (old.rlim_cur != RLIM_INFINITY && lim.rlim_cur > old.rlim_cur) lim.rlim_cur = old.rlim_cur;
    char msg[128] = "";
    pxcd_hull *h = (pxcd_hull *)1;
    pxcd_status st = PXCD_OK;
    const int limited = setrlimit(RLIMIT_AS, &lim) == 0;
    if (limited) {
        st = pxcd_hull_compute_ex(xyz, n, g_hull_flags, &h, NULL, msg, sizeof msg);
        setrlimit(RLIMIT_AS, &old);
    }
    CHECK(limited, "setrlimit failed");
    CHECK(st == PXCD_OUT_OF_MEMORY && h == NULL && strstr(msg, "out of memory"), "st=%d h=%p msg=%s", (int)st,
          (void *)h, msg);
    free(xyz);
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
        tetra(s, 0, 0, P); /* below z = 0 */
        tetra(s, s, 1, Q); /* above z = s: exact gap s */
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

    /* Single points: equal, then apart (3-4-5 triangle). */
    double p1[] = {1, 2, 3}, q1[] = {1, 2, 3}, q2[] = {4, 6, 3};
    st = pxcd_exact_distance(p1, 1, q1, 1, &d, &d2, &zero, NULL, NULL, msg, sizeof msg);
    CHECK(st == PXCD_OK && zero == 1 && d == 0, "equal points: st=%d d=%g zero=%d", (int)st, d, zero);
    st = pxcd_exact_distance(p1, 1, q2, 1, &d, &d2, &zero, NULL, NULL, msg, sizeof msg);
    CHECK(st == PXCD_OK && zero == 0 && d == 5 && d2 == 25, "points: st=%d d=%g d2=%g", (int)st, d, d2);
}

/* Random point clouds at random scales and offsets: the realizing points
 * must be |rp - rq| = d apart, and the plane through rp (rq) normal to
 * rq - rp must have all of P (Q) on its far side, up to rounding. */
static void test_distance_random(void) {
    enum { N = 60 };
    double P[3 * N], Q[3 * N];
    int separated = 0, overlapping = 0;
    for (int round = 0; round < 60; ++round) {
        double scale = pow(10.0, -100 + 200 * rnd01()), gap = 3 * rnd01();
        size_t np = 1 + (size_t)(rnd01() * N), nq = 1 + (size_t)(rnd01() * N);
        for (size_t i = 0; i < 3 * np; ++i) P[i] = scale * (2 * rnd01() - 1);
        for (size_t i = 0; i < 3 * nq; ++i)
            Q[i] = scale * (2 * rnd01() - 1 + (i % 3 == (size_t)round % 3 ? gap : 0));
        double d = -1, d2 = -1, rp[3], rq[3];
        int zero = -1;
        char msg[256] = "";
        pxcd_status st = pxcd_exact_distance(P, np, Q, nq, &d, &d2, &zero, rp, rq, msg, sizeof msg);
        CHECK(st == PXCD_OK, "random round %d: %s", round, msg);
        if (st != PXCD_OK) continue;
        double n[3] = {rq[0] - rp[0], rq[1] - rp[1], rq[2] - rp[2]};
        double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (zero) {
            ++overlapping;
            CHECK(d == 0 && d2 == 0 && len <= 1e-12 * scale, "random round %d: zero but d=%g", round, d);
            continue;
        }
        ++separated;
        CHECK(fabs(len - d) <= 1e-12 * scale && fabs(d * d - d2) <= 1e-12 * d2,
              "random round %d: |rp-rq|=%.17g d=%.17g d2=%.17g", round, len, d, d2);
        double worst = 0;
        for (size_t i = 0; i < np; ++i) {
            const double *p = &P[3 * i];
            double s = (n[0] * (p[0] - rp[0]) + n[1] * (p[1] - rp[1]) + n[2] * (p[2] - rp[2])) / len;
            if (s > worst) worst = s;
        }
        for (size_t i = 0; i < nq; ++i) {
            const double *q = &Q[3 * i];
            double s = -(n[0] * (q[0] - rq[0]) + n[1] * (q[1] - rq[1]) + n[2] * (q[2] - rq[2])) / len;
            if (s > worst) worst = s;
        }
        CHECK(worst <= 1e-12 * scale, "random round %d: a point is %g beyond its support plane", round,
              worst);
    }
    CHECK(separated > 10 && overlapping > 5, "random cases: %d separated, %d overlapping", separated,
          overlapping);
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
    double t0 = now_seconds(), c0 = cpu_seconds();
    pxcd_hull *h = hull_of(xyz, n, &st, &dim);
    double t1 = now_seconds(), c1 = cpu_seconds();
    printf("bench: hull of %zu ellipsoid points: %.3f s wall, %.3f s cpu, V=%zu F=%zu\n", n, t1 - t0, c1 - c0,
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
        t0 = now_seconds(), c0 = cpu_seconds();
        st = pxcd_exact_distance(hp->vertices, hp->vertex_count, hq->vertices, hq->vertex_count, &d, NULL,
                                 &zero, rp, rq, msg, sizeof msg);
        t1 = now_seconds(), c1 = cpu_seconds();
        printf("bench: exact distance %zu x %zu vertices: %.3f s wall, %.3f s cpu, d=%.17g st=%d %s\n",
               hp->vertex_count, hq->vertex_count, t1 - t0, c1 - c0, d, (int)st, msg);
    }
    pxcd_hull_free(hp);
    pxcd_hull_free(hq);
    free(P);
    free(Q);

    /* Two hulls of 200k vertices each. */
    P = ellipsoid(n, 1, 1.5, 2, 0), Q = ellipsoid(n, 2, 1, 1, 3.5);
    {
        double d = 0;
        int zero = 0;
        char msg[256] = "";
        t0 = now_seconds(), c0 = cpu_seconds();
        st = pxcd_exact_distance(P, n, Q, n, &d, NULL, &zero, NULL, NULL, msg, sizeof msg);
        t1 = now_seconds(), c1 = cpu_seconds();
        printf("bench: exact distance %zu x %zu points: %.3f s wall, %.3f s cpu, d=%.17g st=%d %s\n", n, n,
               t1 - t0, c1 - c0, d, (int)st, msg);
    }
    free(P);
    free(Q);
}

int main(int argc, char **argv) {
    int run_bench = 0;
    for (int i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--bench") == 0) {
            run_bench = 1;
        } else if (strcmp(argv[i], "--exact-kernel") == 0) {
            g_hull_flags |= PXCD_HULL_FORCE_EXACT_KERNEL;
        } else {
            fprintf(stderr, "usage: %s [--exact-kernel] [--bench]\n", argv[0]);
            return 2;
        }
    }
    if (g_hull_flags & PXCD_HULL_FORCE_EXACT_KERNEL)
        printf("hulls: exact rational kernel (--exact-kernel)\n");
    test_cube_with_extras();
    test_tetrahedron();
    test_sphere(2000);
    test_box_edges();
    test_random_lattice();
    test_hull_scales();
    test_degenerate();
    test_out_of_memory();
    test_distance_scales();
    test_distance_cubes();
    test_distance_random();
    test_kernel_flag();
    if (run_bench) bench();
    printf("%d passed, %d failed\n", g_passed, g_failed);
    return g_failed == 0 ? 0 : 1;
}
