/* make_assembly: writes the assemblies check_cli.sh runs `proxima check` on
 * (issue 11 §4).
 *
 *   make_assembly boxes --obj FILE | --stl DIR | --dae FILE
 *       eleven parts with known answers, as one OBJ file (one object per
 *       part), a folder of ASCII STL files (one per part, full precision)
 *       or one COLLADA file (one node per part, each geometry in its node's
 *       frame, placed by the node's matrix). Every coordinate is a small
 *       dyadic number, exact in floats, so the distances below are exact:
 *         0 a_overlap  [0,1]^3                    1 b_overlap  overlaps a by 0.25
 *         2 c_touch    [10,11]x[0,1]^2            3 d_touch    touches c (face x = 11)
 *         4 e_gap      [20,21]x[0,1]^2            5 f_gap      0.5 from e
 *         6 g_shell    [30,34]x[0,4]^2 (closed)   7 h_inner    inside g, 1 from its surface
 *         8 i_sheet    one triangle (open) inside g, 0.5 from its surface,
 *                      sqrt(3) from h
 *         9 j_cylinder a 16-gon prism of radius 1 about (40, 0.5), z in [0,1]
 *        10 k_block    [43,44]x[0,1]^2, 2 from j
 *       Any other pair is at least 5 apart.
 *
 *   make_assembly puma DIR MODELS q1 q2 q3 q4 q5 q6
 *       the Puma 560's seven links (MODELS/puma560/nimasarli_puma560_description,
 *       STL in inches) placed at joint angles q (radians) by the URDF of
 *       SOURCE.md's table 1, in metres, as DIR/link1.stl .. link7.stl
 *       (ASCII, full precision).
 *
 * Exit status 0, or 1 with a message. Public API only. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "px_gen.h"

#include "proxima/io.h"
#include "proxima/proxima.h"

#define PI 3.14159265358979323846
#define MAXV 64
#define MAXT 128

typedef struct shape {
    const char *name;
    double v[MAXV][3];
    int t[MAXT][3];
    int nv, nt;
} shape;

/* A prism: the polygon (x[i], y[i]), counter-clockwise seen from +z,
 * between z0 and z1; triangles face out. */
static void prism(shape *s, const char *name, const double *x, const double *y, int n, double z0, double z1) {
    memset(s, 0, sizeof *s);
    s->name = name;
    for (int i = 0; i < n; ++i) {
        s->v[i][0] = s->v[n + i][0] = x[i];
        s->v[i][1] = s->v[n + i][1] = y[i];
        s->v[i][2] = z0;
        s->v[n + i][2] = z1;
    }
    s->nv = 2 * n;
    for (int i = 1; i + 1 < n; ++i) {
        int *b = s->t[s->nt++], *t = s->t[s->nt++];
        b[0] = 0, b[1] = i + 1, b[2] = i;
        t[0] = n, t[1] = n + i, t[2] = n + i + 1;
    }
    for (int i = 0; i < n; ++i) {
        int j = (i + 1) % n;
        int *p = s->t[s->nt++], *q = s->t[s->nt++];
        p[0] = i, p[1] = j, p[2] = n + j;
        q[0] = i, q[1] = n + j, q[2] = n + i;
    }
}

static void box(shape *s, const char *name, double x0, double x1, double y0, double y1, double z0,
                double z1) {
    double x[4] = {x0, x1, x1, x0}, y[4] = {y0, y0, y1, y1};
    prism(s, name, x, y, 4, z0, z1);
}

