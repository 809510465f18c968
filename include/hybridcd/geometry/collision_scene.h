// SPDX-License-Identifier: BSD-3-Clause
// What a checker is built from: one rigid robot mesh and one static environment mesh.
#pragma once

#include "hybridcd/geometry/triangle_mesh.h"

#include <memory>
#include <string>

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
}  // namespace hcd
