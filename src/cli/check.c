/* proxima check: every pair of parts of an assembly that interferes or is
 * closer than a clearance (issue 11 §4; docs/check.md).
 *
 * The assembly is one mesh file (each part px_mesh_load finds is a part)
 * or a folder of mesh files (each file is a part, named by its file name).
 * Each part becomes one model (exact triangle leaves by default) and one
 * static body of a px_scene whose margin and report distance are the
 * clearance: the scene's sweep-and-prune finds the pairs whose boxes come
 * within the clearance and measures them, so the pairs closer than the
 * clearance, with their witness points, are the scene's report.
 *
 * Parts are solids where they are closed: the scene puts a part that lies
 * inside another's closed part, the surfaces apart, at distance 0 and says
 * so (px_scene_pair.contained), with the closest points of the surfaces as
 * witnesses.
 *
 * Uses the public API only. */
#define _POSIX_C_SOURCE 200809L
#include "check.h"

#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "proxima/io.h"
#include "proxima/proxima.h"

/* What a pair is: its surfaces meet; one is inside the other's closed
 * part; closer than the clearance; or, with coarse leaves, a bracket
 * [distance, upper bound] that neither confirms nor clears. */
enum { F_INTERFERENCE = 0, F_INSIDE = 1, F_CLEARANCE = 2, F_POSSIBLE = 3 };
static const char *status_name[] = {"interference", "inside", "clearance", "possible"};

typedef struct part {
    char *name;      /* the part's name (folder: the file name), unique */
    char *base;      /* for "node/mesh#k": "node/mesh", which --ignore also takes; else NULL */
    px_model *model; /* world frame: bodies sit at the identity */
    uint32_t triangles;
    uint32_t closed; /* every mesh part closed (a solid) */
    px_vec3 lo, hi;  /* world box */
} part;

typedef struct finding {
    uint32_t a, b; /* part indices, a < b */
    int status;    /* F_* */
    double distance, upper;
    px_vec3 pa, pb;
    int inside; /* 0: not told, 1: a inside b, 2: b inside a, 3: part of a in b, 4: part of b in a */
} finding;

typedef struct findings {
    finding *v;
    size_t n;
} findings;

/* A part skipped for having no triangles: its name as a part's would be
 * (its node's, else px_mesh_load's, or a folder's file name) and
 * px_mesh_load's name when that differs (else NULL). */
typedef struct skipped_part {
    char *name, *mesh_name;
} skipped_part;

typedef struct assembly {
    part *parts;
    uint32_t count, cap;
    int folder;
    /* The parts skipped for having no triangles, listed in the JSON;
     * `--ignore` may name them (their pairs are not checked anyway). */
    skipped_part *skipped;
    uint32_t n_skipped, cap_skipped;
} assembly;

static void note(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;

/* A note on one line: control bytes of what it quotes (a file name with a
 * line break, a library message naming such a file) are shown as \n, \r,
 * \t or \xHH; names the callers escaped hold none. */
static void note(const char *fmt, ...) {
    char buf[2048];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    fprintf(stderr, "proxima: ");
    for (const unsigned char *c = (const unsigned char *)buf; *c; ++c) {
        if (*c == '\n' || *c == '\r' || *c == '\t')
            fprintf(stderr, "\\%c", *c == '\n' ? 'n' : *c == '\r' ? 'r' : 't');
        else if (*c < 0x20 || *c == 0x7f)
            fprintf(stderr, "\\x%02x", *c);
        else
            fputc(*c, stderr);
    }
    fputc('\n', stderr);
}

static char *dup_string(const char *s) {
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d) memcpy(d, s, n);
    return d;
}

/* The length of the UTF-8 sequence at c (1 to 4), or 0 when it is not
 * one (a stray, overlong or surrogate byte sequence: a Latin-1 file name). */
static int utf8_length(const unsigned char *c) {
    if (c[0] < 0x80) return 1;
    int n = c[0] >= 0xc2 && c[0] <= 0xdf   ? 2
            : c[0] >= 0xe0 && c[0] <= 0xef ? 3
            : c[0] >= 0xf0 && c[0] <= 0xf4 ? 4
                                           : 0;
    for (int k = 1; k < n; ++k)
        if ((c[k] & 0xc0) != 0x80) return 0;
    if ((c[0] == 0xe0 && c[1] < 0xa0) || (c[0] == 0xed && c[1] >= 0xa0) || (c[0] == 0xf0 && c[1] < 0x90) ||
        (c[0] == 0xf4 && c[1] >= 0x90))
        return 0;
    return n;
}

/* Bytes shown as \xHH: C0 and C1 controls (U+0080..U+009F, bytes c2 80 to
 * c2 9f), DEL and bytes that are not UTF-8 (n: utf8_length there). */
static int hidden(const unsigned char *c, int n) {
    return *c < 0x20 || *c == 0x7f || n == 0 || (n == 2 && c[0] == 0xc2 && c[1] < 0xa0);
}

/* s as shown in the table and the notes, into dst (room for 4 strlen(s) + 1
 * bytes): a backslash doubled, \t \n \r, other hidden bytes \xHH, so
 * that two names never look alike and no name moves the cursor. */
static char *escape_into(char *dst, const char *s) {
    char *w = dst;
    for (const unsigned char *c = (const unsigned char *)s; *c;) {
        int n = utf8_length(c);
        if (*c == '\\' || *c == '\t' || *c == '\n' || *c == '\r') {
            *w++ = '\\';
            *w++ = *c == '\t' ? 't' : *c == '\n' ? 'n' : *c == '\r' ? 'r' : '\\';
        } else if (hidden(c, n)) {
            for (int k = 0; k < (n ? n : 1); ++k) w += sprintf(w, "\\x%02x", c[k]);
        } else {
            memcpy(w, c, (size_t)n);
            w += n;
        }
        c += n ? n : 1;
    }
    *w = '\0';
    return dst;
}

