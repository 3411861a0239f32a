// pxcd_hull_compute / pxcd_hull_free: convex hull of a point set as convex
// polygons, behind the C ABI of pxcd.h.
//
// Algorithm and sources:
//   - Affine dimension: exact predicates CGAL::collinear / CGAL::coplanar
//     (CGAL 5.5 manual, "2D and 3D Linear Geometry Kernel", Global Functions).
//     Epick evaluates predicates exactly (static + interval filters, exact
//     fallback), so the dimension we report is the true dimension of the
//     input doubles.
//   - Hull: CGAL::convex_hull_3 (CGAL 5.5 manual, "3D Convex Hulls", section
//     "Static Convex Hull Construction"; quickhull of Barber, Dobkin and
//     Huhdanpaa, ACM TOMS 22(4), 1996) with
//     Exact_predicates_inexact_constructions_kernel into a
//     CGAL::Surface_mesh. The result is triangulated and outward oriented.
//   - Polygons: adjacent hull triangles whose four points are exactly
//     coplanar (CGAL::coplanar) are merged with a union-find; the boundary of
//     each group is traced into one CCW loop.
//
// Why the extra clean-up step after convex_hull_3: quickhull only adds a
// point that is strictly outside the current hull, but a point added early
// can later end up in the relative interior of a hull edge or facet (the
// "farthest point" is chosen with inexact plane distances, and ties are
// possible). Such a point is still a mesh vertex, because the faces around
// it that are coplanar with the new point are not strictly visible and are
// kept. After the merge:
//   - a non-extreme vertex inside a facet is strictly inside the merged
//     region, so it is not on the boundary loop and disappears by itself;
//   - a non-extreme vertex inside a hull edge shows up, in the loops of the
//     two facets sharing that edge, exactly collinear with its two
//     neighbours. Corners of a facet (extreme points of the hull) never are.
// Dropping exactly-collinear loop vertices therefore leaves exactly the
// extreme points, and both facets of an edge drop the same vertices, so
// edges stay paired. The final topological check (Euler, edge pairing)
// turns any surprise into PXCD_ERROR rather than returning a broken mesh.

#include "pxcd.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>
#include <CGAL/exceptions.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <new>
#include <numeric>
#include <stdexcept>
#include <vector>

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point_3 = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point_3>;
using halfedge_descriptor = Mesh::Halfedge_index;
using face_descriptor = Mesh::Face_index;

void set_msg(char *msg, size_t msg_len, const char *text) {
    if (msg != nullptr && msg_len > 0) std::snprintf(msg, msg_len, "%s", text);
}

// Affine dimension of the point set (0..3), with exact predicates. Looks for
// a second distinct point, then a point off their line, then a point off
// their plane; each scan is linear and stops at the first witness.
int affine_dimension(const std::vector<Point_3> &pts) {
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

// Union-find with path halving; the union keeps the smaller index as root so
// the result does not depend on the order of the unions.
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
        if (a < b) parent[b] = a;
        else parent[a] = b;
    }
};

// Polygonal faces in compact form, before conversion to malloc'd C arrays.
struct Polygons {
    std::vector<Mesh::Vertex_index> loop_vertices; // concatenated loops
    std::vector<size_t> offsets{0};                // faces + 1 entries
};

// Exceptions used for internal consistency failures (reported as PXCD_ERROR).
struct Hull_error : std::runtime_error {
    using std::runtime_error::runtime_error;
};

