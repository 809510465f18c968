// SPDX-License-Identifier: BSD-3-Clause
// OMPL adapter: a MotionValidator that never accepts a motion that touches an obstacle.
//
// Along OMPL's interpolation from s1 to s2 (translation linear in the fraction tau, rotation at
// constant angular speed about the robot origin), no robot point moves farther than
//   B * |dtau|,   B = |t2 - t1| + r * angle(R1^T R2),
// where r bounds |p| over robot points (and a point p itself moves at most (|t2 - t1| + |p| angle)
// per unit of tau). So if at the middle of an interval [a, b] every robot part is farther than its
// own reach times (b - a) / 2 from every obstacle, nothing on the interval touches; the hierarchy
// checks that per node, with each node's distance from the robot origin. The validator
// certifies [0, 1] by bisection with that proximity query (an early-exit query, about as cheap as a
// collision check when clearances are large), splitting only the intervals it cannot certify, in
// order from tau = 0 so the first contact found is the earliest. An interval still uncertified two
// splits below its starting interval lists the robot-environment triangle pairs that may come within
// its reach (CollisionChecker::listSweptNearPairs, at most 64); its parts then test only those pairs,
// every other pair being proved apart over the whole interval. When a last valid state is asked
// for, the search then narrows to the bracket [last certified, contact] until it is shorter than
// the contact tolerance. A middle state is tested for collision once its interval spans at most one
// of OMPL's segments (longer intervals split without it: nearly all of them belong to free motions).
// A motion is rejected when a middle state collides (contact found) or when
// an interval shrinks below a clearance too small to certify (1e-7 of the scene size, a near
// contact): a motion is never accepted on rounding alone. The angle is the one OMPL's interpolation
// turns (interpolationTurn: yaw as SO2 takes it, slerp's angle by atan2, exact for tiny turns);
// below about 9e-5 rad SO3's interpolation keeps R1 up to tau = 1 and s2 itself turns by the whole
// angle, so that end turn widens every interval's slack and s2 is checked as it is. States that no
// bound holds for (non-finite values, quaternions off unit length) are refused. When the first
// contact is asked for, the
// bracket closes on the first contact or near contact; the verdict runs first, and its contact
// confines the search to the motion before it (without one, a pass of collision checks at OMPL's
// resolution first finds the earliest colliding sample). The verdict alone (checkMotion without a
// last valid state) checks collisions at states raked over the whole motion
// (1/2, 1/4, 3/4, 1/8, 5/8, ... down to about every eighth of OMPL's samples, then the end),
// stopping at the first collision, and only then certifies the intervals between them.
#pragma once

#include "hybridcd/ompl/state_validity_checker.h"
#include "hybridcd/query/translation_contact.h"

#include <ompl/base/MotionValidator.h>

#include <algorithm>
#include <atomic>
#include <memory>
#include <optional>

namespace hcd
{
class ContinuousMotionValidator : public ompl::base::MotionValidator
{
public:
    /// `robotRadius` bounds |p| over robot points p in the robot frame, or |(p.x, p.y)| when the
    /// checker's scene turns about the robot's z axis (CollisionScene::turnsAboutRobotZ, SE(2));
    /// `sceneScale` sets the smallest clearance certified (1e-7 of it). Queries go through
    /// `validity` so they are counted.
    ContinuousMotionValidator(const ompl::base::SpaceInformationPtr &si,
                              std::shared_ptr<const StateValidityChecker> validity, double robotRadius,
                              double sceneScale);

    bool checkMotion(const ompl::base::State *s1, const ompl::base::State *s2) const override;

    /// On failure, lastValid.first (if not null) receives a collision-free state on the motion and
    /// lastValid.second its fraction in [0, 1): [0, lastValid.second] is proven free, and the motion
    /// is blocked (a contact or a near contact, see Report) within the contact tolerance after it.
    /// s1 anchors the proven-free prefix: it is tested when setStartChecked says so (the first
    /// contact is then s1 itself if it collides), else taken as valid, as the verdict takes it
    /// (checkMotion's contract). A contact at or before setUnwantedLastValidBelow's fraction ends the search
    /// earlier, with the bracket left open (see there).
    bool checkMotion(const ompl::base::State *s1, const ompl::base::State *s2,
                     std::pair<ompl::base::State *, double> &lastValid) const override;

    /// What a detailed check found. When not `free`, [0, lastFree] is proven collision-free.
    /// `blocked`: the motion is blocked at `blockedAt`, with lastFree < blockedAt <= lastFree +
    /// contact tolerance: there the robot touches the environment, or is not proven farther from it
    /// than the smallest clearance ever certified (1e-7 of the scene size), a near contact that is
    /// never accepted either. `contactFound`: the robot touches the environment at `contactAt`
    /// (>= blockedAt). A refused motion (too close to call, or the query budget spent) may have
    /// neither; the bracket promise holds whenever `blocked` is set, which a first-contact search
    /// always sets unless its budget of 5,000 queries runs out.
    struct Report
    {
        bool free = false;
        double lastFree = 0.0;
        bool blocked = false;
        double blockedAt = 1.0;
        bool contactFound = false;
        double contactAt = 1.0;
    };

    /// The full check, with the first blocking point bracketed to the contact tolerance.
    Report checkMotionDetailed(const ompl::base::State *s1, const ompl::base::State *s2) const;

    /// How closely the first contact is bracketed when a last valid state is asked for, as a
    /// fraction of the motion (default 1e-6): lastValid.second is at most this much before it.
    /// With `atMostOneSegment`, the bracket may also be as wide as one of OMPL's validity segments
    /// when that is coarser (what OMPL's discrete validator offers planners).
    void setContactTolerance(double fraction, bool atMostOneSegment = false);

