// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/ompl/control_problem.h"

#include <ompl/base/ProjectionEvaluator.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>

#include <cmath>
#include <stdexcept>

namespace ob = ompl::base;
namespace oc = ompl::control;

namespace hcd
{
namespace
{
// Projects a state on its position, as OMPL.app's GeometricStateProjector2D/3D do.
class PositionProjection : public ob::ProjectionEvaluator
{
public:
    PositionProjection(const ob::StateSpacePtr &space, VehicleModel model, ob::RealVectorBounds bounds)
        : ob::ProjectionEvaluator(space),
          model_(model),
          positionBounds_(std::move(bounds))
    {
    }

    unsigned int getDimension() const override { return unsigned(positionBounds_.low.size()); }

    void project(const ob::State *state, Eigen::Ref<Eigen::VectorXd> projection) const override
    {
        const ob::State *pose = poseComponent(model_, state);
        if (getDimension() == 2)
        {
            const auto *s = pose->as<ob::SE2StateSpace::StateType>();
            projection(0) = s->getX();
            projection(1) = s->getY();
            return;
        }
        const auto *s = pose->as<ob::SE3StateSpace::StateType>();
        projection(0) = s->getX();
        projection(1) = s->getY();
        projection(2) = s->getZ();
    }

    void defaultCellSizes() override
    {
        bounds_ = positionBounds_;
        const std::vector<double> extent = bounds_.getDifference();
        cellSizes_.resize(extent.size());
        for (std::size_t i = 0; i < extent.size(); ++i)
            cellSizes_[i] = extent[i] > 0.0 ? extent[i] / 20.0 : 1.0;
    }

private:
    VehicleModel model_;
    ob::RealVectorBounds positionBounds_;
};

// The full state of a .cfg pose: zero velocities and steering; the blimp keeps only the yaw of
// the orientation (OMPL.app's getFullStateFromGeometricComponent).
void configPoseToVehicleState(const ConfigPose &pose, VehicleModel model, bool planar, ob::State *state)
{
    const ob::State *poseState = poseComponent(model, state);
    configPoseToState(pose, planar, const_cast<ob::State *>(poseState));
    std::vector<double> q = vehicleCoordinates(model, state);
    for (std::size_t i = planar ? 3 : (model == VehicleModel::Blimp ? 4 : 7); i < q.size(); ++i)
        q[i] = 0.0;
    setVehicleCoordinates(model, q, state);
}
}  // namespace

ControlValidityChecker::ControlValidityChecker(const ob::SpaceInformationPtr &si, VehicleModel model,
                                               std::shared_ptr<const hcd::StateValidityChecker> poseValidity)
    : ob::StateValidityChecker(si),
      model_(model),
      poseValidity_(std::move(poseValidity))
{
}

bool ControlValidityChecker::isValid(const ob::State *state) const
{
    const std::vector<double> q = vehicleCoordinates(model_, state);
    for (double v : q)
        if (!std::isfinite(v))
            return false;
    return si_->satisfiesBounds(state) && poseValidity_->collisionFree(poseComponent(model_, state));
}

std::shared_ptr<StateValidityChecker> installControlChecker(ControlProblem &planning, const LoadedProblem &problem,
                                                            std::shared_ptr<const CollisionChecker> checker,
                                                            MotionCheck motion)
{
    const oc::SpaceInformationPtr &si = planning.setup->getSpaceInformation();
    planning.poseValidity = std::make_shared<StateValidityChecker>(planning.poseSpace, std::move(checker),
                                                                   problem.scene, problem.config.planar);
    planning.poseSpace->setStateValidityChecker(planning.poseValidity);
    // A checker that counts turns from the robot's z axis is sound for SE(2) motions alone.
    const bool turnsAboutRobotZ = planning.poseValidity->checker().turnsAboutRobotZ();
    if (turnsAboutRobotZ && !problem.config.planar)
        throw std::invalid_argument("the checker's swept queries count turns about the robot's z axis "
                                    "(CollisionScene::turnsAboutRobotZ), which only a planar problem's motions keep");
    si->setStateValidityChecker(std::make_shared<ControlValidityChecker>(si, planning.model, planning.poseValidity));
    planning.settings.motion = motion;
    planning.propagator =
        std::make_shared<VehiclePropagator>(si, planning.model, planning.settings.integrationStep,
                                            motion == MotionCheck::Continuous ? planning.poseValidity : nullptr,
                                            robotTurnRadius(*problem.robot.mesh, turnsAboutRobotZ));
    si->setStatePropagator(planning.propagator);
    return planning.poseValidity;
}

ControlProblem makeControlProblem(const LoadedProblem &problem, std::shared_ptr<const CollisionChecker> checker,
                                  const ControlSettings &settings)
{
    const ProblemConfig &cfg = problem.config;
    const std::optional<VehicleModel> model = vehicleModelOfName(cfg.control);
    if (!model)
        throw std::invalid_argument(cfg.path + ": unknown control model '" + cfg.control +
                                    "'; expected kinematic_car, dynamic_car, blimp or quadrotor");
    if (vehicleSpec(*model).planar != cfg.planar)
        throw std::invalid_argument(cfg.path + ": control = " + cfg.control + " needs a " +
                                    (vehicleSpec(*model).planar ? "planar" : "3D") + " problem");
    if (!(settings.goalThreshold > 0.0) || !(settings.propagationStep > 0.0) || !(settings.integrationStep > 0.0) ||
        settings.minControlSteps < 1 || settings.minControlSteps > settings.maxControlSteps)
        throw std::invalid_argument("control settings: thresholds and steps must be positive, min <= max steps");

    ControlProblem out;
    out.model = *model;
    out.settings = settings;
    // The position bounds are the geometric problem's (volume grown to hold start and goal).
    const ob::StateSpacePtr poseSpace = makeStateSpace(problem);
    const ob::RealVectorBounds positionBounds =
        cfg.planar ? poseSpace->as<ob::SE2StateSpace>()->getBounds() : poseSpace->as<ob::SE3StateSpace>()->getBounds();
    const ob::StateSpacePtr space = makeVehicleStateSpace(*model, positionBounds);
    out.setup = std::make_shared<oc::SimpleSetup>(makeVehicleControlSpace(*model, space));
    const oc::SpaceInformationPtr si = out.setup->getSpaceInformation();

    // The pose checker lives in a geometric SpaceInformation over the state's own pose subspace.
    const ob::StateSpacePtr poseSubspace =
        *model == VehicleModel::KinematicCar ? space : space->as<ob::CompoundStateSpace>()->getSubspace(0);
    out.poseSpace = std::make_shared<ob::SpaceInformation>(poseSubspace);
    installControlChecker(out, problem, std::move(checker), settings.motion);
    out.poseSpace->setup();
    si->setPropagationStepSize(settings.propagationStep);
    si->setMinMaxControlDuration(settings.minControlSteps, settings.maxControlSteps);
    space->registerDefaultProjection(std::make_shared<PositionProjection>(space, *model, positionBounds));

    ob::ScopedState<> start(space), goal(space);
    configPoseToVehicleState(cfg.start, *model, cfg.planar, start.get());
    configPoseToVehicleState(cfg.goal, *model, cfg.planar, goal.get());
    out.setup->setStartAndGoalStates(start, goal, settings.goalThreshold);
    return out;
}
}  // namespace hcd
