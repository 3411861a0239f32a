// bench_hybrid: the timing experiments of seed 001, section 6 (the
// Lin-Canny/GJK hybrid paper, Figures 1-3), on proxima's three distance
// methods (px_distance: lin-canny, gjk, hybrid), with FCL 0.7's GJK
// (fcl::distance, libccd, tolerance 1e-9; it keeps no state) as a reference.
//
//   (a) "translation": random convex polyhedra of increasing vertex count
//       (n points uniformly at random on the unit sphere: every point is a
//       hull vertex), one at the origin, the other (a second random
//       polyhedron of the same size) moved through 10^4 small translations:
//       its centre travels once around a circle of radius 3 about A (step
//       2 pi 3 / 10^4 ~ 0.0019, i.e. 0.09 % of the diameter), so the gap stays
//       ~1. Each method runs the whole path with tracking (one cache carried
//       from query to query) and without (NULL cache: every query cold).
//       Reported: the total time of the 10^4 queries and the mean per query.
//   (b) "rotation": two 50-point random polyhedra, centres 3 apart; B turns
//       about a fixed random axis through its centre for 10^4 steps at
//       several rotational speeds (degrees per step), tracking on.
//
// Each path is run `--repeat` times (default 3) per method and the fastest
// total is kept (the machine is shared). Errors: every answer is compared
// with lin-canny's on the same pose (max |d - d_lc| / d_lc).
// Output: DIR/hybrid.csv, DIR/hybrid.md; plots by docs/bench/plot_hybrid.gp.
//
// Usage: bench_hybrid [--out DIR] [--quick] [--sizes LIST] [--speeds LIST]
//                     [--steps K] [--repeat K] [--seed S]

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <fcl/geometry/shape/convex.h>
#include <fcl/narrowphase/distance.h>

#include "bench_common.h"
#include "proxima/proxima.h"

