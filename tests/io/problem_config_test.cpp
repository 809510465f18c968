// SPDX-License-Identifier: BSD-3-Clause
#include "support/test_support.h"

#include "hybridcd/io/input_error.h"
#include "hybridcd/io/problem_config.h"
#include "hybridcd/io/problem_scene.h"

#include <gtest/gtest.h>

#include <filesystem>

using namespace hcd;

namespace
{
std::string errorOf(const std::string &cfgText)
{
    const std::string path = test::writeTempFile("bad.cfg", cfgText);
    try
    {
        readProblemConfig(path);
    }
    catch (const InputError &e)
    {
        return e.what();
    }
    return "";
}

const char *kMinimal = "[problem]\nrobot = r.obj\nworld = w.obj\nstart.x = 1\nstart.y = 2\nstart.z = 3\n"
                       "goal.x = 4\ngoal.y = 5\ngoal.z = 6\n";
}  // namespace

TEST(ProblemConfig, ReadsEveryOmplAppProblemOrNamesTheMissingMesh)
{
    HYBRIDCD_REQUIRE_OMPLAPP_ROOT(root);
    int loaded = 0, failed = 0;
    for (const char *dim : {"2D", "3D"})
        for (const auto &entry : std::filesystem::directory_iterator(root + "/" + dim))
        {
            if (entry.path().extension() != ".cfg")
                continue;
            const std::string cfgPath = entry.path().string();
            const ProblemConfig cfg = readProblemConfig(cfgPath);
            // Every key OMPL.app uses is known: none of its problems warns.
            for (const std::string &warning : cfg.warnings)
                ADD_FAILURE() << warning;
            const bool meshesExist = std::filesystem::exists(cfg.robotMesh) &&
                                     (cfg.worldMesh.empty() || std::filesystem::exists(cfg.worldMesh));
            try
            {
                const LoadedProblem p = loadProblem(cfgPath);
                EXPECT_TRUE(meshesExist) << cfgPath;
                EXPECT_GT(p.robot.mesh->triangleCount(), 0u) << cfgPath;
                EXPECT_GT(p.world.mesh->triangleCount(), 0u) << cfgPath;
                EXPECT_EQ(cfg.planar, std::string(dim) == "2D") << cfgPath;
                ++loaded;
            }
            catch (const InputError &e)
            {
                // Only a missing mesh may fail, and the message must name the .cfg line and the file.
                EXPECT_FALSE(meshesExist) << cfgPath << ": " << e.what();
                const std::string missing = std::filesystem::exists(cfg.robotMesh) ? cfg.worldMesh : cfg.robotMesh;
                const std::string message = e.what();
                EXPECT_NE(message.find(cfgPath + ":"), std::string::npos) << message;
                EXPECT_NE(message.find(missing), std::string::npos) << message;
                EXPECT_NE(message.find("cannot open mesh file"), std::string::npos) << message;
                ++failed;
            }
        }
    EXPECT_GE(loaded, 20);
    EXPECT_GE(failed, 1);  // pipedream.cfg names a world mesh that is not shipped
    std::cout << "[ problems ] " << loaded << " loaded, " << failed << " name a missing mesh\n";
}

TEST(ProblemConfig, ParsesSectionsPlannersAndNames)
{
    HYBRIDCD_REQUIRE_OMPLAPP(path, "3D/cubicles_opt.cfg");
    const ProblemConfig cfg = readProblemConfig(path);
    EXPECT_EQ(cfg.name, "cubicles_opt");
    EXPECT_EQ(cfg.objective, "length");
    ASSERT_TRUE(cfg.objectiveThreshold.has_value());
    EXPECT_EQ(*cfg.objectiveThreshold, 0.0);
    EXPECT_FALSE(cfg.planar);
    EXPECT_DOUBLE_EQ(cfg.start.x, -4.96);
    ASSERT_TRUE(cfg.volumeZ.has_value());
    EXPECT_DOUBLE_EQ(cfg.volumeZ->second, 101.0);
    EXPECT_DOUBLE_EQ(cfg.benchmark.timeLimit, 300.0);
    EXPECT_EQ(cfg.benchmark.runCount, 50u);
    // Two aps planners, each refined by the lines after it.
    std::vector<const PlannerRequest *> aps;
    for (const PlannerRequest &r : cfg.planners)
        if (r.type == "aps")
            aps.push_back(&r);
    ASSERT_EQ(aps.size(), 2u);
    EXPECT_EQ(aps[0]->displayName, "APS1");
    EXPECT_EQ(aps[1]->displayName, "APS4");
    ASSERT_EQ(aps[1]->parameters.size(), 1u);
    EXPECT_EQ(aps[1]->parameters[0], std::make_pair(std::string("num_planners"), std::string("4")));
}

