/* Nesting depth of the formats whose Assimp 5.2 readers recurse once per
 * level of the file's own structure, checked before Assimp reads them; and
 * BVH files, refused.
 *
 * Assimp's AC3D, BVH, FBX, OpenGEX, X3D and XGL readers call themselves once
 * per nested object, joint, scope, structure or element, with nothing
 * bounding the depth: a file nesting 200000 levels (1.4 to 7 MB of text)
 * overflowed the 8 MiB stack in each of them (SIGSEGV, measured with Debian
 * bookworm's 5.2.5; the review's ac_nest.ac, bvh_nest.bvh, fbx_nest.fbx,
 * ogex_nest.ogex, x3d_nest.x3d, xgl_nest.xgl). The overflow came after 5700
 * (XGL, about 1.5 KB of stack a level) to 58000 frames. The scans here
 * read the file the way each reader does, iteratively, and refuse a file
 * nested deeper than NEST_MAX_DEPTH (AC3D objects, FBX scopes, OpenGEX
 * structures) or XML_MAX_DEPTH (XML elements, as for COLLADA in
 * graph.c): far above real files (scene graphs a few dozen levels deep,
 * FBX scopes about 6), and far below the stack: the crash depths put
 * Assimp's use at 0.15 to 1.5 KB a level, and files at these limits (each
 * format, ASCII and binary FBX) imported with a 1 MiB stack (ulimit -s).
 *
 * What each reader recurses on, and what is scanned:
 * - AC3D (ACLoader.cpp LoadObjectSection): an OBJECT's "kids n" line loads
 *   n objects, each recursively. The scan follows the reader line by line
 *   (its GetNextLine, TokenMatch and the lines numvert, numsurf/SURF/refs
 *   consume), keeping the kids counts on a stack. A count (kids, numvert,
 *   numsurf, refs) above the bytes that follow it is refused too (Assimp
 *   reserves by it), and so is a numsurf count the reader would spend
 *   re-reading one line for (it does not advance past a line that is neither
 *   SURF, mat nor refs).
 * - BVH (BVHLoader.cpp ReadNode, once per JOINT): refused as a format
 *   (a skeleton without a mesh, see below), so never read.
 * - FBX (FBXParser.cpp Scope/Element, FBXBinaryTokenizer.cpp ReadScope):
 *   ASCII: braces outside ';' comments and double quotes, as the tokenizer
 *   reads them; binary: the records nested in records, walked through their
 *   end offsets as ReadScope walks them.
 * - OpenGEX (openddlparser parseStructure): braces, once its comments are
 *   removed as normalizeBuffer removes them (whatever the quotes); counted
 *   both ignoring and honouring double quotes, the larger depth taken.
 * - XML (X3D, XGL, and the other XML readers: AMF, Irrlicht, Ogre): element
 *   nesting, as pugixml parses it (comments, CDATA, processing instructions
 *   and DOCTYPE skipped). XML in UTF-16, which pugixml converts and this scan
 *   would not, is refused. In XGL files, numbers written "0,0,1" too (see
 *   xgl_misread).
 *
 * Which files are scanned: those whose extension names the format, and
 * those whose first bytes match the signature Assimp would detect them by,
 * unless the extension is one only another importer claims (Assimp then
 * never asks the others). ZGL (compressed XGL) is refused in precheck.c. */
#include "io/scan.h"

#include <string.h>

#include "core/core.h"

#define NEST_MAX_DEPTH 256 /* AC3D objects, FBX scopes, OpenGEX structures */
#define XML_MAX_DEPTH 512  /* XML elements (as graph.c for COLLADA) */

typedef unsigned u32;

static int ext_is(const io_head *h, const char *const *list) {
    for (; *list; ++list)
        if (strcmp(h->ext, *list) == 0) return 1;
    return 0;
}

/* Extensions only one Assimp 5.2 importer claims: a file named so is read by
 * that importer, never by signature. */
static const char *const k_pinned[] = {
    "obj", "stl",  "ply",   "off", "gltf", "glb", "fbx", "dae",     "3ds", "ac",      "ac3d", "acc",
    "bvh", "ogex", "x3d",   "xgl", "zgl",  "amf", "lwo", "lws",     "md2", "md3",     "mdl",  "ms3d",
    "smd", "vta",  "blend", "irr", "3mf",  "q3o", "q3s", "irrmesh", "ter", "hmp",     "csm",  "b3d",
    "nff", "x",    "ase",   "ask", "cob",  "scn", "raw", "ifc",     "mdc", "md5mesh", NULL};

