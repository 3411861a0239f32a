// bench_scene: px_scene against FCL's DynamicAABBTreeCollisionManager and
// brute force all pairs (issue 11 section 5). One run, same process, same
// trajectories:
//
//   scenes  N convex bodies (N = 100, 1,000, 10,000; hulls of 32 random
//           points on the unit sphere, one hull per body, splitmix64 seed
//           per scene) or N models (N = 100, 1,000; one Puma 560 link,
//           PX_PIECES_TRIANGLES, scaled so that its farthest vertex from
//           its bounding-box centre is at 1, like the hulls') in a cubic box
//           at 5 % volume fraction (side = cbrt(total volume / 0.05); the
//           hulls' volumes, the link's closed-mesh volume), random initial
//           positions and rotations (bodies may overlap: no physics)
//   motion  per body a constant velocity (uniform in the ball |v| <= 0.05)
//           and a constant turn about a random world axis through the
//           body's centre (|omega| uniform in [0, 0.05] rad) per step; a
//           centre leaving [0, side] is reflected and that velocity
//           component reversed (bouncing off the walls); time unit = one
//           step; rotations re-orthonormalised every 16 steps
//   margin  0.1: the pairs within 0.1 are the contacts, every method must
//           give them with exact distances
//   methods proxima: px_scene (margin 0.1, report distance = margin, every
//           body declared max_speed 0.05, max_angular_speed 0.05 about its
//           centre); timed: px_scene_set_pose for every body + px_scene_step;
//           once on the calling thread (proxima-scene), once with
//           options.threads = 2 (proxima-scene-2t)
//           FCL 0.7: DynamicAABBTreeCollisionManager over one
//           CollisionObject per body (fcl::Convexd per hull,
//           BVHModel<OBBRSS> of the link shared by the models); timed:
//           setTransform + computeAABB + the box inflated by margin / 2 on
//           every side for every object, update(), then collide() on the
//           manager with a callback that runs fcl::distance (nearest points
//           on; models: rel_err = abs_err = 0) on every pair the broad phase
//           reports and keeps those within the margin (FCL's manager ignores
//           margins: the inflated boxes are how a user gets every pair
//           within 0.1)
//           brute force: px_distance / px_model_distance (cold) on all
//           N (N - 1) / 2 pairs; timed on a subset of the timed steps: the
//           first, then as many more, evenly spaced, as fit in --bf-seconds
//           (20) at the first one's cost
//   check   every step (warm-up included): proxima's contact set (pairs
//           reported with contact = 1) and FCL's (fcl::distance <= margin)
//           against the reference: every pair whose bounding spheres are
//           within the margin (a sweep over x) measured by px_distance /
//           px_model_distance cold, kept when <= margin; pairs culled by
//           the spheres are farther than the margin, so this is brute force
//           all pairs without the queries that cannot answer yes. On the
//           sampled steps the timed brute force's set is compared too.
//   timing  --warm steps (20), then --steps timed steps (200); each method
//           runs its own pass over the trajectory (regenerated from the
//           seed), so no method evicts another's data; the median and p90
//           of the per-step times
//   memory  proxima: px_scene_get_stats' memory_bytes after the last step
//           (the scene only; the shapes are the caller's); FCL: an estimate
//           of the manager and objects (2N - 1 tree nodes, the object table,
//           the CollisionObjects; not the geometries)
//
// Writes scene.csv and scene.md into --out; plot_scene.gp draws scene.png.
//
//   bench_scene [--out DIR] [--models DIR] [--mesh FILE] [--sizes 100,1000,10000]
//               [--model-sizes 100,1000] [--warm 20] [--steps 200] [--bf-seconds 20] [--quick]
// --quick: 60 convex bodies and 20 models, 5 + 20 steps (the smoke test).
// --proxima-only: px_scene alone, no comparison, nothing written (profiling).
#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/broadphase/detail/node_base.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/narrowphase/distance.h>

#include <array>
#include <memory>
#include <unistd.h>

#include "bench_common.h"
#include "real_meshes.h"

