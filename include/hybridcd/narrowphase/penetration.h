// SPDX-License-Identifier: BSD-3-Clause
// Penetration depth of intersecting convex pieces (review, sections 2.2 and 5).
//
// The penetration depth of two intersecting objects is the shortest translation of one that
// brings them into touching contact. For convex pieces A and B, A + s lies clear of B exactly
// when s lies outside the Minkowski difference B - A = {b - a}, so the penetration depth is the
// distance from the origin to the boundary of B - A, and the penetration vector is the foot of
// that distance on the boundary. For polytopes the closest boundary point lies on a facet, and
// the distance to the facet with outward unit normal n is the support value
//
//     h(n) = max_{b in B} n . b - min_{a in A} n . a,
//
// the amount by which the projections of A and B onto n overlap when A is to be pushed towards
// +n: translating A by h(n) n makes A's lowest point along n meet B's highest. Every direction
// gives such a separating translation (h(n) >= depth for every unit n), and the minimum over the
// facet normals of B - A is the exact depth. Those normals are among the face normals of A, the
// face normals of B and the cross products of an edge of A with an edge of B (plus, for points
// and segments, the few extra axes that a degenerate Minkowski difference needs, as in the
// separating-axis test), so `penetrationDepth` takes the minimum of h over that finite candidate
// set, both orientations of each. Cost O(E_A E_B (V_A + V_B)): fine for the pieces of a convex
// decomposition, which have a few dozen vertices. The answer is the same quantity as
// `separatingAxisGap`'s, with the opposite sign and the translation's orientation made explicit.
//
// Section 5 itself works with a direction of motion: over a small time step the motion is a
// translation, and the LP of section 4.1 with time as a fourth variable (see time_of_contact.h)
// yields how far along that motion the contact lies. `directionalPenetration` is that LP read
// backwards: given that A, travelling along `motion`, now overlaps B, how far must A be moved
// back against its motion to just touch B. It is the largest s >= 0 for which A - s m (m the unit
// motion) still meets B:
//
//     maximise s  subject to  n_j . x <= d_j (faces of B),  n_i . (x + s m) <= d_i (faces of A),
//
// a 4-variable LP in (x, s) solved by `solveSmallLp<4>`; the optimal x is the last point of
// contact. Equivalently, the time of contact of A moving back along -m, counted from the far end.
// The two quantities are related: the penetration depth is the minimum of the directional depth
// over all directions, attained at the penetration direction, where both agree.
#pragma once

#include "hybridcd/narrowphase/convex_piece.h"

namespace hcd
{
/// Result of `penetrationDepth`, in the pieces' common frame and units.
struct Penetration
{
    /// True when the pieces intersect or touch (no candidate axis separates them by more than
    /// 1e-9 of the coordinates' magnitude: the narrow phase's criterion).
    bool intersecting = false;
    /// Unit direction in which A is to be translated (when intersecting): A + depth * direction
    /// touches B without overlapping it. Unspecified (but unit) when disjoint.
    Vec3 direction = Vec3::UnitX();
    /// Length of that translation, >= 0 (0 for touching and for disjoint pieces).
    double depth = 0.0;
};

/// Minimum translation of A that separates two intersecting convex pieces (the penetration depth
/// vector, depth * direction): the minimum over candidate unit directions n (the face normals of
/// both pieces and the normalised cross products of their edge pairs, both orientations, which is
/// exact for polytopes; see the essay above) of h(n) = max_{b in B} n . b - min_{a in A} n . a,
/// the translation of A along +n after which A's projection lies just above B's. Translating A
/// by depth * direction leaves the pieces touching (up to rounding); any shorter translation
/// leaves them intersecting. When the pieces are disjoint, `intersecting` is false and `depth`
/// is 0. Preconditions: both pieces in one frame and non-empty, with vertices and edges, as
/// `ConvexPiece::hullOf` builds them.
Penetration penetrationDepth(const ConvexPiece &a, const ConvexPiece &b);

/// Directional penetration depth: how far A, which travels along `motion`, must be moved back
/// along -motion to just touch B, i.e. the largest s >= 0 such that A translated by
/// -s * motion / |motion| still intersects B (the 4-variable LP in the essay above; a length in
/// the pieces' units, along the unit motion direction). 0 when the pieces are disjoint (by the
/// narrow phase's criterion, `intersectConvexPieces`) or just touching. Exact for polytopes up to
/// rounding and a tolerance of 1e-12 of the pair's size. Preconditions: both pieces in one frame
/// and non-empty; `motion` finite and non-zero (otherwise std::invalid_argument).
double directionalPenetration(const ConvexPiece &a, const Vec3 &motion, const ConvexPiece &b);
}  // namespace hcd
