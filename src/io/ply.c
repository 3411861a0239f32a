/* PLY files, checked the way Assimp 5.2.5 reads them (PlyLoader.cpp,
 * PlyParser.cpp, IOStreamBuffer.h; Debian bookworm's 5.2.5~ds0).
 *
 * Why an emulation rather than a PLY parser. Assimp's PLY importer is
 * chosen for any file whose first line starts with "ply" (any case, anything
 * after it: "plyx" is accepted) once its name does not pick another
 * importer, and it reads the header through an IOStreamBuffer and a
 * std::vector<char> "line" from whose front every token test erases. Its
 * loops end only at an "end_header" token: at the end of the file
 * getNextLine fails and leaves the vector as it was, so a header without one
 * loops forever (on the last line, or pushing the same property again and
 * again). A "comment" line leaves the vector at the bytes behind the line,
 * remnants of earlier, longer lines, which are then parsed as header lines;
 * a line-end byte other than '\n' ('\r', NUL, form feed) makes getNextLine
 * skip up to the next '\n' without refilling its cache, so it reads past the
 * cache. The elements Assimp sees, and where its body starts, are what
 * matters for what it allocates, so they are computed by the same steps on
 * the same bytes (ply_header below mirrors PLY::DOM::ParseHeader line for
 * line), and anything Assimp would read outside its data is refused.
 *
 * The body is then walked as Assimp walks it, before Assimp runs:
 * - binary: every record must lie within the file (Assimp reads on past the
 *   end, into a cache refilled with '\n' bytes or stale data, and takes list
 *   lengths from there); a list length is read as Assimp converts it
 *   (signed counts become huge unsigned ones), and Assimp resizes the list
 *   to it before reading a value, so it must fit in the bytes left and in
 *   PX_IO_MAX_PLY_LIST;
 * - ascii: one record per line (getNextLine); every value must be a token
 *   Assimp's parser consumes whole (strtoul10, strtol10, fast_atoreal_move),
 *   so that our tokens are its tokens, and a record may not need more values
 *   than its line holds: after the last one Assimp skips the line break and
 *   reads on into the vector's stale bytes.
 * The walk reads each byte once: its time is linear in the file size, which
 * is capped.
 *
 * Also refused, because Assimp 5.2 writes out of bounds there: a second
 * vertex element, or a second face or tristrips element (LoadVertex and
 * LoadFace size their arrays by the first and index them by the record
 * number of the later one), and a face whose texcoord list holds 6 to 8
 * values while its vertex_indices list has too few entries for them
 * (LoadFace reads mIndices[a / 2] for every texcoord value a). */
#include "io/scan.h"

#include <stdio.h>
#include <string.h>

#include "core/core.h"

#define PLY_CACHE (1u << 20)    /* IOStreamBuffer<char> streamedBuffer(1024 * 1024) */
#define PLY_MAX_ELEMENTS 64     /* element declarations accepted */
#define PLY_MAX_PROPERTIES 1024 /* property declarations accepted, in total */
/* getNextLine calls while reading the header: each takes a byte at least,
 * so the head's bound implies this one. Assimp's cost per header line is
 * several copies of its line vector (the cache size, up to 1 MiB): 7000
 * comment lines took it 0.4 s, measured. */
#define PLY_MAX_HEADER_LINES PXI_IO_HEAD_BYTES

/* Assimp's PLY::EDataType, in its order. */
enum { T_INVALID, T_CHAR, T_UCHAR, T_SHORT, T_USHORT, T_INT, T_UINT, T_FLOAT, T_DOUBLE };
static const unsigned k_type_size[] = {0, 1, 1, 2, 2, 4, 4, 4, 8};

/* The element semantics that matter here (PLY::EElementSemantic). */
enum { E_INVALID, E_VERTEX, E_FACE, E_TRISTRIP, E_OTHER, E_TEXTUREFILE };
/* Property semantics that matter here. */
enum { S_OTHER, S_VERTEX_INDEX, S_TEXCOORD };

typedef struct ply_prop {
    unsigned char list, first, type, sem;
} ply_prop;

typedef struct ply_elem {
    int sem;
    unsigned count; /* NumOccur, as Assimp's strtoul10 reads it (32-bit, wrapping) */
    u64 declared;   /* the same digits, saturated: for the limits and messages */
    size_t prop0, nprop;
    char name[40];
} ply_elem;

/* Assimp's IOStreamBuffer<char> over the file. */
typedef struct ply_sb {
    io_reader *rd;
    u64 filesize;
    size_t cache_size;    /* m_cacheSize */
    unsigned char *cache; /* m_cache: PLY_CACHE bytes, '\n' where nothing was read */
    size_t pos;           /* m_cachePos */
    u64 file_pos;         /* m_filePos */
    int oob;              /* Assimp would read outside its cache */
    int rd_error;
} ply_sb;

/* A std::vector<char> from whose front bytes are erased: the logical
 * vector is mem[off, off + n). Reading past n sets `past` (Assimp would
 * read past the vector's end). */
typedef struct ply_vec {
    unsigned char *mem;
    size_t cap, off, n;
    int past, oom;
} ply_vec;

typedef struct ply_state {
    const io_head *h;
    const px_allocator *alloc;
    ply_sb sb;
    ply_vec v;
    ply_elem elem[PLY_MAX_ELEMENTS];
    size_t nelem;
    ply_prop prop[PLY_MAX_PROPERTIES];
    size_t nprop;
    size_t line_len;  /* bytes the last getNextLine wrote before its '\n' */
    int too_many;     /* more declarations than the arrays above hold */
    int too_long;     /* the header goes past PXI_IO_HEAD_BYTES */
    int bad_property; /* a "property" line Assimp rejects (unknown type, no name) */
    unsigned lines;   /* getNextLine calls while reading the header */
} ply_state;

