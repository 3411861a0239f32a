// pxcd_decompose / pxcd_decomp_free: approximate convex decomposition of a
// triangle mesh behind the C ABI of pxcd_decomp.h (issue 10, section 1).
//
// Sources (ideas only; the code is ours):
//   - CoACD: X. Wei, M. Liu, Z. Ling, H. Su, "Approximate convex
//     decomposition for 3D meshes with collision-aware concavity and tree
//     search", ACM TOG 41(4) (SIGGRAPH 2022), sections 4-5: a worklist of
//     parts, each part whose concavity (hull-to-part Hausdorff distance)
//     exceeds a threshold is cut by a plane chosen to minimise the worst
//     concavity of the results; cut sections are closed by a constrained
//     Delaunay triangulation; a final merge pass joins pieces whose merged
//     hull stays within the threshold, measured against the pieces' own
//     surfaces, cheapest first. We replace the Monte-Carlo tree search by a
//     greedy one-level search over axis-aligned planes followed by a local
//     refinement of the offset (CoACD's own refinement step), and drop the
//     volume term Rv (the certified h of the C side is a distance, not a
//     volume).
//   - V-HACD 4 (K. Mamou, github.com/kmammou/v-hacd): axis-aligned splits of
//     the part's box and a greedy merge by cost; the stopping rules (depth,
//     size) follow it.
//
// Pipeline:
//   1. Weld vertices with bit-identical coordinates; the mesh is "closed"
//      when every undirected edge is used an even number of times (then the
//      part is a solid by the even-odd rule and cuts get caps), "open"
//      otherwise (the part is its triangles). Split into connected
//      components; each is a piece on the worklist. The tolerance is
//      tolerance * diagonal (coordinates are not transformed).
//   2. A piece is a triangle soup (indexed, doubles). Its concavity is
//      sampled: points on its convex hull boundary (grid samples on each
//      hull triangle, edges included), distance to the soup's triangles by
//      a bounding-volume hierarchy (ours, see Bvh); the max is the estimate.
//   3. A piece above tolerance is cut by the best of 3 x kOffsets
//      axis-aligned planes across its box (score: max of the two halves'
//      concavities, sampled coarsely, with branch and bound; scores equal
//      up to rounding are told apart by the sum, see Candidates), refined
//      by a few halving steps on the offset; each half is split into
//      connected components and goes back on the worklist. A piece is kept
//      as is when it is small (box diagonal <= tolerance, which bounds its
//      concavity), at depth kMaxDepth, when no plane separates it, or at
//      max_pieces.
//   4. Merge pass: pairs whose boxes, grown by the tolerance, overlap are
//      candidates; cost = concavity of the hull of both pieces measured
//      against the union of both soups; the cheapest pair within tolerance
//      is merged, repeatedly (ties by index).
//   5. Each piece's points are re-hulled (pxcd_hull_compute: convex_hull_3,
//      Epick with exact predicates) and its extreme points output, sorted.
//
// Cutting (our own soup clipper, not PMP::clip: inputs may be non-manifold,
// inconsistently oriented or open, which PMP::clip rejects, and plain double
// arithmetic is enough for an approximate decomposition):
//   - Planes are axis-aligned, x[a] = c, so the side of a vertex,
//     x[a] - c, has an exact sign (a rounded difference is zero iff the
//     operands are equal and otherwise keeps the sign).
//   - A vertex within ctx.band of the plane (2^-40 of the input's largest
//     coordinate or diagonal, about 4096 ulps) counts as on it. A mesh
//     turned by a half-turn (sin(pi) = 1.2e-16) has the corners of a face
//     that lay in a coordinate plane a few ulps apart; a plane snapped onto
//     one of them (snap_offset) cut the face into ulp-thin flakes, each
//     half getting some (the 3D stairs of test_decomp turned so: 3 to 5
//     pieces at tolerance 0.02 instead of 2). With the band the cut sees
//     that face in the plane, as before the turn. Vertices keep their
//     coordinates (a half may reach the band beyond c); the side is still a
//     function of the vertex alone, so all that follows holds.
//   - Simulation of simplicity: for the negative half a vertex on the
//     plane counts as outside (as if the plane were at c - eps), for the
//     positive half likewise (plane at c + eps). Each half thus sees a plane
//     in general position: its section curves are closed whenever the
//     surface is, and triangles lying in the plane belong to neither half:
//     they are covered by the caps, since a face in the plane separates the
//     two sections (the L-shape cut along its inner face gets two clean
//     boxes instead of a box with a zero-thickness flap). In open mode the
//     in-plane triangles go to the negative half (no caps there).
//   - The point where an edge crosses the plane is computed from the edge
//     with its endpoints in a canonical order (by vertex id), and its a-th
//     coordinate set to c: both triangles of an edge, and both halves, get
//     bit-identical points, so sections close up and halves touch exactly.
//     Rounding moves a cut point off the original edge by ~1 ulp.
//   - Rounding (REFERENCES.md 5.2 warns that Epick constructions drift
//     along chains of cuts and suggests Epeck): we keep doubles. A cut
//     point is within ~1 ulp of the segment it was computed from, and a
//     chain of k cuts moves points by ~k ulps (k <= kMaxDepth); nothing
//     topological depends on it (no manifoldness is required), every vertex
//     of the input stays bit-exact in the piece it lands in, and coverage
//     is off by at most that drift. The builder re-certifies h anyway.
//   - Caps: the section segments, with pairs of identical segments removed
//     (even-odd), are inserted as constraints into a 2D constrained Delaunay
//     triangulation (CGAL); faces at odd nesting depth (flood fill across
//     constraints, the CGAL manual's "polygon_triangulation" example) are
//     the cap. Only exact points are ever triangulated: Epick with exact
//     predicates and no constructions, and where segments cross
//     (self-intersecting or near-degenerate input) Epeck, whose crossing
//     points become new vertices (see triangulate_cap).
//
// Threads: candidate planes (per axis, and per refinement step) and merge
// pairs are evaluated in batches by up to `threads` threads; each result goes
// to its own slot and the slots are reduced in index order on the calling
// thread, with the same bound for the whole batch, so the output does not
// depend on the thread count (see evaluate_batch). The progress callback is
// only called from the calling thread, between batches.
//
// Determinism: every decision is taken in a fixed order. Hulls
// come from pxcd_hull_compute, which is canonical (convex_hull_3's own output
// is not: its vertex order and its triangulation of coplanar facets vary
// between calls), and points are sorted before hulling, so samples, sample
// counts and sums are the same from run to run.
//
// Valgrind: unlike hull.cpp there is no exact-kernel fallback here; under
// valgrind the interval filters of Epick and Epeck may misbehave (see
// hull.cpp).

#include "pxcd.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_plus_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/exceptions.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <exception>
#include <limits>
#include <map>
#include <mutex>
#include <new>
#include <numeric>
#include <stdexcept>
#include <thread>
#include <unordered_map>
#include <utility>
#include <vector>

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point_3 = K::Point_3;
using Vec3 = std::array<double, 3>;
using Tri = std::array<uint32_t, 3>;

constexpr int kOffsets = 5;     // candidate offsets per axis (interior, evenly spaced)
constexpr int kRefineSteps = 2; // halving steps of the offset refinement
constexpr int kMaxDepth = 24;   // cut depth cap
constexpr unsigned kDefaultMaxPieces = 4096;
constexpr size_t kRankSamples = 300;    // hull samples per half when ranking candidate planes
constexpr size_t kAcceptSamples = 2000; // hull samples when deciding that a piece is done
constexpr uint32_t kNone = UINT32_MAX;

