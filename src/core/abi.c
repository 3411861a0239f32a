/* The public structs' sizes, fixed: a change here is an ABI change and must
 * come with a new major (or, before 1.0, minor) version. Checked when the
 * library is compiled; nothing in this file runs. */
#include "proxima/proxima.h"

_Static_assert(sizeof(px_vec3) == 24, "px_vec3");
_Static_assert(sizeof(px_pose) == 96, "px_pose");
_Static_assert(sizeof(px_error) == 260, "px_error");
_Static_assert(sizeof(px_allocator) == 3 * sizeof(void *), "px_allocator");
_Static_assert(sizeof(px_convex_options) == sizeof(void *) + 24, "px_convex_options");
_Static_assert(sizeof(px_bounds) == 80, "px_bounds");
_Static_assert(sizeof(px_feature) == 12, "px_feature");
_Static_assert(sizeof(px_pair_cache) == 88, "px_pair_cache");
_Static_assert(sizeof(px_query_options) == 32, "px_query_options");
_Static_assert(sizeof(px_diagnostics) == 16, "px_diagnostics");
_Static_assert(sizeof(px_distance_result) == 136, "px_distance_result");
_Static_assert(sizeof(px_intersect_result) == 24, "px_intersect_result");
_Static_assert(sizeof(px_translate_result) == 136, "px_translate_result");
_Static_assert(sizeof(px_mesh_node_desc) == sizeof(void *) + 8, "px_mesh_node_desc");
_Static_assert(sizeof(px_mesh_part_desc) == sizeof(void *) + 24, "px_mesh_part_desc");
_Static_assert(sizeof(px_mesh_options) == sizeof(void *) + 32, "px_mesh_options");
_Static_assert(sizeof(px_mesh_part) == sizeof(void *) + 24, "px_mesh_part");
_Static_assert(sizeof(px_mesh_node) == 2 * sizeof(void *), "px_mesh_node");
_Static_assert(sizeof(px_mesh_info) == 72, "px_mesh_info");
/* pointers, sizes and a double: fixed where pointers are 64-bit */
_Static_assert(sizeof(px_mesh_desc) == 88 || sizeof(void *) != 8, "px_mesh_desc");
_Static_assert(sizeof(px_model_options) == 56 || sizeof(void *) != 8, "px_model_options");
_Static_assert(sizeof(px_scene_options) == 64 || sizeof(void *) != 8, "px_scene_options");
_Static_assert(sizeof(px_body_desc) == 200 || sizeof(void *) != 8, "px_body_desc");
_Static_assert(sizeof(px_scene_pair) == 88, "px_scene_pair");
_Static_assert(sizeof(px_scene_event) == 16, "px_scene_event");
_Static_assert(sizeof(px_scene_stats) == 56 || sizeof(void *) != 8, "px_scene_stats");
_Static_assert(sizeof(px_link_desc) == 320 || sizeof(void *) != 8, "px_link_desc");
_Static_assert(sizeof(px_chain_desc) == 136 || sizeof(void *) != 8, "px_chain_desc");
