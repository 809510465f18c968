// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/query/translation_contact.h"

#include "hybridcd/narrowphase/convex_piece.h"
#include "hybridcd/narrowphase/time_of_contact.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hcd
{
namespace
{
// Relative padding of every box: far above the rounding of the box and interval arithmetic below,
// and above the LP's touching tolerance (1e-12 of a pair's size).
constexpr double kPadding = 1e-9;

double magnitude(const BoundingBox &box)
{
    return box.empty() ? 0.0 : std::max(box.min.cwiseAbs().maxCoeff(), box.max.cwiseAbs().maxCoeff());
}

// Times t in [0, 1] at which the box [lo, hi] translated by t * d overlaps [min, max], as
// [enter, exit]; enter > exit when never.
std::pair<double, double> overlapTimes(const Vec3 &lo, const Vec3 &hi, const Vec3 &d, const Vec3 &min, const Vec3 &max)
{
    double enter = 0.0, exit = 1.0;
    for (int k = 0; k < 3; ++k)
    {
        // lo_k + t d_k <= max_k and hi_k + t d_k >= min_k.
        if (d[k] == 0.0)
        {
            if (lo[k] > max[k] || hi[k] < min[k])
                return {1.0, 0.0};
            continue;
        }
        double a = (min[k] - hi[k]) / d[k], b = (max[k] - lo[k]) / d[k];
        if (a > b)
            std::swap(a, b);
        enter = std::max(enter, a);
        exit = std::min(exit, b);
    }
    return {enter, exit};
}
}  // namespace

TranslationContactFinder::TranslationContactFinder(CollisionScene scene)
    : robotFaces_(withoutRepeatedFaces(scene.robot)),
      environmentFaces_(withoutRepeatedFaces(scene.environment))
{
    const TriangleMesh &env = *environmentFaces_.mesh;
    padding_ = kPadding * magnitude(env.bounds());
    for (std::uint32_t t = 0; t < env.triangleCount(); ++t)
    {
        const Vec3 &a = env.corner(t, 0), &b = env.corner(t, 1), &c = env.corner(t, 2);
        environmentBoxes_.push_back({a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c), t});
    }
    std::sort(environmentBoxes_.begin(), environmentBoxes_.end(),
              [](const TriangleBox &p, const TriangleBox &q) { return p.min.x() < q.min.x(); });
}

TranslationContact TranslationContactFinder::solvePair(const RigidTransform &worldFromRobot, const Vec3 &displacement,
                                                       std::uint32_t robot, std::uint32_t environment) const
{
    const TriangleMesh &r = *robotFaces_.mesh, &e = *environmentFaces_.mesh;
    const ConvexPiece moving =
        ConvexPiece::hullOf({worldFromRobot.apply(r.corner(robot, 0)), worldFromRobot.apply(r.corner(robot, 1)),
                             worldFromRobot.apply(r.corner(robot, 2))});
    const ConvexPiece fixed =
        ConvexPiece::hullOf({e.corner(environment, 0), e.corner(environment, 1), e.corner(environment, 2)});
    const TimeOfContact toc = translationalTimeOfContact(moving, displacement, fixed);
    TranslationContact out;
    out.pairsSolved = 1;
    if (toc.contact)
    {
        out.contact = true;
        out.time = toc.time;
        out.point = toc.point;
        out.robotTriangle = robotFaces_.source(robot);
        out.environmentTriangle = environmentFaces_.source(environment);
    }
    return out;
}

