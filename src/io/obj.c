/* OBJ objects as Assimp 5.2's OBJ reader groups them (ObjFileParser,
 * Debian bookworm's 5.2.5), before it does.
 *
 * Every part px_mesh_load returns is one of Assimp's objects. Its reader
 * keeps a list of objects, each with its own meshes, and a current mesh
 * that takes the faces:
 * - `o NAME` takes the name up to its first blank. A name new to the list
 *   starts an object and makes its mesh current; a name already in it
 *   (from an `o` or a `g`) makes that object current again, but not its
 *   mesh: the faces that follow go on into the mesh that was current.
 * - `g NAME` takes the rest of the line, less its leading blanks. The name
 *   of the active group changes nothing; any other starts a new object
 *   (a name already in the list included) whose mesh becomes current.
 * So `o bolt 1` and `o bolt 2` are one part "bolt", whose halves are never
 * measured against each other, and an object named again after another
 * one gets its later faces in the other's part: one part is left open and
 * the other holds two objects, with PX_OK. Such files are refused, naming
 * both lines; the fix is to give each object a distinct name without
 * spaces, or to keep an object's lines together. A new material can start
 * a mesh of the right object in Assimp; those files are refused too. */
#include <string.h>

#include "core/core.h"
#include "io/scan.h"

typedef struct obj_name {
    size_t key, key_len;   /* the name Assimp keeps: offsets into the text */
    size_t full, full_len; /* the whole name as written */
    u64 line;
} obj_name;

typedef struct obj_names {
    const px_allocator *alloc;
    obj_name *v;
    size_t n, cap;
    uint32_t *slot; /* hash of keys: index + 1 of the first object of each key, 0 empty */
    size_t slots;   /* a power of two, at least twice n */
} obj_names;

static uint64_t name_hash(const unsigned char *s, size_t n) {
    uint64_t h = 1469598103934665603ull; /* FNV-1a */
    for (size_t i = 0; i < n; ++i) h = (h ^ s[i]) * 1099511628211ull;
    return h;
}

static int same(const unsigned char *t, size_t a, size_t an, size_t b, size_t bn) {
    return an == bn && memcmp(t + a, t + b, an) == 0;
}

/* The first object whose key is t[k .. k + n), or SIZE_MAX. */
static size_t find(const obj_names *o, const unsigned char *t, size_t k, size_t n) {
    if (!o->slots) return SIZE_MAX;
    for (size_t i = name_hash(t + k, n) & (o->slots - 1);; i = (i + 1) & (o->slots - 1)) {
        uint32_t s = o->slot[i];
        if (!s) return SIZE_MAX;
        if (same(t, o->v[s - 1].key, o->v[s - 1].key_len, k, n)) return s - 1;
    }
}

static void put_slot(obj_names *o, const unsigned char *t, size_t id) {
    size_t i = name_hash(t + o->v[id].key, o->v[id].key_len) & (o->slots - 1);
    while (o->slot[i]) i = (i + 1) & (o->slots - 1);
    o->slot[i] = (uint32_t)(id + 1);
}

/* Appends an object; its key enters the hash when new. 0 when out of
 * memory. */
static int add(obj_names *o, const unsigned char *t, obj_name e) {
    if (o->n == o->cap) {
        size_t nc = o->cap ? 2 * o->cap : 64;
        if (nc > UINT32_MAX - 1) return 0;
        obj_name *w = pxi_alloc_array(o->alloc, nc, sizeof *w);
        if (!w) return 0;
        if (o->n) memcpy(w, o->v, o->n * sizeof *w);
        pxi_free(o->alloc, o->v, o->cap * sizeof *o->v);
        o->v = w;
        o->cap = nc;
    }
    if (2 * (o->n + 1) > o->slots) {
        size_t ns = o->slots ? 2 * o->slots : 128;
        uint32_t *w = pxi_alloc_array(o->alloc, ns, sizeof *w);
        if (!w) return 0;
        memset(w, 0, ns * sizeof *w);
        pxi_free(o->alloc, o->slot, o->slots * sizeof *o->slot);
        o->slot = w;
        o->slots = ns;
        /* Again, first objects first, so that a key keeps its first. */
        for (size_t i = 0; i < o->n; ++i)
            if (find(o, t, o->v[i].key, o->v[i].key_len) == SIZE_MAX) put_slot(o, t, i);
    }
    o->v[o->n] = e;
    if (find(o, t, e.key, e.key_len) == SIZE_MAX) put_slot(o, t, o->n);
    o->n++;
    return 1;
}

