/* The public query entry points and the one place that chooses methods and
 * fallbacks: argument checks, the relative transform, the fallback table,
 * and the conversion of body-frame answers to world results. Every method
 * answers through the same pxi_answer, so the result conventions
 * (docs/methods.md) are written once, here.
 *
 * The fallback table (k_next below). A method that ends without a proof
 * (pxi_outcome) hands its pair to the next step of its row:
 *
 *   step          what runs                                 unproven      out of steps
 *   LC            Lin-Canny from the cache's features, or   LC_RESTART    LC_SEEDED (cold
 *                 cold from the line of centres (round                    start, not a
 *                 bodies, 12 steps)                                       fallback)
 *   LC_SEEDED     GJK to 1e-3, then Lin-Canny from its      LC_RESTART    LC_RESTART
 *                 vertices (the cold start of thin bodies)
 *   LC_FINISH     Lin-Canny from the last answer's features LC_RESTART    LC_RESTART
 *   LC_RESTART    GJK to 1e-12, Lin-Canny in tie-breaking   (GJK's own answer, flagged)
 *                 mode from it
 *   GJK           enhanced GJK                              LC_FINISH     LC_FINISH
 *   HYBRID        the seed 001 hybrid                       GJK           GJK
 *   GJK_NW        enhanced GJK, on a pair Lin-Canny         HYBRID_NW     HYBRID_NW
 *                 cannot walk
 *   HYBRID_NW     the hybrid, on such a pair                (its own answer, flagged)
 *
 * A pair Lin-Canny cannot walk holds a sliver polygon (px_convex.walk_ok:
 * a polygon turning by less than 1e-9 at a vertex, whose normal and side
 * planes rounding decides). Every query then starts at GJK_NW (the hybrid
 * method at HYBRID_NW), from support functions alone, which are exact on
 * any vertex set; asking for Lin-Canny then counts one fallback. Points,
 * segments and every other polygon are walked like solids (convex.h has
 * their Voronoi regions).
 *
 * Signed distance adds EPA (from GJK's simplex) and, when EPA's polytope
 * budget runs out, a translation query along its best normal. Translation
 * tries conservative advancement from a warm cache, then the ray cast (cold
 * again when a warm ray cast does not converge cleanly), and finishes a ray
 * cast that stopped at the rounding floor by advancement.
 *
 * `fallbacks` counts every hand-off after a method that should have
 * concluded did not; seeding a cold walk and declining a warm fast path are
 * not fallbacks. Iterations of every method that ran are summed. */
#include <float.h>
#include <math.h>
#include <string.h>

#include "convex/convex.h"
#include "math/orient.h"
#include "math/vec3.h"
#include "narrow/feature.h"
#include "narrow/narrow.h"
#include "narrow/tolerance.h"

/* The frames of a query: every polytope is stored about its centre
 * (convex.h), so the queries run between the stored frames, and answers map
 * back to the world through them. */
typedef struct pair_frames {
    px_pose t_ab; /* A's stored frame -> B's stored frame */
    const px_pose *pose_a, *pose_b;
    px_vec3 ta, tb; /* the stored frames' origins in the world: t + R origin */
} pair_frames;

/* World point of a stored-frame point of A (which = 0) or B (which = 1). */
static inline px_vec3 to_world(const pair_frames *f, int which, px_vec3 p) {
    return pxi_add(pxi_rot(which ? f->pose_b->r : f->pose_a->r, p), which ? f->tb : f->ta);
}

/* a + b + c + d with Neumaier's compensated summation (A. Neumaier, "Rundungs-
 * fehleranalyse einiger Verfahren zur Summation endlicher Summen", ZAMM 54,
 * 1974): the error is about eps |sum| plus eps^2 times the terms, so large
 * terms that cancel do not take the small result's bits with them. */
static double sum4(double a, double b, double c, double d) {
    double x[3] = {b, c, d}, s = a, comp = 0.0;
    for (int i = 0; i < 3; ++i) {
        double t = s + x[i];
        comp += fabs(s) >= fabs(x[i]) ? (s - t) + x[i] : (x[i] - t) + s;
        s = t;
    }
    return s + comp;
}

/* Checks the arguments every query shares and computes the frames. T_AB's
 * translation is (t_A - t_B) + (R_A o_A - R_B o_B) rotated into B: the
 * poses' difference first, exact when the bodies are close (REFERENCES
 * §1.8, §7), then the centres' offsets. Poses far apart (translations of
 * opposite sign near 1e308) can overflow it even though each pose is
 * finite: PX_ERR_NON_FINITE. */