/* s escaped (escape_into), a string to free; NULL when out of memory. */
static char *escaped(const char *s) {
    char *b = malloc(4 * strlen(s) + 1);
    return b ? escape_into(b, s) : NULL;
}

/* A message about a part of `file`, its name escaped. */
static void note_part(const char *file, const char *name, const char *what) {
    char *e = escaped(name), *ef = escaped(file);
    note("'%s': part '%s': %s", ef ? ef : file, e ? e : name, what);
    free(e);
    free(ef);
}

/* A mesh of the given parts of `m` alone (vertices and triangles copied,
 * indices rebased), or NULL with `e` filled. */
static px_mesh *submesh(const px_mesh *m, const uint32_t *ids, uint32_t n, px_error *e) {
    const double *xyz = px_mesh_vertices(m);
    const uint32_t *tri = px_mesh_triangles(m);
    size_t nv = 0, nt = 0;
    for (uint32_t i = 0; i < n; ++i) {
        px_mesh_part p;
        px_mesh_get_part(m, ids[i], &p);
        nv += p.vertex_count;
        nt += p.triangle_count;
    }
    double *v = malloc(sizeof(double) * 3 * (nv ? nv : 1));
    uint32_t *t = malloc(sizeof(uint32_t) * 3 * (nt ? nt : 1));
    px_mesh_part_desc *pd = calloc(n, sizeof *pd);
    px_mesh *out = NULL;
    if (v && t && pd) {
        size_t fv = 0, ft = 0;
        for (uint32_t i = 0; i < n; ++i) {
            px_mesh_part p;
            px_mesh_get_part(m, ids[i], &p);
            memcpy(v + 3 * fv, xyz + 3 * (size_t)p.first_vertex, sizeof(double) * 3 * p.vertex_count);
            for (size_t k = 0; k < 3 * (size_t)p.triangle_count; ++k)
                t[3 * ft + k] = (uint32_t)(tri[3 * (size_t)p.first_triangle + k] - p.first_vertex + fv);
            pd[i].name = p.name;
            pd[i].node = -1;
            pd[i].first_vertex = (uint32_t)fv;
            pd[i].vertex_count = p.vertex_count;
            pd[i].first_triangle = (uint32_t)ft;
            pd[i].triangle_count = p.triangle_count;
            fv += p.vertex_count;
            ft += p.triangle_count;
        }
        px_mesh_info info;
        px_mesh_get_info(m, &info);
        px_mesh_desc d;
        memset(&d, 0, sizeof d);
        d.xyz = v;
        d.vertex_count = nv;
        d.triangles = t;
        d.triangle_count = nt;
        d.parts = pd;
        d.part_count = n;
        d.unit_metres = info.unit_metres;
        d.float_coordinates = info.float_coordinates;
        out = px_mesh_create(&d, NULL, e);
    } else if (e) {
        e->code = PX_ERR_OUT_OF_MEMORY;
        snprintf(e->message, sizeof e->message, "out of memory");
    }
    free(v);
    free(t);
    free(pd);
    return out;
}

/* Adds the given parts of `m` as one part of the assembly; 0 on error
 * (message printed). */
static int add_part(assembly *as, const check_opts *o, const char *file, const char *name, const px_mesh *m,
                    const uint32_t *ids, uint32_t n) {
    px_error e;
    px_mesh *sub = submesh(m, ids, n, &e);
    if (!sub) {
        note_part(file, name, e.message);
        return 0;
    }
    px_model_options mo;
    memset(&mo, 0, sizeof mo);
    mo.pieces = o->pieces;
    if (o->pieces == PX_PIECES_APPROXIMATE) {
        mo.tolerance = o->tolerance;
        mo.threads = o->threads;
    }
    px_model *model = px_model_create_from_mesh(sub, &mo, &e);
    px_mesh_info mi;
    px_mesh_get_info(sub, &mi);
    uint32_t triangles = px_mesh_triangle_count(sub), closed = mi.closed_parts == px_mesh_part_count(sub);
    px_mesh_destroy(sub);
    if (!model) {
        note_part(file, name, e.message);
        return 0;
    }
    if (as->count == as->cap) {
        uint32_t cap = as->cap ? 2 * as->cap : 16;
        part *p = realloc(as->parts, sizeof *p * cap);
        if (!p) {
            px_model_destroy(model);
            note("out of memory");
            return 0;
        }
        as->parts = p;
        as->cap = cap;
    }
    part *p = &as->parts[as->count];
    memset(p, 0, sizeof *p);
    p->name = dup_string(name);
    if (!p->name) {
        px_model_destroy(model);
        note("out of memory");
        return 0;
    }
    as->count++;
    p->model = model;
    p->triangles = triangles;
    p->closed = closed;
    px_model_info info;
    px_model_get_info(model, &info);
    p->lo = info.min;
    p->hi = info.max;
    return 1;
}

static px_mesh *load(const char *path, const check_opts *o) {
    FILE *f = fopen(path, "rb");
    if (f) {
        char magic[8] = {0};
        size_t got = fread(magic, 1, sizeof magic, f);
        fclose(f);
        if (got == sizeof magic && !memcmp(magic, "PXMODEL", 8)) {
            note("'%s' is a .pxm model: check reads mesh files (or a folder of them), whose parts it names",
                 path);
            return NULL;
        }
    }
    px_mesh_options mo;
    memset(&mo, 0, sizeof mo);
    mo.scale = o->scale;
    px_error e;
    px_mesh *m = px_mesh_load(path, &mo, &e);
    if (!m) note("%s", e.message);
    return m;
}

