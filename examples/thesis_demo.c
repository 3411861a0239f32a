/* proxima_demo: seed 000 §3.5 ("Numerical Experiments") on the shipped models.
 *
 * Lin & Canny's thesis chapter 3 (seed 000) measures the closest-feature
 * algorithm three ways; this program repeats each with proxima:
 *   (a) two convex hulls of a teapot (1047 vertices each in the seed) under
 *       1, 5, 10 and 20 degrees of relative rotation per step, with small
 *       displacements (seed: roughly 50, 61, 100, 150 us on an SGI Indigo2);
 *   (b) polygonised spheres and cylinders of growing resolution, 1000 steps
 *       of 1 degree relative rotation (Fig. 3.12: 50-70 us, roughly constant
 *       in the total number of vertices);
 *   (c) Table 3.1: with vs without initialisation for cubes, cylinders,
 *       cones, frustums with 12-120 facets and a Puma link.
 * Every query is timed with tracking (the coherence cache of the previous
 * step: "warm") and without (a zeroed cache: "cold"); (c) also starts from a
 * random feature pair, the seed's "w/o Init" protocol.
 *
 * Then the newer queries, on the same models (two teapot hulls, two Puma
 * links, a sphere and a thin cylinder):
 *   (d) the three distance methods (Lin-Canny, GJK, hybrid) side by side on
 *       one tracked motion through approach, contact, overlap and separation;
 *   (e) signed distance (penetration depth) at several depths, checked by
 *       moving B out along the normal and against px_translate;
 *   (f) collision translation along hitting, missing and overlapping
 *       directions, cold vs warm;
 *   (g) px_intersect against the distance query's flag over the motion of (d).
 * Every check of (d)-(g) prints OK or FAIL; a FAIL also exits with status 1.
 *
 * Nothing is printed unchecked: every answer (warm, cold and random-start)
 * is verified by an independent certificate built from vertices and face
 * planes only (witness points on the bodies, a separating slab of the
 * reported width), warm and cold answers must agree, and a few answers per
 * row are compared with a brute-force minimum over all vertex-face and
 * edge-edge pairs. Any failure makes the program exit with status 1.
 *
 * Only the public API is used: proxima.h and proxima/io.h. The shapes
 * (polygonised spheres, frustums, boxes), the motions and the random stream
 * come from the shared generators of gen/px_gen.h (also used by the tests
 * and the benchmarks); the checks are the demo's own. */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "proxima/proxima.h"
#include "proxima/io.h"
#include "px_gen.h"

#define DEMO_PI 3.14159265358979323846

/* ------------------------------------------------------------------------- */
/* Small vector helpers (demo-local, so the checks share no code with the    */
/* library or the generators).                                               */
/* ------------------------------------------------------------------------- */

/* The accessors, read in expressions (the API returns a status and fills an
 * output; indices here are always in range). */
static px_vec3 vertex_of(const px_convex *c, uint32_t i) {
    px_vec3 v;
    px_convex_vertex(c, i, &v);
    return v;
}
static uint32_t face_size(const px_convex *c, uint32_t f) {
    uint32_t n;
    px_convex_face(c, f, NULL, NULL, &n);
    return n;
}
static uint32_t face_vertex(const px_convex *c, uint32_t f, uint32_t k) {
    uint32_t v;
    px_convex_face_vertex(c, f, k, &v);
    return v;
}
/* The demo's translations are the collision translation of either sign
 * (Carpin, Mirolo and Pagello): PX_QUERY_BOTH_WAYS. */
static const px_query_options demo_both_ways = {0, PX_QUERY_BOTH_WAYS, {0, 0, 0, 0, 0, 0}};