namespace {

using bench::now_ns;
using bench::percentile;
using bench::operator-;
using bench::operator*;

const double kMargin = 0.1;
const double kSpeed = 0.05;
const double kSpin = 0.05;
const double kFraction = 0.05;

// ---- Shapes ------------------------------------------------------------------

// Volume of a convex polytope from its faces (fans from each face's first
// vertex, tetrahedra to the origin).
double convex_volume(const px_convex *c) {
    double v = 0;
    const uint32_t nf = px_convex_face_count(c);
    for (uint32_t f = 0; f < nf; ++f) {
        uint32_t k = 0;
        px_convex_face(c, f, nullptr, nullptr, &k);
        uint32_t i0, i1, i2;
        px_vec3 p0, p1, p2;
        px_convex_face_vertex(c, f, 0, &i0);
        px_convex_vertex(c, i0, &p0);
        for (uint32_t j = 1; j + 1 < k; ++j) {
            px_convex_face_vertex(c, f, j, &i1);
            px_convex_face_vertex(c, f, j + 1, &i2);
            px_convex_vertex(c, i1, &p1);
            px_convex_vertex(c, i2, &p2);
            v += bench::dot(p0, bench::cross(p1, p2)) / 6.0;
        }
    }
    return v;
}

// FCL's copy of a hull: its vertices and faces ([n, i0, ..., i(n-1)] each).
std::shared_ptr<fcl::Convexd> fcl_convex(const px_convex *c) {
    auto verts = std::make_shared<std::vector<fcl::Vector3d>>();
    auto faces = std::make_shared<std::vector<int>>();
    for (uint32_t i = 0; i < px_convex_vertex_count(c); ++i) {
        px_vec3 p;
        px_convex_vertex(c, i, &p);
        verts->emplace_back(p.x, p.y, p.z);
    }
    const uint32_t nf = px_convex_face_count(c);
    for (uint32_t f = 0; f < nf; ++f) {
        uint32_t k = 0;
        px_convex_face(c, f, nullptr, nullptr, &k);
        faces->push_back((int)k);
        for (uint32_t j = 0; j < k; ++j) {
            uint32_t v;
            px_convex_face_vertex(c, f, j, &v);
            faces->push_back((int)v);
        }
    }
    return std::make_shared<fcl::Convexd>(verts, (int)nf, faces);
}

// A scene's shapes: one hull per body, or one model shared by all bodies.
struct Shapes {
    bool models = false;
    std::vector<px_convex *> convex;                          // per body (convex scenes)
    std::vector<std::shared_ptr<fcl::CollisionGeometryd>> fg; // per body (shared pointer for models)
    std::vector<double> radius;                               // bounding sphere about the centre
    px_model *model = nullptr;                                // models: not owned
    double total_volume = 0;
    ~Shapes() {
        for (px_convex *c : convex) px_convex_destroy(c);
    }
};

void make_hulls(size_t n, uint64_t seed, Shapes *s) {
    pg_sm rng = {seed};
    std::vector<double> xyz(3 * 32);
    for (size_t i = 0; i < n; ++i) {
        px_convex *c = nullptr;
        while (!c) {
            pg_sm_points_sphere(&rng, 32, 1.0, xyz.data());
            c = px_convex_create(xyz.data(), 32, nullptr, nullptr);
        }
        double r = 0;
        for (uint32_t k = 0; k < px_convex_vertex_count(c); ++k) {
            px_vec3 p;
            px_convex_vertex(c, k, &p);
            r = std::max(r, bench::norm(p));
        }
        s->convex.push_back(c);
        s->radius.push_back(r * (1 + 1e-12));
        s->total_volume += convex_volume(c);
        s->fg.push_back(fcl_convex(c));
    }
}

// The link, loaded once.
struct Link {
    std::string name;
    rm::Mesh mesh;
    rm::MeshPtr px_mesh;
    rm::ModelPtr model;
    std::shared_ptr<rm::FclModel> fcl;
    double radius = 0, volume = 0, hull_volume = 0;
    size_t model_bytes = 0;
    uint32_t leaves = 0;
    bool closed = false;
};

bool load_link(const std::string &path, Link *l) {
    std::string err;
    if (!rm::load_with_px(path, &l->mesh, &err))
        return fprintf(stderr, "bench_scene: %s\n", err.c_str()), false;
    l->name = l->mesh.name;
    // Centre the bounding box, then scale the farthest vertex to 1.
    rm::normalize(&l->mesh, 1.0);
    const double r = rm::max_radius(l->mesh);
    for (double &x : l->mesh.xyz) x /= r;
    l->radius = rm::max_radius(l->mesh) * (1 + 1e-12);
    double v = 0;
    for (size_t t = 0; t < l->mesh.nt(); ++t) {
        const double *a = &l->mesh.xyz[3 * l->mesh.tri[3 * t]], *b = &l->mesh.xyz[3 * l->mesh.tri[3 * t + 1]],
                     *c = &l->mesh.xyz[3 * l->mesh.tri[3 * t + 2]];
        v += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
              a[2] * (b[0] * c[1] - b[1] * c[0])) /
             6.0;
    }
    l->volume = std::fabs(v);
    px_convex *hull = px_convex_create(l->mesh.xyz.data(), l->mesh.nv(), nullptr, nullptr);
    if (!hull) return fprintf(stderr, "bench_scene: no hull of %s\n", l->name.c_str()), false;
    l->hull_volume = convex_volume(hull);
    px_convex_destroy(hull);
    l->px_mesh = rm::make_px_mesh(l->mesh, &err);
    if (!l->px_mesh) return fprintf(stderr, "bench_scene: %s\n", err.c_str()), false;
    px_mesh_info mi;
    px_mesh_get_info(l->px_mesh.get(), &mi);
    l->closed = mi.closed_parts == l->mesh.parts();
    l->model = rm::make_model(l->px_mesh.get(), PX_PIECES_TRIANGLES, &err);
    if (!l->model) return fprintf(stderr, "bench_scene: %s\n", err.c_str()), false;
    px_model_info info;
    px_model_get_info(l->model.get(), &info);
    l->model_bytes = info.memory_bytes;
    l->leaves = info.leaves;
    l->fcl = rm::make_fcl(l->mesh);
    fprintf(stderr,
            "link %s: %zu triangles, %zu parts (%u closed), radius 1, volume %.4f, hull volume %.4f\n",
            l->name.c_str(), l->mesh.nt(), l->mesh.parts(), mi.closed_parts, l->volume, l->hull_volume);
    return true;
}

// ---- Motion ------------------------------------------------------------------

struct Sim {
    size_t n = 0;
    double side = 0;
    std::vector<px_pose> pose;
    std::vector<px_vec3> v;
    std::vector<std::array<double, 9>> turn;
    int step = 0;

    Sim(size_t n_, double side_, uint64_t seed) : n(n_), side(side_), pose(n_), v(n_), turn(n_) {
        pg_sm rng = {seed};
        for (size_t i = 0; i < n; ++i) {
            double r[9];
            pg_sm_rot_random(&rng, r);
            std::memcpy(pose[i].r, r, sizeof r);
            pose[i].t =
                px_vec3{side * pg_sm_uniform(&rng), side * pg_sm_uniform(&rng), side * pg_sm_uniform(&rng)};
            const px_vec3 d = pg_sm_unit(&rng);
            const double speed = kSpeed * std::cbrt(pg_sm_uniform(&rng));
            v[i] = speed * d;
            const px_vec3 axis = pg_sm_unit(&rng);
            pg_rot_axis_angle(axis, kSpin * pg_sm_uniform(&rng), turn[i].data());
        }
    }

