/* One px_distance query checked against the brute-force oracle (oracle.h):
 * the property list of issue 3 §4 in one place, shared by test_distance,
 * test_hard and test_bad_inputs. */
#ifndef PX_TESTS_CHECK_H
#define PX_TESTS_CHECK_H

#include <stddef.h>

#include "oracle.h"
#include "proxima/proxima.h"

/* Failed properties (bits of tc_report.fail). */
enum {
    TC_STATUS = 1 << 0,     /* status != PX_OK */
    TC_NONFINITE = 1 << 1,  /* NaN/Inf in the result */
    TC_DISTANCE = 1 << 2,   /* |d - d_oracle| > tol */
    TC_CLASSIFY = 1 << 3,   /* intersecting flag disagrees with the oracle */
    TC_WITNESS = 1 << 4,    /* |pa - pb| != d, or a witness off its body */
    TC_FEATURES = 1 << 5,   /* invalid feature, or features do not realise d */
    TC_INTERSECT_D = 1 << 6 /* intersecting but d != 0 */
};

typedef struct tc_report {
    px_status status;
    px_distance_result res;
    or_result orc; /* oracle answer (in the frame of the smaller body) */
    double tol;    /* 1e-12 * (|t_AB| + R_A + R_B), or the caller's */
    double scale;  /* |t_AB| + R_A + R_B */
    int band;      /* classification skipped: within tol of touching */
    int fail;      /* TC_* bits */
    char msg[600]; /* first failure, human readable */
} tc_report;

/* Tolerance factor (default 1e-12). */
extern double tc_rel_tol;

/* The method every checked query runs (px_distance_ex options), chosen by
 * PROXIMA_TEST_METHOD = lin-canny (default) | gjk | hybrid; read by
 * tc_method_from_env(), which returns its name. */
extern px_query_options tc_options;
const char *tc_method_from_env(void);

/* Runs px_distance(a, pa, b, pb, &tc_options, cache, ...) and checks it against the
 * oracle. Returns rep->fail (0 = all properties hold). */
int tc_query_and_check(const px_convex *a, const px_pose *pa, const px_convex *b, const px_pose *pb,
                       px_pair_cache *cache, tc_report *rep);

/* |t_AB| + R_A + R_B for the pair (R = max |vertex| in the body frame). */
double tc_scale(const px_convex *a, const px_pose *pa, const px_convex *b, const px_pose *pb);

/* Vertices of `a` mapped by T_AB = T_B^-1 T_A into B's frame (the doubles
 * the library sees), in xyz (3 * nv). */
void tc_vertices_in_b(const px_convex *a, const px_pose *pa, const px_pose *pb, double *xyz);
void tc_vertices(const px_convex *c, double *xyz);

/* Exact distance (CGAL) of the pair in B's frame. Returns 0 on success. */
int tc_exact(const px_convex *a, const px_pose *pa, const px_convex *b, const px_pose *pb, double *d,
             int *is_zero);

#endif
