/* proxima_puma_cell: the Puma 560 in a work cell (issue 11, section 3;
 * `make demo` runs it first).
 *
 * The arm (seven link models, examples/puma560.c) moves along a
 * joint-space trajectory past a table, a fixture, a teapot it touches once
 * and a pillar, all bodies of one px_scene: the moving links with motion
 * bounds from the joint speed limits, adjacent links excluded, the cell
 * static and paired with the arm only. Each step it sets the link poses,
 * calls px_scene_step (timed) and px_scene_min_distance, and reports
 * self-collision (non-adjacent links), contacts with the cell and the
 * minimum clearance with its pair.
 *
 * Checks (exit status 1 when one fails): at every step the scene's minimum
 * equals the smallest of the demo's own warm px_model_distance queries
 * over every pair the scene may pair; the reported pairs are exactly those
 * within the report distance; the gripper touches the teapot (a contact
 * begins and ends) and nothing else is in contact.
 *
 * Output: a table every quarter second and a summary on stdout;
 * OUT/puma_cell.png (clearance over time with the closest pair, and the
 * arm drawn at its closest approaches with the witness segment; drawn by
 * gnuplot from OUT/puma_cell_*.dat and OUT/puma_cell.gp, which it
 * writes). Public API only. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "proxima/io.h"
#include "proxima/proxima.h"
#include "puma560.h"

#define NBODY (PUMA_LINKS + PUMA_CELL_BODIES)
#define MARGIN 0.001 /* contact: within 1 mm */
#define REPORT 0.02  /* reported with distance and witnesses: within 20 mm */