TranslationContact TranslationContactFinder::firstContact(const RigidTransform &worldFromRobot,
                                                          const Vec3 &displacement) const
{
    TranslationContact best;
    if (!worldFromRobot.isFinite() || !displacement.allFinite())
    {
        best.contact = true;
        best.time = 0.0;
        return best;
    }
    const TriangleMesh &robot = *robotFaces_.mesh;
    const double pad = std::max(padding_, kPadding * (worldFromRobot.translation.cwiseAbs().maxCoeff() +
                                                      robot.radiusAboutOrigin() + displacement.cwiseAbs().maxCoeff()));

    // Robot triangles at t = 0 (padded), and their boxes swept over the motion.
    std::vector<TriangleBox> start(robot.triangleCount()), swept(robot.triangleCount());
    for (std::uint32_t t = 0; t < robot.triangleCount(); ++t)
    {
        const Vec3 a = worldFromRobot.apply(robot.corner(t, 0)), b = worldFromRobot.apply(robot.corner(t, 1)),
                   c = worldFromRobot.apply(robot.corner(t, 2));
        const Vec3 lo = a.cwiseMin(b).cwiseMin(c).array() - pad, hi = a.cwiseMax(b).cwiseMax(c).array() + pad;
        start[t] = {lo, hi, t};
        swept[t] = {lo.cwiseMin(lo + displacement), hi.cwiseMax(hi + displacement), t};
    }
    std::sort(swept.begin(), swept.end(),
              [](const TriangleBox &p, const TriangleBox &q) { return p.min.x() < q.min.x(); });

    // Candidate pairs with the time their boxes first meet.
    struct Candidate
    {
        double enter;
        std::uint32_t robot, environment;
    };
    std::vector<Candidate> candidates;
    const auto consider = [&](const TriangleBox &r, const TriangleBox &e) {
        if (r.min.y() > e.max.y() + pad || e.min.y() - pad > r.max.y() || r.min.z() > e.max.z() + pad ||
            e.min.z() - pad > r.max.z())
            return;
        const TriangleBox &s = start[r.triangle];
        const auto [enter, exit] = overlapTimes(s.min, s.max, displacement, e.min.array() - pad, e.max.array() + pad);
        // Rounding of the division: a relative margin, still far below any pair's separation.
        if (enter <= exit + 1e-9)
            candidates.push_back({enter, r.triangle, e.triangle});
    };
    std::size_t i = 0, j = 0;
    const std::size_t n = swept.size(), m = environmentBoxes_.size();
    while (i < n && j < m)
    {
        if (swept[i].min.x() <= environmentBoxes_[j].min.x() - pad)
        {
            for (std::size_t k = j; k < m && environmentBoxes_[k].min.x() - pad <= swept[i].max.x(); ++k)
                consider(swept[i], environmentBoxes_[k]);
            ++i;
        }
        else
        {
            for (std::size_t k = i; k < n && swept[k].min.x() <= environmentBoxes_[j].max.x() + pad; ++k)
                consider(swept[k], environmentBoxes_[j]);
            ++j;
        }
    }
    std::sort(candidates.begin(), candidates.end(),
              [](const Candidate &p, const Candidate &q) { return p.enter < q.enter; });

    std::size_t solved = 0;
    for (const Candidate &c : candidates)
    {
        if (best.contact && c.enter - 1e-9 > best.time)
            break;  // these boxes meet only after the contact found
        const TranslationContact pair = solvePair(worldFromRobot, displacement, c.robot, c.environment);
        ++solved;
        if (pair.contact && (!best.contact || pair.time < best.time))
            best = pair;
    }
    best.pairsSolved = solved;
    return best;
}

TranslationContact TranslationContactFinder::firstContactAllPairs(const RigidTransform &worldFromRobot,
                                                                  const Vec3 &displacement) const
{
    TranslationContact best;
    if (!worldFromRobot.isFinite() || !displacement.allFinite())
    {
        best.contact = true;
        best.time = 0.0;
        return best;
    }
    std::size_t solved = 0;
    for (std::uint32_t r = 0; r < robotFaces_.mesh->triangleCount(); ++r)
        for (std::uint32_t e = 0; e < environmentFaces_.mesh->triangleCount(); ++e)
        {
            const TranslationContact pair = solvePair(worldFromRobot, displacement, r, e);
            ++solved;
            if (pair.contact && (!best.contact || pair.time < best.time))
                best = pair;
        }
    best.pairsSolved = solved;
    return best;
}
}  // namespace hcd
