// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/query/volume_tree_checker.h"

#include "hybridcd/bvh/medial_axis.h"
#include "hybridcd/geometry/triangle_distance.h"
#include "hybridcd/geometry/triangle_intersection.h"
#include "hybridcd/narrowphase/linear_program.h"
#include "hybridcd/query/best_first_distance.h"
#include "hybridcd/query/leaf_decomposition.h"
#include "hybridcd/query/placed_robot.h"
#include "hybridcd/query/stamped_slots.h"
#include "hybridcd/query/traversal_stack.h"
#include "hybridcd/query/volume_ratio.h"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <type_traits>

namespace hcd
{
namespace
{
// In NodePair::environment on the traversal stack: the pair's volumes were tested as lanes.
constexpr std::uint32_t kTestedByLanes = std::uint32_t(1) << 31;
// Environment trees of more nodes keep no lanes (a block of four boxes, 0.3-0.6 KB, per inner node
// at an even depth).
constexpr std::size_t kMaxLaneNodes = std::size_t(1) << 18;

// Calls visit(node, lanes, count) for each inner node of `tree` at an even depth, with the nodes
// two levels below it (its grandchildren, or a child that is a leaf; 2 to 4 of them). A traversal
// that splits through them goes from the root to grandchildren, so it never splits a node at an
// odd depth that way, and each box is in one block (half the memory of a block per inner node).
template <class Volume, class Visit>
void forEachLaneBlock(const VolumeTree<Volume> &tree, Visit &&visit)
{
    const auto &nodes = tree.nodes();
    std::vector<std::uint32_t> evenDepth{0};
    while (!evenDepth.empty())
    {
        const std::uint32_t i = evenDepth.back();
        evenDepth.pop_back();
        if (nodes[i].isLeaf())
            continue;
        std::uint32_t lanes[4];
        int count = 0;
        for (int c = 0; c < 2; ++c)
        {
            const std::uint32_t child = std::uint32_t(nodes[i].firstChild + c);
            if (nodes[child].isLeaf())
                lanes[count++] = child;
            else
                for (int g = 0; g < 2; ++g)
                {
                    const std::uint32_t grandchild = std::uint32_t(nodes[child].firstChild + g);
                    lanes[count++] = grandchild;
                    evenDepth.push_back(grandchild);
                }
        }
        visit(i, lanes, count);
    }
}

// Up to eight child pairs for a depth-first stack, ordered so that the pair whose bounding
// spheres' centres lie nearest, relative to the sum of their radii, comes off first: in a
// colliding pose that pair is the likeliest to hold two triangles that meet, so the search reaches
// one sooner (bench/README.md, section 1). A free pose visits every overlapping pair whatever the
// order, so the answer never depends on it.
class NearestOnTop
{
public:
    /// Both children of a robot node against one block of environment lanes at most.
    static constexpr int kCapacity = 2 * ObbLanes::kLanes;

    /// `radiusSum`: the two bounding spheres' radii added. At most kCapacity pairs.
    void add(const NodePair &pair, double squaredCentreDistance, double radiusSum)
    {
        // Kept from the farthest (index 0) to the nearest; "nearer" compares d1^2 / r1^2 with
        // d2^2 / r2^2 multiplied out, so that a radius of 0 divides nothing.
        const double squaredRadiusSum = radiusSum * radiusSum;
        int j = count_++;
        while (j > 0 && squared_[j - 1] * squaredRadiusSum < squaredCentreDistance * squaredRadiusSum_[j - 1])
        {
            pairs_[j] = pairs_[j - 1];
            squared_[j] = squared_[j - 1];
            squaredRadiusSum_[j] = squaredRadiusSum_[j - 1];
            --j;
        }
        pairs_[j] = pair;
        squared_[j] = squaredCentreDistance;
        squaredRadiusSum_[j] = squaredRadiusSum;
    }
    void pushOnto(TraversalStack &stack) const
    {
        for (int i = 0; i < count_; ++i)
            stack.push(pairs_[i]);
    }

private:
    NodePair pairs_[kCapacity];
    double squared_[kCapacity];
    double squaredRadiusSum_[kCapacity];
    int count_ = 0;
};
}  // namespace

namespace
{
// Robot pieces mapped to world for the current query, computed on first use. The storage is the
// query context's, reused across queries; stamps mark what this query has computed (as in
// PlacedRobot).
class PlacedPieces
{
public:
    PlacedPieces(const RigidTransform &pose, QueryContext &context)
        : s_(context.scratch<Scratch>()),
          query_(++s_.query),
          pose_(pose)
    {
    }