/* 1 if the importer whose extensions are `own` may read the file: by its
 * extension, or by signature (`sig`, already tested by the caller) when the
 * extension does not pin another importer. */
static int may_read(const io_head *h, const char *const *own, int sig) {
    if (ext_is(h, own)) return 1;
    return sig && !ext_is(h, k_pinned);
}

static px_status too_deep(const io_head *h, const char *what, int limit, px_error *err) {
    return pxi_error(err, PX_ERR_IO,
                     "mesh file '%s': its %s are nested more than %d deep (Assimp 5.2's reader recurses once "
                     "per level and would overflow the stack)",
                     h->path, what, limit);
}

static int starts_with(const io_head *h, const char *s) {
    size_t n = strlen(s);
    return h->len >= n && memcmp(h->data, s, n) == 0;
}

/* ------------------------------------------------------------------ AC3D */

/* ParsingUtils, on the NUL-terminated text (TextFileToBuffer). */
static int ac_line_end(int c) { return c == '\r' || c == '\n' || c == '\0' || c == '\f'; }
static int ac_space(int c) { return c == ' ' || c == '\t'; }
static int ac_skip_spaces(const unsigned char **p) {
    while (ac_space(**p)) ++*p;
    return !ac_line_end(**p);
}
static void ac_skip_line(const unsigned char **p) {
    while (**p != '\r' && **p != '\n' && **p != '\0') ++*p;
    while (**p == '\r' || **p == '\n') ++*p;
}
static int ac_next_line(const unsigned char **p) { /* AC3DImporter::GetNextLine */
    ac_skip_line(p);
    return ac_skip_spaces(p);
}
static int ac_token(const unsigned char **p, const char *tok) { /* TokenMatch */
    size_t n = strlen(tok);
    if (strncmp((const char *)*p, tok, n) != 0) return 0;
    int c = (*p)[n];
    if (!(ac_space(c) || ac_line_end(c))) return 0;
    *p += c ? n + 1 : n;
    return 1;
}
static u64 ac_strtoul10(const unsigned char **p, u64 *sat) {
    unsigned v = 0;
    u64 s = 0;
    while (**p >= '0' && **p <= '9') {
        v = v * 10u + (unsigned)(**p - '0');
        s = pxi_sat_add(pxi_sat_mul(s, 10), (u64)(**p - '0'));
        ++*p;
    }
    if (sat) *sat = s;
    return v;
}
/* AcGetString: one past the opening character, to the closing quote or the
 * end of the line. Returns 0 where Assimp throws (at the NUL). */
static int ac_get_string(const unsigned char **p) {
    if (**p == '\0') return 0;
    ++*p;
    while (**p != '"' && !ac_line_end(**p)) ++*p;
    if (!ac_line_end(**p)) ++*p;
    return 1;
}

enum { AC_OK, AC_DEEP, AC_COUNT, AC_SPIN, AC_MATERIAL };

typedef struct ac_state {
    const unsigned char *t, *end; /* text, its NUL */
    const char *what;             /* the count refused */
    u64 count, left;              /* its value, the bytes after it */
} ac_state;

/* A count of items that each take at least a byte of what follows. */
static int ac_count_ok(ac_state *s, const unsigned char *p, u64 count, const char *what) {
    if (count <= (u64)(s->end - p)) return 1;
    s->what = what;
    s->count = count;
    s->left = (u64)(s->end - p);
    return 0;
}

/* The numsurf block (LoadObjectSection): t surfaces, each a SURF line
 * (Quick3D files: none) then mat and refs lines. Returns AC_OK, AC_COUNT or
 * AC_SPIN, or -1 where Assimp throws. */
