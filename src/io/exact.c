/* Full-precision positions for plain OFF, ASCII STL, OBJ and PLY (issue 9:
 * "where a format can be read without Assimp at full precision, consider
 * doing so").
 *
 * Assimp 5.2 parses numbers into 32-bit floats (and not quite correctly
 * rounded: up to 1.43 half-ulps measured, docs/io.md). The loader keeps
 * Assimp's scene (faces, triangulation, names, tree) and only reads the
 * coordinates again with strtod (correctly rounded to double). For three
 * formats the order in which Assimp stores the vertices is simple (PLY: see
 * read_ply):
 * - OFF: the file's vertex list, in file order, as the one mesh;
 * - ASCII STL: three vertices per facet, every "vertex x y z" line in file
 *   order, the solids' meshes one after the other.
 * OBJ's is not (face corners, split by object and material), and its
 * positions are paired with the file's vertices by their floats: see
 * read_obj. The OFF and STL reading is strict and gives up (the floats stay) on anything outside
 * that: a header other than a line "OFF" (the NOFF/COFF/... variants,
 * headerless files, a dimension), a blank or comment line inside the
 * vertex list, a vertex line of more or fewer than three numbers, a number
 * strtod does not read whole or that is not finite, a line of 4096 bytes
 * or more, a byte-order mark, vertex counts that differ from the scene's.
 * Last, every double must round to within 2 float ulps of Assimp's float
 * for the same vertex, so a reading that paired the wrong numbers with the
 * wrong vertices cannot pass. The file is opened again without blocking and
 * must still be the file the precheck identified. The numbers are read in
 * the C locale whatever the caller's (strtod in a de_DE locale stops at
 * the '.', and every file fell back to the floats).
 */
#define _POSIX_C_SOURCE 200809L

#include "io/exact.h"

#include <errno.h>
#include <fcntl.h>
#include <locale.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/core.h"
#include "io/import.h"

#define EXACT_LINE 4096

/* read_obj pairs Assimp's positions with the file's by their float bits. */
_Static_assert(sizeof(ai_real) == sizeof(float), "Assimp built with double precision");

typedef enum { FORMAT_NONE, FORMAT_OFF, FORMAT_STL, FORMAT_OBJ, FORMAT_PLY } exact_format;

static exact_format scene_format(const struct aiScene *scene) {
    const char *f = pxi_io_scene_format(scene);
    if (!f) return FORMAT_NONE;
    if (strcmp(f, "OFF Importer") == 0) return FORMAT_OFF;
    if (strcmp(f, "Stereolithography (STL) Importer") == 0) return FORMAT_STL;
    if (strcmp(f, "Wavefront Object Importer") == 0) return FORMAT_OBJ;
    if (strcmp(f, "Stanford Polygon Library (PLY) Importer") == 0) return FORMAT_PLY;
    return FORMAT_NONE;
}

/* Reads one line into buf (NUL-terminated, line break removed). Returns 1,
 * 0 at the end of the file, -1 for a line too long or with a NUL byte. */
static int next_line(FILE *f, char *buf) {
    if (!fgets(buf, EXACT_LINE, f)) return 0;
    size_t n = strlen(buf);
    if (n == EXACT_LINE - 1 && buf[n - 1] != '\n') return -1;
    if (n && buf[n - 1] == '\n') buf[--n] = '\0';
    if (n && buf[n - 1] == '\r') buf[--n] = '\0';
    if (memchr(buf, '\0', n)) return -1;
    return 1;
}

static char *skip_blank(char *p) {
    while (*p == ' ' || *p == '\t') ++p;
    return p;
}

/* Reads exactly `n` finite numbers from p and nothing else. */
static int read_numbers(char *p, double *out, int n) {
    for (int k = 0; k < n; ++k) {
        p = skip_blank(p);
        if (!*p) return 0;
        char *end;
        errno = 0;
        out[k] = strtod(p, &end);
        if (end == p || (*end && *end != ' ' && *end != '\t') || !isfinite(out[k])) return 0;
        p = end;
    }
    return *skip_blank(p) == '\0';
}

static int is_blank_or_comment(char *line) {
    char *p = skip_blank(line);
    return *p == '\0' || *p == '#';
}

