// bench_decomp: approximate convex decomposition, speed against error
// (issue 10 section 3). One run, same process, same meshes and poses:
//
//   meshes   bunny00, elephant, armadillo (CGAL sample meshes), Puma 560
//            link2 and link4 (nimasarli STL set, read by px_mesh_load), the
//            trimesh teapot (STL); every mesh scaled to a bounding-box
//            diagonal of 1 and centred
//   methods  proxima-approx     PX_PIECES_APPROXIMATE at tolerances 0.2, 0.1,
//                               0.05, 0.02, 0.01 (each part's diagonal)
//            bullet-cd          Bullet's ConvexDecomposition (J. Ratcliff's
//                               recursive splitter, libbullet-extras-dev):
//                               ConvexBuilder::process on each part, split
//                               depth and concavity percent refined
//                               together: (1, 5%), (2, 2%), (3, 1%),
//                               (5, 0.2%), (8, 0.02%) (mPpercent 3,
//                               mMaxVertices 64, no skin width)
//            bullet-hacd        Bullet's HACD (K. Mamou): HACD::Compute on
//                               each part, concavity swept (scale factor
//                               1000, 1 cluster at least, 100 vertices per
//                               hull), meshes up to --hacd-max-tris only
//            proxima-parts      one hull per part (PX_PIECES_PARTS)
//            proxima-triangles  the exact triangle leaves (the reference)
//            Bullet's hulls become a model through
//            px_model_create_from_points (h = 0: no bound is claimed).
//   counts   pieces = the model's leaves; hull_vertices = the sum over
//            pieces of px_convex_vertex_count of the piece's hull. proxima
//            has no public accessor for a leaf's hull, so its pieces are
//            built a second time with pxcd_decompose (same inputs and
//            options as src/model/approx.c: the px_mesh's own vertices,
//            each part alone, the same threads) and hulled by px_convex_create, as
//            approx.c does; the piece counts must agree (a determinism
//            check). decomp_s is that pxcd_decompose alone, build_s the
//            whole px_model_create_from_mesh (decomposition, certification
//            of every h, tree).
//   motion   a copy of the same mesh (the same model object: both bodies
//            are represented by the method under test) approaches the mesh
//            as in bench_models: along a straight line from 0.30 before
//            first contact of the triangle surfaces to 0.03 past it in 200
//            poses, turning by 1 rad per unit travelled (0.1 degree per
//            pose)
//   timing   every px_model_distance timed alone (clock_gettime), the
//            px_model_cache warm along the sequence (released before each
//            pass); `passes` runs of the sequence, per pose the median over
//            passes, then the median over poses
//   errors   against the exact triangle-leaf distance d_exact at the same
//            poses: max over poses of |d_model - d_exact| (diagonal 1);
//            bracket_ok: d_model <= d_exact <= upper_bound on every pose
//            (up to 1e-12 + 1e-9 d_exact); lower_ok: d_model <= d_exact on
//            every pose (the hulls cover the mesh where it matters)
//   probes   the approach sees the mesh along one line, where one hull is
//            often as good as many; the probe error does not depend on a
//            direction: max over a fixed set of probe points p of
//            |d_model(p) - d_exact(p)|, each p a one-point px_convex and
//            both distances px_model_distance_convex (cold, no cache).
//            Probes (per mesh, seeded): 1000 far ones, along random
//            directions from the box's centre, from the bounding box out to
//            0.3 beyond it; 1000 near ones, at area-weighted random points
//            of the triangles moved 0 to 0.1 along the triangle's normal,
//            to the side outside the solid (closed meshes: a probe inside
//            on both sides, or touching, is drawn again; open meshes: the
//            normal's side as wound). Coverage error: max over up to 2000
//            mesh vertices (every k-th) of d_model(vertex), 0 where the
//            pieces cover the mesh
//   threads  proxima's builds and pxcd_decompose use --threads (default 2,
//            the machine's cores); Bullet's decomposers are single-threaded
//
// Bullet's decomposers run in a forked child (they may crash or run for a
// long time on large meshes: HACD is quadratic-ish); the child sends its
// hulls back through a pipe and is killed after --bullet-timeout seconds.
// Writes decomposition.csv, decomposition.md and decomposition_curves.dat
// (plot_decomposition.gp draws decomposition.png from it) into --out.
//
//   bench_decomp [--meshes DIR] [--models DIR] [--out DIR] [--passes N]
//                [--only NAME] [--tolerances LIST] [--quick] [--threads N]
//                [--bullet-timeout S] [--hacd-max-tris N]
//                [--cd D:C,D:C] [--hacd C,C]
// --quick: Puma link2 only, tolerances 0.1 and 0.05, two ConvexDecomposition
// settings, no HACD, 40 poses, one pass (the smoke test).
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <functional>

#include "bench_common.h"
#include "pxcd.h"
#include "real_meshes.h"

#ifdef PROXIMA_BENCH_BULLET
#include <ConvexDecomposition/ConvexBuilder.h>
#include <ConvexDecomposition/ConvexDecomposition.h>
#include <HACD/hacdHACD.h>
#endif

