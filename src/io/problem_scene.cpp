// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/io/problem_scene.h"

#include "hybridcd/io/input_error.h"

namespace hcd
{
LoadedProblem loadProblem(const std::string &cfgPath, const MeshLimits &limits)
{
    LoadedProblem p;
    p.config = readProblemConfig(cfgPath);
    try
    {
        p.robot = loadMesh(p.config.robotMesh, p.config.planar ? MeshRole::RobotPlanar : MeshRole::Robot3D, limits);
    }
    catch (const InputError &e)
    {
        throw InputError(cfgPath, p.config.robotLine, std::string("robot mesh: ") + e.what());
    }
    if (!p.config.worldMesh.empty())
    {
        try
        {
            p.world = loadMesh(p.config.worldMesh, MeshRole::Environment, limits);
        }
        catch (const InputError &e)
        {
            throw InputError(cfgPath, p.config.worldLine, std::string("world mesh: ") + e.what());
        }
    }
    auto loadShapeMesh = [&](const ShapeSpec &shape, MeshRole role, const std::string &label) {
        if (shape.file.empty())
            return LoadedMesh{};
        try
        {
            return loadMesh(shape.file, role, limits);
        }
        catch (const InputError &e)
        {
            throw InputError(cfgPath, shape.line, label + " mesh: " + e.what());
        }
    };
    const MeshRole robotRole = p.config.planar ? MeshRole::RobotPlanar : MeshRole::Robot3D;
    for (const RobotSpec &robot : p.config.extraRobots)
        p.extraRobotMeshes.push_back(loadShapeMesh(robot.shape, robotRole, robot.label));
    for (const ObstacleSpec &obstacle : p.config.obstacles)
        p.obstacleMeshes.push_back(loadShapeMesh(obstacle.shape, MeshRole::Environment, obstacle.label));
    p.scene.robot = p.robot.mesh;
    p.scene.environment = p.world.mesh;
    p.scene.robotName = p.config.robotMesh;
    p.scene.environmentName = p.config.worldMesh;
    p.scene.planarPoses = p.config.planar;
    p.scene.turnsAboutRobotZ = p.config.planar;  // SE(2): yaw only
    return p;
}
}  // namespace hcd
