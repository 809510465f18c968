// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/ompl/continuous_motion_validator.h"

#include <ompl/base/SpaceInformation.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

namespace hcd
{
namespace
{
// How far OMPL's interpolation from s1 to s2 moves the robot per unit of tau: a robot point p (robot
// frame) moves at most translation + angle * |p| (|(p.x, p.y)| for SE(2) with a checker that counts
// turns from the robot's z axis, CollisionChecker::turnsAboutRobotZ). `endTurn` is the turn left
// between OMPL's state at tau = 1 and s2 itself: SO3's interpolation keeps R1 to the end below
// about 9e-5 rad, so s2 is reached by a turn of the whole angle that no interval sweeps; every
// interval's slack covers it.
// Margins cover rounding in the bound: the lengths and angles are computed in floating point.
struct MotionRates
{
    double translation = 0.0;  ///< world units per unit of tau
    double angle = 0.0;        ///< radians per unit of tau
    double endTurn = 0.0;      ///< radians, added to every interval's radial slack
    /// OMPL's interpolation keeps s1's rotation at every tau (the endTurn case): its states before
    /// tau = 1 are then s1's pose translated, which the first-contact search sweeps as they are.
    bool startRotationHeld = false;
    bool bounded = false;  ///< false: non-finite states or quaternions off unit length
};

// p1 and p2 are the poses of s1 and s2 (the callers have them already).
MotionRates motionRates(const ompl::base::StateSpacePtr &space, const ompl::base::State *s1,
                        const ompl::base::State *s2, const RigidTransform &p1, const RigidTransform &p2, bool planar,
                        ompl::base::State *scratch)
{
    MotionRates rates;
    const double turn = interpolationTurn(s1, s2, planar);
    if (!p1.isFinite() || !p2.isFinite() || !std::isfinite(turn))
        return rates;
    space->interpolate(s1, s2, 1.0, scratch);
    const double endTurn = interpolationTurn(scratch, s2, planar);
    if (!std::isfinite(endTurn))
        return rates;
    rates.translation = (p2.translation - p1.translation).norm() * (1.0 + 1e-9);
    rates.angle = turn * (1.0 + 1e-9) + 1e-14;
    rates.endTurn = endTurn * (1.0 + 1e-9);
    // The state at tau = 1 carrying s1's rotation bit for bit is SO3's copy of s1 (a turn too small
    // for slerp), which it makes at every tau; slerp's own end state is s2's rotation, rounded.
    rates.startRotationHeld = endTurn > 0.0 && poseOfState(scratch, planar).rotation == p1.rotation;
    rates.bounded = std::isfinite(rates.translation);
    return rates;
}

constexpr std::size_t kMaxQueries = 100000;          // beyond this a motion is refused rather than certified
constexpr std::size_t kMaxRefinementQueries = 5000;  // bracketing a known contact stops here

// Reverses the low `bits` bits of i.
std::uint64_t reverseBits(std::uint64_t i, unsigned bits)
{
    std::uint64_t r = 0;
    for (unsigned b = 0; b < bits; ++b, i >>= 1)
        r = (r << 1) | (i & 1u);
    return r;
}

// The verdict path's raked collision checks: about one per kRakeStride of OMPL's samples (rounded
// to a power of two); certification then starts from the intervals between raked states.
// Measured with bench/motion_comparison.cpp (bench/README.md, section 3).
constexpr unsigned kRakeStride = 8;

// The states of one motion as the robot's poses: OMPL's interpolation from s1 to s2, into a
// scratch state of the space that is freed with this.
class MotionPoses
{
public:
    MotionPoses(ompl::base::SpaceInformation &si, const ompl::base::State *s1, const ompl::base::State *s2, bool planar)
        : si_(&si),
          s1_(s1),
          s2_(s2),
          planar_(planar),
          state_(si.allocState())
    {
    }
    MotionPoses(const MotionPoses &) = delete;
    MotionPoses &operator=(const MotionPoses &) = delete;
    ~MotionPoses() { si_->freeState(state_); }

