/* One px_distance query checked against the brute-force oracle; see check.h. */
#include "access.h"
#include "check.h"

#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "math/vec3.h"
#include "pxcd.h"

double tc_rel_tol = 1e-12;
px_query_options tc_options;

const char *tc_method_from_env(void) {
    static const char *names[] = {"lin-canny", "gjk", "hybrid"};
    const char *m = getenv("PROXIMA_TEST_METHOD");
    memset(&tc_options, 0, sizeof tc_options);
    for (uint32_t k = 0; m && k < 3; ++k)
        if (strcmp(m, names[k]) == 0) tc_options.method = k;
    return names[tc_options.method];
}

static void add_msg(tc_report *rep, int bit, const char *fmt, ...) {
    if (!rep->fail) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(rep->msg, sizeof rep->msg, fmt, ap);
        va_end(ap);
    }
    rep->fail |= bit;
}

static double body_radius(const px_convex *c) {
    double r = 0;
    uint32_t n = px_convex_vertex_count(c);
    for (uint32_t i = 0; i < n; ++i) {
        double l = pxi_len(ta_vertex(c, i));
        if (l > r) r = l;
    }
    return r;
}

double tc_scale(const px_convex *a, const px_pose *pa, const px_convex *b, const px_pose *pb) {
    px_pose t = pxi_relative(pa, pb);
    return pxi_len(t.t) + body_radius(a) + body_radius(b);
}

void tc_vertices_in_b(const px_convex *a, const px_pose *pa, const px_pose *pb, double *xyz) {
    px_pose t = pxi_relative(pa, pb);
    uint32_t n = px_convex_vertex_count(a);
    for (uint32_t i = 0; i < n; ++i) {
        px_vec3 p = pxi_xform(&t, ta_vertex(a, i));
        xyz[3 * i] = p.x, xyz[3 * i + 1] = p.y, xyz[3 * i + 2] = p.z;
    }
}

void tc_vertices(const px_convex *c, double *xyz) {
    uint32_t n = px_convex_vertex_count(c);
    for (uint32_t i = 0; i < n; ++i) {
        px_vec3 p = ta_vertex(c, i);
        xyz[3 * i] = p.x, xyz[3 * i + 1] = p.y, xyz[3 * i + 2] = p.z;
    }
}

int tc_exact(const px_convex *a, const px_pose *pa, const px_convex *b, const px_pose *pb, double *d,
             int *is_zero) {
    uint32_t na = px_convex_vertex_count(a), nb = px_convex_vertex_count(b);
    double *xa = malloc(3 * (size_t)na * sizeof *xa), *xb = malloc(3 * (size_t)nb * sizeof *xb);
    tc_vertices_in_b(a, pa, pb, xa);
    tc_vertices(b, xb);
    double d2;
    char msg[256];
    pxcd_status st = pxcd_exact_distance(xa, na, xb, nb, d, &d2, is_zero, NULL, NULL, msg, sizeof msg);
    free(xa);
    free(xb);
    if (st != PXCD_OK) fprintf(stderr, "pxcd_exact_distance: %s\n", msg);
    return st == PXCD_OK ? 0 : -1;
}

static int feature_valid(const px_convex *c, px_feature f) {
    switch (f.type) {
    case PX_FEATURE_VERTEX: return f.index < px_convex_vertex_count(c);
    case PX_FEATURE_EDGE: return f.index < px_convex_edge_count(c);
    case PX_FEATURE_FACE: return f.index < px_convex_face_count(c);
    default: return 0;
    }
}

