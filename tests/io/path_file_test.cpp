// SPDX-License-Identifier: BSD-3-Clause
#include "support/test_support.h"

#include "hybridcd/io/input_error.h"
#include "hybridcd/io/path_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <sys/stat.h>

using namespace hcd;

namespace
{
void expectRotation(const RigidTransform &t, const Mat3 &expected, const std::string &what)
{
    EXPECT_TRUE(t.isFinite()) << what;
    EXPECT_LT((t.rotation - expected).cwiseAbs().maxCoeff(), 1e-12) << what << "\n" << t.rotation;
}

// A quarter turn about x, and the turn of the quaternion (0.5, 0.5, 0.5, 0.5): x -> y -> z -> x.
Mat3 quarterTurnX() { return (Mat3() << 1, 0, 0, 0, 0, -1, 0, 1, 0).finished(); }
Mat3 cyclicTurn() { return (Mat3() << 0, 0, 1, 1, 0, 0, 0, 1, 0).finished(); }
}  // namespace

TEST(PathFile, FileAndTextReadersAgree)
{
    const std::string text = "1 2 3 0 0 0 1 extra\n\n# comment\n4 5 6 0 0 1 0 # pose\n";
    const std::string path = test::writeTempFile("poses.path", text);
    const auto fromFile = readPoses(path, false), fromText = parsePoses(text, path, false);
    ASSERT_EQ(fromFile.size(), 2u);
    ASSERT_EQ(fromText.size(), 2u);
    for (std::size_t i = 0; i < 2; ++i)
    {
        EXPECT_EQ(fromFile[i].values, fromText[i].values);
        EXPECT_EQ(fromFile[i].line, fromText[i].line);
    }
    EXPECT_EQ(fromText[1].line, 4);
    const auto motions = parseMotions("0 0 0 1 2 3\n", "m.txt", true);
    ASSERT_EQ(motions.size(), 1u);
    EXPECT_EQ(motions[0].second.values, (std::vector<double>{1, 2, 3}));
}

TEST(PathFile, PathMotionsJoinConsecutiveStatesAndKeepTheirLines)
{
    // Three planar states with a comment and a blank line: two motions, each state's line kept; a
    // scene's lines hold every robot's pose.
    const std::string path = test::writeTempFile("motions.path", "1 2 3\n# turn\n\n4 5 6\n7 8 9\n");
    const auto motions = readPathMotions(path, true);
    ASSERT_EQ(motions.size(), 2u);
    EXPECT_EQ(motions[0].first.values, (std::vector<double>{1, 2, 3}));
    EXPECT_EQ(motions[0].second.values, (std::vector<double>{4, 5, 6}));
    EXPECT_EQ(motions[1].first.values, motions[0].second.values);
    EXPECT_EQ(motions[1].second.values, (std::vector<double>{7, 8, 9}));
    EXPECT_EQ(motions[0].first.line, 1);
    EXPECT_EQ(motions[0].second.line, 4);
    EXPECT_EQ(motions[1].second.line, 5);
    const std::string scene = test::writeTempFile("scene.path", "1 2 3 4 5 6\n7 8 9 10 11 12\n");
    const auto sceneMotions = readPathMotions(scene, true, 2);
    ASSERT_EQ(sceneMotions.size(), 1u);
    EXPECT_EQ(sceneMotions[0].second.values.size(), 6u);
    // A motions file (two states on every line) is refused, naming its first line; a path whose
    // lines carry other columns after the state is read as usual.
    const std::string pairs = test::writeTempFile("pairs.txt", "# pairs\n1 2 3 4 5 6\n7 8 9 10 11 12\n");
    try
    {
        readPathMotions(pairs, true);
        FAIL() << "a motions file read as a path";
    }
    catch (const InputError &e)
    {
        EXPECT_NE(std::string(e.what()).find(pairs + ":2: every line holds two states (6 numbers)"), std::string::npos)
            << e.what();
    }
    const std::string extra = test::writeTempFile("extra.path", "1 2 3 4 5 6 7\n7 8 9 10 11 12\n");
    EXPECT_EQ(readPathMotions(extra, true).size(), 1u);
    // Fewer than two states: no motion to check, an error naming the file.
    for (const char *text : {"", "# nothing\n", "1 2 3\n"})
    {
        const std::string shortPath = test::writeTempFile("short.path", text);
        try
        {
            readPathMotions(shortPath, true);
            FAIL() << "no error for '" << text << "'";
        }
        catch (const InputError &e)
        {
            EXPECT_NE(std::string(e.what()).find(shortPath + ": a path needs at least two states"), std::string::npos)
                << e.what();
        }
    }
}

