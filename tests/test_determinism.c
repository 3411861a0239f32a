/* Determinism (issue 3 §4): the same inputs give bit-identical outputs.
 * Builds a set of polytopes and runs a query sequence (cold, then warm along
 * a motion) twice, with different heap states in between (the second pass
 * allocates and scribbles over memory first, and builds the polytopes in
 * reverse order), and compares every output field bitwise. Prints a
 * checksum (FNV-1a over the outputs) so separate runs and builds can be
 * compared too. */
#include <stdint.h>

#include "check.h"
#include "math/vec3.h"
#include "px_gen.h"
#include "test_util.h"

#define NSHAPES 24
#define NQUERIES 3000

typedef struct out_rec {
    double d, pa[3], pb[3];
    uint32_t fa_t, fa_i, fb_t, fb_i, inter, it, fb;
} out_rec;

static uint64_t fnv(uint64_t h, const void *p, size_t n) {
    const unsigned char *b = p;
    for (size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 0x100000001b3ULL;
    return h;
}

/* Serialises a polytope's public view. */
static uint64_t hash_convex(const px_convex *c) {
    uint64_t h = 0xcbf29ce484222325ULL;
    uint32_t nv = px_convex_vertex_count(c), ne = px_convex_edge_count(c), nf = px_convex_face_count(c);
    h = fnv(h, &nv, 4), h = fnv(h, &ne, 4), h = fnv(h, &nf, 4);
    for (uint32_t i = 0; i < nv; ++i) {
        px_vec3 v = px_convex_vertex(c, i);
        h = fnv(h, &v, sizeof v);
    }
    for (uint32_t e = 0; e < ne; ++e) {
        uint32_t ab[2];
        px_convex_edge_vertices(c, e, ab);
        h = fnv(h, ab, sizeof ab);
    }
    for (uint32_t f = 0; f < nf; ++f) {
        px_vec3 n;
        double d;
        px_convex_face_plane(c, f, &n, &d);
        h = fnv(h, &n, sizeof n), h = fnv(h, &d, sizeof d);
        uint32_t k = px_convex_face_size(c, f);
        for (uint32_t j = 0; j < k; ++j) {
            uint32_t v = px_convex_face_vertex(c, f, j);
            h = fnv(h, &v, 4);
        }
    }
    return h;
}

static void run(int pass, out_rec *out, uint64_t *shape_hash) {
    pg_rng rng;
    pg_seed(&rng, 8080);
    static double xyz[NSHAPES][3 * 600];
    static size_t n[NSHAPES];
    for (int i = 0; i < NSHAPES; ++i)
        n[i] = pg_shape(&rng, (pg_kind)(i % PG_KIND_COUNT), 8 + 25 * i, 1.0, xyz[i]);
    px_convex *c[NSHAPES];
    for (int k = 0; k < NSHAPES; ++k) {
        int i = pass ? NSHAPES - 1 - k : k;
        c[i] = px_convex_from_points(xyz[i], n[i], NULL, NULL);
        CHECK(c[i] != NULL, "build %d", i);
        if (pass) { /* disturb the heap between builds */
            void *junk = malloc(1000 + 37 * (size_t)k);
            memset(junk, 0xa5 ^ k, 1000 + 37 * (size_t)k);
            free(junk);
        }
    }
    for (int i = 0; i < NSHAPES; ++i) shape_hash[i] = c[i] ? hash_convex(c[i]) : 0;
    px_distance_cache cache;
    memset(&cache, 0, sizeof cache);
    px_pose pa = pg_pose_random(&rng, 0), pb = pg_pose_random(&rng, 0);
    for (int q = 0; q < NQUERIES; ++q) {
        int ia = (int)pg_below(&rng, NSHAPES), ib = (int)pg_below(&rng, NSHAPES);
        if (q % 100 == 0) memset(&cache, 0, sizeof cache);
        if (q < NQUERIES / 2) { /* cold, random poses */
            pa = pg_pose_random(&rng, 1), pb = pg_pose_random(&rng, 1);
        } else { /* warm: one pair in motion */
            ia = 5, ib = 17;
            double r[9];
            pg_rot_axis_angle(pxi_v(0.6, 0.8, 0), 0.01, r);
            pg_mat_mul(r, pa.r, pa.r);
            pa.t = pxi_v(1.2 * cos(q * 0.01), 0.3, 0.2 * sin(q * 0.013));
        }
        px_distance_result res;
        memset(&res, 0, sizeof res);
        if (c[ia] && c[ib]) px_distance(c[ia], &pa, c[ib], &pb, q < NQUERIES / 2 ? NULL : &cache, &res);
        out_rec *o = &out[q];
        memset(o, 0, sizeof *o);
        o->d = res.distance;
        o->pa[0] = res.point_a.x, o->pa[1] = res.point_a.y, o->pa[2] = res.point_a.z;
        o->pb[0] = res.point_b.x, o->pb[1] = res.point_b.y, o->pb[2] = res.point_b.z;
        o->fa_t = res.feature_a.type, o->fa_i = res.feature_a.index;
        o->fb_t = res.feature_b.type, o->fb_i = res.feature_b.index;
        o->inter = (uint32_t)res.intersecting, o->it = res.iterations, o->fb = res.fallbacks;
    }
    for (int i = 0; i < NSHAPES; ++i) px_convex_destroy(c[i]);
}

int main(void) {
    tu_init("test_determinism");
    static out_rec r1[NQUERIES], r2[NQUERIES];
    uint64_t h1[NSHAPES], h2[NSHAPES];
    run(0, r1, h1);
    run(1, r2, h2);
    int diff_shapes = 0, diff_q = 0, first = -1;
    for (int i = 0; i < NSHAPES; ++i) diff_shapes += h1[i] != h2[i];
    for (int q = 0; q < NQUERIES; ++q)
        if (memcmp(&r1[q], &r2[q], sizeof r1[q]) != 0) {
            if (first < 0) first = q;
            diff_q++;
        }
    CHECK(diff_shapes == 0, "%d polytopes differ between two builds", diff_shapes);
    CHECK(diff_q == 0, "%d of %d query results differ (first #%d: d %.17g vs %.17g)", diff_q, NQUERIES, first,
          first >= 0 ? r1[first].d : 0.0, first >= 0 ? r2[first].d : 0.0);
    uint64_t h = fnv(0xcbf29ce484222325ULL, r1, sizeof r1);
    h = fnv(h, h1, sizeof h1);
    printf("  %d polytopes, %d queries twice: identical; output checksum %016llx\n", NSHAPES, NQUERIES,
           (unsigned long long)h);
    return tu_finish();
}