namespace {

using bench::now_ns;
using bench::percentile;
using rm::Mesh;

// ---- Meshes -------------------------------------------------------------------

struct ConvexDeleter {
    void operator()(px_convex *c) const { px_convex_destroy(c); }
};
using ConvexPtr = std::unique_ptr<px_convex, ConvexDeleter>;

struct Subject {
    std::string name;
    Mesh mesh;
    rm::MeshPtr px_mesh;
    rm::ModelPtr tri;              // exact reference
    std::vector<double> part_diag; // per part of px_mesh
    double radius = 0;
    // Probe points (one-point polytopes) with their exact distances, and
    // the mesh vertices sampled for coverage.
    std::vector<ConvexPtr> probes, cover;
    std::vector<double> probe_exact;
    size_t probes_far = 0, probes_near = 0, probes_redrawn = 0;
    bool closed = false;
};

// The px_mesh's part p as its own vertices and local triangles (what
// approx.c gives pxcd_decompose).
struct PartMesh {
    std::vector<double> xyz;
    std::vector<uint32_t> tri;
    int closed = 0;
};

PartMesh part_mesh(const px_mesh *m, uint32_t p) {
    px_mesh_part mp;
    px_mesh_get_part(m, p, &mp);
    PartMesh out;
    const double *v = px_mesh_vertices(m);
    const uint32_t *t = px_mesh_triangles(m);
    out.xyz.assign(v + 3 * (size_t)mp.first_vertex, v + 3 * ((size_t)mp.first_vertex + mp.vertex_count));
    out.tri.resize(3 * (size_t)mp.triangle_count);
    for (size_t i = 0; i < out.tri.size(); ++i)
        out.tri[i] = t[3 * (size_t)mp.first_triangle + i] - mp.first_vertex;
    out.closed = (int)mp.closed;
    return out;
}

double diag_of(const std::vector<double> &xyz, const std::vector<uint32_t> &tri) {
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (uint32_t i : tri)
        for (int k = 0; k < 3; ++k)
            lo[k] = std::min(lo[k], xyz[3 * (size_t)i + k]), hi[k] = std::max(hi[k], xyz[3 * (size_t)i + k]);
    double d2 = 0;
    for (int k = 0; k < 3; ++k) d2 += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    return tri.empty() ? 0 : std::sqrt(d2);
}

bool prepare(Subject *s) {
    std::string err;
    s->px_mesh = rm::make_px_mesh(s->mesh, &err);
    if (!s->px_mesh) return fprintf(stderr, "%s: %s\n", s->name.c_str(), err.c_str()), false;
    s->tri = rm::make_model(s->px_mesh.get(), PX_PIECES_TRIANGLES, &err);
    if (!s->tri) return fprintf(stderr, "%s: %s\n", s->name.c_str(), err.c_str()), false;
    for (uint32_t p = 0; p < px_mesh_part_count(s->px_mesh.get()); ++p) {
        PartMesh pm = part_mesh(s->px_mesh.get(), p);
        s->part_diag.push_back(diag_of(pm.xyz, pm.tri));
    }
    s->radius = rm::max_radius(s->mesh);
    px_mesh_info mi;
    px_mesh_get_info(s->px_mesh.get(), &mi);
    fprintf(stderr, "%s: %zu triangles, %zu vertices, %u parts (%u closed)\n", s->name.c_str(), s->mesh.nt(),
            s->mesh.nv(), px_mesh_part_count(s->px_mesh.get()), mi.closed_parts);
    return true;
}

// ---- Probe points -----------------------------------------------------------------

ConvexPtr point_convex(const double p[3]) {
    px_error e{};
    return ConvexPtr(px_convex_create(p, 1, nullptr, &e));
}

double point_distance(const px_model *m, const px_convex *pt) {
    const px_pose id = px_pose_identity();
    px_model_distance_result r;
    if (px_model_distance_convex(m, &id, pt, &id, nullptr, &r) != PX_OK) return NAN;
    return r.distance;
}

// 1 when the point lies in the triangle model's solid or touches it.
bool point_hits(const px_model *m, const px_convex *pt) {
    const px_pose id = px_pose_identity();
    px_model_collide_result r;
    return px_model_collide_convex(m, &id, pt, &id, nullptr, &r) == PX_OK && r.hit;
}

// The probe points of the header comment, seeded by the mesh's index.
void make_probes(Subject *s, size_t n_far, size_t n_near, size_t n_cover, uint64_t seed) {
    pg_sm rng = {seed};
    const Mesh &m = s->mesh;
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (size_t i = 0; i < m.nv(); ++i)
        for (int k = 0; k < 3; ++k)
            lo[k] = std::min(lo[k], m.xyz[3 * i + k]), hi[k] = std::max(hi[k], m.xyz[3 * i + k]);
    px_mesh_info mi;
    px_mesh_get_info(s->px_mesh.get(), &mi);
    s->closed = mi.closed_parts == px_mesh_part_count(s->px_mesh.get());
    auto add = [&](const double p[3]) {
        ConvexPtr c = point_convex(p);
        if (!c) return false;
        s->probe_exact.push_back(point_distance(s->tri.get(), c.get()));
        s->probes.push_back(std::move(c));
        return true;
    };
    // Far: from the box's boundary along u out to 0.3 beyond it.
    for (size_t i = 0; i < n_far; ++i) {
        const bench::V3 u = pg_sm_unit(&rng);
        const double uu[3] = {u.x, u.y, u.z};
        double to_box = HUGE_VAL;
        for (int k = 0; k < 3; ++k)
            if (uu[k] != 0) to_box = std::min(to_box, 0.5 * (hi[k] - lo[k]) / std::fabs(uu[k]));
        const double t = to_box + 0.3 * pg_sm_uniform(&rng);
        double p[3];
        for (int k = 0; k < 3; ++k) p[k] = 0.5 * (lo[k] + hi[k]) + t * uu[k];
        s->probes_far += add(p);
    }
    // Near: area-weighted points of the triangles, moved along the normal.
    std::vector<double> cum(m.nt());
    double total = 0;
    for (size_t t = 0; t < m.nt(); ++t) {
        const double *a = &m.xyz[3 * (size_t)m.tri[3 * t]], *b = &m.xyz[3 * (size_t)m.tri[3 * t + 1]],
                     *c = &m.xyz[3 * (size_t)m.tri[3 * t + 2]];
        const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]},
                     e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                             e1[0] * e2[1] - e1[1] * e2[0]};
        total += 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        cum[t] = total;
    }
    for (size_t tries = 0; s->probes_near < n_near && tries < 20 * n_near && total > 0; ++tries) {
        const size_t t = std::min<size_t>(
            std::lower_bound(cum.begin(), cum.end(), pg_sm_uniform(&rng) * total) - cum.begin(), m.nt() - 1);
        const double *a = &m.xyz[3 * (size_t)m.tri[3 * t]], *b = &m.xyz[3 * (size_t)m.tri[3 * t + 1]],
                     *c = &m.xyz[3 * (size_t)m.tri[3 * t + 2]];
        const double r1 = std::sqrt(pg_sm_uniform(&rng)), r2 = pg_sm_uniform(&rng);
        const double wa = 1 - r1, wb = r1 * (1 - r2), wc = r1 * r2, delta = 0.1 * pg_sm_uniform(&rng);
        const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]},
                     e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                       e1[0] * e2[1] - e1[1] * e2[0]};
        const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (!(len > 0)) continue;
        bool placed = false;
        for (int side = 1; side >= -1 && !placed; side -= 2) {
            double p[3];
            for (int k = 0; k < 3; ++k) p[k] = wa * a[k] + wb * b[k] + wc * c[k] + side * delta * n[k] / len;
            if (s->closed) {
                ConvexPtr pc = point_convex(p);
                if (!pc || point_hits(s->tri.get(), pc.get())) continue;
            } else if (side < 0) {
                break;
            }
            placed = add(p);
        }
        if (placed)
            ++s->probes_near;
        else
            ++s->probes_redrawn;
    }
    // Coverage: every k-th vertex.
    const size_t step = std::max<size_t>(1, m.nv() / n_cover);
    for (size_t i = 0; i < m.nv(); i += step)
        if (ConvexPtr c = point_convex(&m.xyz[3 * i])) s->cover.push_back(std::move(c));
    fprintf(stderr, "  probes: %zu far, %zu near (%zu redrawn), %zu vertices for coverage\n", s->probes_far,
            s->probes_near, s->probes_redrawn, s->cover.size());
}

// ---- The approach sequence and its measurement ----------------------------------

struct Sequence {
    std::vector<px_pose> poses;
    std::vector<double> s_rel, d_exact;
    double tri_median_ns = NAN; // the triangle models' own time (the exact row)
};