/* Keeps the names of a part skipped for having no triangles (other: a
 * second name, or ""); 0 when out of memory. */
static int note_skipped(assembly *as, const char *name, const char *other) {
    if (as->n_skipped == as->cap_skipped) {
        uint32_t cap = as->cap_skipped ? 2 * as->cap_skipped : 8;
        skipped_part *v = realloc(as->skipped, sizeof *v * cap);
        if (!v) return 0;
        as->skipped = v;
        as->cap_skipped = cap;
    }
    skipped_part *k = &as->skipped[as->n_skipped];
    int two = other[0] && strcmp(other, name);
    k->name = dup_string(name);
    k->mesh_name = two ? dup_string(other) : NULL;
    if (!k->name || (two && !k->mesh_name)) {
        free(k->name);
        free(k->mesh_name);
        return 0;
    }
    as->n_skipped++;
    return 1;
}

static const char *node_name(const px_mesh *m, uint32_t id);

/* A string and its part's index, sorted by string, then index. */
typedef struct name_ix {
    const char *s;
    uint32_t i;
} name_ix;

static int cmp_name_ix(const void *x, const void *y) {
    const name_ix *a = x, *b = y;
    int c = strcmp(a->s, b->s);
    return c ? c : (a->i > b->i) - (a->i < b->i);
}

/* Sorts the n strings s[] (with their indices) into v and sets alone[i]
 * when no other string equals s[i]. */
static void sort_names(const char *const *s, uint32_t n, name_ix *v, unsigned char *alone) {
    for (uint32_t i = 0; i < n; ++i) v[i] = (name_ix){s[i], i};
    qsort(v, n, sizeof *v, cmp_name_ix);
    for (uint32_t r = 0; r < n;) {
        uint32_t e = r + 1;
        while (e < n && !strcmp(v[e].s, v[r].s)) ++e;
        for (uint32_t k = r; k < e; ++k) alone[v[k].i] = e - r == 1;
        r = e;
    }
}

/* Whether `name` is among the n sorted strings of v. */
static int among(const name_ix *v, uint32_t n, const char *name) {
    name_ix key = {name, 0};
    uint32_t lo = 0, hi = n;
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (strcmp(v[mid].s, key.s) < 0)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < n && !strcmp(v[lo].s, name);
}

/* Indices of the parts of `m` that have triangles (a part of points or
 * lines only has no surface to check: skipped with a note; its names, the
 * node's and px_mesh_load's, stay known to `--ignore`). 0 parts and
 * *ok = 0 when out of memory. */
static uint32_t surface_parts(assembly *as, const px_mesh *m, const char *file, uint32_t *ids, int *ok) {
    uint32_t n = 0, np = px_mesh_part_count(m), skipped = 0;
    for (uint32_t i = 0; i < np; ++i) {
        px_mesh_part p;
        px_mesh_get_part(m, i, &p);
        if (p.triangle_count)
            ids[n++] = i;
        else
            skipped++;
    }
    if (!skipped) return n;
    /* Whose node name no other part's node has (sorted once). */
    size_t cnt = np ? np : 1;
    const char **nodes = calloc(cnt, sizeof *nodes);
    name_ix *v = calloc(cnt, sizeof *v);
    unsigned char *alone = calloc(cnt, 1);
    char *ef = escaped(file);
    *ok = nodes && v && alone;
    if (*ok) {
        for (uint32_t i = 0; i < np; ++i) nodes[i] = node_name(m, i);
        sort_names(nodes, np, v, alone);
    }
    for (uint32_t i = 0; i < np && *ok; ++i) {
        px_mesh_part p;
        px_mesh_get_part(m, i, &p);
        if (p.triangle_count) continue;
        const char *node = nodes[i];
        char *ep = escaped(p.name), *en = escaped(node);
        if (node[0] && strcmp(node, p.name))
            note("note: '%s': part '%s' (node '%s') has no triangles (points or lines only): not checked",
                 ef ? ef : file, ep ? ep : p.name, en ? en : node);
        else
            note("note: '%s': part '%s' has no triangles (points or lines only): not checked", ef ? ef : file,
                 ep ? ep : p.name);
        free(ep);
        free(en);
        /* Named as a part would be: its node's name when no other part's
         * node has it, else the loader's. */
        if (!as->folder) *ok = note_skipped(as, node[0] && alone[i] ? node : p.name, p.name);
    }
    if (!*ok) note("out of memory");
    free(nodes);
    free(v);
    free(alone);
    free(ef);
    return *ok ? n : 0;
}

/* The name of the node part ids[i] hangs from, or "" for none. */
static const char *node_name(const px_mesh *m, uint32_t id) {
    px_mesh_part p;
    px_mesh_node nd;
    px_mesh_get_part(m, id, &p);
    return p.node >= 0 && px_mesh_get_node(m, (uint32_t)p.node, &nd) == PX_OK ? nd.name : "";
}

/* The names of the parts ids[0..n) of m in the report, unique: a part's
 * node's name (the name the file gives the body: a COLLADA or glTF node,
 * an OBJ object) when no other part's node has it, else px_mesh_load's
 * "node/mesh"; a name that two or more parts would then share becomes
 * "name#k" for each of them in file order, k the smallest number that
 * makes a name no part has (instances of one mesh under nodes of one
 * name), with base[i] = that shared name (which `--ignore` takes for all
 * of them) unless a part is named so. A generated "X#k" never equals
 * another group's "Y#j" (the text after the last '#' is k), so only the
 * names of their own are checked. O(n log n): sorted names. out[] and
 * base[] are strings to free (base[i] NULL for a name of its own); 0 when
 * out of memory. */