struct Cancelled {};
struct Bad_input : std::runtime_error {
    using std::runtime_error::runtime_error;
};

void set_msg(char *msg, size_t msg_len, const char *text) {
    if (msg != nullptr && msg_len > 0) std::snprintf(msg, msg_len, "%s", text);
}

// An indexed triangle soup. cap[t] marks cap triangles (for the progress
// measure only).
struct Soup {
    std::vector<Vec3> v;
    std::vector<Tri> t;
    std::vector<uint8_t> cap;
};

struct Box {
    Vec3 lo{{HUGE_VAL, HUGE_VAL, HUGE_VAL}}, hi{{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL}};
    void add(const Vec3 &p) {
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], p[k]);
            hi[k] = std::max(hi[k], p[k]);
        }
    }
    double diagonal() const {
        double s = 0;
        for (int k = 0; k < 3; ++k) s += (hi[k] - lo[k]) * (hi[k] - lo[k]);
        return std::sqrt(s);
    }
    bool overlaps(const Box &o, double grow) const {
        for (int k = 0; k < 3; ++k)
            if (lo[k] > o.hi[k] + grow || o.lo[k] > hi[k] + grow) return false;
        return true;
    }
};

Box box_of(const Soup &s) {
    Box b;
    for (const Tri &t : s.t)
        for (uint32_t i : t) b.add(s.v[i]);
    return b;
}

double tri_area(const Vec3 &a, const Vec3 &b, const Vec3 &c) {
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double x = u[1] * w[2] - u[2] * w[1], y = u[2] * w[0] - u[0] * w[2], z = u[0] * w[1] - u[1] * w[0];
    return 0.5 * std::sqrt(x * x + y * y + z * z);
}

double surface_area(const Soup &s) {
    double a = 0;
    for (size_t i = 0; i < s.t.size(); ++i)
        if (!s.cap[i]) a += tri_area(s.v[s.t[i][0]], s.v[s.t[i][1]], s.v[s.t[i][2]]);
    return a;
}

// ---- Hull and sampling ------------------------------------------------------

// A convex hull in canonical form: points sorted lexicographically, faces
// fanned from their smallest vertex (see hull_of_points).
struct Hull {
    std::vector<Vec3> p;
    std::vector<Tri> t;
};

Point_3 to_point(const Vec3 &v) { return Point_3(v[0], v[1], v[2]); }

// Hull of `pts` through pxcd_hull_compute (hull.cpp): exact predicates and
// a canonical result (polygonal faces, exactly coplanar triangles merged),
// which we fan from each face's first (smallest) vertex. Canonical matters:
// convex_hull_3 alone may triangulate coplanar facets differently from one
// call to the next (seen on the torus), which moves the samples and changed
// the chosen cuts between runs.
Hull hull_of_points(std::vector<Point_3> &pts) {
    Hull h;
    if (pts.empty()) return h;
    std::sort(pts.begin(), pts.end());
    pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
    std::vector<double> xyz(3 * pts.size());
    for (size_t i = 0; i < pts.size(); ++i) {
        xyz[3 * i] = pts[i].x();
        xyz[3 * i + 1] = pts[i].y();
        xyz[3 * i + 2] = pts[i].z();
    }
    pxcd_hull *ph = nullptr;
    char msg[256];
    const pxcd_status st = pxcd_hull_compute(xyz.data(), pts.size(), &ph, nullptr, msg, sizeof msg);
    if (st == PXCD_OUT_OF_MEMORY) throw std::bad_alloc();
    if (st != PXCD_OK) throw std::runtime_error(msg);
    struct Free {
        pxcd_hull *p;
        ~Free() { pxcd_hull_free(p); }
    } guard{ph};
    // Vertex i is the i-th distinct extreme point in input (sorted) order.
    h.p.resize(ph->vertex_count);
    for (size_t i = 0; i < ph->vertex_count; ++i)
        h.p[i] = Vec3{{ph->vertices[3 * i], ph->vertices[3 * i + 1], ph->vertices[3 * i + 2]}};
    for (size_t f = 0; f < ph->face_count; ++f) {
        const size_t b = ph->face_offsets[f], e = ph->face_offsets[f + 1];
        for (size_t k = b + 1; k + 1 < e; ++k)
            h.t.push_back(Tri{{ph->face_indices[b], ph->face_indices[k], ph->face_indices[k + 1]}});
    }
    return h;
}

Hull hull_of_soup(const Soup &s) {
    std::vector<Point_3> pts;
    std::vector<uint8_t> used(s.v.size(), 0);
    for (const Tri &t : s.t)
        for (uint32_t i : t) used[i] = 1;
    for (size_t i = 0; i < s.v.size(); ++i)
        if (used[i]) pts.push_back(to_point(s.v[i]));
    return hull_of_points(pts);
}

// About `target` sample points on the hull's boundary: on each triangle the
// centroids of a k x k subdivision (k by area), points along its edges, and
// the hull vertices; a segment hull is sampled along its length.
std::vector<Point_3> sample_hull(const Hull &h, size_t target) {
    std::vector<Point_3> out;
    if (h.p.empty()) return out;
    if (h.t.empty()) {
        if (h.p.size() >= 2) {
            const Vec3 &a = h.p.front(), &b = h.p.back();
            for (size_t i = 0; i <= target; ++i) {
                const double s = double(i) / double(target);
                out.emplace_back(a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1]),
                                 a[2] + s * (b[2] - a[2]));
            }
        }
        return out;
    }
    double total = 0;
    for (const Tri &t : h.t) total += tri_area(h.p[t[0]], h.p[t[1]], h.p[t[2]]);
    const double a0 = total > 0 ? total / double(target) : 1.0;
    for (const Tri &t : h.t) {
        const Vec3 &a = h.p[t[0]], &b = h.p[t[1]], &c = h.p[t[2]];
        const double area = tri_area(a, b, c);
        int k = int(std::ceil(std::sqrt(area / a0)));
        k = std::max(1, std::min(k, 64));
        auto at = [&](double u, double v) {
            const double w = 1.0 - u - v;
            return Point_3(w * a[0] + u * b[0] + v * c[0], w * a[1] + u * b[1] + v * c[1],
                           w * a[2] + u * b[2] + v * c[2]);
        };
        const double inv = 1.0 / k;
        for (int i = 0; i < k; ++i)
            for (int j = 0; i + j < k; ++j) {
                out.push_back(at((i + 1.0 / 3) * inv, (j + 1.0 / 3) * inv));
                if (i + j + 2 <= k) out.push_back(at((i + 2.0 / 3) * inv, (j + 2.0 / 3) * inv));
            }
        for (int i = 0; i < k; ++i) {
            const double s = (i + 0.5) * inv;
            out.push_back(at(s, 0));
            out.push_back(at(0, s));
            out.push_back(at(s, 1 - s));
        }
    }
    for (const Vec3 &p : h.p) out.push_back(to_point(p));
    return out;
}

// ---- Distance to a soup -----------------------------------------------------

double seg_dist2(const Vec3 &p, const Vec3 &a, const Vec3 &b) {
    const Vec3 ab{{b[0] - a[0], b[1] - a[1], b[2] - a[2]}}, ap{{p[0] - a[0], p[1] - a[1], p[2] - a[2]}};
    const double l = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2];
    double t = l > 0 ? (ap[0] * ab[0] + ap[1] * ab[1] + ap[2] * ab[2]) / l : 0.0;
    t = std::min(1.0, std::max(0.0, t));
    double s = 0;
    for (int k = 0; k < 3; ++k) {
        const double d = ap[k] - t * ab[k];
        s += d * d;
    }
    return s;
}

