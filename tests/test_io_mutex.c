/* Regression for src/io's import lock: when mtx_init failed, io.c used to
 * call Assimp without the lock (Assimp's last-error string is a global
 * written unguarded). Now every load must fail with PX_ERR_INTERNAL, naming
 * the file, and the failure is permanent (the lock is created once).
 *
 * Configuration: this executable defines mtx_init itself, so the call from
 * libproxima binds to this always-failing one instead of the C library's
 * (a static libproxima links it directly; a shared one gets it by symbol
 * interposition). It is a separate executable because the lock is created
 * once per process. */
#define _POSIX_C_SOURCE 200809L

#include <stdio.h>
#include <string.h>
#include <threads.h>
#include <unistd.h>

#include "proxima/io.h"
#include "proxima/proxima.h"

static int g_failures;
#define CHECK(cond)                                                                                          \
    do {                                                                                                     \
        if (!(cond)) {                                                                                       \
            fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond);                         \
            g_failures++;                                                                                    \
        }                                                                                                    \
    } while (0)

static int g_init_calls;

/* Replaces the C library's mtx_init for the whole process: always fails. */
int mtx_init(mtx_t *mutex, int type) {
    (void)mutex;
    (void)type;
    g_init_calls++;
    return thrd_error;
}

int main(void) {
    char path[256];
    snprintf(path, sizeof path, "/tmp/proxima_test_io_mutex_%ld.obj", (long)getpid());
    FILE *f = fopen(path, "wb");
    if (!f) {
        perror(path);
        return 2;
    }
    fputs("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n", f);
    fclose(f);

    for (int round = 0; round < 2; ++round) { /* the second time call_once does not retry */
        double *xyz = (double *)&round;
        size_t n = 99;
        px_error err;
        memset(&err, 0, sizeof err);
        CHECK(px_load_points(path, NULL, &xyz, &n, &err) == PX_ERR_INTERNAL);
        CHECK(err.code == PX_ERR_INTERNAL);
        CHECK(strstr(err.message, path) != NULL && strstr(err.message, "mtx_init") != NULL);
        CHECK(xyz == NULL && n == 0);
        memset(&err, 0, sizeof err);
        CHECK(px_convex_create_from_file(path, NULL, &err) == NULL);
        CHECK(err.code == PX_ERR_INTERNAL && strstr(err.message, path) != NULL);
    }
    CHECK(g_init_calls == 1); /* our mtx_init was the one called, once */
    remove(path);
    if (g_failures) {
        fprintf(stderr, "test_io_mutex: %d failure(s)\n", g_failures);
        return 1;
    }
    printf("test_io_mutex: all checks passed\n");
    return 0;
}
