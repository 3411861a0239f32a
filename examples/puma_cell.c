/* proxima_puma_cell: the Puma 560 in a work cell (issue 11, section 3;
 * `make demo` runs it first).
 *
 * The arm (seven link models, examples/puma560.c) moves along a
 * joint-space trajectory past a table, a fixture, a teapot it touches once
 * and a pillar, all bodies of one px_scene: the moving links with motion
 * bounds from the joint speed limits, adjacent links excluded, the cell
 * static and paired with the arm only (the arm is a px_chain,
 * proxima/chain.h). Each step it sets the joint angles
 * (px_chain_set_joints: forward kinematics and the link poses), calls
 * px_scene_step (timed with px_chain_set_joints) and
 * px_scene_min_distance, and reports self-collision (non-adjacent links),
 * contacts with the cell and the minimum clearance with its pair.
 *
 * Two kinds of models (--pieces):
 * - triangles (exact, the default) or parts: one run, timed;
 * - approximate: the timed run uses coarse models, every body with convex
 *   leaves (the links and the teapot as PX_PIECES_APPROXIMATE pieces at
 *   --tolerance, cached as .pxm files in --cache, default --out; the boxes
 *   as exact point-set pieces). Their distances are brackets: the meshes'
 *   true distance lies in [distance, upper_bound]. A second, untimed run
 *   with the exact models (triangle leaves) on every --exact-every'th step
 *   (the touching step among them) gives the exact numbers (witness
 *   points, the touch), and checks that at each of its steps the exact
 *   distance of every pair the scene may pair lies in the timed run's
 *   bracket (reported pairs) or beyond the report distance (others).
 *
 * Checks (exit status 1 when one fails): at every step of each run the
 * scene's minimum equals the smallest of the demo's own warm
 * px_model_distance queries over every pair the scene may pair, on the
 * same models, and the reported pairs are exactly those within the report
 * distance; with exact models the gripper touches the teapot (a contact
 * begins and ends) and nothing else is in contact; with approximate models
 * the brackets hold the exact distances.
 *
 * Output: a table every quarter second and a summary on stdout;
 * OUT/puma_cell.png (clearance over time with the closest pair: the exact
 * run's as lines, the approximate run's brackets as bands; and the arm
 * drawn at its closest approaches with the exact witness segment; drawn by
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
#define NPAIR (15 + 4 * PUMA_LINKS) /* non-adjacent link pairs, link-cell pairs */
#define MARGIN 0.001                /* contact: within 1 mm */
#define REPORT 0.02                 /* reported with distance and witnesses: within 20 mm */
#define TEAPOT (PUMA_LINKS + 2)
#define GRIPPER 6

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

/* The pairs the scene may pair: non-adjacent links, and every link with
 * every cell body. pair_of[x][y] = index (x < y), -1 otherwise. */
static int pair_x[NPAIR], pair_y[NPAIR], pair_of[NBODY][NBODY];

static void make_pairs(void) {
    int n = 0;
    for (int x = 0; x < NBODY; ++x)
        for (int y = 0; y < NBODY; ++y) pair_of[x][y] = -1;
    for (int x = 0; x < PUMA_LINKS; ++x)
        for (int y = x + 2; y < NBODY; ++y) pair_x[n] = x, pair_y[n] = y, pair_of[x][y] = n++;
    for (int x = 0; x < PUMA_LINKS; ++x)
        if (pair_of[x][PUMA_LINKS] < 0) pair_x[n] = x, pair_y[n] = PUMA_LINKS, pair_of[x][PUMA_LINKS] = n++;
}

/* What the demo records per step (from a run's first repetition). The
 * demo's own distances are lower bounds with an upper bound (equal for
 * exact models); "closest" is by the lower bound. */
typedef struct step_rec {
    int valid;
    double t;
    double min_d, min_u;   /* px_scene_min_distance, and the smallest reported upper bound */
    int min_a, min_b;      /* its pair (demo body indices) */
    double self_d, cell_d; /* the demo's own: closest non-adjacent links, closest link-cell pair */
    double self_u, cell_u; /* the smallest upper bounds over the same pairs */
    int self_a, self_b, cell_a, cell_b;
    px_vec3 cell_pa, cell_pb;
    uint64_t checked;
    uint32_t reported, contacts;
} step_rec;

/* One run of the scene over steps first, first + stride, ... < nsteps. */
typedef struct run {
    const char *label;
    const px_model *model[NBODY];
    const puma_arm *arm;   /* the kinematics (its set) */
    const puma_cell *cell; /* the cell's poses */
    int first, stride, nsteps, reps, table_every;
    double dt;
    int exact; /* exact models: expect the one touch, nothing else */
    /* Results. */
    int count; /* steps run */
    step_rec *rec;
    double *rep_d, *rep_u;            /* [step * NPAIR + pair]: the scene's report (NAN when not reported) */
    double *own_d;                    /* [step * NPAIR + pair]: the demo's own warm distance */
    double *t_step, *t_scene, *t_min; /* [k * reps + rep], k = step's index in the run */
    int failures, began, ended, other_contacts, touched;
    int touch_step;
    char possible[256]; /* pairs that came within the margin (lower bound) */
    size_t mem;
} run;

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