/* OFF: header line "OFF", counts line "V F [E]", then V vertex lines. */
static int read_off(FILE *f, char *line, double *xyz, size_t total) {
    int r;
    while ((r = next_line(f, line)) == 1 && is_blank_or_comment(line)) {
    }
    /* "OFF" alone on its line */
    if (r != 1 || strncmp(skip_blank(line), "OFF", 3) != 0 || *skip_blank(skip_blank(line) + 3) != '\0')
        return 0;
    while ((r = next_line(f, line)) == 1 && is_blank_or_comment(line)) {
    }
    if (r != 1) return 0;
    char *p = skip_blank(line), *end;
    unsigned long long counts[3] = {0, 0, 0};
    int nc = 0;
    while (*p && nc < 3) {
        if (*p < '0' || *p > '9') return 0;
        errno = 0;
        counts[nc++] = strtoull(p, &end, 10);
        if (errno || (*end && *end != ' ' && *end != '\t')) return 0;
        p = skip_blank(end);
    }
    if (*p || nc < 2 || counts[0] != total) return 0;
    for (size_t i = 0; i < total; ++i)
        if (next_line(f, line) != 1 || !read_numbers(line, xyz + 3 * i, 3)) return 0;
    return 1;
}

/* ASCII STL: every "vertex x y z" line, in order; the rest is Assimp's. */
static int read_stl(FILE *f, char *line, double *xyz, size_t total) {
    size_t n = 0;
    int r;
    while ((r = next_line(f, line)) == 1) {
        char *p = skip_blank(line);
        if (strncmp(p, "vertex", 6) != 0 || (p[6] != ' ' && p[6] != '\t')) continue;
        if (n == total || !read_numbers(p + 6, xyz + 3 * n, 3)) return 0;
        ++n;
    }
    return r == 0 && n == total;
}

/* PLY: Assimp 5.2 keeps the vertex element's instances in file order as
 * the one mesh. Read when the header is plain ("ply", a format line,
 * comments, elements and properties, "end_header") and the first element
 * is `vertex`, of the scene's vertex count, with scalar properties only,
 * one each named x, y and z, at least one of them double (Assimp turns
 * doubles into floats; float and integer properties are what the file
 * holds already, and such files keep float_coordinates 1, like binary
 * STL). ASCII: one instance a line, as many numbers as properties, read
 * with strtod (strtof for a float property). Binary (either byte order): fixed-size records. */
/* PLY's scalar types: char, uchar, short, ushort, int, uint, float,
 * double (and their sized names), by index. */
static const int ply_size[8] = {1, 1, 2, 2, 4, 4, 4, 8};

static int ply_type(const char *t) {
    static const char *const names[8][2] = {{"char", "int8"},     {"uchar", "uint8"},   {"short", "int16"},
                                            {"ushort", "uint16"}, {"int", "int32"},     {"uint", "uint32"},
                                            {"float", "float32"}, {"double", "float64"}};
    for (int i = 0; i < 8; ++i)
        if (strcmp(t, names[i][0]) == 0 || strcmp(t, names[i][1]) == 0) return i;
    return -1;
}

/* A binary scalar of type index `t`, as a double (on a little-endian
 * machine, which the caller checks). */
static double ply_binary_value(const unsigned char *p, int t, int big) {
    const int size = ply_size[t];
    unsigned char b[8];
    for (int i = 0; i < size; ++i) b[i] = big ? p[size - 1 - i] : p[i];
    if (t == 7) {
        double d;
        memcpy(&d, b, 8);
        return d;
    }
    if (t == 6) {
        float f;
        memcpy(&f, b, 4);
        return f;
    }
    uint32_t u = 0;
    for (int i = size - 1; i >= 0; --i) u = u << 8 | b[i];
    if (t % 2 == 1) return u; /* unsigned */
    const uint32_t sign = 1u << (8 * size - 1);
    return (double)(int64_t)(u ^ sign) - (double)sign;
}

