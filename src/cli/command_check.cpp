// SPDX-License-Identifier: BSD-3-Clause
// `hybridcd check`: one line per pose, 1 collision-free or 0 colliding; a summary on stderr.
#include "command_line.h"
#include "command_scene.h"
#include "commands.h"
#include "problem_checks.h"

#include "hybridcd/io/path_file.h"
#include "hybridcd/io/problem_scene.h"
#include "hybridcd/query/checker_catalogue.h"

#include <chrono>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace hcd::cli
{
void declareCheck(CommandLine &cl)
{
    cl.positionals("PROBLEM.cfg", "the problem (OMPL.app's .cfg format)")
        .option("states", "FILE", "the poses, one per line as in a .path file (required)");
    addCheckerOptions(cl, false);
    cl.footer(R"(
Prints 1 (collision-free) or 0 (colliding) per pose on stdout, and a summary on stderr.
For a scene problem (robot.K, obstacle.K) each line holds every robot's pose, robot 1 first.
Examples:
  hybridcd check problems/window_3d.cfg --states poses.path
  hybridcd check problems/window_3d.cfg --states poses.path --checker lp --mode approximate --tolerance 0.01
)");
}

int runCheck(const CommandLine &cl, const CheckerCatalogue &checkers)
{
    if (!cl.has("states"))
        throw UsageError("check needs --states FILE");
    const CheckerOptions options = checkerOptionsOf(cl);
    const std::string checkerName = checkerNamesOf(cl, checkers, options).front();
    const LoadedProblem problem = loadProblemFor(cl);
    if (problem.config.isScene())
        return runSceneCheck(problem, cl.text("states", ""), checkerName, options);
    const std::vector<PoseRecord> poses = readPoses(cl.text("states", ""), problem.config.planar);
    const auto checker = checkers.make(checkerName, problem.scene, options);

    std::string out;
    out.reserve(poses.size() * 2);
    std::size_t free = 0;
    QueryContext context;
    const auto start = std::chrono::steady_clock::now();
    for (const PoseRecord &pose : poses)
    {
        const bool collides = checker->collides(transformOfRow(pose.values.data(), problem.config.planar), context);
        free += collides ? 0 : 1;
        out += collides ? "0\n" : "1\n";
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cout << out << std::flush;
    std::cerr << "checked " << poses.size() << " poses with '" << checker->name() << "': " << free << " free, "
              << poses.size() - free << " colliding; mean "
              << (poses.empty() ? 0.0 : 1e9 * seconds / double(poses.size())) << " ns per check\n";
    return kSuccess;
}
}  // namespace hcd::cli

namespace hcd::cli
{
void declareContacts(CommandLine &cl)
{
    cl.positionals("PROBLEM.cfg", "the problem (OMPL.app's .cfg format)")
        .option("states", "FILE", "the poses, one per line as in a .path file (required)")
        .option("limit", "N", "report at most N contacts per pose (default 1000)");
    addCheckerOptions(cl, false);
    cl.footer(R"(
Examples:
  hybridcd contacts problems/window_3d.cfg --states poses.path
  hybridcd contacts problems/window_3d.cfg --states poses.path --limit 10 --surface-only
)");
}

int runContacts(const CommandLine &cl, const CheckerCatalogue &checkers)
{
    if (!cl.has("states"))
        throw UsageError("contacts needs --states FILE");
    const long long limit = cl.positiveInteger("limit", 1000);
    const CheckerOptions options = checkerOptionsOf(cl);
    const std::string checkerName = checkerNamesOf(cl, checkers, options).front();
    const LoadedProblem problem = loadProblemFor(cl);
    // Contacts are robot 1's triangle pairs with the environment mesh: on a scene the other robots
    // and the primitive obstacles would be left out, and a colliding pose listed without contacts.
    if (problem.config.isScene())
        throw InputError(problem.config.path, 0,
                         "contacts lists one robot's triangle pairs with the environment mesh, and this is a "
                         "scene problem (several robots or primitive obstacles): use check or clearance");
    const std::vector<PoseRecord> poses = readPoses(cl.text("states", ""), problem.config.planar);
    const auto checker = checkers.make(checkerName, problem.scene, options);
    std::ostringstream out;
    out << std::setprecision(10);
    QueryContext context;
    for (std::size_t p = 0; p < poses.size(); ++p)
    {
        const auto found = checker->contacts(transformOfRow(poses[p].values.data(), problem.config.planar),
                                             std::size_t(limit), context);
        out << "pose " << p + 1 << " (line " << poses[p].line << "): " << found.size() << " contact"
            << (found.size() == 1 ? "" : "s") << (found.size() == std::size_t(limit) ? " (limit reached)" : "") << '\n';
        for (const ContactPair &c : found)
        {
            const char *kind = c.kind == ContactPair::Kind::Triangles ? "triangles"
                               : c.kind == ContactPair::Kind::Pieces  ? "pieces"
                                                                      : "containment (components)";
            out << "  " << kind << " robot " << c.robotElement << " environment " << c.environmentElement << " at "
                << c.witness.x() << ' ' << c.witness.y() << ' ' << c.witness.z() << '\n';
        }
    }
    std::cout << out.str();
    return kSuccess;
}
}  // namespace hcd::cli
