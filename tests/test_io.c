/* Tests of src/io (px_convex_create_from_file, px_load_points).
 *
 * Oracles are independent of Assimp and of the hull code: the expected
 * points are written into the files by this test, so the loaded, deduplicated
 * point set must equal them exactly (float-representable coordinates), and
 * the hull of a cube must have 8 vertices, 12 edges, 6 faces. Node
 * transforms are tested with a COLLADA file instancing one mesh twice.
 * Every allocation goes through a counting allocator: nothing may leak.
 * Malformed files (lying OFF, PLY and STL headers, formats whose counts
 * cannot be checked, empty files, directories,
 * pipes, devices, oversized files, NaN coordinates) must fail with PX_ERR_IO
 * and the file's name in the message, under a 2 GiB address-space limit. */
#define _POSIX_C_SOURCE 200809L

#include <ctype.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include "proxima/proxima.h"
#include "proxima/io.h"

/* AddressSanitizer builds (PROXIMA_SANITIZE) cannot run under an address-space limit. */
#if defined(__SANITIZE_ADDRESS__)
#define PX_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define PX_TEST_ASAN 1
#endif
#endif
#ifndef PX_TEST_ASAN
#define PX_TEST_ASAN 0
#endif

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

/* Writes `len` bytes to a file in the test directory; returns its path
 * (a static buffer, valid until the next call). */
static const char *write_bytes(const char *name, const void *data, size_t len) {
    static char path[512];
    snprintf(path, sizeof path, "%s/%s", g_dir, name);
    FILE *f = fopen(path, "wb");
    if (!f || fwrite(data, 1, len, f) != len) {
        perror(path);
        exit(2);
    }
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

    /* Flat input: a polygon (a lower-dimensional piece, issue 9). */
    const char *flat = write_file("flat.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 4 3\n");
    px_error err;
    px_convex *square = px_convex_create_from_file(flat, NULL, &err);
    CHECK(square != NULL && err.code == PX_OK);
    CHECK(px_convex_dimension(square) == 2 && px_convex_vertex_count(square) == 4);
    px_convex_destroy(square);

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

/* ------------------------------------------------------------------------
 * Lying headers and other malformed files (BAD_INPUTS.md E.23, E.28, E.30).
 *
 * Regression: Assimp 5.2 (Debian bookworm) allocates and constructs arrays of
 * the sizes a header declares before reading the elements: a 45-byte OFF
 * declaring 2e9 vertices took 13 GB before the process was killed, a 172-byte
 * binary PLY the same, and an ascii PLY or OFF declaring a few million
 * vertices too many loaded "successfully" with the missing vertices at the
 * origin. main() caps the address space at 2 GiB, so a regression fails
 * (Assimp's std::bad_alloc has no "declares" in it) instead of eating the
 * machine. All files are written here, at test time. */

/* A file refused before any import: PX_ERR_IO from both entry points, the
 * file's path and `needle` in the message, outputs reset. */
static void expect_refused(const char *path_in, const char *needle) {
    char path[512];
    snprintf(path, sizeof path, "%s", path_in); /* path_in may be write_file's buffer */
    px_error err;
    memset(&err, 0, sizeof err);
    px_convex *c = px_convex_create_from_file(path, NULL, &err);
    CHECK(c == NULL);
    CHECK(err.code == PX_ERR_IO);
    if (!strstr(err.message, path) || (needle && !strstr(err.message, needle))) {
        fprintf(stderr, "  message for '%s' lacks the path or '%s': %s\n", path, needle ? needle : "",
                err.message);
        g_failures++;
    }
    double *xyz = (double *)&err; /* must be reset to NULL */
    size_t n = 99;
    CHECK(px_load_points(path, NULL, &xyz, &n, &err) == PX_ERR_IO);
    CHECK(xyz == NULL && n == 0);
    px_convex_destroy(c);
}

/* A file that must load as the tetrahedron (0,0,0) (1,0,0) (0,1,0) (0,0,1):
 * guards the checks against refusing valid files. */
static void expect_tetrahedron(const char *path_in) {
    char path[512];
    snprintf(path, sizeof path, "%s", path_in);
    double *xyz = NULL;
    size_t n = 0;
    px_error err;
    px_status st = px_load_points(path, NULL, &xyz, &n, &err);
    if (st != PX_OK) {
        fprintf(stderr, "  '%s' did not load: %s\n", path, err.message);
        g_failures++;
        return;
    }
    CHECK(n == 4);
    CHECK(has_point(xyz, n, 0, 0, 0) && has_point(xyz, n, 1, 0, 0));
    CHECK(has_point(xyz, n, 0, 1, 0) && has_point(xyz, n, 0, 0, 1));
    px_free_points(xyz, n, NULL);
}

/* Valid OBJ files of every kind px_load_points reads (the defect "refuses
 * some valid OBJ files"). The oracle is the file's own text: the distinct
 * positions of the vertices the faces, lines and points use, or of every
 * vertex when there is no f, l or p line (io.h), written here as a list;
 * w divides (Assimp's reading of x y z w), colours do not count. */
static void test_obj_variants(void) {
    static const char *tet = "v 0 0 0\nv 2 0 0\nv 0 2 0\nv 0 0 2\n";
#define OBJ_TET_FACES "f 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n"
    static const char *faces = OBJ_TET_FACES;
    static const double k4[4][3] = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 2}};
    static const struct {
        const char *name, *head, *body; /* the file: head, then body (NULL: none) */
        int n;                          /* expected points: the first n of k4, then (5 5 5) */
    } cases[] = {
        {"o_cloud.obj", "v 0 0 0\nv 2 0 0\nv 0 2 0\nv 0 0 2\n", "vt 0.5 0.5\nvp 0.1 0.2\n", 4},
        {"o_w.obj", "v 0 0 0 1\nv 4 0 0 2\nv 0 1 0 0.5\nv 0 0 2 1\n", NULL, 4},
        {"o_colour.obj", "v 0 0 0 1 0 0\nv 2 0 0 0 1 0\nv 0 2 0 0 0 1\nv 0 0 2 1 1 1\n", OBJ_TET_FACES, 4},
        {"o_vn4.obj", "v 0 0 0\nv 2 0 0\nv 0 2 0\nv 0 0 2\n", "vn 0 0 1\nvn 0 0 1\nvn 0 0 1\nvn 0 0 1\n", 4},
        {"o_lines.obj", "v 0 0 0\nv 2 0 0\nv 0 2 0\nv 0 0 2\nv 5 5 5\n", "l 1 2\nl 2 3 4\nl 4 5\n", 5},
        {"o_points.obj", "v 0 0 0\nv 2 0 0\nv 0 2 0\nv 0 0 2\nv 5 5 5\n", "p 1 2\np 3\np 4\n", 4},
        {"o_vtvn.obj", "v 0 0 0\nv 2 0 0\nv 0 2 0\nv 0 0 2\n",
         "vt 0 0\nvt 1 0\nvn 0 0 1\nf 1/1/1 2/2/1 3/1/1\nf 1//1 2//1 4//1\nf 1/2 3/1 4/2\n", 4},
        {"o_neg.obj", "v 0 0 0\nv 2 0 0\nv 0 2 0\nf -3 -2 -1\nv 0 0 2\nv 5 5 5\n", "f -5 -4 -2\n", 4},
        {"o_groups.obj", "mtllib none.mtl\nv 0 0 0\nv 2 0 0\nv 0 2 0\nv 0 0 2\n",
         "o a\nusemtl red\nf 1 2 3\ng b c\ns 1\nf 1 2 4\no d\nusemtl blue\nf 1 3 4\n", 4},
        {"o_comments.obj", "# head\nv 0 0 0 # origin\nv 2 0 0\n\n\nv 0 2 0\n# v 9 9 9\nv 0 0 2\n",
         "# f 1 2 5\nf 1 2 3\n\nf 1 2 4\n", 4},
        {"o_crlf.obj", "v 0 0 0\r\nv 2 0 0\r\nv 0 2 0\r\nv 0 0 2\r\n", "f 1 2 3\r\nf 1 2 4\r\n", 4},
        {"o_cont.obj", "v 0 0 0\nv 2 \\\n0 0\nv 0 2 0\nv 0 0 2\n", "f 1 2 \\\n3\nf 1 2 4", 4},
        {"o_nonl.obj", "v 0 0 0\nv 2 0 0\nv 0 2 0\nv 0 0 2", NULL, 4},
        {"o_unused.obj", "v 0 0 0\nv 2 0 0\nv 0 2 0\nv 0 0 2\nv 5 5 5\n", OBJ_TET_FACES, 4},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        char text[512];
        snprintf(text, sizeof text, "%s%s", cases[i].head, cases[i].body ? cases[i].body : "");
        double *xyz = NULL;
        size_t n = 0;
        px_error err;
        px_status st = px_load_points(write_file(cases[i].name, text), NULL, &xyz, &n, &err);
        int ok = st == PX_OK && n == (size_t)cases[i].n;
        for (int k = 0; ok && k < 4; ++k) ok = has_point(xyz, n, k4[k][0], k4[k][1], k4[k][2]);
        if (ok && cases[i].n == 5) ok = has_point(xyz, n, 5, 5, 5);
        if (!ok) {
            fprintf(stderr, "  %s: status %d, %zu points, expected %d: %s\n", cases[i].name, (int)st, n,
                    cases[i].n, err.message);
            g_failures++;
        }
        px_free_points(xyz, n, NULL);
    }
    /* What Assimp 5.2 cannot read, refused with the line and the way out
     * (before, the messages were Assimp's: "contains no meshes", "OBJ:
     * vertex normal index out of range", "OBJ: Invalid face index."). */
    char text[512];
    snprintf(text, sizeof text, "o cloud\n%s", tet);
    expect_refused(write_file("r_o_cloud.obj", text), "line 1: an object or group in a point cloud");
    snprintf(text, sizeof text, "%sg grp\n", tet);
    expect_refused(write_file("r_g_cloud.obj", text), "line 5: an object or group in a point cloud");
    snprintf(text, sizeof text, "%svn 0 0 1\n", tet);
    expect_refused(write_file("r_vn_cloud.obj", text),
                   "line 5: a point cloud (vertices, no f, l or p line) of "
                   "4 vertices and 1 vn lines");
    snprintf(text, sizeof text, "%sv 5 5 5 1 0 0\n", tet);
    expect_refused(write_file("r_col_cloud.obj", text), "1 of its 5 vertices have a colour");
    snprintf(text, sizeof text, "%sf 1 2 3 # base\nf 1 2 4\n", tet);
    expect_refused(write_file("r_face_comment.obj", text), "line 5: a comment after a face");
    snprintf(text, sizeof text, "%sl 1 2 #edge\n", tet);
    expect_refused(write_file("r_line_comment.obj", text), "line 5: a comment after a face");
    expect_refused(write_file("r_v7.obj", "v 0 0 0 1 1 1 1\nv 2 0 0\nv 0 2 0\nv 0 0 2\n"),
                   "line 1: a vertex line of 7 numbers");
    /* The same faces with vertices in objects and groups do load: the
     * refusal is the point cloud's only. */
    snprintf(text, sizeof text, "o solid\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n%s", faces);
    expect_tetrahedron(write_file("r_o_faces.obj", text));
}