static px_status check_poses(const px_convex *a, const px_pose *pose_a, const px_convex *b,
                             const px_pose *pose_b, int poses_checked, pair_frames *f) {
    if (!a || !b || !pose_a || !pose_b) return PX_ERR_INVALID_ARGUMENT;
    px_status st = poses_checked ? PX_OK : px_pose_check(pose_a, NULL);
    if (st == PX_OK && !poses_checked) st = px_pose_check(pose_b, NULL);
    if (st != PX_OK) return st;
    /* Checked before the rotation: inf times a zero matrix entry is NaN. */
    px_vec3 dt = pxi_sub(pose_a->t, pose_b->t);
    if (!pxi_is_finite3(dt)) return PX_ERR_NON_FINITE;
    f->pose_a = pose_a;
    f->pose_b = pose_b;
    f->t_ab = pxi_relative(pose_a, pose_b);
    f->ta = pose_a->t;
    f->tb = pose_b->t;
    /* Most bodies sit near their frame's origin (origin 0): nothing more. */
    int ra = a->origin.x != 0.0 || a->origin.y != 0.0 || a->origin.z != 0.0;
    int rb = b->origin.x != 0.0 || b->origin.y != 0.0 || b->origin.z != 0.0;
    if (ra || rb) {
        px_vec3 zero = {0, 0, 0};
        px_vec3 oa = ra ? pxi_rot(pose_a->r, a->origin) : zero,
                ob = rb ? pxi_rot(pose_b->r, b->origin) : zero;
        f->ta = pxi_add(pose_a->t, oa);
        f->tb = pxi_add(pose_b->t, ob);
        /* t_A - t_B + R_A o_A - R_B o_B, summed with compensation: a body
         * whose points sit at 2^40 posed back by -2^40 must keep the bits
         * below ulp(2^40) that the cancellation leaves. */
        px_vec3 d =
            pxi_v(sum4(pose_a->t.x, -pose_b->t.x, oa.x, -ob.x), sum4(pose_a->t.y, -pose_b->t.y, oa.y, -ob.y),
                  sum4(pose_a->t.z, -pose_b->t.z, oa.z, -ob.z));
        if (!pxi_is_finite3(f->ta) || !pxi_is_finite3(f->tb) || !pxi_is_finite3(d)) return PX_ERR_NON_FINITE;
        f->t_ab.t = pxi_rot_t(pose_b->r, d);
    }
    if (!pxi_is_finite3(f->t_ab.t)) return PX_ERR_NON_FINITE;
    /* The pair's span (sizes plus distance) must leave room for the sums and
     * the power-of-two scaling of every method: at most 2^1021 (4.5e307). */
    return pxi_pair_span(a, b, &f->t_ab) <= 0x1p1021 ? PX_OK : PX_ERR_RANGE;
}

static px_status check_pair(const px_convex *a, const px_pose *pose_a, const px_convex *b,
                            const px_pose *pose_b, pair_frames *f) {
    return check_poses(a, pose_a, b, pose_b, 0, f);
}

static inline px_vec3 unit_or_zero(px_vec3 v) {
    double l2 = pxi_len2(v);
    /* the plain formula where |v|^2 neither overflows nor underflows */
    if (l2 > 0x1p-1000 && l2 < 0x1p1000) return pxi_scale(v, 1.0 / sqrt(l2));
    return pxi_unit_safe(v);
}

/* The normal of a separated pair. The closest points' direction is known
 * only to about eps S / d (unit cubes 1e-13 apart: off by 1e-2 rad, 1e-9
 * apart: by 1e-6); when the closest features are a facet of A - B (a face
 * with anything, two edges that cross) whose own normal agrees with it to
 * within the points' rounding, that normal is exact (review s32). Closer
 * than 2^-16 S only: farther, the direction is within about 1e-10 rad, and
 * the common tracked query, resting contacts included, pays one test (the
 * refinement costs about 140 instructions, 8 % of a tracked query). */
PXI_COLD px_vec3 facet_normal(const px_convex *a, const px_convex *b, const pair_frames *fr,
                              const pxi_answer *ans, px_vec3 world_gap, double span) {
    const int facet = (ans->fb.type == PX_FEATURE_FACE && ans->fb.index < b->nf) ||
                      (ans->fa.type == PX_FEATURE_FACE && ans->fa.index < a->nf) ||
                      (ans->fa.type == PX_FEATURE_EDGE && ans->fb.type == PX_FEATURE_EDGE);
    if (!facet) return unit_or_zero(world_gap);
    px_vec3 g = pxi_sub(ans->pb, pxi_xform(&fr->t_ab, ans->pa)); /* B's frame */
    double gg = pxi_len2(g);
    if (!(gg > 0x1p-1000 && gg < 0x1p1000)) return unit_or_zero(world_gap);
    /* the facet's normal, turned towards g (g's own direction for parallel edges) */
    px_vec3 nf = pxi_feature_normal(a, b, &fr->t_ab, ans->fa, ans->fb, g);
    double d = sqrt(gg), tol = 64.0 * DBL_EPSILON * span;
    if (!(pxi_len2(pxi_sub(pxi_scale(nf, d), g)) <= tol * tol)) return unit_or_zero(world_gap);
    return pxi_rot(fr->pose_b->r, nf);
}

static inline px_vec3 separation_normal(const px_convex *a, const px_convex *b, const pair_frames *fr,
                                        const pxi_answer *ans, px_vec3 world_gap) {
    const double span = pxi_pair_span(a, b, &fr->t_ab);
    if (PXI_RARE(ans->distance <= 0x1p-16 * span)) return facet_normal(a, b, fr, ans, world_gap, span);
    return unit_or_zero(world_gap);
}

/* ---- The fallback table. ---- */

typedef enum step {
    STEP_END,
    STEP_LC,
    STEP_LC_SEEDED,
    STEP_LC_FINISH,
    STEP_LC_RESTART,
    STEP_GJK,
    STEP_HYBRID,
    STEP_GJK_NW,
    STEP_HYBRID_NW
} step;

typedef struct next_row {
    step unproven, out_of_steps;
    int oos_is_seed; /* running out of steps is the designed cold start, not a fallback */
} next_row;

static const next_row k_next[] = {
    [STEP_END] = {STEP_END, STEP_END, 0},
    [STEP_LC] = {STEP_LC_RESTART, STEP_LC_SEEDED, 1},
    [STEP_LC_SEEDED] = {STEP_LC_RESTART, STEP_LC_RESTART, 0},
    [STEP_LC_FINISH] = {STEP_LC_RESTART, STEP_LC_RESTART, 0},
    [STEP_LC_RESTART] = {STEP_END, STEP_END, 0},
    [STEP_GJK] = {STEP_LC_FINISH, STEP_LC_FINISH, 0},
    [STEP_HYBRID] = {STEP_GJK, STEP_GJK, 0},
    [STEP_GJK_NW] = {STEP_HYBRID_NW, STEP_HYBRID_NW, 0},
    [STEP_HYBRID_NW] = {STEP_END, STEP_END, 0},
};