int tc_query_and_check(const px_convex *a, const px_pose *pa, const px_convex *b, const px_pose *pb,
                       px_pair_cache *cache, tc_report *rep) {
    memset(rep, 0, sizeof *rep);
    rep->status = px_distance(a, pa, b, pb, &tc_options, cache, &rep->res);
    const px_distance_result *r = &rep->res;
    if (rep->status != PX_OK) {
        add_msg(rep, TC_STATUS, "px_distance returned %s", px_status_string(rep->status));
        return rep->fail;
    }
    if (!isfinite(r->distance) || !pxi_is_finite3(r->point_a) || !pxi_is_finite3(r->point_b)) {
        add_msg(rep, TC_NONFINITE, "non-finite result");
        return rep->fail;
    }
    /* The oracle works in the frame of the smaller body (the other one is
     * mapped into it in double): a tiny body mapped into a huge body's frame
     * far from the origin would collapse (REFERENCES §7.2). */
    px_pose tab = pxi_relative(pa, pb);
    int in_a = body_radius(a) < body_radius(b);
    const px_pose *frame = in_a ? pa : pb;
    px_pose tba = pxi_relative(pb, pa);
    or_poly A, B;
    memset(&A, 0, sizeof A);
    memset(&B, 0, sizeof B);
    int ok = in_a ? (or_poly_init(&A, a, NULL) == 0 && or_poly_init(&B, b, &tba) == 0)
                  : (or_poly_init(&A, a, &tab) == 0 && or_poly_init(&B, b, NULL) == 0);
    if (!ok) {
        or_poly_free(&A);
        or_poly_free(&B);
        add_msg(rep, TC_FEATURES, "oracle could not read the polytopes");
        return rep->fail;
    }
    rep->scale = pxi_len(tab.t) + A.body_radius + B.body_radius;
    rep->tol = tc_rel_tol * rep->scale;
    double tol = rep->tol;
    or_distance(&A, &B, &rep->orc);
    const or_result *o = &rep->orc;

    /* Distance and classification. */
    if (r->intersecting && r->distance != 0)
        add_msg(rep, TC_INTERSECT_D, "intersecting but distance %.17g", r->distance);
    if (!(r->distance >= 0)) add_msg(rep, TC_DISTANCE, "negative distance %.17g", r->distance);
    if (fabs(r->distance - o->distance) > tol)
        add_msg(rep, TC_DISTANCE,
                "distance %.17g, oracle %.17g (oracle %s, margin %.3g), diff %.3g > tol %.3g", r->distance,
                o->distance, o->intersecting ? "intersecting" : "disjoint", o->margin,
                fabs(r->distance - o->distance), tol);
    if (o->intersecting ? o->margin > tol : o->distance > tol) {
        if (r->intersecting != o->intersecting)
            add_msg(rep, TC_CLASSIFY, "intersecting=%d, oracle %d (margin %.3g, oracle d %.3g)",
                    r->intersecting, o->intersecting, o->margin, o->distance);
    } else {
        rep->band = 1;
    }

    /* Witness points, mapped into the oracle's frame. */
    px_vec3 wa = pxi_xform_inv(frame, r->point_a), wb = pxi_xform_inv(frame, r->point_b);
    /* World-frame witnesses cannot be better than the rounding of world
     * coordinates: widen by eps (|t_A| + |t_B| + R_A + R_B). */
    double tol_w = tol + 8 * DBL_EPSILON * (pxi_len(pa->t) + pxi_len(pb->t) + A.body_radius + B.body_radius);
    double sep = pxi_len(pxi_sub(r->point_a, r->point_b));
    if (fabs(sep - r->distance) > tol_w)
        add_msg(rep, TC_WITNESS, "|point_a - point_b| = %.17g but distance %.17g", sep, r->distance);
    double da = or_point_depth(&A, wa), db = or_point_depth(&B, wb);
    if (da > tol_w || db > tol_w)
        add_msg(rep, TC_WITNESS, "witness off its body: point_a depth %.3g in A, point_b depth %.3g in B", da,
                db);
    if (r->intersecting) {
        double ca = or_point_depth(&B, wa), cb = or_point_depth(&A, wb);
        if (ca > tol_w || cb > tol_w)
            add_msg(rep, TC_WITNESS, "intersecting but witnesses not common: %.3g %.3g", ca, cb);
    }

    /* Features: valid, and (disjoint) realising the distance. */
    if (!feature_valid(a, r->feature_a) || !feature_valid(b, r->feature_b)) {
        add_msg(rep, TC_FEATURES, "invalid features A(%u,%u) B(%u,%u)", r->feature_a.type, r->feature_a.index,
                r->feature_b.type, r->feature_b.index);
    } else if (!r->intersecting) {
        /* each witness lies on its reported feature */
        double ea = or_point_feature_distance(&A, r->feature_a, wa),
               eb = or_point_feature_distance(&B, r->feature_b, wb);
        if (ea > tol_w || eb > tol_w)
            add_msg(rep, TC_WITNESS,
                    "witness not on its feature: point_a %.3g from A(%u,%u), point_b %.3g from B(%u,%u)", ea,
                    r->feature_a.type, r->feature_a.index, eb, r->feature_b.type, r->feature_b.index);
        double fd = or_feature_distance(&A, r->feature_a, &B, r->feature_b);
        if (fabs(fd - r->distance) > tol)
            add_msg(rep, TC_FEATURES, "features A(%u,%u) B(%u,%u) are %.17g apart, distance %.17g",
                    r->feature_a.type, r->feature_a.index, r->feature_b.type, r->feature_b.index, fd,
                    r->distance);
    }
    or_poly_free(&A);
    or_poly_free(&B);
    return rep->fail;
}
