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
        options.approximateTolerance = cl.number("tolerance", 0.0);
        if (options.approximateTolerance < 0.0)
            throw UsageError("--tolerance needs a non-negative distance");
    }
    else if (mode != "exact")
        throw UsageError("--mode expects exact or approximate, got '" + mode + "'");
    else if (cl.has("tolerance"))
        throw UsageError("--tolerance applies to --mode approximate");
    return options;
}
}  // namespace hcd::cli
