// pxcd_hull_compute / pxcd_hull_free: convex hull of a point set as convex
// polygons, behind the C ABI of pxcd.h.
//
// Algorithm and sources:
//   - Affine dimension: exact predicates CGAL::collinear / CGAL::coplanar
//     (CGAL 5.5 manual, "2D and 3D Linear Geometry Kernel", Global Functions).
//     Epick evaluates predicates exactly (static and interval filters with an
//     exact fallback), so the reported dimension is that of the input doubles.
//   - Hull: CGAL::convex_hull_3 (CGAL 5.5 manual, "3D Convex Hulls", section
//     "Static Convex Hull Construction"; quickhull of Barber, Dobkin and
//     Huhdanpaa, ACM TOMS 22(4), 1996), kernel
//     Exact_predicates_inexact_constructions_kernel, with the traits
//     Convex_hull_traits_3<Epick, Default, Tag_true>: its "planes" are point
//     triples, so every side-of-plane test is an exact orientation predicate.
//     We use the overload that outputs an indexed triangle set (points +
//     triangles) rather than a Surface_mesh: it runs the same algorithm with
//     the same traits (those are also what the Surface_mesh overload picks by
//     default), but the Surface_mesh overload spends about as long again
//     copying the hull into the mesh through hash maps (measured: ~1.0 s vs
//     ~1.9 s for 200k points on an ellipsoid). We need only triangle
//     adjacency, which is cheap to rebuild. Do NOT use that overload without
//     the traits: it then falls back to the bare kernel, whose Plane_3 is
//     constructed in floating point and makes the hull inexact.
//   - Polygons: adjacent hull triangles whose four points are exactly
//     coplanar (CGAL::coplanar) are merged with a union-find; the boundary of
//     each group is traced into one loop, outward (CCW from outside) like the
//     triangles.
//
// Why a clean-up step after convex_hull_3: quickhull only adds a point that
// is strictly outside the current hull, but a point added early can later end
// up in the relative interior of a hull edge or facet (the "farthest point"
// is chosen among the outside set of one facet only, ties are possible).
// Such a point stays a vertex, because the triangles around it that are
// coplanar with the new point are not strictly visible and are kept. After
// the merge:
//   - a non-extreme vertex inside a facet is strictly inside the merged
//     region, so it is not on the boundary loop and disappears by itself;
//   - a non-extreme vertex inside a hull edge shows up, in the loops of the
//     two facets sharing that edge, exactly collinear with its two
//     neighbours. Corners of a facet (extreme points of the hull) never are.
// Dropping exactly-collinear loop vertices therefore leaves exactly the
// extreme points, and both facets of an edge drop the same vertices, so
// edges stay paired. The final topological check (Euler, edge pairing)
// turns any surprise into PXCD_ERROR instead of a broken hull.
//
// Valgrind: Epick's interval filters switch the FPU to upward rounding, which
// valgrind does not emulate (its SSE arithmetic always rounds to nearest),
// so under valgrind filtered predicates can return wrong signs on
// near-degenerate input and quickhull can crash (seen on a point set one ulp
// off coplanar). CGAL's own start-up check for this aborts, so it is
// disabled (CGAL_DISABLE_ROUNDING_MATH_CHECK); instead we run the same check
// once (directed_rounding_works) and, if rounding modes do not work, compute
// with Simple_cartesian<Exact_rational>: no filters, no dependence on the
// FPU, same algorithm, slower. Tests force that path with
// pxcd_hull_compute_ex(..., PXCD_HULL_FORCE_EXACT_KERNEL, ...); the library
// reads no environment variable.
//
// Determinism: quickhull's output order depends on memory addresses (CGAL
// keys a std::map by vertex handles), so equal inputs gave differently
// ordered triangles from one call to the next (seen in our tests). The hull itself (extreme points, facets)
// is unique, so we canonicalize: vertices are numbered by the index of their first occurrence in the input
// and take that input point's coordinates (bit-identical), each loop starts at its smallest id, and loops are
// sorted by their first two ids (unique: a directed edge belongs to one face).

