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
    p.scene.robot = p.robot.mesh;
    p.scene.environment = p.world.mesh;
    p.scene.robotName = p.config.robotMesh;
    p.scene.environmentName = p.config.worldMesh;
    return p;
}
}  // namespace hcd
