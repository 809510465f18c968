// SPDX-License-Identifier: BSD-3-Clause
// The scene of a problem file: its robots, world mesh and obstacles as bodies (scene/scene.h).
#pragma once

#include "hybridcd/io/problem_scene.h"
#include "hybridcd/scene/scene.h"

#include <memory>
#include <vector>

namespace hcd
{
/// The shape a .cfg names (ShapeSpec), with `mesh` the loaded mesh for "mesh" and "convex" specs.
/// Dimensions are converted from the file's (side lengths, full lengths) to the shape's (half
/// extents, half lengths). Throws InputError("FILE:LINE: ...") for a shape that cannot be built.
Shape shapeOfSpec(const ShapeSpec &spec, const std::shared_ptr<const TriangleMesh> &mesh, const std::string &cfgPath);

/// Every body of `problem`: robot 1 (robot mesh), robot.K, the world mesh as the static body
/// "world" (when given) and every obstacle.K at its pose; allowed pairs from allowed_collisions.
/// Works for problems of one robot without obstacles too (a scene of two bodies).
std::shared_ptr<const Scene> makeProblemScene(const LoadedProblem &problem, const SceneOptions &options = {});

/// The robots' start (or goal) poses of a problem, robot 1 first.
std::vector<RigidTransform> problemStart(const ProblemConfig &config);
std::vector<RigidTransform> problemGoal(const ProblemConfig &config);
}  // namespace hcd
