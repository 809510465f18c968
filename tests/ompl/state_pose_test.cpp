// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/ompl/state_pose.h"

#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <limits>
#include <memory>
#include <random>

using namespace hcd;

namespace
{
using TestRandom = std::mt19937;

bool sameBits(const RigidTransform &a, const RigidTransform &b)
{
    for (int i = 0; i < 9; ++i)
        if (!(a.rotation(i) == b.rotation(i)))
            return false;
    return a.translation == b.translation;
}

// row -> state -> transform, and row -> state -> row -> transform, against row -> transform.
void expectRoundTrip(const ompl::base::StateSpacePtr &space, const double *row, bool planar)
{
    ompl::base::ScopedState<> state(space);
    poseValuesToState(row, planar, state.get());
    const RigidTransform direct = transformOfRow(row, planar);
    EXPECT_TRUE(sameBits(poseOfState(state.get(), planar), direct));
    const std::vector<double> back = stateToPoseValues(state.get(), planar);
    ASSERT_EQ(back.size(), poseColumns(planar));
    EXPECT_TRUE(sameBits(transformOfStateRow(back.data(), planar), direct));
    EXPECT_TRUE(space->satisfiesBounds(state.get()));  // the yaw in [-pi, pi), the quaternion unit
}
}  // namespace

TEST(StatePose, RowsSurviveTheOmplStateBitForBit)
{
    auto se3 = std::make_shared<ompl::base::SE3StateSpace>();
    auto se2 = std::make_shared<ompl::base::SE2StateSpace>();
    ompl::base::RealVectorBounds b3(3), b2(2);
    b3.setLow(-100), b3.setHigh(100), b2.setLow(-100), b2.setHigh(100);
    se3->setBounds(b3);
    se2->setBounds(b2);
    TestRandom random(7);
    std::uniform_real_distribution<double> position(-10.0, 10.0), yaw(-20.0, 20.0);
    std::normal_distribution<double> component(0.0, 1.0);
    for (int i = 0; i < 2000 && !::testing::Test::HasFailure(); ++i)
    {
        double row[7] = {position(random), position(random), position(random)};
        for (int k = 3; k < 7; ++k)
            row[k] = component(random);
        expectRoundTrip(se3, row, false);
        const double planar[3] = {row[0], row[1], yaw(random)};
        expectRoundTrip(se2, planar, true);
    }
    // The extreme quaternions and the zero one, which a state holds as the identity.
    for (double scale : {1e200, 1e-200, 5e-324, 1e154, 0.0})
    {
        const double row[7] = {1, 2, 3, scale, 0, 0, scale};
        expectRoundTrip(se3, row, false);
    }
}

TEST(StatePose, StatesHoldTheRowInPathOrder)
{
    auto se3 = std::make_shared<ompl::base::SE3StateSpace>();
    ompl::base::ScopedState<ompl::base::SE3StateSpace> s(se3);
    const double row[7] = {1, 2, 3, 0, 0, 0, 2};  // not unit: stored as the identity rotation
    poseValuesToState(row, false, s.get());
    EXPECT_EQ(s->getX(), 1.0);
    EXPECT_EQ(s->getZ(), 3.0);
    EXPECT_EQ(s->rotation().w, 1.0);
    EXPECT_EQ(s->rotation().x, 0.0);
    const PoseRow back = rowOfState(s.get(), false);
    EXPECT_EQ(back[6], 1.0);
}

