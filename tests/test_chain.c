/* px_chain (proxima/chain.h): articulated chains.
 *
 * Oracles:
 * - forward kinematics against a second implementation written here with
 *   quaternions (the library composes matrices with Rodrigues' formula),
 *   on random trees of revolute, prismatic and fixed joints;
 * - motion bounds against finite differences: every hull vertex of every
 *   link, at random configurations and joint velocities within the speed
 *   limits, moves no faster than speed + angular speed * its distance to
 *   the centre, and the link turns no faster than the angular speed;
 * - the scene against brute force: random chains with polytope links and
 *   static obstacles, moved by random joint trajectories within the
 *   limits; at every step the reported pairs are exactly the non-adjacent
 *   pairs within the report distance (px_distance over all pairs), with
 *   the same distances, and no link breaks its bounds;
 * - adjacency on a hand-made tree with links without geometry (MoveIt's
 *   rule), checked in the scene with every link overlapping every other;
 * - bad inputs: each refusal, its status and message, and that a failed
 *   px_chain_add_to_scene leaves no body behind (allocation failures). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "proxima/proxima.h"
#include "test_util.h"

#define PI 3.14159265358979323846

static uint64_t rng = 0x9E3779B97F4A7C15ull;
static double urand(void) {
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (double)(rng >> 11) * 0x1p-53;
}
static double srand1(void) { return 2 * urand() - 1; }

/* ---- The oracle: rigid transforms as (unit quaternion, translation) ---- */

typedef struct qt {
    double w, x, y, z;
    px_vec3 t;
} qt;

static qt qt_mul(qt a, qt b) {
    qt o;
    o.w = a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z;
    o.x = a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y;
    o.y = a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x;
    o.z = a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w;
    /* t = a.t + rot(a) b.t, by v' = v + 2w (u x v) + 2 u x (u x v) */
    px_vec3 u = {a.x, a.y, a.z}, v = b.t;
    px_vec3 c = {u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x};
    px_vec3 cc = {u.y * c.z - u.z * c.y, u.z * c.x - u.x * c.z, u.x * c.y - u.y * c.x};
    o.t.x = a.t.x + v.x + 2 * a.w * c.x + 2 * cc.x;
    o.t.y = a.t.y + v.y + 2 * a.w * c.y + 2 * cc.y;
    o.t.z = a.t.z + v.z + 2 * a.w * c.z + 2 * cc.z;
    return o;
}

static px_pose qt_pose(qt a) {
    double w = a.w, x = a.x, y = a.y, z = a.z;
    px_pose p;
    const double r[9] = {1 - 2 * (y * y + z * z), 2 * (x * y - w * z),     2 * (x * z + w * y),
                         2 * (x * y + w * z),     1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
                         2 * (x * z - w * y),     2 * (y * z + w * x),     1 - 2 * (x * x + y * y)};
    memcpy(p.r, r, sizeof r);
    p.t = a.t;
    return p;
}

static qt qt_random(double reach) {
    qt a;
    double n;
    do {
        a.w = srand1(), a.x = srand1(), a.y = srand1(), a.z = srand1();
        n = sqrt(a.w * a.w + a.x * a.x + a.y * a.y + a.z * a.z);
    } while (n < 0.1 || n > 1);
    a.w /= n, a.x /= n, a.y /= n, a.z /= n;
    a.t = (px_vec3){reach * srand1(), reach * srand1(), reach * srand1()};
    return a;
}

static qt qt_identity(void) { return (qt){1, 0, 0, 0, {0, 0, 0}}; }

/* A random chain: its description (as the library sees it) and the same in
 * quaternions (as the oracle sees it). */
#define MAXL 48
typedef struct rchain {
    uint32_t n, dof;
    px_link_desc link[MAXL];
    qt origin[MAXL], geometry[MAXL], base;
    px_vec3 unit_axis[MAXL];
} rchain;

static void random_chain(rchain *c, uint32_t n, double p_fixed, double p_prismatic, int chainlike) {
    memset(c, 0, sizeof *c);
    c->n = n;
    c->base = qt_random(1.0);
    for (uint32_t k = 0; k < n; ++k) {
        px_link_desc *l = &c->link[k];
        if (k == 0 || (!chainlike && urand() < 0.15))
            l->parent = PX_CHAIN_ROOT;
        else
            l->parent = chainlike ? k - 1 : (uint32_t)(urand() * k);
        double u = urand();
        l->joint = u < p_fixed                 ? PX_JOINT_FIXED
                   : u < p_fixed + p_prismatic ? PX_JOINT_PRISMATIC
                                               : PX_JOINT_REVOLUTE;
        c->origin[k] = qt_random(0.5);
        c->geometry[k] = qt_random(0.2);
        l->origin = qt_pose(c->origin[k]);
        l->geometry = qt_pose(c->geometry[k]);
        /* Axes of any length (normalised by the library). */
        px_vec3 a;
        double m;
        do {
            a = (px_vec3){srand1(), srand1(), srand1()};
            m = sqrt(a.x * a.x + a.y * a.y + a.z * a.z);
        } while (m < 0.1 || m > 1);
        double s = ldexp(1.0, (int)(urand() * 20) - 10);
        l->axis = (px_vec3){a.x * s, a.y * s, a.z * s};
        c->unit_axis[k] = (px_vec3){a.x / m, a.y / m, a.z / m};
        if (l->joint == PX_JOINT_PRISMATIC) {
            l->q_min = -0.3 * urand();
            l->q_max = 0.3 * urand();
            l->max_speed = 0.5 * urand();
        } else if (l->joint == PX_JOINT_REVOLUTE) {
            int continuous = urand() < 0.2;
            l->q_min = continuous ? -INFINITY : -PI * urand();
            l->q_max = continuous ? INFINITY : PI * urand();
            l->max_speed = 2 * urand();
        }
        if (l->joint != PX_JOINT_FIXED) c->dof++;
    }
}

static px_chain *make_chain(const rchain *c, px_error *err) {
    px_chain_desc d;
    memset(&d, 0, sizeof d);
    d.links = c->link;
    d.n_links = c->n;
    d.base = qt_pose(c->base);
    return px_chain_create(&d, err);
}