static int ac_surfaces(ac_state *s, const unsigned char **p, u64 t) {
    int q3d = 0;
    for (u64 i = 0; i < t; ++i) {
        const unsigned char *start = *p;
        int q3d_before = q3d;
        ac_next_line(p);
        if (!ac_token(p, "SURF")) {
            --*p;
            q3d = 1;
        }
        ac_skip_spaces(p);
        u64 entries = 0;
        for (;;) {
            if (!ac_next_line(p)) return -1; /* "surface is incomplete" */
            if (ac_token(p, "mat")) {
                ac_skip_spaces(p);
            } else if (ac_token(p, "refs")) {
                if (q3d && entries) {
                    *p = *p - s->t >= 6 ? *p - 6 : s->t; /* (an earlier refs line keeps it inside) */
                    break;
                }
                ac_skip_spaces(p);
                const unsigned char *q = *p;
                const unsigned m = (unsigned)ac_strtoul10(&q, NULL); /* the pointer is not moved */
                if (!ac_count_ok(s, *p, m, "refs")) return AC_COUNT;
                for (unsigned k = 0; k < m; ++k) {
                    if (!ac_next_line(p)) break;
                    ++entries;
                }
            } else {
                --*p;
                break;
            }
        }
        /* No line consumed and the state as before: every further surface
         * re-reads this line (Assimp does, t - i times). */
        if (*p == start && q3d == q3d_before) {
            if (t - i - 1 > 65536) return AC_SPIN;
            return AC_OK;
        }
    }
    return AC_OK;
}

/* Follows AC3DImporter::InternReadFile and LoadObjectSection with a stack of
 * the kids still to load per level. */
static int ac_walk(ac_state *s) {
    u64 stack[NEST_MAX_DEPTH];
    u32 sp = 0;
    const unsigned char *p = s->t;
    while (ac_next_line(&p)) {
        if (ac_token(&p, "MATERIAL")) {
            /* The material's fields are read within this line; then an
             * OBJECT is looked for where they end. Not followed here. */
            const unsigned char *q = p;
            while (!ac_line_end(*q)) {
                if (strncmp((const char *)q, "OBJECT", 6) == 0) return AC_MATERIAL;
                ++q;
            }
            continue;
        }
        /* LoadObjectSection, iteratively: `enter` loads one object. */
    enter:
        if (!ac_token(&p, "OBJECT")) {
            /* Not an object: the siblings still due fail here too. */
            if (sp) stack[sp - 1] = 1;
            goto leave;
        }
        ac_skip_spaces(&p);
        while (ac_next_line(&p)) {
            if (ac_token(&p, "kids")) {
                ac_skip_spaces(&p);
                u64 num = ac_strtoul10(&p, NULL);
                ac_next_line(&p);
                if (!num) goto leave;
                if (!ac_count_ok(s, p, num, "kids")) return AC_COUNT;
                if (sp == NEST_MAX_DEPTH - 1) return AC_DEEP;
                stack[sp++] = num;
                goto enter;
            } else if (ac_token(&p, "name") || ac_token(&p, "texture")) {
                ac_skip_spaces(&p);
                if (!ac_get_string(&p)) return AC_OK;
            } else if (ac_token(&p, "texrep") || ac_token(&p, "texoff") || ac_token(&p, "rot") ||
                       ac_token(&p, "loc") || ac_token(&p, "subdiv") || ac_token(&p, "crease")) {
                ac_skip_spaces(&p); /* the values are read within the line */
            } else if (ac_token(&p, "numvert")) {
                ac_skip_spaces(&p);
                u64 t = ac_strtoul10(&p, NULL);
                if (!ac_count_ok(s, p, t, "numvert")) return AC_COUNT;
                for (u64 i = 0; i < t; ++i) {
                    if (!ac_next_line(&p)) break;
                    if (!((*p >= '0' && *p <= '9') || *p == '-' || *p == '+')) {
                        --p;
                        break;
                    }
                }
            } else if (ac_token(&p, "numsurf")) {
                ac_skip_spaces(&p);
                u64 t = ac_strtoul10(&p, NULL);
                if (!ac_count_ok(s, p, t, "numsurf")) return AC_COUNT;
                int r = ac_surfaces(s, &p, t);
                if (r < 0) return AC_OK;
                if (r != AC_OK) return r;
            }
        }
    leave:
        /* The object is loaded: its parent loads the next of its kids. */
        while (sp) {
            if (--stack[sp - 1]) goto enter;
            --sp;
        }
    }
    return AC_OK;
}

