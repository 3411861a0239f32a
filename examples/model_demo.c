/* proxima_model_demo: the Puma 560 arm as an assembly of seven meshes (make
 * demo). Loads the links (STL, inches: the scale option makes metres),
 * builds two models of each (exact triangle leaves; one hull per link with
 * its certified bound h), moves the arm along a joint-space path, and at
 * every step measures every pair of non-adjacent links and each link
 * against a box obstacle. It checks, and exits 1 if any check fails:
 * - the exact triangle distance lies inside the part-hull bracket;
 * - warm (tracked) and cold answers are the same;
 * - px_model_collide agrees with the distance;
 * - a model saved to .pxm and loaded answers the same.
 * Kinematics: the URDF of nimasarli/puma560_description
 * (models/puma560/SOURCE.md, table 1). Public API only. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "proxima/io.h"
#include "proxima/proxima.h"
#include "puma560.h"

#define NLINK 7
#define PI 3.14159265358979323846

static double now(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* Pose helpers: examples/puma560.c's (URDF origins, joint rotations). */

/* World poses of the seven link meshes at joint angles q[6]. */
static void arm_poses(const double q[6], px_pose out[NLINK]) {
    const double pi = PI;
    const px_vec3 z = {0, 0, 1}, y = {0, 1, 0};
    px_pose link = px_pose_identity();
    out[0] = puma_urdf_origin(0, 0, 0, 0, 0, pi / 2);
    px_pose joints[6] = {puma_urdf_origin(0, 0, 0.6718, pi / 2, 0, 0),
                         puma_urdf_origin(0, 0, 0, 0, 0, 0),
                         puma_urdf_origin(0.4318, -0.0203, 0.1501, 0, 0, -pi / 2),
                         puma_urdf_origin(0, 0, 0, pi / 2, 0, pi / 2),
                         puma_urdf_origin(0, 0, 0.4331, pi / 2, 0, 0),
                         puma_urdf_origin(0, 0.0558, 0, -pi / 2, 0, 0)};
    px_pose visuals[6] = {
        puma_urdf_origin(0, 0, -0.1, 0, 0, 0),    puma_urdf_origin(0, 0, 0.1936, 0, 0, 0),
        puma_urdf_origin(0, 0, 0, 0, 0, 0),       puma_urdf_origin(0, 0, 0.3621, 0, 0, pi / 2),
        puma_urdf_origin(0, 0, 0, pi, 0, pi / 2), puma_urdf_origin(0, 0, -0.010, 0, 0, 0)};
    for (int j = 0; j < 6; ++j) {
        px_pose rot = puma_axis_rotation(j == 0 ? y : z, q[j]);
        px_pose a = puma_compose(&link, &joints[j]);
        link = puma_compose(&a, &rot);
        out[j + 1] = puma_compose(&link, &visuals[j]);
    }
}