static void fail_oom(void) {
    fprintf(stderr, "puma_cell: out of memory\n");
    exit(2);
}

static void *xcalloc(size_t n, size_t size) {
    void *p = calloc(n ? n : 1, size);
    if (!p) fail_oom();
    return p;
}

static void fmt_range(char *buf, size_t size, double d, double u) {
    if (u > d)
        snprintf(buf, size, "[%.2f, %.2f]", 1e3 * d, 1e3 * u);
    else
        snprintf(buf, size, "%.2f", 1e3 * d);
}

/* Runs r->reps repetitions of the trajectory in a fresh scene each; the
 * first records and checks. Returns 0 on a setup or query error. */
static int run_scene(run *r) {
    int n = 0;
    for (int i = r->first; i < r->nsteps; i += r->stride) ++n;
    r->count = n;
    r->rec = xcalloc((size_t)r->nsteps, sizeof *r->rec);
    r->rep_d = xcalloc((size_t)r->nsteps * NPAIR, sizeof(double));
    r->rep_u = xcalloc((size_t)r->nsteps * NPAIR, sizeof(double));
    r->own_d = xcalloc((size_t)r->nsteps * NPAIR, sizeof(double));
    r->t_step = xcalloc((size_t)n * (size_t)r->reps, sizeof(double));
    r->t_scene = xcalloc((size_t)n * (size_t)r->reps, sizeof(double));
    r->t_min = xcalloc((size_t)n * (size_t)r->reps, sizeof(double));
    px_model_cache(*caches)[NBODY] = xcalloc(NBODY, sizeof *caches);
    px_error err;
    memset(&err, 0, sizeof err);
    int ok = 1;
    for (int rep = 0; rep < r->reps && ok; ++rep) {
        px_scene_options so;
        memset(&so, 0, sizeof so);
        so.margin = MARGIN;
        so.report_distance = REPORT;
        px_scene *scene = px_scene_create(&so, &err);
        uint32_t ids[NBODY], back[64];
        double q[PUMA_JOINTS];
        puma_trajectory(r->first * r->dt, q);
        /* The scene holds this run's models: an arm and a cell that point to them. */
        puma_arm arm = *r->arm;
        puma_cell cell = *r->cell;
        for (int k = 0; k < PUMA_LINKS; ++k) arm.link[k] = (px_model *)r->model[k];
        for (int c = 0; c < PUMA_CELL_BODIES; ++c) cell.body[c].model = (px_model *)r->model[PUMA_LINKS + c];
        /* The arm is a px_chain: forward kinematics, adjacent links
         * excluded, motion bounds from the joint speed limits. */
        px_chain *chain = scene ? puma_chain_create(&arm, NULL, 1, 3, &err) : NULL;
        if (!chain || px_chain_add_to_scene(chain, scene, q, ids, &err) != PX_OK ||
            puma_cell_add(&cell, scene, 2, 1, ids + PUMA_LINKS, &err) != PX_OK) {
            fprintf(stderr, "puma_cell: %s\n", err.message);
            px_scene_destroy(scene);
            px_chain_destroy(chain);
            ok = 0;
            break;
        }
        for (int b = 0; b < NBODY; ++b) back[ids[b]] = (uint32_t)b;
        for (int i = r->first, k = 0; i < r->nsteps && ok; i += r->stride, ++k) {
            double t = i * r->dt;
            px_pose pose[NBODY];
            puma_trajectory(t, q);
            puma_link_poses(r->arm->set, q, pose);
            double a = now();
            px_status st = px_chain_set_joints(chain, scene, ids, q, &err);
            double b = now();
            if (st == PX_OK) st = px_scene_step(scene, t, &err);
            double c = now();
            px_scene_pair mp;
            px_status st2 = px_scene_min_distance(scene, &mp, &err);
            double d = now();
            if (st != PX_OK || st2 != PX_OK) {
                fprintf(stderr, "puma_cell: %s: step %d: %s\n", r->label, i, err.message);
                ok = 0;
                break;
            }
            r->t_step[(size_t)k * r->reps + rep] = c - a;
            r->t_scene[(size_t)k * r->reps + rep] = c - b;
            r->t_min[(size_t)k * r->reps + rep] = d - c;
            if (rep) continue;

            /* The first run records and checks. */
            step_rec *s = &r->rec[i];
            px_scene_stats stats;
            px_scene_get_stats(scene, &stats);
            s->valid = 1;
            s->t = t;
            s->checked = stats.pairs_checked;
            if (stats.memory_bytes > r->mem) r->mem = stats.memory_bytes;
            s->min_d = mp.distance;
            s->min_u = mp.upper_bound;
            s->min_a = (int)back[mp.body_a];
            s->min_b = (int)back[mp.body_b];
            size_t np, ne;
            const px_scene_pair *pairs = px_scene_pairs(scene, &np);
            const px_scene_event *ev = px_scene_events(scene, &ne);
            s->reported = (uint32_t)np;
            double *rd = r->rep_d + (size_t)i * NPAIR, *ru = r->rep_u + (size_t)i * NPAIR;
            for (int p = 0; p < NPAIR; ++p) rd[p] = ru[p] = NAN;
            int unknown = 0;
            for (size_t m = 0; m < np; ++m) {
                int x = (int)back[pairs[m].body_a], y = (int)back[pairs[m].body_b];
                int p = x < y ? pair_of[x][y] : pair_of[y][x];
                s->contacts += pairs[m].contact;
                if (pairs[m].upper_bound < s->min_u) s->min_u = pairs[m].upper_bound;
                if (p < 0) {
                    unknown++;
                    continue;
                }
                rd[p] = pairs[m].distance, ru[p] = pairs[m].upper_bound;
                if (pairs[m].distance <= MARGIN) {
                    char name[32];
                    snprintf(name, sizeof name, " %s-%s", body_name[x], body_name[y]);
                    if (!strstr(r->possible, name) && strlen(r->possible) + strlen(name) < sizeof r->possible)
                        strcat(r->possible, name);
                }
            }

            /* The demo's own answer: warm px_model_distance over every pair
             * the scene may pair (non-adjacent links, link-cell). */
            for (int c2 = 0; c2 < PUMA_CELL_BODIES; ++c2) pose[PUMA_LINKS + c2] = r->cell->body[c2].pose;
            s->self_d = s->cell_d = s->self_u = s->cell_u = INFINITY;
            uint32_t within = 0, mismatch = 0;
            for (int p = 0; p < NPAIR; ++p) {
                int x = pair_x[p], y = pair_y[p];
                px_model_distance_result dd;
                if (px_model_distance(r->model[x], &pose[x], r->model[y], &pose[y], &caches[x][y], &dd) !=
                    PX_OK) {
                    fprintf(stderr, "puma_cell: %s: step %d: query failed\n", r->label, i);
                    ok = 0;
                    break;
                }
                r->own_d[(size_t)i * NPAIR + p] = dd.distance;
                within += dd.distance <= REPORT;
                if (dd.distance <= REPORT && !(fabs(rd[p] - dd.distance) <= 1e-12)) mismatch++;
                if (y < PUMA_LINKS) {
                    if (dd.distance < s->self_d) s->self_d = dd.distance, s->self_a = x, s->self_b = y;
                    if (dd.upper_bound < s->self_u) s->self_u = dd.upper_bound;
                } else {
                    if (dd.distance < s->cell_d) {
                        s->cell_d = dd.distance, s->cell_a = x, s->cell_b = y;
                        s->cell_pa = dd.point_a, s->cell_pb = dd.point_b;
                    }
                    if (dd.upper_bound < s->cell_u) s->cell_u = dd.upper_bound;
                }
            }
            double best = s->self_d < s->cell_d ? s->self_d : s->cell_d;
            if (ok && (fabs(best - s->min_d) > 1e-12 || within != np || mismatch || unknown)) {
                if (++r->failures <= 10)
                    fprintf(
                        stderr,
                        "FAIL %s step %d: scene minimum %.17g (%s-%s), own %.17g; reported %zu pairs, own "
                        "%u, %u distances differ\n",
                        r->label, i, s->min_d, body_name[s->min_a], body_name[s->min_b], best, np, within,
                        mismatch);
            }
            char evs[160] = "";
            for (size_t m = 0; m < ne; ++m) {
                int x = (int)back[ev[m].body_a], y = (int)back[ev[m].body_b];
                size_t l = strlen(evs);
                snprintf(evs + l, sizeof evs - l, "%s%s %s-%s", l ? ", " : "", ev[m].began ? "begin" : "end",
                         body_name[x], body_name[y]);
                if (ev[m].began) {
                    r->began++;
                    if (!((x == GRIPPER || y == GRIPPER) && (x == TEAPOT || y == TEAPOT)))
                        r->other_contacts++;
                } else {
                    r->ended++;
                }
            }
            if (i == r->touch_step)
                for (size_t m = 0; m < np; ++m)
                    if (pairs[m].contact && back[pairs[m].body_a] == GRIPPER &&
                        back[pairs[m].body_b] == TEAPOT)
                        r->touched = 1;
            if ((r->table_every && i % r->table_every == 0) || ne || i == r->touch_step) {
                char s1[48], s2[48], g1[32], g2[32];
                fmt_range(g1, sizeof g1, s->self_d, s->self_u);
                fmt_range(g2, sizeof g2, s->cell_d, s->cell_u);
                snprintf(s1, sizeof s1, "%s-%s %s", body_name[s->self_a], body_name[s->self_b], g1);
                snprintf(s2, sizeof s2, "%s-%s %s", body_name[s->cell_a], body_name[s->cell_b], g2);
                printf("%7.3f %7llu %7u %8.2f  %-28s %-29s %s\n", t, (unsigned long long)s->checked,
                       s->reported, 1e6 * (c - a), s1, s2, evs);
            }
        }
        px_scene_destroy(scene);
        px_chain_destroy(chain);
    }
    for (int x = 0; x < NBODY; ++x)
        for (int y = 0; y < NBODY; ++y) px_model_cache_release(&caches[x][y]);
    free(caches);
    return ok;
}

