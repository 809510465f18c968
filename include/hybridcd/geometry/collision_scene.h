// SPDX-License-Identifier: BSD-3-Clause
// What a checker is built from: one rigid robot mesh and one static environment mesh.
#pragma once

#include "hybridcd/geometry/triangle_mesh.h"

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

namespace hcd
{
/// The robot mesh is in the robot frame (its origin is the point a pose places); the environment
/// mesh is in the world frame. Both are immutable once shared, so checkers may alias them.
struct CollisionScene
{
    std::shared_ptr<const TriangleMesh> robot;
    std::shared_ptr<const TriangleMesh> environment;
    std::string robotName;
    std::string environmentName;
    /// The poses queried are mostly planar (OMPL's SE(2)): rotations about z and translations with
    /// z = 0. A hint for first layers that can use it (a footprint grid); every pose, planar or
    /// not, is still answered exactly.
    bool planarPoses = false;
    /// Every motion the swept queries (CollisionChecker::withinSweptDistance and the others) are
    /// asked about turns the robot about its own z axis only, as OMPL's SE(2) interpolation does:
    /// their radial slack then counts from that axis, a robot point p moving up to
    /// radialSlack * |(p.x, p.y)|, instead of from the origin (radialSlack * |p|). Unlike
    /// planarPoses, a promise, not a hint: a motion that tilts the robot breaks it. Tall robots
    /// gain most: a point high above the ground plane moves no farther for its height.
    bool turnsAboutRobotZ = false;
};

/// How far robot point p (robot frame) lies from what a scene's motions turn the robot about: its
/// z axis (CollisionScene::turnsAboutRobotZ) or its origin. A turn by an angle moves p at most
/// the angle times this.
inline double turnReach(const Vec3 &p, bool turnsAboutRobotZ)
{
    return turnsAboutRobotZ ? p.head<2>().norm() : p.norm();
}

/// The largest turnReach over the robot's vertices: radiusAboutZAxis() or radiusAboutOrigin().
inline double robotTurnRadius(const TriangleMesh &robot, bool turnsAboutRobotZ)
{
    return turnsAboutRobotZ ? robot.radiusAboutZAxis() : robot.radiusAboutOrigin();
}

/// Per robot triangle, the largest turnReach of its corners, grown by 1e-12 relative for rounding
/// (for swept proximity).
inline std::vector<double> triangleTurnReaches(const TriangleMesh &robot, bool turnsAboutRobotZ)
{
    std::vector<double> reaches;
    reaches.reserve(robot.triangleCount());
    for (std::size_t t = 0; t < robot.triangleCount(); ++t)
        reaches.push_back(
            std::max({turnReach(robot.corner(t, 0), turnsAboutRobotZ), turnReach(robot.corner(t, 1), turnsAboutRobotZ),
                      turnReach(robot.corner(t, 2), turnsAboutRobotZ)}) *
            (1.0 + 1e-12));
    return reaches;
}
}  // namespace hcd
