/* Brute-force distance and intersection oracle; see oracle.h.
 * Written independently of src/narrow (it shares no code with the library's
 * queries; only px_vec3 and the public accessors). */
#include "access.h"
#include "oracle.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "oracle_vec.h"

static double dist(px_vec3 a, px_vec3 b) { return len(sub(a, b)); }
/* a + t (b - a), evaluated from the nearer end for accuracy. */
static px_vec3 lerp(px_vec3 a, px_vec3 b, double t) {
    px_vec3 d = sub(b, a);
    return t <= 0.5 ? add(a, mul(d, t)) : sub(b, mul(d, 1.0 - t));
}

/* Lower-bound pruning: a pair whose bounding spheres are farther apart than
 * the best distance so far (with a relative slack) cannot be the minimum. */
static int prune(double lb, double best) { return lb > best * (1.0 + 1e-9) + 1e-300; }

/* ---------------------------------------------------------------- building */

static void *xcalloc(size_t n, size_t s) {
    void *p = calloc(n ? n : 1, s);
    if (!p) {
        fprintf(stderr, "oracle: out of memory\n");
        abort();
    }
    return p;
}

/* Planes, bounding spheres: shared by both constructors once v, ev, faces are
 * set. Face normals are computed from the body-frame vertices `vb` (when
 * given) and rotated by T: a sliver face that is axis-aligned in its body
 * frame keeps an exact normal instead of losing eps * length / width to
 * cancellation in the rotated coordinates. */
static int finish_init(or_poly *p, const px_vec3 *vb, const px_pose *T) {
    p->fn = xcalloc(p->nf, sizeof *p->fn);
    p->fw = xcalloc(p->nf, sizeof *p->fw);
    p->fdeg = xcalloc(p->nf, 1);
    p->fd = xcalloc(p->nf, sizeof *p->fd);
    p->fc = xcalloc(p->nf, sizeof *p->fc);
    p->fr = xcalloc(p->nf, sizeof *p->fr);
    p->ec = xcalloc(p->ne, sizeof *p->ec);
    p->er = xcalloc(p->ne, sizeof *p->er);
    for (uint32_t f = 0; f < p->nf; ++f) {
        uint32_t b = p->f_first[f], n = p->f_first[f + 1] - b;
        if (n < 3) {
            fprintf(stderr, "oracle: face %u has %u vertices\n", f, n);
            return -1;
        }
        px_vec3 c = v3(0, 0, 0);
        for (uint32_t k = 0; k < n; ++k) c = add(c, p->v[p->f_vert[b + k]]);
        c = mul(c, 1.0 / (double)n);
        /* Newell's method about the centroid: robust normal of a planar polygon. */
        const px_vec3 *src = vb ? vb : p->v;
        px_vec3 cb = v3(0, 0, 0);
        for (uint32_t k = 0; k < n; ++k) cb = add(cb, src[p->f_vert[b + k]]);
        cb = mul(cb, 1.0 / (double)n);
        px_vec3 nn = v3(0, 0, 0);
        for (uint32_t k = 0; k < n; ++k) {
            px_vec3 a = sub(src[p->f_vert[b + k]], cb), bb = sub(src[p->f_vert[b + (k + 1) % n]], cb);
            nn = add(nn, cross(a, bb));
        }
        if (vb && T)
            nn = v3(T->r[0] * nn.x + T->r[1] * nn.y + T->r[2] * nn.z,
                    T->r[3] * nn.x + T->r[4] * nn.y + T->r[5] * nn.z,
                    T->r[6] * nn.x + T->r[7] * nn.y + T->r[8] * nn.z);
        /* Normalise without overflow (coordinates up to ~1e300 square to inf). */
        double mx = fmax(fabs(nn.x), fmax(fabs(nn.y), fabs(nn.z)));
        if (mx > 0) nn = mul(nn, 1.0 / mx);
        double l = len(nn);
        if (!(mx > 0) || !(l > 0)) {
            /* A face collapsed by rounding (a tiny body mapped far from the
             * origin): no plane. Distances still come from its edges and
             * vertices; containment in this body is not tested. */
            p->fdeg[f] = 1;
            p->degenerate++;
            l = 1;
        }
        nn = mul(nn, 1.0 / l);
        double d = 0, r = 0;
        for (uint32_t k = 0; k < n; ++k) {
            px_vec3 q = p->v[p->f_vert[b + k]];
            d += dot(nn, q);
            double rq = dist(q, c);
            if (rq > r) r = rq;
        }
        p->fw[f] = nn;
        p->fn[f] = nn;
        p->fd[f] = d / (double)n;
        p->fc[f] = c;
        p->fr[f] = r;
    }
    px_vec3 c = v3(0, 0, 0);
    for (uint32_t i = 0; i < p->nv; ++i) c = add(c, p->v[i]);
    p->center = mul(c, 1.0 / (double)p->nv);
    p->radius = 0;
    for (uint32_t i = 0; i < p->nv; ++i) {
        double r = dist(p->v[i], p->center);
        if (r > p->radius) p->radius = r;
    }
    /* Orient the planes outward from the vertex centroid (an interior point)
     * whatever the winding of the face loops: the oracle does not trust the
     * library's orientation (test_convex checks it separately). */
    for (uint32_t f = 0; f < p->nf; ++f)
        if (!p->fdeg[f] && dot(p->fn[f], p->center) - p->fd[f] > 0)
            p->fn[f] = mul(p->fn[f], -1.0), p->fd[f] = -p->fd[f];
    for (uint32_t e = 0; e < p->ne; ++e) {
        px_vec3 a = p->v[p->ev[2 * e]], b = p->v[p->ev[2 * e + 1]];
        p->ec[e] = mul(add(a, b), 0.5);
        p->er[e] = 0.5 * dist(a, b);
    }
    return 0;
}