static int boxes(shape *s) {
    int n = 0;
    box(&s[n++], "a_overlap", 0, 1, 0, 1, 0, 1);
    box(&s[n++], "b_overlap", 0.75, 1.75, 0.25, 0.75, 0.25, 0.75);
    box(&s[n++], "c_touch", 10, 11, 0, 1, 0, 1);
    box(&s[n++], "d_touch", 11, 12, 0, 1, 0, 1);
    box(&s[n++], "e_gap", 20, 21, 0, 1, 0, 1);
    box(&s[n++], "f_gap", 21.5, 22.5, 0, 1, 0, 1);
    box(&s[n++], "g_shell", 30, 34, 0, 4, 0, 4);
    box(&s[n++], "h_inner", 31, 32, 1, 2, 1, 2);
    shape *t = &s[n++];
    memset(t, 0, sizeof *t);
    t->name = "i_sheet";
    const double tv[3][3] = {{33, 3, 3}, {33.5, 3, 3}, {33, 3.5, 3}};
    memcpy(t->v, tv, sizeof tv);
    t->nv = 3;
    t->t[0][0] = 0, t->t[0][1] = 1, t->t[0][2] = 2;
    t->nt = 1;
    double x[16], y[16];
    for (int i = 0; i < 16; ++i) {
        x[i] = 40 + (i == 0 ? 1.0 : cos(2 * PI * i / 16));
        y[i] = 0.5 + (i == 0 ? 0.0 : sin(2 * PI * i / 16));
    }
    prism(&s[n++], "j_cylinder", x, y, 16, 0, 1);
    box(&s[n++], "k_block", 43, 44, 0, 1, 0, 1);
    return n;
}

static FILE *open_out(const char *path) {
    FILE *f = fopen(path, "w");
    if (!f) fprintf(stderr, "make_assembly: cannot write '%s'\n", path);
    return f;
}

static int write_stl(const char *path, const char *name, const double *v, const uint32_t *t, size_t nt) {
    FILE *f = open_out(path);
    if (!f) return 1;
    fprintf(f, "solid %s\n", name);
    for (size_t i = 0; i < nt; ++i) {
        fprintf(f, " facet normal 0 0 0\n  outer loop\n");
        for (int k = 0; k < 3; ++k) {
            const double *p = v + 3 * (size_t)t[3 * i + k];
            fprintf(f, "   vertex %.17g %.17g %.17g\n", p[0], p[1], p[2]);
        }
        fprintf(f, "  endloop\n endfacet\n");
    }
    fprintf(f, "endsolid %s\n", name);
    return fclose(f) != 0;
}

static int shape_stl(const char *dir, const shape *s) {
    char path[1024];
    snprintf(path, sizeof path, "%s/%s.stl", dir, s->name);
    double v[3 * MAXV];
    uint32_t t[3 * MAXT];
    for (int i = 0; i < s->nv; ++i) memcpy(v + 3 * i, s->v[i], sizeof s->v[i]);
    for (int i = 0; i < 3 * s->nt; ++i) t[i] = (uint32_t)s->t[i / 3][i % 3];
    return write_stl(path, s->name, v, t, (size_t)s->nt);
}

static int write_obj(const char *path, const shape *s, int n) {
    FILE *f = open_out(path);
    if (!f) return 1;
    fprintf(f, "# make_assembly boxes: %d parts\n", n);
    int base = 1;
    for (int k = 0; k < n; ++k) {
        fprintf(f, "o %s\n", s[k].name);
        for (int i = 0; i < s[k].nv; ++i)
            fprintf(f, "v %.17g %.17g %.17g\n", s[k].v[i][0], s[k].v[i][1], s[k].v[i][2]);
        for (int i = 0; i < s[k].nt; ++i)
            fprintf(f, "f %d %d %d\n", base + s[k].t[i][0], base + s[k].t[i][1], base + s[k].t[i][2]);
        base += s[k].nv;
    }
    return fclose(f) != 0;
}

/* COLLADA 1.4.1, Y up (no axis rotation), metres: geometry k in the frame
 * of node k, which its matrix moves to (floor of the part's box minimum). */
