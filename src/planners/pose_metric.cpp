// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/planners/pose_metric.h"

#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>

#include <algorithm>
#include <cmath>
#include <typeinfo>

namespace hcd
{
namespace
{
// A quaternion further off unit norm than this is not bounded (PoseCoordinates::rotationBoundable).
constexpr double kBoundableNormTolerance = 1e-9;
}  // namespace

std::optional<PoseMetric> PoseMetric::of(const ompl::base::StateSpace &space)
{
    namespace ob = ompl::base;
    const bool planar = typeid(space) == typeid(ob::SE2StateSpace);
    const bool spatial = typeid(space) == typeid(ob::SE3StateSpace);
    if (!planar && !spatial)
        return std::nullopt;
    const auto &compound = static_cast<const ob::CompoundStateSpace &>(space);
    const double translationWeight = compound.getSubspaceWeight(0);
    const double rotationWeight = compound.getSubspaceWeight(1);
    if (!(translationWeight >= 0.0) || !(rotationWeight >= 0.0) || !std::isfinite(translationWeight) ||
        !std::isfinite(rotationWeight))
        return std::nullopt;
    return PoseMetric(planar, translationWeight, rotationWeight);
}

PoseCoordinates PoseMetric::coordinates(const ompl::base::State *state) const
{
    namespace ob = ompl::base;
    PoseCoordinates out;
    auto &v = out.values;
    if (planar_)
    {
        const auto *pose = state->as<ob::SE2StateSpace::StateType>();
        v[0] = pose->getX();
        v[1] = pose->getY();
        v[2] = pose->getYaw();
        out.rotationBoundable = std::fabs(v[2]) <= PoseMetric::kPi;
    }
    else
    {
        const auto *pose = state->as<ob::SE3StateSpace::StateType>();
        const auto &q = pose->rotation();
        const double sign = q.w < 0.0 ? -1.0 : 1.0;
        v = {pose->getX(), pose->getY(), pose->getZ(), sign * q.x, sign * q.y, sign * q.z, sign * q.w};
        const double norm = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
        out.rotationBoundable = std::fabs(norm - 1.0) <= kBoundableNormTolerance;
    }
    out.finite = std::all_of(v.begin(), v.begin() + dimensions(), [](double x) { return std::isfinite(x); });
    return out;
}

double PoseMetric::spreadWeight(int dimension) const
{
    return dimension < (planar_ ? 2 : 3) ? translationWeight_ : rotationWeight_;
}

}  // namespace hcd
