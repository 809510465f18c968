// SPDX-License-Identifier: BSD-3-Clause
#include "command_line.h"

#include "hybridcd/io/input_error.h"
#include "hybridcd/io/problem_config.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <sstream>

namespace hcd::cli
{
namespace
{
// "hybridcd solve" for a subcommand, "hybridcd" for the program.
std::string pathOf(const CLI::App *app)
{
    std::string path = app->get_name();
    for (const CLI::App *p = app->get_parent(); p; p = p->get_parent())
        path = p->get_name() + " " + path;
    return path;
}

// The deepest subcommand the command line selected (the program itself when none).
CLI::App *selectedApp(CLI::App &app)
{
    CLI::App *current = &app;
    while (!current->get_subcommands().empty())
        current = current->get_subcommands().front();
    return current;
}

int printUsageError(const CLI::App *app, const std::string &message)
{
    std::string program = pathOf(app);
    program = program.substr(0, program.find(' '));
    // The message quotes command-line words, which may hold control bytes: shown escaped.
    std::cerr << program << ": " << printable(message, true) << "\nRun '" << pathOf(app)
              << " --help' for the options.\n";
    return 1;
}

// Optimal string alignment distance: edits, with a swap of neighbours as one edit.
std::size_t editDistance(const std::string &a, const std::string &b)
{
    std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
    for (std::size_t i = 0; i <= a.size(); ++i)
        d[i][0] = i;
    for (std::size_t j = 0; j <= b.size(); ++j)
        d[0][j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i)
        for (std::size_t j = 1; j <= b.size(); ++j)
        {
            d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
                d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
        }
    return d[a.size()][b.size()];
}

// An unknown word left over after parsing: a misspelt option, or a stray argument.
std::string describeExtra(const CLI::App &app, const std::string &word)
{
    if (word.rfind("-", 0) != 0)
        return "unexpected argument '" + word + "'";
    const std::string name = word.substr(0, word.find('='));
    std::vector<std::string> known;
    for (const CLI::Option *o : app.get_options())
        for (const std::string &n : o->get_lnames())
            known.push_back("--" + n);
    std::string message = "unknown option " + name;
    if (const auto close = closestMatch(name, known))
        message += ", did you mean " + *close + "?";
    return message;
}
}  // namespace

CommandLine::CommandLine(CLI::App &app) : app_(&app) {}

CommandLine &CommandLine::option(const std::string &name, const std::string &valueName, const std::string &description)
{
    app_->add_option("--" + name, values_[name], description)->type_name(valueName);
    return *this;
}

CommandLine &CommandLine::flag(const std::string &name, const std::string &description)
{
    app_->add_flag("--" + name, description);
    return *this;
}

CommandLine &CommandLine::positionals(const std::string &valueName, const std::string &description)
{
    app_->add_option("problem", positionals_, description)->type_name(valueName);
    return *this;
}

CommandLine &CommandLine::footer(const std::string &text)
{
    app_->footer(app_->get_footer() + text);
    return *this;
}

std::string CommandLine::commandPath() const { return pathOf(app_); }

bool CommandLine::has(const std::string &key) const
{
    const CLI::Option *o = app_->get_option_no_throw("--" + key);
    return o && o->count() > 0;
}

std::string CommandLine::text(const std::string &key, const std::string &fallback) const
{
    return has(key) ? values_.at(key) : fallback;
}

double CommandLine::number(const std::string &key, double fallback) const
{
    if (!has(key))
        return fallback;
    const std::string &value = values_.at(key);
    // Decimal numbers only (strtod would also read hexadecimal, "0x10" as 16), blanks around them
    // allowed; strtod, not stod, which refuses subnormal numbers.
    const std::size_t first = value.find_first_not_of(" \t"), last = value.find_last_not_of(" \t");
    const std::string word = first == std::string::npos ? std::string() : value.substr(first, last - first + 1);
    if (!word.empty() && word.find_first_not_of("0123456789+-.eE") == std::string::npos)
    {
        char *end = nullptr;
        const double v = std::strtod(word.c_str(), &end);
        if (end == word.c_str() + word.size() && std::isfinite(v))
            return v;
    }
    throw UsageError("option --" + key + " needs a finite number, got '" + value + "'");
}

long long CommandLine::integer(const std::string &key, long long fallback) const
{
    if (!has(key))
        return fallback;
    const std::string &value = values_.at(key);
    if (const std::optional<long long> v = wholeNumber(value))
        return *v;
    throw UsageError("option --" + key + " needs a whole number, got '" + value + "'");
}

double CommandLine::positiveNumber(const std::string &key, double fallback) const
{
    const double v = number(key, fallback);
    if (v <= 0.0)
        throw UsageError("option --" + key + " needs a positive number, got '" + text(key, "") + "'");
    return v;
}

double CommandLine::timeLimit(const std::string &key, double fallback) const
{
    const double v = positiveNumber(key, fallback);
    if (v > kMaxTimeLimitSeconds)
        throw UsageError("option --" + key + " needs at most " + kMaxTimeLimitText + ", got '" + text(key, "") + "'");
    return v;
}

long long CommandLine::positiveInteger(const std::string &key, long long fallback, long long max) const
{
    const long long v = integer(key, fallback);
    if (v < 1)
        throw UsageError("option --" + key + " needs a positive whole number, got '" + text(key, "") + "'");
    if (v > max)
        throw UsageError("option --" + key + " needs a positive whole number up to " + std::to_string(max) + ", got '" +
                         text(key, "") + "'");
    return v;
}

const std::string &CommandLine::problem() const
{
    if (positionals_.size() != 1)
        throw UsageError(positionals_.empty() ? "missing the problem file (.cfg)"
                                              : "expected one problem file, got " +
                                                    std::to_string(positionals_.size()) + " positional arguments");
    return positionals_.front();
}

void configureApp(CLI::App &app)
{
    app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    app.allow_extras();
    app.get_formatter()->column_width(34);
}

std::optional<int> parseArguments(CLI::App &app, int argc, char **argv)
{
    // CLI11 2.1 reports an unknown command as a stray argument: name it, with the closest command.
    const std::vector<CLI::App *> commands = app.get_subcommands([](CLI::App *) { return true; });
    if (!commands.empty() && argc > 1 && argv[1][0] != '-')
    {
        const std::string word = argv[1];
        std::vector<std::string> names;
        for (const CLI::App *c : commands)
            names.push_back(c->get_name());
        if (std::find(names.begin(), names.end(), word) == names.end())
        {
            std::string message = "unknown command '" + word + "'";
            if (const auto close = closestMatch(word, names))
                message += ", did you mean '" + *close + "'?";
            return printUsageError(&app, message);
        }
    }
    try
    {
        app.parse(argc, argv);
    }
    catch (const CLI::Success &e)  // --help, --version
    {
        return app.exit(e, std::cout, std::cerr);
    }
    catch (const CLI::ParseError &e)
    {
        return printUsageError(selectedApp(app), e.what());
    }
    CLI::App *selected = selectedApp(app);
    for (const CLI::App *a = selected; a; a = a->get_parent())
        if (!a->remaining().empty())
        {
            const std::vector<std::string> extras = a->remaining();
            const auto option =
                std::find_if(extras.begin(), extras.end(), [](const std::string &w) { return w.rfind('-', 0) == 0; });
            return printUsageError(selected, describeExtra(*a, option != extras.end() ? *option : extras.front()));
        }
    return std::nullopt;
}

int reportUsageError(const CommandLine &cl, const std::string &message)
{
    std::string program = cl.commandPath();
    program = program.substr(0, program.find(' '));
    std::cerr << program << ": " << printable(message, true) << "\nRun '" << cl.commandPath()
              << " --help' for the options.\n";
    return 1;
}

std::optional<std::string> closestMatch(const std::string &word, const std::vector<std::string> &candidates)
{
    std::optional<std::string> best;
    std::size_t bestDistance = 0;
    for (const std::string &c : candidates)
    {
        const std::size_t d = editDistance(word, c);
        if (!best || d < bestDistance)
        {
            best = c;
            bestDistance = d;
        }
    }
    // Two edits at most, and fewer than the word has letters (so "x" suggests nothing).
    const std::size_t letters = word.size() - std::min<std::size_t>(word.find_first_not_of('-'), word.size());
    if (best && bestDistance <= 2 && bestDistance < letters)
        return best;
    return std::nullopt;
}

std::string checkerHelp(const CheckerCatalogue &checkers)
{
    std::size_t width = 0;
    for (const CheckerEntry &e : checkers.entries())
        width = std::max(width, e.name.size());
    std::string text = "Checkers (--checker NAME):\n";
    for (const CheckerEntry &e : checkers.entries())
        text += "  " + e.name + std::string(width + 2 - e.name.size(), ' ') + e.description + '\n';
    return text;
}

void addCheckerOptions(CommandLine &cl, bool several)
{
    cl.option("checker", several ? "NAME[,NAME...]" : "NAME",
              several ? "the checkers to use, comma-separated (default auto; listed below)"
                      : "the collision checker (default auto; listed below)")
        .flag("surface-only", "treat meshes as surfaces only, as FCL does (default: closed components are solids)")
        .flag("no-grid", "no clearance grid first (default: a grid of the environment proves what it can first)")
        .option("mode", "exact|approximate",
                "exact (default), or approximate with --tolerance (the lp and medial checkers)")
        .option("tolerance", "T", "approximate mode: contact may be reported up to distance T apart (positive)")
        .option("max-triangles", "N", "refuse meshes of more than N triangles (default 2000000, at most 1000000000)");
}

CheckerOptions checkerOptionsOf(const CommandLine &cl)
{
    CheckerOptions options;
    options.semantics = cl.has("surface-only") ? ContactSemantics::SurfaceOnly : ContactSemantics::Solid;
    options.clearanceGrid = !cl.has("no-grid");
    const std::string mode = cl.text("mode", "exact");
    if (mode == "approximate")
    {
        if (!cl.has("tolerance"))
            throw UsageError("option --mode approximate needs --tolerance T, a positive distance");
        options.approximateTolerance = cl.positiveNumber("tolerance", 0.0);
    }
    else if (mode != "exact")
        throw UsageError("option --mode expects exact or approximate, got '" + mode + "'");
    else if (cl.has("tolerance"))
        throw UsageError("option --tolerance applies to --mode approximate");
    return options;
}

std::vector<std::string> checkerNamesOf(const CommandLine &cl, const CheckerCatalogue &checkers,
                                        const CheckerOptions &options, const std::string &fallback)
{
    const std::vector<std::string> names = splitList(cl.text("checker", fallback));
    if (names.empty())
        throw UsageError("option --checker needs at least one checker name");
    for (const std::string &name : names)
        try
        {
            checkers.check(name, options);
        }
        catch (const std::invalid_argument &e)
        {
            std::string message = e.what();
            if (!checkers.find(name))
                if (const auto close = closestMatch(name, checkers.names()))
                    message += "; did you mean '" + *close + "'?";
            if (checkers.find(name) && options.approximateTolerance)
                message = "option --mode approximate: " + message;
            throw UsageError(message);
        }
    return names;
}

std::optional<long long> wholeNumber(const std::string &text)
{
    // stoll alone would skip leading blanks and stop at the first non-digit ("7x" would read as 7).
    if (text.empty() || std::isspace(static_cast<unsigned char>(text.front())))
        return std::nullopt;
    try
    {
        std::size_t used = 0;
        const long long v = std::stoll(text, &used);
        if (used == text.size())
            return v;
    }
    catch (const std::exception &)  // not a number, or beyond long long
    {
    }
    return std::nullopt;
}

std::vector<std::string> splitList(const std::string &text)
{
    std::vector<std::string> items;
    std::stringstream s(text);
    std::string item;
    while (std::getline(s, item, ','))
        if (!item.empty())
            items.push_back(item);
    return items;
}

int treeLevelOf(const CommandLine &cl)
{
    const long long level = cl.integer("level", 0);
    if (level < 0)
        throw UsageError("option --level needs a non-negative tree level, got '" + cl.text("level", "") + "'");
    if (level > std::numeric_limits<int>::max())
        throw UsageError("option --level needs a tree level up to " + std::to_string(std::numeric_limits<int>::max()) +
                         ", got '" + cl.text("level", "") + "'");
    return int(level);
}

std::uint_fast32_t seedOf(const CommandLine &cl)
{
    const long long seed = cl.integer("seed", 1);
    if (seed < 1 || seed > 4294967295LL)
        throw UsageError("option --seed needs a whole number from 1 to 4294967295, got '" + cl.text("seed", "") + "'");
    return std::uint_fast32_t(seed);
}
}  // namespace hcd::cli
