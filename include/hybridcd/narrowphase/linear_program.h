// SPDX-License-Identifier: BSD-3-Clause
// The exact narrow phase by linear programming (review, section 4.1): two convex pieces intersect
// exactly when some point satisfies the inequalities of both, a linear feasibility problem.
//
// Formulation. The review maximises an arbitrary objective over the union of both pieces'
// inequalities n_i . x <= d_i and reads feasibility off the solver. We instead add a slack t and
//
//     maximise t  subject to  n_i . x + t <= d_i  for every face of both pieces     (x, t) in R^4.
//
// With unit normals t is the radius of the largest ball around x inside both pieces, so the
// optimum answers the question and more: t* >= 0 means intersecting (touching when t* = 0), and
// the optimal x is a well-centred witness (the Chebyshev centre of the intersection) rather than
// a corner. The problem is always feasible (t may be very negative), so the solver never has to
// decide infeasibility, the part of LP that is most fragile in floating point. When t* < 0 the
// LP dual gives a certificate of disjointness: multipliers lambda >= 0 on the optimal basis with
// sum lambda_i n_i = 0 and sum lambda_i = 1; the A part w = sum_{i in A} lambda_i n_i satisfies
// w . x <= sum_{i in A} lambda_i d_i on A and w . x >= -sum_{i in B} lambda_i d_i on B, and
// these bounds differ by -t* > 0: w is a separating direction with gap at least -t*. Section 5's
// penetration formulation (a time variable) is the same shape with one more dimension, which is
// why the solver (small_lp.h) is generic in the dimension.
//
// Order. The narrow phase hands Seidel's solver the faces roughly in increasing order of their
// slack at the point between the two centroids (a one-pass bucket order) rather than shuffled:
// the faces that end up tight then come first, and late violations become rare. Together with
// the solver's move-to-front: about 1.7 us for two 20-face pieces, against 21 us in random order.
//
// Robustness. Coordinates are first translated to the pieces' mid-centroid and scaled to unit
// size, and each constraint's normal is normalised, so that one absolute tolerance means the
// same at every scale (1e6 and 1e-6 alike). A box |x_i| <= 4 (four times the data's extent,
// never active at the optimum of intersecting pieces) keeps every subproblem bounded. Every
// answer is certified afterwards in the original frame: the witness against every inequality of
// both pieces, the separating plane against every vertex of both; if the dual plane fails, a
// separating-axis search over face normals and edge-edge cross products (exact for polytopes,
// separating_axes.h) finds one.
//
// Touching. Touching counts as intersecting, with a tolerance of 1e-9 of the coordinates'
// magnitude. The pieces intersect when the witness satisfies every inequality up to rounding
// (t* >= -1e-13 relative), and are disjoint when it violates one by more than the tolerance (then
// the distance exceeds it too). In between, the violation alone does not decide: near a sharp
// vertex a point can be far from a piece yet violate its face planes only slightly, so the pieces
// count as touching only when no plane separates their vertices by more than the tolerance either
// (the dual plane, else the separating-axis search), which is the reference test's criterion.
// Only pairs within about a millionth of their size of touching, and not touching up to rounding,
// fall in that band, so the search's cost (quadratic in the number of edges) is rarely paid.
#pragma once

#include "hybridcd/narrowphase/convex_piece.h"
#include "hybridcd/narrowphase/separating_axes.h"
#include "hybridcd/narrowphase/small_lp.h"

#include <vector>

namespace hcd
{
/// Appends the face inequalities of `piece` as rows of a 4-variable LP in (x', u), with
/// x = center + scale * x' (a working frame in which the data has unit size) and the piece
/// translated by u * motion: n . x' + (n . motion) u <= (d - n . center) / scale, with n normalised
/// (zero normals skipped). `motion` zero gives a static piece. The time of contact and the
/// directional penetration are both LPs over such rows.
void appendWorkingFrameRows(std::vector<Halfspace<4>> &rows, const ConvexPiece &piece, const Vec3 &center, double scale,
                            const Vec3 &motion);

/// Outcome of `intersectConvexPieces`, every field in the pieces' common frame and units.
struct IntersectionResult
{
    /// How the answer was established (for statistics; every answer is certified as stated).
    enum class Certificate
    {
        Witness,       ///< intersecting: `witness` satisfies both pieces' inequalities
        LpDual,        ///< disjoint: plane from the LP's dual multipliers, checked on all vertices
        AxisSearch,    ///< disjoint: plane from the separating-axis search, checked on all vertices
                       ///< (when the dual plane fails or the LP's answer is within the tolerance)
        Conservative,  ///< the LP found no witness but no separating plane was found either:
                       ///< reported intersecting; `witness` is the LP's best point (numerical
                       ///< corner case, never seen in the tests)
    };

    /// True when the pieces intersect or touch: the witness violates no inequality by more than
    /// the tolerance (1e-9 of the largest absolute vertex coordinate) and no plane separates the
    /// pieces' vertices by more than it.
    bool intersecting = false;
    /// When intersecting: a point in both pieces: every inequality of both holds within 1e-9 of
    /// the coordinates' magnitude. It is the centre of a largest ball inside both.
    Vec3 witness = Vec3::Zero();
    /// When disjoint: a unit normal n and offset o with n.x <= o for every vertex of A and
    /// n.x >= o for every vertex of B (as evaluated in double precision).
    Vec3 separatingNormal = Vec3::Zero();
    double separatingOffset = 0.0;
    /// min_i (d_i - n_i . witness) over both pieces, i.e. the LP's optimum t*: when
    /// intersecting, the radius of a ball around the witness inside both (0 when touching or when
    /// a piece is flat); when disjoint, negative, and -t* is at most the distance between them.
    double depth = 0.0;
    Certificate certificate = Certificate::Witness;
};

/// Exact intersection test of two convex pieces given in one frame by the slack LP above (a 4D
/// Seidel LP over the faces of both). Touching pieces count as intersecting. Preconditions:
/// both pieces non-empty, as `ConvexPiece::hullOf` (or `transformed`) builds them.
IntersectionResult intersectConvexPieces(const ConvexPiece &a, const ConvexPiece &b, LpWorkspace &workspace);
/// intersectConvexPieces with a workspace of its own (allocates; for one-off tests).
inline IntersectionResult intersectConvexPieces(const ConvexPiece &a, const ConvexPiece &b)
{
    LpWorkspace workspace;
    return intersectConvexPieces(a, b, workspace);
}

/// The review's plain primal: feasibility of the union of both pieces' inequalities as a 3D LP
/// (objective x + y + z, random constraint order), the same tolerance applied to the
/// constraints. Cheaper than the slack LP (three dimensions instead of four) but it decides by
/// the solver's infeasibility test and gives neither a centred witness nor a separating plane;
/// kept to measure against the slack formulation (bench/micro/lp_micro.cpp).
bool convexPiecesIntersectPrimal(const ConvexPiece &a, const ConvexPiece &b, LpWorkspace &workspace);
inline bool convexPiecesIntersectPrimal(const ConvexPiece &a, const ConvexPiece &b)
{
    LpWorkspace workspace;
    return convexPiecesIntersectPrimal(a, b, workspace);
}
}  // namespace hcd
