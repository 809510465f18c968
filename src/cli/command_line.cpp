// SPDX-License-Identifier: BSD-3-Clause
#include "command_line.h"

#include <cmath>

namespace hcd::cli
{
CommandLine::CommandLine(const std::vector<std::string> &args, const std::set<std::string> &valued,
                         const std::set<std::string> &flags)
{
    for (std::size_t i = 0; i < args.size(); ++i)
    {
        const std::string &a = args[i];
        if (a.rfind("--", 0) != 0)
        {
            positionals_.push_back(a);
            continue;
        }
        std::string key = a.substr(2), value;
        const auto eq = key.find('=');
        const bool inlineValue = eq != std::string::npos;
        if (inlineValue)
        {
            value = key.substr(eq + 1);
            key.erase(eq);
        }
        if (flags.count(key))
        {
            if (inlineValue)
                throw UsageError("option --" + key + " takes no value");
            values_[key] = "1";
        }
        else if (valued.count(key))
        {
            if (!inlineValue)
            {
                if (i + 1 >= args.size())
                    throw UsageError("option --" + key + " needs a value");
                value = args[++i];
            }
            values_[key] = value;
        }
        else
            throw UsageError("unknown option --" + key);
    }
}

std::string CommandLine::text(const std::string &key, const std::string &fallback) const
{
    auto it = values_.find(key);
    return it == values_.end() ? fallback : it->second;
}

double CommandLine::number(const std::string &key, double fallback) const
{
    auto it = values_.find(key);
    if (it == values_.end())
        return fallback;
    try
    {
        std::size_t used = 0;
        const double v = std::stod(it->second, &used);
        if (used == it->second.size() && std::isfinite(v))
            return v;
    }
    catch (const std::exception &)
    {
    }
    throw UsageError("option --" + key + " needs a finite number, got '" + it->second + "'");
}

long long CommandLine::integer(const std::string &key, long long fallback) const
{
    auto it = values_.find(key);
    if (it == values_.end())
        return fallback;
    try
    {
        std::size_t used = 0;
        const long long v = std::stoll(it->second, &used);
        if (used == it->second.size())
            return v;
    }
    catch (const std::exception &)
    {
    }
    throw UsageError("option --" + key + " needs a whole number, got '" + it->second + "'");
}

double CommandLine::positiveNumber(const std::string &key, double fallback) const
{
    const double v = number(key, fallback);
    if (v <= 0.0)
        throw UsageError("option --" + key + " needs a positive number, got '" + text(key, "") + "'");
    return v;
}

long long CommandLine::positiveInteger(const std::string &key, long long fallback) const
{
    const long long v = integer(key, fallback);
    if (v < 1)
        throw UsageError("option --" + key + " needs a positive whole number, got '" + text(key, "") + "'");
    return v;
}

const std::string &CommandLine::problem() const
{
    if (positionals_.size() != 1)
        throw UsageError(positionals_.empty() ? "missing the problem file (.cfg)"
                                              : "expected one problem file, got " + std::to_string(positionals_.size()) +
                                                    " positional arguments");
    return positionals_.front();
}

CheckerOptions checkerOptionsOf(const CommandLine &cl)
{
    CheckerOptions options;
    options.semantics = cl.has("surface-only") ? ContactSemantics::SurfaceOnly : ContactSemantics::Solid;
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

std::uint_fast32_t seedOf(const CommandLine &cl)
{
    const long long seed = cl.integer("seed", 1);
    if (seed < 1 || seed > 4294967295LL)
        throw UsageError("option --seed needs a whole number from 1 to 4294967295, got '" + cl.text("seed", "") + "'");
    return std::uint_fast32_t(seed);
}
}  // namespace hcd::cli