/* Per step the median over the repetitions, then quantiles over the steps. */
static void timing(const run *r, const double *t, double *med, double *p90, double *mx) {
    double *m = xcalloc((size_t)r->count, sizeof *m), *tmp = xcalloc((size_t)r->reps, sizeof *tmp);
    for (int k = 0; k < r->count; ++k) {
        for (int rep = 0; rep < r->reps; ++rep) tmp[rep] = t[(size_t)k * r->reps + rep];
        m[k] = quantile(tmp, r->reps, 0.5);
    }
    *med = 1e6 * quantile(m, r->count, 0.5);
    *p90 = 1e6 * quantile(m, r->count, 0.9);
    *mx = 1e6 * quantile(m, r->count, 1.0);
    free(m), free(tmp);
}

/* The closest records of a run: by the lower bound. */
typedef struct closest {
    int is, ic, ia; /* steps: closest self, closest cell, closest other cell pair apart */
} closest;

static closest find_closest(const run *r) {
    closest c = {-1, -1, -1};
    for (int i = 0; i < r->nsteps; ++i) {
        const step_rec *s = &r->rec[i];
        if (!s->valid) continue;
        if (c.is < 0 || s->self_d < r->rec[c.is].self_d) c.is = i;
        if (c.ic < 0 || s->cell_d < r->rec[c.ic].cell_d) c.ic = i;
    }
    /* The closest approach of another pair than the closest one's, apart. */
    for (int i = 0; i < r->nsteps; ++i) {
        const step_rec *s = &r->rec[i], *k = &r->rec[c.ic];
        if (s->valid && s->cell_d > MARGIN && (s->cell_a != k->cell_a || s->cell_b != k->cell_b) &&
            (c.ia < 0 || s->cell_d < r->rec[c.ia].cell_d))
            c.ia = i;
    }
    if (c.ia < 0) c.ia = c.ic;
    return c;
}

