/* px_urdf: robots from URDF files (proxima/urdf.h).
 *
 * The XML is read by libxml2 from the bytes we read (at most 64 MiB, never
 * decompressed), with no network, and a file with a document type
 * declaration is refused as it is met: no entity can be declared, so a
 * file cannot make the reader fetch or expand anything. A pass over the
 * bytes first bounds what libxml2 is given (prescan: attributes per
 * element, markup in all, encodings), and libxml2 stops at its first
 * error. Namespace errors are refused too; elements in a prefixed
 * namespace (xacro:...) are not URDF's and are skipped, as ROS's parser
 * does. The whole load runs with the caller's floating-point traps held.
 * The robot description follows the URDF specification
 * (wiki.ros.org/urdf/XML): <link name> with <collision> elements (<origin
 * xyz rpy>, <geometry> of one <mesh filename scale>, <box size>, <cylinder
 * radius length> or <sphere radius>), and <joint name type> with <parent
 * link>, <child link>, <origin>, <axis xyz> (default 1 0 0) and <limit
 * lower upper velocity>. rpy is roll, pitch, yaw about the fixed axes X,
 * Y, Z: R = Rz(yaw) Ry(pitch) Rx(roll).
 *
 * Each link's collision elements become the parts of one mesh in the link
 * frame, and that mesh a model (px_model_create_from_mesh); the links,
 * ordered depth first from the root, a px_chain. */
#define _POSIX_C_SOURCE 200809L /* uselocale, open without blocking */

#include "proxima/urdf.h"

#include <errno.h>
#include <fcntl.h>
#include <fenv.h>
#include <limits.h>
#include <float.h>
#include <locale.h>
#include <libxml/parser.h>
#include <libxml/tree.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <threads.h>
#include <unistd.h>

#include "core/core.h"
#include "math/vec3.h"
#include "proxima/io.h"

#define U_MAX_ELEMENTS 65536u /* joints */
#define U_MAX_FILE (64ull << 20)
#define U_PATH 4096
/* The triangles of all the links together: a robot's collision
 * meshes are far smaller, and a file of a few kB could otherwise ask for
 * gigabytes of building (about 500 bytes a triangle are built: 2,000
 * spheres, 640,000 triangles, take 4 s and 300 MB). */
#define U_MAX_TRIANGLES 2000000ull
/* The models' coordinate range (proxima/model.h): a size is at most half
 * of it, so that a primitive's polyhedron (a sphere's reaches 1.9 % beyond
 * its radius) stays inside it, and then placed by an origin within it,
 * every coordinate is finite. */
#define U_MAX_COORD 0x1p250
#define U_MAX_SIZE 0x1p249

struct px_urdf {
    px_allocator alloc;
    px_chain *chain;
    uint32_t n, dof;
    char **link_name;  /* n, in chain order */
    char **joint_name; /* dof */
    px_model **model;  /* n */
};

/* ---- small helpers ---- */

/* An element of URDF's: in no namespace, or the default one (a prefixed
 * element such as <xacro:link> is another vocabulary's). */
static int urdf_element(const xmlNode *n) {
    return n->type == XML_ELEMENT_NODE && (!n->ns || !n->ns->prefix);
}

static int is_el(const xmlNode *n, const char *name) {
    return urdf_element(n) && strcmp((const char *)n->name, name) == 0;
}

static const xmlNode *child_el(const xmlNode *n, const char *name) {
    for (const xmlNode *c = n->children; c; c = c->next)
        if (is_el(c, name)) return c;
    return NULL;
}

static void free_str(const px_allocator *a, char *s) {
    if (s) pxi_free(a, s, strlen(s) + 1);
}

/* Exactly `count` finite decimal numbers separated by blanks (strtod in
 * the C locale, which px_urdf_load sets for its thread; no hexadecimal, as
 * ROS's parser reads none; a subnormal is read, an overflow is not). 1 on
 * success. */
static int numbers(const char *s, double *out, int count) {
    const char *p = s;
    for (int i = 0; i < count; ++i) {
        while (*p == ' ' || *p == '\t' || *p == '\n' || *p == '\r') ++p;
        const char *digits = p + (*p == '+' || *p == '-');
        if (digits[0] == '0' && (digits[1] == 'x' || digits[1] == 'X')) return 0;
        char *end;
        errno = 0;
        double v = strtod(p, &end);
        if (end == p || !isfinite(v) || (errno == ERANGE && fabs(v) > DBL_MIN)) return 0;
        if (*end && *end != ' ' && *end != '\t' && *end != '\n' && *end != '\r') return 0;
        out[i] = v;
        p = end;
    }
    while (*p == ' ' || *p == '\t' || *p == '\n' || *p == '\r') ++p;
    return *p == '\0';
}

/* URDF rpy: R = Rz(yaw) Ry(pitch) Rx(roll). */
static px_pose rpy_pose(const double xyz[3], const double rpy[3]) {
    double cr = cos(rpy[0]), sr = sin(rpy[0]), cp = cos(rpy[1]), sp = sin(rpy[1]), cy = cos(rpy[2]),
           sy = sin(rpy[2]);
    px_pose p;
    const double r[9] = {cy * cp,
                         cy * sp * sr - sy * cr,
                         cy * sp * cr + sy * sr,
                         sy * cp,
                         sy * sp * sr + cy * cr,
                         sy * sp * cr - cy * sr,
                         -sp,
                         cp * sr,
                         cp * cr};
    memcpy(p.r, r, sizeof r);
    p.t = (px_vec3){xyz[0], xyz[1], xyz[2]};
    return p;
}

/* The reading of one file: where errors go and what is being read. */
typedef struct ureader {
    const px_allocator *alloc;
    const char *path;
    px_error *err;
    int oom;      /* an allocation failed in attr() */
    int xml_line; /* libxml2's first error, or the DTD refused */
    char xml_message[160];
    int encoding_error; /* libxml2 met a byte its converter refused */
    size_t triangles;   /* the robot may still have */
} ureader;

#define U_FAIL(r, code, ...) pxi_error((r)->err, (code), __VA_ARGS__)

static px_status u_oom(ureader *r) {
    return U_FAIL(r, PX_ERR_OUT_OF_MEMORY, "URDF file '%s': out of memory", r->path);
}

static char *dup_str(const px_allocator *a, const char *s) {
    size_t len = strlen(s);
    char *d = pxi_alloc(a, len + 1);
    if (d) memcpy(d, s, len + 1);
    return d;
}

/* An attribute's value, copied with the robot's allocator: NULL when
 * absent, or with r->oom set when the copy could not be made. */
static char *attr(ureader *r, const xmlNode *n, const char *name) {
    xmlChar *v = xmlGetNoNsProp(n, (const xmlChar *)name);
    if (!v) return NULL;
    char *s = dup_str(r->alloc, (const char *)v);
    xmlFree(v);
    if (!s) r->oom = 1;
    return s;
}

/* An element's <origin> (identity when absent). */
static px_status read_origin(ureader *r, const xmlNode *n, const char *what, const char *name, px_pose *out) {
    *out = px_pose_identity();
    const xmlNode *o = child_el(n, "origin");
    if (!o) return PX_OK;
    double xyz[3] = {0, 0, 0}, rpy[3] = {0, 0, 0};
    const char *keys[2] = {"xyz", "rpy"};
    double *dst[2] = {xyz, rpy};
    for (int k = 0; k < 2; ++k) {
        xmlChar *v = xmlGetNoNsProp(o, (const xmlChar *)keys[k]);
        if (!v) continue;
        int ok = numbers((const char *)v, dst[k], 3);
        if (!ok) {
            px_status st = U_FAIL(
                r, PX_ERR_IO, "URDF file '%s': %s '%s': <origin %s=\"%.60s\"> is not three finite numbers",
                r->path, what, name, keys[k], (const char *)v);
            xmlFree(v);
            return st;
        }
        xmlFree(v);
    }
    *out = rpy_pose(xyz, rpy);
    return PX_OK;
}

/* ---- geometry: a growing soup of parts in the link frame ---- */

typedef struct soup {
    const px_allocator *alloc;
    size_t *budget; /* triangles the robot may still have */
    double *xyz;
    uint32_t *tri;
    px_mesh_part_desc *part;
    size_t nv, nt, np, cv, ct, cp;
} soup;