    // One step of the user's integration (never timed).
    void advance() {
        ++step;
        for (size_t i = 0; i < n; ++i) {
            px_vec3 &t = pose[i].t;
            px_vec3 &w = v[i];
            double *c[3] = {&t.x, &t.y, &t.z}, *u[3] = {&w.x, &w.y, &w.z};
            for (int k = 0; k < 3; ++k) {
                *c[k] += *u[k];
                if (*c[k] < 0)
                    *c[k] = -*c[k], *u[k] = -*u[k];
                else if (*c[k] > side)
                    *c[k] = 2 * side - *c[k], *u[k] = -*u[k];
            }
            pg_mat_mul(turn[i].data(), pose[i].r, pose[i].r);
            if (step % 16 == 0) pg_rot_orthonormalize(pose[i].r);
        }
    }
};

fcl::Transform3d to_fcl(const px_pose &p) {
    double t[3] = {p.t.x, p.t.y, p.t.z};
    return rm::to_fcl(p.r, t);
}

// ---- Pair sets -----------------------------------------------------------------

using Key = uint64_t;
inline Key key(uint32_t a, uint32_t b) { return a < b ? (uint64_t)a << 32 | b : (uint64_t)b << 32 | a; }

double pair_distance(const Shapes &s, size_t i, size_t j, const px_pose &pi, const px_pose &pj) {
    if (!s.models) {
        px_distance_result r;
        if (px_distance(s.convex[i], &pi, s.convex[j], &pj, nullptr, nullptr, &r) != PX_OK) return NAN;
        return r.distance;
    }
    px_model_distance_result r;
    if (px_model_distance(s.model, &pi, s.model, &pj, nullptr, &r) != PX_OK) return NAN;
    return r.distance;
}

// The reference: bounding spheres within the margin (sweep over x), then
// cold distances; sorted keys and their distances.
void reference_pairs(const Shapes &s, const std::vector<px_pose> &pose, std::vector<Key> *keys,
                     std::vector<double> *dist, uint64_t *queries) {
    const size_t n = pose.size();
    std::vector<uint32_t> order(n);
    double rmax = 0;
    for (size_t i = 0; i < n; ++i) order[i] = (uint32_t)i, rmax = std::max(rmax, s.radius[i]);
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return pose[a].t.x < pose[b].t.x; });
    std::vector<std::pair<Key, double>> found;
    for (size_t a = 0; a < n; ++a) {
        const uint32_t i = order[a];
        for (size_t b = a + 1; b < n; ++b) {
            const uint32_t j = order[b];
            if (pose[j].t.x - pose[i].t.x > 2 * rmax + kMargin + 1e-9) break;
            const double reach = s.radius[i] + s.radius[j] + kMargin + 1e-9;
            const px_vec3 d = pose[j].t - pose[i].t;
            if (bench::dot(d, d) > reach * reach) continue;
            const uint32_t lo = std::min(i, j), hi = std::max(i, j);
            const double dd = pair_distance(s, lo, hi, pose[lo], pose[hi]);
            ++*queries;
            if (!(dd > kMargin)) found.emplace_back(key(lo, hi), dd);
        }
    }
    std::sort(found.begin(), found.end());
    keys->clear();
    dist->clear();
    for (auto &f : found) keys->push_back(f.first), dist->push_back(f.second);
}

// ---- FCL -----------------------------------------------------------------------

// A CollisionObject whose world box can be inflated (the box is a protected
// member; FCL has no margin of its own).
struct MarginObject : fcl::CollisionObjectd {
    using fcl::CollisionObjectd::CollisionObjectd;
    void inflate(double d) {
        const fcl::Vector3d e(d, d, d);
        aabb.min_ -= e;
        aabb.max_ += e;
    }
};

struct FclData {
    fcl::DistanceRequestd req;
    std::vector<std::pair<Key, double>> found;
    uint64_t queries = 0;
};

bool fcl_callback(fcl::CollisionObjectd *o1, fcl::CollisionObjectd *o2, void *cdata) {
    FclData *d = static_cast<FclData *>(cdata);
    fcl::DistanceResultd res;
    const double dist = fcl::distance(o1, o2, d->req, res);
    ++d->queries;
    if (dist <= kMargin) {
        const uint32_t a = (uint32_t)(uintptr_t)o1->getUserData(), b = (uint32_t)(uintptr_t)o2->getUserData();
        d->found.emplace_back(key(a, b), dist);
    }
    return false;
}

// ---- One scene -----------------------------------------------------------------

struct Row {
    std::string method, kind;
    size_t bodies = 0;
    int steps_timed = 0;
    double median_ns = NAN, p90_ns = NAN;
    double pairs_checked = NAN; // per timed step (mean)
    double candidates = NAN;    // broad-phase pairs per timed step (mean)
    uint64_t contacts = 0;      // summed over the compared steps
    uint64_t contacts_bf = 0;   // the reference's over the same steps
    int steps_compared = 0, steps_differing = 0;
    uint64_t missing = 0, extra = 0, missing_threshold = 0, extra_threshold = 0;
    std::string memory; // bytes, or "~bytes" for an estimate
    std::string note;
    double side = NAN;
};

struct Config {
    bool models;
    size_t n;
};

struct Counts {
    uint64_t missing = 0, extra = 0, missing_threshold = 0, extra_threshold = 0;
};

