// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/ompl/scene_planning.h"

#include "hybridcd/ompl/planning_problem.h"
#include "hybridcd/ompl/state_pose.h"
#include "hybridcd/scene/problem_bodies.h"

#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/base/ProjectionEvaluator.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace ob = ompl::base;

namespace hcd
{
namespace
{
// The default projection of a scene's compound space, for planners that grid a projection (KPIECE
// and its kin): robot 1's position, as OMPL's SE(2)/SE(3) spaces project one robot, with cells of
// a twentieth of the bounds.
class FirstRobotPosition : public ob::ProjectionEvaluator
{
public:
    FirstRobotPosition(const ob::StateSpace *space, bool planar, const ob::RealVectorBounds &bounds)
        : ob::ProjectionEvaluator(space),
          planar_(planar),
          bounds_(bounds)
    {
    }
    unsigned int getDimension() const override { return planar_ ? 2u : 3u; }
    void defaultCellSizes() override
    {
        cellSizes_.resize(getDimension());
        for (unsigned i = 0; i < getDimension(); ++i)
        {
            const double extent = bounds_.high[i] - bounds_.low[i];
            cellSizes_[i] = extent > 0.0 ? extent / 20.0 : 1.0;
        }
    }
    void project(const ob::State *state, Eigen::Ref<Eigen::VectorXd> projection) const override
    {
        const ob::State *first = (*state->as<ob::CompoundState>())[0];
        if (planar_)
        {
            const auto *s = first->as<ob::SE2StateSpace::StateType>();
            projection(0) = s->getX();
            projection(1) = s->getY();
            return;
        }
        const auto *s = first->as<ob::SE3StateSpace::StateType>();
        projection(0) = s->getX();
        projection(1) = s->getY();
        projection(2) = s->getZ();
    }

private:
    bool planar_;
    ob::RealVectorBounds bounds_;
};
}  // namespace

ob::StateSpacePtr makeSceneStateSpace(const LoadedProblem &problem, const Scene &scene)
{
    const ProblemConfig &cfg = problem.config;
    const int dims = cfg.planar ? 2 : 3;
    ob::RealVectorBounds bounds(dims);
    // The static bodies' finite extent (half-spaces left out).
    BoundingBox extent;
    for (std::size_t i = 0; i < scene.bodies().size(); ++i)
    {
        const SceneBody &body = scene.bodies()[i];
        if (body.robot >= 0)
            continue;
        const BoundingBox box = worldBounds(body.geometry->shape(), body.ownerFromBody);
        for (int a = 0; a < 3; ++a)
        {
            if (std::isfinite(box.min[a]))
                extent.min[a] = std::min(extent.min[a], box.min[a]);
            if (std::isfinite(box.max[a]))
                extent.max[a] = std::max(extent.max[a], box.max[a]);
        }
    }
    const std::optional<std::pair<double, double>> volume[3] = {cfg.volumeX, cfg.volumeY, cfg.volumeZ};
    for (int i = 0; i < dims; ++i)
    {
        if (volume[i])
        {
            bounds.low[i] = volume[i]->first;
            bounds.high[i] = volume[i]->second;
        }
        else if (extent.min[i] <= extent.max[i])
        {
            bounds.low[i] = extent.min[i];
            bounds.high[i] = extent.max[i];
        }
        else
        {
            bounds.low[i] = bounds.high[i] = 0.0;
        }
    }
    // Grow to contain every start and goal, as OMPL.app does for its one robot.
    std::vector<const ConfigPose *> poses = {&cfg.start, &cfg.goal};
    for (const RobotSpec &robot : cfg.extraRobots)
    {
        poses.push_back(&robot.start);
        poses.push_back(&robot.goal);
    }
    for (const ConfigPose *p : poses)
    {
        const double c[3] = {p->x, p->y, p->z};
        for (int i = 0; i < dims; ++i)
        {
            bounds.low[i] = std::min(bounds.low[i], c[i]);
            bounds.high[i] = std::max(bounds.high[i], c[i]);
        }
    }
    auto compound = std::make_shared<ob::CompoundStateSpace>();
    for (std::size_t r = 0; r < cfg.robotCount(); ++r)
    {
        ob::StateSpacePtr space;
        if (cfg.planar)
        {
            auto se2 = std::make_shared<ob::SE2StateSpace>();
            se2->setBounds(bounds);
            space = se2;
        }
        else
        {
            auto se3 = std::make_shared<ob::SE3StateSpace>();
            se3->setBounds(bounds);
            space = se3;
        }
        space->setName("robot" + std::to_string(r + 1));
        compound->addSubspace(space, 1.0);
    }
    compound->lock();
    compound->registerDefaultProjection(std::make_shared<FirstRobotPosition>(compound.get(), cfg.planar, bounds));
    return compound;
}

void scenePosesOfState(const ob::State *state, bool planar, std::size_t robots, std::vector<RigidTransform> &out)
{
    const auto *compound = state->as<ob::CompoundState>();
    out.resize(robots);
    for (std::size_t r = 0; r < robots; ++r)
        out[r] = poseOfState((*compound)[unsigned(r)], planar);
}

void sceneStateFromRows(const std::vector<double> &rows, bool planar, std::size_t robots, ob::State *state)
{
    auto *compound = state->as<ob::CompoundState>();
    const std::size_t columns = poseColumns(planar);
    for (std::size_t r = 0; r < robots; ++r)
        poseValuesToState(rows.data() + r * columns, planar, (*compound)[unsigned(r)]);
}

std::vector<double> sceneRowsOfState(const ob::State *state, bool planar, std::size_t robots)
{
    const auto *compound = state->as<ob::CompoundState>();
    std::vector<double> rows;
    for (std::size_t r = 0; r < robots; ++r)
    {
        const std::vector<double> row = stateToPoseValues((*compound)[unsigned(r)], planar);
        rows.insert(rows.end(), row.begin(), row.end());
    }
    return rows;
}

SceneValidityChecker::SceneValidityChecker(const ob::SpaceInformationPtr &si, std::shared_ptr<const Scene> scene,
                                           bool planar)
    : ob::StateValidityChecker(si),
      scene_(std::move(scene)),
      planar_(planar)
{
    specs_.clearanceComputationType = ob::StateValidityCheckerSpecs::EXACT;
}

bool SceneValidityChecker::isValid(const ob::State *state) const
{
    if (!si_->satisfiesBounds(state))
        return false;
    checks_.fetch_add(1, std::memory_order_relaxed);
    const auto start = std::chrono::steady_clock::now();
    auto context = contexts_.borrow();
    std::vector<RigidTransform> &poses = context->scratch<std::vector<RigidTransform>>();
    scenePosesOfState(state, planar_, scene_->robotCount(), poses);
    const bool valid = !scene_->collides(poses, *context);
    nanoseconds_.fetch_add(
        std::uint64_t(
            std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start).count()),
        std::memory_order_relaxed);
    return valid;
}