Sequence make_sequence(const Subject &s, int n, int passes, uint64_t seed) {
    Sequence q;
    pg_sm rng = {seed};
    const bench::V3 dir = pg_sm_unit(&rng), axis = pg_sm_unit(&rng);
    rm::Approach ap;
    ap.dir[0] = dir.x, ap.dir[1] = dir.y, ap.dir[2] = dir.z;
    ap.axis[0] = axis.x, ap.axis[1] = axis.y, ap.axis[2] = axis.z;
    ap.rate = 1.0;
    ap.radius_b = s.radius;
    const double s0 = -2 * s.radius - 0.05;
    const double sc = rm::first_contact(s.tri.get(), s.tri.get(), ap, s0, 0.0);
    if (!std::isfinite(sc)) return q;
    for (int i = 0; i < n; ++i) {
        const double si = sc - 0.30 + 0.33 * i / (n - 1);
        q.poses.push_back(ap.px_at(si));
        q.s_rel.push_back(si - sc);
    }
    // The exact distances, and the triangle models' time (same protocol).
    const px_pose pa = px_pose_identity();
    std::vector<std::vector<double>> t(n, std::vector<double>(passes));
    q.d_exact.assign(n, 0);
    for (int p = 0; p < passes; ++p) {
        px_model_cache c{};
        for (int i = 0; i < n; ++i) {
            px_model_distance_result r;
            const double t0 = now_ns();
            px_model_distance(s.tri.get(), &pa, s.tri.get(), &q.poses[i], &c, &r);
            t[i][p] = now_ns() - t0;
            if (p == 0) q.d_exact[i] = r.distance;
        }
        px_model_cache_release(&c);
    }
    std::vector<double> med(n);
    for (int i = 0; i < n; ++i) med[i] = percentile(t[i], 0.5);
    q.tri_median_ns = percentile(med, 0.5);
    return q;
}

struct Measure {
    double median_ns = NAN, p90_ns = NAN, max_err = NAN, max_width = NAN;
    double probe_err = NAN, cover_err = NAN; // over the probes and the sampled vertices
    int bracket_ok = -1, lower_ok = -1;
    size_t cache_bytes = 0;
};

// The probe and coverage errors of model m.
void measure_probes(const px_model *m, const Subject &s, Measure *out) {
    out->probe_err = 0, out->cover_err = 0;
    for (size_t i = 0; i < s.probes.size(); ++i)
        out->probe_err =
            std::max(out->probe_err, std::fabs(point_distance(m, s.probes[i].get()) - s.probe_exact[i]));
    for (auto &c : s.cover) out->cover_err = std::max(out->cover_err, point_distance(m, c.get()));
}

Measure measure(const px_model *m, const Sequence &q, int passes) {
    Measure out;
    const size_t n = q.poses.size();
    const px_pose pa = px_pose_identity();
    std::vector<std::vector<double>> t(n, std::vector<double>(passes));
    std::vector<double> d(n), ub(n);
    for (int p = 0; p < passes; ++p) {
        px_model_cache c{};
        for (size_t i = 0; i < n; ++i) {
            px_model_distance_result r;
            const double t0 = now_ns();
            px_model_distance(m, &pa, m, &q.poses[i], &c, &r);
            t[i][p] = now_ns() - t0;
            if (p == 0) d[i] = r.distance, ub[i] = r.upper_bound;
        }
        out.cache_bytes = c.memory_bytes;
        px_model_cache_release(&c);
    }
    std::vector<double> med(n);
    for (size_t i = 0; i < n; ++i) med[i] = percentile(t[i], 0.5);
    out.median_ns = percentile(med, 0.5);
    out.p90_ns = percentile(med, 0.9);
    out.max_err = 0, out.max_width = 0, out.bracket_ok = 1, out.lower_ok = 1;
    for (size_t i = 0; i < n; ++i) {
        const double de = q.d_exact[i], slack = 1e-12 + 1e-9 * de;
        out.max_err = std::max(out.max_err, std::fabs(d[i] - de));
        out.max_width = std::max(out.max_width, ub[i] - d[i]);
        if (!(d[i] <= de + slack)) out.lower_ok = 0, out.bracket_ok = 0;
        if (!(de <= ub[i] + slack)) out.bracket_ok = 0;
    }
    return out;
}

// ---- Rows -----------------------------------------------------------------------

struct Row {
    std::string method, mesh, params, note;
    double tolerance = NAN;
    size_t pieces = 0, hull_vertices = 0, memory_bytes = 0;
    double max_h = NAN, build_s = NAN, decomp_s = NAN;
    // proxima-approx: leaves whose certified h exceeds tolerance * part
    // diagonal, and the largest h / (tolerance * part diagonal).
    size_t pieces_h_over_tol = 0;
    double worst_h_ratio = NAN;
    unsigned threads = 0; // proxima-approx: options.threads (0: not threaded)
    Measure m;
    bool failed = false;
};

// Sum of hull vertex counts of point sets (px_convex_create on each);
// (*ok)[i] is 0 for a set px_convex_create refuses (not counted).
size_t hull_vertices(const std::vector<std::vector<double>> &sets, std::vector<int> *ok) {
    size_t total = 0;
    ok->assign(sets.size(), 0);
    for (size_t i = 0; i < sets.size(); ++i) {
        px_error e{};
        px_convex *c = px_convex_create(sets[i].data(), sets[i].size() / 3, nullptr, &e);
        if (!c) continue;
        (*ok)[i] = 1;
        total += px_convex_vertex_count(c);
        px_convex_destroy(c);
    }
    return total;
}

// A model from point sets (the peers' hulls), sets px_convex_create refuses
// left out (counted in *dropped).
rm::ModelPtr model_from_sets(const std::vector<std::vector<double>> &sets, size_t *hv, size_t *dropped,
                             std::string *err) {
    std::vector<int> ok;
    *hv = hull_vertices(sets, &ok);
    std::vector<double> xyz;
    std::vector<uint32_t> ends;
    *dropped = 0;
    for (size_t i = 0; i < sets.size(); ++i) {
        if (!ok[i]) {
            ++*dropped;
            continue;
        }
        xyz.insert(xyz.end(), sets[i].begin(), sets[i].end());
        ends.push_back((uint32_t)(xyz.size() / 3));
    }
    if (ends.empty()) return *err = "no usable hull", rm::ModelPtr();
    px_error e{};
    px_model_options o{};
    px_model *m = px_model_create_from_points(xyz.data(), ends.data(), (uint32_t)ends.size(), &o, &e);
    if (!m) *err = std::string("px_model_create_from_points: ") + e.message;
    return rm::ModelPtr(m);
}

void fill_info(Row *r, const px_model *m) {
    px_model_info info;
    px_model_get_info(m, &info);
    r->pieces = info.leaves;
    r->max_h = info.max_h;
    r->memory_bytes = info.memory_bytes;
}

