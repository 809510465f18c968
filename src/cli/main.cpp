// SPDX-License-Identifier: BSD-3-Clause
// hybridcd: exact collision checking for OMPL rigid-body planning, from the command line.
#include "command_line.h"
#include "commands.h"

#include "hybridcd/io/input_error.h"
#ifdef HYBRIDCD_HAVE_FCL
#include "hybridcd/fcl/fcl_checker.h"
#endif

#include <ompl/util/Console.h>

#include <iostream>

namespace
{
const char *kUsage = R"(usage: hybridcd COMMAND PROBLEM.cfg [options]

commands:
  solve    plan a path: [--planner NAME] [--time SECONDS] [--seed N] [--checker NAME]
           [--out PATH_FILE] [--param KEY=VALUE,...] [--motion continuous|discrete]
           [--verbose]
  check    classify poses: --states FILE [--checker NAME]   (prints 1 free / 0 colliding per pose)
  check-motion  continuous motion checks: --motions FILE [--checker NAME] [--contact-tolerance FRACTION]
           (two poses per line; prints 1 free, or 0 T with T the last free fraction before contact)
  clearance  distance to the environment per pose (negative: penetration): --states FILE [--checker NAME]
  contacts  intersecting triangles/pieces per pose with a witness point: --states FILE [--checker NAME]
           [--limit N]
  inspect  describe meshes and hierarchies: [--checker NAME[,NAME...]]
           [--level K --export FILE.obj]  (write the volumes of tree level K as a mesh)
  bench    OMPL benchmark log: [--checker NAME[,NAME...]] [--planner NAME[,NAME...]] [--runs N]
           [--time SECONDS] [--memory MB] [--shard I/N] [--out FILE.log] [--motion ...] [--seed N]

Every command takes --max-triangles N (meshes above N triangles, default 2000000, are refused).
Exit status: 0 success, 1 bad input or options (nothing is written), 2 solve found no path in time.
Output files are written to a temporary file and renamed into place; solve's default output is
NAME.solution.path in the current folder, and no output may replace the .cfg or its meshes.

Checkers: obb (default), lp (convex pieces tested by linear programming; --mode exact|approximate
--tolerance T), bruteforce, fcl (when built with FCL).
Closed mesh components are solids (containment is contact); --surface-only treats meshes as
surfaces only, as FCL does (fcl always does). Planners: see 'hybridcd solve --planner help'.
)";
}

int main(int argc, char **argv)
{
    std::vector<std::string> args(argv + 1, argv + argc);
    if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help")
    {
        std::cout << kUsage;
        return args.empty() ? hcd::cli::kBadInput : hcd::cli::kSuccess;
    }
    const std::string command = args[0];
    args.erase(args.begin());
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
#ifdef HYBRIDCD_HAVE_FCL
    hcd::registerFclChecker();
#endif
    try
    {
        if (command == "solve")
            return hcd::cli::runSolve(args);
        if (command == "check")
            return hcd::cli::runCheck(args);
        if (command == "inspect")
            return hcd::cli::runInspect(args);
        if (command == "bench")
            return hcd::cli::runBench(args);
        if (command == "check-motion")
            return hcd::cli::runCheckMotion(args);
        if (command == "clearance")
            return hcd::cli::runClearance(args);
        if (command == "contacts")
            return hcd::cli::runContacts(args);
        throw hcd::cli::UsageError("unknown command '" + command + "'");
    }
    catch (const hcd::cli::UsageError &e)
    {
        std::cerr << "hybridcd: " << e.what() << "\n\n" << kUsage;
    }
    catch (const hcd::InputError &e)
    {
        std::cerr << "hybridcd: error: " << e.what() << '\n';
    }
    catch (const std::exception &e)
    {
        std::cerr << "hybridcd: error: " << e.what() << '\n';
    }
    return hcd::cli::kBadInput;
}