static void random_q(const rchain *c, double *q) {
    for (uint32_t k = 0, i = 0; k < c->n; ++k) {
        const px_link_desc *l = &c->link[k];
        if (l->joint == PX_JOINT_FIXED) continue;
        double lo = isfinite(l->q_min) ? l->q_min : -10, hi = isfinite(l->q_max) ? l->q_max : 10;
        q[i++] = lo + (hi - lo) * urand();
    }
}

/* The oracle's forward kinematics: geometry poses. */
static void oracle_forward(const rchain *c, const double *q, px_pose *geometry) {
    qt frame[MAXL];
    for (uint32_t k = 0, i = 0; k < c->n; ++k) {
        const px_link_desc *l = &c->link[k];
        qt parent = l->parent == PX_CHAIN_ROOT ? c->base : frame[l->parent];
        qt j = qt_identity();
        px_vec3 a = c->unit_axis[k];
        if (l->joint == PX_JOINT_REVOLUTE) {
            double h = q[i] / 2;
            j.w = cos(h), j.x = sin(h) * a.x, j.y = sin(h) * a.y, j.z = sin(h) * a.z;
        } else if (l->joint == PX_JOINT_PRISMATIC) {
            j.t = (px_vec3){q[i] * a.x, q[i] * a.y, q[i] * a.z};
        }
        if (l->joint != PX_JOINT_FIXED) i++;
        frame[k] = qt_mul(qt_mul(parent, c->origin[k]), j);
        /* A link without geometry: its geometry frame is ignored (its frame). */
        int shape = l->model || l->convex;
        geometry[k] = qt_pose(shape ? qt_mul(frame[k], c->geometry[k]) : frame[k]);
    }
}

static double pose_diff(const px_pose *a, const px_pose *b) {
    double d = fmax(fabs(a->t.x - b->t.x), fmax(fabs(a->t.y - b->t.y), fabs(a->t.z - b->t.z)));
    for (int i = 0; i < 9; ++i) d = fmax(d, fabs(a->r[i] - b->r[i]));
    return d;
}

static px_convex *random_polytope(double r);

static void test_forward(void) {
    double worst = 0;
    px_convex *shape = random_polytope(0.3); /* links with geometry place it; the others ignore theirs */
    int chains = tu_scaled(300);
    for (int it = 0; it < chains; ++it) {
        rchain c;
        random_chain(&c, 1 + (uint32_t)(urand() * MAXL), 0.25, 0.25, it % 2);
        for (uint32_t k = 0; k < c.n; ++k) c.link[k].convex = urand() < 0.7 ? shape : NULL;
        px_error err;
        px_chain *ch = make_chain(&c, &err);
        CHECK(ch != NULL, "create: %s", err.message);
        if (!ch) continue;
        CHECK(px_chain_dof(ch) == c.dof && px_chain_link_count(ch) == c.n, "dof %u (want %u)",
              px_chain_dof(ch), c.dof);
        for (uint32_t i = 0, k = 0; k < c.n; ++k)
            if (c.link[k].joint != PX_JOINT_FIXED) {
                CHECK(px_chain_joint_link(ch, i) == k, "joint %u's link %u, want %u", i,
                      px_chain_joint_link(ch, i), k);
                i++;
            }
        CHECK(px_chain_joint_link(ch, c.dof) == PX_CHAIN_ROOT, "joint past the last");
        for (int n = 0; n < 10; ++n) {
            double q[MAXL];
            random_q(&c, q);
            px_pose want[MAXL], got[MAXL], got2[MAXL], frames[MAXL];
            oracle_forward(&c, q, want);
            CHECK(px_chain_forward(ch, q, frames, got, &err) == PX_OK, "forward: %s", err.message);
            /* Without frames (scratch inside the library): the same bits. */
            CHECK(px_chain_forward(ch, q, NULL, got2, &err) == PX_OK, "forward: %s", err.message);
            CHECK(memcmp(got, got2, c.n * sizeof *got) == 0, "forward without frames differs");
            for (uint32_t k = 0; k < c.n; ++k) {
                double d = pose_diff(&want[k], &got[k]);
                worst = fmax(worst, d);
                CHECK(px_pose_check(&got[k], NULL) == PX_OK, "link %u's pose is not a rotation", k);
            }
        }
        px_chain_destroy(ch);
    }
    px_convex_destroy(shape);
    CHECK(worst <= 1e-12, "forward kinematics differ from the quaternion oracle's by %g", worst);
    printf("forward: %d random chains (up to %d links), poses within %.1e of the quaternion oracle\n", chains,
           MAXL, worst);
}

/* A random small polytope (hull of 12 points within radius r). */
static px_convex *random_polytope(double r) {
    double xyz[36];
    for (int i = 0; i < 36; ++i) xyz[i] = r * srand1();
    px_error err;
    px_convex *p = px_convex_create(xyz, 12, NULL, &err);
    CHECK(p != NULL, "polytope: %s", err.message);
    return p;
}

static double dist3(px_vec3 a, px_vec3 b) {
    return sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) + (a.z - b.z) * (a.z - b.z));
}

/* Rotation angle of R2 R1^T, from |R2 - R1|_F = 2 sqrt(2) sin(angle / 2)
 * (well conditioned for small angles, unlike the trace's acos). */
static double turn_angle(const px_pose *p1, const px_pose *p2) {
    double f = 0;
    for (int i = 0; i < 9; ++i) f += (p2->r[i] - p1->r[i]) * (p2->r[i] - p1->r[i]);
    return 2 * asin(fmin(1.0, sqrt(f) / (2 * sqrt(2.0))));
}

