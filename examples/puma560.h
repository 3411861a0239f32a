/* The Puma 560 arm for the examples and tests (issue 11, section 3):
 * forward kinematics of the two shipped link-mesh sets, the standard DH
 * table, joint limits, one px_model per link and the arm's bodies in a
 * px_scene (adjacent links excluded, motion bounds from joint speeds).
 *
 * Not part of the library: examples/puma_cell.c and tests/test_puma.c
 * compile examples/puma560.c themselves. Public API only.
 *
 * Sources (models/puma560/SOURCE.md has the tables, commits and licences):
 * - nimasarli/puma560_description, urdf/puma560_robot.urdf @ 29d00ff4
 *   (table 1: joint origins and visual origins, meshes in inches);
 * - petercorke/robotics-toolbox-python, rtb-data/.../puma560_robot.urdf.xacro
 *   @ a9ed8d45 (table 2, COLLADA meshes in metres);
 * - the standard DH table of robotics-toolbox-python's
 *   models/DH/Puma560.py @ a9ed8d45 (Corke and Armstrong-Helouvry, ICRA
 *   1994) with its joint limits (Wang and Chen, IEEE T-RA 7(4), 1991).
 *
 * Frames. Link k (k = 0..6) is the URDF's link{k+1}: link 0 is the fixed
 * base (pedestal), link k >= 1 turns with joint k. World = link 0's frame,
 * z up, the base on the plane z = 0. A link's frame follows the URDF:
 * T_k = T_{k-1} . X_joint_k . R(axis_k, q_k), and its mesh sits at
 * T_k . X_visual_k (. the COLLADA fix, see puma560.c). */
#ifndef PROXIMA_EXAMPLES_PUMA560_H
#define PROXIMA_EXAMPLES_PUMA560_H

#include <stdint.h>

#include "proxima/proxima.h"

#define PUMA_JOINTS 6
#define PUMA_LINKS 7

/* The mesh sets (and their URDF chains). */
typedef enum puma_meshes {
    PUMA_NIMASARLI = 0,     /* puma_link1..7.stl (inches), URDF of table 1 */
    PUMA_RTB_VISUAL = 1,    /* puma560_link1..7.dae (metres), xacro of table 2 */
    PUMA_RTB_COLLISION = 2, /* puma560_collision1..6.dae (link 7 has none: the visual) */
    PUMA_MESH_SETS = 3
} puma_meshes;

/* Joint limits (rad; the DH table's, Wang and Chen 1991; the URDFs' are
 * placeholders) and speed limits (rad per unit of time: ours, for the
 * demo; no source in SOURCE.md gives the Puma's). Indexed by joint 0..5. */
extern const double puma_q_min[PUMA_JOINTS], puma_q_max[PUMA_JOINTS], puma_qd_max[PUMA_JOINTS];

/* Joint angles everywhere below are the DH table's (RTB-Python's
 * convention: qz = 0 is the "L" pose, qr = (0, pi/2, -pi/2, 0, 0, 0) the
 * vertical READY pose). The URDF chains turn joint j by
 * q_j + puma_urdf_offset[set][j] about their axes, in the DH sense
 * (nimasarli's forearm hangs down at its own q3 = 0: offsets pi). */
extern const double puma_urdf_offset[PUMA_MESH_SETS][PUMA_JOINTS];

/* Pose helpers (row-major rotation, px_pose convention). */
px_pose puma_compose(const px_pose *a, const px_pose *b);
px_pose puma_inverse(const px_pose *a);
/* URDF origin: translation xyz, then fixed-axis roll, pitch, yaw (R = Rz Ry Rx). */
px_pose puma_urdf_origin(double x, double y, double z, double roll, double pitch, double yaw);
/* Rotation by q (rad) about the unit axis a. */
px_pose puma_axis_rotation(px_vec3 a, double q);

/* Link frames T_k (k = 0..6) of the URDF chain of `set` at joint angles q. */
void puma_link_frames(puma_meshes set, const double q[PUMA_JOINTS], px_pose frame[PUMA_LINKS]);

/* World poses of the link meshes (the bodies) at joint angles q. */
void puma_link_poses(puma_meshes set, const double q[PUMA_JOINTS], px_pose pose[PUMA_LINKS]);

/* Standard DH forward kinematics: frame[0] = base (with d1 = 0.67183: the
 * pedestal, RTB-Python), frame[i] = A_1 ... A_i for i = 1..6, at DH joint
 * angles q. */
void puma_dh_frames(const double q[PUMA_JOINTS], px_pose frame[PUMA_LINKS]);

/* Motion bounds of each link body for joint speeds |qd_j| <= qd_max[j]
 * (NULL: puma_qd_max): `center` = the link frame's origin in the body
 * frame, `speed` bounds its linear speed, `angular` the body's angular
 * speed. Conservative for every configuration: joint j moves link k's
 * origin at most qd_j times its distance to joint j's axis, itself at most
 * the sum of the joint offsets between them; the angular speed is the sum
 * of the joint speeds. Link 0 never moves (0, 0). */
void puma_motion_bounds(puma_meshes set, const double *qd_max, px_vec3 center[PUMA_LINKS],
                        double speed[PUMA_LINKS], double angular[PUMA_LINKS]);