static int read_ply(FILE *f, char *line, double *xyz, size_t total) {
    enum { MAX_PROPS = 64 };
    int type[MAX_PROPS];
    int at[3] = {-1, -1, -1}, np = 0, format = -1, element = 0, doubles = 0;
    if (next_line(f, line) != 1 || strcmp(line, "ply") != 0) return 0;
    for (;;) {
        if (next_line(f, line) != 1) return 0;
        char word[3][64];
        unsigned long long count = 0;
        char more;
        if (strcmp(line, "end_header") == 0) break;
        if (strncmp(line, "comment", 7) == 0 || strncmp(line, "obj_info", 8) == 0) continue;
        if (sscanf(line, "format %63s 1.0 %c", word[0], &more) == 1) {
            format = strcmp(word[0], "ascii") == 0                  ? 0
                     : strcmp(word[0], "binary_little_endian") == 0 ? 1
                     : strcmp(word[0], "binary_big_endian") == 0    ? 2
                                                                    : -1;
            if (format < 0) return 0;
        } else if (sscanf(line, "element %63s %llu %c", word[0], &count, &more) == 2) {
            if (++element == 1 && (strcmp(word[0], "vertex") != 0 || count != total)) return 0;
        } else if (element == 1 && sscanf(line, "property %63s %63s %c", word[0], word[1], &more) == 2) {
            const int t = ply_type(word[0]);
            if (t < 0 || np == MAX_PROPS) return 0;
            for (int k = 0; k < 3; ++k)
                if (strcmp(word[1], (const char *[]){"x", "y", "z"}[k]) == 0) {
                    if (at[k] >= 0) return 0;
                    at[k] = np;
                    doubles += t == 7;
                }
            type[np++] = t;
        } else if (element != 1 && strncmp(line, "property ", 9) == 0) {
            continue;
        } else {
            return 0; /* a list property in the vertex element, or anything else */
        }
    }
    if (format < 0 || element == 0 || at[0] < 0 || at[1] < 0 || at[2] < 0 || !doubles) return 0;
    if (format == 0) {
        for (size_t i = 0; i < total; ++i) {
            if (next_line(f, line) != 1) return 0;
            char *p = line;
            for (int k = 0; k < np; ++k) {
                p = skip_blank(p);
                char *end;
                /* a float property is the float nearest the text */
                const double v = type[k] == 6 ? (double)strtof(p, &end) : strtod(p, &end);
                if (end == p || (*end && *end != ' ' && *end != '\t') || !isfinite(v)) return 0;
                for (int c = 0; c < 3; ++c)
                    if (at[c] == k) xyz[3 * i + c] = v;
                p = end;
            }
            if (*skip_blank(p)) return 0;
        }
        return 1;
    }
    const uint16_t one = 1;
    unsigned char little;
    memcpy(&little, &one, 1);
    if (!little) return 0;
    int offset[MAX_PROPS], record = 0;
    for (int k = 0; k < np; ++k) {
        offset[k] = record;
        record += ply_size[type[k]];
    }
    unsigned char rec[MAX_PROPS * 8];
    for (size_t i = 0; i < total; ++i) {
        if (fread(rec, 1, (size_t)record, f) != (size_t)record) return 0;
        for (int c = 0; c < 3; ++c) {
            const double v = ply_binary_value(rec + offset[at[c]], type[at[c]], format == 2);
            if (!isfinite(v)) return 0;
            xyz[3 * i + c] = v;
        }
    }
    return 1;
}

/* ---- OBJ ------------------------------------------------------------------ */

/* Assimp 5.2's fast_atoreal_move<float> (assimp/fast_atof.h, with
 * AI_FAST_ATOF_RELAVANT_DECIMALS 15), step for step, on a word of the form
 * [+-] (digits [. [digits]] | . digits) [(e|E) [+-] digits]: the integer
 * part converted to float, the first 15 decimals as an integer times a
 * power of ten in double, added in float, then times powf(10, exponent).
 * 0 for any other word, and for forms it reads with an overflow or that
 * this does not follow (an integer part of more than 19 digits, an
 * exponent of more than 4). */
static int assimp_atof(const char *w, size_t n, float *out) {
    static const double tenth[16] = {0.0,  0.1,  0.01,  1e-3,  1e-4,  1e-5,  1e-6,  1e-7,
                                     1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13, 1e-14, 1e-15};
    size_t i = 0;
    const int minus = n > 0 && w[0] == '-';
    if (n > 0 && (w[0] == '-' || w[0] == '+')) ++i;
#define DIGIT(k) ((k) < n && w[k] >= '0' && w[k] <= '9')
    if (!DIGIT(i) && !(i < n && w[i] == '.' && DIGIT(i + 1))) return 0;
    float f = 0.0f;
    if (w[i] != '.') {
        uint64_t v = 0;
        for (int d = 0; DIGIT(i); ++i)
            if (++d > 19)
                return 0;
            else
                v = 10 * v + (uint64_t)(w[i] - '0');
        f = (float)v;
    }
    if (i < n && w[i] == '.' && DIGIT(i + 1)) {
        ++i;
        uint64_t v = 0;
        unsigned used = 0;
        for (; DIGIT(i); ++i)
            if (used < 15) v = 10 * v + (uint64_t)(w[i] - '0'), ++used;
        f += (float)((double)v * tenth[used]);
    } else if (i < n && w[i] == '.') {
        ++i;
    }
    if (i < n && (w[i] == 'e' || w[i] == 'E')) {
        ++i;
        const int eminus = i < n && w[i] == '-';
        if (i < n && (w[i] == '-' || w[i] == '+')) ++i;
        if (!DIGIT(i)) return 0;
        unsigned e = 0;
        for (int d = 0; DIGIT(i); ++i)
            if (++d > 4)
                return 0;
            else
                e = 10 * e + (unsigned)(w[i] - '0');
        float x = (float)e;
        if (eminus) x = -x;
        f *= powf(10.0f, x);
    }
#undef DIGIT
    if (i != n) return 0;
    *out = minus ? -f : f;
    return 1;
}