static void summary(const run *r, const char *models_desc) {
    closest c = find_closest(r);
    const step_rec *S = &r->rec[c.is], *C = &r->rec[c.ic], *A = &r->rec[c.ia];
    char g[48];
    if (r->stride > 1)
        printf("\nsummary, %s: %s, %d steps (every %dth of the timed run's):\n", r->label, models_desc,
               r->count, r->stride);
    else
        printf("\nsummary, %s: %s, %d steps:\n", r->label, models_desc, r->count);
    if (r->exact) {
        printf("  self-collision : %s; closest non-adjacent links %s-%s at %.2f mm (t = %.3f s)\n",
               S->self_d <= MARGIN ? "CONTACT" : "none", body_name[S->self_a], body_name[S->self_b],
               1e3 * S->self_d, S->t);
        printf("  cell           : closest %s-%s at %.3g mm (t = %.3f s); contacts began %d, ended %d%s\n",
               body_name[C->cell_a], body_name[C->cell_b], 1e3 * C->cell_d, C->t, r->began, r->ended,
               r->touched ? " (the gripper touches the teapot)" : "");
        printf("                   closest approach of another pair: %s-%s at %.2f mm (t = %.3f s)\n",
               body_name[A->cell_a], body_name[A->cell_b], 1e3 * A->cell_d, A->t);
    } else {
        /* Clearances are brackets: the true one lies in [smallest lower
         * bound, smallest upper bound] over the pairs. */
        fmt_range(g, sizeof g, S->self_d, S->self_u);
        printf("  self-collision : clearance of non-adjacent links at its smallest in %s mm (closest by the "
               "lower\n"
               "                   bound: %s-%s, t = %.3f s)\n",
               g, body_name[S->self_a], body_name[S->self_b], S->t);
        fmt_range(g, sizeof g, C->cell_d, C->cell_u);
        printf("  cell           : clearance at its smallest in %s mm (%s-%s, t = %.3f s)\n", g,
               body_name[C->cell_a], body_name[C->cell_b], C->t);
        fmt_range(g, sizeof g, A->cell_d, A->cell_u);
        printf(
            "                   closest approach of another pair: %s-%s, clearance in %s mm (t = %.3f s)\n",
            body_name[A->cell_a], body_name[A->cell_b], g, A->t);
        printf("  contacts       : by the lower bound (distance <= %g mm): began %d, ended %d; pairs:%s\n",
               1e3 * MARGIN, r->began, r->ended, r->possible[0] ? r->possible : " none");
    }
    double med, p90, mx, m2, p2, x2;
    timing(r, r->t_step, &med, &p90, &mx);
    timing(r, r->t_scene, &m2, &p2, &x2);
    printf("  px_scene_step  : with px_chain_set_joints (6 link poses): median %.2f us, p90 %.2f us, max "
           "%.2f us "
           "per step\n"
           "                   (median of %d run%s per step); the step alone: median %.2f us, p90 %.2f us\n",
           med, p90, mx, r->reps, r->reps > 1 ? "s" : "", m2, p2);
    double *checked = xcalloc((size_t)r->count, sizeof *checked), tm = 0;
    int k = 0;
    for (int i = r->first; i < r->nsteps; i += r->stride)
        tm += (double)(checked[k++] = (double)r->rec[i].checked);
    printf("                   narrow-phase pairs checked per step: mean %.2f, median %.0f, max %.0f (of %d "
           "pairs);\n"
           "                   scene memory %zu bytes\n",
           tm / r->count, quantile(checked, r->count, 0.5), quantile(checked, r->count, 1.0), NPAIR, r->mem);
    free(checked);
    timing(r, r->t_min, &med, &p90, &mx);
    printf("  min_distance   : median %.2f us, p90 %.2f us per call (after the step)\n", med, p90);
    if (!r->exact) {
        /* Bracket widths of the reported pairs. */
        size_t n = 0;
        double *w = xcalloc((size_t)r->nsteps * NPAIR, sizeof *w);
        for (int i = r->first; i < r->nsteps; i += r->stride)
            for (int p = 0; p < NPAIR; ++p)
                if (!isnan(r->rep_d[(size_t)i * NPAIR + p]))
                    w[n++] = r->rep_u[(size_t)i * NPAIR + p] - r->rep_d[(size_t)i * NPAIR + p];
        if (n)
            printf("  brackets       : %zu reported pair-steps; upper_bound - distance: median %.2f mm, p90 "
                   "%.2f mm, "
                   "max %.2f mm\n",
                   n, 1e3 * quantile(w, (int)n, 0.5), 1e3 * quantile(w, (int)n, 0.9),
                   1e3 * quantile(w, (int)n, 1.0));
        free(w);
    }
}

