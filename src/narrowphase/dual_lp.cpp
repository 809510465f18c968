// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/narrowphase/dual_lp.h"

#include "working_frame.h"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace hcd
{
namespace
{
// The shift y = x' + kShift: every point of either piece has y >= kShift - 1 = 1.
constexpr double kShift = 2.0;
// A reduced cost below -kPriceTolerance may enter; a column entry above kPivotTolerance may pivot.
// The working frame has unit size and unit normals, so costs and entries are of order one.
constexpr double kPriceTolerance = 1e-12;
constexpr double kPivotTolerance = 1e-11;
// Degenerate pivots in a row before Bland's rule takes over.
constexpr int kDegenerateRun = 6;

// The simplex over the workspace's tableau. Columns: faces 0..m-1, surpluses m..m+2, artificials
// m+3..m+5; each column holds its three constraint-row entries and its reduced cost.
struct DualSimplex
{
    enum class Outcome
    {
        Optimal,
        Unbounded,
        Failed,
    };

    int m = 0;
    int columns = 0;
    double *t = nullptr;  // column k at t[4 k .. 4 k + 3]
    double rhs[4] = {0, 0, 0, 0};
    int basis[3] = {0, 0, 0};
    int pivots = 0;
    int entering = -1;  // the unbounded column, when Unbounded

    double &at(int row, int column) { return t[4 * column + row]; }

    void pivot(int row, int column)
    {
        double *const e = t + 4 * column;
        const double f[4] = {e[0], e[1], e[2], e[3]};
        const double inverse = 1.0 / f[row];
        for (int k = 0; k < columns; ++k)
        {
            double *const c = t + 4 * k;
            const double p = c[row] * inverse;
            c[0] -= f[0] * p, c[1] -= f[1] * p, c[2] -= f[2] * p, c[3] -= f[3] * p;
            c[row] = p;
        }
        const double p = rhs[row] * inverse;
        rhs[0] -= f[0] * p, rhs[1] -= f[1] * p, rhs[2] -= f[2] * p, rhs[3] -= f[3] * p;
        rhs[row] = p;
        basis[row] = column;
        ++pivots;
    }

    // Minimises the current reduced-cost row over the columns [0, eligible): Dantzig's rule, then
    // Bland's after a run of degenerate pivots.
    Outcome run(int eligible, int limit)
    {
        bool bland = false;
        int degenerate = 0;
        for (;;)
        {
            if (pivots >= limit)
                return Outcome::Failed;
            int enter = -1;
            double best = -kPriceTolerance;
            for (int k = 0; k < eligible; ++k)
            {
                const double r = t[4 * k + 3];
                if (r < best)
                {
                    enter = k;
                    if (bland)
                        break;
                    best = r;
                }
            }
            if (enter < 0)
                return Outcome::Optimal;
            int leave = -1;
            double ratio = std::numeric_limits<double>::infinity(), pivotSize = 0.0;
            for (int j = 0; j < 3; ++j)
            {
                const double a = at(j, enter);
                if (!(a > kPivotTolerance))
                    continue;
                const double q = std::max(rhs[j], 0.0) / a;
                const bool tie = leave >= 0 && std::fabs(q - ratio) <= 1e-14 * (1.0 + ratio);
                const bool better =
                    leave < 0 || (!tie && q < ratio) || (tie && (bland ? basis[j] < basis[leave] : a > pivotSize));
                if (better)
                    leave = j, ratio = tie ? std::min(q, ratio) : q, pivotSize = a;
            }
            if (leave < 0)
            {
                entering = enter;
                return Outcome::Unbounded;
            }
            degenerate = ratio <= 1e-14 ? degenerate + 1 : 0;
            bland = bland || degenerate >= kDegenerateRun;
            pivot(leave, enter);
        }
    }

    // Sets the reduced-cost row to cost - c_B^T B^-1 A for the given column costs.
    template <typename Cost>
    void price(Cost cost)
    {
        double basicCost[3];
        for (int j = 0; j < 3; ++j)
            basicCost[j] = cost(basis[j]);
        for (int k = 0; k < columns; ++k)
        {
            double *const c = t + 4 * k;
            c[3] = cost(k) - (basicCost[0] * c[0] + basicCost[1] * c[1] + basicCost[2] * c[2]);
        }
        rhs[3] = -(basicCost[0] * rhs[0] + basicCost[1] * rhs[1] + basicCost[2] * rhs[2]);
    }
};

DualLpResult fallBack(const ConvexPiece &a, const ConvexPiece &b, LpWorkspace &slack, int pivots)
{
    const IntersectionResult r = intersectConvexPieces(a, b, slack);
    DualLpResult result;
    result.intersecting = r.intersecting;
    result.witness = r.witness;
    result.separatingNormal = r.separatingNormal;
    result.separatingOffset = r.separatingOffset;
    result.certificate = DualLpResult::Certificate::Fallback;
    result.pivots = pivots;
    return result;
}

// Runs both phases and checks the answer; nullopt when it does not pass (`band` set when it missed
// only within the touching tolerance).
std::optional<DualLpResult> solveAndCheck(const ConvexPiece &a, const ConvexPiece &b, const Frame &frame,
                                          double tolerance, DualSimplex &simplex, const double *normal,
                                          const double *cost, bool phaseOne, int rowsOfA, int limit,
                                          DualLpWorkspace::Counters &counters, bool &band)
{
    const int m = simplex.m;
    if (phaseOne)
    {
        // Phase 1: minimise the sum of the artificials (columns m+3.. cost 1, others 0).
        simplex.price([m](int k) { return k >= m + 3 ? 1.0 : 0.0; });
        const DualSimplex::Outcome first = simplex.run(m + 3, limit);
        counters.phaseOnePivots += std::uint64_t(simplex.pivots);
        if (first != DualSimplex::Outcome::Optimal || -simplex.rhs[3] > 1e-9)
            return std::nullopt;  // cannot happen for bounded pieces but in rounding
        // Drive out artificials left basic at zero.
        for (int j = 0; j < 3; ++j)
        {
            if (simplex.basis[j] < m + 3)
                continue;
            int best = -1;
            for (int k = 0; k < m + 3; ++k)
                if (std::fabs(simplex.at(j, k)) > kPivotTolerance &&
                    (best < 0 || std::fabs(simplex.at(j, k)) > std::fabs(simplex.at(j, best))))
                    best = k;
            if (best < 0)
                return std::nullopt;
            simplex.pivot(j, best);
        }
    }
    // Phase 2: minimise b . lambda over faces and surpluses (artificials never enter again).
    simplex.price([m, cost](int k) { return k < m ? cost[k] : 0.0; });
    const DualSimplex::Outcome outcome = simplex.run(m + 3, limit);

    DualLpResult result;
    result.pivots = simplex.pivots;
    if (outcome == DualSimplex::Outcome::Optimal)
    {
        // The primal point where the basis' constraints are tight: n_i . y = b_i for a basic
        // face, y_j = 0 for a basic surplus (which then fails the check below).
        Eigen::Matrix3d rows;
        Vec3 rhs;
        for (int j = 0; j < 3; ++j)
        {
            const int k = simplex.basis[j];
            if (k >= m + 3)
                return std::nullopt;
            if (k < m)
            {
                rows.row(j) << normal[3 * k], normal[3 * k + 1], normal[3 * k + 2];
                rhs[j] = cost[k];
            }
            else
            {
                rows.row(j) = Vec3::Unit(k - m).transpose();
                rhs[j] = 0.0;
            }
        }
        const Eigen::FullPivLU<Eigen::Matrix3d> lu(rows);
        if (!lu.isInvertible())
            return std::nullopt;
        const Vec3 y = lu.solve(rhs);
        result.witness = frame.center + frame.scale * (y - Vec3::Constant(kShift));
        const double violation = std::max(a.maxViolation(result.witness), b.maxViolation(result.witness));
        if (violation <= kRoundingFraction * tolerance)
        {
            result.intersecting = true;
            result.certificate = DualLpResult::Certificate::Witness;
            return result;
        }
        band = violation <= tolerance;
        return std::nullopt;
    }
    if (outcome == DualSimplex::Outcome::Unbounded)
    {
        // The ray: the entering column at rate 1, the basic variables at rate -t_jk. Its A part,
        // the sum over A's faces of mu_i n_i, is the separating direction.
        const int enter = simplex.entering;
        Vec3 w = Vec3::Zero();
        const auto addFace = [&](int i, double mu) {
            if (i < rowsOfA && mu > 0.0)
                w += mu * Vec3(normal[3 * i], normal[3 * i + 1], normal[3 * i + 2]);
        };
        addFace(enter, 1.0);
        for (int j = 0; j < 3; ++j)
            if (simplex.basis[j] < m)
                addFace(simplex.basis[j], -simplex.at(j, enter));
        double gap;
        if (separateAlong(w, a, b, tolerance, result.separatingNormal, result.separatingOffset, &gap))
        {
            result.intersecting = false;
            result.certificate = DualLpResult::Certificate::FarkasPlane;
            return result;
        }
        band = gap > 0.0;
        return std::nullopt;
    }
    return std::nullopt;
}
}  // namespace

DualLpResult intersectConvexPiecesDual(const ConvexPiece &a, const ConvexPiece &b, DualLpWorkspace &workspace,
                                       const Vec3 &objective)
{
    DualLpWorkspace::Counters &counters = workspace.counters_;
    ++counters.solves;
    double tolerance;
    const Frame frame = workingFrame(a, b, &tolerance);

    // Rows of both pieces in the shifted working frame: unit n_i and b_i = d'_i + kShift sum(n_i).
    const std::size_t faces = a.normals.size() + b.normals.size();
    if (workspace.cost.size() < faces)
    {
        workspace.cost.resize(faces);
        workspace.normal.resize(3 * faces);
    }
    if (workspace.tableau.size() < 4 * (faces + 6))
        workspace.tableau.resize(4 * (faces + 6));
    int m = 0;
    const auto emit = [&](const Vec3 &n, double d) {
        workspace.normal[3 * std::size_t(m)] = n[0];
        workspace.normal[3 * std::size_t(m) + 1] = n[1];
        workspace.normal[3 * std::size_t(m) + 2] = n[2];
        workspace.cost[std::size_t(m)] = d + kShift * (n[0] + n[1] + n[2]);
        ++m;
    };
    forEachScaledPlane(a, frame, emit);
    const int rowsOfA = m;
    forEachScaledPlane(b, frame, emit);
    const double *const normal = workspace.normal.data();

    // The tableau: row j is sum_i n_ij lambda_i - s_j (+ r_j) = c_j, negated where c_j <= 0 so
    // that the surplus starts basic at -c_j >= 0; where c_j > 0 the artificial r_j starts basic.
    DualSimplex simplex;
    simplex.m = m;
    simplex.columns = m + 6;
    simplex.t = workspace.tableau.data();
    std::fill(simplex.t, simplex.t + 4 * (m + 6), 0.0);
    bool phaseOne = false;
    for (int j = 0; j < 3; ++j)
    {
        const double sign = objective[j] > 0.0 ? 1.0 : -1.0;
        for (int i = 0; i < m; ++i)
            simplex.at(j, i) = sign * normal[3 * i + j];
        simplex.at(j, m + j) = -sign;  // surplus
        simplex.rhs[j] = sign * objective[j];
        if (objective[j] > 0.0)
        {
            simplex.at(j, m + 3 + j) = 1.0;  // artificial
            simplex.basis[j] = m + 3 + j;
            phaseOne = true;
        }
        else
            simplex.basis[j] = m + j;
    }
    // Pivot limit: far above what a solve takes, so only a numerical stall reaches it.
    const int limit = 50 + 4 * (m + 6);
    bool band = false;
    const std::optional<DualLpResult> answer = solveAndCheck(
        a, b, frame, tolerance, simplex, normal, workspace.cost.data(), phaseOne, rowsOfA, limit, counters, band);
    counters.pivots += std::uint64_t(simplex.pivots);
    if (answer)
        return *answer;
    ++counters.fallbacks;
    counters.bandFallbacks += band;
    return fallBack(a, b, workspace.slack, simplex.pivots);
}
}  // namespace hcd
