/* Full-precision positions for plain OFF and ASCII STL (issue 9: "where a
 * format can be read without Assimp at full precision, consider doing so").
 *
 * Assimp 5.2 parses numbers into 32-bit floats (and not quite correctly
 * rounded: up to 1.43 half-ulps measured, docs/io.md). For two text formats
 * the order in which Assimp stores the vertices is simple, so the loader
 * keeps Assimp's scene (faces, triangulation, names, tree) and only reads
 * the coordinates again with strtod (correctly rounded to double):
 * - OFF: the file's vertex list, in file order, as the one mesh;
 * - ASCII STL: three vertices per facet, every "vertex x y z" line in file
 *   order, the solids' meshes one after the other.
 * The reading is strict and gives up (the floats stay) on anything outside
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

#define EXACT_LINE 4096

typedef enum { FORMAT_NONE, FORMAT_OFF, FORMAT_STL } exact_format;

static exact_format scene_format(const struct aiScene *scene) {
    const struct aiMetadata *md = scene->mMetaData;
    for (unsigned i = 0; md && md->mKeys && md->mValues && i < md->mNumProperties; ++i) {
        if (strcmp(md->mKeys[i].data, "SourceAsset_Format") != 0 || md->mValues[i].mType != AI_AISTRING ||
            !md->mValues[i].mData)
            continue;
        const char *f = ((const struct aiString *)md->mValues[i].mData)->data;
        if (strcmp(f, "OFF Importer") == 0) return FORMAT_OFF;
        if (strcmp(f, "Stereolithography (STL) Importer") == 0) return FORMAT_STL;
    }
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
    if (total == 0 || (format == FORMAT_OFF && scene->mNumMeshes != 1)) return PX_OK;

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
        ok = format == FORMAT_OFF ? read_off(f, line, out, total) : read_stl(f, line, out, total);
        uselocale(caller);
        freelocale(c_locale);
    } else {
        ok = 0;
    }
    fclose(f);
    pxi_free(alloc, line, EXACT_LINE);
    for (unsigned i = 0, at = 0; ok && i < scene->mNumMeshes; ++i) {
        const struct aiMesh *m = scene->mMeshes[i];
        for (unsigned v = 0; ok && v < m->mNumVertices; ++v, ++at) {
            const double *x = out + 3 * (size_t)at;
            ok = near_float(x[0], m->mVertices[v].x) && near_float(x[1], m->mVertices[v].y) &&
                 near_float(x[2], m->mVertices[v].z);
        }
    }
    if (!ok) {
        pxi_free(alloc, out, total * 3 * sizeof(double));
        return PX_OK;
    }
    *xyz = out;
    *count = total;
    return PX_OK;
}