    /// The pose at fraction tau of the motion (interpolated into the scratch state).
    RigidTransform at(double tau)
    {
        si_->getStateSpace()->interpolate(s1_, s2_, tau, state_);
        return poseOfState(state_, planar_);
    }
    /// The scratch state, for other interpolations of the same motion.
    ompl::base::State *scratch() { return state_; }

private:
    ompl::base::SpaceInformation *si_;
    const ompl::base::State *s1_;
    const ompl::base::State *s2_;
    bool planar_;
    ompl::base::State *state_;
};

// The rates of a motion the validator checks, or nullopt for one it refuses without a contact: s2
// beyond the space's bounds (where bounds apply), or rates that cannot be bounded. p1 and p2 are
// the poses of s1 and s2.
std::optional<MotionRates> admissibleRates(const ompl::base::SpaceInformation &si, bool applyBounds,
                                           const ompl::base::State *s1, const ompl::base::State *s2,
                                           const RigidTransform &p1, const RigidTransform &p2, bool planar,
                                           ompl::base::State *scratch)
{
    if (applyBounds && !si.satisfiesBounds(s2))
        return std::nullopt;
    const MotionRates rates = motionRates(si.getStateSpace(), s1, s2, p1, p2, planar, scratch);
    if (!rates.bounded)
        return std::nullopt;
    return rates;
}
// The search for a first contact starts from intervals of this many of OMPL's segments: wide enough
// for the grid to prove many at once (a sweep of several cells goes to it alone), and split where
// it cannot. Measured with bench/motion_comparison.cpp against single segments (bench/README.md,
// section 3): Maze_planar's lastValid 24% cheaper at the median and 16% on average, cubicles' 10%
// on average, alpha-1.5 level; 8 segments measured alike on Maze_planar and worse on alpha-1.5.
constexpr unsigned kCertifyStartSegments = 4;

// A known contact is narrowed by collision checks to within this fraction of the bracket's
// tolerance after a free state before the prefix is certified. Measured with the same motions
// (bench/README.md, section 3): a half and a quarter alike, a whole tolerance a little dearer.
constexpr double kNarrowing = 0.5;

// Near-pair fronts: once an interval's swept query fails, every triangle pair that may come within
// its slack is listed (at most kFrontLimit of them, or none); its sub-intervals then test only those
// pairs, since every other pair is proved apart over the whole interval. Measured with
// bench/motion_comparison.cpp (bench/README.md, section 3).
constexpr std::size_t kFrontLimit = 64;
// Listing costs a whole traversal without the early exit: only intervals at least this many
// splits below a starting interval list their pairs, where the near contact has shown itself
// persistent (listing from the first failure made Maze's and alpha-1.5's means 20-50% worse).
// Splits of sweeps too wide for the exact query count too: an interval they leave lists at its
// first exact failure (counting only exact failures measured level, within the noise).
constexpr int kFrontDepth = 2;

// A part [a, b] of the motion (fractions) still to certify.
struct MotionInterval
{
    double a, b;
    int front = -1;  ///< the near pairs this interval tests (a front of IntervalChecks), -1: all
    int depth = 0;   ///< splits below the starting interval
};

// Whether an interval spans at most one of the motion's n validity segments: where the verdict and
// the first-contact search test its middle state before splitting it (see verdict()).
bool spansAtMostOneSegment(const MotionInterval &iv, unsigned n) { return (iv.b - iv.a) * double(n) <= 1.0; }

// A sweep wider than this many of the first layer's cells (the clearance grid's) is proved by the
// first layer or split, never sent to the exact query: that query grows every box by the whole
// sweep and prunes poorly, while halves are often proved by the grid alone (bench/README.md,
// section 3, "Wide sweeps": Maze_planar's verdict 31% cheaper on average, alpha-1.5's 17%).
constexpr double kExactSweepCells = 3.0;

// Pairs kept in the fronts of one motion at most: beyond, intervals query the whole scene again
// (a bound on memory, 128 KiB, whatever the number of intervals).
constexpr std::size_t kMaxFrontPairs = std::size_t(1) << 14;

// The swept test of one interval at its middle state, with the near-pair fronts of one motion.
class IntervalChecks
{
public:
    struct Outcome
    {
        bool certified = false;  ///< nothing comes near on the interval
        bool colliding = false;  ///< the middle state collides
        int childFront = -1;     ///< the front its halves (or a bracket inside it) test
    };

