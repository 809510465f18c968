// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/bv/principal_axis.h"

#include <Eigen/Eigenvalues>

namespace hcd
{
Vec3 principalAxis(const std::vector<Vec3> &points)
{
    if (points.empty())
        return Vec3::UnitX();
    Vec3 mean = Vec3::Zero();
    for (const Vec3 &p : points)
        mean += p;
    mean /= double(points.size());
    Mat3 covariance = Mat3::Zero();
    for (const Vec3 &p : points)
        covariance += (p - mean) * (p - mean).transpose();
    Eigen::SelfAdjointEigenSolver<Mat3> solver(covariance);
    if (solver.info() != Eigen::Success || !solver.eigenvectors().allFinite())
        return Vec3::UnitX();
    const Vec3 axis = solver.eigenvectors().col(2);  // eigenvalues are sorted increasingly
    return axis.norm() > 0.5 ? Vec3(axis.normalized()) : Vec3::UnitX();
}
}  // namespace hcd
