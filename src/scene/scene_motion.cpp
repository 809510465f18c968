// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/scene/scene_motion.h"

#include "hybridcd/narrowphase/time_of_contact.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

namespace hcd
{
namespace
{
// The angle of the rotation that takes `from` to `to` (radians, in [0, pi]), by atan2, which stays
// accurate for tiny angles where acos of a dot product rounds to zero.
double rotationAngle(const Mat3 &from, const Mat3 &to)
{
    const Eigen::Quaterniond relative =
        Eigen::Quaterniond(from).normalized().conjugate() * Eigen::Quaterniond(to).normalized();
    return 2.0 * std::atan2(relative.vec().norm(), std::abs(relative.w()));
}

constexpr double kPi = 3.14159265358979323846;

// Below this turn OMPL's SO3 interpolation keeps the start rotation up to the end (about 9e-5 rad;
// this leaves room), where this file's slerp turns: the two paths differ by up to the whole angle.
constexpr double kHeldTurnBelow = 2e-4;
// Within this of a half turn, which way OMPL turns (SO2 by the sign of the yaw difference, SO3 by
// the sign of a dot product near zero) is decided by rounding, and may differ from this file's.
constexpr double kHalfTurnWithin = 1e-9;

// Per robot: how far it translates and turns over the whole motion.
struct RobotSweep
{
    Vec3 displacement = Vec3::Zero();  // dx, world units per unit t
    double translation = 0.0;          // |dx|
    double angle = 0.0;                // radians per unit t
    // Radians by which OMPL's interpolation may be turned away from this file's at any t: the whole
    // angle for turns OMPL keeps to the end or may take the other way round, else 0. Every robot
    // point p then lies within offsetAngle * |p| of where it is placed here.
    double offsetAngle = 0.0;
    bool rotates = false;
};

// Upper bound on |x| over the body's points x in its robot's frame (world units): how far a turn
// of the robot moves them, per radian.
double bodyReach(const SceneBody &b) { return b.ownerFromBody.translation.norm() + b.geometry->boundingRadius(); }

// How far OMPL's placement of the pair's bodies may lie from this file's at any t (world units).
double pairOffset(const Scene &scene, const ScenePair &pair, const std::vector<RobotSweep> &sweeps)
{
    double offset = 0.0;
    for (const std::uint32_t body : {pair.first, pair.second})
    {
        const SceneBody &b = scene.bodies()[body];
        if (b.robot >= 0)
            offset += sweeps[std::size_t(b.robot)].offsetAngle * bodyReach(b) * (1.0 + 1e-12);
    }
    return offset;
}

// Upper bound on how far any point of `body` moves per unit t.
double bodySpeed(const Scene &scene, std::size_t body, const std::vector<RobotSweep> &sweeps)
{
    const SceneBody &b = scene.bodies()[body];
    if (b.robot < 0)
        return 0.0;
    const RobotSweep &sweep = sweeps[std::size_t(b.robot)];
    const double reach = bodyReach(b);
    // A relative 1e-12 for the rounding of the interpolated poses themselves.
    return (sweep.translation + sweep.angle * reach) * (1.0 + 1e-12) + 1e-15 * scene.scale();
}

// Upper bound on how fast max over the body of direction . x grows per unit t (direction unit, world).
double supportRate(const Scene &scene, std::size_t body, const Vec3 &direction, const std::vector<RobotSweep> &sweeps)
{
    const SceneBody &b = scene.bodies()[body];
    if (b.robot < 0)
        return 0.0;
    const RobotSweep &sweep = sweeps[std::size_t(b.robot)];
    const double reach = bodyReach(b);
    const double rate = direction.dot(sweep.displacement) + sweep.angle * reach;
    return rate + 1e-12 * (sweep.translation + sweep.angle * reach) + 1e-15 * scene.scale();
}

// A direction that separates the pair (from its first body to its second) at these poses: a
// half-space's normal, else the line between the closest points. Zero when there is none.
Vec3 separatingDirection(const Scene &scene, const ScenePair &p, const std::vector<RigidTransform> &poses,
                         const Vec3 &onFirst, const Vec3 &onSecond)
{
    const Shape &first = scene.bodies()[p.first].geometry->shape(),
                &second = scene.bodies()[p.second].geometry->shape();
    if (first.kind() == ShapeKind::Halfspace)
        return scene.worldFromBody(p.first, poses.data()).rotation * first.normal();
    if (second.kind() == ShapeKind::Halfspace)
        return -(scene.worldFromBody(p.second, poses.data()).rotation * second.normal());
    const Vec3 line = onSecond - onFirst;
    const double length = line.norm();
    return length > 0.0 && std::isfinite(length) ? Vec3(line / length) : Vec3::Zero();
}

bool validPoses(const std::vector<RigidTransform> &poses, std::size_t count)
{
    if (poses.size() != count)
        return false;
    for (const RigidTransform &p : poses)
        if (!p.isFinite())
            return false;
    return true;
}

// The pair's first contact when neither body turns and both are polytopes: the time-augmented LP.
// Returns false when it does not apply.
bool translationContact(const Scene &scene, std::size_t pair, const std::vector<RigidTransform> &start,
                        const std::vector<RigidTransform> &goal, const std::vector<RobotSweep> &sweeps, double &time)
{
    const ScenePair &p = scene.pairs()[pair];
    const ConvexPiece *a = scene.polytope(p.first), *b = scene.polytope(p.second);
    if (!a || !b)
        return false;
    auto turns = [&](std::uint32_t body) {
        const int robot = scene.bodies()[body].robot;
        return robot >= 0 && sweeps[std::size_t(robot)].rotates;
    };
    if (turns(p.first) || turns(p.second))
        return false;
    auto displacement = [&](std::uint32_t body) -> Vec3 {
        const int robot = scene.bodies()[body].robot;
        return robot < 0 ? Vec3::Zero()
                         : Vec3(goal[std::size_t(robot)].translation - start[std::size_t(robot)].translation);
    };
    const ConvexPiece moving = a->transformed(scene.worldFromBody(p.first, start.data()));
    const ConvexPiece fixed = b->transformed(scene.worldFromBody(p.second, start.data()));
    const TimeOfContact contact =
        translationalTimeOfContact(moving, displacement(p.first) - displacement(p.second), fixed);
    time = contact.contact ? contact.time : 2.0;
    return true;
}
}  // namespace

void interpolateScenePoses(const std::vector<RigidTransform> &start, const std::vector<RigidTransform> &goal, double t,
                           std::vector<RigidTransform> &out)
{
    out.resize(start.size());
    for (std::size_t r = 0; r < start.size(); ++r)
    {
        const Eigen::Quaterniond a(start[r].rotation), b(goal[r].rotation);
        // Eigen's slerp takes the shorter arc, as OMPL's SO(3) (and, for rotations about z, SO(2)).
        out[r].rotation = a.normalized().slerp(t, b.normalized()).toRotationMatrix();
        out[r].translation = start[r].translation + t * (goal[r].translation - start[r].translation);
        if (t == 0.0)
            out[r] = start[r];
        else if (t == 1.0)
            out[r] = goal[r];
    }
}

SceneMotionResult checkSceneMotion(const Scene &scene, const std::vector<RigidTransform> &start,
                                   const std::vector<RigidTransform> &goal, QueryContext &context,
                                   const SceneMotionOptions &options)
{
    SceneMotionResult result;
    const std::size_t robots = scene.robotCount();
    if (!validPoses(start, robots) || !validPoses(goal, robots))
    {
        result.valid = false;
        result.lastValidTime = result.contactTime = 0.0;
        return result;
    }
    const double tolerance = options.contactTolerance > 0.0 ? options.contactTolerance : 1e-9 * scene.scale();
    const double validMargin = std::max(tolerance, 1e-6 * scene.scale());
    std::vector<RobotSweep> sweeps(robots);
    for (std::size_t r = 0; r < robots; ++r)
    {
        sweeps[r].displacement = goal[r].translation - start[r].translation;
        sweeps[r].translation = sweeps[r].displacement.norm();
        sweeps[r].rotates = !(start[r].rotation == goal[r].rotation);
        sweeps[r].angle = sweeps[r].rotates ? rotationAngle(start[r].rotation, goal[r].rotation) * (1.0 + 1e-9) : 0.0;
        if (sweeps[r].rotates &&
            ((!options.planar && sweeps[r].angle < kHeldTurnBelow) || sweeps[r].angle > kPi - kHalfTurnWithin))
            sweeps[r].offsetAngle = sweeps[r].angle;
    }

    // The earliest contact found so far: later pairs need only be advanced up to it. Every pair
    // that touches also bounds the last valid time, whichever touches first.
    double horizon = 1.0;
    bool found = false;
    result.lastValidTime = 1.0;
    std::vector<RigidTransform> poses;
    // Raked states: 1, 1/2, 1/4, 3/4, 1/8, 3/8, 5/8, 7/8.
    double rakedHit = 2.0;
    for (const double t : {1.0, 0.5, 0.25, 0.75, 0.125, 0.375, 0.625, 0.875})
    {
        interpolateScenePoses(start, goal, t, poses);
        if (scene.collides(poses, context))
        {
            rakedHit = t;
            break;
        }
    }
    if (rakedHit <= 1.0)
    {
        if (options.verdictOnly)
        {
            result.valid = false;
            result.lastValidTime = 0.0;
            result.contactTime = rakedHit;
            return result;
        }
        found = true;
        horizon = rakedHit;
        result.contactTime = rakedHit;
    }
    bool touched = false;
    auto touches = [&](std::size_t pair, double contactTime, double lastValid) {
        touched = true;
        result.lastValidTime = std::min(result.lastValidTime, std::max(0.0, std::min(lastValid, contactTime)));
        if (!found || contactTime < horizon)
        {
            found = true;
            horizon = contactTime;
            result.pair = pair;
            result.contactTime = contactTime;
        }
    };
    for (std::size_t pair = 0; pair < scene.pairs().size(); ++pair)
    {
        if (found && options.verdictOnly)
            break;  // the verdict is settled; which pair touches first does not matter
        const ScenePair &p = scene.pairs()[pair];
        double lpTime = 0.0;
        if (options.translationLp && translationContact(scene, pair, start, goal, sweeps, lpTime))
        {
            ++result.lpPairs;
            if (lpTime <= 1.0)
            {
                // The bodies touch at lpTime: the last valid time is just before, once checked.
                double lastValid = std::max(0.0, lpTime - 1e-9);
                interpolateScenePoses(start, goal, lastValid, poses);
                if (scene.pairCollides(pair, poses.data(), context))
                    lastValid = 0.0;
                touches(pair, lpTime, lastValid);
            }
            continue;
        }
        const double speed = bodySpeed(scene, p.first, sweeps) + bodySpeed(scene, p.second, sweeps);
        // OMPL's placement may lie `offset` from the one measured here: every margin grows by it.
        const double offset = pairOffset(scene, p, sweeps);
        const double pairTolerance = tolerance + offset, pairValidMargin = validMargin + offset;
        // safeUntil: up to when the pair is known to stay `pairValidMargin` apart, a margin the narrow
        // phase certifies with room to spare (its undecided band, near touching, is far thinner),
        // so that the state reported as last valid is checked free, not merely near.
        double t = 0.0, safeUntil = 0.0, lastStep = 0.0;
        std::size_t distanceSteps = 0;
        for (;;)
        {
            if (found && t >= horizon)
                break;  // another pair already touches earlier
            interpolateScenePoses(start, goal, t, poses);
            const double remaining = (1.0 - t) * speed;
            // The boxes' gap first: when it alone covers a good part of what is left, step on it.
            const double boxGap = scene.pairBoundsGap(pair, poses.data());
            const double gap = boxGap - pairTolerance;
            if (gap > 0.0 && (gap >= remaining || gap >= 0.25 * remaining))
            {
                ++result.boundSteps;
                if (gap >= remaining)
                    break;
                if (boxGap > pairValidMargin)
                    safeUntil = std::max(safeUntil, t + (boxGap - pairValidMargin) / speed);
                t += gap / speed;
                continue;
            }
            // Advancement slows down without end when the bodies close in at a grazing angle: every
            // 16 steps, probe ahead at growing strides for a state that already touches, which
            // settles the verdict at once.
            if (++distanceSteps % 16 == 0 && lastStep > 0.0)
            {
                bool hit = false;
                for (double stride = 4.0 * lastStep; !hit && t + stride < std::min(1.0, horizon) + stride;
                     stride *= 4.0)
                {
                    const double probe = std::min(1.0, t + stride);
                    interpolateScenePoses(start, goal, probe, poses);
                    if (scene.pairCollides(pair, poses.data(), context))
                    {
                        touches(pair, probe, std::min(safeUntil, t));
                        hit = true;
                    }
                    if (probe >= 1.0)
                        break;
                }
                if (hit)
                    break;
                interpolateScenePoses(start, goal, t, poses);
            }
            ++result.distanceQueries;
            Vec3 onFirst = Vec3::Constant(std::numeric_limits<double>::quiet_NaN()), onSecond = onFirst;
            const double distance = scene.pairDistanceBound(pair, poses.data(), context, &onFirst, &onSecond);
            const double clearance = distance - pairTolerance;
            if (clearance <= 0.0 || distanceSteps >= options.maxStepsPerPair)
            {
                touches(pair, t, std::min(safeUntil, t));
                break;
            }
            // Along a separating direction n the gap between the bodies' supports shrinks only as
            // fast as their motions along n (plus turning), often far slower than the full speed
            // bound: a robot sliding past an obstacle closes no gap at all (Mirtich's advancement).
            double directionalStep = 0.0;
            const Vec3 n = separatingDirection(scene, p, poses, onFirst, onSecond);
            if (n != Vec3::Zero())
            {
                const RigidTransform first = scene.worldFromBody(p.first, poses.data()),
                                     second = scene.worldFromBody(p.second, poses.data());
                const double gapAlong =
                    -scene.supportAlong(p.second, second, -n) - scene.supportAlong(p.first, first, n);
                if (gapAlong > pairTolerance)
                {
                    const double closing =
                        supportRate(scene, p.first, n, sweeps) + supportRate(scene, p.second, -n, sweeps);
                    if (closing <= 0.0)
                        break;  // the plane keeps them apart to the end
                    directionalStep = (gapAlong - pairTolerance) / closing;
                    if (gapAlong > pairValidMargin)
                        safeUntil = std::max(safeUntil, t + (gapAlong - pairValidMargin) / closing);
                    if (directionalStep >= 1.0 - t)
                        break;
                }
            }
            if (clearance >= remaining)
                break;
            if (distance > pairValidMargin)
                safeUntil = std::max(safeUntil, t + (distance - pairValidMargin) / speed);
            lastStep = std::max(clearance / speed, directionalStep);
            t += lastStep;
        }
    }
    // A raked state collides, yet no pair was seen touching before it (possible only when the
    // narrow phase and the distances disagree within rounding): keep the start as last valid.
    if (found && !touched)
        result.lastValidTime = 0.0;
    result.valid = !found;
    if (result.valid)
        result.lastValidTime = result.contactTime = 1.0;
    return result;
}

SceneMotionResult checkSceneMotionBySampling(const Scene &scene, const std::vector<RigidTransform> &start,
                                             const std::vector<RigidTransform> &goal, std::size_t samples,
                                             QueryContext &context)
{
    SceneMotionResult result;
    samples = std::max<std::size_t>(samples, 1);
    std::vector<RigidTransform> poses;
    double lastValid = 0.0;
    for (std::size_t i = 0; i <= samples; ++i)
    {
        const double t = double(i) / double(samples);
        interpolateScenePoses(start, goal, t, poses);
        if (scene.collides(poses, context))
        {
            result.valid = false;
            result.contactTime = t;
            result.lastValidTime = lastValid;
            return result;
        }
        lastValid = t;
    }
    return result;
}
}  // namespace hcd