// Squared distance from p to triangle abc (Ericson, "Real-Time Collision
// Detection", 2005, section 5.1.5, closest point by Voronoi regions).
double tri_dist2(const Vec3 &p, const Vec3 &a, const Vec3 &b, const Vec3 &c) {
    auto sub = [](const Vec3 &x, const Vec3 &y) { return Vec3{{x[0] - y[0], x[1] - y[1], x[2] - y[2]}}; };
    auto dot = [](const Vec3 &x, const Vec3 &y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; };
    auto dist2 = [&](const Vec3 &q) {
        const Vec3 d = sub(p, q);
        return dot(d, d);
    };
    const Vec3 ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
    const double d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return dot(ap, ap);
    const Vec3 bp = sub(p, b);
    const double d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return dot(bp, bp);
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        const double v = d1 / (d1 - d3);
        return dist2(Vec3{{a[0] + v * ab[0], a[1] + v * ab[1], a[2] + v * ab[2]}});
    }
    const Vec3 cp = sub(p, c);
    const double d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return dot(cp, cp);
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        const double w = d2 / (d2 - d6);
        return dist2(Vec3{{a[0] + w * ac[0], a[1] + w * ac[1], a[2] + w * ac[2]}});
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
        const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return dist2(Vec3{{b[0] + w * (c[0] - b[0]), b[1] + w * (c[1] - b[1]), b[2] + w * (c[2] - b[2])}});
    }
    const double sum = va + vb + vc;
    if (!(sum > 0)) // degenerate after all: its edges
        return std::min(seg_dist2(p, a, b), std::min(seg_dist2(p, b, c), seg_dist2(p, c, a)));
    const double denom = 1.0 / sum, v = vb * denom, w = vc * denom;
    return dist2(
        Vec3{{a[0] + ab[0] * v + ac[0] * w, a[1] + ab[1] * v + ac[1] * w, a[2] + ab[2] * v + ac[2] * w}});
}

// A bounding-volume hierarchy of triangles (axis-aligned boxes, median
// splits, up to 4 triangles per leaf) for point-to-soup distances. Ours
// rather than CGAL::AABB_tree: the concavity only asks "is this sample
// within the current worst distance of the surface?", which ends most
// queries after the first leaf; CGAL's traversal has no such early exit
// and its filtered sphere-box predicate dominated the profile (the torus
// test ran ~3x slower with it). Degenerate triangles and slivers are
// measured as their three edges, since Ericson's formula divides by their
// area.
struct Bvh {
    struct Prim {
        Vec3 a, b, c;
        bool flat;
    };
    struct Node {
        Vec3 lo, hi;
        uint32_t first,
            count; // leaf: prims [first, first + count); inner: count == 0, children first, first + 1
    };
    std::vector<Prim> prims;
    std::vector<Node> nodes;

    void build(const Soup *const *soups, size_t n_soups) {
        for (size_t s = 0; s < n_soups; ++s)
            for (const Tri &t : soups[s]->t) {
                const Vec3 &a = soups[s]->v[t[0]], &b = soups[s]->v[t[1]], &c = soups[s]->v[t[2]];
                // Slivers (|ab x ac| ~ 1e-12 |ab| |ac| or less) are measured
                // by their edges: same distances up to ~1e-12 relative, and
                // Ericson's formula divides by their area.
                const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
                const double w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
                const double x = u[1] * w[2] - u[2] * w[1], y = u[2] * w[0] - u[0] * w[2],
                             z = u[0] * w[1] - u[1] * w[0];
                const double uu = u[0] * u[0] + u[1] * u[1] + u[2] * u[2];
                const double ww = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
                prims.push_back(Prim{a, b, c, !(x * x + y * y + z * z > 1e-24 * uu * ww)});
            }
        if (prims.empty()) return;
        std::vector<Vec3> centre(prims.size());
        for (size_t i = 0; i < prims.size(); ++i)
            for (int k = 0; k < 3; ++k) centre[i][k] = (prims[i].a[k] + prims[i].b[k] + prims[i].c[k]) / 3;
        std::vector<uint32_t> order(prims.size());
        std::iota(order.begin(), order.end(), 0u);
        nodes.reserve(2 * prims.size() / 2 + 2);
        nodes.push_back(Node());
        struct Job {
            uint32_t node, begin, end;
        };
        std::vector<Job> jobs{Job{0, 0, uint32_t(prims.size())}};
        while (!jobs.empty()) {
            const Job j = jobs.back();
            jobs.pop_back();
            Box b, cb;
            for (uint32_t i = j.begin; i < j.end; ++i) {
                const Prim &p = prims[order[i]];
                b.add(p.a);
                b.add(p.b);
                b.add(p.c);
                cb.add(centre[order[i]]);
            }
            nodes[j.node].lo = b.lo;
            nodes[j.node].hi = b.hi;
            if (j.end - j.begin <= 4) {
                nodes[j.node].first = j.begin;
                nodes[j.node].count = j.end - j.begin;
                continue;
            }
            int axis = 0;
            for (int k = 1; k < 3; ++k)
                if (cb.hi[k] - cb.lo[k] > cb.hi[axis] - cb.lo[axis]) axis = k;
            const uint32_t mid = j.begin + (j.end - j.begin) / 2;
            // Ties broken by index: the split does not depend on the
            // library's nth_element.
            std::nth_element(order.begin() + j.begin, order.begin() + mid, order.begin() + j.end,
                             [&](uint32_t x, uint32_t y) {
                                 return centre[x][axis] != centre[y][axis] ? centre[x][axis] < centre[y][axis]
                                                                           : x < y;
                             });
            const uint32_t child = uint32_t(nodes.size());
            nodes.push_back(Node());
            nodes.push_back(Node());
            nodes[j.node].first = child;
            nodes[j.node].count = 0;
            jobs.push_back(Job{child, j.begin, mid});
            jobs.push_back(Job{child + 1, mid, j.end});
        }
        std::vector<Prim> sorted(prims.size());
        for (size_t i = 0; i < order.size(); ++i) sorted[i] = prims[order[i]];
        prims.swap(sorted);
    }

    static double box_dist2(const Node &n, const Vec3 &p) {
        double s = 0;
        for (int k = 0; k < 3; ++k) {
            const double d = std::max(0.0, std::max(n.lo[k] - p[k], p[k] - n.hi[k]));
            s += d * d;
        }
        return s;
    }

    // The squared distance from p to the triangles when it is >= stop2;
    // otherwise some value < stop2 (the search ends as soon as one triangle
    // is nearer than sqrt(stop2)). HUGE_VAL when empty.
    double dist2(const Vec3 &p, double stop2) const {
        double best = HUGE_VAL;
        if (nodes.empty()) return best;
        uint32_t stack[96];
        int top = 0;
        stack[top++] = 0;
        while (top > 0) {
            const Node &n = nodes[stack[--top]];
            if (box_dist2(n, p) >= best) continue;
            if (n.count > 0) {
                for (uint32_t i = n.first; i < n.first + n.count; ++i) {
                    const Prim &t = prims[i];
                    const double d = t.flat
                                         ? std::min(seg_dist2(p, t.a, t.b),
                                                    std::min(seg_dist2(p, t.b, t.c), seg_dist2(p, t.c, t.a)))
                                         : tri_dist2(p, t.a, t.b, t.c);
                    best = std::min(best, d);
                }
                if (best < stop2) return best;
                continue;
            }
            const double d0 = box_dist2(nodes[n.first], p), d1 = box_dist2(nodes[n.first + 1], p);
            if (top + 2 > 96) continue; // cannot happen: median splits keep the depth ~log2(n)
            if (d0 < d1) {
                stack[top++] = n.first + 1;
                stack[top++] = n.first;
            } else {
                stack[top++] = n.first;
                stack[top++] = n.first + 1;
            }
        }
        return best;
    }
};