static int soup_grow(soup *s, size_t nv, size_t nt) {
    if (s->np + 1 > s->cp) {
        size_t c = s->cp ? 2 * s->cp : 8;
        px_mesh_part_desc *p = pxi_alloc_array(s->alloc, c, sizeof *p);
        if (!p) return 0;
        if (s->np) memcpy(p, s->part, s->np * sizeof *p);
        pxi_free(s->alloc, s->part, s->cp * sizeof *p);
        s->part = p, s->cp = c;
    }
    if (s->nv + nv > s->cv) {
        size_t c = s->cv ? s->cv : 64;
        while (c < s->nv + nv) c *= 2;
        double *x = pxi_alloc_array(s->alloc, c, 3 * sizeof *x);
        if (!x) return 0;
        if (s->nv) memcpy(x, s->xyz, s->nv * 3 * sizeof *x);
        pxi_free(s->alloc, s->xyz, s->cv * 3 * sizeof *x);
        s->xyz = x, s->cv = c;
    }
    if (s->nt + nt > s->ct) {
        size_t c = s->ct ? s->ct : 64;
        while (c < s->nt + nt) c *= 2;
        uint32_t *t = pxi_alloc_array(s->alloc, c, 3 * sizeof *t);
        if (!t) return 0;
        if (s->nt) memcpy(t, s->tri, s->nt * 3 * sizeof *t);
        pxi_free(s->alloc, s->tri, s->ct * 3 * sizeof *t);
        s->tri = t, s->ct = c;
    }
    return 1;
}

static void soup_free(soup *s) {
    pxi_free(s->alloc, s->xyz, s->cv * 3 * sizeof *s->xyz);
    pxi_free(s->alloc, s->tri, s->ct * 3 * sizeof *s->tri);
    pxi_free(s->alloc, s->part, s->cp * sizeof *s->part);
    memset(s, 0, sizeof *s);
}

/* Appends one part: nv points (scaled by `scale`, then placed by `pose`)
 * and nt triangles indexing them. */
static int soup_add(soup *s, const double *xyz, size_t nv, const uint32_t *tri, size_t nt,
                    const double scale[3], const px_pose *pose) {
    if (nt > *s->budget || nv > 3 * *s->budget + 8) return -1;
    if (!soup_grow(s, nv, nt)) return 0;
    *s->budget -= nt;
    for (size_t i = 0; i < nv; ++i) {
        px_vec3 p = {xyz[3 * i] * scale[0], xyz[3 * i + 1] * scale[1], xyz[3 * i + 2] * scale[2]};
        px_vec3 w = px_pose_apply(pose, p);
        double *d = s->xyz + 3 * (s->nv + i);
        d[0] = w.x, d[1] = w.y, d[2] = w.z;
    }
    for (size_t i = 0; i < 3 * nt; ++i) s->tri[3 * s->nt + i] = tri[i] + (uint32_t)s->nv;
    px_mesh_part_desc *p = &s->part[s->np++];
    memset(p, 0, sizeof *p);
    p->node = -1;
    p->first_vertex = (uint32_t)s->nv;
    p->vertex_count = (uint32_t)nv;
    p->first_triangle = (uint32_t)s->nt;
    p->triangle_count = (uint32_t)nt;
    s->nv += nv;
    s->nt += nt;
    return 1;
}

/* A convex polyhedron as points and outward triangles: the box
 * [-h, h]^3 scaled per axis, a prism or a sphere's. */
static const uint32_t box_tri[36] = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                                     2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};

#define U_SIDES 32
/* The prism of U_SIDES sides circumscribing the cylinder of radius r and
 * length l about z. */
static int add_cylinder(soup *s, double r, double l, const px_pose *pose) {
    double xyz[2 * U_SIDES * 3];
    uint32_t tri[(4 * U_SIDES - 4) * 3];
    const double pi = 3.14159265358979323846, R = r / cos(pi / U_SIDES);
    for (int i = 0; i < U_SIDES; ++i) {
        double a = 2 * pi * i / U_SIDES;
        for (int e = 0; e < 2; ++e) {
            double *p = xyz + 3 * (2 * i + e);
            p[0] = R * cos(a), p[1] = R * sin(a), p[2] = e ? 0.5 * l : -0.5 * l;
        }
    }
    size_t t = 0;
    for (int i = 0; i < U_SIDES; ++i) {
        uint32_t a0 = (uint32_t)(2 * i), a1 = a0 + 1, b0 = (uint32_t)(2 * ((i + 1) % U_SIDES)), b1 = b0 + 1;
        uint32_t side[6] = {a0, b0, a1, a1, b0, b1};
        memcpy(tri + 3 * t, side, sizeof side);
        t += 2;
    }
    for (int i = 1; i + 1 < U_SIDES; ++i) { /* fans: bottom (down), top (up) */
        uint32_t bot[3] = {0, (uint32_t)(2 * (i + 1)), (uint32_t)(2 * i)};
        uint32_t top[3] = {1, (uint32_t)(2 * i + 1), (uint32_t)(2 * (i + 1) + 1)};
        memcpy(tri + 3 * t++, bot, sizeof bot);
        memcpy(tri + 3 * t++, top, sizeof top);
    }
    const double one[3] = {1, 1, 1};
    return soup_add(s, xyz, 2 * U_SIDES, tri, t, one, pose);
}

/* The icosahedron subdivided twice (162 points, 320 faces), its points on
 * the unit sphere, then scaled so that every face lies at least r from the
 * centre: a polyhedron that contains the sphere. */
static int add_sphere(soup *s, double r, const px_pose *pose) {
    enum { NV = 162, NT = 320 };
    double v[NV * 3];
    uint32_t f[NT * 3], g[NT * 3];
    const double t = (1.0 + sqrt(5.0)) / 2.0;
    const double ico[36] = {-1, t,  0,  1, t, 0,  -1, -t, 0,  1, -t, 0, 0,  -1, t,  0,  1, t,
                            0,  -1, -t, 0, 1, -t, t,  0,  -1, t, 0,  1, -t, 0,  -1, -t, 0, 1};
    const uint32_t ifc[60] = {0, 11, 5,  0, 5,  1, 0, 1, 7, 0, 7,  10, 0, 10, 11, 1, 5, 9, 5, 11,
                              4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3,  9,  4, 3,  4,  2, 3, 2, 6, 3,
                              6, 8,  3,  8, 9,  4, 9, 5, 2, 4, 11, 6,  2, 10, 8,  6, 7, 9, 8, 1};
    size_t nv = 12, nf = 20;
    for (size_t i = 0; i < 12; ++i) {
        double n =
            sqrt(ico[3 * i] * ico[3 * i] + ico[3 * i + 1] * ico[3 * i + 1] + ico[3 * i + 2] * ico[3 * i + 2]);
        for (int k = 0; k < 3; ++k) v[3 * i + k] = ico[3 * i + k] / n;
    }
    memcpy(f, ifc, sizeof ifc);
    for (int level = 0; level < 2; ++level) {
        /* Split each edge once: the midpoint of an edge found by a search
         * over the points made at this level (small). */
        size_t first_new = nv, ng = 0;
        for (size_t k = 0; k < nf; ++k) {
            uint32_t c[3] = {f[3 * k], f[3 * k + 1], f[3 * k + 2]}, m[3];
            for (int e = 0; e < 3; ++e) {
                uint32_t a = c[e], b = c[(e + 1) % 3];
                double p[3], n = 0;
                for (int q = 0; q < 3; ++q) p[q] = 0.5 * (v[3 * a + q] + v[3 * b + q]), n += p[q] * p[q];
                n = sqrt(n);
                for (int q = 0; q < 3; ++q) p[q] /= n;
                size_t j = first_new;
                for (; j < nv; ++j)
                    if (v[3 * j] == p[0] && v[3 * j + 1] == p[1] && v[3 * j + 2] == p[2]) break;
                if (j == nv) memcpy(v + 3 * nv++, p, sizeof p);
                m[e] = (uint32_t)j;
            }
            const uint32_t sub[12] = {c[0], m[0], m[2], c[1], m[1], m[0], c[2], m[2], m[1], m[0], m[1], m[2]};
            memcpy(g + 3 * ng, sub, sizeof sub);
            ng += 4;
        }
        nf = ng;
        memcpy(f, g, nf * 3 * sizeof *f);
    }
    /* The nearest face plane to the centre. */
    double inr = 1.0;
    for (size_t k = 0; k < nf; ++k) {
        const double *a = v + 3 * f[3 * k], *b = v + 3 * f[3 * k + 1], *c = v + 3 * f[3 * k + 2];
        double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
        double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        double d = (n[0] * a[0] + n[1] * a[1] + n[2] * a[2]) / len;
        if (d < inr) inr = d;
    }
    /* Scaled a little beyond r / inr: the rounding of the points. */
    double k = r / inr * (1.0 + 1e-12);
    const double scale[3] = {k, k, k};
    return soup_add(s, v, nv, f, nf, scale, pose);
}