static int part_names(const assembly *as, const px_mesh *m, const uint32_t *ids, uint32_t n, char **out,
                      char **base) {
    /* The skipped parts' names count as taken (as->skipped: this file's). */
    size_t n_sk = 2 * (size_t)as->n_skipped, cnt = n + n_sk ? n + n_sk : 1;
    const char **cand = calloc(cnt, sizeof *cand);
    name_ix *v = calloc(cnt, sizeof *v), *own = calloc(cnt, sizeof *own);
    unsigned char *alone = calloc(cnt, 1);
    int ok = cand && v && own && alone;
    uint32_t n_own = 0;
    if (ok) {
        for (uint32_t i = 0; i < n; ++i) cand[i] = node_name(m, ids[i]);
        sort_names(cand, n, v, alone);
        for (uint32_t i = 0; i < n; ++i) {
            px_mesh_part p;
            px_mesh_get_part(m, ids[i], &p);
            if (!(cand[i][0] && alone[i])) cand[i] = p.name;
        }
        sort_names(cand, n, v, alone);
        /* Names taken: the skipped parts' (a part whose name one has is
         * not alone: it takes a "#k" too), then those of their own. */
        for (uint32_t k = 0; k < as->n_skipped; ++k) {
            own[n_own++] = (name_ix){as->skipped[k].name, UINT32_MAX};
            if (as->skipped[k].mesh_name) own[n_own++] = (name_ix){as->skipped[k].mesh_name, UINT32_MAX};
        }
        qsort(own, n_own, sizeof *own, cmp_name_ix);
        for (uint32_t i = 0; i < n; ++i)
            if (alone[i] && among(own, n_own, cand[i])) alone[i] = 0;
        for (uint32_t k = 0; k < n; ++k)
            if (alone[v[k].i]) own[n_own++] = v[k];
        qsort(own, n_own, sizeof *own, cmp_name_ix);
    }
    for (uint32_t i = 0; i < n && ok; ++i)
        if (alone[i]) ok = (out[i] = dup_string(cand[i])) != NULL;
    /* The shared names' groups, each in file order (v's order). */
    for (uint32_t r = 0; r < n && ok;) {
        uint32_t e = r + 1;
        while (e < n && !strcmp(v[e].s, v[r].s)) ++e;
        uint32_t k = 1;
        for (uint32_t g = r; g < e && ok; ++g) {
            uint32_t i = v[g].i;
            if (alone[i]) continue;
            size_t len = strlen(cand[i]) + 16;
            char *name = malloc(len);
            ok = name && (base[i] = dup_string(cand[i])) != NULL;
            while (ok) {
                snprintf(name, len, "%s#%u", cand[i], k++);
                if (!among(own, n_own, name)) break;
            }
            if (ok)
                out[i] = name;
            else
                free(name);
        }
        r = e;
    }
    /* A base that a part or a skipped part is named by names that one
     * only. */
    if (ok) {
        sort_names((const char *const *)out, n, v, alone);
        for (uint32_t i = 0; i < n; ++i)
            if (base[i] && (among(v, n, base[i]) || among(own, n_own, base[i]))) {
                free(base[i]);
                base[i] = NULL;
            }
    }
    free(cand);
    free(v);
    free(own);
    free(alone);
    return ok;
}

/* One file: each part with triangles is a part of the assembly. */
static int load_file(assembly *as, const check_opts *o) {
    px_mesh *m = load(o->file, o);
    if (!m) return 0;
    uint32_t np = px_mesh_part_count(m);
    uint32_t *ids = malloc(sizeof *ids * (np ? np : 1));
    int ok = ids != NULL;
    uint32_t n = ok ? surface_parts(as, m, o->file, ids, &ok) : 0;
    char **names = ok ? calloc(n ? n : 1, sizeof *names) : NULL;
    char **bases = ok ? calloc(n ? n : 1, sizeof *bases) : NULL;
    if (ok && !(names && bases && part_names(as, m, ids, n, names, bases))) {
        note("out of memory");
        ok = 0;
    }
    for (uint32_t i = 0; ok && i < n; ++i) {
        ok = add_part(as, o, o->file, names[i], m, &ids[i], 1);
        if (ok) as->parts[as->count - 1].base = bases[i], bases[i] = NULL;
    }
    for (uint32_t i = 0; i < n && names && bases; ++i) {
        free(names[i]);
        free(bases[i]);
    }
    free(names);
    free(bases);
    if (!ids) note("out of memory");
    free(ids);
    px_mesh_destroy(m);
    return ok;
}

/* The mesh formats a folder's files are taken from (by extension, any
 * case); other files (materials, textures, glTF buffers, notes) are not
 * parts. */
static int mesh_extension(const char *name) {
    static const char *ext[] = {"stl", "obj", "ply", "off",  "dae", "gltf", "glb", "fbx",  "3ds",
                                "ac",  "amf", "lwo", "ms3d", "x3d", "xgl",  "dxf", "blend"};
    const char *dot = strrchr(name, '.');
    if (!dot || dot == name) return 0;
    for (size_t i = 0; i < sizeof ext / sizeof ext[0]; ++i)
        if (!strcasecmp(dot + 1, ext[i])) return 1;
    return 0;
}

static int cmp_name(const void *x, const void *y) { return strcmp(*(char *const *)x, *(char *const *)y); }

/* A folder: each mesh file is one part named by its file name, in byte
 * order of the names. */
