// SPDX-License-Identifier: BSD-3-Clause
// Discrete orientation polytopes (k-DOPs, seed §3.6): slabs along a fixed set of k/2 directions.
#pragma once

#include "hybridcd/geometry/rigid_transform.h"

#include <array>
#include <vector>

namespace hcd
{
template <int K>
struct KDopRotation;

/// The k-DOP {p : lo_i <= n_i . p <= hi_i, i < k/2} for the unit directions n_i of kdopDirections<K>():
/// K = 14: the 3 axes and the 4 cube diagonals; K = 18: the axes and the 6 edge diagonals
/// (1,+-1,0)...; K = 26: all 13. The axes come first, so the first three slabs are the box.
template <int K>
struct KDop
{
    static constexpr int kSlabs = K / 2;
    std::array<double, kSlabs> lo{}, hi{};
    Vec3 center = Vec3::Zero();  ///< the centre of the box slabs, for the hierarchy's sphere test

    /// The tight k-DOP of `points`, each slab grown by 1e-9 of the coordinates' magnitude so
    /// rounding leaves no point outside. `points` must not be empty.
    static KDop fit(const std::vector<Vec3> &points);

    /// fit() in steps, for a hierarchy that builds a parent from its children without revisiting
    /// their points: the exact slabs of `points` (no margin, no centre); the exact slabs of the
    /// union of two such; and the margin and centre added last. withMargin(tight(points)) is
    /// fit(points) bit for bit, and so is withMargin(tightUnion(tight(p), tight(q))) for p and q's union.
    static KDop tight(const std::vector<Vec3> &points);
    static KDop tightUnion(const KDop &a, const KDop &b);
    static KDop withMargin(KDop tight);

    /// True when `p` satisfies every slab (inclusive).
    bool contains(const Vec3 &p) const;

    /// A k-DOP in the frame `pose` maps to that contains this one mapped by `pose`. The rotated
    /// polytope is not a k-DOP of the fixed directions any more; each world direction d is written
    /// as a combination of the three DOP directions spanning the cone of R^T d, and its support
    /// bounded by the combination of their slabs (valid for any combination since both signs of
    /// each direction are slabs). The combinations depend on the rotation only: a caller mapping
    /// many k-DOPs by one pose works them out once (KDopRotation::of) and a node then costs 3 k
    /// multiply-adds.
    KDop transformed(const KDopRotation<K> &mapping) const;
    /// The same, working out the combinations for this one call.
    KDop transformed(const RigidTransform &pose) const;

    /// The polytope's corners (plane triples satisfying every slab), for volumes, export and tests.
    std::vector<Vec3> vertices() const;

    /// The polytope's volume from its corners and faces.
    double volume() const;

    /// The polytope's faces as corner polygons in counter-clockwise order seen from outside.
    std::vector<std::vector<Vec3>> faces() const;
};

/// A pose with each world direction n_m written as a combination of local slab directions,
/// R^T n_m = sum_j coef_j n_{slab_j}: what KDop::transformed needs, worked out once per pose.
template <int K>
struct KDopRotation
{
    RigidTransform pose;
    std::array<std::array<int, 3>, K / 2> slab{};
    std::array<std::array<double, 3>, K / 2> coef{};

    static KDopRotation of(const RigidTransform &pose);
};

/// The K/2 unit directions of a k-DOP, axes first.
template <int K>
const std::array<Vec3, K / 2> &kdopDirections();

/// True unless some direction separates the polytopes by more than `tolerance`.
template <int K>
bool kdopsOverlap(const KDop<K> &a, const KDop<K> &b, double tolerance);

/// The largest gap along the directions (unit vectors, so a distance) less `tolerance`, never
/// below zero.
template <int K>
double kdopDistanceLowerBound(const KDop<K> &a, const KDop<K> &b, double tolerance);
}  // namespace hcd
