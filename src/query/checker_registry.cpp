// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/query/checker_registry.h"

#include "hybridcd/query/brute_force_checker.h"
#include "hybridcd/query/volume_tree_checker.h"

#include <map>
#include <mutex>
#include <stdexcept>

namespace hcd
{
namespace
{
struct Registry
{
    std::mutex mutex;
    std::vector<std::pair<std::string, CheckerFactory>> entries;
};

// Built on first use with the core checkers, so no set-up call can be forgotten.
Registry &registry()
{
    static Registry r{{},
                      {{"obb", [](const CollisionScene &s) { return std::make_unique<ObbTreeChecker>(s, "obb"); }},
                       {"bruteforce", [](const CollisionScene &s) { return std::make_unique<BruteForceChecker>(s); }}}};
    return r;
}
}  // namespace

std::vector<std::string> checkerNames()
{
    Registry &r = registry();
    std::lock_guard<std::mutex> lock(r.mutex);
    std::vector<std::string> names;
    for (const auto &e : r.entries)
        names.push_back(e.first);
    return names;
}

std::unique_ptr<CollisionChecker> makeChecker(const std::string &name, const CollisionScene &scene)
{
    CheckerFactory factory;
    {
        Registry &r = registry();
        std::lock_guard<std::mutex> lock(r.mutex);
        for (const auto &e : r.entries)
            if (e.first == name)
                factory = e.second;
    }
    if (!factory)
    {
        std::string list;
        for (const std::string &n : checkerNames())
            list += (list.empty() ? "" : ", ") + n;
        throw std::invalid_argument("unknown checker '" + name + "'; valid checkers: " + list);
    }
    return factory(scene);
}

void registerChecker(const std::string &name, CheckerFactory factory)
{
    Registry &r = registry();
    std::lock_guard<std::mutex> lock(r.mutex);
    for (auto &e : r.entries)
        if (e.first == name)
        {
            e.second = std::move(factory);
            return;
        }
    r.entries.emplace_back(name, std::move(factory));
}
}  // namespace hcd
