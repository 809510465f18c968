// SPDX-License-Identifier: BSD-3-Clause
// Continuous motion validation: no tunnelling through thin walls, no misses from rotation, last
// valid states that are valid, first contacts bracketed, clearance against brute force.
#include "support/test_support.h"

#include "hybridcd/ompl/continuous_motion_validator.h"
#include "hybridcd/ompl/planning_problem.h"
#include "hybridcd/planners/planner_catalogue.h"
#include "hybridcd/query/checker_catalogue.h"

#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/base/PlannerData.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/geometric/planners/kpiece/BKPIECE1.h>
#include <ompl/geometric/planners/kpiece/KPIECE1.h>
#include <ompl/geometric/planners/kpiece/LBKPIECE1.h>
#include <ompl/geometric/planners/stride/STRIDE.h>
#include <ompl/util/RandomNumbers.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

using namespace hcd;
namespace ob = ompl::base;

namespace
{
// A problem built in memory: robot and environment meshes, SE3, bounds [-50, 50]^3.
LoadedProblem makeProblem(TriangleMesh robot, TriangleMesh environment)
{
    LoadedProblem p;
    p.config.name = "in-memory";
    p.config.volumeX = p.config.volumeY = p.config.volumeZ = std::make_pair(-50.0, 50.0);
    p.robot.mesh = std::make_shared<const TriangleMesh>(std::move(robot));
    p.world.mesh = std::make_shared<const TriangleMesh>(std::move(environment));
    p.scene.robot = p.robot.mesh;
    p.scene.environment = p.world.mesh;
    return p;
}

TriangleMesh thinWall()
{
    TriangleMesh wall;
    wall.vertices = {Vec3(0, -10, -10), Vec3(0, 10, -10), Vec3(0, 10, 10), Vec3(0, -10, 10)};
    wall.triangles = {{0, 1, 2}, {0, 2, 3}};
    return wall;
}

void setPose(ob::State *s, const Vec3 &t, double yaw)
{
    auto *st = s->as<ob::SE3StateSpace::StateType>();
    st->setXYZ(t.x(), t.y(), t.z());
    st->rotation().setAxisAngle(0, 0, 1, yaw);
}

// First colliding fraction found by brute force at `steps` uniform samples, or 2 if none.
double bruteForceFirstContact(const PlanningProblem &planning, const CollisionChecker &reference, const ob::State *a,
                              const ob::State *b, int steps)
{
    const auto si = planning.setup->getSpaceInformation();
    ob::State *s = si->allocState();
    double found = 2.0;
    for (int k = 0; k <= steps && found > 1.0; ++k)
    {
        si->getStateSpace()->interpolate(a, b, double(k) / steps, s);
        if (reference.collides(poseOfState(s, false)))
            found = double(k) / steps;
    }
    si->freeState(s);
    return found;
}
}  // namespace

TEST(MotionValidator, DiscreteTunnelsThroughAThinWallContinuousDoesNot)
{
    const LoadedProblem problem = makeProblem(test::boxMesh(Vec3(-0.5, -0.5, -0.5), Vec3(0.5, 0.5, 0.5)), thinWall());
    PlanningProblem planning = makePlanningProblem(problem, makeChecker("obb", problem.scene));
    planning.setup->setup();
    const auto si = planning.setup->getSpaceInformation();
    ob::ScopedState<> a(si), b(si);
    setPose(a.get(), Vec3(-20, 0, 0), 0.0);
    // Pick the end so that OMPL's samples (at its default resolution) straddle the wall.
    bool straddles = false;
    for (double end = 20.0; end < 24.0 && !straddles; end += 0.01)
    {
        setPose(b.get(), Vec3(end, 0, 0), 0.0);
        const unsigned n = si->getStateSpace()->validSegmentCount(a.get(), b.get());
        straddles = true;
        for (unsigned k = 0; k <= n; ++k)
            straddles = straddles && std::fabs(-20.0 + (end + 20.0) * k / n) > 0.6;
    }
    ASSERT_TRUE(straddles);
    const double end = b->as<ob::SE3StateSpace::StateType>()->getX();
    ASSERT_TRUE(si->isValid(a.get()));
    ASSERT_TRUE(si->isValid(b.get()));
    ob::DiscreteMotionValidator discrete(si);
    EXPECT_TRUE(discrete.checkMotion(a.get(), b.get())) << "the discrete validator was expected to tunnel";
    auto &continuous = dynamic_cast<ContinuousMotionValidator &>(*si->getMotionValidator());
    continuous.setContactTolerance(1e-6);  // the planning setup uses 1e-3
    EXPECT_FALSE(continuous.checkMotion(a.get(), b.get()));
    std::pair<ob::State *, double> last{si->allocState(), 0.0};
    EXPECT_FALSE(continuous.checkMotion(a.get(), b.get(), last));
    // The front face (x + 0.5) reaches the wall at x = 0 when the centre is at -0.5; the last valid
    // fraction is before that, within the default tolerance of 1e-6.
    const double contact = 19.5 / (end + 20.0);
    EXPECT_LE(last.second, contact);
    EXPECT_GE(last.second, contact - 1e-6);
    EXPECT_TRUE(si->isValid(last.first));
    si->freeState(last.first);
}

// The same scene at every scale: a unit box robot beside a thin wall, both scaled by s. A motion
// that ends 0.09 s from the wall, and one that slides along it at that gap, are free, and a motion
// through the wall is bracketed to 1e-6 of its length before the contact. The checkers' rounding
// allowance once had an absolute floor of 1e-10, which at s = 1e-9 took a free gap of 9e-11 for a
// near contact and moved the bracket at s = 1e-6 by 1e-5.
TEST(MotionValidator, NearMotionsAreFreeAndContactsBracketedAtEveryScale)
{
    for (const double s : {1e-9, 1e-6, 1.0, 1e6})
    {
        TriangleMesh wall = thinWall();
        for (Vec3 &v : wall.vertices)
            v *= s;
        LoadedProblem problem = makeProblem(test::boxMesh(Vec3::Constant(-0.5 * s), Vec3::Constant(0.5 * s)), wall);
        problem.config.volumeX = problem.config.volumeY = problem.config.volumeZ = std::make_pair(-50.0 * s, 50.0 * s);
        for (const std::string checker : {"auto", "obb", "aabb", "octree", "bruteforce"})
        {
            PlanningProblem planning = makePlanningProblem(problem, makeChecker(checker, problem.scene));
            planning.setup->setup();
            const auto si = planning.setup->getSpaceInformation();
            auto &continuous = dynamic_cast<ContinuousMotionValidator &>(*si->getMotionValidator());
            continuous.setContactTolerance(1e-6);
            ob::ScopedState<> a(si), b(si);
            const std::string where = checker + " at scale " + std::to_string(s);

            setPose(a.get(), Vec3(-5 * s, 0, 0), 0.0);
            setPose(b.get(), Vec3(-0.59 * s, 0, 0), 0.0);
            EXPECT_TRUE(continuous.checkMotion(a.get(), b.get())) << "towards the wall, " << where;
            setPose(a.get(), Vec3(-0.59 * s, -2 * s, 0), 0.0);
            setPose(b.get(), Vec3(-0.59 * s, 2 * s, 0), 0.0);
            EXPECT_TRUE(continuous.checkMotion(a.get(), b.get())) << "along the wall, " << where;

            // Through the wall: the front face (x + 0.5 s) reaches it at x = -0.5 s, fraction 0.45.
            setPose(a.get(), Vec3(-5 * s, 0, 0), 0.0);
            setPose(b.get(), Vec3(5 * s, 0, 0), 0.0);
            std::pair<ob::State *, double> last{si->allocState(), 0.0};
            EXPECT_FALSE(continuous.checkMotion(a.get(), b.get(), last)) << where;
            EXPECT_LE(last.second, 0.45 + 1e-12) << where;
            EXPECT_GE(last.second, 0.45 - 1e-6 - 1e-12) << where;
            EXPECT_TRUE(si->isValid(last.first)) << where;
            si->freeState(last.first);
        }
    }
}

