// test_fcl_model: px_model on real meshes, with FCL as the second opinion
// (issue 9 section 5).
//
// - Triangle leaves (PX_PIECES_TRIANGLES): px_model_distance equals
//   fcl::distance on fcl::BVHModel<fcl::OBBRSSd> of the same triangles (FCL
//   asked for exact answers: rel_err = abs_err = 0, nearest points on) to
//   1e-9 relative, on random poses and along a coherent approach (warm
//   caches), for elephant against a scaled bunny00 and for two Puma 560
//   links. The witness points lie on the reported triangles, as far apart
//   as the distance.
// - px_model_collide agrees with fcl::collide wherever the distance exceeds
//   1e-9 or the surfaces cross; where FCL misses a containment (fcl #418)
//   proxima reports it, checked against a brute-force ray parity test, and a
//   small bunny inside the elephant is checked on purpose.
// - Part hulls (PX_PIECES_PARTS: the loader's parts for the Puma links,
//   OBJ groups or connected components for the teapots) bracket the triangle distance: distance <= exact <=
//   upper_bound, on the Puma links and the two teapots; so do approximate
//   pieces (PX_PIECES_APPROXIMATE at tolerance 0.02) on the Puma links.
// Every mesh is scaled to a bounding-box diagonal of 1 (the bunny against
// the elephant to 0.5). The CGAL meshes come from PROXIMA_MESH_DATA (filled
// by `make deps`); when they are truly unavailable those cases print SKIP.
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include "real_meshes.h"
#include "test_util.h"

#ifndef PX_SOURCE_DIR
#define PX_SOURCE_DIR "."
#endif