// Largest distance from the samples of `hull` to the triangles of the
// soups; stops early, returning a value > bound, as soon as one sample is
// farther than `bound`. A sample only matters if it is farther than the
// worst so far, so each query stops at the first triangle nearer than that.
double concavity(const Hull &hull, const Soup *const *soups, size_t n_soups, size_t target, double bound) {
    const std::vector<Point_3> samples = sample_hull(hull, target);
    if (samples.empty()) return 0.0;
    Bvh bvh;
    bvh.build(soups, n_soups);
    if (bvh.nodes.empty()) return 0.0;
    const double bound2 = bound * bound;
    double worst2 = 0;
    for (const Point_3 &q : samples) {
        worst2 = std::max(worst2, bvh.dist2(Vec3{{q.x(), q.y(), q.z()}}, worst2));
        // Above bound, even when the square root rounds back onto it: the
        // callers read "<= bound" as "measured in full" (a cut short at
        // bound, read so, once chose a cut whose half was at 0.56 > 0.53).
        if (worst2 > bound2) return std::max(std::sqrt(worst2), std::nextafter(bound, HUGE_VAL));
    }
    return std::sqrt(worst2);
}

double concavity_of(const Soup &s, const Hull &h, size_t target, double bound) {
    const Soup *p = &s;
    return concavity(h, &p, 1, target, bound);
}

// ---- Cutting ----------------------------------------------------------------

// Caps. The section segments are constraints of a 2D constrained Delaunay
// triangulation, filled by the even-odd rule. Segments cross only where the
// input intersects itself or is near-degenerate, and a crossing needs a new
// point. Epick with Exact_predicates_tag (as we had) rounds that point, and
// a rounded crossing can make new crossings; CGAL 5.5 snaps such points
// (CGAL pull request 6602), but nothing proves the insertion ends. (It was
// the first suspect when the Puma's link6 turned by a half-turn never
// finished; the time went into the cut cascade Candidates describes, with
// no crossing in 15 minutes of it.) So the fast triangulation (Epick)
// refuses crossings (No_constraint_intersection_requiring_constructions_tag
// throws; a segment through a vertex, or overlapping another, needs no new
// point and is accepted), and a cap whose segments cross is made again with
// exact constructions (Epeck, through Constrained_triangulation_plus_2,
// which computes each crossing from the input segments, not from pieces of
// them). Each triangulates exact points only, which ends. On the
// self-intersecting soups of test_decomp about one cap in five goes the
// exact way.
struct Face_info {
    int nesting = -1;
};
struct Vertex_info {
    uint32_t id = kNone; // kNone: a crossing point (exact triangulation only)
};
template <class Gt, class Itag> struct Cdt_of {
    using Vb = CGAL::Triangulation_vertex_base_with_info_2<Vertex_info, Gt>;
    using Fbb = CGAL::Triangulation_face_base_with_info_2<Face_info, Gt>;
    using Fb = CGAL::Constrained_triangulation_face_base_2<Gt, Fbb>;
    using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
    using type = CGAL::Constrained_Delaunay_triangulation_2<Gt, Tds, Itag>;
};
using Epeck = CGAL::Exact_predicates_exact_constructions_kernel;
using Cdt_fast = Cdt_of<K, CGAL::No_constraint_intersection_requiring_constructions_tag>::type;
using Cdt_exact = CGAL::Constrained_triangulation_plus_2<Cdt_of<Epeck, CGAL::Exact_intersections_tag>::type>;

// Nesting depth of every face: flood fill from the infinite face, +1 across
// each constraint (CGAL manual, 2D triangulations, "polygon_triangulation").
template <class Cdt> void mark_nesting(Cdt &cdt) {
    using Face_handle = typename Cdt::Face_handle;
    using Edge = typename Cdt::Edge;
    for (Face_handle f : cdt.all_face_handles()) f->info().nesting = -1;
    std::deque<Edge> border;
    auto fill = [&](Face_handle start, int level) {
        if (start->info().nesting != -1) return;
        std::deque<Face_handle> queue{start};
        while (!queue.empty()) {
            Face_handle f = queue.front();
            queue.pop_front();
            if (f->info().nesting != -1) continue;
            f->info().nesting = level;
            for (int i = 0; i < 3; ++i) {
                Face_handle n = f->neighbor(i);
                if (n->info().nesting != -1) continue;
                if (cdt.is_constrained(Edge(f, i)))
                    border.push_back(Edge(f, i));
                else
                    queue.push_back(n);
            }
        }
    };
    fill(cdt.infinite_face(), 0);
    while (!border.empty()) {
        Edge e = border.front();
        border.pop_front();
        Face_handle n = e.first->neighbor(e.second);
        if (n->info().nesting == -1) fill(n, e.first->info().nesting + 1);
    }
}

// Triangulates the segments `odd` (vertex ids of `out`) in the (u, w)
// coordinates of the plane x[axis] = c and adds the cap: its faces at odd
// nesting depth, and crossing points as new vertices on the plane. Throws
// Cdt::Intersection_of_constraints_exception when Cdt refuses crossings
// and two segments cross; `out` is then unchanged.
template <class Cdt>
void triangulate_cap(Soup &out, const std::vector<std::pair<uint32_t, uint32_t>> &odd, int axis, double c) {
    using Vertex_handle = typename Cdt::Vertex_handle;
    using Point = typename Cdt::Point;
    const int u = (axis + 1) % 3, w = (axis + 2) % 3;
    Cdt cdt;
    std::unordered_map<uint32_t, Vertex_handle> handle;
    auto vh = [&](uint32_t id) {
        auto it = handle.find(id);
        if (it != handle.end()) return it->second;
        // Two ids at the same 2D point share one vertex, which takes the
        // later id.
        Vertex_handle h = cdt.insert(Point(out.v[id][u], out.v[id][w]));
        h->info().id = id;
        handle.emplace(id, h);
        return h;
    };
    for (const auto &s : odd) {
        Vertex_handle a = vh(s.first), b = vh(s.second);
        if (a != b) cdt.insert_constraint(a, b);
    }
    if (cdt.dimension() < 2) return;
    mark_nesting(cdt);
    for (Vertex_handle h : cdt.finite_vertex_handles()) {
        if (h->info().id != kNone) continue;
        Vec3 p;
        p[axis] = c;
        p[u] = CGAL::to_double(h->point().x());
        p[w] = CGAL::to_double(h->point().y());
        h->info().id = uint32_t(out.v.size());
        out.v.push_back(p);
    }
    for (auto f : cdt.finite_face_handles()) {
        if (f->info().nesting % 2 != 1) continue;
        out.t.push_back(Tri{{f->vertex(0)->info().id, f->vertex(1)->info().id, f->vertex(2)->info().id}});
        out.cap.push_back(1);
    }
}

