// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/query/collision_checker.h"

namespace hcd
{
namespace
{
// Runs `query` with a fresh context and adds its counters to `stats`.
template <class Query>
auto withOneOffContext(QueryStats *stats, Query &&query)
{
    QueryContext context;
    auto result = query(context);
    if (stats)
    {
        stats->boundingVolumeTests += context.stats.boundingVolumeTests;
        stats->primitiveTests += context.stats.primitiveTests;
    }
    return result;
}
}  // namespace

bool CollisionChecker::collides(const RigidTransform &worldFromRobot, QueryStats *stats) const
{
    return withOneOffContext(stats, [&](QueryContext &c) { return doCollides(worldFromRobot, c); });
}

double CollisionChecker::distance(const RigidTransform &worldFromRobot, QueryStats *stats) const
{
    return withOneOffContext(stats, [&](QueryContext &c) { return doDistance(worldFromRobot, c); });
}

std::vector<ContactPair> CollisionChecker::contacts(const RigidTransform &worldFromRobot, std::size_t limit) const
{
    return withOneOffContext(nullptr, [&](QueryContext &c) { return doContacts(worldFromRobot, limit, c); });
}

bool CollisionChecker::withinDistance(const RigidTransform &worldFromRobot, double delta, QueryStats *stats) const
{
    return withOneOffContext(stats, [&](QueryContext &c) { return doWithinDistance(worldFromRobot, delta, c); });
}

bool CollisionChecker::withinSweptDistance(const RigidTransform &worldFromRobot, double translationSlack,
                                           double radialSlack, double robotRadius, QueryStats *stats) const
{
    return withOneOffContext(stats, [&](QueryContext &c) {
        return doWithinSweptDistance(worldFromRobot, translationSlack, radialSlack, robotRadius, c);
    });
}
}  // namespace hcd
