// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/ompl/continuous_motion_validator.h"

#include <ompl/base/SpaceInformation.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace hcd
{
namespace
{
// Rotation angle of R1^T R2 in [0, pi]: the angle OMPL's shortest-path interpolation sweeps.
double rotationAngle(const Mat3 &r1, const Mat3 &r2)
{
    const double c = 0.5 * ((r1.transpose() * r2).trace() - 1.0);
    return std::acos(std::clamp(c, -1.0, 1.0));
}

constexpr std::size_t kMaxQueries = 100000;  // beyond this a motion is refused rather than certified
constexpr std::size_t kMaxRefinementQueries = 5000;  // bracketing a known contact stops here
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
    return finish(certify(s1, s2, false), s1, s2, nullptr, nullptr);
}

bool ContinuousMotionValidator::checkMotion(const ompl::base::State *s1, const ompl::base::State *s2,
                                            std::pair<ompl::base::State *, double> &lastValid) const
{
    return finish(certify(s1, s2, true), s1, s2, lastValid.first, &lastValid.second);
}

ContinuousMotionValidator::Report ContinuousMotionValidator::checkMotionDetailed(const ompl::base::State *s1,
                                                                                 const ompl::base::State *s2) const
{
    const Report report = certify(s1, s2, true);
    finish(report, s1, s2, nullptr, nullptr);
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
        if (lastValidState)
            si_->getStateSpace()->interpolate(s1, s2, report.lastFree, lastValidState);
    }
    return report.free;
}

