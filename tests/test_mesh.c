/* Tests of px_mesh (include/proxima/mesh.h) and px_mesh_load (io.h).
 *
 * px_mesh_create: every validation error of mesh.h; closed/open detection
 * on hand-made surfaces whose answer is known by construction (a cube split
 * into 12 triangles with its 8 corners listed once or once per triangle, the
 * cube minus a face, inside out, with a fin triangle on one edge, with a
 * collinear sliver); every allocation failure (an allocator that fails its
 * k-th call, for every k until creation succeeds) returns
 * PX_ERR_OUT_OF_MEMORY and leaks nothing.
 *
 * px_mesh_load: small files in every format this test writes with known
 * coordinates (float-representable, so the expected values are exact),
 * the parts, names and node parents Assimp 5.2 produces for them, the
 * shipped models, and bad files that must fail with PX_ERR_IO naming the
 * file. The float cost is measured on a CAD-scale OFF file read by an exact
 * parser here (strtod) and through Assimp.
 */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "proxima/io.h"
#include "proxima/proxima.h"
#include "test_util.h"

/* ---- allocators ---------------------------------------------------------- */

static long g_live_bytes, g_live_blocks;
static long g_fail_at = -1; /* the call that fails (0-based), -1: none */
static long g_calls;

static void *test_alloc(void *user, size_t size) {
    (void)user;
    if (g_fail_at >= 0 && g_calls++ == g_fail_at) return NULL;
    g_live_bytes += (long)size;
    g_live_blocks++;
    return malloc(size);
}
static void test_free(void *user, void *ptr, size_t size) {
    (void)user;
    g_live_bytes -= (long)size;
    g_live_blocks--;
    free(ptr);
}
static px_allocator g_alloc = {test_alloc, test_free, NULL};

static px_mesh_options counted_options(void) {
    px_mesh_options o;
    memset(&o, 0, sizeof o);
    o.allocator = &g_alloc;
    return o;
}

/* ---- hand-made surfaces ---------------------------------------------------- */

/* Unit cube, corners i = x + 2y + 4z, 12 triangles facing out. */
static const double k_cube[8][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0},
                                    {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};
static const uint32_t k_cube_tri[12][3] = {
    {0, 2, 3}, {0, 3, 1}, /* z = 0, normal -z */
    {4, 5, 7}, {4, 7, 6}, /* z = 1 */
    {0, 1, 5}, {0, 5, 4}, /* y = 0 */
    {2, 6, 7}, {2, 7, 3}, /* y = 1 */
    {0, 4, 6}, {0, 6, 2}, /* x = 0 */
    {1, 3, 7}, {1, 7, 5}, /* x = 1 */
};

/* Signed volume of part 0 of m (6 V = sum a . (b x c)). */
static double mesh_volume(const px_mesh *m) {
    px_mesh_part p;
    px_mesh_get_part(m, 0, &p);
    const double *x = px_mesh_vertices(m);
    const uint32_t *t = px_mesh_triangles(m);
    double v = 0;
    for (uint32_t i = p.first_triangle; i < p.first_triangle + p.triangle_count; ++i) {
        const double *a = x + 3 * t[3 * i], *b = x + 3 * t[3 * i + 1], *c = x + 3 * t[3 * i + 2];
        v += a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) +
             a[2] * (b[0] * c[1] - b[1] * c[0]);
    }
    return v / 6;
}

/* Creates a one-part mesh from the cube's triangles (first `nt` of them),
 * with flipped winding if `flip`, corners unshared if `split` (3 per
 * triangle, as STL stores them), and `extra` triangles appended. */
