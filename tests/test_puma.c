/* The Puma 560 in its work cell (issue 11, section 3): the arm's kinematics
 * (examples/puma560.c) against the DH table, its motion bounds against
 * finite differences, and px_scene along the demo's trajectory against
 * brute force: at every step, cold px_model_distance over every pair the
 * scene may pair (non-adjacent links, link-cell) must give exactly the
 * reported pairs, their distances and contacts, and the scene's minimum.
 * A second scene of the same arm and cell with approximate models (links
 * and teapot as PX_PIECES_APPROXIMATE pieces, boxes as point-set pieces,
 * as the demo's timed run) moves along with it: at every step each
 * reported pair's bracket [distance, upper_bound] holds the exact
 * distance, and every pair not reported is exactly farther than the
 * report distance (tolerance 0.05, 532 steps; under the sanitizers, which
 * slow the decomposition 10-20 times, 0.1 and 267 steps). Known
 * configurations: the gripper touches the teapot at the touching
 * waypoint; READY is clear of the cell. */
#define _POSIX_C_SOURCE 200809L /* examples/puma560.c: stat */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../examples/puma560.c"
#include "test_util.h"

#define NBODY (PUMA_LINKS + PUMA_CELL_BODIES)
#define MARGIN 0.001
#define REPORT 0.02

static uint64_t rng_state = 7;
static double urand(void) {
    uint64_t z = (rng_state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return (double)(z >> 11) * 0x1p-53;
}

static void random_q(double q[PUMA_JOINTS]) {
    for (int j = 0; j < PUMA_JOINTS; ++j) q[j] = puma_q_min[j] + urand() * (puma_q_max[j] - puma_q_min[j]);
}

static double rot_diff(const px_pose *a, const px_pose *b) {
    double m = 0;
    for (int i = 0; i < 9; ++i) m = fmax(m, fabs(a->r[i] - b->r[i]));
    return m;
}

static double dist3(px_vec3 a, px_vec3 b) {
    return sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) + (a.z - b.z) * (a.z - b.z));
}

/* Kinematics: every link frame of both URDF chains is the DH frame times
 * a constant rotation (the same for both chains), and the wrist centre
 * (URDF link6's origin, DH frame 4's) agrees to within the chains'
 * documented differences from the DH table (SOURCE.md): nimasarli puts the
 * 20.3 mm elbow offset along the forearm and a 433.1 mm forearm (DH: a3
 * across, d4 = 431.8), RTB's xacro has the shoulder at 623.6 mm (DH 671.8),
 * d3 = 167.6 (DH 150.05) and a3 = 38.1. */
static void test_kinematics(void) {
    const double q0[PUMA_JOINTS] = {0, 0, 0, 0, 0, 0};
    px_pose e[2][PUMA_LINKS], f0[PUMA_LINKS], d0[PUMA_LINKS];
    puma_dh_frames(q0, d0);
    for (int s = 0; s < 2; ++s) {
        puma_link_frames((puma_meshes)s, q0, f0);
        for (int k = 1; k < PUMA_LINKS; ++k) {
            px_pose di = puma_inverse(&d0[k]);
            e[s][k] = puma_compose(&di, &f0[k]);
        }
    }
    const double wc_tol[2] = {0.045, 0.08};
    double worst_rot = 0, worst_same = 0, worst_wc[2] = {0, 0};
    for (int n = 0; n < 500; ++n) {
        double q[PUMA_JOINTS];
        random_q(q);
        px_pose d[PUMA_LINKS], f[2][PUMA_LINKS];
        puma_dh_frames(q, d);
        for (int s = 0; s < 2; ++s) {
            puma_link_frames((puma_meshes)s, q, f[s]);
            for (int k = 1; k < PUMA_LINKS; ++k) {
                px_pose want = puma_compose(&d[k], &e[s][k]);
                worst_rot = fmax(worst_rot, rot_diff(&want, &f[s][k]));
            }
            worst_wc[s] = fmax(worst_wc[s], dist3(f[s][5].t, d[4].t));
        }
        for (int k = 0; k < PUMA_LINKS; ++k) worst_same = fmax(worst_same, rot_diff(&f[0][k], &f[1][k]));
    }
    CHECK(worst_rot < 1e-12, "link rotations differ from DH times a constant by %g", worst_rot);
    CHECK(worst_same < 1e-12, "the two chains' link rotations differ by %g", worst_same);
    for (int s = 0; s < 2; ++s)
        CHECK(worst_wc[s] < wc_tol[s], "chain %d: wrist centre %g m from the DH table's", s, worst_wc[s]);
    printf("kinematics: rotations = DH x constant within %.1e, chains agree within %.1e; wrist centre within "
           "%.1f mm (nimasarli), %.1f mm (RTB) of DH\n",
           worst_rot, worst_same, 1e3 * worst_wc[0], 1e3 * worst_wc[1]);
}

