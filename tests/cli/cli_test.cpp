// SPDX-License-Identifier: BSD-3-Clause
// The command-line tool as a user runs it: exit statuses, outputs, and clear errors on bad input.
#include "support/test_support.h"

#include "hybridcd/io/path_file.h"
#include "hybridcd/query/checker_catalogue.h"
#include "hybridcd/scene/problem_bodies.h"
#include "hybridcd/scene/scene_motion.h"
#ifdef HYBRIDCD_HAVE_FCL
#include "hybridcd/fcl/fcl_checker.h"
#endif

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <sys/wait.h>

using namespace hcd;

namespace
{
using CliRun = test::ShellResult;

// The hybridcd tool with `args` (stdout and stderr together).
CliRun run(const std::string &args) { return test::runShell(std::string(HYBRIDCD_CLI) + " " + args); }

std::string problem3d() { return test::sourcePath("problems/window_3d.cfg"); }
}  // namespace

TEST(Cli, SolveWritesAValidPath)
{
    const std::string out = test::writeTempFile("solution.path", "");
    const CliRun r = run("solve " + test::sourcePath("problems/corridor_2d.cfg") + " --seed 3 --time 30 --out " + out);
    ASSERT_EQ(r.status, 0) << r.output;
    for (const char *field : {"solved: yes", "solve time:", "simplified path length:", "path states:",
                              "collision checks:", "collision checking time:"})
        EXPECT_NE(r.output.find(field), std::string::npos) << field << "\n" << r.output;
    const LoadedProblem problem = loadProblem(test::sourcePath("problems/corridor_2d.cfg"));
    const auto poses = readPoses(out, true);
    ASSERT_GE(poses.size(), 2u);
    const auto reference = makeChecker("bruteforce", problem.scene);
    for (const PoseRecord &p : poses)
        EXPECT_FALSE(reference->collides(transformOfRow(p.values.data(), true)));
    EXPECT_NEAR(poses.front().values[0], problem.config.start.x, 1e-9);
    EXPECT_NEAR(poses.back().values[0], problem.config.goal.x, 1e-9);
}

namespace
{
// The first row of a kinodynamic path file whose header starts with `header`, checked to hold as
// many values as the header announces (states, controls and the duration).
std::vector<double> firstRowMatchingItsHeader(const std::string &path, const std::string &header)
{
    std::ifstream in(path);
    std::string first, row;
    std::getline(in, first);
    EXPECT_EQ(first.rfind(header, 0), 0u) << first;
    unsigned states = 0, controls = 0;
    EXPECT_EQ(std::sscanf(first.c_str() + first.find(": ") + 2,
                          "%u state values (the pose first, as in OMPL.app's "
                          ".path), %u control values",
                          &states, &controls),
              2)
        << first;
    std::getline(in, row);
    std::istringstream columns(row);
    double v = 0.0;
    std::vector<double> values;
    while (columns >> v)
        values.push_back(v);
    EXPECT_EQ(values.size(), std::size_t(states + controls + 1)) << first << "\n" << row;
    return values;
}
}  // namespace

TEST(Cli, SolveRunsAControlPlannerOnAKinodynamicProblem)
{
    const std::string cfg = test::sourcePath("problems/corridor_kcar.cfg");
    const std::string out = test::writeTempFile("kcar.path", "");
    const CliRun r = run("solve " + cfg + " --planner rrt --seed 2 --time 60 --out " + out);
    ASSERT_EQ(r.status, 0) << r.output;
    for (const char *field : {"(kinematic_car, SE2 pose)", "planner: RRT (control)", "solved: yes",
                              "propagation step: 0.2 s, controls of 1 to 20 steps", "states written"})
        EXPECT_NE(r.output.find(field), std::string::npos) << field << "\n" << r.output;
    // Rows: x y theta, speed, steering angle, duration; poses readable as OMPL.app .path poses.
    const LoadedProblem problem = loadProblem(cfg);
    const auto poses = readPoses(out, true);
    ASSERT_GE(poses.size(), 2u);
    const auto reference = makeChecker("bruteforce", problem.scene);
    for (const PoseRecord &p : poses)
        EXPECT_FALSE(reference->collides(transformOfRow(p.values.data(), true)));
    EXPECT_NEAR(poses.front().values[0], problem.config.start.x, 1e-9);
    EXPECT_LT(
        std::hypot(poses.back().values[0] - problem.config.goal.x, poses.back().values[1] - problem.config.goal.y),
        1.0);
    const std::vector<double> values = firstRowMatchingItsHeader(out, "# kinematic_car path: 3 state values");
    ASSERT_EQ(values.size(), 6u);
    EXPECT_LE(std::abs(values[3]), 5.0);
    EXPECT_NEAR(std::fmod(values[5] + 1e-9, 0.2), 0.0, 1e-6) << "a whole number of propagation steps";
}

