// SPDX-License-Identifier: BSD-3-Clause
// OMPL adapter: the state propagator of a vehicle model (vehicle_model.h), with optional
// checking of the motion between its integration steps.
#pragma once

#include "hybridcd/ompl/vehicle_model.h"

#include <ompl/control/StatePropagator.h>

#include <atomic>
#include <cstdint>
#include <memory>

namespace hcd
{
class ContinuousMotionValidator;

/** \brief Integrates the model (RK4, steps of at most `integrationStep` seconds, OMPL.app: 0.01)
    and then does OMPL.app's post-propagation step (vehicle_model.h: finishPropagation).

    OMPL's control planners check states only at the ends of propagation steps (0.2 s by default:
    up to a metre for the kinematic car), so a car may cut a corner between two checks. With a
    `sweep` validator, every integration step's pose-to-pose motion is certified collision-free by
    it (an interpolation that stays within about 1e-4 m of the true arc at OMPL.app's speeds); a
    blocked motion makes the result a state whose position is not a number, which
    ControlValidityChecker rejects, so a planner never keeps it. Thread-safe. */
class VehiclePropagator : public ompl::control::StatePropagator
{
public:
    VehiclePropagator(const ompl::control::SpaceInformationPtr &si, VehicleModel model, double integrationStep,
                      std::shared_ptr<const ContinuousMotionValidator> sweep);

    void propagate(const ompl::base::State *state, const ompl::control::Control *control, double duration,
                   ompl::base::State *result) const override;

    bool canPropagateBackward() const override { return false; }

    VehicleModel model() const { return model_; }

    /// Propagations whose sweep was found blocked (0 without a sweep validator).
    std::uint64_t blockedPropagations() const { return blocked_.load(); }

private:
    VehicleModel model_;
    double integrationStep_;
    std::shared_ptr<const ContinuousMotionValidator> sweep_;
    mutable std::atomic<std::uint64_t> blocked_{0};
};
}  // namespace hcd
