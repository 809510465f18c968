// SPDX-License-Identifier: BSD-3-Clause
// A planning problem as binary glTF 2.0 (.glb), for any glTF viewer: the environment, the robot,
// and the path as an animation of the robot.
//
// Layout: node 0 "scene" turns the problem's z-up world into glTF's y-up frame (-90 degrees about
// x) and holds the other nodes; node 1 "environment" (when there is one) and the "robot" node
// follow as its children. The robot node's translation and rotation are in the problem's world
// frame: at the first path state (the start without a path), and animated by one keyframe per
// path state (LINEAR, channels "translation" and "rotation") when a path is given. Vertices are
// single-precision floats, metres.
#pragma once

#include "hybridcd/geometry/triangle_mesh.h"

#include <string>
#include <vector>

namespace hcd::render
{
struct GltfRequest
{
    const TriangleMesh *environment = nullptr;  ///< world frame; may be null or empty (no node then)
    const TriangleMesh *robot = nullptr;        ///< robot frame; required
    RigidTransform start;                       ///< the robot node's pose without a path
    std::vector<RigidTransform> path;           ///< one keyframe per state; empty for no animation
    /// Seconds the animation lasts; keyframe times follow the distance travelled (at least a
    /// thousandth of the duration between states, since glTF needs increasing times).
    double durationSeconds = 10.0;
};

/// The .glb file's bytes. Throws std::invalid_argument without a robot, std::runtime_error when
/// serialisation fails.
std::string glbBytes(const GltfRequest &request);

/// Writes glbBytes(request) to `path` atomically; throws InputError naming it on failure.
void writeGlb(const GltfRequest &request, const std::string &path);
}  // namespace hcd::render
