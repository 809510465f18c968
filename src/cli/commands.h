// SPDX-License-Identifier: BSD-3-Clause
// The hybridcd subcommands. Each declares its options on a CommandLine (with examples for its
// --help), then runs on the parsed options and returns the exit status.
#pragma once

#include "command_line.h"

#include "hybridcd/query/checker_catalogue.h"

namespace hcd::cli
{
void declareSolve(CommandLine &cl);
void declareCheck(CommandLine &cl);
void declareInspect(CommandLine &cl);
void declareBench(CommandLine &cl);
void declareCheckMotion(CommandLine &cl);
void declareClearance(CommandLine &cl);
void declareContacts(CommandLine &cl);
void declareRender(CommandLine &cl);

int runSolve(const CommandLine &cl, const CheckerCatalogue &checkers);
int runCheck(const CommandLine &cl, const CheckerCatalogue &checkers);
int runInspect(const CommandLine &cl, const CheckerCatalogue &checkers);
int runBench(const CommandLine &cl, const CheckerCatalogue &checkers);
int runCheckMotion(const CommandLine &cl, const CheckerCatalogue &checkers);
int runClearance(const CommandLine &cl, const CheckerCatalogue &checkers);
int runContacts(const CommandLine &cl, const CheckerCatalogue &checkers);
int runRender(const CommandLine &cl, const CheckerCatalogue &checkers);

/// Exit statuses shared by all commands.
enum ExitStatus
{
    kSuccess = 0,
    kBadInput = 1,   ///< unreadable or malformed input, unknown names, misuse
    kNotSolved = 2,  ///< no exact solution in time (solve may have written an approximate path)
};
}  // namespace hcd::cli
