/* The file system Assimp reads through during one import (fs.h).
 *
 * Assimp opens files itself: the mesh file (several times: Exists(), each
 * importer's signature test, the import) and whatever the mesh references,
 * relative to it: glTF buffers, an OBJ material library, the archive of a
 * ZAE file. Through its default file system (fopen), a reference naming a
 * FIFO blocked the import forever while it held the import lock, and one
 * naming a 3 GB file was read whole, past PX_IO_MAX_FILE_BYTES. Given this
 * aiFileIO (aiImportFileEx), every open is checked here first:
 * - stat() before open(): only regular files are opened, and with
 *   O_NONBLOCK, so that a FIFO swapped in between cannot block (fstat then
 *   checks the opened file is the one stat() saw);
 * - a file opened under the mesh file's name, or any name for it, must be
 *   the file the precheck read (same device, inode, size and modification
 *   time): what was checked is what Assimp reads;
 * - any other file may hold at most PX_IO_MAX_FILE_BYTES, and the files one
 *   import reads may hold PX_IO_MAX_IMPORT_BYTES together: each opening of a
 *   file counts its whole size when Assimp first reads it or asks its size
 *   (the mesh file once); an opening Assimp only tests (Exists) is free, and
 *   a file too large for what is left is refused when opened;
 * - reads stop at the size the file had when it was opened (a file growing
 *   meanwhile is read as it was, and a regular file that reports size 0,
 *   such as those under /proc, reads as empty, never blocking);
 * - nothing is opened for writing.
 * A refused open returns NULL to Assimp and is recorded: the import then
 * fails with PX_ERR_IO naming the refused file and why, even where Assimp
 * would go on without the file (an OBJ material library). A missing file is
 * not a refusal: Assimp reports it or does without it. */
#define _POSIX_C_SOURCE 200809L /* stat, open flags, pread */

#include "io/fs.h"

#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/core.h"

#ifndef O_CLOEXEC
#define O_CLOEXEC 0
#endif

typedef unsigned long long u64;

/* One opening of a file. */
typedef struct fs_file {
    struct aiFile ai;
    pxi_io_fs *fs;
    struct fs_file *prev, *next; /* fs->open_files */
    int fd;
    int is_main;
    int charged; /* its size was counted */
    int dead;    /* refused on first use: reads nothing */
    u64 size;    /* when opened */
    u64 pos;
    char name[200];
} fs_file;