static int load_folder(assembly *as, const check_opts *o) {
    DIR *d = opendir(o->file);
    if (!d) {
        note("'%s': cannot read the folder: %s", o->file, strerror(errno));
        return 0;
    }
    char **names = NULL;
    size_t n = 0, cap = 0;
    int ok = 1, refused = 0;
    struct dirent *de;
    size_t dirlen = strlen(o->file);
    while (ok && (de = readdir(d)) != NULL) {
        if (de->d_name[0] == '.' || !mesh_extension(de->d_name)) continue;
        if (n == cap) {
            cap = cap ? 2 * cap : 16;
            char **nn = realloc(names, sizeof *nn * cap);
            if (!nn) {
                ok = 0;
                break;
            }
            names = nn;
        }
        char *path = malloc(dirlen + strlen(de->d_name) + 2);
        if (!path) {
            ok = 0;
            break;
        }
        sprintf(path, "%s/%s", o->file, de->d_name);
        /* A sub-folder is not a part. A mesh name that cannot be read (a
         * broken link, no permission) or is not a file is an error: skipped,
         * its part would be missing from a clean report (review s30). */
        struct stat st;
        const int got = stat(path, &st) == 0, e = errno;
        if (!got || !S_ISREG(st.st_mode)) {
            const int dir = got && S_ISDIR(st.st_mode);
            if (!got)
                note("'%s': cannot read this part: %s", path, strerror(e));
            else if (!dir)
                note("'%s': this part is not a regular file", path);
            free(path);
            if (dir) continue;
            ok = 0;
            refused = 1;
            break;
        }
        free(path);
        names[n] = dup_string(de->d_name);
        if (!names[n])
            ok = 0;
        else
            ++n;
    }
    closedir(d);
    if (!ok && !refused) note("out of memory");
    if (ok && n == 0) {
        note("'%s': the folder holds no mesh file (.stl, .obj, .ply, .off, .dae, .gltf, .glb, ...)", o->file);
        ok = 0;
    }
    if (ok) qsort(names, n, sizeof *names, cmp_name);
    for (size_t i = 0; ok && i < n; ++i) {
        char *path = malloc(dirlen + strlen(names[i]) + 2);
        if (!path) {
            note("out of memory");
            ok = 0;
            break;
        }
        sprintf(path, "%s/%s", o->file, names[i]);
        px_mesh *m = load(path, o);
        if (!m) {
            free(path);
            ok = 0;
            break;
        }
        uint32_t np = px_mesh_part_count(m);
        uint32_t *ids = malloc(sizeof *ids * (np ? np : 1));
        uint32_t k = ids ? surface_parts(as, m, path, ids, &ok) : 0;
        if (!ids) {
            note("out of memory");
            ok = 0;
        } else if (ok && k == 0) {
            char *ep = escaped(path);
            note("note: '%s' has no triangles: not checked", ep ? ep : path);
            free(ep);
            if (!note_skipped(as, names[i], "")) {
                note("out of memory");
                ok = 0;
            }
        } else if (ok) {
            ok = add_part(as, o, path, names[i], m, ids, k);
        }
        free(ids);
        px_mesh_destroy(m);
        free(path);
    }
    for (size_t i = 0; i < n; ++i) free(names[i]);
    free(names);
    return ok;
}

/* ---- ignored pairs --------------------------------------------------- */

typedef struct ipair {
    uint32_t a, b;
} ipair;

/* Whether s is the first len bytes of name (an `--ignore` side). */
static int same_name(const char *s, const char *name, size_t len) {
    return strlen(s) == len && !strncmp(s, name, len);
}

/* Whether part i is named so: its name, or its base name (every
 * instance "node/mesh#k" of "node/mesh"). */
static int named(const assembly *as, const char *name, size_t len, uint32_t i) {
    const part *p = &as->parts[i];
    return same_name(p->name, name, len) || (p->base && same_name(p->base, name, len));
}

/* 2: the name of a part; 1: of a part skipped for having no triangles
 * only; 0: neither. */
static int has_name(const assembly *as, const char *name, size_t len) {
    for (uint32_t i = 0; i < as->count; ++i)
        if (named(as, name, len, i)) return 2;
    for (uint32_t i = 0; i < as->n_skipped; ++i) {
        const skipped_part *k = &as->skipped[i];
        if ((k->name[0] && same_name(k->name, name, len)) ||
            (k->mesh_name && same_name(k->mesh_name, name, len)))
            return 1;
    }
    return 0;
}

static int cmp_ipair(const void *x, const void *y) {
    const ipair *p = x, *q = y;
    if (p->a != q->a) return p->a < q->a ? -1 : 1;
    return (p->b > q->b) - (p->b < q->b);
}

/* Every pair of parts "A,B" names (each of A and B may name several parts;
 * names may hold commas: the split must be the only one that names parts on
 * both sides). Returns the count, or -1 with a message. */