    const ConvexPiece &piece(std::uint32_t node, const ConvexPiece &local)
    {
        s_.pieces.reserve(std::size_t(node) + 1);
        return s_.pieces.get(node, query_, [&](ConvexPiece &p) { p = local.transformed(pose_); });
    }

private:
    struct Scratch
    {
        StampedSlots<ConvexPiece> pieces;
        std::uint64_t query = 0;
    };
    Scratch &s_;
    std::uint64_t query_;
    RigidTransform pose_;
};

// Coherence across queries (the seed's sections 4.3-4.5, Lin-Canny and I-COLLIDE): the triangle
// pair that decided a checker's last "yes" in a context, per query kind (contact, or proximity).
// Neighbouring queries, such as the states of one motion or a planner's successive extensions,
// often meet at the same pair, and trying it first costs one bounds test when it misses.
struct WitnessPair
{
    bool valid = false;
    std::uint32_t robot = 0, environment = 0;
};

class WitnessCache
{
public:
    WitnessPair &of(const void *checker, bool proximity)
    {
        for (Entry &e : entries_)
            if (e.checker == checker && e.proximity == proximity)
                return e.pair;
        // A handful of checkers per context at most; beyond that the oldest entry is reused.
        const Entry fresh{checker, proximity, {}};
        if (entries_.size() < kEntries)
        {
            entries_.push_back(fresh);
            return entries_.back().pair;
        }
        Entry &reused = entries_[next_++ % kEntries];
        reused = fresh;
        return reused.pair;
    }

private:
    struct Entry
    {
        const void *checker;
        bool proximity;
        WitnessPair pair;
    };
    static constexpr std::size_t kEntries = 16;
    std::vector<Entry> entries_;
    std::size_t next_ = 0;
};
}  // namespace

template <class Volume>
VolumeTreeChecker<Volume>::VolumeTreeChecker(CollisionScene scene, std::string name, unsigned maxLeafTriangles,
                                             std::optional<PieceStage> pieces, std::optional<double> leafTolerance)
    : robotFaces_(withoutRepeatedFaces(scene.robot)),
      environmentFaces_(withoutRepeatedFaces(scene.environment)),
      scene_{robotFaces_.mesh,  environmentFaces_.mesh, std::move(scene.robotName), std::move(scene.environmentName),
             scene.planarPoses, scene.turnsAboutRobotZ},
      name_(std::move(name)),
      robotTree_(scene_.robot, pieces ? pieces->leafTriangles : maxLeafTriangles),
      environmentTree_(scene_.environment, pieces ? pieces->leafTriangles : maxLeafTriangles),
      robotRadius_(scene_.robot->radiusAboutOrigin()),
      environmentMagnitude_(scene_.environment->radiusAboutOrigin()),
      pieceStage_(pieces),
      leafTolerance_(leafTolerance)
{
    if constexpr (std::is_same_v<Volume, MedialSphere>)
    {
        placeOnMedialAxis(robotTree_, scene_.robot);
        placeOnMedialAxis(environmentTree_, scene_.environment);
    }
    // How far each robot node and triangle reaches from the robot origin, or from its z axis when
    // motions turn about it (for swept proximity).
    for (const auto &node : robotTree_.nodes())
        robotNodeReach_.push_back(
            (turnReach(VolumeTraits<Volume>::center(node.volume), scene_.turnsAboutRobotZ) + node.radius) *
            (1.0 + 1e-12));
    robotTriangleReach_ = triangleTurnReaches(*scene_.robot, scene_.turnsAboutRobotZ);
    if (pieceStage_)
    {
        robotPieces_ = decomposeLeaves(robotTree_);
        environmentPieces_ = decomposeLeaves(environmentTree_);
    }
    // Two trees alike in size (a puzzle of like parts, as alpha-1.5's): the pairs between a node
    // and the other's children rarely prune there, and splitting both nodes at once skips their
    // tests: on alpha-1.5 the mean state check 1,082 -> 867 ns, the mean motion verdict 16% and
    // lastValid 19% cheaper, clearance on the alpha puzzles 12-19% at the median. Splitting both
    // everywhere costs elsewhere (bugtrap's clearance 2x, Easy's 9%; bench/README.md, section 1,
    // "Clearance", fourth round).
    const auto within2x = [](double x, double y) { return x <= 2.0 * y && y <= 2.0 * x; };
    lockstep_ = !robotTree_.empty() && !environmentTree_.empty() &&
                within2x(double(scene_.robot->triangleCount()), double(scene_.environment->triangleCount())) &&
                within2x(robotTree_.nodes()[0].radius, environmentTree_.nodes()[0].radius);
    if constexpr (LanesOf<Volume>::kUsed)
        if (!pieceStage_)
        {
            if (!environmentTree_.empty() && environmentTree_.nodes().size() <= kMaxLaneNodes)
            {
                const auto &nodes = environmentTree_.nodes();
                lanesOfNode_.assign(nodes.size(), -1);
                forEachLaneBlock(environmentTree_, [&](std::uint32_t node, const std::uint32_t *lane, int count) {
                    typename LanesOf<Volume>::Type lanes;
                    for (int k = 0; k < count; ++k)
                        lanes.add(nodes[lane[k]].volume, nodes[lane[k]].radius, lane[k]);
                    lanes.fill();
                    lanesOfNode_[node] = std::int32_t(environmentLanes_.size());
                    environmentLanes_.push_back(lanes);
                });
                environmentLanes_.shrink_to_fit();
            }
            // The robot's blocks by node only: a query places a block's boxes in world
            // (PlacedRobot::lanes) where it splits the robot node (instructions per state check
            // 3-6% fewer with the grid first, for OBB and re-boxed AABB trees alike).
            if (!robotTree_.empty() && robotTree_.nodes().size() <= kMaxLaneNodes)
            {
                robotBlockOfNode_.assign(robotTree_.nodes().size(), -1);
                forEachLaneBlock(robotTree_, [&](std::uint32_t node, const std::uint32_t *lane, int count) {
                    RobotBlock block{};
                    for (int k = 0; k < count; ++k)
                    {
                        block.node[k] = lane[k];
                        block.reach = std::max(block.reach, robotNodeReach_[lane[k]]);
                    }
                    block.count = count;
                    robotBlockOfNode_[node] = std::int32_t(robotBlocks_.size());
                    robotBlocks_.push_back(block);
                });
                robotBlocks_.shrink_to_fit();
            }
        }
    const TriangleMesh &env = *scene_.environment;
    environmentTriangleBounds_.reserve(env.triangleCount());
    for (std::size_t t = 0; t < env.triangleCount(); ++t)
    {
        const Vec3 &a = env.corner(t, 0), &b = env.corner(t, 1), &c = env.corner(t, 2);
        environmentTriangleBounds_.push_back({a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c)});
    }
}