TEST(PathFile, ErrorsNameTheSourceAndLine)
{
    try
    {
        parsePoses("0 0 0\n1 2\n", "states.txt", true);
        FAIL() << "no error for a short line";
    }
    catch (const InputError &e)
    {
        EXPECT_NE(std::string(e.what()).find("states.txt:2:"), std::string::npos) << e.what();
    }
    EXPECT_THROW(parseMotions("1 2 3 4 5 nan\n", "m.txt", true), InputError);
    EXPECT_THROW(parsePoses("1 2 1e999\n", "p.txt", true), InputError);
}

// Caught by the pose harness's rigidity check (tests/fuzz_corpus/pose/se3_extreme_quaternions.txt):
// the squares of quaternion components beyond about 1e154 overflowed, so the
// quaternion was not normalised and the "rotation" had infinite entries; components below about
// 1e-154 squared to zero and gave the identity instead of their rotation.
TEST(PathFile, ExtremeQuaternionsStillGiveTheirRotation)
{
    // The transform itself stays rigid for any scale of the quaternion's components...
    const auto fromQuaternion = [](double x, double y, double z, double w) {
        return RigidTransform::fromTranslationQuaternion(Vec3(1, 2, 3), w, x, y, z);
    };
    expectRotation(fromQuaternion(1e200, 1e200, 1e200, 1e200), cyclicTurn(), "components 1e200");
    expectRotation(fromQuaternion(1e-200, 0, 0, 1e-200), quarterTurnX(), "components 1e-200");
    expectRotation(fromQuaternion(5e-324, 0, 0, 5e-324), quarterTurnX(), "subnormal components");
    expectRotation(fromQuaternion(1e154, 0, 0, 1e154), quarterTurnX(), "components 1e154");
    // The zero quaternion stays the identity, as before.
    expectRotation(RigidTransform::fromTranslationQuaternion(Vec3::Zero(), 0, 0, 0, 0), Mat3::Identity(), "zero");
    // ...while pose files accept only unit quaternions (within 1e-3), naming the line otherwise.
    for (const char *line :
         {"1 2 3 1e200 1e200 1e200 1e200\n", "1 2 3 1e-200 0 0 1e-200\n", "1 2 3 5e-324 0 0 5e-324\n"})
        EXPECT_THROW(parsePoses(std::string("\n") + line, "extreme.path", false), InputError) << line;
}

// The same overflow in the axis of a .cfg start or goal gave a non-orthonormal matrix.
TEST(PathFile, ExtremeAxesStillGiveTheirRotation)
{
    const double quarter = 1.5707963267948966;
    expectRotation(RigidTransform::fromAxisAngle(Vec3::Zero(), Vec3(1e300, 0, 0), quarter), quarterTurnX(),
                   "axis 1e300");
    expectRotation(RigidTransform::fromAxisAngle(Vec3::Zero(), Vec3(1e-300, 0, 0), quarter), quarterTurnX(),
                   "axis 1e-300");
    expectRotation(RigidTransform::fromAxisAngle(Vec3::Zero(), Vec3::Zero(), quarter), Mat3::Identity(), "zero axis");
}

