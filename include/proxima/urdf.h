/// proxima/urdf.h: robots from URDF files, as articulated chains (link
/// proxima-io; docs/chain.md, "From a URDF file").
///
/// px_urdf_load reads a URDF file (the ROS robot description: links and
/// the joints between them) and builds a px_chain (proxima/chain.h) whose
/// links carry models of their <collision> geometry: meshes (any format
/// px_mesh_load reads, with the element's scale), boxes, and cylinders and
/// spheres as convex polyhedra that contain them (a cylinder as a
/// circumscribed 32-sided prism of 124 triangles, a sphere as a
/// circumscribed polyhedron of 320 triangles: distances to them are lower
/// bounds of the true shapes', at most 0.49 % and 1.81 % of the radius
/// below). A link's collision elements
/// are the parts of its model, placed by their <origin>. <visual>
/// elements are not read.
///
/// Joints: fixed, revolute (with its <limit lower upper velocity>),
/// continuous (a revolute joint without position limits), prismatic; the
/// joint values are those of px_chain_dof, one per movable joint, in the
/// order of the chain's links, which is the file's tree walked depth
/// first from the root, children in the order of their joints in the file
/// (px_urdf_joint_name names each value). A missing velocity limit is
/// infinite (the link's pairs are then checked at every step). A <mimic
/// joint multiplier offset> joint follows the joint it names and takes
/// no value (px_link_desc.mimic: its own <limit> is ignored; it may not
/// follow another mimic). Floating and planar joints are refused.
///
/// Mesh file names: `package://NAME/rest` is looked up as DIR/NAME/rest
/// for each folder DIR of options.package_path, then of the folders that
/// hold the URDF file and each of their parents; `file://` and plain paths
/// are taken as they are, relative ones against the URDF file's folder.
///
/// What a file cannot do: the file is read whole by the library (a
/// regular file of at most 64 MiB; never decompressed, never a FIFO or
/// the standard input) and parsed without network access; a document
/// type declaration (<!DOCTYPE>) is refused, so no entity can be declared
/// or expanded; a namespace error is refused, and elements in a prefixed
/// namespace (<xacro:...>) are skipped as ROS's parser skips them (xacro
/// files must be expanded first). Before libxml2 reads the bytes, a pass
/// over them refuses an element with more than 64 attributes (libxml2
/// 2.9 compares an element's attributes pair by pair) and more than
/// 1,000,000 elements, attributes, comments and processing instructions
/// in all (real robots have a few thousand): at that limit a load peaks
/// at 500 to 800 MB (a 64 MiB file; 64 MiB of "<a/> " took 3.4 GB
/// before); also more than 128 namespace declarations (xmlns) in all and
/// elements nested more than 128 deep. The bytes must be UTF-8, ASCII,
/// ISO-8859-n or windows-125n as declared (a NUL byte, as in UTF-16,
/// EBCDIC and other encodings are refused, and so is a byte the declared
/// encoding does not define).
/// libxml2 stops at its first error; its warnings (XML 1.1, a
/// namespace URI that is not absolute) refuse nothing, as ROS reads those
/// files. A robot has at most 1,024 links and 2,000,000 collision
/// triangles in all. Numbers are decimal (no hexadecimal) and read in the
/// C locale whatever the caller's. libxml2 prints nothing. The caller's
/// floating-point environment is held for the load (traps included: an
/// overflowing number or size is refused, never trapped; numbers rounded
/// to nearest whatever the caller's rounding mode) and restored.
#ifndef PROXIMA_URDF_H
#define PROXIMA_URDF_H

#include "proxima/base.h"
#include "proxima/chain.h"
#include "proxima/math.h"
#include "proxima/model.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct px_urdf px_urdf;

/// Options; zero-initialise, zero = default.
typedef struct px_urdf_options {
    const px_allocator *allocator; ///< everything the robot owns (NULL: malloc/free)
    /// Where the root link stands in the world (the chain's base; NULL:
    /// the identity).
    const px_pose *base;
    /// Folders searched first for package://NAME/..., ':'-separated
    /// (NULL: only those above the URDF file).
    const char *package_path;
    /// How each link's model is built: PX_PIECES_TRIANGLES (exact; 0 is
    /// the same, the default) or PX_PIECES_APPROXIMATE, with `threads`
    /// and `tolerance` as px_model_options has them (both 0 with
    /// TRIANGLES). PX_PIECES_PARTS is not offered (its value, 0, means
    /// the default here); other values are PX_ERR_INVALID_ARGUMENT.
    uint32_t pieces, threads;
    double tolerance;
    /// Every link body's filters (px_body_desc.group, mask; 0 and 0: all).
    uint32_t group, mask;
    uint32_t reserved[4]; ///< must be zero
} px_urdf_options;

/// Reads the robot. Returns NULL and fills `err` (may be NULL) on:
/// PX_ERR_INVALID_ARGUMENT (NULL or empty path; bad options, checked
/// before the file is read and named in the message: reserved not zero,
/// pieces, threads or tolerance as above, a base that fails
/// px_pose_check or is translated beyond 2^250);
/// PX_ERR_IO: the file cannot be read, is not well-formed XML, has no
/// <robot> root, a link or joint without a name or with a name used twice,
/// a joint whose parent or child is not a link, a link with two parent
/// joints, no root link or two, a cycle, an unsupported joint type, a
/// revolute or prismatic joint without <limit>, a number that does not
/// parse or is not finite, a geometry with a negative or zero size, a mesh
/// file that cannot be found or loaded (px_mesh_load's message quoted),
/// a limit above exceeded, a document type declaration; the message names
/// the file and the link or joint, or the line for XML errors;
/// PX_ERR_RANGE for a box size, radius or length above 2^249, a
/// <collision> origin or a scaled mesh beyond 2^250 (the models' range),
/// naming the link and the quantity;
/// and the statuses of px_model_create_from_mesh and px_chain_create
/// (naming the link); PX_ERR_OUT_OF_MEMORY.
PX_API px_urdf *px_urdf_load(const char *path, const px_urdf_options *options, px_error *err);

/// Frees the robot: its chain and its models (after the scenes that hold
/// its bodies). NULL is a no-op.
PX_API void px_urdf_destroy(px_urdf *robot);

/// The robot's chain (owned by the robot), for px_chain_add_to_scene,
/// px_chain_set_joints and px_chain_forward.
PX_API const px_chain *px_urdf_chain(const px_urdf *robot);

/// Link k's name as in the file; NULL for k out of range.
PX_API const char *px_urdf_link_name(const px_urdf *robot, uint32_t link);

/// The name of the joint of joint value i (0 .. px_chain_dof - 1); NULL
/// for i out of range.
PX_API const char *px_urdf_joint_name(const px_urdf *robot, uint32_t i);

/// The link named `name`, or PX_CHAIN_ROOT.
PX_API uint32_t px_urdf_find_link(const px_urdf *robot, const char *name);

/// Link k's model (its collision geometry in its link frame), or NULL for a
/// link without collision geometry or k out of range.
PX_API const px_model *px_urdf_link_model(const px_urdf *robot, uint32_t link);

#ifdef __cplusplus
}
#endif

#endif /* PROXIMA_URDF_H */