namespace {

using namespace bench;

struct Poly {
    px_convex *cx = nullptr;
    std::shared_ptr<fcl::Convexd> fcl;
    size_t n = 0; // hull vertices
    ~Poly() { px_convex_destroy(cx); }
};

// n points uniformly at random on the unit sphere.
std::unique_ptr<Poly> random_poly(pg_sm &rng, size_t n) {
    std::vector<double> xyz(3 * n);
    pg_sm_points_sphere(&rng, n, 1.0, xyz.data());
    std::unique_ptr<Poly> p(new Poly);
    px_error err;
    p->cx = px_convex_create(xyz.data(), n, nullptr, &err);
    if (!p->cx) {
        std::fprintf(stderr, "bench_hybrid: px_convex_create(%zu) failed: %s\n", n, err.message);
        return nullptr;
    }
    const uint32_t nv = px_convex_vertex_count(p->cx), nf = px_convex_face_count(p->cx);
    p->n = nv;
    auto fv = std::make_shared<std::vector<fcl::Vector3d>>(nv);
    for (uint32_t i = 0; i < nv; ++i) {
        const px_vec3 v = ta_vertex(p->cx, i);
        (*fv)[i] = fcl::Vector3d(v.x, v.y, v.z);
    }
    auto ff = std::make_shared<std::vector<int>>();
    for (uint32_t f = 0; f < nf; ++f) {
        const uint32_t k = ta_face_size(p->cx, f);
        ff->push_back((int)k);
        for (uint32_t j = 0; j < k; ++j) ff->push_back((int)ta_face_vertex(p->cx, f, j));
    }
    p->fcl = std::make_shared<fcl::Convexd>(fv, (int)nf, ff, false);
    p->fcl->computeLocalAABB();
    return p;
}

fcl::Transform3d to_fcl(const px_pose &p) {
    fcl::Transform3d tf = fcl::Transform3d::Identity();
    fcl::Matrix3d r;
    r << p.r[0], p.r[1], p.r[2], p.r[3], p.r[4], p.r[5], p.r[6], p.r[7], p.r[8];
    tf.linear() = r;
    tf.translation() = fcl::Vector3d(p.t.x, p.t.y, p.t.z);
    return tf;
}

const char *const kMethods[] = {"lin-canny", "gjk", "hybrid", "fcl-gjk-libccd"};
const int kMethodCount = 4;

struct Result {
    double total_ms = NAN; // fastest of the repeats
    double max_rel_err = 0;
    uint64_t errors = 0;
};

// Runs method m over the path (A fixed at pa, B at pb[k]); `tracking` carries
// one cache along the path, otherwise every query gets NULL. FCL keeps no
// state, so it runs without tracking only. `dist` receives the answers.
Result run_path(const Poly &a, const Poly &b, const px_pose &pa, const std::vector<px_pose> &pb, int m,
                bool tracking, int repeat, std::vector<double> &dist) {
    Result r;
    dist.assign(pb.size(), NAN);
    const fcl::Transform3d ta = to_fcl(pa);
    std::vector<fcl::Transform3d> tb;
    if (m == 3)
        for (const px_pose &p : pb) tb.push_back(to_fcl(p));
    fcl::DistanceRequestd req;
    req.gjk_solver_type = fcl::GST_LIBCCD;
    req.distance_tolerance = 1e-9;
    px_query_options opt;
    std::memset(&opt, 0, sizeof opt);
    opt.method = m == 1 ? PX_METHOD_GJK : m == 2 ? PX_METHOD_HYBRID : PX_METHOD_LIN_CANNY;
    for (int rep = 0; rep < repeat; ++rep) {
        px_pair_cache cache;
        std::memset(&cache, 0, sizeof cache);
        px_pair_cache *c = tracking ? &cache : nullptr;
        px_distance_result res;
        const double t0 = now_ns();
        if (m == 3) {
            for (size_t k = 0; k < pb.size(); ++k) {
                fcl::DistanceResultd fr;
                fcl::distance(a.fcl.get(), ta, b.fcl.get(), tb[k], req, fr);
                dist[k] = fr.min_distance;
            }
        } else {
            for (size_t k = 0; k < pb.size(); ++k) {
                const px_status st = px_distance(a.cx, &pa, b.cx, &pb[k], &opt, c, &res);
                dist[k] = st == PX_OK ? res.distance : NAN;
            }
        }
        r.total_ms = std::min(r.total_ms == r.total_ms ? r.total_ms : HUGE_VAL, (now_ns() - t0) * 1e-6);
    }
    return r;
}

void compare(Result &r, const std::vector<double> &d, const std::vector<double> &ref) {
    for (size_t k = 0; k < d.size(); ++k) {
        double e = std::fabs(d[k] - ref[k]) / ref[k];
        if (!(e == e)) e = HUGE_VAL, ++r.errors;
        r.max_rel_err = std::max(r.max_rel_err, e);
    }
}

struct Row {
    std::string experiment, method, tracking;
    size_t n = 0, queries = 0;
    double speed_deg = 0, total_ms = NAN, max_rel_err = NAN;
};

// Runs every method (with and without tracking where asked) on one path.
void run_all(const Poly &a, const Poly &b, const px_pose &pa, const std::vector<px_pose> &pb,
             const std::string &experiment, double speed, bool both, int repeat, std::vector<Row> &rows) {
    std::vector<double> ref, d;
    run_path(a, b, pa, pb, 0, true, 1, ref); // lin-canny answers: the comparison
    for (int m = 0; m < kMethodCount; ++m)
        for (int tr = 1; tr >= 0; --tr) {
            if (m == 3 && tr) continue; // FCL keeps no state: cold only, in both experiments
            if (!tr && !both && m != 3) continue;
            Result r = run_path(a, b, pa, pb, m, tr != 0, repeat, d);
            compare(r, d, ref);
            Row row;
            row.experiment = experiment, row.method = kMethods[m], row.tracking = tr ? "warm" : "cold";
            row.n = a.n, row.queries = pb.size(), row.speed_deg = speed;
            row.total_ms = r.total_ms, row.max_rel_err = r.max_rel_err;
            rows.push_back(row);
            std::printf("%-11s %-15s %-5s %6zu %6g %10.2f %9.3f %9.2e\n", experiment.c_str(), kMethods[m],
                        row.tracking.c_str(), row.n, speed, row.total_ms,
                        row.total_ms * 1e3 / (double)row.queries, row.max_rel_err);
            std::fflush(stdout);
        }
}

const Row *find(const std::vector<Row> &rows, const std::string &exp, const std::string &method,
                const std::string &tracking, size_t n, double speed) {
    for (const Row &r : rows)
        if (r.experiment == exp && r.method == method && r.tracking == tracking && r.n == n &&
            r.speed_deg == speed)
            return &r;
    return nullptr;
}

int write_outputs(const std::string &dir, const std::vector<Row> &rows, const std::vector<size_t> &sizes,
                  const std::vector<double> &speeds, size_t steps, const std::string &command) {
    const std::string csv = dir + "/hybrid.csv", md = dir + "/hybrid.md";
    FILE *f = std::fopen(csv.c_str(), "w");
    if (!f) {
        std::fprintf(stderr, "bench_hybrid: cannot write %s: %s\n", csv.c_str(), std::strerror(errno));
        return 1;
    }
    std::fprintf(f, "experiment,method,tracking,n,speed_deg,queries,total_ms,mean_us,max_rel_err\n");
    for (const Row &r : rows)
        std::fprintf(f, "%s,%s,%s,%zu,%g,%zu,%.3f,%.4f,%.3e\n", r.experiment.c_str(), r.method.c_str(),
                     r.tracking.c_str(), r.n, r.speed_deg, r.queries, r.total_ms,
                     r.total_ms * 1e3 / (double)r.queries, r.max_rel_err);
    std::fclose(f);
    f = std::fopen(md.c_str(), "w");
    if (!f) {
        std::fprintf(stderr, "bench_hybrid: cannot write %s: %s\n", md.c_str(), std::strerror(errno));
        return 1;
    }
    std::fprintf(f,
                 "# Seed 001 §6 timing experiments (generated by bench_hybrid)\n\n"
                 "Command: `%s`. See bench/bench_hybrid.cpp for the protocol. Times: the fastest of the "
                 "repeats of the whole path of %zu queries, in ms, with the mean per query in µs in "
                 "parentheses. \"err\": the largest |d − d_lin-canny| / d_lin-canny on the path.\n",
                 command.c_str(), steps);
    std::fprintf(f, "\n## (a) Continuous translation, with (warm) and without (cold) tracking\n\n| n |");
    for (int m = 0; m < kMethodCount; ++m)
        for (const char *tr : {"warm", "cold"})
            if (!(m == 3 && std::string(tr) == "warm")) std::fprintf(f, " %s %s |", kMethods[m], tr);
    std::fprintf(f, "\n|---|");
    for (int m = 0; m < 2 * kMethodCount - 1; ++m) std::fprintf(f, "---|");
    std::fprintf(f, "\n");
    for (size_t n : sizes) {
        const Row *any = nullptr;
        for (const Row &r : rows)
            if (r.experiment == "translation" && r.method == std::string("lin-canny") && r.speed_deg == 0 &&
                r.n >= n * 9 / 10 && r.n <= n)
                any = &r;
        if (!any) continue;
        std::fprintf(f, "| %zu |", any->n);
        for (int m = 0; m < kMethodCount; ++m)
            for (const char *tr : {"warm", "cold"}) {
                if (m == 3 && std::string(tr) == "warm") continue;
                const Row *r = find(rows, "translation", kMethods[m], tr, any->n, 0);
                if (r)
                    std::fprintf(f, " %.2f (%.3f) · %s |", r->total_ms,
                                 r->total_ms * 1e3 / (double)r->queries, fmt_err(r->max_rel_err).c_str());
                else
                    std::fprintf(f, " – |");
            }
        std::fprintf(f, "\n");
    }
    std::fprintf(f, "\n![continuous translation](hybrid_translation.png)\n");
    std::fprintf(f, "\n## (b) Continuous rotation of a 50-point polyhedron, tracking on\n\nMean µs per query "
                    "(err).\n\n| degrees / step |");
    for (int m = 0; m < kMethodCount; ++m) std::fprintf(f, " %s |", kMethods[m]);
    std::fprintf(f, "\n|---|");
    for (int m = 0; m < kMethodCount; ++m) std::fprintf(f, "---|");
    std::fprintf(f, "\n");
    for (double s : speeds) {
        std::fprintf(f, "| %g |", s);
        for (int m = 0; m < kMethodCount; ++m) {
            const Row *r = nullptr;
            for (const Row &x : rows)
                if (x.experiment == "rotation" && x.method == std::string(kMethods[m]) && x.speed_deg == s)
                    r = &x;
            if (r)
                std::fprintf(f, " %.3f (%s) |", r->total_ms * 1e3 / (double)r->queries,
                             fmt_err(r->max_rel_err).c_str());
            else
                std::fprintf(f, " – |");
        }
        std::fprintf(f, "\n");
    }
    std::fprintf(f, "\n![continuous rotation](hybrid_rotation.png)\n");
    std::fclose(f);
    std::printf("# wrote %s and %s\n", csv.c_str(), md.c_str());
    return 0;
}

void usage() {
    std::fprintf(stderr,
                 "usage: bench_hybrid [--out DIR] [--quick] [--sizes LIST] [--speeds LIST] [--steps K]\n"
                 "                    [--repeat K] [--seed S]\n"
                 "  --out DIR      write DIR/hybrid.csv and DIR/hybrid.md (default docs/bench)\n"
                 "  --quick        sizes 50,200, speeds 1,10, 1,000 steps, one repeat (smoke run)\n"
                 "  --sizes LIST   vertex counts for (a) (default 50,100,200,500,1000,2000,5000,10000)\n"
                 "  --speeds LIST  degrees per step for (b) (default 0.5,1,2,5,10,20)\n"
                 "  --steps K      queries per path (default 10000)\n"
                 "  --repeat K     runs per path, the fastest kept (default 3)\n");
}

} // namespace