template <class Volume>
double VolumeTreeChecker<Volume>::toleranceFor(const RigidTransform &worldFromRobot) const
{
    // Rounding in the box tests scales with the coordinates involved; 1e-10 of them covers it
    // many times over while costing nothing measurable in culling. Relative only: an absolute
    // floor would be the size of a scene modelled at 1e-9 and widen its proximity tests by it.
    return 1e-10 * (worldFromRobot.translation.norm() + robotRadius_ + environmentMagnitude_);
}

template <class Volume>
bool VolumeTreeChecker<Volume>::doCollides(const RigidTransform &worldFromRobot, QueryContext &context) const
{
    return anyPairWithin(worldFromRobot, {}, context);
}

template <class Volume>
bool VolumeTreeChecker<Volume>::doWithinDistance(const RigidTransform &worldFromRobot, double delta,
                                                 QueryContext &context) const
{
    return anyPairWithin(worldFromRobot, {std::max(0.0, delta), 0.0}, context);
}

template <class Volume>
bool VolumeTreeChecker<Volume>::doWithinSweptDistance(const RigidTransform &worldFromRobot, double translationSlack,
                                                      double radialSlack, double robotRadius,
                                                      QueryContext &context) const
{
    (void)robotRadius;  // per-node reaches are tighter than the robot's radius
    return anyPairWithin(worldFromRobot, {std::max(0.0, translationSlack), std::max(0.0, radialSlack)}, context);
}

template <class Volume>
bool VolumeTreeChecker<Volume>::trianglePairWithin(const PlacedTriangle &a, std::uint32_t rt, std::uint32_t et,
                                                   Slack slack, bool proximity, double tolerance,
                                                   std::uint64_t &tests) const
{
    const double triangleDelta = slack.at(robotTriangleReach_[rt]);
    // Exact comparisons on coordinates need no tolerance; proximity adds its slack.
    const double boundsSlack = proximity ? triangleDelta * (1.0 + 1e-9) + tolerance : 0.0;
    const TriangleBounds &eb = environmentTriangleBounds_[et];
    if ((a.min.array() > eb.max.array() + boundsSlack).any() || (eb.min.array() > a.max.array() + boundsSlack).any())
        return false;
    ++tests;
    const TriangleMesh &env = *scene_.environment;
    const Vec3 &b0 = env.corner(et, 0), &b1 = env.corner(et, 1), &b2 = env.corner(et, 2);
    return !proximity ? trianglesIntersect(a.corners[0], a.corners[1], a.corners[2], b0, b1, b2)
                      : trianglesWithinDistance(a.corners[0], a.corners[1], a.corners[2], b0, b1, b2,
                                                triangleDelta * (1.0 + 1e-9) + tolerance);
}

template <class Volume>
bool VolumeTreeChecker<Volume>::doListSweptNearPairs(const RigidTransform &worldFromRobot, double translationSlack,
                                                     double radialSlack, std::size_t limit,
                                                     std::vector<TrianglePair> &near, QueryContext &context) const
{
    // With pieces or approximate leaves, collides() is not decided by triangle pairs alone: a
    // listed pair's contact would not be this checker's answer.
    if (pieceStage_ || leafTolerance_)
        return false;
    return !anyPairWithin(worldFromRobot, {std::max(0.0, translationSlack), std::max(0.0, radialSlack)}, context,
                          nullptr, limit, &near);
}