Row run_approx(const Subject &s, double tol, unsigned threads, const Sequence &q, int passes) {
    Row r;
    r.method = "proxima-approx";
    r.mesh = s.name;
    r.tolerance = tol;
    char pb[64];
    snprintf(pb, sizeof pb, "tolerance=%g", tol);
    r.params = pb;
    // The model, timed whole.
    px_model_options o{};
    o.pieces = PX_PIECES_APPROXIMATE;
    o.tolerance = tol;
    o.threads = threads;
    r.threads = threads;
    px_error e{};
    double t0 = now_ns();
    rm::ModelPtr m(px_model_create_from_mesh(s.px_mesh.get(), &o, &e));
    r.build_s = (now_ns() - t0) * 1e-9;
    if (!m) {
        // The decomposition alone still gives pieces, hull vertices and its
        // time (below); nothing is measured on the approach.
        r.failed = true;
        r.note = std::string("px_model_create_from_mesh failed: ") + e.message + "; ";
        fprintf(stderr, "  %s tol %g: %s\n", s.name.c_str(), tol, e.message);
    } else {
        fill_info(&r, m.get());
    }
    r.worst_h_ratio = 0;
    for (uint32_t i = 0; m && i < r.pieces; ++i) {
        px_model_leaf lf;
        px_model_get_leaf(m.get(), i, &lf);
        const double lim = tol * (lf.part < s.part_diag.size() ? s.part_diag[lf.part] : 1.0);
        if (lf.h > lim) ++r.pieces_h_over_tol;
        if (lim > 0) r.worst_h_ratio = std::max(r.worst_h_ratio, lf.h / lim);
    }
    // The same pieces again, for their hull vertex counts.
    size_t pieces = 0;
    r.hull_vertices = 0;
    r.decomp_s = 0;
    for (uint32_t p = 0; p < px_mesh_part_count(s.px_mesh.get()); ++p) {
        PartMesh pm = part_mesh(s.px_mesh.get(), p);
        if (pm.tri.empty()) {
            ++pieces;
            continue;
        }
        pxcd_decomp_options d{};
        d.tolerance = tol;
        d.threads = threads;
        pxcd_decomp_result *res = nullptr;
        char msg[256] = "";
        t0 = now_ns();
        pxcd_status st = pxcd_decompose(pm.xyz.data(), pm.xyz.size() / 3, pm.tri.data(), pm.tri.size() / 3,
                                        &d, &res, msg, sizeof msg);
        r.decomp_s += (now_ns() - t0) * 1e-9;
        if (st != PXCD_OK) {
            r.note += std::string("pxcd_decompose: ") + msg + "; ";
            continue;
        }
        std::vector<std::vector<double>> sets;
        for (size_t i = 0; i < res->piece_count; ++i)
            sets.emplace_back(res->pieces[i].vertices,
                              res->pieces[i].vertices + 3 * res->pieces[i].vertex_count);
        std::vector<int> ok;
        r.hull_vertices += hull_vertices(sets, &ok);
        pieces += res->piece_count;
        pxcd_decomp_free(res);
    }
    if (!m) {
        r.pieces = pieces; // from pxcd_decompose
        return r;
    }
    if (pieces != r.pieces) {
        r.note += "second pxcd_decompose gave " + std::to_string(pieces) + " pieces, the model " +
                  std::to_string(r.pieces) + "; ";
        fprintf(stderr, "  %s tol %g: piece counts differ (%zu vs %zu)\n", s.name.c_str(), tol, pieces,
                r.pieces);
    }
    r.m = measure(m.get(), q, passes);
    measure_probes(m.get(), s, &r.m);
    fprintf(stderr,
            "  approx tol %-5g %4zu pieces %6zu hull vertices, max_h %.4f (%zu over tol), build %.2f s "
            "(decompose %.2f s), %s us, err %.4f, probe err %.4f, cover err %.4f, bracket %s\n",
            tol, r.pieces, r.hull_vertices, r.max_h, r.pieces_h_over_tol, r.build_s, r.decomp_s,
            bench::fmt_us(r.m.median_ns).c_str(), r.m.max_err, r.m.probe_err, r.m.cover_err,
            r.m.bracket_ok ? "ok" : "BROKEN");
    return r;
}

Row run_builtin(const Subject &s, uint32_t pieces, const Sequence &q, int passes) {
    Row r;
    r.method = pieces == PX_PIECES_PARTS ? "proxima-parts" : "proxima-triangles";
    r.mesh = s.name;
    std::string err;
    const double t0 = now_ns();
    rm::ModelPtr m = rm::make_model(s.px_mesh.get(), pieces, &err);
    r.build_s = (now_ns() - t0) * 1e-9;
    if (!m) {
        r.failed = true;
        r.note = err;
        return r;
    }
    fill_info(&r, m.get());
    if (pieces == PX_PIECES_PARTS) {
        std::vector<std::vector<double>> sets;
        for (uint32_t p = 0; p < px_mesh_part_count(s.px_mesh.get()); ++p)
            sets.push_back(part_mesh(s.px_mesh.get(), p).xyz);
        std::vector<int> ok;
        r.hull_vertices = hull_vertices(sets, &ok);
    }
    r.m = measure(m.get(), q, passes);
    measure_probes(m.get(), s, &r.m);
    fprintf(stderr, "  %s: %zu pieces, %s us, err %.4f, probe err %.4f, cover err %.4f, bracket %s\n",
            r.method.c_str(), r.pieces, bench::fmt_us(r.m.median_ns).c_str(), r.m.max_err, r.m.probe_err,
            r.m.cover_err, r.m.bracket_ok ? "ok" : "BROKEN");
    return r;
}

// ---- Bullet's decomposers, in a child process --------------------------------------

// What a child sends back: seconds, then the hulls (float coordinates as
// Bullet produces them, widened to double).
struct PeerResult {
    bool ok = false;
    std::string why; // when not ok: crashed, timed out, failed
    double seconds = NAN;
    std::vector<std::vector<double>> hulls;
};

bool write_all(int fd, const void *p, size_t n) {
    const char *c = (const char *)p;
    while (n) {
        ssize_t k = write(fd, c, n);
        if (k <= 0) return false;
        c += k, n -= (size_t)k;
    }
    return true;
}

// Runs `work` (which fills hulls) in a forked child, at most timeout_s.
PeerResult run_child(const std::function<void(std::vector<std::vector<double>> *)> &work, double timeout_s) {
    PeerResult out;
    int fds[2];
    if (pipe(fds) != 0) return out.why = "pipe failed", out;
    fflush(stdout);
    fflush(stderr);
    pid_t pid = fork();
    if (pid < 0) {
        close(fds[0]);
        close(fds[1]);
        return out.why = "fork failed", out;
    }
    if (pid == 0) {
        close(fds[0]);
        std::vector<std::vector<double>> hulls;
        const double t0 = now_ns();
        work(&hulls);
        const double secs = (now_ns() - t0) * 1e-9;
        uint64_t nh = hulls.size();
        bool w = write_all(fds[1], &secs, sizeof secs) && write_all(fds[1], &nh, sizeof nh);
        for (auto &h : hulls) {
            uint64_t k = h.size();
            w = w && write_all(fds[1], &k, sizeof k) && write_all(fds[1], h.data(), k * sizeof(double));
        }
        close(fds[1]);
        _exit(w ? 0 : 3);
    }
    close(fds[1]);
    std::string buf;
    const double deadline = now_ns() + timeout_s * 1e9;
    bool timed_out = false;
    for (;;) {
        const double left_ms = (deadline - now_ns()) * 1e-6;
        if (left_ms <= 0) {
            timed_out = true;
            break;
        }
        struct pollfd pf = {fds[0], POLLIN, 0};
        int pr = poll(&pf, 1, (int)std::min(left_ms, 1000.0) + 1);
        if (pr < 0) {
            if (errno == EINTR) continue;
            break;
        }
        if (pr == 0) continue;
        char tmp[1 << 16];
        ssize_t k = read(fds[0], tmp, sizeof tmp);
        if (k < 0 && errno == EINTR) continue;
        if (k <= 0) break;
        buf.append(tmp, (size_t)k);
    }
    close(fds[0]);
    if (timed_out) kill(pid, SIGKILL);
    int status = 0;
    waitpid(pid, &status, 0);
    if (timed_out) {
        char b[64];
        snprintf(b, sizeof b, "timed out after %.0f s", timeout_s);
        return out.why = b, out;
    }
    if (WIFSIGNALED(status))
        return out.why = "crashed (signal " + std::to_string(WTERMSIG(status)) + ")", out;
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) return out.why = "child failed", out;
    size_t at = 0;
    auto take = [&](void *dst, size_t n) {
        if (at + n > buf.size()) return false;
        memcpy(dst, buf.data() + at, n);
        at += n;
        return true;
    };
    uint64_t nh = 0;
    if (!take(&out.seconds, sizeof out.seconds) || !take(&nh, sizeof nh)) return out.why = "short reply", out;
    for (uint64_t i = 0; i < nh; ++i) {
        uint64_t k = 0;
        if (!take(&k, sizeof k) || k > buf.size()) return out.why = "short reply", out;
        std::vector<double> h(k);
        if (!take(h.data(), k * sizeof(double))) return out.why = "short reply", out;
        out.hulls.push_back(std::move(h));
    }
    out.ok = true;
    return out;
}

