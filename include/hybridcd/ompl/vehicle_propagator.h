// SPDX-License-Identifier: BSD-3-Clause
// OMPL adapter: the state propagator of a vehicle model (vehicle_model.h), optionally certifying
// that the vehicle's whole trajectory, not only the states planners check, is collision-free.
#pragma once

#include "hybridcd/ompl/state_validity_checker.h"
#include "hybridcd/ompl/vehicle_model.h"

#include <ompl/control/StatePropagator.h>

#include <atomic>
#include <cstdint>
#include <memory>

namespace hcd
{
/** \brief Integrates the model (RK4, steps of at most `integrationStep` seconds, OMPL.app: 0.01)
    and then does OMPL.app's post-propagation step (vehicle_model.h: finishPropagation).

    OMPL's control planners check states only at the ends of propagation steps (0.2 s by default:
    up to a metre for the kinematic car), so a car may cut a corner between two checks. Given a
    `sweep` checker, the propagator also certifies the trajectory in between: over a time interval
    of length T from state qa, every robot point p moves at most V T + W |p| T, with V and W
    bounds on the speed of the robot origin and the angular speed that follow from qa, the control
    and the model (vehicle_model.cpp: motionBounds). So when, at the middle of the interval, every
    part of the robot is farther from the environment than that reach for half the interval
    (CollisionChecker::withinSweptDistance), nothing on the interval touches. Intervals that cannot
    be certified are halved, down to 1/64 of an integration step; one still uncertified there
    (a contact, or a pass closer than about speed x 0.15 ms) blocks the propagation, and the
    result is a state whose position is not a number, which ControlValidityChecker rejects, so a
    planner never keeps it. Thread-safe. */
class VehiclePropagator : public ompl::control::StatePropagator
{
public:
    /// `robotRadius` bounds |p| over robot points p (robot frame).
    VehiclePropagator(const ompl::control::SpaceInformationPtr &si, VehicleModel model, double integrationStep,
                      std::shared_ptr<const StateValidityChecker> sweep = nullptr, double robotRadius = 0.0);

    void propagate(const ompl::base::State *state, const ompl::control::Control *control, double duration,
                   ompl::base::State *result) const override;

    bool canPropagateBackward() const override { return false; }

    VehicleModel model() const { return model_; }

    /// Propagations whose trajectory could not be certified (0 without a sweep checker).
    std::uint64_t blockedPropagations() const { return blocked_.load(); }

private:
    bool certify(const std::vector<double> &qa, const double *u, double length, int depth, ompl::base::State *scratch,
                 QueryContext &context) const;

    VehicleModel model_;
    double integrationStep_;
    std::shared_ptr<const StateValidityChecker> sweep_;
    double robotRadius_;
    mutable std::atomic<std::uint64_t> blocked_{0};
};
}  // namespace hcd