/* The arm's models. */
typedef struct puma_arm {
    puma_meshes set;
    px_model *link[PUMA_LINKS];
    px_mesh *mesh[PUMA_LINKS]; /* the loaded meshes (body frames), kept for drawing */
    uint32_t triangles[PUMA_LINKS];
} puma_arm;

/* How the link (and cell) models are built. PX_PIECES_APPROXIMATE takes
 * seconds per link: with a cache folder, each built model is saved there
 * as a .pxm (px_model_save) named after the body, the mesh set and the
 * tolerance, e.g. puma_nimasarli_link5_approx_tol0.02.pxm, and loaded
 * (px_model_load) instead of built when that file exists, is at least as
 * new as the mesh file and holds approximate pieces. px_model_load does
 * not re-certify the bounds h: a cache file edited by hand gives a wrong
 * bracket (never a wrong distance); delete the files to rebuild. */
typedef struct puma_build {
    uint32_t pieces;       /* px_pieces */
    double tolerance;      /* PX_PIECES_APPROXIMATE (0: PX_MODEL_DEFAULT_TOLERANCE) */
    uint32_t threads;      /* PX_PIECES_APPROXIMATE: px_model_options.threads */
    const char *cache_dir; /* PX_PIECES_APPROXIMATE: where the .pxm files are kept (NULL: none) */
    int verbose;           /* print a line per approximate model built or loaded */
    /* Filled in (added to) by the loaders: */
    int built, loaded;    /* approximate models built, and loaded from the cache */
    double build_seconds; /* wall time spent building them */
} puma_build;

/* Loads the seven link meshes of `set` from `models` (the folder holding
 * puma560/) and builds one model each (pieces: px_pieces). Returns PX_OK,
 * or an error naming the file (the arm is then empty). */
px_status puma_arm_load(puma_arm *arm, const char *models, puma_meshes set, uint32_t pieces, px_error *err);
/* The same, built as `build` says (approximate pieces, cached). */
px_status puma_arm_load_with(puma_arm *arm, const char *models, puma_meshes set, puma_build *build,
                             px_error *err);
void puma_arm_destroy(puma_arm *arm);

/* The arm as a px_chain (proxima/chain.h) of its seven link models (the
 * URDF chain of arm->set, with the DH table's joint angles, limits and
 * puma_urdf_offset): link 0 fixed to the world, links 1..6 turned by the
 * joints at speeds up to qd_max (NULL: puma_qd_max); group/mask as
 * px_body_desc. px_chain_add_to_scene puts it in a scene (link 0 static,
 * every adjacent pair (k, k+1) excluded, motion bounds from the joint
 * speeds; ids[k] = body of link k) and px_chain_set_joints moves it. The
 * chain points to arm->link[]: destroy it before the arm. */
px_chain *puma_chain_create(const puma_arm *arm, const double *qd_max, uint32_t group, uint32_t mask,
                            px_error *err);

/* ---- The work cell of the demo (examples/puma_cell.c) and its test ---- */

/* A table in front of the arm (top 0.42 m high), an L-shaped fixture on
 * it, the trimesh teapot on it (an obstacle the gripper touches once) and
 * a pillar beside the arm. World frame as above (metres). */
#define PUMA_CELL_BODIES 4
typedef struct puma_cell_body {
    const char *name;
    px_model *model;
    px_pose pose;
    px_mesh *mesh; /* for drawing (body frame) */
} puma_cell_body;

typedef struct puma_cell {
    puma_cell_body body[PUMA_CELL_BODIES];
} puma_cell;

/* Builds the cell; the teapot is moved so that it touches the arm of
 * `arm` at the trajectory's touching configuration (puma_trajectory at
 * puma_touch_time()). Returns PX_OK or an error. */
px_status puma_cell_build(puma_cell *cell, const char *models, const puma_arm *arm, px_error *err);
void puma_cell_destroy(puma_cell *cell);

/* The same cell with convex leaves only, for a scene whose arm has convex
 * leaves too (a triangle leaf met with a convex leaf costs a px_convex per
 * visited triangle): the boxes as point-set pieces (one exact convex piece
 * per box, h = 0), the teapot as approximate pieces built as `build` says
 * (pieces must be PX_PIECES_APPROXIMATE; cached as the links are), every
 * body at the pose of `exact` (itself placed with exact models). The
 * bodies' meshes are NULL: draw the exact cell. */
px_status puma_cell_build_coarse(puma_cell *cell, const char *models, const puma_cell *exact,
                                 puma_build *build, px_error *err);

/* Adds the cell's bodies to a scene, static; ids[i] = body of cell body i. */
px_status puma_cell_add(const puma_cell *cell, px_scene *scene, uint32_t group, uint32_t mask,
                        uint32_t ids[PUMA_CELL_BODIES], px_error *err);

/* The joint-space trajectory through the cell: waypoints joined by
 * cosine blends (zero speed at each waypoint), each segment as long as the
 * joint speed limits need (peak |qd_j| = 0.9 puma_qd_max[j]). Times in
 * seconds from 0 to puma_trajectory_duration(); q clamped to the ends. */
double puma_trajectory_duration(void);
void puma_trajectory(double t, double q[PUMA_JOINTS]);
/* The time of the waypoint at which the gripper touches the teapot. */
double puma_touch_time(void);

#endif /* PROXIMA_EXAMPLES_PUMA560_H */