double SceneValidityChecker::clearance(const ob::State *state) const
{
    checks_.fetch_add(1, std::memory_order_relaxed);
    auto context = contexts_.borrow();
    std::vector<RigidTransform> &poses = context->scratch<std::vector<RigidTransform>>();
    scenePosesOfState(state, planar_, scene_->robotCount(), poses);
    return scene_->distance(poses.data(), *context);
}

SceneMotionValidator::SceneMotionValidator(const ob::SpaceInformationPtr &si,
                                           std::shared_ptr<const SceneValidityChecker> validity,
                                           SceneMotionOptions options)
    : ob::MotionValidator(si),
      validity_(std::move(validity)),
      options_(options)
{
}

SceneMotionResult SceneMotionValidator::check(const ob::State *s1, const ob::State *s2, bool verdictOnly) const
{
    const Scene &scene = validity_->scene();
    std::vector<RigidTransform> start, goal;
    scenePosesOfState(s1, validity_->planar(), scene.robotCount(), start);
    scenePosesOfState(s2, validity_->planar(), scene.robotCount(), goal);
    auto context = validity_->contexts().borrow();
    SceneMotionOptions options = options_;
    options.verdictOnly = verdictOnly;
    options.planar = validity_->planar();
    return checkSceneMotion(scene, start, goal, *context, options);
}

bool SceneMotionValidator::checkMotion(const ob::State *s1, const ob::State *s2) const
{
    // The bounds are a box in position (convex), so both ends inside keeps the whole motion inside.
    if (!si_->satisfiesBounds(s2))
    {
        invalidCount_.fetch_add(1, std::memory_order_relaxed);
        return false;
    }
    const bool valid = check(s1, s2, true).valid;
    (valid ? validCount_ : invalidCount_).fetch_add(1, std::memory_order_relaxed);
    return valid;
}

bool SceneMotionValidator::checkMotion(const ob::State *s1, const ob::State *s2,
                                       std::pair<ob::State *, double> &lastValid) const
{
    SceneMotionResult result;
    if (!si_->satisfiesBounds(s2))
    {
        // Where the motion leaves the bounds is not bracketed: keep the start only.
        result.valid = false;
        result.lastValidTime = 0.0;
    }
    else
        result = check(s1, s2);
    if (!result.valid)
    {
        if (lastValid.first)
            si_->getStateSpace()->interpolate(s1, s2, result.lastValidTime, lastValid.first);
        lastValid.second = result.lastValidTime;
        invalidCount_.fetch_add(1, std::memory_order_relaxed);
        return false;
    }
    validCount_.fetch_add(1, std::memory_order_relaxed);
    return true;
}

ScenePlanningProblem makeScenePlanningProblem(const LoadedProblem &problem, std::shared_ptr<const Scene> scene,
                                              bool continuous)
{
    const ProblemConfig &cfg = problem.config;
    ScenePlanningProblem out;
    out.planar = cfg.planar;
    out.scene = scene;
    out.setup = std::make_shared<ompl::geometric::SimpleSetup>(makeSceneStateSpace(problem, *scene));
    const ob::SpaceInformationPtr &si = out.setup->getSpaceInformation();
    out.validity = std::make_shared<SceneValidityChecker>(si, scene, cfg.planar);
    si->setStateValidityChecker(out.validity);
    if (continuous)
    {
        out.motion = std::make_shared<SceneMotionValidator>(si, out.validity);
        si->setMotionValidator(out.motion);
    }
    else
        si->setMotionValidator(std::make_shared<ob::DiscreteMotionValidator>(si));

    ob::ScopedState<> start(si->getStateSpace()), goal(si->getStateSpace());
    auto *startState = start.get()->as<ob::CompoundState>();
    auto *goalState = goal.get()->as<ob::CompoundState>();
    configPoseToState(cfg.start, cfg.planar, (*startState)[0]);
    configPoseToState(cfg.goal, cfg.planar, (*goalState)[0]);
    for (std::size_t k = 0; k < cfg.extraRobots.size(); ++k)
    {
        configPoseToState(cfg.extraRobots[k].start, cfg.planar, (*startState)[unsigned(k + 1)]);
        configPoseToState(cfg.extraRobots[k].goal, cfg.planar, (*goalState)[unsigned(k + 1)]);
    }
    out.setup->setStartAndGoalStates(start, goal);
    if (cfg.objective == "length")
        out.setup->setOptimizationObjective(std::make_shared<ob::PathLengthOptimizationObjective>(si));
    return out;
}
}  // namespace hcd
