/* Small vector helpers shared by the test oracles (oracle.c, oracle_sat.c).
 * They are the oracles' own: the oracles stay independent of src/ and use
 * only px_vec3 from the public header. */
#ifndef PX_TESTS_ORACLE_VEC_H
#define PX_TESTS_ORACLE_VEC_H

#include <math.h>

#include "proxima/proxima.h"

static inline px_vec3 v3(double x, double y, double z) {
    px_vec3 r = {x, y, z};
    return r;
}
static inline px_vec3 add(px_vec3 a, px_vec3 b) { return v3(a.x + b.x, a.y + b.y, a.z + b.z); }
static inline px_vec3 sub(px_vec3 a, px_vec3 b) { return v3(a.x - b.x, a.y - b.y, a.z - b.z); }
static inline px_vec3 mul(px_vec3 a, double s) { return v3(a.x * s, a.y * s, a.z * s); }
static inline double dot(px_vec3 a, px_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline px_vec3 cross(px_vec3 a, px_vec3 b) {
    return v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static inline double len(px_vec3 a) { return sqrt(dot(a, a)); }
/* R p and R^T p, R row-major. */
static inline px_vec3 rot(const double r[9], px_vec3 p) {
    return v3(r[0] * p.x + r[1] * p.y + r[2] * p.z, r[3] * p.x + r[4] * p.y + r[5] * p.z,
              r[6] * p.x + r[7] * p.y + r[8] * p.z);
}
static inline px_vec3 rot_t(const double r[9], px_vec3 p) {
    return v3(r[0] * p.x + r[3] * p.y + r[6] * p.z, r[1] * p.x + r[4] * p.y + r[7] * p.z,
              r[2] * p.x + r[5] * p.y + r[8] * p.z);
}

#endif