int or_poly_init(or_poly *p, const px_convex *c, const px_pose *T) {
    memset(p, 0, sizeof *p);
    p->nv = px_convex_vertex_count(c);
    p->ne = px_convex_edge_count(c);
    p->nf = px_convex_face_count(c);
    if (p->nv < 4 || p->nf < 4 || p->ne < 6) {
        fprintf(stderr, "oracle: polytope with V=%u E=%u F=%u\n", p->nv, p->ne, p->nf);
        return -1;
    }
    p->v = xcalloc(p->nv, sizeof *p->v);
    px_vec3 *vb = xcalloc(p->nv, sizeof *vb);
    p->body_radius = 0;
    for (uint32_t i = 0; i < p->nv; ++i) {
        px_vec3 q = ta_vertex(c, i);
        vb[i] = q;
        double r = len(q);
        if (r > p->body_radius) p->body_radius = r;
        if (T) {
            /* R q + t, row-major R */
            q = v3(T->r[0] * q.x + T->r[1] * q.y + T->r[2] * q.z + T->t.x,
                   T->r[3] * q.x + T->r[4] * q.y + T->r[5] * q.z + T->t.y,
                   T->r[6] * q.x + T->r[7] * q.y + T->r[8] * q.z + T->t.z);
        }
        p->v[i] = q;
    }
    p->ev = xcalloc(2 * (size_t)p->ne, sizeof *p->ev);
    for (uint32_t e = 0; e < p->ne; ++e) {
        uint32_t ab[2];
        if (!(px_convex_edge(c, e, ab) == PX_OK) || ab[0] >= p->nv || ab[1] >= p->nv) {
            fprintf(stderr, "oracle: bad edge %u\n", e);
            free(vb);
            return -1;
        }
        p->ev[2 * e] = ab[0];
        p->ev[2 * e + 1] = ab[1];
    }
    p->f_first = xcalloc(p->nf + 1, sizeof *p->f_first);
    size_t total = 0;
    for (uint32_t f = 0; f < p->nf; ++f) total += ta_face_size(c, f);
    p->f_vert = xcalloc(total, sizeof *p->f_vert);
    uint32_t k = 0;
    for (uint32_t f = 0; f < p->nf; ++f) {
        p->f_first[f] = k;
        uint32_t n = ta_face_size(c, f);
        for (uint32_t j = 0; j < n; ++j) {
            uint32_t vi = ta_face_vertex(c, f, j);
            if (vi >= p->nv) {
                fprintf(stderr, "oracle: bad face vertex %u of face %u\n", vi, f);
                free(vb);
                return -1;
            }
            p->f_vert[k++] = vi;
        }
    }
    p->f_first[p->nf] = k;
    int rc = finish_init(p, vb, T);
    free(vb);
    return rc;
}