/* Whether Lin-Canny can walk the pair (convex.h, walk_ok). */
static inline int pair_walk_ok(const px_convex *a, const px_convex *b) { return a->walk_ok && b->walk_ok; }

/* Lin-Canny from a start; its answer. */
static void run_lc(const px_convex *a, const px_convex *b, const px_pose *t_ab, px_feature fa, px_feature fb,
                   uint32_t budget, int tie, pxi_answer *ans) {
    pxi_lc_start start = {fa, fb, budget, tie};
    pxi_lin_canny(a, b, t_ab, &start, ans);
}

static px_feature vertex_feature(uint32_t v) {
    px_feature f = {PX_FEATURE_VERTEX, v, 0};
    return f;
}

/* The cold start of thin bodies (and of round ones whose line-of-centres
 * walk ran long): GJK to a loose tolerance finds vertices near the closest
 * points in a few support queries, and the walk starts from there. When
 * GJK's simplex already encloses the origin by more than rounding, the
 * solids overlap and its barycentric point is a common point: walking to a
 * penetration witness would cost O(n) for nothing. */
static void run_lc_seeded(const px_convex *a, const px_convex *b, const px_pose *t_ab, pxi_answer *ans) {
    pxi_gjk_seed g;
    /* A few iterations suffice: the walk finishes the job, and each GJK
     * iteration (two support queries) costs about three walk steps. */
    uint32_t gjk_cap = 4 + (uint32_t)ilogb((double)a->nv + b->nv);
    pxi_gjk_seed_run(a, b, t_ab, 1e-3, gjk_cap, &g);
    double span = pxi_pair_size(a, b, t_ab);
    if (g.intersecting && g.inside_margin > 64.0 * DBL_EPSILON * span) {
        memset(ans, 0, sizeof *ans);
        ans->intersecting = 1;
        ans->pa = g.pa;
        ans->pb = g.pb;
        ans->fa = vertex_feature(g.va);
        ans->fb = vertex_feature(g.vb);
        ans->iterations = g.iterations;
        ans->outcome = PXI_DONE;
        return;
    }
    run_lc(a, b, t_ab, vertex_feature(g.va), vertex_feature(g.vb), 0, 0, ans);
    ans->iterations += g.iterations;
}

/* The last resort of a cycling walk: GJK at full precision, a walk in
 * tie-breaking mode from its answer, and GJK's own answer if that walk
 * still cycles. */
static void run_lc_restart(const px_convex *a, const px_convex *b, const px_pose *t_ab, pxi_answer *ans) {
    pxi_gjk_seed g;
    pxi_gjk_seed_run(a, b, t_ab, 1e-12, 256, &g);
    run_lc(a, b, t_ab, vertex_feature(g.va), vertex_feature(g.vb), 0, 1, ans);
    ans->iterations += g.iterations;
    if (ans->outcome == PXI_DONE) return;
    uint32_t it = ans->iterations;
    memset(ans, 0, sizeof *ans);
    ans->distance = g.intersecting ? 0.0 : g.distance;
    ans->intersecting = g.intersecting;
    ans->pa = g.pa;
    ans->pb = g.pb;
    ans->fa = vertex_feature(g.va);
    ans->fb = vertex_feature(g.vb);
    ans->iterations = it;
    ans->outcome = PXI_DONE;
    ans->quality = PX_QUALITY_UNPROVEN;
}

/* Runs one step on the pair. `cache` is the caller's for the first step
 * only (fallbacks run cold); `prev` is the answer being finished. */
static void run_step(step s, const px_convex *a, const px_convex *b, const px_pose *t_ab,
                     px_pair_cache *cache, const pxi_answer *prev, pxi_simplex_pairs *simplex,
                     pxi_answer *ans) {
    px_feature none = {PX_FEATURE_NONE, 0, 0};
    switch (s) {
    case STEP_LC:
        /* the cache's features when they are valid (pxi_lin_canny checks),
         * else cold from the line of centres with the cold budget */
        run_lc(a, b, t_ab, cache ? cache->feature_a : none, cache ? cache->feature_b : none,
               PXI_LC_COLD_BUDGET, 0, ans);
        break;
    case STEP_LC_SEEDED: run_lc_seeded(a, b, t_ab, ans); break;
    case STEP_LC_FINISH: run_lc(a, b, t_ab, prev->fa, prev->fb, 0, 0, ans); break;
    case STEP_LC_RESTART: run_lc_restart(a, b, t_ab, ans); break;
    case STEP_GJK:
    case STEP_GJK_NW: pxi_gjk_distance(a, b, t_ab, cache, ans, simplex); break;
    case STEP_HYBRID:
    case STEP_HYBRID_NW: pxi_hybrid(a, b, t_ab, cache, ans); break;
    case STEP_END: break;
    }
}

/* The first step of a method on this pair. */
static step first_step(uint32_t method, const px_convex *a, const px_convex *b, const px_pair_cache *cache) {
    if (!pair_walk_ok(a, b)) return method == PX_METHOD_HYBRID ? STEP_HYBRID_NW : STEP_GJK_NW;
    switch (method) {
    case PX_METHOD_GJK: return STEP_GJK;
    case PX_METHOD_HYBRID: return STEP_HYBRID;
    default:
        if (pxi_lc_line_of_centres_ok(a, b)) return STEP_LC;
        return cache && pxi_feature_valid(a, cache->feature_a) && pxi_feature_valid(b, cache->feature_b)
                   ? STEP_LC
                   : STEP_LC_SEEDED;
    }
}

