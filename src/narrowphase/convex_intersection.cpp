// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/narrowphase/linear_program.h"

#include "axis_search.h"
#include "small_lp_rows.h"
#include "working_frame.h"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>

namespace hcd
{
namespace
{
// Bounds on the slack: above the largest inscribed radius (sqrt 3), below the smallest slack
// anywhere in the box (-(sqrt 3 + 4 sqrt 3)), so neither is active at the optimum.
constexpr double kSlackHigh = 4.0, kSlackLow = -16.0;

// Writes rows[0..n) to `sorted` in increasing order of b (the slack at the origin with t = 0)
// up to buckets: a stable counting sort into n equal buckets between the smallest and largest b.
// It orders the rows as well as a full sort does for Seidel's purposes (the same number of
// subproblem rows within a few percent) at a fraction of the cost, and without a branch.
// `counts` has room for 2 n + 1 entries.
void orderBySlack(const small_lp::Row<4> *rows, int n, small_lp::Row<4> *sorted, std::vector<int> &counts)
{
    if (n == 0)
        return;
    double lo = rows[0].b, hi = rows[0].b;
    for (int i = 1; i < n; ++i)
        lo = std::min(lo, rows[i].b), hi = std::max(hi, rows[i].b);
    const double scale = hi > lo ? double(n) / (hi - lo) : 0.0;
    const double last = double(n - 1);
    int *const count = counts.data();             // n + 1 entries
    int *const bucketOf = counts.data() + n + 1;  // n entries
    std::fill(count, count + n + 1, 0);
    for (int i = 0; i < n; ++i)
    {
        const double v = (rows[i].b - lo) * scale;
        const int bucket = int(std::min(v >= 0.0 ? v : 0.0, last));  // NaN goes first
        bucketOf[i] = bucket;
        ++count[bucket + 1];
    }
    for (int k = 0; k < n; ++k)
        count[k + 1] += count[k];
    for (int i = 0; i < n; ++i)
        sorted[count[bucketOf[i]]++] = rows[i];
}
}  // namespace

IntersectionResult intersectConvexPieces(const ConvexPiece &a, const ConvexPiece &b, LpWorkspace &workspace)
{
    double tolerance;
    const Frame frame = workingFrame(a, b, &tolerance);

    // Rows in the working frame: (n, 1) . (x', t') <= d', A's first, each scaled to a unit
    // normal as solveSmallLp does. The rows are staged by id behind the sorted copy the solver
    // permutes, so that the dual can look up its basis rows.
    small_lp::Workspace &ws = workspace.lists();
    const std::size_t faces = a.normals.size() + b.normals.size();
    if (ws.rows4.size() < 2 * faces)
        ws.rows4.resize(2 * faces);
    if (ws.counts.size() < 2 * faces + 1)
        ws.counts.resize(2 * faces + 1);
    small_lp::Row<4> *const staged = ws.rows4.data() + faces;  // the rows by id; sorted into the front
    int n = 0;
    const auto emit = [&](const Vec3 &unit, double d) {
        // (unit, 1) has length sqrt 2 up to rounding.
        constexpr double kInverseLength = 0.70710678118654752440;
        small_lp::Row<4> &r = staged[n];
        r.a[0] = unit[0] * kInverseLength, r.a[1] = unit[1] * kInverseLength, r.a[2] = unit[2] * kInverseLength;
        r.a[3] = kInverseLength;
        r.b = d * kInverseLength;
        r.id = n;
        ++n;
    };
    forEachScaledPlane(a, frame, emit);
    const int rowsOfA = n;
    forEachScaledPlane(b, frame, emit);
    orderBySlack(staged, n, ws.rows4.data(), ws.counts);

    const double objective[4] = {0.0, 0.0, 0.0, 1.0};
    const double lower[4] = {-kBox, -kBox, -kBox, kSlackLow}, upper[4] = {kBox, kBox, kBox, kSlackHigh};
    struct
    {
        LpStatus status = LpStatus::Infeasible;
        double x[4];
        int basis[4];
    } lp;
    if (small_lp::solveRows<4>(ws, n, objective, lower, upper, kLpTolerance, lp.x, lp.basis))
        lp.status = LpStatus::Optimal;

    IntersectionResult result;
    if (lp.status == LpStatus::Optimal)
    {
        result.witness = frame.center + frame.scale * Vec3(lp.x[0], lp.x[1], lp.x[2]);
        result.depth = -std::max(a.maxViolation(result.witness), b.maxViolation(result.witness));
        // Within rounding: answered without the separating-axis search of the band below. A sharp
        // vertex (angle above 2e-4 rad) within the band is within the tolerance of touching.
        if (result.depth >= -kRoundingFraction * tolerance)
        {
            result.intersecting = true;
            result.certificate = IntersectionResult::Certificate::Witness;
            return result;
        }
        // Dual certificate: sum lambda_j (n_j, 1) = (0, 0, 0, 1) over the basis; the A part of
        // sum lambda_j n_j separates (see the header).
        const bool clearlyApart = result.depth < -tolerance;
        if (std::all_of(lp.basis, lp.basis + 4, [](int id) { return id >= 0; }))
        {
            Eigen::Matrix4d columns;
            for (int j = 0; j < 4; ++j)
            {
                // (n_j, 1) / sqrt 2: a common scale of the columns only scales lambda.
                const small_lp::Row<4> &r = staged[lp.basis[j]];
                columns.col(j) << r.a[0], r.a[1], r.a[2], r.a[3];
            }
            const Eigen::Vector4d lambda = columns.fullPivLu().solve(Eigen::Vector4d::UnitW());
            Vec3 direction = Vec3::Zero();
            for (int j = 0; j < 4; ++j)
                direction += (lp.basis[j] < rowsOfA ? 1.0 : -1.0) * lambda[j] * columns.col(j).head<3>();
            if (lambda.allFinite() && separateAlong(direction, a, b, clearlyApart ? 0.0 : tolerance,
                                                    result.separatingNormal, result.separatingOffset))
            {
                result.certificate = IntersectionResult::Certificate::LpDual;
                return result;
            }
        }
        if (!clearlyApart)
        {
            // The witness violates some inequality, but by no more than the tolerance. Near a
            // sharp edge or vertex that violation can be far smaller than the distance, so the
            // pieces count as touching only if no axis separates them by more than the tolerance
            // either (the reference test's criterion). Rare, so the axis search's cost is too.
            Vec3 axis;
            if (AxisSearch(a, b, tolerance).run(&axis) > tolerance &&
                separateAlong(axis, a, b, tolerance, result.separatingNormal, result.separatingOffset))
            {
                result.certificate = IntersectionResult::Certificate::AxisSearch;
                return result;
            }
            result.intersecting = true;
            result.certificate = IntersectionResult::Certificate::Witness;
            return result;
        }
    }
    Vec3 axis;
    if (separatingAxisGap(a, b, &axis) > 0.0 &&
        separateAlong(axis, a, b, 0.0, result.separatingNormal, result.separatingOffset))
    {
        result.certificate = IntersectionResult::Certificate::AxisSearch;
        return result;
    }
    result.intersecting = true;
    result.certificate = IntersectionResult::Certificate::Conservative;
    if (lp.status != LpStatus::Optimal)
        result.witness = frame.center;
    return result;
}

bool convexPiecesIntersectPrimal(const ConvexPiece &a, const ConvexPiece &b, LpWorkspace &workspace)
{
    const Frame frame = workingFrame(a, b);
    std::vector<Halfspace<3>> &rows = workspace.lists().primalRows;
    rows.clear();
    const auto emit = [&](const Vec3 &n, double d) { rows.push_back({n, d}); };
    forEachScaledPlane(a, frame, emit);
    forEachScaledPlane(b, frame, emit);
    const LpSolution<3> lp = solveSmallLp<3>(workspace, rows, Vec3::Ones(), Vec3::Constant(-kBox), Vec3::Constant(kBox),
                                             pairTolerance(a, b) / frame.scale);
    return lp.status == LpStatus::Optimal;
}

void appendWorkingFrameRows(std::vector<Halfspace<4>> &rows, const ConvexPiece &piece, const Vec3 &center, double scale,
                            const Vec3 &motion)
{
    for (std::size_t i = 0; i < piece.normals.size(); ++i)
    {
        const double norm = piece.normals[i].norm();
        if (!(norm > 0.0))
            continue;
        const Vec3 n = piece.normals[i] / norm;
        Halfspace<4> h;
        h.a << n, n.dot(motion);
        h.b = (piece.offsets[i] / norm - n.dot(center)) / scale;
        rows.push_back(h);
    }
}
}  // namespace hcd
