// SPDX-License-Identifier: BSD-3-Clause
// A scene's bodies as triangle meshes in the world frame, for pictures (`hybridcd render`).
#pragma once

#include "hybridcd/geometry/triangle_mesh.h"
#include "hybridcd/scene/scene.h"

namespace hcd
{
/// The mesh of one body in its own frame: a mesh as it is; a primitive as the hull of points on
/// its surface, `resolution` per quarter turn (inside the shape, within
/// tessellationRelativeError(resolution) of its surface); a half-space as the part of it inside
/// `clip` (world frame; nothing when they do not meet), already in the world frame.
TriangleMesh bodyMesh(const SceneBody &body, const BoundingBox &clip, int resolution = 8);

/// Every static body, world frame, half-spaces cut to `clip`.
TriangleMesh staticBodiesMesh(const Scene &scene, const BoundingBox &clip, int resolution = 8);

/// Every robot body at the robots' poses (robotCount transforms), world frame.
TriangleMesh robotBodiesMesh(const Scene &scene, const RigidTransform *worldFromRobot, int resolution = 8);

/// A box that holds the scene's bounded static bodies and the robots at `poses` (each a list of
/// robotCount transforms), grown by 10% of its diagonal on every side: where half-spaces are cut.
BoundingBox sceneClipBox(const Scene &scene, const std::vector<std::vector<RigidTransform>> &poses);
}  // namespace hcd