// A cube sliding over a slab closer than the near-contact clearance, without touching (found by a
// held-out probe): the verdict refuses it, and the first-contact search used to split on below
// that clearance and accept it. Both now refuse it, the bracket ending at the near contact after a
// free prefix; a slide well above the clearance is accepted by both.
TEST(MotionValidator, VerdictAndBracketAgreeOnASlideBelowTheNearContactClearance)
{
    LoadedProblem problem = makeProblem(test::boxMesh(Vec3::Constant(-0.5), Vec3::Constant(0.5)),
                                        test::boxMesh(Vec3(-5, -5, -0.5), Vec3(5, 5, 0.5)));
    problem.config.volumeX = problem.config.volumeY = problem.config.volumeZ = std::make_pair(-6.0, 6.0);
    const auto reference = makeChecker("bruteforce", problem.scene);
    for (const std::string checker : {"auto", "obb", "bruteforce"})
    {
        PlanningProblem planning = makePlanningProblem(problem, makeChecker(checker, problem.scene));
        planning.setup->setup();
        const auto si = planning.setup->getSpaceInformation();
        auto &continuous = dynamic_cast<ContinuousMotionValidator &>(*si->getMotionValidator());
        continuous.setContactTolerance(1e-6);
        const double near = continuous.minimumClearance();
        ob::ScopedState<> a(si), b(si);
        std::pair<ob::State *, double> last{si->allocState(), 0.0};
        for (const double gap : {0.3 * near, 100.0 * near})
        {
            const std::string where = checker + ", gap " + std::to_string(gap / near) + " of the clearance";
            setPose(a.get(), Vec3(-1, 0, 1 + gap), 0.0);
            setPose(b.get(), Vec3(-0.99, 0, 1 + gap), 0.0);
            ASSERT_FALSE(reference->collides(poseOfState(a.get(), false))) << where;
            const bool verdict = continuous.checkMotion(a.get(), b.get());
            EXPECT_EQ(continuous.checkMotion(a.get(), b.get(), last), verdict) << where;
            EXPECT_EQ(verdict, gap > near) << where;
            if (!verdict)
            {
                EXPECT_TRUE(si->isValid(last.first)) << where;
                EXPECT_GE(last.second, 0.0) << where;
                EXPECT_LT(last.second, 1.0) << where;
            }
        }
        si->freeState(last.first);
    }
}

// Turns too small for slerp (below about 9e-5 rad): OMPL's states keep s1's rotation up to
// tau = 1, so a rod driven into a post reaches it at the same fraction whatever the turn. The
// first contact is bracketed to the tolerance among those states; the turn's reach at s2, which
// every interval of a verdict covers, once stalled the bracket up to 8e-5 before the contact.
TEST(MotionValidator, FirstContactOfATinyTurnIsBracketedToTheTolerance)
{
    TriangleMesh post = test::boxMesh(Vec3(4.6, -1, -1), Vec3(5.6, 1, 1));
    const LoadedProblem problem = makeProblem(test::boxMesh(Vec3(-4, -0.1, -0.1), Vec3(4, 0.1, 0.1)), post);
    const auto reference = makeChecker("bruteforce", problem.scene);
    for (const std::string checker : {"auto", "obb"})
    {
        PlanningProblem planning = makePlanningProblem(problem, makeChecker(checker, problem.scene));
        planning.setup->setup();
        const auto si = planning.setup->getSpaceInformation();
        auto &continuous = dynamic_cast<ContinuousMotionValidator &>(*si->getMotionValidator());
        continuous.setContactTolerance(1e-6);
        for (const double turn : {0.0, 1e-6, 1e-5, 5e-5, 8e-5})
        {
            ob::ScopedState<> a(si), b(si);
            setPose(a.get(), Vec3(-2, 0, 0), 0.0);
            setPose(b.get(), Vec3(2, 0, 0), turn);
            // The first colliding fraction among OMPL's states, by bisection with brute force.
            ob::ScopedState<> s(si);
            double freeAt = 0.0, collidingAt = 1.0;
            while (collidingAt - freeAt > 1e-12)
            {
                const double mid = 0.5 * (freeAt + collidingAt);
                si->getStateSpace()->interpolate(a.get(), b.get(), mid, s.get());
                (reference->collides(poseOfState(s.get(), false)) ? collidingAt : freeAt) = mid;
            }
            ASSERT_NEAR(collidingAt, 0.65, 1e-9) << "turn " << turn;
            std::pair<ob::State *, double> last{si->allocState(), 0.0};
            EXPECT_FALSE(continuous.checkMotion(a.get(), b.get(), last));
            EXPECT_LE(last.second, collidingAt) << checker << ", turn " << turn;
            EXPECT_GE(last.second, collidingAt - 1e-6 - 1e-12) << checker << ", turn " << turn;
            EXPECT_TRUE(si->isValid(last.first)) << checker << ", turn " << turn;
            si->freeState(last.first);
        }
    }
}

TEST(MotionValidator, ContactsBetweenRakedStatesOfAnyWidthAreFound)
{
    // A plate 0.01 thick along the motion crossing slabs, so that the colliding stretch of the
    // motion is a sliver (0.02 world units, about a hundredth of a segment), about half a segment,
    // or several of OMPL's segments, centred at offsets swept over a stretch wider than the
    // verdict's raked spacing (4 to 8 segments), so that many lie wholly between raked states,
    // where only certification and the middle states it tests can find them.
    const double start = -20.0, end = 20.0, thickness = 0.01;
    const TriangleMesh plate = test::boxMesh(Vec3(-0.5 * thickness, -0.5, -0.5), Vec3(0.5 * thickness, 0.5, 0.5));
    double segment = 0.0;  // world units along x per validity segment of this motion
    {
        const LoadedProblem probe = makeProblem(plate, test::boxMesh(Vec3(40, 40, 40), Vec3(41, 41, 41)));
        PlanningProblem probePlanning = makePlanningProblem(probe, makeChecker("obb", probe.scene));
        probePlanning.setup->setup();
        ob::ScopedState<> a(probePlanning.setup->getSpaceInformation()), b(probePlanning.setup->getSpaceInformation());
        setPose(a.get(), Vec3(start, 0, 0), 0.0);
        setPose(b.get(), Vec3(end, 0, 0), 0.0);
        segment = (end - start) / probePlanning.setup->getStateSpace()->validSegmentCount(a.get(), b.get());
    }
    for (const double stretchInSegments : {0.012, 0.5, 2.0, 5.0})
    {
        const double width = std::max(thickness, stretchInSegments * segment - thickness);  // the slab's
        for (int k = 0; k < 23; ++k)
        {
            // The slab's centre, from 6 segments before the middle of the motion to 6 after it.
            const double centre = (-6.0 + 12.0 * k / 22.0) * segment;
            const LoadedProblem problem = makeProblem(
                plate, test::boxMesh(Vec3(centre - 0.5 * width, -10, -10), Vec3(centre + 0.5 * width, 10, 10)));
            PlanningProblem planning = makePlanningProblem(problem, makeChecker("auto", problem.scene));
            planning.setup->setup();
            const auto si = planning.setup->getSpaceInformation();
            ob::ScopedState<> a(si), b(si);
            setPose(a.get(), Vec3(start, 0, 0), 0.0);
            setPose(b.get(), Vec3(end, 0, 0), 0.0);
            auto &validator = dynamic_cast<ContinuousMotionValidator &>(*si->getMotionValidator());
            // With near-pair fronts, the pairs listed on an uncertified interval find the contact;
            // without them, only the middle states tested do.
            for (const bool fronts : {true, false})
            {
                validator.setNearPairFronts(fronts);
                const std::string label = std::to_string(stretchInSegments) + " segments at " + std::to_string(centre) +
                                          (fronts ? ", fronts" : ", no fronts");
                EXPECT_FALSE(validator.checkMotion(a.get(), b.get())) << label;
                // The plate's front face reaches the slab's near face; the slab is crossed, so a real
                // contact is found (not a near contact or a refusal), at or after that fraction.
                const double contact = (centre - 0.5 * width - 0.5 * thickness - start) / (end - start);
                const ContinuousMotionValidator::Report report = validator.checkMotionDetailed(a.get(), b.get());
                EXPECT_FALSE(report.free) << label;
                EXPECT_TRUE(report.contactFound) << label;
                EXPECT_GE(report.contactAt, contact - 1e-9) << label;
                std::pair<ob::State *, double> last{si->allocState(), 0.0};
                EXPECT_FALSE(validator.checkMotion(a.get(), b.get(), last));
                EXPECT_LE(last.second, contact) << label;
                // Bracketed as the planning set-up asks: to 1e-3 of the motion or one segment.
                EXPECT_GE(last.second, contact - std::max(1e-3, segment / (end - start))) << label;
                EXPECT_TRUE(si->isValid(last.first)) << label;
                si->freeState(last.first);
            }
        }
    }
}