    /// On motions along which the rotation stays the same (pure translations), the first contact of
    /// a blocked motion is then found exactly by the time-augmented LP (query/translation_contact.h)
    /// instead of by bisection, when the contact tolerance is finer than 1e-4 of the motion (where
    /// that is faster); the last valid state is placed half the tolerance before it and checked.
    /// The finder must be built on the validity checker's scene. Null turns it off.
    void setTranslationContactFinder(std::shared_ptr<const TranslationContactFinder> finder)
    {
        translations_ = std::move(finder);
    }

    /// Whether checkMotion tests the motion's first state itself (default false;
    /// checkMotionDetailed always does). OMPL's
    /// planners pass only valid first states (checkMotion's contract; OMPL's discrete validator does
    /// not test s1 either), and a planner's s1 is a state it has just tested. A motion from a
    /// colliding s1 is never accepted either way: certification covers the whole motion, s1
    /// included; untested, it is refused after bisecting down to s1 rather than at once.
    void setStartChecked(bool check) { checkStart_ = check; }

    /// Planners that throw away a last valid state at or before a fraction of the motion
    /// (min_valid_path_fraction: 0.2 for KPIECE1 and STRIDE, 0.5 for BKPIECE1 and LBKPIECE1) need
    /// no bracket there. Once a state at or before `fraction` is found colliding, checkMotion with
    /// a last valid state stops searching: lastValid.second is then the proven-free prefix found so
    /// far (0 at least, s1), below that colliding state and so at or below `fraction`, which such a
    /// planner discards as it would the exact one. When the verdict's own contact lies there, that
    /// prefix is s1 at 0, untested unless setStartChecked (taken as valid, as checkMotion's
    /// contract has it). 0 (the default, and for a value that is not a number) always brackets;
    /// checkMotionDetailed always does. The planner catalogue's kpiece, bkpiece, lbkpiece and
    /// stride set it for their run and restore it after. It holds for every caller of this
    /// validator: two planners solving at once on one space information share it.
    void setUnwantedLastValidBelow(double fraction)
    {
        unwantedBelow_.store(fraction > 0.0 ? std::min(fraction, 1.0) : 0.0);  // NaN: 0
    }
    double unwantedLastValidBelow() const { return unwantedBelow_.load(); }

    /// Whether s2 must satisfy the state-space bounds (default true, as OMPL's validators do).
    void setApplyBounds(bool apply) { applyBounds_ = apply; }

    /// The smallest clearance the validator certifies (1e-7 of the scene size): a robot not proven
    /// farther than this from the environment is a near contact.
    double minimumClearance() const { return minimumClearance_; }

    /// Whether uncertified intervals list their near triangle pairs for their parts to test (on by
    /// default; off, every part queries the whole scene). The verdicts are the same either way.
    void setNearPairFronts(bool use) { useFronts_ = use; }
    /// Fronts listed so far (CollisionChecker::listSweptNearPairs calls that succeeded).
    std::uint64_t nearPairFrontsListed() const { return listedFronts_.load(); }
    /// Intervals whose sweep was too wide for the exact query, proved by the first layer (the
    /// clearance grid) or split, so far.
    std::uint64_t wideSweeps() const { return wideSweeps_.load(); }

    std::uint64_t validMotions() const { return validCount_.load(); }
    std::uint64_t invalidMotions() const { return invalidCount_.load(); }
    /// Blocked motions bracketed by their exact first contact (see setTranslationContactFinder).
    std::uint64_t exactTranslationBrackets() const { return translationBrackets_.load(); }

private:
    /// The first-contact search (checkMotionDetailed and checkMotion with a last valid state).
    /// `knownContact`, when at most 1, is a fraction where the robot is known to collide: the
    /// search is then confined to the motion before it.
    /// s1 is not tested here: the verdict before it tested s1 or took it as valid.
    /// `unwantedBelow`: the search also stops once a colliding state at or before it is known
    /// (setUnwantedLastValidBelow), with the bracket left open.
    Report certify(const ompl::base::State *s1, const ompl::base::State *s2, double knownContact = 2.0,
                   double unwantedBelow = 0.0) const;
    /// The verdict alone (no bracket): raked collision checks, then certification of what is left.
    Report verdict(const ompl::base::State *s1, const ompl::base::State *s2, bool testStart) const;
    /// The bracket of a blocked pure translation from its exact first contact, searched for on
    /// [0, knownContact] (a fraction where the robot collides); nullopt when the motion rotates or
    /// the answer cannot be confirmed (certify() then decides).
    std::optional<Report> bracketTranslation(const ompl::base::State *s1, const ompl::base::State *s2,
                                             double knownContact) const;
    /// verdict(), then certify() when the motion was not proven free.
    Report verdictThenBracket(const ompl::base::State *s1, const ompl::base::State *s2, bool testStart,
                              double unwantedBelow) const;
    bool finish(const Report &report, const ompl::base::State *s1, const ompl::base::State *s2,
                ompl::base::State *lastValidState, double *lastValidFraction) const;

    std::shared_ptr<const StateValidityChecker> validity_;
    std::shared_ptr<const TranslationContactFinder> translations_;
    double robotRadius_;
    double minimumClearance_;
    double contactTolerance_ = 1e-6;
    bool toleranceIsSegment_ = false;
    bool checkStart_ = false;
    bool applyBounds_ = true;
    bool useFronts_ = true;
    // Written by a planner's set-up while no query runs, read by every query: atomic all the same.
    std::atomic<double> unwantedBelow_{0.0};
    mutable std::atomic<std::uint64_t> validCount_{0}, invalidCount_{0}, translationBrackets_{0}, listedFronts_{0},
        wideSweeps_{0};
};
}  // namespace hcd
