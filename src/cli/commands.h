// SPDX-License-Identifier: BSD-3-Clause
// The hybridcd subcommands. Each takes the arguments after its name and returns the exit status.
#pragma once

#include <string>
#include <vector>

namespace hcd::cli
{
int runSolve(const std::vector<std::string> &args);
int runCheck(const std::vector<std::string> &args);
int runInspect(const std::vector<std::string> &args);
int runBench(const std::vector<std::string> &args);
int runCheckMotion(const std::vector<std::string> &args);
int runClearance(const std::vector<std::string> &args);
int runContacts(const std::vector<std::string> &args);

/// Exit statuses shared by all commands.
enum ExitStatus
{
    kSuccess = 0,
    kBadInput = 1,    ///< unreadable or malformed input, unknown names, misuse
    kNotSolved = 2,   ///< the planner found no exact solution in time
};
}  // namespace hcd::cli