// Differences between a method's set and the reference's; a difference
// within 1e-6 of the margin (by either side's distance) is "at the threshold".
bool compare_sets(const std::vector<Key> &ref, const std::vector<double> &ref_d,
                  const std::vector<std::pair<Key, double>> &got, Counts *c, const char *who, int step,
                  int *printed) {
    size_t i = 0, j = 0;
    bool same = true;
    while (i < ref.size() || j < got.size()) {
        if (j == got.size() || (i < ref.size() && ref[i] < got[j].first)) {
            const bool thr = std::fabs(ref_d[i] - kMargin) < 1e-6;
            ++c->missing;
            c->missing_threshold += thr;
            same = false;
            if ((*printed)++ < 5)
                fprintf(stderr, "    step %d: %s misses (%u, %u) at %.9g\n", step, who,
                        (uint32_t)(ref[i] >> 32), (uint32_t)ref[i], ref_d[i]);
            ++i;
        } else if (i == ref.size() || got[j].first < ref[i]) {
            const bool thr = std::fabs(got[j].second - kMargin) < 1e-6;
            ++c->extra;
            c->extra_threshold += thr;
            same = false;
            if ((*printed)++ < 5)
                fprintf(stderr, "    step %d: %s reports (%u, %u) at %.9g, the reference does not\n", step,
                        who, (uint32_t)(got[j].first >> 32), (uint32_t)got[j].first, got[j].second);
            ++j;
        } else {
            ++i, ++j;
        }
    }
    return same;
}

std::string fmt_bytes(size_t b, bool estimate) {
    char buf[48];
    snprintf(buf, sizeof buf, "%s%zu", estimate ? "~" : "", b);
    return buf;
}

