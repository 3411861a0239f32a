/* The node graphs of COLLADA and glTF files, checked before Assimp 5.2
 * builds them.
 *
 * Both formats let a node appear under several parents: COLLADA by
 * <instance_node url="#id"> (also of a whole <visual_scene>), glTF by a
 * node index in several "children" arrays. Assimp turns the graph into a
 * tree, one aiNode (over 1 KB: its name is an aiString) per path from the
 * root: ColladaLoader::BuildHierarchy and glTF2Importer's BuildNode recurse
 * through every instance. So 20 levels of two instances of the level below
 * (2.6 KB of COLLADA) became 2^20 nodes, 2.8 GB, and 40 levels exhausted the
 * machine; a COLLADA node instancing itself recursed until the stack
 * overflowed (SIGSEGV), as does any chain deep enough (glTF2's
 * LazyDict::Retrieve recurses along "children" while it reads the file, and
 * rapidjson's parser along nested arrays and objects).
 *
 * The scan here reads the document once, collects the nodes and their edges
 * (nesting and references), and walks the graph with an explicit stack:
 * refused are a cycle, a graph in which some node expands to more than
 * PX_IO_MAX_NODES instances (counted bottom-up, each node once, saturating),
 * a longest path of more than PXI_MAX_NODE_DEPTH edges, and documents nested
 * deeper than the parsers' limits below. The scanners read only inside their
 * buffer (NUL-terminated, with explicit bounds), recurse at most
 * JSON_MAX_DEPTH deep, and take time linear in the document plus the graph.
 *
 * What they do not decode: COLLADA ids, names and urls holding a character
 * reference ('&') or a tab or line break, and escaped glTF member names,
 * are refused rather than compared raw with what pugixml or rapidjson would
 * make of them. glTF 1.0 files (nodes as an object of named nodes) are
 * refused if a node has children. */
#include "io/scan.h"

#include <stdio.h>
#include <string.h>

#include "core/core.h"

#define PXI_MAX_NODE_DEPTH 256 /* longest chain of nodes (parent -> child, or instance) */
#define XML_MAX_DEPTH 512      /* element nesting in a COLLADA file */
#define JSON_MAX_DEPTH 128     /* array and object nesting in glTF JSON */
#define MAX_EDGES (1u << 20)   /* child links and instances */

typedef unsigned u32;

/* ------------------------------------------------------------ the graph */

typedef struct g_graph {
    const px_allocator *alloc;
    u32 n, ncap;             /* vertices */
    u32 *from, *to, m, mcap; /* edges */
    int oom, too_many;
} g_graph;

static int g_grow(g_graph *g, u32 **a, u32 *cap, u32 need) {
    if (need <= *cap) return 1;
    u32 c = *cap ? *cap : 64;
    while (c < need) c *= 2;
    u32 *b = pxi_alloc_array(g->alloc, c, sizeof(u32));
    if (!b) return g->oom = 1, 0;
    if (*a) {
        memcpy(b, *a, (size_t)*cap * sizeof(u32));
        pxi_free(g->alloc, *a, (size_t)*cap * sizeof(u32));
    }
    *a = b;
    *cap = c;
    return 1;
}

static int g_edge(g_graph *g, u32 a, u32 b) {
    if (g->m >= MAX_EDGES) return g->too_many = 1, 0;
    if (g->m == g->mcap) {
        u32 cap = g->mcap ? g->mcap * 2 : 64;
        u32 *f = pxi_alloc_array(g->alloc, cap, sizeof(u32)),
            *t = pxi_alloc_array(g->alloc, cap, sizeof(u32));
        if (!f || !t) {
            if (f) pxi_free(g->alloc, f, (size_t)cap * sizeof(u32));
            if (t) pxi_free(g->alloc, t, (size_t)cap * sizeof(u32));
            return g->oom = 1, 0;
        }
        if (g->mcap) {
            memcpy(f, g->from, (size_t)g->m * sizeof(u32));
            memcpy(t, g->to, (size_t)g->m * sizeof(u32));
            pxi_free(g->alloc, g->from, (size_t)g->mcap * sizeof(u32));
            pxi_free(g->alloc, g->to, (size_t)g->mcap * sizeof(u32));
        }
        g->from = f;
        g->to = t;
        g->mcap = cap;
    }
    g->from[g->m] = a;
    g->to[g->m] = b;
    ++g->m;
    return 1;
}

static void g_free(g_graph *g) {
    if (g->from) pxi_free(g->alloc, g->from, (size_t)g->mcap * sizeof(u32));
    if (g->to) pxi_free(g->alloc, g->to, (size_t)g->mcap * sizeof(u32));
}

/* The result of the walk: 0, or which limit the vertex `where` broke. */
enum { G_OK, G_CYCLE, G_TOO_MANY, G_TOO_DEEP, G_OOM };

/* Walks the graph depth-first with an explicit stack: colour, expansion
 * count (instances of the subtree, saturated just above PX_IO_MAX_NODES) and
 * height. count[] gets each vertex's expansion for the caller. */
static int g_walk(g_graph *g, u64 *count, u32 *where) {
    const u32 n = g->n, m = g->m;
    int res = G_OOM;
    u32 *start = pxi_alloc_array(g->alloc, (size_t)n + 1, sizeof(u32));
    u32 *adj = pxi_alloc_array(g->alloc, m ? m : 1, sizeof(u32));
    u32 *height = pxi_alloc_array(g->alloc, n ? n : 1, sizeof(u32));
    u32 *stack = pxi_alloc_array(g->alloc, n ? n : 1, sizeof(u32));
    u32 *next = pxi_alloc_array(g->alloc, n ? n : 1, sizeof(u32));
    unsigned char *colour = pxi_alloc(g->alloc, n ? n : 1);
    if (!start || !adj || !height || !stack || !next || !colour) goto done;
    /* Adjacency by counting sort of the edges. */
    memset(start, 0, ((size_t)n + 1) * sizeof(u32));
    for (u32 e = 0; e < m; ++e) ++start[g->from[e] + 1];
    for (u32 v = 0; v < n; ++v) start[v + 1] += start[v];
    memcpy(next, start, (size_t)n * sizeof(u32));
    for (u32 e = 0; e < m; ++e) adj[next[g->from[e]]++] = g->to[e];
    memset(colour, 0, n ? n : 1);
    const u64 cap = PX_IO_MAX_NODES + 1;
    res = G_OK;
    for (u32 root = 0; root < n && res == G_OK; ++root) {
        if (colour[root]) continue;
        u32 sp = 0;
        stack[sp++] = root;
        colour[root] = 1;
        next[root] = start[root];
        count[root] = 1;
        height[root] = 0;
        while (sp) {
            u32 v = stack[sp - 1];
            if (next[v] < start[v + 1]) {
                u32 w = adj[next[v]++];
                if (colour[w] == 1) {
                    *where = w;
                    res = G_CYCLE;
                    break;
                }
                if (colour[w] == 0) {
                    colour[w] = 1;
                    next[w] = start[w];
                    count[w] = 1;
                    height[w] = 0;
                    stack[sp++] = w;
                    continue;
                }
                count[v] = count[v] + count[w] > cap ? cap : count[v] + count[w];
                if (height[w] + 1 > height[v]) height[v] = height[w] + 1;
                continue;
            }
            /* v is done: fold it into its parent on the stack. */
            colour[v] = 2;
            --sp;
            if (count[v] > PX_IO_MAX_NODES) {
                *where = v;
                res = G_TOO_MANY;
                break;
            }
            if (height[v] > PXI_MAX_NODE_DEPTH) {
                *where = v;
                res = G_TOO_DEEP;
                break;
            }
            if (sp) {
                u32 p = stack[sp - 1];
                count[p] = count[p] + count[v] > cap ? cap : count[p] + count[v];
                if (height[v] + 1 > height[p]) height[p] = height[v] + 1;
            }
        }
    }
done:
    if (start) pxi_free(g->alloc, start, ((size_t)n + 1) * sizeof(u32));
    if (adj) pxi_free(g->alloc, adj, (size_t)(m ? m : 1) * sizeof(u32));
    if (height) pxi_free(g->alloc, height, (size_t)(n ? n : 1) * sizeof(u32));
    if (stack) pxi_free(g->alloc, stack, (size_t)(n ? n : 1) * sizeof(u32));
    if (next) pxi_free(g->alloc, next, (size_t)(n ? n : 1) * sizeof(u32));
    if (colour) pxi_free(g->alloc, colour, n ? n : 1);
    return res;
}

/* The refusal for a walk's result; `name` describes the vertex. */
static px_status g_error(const io_head *h, int res, const char *format, const char *name, px_error *err) {
    switch (res) {
    case G_CYCLE:
        return pxi_error(err, PX_ERR_IO,
                         "mesh file '%s': its %s node graph is cyclic (%s is its own descendant; Assimp 5.2 "
                         "would recurse until the stack overflows)",
                         h->path, format, name);
    case G_TOO_MANY:
        return pxi_error(err, PX_ERR_IO,
                         "mesh file '%s': %s node %s expands to more than %llu node instances "
                         "(PX_IO_MAX_NODES; Assimp 5.2 builds one node per instance)",
                         h->path, format, name, (u64)PX_IO_MAX_NODES);
    case G_TOO_DEEP:
        return pxi_error(err, PX_ERR_IO,
                         "mesh file '%s': %s node %s starts a chain of more than %d nodes (Assimp 5.2 "
                         "recurses along it)",
                         h->path, format, name, PXI_MAX_NODE_DEPTH);
    default: return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "out of memory reading mesh file '%s'", h->path);
    }
}

/* ---------------------------------------------------------------- COLLADA */

/* A string in the document: offset and length. */
typedef struct g_str {
    u32 off, len;
} g_str;

typedef struct dae_vertex {
    g_str id, name;
} dae_vertex;

typedef struct dae_ref {
    u32 from;
    g_str target;
} dae_ref;

/* A <float_array>, <Name_array> or <IDREF_array>: Assimp 5.2 reads
 * `count` values from it (0 without the attribute). */
typedef struct dae_array {
    g_str id;
    u64 count;
} dae_array;