static void run_free(run *r) {
    free(r->rec), free(r->rep_d), free(r->rep_u), free(r->own_d);
    free(r->t_step), free(r->t_scene), free(r->t_min);
}
static void print_head(void) {
    printf("%7s %7s %7s %8s  %-28s %-29s %s\n", "t (s)", "checked", "report", "step us",
           "self: closest pair (mm)", "cell: closest pair (mm)", "events");
}

static void usage(FILE *f) {
    fprintf(f,
            "usage: proxima_puma_cell [--models DIR] [--out DIR] [--meshes nimasarli|rtb|rtb-collision]\n"
            "                         [--pieces triangles|parts|approximate] [--tolerance T] [--cache DIR]\n"
            "                         [--exact-every N] [--dt S] [--reps R] [--no-plot]\n");
}

/* The gnuplot script: clearance over time (exact lines, approximate
 * brackets as bands) and the arm at two moments of run `e`. */
static int write_plot(const char *out, const run *e, const run *f, double tolerance, const puma_arm *arm,
                      const puma_cell *cell) {
    char path[1024], path2[1024];
    closest c = find_closest(e);
    const step_rec *C = &e->rec[c.ic], *A = &e->rec[c.ia], *S = &e->rec[c.is];
    snprintf(path, sizeof path, "%s/puma_cell_clearance.dat", out);
    FILE *fp = fopen(path, "w");
    if (!fp) return 0;
    fprintf(fp, "# %s: t_s self_mm cell_mm min_mm cell_pair_code self_pair_code (code = 16 a + b)\n",
            e->label);
    for (int i = 0; i < e->nsteps; ++i)
        if (e->rec[i].valid)
            fprintf(fp, "%.4f %.4f %.4f %.4f %d %d\n", e->rec[i].t, 1e3 * e->rec[i].self_d,
                    1e3 * e->rec[i].cell_d, 1e3 * e->rec[i].min_d, 16 * e->rec[i].cell_a + e->rec[i].cell_b,
                    16 * e->rec[i].self_a + e->rec[i].self_b);
    if (fclose(fp)) return 0;
    if (f) {
        snprintf(path, sizeof path, "%s/puma_cell_bracket.dat", out);
        fp = fopen(path, "w");
        if (!fp) return 0;
        fprintf(fp, "# %s: t_s self_lower_mm self_upper_mm cell_lower_mm cell_upper_mm\n", f->label);
        for (int i = 0; i < f->nsteps; ++i)
            if (f->rec[i].valid)
                fprintf(fp, "%.4f %.4f %.4f %.4f %.4f\n", f->rec[i].t, 1e3 * f->rec[i].self_d,
                        1e3 * f->rec[i].self_u, 1e3 * f->rec[i].cell_d, 1e3 * f->rec[i].cell_u);
        if (fclose(fp)) return 0;
    }
    view w = make_view(-0.35, 0.45);
    double q[PUMA_JOINTS];
    int shots[2] = {c.ic, c.ia};
    for (int s = 0; s < 2; ++s) {
        snprintf(path, sizeof path, "%s/puma_cell_view%d.dat", out, s);
        snprintf(path2, sizeof path2, "%s/puma_cell_witness%d.dat", out, s);
        puma_trajectory(e->rec[shots[s]].t, q);
        if (!write_view(path, path2, arm, cell, q, &w, e->rec[shots[s]].cell_pa, e->rec[shots[s]].cell_pb))
            return 0;
    }
    /* One curve of points per cell pair that is the closest somewhere. */
    int codes[64], ncodes = 0;
    for (int i = 0; i < e->nsteps; ++i) {
        if (!e->rec[i].valid) continue;
        int code = 16 * e->rec[i].cell_a + e->rec[i].cell_b, seen = 0;
        for (int k = 0; k < ncodes; ++k) seen |= codes[k] == code;
        if (!seen && ncodes < 64) codes[ncodes++] = code;
    }
    snprintf(path, sizeof path, "%s/puma_cell.gp", out);
    fp = fopen(path, "w");
    if (!fp) return 0;
    char sub[200] = "";
    if (f)
        snprintf(sub, sizeof sub,
                 "\\nlines and points: exact models (triangle leaves), %d steps; bands: approximate pieces "
                 "(tolerance "
                 "%g), [distance, upper bound], %d steps",
                 e->count, tolerance, f->count);
    fprintf(fp,
            "# written by proxima_puma_cell; run from its output folder\n"
            "set terminal pngcairo size 1400,1050 font 'DejaVu Sans,10'\n"
            "set output 'puma_cell.png'\n"
            "set multiplot\n"
            "set origin 0,0.5\nset size 1,0.5\n"
            "set title \"Puma 560 in its cell: clearance along the trajectory (px\\\\_scene)%s\"\n"
            "set xlabel 'time (s)'\nset ylabel 'clearance (mm)'\nset yrange [0:160]\nset grid\n"
            "set key outside right top\n"
            "set arrow 1 from %.4f,%.4f+25 to %.4f,%.4f+1 lw 1.5 lc rgb 'red'\n"
            "set label 1 'touch: %s-%s' at %.4f,%.4f+30 center tc rgb 'red'\n"
            "set arrow 2 from %.4f,%.4f+35 to %.4f,%.4f+1 lw 1.5 lc rgb 'black'\n"
            "set label 2 'closest other pair: %s-%s, %.1f mm' at %.4f,%.4f+40 center\n"
            "plot ",
            sub, C->t, 1e3 * C->cell_d, C->t, 1e3 * C->cell_d, body_name[C->cell_a], body_name[C->cell_b],
            C->t, 1e3 * C->cell_d, A->t, 1e3 * A->cell_d, A->t, 1e3 * A->cell_d, body_name[A->cell_a],
            body_name[A->cell_b], 1e3 * A->cell_d, A->t, 1e3 * A->cell_d);
    if (f)
        fprintf(fp,
                "'puma_cell_bracket.dat' using 1:4:5 with filledcurves fs transparent solid 0.3 noborder "
                "lc rgb '#3070c0' title 'approximate: cell clearance bracket', \\\n"
                "  'puma_cell_bracket.dat' using 1:2:3 with filledcurves fs transparent solid 0.3 noborder "
                "lc rgb '#909090' title 'approximate: self clearance bracket', \\\n  ");
    fprintf(fp,
            "'puma_cell_clearance.dat' using 1:2 with lines lw 2 lc rgb '#666666' title '%sself: closest "
            "non-adjacent links (%s-%s)'",
            f ? "exact: " : "", body_name[S->self_a], body_name[S->self_b]);
    for (int k = 0; k < ncodes; ++k)
        fprintf(fp,
                ", \\\n  'puma_cell_clearance.dat' using 1:($5==%d ? $3 : 1/0) with points pt 7 ps 0.45 "
                "lc %d title '%scell, closest pair %s-%s'",
                codes[k], k + 1, f ? "exact: " : "", body_name[codes[k] / 16], body_name[codes[k] % 16]);
    fprintf(fp, "\nunset arrow\nunset label\nunset grid\nunset key\n"
                "unset xlabel\nunset ylabel\nunset tics\nunset border\nset size ratio -1\n"
                "set style fill solid noborder\nset autoscale\n");
    for (int s = 0; s < 2; ++s) {
        const step_rec *r = &e->rec[shots[s]];
        if (r->cell_d <= MARGIN)
            fprintf(fp, "unset label 3\n");
        else
            fprintf(fp, "set label 3 'gap %.1f mm' at graph 0.05,0.05\n", 1e3 * r->cell_d);
        fprintf(fp,
                "set origin %g,0\nset size 0.5,0.5\n"
                "set title 't = %.3f s: %s-%s %s (%switness points in red)'\n"
                "plot 'puma_cell_view%d.dat' using 1:2:3 with filledcurves closed lc rgb variable, \\\n"
                "  'puma_cell_witness%d.dat' using 1:2 with linespoints lw 3 pt 6 ps 2 lc rgb 'red'\n",
                0.5 * s, r->t, body_name[r->cell_a], body_name[r->cell_b],
                r->cell_d <= MARGIN ? "touching" : "", f ? "exact models, " : "", s, s);
    }
    fprintf(fp, "unset multiplot\n");
    if (fclose(fp)) return 0;
    char cmd[1200];
    snprintf(cmd, sizeof cmd, "cd '%s' && gnuplot puma_cell.gp", out);
    return system(cmd) == 0;
}