// ConvexDecomposition's input scale (its float code has absolute
// epsilons; hulls are scaled back) and hull vertex cap (--cd-scale,
// --cd-maxv).
double g_cd_scale = 1.0;
unsigned g_cd_maxv = 64;

#ifdef PROXIMA_BENCH_BULLET

// Collects ConvexBuilder's hulls.
struct Collect : ConvexDecomposition::ConvexDecompInterface {
    std::vector<std::vector<double>> *hulls = nullptr;
    void ConvexDecompResult(ConvexDecomposition::ConvexResult &r) override {
        std::vector<double> h(r.mHullVertices, r.mHullVertices + 3 * (size_t)r.mHullVcount);
        hulls->push_back(std::move(h));
    }
};

// Ratcliff's splitter on each part: split planes down to `depth`, while the
// concavity exceeds cpercent of the volume, then ConvexBuilder's merge of
// hulls whose union loses less than ppercent, each hull at most max_vertices.
void bullet_cd(const px_mesh *mesh, unsigned depth, float cpercent, float ppercent, unsigned max_vertices,
               std::vector<std::vector<double>> *hulls) {
    for (uint32_t p = 0; p < px_mesh_part_count(mesh); ++p) {
        PartMesh pm = part_mesh(mesh, p);
        if (pm.tri.empty()) continue;
        std::vector<float> v(pm.xyz.size());
        for (size_t i = 0; i < v.size(); ++i) v[i] = (float)(pm.xyz[i] * g_cd_scale);
        const size_t first = hulls->size();
        Collect sink;
        sink.hulls = hulls;
        ConvexDecomposition::DecompDesc d;
        d.mVcount = (unsigned)(v.size() / 3);
        d.mVertices = v.data();
        d.mTcount = (unsigned)(pm.tri.size() / 3);
        d.mIndices = pm.tri.data();
        d.mDepth = depth;
        d.mCpercent = cpercent;
        d.mPpercent = ppercent;
        d.mMaxVertices = max_vertices;
        d.mSkinWidth = 0;
        d.mCallback = &sink;
        // ConvexBuilder::process: calcConvexDecomposition with this depth and
        // concavity percent, then its merge pass (a no-op in this version:
        // ConvexBuilder::getMesh's body is compiled out, so canMerge never
        // sees triangles), then each hull regenerated with at most
        // mMaxVertices vertices. performConvexDecomposition is declared in
        // the header but not in Debian's library.
        ConvexBuilder cb(d.mCallback);
        cb.process(d);
        for (size_t i = first; i < hulls->size(); ++i)
            for (double &x : (*hulls)[i]) x /= g_cd_scale;
    }
}

// Mamou's HACD on each part: bottom-up clustering of the triangle graph
// until merging would exceed `concavity` (in HACD's units: the mesh is
// scaled so that its bounding-box diagonal is 2 * scale = 2000).
void bullet_hacd(const px_mesh *mesh, double concavity, std::vector<std::vector<double>> *hulls) {
    for (uint32_t p = 0; p < px_mesh_part_count(mesh); ++p) {
        PartMesh pm = part_mesh(mesh, p);
        if (pm.tri.empty()) continue;
        std::vector<HACD::Vec3<HACD::Real>> pts;
        for (size_t i = 0; i < pm.xyz.size() / 3; ++i)
            pts.emplace_back(pm.xyz[3 * i], pm.xyz[3 * i + 1], pm.xyz[3 * i + 2]);
        std::vector<HACD::Vec3<long>> tris;
        for (size_t i = 0; i < pm.tri.size() / 3; ++i)
            tris.emplace_back((long)pm.tri[3 * i], (long)pm.tri[3 * i + 1], (long)pm.tri[3 * i + 2]);
        HACD::HACD h;
        h.SetPoints(pts.data());
        h.SetNPoints(pts.size());
        h.SetTriangles(tris.data());
        h.SetNTriangles(tris.size());
        h.SetScaleFactor(1000.0);
        h.SetCompacityWeight(0.1);
        h.SetVolumeWeight(0.0);
        h.SetNClusters(1);
        h.SetNVerticesPerCH(100);
        h.SetConcavity(concavity);
        h.SetAddExtraDistPoints(false);
        h.SetAddNeighboursDistPoints(false);
        h.SetAddFacesPoints(false);
        h.Compute();
        for (size_t c = 0; c < h.GetNClusters(); ++c) {
            const size_t np = h.GetNPointsCH(c), nt = h.GetNTrianglesCH(c);
            std::vector<HACD::Vec3<HACD::Real>> cp(np);
            std::vector<HACD::Vec3<long>> ct(nt);
            h.GetCH(c, cp.data(), ct.data());
            std::vector<double> out;
            for (auto &q : cp) out.insert(out.end(), {q.X(), q.Y(), q.Z()});
            hulls->push_back(std::move(out));
        }
    }
}
#endif