// A control planner that reaches no exact solution writes the path OMPL keeps nearest the goal,
// labelled, as geometric planners do (exit status 2): a goal threshold of 1e-9 is never met.
TEST(Cli, AControlPlannerWritesItsApproximatePathLabelled)
{
    const std::string cfg = test::sourcePath("problems/corridor_kcar.cfg");
    const std::string out = test::writeTempFile("kcar_approximate.path", "");
    std::filesystem::remove(out);
    const CliRun r = run("solve " + cfg + " --planner rrt --seed 1 --time 0.3 --goal-threshold 1e-9 --out " + out);
    ASSERT_EQ(r.status, 2) << r.output;
    for (const char *field : {"solved: no, approximate path only", "APPROXIMATE path written to: ",
                              "from the goal (OMPL's goal distance)", "holds an APPROXIMATE path"})
        EXPECT_NE(r.output.find(field), std::string::npos) << field << "\n" << r.output;
    const LoadedProblem problem = loadProblem(cfg);
    const auto poses = readPoses(out, true);
    ASSERT_GE(poses.size(), 2u);
    EXPECT_NEAR(poses.front().values[0], problem.config.start.x, 1e-9);
    const auto reference = makeChecker("bruteforce", problem.scene);
    for (const PoseRecord &p : poses)
        EXPECT_FALSE(reference->collides(transformOfRow(p.values.data(), true)));
    EXPECT_EQ(firstRowMatchingItsHeader(out, "# kinematic_car path: 3 state values").size(), 6u);
}

TEST(Cli, AQuadrotorPathHeaderCountsTheValuesWritten)
{
    // x y z, the quaternion's four values, six velocities: 13 values, where the space's dimension
    // is 12 (the header once said 12, and columns read by it took the controls wrongly).
    // problems/quadrotor_window.cfg with its goal half a metre from the start, on the start's side
    // of the window: solved at once.
    std::ifstream window(test::sourcePath("problems/quadrotor_window.cfg"));
    std::string text, line;
    while (std::getline(window, line))
    {
        if (line.rfind("goal.x", 0) == 0)
            line = "goal.x = -1.5";
        else if (line.rfind("robot = ", 0) == 0 || line.rfind("world = ", 0) == 0)
            line = line.substr(0, 8) + test::sourcePath("problems/" + line.substr(8));
        text += line + "\n";
    }
    const std::string cfg = test::writeTempFile("quadrotor_near.cfg", text);
    const std::string out = test::writeTempFile("quadrotor.path", "");
    const CliRun r = run("solve " + cfg + " --planner kpiece --seed 1 --time 60 --out " + out);
    ASSERT_EQ(r.status, 0) << r.output;
    const std::vector<double> values = firstRowMatchingItsHeader(out, "# quadrotor path: 13 state values");
    ASSERT_EQ(values.size(), 13u + 4u + 1u);
}

// OMPL 1.5's SORRT* never returns once it holds a shortest possible path (here a free straight
// motion from start to goal): a benchmark run is ended 30 s and its limit past it, with no log
// written (solve's shorter grace is in the hostile-input corpus).
TEST(Cli, BenchEndsARunThatIgnoresItsTimeLimit)
{
    const std::string log = test::writeTempFile("never.log", "");
    std::remove(log.c_str());
    const CliRun r = run("bench " + test::sourcePath("tests/hostile/straight_2d.cfg") +
                         " --planner sorrtstar --runs 1 --time 0.2 --seed 3 --baseline none --out " + log);
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_NE(r.output.find("planner SORRTstar[auto+continuous] did not return within 30.2 s after its limit of "
                            "--time 0.2 s"),
              std::string::npos)
        << r.output;
    EXPECT_FALSE(std::ifstream(log).good()) << "a log was written";
}

TEST(Cli, KinodynamicProblemsRefuseWhatCannotBeDone)
{
    const std::string robot = test::sourcePath("problems/corridor_2d_robot.obj");
    const std::string world = test::sourcePath("problems/corridor_2d_env.obj");
    const std::string hover = test::writeTempFile(
        "hover.cfg", "[problem]\nrobot = " + robot + "\nworld = " + world +
                         "\ncontrol = hovercraft\nstart.x = -40\nstart.y = -20\ngoal.x = -12\ngoal.y = -20\n");
    const std::string kcar = test::sourcePath("problems/corridor_kcar.cfg");
    struct Case
    {
        std::string args, expected;
    };
    const Case cases[] = {
        {"solve " + hover + " --out /dev/null", "hover.cfg:4: unknown control model 'hovercraft'"},
        {"solve " + kcar + " --planner rrtconnect --out /dev/null",
         "valid control planners: est, kpiece, pdst, rrt, sst"},
        {"bench " + kcar + " --planner rrtconnect --out /dev/null", "unknown control planner 'rrtconnect'"},
        {"bench " + problem3d() + " --goal-threshold 2 --out /dev/null",
         "--goal-threshold is for kinodynamic problems"},
        {"solve " + problem3d() + " --goal-threshold 2 --out /dev/null",
         "--goal-threshold is for kinodynamic problems"},
        {"solve " + kcar + " --control-steps 5,2 --out /dev/null", "MIN exceeds MAX"},
    };
    for (const Case &c : cases)
    {
        const CliRun r = run(c.args);
        EXPECT_EQ(r.status, 1) << c.args << "\n" << r.output;
        EXPECT_NE(r.output.find(c.expected), std::string::npos) << c.args << "\n" << r.output;
    }
}

