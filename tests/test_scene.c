/* px_scene against brute force (issue 11, section 2): at every step of
 * random bounded motion, the reported pairs must be exactly the pairs whose
 * distance (px_distance / px_model_distance, cold, all pairs) is at most the
 * report distance, with the same distances, and the contact events must be
 * the transitions of the brute-force contact set. Also: teleports that break
 * the declared bounds, acceleration bounds with velocities, bodies added and
 * removed, filters and excluded pairs, static bodies, the global minimum,
 * determinism, bad inputs. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "proxima/proxima.h"
#include "test_util.h"

/* Deterministic random numbers (splitmix64). */
static uint64_t rng_state = 1;
static double urand(void) {
    uint64_t z = (rng_state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return (double)(z >> 11) * 0x1p-53;
}
static double srand1(void) { return 2.0 * urand() - 1.0; }

/* Hull of n random points on a sphere of radius r. */
static px_convex *random_hull(int n, double r) {
    double p[3 * 64];
    for (int i = 0; i < n; ++i) {
        double x, y, z, l;
        do {
            x = srand1(), y = srand1(), z = srand1();
            l = sqrt(x * x + y * y + z * z);
        } while (l < 0.1 || l > 1.0);
        p[3 * i] = r * x / l, p[3 * i + 1] = r * y / l, p[3 * i + 2] = r * z / l;
    }
    return px_convex_create(p, (size_t)n, NULL, NULL);
}

/* A non-convex model: an L of two boxes, as point-set pieces. */
static px_model *l_model(double s) {
    double p[2 * 8 * 3];
    const double box[2][6] = {{0, 0, 0, 2, 0.5, 0.5}, {0, 0, 0, 0.5, 2, 0.5}};
    for (int b = 0; b < 2; ++b)
        for (int c = 0; c < 8; ++c)
            for (int k = 0; k < 3; ++k)
                p[3 * (8 * b + c) + k] = s * ((c >> k) & 1 ? box[b][3 + k] : box[b][k]) - s * 0.6;
    uint32_t ends[2] = {8, 16};
    return px_model_create_from_points(p, ends, 2, NULL, NULL);
}

static px_pose pose_of(const double q[4], px_vec3 t) {
    px_pose p;
    double tt[3] = {t.x, t.y, t.z};
    px_pose_from_quat(q, tt, &p);
    return p;
}

/* Rotates quaternion q by angle a about a random unit axis. */
static void turn(double q[4], double a) {
    double ax[3] = {srand1(), srand1(), srand1()};
    double l = sqrt(ax[0] * ax[0] + ax[1] * ax[1] + ax[2] * ax[2]);
    if (l < 1e-9) return;
    double s = sin(a / 2) / l, d[4] = {cos(a / 2), ax[0] * s, ax[1] * s, ax[2] * s};
    double r[4] = {d[0] * q[0] - d[1] * q[1] - d[2] * q[2] - d[3] * q[3],
                   d[0] * q[1] + d[1] * q[0] + d[2] * q[3] - d[3] * q[2],
                   d[0] * q[2] - d[1] * q[3] + d[2] * q[0] + d[3] * q[1],
                   d[0] * q[3] + d[1] * q[2] - d[2] * q[1] + d[3] * q[0]};
    double n = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2] + r[3] * r[3]);
    for (int i = 0; i < 4; ++i) q[i] = r[i] / n;
}

typedef struct sim_body {
    px_convex *convex;
    px_model *model;
    double q[4];
    px_vec3 t, v;
    double w; /* angle per step */
    uint32_t id;
    uint32_t group, mask;
    int alive, fixed;
} sim_body;

typedef struct sim {
    const char *name;
    int bodies, steps, models; /* models: every k-th body is an L model (0: none) */
    double box, speed, spin, margin, report;
    int teleport_every; /* 0: never */
    int churn;          /* add and remove bodies now and then (2: many at once) */
    int filters;        /* groups, masks and excluded pairs */
    int statics;        /* some static bodies */
    int accel;          /* accelerating bodies with velocities */
    int flat;           /* every body on one floor (z fixed), no spin off it */
    int threads;        /* px_scene_options.threads */
} sim;

static double pair_distance(const sim_body *x, const sim_body *y, px_vec3 *pa, px_vec3 *pb) {
    px_pose px = pose_of(x->q, x->t), py = pose_of(y->q, y->t);
    if (x->convex && y->convex) {
        px_distance_result r;
        px_status st = px_distance(x->convex, &px, y->convex, &py, NULL, NULL, &r);
        CHECK(st == PX_OK, "brute force px_distance: %d", st);
        *pa = r.point_a, *pb = r.point_b;
        return r.distance;
    }
    px_model_distance_result r;
    px_status st;
    if (x->model && y->model)
        st = px_model_distance(x->model, &px, y->model, &py, NULL, &r);
    else if (x->model)
        st = px_model_distance_convex(x->model, &px, y->convex, &py, NULL, &r);
    else {
        st = px_model_distance_convex(y->model, &py, x->convex, &px, NULL, &r);
        px_vec3 t = r.point_a;
        r.point_a = r.point_b;
        r.point_b = t;
    }
    CHECK(st == PX_OK, "brute force px_model_distance: %d", st);
    *pa = r.point_a, *pb = r.point_b;
    return r.distance;
}

static int excluded_pair(uint32_t a, uint32_t b) { return (a + 3 * b) % 11 == 0; }

static int paired(const sim *c, const sim_body *x, const sim_body *y) {
    if (!c->filters) return 1;
    if (!(x->group & y->mask) || !(y->group & x->mask)) return 0;
    uint32_t a = x->id < y->id ? x->id : y->id, b = x->id < y->id ? y->id : x->id;
    return !excluded_pair(a, b);
}

static void add_sim_body(px_scene *s, const sim *c, sim_body *b, int k) {
    b->convex = NULL;
    b->model = NULL;
    if (c->models && k % c->models == 0)
        b->model = l_model(0.6 + 0.4 * urand());
    else
        b->convex = random_hull(8 + (int)(urand() * 24), 0.5 + 0.5 * urand());
    b->q[0] = 1, b->q[1] = b->q[2] = b->q[3] = 0;
    turn(b->q, 3.0 * urand());
    b->t = (px_vec3){c->box * urand(), c->box * urand(), c->box * urand()};
    double vs = c->speed * urand();
    px_vec3 d = {srand1(), srand1(), srand1()};
    double l = sqrt(d.x * d.x + d.y * d.y + d.z * d.z) + 1e-12;
    b->v = (px_vec3){vs * d.x / l, vs * d.y / l, vs * d.z / l};
    b->w = c->spin * urand();
    if (c->flat) {
        b->t.z = 1.0;
        b->v.z = 0.0;
    }
    b->fixed = c->statics && k % 5 == 1;
    b->group = c->filters ? 1u << (k % 3) : 0;
    b->mask = c->filters ? (k % 4 == 0 ? ~(1u << 1) : 0xFFFFFFFFu) : 0;
    px_body_desc d2;
    memset(&d2, 0, sizeof d2);
    d2.convex = b->convex;
    d2.model = b->model;
    d2.pose = pose_of(b->q, b->t);
    d2.max_speed = b->fixed ? 0 : c->speed;
    d2.max_angular_speed = b->fixed ? 0 : c->spin;
    d2.max_accel = c->accel && !b->fixed ? 0.01 : 0;
    d2.group = b->group;
    d2.mask = b->mask;
    d2.flags = b->fixed ? PX_BODY_STATIC : 0;
    px_error e;
    px_status st = px_scene_add_body(s, &d2, &b->id, &e);
    CHECK(st == PX_OK, "add body: %s", e.message);
    b->alive = 1;
}

static void free_sim_body(sim_body *b) {
    px_convex_destroy(b->convex);
    px_model_destroy(b->model);
    b->convex = NULL;
    b->model = NULL;
    b->alive = 0;
}

/* With filters, a body added during the run gets the exclusions the
 * brute force assumes for its id (ids are reused). */
static void exclude_new(px_scene *s, const sim *c, const sim_body *b, int n, int k) {
    if (!c->filters) return;
    for (int j = 0; j < n; ++j) {
        if (j == k || !b[j].alive) continue;
        uint32_t lo = b[j].id < b[k].id ? b[j].id : b[k].id, hi = b[j].id < b[k].id ? b[k].id : b[j].id;
        if (excluded_pair(lo, hi)) CHECK(px_scene_exclude_pair(s, lo, hi, NULL) == PX_OK, "exclude");
    }
}