static int is_blank(unsigned char c) { return c == ' ' || c == '\t'; }

px_status pxi_check_obj_objects(const io_head *h, px_error *err) {
    unsigned char *t;
    px_status st = pxi_read_all(h, &t, err);
    if (st != PX_OK) return st;
    const size_t size = (size_t)h->size;
    obj_names o = {h->alloc, NULL, 0, 0, NULL, 0};
    /* current: the object whose mesh takes the faces; meant: the one the
     * file means them for (they differ after a name given again). */
    size_t current = SIZE_MAX, meant = SIZE_MAX, group = SIZE_MAX, p = 0;
    u64 line = 0;
    while (st == PX_OK && p < size) {
        /* A line ends at "\n", "\r\n" or a lone "\r", as Assimp ends them. */
        size_t b = p, e = p;
        while (e < size && t[e] != '\n' && t[e] != '\r') ++e;
        p = e < size && t[e] == '\r' && e + 1 < size && t[e + 1] == '\n' ? e + 2 : e + 1;
        ++line;
        const unsigned char c0 = t[b];
        const int blank = e - b >= 2 && is_blank(t[b + 1]);
        if ((c0 == 'f' || c0 == 'l' || c0 == 'p') && blank && meant != current) {
            st = pxi_error(
                err, PX_ERR_IO,
                "mesh file '%s', line %llu: object '%.*s' (line %llu) continues after object '%.*s' "
                "(line %llu), and Assimp 5.2 would put these faces into the part of '%.*s': give "
                "each object a distinct name, or keep an object's lines together",
                h->path, (unsigned long long)line, (int)o.v[meant].full_len,
                (const char *)t + o.v[meant].full, (unsigned long long)o.v[meant].line,
                (int)o.v[current].full_len, (const char *)t + o.v[current].full,
                (unsigned long long)o.v[current].line, (int)o.v[current].full_len,
                (const char *)t + o.v[current].full);
            break;
        }
        const int is_o = c0 == 'o';
        if (!(is_o || c0 == 'g') || !blank) continue;
        size_t s = b + 2;
        while (s < e && is_blank(t[s])) ++s;
        size_t f = e;
        /* An `o` name is its first word; a `g` name keeps trailing blanks. */
        if (is_o)
            while (f > s && is_blank(t[f - 1])) --f;
        if (f == s) continue;
        size_t key_len = f - s;
        if (is_o)
            for (size_t k = s; k < f; ++k)
                if (is_blank(t[k])) {
                    key_len = k - s;
                    break;
                }
        if (!is_o && group != SIZE_MAX && same(t, o.v[group].key, o.v[group].key_len, s, key_len)) {
            meant = group; /* the active group again: Assimp changes nothing */
            continue;
        }
        size_t found = is_o ? find(&o, t, s, key_len) : SIZE_MAX;
        if (found != SIZE_MAX) {
            if (!same(t, o.v[found].full, o.v[found].full_len, s, f - s)) {
                st = pxi_error(
                    err, PX_ERR_IO,
                    "mesh file '%s', line %llu: object '%.*s' is '%.*s' to Assimp 5.2, as is '%.*s' "
                    "on line %llu (it reads an object name up to its first space and joins "
                    "objects of one name into one part): give each object a distinct name "
                    "without spaces",
                    h->path, (unsigned long long)line, (int)(f - s), (const char *)t + s, (int)key_len,
                    (const char *)t + s, (int)o.v[found].full_len, (const char *)t + o.v[found].full,
                    (unsigned long long)o.v[found].line);
                break;
            }
            meant = found; /* Assimp's current mesh stays current's */
            continue;
        }
        obj_name nm = {s, key_len, s, f - s, line};
        if (!add(&o, t, nm)) {
            st = pxi_error(err, PX_ERR_OUT_OF_MEMORY, "mesh file '%s': out of memory", h->path);
            break;
        }
        current = meant = o.n - 1;
        if (!is_o) group = current;
    }
    pxi_free(h->alloc, o.v, o.cap * sizeof *o.v);
    pxi_free(h->alloc, o.slot, o.slots * sizeof *o.slot);
    pxi_free(h->alloc, t, size + 1);
    return st;
}
