// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/query/penetration_estimate.h"

#include "hybridcd/narrowphase/penetration.h"

namespace hcd
{
namespace
{
// The deepest pairwise penetration among the current contacts (depth 0 when there are none).
Penetration deepestPair(const CollisionChecker &checker, const CollisionScene &scene, const RigidTransform &pose,
                        QueryContext &context)
{
    Penetration deepest;
    for (const ContactPair &c : checker.contacts(pose, 256, context))
    {
        if (c.kind != ContactPair::Kind::Triangles)
            continue;
        const TriangleMesh &robot = *scene.robot, &env = *scene.environment;
        const ConvexPiece a = ConvexPiece::hullOf({pose.apply(robot.corner(c.robotElement, 0)),
                                                   pose.apply(robot.corner(c.robotElement, 1)),
                                                   pose.apply(robot.corner(c.robotElement, 2))});
        const ConvexPiece b = ConvexPiece::hullOf({env.corner(c.environmentElement, 0), env.corner(c.environmentElement, 1),
                                                   env.corner(c.environmentElement, 2)});
        const Penetration p = penetrationDepth(a, b);
        if (p.intersecting && (!deepest.intersecting || p.depth > deepest.depth))
            deepest = p;
    }
    return deepest;
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
    const Penetration first = deepestPair(checker, scene, worldFromRobot, context);
    if (!first.intersecting)
        return out;  // contained in a solid: no triangle pair to push out of
    out.depth = first.depth;
    out.direction = first.direction;

    // Push out, a little past each pairwise depth so touching is left behind too.
    RigidTransform pose = worldFromRobot;
    const double scale = 1.0 + worldFromRobot.translation.norm() + scene.robot->radiusAboutOrigin();
    Penetration step = first;
    for (int i = 0; i < maxSteps && step.intersecting; ++i)
    {
        pose.translation += (step.depth * (1.0 + 1e-6) + 1e-9 * scale) * step.direction;
        if (!checker.collides(pose, context))
        {
            out.freePose = pose;
            return out;
        }
        step = deepestPair(checker, scene, pose, context);
    }
    return out;
}

PenetrationEstimate estimatePenetration(const CollisionChecker &checker, const CollisionScene &scene,
                                        const RigidTransform &worldFromRobot, int maxSteps)
{
    QueryContext context;
    return estimatePenetration(checker, scene, worldFromRobot, context, maxSteps);
}
}  // namespace hcd
