// SPDX-License-Identifier: BSD-3-Clause
// The separating-axis test: the reference against which the LP narrow phase is checked, and its
// fallback when the LP's own certificate fails. Two convex polytopes are disjoint exactly when
// their vertices' projections on one of the candidate axes (candidate_axes.h) do not overlap. It
// also fixes what touching means for the whole narrow phase: no axis separates the pieces by more
// than kNarrowPhaseRelativeTolerance of their coordinates' magnitude.
#pragma once

#include "hybridcd/narrowphase/convex_piece.h"

namespace hcd
{
/// The narrow phase's tolerance, relative to the largest absolute vertex coordinate of the pair.
constexpr double kNarrowPhaseRelativeTolerance = 1e-9;

/// The separating-axis test: the largest gap, over the candidate axes, between the projections
/// of the pieces' vertices (face normals of both, cross products of every pair of edges, and for
/// pieces of dimension <= 1 the extra axes their degenerate Minkowski difference needs), which
/// is positive exactly when the pieces are disjoint and, if negative, minus the smallest overlap.
/// `axis`, when given, receives the best unit axis, oriented so that A projects below B.
double separatingAxisGap(const ConvexPiece &a, const ConvexPiece &b, Vec3 *axis = nullptr);

/// Reference test by separating axes (O(E_a E_b (V_a + V_b))): intersecting (or touching) when
/// no axis separates the pieces by more than 1e-9 of the coordinates' magnitude.
bool convexPiecesIntersectSat(const ConvexPiece &a, const ConvexPiece &b);
}  // namespace hcd