TEST(MotionValidator, RotationAloneCannotSweepPastAPost)
{
    // A 20-long bar turning 90 degrees about its centre; a thin post near its tip placed between two
    // of OMPL's samples. Translation is zero, so a bound on translation alone would miss it.
    const TriangleMesh bar = test::boxMesh(Vec3(-10, -0.05, -0.05), Vec3(10, 0.05, 0.05));
    LoadedProblem probe = makeProblem(bar, test::boxMesh(Vec3(40, 40, 40), Vec3(41, 41, 41)));
    PlanningProblem probePlanning = makePlanningProblem(probe, makeChecker("obb", probe.scene));
    probePlanning.setup->setup();
    {
        ob::ScopedState<> a(probePlanning.setup->getSpaceInformation()), b(probePlanning.setup->getSpaceInformation());
        setPose(a.get(), Vec3(0, 0, 0), 0.0);
        setPose(b.get(), Vec3(0, 0, 0), M_PI / 2);
        const unsigned n = probePlanning.setup->getStateSpace()->validSegmentCount(a.get(), b.get());
        const double angle = M_PI / 2 / n * 0.5;  // halfway between the first two samples
        const Vec3 c(9.9 * std::cos(angle), 9.9 * std::sin(angle), 0.0);
        probe = makeProblem(bar, test::boxMesh(c - Vec3(0.02, 0.02, 5), c + Vec3(0.02, 0.02, 5)));
    }
    PlanningProblem planning = makePlanningProblem(probe, makeChecker("obb", probe.scene));
    planning.setup->setup();
    const auto si = planning.setup->getSpaceInformation();
    ob::ScopedState<> a(si), b(si);
    setPose(a.get(), Vec3(0, 0, 0), 0.0);
    setPose(b.get(), Vec3(0, 0, 0), M_PI / 2);
    ASSERT_TRUE(si->isValid(a.get()));
    ASSERT_TRUE(si->isValid(b.get()));
    ob::DiscreteMotionValidator discrete(si);
    EXPECT_TRUE(discrete.checkMotion(a.get(), b.get())) << "the discrete validator was expected to miss the post";
    const auto reference = makeChecker("bruteforce", probe.scene);
    EXPECT_LE(bruteForceFirstContact(planning, *reference, a.get(), b.get(), 2000), 1.0);
    auto &continuous = dynamic_cast<ContinuousMotionValidator &>(*si->getMotionValidator());
    continuous.setContactTolerance(1e-6);
    const auto report = continuous.checkMotionDetailed(a.get(), b.get());
    EXPECT_FALSE(report.free);
    ASSERT_TRUE(report.contactFound);
    ASSERT_TRUE(report.blocked);
    EXPECT_LE(report.blockedAt - report.lastFree, 1e-6);
}

namespace
{
// Every state OMPL's interpolation visits at `samples` + 1 uniform fractions, and s2 itself, checked
// by brute force: the first colliding fraction, 2 when none collides (s2 colliding counts as 1).
double sampledFirstContact(const ob::SpaceInformationPtr &si, bool planar, const CollisionChecker &reference,
                           const ob::State *s1, const ob::State *s2, int samples)
{
    ob::ScopedState<> s(si);
    for (int k = 0; k <= samples; ++k)
    {
        si->getStateSpace()->interpolate(s1, s2, double(k) / samples, s.get());
        if (reference.collides(poseOfState(s.get(), planar)))
            return double(k) / samples;
    }
    return reference.collides(poseOfState(s2, planar)) ? 1.0 : 2.0;
}
}  // namespace

// Below about 9e-5 rad OMPL's SO3 interpolation keeps the start rotation up to tau = 1, so that
// s2 itself is the only state turned: a rod turning 8e-5 rad about its centre under a block 3e-5
// above its tip ends inside it, and the motion must be refused; 1e-3 above, it is free.
TEST(MotionValidator, TurnsTooSmallForSlerpStillReachTheEndState)
{
    const TriangleMesh rod = test::boxMesh(Vec3(-1.0, -0.05, -0.05), Vec3(1.0, 0.05, 0.05));
    for (const double gap : {3e-5, 1e-3})
    {
        SCOPED_TRACE(gap);
        const LoadedProblem problem = makeProblem(rod, test::boxMesh(Vec3(0.9, 0.05 + gap, -1.0), Vec3(1.0, 1.0, 1.0)));
        PlanningProblem planning = makePlanningProblem(problem, makeChecker("obb", problem.scene));
        planning.setup->setup();
        const auto si = planning.setup->getSpaceInformation();
        const auto reference = makeChecker("bruteforce", problem.scene);
        ob::ScopedState<> a(si), b(si), end(si);
        setPose(a.get(), Vec3::Zero(), 0.0);
        setPose(b.get(), Vec3::Zero(), 8e-5);
        // OMPL's state at tau = 1 keeps a's rotation: the turn to b is left to b itself.
        si->getStateSpace()->interpolate(a.get(), b.get(), 1.0, end.get());
        ASSERT_TRUE(poseOfState(end.get(), false).rotation == poseOfState(a.get(), false).rotation);
        ASSERT_FALSE(reference->collides(poseOfState(a.get(), false)));
        const bool endCollides = reference->collides(poseOfState(b.get(), false));
        ASSERT_EQ(endCollides, gap < 8e-5);
        auto &continuous = dynamic_cast<ContinuousMotionValidator &>(*si->getMotionValidator());
        EXPECT_EQ(continuous.checkMotion(a.get(), b.get()), !endCollides);
        std::pair<ob::State *, double> last{si->allocState(), 0.0};
        EXPECT_EQ(continuous.checkMotion(a.get(), b.get(), last), !endCollides);
        if (endCollides)
            EXPECT_FALSE(reference->collides(poseOfState(last.first, false)));
        si->freeState(last.first);
    }
}