    /// `listedFronts` counts the fronts listed and `wideSweeps` the intervals too wide for the exact
    /// query; `useFronts` false queries the whole scene always.
    IntervalChecks(const StateValidityChecker &validity, double robotRadius, QueryContext &context, bool useFronts,
                   std::atomic<std::uint64_t> &listedFronts, std::atomic<std::uint64_t> &wideSweeps)
        : validity_(validity),
          robotRadius_(robotRadius),
          exactSweepAbove_(kExactSweepCells * validity.checker().firstLayerCellSize()),
          context_(context),
          useFronts_(useFronts),
          listedFronts_(listedFronts),
          wideSweeps_(wideSweeps)
    {
    }

    /// `testMiddle` false: a middle state is not checked for collision (`colliding` stays false)
    /// unless a front tests it with the interval.
    Outcome check(const MotionInterval &iv, const RigidTransform &middle, double translationSlack, double radialSlack,
                  bool testMiddle)
    {
        Outcome out;
        if (iv.front >= 0)
        {
            // Only these pairs can come near on this interval; a pair that touches is a collision.
            const std::vector<TrianglePair> &front = fronts_[std::size_t(iv.front)];
            out.colliding =
                validity_.poseSweptNearPairsAmong(middle, translationSlack, radialSlack, front, near_, context_);
            out.certified = near_.empty();
            // The filter keeps the pairs' order: a front of the same size is the same front.
            if (!out.certified)
                out.childFront = near_.size() == front.size() ? iv.front : addFront();
            return out;
        }
        if (exactSweepAbove_ > 0.0 && translationSlack + radialSlack * robotRadius_ > exactSweepAbove_)
        {
            // Too wide for the exact query: the first layer's proof, or halves (no front listed).
            wideSweeps_.fetch_add(1, std::memory_order_relaxed);
            out.certified = validity_.poseSweptFreeByFirstLayer(middle, translationSlack, radialSlack);
            out.colliding = !out.certified && testMiddle && validity_.poseCollides(middle, context_);
            return out;
        }
        if (!validity_.poseWithinSweptDistance(middle, translationSlack, radialSlack, robotRadius_, context_))
        {
            out.certified = true;
            return out;
        }
        out.colliding = testMiddle && validity_.poseCollides(middle, context_);
        // A colliding middle ends the verdict and narrows the bracket: no front for it. (An untested
        // middle may collide and get a front: its halves then test the pairs that touch there.)
        if (useFronts_ && !out.colliding && iv.depth >= kFrontDepth && keptPairs_ + kFrontLimit <= kMaxFrontPairs &&
            validity_.poseListSweptNearPairs(middle, translationSlack, radialSlack, kFrontLimit, near_, context_))
        {
            listedFronts_.fetch_add(1, std::memory_order_relaxed);
            out.childFront = addFront();
        }
        return out;
    }

private:
    int addFront()
    {
        if (keptPairs_ + near_.size() > kMaxFrontPairs)
            return -1;
        keptPairs_ += near_.size();
        fronts_.push_back(near_);
        return int(fronts_.size()) - 1;
    }