template <class Volume>
bool VolumeTreeChecker<Volume>::doSweptNearPairsAmong(const RigidTransform &worldFromRobot, double translationSlack,
                                                      double radialSlack, const std::vector<TrianglePair> &pairs,
                                                      std::vector<TrianglePair> &near, QueryContext &context) const
{
    // The leaf test of anyPairWithin, pair by pair; a pair near enough is also tested for contact.
    const Slack slack{std::max(0.0, translationSlack), std::max(0.0, radialSlack)};
    const double tolerance = toleranceFor(worldFromRobot);
    const TriangleMesh &env = *scene_.environment;
    PlacedRobot<Volume> placed(robotTree_, worldFromRobot, context);
    bool touching = false;
    std::uint64_t triangleTests = 0;
    for (const TrianglePair &p : pairs)
    {
        const PlacedTriangle &a = placed.triangle(p.robot);
        if (!trianglePairWithin(a, p.robot, p.environment, slack, /*proximity=*/true, tolerance, triangleTests))
            continue;
        near.push_back(p);
        touching =
            touching || trianglesIntersect(a.corners[0], a.corners[1], a.corners[2], env.corner(p.environment, 0),
                                           env.corner(p.environment, 1), env.corner(p.environment, 2));
    }
    context.stats.primitiveTests += triangleTests;
    return touching;
}

