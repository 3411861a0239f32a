// bench_convex: proxima's Lin-Canny distance (px_distance) against FCL 0.7
// (fcl::distance on fcl::Convex, GJK through libccd) on the protocol of seed
// 002 (Carretero & Nahon style comparison of CTA, enhanced GJK and PQP,
// section IV): polytopes with vertices on ellipsoids, "balanced" (semi-axes
// 1:1:1) and "thin" (1:8:40), sizes 200 ... 200,000 vertices;
//   - from scratch: ~1,000 random settings per size (uniform random rotations,
//     gap about 10 % of the diameter), no coherence (zero cache);
//   - incremental: sequences of 100 small moves of delta = 1 %, 0.5 %, 0.25 %,
//     0.125 % of the diameter, the cache carried from one query to the next.
// Every method runs in this process on exactly the same poses (same doubles).
// A subset of the answers is checked against the exact distance (CGAL
// Polytope_distance_d over an exact number type, pxcd_exact_distance).
//
// This is a benchmark program, not a test (ARCHITECTURE.md): the machine is
// shared and noisy, so it reports medians and 90th percentiles over many
// queries. Output: DIR/convex.csv (see write_csv) and a summary on stdout.
//
// Usage: bench_convex [--out DIR] [--quick] [--max-n N] [--seed S] (see usage())
// Exit status 3 when a lin-canny answer is an error, NaN, "intersecting" on
// these disjoint bodies, or off by more than 1e-6 relative to the exact
// distance (a smoke check, not a timing assertion).

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <memory>
#include <string>
#include <vector>

#include <fcl/geometry/shape/convex.h>
#include <fcl/narrowphase/distance.h>

#include "proxima/proxima.h"
#include "pxcd.h"