/* Runs one scenario; returns a hash of everything reported. */
static uint64_t run(const sim *c, int verbose) {
    rng_state = 12345;
    px_scene_options o;
    memset(&o, 0, sizeof o);
    o.margin = c->margin;
    o.report_distance = c->report;
    o.threads = (uint32_t)c->threads;
    px_error e;
    px_scene *s = px_scene_create(&o, &e);
    CHECK(s != NULL, "create: %s", e.message);
    if (!s) return 0;
    int cap = c->bodies + (c->churn == 2 ? (c->bodies / 4 + 25) * c->steps : 64);
    sim_body *b = calloc((size_t)cap, sizeof *b);
    int n = c->bodies;
    for (int i = 0; i < n; ++i) add_sim_body(s, c, &b[i], i);
    if (c->filters)
        for (int i = 0; i < n; ++i)
            for (int j = i + 1; j < n; ++j)
                if (excluded_pair(b[i].id < b[j].id ? b[i].id : b[j].id,
                                  b[i].id < b[j].id ? b[j].id : b[i].id))
                    CHECK(px_scene_exclude_pair(s, b[i].id, b[j].id, NULL) == PX_OK, "exclude");
    /* Brute-force contact state per pair of sim indices. */
    unsigned char *contact = calloc((size_t)cap * cap, 1);
    uint64_t hash = 1469598103934665603ull, checked = 0, candidates = 0;
    int mismatches = 0, event_mismatches = 0;
    double worst = 0;
    for (int step = 0; step < c->steps; ++step) {
        /* Motion: constant velocities and spins, bouncing off the walls;
         * accelerating ones change speed within the bound. */
        for (int i = 0; i < n; ++i) {
            sim_body *x = &b[i];
            if (!x->alive || x->fixed || step == 0) continue;
            if (c->accel) {
                px_vec3 a = {0.01 * srand1() / 1.8, 0.01 * srand1() / 1.8, 0.01 * srand1() / 1.8};
                px_vec3 nv = {x->v.x + a.x, x->v.y + a.y, x->v.z + a.z};
                double l = sqrt(nv.x * nv.x + nv.y * nv.y + nv.z * nv.z);
                if (l > 0.999 * c->speed)
                    nv = (px_vec3){nv.x * 0.999 * c->speed / l, nv.y * 0.999 * c->speed / l,
                                   nv.z * 0.999 * c->speed / l};
                x->v = nv;
            }
            x->t.x += x->v.x, x->t.y += x->v.y, x->t.z += x->v.z;
            double *t3[3] = {&x->t.x, &x->t.y, &x->t.z}, *v3[3] = {&x->v.x, &x->v.y, &x->v.z};
            for (int k = 0; k < 3; ++k)
                if (*t3[k] < 0 || *t3[k] > c->box) *v3[k] = -*v3[k];
            turn(x->q, x->w);
            if (c->teleport_every && (step + i) % c->teleport_every == 0)
                x->t = (px_vec3){c->box * urand(), c->box * urand(), c->box * urand()};
            px_pose p = pose_of(x->q, x->t);
            CHECK(px_scene_set_pose(s, x->id, &p, &e) == PX_OK, "set pose: %s", e.message);
            if (c->accel)
                CHECK(px_scene_set_velocity(s, x->id, x->v, x->w, &e) == PX_OK, "set velocity: %s",
                      e.message);
        }
        if (c->churn == 2 && step > 0 && step % 5 == 0) {
            /* Mass churn: a third of the bodies removed at once (their
             * endpoints leave the arrays in one pass at the step), new ones
             * added, and one of those removed again before the step. */
            for (int i = 0; i < n; ++i)
                if (b[i].alive && urand() < 0.33) {
                    CHECK(px_scene_remove_body(s, b[i].id, &e) == PX_OK, "remove: %s", e.message);
                    free_sim_body(&b[i]);
                }
            int first = n;
            for (int k = 0; k < c->bodies / 4 && n < cap; ++k, ++n) {
                add_sim_body(s, c, &b[n], n);
                exclude_new(s, c, b, n + 1, n);
            }
            if (n > first) {
                CHECK(px_scene_remove_body(s, b[first].id, &e) == PX_OK, "remove: %s", e.message);
                free_sim_body(&b[first]);
            }
        }
        if (c->churn == 1 && step > 0 && step % 7 == 0) {
            int victim = (int)(urand() * n);
            if (b[victim].alive) {
                CHECK(px_scene_remove_body(s, b[victim].id, &e) == PX_OK, "remove: %s", e.message);
                /* Contacts of the victim end: the brute force forgets them
                 * and expects ended events. */
                free_sim_body(&b[victim]);
            }
            if (n < cap) {
                add_sim_body(s, c, &b[n], n);
                exclude_new(s, c, b, n + 1, n);
                ++n;
            }
        }
        px_status st = px_scene_step(s, (double)step, &e);
        CHECK(st == PX_OK, "%s: step %d: %s", c->name, step, e.message);
        size_t np, ne;
        const px_scene_pair *pr = px_scene_pairs(s, &np);
        const px_scene_event *ev = px_scene_events(s, &ne);
        px_scene_stats stats;
        px_scene_get_stats(s, &stats);
        checked += stats.pairs_checked;
        candidates += stats.candidate_pairs;
        /* Order. */
        for (size_t k = 0; k + 1 < np; ++k)
            CHECK(pr[k].body_a < pr[k + 1].body_a ||
                      (pr[k].body_a == pr[k + 1].body_a && pr[k].body_b < pr[k + 1].body_b),
                  "%s: pairs out of order", c->name);
        /* Brute force. */
        size_t found = 0;
        size_t expect_events = 0;
        for (int i = 0; i < n; ++i)
            for (int j = i + 1; j < n; ++j) {
                sim_body *x = &b[i], *y = &b[j];
                int both_alive = x->alive && y->alive;
                int was = contact[(size_t)i * cap + j];
                if (!both_alive || !paired(c, x, y) || (x->fixed && y->fixed && 0)) {
                    if (was) {
                        /* ended by removal */
                        contact[(size_t)i * cap + j] = 0;
                        expect_events++;
                    }
                    continue;
                }
                px_vec3 pa, pb;
                double d = pair_distance(x, y, &pa, &pb);
                uint32_t a = x->id < y->id ? x->id : y->id, bb = x->id < y->id ? y->id : x->id;
                const px_scene_pair *hit = NULL;
                for (size_t k = 0; k < np; ++k)
                    if (pr[k].body_a == a && pr[k].body_b == bb) hit = &pr[k];
                double tol = 1e-9 * (1.0 + d);
                if (d <= c->report - tol) {
                    if (!hit) {
                        if (mismatches++ < 10)
                            CHECK(0, "%s: step %d: pair (%u, %u) at %.17g missed (report %g)", c->name, step,
                                  a, bb, d, c->report);
                    } else {
                        double err = fabs(hit->distance - d);
                        if (err > worst) worst = err;
                        CHECK(err <= tol, "%s: step %d: pair (%u, %u) distance %.17g, brute force %.17g",
                              c->name, step, a, bb, hit->distance, d);
                    }
                } else if (d > c->report + tol && hit) {
                    if (mismatches++ < 10)
                        CHECK(0, "%s: step %d: pair (%u, %u) reported at %.17g, brute force %.17g > %g",
                              c->name, step, a, bb, hit->distance, d, c->report);
                }
                if (hit) ++found;
                int now = hit ? (int)hit->contact : 0;
                if (hit) CHECK(hit->contact == (hit->distance <= c->margin), "contact flag");
                if (now != was) expect_events++;
                contact[(size_t)i * cap + j] = (unsigned char)now;
            }
        CHECK(found == np, "%s: step %d: %zu reported pairs, %zu matched", c->name, step, np, found);
        if (ne != expect_events && event_mismatches++ < 5)
            CHECK(0, "%s: step %d: %zu events, expected %zu", c->name, step, ne, expect_events);
        for (size_t k = 0; k < np; ++k) {
            uint64_t w[3] = {pr[k].body_a, pr[k].body_b, 0};
            memcpy(&w[2], &pr[k].distance, sizeof(double));
            for (int m = 0; m < 3; ++m) hash = (hash ^ w[m]) * 1099511628211ull;
        }
        for (size_t k = 0; k < ne; ++k)
            hash = (hash ^ (ev[k].body_a * 31u + ev[k].body_b * 7u + ev[k].began)) * 1099511628211ull;
        /* The work done, too: the same on any number of threads. */
        hash = (hash ^ stats.pairs_checked) * 1099511628211ull;
        hash = (hash ^ stats.pairs_due) * 1099511628211ull;
        /* Global minimum now and then. */
        if (step % 10 == 3) {
            px_scene_pair m;
            CHECK(px_scene_min_distance(s, &m, &e) == PX_OK, "min distance: %s", e.message);
            double best = INFINITY;
            for (int i = 0; i < n; ++i)
                for (int j = i + 1; j < n; ++j) {
                    if (!b[i].alive || !b[j].alive || !paired(c, &b[i], &b[j])) continue;
                    px_vec3 pa, pb;
                    double d = pair_distance(&b[i], &b[j], &pa, &pb);
                    if (d < best) best = d;
                }
            CHECK(fabs(m.distance - best) <= 1e-9 * (1 + best),
                  "%s: step %d: min distance %.17g, brute force %.17g", c->name, step, m.distance, best);
        }
    }
    if (verbose)
        printf("  %s: %d bodies, %d steps: %.1f checks/step of %.1f candidate pairs; worst distance error "
               "%.3g\n",
               c->name, c->bodies, c->steps, (double)checked / c->steps, (double)candidates / c->steps,
               worst);
    px_scene_destroy(s);
    for (int i = 0; i < n; ++i) free_sim_body(&b[i]);
    free(b);
    free(contact);
    return hash;
}

/* 1 when world point w lies in the posed polytope up to tol (px_distance
 * from a one-point polytope; a query's common point lies on both surfaces,
 * an inner ball's inside both). */
static int point_inside(px_vec3 w, const px_convex *c, const px_pose *pose, double tol) {
    double xyz[3] = {w.x, w.y, w.z};
    px_convex *pt = px_convex_create(xyz, 1, NULL, NULL);
    px_pose id;
    px_pose_from_quat((double[4]){1, 0, 0, 0}, NULL, &id);
    px_distance_result r;
    int in = pt && px_distance(pt, &id, c, pose, NULL, NULL, &r) == PX_OK &&
             r.distance <= tol * (1.0 + fabs(w.x) + fabs(w.y) + fabs(w.z));
    px_convex_destroy(pt);
    return in;
}

/* Deeply overlapping polytopes are answered by their inner balls, without
 * a query (scene.c, inner_overlap): pairs of hulls about one centre, some
 * with poses a little off rotations (1e-7, px_pose_check allows 1e-6),
 * then drawn apart step by step through the end of the overlap, against
 * brute force at every step; every reported common point lies in both
 * solids (an independent px_distance from the point). */
static void test_inner_balls(void) {
    rng_state = 777;
    enum { PAIRS = 40 };
    px_scene_options o;
    memset(&o, 0, sizeof o);
    o.margin = 0.05;
    px_error e;
    px_scene *s = px_scene_create(&o, &e);
    CHECK(s != NULL, "inner balls: create: %s", e.message);
    if (!s) return;
    px_convex *c[2 * PAIRS];
    px_pose pose[2 * PAIRS];
    px_vec3 dir[PAIRS];
    for (int i = 0; i < 2 * PAIRS; ++i) {
        c[i] = random_hull(8 + (int)(urand() * 40), 0.5 + 0.5 * urand());
        double q[4] = {1, 0, 0, 0};
        turn(q, 3.0 * urand());
        /* Pairs 10 apart along x: no two pairs meet. */
        pose[i] = pose_of(q, (px_vec3){10.0 * (i / 2), 0.1 * srand1(), 0.1 * srand1()});
        if (i % 4 == 3)
            for (int k = 0; k < 9; ++k) pose[i].r[k] *= 1.0 + 1e-7 * srand1();
        px_body_desc d;
        memset(&d, 0, sizeof d);
        d.convex = c[i];
        d.pose = pose[i];
        d.max_speed = 0.1;
        d.max_angular_speed = 0.05;
        uint32_t id;
        CHECK(px_scene_add_body(s, &d, &id, &e) == PX_OK && id == (uint32_t)i, "inner balls: add: %s",
              e.message);
    }
    for (int p = 0; p < PAIRS; ++p) {
        double x = srand1(), y = srand1(), z = srand1(), l = sqrt(x * x + y * y + z * z) + 1e-9;
        dir[p] = (px_vec3){x / l, y / l, z / l};
    }
    int skipped_steps = 0, certified_total = 0;
    for (int step = 0; step < 30; ++step) {
        if (step > 0)
            for (int p = 0; p < PAIRS; ++p) {
                px_pose *b = &pose[2 * p + 1];
                b->t.x += 0.09 * dir[p].x, b->t.y += 0.09 * dir[p].y, b->t.z += 0.09 * dir[p].z;
                CHECK(px_scene_set_pose(s, (uint32_t)(2 * p + 1), b, &e) == PX_OK, "inner balls: pose: %s",
                      e.message);
            }
        CHECK(px_scene_step(s, step, &e) == PX_OK, "inner balls: step %d: %s", step, e.message);
        size_t np;
        const px_scene_pair *pr = px_scene_pairs(s, &np);
        px_scene_stats st;
        px_scene_get_stats(s, &st);
        int touching = 0;
        for (int p = 0; p < PAIRS; ++p) {
            px_distance_result r;
            CHECK(px_distance(c[2 * p], &pose[2 * p], c[2 * p + 1], &pose[2 * p + 1], NULL, NULL, &r) ==
                      PX_OK,
                  "inner balls: brute force");
            const px_scene_pair *hit = NULL;
            for (size_t k = 0; k < np; ++k)
                if (pr[k].body_a == (uint32_t)(2 * p) && pr[k].body_b == (uint32_t)(2 * p + 1)) hit = &pr[k];
            if (r.distance <= o.margin - 1e-9) {
                CHECK(hit && fabs(hit->distance - r.distance) <= 1e-9 * (1 + r.distance),
                      "inner balls: step %d pair %d: %.17g, brute force %.17g", step, p,
                      hit ? hit->distance : -1.0, r.distance);
            } else if (r.distance > o.margin + 1e-9) {
                CHECK(!hit, "inner balls: step %d pair %d reported at %.17g, brute force %.17g", step, p,
                      hit->distance, r.distance);
            }
            if (hit && hit->distance == 0.0) {
                ++touching;
                /* Skewed poses: px_distance measures in the body's frame
                 * through R^T, off the inverse by the skew (1e-7) times the
                 * coordinates. */
                double tol = p % 2 == 1 ? 1e-6 : 1e-12;
                CHECK(point_inside(hit->point_a, c[2 * p], &pose[2 * p], tol) &&
                          point_inside(hit->point_a, c[2 * p + 1], &pose[2 * p + 1], tol),
                      "inner balls: step %d pair %d: common point outside a body", step, p);
            }
        }
        /* At the start every pair overlaps about one centre: none needs a
         * query; later the certified ones are those not measured. */
        if (step == 0)
            CHECK(st.pairs_checked == 0, "inner balls: %llu queries at the start",
                  (unsigned long long)st.pairs_checked);
        certified_total +=
            touching - (int)(st.pairs_checked < (uint64_t)touching ? st.pairs_checked : (uint64_t)touching);
        if (touching == 0) ++skipped_steps;
    }
    CHECK(skipped_steps > 0, "inner balls: the pairs never came apart");
    printf("  inner balls: %d overlapping pair-steps answered without a query\n", certified_total);
    px_scene_destroy(s);
    for (int i = 0; i < 2 * PAIRS; ++i) px_convex_destroy(c[i]);
}

/* The scheduler must skip most pairs of a sparse, slow scene. */
static void test_savings(void) {
    sim c = {"savings", 80, 120, 0, 14.0, 0.02, 0.01, 0.05, 0.3, 0, 0, 0, 0, 0, 0, 0};
    rng_state = 7;
    run(&c, 1);
}