Polygons merge_coplanar_triangles(const Mesh &mesh) {
    const size_t nf = mesh.number_of_faces();
    // convex_hull_3 builds a fresh mesh, so there are no removed elements and
    // indices are dense; checked here because everything below relies on it.
    if (mesh.has_garbage() || mesh.number_of_faces() == 0)
        throw Hull_error("unexpected mesh layout from convex_hull_3");

    // 1. Group triangles through edges whose two triangles are coplanar.
    //    Hull triangles are never degenerate (a new quickhull triangle joins
    //    a point strictly above a visible face to an edge of that face), so
    //    coplanarity of the 4 points means the triangles span the same plane,
    //    and groups are exactly the hull facets.
    Union_find uf(nf);
    for (auto e : mesh.edges()) {
        halfedge_descriptor h = mesh.halfedge(e);
        halfedge_descriptor o = mesh.opposite(h);
        const Point_3 &a = mesh.point(mesh.source(h));
        const Point_3 &b = mesh.point(mesh.target(h));
        const Point_3 &c = mesh.point(mesh.target(mesh.next(h)));
        const Point_3 &d = mesh.point(mesh.target(mesh.next(o)));
        if (CGAL::coplanar(a, b, c, d))
            uf.unite(static_cast<uint32_t>(mesh.face(h).idx()),
                     static_cast<uint32_t>(mesh.face(o).idx()));
    }
    std::vector<uint32_t> group(nf);
    for (size_t f = 0; f < nf; ++f) group[f] = uf.find(static_cast<uint32_t>(f));

    auto group_of = [&](halfedge_descriptor h) { return group[mesh.face(h).idx()]; };
    auto is_boundary = [&](halfedge_descriptor h) {
        return group_of(h) != group_of(mesh.opposite(h));
    };

    // 2. For each group (in order of its smallest face index: deterministic),
    //    the first boundary halfedge and the number of boundary halfedges.
    const halfedge_descriptor none;
    std::vector<halfedge_descriptor> start(nf, none);
    std::vector<size_t> boundary_count(nf, 0);
    std::vector<uint32_t> roots;
    for (size_t f = 0; f < nf; ++f) {
        const uint32_t g = group[f];
        if (g == f) roots.push_back(g);
        for (halfedge_descriptor h : mesh.halfedges_around_face(mesh.halfedge(face_descriptor(f)))) {
            if (!is_boundary(h)) continue;
            if (start[g] == none) start[g] = h;
            ++boundary_count[g];
        }
    }

    // 3. Trace each group's boundary. From boundary halfedge h (ending at v),
    //    the next boundary halfedge of the same group leaves v: turn around v
    //    through the group's triangles until the opposite face is in another
    //    group. A facet is a disk, so this visits every boundary halfedge of
    //    the group once; the count check catches anything else.
    //    Then drop loop vertices exactly collinear with their neighbours
    //    (non-extreme points inside a hull edge, see the file comment).
    Polygons out;
    out.offsets.reserve(roots.size() + 1);
    std::vector<Mesh::Vertex_index> loop;
    std::vector<char> drop;
    for (uint32_t g : roots) {
        loop.clear();
        const halfedge_descriptor first = start[g];
        if (first == none) throw Hull_error("hull facet without boundary");
        halfedge_descriptor h = first;
        do {
            loop.push_back(mesh.source(h));
            if (loop.size() > boundary_count[g])
                throw Hull_error("hull facet boundary is not a simple loop");
            halfedge_descriptor n = mesh.next(h);
            size_t guard = 0;
            while (!is_boundary(n)) {
                n = mesh.next(mesh.opposite(n));
                if (++guard > nf) throw Hull_error("cannot trace hull facet boundary");
            }
            h = n;
        } while (h != first);
        if (loop.size() != boundary_count[g])
            throw Hull_error("hull facet boundary is not a simple loop");

        const size_t m = loop.size();
        drop.assign(m, 0);
        for (size_t i = 0; i < m; ++i) {
            const Point_3 &p = mesh.point(loop[(i + m - 1) % m]);
            const Point_3 &q = mesh.point(loop[i]);
            const Point_3 &r = mesh.point(loop[(i + 1) % m]);
            drop[i] = CGAL::collinear(p, q, r) ? 1 : 0;
        }
        size_t kept = 0;
        for (size_t i = 0; i < m; ++i)
            if (!drop[i]) {
                out.loop_vertices.push_back(loop[i]);
                ++kept;
            }
        if (kept < 3) throw Hull_error("degenerate hull facet after merging");
        out.offsets.push_back(out.loop_vertices.size());
    }
    return out;
}

// Checks the combinatorics promised by pxcd.h: no repeated vertex in a loop,
// every undirected edge used exactly once in each direction, and Euler's
// formula V - E + F = 2.
void check_topology(size_t vertex_count, const std::vector<size_t> &offsets,
                    const std::vector<uint32_t> &indices) {
    const size_t face_count = offsets.size() - 1;
    std::vector<size_t> stamp(vertex_count, SIZE_MAX);
    // key = (min << 33) | (max << 1) | (direction is min->max ? 0 : 1)
    std::vector<uint64_t> keys;
    keys.reserve(indices.size());
    for (size_t f = 0; f < face_count; ++f) {
        const size_t b = offsets[f], e = offsets[f + 1];
        for (size_t i = b; i < e; ++i) {
            const uint64_t u = indices[i];
            const uint64_t v = indices[i + 1 < e ? i + 1 : b];
            if (stamp[u] == f) throw Hull_error("hull facet repeats a vertex");
            stamp[u] = f;
            const uint64_t lo = std::min(u, v), hi = std::max(u, v);
            keys.push_back((lo << 33) | (hi << 1) | (u < v ? 0u : 1u));
        }
    }
    std::sort(keys.begin(), keys.end());
    if (keys.size() % 2 != 0) throw Hull_error("hull edges are not paired");
    for (size_t i = 0; i < keys.size(); i += 2) {
        // Each undirected edge must appear as exactly the pair (dir 0, dir 1).
        if ((keys[i] & 1u) != 0 || keys[i + 1] != (keys[i] | 1u) ||
            (i + 2 < keys.size() && (keys[i + 2] >> 1) == (keys[i] >> 1)))
            throw Hull_error("hull edges are not paired");
    }
    const size_t edge_count = keys.size() / 2;
    if (vertex_count + face_count != edge_count + 2)
        throw Hull_error("hull violates Euler's formula");
}

} // namespace

