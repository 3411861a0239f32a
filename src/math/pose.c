/* Pose constructors and validation. */
#include <math.h>
#include <string.h>

#include "core/core.h"
#include "math/vec3.h"

px_pose px_pose_identity(void) {
    px_pose p;
    memset(&p, 0, sizeof p);
    p.r[0] = p.r[4] = p.r[8] = 1.0;
    return p;
}

px_pose px_pose_from_rt(const double r[9], const double t[3]) {
    px_pose p = px_pose_identity();
    if (r) memcpy(p.r, r, sizeof p.r);
    if (t) p.t = pxi_v(t[0], t[1], t[2]);
    return p;
}

px_pose px_pose_from_quat(const double q[4], const double t[3]) {
    px_pose p = px_pose_identity();
    if (t) p.t = pxi_v(t[0], t[1], t[2]);
    if (!q) return p;
    double n = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (!(n > 0.0) || !isfinite(n)) {
        /* Leave a pose that px_pose_check rejects rather than inventing one. */
        for (int i = 0; i < 9; ++i) p.r[i] = NAN;
        return p;
    }
    double w = q[0] / n, x = q[1] / n, y = q[2] / n, z = q[3] / n;
    p.r[0] = 1 - 2 * (y * y + z * z);
    p.r[1] = 2 * (x * y - w * z);
    p.r[2] = 2 * (x * z + w * y);
    p.r[3] = 2 * (x * y + w * z);
    p.r[4] = 1 - 2 * (x * x + z * z);
    p.r[5] = 2 * (y * z - w * x);
    p.r[6] = 2 * (x * z - w * y);
    p.r[7] = 2 * (y * z + w * x);
    p.r[8] = 1 - 2 * (x * x + y * y);
    return p;
}

px_status px_pose_check(const px_pose *pose, px_error *err) {
    if (!pose) return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "pose is NULL");
    for (int i = 0; i < 9; ++i)
        if (!isfinite(pose->r[i]))
            return pxi_error(err, PX_ERR_NON_FINITE, "pose rotation entry r[%d] is not finite", i);
    if (!pxi_is_finite3(pose->t)) return pxi_error(err, PX_ERR_NON_FINITE, "pose translation is not finite");
    const double *r = pose->r;
    double worst = 0.0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            double s = r[i] * r[j] + r[3 + i] * r[3 + j] + r[6 + i] * r[6 + j];
            double dev = fabs(s - (i == j ? 1.0 : 0.0));
            if (dev > worst) worst = dev;
        }
    double det = r[0] * (r[4] * r[8] - r[5] * r[7]) - r[1] * (r[3] * r[8] - r[5] * r[6]) +
                 r[2] * (r[3] * r[7] - r[4] * r[6]);
    if (worst > 1e-6 || fabs(det - 1.0) > 1e-6)
        return pxi_error(err, PX_ERR_INVALID_POSE,
                         "pose rotation is not a rotation: |R^T R - I| = %.3g, det R = %.17g", worst, det);
    return PX_OK;
}

px_vec3 px_pose_apply(const px_pose *pose, px_vec3 p_body) {
    if (!pose) return p_body;
    return pxi_xform(pose, p_body);
}