/* ------------------------------------------------------------ the vector */

static int vec_reserve(ply_state *s, size_t need) {
    ply_vec *v = &s->v;
    if (v->off + need <= v->cap) return 1;
    if (need <= v->cap) { /* compact: the erased front is free again */
        memmove(v->mem, v->mem + v->off, v->n);
        v->off = 0;
        return 1;
    }
    size_t cap = v->cap ? v->cap : 4096;
    while (cap < need) cap *= 2;
    unsigned char *mem = pxi_alloc(s->alloc, cap);
    if (!mem) {
        v->oom = 1;
        return 0;
    }
    if (v->n) memcpy(mem, v->mem + v->off, v->n);
    if (v->mem) pxi_free(s->alloc, v->mem, v->cap);
    v->mem = mem;
    v->cap = cap;
    v->off = 0;
    return 1;
}

/* std::vector<char>::resize: new bytes are zero. */
static int vec_resize(ply_state *s, size_t m) {
    ply_vec *v = &s->v;
    if (m > v->n) {
        if (!vec_reserve(s, m)) return 0;
        memset(v->mem + v->off + v->n, 0, m - v->n);
    }
    v->n = m;
    return 1;
}

static int vec_at(ply_vec *v, size_t i) {
    if (i >= v->n) {
        v->past = 1;
        return 0;
    }
    return v->mem[v->off + i];
}

static void vec_erase(ply_vec *v, size_t k) {
    if (k > v->n) k = v->n;
    v->off += k;
    v->n -= k;
}

/* ----------------------------------------------- Assimp's ParsingUtils.h */

static int is_line_end(int c) { return c == '\r' || c == '\n' || c == '\0' || c == '\f'; }
static int is_space(int c) { return c == ' ' || c == '\t'; }

/* The PLY::DOM helpers, each on the vector's front at cursor *i (the
 * erasure is applied by the caller, so that SkipComments can work on a
 * copy). */
static int cur_skip_spaces(ply_vec *v, size_t *i) {
    while (is_space(vec_at(v, *i))) ++*i;
    return !is_line_end(vec_at(v, *i));
}
static int cur_skip_line(ply_vec *v, size_t *i) {
    int c;
    while ((c = vec_at(v, *i)) != '\r' && c != '\n' && c != '\0') ++*i;
    while ((c = vec_at(v, *i)) == '\r' || c == '\n') ++*i;
    return vec_at(v, *i) != 0;
}
static int cur_skip_spaces_and_line_end(ply_vec *v, size_t *i) {
    int c;
    while ((c = vec_at(v, *i)) == ' ' || c == '\t' || c == '\r' || c == '\n') ++*i;
    return vec_at(v, *i) != 0;
}
/* TokenMatch: strncmp(token, in, len) == 0 and a blank or line end follows;
 * consumes the token and that byte (not a NUL). */
static int cur_token(ply_vec *v, size_t *i, const char *token) {
    size_t len = strlen(token);
    for (size_t k = 0; k < len; ++k)
        if (vec_at(v, *i + k) != (unsigned char)token[k]) return 0;
    int after = vec_at(v, *i + len);
    if (!is_space(after) && !is_line_end(after)) return 0;
    *i += after ? len + 1 : len;
    return 1;
}

/* The vector-level helpers: run at the front, then erase. */
static int v_skip_spaces(ply_vec *v) {
    size_t i = 0;
    int r = cur_skip_spaces(v, &i);
    vec_erase(v, i);
    return r;
}
static int v_skip_line(ply_vec *v) {
    size_t i = 0;
    int r = cur_skip_line(v, &i);
    vec_erase(v, i);
    return r;
}
static int v_skip_spaces_and_line_end(ply_vec *v) {
    size_t i = 0;
    int r = cur_skip_spaces_and_line_end(v, &i);
    vec_erase(v, i);
    return r;
}
static int v_token(ply_vec *v, const char *token) {
    size_t i = 0;
    int r = cur_token(v, &i, token);
    vec_erase(v, i);
    return r;
}

/* PLY::DOM::SkipComments: works on a copy, and only on "comment" not
 * followed by "TextureFile" takes the copy (cut after the line) back. */
static int v_skip_comments(ply_vec *v) {
    size_t i = 0;
    if (!cur_skip_spaces(v, &i)) return 0;
    if (!cur_token(v, &i, "comment")) return 0;
    if (!cur_skip_spaces(v, &i)) cur_skip_line(v, &i);
    size_t j = i;
    if (!cur_token(v, &j, "TextureFile")) {
        cur_skip_line(v, &i);
        vec_erase(v, i);
    }
    return 1;
}

/* strtoul10 at the front (no erasure), 32-bit wrapping; *sat gets the value
 * saturated instead. */
static unsigned v_strtoul10(ply_vec *v, u64 *sat) {
    unsigned val = 0;
    u64 s = 0;
    for (size_t i = 0;; ++i) {
        int c = vec_at(v, i);
        if (c < '0' || c > '9') break;
        val = val * 10u + (unsigned)(c - '0');
        s = pxi_sat_add(pxi_sat_mul(s, 10), (u64)(c - '0'));
    }
    *sat = s;
    return val;
}

/* ------------------------------------------------ Assimp's IOStreamBuffer */

static int sb_at(ply_sb *b, size_t i) {
    if (i >= PLY_CACHE) {
        b->oob = 1;
        return '\n';
    }
    return b->cache[i];
}

/* readNextBlock: Seek(m_filePos), Read(m_cacheSize bytes); a short read
 * shrinks m_cacheSize for good. */