/* Resolves a mesh file name to a path; 1 when found. */
static int resolve(const ureader *r, const char *name, const char *package_path, char *out, size_t size) {
    struct stat sb;
    char dir[U_PATH];
    if ((size_t)snprintf(dir, sizeof dir, "%s", r->path) >= sizeof dir) return 0;
    char *slash = strrchr(dir, '/');
    if (slash)
        *slash = '\0';
    else
        snprintf(dir, sizeof dir, ".");
    if (strncmp(name, "package://", 10) == 0) {
        const char *rest = name + 10;
        /* package://PACKAGE/PATH: without a package it names nothing. */
        const char *sep = strchr(rest, '/');
        if (!sep || sep == rest || !sep[1]) return 0;
        /* The folders of package_path, then the URDF file's folder and
         * each parent: DIR/NAME/rest. */
        if (package_path) {
            const char *p = package_path;
            while (*p) {
                const char *e = strchr(p, ':');
                size_t len = e ? (size_t)(e - p) : strlen(p);
                if (len > 0 && len < U_PATH) {
                    if ((size_t)snprintf(out, size, "%.*s/%s", (int)len, p, rest) < size &&
                        stat(out, &sb) == 0 && S_ISREG(sb.st_mode))
                        return 1;
                }
                p += len + (e ? 1 : 0);
            }
        }
        char up[U_PATH];
        snprintf(up, sizeof up, "%s", dir);
        for (int depth = 0; depth < 64; ++depth) {
            if ((size_t)snprintf(out, size, "%s/%s", up, rest) < size && stat(out, &sb) == 0 &&
                S_ISREG(sb.st_mode))
                return 1;
            size_t l = strlen(up);
            if (l + 4 >= sizeof up) break;
            strcat(up, "/..");
        }
        return 0;
    }
    if (strncmp(name, "file://", 7) == 0) name += 7;
    int n =
        name[0] == '/' || !slash ? snprintf(out, size, "%s", name) : snprintf(out, size, "%s/%s", dir, name);
    if (n < 0 || (size_t)n >= size) return 0; /* too long: not some other, shorter path */
    return stat(out, &sb) == 0 && S_ISREG(sb.st_mode);
}

/* One <collision> element into the soup. */
static px_status read_collision(ureader *r, const xmlNode *col, const char *link, const px_urdf_options *o,
                                soup *s) {
    px_pose pose;
    px_status st = read_origin(r, col, "link", link, &pose);
    if (st != PX_OK) return st;
    if (!(pxi_max_abs(pose.t) <= U_MAX_COORD))
        return U_FAIL(r, PX_ERR_RANGE,
                      "URDF file '%s': link '%.80s': a <collision> origin (%g %g %g) is beyond the models' "
                      "range 2^250",
                      r->path, link, pose.t.x, pose.t.y, pose.t.z);
    const xmlNode *geo = child_el(col, "geometry"), *g = NULL;
    if (geo)
        for (const xmlNode *c = geo->children; c && !g; c = c->next)
            if (urdf_element(c)) g = c;
    if (!g)
        return U_FAIL(r, PX_ERR_IO, "URDF file '%s': link '%.80s': a <collision> without a <geometry> shape",
                      r->path, link);
    const char *kind = (const char *)g->name;
    const char *keys[3] = {NULL, NULL, NULL};
    int counts[3] = {0, 0, 0};
    if (strcmp(kind, "box") == 0)
        keys[0] = "size", counts[0] = 3;
    else if (strcmp(kind, "cylinder") == 0)
        keys[0] = "radius", counts[0] = 1, keys[1] = "length", counts[1] = 1;
    else if (strcmp(kind, "sphere") == 0)
        keys[0] = "radius", counts[0] = 1;
    else if (strcmp(kind, "mesh") == 0)
        keys[0] = "filename", counts[0] = 0, keys[1] = "scale", counts[1] = -3;
    else
        return U_FAIL(r, PX_ERR_IO, "URDF file '%s': link '%.80s': unknown geometry <%.40s>", r->path, link,
                      kind);
    double val[2][3] = {{1, 1, 1}, {1, 1, 1}};
    char *filename = NULL;
    for (int k = 0; k < 2 && keys[k]; ++k) {
        xmlChar *v = xmlGetNoNsProp(g, (const xmlChar *)keys[k]);
        if (!v) {
            if (counts[k] < 0) continue; /* optional (mesh scale) */
            return U_FAIL(r, PX_ERR_IO, "URDF file '%s': link '%.80s': <%s> without its %s", r->path, link,
                          kind, keys[k]);
        }
        if (counts[k] == 0) {
            filename = dup_str(r->alloc, (const char *)v);
            xmlFree(v);
            if (!filename) return u_oom(r);
            continue;
        }
        int n = counts[k] < 0 ? -counts[k] : counts[k];
        int ok = numbers((const char *)v, val[k], n);
        if (ok && counts[k] > 0)
            for (int i = 0; i < n; ++i) ok &= val[k][i] > 0;
        if (ok && counts[k] < 0)
            for (int i = 0; i < n; ++i) ok &= val[k][i] != 0;
        if (!ok) {
            st = U_FAIL(r, PX_ERR_IO,
                        "URDF file '%s': link '%.80s': <%s %s=\"%.60s\"> is not %d finite %s number%s",
                        r->path, link, kind, keys[k], (const char *)v, n,
                        counts[k] > 0 ? "positive" : "non-zero", n > 1 ? "s" : "");
            xmlFree(v);
            free_str(r->alloc, filename);
            return st;
        }
        xmlFree(v);
        /* Finite sizes may still be too large: a radius of 1.79e308 would
         * make infinite points. */
        for (int i = 0; i < n && counts[k] > 0; ++i)
            if (!(val[k][i] <= U_MAX_SIZE))
                return U_FAIL(r, PX_ERR_RANGE,
                              "URDF file '%s': link '%.80s': %s %s %g is too large (above 2^249: a model's "
                              "coordinates stay within 2^250)",
                              r->path, link, kind, keys[k], val[k][i]);
    }
    int ok = 1;
    if (strcmp(kind, "box") == 0) {
        double xyz[24];
        for (int i = 0; i < 8; ++i)
            for (int q = 0; q < 3; ++q) xyz[3 * i + q] = ((i >> q) & 1 ? 0.5 : -0.5) * val[0][q];
        const double one[3] = {1, 1, 1};
        ok = soup_add(s, xyz, 8, box_tri, 12, one, &pose);
    } else if (strcmp(kind, "cylinder") == 0) {
        ok = add_cylinder(s, val[0][0], val[1][0], &pose);
    } else if (strcmp(kind, "sphere") == 0) {
        ok = add_sphere(s, val[0][0], &pose);
    } else {
        char file[U_PATH];
        if (!resolve(r, filename, o->package_path, file, sizeof file)) {
            st = U_FAIL(r, PX_ERR_IO,
                        "URDF file '%s': link '%.80s': mesh file not found (or not a regular file): '%.200s'",
                        r->path, link, filename);
            free_str(r->alloc, filename);
            return st;
        }
        free_str(r->alloc, filename);
        px_mesh_options mo;
        memset(&mo, 0, sizeof mo);
        mo.allocator = r->alloc;
        px_error e;
        px_mesh *m = px_mesh_load(file, &mo, &e);
        if (!m) return U_FAIL(r, e.code, "URDF file '%s': link '%.80s': %s", r->path, link, e.message);
        /* Every part of the file, each a part here, if the scale keeps
         * them within the models' range (a scale of 1e308 would make
         * infinite points). */
        const double *xyz = px_mesh_vertices(m);
        const uint32_t *tri = px_mesh_triangles(m);
        uint32_t np = px_mesh_part_count(m);
        double reach = 0;
        for (size_t i = 0; i < 3 * (size_t)px_mesh_vertex_count(m); ++i)
            reach = fmax(reach, fabs(xyz[i] * val[1][i % 3]));
        if (!(reach <= U_MAX_COORD)) {
            px_mesh_destroy(m);
            return U_FAIL(r, PX_ERR_RANGE,
                          "URDF file '%s': link '%.80s': the mesh scaled by %g %g %g reaches %g, beyond the "
                          "models' range 2^250",
                          r->path, link, val[1][0], val[1][1], val[1][2], reach);
        }
        for (uint32_t i = 0; i < np && ok == 1; ++i) {
            px_mesh_part p;
            px_mesh_get_part(m, i, &p);
            /* Indices relative to the part's first vertex. */
            uint32_t *local = pxi_alloc_array(r->alloc, (size_t)p.triangle_count * 3 + 1, sizeof *local);
            if (!local) {
                ok = 0;
                break;
            }
            for (size_t t = 0; t < (size_t)p.triangle_count * 3; ++t)
                local[t] = tri[3 * (size_t)p.first_triangle + t] - p.first_vertex;
            ok = soup_add(s, xyz + 3 * (size_t)p.first_vertex, p.vertex_count, local, p.triangle_count,
                          val[1], &pose);
            pxi_free(r->alloc, local, ((size_t)p.triangle_count * 3 + 1) * sizeof *local);
        }
        px_mesh_destroy(m);
    }
    if (ok < 0)
        return U_FAIL(
            r, PX_ERR_IO,
            "URDF file '%s': link '%.80s': the robot's collision geometry is more than %llu triangles "
            "(spheres are 320 and cylinders 124 each)",
            r->path, link, U_MAX_TRIANGLES);
    if (!ok)
        return U_FAIL(r, PX_ERR_OUT_OF_MEMORY, "URDF file '%s': link '%.80s': out of memory", r->path, link);
    return PX_OK;
}

