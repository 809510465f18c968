// SPDX-License-Identifier: BSD-3-Clause
// Turns a loaded OMPL.app kinodynamic problem (.cfg with `control = ...`) into an OMPL control
// SimpleSetup, the way OMPL.app sets up its vehicles (vehicle_model.h), with a hybridcd checker
// deciding validity.
#pragma once

#include "hybridcd/io/problem_scene.h"
#include "hybridcd/ompl/planning_problem.h"
#include "hybridcd/ompl/vehicle_model.h"
#include "hybridcd/ompl/vehicle_propagator.h"

#include <ompl/control/SimpleSetup.h>

#include <memory>

namespace hcd
{
/// How the vehicle is propagated and when the goal is reached. The defaults are OMPL.app's
/// (its GUI's control planning settings; its integration step is 0.01 s).
struct ControlSettings
{
    double goalThreshold = 1.0;    ///< distance to the goal state (OMPL's compound-space distance)
    double propagationStep = 0.2;  ///< s, the step at which planners check states
    unsigned minControlSteps = 1;  ///< each control lasts between these numbers of propagation steps
    unsigned maxControlSteps = 20;
    double integrationStep = 0.01;  ///< s, the Runge-Kutta step
    /// Continuous: the whole trajectory is certified collision-free as well (VehiclePropagator);
    /// Discrete: states are checked at the propagation steps only, as OMPL.app does.
    MotionCheck motion = MotionCheck::Continuous;
};

/** \brief Valid = the full state inside the state-space bounds (velocities included), its
    position a number (see VehiclePropagator), and its pose collision-free. The pose checks go
    through `poseValidity` (so they are counted and timed there). Thread-safe. */
class ControlValidityChecker : public ompl::base::StateValidityChecker
{
public:
    ControlValidityChecker(const ompl::base::SpaceInformationPtr &si, VehicleModel model,
                           std::shared_ptr<const hcd::StateValidityChecker> poseValidity);
    bool isValid(const ompl::base::State *state) const override;

private:
    VehicleModel model_;
    std::shared_ptr<const hcd::StateValidityChecker> poseValidity_;
};

struct ControlProblem
{
    std::shared_ptr<ompl::control::SimpleSetup> setup;
    VehicleModel model = VehicleModel::KinematicCar;
    /// The SE2/SE3 space of the pose component, with the problem's position bounds, and the
    /// checker that decides collisions there (counting every query).
    ompl::base::SpaceInformationPtr poseSpace;
    std::shared_ptr<StateValidityChecker> poseValidity;
    std::shared_ptr<VehiclePropagator> propagator;
    ControlSettings settings;
};

/// The control SimpleSetup for `problem` (its config's `control` names the model): state and
/// control spaces, propagator, validity checker, OMPL.app's projection on the position (cells of
/// a twentieth of the bounds, for KPIECE, EST and PDST), the start and the goal region (the .cfg
/// poses with zero velocities; the blimp's orientation is reduced to its yaw). The planner is left
/// for the caller to set. Throws std::invalid_argument when the config names no known model.
ControlProblem makeControlProblem(const LoadedProblem &problem, std::shared_ptr<const CollisionChecker> checker,
                                  const ControlSettings &settings = {});

/// Makes `checker` the one `planning` uses, with `motion` for the trajectories: a new pose
/// checker (returned, also stored in planning.poseValidity), validity checker and propagator
/// installed in its SpaceInformation; planning.settings.motion becomes `motion`. Used to switch
/// checkers between benchmark runs (planners read both through the SpaceInformation).
std::shared_ptr<StateValidityChecker> installControlChecker(ControlProblem &planning, const LoadedProblem &problem,
                                                            std::shared_ptr<const CollisionChecker> checker,
                                                            MotionCheck motion);
}  // namespace hcd