static void test_bad_inputs(void) {
    px_error e;
    px_scene_options o;
    memset(&o, 0, sizeof o);
    o.margin = -1;
    CHECK(px_scene_create(&o, &e) == NULL && e.code == PX_ERR_INVALID_ARGUMENT, "negative margin refused");
    o.margin = NAN;
    CHECK(px_scene_create(&o, &e) == NULL, "NaN margin refused");
    o.margin = 0.5;
    o.report_distance = 0.1;
    CHECK(px_scene_create(&o, &e) == NULL, "report below margin refused");
    o.report_distance = 1.0;
    o.reserved[2] = 1;
    CHECK(px_scene_create(&o, &e) == NULL, "reserved refused");
    o.reserved[2] = 0;
    px_scene *s = px_scene_create(&o, &e);
    CHECK(s != NULL, "create");
    px_convex *c = random_hull(12, 1.0);
    px_body_desc d;
    memset(&d, 0, sizeof d);
    d.pose = px_pose_identity();
    uint32_t id;
    CHECK(px_scene_add_body(s, &d, &id, &e) == PX_ERR_INVALID_ARGUMENT, "no shape refused");
    d.convex = c;
    d.max_speed = -1;
    CHECK(px_scene_add_body(s, &d, &id, &e) == PX_ERR_INVALID_ARGUMENT, "negative speed refused");
    d.max_speed = NAN;
    CHECK(px_scene_add_body(s, &d, &id, &e) == PX_ERR_INVALID_ARGUMENT, "NaN speed refused");
    d.max_speed = 1;
    d.pose.t.x = NAN;
    CHECK(px_scene_add_body(s, &d, &id, &e) == PX_ERR_NON_FINITE, "NaN pose refused: %d", e.code);
    d.pose.t.x = 1e300;
    CHECK(px_scene_add_body(s, &d, &id, &e) == PX_ERR_RANGE, "far pose refused");
    d.pose = px_pose_identity();
    d.flags = 8;
    CHECK(px_scene_add_body(s, &d, &id, &e) == PX_ERR_INVALID_ARGUMENT, "unknown flag refused");
    d.flags = PX_BODY_STATIC;
    uint32_t fixed;
    CHECK(px_scene_add_body(s, &d, &fixed, &e) == PX_OK, "static body");
    d.flags = 0;
    CHECK(px_scene_add_body(s, &d, &id, &e) == PX_OK && id == 1, "second body gets id 1");
    px_pose p = px_pose_identity();
    CHECK(px_scene_set_pose(s, fixed, &p, &e) == PX_ERR_INVALID_ARGUMENT, "static body refuses a pose");
    CHECK(px_scene_set_pose(s, 99, &p, &e) == PX_ERR_INVALID_ARGUMENT, "unknown body");
    /* Every entry of the rotation, made NaN or infinite, is refused, and
     * without arithmetic on it (the tests run with FP traps). */
    for (int i = 0; i < 9; ++i) {
        const double bad[3] = {NAN, INFINITY, -INFINITY};
        for (int k = 0; k < 3; ++k) {
            px_pose q = px_pose_identity();
            q.r[i] = bad[k];
            px_status st = px_scene_set_pose(s, id, &q, &e);
            CHECK(st != PX_OK, "rotation entry %d = %g refused", i, bad[k]);
        }
    }
    p.r[0] = 2;
    CHECK(px_scene_set_pose(s, id, &p, &e) == PX_ERR_INVALID_POSE, "bad rotation refused");
    CHECK(px_scene_set_velocity(s, id, (px_vec3){5, 0, 0}, 0, &e) == PX_ERR_INVALID_ARGUMENT,
          "velocity above the bound refused");
    {
        /* Review s32: a NaN centre was PX_ERR_INVALID_ARGUMENT (base.h: NaN
         * input is PX_ERR_NON_FINITE), and a static body took a velocity. */
        px_body_desc cd = d;
        uint32_t cid;
        cd.center = (px_vec3){NAN, 0, 0};
        CHECK(px_scene_add_body(s, &cd, &cid, &e) == PX_ERR_NON_FINITE, "NaN centre: %s", e.message);
        cd.center = (px_vec3){1e300, 0, 0};
        CHECK(px_scene_add_body(s, &cd, &cid, &e) == PX_ERR_RANGE, "centre 1e300: %s", e.message);
        cd.center = (px_vec3){0, 0, 0};
        cd.flags = PX_BODY_STATIC;
        CHECK(px_scene_add_body(s, &cd, &cid, &e) == PX_OK, "static body: %s", e.message);
        CHECK(px_scene_set_velocity(s, cid, (px_vec3){0, 0, 0}, 0, &e) == PX_ERR_INVALID_ARGUMENT,
              "velocity of a static body refused");
        px_scene_remove_body(s, cid, &e);
    }
    {
        /* Speeds whose squares overflow are measured without overflow (a
         * review found 1e200 refused as infinite under a bound of 1e300). */
        px_body_desc f = d;
        f.max_speed = 1e300;
        uint32_t fast;
        CHECK(px_scene_add_body(s, &f, &fast, &e) == PX_OK, "fast body");
        CHECK(px_scene_set_velocity(s, fast, (px_vec3){1e200, -1e200, 0}, 0, &e) == PX_OK,
              "speed 1.4e200: %s", e.message);
        CHECK(px_scene_set_velocity(s, fast, (px_vec3){0, 8e299, 6e299}, 0, &e) == PX_OK, "speed 1e300: %s",
              e.message);
        CHECK(px_scene_set_velocity(s, fast, (px_vec3){0, 8e299, 6.1e299}, 0, &e) == PX_ERR_INVALID_ARGUMENT,
              "speed above 1e300 refused");
        CHECK(px_scene_remove_body(s, fast, &e) == PX_OK, "remove fast body");
    }
    CHECK(px_scene_exclude_pair(s, id, id, &e) == PX_ERR_INVALID_ARGUMENT, "self exclusion refused");
    CHECK(px_scene_step(s, NAN, &e) == PX_ERR_INVALID_ARGUMENT, "NaN time refused");
    CHECK(px_scene_step(s, 1.0, &e) == PX_OK, "step");
    size_t n;
    const px_scene_pair *pr = px_scene_pairs(s, &n);
    CHECK(n == 1 && pr[0].contact == 1 && pr[0].distance == 0.0, "two coincident bodies touch (%zu pairs)",
          n);
    CHECK(px_scene_step(s, 0.5, &e) == PX_ERR_INVALID_ARGUMENT, "time going back refused");
    /* Moving in zero time breaks any finite bound: the pair is checked. */
    p = px_pose_identity();
    p.t.x = 10;
    CHECK(px_scene_set_pose(s, id, &p, &e) == PX_OK, "teleport");
    CHECK(px_scene_step(s, 1.0, &e) == PX_OK, "step at the same time");
    pr = px_scene_pairs(s, &n);
    CHECK(n == 0, "teleported body reported apart (%zu pairs)", n);
    size_t ne;
    const px_scene_event *ev = px_scene_events(s, &ne);
    CHECK(ne == 1 && ev[0].began == 0, "contact ended (%zu events)", ne);
    px_scene_stats st;
    px_scene_get_stats(s, &st);
    CHECK(st.violations == 1, "the teleport counted as a violation (%u)", st.violations);
    CHECK(px_scene_remove_body(s, 7, &e) == PX_ERR_INVALID_ARGUMENT, "unknown body removal refused");
    CHECK(px_scene_remove_body(s, fixed, &e) == PX_OK, "remove");
    CHECK(px_scene_body_user(s, fixed) == NULL, "removed body has no user pointer");
    d.flags = 0;
    d.user = &n;
    CHECK(px_scene_add_body(s, &d, &id, &e) == PX_OK && id == 0, "freed id reused");
    CHECK(px_scene_body_user(s, id) == &n, "user pointer");
    px_scene_destroy(s);
    /* A point body with unbounded speeds, jumping around a polytope: checked
     * at every step, never a NaN. */
    double pt[3] = {0, 0, 0};
    px_convex *point = px_convex_create(pt, 1, NULL, &e);
    CHECK(point != NULL, "one-point polytope: %s", e.message);
    o.margin = 0.1;
    o.report_distance = 0.5;
    s = px_scene_create(&o, &e);
    memset(&d, 0, sizeof d);
    d.convex = c;
    d.pose = px_pose_identity();
    d.flags = PX_BODY_STATIC;
    uint32_t ih, ip;
    CHECK(px_scene_add_body(s, &d, &ih, &e) == PX_OK, "hull");
    d.convex = point;
    d.flags = 0;
    d.max_speed = INFINITY;
    d.max_angular_speed = INFINITY;
    CHECK(px_scene_add_body(s, &d, &ip, &e) == PX_OK, "point with infinite speeds");
    for (int k = 0; k < 200; ++k) {
        p = px_pose_identity();
        p.t = (px_vec3){3 * srand1(), 3 * srand1(), 3 * srand1()};
        CHECK(px_scene_set_pose(s, ip, &p, &e) == PX_OK, "pose");
        CHECK(px_scene_step(s, k, &e) == PX_OK, "step");
        px_distance_result r;
        px_pose idp = px_pose_identity();
        px_distance(c, &idp, point, &p, NULL, NULL, &r);
        pr = px_scene_pairs(s, &n);
        CHECK((n == 1) == (r.distance <= 0.5) && (n == 0 || pr[0].distance == r.distance),
              "point at %g: %zu pairs", r.distance, n);
    }
    px_scene_destroy(s);
    px_convex_destroy(point);
    px_convex_destroy(c);
}

/* A triangle model (triangle leaves) of a mesh given by arrays; NULL with
 * err set when the mesh or the model cannot be built. */
static px_model *triangle_model(const double *xyz, uint32_t nv, const uint32_t *tri, uint32_t nt,
                                px_error *err) {
    px_mesh_desc md;
    memset(&md, 0, sizeof md);
    md.xyz = xyz;
    md.vertex_count = nv;
    md.triangles = tri;
    md.triangle_count = nt;
    px_mesh *mesh = px_mesh_create(&md, NULL, err);
    px_model_options mo;
    memset(&mo, 0, sizeof mo);
    mo.pieces = PX_PIECES_TRIANGLES;
    px_model *m = mesh ? px_model_create_from_mesh(mesh, &mo, err) : NULL;
    px_mesh_destroy(mesh);
    return m;
}

/* n closed cubes of half-size h (1 or 2), centred at x = 0 and x = gap,
 * as one triangle model (n connected pieces). */
static px_model *cubes_triangles(double h, int n, double gap) {
    double xyz[48];
    for (int c = 0; c < 16; ++c)
        for (int k = 0; k < 3; ++k) xyz[3 * c + k] = ((c & 7) >> k) & 1 ? h : -h;
    for (int c = 8; c < 16; ++c) xyz[3 * c] += gap;
    const uint32_t one[36] = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                              2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
    uint32_t tri[72];
    for (int i = 0; i < 36; ++i) tri[i] = one[i], tri[36 + i] = one[i] + 8;
    return triangle_model(xyz, 8 * (uint32_t)n, tri, 12 * (uint32_t)n, NULL);
}

/* A closed box mesh of half-size h at the origin, as a triangle model. */
static px_model *box_triangles(double h) { return cubes_triangles(h, 1, 0.0); }

/* A closed box mesh (triangle leaves: its inside counts through the solid
 * test, not the distance query) with a small polytope moving through it:
 * inside, the pair is in contact at distance 0 and marked contained. */