static int sb_next_block(ply_sb *b) {
    u64 left = b->filesize > b->file_pos ? b->filesize - b->file_pos : 0;
    size_t n = left < b->cache_size ? (size_t)left : b->cache_size;
    if (n == 0) return 0;
    pxi_rd_seek(b->rd, b->file_pos);
    if (!pxi_rd_read(b->rd, b->cache, n)) {
        b->rd_error = 1;
        return 0;
    }
    b->cache_size = n;
    b->file_pos += n;
    b->pos = 0;
    return 1;
}

/* IOStreamBuffer::getNextLine into the vector (its return value, which
 * Assimp ignores everywhere here). Sets b->oob where Assimp's cache index
 * passes the data it holds: the skip of a line end other than '\n' looks
 * for the next '\n' without refilling, and once m_cachePos is past
 * m_cacheSize no block is read again. */
static int sb_next_line(ply_state *s) {
    ply_sb *b = &s->sb;
    ply_vec *v = &s->v;
    s->line_len = 0;
    if (!vec_resize(s, b->cache_size)) return 0;
    if (b->pos == b->cache_size || b->file_pos == 0) {
        if (!sb_next_block(b)) return 0;
    }
    if (is_line_end(sb_at(b, b->pos))) {
        while (sb_at(b, b->pos) != '\n') ++b->pos;
        ++b->pos;
        if (b->pos > b->cache_size) b->oob = 1;
        if (b->oob) return 0;
        if (b->pos == b->cache_size && !sb_next_block(b)) return 0;
    }
    size_t i = 0;
    while (!is_line_end(sb_at(b, b->pos))) {
        v->mem[v->off + i] = b->cache[b->pos];
        ++b->pos;
        s->line_len = ++i;
        if (i == v->n && !vec_resize(s, v->n * 2)) return 0;
        if (b->pos >= b->cache_size && !sb_next_block(b)) return 0;
    }
    if (b->oob) return 0;
    v->mem[v->off + i] = '\n';
    ++b->pos;
    return 1;
}

/* File offset of the stream's next byte. */
static u64 sb_offset(const ply_sb *b) { return b->file_pos - b->cache_size + b->pos; }

/* getNextLine while reading the header: counts the lines and keeps the
 * header within the head. Returns 0 where Assimp's loop would not end. */
static int header_line(ply_state *s) {
    if (++s->lines > PLY_MAX_HEADER_LINES) return 0;
    if (!sb_next_line(s)) return 0;
    if (sb_offset(&s->sb) > PXI_IO_HEAD_BYTES) {
        s->too_long = 1;
        return 0;
    }
    return 1;
}

/* ------------------------------------------------------------ the header */

/* PLY::Property::ParseDataType: consumes a known type name. */
static int parse_type(ply_vec *v) {
    static const struct {
        const char *name;
        int type;
    } names[] = {{"char", T_CHAR},     {"int8", T_CHAR},     {"uchar", T_UCHAR},     {"uint8", T_UCHAR},
                 {"short", T_SHORT},   {"int16", T_SHORT},   {"ushort", T_USHORT},   {"uint16", T_USHORT},
                 {"int32", T_INT},     {"int", T_INT},       {"uint32", T_UINT},     {"uint", T_UINT},
                 {"float", T_FLOAT},   {"float32", T_FLOAT}, {"double64", T_DOUBLE}, {"double", T_DOUBLE},
                 {"float64", T_DOUBLE}};
    for (size_t k = 0; k < sizeof names / sizeof names[0]; ++k)
        if (v_token(v, names[k].name)) return names[k].type;
    return T_INVALID;
}

/* PLY::Property::ParseSemantic: consumes a known name (in Assimp's order),
 * or skips the line for an unknown one. */
static int parse_property_semantic(ply_vec *v) {
    static const char *const known[] = {"red",
                                        "green",
                                        "blue",
                                        "alpha",
                                        "vertex_index",
                                        "vertex_indices",
                                        "texcoord",
                                        "material_index",
                                        "ambient_red",
                                        "ambient_green",
                                        "ambient_blue",
                                        "ambient_alpha",
                                        "diffuse_red",
                                        "diffuse_green",
                                        "diffuse_blue",
                                        "diffuse_alpha",
                                        "specular_red",
                                        "specular_green",
                                        "specular_blue",
                                        "specular_alpha",
                                        "opacity",
                                        "specular_power",
                                        "r",
                                        "g",
                                        "b",
                                        "u",
                                        "s",
                                        "tx",
                                        "texture_u",
                                        "v",
                                        "t",
                                        "ty",
                                        "texture_v",
                                        "x",
                                        "y",
                                        "z",
                                        "nx",
                                        "ny",
                                        "nz"};
    for (size_t k = 0; k < sizeof known / sizeof known[0]; ++k) {
        if (v_token(v, known[k])) {
            if (k == 4 || k == 5) return S_VERTEX_INDEX;
            if (k == 6) return S_TEXCOORD;
            return S_OTHER;
        }
    }
    v_skip_line(v);
    return S_OTHER;
}

/* PLY::Property::ParseProperty. A line that starts with "property" but is
 * rejected sets bad_property: Assimp would drop that property and the rest
 * of the element's, and read the body with another layout. */