static double now(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int cmp_double(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* The p-quantile of v[0..n) (sorts v). */
static double quantile(double *v, int n, double p) {
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    int i = (int)(p * (n - 1) + 0.5);
    return n ? v[i] : 0.0;
}

static const char *body_name[NBODY] = {"link1", "link2", "link3",   "link4",  "link5", "link6",
                                       "link7", "table", "fixture", "teapot", "pillar"};

/* What the demo records per step (from the first run). */
typedef struct step_rec {
    double t;
    double min_d;          /* px_scene_min_distance */
    int min_a, min_b;      /* its pair (demo body indices) */
    double self_d, cell_d; /* the demo's own: closest non-adjacent links, closest link-cell pair */
    int self_a, self_b, cell_a, cell_b;
    px_vec3 cell_pa, cell_pb, min_pa, min_pb;
    uint64_t checked, candidates;
    uint32_t reported, contacts;
} step_rec;

/* ---- Drawing: an orthographic view, painter's order, flat shading ---- */

typedef struct tri2 {
    double depth;
    double x[3], y[3];
    unsigned rgb;
} tri2;

static int cmp_tri(const void *a, const void *b) {
    double x = ((const tri2 *)a)->depth, y = ((const tri2 *)b)->depth;
    return x < y ? -1 : x > y;
}

typedef struct view {
    px_vec3 d, u, v; /* towards the viewer, screen right, screen up */
} view;

static view make_view(double azimuth, double elevation) {
    view w;
    double ca = cos(azimuth), sa = sin(azimuth), ce = cos(elevation), se = sin(elevation);
    w.d = (px_vec3){ca * ce, sa * ce, se};
    w.u = (px_vec3){-sa, ca, 0};
    w.v = (px_vec3){-ca * se, -sa * se, ce};
    return w;
}

static double dot3(px_vec3 a, px_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

static unsigned shade(unsigned rgb, double k) {
    unsigned r = (rgb >> 16) & 255, g = (rgb >> 8) & 255, b = rgb & 255;
    return ((unsigned)(r * k) << 16) | ((unsigned)(g * k) << 8) | (unsigned)(b * k);
}

/* Appends the mesh's triangles at `pose`, seen in `w`, to tris. */
static int add_mesh(tri2 **tris, size_t *n, size_t *cap, const px_mesh *mesh, const px_pose *pose,
                    const view *w, unsigned rgb) {
    const double *xyz = px_mesh_vertices(mesh);
    const uint32_t *t = px_mesh_triangles(mesh);
    uint32_t nt = px_mesh_triangle_count(mesh);
    if (*n + nt > *cap) {
        size_t c = 2 * (*n + nt);
        tri2 *p = realloc(*tris, c * sizeof *p);
        if (!p) return 0;
        *tris = p, *cap = c;
    }
    for (uint32_t i = 0; i < nt; ++i) {
        px_vec3 p[3];
        tri2 *o = &(*tris)[(*n)++];
        o->depth = 0;
        for (int c = 0; c < 3; ++c) {
            const double *v = xyz + 3 * (size_t)t[3 * i + c];
            p[c] = px_pose_apply(pose, (px_vec3){v[0], v[1], v[2]});
            o->x[c] = dot3(p[c], w->u);
            o->y[c] = dot3(p[c], w->v);
            o->depth += dot3(p[c], w->d) / 3;
        }
        px_vec3 e1 = {p[1].x - p[0].x, p[1].y - p[0].y, p[1].z - p[0].z};
        px_vec3 e2 = {p[2].x - p[0].x, p[2].y - p[0].y, p[2].z - p[0].z};
        px_vec3 nn = {e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x};
        double l = sqrt(dot3(nn, nn));
        double k = l > 0 ? fabs(dot3(nn, w->d)) / l : 0;
        o->rgb = shade(rgb, 0.35 + 0.65 * k);
    }
    return 1;
}

/* Writes the scene at q, seen in w, as filled triangles (x y rgb, blank
 * line after each) to path, and the witness points (pa, pb) projected to
 * path_w. Returns 1 on success. */
static int write_view(const char *path, const char *path_w, const puma_arm *arm, const puma_cell *cell,
                      const double q[PUMA_JOINTS], const view *w, px_vec3 pa, px_vec3 pb) {
    static const unsigned link_rgb[PUMA_LINKS] = {0x9a9a9a, 0xd98c2b, 0xe0a040, 0xd98c2b,
                                                  0xe0a040, 0xd98c2b, 0x606060};
    static const unsigned cell_rgb[PUMA_CELL_BODIES] = {0x9b7048, 0x4f7fbf, 0xf0ede0, 0x8aa08a};
    px_pose pose[PUMA_LINKS];
    puma_link_poses(arm->set, q, pose);
    tri2 *tris = NULL;
    size_t n = 0, cap = 0;
    int ok = 1;
    for (int k = 0; k < PUMA_LINKS && ok; ++k)
        ok = add_mesh(&tris, &n, &cap, arm->mesh[k], &pose[k], w, link_rgb[k]);
    for (int c = 0; c < PUMA_CELL_BODIES && ok; ++c)
        ok = add_mesh(&tris, &n, &cap, cell->body[c].mesh, &cell->body[c].pose, w, cell_rgb[c]);
    FILE *f = ok ? fopen(path, "w") : NULL;
    if (f) {
        qsort(tris, n, sizeof *tris, cmp_tri);
        for (size_t i = 0; i < n; ++i) {
            for (int c = 0; c < 3; ++c) fprintf(f, "%.5f %.5f %u\n", tris[i].x[c], tris[i].y[c], tris[i].rgb);
            fputc('\n', f);
        }
        ok = fclose(f) == 0;
    } else {
        ok = 0;
    }
    free(tris);
    f = ok ? fopen(path_w, "w") : NULL;
    if (!f) return 0;
    fprintf(f, "%.6f %.6f\n%.6f %.6f\n", dot3(pa, w->u), dot3(pa, w->v), dot3(pb, w->u), dot3(pb, w->v));
    return fclose(f) == 0;
}

static void usage(FILE *f) {
    fprintf(f, "usage: proxima_puma_cell [--models DIR] [--out DIR] [--meshes nimasarli|rtb|rtb-collision]\n"
               "                         [--pieces triangles|parts] [--dt S] [--reps R] [--no-plot]\n");
}

int main(int argc, char **argv) {
    const char *models = "models", *out = ".";
    puma_meshes set = PUMA_NIMASARLI;
    uint32_t pieces = PX_PIECES_TRIANGLES;
    double dt = 0.004;
    int reps = 5, plot = 1;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "--no-plot")) {
            plot = 0;
        } else if (!strcmp(a, "--help")) {
            usage(stdout);
            return 0;
        } else if (v && !strcmp(a, "--models")) {
            models = v, ++i;
        } else if (v && !strcmp(a, "--out")) {
            out = v, ++i;
        } else if (v && !strcmp(a, "--meshes")) {
            set = !strcmp(v, "rtb")             ? PUMA_RTB_VISUAL
                  : !strcmp(v, "rtb-collision") ? PUMA_RTB_COLLISION
                                                : PUMA_NIMASARLI;
            if (set == PUMA_NIMASARLI && strcmp(v, "nimasarli")) return usage(stderr), 2;
            ++i;
        } else if (v && !strcmp(a, "--pieces")) {
            if (!strcmp(v, "parts"))
                pieces = PX_PIECES_PARTS;
            else if (strcmp(v, "triangles"))
                return usage(stderr), 2;
            ++i;
        } else if (v && !strcmp(a, "--dt")) {
            dt = atof(v), ++i;
        } else if (v && !strcmp(a, "--reps")) {
            reps = atoi(v), ++i;
        } else {
            usage(stderr);
            return 2;
        }
    }
    if (!(dt > 1e-4 && dt < 1) || reps < 1 || reps > 100) return usage(stderr), 2;

    static const char *set_name[PUMA_MESH_SETS] = {"nimasarli STL (inches)", "RTB visual COLLADA",
                                                   "RTB collision COLLADA"};
    printf("== The Puma 560 in a work cell (px_scene, issue 11) ==\n");
    px_error err;
    puma_arm arm;
    puma_cell cell;
    double t0 = now();
    if (puma_arm_load(&arm, models, set, pieces, &err) != PX_OK) {
        fprintf(stderr, "puma_cell: %s\n", err.message);
        return 2;
    }
    if (puma_cell_build(&cell, models, &arm, &err) != PX_OK) {
        fprintf(stderr, "puma_cell: %s\n", err.message);
        puma_arm_destroy(&arm);
        return 2;
    }
    uint32_t tris = 0;
    for (int k = 0; k < PUMA_LINKS; ++k) tris += arm.triangles[k];
    printf("arm   : %s, %u triangles, %s leaves; loaded and built in %.2f s\n", set_name[set], tris,
           pieces == PX_PIECES_TRIANGLES ? "triangle (exact)" : "part-hull", now() - t0);
    printf("cell  : table (5 boxes), fixture (2 boxes), teapot (%u triangles, exact), pillar (1 box);\n"
           "        the teapot is placed to touch the gripper at t = %.3f s, the pillar 15 mm from the arm\n",
           px_mesh_triangle_count(cell.body[2].mesh), puma_touch_time());
    px_vec3 center[PUMA_LINKS];
    double speed[PUMA_LINKS], angular[PUMA_LINKS];
    puma_motion_bounds(set, NULL, center, speed, angular);
    printf("bounds: joint speeds <= (%g %g %g %g %g %g) rad/s; per link |v| <= ", puma_qd_max[0],
           puma_qd_max[1], puma_qd_max[2], puma_qd_max[3], puma_qd_max[4], puma_qd_max[5]);
    for (int k = 1; k < PUMA_LINKS; ++k) printf("%.2f%s", speed[k], k + 1 < PUMA_LINKS ? " " : " m/s, ");
    printf("|w| <= ");
    for (int k = 1; k < PUMA_LINKS; ++k) printf("%g%s", angular[k], k + 1 < PUMA_LINKS ? " " : " rad/s\n");

    /* Steps: dt adjusted so that a step falls on the touching waypoint. */
    double touch = puma_touch_time(), duration = puma_trajectory_duration();
    int touch_step = (int)(touch / dt + 0.5);
    dt = touch / touch_step;
    int nsteps = (int)(duration / dt) + 1;
    printf("scene : margin %g m (contact), report distance %g m; %d steps of %.4f s over %.2f s; %d timed "
           "runs\n\n",
           MARGIN, REPORT, nsteps, dt, duration, reps);

    step_rec *rec = calloc((size_t)nsteps, sizeof *rec);
    double *t_step = malloc(sizeof(double) * (size_t)nsteps * (size_t)reps);
    double *t_min = malloc(sizeof(double) * (size_t)nsteps * (size_t)reps);
    double *tmp = malloc(sizeof(double) * (size_t)(nsteps > reps ? nsteps : reps));
    px_model_cache caches[NBODY][NBODY];
    memset(caches, 0, sizeof caches);
    if (!rec || !t_step || !t_min || !tmp) {
        fprintf(stderr, "puma_cell: out of memory\n");
        return 2;
    }
    int failures = 0, began = 0, ended = 0, other_contacts = 0, touched = 0;
    size_t mem = 0;
    uint64_t checked_total = 0;
    printf("%7s %7s %7s %8s  %-24s %-24s %s\n", "t (s)", "checked", "report", "step us",
           "self: closest pair (mm)", "cell: closest pair (mm)", "events");
    for (int rep = 0; rep < reps; ++rep) {
        px_scene_options so;
        memset(&so, 0, sizeof so);
        so.margin = MARGIN;
        so.report_distance = REPORT;
        px_scene *scene = px_scene_create(&so, &err);
        uint32_t ids[NBODY], back[64];
        double q[PUMA_JOINTS];
        puma_trajectory(0, q);
        if (!scene || puma_arm_add(&arm, scene, q, NULL, 1, 3, ids, &err) != PX_OK ||
            puma_cell_add(&cell, scene, 2, 1, ids + PUMA_LINKS, &err) != PX_OK) {
            fprintf(stderr, "puma_cell: %s\n", err.message);
            return 2;
        }
        for (int b = 0; b < NBODY; ++b) back[ids[b]] = (uint32_t)b;
        for (int i = 0; i < nsteps; ++i) {
            double t = i * dt;
            puma_trajectory(t, q);
            if (puma_arm_set(&arm, scene, ids, q, &err) != PX_OK) {
                fprintf(stderr, "puma_cell: step %d: %s\n", i, err.message);
                return 2;
            }
            double a = now();
            px_status st = px_scene_step(scene, t, &err);
            double b = now();
            px_scene_pair mp;
            px_status st2 = px_scene_min_distance(scene, &mp, &err);
            double c = now();
            if (st != PX_OK || st2 != PX_OK) {
                fprintf(stderr, "puma_cell: step %d: %s\n", i, err.message);
                return 2;
            }
            t_step[(size_t)i * reps + rep] = b - a;
            t_min[(size_t)i * reps + rep] = c - b;
            if (rep) continue;

            /* The first run records and checks. */
            step_rec *r = &rec[i];
            px_scene_stats stats;
            px_scene_get_stats(scene, &stats);
            r->t = t;
            r->checked = stats.pairs_checked;
            r->candidates = stats.candidate_pairs;
            checked_total += stats.pairs_checked;
            if (stats.memory_bytes > mem) mem = stats.memory_bytes;
            r->min_d = mp.distance;
            r->min_a = (int)back[mp.body_a];
            r->min_b = (int)back[mp.body_b];
            r->min_pa = mp.point_a, r->min_pb = mp.point_b;
            size_t np, ne;
            const px_scene_pair *pairs = px_scene_pairs(scene, &np);
            const px_scene_event *ev = px_scene_events(scene, &ne);
            r->reported = (uint32_t)np;
            for (size_t k = 0; k < np; ++k) r->contacts += pairs[k].contact;

            /* The demo's own answer: warm px_model_distance over every pair
             * the scene may pair (non-adjacent links, link-cell). */
            px_pose pose[NBODY];
            puma_link_poses(set, q, pose);
            for (int c2 = 0; c2 < PUMA_CELL_BODIES; ++c2) pose[PUMA_LINKS + c2] = cell.body[c2].pose;
            r->self_d = r->cell_d = INFINITY;
            uint32_t within = 0;
            for (int x = 0; x < PUMA_LINKS; ++x)
                for (int y = x + 2; y < NBODY; ++y) {
                    const px_model *my = y < PUMA_LINKS ? arm.link[y] : cell.body[y - PUMA_LINKS].model;
                    px_model_distance_result d;
                    if (px_model_distance(arm.link[x], &pose[x], my, &pose[y], &caches[x][y], &d) != PX_OK) {
                        fprintf(stderr, "puma_cell: step %d: query failed\n", i);
                        return 2;
                    }
                    within += d.distance <= REPORT;
                    if (y < PUMA_LINKS && d.distance < r->self_d)
                        r->self_d = d.distance, r->self_a = x, r->self_b = y;
                    if (y >= PUMA_LINKS && d.distance < r->cell_d) {
                        r->cell_d = d.distance, r->cell_a = x, r->cell_b = y;
                        r->cell_pa = d.point_a, r->cell_pb = d.point_b;
                    }
                }
            double best = r->self_d < r->cell_d ? r->self_d : r->cell_d;
            if (fabs(best - r->min_d) > 1e-12 || within != np) {
                if (++failures <= 10)
                    fprintf(
                        stderr,
                        "FAIL step %d: scene minimum %.17g (%s-%s), own %.17g; reported %zu pairs, own %u\n",
                        i, r->min_d, body_name[r->min_a], body_name[r->min_b], best, np, within);
            }
            char evs[128] = "";
            for (size_t k = 0; k < ne; ++k) {
                int x = (int)back[ev[k].body_a], y = (int)back[ev[k].body_b];
                size_t l = strlen(evs);
                snprintf(evs + l, sizeof evs - l, "%s%s %s-%s", l ? ", " : "", ev[k].began ? "begin" : "end",
                         body_name[x], body_name[y]);
                if (ev[k].began) {
                    began++;
                    if (!((x == 6 || y == 6) && (x == PUMA_LINKS + 2 || y == PUMA_LINKS + 2)))
                        other_contacts++;
                } else {
                    ended++;
                }
            }
            if (i == touch_step)
                for (size_t k = 0; k < np; ++k)
                    if (pairs[k].contact && back[pairs[k].body_b] == PUMA_LINKS + 2) touched = 1;
            if (i % (int)(0.25 / dt + 0.5) == 0 || ne || i == touch_step) {
                char s1[40], s2[40];
                snprintf(s1, sizeof s1, "%s-%s %.2f", body_name[r->self_a], body_name[r->self_b],
                         1e3 * r->self_d);
                snprintf(s2, sizeof s2, "%s-%s %.2f", body_name[r->cell_a], body_name[r->cell_b],
                         1e3 * r->cell_d);
                printf("%7.3f %7llu %7u %8.2f  %-24s %-24s %s\n", t, (unsigned long long)r->checked,
                       r->reported, 1e6 * (b - a), s1, s2, evs);
            }
        }
        px_scene_destroy(scene);
    }
    for (int x = 0; x < NBODY; ++x)
        for (int y = 0; y < NBODY; ++y) px_model_cache_release(&caches[x][y]);

    /* Timing: per step the median over the runs, then over the trajectory. */
    double *med_step = malloc(sizeof(double) * (size_t)nsteps),
           *med_min = malloc(sizeof(double) * (size_t)nsteps);
    double *checked = malloc(sizeof(double) * (size_t)nsteps);
    for (int i = 0; i < nsteps; ++i) {
        for (int r = 0; r < reps; ++r) tmp[r] = t_step[(size_t)i * reps + r];
        med_step[i] = quantile(tmp, reps, 0.5);
        for (int r = 0; r < reps; ++r) tmp[r] = t_min[(size_t)i * reps + r];
        med_min[i] = quantile(tmp, reps, 0.5);
        checked[i] = (double)rec[i].checked;
    }
    double closest = INFINITY, closest_apart = INFINITY;
    int ic = 0, ia = 0;
    for (int i = 0; i < nsteps; ++i) {
        if (rec[i].cell_d < closest) closest = rec[i].cell_d, ic = i;
    }
    /* The closest approach of another pair than the closest one's, apart. */
    for (int i = 0; i < nsteps; ++i)
        if (rec[i].cell_d > MARGIN && rec[i].cell_d < closest_apart &&
            (rec[i].cell_a != rec[ic].cell_a || rec[i].cell_b != rec[ic].cell_b))
            closest_apart = rec[i].cell_d, ia = i;
    double self_min = INFINITY;
    int is = 0;
    for (int i = 0; i < nsteps; ++i)
        if (rec[i].self_d < self_min) self_min = rec[i].self_d, is = i;
    printf("\nsummary (%d steps):\n", nsteps);
    printf("  self-collision : none; closest non-adjacent links %s-%s at %.2f mm (t = %.3f s)\n",
           body_name[rec[is].self_a], body_name[rec[is].self_b], 1e3 * self_min, rec[is].t);
    printf("  cell           : closest %s-%s at %.3g mm (t = %.3f s); contacts began %d, ended %d%s\n",
           body_name[rec[ic].cell_a], body_name[rec[ic].cell_b], 1e3 * closest, rec[ic].t, began, ended,
           touched ? " (the gripper touches the teapot)" : "");
    printf("                   closest approach of another pair: %s-%s at %.2f mm (t = %.3f s)\n",
           body_name[rec[ia].cell_a], body_name[rec[ia].cell_b], 1e3 * closest_apart, rec[ia].t);
    double tm = 0;
    for (int i = 0; i < nsteps; ++i) tm += checked[i];
    printf("  px_scene_step  : median %.2f us, p90 %.2f us, max %.2f us per step (median of %d runs per "
           "step);\n",
           1e6 * quantile(med_step, nsteps, 0.5), 1e6 * quantile(med_step, nsteps, 0.9),
           1e6 * quantile(med_step, nsteps, 1.0), reps);
    printf("                   narrow-phase pairs checked per step: mean %.2f, median %.0f, max %.0f (of %d "
           "pairs);\n"
           "                   scene memory %zu bytes\n",
           tm / nsteps, quantile(checked, nsteps, 0.5), quantile(checked, nsteps, 1.0), 15 + PUMA_LINKS * 4,
           mem);
    printf("  min_distance   : median %.2f us, p90 %.2f us per call (after the step)\n",
           1e6 * quantile(med_min, nsteps, 0.5), 1e6 * quantile(med_min, nsteps, 0.9));
    /* The trajectory and the cell were laid out for the nimasarli arm. */
    if (set == PUMA_NIMASARLI && (!touched || began != 1 || ended != 1 || other_contacts)) {
        fprintf(stderr,
                "FAIL: expected one contact, gripper-teapot, that begins and ends (touched %d, began %d, "
                "ended %d, others %d)\n",
                touched, began, ended, other_contacts);
        failures++;
    }
    printf("  checks         : scene minimum and reported pairs against warm px_model_distance at every "
           "step: %s\n",
           failures ? "FAILED" : "OK");

    /* Files for the plot. */
    if (plot) {
        char path[1024], path2[1024];
        snprintf(path, sizeof path, "%s/puma_cell_clearance.dat", out);
        FILE *f = fopen(path, "w");
        int ok = f != NULL;
        if (f) {
            fprintf(f, "# t_s self_mm cell_mm min_mm cell_pair_code self_pair_code (code = 16 a + b)\n");
            for (int i = 0; i < nsteps; ++i)
                fprintf(f, "%.4f %.4f %.4f %.4f %d %d\n", rec[i].t, 1e3 * rec[i].self_d, 1e3 * rec[i].cell_d,
                        1e3 * rec[i].min_d, 16 * rec[i].cell_a + rec[i].cell_b,
                        16 * rec[i].self_a + rec[i].self_b);
            ok = fclose(f) == 0;
        }
        view w = make_view(-0.35, 0.45);
        double q[PUMA_JOINTS];
        int shots[2] = {ic, ia};
        for (int s = 0; s < 2 && ok; ++s) {
            snprintf(path, sizeof path, "%s/puma_cell_view%d.dat", out, s);
            snprintf(path2, sizeof path2, "%s/puma_cell_witness%d.dat", out, s);
            puma_trajectory(rec[shots[s]].t, q);
            ok = write_view(path, path2, &arm, &cell, q, &w, rec[shots[s]].cell_pa, rec[shots[s]].cell_pb);
        }
        /* One curve of points per cell pair that is the closest somewhere. */
        int codes[64], ncodes = 0;
        for (int i = 0; i < nsteps; ++i) {
            int c = 16 * rec[i].cell_a + rec[i].cell_b, seen = 0;
            for (int k = 0; k < ncodes; ++k) seen |= codes[k] == c;
            if (!seen && ncodes < 64) codes[ncodes++] = c;
        }
        snprintf(path, sizeof path, "%s/puma_cell.gp", out);
        f = ok ? fopen(path, "w") : NULL;
        if (f) {
            fprintf(f,
                    "# written by proxima_puma_cell; run from its output folder\n"
                    "set terminal pngcairo size 1400,1050 font 'DejaVu Sans,10'\n"
                    "set output 'puma_cell.png'\n"
                    "set multiplot\n"
                    "set origin 0,0.5\nset size 1,0.5\n"
                    "set title 'Puma 560 in its cell: clearance along the trajectory (px\\_scene, %d steps "
                    "of %.1f ms)'\n"
                    "set xlabel 'time (s)'\nset ylabel 'clearance (mm)'\nset yrange [0:160]\nset grid\n"
                    "set key outside right top\n"
                    "set arrow 1 from %.4f,%.4f+25 to %.4f,%.4f+1 lw 1.5 lc rgb 'red'\n"
                    "set label 1 'touch: %s-%s' at %.4f,%.4f+30 center tc rgb 'red'\n"
                    "set arrow 2 from %.4f,%.4f+35 to %.4f,%.4f+1 lw 1.5 lc rgb 'black'\n"
                    "set label 2 'closest other pair: %s-%s, %.1f mm' at %.4f,%.4f+40 center\n"
                    "plot 'puma_cell_clearance.dat' using 1:2 with lines lw 2 lc rgb '#666666' title 'self: "
                    "closest "
                    "non-adjacent links (%s-%s)'",
                    nsteps, 1e3 * dt, rec[ic].t, 1e3 * closest, rec[ic].t, 1e3 * closest,
                    body_name[rec[ic].cell_a], body_name[rec[ic].cell_b], rec[ic].t, 1e3 * closest, rec[ia].t,
                    1e3 * closest_apart, rec[ia].t, 1e3 * closest_apart, body_name[rec[ia].cell_a],
                    body_name[rec[ia].cell_b], 1e3 * closest_apart, rec[ia].t, 1e3 * closest_apart,
                    body_name[rec[is].self_a], body_name[rec[is].self_b]);
            for (int k = 0; k < ncodes; ++k)
                fprintf(
                    f,
                    ", \\\n  'puma_cell_clearance.dat' using 1:($5==%d ? $3 : 1/0) with points pt 7 ps 0.45 "
                    "lc %d title 'cell, closest pair %s-%s'",
                    codes[k], k + 1, body_name[codes[k] / 16], body_name[codes[k] % 16]);
            fprintf(f, "\nunset arrow\nunset label\nunset grid\nunset key\n"
                       "unset xlabel\nunset ylabel\nunset tics\nunset border\nset size ratio -1\n"
                       "set style fill solid noborder\nset autoscale\n");
            for (int s = 0; s < 2; ++s) {
                int i = shots[s];
                if (rec[i].cell_d <= MARGIN)
                    fprintf(f, "unset label 3\n");
                else
                    fprintf(f, "set label 3 'gap %.1f mm' at graph 0.05,0.05\n", 1e3 * rec[i].cell_d);
                fprintf(
                    f,
                    "set origin %g,0\nset size 0.5,0.5\n"
                    "set title 't = %.3f s: %s-%s %s (witness points in red)'\n"
                    "plot 'puma_cell_view%d.dat' using 1:2:3 with filledcurves closed lc rgb variable, \\\n"
                    "  'puma_cell_witness%d.dat' using 1:2 with linespoints lw 3 pt 6 ps 2 lc rgb 'red'\n",
                    0.5 * s, rec[i].t, body_name[rec[i].cell_a], body_name[rec[i].cell_b],
                    rec[i].cell_d <= MARGIN ? "touching" : "", s, s);
            }
            fprintf(f, "unset multiplot\n");
            ok = fclose(f) == 0;
        } else {
            ok = 0;
        }
        if (ok) {
            char cmd[1200];
            snprintf(cmd, sizeof cmd, "cd '%s' && gnuplot puma_cell.gp", out);
            ok = system(cmd) == 0;
        }
        printf("  plot           : %s/puma_cell.png %s\n", out,
               ok ? "written" : "NOT written (gnuplot failed?)");
    }
    free(med_step), free(med_min), free(checked);
    free(rec), free(t_step), free(t_min), free(tmp);
    puma_cell_destroy(&cell);
    puma_arm_destroy(&arm);
    return failures ? 1 : 0;
}
