// SPDX-License-Identifier: BSD-3-Clause
// A problem file together with its loaded meshes: everything a checker and a planner need.
#pragma once

#include "hybridcd/geometry/collision_scene.h"
#include "hybridcd/io/mesh_loader.h"
#include "hybridcd/io/problem_config.h"

namespace hcd
{
/// Each mesh is stored once: `scene.robot` is `robot.mesh` and `scene.environment` is `world.mesh`.
struct LoadedProblem
{
    ProblemConfig config;
    LoadedMesh robot;
    LoadedMesh world;  ///< empty mesh when the problem names no world
    CollisionScene scene;
    /// Scene problems: the mesh of each extra robot and obstacle whose shape is a mesh or convex
    /// file, in the order of config.extraRobots and config.obstacles (an empty LoadedMesh for a
    /// primitive).
    std::vector<LoadedMesh> extraRobotMeshes;
    std::vector<LoadedMesh> obstacleMeshes;
};

/// Reads the .cfg and its meshes. Mesh errors are reported against the .cfg line that names the
/// mesh: "problem.cfg:3: world mesh: path/to/mesh.dae: cannot open mesh file ...".
/// `limits` bound each mesh (see MeshLimits).
LoadedProblem loadProblem(const std::string &cfgPath, const MeshLimits &limits = {});
}  // namespace hcd