Row run_peer(const Subject &s, const std::string &method, const std::string &params,
             const std::function<void(std::vector<std::vector<double>> *)> &work, double timeout_s,
             const Sequence &q, int passes) {
    Row r;
    r.method = method;
    r.mesh = s.name;
    r.params = params;
    PeerResult pr = run_child(work, timeout_s);
    if (!pr.ok) {
        r.failed = true;
        r.note = pr.why;
        fprintf(stderr, "  %s %s: %s\n", method.c_str(), params.c_str(), pr.why.c_str());
        return r;
    }
    r.build_s = pr.seconds;
    r.decomp_s = pr.seconds;
    size_t dropped = 0;
    std::string err;
    rm::ModelPtr m = model_from_sets(pr.hulls, &r.hull_vertices, &dropped, &err);
    if (dropped)
        r.note += std::to_string(dropped) + " of " + std::to_string(pr.hulls.size()) +
                  " hulls refused by px_convex_create (left out); ";
    if (!m) {
        r.failed = true;
        r.note += err;
        fprintf(stderr, "  %s %s: %s\n", method.c_str(), params.c_str(), err.c_str());
        return r;
    }
    fill_info(&r, m.get());
    r.m = measure(m.get(), q, passes);
    measure_probes(m.get(), s, &r.m);
    r.m.bracket_ok = -1; // no bound claimed (h = 0); lower_ok says whether the hulls cover
    fprintf(stderr,
            "  %s %-24s %4zu pieces %6zu hull vertices, %.2f s, %s us, err %.4f, probe err %.4f, cover err "
            "%.4f, lower bound %s\n",
            method.c_str(), params.c_str(), r.pieces, r.hull_vertices, r.build_s,
            bench::fmt_us(r.m.median_ns).c_str(), r.m.max_err, r.m.probe_err, r.m.cover_err,
            r.m.lower_ok ? "ok" : "broken");
    return r;
}

// ---- Output ----------------------------------------------------------------------

std::string num(double v, const char *fmt = "%.6g") {
    if (!(v == v)) return "";
    char b[64];
    snprintf(b, sizeof b, fmt, v);
    return b;
}

std::string flag(int v) { return v < 0 ? "" : std::to_string(v); }

const char *const kMeshes[] = {"bunny00", "elephant", "armadillo", "puma-link2", "puma-link4", "teapot"};
const char *const kCurves[] = {"proxima-approx", "bullet-cd", "bullet-hacd", "proxima-parts"};

} // namespace

int main(int argc, char **argv) {
    std::string meshes = "build/meshdata", models = "models", out_dir = "docs/bench", only;
    int passes = 5, n = 200;
    bool quick = false;
    double bullet_timeout = 180;
    size_t hacd_max_tris = 4000;
    unsigned threads = 2;
    std::vector<double> tols = {0.2, 0.1, 0.05, 0.02, 0.01};
    const char *cd_arg = nullptr, *hacd_arg = nullptr;
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
        else if (a == "--only" && i + 1 < argc)
            only = argv[++i];
        else if (a == "--tolerances" && i + 1 < argc)
            tols = bench::parse_doubles(argv[++i]);
        else if (a == "--bullet-timeout" && i + 1 < argc)
            bullet_timeout = atof(argv[++i]);
        else if (a == "--hacd-max-tris" && i + 1 < argc)
            hacd_max_tris = (size_t)atoll(argv[++i]);
        else if (a == "--cd" && i + 1 < argc)
            cd_arg = argv[++i];
        else if (a == "--hacd" && i + 1 < argc)
            hacd_arg = argv[++i];
        else if (a == "--cd-scale" && i + 1 < argc)
            g_cd_scale = atof(argv[++i]);
        else if (a == "--cd-maxv" && i + 1 < argc)
            g_cd_maxv = (unsigned)atoi(argv[++i]);
        else if (a == "--threads" && i + 1 < argc)
            threads = (unsigned)std::max(1, atoi(argv[++i]));
        else if (a == "--quick")
            quick = true;
        else {
            fprintf(stderr, "usage: bench_decomp [--meshes DIR] [--models DIR] [--out DIR] [--passes N] "
                            "[--only NAME] [--tolerances LIST] [--quick] [--threads N] [--bullet-timeout S] "
                            "[--hacd-max-tris N] [--cd D:C,D:C] [--hacd C,C]\n");
            return 2;
        }
    }
    // Bullet's settings: (split depth, concavity percent) pairs refined
    // together, and HACD concavities (--cd "d:c,d:c", --hacd "c,c").
    std::vector<std::pair<unsigned, double>> cd = {{1, 5}, {2, 2}, {3, 1}, {5, 0.2}, {8, 0.02}};
    std::vector<double> hacd = {400, 100, 25};
    if (quick) {
        passes = 1, n = 40, only = "puma-link2", tols = {0.1, 0.05};
        cd = {{2, 2}, {5, 0.2}};
        hacd.clear(); // HACD takes ~25 s on link2 alone
    }
    if (cd_arg) {
        cd.clear();
        for (auto &w : bench::parse_names(cd_arg)) {
            unsigned d = 0;
            double c = 0;
            if (sscanf(w.c_str(), "%u:%lf", &d, &c) == 2) cd.push_back({d, c});
        }
    }
    if (hacd_arg) hacd = bench::parse_doubles(hacd_arg);
    double load0 = NAN;
    if (FILE *l = fopen("/proc/loadavg", "r")) {
        if (fscanf(l, "%lf", &load0) != 1) load0 = NAN;
        fclose(l);
    }
    const double run_t0 = now_ns();

    std::vector<Row> rows;
    std::vector<std::string> notes;
    std::vector<std::pair<std::string, std::vector<Row>>> by_mesh;
    const std::string puma = models + "/puma560/nimasarli_puma560_description/meshes/";
    for (size_t k = 0; k < sizeof kMeshes / sizeof *kMeshes; ++k) {
        const std::string name = kMeshes[k];
        if (!only.empty() && name.find(only) == std::string::npos) continue;
        Subject s;
        s.name = name;
        std::string err;
        bool loaded;
        if (name == "bunny00" || name == "elephant" || name == "armadillo")
            loaded = rm::load_cgal_mesh(name + ".off", &s.mesh, &err, meshes);
        else if (name == "puma-link2")
            loaded = rm::load_with_px(puma + "puma_link2.stl", &s.mesh, &err);
        else if (name == "puma-link4")
            loaded = rm::load_with_px(puma + "puma_link4.stl", &s.mesh, &err);
        else
            loaded = rm::load_with_px(models + "/teapot/trimesh_mit/teapot.stl", &s.mesh, &err);
        if (!loaded) {
            fprintf(stderr, "bench_decomp: %s\n", err.c_str());
            notes.push_back(name + " was not found (" + err + "): its rows are missing.");
            continue;
        }
        rm::normalize(&s.mesh, 1.0);
        if (!prepare(&s)) {
            notes.push_back(name + ": the mesh or its triangle model could not be built.");
            continue;
        }
        Sequence q = make_sequence(s, n, passes, 21 + k);
        if (q.poses.empty()) {
            notes.push_back(name + ": no contact along the approach line.");
            continue;
        }
        make_probes(&s, quick ? 200 : 1000, quick ? 200 : 1000, quick ? 400 : 2000, 1000 + k);
        std::vector<Row> mr;
        // The exact reference row.
        {
            Row r;
            r.method = "proxima-triangles";
            r.mesh = name;
            px_model_info info;
            px_model_get_info(s.tri.get(), &info);
            r.pieces = info.leaves;
            r.max_h = 0;
            r.memory_bytes = info.memory_bytes;
            r.m.median_ns = q.tri_median_ns;
            r.m.max_err = 0, r.m.max_width = 0, r.m.bracket_ok = 1, r.m.lower_ok = 1;
            measure_probes(s.tri.get(), s, &r.m);
            r.note = "the reference";
            mr.push_back(r);
            fprintf(stderr, "  proxima-triangles: %u leaves, %s us\n", info.leaves,
                    bench::fmt_us(q.tri_median_ns).c_str());
        }
        mr.push_back(run_builtin(s, PX_PIECES_PARTS, q, passes));
        for (double t : tols) mr.push_back(run_approx(s, t, threads, q, passes));
#ifdef PROXIMA_BENCH_BULLET
        const px_mesh *pm = s.px_mesh.get();
        for (auto dc : cd) {
            char pb[96];
            snprintf(pb, sizeof pb, "depth=%u cpercent=%g", dc.first, dc.second);
            mr.push_back(run_peer(
                s, "bullet-cd", pb,
                [&](std::vector<std::vector<double>> *h) {
                    bullet_cd(pm, dc.first, (float)dc.second, 3.0f, g_cd_maxv, h);
                },
                bullet_timeout, q, passes));
        }
        if (s.mesh.nt() <= hacd_max_tris) {
            for (double c : hacd) {
                char pb[96];
                snprintf(pb, sizeof pb, "concavity=%g", c);
                mr.push_back(run_peer(
                    s, "bullet-hacd", pb, [&](std::vector<std::vector<double>> *h) { bullet_hacd(pm, c, h); },
                    bullet_timeout, q, passes));
            }
        } else {
            notes.push_back("HACD was not run on " + name + " (" + std::to_string(s.mesh.nt()) +
                            " triangles > --hacd-max-tris " + std::to_string(hacd_max_tris) + ").");
        }
#endif
        rows.insert(rows.end(), mr.begin(), mr.end());
        by_mesh.emplace_back(name, mr);
    }