std::vector<Row> run_scene(const Config &cfg, const Link *link, int warm, int timed, double bf_budget_s,
                           bool proxima_only, std::vector<std::string> *notes) {
    const uint64_t seed = 0x5ce11 + cfg.n * 7 + (cfg.models ? 1 : 0);
    const char *kind = cfg.models ? "model" : "convex";
    Shapes shapes;
    shapes.models = cfg.models;
    if (cfg.models) {
        shapes.model = link->model.get();
        shapes.radius.assign(cfg.n, link->radius);
        shapes.fg.assign(cfg.n, link->fcl);
        shapes.total_volume = link->hull_volume * (double)cfg.n;
    } else {
        make_hulls(cfg.n, seed, &shapes);
    }
    const double side = std::cbrt(shapes.total_volume / kFraction);
    if (cfg.models && cfg.n >= 1000 && (warm > 10 || timed > 50)) {
        warm = std::min(warm, 10), timed = std::min(timed, 50);
        char b[160];
        snprintf(b, sizeof b,
                 "%zu model bodies: %d warm-up and %d timed steps only (FCL takes seconds per step).", cfg.n,
                 warm, timed);
        notes->push_back(b);
    }
    const int total = warm + timed;
    fprintf(stderr, "%zu %s bodies, box side %.3f, %d + %d steps\n", cfg.n, kind, side, warm, timed);

    std::vector<Row> rows;
    // Per step: each method's contacts.
    std::vector<std::vector<std::pair<Key, double>>> px_sets(total + 1), px2_sets(total + 1),
        fcl_sets(total + 1), bf_sets(total + 1);

    // proxima, on the calling thread, then with one helper thread.
    for (uint32_t threads = 1; threads <= 2; ++threads) {
        std::vector<std::vector<std::pair<Key, double>>> &sets = threads == 1 ? px_sets : px2_sets;
        Row r;
        r.method = threads == 1 ? "proxima-scene" : "proxima-scene-2t", r.kind = kind, r.bodies = cfg.n,
        r.steps_timed = timed;
        px_scene_options o{};
        o.margin = kMargin;
        o.threads = threads;
        px_error e{};
        px_scene *sc = px_scene_create(&o, &e);
        if (!sc) {
            fprintf(stderr, "px_scene_create: %s\n", e.message);
            return rows;
        }
        Sim sim(cfg.n, side, seed ^ 0x9e3779b97f4a7c15ull);
        for (size_t i = 0; i < cfg.n; ++i) {
            px_body_desc d{};
            if (cfg.models)
                d.model = shapes.model;
            else
                d.convex = shapes.convex[i];
            d.pose = sim.pose[i];
            d.max_speed = kSpeed;
            d.max_angular_speed = kSpin;
            uint32_t id = 0;
            if (px_scene_add_body(sc, &d, &id, &e) != PX_OK || id != i) {
                fprintf(stderr, "px_scene_add_body: %s (id %u)\n", e.message, id);
                px_scene_destroy(sc);
                return rows;
            }
        }
        std::vector<double> t;
        double checked = 0, cand = 0, swaps = 0, box_updates = 0;
        uint64_t violations = 0, touching = 0, contacts = 0;
        std::vector<std::array<double, 5>> slow; // time, step, pairs checked, box updates, swaps
        px_scene_stats st{};
        for (int k = 0; k <= total; ++k) {
            if (k > 0) sim.advance();
            const double t0 = now_ns();
            if (k > 0)
                for (size_t i = 0; i < cfg.n; ++i) px_scene_set_pose(sc, (uint32_t)i, &sim.pose[i], nullptr);
            const px_status ps = px_scene_step(sc, (double)k, &e);
            const double t1 = now_ns();
            if (ps != PX_OK) fprintf(stderr, "  px_scene_step %d: %s\n", k, e.message);
            px_scene_get_stats(sc, &st);
            violations += st.violations;
            if (k > warm) {
                t.push_back(t1 - t0);
                checked += (double)st.pairs_checked;
                cand += (double)st.candidate_pairs;
                swaps += (double)st.swaps;
                box_updates += (double)st.box_updates;
                slow.push_back(
                    {t1 - t0, (double)k, (double)st.pairs_checked, (double)st.box_updates, (double)st.swaps});
            }
            size_t np = 0;
            const px_scene_pair *p = px_scene_pairs(sc, &np);
            for (size_t q = 0; q < np; ++q)
                if (p[q].contact) {
                    sets[k].emplace_back(key(p[q].body_a, p[q].body_b), p[q].distance);
                    ++contacts;
                    touching += p[q].distance == 0;
                }
        }
        r.median_ns = percentile(t, 0.5);
        r.p90_ns = percentile(t, 0.9);
        r.pairs_checked = checked / timed;
        r.candidates = cand / timed;
        r.memory = fmt_bytes(st.memory_bytes, false);
        if (violations) {
            char b[160];
            snprintf(b, sizeof b, "%zu %s bodies: px_scene counted %llu bound violations", cfg.n, kind,
                     (unsigned long long)violations);
            notes->push_back(b);
        }
        px_scene_destroy(sc);
        fprintf(stderr,
                "  proxima: median %.1f us, p90 %.1f us, %.1f pairs checked / step, %s bytes; per step: %.1f "
                "candidate pairs, %.1f box updates, %.1f swaps, %llu violations in all\n",
                r.median_ns * 1e-3, r.p90_ns * 1e-3, r.pairs_checked, r.memory.c_str(), r.candidates,
                box_updates / timed, swaps / timed, (unsigned long long)violations);
        std::sort(slow.begin(), slow.end());
        std::reverse(slow.begin(), slow.end());
        fprintf(stderr,
                "  proxima: %.1f %% of the contacts at distance 0; slowest steps (us, step, checked, box "
                "updates, swaps):",
                100.0 * (double)touching / (double)std::max<uint64_t>(contacts, 1));
        for (size_t q = 0; q < slow.size() && q < 6; ++q)
            fprintf(stderr, " (%.0f, %.0f, %.0f, %.0f, %.0f)", slow[q][0] * 1e-3, slow[q][1], slow[q][2],
                    slow[q][3], slow[q][4]);
        fprintf(stderr, "\n");
        rows.push_back(r);
    }
    if (proxima_only) return rows;

    // FCL.
    {
        Row r;
        r.method = "fcl-dynamic-aabb", r.kind = kind, r.bodies = cfg.n, r.steps_timed = timed;
        std::vector<std::unique_ptr<MarginObject>> objs;
        Sim sim(cfg.n, side, seed ^ 0x9e3779b97f4a7c15ull);
        fcl::DynamicAABBTreeCollisionManagerd manager;
        std::vector<fcl::CollisionObjectd *> list;
        for (size_t i = 0; i < cfg.n; ++i) {
            objs.emplace_back(new MarginObject(shapes.fg[i], to_fcl(sim.pose[i])));
            objs.back()->setUserData((void *)(uintptr_t)i);
            objs.back()->computeAABB();
            objs.back()->inflate(0.5 * kMargin);
            list.push_back(objs.back().get());
        }
        manager.registerObjects(list);
        manager.setup();
        FclData data;
        data.req.enable_nearest_points = true;
        if (cfg.models) data.req.rel_err = 0, data.req.abs_err = 0;
        std::vector<double> t;
        double checked = 0;
        for (int k = 0; k <= total; ++k) {
            if (k > 0) sim.advance();
            data.found.clear();
            data.queries = 0;
            const double t0 = now_ns();
            if (k > 0) {
                for (size_t i = 0; i < cfg.n; ++i) {
                    objs[i]->setTransform(to_fcl(sim.pose[i]));
                    objs[i]->computeAABB();
                    objs[i]->inflate(0.5 * kMargin);
                }
                manager.update();
            }
            manager.collide(&data, fcl_callback);
            const double t1 = now_ns();
            if (k > warm) t.push_back(t1 - t0), checked += (double)data.queries;
            std::sort(data.found.begin(), data.found.end());
            fcl_sets[k] = data.found;
        }
        r.median_ns = percentile(t, 0.5);
        r.p90_ns = percentile(t, 0.9);
        r.pairs_checked = checked / timed;
        r.candidates = r.pairs_checked;
        // Tree nodes, the object -> node table (one hash node: next pointer,
        // key, value, cached hash; plus a bucket pointer), the objects.
        const size_t bytes = (2 * cfg.n - 1) * sizeof(fcl::detail::NodeBase<fcl::AABBd>) +
                             cfg.n * (4 * sizeof(void *) + sizeof(void *)) + cfg.n * sizeof(MarginObject);
        r.memory = fmt_bytes(bytes, true);
        fprintf(stderr, "  FCL: median %.1f us, p90 %.1f us, %.1f distance calls / step\n",
                r.median_ns * 1e-3, r.p90_ns * 1e-3, r.pairs_checked);
        rows.push_back(r);
    }

    // Brute force, timed on sampled steps: the first timed step, then as
    // many more, evenly spaced over the rest, as fit in `bf_budget_s` at
    // the first one's cost.
    std::vector<char> sampled(total + 1, 0);
    {
        Row r;
        r.method = "bruteforce", r.kind = kind, r.bodies = cfg.n;
        const double pairs = (double)cfg.n * (double)(cfg.n - 1) / 2;
        Sim sim(cfg.n, side, seed ^ 0x9e3779b97f4a7c15ull);
        std::vector<double> t;
        const int first = std::min(warm + 1, total);
        sampled[first] = 1;
        for (int k = 0; k <= total; ++k) {
            if (k > 0) sim.advance();
            if (!sampled[k]) continue;
            auto &out = bf_sets[k];
            const double t0 = now_ns();
            double done = 0; // pairs measured
            bool cut = false;
            for (size_t i = 0; i < cfg.n && !cut; ++i) {
                for (size_t j = i + 1; j < cfg.n; ++j) {
                    const double d = pair_distance(shapes, i, j, sim.pose[i], sim.pose[j]);
                    if (!(d > kMargin)) out.emplace_back(key((uint32_t)i, (uint32_t)j), d);
                }
                done += (double)(cfg.n - 1 - i);
                // Over budget on the first step: stop and extrapolate.
                if (k == first && (now_ns() - t0) * 1e-9 > bf_budget_s && i + 1 < cfg.n) cut = true;
            }
            const double t1 = now_ns();
            if (cut) {
                t.push_back((t1 - t0) * pairs / done);
                sampled[k] = 0;
                out.clear();
                char b[200];
                snprintf(
                    b, sizeof b,
                    "%zu %s bodies: brute force timed on %.0f of the %.0f pairs of one step (%.1f s) and "
                    "extrapolated to all pairs",
                    cfg.n, kind, done, pairs, (t1 - t0) * 1e-9);
                notes->push_back(b);
                r.note = "extrapolated";
                break;
            }
            t.push_back(t1 - t0);
            if (k == first) {
                const int rest = total - first;
                const int more =
                    (int)std::min<double>(rest, std::floor(bf_budget_s / ((t1 - t0) * 1e-9)) - 1);
                for (int m = 1; m <= more; ++m) sampled[first + (int)((long long)m * rest / more)] = 1;
            }
        }
        r.steps_timed = (int)t.size();
        r.median_ns = percentile(t, 0.5);
        r.p90_ns = percentile(t, 0.9);
        r.pairs_checked = pairs;
        r.candidates = pairs;
        r.memory = "0";
        fprintf(stderr, "  brute force: median %.1f us over %zu steps\n", r.median_ns * 1e-3, t.size());
        rows.push_back(r);
    }

    // The reference, every step, and the comparisons.
    {
        Sim sim(cfg.n, side, seed ^ 0x9e3779b97f4a7c15ull);
        std::vector<Key> keys;
        std::vector<double> dist;
        uint64_t queries = 0;
        Counts cnt[4];
        int printed[4] = {0, 0, 0, 0};
        const char *who[4] = {"proxima", "proxima 2 threads", "FCL", "brute force"};
        for (int k = 0; k <= total; ++k) {
            if (k > 0) sim.advance();
            reference_pairs(shapes, sim.pose, &keys, &dist, &queries);
            const std::vector<std::pair<Key, double>> *sets[4] = {&px_sets[k], &px2_sets[k], &fcl_sets[k],
                                                                  &bf_sets[k]};
            for (int m = 0; m < 4; ++m) {
                if (m == 3 && !sampled[k]) continue;
                Row &r = rows[m];
                ++r.steps_compared;
                r.contacts += sets[m]->size();
                r.contacts_bf += keys.size();
                if (!compare_sets(keys, dist, *sets[m], &cnt[m], who[m], k, &printed[m])) ++r.steps_differing;
            }
        }
        for (int m = 0; m < 4; ++m) {
            rows[m].missing = cnt[m].missing, rows[m].extra = cnt[m].extra;
            rows[m].missing_threshold = cnt[m].missing_threshold,
            rows[m].extra_threshold = cnt[m].extra_threshold;
            fprintf(stderr, "  %s: %d of %d steps differ from the reference (%llu missing, %llu extra)\n",
                    who[m], rows[m].steps_differing, rows[m].steps_compared,
                    (unsigned long long)cnt[m].missing, (unsigned long long)cnt[m].extra);
        }
        for (Row &r : rows) r.side = side;
        fprintf(stderr, "  reference: %.1f contacts / step, %.1f sphere-culled queries / step\n",
                (double)rows[0].contacts_bf / (total + 1), (double)queries / (total + 1));
    }
    return rows;
}