/* Records the first refusal. */
static void refuse(pxi_io_fs *fs, const char *name, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
static void refuse(pxi_io_fs *fs, const char *name, const char *fmt, ...) {
    if (fs->refused) return;
    fs->refused = 1;
    char why[200];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(why, sizeof why, fmt, ap);
    va_end(ap);
    snprintf(fs->message, sizeof fs->message, "'%.200s' was refused: %s", name, why);
}

static const char *file_kind(mode_t m) {
    if (S_ISDIR(m)) return "it is a directory";
    if (S_ISFIFO(m)) return "it is a FIFO (named pipe), whose reads can block forever";
    if (S_ISCHR(m)) return "it is a character device";
    if (S_ISBLK(m)) return "it is a block device";
#ifdef S_ISSOCK
    if (S_ISSOCK(m)) return "it is a socket";
#endif
    return "it is not a regular file";
}

static int same_file(const struct stat *a, const pxi_file_id *b) {
    return (u64)a->st_dev == b->dev && (u64)a->st_ino == b->ino;
}

static fs_file *handle(struct aiFile *f) { return (fs_file *)(void *)f->UserData; }

/* Counts the file's size against the import's limit, once per opening (the
 * mesh file once per import). Returns 0 when the file is refused. */
static int charge(fs_file *h) {
    if (h->dead) return 0;
    if (h->charged) return 1;
    h->charged = 1;
    pxi_io_fs *fs = h->fs;
    if (h->is_main) {
        if (!fs->main_charged) {
            fs->main_charged = 1;
            fs->charged += h->size;
        }
        return 1;
    }
    if (h->size > PX_IO_MAX_IMPORT_BYTES - fs->charged) {
        refuse(fs, h->name,
               "its %llu bytes and the %llu the import read before exceed the limit of %llu bytes for one "
               "import (PX_IO_MAX_IMPORT_BYTES)",
               h->size, fs->charged, (u64)PX_IO_MAX_IMPORT_BYTES);
        h->dead = 1;
        return 0;
    }
    fs->charged += h->size;
    return 1;
}

static size_t fs_read(struct aiFile *f, char *buf, size_t size, size_t count) {
    fs_file *h = handle(f);
    if (!size || !count || !charge(h)) return 0;
    u64 want = count > (size_t)-1 / size ? (u64)((size_t)-1 / size) * size : (u64)size * count;
    u64 left = h->size > h->pos ? h->size - h->pos : 0;
    size_t n = (size_t)(want < left ? want : left), got = 0;
    while (got < n) {
        ssize_t r = pread(h->fd, buf + got, n - got, (off_t)(h->pos + got));
        if (r < 0 && errno == EINTR) continue;
        if (r <= 0) break;
        got += (size_t)r;
    }
    h->pos += got;
    return got / size; /* fread's count of whole items */
}

static size_t fs_write(struct aiFile *f, const char *buf, size_t size, size_t count) {
    (void)f, (void)buf, (void)size, (void)count;
    return 0;
}

static size_t fs_tell(struct aiFile *f) { return (size_t)handle(f)->pos; }

static size_t fs_size(struct aiFile *f) {
    fs_file *h = handle(f);
    return charge(h) ? (size_t)h->size : 0;
}

/* Assimp passes a negative offset as a wrapped size_t (DefaultIOStream casts
 * it back to long for fseek). Positions outside [0, size] fail. */
static enum aiReturn fs_seek(struct aiFile *f, size_t offset, enum aiOrigin origin) {
    fs_file *h = handle(f);
    long long base = origin == aiOrigin_SET   ? 0
                     : origin == aiOrigin_CUR ? (long long)h->pos
                                              : (long long)h->size;
    long long off = (long long)offset; /* two's complement: the wrapped negative offset */
    if (origin == aiOrigin_SET && offset > h->size) return aiReturn_FAILURE;
    long long to = base + off;
    if (to < 0 || (u64)to > h->size) return aiReturn_FAILURE;
    h->pos = (u64)to;
    return aiReturn_SUCCESS;
}

static void fs_flush(struct aiFile *f) { (void)f; }

static struct aiFile *fs_open(struct aiFileIO *io, const char *name, const char *mode) {
    pxi_io_fs *fs = (pxi_io_fs *)(void *)io->UserData;
    if (!name || !name[0]) return NULL;
    if (!mode || strpbrk(mode, "wa+")) {
        refuse(fs, name, "Assimp asked to open it for writing");
        return NULL;
    }
    struct stat st, st2;
    if (stat(name, &st) != 0) return NULL; /* missing: Assimp says so, or does without it */
    if (!S_ISREG(st.st_mode)) {
        refuse(fs, name, "%s", file_kind(st.st_mode));
        return NULL;
    }
    int fd = open(name, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) return NULL;
    if (fstat(fd, &st2) != 0 || !S_ISREG(st2.st_mode) || st2.st_dev != st.st_dev || st2.st_ino != st.st_ino) {
        close(fd);
        refuse(fs, name, "it was replaced while being opened");
        return NULL;
    }
    const int is_main = same_file(&st2, &fs->main);
    const u64 size = (u64)st2.st_size;
    if (is_main && (size != fs->main.size || (long long)st2.st_mtim.tv_sec != fs->main.mtime_sec ||
                    (long long)st2.st_mtim.tv_nsec != fs->main.mtime_nsec)) {
        close(fd);
        refuse(fs, name, "it changed after it was checked");
        return NULL;
    }
    if (!is_main && size > PX_IO_MAX_FILE_BYTES) {
        close(fd);
        refuse(fs, name, "it has %llu bytes, more than the limit of %llu", size, (u64)PX_IO_MAX_FILE_BYTES);
        return NULL;
    }
    /* Refused here already when it cannot fit, rather than on first use:
     * glTF2's Buffer::Read leaks its stream when loading from it throws. */
    if (!is_main && size > PX_IO_MAX_IMPORT_BYTES - fs->charged) {
        close(fd);
        refuse(fs, name,
               "its %llu bytes and the %llu the import read before exceed the limit of %llu bytes for one "
               "import (PX_IO_MAX_IMPORT_BYTES)",
               size, fs->charged, (u64)PX_IO_MAX_IMPORT_BYTES);
        return NULL;
    }
    fs_file *h = pxi_alloc(fs->alloc, sizeof *h);
    if (!h) {
        close(fd);
        if (!fs->refused) fs->out_of_memory = 1;
        refuse(fs, name, "out of memory");
        return NULL;
    }
    memset(h, 0, sizeof *h);
    h->ai.ReadProc = fs_read;
    h->ai.WriteProc = fs_write;
    h->ai.TellProc = fs_tell;
    h->ai.FileSizeProc = fs_size;
    h->ai.SeekProc = fs_seek;
    h->ai.FlushProc = fs_flush;
    h->ai.UserData = (aiUserData)(void *)h;
    h->fs = fs;
    h->fd = fd;
    h->is_main = is_main;
    h->size = size;
    snprintf(h->name, sizeof h->name, "%s", name);
    h->next = fs->open_files;
    if (h->next) h->next->prev = h;
    fs->open_files = h;
    return &h->ai;
}

static void release(pxi_io_fs *fs, fs_file *h) {
    if (h->prev)
        h->prev->next = h->next;
    else
        fs->open_files = h->next;
    if (h->next) h->next->prev = h->prev;
    close(h->fd);
    pxi_free(fs->alloc, h, sizeof *h);
}

static void fs_close(struct aiFileIO *io, struct aiFile *f) {
    if (f) release((pxi_io_fs *)(void *)io->UserData, handle(f));
}

/* Assimp 5.2 leaks a stream where loading from it throws (glTF2's
 * Buffer::Read: a buffer shorter than its byteLength): its descriptor would
 * stay open for the life of the process. */
void pxi_io_fs_finish(pxi_io_fs *fs) {
    while (fs->open_files) release(fs, fs->open_files);
}

void pxi_io_fs_init(pxi_io_fs *fs, const char *path, const pxi_file_id *main, const px_allocator *alloc) {
    memset(fs, 0, sizeof *fs);
    fs->io.OpenProc = fs_open;
    fs->io.CloseProc = fs_close;
    fs->io.UserData = (aiUserData)(void *)fs;
    fs->path = path;
    fs->alloc = alloc;
    fs->main = *main;
}
