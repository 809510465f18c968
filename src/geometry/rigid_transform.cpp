// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/geometry/rigid_transform.h"

#include <cmath>

namespace hcd
{
namespace
{
// A plain norm is exact enough here; outside this range its squares have over- or underflowed
// (components beyond about 1e154 give infinity, below about 1e-154 zero or lost digits), and the
// slower rescaling stableNorm() is used instead.
bool inSafeRange(double norm) { return norm >= 1e-150 && norm <= 1e150; }
}  // namespace

RigidTransform RigidTransform::fromTranslationQuaternion(const Vec3 &t, double qw, double qx, double qy, double qz)
{
    Eigen::Quaterniond q(qw, qx, qy, qz);
    double n = q.norm();
    if (!inSafeRange(n))
        n = q.coeffs().stableNorm();
    if (n > 0.0 && std::isfinite(n))
        q.coeffs() /= n;
    return {q.toRotationMatrix(), t};
}

RigidTransform RigidTransform::fromPlanarPose(double x, double y, double yaw)
{
    const double c = std::cos(yaw), s = std::sin(yaw);
    Mat3 r;
    r << c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0;
    return {r, Vec3(x, y, 0.0)};
}

RigidTransform RigidTransform::fromAxisAngle(const Vec3 &t, const Vec3 &axis, double angle)
{
    double n = axis.norm();
    if (!inSafeRange(n))
        n = axis.stableNorm();
    if (!(n > 0.0))
        return {Mat3::Identity(), t};
    return {Eigen::AngleAxisd(angle, axis / n).toRotationMatrix(), t};
}
}  // namespace hcd
