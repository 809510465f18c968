// SPDX-License-Identifier: BSD-3-Clause
// Turns a loaded OMPL.app problem into an OMPL SimpleSetup, the way OMPL.app sets it up.
#pragma once

#include "hybridcd/io/problem_scene.h"
#include "hybridcd/ompl/state_validity_checker.h"

#include <ompl/geometric/SimpleSetup.h>

#include <memory>
#include <string>
#include <vector>

namespace hcd
{
/// How motions between states are validated.
enum class MotionCheck
{
    Continuous,  ///< ContinuousMotionValidator: never accepts a motion that touches an obstacle
    Discrete,    ///< OMPL's DiscreteMotionValidator at OMPL's default resolution (may tunnel)
};

/// Parses "continuous" or "discrete"; throws std::invalid_argument otherwise.
MotionCheck parseMotionCheck(const std::string &name);

struct PlanningProblem
{
    std::shared_ptr<ompl::geometric::SimpleSetup> setup;
    std::shared_ptr<StateValidityChecker> validity;
    bool planar = false;
};

/// SE2 or SE3 state space whose position bounds are the .cfg volume (or, without one, the
/// environment's bounding box) grown to contain the start and the goal.
ompl::base::StateSpacePtr makeStateSpace(const LoadedProblem &problem);

/// SimpleSetup with the space, start, goal, validity checker, objective and valid-state sampler
/// the .cfg asks for. The planner is left for the caller to set.
PlanningProblem makePlanningProblem(const LoadedProblem &problem, std::shared_ptr<const CollisionChecker> checker,
                                    MotionCheck motion = MotionCheck::Continuous);

/// Makes `checker` the one `planning` uses: a new StateValidityChecker (returned, also stored in
/// planning.validity) and, for MotionCheck::Continuous, a ContinuousMotionValidator over it;
/// for Discrete, OMPL's DiscreteMotionValidator. Used to switch checkers between benchmark runs.
std::shared_ptr<StateValidityChecker> installChecker(PlanningProblem &planning, const LoadedProblem &problem,
                                                     std::shared_ptr<const CollisionChecker> checker, MotionCheck motion);

/// The state of a .cfg pose (3D poses are axis-angle, planar ones yaw).
void configPoseToState(const ConfigPose &pose, bool planar, ompl::base::State *state);

/// Fills a state from .path columns (`values` holds 7 numbers, x y z qx qy qz qw, or 3, x y theta).
/// The quaternion is normalised as RigidTransform::fromTranslationQuaternion does (rescaled when its
/// squares over- or underflow; zero is the identity), so a state and poseToTransform of the same
/// columns place the robot alike. A yaw is wrapped into [-pi, pi), the bounds OMPL asserts.
void poseValuesToState(const double *values, bool planar, ompl::base::State *state);

/// The .path columns of a state: x y z qx qy qz qw, or x y theta.
std::vector<double> stateToPoseValues(const ompl::base::State *state, bool planar);
}  // namespace hcd