static long resolve_ignores(const assembly *as, const check_opts *o, ipair **out) {
    ipair *v = NULL;
    size_t n = 0, cap = 0;
    for (int g = 0; g < o->nignore; ++g) {
        const char *s = o->ignore[g];
        /* Splits into two parts' names first; only when there is none,
         * splits that name a skipped part (so that skipped names never make
         * a name of two parts ambiguous). */
        const char *split = NULL;
        int splits = 0;
        for (int want = 4; want >= 2 && !splits; want -= 2)
            for (const char *c = strchr(s, ','); c; c = strchr(c + 1, ',')) {
                int ha = has_name(as, s, (size_t)(c - s)), hb = has_name(as, c + 1, strlen(c + 1));
                if (ha && hb && (want == 4 ? ha + hb == 4 : ha + hb < 4)) {
                    split = c;
                    ++splits;
                }
            }
        if (splits != 1) {
            note("--ignore '%s': %s", s,
                 splits ? "more than one way to split it into two part names"
                        : "not two part names A,B of the assembly (`proxima check FILE --json` lists them; "
                          "parts without triangles are named in the notes)");
            free(v);
            return -1;
        }
        size_t la = (size_t)(split - s), lb = strlen(split + 1);
        uint32_t many = 0; /* "A,A" is a pair when A names several parts */
        for (uint32_t i = 0; i < as->count && many < 2; ++i) many += named(as, s, la, i);
        if (la == lb && !strncmp(s, split + 1, la) && many < 2) {
            note("--ignore '%s': a part and itself are no pair", s);
            free(v);
            return -1;
        }
        for (uint32_t i = 0; i < as->count; ++i) {
            if (!named(as, s, la, i)) continue;
            for (uint32_t j = 0; j < as->count; ++j) {
                if (j == i || !named(as, split + 1, lb, j)) continue;
                if (n == cap) {
                    cap = cap ? 2 * cap : 16;
                    ipair *nv = realloc(v, sizeof *nv * cap);
                    if (!nv) {
                        free(v);
                        note("out of memory");
                        return -1;
                    }
                    v = nv;
                }
                v[n++] = (ipair){i < j ? i : j, i < j ? j : i};
            }
        }
    }
    /* The same pair named twice, or as B,A, counts once. */
    if (n) qsort(v, n, sizeof *v, cmp_ipair);
    size_t u = 0;
    for (size_t k = 0; k < n; ++k)
        if (!u || v[k].a != v[u - 1].a || v[k].b != v[u - 1].b) v[u++] = v[k];
    *out = v;
    return (long)u;
}

/* ---- the check ------------------------------------------------------- */

static int cmp_finding(const void *x, const void *y) {
    const finding *f = x, *g = y;
    if (f->a != g->a) return f->a < g->a ? -1 : 1;
    return f->b < g->b ? -1 : f->b > g->b;
}

/* ---- output ---------------------------------------------------------- */

/* A JSON string: bytes that are not UTF-8 become U+FFFD (JSON is UTF-8). */
static void json_string(const char *s) {
    putchar('"');
    for (const unsigned char *c = (const unsigned char *)s; *c;) {
        int n = utf8_length(c);
        if (*c == '"' || *c == '\\')
            printf("\\%c", *c);
        else if (*c < 0x20)
            printf("\\u%04x", *c);
        else if (n == 0)
            fputs("\\ufffd", stdout);
        else
            fwrite(c, 1, (size_t)n, stdout);
        c += n ? n : 1;
    }
    putchar('"');
}

/* The distance between the witness points: the surfaces' distance. */
static double gap(const finding *f) {
    double x = f->pb.x - f->pa.x, y = f->pb.y - f->pa.y, z = f->pb.z - f->pa.z;
    return sqrt(x * x + y * y + z * z);
}

static void json_vec(px_vec3 v) { printf("[%.17g, %.17g, %.17g]", v.x, v.y, v.z); }

static const char *pieces_word(uint32_t p) {
    return p == PX_PIECES_TRIANGLES ? "triangles" : p == PX_PIECES_PARTS ? "parts" : "approximate";
}

static void print_json(const assembly *as, const check_opts *o, const findings *fs, const size_t counts[4],
                       const px_scene_pair *closest, const ipair *ig, long nig) {
    printf("{\n  \"format\": \"proxima-check\",\n  \"version\": 1,\n  \"file\": ");
    json_string(o->file);
    printf(",\n  \"kind\": \"%s\",\n  \"clearance\": %.17g,\n  \"pieces\": \"%s\",\n  \"exact\": %s,\n",
           as->folder ? "folder" : "file", o->clearance, pieces_word(o->pieces),
           o->pieces == PX_PIECES_TRIANGLES ? "true" : "false");
    printf("  \"parts\": [");
    for (uint32_t i = 0; i < as->count; ++i) {
        printf("%s\n    {\"index\": %u, \"name\": ", i ? "," : "", i);
        json_string(as->parts[i].name);
        printf(", \"triangles\": %u, \"closed\": %s}", as->parts[i].triangles,
               as->parts[i].closed ? "true" : "false");
    }
    printf("%s],\n  \"skipped\": [", as->count ? "\n  " : "");
    for (uint32_t i = 0; i < as->n_skipped; ++i) {
        printf("%s\n    {\"name\": ", i ? "," : "");
        json_string(as->skipped[i].name);
        printf(", \"mesh_name\": ");
        if (as->skipped[i].mesh_name)
            json_string(as->skipped[i].mesh_name);
        else
            printf("null");
        printf("}");
    }
    printf("%s],\n  \"ignored\": [", as->n_skipped ? "\n  " : "");
    for (long i = 0; i < nig; ++i) printf("%s[%u, %u]", i ? ", " : "", ig[i].a, ig[i].b);
    printf("],\n  \"findings\": [");
    for (size_t i = 0; i < fs->n; ++i) {
        const finding *f = &fs->v[i];
        printf("%s\n    {\"a\": %u, \"b\": %u, \"part_a\": ", i ? "," : "", f->a, f->b);
        json_string(as->parts[f->a].name);
        printf(", \"part_b\": ");
        json_string(as->parts[f->b].name);
        printf(", \"status\": \"%s\", \"distance\": %.17g, \"upper_bound\": %.17g, \"point_a\": ",
               status_name[f->status], f->distance, f->upper);
        json_vec(f->pa);
        printf(", \"point_b\": ");
        json_vec(f->pb);
        printf(", \"surface_distance\": %.17g", gap(f));
        static const char *inside_json[] = {"null", "\"a\"", "\"b\"", "\"part of a\"", "\"part of b\""};
        printf(", \"inside\": %s}", f->status == F_INSIDE ? inside_json[f->inside] : "null");
    }
    printf("%s],\n  \"counts\": {\"interference\": %zu, \"inside\": %zu, \"clearance\": %zu, \"possible\": "
           "%zu},\n",
           fs->n ? "\n  " : "", counts[0], counts[1], counts[2], counts[3]);
    printf("  \"closest\": ");
    if (closest->body_a == UINT32_MAX) {
        printf("null\n}\n");
        return;
    }
    printf("{\"a\": %u, \"b\": %u, \"distance\": %.17g, \"upper_bound\": %.17g, \"point_a\": ",
           closest->body_a, closest->body_b, closest->distance, closest->upper_bound);
    json_vec(closest->point_a);
    printf(", \"point_b\": ");
    json_vec(closest->point_b);
    printf("}\n}\n");
}