TEST(Cli, CheckPrintsOneVerdictPerPose)
{
    // Extra trailing columns are ignored; the first pose is the start (free), the second is inside the wall.
    const std::string states = test::writeTempFile("states.txt", "-26 -10 12 0 0 0 1 extra 5\n0 20 20 0 0 0 1\n\n");
    for (const char *checker : {"obb", "bruteforce"})
    {
        const CliRun r = run("check " + problem3d() + " --states " + states + " --checker " + checker);
        ASSERT_EQ(r.status, 0) << r.output;
        EXPECT_EQ(r.output.rfind("1\n0\n", 0), 0u) << r.output;
        EXPECT_NE(r.output.find("ns per check"), std::string::npos);
    }
}

TEST(Cli, InspectDescribesMeshesAndHierarchies)
{
    const CliRun r = run("inspect " + problem3d() + " --checker obb");
    ASSERT_EQ(r.status, 0) << r.output;
    for (const char *field :
         {"triangles:", "vertices:", "closed (watertight): yes", "bounding box:", "OBB tree:", "nodes"})
        EXPECT_NE(r.output.find(field), std::string::npos) << field << "\n" << r.output;
}

TEST(Cli, BadInputGivesClearErrorsAndNonZeroExit)
{
    struct Case
    {
        std::string args, expected;
    };
    const std::string missingMesh = test::writeTempFile(
        "missing_mesh.cfg", "[problem]\nrobot = no_such_robot.obj\nstart.x=0\nstart.y=0\ngoal.x=1\ngoal.y=1\n");
    const std::string malformed =
        test::writeTempFile("malformed.cfg", "[problem]\nrobot = r.obj\nthis is not a setting\n");
    const std::string nanPose = test::writeTempFile("nan.path", "0 0 0 0 0 0 1\n1 2 nan 0 0 0 1\n");
    const Case cases[] = {
        {"solve " + missingMesh, "missing_mesh.cfg:2: robot mesh"},
        {"solve " + malformed, "malformed.cfg:3: expected 'key = value'"},
        {"solve " + problem3d() + " --planner nosuch", "valid"},
        {"solve " + problem3d() + " --checker nosuch", "valid checkers: obb"},
        {"check " + problem3d() + " --states " + nanPose, "nan.path:2: 'nan' is not a finite number"},
        {"check " + problem3d() + " --states /no/such/file", "/no/such/file"},
        {"solve /no/such/problem.cfg", "/no/such/problem.cfg"},
        {"frobnicate", "unknown command 'frobnicate'"},
        {"check " + problem3d() + " --states " + nanPose + " --checker obb --mode approximate --tolerance 0.1",
         "checker 'obb' has no approximate mode"},
        {"solve " + problem3d() + " --time abc", "--time needs a finite number"},
    };
    for (const Case &c : cases)
    {
        const CliRun r = run(c.args);
        EXPECT_EQ(r.status, 1) << c.args << "\n" << r.output;
        EXPECT_NE(r.output.find(c.expected), std::string::npos) << c.args << "\n" << r.output;
    }
}