    const StateValidityChecker &validity_;
    double robotRadius_;
    double exactSweepAbove_;  ///< sweeps wider than this (world units) skip the exact query; 0: none do
    QueryContext &context_;
    bool useFronts_;
    std::atomic<std::uint64_t> &listedFronts_;
    std::atomic<std::uint64_t> &wideSweeps_;
    std::vector<std::vector<TrianglePair>> fronts_;
    std::size_t keptPairs_ = 0;
    std::vector<TrianglePair> near_;
};
// Bisection needs about log2(1 / tolerance) levels to close a bracket, the exact first contact of a
// translation a fixed amount of LP work: on OMPL.app's problems the LP is 1.3-2x faster at a bracket
// of 1e-6 (check-motion's and the API's default) and up to 2x slower at the planning set-up's 1e-3
// (bench/README.md, "Pure translations"), so it is used for brackets finer than this.
constexpr double kExactTranslationBelow = 1e-4;
}  // namespace

ContinuousMotionValidator::ContinuousMotionValidator(const ompl::base::SpaceInformationPtr &si,
                                                     std::shared_ptr<const StateValidityChecker> validity,
                                                     double robotRadius, double sceneScale)
    : ompl::base::MotionValidator(si),
      validity_(std::move(validity)),
      // Margins cover rounding in the bound: the radius and the angle are computed in floating point.
      robotRadius_(robotRadius * (1.0 + 1e-9) + 1e-12 * sceneScale),
      minimumClearance_(1e-7 * std::max(sceneScale, 1e-300))
{
}

void ContinuousMotionValidator::setContactTolerance(double fraction, bool atMostOneSegment)
{
    contactTolerance_ = std::max(fraction, 1e-12);
    toleranceIsSegment_ = atMostOneSegment;
}

bool ContinuousMotionValidator::checkMotion(const ompl::base::State *s1, const ompl::base::State *s2) const
{
    const StateValidityChecker::Timing timing = validity_->timing();
    return finish(verdict(s1, s2, checkStart_), s1, s2, nullptr, nullptr);
}

bool ContinuousMotionValidator::checkMotion(const ompl::base::State *s1, const ompl::base::State *s2,
                                            std::pair<ompl::base::State *, double> &lastValid) const
{
    const StateValidityChecker::Timing timing = validity_->timing();
    return finish(verdictThenBracket(s1, s2, checkStart_, unwantedBelow_.load(std::memory_order_relaxed)), s1, s2,
                  lastValid.first, &lastValid.second);
}

ContinuousMotionValidator::Report ContinuousMotionValidator::checkMotionDetailed(const ompl::base::State *s1,
                                                                                 const ompl::base::State *s2) const
{
    const StateValidityChecker::Timing timing = validity_->timing();
    const Report report = verdictThenBracket(s1, s2, /*testStart=*/true, /*unwantedBelow=*/0.0);
    finish(report, s1, s2, nullptr, nullptr);
    return report;
}

ContinuousMotionValidator::Report ContinuousMotionValidator::verdictThenBracket(const ompl::base::State *s1,
                                                                                const ompl::base::State *s2,
                                                                                bool testStart,
                                                                                double unwantedBelow) const
{
    // Most motions a planner asks about are free, and proving that costs the same whether or not
    // the first contact is wanted: the verdict first, and the first contact searched for only on a
    // motion the verdict did not prove free.
    Report quick = verdict(s1, s2, testStart);
    if (quick.free)
        return quick;
    if (unwantedBelow > 0.0 && quick.contactFound && quick.contactAt <= unwantedBelow)
    {
        // The bracket is left open: the last valid state is s1 at 0, which the verdict tested or,
        // as checkMotion's contract has it, took as valid.
        quick.blocked = false;
        quick.lastFree = 0.0;
        return quick;
    }
    if (translations_ && quick.contactFound && quick.contactAt > 0.0)
        if (const std::optional<Report> exact = bracketTranslation(s1, s2, quick.contactAt))
            return *exact;
    return certify(s1, s2, quick.contactFound ? quick.contactAt : 2.0, unwantedBelow);
}

std::optional<ContinuousMotionValidator::Report>
ContinuousMotionValidator::bracketTranslation(const ompl::base::State *s1, const ompl::base::State *s2,
                                              double knownContact) const
{
    const bool planar = validity_->planar();
    const RigidTransform p1 = poseOfState(s1, planar), p2 = poseOfState(s2, planar);
    // OMPL interpolates a fixed rotation as itself (SE(2) yaw, SO(3) slerp with equal ends) and the
    // translation linearly: every robot point then moves by tau * (t2 - t1).
    if (p1.rotation != p2.rotation)
        return std::nullopt;
    const ompl::base::StateSpacePtr &space = si_->getStateSpace();
    const unsigned n = std::max(1u, space->validSegmentCount(s1, s2));
    const double tolerance = toleranceIsSegment_ ? std::max(contactTolerance_, 1.0 / n) : contactTolerance_;
    if (tolerance >= kExactTranslationBelow)
        return std::nullopt;
    // The first contact lies at or before the colliding state the verdict found: only that part of
    // the motion is searched (shorter swept boxes, fewer candidate pairs).
    TranslationContact first = translations_->firstContact(p1, knownContact * (p2.translation - p1.translation));
    if (!first.contact || !(first.time > 0.0))
        return std::nullopt;
    first.time *= knownContact;
    // The last valid state half the tolerance before the contact, a colliding state half the
    // tolerance after it: both are checked as any state is (solid semantics included), so that
    // rounding in the LP can never hand a planner a colliding state. A grazing contact (touch, then
    // apart) has no colliding state after it and is left to certify().
    Report report;
    report.lastFree = std::max(0.0, first.time - 0.5 * tolerance);
    const double blockedAt = std::min(1.0, first.time + 0.5 * tolerance);
    MotionPoses poses(*si_, s1, s2, planar);
    const QueryContextPool::Lease context = validity_->contexts().borrow();
    const auto collidesAt = [&](double tau) { return validity_->poseCollides(poses.at(tau), *context); };
    if (collidesAt(report.lastFree) || !collidesAt(blockedAt))
        return std::nullopt;
    report.contactFound = report.blocked = true;
    report.contactAt = report.blockedAt = blockedAt;
    translationBrackets_.fetch_add(1, std::memory_order_relaxed);
    return report;
}

bool ContinuousMotionValidator::finish(const Report &report, const ompl::base::State *s1, const ompl::base::State *s2,
                                       ompl::base::State *lastValidState, double *lastValidFraction) const
{
    (report.free ? validCount_ : invalidCount_).fetch_add(1, std::memory_order_relaxed);
    if (!report.free)
    {
        if (lastValidFraction)
            *lastValidFraction = report.lastFree;
        // s1 itself at 0: no interpolation towards an s2 that may be refused as unbounded.
        if (lastValidState && report.lastFree == 0.0)
            si_->copyState(lastValidState, s1);
        else if (lastValidState)
            si_->getStateSpace()->interpolate(s1, s2, report.lastFree, lastValidState);
    }
    return report.free;
}

ContinuousMotionValidator::Report ContinuousMotionValidator::certify(const ompl::base::State *s1,
                                                                     const ompl::base::State *s2, double knownContact,
                                                                     double unwantedBelow) const
{
    ompl::base::SpaceInformation *si = si_;
    const ompl::base::StateSpacePtr &space = si->getStateSpace();
    const bool planar = validity_->planar();
    // One context for every query of this motion (coherence between neighbouring states).
    const QueryContextPool::Lease context = validity_->contexts().borrow();
    MotionPoses poses(*si, s1, s2, planar);
    Report report;
    // s1 anchors the certified prefix (surfaces kept apart from a free state keep the robot free),
    // and the last valid state comes from it. The verdict before this search tested it when asked
    // (a colliding s1 is then the known contact at 0, bracketed below at once), or took it as valid,
    // as checkMotion's contract has it: not tested again.
    const RigidTransform p1 = poseOfState(s1, planar), p2 = poseOfState(s2, planar);
    const std::optional<MotionRates> rates =
        admissibleRates(*si, applyBounds_, s1, s2, p1, p2, planar, poses.scratch());
    if (!rates)
        return report;  // refused, no contact

    // Without a known contact, a pass of collision checks at OMPL's resolution from s1 onwards: the
    // first contact then only needs to be searched for before the first colliding sample. With one
    // (the verdict's raked contact), the pass is skipped: certification goes through the prefix in
    // order anyway, checks the middle of every interval of a segment or less it cannot certify, and
    // closes on the first contact it meets, so the pass mostly repeated those checks (lastValid 10% cheaper on Maze,
    // level elsewhere within the noise; bench/README.md section 3).
    const unsigned n = std::max(1u, space->validSegmentCount(s1, s2));
    double end = 1.0;        // the search for the first contact stops here
    double freeState = 0.0;  // a state known free (tested), before `end`
    bool contactKnown = knownContact <= 1.0;
    if (contactKnown)
        end = knownContact;  // only samples before it can hold an earlier contact
    for (unsigned k = 1; !contactKnown && k <= n && double(k) / n < end; ++k)
    {
        if (validity_->poseCollides(poses.at(double(k) / n), *context))
        {
            end = double(k) / n;
            contactKnown = true;
            break;
        }
        freeState = double(k) / n;
    }

    const double translationRate = rates->translation, angleRate = rates->angle;

    // Intervals still to certify, earliest on top. [0, certified] is proven free. Once a contact is
    // seen at `contactAt`, only [certified, contactAt] is searched further, down to the tolerance.
    IntervalChecks checks(*validity_, robotRadius_, *context, useFronts_, listedFronts_, wideSweeps_);
    // The bracket to reach: the tolerance, or (for planners) one of OMPL's segments if that is
    // coarser, which is what OMPL's discrete validator offers as a last valid state.
    const double tolerance = toleranceIsSegment_ ? std::max(contactTolerance_, 1.0 / n) : contactTolerance_;
    std::size_t queries = 0;
    // With a contact known, collision checks alone first bring it to within kNarrowing of the
    // tolerance after a free state (bisection), and certification then stops a whole tolerance
    // before it: a prefix that ends that far from the obstacle is certified by far fewer
    // intervals than one that runs up to the contact (bench/README.md, section 3, "lastValid:
    // the contact narrowed first"). Returns the colliding state nearest the free one.
    const auto narrow = [&](double freeAt, double collidingAt) {
        while (collidingAt - freeAt > kNarrowing * tolerance && collidingAt > unwantedBelow &&
               queries < kMaxRefinementQueries)
        {
            const double mid = 0.5 * (freeAt + collidingAt);
            if (!(freeAt < mid && mid < collidingAt))
                break;
            ++queries;
            (validity_->poseCollides(poses.at(mid), *context) ? collidingAt : freeAt) = mid;
        }
        return collidingAt;
    };
    // Certification of [from, contact - tolerance] is all a bracket on `contact` needs.
    const auto certifyBefore = [&](double from, double contact) {
        double to = contact - tolerance;
        while (contact - to > tolerance)  // rounding: the bracket must hold the tolerance
            to = std::nextafter(to, contact);
        return std::max(from, to);
    };
    double certified = 0.0, contactAt = 2.0, nearContactAt = 2.0;
    double target = end;  // the prefix to certify
    if (contactKnown)
    {
        contactAt = narrow(freeState, end);
        target = certifyBefore(0.0, contactAt);
    }
    // Start from groups of kCertifyStartSegments of OMPL's segments rather than [0, 1]: short
    // intervals need small clearances, which the proximity query settles quickly. The earliest
    // interval is processed first, so that [0, certified] is a proven-free prefix. As in the
    // verdict, an uncertified interval's middle state is tested for an earlier contact only once
    // the interval is at most one of OMPL's segments long (certification 2-12% fewer instructions
    // on section 3's motions; bench/README.md).
    std::vector<MotionInterval> pending;
    const unsigned segments = std::max(1u, unsigned(std::ceil(target * n / kCertifyStartSegments - 1e-9)));
    for (unsigned i = 1; i <= segments && target > 0.0; ++i)
    {
        const unsigned k = segments + 1 - i;
        // The last ends at `target` itself (target * k / k may round away from it).
        pending.push_back({target * double(k - 1) / segments, k == segments ? target : target * double(k) / segments});
    }
    bool refused = false;
    // A contact at or before `unwantedBelow` ends the search too: the caller throws away any last
    // valid state there.
    const auto settled = [&] {
        return (contactAt <= 1.0 && (contactAt - certified <= tolerance || contactAt <= unwantedBelow)) ||
               (nearContactAt <= 1.0 && nearContactAt - certified <= tolerance);
    };
    while (!pending.empty() && !settled())
    {
        const MotionInterval iv = pending.back();
        pending.pop_back();
        const double mid = 0.5 * (iv.a + iv.b);
        const double half = 0.5 * (iv.b - iv.a);
        // With a contact known, where OMPL holds s1's rotation (a turn too small for slerp), the
        // states before tau = 1 are translations of s1's pose: swept as such, without the end
        // turn's slack, whose reach would otherwise stall the bracket that far before the contact.
        // Elsewhere (and for a free verdict) every interval covers the turn as the verdict does.
        const bool translated = rates->startRotationHeld && contactAt <= 1.0 && iv.b < 1.0;
        const double radialSlack = translated ? 0.0 : angleRate * half + rates->endTurn;
        // How far the farthest robot point moves over half the interval: the verdict's measure of
        // a near contact (the end turn left out), so that both give up on the same intervals.
        const double needed = translationRate * half + (translated ? 0.0 : robotRadius_ * angleRate * half);
        const RigidTransform pose = poses.at(mid);
        if (++queries > (contactAt <= 1.0 ? kMaxRefinementQueries : kMaxQueries))
        {
            refused = true;  // or, with a contact known, the bracket is left wider than the tolerance
            break;
        }
        const IntervalChecks::Outcome outcome =
            checks.check(iv, pose, translationRate * half, radialSlack, /*testMiddle=*/spansAtMostOneSegment(iv, n));
        if (outcome.certified)
        {
            certified = iv.b;  // intervals are taken in order: the free prefix grows
            continue;
        }
        if (outcome.colliding)
        {
            // An earlier contact: narrowed like the first, between the free prefix and it.
            contactAt = narrow(certified, mid);
            if (settled())
                break;
            // The interval's front covers [certified, contactAt] (intervals are taken in order).
            pending.clear();
            pending.push_back({certified, certifyBefore(certified, contactAt), outcome.childFront});
            continue;
        }
        // Neither certified nor colliding: some robot point is within its reach of the environment.
        // Once that reach is below the smallest clearance ever certified, the middle state is a near
        // contact, which blocks the motion as a contact does. The first-contact search stops there
        // only when the near contact lies within the tolerance of the proven-free
        // prefix (intervals are taken in order, so iv.a == certified) and, once a real contact is
        // known, only after splitting to 1e-3 of the tolerance: a grazing approach (distance falling
        // quadratically in time) is where certification stalls, and elsewhere the bracket closes on
        // the contact itself.
        const bool nearContact = needed < minimumClearance_;
        if (nearContact && mid - certified <= tolerance && (contactAt > 1.0 || iv.b - iv.a < 1e-3 * tolerance))
        {
            nearContactAt = mid;
            break;
        }
        if (nearContact && contactAt > 1.0)
        {
            // No contact known, as when the verdict refused the motion for a near contact: that one
            // blocks it here too (the verdict and this search agree), so only [certified, mid] is
            // left to certify, down to the tolerance before it.
            nearContactAt = mid;
            pending.clear();
            pending.push_back({iv.a, mid, outcome.childFront, iv.depth + 1});
            continue;
        }
        if (!(iv.a < mid && mid < iv.b))
        {
            refused = true;  // at the resolution of doubles: nothing left to split
            break;
        }
        pending.push_back({mid, iv.b, outcome.childFront, iv.depth + 1});
        pending.push_back({iv.a, mid, outcome.childFront, iv.depth + 1});
    }
    report.lastFree = certified;
    if (contactAt <= 1.0)
    {
        report.contactFound = true;
        report.contactAt = contactAt;
    }
    if (nearContactAt <= 1.0)
    {
        report.blocked = true;
        report.blockedAt = nearContactAt;
    }
    else if (contactAt <= 1.0 && contactAt - certified <= tolerance)
    {
        report.blocked = true;
        report.blockedAt = contactAt;
    }
    report.free = !refused && contactAt > 1.0 && nearContactAt > 1.0 && pending.empty();
    return report;
}

ContinuousMotionValidator::Report ContinuousMotionValidator::verdict(const ompl::base::State *s1,
                                                                     const ompl::base::State *s2, bool testStart) const
{
    ompl::base::SpaceInformation *si = si_;
    const ompl::base::StateSpacePtr &space = si->getStateSpace();
    const bool planar = validity_->planar();
    // One context for every query of this motion (coherence between neighbouring states).
    const QueryContextPool::Lease context = validity_->contexts().borrow();
    MotionPoses poses(*si, s1, s2, planar);
    Report report;
    const auto contact = [&](double at) {
        report.contactFound = true;
        report.contactAt = at;
        report.blocked = true;
        report.blockedAt = at;
        return report;
    };
    const RigidTransform p1 = poseOfState(s1, planar);
    if (testStart && validity_->poseCollides(p1, *context))
        return contact(0.0);
    const RigidTransform p2 = poseOfState(s2, planar);
    const std::optional<MotionRates> rates =
        admissibleRates(*si, applyBounds_, s1, s2, p1, p2, planar, poses.scratch());
    if (!rates)
        return report;  // refused, no contact

    // Raked collision checks: states on a dyadic grid of m + 1 points (about one per `kRakeStride`
    // of OMPL's samples) visited coarse to fine, 1/2, 1/4, 3/4, 1/8, 5/8, ... (bit-reversed order),
    // so that a colliding motion is caught after a few checks wherever it collides, and the end
    // last. The first collision stops everything. The end goes last because planners often pass a
    // state they have tested as s2 (RRTConnect's goal tree extends from the new state to a tree
    // state), and because a motion whose end collides mostly collides inside as well: on
    // RRTConnect's motions this order tests 0.2-0.7 fewer free states per motion before the
    // first collision than the end first (bench/README.md, section 3).
    const unsigned n = std::max(1u, space->validSegmentCount(s1, s2));
    unsigned bits = 0;
    while ((1u << bits) * kRakeStride < n && bits < 20)
        ++bits;
    const std::uint64_t m = std::uint64_t(1) << bits;
    for (std::uint64_t i = 1; i < m; ++i)
    {
        const double tau = double(reverseBits(i, bits)) / double(m);
        if (validity_->poseCollides(poses.at(tau), *context))
            return contact(tau);
    }
    // s2 itself, which OMPL's state at tau = 1 differs from by the rates' endTurn.
    if (validity_->poseCollides(p2, *context))
        return contact(1.0);

    const double translationRate = rates->translation, angleRate = rates->angle;
    const double speed = translationRate + robotRadius_ * angleRate;

    // Certification of the dyadic intervals between the raked states, by bisection with the
    // swept-proximity query. The middle state of an interval no longer than one of OMPL's segments
    // is checked for collision before the interval splits (a contact there ends the verdict); a
    // longer interval splits without it. Nearly every motion that gets this far is free (all its
    // raked states were), so those checks mostly confirm free states: skipping them on the long
    // intervals saves 5% of checkMotion's instructions in RRTConnect's runs on alpha-1.5 and 2.5%
    // on Twistycool, while a contact between raked states is still found, a few splits later
    // (bench/README.md, section 3).
    IntervalChecks checks(*validity_, robotRadius_, *context, useFronts_, listedFronts_, wideSweeps_);
    std::vector<MotionInterval> pending;
    for (std::uint64_t k = 1; k <= m; ++k)
        pending.push_back({double(k - 1) / double(m), double(k) / double(m)});
    std::size_t queries = 0;
    while (!pending.empty())
    {
        const MotionInterval iv = pending.back();
        pending.pop_back();
        const double mid = 0.5 * (iv.a + iv.b);
        const double half = 0.5 * (iv.b - iv.a);
        if (++queries > kMaxQueries)
            return report;  // refused
        const IntervalChecks::Outcome outcome =
            checks.check(iv, poses.at(mid), translationRate * half, angleRate * half + rates->endTurn,
                         /*testMiddle=*/spansAtMostOneSegment(iv, n));
        if (outcome.certified)
            continue;
        if (outcome.colliding)
            return contact(mid);
        // A near contact is never accepted; nor is an interval doubles cannot split.
        if (speed * half < minimumClearance_ || !(iv.a < mid && mid < iv.b))
            return report;
        pending.push_back({mid, iv.b, outcome.childFront, iv.depth + 1});
        pending.push_back({iv.a, mid, outcome.childFront, iv.depth + 1});
    }
    report.free = true;
    return report;
}
}  // namespace hcd
