// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/query/penetration_estimate.h"

#include "hybridcd/narrowphase/penetration.h"

#include <algorithm>
#include <utility>

namespace hcd
{
namespace
{
using PiecePair = std::pair<ConvexPiece, ConvexPiece>;

// The current intersecting triangle pairs (containment records left out), each as its two
// triangles' flat convex pieces in world coordinates (robot placed by `pose`). Built once per
// round: both the deepest pair and the clearing distance read them.
std::vector<PiecePair> contactPieces(const CollisionChecker &checker, const CollisionScene &scene,
                                     const RigidTransform &pose, QueryContext &context)
{
    const TriangleMesh &robot = *scene.robot, &env = *scene.environment;
    std::vector<PiecePair> pieces;
    for (const ContactPair &c : checker.contacts(pose, 256, context))
        if (c.kind == ContactPair::Kind::Triangles)
            pieces.emplace_back(
                ConvexPiece::hullOf({pose.apply(robot.corner(c.robotElement, 0)),
                                     pose.apply(robot.corner(c.robotElement, 1)),
                                     pose.apply(robot.corner(c.robotElement, 2))}),
                ConvexPiece::hullOf({env.corner(c.environmentElement, 0), env.corner(c.environmentElement, 1),
                                     env.corner(c.environmentElement, 2)}));
    return pieces;
}

// The deepest pairwise penetration among the pairs (depth 0 when there are none).
Penetration deepestPair(const std::vector<PiecePair> &pairs)
{
    Penetration deepest;
    for (const auto &[a, b] : pairs)
    {
        const Penetration p = penetrationDepth(a, b);
        if (p.intersecting && (!deepest.intersecting || p.depth > deepest.depth))
            deepest = p;
    }
    return deepest;
}

// How far the robot must move along the unit `direction` for every pair to come apart: the largest
// directional penetration (the LP of section 5 read backwards) over the pairs. Moving the deepest
// pair's minimum distance alone leaves the other pairs touching, one more round each; this clears
// them in one step. Pairs that would need more than `limit` (a robot triangle sliding along a long
// wall in that direction) are left to later rounds: the point is a free pose nearby, not one far
// away.
double clearingDistance(const std::vector<PiecePair> &pairs, const Vec3 &direction, double limit)
{
    double distance = 0.0;
    for (const auto &[a, b] : pairs)
    {
        const double s = directionalPenetration(a, -direction, b);
        if (s <= limit)
            distance = std::max(distance, s);
    }
    return distance;
}
}  // namespace

PenetrationEstimate estimatePenetration(const CollisionChecker &checker, const CollisionScene &scene,
                                        const RigidTransform &worldFromRobot, QueryContext &context, int maxSteps)
{
    PenetrationEstimate out;
    if (!worldFromRobot.isFinite())
    {
        out.colliding = true;
        return out;
    }
    out.colliding = checker.collides(worldFromRobot, context);
    if (!out.colliding)
    {
        out.freePose = worldFromRobot;
        return out;
    }
    std::vector<PiecePair> pairs = contactPieces(checker, scene, worldFromRobot, context);
    const Penetration first = deepestPair(pairs);
    if (!first.intersecting)
        return out;  // contained in a solid: no triangle pair to push out of
    out.depth = first.depth;
    out.direction = first.direction;

    // Push out along the deepest pair's direction, far enough to clear every current pair, and a
    // little past it so that touching is left behind too.
    RigidTransform pose = worldFromRobot;
    const double scale = 1.0 + worldFromRobot.translation.norm() + scene.robot->radiusAboutOrigin();
    Penetration step = first;
    for (int i = 0; i < maxSteps && step.intersecting; ++i)
    {
        const double push =
            std::max(step.depth, clearingDistance(pairs, step.direction, scene.robot->radiusAboutOrigin()));
        pose.translation += (push * (1.0 + 1e-6) + 1e-9 * scale) * step.direction;
        if (!checker.collides(pose, context))
        {
            out.freePose = pose;
            return out;
        }
        pairs = contactPieces(checker, scene, pose, context);
        step = deepestPair(pairs);
    }
    return out;
}

PenetrationEstimate estimatePenetration(const CollisionChecker &checker, const CollisionScene &scene,
                                        const RigidTransform &worldFromRobot, int maxSteps)
{
    QueryContext context;
    return estimatePenetration(checker, scene, worldFromRobot, context, maxSteps);
}

SignedClearance signedClearance(const CollisionChecker &checker, const CollisionScene &scene,
                                const RigidTransform &worldFromRobot, QueryContext &context)
{
    const double d = checker.distance(worldFromRobot, context);
    if (d > 0.0)
        return {d, false};
    // The estimate's own collision check decides (a free pose comes back with depth 0).
    const PenetrationEstimate estimate = estimatePenetration(checker, scene, worldFromRobot, context, 0);
    // 0.0 - depth, not -depth: a pose within rounding of contact (depth 0) gives 0, not -0.
    return {0.0 - estimate.depth, estimate.colliding};
}
}  // namespace hcd
