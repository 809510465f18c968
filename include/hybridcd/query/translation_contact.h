// SPDX-License-Identifier: BSD-3-Clause
// First contact of a translating robot, by the time-augmented LP (review, section 5).
//
// When the robot's rotation stays fixed along a motion, every robot point moves by the same
// displacement d, and each robot triangle against each environment triangle is a pair of flat
// convex pieces in relative translation: `translationalTimeOfContact` gives the pair's first
// contact exactly, with no sampling of the motion. The robot's first contact is the earliest over
// all pairs. Pairs are culled by their boxes: each robot triangle's box, swept along d, against
// each environment triangle's box (one sweep along x, as the brute-force checker does), then the
// interval of times at which the moving box overlaps the fixed one; pairs are solved in order of
// that interval's start, and a pair whose boxes meet only after the best contact found is skipped.
// Boxes are padded by 1e-9 of the scene's size, so culling never drops a pair the LP would report.
//
// Surfaces only: this finds the first time the robot's surface touches the environment's. A robot
// that starts outside every solid of the environment (as the solid-semantics check of the start
// state establishes) can only enter one through its surface, so after a free start state the first
// surface contact is the first contact.
#pragma once

#include "hybridcd/geometry/collision_scene.h"
#include "hybridcd/geometry/rigid_transform.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace hcd
{
struct TranslationContact
{
    /// True when the robot's surface touches the environment's at some time in [0, 1].
    bool contact = false;
    /// The earliest such time (1 when there is none).
    double time = 1.0;
    /// World frame: a point of both surfaces at `time` (within about 1e-12 of the pair's size).
    Vec3 point = Vec3::Zero();
    /// The touching triangles, as indices into the source meshes.
    std::uint32_t robotTriangle = 0, environmentTriangle = 0;
    /// Triangle pairs whose LP was solved.
    std::size_t pairsSolved = 0;
};

class TranslationContactFinder
{
public:
    explicit TranslationContactFinder(CollisionScene scene);

    /// The robot placed by `worldFromRobot` and translated by `displacement` (world frame and
    /// units) over t in [0, 1]: robot point p is at worldFromRobot(p) + t * displacement.
    /// A non-finite pose or displacement gives contact at time 0 (never a free answer).
    TranslationContact firstContact(const RigidTransform &worldFromRobot, const Vec3 &displacement) const;

    /// The reference: the same LP on every triangle pair, no culling.
    TranslationContact firstContactAllPairs(const RigidTransform &worldFromRobot, const Vec3 &displacement) const;

private:
    struct TriangleBox
    {
        Vec3 min, max;
        std::uint32_t triangle;
    };
    TranslationContact solvePair(const RigidTransform &worldFromRobot, const Vec3 &displacement, std::uint32_t robot,
                                 std::uint32_t environment) const;

    DistinctFaceMesh robotFaces_, environmentFaces_;
    std::vector<TriangleBox> environmentBoxes_;  ///< padded, sorted by min.x
    double padding_ = 0.0;                       ///< world units
};
}  // namespace hcd