template <class Volume>
bool VolumeTreeChecker<Volume>::anyPairWithin(const RigidTransform &worldFromRobot, Slack slack, QueryContext &context,
                                              std::vector<ContactPair> *found, std::size_t limit,
                                              std::vector<TrianglePair> *near) const
{
    if (!worldFromRobot.isFinite())
        return true;
    if (robotTree_.empty() || environmentTree_.empty())
        return false;

    const double tolerance = toleranceFor(worldFromRobot);
    // A robot part at distance r from the robot origin may be `slack.at(r)` away from where the
    // pose puts it; a pair of parts is "within" when they come that close. Collision: slack 0.
    const bool proximity = slack.translation > 0.0 || slack.radial > 0.0;
    const auto &rNodes = robotTree_.nodes();
    const auto &eNodes = environmentTree_.nodes();
    const TriangleMesh &env = *scene_.environment;
    PlacedRobot<Volume> placed(robotTree_, worldFromRobot, context, robotBlocks_.size());
    PlacedPieces placedPieces(worldFromRobot, context);

    std::uint64_t boxTests = 0, triangleTests = 0, pieceTests = 0;
    const auto trianglesWithin = [&](std::uint32_t rt, std::uint32_t et) {
        return trianglePairWithin(placed.triangle(rt), rt, et, slack, proximity, tolerance, triangleTests);
    };
    const auto record = [&] {
        context.stats.boundingVolumeTests += boxTests;
        context.stats.primitiveTests += triangleTests + pieceTests;
    };

    // The last deciding pair first (not when listing contacts). Checked against this checker's
    // meshes, since a context may outlive a checker whose address is reused.
    WitnessPair *witness = found || near ? nullptr : &context.scratch<WitnessCache>().of(this, proximity);
    if (witness && witness->valid && witness->robot < scene_.robot->triangleCount() &&
        witness->environment < env.triangleCount() && trianglesWithin(witness->robot, witness->environment))
    {
        record();
        return true;
    }

    bool hit = false;
    TraversalStack stack;
    stack.push({0, 0});
    while (!stack.empty() && !hit)
    {
        NodePair pair = stack.pop();
        // A pair pushed by the lanes' test below has had its volumes tested already.
        const bool tested = (pair.environment & kTestedByLanes) != 0;
        pair.environment &= ~kTestedByLanes;
        const typename VolumeTree<Volume>::Node &rn = rNodes[pair.robot];
        const typename VolumeTree<Volume>::Node &en = eNodes[pair.environment];
        // Circumscribed spheres first (a few flops), then the separating-axis test. Growing the
        // tolerance by delta keeps every pair closer than delta (the axes have length <= 1).
        using Traits = VolumeTraits<Volume>;
        if (!tested)
        {
            // (A pair the lanes tested needs neither its robot volume in world nor its slack.)
            const Volume &robotVolume = placed.volume(pair.robot);
            const double delta = slack.at(robotNodeReach_[pair.robot]);
            ++boxTests;
            const double reach = rn.radius + en.radius + tolerance + delta;
            if ((Traits::center(robotVolume) - Traits::center(en.volume)).squaredNorm() > reach * reach ||
                !Traits::overlap(robotVolume, en.volume, tolerance + delta))
                continue;
        }
        if (rn.isLeaf() && en.isLeaf())
        {
            if constexpr (std::is_same_v<Volume, MedialSphere>)
            {
                // Overlapping leaf spheres put the solids within the sum of their bounds (plus the
                // test's tolerance) of each other: small enough, that decides (approximate mode).
                if (leafTolerance_ && !proximity && !found &&
                    placed.volume(pair.robot).approximationBound() + en.volume.approximationBound() + tolerance <=
                        *leafTolerance_)
                {
                    hit = true;
                    continue;
                }
            }
            if (pieceStage_ && !proximity)
            {
                const std::int32_t rp = robotPieces_.pieceOfNode[pair.robot];
                const std::int32_t ep = environmentPieces_.pieceOfNode[pair.environment];
                const IntersectionResult lp =
                    intersectConvexPieces(placedPieces.piece(pair.robot, robotPieces_.pieces[rp]),
                                          environmentPieces_.pieces[ep], context.lp());
                ++pieceTests;
                if (!lp.intersecting)
                    continue;
                const std::optional<double> &t = pieceStage_->approximateTolerance;
                // Hulls that meet put the triangles within the sum of the two bounds of each other.
                if (t && robotPieces_.approximationBound[rp] + environmentPieces_.approximationBound[ep] <= *t)
                {
                    if (!found)
                        hit = true;
                    else
                    {
                        found->push_back({ContactPair::Kind::Pieces, std::uint32_t(rp), std::uint32_t(ep), lp.witness});
                        hit = found->size() >= limit;
                    }
                    continue;
                }
            }
            for (std::uint32_t i = 0; i < rn.triangleCount && !hit; ++i)
            {
                const std::uint32_t rt = robotTree_.triangleOrder()[rn.firstTriangle + i];
                for (std::uint32_t j = 0; j < en.triangleCount; ++j)
                {
                    const std::uint32_t et = environmentTree_.triangleOrder()[en.firstTriangle + j];
                    if (!trianglesWithin(rt, et))
                        continue;
                    if (near)
                    {
                        near->push_back({rt, et});
                        if ((hit = near->size() > limit))
                            break;
                        continue;
                    }
                    if (!found)
                    {
                        hit = true;
                        *witness = {true, rt, et};
                        break;
                    }
                    const PlacedTriangle &a = placed.triangle(rt);
                    found->push_back({ContactPair::Kind::Triangles, rt, et,
                                      triangleContactPoint(a.corners[0], a.corners[1], a.corners[2], env.corner(et, 0),
                                                           env.corner(et, 1), env.corner(et, 2))});
                    if ((hit = found->size() >= limit))
                        break;
                }
            }
            continue;
        }
        if constexpr (LanesOf<Volume>::kUsed)
        {
            // The boxes two levels below the node split are tested at once, by the same sphere and
            // separating-axis tests; the pairs that may overlap are pushed as tested: nearest
            // centres on top for a yes-or-no query (NearestOnTop), else in the order childPairs
            // would visit them.
            const LaneSplit split = laneSplit(pair);
            if (split.kind == LaneSplit::Kind::Environment)
            {
                const auto &lanes = *split.environmentLanes;
                // One robot node, or each of its two children, against every lane at once.
                const int robotCount = split.eachRobotChild ? 2 : 1;
                const auto robotOf = [&](int i) {
                    return split.eachRobotChild ? std::uint32_t(rn.firstChild + i) : pair.robot;
                };
                // The mask of lanes robot node r may overlap; each lane counts as a box test.
                const auto overlappingLanes = [&](std::uint32_t r, const Volume &robotVolume) {
                    boxTests += std::uint64_t(lanes.count);
                    return lanesOverlap(lanes, robotVolume, rNodes[r].radius, tolerance + slack.at(robotNodeReach_[r]));
                };
                if (!near && !found)
                {
                    // A yes-or-no query: the pairs that may overlap, nearest centres on top.
                    NearestOnTop order;
                    for (int i = 0; i < robotCount; ++i)
                    {
                        const std::uint32_t r = robotOf(i);
                        const Volume &robotVolume = placed.volume(r);
                        const unsigned overlapping = overlappingLanes(r, robotVolume);
                        const Vec3 centre = VolumeTraits<Volume>::center(robotVolume);
                        const int c = lanes.kCenter;
                        for (int k = 0; k < lanes.count; ++k)
                            if ((overlapping >> k) & 1u)
                            {
                                const Vec3 laneCentre(lanes.field[c][k], lanes.field[c + 1][k], lanes.field[c + 2][k]);
                                order.add({r, lanes.node[k] | kTestedByLanes}, (laneCentre - centre).squaredNorm(),
                                          lanes.radius[k] + rNodes[r].radius);
                            }
                    }
                    order.pushOnto(stack);
                    continue;
                }
                // Contacts and near pairs are listed in the trees' order: robot children last
                // first, so that the first comes off the stack first.
                for (int i = robotCount - 1; i >= 0; --i)
                {
                    const std::uint32_t r = robotOf(i);
                    const unsigned overlapping = overlappingLanes(r, placed.volume(r));
                    for (int k = lanes.count - 1; k >= 0; --k)
                        if ((overlapping >> k) & 1u)
                            stack.push({r, lanes.node[k] | kTestedByLanes});
                }
                continue;
            }
            if (split.kind == LaneSplit::Kind::Robot)
            {
                // The robot's boxes, placed in world once per query, against the environment node.
                const RobotBlock &block = robotBlocks_[split.robotBlock];
                const auto &lanes = placed.lanes(split.robotBlock, block.node, block.count);
                const unsigned overlapping =
                    lanesOverlap(lanes, en.volume, en.radius, tolerance + slack.at(block.reach));
                boxTests += std::uint64_t(lanes.count);
                for (int k = lanes.count - 1; k >= 0; --k)
                    if ((overlapping >> k) & 1u)
                        stack.push({lanes.node[k], pair.environment | kTestedByLanes});
                continue;
            }
        }
        // Pushed last first, so that the first child pair comes off the stack first.
        NodePair children[4];
        for (int k = childPairs(pair, children) - 1; k >= 0; --k)
            stack.push(children[k]);
    }
    record();
    return hit;
}

