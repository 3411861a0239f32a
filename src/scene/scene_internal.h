/* What the scene layer's other files (chain.c) ask of a px_scene beyond
 * its public API (internal). */
#ifndef PXI_SCENE_INTERNAL_H
#define PXI_SCENE_INTERNAL_H

#include "proxima/scene.h"

/* 1 when `id` is a body of the scene that px_scene_set_pose accepts (alive
 * and not static), else 0. */
int pxi_scene_body_movable(const px_scene *scene, uint32_t id);

#endif