/* An <accessor>: the values it reads from its source array. */
typedef struct dae_accessor {
    g_str source; /* without the '#' */
    u64 count, offset, stride;
    u64 params, size; /* its <param>s, and their width (float4x4: 16) */
} dae_accessor;

typedef struct dae_scan {
    const unsigned char *d;
    size_t size;
    g_graph g;
    dae_vertex *v;
    u32 vcap;
    dae_ref *r;
    u32 nref, rcap;
    int bad_attr;
    int bad_p;      /* a <p> index list with a byte Assimp's reader never passes */
    int big_number; /* a number Assimp's fast_atof reads as 0 (numbers_ok) */
    /* Data arrays and accessors (dae_accessors). */
    dae_array *arr;
    u32 narr, arrcap;
    dae_accessor *acc;
    u32 nacc, acccap;
    u32 acc_depth;  /* element depth of the open <accessor>, or ~0u */
    int bad_number; /* a count, offset or stride that is not a plain number */
    int controller; /* a <controller> (skin or morph) */
} dae_scan;

static u64 hash_str(const unsigned char *s, u32 len) {
    u64 x = 1469598103934665603ull;
    for (u32 i = 0; i < len; ++i) x = (x ^ s[i]) * 1099511628211ull;
    return x;
}

static int str_eq(const dae_scan *s, g_str a, g_str b) {
    return a.len == b.len && memcmp(s->d + a.off, s->d + b.off, a.len) == 0;
}

/* 1 if the attribute value can be compared raw: no character reference and
 * no tab or line break (pugixml would decode or convert those). */
static int plain_value(const unsigned char *p, size_t len) {
    for (size_t i = 0; i < len; ++i)
        if (p[i] == '&' || p[i] == '\t' || p[i] == '\n' || p[i] == '\r') return 0;
    return 1;
}

