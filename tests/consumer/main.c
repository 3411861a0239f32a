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
    /* A two-link chain, as the README shows it: the second cube on a
     * prismatic joint 2 above the first, moved down to 1.5 (0.5 apart). */
    px_link_desc links[2] = {{0}};
    links[0].parent = PX_CHAIN_ROOT;
    links[0].joint = PX_JOINT_FIXED;
    links[0].origin = links[0].geometry = px_pose_identity();
    links[0].convex = c;
    links[1].parent = 0;
    links[1].joint = PX_JOINT_PRISMATIC;
    links[1].origin = links[1].geometry = px_pose_identity();
    links[1].origin.t.z = 2.0;
    links[1].axis = (px_vec3){0, 0, 1};
    links[1].q_min = -1.0, links[1].q_max = 1.0;
    links[1].max_speed = 1.0;
    links[1].convex = c;
    px_chain_desc cd = {0};
    cd.links = links;
    cd.n_links = 2;
    cd.base = px_pose_identity();
    cd.base.t.x = 10.0; /* away from the two cubes above */
    px_chain *robot = px_chain_create(&cd, &err);
    double q[1] = {0.0};
    uint32_t link_body[2];
    size_t nc = 0;
    if (robot && scene && px_chain_add_to_scene(robot, scene, q, link_body, &err) == PX_OK) {
        q[0] = -0.5;
        if (px_chain_set_joints(robot, scene, link_body, q, &err) == PX_OK &&
            px_scene_step(scene, 1.0, &err) == PX_OK) {
            const px_scene_pair *close = px_scene_pairs(scene, &nc);
            /* The chain's two links are adjacent: excluded. */
            if (nc != 1 || close[0].body_a != ia || close[0].body_b != ib) nc = 0;
        }
    }
    px_chain_destroy(robot);
    px_scene_destroy(scene);
    px_convex_destroy(c);
    if (nc != 1) {
        fprintf(stderr, "consumer: the chain in the scene went wrong (%s)\n", err.message);
        return 1;
    }
    if (n != 1) {
        fprintf(stderr, "consumer: the scene did not report the pair at distance 1 (%s)\n", err.message);
        return 1;
    }
    printf("consumer: proxima %s, distance %g, ok\n", px_version_string(), res.distance);
    return 0;
}
