/* An OBJ file as Assimp 5.2's OBJ reader reads it (ObjFileParser and
 * IOStreamBuffer::getNextDataLine, Debian bookworm's 5.2.5), before it
 * does: what it would lose or mix up without a word is refused, with the
 * line.
 *
 * Lines. A line ends at '\n', '\r', '\f' or NUL. A backslash right before
 * the end joins the next line to it: the reader skips to the next '\n'
 * and reads on. A line that starts with blank space is skipped whole (the
 * keyword must come first), and so is the first line after a UTF-8
 * byte-order mark. Refused: a vertex, face, line, point, object or group
 * line so lost; a backslash before a lone '\r', a '\f' or a NUL, or at the
 * file's end (the skip to '\n' would swallow text, or run off the end); a
 * comment whose backslash joins a line with text to it (lost with the
 * comment); a joined line that starts with a keyword (read as more numbers
 * of the line before).
 *
 * Objects. Every part px_mesh_load returns is one of the reader's
 * objects. It keeps a list of objects, each with its own meshes, and a
 * current mesh that takes the faces:
 * - `o NAME` takes the name up to its first blank. A name new to the list
 *   starts an object and makes its mesh current; a name already in it
 *   (from an `o` or a `g`) makes that object current again, but not its
 *   mesh: the faces that follow go on into the mesh that was current.
 * - `g NAME` takes the rest of the line, less its leading blanks. The name
 *   of the active group changes nothing; any other starts a new object
 *   (a name already in the list included) whose mesh becomes current.
 * - `usemtl` may start a mesh of the current object, depending on the
 *   materials before.
 * So `o bolt 1` and `o bolt 2` are one part "bolt", whose halves are never
 * measured against each other, and an object named again after another
 * one gets its later faces in the other's part: one part is left open and
 * the other holds two objects, with PX_OK. Such files are refused, naming
 * both lines: faces, or a `usemtl`, while the object named last is not the
 * one whose mesh is current. The fix is to give each object a distinct
 * name without spaces, or to keep an object's lines together. */
#include <string.h>

#include "core/core.h"
#include "io/scan.h"

typedef struct obj_name {
    const unsigned char *key, *full; /* the name Assimp keeps, the whole name as written */
    size_t key_len, full_len;
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

static int same(const unsigned char *a, size_t an, const unsigned char *b, size_t bn) {
    return an == bn && (an == 0 || memcmp(a, b, an) == 0);
}

/* The first object whose key is k[0 .. n), or SIZE_MAX. */
static size_t find(const obj_names *o, const unsigned char *k, size_t n) {
    if (!o->slots) return SIZE_MAX;
    for (size_t i = name_hash(k, n) & (o->slots - 1);; i = (i + 1) & (o->slots - 1)) {
        uint32_t s = o->slot[i];
        if (!s) return SIZE_MAX;
        if (same(o->v[s - 1].key, o->v[s - 1].key_len, k, n)) return s - 1;
    }
}

static void put_slot(obj_names *o, size_t id) {
    size_t i = name_hash(o->v[id].key, o->v[id].key_len) & (o->slots - 1);
    while (o->slot[i]) i = (i + 1) & (o->slots - 1);
    o->slot[i] = (uint32_t)(id + 1);
}

/* Appends an object; its key enters the hash when new. 0 when out of
 * memory. */
static int add(obj_names *o, obj_name e) {
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
            if (find(o, o->v[i].key, o->v[i].key_len) == SIZE_MAX) put_slot(o, i);
    }
    o->v[o->n] = e;
    if (find(o, e.key, e.key_len) == SIZE_MAX) put_slot(o, o->n);
    o->n++;
    return 1;
}

static int is_blank(unsigned char c) { return c == ' ' || c == '\t'; }
static int is_end(unsigned char c) { return c == '\n' || c == '\r' || c == '\f' || c == '\0'; }

/* The longest word the reader copies whole (its buffer, less the NUL):
 * the rest of a longer one reads as the next word. */
#define OBJ_MAX_WORD 4095

/* IOStreamBuffer's block (its default cache size). */
#define OBJ_BLOCK ((size_t)4096 * 4096)

/* A keyword whose line the reader would lose: v, vt, vn, vp, f, fo, l, p,
 * o, g. */