template <class Volume>
std::vector<ContactPair> VolumeTreeChecker<Volume>::doContacts(const RigidTransform &worldFromRobot, std::size_t limit,
                                                               QueryContext &context) const
{
    std::vector<ContactPair> found;
    if (limit > 0 && worldFromRobot.isFinite())
        anyPairWithin(worldFromRobot, {}, context, &found, limit);
    for (ContactPair &c : found)
        if (c.kind == ContactPair::Kind::Triangles)
        {
            c.robotElement = robotFaces_.source(c.robotElement);
            c.environmentElement = environmentFaces_.source(c.environmentElement);
        }
    return found;
}

template <class Volume>
typename VolumeTreeChecker<Volume>::LaneSplit VolumeTreeChecker<Volume>::laneSplit(const NodePair &pair) const
{
    LaneSplit split;
    const typename VolumeTree<Volume>::Node &rn = robotTree_.nodes()[pair.robot];
    const typename VolumeTree<Volume>::Node &en = environmentTree_.nodes()[pair.environment];
    // childPairs' rule: both nodes in lockstep, else the one with the larger circumscribed sphere
    // (the robot's when the environment's is a leaf).
    const bool both = lockstep_ && !rn.isLeaf() && !en.isLeaf();
    if (both || (!en.isLeaf() && (rn.isLeaf() || rn.radius < en.radius)))
    {
        if (!lanesOfNode_.empty() && lanesOfNode_[pair.environment] >= 0)
        {
            split.kind = LaneSplit::Kind::Environment;
            split.environmentLanes = &environmentLanes_[std::size_t(lanesOfNode_[pair.environment])];
            split.eachRobotChild = both;
        }
    }
    else if (!rn.isLeaf() && !robotBlockOfNode_.empty() && robotBlockOfNode_[pair.robot] >= 0)
    {
        split.kind = LaneSplit::Kind::Robot;
        split.robotBlock = std::size_t(robotBlockOfNode_[pair.robot]);
    }
    return split;
}

template <class Volume>
int VolumeTreeChecker<Volume>::childPairs(const NodePair &pair, NodePair *children) const
{
    const typename VolumeTree<Volume>::Node &rn = robotTree_.nodes()[pair.robot];
    const typename VolumeTree<Volume>::Node &en = environmentTree_.nodes()[pair.environment];
    if (lockstep_ && !rn.isLeaf() && !en.isLeaf())
    {
        // Like trees: both nodes at once (see the constructor).
        for (int i = 0; i < 2; ++i)
            for (int j = 0; j < 2; ++j)
                children[2 * i + j] = {std::uint32_t(rn.firstChild + i), std::uint32_t(en.firstChild + j)};
        return 4;
    }
    // The node with the larger circumscribed sphere (the robot's when the environment's is a leaf).
    if (en.isLeaf() || (!rn.isLeaf() && rn.radius >= en.radius))
    {
        children[0] = {std::uint32_t(rn.firstChild), pair.environment};
        children[1] = {std::uint32_t(rn.firstChild + 1), pair.environment};
    }
    else
    {
        children[0] = {pair.robot, std::uint32_t(en.firstChild)};
        children[1] = {pair.robot, std::uint32_t(en.firstChild + 1)};
    }
    return 2;
}

template <class Volume>
double VolumeTreeChecker<Volume>::doDistance(const RigidTransform &worldFromRobot, QueryContext &context) const
{
    if (!worldFromRobot.isFinite())
        return 0.0;
    if (robotTree_.empty() || environmentTree_.empty())
        return std::numeric_limits<double>::infinity();
    if (doCollides(worldFromRobot, context))
        return 0.0;
    return freeDistance(worldFromRobot, context);
}

template <class Volume>
double VolumeTreeChecker<Volume>::doDistanceOfFreePose(const RigidTransform &worldFromRobot,
                                                       QueryContext &context) const
{
    if (pieceStage_ || leafTolerance_ || !worldFromRobot.isFinite())
        return doDistance(worldFromRobot, context);
    if (robotTree_.empty() || environmentTree_.empty())
        return std::numeric_limits<double>::infinity();
    return freeDistance(worldFromRobot, context);
}