namespace {

// ---------------------------------------------------------------------------
// Deterministic random numbers (splitmix64; identical on every platform, unlike
// the distributions of <random>).
// ---------------------------------------------------------------------------
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
V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V3 operator*(double s, V3 a) { return {s * a.x, s * a.y, s * a.z}; }
double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
double norm(V3 a) { return std::sqrt(dot(a, a)); }
V3 unit(V3 a) { return (1.0 / norm(a)) * a; }

// Uniform random unit vector (Marsaglia: normalised Gaussian via rejection).
V3 random_unit(Rng &rng) {
    for (;;) {
        V3 v = {2 * rng.uniform() - 1, 2 * rng.uniform() - 1, 2 * rng.uniform() - 1};
        double n2 = dot(v, v);
        if (n2 > 1e-6 && n2 <= 1.0) return (1.0 / std::sqrt(n2)) * v;
    }
}

// A pose as the benchmark stores it: row-major rotation and translation.
struct Pose {
    double r[9];
    double t[3];
};

// Row-major rotation matrix of the unit quaternion (w, x, y, z).
void quat_to_matrix(double w, double x, double y, double z, double r[9]) {
    r[0] = 1 - 2 * (y * y + z * z), r[1] = 2 * (x * y - w * z), r[2] = 2 * (x * z + w * y);
    r[3] = 2 * (x * y + w * z), r[4] = 1 - 2 * (x * x + z * z), r[5] = 2 * (y * z - w * x);
    r[6] = 2 * (x * z - w * y), r[7] = 2 * (y * z + w * x), r[8] = 1 - 2 * (x * x + y * y);
}

// Uniformly distributed random rotation (Shoemake, "Uniform random rotations",
// Graphics Gems III, 1992).
void random_rotation(Rng &rng, double r[9]) {
    const double u1 = rng.uniform(), u2 = 2 * M_PI * rng.uniform(), u3 = 2 * M_PI * rng.uniform();
    const double a = std::sqrt(1 - u1), b = std::sqrt(u1);
    quat_to_matrix(b * std::cos(u3), a * std::sin(u2), a * std::cos(u2), b * std::sin(u3), r);
}

// r = rot(axis, angle) * r (Rodrigues), axis a unit vector.
void rotate_left(V3 k, double angle, double r[9]) {
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

V3 apply(const Pose &p, V3 v) {
    return {p.r[0] * v.x + p.r[1] * v.y + p.r[2] * v.z + p.t[0],
            p.r[3] * v.x + p.r[4] * v.y + p.r[5] * v.z + p.t[1],
            p.r[6] * v.x + p.r[7] * v.y + p.r[8] * v.z + p.t[2]};
}
// R^T d: a world direction in the body frame.
V3 to_body(const Pose &p, V3 d) {
    return {p.r[0] * d.x + p.r[3] * d.y + p.r[6] * d.z, p.r[1] * d.x + p.r[4] * d.y + p.r[7] * d.z,
            p.r[2] * d.x + p.r[5] * d.y + p.r[8] * d.z};
}

double now_ns() {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

// ---------------------------------------------------------------------------
// Bodies
// ---------------------------------------------------------------------------
struct Shape {
    const char *name;
    double axes[3];
};
const Shape kShapes[] = {{"balanced", {1, 1, 1}}, {"thin", {1, 8, 40}}};

// n points of a golden-spiral (Fibonacci) lattice on the unit sphere, mapped
// to the ellipsoid with the given semi-axes. Points on a strictly convex
// surface are all extreme, so (up to rounding) every point is a hull vertex.
// The faces of the "thin" ellipsoid are long thin triangles.
std::vector<double> ellipsoid_points(size_t n, const double axes[3]) {
    std::vector<double> xyz(3 * n);
    const double golden = M_PI * (3.0 - std::sqrt(5.0));
    for (size_t i = 0; i < n; ++i) {
        const double z = 1.0 - (2.0 * (double)i + 1.0) / (double)n;
        const double rho = std::sqrt(std::max(0.0, 1.0 - z * z));
        const double phi = golden * (double)i;
        xyz[3 * i] = axes[0] * rho * std::cos(phi);
        xyz[3 * i + 1] = axes[1] * rho * std::sin(phi);
        xyz[3 * i + 2] = axes[2] * z;
    }
    return xyz;
}

struct Body {
    px_convex *cx = nullptr;
    std::vector<V3> verts; // hull vertices, indexed as in px_convex
    std::shared_ptr<fcl::Convexd> fcl;
    double diameter = 0; // 2 * largest semi-axis
    double build_px_ms = 0, build_fcl_ms = 0;
    ~Body() { px_convex_destroy(cx); }
};

std::unique_ptr<Body> make_body(const Shape &shape, size_t n) {
    std::unique_ptr<Body> b(new Body);
    std::vector<double> xyz = ellipsoid_points(n, shape.axes);
    px_error err;
    double t0 = now_ns();
    b->cx = px_convex_from_points(xyz.data(), n, nullptr, &err);
    b->build_px_ms = (now_ns() - t0) * 1e-6;
    if (!b->cx) {
        std::fprintf(stderr, "bench_convex: px_convex_from_points(%s, %zu) failed: %s: %s\n", shape.name, n,
                     px_status_string(err.code), err.message);
        return nullptr;
    }
    const uint32_t nv = px_convex_vertex_count(b->cx), nf = px_convex_face_count(b->cx);
    b->verts.resize(nv);
    auto fv = std::make_shared<std::vector<fcl::Vector3d>>(nv);
    for (uint32_t i = 0; i < nv; ++i) {
        px_vec3 p = px_convex_vertex(b->cx, i);
        b->verts[i] = {p.x, p.y, p.z};
        (*fv)[i] = fcl::Vector3d(p.x, p.y, p.z);
    }
    // FCL face encoding: "count, i0, i1, ..." per face (fcl/geometry/shape/convex.h).
    auto ff = std::make_shared<std::vector<int>>();
    ff->reserve(3 * (size_t)px_convex_edge_count(b->cx) + nf);
    for (uint32_t f = 0; f < nf; ++f) {
        const uint32_t k = px_convex_face_size(b->cx, f);
        ff->push_back((int)k);
        for (uint32_t j = 0; j < k; ++j) ff->push_back((int)px_convex_face_vertex(b->cx, f, j));
    }
    t0 = now_ns();
    b->fcl = std::make_shared<fcl::Convexd>(fv, (int)nf, ff, false);
    b->fcl->computeLocalAABB();
    b->build_fcl_ms = (now_ns() - t0) * 1e-6;
    b->diameter = 2 * std::max(shape.axes[0], std::max(shape.axes[1], shape.axes[2]));
    return b;
}

// Support value max_v (R v) . d of the body at pose p, by a linear scan
// (setup only).
double support(const Body &b, const Pose &p, V3 d) {
    const V3 db = to_body(p, d);
    double best = -HUGE_VAL;
    for (const V3 &v : b.verts) best = std::max(best, dot(v, db));
    return best + p.t[0] * d.x + p.t[1] * d.y + p.t[2] * d.z;
}

// ---------------------------------------------------------------------------
// Methods
// ---------------------------------------------------------------------------
enum Method { kPx = 0, kFclTight = 1, kFclDefault = 2, kMethodCount = 3 };
const char *const kMethodNames[kMethodCount] = {"lin-canny", "fcl-gjk-tol1e-9", "fcl-gjk-default"};

fcl::Transform3d to_fcl(const Pose &p) {
    fcl::Transform3d tf = fcl::Transform3d::Identity();
    fcl::Matrix3d r;
    r << p.r[0], p.r[1], p.r[2], p.r[3], p.r[4], p.r[5], p.r[6], p.r[7], p.r[8];
    tf.linear() = r;
    tf.translation() = fcl::Vector3d(p.t[0], p.t[1], p.t[2]);
    return tf;
}

// FCL 0.7 defaults: DistanceRequest() uses GST_LIBCCD and distance_tolerance 1e-6
// (fcl/narrowphase/distance_request.h); nearest points are in the world frame
// since FCL 0.6.
fcl::DistanceRequestd fcl_request(Method m) {
    fcl::DistanceRequestd req;
    req.enable_nearest_points = true;
    req.gjk_solver_type = fcl::GST_LIBCCD;
    if (m == kFclTight) req.distance_tolerance = 1e-9;
    return req;
}

double fcl_distance(const Body &b, const fcl::Transform3d &ta, const fcl::Transform3d &tb,
                    const fcl::DistanceRequestd &req, V3 *pa, V3 *pb) {
    fcl::DistanceResultd res;
    fcl::distance(b.fcl.get(), ta, b.fcl.get(), tb, req, res);
    if (pa) *pa = {res.nearest_points[0].x(), res.nearest_points[0].y(), res.nearest_points[0].z()};
    if (pb) *pb = {res.nearest_points[1].x(), res.nearest_points[1].y(), res.nearest_points[1].z()};
    return res.min_distance;
}

// ---------------------------------------------------------------------------
// Workloads: a list of sequences. Query 0 of a sequence only primes the cache
// (untimed, not counted) when `warm` is set; for scratch every sequence has
// one pose and every query starts cold.
// ---------------------------------------------------------------------------
struct Workload {
    std::string mode; // "scratch" or "incremental"
    double delta = 0; // fraction of the diameter per move (incremental)
    bool warm = false;
    std::vector<std::vector<Pose>> seq_a, seq_b;
    size_t counted() const {
        size_t n = 0;
        for (const auto &s : seq_a) n += s.size() - (warm ? 1 : 0);
        return n;
    }
};

// Places B (pose pb, rotation set, translation overwritten) along direction u
// from A so that the true distance is gap (within 1 %): first by support
// functions (the gap of the projections on u is exactly `gap`, so the true
// distance is at least `gap`), then by moving B back along u by the excess
// measured with FCL (tolerance 1e-9). Distance is 1-Lipschitz in the
// translation, so every step keeps it >= gap.
void place(const Body &b, const Pose &pa, Pose &pb, V3 u, double gap) {
    pb.t[0] = pb.t[1] = pb.t[2] = 0;
    double s = support(b, pa, u) + support(b, pb, -1.0 * u) + gap;
    const fcl::DistanceRequestd req = fcl_request(kFclTight);
    const fcl::Transform3d ta = to_fcl(pa);
    for (int it = 0; it < 6; ++it) {
        pb.t[0] = s * u.x, pb.t[1] = s * u.y, pb.t[2] = s * u.z;
        const double d = fcl_distance(b, ta, to_fcl(pb), req, nullptr, nullptr);
        if (!(d > 0) || std::fabs(d - gap) <= 0.01 * gap) break;
        s -= d - gap;
    }
}

Workload make_scratch(const Body &b, Rng &rng, size_t count) {
    Workload w;
    w.mode = "scratch";
    for (size_t i = 0; i < count; ++i) {
        Pose pa, pb;
        random_rotation(rng, pa.r);
        random_rotation(rng, pb.r);
        pa.t[0] = pa.t[1] = pa.t[2] = 0;
        place(b, pa, pb, random_unit(rng), 0.1 * b.diameter);
        w.seq_a.push_back({pa});
        w.seq_b.push_back({pb});
    }
    return w;
}

// Sequences of `steps` moves of B (A stays): each move rotates B about its
// centre by an angle whose arc length at B's farthest point is delta * D, about
// an axis fixed per sequence (a constant angular velocity), and translates it
// by delta * D. The translation slides along the tangent plane of the current
// separation direction n (from FCL's witness points) with a radial component
// that pulls the gap back towards 10 % of D, so the bodies never meet.
Workload make_incremental(const Body &b, Rng &rng, double delta, size_t sequences, size_t steps) {
    Workload w;
    w.mode = "incremental";
    w.delta = delta;
    w.warm = true;
    const double D = b.diameter, gap = 0.1 * D, step = delta * D;
    double radius = 0;
    for (const V3 &v : b.verts) radius = std::max(radius, norm(v));
    const double angle = step / radius;
    const fcl::DistanceRequestd req = fcl_request(kFclTight);
    for (size_t s = 0; s < sequences; ++s) {
        Pose pa, pb;
        random_rotation(rng, pa.r);
        random_rotation(rng, pb.r);
        pa.t[0] = pa.t[1] = pa.t[2] = 0;
        place(b, pa, pb, random_unit(rng), gap);
        const V3 axis = random_unit(rng);
        const V3 slide = random_unit(rng);
        const fcl::Transform3d ta = to_fcl(pa);
        std::vector<Pose> sa{pa}, sb{pb};
        for (size_t k = 0; k < steps; ++k) {
            V3 wa, wb;
            const double d = fcl_distance(b, ta, to_fcl(pb), req, &wa, &wb);
            V3 n = wb - wa;
            n = norm(n) > 0 ? unit(n) : unit(V3{pb.t[0], pb.t[1], pb.t[2]});
            V3 tang = slide - dot(slide, n) * n;
            if (norm(tang) < 1e-3) tang = random_unit(rng); // slide direction ~ parallel to n
            tang = unit(tang - dot(tang, n) * n);
            const double c = std::max(-1.0, std::min(1.0, (gap - d) / step));
            const V3 move = step * (c * n + std::sqrt(1 - c * c) * tang);
            rotate_left(axis, angle, pb.r);
            pb.t[0] += move.x, pb.t[1] += move.y, pb.t[2] += move.z;
            sa.push_back(pa);
            sb.push_back(pb);
        }
        w.seq_a.push_back(sa);
        w.seq_b.push_back(sb);
    }
    return w;
}

// ---------------------------------------------------------------------------
// Timing
// ---------------------------------------------------------------------------
struct Run {
    std::vector<double> ns;   // per counted query
    std::vector<double> dist; // per counted query
    double stream_ns = 0;     // one plain pass over the workload / counted queries
    uint64_t iterations = 0, fallbacks = 0, intersecting = 0, errors = 0;
};

// Repetitions so that one timed batch lasts about 2 us (clock_gettime costs
// some 20-50 ns); at most 256.
int reps_for(double est_ns) {
    if (!(est_ns > 0)) return 16;
    const double r = std::ceil(2000.0 / est_ns);
    return (int)std::max(1.0, std::min(256.0, r));
}

Run run_px(const Body &b, const Workload &w) {
    Run run;
    std::vector<std::vector<px_pose>> pa(w.seq_a.size()), pb(w.seq_a.size());
    for (size_t s = 0; s < w.seq_a.size(); ++s)
        for (size_t k = 0; k < w.seq_a[s].size(); ++k) {
            pa[s].push_back(px_pose_from_rt(w.seq_a[s][k].r, w.seq_a[s][k].t));
            pb[s].push_back(px_pose_from_rt(w.seq_b[s][k].r, w.seq_b[s][k].t));
        }
    const size_t first = w.warm ? 1 : 0;
    px_distance_result res;
    // 0. Warm-up: the first sequences (code, branch predictors, clocks).
    for (size_t s = 0; s < std::min<size_t>(pa.size(), 50); ++s) {
        px_distance_cache cache;
        std::memset(&cache, 0, sizeof cache);
        px_distance(b.cx, &pa[s][0], b.cx, &pb[s][0], &cache, &res);
    }
    // 1. Streaming pass: each sequence as an application would run it, timed
    // as a whole (sequence by sequence, so the setup is not timed).
    double total = 0;
    for (size_t s = 0; s < pa.size(); ++s) {
        px_distance_cache cache;
        std::memset(&cache, 0, sizeof cache);
        if (w.warm) px_distance(b.cx, &pa[s][0], b.cx, &pb[s][0], &cache, &res);
        const double t0 = now_ns();
        for (size_t k = first; k < pa[s].size(); ++k) {
            if (!w.warm) std::memset(&cache, 0, sizeof cache);
            px_distance(b.cx, &pa[s][k], b.cx, &pb[s][k], &cache, &res);
        }
        total += now_ns() - t0;
    }
    run.stream_ns = total / (double)w.counted();
    // 2. Per-query timing: every query repeated `reps` times, each repetition
    // from a fresh copy of the cache the query would see in the sequence.
    double est = run.stream_ns;
    for (size_t s = 0; s < pa.size(); ++s) {
        px_distance_cache cache;
        std::memset(&cache, 0, sizeof cache);
        if (w.warm) px_distance(b.cx, &pa[s][0], b.cx, &pb[s][0], &cache, &res);
        for (size_t k = first; k < pa[s].size(); ++k) {
            const int reps = reps_for(est);
            px_distance_cache c = cache;
            px_status st = PX_OK;
            const double t0 = now_ns();
            for (int r = 0; r < reps; ++r) {
                c = cache;
                st = px_distance(b.cx, &pa[s][k], b.cx, &pb[s][k], &c, &res);
            }
            const double dt = (now_ns() - t0) / reps;
            est = dt;
            run.ns.push_back(dt);
            run.dist.push_back(st == PX_OK ? res.distance : NAN);
            run.errors += st != PX_OK;
            run.iterations += res.iterations;
            run.fallbacks += res.fallbacks;
            run.intersecting += res.intersecting != 0;
            if (w.warm) cache = c;
        }
    }
    return run;
}

Run run_fcl(const Body &b, const Workload &w, Method m) {
    Run run;
    const fcl::DistanceRequestd req = fcl_request(m);
    std::vector<std::vector<fcl::Transform3d>> ta(w.seq_a.size()), tb(w.seq_a.size());
    for (size_t s = 0; s < w.seq_a.size(); ++s)
        for (size_t k = 0; k < w.seq_a[s].size(); ++k) {
            ta[s].push_back(to_fcl(w.seq_a[s][k]));
            tb[s].push_back(to_fcl(w.seq_b[s][k]));
        }
    const size_t first = w.warm ? 1 : 0; // FCL keeps no state between calls
    for (size_t s = 0; s < std::min<size_t>(ta.size(), 50); ++s) {
        fcl::DistanceResultd res;
        fcl::distance(b.fcl.get(), ta[s][0], b.fcl.get(), tb[s][0], req, res);
    }
    double total = 0;
    for (size_t s = 0; s < ta.size(); ++s) {
        const double t0 = now_ns();
        for (size_t k = first; k < ta[s].size(); ++k) {
            fcl::DistanceResultd res;
            fcl::distance(b.fcl.get(), ta[s][k], b.fcl.get(), tb[s][k], req, res);
        }
        total += now_ns() - t0;
    }
    run.stream_ns = total / (double)w.counted();
    double est = run.stream_ns;
    for (size_t s = 0; s < ta.size(); ++s)
        for (size_t k = first; k < ta[s].size(); ++k) {
            const int reps = reps_for(est);
            fcl::DistanceResultd res;
            const double t0 = now_ns();
            for (int r = 0; r < reps; ++r) {
                res.clear();
                fcl::distance(b.fcl.get(), ta[s][k], b.fcl.get(), tb[s][k], req, res);
            }
            const double dt = (now_ns() - t0) / reps;
            est = dt;
            run.ns.push_back(dt);
            run.dist.push_back(res.min_distance);
            run.intersecting += res.min_distance <= 0;
        }
    return run;
}

double percentile(std::vector<double> v, double p) {
    if (v.empty()) return NAN;
    const size_t i = (size_t)std::floor(p * (double)(v.size() - 1));
    std::nth_element(v.begin(), v.begin() + (long)i, v.end());
    return v[i];
}

// ---------------------------------------------------------------------------
// Exact ground truth on a subset: `count` counted queries, evenly spread.
// ---------------------------------------------------------------------------
struct Exact {
    std::vector<size_t> index; // counted-query indices checked
    std::vector<double> dist;
    double min_gap = 0, max_gap = 0; // exact distance / D over the subset
    double seconds = 0;
};

Exact exact_subset(const Body &b, const Workload &w, size_t count) {
    Exact ex;
    std::vector<std::pair<const Pose *, const Pose *>> q;
    const size_t first = w.warm ? 1 : 0;
    for (size_t s = 0; s < w.seq_a.size(); ++s)
        for (size_t k = first; k < w.seq_a[s].size(); ++k) q.push_back({&w.seq_a[s][k], &w.seq_b[s][k]});
    count = std::min(count, q.size());
    std::vector<double> pa(3 * b.verts.size()), pb(3 * b.verts.size());
    const double t0 = now_ns();
    for (size_t j = 0; j < count; ++j) {
        const size_t i = j * q.size() / count;
        for (size_t v = 0; v < b.verts.size(); ++v) {
            const V3 a = apply(*q[i].first, b.verts[v]), c = apply(*q[i].second, b.verts[v]);
            pa[3 * v] = a.x, pa[3 * v + 1] = a.y, pa[3 * v + 2] = a.z;
            pb[3 * v] = c.x, pb[3 * v + 1] = c.y, pb[3 * v + 2] = c.z;
        }
        double d = NAN, d2 = NAN;
        int zero = 0;
        char msg[256] = "";
        const pxcd_status st = pxcd_exact_distance(pa.data(), b.verts.size(), pb.data(), b.verts.size(), &d,
                                                   &d2, &zero, nullptr, nullptr, msg, sizeof msg);
        if (st != PXCD_OK) {
            std::fprintf(stderr, "bench_convex: exact distance failed: %s\n", msg);
            continue;
        }
        ex.index.push_back(i);
        ex.dist.push_back(d);
        ex.min_gap = ex.index.size() == 1 ? d / b.diameter : std::min(ex.min_gap, d / b.diameter);
        ex.max_gap = std::max(ex.max_gap, d / b.diameter);
    }
    ex.seconds = (now_ns() - t0) * 1e-9;
    return ex;
}

double max_rel_err(const Run &run, const Exact &ex) {
    double worst = 0;
    for (size_t j = 0; j < ex.index.size(); ++j) {
        const double d = run.dist[ex.index[j]], e = ex.dist[j];
        double err = e > 0 ? std::fabs(d - e) / e : std::fabs(d);
        if (!(err == err)) err = HUGE_VAL; // NaN answer: infinitely wrong
        worst = std::max(worst, err);
    }
    return worst;
}

// ---------------------------------------------------------------------------
// Driver
// ---------------------------------------------------------------------------
struct Row {
    std::string method, shape, mode;
    size_t n, queries, checked;
    double delta, median_ns, p90_ns, max_rel_err, stream_ns;
};

struct Options {
    std::string out = "docs/bench";
    bool quick = false;
    size_t max_n = SIZE_MAX;
    uint64_t seed = 2;
    std::vector<size_t> sizes; // --sizes: instead of the default list
    size_t scratch = 0;        // --scratch: settings per size (0: default)
    size_t sequences = 0;      // --sequences: per size and delta (0: default)
    size_t exact = SIZE_MAX;   // --exact: ground-truth checks per workload
};

std::vector<size_t> parse_list(const char *s) {
    std::vector<size_t> v;
    while (*s) {
        char *end = nullptr;
        v.push_back(std::strtoull(s, &end, 10));
        if (end == s) break;
        s = *end == ',' ? end + 1 : end;
    }
    return v;
}

// Ground-truth checks per workload. CGAL's exact Polytope_distance_d takes
// about 4 ms at n = 200, 0.5 s at 20k and 7-10 s at 200k per query on the
// 2-core machine, so large sizes are checked on a few queries only.
size_t exact_count(size_t n, bool quick) {
    if (quick) return 10;
    if (n <= 1000) return 200;
    if (n <= 5000) return 50;
    if (n <= 20000) return 20;
    if (n <= 100000) return 5;
    return 3;
}

int write_csv(const std::string &path, const std::vector<Row> &rows) {
    FILE *f = std::fopen(path.c_str(), "w");
    if (!f) {
        std::fprintf(stderr, "bench_convex: cannot write %s: %s\n", path.c_str(), std::strerror(errno));
        return 1;
    }
    std::fprintf(
        f, "method,shape,n,mode,delta,median_ns,p90_ns,max_rel_err,queries,stream_mean_ns,exact_checked\n");
    for (const Row &r : rows) {
        char delta[32] = "";
        if (r.mode == "incremental") std::snprintf(delta, sizeof delta, "%g", r.delta);
        std::fprintf(f, "%s,%s,%zu,%s,%s,%.1f,%.1f,%.3e,%zu,%.1f,%zu\n", r.method.c_str(), r.shape.c_str(),
                     r.n, r.mode.c_str(), delta, r.median_ns, r.p90_ns, r.max_rel_err, r.queries, r.stream_ns,
                     r.checked);
    }
    std::fclose(f);
    return 0;
}

void usage(void) {
    std::fprintf(stderr, "usage: bench_convex [--out DIR] [--quick] [--max-n N] [--seed S] [--sizes N,N,..]\n"
                         "                    [--scratch K] [--sequences K] [--exact K]\n"
                         "  --out DIR       write DIR/convex.csv (default docs/bench)\n"
                         "  --quick         n = 200 and 1000 only, few queries (smoke run)\n"
                         "  --max-n N       skip sizes above N vertices\n"
                         "  --sizes LIST    vertex counts instead of 200,1000,5000,20000,100000,200000\n"
                         "  --scratch K     random settings per size (default 1000)\n"
                         "  --sequences K   sequences of 100 moves per size and delta (default 10)\n"
                         "  --exact K       queries per workload checked against the exact distance\n");
}

} // namespace

int main(int argc, char **argv) {
    Options opt;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--out" && i + 1 < argc)
            opt.out = argv[++i];
        else if (a == "--quick")
            opt.quick = true;
        else if (a == "--max-n" && i + 1 < argc)
            opt.max_n = std::strtoull(argv[++i], nullptr, 10);
        else if (a == "--seed" && i + 1 < argc)
            opt.seed = std::strtoull(argv[++i], nullptr, 10);
        else if (a == "--sizes" && i + 1 < argc)
            opt.sizes = parse_list(argv[++i]);
        else if (a == "--scratch" && i + 1 < argc)
            opt.scratch = std::strtoull(argv[++i], nullptr, 10);
        else if (a == "--sequences" && i + 1 < argc)
            opt.sequences = std::strtoull(argv[++i], nullptr, 10);
        else if (a == "--exact" && i + 1 < argc)
            opt.exact = std::strtoull(argv[++i], nullptr, 10);
        else {
            usage();
            return a == "--help" || a == "-h" ? 0 : 2;
        }
    }
    std::vector<size_t> sizes = {200, 1000, 5000, 20000, 100000, 200000};
    if (opt.quick) sizes = {200, 1000};
    if (!opt.sizes.empty()) sizes = opt.sizes;
    const size_t scratch_count = opt.scratch ? opt.scratch : opt.quick ? 50 : 1000;
    const size_t sequences = opt.sequences ? opt.sequences : opt.quick ? 2 : 10, steps = 100;
    const double deltas[] = {0.01, 0.005, 0.0025, 0.00125};

    std::vector<Row> rows;
    unsigned long long bad = 0; // lin-canny answers that are errors, NaN, "intersecting" or off by > 1e-6
    std::printf("%-16s %-9s %7s %-12s %7s %11s %11s %11s %10s %6s\n", "method", "shape", "n", "mode", "delta",
                "median_ns", "p90_ns", "stream_ns", "max_rel", "ratio");
    for (size_t n : sizes) {
        if (n > opt.max_n) continue;
        for (const Shape &shape : kShapes) {
            std::unique_ptr<Body> body = make_body(shape, n);
            if (!body) return 1;
            std::printf(
                "# %s n=%zu: hull %zu vertices, %u faces; build px %.1f ms (%zu bytes/vertex), fcl %.1f "
                "ms\n",
                shape.name, n, body->verts.size(), px_convex_face_count(body->cx), body->build_px_ms,
                px_convex_memory_bytes(body->cx) / body->verts.size(), body->build_fcl_ms);
            Rng rng{opt.seed * 1000003u + n * 7 + (shape.axes[2] > 1 ? 1 : 0)};
            std::vector<Workload> loads;
            loads.push_back(make_scratch(*body, rng, scratch_count));
            for (double d : deltas) loads.push_back(make_incremental(*body, rng, d, sequences, steps));
            for (const Workload &w : loads) {
                Run runs[kMethodCount];
                runs[kPx] = run_px(*body, w);
                runs[kFclTight] = run_fcl(*body, w, kFclTight);
                runs[kFclDefault] = run_fcl(*body, w, kFclDefault);
                const Exact ex =
                    exact_subset(*body, w, opt.exact != SIZE_MAX ? opt.exact : exact_count(n, opt.quick));
                const double px_median = percentile(runs[kPx].ns, 0.5);
                for (int m = 0; m < kMethodCount; ++m) {
                    Row r;
                    r.method = kMethodNames[m];
                    r.shape = shape.name;
                    r.mode = w.mode;
                    r.n = body->verts.size();
                    r.delta = w.delta;
                    r.queries = runs[m].ns.size();
                    r.checked = ex.index.size();
                    r.median_ns = percentile(runs[m].ns, 0.5);
                    r.p90_ns = percentile(runs[m].ns, 0.9);
                    r.max_rel_err = max_rel_err(runs[m], ex);
                    r.stream_ns = runs[m].stream_ns;
                    rows.push_back(r);
                    char delta[32] = "-";
                    if (w.warm) std::snprintf(delta, sizeof delta, "%g", w.delta);
                    std::printf("%-16s %-9s %7zu %-12s %7s %11.1f %11.1f %11.1f %10.2e %6.1f\n",
                                r.method.c_str(), r.shape.c_str(), r.n, r.mode.c_str(), delta, r.median_ns,
                                r.p90_ns, r.stream_ns, r.max_rel_err, r.median_ns / px_median);
                }
                const double px_err = max_rel_err(runs[kPx], ex);
                bad += runs[kPx].errors + runs[kPx].intersecting + (px_err > 1e-6 ? 1 : 0);
                for (double d : runs[kPx].dist) bad += !(d > 0 && d < HUGE_VAL);
                std::printf("#   lin-canny: %.2f iterations/query, %llu fallbacks, %llu intersecting, %llu "
                            "errors; fcl-default intersecting %llu; exact on %zu queries (%.1f s), gap/D in "
                            "[%.3f, %.3f]\n",
                            (double)runs[kPx].iterations / (double)runs[kPx].ns.size(),
                            (unsigned long long)runs[kPx].fallbacks,
                            (unsigned long long)runs[kPx].intersecting, (unsigned long long)runs[kPx].errors,
                            (unsigned long long)runs[kFclDefault].intersecting, ex.index.size(), ex.seconds,
                            ex.min_gap, ex.max_gap);
                std::fflush(stdout);
            }
        }
    }
    if (write_csv(opt.out + "/convex.csv", rows)) return 1;
    std::printf("# wrote %s/convex.csv\n", opt.out.c_str());
    if (bad) {
        std::fprintf(stderr,
                     "bench_convex: %llu lin-canny answers were errors, NaN, reported intersecting on "
                     "disjoint bodies, or off by more than 1e-6 relative\n",
                     bad);
        return 3;
    }
    return 0;
}
