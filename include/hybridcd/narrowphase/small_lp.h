// SPDX-License-Identifier: BSD-3-Clause
// Linear programs in a few variables (one to four). The narrow phase's slack LP
// (`intersectConvexPieces`), the time of contact and the directional penetration are instances.
//
// Solver. Seidel's randomized incremental algorithm (Seidel 1991): take the constraints in a
// random order keeping the optimum of those seen so far; when a new constraint is violated the
// new optimum lies on its hyperplane, found by the same algorithm one dimension down on the
// constraints seen so far, substituted into that hyperplane. Expected time O(d! n), linear in
// the number of constraints for fixed d, with no setup: for the few dozen faces of a convex piece
// it beats general-purpose LP codes by orders of magnitude. The order comes from a seeded shuffle,
// so results are deterministic; a caller that knows a point near the optimum may instead order
// the constraints by their slack there (`orderHint`), so that the constraints that end up tight
// come first and late violations, which cost a subproblem over all earlier constraints, become
// rare. A violated constraint also moves to the front of its level (move-to-front, which leaves
// the optimum unchanged), and the box rows of a subproblem go last. No allocation per call (a
// workspace the caller owns, LpWorkspace). The two-dimensional level solves its one-dimensional
// subproblems in place.
//
// Robustness. A box lower <= x <= upper keeps every subproblem bounded without special cases.
// Constraints are normalised to unit normals, and the hyperplane substitution pivots on the
// largest coefficient, so substituted coefficients never grow by more than a factor of two per
// level; violations are therefore measured in the original constraints' units at every level. A
// constraint that becomes (numerically) constant in a subproblem, as parallel and coincident
// faces do, is checked as a constant rather than divided by.
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace hcd
{
/// One linear inequality a . x <= b in R^D.
template <int D>
struct Halfspace
{
    Eigen::Matrix<double, D, 1> a = Eigen::Matrix<double, D, 1>::Zero();
    double b = 0.0;
};

/// Scratch memory of the LP solver: row lists that only grow, so that once warm no solve
/// allocates. Owned by the caller (a QueryContext holds one) and used by one solve at a time;
/// the overloads without one make a fresh workspace per call.
class LpWorkspace
{
public:
    LpWorkspace();
    ~LpWorkspace();
    LpWorkspace(LpWorkspace &&) noexcept;
    LpWorkspace &operator=(LpWorkspace &&) noexcept;

    struct Lists;  // defined by the solver
    Lists &lists() { return *lists_; }

private:
    std::unique_ptr<Lists> lists_;
};

/// Whether a small LP has a solution (it is never unbounded: the box bounds every variable).
enum class LpStatus
{
    Optimal,
    Infeasible
};

/// The basis entries that stand for the box: x_j >= lower_j and x_j <= upper_j.
constexpr int lpLowerBoundId(int j) { return -1 - 2 * j; }
constexpr int lpUpperBoundId(int j) { return -2 - 2 * j; }

/// Result of `solveSmallLp`.
template <int D>
struct LpSolution
{
    LpStatus status = LpStatus::Infeasible;
    /// An optimal point (meaningful when `status` is Optimal).
    Eigen::Matrix<double, D, 1> x = Eigen::Matrix<double, D, 1>::Zero();
    /// The D constraints whose hyperplanes meet at `x`: indices into the constraint list, or
    /// lpLowerBoundId(j) / lpUpperBoundId(j) for the box. Their dual multipliers are the LP's.
    std::array<int, D> basis{};
};

/// Maximises objective . x subject to every constraint and lower <= x <= upper, by Seidel's
/// algorithm (expected O(D! n)). Constraints are normalised to unit normals first (constraints
/// with a zero normal are checked as constants); `tolerance` is then an absolute distance: a
/// constraint counts as satisfied when a.x - b <= tolerance, and the LP as infeasible only when
/// no point comes within `tolerance` of every constraint. The caller scales its coordinates to
/// order one so that the tolerance is meaningful. Constraints are taken in a random order
/// (deterministic for a given `seed`) or, when `orderHint` is given, in increasing order of their
/// slack b - a . hint at that point: with a hint near the optimum the constraints that end up
/// tight come first and later ones rarely trigger subproblems (a heuristic: the expected bound
/// is only proven for the random order; ties go by index).
/// Instantiated for D = 1, 2, 3, 4.
template <int D>
LpSolution<D> solveSmallLp(LpWorkspace &workspace, const std::vector<Halfspace<D>> &constraints,
                           const Eigen::Matrix<double, D, 1> &objective, const Eigen::Matrix<double, D, 1> &lower,
                           const Eigen::Matrix<double, D, 1> &upper, double tolerance,
                           const Eigen::Matrix<double, D, 1> *orderHint = nullptr,
                           std::uint64_t seed = 0x2545F4914F6CDD1DULL);

/// solveSmallLp with a workspace of its own (allocates; for one-off solves).
template <int D>
LpSolution<D> solveSmallLp(const std::vector<Halfspace<D>> &constraints, const Eigen::Matrix<double, D, 1> &objective,
                           const Eigen::Matrix<double, D, 1> &lower, const Eigen::Matrix<double, D, 1> &upper,
                           double tolerance, const Eigen::Matrix<double, D, 1> *orderHint = nullptr,
                           std::uint64_t seed = 0x2545F4914F6CDD1DULL)
{
    LpWorkspace workspace;
    return solveSmallLp<D>(workspace, constraints, objective, lower, upper, tolerance, orderHint, seed);
}

#define HYBRIDCD_DECLARE_SMALL_LP(D)                                                                                   \
    extern template LpSolution<D> solveSmallLp<D>(                                                                     \
        LpWorkspace &, const std::vector<Halfspace<D>> &, const Eigen::Matrix<double, D, 1> &,                         \
        const Eigen::Matrix<double, D, 1> &, const Eigen::Matrix<double, D, 1> &, double,                              \
        const Eigen::Matrix<double, D, 1> *, std::uint64_t);
HYBRIDCD_DECLARE_SMALL_LP(1)
HYBRIDCD_DECLARE_SMALL_LP(2)
HYBRIDCD_DECLARE_SMALL_LP(3)
HYBRIDCD_DECLARE_SMALL_LP(4)
#undef HYBRIDCD_DECLARE_SMALL_LP
}  // namespace hcd