// A yaw change of 1e-8 turns a 2-long needle's tip by 1e-8, past a speck 1.5e-9 to 3.5e-9 above
// it: acos of a rotation's trace rounds that angle to zero, the atan2 the validator uses does not.
TEST(MotionValidator, TinyYawChangesKeepTheirWholeSweep)
{
    LoadedProblem problem = makeProblem(test::boxMesh(Vec3(-1.0, -1e-10, -0.5), Vec3(1.0, 1e-10, 0.5)),
                                        test::boxMesh(Vec3(0.98, 1.5e-9, -0.5), Vec3(0.99, 3.5e-9, 0.5)));
    problem.config.planar = true;
    PlanningProblem planning = makePlanningProblem(problem, makeChecker("obb", problem.scene));
    planning.setup->setup();
    const auto si = planning.setup->getSpaceInformation();
    const auto reference = makeChecker("bruteforce", problem.scene);
    auto &continuous = dynamic_cast<ContinuousMotionValidator &>(*si->getMotionValidator());
    ob::ScopedState<> a(si), b(si);
    int blocked = 0;
    for (const double turn : {1e-8, -1e-8, 3e-8})
    {
        SCOPED_TRACE(turn);
        a->as<ob::SE2StateSpace::StateType>()->setXY(0.0, 0.0);
        a->as<ob::SE2StateSpace::StateType>()->setYaw(0.0);
        b->as<ob::SE2StateSpace::StateType>()->setXY(0.0, 0.0);
        b->as<ob::SE2StateSpace::StateType>()->setYaw(turn);
        const double sampled = sampledFirstContact(si, true, *reference, a.get(), b.get(), 2000);
        // Turning the other way (-1e-8) moves the tip away from the speck: free.
        ASSERT_EQ(sampled <= 1.0, turn > 0.0);
        const bool free = continuous.checkMotion(a.get(), b.get());
        EXPECT_EQ(free, sampled > 1.0);
        blocked += free ? 0 : 1;
        std::pair<ob::State *, double> last{si->allocState(), 0.0};
        if (!continuous.checkMotion(a.get(), b.get(), last))
        {
            EXPECT_LE(last.second, sampled);
            EXPECT_FALSE(reference->collides(poseOfState(last.first, true)));
        }
        si->freeState(last.first);
    }
    EXPECT_EQ(blocked, 2);
}

// States no bound holds for are refused, never accepted: a non-finite or unnormalised quaternion at
// either end (bounds not applied, as check-motion runs), where OMPL's slerp turns at an uneven rate.
TEST(MotionValidator, RefusesEndsNoBoundHoldsFor)
{
    const LoadedProblem problem = makeProblem(test::boxMesh(Vec3(-0.5, -0.5, -0.5), Vec3(0.5, 0.5, 0.5)), thinWall());
    PlanningProblem planning = makePlanningProblem(problem, makeChecker("obb", problem.scene));
    planning.setup->setup();
    const auto si = planning.setup->getSpaceInformation();
    auto &continuous = dynamic_cast<ContinuousMotionValidator &>(*si->getMotionValidator());
    continuous.setApplyBounds(false);
    ob::ScopedState<> a(si), b(si);
    setPose(a.get(), Vec3(-5, 0, 0), 0.0);
    setPose(b.get(), Vec3(-4, 0, 0), 0.3);
    ASSERT_TRUE(continuous.checkMotion(a.get(), b.get()));
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    for (const double w : {nan, inf, 2.0})
    {
        SCOPED_TRACE(w);
        setPose(b.get(), Vec3(-4, 0, 0), 0.3);
        b->as<ob::SE3StateSpace::StateType>()->rotation().w = w;
        EXPECT_FALSE(continuous.checkMotion(a.get(), b.get()));
        EXPECT_FALSE(continuous.checkMotion(b.get(), a.get()));
        std::pair<ob::State *, double> last{si->allocState(), 1.0};
        EXPECT_FALSE(continuous.checkMotion(a.get(), b.get(), last));
        si->freeState(last.first);
    }
}

namespace
{
// Random motions on an OMPL.app problem through checkMotionDetailed: a proven-free prefix that
// brute force finds free, and every motion that is not free blocked within the bracket after it
// (`tolerance`, or with `perSegment` the coarser of it and one of OMPL's validity segments, as
// the planning set-up brackets), by a contact or a near contact measured exactly.
void expectFirstContactsBracketed(const std::string &cfg, const std::string &checker, double tolerance, bool perSegment,
                                  double reach)
{
    const LoadedProblem problem = loadProblem(cfg);
    const bool planar = problem.config.planar;
    PlanningProblem planning = makePlanningProblem(problem, makeChecker(checker, problem.scene));
    planning.setup->setup();
    const auto si = planning.setup->getSpaceInformation();
    auto &validator = dynamic_cast<ContinuousMotionValidator &>(*si->getMotionValidator());
    validator.setContactTolerance(tolerance, perSegment);
    const auto reference = makeChecker("bruteforce", problem.scene);
    auto sampler = si->allocStateSampler();
    ob::State *a = si->allocState(), *b = si->allocState(), *s = si->allocState();
    int free = 0, colliding = 0, nearContacts = 0, attempts = 0;
    while ((free < 20 || colliding < 40) && ++attempts < 5000)
    {
        sampler->sampleUniform(a);
        if (!si->isValid(a))
            continue;
        sampler->sampleUniformNear(b, a, reach * si->getMaximumExtent());
        si->enforceBounds(b);
        const auto report = validator.checkMotionDetailed(a, b);
        // Never later than the true contact: brute force finds nothing on [0, lastFree].
        const int steps = 400;
        for (int k = 0; k <= steps; ++k)
        {
            si->getStateSpace()->interpolate(a, b, report.lastFree * k / steps, s);
            ASSERT_FALSE(reference->collides(poseOfState(s, planar)));
        }
        if (report.free)
        {
            ++free;
            continue;
        }
        ++colliding;
        // The promise: blocked within the bracket after the proven-free prefix, by a contact or a
        // near contact (not farther than the minimum clearance, measured exactly here).
        const unsigned segments = std::max(1u, si->getStateSpace()->validSegmentCount(a, b));
        const double bracket = perSegment ? std::max(tolerance, 1.0 / segments) : tolerance;
        ASSERT_TRUE(report.blocked) << "no bracket for a blocked motion";
        EXPECT_GT(report.blockedAt, report.lastFree);
        EXPECT_LE(report.blockedAt - report.lastFree, bracket);
        si->getStateSpace()->interpolate(a, b, report.blockedAt, s);
        const RigidTransform blockedPose = poseOfState(s, planar);
        if (report.contactFound && report.contactAt == report.blockedAt)
            EXPECT_TRUE(reference->collides(blockedPose));
        else
        {
            ++nearContacts;
            EXPECT_LE(reference->distance(blockedPose), validator.minimumClearance() * (1.0 + 1e-6));
        }
        if (report.contactFound)
        {
            EXPECT_GE(report.contactAt, report.blockedAt);
            si->getStateSpace()->interpolate(a, b, report.contactAt, s);
            EXPECT_TRUE(reference->collides(poseOfState(s, planar)));
        }
    }
    EXPECT_GE(free, 20);
    EXPECT_GE(colliding, 40);
    EXPECT_LE(nearContacts, colliding / 4);
    si->freeState(a);
    si->freeState(b);
    si->freeState(s);
}
}  // namespace

