/* proxima: the command line.
 *   proxima info FILE
 *   proxima build IN -o OUT.pxm [--pieces parts|triangles|approximate] [--tolerance T] [--scale S]
 *   proxima distance A B [--pose-a P] [--pose-b P] [--pieces ...] [--tolerance T] [--scale S]
 *   proxima check FILE [--clearance C] [--json] [--ignore A,B]... [--pieces ...] [--scale S]
 * FILE, IN, A, B: mesh files (any format proxima-io reads) or .pxm models
 * (recognised by their content, not their name). Uses the public API only. */
#include <errno.h>
#include <unistd.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "proxima/io.h"
#include "proxima/proxima.h"

static const char *usage_text =
    "usage:\n"
    "  proxima info FILE\n"
    "      parts, triangles, closed or open, bounding box, units of a mesh file;\n"
    "      leaves, nodes, memory and bound h of a .pxm model\n"
    "  proxima build IN -o OUT.pxm [--pieces parts|triangles|approximate] [--tolerance T]\n"
    "                [--threads N] [--scale S]\n"
    "      builds the sub-part hierarchy tree of a mesh file and saves it\n"
    "  proxima distance A B [--pose-a P] [--pose-b P] [--pieces ...] [--tolerance T]\n"
    "                [--scale S]\n"
    "      distance, closest points, bracket and collision of two models\n"
    "  proxima check FILE [--clearance C] [--json] [--ignore A,B]... [--pieces ...]\n"
    "                [--tolerance T] [--threads N] [--scale S]\n"
    "      every pair of parts of an assembly that interferes (touches, overlaps,\n"
    "      or lies inside a closed part) or is closer than C (default 0), with\n"
    "      distance and witness points; FILE is one file with many parts or a\n"
    "      folder of part files (each file a part named by its file name)\n"
    "\n"
    "FILE, IN, A, B are mesh files (OBJ, STL, PLY, OFF, COLLADA, glTF, ... through\n"
    "Assimp) or .pxm files written by `proxima build`; check takes mesh files\n"
    "and folders of them only (it names the parts).\n"
    "  --pieces   leaves of a model built from a mesh: `triangles` (exact, the\n"
    "             default for distance and check) or `parts` (one convex hull per\n"
    "             part, with a certified bound h; the default for build) or\n"
    "             `approximate` (each part cut into convex pieces that stay within\n"
    "             --tolerance of it, each with a certified bound h)\n"
    "  --tolerance T  for approximate pieces: how far a piece may reach outside\n"
    "             its part, relative to the part's bounding-box diagonal, in\n"
    "             [0.0001, 1]\n"
    "             (default 0.02)\n"
    "  --threads N  for approximate pieces: threads the decomposition may use\n"
    "             (default 1; the model is the same for any N)\n"
    "  --scale S  multiplies the mesh files' coordinates (e.g. 0.0254: inches to\n"
    "             metres); a .pxm model keeps the scale it was built with\n"
    "  --pose-a, --pose-b P   the model's pose: tx,ty,tz or tx,ty,tz,qw,qx,qy,qz\n"
    "             (translation, then a quaternion of any non-zero length)\n"
    "  --clearance C  check: the distance parts must keep (>= 0, in the mesh's\n"
    "             units after --scale); pairs closer than C are reported\n"
    "  --json     check: a JSON document instead of the table (docs/check.md)\n"
    "  --ignore A,B   check: never report parts A and B (touching by design);\n"
    "             repeatable\n"
    "Exit status: 0 success, 1 an error (the message names the file), 2 bad usage;\n"
    "for check: 0 clean, 1 something found, 2 an error or bad usage.\n";

static int usage_error(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;

static int usage_error(const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "proxima: ");
    vfprintf(stderr, fmt, ap);
    fprintf(stderr, "\n(proxima --help for usage)\n");
    va_end(ap);
    return 2;
}

typedef struct opts {
    const char *files[2];
    int nfiles;
    const char *out;
    int pieces; /* -1: command default */
    double scale;
    double tolerance; /* 0: the library's default */
    unsigned threads; /* 0: one */
    px_pose pose[2];
    int has_pose;
    double clearance;
    int has_clearance, json;
    const char **ignore; /* check's --ignore values (room for argc) */
    int nignore;
} opts;

