// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/query/checker_catalogue.h"

#include "hybridcd/query/brute_force_checker.h"
#include "hybridcd/query/grid_first_checker.h"
#include "hybridcd/query/octree_checker.h"
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

/// Share of a mesh's surface area (each face once) whose normal is within about 1 degree of a
/// coordinate axis: walls, floors and boxes of architectural models.
void addAxisAlignedArea(const TriangleMesh &mesh, double &aligned, double &total)
{
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
    {
        const Vec3 n = (mesh.corner(t, 1) - mesh.corner(t, 0)).cross(mesh.corner(t, 2) - mesh.corner(t, 0));
        const double twiceArea = n.norm();
        total += twiceArea;
        if (twiceArea > 0.0 && n.cwiseAbs().maxCoeff() >= 0.99985 * twiceArea)
            aligned += twiceArea;
    }
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
    c.add(treeEntry<Obb>("obb", "OBB trees, exact triangle tests at the leaves"));
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
    // Swept-sphere volumes (seed §3.7).
    c.add(treeEntry<Ssv>("ssv", "swept-sphere trees: point, line or rectangle swept spheres, whichever is smallest"));
    // An octree of the environment's volume (seed §3.1), the robot's OBB tree against its cells.
    c.add(
        {"octree", "an octree of the environment (occupied cells only) against the robot's OBB tree",
         [](const CollisionScene &s, const CheckerOptions &) { return std::make_unique<OctreeChecker>(s, "octree"); }});
    c.add({"auto",
           "the default: the volume for the scene, from the bench tables: kdop18 for environments of 10,000 faces or "
           "more, "
           "aabb where 60% of the environment's area faces a coordinate axis, obb otherwise",
           [](const CollisionScene &s, const CheckerOptions &o) -> std::unique_ptr<CollisionChecker> {
               const DistinctFaceMesh environment = withoutRepeatedFaces(s.environment);
               if (environment.mesh->triangleCount() >= 10000)
                   return treeEntry<KDop<18>>("auto", "").factory(s, o);
               double aligned = 0.0, total = 0.0;
               addAxisAlignedArea(*environment.mesh, aligned, total);
               if (total > 0.0 && aligned >= 0.6 * total)
                   return treeEntry<Aabb>("auto", "").factory(s, o);
               return treeEntry<Obb>("auto", "").factory(s, o);
           }});
    c.add({"bruteforce", "every triangle pair, no hierarchy (the slow reference)",
           [](const CollisionScene &s, const CheckerOptions &) { return std::make_unique<BruteForceChecker>(s); },
           false, false, true});
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
    if (entry.keepsOwnSemantics)
        return entry.factory(scene, options);
    std::unique_ptr<CollisionChecker> exact = entry.factory(scene, options);
    if (options.semantics == ContactSemantics::Solid)
        exact = std::make_unique<SolidSemanticsChecker>(std::move(exact), scene);
    if (!options.clearanceGrid || entry.reference || options.approximateTolerance)
        return exact;
    return std::make_unique<GridFirstChecker>(std::move(exact), scene, options.semantics);
}

std::unique_ptr<CollisionChecker> makeChecker(const std::string &name, const CollisionScene &scene,
                                              const CheckerOptions &options)
{
    // Immutable once built; a catalogue per call would cost little more.
    static const CheckerCatalogue core = CheckerCatalogue::builtIn();
    return core.make(name, scene, options);
}
}  // namespace hcd
