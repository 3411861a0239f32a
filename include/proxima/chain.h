/// proxima/chain.h: articulated chains (robot arms and other mechanisms):
/// links joined by revolute, prismatic or fixed joints in a tree, their
/// forward kinematics, and their links as bodies of a px_scene.
///
/// A chain is described as a URDF describes a robot: each link names its
/// parent, the frame of its joint in the parent's link frame (`origin`),
/// the joint's axis in that frame, its limits and its speed limit, and
/// the frame of its geometry (a model or a polytope) in its own link frame.
/// The link frames at joint values q are
///
///     T_k = T_parent(k) * origin_k * J_k(q_k),
///
/// where J_k turns by q_k radians about the axis (revolute), moves by q_k
/// along it (prismatic) or is the identity (fixed), and the root links'
/// parent frame is the chain's `base` (where it is mounted, in the world).
/// Link k's geometry sits at T_k * geometry_k.
///
/// In a scene (px_chain_add_to_scene) each link with geometry becomes one
/// body. The chain:
/// - excludes the pairs of adjacent links, which touch by design: each link
///   with geometry and its nearest ancestor with geometry (its parent, or
///   the first link with geometry above the links without geometry between
///   them). Siblings and root links are never adjacent (docs/chain.md says
///   why this departs from MoveIt's rule);
/// - gives each body motion bounds from the joint speed limits, valid in
///   every configuration within the limits (docs/chain.md): link k's
///   frame origin moves at most sum_j |qd_j| * reach_jk (revolute joints j
///   between the base and k; reach_jk bounds the distance from joint j to
///   link k's origin: the joint offsets between them plus the travel of the
///   prismatic joints between them) + sum_j |qd_j| (prismatic), and the
///   link turns at most sum_j |qd_j| (revolute) (hpp-core's per-pair bound,
///   REFERENCES §4.4, taken per link);
/// - makes links that only fixed joints join to the base static bodies.
/// The scene's guarantee does not rest on these bounds (it measures how
/// far each body moved); they decide how often pairs are checked.
///
/// Joint values q are one per movable (revolute or prismatic) joint that
/// follows no other (mimic), in link order. A value outside its joint's
/// limits is refused (PX_ERR_RANGE), NaN or infinity too
/// (PX_ERR_NON_FINITE); a mimic joint's value is computed from them.
///
/// A chain is immutable once created and may be shared: one chain can be
/// added to several scenes, or several times to one scene (the caller keeps
/// each copy's body ids), and used from several threads at once (one scene
/// per thread); a chain of more than 32 links then needs a thread-safe
/// allocator (px_chain_forward and px_chain_set_joints take two scratch
/// arrays from it). The models and polytopes it points to are not copied
/// and must outlive it and the bodies made from it.
#ifndef PROXIMA_CHAIN_H
#define PROXIMA_CHAIN_H

#include "proxima/base.h"
#include "proxima/convex.h"
#include "proxima/math.h"
#include "proxima/model.h"
#include "proxima/scene.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct px_chain px_chain;

/// Parent of a root link: the chain's base frame.
#define PX_CHAIN_ROOT UINT32_MAX
/// At most this many links in a chain.
#define PX_CHAIN_MAX_LINKS 1024u
/// The body id of a link without geometry (px_chain_add_to_scene).
#define PX_CHAIN_NO_BODY UINT32_MAX

/// Joint types (px_link_desc.joint).
typedef enum px_joint_type {
    PX_JOINT_FIXED = 0,     ///< no motion; takes no joint value
    PX_JOINT_REVOLUTE = 1,  ///< turns by q radians about the axis (right-handed)
    PX_JOINT_PRISMATIC = 2, ///< moves by q world units along the axis
} px_joint_type;

/// One link and the joint that joins it to its parent.
typedef struct px_link_desc {
    /// Index of the parent link (smaller than this link's), or
    /// PX_CHAIN_ROOT: the chain's base.
    uint32_t parent;
    uint32_t joint; ///< px_joint_type
    /// The joint frame in the parent's link frame (URDF <joint><origin>).
    px_pose origin;
    /// The joint axis in the joint frame (URDF <axis>): finite and not zero
    /// for movable joints (it is normalised); ignored for fixed ones.
    px_vec3 axis;
    /// Joint limits (q_min <= q_max; -INFINITY and INFINITY allowed, e.g. a
    /// continuous joint) and speed limit (>= 0 per unit of the scene's
    /// time; INFINITY allowed: the link's pairs are then checked every
    /// step). Ignored for fixed joints.
    double q_min, q_max, max_speed;
    /// The link's geometry: a model, a polytope, or neither (a link without
    /// geometry: a frame only, no body).
    const px_model *model;
    const px_convex *convex;
    /// The geometry's frame in the link frame (URDF <collision><origin>);
    /// ignored (may be left zero) for a link without geometry.
    px_pose geometry;
    uint32_t group, mask; ///< the body's filters (px_body_desc); 0 and 0: all
    void *user;           ///< the body's user pointer (px_scene_body_user)
    /// A movable joint that follows another (URDF <mimic>): with `mimic`
    /// 1, its value is mimic_multiplier * q + mimic_offset, q the value of
    /// link `mimic_link`'s joint (any other link whose joint is movable and
    /// follows none), and it takes no joint value of its own. Its limits
    /// and speed limit are then ignored: it moves over the image of the
    /// followed joint's limits, at |mimic_multiplier| times its speed.
    /// 0: an independent joint (the other two fields ignored).
    uint32_t mimic, mimic_link;
    double mimic_multiplier, mimic_offset;
    uint32_t reserved[4]; ///< must be zero
} px_link_desc;

