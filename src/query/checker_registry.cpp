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
    struct Entry
    {
        std::string name;
        CheckerFactory factory;
        bool surfaceOnly;
    };
    std::vector<Entry> entries;
};

// Built on first use with the core checkers, so no set-up call can be forgotten.
Registry &registry()
{
    static Registry r{{},
                      {{"obb", [](const CollisionScene &s, const CheckerOptions &) { return std::make_unique<ObbTreeChecker>(s, "obb"); },
                        false},
                       {"ellipsoid",
                        [](const CollisionScene &s, const CheckerOptions &) {
                            return std::make_unique<VolumeTreeChecker<Ellipsoid>>(s, "ellipsoid");
                        },
                        false},
                       {"hybrid",
                        [](const CollisionScene &s, const CheckerOptions &) {
                            return std::make_unique<VolumeTreeChecker<HybridVolume<false>>>(s, "hybrid");
                        },
                        false},
                       {"hybrid-ellipsoid-first",
                        [](const CollisionScene &s, const CheckerOptions &) {
                            return std::make_unique<VolumeTreeChecker<HybridVolume<true>>>(s, "hybrid-ellipsoid-first");
                        },
                        false},
                       {"bruteforce",
                        [](const CollisionScene &s, const CheckerOptions &) { return std::make_unique<BruteForceChecker>(s); },
                        false},
                       {"lp",
                        [](const CollisionScene &s, const CheckerOptions &o) {
                            PieceStage stage;
                            stage.approximateTolerance = o.approximateTolerance;
                            return std::make_unique<ObbTreeChecker>(s, "lp", 1, stage);
                        },
                        false}}};
    return r;
}
}  // namespace

std::vector<std::string> checkerNames()
{
    Registry &r = registry();
    std::lock_guard<std::mutex> lock(r.mutex);
    std::vector<std::string> names;
    for (const auto &e : r.entries)
        names.push_back(e.name);
    return names;
}

std::unique_ptr<CollisionChecker> makeChecker(const std::string &name, const CollisionScene &scene,
                                              const CheckerOptions &options)
{
    CheckerFactory factory;
    bool surfaceOnly = false;
    {
        Registry &r = registry();
        std::lock_guard<std::mutex> lock(r.mutex);
        for (const auto &e : r.entries)
            if (e.name == name)
            {
                factory = e.factory;
                surfaceOnly = e.surfaceOnly;
            }
    }
    if (!factory)
    {
        std::string list;
        for (const std::string &n : checkerNames())
            list += (list.empty() ? "" : ", ") + n;
        throw std::invalid_argument("unknown checker '" + name + "'; valid checkers: " + list);
    }
    if (options.semantics == ContactSemantics::SurfaceOnly || surfaceOnly)
        return factory(scene, options);
    return std::make_unique<SolidSemanticsChecker>(factory(scene, options), scene);
}

void registerChecker(const std::string &name, CheckerFactory factory, bool surfaceOnly)
{
    Registry &r = registry();
    std::lock_guard<std::mutex> lock(r.mutex);
    for (auto &e : r.entries)
        if (e.name == name)
        {
            e.factory = std::move(factory);
            e.surfaceOnly = surfaceOnly;
            return;
        }
    r.entries.push_back({name, std::move(factory), surfaceOnly});
}
}  // namespace hcd
