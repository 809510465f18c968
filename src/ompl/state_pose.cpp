// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/ompl/state_pose.h"

#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>

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