int main(int argc, char **argv) {
    const char *models = "models", *out = ".", *cache = NULL;
    puma_meshes set = PUMA_NIMASARLI;
    uint32_t pieces = PX_PIECES_TRIANGLES;
    double dt = 0.004, tolerance = PX_MODEL_DEFAULT_TOLERANCE;
    int reps = 5, plot = 1, exact_every = 1;
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
        } else if (v && !strcmp(a, "--cache")) {
            cache = v, ++i;
        } else if (v && !strcmp(a, "--meshes")) {
            set = !strcmp(v, "rtb")             ? PUMA_RTB_VISUAL
                  : !strcmp(v, "rtb-collision") ? PUMA_RTB_COLLISION
                                                : PUMA_NIMASARLI;
            if (set == PUMA_NIMASARLI && strcmp(v, "nimasarli")) return usage(stderr), 2;
            ++i;
        } else if (v && !strcmp(a, "--pieces")) {
            if (!strcmp(v, "parts"))
                pieces = PX_PIECES_PARTS;
            else if (!strcmp(v, "approximate"))
                pieces = PX_PIECES_APPROXIMATE;
            else if (strcmp(v, "triangles"))
                return usage(stderr), 2;
            ++i;
        } else if (v && !strcmp(a, "--tolerance")) {
            tolerance = atof(v), ++i;
        } else if (v && !strcmp(a, "--exact-every")) {
            exact_every = atoi(v), ++i;
        } else if (v && !strcmp(a, "--dt")) {
            dt = atof(v), ++i;
        } else if (v && !strcmp(a, "--reps")) {
            reps = atoi(v), ++i;
        } else {
            usage(stderr);
            return 2;
        }
    }
    if (!(dt > 1e-4 && dt < 1) || reps < 1 || reps > 100 || exact_every < 1 ||
        !(tolerance >= PX_MODEL_MIN_TOLERANCE && tolerance <= 1))
        return usage(stderr), 2;
    if (!cache) cache = out;
    int approx = pieces == PX_PIECES_APPROXIMATE;
    make_pairs();

    static const char *set_name[PUMA_MESH_SETS] = {"nimasarli STL (inches)", "RTB visual COLLADA",
                                                   "RTB collision COLLADA"};
    printf("== The Puma 560 in a work cell (px_scene, issue 11) ==\n");
    px_error err;
    puma_arm arm, fast_arm;
    puma_cell cell, fast_cell;
    memset(&fast_arm, 0, sizeof fast_arm);
    memset(&fast_cell, 0, sizeof fast_cell);
    double t0 = now();
    /* The exact models (or the parts) always: the cell is placed with them. */
    if (puma_arm_load(&arm, models, set, approx ? PX_PIECES_TRIANGLES : pieces, &err) != PX_OK) {
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
    printf("arm   : %s, %u triangles; %s leaves loaded and built in %.2f s\n", set_name[set], tris,
           pieces == PX_PIECES_PARTS ? "part-hull" : "triangle (exact)", now() - t0);
    printf("cell  : table (5 boxes), fixture (2 boxes), teapot (%u triangles), pillar (1 box); triangle "
           "leaves;\n"
           "        the teapot is placed to touch the gripper at t = %.3f s, the pillar 15 mm from the arm\n",
           px_mesh_triangle_count(cell.body[2].mesh), puma_touch_time());
    puma_build build;
    memset(&build, 0, sizeof build);
    if (approx) {
        build.pieces = PX_PIECES_APPROXIMATE;
        build.tolerance = tolerance;
        build.threads = 2;
        build.cache_dir = cache;
        build.verbose = 1;
        t0 = now();
        printf("approximate models (tolerance %g of each part's box diagonal, cache %s):\n", tolerance,
               cache);
        if (puma_arm_load_with(&fast_arm, models, set, &build, &err) != PX_OK ||
            puma_cell_build_coarse(&fast_cell, models, &cell, &build, &err) != PX_OK) {
            fprintf(stderr, "puma_cell: %s\n", err.message);
            puma_arm_destroy(&fast_arm);
            puma_cell_destroy(&cell);
            puma_arm_destroy(&arm);
            return 2;
        }
        printf("        %d built (%.2f s), %d loaded from the cache; %.2f s in all; boxes as exact point-set "
               "pieces\n",
               build.built, build.build_seconds, build.loaded, now() - t0);
    }
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
    printf("scene : margin %g m (contact), report distance %g m; %d steps of %.4f s over %.2f s\n", MARGIN,
           REPORT, nsteps, dt, duration);

    run e, f;
    memset(&e, 0, sizeof e);
    memset(&f, 0, sizeof f);
    e.label = "exact";
    e.arm = &arm;
    e.cell = &cell;
    for (int k = 0; k < PUMA_LINKS; ++k) e.model[k] = arm.link[k];
    for (int c = 0; c < PUMA_CELL_BODIES; ++c) e.model[PUMA_LINKS + c] = cell.body[c].model;
    e.nsteps = nsteps, e.dt = dt, e.touch_step = touch_step;
    e.exact = pieces == PX_PIECES_TRIANGLES || approx;
    int table_every = (int)(0.25 / dt + 0.5), ok = 1;
    if (!approx) {
        /* One run, timed, with the models asked for. */
        if (pieces == PX_PIECES_PARTS) e.label = "part hulls";
        e.first = 0, e.stride = 1, e.reps = reps, e.table_every = table_every;
        printf("        %d timed runs\n\n", reps);
        print_head();
        ok = run_scene(&e);
    } else {
        f = e;
        f.label = "approximate";
        f.arm = &fast_arm;
        f.cell = &fast_cell;
        f.exact = 0;
        for (int k = 0; k < PUMA_LINKS; ++k) f.model[k] = fast_arm.link[k];
        for (int c = 0; c < PUMA_CELL_BODIES; ++c) f.model[PUMA_LINKS + c] = fast_cell.body[c].model;
        f.first = 0, f.stride = 1, f.reps = reps, f.table_every = table_every;
        printf("\n-- timed run: approximate models, %d runs; distances in mm, [lower, upper] brackets --\n",
               reps);
        print_head();
        ok = run_scene(&f);
        e.first = touch_step % exact_every, e.stride = exact_every, e.reps = 1, e.table_every = 0;
        printf("\n-- reference run: exact models (triangle leaves), every %d%s step, one run; rows: events "
               "only --\n",
               exact_every, exact_every == 1 ? "st" : "th");
        print_head();
        ok = ok && run_scene(&e);
    }
    if (!ok) return 2;
    int failures = e.failures + f.failures;

    /* The trajectory and the cell were laid out for the nimasarli arm. */
    if (approx) summary(&f, "approximate pieces (timed)");
    summary(&e, approx ? "exact models (triangle leaves; reference: one run, its times for comparison only)"
                : pieces == PX_PIECES_PARTS ? "part hulls (coarse: brackets), timed"
                                            : "triangle leaves, timed");
    if (set == PUMA_NIMASARLI && e.exact &&
        (!e.touched || e.began != 1 || e.ended != 1 || e.other_contacts)) {
        fprintf(stderr,
                "FAIL: expected one contact, gripper-teapot, that begins and ends (touched %d, began %d, "
                "ended %d, others %d)\n",
                e.touched, e.began, e.ended, e.other_contacts);
        failures++;
    }
    printf("  checks         : scene minimum and reported pairs against warm px_model_distance at every "
           "step: %s\n",
           failures ? "FAILED" : "OK");
    if (approx) {
        /* The brackets against the exact distances, at the exact run's steps. */
        long pair_steps = 0, reported = 0, bad = 0;
        double slack = 1e-9;
        for (int i = e.first; i < nsteps; i += e.stride)
            for (int p = 0; p < NPAIR; ++p) {
                double x = e.own_d[(size_t)i * NPAIR + p], d = f.rep_d[(size_t)i * NPAIR + p],
                       u = f.rep_u[(size_t)i * NPAIR + p];
                int good = isnan(d) ? x > REPORT : (x >= d - slack && x <= u + slack);
                pair_steps++;
                reported += !isnan(d);
                if (!good && bad++ < 10)
                    fprintf(stderr, "FAIL bracket: step %d %s-%s: exact %.9g, approximate %s [%.9g, %.9g]\n",
                            i, body_name[pair_x[p]], body_name[pair_y[p]], x, isnan(d) ? "not reported" : "",
                            d, u);
            }
        if (set == PUMA_NIMASARLI && !f.touched) {
            fprintf(stderr, "FAIL: the approximate run has no gripper-teapot contact at the touching step\n");
            failures++;
        }
        failures += bad > 0;
        printf(
            "  brackets       : exact distance in the timed run's [distance, upper_bound] for every reported "
            "pair,\n                   beyond %g mm for the others: %s (%ld pair-steps, %ld reported)\n",
            1e3 * REPORT, bad ? "FAILED" : "OK", pair_steps, reported);
    }
    if (plot) {
        int w = write_plot(out, &e, approx ? &f : NULL, tolerance, &arm, &cell);
        printf("  plot           : %s/puma_cell.png %s\n", out,
               w ? "written" : "NOT written (the folder could not be written to, or gnuplot failed)");
    }
    run_free(&e);
    if (approx) run_free(&f);
    puma_cell_destroy(&fast_cell);
    puma_arm_destroy(&fast_arm);
    puma_cell_destroy(&cell);
    puma_arm_destroy(&arm);
    return failures ? 1 : 0;
}