static void test_bounds(void) {
    double worst = 0, tight = 0;
    int chains = tu_scaled(200);
    for (int it = 0; it < chains; ++it) {
        rchain c;
        random_chain(&c, 1 + (uint32_t)(urand() * 12), 0.2, 0.3, it % 2);
        px_convex *poly[MAXL];
        for (uint32_t k = 0; k < c.n; ++k) c.link[k].convex = poly[k] = random_polytope(0.3);
        px_error err;
        px_chain *ch = make_chain(&c, &err);
        CHECK(ch != NULL, "create: %s", err.message);
        for (int n = 0; ch && n < 20; ++n) {
            double q[MAXL], q2[MAXL], h = 1e-7;
            random_q(&c, q);
            for (uint32_t k = 0, i = 0; k < c.n; ++k) {
                const px_link_desc *l = &c.link[k];
                if (l->joint == PX_JOINT_FIXED) continue;
                q2[i] = q[i] + h * l->max_speed * (urand() < 0.5 ? -1 : 1) * (0.5 + 0.5 * urand());
                q2[i] = fmin(fmax(q2[i], l->q_min), l->q_max);
                i++;
            }
            px_pose p1[MAXL], p2[MAXL];
            if (px_chain_forward(ch, q, NULL, p1, &err) != PX_OK ||
                px_chain_forward(ch, q2, NULL, p2, &err) != PX_OK) {
                CHECK(0, "forward: %s", err.message);
                break;
            }
            for (uint32_t k = 0; k < c.n; ++k) {
                px_vec3 center;
                double v, w;
                CHECK(px_chain_motion_bounds(ch, k, &center, &v, &w, &err) == PX_OK, "bounds: %s",
                      err.message);
                CHECK(isfinite(v) && isfinite(w), "link %u: infinite bounds %g %g with finite limits", k, v,
                      w);
                worst = fmax(worst, turn_angle(&p1[k], &p2[k]) / h - w);
                for (uint32_t i = 0; i < px_convex_vertex_count(poly[k]); ++i) {
                    px_vec3 x;
                    px_convex_vertex(poly[k], i, &x);
                    double moved = dist3(px_pose_apply(&p1[k], x), px_pose_apply(&p2[k], x)) / h;
                    double bound = v + w * dist3(x, center);
                    worst = fmax(worst, moved - bound);
                    if (bound > 0) tight = fmax(tight, moved / bound);
                }
            }
        }
        px_chain_destroy(ch);
        for (uint32_t k = 0; k < c.n; ++k) px_convex_destroy(poly[k]);
    }
    CHECK(worst <= 1e-6, "a link point moves %g faster than its bound", worst);
    CHECK(tight > 0.3, "the bounds are never approached (largest ratio %g): too loose to be useful?", tight);
    printf(
        "bounds: %d random chains, no point faster than its bound (worst excess %.1e; largest speed / bound "
        "%.2f)\n",
        chains, worst, tight);
}

/* A scene of a random chain with polytope links and static obstacles along
 * a random joint trajectory, against brute force at every step. */
#define MARGIN 0.01
#define REPORT 0.05
static void test_scene(void) {
    int runs = tu_scaled(12), steps = tu_sanitized() ? 60 : 150, mismatches = 0, violations = 0;
    uint64_t reported = 0, checked_total = 0, pair_steps = 0;
    for (int run = 0; run < runs; ++run) {
        rchain c;
        random_chain(&c, 4 + (uint32_t)(urand() * 10), 0.15, 0.25, run % 3 != 0);
        c.base = qt_identity();
        px_convex *poly[MAXL];
        for (uint32_t k = 0; k < c.n; ++k) {
            c.link[k].convex = poly[k] = urand() < 0.15 ? NULL : random_polytope(0.35);
            c.link[k].user = &poly[k];
        }
        px_error err;
        px_chain *ch = make_chain(&c, &err);
        px_scene_options so;
        memset(&so, 0, sizeof so);
        so.margin = MARGIN;
        so.report_distance = REPORT;
        so.threads = run % 2 ? 2 : 1;
        px_scene *s = px_scene_create(&so, &err);
        double q[MAXL], qd[MAXL];
        random_q(&c, q);
        uint32_t ids[MAXL];
        CHECK(ch && s && px_chain_add_to_scene(ch, s, q, ids, &err) == PX_OK, "setup: %s", err.message);
        if (!ch || !s) {
            px_chain_destroy(ch);
            px_scene_destroy(s);
            continue;
        }
        /* Obstacles around the chain. */
        enum { NOBS = 6 };
        px_convex *obs[NOBS];
        px_pose obs_pose[NOBS];
        uint32_t obs_id[NOBS];
        for (int o = 0; o < NOBS; ++o) {
            obs[o] = random_polytope(0.4);
            obs_pose[o] = qt_pose(qt_random(1.2));
            px_body_desc bd;
            memset(&bd, 0, sizeof bd);
            bd.convex = obs[o];
            bd.pose = obs_pose[o];
            bd.flags = PX_BODY_STATIC;
            CHECK(px_scene_add_body(s, &bd, &obs_id[o], &err) == PX_OK, "obstacle: %s", err.message);
        }
        for (uint32_t k = 0; k < c.n; ++k) {
            CHECK((ids[k] == PX_CHAIN_NO_BODY) == (poly[k] == NULL), "link %u: body %u", k, ids[k]);
            if (ids[k] != PX_CHAIN_NO_BODY)
                CHECK(px_scene_body_user(s, ids[k]) == &poly[k], "link %u: user pointer", k);
        }
        /* Random joint velocities within the limits, bouncing at the
         * joint limits, renewed now and then. */
        double dt = 0.02;
        for (int step = 0; step < steps; ++step) {
            for (uint32_t k = 0, i = 0; k < c.n; ++k) {
                const px_link_desc *l = &c.link[k];
                if (l->joint == PX_JOINT_FIXED) continue;
                if (step % 25 == 0) qd[i] = l->max_speed * srand1();
                double nq = q[i] + qd[i] * dt;
                if (nq < l->q_min || nq > l->q_max) {
                    qd[i] = -qd[i];
                    nq = fmin(fmax(nq, l->q_min), l->q_max);
                }
                q[i++] = nq;
            }
            CHECK(px_chain_set_joints(ch, s, ids, q, &err) == PX_OK, "set: %s", err.message);
            CHECK(px_scene_step(s, step * dt, &err) == PX_OK, "step: %s", err.message);
            px_scene_stats st;
            px_scene_get_stats(s, &st);
            violations += (int)st.violations;
            checked_total += st.pairs_checked;
            /* Brute force over all pairs of bodies. */
            px_pose g[MAXL];
            px_chain_forward(ch, q, NULL, g, &err);
            uint32_t nb = 0, body[MAXL + NOBS], link_of[MAXL + NOBS];
            const px_convex *shape[MAXL + NOBS];
            px_pose pose[MAXL + NOBS];
            for (uint32_t k = 0; k < c.n; ++k)
                if (poly[k]) body[nb] = ids[k], link_of[nb] = k, shape[nb] = poly[k], pose[nb++] = g[k];
            for (int o = 0; o < NOBS; ++o)
                body[nb] = obs_id[o], link_of[nb] = UINT32_MAX, shape[nb] = obs[o], pose[nb++] = obs_pose[o];
            size_t np;
            const px_scene_pair *pairs = px_scene_pairs(s, &np);
            size_t want = 0;
            for (uint32_t x = 0; x < nb; ++x)
                for (uint32_t y = x + 1; y < nb; ++y) {
                    int adjacent = link_of[x] != UINT32_MAX && link_of[y] != UINT32_MAX &&
                                   px_chain_adjacent(ch, link_of[x], link_of[y]);
                    pair_steps++;
                    px_distance_result r;
                    px_distance(shape[x], &pose[x], shape[y], &pose[y], NULL, NULL, &r);
                    uint32_t a = body[x] < body[y] ? body[x] : body[y], b = body[x] ^ body[y] ^ a;
                    const px_scene_pair *found = NULL;
                    for (size_t m = 0; m < np; ++m)
                        if (pairs[m].body_a == a && pairs[m].body_b == b) found = &pairs[m];
                    int should = !adjacent && r.distance <= REPORT;
                    want += should;
                    if (should != (found != NULL) || (found && !(fabs(found->distance - r.distance) <= 1e-9 &&
                                                                 found->contact == (r.distance <= MARGIN)))) {
                        if (mismatches++ < 5)
                            fprintf(
                                stderr,
                                "run %d step %d: pair %u-%u (links %u, %u; adjacent %d): brute force %.17g, "
                                "scene %s %.17g\n",
                                run, step, a, b, link_of[x], link_of[y], adjacent, r.distance,
                                found ? "reports" : "does not report", found ? found->distance : NAN);
                    }
                }
            CHECK(np == want, "run %d step %d: %zu reported, brute force %zu", run, step, np, want);
            reported += np;
        }
        px_scene_destroy(s);
        px_chain_destroy(ch);
        for (uint32_t k = 0; k < c.n; ++k) px_convex_destroy(poly[k]);
        for (int o = 0; o < NOBS; ++o) px_convex_destroy(obs[o]);
    }
    CHECK(mismatches == 0, "%d pair-steps differ from brute force", mismatches);
    CHECK(violations == 0, "%d link-steps broke px_chain's motion bounds", violations);
    CHECK(reported > 0, "no pair ever came within the report distance: the test tests nothing");
    printf(
        "scene: %d chains x %d steps, reports equal to brute force over %llu pair-steps (%llu reported, %llu "
        "narrow-phase queries); no bound broken\n",
        runs, steps, (unsigned long long)pair_steps, (unsigned long long)reported,
        (unsigned long long)checked_total);
}

