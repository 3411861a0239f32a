/* Separating-axis oracles for penetration depth and collision translation;
 * see oracle_sat.h. Written independently of src/: only px_vec3, px_pose and
 * the public px_convex accessors. */
#include "access.h"
#include "oracle_sat.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "oracle_vec.h"

int os_prune = 1;

static void *xcalloc(size_t n, size_t s) {
    void *p = calloc(n ? n : 1, s);
    if (!p) {
        fprintf(stderr, "oracle_sat: out of memory\n");
        abort();
    }
    return p;
}

/* ---------------------------------------------------------------- shapes */

typedef struct half_edge {
    uint32_t lo, hi, face;
} half_edge;

static int cmp_half_edge(const void *x, const void *y) {
    const half_edge *a = x, *b = y;
    if (a->lo != b->lo) return a->lo < b->lo ? -1 : 1;
    if (a->hi != b->hi) return a->hi < b->hi ? -1 : 1;
    return a->face < b->face ? -1 : (a->face > b->face);
}

int os_shape_init(os_shape *s, const px_convex *c) {
    memset(s, 0, sizeof *s);
    s->c = c;
    s->nv = px_convex_vertex_count(c);
    s->nf = px_convex_face_count(c);
    s->v = xcalloc(s->nv, sizeof *s->v);
    s->fn = xcalloc(s->nf, sizeof *s->fn);
    s->fd = xcalloc(s->nf, sizeof *s->fd);
    px_vec3 mean = v3(0, 0, 0);
    for (uint32_t i = 0; i < s->nv; ++i) {
        s->v[i] = ta_vertex(c, i);
        mean = add(mean, s->v[i]);
        double l = len(s->v[i]);
        if (l > s->radius) s->radius = l;
    }
    s->mean = mul(mean, 1.0 / (double)(s->nv ? s->nv : 1));
    size_t nh = 0;
    for (uint32_t f = 0; f < s->nf; ++f) nh += ta_face_size(c, f);
    half_edge *h = xcalloc(nh, sizeof *h);
    size_t k = 0;
    for (uint32_t f = 0; f < s->nf; ++f) {
        uint32_t n = ta_face_size(c, f);
        if (n < 3) {
            fprintf(stderr, "oracle_sat: face %u has %u vertices\n", f, n);
            free(h);
            return -1;
        }
        /* Newell's method about the face centroid, in the body frame, where
         * the coordinates are the exact hull vertices. */
        px_vec3 cen = v3(0, 0, 0);
        for (uint32_t q = 0; q < n; ++q) cen = add(cen, s->v[ta_face_vertex(c, f, q)]);
        cen = mul(cen, 1.0 / (double)n);
        px_vec3 nn = v3(0, 0, 0);
        for (uint32_t q = 0; q < n; ++q) {
            uint32_t u = ta_face_vertex(c, f, q), w = ta_face_vertex(c, f, (q + 1) % n);
            nn = add(nn, cross(sub(s->v[u], cen), sub(s->v[w], cen)));
            h[k].lo = u < w ? u : w;
            h[k].hi = u < w ? w : u;
            h[k].face = f;
            ++k;
        }
        double l = len(nn);
        if (!(l > 0)) {
            fprintf(stderr, "oracle_sat: face %u has no normal\n", f);
            free(h);
            return -1;
        }
        nn = mul(nn, 1.0 / l);
        /* CCW seen from outside gives the outward normal; the check against
         * the vertex mean only guards against a mis-wound loop. */
        if (dot(nn, sub(cen, s->mean)) < 0) nn = mul(nn, -1.0);
        s->fn[f] = nn;
        double off = 0;
        for (uint32_t q = 0; q < n; ++q) off += dot(nn, s->v[ta_face_vertex(c, f, q)]);
        s->fd[f] = off / (double)n;
    }
    /* Every edge is the shared side of exactly two face loops. */
    qsort(h, nh, sizeof *h, cmp_half_edge);
    s->ne = (uint32_t)(nh / 2);
    s->ev = xcalloc(2 * (size_t)s->ne, sizeof *s->ev);
    s->ef = xcalloc(2 * (size_t)s->ne, sizeof *s->ef);
    int ok = nh % 2 == 0 && s->ne == px_convex_edge_count(c);
    for (uint32_t e = 0; ok && e < s->ne; ++e) {
        const half_edge *x = &h[2 * e], *y = &h[2 * e + 1];
        ok = x->lo == y->lo && x->hi == y->hi && x->face != y->face &&
             (2 * e + 2 >= nh || h[2 * e + 2].lo != x->lo || h[2 * e + 2].hi != x->hi);
        s->ev[2 * e] = x->lo, s->ev[2 * e + 1] = x->hi;
        s->ef[2 * e] = x->face, s->ef[2 * e + 1] = y->face;
    }
    free(h);
    if (!ok) fprintf(stderr, "oracle_sat: the face loops are not a closed 2-manifold\n");
    return ok ? 0 : -1;
}

