// Real meshes for test_fcl_model and bench_models: small strict readers
// (OFF, binary STL, OBJ) independent of the library's loader (px_mesh_load
// is the thing under test elsewhere), scaling to a bounding-box diagonal,
// parts as connected components, and the same triangles as a px_mesh and
// as FCL's BVHModel<OBBRSS>. Header-only C++, internal to tests/ and bench/.
//
// The CGAL sample meshes (bunny00, elephant, armadillo) are looked up in
// PROXIMA_MESH_DATA (a directory `make deps` fills, tests/CMakeLists.txt
// defines it), then in the system's libcgal-demo data.tar.gz.
#ifndef PX_TESTS_REAL_MESHES_H
#define PX_TESTS_REAL_MESHES_H

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>

#include "proxima/io.h"
#include "proxima/proxima.h"

namespace rm {

// An indexed triangle mesh with parts: part p owns triangles
// [part_tri[p], part_tri[p + 1]) and vertices [part_vtx[p], part_vtx[p + 1]).
struct Mesh {
    std::string name;
    std::vector<double> xyz;
    std::vector<uint32_t> tri;
    std::vector<uint32_t> part_tri{0}, part_vtx{0};
    size_t nv() const { return xyz.size() / 3; }
    size_t nt() const { return tri.size() / 3; }
    size_t parts() const { return part_tri.size() - 1; }
};

// ---- Readers -------------------------------------------------------------

// Tokens of `text` with '#' comments removed, by line.
inline std::vector<std::vector<std::string>> lines_of(const std::string &text) {
    std::vector<std::vector<std::string>> out;
    size_t i = 0, n = text.size();
    while (i < n) {
        size_t e = text.find('\n', i);
        if (e == std::string::npos) e = n;
        std::string line = text.substr(i, e - i);
        i = e + 1;
        size_t h = line.find('#');
        if (h != std::string::npos) line.resize(h);
        std::vector<std::string> tok;
        size_t k = 0;
        while (k < line.size()) {
            while (k < line.size() && std::isspace((unsigned char)line[k])) ++k;
            size_t s = k;
            while (k < line.size() && !std::isspace((unsigned char)line[k])) ++k;
            if (k > s) tok.push_back(line.substr(s, k - s));
        }
        if (!tok.empty()) out.push_back(tok);
    }
    return out;
}

inline bool parse_double(const std::string &s, double *v) {
    char *end = nullptr;
    errno = 0;
    *v = std::strtod(s.c_str(), &end);
    return end && *end == 0 && errno == 0 && std::isfinite(*v);
}

inline bool parse_index(const std::string &s, long long *v) {
    char *end = nullptr;
    errno = 0;
    *v = std::strtoll(s.c_str(), &end, 10);
    return end && *end == 0 && errno == 0 && !s.empty();
}

// OFF, strictly: "OFF", then "nv nf ne", nv lines of exactly 3 finite
// coordinates, nf lines "k i1 .. ik" (k >= 3, indices in range, nothing
// after them; polygons fanned into triangles), nothing after the faces.
inline bool read_off_text(const std::string &text, Mesh *m, std::string *err) {
    auto L = lines_of(text);
    if (L.empty() || L[0].size() != 1 || L[0][0] != "OFF") return *err = "not OFF", false;
    long long nv, nf, ne;
    if (L.size() < 2 || L[1].size() != 3 || !parse_index(L[1][0], &nv) || !parse_index(L[1][1], &nf) ||
        !parse_index(L[1][2], &ne) || nv <= 0 || nf <= 0 || nv > (1ll << 30) || nf > (1ll << 30))
        return *err = "bad OFF counts", false;
    if ((long long)L.size() != 2 + nv + nf) return *err = "OFF: line count differs from the header", false;
    m->xyz.clear();
    m->tri.clear();
    for (long long i = 0; i < nv; ++i) {
        const auto &t = L[(size_t)(2 + i)];
        double v[3];
        if (t.size() != 3 || !parse_double(t[0], &v[0]) || !parse_double(t[1], &v[1]) ||
            !parse_double(t[2], &v[2]))
            return *err = "OFF: bad vertex line " + std::to_string(i), false;
        m->xyz.insert(m->xyz.end(), v, v + 3);
    }
    for (long long f = 0; f < nf; ++f) {
        const auto &t = L[(size_t)(2 + nv + f)];
        long long k;
        if (t.empty() || !parse_index(t[0], &k) || k < 3 || (long long)t.size() != k + 1)
            return *err = "OFF: bad face line " + std::to_string(f), false;
        std::vector<uint32_t> idx;
        for (long long j = 0; j < k; ++j) {
            long long x;
            if (!parse_index(t[(size_t)(1 + j)], &x) || x < 0 || x >= nv)
                return *err = "OFF: bad index on face " + std::to_string(f), false;
            idx.push_back((uint32_t)x);
        }
        for (size_t j = 1; j + 1 < idx.size(); ++j) m->tri.insert(m->tri.end(), {idx[0], idx[j], idx[j + 1]});
    }
    m->part_tri = {0, (uint32_t)m->nt()};
    m->part_vtx = {0, (uint32_t)m->nv()};
    return true;
}

inline bool read_file(const std::string &path, std::string *out) {
    FILE *f = std::fopen(path.c_str(), "rb");
    if (!f) return false;
    out->clear();
    char buf[1 << 16];
    size_t k;
    while ((k = std::fread(buf, 1, sizeof buf, f)) > 0) out->append(buf, k);
    std::fclose(f);
    return true;
}

// Binary STL, strictly: 80-byte header, count, 50 bytes per triangle, size
// exactly that. Corners are joined where bit-identical.
inline bool read_stl_text(const std::string &s, Mesh *m, std::string *err) {
    if (s.size() < 84) return *err = "STL: short file", false;
    uint32_t n;
    std::memcpy(&n, s.data() + 80, 4);
    if (s.size() != 84 + 50 * (size_t)n || n == 0) return *err = "STL: size does not match the count", false;
    std::map<std::tuple<float, float, float>, uint32_t> at;
    m->xyz.clear();
    m->tri.clear();
    for (uint32_t t = 0; t < n; ++t) {
        const char *r = s.data() + 84 + 50 * (size_t)t + 12;
        for (int c = 0; c < 3; ++c) {
            float p[3];
            std::memcpy(p, r + 12 * c, 12);
            if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
                return *err = "STL: non-finite coordinate", false;
            auto key = std::make_tuple(p[0], p[1], p[2]);
            auto it = at.find(key);
            uint32_t id;
            if (it == at.end()) {
                id = (uint32_t)m->nv();
                at.emplace(key, id);
                m->xyz.insert(m->xyz.end(), {(double)p[0], (double)p[1], (double)p[2]});
            } else {
                id = it->second;
            }
            m->tri.push_back(id);
        }
    }
    m->part_tri = {0, (uint32_t)m->nt()};
    m->part_vtx = {0, (uint32_t)m->nv()};
    return true;
}

// OBJ: `v x y z`, `f a[/t[/n]] ...` (1-based or negative indices, polygons
// fanned); `g`/`o` start a new part; vt, vn, s, usemtl, mtllib ignored;
// anything else is an error. Parts get their own vertex ranges (a vertex
// several parts use is copied into each).
inline bool read_obj_text(const std::string &text, Mesh *m, std::string *err) {
    auto L = lines_of(text);
    std::vector<double> v;
    std::vector<std::vector<uint32_t>> groups(1);
    for (const auto &t : L) {
        if (t[0] == "v") {
            double c[3];
            if (t.size() < 4 || t.size() > 5 || !parse_double(t[1], &c[0]) || !parse_double(t[2], &c[1]) ||
                !parse_double(t[3], &c[2]))
                return *err = "OBJ: bad v line", false;
            v.insert(v.end(), c, c + 3);
        } else if (t[0] == "f") {
            std::vector<uint32_t> idx;
            for (size_t j = 1; j < t.size(); ++j) {
                long long x;
                if (!parse_index(t[j].substr(0, t[j].find('/')), &x)) return *err = "OBJ: bad f index", false;
                long long n = (long long)(v.size() / 3);
                x = x < 0 ? n + x : x - 1;
                if (x < 0 || x >= n) return *err = "OBJ: f index out of range", false;
                idx.push_back((uint32_t)x);
            }
            if (idx.size() < 3) return *err = "OBJ: face with fewer than 3 corners", false;
            for (size_t j = 1; j + 1 < idx.size(); ++j)
                groups.back().insert(groups.back().end(), {idx[0], idx[j], idx[j + 1]});
        } else if (t[0] == "g" || t[0] == "o") {
            if (!groups.back().empty()) groups.emplace_back();
        } else if (t[0] != "vt" && t[0] != "vn" && t[0] != "s" && t[0] != "usemtl" && t[0] != "mtllib") {
            return *err = "OBJ: unknown record " + t[0], false;
        }
    }
    m->xyz.clear();
    m->tri.clear();
    m->part_tri = {0};
    m->part_vtx = {0};
    for (const auto &g : groups) {
        if (g.empty()) continue;
        std::map<uint32_t, uint32_t> local;
        for (uint32_t x : g) {
            auto it = local.find(x);
            if (it == local.end()) {
                it = local.emplace(x, (uint32_t)m->nv()).first;
                m->xyz.insert(m->xyz.end(), {v[3 * x], v[3 * x + 1], v[3 * x + 2]});
            }
            m->tri.push_back(it->second);
        }
        m->part_tri.push_back((uint32_t)m->nt());
        m->part_vtx.push_back((uint32_t)m->nv());
    }
    if (m->nt() == 0) return *err = "OBJ: no faces", false;
    return true;
}

inline bool ends_with(const std::string &s, const char *suf) {
    size_t k = std::strlen(suf);
    return s.size() >= k && s.compare(s.size() - k, k, suf) == 0;
}

inline bool read_mesh_file(const std::string &path, Mesh *m, std::string *err) {
    std::string text;
    if (!read_file(path, &text)) return *err = "cannot open " + path, false;
    m->name = path.substr(path.find_last_of('/') + 1);
    if (ends_with(path, ".off")) return read_off_text(text, m, err);
    if (ends_with(path, ".stl")) return read_stl_text(text, m, err);
    if (ends_with(path, ".obj")) return read_obj_text(text, m, err);
    return *err = "unknown extension: " + path, false;
}

// A mesh file through the library's loader (px_mesh_load, proxima-io): its
// vertices, triangles and parts copied into a Mesh, so that FCL gets the
// very triangles the models are built from.
inline bool load_with_px(const std::string &path, Mesh *m, std::string *err) {
    px_error e{};
    px_mesh *mesh = px_mesh_load(path.c_str(), nullptr, &e);
    if (!mesh) return *err = std::string("px_mesh_load: ") + e.message, false;
    const uint32_t nv = px_mesh_vertex_count(mesh), nt = px_mesh_triangle_count(mesh);
    m->name = path.substr(path.find_last_of('/') + 1);
    m->xyz.assign(px_mesh_vertices(mesh), px_mesh_vertices(mesh) + 3 * (size_t)nv);
    m->tri.assign(px_mesh_triangles(mesh), px_mesh_triangles(mesh) + 3 * (size_t)nt);
    m->part_tri = {0};
    m->part_vtx = {0};
    bool ok = true;
    for (uint32_t p = 0; p < px_mesh_part_count(mesh); ++p) {
        px_mesh_part mp;
        px_mesh_get_part(mesh, p, &mp);
        // Parts as consecutive ranges (what Mesh holds); the loader writes
        // them in order.
        ok = ok && mp.first_triangle == m->part_tri.back() && mp.first_vertex == m->part_vtx.back();
        m->part_tri.push_back(mp.first_triangle + mp.triangle_count);
        m->part_vtx.push_back(mp.first_vertex + mp.vertex_count);
    }
    ok = ok && m->part_tri.back() == nt && m->part_vtx.back() == nv;
    px_mesh_destroy(mesh);
    if (!ok) return *err = path + ": parts are not consecutive ranges", false;
    return true;
}

#ifndef PROXIMA_MESH_DATA
#define PROXIMA_MESH_DATA ""
#endif
inline const char *cgal_data_tgz() { return "/usr/share/doc/libcgal-dev/data.tar.gz"; }

// A CGAL sample mesh ("bunny00.off") from `dir` (default PROXIMA_MESH_DATA),
// else from the system's data.tar.gz; false with *err saying why when
// neither has it.
inline bool load_cgal_mesh(const std::string &file, Mesh *m, std::string *err, std::string dir = "") {
    if (dir.empty()) dir = PROXIMA_MESH_DATA;
    std::string text;
    if (!dir.empty() && read_file(dir + "/" + file, &text)) {
        m->name = file;
        return read_off_text(text, m, err);
    }
    FILE *t = std::fopen(cgal_data_tgz(), "rb");
    if (t) {
        std::fclose(t);
        std::string cmd =
            std::string("tar -xzOf ") + cgal_data_tgz() + " data/meshes/" + file + " 2>/dev/null";
        FILE *p = popen(cmd.c_str(), "r");
        if (p) {
            char buf[1 << 16];
            size_t k;
            while ((k = std::fread(buf, 1, sizeof buf, p)) > 0) text.append(buf, k);
            int rc = pclose(p);
            if (rc == 0 && !text.empty()) {
                m->name = file;
                return read_off_text(text, m, err);
            }
        }
    }
    *err = file + " not in '" + dir + "' nor in " + cgal_data_tgz() + " (run `make deps`)";
    return false;
}

// ---- Shaping ---------------------------------------------------------------

inline void bbox(const Mesh &m, double lo[3], double hi[3]) {
    for (int k = 0; k < 3; ++k) lo[k] = HUGE_VAL, hi[k] = -HUGE_VAL;
    for (size_t i = 0; i < m.nv(); ++i)
        for (int k = 0; k < 3; ++k)
            lo[k] = std::min(lo[k], m.xyz[3 * i + k]), hi[k] = std::max(hi[k], m.xyz[3 * i + k]);
}

// Centres the bounding box at the origin and scales its diagonal to `diag`.
inline void normalize(Mesh *m, double diag) {
    double lo[3], hi[3];
    bbox(*m, lo, hi);
    double c[3], d2 = 0;
    for (int k = 0; k < 3; ++k) c[k] = 0.5 * (lo[k] + hi[k]), d2 += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    const double s = diag / std::sqrt(d2);
    for (size_t i = 0; i < m->nv(); ++i)
        for (int k = 0; k < 3; ++k) m->xyz[3 * i + k] = (m->xyz[3 * i + k] - c[k]) * s;
}

// Parts = connected components (triangles sharing a vertex index), each
// with its own contiguous vertex and triangle ranges.
inline void split_components(Mesh *m) {
    const size_t nv = m->nv(), nt = m->nt();
    std::vector<uint32_t> up(nv);
    for (size_t i = 0; i < nv; ++i) up[i] = (uint32_t)i;
    auto find = [&](uint32_t x) {
        while (up[x] != x) x = up[x] = up[up[x]];
        return x;
    };
    for (size_t t = 0; t < nt; ++t)
        for (int k = 1; k < 3; ++k) {
            uint32_t a = find(m->tri[3 * t]), b = find(m->tri[3 * t + k]);
            if (a != b) up[std::max(a, b)] = std::min(a, b);
        }
    std::map<uint32_t, std::vector<uint32_t>> comp; // root -> triangles
    for (size_t t = 0; t < nt; ++t) comp[find(m->tri[3 * t])].push_back((uint32_t)t);
    Mesh out;
    out.name = m->name;
    out.part_tri = {0};
    out.part_vtx = {0};
    for (auto &c : comp) {
        std::map<uint32_t, uint32_t> local;
        for (uint32_t t : c.second)
            for (int k = 0; k < 3; ++k) {
                uint32_t x = m->tri[3 * t + k];
                auto it = local.find(x);
                if (it == local.end()) {
                    it = local.emplace(x, (uint32_t)out.nv()).first;
                    out.xyz.insert(out.xyz.end(), {m->xyz[3 * x], m->xyz[3 * x + 1], m->xyz[3 * x + 2]});
                }
                out.tri.push_back(it->second);
            }
        out.part_tri.push_back((uint32_t)out.nt());
        out.part_vtx.push_back((uint32_t)out.nv());
    }
    *m = out;
}

// ---- The same triangles for proxima and FCL ---------------------------------

struct MeshDeleter {
    void operator()(px_mesh *p) const { px_mesh_destroy(p); }
};
struct ModelDeleter {
    void operator()(px_model *p) const { px_model_destroy(p); }
};
using MeshPtr = std::unique_ptr<px_mesh, MeshDeleter>;
using ModelPtr = std::unique_ptr<px_model, ModelDeleter>;

inline MeshPtr make_px_mesh(const Mesh &m, std::string *err) {
    std::vector<px_mesh_part_desc> parts(m.parts());
    for (size_t p = 0; p < m.parts(); ++p) {
        parts[p] = px_mesh_part_desc{};
        parts[p].node = -1;
        parts[p].first_vertex = m.part_vtx[p];
        parts[p].vertex_count = m.part_vtx[p + 1] - m.part_vtx[p];
        parts[p].first_triangle = m.part_tri[p];
        parts[p].triangle_count = m.part_tri[p + 1] - m.part_tri[p];
    }
    px_mesh_desc d{};
    d.xyz = m.xyz.data();
    d.vertex_count = m.nv();
    d.triangles = m.tri.data();
    d.triangle_count = m.nt();
    d.parts = parts.data();
    d.part_count = (uint32_t)parts.size();
    px_error e{};
    px_mesh *mesh = px_mesh_create(&d, nullptr, &e);
    if (!mesh) *err = std::string("px_mesh_create: ") + e.message;
    return MeshPtr(mesh);
}

// tolerance: PX_PIECES_APPROXIMATE's (0: the default).
inline ModelPtr make_model(const px_mesh *mesh, uint32_t pieces, std::string *err, double tolerance = 0.0) {
    px_model_options o{};
    o.pieces = pieces;
    o.tolerance = tolerance;
    px_error e{};
    px_model *mo = px_model_create_from_mesh(mesh, &o, &e);
    if (!mo) *err = std::string("px_model_create_from_mesh: ") + e.message;
    return ModelPtr(mo);
}

using FclModel = fcl::BVHModel<fcl::OBBRSSd>;

// FCL's BVHModel<OBBRSS> of the mesh's triangles (FCL's default build: the
// mean split), the mesh's own vertex array and winding.
inline std::shared_ptr<FclModel> make_fcl(const Mesh &m) {
    std::vector<fcl::Vector3d> pts(m.nv());
    for (size_t i = 0; i < m.nv(); ++i)
        pts[i] = fcl::Vector3d(m.xyz[3 * i], m.xyz[3 * i + 1], m.xyz[3 * i + 2]);
    std::vector<fcl::Triangle> tris(m.nt());
    for (size_t t = 0; t < m.nt(); ++t)
        tris[t] = fcl::Triangle(m.tri[3 * t], m.tri[3 * t + 1], m.tri[3 * t + 2]);
    auto b = std::make_shared<FclModel>();
    b->beginModel((int)m.nt(), (int)m.nv());
    b->addSubModel(pts, tris);
    b->endModel();
    b->computeLocalAABB();
    return b;
}

// Bytes FCL's BVHModel<OBBRSS> holds for its tree and geometry: its BV
// nodes (getNumBVs() x sizeof(BVNode<OBBRSS>)), its triangles
// (sizeof(fcl::Triangle) each), its vertices (sizeof(Vector3d) each) and
// the primitive index array (one unsigned int per triangle). Allocator
// overhead and the object itself are not counted (nor for proxima's
// px_model_get_info, which counts what it allocates).
inline size_t fcl_memory_bytes(const FclModel &b) {
    return (size_t)b.getNumBVs() * sizeof(fcl::BVNode<fcl::OBBRSSd>) +
           (size_t)b.num_tris * sizeof(fcl::Triangle) + (size_t)b.num_vertices * sizeof(fcl::Vector3d) +
           (size_t)b.num_tris * sizeof(unsigned int) + sizeof(FclModel);
}

// A px_pose and an fcl::Transform3d from a row-major rotation and a
// translation.
inline px_pose to_px(const double r[9], const double t[3]) {
    px_pose p;
    std::memcpy(p.r, r, sizeof p.r);
    p.t = px_vec3{t[0], t[1], t[2]};
    return p;
}

inline fcl::Transform3d to_fcl(const double r[9], const double t[3]) {
    fcl::Transform3d tf = fcl::Transform3d::Identity();
    fcl::Matrix3d R;
    R << r[0], r[1], r[2], r[3], r[4], r[5], r[6], r[7], r[8];
    tf.linear() = R;
    tf.translation() = fcl::Vector3d(t[0], t[1], t[2]);
    return tf;
}

// Rotation about unit axis u by angle a (row-major).
inline void axis_angle(const double u[3], double a, double r[9]) {
    const double c = std::cos(a), s = std::sin(a), C = 1 - c;
    const double x = u[0], y = u[1], z = u[2];
    const double m[9] = {c + x * x * C,     x * y * C - z * s, x * z * C + y * s,
                         y * x * C + z * s, c + y * y * C,     y * z * C - x * s,
                         z * x * C - y * s, z * y * C + x * s, c + z * z * C};
    std::memcpy(r, m, sizeof m);
}

inline void mat_mul(const double a[9], const double b[9], double out[9]) {
    double r[9];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            r[3 * i + j] = a[3 * i] * b[j] + a[3 * i + 1] * b[3 + j] + a[3 * i + 2] * b[6 + j];
    std::memcpy(out, r, sizeof r);
}

// ---- The approach sequence ------------------------------------------------------

// B moving along a line toward A (A at the identity): B's centre at s * dir
// with rotation R(s) = axis_angle(axis, rate * s). first_contact() finds the
// s where the triangle surfaces first touch, by conservative advancement
// from s0 (where they are apart): each step moves by at most the distance
// divided by (1 + rate * radius_b), so no point of B travels farther than
// the current distance and no contact is stepped over.
struct Approach {
    double dir[3], axis[3];
    double rate;     // radians per unit of s
    double radius_b; // max |x| over B's vertices (B's body frame)
    void pose_at(double s, double r[9], double t[3]) const {
        axis_angle(axis, rate * s, r);
        for (int k = 0; k < 3; ++k) t[k] = s * dir[k];
    }
    px_pose px_at(double s) const {
        double r[9], t[3];
        pose_at(s, r, t);
        return to_px(r, t);
    }
};

inline double max_radius(const Mesh &m) {
    double r2 = 0;
    for (size_t i = 0; i < m.nv(); ++i)
        r2 = std::max(r2, m.xyz[3 * i] * m.xyz[3 * i] + m.xyz[3 * i + 1] * m.xyz[3 * i + 1] +
                              m.xyz[3 * i + 2] * m.xyz[3 * i + 2]);
    return std::sqrt(r2);
}

// The first s >= s0 where the triangle models touch (distance below
// 1e-12), NAN when it does not happen before s1.
inline double first_contact(const px_model *a, const px_model *b, const Approach &ap, double s0, double s1) {
    px_pose ia = px_pose_identity();
    px_model_cache cache{};
    double s = s0;
    double found = NAN;
    for (int it = 0; it < 100000 && s <= s1; ++it) {
        px_pose pb = ap.px_at(s);
        px_model_distance_result r;
        if (px_model_distance(a, &ia, b, &pb, &cache, &r) != PX_OK) break;
        if (r.distance < 1e-12) {
            found = s;
            break;
        }
        s += r.distance / (1.0 + std::fabs(ap.rate) * ap.radius_b) * (1.0 - 1e-9);
    }
    px_model_cache_release(&cache);
    return found;
}

// ---- A brute-force inside test (for containment cases) -----------------------

// Parity of a ray's crossings with the mesh's triangles, cast along three
// fixed directions; the majority decides (a point on the surface is
// undefined). O(triangles).
inline bool point_inside(const Mesh &m, const double p[3]) {
    static const double dirs[3][3] = {{0.267261241912424, 0.534522483824849, 0.801783725737273},
                                      {-0.762000762001143, 0.127000127000191, 0.635000635000953},
                                      {0.408248290463863, -0.816496580927726, 0.408248290463863}};
    int votes = 0;
    for (const auto &d : dirs) {
        int cross = 0;
        for (size_t t = 0; t < m.nt(); ++t) {
            const double *a = &m.xyz[3 * m.tri[3 * t]], *b = &m.xyz[3 * m.tri[3 * t + 1]],
                         *c = &m.xyz[3 * m.tri[3 * t + 2]];
            double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]},
                   e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
            double h[3] = {d[1] * e2[2] - d[2] * e2[1], d[2] * e2[0] - d[0] * e2[2],
                           d[0] * e2[1] - d[1] * e2[0]};
            double det = e1[0] * h[0] + e1[1] * h[1] + e1[2] * h[2];
            if (det == 0) continue;
            double s[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
            double u = (s[0] * h[0] + s[1] * h[1] + s[2] * h[2]) / det;
            if (u < 0 || u > 1) continue;
            double q[3] = {s[1] * e1[2] - s[2] * e1[1], s[2] * e1[0] - s[0] * e1[2],
                           s[0] * e1[1] - s[1] * e1[0]};
            double v = (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]) / det;
            if (v < 0 || u + v > 1) continue;
            double tt = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) / det;
            if (tt > 0) cross++;
        }
        votes += cross & 1;
    }
    return votes >= 2;
}

} // namespace rm

#endif
