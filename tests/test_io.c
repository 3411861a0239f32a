/* Tests of src/io (px_convex_from_file, px_mesh_points_from_file).
 *
 * Oracles are independent of Assimp and of the hull code: the expected
 * points are written into the files by this test, so the loaded, deduplicated
 * point set must equal them exactly (float-representable coordinates), and
 * the hull of a cube must have 8 vertices, 12 edges, 6 faces. Node
 * transforms are tested with a COLLADA file instancing one mesh twice.
 * Every allocation goes through a counting allocator: nothing may leak. */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "proxima/proxima.h"
#include "proxima/io.h"

static int g_failures;
#define CHECK(cond)                                                                                          \
    do {                                                                                                     \
        if (!(cond)) {                                                                                       \
            fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond);                         \
            g_failures++;                                                                                    \
        }                                                                                                    \
    } while (0)

static long g_live_bytes, g_live_blocks;
static void *count_alloc(void *user, size_t size) {
    (void)user;
    g_live_bytes += (long)size;
    g_live_blocks++;
    return malloc(size);
}
static void count_free(void *user, void *ptr, size_t size) {
    (void)user;
    g_live_bytes -= (long)size;
    g_live_blocks--;
    free(ptr);
}

/* Every polytope and point array the test makes goes through the counter. */
static px_allocator g_counting = {count_alloc, count_free, NULL};
static const px_convex_options *g_opt;

static char g_dir[256];

static const char *write_file(const char *name, const char *text) {
    static char path[512];
    snprintf(path, sizeof path, "%s/%s", g_dir, name);
    FILE *f = fopen(path, "wb");
    if (!f) {
        perror(path);
        exit(2);
    }
    fputs(text, f);
    fclose(f);
    return path;
}

static int has_point(const double *xyz, size_t n, double x, double y, double z) {
    for (size_t i = 0; i < n; ++i)
        if (xyz[3 * i] == x && xyz[3 * i + 1] == y && xyz[3 * i + 2] == z) return 1;
    return 0;
}

static const char *k_cube_obj = "# unit cube, quads, each corner listed twice\n"
                                "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                                "v 0 0 0\nv 1 1 1\n"
                                "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";

static void test_cube_obj(void) {
    const char *path = write_file("cube.obj", k_cube_obj);
    double *xyz = NULL;
    size_t n = 0;
    px_error err;
    CHECK(px_load_points(path, &g_counting, &xyz, &n, &err) == PX_OK);
    CHECK(n == 8); /* duplicates removed exactly */
    for (int i = 0; i < 8; ++i) CHECK(has_point(xyz, n, i & 1, (i >> 1) & 1, (i >> 2) & 1));
    px_free_points(xyz, n, &g_counting);

    px_convex *c = px_convex_create_from_file(path, g_opt, &err);
    CHECK(c != NULL);
    if (c) {
        CHECK(px_convex_vertex_count(c) == 8);
        CHECK(px_convex_edge_count(c) == 12);
        CHECK(px_convex_face_count(c) == 6);
        CHECK(px_convex_validate(c, NULL) == PX_OK);
        px_convex_destroy(c);
    }
}

/* A tetrahedron mesh instanced by two nodes: translated by (10, 0, 0) and
 * rotated 90 degrees about z then translated by (0, 5, 0). Y_UP so Assimp
 * adds no axis conversion; unit meter = 1. */
static const char *k_dae =
    "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
    "<COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" version=\"1.4.1\">\n"
    "<asset><unit name=\"meter\" meter=\"1\"/><up_axis>Y_UP</up_axis></asset>\n"
    "<library_geometries><geometry id=\"tet\"><mesh>\n"
    "<source id=\"p\"><float_array id=\"pa\" count=\"12\">0 0 0 1 0 0 0 1 0 0 0 1</float_array>\n"
    "<technique_common><accessor source=\"#pa\" count=\"4\" stride=\"3\">\n"
    "<param name=\"X\" type=\"float\"/><param name=\"Y\" type=\"float\"/><param name=\"Z\" type=\"float\"/>\n"
    "</accessor></technique_common></source>\n"
    "<vertices id=\"v\"><input semantic=\"POSITION\" source=\"#p\"/></vertices>\n"
    "<triangles count=\"4\"><input semantic=\"VERTEX\" source=\"#v\" offset=\"0\"/>\n"
    "<p>0 2 1 0 1 3 0 3 2 1 2 3</p></triangles>\n"
    "</mesh></geometry></library_geometries>\n"
    "<library_visual_scenes><visual_scene id=\"s\">\n"
    "<node id=\"a\"><matrix>1 0 0 10 0 1 0 0 0 0 1 0 0 0 0 1</matrix>"
    "<instance_geometry url=\"#tet\"/></node>\n"
    "<node id=\"b\"><matrix>0 -1 0 0 1 0 0 5 0 0 1 0 0 0 0 1</matrix>"
    "<instance_geometry url=\"#tet\"/></node>\n"
    "</visual_scene></library_visual_scenes>\n"
    "<scene><instance_visual_scene url=\"#s\"/></scene>\n"
    "</COLLADA>\n";

