// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/geometry/rigid_transform.h"

#include <cmath>

namespace hcd
{
namespace
{
// The norm of `v`, rescaling `v` first (direction kept, largest component +-1) when the plain
// norm's squares over- or underflow: components beyond about 1e154 give infinity, below about
// 1e-154 zero or lost digits (subnormal ones round to the wrong length even with stableNorm).
template <typename Vector>
double rescaledNorm(Vector &&v)
{
    const double n = v.norm();
    if (n >= 1e-150 && n <= 1e150)
        return n;
    const double largest = v.cwiseAbs().maxCoeff();
    if (largest > 0.0 && std::isfinite(largest))
        v /= largest;
    return v.norm();
}
}  // namespace

RigidTransform RigidTransform::fromTranslationQuaternion(const Vec3 &t, double qw, double qx, double qy, double qz)
{
    return {unitQuaternion(qw, qx, qy, qz).toRotationMatrix(), t};
}

Eigen::Quaterniond RigidTransform::unitQuaternion(double qw, double qx, double qy, double qz)
{
    Eigen::Quaterniond q(qw, qx, qy, qz);
    const double n = rescaledNorm(q.coeffs());
    if (n > 0.0 && std::isfinite(n))
        q.coeffs() /= n;
    else if (n == 0.0)
        q.setIdentity();  // the same matrix as the zero quaternion gives, and a state OMPL accepts
    return q;
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
    Vec3 direction = axis;
    const double n = rescaledNorm(direction);
    if (!(n > 0.0))
        return {Mat3::Identity(), t};
    return {Eigen::AngleAxisd(angle, direction / n).toRotationMatrix(), t};
}
}  // namespace hcd