int main(int argc, char **argv) {
    std::string out = "docs/bench", command = "bench_hybrid";
    for (int i = 1; i < argc; ++i) command += std::string(" ") + argv[i];
    std::vector<size_t> sizes = {50, 100, 200, 500, 1000, 2000, 5000, 10000};
    std::vector<double> speeds = {0.5, 1, 2, 5, 10, 20};
    size_t steps = 10000;
    int repeat = 3;
    uint64_t seed = 1;
    bool quick = false;
    std::vector<size_t> user_sizes;
    std::vector<double> user_speeds;
    size_t user_steps = 0;
    int user_repeat = 0;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--out" && i + 1 < argc)
            out = argv[++i];
        else if (a == "--quick")
            quick = true;
        else if (a == "--sizes" && i + 1 < argc)
            user_sizes = parse_sizes(argv[++i]);
        else if (a == "--speeds" && i + 1 < argc)
            user_speeds = parse_doubles(argv[++i]);
        else if (a == "--steps" && i + 1 < argc)
            user_steps = std::strtoull(argv[++i], nullptr, 10);
        else if (a == "--repeat" && i + 1 < argc)
            user_repeat = std::atoi(argv[++i]);
        else if (a == "--seed" && i + 1 < argc)
            seed = std::strtoull(argv[++i], nullptr, 10);
        else {
            usage();
            return a == "--help" || a == "-h" ? 0 : 2;
        }
    }
    if (quick) sizes = {50, 200}, speeds = {1, 10}, steps = 1000, repeat = 1;
    if (!user_sizes.empty()) sizes = user_sizes;
    if (!user_speeds.empty()) speeds = user_speeds;
    if (user_steps) steps = user_steps;
    if (user_repeat > 0) repeat = user_repeat;

    std::vector<Row> rows;
    std::printf("%-11s %-15s %-5s %6s %6s %10s %9s %9s\n", "experiment", "method", "track", "n", "deg",
                "total_ms", "mean_us", "max_err");
    const double radius = 3.0;
    for (size_t n : sizes) {
        pg_sm rng{seed * 1000003u + n};
        std::unique_ptr<Poly> a = random_poly(rng, n), b = random_poly(rng, n);
        if (!a || !b) return 1;
        const px_pose pa = px_pose_identity();
        std::vector<px_pose> pb(steps);
        double r[9];
        pg_sm_rot_random(&rng, r);
        const V3 axis = pg_sm_unit(&rng), u = pg_sm_perpendicular(&rng, axis), v = cross(axis, u);
        for (size_t k = 0; k < steps; ++k) {
            const V3 c = pg_circle_point(u, v, radius, k, steps);
            const double t[3] = {c.x, c.y, c.z};
            pb[k] = ta_pose_rt(r, t);
        }
        run_all(*a, *b, pa, pb, "translation", 0, true, repeat, rows);
    }
    {
        pg_sm rng{seed * 1000033u};
        std::unique_ptr<Poly> a = random_poly(rng, 50), b = random_poly(rng, 50);
        if (!a || !b) return 1;
        const px_pose pa = px_pose_identity();
        const V3 axis = pg_sm_unit(&rng), c = radius * pg_sm_unit(&rng);
        const double t[3] = {c.x, c.y, c.z};
        for (double s : speeds) {
            double r[9];
            pg_sm_rot_random(&rng, r);
            std::vector<px_pose> pb(steps);
            for (size_t k = 0; k < steps; ++k) {
                pb[k] = ta_pose_rt(r, t);
                pg_rot_turn(axis, s * M_PI / 180, r);
            }
            run_all(*a, *b, pa, pb, "rotation", s, false, repeat, rows);
        }
    }
    return write_outputs(out, rows, sizes, speeds, steps, command);
}