/* Whether a number's integer part or exponent is a run of more than 19
 * digits: Assimp 5.2's strtoul10_64 overflows there and the number reads
 * as 0 (review s30: "v 18446744073709551617 0 0" loaded at x = 0). */
static int long_digit_run(const char *w, size_t n) {
    size_t run = 0;
    int frac = 0;
    for (size_t i = 0; i < n; ++i) {
        if (w[i] >= '0' && w[i] <= '9') {
            if (!frac && ++run > 19) return 1;
        } else {
            run = 0;
            if (w[i] == '.') frac = 1;
            if (w[i] == 'e' || w[i] == 'E') frac = 0;
        }
    }
    return 0;
}

/* One of the file's vertices: at full precision, and as Assimp's float. */
typedef struct obj_vertex {
    double x[3];
    float f[3];
    int twin; /* another vertex has the same floats and other doubles */
} obj_vertex;

/* Whether Assimp 5.2's getNumComponentsInDataDefinition counts the word
 * at w (n bytes) as a number: it starts with a digit, '-' or '+', or with
 * "nan" or "inf" in any case. */
static int assimp_counts(const char *w, size_t n) {
    if (*w == '-' || *w == '+' || (*w >= '0' && *w <= '9')) return 1;
    if (n < 3) return 0;
    const char a = (char)(w[0] | 0x20), b = (char)(w[1] | 0x20), c = (char)(w[2] | 0x20);
    return (a == 'n' && b == 'a' && c == 'n') || (a == 'i' && b == 'n' && c == 'f');
}

/* A vertex line's words after the keyword, [p, e): 3, 4 (homogeneous) or 6
 * (a colour after) numbers, then nothing or a comment. Assimp counts the
 * words that start like a number, comment included, and reads that many
 * words from the first: this takes only lines where those are the same
 * words (review s29: "v 16777216 0 0 .5" is three numbers to Assimp, and
 * was taken for a homogeneous vertex). */
static int obj_vertex_line(const char *p, const char *e, obj_vertex *v) {
    double d[6];
    float f[6];
    int n = 0, counted = 0, comment = 0;
    for (;;) {
        while (p < e && (*p == ' ' || *p == '\t')) ++p;
        if (p == e) break;
        const char *w = p;
        while (p < e && *p != ' ' && *p != '\t') ++p;
        const size_t len = (size_t)(p - w);
        const int number = assimp_counts(w, len);
        counted += number;
        if (comment || (*w == '#' && (comment = 1))) continue;
        if (number && long_digit_run(w, len)) return -2;
        if (!number || n == 6 || !assimp_atof(w, len, &f[n])) return 0;
        char buf[64], *end;
        if (len >= sizeof buf) return 0;
        memcpy(buf, w, len);
        buf[len] = '\0';
        d[n] = strtod(buf, &end);
        if (*end || !isfinite(d[n])) return 0;
        ++n;
    }
    if ((n != 3 && n != 4 && n != 6) || counted != n) return 0;
    for (int k = 0; k < 3; ++k) {
        /* getHomogeneousVector3 divides in float; w = 0 fails the import. */
        v->x[k] = n == 4 ? d[k] / d[3] : d[k];
        v->f[k] = n == 4 ? f[k] / f[3] : f[k];
        if (!isfinite(v->x[k])) return 0;
    }
    v->twin = 0;
    return 1;
}

static uint64_t obj_hash(const float f[3]) {
    uint32_t b[3];
    memcpy(b, f, sizeof b);
    uint64_t h = ((uint64_t)b[0] << 32 | b[1]) * 0x9E3779B97F4A7C15ull ^ b[2] * 0xC2B2AE3D27D4EB4Full;
    return h ^ h >> 29;
}

