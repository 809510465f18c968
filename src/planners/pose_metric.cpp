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

constexpr double kPosePi = 3.14159265358979323846;

// OMPL's SO(3) distance is 0 where |q1 . q2| > 1 - 1e-9, i.e. below an angle of 4.5e-5 rad, and
// quaternions whose norm is off 1 by 1e-9 move the angle by up to 6.3e-5 rad: the chord bound
// gives up this much so that it stays below OMPL's value.
constexpr double kChordSlack = 2e-4;
constexpr double kBoundableNormTolerance = 1e-9;
// The wrapped yaw difference is a subtraction and a comparison; its rounding is far below this.
constexpr double kWrappedYawSlack = 1e-9;
// Rounding of the weighted sum.
constexpr double kWeightedSumSlack = 1e-12;

// Distance from v to the interval [low, high] (0 inside).
double intervalGap(double v, double low, double high)
{
    return std::max({low - v, v - high, 0.0});
}

double wrappedYawDifference(double a, double b)
{
    const double d = std::fabs(a - b);
    return d > kPosePi ? 2.0 * kPosePi - d : d;
}

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
        out.rotationBoundable = std::fabs(v[2]) <= kPosePi;
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

double PoseMetric::lowerBound(const PoseCoordinates &p, const double *low, const double *high) const
{
    const auto &v = p.values;
    const int translationDimensions = planar_ ? 2 : 3;
    double squared = 0.0;
    for (int i = 0; i < translationDimensions; ++i)
    {
        const double g = intervalGap(v[i], low[i], high[i]);
        squared += g * g;
    }
    double bound = translationWeight_ * std::sqrt(squared);
    if (p.rotationBoundable)
    {
        double angle = 0.0;
        if (planar_)
        {
            if (v[2] < low[2] || v[2] > high[2])
                angle = std::min(wrappedYawDifference(v[2], low[2]), wrappedYawDifference(v[2], high[2])) - kWrappedYawSlack;
        }
        else
        {
            // For unit quaternions the chord min(|q1 - q2|, |q1 + q2|) = 2 sin(angle / 2) is at
            // most the angle, and the box's nearest point to q (or to -q) is at most the chord.
            double plus = 0.0;
            double minus = 0.0;
            for (int i = 3; i < 7; ++i)
            {
                const double g = intervalGap(v[i], low[i], high[i]);
                const double h = intervalGap(-v[i], low[i], high[i]);
                plus += g * g;
                minus += h * h;
            }
            angle = std::sqrt(std::min(plus, minus)) - kChordSlack;
        }
        bound += rotationWeight_ * std::max(angle, 0.0);
    }
    return bound * (1.0 - kWeightedSumSlack);
}

double PoseMetric::spreadWeight(int dimension) const
{
    return dimension < (planar_ ? 2 : 3) ? translationWeight_ : rotationWeight_;
}

}  // namespace hcd