TEST(ProblemConfig, PlanarProblemAndSampler)
{
    HYBRIDCD_REQUIRE_OMPLAPP(maze, "2D/Maze_planar.cfg");
    EXPECT_TRUE(readProblemConfig(maze).planar);
    HYBRIDCD_REQUIRE_OMPLAPP(alpha, "3D/alpha-1.5.cfg");
    const ProblemConfig cfg = readProblemConfig(alpha);
    EXPECT_EQ(cfg.sampler, "obstacle_based");
    ASSERT_EQ(cfg.planners.size(), 4u);
    EXPECT_EQ(cfg.planners[2].type, "rrt");
    EXPECT_EQ(cfg.planners[2].parameters.at(0).second, "10");
}

TEST(ProblemConfig, ErrorsNameFileAndLine)
{
    EXPECT_NE(
        errorOf(std::string(kMinimal) + "this line has no equals sign\n").find("bad.cfg:10: expected 'key = value'"),
        std::string::npos);
    EXPECT_NE(
        errorOf(std::string(kMinimal) + "start.theta = abc\n").find("bad.cfg:10: 'start.theta' needs a finite number"),
        std::string::npos);
    EXPECT_NE(errorOf(std::string(kMinimal) + "start.theta = nan\n").find(":10:"), std::string::npos);
    EXPECT_NE(errorOf(std::string(kMinimal) + "[planner]\nrrt.range=3\n").find("bad.cfg:11: setting for planner 'rrt'"),
              std::string::npos);
    EXPECT_NE(errorOf(std::string(kMinimal) + "[nonsense]\n").find("bad.cfg:10: unknown section"), std::string::npos);
    EXPECT_NE(errorOf("[problem]\nworld = w.obj\n").find("lacks the required key 'robot'"), std::string::npos);
    EXPECT_NE(errorOf("robot = r.obj\n").find("bad.cfg:1: 'robot' appears before any [section]"), std::string::npos);
    EXPECT_NE(errorOf(std::string(kMinimal) + "[benchmark]\nrun_count = 2.5\n").find("bad.cfg:11: run_count"),
              std::string::npos);
    // Found by fuzzing (tests/fuzz_corpus/cfg/regression_huge_run_count.cfg): converting a count
    // beyond the largest unsigned was undefined behaviour.
    EXPECT_NE(errorOf(std::string(kMinimal) + "[benchmark]\nrun_count = 5e98\n").find("bad.cfg:11: run_count"),
              std::string::npos);
    EXPECT_NE(errorOf(std::string(kMinimal) + "[benchmark]\nrun_count = 4294967296\n").find("bad.cfg:11: run_count"),
              std::string::npos);
    EXPECT_EQ(errorOf(kMinimal), "");
}

TEST(ProblemConfig, ControlModelsAreKnownAndMatchTheDimension)
{
    const std::string planar = "[problem]\nrobot = r.obj\nworld = w.obj\nstart.x = 1\nstart.y = 2\n"
                               "goal.x = 4\ngoal.y = 5\n";
    const std::string path = test::writeTempFile("car.cfg", planar + "control = Kinematic_Car\n");
    const ProblemConfig cfg = readProblemConfig(path);
    EXPECT_EQ(cfg.control, "kinematic_car");
    EXPECT_EQ(cfg.controlLine, 8);
    EXPECT_NE(errorOf(planar + "control = hovercraft\n").find("bad.cfg:8: unknown control model 'hovercraft'"),
              std::string::npos);
    EXPECT_NE(errorOf(planar + "control = quadrotor\n").find("bad.cfg:8: control = quadrotor is a 3D vehicle"),
              std::string::npos);
    EXPECT_NE(errorOf(std::string(kMinimal) + "control = dynamic_car\n")
                  .find("bad.cfg:10: control = dynamic_car is a "
                        "planar vehicle"),
              std::string::npos);
    EXPECT_EQ(errorOf(std::string(kMinimal) + "control = blimp\n"), "");
    EXPECT_EQ(errorOf(planar + "control = dynamic_car\n"), "");
}