/* OBJ: Assimp 5.2 copies position m_Vertices[i] (the i-th `v` line) into
 * every face corner that names vertex i, mesh by mesh, split by object,
 * group and material: the order is not simple, but every position of the
 * scene is one of the file's vertices as Assimp's floats. The vertex
 * lines are read twice, with strtod and as Assimp's number reader reads
 * them (assimp_atof), and each position of the scene takes the doubles of
 * the vertex whose floats it has, bit for bit. Given up: a byte-order
 * mark (the first line is skipped), a backslash at a line's end (joined
 * lines), a vertex line of another form than obj_vertex_line's, a position
 * that no vertex has (a number read otherwise than assimp_atof reads it),
 * or two vertices with the same floats and different doubles that the
 * scene uses (which one a corner names is not known). Returns 1 with `xyz`
 * filled, 0 to keep the floats, -1 out of memory. */
static int read_obj(FILE *file, size_t size, const struct aiScene *scene, const px_allocator *alloc,
                    double *xyz) {
    char *t = size < SIZE_MAX ? pxi_alloc(alloc, size + 1) : NULL;
    if (!t) return -1;
    int ok = fread(t, 1, size, file) == size && fgetc(file) == EOF;
    t[size] = '\0';
    /* Pass 1 counts the vertex lines, pass 2 reads them. */
    size_t nv = 0;
    obj_vertex *v = NULL;
    int misread = 0;
    for (int pass = 0; ok && pass < 2; ++pass) {
        size_t k = 0;
        for (size_t b = 0; ok && b < size;) {
            size_t e = b;
            while (e < size && t[e] != '\n' && t[e] != '\r' && t[e] != '\f' && t[e] != '\0') ++e;
            if (e > b && t[e - 1] == '\\') ok = 0;
            if (ok && e - b >= 2 && t[b] == 'v' && (t[b + 1] == ' ' || t[b + 1] == '\t')) {
                if (pass == 1) ok = obj_vertex_line(t + b + 2, t + e, &v[k]);
                if (ok == -2) misread = 1, ok = 0;
                ++k;
            }
            b = e + 1;
        }
        if (pass == 0) {
            nv = k;
            v = ok && nv ? pxi_alloc_array(alloc, nv, sizeof *v) : NULL;
            if (ok && nv && !v) {
                pxi_free(alloc, t, size + 1);
                return -1;
            }
            ok = ok && nv;
        }
    }
    pxi_free(alloc, t, size + 1);
    if (misread) {
        pxi_free(alloc, v, nv * sizeof *v);
        return -2;
    }
    /* Vertex index + 1 by floats, open addressing. */
    size_t cap = 16;
    while (ok && cap < 2 * nv) cap *= 2;
    uint32_t *slot = ok ? pxi_alloc_array(alloc, cap, sizeof *slot) : NULL;
    if (ok && (!slot || nv >= UINT32_MAX)) {
        pxi_free(alloc, v, nv * sizeof *v);
        pxi_free(alloc, slot, cap * sizeof *slot);
        return nv >= UINT32_MAX ? 0 : -1;
    }
    for (size_t i = 0; ok && i < cap; ++i) slot[i] = 0;
    for (size_t i = 0; ok && i < nv; ++i) {
        size_t h = (size_t)obj_hash(v[i].f) & (cap - 1);
        for (;; h = (h + 1) & (cap - 1)) {
            if (!slot[h]) {
                slot[h] = (uint32_t)i + 1;
                break;
            }
            obj_vertex *o = &v[slot[h] - 1];
            if (memcmp(o->f, v[i].f, sizeof o->f) == 0) {
                if (memcmp(o->x, v[i].x, sizeof o->x) != 0) o->twin = 1;
                break;
            }
        }
    }
    for (unsigned m = 0, at = 0; ok && m < scene->mNumMeshes; ++m) {
        const struct aiMesh *mesh = scene->mMeshes[m];
        for (unsigned q = 0; ok && q < mesh->mNumVertices; ++q, ++at) {
            const float f[3] = {mesh->mVertices[q].x, mesh->mVertices[q].y, mesh->mVertices[q].z};
            size_t h = (size_t)obj_hash(f) & (cap - 1);
            while (slot[h] && memcmp(v[slot[h] - 1].f, f, sizeof f) != 0) h = (h + 1) & (cap - 1);
            ok = slot[h] && !v[slot[h] - 1].twin;
            if (ok) memcpy(xyz + 3 * (size_t)at, v[slot[h] - 1].x, sizeof v->x);
        }
    }
    pxi_free(alloc, v, nv * sizeof *v);
    pxi_free(alloc, slot, cap * sizeof *slot);
    return ok;
}