// Adds to `out` the cap on the plane x[axis] = c bounded by `segs` (vertex
// ids of `out`, all within ctx.band of the plane).
void add_cap(Soup &out, std::vector<std::pair<uint32_t, uint32_t>> &segs, int axis, double c) {
    for (auto &s : segs)
        if (s.first > s.second) std::swap(s.first, s.second);
    std::sort(segs.begin(), segs.end());
    // Even-odd: identical segments cancel in pairs.
    std::vector<std::pair<uint32_t, uint32_t>> odd;
    for (size_t i = 0; i < segs.size();) {
        size_t j = i;
        while (j < segs.size() && segs[j] == segs[i]) ++j;
        if ((j - i) % 2 == 1) odd.push_back(segs[i]);
        i = j;
    }
    if (odd.size() < 3) return;
    try {
        triangulate_cap<Cdt_fast>(out, odd, axis, c);
    } catch (const Cdt_fast::Intersection_of_constraints_exception &) {
        triangulate_cap<Cdt_exact>(out, odd, axis, c);
    }
}

// One half of `s` cut by x[axis] = c: the negative side (x < c) when
// negative, else the positive side (x > c); see the header comment for the
// treatment of vertices on the plane. With caps, the section is closed by a
// cap. Vertices keep their coordinates; unused vertices are dropped.
Soup clip_half(const Soup &s, int axis, double c, bool negative, bool caps, double band) {
    Soup out;
    std::vector<double> f(s.v.size());
    for (size_t i = 0; i < s.v.size(); ++i) {
        f[i] = negative ? s.v[i][axis] - c : c - s.v[i][axis];
        if (std::fabs(f[i]) <= band) f[i] = 0; // on the plane (see the header comment)
    }
    std::vector<uint32_t> map(s.v.size(), kNone);
    auto keep = [&](uint32_t i) {
        if (map[i] == kNone) {
            map[i] = uint32_t(out.v.size());
            out.v.push_back(s.v[i]);
        }
        return map[i];
    };
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> cross_id;
    // Point where edge (i inside, j outside) crosses the plane.
    auto cross = [&](uint32_t i, uint32_t j) {
        if (f[j] == 0) return keep(j);
        const uint32_t a = std::min(i, j), b = std::max(i, j);
        auto it = cross_id.find({a, b});
        if (it != cross_id.end()) return it->second;
        const Vec3 &pa = s.v[a], &pb = s.v[b];
        // f has opposite signs at a and b (t is the same for both halves).
        const double t = f[a] / (f[a] - f[b]);
        Vec3 p;
        for (int k = 0; k < 3; ++k) {
            double x = pa[k] + t * (pb[k] - pa[k]);
            p[k] = std::min(std::max(x, std::min(pa[k], pb[k])), std::max(pa[k], pb[k]));
        }
        p[axis] = c;
        const uint32_t id = uint32_t(out.v.size());
        out.v.push_back(p);
        cross_id.emplace(std::make_pair(a, b), id);
        return id;
    };
    std::vector<std::pair<uint32_t, uint32_t>> segs;
    for (size_t ti = 0; ti < s.t.size(); ++ti) {
        const Tri &t = s.t[ti];
        const bool in[3] = {f[t[0]] < 0, f[t[1]] < 0, f[t[2]] < 0};
        const int n_in = in[0] + in[1] + in[2];
        if (n_in == 3) {
            out.t.push_back(Tri{{keep(t[0]), keep(t[1]), keep(t[2])}});
            out.cap.push_back(s.cap[ti]);
            continue;
        }
        if (n_in == 0) {
            if (!caps && negative && f[t[0]] == 0 && f[t[1]] == 0 && f[t[2]] == 0) {
                out.t.push_back(Tri{{keep(t[0]), keep(t[1]), keep(t[2])}});
                out.cap.push_back(s.cap[ti]);
            }
            continue;
        }
        // Sutherland-Hodgman on one triangle: 3 or 4 vertices.
        uint32_t poly[4];
        int n = 0;
        uint32_t x[2];
        int nx = 0;
        for (int e = 0; e < 3; ++e) {
            const uint32_t i = t[e], j = t[(e + 1) % 3];
            const bool ii = in[e], jj = in[(e + 1) % 3];
            if (ii) poly[n++] = keep(i);
            if (ii != jj) {
                const uint32_t p = ii ? cross(i, j) : cross(j, i);
                poly[n++] = p;
                x[nx++] = p;
            }
        }
        for (int k = 1; k + 1 < n; ++k) {
            out.t.push_back(Tri{{poly[0], poly[k], poly[k + 1]}});
            out.cap.push_back(s.cap[ti]);
        }
        if (nx == 2 && x[0] != x[1]) segs.emplace_back(x[0], x[1]);
    }
    if (caps && !segs.empty()) add_cap(out, segs, axis, c);
    return out;
}

// Connected components (through shared vertex ids), in order of their
// first triangle.
std::vector<Soup> components(const Soup &s) {
    std::vector<uint32_t> parent(s.v.size());
    std::iota(parent.begin(), parent.end(), 0u);
    auto find = [&](uint32_t x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    };
    for (const Tri &t : s.t)
        for (int k = 1; k < 3; ++k) {
            uint32_t a = find(t[0]), b = find(t[k]);
            if (a != b) parent[std::max(a, b)] = std::min(a, b);
        }
    std::vector<uint32_t> comp_of_root(s.v.size(), kNone);
    std::vector<Soup> out;
    std::vector<std::vector<uint32_t>> maps;
    for (size_t ti = 0; ti < s.t.size(); ++ti) {
        const Tri &t = s.t[ti];
        const uint32_t r = find(t[0]);
        if (comp_of_root[r] == kNone) {
            comp_of_root[r] = uint32_t(out.size());
            out.emplace_back();
            maps.emplace_back(s.v.size(), kNone);
        }
        Soup &o = out[comp_of_root[r]];
        std::vector<uint32_t> &m = maps[comp_of_root[r]];
        Tri nt;
        for (int k = 0; k < 3; ++k) {
            if (m[t[k]] == kNone) {
                m[t[k]] = uint32_t(o.v.size());
                o.v.push_back(s.v[t[k]]);
            }
            nt[k] = m[t[k]];
        }
        o.t.push_back(nt);
        o.cap.push_back(s.cap[ti]);
    }
    return out;
}

// ---- Driver -----------------------------------------------------------------

struct Piece {
    Soup soup;
    Hull hull;
    Box box;
    double concavity = 0;
    int depth = 0;
};

struct Context {
    double tol = 0;  // absolute
    double band = 0; // vertices this close to a cutting plane are on it (absolute)
    double tie = 0;  // cut scores this close are equal (absolute; see Candidates)
    bool closed = false;
    unsigned max_pieces = kDefaultMaxPieces;
    unsigned threads = 1;
    int (*progress)(void *, int, double) = nullptr;
    void *user = nullptr;
    size_t cuts = 0, merges = 0;

    void report(int stage, double fraction) const {
        if (progress != nullptr && progress(user, stage, std::min(1.0, std::max(0.0, fraction))) != 0)
            throw Cancelled();
    }
};

// Runs f(0) .. f(n - 1) on up to `threads` threads (the caller's included).
// Callers write results into slots indexed by i and reduce them in index
// order afterwards, so the outcome does not depend on the thread count. The
// first exception thrown by a task is rethrown here after all threads end.
template <class F> void parallel_for(unsigned threads, size_t n, F &&f) {
    if (threads <= 1 || n <= 1) {
        for (size_t i = 0; i < n; ++i) f(i);
        return;
    }
    std::atomic<size_t> next{0};
    std::exception_ptr error;
    std::mutex error_mutex;
    auto work = [&]() {
        for (;;) {
            const size_t i = next.fetch_add(1);
            if (i >= n) return;
            try {
                f(i);
            } catch (...) {
                std::lock_guard<std::mutex> lock(error_mutex);
                if (!error) error = std::current_exception();
                next.store(n);
                return;
            }
        }
    };
    std::vector<std::thread> pool;
    const size_t extra = std::min<size_t>(threads, n) - 1;
    try {
        for (size_t t = 0; t < extra; ++t) pool.emplace_back(work);
    } catch (...) {
        // Could not start a thread: the caller's thread does the rest.
    }
    work();
    for (std::thread &t : pool) t.join();
    if (error) std::rethrow_exception(error);
}

