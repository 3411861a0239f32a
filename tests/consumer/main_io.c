/* A user of an installed proxima who loads a mesh file and, when given one,
 * a URDF robot (links proxima-io). */
#include <proxima/proxima.h>
#include <stdio.h>

int main(int argc, char **argv) {
    if (argc != 2 && argc != 3) {
        fprintf(stderr, "usage: %s MESH_FILE [URDF_FILE]\n", argv[0]);
        return 2;
    }
    px_error err;
    px_convex *c = px_convex_create_from_file(argv[1], NULL, &err);
    if (!c) {
        fprintf(stderr, "consumer_io: %s\n", err.message);
        return 1;
    }
    px_bounds box;
    px_status st = px_convex_bounds(c, NULL, &box);
    printf("consumer_io: %u vertices, box (%g %g %g) .. (%g %g %g), %s\n", px_convex_vertex_count(c),
           box.min.x, box.min.y, box.min.z, box.max.x, box.max.y, box.max.z, px_status_string(st));
    px_convex_destroy(c);
    if (st == PX_OK && argc == 3) {
        px_urdf *robot = px_urdf_load(argv[2], NULL, &err);
        if (!robot) {
            fprintf(stderr, "consumer_io: %s\n", err.message);
            return 1;
        }
        const px_chain *arm = px_urdf_chain(robot);
        printf("consumer_io: robot of %u links and %u joints, the first '%s' moves link '%s'\n",
               px_chain_link_count(arm), px_chain_dof(arm), px_urdf_joint_name(robot, 0),
               px_urdf_link_name(robot, px_chain_joint_link(arm, 0)));
        px_urdf_destroy(robot);
    }
    return st == PX_OK ? 0 : 1;
}