static void test_containment(void) {
    const double h = 2.0;
    px_error e;
    px_model *box = box_triangles(h);
    CHECK(box != NULL, "box model");
    px_convex *small = random_hull(12, 0.3);
    px_scene_options o;
    memset(&o, 0, sizeof o);
    o.margin = 0.05;
    o.report_distance = 0.2;
    px_scene *s = px_scene_create(&o, &e);
    px_body_desc d;
    memset(&d, 0, sizeof d);
    d.model = box;
    d.pose = px_pose_identity();
    d.flags = PX_BODY_STATIC;
    uint32_t ib, ic;
    CHECK(px_scene_add_body(s, &d, &ib, &e) == PX_OK, "add box");
    memset(&d, 0, sizeof d);
    d.convex = small;
    d.pose = px_pose_identity();
    d.pose.t.x = -4;
    d.max_speed = 0.1;
    CHECK(px_scene_add_body(s, &d, &ic, &e) == PX_OK, "add small");
    int inside_steps = 0;
    for (int k = 0; k <= 80; ++k) {
        px_pose p = px_pose_identity();
        p.t.x = -4 + 0.1 * k;
        CHECK(px_scene_set_pose(s, ic, &p, &e) == PX_OK, "pose");
        CHECK(px_scene_step(s, k, &e) == PX_OK, "step: %s", e.message);
        size_t n;
        const px_scene_pair *pr = px_scene_pairs(s, &n);
        /* Brute force: the surface distance, and inside when the centre is
         * inside the box and the surfaces are apart. */
        px_model_distance_result r;
        px_pose id = px_pose_identity();
        px_model_distance_convex(box, &id, small, &p, NULL, &r);
        int inside = fabs(p.t.x) < h && r.distance > 0;
        double want = inside ? 0.0 : r.distance;
        if (want <= o.report_distance) {
            CHECK(n == 1 && pr[0].distance == want && pr[0].contained == (uint32_t)(inside ? 2 | 8 : 0) &&
                      pr[0].contact == (want <= o.margin),
                  "containment: x %.2f: %zu pairs, distance %g (want %g), contained %u", p.t.x, n,
                  n ? pr[0].distance : -1.0, want, n ? pr[0].contained : 9u);
        } else {
            CHECK(n == 0, "containment: x %.2f: %zu pairs at surface distance %g", p.t.x, n, r.distance);
        }
        inside_steps += inside;
    }
    CHECK(inside_steps > 20, "the polytope spent steps inside (%d)", inside_steps);
    px_scene_destroy(s);
    px_convex_destroy(small);
    px_model_destroy(box);
}

/* A body of two pieces whose one piece lies inside a closed box and the
 * other outside: contained says a piece is inside (bit 0 or 1) but not
 * all of it (bits 2 and 3 clear); with both pieces inside it says all. */
static void test_partial_containment(void) {
    px_error e;
    px_model *box = box_triangles(1.5), *two = cubes_triangles(0.25, 2, 10.0),
             *near = cubes_triangles(0.25, 2, 1.0);
    CHECK(box && two && near, "models");
    px_scene_options o;
    memset(&o, 0, sizeof o);
    px_scene *s = px_scene_create(&o, &e);
    px_body_desc d;
    memset(&d, 0, sizeof d);
    d.pose = px_pose_identity();
    d.flags = PX_BODY_STATIC;
    uint32_t id[3];
    d.model = two;
    CHECK(px_scene_add_body(s, &d, &id[0], &e) == PX_OK, "add two");
    d.model = box;
    CHECK(px_scene_add_body(s, &d, &id[1], &e) == PX_OK, "add box");
    d.model = near;
    d.pose.t.x = -0.5; /* its cubes at -0.5 and 0.5: both inside the box */
    d.pose.t.y = 30.0;
    CHECK(px_scene_add_body(s, &d, &id[2], &e) == PX_OK, "add near");
    px_pose boxed = px_pose_identity();
    boxed.t.y = 30.0;
    memset(&d, 0, sizeof d);
    d.model = box;
    d.pose = boxed;
    d.flags = PX_BODY_STATIC;
    uint32_t id4;
    CHECK(px_scene_add_body(s, &d, &id4, &e) == PX_OK, "add second box");
    CHECK(px_scene_step(s, 0, &e) == PX_OK, "step: %s", e.message);
    size_t n;
    const px_scene_pair *pr = px_scene_pairs(s, &n);
    int seen = 0;
    for (size_t i = 0; i < n; ++i) {
        if (pr[i].body_a == id[0] && pr[i].body_b == id[1]) {
            CHECK(pr[i].distance == 0.0 && pr[i].contained == 1, "one of two pieces inside: contained %u",
                  pr[i].contained);
            seen |= 1;
        }
        if (pr[i].body_a == id[2] && pr[i].body_b == id4) {
            CHECK(pr[i].distance == 0.0 && pr[i].contained == (1 | 4), "both pieces inside: contained %u",
                  pr[i].contained);
            seen |= 2;
        }
    }
    CHECK(seen == 3, "both pairs reported (%d, %zu pairs)", seen, n);
    px_scene_destroy(s);
    px_model_destroy(box);
    px_model_destroy(two);
    px_model_destroy(near);
}

/* Static model bodies (an assembly check): a pair of two static bodies is
 * never measured again, so its node-pair cache is given back after its
 * query. 40 overlapping boxes of 2,000 triangles (every pair in contact):
 * the scene keeps a record per pair, not up to model_cache_bytes (before,
 * about 20 KB a pair). */
static void test_static_caches(void) {
    const int n = 40;
    px_error e;
    /* a box with its faces split into 2 x 10 x 10 triangles each: deep fronts */
    enum { G = 10 };
    double xyz[6 * (G + 1) * (G + 1) * 3];
    uint32_t tri[6 * G * G * 6];
    uint32_t nv = 0, nt = 0;
    for (int f = 0; f < 6; ++f) {
        int ax = f / 2, sgn = f % 2 ? 1 : -1, u = (ax + 1) % 3, w = (ax + 2) % 3;
        uint32_t base = nv;
        for (int i = 0; i <= G; ++i)
            for (int j = 0; j <= G; ++j, ++nv) {
                xyz[3 * nv + ax] = sgn;
                xyz[3 * nv + u] = -1.0 + 2.0 * i / G;
                xyz[3 * nv + w] = -1.0 + 2.0 * j / G;
            }
        for (int i = 0; i < G; ++i)
            for (int j = 0; j < G; ++j) {
                uint32_t a = base + (uint32_t)(i * (G + 1) + j), b = a + G + 1, c = a + 1, d = b + 1;
                uint32_t q[6] = {a, b, c, c, b, d};
                if (sgn < 0) q[1] = c, q[2] = b, q[4] = d, q[5] = b;
                memcpy(tri + 3 * nt, q, sizeof q);
                nt += 2;
            }
    }
    px_model *box = triangle_model(xyz, nv, tri, nt, &e);
    CHECK(box != NULL, "static caches: box model: %s", e.message);
    if (!box) return;
    px_scene_options o;
    memset(&o, 0, sizeof o);
    o.margin = o.report_distance = 0.01;
    px_scene *s = px_scene_create(&o, &e);
    for (int i = 0; i < n; ++i) {
        px_body_desc d;
        memset(&d, 0, sizeof d);
        d.model = box;
        double q[4] = {srand1(), srand1(), srand1(), 1.0},
               t[3] = {0.3 * srand1(), 0.3 * srand1(), 0.3 * srand1()};
        double l = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
        for (int k = 0; k < 4; ++k) q[k] /= l;
        CHECK(px_pose_from_quat(q, t, &d.pose) == PX_OK, "static caches: pose");
        d.flags = PX_BODY_STATIC;
        uint32_t id;
        CHECK(px_scene_add_body(s, &d, &id, &e) == PX_OK, "static caches: add: %s", e.message);
    }
    px_scene_stats before;
    px_scene_get_stats(s, &before);
    CHECK(px_scene_step(s, 0.0, &e) == PX_OK, "static caches: step: %s", e.message);
    size_t np;
    const px_scene_pair *p = px_scene_pairs(s, &np);
    size_t contacts = 0;
    for (size_t i = 0; i < np; ++i) contacts += p[i].contact;
    px_scene_stats st;
    px_scene_get_stats(s, &st);
    size_t pairs = (size_t)n * (n - 1) / 2;
    double per_pair = ((double)st.memory_bytes - (double)before.memory_bytes) / (double)pairs;
    CHECK(contacts == pairs, "static caches: %zu of %zu pairs in contact", contacts, pairs);
    CHECK(per_pair < 2048.0, "static caches: %.0f bytes a pair after the step", per_pair);
    printf("static caches: %zu pairs in contact, %.0f bytes a pair after the step\n", pairs, per_pair);
    px_scene_destroy(s);
    px_model_destroy(box);
}

/* Bodies at tiny scales (a review's finding): lengths of moves below about
 * 1e-154 underflowed in their squares, so a body of half-side 1e-170 never
 * travelled, never left its fat box and was never paired. Cubes of
 * half-side s from 1e-300 to 1e-120, one approaching another within its
 * speed bound while turning, one teleported onto it, checked at every
 * step against px_distance. */
static void test_tiny_scales(void) {
    const double scales[] = {1e-300, 1e-250, 1e-200, 1e-170, 1e-160, 1e-120};
    for (size_t si = 0; si < sizeof scales / sizeof scales[0]; ++si) {
        const double sz = scales[si];
        double box[24];
        for (int c = 0; c < 8; ++c)
            for (int k = 0; k < 3; ++k) box[3 * c + k] = (c >> k) & 1 ? sz : -sz;
        px_error e;
        px_convex *cv = px_convex_create(box, 8, NULL, &e);
        CHECK(cv != NULL, "tiny %g: cube: %s", sz, e.message);
        if (!cv) continue;
        px_scene_options o;
        memset(&o, 0, sizeof o);
        o.report_distance = sz;
        o.margin = 0.1 * sz;
        px_scene *s = px_scene_create(&o, &e);
        px_body_desc d;
        memset(&d, 0, sizeof d);
        d.convex = cv;
        d.pose = px_pose_identity();
        d.max_speed = sz;
        d.max_angular_speed = 0.3;
        uint32_t id[3];
        CHECK(px_scene_add_body(s, &d, &id[0], &e) == PX_OK, "tiny: add");
        d.pose.t.x = 10 * sz;
        CHECK(px_scene_add_body(s, &d, &id[1], &e) == PX_OK, "tiny: add");
        d.pose.t.x = -100 * sz;
        CHECK(px_scene_add_body(s, &d, &id[2], &e) == PX_OK, "tiny: add");
        int found = 0;
        for (int k = 0; k <= 14; ++k) {
            px_pose p[3];
            p[0] = px_pose_identity();
            /* body 1: 0.8 s a step toward body 0, turning 0.25 rad a step */
            double ang = 0.25 * k, q[4] = {0, 0, sin(0.5 * ang), cos(0.5 * ang)},
                   t[3] = {(10.0 - 0.8 * k) * sz, 0, 0};
            px_pose_from_quat(q, t, &p[1]);
            /* body 2: far, then teleported onto body 0 at step 7 */
            p[2] = px_pose_identity();
            p[2].t.x = k < 7 ? -100 * sz : 0.5 * sz;
            CHECK(px_scene_set_pose(s, id[1], &p[1], &e) == PX_OK &&
                      px_scene_set_pose(s, id[2], &p[2], &e) == PX_OK,
                  "tiny: pose");
            CHECK(px_scene_step(s, (double)k, &e) == PX_OK, "tiny %g: step: %s", sz, e.message);
            size_t n;
            const px_scene_pair *pr = px_scene_pairs(s, &n);
            for (int a = 0; a < 3; ++a)
                for (int b = a + 1; b < 3; ++b) {
                    px_distance_result r;
                    px_distance(cv, &p[a], cv, &p[b], NULL, NULL, &r);
                    const px_scene_pair *hit = NULL;
                    for (size_t i = 0; i < n; ++i)
                        if (pr[i].body_a == (uint32_t)a && pr[i].body_b == (uint32_t)b) hit = &pr[i];
                    if (r.distance <= o.report_distance) {
                        ++found;
                        CHECK(hit && fabs(hit->distance - r.distance) <= 1e-9 * sz,
                              "tiny %g: step %d: pair (%d, %d) at %g s %s (scene %g s)", sz, k, a, b,
                              r.distance / sz, hit ? "misreported" : "missed",
                              hit ? hit->distance / sz : -1.0);
                    } else {
                        CHECK(!hit || hit->distance > o.report_distance * 0.999999,
                              "tiny %g: step %d: pair (%d, %d) reported at %g s, is %g s", sz, k, a, b,
                              hit ? hit->distance / sz : -1.0, r.distance / sz);
                    }
                }
        }
        CHECK(found >= 10, "tiny %g: %d close pairs over the steps", sz, found);
        px_scene_destroy(s);
        px_convex_destroy(cv);
    }
}

/* Allocation: bodies moving periodically meet the same pairs every period,
 * so once the first period is over, steps allocate nothing. */
static size_t n_allocs;
static void *count_alloc(void *user, size_t size) {
    (void)user;
    ++n_allocs;
    return malloc(size);
}
static void count_free(void *user, void *p, size_t size) {
    (void)user;
    (void)size;
    free(p);
}