TEST(MotionValidator, FirstContactIsBracketedOnOmplAppMotions)
{
    HYBRIDCD_REQUIRE_OMPLAPP(cfg, "3D/cubicles.cfg");
    // Short motions (a tenth of the space) so that both outcomes are common.
    expectFirstContactsBracketed(cfg, "obb", 1e-6, false, 0.1);
}

// The planning set-up's bracket (1e-3 of a motion or one validity segment, whichever is coarser),
// which the contact narrowed by collision checks first serves: a 3D problem and a planar one, with
// the default checker.
TEST(MotionValidator, FirstContactIsBracketedToOneSegmentAsPlannersAskIt)
{
    HYBRIDCD_REQUIRE_OMPLAPP(cubicles, "3D/cubicles.cfg");
    expectFirstContactsBracketed(cubicles, "auto", 1e-3, true, 0.2);
    HYBRIDCD_REQUIRE_OMPLAPP(maze, "2D/Maze_planar.cfg");
    expectFirstContactsBracketed(maze, "auto", 1e-3, true, 0.2);
}

// Planners that discard a last valid state at or before a fraction of the motion (KPIECE's
// min_valid_path_fraction) tell the validator so, and a contact it finds before that fraction is
// left unbracketed: what such a planner keeps is the same as with the whole bracket, and what it
// is handed is still proven free (brute force along it).
TEST(MotionValidator, ContactsBeforeAnUnwantedFractionAreLeftUnbracketed)
{
    HYBRIDCD_REQUIRE_OMPLAPP(cubicles, "3D/cubicles.cfg");
    HYBRIDCD_REQUIRE_OMPLAPP(maze, "2D/Maze_planar.cfg");
    for (const std::string &cfg : {cubicles, maze})
    {
        SCOPED_TRACE(cfg);
        const LoadedProblem problem = loadProblem(cfg);
        const bool planar = problem.config.planar;
        PlanningProblem planning = makePlanningProblem(problem, makeChecker("auto", problem.scene));
        planning.setup->setup();
        const auto si = planning.setup->getSpaceInformation();
        auto &validator = dynamic_cast<ContinuousMotionValidator &>(*si->getMotionValidator());
        EXPECT_EQ(validator.unwantedLastValidBelow(), 0.0);
        const auto reference = makeChecker("bruteforce", problem.scene);
        auto sampler = si->allocStateSampler();
        ob::ScopedState<> a(si), b(si), s(si), whole(si), cut(si);
        int blocked = 0, kept = 0, unbracketed = 0;
        for (int attempt = 0; attempt < 4000 && blocked < 80; ++attempt)
        {
            sampler->sampleUniform(a.get());
            if (!si->isValid(a.get()))
                continue;
            sampler->sampleUniformNear(b.get(), a.get(), 0.2 * si->getMaximumExtent());
            si->enforceBounds(b.get());
            const double unwanted = attempt % 2 ? 0.2 : 0.5;
            validator.setUnwantedLastValidBelow(0.0);
            std::pair<ob::State *, double> bracketed{whole.get(), -1.0};
            const bool free = validator.checkMotion(a.get(), b.get(), bracketed);
            validator.setUnwantedLastValidBelow(unwanted);
            std::pair<ob::State *, double> left{cut.get(), -1.0};
            ASSERT_EQ(validator.checkMotion(a.get(), b.get(), left), free);
            if (free)
                continue;
            ++blocked;
            EXPECT_EQ(bracketed.second > unwanted, left.second > unwanted);
            if (bracketed.second > unwanted)
            {
                ++kept;
                EXPECT_EQ(left.second, bracketed.second);
            }
            else
            {
                EXPECT_LE(left.second, unwanted);
                unbracketed += left.second < bracketed.second;
            }
            si->getStateSpace()->interpolate(a.get(), b.get(), left.second, s.get());
            EXPECT_LT(si->distance(s.get(), cut.get()), 1e-9);
            for (int k = 0; k <= 200; ++k)
            {
                si->getStateSpace()->interpolate(a.get(), b.get(), left.second * k / 200, s.get());
                ASSERT_FALSE(reference->collides(poseOfState(s.get(), planar))) << left.second * k / 200;
            }
        }
        EXPECT_GE(blocked, 80);
        EXPECT_GT(kept, 0);
        EXPECT_GT(unbracketed, 0);
        // The detailed check always brackets: from a colliding s1, blocked at s1 itself, whatever
        // the setting (0 included).
        int collidingStarts = 0;
        for (int attempt = 0; attempt < 2000 && collidingStarts < 10; ++attempt)
        {
            sampler->sampleUniform(a.get());
            if (si->isValid(a.get()))
                continue;
            ++collidingStarts;
            sampler->sampleUniformNear(b.get(), a.get(), 0.2 * si->getMaximumExtent());
            si->enforceBounds(b.get());
            for (const double unwanted : {0.0, 0.5})
            {
                validator.setUnwantedLastValidBelow(unwanted);
                const auto report = validator.checkMotionDetailed(a.get(), b.get());
                EXPECT_FALSE(report.free);
                EXPECT_TRUE(report.blocked);
                EXPECT_TRUE(report.contactFound);
                EXPECT_EQ(report.lastFree, 0.0);
                EXPECT_EQ(report.blockedAt, 0.0);
            }
        }
        EXPECT_EQ(collidingStarts, 10);
        validator.setUnwantedLastValidBelow(std::numeric_limits<double>::quiet_NaN());
        EXPECT_EQ(validator.unwantedLastValidBelow(), 0.0);
        validator.setUnwantedLastValidBelow(7.0);
        EXPECT_EQ(validator.unwantedLastValidBelow(), 1.0);
        validator.setUnwantedLastValidBelow(0.0);
    }
}

// KPIECE1, BKPIECE1, LBKPIECE1 and STRIDE from the catalogue tell the validator their
// min_valid_path_fraction for the run, and the setting is back at 0 afterwards; with the same
// seed the three KPIECEs plan the same tree and path as OMPL's own classes, which leave it at 0.
TEST(MotionValidator, KpiecePlansTheSameWithItsUnwantedLastValidStatesLeftUnbracketed)
{
    HYBRIDCD_REQUIRE_OMPLAPP(maze, "2D/Maze_planar.cfg");
    const LoadedProblem problem = loadProblem(maze);
    PlanningProblem planning = makePlanningProblem(problem, makeChecker("auto", problem.scene));
    planning.setup->setup();
    const auto si = planning.setup->getSpaceInformation();
    const auto &validator = dynamic_cast<const ContinuousMotionValidator &>(*si->getMotionValidator());
    for (const std::string name : {"kpiece", "bkpiece", "lbkpiece", "stride"})
    {
        SCOPED_TRACE(name);
        std::vector<std::vector<double>> paths[2];
        std::size_t vertices[2] = {0, 0};
        for (int run = 0; run < 2; ++run)
        {
            const auto level = ompl::msg::getLogLevel();
            ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
            ompl::RNG::setSeed(std::uint_fast32_t(test::seeded(5)));
            planning.setup->clear();
            ob::PlannerPtr planner;
            double minimumFraction = 0.0;
            if (run == 0)
            {
                planner = makePlanner({name, "", {}}, si);
                minimumFraction = std::stod(planner->params().getParam("min_valid_path_fraction")->getValue());
            }
            else if (name == "kpiece")
                planner = std::make_shared<ompl::geometric::KPIECE1>(si);
            else if (name == "bkpiece")
                planner = std::make_shared<ompl::geometric::BKPIECE1>(si);
            else if (name == "lbkpiece")
                planner = std::make_shared<ompl::geometric::LBKPIECE1>(si);
            else
                planner = std::make_shared<ompl::geometric::STRIDE>(si);
            planning.setup->setPlanner(planner);
            // The setting as the planner runs: its fraction from the catalogue, 0 from OMPL's class.
            double seen = 0.0;
            const ob::PlannerTerminationCondition watch([&] {
                seen = std::max(seen, validator.unwantedLastValidBelow());
                return false;
            });
            const ob::PlannerStatus status = planning.setup->solve(
                ob::plannerOrTerminationCondition(watch, ob::timedPlannerTerminationCondition(60.0)));
            ompl::msg::setLogLevel(level);
            ASSERT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION);
            EXPECT_GT(seen, run == 0 ? 0.1 : -1.0);
            EXPECT_EQ(seen, minimumFraction);
            EXPECT_EQ(validator.unwantedLastValidBelow(), 0.0);
            ob::PlannerData data(si);
            planning.setup->getPlannerData(data);
            vertices[run] = data.numVertices();
            for (const ob::State *state : planning.setup->getSolutionPath().getStates())
            {
                std::vector<double> values;
                si->getStateSpace()->copyToReals(values, state);
                paths[run].push_back(values);
            }
        }
        EXPECT_GT(vertices[0], 20u);
        // STRIDE plans differently from one run to the next here even with OMPL's class in both
        // runs (its structures draw seeds of their own as it is cleared and set up again): only the
        // setting is checked for it; what it keeps is checked motion by motion above.
        if (name == "stride")
            continue;
        EXPECT_EQ(vertices[0], vertices[1]);
        EXPECT_EQ(paths[0], paths[1]);
    }
}

