// SPDX-License-Identifier: BSD-3-Clause
// A scene of many bodies: static obstacles and several rigid robots (review §2.3).
//
// Every body is a shape (query/body_geometry.h): a triangle mesh, a convex hull or an implicit
// primitive. Static bodies sit at fixed world poses; each robot carries one or more bodies at fixed
// poses in its own frame and is placed by a world-from-robot transform per query. The pairs that
// are ever checked are fixed at construction: every robot body against every static body and every
// body of every other robot, less the pairs the caller allows to touch (an allowed-collision list,
// as MoveIt's), and with self-pairs (bodies of one robot) only on request.
//
// A query runs in two phases, as the review's hybrid approach has it:
//   1. broad phase: the bodies' world boxes in a sweep and prune (broadphase/sweep_and_prune.h)
//      that lives in the caller's QueryContext and is updated incrementally from query to query,
//      so that coherent queries (a planner's neighbouring states, the states of one motion) move
//      few endpoints; only pairs whose boxes overlap go on;
//   2. narrow phase: mesh against mesh through a collision checker of the catalogue built for
//      that pair (the robot's tree against the other mesh's, with the grid in front), every other
//      pair through the shape narrow phase (bodiesIntersect: closed forms, LP or verified GJK).
// Touching counts as collision, as everywhere in hybridcd. `SceneOptions::bruteForce` replaces
// both phases by the references: every checkable pair, mesh pairs by the brute-force checker.
#pragma once