static int parse_property(ply_state *s, ply_prop *p) {
    ply_vec *v = &s->v;
    memset(p, 0, sizeof *p);
    if (!v_skip_spaces(v)) return 0;
    if (!v_token(v, "property")) return 0;
    s->bad_property = 1;
    if (!v_skip_spaces(v)) return 0;
    if (v_token(v, "list")) {
        p->list = 1;
        if ((p->first = (unsigned char)parse_type(v)) == T_INVALID) return v_skip_line(v), 0;
        if (!v_skip_spaces(v)) return 0;
        if ((p->type = (unsigned char)parse_type(v)) == T_INVALID) return v_skip_line(v), 0;
    } else if ((p->type = (unsigned char)parse_type(v)) == T_INVALID) {
        return v_skip_line(v), 0;
    }
    if (!v_skip_spaces(v)) return 0;
    p->sem = (unsigned char)parse_property_semantic(v);
    v_skip_spaces_and_line_end(v);
    s->bad_property = 0;
    return 1;
}

/* The element name for messages: the token at the vector's front. */
static void elem_name(ply_vec *v, char *out, size_t size) {
    size_t k = 0;
    for (; k + 1 < size && k < v->n && v->mem[v->off + k] > ' ' && v->mem[v->off + k] < 127; ++k)
        out[k] = (char)v->mem[v->off + k];
    out[k] = '\0';
}

/* PLY::Element::ParseElement, with its property loop. Returns 1 when an
 * element was added, 0 when the line is not one; -1 when Assimp would not
 * end (getNextLine at the end of the file) or a limit was hit. */
static int parse_element(ply_state *s) {
    ply_vec *v = &s->v;
    if (!v_skip_spaces(v)) return 0;
    if (!v_token(v, "element") && !v_token(v, "comment")) return 0;
    if (!v_skip_spaces(v)) return 0;
    if (s->nelem == PLY_MAX_ELEMENTS) {
        s->too_many = 1;
        return -1;
    }
    ply_elem *e = &s->elem[s->nelem];
    memset(e, 0, sizeof *e);
    elem_name(v, e->name, sizeof e->name);
    static const char *const sems[] = {"vertex", "face", "tristrips", "edge", "material", "TextureFile"};
    static const int codes[] = {E_VERTEX, E_FACE, E_TRISTRIP, E_OTHER, E_OTHER, E_TEXTUREFILE};
    e->sem = E_INVALID;
    for (size_t k = 0; k < 6 && e->sem == E_INVALID; ++k)
        if (v_token(v, sems[k])) e->sem = codes[k];
    if (e->sem == E_INVALID) { /* szName = strlen(buffer): a NUL must follow */
        size_t k = 0;
        while (vec_at(v, k)) ++k;
    }
    if (!v_skip_spaces(v)) return 0;
    e->prop0 = s->nprop;
    ++s->nelem;
    if (e->sem == E_TEXTUREFILE) {
        v_skip_spaces_and_line_end(v);
        return 1;
    }
    e->count = v_strtoul10(v, &e->declared);
    if (e->sem == E_INVALID) {
        /* Assimp does not consume an unknown element's name, so it reads its
         * count as 0 (or as the name's leading digits). The size check still
         * takes the count the header declares after the name. */
        size_t k = 0;
        int c, past = v->past;
        while ((c = vec_at(v, k)) > ' ') ++k;
        while (is_space(vec_at(v, k))) ++k;
        u64 d = 0;
        while ((c = vec_at(v, k)) >= '0' && c <= '9')
            d = pxi_sat_add(pxi_sat_mul(d, 10), (u64)(c - '0')), ++k;
        v->past = past; /* for the size check only: not a read of Assimp's */
        if (d > e->declared) e->declared = d;
    }
    v_skip_spaces_and_line_end(v);
    for (;;) {
        if (!header_line(s)) return -1;
        v_skip_comments(v);
        ply_prop p;
        if (!parse_property(s, &p)) break;
        if (s->nprop == PLY_MAX_PROPERTIES) {
            s->too_many = 1;
            return -1;
        }
        s->prop[s->nprop++] = p;
        ++e->nprop;
    }
    return s->bad_property ? -1 : 1;
}

/* The header as the PLY format defines it, against the elements Assimp
 * read (ply_header): "element NAME N" starts an element, "property ..."
 * adds to the last one, "comment" and "obj_info" lines are nothing.
 * Assimp reads a comment line among an element's properties as an element
 * of its own (and, with the stale bytes a short line leaves, more), which
 * takes the properties after it: review s29's "property y / comment /
 * property z" gave vertices without z, with PX_OK. Compared: the number of
 * elements that have properties, and each one's count and property count
 * (Assimp's comment "elements" have none unless they took some). Returns 1
 * when they agree. */
static int header_as_defined(const ply_state *s) {
    const unsigned char *t = s->h->data;
    const size_t n = s->h->len;
    size_t k = 0; /* Assimp's next element with properties */
    size_t props = 0;
    u64 count = 0;
    int open = 0;
    for (size_t b = 0; b < n;) {
        size_t e = b;
        while (e < n && t[e] != '\n') ++e;
        size_t q = b;
        while (q < e && (t[q] == ' ' || t[q] == '\t')) ++q;
        const int element =
            e - q > 8 && memcmp(t + q, "element", 7) == 0 && (t[q + 7] == ' ' || t[q + 7] == '\t');
        const int property =
            e - q > 9 && memcmp(t + q, "property", 8) == 0 && (t[q + 8] == ' ' || t[q + 8] == '\t');
        const int end = e - q >= 10 && memcmp(t + q, "end_header", 10) == 0;
        if ((element || end) && open && props > 0) {
            while (k < s->nelem && s->elem[k].nprop == 0) ++k;
            if (k == s->nelem || s->elem[k].nprop != props || s->elem[k].declared != count) return 0;
            ++k;
        }
        if (end) {
            while (k < s->nelem && s->elem[k].nprop == 0) ++k;
            return k == s->nelem;
        }
        if (element) {
            open = 1, props = 0, count = 0;
            size_t c = q + 8;
            while (c < e && (t[c] == ' ' || t[c] == '\t')) ++c;
            while (c < e && t[c] != ' ' && t[c] != '\t') ++c; /* the name */
            while (c < e && (t[c] == ' ' || t[c] == '\t')) ++c;
            while (c < e && t[c] >= '0' && t[c] <= '9')
                count = pxi_sat_add(pxi_sat_mul(count, 10), (u64)(t[c++] - '0'));
        } else if (property && open) {
            ++props;
        }
        b = e + 1;
    }
    return 0;
}

