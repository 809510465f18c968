// SPDX-License-Identifier: BSD-3-Clause
// OMPL adapter: a StateValidityChecker for SE2 and SE3 rigid bodies backed by a CollisionChecker.
#pragma once

#include "hybridcd/ompl/state_pose.h"
#include "hybridcd/query/collision_checker.h"
#include "hybridcd/query/penetration_estimate.h"
#include "hybridcd/query/query_context_pool.h"

#include <ompl/base/StateValidityChecker.h>

#include <atomic>
#include <chrono>
#include <memory>

namespace hcd
{
/** \brief Valid = inside the state-space bounds and collision-free (OMPL.app's definition).
    Thread-safe: the checker is immutable and the counters are atomic, so OMPL's parallel
    planners may call isValid concurrently. */
class StateValidityChecker : public ompl::base::StateValidityChecker
{
public:
    /// `scene` is what `checker` was built over (needed for penetration estimates).
    StateValidityChecker(const ompl::base::SpaceInformationPtr &si, std::shared_ptr<const CollisionChecker> checker,
                         CollisionScene scene, bool planar);

    bool isValid(const ompl::base::State *state) const override;

    /// Collision test alone, without the bounds (still counted and timed).
    bool collisionFree(const ompl::base::State *state) const;

    /// Distance to the environment when free (exact up to rounding); when colliding, minus the
    /// penetration estimate (the deepest pairwise penetration, see penetration_estimate.h). The
    /// specs say APPROXIMATE because of the colliding case. Counted and timed as a check.
    double clearance(const ompl::base::State *state) const override;

    /** \brief As isValid(state); also reports the clearance in `dist` and, for a colliding state,
        offers in `validState` a nearby state pushed out along penetration vectors, verified valid
        (bounds and collisions) before `validStateAvailable` is set. */
    bool isValid(const ompl::base::State *state, double &dist, ompl::base::State *validState,
                 bool &validStateAvailable) const override;
    bool isValid(const ompl::base::State *state, double &dist) const override;
    using ompl::base::StateValidityChecker::isValid;

    /// For a colliding `state`: writes to `out` a nearby state with the same orientation, pushed out
    /// along penetration vectors (query/penetration_estimate.h), and returns true when that state is
    /// verified valid (bounds and collisions). Returns false, with `out` unspecified, when no such
    /// state was found. A collision-free `state` is copied as it is.
    bool pushedOut(const ompl::base::State *state, ompl::base::State *out) const;

    /// Counted forms of the checker's queries for a pose, for the motion validator, made with the
    /// caller's context (one per thread: see contexts()). They are not timed one by one (a clock
    /// read costs as much as a grid's answer): the caller times a run of them with timing().
    bool poseCollides(const RigidTransform &worldFromRobot, QueryContext &context) const;
    bool poseWithinDistance(const RigidTransform &worldFromRobot, double delta, QueryContext &context) const;
    bool poseWithinSweptDistance(const RigidTransform &worldFromRobot, double translationSlack, double radialSlack,
                                 double robotRadius, QueryContext &context) const;
    /// CollisionChecker::sweptFreeByFirstLayer, counted.
    bool poseSweptFreeByFirstLayer(const RigidTransform &worldFromRobot, double translationSlack,
                                   double radialSlack) const;
    /// CollisionChecker::listSweptNearPairs and sweptNearPairsAmong, counted.
    bool poseListSweptNearPairs(const RigidTransform &worldFromRobot, double translationSlack, double radialSlack,
                                std::size_t limit, std::vector<TrianglePair> &near, QueryContext &context) const;
    bool poseSweptNearPairsAmong(const RigidTransform &worldFromRobot, double translationSlack, double radialSlack,
                                 const std::vector<TrianglePair> &pairs, std::vector<TrianglePair> &near,
                                 QueryContext &context) const;

    /// The contexts this checker's own queries borrow (OMPL calls it from any thread); callers
    /// that make many queries in a row, such as a motion validator, borrow one for all of them.
    QueryContextPool &contexts() const { return contexts_; }

    const CollisionChecker &checker() const { return *checker_; }
    bool planar() const { return planar_; }

    /// Adds the wall time from its construction to its destruction to checkSeconds(): a motion
    /// validator holds one over each motion it checks with the pose queries above.
    class Timing
    {
    public:
        explicit Timing(const StateValidityChecker &validity);
        ~Timing();
        Timing(const Timing &) = delete;
        Timing &operator=(const Timing &) = delete;

    private:
        const StateValidityChecker &validity_;
        std::chrono::steady_clock::time_point start_;
    };
    Timing timing() const { return Timing(*this); }

    /// Number of collision queries answered so far.
    std::uint64_t checkCount() const { return checks_.load(std::memory_order_relaxed); }
    /// Wall time spent inside collision queries (and motion checks timed with timing()), in seconds.
    double checkSeconds() const { return 1e-9 * double(nanoseconds_.load(std::memory_order_relaxed)); }
    void resetCounters();

private:
    template <typename Query>
    auto timed(const Query &query) const;
    /// signedClearance at the state's pose, timed as one query.
    SignedClearance signedClearanceOf(const ompl::base::State *state) const;
    template <typename Query>
    auto counted(const Query &query) const;

    std::shared_ptr<const CollisionChecker> checker_;
    CollisionScene scene_;
    bool planar_;
    mutable QueryContextPool contexts_;
    mutable std::atomic<std::uint64_t> checks_{0};
    mutable std::atomic<std::uint64_t> nanoseconds_{0};
};

using StateValidityCheckerPtr = std::shared_ptr<StateValidityChecker>;
}  // namespace hcd