static int write_dae(const char *path, const shape *s, int n) {
    FILE *f = open_out(path);
    if (!f) return 1;
    fprintf(f, "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
               "<COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" version=\"1.4.1\">\n"
               "  <asset><unit name=\"meter\" meter=\"1\"/><up_axis>Y_UP</up_axis></asset>\n"
               "  <library_geometries>\n");
    double origin[16][3];
    for (int k = 0; k < n; ++k) {
        for (int c = 0; c < 3; ++c) {
            double lo = INFINITY;
            for (int i = 0; i < s[k].nv; ++i) lo = fmin(lo, s[k].v[i][c]);
            origin[k][c] = floor(lo);
        }
        fprintf(f, "    <geometry id=\"%s-mesh\" name=\"%s\"><mesh>\n", s[k].name, s[k].name);
        fprintf(f, "      <source id=\"g%d-pos\"><float_array id=\"g%d-arr\" count=\"%d\">", k, k,
                3 * s[k].nv);
        for (int i = 0; i < s[k].nv; ++i)
            fprintf(f, "%s%.9g %.9g %.9g", i ? " " : "", s[k].v[i][0] - origin[k][0],
                    s[k].v[i][1] - origin[k][1], s[k].v[i][2] - origin[k][2]);
        fprintf(f,
                "</float_array>\n        <technique_common><accessor source=\"#g%d-arr\" count=\"%d\" "
                "stride=\"3\">"
                "<param name=\"X\" type=\"float\"/><param name=\"Y\" type=\"float\"/>"
                "<param name=\"Z\" type=\"float\"/></accessor></technique_common></source>\n",
                k, s[k].nv);
        fprintf(
            f,
            "      <vertices id=\"g%d-vtx\"><input semantic=\"POSITION\" source=\"#g%d-pos\"/></vertices>\n",
            k, k);
        fprintf(
            f,
            "      <triangles count=\"%d\"><input semantic=\"VERTEX\" source=\"#g%d-vtx\" offset=\"0\"/><p>",
            s[k].nt, k);
        for (int i = 0; i < s[k].nt; ++i)
            fprintf(f, "%s%d %d %d", i ? " " : "", s[k].t[i][0], s[k].t[i][1], s[k].t[i][2]);
        fprintf(f, "</p></triangles>\n    </mesh></geometry>\n");
    }
    fprintf(f,
            "  </library_geometries>\n  <library_visual_scenes><visual_scene id=\"scene\" name=\"scene\">\n");
    for (int k = 0; k < n; ++k)
        fprintf(f,
                "    <node id=\"%s\" name=\"%s\"><matrix>1 0 0 %.9g 0 1 0 %.9g 0 0 1 %.9g 0 0 0 1</matrix>"
                "<instance_geometry url=\"#%s-mesh\"/></node>\n",
                s[k].name, s[k].name, origin[k][0], origin[k][1], origin[k][2], s[k].name);
    fprintf(f, "  </visual_scene></library_visual_scenes>\n"
               "  <scene><instance_visual_scene url=\"#scene\"/></scene>\n</COLLADA>\n");
    return fclose(f) != 0;
}

/* ---- the Puma 560 (SOURCE.md table 1; as examples/model_demo.c) ------- */

static px_pose compose(const px_pose *a, const px_pose *b) {
    px_pose out;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            out.r[3 * i + j] =
                a->r[3 * i] * b->r[j] + a->r[3 * i + 1] * b->r[3 + j] + a->r[3 * i + 2] * b->r[6 + j];
    out.t = px_pose_apply(a, b->t);
    return out;
}

/* URDF origin: translation, then fixed-axis roll-pitch-yaw (R = Rz Ry Rx). */
static px_pose origin(double x, double y, double z, double roll, double pitch, double yaw) {
    px_pose p;
    pg_rot_rpy(roll, pitch, yaw, p.r);
    p.t = (px_vec3){x, y, z};
    return p;
}

/* Rotation by q about a unit axis. */
static px_pose about(px_vec3 a, double q) {
    double c = cos(q), s = sin(q), t = 1 - c;
    px_pose p;
    double r[9] = {t * a.x * a.x + c,       t * a.x * a.y - s * a.z, t * a.x * a.z + s * a.y,
                   t * a.x * a.y + s * a.z, t * a.y * a.y + c,       t * a.y * a.z - s * a.x,
                   t * a.x * a.z - s * a.y, t * a.y * a.z + s * a.x, t * a.z * a.z + c};
    memcpy(p.r, r, sizeof r);
    p.t = (px_vec3){0, 0, 0};
    return p;
}