/* Part names in the table: a control character (a tab or newline in a
 * node's name) is written as \t, \n, \r or \xHH, and so is a byte that is
 * not UTF-8, so that it cannot break the columns; a UTF-8 character counts
 * as one column (the JSON escapes them its own way; `--ignore` takes the
 * names as they are). */

/* Columns of text already escaped: a UTF-8 character counts as one. */
static int columns(const char *e) {
    int w = 0;
    for (const unsigned char *c = (const unsigned char *)e; *c; ++c) w += (*c & 0xc0) != 0x80;
    return w;
}

/* Columns of s as shown. */
static int width(const char *s) {
    char *e = escaped(s);
    int w = columns(e ? e : s);
    free(e);
    return w;
}

static void put_name(const char *s, int pad) {
    char *e = escaped(s);
    const char *shown = e ? e : s;
    fputs(shown, stdout);
    for (int w = columns(shown); w < pad; ++w) putchar(' ');
    free(e);
}

/* The shortest %g form of x that reads back as x (the clearance as given),
 * without an exponent between 1e-4 and 1e15 (100 was shown as 1e+02). */
static void shortest(char *buf, size_t size, double x) {
    const int plain_ok = fabs(x) >= 1e-4 && fabs(x) < 1e15;
    for (int p = 1; p <= 17; ++p) {
        snprintf(buf, size, "%.*g", p, x);
        if (strtod(buf, NULL) == x && (!plain_ok || !strchr(buf, 'e'))) return;
    }
    snprintf(buf, size, "%.17g", x);
}

static void print_table(const assembly *as, const check_opts *o, const findings *fs, const size_t counts[4],
                        const px_scene_pair *closest, long nig) {
    char c[32];
    shortest(c, sizeof c, o->clearance);
    uint32_t closed = 0;
    for (uint32_t i = 0; i < as->count; ++i) closed += as->parts[i].closed;
    int exact = o->pieces == PX_PIECES_TRIANGLES;
    char *ef = escaped(o->file);
    printf("assembly:  %s (%s, %u part%s, %u closed)\n", ef ? ef : "?", as->folder ? "folder" : "file",
           as->count, as->count == 1 ? "" : "s", closed);
    free(ef);
    printf("check:     interference and clearance %s, %s", c,
           exact                          ? "exact (triangle leaves)"
           : o->pieces == PX_PIECES_PARTS ? "one hull per part (distance brackets)"
                                          : "approximate convex pieces (distance brackets)");
    if (nig) printf(", %ld pairs ignored", nig);
    printf("\n");
    if (fs->n) {
        int wa = width("part a"), wb = width("part b");
        for (size_t i = 0; i < fs->n; ++i) {
            int na = width(as->parts[fs->v[i].a].name), nb = width(as->parts[fs->v[i].b].name);
            if (na > wa) wa = na;
            if (nb > wb) wb = nb;
        }
        printf("\n%-*s  %-*s  %-14s  %-14s  %s%-38s  %s\n", wa, "part a", wb, "part b", "status", "distance",
               exact ? "" : "upper bound     ", "point a (world)", "point b (world)");
        for (size_t i = 0; i < fs->n; ++i) {
            const finding *f = &fs->v[i];
            char st[32], pa[96], pb[96], up[32] = "";
            static const char *inside_table[] = {"inside", "a inside b", "b inside a", "part of a in b",
                                                 "part of b in a"};
            snprintf(st, sizeof st, "%s",
                     f->status == F_INSIDE ? inside_table[f->inside] : status_name[f->status]);
            snprintf(pa, sizeof pa, "%.9g %.9g %.9g", f->pa.x, f->pa.y, f->pa.z);
            snprintf(pb, sizeof pb, "%.9g %.9g %.9g", f->pb.x, f->pb.y, f->pb.z);
            if (!exact) snprintf(up, sizeof up, "%-14.9g  ", f->upper);
            put_name(as->parts[f->a].name, wa);
            printf("  ");
            put_name(as->parts[f->b].name, wb);
            printf("  %-14s  %-14.9g  %s%-38s  %s\n", st, f->distance, up, pa, pb);
        }
        printf("\n");
        printf("found:     %zu pairs: %zu interfering, %zu inside another part, %zu closer than %s", fs->n,
               counts[0], counts[1], counts[2], c);
        if (counts[3]) printf(", %zu possibly (brackets across it: try the exact default)", counts[3]);
        printf("\n");
    } else if (as->count < 2) {
        printf("found:     nothing (%s)\n", as->count ? "one part only" : "no part with triangles");
    } else {
        printf("found:     nothing: no interference, no pair closer than %s\n", c);
    }
    if (closest->body_a != UINT32_MAX) {
        printf("closest:   %.9g between ", closest->distance);
        put_name(as->parts[closest->body_a].name, 0);
        printf(" and ");
        put_name(as->parts[closest->body_b].name, 0);
        printf("\n");
    }
}