template <class Volume>
double VolumeTreeChecker<Volume>::freeDistance(const RigidTransform &worldFromRobot, QueryContext &context) const
{
    // Branch and bound, nearest pair first (best_first_distance.h), on volume lower bounds.
    const double tolerance = toleranceFor(worldFromRobot);
    const auto &rNodes = robotTree_.nodes();
    const auto &eNodes = environmentTree_.nodes();
    const TriangleMesh &env = *scene_.environment;
    PlacedRobot<Volume> placed(robotTree_, worldFromRobot, context, robotBlocks_.size());
    std::uint64_t boxTests = 0, triangleTests = 0;
    const auto lowerBound = [&](const NodePair &p, double best) {
        ++boxTests;
        const Volume &robotVolume = placed.volume(p.robot);
        const Volume &envVolume = eNodes[p.environment].volume;
        const double centres =
            (VolumeTraits<Volume>::center(robotVolume) - VolumeTraits<Volume>::center(envVolume)).squaredNorm();
        const double reach = rNodes[p.robot].radius + eNodes[p.environment].radius + tolerance;
        // A pair the bounding spheres already put beyond the best distance needs no volume bound
        // (nor a square root: best itself is then a valid answer).
        if (centres >= (best + reach) * (best + reach) && best + reach >= 0.0)
            return best;
        const double sphereGap = std::sqrt(centres) - reach;
        if (sphereGap >= best)
            return sphereGap;
        const typename VolumeTree<Volume>::Node &rn = rNodes[p.robot];
        const typename VolumeTree<Volume>::Node &en = eNodes[p.environment];
        if (rn.isLeaf() && en.isLeaf() && rn.triangleCount == 1 && en.triangleCount == 1)
        {
            // Two triangles: their own world boxes are tighter than a robot volume re-boxed or
            // turned, and where they fail the triangles' distance (which the culls of
            // disjointTriangleDistanceBelow keep cheap) costs about what the volumes' bound would
            // (bugtrap's clearance 5% cheaper without that bound, alpha-1.5's 2%).
            const PlacedTriangle &a = placed.triangle(robotTree_.triangleOrder()[rn.firstTriangle]);
            const TriangleBounds &b = environmentTriangleBounds_[environmentTree_.triangleOrder()[en.firstTriangle]];
            return std::max(sphereGap, boxSeparation(a.min, a.max, b.min, b.max).norm() - tolerance);
        }
        // Boxes stop at the first stage of their bound that puts the pair beyond the best distance.
        if constexpr (std::is_same_v<Volume, Obb>)
            return std::max(sphereGap, obbDistanceLowerBound(robotVolume, envVolume, tolerance, best));
        else
            return std::max(sphereGap, VolumeTraits<Volume>::lowerBound(robotVolume, envVolume, tolerance));
    };
    const auto isLeafPair = [&](const NodePair &p) {
        return rNodes[p.robot].isLeaf() && eNodes[p.environment].isLeaf();
    };
    // The pose is free: no pair of triangles meets.
    const auto leafDistance = [&](const NodePair &p, double best) {
        const typename VolumeTree<Volume>::Node &rn = rNodes[p.robot];
        const typename VolumeTree<Volume>::Node &en = eNodes[p.environment];
        return leafTrianglesDistance(placed, robotTree_.triangleOrder().data() + rn.firstTriangle, rn.triangleCount,
                                     env, environmentTree_.triangleOrder().data() + en.firstTriangle, en.triangleCount,
                                     best, triangleTests);
    };
    const auto boundedSplit = [&](const NodePair &p, double best, BoundedPair *out) {
        if constexpr (LanesOf<Volume>::kUsed)
        {
            // Where the environment node (or the robot node) is split, the boxes two levels below
            // it are bounded at once, as in anyPairWithin.
            const typename VolumeTree<Volume>::Node &rn = rNodes[p.robot];
            const typename VolumeTree<Volume>::Node &en = eNodes[p.environment];
            int count = 0;
            double bounds[4];
            // A pair of single triangles also takes their world boxes' separation, as lowerBound.
            const auto add = [&](std::uint32_t r, std::uint32_t e, double bound) {
                const typename VolumeTree<Volume>::Node &a = rNodes[r], &b = eNodes[e];
                if (bound < best && a.isLeaf() && b.isLeaf() && a.triangleCount == 1 && b.triangleCount == 1)
                {
                    const PlacedTriangle &ta = placed.triangle(robotTree_.triangleOrder()[a.firstTriangle]);
                    const TriangleBounds &tb =
                        environmentTriangleBounds_[environmentTree_.triangleOrder()[b.firstTriangle]];
                    bound = std::max(bound, boxSeparation(ta.min, ta.max, tb.min, tb.max).norm() - tolerance);
                }
                out[count++] = {{r, e}, bound};
            };
            const LaneSplit split = laneSplit(p);
            if (split.kind == LaneSplit::Kind::Environment)
            {
                const auto &lanes = *split.environmentLanes;
                for (int i = 0; i < (split.eachRobotChild ? 2 : 1); ++i)
                {
                    const std::uint32_t r = split.eachRobotChild ? std::uint32_t(rn.firstChild + i) : p.robot;
                    lanesDistanceLowerBound(lanes, placed.volume(r), rNodes[r].radius, tolerance, bounds);
                    boxTests += std::uint64_t(lanes.count);
                    for (int k = 0; k < lanes.count; ++k)
                        add(r, lanes.node[k], bounds[k]);
                }
                return count;
            }
            if (split.kind == LaneSplit::Kind::Robot)
            {
                const RobotBlock &block = robotBlocks_[split.robotBlock];
                const auto &lanes = placed.lanes(split.robotBlock, block.node, block.count);
                lanesDistanceLowerBound(lanes, en.volume, en.radius, tolerance, bounds);
                boxTests += std::uint64_t(lanes.count);
                for (int k = 0; k < lanes.count; ++k)
                    add(lanes.node[k], p.environment, bounds[k]);
                return count;
            }
        }
        NodePair children[kMaxPairChildren];
        const int count = childPairs(p, children);
        for (int k = 0; k < count; ++k)
            out[k] = {children[k], lowerBound(children[k], best)};
        return count;
    };
    const double best = bestFirstDistanceBounded(context.scratch<NearestPairQueue>(),
                                                 lowerBound(NodePair{0, 0}, std::numeric_limits<double>::infinity()),
                                                 isLeafPair, leafDistance, boundedSplit);
    context.stats.boundingVolumeTests += boxTests;
    context.stats.primitiveTests += triangleTests;
    return best;
}