static px_status check_ac(const io_head *h, px_error *err) {
    if (h->len >= 2 &&
        ((h->data[0] == 0xFE && h->data[1] == 0xFF) || (h->data[0] == 0xFF && h->data[1] == 0xFE)))
        return pxi_error(err, PX_ERR_IO,
                         "mesh file '%s' starts with a UTF-16 byte-order mark, which Assimp 5.2 mishandles: "
                         "save it as ASCII or UTF-8",
                         h->path);
    unsigned char *doc;
    px_status st = pxi_read_all(h, &doc, err);
    if (st != PX_OK) return st;
    ac_state s;
    memset(&s, 0, sizeof s);
    size_t skip = h->size >= 3 && doc[0] == 0xEF && doc[1] == 0xBB && doc[2] == 0xBF ? 3 : 0;
    s.t = doc + skip;
    s.end = s.t + strlen((const char *)s.t);
    switch (ac_walk(&s)) {
    case AC_DEEP: st = too_deep(h, "AC3D objects (kids)", NEST_MAX_DEPTH, err); break;
    case AC_COUNT:
        st = pxi_error(
            err, PX_ERR_IO,
            "mesh file '%s': an AC3D '%s %llu' line declares more entries than the %llu bytes after "
            "it can hold (Assimp 5.2 reserves memory by it)",
            h->path, s.what, s.count, s.left);
        break;
    case AC_SPIN:
        st = pxi_error(err, PX_ERR_IO,
                       "mesh file '%s': an AC3D numsurf count exceeds the surfaces that follow by more than "
                       "65536 (Assimp 5.2 would re-read one line for each)",
                       h->path);
        break;
    case AC_MATERIAL:
        st = pxi_error(err, PX_ERR_IO,
                       "mesh file '%s': an AC3D MATERIAL line holds OBJECT (not accepted: where Assimp 5.2 "
                       "starts reading that object was not checked)",
                       h->path);
        break;
    default: break;
    }
    pxi_free(h->alloc, doc, (size_t)h->size + 1);
    return st;
}

/* ------------------------------------------------------------------- BVH */

/* BVH files hold a skeleton and its motion, no mesh: Assimp 5.2's reader
 * (which recursed once per JOINT, overflowing the stack at 24000 levels)
 * then builds a mesh of pyramids around the bones (SkeletonMeshBuilder), and
 * those made-up points came back as the file's points with PX_OK. Refused:
 * by extension, and by signature when the first token is HIERARCHY (the
 * reader throws at anything else). */
static int bvh_space(int c) { return c == ' ' || (c >= '\t' && c <= '\r'); } /* isspace, "C" locale */

static int bvh_first_token(const io_head *h) {
    size_t i = 0;
    while (i < h->len && bvh_space(h->data[i])) ++i;
    return h->len - i >= 9 && memcmp(h->data + i, "HIERARCHY", 9) == 0 &&
           (h->len - i == 9 || bvh_space(h->data[i + 9]));
}

/* ------------------------------------------------------------------- FBX */

static u64 read_le(const unsigned char *b, int n) {
    u64 v = 0;
    for (int i = n - 1; i >= 0; --i) v = v << 8 | b[i];
    return v;
}

/* TokenizeBinary and ReadScope, with the nested blocks on a stack. Where the
 * tokenizer would throw, the scan ends. */
static int fbx_binary_deep(const unsigned char *in, u64 len) {
    struct {
        u64 end, inner;
    } stack[NEST_MAX_DEPTH];
    u32 sp = 0;
    if (len < 0x1b) return 0;
    const u32 version = (u32)read_le(in + 23, 4);
    const int w = version >= 7500 ? 8 : 4;
    const u64 sentinel = (u64)(3 * w + 1);
    u64 pos = 27;
    for (;;) {
        const u64 limit = sp ? stack[sp - 1].inner : len;
        if (sp && pos >= limit) {
            pos += sentinel; /* the zero record closing the block */
            if (pos != stack[sp - 1].end) return 0;
            --sp;
            continue;
        }
        if (!sp && pos >= len) return 0;
        if (limit - pos < (u64)w) return 0;
        const u64 end_offset = read_le(in + pos, w);
        pos += (u64)w;
        if (!end_offset) {
            if (!sp) return 0; /* the footer */
            continue;
        }
        if (end_offset > limit || end_offset < pos) return 0;
        if (limit - pos < 2 * (u64)w + 1) return 0;
        const u64 prop_length = read_le(in + pos + w, w);
        pos += 2 * (u64)w;
        const u64 name_length = in[pos++];
        if (limit - pos < name_length) return 0;
        pos += name_length;
        if (prop_length > limit - pos) return 0;
        pos += prop_length;
        if (pos < end_offset) {
            if (end_offset - pos < sentinel) return 0;
            if (sp == NEST_MAX_DEPTH - 1) return 1;
            stack[sp].end = end_offset;
            stack[sp].inner = end_offset - sentinel;
            ++sp;
        } else if (pos != end_offset) {
            return 0;
        }
    }
}