/* A decimal number only: [+-] (digits [. digits] | . digits) [e [+-] digits],
 * none of strtod's hexadecimal, infinities or NaNs (review s29: --clearance
 * 0x10 ran with 16). Returns where it stopped, or NULL. */
static const char *decimal(const char *s, double *out) {
    const char *p = s + (*s == '+' || *s == '-');
    int digits = 0;
    while (*p >= '0' && *p <= '9') ++p, ++digits;
    if (*p == '.')
        for (++p; *p >= '0' && *p <= '9'; ++p) ++digits;
    if (!digits) return NULL;
    if (*p == 'e' || *p == 'E') {
        const char *q = p + 1 + (p[1] == '+' || p[1] == '-');
        if (!(*q >= '0' && *q <= '9')) return NULL;
        while (*q >= '0' && *q <= '9') ++q;
        p = q;
    }
    char *end;
    errno = 0;
    *out = strtod(s, &end);
    if (end != p) return NULL;
    *out += 0.0; /* -0 is 0 */
    return p;
}

/* A whole argument that is a decimal number. */
static int decimal_arg(const char *s, double *out) {
    const char *end = decimal(s, out);
    return end && !*end;
}

static int parse_pose(const char *s, px_pose *out) {
    double v[7];
    int n = 0;
    const char *p = s;
    while (n < 7) {
        const char *end = decimal(p, &v[n]);
        /* (a subnormal sets ERANGE too, and is a number) */
        if (!end || !isfinite(v[n]) || (errno == ERANGE && v[n] == 0.0)) return 0;
        ++n;
        p = end;
        if (*p == '\0') break;
        if (*p != ',') return 0;
        ++p;
    }
    if (*p != '\0' || (n != 3 && n != 7)) return 0;
    double q[4] = {1, 0, 0, 0};
    if (n == 7) memcpy(q, v + 3, sizeof q);
    return px_pose_from_quat(q, v, out) == PX_OK;
}

static int parse(int argc, char **argv, int first, opts *o, const char **ignore) {
    memset(o, 0, sizeof *o);
    o->ignore = ignore;
    o->pieces = -1;
    o->pose[0] = o->pose[1] = px_pose_identity();
    for (int i = first; i < argc; ++i) {
        const char *a = argv[i];
        int has_value = i + 1 < argc;
        if (!strcmp(a, "-o")) {
            if (!has_value) return usage_error("%s needs a file name", a);
            o->out = argv[++i];
        } else if (!strcmp(a, "--pieces")) {
            if (!has_value) return usage_error("%s needs parts, triangles or approximate", a);
            const char *v = argv[++i];
            if (!strcmp(v, "parts"))
                o->pieces = PX_PIECES_PARTS;
            else if (!strcmp(v, "triangles"))
                o->pieces = PX_PIECES_TRIANGLES;
            else if (!strcmp(v, "approximate"))
                o->pieces = PX_PIECES_APPROXIMATE;
            else
                return usage_error("--pieces takes parts, triangles or approximate, not '%s'", v);
        } else if (!strcmp(a, "--threads")) {
            if (!has_value) return usage_error("%s needs a number", a);
            char *end;
            const char *v = argv[++i];
            long t = strtol(v, &end, 10);
            if (end == v || *end || t < 1 || t > 256)
                return usage_error("--threads takes a whole number from 1 to 256, not '%s'", v);
            o->threads = (unsigned)t;
        } else if (!strcmp(a, "--tolerance")) {
            if (!has_value) return usage_error("%s needs a number", a);
            const char *v = argv[++i];
            if (!decimal_arg(v, &o->tolerance) ||
                (errno == ERANGE && (isinf(o->tolerance) || o->tolerance == 0.0)) ||
                !(o->tolerance >= PX_MODEL_MIN_TOLERANCE && o->tolerance <= 1.0))
                return usage_error("--tolerance takes a number in [%g, 1], not '%s'", PX_MODEL_MIN_TOLERANCE,
                                   v);
        } else if (!strcmp(a, "--scale")) {
            if (!has_value) return usage_error("%s needs a number", a);
            const char *v = argv[++i];
            if (!decimal_arg(v, &o->scale) || (errno == ERANGE && (isinf(o->scale) || o->scale == 0.0)) ||
                !isfinite(o->scale) || !(o->scale > 0.0))
                return usage_error("--scale takes a positive number, not '%s'", v);
        } else if (!strcmp(a, "--pose-a") || !strcmp(a, "--pose-b")) {
            if (!has_value) return usage_error("%s needs tx,ty,tz[,qw,qx,qy,qz]", a);
            const char *v = argv[++i];
            if (!parse_pose(v, &o->pose[a[7] == 'b']))
                return usage_error("bad pose '%s': tx,ty,tz or tx,ty,tz,qw,qx,qy,qz (quaternion not zero)",
                                   v);
            o->has_pose = 1;
        } else if (!strcmp(a, "--clearance")) {
            if (!has_value) return usage_error("%s needs a number", a);
            const char *v = argv[++i];
            const int number = decimal_arg(v, &o->clearance);
            if (number && errno == ERANGE && (isinf(o->clearance) || o->clearance == 0.0))
                return usage_error("--clearance '%s' is beyond the range of doubles", v);
            if (!number || !isfinite(o->clearance) || !(o->clearance >= 0.0))
                return usage_error("--clearance takes a finite number >= 0, not '%s'", v);
            o->has_clearance = 1;
        } else if (!strcmp(a, "--json")) {
            o->json = 1;
        } else if (!strcmp(a, "--ignore")) {
            if (!has_value) return usage_error("%s needs two part names A,B", a);
            const char *v = argv[++i];
            if (!strchr(v, ',')) return usage_error("--ignore takes two part names A,B, not '%s'", v);
            o->ignore[o->nignore++] = v;
        } else if (a[0] == '-' && a[1] != '\0') {
            return usage_error("unknown option '%s'", a);
        } else {
            if (o->nfiles == 2) return usage_error("too many files ('%s')", a);
            o->files[o->nfiles++] = a;
        }
    }
    if ((o->tolerance != 0.0 || o->threads) && o->pieces != PX_PIECES_APPROXIMATE)
        return usage_error("--tolerance and --threads need --pieces approximate");
    return 0;
}

