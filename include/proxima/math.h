/// proxima/math.h: vectors and rigid poses.
///
/// Frames: every geometry object is described in its own local ("body")
/// frame. A `px_pose` maps body coordinates to world coordinates:
/// `p_world = R * p_body + t`.
#ifndef PROXIMA_MATH_H
#define PROXIMA_MATH_H

#include "proxima/base.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct px_vec3 {
    double x, y, z;
} px_vec3;

/// Rigid transform body -> world: `p_world = R * p_body + t`, with `r` the
/// rotation matrix in row-major order (r[3*i + j] = R_ij).
typedef struct px_pose {
    double r[9];
    px_vec3 t;
} px_pose;

/// The identity pose.
PX_API px_pose px_pose_identity(void);

/// Pose from a row-major 3x3 rotation `r` and a translation `t`, checked as
/// `px_pose_check` does. PX_ERR_INVALID_ARGUMENT when an argument is NULL;
/// otherwise the status of the check (*out is the identity on error).
PX_API px_status px_pose_from_rt(const double r[9], const double t[3], px_pose *out);

/// Pose from a quaternion (w, x, y, z) of any finite, non-zero length (it is
/// normalised without overflow or underflow, so 1e-300 and 1e300 times a
/// unit quaternion work) and a translation. PX_ERR_INVALID_ARGUMENT for a
/// NULL argument or a zero quaternion, PX_ERR_NON_FINITE for NaN or Inf
/// (*out is the identity on error).
PX_API px_status px_pose_from_quat(const double q[4], const double t[3], px_pose *out);

/// PX_OK when every entry is finite and R is a proper rotation within 1e-6
/// (rows 0 and 1 orthonormal, row 2 = row 0 x row 1); otherwise
/// PX_ERR_INVALID_ARGUMENT (NULL), PX_ERR_NON_FINITE or PX_ERR_INVALID_POSE,
/// with a message when `err` is not NULL.
PX_API px_status px_pose_check(const px_pose *pose, px_error *err);

/// World coordinates of a body-frame point (R p + t). A NULL pose is the
/// identity.
PX_API px_vec3 px_pose_apply(const px_pose *pose, px_vec3 p_body);

#ifdef __cplusplus
}
#endif

#endif /* PROXIMA_MATH_H */
