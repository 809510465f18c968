// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/ompl/vehicle_propagator.h"

#include "hybridcd/ompl/continuous_motion_validator.h"

#include <ompl/control/SpaceInformation.h>
#include <ompl/control/spaces/RealVectorControlSpace.h>

#include <cmath>
#include <limits>

namespace hcd
{
VehiclePropagator::VehiclePropagator(const ompl::control::SpaceInformationPtr &si, VehicleModel model,
                                     double integrationStep, std::shared_ptr<const ContinuousMotionValidator> sweep)
    : ompl::control::StatePropagator(si),
      model_(model),
      integrationStep_(integrationStep),
      sweep_(std::move(sweep))
{
}

void VehiclePropagator::propagate(const ompl::base::State *state, const ompl::control::Control *control,
                                  double duration, ompl::base::State *result) const
{
    const double *u = control->as<ompl::control::RealVectorControlSpace::ControlType>()->values;
    std::vector<double> q = vehicleCoordinates(model_, state);
    if (!sweep_)
    {
        integrateVehicle(model_, q, u, duration, integrationStep_);
        finishPropagation(model_, q);
        setVehicleCoordinates(model_, q, result);
        return;
    }
    // Step by step, each step's motion certified from the previous pose. The intermediate poses
    // get the same post-step as the end (angles wrapped, quaternion unit) so that they are states
    // the pose space accepts; the velocities they carry are not used.
    const long steps = std::max(1L, long(std::ceil(duration / integrationStep_ - 1e-9)));
    const double h = duration / double(steps);
    const ompl::base::SpaceInformation &si = *si_;
    ompl::base::State *previous = si.allocState();
    ompl::base::State *next = si.allocState();
    si.copyState(previous, state);
    bool blocked = false;
    for (long s = 0; s < steps && !blocked; ++s)
    {
        integrateVehicle(model_, q, u, h, h);
        std::vector<double> shown = q;
        finishPropagation(model_, shown);
        setVehicleCoordinates(model_, shown, next);
        blocked = !sweep_->checkMotion(poseComponent(model_, previous), poseComponent(model_, next));
        std::swap(previous, next);
    }
    si.freeState(next);
    si.freeState(previous);
    finishPropagation(model_, q);
    if (blocked)
    {
        q[0] = std::numeric_limits<double>::quiet_NaN();
        blocked_.fetch_add(1, std::memory_order_relaxed);
    }
    setVehicleCoordinates(model_, q, result);
}
}  // namespace hcd
