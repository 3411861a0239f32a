// bench_models: px_model against FCL's BVHModel<OBBRSS> on real meshes
// (issue 9 section 6). One run, same process, same poses:
//
//   pairs   bunny00 vs elephant, armadillo vs bunny00 (CGAL sample meshes),
//           Puma 560 link2 vs link4 (read by px_mesh_load); every mesh scaled to a bounding-box
//           diagonal of 1 and centred
//   motion  B approaches A (A at the identity) along a straight line from
//           0.30 before first contact to 0.03 past it in 200 poses, turning
//           about a fixed axis by 1 rad per unit travelled (0.1 degree per
//           pose)
//   methods proxima triangle leaves (PX_PIECES_TRIANGLES, exact), proxima
//           part hulls (PX_PIECES_PARTS, a bracket), FCL 0.7
//           BVHModel<OBBRSS> on the original triangles (fcl::distance with
//           rel_err = abs_err = 0, fcl::collide with one contact)
//   timing  every query timed alone (clock_gettime); proxima's caches warm
//           along the sequence (released before each pass), FCL as it is;
//           `passes` runs of the sequence, per pose the median over passes,
//           then the median and p90 over poses
//   memory  proxima: px_model_get_info's memory_bytes of A and B, and the
//           caches' memory_bytes after the sequence; FCL: its BV nodes
//           (getNumBVs() x sizeof(BVNode<OBBRSS>)), triangles, vertices and
//           primitive indices (rm::fcl_memory_bytes)
//   errors  triangle leaves: max |d - d_FCL| / d_FCL over poses with
//           d_FCL > 0 (both 0 counts as 0); part hulls: whether d_FCL lies in
//           [distance, upper_bound] on every pose, and the worst distance of
//           the bracket's ends from d_FCL
// plus the build of a triangle tree over a 100,000-triangle mesh (bunny00
// with edges split, still closed). Writes models.csv, models_poses.csv and
// models.md into --out; plot_models.gp draws models_approach.png.
//
//   bench_models --meshes DIR --models DIR --out DIR [--passes N] [--quick] [--only NAME]
// --quick: the Puma pair only, 40 poses, one pass, no 100k build (the smoke
// test). --only NAME: the pairs whose name contains NAME (bunny00-elephant,
// armadillo-bunny00, puma-link2-link4), no 100k build.
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/detail/traversal/collision/mesh_collision_traversal_node.h>
#include <fcl/narrowphase/detail/traversal/collision_node.h>
#include <fcl/narrowphase/detail/traversal/distance/mesh_distance_traversal_node.h>
#include <fcl/narrowphase/distance.h>

#include <unistd.h>

#include "bench_common.h"
#include "real_meshes.h"

