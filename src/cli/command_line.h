// SPDX-License-Identifier: BSD-3-Clause
// One command's options on CLI11, shared by the hybridcd tool and the benchmark programs: CLI11
// reads the words (help, --name=value, unknown names); the values are kept as given and checked
// when read, so every message names its option ("option --time needs a positive number").
#pragma once

#include "hybridcd/query/checker_catalogue.h"

#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace CLI
{
class App;
}

namespace hcd::cli
{
/// Thrown for misuse of the command line; the message is printed with a pointer to --help, and
/// the run ends with status 1.
struct UsageError : std::runtime_error
{
    using std::runtime_error::runtime_error;
};

/// The options of one command: declared before parsing, read after. Not copyable: CLI11 keeps
/// pointers to the stored values.
class CommandLine
{
public:
    /// `app` is the program's own CLI::App or one of its subcommands; it must outlive this object.
    explicit CommandLine(CLI::App &app);
    CommandLine(const CommandLine &) = delete;
    CommandLine &operator=(const CommandLine &) = delete;

    /// `--name VALUE`; `valueName` is shown in the help (SECONDS, FILE, N...).
    CommandLine &option(const std::string &name, const std::string &valueName, const std::string &description);
    /// `--name` without a value.
    CommandLine &flag(const std::string &name, const std::string &description);
    /// The positional arguments, shown as `valueName` (PROBLEM.cfg).
    CommandLine &positionals(const std::string &valueName, const std::string &description);
    /// Text shown at the end of --help (examples, notes); each call appends.
    CommandLine &footer(const std::string &text);

    /// "hybridcd solve": how the help refers to this command.
    std::string commandPath() const;

    const std::vector<std::string> &positionals() const { return positionals_; }
    bool has(const std::string &key) const;
    std::string text(const std::string &key, const std::string &fallback) const;
    double number(const std::string &key, double fallback) const;
    long long integer(const std::string &key, long long fallback) const;
    /// number() that must be greater than zero (times, tolerances, limits); a UsageError names the option.
    double positiveNumber(const std::string &key, double fallback) const;
    /// positiveNumber() of seconds for OMPL's planners, at most kMaxTimeLimitSeconds (beyond it
    /// OMPL's clock overflows into an immediate timeout); a UsageError names the option.
    double timeLimit(const std::string &key, double fallback) const;
    /// integer() that must be at least 1 (counts, limits) and at most `max`, the largest value the
    /// count is kept in; a UsageError names the option.
    long long positiveInteger(const std::string &key, long long fallback,
                              long long max = std::numeric_limits<long long>::max()) const;
    /// The single positional argument every hybridcd command takes (the problem file).
    const std::string &problem() const;

private:
    CLI::App *app_;
    std::map<std::string, std::string> values_;  // map nodes stay put, so CLI11 may point at them
    std::vector<std::string> positionals_;
};

/// Settings every program shares: the last of repeated options wins, and unknown words are kept
/// for parseArguments to report with a suggestion.
void configureApp(CLI::App &app);

/// Parses argv into `app`. Returns std::nullopt when the program should go on, else the exit
/// status: 0 after --help or --version (printed on stdout), 1 after misuse (the message, with a
/// suggestion for a misspelt command or option, and a pointer to --help, on stderr).
std::optional<int> parseArguments(CLI::App &app, int argc, char **argv);

/// Prints "PROGRAM: MESSAGE" and "Run 'COMMAND --help' for the options." on stderr; returns 1.
int reportUsageError(const CommandLine &cl, const std::string &message);

/// The closest of `candidates` to `word` by edit distance, when close enough to be a likely typo.
std::optional<std::string> closestMatch(const std::string &word, const std::vector<std::string> &candidates);

/// "Checkers:" and one line per catalogue entry with its description, for help texts.
std::string checkerHelp(const CheckerCatalogue &checkers);

/// Declares the options every hybridcd command shares: --checker (a comma-separated list when
/// `several`), --surface-only, --mode, --tolerance and --max-triangles.
void addCheckerOptions(CommandLine &cl, bool several);

/// --surface-only, --mode exact|approximate and --tolerance T (the approximate mode's distance;
/// required there, and positive).
CheckerOptions checkerOptionsOf(const CommandLine &cl);

/// The --checker names (default `fallback`), each known to `checkers` and accepting `options`; a
/// UsageError otherwise (listing the valid names, or suggesting the closest).
std::vector<std::string> checkerNamesOf(const CommandLine &cl, const CheckerCatalogue &checkers,
                                        const CheckerOptions &options = {}, const std::string &fallback = "auto");

/// The whole number `text` spells in decimal, with an optional sign and nothing after it; nullopt
/// when it is not one, or beyond long long. Option values are read with it (integer()).
std::optional<long long> wholeNumber(const std::string &text);

/// Splits "a,b,c" (empty items dropped).
std::vector<std::string> splitList(const std::string &text);

/// --level K, a tree level (default 0, the root): a whole number from 0 to the largest int.
int treeLevelOf(const CommandLine &cl);

/// --seed as OMPL takes it: a whole number from 1 to 2^32 - 1 (OMPL ignores a seed of 0).
std::uint_fast32_t seedOf(const CommandLine &cl);
}  // namespace hcd::cli
