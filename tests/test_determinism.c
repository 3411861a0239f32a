/* Determinism: the same inputs give bit-identical outputs, run to run and
 * build to build.
 *
 * 24 polytopes, then every query kind on them: the three distance methods,
 * unsigned and signed, cold on random poses and warm along a motion; the
 * collision translation forward and both ways, cold and warm;
 * px_intersect, cold and warm. Everything runs twice, with different heap
 * states in between (the second pass allocates and scribbles over memory
 * first, and builds the polytopes in reverse order), and every output field
 * is compared bitwise. Every status must be PX_OK, and the answers must be
 * mixed (some intersecting, some not; some hits, some misses), so that a run
 * where everything failed the same way cannot pass.
 *
 * Each kind's outputs are hashed (FNV-1a over the values: geometry apart
 * from the diagnostics), and the hashes are compared with the golden values
 * committed for this build type (argv[1]). A difference means a behaviour
 * change: if it is intended and documented, regenerate the file with
 * PROXIMA_UPDATE_GOLDEN=1 and commit it with the change. */
#include <stdint.h>

#include "access.h"
#include "math/vec3.h"
#include "px_gen.h"
#include "test_util.h"

#define NSHAPES 24
#define NQ 1000 /* per half (cold, warm) of each kind */

enum { K_DIST = 0, K_TRANSLATE = 6, K_INTERSECT = 8, K_COUNT = 9 };
static const char *const k_names[K_COUNT] = {"distance.lin-canny", "distance.gjk",        "distance.hybrid",
                                             "signed.lin-canny",   "signed.gjk",          "signed.hybrid",
                                             "translate.forward",  "translate.both-ways", "intersect"};

typedef struct hashes {
    uint64_t shapes, geom[K_COUNT], diag[K_COUNT];
    long queries, bad_status, yes[K_COUNT], no[K_COUNT];
} hashes;