void os_shape_free(os_shape *s) {
    free(s->v);
    free(s->fn);
    free(s->fd);
    free(s->ev);
    free(s->ef);
    memset(s, 0, sizeof *s);
}

/* ------------------------------------------------------- the shifted frame */

/* Both bodies in world orientation, translated so that the centre of the
 * smaller one is the origin: rounding is then relative to the pair's size. */
typedef struct frame {
    px_vec3 origin;
    px_vec3 *va, *vb;   /* vertices */
    px_vec3 *na, *nb;   /* face normals (world orientation) */
    px_vec3 *ea, *eb;   /* edge vectors */
    px_vec3 *bxa, *dxc; /* per edge: normal of its Gauss arc's great circle */
} frame;

static void frame_init(frame *fr, const os_shape *a, const px_pose *pa, const os_shape *b,
                       const px_pose *pb) {
    const os_shape *small = a->radius <= b->radius ? a : b;
    const px_pose *ps = small == a ? pa : pb;
    fr->origin = add(rot(ps->r, small->mean), ps->t);
    px_vec3 sa = sub(pa->t, fr->origin), sb = sub(pb->t, fr->origin);
    fr->va = xcalloc(a->nv, sizeof *fr->va);
    fr->vb = xcalloc(b->nv, sizeof *fr->vb);
    fr->na = xcalloc(a->nf, sizeof *fr->na);
    fr->nb = xcalloc(b->nf, sizeof *fr->nb);
    fr->ea = xcalloc(a->ne, sizeof *fr->ea);
    fr->eb = xcalloc(b->ne, sizeof *fr->eb);
    fr->bxa = xcalloc(a->ne, sizeof *fr->bxa);
    fr->dxc = xcalloc(b->ne, sizeof *fr->dxc);
    for (uint32_t i = 0; i < a->nv; ++i) fr->va[i] = add(rot(pa->r, a->v[i]), sa);
    for (uint32_t i = 0; i < b->nv; ++i) fr->vb[i] = add(rot(pb->r, b->v[i]), sb);
    for (uint32_t f = 0; f < a->nf; ++f) fr->na[f] = rot(pa->r, a->fn[f]);
    /* -B's Gauss map: B's normals negated. */
    for (uint32_t f = 0; f < b->nf; ++f) fr->nb[f] = mul(rot(pb->r, b->fn[f]), -1.0);
    for (uint32_t e = 0; e < a->ne; ++e) {
        /* Edge vectors from the rotated body-frame difference: no cancellation
         * against the translation. */
        fr->ea[e] = rot(pa->r, sub(a->v[a->ev[2 * e + 1]], a->v[a->ev[2 * e]]));
        fr->bxa[e] = cross(fr->na[a->ef[2 * e + 1]], fr->na[a->ef[2 * e]]);
    }
    for (uint32_t e = 0; e < b->ne; ++e) {
        fr->eb[e] = rot(pb->r, sub(b->v[b->ev[2 * e + 1]], b->v[b->ev[2 * e]]));
        fr->dxc[e] = cross(fr->nb[b->ef[2 * e + 1]], fr->nb[b->ef[2 * e]]);
    }
}

static void frame_free(frame *fr) {
    free(fr->va);
    free(fr->vb);
    free(fr->na);
    free(fr->nb);
    free(fr->ea);
    free(fr->eb);
    free(fr->bxa);
    free(fr->dxc);
}