/* ---- the robot ---- */

typedef struct ujoint {
    const xmlNode *node;
    char *name, *parent, *child;
    uint32_t type; /* px_joint_type */
    int continuous;
    uint32_t p, c; /* link indices (file order) */
} ujoint;

typedef struct ulink {
    const xmlNode *node;
    char *name;
    uint32_t parent_joint;              /* UINT32_MAX: none */
    uint32_t first_child, next_sibling; /* joints, in file order */
} ulink;

static int cmp_name(const void *x, const void *y) {
    const char *const *a = x, *const *b = y;
    return strcmp(*a, *b);
}

/* The file-order index of the link named `name` (sorted: (name, index)
 * pairs), or UINT32_MAX. */
typedef struct uname {
    const char *name;
    uint32_t index;
} uname;

static uint32_t find_name(const uname *v, uint32_t n, const char *name) {
    uint32_t lo = 0, hi = n;
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        int c = strcmp(v[mid].name, name);
        if (c == 0) return v[mid].index;
        if (c < 0)
            lo = mid + 1;
        else
            hi = mid;
    }
    return UINT32_MAX;
}

void px_urdf_destroy(px_urdf *u) {
    if (!u) return;
    px_allocator a = u->alloc;
    px_chain_destroy(u->chain);
    for (uint32_t k = 0; u->link_name && k < u->n; ++k) free_str(&a, u->link_name[k]);
    for (uint32_t k = 0; u->joint_name && k < u->dof; ++k) free_str(&a, u->joint_name[k]);
    for (uint32_t k = 0; u->model && k < u->n; ++k) px_model_destroy(u->model[k]);
    pxi_free(&a, u->link_name, (size_t)u->n * sizeof *u->link_name);
    pxi_free(&a, u->joint_name, (size_t)u->n * sizeof *u->joint_name);
    pxi_free(&a, u->model, (size_t)u->n * sizeof *u->model);
    pxi_free(&a, u, sizeof *u);
}

const px_chain *px_urdf_chain(const px_urdf *u) { return u ? u->chain : NULL; }
const char *px_urdf_link_name(const px_urdf *u, uint32_t k) { return u && k < u->n ? u->link_name[k] : NULL; }
const char *px_urdf_joint_name(const px_urdf *u, uint32_t i) {
    return u && i < u->dof ? u->joint_name[i] : NULL;
}
const px_model *px_urdf_link_model(const px_urdf *u, uint32_t k) {
    return u && k < u->n ? u->model[k] : NULL;
}
uint32_t px_urdf_find_link(const px_urdf *u, const char *name) {
    if (!u || !name) return PX_CHAIN_ROOT;
    for (uint32_t k = 0; k < u->n; ++k)
        if (strcmp(u->link_name[k], name) == 0) return k;
    return PX_CHAIN_ROOT;
}

/* A joint's type, limits and axis into a link description. */
static px_status read_joint(ureader *r, const ujoint *j, px_link_desc *d) {
    px_status st = read_origin(r, j->node, "joint", j->name, &d->origin);
    if (st != PX_OK) return st;
    d->joint = j->type;
    if (j->type == PX_JOINT_FIXED) return PX_OK;
    double axis[3] = {1, 0, 0};
    const xmlNode *ax = child_el(j->node, "axis");
    if (ax) {
        xmlChar *v = xmlGetNoNsProp(ax, (const xmlChar *)"xyz");
        if (v) {
            int ok = numbers((const char *)v, axis, 3) && (axis[0] != 0 || axis[1] != 0 || axis[2] != 0);
            if (!ok) {
                st = U_FAIL(r, PX_ERR_IO,
                            "URDF file '%s': joint '%.80s': <axis xyz=\"%.60s\"> is not a non-zero vector",
                            r->path, j->name, (const char *)v);
                xmlFree(v);
                return st;
            }
            xmlFree(v);
        }
    }
    d->axis = (px_vec3){axis[0], axis[1], axis[2]};
    /* URDF: revolute and prismatic joints need <limit>, whose lower and
     * upper default to 0; a continuous joint has no position limits. */
    const xmlNode *lim = child_el(j->node, "limit");
    if (!lim && !j->continuous)
        return U_FAIL(r, PX_ERR_IO, "URDF file '%s': joint '%.80s': a %s joint without <limit>", r->path,
                      j->name, j->type == PX_JOINT_PRISMATIC ? "prismatic" : "revolute");
    d->q_min = j->continuous ? -INFINITY : 0.0;
    d->q_max = j->continuous ? INFINITY : 0.0;
    d->max_speed = INFINITY;
    const char *keys[3] = {"lower", "upper", "velocity"};
    double *dst[3] = {&d->q_min, &d->q_max, &d->max_speed};
    for (int k = 0; lim && k < 3; ++k) {
        xmlChar *v = xmlGetNoNsProp(lim, (const xmlChar *)keys[k]);
        if (!v) continue;
        double x;
        int ok = numbers((const char *)v, &x, 1) && (k < 2 || x >= 0);
        if (!ok) {
            st = U_FAIL(r, PX_ERR_IO,
                        "URDF file '%s': joint '%.80s': <limit %s=\"%.60s\"> is not a finite number%s",
                        r->path, j->name, keys[k], (const char *)v, k == 2 ? " >= 0" : "");
            xmlFree(v);
            return st;
        }
        xmlFree(v);
        if (k < 2 && j->continuous) continue;
        *dst[k] = x;
    }
    if (d->q_min > d->q_max)
        return U_FAIL(r, PX_ERR_IO,
                      "URDF file '%s': joint '%.80s': <limit lower=\"%g\" upper=\"%g\"> is empty", r->path,
                      j->name, d->q_min, d->q_max);
    return PX_OK;
}

/* A joint's <mimic joint multiplier offset> (multiplier 1 and offset 0 by
 * default): the link of the joint it follows into d (chain indices), or
 * nothing when it has none. The followed joint must exist; px_chain_create
 * checks that it is movable and follows none. */
static px_status read_mimic(ureader *r, const ujoint *j, const ujoint *joint, const uname *jnames,
                            uint32_t nj, const uint32_t *chain_of, px_link_desc *d) {
    const xmlNode *m = child_el(j->node, "mimic");
    if (!m || j->type == PX_JOINT_FIXED) return PX_OK; /* urdfdom ignores it on fixed joints too */
    xmlChar *name = xmlGetNoNsProp(m, (const xmlChar *)"joint");
    if (!name)
        return U_FAIL(r, PX_ERR_IO, "URDF file '%s': joint '%.80s': <mimic> without a joint", r->path,
                      j->name);
    uint32_t i = find_name(jnames, nj, (const char *)name);
    if (i == UINT32_MAX) {
        px_status st =
            U_FAIL(r, PX_ERR_IO, "URDF file '%s': joint '%.80s': <mimic joint=\"%.80s\">: no such joint",
                   r->path, j->name, (const char *)name);
        xmlFree(name);
        return st;
    }
    xmlFree(name);
    double v[2] = {1.0, 0.0};
    const char *keys[2] = {"multiplier", "offset"};
    for (int k = 0; k < 2; ++k) {
        xmlChar *x = xmlGetNoNsProp(m, (const xmlChar *)keys[k]);
        if (!x) continue;
        int ok = numbers((const char *)x, &v[k], 1);
        if (!ok) {
            px_status st = U_FAIL(
                r, PX_ERR_IO, "URDF file '%s': joint '%.80s': <mimic %s=\"%.60s\"> is not a finite number",
                r->path, j->name, keys[k], (const char *)x);
            xmlFree(x);
            return st;
        }
        xmlFree(x);
    }
    d->mimic = 1;
    d->mimic_link = chain_of[joint[i].c];
    d->mimic_multiplier = v[0];
    d->mimic_offset = v[1];
    return PX_OK;
}

static once_flag u_xml_once = ONCE_FLAG_INIT;
/* libxml2's set-up computes NaN and infinities (xmlXPathInit: 0.0 / 0.0):
 * it runs inside px_urdf_load, with the caller's traps held. */