/* Within 2 float ulps of x (the float Assimp made of the same text). */
static int near_float(double x, double f) {
    if (x == f) return 1;
    int e;
    frexp(x, &e);
    double ulp = ldexp(1.0, e - 24);
    if (ulp < 0x1p-149) ulp = 0x1p-149;
    return fabs(x - f) <= 2 * ulp;
}

px_status pxi_io_exact_positions(const char *path, const pxi_file_id *id, const struct aiScene *scene,
                                 const px_allocator *alloc, double **xyz, size_t *count, px_error *err) {
    *xyz = NULL;
    *count = 0;
    exact_format format = scene_format(scene);
    if (format == FORMAT_NONE) return PX_OK;
    size_t total = 0;
    for (unsigned i = 0; i < scene->mNumMeshes; ++i) total += scene->mMeshes[i]->mNumVertices;
    if (total == 0 || ((format == FORMAT_OFF || format == FORMAT_PLY) && scene->mNumMeshes != 1))
        return PX_OK;

    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) return PX_OK;
    struct stat st;
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) || (unsigned long long)st.st_dev != id->dev ||
        (unsigned long long)st.st_ino != id->ino || (unsigned long long)st.st_size != id->size ||
        (long long)st.st_mtim.tv_sec != id->mtime_sec || (long long)st.st_mtim.tv_nsec != id->mtime_nsec) {
        close(fd);
        return PX_OK;
    }
    FILE *f = fdopen(fd, "rb");
    if (!f) {
        close(fd);
        return PX_OK;
    }
    char *line = pxi_alloc(alloc, EXACT_LINE);
    double *out = line ? pxi_alloc_array(alloc, total, 3 * sizeof(double)) : NULL;
    if (!out) {
        fclose(f);
        pxi_free(alloc, line, EXACT_LINE);
        return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "out of memory reading mesh file '%s' at full precision",
                         path);
    }
    /* a byte-order mark: give up (Assimp skips it; not worth a special case) */
    int c0 = fgetc(f);
    int ok = c0 != EOF && c0 != 0xEF && c0 != 0xFE && c0 != 0xFF && ungetc(c0, f) != EOF;
    /* This thread only, restored at once (without a C locale object: the
     * floats stay). */
    locale_t c_locale = ok ? newlocale(LC_NUMERIC_MASK, "C", (locale_t)0) : (locale_t)0;
    if (c_locale != (locale_t)0) {
        locale_t caller = uselocale(c_locale);
        ok = format == FORMAT_OFF   ? read_off(f, line, out, total)
             : format == FORMAT_STL ? read_stl(f, line, out, total)
             : format == FORMAT_PLY ? read_ply(f, line, out, total)
                                    : read_obj(f, (size_t)st.st_size, scene, alloc, out);
        uselocale(caller);
        freelocale(c_locale);
    } else {
        ok = 0;
    }
    fclose(f);
    pxi_free(alloc, line, EXACT_LINE);
    int misread = ok == -2;
    if (ok < 0 && !misread) {
        pxi_free(alloc, out, total * 3 * sizeof(double));
        return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "out of memory reading mesh file '%s' at full precision",
                         path);
    }
    for (unsigned i = 0, at = 0; ok > 0 && i < scene->mNumMeshes; ++i) {
        const struct aiMesh *m = scene->mMeshes[i];
        for (unsigned v = 0; ok && v < m->mNumVertices; ++v, ++at) {
            const double *x = out + 3 * (size_t)at;
            const float *g = &m->mVertices[v].x;
            for (int k = 0; ok && k < 3; ++k) {
                ok = near_float(x[k], g[k]);
                /* In file order (OFF, PLY), a number of 2^64 or more that
                 * Assimp did not read: a run of 20 digits (read as 0). */
                misread |= !ok && format != FORMAT_OBJ && fabs(x[k]) >= 0x1p64;
            }
        }
    }
    if (misread) {
        pxi_free(alloc, out, total * 3 * sizeof(double));
        return pxi_error(
            err, PX_ERR_IO,
            "mesh file '%s': a vertex coordinate with more than 19 digits before its point or in its "
            "exponent, which Assimp 5.2 reads as 0; write it with an exponent (1.2e22)",
            path);
    }
    if (!ok) {
        pxi_free(alloc, out, total * 3 * sizeof(double));
        return PX_OK;
    }
    *xyz = out;
    *count = total;
    return PX_OK;
}