static px_mesh *cube_mesh(int nt, int flip, int split, const uint32_t (*extra)[3], int nextra,
                          const double (*extra_v)[3], int nextra_v) {
    double xyz[3 * (36 + 8)];
    uint32_t tri[3 * 24];
    size_t nv = 0;
    if (!split) {
        memcpy(xyz, k_cube, sizeof k_cube);
        nv = 8;
    }
    for (int i = 0; i < nextra_v; ++i, ++nv) memcpy(xyz + 3 * nv, extra_v[i], 3 * sizeof(double));
    for (int i = 0; i < nt + nextra; ++i) {
        const uint32_t *t = i < nt ? k_cube_tri[i] : extra[i - nt];
        for (int k = 0; k < 3; ++k) {
            int kk = flip && k ? 3 - k : k;
            uint32_t v = t[kk];
            if (split && v < 8) {
                memcpy(xyz + 3 * nv, k_cube[v], 3 * sizeof(double));
                v = (uint32_t)nv++;
            }
            tri[3 * i + k] = v;
        }
    }
    px_mesh_desc d;
    memset(&d, 0, sizeof d);
    d.xyz = xyz;
    d.vertex_count = nv;
    d.triangles = tri;
    d.triangle_count = (size_t)(nt + nextra);
    px_mesh_options o = counted_options();
    px_error err;
    px_mesh *m = px_mesh_create(&d, &o, &err);
    CHECK(m != NULL, "cube_mesh: %s", err.message);
    return m;
}

static uint32_t part0_closed(const px_mesh *m) {
    px_mesh_part p;
    return px_mesh_get_part(m, 0, &p) == PX_OK ? p.closed : 99;
}

