// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/io/pose_codec.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

using namespace hcd;

namespace
{
using TestRandom = std::mt19937;

void expectRotation(const RigidTransform &t, const Mat3 &expected, const std::string &what)
{
    EXPECT_TRUE(t.isFinite()) << what;
    EXPECT_LT((t.rotation - expected).cwiseAbs().maxCoeff(), 1e-12) << what << "\n" << t.rotation;
}

void expectSameBits(const RigidTransform &a, const RigidTransform &b, const std::string &what)
{
    for (int i = 0; i < 9; ++i)
        EXPECT_EQ(a.rotation(i), b.rotation(i)) << what << " rotation entry " << i;
    for (int i = 0; i < 3; ++i)
        EXPECT_EQ(a.translation[i], b.translation[i]) << what << " translation " << i;
}

// Rotations by hand: columns are the images of the robot's x, y and z axes in the world.
Mat3 quarterTurnX() { return (Mat3() << 1, 0, 0, 0, 0, -1, 0, 1, 0).finished(); }
Mat3 quarterTurnZ() { return (Mat3() << 0, -1, 0, 1, 0, 0, 0, 0, 1).finished(); }
Mat3 halfTurnY() { return (Mat3() << -1, 0, 0, 0, 1, 0, 0, 0, -1).finished(); }
Mat3 cyclicTurn() { return (Mat3() << 0, 0, 1, 1, 0, 0, 0, 1, 0).finished(); }
const double kHalfSqrt2 = std::sqrt(0.5);
}  // namespace

TEST(PoseCodec, ColumnsFollowThePathFile)
{
    EXPECT_EQ(poseColumns(true), 3u);
    EXPECT_EQ(poseColumns(false), 7u);
}

TEST(PoseCodec, RowsGiveTheirHandComputedRotations)
{
    const double x[] = {1, 2, 3, kHalfSqrt2, 0, 0, kHalfSqrt2};
    const RigidTransform tx = transformOfRow(x, false);
    expectRotation(tx, quarterTurnX(), "quarter turn about x");
    EXPECT_EQ(tx.translation, Vec3(1, 2, 3));
    const double z[] = {0, 0, 0, 0, 0, kHalfSqrt2, kHalfSqrt2};
    expectRotation(transformOfRow(z, false), quarterTurnZ(), "quarter turn about z");
    const double y[] = {0, 0, 0, 0, 1, 0, 0};
    expectRotation(transformOfRow(y, false), halfTurnY(), "half turn about y");
    const double cyclic[] = {0, 0, 0, 0.5, 0.5, 0.5, 0.5};
    expectRotation(transformOfRow(cyclic, false), cyclicTurn(), "x -> y -> z -> x");

    const double planar[] = {4, -5, M_PI / 2};
    const RigidTransform tp = transformOfRow(planar, true);
    expectRotation(tp, quarterTurnZ(), "yaw pi/2");
    EXPECT_EQ(tp.translation, Vec3(4, -5, 0));
    // A yaw a full turn away is the same pose.
    const double turned[] = {4, -5, M_PI / 2 + 2 * M_PI};
    expectRotation(transformOfRow(turned, true), quarterTurnZ(), "yaw pi/2 + 2 pi");
}

// The extreme quaternions of tests/fuzz_corpus/pose/se3_extreme_quaternions.txt (path_file_test
// checks that pose files refuse them): the squares overflow or underflow, yet the rotation holds.
TEST(PoseCodec, ExtremeQuaternionsStillGiveTheirRotation)
{
    const double huge[] = {1, 2, 3, 1e200, 1e200, 1e200, 1e200};
    expectRotation(transformOfRow(huge, false), cyclicTurn(), "components 1e200");
    const double tiny[] = {1, 2, 3, 1e-200, 0, 0, 1e-200};
    expectRotation(transformOfRow(tiny, false), quarterTurnX(), "components 1e-200");
    const double subnormal[] = {1, 2, 3, 5e-324, 0, 0, 5e-324};
    expectRotation(transformOfRow(subnormal, false), quarterTurnX(), "subnormal components");
    const double edge[] = {1, 2, 3, 1e154, 0, 0, 1e154};
    expectRotation(transformOfRow(edge, false), quarterTurnX(), "components 1e154");
    const double zero[] = {1, 2, 3, 0, 0, 0, 0};
    expectRotation(transformOfRow(zero, false), Mat3::Identity(), "zero");
    // The state form holds a unit quaternion for each, the identity for zero.
    for (const double *row : {huge, tiny, subnormal, edge, zero})
    {
        const PoseRow s = stateRowOf(row, false);
        EXPECT_NEAR(std::sqrt(s[3] * s[3] + s[4] * s[4] + s[5] * s[5] + s[6] * s[6]), 1.0, 1e-15);
    }
    EXPECT_EQ(stateRowOf(zero, false)[6], 1.0);
}

