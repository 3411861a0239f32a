// Helpers shared by the benchmark programs (bench_convex, bench_hybrid):
// small vector algebra on px_vec3, poses, the monotonic clock, percentiles
// and list parsing. Header-only, internal to bench/. The random streams,
// shapes, rotations and motions are the shared generators of gen/px_gen.h
// (pg_sm_*: the splitmix64 stream the benchmarks have always used).
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

#include <unistd.h>

#include "access.h" /* tests/: value-returning accessors, tu_both_ways */
#include "proxima/proxima.h"
#include "px_gen.h"

namespace bench {

// Vectors are proxima's px_vec3, so the generators' results are used as they
// come.
using V3 = px_vec3;
inline V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 operator-(V3 a) { return {-a.x, -a.y, -a.z}; }
inline V3 operator*(double s, V3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline double norm(V3 a) { return std::sqrt(dot(a, a)); }
inline V3 unit(V3 a) { return (1.0 / norm(a)) * a; }

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

// The machine's CPU model name ("unknown CPU" when /proc/cpuinfo says none).
inline std::string cpu_name() {
    std::string cpu = "unknown CPU";
    if (FILE *f = fopen("/proc/cpuinfo", "r")) {
        char line[512];
        while (fgets(line, sizeof line, f))
            if (!strncmp(line, "model name", 10)) {
                const char *c = strchr(line, ':');
                cpu = c ? c + 2 : line;
                cpu.erase(cpu.find_last_not_of("\n") + 1);
                break;
            }
        fclose(f);
    }
    return cpu;
}

// The 1-minute load average (NaN when unknown).
inline double load_average() {
    double l = NAN;
    if (FILE *f = fopen("/proc/loadavg", "r")) {
        if (fscanf(f, "%lf", &l) != 1) l = NAN;
        fclose(f);
    }
    return l;
}

// "CPU, N cores online, load average L at the end of the run".
inline std::string machine_line() {
    char b[768];
    snprintf(b, sizeof b, "%s, %ld cores online, load average %.2f at the end of the run", cpu_name().c_str(),
             sysconf(_SC_NPROCESSORS_ONLN), load_average());
    return b;
}

} // namespace bench

#endif
