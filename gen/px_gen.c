/* Deterministic shape and motion generators; see px_gen.h. Every formula is
 * written as its first user wrote it (tests/gen.c, bench/, the demo), so the
 * results stay bit-identical: keep the order of the operations. */
#include "px_gen.h"

#include <math.h>
#include <string.h>

static const double PG_PI = 3.14159265358979323846;

static px_vec3 vec(double x, double y, double z) {
    px_vec3 v = {x, y, z};
    return v;
}

static px_pose pose_rt(const double r[9], px_vec3 t) {
    px_pose p;
    memcpy(p.r, r, sizeof p.r);
    p.t = t;
    return p;
}

/* ------------------------------------------------------------------------- */
/* Random streams                                                            */
/* ------------------------------------------------------------------------- */

/* splitmix64 (Steele, Lea, Flood 2014): one step of the sequence x += golden
 * gamma, then the mix. */
static uint64_t splitmix64(uint64_t *x) {
    uint64_t z = (*x += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

/* xoshiro256**, its state expanded from the seed by splitmix64. */
void pg_seed(pg_rng *rng, uint64_t seed) {
    uint64_t x = seed;
    for (int i = 0; i < 4; ++i) rng->s[i] = splitmix64(&x);
}

static uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

uint64_t pg_next(pg_rng *rng) {
    uint64_t *s = rng->s;
    uint64_t result = rotl(s[1] * 5, 7) * 9;
    uint64_t t = s[1] << 17;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = rotl(s[3], 45);
    return result;
}

double pg_uniform(pg_rng *rng) {
    /* (k + 0.5) / 2^53 with k in [0, 2^53): strictly inside (0, 1). */
    uint64_t k = pg_next(rng) >> 11;
    return ((double)k + 0.5) * (1.0 / 9007199254740992.0);
}

double pg_range(pg_rng *rng, double lo, double hi) { return lo + (hi - lo) * pg_uniform(rng); }

uint32_t pg_below(pg_rng *rng, uint32_t n) { return (uint32_t)((pg_next(rng) >> 32) % n); }

uint32_t pg_log_int(pg_rng *rng, uint32_t lo, uint32_t hi) {
    double l = log((double)lo), h = log((double)hi + 1.0);
    uint32_t v = (uint32_t)exp(pg_range(rng, l, h));
    if (v < lo) v = lo;
    if (v > hi) v = hi;
    return v;
}

double pg_normal(pg_rng *rng) {
    double u1 = pg_uniform(rng), u2 = pg_uniform(rng);
    return sqrt(-2.0 * log(u1)) * cos(2.0 * PG_PI * u2);
}

px_vec3 pg_unit(pg_rng *rng) {
    for (;;) {
        double x = pg_normal(rng), y = pg_normal(rng), z = pg_normal(rng);
        double l = sqrt(x * x + y * y + z * z);
        if (l > 1e-6) return vec(x / l, y / l, z / l);
    }
}

uint64_t pg_sm_next(pg_sm *rng) { return splitmix64(&rng->s); }

double pg_sm_uniform(pg_sm *rng) { return (double)(pg_sm_next(rng) >> 11) * (1.0 / 9007199254740992.0); }

px_vec3 pg_sm_unit(pg_sm *rng) {
    for (;;) {
        double x = 2 * pg_sm_uniform(rng) - 1;
        double y = 2 * pg_sm_uniform(rng) - 1;
        double z = 2 * pg_sm_uniform(rng) - 1;
        double n2 = x * x + y * y + z * z;
        if (n2 > 1e-6 && n2 <= 1.0) {
            double f = 1.0 / sqrt(n2);
            return vec(f * x, f * y, f * z);
        }
    }
}

px_vec3 pg_sm_perpendicular(pg_sm *rng, px_vec3 u) {
    for (;;) {
        px_vec3 w = pg_sm_unit(rng);
        double d = w.x * u.x + w.y * u.y + w.z * u.z;
        w = vec(w.x - d * u.x, w.y - d * u.y, w.z - d * u.z);
        double l = sqrt(w.x * w.x + w.y * w.y + w.z * w.z);
        if (l > 1e-3) {
            double f = 1.0 / l;
            return vec(f * w.x, f * w.y, f * w.z);
        }
    }
}

/* ------------------------------------------------------------------------- */
/* Point sets                                                                */
/* ------------------------------------------------------------------------- */

void pg_points_ball(pg_rng *rng, size_t n, double radius, double *xyz) {
    for (size_t i = 0; i < n; ++i) {
        px_vec3 u = pg_unit(rng);
        double r = radius * cbrt(pg_uniform(rng));
        xyz[3 * i] = r * u.x;
        xyz[3 * i + 1] = r * u.y;
        xyz[3 * i + 2] = r * u.z;
    }
}

void pg_points_sphere(pg_rng *rng, size_t n, double radius, double *xyz) {
    pg_points_ellipsoid(rng, n, radius, radius, radius, xyz);
}

void pg_points_ellipsoid(pg_rng *rng, size_t n, double a, double b, double c, double *xyz) {
    for (size_t i = 0; i < n; ++i) {
        px_vec3 u = pg_unit(rng);
        xyz[3 * i] = a * u.x;
        xyz[3 * i + 1] = b * u.y;
        xyz[3 * i + 2] = c * u.z;
    }
}

void pg_points_in_box(pg_rng *rng, size_t n, double hx, double hy, double hz, double *xyz) {
    for (size_t i = 0; i < n; ++i) {
        xyz[3 * i] = pg_range(rng, -hx, hx);
        xyz[3 * i + 1] = pg_range(rng, -hy, hy);
        xyz[3 * i + 2] = pg_range(rng, -hz, hz);
    }
}

void pg_sm_points_sphere(pg_sm *rng, size_t n, double radius, double *xyz) {
    for (size_t i = 0; i < n; ++i) {
        px_vec3 u = pg_sm_unit(rng);
        xyz[3 * i] = radius * u.x;
        xyz[3 * i + 1] = radius * u.y;
        xyz[3 * i + 2] = radius * u.z;
    }
}

void pg_points_fibonacci_ellipsoid(size_t n, double a, double b, double c, double *xyz) {
    const double golden = PG_PI * (3.0 - sqrt(5.0));
    for (size_t i = 0; i < n; ++i) {
        double z = 1.0 - (2.0 * (double)i + 1.0) / (double)n;
        double s = 1.0 - z * z;
        double rho = sqrt(0.0 < s ? s : 0.0);
        double phi = golden * (double)i;
        xyz[3 * i] = a * rho * cos(phi);
        xyz[3 * i + 1] = b * rho * sin(phi);
        xyz[3 * i + 2] = c * z;
    }
}

void pg_box(double hx, double hy, double hz, double xyz[24]) {
    for (int i = 0; i < 8; ++i) {
        xyz[3 * i] = (i & 1) ? hx : -hx;
        xyz[3 * i + 1] = (i & 2) ? hy : -hy;
        xyz[3 * i + 2] = (i & 4) ? hz : -hz;
    }
}

void pg_regular_tetrahedron(double edge, double xyz[12]) {
    /* Alternate corners of a cube of side edge/sqrt(2). */
    double h = edge / (2.0 * sqrt(2.0));
    static const double s[12] = {1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1};
    for (int i = 0; i < 12; ++i) xyz[i] = h * s[i];
}

static double tet_volume(const double p[12]) {
    double ax = p[3] - p[0], ay = p[4] - p[1], az = p[5] - p[2];
    double bx = p[6] - p[0], by = p[7] - p[1], bz = p[8] - p[2];
    double cx = p[9] - p[0], cy = p[10] - p[1], cz = p[11] - p[2];
    return fabs(ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx)) / 6.0;
}

void pg_random_tetrahedron(pg_rng *rng, double r, double xyz[12]) {
    double edge = r * sqrt(8.0 / 3.0);
    double vreg = edge * edge * edge / (6.0 * sqrt(2.0));
    for (int attempt = 0; attempt < 1000; ++attempt) {
        pg_points_sphere(rng, 4, r, xyz);
        if (tet_volume(xyz) >= 0.05 * vreg) return;
    }
    pg_regular_tetrahedron(edge, xyz);
}

void pg_cylinder(size_t k, double radius, double half_height, double *xyz) {
    for (size_t i = 0; i < k; ++i) {
        double a = 2.0 * PG_PI * (double)i / (double)k;
        for (int s = 0; s < 2; ++s) {
            double *p = xyz + 3 * (2 * i + (size_t)s);
            p[0] = radius * cos(a);
            p[1] = radius * sin(a);
            p[2] = s ? half_height : -half_height;
        }
    }
}

size_t pg_frustum(int n, double r0, double r1, double h, double *xyz) {
    size_t count = (size_t)n + (r1 > 0 ? (size_t)n : 1), k = 0;
    if (!xyz) return count;
    for (int j = 0; j < n; ++j) {
        double ph = 2.0 * PG_PI * j / n;
        xyz[k++] = r0 * cos(ph), xyz[k++] = r0 * sin(ph), xyz[k++] = -0.5 * h;
    }
    if (r1 > 0) {
        for (int j = 0; j < n; ++j) {
            double ph = 2.0 * PG_PI * j / n;
            xyz[k++] = r1 * cos(ph), xyz[k++] = r1 * sin(ph), xyz[k++] = 0.5 * h;
        }
    } else {
        xyz[k++] = 0, xyz[k++] = 0, xyz[k++] = 0.5 * h;
    }
    return count;
}

size_t pg_sphere_latlong(int nlat, int nlon, double r, double *xyz) {
    size_t count = 2 + (size_t)(nlat - 1) * nlon, k = 0;
    if (!xyz) return count;
    xyz[k++] = 0, xyz[k++] = 0, xyz[k++] = r;
    xyz[k++] = 0, xyz[k++] = 0, xyz[k++] = -r;
    for (int i = 1; i < nlat; ++i) {
        double th = PG_PI * i / nlat;
        for (int j = 0; j < nlon; ++j) {
            double ph = 2.0 * PG_PI * j / nlon;
            xyz[k++] = r * sin(th) * cos(ph);
            xyz[k++] = r * sin(th) * sin(ph);
            xyz[k++] = r * cos(th);
        }
    }
    return count;
}

const char *pg_kind_name(pg_kind kind) {
    static const char *names[PG_KIND_COUNT] = {
        "ball", "sphere", "ellipsoid-thin", "ellipsoid-rand", "box", "tetra", "cylinder", "needle", "slab"};
    return kind < PG_KIND_COUNT ? names[kind] : "?";
}

size_t pg_shape(pg_rng *rng, pg_kind kind, size_t n, double size, double *xyz) {
    double h = 0.5 * size;
    switch (kind) {
    case PG_BALL: pg_points_ball(rng, n, h, xyz); return n;
    case PG_SPHERE: pg_points_sphere(rng, n, h, xyz); return n;
    case PG_ELLIPSOID_THIN: pg_points_ellipsoid(rng, n, h / 40.0, h / 5.0, h, xyz); return n;
    case PG_ELLIPSOID_RAND: {
        double a = pg_range(rng, 1, 30), b = pg_range(rng, 1, 30), c = pg_range(rng, 1, 30);
        double m = fmax(a, fmax(b, c));
        pg_points_ellipsoid(rng, n, h * a / m, h * b / m, h * c / m, xyz);
        return n;
    }
    case PG_BOX: {
        /* The box's and the cylinder's sizes are drawn last argument first:
         * tests/gen.c drew them as the arguments of one call, in an order C
         * leaves unspecified, and GCC's right-to-left is written down here so
         * that the stream stays as it was and no longer depends on the
         * compiler. */
        double hz = h * pg_range(rng, 0.05, 1);
        double hy = h * pg_range(rng, 0.05, 1);
        double hx = h * pg_range(rng, 0.05, 1);
        pg_box(hx, hy, hz, xyz);
        return 8;
    }
    case PG_TETRA: pg_random_tetrahedron(rng, h, xyz); return 4;
    case PG_CYLINDER: {
        size_t k = n / 2 < 3 ? 3 : n / 2;
        double half_height = h * pg_range(rng, 0.1, 1);
        double radius = h * pg_range(rng, 0.2, 1);
        pg_cylinder(k, radius, half_height, xyz);
        return 2 * k;
    }
    case PG_NEEDLE: pg_points_ellipsoid(rng, n, h / 100.0, h / 100.0, h, xyz); return n;
    case PG_SLAB: pg_points_in_box(rng, n, h, h, h / 50.0, xyz); return n;
    default: break;
    }
    pg_points_sphere(rng, n, h, xyz);
    return n;
}

/* ------------------------------------------------------------------------- */
/* Rotations                                                                 */
/* ------------------------------------------------------------------------- */

void pg_quat_shoemake(double u1, double u2, double u3, double q[4]) {
    double a = sqrt(1.0 - u1), b = sqrt(u1);
    q[0] = b * cos(2.0 * PG_PI * u3);
    q[1] = a * sin(2.0 * PG_PI * u2);
    q[2] = a * cos(2.0 * PG_PI * u2);
    q[3] = b * sin(2.0 * PG_PI * u3);
}

void pg_quat_uniform(pg_rng *rng, double q[4]) {
    double u1 = pg_uniform(rng), u2 = pg_uniform(rng), u3 = pg_uniform(rng);
    pg_quat_shoemake(u1, u2, u3, q);
}

void pg_rot_from_unit_quat(const double q[4], double r[9]) {
    double w = q[0], x = q[1], y = q[2], z = q[3];
    r[0] = 1 - 2 * (y * y + z * z);
    r[1] = 2 * (x * y - w * z);
    r[2] = 2 * (x * z + w * y);
    r[3] = 2 * (x * y + w * z);
    r[4] = 1 - 2 * (x * x + z * z);
    r[5] = 2 * (y * z - w * x);
    r[6] = 2 * (x * z - w * y);
    r[7] = 2 * (y * z + w * x);
    r[8] = 1 - 2 * (x * x + y * y);
}

void pg_rot_from_quat(const double q[4], double r[9]) {
    double n = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    double u[4] = {q[0] / n, q[1] / n, q[2] / n, q[3] / n};
    pg_rot_from_unit_quat(u, r);
}

void pg_rot_axis_angle(px_vec3 axis, double angle, double r[9]) {
    double h = 0.5 * angle, s = sin(h);
    double q[4] = {cos(h), axis.x * s, axis.y * s, axis.z * s};
    pg_rot_from_quat(q, r);
}

void pg_rot_rodrigues(px_vec3 u, double angle, double r[9]) {
    double c = cos(angle), s = sin(angle), k = 1.0 - c;
    r[0] = c + u.x * u.x * k;
    r[1] = u.x * u.y * k - u.z * s;
    r[2] = u.x * u.z * k + u.y * s;
    r[3] = u.y * u.x * k + u.z * s;
    r[4] = c + u.y * u.y * k;
    r[5] = u.y * u.z * k - u.x * s;
    r[6] = u.z * u.x * k - u.y * s;
    r[7] = u.z * u.y * k + u.x * s;
    r[8] = c + u.z * u.z * k;
}

void pg_rot_turn(px_vec3 u, double angle, double r[9]) {
    const double c = cos(angle), s = sin(angle);
    double q[9];
    q[0] = c + (1 - c) * u.x * u.x;
    q[1] = (1 - c) * u.x * u.y - s * u.z;
    q[2] = (1 - c) * u.x * u.z + s * u.y;
    q[3] = (1 - c) * u.y * u.x + s * u.z;
    q[4] = c + (1 - c) * u.y * u.y;
    q[5] = (1 - c) * u.y * u.z - s * u.x;
    q[6] = (1 - c) * u.z * u.x - s * u.y;
    q[7] = (1 - c) * u.z * u.y + s * u.x;
    q[8] = c + (1 - c) * u.z * u.z;
    pg_mat_mul(q, r, r);
}

void pg_rot_random(pg_rng *rng, double r[9]) {
    double q[4];
    pg_quat_uniform(rng, q);
    pg_rot_from_quat(q, r);
}

void pg_sm_rot_random(pg_sm *rng, double r[9]) {
    double u1 = pg_sm_uniform(rng), u2 = pg_sm_uniform(rng), u3 = pg_sm_uniform(rng), q[4];
    pg_quat_shoemake(u1, u2, u3, q);
    pg_rot_from_unit_quat(q, r);
}

void pg_mat_mul(const double a[9], const double b[9], double out[9]) {
    double t[9];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            t[3 * i + j] = a[3 * i] * b[j] + a[3 * i + 1] * b[3 + j] + a[3 * i + 2] * b[6 + j];
    for (int i = 0; i < 9; ++i) out[i] = t[i];
}

void pg_rot_orthonormalize(double r[9]) {
    double *x = r, *y = r + 3, *z = r + 6;
    double lx = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    for (int i = 0; i < 3; ++i) x[i] /= lx;
    double d = x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
    for (int i = 0; i < 3; ++i) y[i] -= d * x[i];
    double ly = sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]);
    for (int i = 0; i < 3; ++i) y[i] /= ly;
    z[0] = x[1] * y[2] - x[2] * y[1];
    z[1] = x[2] * y[0] - x[0] * y[2];
    z[2] = x[0] * y[1] - x[1] * y[0];
}