/// A chain.
typedef struct px_chain_desc {
    const px_link_desc *links;     ///< links[0 .. n_links-1], parents first
    uint32_t n_links;              ///< 1 .. PX_CHAIN_MAX_LINKS
    uint32_t reserved0;            ///< must be zero
    px_pose base;                  ///< the base frame in the world (where the chain is mounted)
    const px_allocator *allocator; ///< NULL: malloc/free
    uint32_t reserved[4];          ///< must be zero
} px_chain_desc;

/// A new chain, or NULL with the reason in `err` (may be NULL):
/// PX_ERR_INVALID_ARGUMENT for a NULL or empty description, more than
/// PX_CHAIN_MAX_LINKS links, a parent that is not an earlier link, an
/// unknown joint type, an axis that is zero, limits that are NaN, empty or
/// both infinite on one side, a negative or NaN speed limit, both a model
/// and a polytope, non-zero reserved fields, a mimic joint that is fixed
/// or follows a link that is not another link with a movable joint
/// following none; PX_ERR_NON_FINITE for an axis, a mimic multiplier or
/// offset with a NaN or infinity; the poses as px_pose_check (PX_ERR_NON_FINITE,
/// PX_ERR_INVALID_POSE); PX_ERR_RANGE for an origin or base translated
/// beyond 2^250 or a geometry frame beyond 2^249; PX_ERR_OUT_OF_MEMORY.
/// The message names the link.
PX_API px_chain *px_chain_create(const px_chain_desc *desc, px_error *err);

/// Frees the chain (not its models or polytopes); NULL is a no-op.
PX_API void px_chain_destroy(px_chain *chain);

/// The number of links, and of joint values (movable joints that follow
/// no other).
PX_API uint32_t px_chain_link_count(const px_chain *chain);
PX_API uint32_t px_chain_dof(const px_chain *chain);

/// The link of joint value i (0 .. dof-1), or PX_CHAIN_ROOT when i is out
/// of range.
PX_API uint32_t px_chain_joint_link(const px_chain *chain, uint32_t i);

/// Forward kinematics at joint values q (px_chain_dof of them; may be
/// NULL when there are none): the world frames of the links in
/// `frames[k]` and the world poses of their geometry in `geometry[k]` (a
/// link without geometry: its frame). Either may be NULL, and both may be
/// the same array (it then holds the geometry). PX_ERR_RANGE for a value
/// outside its limits, a mimic joint's value that is not finite, or a
/// frame beyond 2^250; PX_ERR_NON_FINITE for NaN
/// or infinite values; PX_ERR_INVALID_ARGUMENT for a NULL chain, or a NULL
/// q with joints; PX_ERR_OUT_OF_MEMORY (chains of more than 32 links take
/// scratch arrays from the chain's allocator when frames is NULL or
/// overlaps geometry).
PX_API px_status px_chain_forward(const px_chain *chain, const double *q, px_pose *frames, px_pose *geometry,
                                  px_error *err);

/// Motion bounds of link k's body (see above): `center` (its geometry
/// frame) moves at most `speed` and the body turns at most `angular_speed`
/// per unit of time while every joint keeps to its limits. Any output may
/// be NULL. PX_ERR_INVALID_ARGUMENT for an unknown link.
PX_API px_status px_chain_motion_bounds(const px_chain *chain, uint32_t link, px_vec3 *center, double *speed,
                                        double *angular_speed, px_error *err);

/// Whether the scene excludes the pair of links a and b (adjacent, as
/// above): 1 or 0; 0 for unknown links or a == b.
PX_API int px_chain_adjacent(const px_chain *chain, uint32_t a, uint32_t b);

/// Adds the chain's links with geometry to a scene at joint values q, with
/// their motion bounds and filters, and excludes the adjacent pairs.
/// ids[k] (px_chain_link_count entries) receives link k's body id, or
/// PX_CHAIN_NO_BODY for a link without geometry. On error no body is left
/// in the scene. Errors as px_chain_forward and px_scene_add_body.
PX_API px_status px_chain_add_to_scene(const px_chain *chain, px_scene *scene, const double *q, uint32_t *ids,
                                       px_error *err);

/// Sets the poses of the chain's moving bodies (those of
/// px_chain_add_to_scene, `ids` as it filled them) at joint values q, for
/// the next px_scene_step. Errors as px_chain_forward (chains of more than
/// 32 links take scratch arrays from the chain's allocator: PX_ERR_OUT_OF_MEMORY)
/// and px_scene_set_pose, PX_ERR_INVALID_ARGUMENT for an id that is not a
/// moving body of the scene; on error no pose is changed.
PX_API px_status px_chain_set_joints(const px_chain *chain, px_scene *scene, const uint32_t *ids,
                                     const double *q, px_error *err);

#ifdef __cplusplus
}
#endif

#endif /* PROXIMA_CHAIN_H */