/* Motion bounds: over random configurations and joint velocities within
 * the limits, the finite-difference speed of each link's centre and its
 * angular speed stay below puma_motion_bounds. The trajectory keeps to the
 * joint and speed limits. */
static void test_bounds(void) {
    for (int s = 0; s < PUMA_MESH_SETS; ++s) {
        px_vec3 c[PUMA_LINKS];
        double v[PUMA_LINKS], w[PUMA_LINKS];
        puma_motion_bounds((puma_meshes)s, NULL, c, v, w);
        double worst = 0;
        for (int n = 0; n < 300; ++n) {
            double q[PUMA_JOINTS], q2[PUMA_JOINTS], h = 1e-6;
            random_q(q);
            for (int j = 0; j < PUMA_JOINTS; ++j) q2[j] = q[j] + h * (2 * urand() - 1) * puma_qd_max[j];
            px_pose p[PUMA_LINKS], p2[PUMA_LINKS];
            puma_link_poses((puma_meshes)s, q, p);
            puma_link_poses((puma_meshes)s, q2, p2);
            for (int k = 1; k < PUMA_LINKS; ++k) {
                double sp = dist3(px_pose_apply(&p[k], c[k]), px_pose_apply(&p2[k], c[k])) / h;
                /* angle of R2 R^T: acos((trace - 1) / 2) */
                double tr = 0;
                for (int i = 0; i < 3; ++i)
                    for (int j = 0; j < 3; ++j) tr += p2[k].r[3 * i + j] * p[k].r[3 * i + j];
                double ang = acos(fmin(1.0, fmax(-1.0, (tr - 1) / 2))) / h;
                worst = fmax(worst, fmax(sp - v[k], ang - w[k]));
            }
        }
        CHECK(worst <= 1e-6, "set %d: a link moves %g faster than its bound", s, worst);
    }
    double T = puma_trajectory_duration(), dt = 1e-3, worst_q = 0, worst_qd = 0;
    double prev[PUMA_JOINTS];
    puma_trajectory(0, prev);
    for (double t = dt; t <= T; t += dt) {
        double q[PUMA_JOINTS];
        puma_trajectory(t, q);
        for (int j = 0; j < PUMA_JOINTS; ++j) {
            worst_q = fmax(worst_q, fmax(puma_q_min[j] - q[j], q[j] - puma_q_max[j]));
            worst_qd = fmax(worst_qd, fabs(q[j] - prev[j]) / dt / puma_qd_max[j]);
            prev[j] = q[j];
        }
    }
    CHECK(worst_q <= 0, "the trajectory leaves the joint limits by %g rad", worst_q);
    CHECK(worst_qd <= 0.91, "the trajectory reaches %g of a joint speed limit", worst_qd);
}

/* The arm as a px_chain (proxima/chain.h) against the hand-written URDF
 * chains above: link poses within 1e-12 m at random configurations, the
 * same motion bounds, adjacency (k, k+1) only, the joint limits refused. */