namespace {

using bench::now_ns;
using bench::percentile;
using rm::Mesh;

struct Body {
    Mesh mesh;
    rm::MeshPtr px_mesh;
    rm::ModelPtr tri, parts;
    std::shared_ptr<rm::FclModel> fcl;
    double build_tri_s = 0, build_parts_s = 0, build_fcl_s = 0;
    size_t tri_bytes = 0, parts_bytes = 0, fcl_bytes = 0;
    uint32_t tri_leaves = 0, parts_leaves = 0;
    double radius = 0;
};

bool build_body(Body *b) {
    std::string err;
    b->px_mesh = rm::make_px_mesh(b->mesh, &err);
    if (!b->px_mesh) return fprintf(stderr, "%s: %s\n", b->mesh.name.c_str(), err.c_str()), false;
    double t0 = now_ns();
    b->tri = rm::make_model(b->px_mesh.get(), PX_PIECES_TRIANGLES, &err);
    b->build_tri_s = (now_ns() - t0) * 1e-9;
    if (!b->tri) return fprintf(stderr, "%s: %s\n", b->mesh.name.c_str(), err.c_str()), false;
    t0 = now_ns();
    b->parts = rm::make_model(b->px_mesh.get(), PX_PIECES_PARTS, &err);
    b->build_parts_s = (now_ns() - t0) * 1e-9;
    if (!b->parts) return fprintf(stderr, "%s (parts): %s\n", b->mesh.name.c_str(), err.c_str()), false;
    t0 = now_ns();
    b->fcl = rm::make_fcl(b->mesh);
    b->build_fcl_s = (now_ns() - t0) * 1e-9;
    px_model_info info;
    px_model_get_info(b->tri.get(), &info);
    b->tri_bytes = info.memory_bytes;
    b->tri_leaves = info.leaves;
    px_model_get_info(b->parts.get(), &info);
    b->parts_bytes = info.memory_bytes;
    b->parts_leaves = info.leaves;
    b->fcl_bytes = rm::fcl_memory_bytes(*b->fcl);
    b->radius = rm::max_radius(b->mesh);
    fprintf(stderr, "  %s: %zu triangles, %zu parts; build: triangles %.3f s, parts %.3f s, FCL %.3f s\n",
            b->mesh.name.c_str(), b->mesh.nt(), b->mesh.parts(), b->build_tri_s, b->build_parts_s,
            b->build_fcl_s);
    return true;
}

fcl::DistanceRequestd exact_request() {
    fcl::DistanceRequestd req;
    req.enable_nearest_points = true;
    req.rel_err = 0.0;
    req.abs_err = 0.0;
    req.distance_tolerance = 0.0;
    return req;
}

// FCL's traversal counts for one query (the same traversal fcl::distance and
// fcl::collide run for two OBBRSS meshes, with statistics on).
void fcl_counts(const Body &a, const fcl::Transform3d &ta, const Body &b, const fcl::Transform3d &tb,
                double *bv_d, double *leaf_d, double *bv_c, double *leaf_c) {
    {
        fcl::DistanceResultd res;
        fcl::detail::MeshDistanceTraversalNodeOBBRSS<double> node;
        fcl::detail::initialize(node, *a.fcl, ta, *b.fcl, tb, exact_request(), res);
        node.enable_statistics = true;
        fcl::detail::distance(&node, nullptr, 2);
        *bv_d += node.num_bv_tests;
        *leaf_d += node.num_leaf_tests;
    }
    {
        fcl::CollisionRequestd req;
        fcl::CollisionResultd res;
        fcl::detail::MeshCollisionTraversalNodeOBBRSS<double> node;
        fcl::detail::initialize(node, *a.fcl, ta, *b.fcl, tb, req, res);
        node.enable_statistics = true;
        fcl::detail::collide(&node, nullptr);
        *bv_c += node.num_bv_tests;
        *leaf_c += node.num_leaf_tests;
    }
}

enum { PX_TRI_D, PX_TRI_C, PX_PART_D, PX_PART_C, FCL_D, FCL_C, N_SERIES };
const char *series_method[N_SERIES] = {"proxima-triangles", "proxima-triangles", "proxima-parts",
                                       "proxima-parts",     "fcl-obbrss",        "fcl-obbrss"};
const char *series_query[N_SERIES] = {"distance", "collide", "distance", "collide", "distance", "collide"};

struct Row {
    std::string method, pair, leaves, query;
    double median_ns = NAN, p90_ns = NAN, max_rel_err = NAN, max_abs_err = NAN;
    int bracket_ok = -1; // part hulls: 1 when every pose is bracketed
    double agree = NAN;  // collide: fraction of poses agreeing with FCL
    size_t memory_bytes = 0, cache_bytes = 0;
    double build_s = NAN;
    double node_pairs = NAN, leaf_pairs = NAN; // per query (FCL: BV tests, leaf tests)
};

struct PairResult {
    std::string pair;
    std::vector<Row> rows;
    std::vector<double> s_rel, d_fcl;
    std::vector<double> t[N_SERIES];
};

PairResult run_pair(const std::string &name, const Body &a, const Body &b, int n, int passes, uint64_t seed) {
    PairResult out;
    out.pair = name;
    // The line and the turn: fixed pseudo-random unit vectors per pair.
    pg_sm rng = {seed};
    const bench::V3 dir = pg_sm_unit(&rng), axis = pg_sm_unit(&rng);
    rm::Approach ap;
    ap.dir[0] = dir.x, ap.dir[1] = dir.y, ap.dir[2] = dir.z;
    ap.axis[0] = axis.x, ap.axis[1] = axis.y, ap.axis[2] = axis.z;
    ap.rate = 1.0;
    ap.radius_b = b.radius;
    const double s0 = -(a.radius + b.radius) - 0.05;
    const double sc = rm::first_contact(a.tri.get(), b.tri.get(), ap, s0, 0.0);
    if (!std::isfinite(sc)) {
        fprintf(stderr, "%s: no contact along the line\n", name.c_str());
        return out;
    }
    std::vector<px_pose> px_b(n);
    std::vector<fcl::Transform3d, Eigen::aligned_allocator<fcl::Transform3d>> fcl_b(n);
    for (int i = 0; i < n; ++i) {
        const double s = sc - 0.30 + 0.33 * i / (n - 1);
        double r[9], t[3];
        ap.pose_at(s, r, t);
        px_b[i] = rm::to_px(r, t);
        fcl_b[i] = rm::to_fcl(r, t);
        out.s_rel.push_back(s - sc);
    }
    const px_pose pa = px_pose_identity();
    const fcl::Transform3d ta = fcl::Transform3d::Identity();

    // Answers (first pass) and times (every pass).
    std::vector<std::vector<double>> times(N_SERIES, std::vector<double>((size_t)n * passes));
    std::vector<double> d_tri(n), d_part(n), ub_part(n);
    std::vector<int> c_tri(n), c_part(n), c_fcl(n), contained(n);
    out.d_fcl.assign(n, 0);
    double np_d = 0, lp_d = 0, np_c = 0, lp_c = 0, npp_d = 0, lpp_d = 0, npp_c = 0, lpp_c = 0;
    size_t cache_tri = 0, cache_part = 0;
    const auto freq = exact_request();
    for (int pass = 0; pass < passes; ++pass) {
        px_model_cache ctd{}, ctc{}, cpd{}, cpc{};
        for (int i = 0; i < n; ++i) {
            const px_pose &pb = px_b[i];
            px_model_distance_result rd;
            px_model_collide_result rc;
            double t0 = now_ns();
            px_model_distance(a.tri.get(), &pa, b.tri.get(), &pb, &ctd, &rd);
            double t1 = now_ns();
            px_model_collide(a.tri.get(), &pa, b.tri.get(), &pb, &ctc, &rc);
            double t2 = now_ns();
            times[PX_TRI_D][(size_t)pass * n + i] = t1 - t0;
            times[PX_TRI_C][(size_t)pass * n + i] = t2 - t1;
            if (pass == 0) {
                d_tri[i] = rd.distance, c_tri[i] = rc.hit, contained[i] = rc.contained;
                np_d += rd.node_pairs, lp_d += rd.leaf_pairs, np_c += rc.node_pairs, lp_c += rc.leaf_pairs;
            }
            px_model_distance_result pd;
            px_model_collide_result pc;
            t0 = now_ns();
            px_model_distance(a.parts.get(), &pa, b.parts.get(), &pb, &cpd, &pd);
            t1 = now_ns();
            px_model_collide(a.parts.get(), &pa, b.parts.get(), &pb, &cpc, &pc);
            t2 = now_ns();
            times[PX_PART_D][(size_t)pass * n + i] = t1 - t0;
            times[PX_PART_C][(size_t)pass * n + i] = t2 - t1;
            if (pass == 0) {
                d_part[i] = pd.distance, ub_part[i] = pd.upper_bound, c_part[i] = pc.hit;
                npp_d += pd.node_pairs, lpp_d += pd.leaf_pairs, npp_c += pc.node_pairs,
                    lpp_c += pc.leaf_pairs;
            }
            fcl::DistanceResultd fd;
            fcl::CollisionRequestd creq;
            fcl::CollisionResultd fc;
            t0 = now_ns();
            fcl::distance(a.fcl.get(), ta, b.fcl.get(), fcl_b[i], freq, fd);
            t1 = now_ns();
            fcl::collide(a.fcl.get(), ta, b.fcl.get(), fcl_b[i], creq, fc);
            t2 = now_ns();
            times[FCL_D][(size_t)pass * n + i] = t1 - t0;
            times[FCL_C][(size_t)pass * n + i] = t2 - t1;
            if (pass == 0) out.d_fcl[i] = fd.min_distance, c_fcl[i] = fc.isCollision();
        }
        cache_tri = ctd.memory_bytes + ctc.memory_bytes;
        cache_part = cpd.memory_bytes + cpc.memory_bytes;
        px_model_cache_release(&ctd);
        px_model_cache_release(&ctc);
        px_model_cache_release(&cpd);
        px_model_cache_release(&cpc);
    }
    double fbv_d = 0, flf_d = 0, fbv_c = 0, flf_c = 0;
    for (int i = 0; i < n; ++i) fcl_counts(a, ta, b, fcl_b[i], &fbv_d, &flf_d, &fbv_c, &flf_c);

    // Per pose: the median over passes.
    for (int k = 0; k < N_SERIES; ++k) {
        out.t[k].resize(n);
        for (int i = 0; i < n; ++i) {
            std::vector<double> v;
            for (int p = 0; p < passes; ++p) v.push_back(times[k][(size_t)p * n + i]);
            out.t[k][i] = percentile(v, 0.5);
        }
    }
    // Errors and agreement.
    double rel_tri = 0, abs_tri = 0, abs_part = 0, rel_part = 0;
    int bracketed = 1, agree_tri = 0, agree_part = 0, n_contained = 0;
    for (int i = 0; i < n; ++i) {
        const double df = out.d_fcl[i];
        const double e = std::fabs(d_tri[i] - df);
        abs_tri = std::max(abs_tri, e);
        if (df > 0)
            rel_tri = std::max(rel_tri, e / df);
        else if (e > 0)
            rel_tri = HUGE_VAL;
        const double slack = 1e-12 + 1e-9 * df;
        if (!(d_part[i] <= df + slack && df <= ub_part[i] + slack)) bracketed = 0;
        const double w = std::max(std::fabs(df - d_part[i]), std::fabs(ub_part[i] - df));
        abs_part = std::max(abs_part, w);
        if (df > 0) rel_part = std::max(rel_part, w / df);
        agree_tri += c_tri[i] == c_fcl[i];
        agree_part += c_part[i] == c_fcl[i];
        n_contained += contained[i];
    }
    if (n_contained)
        fprintf(stderr, "  %s: %d poses contained (FCL misses those)\n", name.c_str(), n_contained);

    char leaves_tri[64], leaves_part[64];
    snprintf(leaves_tri, sizeof leaves_tri, "%u+%u", a.tri_leaves, b.tri_leaves);
    snprintf(leaves_part, sizeof leaves_part, "%u+%u", a.parts_leaves, b.parts_leaves);
    for (int k = 0; k < N_SERIES; ++k) {
        Row r;
        r.method = series_method[k];
        r.pair = name;
        r.query = series_query[k];
        r.median_ns = percentile(out.t[k], 0.5);
        r.p90_ns = percentile(out.t[k], 0.9);
        const bool dist = k == PX_TRI_D || k == PX_PART_D || k == FCL_D;
        if (k == PX_TRI_D || k == PX_TRI_C) {
            r.leaves = leaves_tri;
            r.memory_bytes = a.tri_bytes + b.tri_bytes;
            r.cache_bytes = cache_tri;
            r.build_s = a.build_tri_s + b.build_tri_s;
            if (dist)
                r.max_rel_err = rel_tri, r.max_abs_err = abs_tri, r.bracket_ok = 1;
            else
                r.agree = (double)agree_tri / n;
            r.node_pairs = (dist ? np_d : np_c) / n;
            r.leaf_pairs = (dist ? lp_d : lp_c) / n;
        } else if (k == PX_PART_D || k == PX_PART_C) {
            r.leaves = leaves_part;
            r.memory_bytes = a.parts_bytes + b.parts_bytes;
            r.cache_bytes = cache_part;
            r.build_s = a.build_parts_s + b.build_parts_s;
            if (dist)
                r.max_rel_err = rel_part, r.max_abs_err = abs_part, r.bracket_ok = bracketed;
            else
                r.agree = (double)agree_part / n;
            r.node_pairs = (dist ? npp_d : npp_c) / n;
            r.leaf_pairs = (dist ? lpp_d : lpp_c) / n;
        } else {
            r.leaves = std::to_string(a.mesh.nt()) + "+" + std::to_string(b.mesh.nt());
            r.memory_bytes = a.fcl_bytes + b.fcl_bytes;
            r.build_s = a.build_fcl_s + b.build_fcl_s;
            if (dist)
                r.max_rel_err = 0, r.max_abs_err = 0, r.bracket_ok = 1;
            else
                r.agree = 1;
            r.node_pairs = (dist ? fbv_d : fbv_c) / n;
            r.leaf_pairs = (dist ? flf_d : flf_c) / n;
        }
        out.rows.push_back(r);
    }
    return out;
}

// bunny00 with edges split until it has `target` triangles: repeatedly the
// longest edge whose two triangles are both unsplit, each of the two
// triangles becoming two (the mesh stays closed and conforming).
Mesh split_to(const Mesh &m, size_t target) {
    Mesh out = m;
    std::map<std::pair<uint32_t, uint32_t>, std::vector<uint32_t>> edges;
    const size_t nt = m.nt();
    for (size_t t = 0; t < nt; ++t)
        for (int k = 0; k < 3; ++k) {
            uint32_t u = m.tri[3 * t + k], v = m.tri[3 * t + (k + 1) % 3];
            edges[{std::min(u, v), std::max(u, v)}].push_back((uint32_t)t);
        }
    struct E {
        double len;
        uint32_t u, v, t0, t1;
    };
    std::vector<E> list;
    for (auto &e : edges) {
        if (e.second.size() != 2) continue;
        const double *p = &m.xyz[3 * e.first.first], *q = &m.xyz[3 * e.first.second];
        const double l =
            (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]);
        list.push_back({l, e.first.first, e.first.second, e.second[0], e.second[1]});
    }
    std::sort(list.begin(), list.end(), [](const E &x, const E &y) { return x.len > y.len; });
    std::vector<char> used(nt, 0);
    for (const E &e : list) {
        if (out.nt() >= target) break;
        if (used[e.t0] || used[e.t1]) continue;
        used[e.t0] = used[e.t1] = 1;
        const uint32_t mid = (uint32_t)out.nv();
        for (int k = 0; k < 3; ++k) out.xyz.push_back(0.5 * (m.xyz[3 * e.u + k] + m.xyz[3 * e.v + k]));
        for (uint32_t t : {e.t0, e.t1}) {
            uint32_t c[3] = {out.tri[3 * t], out.tri[3 * t + 1], out.tri[3 * t + 2]};
            int k = 0; // the corner where the edge starts, in this triangle's order
            while (!((c[k] == e.u && c[(k + 1) % 3] == e.v) || (c[k] == e.v && c[(k + 1) % 3] == e.u))) ++k;
            const uint32_t p0 = c[k], p1 = c[(k + 1) % 3], p2 = c[(k + 2) % 3];
            out.tri[3 * t] = p0, out.tri[3 * t + 1] = mid, out.tri[3 * t + 2] = p2;
            out.tri.insert(out.tri.end(), {mid, p1, p2});
        }
    }
    out.part_tri = {0, (uint32_t)out.nt()};
    out.part_vtx = {0, (uint32_t)out.nv()};
    out.name = m.name + "-split";
    return out;
}