static void u_xml_init(void) { xmlInitParser(); }

/* A link's collision elements as one model (NULL, PX_OK when it has none). */
static px_status link_model(ureader *r, const ulink *l, const px_urdf_options *o, px_model **out) {
    *out = NULL;
    soup s;
    memset(&s, 0, sizeof s);
    s.alloc = r->alloc;
    s.budget = &r->triangles;
    px_status st = PX_OK;
    for (const xmlNode *c = l->node->children; c && st == PX_OK; c = c->next)
        if (is_el(c, "collision")) st = read_collision(r, c, l->name, o, &s);
    if (st == PX_OK && s.np > 0) {
        px_mesh_desc md;
        memset(&md, 0, sizeof md);
        md.xyz = s.xyz;
        md.vertex_count = s.nv;
        md.triangles = s.tri;
        md.triangle_count = s.nt;
        md.parts = s.part;
        md.part_count = (uint32_t)s.np;
        px_mesh_options mo;
        memset(&mo, 0, sizeof mo);
        mo.allocator = r->alloc;
        px_error e;
        px_mesh *m = px_mesh_create(&md, &mo, &e);
        if (!m) {
            st = U_FAIL(r, e.code, "URDF file '%s': link '%.80s': %s", r->path, l->name, e.message);
        } else {
            px_model_options mopt;
            memset(&mopt, 0, sizeof mopt);
            mopt.allocator = r->alloc;
            mopt.pieces = o->pieces ? o->pieces : PX_PIECES_TRIANGLES;
            mopt.threads = o->threads;
            mopt.tolerance = o->tolerance;
            *out = px_model_create_from_mesh(m, &mopt, &e);
            if (!*out)
                st = U_FAIL(r, e.code, "URDF file '%s': link '%.80s': %s", r->path, l->name, e.message);
            px_mesh_destroy(m);
        }
    }
    soup_free(&s);
    return st;
}

/* The whole file into `*bytes` (NUL-terminated, size + 1 bytes from the
 * robot's allocator): a regular file of at most 64 MiB, opened without
 * blocking (a FIFO is refused, not waited on). */
static px_status read_file(ureader *r, unsigned char **bytes, size_t *size) {
    *bytes = NULL;
    int fd = open(r->path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) return U_FAIL(r, PX_ERR_IO, "cannot open URDF file '%s': %s", r->path, strerror(errno));
    struct stat sb;
    px_status st = PX_OK;
    if (fstat(fd, &sb) != 0 || !S_ISREG(sb.st_mode))
        st = U_FAIL(r, PX_ERR_IO, "URDF file '%s' is not a regular file", r->path);
    else if ((unsigned long long)sb.st_size > U_MAX_FILE)
        st = U_FAIL(r, PX_ERR_IO, "URDF file '%s' is larger than 64 MiB", r->path);
    size_t n = st == PX_OK ? (size_t)sb.st_size : 0, got = 0;
    unsigned char *b = st == PX_OK ? pxi_alloc(r->alloc, n + 1) : NULL;
    if (st == PX_OK && !b) st = u_oom(r);
    while (st == PX_OK && got < n) {
        ssize_t k = read(fd, b + got, n - got);
        if (k < 0 && errno == EINTR) continue;
        if (k < 0)
            st = U_FAIL(r, PX_ERR_IO, "URDF file '%s': read error: %s", r->path, strerror(errno));
        else if (k == 0)
            st = U_FAIL(r, PX_ERR_IO, "URDF file '%s' became shorter while it was read", r->path);
        else
            got += (size_t)k;
    }
    close(fd);
    if (st != PX_OK) {
        if (b) pxi_free(r->alloc, b, n + 1);
        return st;
    }
    b[n] = '\0';
    *bytes = b;
    *size = n;
    return PX_OK;
}

/* libxml2's errors: the first one kept for the message, none printed, and
 * the parse stopped there (libxml2 would go on to the end of a file it
 * already refuses: prescan's bounds hold for what it reads as XML, and a
 * broken file may be read otherwise past the break). Warnings (a
 * namespace URI that is not absolute, XML 1.1) refuse nothing: ROS reads
 * those files. */
static void xml_error(void *data, xmlErrorPtr e) {
    xmlParserCtxtPtr ctxt = data;
    ureader *r = ctxt->_private;
    if (!e || e->level < XML_ERR_ERROR) return;
    if (!r->xml_message[0]) {
        r->xml_line = e->line;
        snprintf(r->xml_message, sizeof r->xml_message, "%s",
                 e->message ? e->message : "not well-formed XML");
        size_t l = strlen(r->xml_message);
        while (l && (r->xml_message[l - 1] == '\n' || r->xml_message[l - 1] == ' '))
            r->xml_message[--l] = '\0';
    }
    xmlStopParser(ctxt);
}

/* Errors libxml2 raises without a parser context (its encoding
 * converters): noted, never printed. */
static void xml_generic_error(void *data, const char *msg, ...) {
    ureader *r = data;
    if (msg && strstr(msg, "encod")) r->encoding_error = 1;
}

static void xml_structured_error(void *data, xmlErrorPtr e) {
    ureader *r = data;
    if (e && (e->domain == XML_FROM_I18N || e->domain == XML_FROM_IO)) r->encoding_error = 1;
}

/* A document type declaration stops the parse before any of it is used. */
static void xml_doctype(void *data, const xmlChar *name, const xmlChar *external_id,
                        const xmlChar *system_id) {
    (void)name, (void)external_id, (void)system_id;
    xmlParserCtxtPtr ctxt = data;
    ureader *r = ctxt->_private;
    if (!r->xml_message[0]) {
        r->xml_line = xmlSAX2GetLineNumber(ctxt);
        snprintf(r->xml_message, sizeof r->xml_message,
                 "a document type declaration (<!DOCTYPE>) is not accepted: URDF has none, and it could "
                 "declare entities");
    }
    xmlStopParser(ctxt);
}

/* ---- a linear pass over the bytes before libxml2 reads them ----
 *
 * libxml2 2.9 checks a start tag's attributes for duplicates pair by pair
 * (200,000 attributes, 2 MB, take minutes), and builds about 300 bytes of
 * tree for each element, attribute, comment or processing instruction
 * (64 MiB of "<a/> " would take 3.4 GB). This pass counts them as libxml2
 * will read them and refuses more than U_MAX_ATTRIBUTES in one start tag
 * or U_MAX_MARKUP in all; it also bounds the namespace declarations
 * (libxml2 looks each prefix up through every one in scope) and the
 * nesting depth (libxml2 parses with XML_PARSE_HUGE, which lifts its own). It skips what libxml2 does not
 * read as markup: comments (to the first "-->"), CDATA sections ("]]>"), processing instructions and the XML
 * declaration ("?>"), and quoted attribute values. Where a file breaks XML's rules (an unterminated comment,
 * a '<' inside a value, a name it would not read) libxml2 reports an error and xml_error stops it there, so
 * the pass need only follow well-formed XML and count at least as much as libxml2 reads of the rest. It also
 * needs the bytes to be ASCII's for ASCII: a NUL byte (UTF-16, UTF-32), EBCDIC and declared encodings other
 * than UTF-8, ASCII, ISO-8859-n and windows-125n are refused. */
#define U_MAX_ATTRIBUTES 64
#define U_MAX_NAMESPACES 128
#define U_MAX_DEPTH 128
#define U_MAX_MARKUP 1000000u