/* 1 when the file starts with the .pxm magic. */
static int is_pxm(const char *path) {
    FILE *f = fopen(path, "rb");
    if (!f) return 0;
    char magic[8] = {0};
    size_t n = fread(magic, 1, 8, f);
    fclose(f);
    return n == 8 && memcmp(magic, "PXMODEL", 8) == 0;
}

static px_mesh *load_mesh(const char *path, double scale) {
    px_mesh_options mo;
    memset(&mo, 0, sizeof mo);
    mo.scale = scale;
    px_error e;
    px_mesh *m = px_mesh_load(path, &mo, &e);
    if (!m) fprintf(stderr, "proxima: %s\n", e.message);
    return m;
}

/* A progress bar on standard error while a decomposition runs (only when
 * it is a terminal). */
typedef struct bar {
    const char *name;
    int shown; /* last percentage drawn, -1 for none */
} bar;

static int draw_bar(void *user, double fraction) {
    bar *b = user;
    int pct = (int)(fraction * 100.0 + 0.5);
    if (pct == b->shown) return 0;
    b->shown = pct;
    int width = 30, fill = pct * width / 100;
    fprintf(stderr, "\r%s: decomposing [%.*s%*s] %3d%%", b->name, fill, "##############################",
            width - fill, "", pct);
    if (pct >= 100) fprintf(stderr, "\n");
    fflush(stderr);
    return 0;
}

/* A model from a .pxm file or a mesh file. */
static px_model *load_model(const char *path, int pieces, double scale, double tolerance, unsigned threads) {
    px_error e;
    if (is_pxm(path)) {
        if (scale != 0.0)
            fprintf(stderr, "proxima: note: --scale does not apply to the .pxm file '%s'\n", path);
        px_model *m = px_model_load(path, NULL, &e);
        if (!m) fprintf(stderr, "proxima: %s\n", e.message);
        return m;
    }
    px_mesh *mesh = load_mesh(path, scale);
    if (!mesh) return NULL;
    px_model_options o;
    memset(&o, 0, sizeof o);
    o.pieces = (uint32_t)pieces;
    bar b = {path, -1};
    if (pieces == PX_PIECES_APPROXIMATE) {
        o.tolerance = tolerance;
        o.threads = threads;
        if (isatty(STDERR_FILENO)) {
            o.progress = draw_bar;
            o.progress_user = &b;
        }
    }
    px_model *m = px_model_create_from_mesh(mesh, &o, &e);
    if (b.shown >= 0 && b.shown < 100) fprintf(stderr, "\n");
    if (!m) fprintf(stderr, "proxima: '%s': %s\n", path, e.message);
    px_mesh_destroy(mesh);
    return m;
}