std::string csv_num(double v, const char *fmt = "%.6g") {
    if (!(v == v)) return "";
    if (v == HUGE_VAL) return "inf";
    char b[64];
    snprintf(b, sizeof b, fmt, v);
    return b;
}

// The error cell of models.md: relative for exact leaves, the bracket's
// reach for part hulls.
std::string err_cell(const Row &r) {
    if (!(r.max_rel_err == r.max_rel_err)) return "";
    if (r.method == "proxima-parts") return "bracket ends ≤ " + csv_num(r.max_abs_err, "%.3f") + " away";
    return "rel " + bench::fmt_err(r.max_rel_err);
}

} // namespace

int main(int argc, char **argv) {
    std::string meshes = "build/meshdata", models = "models", out_dir = "docs/bench";
    int passes = 5, n = 200;
    bool quick = false;
    std::string only; // --only NAME: the pairs whose name contains NAME, no 100k build
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        if (a == "--meshes" && i + 1 < argc)
            meshes = argv[++i];
        else if (a == "--models" && i + 1 < argc)
            models = argv[++i];
        else if (a == "--out" && i + 1 < argc)
            out_dir = argv[++i];
        else if (a == "--passes" && i + 1 < argc)
            passes = std::max(1, atoi(argv[++i]));
        else if (a == "--quick")
            quick = true;
        else if (a == "--only" && i + 1 < argc)
            only = argv[++i];
        else {
            fprintf(stderr, "usage: bench_models [--meshes DIR] [--models DIR] [--out DIR] [--passes N] "
                            "[--quick] [--only NAME]\n");
            return 2;
        }
    }
    if (quick) passes = 1, n = 40;

    double load0 = NAN;
    if (FILE *l = fopen("/proc/loadavg", "r")) {
        if (fscanf(l, "%lf", &load0) != 1) load0 = NAN;
        fclose(l);
    }
    std::vector<PairResult> results;
    std::vector<std::string> notes;
    auto load_cgal = [&](const char *file, Body *b) {
        std::string err;
        if (!rm::load_cgal_mesh(file, &b->mesh, &err, meshes)) {
            fprintf(stderr, "bench_models: %s\n", err.c_str());
            return false;
        }
        rm::normalize(&b->mesh, 1.0);
        return true;
    };
    auto want = [&](const char *pair) {
        return only.empty() || std::string(pair).find(only) != std::string::npos;
    };
    if (!quick && (want("bunny00-elephant") || want("armadillo-bunny00"))) {
        Body bunny, elephant, armadillo;
        fprintf(stderr, "building the CGAL meshes\n");
        if (load_cgal("bunny00.off", &bunny) && load_cgal("elephant.off", &elephant) &&
            load_cgal("armadillo.off", &armadillo) && build_body(&bunny) && build_body(&elephant) &&
            build_body(&armadillo)) {
            if (want("bunny00-elephant")) {
                fprintf(stderr, "bunny00 vs elephant\n");
                results.push_back(run_pair("bunny00-elephant", bunny, elephant, n, passes, 11));
            }
            if (want("armadillo-bunny00")) {
                fprintf(stderr, "armadillo vs bunny00\n");
                results.push_back(run_pair("armadillo-bunny00", armadillo, bunny, n, passes, 12));
            }
        } else {
            notes.push_back("The CGAL meshes were not found (run `make deps`): their pairs are missing.");
        }
    }
    if (want("puma-link2-link4")) {
        Body l2, l4;
        const std::string dir = models + "/puma560/nimasarli_puma560_description/meshes/";
        std::string err;
        if (rm::load_with_px(dir + "puma_link2.stl", &l2.mesh, &err) &&
            rm::load_with_px(dir + "puma_link4.stl", &l4.mesh, &err)) {
            rm::normalize(&l2.mesh, 1.0);
            rm::normalize(&l4.mesh, 1.0);
            fprintf(stderr, "puma link2 vs link4\n");
            if (build_body(&l2) && build_body(&l4))
                results.push_back(run_pair("puma-link2-link4", l2, l4, n, passes, 13));
        } else {
            fprintf(stderr, "bench_models: %s\n", err.c_str());
        }
    }
    // The 100k-triangle build.
    Row big;
    double big_bytes_per_tri = NAN, big_fcl_s = NAN;
    size_t big_nt = 0, big_fcl_bytes = 0;
    if (!quick && only.empty()) {
        Mesh bunny;
        std::string err;
        if (rm::load_cgal_mesh("bunny00.off", &bunny, &err, meshes)) {
            rm::normalize(&bunny, 1.0);
            Mesh big_mesh = split_to(bunny, 100000);
            big_nt = big_mesh.nt();
            rm::MeshPtr pm = rm::make_px_mesh(big_mesh, &err);
            px_mesh_info mi;
            px_mesh_get_info(pm.get(), &mi);
            fprintf(stderr, "100k build: %zu triangles (%u closed parts)\n", big_nt, mi.closed_parts);
            const double t0 = now_ns();
            rm::ModelPtr mo = rm::make_model(pm.get(), PX_PIECES_TRIANGLES, &err);
            const double s = (now_ns() - t0) * 1e-9;
            const double t1 = now_ns();
            auto fm = rm::make_fcl(big_mesh);
            big_fcl_s = (now_ns() - t1) * 1e-9;
            big_fcl_bytes = rm::fcl_memory_bytes(*fm);
            if (mo) {
                px_model_info info;
                px_model_get_info(mo.get(), &info);
                big.method = "proxima-triangles";
                big.pair = "bunny00-split-100k";
                big.leaves = std::to_string(info.leaves);
                big.query = "build";
                big.build_s = s;
                big.median_ns = s * 1e9;
                big.p90_ns = s * 1e9;
                big.memory_bytes = info.memory_bytes;
                big_bytes_per_tri = (double)info.memory_bytes / (double)info.leaves;
                fprintf(stderr, "  %.2f s, %.0f bytes per triangle (FCL: %.3f s, %.0f bytes per triangle)\n",
                        s, big_bytes_per_tri, big_fcl_s, (double)big_fcl_bytes / (double)big_nt);
            } else {
                fprintf(stderr, "100k build failed: %s\n", err.c_str());
            }
        }
    }

    // models.csv
    const std::string csv = out_dir + "/models.csv";
    FILE *f = fopen(csv.c_str(), "w");
    if (!f) return fprintf(stderr, "cannot write %s\n", csv.c_str()), 1;
    fprintf(f,
            "method,pair,leaves,query,median_ns,p90_ns,max_rel_err,max_abs_err,bracket_ok,agree,memory_bytes,"
            "cache_bytes,build_s,node_pairs,leaf_pairs\n");
    auto put = [&](const Row &r) {
        fprintf(f, "%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%zu,%zu,%s,%s,%s\n", r.method.c_str(), r.pair.c_str(),
                r.leaves.c_str(), r.query.c_str(), csv_num(r.median_ns, "%.0f").c_str(),
                csv_num(r.p90_ns, "%.0f").c_str(), csv_num(r.max_rel_err, "%.3g").c_str(),
                csv_num(r.max_abs_err, "%.3g").c_str(),
                r.bracket_ok < 0 ? "" : std::to_string(r.bracket_ok).c_str(),
                csv_num(r.agree, "%.3f").c_str(), r.memory_bytes, r.cache_bytes,
                csv_num(r.build_s, "%.4f").c_str(), csv_num(r.node_pairs, "%.1f").c_str(),
                csv_num(r.leaf_pairs, "%.1f").c_str());
    };
    for (auto &p : results)
        for (auto &r : p.rows) put(r);
    if (!big.method.empty()) put(big);
    fclose(f);

    // models_poses.csv (the plot's data)
    const std::string pcsv = out_dir + "/models_poses.csv";
    f = fopen(pcsv.c_str(), "w");
    if (!f) return fprintf(stderr, "cannot write %s\n", pcsv.c_str()), 1;
    fprintf(f, "# pair index, pose, s - s_contact, FCL distance, then per-pose median ns: px_tri_distance "
               "px_tri_collide px_parts_distance px_parts_collide fcl_distance fcl_collide\n");
    for (size_t k = 0; k < results.size(); ++k) {
        const auto &p = results[k];
        for (size_t i = 0; i < p.s_rel.size(); ++i)
            fprintf(f, "%zu %zu %.6f %.9g %.0f %.0f %.0f %.0f %.0f %.0f\n", k, i, p.s_rel[i], p.d_fcl[i],
                    p.t[PX_TRI_D][i], p.t[PX_TRI_C][i], p.t[PX_PART_D][i], p.t[PX_PART_C][i], p.t[FCL_D][i],
                    p.t[FCL_C][i]);
        fprintf(f, "\n\n");
    }
    fclose(f);

    // models.md
    const std::string md = out_dir + "/models.md";
    f = fopen(md.c_str(), "w");
    if (!f) return fprintf(stderr, "cannot write %s\n", md.c_str()), 1;
    fprintf(f, "# px_model against FCL's BVHModel<OBBRSS> on real meshes\n\n");
    fprintf(
        f,
        "Written by `bench/bench_models.cpp` (`make bench`; the method is in its header comment). %d poses "
        "per pair, B approaching A from 0.30 before first contact to 0.03 past it, turning 0.1 degree per "
        "pose; every query timed alone, per pose the median of %d passes, then the median and p90 over "
        "poses. proxima's caches are warm along the sequence; FCL runs as it is. Meshes scaled to a "
        "bounding-box diagonal of 1. Machine: %s (%.2f at the start; other work shared the machine, so "
        "absolute times carry its noise, ratios less so).\n\n",
        n, passes, bench::machine_line().c_str(), load0);
    for (auto &nt : notes) fprintf(f, "%s\n\n", nt.c_str());
    fprintf(f,
            "| pair | method | leaves | query | median µs | p90 µs | error vs FCL's distance | bracket ok | "
            "agrees "
            "with FCL | node pairs / query | leaf pairs / query | model bytes | cache bytes | build s |\n");
    fprintf(f, "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (auto &p : results)
        for (auto &r : p.rows)
            fprintf(f, "| %s | %s | %s | %s | %s | %s | %s | %s | %s | %.0f | %.0f | %zu | %zu | %.3f |\n",
                    r.pair.c_str(), r.method.c_str(), r.leaves.c_str(), r.query.c_str(),
                    bench::fmt_us(r.median_ns).c_str(), bench::fmt_us(r.p90_ns).c_str(), err_cell(r).c_str(),
                    r.bracket_ok < 0 ? "" : (r.bracket_ok ? "yes" : "**no**"),
                    r.agree == r.agree ? csv_num(100 * r.agree, "%.1f%%").c_str() : "", r.node_pairs,
                    r.leaf_pairs, r.memory_bytes, r.cache_bytes, r.build_s);
    fprintf(
        f,
        "\nErrors: triangle leaves, the largest |d - d_FCL| / d_FCL over the poses (FCL asked for exact "
        "answers: rel_err = abs_err = 0); part hulls, the largest distance from d_FCL to either end of the "
        "bracket [distance, upper_bound] (absolute, diagonal 1), and whether d_FCL lay inside it on every "
        "pose. "
        "FCL's node pairs are its BV tests and its leaf pairs its triangle tests (the same traversal with "
        "statistics on). FCL memory: BV nodes (getNumBVs() × sizeof(BVNode<OBBRSS>) = %zu bytes each), "
        "triangles (%zu bytes), vertices (%zu bytes), one primitive index per triangle (%zu bytes), and "
        "the BVHModel object (%zu bytes). The part-hull collide answers whether the hulls intersect, so "
        "it disagrees with the meshes' answer wherever the hulls overlap and the meshes do not.\n\n",
        sizeof(fcl::BVNode<fcl::OBBRSSd>), sizeof(fcl::Triangle), sizeof(fcl::Vector3d), sizeof(unsigned int),
        sizeof(rm::FclModel));

    // Targets.
    fprintf(f, "## Targets (issue 9)\n\n| target | pair | measured | met |\n|---|---|---|---|\n");
    for (auto &p : results) {
        const Row *rows = p.rows.data();
        if (p.rows.size() < N_SERIES) continue;
        const double sd = rows[FCL_D].median_ns / rows[PX_TRI_D].median_ns;
        const double sc = rows[FCL_C].median_ns / rows[PX_TRI_C].median_ns;
        fprintf(
            f, "| exact distance ≥ 10× faster than FCL (median per pose) | %s | %.2f× (%s vs %s µs) | %s |\n",
            p.pair.c_str(), sd, bench::fmt_us(rows[PX_TRI_D].median_ns).c_str(),
            bench::fmt_us(rows[FCL_D].median_ns).c_str(), sd >= 10 ? "yes" : "**no**");
        fprintf(f, "| exact distance identical to FCL's to 1e-9 | %s | max rel err %s | %s |\n",
                p.pair.c_str(), bench::fmt_err(rows[PX_TRI_D].max_rel_err).c_str(),
                rows[PX_TRI_D].max_rel_err <= 1e-9 ? "yes" : "**no**");
        fprintf(f, "| collide ≥ 4× faster than FCL (median per pose) | %s | %.2f× (%s vs %s µs) | %s |\n",
                p.pair.c_str(), sc, bench::fmt_us(rows[PX_TRI_C].median_ns).c_str(),
                bench::fmt_us(rows[FCL_C].median_ns).c_str(), sc >= 4 ? "yes" : "**no**");
        fprintf(f, "| part-hull distance ≤ 10 µs per pose (median; p90) | %s | %s; %s µs | %s |\n",
                p.pair.c_str(), bench::fmt_us(rows[PX_PART_D].median_ns).c_str(),
                bench::fmt_us(rows[PX_PART_D].p90_ns).c_str(),
                rows[PX_PART_D].median_ns <= 10000 ? "yes" : "**no**");
    }
    if (!big.method.empty()) {
        fprintf(f, "| 100k-triangle build ≤ 10 s | %s (%zu triangles) | %.2f s (FCL: %.3f s) | %s |\n",
                big.pair.c_str(), big_nt, big.build_s, big_fcl_s, big.build_s <= 10 ? "yes" : "**no**");
        fprintf(
            f,
            "| 100k-triangle model ≤ 1 KB per triangle | %s | %.0f bytes per triangle (FCL: %.0f) | %s |\n",
            big.pair.c_str(), big_bytes_per_tri, (double)big_fcl_bytes / (double)big_nt,
            big_bytes_per_tri <= 1024 ? "yes" : "**no**");
    }
    fprintf(f, "\n![time per pose along the approach](models_approach.png)\n");
    fclose(f);
    fprintf(stderr, "wrote %s, %s, %s\n", csv.c_str(), pcsv.c_str(), md.c_str());
    return 0;
}