int or_poly_init_raw(or_poly *p, const double *xyz, uint32_t nv, const uint32_t *f_first,
                     const uint32_t *f_vert, uint32_t nf) {
    memset(p, 0, sizeof *p);
    p->nv = nv;
    p->nf = nf;
    p->v = xcalloc(nv, sizeof *p->v);
    for (uint32_t i = 0; i < nv; ++i) {
        p->v[i] = v3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
        double r = len(p->v[i]);
        if (r > p->body_radius) p->body_radius = r;
    }
    p->f_first = xcalloc(nf + 1, sizeof *p->f_first);
    memcpy(p->f_first, f_first, (nf + 1) * sizeof *f_first);
    uint32_t total = f_first[nf];
    p->f_vert = xcalloc(total, sizeof *p->f_vert);
    memcpy(p->f_vert, f_vert, total * sizeof *f_vert);
    /* Each undirected edge appears once as a -> b with a < b in a closed
     * consistently oriented surface; an edge of an open one (a single
     * polygon) appears in one direction only, and is kept either way. */
    p->ev = xcalloc(2 * (size_t)total, sizeof *p->ev);
    p->ne = 0;
    for (uint32_t f = 0; f < nf; ++f) {
        uint32_t b = f_first[f], n = f_first[f + 1] - b;
        for (uint32_t k = 0; k < n; ++k) {
            uint32_t a = f_vert[b + k], c = f_vert[b + (k + 1) % n];
            int keep = a < c;
            if (!keep) {
                /* a > c: kept unless some face has c -> a. */
                keep = 1;
                for (uint32_t g = 0; g < nf && keep; ++g) {
                    uint32_t gb = f_first[g], gn = f_first[g + 1] - gb;
                    for (uint32_t j = 0; j < gn; ++j)
                        if (f_vert[gb + j] == c && f_vert[gb + (j + 1) % gn] == a) keep = 0;
                }
                if (keep) {
                    uint32_t t = a;
                    a = c;
                    c = t;
                }
            }
            if (keep) {
                p->ev[2 * p->ne] = a;
                p->ev[2 * p->ne + 1] = c;
                p->ne++;
            }
        }
    }
    return finish_init(p, NULL, NULL);
}

void or_poly_free(or_poly *p) {
    free(p->v);
    free(p->ev);
    free(p->f_first);
    free(p->f_vert);
    free(p->fn);
    free(p->fw);
    free(p->fdeg);
    free(p->fd);
    free(p->fc);
    free(p->fr);
    free(p->ec);
    free(p->er);
    memset(p, 0, sizeof *p);
}

/* -------------------------------------------------------------- primitives */

double or_pt_seg(px_vec3 p, px_vec3 a, px_vec3 b, px_vec3 *q) {
    px_vec3 d = sub(b, a);
    double dd = dot(d, d);
    double t = 0;
    if (dd > 0) {
        t = dot(sub(p, a), d) / dd;
        if (t < 0) t = 0;
        if (t > 1) t = 1;
    }
    px_vec3 c = lerp(a, b, t);
    if (q) *q = c;
    return dist(p, c);
}