static const char *pieces_name(uint32_t p) {
    return p == PX_PIECES_PARTS         ? "parts"
           : p == PX_PIECES_TRIANGLES   ? "triangles"
           : p == PX_PIECES_APPROXIMATE ? "approximate convex pieces"
                                        : "points";
}

static int cmd_info(const opts *o) {
    if (o->nfiles != 1) return usage_error("info takes one file");
    const char *path = o->files[0];
    if (is_pxm(path)) {
        px_error e;
        px_model *m = px_model_load(path, NULL, &e);
        if (!m) {
            fprintf(stderr, "proxima: %s\n", e.message);
            return 1;
        }
        px_model_info in;
        px_model_get_info(m, &in);
        printf("file:        %s (.pxm model)\n", path);
        printf("leaves:      %u (%s)\n", in.leaves, pieces_name(in.pieces));
        printf("nodes:       %u, %u with a hull, depth %u\n", in.nodes, in.hull_nodes, in.depth);
        if (in.pieces == PX_PIECES_TRIANGLES)
            printf("solid:       %s (%u closed parts)\n",
                   in.solid         ? "yes"
                   : in.solid_parts ? "partly"
                                    : "no",
                   in.solid_parts);
        else
            printf("solid:       yes (convex pieces are solids)\n");
        printf("largest h:   %.9g\n", in.max_h);
        printf("box:         [%.9g, %.9g, %.9g] .. [%.9g, %.9g, %.9g]\n", in.min.x, in.min.y, in.min.z,
               in.max.x, in.max.y, in.max.z);
        printf("memory:      %zu bytes\n", in.memory_bytes);
        px_model_destroy(m);
        return 0;
    }
    px_mesh *m = load_mesh(path, o->scale);
    if (!m) return 1;
    px_mesh_info in;
    px_mesh_get_info(m, &in);
    uint32_t np = px_mesh_part_count(m);
    printf("file:        %s\n", path);
    printf("parts:       %u (%u closed, %u open)\n", np, in.closed_parts, np - in.closed_parts);
    printf("triangles:   %u\n", px_mesh_triangle_count(m));
    printf("vertices:    %u\n", px_mesh_vertex_count(m));
    printf("closed:      %s\n", in.closed_parts == np ? "yes (every part bounds a solid)"
                                : in.closed_parts     ? "partly"
                                                      : "no (open surfaces)");
    printf("box:         [%.9g, %.9g, %.9g] .. [%.9g, %.9g, %.9g]\n", in.min.x, in.min.y, in.min.z, in.max.x,
           in.max.y, in.max.z);
    if (in.unit_metres > 0.0)
        printf("units:       1 unit = %.9g m in the file%s\n", in.unit_metres,
               in.scale != 1.0 ? ", then scaled by --scale" : "");
    else
        printf("units:       not stated by the file%s\n", in.scale != 1.0 ? " (scaled by --scale)" : "");
    printf("coordinates: %s\n", in.float_coordinates
                                    ? "32-bit floats, as Assimp reads this file (docs/io.md says which files "
                                      "are read at full precision)"
                                    : "the file's numbers at full precision (doubles)");
    for (uint32_t i = 0; i < np; ++i) {
        px_mesh_part p;
        px_mesh_get_part(m, i, &p);
        printf("  part %u: '%s', %u triangles, %u vertices, %s\n", i, p.name, p.triangle_count,
               p.vertex_count, p.closed ? "closed" : "open");
    }
    px_mesh_destroy(m);
    return 0;
}

static int cmd_build(const opts *o) {
    if (o->nfiles != 1) return usage_error("build takes one input file");
    if (!o->out) return usage_error("build needs -o OUT.pxm");
    if (is_pxm(o->files[0])) return usage_error("'%s' is already a .pxm model", o->files[0]);
    px_model *m = load_model(o->files[0], o->pieces < 0 ? PX_PIECES_PARTS : o->pieces, o->scale, o->tolerance,
                             o->threads);
    if (!m) return 1;
    px_error e;
    int rc = 0;
    if (px_model_save(m, o->out, &e) != PX_OK) {
        fprintf(stderr, "proxima: %s\n", e.message);
        rc = 1;
    } else {
        px_model_info in;
        px_model_get_info(m, &in);
        printf("%s: %u leaves (%s), %u nodes, largest h %.9g, %zu bytes in memory\n", o->out, in.leaves,
               pieces_name(in.pieces), in.nodes, in.max_h, in.memory_bytes);
    }
    px_model_destroy(m);
    return rc;
}