static px_status check_fbx(const io_head *h, px_error *err) {
    unsigned char *doc;
    px_status st = pxi_read_all(h, &doc, err);
    if (st != PX_OK) return st;
    int deep = 0;
    if (h->size >= 18 && memcmp(doc, "Kaydara FBX Binary", 18) == 0) {
        deep = fbx_binary_deep(doc, h->size + 1); /* Assimp appends a NUL and counts it */
    } else {
        /* FBX::Tokenize: ';' comments to the end of the line, double quotes,
         * braces; the text ends at its first NUL. */
        int comment = 0, quoted = 0;
        u64 depth = 0;
        for (const unsigned char *c = doc; *c && !deep; ++c) {
            if (*c == '\r' || *c == '\n' || *c == '\f') comment = 0;
            if (comment) continue;
            if (quoted) {
                if (*c == '"') quoted = 0;
                continue;
            }
            if (*c == '"') quoted = 1;
            if (*c == ';') comment = 1;
            if (*c == '{') deep = ++depth > NEST_MAX_DEPTH;
            if (*c == '}' && depth) --depth;
        }
    }
    if (deep) st = too_deep(h, "FBX scopes", NEST_MAX_DEPTH, err);
    pxi_free(h->alloc, doc, (size_t)h->size + 1);
    return st;
}

/* --------------------------------------------------------------- OpenGEX */

static int ddl_letter(int c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }

static px_status check_ogex(const io_head *h, px_error *err) {
    if (h->len >= 2 &&
        ((h->data[0] == 0xFE && h->data[1] == 0xFF) || (h->data[0] == 0xFF && h->data[1] == 0xFE)))
        return pxi_error(err, PX_ERR_IO,
                         "mesh file '%s' starts with a UTF-16 byte-order mark, which Assimp 5.2 mishandles: "
                         "save it as ASCII or UTF-8",
                         h->path);
    unsigned char *doc;
    px_status st = pxi_read_all(h, &doc, err);
    if (st != PX_OK) return st;
    size_t i = h->size >= 3 && doc[0] == 0xEF && doc[1] == 0xBB && doc[2] == 0xBF ? 3 : 0;
    const size_t len = (size_t)h->size;
    u64 all = 0, outside = 0; /* depth counting every brace; braces outside quotes */
    int quoted = 0, deep = 0;
    /* OpenDDLParser::normalizeBuffer: block and line comments dropped
     * (quotes or not; "//x/" is no comment), then the braces counted. */
    for (; i < len && !deep; ++i) {
        const unsigned char c = doc[i];
        if (c == '/' && i + 1 < len && doc[i + 1] == '*') {
            ++i;
            while (i < len && !(doc[i] == '*' && i + 1 < len && doc[i + 1] == '/')) ++i;
            ++i;
            continue;
        }
        if (c == '/' && i + 1 < len && doc[i + 1] == '/' && !(ddl_letter(doc[i + 2]) && doc[i + 3] == '/')) {
            while (i + 1 < len && doc[i + 1] != '\n') ++i;
            continue;
        }
        if (c == '"') quoted = !quoted;
        if (c == '{') {
            ++all;
            if (!quoted) ++outside;
        }
        if (c == '}') {
            if (all) --all;
            if (!quoted && outside) --outside;
        }
        deep = all > NEST_MAX_DEPTH || outside > NEST_MAX_DEPTH;
    }
    if (deep) st = too_deep(h, "OpenGEX structures", NEST_MAX_DEPTH, err);
    pxi_free(h->alloc, doc, (size_t)h->size + 1);
    return st;
}

/* ------------------------------------------------------------------- XML */

