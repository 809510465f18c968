// SPDX-License-Identifier: BSD-3-Clause
// `hybridcd check-motion` and `hybridcd clearance`: continuous motion checks and distances per line.
#include "command_line.h"
#include "command_scene.h"
#include "commands.h"
#include "motion_verdicts.h"
#include "problem_checks.h"

#include "hybridcd/io/path_file.h"
#include "hybridcd/ompl/continuous_motion_validator.h"
#include "hybridcd/ompl/planning_problem.h"
#include "hybridcd/query/checker_catalogue.h"
#include "hybridcd/query/penetration_estimate.h"

#include <ompl/base/SpaceInformation.h>

#include <chrono>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>

namespace hcd::cli
{
void declareCheckMotion(CommandLine &cl)
{
    cl.positionals("PROBLEM.cfg", "the problem (OMPL.app's .cfg format)")
        .option("motions", "FILE", "two poses per line, start then end (this or --path)")
        .option("path", "FILE", "a path, one state per line (.path format): the motions between consecutive states")
        .option("contact-tolerance", "FRACTION",
                "bracket the first contact to this fraction of the motion, in (0, 1] (default 1e-6)")
        .flag("verdict-only", "only 1 or 0 per motion, stopping at the first contact seen (as a planner checks)");
    addCheckerOptions(cl, false);
    cl.footer(R"(
Prints 1 (free) or 0 T per motion, T the last free fraction before contact. With --path, stderr
also names the first motion of the path that is not free, with its two lines.
For a scene problem (robot.K, obstacle.K) each state holds every robot's pose, robot 1 first.
Examples:
  hybridcd check-motion problems/window_3d.cfg --motions motions.txt
  hybridcd check-motion problems/window_3d.cfg --motions motions.txt --verdict-only
  hybridcd check-motion problems/window_3d.cfg --path window_3d.solution.path --verdict-only
)");
}

namespace
{
/// check-motion for one robot: returns the index of the first motion that is not free, if any.
std::optional<std::size_t> checkRobotMotions(const LoadedProblem &problem,
                                             const std::vector<std::pair<PoseRecord, PoseRecord>> &motions,
                                             std::unique_ptr<CollisionChecker> checker, const std::string &checkerName,
                                             double contactTolerance, bool verdictOnly)
{
    PlanningProblem planning = makePlanningProblem(problem, std::move(checker), MotionCheck::Continuous);
    const auto si = planning.setup->getSpaceInformation();
    ContinuousMotionValidator *validator = planning.continuousValidator.get();
    validator->setContactTolerance(contactTolerance);
    validator->setApplyBounds(false);  // as in `check`, only collisions decide
    validator->setStartChecked(true);  // a listed motion may start in collision: said at once
    ompl::base::State *a = si->allocState(), *b = si->allocState(), *last = si->allocState();
    MotionVerdicts verdicts(verdictOnly);
    const auto start = std::chrono::steady_clock::now();
    for (const auto &[from, to] : motions)
    {
        poseValuesToState(from.values.data(), problem.config.planar, a);
        poseValuesToState(to.values.data(), problem.config.planar, b);
        std::pair<ompl::base::State *, double> lastValid{last, 0.0};
        // Verdict only: OMPL's two-state checkMotion, which stops at the first contact it sees and
        // never brackets it (what a planner pays for a motion it does not extend along).
        const bool free = verdictOnly ? validator->checkMotion(a, b) : validator->checkMotion(a, b, lastValid);
        verdicts.add(free, lastValid.second);
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    si->freeState(a);
    si->freeState(b);
    si->freeState(last);
    verdicts.print(checkerName, seconds);
    return verdicts.firstBlocked();
}

/// What a path's motions came to, on stderr: free throughout, or the first motion that is not.
void reportPath(const std::string &path, const std::vector<std::pair<PoseRecord, PoseRecord>> &motions,
                std::optional<std::size_t> firstBlocked)
{
    if (!firstBlocked)
    {
        std::cerr << "path " << path << ": "
                  << (motions.size() == 1 ? std::string("its one motion is free")
                                          : "all " + std::to_string(motions.size()) + " motions are free")
                  << '\n';
        return;
    }
    const auto &[from, to] = motions[*firstBlocked];
    std::cerr << "path " << path << ": motion " << *firstBlocked + 1 << " of " << motions.size() << " (lines "
              << from.line << "-" << to.line << ") is not free\n";
}
}  // namespace

int runCheckMotion(const CommandLine &cl, const CheckerCatalogue &checkers)
{
    if (cl.has("motions") && cl.has("path"))
        throw UsageError("check-motion takes --motions FILE or --path FILE, not both");
    if (!cl.has("motions") && !cl.has("path"))
        throw UsageError("check-motion needs --motions FILE or --path FILE");
    // A fraction of the motion: zero would bisect without end, more than 1 says nothing.
    const double contactTolerance = cl.positiveNumber("contact-tolerance", 1e-6);
    if (contactTolerance > 1.0)
        throw UsageError("option --contact-tolerance needs a fraction of the motion in (0, 1], got '" +
                         cl.text("contact-tolerance", "") + "'");
    const CheckerOptions options = checkerOptionsOf(cl);
    const std::string checkerName = checkerNamesOf(cl, checkers, options).front();
    const LoadedProblem problem = loadProblemFor(cl);
    const bool onPath = cl.has("path");
    const std::string input = cl.text(onPath ? "path" : "motions", "");
    const std::size_t robots = problem.config.isScene() ? problem.config.robotCount() : 1;
    const auto motions = onPath ? readPathMotions(input, problem.config.planar, robots)
                                : readMotions(input, problem.config.planar, robots);
    const bool verdictOnly = cl.has("verdict-only");
    const std::optional<std::size_t> firstBlocked =
        problem.config.isScene()
            ? runSceneCheckMotion(problem, motions, checkerName, options, verdictOnly)
            : checkRobotMotions(problem, motions, checkers.make(checkerName, problem.scene, options), checkerName,
                                contactTolerance, verdictOnly);
    if (onPath)
        reportPath(input, motions, firstBlocked);
    return kSuccess;
}

void declareClearance(CommandLine &cl)
{
    cl.positionals("PROBLEM.cfg", "the problem (OMPL.app's .cfg format)")
        .option("states", "FILE", "the poses, one per line as in a .path file (required)");
    addCheckerOptions(cl, false);
    cl.footer(R"(
Prints the distance to the environment per pose; colliding poses get minus a penetration estimate
(the deepest penetration among intersecting triangle pairs), and 0 when the robot is contained in
a closed obstacle (or holds one) without a surface crossing, as touching poses do: 'check' or
'contacts' tell them apart. A free pose whose distance rounds to 0 prints 0 and counts as free.
For a scene problem: the smallest distance over the checked pairs (0 when touching) per line of poses.
Examples:
  hybridcd clearance problems/window_3d.cfg --states poses.path
  hybridcd clearance problems/window_3d.cfg --states poses.path --checker bruteforce
)");
}

int runClearance(const CommandLine &cl, const CheckerCatalogue &checkers)
{
    if (!cl.has("states"))
        throw UsageError("clearance needs --states FILE");
    const CheckerOptions options = checkerOptionsOf(cl);
    const std::string checkerName = checkerNamesOf(cl, checkers, options).front();
    const LoadedProblem problem = loadProblemFor(cl);
    if (problem.config.isScene())
        return runSceneClearance(problem, cl.text("states", ""), checkerName, options);
    const auto poses = readPoses(cl.text("states", ""), problem.config.planar);
    const auto checker = checkers.make(checkerName, problem.scene, options);
    std::ostringstream out;
    out << std::setprecision(std::numeric_limits<double>::max_digits10);
    // Free: the exact distance. Colliding: minus the penetration estimate (0 when contained in a
    // solid, where no triangle pair gives a direction), as the OMPL adapter's clearance() reports.
    std::size_t free = 0;
    const auto start = std::chrono::steady_clock::now();
    QueryContext context;
    for (const PoseRecord &p : poses)
    {
        const RigidTransform pose = transformOfRow(p.values.data(), problem.config.planar);
        const SignedClearance clearance = signedClearance(*checker, problem.scene, pose, context);
        free += clearance.colliding ? 0 : 1;
        out << clearance.value << '\n';
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cout << out.str();
    std::cerr << "computed the clearance of " << poses.size() << " poses with '" << checker->name() << "': " << free
              << " free, " << poses.size() - free << " colliding; mean "
              << (poses.empty() ? 0.0 : 1e9 * seconds / double(poses.size())) << " ns per clearance\n";
    return kSuccess;
}
}  // namespace hcd::cli