static int cmd_distance(const opts *o) {
    if (o->nfiles != 2) return usage_error("distance takes two files");
    int pieces = o->pieces < 0 ? PX_PIECES_TRIANGLES : o->pieces;
    px_model *a = load_model(o->files[0], pieces, o->scale, o->tolerance, o->threads);
    if (!a) return 1;
    px_model *b = load_model(o->files[1], pieces, o->scale, o->tolerance, o->threads);
    if (!b) {
        px_model_destroy(a);
        return 1;
    }
    px_model_distance_result r;
    px_model_collide_result c;
    px_status st = px_model_distance(a, &o->pose[0], b, &o->pose[1], NULL, &r);
    if (st == PX_OK) st = px_model_collide(a, &o->pose[0], b, &o->pose[1], NULL, &c);
    int rc = 0;
    if (st != PX_OK) {
        fprintf(stderr, "proxima: distance of '%s' and '%s': %s%s\n", o->files[0], o->files[1],
                px_status_string(st),
                st == PX_ERR_RANGE ? " (the poses place the models more than 2^250, about 1.8e75, "
                                     "apart)"
                                   : "");
        rc = 1;
    } else {
        printf("distance:    %.17g\n", r.distance);
        if (r.upper_bound > r.distance)
            printf("bracket:     [%.17g, %.17g] (the meshes' distance lies in it)\n", r.distance,
                   r.upper_bound);
        printf("point a:     %.17g %.17g %.17g (leaf %u)\n", r.point_a.x, r.point_a.y, r.point_a.z, r.leaf_a);
        printf("point b:     %.17g %.17g %.17g (leaf %u)\n", r.point_b.x, r.point_b.y, r.point_b.z, r.leaf_b);
        printf("collide:     %s\n",
               c.hit ? (c.contained ? "yes (one inside the other's solid)" : "yes") : "no");
        printf("work:        %u node pairs, %u leaf pairs\n", r.node_pairs, r.leaf_pairs);
    }
    px_model_destroy(a);
    px_model_destroy(b);
    return rc;
}

static int cmd_check(const opts *o) {
    if (o->nfiles != 1) return usage_error("check takes one assembly (a file or a folder)");
    if (o->out || o->has_pose) return usage_error("check takes no -o, --pose-a or --pose-b");
    check_opts c;
    memset(&c, 0, sizeof c);
    c.file = o->files[0];
    c.clearance = o->clearance;
    c.json = o->json;
    c.pieces = o->pieces < 0 ? PX_PIECES_TRIANGLES : (uint32_t)o->pieces;
    c.tolerance = o->tolerance;
    c.threads = o->threads;
    c.scale = o->scale;
    c.ignore = o->ignore;
    c.nignore = o->nignore;
    return check_run(&c);
}

int main(int argc, char **argv) {
    if (argc < 2 || !strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") || !strcmp(argv[1], "help")) {
        fputs(usage_text, argc < 2 ? stderr : stdout);
        return argc < 2 ? 2 : 0;
    }
    if (!strcmp(argv[1], "--version")) {
        printf("proxima %s\n", px_version_string());
        return 0;
    }
    opts o;
    const char **ignore = calloc((size_t)argc, sizeof *ignore);
    if (!ignore) {
        fprintf(stderr, "proxima: out of memory\n");
        return 2;
    }
    int rc = parse(argc, argv, 2, &o, ignore);
    if (!rc) {
        int check = !strcmp(argv[1], "check");
        if (!check && (o.has_clearance || o.json || o.nignore))
            rc = usage_error("--clearance, --json and --ignore are options of check");
        else if (check)
            rc = cmd_check(&o);
        else if (!strcmp(argv[1], "info"))
            rc = cmd_info(&o);
        else if (!strcmp(argv[1], "build"))
            rc = cmd_build(&o);
        else if (!strcmp(argv[1], "distance"))
            rc = cmd_distance(&o);
        else
            rc = usage_error("unknown command '%s' (info, build, distance, check)", argv[1]);
    }
    free(ignore);
    return rc;
}