namespace {

using rm::Mesh;

struct Rng {
    uint64_t s;
    uint64_t next() {
        uint64_t z = (s += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    double uniform() { return (double)(next() >> 11) * (1.0 / 9007199254740992.0); }
    double range(double a, double b) { return a + (b - a) * uniform(); }
    void unit(double u[3]) {
        double n2;
        do {
            for (int k = 0; k < 3; ++k) u[k] = range(-1, 1);
            n2 = u[0] * u[0] + u[1] * u[1] + u[2] * u[2];
        } while (n2 > 1 || n2 < 1e-6);
        for (int k = 0; k < 3; ++k) u[k] /= std::sqrt(n2);
    }
};

// FCL's own floating point divides by zero on parallel segments and goes on
// (TriangleDistance::segPoints): the test's traps are off inside FCL calls.
struct FclFpGuard {
    int was = fegetexcept();
    FclFpGuard() {
        if (was) tu_untrap_fp();
    }
    ~FclFpGuard() {
        if (was) feenableexcept(was);
    }
};

struct Body {
    Mesh mesh;
    rm::MeshPtr px_mesh;
    rm::ModelPtr tri;    // PX_PIECES_TRIANGLES
    rm::ModelPtr parts;  // PX_PIECES_PARTS (bracket cases only)
    rm::ModelPtr approx; // PX_PIECES_APPROXIMATE (when asked for)
    std::shared_ptr<rm::FclModel> fcl;
    double radius = 0;
};

bool make_body(Body *b, bool parts, double approx_tolerance = 0.0) {
    std::string err;
    b->px_mesh = rm::make_px_mesh(b->mesh, &err);
    CHECK(b->px_mesh != nullptr, "%s: %s", b->mesh.name.c_str(), err.c_str());
    if (!b->px_mesh) return false;
    b->tri = rm::make_model(b->px_mesh.get(), PX_PIECES_TRIANGLES, &err);
    CHECK(b->tri != nullptr, "%s: %s", b->mesh.name.c_str(), err.c_str());
    if (parts) {
        b->parts = rm::make_model(b->px_mesh.get(), PX_PIECES_PARTS, &err);
        CHECK(b->parts != nullptr, "%s (parts): %s", b->mesh.name.c_str(), err.c_str());
        if (!b->parts) return false;
    }
    if (approx_tolerance > 0.0) {
        b->approx = rm::make_model(b->px_mesh.get(), PX_PIECES_APPROXIMATE, &err, approx_tolerance);
        CHECK(b->approx != nullptr, "%s (approximate): %s", b->mesh.name.c_str(), err.c_str());
        if (!b->approx) return false;
    }
    {
        FclFpGuard guard;
        b->fcl = rm::make_fcl(b->mesh);
    }
    b->radius = rm::max_radius(b->mesh);
    return b->tri != nullptr;
}

// Exact FCL distance: no relative or absolute slack in the BVH traversal
// (fcl/narrowphase/distance_request.h), nearest points returned.
fcl::DistanceRequestd exact_request() {
    fcl::DistanceRequestd req;
    req.enable_nearest_points = true;
    req.enable_signed_distance = false;
    req.rel_err = 0.0;
    req.abs_err = 0.0;
    req.distance_tolerance = 0.0;
    return req;
}

double fcl_distance(const Body &a, const fcl::Transform3d &ta, const Body &b, const fcl::Transform3d &tb) {
    FclFpGuard guard;
    fcl::DistanceResultd res;
    fcl::distance(a.fcl.get(), ta, b.fcl.get(), tb, exact_request(), res);
    return res.min_distance;
}

bool fcl_collide(const Body &a, const fcl::Transform3d &ta, const Body &b, const fcl::Transform3d &tb) {
    FclFpGuard guard;
    fcl::CollisionRequestd req; // one contact, no contact data: the boolean query
    fcl::CollisionResultd res;
    fcl::collide(a.fcl.get(), ta, b.fcl.get(), tb, req, res);
    return res.isCollision();
}

px_vec3 xf(const px_pose &p, const double *v) {
    return px_vec3{p.r[0] * v[0] + p.r[1] * v[1] + p.r[2] * v[2] + p.t.x,
                   p.r[3] * v[0] + p.r[4] * v[1] + p.r[5] * v[2] + p.t.y,
                   p.r[6] * v[0] + p.r[7] * v[1] + p.r[8] * v[2] + p.t.z};
}

double dist3(px_vec3 a, px_vec3 b) {
    return std::sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) + (a.z - b.z) * (a.z - b.z));
}

// Distance from point p to triangle (a, b, c): by projection when inside,
// else the nearest of the three edges.
double point_tri(px_vec3 p, px_vec3 a, px_vec3 b, px_vec3 c) {
    auto sub = [](px_vec3 u, px_vec3 v) { return px_vec3{u.x - v.x, u.y - v.y, u.z - v.z}; };
    auto dot = [](px_vec3 u, px_vec3 v) { return u.x * v.x + u.y * v.y + u.z * v.z; };
    auto seg = [&](px_vec3 u, px_vec3 v) {
        px_vec3 d = sub(v, u);
        double t = dot(sub(p, u), d) / dot(d, d);
        t = t < 0 ? 0 : t > 1 ? 1 : t;
        return dist3(p, px_vec3{u.x + t * d.x, u.y + t * d.y, u.z + t * d.z});
    };
    px_vec3 e1 = sub(b, a), e2 = sub(c, a);
    px_vec3 n{e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x};
    double nn = dot(n, n);
    px_vec3 ap = sub(p, a);
    double h = dot(ap, n) / nn;
    px_vec3 q{p.x - h * n.x, p.y - h * n.y, p.z - h * n.z};
    px_vec3 aq = sub(q, a);
    double d00 = dot(e1, e1), d01 = dot(e1, e2), d11 = dot(e2, e2), d20 = dot(aq, e1), d21 = dot(aq, e2);
    double den = d00 * d11 - d01 * d01;
    double v = (d11 * d20 - d01 * d21) / den, w = (d00 * d21 - d01 * d20) / den;
    if (v >= 0 && w >= 0 && v + w <= 1) return std::fabs(h) * std::sqrt(nn);
    return std::min(seg(a, b), std::min(seg(b, c), seg(c, a)));
}

// Distance from world point p to leaf `leaf` (a triangle) of body b at pose.
double witness_off(const Body &b, const px_pose &pose, uint32_t leaf, px_vec3 p) {
    px_model_leaf lf;
    if (px_model_get_leaf(b.tri.get(), leaf, &lf) != PX_OK || lf.triangle == UINT32_MAX) return HUGE_VAL;
    const uint32_t *t = &b.mesh.tri[3 * (size_t)lf.triangle];
    return point_tri(p, xf(pose, &b.mesh.xyz[3 * t[0]]), xf(pose, &b.mesh.xyz[3 * t[1]]),
                     xf(pose, &b.mesh.xyz[3 * t[2]]));
}

// A vertex of `in` (at pose_in) inside the closed mesh `out` (at pose_out),
// by brute-force ray parity: the independent check of a containment.
bool some_vertex_inside(const Body &in, const px_pose &pose_in, const Body &out, const px_pose &pose_out) {
    const size_t step = std::max<size_t>(1, in.mesh.nv() / 16);
    for (size_t i = 0; i < in.mesh.nv(); i += step) {
        px_vec3 w = xf(pose_in, &in.mesh.xyz[3 * i]);
        // world -> out's body frame: R^T (w - t)
        double d[3] = {w.x - pose_out.t.x, w.y - pose_out.t.y, w.z - pose_out.t.z};
        const double *r = pose_out.r;
        double p[3] = {r[0] * d[0] + r[3] * d[1] + r[6] * d[2], r[1] * d[0] + r[4] * d[1] + r[7] * d[2],
                       r[2] * d[0] + r[5] * d[1] + r[8] * d[2]};
        if (rm::point_inside(out.mesh, p)) return true;
    }
    return false;
}

struct Stats {
    int poses = 0, crossing = 0, apart = 0, touching = 0, contained = 0;
    double max_rel = 0;
    uint64_t node_pairs = 0, leaf_pairs = 0;
};

// One pose: distance against FCL, witnesses, collide against FCL.
void check_pose(const char *what, const Body &a, const Body &b, const px_pose &pb, px_model_cache *dcache,
                px_model_cache *ccache, Stats *st) {
    const px_pose pa = px_pose_identity();
    const fcl::Transform3d ta = rm::to_fcl(pa.r, &pa.t.x), tb = rm::to_fcl(pb.r, &pb.t.x);
    px_model_distance_result r;
    px_status s = px_model_distance(a.tri.get(), &pa, b.tri.get(), &pb, dcache, &r);
    CHECK(s == PX_OK, "%s pose %d: px_model_distance %s", what, st->poses, px_status_string(s));
    if (s != PX_OK) return;
    const double df = fcl_distance(a, ta, b, tb);
    const double err = std::fabs(r.distance - df);
    const double rel = err / std::max(df, 1e-300);
    if (err > 0) st->max_rel = std::max(st->max_rel, err <= 1e-300 ? 0.0 : rel);
    CHECK(err <= 1e-9 * df || err <= 1e-15, "%s pose %d: proxima %.17g, FCL %.17g (rel %.3g)", what,
          st->poses, r.distance, df, rel);
    CHECK(r.upper_bound == r.distance, "%s pose %d: triangle leaves, upper bound %.17g", what, st->poses,
          r.upper_bound);
    // The witnesses: on the reported triangles, as far apart as the distance.
    const double off_a = witness_off(a, pa, r.leaf_a, r.point_a),
                 off_b = witness_off(b, pb, r.leaf_b, r.point_b);
    CHECK(off_a <= 1e-12 && off_b <= 1e-12, "%s pose %d: witnesses off their triangles by %.3g, %.3g", what,
          st->poses, off_a, off_b);
    const double gap = dist3(r.point_a, r.point_b);
    CHECK(std::fabs(gap - r.distance) <= 1e-12 + 1e-9 * r.distance,
          "%s pose %d: witnesses %.17g apart, distance %.17g", what, st->poses, gap, r.distance);
    st->node_pairs += r.node_pairs;
    st->leaf_pairs += r.leaf_pairs;

    px_model_collide_result c;
    s = px_model_collide(a.tri.get(), &pa, b.tri.get(), &pb, ccache, &c);
    CHECK(s == PX_OK, "%s pose %d: px_model_collide %s", what, st->poses, px_status_string(s));
    const bool fc = fcl_collide(a, ta, b, tb);
    if (df == 0.0 && r.distance == 0.0) {
        st->crossing++;
        CHECK(c.hit == 1 && fc, "%s pose %d: surfaces cross; proxima hit %d, FCL %d", what, st->poses, c.hit,
              (int)fc);
    } else if (df > 1e-9) {
        st->apart++;
        CHECK(!fc, "%s pose %d: FCL collides at distance %.17g", what, st->poses, df);
        if (c.hit) {
            // Only a containment may make disjoint surfaces collide.
            st->contained++;
            const bool inside = some_vertex_inside(b, pb, a, pa) || some_vertex_inside(a, pa, b, pb);
            CHECK(c.contained == 1 && inside,
                  "%s pose %d: proxima hit at distance %.17g (contained %d, ray test %d)", what, st->poses,
                  df, c.contained, (int)inside);
        } else {
            // Not hit: the brute-force test must find no containment either.
            const bool inside = some_vertex_inside(b, pb, a, pa) || some_vertex_inside(a, pa, b, pb);
            CHECK(!inside, "%s pose %d: a containment proxima misses (distance %.17g)", what, st->poses, df);
        }
    } else {
        st->touching++;
    }
    st->poses++;
}

void report(const char *what, const Stats &st) {
    printf("%s: %d poses (%d crossing, %d apart of which %d contained, %d within 1e-9), max rel err vs FCL "
           "%.2e, "
           "%.1f node pairs and %.1f leaf pairs per distance query\n",
           what, st.poses, st.crossing, st.apart, st.contained, st.touching, st.max_rel,
           (double)st.node_pairs / std::max(1, st.poses), (double)st.leaf_pairs / std::max(1, st.poses));
}

// Random poses of B around A (A at the identity): random rotation, centre
// uniform in the ball of radius 0.9 (r_a + r_b), so that poses cross,
// touch, miss and (for a small B) nest.
void random_poses(const char *what, const Body &a, const Body &b, int n, uint64_t seed) {
    const double t0 = tu_now();
    Rng rng{seed};
    Stats st;
    px_model_cache dc{}, cc{};
    const double R = 0.9 * (a.radius + b.radius);
    for (int i = 0; i < n; ++i) {
        double u[3], r[9], t[3];
        rng.unit(u);
        rm::axis_angle(u, rng.range(0, M_PI), r);
        double d[3];
        rng.unit(d);
        const double rad = R * std::cbrt(rng.uniform());
        for (int k = 0; k < 3; ++k) t[k] = rad * d[k];
        const px_pose pb = rm::to_px(r, t);
        // cold and warm caches alternate: random poses share nothing
        check_pose(what, a, b, pb, (i & 1) ? &dc : nullptr, (i & 1) ? &cc : nullptr, &st);
    }
    px_model_cache_release(&dc);
    px_model_cache_release(&cc);
    report(what, st);
    printf("%s: %.2f s\n", what, tu_now() - t0);
    CHECK(st.crossing > 0 && st.apart > 0, "%s: the random poses should both cross and miss", what);
}

// B approaches A along a line, from 0.30 before first contact to 0.03 past
// it, turning a little each pose; warm caches throughout.
void approach(const char *what, const Body &a, const Body &b, int n, uint64_t seed) {
    const double t0 = tu_now();
    Rng rng{seed};
    rm::Approach ap;
    rng.unit(ap.dir);
    rng.unit(ap.axis);
    ap.rate = 0.5;
    ap.radius_b = b.radius;
    const double s0 = -(a.radius + b.radius) - 0.05;
    const double sc = rm::first_contact(a.tri.get(), b.tri.get(), ap, s0, 0.0);
    CHECK(std::isfinite(sc), "%s: no contact along the line", what);
    if (!std::isfinite(sc)) return;
    Stats st;
    px_model_cache dc{}, cc{};
    for (int i = 0; i < n; ++i) {
        const double s = sc - 0.30 + 0.33 * i / (n - 1);
        check_pose(what, a, b, ap.px_at(s), &dc, &cc, &st);
    }
    printf("%s: cache %zu + %zu bytes, %llu cold runs\n", what, dc.memory_bytes, cc.memory_bytes,
           (unsigned long long)(dc.cold_runs + cc.cold_runs));
    px_model_cache_release(&dc);
    px_model_cache_release(&cc);
    report(what, st);
    printf("%s: %.2f s\n", what, tu_now() - t0);
    CHECK(st.crossing > 0 && st.apart > 0, "%s: the approach should end crossing", what);
}

// A small bunny (an elephant under the sanitizers) inside the elephant's
// body: FCL's BVH collide says no (fcl #418), proxima says contained; both
// agree on the (positive) distance.
void containment(const Body &elephant, const Mesh &bunny_src) {
    Body small;
    small.mesh = bunny_src;
    rm::normalize(&small.mesh, 0.04);
    if (!make_body(&small, false)) return;
    double lo[3], hi[3];
    rm::bbox(elephant.mesh, lo, hi);
    // candidate centres on a grid, the first inside with room for the bunny
    const int g = 9;
    bool done = false;
    for (int i = 1; i < g && !done; ++i)
        for (int j = 1; j < g && !done; ++j)
            for (int k = 1; k < g && !done; ++k) {
                double c[3] = {lo[0] + (hi[0] - lo[0]) * i / g, lo[1] + (hi[1] - lo[1]) * j / g,
                               lo[2] + (hi[2] - lo[2]) * k / g};
                if (!rm::point_inside(elephant.mesh, c)) continue;
                const double id[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
                const px_pose pb = rm::to_px(id, c), pa = px_pose_identity();
                px_model_distance_result r;
                if (px_model_distance(elephant.tri.get(), &pa, small.tri.get(), &pb, nullptr, &r) != PX_OK)
                    continue;
                if (r.distance < 0.01) continue;
                done = true;
                const double df =
                    fcl_distance(elephant, rm::to_fcl(pa.r, &pa.t.x), small, rm::to_fcl(pb.r, &pb.t.x));
                CHECK(std::fabs(df - r.distance) <= 1e-9 * df, "containment: distance %.17g, FCL %.17g",
                      r.distance, df);
                px_model_collide_result cr;
                CHECK(px_model_collide(elephant.tri.get(), &pa, small.tri.get(), &pb, nullptr, &cr) == PX_OK,
                      "containment: collide failed");
                const bool fc =
                    fcl_collide(elephant, rm::to_fcl(pa.r, &pa.t.x), small, rm::to_fcl(pb.r, &pb.t.x));
                CHECK(cr.hit == 1 && cr.contained == 1, "containment: proxima hit %d contained %d", cr.hit,
                      cr.contained);
                printf("containment: %s (diagonal 0.04) inside the elephant at (%.3f, %.3f, %.3f), "
                       "distance %.4f: "
                       "proxima hit %d contained %d, FCL collide %d%s\n",
                       bunny_src.name.c_str(), c[0], c[1], c[2], r.distance, cr.hit, cr.contained, (int)fc,
                       fc ? "" : " (FCL misses containment, fcl #418)");
            }
    CHECK(done, "containment: no interior point with room for the bunny");
}

// Part hulls (or approximate pieces, `approx`) bracket the triangles'
// distance: parts.distance <= exact <= parts.upper_bound (exact from the
// triangle models, FCL-checked above).
void bracket(const char *what, const Body &a, const Body &b, int n, uint64_t seed, bool approx = false) {
    const double t0 = tu_now();
    Rng rng{seed};
    const px_model *ma = approx ? a.approx.get() : a.parts.get(),
                   *mb = approx ? b.approx.get() : b.parts.get();
    px_model_info ia, ib;
    px_model_get_info(ma, &ia);
    px_model_get_info(mb, &ib);
    const px_pose pa = px_pose_identity();
    const double R = 1.1 * (a.radius + b.radius);
    px_model_cache pc{}, tc{};
    int tight = 0, ok_count = 0;
    double max_width = 0;
    for (int i = 0; i < n; ++i) {
        double u[3], r[9], t[3], d[3];
        rng.unit(u);
        rm::axis_angle(u, rng.range(0, M_PI), r);
        rng.unit(d);
        const double rad = R * std::cbrt(rng.uniform());
        for (int k = 0; k < 3; ++k) t[k] = rad * d[k];
        const px_pose pb = rm::to_px(r, t);
        px_model_distance_result rp, rt;
        px_status s1 = px_model_distance(ma, &pa, mb, &pb, &pc, &rp);
        px_status s2 = px_model_distance(a.tri.get(), &pa, b.tri.get(), &pb, &tc, &rt);
        CHECK(s1 == PX_OK && s2 == PX_OK, "%s pose %d: %s / %s", what, i, px_status_string(s1),
              px_status_string(s2));
        if (s1 != PX_OK || s2 != PX_OK) continue;
        const double slack = 1e-12 + 1e-9 * rt.distance;
        const bool ok = rp.distance <= rt.distance + slack && rt.distance <= rp.upper_bound + slack;
        CHECK(ok, "%s pose %d: triangles %.17g outside the parts' bracket [%.17g, %.17g]", what, i,
              rt.distance, rp.distance, rp.upper_bound);
        ok_count += ok;
        tight += rp.upper_bound - rp.distance <= 0.05;
        max_width = std::max(max_width, rp.upper_bound - rp.distance);
    }
    px_model_cache_release(&pc);
    px_model_cache_release(&tc);
    printf("%s: %d pieces (max h %.4f) vs %d pieces (max h %.4f): %d/%d poses bracketed, widest bracket "
           "%.4f, %d "
           "within 0.05 (%.2f s)\n",
           what, ia.leaves, ia.max_h, ib.leaves, ib.max_h, ok_count, n, max_width, tight, tu_now() - t0);
}

// components: parts become the connected components (own readers); with
// px_loader the file goes through px_mesh_load and keeps its parts.
bool load(const std::string &path, Mesh *m, double diag, bool components, bool px_loader = false) {
    std::string err;
    bool ok = px_loader ? rm::load_with_px(path, m, &err) : rm::read_mesh_file(path, m, &err);
    CHECK(ok, "%s", err.c_str());
    if (!ok) return false;
    if (components) rm::split_components(m);
    rm::normalize(m, diag);
    return true;
}

} // namespace

int main() {
    tu_init("test_fcl_model");
    const bool asan = tu_sanitized();
    // Counts for about 25 s of CPU in Release on the 2-core machine (most of
    // it FCL, the brute-force inside tests and the bunny's build); fewer
    // under the sanitizers.
    const int n_random = tu_scaled(asan ? 12 : 100), n_approach = tu_scaled(asan ? 12 : 100);
    const int n_bracket = tu_scaled(asan ? 20 : 200);
    const std::string puma =
        std::string(PX_SOURCE_DIR) + "/models/puma560/nimasarli_puma560_description/meshes/";
    const std::string teapot = std::string(PX_SOURCE_DIR) + "/models/teapot/";

    // Two Puma links (closed meshes), read by px_mesh_load.
    {
        Body l2, l4;
        if (load(puma + "puma_link2.stl", &l2.mesh, 1.0, false, true) &&
            load(puma + "puma_link4.stl", &l4.mesh, 1.0, false, true) && make_body(&l2, true, 0.02) &&
            make_body(&l4, true, 0.02)) {
            random_poses("puma link2 vs link4, random", l2, l4, n_random, 1);
            approach("puma link2 vs link4, approach", l2, l4, n_approach, 2);
            bracket("puma link2 vs link4, part hulls", l2, l4, n_bracket, 3);
            bracket("puma link2 vs link4, approximate pieces (0.02)", l2, l4, n_bracket, 6, true);
        }
    }
    // The teapots: the closed OBJ (two groups) and the open STL.
    {
        Body t1, t2;
        if (load(teapot + "mcguire_cc0/teapot.obj", &t1.mesh, 1.0, false) &&
            load(teapot + "trimesh_mit/teapot.stl", &t2.mesh, 1.0, true) && make_body(&t1, true) &&
            make_body(&t2, true)) {
            random_poses("teapot obj vs teapot stl, random", t1, t2, n_random / 2 + 1, 4);
            bracket("teapot obj vs teapot stl, part hulls", t1, t2, n_bracket, 5);
        }
    }
    // Elephant against a scaled bunny00 (CGAL sample meshes). Under the
    // sanitizers bunny00's 75k-triangle build alone takes about a minute, so
    // the elephant meets a half-size elephant there instead.
    {
        Mesh e, bn;
        std::string err1, err2;
        const bool have_e = rm::load_cgal_mesh("elephant.off", &e, &err1);
        const bool have_b = asan ? have_e : rm::load_cgal_mesh("bunny00.off", &bn, &err2);
        if (asan) bn = e;
        const char *other = asan ? "elephant" : "bunny00";
        if (!have_e || !have_b) {
            printf("test_fcl_model: SKIP elephant vs %s: %s\n", other, (!have_e ? err1 : err2).c_str());
        } else {
            if (asan)
                printf("test_fcl_model: sanitizer build: elephant vs a half-size elephant, not bunny00\n");
            Body el, bu;
            el.mesh = e;
            bu.mesh = bn;
            rm::normalize(&el.mesh, 1.0);
            rm::normalize(&bu.mesh, 0.5);
            const double t0 = tu_now();
            if (make_body(&el, false) && make_body(&bu, false)) {
                printf("elephant (%zu triangles) and %s (%zu triangles): models built in %.2f s\n",
                       el.mesh.nt(), other, bu.mesh.nt(), tu_now() - t0);
                const std::string w = std::string("elephant vs ") + other;
                random_poses((w + ", random").c_str(), el, bu, n_random, 6);
                approach((w + ", approach").c_str(), el, bu, n_approach, 7);
                containment(el, bn);
            }
        }
    }
    return tu_finish();
}