static void test_chain(void) {
    double worst_pose = 0, worst_bound = 0;
    for (int s = 0; s < PUMA_MESH_SETS; ++s) {
        /* One small model on every link: the chain places it by the
         * mesh frames (a link without geometry would ignore them). */
        static const double tet[12] = {0, 0, 0, 0.01, 0, 0, 0, 0.01, 0, 0, 0, 0.01};
        static const uint32_t end[1] = {4};
        px_error err;
        px_model *tiny = px_model_create_from_points(tet, end, 1, NULL, &err);
        puma_arm arm;
        memset(&arm, 0, sizeof arm);
        arm.set = (puma_meshes)s;
        for (int k = 0; k < PUMA_LINKS; ++k) arm.link[k] = tiny;
        px_chain *c = puma_chain_create(&arm, NULL, 0, 0, &err);
        CHECK(c != NULL, "set %d: px_chain_create: %s", s, err.message);
        if (!c) {
            px_model_destroy(tiny);
            continue;
        }
        CHECK(px_chain_link_count(c) == PUMA_LINKS && px_chain_dof(c) == PUMA_JOINTS,
              "set %d: %u links, %u dof", s, px_chain_link_count(c), px_chain_dof(c));
        for (uint32_t i = 0; i < PUMA_JOINTS; ++i)
            CHECK(px_chain_joint_link(c, i) == i + 1, "joint %u drives link %u", i,
                  px_chain_joint_link(c, i));
        for (int n = 0; n < 200; ++n) {
            double q[PUMA_JOINTS];
            random_q(q);
            px_pose want[PUMA_LINKS], got[PUMA_LINKS], frames[PUMA_LINKS];
            puma_link_poses((puma_meshes)s, q, want);
            CHECK(px_chain_forward(c, q, frames, got, &err) == PX_OK, "forward: %s", err.message);
            for (int k = 0; k < PUMA_LINKS; ++k) {
                worst_pose = fmax(worst_pose, dist3(want[k].t, got[k].t));
                for (int i = 0; i < 9; ++i) worst_pose = fmax(worst_pose, fabs(want[k].r[i] - got[k].r[i]));
            }
        }
        px_vec3 cw[PUMA_LINKS];
        double vw[PUMA_LINKS], ww[PUMA_LINKS];
        puma_motion_bounds((puma_meshes)s, NULL, cw, vw, ww);
        for (uint32_t k = 0; k < PUMA_LINKS; ++k) {
            px_vec3 cg;
            double vg, wg;
            CHECK(px_chain_motion_bounds(c, k, &cg, &vg, &wg, &err) == PX_OK, "bounds: %s", err.message);
            worst_bound = fmax(worst_bound, fmax(dist3(cg, cw[k]), fmax(fabs(vg - vw[k]), fabs(wg - ww[k]))));
        }
        /* Limits: joint 2 just beyond its maximum, and NaN. */
        double q[PUMA_JOINTS];
        random_q(q);
        q[1] = nextafter(puma_q_max[1], INFINITY);
        CHECK(px_chain_forward(c, q, NULL, NULL, &err) == PX_ERR_RANGE && strstr(err.message, "limits"),
              "beyond a limit: %s", err.message);
        q[1] = NAN;
        CHECK(px_chain_forward(c, q, NULL, NULL, &err) == PX_ERR_NON_FINITE, "NaN joint: %s", err.message);
        for (uint32_t a = 0; a < PUMA_LINKS; ++a)
            for (uint32_t b = 0; b < PUMA_LINKS; ++b)
                CHECK(px_chain_adjacent(c, a, b) == (a + 1 == b || b + 1 == a), "links %u, %u adjacent %d", a,
                      b, px_chain_adjacent(c, a, b));
        px_chain_destroy(c);
        px_model_destroy(tiny);
    }
    CHECK(worst_pose <= 1e-12, "px_chain poses differ from the URDF chain's by %g", worst_pose);
    CHECK(worst_bound <= 1e-12, "px_chain motion bounds differ from puma_motion_bounds by %g", worst_bound);
    printf("chain: px_chain link poses within %.1e of the URDF chains, motion bounds within %.1e\n",
           worst_pose, worst_bound);
}

typedef struct world {
    puma_arm arm;
    px_chain *chain; /* the arm as a px_chain (make_scene) */
    puma_cell cell;
    const px_model *model[NBODY];
} world;

static void poses_at(const world *w, const double q[PUMA_JOINTS], px_pose pose[NBODY]) {
    puma_link_poses(w->arm.set, q, pose);
    for (int c = 0; c < PUMA_CELL_BODIES; ++c) pose[PUMA_LINKS + c] = w->cell.body[c].pose;
}

/* Pairs the scene may pair (x < y): non-adjacent links, and link-cell. */
static int paired(int x, int y) { return x < PUMA_LINKS && (y >= x + 2 || y >= PUMA_LINKS); }