#include "pxcd.h"

#include <CGAL/Convex_hull_traits_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Exact_rational.h>
#include <CGAL/FPU.h>
#include <CGAL/Projection_traits_xy_3.h>
#include <CGAL/Projection_traits_xz_3.h>
#include <CGAL/Projection_traits_yz_3.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/convex_hull_2.h>
#include <CGAL/convex_hull_3.h>
#include <CGAL/exceptions.h>

#include <algorithm>
#include <cfenv>
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <iterator>
#include <new>
#include <numeric>
#include <stdexcept>
#include <utility>
#include <vector>

namespace {

// Fast path: filtered exact predicates; Tag_true selects the point-triple
// side-of-plane predicate with static filters.
using Fast_kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Fast_traits = CGAL::Convex_hull_traits_3<Fast_kernel, CGAL::Default, CGAL::Tag_true>;
// Fallback when directed rounding does not work (valgrind): plain rationals.
using Exact_kernel = CGAL::Simple_cartesian<CGAL::Exact_rational>;
using Exact_traits = CGAL::Convex_hull_traits_3<Exact_kernel>;

using Triangle = std::array<std::size_t, 3>;
using Xyz = std::array<double, 3>;

constexpr uint32_t kNone = UINT32_MAX;

void set_msg(char *msg, size_t msg_len, const char *text) {
    if (msg != nullptr && msg_len > 0) std::snprintf(msg, msg_len, "%s", text);
}

// Internal consistency failures, reported as PXCD_ERROR.
struct Hull_error : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Affine dimension of the point set (0..3), with exact predicates. Looks for
// a second distinct point, then a point off their line, then a point off
// their plane; each scan is linear and stops at the first witness.
template <class Point_3> int affine_dimension(const std::vector<Point_3> &pts) {
    const Point_3 &a = pts[0];
    size_t i = 1;
    while (i < pts.size() && pts[i] == a) ++i;
    if (i == pts.size()) return 0;
    const Point_3 &b = pts[i];
    size_t j = i + 1;
    while (j < pts.size() && CGAL::collinear(a, b, pts[j])) ++j;
    if (j >= pts.size()) return 1;
    const Point_3 &c = pts[j];
    size_t k = j + 1;
    while (k < pts.size() && CGAL::coplanar(a, b, c, pts[k])) ++k;
    if (k >= pts.size()) return 2;
    return 3;
}

// Union-find with path halving; the union keeps the smaller index as root.
struct Union_find {
    std::vector<uint32_t> parent;
    explicit Union_find(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
    uint32_t find(uint32_t x) {
        while (parent[x] != x) {
            parent[x] = parent[parent[x]];
            x = parent[x];
        }
        return x;
    }
    void unite(uint32_t a, uint32_t b) {
        a = find(a);
        b = find(b);
        if (a == b) return;
        if (a < b)
            parent[b] = a;
        else
            parent[a] = b;
    }
};

// Closed triangle mesh with implicit halfedges: halfedge h = 3 t + i goes
// from tri[t][i] to tri[t][(i + 1) % 3]; opposite[] (filled by link()) is
// the only stored connectivity.
template <class Point_3> struct Tri_mesh {
    std::vector<Point_3> points;
    std::vector<Triangle> tris;
    std::vector<uint32_t> opposite;

    static uint32_t next(uint32_t h) { return h % 3 == 2 ? h - 2 : h + 1; }
    static uint32_t face(uint32_t h) { return h / 3; }
    uint32_t source(uint32_t h) const { return static_cast<uint32_t>(tris[h / 3][h % 3]); }
    uint32_t target(uint32_t h) const { return source(next(h)); }
    const Point_3 &point(uint32_t v) const { return points[v]; }

    void link();
};

// For directed edges e = src[e] -> dst[e] over vertices 0..vertex_count-1,
// returns rev with rev[e] = the edge dst[e] -> src[e]. Throws unless every
// edge has exactly one reverse; this also rules out repeated directed edges
// (the reverse of a repeated edge would see two candidates). Linear time:
// edges are bucketed by source (compressed rows), and the reverse of u -> v
// is looked up among the few edges leaving v.
std::vector<uint32_t> pair_reverse_edges(size_t vertex_count, const std::vector<uint32_t> &src,
                                         const std::vector<uint32_t> &dst) {
    const size_t ne = src.size();
    if (ne >= kNone || vertex_count >= kNone) throw Hull_error("hull too large for 32-bit indices");
    std::vector<uint32_t> first(vertex_count + 1, 0);
    for (uint32_t u : src) {
        if (u >= vertex_count) throw Hull_error("vertex index out of range");
        ++first[u + 1];
    }
    std::partial_sum(first.begin(), first.end(), first.begin());
    std::vector<uint32_t> fill(first.begin(), first.end() - 1), out_dst(ne), out_edge(ne);
    for (uint32_t e = 0; e < ne; ++e) {
        const uint32_t k = fill[src[e]]++;
        out_dst[k] = dst[e];
        out_edge[k] = e;
    }
    std::vector<uint32_t> rev(ne, kNone);
    for (uint32_t e = 0; e < ne; ++e) {
        const uint32_t u = src[e], v = dst[e];
        if (v >= vertex_count) throw Hull_error("vertex index out of range");
        for (uint32_t k = first[v]; k < first[v + 1]; ++k)
            if (out_dst[k] == u) {
                if (rev[e] != kNone) throw Hull_error("hull edges are not paired");
                rev[e] = out_edge[k];
            }
        if (rev[e] == kNone) throw Hull_error("hull edges are not paired");
    }
    return rev;
}

template <class Point_3> void Tri_mesh<Point_3>::link() {
    const size_t nh = 3 * tris.size();
    if (nh >= kNone) throw Hull_error("hull too large for 32-bit indices");
    std::vector<uint32_t> src(nh), dst(nh);
    for (uint32_t h = 0; h < nh; ++h) {
        const std::size_t u = tris[h / 3][h % 3], v = tris[h / 3][(h + 1) % 3];
        if (u >= points.size() || v >= points.size()) throw Hull_error("bad vertex index from convex_hull_3");
        src[h] = static_cast<uint32_t>(u);
        dst[h] = static_cast<uint32_t>(v);
    }
    opposite = pair_reverse_edges(points.size(), src, dst);
}

// Merges exactly coplanar adjacent triangles; returns the facet loops
// (mesh vertex ids, outward), concatenated, with offsets (size F + 1).
template <class Point_3>
void merge_coplanar_triangles(const Tri_mesh<Point_3> &mesh, std::vector<uint32_t> &loops,
                              std::vector<size_t> &offsets) {
    using Mesh = Tri_mesh<Point_3>;
    const size_t nf = mesh.tris.size(), nh = 3 * nf;

    // 1. Group triangles across edges whose two triangles are coplanar.
    //    Hull triangles are never degenerate (a new quickhull triangle joins
    //    a point strictly above a visible face to an edge of that face), so
    //    four coplanar points mean the same supporting plane, and groups are
    //    exactly the hull facets.
    Union_find uf(nf);
    for (uint32_t h = 0; h < nh; ++h) {
        const uint32_t o = mesh.opposite[h];
        if (o < h) continue; // each edge once
        const Point_3 &a = mesh.point(mesh.source(h));
        const Point_3 &b = mesh.point(mesh.target(h));
        const Point_3 &c = mesh.point(mesh.target(Mesh::next(h)));
        const Point_3 &d = mesh.point(mesh.target(Mesh::next(o)));
        if (CGAL::coplanar(a, b, c, d)) uf.unite(Mesh::face(h), Mesh::face(o));
    }
    std::vector<uint32_t> group(nf);
    for (uint32_t f = 0; f < nf; ++f) group[f] = uf.find(f);
    auto is_boundary = [&](uint32_t h) {
        return group[Mesh::face(h)] != group[Mesh::face(mesh.opposite[h])];
    };

    // 2. Per group: first boundary halfedge and number of boundary halfedges.
    std::vector<uint32_t> start(nf, kNone), boundary_count(nf, 0), roots;
    for (uint32_t h = 0; h < nh; ++h) {
        const uint32_t g = group[Mesh::face(h)];
        if (h % 3 == 0 && g == Mesh::face(h)) roots.push_back(g);
        if (!is_boundary(h)) continue;
        if (start[g] == kNone) start[g] = h;
        ++boundary_count[g];
    }

    // 3. Trace each group's boundary. From boundary halfedge h (ending at v),
    //    the next boundary halfedge of the group leaves v: turn around v
    //    through the group's triangles until the opposite triangle belongs to
    //    another group. A facet is a disk, so this visits every boundary
    //    halfedge of the group exactly once; the count check catches anything
    //    else. Then drop loop vertices exactly collinear with their
    //    neighbours (non-extreme points inside a hull edge, see above).
    loops.clear();
    offsets.assign(1, 0);
    std::vector<uint32_t> loop;
    std::vector<char> drop;
    for (uint32_t g : roots) {
        loop.clear();
        const uint32_t first = start[g];
        if (first == kNone) throw Hull_error("hull facet without boundary");
        uint32_t h = first;
        do {
            loop.push_back(mesh.source(h));
            if (loop.size() > boundary_count[g]) throw Hull_error("hull facet boundary is not a simple loop");
            uint32_t n = Mesh::next(h);
            size_t guard = 0;
            while (!is_boundary(n)) {
                n = Mesh::next(mesh.opposite[n]);
                if (++guard > nh) throw Hull_error("cannot trace a hull facet boundary");
            }
            h = n;
        } while (h != first);
        if (loop.size() != boundary_count[g]) throw Hull_error("hull facet boundary is not a simple loop");

        // A 3-vertex loop bounds a non-degenerate triangle: nothing to drop.
        const size_t m = loop.size();
        drop.assign(m, 0);
        for (size_t i = 0; m > 3 && i < m; ++i)
            drop[i] = CGAL::collinear(mesh.point(loop[(i + m - 1) % m]), mesh.point(loop[i]),
                                      mesh.point(loop[(i + 1) % m]));
        const size_t before = loops.size();
        for (size_t i = 0; i < m; ++i)
            if (!drop[i]) loops.push_back(loop[i]);
        if (loops.size() - before < 3) throw Hull_error("degenerate hull facet after merging");
        offsets.push_back(loops.size());
    }
}

// Open-addressing hash table from coordinates to an index into `points`
// (distinct points). Keys compare with == like CGAL's Point_3, so -0.0 and
// 0.0 match; the hash normalizes zeros (x + 0.0 turns -0.0 into 0.0).
class Point_table {
  public:
    Point_table(const std::vector<Xyz> &points, const std::vector<uint32_t> &keys) : points_(points) {
        size_t cap = 16;
        while (cap < 2 * keys.size()) cap *= 2;
        mask_ = cap - 1;
        slots_.assign(cap, kNone);
        for (uint32_t v : keys) {
            size_t i = hash(points[v].data()) & mask_;
            while (slots_[i] != kNone) i = (i + 1) & mask_;
            slots_[i] = v;
        }
    }
    // Index of the point with exactly these coordinates, or kNone.
    uint32_t find(const double *c) const {
        for (size_t i = hash(c) & mask_;; i = (i + 1) & mask_) {
            const uint32_t v = slots_[i];
            if (v == kNone) return kNone;
            const Xyz &p = points_[v];
            if (p[0] == c[0] && p[1] == c[1] && p[2] == c[2]) return v;
        }
    }