/* Adjacency on a hand-made tree. Links (g: geometry, -: none):
 *   0 A g  root        3 D g  child of 1     6 G g  child of 5
 *   1 B -  child of 0  4 E g  child of 2     7 H g  child of 6 (prismatic)
 *   2 C g  child of 1  5 F -  root
 * Adjacent: each link and its nearest ancestor with geometry: C-A and D-A
 * (through B), E-C, H-G. Not: C-D (siblings through B), A-G (roots through
 * F and the base). Every link is a unit cube at the origin, so every pair
 * overlaps: the scene must report exactly the others. */
static void test_adjacency(void) {
    static const uint32_t parent[8] = {PX_CHAIN_ROOT, 0, 1, 1, 2, PX_CHAIN_ROOT, 5, 6};
    static const int geo[8] = {1, 0, 1, 1, 1, 0, 1, 1};
    static const int want[8][8] = {
        {0, 0, 1, 1, 0, 0, 0, 0}, {0}, {1, 0, 0, 0, 1, 0, 0, 0}, {1, 0, 0, 0, 0, 0, 0, 0},
        {0, 0, 1, 0, 0, 0, 0, 0}, {0}, {0, 0, 0, 0, 0, 0, 0, 1}, {0, 0, 0, 0, 0, 0, 1, 0},
    };
    const double cube[24] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 0, 1, 1, 0, 1, 0, 1, 1, 1, 1, 1};
    px_error err;
    px_convex *box = px_convex_create(cube, 8, NULL, &err);
    px_link_desc l[8];
    memset(l, 0, sizeof l);
    for (int k = 0; k < 8; ++k) {
        l[k].parent = parent[k];
        l[k].joint = k == 7 ? PX_JOINT_PRISMATIC : k == 2 || k == 6 ? PX_JOINT_REVOLUTE : PX_JOINT_FIXED;
        l[k].origin = px_pose_identity();
        if (geo[k]) l[k].geometry = px_pose_identity(); /* (ignored without geometry: left zero) */
        l[k].axis = (px_vec3){0, 0, 1};
        l[k].q_min = -1;
        l[k].q_max = 1;
        l[k].max_speed = 1;
        l[k].convex = geo[k] ? box : NULL;
    }
    px_chain_desc d;
    memset(&d, 0, sizeof d);
    d.links = l;
    d.n_links = 8;
    d.base = px_pose_identity();
    px_chain *c = px_chain_create(&d, &err);
    CHECK(c != NULL, "create: %s", err.message);
    if (!c) {
        px_convex_destroy(box);
        return;
    }
    for (uint32_t a = 0; a < 8; ++a)
        for (uint32_t b = 0; b < 8; ++b)
            CHECK(px_chain_adjacent(c, a, b) == want[a][b], "links %u, %u: adjacent %d, want %d", a, b,
                  px_chain_adjacent(c, a, b), want[a][b]);
    CHECK(!px_chain_adjacent(c, 0, 99) && !px_chain_adjacent(NULL, 0, 2), "unknown links are not adjacent");
    px_scene_options so;
    memset(&so, 0, sizeof so);
    px_scene *s = px_scene_create(&so, &err);
    uint32_t ids[8];
    double q[3] = {0.5, -0.25, 0.0};
    CHECK(px_chain_add_to_scene(c, s, q, ids, &err) == PX_OK, "add: %s", err.message);
    CHECK(px_scene_step(s, 0, &err) == PX_OK, "step: %s", err.message);
    /* Links 0 and 5's subtree: 0 and 3 hang on fixed joints only: static. */
    px_error e2;
    CHECK(px_scene_set_pose(s, ids[0], &l[0].origin, &e2) == PX_ERR_INVALID_ARGUMENT &&
              px_scene_set_pose(s, ids[3], &l[0].origin, &e2) == PX_ERR_INVALID_ARGUMENT,
          "links on fixed joints only are static bodies");
    size_t np;
    const px_scene_pair *pairs = px_scene_pairs(s, &np);
    int seen[8][8];
    memset(seen, 0, sizeof seen);
    for (size_t m = 0; m < np; ++m) {
        int x = -1, y = -1;
        for (int k = 0; k < 8; ++k) {
            if (geo[k] && ids[k] == pairs[m].body_a) x = k;
            if (geo[k] && ids[k] == pairs[m].body_b) y = k;
        }
        CHECK(x >= 0 && y >= 0 && !want[x][y], "pair %d-%d reported", x, y);
        if (x >= 0 && y >= 0) seen[x][y] = seen[y][x] = 1;
    }
    for (int x = 0; x < 8; ++x)
        for (int y = x + 1; y < 8; ++y)
            if (geo[x] && geo[y] && !want[x][y])
                CHECK(seen[x][y], "overlapping pair %d-%d not reported", x, y);
    px_scene_destroy(s);
    px_chain_destroy(c);
    px_convex_destroy(box);
}

