// SPDX-License-Identifier: BSD-3-Clause
// A covering ball centred on a solid's medial axis, remembering the inscribed ball it grew from.
#pragma once

#include "hybridcd/bv/sphere.h"

namespace hcd
{
/// Ball {p : |p - ball.center| <= ball.radius} that contains a node's triangles. When `inner` is
/// positive, the ball of that radius about the same centre lies inside a closed solid of the mesh
/// (the centre is a medial-axis point and `inner` its distance to the surface, seed eq. 5); 0 when
/// the centre is not known to be inside a solid (open meshes, internal nodes fitted to points).
struct MedialSphere
{
    Sphere ball;
    double inner = 0.0;

    /// The same balls mapped by `pose` (rotation-invariant: only the centre moves).
    MedialSphere transformed(const RigidTransform &pose) const { return {ball.transformed(pose), inner}; }

    /// How far apart the things this ball stands for may be when two such balls meet, counted per
    /// ball: with an inscribed ball, radius - inner (the solid reaches within that of any point of
    /// the covering ball); without, 2 radius (any triangle point lies within that of any point of
    /// the ball). Two leaves that overlap put their solids (or, without solids, their triangles)
    /// within the sum of the two bounds of each other.
    double approximationBound() const { return inner > 0.0 ? ball.radius - inner : 2.0 * ball.radius; }
};
}  // namespace hcd