void pg_rot_rpy(double roll, double pitch, double yaw, double r[9]) {
    const double cr = cos(roll), sr = sin(roll), cp = cos(pitch), sp = sin(pitch), cy = cos(yaw),
                 sy = sin(yaw);
    const double m[9] = {cy * cp,
                         cy * sp * sr - sy * cr,
                         cy * sp * cr + sy * sr,
                         sy * cp,
                         sy * sp * sr + cy * cr,
                         sy * sp * cr - cy * sr,
                         -sp,
                         cp * sr,
                         cp * cr};
    memcpy(r, m, sizeof m);
}

px_vec3 pg_rot_apply(const double r[9], px_vec3 p) {
    return vec(r[0] * p.x + r[1] * p.y + r[2] * p.z, r[3] * p.x + r[4] * p.y + r[5] * p.z,
               r[6] * p.x + r[7] * p.y + r[8] * p.z);
}

/* ------------------------------------------------------------------------- */
/* Poses                                                                     */
/* ------------------------------------------------------------------------- */

px_pose pg_pose_random(pg_rng *rng, double tr) {
    px_pose p;
    pg_rot_random(rng, p.r);
    p.t.x = pg_range(rng, -tr, tr);
    p.t.y = pg_range(rng, -tr, tr);
    p.t.z = pg_range(rng, -tr, tr);
    return p;
}