/* A scene of the arm and cell of w (bodies numbered as the demo's). */
static px_scene *make_scene(world *w) {
    px_scene_options so;
    memset(&so, 0, sizeof so);
    so.margin = MARGIN;
    so.report_distance = REPORT;
    px_error err;
    memset(&err, 0, sizeof err);
    px_scene *scene = px_scene_create(&so, &err);
    uint32_t ids[NBODY];
    double q[PUMA_JOINTS];
    puma_trajectory(0, q);
    px_chain_destroy(w->chain);
    w->chain = puma_chain_create(&w->arm, NULL, 1, 3, &err);
    int ok = scene && w->chain && px_chain_add_to_scene(w->chain, scene, q, ids, &err) == PX_OK &&
             puma_cell_add(&w->cell, scene, 2, 1, ids + PUMA_LINKS, &err) == PX_OK;
    CHECK(ok, "scene setup: %s", err.message);
    if (!ok) {
        px_scene_destroy(scene);
        return NULL;
    }
    for (int b = 0; b < NBODY; ++b) CHECK(ids[b] == (uint32_t)b, "body %d got id %u", b, ids[b]);
    return scene;
}

/* The approximate scene's reports at one step against the exact distances
 * exact[x][y] of every paired (x, y): the bracket holds each reported
 * pair's, and the others are farther than the report distance. Returns
 * the number of failures; adds the bracket widths to *width. */
static int check_brackets(const px_scene *scene, int step, double exact[NBODY][NBODY], double *width,
                          double *worst) {
    size_t np;
    const px_scene_pair *pairs = px_scene_pairs(scene, &np);
    int bad = 0, seen[NBODY][NBODY];
    memset(seen, 0, sizeof seen);
    const double slack = 1e-9; /* the two queries round differently */
    for (size_t k = 0; k < np; ++k) {
        int x = (int)pairs[k].body_a, y = (int)pairs[k].body_b;
        if (x >= NBODY || y >= NBODY || x >= y || !paired(x, y)) {
            if (bad++ < 5) fprintf(stderr, "step %d: approximate scene reports pair %d-%d\n", step, x, y);
            continue;
        }
        seen[x][y] = 1;
        double e = exact[x][y], d = pairs[k].distance, u = pairs[k].upper_bound;
        *width += u - d;
        *worst = fmax(*worst, u - d);
        if (!(d - slack <= e && e <= u + slack) && bad++ < 5)
            fprintf(stderr, "step %d: pair %d-%d: exact %.17g outside the bracket [%.17g, %.17g]\n", step, x,
                    y, e, d, u);
    }
    for (int x = 0; x < NBODY; ++x)
        for (int y = x + 1; y < NBODY; ++y)
            if (paired(x, y) && !seen[x][y] && !(exact[x][y] > REPORT) && bad++ < 5)
                fprintf(stderr, "step %d: pair %d-%d at exact %.17g not reported by the approximate scene\n",
                        step, x, y, exact[x][y]);
    return bad;
}

/* The scene along the trajectory against brute force (cold), every step;
 * the approximate scene of `coarse` (if not NULL) against the same. */
