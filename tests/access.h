/* Value-returning shorthands for the public accessors, for tests that read
 * polytopes in expressions (the API returns a status and fills an output;
 * these return the output, zeroed on error, which the tests' oracles then
 * catch). Test-only. */
#ifndef PX_TESTS_ACCESS_H
#define PX_TESTS_ACCESS_H

#include "access.h"
#include "proxima/proxima.h"

static inline px_vec3 ta_vertex(const px_convex *c, uint32_t i) {
    px_vec3 v;
    px_convex_vertex(c, i, &v);
    return v;
}
static inline uint32_t ta_face_size(const px_convex *c, uint32_t f) {
    uint32_t n;
    px_convex_face(c, f, NULL, NULL, &n);
    return n;
}
static inline uint32_t ta_face_vertex(const px_convex *c, uint32_t f, uint32_t k) {
    uint32_t v;
    px_convex_face_vertex(c, f, k, &v);
    return v;
}
/* The pose holding exactly these numbers, unchecked (t NULL: zero): the
 * tests build valid rotations themselves and also feed invalid ones to the
 * queries on purpose. px_pose_from_rt, which checks, is tested in
 * test_api.c. */
static inline px_pose ta_pose_rt(const double r[9], const double t[3]) {
    px_pose p = px_pose_identity();
    for (int i = 0; i < 9; ++i) p.r[i] = r[i];
    if (t) p.t.x = t[0], p.t.y = t[1], p.t.z = t[2];
    return p;
}
static inline px_pose ta_pose_quat(const double q[4], const double t[3]) {
    px_pose p;
    px_pose_from_quat(q, t, &p);
    return p;
}
/* The collision translation of either sign (PX_QUERY_BOTH_WAYS): what the
 * translation oracles compute. */
static const px_query_options tu_both_ways = {0, PX_QUERY_BOTH_WAYS, {0, 0, 0, 0, 0, 0}};

#endif
