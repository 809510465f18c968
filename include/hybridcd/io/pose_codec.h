// SPDX-License-Identifier: BSD-3-Clause
// The pose codec: the one place a pose changes form. A pose row is the column layout of a .path
// file, x y theta in the plane and x y z qx qy qz qw in 3D (metres, radians, quaternion x y z w).
// Rows become world-from-robot transforms here, and here they take the form an OMPL state holds
// (yaw in [-pi, pi), unit quaternion); the OMPL adapters only copy fields to and from states.
#pragma once

#include "hybridcd/geometry/rigid_transform.h"
#include "hybridcd/io/problem_config.h"

#include <array>
#include <cstddef>
#include <string>

namespace hcd
{
/// Columns of a planar pose row: x y theta.
constexpr std::size_t kPlanarPoseColumns = 3;
/// Columns of a 3D pose row: x y z qx qy qz qw.
constexpr std::size_t kSpatialPoseColumns = 7;
/// Column of a 3D row where its quaternion (qx qy qz qw) starts.
constexpr std::size_t kQuaternionColumn = 3;

/// Number of leading columns a pose needs: 7 in 3D, 3 in the plane.
constexpr std::size_t poseColumns(bool planar) { return planar ? kPlanarPoseColumns : kSpatialPoseColumns; }

/// One pose row in fixed storage (no allocation, so it can be used per state check); a planar
/// row uses the first 3 entries.
using PoseRow = std::array<double, kSpatialPoseColumns>;

/// How far from 1 the norm of a row's quaternion may be when read from outside (a pose file, a
/// NumPy array): OMPL.app and hybridcd write unit quaternions with 17 significant digits, so
/// anything beyond this is a wrong input, not rounding. A zero quaternion is never accepted.
constexpr double kQuaternionNormTolerance = 1e-3;

/// The unit quaternion of a 3D row (`row` holds 7 numbers), as an OMPL state stores it: rescaled
/// first when the squares of its components over- or underflow, and the identity for the zero
/// quaternion (see RigidTransform::unitQuaternion). Non-finite components are left as they are.
Eigen::Quaterniond rowQuaternion(const double *row);

/// A yaw (radians) wrapped into SO2's [-pi, pi), as SO2StateSpace::enforceBounds does; a yaw
/// already in that range is returned unchanged, bit for bit.
double wrapYaw(double yaw);

/// The world-from-robot transform of a row (`row` holds poseColumns(planar) numbers). The
/// quaternion is normalised by rowQuaternion; the yaw is wrapped by wrapYaw.
RigidTransform transformOfRow(const double *row, bool planar);

/// The row as an OMPL state holds it: the yaw wrapped into [-pi, pi), the quaternion made unit by
/// rowQuaternion. transformOfStateRow of the result is bit for bit transformOfRow of `row`.
PoseRow stateRowOf(const double *row, bool planar);

/// The world-from-robot transform of a row read from an OMPL state. A quaternion that is unit up
/// to rounding (within 8 ulps, as stateRowOf writes and OMPL's samplers make) is used as it is:
/// normalising it again could change its bits and so the pose. Others go through rowQuaternion.
RigidTransform transformOfStateRow(const double *row, bool planar);

/// The world-from-robot transform of a .cfg's start or goal: (x, y, z) and `theta` radians about
/// the axis in 3D, (x, y) and yaw `theta` in the plane, as OMPL.app builds the state.
RigidTransform transformOfConfigPose(const ConfigPose &pose, bool planar);

/// What reading a quaternion from outside found (normaliseRowQuaternion).
struct QuaternionCheck
{
    enum class Verdict
    {
        Unit,     ///< accepted, and now of unit norm
        Zero,     ///< refused: the zero quaternion is no rotation
        NotUnit,  ///< refused: the norm differs from 1 by more than kQuaternionNormTolerance
    };
    Verdict verdict = Verdict::Unit;
    double norm = 1.0;  ///< the norm as read
};

/// Checks the quaternion of a 3D row read from outside (`row` holds 7 finite numbers) and, when
/// accepted, scales it to unit norm in place. A quaternion already unit up to rounding is kept as
/// it is, so that a row written with full precision reads back bit for bit.
QuaternionCheck normaliseRowQuaternion(double *row);

/// The reason a refused quaternion was refused, as pose files report it ("" when accepted).
std::string quaternionProblem(const QuaternionCheck &check);
}  // namespace hcd