static void test_scene(world *w, world *coarse, double dt) {
    px_error err;
    memset(&err, 0, sizeof err);
    px_scene *scene = make_scene(w), *fast = coarse ? make_scene(coarse) : NULL;
    if (!scene || (coarse && !fast)) {
        px_scene_destroy(scene);
        px_scene_destroy(fast);
        return;
    }
    uint32_t ids[NBODY];
    for (int b = 0; b < NBODY; ++b) ids[b] = (uint32_t)b;
    double q[PUMA_JOINTS];
    double touch = puma_touch_time(), T = puma_trajectory_duration();
    int touch_step = (int)(touch / dt + 0.5), steps = 0, touched = 0, bad_pairs = 0, bad_min = 0;
    int bad_brackets = 0, fast_touched = 0;
    dt = touch / touch_step;
    uint64_t checked = 0, fast_checked = 0, fast_reported = 0;
    double width = 0, worst = 0;
    for (int i = 0; i * dt <= T; ++i, ++steps) {
        double t = i * dt;
        puma_trajectory(t, q);
        CHECK(px_chain_set_joints(w->chain, scene, ids, q, &err) == PX_OK, "set: %s", err.message);
        px_status st = px_scene_step(scene, t, &err);
        CHECK(st == PX_OK, "step %d: %s", i, err.message);
        px_scene_stats stats;
        px_scene_get_stats(scene, &stats);
        checked += stats.pairs_checked;
        /* px_chain's motion bounds hold along the trajectory (it keeps to
         * 0.9 of the joint speed limits). */
        CHECK(stats.violations == 0, "step %d: %u links broke px_chain's motion bounds", i, stats.violations);
        if (fast) {
            CHECK(px_chain_set_joints(coarse->chain, fast, ids, q, &err) == PX_OK, "set: %s", err.message);
            CHECK(px_scene_step(fast, t, &err) == PX_OK, "approximate step %d: %s", i, err.message);
            px_scene_get_stats(fast, &stats);
            fast_checked += stats.pairs_checked;
        }
        size_t np;
        const px_scene_pair *pairs = px_scene_pairs(scene, &np);
        px_pose pose[NBODY];
        poses_at(w, q, pose);
        double best = INFINITY, exact[NBODY][NBODY];
        size_t k = 0;
        for (int x = 0; x < NBODY; ++x)
            for (int y = x + 1; y < NBODY; ++y) {
                if (!paired(x, y)) continue;
                px_model_distance_result d;
                CHECK(px_model_distance(w->model[x], &pose[x], w->model[y], &pose[y], NULL, &d) == PX_OK,
                      "brute force %d-%d", x, y);
                exact[x][y] = d.distance;
                best = fmin(best, d.distance);
                if (d.distance > REPORT) continue;
                /* the next reported pair must be this one, same distance */
                int ok = k < np && pairs[k].body_a == (uint32_t)x && pairs[k].body_b == (uint32_t)y &&
                         fabs(pairs[k].distance - d.distance) <= 1e-12 &&
                         pairs[k].contact == (uint32_t)(d.distance <= MARGIN);
                if (!ok && bad_pairs++ < 10)
                    fprintf(stderr, "step %d: pair %d-%d at %.17g: reported %s\n", i, x, y, d.distance,
                            k < np ? "another pair or distance" : "nothing");
                if (k < np && pairs[k].body_a == (uint32_t)x && pairs[k].body_b == (uint32_t)y) ++k;
                if (i == touch_step && x == 6 && y == PUMA_LINKS + 2 && d.distance <= MARGIN) touched = 1;
            }
        if (k != np && bad_pairs++ < 10)
            fprintf(stderr, "step %d: %zu pairs reported beyond brute force's\n", i, np - k);
        px_scene_pair mp;
        CHECK(px_scene_min_distance(scene, &mp, &err) == PX_OK, "min_distance: %s", err.message);
        if (fabs(mp.distance - best) > 1e-12 && bad_min++ < 10)
            fprintf(stderr, "step %d: scene minimum %.17g, brute force %.17g\n", i, mp.distance, best);
        if (fast) {
            bad_brackets += check_brackets(fast, i, exact, &width, &worst) > 0;
            pairs = px_scene_pairs(fast, &np);
            fast_reported += np;
            if (i == touch_step)
                for (size_t m = 0; m < np; ++m)
                    fast_touched |=
                        pairs[m].body_a == 6 && pairs[m].body_b == PUMA_LINKS + 2 && pairs[m].contact;
        }
    }
    CHECK(bad_pairs == 0, "%d steps reported other pairs than brute force", bad_pairs);
    CHECK(bad_min == 0, "%d steps gave another minimum than brute force", bad_min);
    CHECK(touched, "the gripper does not touch the teapot at the touching waypoint");
    printf(
        "scene: %d steps of %.4f s, reports and minimum equal to brute force (%d pairs, cold) at every step; "
        "%.2f narrow-phase queries per step\n",
        steps, dt, 15 + 4 * PUMA_LINKS, (double)checked / steps);
    if (fast) {
        CHECK(bad_brackets == 0, "%d steps where the approximate scene's brackets miss the exact distance",
              bad_brackets);
        CHECK(fast_touched, "the approximate scene has no gripper-teapot contact at the touching waypoint");
        printf(
            "approximate scene: brackets hold the exact distance of all %llu reported pairs, the %llu others "
            "beyond %g m; widths mean %.2f mm, max %.2f mm; %.2f narrow-phase queries per step\n",
            (unsigned long long)fast_reported,
            (unsigned long long)(steps * (15 + 4 * PUMA_LINKS) - fast_reported), REPORT,
            fast_reported ? 1e3 * width / (double)fast_reported : 0.0, 1e3 * worst,
            (double)fast_checked / steps);
    }
    px_scene_destroy(scene);
    px_scene_destroy(fast);
}

