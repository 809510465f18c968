// SPDX-License-Identifier: BSD-3-Clause
// The common interface of every collision checker (brute force, OBB tree, ...).
#pragma once

#include "hybridcd/bvh/export_mesh.h"
#include "hybridcd/geometry/collision_scene.h"
#include "hybridcd/geometry/rigid_transform.h"
#include "hybridcd/query/query_context.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace hcd
{
/// One intersecting part pair found by a contact query: the paper's "intersecting parts".
struct ContactPair
{
    enum class Kind
    {
        Triangles,    ///< robot triangle and environment triangle (mesh indices)
        Pieces,       ///< robot and environment convex pieces (LP approximate mode)
        Containment,  ///< one object inside a solid of the other (component indices)
    };
    Kind kind = Kind::Triangles;
    std::uint32_t robotElement = 0;
    std::uint32_t environmentElement = 0;
    Vec3 witness = Vec3::Zero();  ///< a world point in both parts
};

/// A robot triangle and an environment triangle by a checker's own indices: what its swept
/// proximity lists (listSweptNearPairs) and takes back (sweptNearPairsAmong).
struct TrianglePair
{
    std::uint32_t robot = 0;
    std::uint32_t environment = 0;
};

/// One line of `inspect` output about a checker's data structures.
struct HierarchyReport
{
    std::string label;  ///< e.g. "robot OBB tree"
    std::size_t nodes = 0;
    std::size_t depth = 0;
    double buildSeconds = 0.0;
    std::size_t memoryBytes = 0;
    /// Mean over sampled non-flat nodes of (node volume) / (volume of the convex hull of the node's
    /// triangles): how tightly the volumes wrap their content. NaN when not measured.
    double meanVolumeRatio = std::numeric_limits<double>::quiet_NaN();
    std::size_t ratioNodes = 0;  ///< nodes the mean was taken over
};

/// The volumes of one level of a checker's two hierarchies, as meshes (bvh/export_mesh.h).
struct LevelVolumes
{
    std::string kind;            ///< the volume type, e.g. "OBB"
    ExportMesh robot;            ///< in the robot's own frame
    ExportMesh environment;      ///< in the world frame
    std::size_t robotDepth = 0;  ///< levels of the robot tree: `level` ranges over 0 to robotDepth - 1
    std::size_t environmentDepth = 0;
};

/// Answers "does the robot at this pose touch the environment?". Touching counts as collision.
/// Implementations are immutable after construction and safe to query from many threads at once.
/// Each query takes the caller's QueryContext (scratch, counters, coherence), one per thread; the
/// forms without one make a fresh context per call, which allocates: use them for one-off queries.
class CollisionChecker
{
public:
    virtual ~CollisionChecker() = default;

    /// The name `--checker` selects this checker by.
    virtual std::string name() const = 0;

    /// True when the robot placed by `worldFromRobot` shares a point with the environment.
    /// A non-finite pose is reported as a collision (it can never be shown to be free).
    bool collides(const RigidTransform &worldFromRobot, QueryContext &context) const
    {
        return doCollides(worldFromRobot, context);
    }
    bool collides(const RigidTransform &worldFromRobot, QueryStats *stats = nullptr) const;

    /// Distance between the robot placed by `worldFromRobot` and the environment: 0 when they touch
    /// (decided exactly), otherwise the smallest triangle-to-triangle distance (floating point,
    /// relative error of a few ulps). Infinite when either mesh is empty; 0 for a non-finite pose.
    double distance(const RigidTransform &worldFromRobot, QueryContext &context) const
    {
        return doDistance(worldFromRobot, context);
    }
    double distance(const RigidTransform &worldFromRobot, QueryStats *stats = nullptr) const;

    /// distance() for a pose the caller has already proved free (collides() would answer false):
    /// hierarchical checkers then skip their own collision pass. The answer is distance()'s; on a
    /// pose that is not free it is unspecified.
    double distanceOfFreePose(const RigidTransform &worldFromRobot, QueryContext &context) const
    {
        return doDistanceOfFreePose(worldFromRobot, context);
    }

    /// Every intersecting part pair at this pose, up to `limit` of them (empty when free). Checkers
    /// without contact reporting give none; hierarchical and brute-force checkers report them.
    std::vector<ContactPair> contacts(const RigidTransform &worldFromRobot, std::size_t limit,
                                      QueryContext &context) const
    {
        return doContacts(worldFromRobot, limit, context);
    }
    std::vector<ContactPair> contacts(const RigidTransform &worldFromRobot, std::size_t limit) const;

    /// Proximity: true when the distance may be at most `delta` (so false proves distance > delta).
    /// Touching gives true for any delta >= 0.
    bool withinDistance(const RigidTransform &worldFromRobot, double delta, QueryContext &context) const
    {
        return doWithinDistance(worldFromRobot, delta, context);
    }
    bool withinDistance(const RigidTransform &worldFromRobot, double delta, QueryStats *stats = nullptr) const;

    /// Swept proximity: false proves that no robot point p (robot frame) comes within
    /// `translationSlack + radialSlack * |p|` of the environment at this pose, which is how far p can
    /// move during a motion interval (translation plus rotation about the robot origin). A checker
    /// built from a scene that turns about the robot's z axis (turnsAboutRobotZ()) counts
    /// `|(p.x, p.y)|` instead of `|p|`, here and in every swept query below: only for motions that
    /// turn the robot about that axis alone (SE(2)).
    bool withinSweptDistance(const RigidTransform &worldFromRobot, double translationSlack, double radialSlack,
                             double robotRadius, QueryContext &context) const
    {
        return doWithinSweptDistance(worldFromRobot, translationSlack, radialSlack, robotRadius, context);
    }
    bool withinSweptDistance(const RigidTransform &worldFromRobot, double translationSlack, double radialSlack,
                             double robotRadius, QueryStats *stats = nullptr) const;

    /// A cheap first word on swept proximity, for motion validators: true proves what a false from
    /// withinSweptDistance proves (no robot point p comes within translationSlack + radialSlack * |p|
    /// of the environment); false proves nothing. Checkers with a first layer (the clearance grid)
    /// answer from it alone; the others prove nothing. A negative or non-finite slack, or a
    /// non-finite pose, gives false.
    bool sweptFreeByFirstLayer(const RigidTransform &worldFromRobot, double translationSlack, double radialSlack) const
    {
        if (!slacksAreFinite(translationSlack, radialSlack) || !worldFromRobot.isFinite())
            return false;
        return doSweptFreeByFirstLayer(worldFromRobot, translationSlack, radialSlack);
    }
    /// The first layer's cell size (world units; 0 without a first layer). A sweep many cells wider
    /// than this is better split and proved by the first layer than sent to the exact query, which
    /// grows every box by the whole sweep.
    virtual double firstLayerCellSize() const { return 0.0; }
    /// Whether the swept queries count radial slack from the robot's z axis
    /// (CollisionScene::turnsAboutRobotZ) rather than from its origin.
    virtual bool turnsAboutRobotZ() const { return false; }

    /// Swept proximity that says what is near: when it returns true, `near` holds every pair of
    /// robot and environment triangles that may come within the swept slack at this pose (as
    /// withinSweptDistance measures it), and every other pair is proved farther apart; so proving
    /// the listed pairs apart over a part of a motion interval proves the robot's surface apart from
    /// the environment's there (and so the robot free there when some state joined to that part by
    /// such proofs is known free: neither object enters the other while the surfaces stay apart).
    /// Returns false, `near` then meaning nothing, when the checker cannot
    /// list pairs (the default), when more than `limit` pairs are near, or when one object is inside
    /// a solid of the other at this pose. Slacks must not both be 0.
    bool listSweptNearPairs(const RigidTransform &worldFromRobot, double translationSlack, double radialSlack,
                            std::size_t limit, std::vector<TrianglePair> &near, QueryContext &context) const
    {
        near.clear();
        if (!slacksAreFinite(translationSlack, radialSlack) || !(translationSlack > 0.0 || radialSlack > 0.0) ||
            !worldFromRobot.isFinite())
            return false;
        return doListSweptNearPairs(worldFromRobot, translationSlack, radialSlack, limit, near, context);
    }
    /// The pairs of `pairs` (from listSweptNearPairs on this checker) that may come within the swept
    /// slack at this pose go into `near`; returns true when one of them intersects at this pose (the
    /// robot collides there). Without list support every pair stays near; a non-finite pose or slack
    /// keeps every pair and counts as a collision, as collides() counts a non-finite pose.
    bool sweptNearPairsAmong(const RigidTransform &worldFromRobot, double translationSlack, double radialSlack,
                             const std::vector<TrianglePair> &pairs, std::vector<TrianglePair> &near,
                             QueryContext &context) const
    {
        near.clear();
        if (!worldFromRobot.isFinite() || !slacksAreFinite(translationSlack, radialSlack))
        {
            near = pairs;
            return true;
        }
        return doSweptNearPairsAmong(worldFromRobot, translationSlack, radialSlack, pairs, near, context);
    }
    /// Hierarchies built for this checker (empty for brute force). `withVolumeRatios` also measures
    /// the node/content volume ratios (costly: a convex hull per sampled node).
    virtual std::vector<HierarchyReport> hierarchies(bool withVolumeRatios = false) const
    {
        (void)withVolumeRatios;
        return {};
    }

    /// The volumes of tree level `level` (the root is level 0; a leaf above that level stands for
    /// itself) of the robot and environment hierarchies, or nullopt when this checker has none.
    virtual std::optional<LevelVolumes> levelVolumes(int level) const
    {
        (void)level;
        return std::nullopt;
    }

    /// Writes levelVolumes(level) as a Wavefront OBJ mesh in world coordinates: group "robot" holds
    /// the robot's volumes placed by `worldFromRobot`, group "environment" the environment's.
    /// Returns false (and writes nothing) when this checker has no such hierarchy.
    bool exportLevel(int level, std::ostream &obj, const RigidTransform &worldFromRobot) const;

private:
    /// Both slacks non-negative and finite (NaN fails).
    static bool slacksAreFinite(double translationSlack, double radialSlack)
    {
        return translationSlack >= 0.0 && radialSlack >= 0.0 && std::isfinite(translationSlack + radialSlack);
    }

    // What each checker implements; the public forms above call these.
    virtual bool doCollides(const RigidTransform &worldFromRobot, QueryContext &context) const = 0;
    virtual double doDistance(const RigidTransform &worldFromRobot, QueryContext &context) const = 0;
    virtual double doDistanceOfFreePose(const RigidTransform &worldFromRobot, QueryContext &context) const
    {
        return doDistance(worldFromRobot, context);
    }
    virtual std::vector<ContactPair> doContacts(const RigidTransform &worldFromRobot, std::size_t limit,
                                                QueryContext &context) const
    {
        (void)worldFromRobot, (void)limit, (void)context;
        return {};
    }
    /// Hierarchical checkers override this with an early exit.
    virtual bool doWithinDistance(const RigidTransform &worldFromRobot, double delta, QueryContext &context) const
    {
        return doDistance(worldFromRobot, context) <= delta;
    }
    virtual bool doListSweptNearPairs(const RigidTransform &worldFromRobot, double translationSlack, double radialSlack,
                                      std::size_t limit, std::vector<TrianglePair> &near, QueryContext &context) const
    {
        (void)worldFromRobot, (void)translationSlack, (void)radialSlack, (void)limit, (void)near, (void)context;
        return false;
    }
    virtual bool doSweptNearPairsAmong(const RigidTransform &worldFromRobot, double translationSlack,
                                       double radialSlack, const std::vector<TrianglePair> &pairs,
                                       std::vector<TrianglePair> &near, QueryContext &context) const
    {
        (void)worldFromRobot, (void)translationSlack, (void)radialSlack, (void)context;
        near = pairs;
        return false;
    }
    virtual bool doSweptFreeByFirstLayer(const RigidTransform &worldFromRobot, double translationSlack,
                                         double radialSlack) const
    {
        (void)worldFromRobot, (void)translationSlack, (void)radialSlack;
        return false;
    }
    /// The default uses the robot's radius for every point; hierarchical checkers use each part's
    /// own reach.
    virtual bool doWithinSweptDistance(const RigidTransform &worldFromRobot, double translationSlack,
                                       double radialSlack, double robotRadius, QueryContext &context) const
    {
        return doWithinDistance(worldFromRobot, translationSlack + radialSlack * robotRadius, context);
    }
};
}  // namespace hcd