// Caught by the path harness's round-trip check (tests/fuzz_corpus/path/regression_hex_subnormal.path):
// "0x1p-1074" was read, but writePoses writes it as 4.9406564584124654e-324,
// which std::stod refuses (it throws on underflow), so a written path did not read back.
TEST(PathFile, SubnormalNumbersAreNumbers)
{
    const auto poses = parsePoses("0x1p-1074 4.9406564584124654e-324 1e-310\n", "tiny.path", true);
    ASSERT_EQ(poses.size(), 1u);
    EXPECT_EQ(poses[0].values[0], poses[0].values[1]);
    EXPECT_GT(poses[0].values[0], 0.0);
    EXPECT_EQ(poses[0].values[2], 1e-310);
}

TEST(PathFile, WrittenPosesReadBackBitForBit)
{
    // Down to the smallest subnormal, and up to the largest magnitude a file may hold (1e100).
    const std::vector<std::vector<double>> poses = {
        {-0.0, 4.9406564584124654e-324, 1e100}, {0.1, 1.0 / 3.0, -2.5e-300}, {-1e100, 9.999999999999999e99, -0.0}};
    std::ostringstream out;
    writePoses(out, poses);
    const auto back = parsePoses(out.str(), "written.path", true);
    ASSERT_EQ(back.size(), poses.size());
    for (std::size_t i = 0; i < poses.size(); ++i)
        for (std::size_t k = 0; k < 3; ++k)
        {
            EXPECT_EQ(back[i].values[k], poses[i][k]);
            EXPECT_EQ(std::signbit(back[i].values[k]), std::signbit(poses[i][k]));
        }
}

// Beyond magnitude 1e100 squared distances overflow: a file's number there is refused with its line.
TEST(PathFile, NumbersBeyondMagnitude1e100AreRefusedWithTheirLine)
{
    for (const char *far : {"1.0000000000000002e100", "-1e101", "1.7976931348623157e308"})
    {
        const std::string text = std::string("0 0 0\n# far\n0 ") + far + " 0\n";
        try
        {
            (void)parsePoses(text, "far.path", true);
            ADD_FAILURE() << far << " was read";
        }
        catch (const InputError &e)
        {
            EXPECT_NE(std::string(e.what()).find("far.path:3: '" + std::string(far) + "' is beyond magnitude 1e100"),
                      std::string::npos)
                << e.what();
        }
    }
}

// Reading normalises a quaternion that is off unit length; reading what was written must not
// normalise it again, or the bits change (found by fuzzing,
// tests/fuzz_corpus/path/regression_renormalised_quaternion.path). Checked on seeded random
// quaternions scaled off unit length by up to the accepted 1e-3.
TEST(PathFile, NormalisedQuaternionsReadBackBitForBit)
{
    test::TestRandom rng(test::seeded(17));
    std::normal_distribution<double> gauss;
    std::uniform_real_distribution<double> off(-9e-4, 9e-4);
    std::ostringstream text;
    text.precision(17);
    for (int i = 0; i < 2000; ++i)
    {
        double q[4];
        double norm = 0.0;
        for (double &c : q)
            c = gauss(rng), norm += c * c;
        const double scale = (1.0 + off(rng)) / std::sqrt(norm);
        text << gauss(rng) << ' ' << gauss(rng) << ' ' << gauss(rng);
        for (double c : q)
            text << ' ' << c * scale;
        text << '\n';
    }
    std::vector<std::vector<double>> first;
    for (const PoseRecord &p : parsePoses(text.str(), "random.path", false))
        first.push_back(p.values);
    std::ostringstream written;
    writePoses(written, first);
    const auto second = parsePoses(written.str(), "written.path", false);
    ASSERT_EQ(second.size(), first.size());
    for (std::size_t i = 0; i < first.size(); ++i)
        for (std::size_t k = 0; k < 7; ++k)
            ASSERT_EQ(second[i].values[k], first[i][k]) << "pose " << i << " value " << k;
}

namespace
{
// The message of the InputError `read` throws, or "" when it throws none.
template <typename Read>
std::string errorOf(Read read)
{
    try
    {
        read();
    }
    catch (const InputError &e)
    {
        return e.what();
    }
    return "";
}
}  // namespace

