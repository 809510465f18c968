// SPDX-License-Identifier: BSD-3-Clause
// OMPL adapters for scenes of many bodies: every robot's SE(2) or SE(3) state in one compound
// state, a validity checker and a continuous motion validator over a Scene (scene/scene.h).
#pragma once

#include "hybridcd/io/problem_scene.h"
#include "hybridcd/query/query_context_pool.h"
#include "hybridcd/scene/scene.h"
#include "hybridcd/scene/scene_motion.h"

#include <ompl/base/MotionValidator.h>
#include <ompl/base/StateValidityChecker.h>
#include <ompl/geometric/SimpleSetup.h>

#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

namespace hcd
{
/// The compound space of `robots` SE(2) (planar) or SE(3) spaces, named robot1, robot2, ...,
/// each with the same position bounds: the .cfg volume, or else the box around the static bodies
/// grown to contain every robot's start and goal (as makeStateSpace does for one robot).
ompl::base::StateSpacePtr makeSceneStateSpace(const LoadedProblem &problem, const Scene &scene);

/// The robots' poses held by a compound state (one transform per robot, robot 1 first).
void scenePosesOfState(const ompl::base::State *state, bool planar, std::size_t robots,
                       std::vector<RigidTransform> &out);
/// Writes robot r's pose row (x y theta, or x y z qx qy qz qw) into the compound state.
void sceneStateFromRows(const std::vector<double> &rows, bool planar, std::size_t robots, ompl::base::State *state);
/// The rows of every robot of a compound state, robot 1 first (a .path line).
std::vector<double> sceneRowsOfState(const ompl::base::State *state, bool planar, std::size_t robots);

/** \brief Valid = inside the bounds and no checked pair of the scene touches. Thread-safe: the
    scene is immutable, contexts come from a pool, counters are atomic. */
class SceneValidityChecker : public ompl::base::StateValidityChecker
{
public:
    SceneValidityChecker(const ompl::base::SpaceInformationPtr &si, std::shared_ptr<const Scene> scene, bool planar);

    bool isValid(const ompl::base::State *state) const override;
    /// The smallest distance between checked pairs (0 when touching). Exact up to rounding.
    double clearance(const ompl::base::State *state) const override;

    const Scene &scene() const { return *scene_; }
    bool planar() const { return planar_; }
    QueryContextPool &contexts() const { return contexts_; }
    /// Number of state checks (isValid and clearance) answered so far.
    std::uint64_t checkCount() const { return checks_.load(std::memory_order_relaxed); }
    /// Wall time spent inside those checks, in seconds.
    double checkSeconds() const { return 1e-9 * double(nanoseconds_.load(std::memory_order_relaxed)); }

private:
    std::shared_ptr<const Scene> scene_;
    bool planar_;
    mutable QueryContextPool contexts_;
    mutable std::atomic<std::uint64_t> checks_{0};
    mutable std::atomic<std::uint64_t> nanoseconds_{0};
};

/** \brief Continuous motion validation of all robots at once by conservative advancement
    (checkSceneMotion): never accepts a motion along which a checked pair touches. lastValid is
    the state at a time before which every pair was shown apart. */
class SceneMotionValidator : public ompl::base::MotionValidator
{
public:
    SceneMotionValidator(const ompl::base::SpaceInformationPtr &si,
                         std::shared_ptr<const SceneValidityChecker> validity, SceneMotionOptions options = {});

    bool checkMotion(const ompl::base::State *s1, const ompl::base::State *s2) const override;
    bool checkMotion(const ompl::base::State *s1, const ompl::base::State *s2,
                     std::pair<ompl::base::State *, double> &lastValid) const override;

    /// The full answer for one motion (no OMPL counters touched); `verdictOnly` as in
    /// SceneMotionOptions (the two-state checkMotion uses it).
    SceneMotionResult check(const ompl::base::State *s1, const ompl::base::State *s2, bool verdictOnly = false) const;

    /// Motions answered valid and invalid so far. Atomic: OMPL's own counters (valid_, invalid_)
    /// are plain integers, which parallel planners would race on, so they stay untouched.
    std::uint64_t validMotions() const { return validCount_.load(); }
    std::uint64_t invalidMotions() const { return invalidCount_.load(); }

private:
    std::shared_ptr<const SceneValidityChecker> validity_;
    SceneMotionOptions options_;
    mutable std::atomic<std::uint64_t> validCount_{0}, invalidCount_{0};
};

/// A SimpleSetup for a scene problem with its typed adapters.
struct ScenePlanningProblem
{
    std::shared_ptr<ompl::geometric::SimpleSetup> setup;
    std::shared_ptr<const Scene> scene;
    std::shared_ptr<SceneValidityChecker> validity;
    std::shared_ptr<SceneMotionValidator> motion;  ///< null when the discrete validator is used
    bool planar = false;
};

/// The space, start, goal, validity checker and motion validator (continuous, or OMPL's discrete
/// one when `continuous` is false) of a scene problem. The planner is left to the caller.
ScenePlanningProblem makeScenePlanningProblem(const LoadedProblem &problem, std::shared_ptr<const Scene> scene,
                                              bool continuous = true);
}  // namespace hcd