/* Names the open parts (up to 8): a part inside one of them is not found
 * (with one hull per part, the hull is a solid and it is), and a flaw of
 * the mesh (a hole, an edge of three triangles, a T-junction, a flipped,
 * repeated or zero-area triangle) is the usual reason a part meant as a
 * solid is open. */
static void note_open_parts(const assembly *as, const check_opts *o) {
    if (as->count < 2) return;
    uint32_t open = 0;
    for (uint32_t i = 0; i < as->count; ++i) {
        if (as->parts[i].closed) continue;
        if (open++ >= 8) continue;
        char *e = escaped(as->parts[i].name);
        note("note: part '%s' is not a closed surface (a hole, an edge of three or more triangles, a "
             "T-junction, or a flipped, repeated or zero-area triangle): %s",
             e ? e : as->parts[i].name,
             o->pieces == PX_PIECES_PARTS ? "its hull, a solid, is checked"
                                          : "it is checked as a surface, and a part inside it is not found");
        free(e);
    }
    if (open > 8) note("note: and %u more open parts", open - 8);
}

int check_run(const check_opts *o) {
    assembly as;
    memset(&as, 0, sizeof as);
    struct stat st;
    if (stat(o->file, &st) != 0) {
        note("cannot open '%s': %s", o->file, strerror(errno));
        return 2;
    }
    as.folder = S_ISDIR(st.st_mode);
    int rc = 2;
    ipair *ig = NULL;
    long nig = 0;
    findings fs = {NULL, 0};
    px_scene *scene = NULL;
    if (!(as.folder ? load_folder(&as, o) : load_file(&as, o))) goto done;
    note_open_parts(&as, o);
    nig = resolve_ignores(&as, o, &ig);
    if (nig < 0) goto done;

    /* The scene: one static body per part, the clearance as margin and
     * report distance. */
    px_error e;
    px_scene_options so;
    memset(&so, 0, sizeof so);
    so.margin = so.report_distance = o->clearance;
    scene = px_scene_create(&so, &e);
    if (!scene) {
        note("%s", e.message);
        goto done;
    }
    for (uint32_t i = 0; i < as.count; ++i) {
        px_body_desc d;
        memset(&d, 0, sizeof d);
        d.model = as.parts[i].model;
        d.pose = px_pose_identity();
        d.flags = PX_BODY_STATIC;
        uint32_t id;
        if (px_scene_add_body(scene, &d, &id, &e) != PX_OK) {
            note_part(o->file, as.parts[i].name, e.message);
            goto done;
        }
    }
    for (long i = 0; i < nig; ++i)
        if (px_scene_exclude_pair(scene, ig[i].a, ig[i].b, &e) != PX_OK) {
            note("%s", e.message);
            goto done;
        }
    if (px_scene_step(scene, 0.0, &e) != PX_OK) {
        note("'%s': %s", o->file, e.message);
        goto done;
    }
    size_t np;
    const px_scene_pair *pairs = px_scene_pairs(scene, &np);
    fs.v = malloc(sizeof *fs.v * (np ? np : 1));
    if (!fs.v) {
        note("out of memory");
        goto done;
    }
    for (size_t i = 0; i < np; ++i) {
        const px_scene_pair *p = &pairs[i];
        /* Closer than the clearance, or touching (a clearance of 0 still
         * reports interference). */
        if (!(p->distance < o->clearance || p->distance == 0.0)) continue;
        finding *f = &fs.v[fs.n++];
        memset(f, 0, sizeof *f);
        f->a = p->body_a;
        f->b = p->body_b;
        f->status = p->contained ? F_INSIDE : p->distance == 0.0 ? F_INTERFERENCE : F_CLEARANCE;
        /* Coarse leaves: the meshes' distance lies in [distance,
         * upper_bound]; found for sure only when the bound says so. */
        if (p->upper_bound > p->distance && !(p->upper_bound < o->clearance))
            f->status = F_POSSIBLE;
        else if (p->upper_bound > 0.0 && f->status == F_INTERFERENCE)
            f->status = F_CLEARANCE;
        /* Which one is inside: the scene says (bit 0: a piece of a inside
         * b, bit 2: all of a; bits 1 and 3 the same for b). Pieces of each
         * inside the other name neither. */
        uint32_t c = p->contained;
        f->inside = (c & 3) == 1 ? (c & 4 ? 1 : 3) : (c & 3) == 2 ? (c & 8 ? 2 : 4) : 0;
        f->distance = p->distance;
        f->upper = p->upper_bound;
        f->pa = p->point_a;
        f->pb = p->point_b;
    }
    qsort(fs.v, fs.n, sizeof *fs.v, cmp_finding); /* the scene's order already; kept explicit */
    px_scene_pair closest;
    if (px_scene_min_distance(scene, &closest, &e) != PX_OK) {
        note("'%s': %s", o->file, e.message);
        goto done;
    }
    size_t counts[4] = {0, 0, 0, 0};
    for (size_t i = 0; i < fs.n; ++i) counts[fs.v[i].status]++;
    if (o->json)
        print_json(&as, o, &fs, counts, &closest, ig, nig);
    else
        print_table(&as, o, &fs, counts, &closest, nig);
    rc = fs.n ? 1 : 0;
done:
    px_scene_destroy(scene);
    free(fs.v);
    free(ig);
    for (uint32_t i = 0; i < as.count; ++i) {
        px_model_destroy(as.parts[i].model);
        free(as.parts[i].name);
        free(as.parts[i].base);
    }
    free(as.parts);
    for (uint32_t i = 0; i < as.n_skipped; ++i) {
        free(as.skipped[i].name);
        free(as.skipped[i].mesh_name);
    }
    free(as.skipped);
    return rc;
}
