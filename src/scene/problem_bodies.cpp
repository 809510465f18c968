// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/scene/problem_bodies.h"

#include "hybridcd/io/input_error.h"
#include "hybridcd/io/pose_codec.h"

#include <map>
#include <stdexcept>

namespace hcd
{
Shape shapeOfSpec(const ShapeSpec &spec, const std::shared_ptr<const TriangleMesh> &mesh, const std::string &cfgPath)
{
    try
    {
        if (spec.kind == "mesh" || spec.kind == "convex")
        {
            if (!mesh || mesh->triangles.empty())
                throw std::invalid_argument("the mesh file " + spec.file + " has no triangles");
            return spec.kind == "mesh" ? Shape::mesh(mesh) : Shape::convex(mesh->vertices);
        }
        return primitiveShapeOfSpec(spec);
    }
    catch (const std::exception &e)
    {
        throw InputError(cfgPath, spec.line, spec.kind + ": " + e.what());
    }
}

std::vector<RigidTransform> problemStart(const ProblemConfig &config)
{
    std::vector<RigidTransform> poses{transformOfConfigPose(config.start, config.planar)};
    for (const RobotSpec &robot : config.extraRobots)
        poses.push_back(transformOfConfigPose(robot.start, config.planar));
    return poses;
}

std::vector<RigidTransform> problemGoal(const ProblemConfig &config)
{
    std::vector<RigidTransform> poses{transformOfConfigPose(config.goal, config.planar)};
    for (const RobotSpec &robot : config.extraRobots)
        poses.push_back(transformOfConfigPose(robot.goal, config.planar));
    return poses;
}

std::shared_ptr<const Scene> makeProblemScene(const LoadedProblem &problem, const SceneOptions &options)
{
    const ProblemConfig &config = problem.config;
    std::vector<SceneBody> bodies;
    std::map<std::string, std::size_t> bodyOfLabel;
    auto add = [&](std::string label, Shape shape, int robot, const RigidTransform &pose) {
        bodyOfLabel[label] = bodies.size();
        bodies.push_back({std::move(label), std::make_shared<const BodyGeometry>(std::move(shape)), robot, pose});
    };
    add("robot", Shape::mesh(problem.robot.mesh), 0, RigidTransform());
    for (std::size_t k = 0; k < config.extraRobots.size(); ++k)
    {
        const RobotSpec &robot = config.extraRobots[k];
        add(robot.label, shapeOfSpec(robot.shape, problem.extraRobotMeshes[k].mesh, config.path), int(k + 1),
            RigidTransform());
    }
    if (!problem.world.mesh->triangles.empty())
        add("world", Shape::mesh(problem.world.mesh), -1, RigidTransform());
    for (std::size_t k = 0; k < config.obstacles.size(); ++k)
    {
        const ObstacleSpec &obstacle = config.obstacles[k];
        add(obstacle.label, shapeOfSpec(obstacle.shape, problem.obstacleMeshes[k].mesh, config.path), -1,
            transformOfConfigPose(obstacle.pose, config.planar));
    }
    std::vector<std::pair<std::size_t, std::size_t>> allowed;
    for (const auto &[a, b] : config.allowedCollisions)
    {
        const auto first = bodyOfLabel.find(a), second = bodyOfLabel.find(b);
        if (first == bodyOfLabel.end() || second == bodyOfLabel.end())
            throw InputError(config.path, config.allowedCollisionsLine,
                             "allowed_collisions names '" + (first == bodyOfLabel.end() ? a : b) +
                                 "', which is no body of this problem");
        allowed.emplace_back(first->second, second->second);
    }
    return std::make_shared<const Scene>(std::move(bodies), config.robotCount(), allowed, options);
}
}  // namespace hcd
