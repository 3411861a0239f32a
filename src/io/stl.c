/* The walk of an ASCII STL file, as Assimp 5.2's STL importer reads it
 * (STLImporter::LoadASCIIFile and fast_atoreal_move, Debian bookworm's
 * 5.2.5), before it does.
 *
 * Assimp keeps the meshes and nodes of the solids it has read in local
 * vectors of raw pointers until the whole file is read: when a later
 * number does not parse, or a solid's vertex or normal count comes out
 * wrong, it throws and leaks them (LeakSanitizer: about 2.4 KB for a
 * vertex line with two numbers). Other slips it only logs and reads on:
 * a vertex before any `facet` or a fourth one in a facet is dropped, a
 * facet of two vertices throws or, with another short one, shifts the
 * triangles between them by a corner, a run of digits above 2^64 (before
 * the point or in the exponent) reads as 0 and is read again as the next
 * coordinate, and a NUL byte ends the file there (checked with Assimp
 * 5.2.5). Each of these is refused here with the line it is on (runs of
 * more than 19 digits, to stay clear of 2^64); a file that passes reads in
 * Assimp as it reads here, every facet one triangle.
 *
 * The walk follows the importer's tokenizer step by step: spaces are ' '
 * and '\t', line ends '\r', '\n', '\f' and NUL; `facet` must be followed by
 * blank space and `normal` (matched on its first six letters, the seventh
 * byte skipped); the three numbers of a normal or vertex each follow blank
 * space on the same line; `endsolid` ends a solid (on its first eight
 * letters) and the rest of its line; any other word is skipped. A new
 * solid starts where the text left after `endsolid` starts with `solid`.
 * Numbers read as fast_atoreal_move reads them: a sign, then `nan`, `inf`
 * or `infinity` (any case), or digits with an optional '.' or ',' and
 * fraction, then an optional exponent with at least one digit. */
#include "core/core.h"
#include "io/scan.h"

/* Longest solid name Assimp 5.2 takes (AI_MAXLEN - 1). */
#define STL_MAX_NAME 1023
/* Longest digit run strtoul10_64 reads without overflowing (2^64 has 20). */
#define STL_MAX_DIGITS 19

static int is_space(unsigned char c) { return c == ' ' || c == '\t'; }
static int is_line_end(unsigned char c) { return c == '\r' || c == '\n' || c == '\f' || c == '\0'; }
static int is_blank(unsigned char c) { return is_space(c) || is_line_end(c); }
static int is_digit(unsigned char c) { return c >= '0' && c <= '9'; }

static const unsigned char *skip_spaces(const unsigned char *p) {
    while (is_space(*p)) ++p;
    return p;
}