/* The witness plane of a miss whose normal, from the projected GJK, is
 * known only to eps span / gap (a line passing within 1e-12 of the size of
 * B): its supports did not separate. The closest approach is near tau* =
 * d . (pb - pa) / |d|^2, where Lin-Canny gives exact closest features. A
 * plane parallel to d that separates the bodies there has a normal in the
 * span of their geometry: d x u for an edge u of either feature (a face
 * offers its boundary edges), or the features' own normal made orthogonal
 * to d. Each candidate is tried; kept is the one whose supports separate by
 * the most (a certificate by construction), if any. */
typedef struct miss_best {
    double gap;
    px_vec3 n;
    uint32_t sa, sb;
} miss_best;

static void try_miss_normal(const px_convex *a, const px_convex *b, const px_pose *t_ab, px_vec3 dir,
                            px_vec3 approx, px_vec3 n, miss_best *best) {
    n = pxi_unit_safe(pxi_madd(n, dir, -pxi_dot(n, dir) / pxi_dot(dir, dir)));
    if (!(pxi_max_abs(n) > 0.0)) return;
    if (pxi_dot(n, approx) < 0.0) n = pxi_neg(n);
    uint32_t sa = pxi_support(a, pxi_rot_t(t_ab->r, n), UINT32_MAX),
             sb = pxi_support(b, pxi_neg(n), UINT32_MAX);
    double gap = pxi_dot(n, pxi_sub(b->v[sb], pxi_xform(t_ab, a->v[sa])));
    if (gap > best->gap) best->gap = gap, best->n = n, best->sa = sa, best->sb = sb;
}

/* d x (edges of feature f of body c, mapped by R into B's frame). */
static void try_feature_edges(const px_convex *a, const px_convex *b, const px_pose *t_ab, px_vec3 dir,
                              px_vec3 approx, const px_convex *c, const double *r, px_feature f,
                              miss_best *best) {
    if (f.type == PX_FEATURE_EDGE && f.index < c->ne) {
        px_vec3 u = r ? pxi_rot(r, c->e[f.index].u) : c->e[f.index].u;
        try_miss_normal(a, b, t_ab, dir, approx, pxi_cross(dir, u), best);
    } else if (f.type == PX_FEATURE_FACE && f.index < c->nf) {
        const pxi_face *F = &c->f[f.index];
        for (uint32_t k = 0; k < F->count; ++k) {
            px_vec3 u = c->e[c->f_edges[F->first + k]].u;
            try_miss_normal(a, b, t_ab, dir, approx, pxi_cross(dir, r ? pxi_rot(r, u) : u), best);
        }
    }
}

/* Lin-Canny with A moved by s along dir (the pose in *tt), started from the
 * features of the translation answer, whose iteration count it adds to; a
 * pair Lin-Canny cannot walk (a sliver polygon) gets GJK there instead. */
static void lin_canny_moved(const px_convex *a, const px_convex *b, const px_pose *t_ab, px_vec3 dir,
                            double s, pxi_translation *out, px_pose *tt, pxi_answer *ans) {
    *tt = *t_ab;
    tt->t = pxi_madd(tt->t, dir, s);
    if (!pair_walk_ok(a, b)) {
        pxi_gjk_distance(a, b, tt, NULL, ans, NULL);
        out->iterations += ans->iterations;
        return;
    }
    pxi_lc_start start;
    memset(&start, 0, sizeof start);
    start.fa = out->fa;
    start.fb = out->fb;
    pxi_lin_canny(a, b, tt, &start, ans);
    out->iterations += ans->iterations;
}

static void refine_miss(const px_convex *a, const px_convex *b, const px_pose *t_ab, px_vec3 dir,
                        pxi_translation *out) {
    double dd = pxi_dot(dir, dir);
    px_pose tt;
    pxi_answer ans;
    lin_canny_moved(a, b, t_ab, dir, pxi_dot(dir, pxi_sub(out->pb, pxi_xform(t_ab, out->pa))) / dd, out, &tt,
                    &ans);
    if (ans.outcome != PXI_DONE || ans.intersecting) return;
    px_vec3 approx = pxi_sub(ans.pb, pxi_xform(&tt, ans.pa));
    miss_best best = {0.0, {0, 0, 0}, 0, 0};
    try_feature_edges(a, b, t_ab, dir, approx, a, t_ab->r, ans.fa, &best);
    try_feature_edges(a, b, t_ab, dir, approx, b, NULL, ans.fb, &best);
    try_miss_normal(a, b, t_ab, dir, approx, pxi_feature_normal(a, b, &tt, ans.fa, ans.fb, approx), &best);
    try_miss_normal(a, b, t_ab, dir, approx, out->normal, &best);
    if (!(best.gap > 0.0)) return;
    out->normal = best.n;
    out->pa = a->v[best.sa];
    out->pb = b->v[best.sb];
    out->gap = best.gap;
    out->fa = pxi_feature_of_vertices(a, &best.sa, 1, NULL);
    out->fb = pxi_feature_of_vertices(b, &best.sb, 1, NULL);
    out->quality &= ~(uint32_t)PX_QUALITY_UNPROVEN;
}

/* A hit the ray cast reached at its rounding floor, which advancement could
 * not confirm (thin bodies: slabs of 1e-6, needles of 1e-5, where the ray
 * cast's planes are nearly parallel to the line): is A + tau d really
 * within the contact band of B? If it is, tau is a contact but maybe not
 * the first (review s31: two needles 1e-9 wide, both ways, entered late by
 * 0.8 of their width): the set of taus within the band is an interval (the
 * distance is convex along the line), so bisection between the ray's
 * proved lower bound and tau finds its start, the contact points taken
 * there. If not, the line may miss B altogether (the projection of B - A
 * along d keeps a gap): then that is the answer; otherwise the hit stands,
 * flagged unproven. */