// Found by a probe: /dev/zero as --states grew to gigabytes and died of std::bad_alloc, and a FIFO
// blocked for ever. Only regular files are read, and no more than kMaxPoseFileBytes.
TEST(PathFile, OnlyRegularFilesWithinTheSizeBoundAreRead)
{
    for (const char *device : {"/dev/zero", "/dev/urandom"})
    {
        EXPECT_NE(errorOf([&] {
                      readPoses(device, false);
                  }).find(std::string(device) + ": is not a regular file (a device, pipe or socket); a pose file"),
                  std::string::npos)
            << device;
        EXPECT_NE(errorOf([&] { readMotions(device, false); }).find("is not a regular file"), std::string::npos);
        EXPECT_NE(errorOf([&] { readPathMotions(device, false); }).find("is not a regular file"), std::string::npos);
    }
    // A pipe with no writer: refused at once, never opened for a read that would wait.
    const std::string fifo =
        std::filesystem::path(test::writeTempFile("fifo.path", "")).replace_filename("fifo").string();
    std::filesystem::remove(fifo);
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    EXPECT_NE(errorOf([&] { readPoses(fifo, false); }).find(fifo + ": is not a regular file"), std::string::npos);
    std::filesystem::remove(fifo);
    // A symbolic link to itself: an InputError naming it, not a filesystem_error.
    const std::string loop = fifo + ".loop";
    std::filesystem::remove(loop);
    std::filesystem::create_symlink(loop, loop);
    EXPECT_NE(errorOf([&] { readPoses(loop, false); }).find(loop + ": cannot open pose file"), std::string::npos);
    std::filesystem::remove(loop);
    // One byte above the bound, sparse on disk: refused before it is read.
    const std::string big = test::writeTempFile("big.path", "0 0 0\n");
    std::filesystem::resize_file(big, kMaxPoseFileBytes + 1);
    EXPECT_NE(errorOf([&] { readPoses(big, true); })
                  .find(big + ": the pose file has " + std::to_string(kMaxPoseFileBytes + 1) +
                        " bytes, above the limit of " + std::to_string(kMaxPoseFileBytes) + " bytes"),
              std::string::npos);
    std::filesystem::remove(big);
    EXPECT_NE(errorOf([] {
                  readPoses("/nonexistent/poses.path", true);
              }).find("/nonexistent/poses.path: cannot open pose file"),
              std::string::npos);
}

// A UTF-8 byte-order mark, as some editors write, is skipped as the .cfg reader skips it; it was
// read as part of the first number ("'\ufeff0' is not a number").
TEST(PathFile, ByteOrderMarkIsSkipped)
{
    const std::string path = test::writeTempFile("bom.path", "\xEF\xBB\xBF"
                                                             "1 2 3\n4 5 6\n");
    const auto poses = readPoses(path, true);
    ASSERT_EQ(poses.size(), 2u);
    EXPECT_EQ(poses[0].values, (std::vector<double>{1, 2, 3}));
    EXPECT_EQ(poses[0].line, 1);
    // Only at the very start: elsewhere it is not a number.
    EXPECT_THROW(parsePoses("1 2 3\n\xEF\xBB\xBF"
                            "4 5 6\n",
                            "p.txt", true),
                 InputError);
}

// A word quoted in a message shows its control bytes and invalid UTF-8 escaped (a NUL cut the
// message short, an escape sequence reached the terminal), and no more than 60 bytes of it.
TEST(PathFile, QuotedWordsAreEscapedAndShortened)
{
    const std::string binary("\x00\x01\x1b[2Jx\x89 0 0\n", 13);
    EXPECT_EQ(errorOf([&] { parsePoses(binary, "bin.path", true); }),
              "bin.path:1: '\\x00\\x01\\x1b[2Jx\\x89' is not a number");
    EXPECT_EQ(errorOf([] { parsePoses("1 2 \xc3\xa9\n", "p.txt", true); }), "p.txt:1: '\xc3\xa9' is not a number");
    const std::string longWord(5000, '7');
    EXPECT_EQ(errorOf([&] { parsePoses("1 2 " + longWord + "x\n", "p.txt", true); }),
              "p.txt:1: '" + longWord.substr(0, 60) + "...' is not a number");
}
