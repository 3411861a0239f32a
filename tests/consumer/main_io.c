/* A user of an installed proxima who loads a mesh file (links proxima-io). */
#include <proxima/proxima.h>
#include <stdio.h>

int main(int argc, char **argv) {
    if (argc != 2) {
        fprintf(stderr, "usage: %s MESH_FILE\n", argv[0]);
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
    return st == PX_OK ? 0 : 1;
}
