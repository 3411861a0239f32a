/* Smallest user of an installed proxima: two unit cubes 1 apart, as a
 * query and in a scene, the version, and the header/library match. Links
 * libproxima only. */
#include <proxima/proxima.h>
#include <stdio.h>

int main(void) {
    if (px_version() != PX_VERSION) {
        fprintf(stderr, "consumer: headers %d, library %u\n", PX_VERSION, px_version());
        return 1;
    }
    double cube[24];
    for (int i = 0, k = 0; i < 8; ++i) {
        cube[k++] = (i & 1) ? 1 : 0;
        cube[k++] = (i & 2) ? 1 : 0;
        cube[k++] = (i & 4) ? 1 : 0;
    }
    px_error err;
    px_convex *c = px_convex_create(cube, 8, NULL, &err);
    if (!c) {
        fprintf(stderr, "consumer: %s\n", err.message);
        return 1;
    }
    double r[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, t[3] = {2, 0, 0};
    px_pose pa = px_pose_identity(), pb;
    px_status st = px_pose_from_rt(r, t, &pb);
    px_distance_result res;
    if (st == PX_OK) st = px_distance(c, &pa, c, &pb, NULL, NULL, &res);
    if (st != PX_OK || res.distance != 1.0) {
        fprintf(stderr, "consumer: expected distance 1, got %g (%s)\n", res.distance, px_status_string(st));
        px_convex_destroy(c);
        return 1;
    }
    /* The same pair in a scene, as the README shows it. */
    px_scene_options so = {0};
    so.margin = 0.01;
    so.report_distance = 1.5;
    px_scene *scene = px_scene_create(&so, &err);
    px_body_desc bd = {0};
    bd.convex = c;
    bd.pose = pa;
    bd.max_speed = 1.0;
    uint32_t ia = 0, ib = 0;
    size_t n = 0;
    if (scene && px_scene_add_body(scene, &bd, &ia, &err) == PX_OK) {
        bd.pose = pb;
        if (px_scene_add_body(scene, &bd, &ib, &err) == PX_OK && px_scene_step(scene, 0.0, &err) == PX_OK) {
            const px_scene_pair *close = px_scene_pairs(scene, &n);
            if (n != 1 || close[0].distance != 1.0 || close[0].contact) n = 0;
        }
    }
    px_scene_destroy(scene);
    px_convex_destroy(c);
    if (n != 1) {
        fprintf(stderr, "consumer: the scene did not report the pair at distance 1 (%s)\n", err.message);
        return 1;
    }
    printf("consumer: proxima %s, distance %g, ok\n", px_version_string(), res.distance);
    return 0;
}
