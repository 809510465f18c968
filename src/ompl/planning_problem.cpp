// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/ompl/planning_problem.h"

#include "hybridcd/ompl/continuous_motion_validator.h"

#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/base/objectives/MaximizeMinClearanceObjective.h>
#include <ompl/base/objectives/MechanicalWorkOptimizationObjective.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/base/samplers/BridgeTestValidStateSampler.h>
#include <ompl/base/samplers/GaussianValidStateSampler.h>
#include <ompl/base/samplers/MaximizeClearanceValidStateSampler.h>
#include <ompl/base/samplers/ObstacleBasedValidStateSampler.h>
#include <ompl/base/samplers/UniformValidStateSampler.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ob = ompl::base;

namespace hcd
{
ob::StateSpacePtr makeStateSpace(const LoadedProblem &problem)
{
    const ProblemConfig &cfg = problem.config;
    const int dims = cfg.planar ? 2 : 3;
    ob::RealVectorBounds bounds(dims);
    const std::optional<std::pair<double, double>> volume[3] = {cfg.volumeX, cfg.volumeY, cfg.volumeZ};
    const BoundingBox envBox = problem.world.mesh->bounds();
    for (int i = 0; i < dims; ++i)
    {
        if (volume[i])
        {
            bounds.low[i] = volume[i]->first;
            bounds.high[i] = volume[i]->second;
        }
        else if (!envBox.empty())
        {
            bounds.low[i] = envBox.min[i];
            bounds.high[i] = envBox.max[i];
        }
        else
        {
            bounds.low[i] = bounds.high[i] = 0.0;
        }
    }
    // Grow to contain start and goal, as OMPL.app's InferProblemDefinitionBounds does.
    for (const ConfigPose *p : {&cfg.start, &cfg.goal})
    {
        const double c[3] = {p->x, p->y, p->z};
        for (int i = 0; i < dims; ++i)
        {
            bounds.low[i] = std::min(bounds.low[i], c[i]);
            bounds.high[i] = std::max(bounds.high[i], c[i]);
        }
    }
    if (cfg.planar)
    {
        auto space = std::make_shared<ob::SE2StateSpace>();
        space->setBounds(bounds);
        return space;
    }
    auto space = std::make_shared<ob::SE3StateSpace>();
    space->setBounds(bounds);
    return space;
}

void configPoseToState(const ConfigPose &pose, bool planar, ob::State *state)
{
    if (planar)
    {
        auto *s = state->as<ob::SE2StateSpace::StateType>();
        s->setXY(pose.x, pose.y);
        s->setYaw(pose.theta);
        return;
    }
    auto *s = state->as<ob::SE3StateSpace::StateType>();
    s->setXYZ(pose.x, pose.y, pose.z);
    const RigidTransform r =
        RigidTransform::fromAxisAngle(Vec3::Zero(), Vec3(pose.axisX, pose.axisY, pose.axisZ), pose.theta);
    const Eigen::Quaterniond q(r.rotation);
    s->rotation().w = q.w();
    s->rotation().x = q.x();
    s->rotation().y = q.y();
    s->rotation().z = q.z();
}

std::shared_ptr<StateValidityChecker> installChecker(PlanningProblem &planning, const LoadedProblem &problem,
                                                     std::shared_ptr<const CollisionChecker> checker,
                                                     MotionCheck motion)
{
    const ob::SpaceInformationPtr &si = planning.setup->getSpaceInformation();
    planning.validity =
        std::make_shared<StateValidityChecker>(si, std::move(checker), problem.scene, problem.config.planar);
    si->setStateValidityChecker(planning.validity);
    // A checker that counts turns from the robot's z axis is sound for SE(2) motions alone.
    const bool turnsAboutRobotZ = planning.validity->checker().turnsAboutRobotZ();
    if (turnsAboutRobotZ && !problem.config.planar)
        throw std::invalid_argument("the checker's swept queries count turns about the robot's z axis "
                                    "(CollisionScene::turnsAboutRobotZ), which only a planar problem's motions keep");
    if (motion == MotionCheck::Continuous)
    {
        const BoundingBox box = problem.world.mesh->bounds();
        const double scale = box.empty() ? 1.0 : (box.max - box.min).norm();
        // The robot's reach as the checker counts it: from its z axis when the checker counts SE(2)
        // turns from there, from its origin otherwise.
        auto validator = std::make_shared<ContinuousMotionValidator>(
            si, planning.validity, robotTurnRadius(*problem.robot.mesh, turnsAboutRobotZ), scale);
        // Planners use the last valid state only to keep part of a blocked motion; bracketing the
        // contact to 1e-3 of the motion or one validity segment, whichever is coarser, keeps that
        // cheap (check-motion and the API default to 1e-6).
        validator->setContactTolerance(1e-3, true);
        validator->setTranslationContactFinder(std::make_shared<const TranslationContactFinder>(problem.scene));
        si->setMotionValidator(validator);
        planning.continuousValidator = std::move(validator);
    }
    else
    {
        si->setMotionValidator(std::make_shared<ob::DiscreteMotionValidator>(si));
        planning.continuousValidator.reset();
    }
    return planning.validity;
}

MotionCheck parseMotionCheck(const std::string &name)
{
    if (name == "continuous")
        return MotionCheck::Continuous;
    if (name == "discrete")
        return MotionCheck::Discrete;
    throw std::invalid_argument("unknown motion check '" + name + "'; expected continuous or discrete");
}

PlanningProblem makePlanningProblem(const LoadedProblem &problem, std::shared_ptr<const CollisionChecker> checker,
                                    MotionCheck motion)
{
    const ProblemConfig &cfg = problem.config;
    PlanningProblem out;
    out.planar = cfg.planar;
    out.setup = std::make_shared<ompl::geometric::SimpleSetup>(makeStateSpace(problem));
    const ob::SpaceInformationPtr &si = out.setup->getSpaceInformation();
    installChecker(out, problem, std::move(checker), motion);

    ob::ScopedState<> start(si->getStateSpace()), goal(si->getStateSpace());
    configPoseToState(cfg.start, cfg.planar, start.get());
    configPoseToState(cfg.goal, cfg.planar, goal.get());
    out.setup->setStartAndGoalStates(start, goal);

    if (!cfg.objective.empty())
    {
        ob::OptimizationObjectivePtr objective;
        if (cfg.objective == "length")
            objective = std::make_shared<ob::PathLengthOptimizationObjective>(si);
        else if (cfg.objective == "max min clearance")
            objective = std::make_shared<ob::MaximizeMinClearanceObjective>(si);
        else
            objective = std::make_shared<ob::MechanicalWorkOptimizationObjective>(si);
        if (cfg.objectiveThreshold)
            objective->setCostThreshold(ob::Cost(*cfg.objectiveThreshold));
        out.setup->setOptimizationObjective(objective);
    }

    const std::string sampler = cfg.sampler;
    if (!sampler.empty() && sampler != "uniform")
        si->setValidStateSamplerAllocator([sampler](const ob::SpaceInformation *s) -> ob::ValidStateSamplerPtr {
            if (sampler == "gaussian")
                return std::make_shared<ob::GaussianValidStateSampler>(s);
            if (sampler == "obstacle_based")
                return std::make_shared<ob::ObstacleBasedValidStateSampler>(s);
            if (sampler == "max_clearance")
                return std::make_shared<ob::MaximizeClearanceValidStateSampler>(s);
            return std::make_shared<ob::BridgeTestValidStateSampler>(s);
        });
    return out;
}
}  // namespace hcd