ContinuousMotionValidator::Report ContinuousMotionValidator::certify(const ompl::base::State *s1,
                                                                     const ompl::base::State *s2, bool refine) const
{
    ompl::base::SpaceInformation *si = si_;
    const ompl::base::StateSpacePtr &space = si->getStateSpace();
    const bool planar = validity_->planar();
    struct StateHolder
    {
        ompl::base::SpaceInformation *si;
        ompl::base::State *state;
        ~StateHolder() { si->freeState(state); }
    } holder{si, si->allocState()};
    ompl::base::State *state = holder.state;
    const auto poseAt = [&](double tau) {
        space->interpolate(s1, s2, tau, state);
        return poseOfState(state, planar);
    };
    Report report;
    // A contact at `at` with [0, lastFree] proven free; it also blocks the motion there when the
    // bracket is within the tolerance (or when blocking is all that was asked for).
    const auto contact = [&](double lastFree, double at) {
        report.lastFree = lastFree;
        report.contactFound = true;
        report.contactAt = at;
        report.blocked = true;
        report.blockedAt = at;
        return report;
    };
    if (validity_->poseCollides(poseOfState(s1, planar)))
        return contact(0.0, 0.0);
    if (applyBounds_ && !si->satisfiesBounds(s2))
        return report;  // refused, no contact

    // A pass of collision checks at OMPL's resolution rejects most blocked motions cheaply: from s2
    // backwards when only validity matters (as OMPL's discrete validator
    // does: motions into an obstacle usually end in it), from s1 onwards when the first contact is
    // wanted, since then it only needs to be searched for before the first colliding sample.
    const unsigned n = std::max(1u, space->validSegmentCount(s1, s2));
    double end = 1.0;  // the search for the first contact stops here
    bool contactKnown = false;
    if (!refine)
    {
        // Every fourth sample: most blocked motions are caught, and free ones (which the
        // certification below settles anyway) pay a quarter of the discrete validator's cost.
        for (unsigned k = n; k >= 1; k = k > 4 ? k - 4 : 0)
            if (validity_->poseCollides(poseAt(double(k) / n)))
                return contact(0.0, double(k) / n);
    }
    else
        for (unsigned k = 1; k <= n; ++k)
            if (validity_->poseCollides(poseAt(double(k) / n)))
            {
                end = double(k) / n;
                contactKnown = true;
                break;
            }

    const RigidTransform p1 = poseOfState(s1, planar), p2 = poseOfState(s2, planar);
    // Per unit of tau a robot point p moves at most translationRate + angleRate * |p|.
    const double translationRate = (p2.translation - p1.translation).norm() * (1.0 + 1e-9);
    const double angleRate = rotationAngle(p1.rotation, p2.rotation) * (1.0 + 1e-9) + 1e-15;
    const double speed = translationRate + robotRadius_ * angleRate;
    if (!(speed > 0.0))
    {
        if (validity_->poseCollides(p2))
            return contact(0.0, 1.0);
        report.free = true;
        return report;
    }

    // Intervals still to certify, earliest on top. [0, certified] is proven free. Once a contact is
    // seen at `contactAt`, only [certified, contactAt] is searched further, down to the tolerance.
    struct Interval
    {
        double a, b;
    };
    // Start from OMPL's segments rather than [0, 1]: short intervals need small clearances, which
    // the proximity query settles quickly. The earliest segment is processed first when the first
    // contact is wanted (so [0, certified] is a proven-free prefix); otherwise the last one is, as
    // blocked motions mostly end in the obstacle.
    std::vector<Interval> pending;
    const unsigned segments = std::max(1u, unsigned(std::ceil(end * n - 1e-9)));
    for (unsigned i = 1; i <= segments; ++i)
    {
        const unsigned k = refine ? segments + 1 - i : i;
        pending.push_back({end * double(k - 1) / segments, end * double(k) / segments});
    }
    double certified = 0.0, contactAt = contactKnown ? end : 2.0, nearContactAt = 2.0;
    std::size_t queries = 0;
    bool refused = false;
    // The bracket to reach: the tolerance, or (for planners) one of OMPL's segments if that is
    // coarser, which is what OMPL's discrete validator offers as a last valid state.
    const double tolerance = toleranceIsSegment_ ? std::max(contactTolerance_, 1.0 / n) : contactTolerance_;
    while (!pending.empty() && !(contactAt <= 1.0 && contactAt - certified <= tolerance))
    {
        const Interval iv = pending.back();
        pending.pop_back();
        const double mid = 0.5 * (iv.a + iv.b);
        const double half = 0.5 * (iv.b - iv.a);
        const double needed = speed * half;  // for the farthest robot point
        const RigidTransform pose = poseAt(mid);
        if (++queries > (contactAt <= 1.0 ? kMaxRefinementQueries : kMaxQueries))
        {
            refused = true;  // or, with a contact known, the bracket is left wider than the tolerance
            break;
        }
        if (!validity_->poseWithinSweptDistance(pose, translationRate * half, angleRate * half, robotRadius_))
        {
            if (refine)
                certified = iv.b;  // intervals are taken in order: the free prefix grows
            continue;
        }
        if (validity_->poseCollides(pose))
        {
            contactAt = mid;
            if (!refine || contactAt - certified <= tolerance)
                break;
            pending.clear();
            pending.push_back({certified, contactAt});
            continue;
        }
        // Neither certified nor colliding: some robot point is within its reach of the environment.
        // Once that reach is below the smallest clearance ever certified, the middle state is a near
        // contact, which blocks the motion as a contact does. Verdicts stop there. The first-contact
        // search stops there only when the near contact lies within the tolerance of the proven-free
        // prefix (intervals are taken in order, so iv.a == certified) and, once a real contact is
        // known, only after splitting to 1e-3 of the tolerance: a grazing approach (distance falling
        // quadratically in time) is where certification stalls, and elsewhere the bracket closes on
        // the contact itself.
        const bool nearContact = needed < minimumClearance_;
        if (!refine && nearContact)
        {
            refused = true;
            break;
        }
        if (refine && nearContact && mid - certified <= tolerance &&
            (contactAt > 1.0 || iv.b - iv.a < 1e-3 * tolerance))
        {
            nearContactAt = mid;
            break;
        }
        if (!(iv.a < mid && mid < iv.b))
        {
            refused = true;  // at the resolution of doubles: nothing left to split
            break;
        }
        pending.push_back({mid, iv.b});
        pending.push_back({iv.a, mid});
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
    else if (contactAt <= 1.0 && (!refine || contactAt - certified <= tolerance))
    {
        report.blocked = true;
        report.blockedAt = contactAt;
    }
    report.free = !refused && contactAt > 1.0 && nearContactAt > 1.0 && pending.empty();
    return report;
}
}  // namespace hcd
