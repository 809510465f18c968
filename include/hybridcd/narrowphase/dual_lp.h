// SPDX-License-Identifier: BSD-3-Clause
// The review's dual LP (section 4.1, eq. 4): whether two convex pieces intersect, decided by a
// small dense simplex on the dual of the feasibility LP, beside the primal Seidel LPs of
// linear_program.h.
//
// The primal. Both pieces are sets of inequalities n_i . x <= d_i (unit normals). In the working
// frame of linear_program.h (translated to the mid-centroid, scaled so every vertex has
// |x'_k| <= 1) shift once more, y = x' + 2 (componentwise), so that every point of either piece has
// y >= 1. Eq. 2-3 with the review's sign convention is then
//     maximise c . y   subject to   n_i . y <= b_i  (every face of both),   y >= 0,
// with b_i = d'_i + 2 (n_i . (1, 1, 1)). The constraint y >= 0 never cuts the intersection (it
// lies in y >= 1), so the primal is feasible exactly when the pieces intersect, and then bounded
// (the pieces are).
//
// The dual (eq. 4):
//     minimise b . lambda   subject to   sum_i lambda_i n_i >= c,   lambda >= 0,
// three constraints whatever the number of faces, one variable per face. LP duality: the primal
// is feasible and bounded exactly when the dual has an optimum; the primal is infeasible exactly
// when the dual is unbounded, provided the dual is feasible.
//
// Why the dual is always feasible. A bounded piece has no direction u != 0 with n_i . u <= 0 for
// all its faces (that would be a ray inside it), so by Farkas' lemma its normals positively span
// R^3: every c, whatever its sign, is sum lambda_i n_i with lambda >= 0 over the faces of A alone.
// The choice of c then only decides where the simplex starts and which vertex is the witness:
//   - c = (1, 1, 1), the review's: lambda = 0 is not feasible, so phase 1 first minimises the sum
//     of three artificial variables to find a feasible basis;
//   - c = -(1, 1, 1) (the default): lambda = 0 with the three surplus variables s = -c = 1 is a
//     feasible basis at once, and phase 1 is skipped. The witness is then the vertex of the
//     intersection nearest the working frame's lower corner in the 1-norm.
// Any other c is accepted (rows with c_j > 0 get an artificial, the others start on their surplus).
//
// Reading the answer. At a dual optimum the basis holds three columns; by complementary slackness
// the faces among them are tight at the primal optimum, which is the point where those three face
// planes meet. It is solved from the original rows (not from the tableau, which has seen rounding)
// and mapped back to the pieces' frame: the witness. When the simplex finds an entering column
// with no positive entry the dual is unbounded, and the ray mu >= 0 (the entering column and the
// basic variables' rates) satisfies sum mu_i n_i >= 0 and b . mu < 0: a Farkas certificate. Its A
// part w = sum_{i in A} mu_i n_i separates: on A, w . y <= sum_A mu_i b_i; on B, since
// sum_B mu_i n_i = v - w with v >= 0 and y >= 0 there, w . y >= -sum_B mu_i b_i; the two bounds
// differ by -b . mu > 0.
//
// The simplex. A dense tableau of three constraint rows and one reduced-cost row over m + 6
// columns (faces, surpluses, artificials), stored column by column. Entering column by Dantzig's
// rule (most negative reduced cost); after a run of degenerate pivots (no progress) it switches to
// Bland's rule (lowest index enters, lowest basic index leaves among ties), which cannot cycle.
// A pivot costs O(m), like one violation check of Seidel's algorithm over all faces, and a solve
// takes a handful of pivots (bench/micro/lp_micro.cpp prints the counts). The workspace is the
// caller's and only grows, so a warm solve allocates nothing.
//
// Verification, touching and the fallback. Every answer is checked in the pieces' own frame
// before it is returned: a witness against every inequality of both pieces, a separating plane
// against every vertex of both. The touching rule is linear_program.h's: touching counts as
// intersecting, and the tolerance is 1e-9 of the pair's largest absolute vertex coordinate. The
// dual's answer stands only where it is clear-cut: a witness violating no inequality by more than
// rounding (1e-13 relative, as the slack LP), or a plane separating the vertices by more than the
// tolerance. Anything else (a check that fails, an answer within the tolerance band where
// violation and distance can disagree, a singular basis, a pivot limit) falls back to
// `intersectConvexPieces`, the slack LP, whose answer is returned and the fallback counted in the
// workspace.
#pragma once