static void check_floor_hit(const px_convex *a, const px_convex *b, const px_pose *t_ab, px_vec3 dir,
                            double lower, pxi_translation *out) {
    px_pose tt;
    pxi_answer ans;
    lin_canny_moved(a, b, t_ab, dir, out->tau, out, &tt, &ans);
    double band = PXI_CONTACT_BAND * pxi_pair_size(a, b, &tt);
    if (ans.outcome == PXI_DONE && (ans.intersecting || ans.distance <= band)) {
        /* The band of each pose is the pair's size there (at tau = 0 it
         * counts the starting distance: from 1e3 away, a review found the
         * first in-band point 2e3 bands early). Bisection stops once tau's
         * step moves A by less than a band. */
        double lo = lower, hi = out->tau, len = sqrt(pxi_dot(dir, dir));
        pxi_answer at_hi = ans;
        px_pose th = tt;
        for (int k = 0; k < 80 && lo < hi; ++k) {
            double mid = lo + 0.5 * (hi - lo);
            if (!(mid > lo && mid < hi)) break;
            lin_canny_moved(a, b, t_ab, dir, mid, out, &tt, &ans);
            const double band_mid = PXI_CONTACT_BAND * pxi_pair_size(a, b, &tt);
            if (ans.outcome != PXI_DONE) {
                out->quality |= PX_QUALITY_UNPROVEN;
                break;
            }
            if (ans.intersecting || ans.distance <= band_mid)
                hi = mid, at_hi = ans, th = tt;
            else
                lo = mid;
            if ((hi - lo) * len <= band_mid) break;
        }
        if (hi < out->tau) {
            /* decided by the band: the contact points and the normal there */
            out->tau = hi;
            out->pa = at_hi.pa;
            out->pb = at_hi.pb;
            out->fa = at_hi.fa;
            out->fb = at_hi.fb;
            /* The gap's direction within the band is rounding noise: a
             * facet pair's own normal where there is one. */
            px_vec3 g = pxi_sub(at_hi.pb, pxi_xform(&th, at_hi.pa));
            if (!at_hi.intersecting && pxi_max_abs(g) > 0.0)
                out->normal = pxi_feature_normal(a, b, &th, at_hi.fa, at_hi.fb, g);
            out->quality |= PX_QUALITY_CONTACT_BAND;
        }
        return;
    }
    pxi_translation miss;
    pxi_ray_miss(a, b, t_ab, dir, &miss);
    if (miss.quality & PX_QUALITY_UNPROVEN) refine_miss(a, b, t_ab, dir, &miss);
    out->iterations += miss.iterations;
    if (miss.gap > band) {
        *out = miss;
        return;
    }
    out->quality |= PX_QUALITY_UNPROVEN;
}

/* The translation chain (also EPA's fallback). */
void pxi_translation_query(const px_convex *a, const px_convex *b, const px_pose *t_ab, px_vec3 dir,
                           px_pair_cache *cache, pxi_translation *out, uint32_t *fallbacks) {
    memset(out, 0, sizeof *out);
    int warm = cache && cache->simplex_count >= 1 && cache->simplex_count <= 3 &&
               cache->vertex_a[0] < a->nv && cache->vertex_b[0] < b->nv &&
               cache->feature_a.type >= PX_FEATURE_VERTEX && cache->feature_b.type >= PX_FEATURE_VERTEX;
    /* Advancement walks with Lin-Canny: not on a pair it cannot walk. */
    int walk = pair_walk_ok(a, b);
    if (warm && walk && pxi_advance_warm(a, b, t_ab, dir, cache, out) == PXI_DONE) return;
    pxi_ray_bound bound;
    px_pair_cache *ray_cache = cache;
    pxi_outcome st = pxi_raycast(a, b, t_ab, dir, ray_cache, out, &bound);
    if (st == PXI_OUT_OF_STEPS) { /* a warm ray cast that did not converge cleanly: cold */
        uint32_t it = out->iterations;
        ray_cache = NULL;
        st = pxi_raycast(a, b, t_ab, dir, NULL, out, &bound);
        out->iterations += it;
        ++*fallbacks;
    }
    if (st != PXI_UNPROVEN) {
        if (!out->hit && (out->quality & PX_QUALITY_UNPROVEN)) refine_miss(a, b, t_ab, dir, out);
        return;
    }
    /* Stopped at the rounding floor: conservative advancement (exact there)
     * finishes from the proved lower bound; else the ray cast's refined hit
     * stands. */
    ++*fallbacks;
    pxi_translation adv;
    if (!walk ||
        pxi_advance(a, b, t_ab, dir, bound.tau, bound.normal, bound.fa, bound.fb, &adv) != PXI_DONE) {
        check_floor_hit(a, b, t_ab, dir, bound.tau, out);
        return;
    }
    adv.iterations += out->iterations;
    *out = adv;
    if (ray_cache) {
        ray_cache->simplex_count = (uint8_t)bound.simplex.n;
        for (int m = 0; m < bound.simplex.n; ++m) {
            ray_cache->vertex_a[m] = bound.simplex.ia[m];
            ray_cache->vertex_b[m] = bound.simplex.ib[m];
        }
        ray_cache->direction[0] = -out->normal.x;
        ray_cache->direction[1] = -out->normal.y;
        ray_cache->direction[2] = -out->normal.z;
        ray_cache->feature_a = out->fa;
        ray_cache->feature_b = out->fb;
    }
}

/* Penetration depth of an intersecting pair: EPA from GJK's simplex (one is
 * computed when the method kept none), and when EPA's budget runs out the
 * exact depth along its best normal: a translation query of A along +n
 * (entry tau = -depth), whose contact points lie on both boundaries. */