// The turn OMPL's interpolation makes, against the sum of the turns between 2,000 of its states
// (moderate angles, where that sum is accurate), and against angles set exactly (tiny ones, where
// acos of a dot product rounds to zero).
TEST(StatePose, InterpolationTurnIsTheAngleOmplsInterpolationSweeps)
{
    TestRandom rng(20261127);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (const bool planar : {true, false})
    {
        ompl::base::StateSpacePtr space;
        if (planar)
            space = std::make_shared<ompl::base::SE2StateSpace>();
        else
            space = std::make_shared<ompl::base::SE3StateSpace>();
        ompl::base::ScopedState<> a(space), b(space), s(space), previous(space);
        for (int i = 0; i < 50; ++i)
        {
            if (planar)
            {
                a->as<ompl::base::SE2StateSpace::StateType>()->setYaw(M_PI * unit(rng));
                b->as<ompl::base::SE2StateSpace::StateType>()->setYaw(M_PI * unit(rng));
            }
            else
            {
                a->as<ompl::base::SE3StateSpace::StateType>()->rotation().setAxisAngle(unit(rng), unit(rng), unit(rng),
                                                                                       M_PI * unit(rng));
                b->as<ompl::base::SE3StateSpace::StateType>()->rotation().setAxisAngle(unit(rng), unit(rng), unit(rng),
                                                                                       M_PI * unit(rng));
            }
            double swept = 0.0;
            previous = a;
            for (int k = 1; k <= 2000; ++k)
            {
                space->interpolate(a.get(), b.get(), k / 2000.0, s.get());
                const Mat3 relative =
                    poseOfState(previous.get(), planar).rotation.transpose() * poseOfState(s.get(), planar).rotation;
                swept += Eigen::AngleAxisd(relative).angle();
                previous = s;
            }
            const double turn = interpolationTurn(a.get(), b.get(), planar);
            EXPECT_LE(turn, M_PI + 1e-12);
            EXPECT_NEAR(turn, swept, 1e-9) << (planar ? "SE2" : "SE3") << ", pair " << i;
        }
        for (const double angle : {1e-8, 3e-12, 2e-5, 1e-3})
        {
            if (planar)
            {
                a->as<ompl::base::SE2StateSpace::StateType>()->setYaw(0.5);
                b->as<ompl::base::SE2StateSpace::StateType>()->setYaw(0.5 + angle);
            }
            else
            {
                a->as<ompl::base::SE3StateSpace::StateType>()->rotation().setIdentity();
                b->as<ompl::base::SE3StateSpace::StateType>()->rotation().setAxisAngle(0.0, 0.6, 0.8, angle);
            }
            // SE2 turns by the difference of the yaws as doubles hold them.
            const double expected = planar ? (0.5 + angle) - 0.5 : angle;
            EXPECT_NEAR(interpolationTurn(a.get(), b.get(), planar), expected, 1e-6 * expected);
        }
    }
    // No bound holds: a non-finite yaw, a quaternion off unit length.
    const auto planarSpace = std::make_shared<ompl::base::SE2StateSpace>();
    ompl::base::ScopedState<> p(planarSpace), q(planarSpace);
    q->as<ompl::base::SE2StateSpace::StateType>()->setYaw(std::numeric_limits<double>::quiet_NaN());
    EXPECT_TRUE(std::isinf(interpolationTurn(p.get(), q.get(), true)));
    const auto space = std::make_shared<ompl::base::SE3StateSpace>();
    ompl::base::ScopedState<> u(space), v(space);
    u->as<ompl::base::SE3StateSpace::StateType>()->rotation().setIdentity();
    v->as<ompl::base::SE3StateSpace::StateType>()->rotation().setIdentity();
    v->as<ompl::base::SE3StateSpace::StateType>()->rotation().w = 1.0 + 1e-6;
    EXPECT_TRUE(std::isinf(interpolationTurn(u.get(), v.get(), false)));
}

// A row's yaw is wrapped into SO2's bounds [-pi, pi) (OMPL asserts on states outside them): a row's
// +pi is -pi, so from yaw 0 OMPL turns clockwise through -pi/2 to it, as to -pi, and
// counterclockwise through about +pi/2 to a yaw just short of +pi.
TEST(StatePose, HalfTurnsTurnTheWayOmplsBoundsSay)
{
    const auto space = std::make_shared<ompl::base::SE2StateSpace>();
    ompl::base::ScopedState<> from(space), to(space), middle(space);
    const double start[3] = {0.0, 0.0, 0.0};
    poseValuesToState(start, true, from.get());
    for (const double end : {M_PI, -M_PI, std::nextafter(M_PI, 0.0)})
    {
        const double row[3] = {0.0, 0.0, end};
        poseValuesToState(row, true, to.get());
        EXPECT_TRUE(space->satisfiesBounds(to.get())) << end;
        space->interpolate(from.get(), to.get(), 0.5, middle.get());
        const double expected = end < M_PI ? end / 2.0 : -M_PI / 2.0;
        EXPECT_NEAR(middle->as<ompl::base::SE2StateSpace::StateType>()->getYaw(), expected, 1e-15) << end;
    }
}
