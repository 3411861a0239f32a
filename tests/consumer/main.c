/* Smallest user of an installed proxima: two unit cubes 1 apart, the
 * version, and the header/library match. Links libproxima only. */
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
    px_convex_destroy(c);
    if (st != PX_OK || res.distance != 1.0) {
        fprintf(stderr, "consumer: expected distance 1, got %g (%s)\n", res.distance, px_status_string(st));
        return 1;
    }
    printf("consumer: proxima %s, distance %g, ok\n", px_version_string(), res.distance);
    return 0;
}