/* h_K(n) = max_a a.n - min_b b.n by brute force. */
static double support_diff(const px_vec3 *va, uint32_t na, const px_vec3 *vb, uint32_t nb, px_vec3 n) {
    double ma = -DBL_MAX, mb = DBL_MAX;
    for (uint32_t i = 0; i < na; ++i) {
        double x = dot(va[i], n);
        if (x > ma) ma = x;
    }
    for (uint32_t i = 0; i < nb; ++i) {
        double x = dot(vb[i], n);
        if (x < mb) mb = x;
    }
    return ma - mb;
}

/* Gauss-map arcs (a, b) of an edge of A and (c, d) of an edge of -B cross
 * (Gregorius 2013): c and d on opposite sides of the plane of (a, b), a and b
 * on opposite sides of the plane of (c, d), and the same hemisphere. The
 * slack keeps arcs that touch or nearly touch: a false "cross" only adds an
 * axis, a false "miss" could drop a facet. */
static int arcs_cross(px_vec3 a, px_vec3 b, px_vec3 bxa, px_vec3 c, px_vec3 d, px_vec3 dxc) {
    const double slack = 1e-12;
    double cba = dot(c, bxa), dba = dot(d, bxa), adc = dot(a, dxc), bdc = dot(b, dxc);
    return cba * dba < slack && adc * bdc < slack && cba * bdc > -slack;
}

/* Calls visit(ctx, n) for every candidate facet normal of K = A - B. */
typedef void (*axis_fn)(void *ctx, px_vec3 n);

static uint32_t for_each_axis(const frame *fr, const os_shape *a, const os_shape *b, axis_fn visit,
                              void *ctx) {
    uint32_t count = 0;
    for (uint32_t f = 0; f < a->nf; ++f, ++count) visit(ctx, fr->na[f]);
    for (uint32_t f = 0; f < b->nf; ++f, ++count) visit(ctx, fr->nb[f]);
    for (uint32_t i = 0; i < a->ne; ++i) {
        px_vec3 u1 = fr->na[a->ef[2 * i]], u2 = fr->na[a->ef[2 * i + 1]];
        double la = len(fr->ea[i]);
        for (uint32_t j = 0; j < b->ne; ++j) {
            if (os_prune &&
                !arcs_cross(u1, u2, fr->bxa[i], fr->nb[b->ef[2 * j]], fr->nb[b->ef[2 * j + 1]], fr->dxc[j]))
                continue;
            px_vec3 cr = cross(fr->ea[i], fr->eb[j]);
            double l = len(cr);
            if (!(l > 1e-14 * la * len(fr->eb[j]))) continue;
            px_vec3 n = mul(cr, 1.0 / l);
            visit(ctx, n);
            visit(ctx, mul(n, -1.0));
            count += 2;
        }
    }
    return count;
}

/* ----------------------------------------------------------- penetration */

typedef struct pen_ctx {
    const frame *fr;
    uint32_t na, nb;
    double best;
    px_vec3 normal;
} pen_ctx;

static void pen_visit(void *p, px_vec3 n) {
    pen_ctx *c = p;
    double h = support_diff(c->fr->va, c->na, c->fr->vb, c->nb, n);
    if (h < c->best) c->best = h, c->normal = n;
}

void os_penetration(const os_shape *a, const px_pose *pa, const os_shape *b, const px_pose *pb,
                    os_pen_result *out) {
    frame fr;
    frame_init(&fr, a, pa, b, pb);
    pen_ctx c = {&fr, a->nv, b->nv, DBL_MAX, v3(0, 0, 1)};
    out->axes = for_each_axis(&fr, a, b, pen_visit, &c);
    out->depth = c.best;
    out->normal = c.normal;
    out->separated = c.best < 0;
    out->origin = fr.origin;
    frame_free(&fr);
}

double os_support_diff(const os_shape *a, const px_pose *pa, const os_shape *b, const px_pose *pb,
                       px_vec3 n) {
    /* h_K(n) does not depend on the origin; shift anyway for accuracy. */
    const os_shape *small = a->radius <= b->radius ? a : b;
    const px_pose *ps = small == a ? pa : pb;
    px_vec3 o = add(rot(ps->r, small->mean), ps->t);
    px_vec3 sa = sub(pa->t, o), sb = sub(pb->t, o);
    double ma = -DBL_MAX, mb = DBL_MAX;
    for (uint32_t i = 0; i < a->nv; ++i) {
        double x = dot(add(rot(pa->r, a->v[i]), sa), n);
        if (x > ma) ma = x;
    }
    for (uint32_t i = 0; i < b->nv; ++i) {
        double x = dot(add(rot(pb->r, b->v[i]), sb), n);
        if (x < mb) mb = x;
    }
    return ma - mb;
}