/* An allocator that fails after `left` allocations. */
typedef struct failing {
    int left;
} failing;
static void *f_alloc(void *u, size_t n) {
    failing *f = u;
    if (f->left-- <= 0) return NULL;
    return malloc(n);
}
static void f_free(void *u, void *p, size_t n) {
    (void)u;
    (void)n;
    free(p);
}

static void expect(px_status got, px_status want, const px_error *err, const char *what) {
    CHECK(got == want, "%s: %s, want %s (%s)", what, px_status_string(got), px_status_string(want),
          err->message);
    CHECK(got == PX_OK || err->message[0], "%s: no message", what);
}

static void test_bad_inputs(void) {
    const double cube[24] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 0, 1, 1, 0, 1, 0, 1, 1, 1, 1, 1};
    px_error err;
    px_convex *box = px_convex_create(cube, 8, NULL, &err);
    px_link_desc good[3];
    memset(good, 0, sizeof good);
    for (int k = 0; k < 3; ++k) {
        good[k].parent = k ? (uint32_t)k - 1 : PX_CHAIN_ROOT;
        good[k].joint = k ? PX_JOINT_REVOLUTE : PX_JOINT_FIXED;
        good[k].origin = good[k].geometry = px_pose_identity();
        good[k].origin.t = (px_vec3){0, 0, k ? 1.0 : 0.0};
        good[k].axis = (px_vec3){1, 0, 0};
        good[k].q_min = -1;
        good[k].q_max = 1;
        good[k].max_speed = 1;
        good[k].convex = box;
    }
    px_chain_desc d;
    memset(&d, 0, sizeof d);
    d.links = good;
    d.n_links = 3;
    d.base = px_pose_identity();
    px_chain *c = px_chain_create(&d, &err);
    CHECK(c != NULL, "the good chain: %s", err.message);
    /* Each broken in one way. */
    struct {
        const char *what;
        int link;
        px_status want;
    } cases[] = {
        {"parent is itself", 1, PX_ERR_INVALID_ARGUMENT},
        {"parent is later", 2, PX_ERR_INVALID_ARGUMENT},
        {"joint type 3", 1, PX_ERR_INVALID_ARGUMENT},
        {"zero axis", 1, PX_ERR_INVALID_ARGUMENT},
        {"NaN axis", 1, PX_ERR_NON_FINITE},
        {"infinite axis", 1, PX_ERR_NON_FINITE},
        {"reversed limits", 1, PX_ERR_INVALID_ARGUMENT},
        {"NaN limit", 1, PX_ERR_INVALID_ARGUMENT},
        {"limits both +inf", 1, PX_ERR_INVALID_ARGUMENT},
        {"negative speed", 1, PX_ERR_INVALID_ARGUMENT},
        {"NaN speed", 1, PX_ERR_INVALID_ARGUMENT},
        {"model and polytope", 1, PX_ERR_INVALID_ARGUMENT},
        {"origin not a rotation", 1, PX_ERR_INVALID_POSE},
        {"geometry NaN", 2, PX_ERR_NON_FINITE},
        {"origin beyond 2^250", 1, PX_ERR_RANGE},
        {"reserved", 0, PX_ERR_INVALID_ARGUMENT},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; ++i) {
        px_link_desc l[3];
        memcpy(l, good, sizeof l);
        px_link_desc *b = &l[cases[i].link];
        switch (i) {
        case 0: b->parent = 1; break;
        case 1: b->parent = 2; break;
        case 2: b->joint = 3; break;
        case 3: b->axis = (px_vec3){0, 0, 0}; break;
        case 4: b->axis.y = NAN; break;
        case 5: b->axis.z = INFINITY; break;
        case 6: b->q_min = 1, b->q_max = -1; break;
        case 7: b->q_max = NAN; break;
        case 8: b->q_min = b->q_max = INFINITY; break;
        case 9: b->max_speed = -1; break;
        case 10: b->max_speed = NAN; break;
        case 11: b->model = (const px_model *)box; break;
        case 12: b->origin.r[0] = 2; break;
        case 13: b->geometry.t.x = NAN; break;
        case 14: b->origin.t.x = 0x1p260; break;
        case 15: b->reserved[2] = 1; break;
        }
        px_chain_desc dd = d;
        dd.links = l;
        px_chain *bad = px_chain_create(&dd, &err);
        CHECK(bad == NULL, "%s: accepted", cases[i].what);
        expect(err.code, cases[i].want, &err, cases[i].what);
        if (cases[i].link > 0 && err.code != PX_OK) {
            char tag[32];
            snprintf(tag, sizeof tag, "link %d", cases[i].link);
            CHECK(strstr(err.message, tag) != NULL, "%s: the message does not name %s: %s", cases[i].what,
                  tag, err.message);
        }
        px_chain_destroy(bad);
    }
    /* The description itself. */
    px_chain_desc dd = d;
    CHECK(px_chain_create(NULL, &err) == NULL && err.code == PX_ERR_INVALID_ARGUMENT, "NULL desc");
    dd.n_links = 0;
    CHECK(px_chain_create(&dd, &err) == NULL && err.code == PX_ERR_INVALID_ARGUMENT, "no links");
    dd = d;
    dd.links = NULL;
    CHECK(px_chain_create(&dd, &err) == NULL && err.code == PX_ERR_INVALID_ARGUMENT, "NULL links");
    dd = d;
    dd.base.r[4] = NAN;
    CHECK(px_chain_create(&dd, &err) == NULL && err.code == PX_ERR_NON_FINITE, "NaN base: %s", err.message);
    dd = d;
    dd.reserved0 = 1;
    CHECK(px_chain_create(&dd, &err) == NULL && err.code == PX_ERR_INVALID_ARGUMENT, "reserved0");
    dd = d;
    dd.n_links = PX_CHAIN_MAX_LINKS + 1;
    CHECK(px_chain_create(&dd, &err) == NULL && err.code == PX_ERR_INVALID_ARGUMENT, "too many links");
    /* The largest chain: 1,024 links in a line (the scratch beyond the
     * stack), all turning: forward works and the far end is 1,023 away. */
    {
        px_link_desc *big = calloc(PX_CHAIN_MAX_LINKS, sizeof *big);
        double *q = calloc(PX_CHAIN_MAX_LINKS, sizeof *q);
        px_pose *g = calloc(PX_CHAIN_MAX_LINKS, sizeof *g);
        for (uint32_t k = 0; k < PX_CHAIN_MAX_LINKS; ++k) {
            big[k] = good[k ? 1 : 0];
            big[k].parent = k ? k - 1 : PX_CHAIN_ROOT;
            big[k].joint = PX_JOINT_REVOLUTE;
            big[k].axis = (px_vec3){0, 0, 1};
        }
        dd = d;
        dd.links = big;
        dd.n_links = PX_CHAIN_MAX_LINKS;
        px_chain *bc = px_chain_create(&dd, &err);
        CHECK(bc && px_chain_forward(bc, q, NULL, g, &err) == PX_OK, "1,024 links: %s", err.message);
        if (bc)
            CHECK(fabs(g[PX_CHAIN_MAX_LINKS - 1].t.z - 1023) < 1e-9, "far end at %g",
                  g[PX_CHAIN_MAX_LINKS - 1].t.z);
        double v = 0;
        px_chain_motion_bounds(bc, PX_CHAIN_MAX_LINKS - 1, NULL, &v, NULL, &err);
        CHECK(v > 0 && isfinite(v), "far end's speed bound %g", v);
        px_chain_destroy(bc);
        free(big);
        free(q);
        free(g);
    }
    /* Joint values and the scene calls. */
    double q[2] = {0.5, 1.5};
    px_pose g[3];
    expect(px_chain_forward(c, q, NULL, g, &err), PX_ERR_RANGE, &err, "q beyond a limit");
    CHECK(strstr(err.message, "joint value 1") != NULL, "the message names the joint: %s", err.message);
    q[1] = -INFINITY;
    expect(px_chain_forward(c, q, NULL, g, &err), PX_ERR_NON_FINITE, &err, "infinite q");
    expect(px_chain_forward(c, NULL, NULL, g, &err), PX_ERR_INVALID_ARGUMENT, &err, "NULL q");
    expect(px_chain_forward(NULL, q, NULL, g, &err), PX_ERR_INVALID_ARGUMENT, &err, "NULL chain");
    expect(px_chain_motion_bounds(c, 3, NULL, NULL, NULL, &err), PX_ERR_INVALID_ARGUMENT, &err,
           "unknown link");
    q[1] = 0.5;
    px_scene_options so;
    memset(&so, 0, sizeof so);
    px_scene *s = px_scene_create(&so, &err);
    uint32_t ids[3];
    CHECK(px_chain_add_to_scene(c, s, q, ids, &err) == PX_OK, "add: %s", err.message);
    CHECK(px_scene_step(s, 0, &err) == PX_OK, "step: %s", err.message);
    q[0] = 2;
    expect(px_chain_set_joints(c, s, ids, q, &err), PX_ERR_RANGE, &err, "set beyond a limit");
    q[0] = 0.25;
    uint32_t wrong[3] = {ids[0], ids[1], 77};
    expect(px_chain_set_joints(c, s, wrong, q, &err), PX_ERR_INVALID_ARGUMENT, &err, "unknown body");
    uint32_t stat[3] = {ids[0], ids[0], ids[2]};
    expect(px_chain_set_joints(c, s, stat, q, &err), PX_ERR_INVALID_ARGUMENT, &err, "a static body");
    /* Nothing moved by the failed calls: the step measures no motion. */
    CHECK(px_scene_step(s, 1, &err) == PX_OK, "step: %s", err.message);
    px_scene_stats st;
    px_scene_get_stats(s, &st);
    CHECK(st.moved == 0, "failed px_chain_set_joints moved %u bodies", st.moved);
    CHECK(px_chain_set_joints(c, s, ids, q, &err) == PX_OK, "set: %s", err.message);
    expect(px_chain_add_to_scene(c, NULL, q, ids, &err), PX_ERR_INVALID_ARGUMENT, &err, "NULL scene");
    px_scene_destroy(s);
    /* Allocation failures in px_chain_create and px_chain_add_to_scene:
     * NULL or the chain, and a failed add leaves no body. */
    int oom = 0;
    for (int left = 0; left < 40; ++left) {
        failing f = {left};
        px_allocator a = {f_alloc, f_free, &f};
        dd = d;
        dd.allocator = &a;
        px_chain *fc = px_chain_create(&dd, &err);
        if (!fc) {
            CHECK(err.code == PX_ERR_OUT_OF_MEMORY, "create with %d allocations: %s", left, err.message);
            continue;
        }
        px_chain_destroy(fc);
        failing fs = {left};
        px_allocator as = {f_alloc, f_free, &fs};
        memset(&so, 0, sizeof so);
        so.allocator = &as;
        s = px_scene_create(&so, &err);
        if (!s) continue;
        px_status r = px_chain_add_to_scene(c, s, q, ids, &err);
        px_scene_step(s, 0, &err);
        px_scene_get_stats(s, &st);
        if (r != PX_OK) {
            oom++;
            CHECK(r == PX_ERR_OUT_OF_MEMORY, "add with %d allocations: %s", left, err.message);
            CHECK(st.bodies == 0, "a failed add left %u bodies", st.bodies);
            for (int k = 0; k < 3; ++k)
                CHECK(ids[k] == PX_CHAIN_NO_BODY, "a failed add left ids[%d] = %u", k, ids[k]);
        } else {
            CHECK(st.bodies == 3, "add: %u bodies", st.bodies);
        }
        px_scene_destroy(s);
    }
    CHECK(oom > 0, "no allocation failure reached px_chain_add_to_scene");
    px_chain_destroy(c);
    px_chain_destroy(NULL);
    px_convex_destroy(box);
}