struct Cut {
    int axis = -1;
    double offset = 0;
    double score = HUGE_VAL;
    double sum = HUGE_VAL;
};

// Score of cutting `s` at x[axis] = c: the larger sampled concavity of the
// two halves (each half measured as a whole, before splitting into
// components: cheaper, and an upper bound in practice). Returns HUGE_VAL
// when one side is empty. Branch and bound: a half worse than `best` ends
// the evaluation.
Cut evaluate(const Context &ctx, const Soup &s, int axis, double c, double best) {
    Cut r;
    r.axis = axis;
    r.offset = c;
    const Soup a = clip_half(s, axis, c, true, ctx.closed, ctx.band);
    if (a.t.empty()) return r;
    const Soup b = clip_half(s, axis, c, false, ctx.closed, ctx.band);
    if (b.t.empty()) return r;
    const double ca = concavity_of(a, hull_of_soup(a), kRankSamples, best);
    if (ca > best) {
        r.score = ca;
        return r;
    }
    const double cb = concavity_of(b, hull_of_soup(b), kRankSamples, best);
    r.score = std::max(ca, cb);
    r.sum = ca + cb;
    return r;
}

// The cuts evaluated for one piece, and the choice among them. Scores
// within ctx.tie of the lowest count as equal (2^-30 of the input's largest
// coordinate or diagonal, at most 2^-10 of the tolerance), and among those
// the lowest sum wins (the cut whose other half is best), then the lowest
// score, then the first evaluated. Why: often every good cut leaves the
// same worst feature in one half (a symmetric part), so their scores are
// equal but for rounding, and only the sum tells them apart. Compared
// exactly, the rounding chose. On the Puma's link6 turned by a half-turn
// (sin(pi) = 1.2e-16 moves coordinates by ulps), a cut scored 2 ulps below
// the cut that sliced off a clean piece left both halves as concave as the
// whole, and so did the cuts after it: after 15 minutes 370 pieces had been
// cut, to depth 10, each still spanning the link, of up to 26,000
// triangles (caps cut into caps), and px_urdf_load never returned.
struct Candidates {
    std::vector<Cut> all;
    double lowest = HUGE_VAL; // lowest score so far

    Cut best(double tie) const {
        Cut b;
        if (!(lowest < HUGE_VAL)) return b;
        for (const Cut &c : all) {
            if (!(c.score <= lowest + tie)) continue;
            if (b.axis < 0 || c.sum < b.sum || (c.sum == b.sum && c.score < b.score)) b = c;
        }
        return b;
    }
};

// Evaluates the planes x[axis] = offsets[i] as one batch (in parallel when
// ctx.threads > 1), all with the bound `lowest + tie` taken before the
// batch, and adds them to `cands` in index order. Same choice as evaluating
// every candidate in full: a candidate cut short by the bound scores above
// it, hence outside the ties for good (the lowest only goes down), and
// candidates within the bound are exact.
void evaluate_batch(const Context &ctx, const Soup &s, int axis, const std::vector<double> &offsets,
                    Candidates &cands) {
    std::vector<Cut> r(offsets.size());
    const double bound = cands.lowest + ctx.tie;
    parallel_for(ctx.threads, offsets.size(),
                 [&](size_t i) { r[i] = evaluate(ctx, s, axis, offsets[i], bound); });
    for (const Cut &c : r) {
        cands.all.push_back(c);
        cands.lowest = std::min(cands.lowest, c.score);
    }
}

// Sorted coordinates of the soup's vertices along `axis`.
std::vector<double> sorted_coordinates(const Soup &s, int axis) {
    std::vector<double> x(s.v.size());
    for (size_t i = 0; i < s.v.size(); ++i) x[i] = s.v[i][axis];
    std::sort(x.begin(), x.end());
    return x;
}

// A plane within a hair (1e-9 of the extent) of a vertex would make cut
// points a few ulps from that vertex, hence sliver hull faces and
// near-duplicate hull points (CAD meshes have vertices at round fractions of
// their box, like our offsets): move the plane onto the vertex instead; the
// cut then passes exactly through it (on-plane rule above).
double snap_offset(const std::vector<double> &sorted, double c, double extent) {
    const double hair = 1e-9 * extent;
    auto it = std::lower_bound(sorted.begin(), sorted.end(), c);
    double best = c, gap = HUGE_VAL;
    if (it != sorted.end() && *it - c < gap) {
        gap = *it - c;
        best = *it;
    }
    if (it != sorted.begin() && c - *(it - 1) < gap) {
        gap = c - *(it - 1);
        best = *(it - 1);
    }
    return gap <= hair ? best : c;
}

Cut best_cut(const Context &ctx, const Piece &p, double fraction) {
    Candidates cands;
    double step[3];
    std::vector<double> sorted[3];
    for (int axis = 0; axis < 3; ++axis) {
        const double lo = p.box.lo[axis], hi = p.box.hi[axis];
        step[axis] = (hi - lo) / (kOffsets + 1);
        // Along an axis where the piece is no thicker than the tolerance,
        // its concavity (above the tolerance) lies across the axis, and
        // cutting along it only makes thinner slabs of the same cross
        // section. A slab between two cuts, full of cap triangles, was cut
        // along its thickness again and again (coarse scores promised
        // 0.0128, the halves came back at the parent's 0.0174): Puma link 2
        // scaled by 0.1 at tolerance 0.01 ran for over 15 minutes.
        if (!(hi - lo > ctx.tol)) continue;
        sorted[axis] = sorted_coordinates(p.soup, axis);
        std::vector<double> offsets;
        for (int i = 1; i <= kOffsets; ++i) {
            const double c = snap_offset(sorted[axis], lo + (hi - lo) * i / (kOffsets + 1), hi - lo);
            if (c > lo && c < hi) offsets.push_back(c);
        }
        evaluate_batch(ctx, p.soup, axis, offsets, cands);
        ctx.report(PXCD_STAGE_CUT, fraction);
    }
    Cut best = cands.best(ctx.tie);
    if (best.axis < 0) return best;
    // Local refinement of the offset (CoACD refines its best plane too).
    const int axis = best.axis;
    double h = step[axis] * 0.5;
    const double lo = p.box.lo[axis], hi = p.box.hi[axis];
    for (int it = 0; it < kRefineSteps && best.axis == axis; ++it, h *= 0.5) {
        std::vector<double> offsets;
        for (int sgn = -1; sgn <= 1; sgn += 2) {
            const double c = snap_offset(sorted[axis], best.offset + sgn * h, hi - lo);
            if (c > lo && c < hi) offsets.push_back(c);
        }
        evaluate_batch(ctx, p.soup, axis, offsets, cands);
        best = cands.best(ctx.tie);
    }
    return best;
}

Piece make_piece(Soup &&s, int depth) {
    Piece p;
    p.soup = std::move(s);
    p.box = box_of(p.soup);
    p.depth = depth;
    return p;
}