static const unsigned char *xml_find(const unsigned char *p, const unsigned char *end, const char *pat) {
    size_t n = strlen(pat);
    while ((size_t)(end - p) >= n) {
        const unsigned char *q = memchr(p, (unsigned char)pat[0], (size_t)(end - p));
        if (!q || (size_t)(end - q) < n) return end;
        if (memcmp(q, pat, n) == 0) return q;
        p = q + 1;
    }
    return end;
}

static int is_digit(int c) { return c >= '0' && c <= '9'; }

/* 1 if the text [a, b) is numbers only and one of them is an integer
 * followed by a comma and a digit ("0,0,1"): Assimp 5.2's fast_atof takes
 * such a comma for a decimal point (0,0 -> 0.0), and its XGL reader (ReadVec3,
 * ReadVec2: values separated by commas) then returns other points than the
 * file's, with no error ((0,0,1) became (0,1,0), (0,1,0) became (0.1,0,0)).
 * "0, 0, 1" and "0.0,0.0,1.0" are read right. */
static int xgl_misread(const unsigned char *a, const unsigned char *b) {
    for (const unsigned char *q = a; q < b; ++q)
        if (!is_digit(*q) && !strchr("+-.eE, \t\r\n", *q)) return 0;
    for (const unsigned char *q = a + 1; q + 1 < b; ++q) {
        if (*q != ',' || !is_digit(q[-1]) || !is_digit(q[1])) continue;
        const unsigned char *r = q;
        while (r > a && is_digit(r[-1])) --r;
        int c = r > a ? r[-1] : ' ';
        if ((c == '+' || c == '-') && r - 1 > a) c = r[-2];
        if (c != '.' && c != 'e' && c != 'E') return 1; /* an integer part, then ",digit" */
    }
    return 0;
}

/* Element nesting depth of an XML document (pugixml's reading of it), up to
 * `limit` + 1; with `xgl`, sets *misread when a text xgl_misread finds. */
static u64 xml_depth(const unsigned char *d, size_t size, u64 limit, int xgl, int *misread) {
    const unsigned char *p = d, *end = d + size;
    u64 depth = 0;
    while (p < end) {
        const unsigned char *lt = memchr(p, '<', (size_t)(end - p));
        if (!lt) break;
        if (xgl && !*misread) *misread = xgl_misread(p, lt);
        p = lt;
        size_t left = (size_t)(end - p);
        if (left >= 4 && memcmp(p, "<!--", 4) == 0) {
            p = xml_find(p + 4, end, "-->") + 3;
        } else if (left >= 9 && memcmp(p, "<![CDATA[", 9) == 0) {
            p = xml_find(p + 9, end, "]]>") + 3;
        } else if (left >= 2 && p[1] == '?') {
            p = xml_find(p + 2, end, "?>") + 2;
        } else if (left >= 2 && p[1] == '!') { /* DOCTYPE, with an internal subset in [] */
            int bracket = 0;
            for (p += 2; p < end && (*p != '>' || bracket); ++p) {
                if (*p == '[') bracket = 1;
                if (*p == ']') bracket = 0;
            }
            ++p;
        } else if (left >= 2 && p[1] == '/') {
            if (depth) --depth;
            const unsigned char *gt = memchr(p, '>', left);
            p = gt ? gt + 1 : end;
        } else {
            /* A start tag: attributes (quoted values may hold '>'), then
             * "/>" or ">". */
            int self_closing = 0;
            for (++p; p < end;) {
                if (*p == '"' || *p == '\'') {
                    const unsigned char *q = memchr(p + 1, *p, (size_t)(end - p - 1));
                    p = q ? q + 1 : end;
                } else if (*p == '>') {
                    self_closing = p[-1] == '/';
                    ++p;
                    break;
                } else {
                    ++p;
                }
            }
            if (!self_closing && ++depth > limit) return depth;
        }
    }
    return depth;
}

/* XML in UTF-16 (pugixml converts it; the scans here would read it raw). */
static px_status check_xml_utf16(const io_head *h, px_error *err) {
    const unsigned char *b = h->data;
    if (h->len >= 2 && ((b[0] == 0xFE && b[1] == 0xFF) || (b[0] == 0xFF && b[1] == 0xFE) ||
                        (b[0] == 0 && b[1] == '<') || (b[0] == '<' && b[1] == 0)))
        return pxi_error(err, PX_ERR_IO,
                         "mesh file '%s': XML in UTF-16 is not accepted (its nesting could not be checked): "
                         "save it as UTF-8",
                         h->path);
    return PX_OK;
}