// A tall robot on a planar problem (SE(2), its turns counted from its z axis) crossing a thin wall
// on its way to a closed box that holds s2: the verdict's contact is s2, the first contact the wall,
// which the search finds by narrowing twice. Then a start closer to the wall than the bracket: the
// last valid state is s1 itself.
TEST(MotionValidator, FirstContactOfATallPlanarRobotIsTheThinWallBeforeTheVerdictsContact)
{
    TriangleMesh environment;
    environment.vertices = {Vec3(3, -10, -10), Vec3(3, 10, -10), Vec3(3, 10, 10), Vec3(3, -10, 10)};
    environment.triangles = {{0, 1, 2}, {0, 2, 3}};
    const TriangleMesh box = test::boxMesh(Vec3(8, -10, -10), Vec3(12, 10, 10));
    for (const Vec3 &v : box.vertices)
        environment.vertices.push_back(v);
    for (const auto &t : box.triangles)
        environment.triangles.push_back({t[0] + 4, t[1] + 4, t[2] + 4});
    LoadedProblem problem = makeProblem(test::boxMesh(Vec3(-0.5, -0.5, -3), Vec3(0.5, 0.5, 3)), environment);
    problem.config.planar = true;
    problem.scene.planarPoses = problem.scene.turnsAboutRobotZ = true;
    const auto reference = makeChecker("bruteforce", problem.scene);
    for (const std::string checker : {"auto", "obb"})
    {
        SCOPED_TRACE(checker);
        PlanningProblem planning = makePlanningProblem(problem, makeChecker(checker, problem.scene));
        planning.setup->setup();
        ASSERT_TRUE(planning.validity->checker().turnsAboutRobotZ());
        const auto si = planning.setup->getSpaceInformation();
        auto &validator = dynamic_cast<ContinuousMotionValidator &>(*si->getMotionValidator());
        ob::ScopedState<> a(si), b(si), s(si);
        const auto set = [](ob::ScopedState<> &state, double x, double y, double yaw) {
            state->as<ob::SE2StateSpace::StateType>()->setXY(x, y);
            state->as<ob::SE2StateSpace::StateType>()->setYaw(yaw);
        };
        for (const auto &[tolerance, perSegment] : {std::pair{1e-3, true}, std::pair{1e-6, false}})
        {
            SCOPED_TRACE(tolerance);
            validator.setContactTolerance(tolerance, perSegment);
            const double bracket =
                perSegment
                    ? std::max(tolerance, 1.0 / std::max(1u, si->getStateSpace()->validSegmentCount(a.get(), b.get())))
                    : tolerance;
            set(a, 0.0, 0.0, 0.0);
            set(b, 10.0, 0.5, 0.4);
            const int steps = 20000;
            const double sampled = sampledFirstContact(si, true, *reference, a.get(), b.get(), steps);
            ASSERT_LT(sampled, 0.35);  // the wall, well before the box
            const auto report = validator.checkMotionDetailed(a.get(), b.get());
            EXPECT_FALSE(report.free);
            ASSERT_TRUE(report.blocked);
            EXPECT_LE(report.blockedAt - report.lastFree, bracket);
            EXPECT_LE(report.lastFree, sampled);
            EXPECT_GE(report.blockedAt, sampled - 1.0 / steps);
            for (int k = 0; k <= 400; ++k)
            {
                si->getStateSpace()->interpolate(a.get(), b.get(), report.lastFree * k / 400, s.get());
                ASSERT_FALSE(reference->collides(poseOfState(s.get(), true)));
            }
            ASSERT_TRUE(report.contactFound);
            si->getStateSpace()->interpolate(a.get(), b.get(), report.contactAt, s.get());
            EXPECT_TRUE(reference->collides(poseOfState(s.get(), true)));
            std::pair<ob::State *, double> last{si->allocState(), -1.0};
            EXPECT_FALSE(validator.checkMotion(a.get(), b.get(), last));
            EXPECT_EQ(last.second, report.lastFree);
            si->freeState(last.first);

            // The robot's face 1e-7 before the wall, moving into it: the contact lies within the
            // bracket after s1.
            set(a, 2.5 - 1e-7, 0.0, 0.0);
            set(b, 6.0, 0.0, 0.0);
            const auto close = validator.checkMotionDetailed(a.get(), b.get());
            EXPECT_FALSE(close.free);
            ASSERT_TRUE(close.blocked);
            EXPECT_EQ(close.lastFree, 0.0);
            EXPECT_LE(close.blockedAt, bracket);
        }
    }
    // A checker that counts turns from the z axis is refused for a problem whose motions tilt.
    problem.config.planar = false;
    EXPECT_THROW(makePlanningProblem(problem, makeChecker("obb", problem.scene)), std::invalid_argument);
}

