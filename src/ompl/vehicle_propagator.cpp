// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/ompl/vehicle_propagator.h"

#include <ompl/control/SpaceInformation.h>
#include <ompl/control/spaces/RealVectorControlSpace.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace hcd
{
namespace
{
// Halvings of an integration step before an interval is given up as blocked.
constexpr int kExtraDepth = 6;
}  // namespace

VehiclePropagator::VehiclePropagator(const ompl::control::SpaceInformationPtr &si, VehicleModel model,
                                     double integrationStep, std::shared_ptr<const StateValidityChecker> sweep,
                                     double robotRadius)
    : ompl::control::StatePropagator(si),
      model_(model),
      integrationStep_(integrationStep),
      sweep_(std::move(sweep)),
      robotRadius_(robotRadius)
{
}

bool VehiclePropagator::certify(const std::vector<double> &qa, const double *u, double length, int depth,
                                ompl::base::State *scratch, QueryContext &context) const
{
    const double half = 0.5 * length;
    std::vector<double> qc = qa;
    integrateVehicle(model_, qc, u, half, integrationStep_);
    const MotionBounds bounds = motionBounds(model_, qa, u, length);
    std::vector<double> shown = qc;
    finishPropagation(model_, shown);
    setVehicleCoordinates(model_, shown, scratch);
    const RigidTransform pose = poseOfState(poseComponent(model_, scratch), vehicleSpec(model_).planar);
    if (std::isfinite(bounds.speed) && std::isfinite(bounds.angularSpeed) &&
        !sweep_->poseWithinSweptDistance(pose, bounds.speed * half, bounds.angularSpeed * half, robotRadius_, context))
        return true;
    if (length <= integrationStep_ / double(1 << kExtraDepth) || depth > 40)
        return false;
    return certify(qa, u, half, depth + 1, scratch, context) && certify(qc, u, half, depth + 1, scratch, context);
}

void VehiclePropagator::propagate(const ompl::base::State *state, const ompl::control::Control *control,
                                  double duration, ompl::base::State *result) const
{
    const double *u = control->as<ompl::control::RealVectorControlSpace::ControlType>()->values;
    const std::vector<double> q0 = vehicleCoordinates(model_, state);
    std::vector<double> q = q0;
    integrateVehicle(model_, q, u, duration, integrationStep_);
    finishPropagation(model_, q);
    if (sweep_ && duration > 0.0)
    {
        const StateValidityChecker::Timing timing = sweep_->timing();
        ompl::base::State *scratch = si_->allocState();
        const bool free = certify(q0, u, duration, 0, scratch, *sweep_->contexts().borrow());
        si_->freeState(scratch);
        if (!free)
        {
            q[0] = std::numeric_limits<double>::quiet_NaN();
            blocked_.fetch_add(1, std::memory_order_relaxed);
        }
    }
    setVehicleCoordinates(model_, q, result);
}
}  // namespace hcd
