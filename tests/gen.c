/* Deterministic random geometry for the tests; see gen.h. */
#include "gen.h"

#include <math.h>

static const double TG_PI = 3.14159265358979323846;

/* splitmix64 (Steele, Lea, Flood 2014), used only to expand the seed. */
static uint64_t splitmix64(uint64_t *x) {
    uint64_t z = (*x += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

void tg_seed(tg_rng *rng, uint64_t seed) {
    uint64_t x = seed;
    for (int i = 0; i < 4; ++i) rng->s[i] = splitmix64(&x);
}

static uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

/* xoshiro256** */
uint64_t tg_next(tg_rng *rng) {
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

double tg_uniform(tg_rng *rng) {
    /* (k + 0.5) / 2^53 with k in [0, 2^53): strictly inside (0, 1). */
    uint64_t k = tg_next(rng) >> 11;
    return ((double)k + 0.5) * (1.0 / 9007199254740992.0);
}

double tg_range(tg_rng *rng, double lo, double hi) { return lo + (hi - lo) * tg_uniform(rng); }

uint32_t tg_below(tg_rng *rng, uint32_t n) { return (uint32_t)((tg_next(rng) >> 32) % n); }

uint32_t tg_log_int(tg_rng *rng, uint32_t lo, uint32_t hi) {
    double l = log((double)lo), h = log((double)hi + 1.0);
    uint32_t v = (uint32_t)exp(tg_range(rng, l, h));
    if (v < lo) v = lo;
    if (v > hi) v = hi;
    return v;
}

double tg_normal(tg_rng *rng) {
    double u1 = tg_uniform(rng), u2 = tg_uniform(rng);
    return sqrt(-2.0 * log(u1)) * cos(2.0 * TG_PI * u2);
}

px_vec3 tg_unit(tg_rng *rng) {
    for (;;) {
        double x = tg_normal(rng), y = tg_normal(rng), z = tg_normal(rng);
        double l = sqrt(x * x + y * y + z * z);
        if (l > 1e-6) {
            px_vec3 v = {x / l, y / l, z / l};
            return v;
        }
    }
}

void tg_points_ball(tg_rng *rng, size_t n, double radius, double *xyz) {
    for (size_t i = 0; i < n; ++i) {
        px_vec3 u = tg_unit(rng);
        double r = radius * cbrt(tg_uniform(rng));
        xyz[3 * i] = r * u.x;
        xyz[3 * i + 1] = r * u.y;
        xyz[3 * i + 2] = r * u.z;
    }
}

void tg_points_sphere(tg_rng *rng, size_t n, double radius, double *xyz) {
    tg_points_ellipsoid(rng, n, radius, radius, radius, xyz);
}

void tg_points_ellipsoid(tg_rng *rng, size_t n, double a, double b, double c, double *xyz) {
    for (size_t i = 0; i < n; ++i) {
        px_vec3 u = tg_unit(rng);
        xyz[3 * i] = a * u.x;
        xyz[3 * i + 1] = b * u.y;
        xyz[3 * i + 2] = c * u.z;
    }
}

void tg_points_in_box(tg_rng *rng, size_t n, double hx, double hy, double hz, double *xyz) {
    for (size_t i = 0; i < n; ++i) {
        xyz[3 * i] = tg_range(rng, -hx, hx);
        xyz[3 * i + 1] = tg_range(rng, -hy, hy);
        xyz[3 * i + 2] = tg_range(rng, -hz, hz);
    }
}

void tg_box(double hx, double hy, double hz, double xyz[24]) {
    for (int i = 0; i < 8; ++i) {
        xyz[3 * i] = (i & 1) ? hx : -hx;
        xyz[3 * i + 1] = (i & 2) ? hy : -hy;
        xyz[3 * i + 2] = (i & 4) ? hz : -hz;
    }
}

void tg_regular_tetrahedron(double edge, double xyz[12]) {
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

void tg_random_tetrahedron(tg_rng *rng, double r, double xyz[12]) {
    double edge = r * sqrt(8.0 / 3.0);
    double vreg = edge * edge * edge / (6.0 * sqrt(2.0));
    for (int attempt = 0; attempt < 1000; ++attempt) {
        tg_points_sphere(rng, 4, r, xyz);
        if (tet_volume(xyz) >= 0.05 * vreg) return;
    }
    tg_regular_tetrahedron(edge, xyz);
}

void tg_cylinder(size_t k, double radius, double half_height, double *xyz) {
    for (size_t i = 0; i < k; ++i) {
        double a = 2.0 * TG_PI * (double)i / (double)k;
        for (int s = 0; s < 2; ++s) {
            double *p = xyz + 3 * (2 * i + (size_t)s);
            p[0] = radius * cos(a);
            p[1] = radius * sin(a);
            p[2] = s ? half_height : -half_height;
        }
    }
}

const char *tg_kind_name(tg_kind kind) {
    static const char *names[TG_KIND_COUNT] = {
        "ball", "sphere", "ellipsoid-thin", "ellipsoid-rand", "box", "tetra", "cylinder", "needle", "slab"};
    return kind < TG_KIND_COUNT ? names[kind] : "?";
}

size_t tg_shape(tg_rng *rng, tg_kind kind, size_t n, double size, double *xyz) {
    double h = 0.5 * size;
    switch (kind) {
    case TG_BALL: tg_points_ball(rng, n, h, xyz); return n;
    case TG_SPHERE: tg_points_sphere(rng, n, h, xyz); return n;
    case TG_ELLIPSOID_THIN: tg_points_ellipsoid(rng, n, h / 40.0, h / 5.0, h, xyz); return n;
    case TG_ELLIPSOID_RAND: {
        double a = tg_range(rng, 1, 30), b = tg_range(rng, 1, 30), c = tg_range(rng, 1, 30);
        double m = fmax(a, fmax(b, c));
        tg_points_ellipsoid(rng, n, h * a / m, h * b / m, h * c / m, xyz);
        return n;
    }
    case TG_BOX:
        tg_box(h * tg_range(rng, 0.05, 1), h * tg_range(rng, 0.05, 1), h * tg_range(rng, 0.05, 1), xyz);
        return 8;
    case TG_TETRA: tg_random_tetrahedron(rng, h, xyz); return 4;
    case TG_CYLINDER: {
        size_t k = n / 2 < 3 ? 3 : n / 2;
        tg_cylinder(k, h * tg_range(rng, 0.2, 1), h * tg_range(rng, 0.1, 1), xyz);
        return 2 * k;
    }
    case TG_NEEDLE: tg_points_ellipsoid(rng, n, h / 100.0, h / 100.0, h, xyz); return n;
    case TG_SLAB: tg_points_in_box(rng, n, h, h, h / 50.0, xyz); return n;
    default: break;
    }
    tg_points_sphere(rng, n, h, xyz);
    return n;
}

void tg_quat_uniform(tg_rng *rng, double q[4]) {
    /* Shoemake, "Uniform random rotations", Graphics Gems III (1992). */
    double u1 = tg_uniform(rng), u2 = tg_uniform(rng), u3 = tg_uniform(rng);
    double a = sqrt(1.0 - u1), b = sqrt(u1);
    q[0] = b * cos(2.0 * TG_PI * u3);
    q[1] = a * sin(2.0 * TG_PI * u2);
    q[2] = a * cos(2.0 * TG_PI * u2);
    q[3] = b * sin(2.0 * TG_PI * u3);
}

void tg_rot_from_quat(const double q[4], double r[9]) {
    double n = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    double w = q[0] / n, x = q[1] / n, y = q[2] / n, z = q[3] / n;
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

void tg_rot_axis_angle(px_vec3 axis, double angle, double r[9]) {
    double h = 0.5 * angle, s = sin(h);
    double q[4] = {cos(h), axis.x * s, axis.y * s, axis.z * s};
    tg_rot_from_quat(q, r);
}

void tg_rot_random(tg_rng *rng, double r[9]) {
    double q[4];
    tg_quat_uniform(rng, q);
    tg_rot_from_quat(q, r);
}

void tg_mat_mul(const double a[9], const double b[9], double out[9]) {
    double t[9];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            t[3 * i + j] = a[3 * i] * b[j] + a[3 * i + 1] * b[3 + j] + a[3 * i + 2] * b[6 + j];
    for (int i = 0; i < 9; ++i) out[i] = t[i];
}

void tg_rot_orthonormalize(double r[9]) {
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

px_pose tg_pose_random(tg_rng *rng, double tr) {
    px_pose p;
    tg_rot_random(rng, p.r);
    p.t.x = tg_range(rng, -tr, tr);
    p.t.y = tg_range(rng, -tr, tr);
    p.t.z = tg_range(rng, -tr, tr);
    return p;
}
