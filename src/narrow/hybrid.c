/* PLACEHOLDER: the seed 001 hybrid is being written; until then it runs GJK. */
#include "narrow/narrow.h"

void pxi_hybrid(const px_convex *a, const px_convex *b, const px_pose *t_ab, px_distance_cache *cache,
                pxi_answer *out) {
    pxi_gjk_distance(a, b, t_ab, cache, out, NULL);
}