static int geometry_keyword(const unsigned char *t, size_t b, size_t e) {
    size_t n = 0;
    while (b + n < e && !is_blank(t[b + n])) ++n;
    if (n == 1) return strchr("vflpog", t[b]) != NULL;
    return n == 2 && ((t[b] == 'v' && strchr("tnp", t[b + 1]) != NULL) || (t[b] == 'f' && t[b + 1] == 'o'));
}

/* The editor's line count over t[a, b): "\n", "\r\n" and a lone "\r"
 * each end a line. */
static u64 lines_in(const unsigned char *t, size_t a, size_t b, size_t size) {
    u64 n = 0;
    for (size_t i = a; i < b; ++i) n += t[i] == '\n' || (t[i] == '\r' && !(i + 1 < size && t[i + 1] == '\n'));
    return n;
}

/* What a line holds for the checks of its words. */
enum { W_OTHER, W_VERTEX, W_FACE };

static int lower_is(const unsigned char *t, size_t i, size_t e, const char *w) {
    for (; *w; ++w, ++i)
        if (i >= e || (t[i] | 0x20) != *w) return 0;
    return 1;
}

/* The words of t[b, e) (one piece of a line, its keyword and a joining
 * backslash left out): a vertex line's numbers as Assimp 5.2 counts them
 * (getNumComponentsInDataDefinition: a word that starts with a digit, '-'
 * or '+', or with "nan" or "inf"); a face line's indices written with '+'
 * or leading zeros (getFace steps over the digits of the value it read,
 * not over the text, and reads them again). */
static void scan_words(const unsigned char *t, size_t b, size_t e, int kind, size_t *numbers,
                       int *bad_index) {
    for (size_t i = b; i < e;) {
        while (i < e && is_blank(t[i])) ++i;
        if (i >= e) break;
        size_t w = i;
        while (i < e && !is_blank(t[i])) ++i;
        if (kind != W_OTHER && i - w > OBJ_MAX_WORD) *bad_index = 2;
        if (kind == W_VERTEX) {
            unsigned char c = t[w];
            *numbers += (c >= '0' && c <= '9') || c == '-' || c == '+' || lower_is(t, w, i, "nan") ||
                        lower_is(t, w, i, "inf");
        } else if (kind == W_FACE) {
            if (memchr(t + w, '#', i - w)) *bad_index = 3;
            for (size_t k = w; k < i; ++k) {
                if (k != w && t[k - 1] != '/') continue; /* the start of an index */
                size_t d = k + (t[k] == '-');
                if (t[k] == '+' || (d + 1 < i && t[d] == '0' && t[d + 1] >= '0' && t[d + 1] <= '9'))
                    *bad_index = 1;
            }
        }
    }
}

static px_status refuse(const io_head *h, u64 line, const char *why, px_error *err) {
    return pxi_error(err, PX_ERR_IO, "mesh file '%s', line %llu: %s", h->path, (unsigned long long)line, why);
}