static PXI_NOINLINE void penetration(const px_convex *a, const px_convex *b, const px_pose *t_ab,
                                     const pxi_simplex_pairs *method_simplex, pxi_penetration *pen,
                                     uint32_t *iterations, uint32_t *fallbacks, uint32_t *quality) {
    pxi_simplex_pairs simplex = *method_simplex;
    if (simplex.n < 4) {
        pxi_answer g;
        pxi_gjk_distance(a, b, t_ab, NULL, &g, &simplex);
        *iterations += g.iterations;
    }
    pxi_epa(a, b, t_ab, &simplex, pen);
    *iterations += pen->iterations;
    if (pen->outcome == PXI_UNPROVEN) *quality |= PX_QUALITY_UNPROVEN;
    if (pen->outcome != PXI_OUT_OF_STEPS) return;
    ++*fallbacks;
    *quality |= PX_QUALITY_DEPTH_BUDGET;
    pxi_translation tr;
    pxi_translation_query(a, b, t_ab, pen->normal, NULL, &tr, fallbacks);
    *iterations += tr.iterations;
    if (tr.hit && tr.tau <= 0.0) {
        pen->depth = -tr.tau;
        pen->pa = tr.pa;
        pen->pb = tr.pb;
        pen->fa = tr.fa;
        pen->fb = tr.fb;
    }
}

/* What every distance answer ends with: the cache keeps its features, and
 * the contact band, the same for every method (proxima/query.h), settles
 * what each method's own band (inside it) left separated. */
static inline void finish_answer(const px_convex *a, const px_convex *b, const px_pose *t_ab,
                                 px_pair_cache *cache, pxi_answer *out) {
    if (cache) {
        cache->feature_a = out->fa;
        cache->feature_b = out->fb;
    }
    if (!out->intersecting && out->distance <= PXI_CONTACT_BAND * pxi_pair_size_bound(a, b, t_ab) &&
        out->distance <= PXI_CONTACT_BAND * pxi_pair_size(a, b, t_ab)) {
        out->intersecting = 1;
        out->distance = 0.0;
        out->quality |= PX_QUALITY_CONTACT_BAND;
    }
}

/* Follows the table from step s, whose answer in out was not proved, until
 * an answer is (kept apart from the common path, which ends at the first
 * step). */
static PXI_NOINLINE void follow_table(const px_convex *a, const px_convex *b, const px_pose *t_ab,
                                      const pxi_policy *policy, step s, pxi_simplex_pairs *simplex,
                                      pxi_answer *out, uint32_t *fallbacks) {
    uint32_t iterations = out->iterations;
    pxi_answer prev;
    for (;;) {
        int seed = out->outcome == PXI_OUT_OF_STEPS && k_next[s].oos_is_seed;
        if (policy->accept_bound && !seed) {
            out->quality |= PX_QUALITY_UNPROVEN;
            break;
        }
        step next = out->outcome == PXI_UNPROVEN ? k_next[s].unproven : k_next[s].out_of_steps;
        if (!seed) ++*fallbacks;
        if (next == STEP_END) { /* the end of a row without a proof: the last answer, flagged */
            out->quality |= PX_QUALITY_UNPROVEN;
            out->outcome = PXI_DONE;
            break;
        }
        s = next;
        prev = *out;
        run_step(s, a, b, t_ab, NULL, &prev, simplex, out); /* fallbacks run cold */
        iterations += out->iterations;
        if (out->outcome == PXI_DONE) break;
    }
    out->iterations = iterations;
}

void pxi_distance_pair(const px_convex *a, const px_convex *b, const px_pose *t_ab, const pxi_policy *policy,
                       px_pair_cache *cache, pxi_answer *out, pxi_penetration *pen, uint32_t *fallbacks) {
    pxi_simplex_pairs simplex;
    simplex.n = 0;
    step s = first_step(policy->method, a, b, cache);
    /* Lin-Canny asked for a pair it cannot walk: handed to GJK, a fallback. */
    if (policy->method == PX_METHOD_LIN_CANNY && s == STEP_GJK_NW) ++*fallbacks;
    /* The first step answers into out directly: most queries end there. */
    run_step(s, a, b, t_ab, cache, NULL, &simplex, out);
    if (out->outcome != PXI_DONE) follow_table(a, b, t_ab, policy, s, &simplex, out, fallbacks);
    finish_answer(a, b, t_ab, cache, out);
    if (pen) pen->flat = 1; /* no depth unless computed below */
    if (!pen || !policy->signed_depth || !out->intersecting) return;
    if (policy->method != PX_METHOD_GJK) simplex.n = 0;
    penetration(a, b, t_ab, &simplex, pen, &out->iterations, fallbacks, &out->quality);
}

/* ---- Public entry points. ---- */

/* The method and flags of the options, checked: PX_ERR_INVALID_ARGUMENT for
 * an unknown method, a flag outside `allowed` or a reserved field set. */
static px_status read_options(const px_query_options *o, uint32_t allowed, uint32_t *method,
                              uint32_t *flags) {
    *method = PX_METHOD_LIN_CANNY;
    *flags = 0;
    if (!o) return PX_OK;
    uint32_t any = 0;
    for (size_t i = 0; i < sizeof o->reserved / sizeof o->reserved[0]; ++i) any |= o->reserved[i];
    if (any) return PX_ERR_INVALID_ARGUMENT;
    if (o->method > PX_METHOD_HYBRID || (o->flags & ~allowed)) return PX_ERR_INVALID_ARGUMENT;
    *method = o->method;
    *flags = o->flags;
    return PX_OK;
}

