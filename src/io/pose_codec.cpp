// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/io/pose_codec.h"

#include <cmath>
#include <limits>
#include <sstream>

namespace hcd
{
namespace
{
// Within this of 1, a norm is 1 up to the rounding of a normalisation (a few ulps).
constexpr double kUnitByRounding = 8.0 * std::numeric_limits<double>::epsilon();

// The quaternion (qx qy qz qw) at row[3..6], scaled to unit norm unless it already is up to rounding.
Eigen::Quaterniond storedQuaternion(const double *row)
{
    const double *q = row + kQuaternionColumn;
    const Eigen::Quaterniond stored(q[3], q[0], q[1], q[2]);
    if (std::abs(stored.norm() - 1.0) <= kUnitByRounding)
        return stored;
    return rowQuaternion(row);
}
}  // namespace

Eigen::Quaterniond rowQuaternion(const double *row)
{
    const double *q = row + kQuaternionColumn;
    return RigidTransform::unitQuaternion(q[3], q[0], q[1], q[2]);
}

double wrapYaw(double yaw)
{
    // fmod is exact, and leaves a yaw in [-pi, pi) as it is.
    double wrapped = std::fmod(yaw, 2.0 * M_PI);
    if (wrapped < -M_PI)
        wrapped += 2.0 * M_PI;
    else if (wrapped >= M_PI)
        wrapped -= 2.0 * M_PI;
    return wrapped;
}

RigidTransform transformOfConfigPose(const ConfigPose &pose, bool planar)
{
    if (planar)
        return RigidTransform::fromPlanarPose(pose.x, pose.y, pose.theta);
    return RigidTransform::fromAxisAngle(Vec3(pose.x, pose.y, pose.z), Vec3(pose.axisX, pose.axisY, pose.axisZ),
                                         pose.theta);
}

RigidTransform transformOfRow(const double *row, bool planar)
{
    if (planar)
        return RigidTransform::fromPlanarPose(row[0], row[1], wrapYaw(row[2]));
    return {rowQuaternion(row).toRotationMatrix(), Vec3(row[0], row[1], row[2])};
}

PoseRow stateRowOf(const double *row, bool planar)
{
    PoseRow out{};
    if (planar)
    {
        out = {row[0], row[1], wrapYaw(row[2])};
        return out;
    }
    const Eigen::Quaterniond q = rowQuaternion(row);
    out = {row[0], row[1], row[2], q.x(), q.y(), q.z(), q.w()};
    return out;
}

RigidTransform transformOfStateRow(const double *row, bool planar)
{
    if (planar)
        return transformOfRow(row, true);
    return {storedQuaternion(row).toRotationMatrix(), Vec3(row[0], row[1], row[2])};
}

QuaternionCheck normaliseRowQuaternion(double *row)
{
    double *q = row + kQuaternionColumn;
    QuaternionCheck check;
    check.norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (check.norm == 0.0)
        check.verdict = QuaternionCheck::Verdict::Zero;
    else if (std::abs(check.norm - 1.0) > kQuaternionNormTolerance)
        check.verdict = QuaternionCheck::Verdict::NotUnit;
    // A quaternion already unit up to rounding is kept as it is: dividing by a norm that is 1 only
    // up to a few ulps would change its bits, so a path written by writePoses would not read back
    // bit for bit (found by fuzzing, tests/fuzz_corpus/path/regression_renormalised_quaternion.path).
    else if (std::abs(check.norm - 1.0) > kUnitByRounding)
        for (int k = 0; k < 4; ++k)
            q[k] /= check.norm;
    return check;
}

std::string quaternionProblem(const QuaternionCheck &check)
{
    switch (check.verdict)
    {
    case QuaternionCheck::Verdict::Unit:
        return {};
    case QuaternionCheck::Verdict::Zero:
        return "the quaternion (qx qy qz qw) is zero; a rotation needs a unit quaternion";
    case QuaternionCheck::Verdict::NotUnit:
        break;
    }
    std::ostringstream message;
    message << "the quaternion (qx qy qz qw) has norm " << check.norm << "; a unit quaternion is expected (within "
            << kQuaternionNormTolerance << ")";
    return message.str();
}
}  // namespace hcd