static const unsigned char *skip_blank(const unsigned char *p) {
    while (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n') ++p;
    return p;
}

/* 1 if p starts with s (strncmp: stops at the text's terminating NUL). */
static int starts(const unsigned char *p, const char *s) {
    for (; *s; ++p, ++s)
        if (*p != (unsigned char)*s) return 0;
    return 1;
}

/* 1 if only blanks precede p on its line (t: the text's start). */
static int first_on_line(const unsigned char *t, const unsigned char *p) {
    while (p > t && is_space(p[-1])) --p;
    return p == t || is_line_end(p[-1]);
}

/* ASCII case-insensitive: 1 if p starts with lowercase s. */
static int starts_ci(const unsigned char *p, const char *s) {
    for (; *s; ++p, ++s)
        if (pxi_lower(*p) != *s) return 0;
    return 1;
}

/* A run of digits; NULL when it has more than STL_MAX_DIGITS. */
static const unsigned char *digits(const unsigned char *p) {
    const unsigned char *q = p;
    while (is_digit(*q)) ++q;
    return q - p > STL_MAX_DIGITS ? NULL : q;
}

enum { NUM_OK, NUM_NONE, NUM_LONG };

/* One number at *pp, as fast_atoreal_move reads it; moves *pp past it. */
static int number(const unsigned char **pp) {
    const unsigned char *p = *pp;
    if (*p == '-' || *p == '+') ++p;
    if (starts_ci(p, "nan")) {
        *pp = p + 3;
        return NUM_OK;
    }
    if (starts_ci(p, "inf")) {
        p += 3;
        if (starts_ci(p, "inity")) p += 5;
        *pp = p;
        return NUM_OK;
    }
    int point = *p == '.' || *p == ',';
    if (!is_digit(*p) && !(point && is_digit(p[1]))) return NUM_NONE;
    if (!point && !(p = digits(p))) return NUM_LONG;
    if ((*p == '.' || *p == ',') && is_digit(p[1])) {
        ++p;
        while (is_digit(*p)) ++p; /* only the first 15 count: no overflow */
    } else if (*p == '.') {
        ++p;
    }
    if (*p == 'e' || *p == 'E') {
        ++p;
        if (*p == '-' || *p == '+') ++p;
        if (!is_digit(*p)) return NUM_NONE;
        if (!(p = digits(p))) return NUM_LONG;
    }
    *pp = p;
    return NUM_OK;
}

/* 1-based line of position p of the text t. */
static u64 line_of(const unsigned char *t, const unsigned char *p) {
    u64 n = 1;
    for (; t < p; ++t) n += *t == '\n';
    return n;
}

/* Assimp's IsAsciiSTL on the text left at p (`left` bytes by its count,
 * which includes a dropped byte-order mark): not of binary STL size, and
 * `solid` after spaces. */
static int solid_follows(const unsigned char *p, const unsigned char *end, u64 left) {
    if (left >= 84) {
        unsigned char c[4] = {0, 0, 0, 0}; /* past the text: the terminating NUL, then nothing read */
        for (int i = 0; i < 4; ++i)
            if (p + 80 + i < end) c[i] = p[80 + i];
        uint32_t n = (uint32_t)c[0] | (uint32_t)c[1] << 8 | (uint32_t)c[2] << 16 | (uint32_t)c[3] << 24;
        if ((uint32_t)(n * 50u + 84u) == (uint32_t)left) return 0;
    }
    const unsigned char *q = skip_spaces(p);
    if (is_line_end(*q) || (u64)(q - p) + 5 >= left) return 0;
    return starts(q, "solid");
}

static px_status refuse(const io_head *h, const unsigned char *t, const unsigned char *at, const char *what,
                        px_error *err) {
    return pxi_error(err, PX_ERR_IO, "mesh file '%s', line %llu: %s", h->path, line_of(t, at), what);
}

/* The three numbers of a normal or a vertex, each after spaces. */
static const char *three_numbers(const unsigned char **pp) {
    for (int i = 0; i < 3; ++i) {
        *pp = skip_spaces(*pp);
        int r = number(pp);
        if (r == NUM_LONG)
            return "a number with more than 19 digits before its point or in its exponent (Assimp 5.2 "
                   "reads it as 0)";
        if (r != NUM_OK) return NULL;
    }
    return "";
}

/* The three numbers after the keyword of `word` bytes at *pp (the byte
 * after it skipped, as Assimp does): NULL when read, else why not
 * (`missing` when a number is not there). */
static const char *numbers_after(const unsigned char **pp, size_t word, const char *missing) {
    if ((*pp)[word] == '\0') return "the file ends inside a facet";
    *pp += word + 1;
    const char *e = three_numbers(pp);
    return !e ? missing : *e ? e : NULL;
}

px_status pxi_check_stl_ascii(const io_head *h, px_error *err) {
    unsigned char *buf;
    px_status st = pxi_read_all(h, &buf, err);
    if (st != PX_OK) return st;
    const size_t bom = h->size >= 3 && buf[0] == 0xEF && buf[1] == 0xBB && buf[2] == 0xBF ? 3 : 0;
    const unsigned char *t = buf + bom, *end = buf + h->size, *p = t;
    const char *why = NULL;
    const unsigned char *at = p;
    u64 vertices = 0;
    while (!why && solid_follows(p, end, h->size - (u64)(p - t))) {
        p = skip_spaces(p) + 5;
        p = skip_spaces(p);
        const unsigned char *name = p;
        while (!is_blank(*p)) ++p;
        at = name;
        if (p - name > STL_MAX_NAME) {
            why = "a solid name longer than 1023 bytes (Assimp 5.2 refuses it)";
            break;
        }
        unsigned corners = 3; /* of the facet being read: none before the first */
        u64 positions = 0, normals = 0;
        for (;;) {
            p = skip_blank(p);
            at = p;
            if (*p == '\0') {
                if (p < end) why = "a NUL byte (Assimp 5.2 would stop reading the file there)";
                break;
            }
            if (starts(p, "facet") && is_blank(p[5]) && p[5] != '\0') {
                if (corners != 3) {
                    why = "a facet begins before the last one had three vertices (Assimp 5.2 would shift "
                          "every later triangle)";
                    break;
                }
                corners = 0;
                p = skip_spaces(p + 6);
                if (!starts(p, "normal")) {
                    why = "a facet without 'normal' (Assimp 5.2 needs one per facet)";
                    break;
                }
                if ((why = numbers_after(&p, 6, "a facet normal needs three numbers on its line"))) break;
                normals += 3;
            } else if (starts(p, "vertex") && is_blank(p[6])) {
                if (corners >= 3) {
                    why = corners == 3 && positions == 0 && normals == 0
                              ? "a vertex before any facet (Assimp 5.2 drops it)"
                              : "a vertex outside a facet, or a facet with more than three (Assimp 5.2 "
                                "drops it)";
                    break;
                }
                if ((why = numbers_after(&p, 6, "a vertex needs three numbers on its line"))) break;
                ++positions;
                ++corners;
                if (++vertices > PX_IO_MAX_ELEMENTS / 4 * 3) {
                    why = "more vertices than the limit PX_IO_MAX_ELEMENTS allows (3 per triangle)";
                    break;
                }
            } else if (starts(p, "endsolid")) {
                do ++p;
                while (!is_line_end(*p));
                p = skip_blank(p);
                break;
            } else if (first_on_line(t, p) && ((starts_ci(p, "facet") && is_blank(p[5])) ||
                                               (starts_ci(p, "vertex") && is_blank(p[6])))) {
                why = "a keyword in capitals (Assimp 5.2 reads 'facet' and 'vertex' in lower case only, and "
                      "would skip this one)";
                break;
            } else {
                do ++p;
                while (!is_blank(*p));
            }
        }
        if (why) break;
        if (corners != 3) {
            why = "the solid ends inside a facet of fewer than three vertices";
            break;
        }
        if (normals != positions) { /* not reached: every facet read has a normal and three vertices */
            why = "facet normals and vertices do not match";
            break;
        }
    }
    if (!why && p < end && *p) {
        /* Assimp 5.2 stops at text after a solid that does not open
         * another: the facets after it were lost without a word (review
         * s32: a stray line between two solids dropped the second). A line
         * that starts with "solid" or "facet" after it says there was more;
         * words elsewhere ("4 facet triangles") are a trailer. */
        for (const unsigned char *r = p; r < end && *r;) {
            const unsigned char *w = skip_spaces(r); /* a line's first word */
            if ((starts(w, "facet") || starts(w, "solid")) && is_blank(w[5])) {
                at = p;
                why = "text after a solid that does not start another, with a solid or facet after it "
                      "(Assimp 5.2 would stop reading there, losing them)";
                break;
            }
            while (r < end && *r && !is_line_end(*r)) ++r; /* the walk's line ends: \r, \n, \f */
            while (r < end && *r && is_line_end(*r)) ++r;
        }
    }
    st = why ? refuse(h, t, at, why, err) : PX_OK;
    pxi_free(h->alloc, buf, (size_t)h->size + 1);
    return st;
}