static void test_closed(void) {
    for (int split = 0; split < 2; ++split) {
        px_mesh *m = cube_mesh(12, 0, split, NULL, 0, NULL, 0);
        CHECK(part0_closed(m) == 1, "cube closed (split %d)", split);
        CHECK(fabs(mesh_volume(m) - 1) < 1e-15, "cube volume %g", mesh_volume(m));
        px_mesh_info info;
        CHECK(px_mesh_get_info(m, &info) == PX_OK && info.closed_parts == 1, "closed_parts");
        CHECK(info.min.x == 0 && info.max.z == 1 && info.scale == 1 && info.unit_metres == 0, "info");
        px_mesh_destroy(m);

        m = cube_mesh(10, 0, split, NULL, 0, NULL, 0);
        CHECK(part0_closed(m) == 0, "cube minus a face is open (split %d)", split);
        px_mesh_destroy(m);

        /* inside out: closed, and the triangles come back reversed */
        m = cube_mesh(12, 1, split, NULL, 0, NULL, 0);
        CHECK(part0_closed(m) == 1, "inside-out cube closed (split %d)", split);
        CHECK(fabs(mesh_volume(m) - 1) < 1e-15, "inside-out cube flipped: volume %g", mesh_volume(m));
        px_mesh_destroy(m);

        /* an open inside-out cube is left as it is */
        m = cube_mesh(10, 1, split, NULL, 0, NULL, 0);
        CHECK(part0_closed(m) == 0, "open inside-out");
        const uint32_t *t = px_mesh_triangles(m);
        CHECK(split || (t[0] == 0 && t[1] == 3 && t[2] == 2), "open part not flipped");
        px_mesh_destroy(m);

        /* a fin on edge 0-1 (used 3 times): non-manifold, open */
        if (!split) {
            static const double fin_v[1][3] = {{0.5, -1, 0}};
            static const uint32_t fin_t[1][3] = {{0, 1, 8}};
            m = cube_mesh(12, 0, 0, fin_t, 1, fin_v, 1);
            CHECK(part0_closed(m) == 0, "edge used 3 times: open");
            px_mesh_destroy(m);
        }

        /* a degenerate triangle (repeated corner) makes the part open */
        static const uint32_t deg[1][3] = {{0, 1, 1}};
        if (!split) {
            m = cube_mesh(12, 0, 0, deg, 1, NULL, 0);
            CHECK(part0_closed(m) == 0, "degenerate triangle: open");
            px_mesh_destroy(m);
        }
    }

    /* Two cubes' worth of triangles in one part: every edge used 4 times. */
    {
        px_mesh *m = cube_mesh(12, 0, 0, k_cube_tri, 12, NULL, 0);
        CHECK(part0_closed(m) == 0, "every edge used 4 times: open");
        px_mesh_destroy(m);
    }

    /* A closed surface with a zero-area triangle of distinct corners: the
     * tetrahedron a b d e (a = 0, b = (2,0,0), d = (0,1,0), e = (0,0,1))
     * with face a b e split at c = (1,0,0) into a c e and c b e; the
     * sliver a b c, collinear, closes the seam. Every edge is then used
     * once each way, so only the zero-area test makes it open. */
    {
        const double v[5][3] = {{0, 0, 0}, {2, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
        /* a=0 b=1 c=2 d=3 e=4; outward faces of tetra a b d e: (a,d,b) z=0,
         * (a,b,e) y=0, (a,e,d) x=0, (b,d,e) slanted */
        const uint32_t t[6][3] = {{0, 3, 1}, {0, 2, 4}, {2, 1, 4}, {0, 4, 3}, {1, 3, 4}, {0, 1, 2}};
        px_mesh_desc d;
        memset(&d, 0, sizeof d);
        d.xyz = &v[0][0];
        d.vertex_count = 5;
        d.triangles = &t[0][0];
        d.triangle_count = 6;
        px_mesh *m = px_mesh_create(&d, NULL, NULL);
        CHECK(m && part0_closed(m) == 0, "a collinear triangle makes the part open");
        d.triangle_count = 5; /* without the sliver: edges a-b, a-c, c-b used once */
        px_mesh *m2 = px_mesh_create(&d, NULL, NULL);
        CHECK(m2 && part0_closed(m2) == 0, "open without the sliver");
        px_mesh_destroy(m);
        px_mesh_destroy(m2);
    }

    /* Two parts: a closed cube and an open one, in one mesh. */
    {
        double xyz[16 * 3];
        uint32_t tri[22 * 3];
        memcpy(xyz, k_cube, sizeof k_cube);
        for (int i = 0; i < 8; ++i)
            for (int k = 0; k < 3; ++k) xyz[24 + 3 * i + k] = k_cube[i][k] + 5;
        for (int i = 0; i < 12; ++i)
            for (int k = 0; k < 3; ++k) tri[3 * i + k] = k_cube_tri[i][k];
        for (int i = 0; i < 10; ++i)
            for (int k = 0; k < 3; ++k) tri[36 + 3 * i + k] = k_cube_tri[i][k] + 8;
        px_mesh_part_desc parts[2] = {{"closed", 0, 0, 8, 0, 12, 0}, {"open", 1, 8, 8, 12, 10, 0}};
        px_mesh_node_desc nodes[2] = {{"root", -1, 0}, {NULL, 0, 0}};
        px_mesh_desc d;
        memset(&d, 0, sizeof d);
        d.xyz = xyz;
        d.vertex_count = 16;
        d.triangles = tri;
        d.triangle_count = 22;
        d.parts = parts;
        d.part_count = 2;
        d.nodes = nodes;
        d.node_count = 2;
        d.unit_metres = 0.001;
        px_mesh_options o = counted_options();
        o.scale = 2;
        px_error err;
        px_mesh *m = px_mesh_create(&d, &o, &err);
        CHECK(m != NULL, "two parts: %s", err.message);
        px_mesh_part p;
        px_mesh_node n;
        CHECK(px_mesh_get_part(m, 0, &p) == PX_OK && p.closed == 1 && strcmp(p.name, "closed") == 0 &&
                  p.node == 0,
              "part 0");
        CHECK(px_mesh_get_part(m, 1, &p) == PX_OK && p.closed == 0 && strcmp(p.name, "open") == 0 &&
                  p.first_vertex == 8 && p.triangle_count == 10,
              "part 1");
        CHECK(px_mesh_get_part(m, 2, &p) == PX_ERR_INVALID_ARGUMENT && p.name == NULL, "part 2 out of range");
        CHECK(px_mesh_get_node(m, 1, &n) == PX_OK && n.parent == 0 && strcmp(n.name, "") == 0, "node 1");
        CHECK(px_mesh_get_node(m, 2, &n) == PX_ERR_INVALID_ARGUMENT && n.name == NULL, "node 2");
        CHECK(px_mesh_get_node(NULL, 0, &n) == PX_ERR_INVALID_ARGUMENT, "NULL mesh");
        CHECK(px_mesh_get_node(m, 0, NULL) == PX_ERR_INVALID_ARGUMENT, "NULL out");
        px_mesh_info info;
        CHECK(px_mesh_get_info(m, &info) == PX_OK && info.closed_parts == 1 && info.scale == 2 &&
                  info.unit_metres == 0.001 && info.max.x == 12 && info.min.y == 0,
              "info");
        CHECK(px_mesh_vertices(m)[3 * 9] == 12, "scaled");
        CHECK(px_mesh_vertex_count(m) == 16 && px_mesh_triangle_count(m) == 22 &&
                  px_mesh_part_count(m) == 2 && px_mesh_node_count(m) == 2,
              "counts");
        CHECK(px_mesh_memory_bytes(m) == (size_t)g_live_bytes, "memory_bytes %zu vs %ld",
              px_mesh_memory_bytes(m), g_live_bytes);
        px_mesh_destroy(m);
    }
    CHECK(g_live_bytes == 0 && g_live_blocks == 0, "leak after test_closed: %ld bytes", g_live_bytes);
}

/* ---- validation ------------------------------------------------------------- */

static void expect_create_error(const px_mesh_desc *d, const px_mesh_options *o, px_status code,
                                const char *needle, int line) {
    px_error err;
    memset(&err, 0x55, sizeof err);
    px_mesh *m = px_mesh_create(d, o, &err);
    CHECK(m == NULL && err.code == code, "line %d: expected %s, got %s (%s)", line, px_status_string(code),
          px_status_string(err.code), err.message);
    CHECK(!needle || strstr(err.message, needle), "line %d: message '%s' lacks '%s'", line, err.message,
          needle);
    px_mesh_destroy(m);
}
#define EXPECT(d, o, code, needle) expect_create_error(d, o, code, needle, __LINE__)

static void test_validation(void) {
    double xyz[8 * 3];
    memcpy(xyz, k_cube, sizeof xyz);
    uint32_t tri[12 * 3];
    memcpy(tri, k_cube_tri, sizeof tri);
    px_mesh_part_desc parts[2] = {{"a", -1, 0, 4, 0, 0, 0}, {"b", -1, 4, 4, 0, 0, 0}};
    px_mesh_node_desc nodes[2] = {{"r", -1, 0}, {"c", 0, 0}};
    px_mesh_desc base;
    memset(&base, 0, sizeof base);
    base.xyz = xyz;
    base.vertex_count = 8;
    base.triangles = tri;
    base.triangle_count = 12;
    px_mesh_desc d;
    px_mesh_options o;
    memset(&o, 0, sizeof o);

    EXPECT(NULL, NULL, PX_ERR_INVALID_ARGUMENT, "desc is NULL");
    d = base, d.reserved[3] = 1;
    EXPECT(&d, NULL, PX_ERR_INVALID_ARGUMENT, "reserved[3]");
    o.reserved[5] = 1;
    EXPECT(&base, &o, PX_ERR_INVALID_ARGUMENT, "options.reserved[5]");
    memset(&o, 0, sizeof o);
    double bad_scales[] = {-1, NAN, INFINITY, -0.0 - 1e-300};
    for (int i = 0; i < 4; ++i) {
        o.scale = bad_scales[i];
        EXPECT(&base, &o, PX_ERR_INVALID_ARGUMENT, "scale");
    }
    o.scale = 0;
    px_allocator half = {test_alloc, NULL, NULL};
    o.allocator = &half;
    EXPECT(&base, &o, PX_ERR_INVALID_ARGUMENT, "allocator");
    o.allocator = NULL;
    d = base, d.vertex_count = (1ull << 31) + 1;
    EXPECT(&d, NULL, PX_ERR_INVALID_ARGUMENT, "2^31");
    d = base, d.triangle_count = (size_t)1 << 32;
    EXPECT(&d, NULL, PX_ERR_INVALID_ARGUMENT, "2^31");
    d = base, d.part_count = 0x80000001u, d.parts = parts;
    EXPECT(&d, NULL, PX_ERR_INVALID_ARGUMENT, "2^31");
    d = base, d.xyz = NULL;
    EXPECT(&d, NULL, PX_ERR_INVALID_ARGUMENT, "NULL");
    d = base, d.triangles = NULL;
    EXPECT(&d, NULL, PX_ERR_INVALID_ARGUMENT, "NULL");
    d = base, d.part_count = 1;
    EXPECT(&d, NULL, PX_ERR_INVALID_ARGUMENT, "NULL");
    d = base, d.node_count = 1;
    EXPECT(&d, NULL, PX_ERR_INVALID_ARGUMENT, "NULL");
    d = base, d.unit_metres = -1;
    EXPECT(&d, NULL, PX_ERR_INVALID_ARGUMENT, "unit_metres");
    d = base, d.unit_metres = INFINITY;
    EXPECT(&d, NULL, PX_ERR_INVALID_ARGUMENT, "unit_metres");

    xyz[3 * 5 + 1] = NAN;
    EXPECT(&base, NULL, PX_ERR_NON_FINITE, "vertex 5");
    xyz[3 * 5 + 1] = -INFINITY;
    EXPECT(&base, NULL, PX_ERR_NON_FINITE, "vertex 5");
    xyz[3 * 5 + 1] = 1e300;
    o.scale = 1e10;
    EXPECT(&base, &o, PX_ERR_NON_FINITE, "vertex 5 overflows");
    o.scale = 0;
    xyz[3 * 5 + 1] = 0;

    tri[3 * 7 + 2] = 8;
    EXPECT(&base, NULL, PX_ERR_INVALID_ARGUMENT, "triangle 7 uses vertex 8");
    tri[3 * 7 + 2] = 3;

    d = base, d.nodes = nodes, d.node_count = 2;
    nodes[1].reserved = 1;
    EXPECT(&d, NULL, PX_ERR_INVALID_ARGUMENT, "node 1: reserved");
    nodes[1].reserved = 0;
    int32_t bad_parents[] = {1, 2, -2, INT32_MAX};
    for (int i = 0; i < 4; ++i) {
        nodes[1].parent = bad_parents[i];
        EXPECT(&d, NULL, PX_ERR_INVALID_ARGUMENT, "node 1 has parent");
    }
    nodes[1].parent = 0;
    nodes[0].parent = 0; /* its own parent: a cycle */
    EXPECT(&d, NULL, PX_ERR_INVALID_ARGUMENT, "node 0 has parent 0");
    nodes[0].parent = -1;

    px_mesh_desc dp = base;
    dp.triangle_count = 0;
    dp.parts = parts;
    dp.part_count = 2;
    dp.nodes = nodes;
    dp.node_count = 2;
    px_mesh *ok = px_mesh_create(&dp, NULL, NULL);
    CHECK(ok != NULL, "two point-set parts");
    px_mesh_destroy(ok);
    parts[1].reserved = 7;
    EXPECT(&dp, NULL, PX_ERR_INVALID_ARGUMENT, "part 1: reserved");
    parts[1].reserved = 0;
    parts[1].node = 2;
    EXPECT(&dp, NULL, PX_ERR_INVALID_ARGUMENT, "part 1 hangs from node 2");
    parts[1].node = -2;
    EXPECT(&dp, NULL, PX_ERR_INVALID_ARGUMENT, "part 1 hangs from node -2");
    parts[1].node = 1;
    parts[1].vertex_count = 5;
    EXPECT(&dp, NULL, PX_ERR_INVALID_ARGUMENT, "part 1: vertices 4 + 5");
    parts[1].first_vertex = UINT32_MAX; /* wraps in 32 bits */
    parts[1].vertex_count = 2;
    EXPECT(&dp, NULL, PX_ERR_INVALID_ARGUMENT, "part 1: vertices");
    parts[1].first_vertex = 3;
    parts[1].vertex_count = 5;
    EXPECT(&dp, NULL, PX_ERR_INVALID_ARGUMENT, "parts 0 and 1 share vertices");
    parts[1].first_vertex = 4;
    parts[1].vertex_count = 4;
    parts[1].triangle_count = 1;
    EXPECT(&dp, NULL, PX_ERR_INVALID_ARGUMENT, "part 1: triangles 0 + 1");
    /* triangles: part 0 takes the first 6 triangles, whose vertices are not all below 4 */
    dp.triangle_count = 12;
    parts[1].triangle_count = 0;
    parts[0].triangle_count = 1; /* triangle 0 = (0, 2, 3): inside 0..3 */
    ok = px_mesh_create(&dp, NULL, NULL);
    CHECK(ok != NULL, "a part's triangle inside its vertices");
    px_mesh_destroy(ok);
    parts[0].triangle_count = 3; /* triangle 2 = (4, 5, 7) */
    EXPECT(&dp, NULL, PX_ERR_INVALID_ARGUMENT, "part 0: triangle 2 uses vertex 4");
    parts[0].triangle_count = 1;
    parts[1].first_triangle = 1; /* (0, 3, 1) */
    parts[1].triangle_count = 1;
    EXPECT(&dp, NULL, PX_ERR_INVALID_ARGUMENT, "part 1: triangle 1 uses vertex 0");
    parts[1].first_triangle = 2; /* overlaps part 0's triangles 0..2 */
    parts[0].triangle_count = 3;
    parts[0].vertex_count = 8;
    parts[1].first_vertex = 8;
    parts[1].vertex_count = 0;
    EXPECT(&dp, NULL, PX_ERR_INVALID_ARGUMENT, "parts 0 and 1 share triangles");

    /* empty meshes are fine: one part, no vertices */
    px_mesh_desc empty;
    memset(&empty, 0, sizeof empty);
    px_mesh *e = px_mesh_create(&empty, NULL, NULL);
    CHECK(e && px_mesh_part_count(e) == 1 && px_mesh_vertices(e) == NULL && px_mesh_triangles(e) == NULL,
          "empty mesh");
    px_mesh_info info;
    CHECK(px_mesh_get_info(e, &info) == PX_OK && info.min.x == 0 && info.max.x == 0 && info.scale == 1,
          "empty info");
    px_mesh_destroy(e);
    CHECK(px_mesh_vertex_count(NULL) == 0 && px_mesh_part_count(NULL) == 0 &&
              px_mesh_vertices(NULL) == NULL && px_mesh_memory_bytes(NULL) == 0 &&
              px_mesh_get_info(NULL, &info) == PX_ERR_INVALID_ARGUMENT,
          "NULL mesh accessors");
    px_mesh_destroy(NULL);
    CHECK(g_live_bytes == 0 && g_live_blocks == 0, "leak after test_validation");
}

/* Every allocation of a two-part creation fails in turn. */
static void test_alloc_failures(void) {
    double xyz[16 * 3];
    uint32_t tri[24 * 3];
    memcpy(xyz, k_cube, sizeof k_cube);
    memcpy(xyz + 24, k_cube, sizeof k_cube);
    for (int i = 0; i < 24; ++i)
        for (int k = 0; k < 3; ++k) tri[3 * i + k] = k_cube_tri[i % 12][k] + (i >= 12 ? 8 : 0);
    px_mesh_part_desc parts[2] = {{"a", -1, 0, 8, 0, 12, 0}, {"b", -1, 8, 8, 12, 12, 0}};
    px_mesh_desc d;
    memset(&d, 0, sizeof d);
    d.xyz = xyz;
    d.vertex_count = 16;
    d.triangles = tri;
    d.triangle_count = 24;
    d.parts = parts;
    d.part_count = 2;
    px_mesh_options o = counted_options();
    long k;
    for (k = 0; k < 100; ++k) {
        g_fail_at = k;
        g_calls = 0;
        px_error err;
        px_mesh *m = px_mesh_create(&d, &o, &err);
        if (m) {
            CHECK(g_calls == k, "success only once no allocation fails");
            px_mesh_destroy(m);
            break;
        }
        CHECK(err.code == PX_ERR_OUT_OF_MEMORY && strstr(err.message, "out of memory"),
              "allocation %ld failing: %s", k, err.message);
        CHECK(g_live_bytes == 0 && g_live_blocks == 0, "allocation %ld failing leaks %ld bytes", k,
              g_live_bytes);
    }
    g_fail_at = -1;
    CHECK(k == 5, "a two-part creation makes 5 allocations (got %ld)", k);
    CHECK(g_live_bytes == 0 && g_live_blocks == 0, "leak after test_alloc_failures");
}

int main(void) {
    tu_init("test_mesh");
    test_validation();
    test_closed();
    test_alloc_failures();
    return tu_finish();
}