static const float k_tet[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
static const int k_tet_faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};

static unsigned char *put_u32(unsigned char *p, uint32_t v, int big_endian) {
    for (int i = 0; i < 4; ++i) p[i] = (unsigned char)(v >> (8 * (big_endian ? 3 - i : i)));
    return p + 4;
}
static unsigned char *put_f32(unsigned char *p, float f, int big_endian) {
    uint32_t v;
    memcpy(&v, &f, 4);
    return put_u32(p, v, big_endian);
}

/* Binary STL: an 80-byte header starting with `header` (space padded), the
 * count `declared`, then the first `ntri` triangles of the tetrahedron (zero
 * normals); `nan_z` puts a NaN into the last triangle. Returns the length. */
static size_t make_stl(unsigned char *buf, const char *header, uint32_t declared, int ntri, int nan_z) {
    memset(buf, ' ', 80);
    memcpy(buf, header, strlen(header));
    unsigned char *p = put_u32(buf + 80, declared, 0);
    for (int t = 0; t < ntri; ++t) {
        for (int k = 0; k < 3; ++k) p = put_f32(p, 0, 0);
        for (int v = 0; v < 3; ++v)
            for (int k = 0; k < 3; ++k)
                p = put_f32(p, nan_z && t == 3 && k == 2 ? NAN : k_tet[k_tet_faces[t][v]][k], 0);
        *p++ = 0;
        *p++ = 0;
    }
    return (size_t)(p - buf);
}

/* Binary PLY of the tetrahedron: vertices (float x y z) declared `nv`,
 * faces (list uchar int) declared `nf`; the data of 4 vertices and
 * `faces_written` faces follows. Returns the length. */
static size_t make_ply(unsigned char *buf, int big_endian, unsigned long long nv, unsigned long long nf,
                       int faces_written, int nan_z) {
    int h = sprintf((char *)buf,
                    "ply\nformat %s 1.0\ncomment made by test_io\nelement vertex %llu\nproperty float x\n"
                    "property float y\nproperty float z\nelement face %llu\n"
                    "property list uchar int vertex_indices\nend_header\n",
                    big_endian ? "binary_big_endian" : "binary_little_endian", nv, nf);
    unsigned char *p = buf + h;
    for (int v = 0; v < 4; ++v)
        for (int k = 0; k < 3; ++k) p = put_f32(p, nan_z && v == 3 && k == 2 ? NAN : k_tet[v][k], big_endian);
    for (int f = 0; f < faces_written; ++f) {
        *p++ = 3;
        for (int k = 0; k < 3; ++k) p = put_u32(p, (uint32_t)k_tet_faces[f % 4][k], big_endian);
    }
    return (size_t)(p - buf);
}

static const char *k_tet_off_body = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";

