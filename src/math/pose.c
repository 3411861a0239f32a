/* Pose constructors and validation. The quaternion-to-matrix map is the
 * standard one (K. Shoemake, "Animating rotation with quaternion curves",
 * SIGGRAPH 1985). */
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

px_status px_pose_from_rt(const double r[9], const double t[3], px_pose *out) {
    if (!out) return PX_ERR_INVALID_ARGUMENT;
    *out = px_pose_identity();
    if (!r || !t) return PX_ERR_INVALID_ARGUMENT;
    px_pose p;
    memcpy(p.r, r, sizeof p.r);
    p.t = pxi_v(t[0], t[1], t[2]);
    px_status st = px_pose_check(&p, NULL);
    if (st == PX_OK) *out = p;
    return st;
}

px_status px_pose_from_quat(const double q[4], const double t[3], px_pose *out) {
    if (!out) return PX_ERR_INVALID_ARGUMENT;
    *out = px_pose_identity();
    if (!q || !t) return PX_ERR_INVALID_ARGUMENT;
    /* isfinite first: an ordered comparison with NaN raises FE_INVALID. */
    for (int i = 0; i < 4; ++i)
        if (!isfinite(q[i])) return PX_ERR_NON_FINITE;
    if (!isfinite(t[0]) || !isfinite(t[1]) || !isfinite(t[2])) return PX_ERR_NON_FINITE;
    double m = 0.0;
    for (int i = 0; i < 4; ++i)
        if (fabs(q[i]) > m) m = fabs(q[i]);
    if (!(m > 0.0)) return PX_ERR_INVALID_ARGUMENT;
    /* Divide by the largest component (a power of two, so exactly) before
     * squaring: |q| of 1e-300 or 1e300 neither underflows nor overflows. */
    int e = ilogb(m);
    double s[4];
    for (int i = 0; i < 4; ++i) s[i] = ldexp(q[i], -e); /* not q * 2^-e: 2^1031 overflows for subnormal q */
    double n = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2] + s[3] * s[3]);
    double w = s[0] / n, x = s[1] / n, y = s[2] / n, z = s[3] / n;
    px_pose p;
    p.t = pxi_v(t[0], t[1], t[2]);
    p.r[0] = 1 - 2 * (y * y + z * z);
    p.r[1] = 2 * (x * y - w * z);
    p.r[2] = 2 * (x * z + w * y);
    p.r[3] = 2 * (x * y + w * z);
    p.r[4] = 1 - 2 * (x * x + z * z);
    p.r[5] = 2 * (y * z - w * x);
    p.r[6] = 2 * (x * z - w * y);
    p.r[7] = 2 * (y * z + w * x);
    p.r[8] = 1 - 2 * (x * x + y * y);
    *out = p;
    return PX_OK;
}

px_status px_pose_check(const px_pose *pose, px_error *err) {
    pxi_error_clear(err);
    if (!pose) return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "pose is NULL");
    const double *r = pose->r;
    for (int i = 0; i < 9; ++i)
        if (!isfinite(r[i]))
            return pxi_error(err, PX_ERR_NON_FINITE, "pose rotation entry r[%d] is not finite", i);
    if (!isfinite(pose->t.x) || !isfinite(pose->t.y) || !isfinite(pose->t.z))
        return pxi_error(err, PX_ERR_NON_FINITE, "pose translation is not finite");
    /* Rows orthonormal and det +1 (row 2 = row 0 x row 1), within 1e-6. */
    double res[6];
    if (!pxi_rotation_residuals(r, res))
        return pxi_error(
            err, PX_ERR_INVALID_POSE,
            "pose rotation is not a proper rotation (rows not orthonormal or det != +1 within "
            "1e-6: |r0|^2-1 = %.3g, |r1|^2-1 = %.3g, r0.r1 = %.3g, r2 - r0 x r1 = (%.3g %.3g %.3g))",
            res[0], res[1], res[2], res[3], res[4], res[5]);
    return PX_OK;
}

px_vec3 px_pose_apply(const px_pose *pose, px_vec3 p_body) {
    if (!pose) return p_body;
    return pxi_xform(pose, p_body);
}