#ifndef PROXIMA_BENCH_BULLET
    notes.push_back("Built without Bullet's extras (libbullet-extras-dev): no Bullet rows.");
#endif
    const double run_s = (now_ns() - run_t0) * 1e-9;
    const size_t n_probes = quick ? 400 : 2000;

    // decomposition.csv
    const std::string csv = out_dir + "/decomposition.csv";
    FILE *f = fopen(csv.c_str(), "w");
    if (!f) return fprintf(stderr, "cannot write %s\n", csv.c_str()), 1;
    fprintf(f, "method,mesh,tolerance,params,pieces,hull_vertices,max_h,pieces_h_over_tol,build_s,decomp_s,"
               "query_median_ns,query_p90_ns,max_dist_err,max_bracket_width,bracket_ok,lower_ok,memory_bytes,"
               "cache_bytes,note,threads,max_probe_err,max_cover_err\n");
    for (auto &r : rows)
        fprintf(f, "%s,%s,%s,%s,%zu,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%zu,%zu,\"%s\",%s,%s,%s\n",
                r.method.c_str(), r.mesh.c_str(), num(r.tolerance, "%g").c_str(), r.params.c_str(), r.pieces,
                r.hull_vertices ? std::to_string(r.hull_vertices).c_str() : "", num(r.max_h, "%.5g").c_str(),
                r.method == "proxima-approx" ? std::to_string(r.pieces_h_over_tol).c_str() : "",
                num(r.build_s, "%.4f").c_str(), num(r.decomp_s, "%.4f").c_str(),
                num(r.m.median_ns, "%.0f").c_str(), num(r.m.p90_ns, "%.0f").c_str(),
                num(r.m.max_err, "%.5g").c_str(), num(r.m.max_width, "%.5g").c_str(),
                flag(r.m.bracket_ok).c_str(), flag(r.m.lower_ok).c_str(), r.memory_bytes, r.m.cache_bytes,
                r.note.c_str(), r.threads ? std::to_string(r.threads).c_str() : "",
                num(r.m.probe_err, "%.5g").c_str(), num(r.m.cover_err, "%.5g").c_str());
    fclose(f);

    // decomposition_curves.dat: per mesh (fixed order), per curve of
    // kCurves, the (error, time, pieces) points sorted by error; then the
    // exact row as a horizontal segment. A missing curve is one NaN line so
    // that block indices stay fixed for the plot script.
    const std::string dat = out_dir + "/decomposition_curves.dat";
    f = fopen(dat.c_str(), "w");
    if (!f) return fprintf(stderr, "cannot write %s\n", dat.c_str()), 1;
    fprintf(f, "# bench_decomp: blocks mesh-major (bunny00 elephant armadillo puma-link2 puma-link4 teapot), "
               "per mesh: proxima-approx bullet-cd bullet-hacd proxima-parts proxima-triangles;\n"
               "# columns: max_probe_err query_median_us pieces max_dist_err (the approach line's)\n");
    for (const char *mname : kMeshes) {
        const std::vector<Row> *mr = nullptr;
        for (auto &b : by_mesh)
            if (b.first == mname) mr = &b.second;
        for (const char *c : kCurves) {
            std::vector<const Row *> pts;
            if (mr)
                for (auto &r : *mr)
                    if (r.method == c && !r.failed) pts.push_back(&r);
            std::sort(pts.begin(), pts.end(),
                      [](const Row *a, const Row *b) { return a->m.probe_err < b->m.probe_err; });
            fprintf(f, "# %s %s\n", mname, c);
            if (pts.empty()) fprintf(f, "NaN NaN NaN NaN\n");
            for (auto *r : pts)
                fprintf(f, "%.6g %.4f %zu %.6g\n", std::max(r->m.probe_err, 1e-5), r->m.median_ns * 1e-3,
                        r->pieces, r->m.max_err);
            fprintf(f, "\n\n");
        }
        double tri = NAN;
        if (mr)
            for (auto &r : *mr)
                if (r.method == "proxima-triangles") tri = r.m.median_ns * 1e-3;
        fprintf(f, "# %s proxima-triangles (exact: error 0, drawn across)\n", mname);
        if (tri == tri)
            fprintf(f, "1e-5 %.4f 0 0\n1 %.4f 0 0\n\n\n", tri, tri);
        else
            fprintf(f, "NaN NaN NaN NaN\n\n\n");
    }
    fclose(f);

    // decomposition.md
    const std::string md = out_dir + "/decomposition.md";
    f = fopen(md.c_str(), "w");
    if (!f) return fprintf(stderr, "cannot write %s\n", md.c_str()), 1;
    fprintf(f, "# Approximate convex decomposition: speed against error\n\n");
    fprintf(
        f,
        "Written by `bench/bench_decomp.cpp` (`make bench-decomp`; the method is in its header comment), "
        "issue 10 section 3. Each mesh is scaled to a bounding-box diagonal of 1 and approached by a copy of "
        "itself represented by the same method (the same model object for both bodies): %d poses from 0.30 "
        "before first contact of the triangle surfaces to 0.03 past it, turning 0.1 degree per pose. "
        "px_model_distance timed alone per pose, cache warm along the sequence, per pose the median of %d "
        "passes, then the median over poses. Approach error: the largest |d_model - d_exact| over the poses, "
        "d_exact from the triangle-leaf models at the same poses (diagonal 1). Along one line one hull is "
        "often as good as many, so the error that decides is the **probe error**, which does not depend "
        "on a direction: the largest |d_model(p) - d_exact(p)| over %zu fixed probe points p per mesh "
        "(a one-point px_convex each, px_model_distance_convex): half of them far, from the bounding box "
        "out to 0.3 beyond it along random directions, half near, at random points of the surface moved 0 "
        "to 0.1 along the normal to the outside (the teapot is open: the normal's side as wound). Cover "
        "error: the largest distance from a mesh vertex (up to 2000, every k-th) to the pieces, 0 when "
        "they cover it. Bullet's hulls are wrapped "
        "with px_model_create_from_points (h = 0, no bound claimed), so their bracket is not checked; "
        "`lower ok` says whether d_model <= d_exact held on every pose. proxima's builds use %u threads "
        "(`options.threads`, the decomposition and the certification of h); Bullet's decomposers run on "
        "one. Machine: %s (%.2f at the start; "
        "other work shared the machine, so absolute times carry its noise). Whole run: %.0f s.\n\n",
        n, passes, n_probes, threads, bench::machine_line().c_str(), load0, run_s);
    for (auto &nt : notes) fprintf(f, "%s\n\n", nt.c_str());
    fprintf(f, "| mesh | method | parameters | pieces | hull vertices | max h | pieces h > tol | build s | "
               "decompose s | distance µs (median) | p90 µs | approach error | probe error | cover error | "
               "bracket ok | lower ok | note |\n");
    fprintf(f, "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (auto &r : rows) {
        fprintf(f, "| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n",
                r.mesh.c_str(), r.method.c_str(), r.params.c_str(),
                r.pieces ? std::to_string(r.pieces).c_str() : "",
                r.hull_vertices ? std::to_string(r.hull_vertices).c_str() : "", num(r.max_h, "%.4f").c_str(),
                r.method == "proxima-approx" && !r.failed ? std::to_string(r.pieces_h_over_tol).c_str() : "",
                num(r.build_s, "%.2f").c_str(), num(r.decomp_s, "%.2f").c_str(),
                bench::fmt_us(r.m.median_ns).c_str(), bench::fmt_us(r.m.p90_ns).c_str(),
                num(r.m.max_err, "%.4f").c_str(), num(r.m.probe_err, "%.4f").c_str(),
                num(r.m.cover_err, "%.4f").c_str(),
                r.m.bracket_ok < 0 ? "" : (r.m.bracket_ok ? "yes" : "**no**"),
                r.m.lower_ok < 0 ? "" : (r.m.lower_ok ? "yes" : "**no**"), r.note.c_str());
    }
    fprintf(
        f,
        "\nmax h: the model's largest certified leaf bound (px_model_get_info; h_overlap, which bounds the "
        "whole hull); pieces h > tol: leaves whose certified boundary bound h exceeds tolerance × the "
        "part's diagonal. build s: px_model_create_from_mesh whole (proxima) or the peer's decomposition "
        "(Bullet, in a child process); decompose s: pxcd_decompose alone, on the same threads (the rest of "
        "build s is certifying h and building the tree). Hull vertices: px_convex_vertex_count of each "
        "piece's hull, summed.\n\n");

    // Targets.
    fprintf(f, "## Targets (issue 10)\n\n| target | mesh | measured | met |\n|---|---|---|---|\n");
    for (auto &b : by_mesh)
        for (auto &r : b.second)
            if (r.method == "proxima-approx" && r.tolerance == 0.01 && b.first == "bunny00")
                fprintf(f,
                        "| bunny00 at tolerance 0.01 decomposed in ≤ 60 s | bunny00 | %.1f s build on %u "
                        "threads (%.1f s pxcd_decompose alone), %zu pieces | %s |\n",
                        r.build_s, r.threads, r.decomp_s, r.pieces,
                        r.failed ? "**failed**" : (r.build_s <= 60 ? "yes" : "**no**"));
    for (auto &b : by_mesh)
        for (auto &r : b.second)
            if (r.method == "proxima-approx" && r.tolerance == 0.02 && !r.failed)
                fprintf(f,
                        "| model distance ≤ 10 µs per pose at tolerance 0.02 (median) | %s | %s µs (p90 %s) "
                        "| %s |\n",
                        b.first.c_str(), bench::fmt_us(r.m.median_ns).c_str(),
                        bench::fmt_us(r.m.p90_ns).c_str(), r.m.median_ns <= 10000 ? "yes" : "**no**");
    // Fewer pieces at equal measured error: for every Bullet row, proxima's
    // fewest pieces among its rows whose probe error is at most Bullet's
    // (and, for reference, the same by the approach line's error).
    auto fewer_than_bullet = [](const std::vector<Row> &mr, double Measure::*err, int *compared, int *fewer,
                                int *unreached) {
        *compared = *fewer = *unreached = 0;
        for (auto &r : mr) {
            if (r.failed || (r.method != "bullet-cd" && r.method != "bullet-hacd")) continue;
            const Row *best = nullptr;
            for (auto &p : mr)
                if (p.method == "proxima-approx" && !p.failed && p.m.*err <= r.m.*err &&
                    (!best || p.pieces < best->pieces))
                    best = &p;
            if (!best) {
                ++*unreached;
                continue;
            }
            ++*compared;
            if (best->pieces < r.pieces) ++*fewer;
        }
    };
    for (auto &b : by_mesh) {
        int compared, fewer, unreached, c_line, f_line, u_line, uncovered = 0;
        double worst_cover = 0;
        fewer_than_bullet(b.second, &Measure::probe_err, &compared, &fewer, &unreached);
        fewer_than_bullet(b.second, &Measure::max_err, &c_line, &f_line, &u_line);
        for (auto &r : b.second)
            if (!r.failed && (r.method == "bullet-cd" || r.method == "bullet-hacd") && r.m.cover_err > 1e-9)
                ++uncovered, worst_cover = std::max(worst_cover, r.m.cover_err);
        if (compared + unreached == 0) continue;
        std::string detail = "by probe error: fewer in " + std::to_string(fewer) + " of " +
                             std::to_string(compared) + " Bullet settings";
        if (unreached) detail += ", " + std::to_string(unreached) + " more accurate than every proxima row";
        detail += " (approach line: " + std::to_string(f_line) + " of " + std::to_string(c_line) +
                  (u_line ? ", " + std::to_string(u_line) + " unreached" : std::string()) + ")";
        if (uncovered)
            detail += "; " + std::to_string(uncovered) + " Bullet settings leave vertices uncovered (up to " +
                      num(worst_cover, "%.4f") + ")";
        fprintf(f, "| fewer pieces than Bullet at equal measured error | %s | %s | %s |\n", b.first.c_str(),
                detail.c_str(),
                compared > 0 && fewer == compared && unreached == 0
                    ? "yes"
                    : (fewer == compared && compared > 0 ? "yes where comparable" : "**no**"));
    }
    fprintf(
        f,
        "\n\"Fewer pieces at equal measured error\": for each Bullet row, proxima's fewest pieces among its "
        "rows whose probe error is at most that row's; a Bullet row more accurate than every proxima row "
        "is not comparable. In parentheses the same count with the approach line's error, the measure of "
        "earlier runs.\n\n![query time against probe error](decomposition.png)\n");
    fclose(f);
    fprintf(stderr, "wrote %s, %s, %s (%.0f s)\n", csv.c_str(), dat.c_str(), md.c_str(), run_s);
    return 0;
}