static int cmp_double(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double median(double *v, int n) {
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n ? v[n / 2] : 0.0;
}

int main(int argc, char **argv) {
    const char *models = "models";
    for (int i = 1; i + 1 < argc; ++i)
        if (!strcmp(argv[i], "--models")) models = argv[i + 1];
    printf("== Models: the Puma 560 arm as seven link meshes (issue 9) ==\n");
    px_model *tri[NLINK], *hull[NLINK];
    double t0 = now();
    size_t tri_bytes = 0, hull_bytes = 0;
    uint32_t triangles = 0;
    for (int i = 0; i < NLINK; ++i) {
        char path[1024];
        snprintf(path, sizeof path, "%s/puma560/nimasarli_puma560_description/meshes/puma_link%d.stl", models,
                 i + 1);
        px_mesh_options mo;
        memset(&mo, 0, sizeof mo);
        mo.scale = 0.0254; /* the STLs are in inches */
        px_error e;
        px_mesh *mesh = px_mesh_load(path, &mo, &e);
        if (!mesh) {
            fprintf(stderr, "model_demo: %s\n", e.message);
            return 1;
        }
        px_model_options o;
        memset(&o, 0, sizeof o);
        o.pieces = PX_PIECES_TRIANGLES;
        tri[i] = px_model_create_from_mesh(mesh, &o, &e);
        o.pieces = PX_PIECES_PARTS;
        hull[i] = tri[i] ? px_model_create_from_mesh(mesh, &o, &e) : NULL;
        if (!tri[i] || !hull[i]) {
            fprintf(stderr, "model_demo: link %d: %s\n", i + 1, e.message);
            return 1;
        }
        px_mesh_part part;
        px_mesh_get_part(mesh, 0, &part);
        px_model_info ti, hi;
        px_model_get_info(tri[i], &ti);
        px_model_get_info(hull[i], &hi);
        printf("link %d: %5u triangles, %s, h = %.4f m (hull %.1f KB, triangle tree %.1f KB)\n", i + 1,
               px_mesh_triangle_count(mesh), part.closed ? "closed" : "open  ", hi.max_h,
               hi.memory_bytes / 1024.0, ti.memory_bytes / 1024.0);
        triangles += px_mesh_triangle_count(mesh);
        tri_bytes += ti.memory_bytes;
        hull_bytes += hi.memory_bytes;
        px_mesh_destroy(mesh);
    }
    printf("built %u triangles into 14 models in %.2f s (%.0f bytes per triangle for the exact trees)\n",
           triangles, now() - t0, (double)tri_bytes / triangles);

    /* A box obstacle beside the arm's path. */
    double box[24];
    for (int k = 0; k < 8; ++k) {
        box[3 * k] = (k & 1) ? 0.1 : -0.1;
        box[3 * k + 1] = (k & 2) ? 0.15 : -0.15;
        box[3 * k + 2] = (k & 4) ? 0.2 : -0.2;
    }
    px_convex *obstacle = px_convex_create(box, 8, NULL, NULL);
    px_pose obstacle_pose = px_pose_identity();
    obstacle_pose.t = (px_vec3){0.55, 0.45, 0.7};

    /* The pairs: non-adjacent links, and every link against the box. */
    int pa[32], pb[32], npairs = 0;
    for (int i = 0; i < NLINK; ++i)
        for (int j = i + 2; j < NLINK; ++j) pa[npairs] = i, pb[npairs++] = j;
    px_model_cache tri_cache[32], hull_cache[32], box_cache[NLINK];
    memset(tri_cache, 0, sizeof tri_cache);
    memset(hull_cache, 0, sizeof hull_cache);
    memset(box_cache, 0, sizeof box_cache);

    const int steps = 120;
    double *t_tri = malloc(sizeof(double) * steps * npairs),
           *t_hull = malloc(sizeof(double) * steps * npairs);
    double *t_cold = malloc(sizeof(double) * steps * npairs);
    int nt = 0, checks = 0, failures = 0, hits = 0;
    double widest = 0.0, closest = INFINITY;
    const double goal[6] = {0.9, 1.2, -1.3, 0.8, 1.0, 1.5};
    printf("\n%-6s", "step");
    for (int k = 0; k < npairs; ++k) printf("  %d-%d   ", pa[k] + 1, pb[k] + 1);
    printf(" (exact distance, mm)\n");
    for (int s = 0; s < steps; ++s) {
        double q[6];
        for (int j = 0; j < 6; ++j) q[j] = goal[j] * sin(PI * s / (steps - 1));
        px_pose pose[NLINK];
        arm_poses(q, pose);
        int print = s % 20 == 0 || s == steps - 1;
        if (print) printf("%-6d", s);
        for (int k = 0; k < npairs; ++k) {
            px_model_distance_result r, h, c;
            double a = now();
            px_status st =
                px_model_distance(tri[pa[k]], &pose[pa[k]], tri[pb[k]], &pose[pb[k]], &tri_cache[k], &r);
            double b = now();
            st |= px_model_distance(hull[pa[k]], &pose[pa[k]], hull[pb[k]], &pose[pb[k]], &hull_cache[k], &h);
            double c0 = now();
            st |= px_model_distance(tri[pa[k]], &pose[pa[k]], tri[pb[k]], &pose[pb[k]], NULL, &c);
            double c1 = now();
            t_tri[nt] = b - a;
            t_hull[nt] = c0 - b;
            t_cold[nt++] = c1 - c0;
            px_model_collide_result col;
            st |= px_model_collide(tri[pa[k]], &pose[pa[k]], tri[pb[k]], &pose[pb[k]], &tri_cache[k], &col);
            checks += 4;
            int ok_status = st == PX_OK;
            int ok_bracket = h.distance <= r.distance + 1e-12 && r.distance <= h.upper_bound + 1e-12;
            /* Warm and cold may end on different leaf pairs realising the same
             * distance (a vertex shared by several triangles): equal to rounding. */
            int ok_warm = fabs(c.distance - r.distance) <= 8e-16 * (1.0 + r.distance);
            int ok_collide = col.hit == (r.distance == 0.0) || (col.contained && r.distance > 0.0) ||
                             (r.distance > 0.0 && r.distance < 1e-12);
            if (!ok_status || !ok_bracket || !ok_warm || !ok_collide) {
                ++failures;
                fprintf(stderr,
                        "model_demo: step %d links %d-%d: status %d, exact %.17g, bracket [%.17g, %.17g], "
                        "cold %.17g, "
                        "collide %d\n",
                        s, pa[k] + 1, pb[k] + 1, (int)st, r.distance, h.distance, h.upper_bound, c.distance,
                        col.hit);
            }
            hits += col.hit;
            widest = fmax(widest, h.upper_bound - h.distance);
            closest = fmin(closest, r.distance);
            if (print) printf("  %7.2f", 1000.0 * r.distance);
        }
        if (print) printf("\n");
        for (int i = 0; i < NLINK; ++i) {
            px_model_distance_result r;
            px_model_collide_result col;
            px_status st =
                px_model_distance_convex(tri[i], &pose[i], obstacle, &obstacle_pose, &box_cache[i], &r);
            st |= px_model_collide_convex(tri[i], &pose[i], obstacle, &obstacle_pose, NULL, &col);
            checks += 1;
            if (st != PX_OK && st != PX_ERR_DEGENERATE) ++failures;
            (void)r;
            (void)col;
        }
    }

    /* .pxm: save, load, same answers. */
    int pxm_ok = 1;
    for (int i = 0; i < NLINK && pxm_ok; ++i) {
        const char *path = "proxima_model_demo.pxm";
        px_error e;
        px_model *l = NULL;
        if (px_model_save(hull[i], path, &e) == PX_OK) l = px_model_load(path, NULL, &e);
        remove(path);
        if (!l) {
            fprintf(stderr, "model_demo: .pxm: %s\n", e.message);
            pxm_ok = 0;
            break;
        }
        px_pose id = px_pose_identity(), off = id;
        off.t = (px_vec3){0.3, 0.2, 0.1};
        px_model_distance_result r0, r1;
        px_model_distance(hull[i], &id, hull[(i + 1) % NLINK], &off, NULL, &r0);
        px_model_distance(l, &id, hull[(i + 1) % NLINK], &off, NULL, &r1);
        if (fabs(r0.distance - r1.distance) > 1e-14 ||
            r0.upper_bound - r0.distance != r1.upper_bound - r1.distance)
            pxm_ok = 0;
        px_model_destroy(l);
        checks += 1;
    }
    failures += !pxm_ok;

    printf("\n%d link pairs x %d poses: closest approach %.3f mm, %d poses in collision, widest bracket %.1f "
           "mm\n",
           npairs, steps, 1000.0 * closest, hits, 1000.0 * widest);
    double mt = median(t_tri, nt), mh = median(t_hull, nt), mc = median(t_cold, nt);
    printf("median time per query: exact tracked %.1f us, exact cold %.1f us, part hulls tracked %.2f us\n",
           1e6 * mt, 1e6 * mc, 1e6 * mh);
    size_t cache_tri = 0, cache_hull = 0;
    for (int k = 0; k < npairs; ++k)
        cache_tri += tri_cache[k].memory_bytes, cache_hull += hull_cache[k].memory_bytes;
    printf("cache memory after the path: %zu bytes for the exact trees' node pairs, %zu for the hulls'\n",
           cache_tri, cache_hull);
    printf("checks: %d (bracket, warm = cold, collide = distance, .pxm round trip), failures: %d\n", checks,
           failures);
    for (int k = 0; k < npairs; ++k) {
        px_model_cache_release(&tri_cache[k]);
        px_model_cache_release(&hull_cache[k]);
    }
    for (int i = 0; i < NLINK; ++i) {
        px_model_cache_release(&box_cache[i]);
        px_model_destroy(tri[i]);
        px_model_destroy(hull[i]);
    }
    px_convex_destroy(obstacle);
    free(t_tri);
    free(t_hull);
    free(t_cold);
    printf("%s\n", failures ? "model demo: FAILED" : "model demo: all checks passed");
    return failures ? 1 : 0;
}