static int u_blank(unsigned char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

static int u_starts(const unsigned char *b, size_t n, size_t i, const char *s) {
    size_t k = strlen(s);
    return i + k <= n && memcmp(b + i, s, k) == 0;
}

/* The first `s` at or after b[i], or n. */
static size_t u_find(const unsigned char *b, size_t n, size_t i, const char *s) {
    for (; i < n; ++i)
        if (b[i] == (unsigned char)s[0] && u_starts(b, n, i, s)) return i;
    return n;
}

/* The line of b[at]. */
static int u_line(const unsigned char *b, size_t at) {
    int line = 1;
    for (size_t i = 0; i < at; ++i) line += b[i] == '\n';
    return line;
}

/* The encodings whose bytes below 0x80 are ASCII's, as libxml2 (iconv)
 * names them: UTF-8, ASCII, ISO-8859-n and the Windows code pages 125n
 * (latin1 is ISO-8859-1's alias). */
static int u_ascii_encoding(const unsigned char *s, size_t len) {
    static const char *const names[] = {"UTF-8", "UTF8", "US-ASCII", "ASCII", "LATIN1"};
    for (size_t i = 0; i < sizeof names / sizeof *names; ++i)
        if (len == strlen(names[i]) && strncasecmp((const char *)s, names[i], len) == 0) return 1;
    /* A prefix and one or two digits. */
    static const char *const prefixes[] = {"ISO-8859-", "ISO8859-", "ISO_8859-", "WINDOWS-125", "CP125"};
    for (size_t i = 0; i < sizeof prefixes / sizeof *prefixes; ++i) {
        size_t k = strlen(prefixes[i]);
        if (len <= k || len > k + 2 || strncasecmp((const char *)s, prefixes[i], k) != 0) continue;
        for (size_t j = k; j < len; ++j)
            if (s[j] < '0' || s[j] > '9') return 0;
        return 1;
    }
    return 0;
}

static px_status prescan(ureader *r, const unsigned char *b, size_t n) {
    const unsigned char *nul = memchr(b, '\0', n);
    if (nul)
        return U_FAIL(r, PX_ERR_IO,
                      "URDF file '%s': line %d: a NUL byte (URDF files are UTF-8; UTF-16 and UTF-32 are not "
                      "read)",
                      r->path, u_line(b, (size_t)(nul - b)));
    if (u_starts(b, n, 0, "\x4c\x6f\xa7\x94"))
        return U_FAIL(r, PX_ERR_IO, "URDF file '%s': EBCDIC is not read (URDF files are UTF-8)", r->path);
    /* The XML declaration's encoding: any `encoding = "NAME"` in it. */
    size_t s = u_starts(b, n, 0, "\xef\xbb\xbf") ? 3 : 0;
    if (u_starts(b, n, s, "<?xml") && s + 5 < n && u_blank(b[s + 5])) {
        size_t end = u_find(b, n, s, "?>");
        for (size_t i = u_find(b, end, s, "encoding"); i < end; i = u_find(b, end, i + 1, "encoding")) {
            size_t j = i + 8;
            while (j < end && u_blank(b[j])) ++j;
            if (j >= end || b[j] != '=') continue;
            for (++j; j < end && u_blank(b[j]); ++j) {
            }
            if (j >= end || (b[j] != '"' && b[j] != '\'')) continue;
            size_t k = j + 1;
            while (k < end && b[k] != b[j]) ++k;
            if (!u_ascii_encoding(b + j + 1, k - j - 1))
                return U_FAIL(r, PX_ERR_IO,
                              "URDF file '%s': line %d: encoding '%.*s' is not read (UTF-8, ASCII, "
                              "ISO-8859-n and windows-125n are)",
                              r->path, u_line(b, i), (int)(k - j - 1 < 40 ? k - j - 1 : 40), b + j + 1);
        }
    }
    size_t markup = 0, namespaces = 0, depth = 0;
    for (size_t i = 0; i < n;) {
        if (b[i] != '<') {
            ++i;
            continue;
        }
        if (u_starts(b, n, i, "<!--")) {
            i = u_find(b, n, i + 4, "-->") + 3;
        } else if (u_starts(b, n, i, "<![CDATA[")) {
            i = u_find(b, n, i + 9, "]]>") + 3;
        } else if (u_starts(b, n, i, "<?")) {
            i = u_find(b, n, i + 2, "?>") + 2;
        } else if (u_starts(b, n, i, "<!")) {
            /* libxml2 stops here: a document type declaration is refused
             * as it is met, anything else is an error. */
            return PX_OK;
        } else if (u_starts(b, n, i, "</")) {
            i += 2;
            depth -= depth > 0;
            continue; /* an end tag: a name, no attributes */
        } else {
            /* A start tag: its name, then `name = "value"` pairs. */
            size_t at = i, j = i + 1, attributes = 0;
            while (j < n && !u_blank(b[j]) && b[j] != '>' && b[j] != '/' && b[j] != '<') ++j;
            for (;;) {
                while (j < n && u_blank(b[j])) ++j;
                size_t k = j;
                while (k < n && !u_blank(b[k]) && !strchr("=>/<\"'", b[k])) ++k;
                if (k == j) break; /* the tag's end, or not an attribute: libxml2 stops */
                /* libxml2 looks each prefix up through every namespace
                 * declaration in scope: their number bounds a look-up. */
                int is_xmlns =
                    k - j >= 5 && memcmp(b + j, "xmlns", 5) == 0 && (k - j == 5 || b[j + 5] == ':');
                while (k < n && u_blank(b[k])) ++k;
                if (k >= n || b[k] != '=') break;
                for (++k; k < n && u_blank(b[k]); ++k) {
                }
                if (k >= n || (b[k] != '"' && b[k] != '\'')) break;
                size_t v = k + 1;
                while (v < n && b[v] != b[k] && b[v] != '<') ++v;
                if (v >= n || b[v] == '<') { /* not a value: libxml2 stops */
                    j = v;
                    break;
                }
                j = v + 1;
                if (is_xmlns && ++namespaces > U_MAX_NAMESPACES)
                    return U_FAIL(r, PX_ERR_IO,
                                  "URDF file '%s': line %d: more than %d namespace declarations (xmlns)",
                                  r->path, u_line(b, at), U_MAX_NAMESPACES);
                if (++attributes > U_MAX_ATTRIBUTES)
                    return U_FAIL(r, PX_ERR_IO,
                                  "URDF file '%s': line %d: an element with more than %d attributes", r->path,
                                  u_line(b, at), U_MAX_ATTRIBUTES);
                markup++;
            }
            /* Not closed by "/>": its content is one level deeper. */
            if (!(j < n && b[j] == '/') && ++depth > U_MAX_DEPTH)
                return U_FAIL(r, PX_ERR_IO, "URDF file '%s': line %d: elements nested more than %d deep",
                              r->path, u_line(b, at), U_MAX_DEPTH);
            i = j;
        }
        if (++markup > U_MAX_MARKUP)
            return U_FAIL(r, PX_ERR_IO,
                          "URDF file '%s': line %d: more than %u elements, attributes, comments and "
                          "processing instructions",
                          r->path, u_line(b, i < n ? i : n), U_MAX_MARKUP);
    }
    return PX_OK;
}

/* The document, or NULL with the error set. */
static xmlDoc *parse_xml(ureader *r, const unsigned char *bytes, size_t size) {
    if (size > INT_MAX) return U_FAIL(r, PX_ERR_IO, "URDF file '%s' is too large", r->path), (xmlDoc *)NULL;
    if (prescan(r, bytes, size) != PX_OK) return NULL;
    xmlParserCtxtPtr ctxt = xmlNewParserCtxt();
    if (!ctxt || !ctxt->sax) {
        xmlFreeParserCtxt(ctxt);
        return u_oom(r), (xmlDoc *)NULL;
    }
    ctxt->_private = r;
    ctxt->sax->serror = xml_error;
    ctxt->sax->internalSubset = xml_doctype;
    ctxt->sax->externalSubset = xml_doctype;
    /* This thread's handlers for the errors raised without the context
     * (libxml2 keeps them per thread), restored after the parse. */
    xmlGenericErrorFunc generic = xmlGenericError;
    void *generic_data = xmlGenericErrorContext;
    xmlStructuredErrorFunc structured = xmlStructuredError;
    void *structured_data = xmlStructuredErrorContext;
    xmlSetGenericErrorFunc(r, xml_generic_error);
    xmlSetStructuredErrorFunc(r, xml_structured_error);
    /* XML_PARSE_HUGE: libxml2's own size limits (10 MB for a text node, a
     * value or the look-ahead of a tag) would refuse files within the 64
     * MiB cap; the pre-scan bounds nesting, attributes and markup. */
    xmlDoc *doc =
        xmlCtxtReadMemory(ctxt, (const char *)bytes, (int)size, r->path, NULL,
                          XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING | XML_PARSE_HUGE);
    xmlSetGenericErrorFunc(generic_data, generic);
    xmlSetStructuredErrorFunc(structured_data, structured);
    int ok = doc && ctxt->wellFormed && ctxt->nsWellFormed && !doc->intSubset && !doc->extSubset &&
             !r->xml_message[0] && !r->encoding_error;
    xmlFreeParserCtxt(ctxt);
    if (ok) return doc;
    xmlFreeDoc(doc);
    if (r->encoding_error)
        return U_FAIL(r, PX_ERR_IO,
                      "URDF file '%s': near line %d: a byte that is not a character of the declared encoding",
                      r->path, r->xml_line ? r->xml_line : 1),
               (xmlDoc *)NULL;
    if (!r->xml_message[0]) snprintf(r->xml_message, sizeof r->xml_message, "not well-formed XML");
    return U_FAIL(r, PX_ERR_IO, "URDF file '%s': line %d: %s", r->path, r->xml_line, r->xml_message),
           (xmlDoc *)NULL;
}

/* The options, checked before any file is read. */
static px_status check_options(const px_urdf_options *o, px_error *err) {
    for (int i = 0; i < 4; ++i)
        if (o->reserved[i])
            return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_urdf_load: options.reserved[%d] must be 0", i);
    /* PX_PIECES_PARTS is 0, the default (TRIANGLES): it cannot be asked for. */
    if (o->pieces != 0 && o->pieces != PX_PIECES_TRIANGLES && o->pieces != PX_PIECES_APPROXIMATE)
        return pxi_error(err, PX_ERR_INVALID_ARGUMENT,
                         "px_urdf_load: options.pieces %u is not PX_PIECES_TRIANGLES (or 0) or "
                         "PX_PIECES_APPROXIMATE",
                         o->pieces);
    if (o->pieces != PX_PIECES_APPROXIMATE && (o->tolerance != 0.0 || o->threads))
        return pxi_error(err, PX_ERR_INVALID_ARGUMENT,
                         "px_urdf_load: options.%s is for PX_PIECES_APPROXIMATE only (0 with exact pieces)",
                         o->tolerance != 0.0 ? "tolerance" : "threads");
    if (o->tolerance != 0.0 && !(o->tolerance >= PX_MODEL_MIN_TOLERANCE && o->tolerance <= 1.0))
        return pxi_error(err, PX_ERR_INVALID_ARGUMENT,
                         "px_urdf_load: options.tolerance %g is not in [%g, 1] (0: %g)", o->tolerance,
                         PX_MODEL_MIN_TOLERANCE, PX_MODEL_DEFAULT_TOLERANCE);
    if (o->base) {
        px_error e;
        if (px_pose_check(o->base, &e) != PX_OK)
            return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_urdf_load: options.base: %s", e.message);
        if (!(fmax(fabs(o->base->t.x), fmax(fabs(o->base->t.y), fabs(o->base->t.z))) <= U_MAX_COORD))
            return pxi_error(err, PX_ERR_INVALID_ARGUMENT,
                             "px_urdf_load: options.base's translation is beyond 2^250");
    }
    return PX_OK;
}

static px_urdf *urdf_load(const char *path, const px_urdf_options *options, px_error *err);

/* The caller's floating-point traps are held for the whole load (numbers
 * that overflow in strtod, libxml2's NaN, the geometry's arithmetic) and
 * the caller's environment, flags included, restored afterwards. */
px_urdf *px_urdf_load(const char *path, const px_urdf_options *options, px_error *err) {
    fenv_t env;
    feholdexcept(&env);
    /* Numbers and frames as in the C library's default: rounded to
     * nearest (strtod, sin and cos follow the rounding mode). */
    fesetround(FE_TONEAREST);
    px_urdf *u = urdf_load(path, options, err);
    fesetenv(&env);
    return u;
}

static px_urdf *urdf_load(const char *path, const px_urdf_options *options, px_error *err) {
    pxi_error_clear(err);
    if (!path || !path[0])
        return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_urdf_load: the path is NULL or empty"),
               (px_urdf *)NULL;
    px_urdf_options o;
    memset(&o, 0, sizeof o);
    if (options) o = *options;
    if (check_options(&o, err) != PX_OK) return NULL;
    px_allocator alloc;
    if (pxi_allocator_resolve(o.allocator, &alloc, err) != PX_OK) return NULL;
    call_once(&u_xml_once, u_xml_init);
    ureader rd = {&alloc, path, err, 0, 0, "", 0, U_MAX_TRIANGLES}, *r = &rd;
    unsigned char *bytes = NULL;
    size_t size = 0;
    if (read_file(r, &bytes, &size) != PX_OK) return NULL;
    /* Numbers are read and printed in the C locale whatever the caller's
     * (uselocale: this thread only, restored before returning). */
    locale_t c_locale = newlocale(LC_ALL_MASK, "C", (locale_t)0);
    if (c_locale == (locale_t)0) {
        pxi_free(&alloc, bytes, size + 1);
        return u_oom(r), (px_urdf *)NULL;
    }
    locale_t caller_locale = uselocale(c_locale);
    xmlDoc *doc = parse_xml(r, bytes, size);
    pxi_free(&alloc, bytes, size + 1);
    if (!doc) {
        uselocale(caller_locale);
        freelocale(c_locale);
        return NULL;
    }
    px_urdf *u = NULL;
    ulink *link = NULL;
    ujoint *joint = NULL;
    uname *names = NULL, *jnames = NULL;
    uint32_t *order = NULL, *chain_of = NULL, *stack = NULL;
    px_link_desc *desc = NULL;
    uint32_t nl = 0, nj = 0;
    px_status st = PX_OK;
    const xmlNode *root = xmlDocGetRootElement(doc);
    if (!root || !is_el(root, "robot")) {
        st = U_FAIL(r, PX_ERR_IO, "URDF file '%s': the root element is not <robot>", path);
        goto done;
    }
    for (const xmlNode *c = root->children; c; c = c->next) {
        nl += is_el(c, "link");
        nj += is_el(c, "joint");
    }
    if (nl == 0 || nl > PX_CHAIN_MAX_LINKS) {
        st = U_FAIL(r, PX_ERR_IO, "URDF file '%s': %u links (1 to %u allowed)", path, nl, PX_CHAIN_MAX_LINKS);
        goto done;
    }
    if (nj > U_MAX_ELEMENTS) { /* a tree of nl links has nl - 1 joints: the tree's checks name them */
        st = U_FAIL(r, PX_ERR_IO, "URDF file '%s': %u joints for %u links (a tree of links has one fewer)",
                    path, nj, nl);
        goto done;
    }
    /* link and joint zeroed at once: the names they will hold are freed
     * at the end whatever fails. */
    link = pxi_alloc_array(&alloc, nl, sizeof *link);
    if (link) memset(link, 0, nl * sizeof *link);
    joint = pxi_alloc_array(&alloc, nj ? nj : 1, sizeof *joint);
    if (joint) memset(joint, 0, (nj ? nj : 1) * sizeof *joint);
    names = pxi_alloc_array(&alloc, nl, sizeof *names);
    jnames = pxi_alloc_array(&alloc, nj ? nj : 1, sizeof *jnames);
    order = pxi_alloc_array(&alloc, nl, sizeof *order);
    chain_of = pxi_alloc_array(&alloc, nl, sizeof *chain_of);
    stack = pxi_alloc_array(&alloc, nl + nj + 1, sizeof *stack);
    desc = pxi_alloc_array(&alloc, nl, sizeof *desc);
    if (!link || !joint || !names || !jnames || !order || !chain_of || !stack || !desc) {
        st = u_oom(r);
        goto done;
    }
    /* Names. */
    {
        uint32_t il = 0, ij = 0;
        for (const xmlNode *c = root->children; c && st == PX_OK; c = c->next) {
            if (!is_el(c, "link") && !is_el(c, "joint")) continue;
            int is_link = is_el(c, "link");
            char *name = attr(r, c, "name");
            if (r->oom) {
                st = u_oom(r);
                break;
            }
            if (!name || !name[0]) {
                st = U_FAIL(r, PX_ERR_IO, "URDF file '%s': line %d: a <%s> without a name", path,
                            (int)c->line, is_link ? "link" : "joint");
                free_str(&alloc, name);
                break;
            }
            if (is_link) {
                link[il] = (ulink){c, name, UINT32_MAX, UINT32_MAX, UINT32_MAX};
                names[il] = (uname){name, il};
                il++;
            } else {
                joint[ij].node = c;
                joint[ij].name = name;
                jnames[ij] = (uname){name, ij};
                ij++;
            }
        }
        if (st != PX_OK) goto done;
        qsort(names, nl, sizeof *names, cmp_name);
        qsort(jnames, nj, sizeof *jnames, cmp_name);
        for (uint32_t i = 1; i < nl && st == PX_OK; ++i)
            if (strcmp(names[i].name, names[i - 1].name) == 0)
                st = U_FAIL(r, PX_ERR_IO, "URDF file '%s': two links are named '%.80s'", path, names[i].name);
        for (uint32_t i = 1; i < nj && st == PX_OK; ++i)
            if (strcmp(jnames[i].name, jnames[i - 1].name) == 0)
                st = U_FAIL(r, PX_ERR_IO, "URDF file '%s': two joints are named '%.80s'", path,
                            jnames[i].name);
        if (st != PX_OK) goto done;
    }
    /* Joints: type, parent and child; the tree. */
    for (uint32_t i = 0; i < nj && st == PX_OK; ++i) {
        ujoint *j = &joint[i];
        char *type = attr(r, j->node, "type");
        const xmlNode *pe = child_el(j->node, "parent"), *ce = child_el(j->node, "child");
        j->parent = pe ? attr(r, pe, "link") : NULL;
        j->child = ce ? attr(r, ce, "link") : NULL;
        if (r->oom)
            st = u_oom(r);
        else if (!type)
            st = U_FAIL(r, PX_ERR_IO, "URDF file '%s': joint '%.80s': no type", path, j->name);
        else if (strcmp(type, "fixed") == 0)
            j->type = PX_JOINT_FIXED;
        else if (strcmp(type, "revolute") == 0)
            j->type = PX_JOINT_REVOLUTE;
        else if (strcmp(type, "continuous") == 0)
            j->type = PX_JOINT_REVOLUTE, j->continuous = 1;
        else if (strcmp(type, "prismatic") == 0)
            j->type = PX_JOINT_PRISMATIC;
        else
            st = U_FAIL(r, PX_ERR_IO,
                        "URDF file '%s': joint '%.80s': type '%.40s' is not supported (fixed, revolute, "
                        "continuous and prismatic are)",
                        path, j->name, type);
        free_str(&alloc, type);
        if (st != PX_OK) break;
        if (!j->parent || !j->child) {
            st = U_FAIL(r, PX_ERR_IO, "URDF file '%s': joint '%.80s': no <%s link=...>", path, j->name,
                        j->parent ? "child" : "parent");
            break;
        }
        j->p = find_name(names, nl, j->parent);
        j->c = find_name(names, nl, j->child);
        if (j->p == UINT32_MAX || j->c == UINT32_MAX) {
            st = U_FAIL(r, PX_ERR_IO, "URDF file '%s': joint '%.80s': no link named '%.80s'", path, j->name,
                        j->p == UINT32_MAX ? j->parent : j->child);
            break;
        }
        if (j->p == j->c) {
            st = U_FAIL(r, PX_ERR_IO, "URDF file '%s': joint '%.80s' joins link '%.80s' to itself", path,
                        j->name, j->parent);
            break;
        }
        ulink *cl = &link[j->c];
        if (cl->parent_joint != UINT32_MAX) {
            st = U_FAIL(r, PX_ERR_IO,
                        "URDF file '%s': link '%.80s' is the child of two joints, '%.60s' and '%.60s'", path,
                        cl->name, joint[cl->parent_joint].name, j->name);
            break;
        }
        cl->parent_joint = i;
    }
    if (st != PX_OK) goto done;
    /* Children lists in file order (built backwards). */
    for (uint32_t i = nj; i-- > 0;) {
        ulink *pl = &link[joint[i].p];
        link[joint[i].c].next_sibling = pl->first_child;
        pl->first_child = i;
    }
    {
        uint32_t root_link = UINT32_MAX;
        for (uint32_t k = 0; k < nl && st == PX_OK; ++k)
            if (link[k].parent_joint == UINT32_MAX) {
                if (root_link != UINT32_MAX)
                    st = U_FAIL(r, PX_ERR_IO,
                                "URDF file '%s': two root links (without a parent joint): '%.80s' and "
                                "'%.80s'",
                                path, link[root_link].name, link[k].name);
                root_link = k;
            }
        if (st != PX_OK) goto done;
        if (root_link == UINT32_MAX) {
            st = U_FAIL(r, PX_ERR_IO, "URDF file '%s': no root link: the joints make a cycle", path);
            goto done;
        }
        /* Depth first from the root, children in file order. */
        uint32_t top = 0, n = 0;
        stack[top++] = root_link;
        while (top) {
            uint32_t k = stack[--top];
            chain_of[k] = n;
            order[n++] = k;
            uint32_t m = 0;
            for (uint32_t jj = link[k].first_child; jj != UINT32_MAX; jj = link[joint[jj].c].next_sibling)
                m++;
            /* Push in reverse so the first child comes out first. */
            uint32_t at = top + m;
            for (uint32_t jj = link[k].first_child; jj != UINT32_MAX; jj = link[joint[jj].c].next_sibling)
                stack[--at] = joint[jj].c;
            top += m;
        }
        if (n != nl) {
            for (uint32_t k = 0; k < nl; ++k) chain_of[k] = UINT32_MAX;
            for (uint32_t i = 0; i < n; ++i) chain_of[order[i]] = i;
            uint32_t lost = 0;
            while (chain_of[lost] != UINT32_MAX) lost++;
            st = U_FAIL(r, PX_ERR_IO,
                        "URDF file '%s': link '%.80s' is not reachable from the root link '%.80s' (a "
                        "cycle of joints)",
                        path, link[lost].name, link[root_link].name);
            goto done;
        }
    }
    /* The robot. */
    u = pxi_alloc(&alloc, sizeof *u);
    if (!u) {
        st = u_oom(r);
        goto done;
    }
    memset(u, 0, sizeof *u);
    u->alloc = alloc;
    u->n = nl;
    u->link_name = pxi_alloc_array(&alloc, nl, sizeof *u->link_name);
    u->joint_name = pxi_alloc_array(&alloc, nl, sizeof *u->joint_name);
    u->model = pxi_alloc_array(&alloc, nl, sizeof *u->model);
    if (!u->link_name || !u->joint_name || !u->model) {
        pxi_free(&alloc, u->link_name, (size_t)nl * sizeof *u->link_name);
        pxi_free(&alloc, u->joint_name, (size_t)nl * sizeof *u->joint_name);
        pxi_free(&alloc, u->model, (size_t)nl * sizeof *u->model);
        u->link_name = u->joint_name = NULL;
        u->model = NULL;
        st = u_oom(r);
        goto done;
    }
    memset(u->link_name, 0, nl * sizeof *u->link_name);
    memset(u->joint_name, 0, nl * sizeof *u->joint_name);
    memset(u->model, 0, nl * sizeof *u->model);
    memset(desc, 0, nl * sizeof *desc);
    for (uint32_t k = 0; k < nl && st == PX_OK; ++k) {
        const ulink *l = &link[order[k]];
        px_link_desc *d = &desc[k];
        u->link_name[k] = dup_str(&alloc, l->name);
        if (!u->link_name[k]) {
            st = u_oom(r);
            break;
        }
        d->geometry = px_pose_identity();
        d->group = o.group;
        d->mask = o.mask;
        if (l->parent_joint == UINT32_MAX) {
            d->parent = PX_CHAIN_ROOT;
            d->joint = PX_JOINT_FIXED;
            d->origin = px_pose_identity();
        } else {
            const ujoint *j = &joint[l->parent_joint];
            d->parent = chain_of[j->p];
            st = read_joint(r, j, d);
            if (st == PX_OK) st = read_mimic(r, j, joint, jnames, nj, chain_of, d);
            if (st == PX_OK && d->joint != PX_JOINT_FIXED && !d->mimic) {
                u->joint_name[u->dof] = dup_str(&alloc, j->name);
                if (!u->joint_name[u->dof])
                    st = u_oom(r);
                else
                    u->dof++;
            }
        }
        if (st == PX_OK) st = link_model(r, l, &o, &u->model[k]);
        d->model = u->model[k];
    }
    if (st == PX_OK) {
        px_chain_desc cd;
        memset(&cd, 0, sizeof cd);
        cd.links = desc;
        cd.n_links = nl;
        cd.base = o.base ? *o.base : px_pose_identity();
        cd.allocator = &alloc;
        px_error e;
        u->chain = px_chain_create(&cd, &e);
        if (!u->chain) {
            /* px_chain_create names the link by its index: name it. */
            unsigned k = 0;
            int at = 0;
            if (sscanf(e.message, "px_chain_create: link %u: %n", &k, &at) == 1 && at > 0 && k < nl)
                st = U_FAIL(r, e.code, "URDF file '%s': link '%.80s': %s", path, u->link_name[k],
                            e.message + at);
            else
                st = U_FAIL(r, e.code, "URDF file '%s': %s", path, e.message);
        }
    }
done:
    if (st != PX_OK) {
        px_urdf_destroy(u);
        u = NULL;
    }
    for (uint32_t k = 0; link && k < nl; ++k) free_str(&alloc, link[k].name);
    for (uint32_t i = 0; joint && i < nj; ++i) {
        free_str(&alloc, joint[i].name);
        free_str(&alloc, joint[i].parent);
        free_str(&alloc, joint[i].child);
    }
    pxi_free(&alloc, link, nl * sizeof *link);
    pxi_free(&alloc, joint, (nj ? nj : 1) * sizeof *joint);
    pxi_free(&alloc, names, nl * sizeof *names);
    pxi_free(&alloc, jnames, (nj ? nj : 1) * sizeof *jnames);
    pxi_free(&alloc, order, nl * sizeof *order);
    pxi_free(&alloc, chain_of, nl * sizeof *chain_of);
    pxi_free(&alloc, stack, (nl + nj + 1) * sizeof *stack);
    pxi_free(&alloc, desc, nl * sizeof *desc);
    xmlFreeDoc(doc);
    uselocale(caller_locale);
    freelocale(c_locale);
    return u;
}