/* A scene on the counting allocator: margin 0.1, report distance 0.3. */
static px_scene *counting_scene(px_error *e) {
    static const px_allocator al = {count_alloc, count_free, NULL};
    px_scene_options o;
    memset(&o, 0, sizeof o);
    o.allocator = &al;
    o.margin = 0.1;
    o.report_distance = 0.3;
    return px_scene_create(&o, e);
}

static void test_no_allocation(void) {
    px_error e;
    px_scene *s = counting_scene(&e);
    enum { N = 60, PERIOD = 40 };
    px_convex *h[N];
    px_vec3 c[N], amp[N];
    uint32_t id[N];
    rng_state = 99;
    for (int i = 0; i < N; ++i) {
        h[i] = random_hull(16, 0.5 + 0.3 * urand());
        c[i] = (px_vec3){6 * urand(), 6 * urand(), 6 * urand()};
        amp[i] = (px_vec3){srand1(), srand1(), srand1()};
        px_body_desc d;
        memset(&d, 0, sizeof d);
        d.convex = h[i];
        d.pose = px_pose_identity();
        d.pose.t = c[i];
        d.max_speed = 0.2;
        CHECK(px_scene_add_body(s, &d, &id[i], &e) == PX_OK, "add");
    }
    size_t before = 0;
    for (int k = 0; k < 3 * PERIOD; ++k) {
        if (k == PERIOD) before = n_allocs;
        double ph = sin(2 * 3.14159265358979 * (k % PERIOD) / PERIOD);
        for (int i = 0; i < N; ++i) {
            px_pose p = px_pose_identity();
            p.t = (px_vec3){c[i].x + ph * amp[i].x, c[i].y + ph * amp[i].y, c[i].z + ph * amp[i].z};
            px_scene_set_pose(s, id[i], &p, NULL);
        }
        CHECK(px_scene_step(s, k, &e) == PX_OK, "step");
    }
    size_t np;
    px_scene_pairs(s, &np);
    CHECK(n_allocs == before, "steps after the first period allocated %zu times", n_allocs - before);
    px_scene_destroy(s);
    for (int i = 0; i < N; ++i) px_convex_destroy(h[i]);
}

/* The same with a triangle model (a closed box) and polytopes swinging
 * close to its faces and away, never far enough for the pairs to give
 * their node-pair caches back: its triangle leaves against the polytopes
 * are measured through a px_convex of each triangle built on the stack (it
 * once allocated at every leaf pair, CGAL's hull included: 44,112 times
 * here). */
static void test_no_allocation_model(void) {
    px_error e;
    px_scene *s = counting_scene(&e);
    px_model *box = box_triangles(1.0);
    CHECK(s && box, "scene and box");
    px_body_desc bd;
    memset(&bd, 0, sizeof bd);
    bd.model = box;
    bd.pose = px_pose_identity();
    bd.flags = PX_BODY_STATIC;
    uint32_t box_id = 0;
    CHECK(px_scene_add_body(s, &bd, &box_id, &e) == PX_OK, "add the box");
    enum { N = 6, PERIOD = 40 };
    const px_vec3 dir[N] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    px_convex *h[N];
    uint32_t id[N];
    rng_state = 7;
    for (int i = 0; i < N; ++i) {
        h[i] = random_hull(16, 0.4);
        px_body_desc d;
        memset(&d, 0, sizeof d);
        d.convex = h[i];
        d.pose = px_pose_identity();
        d.pose.t = (px_vec3){dir[i].x * (1.8), dir[i].y * (1.8), dir[i].z * (1.8)};
        d.max_speed = 0.2;
        d.max_angular_speed = 0.2;
        CHECK(px_scene_add_body(s, &d, &id[i], &e) == PX_OK, "add");
    }
    size_t before = 0, near = 0;
    for (int k = 0; k < 3 * PERIOD; ++k) {
        if (k == PERIOD) before = n_allocs;
        double ph = sin(2 * 3.14159265358979 * (k % PERIOD) / PERIOD);
        for (int i = 0; i < N; ++i) {
            double q[4] = {cos(0.2 * ph), sin(0.2 * ph), 0, 0}, t[3];
            px_vec3 c = (px_vec3){dir[i].x * (1.55 + 0.3 * ph), dir[i].y * (1.55 + 0.3 * ph),
                                  dir[i].z * (1.55 + 0.3 * ph)};
            t[0] = c.x, t[1] = c.y, t[2] = c.z;
            px_pose p;
            px_pose_from_quat(q, t, &p);
            px_scene_set_pose(s, id[i], &p, NULL);
        }
        CHECK(px_scene_step(s, k, &e) == PX_OK, "step");
        size_t np;
        const px_scene_pair *pp = px_scene_pairs(s, &np);
        for (size_t u = 0; u < np; ++u) near += pp[u].body_a == box_id && pp[u].distance < 0.3;
    }
    CHECK(near > 100, "the polytopes came near the box %zu times", near);
    CHECK(n_allocs == before, "steps after the first period allocated %zu times", n_allocs - before);
    px_scene_destroy(s);
    px_model_destroy(box);
    for (int i = 0; i < N; ++i) px_convex_destroy(h[i]);
}

/* Review cases (issue 11's review; the configurations are recorded here).
 * Each one once made px_scene_step miss a pair with PX_OK. */
static px_convex *box3(double hx, double hy, double hz) {
    double p[24];
    for (int c = 0; c < 8; ++c) {
        p[3 * c] = (c & 1) ? hx : -hx;
        p[3 * c + 1] = (c & 2) ? hy : -hy;
        p[3 * c + 2] = (c & 4) ? hz : -hz;
    }
    return px_convex_create(p, 8, NULL, NULL);
}

static px_pose at3(double x, double y, double z) {
    px_pose p = px_pose_identity();
    p.t = (px_vec3){x, y, z};
    return p;
}

static void test_review_cases(void) {
    px_error e;
    size_t n;
    /* 1. A 2 mm part parked 1e12 away and brought back, then moving 0.1 mm
     *    per step within its bounds onto another: a running sum of its
     *    motion had grown so large that the small moves rounded away. */
    {
        px_scene_options so = {0};
        so.report_distance = 1e-3;
        px_scene *s = px_scene_create(&so, &e);
        px_convex *c = box3(1e-3, 1e-3, 1e-3);
        px_body_desc d = {0};
        d.convex = c;
        d.max_speed = 1.0;
        d.max_angular_speed = 1.0;
        uint32_t a, b;
        d.pose = at3(0, 0, 0);
        px_scene_add_body(s, &d, &a, &e);
        d.pose = at3(0.01, 0, 0);
        px_scene_add_body(s, &d, &b, &e);
        double t = 0;
        px_scene_step(s, t, &e);
        px_pose far = at3(1e12, 0, 0), home = at3(0, 0, 0);
        px_scene_set_pose(s, a, &far, &e);
        px_scene_step(s, t += 1, &e);
        px_scene_set_pose(s, a, &home, &e);
        px_scene_step(s, t += 1, &e);
        int missed = 0;
        for (int i = 1; i <= 100; ++i) {
            px_pose p = at3(i * 1e-4, 0, 0);
            px_scene_set_pose(s, a, &p, &e);
            CHECK(px_scene_step(s, t += 1e-3, &e) == PX_OK, "step");
            px_distance_result r;
            px_distance(c, &p, c, &d.pose, NULL, NULL, &r);
            px_scene_pairs(s, &n);
            missed += r.distance <= so.report_distance && n == 0;
        }
        CHECK(missed == 0, "review 1: a part back from 1e12 missed at %d steps", missed);
        px_scene_destroy(s);
        px_convex_destroy(c);
    }
    /* 2. A rod of half-length 1000 turned by a matrix px_pose_check accepts
     *    (x scaled by 1 + 4.9e-7): its tip moves sqrt 2 farther than the
     *    angle of a true rotation says. */
    {
        px_scene_options so = {0};
        so.report_distance = 0.1;
        px_scene *s = px_scene_create(&so, &e);
        px_convex *rod = box3(1000, 0.5, 0.5), *c = box3(0.5, 0.5, 0.5);
        px_body_desc d = {0};
        d.max_speed = INFINITY;
        d.max_angular_speed = INFINITY;
        uint32_t a, b;
        d.convex = rod;
        d.pose = at3(0, 0, 0);
        px_scene_add_body(s, &d, &a, &e);
        px_pose pb = at3(1000 + 0.5 + 0.1 + 4e-4, 0, 0);
        d.convex = c;
        d.pose = pb;
        px_scene_add_body(s, &d, &b, &e);
        px_scene_step(s, 0, &e);
        px_pose q = px_pose_identity();
        q.r[0] = 1.0 + 4.9e-7;
        CHECK(px_pose_check(&q, &e) == PX_OK, "the skewed pose is accepted");
        px_scene_set_pose(s, a, &q, &e);
        px_scene_step(s, 1, &e);
        px_distance_result r;
        px_distance(rod, &q, c, &pb, NULL, NULL, &r);
        px_scene_pairs(s, &n);
        CHECK((r.distance <= 0.1) == (n == 1), "review 2: skewed rotation: distance %.9g, %zu pairs",
              r.distance, n);
        px_scene_destroy(s);
        px_convex_destroy(rod);
        px_convex_destroy(c);
    }
    /* 3. Steps at t = -1e308 then 1e308: the time step overflows to
     *    infinity, once read as "before the first step"; a body with zero
     *    speed bounds teleported onto another must be seen. */
    {
        px_scene_options so = {0};
        so.report_distance = 0.1;
        px_scene *s = px_scene_create(&so, &e);
        px_convex *c = box3(0.5, 0.5, 0.5);
        px_body_desc d = {0};
        d.convex = c;
        uint32_t a, b;
        d.pose = at3(0, 0, 0);
        px_scene_add_body(s, &d, &a, &e);
        d.pose = at3(1.5, 0, 0);
        px_scene_add_body(s, &d, &b, &e);
        px_scene_step(s, -1e308, &e);
        px_pose p = at3(1.2, 0, 0);
        px_scene_set_pose(s, a, &p, &e);
        CHECK(px_scene_step(s, 1e308, &e) == PX_OK, "step");
        px_scene_pairs(s, &n);
        CHECK(n == 1, "review 3: overflowing time step: %zu pairs", n);
        px_scene_destroy(s);
        px_convex_destroy(c);
    }
    /* Second review. 5. Two touching cubes both moved +100 in one step and
     *    still touching: the sweep, moving one body at a time, dropped the
     *    pair and added it back, with an ended and a began event. */
    for (uint32_t threads = 1; threads <= 2; ++threads) {
        px_scene_options so = {0};
        so.margin = 0.01;
        so.report_distance = 0.1;
        so.threads = threads;
        px_scene *s = px_scene_create(&so, &e);
        px_convex *c = box3(0.5, 0.5, 0.5);
        px_body_desc d = {0};
        d.convex = c;
        d.max_speed = INFINITY;
        uint32_t a, b;
        d.pose = at3(0, 0, 0);
        CHECK(px_scene_add_body(s, &d, &a, &e) == PX_OK, "add");
        d.pose = at3(1, 0, 0);
        CHECK(px_scene_add_body(s, &d, &b, &e) == PX_OK, "add");
        CHECK(px_scene_step(s, 0, &e) == PX_OK, "step");
        px_scene_events(s, &n);
        CHECK(n == 1, "review 5: the contact begins");
        px_pose pa = at3(100, 0, 0), pb = at3(101, 0, 0);
        px_scene_set_pose(s, a, &pa, &e);
        px_scene_set_pose(s, b, &pb, &e);
        CHECK(px_scene_step(s, 1, &e) == PX_OK, "step");
        px_scene_events(s, &n);
        CHECK(n == 0, "review 5: %zu events for a contact that held at both steps", n);
        px_scene_pairs(s, &n);
        CHECK(n == 1, "review 5: the pair is still reported");
        pa = at3(-100, 0, 0);
        px_scene_set_pose(s, a, &pa, &e);
        CHECK(px_scene_step(s, 2, &e) == PX_OK, "step");
        const px_scene_event *ev = px_scene_events(s, &n);
        CHECK(n == 1 && !ev[0].began, "review 5: the contact ends when the boxes part");
        px_scene_destroy(s);
        px_convex_destroy(c);
    }
    /* 6. A rotation that px_pose_check accepts but that stretches by
     *    1 + 4.9e-7 (s I): 1,000-unit cubes corner to corner at 0.0095, report
     *    distance 0.01. The bounding-sphere lower bound must count the
     *    stretch. */
    {
        px_scene_options so = {0};
        so.margin = 0.01;
        so.report_distance = 0.01;
        px_scene *s = px_scene_create(&so, &e);
        px_convex *c = box3(1000, 1000, 1000);
        double sc = 1 + 4.9e-7, k = 1000 + 1000 * sc + 0.0095 / sqrt(3.0);
        px_pose pa = px_pose_identity(), pb = at3(k, k, k);
        pa.r[0] = pa.r[4] = pa.r[8] = sc;
        CHECK(px_pose_check(&pa, &e) == PX_OK, "the stretched pose is accepted");
        px_distance_result r;
        CHECK(px_distance(c, &pa, c, &pb, NULL, NULL, &r) == PX_OK && r.distance <= 0.01, "cold distance");
        px_body_desc d = {0};
        d.convex = c;
        d.max_speed = 1;
        uint32_t a, b;
        d.pose = pa;
        CHECK(px_scene_add_body(s, &d, &a, &e) == PX_OK, "add");
        d.pose = pb;
        CHECK(px_scene_add_body(s, &d, &b, &e) == PX_OK, "add");
        CHECK(px_scene_step(s, 0, &e) == PX_OK, "step");
        const px_scene_pair *pr = px_scene_pairs(s, &n);
        CHECK(n == 1 && fabs(pr[0].distance - r.distance) <= 1e-9,
              "review 6: the pair at %.6g is reported (%zu pairs)", r.distance, n);
        px_scene_destroy(s);
        px_convex_destroy(c);
    }
}