/* PLYImporter::InternReadFile up to the header's end, and
 * PLY::DOM::ParseHeader. Returns PX_OK with *format = 0 when Assimp's PLY
 * importer would refuse the file before reading a header (no "ply" magic
 * line, no known format: nothing to check), 1 ascii, 2 binary little
 * endian, 3 binary big endian. */
static px_status ply_header(ply_state *s, int *format, px_error *err) {
    const io_head *h = s->h;
    ply_sb *b = &s->sb;
    ply_vec *v = &s->v;
    *format = 0;
    /* The magic line (the caller saw "ply" at its start), then the format
     * line, each in a fresh vector; the format line is read by pointer. */
    (void)sb_next_line(s);
    if (b->oob || b->rd_error || v->oom) goto stream_error;
    v->n = v->off = 0;
    (void)sb_next_line(s);
    if (b->oob || b->rd_error || v->oom) goto stream_error;
    size_t i = 0;
    cur_skip_spaces_and_line_end(v, &i);
    if (!cur_token(v, &i, "format")) return PX_OK;
    if (cur_token(v, &i, "ascii")) {
        *format = 1;
    } else {
        static const char binary[] = "binary_";
        for (size_t k = 0; k < 7; ++k)
            if (vec_at(v, i + k) != binary[k]) return PX_OK;
        int c = vec_at(v, i + 7);
        *format = c == 'b' || c == 'B' ? 3 : 2; /* isBigEndian() */
    }
    if (v->past) goto past;
    /* DOM::ParseInstance(Binary): a fresh vector, one line, ParseHeader. */
    v->n = v->off = 0;
    s->lines = 2;
    if (!header_line(s)) goto no_end;
    for (;;) {
        if (v->n == 0) break; /* while (!buffer.empty()) */
        v_skip_comments(v);
        int r = parse_element(s);
        if (r < 0) goto no_end;
        if (r == 0) {
            if (v_token(v, "end_header")) break;
            if (!header_line(s)) goto no_end;
        }
        if (v->past) goto past;
    }
    if (v->past) goto past;
    return PX_OK;

no_end:
    if (v->oom) return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "out of memory reading mesh file '%s'", h->path);
    if (b->rd_error) return pxi_rd_error(h, err);
    if (s->too_many)
        return pxi_error(err, PX_ERR_IO,
                         "mesh file '%s': the PLY header declares more than %d elements or %d "
                         "properties",
                         h->path, PLY_MAX_ELEMENTS, PLY_MAX_PROPERTIES);
    if (s->bad_property)
        return pxi_error(err, PX_ERR_IO,
                         "mesh file '%s': a PLY property has a type Assimp does not read, or no name",
                         h->path);
    if (b->oob) goto stream_error;
    if (v->past) goto past;
    if (s->lines > PLY_MAX_HEADER_LINES) s->too_long = 1;
    if (s->too_long)
        return pxi_error(err, PX_ERR_IO,
                         "mesh file '%s': the PLY header does not end within its first %d bytes", h->path,
                         PXI_IO_HEAD_BYTES);
    return pxi_error(err, PX_ERR_IO,
                     "mesh file '%s': the PLY header has no end_header line that Assimp 5.2 reads (it would "
                     "loop forever)",
                     h->path);
stream_error:
    if (v->oom) return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "out of memory reading mesh file '%s'", h->path);
    if (b->rd_error) return pxi_rd_error(h, err);
    return pxi_error(err, PX_ERR_IO,
                     "mesh file '%s': a PLY header line ends in '\\r', NUL or form feed without a following "
                     "'\\n', which Assimp 5.2 misreads (it reads past its buffer)",
                     h->path);
past:
    return pxi_error(err, PX_ERR_IO,
                     "mesh file '%s': the PLY header makes Assimp 5.2 read past its line buffer", h->path);
}

/* ------------------------------------------------------------- the body */

/* Plural noun for an element's records in messages. */
static void elem_noun(const ply_elem *e, char *out, size_t size) {
    if (e->sem == E_VERTEX)
        snprintf(out, size, "vertices");
    else if (e->sem == E_FACE)
        snprintf(out, size, "faces");
    else
        snprintf(out, size, "'%s' elements", e->name);
}

/* The size check of the header alone: each record at its smallest (lists
 * empty; ascii: one digit and one separator per value), and the total of
 * the declared records. */