// Rows become transforms exactly as RigidTransform::fromTranslationQuaternion makes them, and the
// state form of a row gives the very same transform (what `check` and `check-motion` rely on).
TEST(PoseCodec, StateRowsGiveTheSameTransformBitForBit)
{
    TestRandom random(20240611);
    std::uniform_real_distribution<double> position(-10.0, 10.0), yaw(-20.0, 20.0);
    std::normal_distribution<double> component(0.0, 1.0);
    std::uniform_int_distribution<int> exponent(-300, 300);
    for (int i = 0; i < 10000; ++i)
    {
        double row[7] = {position(random), position(random), position(random)};
        // Mostly near-unit quaternions, as files hold; every tenth of any scale.
        const double scale = i % 10 == 0 ? std::pow(10.0, exponent(random)) : 1.0;
        for (int k = 3; k < 7; ++k)
            row[k] = scale * component(random);
        const RigidTransform direct = transformOfRow(row, false);
        expectSameBits(
            direct,
            RigidTransform::fromTranslationQuaternion(Vec3(row[0], row[1], row[2]), row[6], row[3], row[4], row[5]),
            "fromTranslationQuaternion");
        expectSameBits(transformOfStateRow(stateRowOf(row, false).data(), false), direct, "3D state row");

        const double planar[3] = {row[0], row[1], yaw(random)};
        expectSameBits(transformOfStateRow(stateRowOf(planar, true).data(), true), transformOfRow(planar, true),
                       "planar state row");
        const double wrapped = stateRowOf(planar, true)[2];
        EXPECT_TRUE(wrapped >= -M_PI && wrapped < M_PI) << planar[2];
        if (::testing::Test::HasFailure())
            break;
    }
}

TEST(PoseCodec, YawsInRangeAreKeptBitForBit)
{
    for (double yaw : {-M_PI, -1.0, -0.0, 0.0, 1e-300, 3.0, std::nextafter(M_PI, 0.0)})
        EXPECT_EQ(wrapYaw(yaw), yaw);
    EXPECT_EQ(wrapYaw(M_PI), -M_PI);
}

TEST(PoseCodec, QuaternionsReadFromOutsideAreCheckedAndNormalised)
{
    double unit[] = {0, 0, 0, 0, 0, 0, 1};
    EXPECT_EQ(normaliseRowQuaternion(unit).verdict, QuaternionCheck::Verdict::Unit);
    EXPECT_EQ(unit[6], 1.0);
    double close[] = {0, 0, 0, 0, 0, 0, 1.0005};
    EXPECT_EQ(normaliseRowQuaternion(close).verdict, QuaternionCheck::Verdict::Unit);
    EXPECT_EQ(close[6], 1.0);
    double zero[] = {0, 0, 0, 0, 0, 0, 0};
    const QuaternionCheck z = normaliseRowQuaternion(zero);
    EXPECT_EQ(z.verdict, QuaternionCheck::Verdict::Zero);
    EXPECT_EQ(quaternionProblem(z), "the quaternion (qx qy qz qw) is zero; a rotation needs a unit quaternion");
    double twice[] = {0, 0, 0, 0, 0, 0, 2};
    const QuaternionCheck t = normaliseRowQuaternion(twice);
    EXPECT_EQ(t.verdict, QuaternionCheck::Verdict::NotUnit);
    EXPECT_EQ(t.norm, 2.0);
    EXPECT_EQ(twice[6], 2.0);  // refused rows are left as they are
    EXPECT_EQ(quaternionProblem(t),
              "the quaternion (qx qy qz qw) has norm 2; a unit quaternion is expected (within 0.001)");
    EXPECT_EQ(quaternionProblem(QuaternionCheck{}), "");
}
