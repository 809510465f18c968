// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/ompl/state_validity_checker.h"

#include "hybridcd/query/penetration_estimate.h"

#include <ompl/base/SpaceInformation.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>

#include <chrono>

namespace hcd
{
StateValidityChecker::StateValidityChecker(const ompl::base::SpaceInformationPtr &si,
                                           std::shared_ptr<const CollisionChecker> checker, CollisionScene scene,
                                           bool planar)
    : ompl::base::StateValidityChecker(si),
      checker_(std::move(checker)),
      scene_(std::move(scene)),
      planar_(planar)
{
    specs_.clearanceComputationType = ompl::base::StateValidityCheckerSpecs::APPROXIMATE;
    specs_.hasValidDirectionComputation = false;
}

template <typename Query>
auto StateValidityChecker::timed(const Query &query) const
{
    // One query counted, and timed by a Timing scope of its own.
    const Timing timing(*this);
    return counted(query);
}

template <typename Query>
auto StateValidityChecker::counted(const Query &query) const
{
    checks_.fetch_add(1, std::memory_order_relaxed);
    return query();
}

StateValidityChecker::Timing::Timing(const StateValidityChecker &validity)
    : validity_(validity),
      start_(std::chrono::steady_clock::now())
{
}

StateValidityChecker::Timing::~Timing()
{
    const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start_);
    validity_.nanoseconds_.fetch_add(std::uint64_t(ns.count()), std::memory_order_relaxed);
}

bool StateValidityChecker::isValid(const ompl::base::State *state) const
{
    return si_->satisfiesBounds(state) && collisionFree(state);
}

bool StateValidityChecker::collisionFree(const ompl::base::State *state) const
{
    const RigidTransform pose = poseOfState(state, planar_);
    const QueryContextPool::Lease context = contexts_.borrow();
    return !timed([&] { return checker_->collides(pose, *context); });
}

SignedClearance StateValidityChecker::signedClearanceOf(const ompl::base::State *state) const
{
    const RigidTransform pose = poseOfState(state, planar_);
    const QueryContextPool::Lease context = contexts_.borrow();
    return timed([&] { return signedClearance(*checker_, scene_, pose, *context); });
}

double StateValidityChecker::clearance(const ompl::base::State *state) const { return signedClearanceOf(state).value; }

bool StateValidityChecker::isValid(const ompl::base::State *state, double &dist) const
{
    const SignedClearance clearance = signedClearanceOf(state);
    dist = clearance.value;
    // The collision check decides, as isValid(state) does: a free pose may have a distance that
    // rounds to 0.
    return si_->satisfiesBounds(state) && !clearance.colliding;
}

bool StateValidityChecker::isValid(const ompl::base::State *state, double &dist, ompl::base::State *validState,
                                   bool &validStateAvailable) const
{
    validStateAvailable = false;
    const bool valid = isValid(state, dist);
    if (valid || !validState)
        return valid;
    validStateAvailable = pushedOut(state, validState);
    return false;
}

bool StateValidityChecker::pushedOut(const ompl::base::State *state, ompl::base::State *out) const
{
    const PenetrationEstimate estimate =
        estimatePenetration(*checker_, scene_, poseOfState(state, planar_), *contexts_.borrow());
    if (!estimate.freePose)
        return false;
    // The pushed-out pose as a state: same orientation, new position.
    si_->copyState(out, state);
    const Vec3 &t = estimate.freePose->translation;
    if (planar_)
        out->as<ompl::base::SE2StateSpace::StateType>()->setXY(t.x(), t.y());
    else
        out->as<ompl::base::SE3StateSpace::StateType>()->setXYZ(t.x(), t.y(), t.z());
    return si_->satisfiesBounds(out) && collisionFree(out);
}

bool StateValidityChecker::poseCollides(const RigidTransform &worldFromRobot, QueryContext &context) const
{
    return counted([&] { return checker_->collides(worldFromRobot, context); });
}

bool StateValidityChecker::poseWithinSweptDistance(const RigidTransform &worldFromRobot, double translationSlack,
                                                   double radialSlack, double robotRadius, QueryContext &context) const
{
    return counted([&] {
        return checker_->withinSweptDistance(worldFromRobot, translationSlack, radialSlack, robotRadius, context);
    });
}

bool StateValidityChecker::poseSweptFreeByFirstLayer(const RigidTransform &worldFromRobot, double translationSlack,
                                                     double radialSlack) const
{
    return counted([&] { return checker_->sweptFreeByFirstLayer(worldFromRobot, translationSlack, radialSlack); });
}

bool StateValidityChecker::poseListSweptNearPairs(const RigidTransform &worldFromRobot, double translationSlack,
                                                  double radialSlack, std::size_t limit,
                                                  std::vector<TrianglePair> &near, QueryContext &context) const
{
    return counted([&] {
        return checker_->listSweptNearPairs(worldFromRobot, translationSlack, radialSlack, limit, near, context);
    });
}

bool StateValidityChecker::poseSweptNearPairsAmong(const RigidTransform &worldFromRobot, double translationSlack,
                                                   double radialSlack, const std::vector<TrianglePair> &pairs,
                                                   std::vector<TrianglePair> &near, QueryContext &context) const
{
    return counted([&] {
        return checker_->sweptNearPairsAmong(worldFromRobot, translationSlack, radialSlack, pairs, near, context);
    });
}

bool StateValidityChecker::poseWithinDistance(const RigidTransform &worldFromRobot, double delta,
                                              QueryContext &context) const
{
    return counted([&] { return checker_->withinDistance(worldFromRobot, delta, context); });
}

void StateValidityChecker::resetCounters()
{
    checks_.store(0);
    nanoseconds_.store(0);
}
}  // namespace hcd
