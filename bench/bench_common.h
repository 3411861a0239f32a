// Helpers shared by the benchmark programs (bench_convex, bench_hybrid):
// deterministic random numbers, small vector algebra, random rotations, the
// monotonic clock, percentiles and list parsing. Header-only, internal to
// bench/.
#ifndef PROXIMA_BENCH_COMMON_H
#define PROXIMA_BENCH_COMMON_H

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

namespace bench {

// Deterministic random numbers (splitmix64; identical on every platform,
// unlike the distributions of <random>).
struct Rng {
    uint64_t s;
    uint64_t next() {
        uint64_t z = (s += 0x9e3779b97f4a7c15ULL);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        return z ^ (z >> 31);
    }
    double uniform() { return (double)(next() >> 11) * (1.0 / 9007199254740992.0); } // [0, 1)
};

struct V3 {
    double x, y, z;
};
inline V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 operator-(V3 a) { return {-a.x, -a.y, -a.z}; }
inline V3 operator*(double s, V3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline double norm(V3 a) { return std::sqrt(dot(a, a)); }
inline V3 unit(V3 a) { return (1.0 / norm(a)) * a; }

// Uniform random unit vector (normalised point of the unit ball, by rejection).
inline V3 random_unit(Rng &rng) {
    for (;;) {
        V3 v = {2 * rng.uniform() - 1, 2 * rng.uniform() - 1, 2 * rng.uniform() - 1};
        double n2 = dot(v, v);
        if (n2 > 1e-6 && n2 <= 1.0) return (1.0 / std::sqrt(n2)) * v;
    }
}

// A unit vector perpendicular to the unit vector u, uniformly at random.
inline V3 random_perpendicular(Rng &rng, V3 u) {
    for (;;) {
        V3 w = random_unit(rng);
        w = w - dot(w, u) * u;
        if (norm(w) > 1e-3) return unit(w);
    }
}

// A pose as the benchmarks store it: row-major rotation and translation.
struct Pose {
    double r[9];
    double t[3];
};

inline Pose pose_identity() {
    Pose p;
    const double id[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    std::memcpy(p.r, id, sizeof id);
    p.t[0] = p.t[1] = p.t[2] = 0;
    return p;
}

inline V3 translation(const Pose &p) { return {p.t[0], p.t[1], p.t[2]}; }
inline void set_translation(Pose &p, V3 t) { p.t[0] = t.x, p.t[1] = t.y, p.t[2] = t.z; }
// p translated by s (world frame).
inline Pose translated(Pose p, V3 s) {
    set_translation(p, translation(p) + s);
    return p;
}

// Row-major rotation matrix of the unit quaternion (w, x, y, z).
inline void quat_to_matrix(double w, double x, double y, double z, double r[9]) {
    r[0] = 1 - 2 * (y * y + z * z), r[1] = 2 * (x * y - w * z), r[2] = 2 * (x * z + w * y);
    r[3] = 2 * (x * y + w * z), r[4] = 1 - 2 * (x * x + z * z), r[5] = 2 * (y * z - w * x);
    r[6] = 2 * (x * z - w * y), r[7] = 2 * (y * z + w * x), r[8] = 1 - 2 * (x * x + y * y);
}

// Uniformly distributed random rotation (Shoemake, "Uniform random rotations",
// Graphics Gems III, 1992).
inline void random_rotation(Rng &rng, double r[9]) {
    const double u1 = rng.uniform(), u2 = 2 * M_PI * rng.uniform(), u3 = 2 * M_PI * rng.uniform();
    const double a = std::sqrt(1 - u1), b = std::sqrt(u1);
    quat_to_matrix(b * std::cos(u3), a * std::sin(u2), a * std::cos(u2), b * std::sin(u3), r);
}

// r = rot(axis, angle) * r (Rodrigues), axis a unit vector.
inline void rotate_left(V3 k, double angle, double r[9]) {
    const double c = std::cos(angle), s = std::sin(angle);
    double q[9];
    // Rodrigues: Q = c I + s [k]x + (1 - c) k k^T.
    q[0] = c + (1 - c) * k.x * k.x, q[1] = (1 - c) * k.x * k.y - s * k.z,
    q[2] = (1 - c) * k.x * k.z + s * k.y;
    q[3] = (1 - c) * k.y * k.x + s * k.z, q[4] = c + (1 - c) * k.y * k.y,
    q[5] = (1 - c) * k.y * k.z - s * k.x;
    q[6] = (1 - c) * k.z * k.x - s * k.y, q[7] = (1 - c) * k.z * k.y + s * k.x,
    q[8] = c + (1 - c) * k.z * k.z;
    double out[9];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            out[3 * i + j] = q[3 * i] * r[j] + q[3 * i + 1] * r[3 + j] + q[3 * i + 2] * r[6 + j];
    std::memcpy(r, out, sizeof out);
}

// R v (a body direction in the world frame), R v + t (a body point).
inline V3 rotate(const Pose &p, V3 v) {
    return {p.r[0] * v.x + p.r[1] * v.y + p.r[2] * v.z, p.r[3] * v.x + p.r[4] * v.y + p.r[5] * v.z,
            p.r[6] * v.x + p.r[7] * v.y + p.r[8] * v.z};
}
inline V3 apply(const Pose &p, V3 v) { return rotate(p, v) + translation(p); }
// R^T d: a world direction in the body frame.
inline V3 to_body(const Pose &p, V3 d) {
    return {p.r[0] * d.x + p.r[3] * d.y + p.r[6] * d.z, p.r[1] * d.x + p.r[4] * d.y + p.r[7] * d.z,
            p.r[2] * d.x + p.r[5] * d.y + p.r[8] * d.z};
}

inline double now_ns() {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

// Repetitions so that one timed batch lasts about 2 us (clock_gettime costs
// some 20-50 ns); at most 256.
inline int reps_for(double est_ns) {
    if (!(est_ns > 0)) return 16;
    const double r = std::ceil(2000.0 / est_ns);
    return (int)std::max(1.0, std::min(256.0, r));
}

inline double percentile(std::vector<double> v, double p) {
    if (v.empty()) return NAN;
    const size_t i = (size_t)std::floor(p * (double)(v.size() - 1));
    std::nth_element(v.begin(), v.begin() + (long)i, v.end());
    return v[i];
}

inline std::vector<size_t> parse_sizes(const char *s) {
    std::vector<size_t> v;
    while (*s) {
        char *end = nullptr;
        v.push_back(std::strtoull(s, &end, 10));
        if (end == s) break;
        s = *end == ',' ? end + 1 : end;
    }
    return v;
}

inline std::vector<double> parse_doubles(const char *s) {
    std::vector<double> v;
    while (*s) {
        char *end = nullptr;
        v.push_back(std::strtod(s, &end));
        if (end == s) break;
        s = *end == ',' ? end + 1 : end;
    }
    return v;
}

inline std::vector<std::string> parse_names(const char *s) {
    std::vector<std::string> v;
    std::string cur;
    for (; *s; ++s) {
        if (*s == ',') {
            if (!cur.empty()) v.push_back(cur);
            cur.clear();
        } else {
            cur += *s;
        }
    }
    if (!cur.empty()) v.push_back(cur);
    return v;
}

// "%.3g"-like short formatting of a time in microseconds for tables.
inline std::string fmt_us(double ns) {
    char buf[32];
    if (!(ns == ns)) return "–";
    const double us = ns * 1e-3;
    if (us < 1)
        std::snprintf(buf, sizeof buf, "%.3f", us);
    else if (us < 100)
        std::snprintf(buf, sizeof buf, "%.3g", us);
    else
        std::snprintf(buf, sizeof buf, "%.0f", us);
    return buf;
}

inline std::string fmt_err(double e) {
    char buf[32];
    if (!(e == e)) return "–";
    if (e == HUGE_VAL) return "inf";
    std::snprintf(buf, sizeof buf, "%.1e", e);
    return buf;
}

} // namespace bench

#endif