static px_status ply_sizes(ply_state *s, int binary, u64 body, px_error *err) {
    const io_head *h = s->h;
    u64 avail = body < h->size ? h->size - body : 0, need = 0, total = 0;
    for (size_t k = 0; k < s->nelem; ++k) {
        const ply_elem *e = &s->elem[k];
        u64 bytes = 0, values = 0;
        for (size_t p = e->prop0; p < e->prop0 + e->nprop; ++p) {
            bytes += k_type_size[s->prop[p].list ? s->prop[p].first : s->prop[p].type];
            values += 1;
        }
        u64 record = binary ? bytes : 2 * values;
        if (record == 0) record = 1; /* Assimp still allocates a record (and reads a line) */
        need = pxi_sat_add(need, pxi_sat_mul(e->declared, record));
        total = pxi_sat_add(total, e->declared);
        if (need > (binary ? avail : pxi_sat_add(avail, 1))) {
            char noun[64];
            elem_noun(e, noun, sizeof noun);
            return pxi_error(
                err, PX_ERR_IO,
                "mesh file '%s' declares %llu %s but has only %llu bytes after its header (PLY %s: "
                "at least %llu needed)",
                h->path, e->declared, noun, avail, binary ? "binary" : "ascii", need);
        }
    }
    if (total > PX_IO_MAX_ELEMENTS)
        return pxi_error(err, PX_ERR_IO, "mesh file '%s' declares %llu elements, more than the limit of %llu",
                         h->path, total, (u64)PX_IO_MAX_ELEMENTS);
    int vertex = 0, face = 0;
    for (size_t k = 0; k < s->nelem; ++k) {
        vertex += s->elem[k].sem == E_VERTEX;
        face += s->elem[k].sem == E_FACE || s->elem[k].sem == E_TRISTRIP;
    }
    if (vertex > 1 || face > 1)
        return pxi_error(err, PX_ERR_IO,
                         "mesh file '%s': the PLY header declares several %s elements (Assimp 5.2 writes the "
                         "later ones past the arrays it sized for the first)",
                         h->path, vertex > 1 ? "vertex" : "face or tristrips");
    for (size_t k = 0; k < s->nelem; ++k)
        if (s->elem[k].sem == E_TRISTRIP && s->elem[k].declared > 0)
            return pxi_error(
                err, PX_ERR_IO,
                "mesh file '%s': its PLY tristrips element cannot be read: Assimp 5.2 keeps only "
                "the last triangle of each strip (review s30: a strip of 6 corners gave 1 "
                "triangle of 4); write the triangles as a face element",
                h->path);
    return PX_OK;
}

/* Where a list was found, for messages. */
static px_status err_list(const ply_state *s, const ply_elem *e, u64 record, u64 len, const char *why,
                          px_error *err) {
    char noun[64];
    elem_noun(e, noun, sizeof noun);
    return pxi_error(err, PX_ERR_IO,
                     "mesh file '%s': a list of record %llu of its %s declares %llu values, %s", s->h->path,
                     record, noun, len, why);
}

/* The face check of LoadFace (see the file comment): lengths of the record's
 * last vertex_indices and texcoord lists (-1: none). */
static px_status check_texcoord(const ply_state *s, const ply_elem *e, u64 record, long long vi, long long tc,
                                px_error *err) {
    if (e->sem != E_FACE || tc < 0 || tc / 3 != 2) return PX_OK;
    if (vi > (tc - 1) / 2) return PX_OK;
    return pxi_error(err, PX_ERR_IO,
                     "mesh file '%s': face %llu has a texcoord list of %lld values but %lld vertex indices "
                     "(Assimp 5.2 reads vertex index n / 2 for texcoord value n, past the end)",
                     s->h->path, record, tc, vi < 0 ? 0 : vi);
}

/* A list length as Assimp's ConvertTo<unsigned int> makes it. */
static u64 list_length(int type, const unsigned char *b, int big_endian) {
    unsigned size = k_type_size[type];
    unsigned long long u = 0;
    for (unsigned k = 0; k < size; ++k)
        u |= (unsigned long long)b[big_endian ? k : size - 1 - k] << (8 * (size - 1 - k));
    switch (type) {
    case T_CHAR: return (unsigned)(int)(signed char)(u & 0xFF);
    case T_SHORT: return (unsigned)(int)(short)(u & 0xFFFF);
    default: return (unsigned)u;
    }
}

#define PLY_MAX_LIST_TOTAL (4 * (u64)PX_IO_MAX_ELEMENTS)

static px_status walk_binary(ply_state *s, u64 body, int big_endian, px_error *err) {
    const io_head *h = s->h;
    io_reader *rd = h->rd;
    pxi_rd_seek(rd, body);
    u64 total = 0;
    for (size_t k = 0; k < s->nelem; ++k) {
        const ply_elem *e = &s->elem[k];
        const ply_prop *p = s->prop + e->prop0;
        u64 fixed = 0;
        int lists = 0;
        for (size_t q = 0; q < e->nprop; ++q) {
            lists |= p[q].list;
            fixed += k_type_size[p[q].list ? p[q].first : p[q].type];
        }
        if (!lists) { /* records of one size: skip them at once */
            if (!pxi_rd_skip(rd, pxi_sat_mul(e->count, fixed))) goto truncated;
            continue;
        }
        for (u64 r = 0; r < e->count; ++r) {
            long long vi = -1, tc = -1;
            for (size_t q = 0; q < e->nprop; ++q) {
                if (!p[q].list) {
                    if (!pxi_rd_skip(rd, k_type_size[p[q].type])) goto truncated;
                    continue;
                }
                if (p[q].first == T_FLOAT || p[q].first == T_DOUBLE)
                    return pxi_error(err, PX_ERR_IO,
                                     "mesh file '%s': a PLY list has a floating-point length type", h->path);
                unsigned char b[4];
                if (!pxi_rd_read(rd, b, k_type_size[p[q].first])) goto truncated;
                u64 len = list_length(p[q].first, b, big_endian);
                if (len > PX_IO_MAX_PLY_LIST)
                    return err_list(s, e, r, len, "more than the limit of values per list", err);
                u64 bytes = len * k_type_size[p[q].type];
                if (bytes > h->size - pxi_rd_tell(rd))
                    return err_list(s, e, r, len, "more than the bytes left in the file hold", err);
                total += len;
                if (total > PLY_MAX_LIST_TOTAL)
                    return pxi_error(err, PX_ERR_IO,
                                     "mesh file '%s': its PLY lists hold more than %llu values in total",
                                     h->path, PLY_MAX_LIST_TOTAL);
                (void)pxi_rd_skip(rd, bytes);
                if (p[q].sem == S_VERTEX_INDEX) vi = (long long)len;
                if (p[q].sem == S_TEXCOORD) tc = (long long)len;
            }
            px_status st = check_texcoord(s, e, r, vi, tc, err);
            if (st != PX_OK) return st;
        }
        continue;
    truncated:
        if (rd->error) return pxi_rd_error(h, err);
        char noun[64];
        elem_noun(e, noun, sizeof noun);
        return pxi_error(err, PX_ERR_IO,
                         "mesh file '%s' declares %llu %s but its binary data ends before them (Assimp 5.2 "
                         "would read past the end of the file)",
                         h->path, e->declared, noun);
    }
    return PX_OK;
}