namespace
{
template <class Volume>
ExportMesh levelMesh(const VolumeTree<Volume> &tree, int level)
{
    ExportMesh mesh;
    std::vector<std::pair<std::uint32_t, int>> stack{{0, 0}};
    while (!stack.empty() && !tree.empty())
    {
        const auto [node, depth] = stack.back();
        stack.pop_back();
        const auto &n = tree.nodes()[node];
        if (depth == level || (n.isLeaf() && depth < level))
        {
            VolumeTraits<Volume>::appendMesh(n.volume, mesh);
            continue;
        }
        if (!n.isLeaf())
        {
            stack.push_back({std::uint32_t(n.firstChild + 1), depth + 1});
            stack.push_back({std::uint32_t(n.firstChild), depth + 1});
        }
    }
    return mesh;
}
}  // namespace

template <class Volume>
std::optional<LevelVolumes> VolumeTreeChecker<Volume>::levelVolumes(int level) const
{
    LevelVolumes v;
    v.kind = VolumeTraits<Volume>::kName;
    v.robot = levelMesh(robotTree_, level);
    v.environment = levelMesh(environmentTree_, level);
    v.robotDepth = robotTree_.depth();
    v.environmentDepth = environmentTree_.depth();
    return v;
}

template <class Volume>
std::vector<HierarchyReport> VolumeTreeChecker<Volume>::hierarchies(bool withVolumeRatios) const
{
    const std::string kind = VolumeTraits<Volume>::kName;
    std::vector<HierarchyReport> reports = {{"robot " + kind + " tree", robotTree_.nodes().size(), robotTree_.depth(),
                                             robotTree_.buildSeconds(), robotTree_.memoryBytes()},
                                            {"environment " + kind + " tree", environmentTree_.nodes().size(),
                                             environmentTree_.depth(), environmentTree_.buildSeconds(),
                                             environmentTree_.memoryBytes() +
                                                 environmentTriangleBounds_.capacity() * sizeof(TriangleBounds) +
                                                 environmentLanes_.capacity() * sizeof(typename LanesOf<Volume>::Type) +
                                                 lanesOfNode_.capacity() * sizeof(std::int32_t)}};
    reports[0].memoryBytes +=
        robotBlocks_.capacity() * sizeof(RobotBlock) + robotBlockOfNode_.capacity() * sizeof(std::int32_t);
    if (withVolumeRatios)
    {
        std::tie(reports[0].meanVolumeRatio, reports[0].ratioNodes) = meanVolumeRatio(robotTree_);
        std::tie(reports[1].meanVolumeRatio, reports[1].ratioNodes) = meanVolumeRatio(environmentTree_);
    }
    if (pieceStage_)
        for (const auto &[label, d] :
             {std::pair<const char *, const ConvexDecomposition *>{"robot convex pieces", &robotPieces_},
              {"environment convex pieces", &environmentPieces_}})
        {
            std::size_t bytes = 0;
            for (const ConvexPiece &p : d->pieces)
                bytes += p.normals.size() * (sizeof(Vec3) + sizeof(double)) + p.vertices.size() * sizeof(Vec3);
            reports.push_back({label, d->pieces.size(), 0, d->seconds, bytes});
        }
    return reports;
}

template class VolumeTreeChecker<Obb>;
template class VolumeTreeChecker<Ellipsoid>;
template class VolumeTreeChecker<HybridVolume<false>>;
template class VolumeTreeChecker<HybridVolume<true>>;
template class VolumeTreeChecker<Sphere>;
template class VolumeTreeChecker<Aabb>;
template class VolumeTreeChecker<FixedAabb>;
template class VolumeTreeChecker<KDop<14>>;
template class VolumeTreeChecker<KDop<18>>;
template class VolumeTreeChecker<KDop<26>>;
template class VolumeTreeChecker<Ssv>;
template class VolumeTreeChecker<MedialSphere>;
template class VolumeTreeChecker<CTreeVolume>;
}  // namespace hcd
