// SPDX-License-Identifier: BSD-3-Clause
// Continuous motion checks in a scene of many bodies: every robot moves at once.
//
// A scene motion takes every robot r from start[r] to goal[r] over t in [0, 1] as OMPL interpolates
// SE(2) and SE(3) states: the position linearly, the rotation along the shortest arc at constant
// angular rate (slerp; the planar yaw along the shorter way round). A robot point p (robot frame)
// then moves at a speed of at most |dx| + |dtheta| * |p| per unit t, where dx is the robot's
// displacement and dtheta the angle of its relative rotation; a static body does not move.
//
// Conservative advancement (Mirtich; the distance-based form of the review's §4.3 coherence):
// each checked pair is advanced on its own. At time t the pair is at distance d apart; neither of
// its points can close that gap faster than the sum of the two bodies' speed bounds s, so the
// pair stays apart until t + d / s at least. Stepping so never skips a contact: a motion is free
// when every pair reaches t = 1 (the end pose included) without the distance falling to the
// contact tolerance. Each step first tries the gap between the bodies' world boxes, a lower bound
// on the distance that costs next to nothing, and computes the exact distance only when the boxes
// alone cannot carry the pair to the end of the motion.
//
// Raked states first. Most motions a planner tries touch something; before any advancement the
// states at t = 1, 1/2, 1/4, 3/4, 1/8, ... (8 of them) are checked exactly, as VAMP rakes a motion.
// One that collides decides the verdict, and bounds how far pairs need advancing for lastValid.
//
// Grazing approaches. Where the bodies close in at a shallow angle, each step covers only a little
// of the remaining gap and advancement would crawl: every 16 steps of a pair, states ahead at
// growing strides are checked exactly, and one that touches settles the verdict at once.
//
// Touching and near-touching. A pair whose distance falls to `contactTolerance` (default 1e-9 of
// the scene's size) counts as touching: a motion that passes that close to contact is rejected,
// never accepted, so the answer errs only towards collision, and only for motions within that
// tolerance of contact. Every state on the way is also a valid pose (the checks are exact at each).
//
// Pure translation (the review's §5). When neither body of a pair rotates and both are convex
// polytopes (box or convex hull), the pair's first contact is the optimum of the time-augmented
// LP in (x, y, z, t) (narrowphase/time_of_contact.h): exact, with no stepping at all.
#pragma once

#include "hybridcd/scene/scene.h"

#include <cstddef>
#include <vector>

namespace hcd
{
/// What checkMotion found.
struct SceneMotionResult
{
    bool valid = true;                ///< no checked pair touches at any t in [0, 1]
    double lastValidTime = 1.0;       ///< when invalid: every pair stays apart on [0, lastValidTime]
    double contactTime = 1.0;         ///< when invalid: a time at which `pair` touches (or comes within the
                                      ///< tolerance); the earliest such time found, not always the first
                                      ///< contact (a probe ahead may find a later one)
    std::size_t pair = 0;             ///< when invalid: the pair (index into Scene::pairs()) that touched
    std::size_t distanceQueries = 0;  ///< exact distance queries made
    std::size_t boundSteps = 0;       ///< steps carried by the boxes' gap alone
    std::size_t lpPairs = 0;          ///< pairs decided by the time-augmented LP
};

/// How checkMotion decides.
struct SceneMotionOptions
{
    /// Distance at or below which a pair counts as touching; <= 0 means 1e-9 of Scene::scale().
    double contactTolerance = 0.0;
    /// Use the time-augmented LP for pairs of translating polytopes (otherwise they are advanced).
    bool translationLp = true;
    /// The verdict alone (as a planner asks before extending along a motion): a raked state that
    /// collides ends the check at once, and lastValidTime is then 0, not bracketed.
    bool verdictOnly = false;
    /// Give up advancing a pair after this many distance steps and report it as touching (never as
    /// free): only motions that pass within a hair of contact without touching take that many.
    std::size_t maxStepsPerPair = 5000;
    /// The robots turn about z only, as OMPL's SE(2) interpolates them. Otherwise (SE(3)) turns
    /// below 2e-4 rad are certified for their whole angle at every t, since OMPL's SO(3) keeps the
    /// start rotation up to the end below about 9e-5 rad. Either way a turn within 1e-9 of half a
    /// circle, whose direction rounding decides, is certified both ways round.
    bool planar = false;
};

/// The robots' poses at time t of the motion from `start` to `goal` (robotCount transforms each):
/// positions linearly, rotations along the shortest arc, as OMPL's SE(2)/SE(3) interpolate (up to
/// the cases SceneMotionOptions::planar describes, which checkSceneMotion covers).
void interpolateScenePoses(const std::vector<RigidTransform> &start, const std::vector<RigidTransform> &goal, double t,
                           std::vector<RigidTransform> &out);

/// Checks the motion of every robot from start[r] to goal[r] at once (see the essay above). The
/// start state is checked too. Thread-safe with a context per thread.
SceneMotionResult checkSceneMotion(const Scene &scene, const std::vector<RigidTransform> &start,
                                   const std::vector<RigidTransform> &goal, QueryContext &context,
                                   const SceneMotionOptions &options = {});

/// The reference: the poses at `samples` + 1 evenly spaced times, each checked exactly. It can
/// miss a contact between samples, so it serves to find motions that must be invalid.
SceneMotionResult checkSceneMotionBySampling(const Scene &scene, const std::vector<RigidTransform> &start,
                                             const std::vector<RigidTransform> &goal, std::size_t samples,
                                             QueryContext &context);
}  // namespace hcd