/* Bytes of the ascii value at v[i] as Assimp's parser for `type` consumes
 * it, or 0 if it consumes none, throws, or stops inside the token (then our
 * tokens would not be its tokens). *value gets an unsigned or signed value
 * as ConvertTo<unsigned int> makes it. */
static size_t ascii_value(ply_vec *v, size_t i, int type, u64 *value) {
    size_t j = i;
    int c = vec_at(v, j);
    *value = 0;
    if (type == T_FLOAT || type == T_DOUBLE) { /* fast_atoreal_move */
        if (c == '-' || c == '+') c = vec_at(v, ++j);
        int digits = 0;
        while (c >= '0' && c <= '9') c = vec_at(v, ++j), ++digits;
        if ((c == '.' || c == ',') && vec_at(v, j + 1) >= '0' && vec_at(v, j + 1) <= '9') {
            c = vec_at(v, ++j);
            while (c >= '0' && c <= '9') c = vec_at(v, ++j), ++digits;
        } else if (c == '.' && digits) {
            c = vec_at(v, ++j);
        }
        if (!digits) return 0; /* also "nan", "inf": refused (not finite anyway) */
        if (c == 'e' || c == 'E') {
            c = vec_at(v, ++j);
            if (c == '-' || c == '+') c = vec_at(v, ++j);
            if (c < '0' || c > '9') return 0;
            while (c >= '0' && c <= '9') c = vec_at(v, ++j);
        }
    } else { /* strtoul10, or strtol10 for the signed types */
        int neg = 0;
        if ((type == T_CHAR || type == T_SHORT || type == T_INT) && (c == '-' || c == '+')) {
            neg = c == '-';
            c = vec_at(v, ++j);
        }
        unsigned u = 0;
        int digits = 0;
        while (c >= '0' && c <= '9') u = u * 10u + (unsigned)(c - '0'), c = vec_at(v, ++j), ++digits;
        if (!digits) return 0;
        *value = neg ? (unsigned)(0u - u) : u;
    }
    if (!is_space(c) && !is_line_end(c)) return 0;
    return j - i;
}

/* Steps of PLY::PropertyInstance::ParseInstance on the line in the vector,
 * from *i. The line holds `line_len` bytes; reading a value past them means
 * reading stale bytes. Returns 0 on success, else a refusal was made. */
static px_status walk_ascii_record(ply_state *s, const ply_elem *e, u64 r, size_t line_len, u64 *total,
                                   px_error *err) {
    ply_vec *v = &s->v;
    const ply_prop *p = s->prop + e->prop0;
    size_t i = 0;
    long long vi = -1, tc = -1;
    char noun[64];
    for (size_t q = 0; q < e->nprop; ++q) {
        if (!cur_skip_spaces(v, &i) || i >= line_len) goto few;
        u64 val;
        size_t n = ascii_value(v, i, p[q].list ? p[q].first : p[q].type, &val);
        if (!n) goto bad_value;
        if (p[q].list && (p[q].first == T_FLOAT || p[q].first == T_DOUBLE))
            return pxi_error(err, PX_ERR_IO, "mesh file '%s': a PLY list has a floating-point length type",
                             s->h->path);
        i += n;
        if (i > line_len) goto few; /* the value ran into stale bytes */
        if (p[q].list) {
            if (val > PX_IO_MAX_PLY_LIST)
                return err_list(s, e, r, val, "more than the limit of values per list", err);
            /* Each value takes two bytes at least: the line cannot hold more. */
            if (val > (line_len - i) / 2) return err_list(s, e, r, val, "more than its line holds", err);
            *total += val;
            if (*total > PLY_MAX_LIST_TOTAL)
                return pxi_error(err, PX_ERR_IO,
                                 "mesh file '%s': its PLY lists hold more than %llu values in total",
                                 s->h->path, PLY_MAX_LIST_TOTAL);
            for (u64 k = 0; k < val; ++k) {
                u64 ignored;
                if (!cur_skip_spaces(v, &i) || i >= line_len) goto few;
                size_t m = ascii_value(v, i, p[q].type, &ignored);
                if (!m) goto bad_value;
                i += m;
            }
            if (p[q].sem == S_VERTEX_INDEX) vi = (long long)val;
            if (p[q].sem == S_TEXCOORD) tc = (long long)val;
        }
        if (i > line_len) goto few; /* the value ran into stale bytes */
        cur_skip_spaces_and_line_end(v, &i);
    }
    if (v->past) goto few;
    return check_texcoord(s, e, r, vi, tc, err);
few:
    elem_noun(e, noun, sizeof noun);
    return pxi_error(
        err, PX_ERR_IO,
        "mesh file '%s': line %llu of its %s has fewer values than its properties need (Assimp 5.2 "
        "reads the missing ones from earlier lines)",
        s->h->path, r, noun);
bad_value:
    elem_noun(e, noun, sizeof noun);
    return pxi_error(err, PX_ERR_IO,
                     "mesh file '%s': line %llu of its %s has a value that is not a number of "
                     "its property's type",
                     s->h->path, r, noun);
}