TEST(Cli, CollidingGoalIsRejectedBeforePlanning)
{
    // The goal lies inside the dividing wall: solve says so at once instead of spending --time.
    std::string cfg = test::fileText(problem3d());
    const auto replace = [&](const std::string &key, const std::string &value) {
        const auto at = cfg.find(key);
        const auto end = cfg.find('\n', at);
        cfg.replace(at, end - at, key + " = " + value);
    };
    replace("goal.x", "0");
    replace("goal.y", "20");
    replace("goal.z", "20");
    const std::string dir = test::sourcePath("problems");
    const std::string path = dir + "/.unsolvable_test.cfg";
    std::ofstream(path) << cfg;
    const CliRun r = run("solve " + path + " --time 60 --out /dev/null");
    std::remove(path.c_str());
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_NE(r.output.find(".unsolvable_test.cfg:"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("the goal (0, 20, 20) collides with the environment"), std::string::npos) << r.output;
}

TEST(Cli, NoPathInTimeExitsTwo)
{
    // Start and goal are free, but a tenth of a millisecond is far too short to pass the window.
    const std::string out = test::writeTempFile("unsolved.path", "");
    std::remove(out.c_str());
    const CliRun r = run("solve " + problem3d() + " --seed 1 --time 0.0001 --out " + out);
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_NE(r.output.find("solved: no"), std::string::npos) << r.output;
    EXPECT_FALSE(std::ifstream(out).good()) << "no path file is written when nothing was found";
}

namespace
{
// window_3d with its window closed by one more box: start and goal lie in two sealed rooms.
std::string sealedWindowProblem()
{
    std::string env = test::fileText(test::sourcePath("problems/window_3d_env.obj"));
    int vertices = 0;
    std::istringstream lines(env);
    for (std::string line; std::getline(lines, line);)
        vertices += line.rfind("v ", 0) == 0;
    const double lo[3] = {-2, -10, 15}, hi[3] = {2, 10, 35};
    std::ostringstream box;
    for (int c = 0; c < 8; ++c)
        box << "v " << (c & 1 ? hi : lo)[0] << ' ' << (c & 2 ? hi : lo)[1] << ' ' << (c & 4 ? hi : lo)[2] << '\n';
    // The 12 triangles of the box's faces (corner c has bit 0 = x, bit 1 = y, bit 2 = z), outward.
    const int faces[12][3] = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                              {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
    for (const auto &f : faces)
        box << "f " << vertices + f[0] + 1 << ' ' << vertices + f[1] + 1 << ' ' << vertices + f[2] + 1 << '\n';
    test::writeTempFile("sealed_env.obj", env + "\n" + box.str());
    test::writeTempFile("sealed_robot.obj", test::fileText(test::sourcePath("problems/window_3d_robot.obj")));
    std::string cfg = test::fileText(problem3d());
    cfg.replace(cfg.find("window_3d_robot.obj"), 19, "sealed_robot.obj");
    cfg.replace(cfg.find("window_3d_env.obj"), 17, "sealed_env.obj");
    return test::writeTempFile("sealed.cfg", cfg);
}

// The numbers after `key` in each line of `text` that contains it.
std::vector<double> numbersAfter(const std::string &text, const std::string &key)
{
    std::vector<double> out;
    for (std::size_t at = text.find(key); at != std::string::npos; at = text.find(key, at + 1))
        if (std::isdigit(static_cast<unsigned char>(text[at + key.size()])))
            out.push_back(std::stod(text.substr(at + key.size())));
    return out;
}
}  // namespace

TEST(Cli, SolveReportsProgressAndLabelsAnApproximatePath)
{
    const std::string cfg = sealedWindowProblem();
    const std::string out = test::writeTempFile("approximate.path", "");
    std::remove(out.c_str());
    // stdout and stderr apart: progress goes to stderr, the summary of results to stdout.
    const std::string err = test::writeTempFile("progress.txt", "");
    const auto solveTo = [&](const std::string &args) {
        return test::runShell("{ " + std::string(HYBRIDCD_CLI) + " solve " + cfg + " " + args + " 2>" + err + "; }");
    };
    const CliRun r = solveTo("--planner rrt --seed 1 --time 2.5 --out " + out);
    const std::string progress = test::fileText(err);
    EXPECT_EQ(r.status, 2) << r.output << progress;

    // A line a second with the elapsed time, the iterations and the collision checks, then a summary.
    const std::vector<double> elapsed = numbersAfter(progress, "solve: ");
    ASSERT_GE(elapsed.size(), 2u) << progress;
    // Lines are due at whole seconds from the start; a loaded machine may only print them late.
    for (std::size_t i = 0; i < 2; ++i)
    {
        EXPECT_GE(elapsed[i], double(i) + 0.95) << progress;
        EXPECT_LT(elapsed[i], double(i) + 1.6) << progress;
    }
    EXPECT_NE(progress.find(" s of 2.5, "), std::string::npos) << progress;
    const std::vector<double> checks = numbersAfter(progress, "iterations, ");
    ASSERT_GE(checks.size(), 3u) << progress;
    for (std::size_t i = 1; i < checks.size(); ++i)
        EXPECT_GE(checks[i], checks[i - 1]) << progress;
    EXPECT_GT(checks.front(), 0.0) << progress;
    EXPECT_NE(progress.find("solve: approximate solution only after 2."), std::string::npos) << progress;
    // The summary's count is the one the run reports on stdout.
    const std::vector<double> reported = numbersAfter(r.output, "collision checks: ");
    ASSERT_EQ(reported.size(), 1u) << r.output;
    EXPECT_EQ(checks.back(), reported.front()) << progress << r.output;

    // The approximate path is written, labelled, and free; it starts at the start and stops short.
    EXPECT_NE(r.output.find("solved: no, approximate path only"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("APPROXIMATE path written to: " + out), std::string::npos) << r.output;
    EXPECT_NE(progress.find("warning: no exact solution in 2.5 s; " + out + " holds an APPROXIMATE path"),
              std::string::npos)
        << progress;
    const auto poses = readPoses(out, false);
    ASSERT_GE(poses.size(), 2u);
    const LoadedProblem problem = loadProblem(cfg);
    const auto reference = makeChecker("bruteforce", problem.scene);
    for (const PoseRecord &p : poses)
        EXPECT_FALSE(reference->collides(transformOfRow(p.values.data(), false)));
    EXPECT_NEAR(poses.front().values[0], problem.config.start.x, 1e-9);
    EXPECT_LT(poses.back().values[0], 0.0) << "the goal's room is sealed";

    // --quiet: no progress at all; a terminal gets one bar redrawn in place.
    const CliRun quiet = solveTo("--planner rrt --seed 1 --time 1.2 --quiet --out " + out);
    EXPECT_EQ(quiet.status, 2) << quiet.output;
    EXPECT_EQ(test::fileText(err).find("solve: "), std::string::npos) << test::fileText(err);
    const test::ShellResult bar = test::runShell("script -qec '" + std::string(HYBRIDCD_CLI) + " solve " + cfg +
                                                 " --planner rrt --seed 1 --time 1.2 --out " + out + "' /dev/null");
    EXPECT_EQ(bar.status, 2) << bar.output;
    EXPECT_NE(bar.output.find("\r\033[K[#"), std::string::npos) << bar.output;
    EXPECT_NE(bar.output.find("/1.2 s, "), std::string::npos) << bar.output;
    EXPECT_NE(bar.output.find("\r\033[Ksolve: approximate solution only after 1."), std::string::npos) << bar.output;
}

TEST(Cli, ClearanceAndCheckMotion)
{
    const std::string states = test::writeTempFile("clearance.txt", "-26 -10 12 0 0 0 1\n0 20 20 0 0 0 1\n");
    const CliRun clearance = run("clearance " + problem3d() + " --states " + states + " 2>/dev/null");
    ASSERT_EQ(clearance.status, 0) << clearance.output;
    std::istringstream values(clearance.output);
    double free = 0.0, colliding = 0.0;
    values >> free >> colliding;
    EXPECT_GT(free, 1.0);       // the start stands clear of every obstacle
    EXPECT_LT(colliding, 0.0);  // inside the wall: negative, a penetration
    // The mean time per query on stderr, in the form check uses.
    const CliRun timed = run("clearance " + problem3d() + " --states " + states);
    ASSERT_EQ(timed.status, 0) << timed.output;
    EXPECT_NE(timed.output.find("1 free, 1 colliding; mean "), std::string::npos) << timed.output;
    EXPECT_NE(timed.output.find(" ns per clearance"), std::string::npos) << timed.output;
    // A motion straight through the dividing wall below the window, and one through the window.
    const std::string motions =
        test::writeTempFile("motions.txt", "-26 -10 12 0 0 0 1 26 -10 12 0 0 0 1\n-26 0 25 0 0 0 1 26 0 25 0 0 0 1\n");
    const CliRun motion = run("check-motion " + problem3d() + " --motions " + motions + " 2>/dev/null");
    ASSERT_EQ(motion.status, 0) << motion.output;
    std::istringstream lines(motion.output);
    int first = -1, second = -1;
    double t = -1.0;
    lines >> first >> t >> second;
    EXPECT_EQ(first, 0);
    // The robot's front face (its largest x about the centre) reaches the wall face x = -2 when the
    // centre, starting at -26 and travelling 52, is at -2 - front.
    const double front = loadProblem(problem3d()).robot.mesh->bounds().max.x();
    const double contact = (-2.0 - front + 26.0) / 52.0;
    EXPECT_LE(t, contact);
    EXPECT_GE(t, contact - 1e-6);
    EXPECT_EQ(second, 1);
    // The verdict alone: no fraction, and the mean time per motion on stderr.
    const CliRun verdict = run("check-motion " + problem3d() + " --motions " + motions + " --verdict-only 2>&1");
    ASSERT_EQ(verdict.status, 0) << verdict.output;
    EXPECT_EQ(verdict.output.substr(0, 4), "0\n1\n") << verdict.output;
    EXPECT_NE(verdict.output.find("us per motion"), std::string::npos) << verdict.output;
}

TEST(Cli, CheckMotionAlongAPathAgreesWithDenseBruteForceSampling)
{
    // A path of five states (a comment and a blank line in between): up beside the wall, through
    // the window, down, and back straight through the wall. Rotations stay the identity, so the
    // motions are straight lines and their samples need no interpolation of rotations.
    const std::vector<std::array<double, 3>> states = {
        {-26, -10, 12}, {-26, 0, 25}, {26, 0, 25}, {26, -10, 12}, {-26, -10, 12}};
    const std::vector<int> lines = {2, 3, 5, 6, 8};
    std::ostringstream text;
    text << "# a window path\n";
    for (std::size_t i = 0; i < states.size(); ++i)
    {
        if (i == 2)
            text << "\n";
        if (i == 4)
            text << "# back through the wall\n";
        text << states[i][0] << ' ' << states[i][1] << ' ' << states[i][2] << " 0 0 0 1\n";
    }
    const std::string path = test::writeTempFile("window.path", text.str());
    const CliRun r = run("check-motion " + problem3d() + " --path " + path + " 2>/dev/null");
    ASSERT_EQ(r.status, 0) << r.output;
    // The reference: 2,001 states along each motion, checked one by one with the brute-force checker.
    std::ostringstream samples;
    constexpr int kSamples = 2000;
    for (std::size_t m = 0; m + 1 < states.size(); ++m)
        for (int k = 0; k <= kSamples; ++k)
        {
            const double t = double(k) / kSamples;
            for (int c = 0; c < 3; ++c)
                samples << states[m][c] + t * (states[m + 1][c] - states[m][c]) << ' ';
            samples << "0 0 0 1\n";
        }
    const std::string sampled = test::writeTempFile("window_samples.path", samples.str());
    const CliRun reference = run("check " + problem3d() + " --states " + sampled + " --checker bruteforce 2>/dev/null");
    ASSERT_EQ(reference.status, 0) << reference.output;
    std::istringstream verdicts(reference.output), motions(r.output);
    std::size_t firstBlocked = states.size();
    for (std::size_t m = 0; m + 1 < states.size(); ++m)
    {
        int firstColliding = -1;  // the first sample that collides, -1: none
        for (int k = 0; k <= kSamples; ++k)
        {
            int v = -1;
            verdicts >> v;
            ASSERT_TRUE(v == 0 || v == 1) << reference.output;
            if (v == 0 && firstColliding < 0)
                firstColliding = k;
        }
        int verdict = -1;
        motions >> verdict;
        ASSERT_TRUE(verdict == 0 || verdict == 1) << r.output;
        EXPECT_EQ(verdict == 1, firstColliding < 0) << "motion " << m + 1;
        if (verdict == 0)
        {
            // The first contact lies after the last free sample before the first colliding one and
            // at or before that one; T is within the bracket (1e-6) before it.
            double lastFree = -1.0;
            motions >> lastFree;
            ASSERT_GT(firstColliding, 0) << "motion " << m + 1;
            EXPECT_LE(lastFree, double(firstColliding) / kSamples) << "motion " << m + 1;
            EXPECT_GE(lastFree, double(firstColliding - 1) / kSamples - 1e-6) << "motion " << m + 1;
            firstBlocked = std::min(firstBlocked, m);
        }
    }
    // The last motion crosses the dividing wall; stderr names it with its two lines, in both forms.
    ASSERT_EQ(firstBlocked, states.size() - 2) << r.output;
    const std::string named = "motion " + std::to_string(firstBlocked + 1) + " of 4 (lines " +
                              std::to_string(lines[firstBlocked]) + "-" + std::to_string(lines[firstBlocked + 1]) +
                              ") is not free";
    for (const char *form : {"", " --verdict-only"})
    {
        const CliRun summary = run("check-motion " + problem3d() + " --path " + path + form + " 2>&1");
        ASSERT_EQ(summary.status, 0) << summary.output;
        EXPECT_NE(summary.output.find(named), std::string::npos) << form << "\n" << summary.output;
    }
    // The free part alone: every motion free.
    const std::string freePath =
        test::writeTempFile("window_free.path", "-26 -10 12 0 0 0 1\n-26 0 25 0 0 0 1\n26 0 25 0 0 0 1\n");
    const CliRun free = run("check-motion " + problem3d() + " --path " + freePath + " 2>&1");
    ASSERT_EQ(free.status, 0) << free.output;
    EXPECT_EQ(free.output.substr(0, 4), "1\n1\n") << free.output;
    EXPECT_NE(free.output.find("all 2 motions are free"), std::string::npos) << free.output;
}

TEST(Cli, EveryCommandHasHelpWithItsOptionsAndExamples)
{
    const std::map<std::string, std::vector<std::string>> commands = {
        {"solve", {"--planner", "--time", "--seed", "--out", "--param", "--motion", "--verbose"}},
        {"check", {"--states"}},
        {"check-motion", {"--motions", "--path", "--contact-tolerance", "--verdict-only"}},
        {"clearance", {"--states"}},
        {"contacts", {"--states", "--limit"}},
        {"inspect", {"--level", "--export"}},
        {"render",
         {"--out", "--gltf", "--path", "--samples", "--level", "--volumes-at", "--view", "--width", "--height"}},
        {"bench", {"--planner", "--runs", "--time", "--memory", "--shard", "--out", "--motion", "--seed"}},
    };
    for (const auto &[command, options] : commands)
        for (const std::string &form : {command + " --help", "help " + command})
        {
            const CliRun r = run(form);
            EXPECT_EQ(r.status, 0) << form << "\n" << r.output;
            std::vector<std::string> expected = options;
            for (const char *common :
                 {"--checker", "--surface-only", "--mode", "--tolerance", "--max-triangles", "Examples:", "hybridcd "})
                expected.push_back(common);
            expected.push_back("hybridcd " + command + " ");
            for (const std::string &text : expected)
                EXPECT_NE(r.output.find(text), std::string::npos) << form << ": no '" << text << "'\n" << r.output;
        }
    const CliRun overview = run("--help");
    EXPECT_EQ(overview.status, 0) << overview.output;
    for (const auto &[command, options] : commands)
        EXPECT_NE(overview.output.find("  " + command + " "), std::string::npos) << command << "\n" << overview.output;
    // Without any argument: the overview too, but as a failure.
    const CliRun bare = run("");
    EXPECT_EQ(bare.status, 1);
    EXPECT_NE(bare.output.find("solve"), std::string::npos) << bare.output;
}

TEST(Cli, VersionIsTheProjectVersion)
{
    const CliRun r = run("--version");
    EXPECT_EQ(r.status, 0) << r.output;
    EXPECT_EQ(r.output, std::string("hybridcd ") + HYBRIDCD_VERSION + "\n");
}

TEST(Cli, HelpListsEveryCheckerOfTheCatalogueWithItsDescription)
{
#ifdef HYBRIDCD_HAVE_FCL
    const CheckerCatalogue catalogue = checkersWithFcl();
#else
    const CheckerCatalogue catalogue = CheckerCatalogue::builtIn();
#endif
    for (const char *form : {"--help", "check --help"})
    {
        const CliRun r = run(form);
        ASSERT_EQ(r.status, 0) << r.output;
        for (const CheckerEntry &e : catalogue.entries())
            EXPECT_NE(r.output.find("  " + e.name + " "), std::string::npos) << form << ": " << e.name << "\n"
                                                                             << r.output;
        for (const CheckerEntry &e : catalogue.entries())
            EXPECT_NE(r.output.find(e.description), std::string::npos) << form << ": " << e.name << "\n" << r.output;
    }
}

TEST(Cli, TyposGetASuggestionAndExitOne)
{
    struct Case
    {
        std::string args, expected;
    };
    const Case cases[] = {
        {"chek " + problem3d(), "unknown command 'chek', did you mean 'check'?"},
        {"slove " + problem3d(), "unknown command 'slove', did you mean 'solve'?"},
        {"check " + problem3d() + " --stats poses.path", "unknown option --stats, did you mean --states?"},
        {"solve " + problem3d() + " --tiem 3", "unknown option --tiem, did you mean --time?"},
        {"solve " + problem3d() + " --seeed=3", "unknown option --seeed, did you mean --seed?"},
        {"check " + problem3d() + " --states poses.path --checker obbb", "did you mean 'obb'?"},
    };
    for (const Case &c : cases)
    {
        const CliRun r = run(c.args);
        EXPECT_EQ(r.status, 1) << c.args << "\n" << r.output;
        EXPECT_NE(r.output.find(c.expected), std::string::npos) << c.args << "\n" << r.output;
        EXPECT_NE(r.output.find("--help"), std::string::npos) << "points to --help: " << c.args << "\n" << r.output;
    }
}

TEST(Cli, UnknownOptionsAndStrayArgumentsExitOne)
{
    struct Case
    {
        std::string args, expected;
    };
    const Case cases[] = {
        {"inspect " + problem3d() + " --frobnicate", "unknown option --frobnicate"},
        {"--frobnicate", "hybridcd: "},
        {"solve " + problem3d() + " --time", "--time"},
        {"inspect " + problem3d() + " " + problem3d(), "expected one problem file, got 2"},
        {"inspect", "missing the problem file"},
    };
    for (const Case &c : cases)
    {
        const CliRun r = run(c.args);
        EXPECT_EQ(r.status, 1) << c.args << "\n" << r.output;
        EXPECT_NE(r.output.find(c.expected), std::string::npos) << c.args << "\n" << r.output;
        EXPECT_NE(r.output.find("--help"), std::string::npos) << c.args << "\n" << r.output;
    }
}

// Scene problems: several robots and primitive obstacles (README, "Scenes of many bodies").
TEST(Cli, SolvesASceneOfThreeRobotsAndThePathHoldsUnderBruteForce)
{
    const std::string cfg = test::sourcePath("problems/crossing_2d.cfg");
    const std::string out = test::writeTempFile("crossing.path", "");
    const CliRun r = run("solve " + cfg + " --seed 1 --time 60 --out " + out);
    ASSERT_EQ(r.status, 0) << r.output;
    for (const char *field : {"(3 robots, SE2 each)", "solved: yes", "path written to:"})
        EXPECT_NE(r.output.find(field), std::string::npos) << field << "\n" << r.output;
    const LoadedProblem problem = loadProblem(cfg);
    const auto records = readPoses(out, true, 3);
    ASSERT_GE(records.size(), 2u);
    SceneOptions reference;
    reference.bruteForce = true;
    const auto scene = makeProblemScene(problem, reference);
    auto posesOf = [](const PoseRecord &record) {
        std::vector<RigidTransform> poses;
        for (std::size_t k = 0; k < 3; ++k)
            poses.push_back(transformOfRow(record.values.data() + 3 * k, true));
        return poses;
    };
    QueryContext context;
    // Every state free, and every motion between written states free at fine steps (brute force)
    // and under the continuous check of the brute-force scene.
    for (std::size_t i = 0; i + 1 < records.size(); ++i)
    {
        const auto from = posesOf(records[i]), to = posesOf(records[i + 1]);
        ASSERT_FALSE(scene->collides(from, context)) << "state " << i;
        ASSERT_TRUE(checkSceneMotionBySampling(*scene, from, to, 50, context).valid) << "motion " << i;
        ASSERT_TRUE(checkSceneMotion(*scene, from, to, context).valid) << "motion " << i;
    }
    const std::vector<double> &first = records.front().values, &last = records.back().values;
    const std::vector<RigidTransform> start = problemStart(problem.config), goal = problemGoal(problem.config);
    for (std::size_t k = 0; k < 3; ++k)
    {
        EXPECT_NEAR(first[3 * k], start[k].translation.x(), 1e-9);
        EXPECT_NEAR(last[3 * k + 1], goal[k].translation.y(), 1e-9);
    }
    // The same file through `check` with the brute-force reference: one 1 per state.
    const CliRun check = run("check " + cfg + " --states " + out + " --checker bruteforce 2>/dev/null");
    ASSERT_EQ(check.status, 0) << check.output;
    std::string ones;
    for (std::size_t i = 0; i < records.size(); ++i)
        ones += "1\n";
    // stdout first (stderr's summary follows it in what the shell captured).
    EXPECT_EQ(check.output.substr(0, ones.size()), ones) << check.output;
    EXPECT_NE(check.output.find(std::to_string(records.size()) + " free, 0 colliding"), std::string::npos)
        << check.output;
}

TEST(Cli, SceneCommandsTakeEveryRobotsPosePerLine)
{
    const std::string cfg = test::sourcePath("problems/crossing_2d.cfg");
    // The start; robot 2 inside the middle wall box; robot 3 overlapping robot 1.
    const std::string states = test::writeTempFile(
        "scene_states.txt", "-15 -8 0 -15 8 0 15 0 0\n-15 -8 0 0 0 0 15 0 0\n-15 -8 0 -15 8 0 -15 -8 0\n");
    const CliRun check = run("check " + cfg + " --states " + states);
    ASSERT_EQ(check.status, 0) << check.output;
    EXPECT_EQ(check.output.substr(0, 6), "1\n0\n0\n") << check.output;
    EXPECT_NE(check.output.find("3 robots, "), std::string::npos) << check.output;
    const CliRun clearance = run("clearance " + cfg + " --states " + states + " 2>/dev/null");
    ASSERT_EQ(clearance.status, 0) << clearance.output;
    std::istringstream values(clearance.output);
    double d0 = -1, d1 = -1, d2 = -1;
    values >> d0 >> d1 >> d2;
    EXPECT_GT(d0, 0.5);
    EXPECT_EQ(d1, 0.0);
    EXPECT_EQ(d2, 0.0);
    // Robot 3 drives straight through the middle wall (it must not pass), robot 3 moves in the open.
    const std::string motions =
        test::writeTempFile("scene_motions.txt", "-15 -8 0 -15 8 0 15 0 0 -15 -8 0 -15 8 0 -15 0 0\n"
                                                 "-15 -8 0 -15 8 0 15 0 0 -15 -8 0 -15 8 0 12 0 0\n");
    const CliRun motion = run("check-motion " + cfg + " --motions " + motions + " 2>/dev/null");
    ASSERT_EQ(motion.status, 0) << motion.output;
    std::istringstream lines(motion.output);
    int first = -1, second = -1;
    double t = -1.0;
    lines >> first >> t >> second;
    EXPECT_EQ(first, 0);
    // The disc (radius 1) meets the wall face x = 1 when its centre reaches x = 2: after 13 of 30.
    // The last valid state keeps 1e-6 of the scene's size (about 40) from contact.
    EXPECT_LE(t, 13.0 / 30.0);
    EXPECT_GE(t, 13.0 / 30.0 - 1e-5);
    EXPECT_EQ(second, 1);
    // The states as a path: the first motion drives robot 2 into the wall, and stderr names it.
    const CliRun path = run("check-motion " + cfg + " --path " + states + " --verdict-only 2>&1");
    ASSERT_EQ(path.status, 0) << path.output;
    EXPECT_EQ(path.output.substr(0, 4), "0\n0\n") << path.output;
    EXPECT_NE(path.output.find("motion 1 of 2 (lines 1-2) is not free"), std::string::npos) << path.output;
    // A line with the poses of too few robots names the file and line.
    const std::string shortLine = test::writeTempFile("scene_short.txt", "-15 -8 0 -15 8 0 15 0 0\n1 2 3 4 5 6\n");
    const CliRun bad = run("check " + cfg + " --states " + shortLine);
    EXPECT_EQ(bad.status, 1) << bad.output;
    EXPECT_NE(bad.output.find(shortLine + ":2:"), std::string::npos) << bad.output;
    EXPECT_NE(bad.output.find("3 planar poses"), std::string::npos) << bad.output;
}

TEST(Cli, BenchRunsASceneProblemPerConfiguration)
{
    const std::string cfg = test::sourcePath("problems/crossing_2d.cfg");
    const std::string log = test::writeTempFile("crossing_bench.log", "");
    const CliRun r = run("bench " + cfg +
                         " --planner rrtconnect --runs 2 --time 20 --seed 3 --motion continuous,discrete"
                         " --out " +
                         log + " 2>/dev/null");
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("3 robots; configurations: auto+continuous,auto+discrete(0.01)"), std::string::npos)
        << r.output;
    const std::string text = test::fileText(log);
    EXPECT_NE(text.find("RRTConnect[auto+continuous]"), std::string::npos);
    EXPECT_NE(text.find("RRTConnect[auto+discrete(0.01)]"), std::string::npos);
    // OMPL.app has no set-up for several robots to compare with.
    const CliRun baseline = run("bench " + cfg + " --baseline omplapp --runs 1 --out " + log);
    EXPECT_EQ(baseline.status, 1) << baseline.output;
    EXPECT_NE(baseline.output.find("scene problem"), std::string::npos) << baseline.output;
}