static px_vec3 v3(double x, double y, double z) {
    px_vec3 r = {x, y, z};
    return r;
}
static px_vec3 vadd(px_vec3 a, px_vec3 b) { return v3(a.x + b.x, a.y + b.y, a.z + b.z); }
static px_vec3 vsub(px_vec3 a, px_vec3 b) { return v3(a.x - b.x, a.y - b.y, a.z - b.z); }
static px_vec3 vscale(px_vec3 a, double s) { return v3(a.x * s, a.y * s, a.z * s); }
static double vdot(px_vec3 a, px_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static px_vec3 vcross(px_vec3 a, px_vec3 b) {
    return v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static double vlen(px_vec3 a) { return sqrt(vdot(a, a)); }

static px_vec3 rot_apply(const double r[9], px_vec3 p) {
    return v3(r[0] * p.x + r[1] * p.y + r[2] * p.z, r[3] * p.x + r[4] * p.y + r[5] * p.z,
              r[6] * p.x + r[7] * p.y + r[8] * p.z);
}

static double now_ns(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

/* Deterministic random stream (splitmix64) so every run does the same work. */
static pg_sm g_rng = {0x9E3779B97F4A7C15ull};

static int cmp_double(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, size_t n) {
    if (n == 0) return 0.0;
    qsort(v, n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* ------------------------------------------------------------------------- */
/* Bodies                                                                     */
/* ------------------------------------------------------------------------- */

typedef struct body {
    char name[64];
    px_convex *c;
    uint32_t nv, ne, nf;
    px_vec3 center; /* mean of the hull vertices (body frame) */
    double radius;  /* max distance of a hull vertex from center */
} body;

static int body_init(body *b, const char *name, px_convex *c) {
    memset(b, 0, sizeof *b);
    snprintf(b->name, sizeof b->name, "%s", name);
    b->c = c;
    b->nv = px_convex_vertex_count(c);
    b->ne = px_convex_edge_count(c);
    b->nf = px_convex_face_count(c);
    px_vec3 s = v3(0, 0, 0);
    for (uint32_t i = 0; i < b->nv; ++i) s = vadd(s, vertex_of(c, i));
    b->center = vscale(s, 1.0 / b->nv);
    for (uint32_t i = 0; i < b->nv; ++i) {
        double r = vlen(vsub(vertex_of(c, i), b->center));
        if (r > b->radius) b->radius = r;
    }
    px_error err;
    if (px_convex_validate(c, &err) != PX_OK) {
        fprintf(stderr, "proxima_demo: polytope '%s' fails validation: %s\n", name, err.message);
        return 0;
    }
    return 1;
}

static px_convex *from_points_or_die(const char *what, const double *xyz, size_t n) {
    px_error err;
    px_convex *c = px_convex_create(xyz, n, NULL, &err);
    if (!c) {
        fprintf(stderr, "proxima_demo: cannot build %s: %s (%s)\n", what, err.message,
                px_status_string(err.code));
        exit(2);
    }
    return c;
}

/* Hull of pg_sphere_latlong (polygonised sphere: nlat latitude bands, nlon
 * meridians; 2 + (nlat-1)*nlon vertices). */
static px_convex *make_sphere(int nlat, int nlon, double r) {
    size_t n = pg_sphere_latlong(nlat, nlon, r, NULL);
    double *p = malloc(3 * n * sizeof *p);
    if (!p) exit(2);
    pg_sphere_latlong(nlat, nlon, r, p);
    char what[64];
    snprintf(what, sizeof what, "sphere %dx%d", nlat, nlon);
    px_convex *c = from_points_or_die(what, p, n);
    free(p);
    return c;
}

/* Hull of pg_frustum (prism/cone/frustum family: an n-gon of radius r0 at
 * z = -h/2 and one of radius r1 at z = +h/2; r1 = 0: a cone). */
static px_convex *make_frustum(int n, double r0, double r1, double h) {
    size_t cnt = pg_frustum(n, r0, r1, h, NULL);
    double *p = malloc(3 * cnt * sizeof *p);
    if (!p) exit(2);
    pg_frustum(n, r0, r1, h, p);
    char what[64];
    snprintf(what, sizeof what, "frustum n=%d", n);
    px_convex *c = from_points_or_die(what, p, cnt);
    free(p);
    return c;
}

/* Box of side lengths sx, sy, sz centred at the origin. */
static px_convex *make_box(double sx, double sy, double sz) {
    double p[24];
    pg_box(0.5 * sx, 0.5 * sy, 0.5 * sz, p);
    return from_points_or_die("box", p, 8);
}

/* ------------------------------------------------------------------------- */
/* Motion: the relative rotation of the seed's experiments                   */
/* ------------------------------------------------------------------------- */

/* pg_spin (px_gen.h): both bodies spin about the same world axis through
 * their own centres in opposite senses, so the relative rotation turns by
 * exactly theta per step. A's centre sits at the origin, B's at (D, 0, 0) +
 * a displacement, with D = R_A + R_B + gap (bounding spheres stay apart: the
 * hulls are disjoint at every step) and a displacement amplitude < gap. */
static const px_vec3 k_axis = {0.26726124191242438, 0.53452248382484879,
                               0.80178372573727319}; /* (1,2,3)/|.| */

static pg_spin spin_motion(const body *a, const body *b, double theta, double gap, double disp_amp) {
    pg_spin m;
    m.axis = k_axis;
    m.theta = theta;
    m.separation = a->radius + b->radius + gap;
    m.disp_amp = disp_amp;
    return m;
}

/* ------------------------------------------------------------------------- */
/* Independent checks                                                        */
/* ------------------------------------------------------------------------- */

typedef struct sanity {
    unsigned long certificates, certificate_failures;
    unsigned long brute, brute_failures;
    unsigned long agreement_failures; /* warm vs cold vs random-start distance */
    unsigned long query_errors;
    double worst_brute_rel; /* max |d - d_brute| / scale */
    double worst_cert_rel;
} sanity;

static sanity g_sanity;
static int g_verbose; /* --verbose: print the configuration of every fallback */

static void print_pose_hex(const char *label, const px_pose *p) {
    fprintf(stderr, "    %s r = {%a, %a, %a, %a, %a, %a, %a, %a, %a}, t = {%a, %a, %a}\n", label, p->r[0],
            p->r[1], p->r[2], p->r[3], p->r[4], p->r[5], p->r[6], p->r[7], p->r[8], p->t.x, p->t.y, p->t.z);
}

/* Scratch for world-frame vertices. */
typedef struct world {
    px_vec3 *va, *vb;
    size_t cap_a, cap_b;
} world;

static void world_fill(world *w, const body *a, const px_pose *pa, const body *b, const px_pose *pb) {
    if (w->cap_a < a->nv) {
        free(w->va);
        w->va = malloc(a->nv * sizeof *w->va);
        w->cap_a = a->nv;
    }
    if (w->cap_b < b->nv) {
        free(w->vb);
        w->vb = malloc(b->nv * sizeof *w->vb);
        w->cap_b = b->nv;
    }
    if (!w->va || !w->vb) exit(2);
    for (uint32_t i = 0; i < a->nv; ++i) w->va[i] = px_pose_apply(pa, vertex_of(a->c, i));
    for (uint32_t i = 0; i < b->nv; ++i) w->vb[i] = px_pose_apply(pb, vertex_of(b->c, i));
}

/* Largest signed distance of world point p above the face planes of body b. */
static double max_plane_excess(const body *b, const px_pose *pose, px_vec3 p) {
    double worst = -INFINITY;
    for (uint32_t f = 0; f < b->nf; ++f) {
        px_vec3 n;
        double d;
        px_convex_face(b->c, f, &n, &d, NULL);
        px_vec3 nw = rot_apply(pose->r, n);
        double dw = d + vdot(nw, pose->t);
        double e = vdot(nw, p) - dw;
        if (e > worst) worst = e;
    }
    return worst;
}

/* Certificate for one answer, from vertices and face planes only:
 * - witness points lie in their bodies (below every face plane);
 * - |point_a - point_b| equals the distance;
 * - disjoint: the slab between the planes through point_a and point_b
 *   normal to (point_b - point_a) separates all vertices of A from all of B,
 *   so no pair of points is closer than the reported distance (minus tol).
 * - intersecting: the common point lies in both bodies.
 * Returns the worst violation relative to `scale` (0 when all hold). */
static double certify(const world *w, const body *a, const px_pose *pa, const body *b, const px_pose *pb,
                      const px_distance_result *r, double scale) {
    double viol = 0.0;
    double ea = max_plane_excess(a, pa, r->point_a), eb = max_plane_excess(b, pb, r->point_b);
    if (ea > viol) viol = ea;
    if (eb > viol) viol = eb;
    if (!isfinite(r->distance) || r->distance < 0) return INFINITY;
    if (r->intersecting) {
        if (r->distance != 0.0) return INFINITY;
        double e = max_plane_excess(b, pb, r->point_a);
        if (e > viol) viol = e;
        return viol / scale;
    }
    px_vec3 dv = vsub(r->point_b, r->point_a);
    double len = vlen(dv);
    double e = fabs(len - r->distance);
    if (e > viol) viol = e;
    if (!(len > 0)) return INFINITY; /* disjoint bodies need a positive gap */
    px_vec3 n = vscale(dv, 1.0 / len);
    double ha = vdot(n, r->point_a), hb = vdot(n, r->point_b);
    for (uint32_t i = 0; i < a->nv; ++i) {
        double x = vdot(n, w->va[i]) - ha;
        if (x > viol) viol = x;
    }
    for (uint32_t i = 0; i < b->nv; ++i) {
        double x = hb - vdot(n, w->vb[i]);
        if (x > viol) viol = x;
    }
    return viol / scale;
}

/* Distance between segments p0p1 and q0q1 (Ericson, Real-Time Collision
 * Detection, §5.1.9, with clamping). */
static double seg_seg(px_vec3 p0, px_vec3 p1, px_vec3 q0, px_vec3 q1) {
    px_vec3 d1 = vsub(p1, p0), d2 = vsub(q1, q0), r = vsub(p0, q0);
    double a = vdot(d1, d1), e = vdot(d2, d2), f = vdot(d2, r);
    double s = 0, t = 0;
    if (a <= 0 && e <= 0) return vlen(r);
    if (a <= 0) {
        t = fmin(fmax(f / e, 0), 1);
    } else {
        double c = vdot(d1, r);
        if (e <= 0) {
            s = fmin(fmax(-c / a, 0), 1);
        } else {
            double b = vdot(d1, d2), den = a * e - b * b;
            s = den > 0 ? fmin(fmax((b * f - c * e) / den, 0), 1) : 0;
            t = (b * s + f) / e;
            if (t < 0) {
                t = 0;
                s = fmin(fmax(-c / a, 0), 1);
            } else if (t > 1) {
                t = 1;
                s = fmin(fmax((b - c) / a, 0), 1);
            }
        }
    }
    return vlen(vsub(vadd(p0, vscale(d1, s)), vadd(q0, vscale(d2, t))));
}

/* Distance from p to face f of b (world), if p projects inside the face;
 * otherwise INFINITY (the edge-edge pairs cover that case). */
static double point_face(const body *b, const px_vec3 *wv, const px_pose *pose, uint32_t f, px_vec3 p) {
    px_vec3 n;
    double d;
    px_convex_face(b->c, f, &n, &d, NULL);
    px_vec3 nw = rot_apply(pose->r, n);
    uint32_t m = face_size(b->c, f);
    px_vec3 v0 = wv[face_vertex(b->c, f, 0)];
    double s = vdot(nw, vsub(p, v0));
    px_vec3 q = vsub(p, vscale(nw, s));
    for (uint32_t k = 0; k < m; ++k) {
        px_vec3 x0 = wv[face_vertex(b->c, f, k)];
        px_vec3 x1 = wv[face_vertex(b->c, f, (k + 1) % m)];
        if (vdot(vcross(vsub(x1, x0), vsub(q, x0)), nw) < 0) return INFINITY;
    }
    return fabs(s);
}

/* Brute force distance between two disjoint convex polytopes: the minimum
 * over all vertex-face and edge-edge pairs (every candidate is a distance
 * between a point of A and a point of B, and the closest pair of disjoint
 * polytopes is always realised by one of these pairs). */
static double brute_distance(const world *w, const body *a, const px_pose *pa, const body *b,
                             const px_pose *pb) {
    double best = INFINITY;
    for (uint32_t i = 0; i < a->nv; ++i)
        for (uint32_t f = 0; f < b->nf; ++f) best = fmin(best, point_face(b, w->vb, pb, f, w->va[i]));
    for (uint32_t i = 0; i < b->nv; ++i)
        for (uint32_t f = 0; f < a->nf; ++f) best = fmin(best, point_face(a, w->va, pa, f, w->vb[i]));
    for (uint32_t e = 0; e < a->ne; ++e) {
        uint32_t ea[2];
        px_convex_edge(a->c, e, ea);
        for (uint32_t g = 0; g < b->ne; ++g) {
            uint32_t eb[2];
            px_convex_edge(b->c, g, eb);
            best = fmin(best, seg_seg(w->va[ea[0]], w->va[ea[1]], w->vb[eb[0]], w->vb[eb[1]]));
        }
    }
    return best;
}

/* Relative tolerance of all checks: 1e-9 of |t_AB| + R_A + R_B (REFERENCES
 * §7.2: a plain relative bound on the distance is meaningless near contact). */
#define DEMO_REL_TOL 1e-9

static void check_answer(const world *w, const body *a, const px_pose *pa, const body *b, const px_pose *pb,
                         const px_distance_result *r, double scale, const char *what) {
    double v = certify(w, a, pa, b, pb, r, scale);
    g_sanity.certificates++;
    if (v > g_sanity.worst_cert_rel) g_sanity.worst_cert_rel = v;
    if (!(v <= DEMO_REL_TOL)) {
        if (g_sanity.certificate_failures++ < 5)
            fprintf(stderr, "SANITY: %s vs %s (%s): certificate violated by %.3g x scale (d = %.17g)\n",
                    a->name, b->name, what, v, r->distance);
    }
}

/* ------------------------------------------------------------------------- */
/* One experiment: a pair of bodies along a motion                           */
/* ------------------------------------------------------------------------- */

typedef struct run_opts {
    int steps;
    int reps;         /* timed repetitions of each query (the cache is restored before each) */
    int random_start; /* also time queries started from a random feature pair */
} run_opts;

typedef struct run_stats {
    double warm_med, warm_mean, cold_med, cold_mean, rand_med, rand_mean; /* microseconds per query */
    double warm_iter, cold_iter, rand_iter;                               /* mean feature changes per query */
    unsigned long fallbacks[3]; /* safeguard restarts: tracking, cold, random start */
    int intersecting_steps;
    double dmin, dmax;
} run_stats;

static px_feature random_feature(const body *b) {
    px_feature f;
    uint64_t x = pg_sm_next(&g_rng);
    uint32_t type = 1 + (uint32_t)(x % 3);
    uint32_t n = type == PX_FEATURE_VERTEX ? b->nv : type == PX_FEATURE_EDGE ? b->ne : b->nf;
    f.type = type;
    f.index = (uint32_t)((x >> 8) % n);
    return f;
}

/* Times one query (px_distance, or px_distance when `opt` is not NULL). */
static int timed_query_ex(const body *a, const px_pose *pa, const body *b, const px_pose *pb,
                          const px_query_options *opt, px_pair_cache *cache, int reps, double *us,
                          px_distance_result *res) {
    px_pair_cache start = *cache, c = start;
    px_status st = PX_OK;
    double t0 = now_ns();
    for (int r = 0; r < reps; ++r) {
        c = start;
        st = opt ? px_distance(a->c, pa, b->c, pb, opt, &c, res)
                 : px_distance(a->c, pa, b->c, pb, NULL, &c, res);
    }
    double t1 = now_ns();
    *us = (t1 - t0) * 1e-3 / reps;
    *cache = c;
    if (st != PX_OK) {
        if (g_sanity.query_errors++ < 5)
            fprintf(stderr, "SANITY: px_distance(%s, %s) failed: %s\n", a->name, b->name,
                    px_status_string(st));
        return 0;
    }
    return 1;
}

static int timed_query(const body *a, const px_pose *pa, const body *b, const px_pose *pb,
                       px_pair_cache *cache, int reps, double *us, px_distance_result *res) {
    return timed_query_ex(a, pa, b, pb, NULL, cache, reps, us, res);
}

static run_stats run_pair(const body *a, const body *b, const pg_spin *m, const run_opts *o,
                          int brute_checks) {
    run_stats s;
    memset(&s, 0, sizeof s);
    s.dmin = INFINITY;
    int n = o->steps;
    double *tw = calloc(n, sizeof *tw), *tc = calloc(n, sizeof *tc), *tr = calloc(n, sizeof *tr);
    if (!tw || !tc || !tr) exit(2);
    world w;
    memset(&w, 0, sizeof w);
    px_pair_cache warm;
    memset(&warm, 0, sizeof warm);
    double scale = a->radius + b->radius + (m->separation + m->disp_amp);
    double sum_w = 0, sum_c = 0, sum_r = 0;
    for (int k = 0; k < n; ++k) {
        px_pose pa, pb;
        pg_spin_poses(m, a->center, b->center, k, &pa, &pb);
        world_fill(&w, a, &pa, b, &pb);

        px_distance_result rw, rc, rr;
        timed_query(a, &pa, b, &pb, &warm, o->reps, &tw[k], &rw);
        px_pair_cache cold;
        memset(&cold, 0, sizeof cold);
        timed_query(a, &pa, b, &pb, &cold, o->reps, &tc[k], &rc);
        sum_w += tw[k];
        sum_c += tc[k];
        s.warm_iter += rw.diag.iterations;
        s.cold_iter += rc.diag.iterations;
        s.fallbacks[0] += rw.diag.fallbacks;
        s.fallbacks[1] += rc.diag.fallbacks;
        if (g_verbose && (rw.diag.fallbacks || rc.diag.fallbacks)) {
            fprintf(stderr, "fallback: %s / %s step %d (tracking %u, cold %u), d = %.17g\n", a->name, b->name,
                    k, rw.diag.fallbacks, rc.diag.fallbacks, rw.distance);
            print_pose_hex("pose_a", &pa);
            print_pose_hex("pose_b", &pb);
        }
        check_answer(&w, a, &pa, b, &pb, &rw, scale, "tracking");
        check_answer(&w, a, &pa, b, &pb, &rc, scale, "cold");
        if (fabs(rw.distance - rc.distance) > DEMO_REL_TOL * scale || rw.intersecting != rc.intersecting) {
            if (g_sanity.agreement_failures++ < 5)
                fprintf(stderr, "SANITY: %s vs %s step %d: tracking d = %.17g, cold d = %.17g\n", a->name,
                        b->name, k, rw.distance, rc.distance);
        }
        if (o->random_start) {
            px_pair_cache rnd;
            rnd.feature_a = random_feature(a);
            rnd.feature_b = random_feature(b);
            timed_query(a, &pa, b, &pb, &rnd, o->reps, &tr[k], &rr);
            sum_r += tr[k];
            s.rand_iter += rr.diag.iterations;
            s.fallbacks[2] += rr.diag.fallbacks;
            check_answer(&w, a, &pa, b, &pb, &rr, scale, "random start");
            if (fabs(rw.distance - rr.distance) > DEMO_REL_TOL * scale) {
                if (g_sanity.agreement_failures++ < 5)
                    fprintf(stderr, "SANITY: %s vs %s step %d: tracking d = %.17g, random-start d = %.17g\n",
                            a->name, b->name, k, rw.distance, rr.distance);
            }
        }
        if (rw.intersecting) s.intersecting_steps++;
        if (rw.distance < s.dmin) s.dmin = rw.distance;
        if (rw.distance > s.dmax) s.dmax = rw.distance;
        /* Brute force at evenly spaced steps (disjoint answers only). */
        int interval = brute_checks > 0 && n / brute_checks > 0 ? n / brute_checks : 1;
        if (brute_checks > 0 && k % interval == 0 && k / interval < brute_checks && !rw.intersecting) {
            double d = brute_distance(&w, a, &pa, b, &pb);
            double rel = fabs(d - rw.distance) / scale;
            g_sanity.brute++;
            if (rel > g_sanity.worst_brute_rel) g_sanity.worst_brute_rel = rel;
            if (!(rel <= DEMO_REL_TOL)) {
                if (g_sanity.brute_failures++ < 5)
                    fprintf(stderr, "SANITY: %s vs %s step %d: d = %.17g, brute force %.17g\n", a->name,
                            b->name, k, rw.distance, d);
            }
        }
    }
    s.warm_mean = sum_w / n;
    s.cold_mean = sum_c / n;
    s.rand_mean = sum_r / n;
    s.warm_med = median(tw, n);
    s.cold_med = median(tc, n);
    s.rand_med = median(tr, n);
    s.warm_iter /= n;
    s.cold_iter /= n;
    s.rand_iter /= n;
    free(tw);
    free(tc);
    free(tr);
    free(w.va);
    free(w.vb);
    return s;
}

static unsigned long g_fallbacks_total;

/* The library's safeguard (cycle detector / step cap -> exhaustive restart)
 * is expected never to fire; show it when it does. */
static void print_fallbacks(const run_stats *s) {
    unsigned long t = s->fallbacks[0] + s->fallbacks[1] + s->fallbacks[2];
    if (!t) return;
    g_fallbacks_total += t;
    printf("      ^ safeguard fallbacks (px_distance_result.diag.fallbacks, expected 0): tracking %lu, cold "
           "%lu, "
           "random start %lu\n",
           s->fallbacks[0], s->fallbacks[1], s->fallbacks[2]);
}

/* Brute-force checks per row: fewer on big pairs (each costs ~ne_A*ne_B). */
static int brute_budget(const body *a, const body *b) {
    double work = (double)a->ne * b->ne + 3.0 * ((double)a->nv * b->nf + (double)b->nv * a->nf);
    if (work > 3e7) return 1;
    if (work > 3e6) return 2;
    return 4;
}

/* ------------------------------------------------------------------------- */
/* (d)-(g): the newer queries (methods, signed distance, collision           */
/* translation, boolean test) on the shipped models                          */
/* ------------------------------------------------------------------------- */

/* Every check of (d)-(g) goes through record(): a FAIL is printed and makes
 * the program exit with status 1. */
static unsigned long g_checks, g_check_failures;

static int record(int ok) {
    g_checks++;
    if (!ok) g_check_failures++;
    return ok;
}
static const char *okfail(int ok) { return ok ? "OK" : "FAIL"; }

#define NEW_TOL 1e-9     /* tolerance of the (d)-(g) checks, x size (size = R_A + R_B) */
#define TOUCH_BAND 1e-12 /* |signed distance| <= TOUCH_BAND x size: "touching" */
#define N_METHODS 3

static const char *const k_method_names[N_METHODS] = {"Lin-Canny", "GJK", "hybrid"};
static const uint32_t k_methods[N_METHODS] = {PX_METHOD_LIN_CANNY, PX_METHOD_GJK, PX_METHOD_HYBRID};

static px_vec3 vunit(px_vec3 a) { return vscale(a, 1.0 / vlen(a)); }

/* A random direction for the minimality check of (e), from the demo's stream:
 * a point of the cube [-1, 1)^3 kept if 1e-4 <= |d|^2 <= 1, normalised. The
 * coordinates are drawn z, y, x: the old code drew them as the three
 * arguments of one call, in an unspecified order, and GCC's right-to-left is
 * written down here so that the table of (e) stays as it was (and no longer
 * depends on the compiler). pg_sm_unit draws x, y, z. */
static px_vec3 random_direction(void) {
    for (;;) {
        double z = 2 * pg_sm_uniform(&g_rng) - 1;
        double y = 2 * pg_sm_uniform(&g_rng) - 1;
        double x = 2 * pg_sm_uniform(&g_rng) - 1;
        px_vec3 d = v3(x, y, z);
        if (vdot(d, d) <= 1.0 && vdot(d, d) >= 1e-4) return vunit(d);
    }
}

/* Pose with rotation r that puts the body's centre at world point c. */
static px_pose pose_centred(const body *b, const double r[9], px_vec3 c) {
    return pg_pose_centred(r, b->center, c);
}

static px_pose pose_shifted(const px_pose *p, px_vec3 d) {
    px_pose q = *p;
    q.t = vadd(q.t, d);
    return q;
}

/* A copy of a body's hull scaled about the body origin by f. */
static int make_scaled(const body *src, double f, const char *name, body *out) {
    double *p = malloc(3 * (size_t)src->nv * sizeof *p);
    if (!p) exit(2);
    for (uint32_t v = 0; v < src->nv; ++v) {
        px_vec3 q = vscale(vertex_of(src->c, v), f);
        p[3 * v] = q.x, p[3 * v + 1] = q.y, p[3 * v + 2] = q.z;
    }
    px_convex *c = from_points_or_die(name, p, src->nv);
    free(p);
    return body_init(out, name, c);
}

/* A pair of (d)-(g). B gets a fixed extra rotation r0 so that two copies of
 * a hull do not meet mirror-aligned. */
typedef struct qpair {
    const char *name;
    const body *a, *b;
    double size; /* R_A + R_B: the unit of every tolerance */
    double r0[9];
} qpair;

/* Tracked motion (pg_swing, px_gen.h), step k of n, phi = accumulated
 * relative rotation (the sum of pg_swing_step): A turns by +phi/2 and B by
 * -phi/2 about (1,2,3)/sqrt(14), A's centre stays at the origin, B's centre
 * is f(k) * size along x with f swinging twice from 1.15 (apart) to 0.35
 * (deep overlap) and back, plus a sideways wobble of 8% of size. */
static void track_poses(const qpair *p, int k, int n, double phi, px_pose *pa, px_pose *pb) {
    pg_swing m;
    m.axis = k_axis;
    m.size = p->size;
    memcpy(m.r0, p->r0, sizeof m.r0);
    pg_swing_poses(&m, p->a->center, p->b->center, k, n, phi, pa, pb);
}

/* World centre of a body at a pose. */
static px_vec3 centre_at(const body *b, const px_pose *p) { return px_pose_apply(p, b->center); }

static int timed_intersect(const body *a, const px_pose *pa, const body *b, const px_pose *pb,
                           px_pair_cache *cache, int reps, double *us, int *hit) {
    px_pair_cache start = *cache, c = start;
    px_status st = PX_OK;
    double t0 = now_ns();
    for (int r = 0; r < reps; ++r) {
        c = start;
        px_intersect_result ir;
        st = px_intersect(a->c, pa, b->c, pb, NULL, &c, &ir);
        *hit = ir.intersecting;
    }
    *us = (now_ns() - t0) * 1e-3 / reps;
    *cache = c;
    if (!record(st == PX_OK))
        fprintf(stderr, "FAIL: px_intersect(%s, %s): %s\n", a->name, b->name, px_status_string(st));
    return st == PX_OK;
}

static int timed_translation(const body *a, const px_pose *pa, const body *b, const px_pose *pb, px_vec3 dir,
                             px_pair_cache *cache, int reps, double *us, px_translate_result *res) {
    px_pair_cache start = *cache, c = start;
    px_status st = PX_OK;
    double t0 = now_ns();
    for (int r = 0; r < reps; ++r) {
        c = start;
        st = px_translate(a->c, pa, b->c, pb, dir, &demo_both_ways, &c, res);
    }
    *us = (now_ns() - t0) * 1e-3 / reps;
    *cache = c;
    if (!record(st == PX_OK))
        fprintf(stderr, "FAIL: px_translate(%s, %s): %s\n", a->name, b->name, px_status_string(st));
    return st == PX_OK;
}

/* Unsigned or signed distance by one method, cold, untimed. */
static px_distance_result query(const qpair *p, const px_pose *pa, const px_pose *pb, uint32_t method,
                                uint32_t flags) {
    px_query_options o;
    memset(&o, 0, sizeof o);
    o.method = method;
    o.flags = flags;
    px_distance_result r;
    px_status st = px_distance(p->a->c, pa, p->b->c, pb, &o, NULL, &r);
    if (!record(st == PX_OK)) {
        fprintf(stderr, "FAIL: px_distance(%s, method %u, flags %u): %s\n", p->name, method, flags,
                px_status_string(st));
        memset(&r, 0, sizeof r);
        r.signed_distance = r.distance = NAN;
    }
    return r;
}

/* Certificate of (d): as certify(), but a disjoint answer's slab is normal to the reported `normal`
 * (a unit vector with normal . (point_b - point_a) = distance). Below 1e-6 x scale the slab is not
 * checked: a normal computed as (point_b - point_a) / distance has a direction error of about
 * eps |point| / distance, which the slab magnifies by the body's extent; there only the witness
 * points are checked (in their bodies, |point_b - point_a| = distance). */
#define CERT_SLAB_MIN 1e-6
static double certify_n(const world *w, const body *a, const px_pose *pa, const body *b, const px_pose *pb,
                        const px_distance_result *r, double scale) {
    if (r->intersecting) return certify(w, a, pa, b, pb, r, scale);
    if (!isfinite(r->distance) || r->distance < 0) return INFINITY;
    px_vec3 n = r->normal, dv = vsub(r->point_b, r->point_a);
    double viol = fmax(max_plane_excess(a, pa, r->point_a), max_plane_excess(b, pb, r->point_b));
    viol = fmax(viol, fabs(vlen(dv) - r->distance));
    if (r->distance < CERT_SLAB_MIN * scale) return viol / scale;
    viol = fmax(viol, fabs(vlen(n) - 1.0) * scale);
    viol = fmax(viol, fabs(vdot(n, dv) - r->distance));
    double ha = vdot(n, r->point_a), hb = vdot(n, r->point_b);
    for (uint32_t i = 0; i < a->nv; ++i) viol = fmax(viol, vdot(n, w->va[i]) - ha);
    for (uint32_t i = 0; i < b->nv; ++i) viol = fmax(viol, hb - vdot(n, w->vb[i]));
    return viol / scale;
}

/* Per-method statistics of (d). */
typedef struct method_stats {
    double track_med, cold_med, max_rel_diff, worst_cert;
    unsigned long flag_out, flag_band, fallbacks, cert_fail, warm_cold_fail;
} method_stats;

/* Statistics of (g), per pair. */
typedef struct intersect_stats {
    double track_med, cold_med;
    unsigned long agree, dis_out, dis_band;
} intersect_stats;

typedef struct track_stats {
    int steps, intersecting, band, touch_snaps;
    method_stats m[N_METHODS];
    intersect_stats x;
} track_stats;

/* (d) and (g): the tracked motion, every method with its own warm cache plus
 * a cold query per step, and px_intersect. */
static track_stats run_tracked(const qpair *p, int n, int reps) {
    track_stats s;
    memset(&s, 0, sizeof s);
    s.steps = n;
    double *tw[N_METHODS + 1], *tc[N_METHODS + 1];
    for (int m = 0; m <= N_METHODS; ++m) {
        tw[m] = calloc(n, sizeof *tw[m]);
        tc[m] = calloc(n, sizeof *tc[m]);
        if (!tw[m] || !tc[m]) exit(2);
    }
    px_pair_cache warm[N_METHODS], xwarm, ref_cache;
    memset(warm, 0, sizeof warm);
    memset(&xwarm, 0, sizeof xwarm);
    memset(&ref_cache, 0, sizeof ref_cache);
    world w;
    memset(&w, 0, sizeof w);
    double phi = 0.0;
    for (int k = 0; k < n; ++k) {
        px_pose pa, pb;
        track_poses(p, k, n, phi, &pa, &pb);
        phi += pg_swing_step(k);
        if (k % 50 == 25) {
            /* Touching: slide A along the line of centres until it touches B. */
            px_vec3 u = vunit(vsub(centre_at(p->b, &pb), centre_at(p->a, &pa)));
            px_translate_result tr;
            px_status st = px_translate(p->a->c, &pa, p->b->c, &pb, u, &demo_both_ways, NULL, &tr);
            if (!record(st == PX_OK && tr.hit))
                fprintf(stderr, "FAIL: %s step %d: px_translate along the line of centres: %s, hit %d\n",
                        p->name, k, px_status_string(st), tr.hit);
            else
                pa = pose_shifted(&pa, vscale(u, tr.tau)), s.touch_snaps++;
        }
        world_fill(&w, p->a, &pa, p->b, &pb);
        /* Reference: the signed Lin-Canny distance (with EPA depth) says which steps are in the band. */
        px_query_options ro;
        memset(&ro, 0, sizeof ro);
        ro.flags = PX_QUERY_SIGNED;
        px_distance_result ref;
        px_status st = px_distance(p->a->c, &pa, p->b->c, &pb, &ro, &ref_cache, &ref);
        record(st == PX_OK);
        int band = fabs(ref.signed_distance) <= TOUCH_BAND * p->size;
        s.band += band;
        px_distance_result rw[N_METHODS];
        for (int m = 0; m < N_METHODS; ++m) {
            px_query_options o;
            memset(&o, 0, sizeof o);
            o.method = k_methods[m];
            px_distance_result rc;
            px_pair_cache cold;
            memset(&cold, 0, sizeof cold);
            record(timed_query_ex(p->a, &pa, p->b, &pb, &o, &warm[m], reps, &tw[m][k], &rw[m]));
            record(timed_query_ex(p->a, &pa, p->b, &pb, &o, &cold, reps, &tc[m][k], &rc));
            method_stats *ms = &s.m[m];
            ms->fallbacks += rw[m].diag.fallbacks + rc.diag.fallbacks;
            for (int j = 0; j < 2; ++j) {
                double v = certify_n(&w, p->a, &pa, p->b, &pb, j ? &rc : &rw[m], p->size);
                if (v > ms->worst_cert) ms->worst_cert = v;
                if (!record(v <= NEW_TOL)) {
                    if (ms->cert_fail++ < 3)
                        fprintf(stderr, "FAIL: %s step %d, %s (%s): certificate violated by %.3g x size\n",
                                p->name, k, k_method_names[m], j ? "cold" : "track", v);
                    if (ms->cert_fail <= 3) print_pose_hex("pose_a", &pa), print_pose_hex("pose_b", &pb);
                }
            }
            int same = fabs(rw[m].distance - rc.distance) <= NEW_TOL * p->size &&
                       (band || rw[m].intersecting == rc.intersecting);
            if (!record(same)) {
                if (ms->warm_cold_fail++ < 3)
                    fprintf(stderr,
                            "FAIL: %s step %d, %s: track d = %.17g (int %d), cold d = %.17g (int %d)\n",
                            p->name, k, k_method_names[m], rw[m].distance, rw[m].intersecting, rc.distance,
                            rc.intersecting);
            }
        }
        s.intersecting += rw[0].intersecting;
        for (int m = 1; m < N_METHODS; ++m) {
            method_stats *ms = &s.m[m];
            double rel = fabs(rw[m].distance - rw[0].distance) / p->size;
            if (!(rel <= ms->max_rel_diff)) ms->max_rel_diff = rel;
            if (rw[m].intersecting != rw[0].intersecting) {
                if (band) {
                    ms->flag_band++;
                } else if (ms->flag_out++ < 3) {
                    fprintf(stderr,
                            "FAIL: %s step %d: %s intersecting = %d (d = %.17g), Lin-Canny %d (d = %.17g, "
                            "signed %.17g)\n",
                            p->name, k, k_method_names[m], rw[m].intersecting, rw[m].distance,
                            rw[0].intersecting, rw[0].distance, ref.signed_distance);
                    print_pose_hex("pose_a", &pa);
                    print_pose_hex("pose_b", &pb);
                }
            }
        }
        /* (g) px_intersect against the Lin-Canny flag. */
        int xw = -1, xc = -1;
        px_pair_cache xcold;
        memset(&xcold, 0, sizeof xcold);
        timed_intersect(p->a, &pa, p->b, &pb, &xwarm, reps, &tw[N_METHODS][k], &xw);
        timed_intersect(p->a, &pa, p->b, &pb, &xcold, reps, &tc[N_METHODS][k], &xc);
        for (int j = 0; j < 2; ++j) {
            int x = j ? xc : xw;
            if (x == rw[0].intersecting) {
                s.x.agree++;
            } else if (band) {
                s.x.dis_band++;
            } else if (s.x.dis_out++ < 3) {
                fprintf(stderr,
                        "FAIL: %s step %d: px_intersect (%s) = %d, Lin-Canny intersecting = %d (d = %.17g)\n",
                        p->name, k, j ? "cold" : "track", x, rw[0].intersecting, rw[0].distance);
            }
        }
    }
    for (int m = 0; m < N_METHODS; ++m) {
        s.m[m].track_med = median(tw[m], n);
        s.m[m].cold_med = median(tc[m], n);
        record(s.m[m].flag_out == 0);
    }
    record(s.x.dis_out == 0);
    s.x.track_med = median(tw[N_METHODS], n);
    s.x.cold_med = median(tc[N_METHODS], n);
    for (int m = 0; m <= N_METHODS; ++m) free(tw[m]), free(tc[m]);
    free(w.va);
    free(w.vb);
    return s;
}

static void print_tracked(const qpair *p, const track_stats *s) {
    printf("\n    %s: size %.4g, %d steps, %d intersecting, %d in the touching band (%d slid to contact)\n",
           p->name, p->size, s->steps, s->intersecting, s->band, s->touch_snaps);
    for (int m = 0; m < N_METHODS; ++m) {
        const method_stats *ms = &s->m[m];
        int ok = ms->flag_out == 0 && ms->cert_fail == 0 && ms->warm_cold_fail == 0;
        char diff[32], flags[32];
        if (m == 0)
            snprintf(diff, sizeof diff, "(reference)"), snprintf(flags, sizeof flags, "-");
        else
            snprintf(diff, sizeof diff, "%.2g", ms->max_rel_diff),
                snprintf(flags, sizeof flags, "%lu (%lu)", ms->flag_out, ms->flag_band);
        printf("      %-10s %9.3f %9.3f %16s %14s %9lu %10.2g  %s\n", k_method_names[m], ms->track_med,
               ms->cold_med, diff, flags, ms->fallbacks, ms->worst_cert, okfail(ok));
    }
}

/* (e) one pair pushed into overlap by several depths. */
static void run_signed(const qpair *p, int reps) {
    /* Base configuration: the tracked motion's orientation at step 137, B apart along x. */
    double phi = 0.0;
    for (int k = 0; k < 137; ++k) phi += pg_swing_step(k);
    px_pose pa, pb;
    track_poses(p, 0, 1000, phi, &pa, &pb);
    px_vec3 u = vunit(vsub(centre_at(p->b, &pb), centre_at(p->a, &pa)));
    px_translate_result tr;
    px_status st = px_translate(p->a->c, &pa, p->b->c, &pb, u, &demo_both_ways, NULL, &tr);
    if (!record(st == PX_OK && tr.hit)) {
        printf("      %-34s FAIL: px_translate along the line of centres: %s, hit %d\n", p->name,
               px_status_string(st), tr.hit);
        return;
    }
    const double push[] = {1e-6, 1e-3, 0.02, 0.1, 0.3};
    for (size_t i = 0; i < sizeof push / sizeof *push; ++i) {
        px_pose pai = pose_shifted(&pa, vscale(u, tr.tau + push[i] * p->size));
        px_distance_result r[N_METHODS];
        double us[N_METHODS];
        int ok_int = 1;
        double agree = 0, move = 0, wit = 0;
        for (int m = 0; m < N_METHODS; ++m) {
            px_query_options o;
            memset(&o, 0, sizeof o);
            o.method = k_methods[m];
            o.flags = PX_QUERY_SIGNED;
            double batch[7]; /* one query: the median of 7 timed batches, against interruptions */
            for (int b = 0; b < 7; ++b) {
                px_pair_cache cold;
                memset(&cold, 0, sizeof cold);
                record(timed_query_ex(p->a, &pai, p->b, &pb, &o, &cold, reps, &batch[b], &r[m]));
            }
            us[m] = median(batch, 7);
            ok_int &= r[m].intersecting && r[m].signed_distance < 0 && r[m].distance == 0.0;
            agree = fmax(agree, fabs(r[m].signed_distance - r[0].signed_distance) / p->size);
            /* Witnesses: point_b - point_a == signed_distance * normal, |normal| = 1, both points on
             * their bodies' boundaries. */
            px_vec3 e = vsub(vsub(r[m].point_b, r[m].point_a), vscale(r[m].normal, r[m].signed_distance));
            wit = fmax(wit, vlen(e) / p->size);
            wit = fmax(wit, fabs(vlen(r[m].normal) - 1.0));
            wit = fmax(wit, fabs(max_plane_excess(p->a, &pai, r[m].point_a)) / p->size);
            wit = fmax(wit, fabs(max_plane_excess(p->b, &pb, r[m].point_b)) / p->size);
            /* Translating B by depth * normal makes the pair touch: signed distance ~ 0 afterwards. */
            px_pose pbm = pose_shifted(&pb, vscale(r[m].normal, -r[m].signed_distance));
            px_distance_result after = query(p, &pai, &pbm, PX_METHOD_LIN_CANNY, PX_QUERY_SIGNED);
            move = fmax(move, fabs(after.signed_distance) / p->size);
        }
        double depth = -r[0].signed_distance;
        /* Minimality: depth = min over directions d of the translation that separates, |tau(d)|. It
         * must be reached along the normal, and no direction (the push direction, 64 random ones)
         * may need less. */
        double min_tau = INFINITY, along_n = NAN;
        for (int j = 0; j < 66; ++j) {
            px_vec3 d;
            if (j == 0)
                d = r[0].normal;
            else if (j == 1)
                d = u;
            else
                d = random_direction();
            px_translate_result t;
            px_status s2 = px_translate(p->a->c, &pai, p->b->c, &pb, d, &demo_both_ways, NULL, &t);
            if (!record(s2 == PX_OK && t.hit && t.tau <= 0)) {
                min_tau = -INFINITY;
                continue;
            }
            if (j == 0)
                along_n = -t.tau;
            else
                min_tau = fmin(min_tau, -t.tau);
        }
        int ok_agree = agree <= TOUCH_BAND, ok_move = move <= NEW_TOL, ok_wit = wit <= NEW_TOL;
        double n_err = fabs(along_n - depth) / p->size;
        int ok_min = min_tau >= depth - NEW_TOL * p->size && n_err <= NEW_TOL;
        int ok = record(ok_int) & record(ok_agree) & record(ok_move) & record(ok_wit) & record(ok_min);
        printf(
            "      %-30s %7.0e %12.6g %12.6g %12.6g %7.1g %7.1g %7.1g %7.1g %8.4f  %5.2f %5.2f %5.2f  %s\n",
            i == 0 ? p->name : "", push[i], depth, -r[1].signed_distance, -r[2].signed_distance, agree, move,
            wit, n_err, min_tau / depth, us[0], us[1], us[2], okfail(ok));
        if (!ok)
            fprintf(stderr,
                    "FAIL: (e) %s push %g: intersecting %d, agreement %.3g, move %.3g, witnesses %.3g, "
                    "min |tau| %.17g vs depth %.17g (along the normal %.17g)\n",
                    p->name, push[i], ok_int, agree, move, wit, min_tau, depth, along_n);
    }
}

/* (f) A slides along a direction toward B. */
static void run_translation_row(const qpair *p, const char *label, px_vec3 dir, double centre_dist,
                                int expect, int reps) {
    double ra[9], rb1[9], rb[9];
    pg_rot_rodrigues(k_axis, 0.4, ra);
    pg_rot_rodrigues(k_axis, -0.4, rb1);
    pg_mat_mul(rb1, p->r0, rb);
    px_pose pa = pose_centred(p->a, ra, v3(0, 0, 0));
    px_pose pb = pose_centred(p->b, rb, v3(centre_dist * p->size, 0, 0));
    dir = vunit(dir);
    px_translate_result t;
    px_status st = px_translate(p->a->c, &pa, p->b->c, &pb, dir, &demo_both_ways, NULL, &t);
    if (!record(st == PX_OK)) {
        printf("      %-26s FAIL: %s\n", label, px_status_string(st));
        return;
    }
    int ok = 1;
    char what[96], check[96];
    if (expect >= 0) ok &= t.hit == expect;
    if (t.hit) {
        /* Touching at tau, disjoint a little before, not overlapping at tau. */
        px_pose at = pose_shifted(&pa, vscale(dir, t.tau));
        px_pose before = pose_shifted(&pa, vscale(dir, t.tau - 1e-6 * p->size));
        px_distance_result r0 = query(p, &at, &pb, PX_METHOD_LIN_CANNY, PX_QUERY_SIGNED);
        px_distance_result r1 = query(p, &before, &pb, PX_METHOD_LIN_CANNY, 0);
        double gap_pts = vlen(vsub(t.point_b, t.point_a)) / p->size;
        ok &= fabs(r0.signed_distance) <= NEW_TOL * p->size && r1.distance > 0 && !r1.intersecting &&
              gap_pts <= NEW_TOL && fabs(vlen(t.normal) - 1.0) <= 1e-12;
        snprintf(what, sizeof what, "tau %+.6f  n (%+.3f %+.3f %+.3f)", t.tau / p->size, t.normal.x,
                 t.normal.y, t.normal.z);
        snprintf(check, sizeof check, "|d(tau)| %7.1e  d(tau-1e-6) %8.2e", fabs(r0.signed_distance) / p->size,
                 r1.distance / p->size);
    } else {
        /* A separating slab of width gap, parallel to the direction: holds for every tau. */
        world w;
        memset(&w, 0, sizeof w);
        world_fill(&w, p->a, &pa, p->b, &pb);
        double ha = vdot(t.normal, t.point_a), hb = vdot(t.normal, t.point_b), viol = 0;
        for (uint32_t i = 0; i < p->a->nv; ++i) viol = fmax(viol, vdot(t.normal, w.va[i]) - ha);
        for (uint32_t i = 0; i < p->b->nv; ++i) viol = fmax(viol, hb - vdot(t.normal, w.vb[i]));
        free(w.va);
        free(w.vb);
        double dmin = INFINITY;
        for (int j = -4; j <= 4; ++j) {
            px_pose q = pose_shifted(&pa, vscale(dir, 0.5 * j * p->size));
            dmin = fmin(dmin, query(p, &q, &pb, PX_METHOD_LIN_CANNY, 0).distance);
        }
        ok &= t.gap > 0 && fabs(vdot(t.normal, dir)) <= 1e-12 && fabs(vlen(t.normal) - 1.0) <= 1e-12 &&
              viol <= NEW_TOL * p->size && fabs(hb - ha - t.gap) <= NEW_TOL * p->size &&
              dmin >= t.gap - NEW_TOL * p->size;
        snprintf(what, sizeof what, "gap %.6f  n (%+.3f %+.3f %+.3f)", t.gap / p->size, t.normal.x,
                 t.normal.y, t.normal.z);
        snprintf(check, sizeof check, "slab %8.1e  min d(tau) %.4f", viol / p->size, dmin / p->size);
    }
    /* Timing: 100 small moves of A (0.5 degree and 0.2% of size per step), with a warm cache and cold;
     * the two answers must agree. */
    double tw[100], tc[100];
    px_pair_cache warm;
    memset(&warm, 0, sizeof warm);
    unsigned long dis = 0;
    for (int j = 0; j < 100; ++j) {
        double rj[9], raj[9];
        pg_rot_rodrigues(v3(0.6, 0, 0.8), j * 0.5 * DEMO_PI / 180.0, rj);
        pg_mat_mul(rj, ra, raj);
        px_pose pj = pose_centred(p->a, raj, v3(0, 0.002 * j * p->size, -0.001 * j * p->size));
        px_translate_result a1, a2;
        px_pair_cache cold;
        memset(&cold, 0, sizeof cold);
        timed_translation(p->a, &pj, p->b, &pb, dir, &warm, reps, &tw[j], &a1);
        timed_translation(p->a, &pj, p->b, &pb, dir, &cold, reps, &tc[j], &a2);
        if (a1.hit != a2.hit || (a1.hit && fabs(a1.tau - a2.tau) > NEW_TOL * p->size) ||
            (!a1.hit && fabs(a1.gap - a2.gap) > NEW_TOL * p->size)) {
            if (dis++ < 3)
                fprintf(stderr,
                        "FAIL: (f) %s move %d: warm hit %d tau %.17g gap %.17g, cold hit %d tau %.17g gap "
                        "%.17g\n",
                        label, j, a1.hit, a1.tau, a1.gap, a2.hit, a2.tau, a2.gap);
        }
    }
    ok &= dis == 0;
    record(ok);
    printf("      %-24s %-5s %-43s %-36s %6.3f %6.3f  %s\n", label, t.hit ? "hit" : "miss", what, check,
           median(tc, 100), median(tw, 100), okfail(ok));
    if (!ok)
        fprintf(stderr,
                "FAIL: (f) %s: hit %d (expected %d), tau %.17g, gap %.17g, warm/cold disagreements %lu\n",
                label, t.hit, expect, t.tau, t.gap, dis);
}

/* Runs (d)-(g); returns the number of failed checks. */
static unsigned long run_new_sections(const char *models, body *tea, body *puma, const run_opts *o) {
    body sc_tea, sc_puma, sphere, rod;
    if (!make_scaled(&tea[1], tea[0].radius / tea[1].radius, "teapot.stl hull, scaled", &sc_tea)) return 1;
    if (!make_scaled(&puma[1], puma[0].radius / puma[1].radius, "Puma link3.dae, scaled", &sc_puma)) return 1;
    if (!body_init(&sphere, "sphere 16x30", make_sphere(16, 30, 1.0))) return 1;
    if (!body_init(&rod, "thin cylinder 48", make_frustum(48, 0.04, 0.04, 2.0))) return 1;
    (void)models;
    qpair pairs[4] = {
        {"teapot.obj / teapot.obj", &tea[0], &tea[0], 0, {0}},
        {"teapot.obj / teapot.stl scaled", &tea[0], &sc_tea, 0, {0}},
        {"Puma link2 / link3 scaled", &puma[0], &sc_puma, 0, {0}},
        {"sphere 16x30 / thin cylinder", &sphere, &rod, 0, {0}},
    };
    for (int i = 0; i < 4; ++i) {
        pairs[i].size = pairs[i].a->radius + pairs[i].b->radius;
        pg_rot_rodrigues(v3(0, 0.6, 0.8), 1.1 + 0.5 * i, pairs[i].r0);
    }
    unsigned long before = g_check_failures;

    /* ---------------------------------------------------------------- (d) */
    printf(
        "\n(d) Methods side by side (px_distance): Lin-Canny, GJK and the hybrid on one tracked motion\n"
        "    %d steps of 1-5 degrees of relative rotation (about (1,2,3)/sqrt(14)); B's centre swings\n"
        "    twice from 1.15 x size to 0.35 x size from A's and back (size = R_A + R_B), with a sideways\n"
        "    wobble: approach, contact, overlap, separation; at every 50th step A is slid along the line\n"
        "    of centres until it touches B (px_translate). Each method keeps its own cache ('track');\n"
        "    'cold' is a zeroed cache. 'max |d-d_LC|' = largest distance difference from Lin-Canny, x size;\n"
        "    'flags' = steps where the intersecting flag differs from Lin-Canny outside the touching band\n"
        "    |signed distance| <= %.0e x size (inside it in parentheses); 'cert' = worst certificate\n"
        "    violation over track and cold answers, x size (as in (a)-(c), but the slab is normal to the\n"
        "    reported normal, and below %.0e x size only the witness points are checked). Times in us.\n",
        o->steps, TOUCH_BAND, CERT_SLAB_MIN);
    printf("\n      %-10s %9s %9s %16s %14s %9s %10s  %s\n", "method", "track med", "cold med",
           "max |d-d_LC|", "flags (band)", "fallbacks", "cert", "check");
    track_stats ts[4];
    for (int i = 0; i < 4; ++i) {
        ts[i] = run_tracked(&pairs[i], o->steps, o->reps);
        print_tracked(&pairs[i], &ts[i]);
    }

    /* ---------------------------------------------------------------- (e) */
    printf(
        "\n(e) Signed distance (PX_QUERY_SIGNED): each pair slid into contact along its line of centres\n"
        "    (px_translate), then pushed a further 'push' x size. Depth = -signed_distance per method;\n"
        "    'agree' = largest depth difference between methods, x size (check: <= %.0e); 'move' = |signed\n"
        "    distance| after translating B by depth x normal, worst method, x size (check: <= %.0e, i.e. "
        "the\n"
        "    pair touches); 'wit' = witness consistency (point_b - point_a = signed_distance x normal, both\n"
        "    points on their boundaries), x size. Minimality, from px_translate (the least translation\n"
        "    of A along d that separates the pair is |tau(d)|, and the depth is its minimum over all d):\n"
        "    'tau(n)' = ||tau(normal)| - depth|, x size (check: <= %.0e); 'min/d' = the least |tau(d)| over\n"
        "    the push direction and 64 random directions, / depth (check: >= 1). Times: one cold signed\n"
        "    query (median of 7 batches of R), us.\n",
        TOUCH_BAND, NEW_TOL, NEW_TOL);
    printf("\n      %-30s %7s %12s %12s %12s %7s %7s %7s %7s %8s  %5s %5s %5s  %s\n", "pair", "push",
           "depth LC", "depth GJK", "depth hyb", "agree", "move", "wit", "tau(n)", "min/d", "LC", "GJK",
           "hyb", "check");
    for (int i = 0; i < 4; ++i) run_signed(&pairs[i], o->reps);

    /* ---------------------------------------------------------------- (f) */
    const qpair *tp = &pairs[1];
    printf(
        "\n(f) Collision translation (px_translate): %s; A slides along a direction, B stays.\n"
        "    Centres 1.1 x size apart along x unless 'overlap' (0.5 x size: starts intersecting, tau < 0).\n"
        "    hit: tau (x size, A moved by tau x direction touches B) and the contact normal; checked: the\n"
        "    signed distance at tau is ~0 (x size), the pair is disjoint 1e-6 x size before, the contact\n"
        "    points coincide. miss: the gap and separating normal (perpendicular to the direction); "
        "checked:\n"
        "    the slab separates all vertices ('slab' = worst violation, x size) and the distance at 9 "
        "points\n"
        "    of the line is >= gap. Head-on must hit, sideways must miss (bounding spheres). Timing: 100\n"
        "    small moves of A (0.5 degree, 0.2%% of size each), a zeroed cache ('cold') vs the previous\n"
        "    answer ('warm'); warm and cold answers must agree. Times in us.\n",
        tp->name);
    printf("\n      %-24s %-5s %-43s %-36s %6s %6s  %s\n", "direction", "", "result (x size)", "check",
           "cold", "warm", "check");
    run_translation_row(tp, "head-on +x", v3(1, 0, 0), 1.1, 1, o->reps);
    run_translation_row(tp, "oblique (1, .3, .2)", v3(1, 0.3, 0.2), 1.1, -1, o->reps);
    run_translation_row(tp, "oblique (1, .8, -.3)", v3(1, 0.8, -0.3), 1.1, -1, o->reps);
    run_translation_row(tp, "away -x (tau < 0)", v3(-1, 0, 0), 1.1, 1, o->reps);
    run_translation_row(tp, "sideways +y", v3(0, 1, 0), 1.1, 0, o->reps);
    run_translation_row(tp, "sideways (.1, .6, .8)", v3(0.1, 0.6, 0.8), 1.1, -1, o->reps);
    run_translation_row(tp, "overlap, +x", v3(1, 0, 0), 0.5, 1, o->reps);
    run_translation_row(tp, "overlap, (0, .3, 1)", v3(0, 0.3, 1), 0.5, 1, o->reps);

    /* ---------------------------------------------------------------- (g) */
    printf("\n(g) px_intersect (boolean, GJK with early exit) over the motion of (d), warm cache and cold, "
           "against\n"
           "    Lin-Canny's intersecting flag; disagreements outside the touching band fail. Times in us.\n");
    printf("\n      %-34s %9s %9s %9s %13s %12s  %s\n", "pair", "track med", "cold med", "agree",
           "disagree out", "in band", "check");
    for (int i = 0; i < 4; ++i) {
        const intersect_stats *x = &ts[i].x;
        printf("      %-34s %9.3f %9.3f %9lu %13lu %12lu  %s\n", pairs[i].name, x->track_med, x->cold_med,
               x->agree, x->dis_out, x->dis_band, okfail(x->dis_out == 0));
    }

    px_convex_destroy(sc_tea.c);
    px_convex_destroy(sc_puma.c);
    px_convex_destroy(sphere.c);
    px_convex_destroy(rod.c);
    unsigned long f = g_check_failures - before;
    printf("\nchecks of (d)-(g): %lu, %s: %lu failure(s).\n", g_checks, f ? "FAILED" : "passed", f);
    return f;
}

/* ------------------------------------------------------------------------- */
/* Program                                                                    */
/* ------------------------------------------------------------------------- */

static void usage(FILE *f) {
    fprintf(
        f,
        "usage: proxima_demo [--models DIR] [--steps N] [--reps R] [--verbose] [--help]\n"
        "\n"
        "Runs the numerical experiments of seed 000 (Lin-Canny thesis, section 3.5) with proxima:\n"
        "  (a) two teapot hulls under 1, 5, 10, 20 degrees of relative rotation per step;\n"
        "  (b) polygonised spheres and cylinders of growing resolution, 1 degree per step;\n"
        "  (c) Table 3.1: with vs without initialisation (cubes, cylinders, cones, frustums, Puma links).\n"
        "Each query is timed with tracking (warm cache) and without (cold cache), and every answer is\n"
        "checked against an independent certificate; a few against brute force. Then the newer queries:\n"
        "  (d) Lin-Canny, GJK and hybrid side by side on one motion through contact and overlap;\n"
        "  (e) signed distance (penetration depth); (f) collision translation; (g) px_intersect.\n"
        "\n"
        "  --models DIR  folder with teapot/ and puma560/ (default: models)\n"
        "  --steps N     motion steps per experiment (default 1000, as in the seed)\n"
        "  --reps R      timed repetitions of each query, cache restored before each (default 10)\n"
        "  --verbose     print the poses (hex floats) of every query that needed a safeguard fallback\n"
        "  --help        this text\n"
        "Exit status: 0 when every check passed, 1 when a check failed, 2 on a usage or file error.\n");
}

/* Value of the first "key : value" line of /proc/cpuinfo, or "" . */
static void cpuinfo_field(const char *key, char *out, size_t size) {
    out[0] = '\0';
    FILE *f = fopen("/proc/cpuinfo", "r");
    if (!f) return;
    char line[512];
    size_t klen = strlen(key);
    while (fgets(line, sizeof line, f)) {
        if (strncmp(line, key, klen) == 0) {
            char *p = strchr(line, ':');
            if (p) {
                p++;
                while (*p == ' ' || *p == '\t') p++;
                snprintf(out, size, "%s", p);
                out[strcspn(out, "\n")] = '\0';
            }
            break;
        }
    }
    fclose(f);
}

static void print_machine(int steps, int reps) {
    char model[256], mhz[64], load[64] = "";
    cpuinfo_field("model name", model, sizeof model);
    cpuinfo_field("cpu MHz", mhz, sizeof mhz);
    FILE *f = fopen("/proc/loadavg", "r");
    if (f) {
        if (!fgets(load, sizeof load, f)) load[0] = '\0';
        load[strcspn(load, " ")] = '\0'; /* 1-minute load average */
        fclose(f);
    }
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    printf("machine : %s%s%s%s, %ld logical core(s) online; load average %s at start\n",
           model[0] ? model : "unknown CPU", mhz[0] ? " @ " : "", mhz, mhz[0] ? " MHz" : "", cores,
           load[0] ? load : "unknown");
    printf("build   : proxima %d.%d.%d, %s"
#ifdef __VERSION__
           ", compiler " __VERSION__
#endif
#ifdef NDEBUG
           ", NDEBUG"
#endif
           "\n",
           PX_VERSION_MAJOR, PX_VERSION_MINOR, PX_VERSION_PATCH, sizeof(void *) == 8 ? "64-bit" : "32-bit");
    printf("timing  : CLOCK_MONOTONIC around %d repetitions of each query (cache restored before each),\n"
           "          single thread; per-step time = batch / %d; median and mean over %d steps.\n",
           reps, reps, steps);
    printf("          'track' = cache from the previous step (Lin-Canny coherence); 'cold' = zeroed cache\n"
           "          (proxima's cold start: a line-of-centres or GJK seed, then the walk). Times in us.\n");
}

static int file_exists(const char *path) {
    FILE *f = fopen(path, "rb");
    if (!f) return 0;
    fclose(f);
    return 1;
}

static px_convex *load_or_die(const char *dir, const char *rel) {
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, rel);
    px_error err;
    px_convex *c = px_convex_create_from_file(path, NULL, &err);
    if (!c) {
        fprintf(stderr, "proxima_demo: %s (%s)\n", err.message, px_status_string(err.code));
        exit(2);
    }
    return c;
}

static int parse_int(const char *s, int lo, int hi, int *out) {
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (errno || end == s || *end || v < lo || v > hi) return 0;
    *out = (int)v;
    return 1;
}

static const char *k_teapot_obj = "teapot/mcguire_cc0/teapot.obj";
static const char *k_teapot_stl = "teapot/trimesh_mit/teapot.stl";
static const char *k_puma_stl = "puma560/nimasarli_puma560_description/meshes/puma_link2.stl";
static const char *k_puma_dae = "puma560/rtb_puma560_description/meshes/puma560_link3.dae";

int main(int argc, char **argv) {
    const char *models = "models";
    run_opts opts = {1000, 10, 0};
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            usage(stdout);
            return 0;
        } else if (!strcmp(argv[i], "--verbose")) {
            g_verbose = 1;
        } else if (!strcmp(argv[i], "--models") && i + 1 < argc) {
            models = argv[++i];
        } else if (!strcmp(argv[i], "--steps") && i + 1 < argc) {
            if (!parse_int(argv[++i], 10, 100000000, &opts.steps)) {
                fprintf(stderr, "proxima_demo: --steps wants an integer in [10, 1e8], got '%s'\n", argv[i]);
                return 2;
            }
        } else if (!strcmp(argv[i], "--reps") && i + 1 < argc) {
            if (!parse_int(argv[++i], 1, 1000000, &opts.reps)) {
                fprintf(stderr, "proxima_demo: --reps wants an integer in [1, 1e6], got '%s'\n", argv[i]);
                return 2;
            }
        } else {
            fprintf(stderr, "proxima_demo: unknown or incomplete argument '%s'\n\n", argv[i]);
            usage(stderr);
            return 2;
        }
    }
    /* Fail early and clearly if a model is missing. */
    const char *needed[] = {k_teapot_obj, k_teapot_stl, k_puma_stl, k_puma_dae};
    for (size_t i = 0; i < sizeof needed / sizeof *needed; ++i) {
        char path[1024];
        snprintf(path, sizeof path, "%s/%s", models, needed[i]);
        if (!file_exists(path)) {
            fprintf(stderr,
                    "proxima_demo: model file '%s' is missing (%s); run from the repository root or pass "
                    "--models DIR\n",
                    path, strerror(errno));
            return 2;
        }
    }

    printf("proxima demo: seed 000 (Lin-Canny thesis) section 3.5 experiments\n");
    print_machine(opts.steps, opts.reps);

    /* ---------------------------------------------------------------- (a) */
    body tea[2];
    if (!body_init(&tea[0], "teapot.obj hull", load_or_die(models, k_teapot_obj))) return 1;
    if (!body_init(&tea[1], "teapot.stl hull", load_or_die(models, k_teapot_stl))) return 1;
    printf("\n(a) Two teapot hulls, relative rotation of 1, 5, 10, 20 degrees per step plus small "
           "displacements\n");
    printf("    seed: hulls of 1047 vertices, 3135 edges, 2090 faces each (the seed's teapot model).\n");
    for (int t = 0; t < 2; ++t)
        printf("    ours: %-16s %4u vertices, %4u edges, %4u faces, %zu bytes (%.0f B/vertex)  from %s\n",
               tea[t].name, tea[t].nv, tea[t].ne, tea[t].nf, px_convex_memory_bytes(tea[t].c),
               (double)px_convex_memory_bytes(tea[t].c) / tea[t].nv, t == 0 ? k_teapot_obj : k_teapot_stl);
    printf(
        "    Motion: each body spins about the axis (1,2,3)/sqrt(14) through its centre, in opposite senses\n"
        "    (relative rotation = the step angle); centres R_A + R_B + 10%% of R apart (bounding spheres\n"
        "    disjoint), plus a displacement of amplitude 40%% of that gap whose phase advances with the\n"
        "    rotation. Two copies of the same hull per row.\n");
    printf("\n    %-7s %-11s %9s %9s %9s %9s %8s %8s  %s\n", "model", "deg/step", "track med", "track avg",
           "cold med", "cold avg", "chg trk", "chg cold", "seed (1993, SGI Indigo2)");
    const double seed_us[4] = {50, 61, 100, 150};
    const int degs[4] = {1, 5, 10, 20};
    for (int t = 0; t < 2; ++t) {
        for (int d = 0; d < 4; ++d) {
            double gap = 0.05 * (tea[t].radius * 2);
            pg_spin m = spin_motion(&tea[t], &tea[t], degs[d] * DEMO_PI / 180.0, gap, 0.4 * gap);
            run_stats s = run_pair(&tea[t], &tea[t], &m, &opts, d == 0 ? 2 : 1);
            printf("    %-7s %-11d %9.3f %9.3f %9.3f %9.3f %8.2f %8.2f  ~%.0f us\n", t == 0 ? "obj" : "stl",
                   degs[d], s.warm_med, s.warm_mean, s.cold_med, s.cold_mean, s.warm_iter, s.cold_iter,
                   seed_us[d]);
            print_fallbacks(&s);
        }
    }
    printf("    'chg' = mean feature-pair changes per query (px_distance_result.diag.iterations); med/avg = "
           "median/mean.\n");

    /* ---------------------------------------------------------------- (b) */
    printf(
        "\n(b) Polygonised spheres and cylinders of growing resolution (seed Fig. 3.12), 1 degree per step,\n"
        "    two copies of each shape, no displacement. Seed: 50-70 us per query, roughly constant.\n");
    printf("\n    %-22s %7s %9s %9s %9s %9s %8s %8s\n", "shape (each body)", "total V", "track med",
           "track avg", "cold med", "cold avg", "chg trk", "chg cold");
    const int sph[][2] = {{3, 4}, {4, 6}, {6, 8}, {8, 12}, {10, 20}, {16, 30}, {22, 44}, {32, 64}};
    const int cyl[] = {6, 12, 20, 24, 48, 120, 250, 500, 1000};
    for (int kind = 0; kind < 2; ++kind) {
        int count = kind == 0 ? (int)(sizeof sph / sizeof *sph) : (int)(sizeof cyl / sizeof *cyl);
        for (int i = 0; i < count; ++i) {
            char name[64];
            px_convex *c;
            if (kind == 0) {
                snprintf(name, sizeof name, "sphere %dx%d", sph[i][0], sph[i][1]);
                c = make_sphere(sph[i][0], sph[i][1], 1.0);
            } else {
                snprintf(name, sizeof name, "cylinder %d facets", cyl[i]);
                c = make_frustum(cyl[i], 1.0, 1.0, 2.0);
            }
            body bb;
            if (!body_init(&bb, name, c)) return 1;
            pg_spin m = spin_motion(&bb, &bb, DEMO_PI / 180.0, 0.1 * bb.radius, 0.0);
            run_stats s = run_pair(&bb, &bb, &m, &opts, brute_budget(&bb, &bb));
            printf("    %-22s %7u %9.3f %9.3f %9.3f %9.3f %8.2f %8.2f\n", name, 2 * bb.nv, s.warm_med,
                   s.warm_mean, s.cold_med, s.cold_mean, s.warm_iter, s.cold_iter);
            print_fallbacks(&s);
            px_convex_destroy(c);
        }
    }

    /* ---------------------------------------------------------------- (c) */
    printf(
        "\n(c) With vs without initialisation (seed Table 3.1), 1 degree per step.\n"
        "    'track' starts from the previous closest pair (seed: w/ Init); 'random' starts from a random\n"
        "    feature pair of each body (seed: w/o Init, arbitrary initial features); 'cold' is a zeroed\n"
        "    cache (proxima's cold start). Primitives are scaled to the Puma link's size in its rows.\n");
    body puma[2];
    if (!body_init(&puma[0], "Puma link 2 (STL, in)", load_or_die(models, k_puma_stl))) return 1;
    if (!body_init(&puma[1], "Puma link 3 (DAE, m)", load_or_die(models, k_puma_dae))) return 1;
    printf(
        "    Puma links (px_convex_create_from_file): link2.stl hull %u V / %u E / %u F (inches) from %s;\n"
        "    link3.dae hull %u V / %u E / %u F (metres) from %s.\n",
        puma[0].nv, puma[0].ne, puma[0].nf, k_puma_stl, puma[1].nv, puma[1].ne, puma[1].nf, k_puma_dae);
    printf("\n    %-34s %17s %9s %10s %9s %7s %7s %7s\n", "pair (A / B)", "M1 + M2 = N", "track med",
           "random med", "cold med", "chg trk", "chg rnd", "chg cld");
    struct {
        const char *na, *nb;
        int kind_a, kind_b, n_a,
            n_b; /* kind: 0 cube, 1 cylinder, 2 cone, 3 frustum, 4 puma stl, 5 puma dae */
    } rows[] = {
        {"cube", "cube", 0, 0, 4, 4},
        {"cylinder 12", "cone 12", 1, 2, 12, 12},
        {"cone 20", "frustum 20", 2, 3, 20, 20},
        {"cylinder 24", "frustum 24", 1, 3, 24, 24},
        {"frustum 48", "cone 20", 3, 2, 48, 20},
        {"cylinder 48", "cylinder 24", 1, 1, 48, 24},
        {"cone 120", "frustum 120", 2, 3, 120, 120},
        {"cylinder 120", "cube", 1, 0, 120, 4},
        {"Puma link2.stl", "cylinder 48", 4, 1, 0, 48},
        {"Puma link2.stl", "Puma link2.stl", 4, 4, 0, 0},
        {"Puma link3.dae", "frustum 24", 5, 3, 0, 24},
        {"Puma link3.dae", "link2.stl scaled", 5, 4, 0, 0},
    };
    run_opts copts = opts;
    copts.random_start = 1;
    for (size_t i = 0; i < sizeof rows / sizeof *rows; ++i) {
        body bd[2];
        px_convex *made[2] = {NULL, NULL};
        int kinds[2] = {rows[i].kind_a, rows[i].kind_b}, ns[2] = {rows[i].n_a, rows[i].n_b};
        const char *names[2] = {rows[i].na, rows[i].nb};
        /* Size of the primitives: the Puma link's radius when the row has one, else 1. */
        double size = 1.0;
        if (kinds[0] >= 4) size = puma[kinds[0] - 4].radius;
        for (int j = 0; j < 2; ++j) {
            if (kinds[j] >= 4) {
                bd[j] = puma[kinds[j] - 4];
                if (j == 1 && kinds[0] >= 4 && kinds[0] != kinds[j]) {
                    /* Two different Puma files in different units: rescale B's hull to A's size. */
                    double f = size / bd[j].radius;
                    uint32_t nv = bd[j].nv;
                    double *p = malloc(3 * (size_t)nv * sizeof *p);
                    if (!p) return 2;
                    for (uint32_t v = 0; v < nv; ++v) {
                        px_vec3 q = vscale(vertex_of(bd[j].c, v), f);
                        p[3 * v] = q.x, p[3 * v + 1] = q.y, p[3 * v + 2] = q.z;
                    }
                    made[j] = from_points_or_die(names[j], p, nv);
                    free(p);
                    if (!body_init(&bd[j], names[j], made[j])) return 1;
                }
                snprintf(bd[j].name, sizeof bd[j].name, "%s", names[j]);
                continue;
            }
            switch (kinds[j]) {
            case 0: made[j] = make_box(1.4 * size, 1.4 * size, 1.4 * size); break;
            case 1: made[j] = make_frustum(ns[j], size, size, 2 * size); break;
            case 2: made[j] = make_frustum(ns[j], size, 0, 2 * size); break;
            default: made[j] = make_frustum(ns[j], size, 0.5 * size, 2 * size); break;
            }
            if (!body_init(&bd[j], names[j], made[j])) return 1;
        }
        pg_spin m = spin_motion(&bd[0], &bd[1], DEMO_PI / 180.0, 0.05 * (bd[0].radius + bd[1].radius), 0.0);
        run_stats s = run_pair(&bd[0], &bd[1], &m, &copts, brute_budget(&bd[0], &bd[1]));
        char pair[80], mn[40];
        snprintf(pair, sizeof pair, "%s / %s", rows[i].na, rows[i].nb);
        snprintf(mn, sizeof mn, "%u + %u = %u", bd[0].nv, bd[1].nv, bd[0].nv + bd[1].nv);
        printf("    %-34s %17s %9.3f %10.3f %9.3f %7.2f %7.2f %7.2f\n", pair, mn, s.warm_med, s.rand_med,
               s.cold_med, s.warm_iter, s.rand_iter, s.cold_iter);
        print_fallbacks(&s);
        for (int j = 0; j < 2; ++j) px_convex_destroy(made[j]);
    }
    printf(
        "    Seed Table 3.1 (Lisp on a Sun4 SPARCstation, milliseconds, average of 50 trials x 18 starts):\n"
        "      69 vertices (48 + 21): w/o Init 41 ms, w/ Init 3.5 ms; 144 vertices (96 + 48): 67 ms, 3.0 "
        "ms.\n"
        "      The thesis puts its C code at about 10x the Lisp speed (~50-70 us per tracked query).\n");

    /* ------------------------------------------------------------ sanity */
    unsigned long failures = g_sanity.certificate_failures + g_sanity.brute_failures +
                             g_sanity.agreement_failures + g_sanity.query_errors;
    printf("\nsanity: %lu answers certified from vertices and face planes (worst violation %.2g x scale),\n"
           "        %lu answers compared with brute force over all vertex-face and edge-edge pairs (worst\n"
           "        difference %.2g x scale), tracking/cold/random-start distances compared at every step;\n"
           "        tolerance %.0e x (R_A + R_B + centre distance). %s: %lu failure(s).\n",
           g_sanity.certificates, g_sanity.worst_cert_rel, g_sanity.brute, g_sanity.worst_brute_rel,
           DEMO_REL_TOL, failures ? "FAILED" : "passed", failures);
    printf("        safeguard fallbacks in all queries: %lu (answers still certified; expected 0).\n",
           g_fallbacks_total);

    unsigned long new_failures = run_new_sections(models, tea, puma, &opts);

    for (int t = 0; t < 2; ++t) px_convex_destroy(tea[t].c);
    for (int t = 0; t < 2; ++t) px_convex_destroy(puma[t].c);
    return failures || new_failures ? 1 : 0;
}