static uint64_t fnv(uint64_t h, const void *p, size_t n) {
    const unsigned char *b = p;
    for (size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 0x100000001b3ULL;
    return h;
}
static uint64_t hd(uint64_t h, double d) { return fnv(h, &d, sizeof d); }
static uint64_t hv(uint64_t h, px_vec3 v) { return hd(hd(hd(h, v.x), v.y), v.z); }
static uint64_t hu(uint64_t h, uint32_t u) { return fnv(h, &u, sizeof u); }
static uint64_t hf(uint64_t h, px_feature f) { return hu(hu(hu(h, f.type), f.index), f.piece); }

/* Serialises a polytope's public view. */
static uint64_t hash_convex(uint64_t h, const px_convex *c) {
    uint32_t nv = px_convex_vertex_count(c), ne = px_convex_edge_count(c), nf = px_convex_face_count(c);
    h = hu(hu(hu(h, nv), ne), nf);
    for (uint32_t i = 0; i < nv; ++i) h = hv(h, ta_vertex(c, i));
    for (uint32_t e = 0; e < ne; ++e) {
        uint32_t ab[2];
        px_convex_edge(c, e, ab);
        h = hu(hu(h, ab[0]), ab[1]);
    }
    for (uint32_t f = 0; f < nf; ++f) {
        px_vec3 n;
        double d;
        uint32_t k;
        px_convex_face(c, f, &n, &d, &k);
        h = hd(hv(h, n), d);
        for (uint32_t j = 0; j < k; ++j) h = hu(h, ta_face_vertex(c, f, j));
    }
    return h;
}

/* The pose of A at step q of a kind: random (cold half) or along a motion
 * that passes through contact (warm half). */
static void poses(pg_rng *rng, int q, double reach, px_pose *pa, px_pose *pb) {
    if (q < NQ) {
        *pa = pg_pose_random(rng, reach);
        *pb = pg_pose_random(rng, reach);
        return;
    }
    double r[9];
    pg_rot_axis_angle(pxi_v(0.6, 0.8, 0), 0.01, r);
    pg_mat_mul(r, pa->r, pa->r);
    pg_rot_orthonormalize(pa->r);
    pa->t = pxi_v(1.2 * reach * cos(q * 0.01), 0.3, 0.2 * sin(q * 0.013));
}

static void check_status(hashes *h, px_status st) {
    h->queries++;
    if (st != PX_OK) h->bad_status++;
}

static void run(int pass, hashes *h) {
    memset(h, 0, sizeof *h);
    pg_rng rng;
    pg_seed(&rng, 8080);
    static double xyz[NSHAPES][3 * 600];
    static size_t n[NSHAPES];
    for (int i = 0; i < NSHAPES; ++i)
        n[i] = pg_shape(&rng, (pg_kind)(i % PG_KIND_COUNT), 8 + 25 * (size_t)i, 1.0, xyz[i]);
    px_convex *c[NSHAPES];
    for (int k = 0; k < NSHAPES; ++k) {
        int i = pass ? NSHAPES - 1 - k : k;
        c[i] = px_convex_create(xyz[i], n[i], NULL, NULL);
        CHECK(c[i] != NULL, "build %d", i);
        if (pass) { /* disturb the heap between builds */
            void *junk = malloc(1000 + 37 * (size_t)k);
            memset(junk, 0xa5 ^ k, 1000 + 37 * (size_t)k);
            free(junk);
        }
    }
    h->shapes = 0xcbf29ce484222325ULL;
    for (int i = 0; i < NSHAPES; ++i)
        if (c[i]) h->shapes = hash_convex(h->shapes, c[i]);
    for (int k = 0; k < K_COUNT; ++k) {
        uint64_t g = 0xcbf29ce484222325ULL, d = g;
        pg_seed(&rng, 77 + (uint64_t)k);
        px_pair_cache cache;
        memset(&cache, 0, sizeof cache);
        px_query_options opt;
        memset(&opt, 0, sizeof opt);
        if (k < K_TRANSLATE) opt.method = (uint32_t)(k % 3), opt.flags = k >= 3 ? PX_QUERY_SIGNED : 0;
        if (k == K_TRANSLATE + 1) opt.flags = PX_QUERY_BOTH_WAYS;
        double reach = k >= K_TRANSLATE && k < K_INTERSECT ? 2.0 : 1.0;
        px_pose pa = pg_pose_random(&rng, reach), pb = pg_pose_random(&rng, reach);
        for (int q = 0; q < 2 * NQ && c[0]; ++q) {
            int ia = (int)pg_below(&rng, NSHAPES), ib = (int)pg_below(&rng, NSHAPES);
            if (q >= NQ) ia = 5 + k, ib = 17 - k;
            poses(&rng, q, reach, &pa, &pb);
            px_pair_cache *cc = q < NQ ? NULL : &cache;
            px_diagnostics diag;
            int yes;
            if (k < K_TRANSLATE) {
                px_distance_result r;
                check_status(h, px_distance(c[ia], &pa, c[ib], &pb, &opt, cc, &r));
                g = hd(hd(g, r.distance), r.signed_distance);
                g = hv(hv(hv(g, r.point_a), r.point_b), r.normal);
                g = hu(hf(hf(g, r.feature_a), r.feature_b), (uint32_t)r.intersecting);
                diag = r.diag;
                yes = r.intersecting;
            } else if (k < K_INTERSECT) {
                px_vec3 dir = q < NQ ? pg_unit(&rng) : pxi_v(-pa.t.x, -pa.t.y + 0.1, -pa.t.z);
                px_translate_result r;
                check_status(h, px_translate(c[ia], &pa, c[ib], &pb, dir, &opt, cc, &r));
                g = hu(hu(hd(g, r.tau), (uint32_t)r.hit), (uint32_t)r.in_contact);
                g = hv(hv(hv(g, r.point_a), r.point_b), r.normal);
                g = hf(hf(hd(g, r.gap), r.feature_a), r.feature_b);
                diag = r.diag;
                yes = r.hit;
            } else {
                px_intersect_result r;
                check_status(h, px_intersect(c[ia], &pa, c[ib], &pb, NULL, cc, &r));
                g = hu(g, (uint32_t)r.intersecting);
                diag = r.diag;
                yes = r.intersecting;
            }
            d = hu(hu(hu(d, diag.iterations), diag.fallbacks), diag.quality);
            if (yes)
                h->yes[k]++;
            else
                h->no[k]++;
        }
        h->geom[k] = g;
        h->diag[k] = d;
    }
    for (int i = 0; i < NSHAPES; ++i) px_convex_destroy(c[i]);
}

/* Reads "name geom diag" lines; returns the number read. */
static int read_golden(const char *path, hashes *g, uint64_t *shapes) {
    FILE *f = fopen(path, "r");
    if (!f) return -1;
    char name[64];
    unsigned long long a, b;
    int got = 0;
    while (fscanf(f, "%63s %llx %llx", name, &a, &b) == 3) {
        if (strcmp(name, "shapes") == 0) *shapes = a, got++;
        for (int k = 0; k < K_COUNT; ++k)
            if (strcmp(name, k_names[k]) == 0) g->geom[k] = a, g->diag[k] = b, got++;
    }
    fclose(f);
    return got;
}

static void write_golden(const char *path, const hashes *h) {
    FILE *f = fopen(path, "w");
    CHECK(f != NULL, "cannot write %s", path);
    if (!f) return;
    fprintf(f, "shapes %016llx %016llx\n", (unsigned long long)h->shapes, 0ull);
    for (int k = 0; k < K_COUNT; ++k)
        fprintf(f, "%s %016llx %016llx\n", k_names[k], (unsigned long long)h->geom[k],
                (unsigned long long)h->diag[k]);
    fclose(f);
    printf("  wrote %s\n", path);
}

int main(int argc, char **argv) {
    tu_init("test_determinism");
    static hashes h1, h2;
    run(0, &h1);
    run(1, &h2);
    CHECK(h1.shapes == h2.shapes, "polytopes differ between two builds");
    for (int k = 0; k < K_COUNT; ++k) {
        CHECK(h1.geom[k] == h2.geom[k] && h1.diag[k] == h2.diag[k], "%s differs between two runs",
              k_names[k]);
        CHECK(h1.yes[k] > 20 && h1.no[k] > 20, "%s: %ld yes and %ld no answers, not a mixed workload",
              k_names[k], h1.yes[k], h1.no[k]);
    }
    CHECK(h1.bad_status == 0, "%ld of %ld queries returned an error", h1.bad_status, h1.queries);
    printf("  %d polytopes, %ld queries of %d kinds twice: identical, every status PX_OK\n", NSHAPES,
           h1.queries, K_COUNT);
    if (argc < 2) {
        printf("  (no golden file given: hashes not compared)\n");
        return tu_finish();
    }
    const char *update = getenv("PROXIMA_UPDATE_GOLDEN");
    if (update && *update == '1') {
        write_golden(argv[1], &h1);
        return tu_finish();
    }
    hashes g;
    memset(&g, 0, sizeof g);
    uint64_t shapes = 0;
    int got = read_golden(argv[1], &g, &shapes);
    CHECK(got == K_COUNT + 1, "golden file %s: %d of %d entries (regenerate with PROXIMA_UPDATE_GOLDEN=1)",
          argv[1], got, K_COUNT + 1);
    CHECK(shapes == h1.shapes, "polytopes differ from the golden hashes of %s", argv[1]);
    for (int k = 0; k < K_COUNT; ++k) {
        CHECK(g.geom[k] == h1.geom[k], "%s: answers %016llx, golden %016llx (a behaviour change?)",
              k_names[k], (unsigned long long)h1.geom[k], (unsigned long long)g.geom[k]);
        CHECK(g.diag[k] == h1.diag[k], "%s: diagnostics %016llx, golden %016llx", k_names[k],
              (unsigned long long)h1.diag[k], (unsigned long long)g.diag[k]);
    }
    printf("  hashes match %s\n", argv[1]);
    return tu_finish();
}