double os_boundary_offset(const os_shape *s, const px_pose *pose, px_vec3 p) {
    px_vec3 q = rot_t(pose->r, sub(p, pose->t));
    double m = -DBL_MAX;
    for (uint32_t f = 0; f < s->nf; ++f) {
        double x = dot(s->fn[f], q) - s->fd[f];
        if (x > m) m = x;
    }
    return m;
}

/* ----------------------------------------------------------- translation */

/* A + tau u touches B  <=>  tau u in K' = B - A = -K. For a facet normal m
 * of K the facet normal of K' is -m with the same support value h_K(m), so
 * the constraint is  -tau (m . u) <= h_K(m). */
typedef struct tr_ctx {
    const frame *fr;
    uint32_t na, nb;
    px_vec3 u;
    double lo, hi; /* tau interval (units of u) */
    int infeasible;
    px_vec3 normal;
} tr_ctx;

static void tr_visit(void *p, px_vec3 m) {
    tr_ctx *c = p;
    double h = support_diff(c->fr->va, c->na, c->fr->vb, c->nb, m);
    double s = -dot(m, c->u);
    /* |s| <= 1e-13: the facet is parallel to the line (to rounding); its
     * constraint is 0 <= h, and a non-parallel reading would only bound tau
     * beyond |h| / 1e-13, far outside any tested range. */
    if (s > 1e-13) {
        double t = h / s;
        if (t < c->hi) c->hi = t;
    } else if (s < -1e-13) {
        double t = h / s;
        if (t > c->lo) c->lo = t, c->normal = m;
    } else if (h < 0) {
        c->infeasible = 1;
    }
}

void os_translation(const os_shape *a, const px_pose *pa, const os_shape *b, const px_pose *pb, px_vec3 d,
                    os_tr_result *out) {
    memset(out, 0, sizeof *out);
    /* Unit direction without overflow or underflow: scale by a power of two
     * (exact) to max-norm in [1, 2), then normalise. tau for d is then
     * tau_u * k / |k d|. */
    double m = fmax(fabs(d.x), fmax(fabs(d.y), fabs(d.z)));
    if (!(m > 0) || !isfinite(m)) return;
    double k = ldexp(1.0, -ilogb(m));
    px_vec3 dk = mul(d, k);
    double L = len(dk);
    px_vec3 u = mul(dk, 1.0 / L);
    frame fr;
    frame_init(&fr, a, pa, b, pb);
    tr_ctx c = {&fr, a->nv, b->nv, u, -DBL_MAX, DBL_MAX, 0, v3(0, 0, 0)};
    out->axes = for_each_axis(&fr, a, b, tr_visit, &c);
    out->hit = !c.infeasible && c.lo <= c.hi;
    /* The shifted origin is not A's or B's reference: tau is a translation,
     * independent of it. */
    if (out->hit) {
        out->tau_min = c.lo / L * k;
        out->tau_max = c.hi / L * k;
        out->normal = c.normal;
    }
    /* Perpendicular gap over the projected edge normals of A and B. */
    double gap = -DBL_MAX;
    px_vec3 gn = v3(0, 0, 0);
    for (int body = 0; body < 2; ++body) {
        const px_vec3 *e = body ? fr.eb : fr.ea;
        uint32_t ne = body ? b->ne : a->ne;
        for (uint32_t i = 0; i < ne; ++i) {
            px_vec3 cr = cross(u, e[i]);
            double l = len(cr);
            if (!(l > 1e-12 * len(e[i]))) continue; /* parallel to d: projects to a point */
            px_vec3 n = mul(cr, 1.0 / l);
            for (int sgn = 0; sgn < 2; ++sgn, n = mul(n, -1.0)) {
                double g = -support_diff(fr.va, a->nv, fr.vb, b->nv, n);
                if (g > gap) gap = g, gn = n;
            }
        }
    }
    out->gap = gap;
    out->gap_normal = gn;
    frame_free(&fr);
}