std::vector<Piece> cut_all(Context &ctx, std::vector<Soup> &&initial, double total_area) {
    std::deque<Piece> work;
    for (Soup &s : initial) work.push_back(make_piece(std::move(s), 0));
    std::vector<Piece> done;
    double done_area = 0;
    auto finish = [&](Piece &&p) {
        done_area += surface_area(p.soup);
        done.push_back(std::move(p));
    };
    while (!work.empty()) {
        Piece p = std::move(work.front());
        work.pop_front();
        const double fraction = total_area > 0 ? done_area / total_area : 0.0;
        ctx.report(PXCD_STAGE_CUT, fraction);
        p.hull = hull_of_soup(p.soup);
        const bool small = p.box.diagonal() <= ctx.tol;
        const bool capped = p.depth >= kMaxDepth || done.size() + work.size() + 1 >= ctx.max_pieces;
        // The concavity is at most the box diagonal, so small pieces need
        // no measure to be accepted; they still get their estimate.
        const double bound = small || capped ? HUGE_VAL : ctx.tol;
        p.concavity = concavity_of(p.soup, p.hull, kAcceptSamples, bound);
        if (p.concavity <= ctx.tol || small || capped) {
            finish(std::move(p));
            continue;
        }
        const Cut cut = best_cut(ctx, p, fraction);
        if (cut.axis < 0 || !(cut.score < HUGE_VAL)) {
            p.concavity = concavity_of(p.soup, p.hull, kAcceptSamples, HUGE_VAL);
            finish(std::move(p));
            continue;
        }
        ++ctx.cuts;
        for (int side = 0; side < 2; ++side) {
            Soup half = clip_half(p.soup, cut.axis, cut.offset, side == 0, ctx.closed, ctx.band);
            for (Soup &c : components(half)) work.push_back(make_piece(std::move(c), p.depth + 1));
        }
    }
    return done;
}

Soup join(const Soup &a, const Soup &b) {
    Soup s = a;
    const uint32_t off = uint32_t(s.v.size());
    s.v.insert(s.v.end(), b.v.begin(), b.v.end());
    for (const Tri &t : b.t) s.t.push_back(Tri{{t[0] + off, t[1] + off, t[2] + off}});
    s.cap.insert(s.cap.end(), b.cap.begin(), b.cap.end());
    return s;
}

Hull hull_of_two(const Piece &a, const Piece &b) {
    std::vector<Point_3> pts;
    for (const Vec3 &v : a.hull.p) pts.push_back(to_point(v));
    for (const Vec3 &v : b.hull.p) pts.push_back(to_point(v));
    return hull_of_points(pts);
}

// Greedy merge pass (CoACD's, with the cost measured against the union of
// the two pieces' own surfaces). A merged piece's estimate is that cost.
void merge_all(Context &ctx, std::vector<Piece> &pieces) {
    const size_t n = pieces.size();
    if (n < 2) return;
    std::vector<uint8_t> alive(n, 1);
    // cost[(i, j)] for i < j, only pairs within reach and within tolerance.
    std::map<std::pair<uint32_t, uint32_t>, double> cost;
    // Evaluates the pairs as one batch (in parallel when threads > 1) and
    // records them in order.
    auto eval = [&](const std::vector<std::pair<uint32_t, uint32_t>> &pairs) {
        std::vector<double> c(pairs.size());
        parallel_for(ctx.threads, pairs.size(), [&](size_t k) {
            const Piece &a = pieces[pairs[k].first], &b = pieces[pairs[k].second];
            const Hull h = hull_of_two(a, b);
            const Soup *both[2] = {&a.soup, &b.soup};
            c[k] = concavity(h, both, 2, kAcceptSamples, ctx.tol);
        });
        for (size_t k = 0; k < pairs.size(); ++k)
            if (c[k] <= ctx.tol) cost[pairs[k]] = c[k];
    };
    {
        std::vector<std::pair<uint32_t, uint32_t>> all;
        for (uint32_t i = 0; i < n; ++i)
            for (uint32_t j = i + 1; j < n; ++j)
                if (pieces[i].box.overlaps(pieces[j].box, ctx.tol)) all.emplace_back(i, j);
        // In chunks, so that the progress callback is called now and then.
        const size_t chunk = 32;
        for (size_t b = 0; b < all.size(); b += chunk) {
            ctx.report(PXCD_STAGE_MERGE, 0.5 * double(b) / double(all.size()));
            eval(std::vector<std::pair<uint32_t, uint32_t>>(all.begin() + b,
                                                            all.begin() + std::min(all.size(), b + chunk)));
        }
    }
    size_t live = n;
    while (!cost.empty()) {
        auto best = cost.begin();
        for (auto it = cost.begin(); it != cost.end(); ++it)
            if (it->second < best->second) best = it; // map order breaks ties by (i, j)
        const uint32_t i = best->first.first, j = best->first.second;
        const double c = best->second;
        Piece m;
        m.soup = join(pieces[i].soup, pieces[j].soup);
        m.hull = hull_of_two(pieces[i], pieces[j]);
        m.box = pieces[i].box;
        m.box.add(pieces[j].box.lo);
        m.box.add(pieces[j].box.hi);
        m.concavity = c;
        m.depth = std::min(pieces[i].depth, pieces[j].depth);
        pieces[i] = std::move(m);
        pieces[j] = Piece();
        alive[j] = 0;
        --live;
        ++ctx.merges;
        for (auto it = cost.begin(); it != cost.end();)
            if (it->first.first == i || it->first.second == i || it->first.first == j ||
                it->first.second == j)
                it = cost.erase(it);
            else
                ++it;
        ctx.report(PXCD_STAGE_MERGE, 0.5 + 0.5 * double(n - live) / double(n));
        std::vector<std::pair<uint32_t, uint32_t>> pairs;
        for (uint32_t k = 0; k < n; ++k)
            if (alive[k] && k != i && pieces[i].box.overlaps(pieces[k].box, ctx.tol))
                pairs.emplace_back(std::min(i, k), std::max(i, k));
        eval(pairs);
    }
    std::vector<Piece> kept;
    for (size_t k = 0; k < n; ++k)
        if (alive[k]) kept.push_back(std::move(pieces[k]));
    pieces.swap(kept);
}

bool finite3(const double *p) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }

struct Bits_hash {
    size_t operator()(const Vec3 &v) const {
        uint64_t h = 1469598103934665603ull;
        for (double d : v) {
            uint64_t b;
            std::memcpy(&b, &d, 8);
            h = (h ^ b) * 1099511628211ull;
            h ^= h >> 29;
        }
        return size_t(h);
    }
};
struct Bits_equal {
    bool operator()(const Vec3 &a, const Vec3 &b) const { return std::memcmp(a.data(), b.data(), 24) == 0; }
};