static void arm_poses(const double q[6], px_pose out[7]) {
    const px_vec3 z = {0, 0, 1}, y = {0, 1, 0};
    px_pose link = px_pose_identity();
    out[0] = origin(0, 0, 0, 0, 0, PI / 2);
    const px_pose joints[6] = {origin(0, 0, 0.6718, PI / 2, 0, 0),
                               origin(0, 0, 0, 0, 0, 0),
                               origin(0.4318, -0.0203, 0.1501, 0, 0, -PI / 2),
                               origin(0, 0, 0, PI / 2, 0, PI / 2),
                               origin(0, 0, 0.4331, PI / 2, 0, 0),
                               origin(0, 0.0558, 0, -PI / 2, 0, 0)};
    const px_pose visuals[6] = {origin(0, 0, -0.1, 0, 0, 0),    origin(0, 0, 0.1936, 0, 0, 0),
                                origin(0, 0, 0, 0, 0, 0),       origin(0, 0, 0.3621, 0, 0, PI / 2),
                                origin(0, 0, 0, PI, 0, PI / 2), origin(0, 0, -0.010, 0, 0, 0)};
    for (int j = 0; j < 6; ++j) {
        px_pose rot = about(j == 0 ? y : z, q[j]);
        px_pose a = compose(&link, &joints[j]);
        link = compose(&a, &rot);
        out[j + 1] = compose(&link, &visuals[j]);
    }
}

static int puma(const char *dir, const char *models, const double q[6]) {
    px_pose pose[7];
    arm_poses(q, pose);
    for (int i = 0; i < 7; ++i) {
        char path[1024], name[32];
        snprintf(path, sizeof path, "%s/puma560/nimasarli_puma560_description/meshes/puma_link%d.stl", models,
                 i + 1);
        px_mesh_options mo;
        memset(&mo, 0, sizeof mo);
        mo.scale = 0.0254; /* inches */
        px_error e;
        px_mesh *m = px_mesh_load(path, &mo, &e);
        if (!m) {
            fprintf(stderr, "make_assembly: %s\n", e.message);
            return 1;
        }
        size_t nv = px_mesh_vertex_count(m);
        double *v = malloc(sizeof(double) * 3 * nv);
        if (!v) {
            px_mesh_destroy(m);
            return 1;
        }
        const double *src = px_mesh_vertices(m);
        for (size_t k = 0; k < nv; ++k) {
            px_vec3 p = px_pose_apply(&pose[i], (px_vec3){src[3 * k], src[3 * k + 1], src[3 * k + 2]});
            v[3 * k] = p.x, v[3 * k + 1] = p.y, v[3 * k + 2] = p.z;
        }
        snprintf(name, sizeof name, "link%d", i + 1);
        snprintf(path, sizeof path, "%s/link%d.stl", dir, i + 1);
        int bad = write_stl(path, name, v, px_mesh_triangles(m), px_mesh_triangle_count(m));
        free(v);
        px_mesh_destroy(m);
        if (bad) return 1;
    }
    return 0;
}

int main(int argc, char **argv) {
    if (argc == 4 && !strcmp(argv[1], "boxes")) {
        shape s[16];
        int n = boxes(s);
        if (!strcmp(argv[2], "--obj")) return write_obj(argv[3], s, n);
        if (!strcmp(argv[2], "--dae")) return write_dae(argv[3], s, n);
        if (!strcmp(argv[2], "--stl")) {
            for (int k = 0; k < n; ++k)
                if (shape_stl(argv[3], &s[k])) return 1;
            return 0;
        }
    }
    if (argc == 10 && !strcmp(argv[1], "puma")) {
        double q[6];
        for (int j = 0; j < 6; ++j) {
            char *end;
            q[j] = strtod(argv[4 + j], &end);
            if (end == argv[4 + j] || *end) {
                fprintf(stderr, "make_assembly: bad angle '%s'\n", argv[4 + j]);
                return 1;
            }
        }
        return puma(argv[2], argv[3], q);
    }
    fprintf(stderr, "usage: make_assembly boxes --obj FILE | --stl DIR | --dae FILE\n"
                    "       make_assembly puma DIR MODELS q1 q2 q3 q4 q5 q6\n");
    return 1;
}
