// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/query/solid_semantics_checker.h"

namespace hcd
{
namespace
{
// Vertices per robot component the grid is asked about before rays are cast.
constexpr std::size_t kRobotProbes = 8;
}  // namespace

SolidSemanticsChecker::SolidSemanticsChecker(std::unique_ptr<CollisionChecker> surface, const CollisionScene &scene)
    : surface_(std::move(surface)),
      environmentSolids_(scene.environment),
      robotSolids_(scene.robot),
      robotRepresentatives_(firstVertexOfEachComponent(robotSolids_)),
      environmentRepresentatives_(firstVertexOfEachComponent(environmentSolids_)),
      // Near an obstacle, some of a component's spread vertices usually lie in cells the grid has
      // proven outside; the representative comes first.
      robotProbes_(verticesSpreadOverEachComponent(robotSolids_, kRobotProbes))
{
}

bool SolidSemanticsChecker::robotComponentInside(const RigidTransform &worldFromRobot, std::size_t component) const
{
    const Vec3 representative = worldFromRobot.apply(robotRepresentatives_[component]);
    if (!environmentSolids_.withinSolidBounds(representative))
        return false;  // beyond every solid's box: no ray needed, nor the grid
    // Rays can cost: through a vertex level with faces of the environment (planar scenes) they
    // fall back to generic directions. A probe proven outside by the grid settles it first.
    if (environmentGrid_)
        for (const Vec3 &v : robotProbes_[component])
            if (environmentGrid_->clears(worldFromRobot.apply(v), 0.0, /*outside=*/true))
                return false;  // a point of it proven outside every solid: all of it is
    return environmentSolids_.insideAnySolid(representative);
}

bool SolidSemanticsChecker::contained(const RigidTransform &worldFromRobot) const
{
    if (environmentSolids_.closedComponentCount() > 0)
        for (std::size_t i = 0; i < robotRepresentatives_.size(); ++i)
            if (robotComponentInside(worldFromRobot, i))
                return true;
    if (robotSolids_.closedComponentCount() > 0)
    {
        const RigidTransform robotFromWorld = worldFromRobot.inverse();
        for (const Vec3 &v : environmentRepresentatives_)
            if (robotSolids_.insideAnySolid(robotFromWorld.apply(v)))
                return true;
    }
    return false;
}

std::vector<ContactPair> SolidSemanticsChecker::doContacts(const RigidTransform &worldFromRobot, std::size_t limit,
                                                           QueryContext &context) const
{
    std::vector<ContactPair> found = surface_->contacts(worldFromRobot, limit, context);
    if (!found.empty() || limit == 0 || !worldFromRobot.isFinite())
        return found;
    for (std::size_t i = 0; i < robotRepresentatives_.size(); ++i)
    {
        const Vec3 w = worldFromRobot.apply(robotRepresentatives_[i]);
        const int solid = environmentSolids_.solidContaining(w);
        if (solid >= 0)
            return {{ContactPair::Kind::Containment, std::uint32_t(i), std::uint32_t(solid), w}};
    }
    if (robotSolids_.closedComponentCount() > 0)
    {
        const RigidTransform robotFromWorld = worldFromRobot.inverse();
        for (std::size_t j = 0; j < environmentRepresentatives_.size(); ++j)
        {
            const int solid = robotSolids_.solidContaining(robotFromWorld.apply(environmentRepresentatives_[j]));
            if (solid >= 0)
                return {{ContactPair::Kind::Containment, std::uint32_t(solid), std::uint32_t(j),
                         environmentRepresentatives_[j]}};
        }
    }
    return found;
}

bool SolidSemanticsChecker::doCollides(const RigidTransform &worldFromRobot, QueryContext &context) const
{
    if (!worldFromRobot.isFinite())
        return true;
    return surface_->collides(worldFromRobot, context) || contained(worldFromRobot);
}

double SolidSemanticsChecker::doDistance(const RigidTransform &worldFromRobot, QueryContext &context) const
{
    if (!worldFromRobot.isFinite())
        return 0.0;
    // Containment first (a few point-in-solid tests): a robot inside a solid is at distance 0
    // without the surfaces' branch and bound, which answers touching surfaces itself.
    if (contained(worldFromRobot))
        return 0.0;
    return surface_->distance(worldFromRobot, context);
}

bool SolidSemanticsChecker::doWithinDistance(const RigidTransform &worldFromRobot, double delta,
                                             QueryContext &context) const
{
    if (!worldFromRobot.isFinite())
        return true;
    return surface_->withinDistance(worldFromRobot, delta, context) || contained(worldFromRobot);
}
}  // namespace hcd