static px_status distance(const px_convex *a, const px_pose *pose_a, const px_convex *b,
                          const px_pose *pose_b, const px_query_options *options, px_pair_cache *cache,
                          px_distance_result *result, int poses_checked) {
    if (result) memset(result, 0, sizeof *result);
    if (!result) return PX_ERR_INVALID_ARGUMENT;
    uint32_t method, flags;
    px_status st = read_options(options, PX_QUERY_SIGNED, &method, &flags);
    if (st != PX_OK) return st;
    pair_frames fr;
    st = check_poses(a, pose_a, b, pose_b, poses_checked, &fr);
    if (st != PX_OK) return st;
    const px_pose *t_ab = &fr.t_ab;
    pxi_policy policy;
    memset(&policy, 0, sizeof policy);
    policy.method = method;
    policy.signed_depth = (flags & PX_QUERY_SIGNED) != 0;
    pxi_answer ans;
    pxi_penetration pen;
    uint32_t fallbacks = 0;
    pen.flat = 1;
    /* The table's first step for the most common query, a tracked unsigned
     * Lin-Canny distance, taken directly (the same step pxi_distance_pair
     * would take, without its dispatch); anything it does not prove goes
     * through the table from the start. */
    int done = 0;
    if (method == PX_METHOD_LIN_CANNY && !policy.signed_depth && cache && pair_walk_ok(a, b) &&
        pxi_feature_valid(a, cache->feature_a) && pxi_feature_valid(b, cache->feature_b)) {
        pxi_lc_start start = {cache->feature_a, cache->feature_b, 0, 0};
        pxi_lin_canny(a, b, t_ab, &start, &ans);
        done = ans.outcome == PXI_DONE;
        if (done) finish_answer(a, b, t_ab, cache, &ans);
    }
    if (!done) pxi_distance_pair(a, b, t_ab, &policy, cache, &ans, &pen, &fallbacks);
    result->distance = ans.distance;
    result->signed_distance = ans.distance;
    result->intersecting = ans.intersecting;
    result->feature_a = ans.fa;
    result->feature_b = ans.fb;
    result->diag.iterations = ans.iterations;
    result->diag.fallbacks = fallbacks;
    result->diag.quality = ans.quality;
    result->point_a = to_world(&fr, 0, ans.pa);
    if (!ans.intersecting) {
        result->point_b = to_world(&fr, 1, ans.pb);
        result->normal = separation_normal(a, b, &fr, &ans, pxi_sub(result->point_b, result->point_a));
        return PX_OK;
    }
    /* Intersecting: one common point, reported once (the two frames' copies
     * differ by rounding, or by the noise band of contact detection). */
    result->point_b = result->point_a;
    result->distance = 0.0;
    result->signed_distance = 0.0;
    if (pen.flat) return PX_OK; /* not asked, or A - B flat within rounding: touching, as reported */
    result->signed_distance = -pen.depth;
    result->point_a = to_world(&fr, 0, pen.pa);
    result->point_b = to_world(&fr, 1, pen.pb);
    result->normal = pen.depth > 0.0 ? pxi_rot(pose_b->r, pen.normal) : pxi_v(0, 0, 0);
    result->feature_a = pen.fa;
    result->feature_b = pen.fb;
    return PX_OK;
}

px_status px_distance(const px_convex *a, const px_pose *pose_a, const px_convex *b, const px_pose *pose_b,
                      const px_query_options *options, px_pair_cache *cache, px_distance_result *result) {
    return distance(a, pose_a, b, pose_b, options, cache, result, 0);
}

px_status pxi_distance_checked(const px_convex *a, const px_pose *pose_a, const px_convex *b,
                               const px_pose *pose_b, px_pair_cache *cache, px_distance_result *result) {
    return distance(a, pose_a, b, pose_b, NULL, cache, result, 1);
}

px_status px_intersect(const px_convex *a, const px_pose *pose_a, const px_convex *b, const px_pose *pose_b,
                       const px_query_options *options, px_pair_cache *cache, px_intersect_result *result) {
    if (result) memset(result, 0, sizeof *result);
    if (!result) return PX_ERR_INVALID_ARGUMENT;
    uint32_t method, flags;
    px_status st = read_options(options, 0u, &method, &flags);
    if (st != PX_OK) return st;
    pair_frames fr;
    st = check_pair(a, pose_a, b, pose_b, &fr);
    if (st != PX_OK) return st;
    const px_pose *t_ab = &fr.t_ab;
    uint32_t it = 0, quality = 0;
    int hit = 0;
    pxi_outcome oc = pxi_gjk_intersect(a, b, t_ab, cache, &hit, &it, &quality);
    result->intersecting = hit;
    result->diag.iterations = it;
    result->diag.quality = quality;
    if (oc == PXI_DONE) return PX_OK;
    /* Not proved either way (near contact between nearly coplanar facets):
     * the distance query decides, by the method asked for. */
    pxi_policy policy;
    memset(&policy, 0, sizeof policy);
    policy.method = method;
    pxi_answer ans;
    uint32_t fallbacks = 1;
    pxi_distance_pair(a, b, t_ab, &policy, NULL, &ans, NULL, &fallbacks);
    result->intersecting = ans.intersecting;
    result->diag.iterations += ans.iterations;
    result->diag.fallbacks = fallbacks;
    result->diag.quality = ans.quality;
    return PX_OK;
}