/* The review's cases: frames and geometry in one array (the same answer
 * as apart), and a mobile base (prismatic root links without geometry)
 * driven into a table fixed to the base: their contact is reported (the
 * two are not adjacent). */
static void test_review_cases(void) {
    const double cube[24] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 0, 1, 1, 0, 1, 0, 1, 1, 1, 1, 1};
    px_error err;
    px_convex *box = px_convex_create(cube, 8, NULL, &err);
    /* 0 table (fixed root), 1 rail x (prismatic root, no geometry), 2 rail
     * y (prismatic, no geometry), 3 chassis. */
    px_link_desc l[4];
    memset(l, 0, sizeof l);
    for (int k = 0; k < 4; ++k) {
        l[k].parent = k == 0 || k == 1 ? PX_CHAIN_ROOT : (uint32_t)k - 1;
        l[k].joint = k == 1 || k == 2 ? PX_JOINT_PRISMATIC : PX_JOINT_FIXED;
        l[k].origin = px_pose_identity();
        l[k].axis = k == 1 ? (px_vec3){1, 0, 0} : (px_vec3){0, 1, 0};
        l[k].q_min = -10, l[k].q_max = 10, l[k].max_speed = 1;
        if (k == 0 || k == 3) {
            l[k].convex = box;
            l[k].geometry = px_pose_identity();
        }
    }
    l[0].origin.t = (px_vec3){5, 0, 0};
    px_chain_desc d;
    memset(&d, 0, sizeof d);
    d.links = l;
    d.n_links = 4;
    d.base = px_pose_identity();
    px_chain *c = px_chain_create(&d, &err);
    CHECK(c != NULL, "mobile base: %s", err.message);
    if (!c) {
        px_convex_destroy(box);
        return;
    }
    CHECK(!px_chain_adjacent(c, 0, 3), "the table and the chassis are adjacent");
    double q[2] = {0, 0};
    px_pose f[4], g[4], both[4];
    CHECK(px_chain_forward(c, q, f, g, &err) == PX_OK, "forward: %s", err.message);
    /* One array for both: the geometry poses, as apart. */
    CHECK(px_chain_forward(c, q, both, both, &err) == PX_OK && memcmp(both, g, sizeof g) == 0,
          "frames and geometry in one array");
    px_scene_options so;
    memset(&so, 0, sizeof so);
    px_scene *s = px_scene_create(&so, &err);
    uint32_t ids[4];
    CHECK(px_chain_add_to_scene(c, s, q, ids, &err) == PX_OK, "add: %s", err.message);
    int contact = 0;
    for (int step = 0; step <= 60; ++step) {
        q[0] = 0.1 * step;
        CHECK(px_chain_set_joints(c, s, ids, q, &err) == PX_OK, "set: %s", err.message);
        CHECK(px_scene_step(s, step, &err) == PX_OK, "step: %s", err.message);
        size_t np;
        const px_scene_pair *p = px_scene_pairs(s, &np);
        int want = q[0] >= 4.0 - 1e-12;
        int got = np == 1 && p[0].contact;
        CHECK(got == want, "step %d (x = %g): contact %d, want %d", step, q[0], got, want);
        contact |= got;
    }
    CHECK(contact, "the chassis never reached the table");
    px_scene_destroy(s);
    px_chain_destroy(c);
    px_convex_destroy(box);
}

