// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/bv/principal_axis.h"

#include <Eigen/Eigenvalues>

namespace hcd
{
Vec3 principalAxis(const std::vector<Vec3> &points)
{
    if (points.empty())
        return Vec3::UnitX();
    // One pass over the points: sums of the offsets from the first point and of their six distinct
    // products (the shift keeps the sums of squares from cancelling far from the origin). Large sets
    // (the top levels of a tree over a big mesh) are sampled at a regular stride: the axis only
    // guides a split, and the full pass made these levels the bulk of a tree's build.
    const std::size_t stride = principalAxisStride(points.size());
    const Vec3 shift = points.front();
    double sx = 0, sy = 0, sz = 0, sxx = 0, syy = 0, szz = 0, sxy = 0, sxz = 0, syz = 0;
    std::size_t count = 0;
    for (std::size_t i = 0; i < points.size(); i += stride, ++count)
    {
        const Vec3 &p = points[i];
        const double x = p.x() - shift.x(), y = p.y() - shift.y(), z = p.z() - shift.z();
        sx += x;
        sy += y;
        sz += z;
        sxx += x * x;
        syy += y * y;
        szz += z * z;
        sxy += x * y;
        sxz += x * z;
        syz += y * z;
    }
    const double inverse = 1.0 / double(count);
    const double mx = sx * inverse, my = sy * inverse, mz = sz * inverse;
    Mat3 covariance;
    covariance(0, 0) = sxx - sx * mx;
    covariance(1, 1) = syy - sy * my;
    covariance(2, 2) = szz - sz * mz;
    covariance(0, 1) = covariance(1, 0) = sxy - sx * my;
    covariance(0, 2) = covariance(2, 0) = sxz - sx * mz;
    covariance(1, 2) = covariance(2, 1) = syz - sy * mz;
    Eigen::SelfAdjointEigenSolver<Mat3> solver;
    solver.computeDirect(covariance);
    if (solver.info() != Eigen::Success || !solver.eigenvectors().allFinite())
        return Vec3::UnitX();
    const Vec3 axis = solver.eigenvectors().col(2);  // eigenvalues are sorted increasingly
    return axis.norm() > 0.5 ? Vec3(axis.normalized()) : Vec3::UnitX();
}
}  // namespace hcd