px_pose pg_pose_around(pg_rng *rng, px_vec3 centre, double dist) {
    px_pose p = pg_pose_random(rng, 0);
    px_vec3 u = pg_unit(rng);
    p.t = vec(centre.x + u.x * dist, centre.y + u.y * dist, centre.z + u.z * dist);
    return p;
}

px_pose pg_pose_centred(const double r[9], px_vec3 body_centre, px_vec3 at) {
    px_vec3 c = pg_rot_apply(r, body_centre);
    return pose_rt(r, vec(at.x - c.x, at.y - c.y, at.z - c.z));
}

/* ------------------------------------------------------------------------- */
/* Motions                                                                   */
/* ------------------------------------------------------------------------- */

void pg_spin_poses(const pg_spin *m, px_vec3 centre_a, px_vec3 centre_b, int k, px_pose *pa, px_pose *pb) {
    double ra[9], rb[9];
    pg_rot_rodrigues(m->axis, 0.5 * k * m->theta, ra);
    pg_rot_rodrigues(m->axis, -0.5 * k * m->theta, rb);
    px_vec3 ca = pg_rot_apply(ra, centre_a);
    double s = k * m->theta;
    px_vec3 d = vec(sin(1.3 * s), 0.5 * sin(0.7 * s + 1.0), 0.5 * sin(1.1 * s + 2.0));
    px_vec3 cb = vec(m->separation + d.x * m->disp_amp, 0.0 + d.y * m->disp_amp, 0.0 + d.z * m->disp_amp);
    *pa = pose_rt(ra, vec(-ca.x, -ca.y, -ca.z));
    *pb = pg_pose_centred(rb, centre_b, cb);
}

