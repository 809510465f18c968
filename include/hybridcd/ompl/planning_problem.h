// SPDX-License-Identifier: BSD-3-Clause
// Turns a loaded OMPL.app problem into an OMPL SimpleSetup, the way OMPL.app sets it up.
#pragma once

#include "hybridcd/io/problem_scene.h"
#include "hybridcd/ompl/state_pose.h"
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

class ContinuousMotionValidator;

/// A SimpleSetup and the hybridcd objects installed in its SpaceInformation, typed, so that callers
/// tune them without casting OMPL's base pointers back.
struct PlanningProblem
{
    std::shared_ptr<ompl::geometric::SimpleSetup> setup;
    std::shared_ptr<StateValidityChecker> validity;
    /// The motion validator installed for MotionCheck::Continuous; null for Discrete.
    std::shared_ptr<ContinuousMotionValidator> continuousValidator;
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
/// planning.validity) and, for MotionCheck::Continuous, a ContinuousMotionValidator over it
/// (also stored in planning.continuousValidator);
/// for Discrete, OMPL's DiscreteMotionValidator. Used to switch checkers between benchmark runs.
std::shared_ptr<StateValidityChecker> installChecker(PlanningProblem &planning, const LoadedProblem &problem,
                                                     std::shared_ptr<const CollisionChecker> checker,
                                                     MotionCheck motion);

/// The state of a .cfg pose (3D poses are axis-angle, planar ones yaw).
void configPoseToState(const ConfigPose &pose, bool planar, ompl::base::State *state);

}  // namespace hcd
