// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/query/brute_force_checker.h"

#include "hybridcd/geometry/triangle_distance.h"
#include "hybridcd/geometry/triangle_intersection.h"
#include "hybridcd/narrowphase/convex_decomposition.h"

#include <algorithm>

namespace hcd
{
BruteForceChecker::BruteForceChecker(CollisionScene scene)
    : robotFaces_(withoutRepeatedFaces(scene.robot)),
      environmentFaces_(withoutRepeatedFaces(scene.environment)),
      scene_{robotFaces_.mesh, environmentFaces_.mesh, std::move(scene.robotName), std::move(scene.environmentName)}
{
    const TriangleMesh &env = *scene_.environment;
    for (std::uint32_t t = 0; t < env.triangleCount(); ++t)
    {
        const Vec3 &a = env.corner(t, 0), &b = env.corner(t, 1), &c = env.corner(t, 2);
        environmentBoxes_.push_back({a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c), t});
    }
    std::sort(environmentBoxes_.begin(), environmentBoxes_.end(),
              [](const TriangleBox &p, const TriangleBox &q) { return p.min.x() < q.min.x(); });
}

bool BruteForceChecker::doCollides(const RigidTransform &worldFromRobot, QueryContext &context) const
{
    if (!worldFromRobot.isFinite())
        return true;
    const TriangleMesh &robot = *scene_.robot, &env = *scene_.environment;
    std::vector<Vec3> corners(3 * robot.triangleCount());
    std::vector<TriangleBox> robotBoxes(robot.triangleCount());
    for (std::uint32_t t = 0; t < robot.triangleCount(); ++t)
    {
        for (int k = 0; k < 3; ++k)
            corners[3 * t + k] = worldFromRobot.apply(robot.corner(t, k));
        const Vec3 &a = corners[3 * t], &b = corners[3 * t + 1], &c = corners[3 * t + 2];
        robotBoxes[t] = {a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c), t};
    }
    std::sort(robotBoxes.begin(), robotBoxes.end(),
              [](const TriangleBox &p, const TriangleBox &q) { return p.min.x() < q.min.x(); });

    std::uint64_t tests = 0;
    // Tests one pair whose x-intervals overlap; true on contact.
    auto test = [&](const TriangleBox &r, const TriangleBox &e) {
        if (r.min.y() > e.max.y() || e.min.y() > r.max.y() || r.min.z() > e.max.z() || e.min.z() > r.max.z())
            return false;
        ++tests;
        const std::uint32_t t = r.triangle;
        return trianglesIntersect(corners[3 * t], corners[3 * t + 1], corners[3 * t + 2], env.corner(e.triangle, 0),
                                  env.corner(e.triangle, 1), env.corner(e.triangle, 2));
    };
    // One sweep over both lists sorted by min.x reports every x-overlapping pair exactly once:
    // whichever box starts first is paired with all boxes of the other list starting within it.
    bool hit = false;
    std::size_t i = 0, j = 0;
    const std::size_t n = robotBoxes.size(), m = environmentBoxes_.size();
    while (!hit && i < n && j < m)
    {
        if (robotBoxes[i].min.x() <= environmentBoxes_[j].min.x())
        {
            for (std::size_t k = j; !hit && k < m && environmentBoxes_[k].min.x() <= robotBoxes[i].max.x(); ++k)
                hit = test(robotBoxes[i], environmentBoxes_[k]);
            ++i;
        }
        else
        {
            for (std::size_t k = i; !hit && k < n && robotBoxes[k].min.x() <= environmentBoxes_[j].max.x(); ++k)
                hit = test(robotBoxes[k], environmentBoxes_[j]);
            ++j;
        }
    }
    context.stats.primitiveTests += tests;
    return hit;
}

std::vector<ContactPair> BruteForceChecker::doContacts(const RigidTransform &worldFromRobot, std::size_t limit,
                                                       QueryContext &) const
{
    std::vector<ContactPair> found;
    if (!worldFromRobot.isFinite())
        return found;
    const TriangleMesh &robot = *scene_.robot, &env = *scene_.environment;
    for (std::uint32_t i = 0; i < robot.triangleCount() && found.size() < limit; ++i)
    {
        const Vec3 a0 = worldFromRobot.apply(robot.corner(i, 0));
        const Vec3 a1 = worldFromRobot.apply(robot.corner(i, 1));
        const Vec3 a2 = worldFromRobot.apply(robot.corner(i, 2));
        const Vec3 lo = a0.cwiseMin(a1).cwiseMin(a2), hi = a0.cwiseMax(a1).cwiseMax(a2);
        for (std::uint32_t j = 0; j < env.triangleCount() && found.size() < limit; ++j)
        {
            // Triangles whose bounding boxes are disjoint cannot meet (exact comparisons).
            const Vec3 &b0 = env.corner(j, 0), &b1 = env.corner(j, 1), &b2 = env.corner(j, 2);
            if ((b0.array() > hi.array() && b1.array() > hi.array() && b2.array() > hi.array()).any() ||
                (b0.array() < lo.array() && b1.array() < lo.array() && b2.array() < lo.array()).any())
                continue;
            if (trianglesIntersect(a0, a1, a2, env.corner(j, 0), env.corner(j, 1), env.corner(j, 2)))
                found.push_back(
                    {ContactPair::Kind::Triangles, robotFaces_.source(i), environmentFaces_.source(j),
                     triangleContactPoint(a0, a1, a2, env.corner(j, 0), env.corner(j, 1), env.corner(j, 2))});
        }
    }
    return found;
}

double BruteForceChecker::doDistance(const RigidTransform &worldFromRobot, QueryContext &context) const
{
    if (!worldFromRobot.isFinite())
        return 0.0;
    const TriangleMesh &robot = *scene_.robot, &env = *scene_.environment;
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < robot.triangleCount() && best > 0.0; ++i)
    {
        const Vec3 a0 = worldFromRobot.apply(robot.corner(i, 0));
        const Vec3 a1 = worldFromRobot.apply(robot.corner(i, 1));
        const Vec3 a2 = worldFromRobot.apply(robot.corner(i, 2));
        const Vec3 lo = a0.cwiseMin(a1).cwiseMin(a2), hi = a0.cwiseMax(a1).cwiseMax(a2);
        for (std::size_t j = 0; j < env.triangleCount() && best > 0.0; ++j)
        {
            // The gap between the bounding boxes is at most the triangles' distance: a pair whose
            // gap, less a margin far above rounding at these coordinates, is no nearer than the
            // best distance yet cannot lower it.
            const Vec3 &b0 = env.corner(j, 0), &b1 = env.corner(j, 1), &b2 = env.corner(j, 2);
            const Vec3 blo = b0.cwiseMin(b1).cwiseMin(b2), bhi = b0.cwiseMax(b1).cwiseMax(b2);
            const double gap = (blo - hi).cwiseMax(lo - bhi).cwiseMax(0.0).norm();
            const double margin = 1e-9 * std::max({lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff(),
                                                   blo.cwiseAbs().maxCoeff(), bhi.cwiseAbs().maxCoeff()});
            if (gap - margin >= best)
                continue;
            best = std::min(best, triangleDistance(a0, a1, a2, b0, b1, b2));
        }
    }
    context.stats.primitiveTests += robot.triangleCount() * env.triangleCount();
    return best;
}
}  // namespace hcd