static int is_xml_space(int c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

/* Finds `pat` at or after i; returns its offset or size. */
static size_t find(const dae_scan *s, size_t i, const char *pat) {
    size_t n = strlen(pat);
    while (i + n <= s->size) {
        const unsigned char *q = memchr(s->d + i, (unsigned char)pat[0], s->size - i);
        if (!q) return s->size;
        i = (size_t)(q - s->d);
        if (i + n <= s->size && memcmp(q, pat, n) == 0) return i;
        ++i;
    }
    return s->size;
}

static int dae_add_vertex(dae_scan *s, g_str id, g_str name, u32 *out) {
    if (s->g.n >= PX_IO_MAX_NODES) return s->g.too_many = 1, 0;
    if (s->g.n == s->vcap) {
        u32 cap = s->vcap ? s->vcap * 2 : 64;
        dae_vertex *nv = pxi_alloc_array(s->g.alloc, cap, sizeof *nv);
        if (!nv) return s->g.oom = 1, 0;
        if (s->v) {
            memcpy(nv, s->v, (size_t)s->vcap * sizeof *nv);
            pxi_free(s->g.alloc, s->v, (size_t)s->vcap * sizeof *nv);
        }
        s->v = nv;
        s->vcap = cap;
    }
    s->v[s->g.n].id = id;
    s->v[s->g.n].name = name;
    *out = s->g.n++;
    return 1;
}

static int dae_add_ref(dae_scan *s, u32 from, g_str target) {
    if (s->nref >= MAX_EDGES) return s->g.too_many = 1, 0;
    if (s->nref == s->rcap) {
        u32 cap = s->rcap ? s->rcap * 2 : 64;
        dae_ref *nr = pxi_alloc_array(s->g.alloc, cap, sizeof *nr);
        if (!nr) return s->g.oom = 1, 0;
        if (s->r) {
            memcpy(nr, s->r, (size_t)s->rcap * sizeof *nr);
            pxi_free(s->g.alloc, s->r, (size_t)s->rcap * sizeof *nr);
        }
        s->r = nr;
        s->rcap = cap;
    }
    s->r[s->nref].from = from;
    s->r[s->nref].target = target;
    ++s->nref;
    return 1;
}

/* The text of a <p> element (from `i`) as ColladaParser::ReadPrimitives
 * reads it: its first text or CDATA child. ReadPrimitives loops while the
 * text has bytes, strtol10 then SkipSpacesAndLineEnd: a byte that is neither
 * a digit, a sign nor ' ', '\t', '\r', '\n' is never passed, and a 0 index is
 * pushed for ever (a 1-byte corruption of a 1 KB file took 60 s and ended in
 * std::bad_alloc). A character reference is refused too (pugixml would
 * decode it to anything). */
static int p_content_ok(const dae_scan *s, size_t i) {
    const unsigned char *d = s->d;
    size_t j = i, end = s->size;
    while (j < end && is_xml_space(d[j])) ++j;
    if (end - j >= 9 && memcmp(d + j, "<![CDATA[", 9) == 0) { /* whitespace text is dropped */
        i = j + 9;
        end = find(s, i, "]]>");
    }
    /* Indices are non-negative and below 2^31 (every array count is): a
     * sign or a larger number was wrapped by strtol10 (review s32: -1 read
     * as 0, 4294967297 as 1, with PX_OK). */
    u64 v = 0;
    int in_token = 0; /* a '+' may open a token (xs:unsignedLong allows it) */
    for (j = i; j < end && !(d[j] == '<' && end == s->size); ++j) {
        if (d[j] >= '0' && d[j] <= '9') {
            v = 10 * v + (u64)(d[j] - '0');
            if (v > 0x7FFFFFFFull) return 0;
            in_token = 1;
        } else if (is_xml_space(d[j])) {
            v = 0, in_token = 0;
        } else if (d[j] == '+' && !in_token && j + 1 < end && d[j + 1] >= '0' && d[j + 1] <= '9') {
            in_token = 1;
        } else {
            return 0;
        }
    }
    return 1;
}

/* The numbers of a <float_array>, a transform element or a <unit meter>
 * as Assimp's fast_atoreal_move reads them: the digits before the point
 * through strtoul10_64, which returns 0 past 2^64 - 1, and the exponent's
 * through a 32-bit strtoul10, which wraps (review s32:
 * 10000000000000000000000 in a float_array made every vertex 0, in
 * <translate> or <unit meter> it collapsed the mesh or left it where it
 * was, with PX_OK). Such a number is refused. */
static int numbers_ok(const unsigned char *d, size_t i, size_t end) {
    u64 mant = 0, expo = 0;
    int part = 0; /* 0 integer digits, 1 fraction, 2 exponent */
    for (; i < end && d[i] != '<'; ++i) {
        unsigned char c = d[i];
        if (c >= '0' && c <= '9') {
            const u64 k = (u64)(c - '0');
            if (part == 0) {
                if (mant > (~0ull - k) / 10) return 0;
                mant = 10 * mant + k;
            } else if (part == 2) {
                expo = 10 * expo + k;
                if (expo > 0xFFFFFFFFull) return 0;
            }
        } else if (c == '.' && part == 0) {
            part = 1;
        } else if (c == 'e' || c == 'E') {
            part = 2;
        } else if (c != '+' && c != '-') {
            mant = expo = 0, part = 0;
        }
    }
    return 1;
}

/* Grows a table of `size`-byte records to hold one more. */
static void *dae_grow(dae_scan *s, void *a, u32 n, u32 *cap, size_t size) {
    if (n < *cap) return a;
    if (n >= MAX_EDGES) return s->g.too_many = 1, NULL;
    u32 c = *cap ? *cap * 2 : 64;
    void *b = pxi_alloc_array(s->g.alloc, c, size);
    if (!b) return s->g.oom = 1, NULL;
    if (a) {
        memcpy(b, a, (size_t)n * size);
        pxi_free(s->g.alloc, a, (size_t)*cap * size);
    }
    *cap = c;
    return b;
}

/* An attribute value as pugixml's as_uint would read it, when it is plain
 * decimal digits (blank space around them allowed) of at most 32 bits; else
 * sets bad_number. An absent attribute is `absent`. */
static u64 dae_number(dae_scan *s, g_str v, int present, u64 absent) {
    if (!present) return absent;
    const unsigned char *p = s->d + v.off, *e = p + v.len;
    while (p < e && is_xml_space(*p)) ++p;
    while (e > p && is_xml_space(e[-1])) --e;
    u64 x = 0;
    if (p == e) s->bad_number = 1;
    for (; p < e; ++p) {
        if (*p < '0' || *p > '9' || x > 0xFFFFFFFFull) return s->bad_number = 1, 0;
        x = x * 10 + (u64)(*p - '0');
    }
    if (x > 0x7FFFFFFFull) s->bad_number = 1; /* accessor counts are read as int */
    return x;
}

/* Scans the document's tags. Returns 0 on a refusal (flags in s). */
static int dae_tags(dae_scan *s, int *too_deep) {
    /* Open elements: the graph vertex each is, or ~0u. */
    static const u32 none = ~0u;
    u32 open[XML_MAX_DEPTH];
    u32 depth = 0, vtop = none; /* innermost open vertex */
    size_t i = 0;
    const unsigned char *d = s->d;
    while (i < s->size) {
        const unsigned char *lt = memchr(d + i, '<', s->size - i);
        if (!lt) break;
        i = (size_t)(lt - d);
        if (s->size - i >= 4 && memcmp(d + i, "<!--", 4) == 0) {
            i = find(s, i + 4, "-->") + 3;
            continue;
        }
        if (s->size - i >= 9 && memcmp(d + i, "<![CDATA[", 9) == 0) {
            i = find(s, i + 9, "]]>") + 3;
            continue;
        }
        if (s->size - i >= 2 && d[i + 1] == '?') {
            i = find(s, i + 2, "?>") + 2;
            continue;
        }
        if (s->size - i >= 2 && d[i + 1] == '!') { /* DOCTYPE, with an internal subset in [] */
            size_t j = i + 2;
            int bracket = 0;
            while (j < s->size && (d[j] != '>' || bracket)) {
                if (d[j] == '[') bracket = 1;
                if (d[j] == ']') bracket = 0;
                ++j;
            }
            i = j + 1;
            continue;
        }
        if (s->size - i >= 2 && d[i + 1] == '/') { /* end tag: closes the innermost element */
            if (depth) {
                --depth;
                if (depth == s->acc_depth) s->acc_depth = none;
                if (open[depth] != none) {
                    vtop = none;
                    for (u32 k = depth; k-- > 0;)
                        if (open[k] != none) {
                            vtop = open[k];
                            break;
                        }
                }
            }
            const unsigned char *gt = memchr(d + i, '>', s->size - i);
            i = gt ? (size_t)(gt - d) + 1 : s->size;
            continue;
        }
        /* Start tag: name, attributes, "/>" or ">". */
        size_t j = i + 1, name0 = j;
        while (j < s->size && !is_xml_space(d[j]) && d[j] != '/' && d[j] != '>') ++j;
        size_t name_len = j - name0;
        g_str id = {0, 0}, name = {0, 0}, url = {0, 0}, count = {0, 0}, offset = {0, 0}, stride = {0, 0},
              source = {0, 0}, type = {0, 0}, meter = {0, 0};
        int has_url = 0, self_closing = 0, has_id = 0, has_count = 0, has_offset = 0, has_stride = 0,
            has_source = 0, has_type = 0, has_meter = 0;
        for (;;) {
            while (j < s->size && is_xml_space(d[j])) ++j;
            if (j >= s->size) break;
            if (d[j] == '>') {
                ++j;
                break;
            }
            if (d[j] == '/') {
                self_closing = j + 1 < s->size && d[j + 1] == '>';
                j += self_closing ? 2 : 1;
                if (self_closing) break;
                continue;
            }
            size_t a0 = j;
            while (j < s->size && d[j] != '=' && d[j] != '>' && d[j] != '/' && !is_xml_space(d[j])) ++j;
            size_t a_len = j - a0;
            while (j < s->size && is_xml_space(d[j])) ++j;
            if (j >= s->size || d[j] != '=') continue;
            ++j;
            while (j < s->size && is_xml_space(d[j])) ++j;
            if (j >= s->size || (d[j] != '"' && d[j] != '\'')) continue;
            unsigned char q = d[j++];
            size_t v0 = j;
            const unsigned char *qe = memchr(d + j, q, s->size - j);
            j = qe ? (size_t)(qe - d) : s->size;
            g_str val = {(u32)v0, (u32)(j - v0)};
            if (j < s->size) ++j;
#define ATTR_IS(s_) (a_len == sizeof(s_) - 1 && memcmp(d + a0, s_, a_len) == 0)
            if (ATTR_IS("id")) id = val, has_id = 1;
            if (ATTR_IS("name")) name = val;
            if (ATTR_IS("url")) url = val, has_url = 1;
            if (ATTR_IS("count")) count = val, has_count = 1;
            if (ATTR_IS("offset")) offset = val, has_offset = 1;
            if (ATTR_IS("stride")) stride = val, has_stride = 1;
            if (ATTR_IS("source")) source = val, has_source = 1;
            if (ATTR_IS("type")) type = val, has_type = 1;
            if (ATTR_IS("meter")) meter = val, has_meter = 1;
#undef ATTR_IS
        }
        i = j;
        /* <vcount> is read as <p> is: a count of 4294967299 wrapped to 3 (review s32). */
        if (((name_len == 1 && d[name0] == 'p') || (name_len == 6 && memcmp(d + name0, "vcount", 6) == 0)) &&
            !self_closing && !p_content_ok(s, i))
            return s->bad_p = 1, 0;
#define NAME_IS(s_) (name_len == sizeof(s_) - 1 && memcmp(d + name0, s_, name_len) == 0)
        if (!self_closing &&
            (NAME_IS("float_array") || NAME_IS("translate") || NAME_IS("rotate") || NAME_IS("scale") ||
             NAME_IS("matrix") || NAME_IS("lookat") || NAME_IS("skew")) &&
            !numbers_ok(d, i, s->size))
            return s->big_number = 1, 0;
        if (NAME_IS("unit") && has_meter && !numbers_ok(d, meter.off, (size_t)meter.off + meter.len))
            return s->big_number = 1, 0;
        /* Controllers are refused: ColladaParser::ReadControllerWeights
         * resizes its weights to the sum of <vcount> (a 2 KB file took
         * 1.5 GB, instantiated or not), and ColladaLoader indexes bones,
         * weights and vertices by the <v> values and the joint count
         * unchecked (SIGSEGV; an ai_assert abort). */
        if (NAME_IS("controller")) return s->controller = 1, 0;
        if (NAME_IS("float_array") || NAME_IS("Name_array") || NAME_IS("IDREF_array")) {
            if (has_id) {
                if (!plain_value(d + id.off, id.len)) return s->bad_attr = 1, 0;
                dae_array *a = dae_grow(s, s->arr, s->narr, &s->arrcap, sizeof *a);
                if (!a) return 0;
                s->arr = a;
                a[s->narr].id = id;
                a[s->narr].count = dae_number(s, count, has_count, 0);
                ++s->narr;
            }
        } else if (NAME_IS("accessor") && s->acc_depth == none) {
            dae_accessor *a = dae_grow(s, s->acc, s->nacc, &s->acccap, sizeof *a);
            if (!a) return 0;
            s->acc = a;
            a += s->nacc++;
            memset(a, 0, sizeof *a);
            if (has_source && source.len && d[source.off] == '#') {
                if (!plain_value(d + source.off, source.len)) return s->bad_attr = 1, 0;
                a->source.off = source.off + 1;
                a->source.len = source.len - 1;
            }
            a->count = dae_number(s, count, has_count, 0);
            a->offset = dae_number(s, offset, has_offset, 0);
            a->stride = dae_number(s, stride, has_stride, 1);
            if (!self_closing) s->acc_depth = depth;
        } else if (NAME_IS("param") && s->acc_depth != none) {
            /* ReadAccessor: each <param> below the accessor; a typed one
             * adds its width. */
            dae_accessor *a = &s->acc[s->nacc - 1];
            ++a->params;
            if (has_type) a->size += type.len == 8 && memcmp(d + type.off, "float4x4", 8) == 0 ? 16 : 1;
        }
#undef NAME_IS
        if (s->bad_number) return 0;
        int is_node = (name_len == 4 && memcmp(d + name0, "node", 4) == 0) ||
                      (name_len == 12 && memcmp(d + name0, "visual_scene", 12) == 0);
        int is_inst = name_len == 13 && memcmp(d + name0, "instance_node", 13) == 0;
        u32 vertex = none;
        if (is_node) {
            if (!plain_value(d + id.off, id.len) || !plain_value(d + name.off, name.len))
                return s->bad_attr = 1, 0;
            if (!dae_add_vertex(s, id, name, &vertex)) return 0;
            if (vtop != none && !g_edge(&s->g, vtop, vertex)) return 0;
        } else if (is_inst && has_url && vtop != none && url.len && d[url.off] == '#') {
            if (!plain_value(d + url.off, url.len)) return s->bad_attr = 1, 0;
            g_str target = {url.off + 1, url.len - 1};
            if (!dae_add_ref(s, vtop, target)) return 0;
        }
        if (!self_closing) {
            if (depth == XML_MAX_DEPTH) return *too_deep = 1, 0;
            open[depth++] = vertex;
            if (vertex != none) vtop = vertex;
        }
    }
    return 1;
}

/* Resolves the references as ColladaLoader::ResolveNodeInstances does: by
 * id, else (FindNode) by name or id; every match gets an edge. */
static int dae_resolve(dae_scan *s) {
    u32 n = s->g.n, size = 16;
    while (size < 2 * n) size *= 2;
    u32 *by_id = pxi_alloc_array(s->g.alloc, size, sizeof(u32));
    u32 *by_name = pxi_alloc_array(s->g.alloc, size, sizeof(u32));
    int ok = 0;
    if (!by_id || !by_name) {
        s->g.oom = 1;
        goto done;
    }
    memset(by_id, 0xFF, (size_t)size * sizeof(u32));
    memset(by_name, 0xFF, (size_t)size * sizeof(u32));
    for (u32 v = 0; v < n; ++v) {
        u32 k = (u32)hash_str(s->d + s->v[v].id.off, s->v[v].id.len) & (size - 1);
        while (by_id[k] != ~0u) k = (k + 1) & (size - 1);
        by_id[k] = v;
        k = (u32)hash_str(s->d + s->v[v].name.off, s->v[v].name.len) & (size - 1);
        while (by_name[k] != ~0u) k = (k + 1) & (size - 1);
        by_name[k] = v;
    }
    for (u32 r = 0; r < s->nref; ++r) {
        g_str t = s->r[r].target;
        int found = 0;
        for (int pass = 0; pass < 2 && !found; ++pass) {
            u32 *table = pass ? by_name : by_id;
            u32 k = (u32)hash_str(s->d + t.off, t.len) & (size - 1);
            for (; table[k] != ~0u; k = (k + 1) & (size - 1)) {
                const dae_vertex *w = &s->v[table[k]];
                if (str_eq(s, pass ? w->name : w->id, t)) {
                    if (!g_edge(&s->g, s->r[r].from, table[k])) goto done;
                    found = 1;
                }
            }
        }
    }
    ok = 1;
done:
    if (by_id) pxi_free(s->g.alloc, by_id, (size_t)size * sizeof(u32));
    if (by_name) pxi_free(s->g.alloc, by_name, (size_t)size * sizeof(u32));
    return ok;
}

/* Describes vertex v for a message: its id or name. */
static void dae_name(const dae_scan *s, u32 v, char *out, size_t size) {
    g_str a = s->v[v].id.len ? s->v[v].id : s->v[v].name;
    snprintf(out, size, "'%.*s'", (int)(a.len < 60 ? a.len : 60), (const char *)s->d + a.off);
}

/* The accessors, checked against the arrays they read (Assimp 5.2 does not):
 * ColladaParser::ExtractDataObjectFromChannel reads, for an index below the
 * accessor's count, the values offset + index * stride + (0 .. params - 1)
 * of its source array, and ColladaLoader::ReadFloat offset + index * stride
 * + (0 .. width - 1), where the array holds the `count` values its count
 * attribute declares (none without it). An accessor reading past them made
 * Assimp read past the array's heap block: a SIGSEGV (no count attribute,
 * or an offset of 100000), or garbage points returned as PX_OK (a count of
 * 3 for 24 values, a stride of 1000). A duplicate array id counts with its
 * smallest count. Returns the first accessor that reads too far, or ~0u;
 * *need and *have get its values. */
static u32 dae_accessors(dae_scan *s, u64 *need, u64 *have) {
    u32 size = 16, bad = ~0u;
    while (size < 2 * s->narr) size *= 2;
    u32 *table = pxi_alloc_array(s->g.alloc, size, sizeof(u32));
    if (!table) return s->g.oom = 1, ~0u;
    memset(table, 0xFF, (size_t)size * sizeof(u32));
    for (u32 a = 0; a < s->narr; ++a) {
        const g_str id = s->arr[a].id;
        u32 k = (u32)hash_str(s->d + id.off, id.len) & (size - 1);
        for (; table[k] != ~0u; k = (k + 1) & (size - 1))
            if (str_eq(s, s->arr[table[k]].id, id)) break;
        if (table[k] == ~0u)
            table[k] = a;
        else if (s->arr[a].count < s->arr[table[k]].count)
            s->arr[table[k]].count = s->arr[a].count;
    }
    for (u32 c = 0; c < s->nacc && bad == ~0u; ++c) {
        const dae_accessor *a = &s->acc[c];
        if (!a->count || !a->source.len) continue;
        u32 k = (u32)hash_str(s->d + a->source.off, a->source.len) & (size - 1);
        for (; table[k] != ~0u; k = (k + 1) & (size - 1))
            if (str_eq(s, s->arr[table[k]].id, a->source)) break;
        if (table[k] == ~0u) continue; /* Assimp: "Unable to resolve library reference" */
        u64 width = a->params > a->size ? a->params : a->size;
        if (width < 1) width = 1;
        const u64 n = pxi_sat_add(pxi_sat_add(a->offset, pxi_sat_mul(a->count - 1, a->stride)), width);
        if (n > s->arr[table[k]].count) {
            bad = c;
            *need = n;
            *have = s->arr[table[k]].count;
        }
    }
    pxi_free(s->g.alloc, table, (size_t)size * sizeof(u32));
    return bad;
}

px_status pxi_check_dae(const io_head *h, px_error *err) {
    unsigned char *doc;
    px_status st = pxi_read_all(h, &doc, err);
    if (st != PX_OK) return st;
    dae_scan s;
    memset(&s, 0, sizeof s);
    s.d = doc;
    s.size = (size_t)h->size;
    s.g.alloc = h->alloc;
    s.acc_depth = ~0u;
    int too_deep = 0;
    u64 *count = NULL;
    if (h->size >= ~0u) {
        st = pxi_error(err, PX_ERR_IO, "mesh file '%s': a COLLADA file of 4 GiB or more", h->path);
        goto done;
    }
    if (!dae_tags(&s, &too_deep) || !dae_resolve(&s)) {
        if (s.g.oom)
            st = pxi_error(err, PX_ERR_OUT_OF_MEMORY, "out of memory reading mesh file '%s'", h->path);
        else if (too_deep)
            st = pxi_error(err, PX_ERR_IO, "mesh file '%s': its XML is nested more than %d elements deep",
                           h->path, XML_MAX_DEPTH);
        else if (s.controller)
            st = pxi_error(err, PX_ERR_IO,
                           "mesh file '%s': COLLADA controllers (skins, morphs) are not accepted (Assimp 5.2 "
                           "reads their vertex weights unchecked)",
                           h->path);
        else if (s.bad_number)
            st = pxi_error(
                err, PX_ERR_IO,
                "mesh file '%s': a COLLADA accessor or data array has a count, offset or stride that "
                "is not a plain number below 2^31 (not accepted: what Assimp 5.2 reads could not be "
                "checked)",
                h->path);
        else if (s.big_number)
            st = pxi_error(err, PX_ERR_IO,
                           "mesh file '%s': a COLLADA number of 2^64 or more before its point, or with an "
                           "exponent of 2^32 or more (Assimp 5.2 would read it as 0, or wrap the exponent)",
                           h->path);
        else if (s.bad_p)
            st =
                pxi_error(err, PX_ERR_IO,
                          "mesh file '%s': a COLLADA <p> or <vcount> list holds something other than "
                          "integers from 0 to 2^31 - 1 and blanks (Assimp 5.2 would push 0 indices for ever, "
                          "or wrap the number)",
                          h->path);
        else if (s.bad_attr)
            st = pxi_error(err, PX_ERR_IO,
                           "mesh file '%s': a COLLADA node id, name or instance_node url holds a character "
                           "reference, tab or line break (not accepted: the node graph could not be checked)",
                           h->path);
        else
            st = pxi_error(err, PX_ERR_IO,
                           "mesh file '%s': its COLLADA node graph has more than %llu nodes or %u links",
                           h->path, (u64)PX_IO_MAX_NODES, MAX_EDGES);
        goto done;
    }
    u64 need = 0, have = 0;
    const u32 bad_acc = dae_accessors(&s, &need, &have);
    if (s.g.oom) {
        st = pxi_error(err, PX_ERR_OUT_OF_MEMORY, "out of memory reading mesh file '%s'", h->path);
        goto done;
    }
    if (bad_acc != ~0u) {
        const dae_accessor *a = &s.acc[bad_acc];
        st = pxi_error(
            err, PX_ERR_IO,
            "mesh file '%s': a COLLADA accessor of array '%.*s' reads %llu values (offset %llu, "
            "count %llu, stride %llu), but the array declares %llu (its count attribute; Assimp 5.2 "
            "would read past it)",
            h->path, (int)(a->source.len < 60 ? a->source.len : 60), (const char *)s.d + a->source.off, need,
            a->offset, a->count, a->stride, have);
        goto done;
    }
    count = pxi_alloc_array(h->alloc, s.g.n ? s.g.n : 1, sizeof(u64));
    if (!count) {
        st = pxi_error(err, PX_ERR_OUT_OF_MEMORY, "out of memory reading mesh file '%s'", h->path);
        goto done;
    }
    u32 where = 0;
    int res = g_walk(&s.g, count, &where);
    if (res != G_OK) {
        char name[80];
        if (res != G_OOM) dae_name(&s, where, name, sizeof name);
        st = g_error(h, res, "COLLADA", res == G_OOM ? "" : name, err);
    }
done:
    if (count) pxi_free(h->alloc, count, (size_t)(s.g.n ? s.g.n : 1) * sizeof(u64));
    if (s.v) pxi_free(h->alloc, s.v, (size_t)s.vcap * sizeof *s.v);
    if (s.r) pxi_free(h->alloc, s.r, (size_t)s.rcap * sizeof *s.r);
    if (s.arr) pxi_free(h->alloc, s.arr, (size_t)s.arrcap * sizeof *s.arr);
    if (s.acc) pxi_free(h->alloc, s.acc, (size_t)s.acccap * sizeof *s.acc);
    g_free(&s.g);
    pxi_free(h->alloc, doc, (size_t)h->size + 1);
    return st;
}

/* ------------------------------------------------------------------- glTF */

typedef struct json {
    const unsigned char *p, *end;
    int bad; /* not JSON (rapidjson would refuse it too), or too deep */
    int deep;
    int escaped_key;
    int dup;         /* a member that matters given twice */
    int bad_child;   /* a child that is not a node index */
    int v1_children; /* glTF 1.0 nodes with children */
    int sparse;      /* an accessor with a "sparse" member */
    int quantized;   /* an extension that changes how positions are stored */
    g_graph g;
    u32 nodes; /* elements of "nodes" */
    int have_nodes, have_scenes, have_scene;
    u32 *roots; /* scene roots, scene by scene: counts in roots_n */
    u32 nroots, rcap;
    u32 *scene_end; /* end index in roots of each scene */
    u32 nscenes, scap;
    /* For the count of triangles Assimp must return (pxi_check_gltf): each
     * accessor's "count" (~0u: none or not a plain 32-bit count), and each
     * mesh primitive's indices accessor, POSITION accessor and mode (~0u:
     * absent), three entries a primitive. */
    u32 *acc_count, nacc, acc_cap;
    /* Where each accessor reads (accessor_info, four a accessor: bufferView,
     * byteOffset, componentType, components), each buffer view (four a view:
     * buffer, byteOffset, byteLength, byteStride) and each buffer's
     * byteLength; J_ABSENT or J_UNREAD where the member is missing or not a
     * plain 32-bit count. */
    u32 *acc_info, nacc_info, acc_info_cap;
    u32 *views, nviews, views_cap;
    u32 *bufs, nbufs, bufs_cap;
    /* (primitive, accessor) of every other attribute and morph target a
     * primitive names (NORMAL, TEXCOORD_0, COLOR_0, targets' POSITION...):
     * Assimp reads them too. */
    u32 *attrs, nattrs, attrs_cap;
    u32 *prim, nprim, prim_cap;
    u32 *mesh_end, nmesh, mesh_cap;     /* each mesh's end in prim, in primitives */
    u32 *node_mesh, nnode_mesh, nm_cap; /* (node, mesh) pairs of the nodes' "mesh" members */
    u32 scene;                          /* the "scene" member (~0u: none, 0 is taken) */
    int meshes_v1;                      /* "meshes" is not an array (glTF 1.0) */
} json;

static void j_ws(json *j) {
    while (j->p < j->end && (*j->p == ' ' || *j->p == '\t' || *j->p == '\n' || *j->p == '\r')) ++j->p;
}

/* A string: sets *s, *n to its raw bytes (escapes not decoded), *esc when it
 * has an escape. */
static int j_string(json *j, const unsigned char **s, size_t *n, int *esc) {
    j_ws(j);
    if (j->p >= j->end || *j->p != '"') return j->bad = 1, 0;
    const unsigned char *b = ++j->p;
    int e = 0;
    while (j->p < j->end && *j->p != '"') {
        if (*j->p < 0x20) return j->bad = 1, 0;
        if (*j->p == '\\') {
            e = 1;
            if (++j->p >= j->end) return j->bad = 1, 0;
        }
        ++j->p;
    }
    if (j->p >= j->end) return j->bad = 1, 0;
    if (s) *s = b, *n = (size_t)(j->p - b);
    if (esc) *esc = e;
    ++j->p;
    return 1;
}

static int j_value(json *j, int depth);

/* A number (JSON grammar). *uint gets its value when it is a plain
 * non-negative integer that fits in 32 bits, else stays ~0. */
static int j_number(json *j, u64 *uint) {
    const unsigned char *b = j->p;
    if (uint) *uint = ~0ull;
    if (j->p < j->end && *j->p == '-') ++j->p;
    if (j->p >= j->end || *j->p < '0' || *j->p > '9') return j->bad = 1, 0;
    u64 v = 0;
    int plain = *b != '-';
    if (*j->p == '0') {
        ++j->p;
    } else {
        while (j->p < j->end && *j->p >= '0' && *j->p <= '9')
            v = pxi_sat_add(pxi_sat_mul(v, 10), (u64)(*j->p++ - '0'));
    }
    if (j->p < j->end && *j->p == '.') {
        plain = 0;
        ++j->p;
        if (j->p >= j->end || *j->p < '0' || *j->p > '9') return j->bad = 1, 0;
        while (j->p < j->end && *j->p >= '0' && *j->p <= '9') ++j->p;
    }
    if (j->p < j->end && (*j->p == 'e' || *j->p == 'E')) {
        plain = 0;
        ++j->p;
        if (j->p < j->end && (*j->p == '+' || *j->p == '-')) ++j->p;
        if (j->p >= j->end || *j->p < '0' || *j->p > '9') return j->bad = 1, 0;
        while (j->p < j->end && *j->p >= '0' && *j->p <= '9') ++j->p;
    }
    if (plain && uint && v <= 0xFFFFFFFFu) *uint = v;
    return 1;
}

static int j_literal(json *j, const char *lit) {
    size_t n = strlen(lit);
    if ((size_t)(j->end - j->p) < n || memcmp(j->p, lit, n) != 0) return j->bad = 1, 0;
    j->p += n;
    return 1;
}

/* Skips any value (depth: nesting of the value's container). */
static int j_value(json *j, int depth) {
    j_ws(j);
    if (j->p >= j->end) return j->bad = 1, 0;
    if (depth > JSON_MAX_DEPTH) return j->deep = 1, j->bad = 1, 0;
    switch (*j->p) {
    case '{':
        ++j->p;
        j_ws(j);
        if (j->p < j->end && *j->p == '}') return ++j->p, 1;
        for (;;) {
            if (!j_string(j, NULL, NULL, NULL)) return 0;
            j_ws(j);
            if (j->p >= j->end || *j->p != ':') return j->bad = 1, 0;
            ++j->p;
            if (!j_value(j, depth + 1)) return 0;
            j_ws(j);
            if (j->p < j->end && *j->p == ',') {
                ++j->p;
                continue;
            }
            if (j->p < j->end && *j->p == '}') return ++j->p, 1;
            return j->bad = 1, 0;
        }
    case '[':
        ++j->p;
        j_ws(j);
        if (j->p < j->end && *j->p == ']') return ++j->p, 1;
        for (;;) {
            if (!j_value(j, depth + 1)) return 0;
            j_ws(j);
            if (j->p < j->end && *j->p == ',') {
                ++j->p;
                continue;
            }
            if (j->p < j->end && *j->p == ']') return ++j->p, 1;
            return j->bad = 1, 0;
        }
    case '"': return j_string(j, NULL, NULL, NULL);
    case 't': return j_literal(j, "true");
    case 'f': return j_literal(j, "false");
    case 'n': return j_literal(j, "null");
    default: return j_number(j, NULL);
    }
}

/* Iterates over an object's members: calls `member` for each with its raw
 * key; `member` must consume the value. */
typedef int (*j_member_fn)(json *j, const unsigned char *key, size_t n, int depth, void *ctx);

static int j_object(json *j, int depth, j_member_fn member, void *ctx) {
    j_ws(j);
    if (depth > JSON_MAX_DEPTH) return j->deep = 1, j->bad = 1, 0;
    if (j->p >= j->end || *j->p != '{')
        return j_value(j, depth); /* not an object: skipped (Assimp refuses) */
    ++j->p;
    j_ws(j);
    if (j->p < j->end && *j->p == '}') return ++j->p, 1;
    for (;;) {
        const unsigned char *k;
        size_t n;
        int esc;
        if (!j_string(j, &k, &n, &esc)) return 0;
        j_ws(j);
        if (j->p >= j->end || *j->p != ':') return j->bad = 1, 0;
        ++j->p;
        if (esc) j->escaped_key = 1;
        if (!member(j, k, n, depth + 1, ctx)) return 0;
        j_ws(j);
        if (j->p < j->end && *j->p == ',') {
            ++j->p;
            continue;
        }
        if (j->p < j->end && *j->p == '}') return ++j->p, 1;
        return j->bad = 1, 0;
    }
}

/* Iterates over an array's elements: calls `element` with the index. */
typedef int (*j_element_fn)(json *j, u32 index, int depth, void *ctx);

static int j_array(json *j, int depth, j_element_fn element, void *ctx) {
    j_ws(j);
    if (depth > JSON_MAX_DEPTH) return j->deep = 1, j->bad = 1, 0;
    if (j->p >= j->end || *j->p != '[') return j_value(j, depth); /* not an array: skipped */
    ++j->p;
    j_ws(j);
    if (j->p < j->end && *j->p == ']') return ++j->p, 1;
    for (u32 i = 0;; ++i) {
        if (!element(j, i, depth + 1, ctx)) return 0;
        j_ws(j);
        if (j->p < j->end && *j->p == ',') {
            ++j->p;
            continue;
        }
        if (j->p < j->end && *j->p == ']') return ++j->p, 1;
        return j->bad = 1, 0;
    }
}

static int key_is(const unsigned char *k, size_t n, const char *s) {
    return n == strlen(s) && memcmp(k, s, n) == 0;
}

static int push_u32(json *j, u32 **a, u32 *len, u32 *cap, u32 v) {
    if (*len >= MAX_EDGES) return j->g.too_many = 1, 0;
    if (!g_grow(&j->g, a, cap, *len + 1)) return 0;
    (*a)[(*len)++] = v;
    return 1;
}

/* Member `want` of an object: its value into *out when it is a plain
 * 32-bit count (else ~0u); any other member is skipped. */
static int j_plain_u32(json *j, const unsigned char *k, size_t n, const char *want, int depth, u32 *out) {
    if (!key_is(k, n, want)) return j_value(j, depth);
    j_ws(j);
    if (j->p >= j->end || *j->p < '0' || *j->p > '9') return j_value(j, depth);
    u64 v;
    if (!j_number(j, &v)) return 0;
    *out = v == ~0ull ? ~0u : (u32)v;
    return 1;
}

/* An element of a "children" or a scene's "nodes" array: a node index. */
typedef struct j_list_ctx {
    u32 owner; /* the parent node, or ~0u for a scene */
} j_list_ctx;

static int child_element(json *j, u32 index, int depth, void *ctx) {
    (void)index;
    j_list_ctx *c = ctx;
    j_ws(j);
    u64 v;
    if (j->p >= j->end || ((*j->p < '0' || *j->p > '9') && *j->p != '-')) {
        if (!j_value(j, depth)) return 0;
        return j->bad_child = 1, 0;
    }
    if (!j_number(j, &v)) return 0;
    if (v == ~0ull) return j->bad_child = 1, 0;
    if (c->owner == ~0u) return push_u32(j, &j->roots, &j->nroots, &j->rcap, (u32)v);
    return g_edge(&j->g, c->owner, (u32)v);
}

typedef struct j_node_ctx {
    u32 index;
    int children_seen, mesh_seen;
    int v1; /* glTF 1.0: nodes is an object */
} j_node_ctx;

static int node_member(json *j, const unsigned char *k, size_t n, int depth, void *ctx) {
    j_node_ctx *c = ctx;
    if (key_is(k, n, "mesh") && !c->v1) {
        if (c->mesh_seen++) return j->dup = 1, 0;
        u32 m = ~0u;
        if (!j_plain_u32(j, k, n, "mesh", depth, &m)) return 0;
        return m == ~0u || (push_u32(j, &j->node_mesh, &j->nnode_mesh, &j->nm_cap, c->index) &&
                            push_u32(j, &j->node_mesh, &j->nnode_mesh, &j->nm_cap, m));
    }
    if (!key_is(k, n, "children")) return j_value(j, depth);
    if (c->v1) {
        j->v1_children = 1;
        return 0;
    }
    if (c->children_seen++) return j->dup = 1, 0;
    j_list_ctx lc = {c->index};
    return j_array(j, depth, child_element, &lc);
}

static int node_element(json *j, u32 index, int depth, void *ctx) {
    (void)ctx;
    if (index >= PX_IO_MAX_NODES) return j->g.too_many = 1, 0;
    j->nodes = index + 1;
    j_node_ctx c = {.index = index};
    return j_object(j, depth, node_member, &c);
}

/* glTF 1.0: "nodes": {"name": {...}, ...}. */
static int node_v1_member(json *j, const unsigned char *k, size_t n, int depth, void *ctx) {
    (void)k, (void)n, (void)ctx;
    j_node_ctx c = {.v1 = 1};
    return j_object(j, depth, node_member, &c);
}

static int scene_member(json *j, const unsigned char *k, size_t n, int depth, void *ctx) {
    (void)ctx;
    if (!key_is(k, n, "nodes")) return j_value(j, depth);
    j_list_ctx lc = {~0u};
    return j_array(j, depth, child_element, &lc);
}

static int scene_element(json *j, u32 index, int depth, void *ctx) {
    (void)index, (void)ctx;
    if (!j_object(j, depth, scene_member, NULL)) return 0;
    return push_u32(j, &j->scene_end, &j->nscenes, &j->scap, j->nroots);
}

/* Members not given (J_ABSENT) or given as something other than a plain
 * 32-bit count (J_UNREAD: negative, fractional, too large, a string). */
#define J_ABSENT (~0u)
#define J_UNREAD (~0u - 1)

/* A member's value as a plain 32-bit count, or J_UNREAD. */
static int j_count_value(json *j, int depth, u32 *out) {
    j_ws(j);
    if (j->p < j->end && *j->p >= '0' && *j->p <= '9') {
        u64 v;
        if (!j_number(j, &v)) return 0;
        *out = v >= J_UNREAD ? J_UNREAD : (u32)v;
        return 1;
    }
    *out = J_UNREAD;
    return j_value(j, depth);
}

static int j_count_member(json *j, const unsigned char *k, size_t n, const char *want, int depth, u32 *out,
                          int *matched) {
    if (!key_is(k, n, want)) return 1;
    *matched = 1;
    return j_count_value(j, depth, out);
}

/* An accessor's "type": its number of components (J_UNREAD if unknown). */
static u32 accessor_components(const unsigned char *t, size_t n) {
    static const struct {
        const char *name;
        u32 count;
    } types[] = {{"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3}, {"VEC4", 4},
                 {"MAT2", 4},   {"MAT3", 9}, {"MAT4", 16}};
    for (size_t i = 0; i < sizeof types / sizeof types[0]; ++i)
        if (key_is(t, n, types[i].name)) return types[i].count;
    return J_UNREAD;
}

typedef struct j_accessor {
    u32 count, view, offset, ctype, ncomp;
} j_accessor;

/* glTF 2.0 sparse accessors (glTF2Asset.inl Accessor::Read and
 * Sparse::PatchData) are refused: Assimp 5.2 dereferences their "indices"
 * and its "bufferView" without checking they exist (SIGSEGV on a 400-byte
 * file), reads sparse.count indices and values without checking them
 * against their buffer views, and allocates count * element size bytes for
 * an accessor without a buffer view (the review's gltf_sparse.gltf: 1.8 GB
 * before std::bad_alloc). */
static int accessor_member(json *j, const unsigned char *k, size_t n, int depth, void *ctx) {
    j_accessor *a = ctx;
    if (key_is(k, n, "sparse")) return j->sparse = 1, 0;
    if (key_is(k, n, "type")) {
        const unsigned char *t;
        size_t tn;
        int esc;
        j_ws(j);
        if (j->p >= j->end || *j->p != '"') return a->ncomp = J_UNREAD, j_value(j, depth);
        if (!j_string(j, &t, &tn, &esc)) return 0;
        a->ncomp = esc ? J_UNREAD : accessor_components(t, tn);
        return 1;
    }
    int m = 0;
    if (!j_count_member(j, k, n, "count", depth, &a->count, &m) ||
        !j_count_member(j, k, n, "bufferView", depth, &a->view, &m) ||
        !j_count_member(j, k, n, "byteOffset", depth, &a->offset, &m) ||
        !j_count_member(j, k, n, "componentType", depth, &a->ctype, &m))
        return 0;
    return m ? 1 : j_value(j, depth);
}

static int accessor_element(json *j, u32 index, int depth, void *ctx) {
    (void)index, (void)ctx;
    j_accessor a = {J_ABSENT, J_ABSENT, 0, J_ABSENT, J_ABSENT};
    if (!j_object(j, depth, accessor_member, &a)) return 0;
    /* count: as before, ~0u when it is not a plain 32-bit count */
    return push_u32(j, &j->acc_count, &j->nacc, &j->acc_cap, a.count == J_UNREAD ? ~0u : a.count) &&
           push_u32(j, &j->acc_info, &j->nacc_info, &j->acc_info_cap, a.view) &&
           push_u32(j, &j->acc_info, &j->nacc_info, &j->acc_info_cap, a.offset) &&
           push_u32(j, &j->acc_info, &j->nacc_info, &j->acc_info_cap, a.ctype) &&
           push_u32(j, &j->acc_info, &j->nacc_info, &j->acc_info_cap, a.ncomp);
}

static int view_member(json *j, const unsigned char *k, size_t n, int depth, void *ctx) {
    u32 *v = ctx;
    int m = 0;
    if (!j_count_member(j, k, n, "buffer", depth, &v[0], &m) ||
        !j_count_member(j, k, n, "byteOffset", depth, &v[1], &m) ||
        !j_count_member(j, k, n, "byteLength", depth, &v[2], &m) ||
        !j_count_member(j, k, n, "byteStride", depth, &v[3], &m))
        return 0;
    return m ? 1 : j_value(j, depth);
}

static int view_element(json *j, u32 index, int depth, void *ctx) {
    (void)index, (void)ctx;
    u32 v[4] = {J_ABSENT, 0, J_ABSENT, 0};
    if (!j_object(j, depth, view_member, v)) return 0;
    for (int i = 0; i < 4; ++i)
        if (!push_u32(j, &j->views, &j->nviews, &j->views_cap, v[i])) return 0;
    return 1;
}

static int buffer_member(json *j, const unsigned char *k, size_t n, int depth, void *ctx) {
    int m = 0;
    if (!j_count_member(j, k, n, "byteLength", depth, ctx, &m)) return 0;
    return m ? 1 : j_value(j, depth);
}

static int buffer_element(json *j, u32 index, int depth, void *ctx) {
    (void)index, (void)ctx;
    u32 len = J_ABSENT;
    if (!j_object(j, depth, buffer_member, &len)) return 0;
    return push_u32(j, &j->bufs, &j->nbufs, &j->bufs_cap, len);
}

/* Checks that accessor `a` of a mesh primitive reads within its buffer
 * view, and the view within its buffer, by the sizes the file declares.
 * Assimp 5.2 checks only count times the component size against the view:
 * a byteOffset or byteStride past its end was read out of the heap (review
 * s32: 100,000 positions at byteOffset 800,000 crashed it; 8 of them at
 * byteOffset 8 loaded a coordinate of 4.6e-44 from stray memory). `kind`:
 * 0 indices (unsigned integer scalars), 1 POSITION (VEC3 floats, what glTF
 * 2.0 requires and Assimp assumes: 16-bit positions were read as float
 * bits), 2 any other attribute or morph target (any glTF element). Returns
 * NULL when it does, else what is wrong. */
static const char *gltf_accessor_problem(const json *j, u32 a, int kind) {
    const int position = kind == 1;
    if (a >= j->nacc || 4 * (u64)a + 3 >= j->nacc_info) return "names an accessor that does not exist";
    const u32 *ai = &j->acc_info[4 * (size_t)a];
    const u32 view = ai[0], offset = ai[1], ctype = ai[2], ncomp = ai[3], count = j->acc_count[a];
    u32 csize;
    switch (ctype) {
    case 5120:
    case 5121: csize = 1; break;
    case 5122:
    case 5123: csize = 2; break;
    case 5125:
    case 5126: csize = 4; break;
    default: return "has a componentType that is not a glTF one";
    }
    if (ncomp == J_ABSENT || ncomp == J_UNREAD) return "has no valid \"type\"";
    if (kind != 2 && (position ? ctype != 5126 || ncomp != 3
                               : (ctype == 5126 || ctype == 5120 || ctype == 5122 || ncomp != 1)))
        return position ? "is not VEC3 of floats (5126), as glTF 2.0 requires of POSITION"
                        : "is not a SCALAR of unsigned integers, as glTF 2.0 requires of indices";
    if (count == ~0u) return "has no valid \"count\"";
    if (view == J_ABSENT) return NULL; /* no data: zeros (sparse accessors are refused) */
    if (view == J_UNREAD || offset == J_UNREAD || view >= j->nviews / 4)
        return "names a buffer view that does not exist";
    const u32 *v = &j->views[4 * (size_t)view];
    if (v[0] == J_ABSENT || v[0] == J_UNREAD || v[0] >= j->nbufs || v[1] == J_UNREAD || v[2] == J_ABSENT ||
        v[2] == J_UNREAD || v[3] == J_UNREAD)
        return "reads a buffer view without a valid buffer, byteOffset, byteLength or byteStride";
    const u32 buf = j->bufs[v[0]];
    if (buf == J_ABSENT || buf == J_UNREAD || (u64)v[1] + v[2] > buf)
        return "reads a buffer view that runs past the end of its buffer";
    const u64 elem = (u64)csize * ncomp, stride = v[3] ? v[3] : elem;
    if (stride < elem) return "reads a buffer view whose byteStride is smaller than one element";
    if (count && (u64)offset + (count - 1) * stride + elem > v[2])
        return "reads past the end of its buffer view (byteOffset + count * byteStride)";
    return NULL;
}

/* A mesh primitive: "indices", "mode" and "attributes"."POSITION". A
 * "mode" member whose value is not a plain count (-1, 4.5, "4") is
 * PRIM_MODE_UNREAD; without one the mode is ~0u (4, triangles). */
#define PRIM_MODE_UNREAD (~0u - 1)

/* Another attribute's accessor, recorded with the primitive being read
 * (its index: the primitives pushed so far). */
static int other_attribute(json *j, const unsigned char *k, size_t n, int depth, void *ctx) {
    (void)ctx, (void)k, (void)n;
    u32 acc = J_ABSENT;
    if (!j_count_value(j, depth, &acc)) return 0;
    return push_u32(j, &j->attrs, &j->nattrs, &j->attrs_cap, j->nprim / 3) &&
           push_u32(j, &j->attrs, &j->nattrs, &j->attrs_cap, acc);
}

static int attribute_member(json *j, const unsigned char *k, size_t n, int depth, void *ctx) {
    if (!key_is(k, n, "POSITION")) return other_attribute(j, k, n, depth, ctx);
    return j_plain_u32(j, k, n, "POSITION", depth, &((u32 *)ctx)[1]);
}

static int target_element(json *j, u32 index, int depth, void *ctx) {
    (void)index;
    return j_object(j, depth, other_attribute, ctx); /* a morph target: attributes */
}

static int primitive_member(json *j, const unsigned char *k, size_t n, int depth, void *ctx) {
    u32 *pr = ctx;
    if (key_is(k, n, "attributes")) return j_object(j, depth, attribute_member, pr);
    if (key_is(k, n, "targets")) return j_array(j, depth, target_element, pr);
    if (key_is(k, n, "mode")) {
        pr[2] = PRIM_MODE_UNREAD; /* stays so unless a plain count follows */
        if (!j_plain_u32(j, k, n, "mode", depth, &pr[2])) return 0;
        if (pr[2] == ~0u) pr[2] = PRIM_MODE_UNREAD; /* a count beyond 32 bits */
        return 1;
    }
    return j_plain_u32(j, k, n, "indices", depth, &pr[0]);
}

static int primitive_element(json *j, u32 index, int depth, void *ctx) {
    (void)index, (void)ctx;
    u32 pr[3] = {~0u, ~0u, ~0u};
    if (!j_object(j, depth, primitive_member, pr)) return 0;
    for (int i = 0; i < 3; ++i)
        if (!push_u32(j, &j->prim, &j->nprim, &j->prim_cap, pr[i])) return 0;
    return 1;
}

static int mesh_member(json *j, const unsigned char *k, size_t n, int depth, void *ctx) {
    (void)ctx;
    if (!key_is(k, n, "primitives")) return j_value(j, depth);
    return j_array(j, depth, primitive_element, NULL);
}

static int mesh_element(json *j, u32 index, int depth, void *ctx) {
    (void)index, (void)ctx;
    if (!j_object(j, depth, mesh_member, NULL)) return 0;
    return push_u32(j, &j->mesh_end, &j->nmesh, &j->mesh_cap, j->nprim / 3);
}

/* Why gltf_triangles refused a primitive. */
enum { PRIM_OK, PRIM_LIST_REMAINDER, PRIM_SHORT_STRIP, PRIM_SHORT_LINE, PRIM_BAD_MODE };

/* The triangles Assimp 5.2's glTF 2.0 importer makes: it reads the meshes
 * of the nodes reachable from the scene the "scene" member names (0 by
 * default; glTF2Asset.inl Asset::Load, lazily), each mesh once, and makes
 * the triangles of a primitive from its index count (or, without indices,
 * its POSITION count) n (glTF2Importer.cpp ImportMeshes):
 * - mode 4, triangles (the default): n / 3, the indices left over dropped;
 * - mode 5, triangle strip, and 6, triangle fan: n - 2, degenerate ones
 *   (two equal indices) included: Assimp 5.2 keeps them (measured, with
 *   indices and without);
 * - modes 0 to 3 (points, lines, line loop, line strip): none; their faces
 *   have 1 or 2 indices, and every POSITION is kept as a vertex.
 * Any triangle with an index out of range is dropped with a warning only,
 * which the count lets import.c see. ~0ull when the count is not known
 * (glTF 1.0, no such scene, an accessor count not read); 0 with *bad set
 * to the first mesh primitive Assimp would read wrongly and *why to the
 * reason: a triangle list whose n is not a multiple of 3, a strip or fan
 * of n < 3 (Assimp 5.2 computes n - 2 faces in unsigned arithmetic, or
 * reads past the index buffer, then throws and leaks), a line strip or
 * loop of n < 2 (it reads a second index that is not there), a "mode"
 * that is not one of glTF's 0 to 6. `reach` holds one byte per node,
 * `used` one per mesh (zeroed). */
static u64 gltf_triangles(const json *j, unsigned char *reach, unsigned char *used, u32 *bad, int *why) {
    *bad = ~0u;
    *why = PRIM_OK;
    u32 scene = j->scene == ~0u ? 0 : j->scene;
    if (j->meshes_v1 || scene >= j->nscenes) return ~0ull;
    int any = 0;
    for (u32 r = scene ? j->scene_end[scene - 1] : 0; r < j->scene_end[scene]; ++r)
        reach[j->roots[r]] = 1, any = 1;
    /* The child links are scanned in rounds until nothing new is reached:
     * at most the graph's depth plus one, which g_walk bounded by
     * PXI_MAX_NODE_DEPTH. */
    for (int changed = any; changed;) {
        changed = 0;
        for (u32 e = 0; e < j->g.m; ++e)
            if (reach[j->g.from[e]] && !reach[j->g.to[e]]) reach[j->g.to[e]] = 1, changed = 1;
    }
    for (u32 i = 0; i + 1 < j->nnode_mesh; i += 2) {
        u32 node = j->node_mesh[i], mesh = j->node_mesh[i + 1];
        if (node < j->nodes && reach[node]) {
            if (mesh >= j->nmesh) return ~0ull;
            used[mesh] = 1;
        }
    }
    u64 total = 0;
    int unknown = 0;
    for (u32 m = 0; m < j->nmesh; ++m) {
        if (!used[m]) continue;
        for (u32 p = m ? j->mesh_end[m - 1] : 0; p < j->mesh_end[m]; ++p) {
            const u32 *pr = &j->prim[3 * p];
            u32 acc = pr[0] != ~0u ? pr[0] : pr[1], mode = pr[2] == ~0u ? 4 : pr[2];
            if (mode > 6) {
                *bad = p, *why = PRIM_BAD_MODE;
                return 0;
            }
            if (acc >= j->nacc || j->acc_count[acc] == ~0u) {
                unknown = 1; /* still checking the other primitives' modes */
                continue;
            }
            const u64 n = j->acc_count[acc];
            if (mode == 4 && n % 3 != 0) *why = PRIM_LIST_REMAINDER;
            if ((mode == 5 || mode == 6) && n < 3) *why = PRIM_SHORT_STRIP;
            if ((mode == 2 || mode == 3) && n < 2) *why = PRIM_SHORT_LINE;
            if (*why != PRIM_OK) {
                *bad = p;
                return 0;
            }
            total += mode == 4 ? n / 3 : mode >= 5 ? n - 2 : 0;
        }
    }
    return unknown ? ~0ull : total;
}

/* An element of "extensionsUsed" or "extensionsRequired": Assimp 5.2
 * reads neither of these and takes the stored integers for float bits
 * (review s30: a position of 0.248 came out as 2.3e-41). */
static int extension_element(json *j, u32 index, int depth, void *ctx) {
    (void)index;
    (void)ctx;
    j_ws(j);
    if (j->p >= j->end || *j->p != '"') return j_value(j, depth);
    const unsigned char *k;
    size_t n;
    if (!j_string(j, &k, &n, NULL)) return 0;
    if (key_is(k, n, "KHR_mesh_quantization") || key_is(k, n, "EXT_meshopt_compression")) j->quantized = 1;
    return 1;
}

static int top_member(json *j, const unsigned char *k, size_t n, int depth, void *ctx) {
    (void)ctx;
    if (key_is(k, n, "extensionsUsed") || key_is(k, n, "extensionsRequired"))
        return j_array(j, depth, extension_element, NULL);
    if (key_is(k, n, "nodes")) {
        if (j->have_nodes++) return j->dup = 1, 0;
        j_ws(j);
        if (j->p < j->end && *j->p == '{') return j_object(j, depth, node_v1_member, NULL);
        return j_array(j, depth, node_element, NULL);
    }
    if (key_is(k, n, "accessors")) return j_array(j, depth, accessor_element, NULL);
    if (key_is(k, n, "bufferViews")) return j_array(j, depth, view_element, NULL);
    if (key_is(k, n, "buffers")) return j_array(j, depth, buffer_element, NULL);
    if (key_is(k, n, "scene")) {
        if (j->have_scene++) return j->dup = 1, 0;
        return j_plain_u32(j, k, n, "scene", depth, &j->scene);
    }
    if (key_is(k, n, "meshes")) {
        j_ws(j);
        if (j->p < j->end && *j->p != '[') j->meshes_v1 = 1;
        return j_array(j, depth, mesh_element, NULL);
    }
    if (key_is(k, n, "scenes")) {
        if (j->have_scenes++) return j->dup = 1, 0;
        j_ws(j);
        if (j->p < j->end && *j->p == '{') return j_value(j, depth); /* glTF 1.0 scenes: roots only */
        return j_array(j, depth, scene_element, NULL);
    }
    return j_value(j, depth);
}

/* The JSON of a .gltf file, or of the first chunk of a binary glTF
 * (.glb: "glTF", version, length, then the JSON chunk's length and type). */
static px_status gltf_json(const io_head *h, unsigned char **out, size_t *len, px_error *err) {
    if (h->len >= 4 && memcmp(h->data, "glTF", 4) == 0) {
        if (h->len < 20)
            return pxi_error(err, PX_ERR_IO, "mesh file '%s': a binary glTF file shorter than its header",
                             h->path);
        u64 n = (u64)h->data[12] | (u64)h->data[13] << 8 | (u64)h->data[14] << 16 | (u64)h->data[15] << 24;
        if (n > h->size - 20) n = h->size - 20; /* Assimp refuses a chunk past the end */
        unsigned char *buf = pxi_alloc(h->alloc, (size_t)n + 1);
        if (!buf)
            return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "out of memory reading mesh file '%s'", h->path);
        pxi_rd_seek(h->rd, 20);
        if (!pxi_rd_read(h->rd, buf, (size_t)n)) {
            pxi_free(h->alloc, buf, (size_t)n + 1);
            return pxi_rd_error(h, err);
        }
        buf[n] = 0;
        *out = buf;
        *len = (size_t)n;
        return PX_OK;
    }
    *len = (size_t)h->size;
    return pxi_read_all(h, out, err);
}

px_status pxi_check_gltf(const io_head *h, px_error *err) {
    unsigned char *doc = NULL;
    size_t len = 0;
    px_status st = gltf_json(h, &doc, &len, err);
    if (st != PX_OK) return st;
    json j;
    memset(&j, 0, sizeof j);
    j.scene = ~0u;
    j.p = doc;
    j.end = doc + len;
    j.g.alloc = h->alloc;
    u64 *count = NULL;
    /* A binary glTF 1.0 or anything that is not an object: left to Assimp. */
    j_ws(&j);
    if (j.p >= j.end || *j.p != '{') goto done;
    int ok = j_object(&j, 1, top_member, NULL);
    if (ok) {
        j_ws(&j);
        if (j.p != j.end && !(j.end - j.p == 1 && *j.p == 0)) ok = 0, j.bad = 1;
    }
    if (!ok) {
        if (j.g.oom)
            st = pxi_error(err, PX_ERR_OUT_OF_MEMORY, "out of memory reading mesh file '%s'", h->path);
        else if (j.sparse)
            st = pxi_error(err, PX_ERR_IO,
                           "mesh file '%s': a glTF sparse accessor (not accepted: Assimp 5.2 reads sparse "
                           "accessors without checking their indices, values and size)",
                           h->path);
        else if (j.v1_children)
            st = pxi_error(err, PX_ERR_IO,
                           "mesh file '%s': a glTF 1.0 node with children (not accepted: convert the file to "
                           "glTF 2.0)",
                           h->path);
        else if (j.deep)
            st = pxi_error(err, PX_ERR_IO, "mesh file '%s': its JSON is nested more than %d levels deep",
                           h->path, JSON_MAX_DEPTH);
        else if (j.dup)
            st = pxi_error(err, PX_ERR_IO,
                           "mesh file '%s': a glTF \"nodes\", \"scenes\", \"scene\", \"children\" or "
                           "node \"mesh\" member appears twice (readers disagree on which one counts)",
                           h->path);
        else if (j.bad_child)
            st = pxi_error(err, PX_ERR_IO,
                           "mesh file '%s': a glTF node's \"children\" or a scene's \"nodes\" "
                           "holds something other than a node index",
                           h->path);
        else if (j.g.too_many)
            st = pxi_error(err, PX_ERR_IO,
                           "mesh file '%s': its glTF node graph has more than %llu nodes or %u "
                           "links",
                           h->path, (u64)PX_IO_MAX_NODES, MAX_EDGES);
        else
            st = pxi_error(err, PX_ERR_IO, "mesh file '%s' is not valid JSON (glTF)", h->path);
        goto done;
    }
    if (j.quantized) {
        st =
            pxi_error(err, PX_ERR_IO,
                      "mesh file '%s': its glTF uses KHR_mesh_quantization or EXT_meshopt_compression, which "
                      "Assimp 5.2 does not read (integer positions would be taken for float bits); export "
                      "it with float positions",
                      h->path);
        goto done;
    }
    if (j.escaped_key) {
        st = pxi_error(
            err, PX_ERR_IO,
            "mesh file '%s': a glTF member name has an escape sequence (not accepted: the node graph "
            "could not be checked)",
            h->path);
        goto done;
    }
    /* Children and roots must name nodes (Assimp: "out of bounds"). */
    j.g.n = j.nodes;
    for (u32 e = 0; e < j.g.m; ++e)
        if (j.g.to[e] >= j.nodes) {
            st = pxi_error(err, PX_ERR_IO, "mesh file '%s': glTF node %u has child %u, which does not exist",
                           h->path, j.g.from[e], j.g.to[e]);
            goto done;
        }
    for (u32 r = 0; r < j.nroots; ++r)
        if (j.roots[r] >= j.nodes) {
            st = pxi_error(err, PX_ERR_IO, "mesh file '%s': a glTF scene lists node %u, which does not exist",
                           h->path, j.roots[r]);
            goto done;
        }
    count = pxi_alloc_array(h->alloc, j.nodes ? j.nodes : 1, sizeof(u64));
    if (!count) {
        st = pxi_error(err, PX_ERR_OUT_OF_MEMORY, "out of memory reading mesh file '%s'", h->path);
        goto done;
    }
    u32 where = 0;
    int res = g_walk(&j.g, count, &where);
    char name[32];
    snprintf(name, sizeof name, "%u", where);
    if (res != G_OK) {
        st = g_error(h, res, "glTF", name, err);
        goto done;
    }
    /* A scene instances its roots: their instances add up. */
    for (u32 s = 0, r = 0; s < j.nscenes; ++s) {
        u64 total = 0;
        for (; r < j.scene_end[s]; ++r) total += count[j.roots[r]];
        if (total > PX_IO_MAX_NODES) {
            st = pxi_error(err, PX_ERR_IO,
                           "mesh file '%s': glTF scene %u expands to more than %llu node instances "
                           "(PX_IO_MAX_NODES; Assimp 5.2 builds one node per instance)",
                           h->path, s, (u64)PX_IO_MAX_NODES);
            goto done;
        }
    }
    u32 bad = ~0u;
    int why = PRIM_OK;
    u64 tri = ~0ull;
    unsigned char *reach = pxi_alloc(h->alloc, (size_t)j.nodes + 1),
                  *used = pxi_alloc(h->alloc, (size_t)j.nmesh + 1);
    if (reach && used) {
        memset(reach, 0, (size_t)j.nodes + 1);
        memset(used, 0, (size_t)j.nmesh + 1);
        tri = gltf_triangles(&j, reach, used, &bad, &why);
    }
    /* The accessors Assimp will read: those of the meshes the scene uses. */
    const char *problem = NULL;
    u32 bad_acc = 0, bad_mesh = 0, bad_prim = 0;
    /* kinds: 0 indices, 1 POSITION, 2 the other attributes and morph
     * targets, whose (primitive, accessor) pairs `attrs` lists in order */
    for (u32 m = 0, t = 0; reach && used && bad == ~0u && !problem && m < j.nmesh; ++m) {
        for (u32 p = m ? j.mesh_end[m - 1] : 0; !problem && p < j.mesh_end[m]; ++p) {
            const u32 t0 = t;
            while (t + 1 < j.nattrs && j.attrs[t] == p) t += 2;
            if (!used[m]) continue;
            for (u32 k = 0; k < 2 + (t - t0) / 2 && !problem; ++k) {
                const u32 acc = k < 2 ? j.prim[3 * p + k] : j.attrs[t0 + 2 * (k - 2) + 1];
                if (acc == ~0u) continue;
                if ((problem = gltf_accessor_problem(&j, acc, k < 2 ? (int)k : 2)))
                    bad_acc = acc, bad_mesh = m, bad_prim = p - (m ? j.mesh_end[m - 1] : 0);
            }
        }
    }
    if (reach) pxi_free(h->alloc, reach, (size_t)j.nodes + 1);
    if (used) pxi_free(h->alloc, used, (size_t)j.nmesh + 1);
    if (problem) {
        st = pxi_error(err, PX_ERR_IO, "mesh file '%s': glTF accessor %u (of meshes[%u].primitives[%u]) %s",
                       h->path, bad_acc, bad_mesh, bad_prim, problem);
        goto done;
    }
    if (!reach || !used) {
        st = pxi_error(err, PX_ERR_OUT_OF_MEMORY, "out of memory reading mesh file '%s'", h->path);
        goto done;
    }
    if (bad != ~0u) {
        /* `bad` counts the primitives of all meshes; name the mesh and the
         * primitive in it, as the file does. */
        u32 mesh = 0;
        while (mesh < j.nmesh && j.mesh_end[mesh] <= bad) ++mesh;
        const u32 first = mesh ? j.mesh_end[mesh - 1] : 0, mode = j.prim[3 * bad + 2];
        const u32 acc = j.prim[3 * bad] != ~0u ? j.prim[3 * bad] : j.prim[3 * bad + 1];
        const unsigned long long n = acc < j.nacc ? j.acc_count[acc] : 0;
        const char *what = j.prim[3 * bad] != ~0u
                               ? (n == 1 ? "index" : "indices")
                               : (n == 1 ? "vertex (no indices)" : "vertices (no indices)");
        if (why == PRIM_LIST_REMAINDER)
            st = pxi_error(err, PX_ERR_IO,
                           "mesh file '%s': glTF meshes[%u].primitives[%u] is a triangle list of %llu %s, "
                           "not a multiple of 3 (Assimp 5.2 would drop the indices left over)",
                           h->path, mesh, bad - first, n, what);
        else if (why == PRIM_SHORT_STRIP)
            st = pxi_error(err, PX_ERR_IO,
                           "mesh file '%s': glTF meshes[%u].primitives[%u] is a triangle %s of %llu %s, "
                           "fewer than 3 (Assimp 5.2 mishandles it)",
                           h->path, mesh, bad - first, mode == 5 ? "strip" : "fan", n, what);
        else if (why == PRIM_SHORT_LINE)
            st = pxi_error(err, PX_ERR_IO,
                           "mesh file '%s': glTF meshes[%u].primitives[%u] is a line %s of %llu %s, fewer "
                           "than 2 (Assimp 5.2 reads an index that is not there)",
                           h->path, mesh, bad - first, mode == 2 ? "loop" : "strip", n, what);
        else if (mode == PRIM_MODE_UNREAD)
            st = pxi_error(err, PX_ERR_IO,
                           "mesh file '%s': glTF meshes[%u].primitives[%u] has a \"mode\" that is not an "
                           "integer from 0 to 6",
                           h->path, mesh, bad - first);
        else
            st = pxi_error(err, PX_ERR_IO,
                           "mesh file '%s': glTF meshes[%u].primitives[%u] has mode %u, not a glTF primitive "
                           "mode (0 to 6)",
                           h->path, mesh, bad - first, mode);
        goto done;
    }
    if (h->gltf_triangles) *h->gltf_triangles = tri;
done:
    if (count) pxi_free(h->alloc, count, (size_t)(j.nodes ? j.nodes : 1) * sizeof(u64));
    if (j.acc_count) pxi_free(h->alloc, j.acc_count, (size_t)j.acc_cap * sizeof(u32));
    if (j.acc_info) pxi_free(h->alloc, j.acc_info, (size_t)j.acc_info_cap * sizeof(u32));
    if (j.views) pxi_free(h->alloc, j.views, (size_t)j.views_cap * sizeof(u32));
    if (j.bufs) pxi_free(h->alloc, j.bufs, (size_t)j.bufs_cap * sizeof(u32));
    if (j.attrs) pxi_free(h->alloc, j.attrs, (size_t)j.attrs_cap * sizeof(u32));
    if (j.prim) pxi_free(h->alloc, j.prim, (size_t)j.prim_cap * sizeof(u32));
    if (j.mesh_end) pxi_free(h->alloc, j.mesh_end, (size_t)j.mesh_cap * sizeof(u32));
    if (j.node_mesh) pxi_free(h->alloc, j.node_mesh, (size_t)j.nm_cap * sizeof(u32));
    if (j.roots) pxi_free(h->alloc, j.roots, (size_t)j.rcap * sizeof(u32));
    if (j.scene_end) pxi_free(h->alloc, j.scene_end, (size_t)j.scap * sizeof(u32));
    g_free(&j.g);
    pxi_free(h->alloc, doc, len + 1);
    return st;
}