namespace
{
// The verdict path (checkMotion without a last valid state: raked checks, then certification) and
// the bracketing path (checkMotionDetailed) agree on free / not free on random motions as planners
// make them (valid start, end up to a fifth of the extent away), and no motion the verdict path
// accepts touches the environment under brute force at 2000 uniform samples.
void expectVerdictMatchesBracketing(const std::string &cfg, int motions)
{
    const LoadedProblem problem = loadProblem(cfg);
    const bool planar = problem.config.planar;
    PlanningProblem planning = makePlanningProblem(problem, makeChecker("obb", problem.scene));
    planning.setup->setup();
    const auto si = planning.setup->getSpaceInformation();
    auto &validator = dynamic_cast<ContinuousMotionValidator &>(*si->getMotionValidator());
    validator.setContactTolerance(1e-6);
    const auto reference = makeChecker("bruteforce", problem.scene);
    auto sampler = si->allocStateSampler();
    ob::State *a = si->allocState(), *b = si->allocState(), *s = si->allocState();
    int free = 0, blocked = 0;
    for (int i = 0; i < motions; ++i)
    {
        do
            sampler->sampleUniform(a);
        while (!si->isValid(a));
        sampler->sampleUniformNear(b, a, 0.2 * si->getMaximumExtent());
        si->enforceBounds(b);
        const bool verdict = validator.checkMotion(a, b);
        const auto report = validator.checkMotionDetailed(a, b);
        ASSERT_EQ(verdict, report.free) << "motion " << i << " of " << cfg;
        // Near-pair fronts change what each query costs, never what is certified.
        validator.setNearPairFronts(false);
        const bool verdictWithoutFronts = validator.checkMotion(a, b);
        const auto reportWithoutFronts = validator.checkMotionDetailed(a, b);
        validator.setNearPairFronts(true);
        ASSERT_EQ(verdictWithoutFronts, verdict) << "motion " << i << " of " << cfg;
        ASSERT_EQ(reportWithoutFronts.lastFree, report.lastFree) << "motion " << i << " of " << cfg;
        ASSERT_EQ(reportWithoutFronts.blocked, report.blocked) << "motion " << i << " of " << cfg;
        if (!verdict)
        {
            ++blocked;
            continue;
        }
        ++free;
        const int steps = 2000;
        for (int k = 0; k <= steps; ++k)
        {
            si->getStateSpace()->interpolate(a, b, double(k) / steps, s);
            ASSERT_FALSE(reference->collides(poseOfState(s, planar)))
                << "accepted motion " << i << " of " << cfg << " touches at " << double(k) / steps;
        }
    }
    // Both outcomes occur, so both paths are exercised, and so do fronts and sweeps too wide for
    // the exact query (left to the grid or split).
    EXPECT_GT(free, 0) << cfg;
    EXPECT_GT(blocked, 0) << cfg;
    EXPECT_GT(validator.nearPairFrontsListed(), 0u) << cfg;
    EXPECT_GT(validator.wideSweeps(), 0u) << cfg;
    si->freeState(a);
    si->freeState(b);
    si->freeState(s);
}
// Pure translations (the rotation copied from the start) bracketed twice: by the exact first contact
// of the time-augmented LP, and by bisection alone. Both keep the bracket promise, agree on the
// verdict, and their brackets overlap; brute force finds nothing on the proven-free prefix.
void expectTranslationBracketsAgree(const std::string &cfg, int motions)
{
    const LoadedProblem problem = loadProblem(cfg);
    PlanningProblem planning = makePlanningProblem(problem, makeChecker("obb", problem.scene));
    const auto si = planning.setup->getSpaceInformation();
    auto &validator = dynamic_cast<ContinuousMotionValidator &>(*si->getMotionValidator());
    validator.setContactTolerance(1e-6);
    const auto finder = std::make_shared<const TranslationContactFinder>(problem.scene);
    const auto reference = makeChecker("bruteforce", problem.scene);
    auto sampler = si->allocStateSampler();
    ob::State *a = si->allocState(), *b = si->allocState(), *s = si->allocState();
    int blocked = 0, attempts = 0;
    for (int motion = 0; motion < motions && ++attempts < 20000;)
    {
        sampler->sampleUniform(a);
        if (!si->isValid(a))
            continue;
        sampler->sampleUniformNear(b, a, 0.2 * si->getMaximumExtent());
        si->enforceBounds(b);
        if (problem.config.planar)
            b->as<ob::SE2StateSpace::StateType>()->setYaw(a->as<ob::SE2StateSpace::StateType>()->getYaw());
        else
            si->getStateSpace()->as<ob::SE3StateSpace>()->getSubspace(1)->copyState(
                b->as<ob::SE3StateSpace::StateType>()->as<ob::SO3StateSpace::StateType>(1),
                a->as<ob::SE3StateSpace::StateType>()->as<ob::SO3StateSpace::StateType>(1));
        ++motion;
        validator.setTranslationContactFinder(finder);
        const auto exact = validator.checkMotionDetailed(a, b);
        validator.setTranslationContactFinder(nullptr);
        const auto bisected = validator.checkMotionDetailed(a, b);
        ASSERT_EQ(exact.free, bisected.free) << cfg << " motion " << motion;
        if (exact.free)
            continue;
        ++blocked;
        for (const auto &report : {exact, bisected})
        {
            ASSERT_TRUE(report.blocked) << cfg << " motion " << motion;
            EXPECT_GT(report.blockedAt, report.lastFree);
            EXPECT_LE(report.blockedAt - report.lastFree, 1e-6 * (1.0 + 1e-9));
            for (int k = 0; k <= 200; ++k)
            {
                si->getStateSpace()->interpolate(a, b, report.lastFree * k / 200, s);
                ASSERT_FALSE(reference->collides(poseOfState(s, problem.config.planar))) << cfg << " motion " << motion;
            }
        }
        // Both brackets hold the same first blocking point (a near contact may block bisection a
        // little earlier than the exact contact, never later).
        EXPECT_LE(bisected.lastFree, exact.blockedAt) << cfg << " motion " << motion;
        EXPECT_LE(exact.lastFree - bisected.blockedAt, 1e-6) << cfg << " motion " << motion;
    }
    EXPECT_GE(blocked, motions / 5) << cfg;
    // Most blocked translations took the exact path (grazing contacts are left to bisection).
    EXPECT_GE(validator.exactTranslationBrackets(), std::uint64_t(blocked) * 3 / 4) << cfg;
    si->freeState(a);
    si->freeState(b);
    si->freeState(s);
}
}  // namespace

TEST(MotionValidator, PureTranslationsGetTheExactFirstContact)
{
    HYBRIDCD_REQUIRE_OMPLAPP(cubicles, "3D/cubicles.cfg");
    expectTranslationBracketsAgree(cubicles, test::cases(60));
    HYBRIDCD_REQUIRE_OMPLAPP(maze, "2D/Maze_planar.cfg");
    expectTranslationBracketsAgree(maze, test::cases(60));
    expectTranslationBracketsAgree(test::sourcePath("problems/window_3d.cfg"), test::cases(60));
}

TEST(MotionValidator, VerdictAgreesWithBracketingOnOmplAppMotions)
{
    HYBRIDCD_REQUIRE_OMPLAPP(cubicles, "3D/cubicles.cfg");
    expectVerdictMatchesBracketing(cubicles, test::cases(150));
    HYBRIDCD_REQUIRE_OMPLAPP(maze, "2D/Maze_planar.cfg");
    expectVerdictMatchesBracketing(maze, test::cases(150));
}

TEST(MotionValidator, VerdictAgreesWithBracketingOnProjectProblems)
{
    expectVerdictMatchesBracketing(test::sourcePath("problems/window_3d.cfg"), test::cases(150));
    expectVerdictMatchesBracketing(test::sourcePath("problems/corridor_2d.cfg"), test::cases(150));
}

// Motions from a colliding first state, which OMPL's planners never ask about: the validator does
// not test s1 by default (checkMotion's contract), yet never accepts such a motion, with or
// without the test and with or without a last valid state asked for.
void expectNoMotionFromACollidingStartAccepted(const LoadedProblem &problem, const std::string &checker,
                                               const std::vector<std::pair<ob::State *, ob::State *>> &motions,
                                               const ob::SpaceInformationPtr &si, const std::string &label)
{
    auto &validator = dynamic_cast<ContinuousMotionValidator &>(*si->getMotionValidator());
    const auto reference = makeChecker("bruteforce", problem.scene);
    std::pair<ob::State *, double> last{si->allocState(), 0.0};
    for (std::size_t i = 0; i < motions.size(); ++i)
    {
        const auto [a, b] = motions[i];
        ASSERT_TRUE(reference->collides(poseOfState(a, problem.config.planar))) << label << " motion " << i;
        for (const bool startChecked : {false, true})
        {
            validator.setStartChecked(startChecked);
            EXPECT_FALSE(validator.checkMotion(a, b)) << label << " " << checker << " motion " << i;
            EXPECT_FALSE(validator.checkMotion(a, b, last)) << label << " " << checker << " motion " << i;
            EXPECT_FALSE(validator.checkMotionDetailed(a, b).free) << label << " " << checker << " motion " << i;
        }
        validator.setStartChecked(false);
    }
    si->freeState(last.first);
}