#include "hybridcd/narrowphase/convex_piece.h"
#include "hybridcd/narrowphase/linear_program.h"

#include <cstdint>
#include <vector>

namespace hcd
{
struct DualLpResult;

/// The objective of the dual LP's primal, c in eq. 2, in the shifted working frame (see the file
/// comment): -(1, 1, 1) needs no phase 1.
inline const Vec3 kDualLpDefaultObjective = Vec3(-1.0, -1.0, -1.0);
/// The review's objective, x + y + z (needs phase 1 with artificial variables).
inline const Vec3 kDualLpReviewObjective = Vec3(1.0, 1.0, 1.0);

/// Scratch memory of the dual simplex (a tableau and the working-frame rows, which only grow), the
/// slack LP's workspace for the fallback, and counters of what the solves did. Owned by the caller
/// and used by one solve at a time.
class DualLpWorkspace
{
public:
    /// Counts since construction (or the last `resetCounters`).
    struct Counters
    {
        std::uint64_t solves = 0;
        std::uint64_t pivots = 0;          ///< simplex pivots over all solves, both phases
        std::uint64_t phaseOnePivots = 0;  ///< pivots spent finding a feasible dual basis
        std::uint64_t fallbacks = 0;       ///< answers given by intersectConvexPieces instead
        std::uint64_t bandFallbacks = 0;   ///< of which: the dual's answer was within the tolerance
    };

    const Counters &counters() const { return counters_; }
    void resetCounters() { counters_ = Counters{}; }

private:
    friend DualLpResult intersectConvexPiecesDual(const ConvexPiece &, const ConvexPiece &, DualLpWorkspace &,
                                                  const Vec3 &);
    Counters counters_;
    std::vector<double> tableau;  // (m + 6) columns of 4: three constraint rows, reduced cost
    std::vector<double> normal;   // 3 m: unit normals in the working frame (the pieces' directions)
    std::vector<double> cost;     // m: b_i in the shifted working frame
    LpWorkspace slack;            // for the fallback
};

/// Outcome of `intersectConvexPiecesDual`, every field in the pieces' common frame and units.
struct DualLpResult
{
    /// Who answered.
    enum class Certificate
    {
        Witness,      ///< intersecting: the dual optimum's primal point, checked against both pieces
        FarkasPlane,  ///< disjoint: the plane of the dual's unbounded ray, checked on all vertices
        Fallback,     ///< the dual's answer did not pass its check: intersectConvexPieces answered
    };

    /// True when the pieces intersect or touch (the touching rule of linear_program.h).
    bool intersecting = false;
    /// When intersecting: a point violating no inequality of either piece by more than 1e-9 of the
    /// coordinates' magnitude (a vertex of the intersection, unless the fallback answered).
    Vec3 witness = Vec3::Zero();
    /// When disjoint: a unit normal n and offset o with n.x <= o on every vertex of A and
    /// n.x >= o on every vertex of B.
    Vec3 separatingNormal = Vec3::Zero();
    double separatingOffset = 0.0;
    Certificate certificate = Certificate::Witness;
    /// Simplex pivots this solve took (both phases).
    int pivots = 0;
};

/// Exact intersection test of two convex pieces given in one frame, by the dual simplex on eq. 4
/// (see the file comment), every answer verified and the slack LP (intersectConvexPieces) used
/// when the verification fails. Touching pieces count as intersecting. `objective` is c of eq. 2
/// in the shifted working frame; any value gives the same verdict. Preconditions: both pieces
/// non-empty, as ConvexPiece::hullOf (or transformed) builds them.
DualLpResult intersectConvexPiecesDual(const ConvexPiece &a, const ConvexPiece &b, DualLpWorkspace &workspace,
                                       const Vec3 &objective = kDualLpDefaultObjective);
}  // namespace hcd