extern "C" pxcd_status pxcd_hull_compute(const double *xyz, size_t count, pxcd_hull **out,
                                         int *dimension, char *msg, size_t msg_len) {
    if (out != nullptr) *out = nullptr;
    if (out == nullptr) {
        set_msg(msg, msg_len, "pxcd_hull_compute: out is NULL");
        return PXCD_ERROR;
    }
    if (count == 0 || xyz == nullptr) {
        set_msg(msg, msg_len, "pxcd_hull_compute: no input points");
        return PXCD_ERROR;
    }
    pxcd_hull *hull = nullptr;
    try {
        std::vector<Point_3> pts;
        pts.reserve(count);
        for (size_t i = 0; i < count; ++i)
            pts.emplace_back(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);

        const int dim = affine_dimension(pts);
        if (dim < 3) {
            if (dimension != nullptr) *dimension = dim;
            return PXCD_DEGENERATE;
        }

        Mesh mesh;
        CGAL::convex_hull_3(pts.begin(), pts.end(), mesh);
        std::vector<Point_3>().swap(pts); // release early: mesh has copies

        const Polygons polys = merge_coplanar_triangles(mesh);

        // Renumber used vertices 0..V-1 by first appearance in the loops.
        if (mesh.number_of_vertices() > UINT32_MAX)
            throw Hull_error("too many hull vertices for 32-bit ids");
        std::vector<uint32_t> new_id(mesh.number_of_vertices(), UINT32_MAX);
        std::vector<Mesh::Vertex_index> used;
        std::vector<uint32_t> indices;
        indices.reserve(polys.loop_vertices.size());
        for (Mesh::Vertex_index v : polys.loop_vertices) {
            uint32_t &id = new_id[v.idx()];
            if (id == UINT32_MAX) {
                id = static_cast<uint32_t>(used.size());
                used.push_back(v);
            }
            indices.push_back(id);
        }
        check_topology(used.size(), polys.offsets, indices);

        // Copy into malloc'd arrays (freed by pxcd_hull_free on the C side).
        hull = static_cast<pxcd_hull *>(std::calloc(1, sizeof(pxcd_hull)));
        if (hull == nullptr) throw std::bad_alloc();
        hull->vertex_count = used.size();
        hull->face_count = polys.offsets.size() - 1;
        hull->vertices = static_cast<double *>(std::malloc(3 * used.size() * sizeof(double)));
        hull->face_offsets =
            static_cast<size_t *>(std::malloc(polys.offsets.size() * sizeof(size_t)));
        hull->face_indices = static_cast<uint32_t *>(std::malloc(indices.size() * sizeof(uint32_t)));
        if (hull->vertices == nullptr || hull->face_offsets == nullptr ||
            hull->face_indices == nullptr)
            throw std::bad_alloc();
        // Epick points store the input doubles unchanged, so these are
        // bit-identical copies of input coordinates.
        for (size_t i = 0; i < used.size(); ++i) {
            const Point_3 &p = mesh.point(used[i]);
            hull->vertices[3 * i] = p.x();
            hull->vertices[3 * i + 1] = p.y();
            hull->vertices[3 * i + 2] = p.z();
        }
        std::copy(polys.offsets.begin(), polys.offsets.end(), hull->face_offsets);
        std::copy(indices.begin(), indices.end(), hull->face_indices);

        if (dimension != nullptr) *dimension = 3;
        *out = hull;
        return PXCD_OK;
    } catch (const std::bad_alloc &) {
        pxcd_hull_free(hull);
        set_msg(msg, msg_len, "pxcd_hull_compute: out of memory");
    } catch (const CGAL::Failure_exception &e) {
        pxcd_hull_free(hull);
        char buf[512];
        std::snprintf(buf, sizeof buf, "pxcd_hull_compute: CGAL failure: %s", e.what());
        set_msg(msg, msg_len, buf);
    } catch (const std::exception &e) {
        pxcd_hull_free(hull);
        char buf[512];
        std::snprintf(buf, sizeof buf, "pxcd_hull_compute: %s", e.what());
        set_msg(msg, msg_len, buf);
    } catch (...) {
        pxcd_hull_free(hull);
        set_msg(msg, msg_len, "pxcd_hull_compute: unknown exception");
    }
    return PXCD_ERROR;
}

extern "C" void pxcd_hull_free(pxcd_hull *hull) {
    if (hull == nullptr) return;
    std::free(hull->vertices);
    std::free(hull->face_offsets);
    std::free(hull->face_indices);
    std::free(hull);
}