px_status pxi_check_obj(const io_head *h, px_error *err) {
    unsigned char *t;
    px_status st = pxi_read_all(h, &t, err);
    if (st != PX_OK) return st;
    const size_t size = (size_t)h->size;
    obj_names o = {h->alloc, NULL, 0, 0, NULL, 0};
    /* current: the object whose mesh takes the faces; meant: the one the
     * file means them for (they differ after a name given again). */
    size_t current = SIZE_MAX, meant = SIZE_MAX, group = SIZE_MAX, p = 0;
    u64 line = 1; /* the editor's line at p */
    const int bom = size >= 3 && t[0] == 0xEF && t[1] == 0xBB && t[2] == 0xBF;
    /* What a point cloud holds: vertex lines (those with a colour), vn
     * lines (the first one's line), whether a face, line or point line
     * came, the line of the first object an `o` or `g` started. */
    struct {
        u64 v, coloured, vn, vn_line, object_line;
        int elements;
    } cloud = {0, 0, 0, 0, 0, 0};
    while (st == PX_OK && p < size) {
        const size_t b = p;
        const u64 at = line;
        size_t e = b;
        while (e < size && !is_end(t[e])) ++e;
        /* The line's end, and the lines a backslash joins to it; the words
         * of vertex and face lines on the way. */
        size_t q = e, numbers = 0;
        int comment = t[b] == '#', bad_index = 0;
        const int kind =
            t[b] == 'v' && e - b >= 2 && is_blank(t[b + 1]) ? W_VERTEX
            : ((t[b] == 'f' || t[b] == 'l' || t[b] == 'p') && e - b >= 2 && is_blank(t[b + 1])) ||
                    (t[b] == 'f' && e - b >= 3 && t[b + 1] == 'o' && is_blank(t[b + 2]))
                ? W_FACE
                : W_OTHER;
        size_t seg = kind == W_OTHER ? b : b + (t[b + 1] == 'o' ? 2 : 1);
        while (st == PX_OK && q < size && q > b && t[q - 1] == '\\') {
            const size_t bs = q - 1; /* the backslash */
            scan_words(t, seg, bs, kind, &numbers, &bad_index);
            if (!(t[q] == '\n' || (t[q] == '\r' && q + 1 < size && t[q + 1] == '\n'))) {
                st = refuse(h, at + lines_in(t, b, q, size),
                            "a backslash before a line end other than LF or CRLF (Assimp 5.2 would skip "
                            "the text up to the next LF)",
                            err);
                break;
            }
            q += t[q] == '\r' ? 2 : 1;
            size_t nb = q, ne = q;
            while (ne < size && !is_end(t[ne])) ++ne;
            /* The reader copies the byte after the LF unread: an empty
             * line there glues the next one on. */
            if (nb + 1 < size && (t[nb] == '\n' || t[nb] == '\f' || t[nb] == '\0') && !is_end(t[nb + 1])) {
                st =
                    refuse(h, at + lines_in(t, b, nb, size),
                           "a backslash at the end of a line, then an empty line: Assimp 5.2 would join the "
                           "line after it to the first, and lose it (remove the backslash or the empty line)",
                           err);
                break;
            }
            size_t f = nb;
            while (f < ne && is_blank(t[f])) ++f;
            if (comment && f < ne)
                st = refuse(h, at + lines_in(t, b, nb, size),
                            "a comment that ends in a backslash joins this line to it (Assimp 5.2 would skip "
                            "both)",
                            err);
            else if (f < ne && geometry_keyword(t, f, ne))
                st = refuse(h, at + lines_in(t, b, nb, size),
                            "the backslash at the end of the line before joins this line to it (Assimp 5.2 "
                            "would read its keyword as part of that line)",
                            err);
            else if (!comment && nb < ne && !is_blank(t[nb]) && bs > seg && !is_blank(t[bs - 1]))
                st = refuse(h, at + lines_in(t, b, nb, size),
                            "the backslash at the end of the line before joins a word of it to the first "
                            "word of this one (Assimp 5.2 reads them as one): put a space before the "
                            "backslash",
                            err);
            seg = nb;
            q = ne;
        }
        if (st == PX_OK) scan_words(t, seg, q, kind, &numbers, &bad_index);
        if (st != PX_OK) break;
        if (q >= size && q > b && t[q - 1] == '\\') {
            st = refuse(h, at + lines_in(t, b, q, size),
                        "the file ends in a backslash (Assimp 5.2 would read past its end)", err);
            break;
        }
        /* Past the line end. */
        p = q < size ? q + 1 : size;
        line = at + lines_in(t, b, p, size);
        if (bom && b == 0) {
            size_t f = 3;
            while (f < e && is_blank(t[f])) ++f;
            if (f < e && t[f] != '#') {
                st = refuse(h, at,
                            "the file starts with a byte-order mark, and Assimp 5.2 skips the line it is "
                            "on: save it without one, or begin with a comment",
                            err);
                break;
            }
            continue;
        }
        if (is_blank(t[b])) {
            size_t f = b;
            while (f < e && is_blank(t[f])) ++f;
            if (f < e && geometry_keyword(t, f, e)) {
                st = refuse(h, at,
                            "a line that starts with blank space (Assimp 5.2 skips it whole: an indented "
                            "vertex, face or object would be lost)",
                            err);
                break;
            }
            continue;
        }
        if (kind == W_VERTEX && numbers != 3 && numbers != 4 && numbers != 6) {
            st = pxi_error(
                err, PX_ERR_IO,
                "mesh file '%s', line %llu: a vertex line of %zu numbers, as Assimp 5.2 counts them "
                "(a word that starts with a digit, a sign, \"nan\" or \"inf\"; .5 is not one): it "
                "reads 3 (x y z), 4 (x y z w) or 6 (x y z r g b) and would drop this vertex, "
                "shifting every later index",
                h->path, (unsigned long long)at, numbers);
            break;
        }
        if (kind == W_VERTEX) {
            ++cloud.v;
            cloud.coloured += numbers == 6;
        } else if (kind == W_FACE) {
            cloud.elements = 1;
        } else if (t[b] == 'v' && e - b >= 3 && t[b + 1] == 'n' && is_blank(t[b + 2])) {
            ++cloud.vn;
            if (!cloud.vn_line) cloud.vn_line = at;
        }
        if (bad_index == 2) {
            st = refuse(h, at,
                        "a word of more than 4095 bytes on a vertex or face line (Assimp 5.2 would read its "
                        "rest as the next number)",
                        err);
            break;
        }
        if (kind == W_FACE && bad_index == 3) {
            st = refuse(h, at,
                        "a comment after a face, line or point (Assimp 5.2 reads its '#' as an index and "
                        "fails: put the comment on a line of its own)",
                        err);
            break;
        }
        if (kind == W_FACE && bad_index) {
            st = refuse(h, at,
                        "a face index written with '+' or leading zeros (Assimp 5.2 would read its digits "
                        "twice)",
                        err);
            break;
        }
        if (e - b >= 6 && memcmp(t + b, "cstype", 6) == 0 && (e - b == 6 || is_blank(t[b + 6]))) {
            st = refuse(h, at,
                        "free-form geometry (cstype ... end): Assimp 5.2 skips it, with every vertex and "
                        "face line inside",
                        err);
            break;
        }
        const unsigned char c0 = t[b];
        const int blank = e - b >= 2 && is_blank(t[b + 1]);
        const int usemtl =
            e - b >= 6 && memcmp(t + b, "usemtl", 6) == 0 && (e - b == 6 || is_blank(t[b + 6]));
        if (kind == W_FACE && current == SIZE_MAX) {
            /* Faces before any object: Assimp starts one named
             * "defaultobject", which a later `o` can name again. */
            static const unsigned char dflt[] = "defaultobject";
            obj_name nm = {dflt, dflt, sizeof dflt - 1, sizeof dflt - 1, at};
            if (!add(&o, nm)) {
                st = pxi_error(err, PX_ERR_OUT_OF_MEMORY, "mesh file '%s': out of memory", h->path);
                break;
            }
            current = meant = o.n - 1;
        }
        if (kind == W_FACE || usemtl) {
            if (meant != current && usemtl)
                st = pxi_error(
                    err, PX_ERR_IO,
                    "mesh file '%s', line %llu: object '%.*s' (line %llu) is named again after "
                    "object '%.*s' (line %llu), and with a material starting here Assimp 5.2 may put "
                    "the faces that follow into either part: give each object a distinct name, or "
                    "keep an object's lines together",
                    h->path, (unsigned long long)at, (int)o.v[meant].full_len, (const char *)o.v[meant].full,
                    (unsigned long long)o.v[meant].line, (int)o.v[current].full_len,
                    (const char *)o.v[current].full, (unsigned long long)o.v[current].line);
            else if (meant != current)
                st = pxi_error(
                    err, PX_ERR_IO,
                    "mesh file '%s', line %llu: object '%.*s' (line %llu) continues after object "
                    "'%.*s' (line %llu), and Assimp 5.2 would put the faces from here into the part "
                    "of '%.*s': give each object a distinct name, or keep an object's lines together",
                    h->path, (unsigned long long)at, (int)o.v[meant].full_len, (const char *)o.v[meant].full,
                    (unsigned long long)o.v[meant].line, (int)o.v[current].full_len,
                    (const char *)o.v[current].full, (unsigned long long)o.v[current].line,
                    (int)o.v[current].full_len, (const char *)o.v[current].full);
            if (st != PX_OK) break;
            continue;
        }
        const int is_o = c0 == 'o';
        /* A bare `g` names the group "" (Assimp starts an object so named). */
        if (!(is_o && blank) && !(c0 == 'g' && (blank || e - b == 1))) continue;
        size_t s = b + 1; /* past the keyword (a bare `g` has nothing after it) */
        while (s < e && is_blank(t[s])) ++s;
        size_t f = e;
        /* An `o` name is its first word; a `g` name keeps trailing blanks. */
        if (is_o)
            while (f > s && is_blank(t[f - 1])) --f;
        if (f == s && is_o) continue; /* Assimp ignores an `o` without a name */
        size_t key_len = f - s;
        if (is_o)
            for (size_t k = s; k < f; ++k)
                if (is_blank(t[k])) {
                    key_len = k - s;
                    break;
                }
        /* The active group named again changes nothing (the faces go on
         * into the current object's mesh, as the file's last `o` means). */
        if (!is_o &&
            (group != SIZE_MAX ? same(o.v[group].key, o.v[group].key_len, t + s, key_len) : key_len == 0))
            continue; /* (the active group starts as "") */
        size_t found = is_o ? find(&o, t + s, key_len) : SIZE_MAX;
        if (found != SIZE_MAX) {
            if (!same(o.v[found].full, o.v[found].full_len, t + s, f - s)) {
                st = pxi_error(
                    err, PX_ERR_IO,
                    "mesh file '%s', line %llu: object '%.*s' is '%.*s' to Assimp 5.2, as is '%.*s' "
                    "on line %llu (it reads an object name up to its first space and joins "
                    "objects of one name into one part): give each object a distinct name "
                    "without spaces",
                    h->path, (unsigned long long)at, (int)(f - s), (const char *)t + s, (int)key_len,
                    (const char *)t + s, (int)o.v[found].full_len, (const char *)o.v[found].full,
                    (unsigned long long)o.v[found].line);
                break;
            }
            meant = found; /* Assimp's current mesh stays current's */
            continue;
        }
        obj_name nm = {t + s, t + s, key_len, f - s, at};
        if (!add(&o, nm)) {
            st = pxi_error(err, PX_ERR_OUT_OF_MEMORY, "mesh file '%s': out of memory", h->path);
            break;
        }
        current = meant = o.n - 1;
        if (!is_o) group = current;
        if (!cloud.object_line) cloud.object_line = at;
    }
    /* A point cloud (vertices, no f, l or p line): Assimp 5.2 makes one
     * mesh of all vertices only when no `o` or `g` started an object (else
     * its objects have no faces, and the scene no mesh), and throws when
     * some but not all vertices have a normal (vn lines, which it pairs
     * with the vertices in order) or a colour. The file is valid OBJ, but
     * Assimp cannot read it: refused with the line and the way out. */
    if (st == PX_OK && cloud.v && !cloud.elements) {
        if (cloud.object_line)
            st = refuse(h, cloud.object_line,
                        "an object or group in a point cloud (vertices, no f, l or p line): Assimp 5.2 reads "
                        "the vertices into no mesh (remove the o and g lines)",
                        err);
        else if (cloud.vn && cloud.vn < cloud.v)
            st = pxi_error(err, PX_ERR_IO,
                           "mesh file '%s', line %llu: a point cloud (vertices, no f, l or p line) of %llu "
                           "vertices and %llu vn lines: Assimp 5.2 refuses one with fewer normals than "
                           "vertices (remove the vn lines)",
                           h->path, (unsigned long long)cloud.vn_line, (unsigned long long)cloud.v,
                           (unsigned long long)cloud.vn);
        else if (cloud.coloured && cloud.coloured < cloud.v)
            st = pxi_error(
                err, PX_ERR_IO,
                "mesh file '%s': a point cloud (vertices, no f, l or p line) where %llu of its %llu "
                "vertices have a colour (6 numbers): Assimp 5.2 refuses one unless all or none "
                "have (remove the colours)",
                h->path, (unsigned long long)cloud.coloured, (unsigned long long)cloud.v);
    }
    /* Assimp reads the file in blocks of 16 MiB, and in a file of more
     * than one it drops a last line that no line end closes. */
    if (st == PX_OK && size >= OBJ_BLOCK && !is_end(t[size - 1])) {
        size_t b = size;
        while (b > 0 && !is_end(t[b - 1])) --b;
        while (b < size && is_blank(t[b])) ++b;
        if (b < size)
            st = refuse(h, line,
                        "the last line has no line end, and Assimp 5.2 drops such a line in a file of more "
                        "than 16 MiB: end the file with a newline",
                        err);
    }
    pxi_free(h->alloc, o.v, o.cap * sizeof *o.v);
    pxi_free(h->alloc, o.slot, o.slots * sizeof *o.slot);
    pxi_free(h->alloc, t, size + 1);
    return st;
}