/* Known configurations: touching at the touching waypoint (the gripper,
 * link7, against the teapot, distance 0), clear at READY. */
static void test_known(const world *w) {
    double q[PUMA_JOINTS];
    px_pose pose[NBODY];
    puma_trajectory(puma_touch_time(), q);
    poses_at(w, q, pose);
    px_model_distance_result d;
    px_model_distance(w->model[6], &pose[6], w->model[PUMA_LINKS + 2], &pose[PUMA_LINKS + 2], NULL, &d);
    CHECK(d.distance <= 1e-12, "touching configuration: gripper-teapot %g", d.distance);
    const double ready[PUMA_JOINTS] = {0, PI / 2, -PI / 2, 0, 0, 0};
    poses_at(w, ready, pose);
    double self = INFINITY, cell = INFINITY;
    for (int x = 0; x < NBODY; ++x)
        for (int y = x + 1; y < NBODY; ++y)
            if (paired(x, y)) {
                px_model_distance(w->model[x], &pose[x], w->model[y], &pose[y], NULL, &d);
                if (y < PUMA_LINKS)
                    self = fmin(self, d.distance);
                else
                    cell = fmin(cell, d.distance);
            }
    CHECK(self > 0.004 && cell > 0.1, "READY: self clearance %g, cell clearance %g", self, cell);
}

int main(void) {
    tu_init("test_puma");
    test_kinematics();
    test_bounds();
    test_chain();
    world w;
    memset(&w, 0, sizeof w);
    px_error err;
    if (puma_arm_load(&w.arm, PX_SOURCE_DIR "/models", PUMA_NIMASARLI, PX_PIECES_TRIANGLES, &err) != PX_OK ||
        puma_cell_build(&w.cell, PX_SOURCE_DIR "/models", &w.arm, &err) != PX_OK) {
        CHECK(0, "loading: %s", err.message);
        return tu_finish();
    }
    for (int k = 0; k < PUMA_LINKS; ++k) w.model[k] = w.arm.link[k];
    for (int c = 0; c < PUMA_CELL_BODIES; ++c) w.model[PUMA_LINKS + c] = w.cell.body[c].model;
    test_known(&w);
    /* The approximate models: a coarser tolerance under the sanitizers,
     * which slow the decomposition (CGAL) 10-20 times; no cache. */
    world c;
    memset(&c, 0, sizeof c);
    puma_build b;
    memset(&b, 0, sizeof b);
    b.pieces = PX_PIECES_APPROXIMATE;
    b.tolerance = tu_sanitized() ? 0.1 : 0.05;
    b.threads = 2;
    int have_coarse =
        puma_arm_load_with(&c.arm, PX_SOURCE_DIR "/models", PUMA_NIMASARLI, &b, &err) == PX_OK &&
        puma_cell_build_coarse(&c.cell, PX_SOURCE_DIR "/models", &w.cell, &b, &err) == PX_OK;
    CHECK(have_coarse, "approximate models: %s", err.message);
    if (have_coarse) {
        printf("approximate models at tolerance %g built in %.1f s\n", b.tolerance, b.build_seconds);
        for (int k = 0; k < PUMA_LINKS; ++k) c.model[k] = c.arm.link[k];
        for (int k = 0; k < PUMA_CELL_BODIES; ++k) c.model[PUMA_LINKS + k] = c.cell.body[k].model;
    }
    test_scene(&w, have_coarse ? &c : NULL, (tu_sanitized() ? 0.04 : 0.02) / tu_scale());
    px_chain_destroy(c.chain);
    px_chain_destroy(w.chain);
    puma_cell_destroy(&c.cell);
    puma_arm_destroy(&c.arm);
    puma_cell_destroy(&w.cell);
    puma_arm_destroy(&w.arm);
    return tu_finish();
}