std::string csv_num(double v, const char *fmt = "%.6g") {
    if (!(v == v)) return "";
    char b[64];
    snprintf(b, sizeof b, fmt, v);
    return b;
}

// The tree the run measured: HEAD's short hash, "+ uncommitted changes in
// src/ or include/" when there are some ("unknown" outside a git tree).
std::string source_version() {
    std::string v;
    if (FILE *p = popen("git rev-parse --short HEAD 2>/dev/null", "r")) {
        char b[64];
        if (fgets(b, sizeof b, p)) v = b;
        pclose(p);
    }
    v.erase(v.find_last_not_of("\n") + 1);
    if (v.empty()) return "unknown";
    if (FILE *p = popen("git status --porcelain -- src include 2>/dev/null", "r")) {
        char b[256];
        if (fgets(b, sizeof b, p)) v += " + uncommitted changes in src/ or include/";
        pclose(p);
    }
    return v;
}

const Row *find_row(const std::vector<Row> &rows, const std::string &method, const std::string &kind,
                    size_t n) {
    for (auto &r : rows)
        if (r.method == method && r.kind == kind && r.bodies == n) return &r;
    return nullptr;
}

} // namespace

int main(int argc, char **argv) {
    std::string out_dir = "docs/bench", models = "models", mesh;
    std::vector<size_t> sizes = {100, 1000, 10000}, model_sizes = {100, 1000};
    int warm = 20, timed = 200;
    double bf_budget_s = 20;
    bool quick = false, proxima_only = false; // --proxima-only: no FCL, brute force nor check (profiling)
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        if (a == "--out" && i + 1 < argc)
            out_dir = argv[++i];
        else if (a == "--models" && i + 1 < argc)
            models = argv[++i];
        else if (a == "--mesh" && i + 1 < argc)
            mesh = argv[++i];
        else if (a == "--sizes" && i + 1 < argc)
            sizes = bench::parse_sizes(argv[++i]);
        else if (a == "--model-sizes" && i + 1 < argc)
            model_sizes = bench::parse_sizes(argv[++i]);
        else if (a == "--warm" && i + 1 < argc)
            warm = std::max(0, atoi(argv[++i]));
        else if (a == "--steps" && i + 1 < argc)
            timed = std::max(1, atoi(argv[++i]));
        else if (a == "--bf-seconds" && i + 1 < argc)
            bf_budget_s = std::strtod(argv[++i], nullptr);
        else if (a == "--quick")
            quick = true;
        else if (a == "--proxima-only")
            proxima_only = true;
        else {
            fprintf(
                stderr,
                "usage: bench_scene [--out DIR] [--models DIR] [--mesh FILE] [--sizes N,...] "
                "[--model-sizes N,...] [--warm K] [--steps K] [--bf-seconds S] [--quick] [--proxima-only]\n");
            return 2;
        }
    }
    if (quick) sizes = {60}, model_sizes = {20}, warm = 5, timed = 20, bf_budget_s = 0.3;
    if (mesh.empty()) mesh = models + "/puma560/nimasarli_puma560_description/meshes/puma_link3.stl";

    const double load0 = bench::load_average();
    const std::string version = source_version();
    const double wall0 = now_ns();
    std::vector<Row> rows;
    std::vector<std::string> notes;
    for (size_t n : sizes) {
        auto r = run_scene(Config{false, n}, nullptr, warm, timed, bf_budget_s, proxima_only, &notes);
        rows.insert(rows.end(), r.begin(), r.end());
    }
    Link link;
    if (!model_sizes.empty()) {
        if (load_link(mesh, &link)) {
            for (size_t n : model_sizes) {
                auto r = run_scene(Config{true, n}, &link, warm, timed, bf_budget_s, proxima_only, &notes);
                rows.insert(rows.end(), r.begin(), r.end());
            }
        } else {
            notes.push_back("The link " + mesh + " could not be loaded: the model scenes are missing.");
        }
    }
    const double load1 = bench::load_average();
    const double wall_s = (now_ns() - wall0) * 1e-9;

    if (proxima_only) return 0;

    // scene.csv
    const std::string csv = out_dir + "/scene.csv";
    FILE *f = fopen(csv.c_str(), "w");
    if (!f) return fprintf(stderr, "cannot write %s\n", csv.c_str()), 1;
    fprintf(
        f, "method,kind,bodies,steps_timed,median_step_ns,p90_step_ns,pairs_checked,candidate_pairs,contacts,"
           "contacts_bruteforce,steps_compared,steps_differing,missing,extra,memory_bytes\n");
    for (auto &r : rows)
        fprintf(f, "%s,%s,%zu,%d,%s,%s,%s,%s,%llu,%llu,%d,%d,%llu,%llu,%s\n", r.method.c_str(),
                r.kind.c_str(), r.bodies, r.steps_timed, csv_num(r.median_ns, "%.0f").c_str(),
                csv_num(r.p90_ns, "%.0f").c_str(), csv_num(r.pairs_checked, "%.1f").c_str(),
                csv_num(r.candidates, "%.1f").c_str(), (unsigned long long)r.contacts,
                (unsigned long long)r.contacts_bf, r.steps_compared, r.steps_differing,
                (unsigned long long)r.missing, (unsigned long long)r.extra,
                r.memory == "0" ? "-" : (r.memory[0] == '~' ? r.memory.substr(1).c_str() : r.memory.c_str()));
    fclose(f);

    // scene.md
    const std::string md = out_dir + "/scene.md";
    f = fopen(md.c_str(), "w");
    if (!f) return fprintf(stderr, "cannot write %s\n", md.c_str()), 1;
    fprintf(f, "# px_scene against FCL's DynamicAABBTreeCollisionManager and brute force\n\n");
    fprintf(
        f,
        "Written by `bench/bench_scene.cpp` (`make bench-scene`, part of `make bench`; the method is in its "
        "header comment). Bodies move with constant random velocities (|v| ≤ %.2f per step, uniform in the "
        "ball) and turn about a random axis through their centre (|ω| ≤ %.2f rad per step), bouncing off the "
        "walls of a cubic box at %.0f %% volume fraction; they pass through each other. Margin %.1f: every "
        "method must find every pair within %.1f with its exact distance. Convex bodies: hulls of 32 random "
        "points on the unit sphere, one per body; models: `%s` (PX_PIECES_TRIANGLES, %u triangles; FCL: "
        "BVHModel<OBBRSS> of the same triangles) scaled to a bounding radius of 1, one model shared by all "
        "bodies. %d warm-up steps, then %d timed steps; each method runs its own pass over the same "
        "trajectory. Time per step: proxima, `px_scene_set_pose` for every body + `px_scene_step`; FCL, "
        "`setTransform` + `computeAABB` + the box inflated by margin / 2 for every object, `update()`, then "
        "`collide()` on the manager with a callback that runs `fcl::distance` (nearest points on; models: "
        "rel_err = abs_err = 0) on every broad-phase pair; brute force, px_distance / px_model_distance "
        "(cold) on all pairs, timed on a subset of the timed steps only (`steps timed`). The motion itself "
        "is never timed.\n\n",
        kSpeed, kSpin, 100 * kFraction, kMargin, kMargin, link.name.empty() ? "-" : link.name.c_str(),
        link.leaves, warm, timed);
    fprintf(
        f,
        "Machine: %s, %ld cores online; load average %.2f at the start and %.2f at the end of the run "
        "(%.0f s; other work shared the machine, so absolute times carry its noise, ratios measured in the "
        "same run less so; a step preempted by other work shows in the p90). Source: %s.\n\n",
        bench::cpu_name().c_str(), sysconf(_SC_NPROCESSORS_ONLN), load0, load1, wall_s, version.c_str());
    for (auto &nt : notes) fprintf(f, "%s\n\n", nt.c_str());
    fprintf(f, "| kind | bodies | box side | method | median µs / step | p90 µs / step | steps timed | pairs "
               "checked / step | contacts | contacts brute force | steps differing | memory bytes |\n");
    fprintf(f, "|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (auto &r : rows)
        fprintf(f, "| %s | %zu | %.2f | %s | %s | %s | %d%s | %s | %llu | %llu | %d of %d | %s |\n",
                r.kind.c_str(), r.bodies, r.side, r.method.c_str(), bench::fmt_us(r.median_ns).c_str(),
                bench::fmt_us(r.p90_ns).c_str(), r.steps_timed, r.note.empty() ? "" : (", " + r.note).c_str(),
                csv_num(r.pairs_checked, "%.1f").c_str(), (unsigned long long)r.contacts,
                (unsigned long long)r.contacts_bf, r.steps_differing, r.steps_compared,
                r.memory == "0" ? "-" : r.memory.c_str());
    fprintf(
        f,
        "\n`contacts`: pairs within the margin summed over the compared steps (every step, warm-up "
        "included, for proxima and FCL; the timed steps for brute force); `contacts brute force`: the "
        "reference's over the same steps (every pair whose bounding spheres are within the margin, measured "
        "cold with px_distance / px_model_distance: the pairs the spheres cull are farther than the margin). "
        "`pairs checked`: narrow-phase queries per timed step (px_scene_get_stats' pairs_checked; FCL's "
        "fcl::distance calls, one per pair its broad phase reports; brute force: all pairs). Memory: "
        "proxima, px_scene_get_stats' memory_bytes (the scene, not the shapes); FCL (~), an estimate: "
        "2N - 1 tree nodes of %zu bytes, 40 bytes per entry of the object table, the CollisionObjects "
        "(%zu bytes each), not the geometries.\n\n",
        sizeof(fcl::detail::NodeBase<fcl::AABBd>), sizeof(fcl::CollisionObjectd));
    bool any_diff = false;
    for (auto &r : rows)
        if (r.steps_differing) {
            if (!any_diff) fprintf(f, "Differences from the reference:\n\n");
            any_diff = true;
            fprintf(
                f,
                "- %s, %zu %s bodies: %llu pairs missing (%llu within 1e-6 of the margin), %llu extra (%llu "
                "within 1e-6 of the margin)\n",
                r.method.c_str(), r.bodies, r.kind.c_str(), (unsigned long long)r.missing,
                (unsigned long long)r.missing_threshold, (unsigned long long)r.extra,
                (unsigned long long)r.extra_threshold);
        }
    if (any_diff) fprintf(f, "\n");

    fprintf(f, "## Targets (issue 11 section 5)\n\n| target | measured | met |\n|---|---|---|\n");
    auto target = [&](size_t n, double limit_ns) {
        for (const char *m : {"proxima-scene", "proxima-scene-2t"}) {
            const Row *p = find_row(rows, m, "convex", n);
            if (!p) continue;
            fprintf(f,
                    "| %zu convex bodies ≤ %s µs per step (median), exact distances for all pairs within "
                    "the margin (%s) | %s µs (p90 %s) | %s |\n",
                    n, bench::fmt_us(limit_ns).c_str(), m[13] ? "2 threads" : "1 thread",
                    bench::fmt_us(p->median_ns).c_str(), bench::fmt_us(p->p90_ns).c_str(),
                    p->median_ns <= limit_ns ? "yes" : "**no**");
        }
    };
    target(1000, 100e3);
    target(10000, 1000e3);
    for (auto &r : rows)
        if (r.method.rfind("proxima-scene", 0) == 0)
            fprintf(f,
                    "| contacts equal to brute force on every step: %zu %s bodies (%s) | %d of %d steps "
                    "differ | %s |\n",
                    r.bodies, r.kind.c_str(), r.method == "proxima-scene" ? "1 thread" : "2 threads",
                    r.steps_differing, r.steps_compared, r.steps_differing == 0 ? "yes" : "**no**");
    fprintf(
        f, "\nThe Puma arm target (≤ 10 µs per step with self-collision and its cell) belongs to section 3's "
           "scene and is not measured here.\n\n");
    fprintf(f, "## Ratios in this run (median step time)\n\n| kind | bodies | FCL / proxima | brute force / "
               "proxima | proxima 1 thread / 2 threads |\n|---|---|---|---|---|\n");
    for (auto &r : rows) {
        if (r.method != "proxima-scene") continue;
        const Row *fc = find_row(rows, "fcl-dynamic-aabb", r.kind, r.bodies);
        const Row *bf = find_row(rows, "bruteforce", r.kind, r.bodies);
        const Row *t2 = find_row(rows, "proxima-scene-2t", r.kind, r.bodies);
        fprintf(f, "| %s | %zu | %s× | %s× | %s× |\n", r.kind.c_str(), r.bodies,
                fc ? csv_num(fc->median_ns / r.median_ns, "%.1f").c_str() : "–",
                bf ? csv_num(bf->median_ns / r.median_ns, "%.0f").c_str() : "–",
                t2 ? csv_num(r.median_ns / t2->median_ns, "%.2f").c_str() : "–");
    }
    fprintf(f, "\n![median time per step against the number of bodies](scene.png)\n");
    fclose(f);
    fprintf(stderr, "wrote %s, %s (%.0f s)\n", csv.c_str(), md.c_str(), wall_s);
    int bad = 0;
    for (auto &r : rows)
        if (r.method.rfind("proxima-scene", 0) == 0 && r.steps_differing) bad = 1;
    return bad;
}