/* Out of memory inside px_scene_step (review): 20 cubes moved onto one
 * point while the allocator fails from the k-th call; once memory is back,
 * every pair must be there. Also px_scene_add_body failing: no ghost body,
 * and every free gets the size that was allocated. */
static long fail_after = -1; /* allocations left before failing; -1: never */
static size_t bad_frees;
typedef struct sized {
    size_t size;
    double align;
} sized;
static void *failing_alloc(void *user, size_t size) {
    (void)user;
    if (fail_after == 0) return NULL;
    if (fail_after > 0) --fail_after;
    sized *p = malloc(sizeof(sized) + size);
    if (!p) return NULL;
    p->size = size;
    return p + 1;
}
static void failing_free(void *user, void *ptr, size_t size) {
    (void)user;
    if (!ptr) return;
    sized *p = (sized *)ptr - 1;
    bad_frees += p->size != size;
    free(p);
}

static void test_out_of_memory(void) {
    px_allocator al = {failing_alloc, failing_free, NULL};
    px_convex *c = box3(0.5, 0.5, 0.5);
    for (long k = 0; k < 60; ++k) {
        px_scene_options o;
        memset(&o, 0, sizeof o);
        o.allocator = &al;
        o.report_distance = 0.1;
        fail_after = -1;
        px_error e;
        px_scene *s = px_scene_create(&o, &e);
        enum { N = 20 };
        uint32_t id[N];
        int added = 0;
        fail_after = k; /* from the k-th allocation on, while adding and stepping */
        for (int i = 0; i < N; ++i) {
            px_body_desc d;
            memset(&d, 0, sizeof d);
            d.convex = c;
            d.pose = at3(3.0 * i, 0, 0);
            d.max_speed = INFINITY;
            if (px_scene_add_body(s, &d, &id[added], &e) == PX_OK) ++added;
        }
        px_scene_step(s, 0, &e);
        for (int i = 0; i < added; ++i) {
            px_pose p = at3(0.01 * i, 0, 0);
            px_scene_set_pose(s, id[i], &p, &e);
        }
        px_scene_step(s, 1, &e);
        fail_after = -1;
        CHECK(px_scene_step(s, 2, &e) == PX_OK, "k %ld: step once memory is back: %s", k, e.message);
        size_t n;
        const px_scene_pair *pr = px_scene_pairs(s, &n);
        CHECK(n == (size_t)added * (size_t)(added - 1) / 2, "k %ld: %zu pairs of %d bodies on one point", k,
              n, added);
        for (size_t i = 0; i < n; ++i)
            CHECK(pr[i].body_a < pr[i].body_b && pr[i].body_b < (uint32_t)N, "ids");
        px_scene_destroy(s);
    }
    CHECK(bad_frees == 0, "%zu frees with a size other than the allocation's", bad_frees);
    px_convex_destroy(c);
}

/* Second review (after the near list and threads): contacts ending while an
 * allocation fails. A slab with 12 cubes on it, each contact begun in its
 * own step; then the slab is removed (mode 0) or moved away (mode 1) with
 * the k-th allocation failing. Every contact must end with exactly one
 * event, or the call must fail; the reports after a failed step must be
 * readable (ASan checks the reads). */
static void test_out_of_memory_events(void) {
    px_allocator al = {failing_alloc, failing_free, NULL};
    double sl[24];
    for (int c = 0; c < 8; ++c) {
        sl[3 * c] = (c & 1) ? 30.0 : -1.0;
        sl[3 * c + 1] = (c & 2) ? 0.5 : -0.5;
        sl[3 * c + 2] = (c & 4) ? 0.0 : -1.0;
    }
    px_convex *slab = px_convex_create(sl, 8, NULL, NULL), *cube = box3(0.25, 0.25, 0.25);
    for (int mode = 0; mode < 2; ++mode)
        for (long k = 0; k < 12; ++k) {
            px_scene_options o = {0};
            o.allocator = &al;
            o.margin = 0.01;
            o.report_distance = 0.1;
            fail_after = -1;
            px_error e;
            px_scene *s = px_scene_create(&o, &e);
            px_body_desc d = {0};
            d.convex = slab;
            d.pose = at3(0, 0, 0);
            d.max_speed = INFINITY;
            uint32_t sid, id;
            CHECK(px_scene_add_body(s, &d, &sid, &e) == PX_OK, "slab");
            double t = 0;
            px_scene_step(s, t++, &e);
            long begun = 0, ended = 0;
            for (int i = 0; i < 12; ++i) {
                d.convex = cube;
                d.pose = at3(2.0 * i, 0, 0.25);
                d.max_speed = 0;
                CHECK(px_scene_add_body(s, &d, &id, &e) == PX_OK, "cube");
                CHECK(px_scene_step(s, t++, &e) == PX_OK, "step: %s", e.message);
                size_t ne;
                const px_scene_event *ev = px_scene_events(s, &ne);
                for (size_t j = 0; j < ne; ++j) begun += ev[j].began ? 1 : -1;
            }
            CHECK(begun == 12, "mode %d: %ld contacts began", mode, begun);
            fail_after = k;
            int removed = 1;
            if (mode == 0) {
                removed = px_scene_remove_body(s, sid, &e) == PX_OK;
            } else {
                px_pose far = at3(0, 0, -1000);
                CHECK(px_scene_set_pose(s, sid, &far, &e) == PX_OK, "set pose");
            }
            for (int i = 0; i < 4; ++i) {
                px_status st = px_scene_step(s, t++, &e);
                size_t ne, np;
                const px_scene_event *ev = px_scene_events(s, &ne);
                const px_scene_pair *pr = px_scene_pairs(s, &np);
                double sum = 0;
                for (size_t j = 0; j < np; ++j) sum += pr[j].distance; /* readable */
                CHECK(sum >= 0 && (st == PX_OK || (np == 0 && ne == 0)),
                      "mode %d k %ld: a failed step reports", mode, k);
                for (size_t j = 0; j < ne; ++j) ended += ev[j].began ? 0 : 1;
                px_scene_pair m;
                if (st != PX_OK) px_scene_min_distance(s, &m, &e);
                fail_after = -1;
            }
            if (removed)
                CHECK(ended == 12, "mode %d k %ld: %ld of 12 contacts ended with an event", mode, k, ended);
            px_scene_destroy(s);
        }
    CHECK(bad_frees == 0, "%zu frees with a size other than the allocation's", bad_frees);
    px_convex_destroy(slab);
    px_convex_destroy(cube);
}

/* Exclusions and the poses set before a removal, kept per body (review
 * s29: each removal walked the whole exclusion table and the list of set
 * poses, 274 us a removal at 20,000). 24 boxes on one point (every pair in
 * contact), exclusions added (some twice), bodies removed, some after a
 * pose was set, ids reused, over 300 steps: the reported pairs are every
 * pair of live bodies less the exclusions made since both were added. */
static void test_exclusion_lists(void) {
    enum { N = 24 };
    px_convex *c = box3(0.5, 0.5, 0.5);
    px_scene_options o = {0};
    o.report_distance = 0.1;
    px_error e;
    px_scene *s = px_scene_create(&o, &e);
    int alive[N] = {0}, excl[N][N] = {{0}};
    uint64_t r = 0x5eedull;
    int mismatches = 0, steps = 0;
    for (int step = 0; step < 300; ++step) {
        for (int op = 0; op < 6; ++op) {
            r = r * 6364136223846793005ull + 1442695040888963407ull;
            const int i = (int)((r >> 33) % N), j = (int)((r >> 45) % N), what = (int)((r >> 58) % 4);
            if (what == 0 && !alive[i]) {
                px_body_desc d = {0};
                d.convex = c;
                d.pose = at3(0.001 * i, 0, 0);
                d.max_speed = 1;
                uint32_t id;
                CHECK(px_scene_add_body(s, &d, &id, &e) == PX_OK, "add");
                if (id < N) alive[id] = 1;
            } else if (what == 1 && alive[i]) {
                if ((r >> 20) & 1) {
                    px_pose p = at3(0.001 * i + 0.0005, 0, 0);
                    CHECK(px_scene_set_pose(s, (uint32_t)i, &p, &e) == PX_OK, "set pose");
                }
                CHECK(px_scene_remove_body(s, (uint32_t)i, &e) == PX_OK, "remove");
                alive[i] = 0;
                for (int k = 0; k < N; ++k) excl[i][k] = excl[k][i] = 0;
            } else if (what >= 2 && alive[i] && alive[j] && i != j) {
                CHECK(px_scene_exclude_pair(s, (uint32_t)i, (uint32_t)j, &e) == PX_OK, "exclude");
                excl[i][j] = excl[j][i] = 1;
            } else if (what >= 2 && alive[i]) {
                px_pose p = at3(0.001 * i + ((r >> 21) & 1) * 0.0005, 0, 0);
                CHECK(px_scene_set_pose(s, (uint32_t)i, &p, &e) == PX_OK, "set pose");
            }
        }
        CHECK(px_scene_step(s, step, &e) == PX_OK, "step: %s", e.message);
        size_t n;
        const px_scene_pair *pr = px_scene_pairs(s, &n);
        size_t want = 0, got = 0;
        for (int a = 0; a < N; ++a)
            for (int b = a + 1; b < N; ++b) want += alive[a] && alive[b] && !excl[a][b];
        for (size_t k = 0; k < n; ++k)
            got += pr[k].body_a < N && pr[k].body_b < N && alive[pr[k].body_a] && alive[pr[k].body_b] &&
                   !excl[pr[k].body_a][pr[k].body_b];
        mismatches += got != want || n != want;
        ++steps;
    }
    CHECK(mismatches == 0, "%d of %d steps reported other pairs than the live, unexcluded ones", mismatches,
          steps);
    px_scene_destroy(s);
    px_convex_destroy(c);
}

/* px_scene_exclude_pair failing at each of its allocations: the pair is
 * either excluded (PX_OK) or not (PX_ERR_OUT_OF_MEMORY, still reported),
 * and removing both bodies afterwards leaves nothing behind. */
