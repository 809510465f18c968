// SPDX-License-Identifier: BSD-3-Clause
// Planning end to end; every returned path is re-checked independently (brute force, fine steps).
#include "support/test_support.h"

#include "hybridcd/ompl/planning_problem.h"
#include "hybridcd/ompl/retraction_sampler.h"
#include "hybridcd/planners/planner_catalogue.h"
#include "hybridcd/query/checker_catalogue.h"

#include <ompl/geometric/PathGeometric.h>
#include <ompl/util/RandomNumbers.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace hcd;

namespace
{
// Every state of the path, and states every `step` (in state-space distance) between them, are
// collision-free under brute force and inside the bounds.
void expectPathValid(const PlanningProblem &planning, const LoadedProblem &problem,
                     const ompl::geometric::PathGeometric &path)
{
    const auto bruteForce = makeChecker("bruteforce", problem.scene);
    const auto si = planning.setup->getSpaceInformation();
    const double step = 0.001 * si->getMaximumExtent();
    ompl::base::State *s = si->allocState();
    std::size_t checked = 0;
    for (std::size_t i = 0; i + 1 < path.getStateCount(); ++i)
    {
        const double d = si->distance(path.getState(i), path.getState(i + 1));
        const int n = std::max(1, int(std::ceil(d / step)));
        for (int k = 0; k <= n; ++k)
        {
            si->getStateSpace()->interpolate(path.getState(i), path.getState(i + 1), double(k) / n, s);
            ASSERT_TRUE(si->satisfiesBounds(s));
            ASSERT_FALSE(bruteForce->collides(poseOfState(s, problem.config.planar)))
                << "segment " << i << " fraction " << double(k) / n;
            ++checked;
        }
    }
    si->freeState(s);
    EXPECT_GT(checked, path.getStateCount());
}

void solveAndVerify(const std::string &cfg, const std::string &planner, double seconds, bool retraction = false)
{
    static const bool seeded = (ompl::RNG::setSeed(7), true);  // OMPL accepts a seed only once
    (void)seeded;
    const LoadedProblem problem = loadProblem(cfg);
    PlanningProblem planning = makePlanningProblem(problem, makeChecker("obb", problem.scene));
    if (retraction)
        useRetractionSampling(planning);
    planning.setup->setPlanner(makePlanner({planner, "", {}}, planning.setup->getSpaceInformation()));
    const auto status = planning.setup->solve(seconds);
    ASSERT_EQ(status, ompl::base::PlannerStatus::EXACT_SOLUTION) << cfg;
    planning.setup->simplifySolution();
    expectPathValid(planning, problem, planning.setup->getSolutionPath());
    EXPECT_GT(planning.validity->checkCount(), 0u);
}
}  // namespace

TEST(Solve, Cubicles)
{
    HYBRIDCD_REQUIRE_OMPLAPP(cfg, "3D/cubicles.cfg");
    solveAndVerify(cfg, "rrtconnect", 60);
}
TEST(Solve, Easy)
{
    HYBRIDCD_REQUIRE_OMPLAPP(cfg, "3D/Easy.cfg");
    solveAndVerify(cfg, "rrtconnect", 60);
}
// The narrow-passage problem, planned with continuous motion checks (the default) as well.
TEST(Solve, Twistycool)
{
    HYBRIDCD_REQUIRE_OMPLAPP(cfg, "3D/Twistycool.cfg");
    solveAndVerify(cfg, "rrtconnect", 120);
}
TEST(Solve, MazePlanar)
{
    HYBRIDCD_REQUIRE_OMPLAPP(cfg, "2D/Maze_planar.cfg");
    solveAndVerify(cfg, "rrtconnect", 60);
}
TEST(Solve, ProjectProblems)
{
    solveAndVerify(test::sourcePath("problems/window_3d.cfg"), "rrtconnect", 60);
    solveAndVerify(test::sourcePath("problems/corridor_2d.cfg"), "rrtconnect", 60);
    solveAndVerify(test::sourcePath("problems/corridor_2d.cfg"), "kpiece", 60);
}
// The organic problems (smooth closed meshes of a few thousand triangles, problems/README.md).
TEST(Solve, OrganicProblems)
{
    solveAndVerify(test::sourcePath("problems/bone_3d.cfg"), "rrtconnect", 60);
    solveAndVerify(test::sourcePath("problems/ribcage_3d.cfg"), "rrtconnect", 60);
    solveAndVerify(test::sourcePath("problems/bones_2d.cfg"), "rrtconnect", 60);
}
// Samples pushed out onto the obstacles' surfaces: paths stay valid. (On problems that solve in well
// under a second: retraction makes Twistycool slower to solve, bench/README.md, so a time limit
// there would make the test depend on the machine's load.)
TEST(Solve, WithRetractionSampling)
{
    solveAndVerify(test::sourcePath("problems/window_3d.cfg"), "rrtconnect", 60, true);
    solveAndVerify(test::sourcePath("problems/corridor_2d.cfg"), "kpiece", 60, true);
    solveAndVerify(test::sourcePath("problems/corridor_2d.cfg"), "rrtconnect", 60, true);
}
