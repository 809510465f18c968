// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/query/collision_checker.h"

#include <ostream>

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

void writeGroup(std::ostream &obj, const char *group, const ExportMesh &mesh, const RigidTransform &placement,
                std::size_t &vertexBase)
{
    obj << "g " << group << '\n';
    for (const Vec3 &local : mesh.vertices)
    {
        const Vec3 v = placement.apply(local);
        obj << "v " << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
    }
    for (const auto &t : mesh.triangles)
        obj << "f " << vertexBase + t[0] + 1 << ' ' << vertexBase + t[1] + 1 << ' ' << vertexBase + t[2] + 1 << '\n';
    vertexBase += mesh.vertices.size();
}
}  // namespace

bool CollisionChecker::exportLevel(int level, std::ostream &obj, const RigidTransform &worldFromRobot) const
{
    const std::optional<LevelVolumes> volumes = levelVolumes(level);
    if (!volumes)
        return false;
    obj << "# " << volumes->kind << " volumes of tree level " << level
        << " (leaves above that level included), the robot's placed at its pose\n";
    std::size_t base = 0;
    writeGroup(obj, "robot", volumes->robot, worldFromRobot, base);
    writeGroup(obj, "environment", volumes->environment, RigidTransform::identity(), base);
    return true;
}

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