px_status px_translate(const px_convex *a, const px_pose *pose_a, const px_convex *b, const px_pose *pose_b,
                       px_vec3 direction, const px_query_options *options, px_pair_cache *cache,
                       px_translate_result *result) {
    if (result) memset(result, 0, sizeof *result);
    if (!result) return PX_ERR_INVALID_ARGUMENT;
    uint32_t method, flags;
    px_status st = read_options(options, PX_QUERY_BOTH_WAYS, &method, &flags);
    if (st != PX_OK) return st;
    if (!pxi_is_finite3(direction)) return PX_ERR_NON_FINITE;
    if (!(pxi_max_abs(direction) > 0.0)) return PX_ERR_INVALID_ARGUMENT;
    pair_frames fr;
    st = check_pair(a, pose_a, b, pose_b, &fr);
    if (st != PX_OK) return st;
    const px_pose *t_ab = &fr.t_ab;
    /* Scale the direction by 2^-e to max-norm in [1, 2) (exact, also for
     * subnormal lengths), so that its squared length can neither overflow
     * nor underflow; tau is rescaled at the end. */
    int e = ilogb(pxi_max_abs(direction));
    px_vec3 ds = pxi_v(ldexp(direction.x, -e), ldexp(direction.y, -e), ldexp(direction.z, -e));
    px_vec3 dir_b = pxi_rot_t(pose_b->r, ds);
    pxi_translation tr;
    uint32_t fallbacks = 0;
    pxi_translation_query(a, b, t_ab, dir_b, cache, &tr, &fallbacks);
    result->diag.iterations = tr.iterations;
    result->diag.fallbacks = fallbacks;
    result->diag.quality = tr.quality;
    /* Forward mode: is A in contact with B now? Certainly when the entry
     * point is behind A (tau < 0: A overlaps B, or B lies behind it), and
     * when it is ahead by less than the contact band (the distance now is at
     * most tau |d|). It is not when the contact plane's gap now, tau (n . d),
     * clears the band. In between (a grazing approach), and whenever the
     * entry is behind, the distance query at tau = 0 decides, so that every
     * query calls the same pairs touching. */
    int check_now = 0;
    if (!(flags & PX_QUERY_BOTH_WAYS)) {
        /* Lengths: tr.tau is in units of the scaled direction dir_b, so
         * tr.tau |dir_b| is the distance A travels, whatever |direction|. */
        double band = PXI_CONTACT_BAND * pxi_pair_size(a, b, t_ab);
        if (tr.hit) {
            double along = tr.tau * sqrt(pxi_dot(dir_b, dir_b)),
                   normal_gap = tr.tau * pxi_dot(tr.normal, dir_b);
            check_now = tr.tau < 0.0 || !(normal_gap > band);
            if (tr.tau >= 0.0 && along <= band) check_now = 1;
        } else {
            /* A miss whose line passes within the band of B: sliding along a
             * face A already touches. */
            check_now = !(tr.gap > band);
        }
    }
    if (check_now) {
        /* Either A touches B now (the time of impact is 0), or the whole
         * contact interval lies behind and A moving forward only gets
         * farther: then the distance at tau = 0 is the witness (its normal
         * has normal . direction <= 0, and the distance of A + tau d to B is
         * convex in tau, so it only grows). */
        pxi_policy policy;
        memset(&policy, 0, sizeof policy);
        policy.method = method;
        pxi_answer ans;
        pxi_distance_pair(a, b, t_ab, &policy, NULL, &ans, NULL, &result->diag.fallbacks);
        result->diag.iterations += ans.iterations;
        if (ans.intersecting || tr.tau < 0.0) {
            result->diag.quality = ans.quality;
            result->feature_a = ans.fa;
            result->feature_b = ans.fb;
            result->point_a = to_world(&fr, 0, ans.pa);
            if (ans.intersecting) {
                result->hit = 1;
                result->in_contact = 1;
                result->point_b = result->point_a;
                return PX_OK;
            }
            /* The witness: the plane of the closest features' normal (exact,
             * where the closest points' difference near contact is not),
             * through A's highest and B's lowest vertex along it; A moving
             * forward only leaves it (normal . d <= 0). */
            px_pose tt = *t_ab;
            px_vec3 n =
                pxi_feature_normal(a, b, t_ab, ans.fa, ans.fb, pxi_sub(ans.pb, pxi_xform(&tt, ans.pa)));
            uint32_t sa = pxi_support(a, pxi_rot_t(t_ab->r, n), UINT32_MAX),
                     sb = pxi_support(b, pxi_neg(n), UINT32_MAX);
            double gap = pxi_dot(n, pxi_sub(b->v[sb], pxi_xform(t_ab, a->v[sa])));
            if (gap > 0.0 && !(pxi_dot(n, dir_b) > 0.0)) {
                result->point_a = to_world(&fr, 0, a->v[sa]);
                result->point_b = to_world(&fr, 1, b->v[sb]);
                result->normal = pxi_rot(pose_b->r, n);
                result->gap = gap;
                result->feature_a = pxi_feature_of_vertices(a, &sa, 1, NULL);
                result->feature_b = pxi_feature_of_vertices(b, &sb, 1, NULL);
                return PX_OK;
            }
            result->point_b = to_world(&fr, 1, ans.pb);
            result->normal = unit_or_zero(pxi_sub(result->point_b, result->point_a));
            result->gap = ans.distance;
            result->diag.quality |= PX_QUALITY_UNPROVEN; /* the closest points' plane, not proved */
            return PX_OK;
        }
    }
    double tau = ldexp(tr.tau, -e);
    if (!isfinite(tau)) {
        memset(result, 0, sizeof *result);
        return PX_ERR_NON_FINITE; /* a direction so short that tau overflows */
    }
    result->hit = tr.hit;
    result->tau = tau;
    result->feature_a = tr.fa;
    result->feature_b = tr.fb;
    result->normal = pxi_rot(pose_b->r, tr.normal);
    result->gap = tr.gap;
    px_vec3 pa = to_world(&fr, 0, tr.pa);
    if (tr.hit) pa = pxi_madd(pa, ds, tr.tau); /* tau * direction, without overflow */
    result->point_a = pa;
    result->point_b = to_world(&fr, 1, tr.pb);
    return PX_OK;
}