double or_seg_seg(px_vec3 a0, px_vec3 a1, px_vec3 b0, px_vec3 b1, px_vec3 *pa, px_vec3 *pb) {
    /* The squared distance is convex on [0,1]^2: its minimum is either the
     * unconstrained one (if inside) or on the boundary, i.e. an endpoint
     * against the other segment. Take the best of all five candidates. */
    px_vec3 q, ba = a0, bb = b0;
    double best = or_pt_seg(a0, b0, b1, &q);
    bb = q;
    double dd = or_pt_seg(a1, b0, b1, &q);
    if (dd < best) best = dd, ba = a1, bb = q;
    dd = or_pt_seg(b0, a0, a1, &q);
    if (dd < best) best = dd, ba = q, bb = b0;
    dd = or_pt_seg(b1, a0, a1, &q);
    if (dd < best) best = dd, ba = q, bb = b1;
    /* Unit directions keep every product in range (no overflow at 1e150). */
    px_vec3 d1 = sub(a1, a0), d2 = sub(b1, b0);
    double l1 = len(d1), l2 = len(d2);
    if (!(l1 > 0) || !(l2 > 0)) goto done;
    px_vec3 u1 = mul(d1, 1.0 / l1), u2 = mul(d2, 1.0 / l2);
    px_vec3 n = cross(u1, u2);
    double nn = dot(n, n);
    /* sin^2 of the angle above 1e-28: otherwise the segments are parallel and
     * an endpoint candidate already attains the minimum. */
    if (nn > 1e-28) {
        px_vec3 w = sub(b0, a0);
        double s = dot(cross(w, u2), n) / nn / l1;
        double t = dot(cross(w, u1), n) / nn / l2;
        if (s >= 0 && s <= 1 && t >= 0 && t <= 1) {
            /* Polish the closed form with two alternating projections. */
            px_vec3 x = lerp(a0, a1, s), y;
            or_pt_seg(x, b0, b1, &y);
            or_pt_seg(y, a0, a1, &x);
            or_pt_seg(x, b0, b1, &y);
            dd = dist(x, y);
            if (dd < best) best = dd, ba = x, bb = y;
        }
    }
done:
    if (pa) *pa = ba;
    if (pb) *pb = bb;
    return best;
}

/* Smallest signed distance (positive inside) of in-plane point x to the edge
 * lines of face f; >= 0 means inside the closed polygon. */
static double face_inside_margin(const or_poly *P, uint32_t f, px_vec3 x) {
    uint32_t b = P->f_first[f], n = P->f_first[f + 1] - b;
    double m = INFINITY;
    for (uint32_t k = 0; k < n; ++k) {
        px_vec3 v0 = P->v[P->f_vert[b + k]], v1 = P->v[P->f_vert[b + (k + 1) % n]];
        px_vec3 e = sub(v1, v0);
        double le = len(e);
        if (!(le > 0)) continue;
        double c = dot(cross(e, sub(x, v0)), P->fw[f]) / le;
        if (c < m) m = c;
    }
    return m;
}

double or_pt_face(px_vec3 p, const or_poly *P, uint32_t f, px_vec3 *q) {
    px_vec3 n = P->fn[f];
    double h = dot(n, p) - P->fd[f];
    if (!P->fdeg[f] && face_inside_margin(P, f, p) >= 0) {
        if (q) *q = sub(p, mul(n, h));
        return fabs(h);
    }
    /* Outside the prism: the closest point of a convex polygon is on its boundary. */
    uint32_t b = P->f_first[f], cnt = P->f_first[f + 1] - b;
    double best = INFINITY;
    px_vec3 bq = p, t;
    for (uint32_t k = 0; k < cnt; ++k) {
        double d = or_pt_seg(p, P->v[P->f_vert[b + k]], P->v[P->f_vert[b + (k + 1) % cnt]], &t);
        if (d < best) best = d, bq = t;
    }
    if (q) *q = bq;
    return best;
}

/* Where segment a0-a1 crosses the plane of face f inside the polygon: returns
 * 1 and the point (and a robustness margin) if it does. */
