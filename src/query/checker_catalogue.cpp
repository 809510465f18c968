// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/query/checker_catalogue.h"

#include "hybridcd/query/brute_force_checker.h"
#include "hybridcd/query/volume_tree_checker.h"

#include <stdexcept>

namespace hcd
{
namespace
{
template <class Volume>
CheckerEntry treeEntry(const char *name, const char *description)
{
    const std::string n = name;
    return {n, description, [n](const CollisionScene &s, const CheckerOptions &) {
                return std::make_unique<VolumeTreeChecker<Volume>>(s, n);
            }};
}

std::string joined(const std::vector<std::string> &names)
{
    std::string list;
    for (const std::string &n : names)
        list += (list.empty() ? "" : ", ") + n;
    return list;
}
}  // namespace

CheckerCatalogue CheckerCatalogue::builtIn()
{
    CheckerCatalogue c;
    c.add(treeEntry<Obb>("obb", "OBB trees, exact triangle tests at the leaves (the default)"));
    c.add(treeEntry<Ellipsoid>("ellipsoid", "bounding-ellipsoid trees, exact triangle tests at the leaves"));
    c.add(treeEntry<HybridVolume<false>>("hybrid", "OBB and ellipsoid per node, the box tested first"));
    c.add(treeEntry<HybridVolume<true>>("hybrid-ellipsoid-first",
                                        "OBB and ellipsoid per node, the ellipsoid tested first"));
    c.add(treeEntry<Sphere>("sphere", "bounding-sphere trees, exact triangle tests at the leaves"));
    c.add(treeEntry<Aabb>("aabb", "axis-aligned box trees, robot boxes re-boxed in the world frame per query"));
    c.add(treeEntry<FixedAabb>("aabb-fixed",
                               "fixed-size axis-aligned boxes (the cube of each bounding sphere), never refitted"));
    c.add(treeEntry<KDop<14>>("kdop14", "14-DOP trees (axes and cube diagonals), exact triangle tests at the leaves"));
    c.add(treeEntry<KDop<18>>("kdop18", "18-DOP trees (axes and edge diagonals), exact triangle tests at the leaves"));
    c.add(treeEntry<KDop<26>>("kdop26", "26-DOP trees (all 13 directions), exact triangle tests at the leaves"));
    c.add({"bruteforce", "every triangle pair, no hierarchy (the slow reference)",
           [](const CollisionScene &s, const CheckerOptions &) { return std::make_unique<BruteForceChecker>(s); }});
    c.add({"lp", "OBB trees over convex pieces tested by linear programming; exact, or approximate with a tolerance",
           [](const CollisionScene &s, const CheckerOptions &o) {
               PieceStage stage;
               stage.approximateTolerance = o.approximateTolerance;
               return std::make_unique<ObbTreeChecker>(s, "lp", 1, stage);
           },
           false, true});
    // Medial-axis spheres (seed section 3.2, eq. 5): leaves of up to 8 triangles.
    c.add({"medial",
           "sphere trees with the spheres on the medial axis of closed solids; exact, or approximate with a tolerance",
           [](const CollisionScene &s, const CheckerOptions &o) {
               return std::make_unique<VolumeTreeChecker<MedialSphere>>(s, "medial", 8, std::nullopt,
                                                                        o.approximateTolerance);
           },
           false, true});
    // C-tree (seed section 3.3): each node a sphere or an oriented box, whichever is smaller.
    c.add(treeEntry<CTreeVolume>("ctree", "C-trees: per node a sphere or an oriented box, whichever bounds "
                                          "its triangles with less volume; exact triangle tests at the leaves"));
    return c;
}

void CheckerCatalogue::add(CheckerEntry entry)
{
    if (entry.name.empty() || !entry.factory)
        throw std::invalid_argument("a checker entry needs a name and a factory");
    if (find(entry.name))
        throw std::invalid_argument("the checker catalogue already has '" + entry.name + "'");
    entries_.push_back(std::move(entry));
}

std::vector<std::string> CheckerCatalogue::names() const
{
    std::vector<std::string> names;
    for (const CheckerEntry &e : entries_)
        names.push_back(e.name);
    return names;
}

const CheckerEntry *CheckerCatalogue::find(const std::string &name) const
{
    for (const CheckerEntry &e : entries_)
        if (e.name == name)
            return &e;
    return nullptr;
}

void CheckerCatalogue::check(const std::string &name, const CheckerOptions &options) const
{
    const CheckerEntry *entry = find(name);
    if (!entry)
        throw std::invalid_argument("unknown checker '" + name + "'; valid checkers: " + joined(names()));
    if (options.approximateTolerance && !entry->approximate)
    {
        std::vector<std::string> approximate;
        for (const CheckerEntry &e : entries_)
            if (e.approximate)
                approximate.push_back(e.name);
        throw std::invalid_argument("checker '" + name + "' has no approximate mode (checkers that have one: " +
                                    (approximate.empty() ? std::string("none") : joined(approximate)) + ")");
    }
    if (options.approximateTolerance && !(*options.approximateTolerance >= 0.0))
        throw std::invalid_argument("the approximate tolerance must be a non-negative distance");
}

std::unique_ptr<CollisionChecker> CheckerCatalogue::make(const std::string &name, const CollisionScene &scene,
                                                         const CheckerOptions &options) const
{
    check(name, options);
    const CheckerEntry &entry = *find(name);
    if (options.semantics == ContactSemantics::SurfaceOnly || entry.keepsOwnSemantics)
        return entry.factory(scene, options);
    return std::make_unique<SolidSemanticsChecker>(entry.factory(scene, options), scene);
}

std::unique_ptr<CollisionChecker> makeChecker(const std::string &name, const CollisionScene &scene,
                                              const CheckerOptions &options)
{
    // Immutable once built; a catalogue per call would cost little more.
    static const CheckerCatalogue core = CheckerCatalogue::builtIn();
    return core.make(name, scene, options);
}
}  // namespace hcd