#include "hybridcd/broadphase/broad_phase.h"
#include "hybridcd/geometry/rigid_transform.h"
#include "hybridcd/narrowphase/convex_piece.h"
#include "hybridcd/query/body_geometry.h"
#include "hybridcd/query/checker_catalogue.h"
#include "hybridcd/query/collision_checker.h"
#include "hybridcd/query/query_context.h"

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace hcd
{
/// One body of a scene.
struct SceneBody
{
    std::string label;                                ///< e.g. "world", "obstacle.2", "robot.3"
    std::shared_ptr<const BodyGeometry> geometry;     ///< never null
    int robot = -1;                                   ///< index of the robot carrying it; -1: static
    RigidTransform ownerFromBody = RigidTransform();  ///< world-from-body (static) or robot-from-body
};

/// How a scene checks its pairs.
struct SceneOptions
{
    /// The catalogue checker built for every mesh-mesh pair ("auto" picks by the meshes).
    std::string meshChecker = "auto";
    CheckerOptions meshCheckerOptions;
    /// Check pairs of bodies carried by the same robot too.
    bool selfCollision = false;
    /// The reference: no broad phase, every checkable pair, mesh pairs by brute force.
    bool bruteForce = false;
};

/// A pair of bodies the scene checks (indices into bodies()).
struct ScenePair
{
    std::uint32_t first = 0, second = 0;
};

/// The answer of a scene query that found contact.
struct SceneContact
{
    ScenePair pair;
    Vec3 witness = Vec3::Zero();  ///< world frame; a point of both bodies when the pair gives one
};

/// Statics and robots, checked pair by pair. Immutable after construction and safe to query from
/// many threads at once, each with its own QueryContext.
class Scene
{
public:
    /// `bodies` in any order; robots are numbered 0 .. robotCount - 1 by SceneBody::robot.
    /// `allowedPairs` index `bodies` and are never checked. Throws std::invalid_argument for a
    /// body without geometry, a robot index out of range, a robot without bodies, or a pair of
    /// allowed indices out of range.
    Scene(std::vector<SceneBody> bodies, std::size_t robotCount,
          const std::vector<std::pair<std::size_t, std::size_t>> &allowedPairs, const SceneOptions &options = {});
    ~Scene();
    Scene(const Scene &) = delete;
    Scene &operator=(const Scene &) = delete;

    std::size_t robotCount() const { return robotCount_; }
    const std::vector<SceneBody> &bodies() const { return bodies_; }
    /// The pairs checked, in a fixed order (first < second).
    const std::vector<ScenePair> &pairs() const { return pairs_; }
    const SceneOptions &options() const { return options_; }
    /// max |p| over robot `robot`'s bodies, p in the robot's frame (how far a rotation moves a point).
    double robotRadius(std::size_t robot) const { return robotRadius_[robot]; }
    /// The diagonal of the box around the static bodies and robots' reach: the scene's length scale.
    double scale() const { return scale_; }

    /// World pose of body `body` when robot r sits at worldFromRobot[r].
    RigidTransform worldFromBody(std::size_t body, const RigidTransform *worldFromRobot) const;

    /// True when some checked pair shares a point with the robots at `worldFromRobot`
    /// (robotCount() transforms). A non-finite pose collides.
    bool collides(const RigidTransform *worldFromRobot, QueryContext &context) const;
    bool collides(const std::vector<RigidTransform> &worldFromRobot, QueryContext &context) const
    {
        return collides(worldFromRobot.data(), context);
    }
    /// The first colliding pair found, or nullopt when free (as collides()).
    std::optional<SceneContact> firstContact(const RigidTransform *worldFromRobot, QueryContext &context) const;

    /// Whether pair `pair` (an index into pairs()) shares a point at these poses (no broad phase).
    bool pairCollides(std::size_t pair, const RigidTransform *worldFromRobot, QueryContext &context) const;
    /// Distance of pair `pair` at these poses: 0 when touching, otherwise the distance between the
    /// bodies (floating point, never above the true distance by more than a relative 1e-9).
    double pairDistance(std::size_t pair, const RigidTransform *worldFromRobot, QueryContext &context) const
    {
        return pairDistance(pair, worldFromRobot, context, nullptr, nullptr);
    }
    /// The same, also giving the closest points (world frame) on the pair's first and second body
    /// when the narrow phase yields them (pairs with a shape); left unchanged otherwise (mesh pairs).
    double pairDistance(std::size_t pair, const RigidTransform *worldFromRobot, QueryContext &context, Vec3 *onFirst,
                        Vec3 *onSecond) const;
    /// A certified lower bound on pairDistance within about 1e-2 of it (bodiesDistanceBound; mesh
    /// pairs give their exact distance), with the points that gave it: what advancement steps on.
    double pairDistanceBound(std::size_t pair, const RigidTransform *worldFromRobot, QueryContext &context,
                             Vec3 *onFirst, Vec3 *onSecond) const;
    /// max over the body of direction . x (world frame, `direction` unit), the body placed by
    /// `worldFromBody`; up to a relative 1e-12 above the exact value (never below). Infinite when
    /// unbounded (a half-space in any direction but its normal) or too costly (meshes of more than
    /// 4096 vertices).
    double supportAlong(std::size_t body, const RigidTransform &worldFromBody, const Vec3 &direction) const;
    /// A cheap lower bound on pairDistance: the gap between the bodies' world boxes.
    double pairBoundsGap(std::size_t pair, const RigidTransform *worldFromRobot) const;
    /// The smallest pairDistance over every checked pair (infinity when there are none).
    double distance(const RigidTransform *worldFromRobot, QueryContext &context) const;

    /// The body as a convex polytope in its own frame, for boxes and convex hulls (the time-augmented
    /// LP works on these); null for every other shape.
    const ConvexPiece *polytope(std::size_t body) const { return polytopes_[body].get(); }

    /// Label of pair `pair`, "robot.2 / obstacle.1".
    std::string pairLabel(std::size_t pair) const;

private:
    struct MeshPairChecker;
    bool narrowPhase(std::size_t pair, const RigidTransform *worldFromRobot, QueryContext &context,
                     Vec3 *witness) const;
    std::optional<SceneContact> bruteForceContact(const RigidTransform *worldFromRobot, QueryContext &context) const;
    std::optional<SceneContact> broadPhaseContact(const RigidTransform *worldFromRobot, QueryContext &context) const;

    std::vector<SceneBody> bodies_;
    std::size_t robotCount_ = 0;
    SceneOptions options_;
    std::vector<ScenePair> pairs_;
    /// pairIndex_[first * bodies + second] (first < second): index into pairs_, or -1.
    std::vector<std::int32_t> pairIndex_;
    /// Per pair: the checker of a mesh-mesh pair (null for pairs with a shape).
    std::vector<std::unique_ptr<MeshPairChecker>> meshCheckers_;
    std::vector<BroadPhaseBox> staticBounds_;  ///< world boxes of static bodies (unused for robot bodies)
    std::vector<double> robotRadius_;
    std::vector<std::unique_ptr<const ConvexPiece>> polytopes_;
    double scale_ = 1.0;
    std::uint64_t id_ = 0;  ///< unique per scene, for the broad phase kept in contexts
};
}  // namespace hcd