static void test_off_headers(void) {
    char text[512];
    /* The file of the report: 2e9 vertices declared in 45 bytes. */
    expect_refused(write_file("lying.off", "OFF\n2000000000 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
                   "declares 2000000000 vertices but has only 45 bytes");
    /* A smaller lie: Assimp gave PX_OK with 2e6 - 3 extra vertices at the origin. */
    expect_refused(write_file("small_lie.off", "OFF\n2000000 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
                   "declares 2000000 vertices");
    expect_refused(write_file("faces_lie.off", "OFF\n4 3000000 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n"),
                   "declares 4 vertices and 3000000 faces");
    /* The variants Assimp accepts: colours, normals, texture coordinates,
     * homogeneous, an explicit dimension; headerless (by extension);
     * comments; a UTF-8 byte-order mark; OFF found by its signature. */
    expect_refused(write_file("colour.off", "COFF\n100000000 1 0\n0 0 0 1 1 1 1\n"),
                   "declares 100000000 vertices");
    expect_refused(write_file("normal.off", "NOFF\n100000000 1 0\n0 0 0 0 0 1\n"),
                   "declares 100000000 vertices");
    expect_refused(write_file("all.off", "STCN4OFF\n100000000 1 0\n0 0 0 1\n"),
                   "declares 100000000 vertices");
    expect_refused(write_file("dim.off", "nOFF 3\n100000000 1 0\n0 0 0\n"), "declares 100000000 vertices");
    expect_refused(write_file("headerless.off", "# no keyword\n\n100000000 1 0\n0 0 0\n"),
                   "declares 100000000 vertices");
    expect_refused(write_file("bom.off", "\xEF\xBB\xBFOFF\n100000000 1 0\n0 0 0\n"),
                   "declares 100000000 vertices");
    expect_refused(write_file("lying_off.model", "OFF\n100000000 1 0\n0 0 0\n"),
                   "declares 100000000 vertices");
    /* Counts beyond 32 bits (Assimp's strtoul10 wraps them). */
    expect_refused(write_file("wrap.off", "OFF\n4294967300 1 0\n0 0 0\n"), "declares 4294967300 vertices");

    /* Enough bytes (a sparse file of NULs) but more than PX_IO_MAX_ELEMENTS. */
    const char *big = write_file("too_many.off", "OFF\n33554432 1 0\n");
    CHECK(truncate(big, 80 << 20) == 0);
    expect_refused(big, "declares 33554433 elements, more than the limit of 33554432");

    /* Valid files still load. */
    snprintf(text, sizeof text, "OFF\n4 4 6\n%s", k_tet_off_body);
    expect_tetrahedron(write_file("tet.off", text));
    snprintf(text, sizeof text, "# comment\n  OFF # comment\n# comment\n4 4 6\n%s", k_tet_off_body);
    expect_tetrahedron(write_file("tet_comments.off", text));
    /* Headerless; not "4 ...": Assimp takes a leading 4 for the 4OFF prefix. */
    snprintf(text, sizeof text, "04 4 6\n%s", k_tet_off_body);
    expect_tetrahedron(write_file("tet_headerless.off", text));
    /* Tightest: 8 lines of a few bytes, no final line break. */
    expect_tetrahedron(write_file("tet_tight.off",
                                  "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n"
                                  "3 0 3 2\n3 1 2 3"));
    expect_refused(write_file("nan.off",
                              "OFF\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 nan\n3 0 2 1\n3 0 1 3\n3 0 3 2\n"
                              "3 1 2 3\n"),
                   "NaN");
}

static void test_ply_headers(void) {
    static unsigned char buf[4096];
    /* The report's case: a binary PLY declaring 2e9 vertices and faces. */
    size_t len = make_ply(buf, 0, 2000000000ull, 2000000000ull, 0, 0);
    expect_refused(write_bytes("lying.ply", buf, len), "declares 2000000000 vertices but has only");
    len = make_ply(buf, 0, 1000000, 4, 4, 0);
    expect_refused(write_bytes("vertices_lie.ply", buf, len), "declares 1000000 vertices");
    len = make_ply(buf, 1, 1000000, 4, 4, 0);
    expect_refused(write_bytes("vertices_lie_be.ply", buf, len), "declares 1000000 vertices");
    /* Faces at their smallest (empty lists, 1 byte each) still do not fit. */
    len = make_ply(buf, 0, 4, 1000000, 4, 0);
    expect_refused(write_bytes("faces_lie.ply", buf, len), "declares 1000000 faces");
    /* Found by its signature, whatever the extension. */
    len = make_ply(buf, 0, 1000000, 4, 4, 0);
    expect_refused(write_bytes("lying_ply.model", buf, len), "declares 1000000 vertices");
    /* Ascii: 1e8 vertices declared, one written (Assimp: PX_OK, 1e8 points). */
    expect_refused(write_file("lying_ascii.ply",
                              "ply\nformat ascii 1.0\nelement vertex 100000000\nproperty float x\n"
                              "property float y\nproperty float z\nend_header\n0 0 0\n"),
                   "declares 100000000 vertices");
    /* Elements other than vertex and face, with and without properties. */
    expect_refused(write_file("junk.ply", "ply\nformat binary_little_endian 1.0\nelement junk 100000000\n"
                                          "property float a\nend_header\n0000"),
                   "declares 100000000 'junk' elements");
    expect_refused(write_file("empty_records.ply",
                              "ply\nformat binary_little_endian 1.0\nelement nothing 1000000\n"
                              "end_header\n"),
                   "declares 1000000 'nothing' elements");
    expect_refused(write_file("int64.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 1\n"
                                           "property int64 x\nend_header\n00000000"),
                   "type Assimp does not read");
    expect_refused(write_file("no_end.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n1\n"),
                   "no end_header");

    /* Valid files still load, including an exactly sized binary body, big
     * endian, and an ascii header with CRLF line breaks and comments. */
    len = make_ply(buf, 0, 4, 4, 4, 0);
    expect_tetrahedron(write_bytes("tet.ply", buf, len));
    len = make_ply(buf, 1, 4, 4, 4, 0);
    expect_tetrahedron(write_bytes("tet_be.ply", buf, len));
    expect_tetrahedron(write_file("tet_ascii.ply",
                                  "ply\r\nformat ascii 1.0\r\ncomment x\r\nobj_info y\r\n"
                                  "element vertex 4\r\nproperty float x\r\nproperty float y\r\n"
                                  "property float z\r\nelement face 4\r\n"
                                  "property list uchar int vertex_indices\r\nend_header\r\n"
                                  "0 0 0\r\n1 0 0\r\n0 1 0\r\n0 0 1\r\n3 0 2 1\r\n3 0 1 3\r\n"
                                  "3 0 3 2\r\n3 1 2 3\r\n"));
    len = make_ply(buf, 0, 4, 4, 4, 1);
    expect_refused(write_bytes("nan.ply", buf, len), "NaN");
}

static void test_stl_files(void) {
    static unsigned char buf[4096];
    size_t len = make_stl(buf, "binary tetrahedron", 4, 4, 0);
    expect_tetrahedron(write_bytes("tet.stl", buf, len));
    /* Exporters often start a binary header with "solid". */
    len = make_stl(buf, "solid but binary", 4, 4, 0);
    expect_tetrahedron(write_bytes("tet_solid.stl", buf, len));
    const char *ascii =
        "solid t\n"
        "facet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 0 1 0\nvertex 1 0 0\nendloop\nendfacet\n"
        "facet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 0 1\nendloop\nendfacet\n"
        "facet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 0 0 1\nvertex 0 1 0\nendloop\nendfacet\n"
        "facet normal 0 0 0\nouter loop\nvertex 1 0 0\nvertex 0 1 0\nvertex 0 0 1\nendloop\nendfacet\n"
        "endsolid t\n";
    expect_tetrahedron(write_file("tet_ascii.stl", ascii));
    char bom[1024];
    snprintf(bom, sizeof bom, "\xEF\xBB\xBF%s", ascii);
    expect_tetrahedron(write_file("tet_ascii_bom.stl", bom));
    /* Keywords in upper case: Assimp 5.2 reads them in lower case only
     * (review s29: the message spoke of a binary STL of 1163153989
     * triangles). A binary STL whose header says "SolidWorks" still loads. */
    char upper[1024];
    for (size_t i = 0; i <= strlen(ascii); ++i) upper[i] = (char)toupper((unsigned char)ascii[i]);
    expect_refused(write_file("tet_upper.stl", upper), "keywords not in lower case");
    /* ... but only a .stl file: this is an OBJ whose first line says "Solid". */
    expect_tetrahedron(write_file("solid_words.obj",
                                  "Solid model exported by CAD\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                  "v 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"));
    len = make_stl(buf, "SolidWorks export", 4, 4, 0);
    expect_tetrahedron(write_bytes("tet_solidworks.stl", buf, len));

    /* Truncated: 4 triangles declared, 3 written; also cut inside the header. */
    len = make_stl(buf, "binary", 4, 3, 0);
    expect_refused(write_bytes("truncated.stl", buf, len), "declares 4 triangles");
    expect_refused(write_bytes("truncated_header.stl", buf, 60), "neither ASCII STL nor binary STL");
    /* A "solid" header does not make a truncated binary file ASCII. */
    len = make_stl(buf, "solid", 4, 3, 0);
    expect_refused(write_bytes("truncated_solid.stl", buf, len), "declares 4 triangles");
    /* Count and size disagree, either way. */
    len = make_stl(buf, "binary", 1000000, 4, 0);
    expect_refused(write_bytes("count_mismatch.stl", buf, len), "declares 1000000 triangles");
    len = make_stl(buf, "binary", 3, 4, 0);
    expect_refused(write_bytes("padded.stl", buf, len), "declares 3 triangles");
    /* 2^31 + 4 triangles: 84 + 50 n wraps to the size of 4 (284 bytes) in
     * Assimp's 32-bit arithmetic; also found by signature ("solid"). */
    len = make_stl(buf, "binary", 0x80000004u, 4, 0);
    expect_refused(write_bytes("wrapped.stl", buf, len),
                   "declares 2147483652 triangles but has only 284 bytes");
    len = make_stl(buf, "solid", 0x80000004u, 4, 0);
    expect_refused(write_bytes("wrapped_stl.model", buf, len), "declares 2147483652 triangles");
    /* A UTF-8 byte-order mark before a binary header: Assimp drops 3 bytes
     * from its buffer but not from the size it checks. */
    len = make_stl(buf, "\xEF\xBB\xBF", 4, 4, 0);
    expect_refused(write_bytes("bom.stl", buf, len), "byte-order mark");
    len = make_stl(buf, "binary", 4, 4, 1);
    expect_refused(write_bytes("nan.stl", buf, len), "NaN");
}

/* Regression: Assimp 5.2's X, ASE, MD5, NFF and COB importers size arrays by
 * counts in the body of the file (1e8 vertices declared in ~200 bytes:
 * 1.1-1.5 GB committed); no header check can bound them, so they are refused
 * by extension and, for X, ASE and MD5, by signature under any name. Also
 * the two 4-byte prefixes Assimp takes for UTF-32 byte-order marks. */
static void test_unchecked_formats(void) {
    const char *x = "xof 0303txt 0032\nMesh m {\n100000000;\n0;0;0;,\n1;0;0;,\n0;1;0;;\n1;\n3;0,1,2;;\n}\n";
    const char *ase = "*3DSMAX_ASCIIEXPORT 200\n*GEOMOBJECT {\n*MESH {\n*MESH_NUMVERTEX 100000000\n"
                      "*MESH_NUMFACES 1\n*MESH_VERTEX_LIST {\n*MESH_VERTEX 0 0 0 0\n}\n}\n}\n";
    const char *md5 = "MD5Version 10\ncommandline \"\"\nnumJoints 1\nnumMeshes 1\n"
                      "joints {\n\"root\" -1 ( 0 0 0 ) ( 0 0 0 )\n}\n"
                      "mesh {\nshader \"a\"\nnumverts 100000000\nvert 0 ( 0 0 ) 0 1\n}\n";
    expect_refused(write_file("lying.x", x), "DirectX files are not accepted");
    expect_refused(write_file("lying_x.txt", x), "DirectX files are not accepted");
    expect_refused(write_file("lying.ase", ase), "ASE files are not accepted");
    expect_refused(write_file("lying_ase.dat", ase), "ASE files are not accepted");
    expect_refused(write_file("lying.md5mesh", md5), "MD5 files are not accepted");
    expect_refused(write_file("lying_md5.bin", md5), "MD5 files are not accepted");
    expect_refused(write_file("lying.nff", "pp 100000000\n0 0 0\n1 0 0\n0 1 0\n"),
                   "NFF files are not accepted");
    expect_refused(write_file("lying.cob",
                              "Caligari V00.01ALH             \nPolH V0.08 Id 1 Parent 0 Size 00000100\n"
                              "World Vertices 100000000\n0 0 0\n"),
                   "COB files are not accepted");
    static const unsigned char utf32_be[] = {0, 0, 0xFE, 0xFF, 0, 0, 0, 'O', 0, 0, 0, 'F', 0, 0, 0, 'F', 0};
    static const unsigned char utf32_le[] = {0xFE, 0xFF, 0, 0, 'O', 0, 0, 0, 'F', 0, 0, 0, 'F', 0, 0, 0};
    expect_refused(write_bytes("utf32_be.off", utf32_be, sizeof utf32_be), "UTF-32");
    expect_refused(write_bytes("utf32_le.obj", utf32_le, sizeof utf32_le), "UTF-32");
}

/* Empty files of each format, paths that are not regular files, and a file
 * over PX_IO_MAX_FILE_BYTES (sparse: no disk space used). */
static void test_special_files(void) {
    static const char *names[] = {"empty.off",  "empty.ply", "empty.stl", "empty.obj", "empty.dae",
                                  "empty.gltf", "empty.glb", "empty.fbx", "empty.3ds", "empty"};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; ++i)
        expect_refused(write_file(names[i], ""), "is empty");
    char path[512];
    snprintf(path, sizeof path, "%s/dir.stl", g_dir);
    CHECK(mkdir(path, 0700) == 0);
    expect_refused(path, "directory");
    snprintf(path, sizeof path, "%s/missing.ply", g_dir);
    expect_refused(path, "No such file");
    expect_refused("/dev/null", "not a regular file");
    snprintf(path, sizeof path, "%s/pipe.stl", g_dir); /* fopen would block: nobody writes */
    CHECK(mkfifo(path, 0600) == 0);
    expect_refused(path, "not a regular file");
    const char *huge = write_file("huge.obj", "v 0 0 0\n");
    CHECK(truncate(huge, (1l << 30) + 1) == 0);
    expect_refused(huge, "has 1073741825 bytes, more than the limit of 1073741824");
}

/* ------------------------------------------------------------------------
 * The adversarial review of the loaders (Assimp 5.2.5, Debian bookworm).
 * Every file is generated here; each block says what it reproduces. */

#if !PX_TEST_ASAN
/* Open file descriptors of this process (/proc/self/fd). */
static int count_fds(void) {
    int n = 0;
    char path[64];
    for (int fd = 0; fd < 4096; ++fd) {
        snprintf(path, sizeof path, "/proc/self/fd/%d", fd);
        n += access(path, F_OK) == 0;
    }
    return n;
}
#endif

/* A glTF 2.0 file with the given "nodes" and "scenes" arrays and one point
 * mesh reading 4 positions from buffer `uri` of `length` bytes. */
static const char *write_gltf(const char *name, const char *nodes, const char *scenes, const char *uri,
                              unsigned long long length) {
    static char text[65536];
    snprintf(
        text, sizeof text,
        "{\"asset\": {\"version\": \"2.0\"}, \"scene\": 0, \"scenes\": %s, \"nodes\": %s,\n"
        "\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": 0}, \"mode\": 0}]}],\n"
        "\"buffers\": [{\"uri\": \"%s\", \"byteLength\": %llu}],\n"
        "\"bufferViews\": [{\"buffer\": 0, \"byteOffset\": 0, \"byteLength\": 48}],\n"
        "\"accessors\": [{\"bufferView\": 0, \"componentType\": 5126, \"count\": 4, \"type\": \"VEC3\",\n"
        "\"min\": [0, 0, 0], \"max\": [1, 1, 1]}]}\n",
        scenes, nodes, uri, length);
    return write_file(name, text);
}

/* Finding 1: Assimp takes any first line starting with "ply" (any case) as
 * the PLY magic, "plyx" too, and the header check used to require
 * "ply" + blank + "format": a 132-byte "plyx" file declaring 3e7 vertices
 * took 1.4 GB and 75 s and loaded; "ply0" + a format line and nothing else
 * made Assimp loop forever (its header loop ends only at end_header, and
 * getNextLine at the end of the file leaves the line as it was). */
/* Comments in PLY headers (review s29): where exporters put them (before
 * the elements, TextureFile, obj_info, between elements, CRLF) they load;
 * among an element's properties Assimp makes the comment an element that
 * takes the properties after it (a vertex lost its z, with PX_OK): refused. */
static void test_ply_comments(void) {
    static const char *body = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
    static const char *const good[] = {
        "comment VCGLIB generated\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 4\nproperty list uchar int vertex_indices\n",
        "comment TextureFile tex.png\nobj_info num_cols 4\nelement vertex 4\nproperty float x\n"
        "property float y\nproperty float z\nelement face 4\nproperty list uchar int vertex_indices\n",
        "element vertex 4\nproperty float x\nproperty float y\nproperty float z\ncomment faces next\n"
        "element face 4\nproperty list uchar int vertex_indices\n",
        "comment a\ncomment a much longer comment line than the others here\nelement vertex 4\n"
        "property float x\nproperty float y\nproperty float z\nelement face 4\n"
        "property list uchar int vertex_indices\n"};
    char text[1024];
    for (size_t i = 0; i < sizeof good / sizeof *good; ++i) {
        snprintf(text, sizeof text, "ply\nformat ascii 1.0\n%send_header\n%s", good[i], body);
        expect_tetrahedron(write_file("comments.ply", text));
    }
    snprintf(text, sizeof text,
             "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\ncomment z next\n"
             "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n%s",
             body);
    expect_refused(write_file("comment_in_props.ply", text), "comment among an element's properties");
}

static void test_ply_magic(void) {
    const char *props = "property float x\nproperty float y\nproperty float z\n";
    char text[1024];
    snprintf(text, sizeof text,
             "plyx\nformat ascii 1.0\nelement vertex 30000000\n%send_header\n0 0 0\n1 0 0\n", props);
    expect_refused(write_file("lie_plyx.ply", text), "declares 30000000 vertices");
    expect_refused(write_file("hang_ply0.ply", "ply0\nformat binary_little_endian 1.0\n"), "loop forever");
    expect_refused(write_file("hang_plyx.ply", "plyx\nformat ascii 1.0\nelement vertex 4\n"), "loop forever");
    expect_refused(
        write_file("hang_upper.model", "PLY\nformat ascii 1.0\nelement vertex 4\nproperty float x\n"),
        "loop forever");
    /* A line-end byte other than "\n" starting a line: getNextLine skips to
     * the next '\n' without refilling its cache (here: past the file). */
    expect_refused(write_file("cr_end.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n\r"),
                   "misreads");
    /* Valid files with such magic lines still load, also with comments. */
    snprintf(text, sizeof text,
             "plyjunk\nformat ascii 1.0\ncomment c\nelement vertex 4\n%send_header\n"
             "0 0 0\n1 0 0\n0 1 0\n0 0 1\n",
             props);
    expect_tetrahedron(write_file("plyjunk.ply", text));
    snprintf(text, sizeof text,
             "PlY\r\nformat ascii 1.0\r\nelement vertex 4\r\n"
             "property float x\r\nproperty float y\r\nproperty float z\r\nend_header\r\n"
             "0 0 0\r\n1 0 0\r\n0 1 0\r\n0 0 1");
    expect_tetrahedron(write_file("plycase.data", text));
}

/* Finding 2: list lengths in the body. Assimp resizes a list to its
 * declared length before reading a value: an ascii list of 2e8 values in a
 * 193-byte file took 3.1 GB and loaded; a binary one 1.5 GB. The check only
 * assumed empty lists. Now the body is walked as Assimp walks it. */
static void test_ply_lists(void) {
    const char *head = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                       "property float z\nelement face 1\nproperty list uint int vertex_indices\nend_header\n"
                       "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
    char text[1024];
    snprintf(text, sizeof text, "%s200000000 0 1 2\n", head);
    expect_refused(write_file("listbomb_ascii.ply", text), "more than the limit of values per list");
    snprintf(text, sizeof text, "%s1000 0 1 2\n", head);
    expect_refused(write_file("list_line.ply", text), "more than its line holds");
    snprintf(text, sizeof text, "%s3 0 1\n", head);
    expect_refused(write_file("list_short.ply", text), "more than its line holds");
    expect_refused(write_file("vertex_short.ply",
                              "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\n"
                              "property float y\nproperty float z\nend_header\n"
                              "0.0 0.0 0.0\n1.0 0.0\n0.0 1.0 0.0\n0.0 0.0 1.0\n"),
                   "fewer values");
    snprintf(text, sizeof text, "%s3 0 1 x\n", head);
    expect_refused(write_file("list_junk.ply", text), "not a number");
    /* Binary: lengths 1e6 (in 12 bytes), 2e8, and -1 as a signed count
     * (Assimp makes it 4294967295). */
    static unsigned char buf[4096];
    const unsigned lens[] = {1000000u, 200000000u};
    for (int k = 0; k < 2; ++k) {
        int h =
            sprintf((char *)buf, "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\n"
                                 "property float y\nproperty float z\nelement face 1\n"
                                 "property list uint int vertex_indices\nend_header\n");
        unsigned char *p = buf + h;
        for (int v = 0; v < 4; ++v)
            for (int c = 0; c < 3; ++c) p = put_f32(p, k_tet[v][c], 0);
        p = put_u32(p, lens[k], 0);
        for (int i = 0; i < 3; ++i) p = put_u32(p, (uint32_t)i, 0);
        expect_refused(write_bytes(k ? "listbomb_bin2.ply" : "listbomb_bin.ply", buf, (size_t)(p - buf)),
                       k ? "more than the limit of values per list" : "more than the bytes left");
    }
    int h = sprintf((char *)buf, "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\n"
                                 "property float y\nproperty float z\nelement face 1\n"
                                 "property list int int vertex_indices\nend_header\n");
    unsigned char *p = buf + h;
    for (int v = 0; v < 4; ++v)
        for (int c = 0; c < 3; ++c) p = put_f32(p, k_tet[v][c], 0);
    p = put_u32(p, 0xFFFFFFFFu, 0);
    expect_refused(write_bytes("list_negative.ply", buf, (size_t)(p - buf)), "declares 4294967295 values");
    /* Assimp writes past its arrays: a second vertex element, and a face
     * whose texcoord list (6 to 8 values) outnumbers its vertex indices. */
    snprintf(text, sizeof text,
             "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nelement vertex 3\n"
             "property float x\nend_header\n0\n1\n2\n3\n");
    expect_refused(write_file("two_vertex.ply", text), "several vertex elements");
    snprintf(text, sizeof text,
             "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
             "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
             "property list uchar float texcoord\nend_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
             "2 0 1 8 0 0 1 0 0 1 1 1\n");
    expect_refused(write_file("texcoord.ply", text), "texcoord");
    /* Valid lists still load (ascii and binary: the existing tet files). */
    snprintf(text, sizeof text, "%s3 0 1 2\n", head);
    expect_tetrahedron(write_file("list_ok.ply", text));
}

/* Finding 3: files a mesh references. A glTF buffer or an OBJ mtllib naming
 * a FIFO hung the import forever, holding the import lock; a buffer that is
 * a 3 GB sparse file was read whole (2.9 GB). Assimp now opens every file
 * through proxima's aiFileIO. */
static void test_referenced_files(void) {
    char path[512], uri[600];
    /* Valid: an external buffer and a material library load. */
    static unsigned char bin[48];
    for (int v = 0; v < 4; ++v)
        for (int c = 0; c < 3; ++c) put_f32(bin + 12 * v + 4 * c, k_tet[v][c], 0);
    write_bytes("tet.bin", bin, sizeof bin);
    expect_tetrahedron(write_gltf("ext_ok.gltf", "[{\"mesh\": 0}]", "[{\"nodes\": [0]}]", "tet.bin", 48));
    write_file("ok.mtl", "newmtl m\nKd 1 1 1\n");
    expect_tetrahedron(write_file("mtl_ok.obj", "mtllib ok.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                                                "usemtl m\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n"));
    /* A FIFO (nobody writes to it: opening it would block). */
    snprintf(path, sizeof path, "%s/fifo.bin", g_dir);
    CHECK(mkfifo(path, 0600) == 0);
    expect_refused(write_gltf("ext_fifo.gltf", "[{\"mesh\": 0}]", "[{\"nodes\": [0]}]", "fifo.bin", 48),
                   "fifo.bin' was refused: it is a FIFO");
    expect_refused(write_file("mtl_fifo.obj", "mtllib fifo.bin\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                                              "f 1 2 3\nf 1 2 4\n"),
                   "fifo.bin' was refused: it is a FIFO");
    /* A directory, a character device. */
    snprintf(path, sizeof path, "%s/sub", g_dir);
    CHECK(mkdir(path, 0700) == 0);
    expect_refused(write_gltf("ext_dir.gltf", "[{\"mesh\": 0}]", "[{\"nodes\": [0]}]", "sub", 48),
                   "it is a directory");
    /* (Assimp puts the directory in front of a buffer's uri: climb to /.) */
    expect_refused(write_gltf("ext_dev.gltf", "[{\"mesh\": 0}]", "[{\"nodes\": [0]}]",
                              "../../../../../../../../../../dev/zero", 48),
                   "it is a character device");
    /* Sparse buffers: one byte over the per-file limit, and exactly at it
     * (then the mesh file and the buffer exceed PX_IO_MAX_IMPORT_BYTES).
     * Neither is read. */
    const char *big = write_bytes("big.bin", bin, sizeof bin);
    CHECK(truncate(big, (off_t)PX_IO_MAX_FILE_BYTES + 1) == 0);
    snprintf(uri, sizeof uri, "big.bin");
    expect_refused(write_gltf("ext_big.gltf", "[{\"mesh\": 0}]", "[{\"nodes\": [0]}]", uri, 48),
                   "more than the limit of 1073741824");
    CHECK(truncate(big, (off_t)PX_IO_MAX_FILE_BYTES) == 0);
    expect_refused(write_gltf("ext_total.gltf", "[{\"mesh\": 0}]", "[{\"nodes\": [0]}]", uri, 48),
                   "PX_IO_MAX_IMPORT_BYTES");
#if !PX_TEST_ASAN
    /* A buffer shorter than its byteLength: glTF2's Buffer::Read throws
     * without deleting its stream, so each such load left a descriptor open
     * (fs.c now closes what Assimp leaves open). Not under AddressSanitizer:
     * LeakSanitizer reports Assimp's own 24-byte stream wrapper, which
     * proxima cannot free. */
    const char *shortbuf =
        write_gltf("ext_short.gltf", "[{\"mesh\": 0}]", "[{\"nodes\": [0]}]", "tet.bin", 100);
    int before = count_fds();
    for (int i = 0; i < 20; ++i) {
        double *xyz = NULL;
        size_t n = 0;
        CHECK(px_load_points(shortbuf, NULL, &xyz, &n, NULL) == PX_ERR_IO);
    }
    CHECK(count_fds() == before);
#endif
}

/* Finding 4: OFF face lines. Assimp skips a face line whose count is 0 or
 * above 9 with --mNumFaces and reads on: two such lines in a one-face file
 * wrap the count to 2^32 - 1 over an array of one face, and
 * ScenePreprocessor reads past it (SIGSEGV on a 38-byte file). */
static void test_off_faces(void) {
    const char *verts = "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
    char text[8192];
    snprintf(text, sizeof text, "%s0\n0 ", verts);
    expect_refused(write_file("c_c.off", text), "has 0 vertices");
    snprintf(text, sizeof text, "%s2 0 1\n", verts);
    expect_refused(write_file("face2.off", text), "a face needs at least 3");
    snprintf(text, sizeof text, "%s3 0 1 4\n", verts);
    expect_refused(write_file("face_range.off", text), "out of range");
    snprintf(text, sizeof text, "%s3 0 1\n", verts);
    expect_refused(write_file("face_short.off", text), "fewer vertex indices");
    snprintf(text, sizeof text, "%s10 0 1 2 3 0 1 2 3 0 1\n10 0 1 2 3 0 1 2 3 0 1\n", verts);
    expect_refused(write_file("face_wrap.off", text), "wraps its face count");
    expect_refused(write_file("verts_short.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n"), "ends after 2 vertex lines");
    /* (With 3 vertex lines, the face line is read as the fourth vertex.) */
    expect_refused(write_file("faces_short.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
                   "declares 1 faces but its text ends after 0");
    /* A line of 4096 bytes: Assimp writes one byte past its line buffer. */
    size_t n = (size_t)snprintf(text, sizeof text, "OFF\n4 1 0\n0 0 0");
    while (n < 4096 + 16) text[n++] = ' ';
    snprintf(text + n, sizeof text - n, "\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n");
    expect_refused(write_file("long_line.off", text), "line of 4096 bytes");
    /* A 10-gon: Assimp drops the face (its vertices stay), so its mesh
     * would lose triangles: refused since review s30, also here, where
     * only the points count (the loaders share px_mesh_load). */
    snprintf(text, sizeof text, "%s10 0 1 2 3 0 1 2 3 0 1\n", verts);
    expect_refused(write_file("face10.off", text), "10 or more vertices");
}

/* The contents of a file written by this test (a static buffer). */
static const char *read_back(const char *path) {
    static char text[65536];
    FILE *f = fopen(path, "rb");
    size_t len = f ? fread(text, 1, sizeof text - 1, f) : 0;
    if (f) fclose(f);
    text[len] = '\0';
    return text;
}

/* A COLLADA file: the tetrahedron geometry, library nodes `library`, and a
 * visual scene whose node instances `root`. */
static const char *write_dae(const char *name, const char *library, const char *root) {
    static char text[65536];
    snprintf(text, sizeof text,
             "<?xml version=\"1.0\"?>\n"
             "<COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" version=\"1.4.1\">\n"
             "<asset><unit name=\"meter\" meter=\"1\"/><up_axis>Y_UP</up_axis></asset>\n"
             "<library_geometries><geometry id=\"tet\"><mesh>\n"
             "<source id=\"p\"><float_array id=\"pa\" count=\"12\">0 0 0 1 0 0 0 1 0 0 0 1</float_array>\n"
             "<technique_common><accessor source=\"#pa\" count=\"4\" stride=\"3\">\n"
             "<param name=\"X\" type=\"float\"/><param name=\"Y\" type=\"float\"/>"
             "<param name=\"Z\" type=\"float\"/>\n</accessor></technique_common></source>\n"
             "<vertices id=\"v\"><input semantic=\"POSITION\" source=\"#p\"/></vertices>\n"
             "<triangles count=\"4\"><input semantic=\"VERTEX\" source=\"#v\" offset=\"0\"/>\n"
             "<p>0 2 1 0 1 3 0 3 2 1 2 3</p></triangles>\n</mesh></geometry></library_geometries>\n"
             "<library_nodes>%s</library_nodes>\n"
             "<library_visual_scenes><visual_scene id=\"s\"><node id=\"r\">%s</node></visual_scene>"
             "</library_visual_scenes>\n<scene><instance_visual_scene url=\"#s\"/></scene>\n</COLLADA>\n",
             library, root);
    return write_file(name, text);
}

/* Finding 5: node graphs. A COLLADA node instancing itself made Assimp
 * recurse until the stack overflowed (SIGSEGV); 20 levels of two instances
 * of the level below (2.6 KB) built 2^20 nodes (2.8 GB), 40 levels 16 GB;
 * the glTF equivalent (children [i+1, i+1]) 2.5 GB at 20 levels. */
static void test_node_graphs(void) {
    static char lib[32768], nodes[8192];
    expect_refused(write_dae("cyclic.dae",
                             "<node id=\"loop\"><instance_geometry url=\"#tet\"/>"
                             "<instance_node url=\"#loop\"/></node>",
                             "<instance_node url=\"#loop\"/>"),
                   "cyclic ('loop'");
    /* A visual scene instanced from inside itself. */
    expect_refused(
        write_dae("cyclic_scene.dae", "", "<instance_geometry url=\"#tet\"/><instance_node url=\"#s\"/>"),
        "cyclic");
    size_t n = 0;
    for (int i = 0; i < 20; ++i)
        n += (size_t)snprintf(
            lib + n, sizeof lib - n,
            "<node id=\"L%d\"><instance_node url=\"#L%d\"/><instance_node url=\"#L%d\"/></node>\n", i, i + 1,
            i + 1);
    snprintf(lib + n, sizeof lib - n, "<node id=\"L20\"><instance_geometry url=\"#tet\"/></node>\n");
    expect_refused(write_dae("expo20.dae", lib, "<instance_node url=\"#L0\"/>"), "65536 node instances");
    /* A chain of 300 nested nodes (Assimp recurses along it). */
    n = 0;
    for (int i = 0; i < 300; ++i) n += (size_t)snprintf(lib + n, sizeof lib - n, "<node id=\"C%d\">", i);
    n += (size_t)snprintf(lib + n, sizeof lib - n, "<instance_geometry url=\"#tet\"/>");
    for (int i = 0; i < 300; ++i) n += (size_t)snprintf(lib + n, sizeof lib - n, "</node>");
    expect_refused(write_dae("chain.dae", lib, "<instance_node url=\"#C0\"/>"), "chain of more than 256");
    /* Valid instancing: L0 instances L1 twice, translated by x = 0 and 10. */
    double *xyz = NULL;
    size_t count = 0;
    px_error err;
    const char *dag = write_dae("dag.dae",
                                "<node id=\"L0\"><node><instance_node url=\"#L1\"/></node>"
                                "<node><matrix>1 0 0 10 0 1 0 0 0 0 1 0 0 0 0 1</matrix>"
                                "<instance_node url=\"#L1\"/></node></node>"
                                "<node id=\"L1\"><instance_geometry url=\"#tet\"/></node>",
                                "<instance_node url=\"#L0\"/>");
    CHECK(px_load_points(dag, NULL, &xyz, &count, &err) == PX_OK);
    CHECK(count == 8 && has_point(xyz, count, 10, 0, 0) && has_point(xyz, count, 0, 0, 1));
    px_free_points(xyz, count, NULL);

    /* glTF. */
    expect_refused(write_gltf("cyclic.gltf", "[{\"children\": [1], \"mesh\": 0}, {\"children\": [0]}]",
                              "[{\"nodes\": [0]}]", "tet.bin", 48),
                   "cyclic");
    n = (size_t)snprintf(nodes, sizeof nodes, "[");
    for (int i = 0; i < 20; ++i)
        n += (size_t)snprintf(nodes + n, sizeof nodes - n, "{\"children\": [%d, %d]}, ", i + 1, i + 1);
    snprintf(nodes + n, sizeof nodes - n, "{\"mesh\": 0}]");
    expect_refused(write_gltf("expo20.gltf", nodes, "[{\"nodes\": [0]}]", "tet.bin", 48),
                   "65536 node instances");
    /* JSON nested deeper than 128 levels (rapidjson's parser recurses). */
    n = (size_t)snprintf(nodes, sizeof nodes, "[{\"mesh\": 0, \"extras\": ");
    for (int i = 0; i < 200; ++i) nodes[n++] = '[';
    for (int i = 0; i < 200; ++i) nodes[n++] = ']';
    snprintf(nodes + n, sizeof nodes - n, "}]");
    expect_refused(write_gltf("deep.gltf", nodes, "[{\"nodes\": [0]}]", "tet.bin", 48),
                   "nested more than 128");
    /* Valid: one mesh node instanced by two parents. */
    xyz = NULL;
    const char *shared = write_gltf("shared.gltf",
                                    "[{\"children\": [2]}, {\"children\": [2], \"translation\": [10, 0, 0]}, "
                                    "{\"mesh\": 0}]",
                                    "[{\"nodes\": [0, 1]}]", "tet.bin", 48);
    CHECK(px_load_points(shared, NULL, &xyz, &count, &err) == PX_OK);
    CHECK(count == 8 && has_point(xyz, count, 10, 0, 0) && has_point(xyz, count, 0, 0, 1));
    px_free_points(xyz, count, NULL);
}

/* Found by fuzzing the COLLADA scan: ColladaParser::ReadPrimitives reads a
 * <p> list with strtol10 and SkipSpacesAndLineEnd while bytes remain, and
 * never passes a byte that is neither: a 0x1D in seed.dae's <p> (1 KB) made
 * it push 0 indices until std::bad_alloc (60 s, many GB). */
static void test_dae_index_list(void) {
    static char text[65536];
    snprintf(text, sizeof text, "%s",
             read_back(write_dae("p_tmp.dae", "", "<instance_geometry url=\"#tet\"/>")));
    char *p = strstr(text, "<p>0 2 1 0");
    CHECK(p != NULL);
    if (!p) return;
    p[8] = 'x';
    expect_refused(write_file("p_junk.dae", text), "<p> or <vcount> list");
    p[8] = ' ';
    expect_tetrahedron(write_file("p_ok.dae", text));
}

/* Finding 6: which formats keep vertices no face uses (io.h). Assimp's OBJ
 * and COLLADA readers build meshes from faces; PLY, OFF and glTF keep every
 * listed vertex. A tetrahedron file whose one face leaves (0,0,1) out. */
static void test_unreferenced_vertices(void) {
    struct {
        const char *name, *text;
        size_t expected;
    } cases[] = {
        {"unused.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n", 3},
        {"unused.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n", 4},
        {"unused.ply",
         "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
         "3 0 1 2\n",
         4},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        double *xyz = NULL;
        size_t n = 0;
        px_error err;
        CHECK(px_load_points(write_file(cases[i].name, cases[i].text), NULL, &xyz, &n, &err) == PX_OK);
        if (n != cases[i].expected) {
            fprintf(stderr, "  %s: %zu points, expected %zu\n", cases[i].name, n, cases[i].expected);
            g_failures++;
        }
        px_free_points(xyz, n, NULL);
    }
    /* COLLADA: one triangle of the four. */
    static char dae[4096];
    const char *full = write_dae("unused_tmp.dae", "", "<instance_geometry url=\"#tet\"/>");
    FILE *f = fopen(full, "rb");
    size_t len = f ? fread(dae, 1, sizeof dae - 1, f) : 0;
    if (f) fclose(f);
    dae[len] = '\0';
    char *tri = strstr(dae, "<triangles count=\"4\">");
    char *p = strstr(dae, "<p>0 2 1 0 1 3 0 3 2 1 2 3</p>");
    CHECK(tri && p);
    if (tri && p) {
        memcpy(tri, "<triangles count=\"1\">", 21);
        memset(p + strlen("<p>0 2 1"), ' ', strlen(" 0 1 3 0 3 2 1 2 3"));
        double *xyz = NULL;
        size_t n = 0;
        px_error err;
        CHECK(px_load_points(write_file("unused.dae", dae), NULL, &xyz, &n, &err) == PX_OK);
        CHECK(n == 3);
        px_free_points(xyz, n, NULL);
    }
    /* glTF: a triangle of indices 0 1 2 (uint16, after the positions). */
    static unsigned char bin[56];
    for (int v = 0; v < 4; ++v)
        for (int c = 0; c < 3; ++c) put_f32(bin + 12 * v + 4 * c, k_tet[v][c], 0);
    bin[48] = 0, bin[50] = 1, bin[52] = 2;
    write_bytes("tet_idx.bin", bin, sizeof bin);
    const char *gltf = write_file(
        "unused.gltf",
        "{\"asset\": {\"version\": \"2.0\"}, \"scene\": 0, \"scenes\": [{\"nodes\": [0]}], \"nodes\": "
        "[{\"mesh\": 0}],\n"
        "\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": 0}, \"indices\": 1, \"mode\": "
        "4}]}],\n"
        "\"buffers\": [{\"uri\": \"tet_idx.bin\", \"byteLength\": 56}],\n"
        "\"bufferViews\": [{\"buffer\": 0, \"byteOffset\": 0, \"byteLength\": 48},\n"
        "{\"buffer\": 0, \"byteOffset\": 48, \"byteLength\": 6}],\n"
        "\"accessors\": [{\"bufferView\": 0, \"componentType\": 5126, \"count\": 4, \"type\": \"VEC3\",\n"
        "\"min\": [0, 0, 0], \"max\": [1, 1, 1]},\n"
        "{\"bufferView\": 1, \"componentType\": 5123, \"count\": 3, \"type\": \"SCALAR\"}]}\n");
    double *xyz = NULL;
    size_t n = 0;
    px_error err;
    CHECK(px_load_points(gltf, NULL, &xyz, &n, &err) == PX_OK);
    CHECK(n == 4);
    px_free_points(xyz, n, NULL);
}

/* ------------------------------------------------------------------------
 * Review io2: nesting Assimp 5.2's readers recurse on, COLLADA accessors,
 * glTF sparse accessors, compressed files, BVH. */

/* Writes head, `open` n times, `close` n times, then tail; returns the path
 * (write_file's buffer). */
static const char *write_nested(const char *name, const char *head, const char *open, const char *close,
                                size_t n, const char *tail) {
    const char *path = write_file(name, head);
    FILE *f = fopen(path, "ab");
    if (!f) {
        perror(path);
        exit(2);
    }
    for (size_t i = 0; i < n; ++i) fputs(open, f);
    for (size_t i = 0; i < n; ++i) fputs(close, f);
    fputs(tail, f);
    fclose(f);
    return path;
}

/* A binary FBX (7.4, 32-bit offsets) of `depth` records nested in one
 * another: each a 14-byte header (end offset, no properties, name "N")
 * closed by a 13-byte zero record. */
static const char *write_fbx_binary(const char *name, size_t depth) {
    size_t size = 27 + 27 * depth + 13 + 16;
    unsigned char *b = calloc(size, 1);
    if (!b) exit(2);
    memcpy(b, "Kaydara FBX Binary  \0\x1a\0", 23);
    put_u32(b + 23, 7400, 0);
    const size_t leaf_end = 27 + 14 * depth;
    for (size_t i = 0; i < depth; ++i) {
        unsigned char *r = b + 27 + 14 * i;
        put_u32(r, (uint32_t)(leaf_end + 13 * (depth - 1 - i)), 0);
        r[12] = 1;
        r[13] = 'N';
    }
    const char *path = write_bytes(name, b, size);
    free(b);
    return path;
}

/* The review's ac_nest.ac, bvh_nest.bvh, fbx_nest.fbx, ogex_nest.ogex,
 * x3d_nest.x3d and xgl_nest.xgl nested 200000 levels and crashed Assimp
 * (SIGSEGV: its readers recurse once per level). The same depths, written
 * here, must be refused before Assimp reads them; the depths the checks
 * allow must not be refused. */
static void test_nesting(void) {
    const size_t n = 200000;
    const char *ac_head = "AC3Db\nMATERIAL \"m\" rgb 1 1 1  amb 0.2 0.2 0.2  emis 0 0 0  spec 0.5 0.5 0.5  "
                          "shi 10  trans 0\nOBJECT world\nkids 1\n";
    const char *ac_tail = "OBJECT poly\nnumvert 4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\nnumsurf 1\nSURF 0x10\nmat 0\n"
                          "refs 3\n0 0 0\n1 0 0\n2 0 0\nkids 0\n";
    expect_refused(write_nested("nest.ac", ac_head, "OBJECT group\nkids 1\n", "", n, ac_tail),
                   "AC3D objects (kids) are nested more than 256");
    expect_refused(write_nested("nest_ac.dat", ac_head, "OBJECT group\nkids 1\n", "", n, ac_tail),
                   "nested more than 256");
    /* "OBJECT" followed by a line break: Assimp skips the next line (the
     * kids line), and still nests by the next one. */
    expect_refused(
        write_nested("nest_nl.ac", ac_head, "OBJECT\nkids 1\nOBJECT group\nkids 1\n", "", n, ac_tail),
        "nested more than 256");
    expect_refused(write_nested("nest.fbx", "; FBX 7.4.0 project file\n", "A: {\n", "}\n", n, ""),
                   "FBX scopes are nested more than 256");
    expect_refused(write_nested("nest_q.fbx", "; FBX 7.4.0 project file\n", "A: \"}\" { ; }\n", "}\n", n, ""),
                   "FBX scopes are nested more than 256");
    expect_refused(write_fbx_binary("nest_bin.fbx", n), "FBX scopes are nested more than 256");
    expect_refused(write_nested("nest.ogex", "Metric {float {1}}\n", "Node { // }\n", "}\n", n, ""),
                   "OpenGEX structures are nested more than 256");
    expect_refused(
        write_nested("nest_ogex.txt", "Metric {float {1}}\n", "Node (a = \"}\") {\n", "}\n", n, ""),
        "OpenGEX structures are nested more than 256");
    expect_refused(write_nested("nest.x3d", "<?xml version=\"1.0\"?>\n<X3D><Scene>", "<Transform>",
                                "</Transform>", n, "</Scene></X3D>\n"),
                   "XML is nested more than 512");
    expect_refused(write_nested("nest.xgl", "<WORLD>", "<OBJECT>", "</OBJECT>", n, "</WORLD>\n"),
                   "XML is nested more than 512");
    expect_refused(
        write_nested("nest_xgl.dat", "<WORLD>", "<OBJECT><!-- </OBJECT> -->", "</OBJECT>", n, "</WORLD>\n"),
        "XML is nested more than 512");
    static const unsigned char utf16[] = {0xFF, 0xFE, '<', 0, 'X', 0, '3', 0, 'D', 0, '/', 0, '>', 0};
    expect_refused(write_bytes("utf16.x3d", utf16, sizeof utf16), "UTF-16");

    /* At the limits: read by Assimp (the AC3D file loads its triangle). */
    double *xyz = NULL;
    size_t count = 0;
    px_error err;
    CHECK(px_load_points(write_nested("deep_ok.ac", ac_head, "OBJECT group\nkids 1\n", "", 254, ac_tail),
                         NULL, &xyz, &count, &err) == PX_OK);
    CHECK(count == 3);
    px_free_points(xyz, count, NULL);
    const char *x3d = write_nested("deep_ok.x3d", "<?xml version=\"1.0\"?>\n<X3D><Scene>", "<Transform>",
                                   "</Transform>", 509, "</Scene></X3D>\n");
    CHECK(px_load_points(x3d, NULL, &xyz, &count, &err) == PX_ERR_IO); /* no mesh in it */
    CHECK(strstr(err.message, "nested") == NULL);
    const char *fbx = write_nested("deep_ok.fbx", "; FBX 7.4.0 project file\n", "A: {\n", "}\n", 256, "");
    CHECK(px_load_points(fbx, NULL, &xyz, &count, &err) == PX_ERR_IO); /* not an FBX scene */
    CHECK(strstr(err.message, "nested") == NULL);
    CHECK(px_load_points(write_fbx_binary("deep_ok_bin.fbx", 256), NULL, &xyz, &count, &err) == PX_ERR_IO);
    CHECK(strstr(err.message, "nested") == NULL);

    /* AC3D counts above the bytes that follow them (Assimp reserves by them),
     * a numsurf count Assimp would spend re-reading one line for, and an
     * OBJECT on a MATERIAL line (not followed). */
    expect_refused(write_file("count.ac", "AC3Db\nOBJECT poly\nnumvert 100000000\n0 0 0\nkids 0\n"),
                   "'numvert 100000000' line declares more entries");
    expect_refused(write_file("kids.ac", "AC3Db\nOBJECT world\nkids 4000000000\nOBJECT poly\nkids 0\n"),
                   "'kids 4000000000' line declares more entries");
    static char spin[400000];
    memset(spin, 'z', sizeof spin - 2);
    spin[sizeof spin - 2] = '\n';
    memcpy(spin, "AC3Db\nOBJECT poly\nnumsurf 200000\nbad\nkids 0\n", 44);
    expect_refused(write_file("spin.ac", spin), "re-read one line");
    expect_refused(write_file("mat.ac", "AC3Db\nMATERIAL \"m\" rgb 1 1 1 OBJECT poly\nkids 0\n"),
                   "MATERIAL line");

    /* Valid small files of these formats load. */
    expect_tetrahedron(write_file("tet.ac",
                                  "AC3Db\nMATERIAL \"m\" rgb 1 1 1  amb 0.2 0.2 0.2  emis 0 0 0  "
                                  "spec 0.5 0.5 0.5  shi 10  trans 0\nOBJECT world\nkids 1\n"
                                  "OBJECT poly\nname \"tet\"\nnumvert 4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
                                  "numsurf 4\nSURF 0x10\nmat 0\nrefs 3\n0 0 0\n2 0 0\n1 0 0\n"
                                  "SURF 0x10\nmat 0\nrefs 3\n0 0 0\n1 0 0\n3 0 0\n"
                                  "SURF 0x10\nmat 0\nrefs 3\n0 0 0\n3 0 0\n2 0 0\n"
                                  "SURF 0x10\nmat 0\nrefs 3\n1 0 0\n2 0 0\n3 0 0\nkids 0\n"));
    expect_tetrahedron(write_file(
        "tet.x3d",
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<X3D profile=\"Interchange\" version=\"3.3\">"
        "<Scene><Transform><Shape>\n<IndexedFaceSet coordIndex=\"0 2 1 -1 0 1 3 -1 0 3 2 -1 1 2 3 -1\">"
        "<Coordinate point=\"0 0 0 1 0 0 0 1 0 0 0 1\"/></IndexedFaceSet>\n</Shape></Transform>"
        "</Scene></X3D>\n"));
    expect_tetrahedron(write_file(
        "tet.ogex", "Metric (key = \"distance\") {float {1}}\nMetric (key = \"up\") {string {\"z\"}}\n"
                    "GeometryNode $node1\n{\n\tName {string {\"tet\"}}\n\tObjectRef {ref {$geometry1}}\n"
                    "}\nGeometryObject $geometry1 // the mesh\n{\n\tMesh (primitive = \"triangles\")\n"
                    "\t{\n\t\tVertexArray (attrib = \"position\") {float[3] {{0, 0, 0}, {1, 0, 0}, "
                    "{0, 1, 0}, {0, 0, 1}}}\n\t\tIndexArray {unsigned_int32[3] {{0, 2, 1}, {0, 1, 3}, "
                    "{0, 3, 2}, {1, 2, 3}}}\n\t}\n}\n"));
    expect_tetrahedron(
        write_file("tet.fbx", "; FBX 7.4.0 project file\nFBXHeaderExtension:  {\n\tFBXHeaderVersion: 1003\n"
                              "\tFBXVersion: 7400\n}\nGlobalSettings:  {\n\tVersion: 1000\n}\nObjects:  {\n"
                              "\tGeometry: 1, \"Geometry::tet\", \"Mesh\" {\n\t\tVertices: *12 {\n"
                              "\t\t\ta: 0,0,0,1,0,0,0,1,0,0,0,1\n\t\t}\n\t\tPolygonVertexIndex: *12 {\n"
                              "\t\t\ta: 0,2,-2,0,1,-4,0,3,-3,1,2,-4\n\t\t}\n\t\tGeometryVersion: 124\n\t}\n"
                              "\tModel: 2, \"Model::tet\", \"Mesh\" {\n\t\tVersion: 232\n\t}\n}\n"
                              "Connections:  {\n\tC: \"OO\",1,2\n\tC: \"OO\",2,0\n}\n"));
    expect_tetrahedron(write_file(
        "tet.xgl",
        "<WORLD><OBJECT><MESH ID=\"0\"><MAT ID=\"0\"><AMB>1, 1, 1</AMB><DIFF>1, 1, 1</DIFF></MAT>\n"
        "<P ID=\"0\">0, 0, 0</P><P ID=\"1\">1, 0, 0</P><P ID=\"2\">0, 1, 0</P><P ID=\"3\">0, 0, 1</P>\n"
        "<F><MATREF>0</MATREF><FV1><PREF>0</PREF></FV1><FV2><PREF>2</PREF></FV2>"
        "<FV3><PREF>1</PREF></FV3></F>\n"
        "<F><MATREF>0</MATREF><FV1><PREF>0</PREF></FV1><FV2><PREF>1</PREF></FV2>"
        "<FV3><PREF>3</PREF></FV3></F>\n"
        "<F><MATREF>0</MATREF><FV1><PREF>0</PREF></FV1><FV2><PREF>3</PREF></FV2>"
        "<FV3><PREF>2</PREF></FV3></F>\n"
        "<F><MATREF>0</MATREF><FV1><PREF>1</PREF></FV1><FV2><PREF>2</PREF></FV2>"
        "<FV3><PREF>3</PREF></FV3></F>\n</MESH><MESHREF>0</MESHREF></OBJECT></WORLD>\n"));

    /* The same XGL without blanks after the commas: Assimp read "0,1,0" as
     * (0.1, 0, 0) and "0,0,1" as (0, 1, 0), with PX_OK. */
    expect_refused(write_file("compact.xgl",
                              "<WORLD><OBJECT><MESH ID=\"0\"><MAT ID=\"0\"><AMB>1.0,1.0,1.0</AMB>"
                              "</MAT>\n<P ID=\"0\">0,0,0</P><P ID=\"1\">1,0,0</P></MESH></OBJECT>"
                              "</WORLD>\n"),
                   "decimal comma");
    expect_refused(write_file("compact_xgl.txt",
                              "<WORLD><OBJECT><MESH><P ID=\"0\">-1,2.5,3</P></MESH></OBJECT>"
                              "</WORLD>\n"),
                   "decimal comma");

    /* BVH: a skeleton, no mesh (Assimp made up points around the bones). */
    const char *bvh = "HIERARCHY\nROOT hips\n{\n\tOFFSET 0 0 0\n\tCHANNELS 3 Xposition Yposition Zposition\n"
                      "\tJOINT knee\n\t{\n\t\tOFFSET 0 -1 0\n\t\tCHANNELS 0\n\t\tEnd Site\n\t\t{\n"
                      "\t\t\tOFFSET 0 -1 0\n\t\t}\n\t}\n}\nMOTION\nFrames: 1\nFrame Time: 0.1\n0 0 0\n";
    expect_refused(write_file("skeleton.bvh", bvh), "BVH files are not accepted");
    expect_refused(write_file("skeleton_bvh.txt", bvh), "BVH files are not accepted");
    expect_refused(write_nested("nest.bvh", "HIERARCHY\nROOT r\n{\nOFFSET 0 0 0\nCHANNELS 0\n",
                                "JOINT j\n{\nOFFSET 0 0 0\nCHANNELS 0\n", "}\n", n,
                                "}\nMOTION\nFrames: 1\nFrame Time: 0.1\n\n"),
                   "BVH files are not accepted");

    /* Compressed files Assimp inflates whole (the review's zgl_bomb.zgl and
     * blend_bomb.blend took 1 GB before std::bad_alloc). */
    static const unsigned char gz[] = {0x1F, 0x8B, 8, 0, 0, 0, 0, 0, 0, 3, 3, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    expect_refused(write_bytes("packed.blend", gz, sizeof gz), "compressed (gzip) Blender");
    expect_refused(write_bytes("packed.zgl", gz + 10, sizeof gz - 10), "ZGL (compressed XGL)");
}

/* Replaces the first `from` in `text` (a buffer of `size`) by `to`. */
static void replace_once(char *text, size_t size, const char *from, const char *to) {
    char *p = strstr(text, from);
    CHECK(p != NULL && strlen(text) - strlen(from) + strlen(to) < size);
    if (!p) return;
    memmove(p + strlen(to), p + strlen(from), strlen(p + strlen(from)) + 1);
    memcpy(p, to, strlen(to));
}

/* COLLADA accessors reading past their arrays (the review's dae_nocount.dae
 * and dae_acc_offset.dae crashed Assimp; dae_count_short.dae and
 * dae_acc_stride.dae returned PX_OK with 7 and 2 points of a cube of 8,
 * read from past the array). */
static void test_dae_accessors(void) {
    static char base[65536], text[65536];
    snprintf(base, sizeof base, "%s",
             read_back(write_dae("acc_tmp.dae", "", "<instance_geometry url=\"#tet\"/>")));
    expect_tetrahedron(write_file("acc_ok.dae", base));
    static const struct {
        const char *name, *from, *to, *needle;
    } cases[] = {
        {"acc_nocount.dae", " count=\"12\"", "",
         "reads 12 values (offset 0, count 4, stride 3), but the array declares 0"},
        {"acc_short.dae", "count=\"12\"", "count=\"3\"", "but the array declares 3"},
        {"acc_offset.dae", "count=\"4\" stride=\"3\"", "count=\"4\" offset=\"100000\" stride=\"3\"",
         "reads 100012 values"},
        {"acc_stride.dae", "stride=\"3\"", "stride=\"1000\"", "reads 3003 values"},
        {"acc_count.dae", "count=\"4\" stride", "count=\"5\" stride", "reads 15 values"},
        {"acc_negative.dae", "count=\"4\" stride", "count=\"-1\" stride", "not a plain number"},
        {"acc_params.dae", "stride=\"3\"", "stride=\"1\"", NULL},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        snprintf(text, sizeof text, "%s", base);
        replace_once(text, sizeof text, cases[i].from, cases[i].to);
        const char *path = write_file(cases[i].name, text);
        if (cases[i].needle) {
            expect_refused(path, cases[i].needle);
        } else {
            /* stride 1 with three params reads values 0 .. 5 of 12: within
             * the array (Assimp reads overlapping points; not refused). */
            double *xyz = NULL;
            size_t n = 0;
            px_error err;
            CHECK(px_load_points(path, NULL, &xyz, &n, &err) == PX_OK);
            px_free_points(xyz, n, NULL);
        }
    }
}

/* COLLADA controllers: a skin whose <v> names joint 1e8 crashed Assimp
 * (SIGSEGV), weight 1e8 aborted it (ai_assert), and a <vcount> of 1e8 took
 * 1.5 GB (instantiated or not). */
static void test_dae_controllers(void) {
    static char text[65536];
    snprintf(text, sizeof text, "%s",
             read_back(write_dae("ctrl_tmp.dae", "", "<instance_geometry url=\"#tet\"/>")));
    replace_once(text, sizeof text, "<library_nodes>",
                 "<library_controllers><controller id=\"skin\"><skin source=\"#tet\">"
                 "<vertex_weights count=\"4\"><vcount>1 1 1 100000000</vcount><v>0 0 0 0 0 0 0 0</v>"
                 "</vertex_weights></skin></controller></library_controllers>\n<library_nodes>");
    expect_refused(write_file("ctrl.dae", text), "COLLADA controllers (skins, morphs) are not accepted");
}

/* glTF sparse accessors: one without "indices" crashed Assimp (SIGSEGV),
 * the review's gltf_sparse.gltf (count 1.5e8, no buffer view) took 1.8 GB
 * before std::bad_alloc. A relative buffer URI with ".." is legitimate. */
static void test_gltf_sparse(void) {
    static unsigned char bin[48];
    for (int v = 0; v < 4; ++v)
        for (int c = 0; c < 3; ++c) put_f32(bin + 12 * v + 4 * c, k_tet[v][c], 0);
    write_bytes("sparse.bin", bin, sizeof bin);
#define SPARSE_DOC                                                                                           \
    "{\"asset\": {\"version\": \"2.0\"}, \"scene\": 0, \"scenes\": [{\"nodes\": [0]}],\n"                    \
    "\"nodes\": [{\"mesh\": 0}], \"meshes\": [{\"primitives\": [{\"attributes\": "                           \
    "{\"POSITION\": 0}, \"mode\": 0}]}],\n"                                                                  \
    "\"buffers\": [{\"uri\": \"%s\", \"byteLength\": 48}],\n"                                                \
    "\"bufferViews\": [{\"buffer\": 0, \"byteLength\": 48}],\n"                                              \
    "\"accessors\": [{\"bufferView\": 0, \"componentType\": 5126, \"count\": %s, "                           \
    "\"type\": \"VEC3\"%s}]}\n"
    static char text[4096];
    snprintf(text, sizeof text, SPARSE_DOC, "sparse.bin", "4",
             ", \"sparse\": {\"count\": 1, \"values\": {\"bufferView\": 0}}");
    expect_refused(write_file("sparse_noidx.gltf", text), "glTF sparse accessor");
    snprintf(text, sizeof text, SPARSE_DOC, "sparse.bin", "150000000",
             ", \"sparse\": {\"count\": 1, \"indices\": {\"bufferView\": 0, \"componentType\": 5125}, "
             "\"values\": {\"bufferView\": 0}}");
    replace_once(text, sizeof text, "\"bufferView\": 0, \"componentType\": 5126", "\"componentType\": 5126");
    expect_refused(write_file("sparse_big.gltf", text), "glTF sparse accessor");
    snprintf(text, sizeof text, SPARSE_DOC, "../sparse.bin", "4", "");
    char sub[600];
    snprintf(sub, sizeof sub, "%s/up", g_dir);
    CHECK(mkdir(sub, 0700) == 0);
    expect_tetrahedron(write_file("up/dotdot.gltf", text));
#undef SPARSE_DOC
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
#if !PX_TEST_ASAN
    /* 2 GiB of address space: a load that allocates by a lying header fails
     * at once (std::bad_alloc) instead of exhausting the machine. AddressSanitizer
     * reserves terabytes of shadow memory, so not there. */
    struct rlimit as_limit = {2ul << 30, 2ul << 30};
    CHECK(setrlimit(RLIMIT_AS, &as_limit) == 0);
#endif

    test_cube_obj();
    test_obj_variants();
    test_node_transforms();
    test_errors();
    test_point_cloud();
    test_off_headers();
    test_ply_headers();
    test_stl_files();
    test_unchecked_formats();
    test_special_files();
    test_ply_magic();
    test_ply_comments();
    test_ply_lists();
    test_referenced_files();
    test_off_faces();
    test_node_graphs();
    test_dae_index_list();
    test_unreferenced_vertices();
    test_nesting();
    test_dae_accessors();
    test_dae_controllers();
    test_gltf_sparse();
#if !PX_TEST_ASAN
    struct rusage usage;
    CHECK(getrusage(RUSAGE_SELF, &usage) == 0);
    CHECK(usage.ru_maxrss < 256 * 1024); /* kB: every lie was refused before Assimp allocated */
#endif

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
