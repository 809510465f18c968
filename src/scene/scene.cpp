// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/scene/scene.h"

#include "hybridcd/broadphase/sweep_and_prune.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace hcd
{
namespace
{
constexpr double kInfinity = std::numeric_limits<double>::infinity();

bool isMesh(const SceneBody &body) { return body.geometry->shape().kind() == ShapeKind::Mesh; }

// The world box of a body at `worldFromBody`. A half-space's box is infinite on the sides it is
// unbounded (BoundingBox keeps one-sided infinities, which centre and half extents cannot).
BroadPhaseBox boundsOf(const SceneBody &body, const RigidTransform &worldFromBody)
{
    const Shape &shape = body.geometry->shape();
    if (shape.kind() == ShapeKind::Halfspace)
    {
        const BoundingBox box = worldBounds(shape, worldFromBody);
        return {box.min, box.max};
    }
    return BroadPhaseBox::of(body.geometry->worldBounds(worldFromBody));
}

// Gap between two world boxes (0 when they overlap or on an axis where either is unbounded).
double boxGap(const BroadPhaseBox &a, const BroadPhaseBox &b)
{
    Vec3 gap;
    for (int i = 0; i < 3; ++i)
    {
        const double d = std::max(a.lower[i] - b.upper[i], b.lower[i] - a.upper[i]);
        gap[i] = std::isfinite(d) && d > 0.0 ? d : 0.0;
    }
    return gap.norm();
}

// What the broad phase of one QueryContext keeps between queries of one scene: the sweep and
// prune with every body in it, the robot bodies moved to their last poses.
struct BroadPhaseScratch
{
    std::uint64_t scene = 0;  // the id of the scene the handles below belong to (0: none)
    SweepAndPrune sweep;
    std::vector<BodyHandle> handles;
    std::vector<UserDataPair> overlaps;
    std::vector<RigidTransform> worldFromBody;
};
}  // namespace

// A catalogue checker for one mesh-mesh pair: `moving` is the checker's robot, `reference` its
// environment, kept in the reference body's frame (world frame for a static body, baked in).
struct Scene::MeshPairChecker
{
    std::unique_ptr<CollisionChecker> checker;
    std::uint32_t moving = 0, reference = 0;
    bool referenceStatic = false;

    // The pose the checker takes: reference-from-moving.
    RigidTransform relativePose(const Scene &scene, const RigidTransform *worldFromRobot) const
    {
        const RigidTransform worldFromMoving = scene.worldFromBody(moving, worldFromRobot);
        if (referenceStatic)
            return worldFromMoving;
        return scene.worldFromBody(reference, worldFromRobot).inverse() * worldFromMoving;
    }
};

Scene::Scene(std::vector<SceneBody> bodies, std::size_t robotCount,
             const std::vector<std::pair<std::size_t, std::size_t>> &allowedPairs, const SceneOptions &options)
    : bodies_(std::move(bodies)),
      robotCount_(robotCount),
      options_(options)
{
    // Ids tell contexts which scene their broad phase holds (an address could be reused).
    static std::atomic<std::uint64_t> nextId{1};
    id_ = nextId.fetch_add(1, std::memory_order_relaxed);
    const std::size_t n = bodies_.size();
    std::vector<int> bodiesOfRobot(robotCount_, 0);
    for (const SceneBody &body : bodies_)
    {
        if (!body.geometry)
            throw std::invalid_argument("scene body '" + body.label + "' has no geometry");
        if (body.robot >= int(robotCount_) || body.robot < -1)
            throw std::invalid_argument("scene body '" + body.label + "' names robot " + std::to_string(body.robot) +
                                        " of " + std::to_string(robotCount_));
        if (body.robot >= 0)
        {
            if (body.geometry->shape().kind() == ShapeKind::Halfspace)
                throw std::invalid_argument("scene body '" + body.label + "': a robot cannot carry a halfspace");
            ++bodiesOfRobot[std::size_t(body.robot)];
        }
    }
    for (std::size_t r = 0; r < robotCount_; ++r)
        if (bodiesOfRobot[r] == 0)
            throw std::invalid_argument("robot " + std::to_string(r) + " of the scene carries no body");

    std::vector<char> allowed(n * n, 0);
    for (const auto &[a, b] : allowedPairs)
    {
        if (a >= n || b >= n)
            throw std::invalid_argument("allowed scene pair out of range");
        allowed[a * n + b] = allowed[b * n + a] = 1;
    }

    // Which pairs are checked, and the checkers of mesh-mesh pairs.
    pairIndex_.assign(n * n, -1);
    const CheckerCatalogue &catalogue = CheckerCatalogue::builtIn();
    const std::string meshChecker = options_.bruteForce ? "bruteforce" : options_.meshChecker;
    for (std::uint32_t a = 0; a < n; ++a)
        for (std::uint32_t b = a + 1; b < n; ++b)
        {
            const SceneBody &A = bodies_[a], &B = bodies_[b];
            if (A.robot < 0 && B.robot < 0)
                continue;  // statics never move against each other
            if (A.robot == B.robot && !options_.selfCollision)
                continue;
            if (allowed[a * n + b])
                continue;
            pairIndex_[a * n + b] = std::int32_t(pairs_.size());
            pairs_.push_back({a, b});
            std::unique_ptr<MeshPairChecker> meshPair;
            if (isMesh(A) && isMesh(B))
            {
                meshPair = std::make_unique<MeshPairChecker>();
                // The static body (if any) is the checker's environment, so that its structures are
                // built in the world frame once; else the second body's frame is the reference.
                const bool firstStatic = A.robot < 0;
                meshPair->moving = firstStatic ? b : a;
                meshPair->reference = firstStatic ? a : b;
                const SceneBody &moving = bodies_[meshPair->moving], &reference = bodies_[meshPair->reference];
                meshPair->referenceStatic = reference.robot < 0;
                CollisionScene pairScene;
                pairScene.robot = moving.geometry->shape().meshPointer();
                pairScene.robotName = moving.label;
                pairScene.environmentName = reference.label;
                if (meshPair->referenceStatic)
                {
                    // Bake the static pose into the environment's vertices (world frame).
                    auto world = std::make_shared<TriangleMesh>(*reference.geometry->shape().meshPointer());
                    for (Vec3 &v : world->vertices)
                        v = reference.ownerFromBody.apply(v);
                    pairScene.environment = std::move(world);
                }
                else
                {
                    pairScene.environment = reference.geometry->shape().meshPointer();
                }
                meshPair->checker = catalogue.make(meshChecker, pairScene, options_.meshCheckerOptions);
            }
            meshCheckers_.push_back(std::move(meshPair));
        }

    // Boxes and hulls as polytopes, for the time-augmented LP of translating pairs.
    polytopes_.resize(n);
    for (std::size_t i = 0; i < n; ++i)
    {
        const Shape &shape = bodies_[i].geometry->shape();
        if (shape.kind() == ShapeKind::Box)
        {
            std::vector<Vec3> corners;
            for (int c = 0; c < 8; ++c)
                corners.push_back(
                    Vec3(c & 1 ? 1.0 : -1.0, c & 2 ? 1.0 : -1.0, c & 4 ? 1.0 : -1.0).cwiseProduct(shape.extents()));
            polytopes_[i] = std::make_unique<const ConvexPiece>(ConvexPiece::hullOf(corners));
        }
        else if (shape.kind() == ShapeKind::Convex)
            polytopes_[i] = std::make_unique<const ConvexPiece>(ConvexPiece::hullOf(shape.points()));
    }

    // Static boxes, robot radii and the scene's length scale.
    staticBounds_.resize(n);
    robotRadius_.assign(robotCount_, 0.0);
    BoundingBox extent;
    for (std::size_t i = 0; i < n; ++i)
    {
        const SceneBody &body = bodies_[i];
        if (body.robot < 0)
        {
            staticBounds_[i] = boundsOf(body, body.ownerFromBody);
            const BroadPhaseBox &box = staticBounds_[i];
            if (box.lower.allFinite() && box.upper.allFinite())
            {
                extent.extend(box.lower);
                extent.extend(box.upper);
            }
        }
        else
        {
            const double reach = body.ownerFromBody.translation.norm() + body.geometry->boundingRadius();
            robotRadius_[std::size_t(body.robot)] = std::max(robotRadius_[std::size_t(body.robot)], reach);
        }
    }
    double diagonal = extent.empty() ? 0.0 : (extent.max - extent.min).norm();
    for (double r : robotRadius_)
        diagonal = std::max(diagonal, 2.0 * r);
    scale_ = diagonal > 0.0 && std::isfinite(diagonal) ? diagonal : 1.0;
}

Scene::~Scene() = default;

RigidTransform Scene::worldFromBody(std::size_t body, const RigidTransform *worldFromRobot) const
{
    const SceneBody &b = bodies_[body];
    return b.robot < 0 ? b.ownerFromBody : worldFromRobot[b.robot] * b.ownerFromBody;
}

bool Scene::narrowPhase(std::size_t pair, const RigidTransform *worldFromRobot, QueryContext &context,
                        Vec3 *witness) const
{
    const ScenePair &p = pairs_[pair];
    if (const MeshPairChecker *mesh = meshCheckers_[pair].get())
    {
        const bool hit = mesh->checker->collides(mesh->relativePose(*this, worldFromRobot), context);
        if (hit && witness)
            *witness = worldFromBody(mesh->moving, worldFromRobot).translation;
        return hit;
    }
    const BodyPairResult result =
        bodiesIntersect(*bodies_[p.first].geometry, worldFromBody(p.first, worldFromRobot), *bodies_[p.second].geometry,
                        worldFromBody(p.second, worldFromRobot), context);
    if (result.intersecting && witness)
        *witness = result.pointA;
    return result.intersecting;
}

bool Scene::pairCollides(std::size_t pair, const RigidTransform *worldFromRobot, QueryContext &context) const
{
    return narrowPhase(pair, worldFromRobot, context, nullptr);
}

double Scene::pairDistance(std::size_t pair, const RigidTransform *worldFromRobot, QueryContext &context, Vec3 *onFirst,
                           Vec3 *onSecond) const
{
    const ScenePair &p = pairs_[pair];
    if (const MeshPairChecker *mesh = meshCheckers_[pair].get())
        return mesh->checker->distance(mesh->relativePose(*this, worldFromRobot), context);
    const BodyPairResult result =
        bodiesDistance(*bodies_[p.first].geometry, worldFromBody(p.first, worldFromRobot), *bodies_[p.second].geometry,
                       worldFromBody(p.second, worldFromRobot), context);
    if (onFirst)
        *onFirst = result.pointA;
    if (onSecond)
        *onSecond = result.pointB;
    return result.distance;
}

double Scene::pairDistanceBound(std::size_t pair, const RigidTransform *worldFromRobot, QueryContext &context,
                                Vec3 *onFirst, Vec3 *onSecond) const
{
    const ScenePair &p = pairs_[pair];
    if (meshCheckers_[pair])
        return pairDistance(pair, worldFromRobot, context, onFirst, onSecond);
    const BodyPairResult result =
        bodiesDistanceBound(*bodies_[p.first].geometry, worldFromBody(p.first, worldFromRobot),
                            *bodies_[p.second].geometry, worldFromBody(p.second, worldFromRobot), context);
    if (onFirst)
        *onFirst = result.pointA;
    if (onSecond)
        *onSecond = result.pointB;
    return result.distance;
}

double Scene::supportAlong(std::size_t body, const RigidTransform &worldFromBody, const Vec3 &direction) const
{
    const Shape &shape = bodies_[body].geometry->shape();
    double value = kInfinity, magnitude = worldFromBody.translation.norm();
    switch (shape.kind())
    {
    case ShapeKind::Halfspace:
    {
        // Bounded along its own outward normal only: there the support is the plane.
        const Vec3 normal = worldFromBody.rotation * shape.normal();
        if (normal == direction)
            value = shape.offset() + normal.dot(worldFromBody.translation);
        magnitude += std::abs(shape.offset());
        break;
    }
    case ShapeKind::Mesh:
    {
        const TriangleMesh &mesh = *shape.meshPointer();
        if (mesh.vertices.size() > 4096)
            return kInfinity;
        const Vec3 local = worldFromBody.rotation.transpose() * direction;
        double best = -kInfinity;
        for (const Vec3 &v : mesh.vertices)
            best = std::max(best, local.dot(v));
        value = best + direction.dot(worldFromBody.translation);
        magnitude += bodies_[body].geometry->boundingRadius();
        break;
    }
    default:
        value = direction.dot(worldFromBody.apply(supportPoint(shape, worldFromBody.rotation.transpose() * direction)));
        magnitude += bodies_[body].geometry->boundingRadius();
        break;
    }
    // Rounding of the transform and the support point: a relative 1e-12 of the coordinates.
    return value + 1e-12 * magnitude;
}

double Scene::pairBoundsGap(std::size_t pair, const RigidTransform *worldFromRobot) const
{
    const ScenePair &p = pairs_[pair];
    auto box = [&](std::uint32_t i) {
        return bodies_[i].robot < 0 ? staticBounds_[i] : boundsOf(bodies_[i], worldFromBody(i, worldFromRobot));
    };
    return boxGap(box(p.first), box(p.second));
}

double Scene::distance(const RigidTransform *worldFromRobot, QueryContext &context) const
{
    for (std::size_t r = 0; r < robotCount_; ++r)
        if (!worldFromRobot[r].isFinite())
            return 0.0;
    double best = kInfinity;
    for (std::size_t pair = 0; pair < pairs_.size(); ++pair)
    {
        // A pair whose boxes are already farther apart than the best distance cannot be nearer.
        if (pairBoundsGap(pair, worldFromRobot) >= best)
            continue;
        best = std::min(best, pairDistance(pair, worldFromRobot, context));
        if (best == 0.0)
            break;
    }
    return best;
}

std::optional<SceneContact> Scene::bruteForceContact(const RigidTransform *worldFromRobot, QueryContext &context) const
{
    for (std::size_t pair = 0; pair < pairs_.size(); ++pair)
    {
        SceneContact contact{pairs_[pair], Vec3::Zero()};
        if (narrowPhase(pair, worldFromRobot, context, &contact.witness))
            return contact;
    }
    return std::nullopt;
}

std::optional<SceneContact> Scene::broadPhaseContact(const RigidTransform *worldFromRobot, QueryContext &context) const
{
    BroadPhaseScratch &broad = context.scratch<BroadPhaseScratch>();
    const std::size_t n = bodies_.size();
    // A context that last served another scene starts its sweep afresh.
    if (broad.scene != id_)
    {
        broad.sweep = SweepAndPrune();
        broad.handles.clear();
        for (std::size_t i = 0; i < n; ++i)
        {
            const BroadPhaseBox box =
                bodies_[i].robot < 0 ? staticBounds_[i] : boundsOf(bodies_[i], worldFromBody(i, worldFromRobot));
            // Statics are never paired with statics.
            broad.handles.push_back(broad.sweep.add(box, std::uint32_t(i),
                                                    bodies_[i].robot < 0 ? BroadPhaseFilter::staticBody()
                                                                         : BroadPhaseFilter::dynamicBody()));
        }
        broad.scene = id_;
    }
    else
    {
        for (std::size_t i = 0; i < n; ++i)
            if (bodies_[i].robot >= 0)
                broad.sweep.update(broad.handles[i], boundsOf(bodies_[i], worldFromBody(i, worldFromRobot)));
    }
    broad.overlaps.clear();
    broad.sweep.overlappingPairs(broad.overlaps);
    for (const auto &[a, b] : broad.overlaps)
    {
        const std::uint32_t first = std::min(a, b), second = std::max(a, b);
        const std::int32_t pair = pairIndex_[std::size_t(first) * n + second];
        if (pair < 0)
            continue;
        SceneContact contact{pairs_[std::size_t(pair)], Vec3::Zero()};
        if (narrowPhase(std::size_t(pair), worldFromRobot, context, &contact.witness))
            return contact;
    }
    return std::nullopt;
}

std::optional<SceneContact> Scene::firstContact(const RigidTransform *worldFromRobot, QueryContext &context) const
{
    for (std::size_t r = 0; r < robotCount_; ++r)
        if (!worldFromRobot[r].isFinite())
            return SceneContact{pairs_.empty() ? ScenePair{} : pairs_.front(), Vec3::Zero()};
    return options_.bruteForce ? bruteForceContact(worldFromRobot, context)
                               : broadPhaseContact(worldFromRobot, context);
}

bool Scene::collides(const RigidTransform *worldFromRobot, QueryContext &context) const
{
    return firstContact(worldFromRobot, context).has_value();
}

std::string Scene::pairLabel(std::size_t pair) const
{
    return bodies_[pairs_[pair].first].label + " / " + bodies_[pairs_[pair].second].label;
}
}  // namespace hcd
