/* Shared helpers of the test executables: assertion counters, the summary
 * line, floating-point traps and the PROXIMA_TEST_SCALE knob.
 * Compiled with _GNU_SOURCE (tests/CMakeLists.txt) for feenableexcept. */
#ifndef PX_TESTS_TEST_UTIL_H
#define PX_TESTS_TEST_UTIL_H

#include <fenv.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static int tu_pass_count;
static int tu_fail_count;
static const char *tu_name = "test";
static int tu_print_limit = 60; /* PROXIMA_TEST_MAXPRINT overrides */

/* Counts one assertion; prints the first 60 failures with file:line. */
#define CHECK(cond, ...)                                                                                     \
    do {                                                                                                     \
        if (cond) {                                                                                          \
            tu_pass_count++;                                                                                 \
        } else {                                                                                             \
            tu_fail_count++;                                                                                 \
            if (tu_fail_count <= tu_print_limit) {                                                           \
                fprintf(stderr, "%s:%d: FAILED %s: ", __FILE__, __LINE__, #cond);                            \
                fprintf(stderr, __VA_ARGS__);                                                                \
                fputc('\n', stderr);                                                                         \
            }                                                                                                \
        }                                                                                                    \
    } while (0)

/* Trap invalid operations and divisions by zero: a NaN produced anywhere
 * (library, oracle, generators) kills the test with SIGFPE. */
static inline void tu_trap_fp(void) { feenableexcept(FE_INVALID | FE_DIVBYZERO); }
static inline void tu_untrap_fp(void) {
    fedisableexcept(FE_INVALID | FE_DIVBYZERO);
    feclearexcept(FE_ALL_EXCEPT);
}

/* PROXIMA_TEST_NOTRAP=1 disables the traps (diagnosis only: to see what
 * else fails after a trap). */
static inline void tu_init(const char *name) {
    tu_name = name;
    setvbuf(stdout, NULL, _IOLBF, 0);
    const char *mp = getenv("PROXIMA_TEST_MAXPRINT");
    if (mp && *mp) tu_print_limit = atoi(mp);
    const char *nt = getenv("PROXIMA_TEST_NOTRAP");
    if (nt && *nt == '1')
        printf("%s: floating-point traps disabled (PROXIMA_TEST_NOTRAP)\n", name);
    else
        tu_trap_fp();
}

/* PROXIMA_TEST_SCALE (default 1) multiplies iteration counts; 0.1 for a
 * quick run. Clamped to [0.01, 100]. */
static inline double tu_scale(void) {
    const char *s = getenv("PROXIMA_TEST_SCALE");
    if (!s || !*s) return 1.0;
    double v = strtod(s, NULL);
    if (!(v >= 0.01)) v = 0.01;
    if (v > 100) v = 100;
    return v;
}
static inline int tu_scaled(int n) {
    int k = (int)(n * tu_scale() + 0.5);
    return k < 1 ? 1 : k;
}

/* 1 in sanitizer builds (ASan/UBSan slow CGAL's exact arithmetic by 10-20x):
 * tests that lean on exact ground truth shorten their loops there. */
static inline int tu_sanitized(void) {
#if defined(__SANITIZE_ADDRESS__)
    return 1;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
    return 1;
#else
    return 0;
#endif
#else
    return 0;
#endif
}

static inline double tu_now(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Prints "name: P passed, F failed" and returns the exit code. */
static inline int tu_finish(void) {
    printf("%s: %d passed, %d failed\n", tu_name, tu_pass_count, tu_fail_count);
    return tu_fail_count ? 1 : 0;
}

#endif
