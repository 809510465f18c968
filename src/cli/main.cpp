// SPDX-License-Identifier: BSD-3-Clause
// hybridcd: exact collision checking for OMPL rigid-body planning, from the command line.
#include "command_line.h"
#include "commands.h"

#include "hybridcd/io/input_error.h"
#ifdef HYBRIDCD_HAVE_FCL
#include "hybridcd/fcl/fcl_checker.h"
#endif

#include <CLI/CLI.hpp>
#include <ompl/util/Console.h>

#include <iostream>
#include <memory>

namespace
{
using namespace hcd::cli;

struct Command
{
    const char *name;
    const char *summary;
    void (*declare)(CommandLine &);
    int (*run)(const CommandLine &, const hcd::CheckerCatalogue &);
};

const Command kCommands[] = {
    {"solve", "plan a path and write it in OMPL.app's .path format", declareSolve, runSolve},
    {"check", "classify poses: 1 free, 0 colliding, one line per pose", declareCheck, runCheck},
    {"check-motion", "continuous motion checks: 1 free, or 0 and the last free fraction", declareCheckMotion,
     runCheckMotion},
    {"clearance", "distance to the environment per pose (negative: penetration)", declareClearance, runClearance},
    {"contacts", "intersecting triangles or pieces per pose, with a witness point", declareContacts, runContacts},
    {"inspect", "describe the meshes and the hierarchies each checker builds", declareInspect, runInspect},
    {"render", "draw the problem and a path: PNG picture, glTF scene with the path animated", declareRender, runRender},
    {"bench", "OMPL benchmark log of planners and checkers (optionally one shard)", declareBench, runBench},
};

const char *kNotes =
    R"(Every command takes a problem file (OMPL.app's .cfg) and prints its own options and examples with
'hybridcd COMMAND --help'; planners are listed by 'hybridcd solve PROBLEM.cfg --planner help'.
Exit status: 0 success, 1 bad input or options (nothing is written), 2 solve found no path in time.
Output files are written to a temporary file and renamed into place; no output may replace the
.cfg or its meshes.
Closed mesh components are solids (containment is contact); --surface-only treats meshes as
surfaces only, as FCL does (fcl always does).

)";
}  // namespace

int main(int argc, char **argv)
{
#ifdef HYBRIDCD_HAVE_FCL
    const hcd::CheckerCatalogue checkers = hcd::checkersWithFcl();
#else
    const hcd::CheckerCatalogue checkers = hcd::CheckerCatalogue::builtIn();
#endif
    CLI::App app("hybridcd: exact collision checking for OMPL rigid-body planning", "hybridcd");
    configureApp(app);
    app.set_version_flag("--version", std::string("hybridcd ") + HYBRIDCD_VERSION, "Print the version and exit");
    app.require_subcommand(1);
    std::vector<std::unique_ptr<CommandLine>> lines;
    for (const Command &c : kCommands)
    {
        lines.push_back(std::make_unique<CommandLine>(*app.add_subcommand(c.name, c.summary)));
        c.declare(*lines.back());
        lines.back()->footer("\n" + checkerHelp(checkers));
    }
    app.footer(kNotes + checkerHelp(checkers));  // after the commands, which would inherit it

    // No arguments: the overview, as a reminder, but not a success. "help [COMMAND]" as --help.
    std::vector<std::string> args(argv + 1, argv + argc);
    if (args.empty())
    {
        std::cout << app.help();
        return kBadInput;
    }
    if (args[0] == "help" && args.size() <= 2)
    {
        if (args.size() == 1)
        {
            std::cout << app.help();
            return kSuccess;
        }
        args.erase(args.begin());
        args.push_back("--help");
        std::vector<char *> words{argv[0]};
        for (std::string &a : args)
            words.push_back(a.data());
        return parseArguments(app, int(words.size()), words.data()).value_or(kSuccess);
    }
    if (const auto status = parseArguments(app, argc, argv))
        return *status;

    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
    for (std::size_t i = 0; i < lines.size(); ++i)
    {
        if (!app.got_subcommand(kCommands[i].name))
            continue;
        try
        {
            return kCommands[i].run(*lines[i], checkers);
        }
        catch (const UsageError &e)
        {
            return reportUsageError(*lines[i], e.what());
        }
        catch (const std::exception &e)
        {
            // File names and contents in the message may hold control bytes: shown escaped.
            std::cerr << "hybridcd: error: " << hcd::printable(e.what(), true) << '\n';
            return kBadInput;
        }
    }
    return kBadInput;  // parseArguments requires a command
}