/* Mimic joints (URDF <mimic>): random chains with some joints following
 * others (multipliers of either sign and 0, offsets; their own limits NaN,
 * ignored) give the frames, bit for bit, and the motion bounds of the same
 * chain without mimics at the values the mimics compute, with limits the
 * image of the followed joint's and speeds |multiplier| times its speed;
 * and those bounds hold (finite differences, as test_bounds). */
static void test_mimic(void) {
    int chains = tu_scaled(150), mimics = 0;
    double worst = 0;
    for (int it = 0; it < chains; ++it) {
        rchain c, e;
        random_chain(&c, 2 + (uint32_t)(urand() * 12), 0.2, 0.3, it % 2);
        uint32_t indep[MAXL], ni = 0, dof_of[MAXL];
        int follows[MAXL];
        for (uint32_t k = 0; k < c.n; ++k) {
            follows[k] = c.link[k].joint != PX_JOINT_FIXED && urand() < 0.4;
            if (c.link[k].joint != PX_JOINT_FIXED && !follows[k]) dof_of[k] = ni, indep[ni++] = k;
        }
        if (ni == 0) continue;
        e = c;
        for (uint32_t k = 0; k < c.n; ++k) {
            if (!follows[k]) continue;
            px_link_desc *l = &c.link[k], *x = &e.link[k];
            const px_link_desc *m = &c.link[indep[(uint32_t)(urand() * ni)]];
            l->mimic = 1;
            l->mimic_link = (uint32_t)(m - c.link);
            l->mimic_multiplier = urand() < 0.1 ? 0.0 : 4 * urand() - 2;
            l->mimic_offset = 0.6 * urand() - 0.3;
            l->q_min = l->q_max = l->max_speed = NAN;
            double f = l->mimic_multiplier;
            double lo = (f == 0 || m->q_min == 0 ? 0 : f * m->q_min) + l->mimic_offset;
            double hi = (f == 0 || m->q_max == 0 ? 0 : f * m->q_max) + l->mimic_offset;
            x->q_min = f < 0 ? hi : lo;
            x->q_max = f < 0 ? lo : hi;
            x->max_speed = f == 0 || m->max_speed == 0 ? 0 : fabs(f) * m->max_speed;
            mimics++;
        }
        px_error err;
        px_chain *cm = make_chain(&c, &err), *ce = make_chain(&e, &err);
        CHECK(cm && ce, "mimic chain: %s", err.message);
        CHECK(!cm || px_chain_dof(cm) == ni, "mimic chain: %u joint values, %u expected",
              cm ? px_chain_dof(cm) : 0, ni);
        for (uint32_t k = 0; cm && ce && k < c.n; ++k) {
            double v1, w1, v2, w2;
            px_chain_motion_bounds(cm, k, NULL, &v1, &w1, NULL);
            px_chain_motion_bounds(ce, k, NULL, &v2, &w2, NULL);
            CHECK(v1 == v2 && w1 == w2, "mimic chain: link %u's bounds %g %g, without mimics %g %g", k, v1,
                  w1, v2, w2);
        }
        for (int n = 0; cm && ce && n < 10; ++n) {
            double q[MAXL], full[MAXL], q2[MAXL], h = 1e-7;
            for (uint32_t i = 0; i < ni; ++i) {
                const px_link_desc *l = &c.link[indep[i]];
                double lo = isfinite(l->q_min) ? l->q_min : -10, hi = isfinite(l->q_max) ? l->q_max : 10;
                q[i] = lo + (hi - lo) * urand();
                q2[i] = q[i] + h * l->max_speed * (urand() < 0.5 ? -1 : 1) * (0.5 + 0.5 * urand());
                q2[i] = fmin(fmax(q2[i], l->q_min), l->q_max);
            }
            for (uint32_t k = 0, j = 0; k < c.n; ++k) {
                const px_link_desc *l = &c.link[k];
                if (l->joint == PX_JOINT_FIXED) continue;
                uint32_t d = l->mimic ? dof_of[l->mimic_link] : dof_of[k];
                full[j] = l->mimic ? l->mimic_multiplier * q[d] + l->mimic_offset : q[d];
                j++;
            }
            px_pose g1[MAXL], g2[MAXL], p1[MAXL];
            px_status s1 = px_chain_forward(cm, q, NULL, g1, &err),
                      s2 = px_chain_forward(ce, full, NULL, g2, &err);
            CHECK(s1 == PX_OK && s2 == PX_OK, "mimic forward: %s", err.message);
            CHECK(s1 != PX_OK || memcmp(g1, g2, c.n * sizeof *g1) == 0,
                  "mimic forward differs from the explicit chain");
            if (px_chain_forward(cm, q2, NULL, p1, &err) != PX_OK) continue;
            for (uint32_t k = 0; k < c.n; ++k) {
                px_vec3 center;
                double v, w;
                px_chain_motion_bounds(cm, k, &center, &v, &w, NULL);
                worst = fmax(worst, turn_angle(&g1[k], &p1[k]) / h - w);
                double moved = dist3(px_pose_apply(&g1[k], center), px_pose_apply(&p1[k], center)) / h;
                worst = fmax(worst, moved - v);
            }
        }
        px_chain_destroy(cm);
        px_chain_destroy(ce);
    }
    CHECK(worst <= 1e-6, "mimic chains: a link moves %g faster than its bound", worst);
    /* Bad mimics. */
    rchain c;
    random_chain(&c, 3, 0.0, 0.0, 1); /* three revolute joints in a row */
    px_error err;
    struct {
        uint32_t mimic, link;
        double f, off;
        uint32_t joint1;
        px_status want;
        const char *what;
    } bad[] = {
        {2, 0, 1, 0, PX_JOINT_REVOLUTE, PX_ERR_INVALID_ARGUMENT, "mimic 2"},
        {1, 1, 1, 0, PX_JOINT_REVOLUTE, PX_ERR_INVALID_ARGUMENT, "following itself"},
        {1, 7, 1, 0, PX_JOINT_REVOLUTE, PX_ERR_INVALID_ARGUMENT, "following no link"},
        {1, 0, 1, 0, PX_JOINT_FIXED, PX_ERR_INVALID_ARGUMENT, "a fixed mimic"},
        {1, 0, NAN, 0, PX_JOINT_REVOLUTE, PX_ERR_NON_FINITE, "a NaN multiplier"},
        {1, 0, 1, INFINITY, PX_JOINT_REVOLUTE, PX_ERR_NON_FINITE, "an infinite offset"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof *bad; ++i) {
        rchain b = c;
        b.link[1].joint = bad[i].joint1;
        b.link[1].mimic = bad[i].mimic;
        b.link[1].mimic_link = bad[i].link;
        b.link[1].mimic_multiplier = bad[i].f;
        b.link[1].mimic_offset = bad[i].off;
        px_chain *x = make_chain(&b, &err);
        CHECK(!x && err.code == bad[i].want && strstr(err.message, "link 1"), "%s: %s", bad[i].what,
              err.message);
        px_chain_destroy(x);
    }
    /* Following a fixed joint, or a mimic. */
    rchain b = c;
    b.link[0].joint = PX_JOINT_FIXED;
    b.link[1].mimic = 1;
    b.link[1].mimic_link = 0;
    px_chain *x = make_chain(&b, &err);
    CHECK(!x && err.code == PX_ERR_INVALID_ARGUMENT, "following a fixed joint: %s", err.message);
    px_chain_destroy(x);
    b = c;
    b.link[1].mimic = b.link[2].mimic = 1;
    b.link[1].mimic_link = 0;
    b.link[2].mimic_link = 1;
    b.link[1].mimic_multiplier = b.link[2].mimic_multiplier = 1;
    x = make_chain(&b, &err);
    CHECK(!x && err.code == PX_ERR_INVALID_ARGUMENT && strstr(err.message, "link 2"), "following a mimic: %s",
          err.message);
    px_chain_destroy(x);
    /* A value that overflows: a continuous joint followed at a large multiplier. */
    b = c;
    b.link[0].q_min = -INFINITY;
    b.link[0].q_max = INFINITY;
    b.link[1].mimic = 1;
    b.link[1].mimic_link = 0;
    b.link[1].mimic_multiplier = 1e300;
    x = make_chain(&b, &err);
    CHECK(x != NULL, "a large multiplier: %s", err.message);
    double q[2] = {1e300, 0}, v, w;
    px_pose g[3];
    CHECK(x && px_chain_forward(x, q, NULL, g, &err) == PX_ERR_RANGE && strstr(err.message, "mimic"),
          "an overflowing mimic value: %s", err.message);
    CHECK(x && px_chain_motion_bounds(x, 1, NULL, &v, &w, NULL) == PX_OK && !isnan(v) && !isnan(w),
          "a large multiplier's bounds: %g %g", v, w);
    px_chain_destroy(x);
    printf(
        "mimic: %d chains, %d mimic joints: frames equal to the explicit chains', bounds hold (worst excess "
        "%.1e)\n",
        chains, mimics, worst);
}

int main(void) {
    tu_init("test_chain");
    test_review_cases();
    test_forward();
    test_bounds();
    test_mimic();
    test_adjacency();
    test_scene();
    test_bad_inputs();
    return tu_finish();
}