  private:
    static size_t hash(const double *c) {
        uint64_t h = 0x9E3779B97F4A7C15ull;
        for (int k = 0; k < 3; ++k) {
            const double x = c[k] + 0.0;
            uint64_t bits;
            std::memcpy(&bits, &x, sizeof bits);
            h = (h ^ bits) * 0xFF51AFD7ED558CCDull;
            h ^= h >> 32;
        }
        return static_cast<size_t>(h);
    }
    const std::vector<Xyz> &points_;
    std::vector<uint32_t> slots_;
    size_t mask_ = 0;
};

// Checks the combinatorics promised by pxcd.h: no repeated vertex in a loop,
// every undirected edge used exactly once in each direction, and Euler's
// formula V - E + F = 2.
void check_topology(size_t vertex_count, const std::vector<size_t> &offsets,
                    const std::vector<uint32_t> &indices) {
    const size_t face_count = offsets.size() - 1;
    std::vector<size_t> stamp(vertex_count, SIZE_MAX);
    std::vector<uint32_t> src(indices.size()), dst(indices.size());
    for (size_t f = 0; f < face_count; ++f) {
        const size_t b = offsets[f], e = offsets[f + 1];
        for (size_t i = b; i < e; ++i) {
            const uint32_t u = indices[i];
            if (stamp[u] == f) throw Hull_error("a hull facet repeats a vertex");
            stamp[u] = f;
            src[i] = u;
            dst[i] = indices[i + 1 < e ? i + 1 : b];
        }
    }
    // Each directed edge has exactly one reverse, so none repeats, and
    // undirected edges are exactly pairs of directed ones.
    pair_reverse_edges(vertex_count, src, dst);
    if (vertex_count + face_count != indices.size() / 2 + 2)
        throw Hull_error("hull violates Euler's formula");
}

// Hull facets as loops over `points` (hull vertices, as doubles), before
// canonical numbering. Lower-dimensional hulls: a polygon has two loops
// (the polygon both ways round), a segment its two end points and no loop,
// a point itself and no loop.
struct Facets {
    int dim = 3;
    std::vector<Xyz> points;
    std::vector<uint32_t> loops;
    std::vector<size_t> offsets;
};

template <class Point_3> Xyz to_xyz(const Point_3 &p) {
    return {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
}

// The extreme points of a planar point set, counter-clockwise in the
// coordinate plane `drop` leaves out (0: yz, 1: xz, 2: xy), by CGAL's
// convex_hull_2 with the projection traits: exact predicates on the input
// doubles, and only extreme points (no duplicate, no point in the middle
// of an edge). Projecting onto a coordinate plane that the points' plane is
// not perpendicular to maps the planar hull one to one.
template <class K>
void planar_hull(const std::vector<typename K::Point_3> &pts, int drop,
                 std::vector<typename K::Point_3> &out) {
    if (drop == 0)
        CGAL::convex_hull_2(pts.cbegin(), pts.cend(), std::back_inserter(out),
                            CGAL::Projection_traits_yz_3<K>());
    else if (drop == 1)
        CGAL::convex_hull_2(pts.cbegin(), pts.cend(), std::back_inserter(out),
                            CGAL::Projection_traits_xz_3<K>());
    else
        CGAL::convex_hull_2(pts.cbegin(), pts.cend(), std::back_inserter(out),
                            CGAL::Projection_traits_xy_3<K>());
}

// The hull of a point set of affine dimension below 3: a point, the two
// extreme points of a collinear set (the lexicographic least and greatest:
// along a line the lexicographic order is the order along it, and
// comparing coordinates is exact), or the polygon of a coplanar set.
template <class K>
void lower_dimensional_hull(const std::vector<typename K::Point_3> &pts, int dim, Facets &out) {
    using Point_3 = typename K::Point_3;
    out.offsets.assign(1, 0);
    if (dim == 0) {
        out.points.push_back(to_xyz(pts[0]));
        return;
    }
    if (dim == 1) {
        const auto lo = std::min_element(pts.cbegin(), pts.cend(), [](const Point_3 &a, const Point_3 &b) {
            return CGAL::compare_xyz(a, b) == CGAL::SMALLER;
        });
        const auto hi = std::max_element(pts.cbegin(), pts.cend(), [](const Point_3 &a, const Point_3 &b) {
            return CGAL::compare_xyz(a, b) == CGAL::SMALLER;
        });
        out.points.push_back(to_xyz(*lo));
        out.points.push_back(to_xyz(*hi));
        return;
    }
    // A coordinate plane the points' plane is not perpendicular to: one
    // where three affinely independent points project to a proper triangle
    // (an exact 2D orientation of input coordinates).
    const Point_3 &a = pts[0];
    size_t i = 1;
    while (CGAL::compare_xyz(pts[i], a) == CGAL::EQUAL) ++i;
    size_t j = i + 1;
    while (CGAL::collinear(a, pts[i], pts[j])) ++j;
    const Point_3 &b = pts[i], &c = pts[j];
    int drop = 2;
    if (CGAL::Projection_traits_xy_3<K>().orientation_2_object()(a, b, c) != CGAL::COLLINEAR)
        drop = 2;
    else if (CGAL::Projection_traits_yz_3<K>().orientation_2_object()(a, b, c) != CGAL::COLLINEAR)
        drop = 0;
    else
        drop = 1;
    std::vector<Point_3> ring;
    planar_hull<K>(pts, drop, ring);
    if (ring.size() < 3) throw Hull_error("planar hull of a coplanar set has fewer than 3 points");
    const uint32_t n = static_cast<uint32_t>(ring.size());
    for (const Point_3 &p : ring) out.points.push_back(to_xyz(p));
    // Both sides of the polygon: the ring, then the ring reversed.
    for (uint32_t k = 0; k < n; ++k) out.loops.push_back(k);
    out.offsets.push_back(n);
    for (uint32_t k = 0; k < n; ++k) out.loops.push_back(n - 1 - k);
    out.offsets.push_back(2 * size_t(n));
}

// Affine dimension, and the facets, computed with kernel K.
template <class K, class Traits> int compute_facets(const double *xyz, size_t count, Facets &out) {
    using Point_3 = typename K::Point_3;
    std::vector<Point_3> pts;
    pts.reserve(count);
    for (size_t i = 0; i < count; ++i) pts.emplace_back(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);

    const int dim = affine_dimension(pts);
    out.dim = dim;
    if (dim < 3) {
        lower_dimensional_hull<K>(pts, dim, out);
        return dim;
    }

    // The traits-taking overload has an extra template parameter that cannot
    // be deduced in CGAL 5.5 (unused; any type works), hence the explicit
    // template arguments.
    Tri_mesh<Point_3> mesh;
    using Iterator = typename std::vector<Point_3>::const_iterator;
    CGAL::convex_hull_3<Iterator, void, std::vector<Point_3>, std::vector<Triangle>, Traits>(
        pts.cbegin(), pts.cend(), mesh.points, mesh.tris, Traits());
    std::vector<Point_3>().swap(pts); // release early
    mesh.link();
    merge_coplanar_triangles(mesh, out.loops, out.offsets);

    // Hull points are copies of input doubles, so to_double is exact.
    out.points.resize(mesh.points.size());
    for (size_t v = 0; v < mesh.points.size(); ++v) out.points[v] = to_xyz(mesh.points[v]);
    return 3;
}

// CGAL's own test (Interval_nt.h, Test_runtime_rounding_modes): under
// upward rounding, -(-a * b) and a * b differ for inexact products.
bool directed_rounding_works() {
    using CGAL::IA_up; // the CGAL_IA_* macros expect to be used inside namespace CGAL
    CGAL::Protect_FPU_rounding<true> protect(CGAL_FE_UPWARD);
    return -CGAL_IA_MUL(-1.1, 10.1) != CGAL_IA_MUL(1.1, 10.1) && -CGAL_IA_DIV(-1., 10) != CGAL_IA_DIV(1., 10);
}

// Whether to compute with the exact kernel: when the caller forces it
// (tests), or when directed rounding does not work here (valgrind). The
// rounding test runs once; its answer is a property of the machine, not a
// setting.
bool use_exact_kernel(bool force) {
    static const bool rounding_works = directed_rounding_works();
    return force || !rounding_works;
}

// The hull (of any affine dimension, in *dimension), computed with
// the exact kernel if force_exact or use_exact_kernel says so. Throws on
// failure (std::bad_alloc, CGAL::Failure_exception, Hull_error).
pxcd_hull *compute(const double *xyz, size_t count, int *dimension, bool force_exact) {
    Facets facets;
    const int dim = use_exact_kernel(force_exact)
                        ? compute_facets<Exact_kernel, Exact_traits>(xyz, count, facets)
                        : compute_facets<Fast_kernel, Fast_traits>(xyz, count, facets);
    if (dimension != nullptr) *dimension = dim;
    const std::vector<uint32_t> &loops = facets.loops;
    const std::vector<size_t> &offsets = facets.offsets;
    const size_t face_count = offsets.size() - 1;
    const size_t point_count = facets.points.size();

    // Canonical vertex numbering: by first occurrence in the input. The used
    // hull vertices go into a hash table keyed by coordinates; one pass over
    // the input finds each one's first occurrence.
    std::vector<uint32_t> used;
    {
        std::vector<char> is_used(point_count, 0);
        for (uint32_t v : loops) is_used[v] = 1;
        if (dim < 2) std::fill(is_used.begin(), is_used.end(), 1); // a point or a segment: no loops
        for (uint32_t v = 0; v < point_count; ++v)
            if (is_used[v]) used.push_back(v);
    }
    std::vector<size_t> first_input(point_count, SIZE_MAX);
    {
        Point_table table(facets.points, used);
        size_t found = 0;
        for (size_t i = 0; i < count && found < used.size(); ++i) {
            const uint32_t v = table.find(&xyz[3 * i]);
            if (v != kNone && first_input[v] == SIZE_MAX) {
                first_input[v] = i;
                ++found;
            }
        }
        if (found != used.size()) throw Hull_error("a hull vertex is not an input point");
    }
    std::sort(used.begin(), used.end(),
              [&](uint32_t a, uint32_t b) { return first_input[a] < first_input[b]; });
    std::vector<uint32_t> new_id(point_count, kNone);
    for (uint32_t i = 0; i < used.size(); ++i) new_id[used[i]] = i;

    // Canonical loops: renumbered, rotated to start at the smallest id,
    // sorted by their first two ids.
    std::vector<uint32_t> indices(loops.size());
    for (size_t f = 0; f < face_count; ++f) {
        const size_t b = offsets[f], e = offsets[f + 1];
        for (size_t i = b; i < e; ++i) indices[i] = new_id[loops[i]];
        std::rotate(indices.begin() + b, std::min_element(indices.begin() + b, indices.begin() + e),
                    indices.begin() + e);
    }
    std::vector<std::pair<uint64_t, uint32_t>> face_order(face_count);
    for (uint32_t f = 0; f < face_count; ++f) {
        const uint32_t *p = &indices[offsets[f]];
        face_order[f] = {(uint64_t(p[0]) << 32) | p[1], f};
    }
    std::sort(face_order.begin(), face_order.end());
    std::vector<size_t> out_offsets(1, 0);
    std::vector<uint32_t> out_indices;
    out_offsets.reserve(face_count + 1);
    out_indices.reserve(indices.size());
    for (const auto &key_face : face_order) {
        const uint32_t f = key_face.second;
        out_indices.insert(out_indices.end(), indices.begin() + offsets[f], indices.begin() + offsets[f + 1]);
        out_offsets.push_back(out_indices.size());
    }
    if (dim >= 2) check_topology(used.size(), out_offsets, out_indices);

    // Copy into malloc'd arrays (the C side frees them with pxcd_hull_free).
    pxcd_hull *hull = static_cast<pxcd_hull *>(std::calloc(1, sizeof(pxcd_hull)));
    if (hull == nullptr) throw std::bad_alloc();
    hull->vertex_count = used.size();
    hull->face_count = face_count;
    hull->vertices = static_cast<double *>(std::malloc(3 * used.size() * sizeof(double)));
    hull->face_offsets = static_cast<size_t *>(std::malloc(out_offsets.size() * sizeof(size_t)));
    hull->face_indices = static_cast<uint32_t *>(std::malloc(out_indices.size() * sizeof(uint32_t)));
    if (hull->vertices == nullptr || hull->face_offsets == nullptr || hull->face_indices == nullptr) {
        pxcd_hull_free(hull);
        throw std::bad_alloc();
    }
    for (size_t i = 0; i < used.size(); ++i)
        std::copy(&xyz[3 * first_input[used[i]]], &xyz[3 * first_input[used[i]] + 3], &hull->vertices[3 * i]);
    std::copy(out_offsets.begin(), out_offsets.end(), hull->face_offsets);
    std::copy(out_indices.begin(), out_indices.end(), hull->face_indices);
    return hull;
}

} // namespace

extern "C" pxcd_status pxcd_hull_compute(const double *xyz, size_t count, pxcd_hull **out, int *dimension,
                                         char *msg, size_t msg_len) {
    return pxcd_hull_compute_ex(xyz, count, 0, out, dimension, msg, msg_len);
}

namespace {
// Saves the floating-point environment, clears the flags and turns traps off
// (feholdexcept); restores the saved environment when it goes out of scope.
struct Fenv_guard {
    std::fenv_t env;
    Fenv_guard() { std::feholdexcept(&env); }
    ~Fenv_guard() { std::fesetenv(&env); }
    Fenv_guard(const Fenv_guard &) = delete;
    Fenv_guard &operator=(const Fenv_guard &) = delete;
};
} // namespace

extern "C" pxcd_status pxcd_hull_compute_ex(const double *xyz, size_t count, unsigned flags, pxcd_hull **out,
                                            int *dimension, char *msg, size_t msg_len) {
    if (out == nullptr) {
        set_msg(msg, msg_len, "pxcd_hull_compute: out is NULL");
        return PXCD_ERROR;
    }
    *out = nullptr;
    if ((flags & ~static_cast<unsigned>(PXCD_HULL_FORCE_EXACT_KERNEL)) != 0) {
        set_msg(msg, msg_len, "pxcd_hull_compute_ex: unknown flags");
        return PXCD_ERROR;
    }
    if (count == 0 || xyz == nullptr) {
        set_msg(msg, msg_len, "pxcd_hull_compute: no input points");
        return PXCD_ERROR;
    }
    // CGAL's interval filters raise floating-point exceptions internally
    // (FE_INVALID when an interval overflows, for coordinates of 1e154 and
    // beyond, or meets subnormal ones) and then decide exactly. The caller's
    // floating-point environment is kept and restored on every return: traps
    // the caller enabled do not fire inside the hull, and no flag leaks out.
    Fenv_guard fenv_guard;
    // Out of memory is told by the exception's type, never by its text.
    const char *what = nullptr;
    char buf[512];
    try {
        *out = compute(xyz, count, dimension, (flags & PXCD_HULL_FORCE_EXACT_KERNEL) != 0);
        return PXCD_OK;
    } catch (const std::bad_alloc &) {
        set_msg(msg, msg_len, "pxcd_hull_compute: out of memory");
        return PXCD_OUT_OF_MEMORY;
    } catch (const CGAL::Failure_exception &e) {
        std::snprintf(buf, sizeof buf, "pxcd_hull_compute: CGAL failure: %s", e.what());
        what = buf;
    } catch (const std::exception &e) {
        std::snprintf(buf, sizeof buf, "pxcd_hull_compute: %s", e.what());
        what = buf;
    } catch (...) {
        what = "pxcd_hull_compute: unknown exception";
    }
    set_msg(msg, msg_len, what);
    return PXCD_ERROR;
}

extern "C" void pxcd_hull_free(pxcd_hull *hull) {
    if (hull == nullptr) return;
    std::free(hull->vertices);
    std::free(hull->face_offsets);
    std::free(hull->face_indices);
    std::free(hull);
}