static void test_exclusion_out_of_memory(void) {
    px_allocator al = {failing_alloc, failing_free, NULL};
    px_convex *c = box3(0.5, 0.5, 0.5);
    for (long k = 0; k < 8; ++k) {
        fail_after = -1;
        px_scene_options o = {0};
        o.allocator = &al;
        o.report_distance = 0.1;
        px_error e;
        px_scene *s = px_scene_create(&o, &e);
        px_body_desc d = {0};
        d.convex = c;
        d.max_speed = 1;
        uint32_t id[3];
        for (int i = 0; i < 3; ++i) {
            d.pose = at3(0.1 * i, 0, 0);
            CHECK(px_scene_add_body(s, &d, &id[i], &e) == PX_OK, "add");
        }
        CHECK(px_scene_exclude_pair(s, id[0], id[2], &e) == PX_OK, "a first exclusion");
        fail_after = k;
        const px_status st = px_scene_exclude_pair(s, id[0], id[1], &e);
        fail_after = -1;
        CHECK(st == PX_OK || st == PX_ERR_OUT_OF_MEMORY, "k %ld: status %d", k, (int)st);
        CHECK(px_scene_step(s, 0, &e) == PX_OK, "step");
        size_t n;
        px_scene_pairs(s, &n);
        CHECK(n == (st == PX_OK ? 1u : 2u), "k %ld: %zu pairs after an exclusion that %s", k, n,
              st == PX_OK ? "succeeded" : "failed");
        CHECK(px_scene_remove_body(s, id[0], &e) == PX_OK && px_scene_remove_body(s, id[1], &e) == PX_OK,
              "remove");
        for (int i = 0; i < 2; ++i) {
            d.pose = at3(0.1 * i, 0, 0);
            CHECK(px_scene_add_body(s, &d, &id[i], &e) == PX_OK, "add again");
        }
        CHECK(px_scene_step(s, 1, &e) == PX_OK, "step");
        px_scene_pairs(s, &n);
        CHECK(n == 3, "k %ld: %zu pairs once the ids are reused (exclusions forgotten)", k, n);
        px_scene_destroy(s);
    }
    CHECK(bad_frees == 0, "%zu frees with a size other than the allocation's", bad_frees);
    px_convex_destroy(c);
}

/* Fourth review (s29): a step that failed in the sweep had measured the
 * moved bodies against its time but did not record it, so the next step
 * measured the next motion against the same interval again: a body moving
 * 0.29 in each of two steps of 0.3 at speed 1, towards a static ball 0.5
 * away (report distance 0.1), reached it unreported, with PX_OK. Every
 * allocation in the failing step fails in turn; the second move comes at
 * the failed step's time again, which the scene must take as no time at
 * all (a teleport, checked at once). */
static void test_out_of_memory_time(void) {
    px_allocator al = {failing_alloc, failing_free, NULL};
    double v[600];
    for (int i = 0; i < 200; ++i) {
        double z = 1 - 2 * (i + 0.5) / 200, r = sqrt(1 - z * z), ph = i * 2.399963229728653;
        v[3 * i] = 0.5 * r * cos(ph), v[3 * i + 1] = 0.5 * r * sin(ph), v[3 * i + 2] = 0.5 * z;
    }
    px_convex *ball = px_convex_create(v, 200, NULL, NULL);
    int failures = 0;
    for (long k = 0; k < 400; ++k) {
        fail_after = -1;
        px_scene_options o = {0};
        o.allocator = &al;
        o.report_distance = 0.1;
        px_error e;
        px_scene *s = px_scene_create(&o, &e);
        px_body_desc d = {0};
        d.convex = ball;
        uint32_t a, b, id;
        d.pose = at3(0, 0, 0);
        d.flags = PX_BODY_STATIC;
        CHECK(px_scene_add_body(s, &d, &b, &e) == PX_OK, "ball");
        d.flags = 0;
        d.max_speed = 1.0;
        d.pose = at3(1.5, 0, 0);
        CHECK(px_scene_add_body(s, &d, &a, &e) == PX_OK, "mover");
        CHECK(px_scene_step(s, 0.0, &e) == PX_OK, "step 0");
        px_pose p = at3(1.21, 0, 0);
        px_scene_set_pose(s, a, &p, &e);
        for (int i = 0; i < 40; ++i) {
            d.pose = at3(100 + (i % 5) * 0.5, (i / 5) * 0.5, 0);
            px_scene_add_body(s, &d, &id, &e);
        }
        fail_after = k;
        const px_status st = px_scene_step(s, 0.3, &e);
        fail_after = -1;
        if (st == PX_OK) {
            px_scene_destroy(s);
            break;
        }
        ++failures;
        p = at3(0.92, 0, 0); /* 0.42 from the ball's centre: the balls overlap */
        px_scene_set_pose(s, a, &p, &e);
        const px_status st2 = px_scene_step(s, 0.3, &e);
        size_t n;
        const px_scene_pair *pr = px_scene_pairs(s, &n);
        int reported = 0;
        for (size_t i = 0; i < n; ++i)
            reported |= pr[i].body_a == b && pr[i].body_b == a && pr[i].distance == 0;
        CHECK(st2 == PX_OK && reported, "k %ld: after a failed step the overlapping pair is %s (status %d)",
              k, reported ? "reported" : "missed", (int)st2);
        /* The failed step's time counts: an earlier one is refused. */
        CHECK(px_scene_step(s, 0.25, &e) == PX_ERR_INVALID_ARGUMENT, "k %ld: time going back accepted", k);
        px_scene_destroy(s);
    }
    CHECK(failures > 0, "no allocation failed in the step");
    CHECK(bad_frees == 0, "%zu frees with a size other than the allocation's", bad_frees);
    px_convex_destroy(ball);
}

/* Third review: skewed poses, stale witness points, failed steps.
 * 1. Matrices off a rotation by 4.9e-7 (px_pose_check accepts them, a float
 *    rotation is this far off): px_distance measures in b's frame through
 *    R_b^T, 3.4e-7 nearer than the world's; a pair at 0.99999966 with
 *    report = 1 was never reported. Also each body more skewed than the
 *    last, in later steps (the allowance grows while pairs are queued).
 * 2. A point and a box turned together by an exact rotation: the relative
 *    test finds no motion, and the pair kept its old witness points.
 * 3. px_scene_min_distance used the current pose's skew for the last pose.
 * 4. A contact that began in a failed step, then excluded: its began event
 *    was delivered, never ended. A failed step that failed at once kept the
 *    last step's reports. */
/* A scene (margin 0.01, report distance 0.1) on allocator al, and in *d a
 * body of polytope c moving at up to 10. */
static px_scene *cube_scene(const px_allocator *al, const px_convex *c, px_body_desc *d, px_error *e) {
    px_scene_options o = {0};
    o.margin = 0.01;
    o.report_distance = 0.1;
    o.allocator = al;
    memset(d, 0, sizeof *d);
    d->convex = c;
    d->max_speed = 10;
    return px_scene_create(&o, e);
}