TEST(MotionValidator, NoMotionFromACollidingStartIsAccepted)
{
    // Adversarial starts: touching a thin wall and moving away from it, sliding along it, inside a
    // closed box (solid semantics) staying inside or leaving it.
    TriangleMesh scene = thinWall();
    const TriangleMesh closed = test::boxMesh(Vec3(10, -5, -5), Vec3(20, 5, 5));
    const std::uint32_t base = std::uint32_t(scene.vertices.size());
    scene.vertices.insert(scene.vertices.end(), closed.vertices.begin(), closed.vertices.end());
    for (const auto &t : closed.triangles)
        scene.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
    const LoadedProblem problem = makeProblem(test::boxMesh(Vec3(-0.5, -0.5, -0.5), Vec3(0.5, 0.5, 0.5)), scene);
    for (const std::string checker : {"auto", "obb"})
    {
        PlanningProblem planning = makePlanningProblem(problem, makeChecker(checker, problem.scene));
        planning.setup->setup();
        const auto si = planning.setup->getSpaceInformation();
        std::vector<std::pair<ob::State *, ob::State *>> motions;
        const auto motion = [&](const Vec3 &from, double fromYaw, const Vec3 &to, double toYaw) {
            motions.push_back({si->allocState(), si->allocState()});
            setPose(motions.back().first, from, fromYaw);
            setPose(motions.back().second, to, toYaw);
        };
        motion(Vec3(-0.5, 0, 0), 0.0, Vec3(-5, 0, 0), 0.0);    // face on the wall, moving off
        motion(Vec3(-0.5, 0, 0), 0.0, Vec3(-0.5, 3, 0), 0.0);  // face on the wall, sliding
        motion(Vec3(-0.5, 0, 0), 0.0, Vec3(-3, 1, 0), 1.0);    // face on the wall, turning away
        motion(Vec3(0.2, 0, 0), 0.0, Vec3(-4, 0, 0), 0.0);     // through the wall, moving off
        motion(Vec3(15, 0, 0), 0.0, Vec3(16, 1, 0), 0.5);      // inside the closed box, staying
        motion(Vec3(15, 0, 0), 0.0, Vec3(25, 0, 0), 0.0);      // inside the closed box, leaving
        motion(Vec3(10, 0, 0), 0.0, Vec3(7, 0, 0), 0.0);       // across the box's wall, leaving
        expectNoMotionFromACollidingStartAccepted(problem, checker, motions, si, "in-memory");
        for (auto &[a, b] : motions)
        {
            si->freeState(a);
            si->freeState(b);
        }
    }
}

// Colliding starts drawn uniformly, ends as a planner would pick them (valid or not).
void expectNoRandomMotionFromACollidingStartAccepted(const std::string &cfg, int count)
{
    const LoadedProblem problem = loadProblem(cfg);
    PlanningProblem planning = makePlanningProblem(problem, makeChecker("auto", problem.scene));
    planning.setup->setup();
    const auto si = planning.setup->getSpaceInformation();
    const auto reference = makeChecker("bruteforce", problem.scene);
    auto sampler = si->allocStateSampler();
    std::vector<std::pair<ob::State *, ob::State *>> motions;
    for (int i = 0; i < count; ++i)
    {
        ob::State *a = si->allocState(), *b = si->allocState();
        do
            sampler->sampleUniform(a);
        while (!reference->collides(poseOfState(a, problem.config.planar)));
        sampler->sampleUniformNear(b, a, 0.2 * si->getMaximumExtent());
        si->enforceBounds(b);
        motions.push_back({a, b});
    }
    expectNoMotionFromACollidingStartAccepted(problem, "auto", motions, si, cfg);
    for (auto &[a, b] : motions)
    {
        si->freeState(a);
        si->freeState(b);
    }
}

TEST(MotionValidator, NoMotionFromACollidingStartIsAcceptedOnOmplAppProblems)
{
    HYBRIDCD_REQUIRE_OMPLAPP(cubicles, "3D/cubicles.cfg");
    expectNoRandomMotionFromACollidingStartAccepted(cubicles, test::cases(40));
    HYBRIDCD_REQUIRE_OMPLAPP(maze, "2D/Maze_planar.cfg");
    expectNoRandomMotionFromACollidingStartAccepted(maze, test::cases(40));
}

TEST(Clearance, MatchesBruteForceDistanceOnFreePoses)
{
    HYBRIDCD_REQUIRE_OMPLAPP(cfg, "3D/cubicles.cfg");
    const LoadedProblem problem = loadProblem(cfg);
    const auto obb = makeChecker("obb", problem.scene);
    const auto reference = makeChecker("bruteforce", problem.scene);
    test::TestRandom rng(3);
    int checked = 0;
    for (const RigidTransform &pose : test::randomPoses(problem, 600, rng))
    {
        const double expected = reference->distance(pose);
        const double got = obb->distance(pose);
        EXPECT_NEAR(got, expected, 1e-9 * (1.0 + expected));
        EXPECT_EQ(expected == 0.0, reference->collides(pose));
        // The proximity query agrees with the distance on either side of it.
        if (expected > 1e-6)
        {
            EXPECT_FALSE(obb->withinDistance(pose, 0.99 * expected));
            EXPECT_TRUE(obb->withinDistance(pose, 1.01 * expected));
            ++checked;
        }
    }
    EXPECT_GT(checked, 100);
}

TEST(Clearance, CollidingStatesGetNegativeClearanceAndAValidStateNearby)
{
    HYBRIDCD_REQUIRE_OMPLAPP(cfg, "3D/cubicles.cfg");
    const LoadedProblem problem = loadProblem(cfg);
    PlanningProblem planning = makePlanningProblem(problem, makeChecker("obb", problem.scene));
    planning.setup->setup();
    const auto si = planning.setup->getSpaceInformation();
    const auto reference = makeChecker("bruteforce", problem.scene);
    auto sampler = si->allocStateSampler();
    ob::State *s = si->allocState(), *fixed = si->allocState();
    int colliding = 0, offered = 0;
    for (int i = 0; i < 3000 && colliding < 200; ++i)
    {
        sampler->sampleUniform(s);
        if (!si->satisfiesBounds(s) || !reference->collides(poseOfState(s, false)))
            continue;
        ++colliding;
        double dist = 1.0;
        bool available = false;
        EXPECT_FALSE(planning.validity->isValid(s, dist, fixed, available));
        EXPECT_LE(dist, 0.0);
        if (available)
        {
            ++offered;
            // Verified independently: in bounds and free under brute force, and nearby.
            EXPECT_TRUE(si->satisfiesBounds(fixed));
            EXPECT_FALSE(reference->collides(poseOfState(fixed, false)));
            EXPECT_LT(si->distance(s, fixed), 0.5 * si->getMaximumExtent());
        }
    }
    EXPECT_GE(colliding, 100);
    EXPECT_GE(offered, colliding / 4);
    std::cout << "[ push-out ] valid states offered for " << offered << " of " << colliding << " colliding states\n";
    si->freeState(s);
    si->freeState(fixed);
}