static int seg_crosses_face(px_vec3 a0, px_vec3 a1, const or_poly *P, uint32_t f, px_vec3 *x,
                            double *margin) {
    if (P->fdeg[f]) return 0;
    double h0 = dot(P->fn[f], a0) - P->fd[f], h1 = dot(P->fn[f], a1) - P->fd[f];
    if ((h0 > 0 && h1 > 0) || (h0 < 0 && h1 < 0)) return 0;
    if (h0 == h1) return 0; /* both 0: in the plane; boundary tests cover it */
    double t = h0 / (h0 - h1);
    px_vec3 p = lerp(a0, a1, t);
    double m = face_inside_margin(P, f, p);
    if (m < 0) return 0;
    if (x) *x = p;
    if (margin) *margin = fmin(m, fmin(fabs(h0), fabs(h1)));
    return 1;
}

double or_seg_face(px_vec3 a0, px_vec3 a1, const or_poly *P, uint32_t f, px_vec3 *pa, px_vec3 *pq) {
    px_vec3 x;
    if (seg_crosses_face(a0, a1, P, f, &x, NULL)) {
        if (pa) *pa = x;
        if (pq) *pq = x;
        return 0;
    }
    px_vec3 q, ba, bq;
    double best = or_pt_face(a0, P, f, &q);
    ba = a0, bq = q;
    double d = or_pt_face(a1, P, f, &q);
    if (d < best) best = d, ba = a1, bq = q;
    uint32_t b = P->f_first[f], n = P->f_first[f + 1] - b;
    for (uint32_t k = 0; k < n; ++k) {
        px_vec3 s, t;
        d = or_seg_seg(a0, a1, P->v[P->f_vert[b + k]], P->v[P->f_vert[b + (k + 1) % n]], &s, &t);
        if (d < best) best = d, ba = s, bq = t;
    }
    if (pa) *pa = ba;
    if (pq) *pq = bq;
    return best;
}

double or_face_face(const or_poly *A, uint32_t fa, const or_poly *B, uint32_t fb, px_vec3 *pa, px_vec3 *pb) {
    /* Two convex polygons: 0 if an edge of one meets the other, else the
     * minimum is attained on a boundary edge of one of them. */
    double best = INFINITY;
    px_vec3 ba = A->fc[fa], bb = B->fc[fb], s, t;
    uint32_t b = A->f_first[fa], n = A->f_first[fa + 1] - b;
    for (uint32_t k = 0; k < n; ++k) {
        double d = or_seg_face(A->v[A->f_vert[b + k]], A->v[A->f_vert[b + (k + 1) % n]], B, fb, &s, &t);
        if (d < best) best = d, ba = s, bb = t;
    }
    b = B->f_first[fb], n = B->f_first[fb + 1] - b;
    for (uint32_t k = 0; k < n; ++k) {
        double d = or_seg_face(B->v[B->f_vert[b + k]], B->v[B->f_vert[b + (k + 1) % n]], A, fa, &s, &t);
        if (d < best) best = d, ba = t, bb = s;
    }
    if (pa) *pa = ba;
    if (pb) *pb = bb;
    return best;
}

static int feature_ok(const or_poly *P, px_feature f) {
    switch (f.type) {
    case PX_FEATURE_VERTEX: return f.index < P->nv;
    case PX_FEATURE_EDGE: return f.index < P->ne;
    case PX_FEATURE_FACE: return f.index < P->nf;
    default: return 0;
    }
}