/* The ascii body: DOM::ParseInstance after ParseHeader, then
 * ParseElementInstanceLists. One getNextLine before the first record and one
 * after each; a record read when the last one failed would be parsed from
 * the stale vector. */
static px_status walk_ascii(ply_state *s, px_error *err) {
    const io_head *h = s->h;
    ply_sb *b = &s->sb;
    v_skip_spaces_and_line_end(&s->v); /* ParseInstance, after ParseHeader */
    int ok = sb_next_line(s);
    u64 total = 0;
    for (size_t k = 0; k < s->nelem; ++k) {
        const ply_elem *e = &s->elem[k];
        for (u64 r = 0; r < e->count; ++r) {
            /* A line cut by the end of the file is still parsed (the values
             * must not run into the stale bytes behind it); no line at all
             * means the previous one is parsed again. */
            if (b->oob || s->v.oom || b->rd_error || (!ok && s->line_len == 0)) {
                if (s->v.oom)
                    return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "out of memory reading mesh file '%s'",
                                     h->path);
                if (b->rd_error) return pxi_rd_error(h, err);
                char noun[64];
                elem_noun(e, noun, sizeof noun);
                if (b->oob)
                    return pxi_error(
                        err, PX_ERR_IO,
                        "mesh file '%s': a line of its %s ends in '\\r', NUL or form feed without "
                        "a following '\\n', which Assimp 5.2 misreads (it reads past its buffer)",
                        h->path, noun);
                return pxi_error(
                    err, PX_ERR_IO,
                    "mesh file '%s' declares %llu %s but its text ends at %s %llu (one per line)", h->path,
                    e->declared, noun, e->sem == E_VERTEX ? "vertex" : "record", r);
            }
            if (e->sem != E_INVALID && e->nprop) {
                px_status st = walk_ascii_record(s, e, r, s->line_len, &total, err);
                if (st != PX_OK) return st;
            } else { /* ParseInstanceList's skip of an unknown element */
                v_skip_comments(&s->v);
                v_skip_line(&s->v);
            }
            ok = sb_next_line(s);
        }
    }
    return PX_OK;
}

/* Whether Assimp's PLY importer gets past its magic test: the first line,
 * as getNextLine returns it, starts with "ply" in any case. When the file
 * starts with a line-end byte, getNextLine first skips to the first '\n'
 * (past a file without one: then its line is empty). Returns -1 when that
 * '\n' is not in the head of a file larger than the head. */
static int ply_magic(const io_head *h) {
    const unsigned char *d = h->data;
    size_t p = 0;
    if (h->len && is_line_end(d[0])) {
        while (p < h->len && d[p] != '\n') ++p;
        if (p == h->len) return h->len < h->size ? -1 : 0;
        ++p;
    }
    return h->len - p >= 3 && pxi_lower(d[p]) == 'p' && pxi_lower(d[p + 1]) == 'l' &&
           pxi_lower(d[p + 2]) == 'y';
}

px_status pxi_check_ply(const io_head *h, px_error *err) {
    int magic = ply_magic(h);
    if (magic < 0)
        return pxi_error(
            err, PX_ERR_IO,
            "mesh file '%s' starts with a line-end byte and has no line break in its first %d bytes "
            "(Assimp 5.2's PLY reader would read past its buffer)",
            h->path, PXI_IO_HEAD_BYTES);
    if (!magic) return PX_OK; /* Assimp: "Incorrect magic number" */
    ply_state *s = pxi_alloc(h->alloc, sizeof *s);
    unsigned char *cache = pxi_alloc(h->alloc, PLY_CACHE);
    px_status st = PX_OK;
    if (!s || !cache) {
        st = pxi_error(err, PX_ERR_OUT_OF_MEMORY, "out of memory reading mesh file '%s'", h->path);
        goto done;
    }
    memset(s, 0, sizeof *s);
    s->h = h;
    s->alloc = h->alloc;
    s->sb.rd = h->rd;
    s->sb.filesize = h->size;
    s->sb.cache = cache;
    memset(cache, '\n', PLY_CACHE);
    s->sb.cache_size = h->size < PLY_CACHE ? (size_t)h->size : PLY_CACHE;
    int format;
    st = ply_header(s, &format, err);
    if (st != PX_OK || !format) goto done;
    if (!header_as_defined(s)) {
        st = pxi_error(err, PX_ERR_IO,
                       "mesh file '%s': a PLY comment among an element's properties (Assimp 5.2 makes it an "
                       "element that takes the properties after it): put comments before the first element",
                       h->path);
        goto done;
    }
    /* Where Assimp's body starts: binary, the rest of the cache after the
     * end_header line, less a first '\n' (meant for "\r\n"; a body whose first
     * byte is 0x0A loses it). The header lies in the first block. */
    u64 body = sb_offset(&s->sb);
    if (format > 1 && body < h->size && s->sb.cache[s->sb.pos] == '\n') ++body;
    st = ply_sizes(s, format > 1, body, err);
    if (st != PX_OK) goto done;
    st = format > 1 ? walk_binary(s, body, format == 3, err) : walk_ascii(s, err);
done:
    if (s && s->v.mem) pxi_free(h->alloc, s->v.mem, s->v.cap);
    if (cache) pxi_free(h->alloc, cache, PLY_CACHE);
    if (s) pxi_free(h->alloc, s, sizeof *s);
    return st;
}