pxcd_decomp_result *run(const double *xyz, size_t n_vertices, const uint32_t *tri, size_t n_triangles,
                        const pxcd_decomp_options *opt) {
    if (xyz == nullptr || tri == nullptr || opt == nullptr) throw Bad_input("a required pointer is NULL");
    if (n_triangles == 0) throw Bad_input("no triangles");
    if (n_vertices == 0 || n_vertices > UINT32_MAX) throw Bad_input("vertex count is 0 or above UINT32_MAX");
    if (n_triangles > (size_t(UINT32_MAX) / 4)) throw Bad_input("too many triangles");
    if (!std::isfinite(opt->tolerance) || !(opt->tolerance > 0))
        throw Bad_input("tolerance must be finite and > 0");
    for (unsigned r : opt->reserved)
        if (r != 0) throw Bad_input("reserved option fields must be zero");
    for (size_t i = 0; i < 3 * n_triangles; ++i)
        if (tri[i] >= n_vertices) throw Bad_input("a triangle has a vertex id out of range");
    for (size_t i = 0; i < 3 * n_triangles; ++i)
        if (!finite3(xyz + 3 * size_t(tri[i]))) throw Bad_input("a vertex used by a triangle is not finite");

    Context ctx;
    ctx.max_pieces = opt->max_pieces != 0 ? opt->max_pieces : kDefaultMaxPieces;
    ctx.threads = std::max(1u, std::min(opt->threads, 64u));
    ctx.progress = opt->progress;
    ctx.user = opt->user;

    // Weld bit-identical vertices (first occurrence order).
    Soup all;
    {
        std::unordered_map<Vec3, uint32_t, Bits_hash, Bits_equal> id;
        std::vector<uint32_t> map(n_vertices, kNone);
        all.t.reserve(n_triangles);
        for (size_t i = 0; i < n_triangles; ++i) {
            Tri t;
            for (int k = 0; k < 3; ++k) {
                const uint32_t v = tri[3 * i + k];
                if (map[v] == kNone) {
                    const Vec3 p{{xyz[3 * v] + 0.0, xyz[3 * v + 1] + 0.0, xyz[3 * v + 2] + 0.0}}; // -0 -> +0
                    auto ins = id.emplace(p, uint32_t(all.v.size()));
                    if (ins.second) all.v.push_back(p);
                    map[v] = ins.first->second;
                }
                t[k] = map[v];
            }
            all.t.push_back(t);
        }
        all.cap.assign(all.t.size(), 0);
    }
    // Closed: every undirected edge (between distinct vertices) used an even
    // number of times.
    {
        std::vector<std::pair<uint32_t, uint32_t>> edges;
        edges.reserve(3 * all.t.size());
        for (const Tri &t : all.t)
            for (int k = 0; k < 3; ++k) {
                uint32_t a = t[k], b = t[(k + 1) % 3];
                if (a == b) continue;
                edges.emplace_back(std::min(a, b), std::max(a, b));
            }
        std::sort(edges.begin(), edges.end());
        bool closed = true;
        for (size_t i = 0; i < edges.size() && closed;) {
            size_t j = i;
            while (j < edges.size() && edges[j] == edges[i]) ++j;
            if ((j - i) % 2 != 0) closed = false;
            i = j;
        }
        ctx.closed = closed && !edges.empty();
    }
    const Box box = box_of(all);
    const double diagonal = box.diagonal();
    ctx.tol = opt->tolerance * diagonal;
    if (!std::isfinite(diagonal)) throw Bad_input("the mesh's bounding-box diagonal overflows");
    {
        // 2^12 ulps of the largest coordinate or of the diagonal: far above
        // the rounding of a turned or scaled mesh, far below any tolerance.
        double scale = diagonal;
        for (int k = 0; k < 3; ++k)
            scale = std::max(scale, std::max(std::fabs(box.lo[k]), std::fabs(box.hi[k])));
        ctx.band = std::ldexp(scale, -40);
        ctx.tie = std::min(std::ldexp(scale, -30), std::ldexp(ctx.tol, -10));
    }

    ctx.report(PXCD_STAGE_CUT, 0.0);
    const double total_area = surface_area(all);
    std::vector<Piece> pieces = cut_all(ctx, components(all), total_area);
    ctx.report(PXCD_STAGE_CUT, 1.0);
    merge_all(ctx, pieces);
    ctx.report(PXCD_STAGE_MERGE, 1.0);

    // Output: C allocations, freed by pxcd_decomp_free (also on failure).
    struct Guard {
        pxcd_decomp_result *r;
        ~Guard() { pxcd_decomp_free(r); }
    } guard{static_cast<pxcd_decomp_result *>(std::calloc(1, sizeof(pxcd_decomp_result)))};
    pxcd_decomp_result *res = guard.r;
    if (res == nullptr) throw std::bad_alloc();
    res->pieces = static_cast<pxcd_decomp_piece *>(
        std::calloc(pieces.size() ? pieces.size() : 1, sizeof(pxcd_decomp_piece)));
    if (res->pieces == nullptr) throw std::bad_alloc();
    res->diagonal = diagonal;
    res->closed = ctx.closed ? 1 : 0;
    res->cuts = ctx.cuts;
    res->merges = ctx.merges;
    for (size_t i = 0; i < pieces.size(); ++i) {
        ctx.report(PXCD_STAGE_HULL, double(i) / double(pieces.size()));
        const Hull h = hull_of_soup(pieces[i].soup); // re-hull (canonical: sorted points)
        pxcd_decomp_piece &out = res->pieces[i];
        out.vertices = static_cast<double *>(std::malloc(3 * sizeof(double) * (h.p.size() ? h.p.size() : 1)));
        if (out.vertices == nullptr) throw std::bad_alloc();
        for (size_t k = 0; k < h.p.size(); ++k)
            for (int d = 0; d < 3; ++d) out.vertices[3 * k + d] = h.p[k][d];
        out.vertex_count = h.p.size();
        out.concavity = pieces[i].concavity;
        res->piece_count = i + 1;
        if (out.concavity > ctx.tol) ++res->pieces_over;
    }
    ctx.report(PXCD_STAGE_HULL, 1.0);
    guard.r = nullptr;
    return res;
}

} // namespace

extern "C" pxcd_status pxcd_decompose(const double *xyz, size_t n_vertices, const uint32_t *tri,
                                      size_t n_triangles, const pxcd_decomp_options *opt,
                                      pxcd_decomp_result **out, char *msg, size_t msg_len) {
    set_msg(msg, msg_len, "");
    if (out == nullptr) {
        set_msg(msg, msg_len, "pxcd_decompose: out is NULL");
        return PXCD_INVALID_INPUT;
    }
    *out = nullptr;
    try {
        *out = run(xyz, n_vertices, tri, n_triangles, opt);
        return PXCD_OK;
    } catch (const Bad_input &e) {
        char buf[256];
        std::snprintf(buf, sizeof buf, "pxcd_decompose: %s", e.what());
        set_msg(msg, msg_len, buf);
        return PXCD_INVALID_INPUT;
    } catch (const Cancelled &) {
        set_msg(msg, msg_len, "pxcd_decompose: cancelled by the progress callback");
        return PXCD_CANCELLED;
    } catch (const std::bad_alloc &) {
        set_msg(msg, msg_len, "pxcd_decompose: out of memory");
        return PXCD_OUT_OF_MEMORY;
    } catch (const CGAL::Failure_exception &e) {
        char buf[512];
        std::snprintf(buf, sizeof buf, "pxcd_decompose: CGAL failure: %s", e.what());
        set_msg(msg, msg_len, buf);
        return PXCD_ERROR;
    } catch (const std::exception &e) {
        char buf[512];
        std::snprintf(buf, sizeof buf, "pxcd_decompose: %s", e.what());
        set_msg(msg, msg_len, buf);
        return PXCD_ERROR;
    } catch (...) {
        set_msg(msg, msg_len, "pxcd_decompose: unknown exception");
        return PXCD_ERROR;
    }
}

extern "C" void pxcd_decomp_free(pxcd_decomp_result *result) {
    if (result == nullptr) return;
    if (result->pieces != nullptr)
        for (size_t i = 0; i < result->piece_count; ++i) std::free(result->pieces[i].vertices);
    std::free(result->pieces);
    std::free(result);
}