double or_feature_distance(const or_poly *A, px_feature fa, const or_poly *B, px_feature fb) {
    if (!feature_ok(A, fa) || !feature_ok(B, fb)) return -1;
    /* Order so that the first feature has the lower dimension. */
    if (fa.type > fb.type) {
        const or_poly *tp = A;
        A = B;
        B = tp;
        px_feature tf = fa;
        fa = fb;
        fb = tf;
    }
    px_vec3 p0 = {0, 0, 0}, p1 = {0, 0, 0};
    if (fa.type == PX_FEATURE_VERTEX) p0 = A->v[fa.index];
    if (fa.type == PX_FEATURE_EDGE) p0 = A->v[A->ev[2 * fa.index]], p1 = A->v[A->ev[2 * fa.index + 1]];
    switch (fa.type * 4 + fb.type) {
    case PX_FEATURE_VERTEX * 4 + PX_FEATURE_VERTEX: return dist(p0, B->v[fb.index]);
    case PX_FEATURE_VERTEX * 4 + PX_FEATURE_EDGE:
        return or_pt_seg(p0, B->v[B->ev[2 * fb.index]], B->v[B->ev[2 * fb.index + 1]], NULL);
    case PX_FEATURE_VERTEX * 4 + PX_FEATURE_FACE: return or_pt_face(p0, B, fb.index, NULL);
    case PX_FEATURE_EDGE * 4 + PX_FEATURE_EDGE:
        return or_seg_seg(p0, p1, B->v[B->ev[2 * fb.index]], B->v[B->ev[2 * fb.index + 1]], NULL, NULL);
    case PX_FEATURE_EDGE * 4 + PX_FEATURE_FACE: return or_seg_face(p0, p1, B, fb.index, NULL, NULL);
    case PX_FEATURE_FACE * 4 + PX_FEATURE_FACE: return or_face_face(A, fa.index, B, fb.index, NULL, NULL);
    default: return -1;
    }
}

double or_point_feature_distance(const or_poly *P, px_feature f, px_vec3 p) {
    if (!feature_ok(P, f)) return -1;
    switch (f.type) {
    case PX_FEATURE_VERTEX: return dist(p, P->v[f.index]);
    case PX_FEATURE_EDGE: return or_pt_seg(p, P->v[P->ev[2 * f.index]], P->v[P->ev[2 * f.index + 1]], NULL);
    default: return or_pt_face(p, P, f.index, NULL);
    }
}

double or_point_depth(const or_poly *P, px_vec3 p) {
    double m = -INFINITY;
    for (uint32_t f = 0; f < P->nf; ++f) {
        if (P->fdeg[f]) continue;
        double h = dot(P->fn[f], p) - P->fd[f];
        if (h > m) m = h;
    }
    return m;
}

/* ------------------------------------------------------------ intersection */

static void intersect_one_way(const or_poly *A, const or_poly *B, int *hit, double *margin) {
    /* Vertices of A inside B (B needs all its planes for that). */
    for (uint32_t i = 0; i < A->nv && !B->degenerate; ++i) {
        if (dist(A->v[i], B->center) > B->radius * (1 + 1e-9)) continue;
        double depth = or_point_depth(B, A->v[i]);
        if (depth <= 0) {
            *hit = 1;
            if (-depth > *margin) *margin = -depth;
        }
    }
    /* Edges of A crossing faces of B. */
    for (uint32_t e = 0; e < A->ne; ++e) {
        if (dist(A->ec[e], B->center) > (A->er[e] + B->radius) * (1 + 1e-9)) continue;
        px_vec3 a0 = A->v[A->ev[2 * e]], a1 = A->v[A->ev[2 * e + 1]];
        for (uint32_t f = 0; f < B->nf; ++f) {
            if (dist(A->ec[e], B->fc[f]) > (A->er[e] + B->fr[f]) * (1 + 1e-9)) continue;
            double m;
            if (seg_crosses_face(a0, a1, B, f, NULL, &m)) {
                *hit = 1;
                if (m > *margin) *margin = m;
            }
        }
    }
}

int or_intersect(const or_poly *A, const or_poly *B, double *margin) {
    int hit = 0;
    double m = 0;
    if (dist(A->center, B->center) <= (A->radius + B->radius) * (1 + 1e-9)) {
        intersect_one_way(A, B, &hit, &m);
        intersect_one_way(B, A, &hit, &m);
    }
    if (margin) *margin = hit ? m : 0;
    return hit;
}

/* ---------------------------------------------------------------- distance */

