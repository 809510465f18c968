// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/ompl/state_pose.h"

#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>

#include <Eigen/Geometry>

#include <cmath>
#include <limits>

namespace hcd
{
PoseRow rowOfState(const ompl::base::State *state, bool planar)
{
    PoseRow row{};
    if (planar)
    {
        const auto *s = state->as<ompl::base::SE2StateSpace::StateType>();
        row = {s->getX(), s->getY(), s->getYaw()};
        return row;
    }
    const auto *s = state->as<ompl::base::SE3StateSpace::StateType>();
    const auto &q = s->rotation();
    row = {s->getX(), s->getY(), s->getZ(), q.x, q.y, q.z, q.w};
    return row;
}

RigidTransform poseOfState(const ompl::base::State *state, bool planar)
{
    return transformOfStateRow(rowOfState(state, planar).data(), planar);
}

double interpolationTurn(const ompl::base::State *from, const ompl::base::State *to, bool planar)
{
    constexpr double pi = 3.14159265358979323846;
    constexpr double unbounded = std::numeric_limits<double>::infinity();
    if (planar)
    {
        const double a = from->as<ompl::base::SE2StateSpace::StateType>()->getYaw();
        const double b = to->as<ompl::base::SE2StateSpace::StateType>()->getYaw();
        // SO2StateSpace::interpolate: the difference itself when at most pi, else 2 pi minus it
        // (with its sign), the yaw then moving linearly in t by that amount.
        const double diff = b - a;
        if (!std::isfinite(diff))
            return unbounded;
        if (std::fabs(diff) <= pi)
            return std::fabs(diff);
        return std::fabs(diff > 0.0 ? 2.0 * pi - diff : -2.0 * pi - diff);
    }
    const auto &p = from->as<ompl::base::SE3StateSpace::StateType>()->rotation();
    const auto &q = to->as<ompl::base::SE3StateSpace::StateType>()->rotation();
    const Eigen::Quaterniond a(p.w, p.x, p.y, p.z), b(q.w, q.x, q.y, q.z);
    if (!a.coeffs().allFinite() || !b.coeffs().allFinite() || !(std::fabs(a.norm() - 1.0) <= 1e-9) ||
        !(std::fabs(b.norm() - 1.0) <= 1e-9))
        return unbounded;
    // OMPL's slerp goes to b or -b, whichever is nearer: |w| picks the same shorter arc.
    const Eigen::Quaterniond relative = a.conjugate() * b;
    return 2.0 * std::atan2(relative.vec().norm(), std::fabs(relative.w()));
}

void poseValuesToState(const double *values, bool planar, ompl::base::State *state)
{
    const PoseRow row = stateRowOf(values, planar);
    if (planar)
    {
        auto *s = state->as<ompl::base::SE2StateSpace::StateType>();
        s->setXY(row[0], row[1]);
        s->setYaw(row[2]);
        return;
    }
    auto *s = state->as<ompl::base::SE3StateSpace::StateType>();
    s->setXYZ(row[0], row[1], row[2]);
    s->rotation().x = row[3];
    s->rotation().y = row[4];
    s->rotation().z = row[5];
    s->rotation().w = row[6];
}

std::vector<double> stateToPoseValues(const ompl::base::State *state, bool planar)
{
    const PoseRow row = rowOfState(state, planar);
    return {row.begin(), row.begin() + long(poseColumns(planar))};
}
}  // namespace hcd