static void test_third_review(void) {
    px_error e;
    size_t n;
    {
        double oct[18] = {0.1, 0, 0, -0.1, 0, 0, 0, 0.1, 0, 0, -0.1, 0, 0, 0, 0.1, 0, 0, -0.1};
        px_convex *c = px_convex_create(oct, 6, NULL, &e);
        for (uint32_t th = 1; th <= 2; ++th)
            for (int late = 0; late < 2; ++late) {
                px_scene_options o = {0};
                o.margin = 1.0;
                o.threads = th;
                px_scene *s = px_scene_create(&o, &e);
                px_body_desc d = {0};
                d.convex = c;
                d.max_speed = 1e-3;
                uint32_t a, b, far;
                px_pose pa = at3(1.2 + 2e-7, 0, 0), pb = at3(0, 0, 0), pf = at3(50, 0, 0);
                px_pose sb = pb; /* shrinks lengths by 4.9e-7 */
                for (int i = 0; i < 9; i += 4) sb.r[i] = 1 - 4.9e-7;
                CHECK(px_pose_check(&sb, &e) == PX_OK, "skewed pose accepted");
                d.pose = pa;
                px_scene_add_body(s, &d, &a, &e);
                d.pose = late ? pb : sb;
                px_scene_add_body(s, &d, &b, &e);
                d.pose = pf;
                px_scene_add_body(s, &d, &far, &e);
                CHECK(px_scene_step(s, 0, &e) == PX_OK, "step");
                if (late) { /* the skew comes after the pair was keyed */
                    px_scene_set_pose(s, b, &sb, &e);
                    for (int i = 0; i < 9; i += 4) pf.r[i] = 1 - 1e-7;
                    px_scene_set_pose(s, far, &pf, &e);
                }
                CHECK(px_scene_step(s, 1, &e) == PX_OK, "step");
                px_distance_result r;
                px_distance(c, &pa, c, &sb, NULL, NULL, &r);
                const px_scene_pair *pr = px_scene_pairs(s, &n);
                CHECK(r.distance <= 1.0 && n == 1 && pr[0].contact &&
                          fabs(pr[0].distance - r.distance) < 1e-12,
                      "review 3.1 (threads %u, late %d): px_distance %.17g, %zu pairs reported", th, late,
                      r.distance, n);
                px_scene_pair m;
                CHECK(px_scene_min_distance(s, &m, &e) == PX_OK && m.body_a == a && m.body_b == b,
                      "review 3.1: min distance");
                px_scene_destroy(s);
            }
        px_convex_destroy(c);
    }
    {
        double pt[3] = {0, 0, 0};
        double bp[24]; /* a cube of half-size 0.5 about (1.05, 0, 0), in its own frame */
        for (int c = 0; c < 8; ++c)
            for (int k = 0; k < 3; ++k) bp[3 * c + k] = ((c >> k) & 1 ? 0.5 : -0.5) + (k == 0 ? 1.05 : 0.0);
        px_convex *a = px_convex_create(pt, 1, NULL, &e), *b = px_convex_create(bp, 8, NULL, &e);
        px_scene_options o = {0};
        o.margin = 0.6;
        px_scene *s = px_scene_create(&o, &e);
        px_body_desc d = {0};
        d.max_speed = 1;
        d.max_angular_speed = 10;
        uint32_t ia, ib;
        d.convex = a;
        d.pose = at3(0, 0, 0);
        px_scene_add_body(s, &d, &ia, &e);
        d.convex = b;
        px_scene_add_body(s, &d, &ib, &e);
        px_scene_step(s, 0, &e);
        /* both turned 90 degrees about z (exactly), translations 0 */
        px_pose ra = at3(0, 0, 0), rb = at3(0, 0, 0);
        ra.r[0] = rb.r[0] = 0, ra.r[1] = rb.r[1] = -1, ra.r[3] = rb.r[3] = 1, ra.r[4] = rb.r[4] = 0;
        px_scene_set_pose(s, ia, &ra, &e);
        px_scene_set_pose(s, ib, &rb, &e);
        CHECK(px_scene_step(s, 1, &e) == PX_OK, "step");
        px_distance_result r;
        px_distance(a, &ra, b, &rb, NULL, NULL, &r);
        const px_scene_pair *pr = px_scene_pairs(s, &n);
        CHECK(n == 1 && fabs(pr[0].point_b.x - r.point_b.x) < 1e-12 &&
                  fabs(pr[0].point_b.y - r.point_b.y) < 1e-12,
              "review 3.2: witness (%g %g) expected (%g %g)", n ? pr[0].point_b.x : NAN,
              n ? pr[0].point_b.y : NAN, r.point_b.x, r.point_b.y);
        px_scene_destroy(s);
        px_convex_destroy(a);
        px_convex_destroy(b);
    }
    {
        /* Cubes of half-size 1000 corner to corner along the sweep frame's
         * x axis: (A,B) 0.1 apart with A stretched by 1 + 4.9e-7, (C,D)
         * 0.1003 apart and visited first. A is then given an exact pose,
         * not stepped yet: the minimum is at the last step's poses. */
        const double U[3] = {0.6312514969513067, -0.5646424733950354, 0.5316958010320105};
        double nn[3] = {1, 1, 1}, pp[3] = {1, -1, 0}, qq[3], v[3], w[3];
        double ln = sqrt(3.0), lp = sqrt(2.0);
        for (int i = 0; i < 3; ++i) nn[i] /= ln, pp[i] /= lp;
        qq[0] = nn[1] * pp[2] - nn[2] * pp[1], qq[1] = nn[2] * pp[0] - nn[0] * pp[2],
        qq[2] = nn[0] * pp[1] - nn[1] * pp[0];
        v[0] = U[1], v[1] = -U[0], v[2] = 0; /* U x z */
        double lv = sqrt(v[0] * v[0] + v[1] * v[1]);
        v[0] /= lv, v[1] /= lv;
        w[0] = U[1] * v[2] - U[2] * v[1], w[1] = U[2] * v[0] - U[0] * v[2], w[2] = U[0] * v[1] - U[1] * v[0];
        px_pose r0 = px_pose_identity();
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) r0.r[3 * i + j] = U[i] * nn[j] + v[i] * pp[j] + w[i] * qq[j];
        CHECK(px_pose_check(&r0, &e) == PX_OK, "review 3.3: frame");
        double h = 1000, s3 = sqrt(3.0) * h, sc = 1 + 4.9e-7;
        px_convex *c = box3(h, h, h);
        px_pose p[4] = {r0, r0, r0, r0};
        for (int i = 0; i < 9; ++i) p[0].r[i] *= sc;
        double xs[4] = {0, sc * s3 + s3 + 0.1, -20000, -20000 + 2 * s3 + 0.1003};
        for (int k = 0; k < 4; ++k) p[k].t = (px_vec3){xs[k] * U[0], xs[k] * U[1], xs[k] * U[2]};
        px_scene_options o = {0};
        o.margin = o.report_distance = 0.01;
        px_scene *s = px_scene_create(&o, &e);
        px_body_desc d = {0};
        d.convex = c;
        d.max_speed = INFINITY;
        uint32_t id[4];
        for (int i = 0; i < 4; ++i) {
            d.pose = p[i];
            px_scene_add_body(s, &d, &id[i], &e);
        }
        px_scene_step(s, 0, &e);
        px_pose exact = r0;
        exact.t = p[0].t;
        px_scene_set_pose(s, id[0], &exact, &e);
        px_scene_pair m;
        px_distance_result r;
        px_distance(c, &p[0], c, &p[1], NULL, NULL, &r);
        CHECK(px_scene_min_distance(s, &m, &e) == PX_OK && m.body_a == id[0] && m.body_b == id[1] &&
                  fabs(m.distance - r.distance) < 1e-9,
              "review 3.3: min distance (%u,%u) %.17g, expected (0,1) %.17g", m.body_a, m.body_b, m.distance,
              r.distance);
        px_scene_destroy(s);
        px_convex_destroy(c);
    }
    {
        px_allocator al = {failing_alloc, failing_free, NULL};
        px_convex *c = box3(0.5, 0.5, 0.5);
        px_body_desc d;
        int failed_once = 0;
        for (long k = 0; k < 40; ++k) {
            fail_after = -1;
            px_scene *s = cube_scene(&al, c, &d, &e);
            uint32_t a, b;
            d.pose = at3(0, 0, 0);
            px_scene_add_body(s, &d, &a, &e);
            d.pose = at3(1.5, 0, 0);
            px_scene_add_body(s, &d, &b, &e);
            px_scene_step(s, 0, &e);
            px_pose pb = at3(1.0, 0, 0);
            px_scene_set_pose(s, b, &pb, &e);
            fail_after = k;
            px_status st = px_scene_step(s, 0.1, &e);
            fail_after = -1;
            if (st == PX_OK) {
                px_scene_destroy(s);
                break;
            }
            failed_once = 1;
            px_scene_pairs(s, &n);
            size_t ne;
            px_scene_events(s, &ne);
            CHECK(n == 0 && ne == 0, "review 3.4 (k %ld): a failed step shows %zu pairs, %zu events", k, n,
                  ne);
            px_scene_exclude_pair(s, a, b, &e);
            CHECK(px_scene_step(s, 0.2, &e) == PX_OK, "step");
            const px_scene_event *ev = px_scene_events(s, &ne);
            int began = 0;
            for (size_t i = 0; i < ne; ++i) began += ev[i].began;
            CHECK(began == 0, "review 3.4 (k %ld): an excluded pair's contact began and never ends", k);
            px_scene_destroy(s);
        }
        CHECK(failed_once, "review 3.4: no step failed");
        /* Reports of the last step are gone when the next fails at once. */
        px_scene *s = cube_scene(&al, c, &d, &e);
        uint32_t id;
        for (int i = 0; i < 20; ++i) {
            d.pose = at3(i * 1.0, 0, 0);
            px_scene_add_body(s, &d, &id, &e);
        }
        px_scene_step(s, 0, &e);
        for (int i = 0; i < 20; ++i) {
            d.pose = at3(i * 1.0, 5, 0);
            px_scene_add_body(s, &d, &id, &e);
        }
        px_scene_step(s, 1, &e);
        fail_after = 0;
        px_status st = px_scene_step(s, 2, &e);
        fail_after = -1;
        size_t ne;
        px_scene_pairs(s, &n);
        px_scene_events(s, &ne);
        CHECK(st != PX_OK || (n > 0), "step");
        if (st != PX_OK)
            CHECK(n == 0 && ne == 0, "review 3.4: a failed step shows %zu pairs, %zu events", n, ne);
        px_scene_destroy(s);
        px_convex_destroy(c);
    }
    {
        /* 5. A flat square and a closed cube model (triangles) at poses off
         *    rotations by ~5e-7: the model query pruned by bounds taken in
         *    the model's frame while the square's leaf distances are taken
         *    in its own, so a warm cache found 0.22496470 and a cold query
         *    0.22496440 (the smaller: every leaf measured as the model
         *    query measures it, the leaf first, the square second). */
        px_pose P0 = {{-0x1.1e64349452027p-2, 0x1.4999f371dbd78p-1, 0x1.6cb1cc55a6ccp-1,
                       -0x1.49c26849be43dp-1, 0x1.b29638572dec6p-2, -0x1.45dcd8a258245p-1,
                       -0x1.6c8d380317c36p-1, -0x1.4605c43ee92dfp-1, 0x1.2f05a49068ff1p-2},
                      {-0x1.ac3ef1d69850bp+0, 0x1.79ddf7de46a54p+0, -0x1.2e29dcaa3c7e4p+1}};
        px_pose P1 = {{-0x1.1e6428f34a893p-2, 0x1.4999e60fa9e5cp-1, 0x1.6cb1bd86aa109p-1,
                       -0x1.49c25ae5e7c7p-1, 0x1.b29626b1aa123p-2, -0x1.45dccb670344dp-1,
                       -0x1.6c8d29359745cp-1, -0x1.4605b701eaf0dp-1, 0x1.2f059842819adp-2},
                      {-0x1.ac3ecf2c94a35p+0, 0x1.79ddea3cf2c9ap+0, -0x1.2e29d204db117p+1}};
        px_pose P2 = {{0x1.6421c7ba66316p-1, -0x1.3636897655319p-1, 0x1.8b62040f560b4p-2,
                       0x1.9e43db72be514p-3, 0x1.5c961b1172b61p-1, 0x1.686c969cdc888p-1,
                       -0x1.60f8681998222p-1, -0x1.a56c669fa6f94p-2, 0x1.31372c0a014afp-1},
                      {-0x1.e10aeed871497p-1, 0x1.7f5fec75f7c97p+0, -0x1.6eafbc80d00dep-1}};
        px_pose P3 = P2; /* the cube does not move */
        double h = 0.5, fl[12] = {-h, -h, 0, h, -h, 0, h, h, 0, -h, h, 0}, v[24];
        px_convex *sq = px_convex_create(fl, 4, NULL, &e);
        for (int c = 0; c < 8; ++c)
            for (int k = 0; k < 3; ++k) v[3 * c + k] = ((c >> k) & 1 ? 0.8 : -0.8);
        uint32_t t[36] = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                          2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
        px_model *cube = triangle_model(v, 8, t, 12, &e);
        px_model_distance_result cold, w0, w1;
        px_model_cache mc;
        memset(&mc, 0, sizeof mc);
        px_model_distance_convex(cube, &P3, sq, &P1, NULL, &cold);
        px_model_distance_convex(cube, &P2, sq, &P0, &mc, &w0);
        px_model_distance_convex(cube, &P3, sq, &P1, &mc, &w1);
        double brute = INFINITY;
        for (int k = 0; k < 12; ++k) {
            double tp[9];
            for (int j = 0; j < 3; ++j)
                for (int c = 0; c < 3; ++c) tp[3 * j + c] = v[3 * t[3 * k + j] + c];
            px_convex *tc = px_convex_create(tp, 3, NULL, &e);
            px_distance_result r;
            px_distance(tc, &P3, sq, &P1, NULL, NULL, &r);
            if (r.distance < brute) brute = r.distance;
            px_convex_destroy(tc);
        }
        CHECK(cold.distance == w1.distance && fabs(cold.distance - brute) < 1e-15,
              "review 3.5: cold %.17g, warm %.17g, every leaf %.17g", cold.distance, w1.distance, brute);
        px_model_cache_release(&mc);
        px_model_destroy(cube);
        px_convex_destroy(sq);
    }
}

int main(void) {
    tu_init("test_scene");
    int quick = tu_sanitized();
    sim cases[] = {
        {"convex", 40, quick ? 60 : 200, 0, 8.0, 0.05, 0.05, 0.1, 0.4, 0, 0, 0, 0, 0, 0, 0},
        {"convex dense", 60, quick ? 40 : 150, 0, 5.0, 0.08, 0.1, 0.05, 0.25, 0, 0, 0, 0, 0, 0, 0},
        {"teleports", 40, quick ? 50 : 150, 0, 8.0, 0.05, 0.05, 0.1, 0.4, 13, 0, 0, 0, 0, 0, 0},
        /* half the bodies teleported at every step: the arrays are sorted
         * anew and stale pairs dropped (rebuild, drop_stale) */
        {"mass teleports", 60, quick ? 30 : 80, 0, 8.0, 0.05, 0.05, 0.1, 0.4, 2, 0, 0, 0, 0, 0, 0},
        {"mass teleports, models, churn, statics", 60, quick ? 30 : 80, 3, 7.0, 0.05, 0.05, 0.1, 0.4, 2, 1, 0,
         1, 0, 0, 0},
        {"mass churn", 60, quick ? 40 : 100, 3, 7.0, 0.05, 0.05, 0.1, 0.4, 0, 2, 0, 1, 0, 0, 0},
        {"mass teleports, filters", 60, quick ? 30 : 80, 0, 7.0, 0.05, 0.05, 0.1, 0.4, 2, 0, 1, 0, 0, 0, 0},
        /* a ninth teleported and every fifth step a third removed and 50
         * added: both merged into the arrays (merge_in) in the same step
         * as other bodies sift (review s30: these took O(n) swaps apiece) */
        {"teleports and mass churn", 200, quick ? 25 : 60, 5, 13.0, 0.05, 0.05, 0.1, 0.4, 9, 2, 1, 1, 0, 0,
         0},
        {"models", 30, quick ? 40 : 120, 2, 7.0, 0.05, 0.05, 0.1, 0.5, 0, 0, 0, 0, 0, 0, 0},
        {"churn", 40, quick ? 60 : 150, 3, 8.0, 0.05, 0.05, 0.1, 0.4, 0, 1, 0, 0, 0, 0, 0},
        {"filters", 40, quick ? 60 : 150, 0, 7.0, 0.05, 0.05, 0.1, 0.4, 0, 0, 1, 0, 0, 0, 0},
        {"statics", 40, quick ? 60 : 150, 4, 7.0, 0.05, 0.05, 0.1, 0.4, 0, 0, 0, 1, 0, 0, 0},
        {"accel", 40, quick ? 60 : 200, 0, 8.0, 0.06, 0.02, 0.1, 0.4, 0, 0, 0, 0, 1, 0, 0},
        {"floor", 60, quick ? 40 : 120, 0, 9.0, 0.05, 0.05, 0.1, 0.4, 0, 0, 0, 0, 0, 1, 0},
        {"zero margin", 50, quick ? 60 : 150, 0, 6.0, 0.05, 0.05, 0.0, 0.0, 0, 0, 0, 0, 0, 0, 0},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        uint64_t h1 = run(&cases[i], 1);
        if (i < 2) CHECK(run(&cases[i], 0) == h1, "%s: a second run reports the same", cases[i].name);
    }
    /* Helper threads: a crowded scene (hundreds of due pairs a step, so
     * the helpers get work) with models, teleports and churn, against brute
     * force and bit for bit against one thread. */
    sim crowd = {"threads", 240, quick ? 12 : 40, 4, 12.0, 0.06, 0.06, 0.1, 0.3, 17, 1, 0, 0, 0, 0, 1};
    uint64_t one = run(&crowd, 1);
    for (int t = 2; t <= 3; ++t) {
        crowd.threads = t;
        CHECK(run(&crowd, 0) == one, "threads: %d threads report the same as one", t);
    }
    test_savings();
    test_inner_balls();
    test_containment();
    test_partial_containment();
    test_static_caches();
    test_tiny_scales();
    test_no_allocation();
    test_no_allocation_model();
    test_review_cases();
    test_out_of_memory();
    test_out_of_memory_events();
    test_out_of_memory_time();
    test_exclusion_lists();
    test_exclusion_out_of_memory();
    test_third_review();
    test_bad_inputs();
    return tu_finish();
}