static px_feature feat(uint32_t type, uint32_t index) {
    px_feature f = {type, index, 0};
    return f;
}

void or_distance(const or_poly *A, const or_poly *B, or_result *out) {
    memset(out, 0, sizeof *out);
    out->intersecting = or_intersect(A, B, &out->margin);
    double best = INFINITY;
    px_vec3 q, r;
    /* V-V */
    for (uint32_t i = 0; i < A->nv; ++i)
        for (uint32_t j = 0; j < B->nv; ++j) {
            double d = dist(A->v[i], B->v[j]);
            if (d < best) {
                best = d;
                out->fa = feat(PX_FEATURE_VERTEX, i), out->fb = feat(PX_FEATURE_VERTEX, j);
                out->pa = A->v[i], out->pb = B->v[j];
            }
        }
    /* V-E both ways */
    for (uint32_t i = 0; i < A->nv; ++i)
        for (uint32_t e = 0; e < B->ne; ++e) {
            if (prune(dist(A->v[i], B->ec[e]) - B->er[e], best)) continue;
            double d = or_pt_seg(A->v[i], B->v[B->ev[2 * e]], B->v[B->ev[2 * e + 1]], &q);
            if (d < best) {
                best = d;
                out->fa = feat(PX_FEATURE_VERTEX, i), out->fb = feat(PX_FEATURE_EDGE, e);
                out->pa = A->v[i], out->pb = q;
            }
        }
    for (uint32_t j = 0; j < B->nv; ++j)
        for (uint32_t e = 0; e < A->ne; ++e) {
            if (prune(dist(B->v[j], A->ec[e]) - A->er[e], best)) continue;
            double d = or_pt_seg(B->v[j], A->v[A->ev[2 * e]], A->v[A->ev[2 * e + 1]], &q);
            if (d < best) {
                best = d;
                out->fa = feat(PX_FEATURE_EDGE, e), out->fb = feat(PX_FEATURE_VERTEX, j);
                out->pa = q, out->pb = B->v[j];
            }
        }
    /* V-F both ways */
    for (uint32_t i = 0; i < A->nv; ++i)
        for (uint32_t f = 0; f < B->nf; ++f) {
            if (prune(dist(A->v[i], B->fc[f]) - B->fr[f], best)) continue;
            double d = or_pt_face(A->v[i], B, f, &q);
            if (d < best) {
                best = d;
                out->fa = feat(PX_FEATURE_VERTEX, i), out->fb = feat(PX_FEATURE_FACE, f);
                out->pa = A->v[i], out->pb = q;
            }
        }
    for (uint32_t j = 0; j < B->nv; ++j)
        for (uint32_t f = 0; f < A->nf; ++f) {
            if (prune(dist(B->v[j], A->fc[f]) - A->fr[f], best)) continue;
            double d = or_pt_face(B->v[j], A, f, &q);
            if (d < best) {
                best = d;
                out->fa = feat(PX_FEATURE_FACE, f), out->fb = feat(PX_FEATURE_VERTEX, j);
                out->pa = q, out->pb = B->v[j];
            }
        }
    /* E-E */
    for (uint32_t e = 0; e < A->ne; ++e) {
        if (prune(dist(A->ec[e], B->center) - A->er[e] - B->radius, best)) continue;
        for (uint32_t g = 0; g < B->ne; ++g) {
            if (prune(dist(A->ec[e], B->ec[g]) - A->er[e] - B->er[g], best)) continue;
            double d = or_seg_seg(A->v[A->ev[2 * e]], A->v[A->ev[2 * e + 1]], B->v[B->ev[2 * g]],
                                  B->v[B->ev[2 * g + 1]], &q, &r);
            if (d < best) {
                best = d;
                out->fa = feat(PX_FEATURE_EDGE, e), out->fb = feat(PX_FEATURE_EDGE, g);
                out->pa = q, out->pb = r;
            }
        }
    }
    out->distance = out->intersecting ? 0.0 : best;
}
