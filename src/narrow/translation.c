/* PLACEHOLDER */
#include <string.h>

#include "narrow/narrow.h"

void pxi_translation_query(const px_convex *a, const px_convex *b, const px_pose *t_ab, px_vec3 dir,
                           px_distance_cache *cache, pxi_translation *out) {
    (void)a, (void)b, (void)t_ab, (void)dir, (void)cache;
    memset(out, 0, sizeof *out);
}