static px_status check_xml(const io_head *h, int xgl, px_error *err) {
    px_status st = check_xml_utf16(h, err);
    if (st != PX_OK) return st;
    unsigned char *doc;
    st = pxi_read_all(h, &doc, err);
    if (st != PX_OK) return st;
    int misread = 0;
    if (xml_depth(doc, (size_t)h->size, XML_MAX_DEPTH, xgl, &misread) > XML_MAX_DEPTH)
        st = pxi_error(
            err, PX_ERR_IO,
            "mesh file '%s': its XML is nested more than %d elements deep (Assimp 5.2's XML readers "
            "recurse once per element and would overflow the stack)",
            h->path, XML_MAX_DEPTH);
    else if (misread)
        st = pxi_error(err, PX_ERR_IO,
                       "mesh file '%s': an XGL value list writes an integer and a comma before a digit (as "
                       "\"0,0,1\"), which Assimp 5.2 reads as a decimal comma, returning other points: write "
                       "\"0, 0, 1\" or \"0.0,0.0,1.0\"",
                       h->path);
    pxi_free(h->alloc, doc, (size_t)h->size + 1);
    return st;
}

/* ----------------------------------------------------------------- entry */

px_status pxi_check_nesting(const io_head *h, px_error *err) {
    static const char *const ac[] = {"ac", "acc", "ac3d", NULL}, *const bvh[] = {"bvh", NULL},
                             *const fbx[] = {"fbx", NULL}, *const ogex[] = {"ogex", NULL},
                             *const xml[] = {"x3d", "x3db", "xgl", "amf", "irr", "irrmesh", "xml", NULL},
                             *const xgl[] = {"xgl", NULL};
    px_status st = PX_OK;
    /* AC3D: CheckMagicToken, "AC3D" at byte 0 (or byte-swapped). */
    if (st == PX_OK && may_read(h, ac, starts_with(h, "AC3D") || starts_with(h, "D3CA")))
        st = check_ac(h, err);
    if (st == PX_OK && may_read(h, bvh, pxi_signature_has(h, "hierarchy") && bvh_first_token(h)))
        st = pxi_error(err, PX_ERR_IO,
                       "mesh file '%s': BVH files are not accepted: they hold a skeleton and its motion, no "
                       "mesh (Assimp 5.2 would return a mesh it makes up around the bones)",
                       h->path);
    if (st == PX_OK && may_read(h, fbx, pxi_signature_has(h, "fbx"))) st = check_fbx(h, err);
    if (st == PX_OK &&
        may_read(h, ogex,
                 pxi_signature_has(h, "metric") || pxi_signature_has(h, "geometrynode") ||
                     pxi_signature_has(h, "vertexarray (attrib") || pxi_signature_has(h, "indexarray")))
        st = check_ogex(h, err);
    /* XML: by name, or a document starting with '<' (after blank space and
     * a UTF-8 byte-order mark), or one in UTF-16. COLLADA files get the same
     * scan in graph.c. */
    size_t b = h->len >= 3 && h->data[0] == 0xEF && h->data[1] == 0xBB && h->data[2] == 0xBF ? 3 : 0;
    while (b < h->len &&
           (h->data[b] == ' ' || h->data[b] == '\t' || h->data[b] == '\n' || h->data[b] == '\r'))
        ++b;
    int looks_xml =
        (b < h->len && h->data[b] == '<') ||
        (h->len >= 4 && ((h->data[0] == 0xFF && h->data[1] == 0xFE && h->data[2] == '<') ||
                         (h->data[0] == 0xFE && h->data[1] == 0xFF && h->data[3] == '<') ||
                         (h->data[0] == '<' && h->data[1] == 0) || (h->data[0] == 0 && h->data[1] == '<')));
    if (st == PX_OK && strcmp(h->ext, "dae") == 0)
        st = check_xml_utf16(h, err);
    else if (st == PX_OK && may_read(h, xml, looks_xml))
        st = check_xml(h, may_read(h, xgl, pxi_signature_has(h, "<world>")), err);
    return st;
}