TEST(ProblemConfig, TextAndFileReadersAgree)
{
    const std::string path = test::writeTempFile("text.cfg", std::string(kMinimal) + "start.theta = 1e-310\n");
    const ProblemConfig fromFile = readProblemConfig(path);
    const ProblemConfig fromText = parseProblemConfig(std::string(kMinimal) + "start.theta = 1e-310\n", path);
    EXPECT_EQ(fromText.robotMesh, fromFile.robotMesh);
    EXPECT_EQ(fromText.name, "text");
    EXPECT_EQ(fromText.start.theta, 1e-310);  // subnormal numbers are numbers
    EXPECT_EQ(fromFile.start.theta, 1e-310);
    EXPECT_EQ(fromText.goal.z, 6.0);
    try
    {
        parseProblemConfig("[problem]\nrobot = r.obj\nstart.x = 1e999\n", "memory.cfg");
        FAIL() << "no error for an overflowing number";
    }
    catch (const InputError &e)
    {
        EXPECT_NE(std::string(e.what()).find("memory.cfg:3: 'start.x' needs a finite number"), std::string::npos)
            << e.what();
    }
}

TEST(ProblemConfig, MissingFileIsAnInputError)
{
    EXPECT_THROW(readProblemConfig("/nonexistent/problem.cfg"), InputError);
}

// Found by a probe: volume.min.x = -1e308 with volume.max.x = 1e308 was accepted, and its width
// (infinite) failed later in OMPL without a file or line.
TEST(ProblemConfig, NumbersBeyondMagnitude1e100AreRefused)
{
    // OMPL samples in and measures the volume by its width, which must stay finite; states beyond
    // 1e100 would overflow squared distances.
    const std::string wide = std::string(kMinimal) + "volume.min.x = -1e308\nvolume.max.x = 1e308\n";
    EXPECT_NE(errorOf(wide).find("bad.cfg:10: 'volume.min.x' needs a number of magnitude at most 1e100, got '-1e308'"),
              std::string::npos)
        << errorOf(wide);
    EXPECT_NE(errorOf(std::string(kMinimal) + "volume.min.x = -1\nvolume.max.x = 1.0000000000000002e100\n")
                  .find("bad.cfg:11: 'volume.max.x' needs a number of magnitude at most 1e100"),
              std::string::npos);
    EXPECT_EQ(errorOf(std::string(kMinimal) + "volume.min.x = -1e100\nvolume.max.x = 1e100\n"), "");
}

// --time 1e10 timed out at once (OMPL's nanosecond clock overflows); a .cfg's time_limit is the
// same limit for bench.
TEST(ProblemConfig, TimeLimitBeyondOmplsClockIsRefused)
{
    EXPECT_NE(errorOf(std::string(kMinimal) + "[benchmark]\ntime_limit = 1e10\n")
                  .find("bad.cfg:11: time_limit needs at most 1e9 seconds"),
              std::string::npos);
    EXPECT_EQ(errorOf(std::string(kMinimal) + "[benchmark]\ntime_limit = 1e9\n"), "");
}

// Only regular files within kMaxProblemFileBytes are read (a device such as /dev/zero would be
// read without end, a symbolic link loop gave a bare filesystem_error).
TEST(ProblemConfig, OnlyRegularFilesWithinTheSizeBoundAreRead)
{
    auto messageOf = [](const std::string &path) -> std::string {
        try
        {
            readProblemConfig(path);
        }
        catch (const InputError &e)
        {
            return e.what();
        }
        return "";
    };
    EXPECT_NE(messageOf("/dev/zero").find("/dev/zero: is not a regular file (a device, pipe or socket)"),
              std::string::npos);
    const std::string big = test::writeTempFile("big.cfg", kMinimal);
    std::filesystem::resize_file(big, kMaxProblemFileBytes + 1);
    EXPECT_NE(messageOf(big).find(big + ": the problem file (.cfg) has " + std::to_string(kMaxProblemFileBytes + 1) +
                                  " bytes, above the limit of " + std::to_string(kMaxProblemFileBytes) + " bytes"),
              std::string::npos)
        << messageOf(big);
    std::filesystem::remove(big);
    const std::string loop = big + ".loop";
    std::filesystem::remove(loop);
    std::filesystem::create_symlink(loop, loop);
    EXPECT_NE(messageOf(loop).find(loop + ": cannot open problem file (.cfg)"), std::string::npos) << messageOf(loop);
    std::filesystem::remove(loop);
    EXPECT_NE(messageOf("/nonexistent/problem.cfg").find("/nonexistent/problem.cfg: cannot open"), std::string::npos);
}
