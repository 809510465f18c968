// SPDX-License-Identifier: BSD-3-Clause
// A small command-line reader: one positional argument (the problem) and --key value options.
#pragma once

#include "hybridcd/query/checker_registry.h"

#include <cstdint>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace hcd::cli
{
/// Thrown for misuse of the command line; main prints it with the usage and exits with status 1.
struct UsageError : std::runtime_error
{
    using std::runtime_error::runtime_error;
};

class CommandLine
{
public:
    /// `valued` options take a value, `flags` take none; anything else is an error.
    CommandLine(const std::vector<std::string> &args, const std::set<std::string> &valued,
                const std::set<std::string> &flags);

    const std::vector<std::string> &positionals() const { return positionals_; }
    bool has(const std::string &key) const { return values_.count(key) > 0; }
    std::string text(const std::string &key, const std::string &fallback) const;
    double number(const std::string &key, double fallback) const;
    long long integer(const std::string &key, long long fallback) const;
    /// number() that must be greater than zero (times, tolerances, limits); a UsageError names the option.
    double positiveNumber(const std::string &key, double fallback) const;
    /// integer() that must be at least 1 (counts, limits).
    long long positiveInteger(const std::string &key, long long fallback) const;
    /// The single positional argument every command takes (the problem file).
    const std::string &problem() const;

private:
    std::vector<std::string> positionals_;
    std::map<std::string, std::string> values_;
};

/// Options every checker-building command shares: --surface-only, --mode exact|approximate and
/// --tolerance T (the LP checker's approximate mode; required there, and positive).
CheckerOptions checkerOptionsOf(const CommandLine &cl);

/// The valued options every command accepts, added to a command's own: those checkerOptionsOf
/// reads, and --max-triangles (the mesh size bound, see MeshLimits).
inline std::set<std::string> withCommonOptions(std::set<std::string> valued)
{
    valued.insert({"mode", "tolerance", "max-triangles"});
    return valued;
}

/// --seed as OMPL takes it: a whole number from 1 to 2^32 - 1 (OMPL ignores a seed of 0).
std::uint_fast32_t seedOf(const CommandLine &cl);
}  // namespace hcd::cli