static void test_node_transforms(void) {
    const char *path = write_file("two_tets.dae", k_dae);
    double *xyz = NULL;
    size_t n = 0;
    px_error err;
    px_status st = px_load_points(path, &g_counting, &xyz, &n, &err);
    CHECK(st == PX_OK);
    if (st != PX_OK) {
        fprintf(stderr, "  %s\n", err.message);
        return;
    }
    CHECK(n == 8);
    /* node a: p + (10,0,0) */
    CHECK(has_point(xyz, n, 10, 0, 0));
    CHECK(has_point(xyz, n, 11, 0, 0));
    CHECK(has_point(xyz, n, 10, 1, 0));
    CHECK(has_point(xyz, n, 10, 0, 1));
    /* node b: Rz(90) p + (0,5,0): (x,y,z) -> (-y, x, z) + (0,5,0) */
    CHECK(has_point(xyz, n, 0, 5, 0));
    CHECK(has_point(xyz, n, 0, 6, 0));
    CHECK(has_point(xyz, n, -1, 5, 0));
    CHECK(has_point(xyz, n, 0, 5, 1));
    px_free_points(xyz, n, &g_counting);
}

static void expect_io_error(const char *path, const char *needle) {
    px_error err;
    memset(&err, 0, sizeof err);
    px_convex *c = px_convex_create_from_file(path, g_opt, &err);
    CHECK(c == NULL);
    CHECK(err.code == PX_ERR_IO);
    CHECK(strstr(err.message, path) != NULL || strstr(err.message, "mesh file") != NULL);
    if (needle && !strstr(err.message, needle)) {
        fprintf(stderr, "  message for '%s' lacks '%s': %s\n", path, needle, err.message);
        g_failures++;
    }
    double *xyz = (double *)&err; /* must be reset to NULL */
    size_t n = 99;
    CHECK(px_load_points(path, &g_counting, &xyz, &n, NULL) == PX_ERR_IO);
    CHECK(xyz == NULL && n == 0);
    px_convex_destroy(c);
}

static void test_errors(void) {
    char missing[512];
    snprintf(missing, sizeof missing, "%s/does_not_exist.obj", g_dir);
    expect_io_error(missing, "No such file");
    expect_io_error(write_file("empty.obj", ""), "empty");
    expect_io_error(g_dir, "directory");
    expect_io_error(write_file("notes.txt", "hello, not a mesh\n"), NULL);
    expect_io_error(write_file("nan.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 nan\nf 1 2 3\nf 1 2 4\n"), "NaN");
    expect_io_error(write_file("inf.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1e39\nf 1 2 3\nf 1 2 4\n"),
                    "NaN");
    expect_io_error(write_file("empty.stl", "solid x\nendsolid x\n"), NULL);

    /* Flat input: a degenerate hull, reported with the file name. */
    const char *flat = write_file("flat.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 4 3\n");
    px_error err;
    CHECK(px_convex_create_from_file(flat, NULL, &err) == NULL);
    CHECK(err.code == PX_ERR_DEGENERATE);
    CHECK(strstr(err.message, "flat.obj") != NULL);

    CHECK(px_convex_create_from_file(NULL, NULL, &err) == NULL && err.code == PX_ERR_INVALID_ARGUMENT);
    CHECK(px_convex_create_from_file("", NULL, &err) == NULL && err.code == PX_ERR_INVALID_ARGUMENT);
    double *xyz;
    size_t n;
    CHECK(px_load_points(flat, NULL, NULL, &n, &err) == PX_ERR_INVALID_ARGUMENT);
    CHECK(px_load_points(flat, NULL, &xyz, NULL, &err) == PX_ERR_INVALID_ARGUMENT);
    px_free_points(NULL, 0, NULL);
}

/* Point clouds (OBJ with only `v` lines) are valid hull input. */
static void test_point_cloud(void) {
    const char *path = write_file("cloud.obj", "v 0 0 0\nv 2 0 0\nv 0 2 0\nv 0 0 2\nv 0.25 0.25 0.25\n");
    px_error err;
    px_convex *c = px_convex_create_from_file(path, g_opt, &err);
    CHECK(c != NULL);
    if (c) {
        CHECK(px_convex_vertex_count(c) == 4); /* the interior point is not a vertex */
        px_convex_destroy(c);
    }
}

int main(void) {
    snprintf(g_dir, sizeof g_dir, "/tmp/proxima_test_io_%ld", (long)getpid());
    char cmd[300];
    snprintf(cmd, sizeof cmd, "mkdir -p '%s'", g_dir);
    if (system(cmd) != 0) return 2;
    px_convex_options counted;
    memset(&counted, 0, sizeof counted);
    counted.allocator = &g_counting;
    g_opt = &counted;

    test_cube_obj();
    test_node_transforms();
    test_errors();
    test_point_cloud();

    CHECK(g_live_bytes == 0 && g_live_blocks == 0);
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", g_dir);
    if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", g_dir);
    if (g_failures) {
        fprintf(stderr, "test_io: %d failure(s)\n", g_failures);
        return 1;
    }
    printf("test_io: all checks passed\n");
    return 0;
}