double pg_swing_step(int k) { return (3.0 + 2.0 * sin(0.37 * k + 0.5)) * PG_PI / 180.0; }

void pg_swing_poses(const pg_swing *m, px_vec3 centre_a, px_vec3 centre_b, int k, int n, double phi,
                    px_pose *pa, px_pose *pb) {
    double ra[9], rb1[9], rb[9];
    pg_rot_rodrigues(m->axis, 0.5 * phi, ra);
    pg_rot_rodrigues(m->axis, -0.5 * phi, rb1);
    pg_mat_mul(rb1, m->r0, rb);
    double f = 0.75 + 0.4 * cos(4.0 * PG_PI * k / n);
    px_vec3 cb = vec(f * m->size, 0.08 * m->size * sin(0.05 * k), 0.08 * m->size * cos(0.031 * k));
    *pa = pg_pose_centred(ra, centre_a, vec(0, 0, 0));
    *pb = pg_pose_centred(rb, centre_b, cb);
}

px_vec3 pg_circle_point(px_vec3 u, px_vec3 v, double radius, size_t k, size_t n) {
    double phi = 2 * PG_PI * (double)k / (double)n;
    double c = cos(phi), s = sin(phi);
    return vec(radius * (c * u.x + s * v.x), radius * (c * u.y + s * v.y), radius * (c * u.z + s * v.z));
}
