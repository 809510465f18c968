// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/narrowphase/penetration.h"

#include "hybridcd/narrowphase/linear_program.h"

#include "axis_search.h"
#include "working_frame.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace hcd
{
namespace
{
// Upper bound on the working-frame distance moved back: both pieces lie in the unit cube, so a
// translation that keeps them meeting is at most its diagonal, 2 sqrt 3 < 4.
constexpr double kMaxBack = 8.0;
}  // namespace

Penetration penetrationDepth(const ConvexPiece &a, const ConvexPiece &b)
{
    // h(n) = max_B n.b - min_A n.a (see the header) is minus the gap between the projections
    // along -n, so the smallest push is minus the largest gap, along minus its axis.
    constexpr double kNoStop = std::numeric_limits<double>::infinity();
    Vec3 axis;
    const double gap = AxisSearch(a, b, kNoStop, AxisSearch::Ties::Negative).run(&axis);
    const double push = -gap;
    Penetration result;
    // push < 0 means some axis separates the projections, by -push.
    result.intersecting = push >= -pairTolerance(a, b);
    result.direction = gap > -std::numeric_limits<double>::infinity() ? Vec3(-axis) : Vec3::UnitX();
    result.depth = result.intersecting ? std::max(0.0, push) : 0.0;
    return result;
}

double directionalPenetration(const ConvexPiece &a, const Vec3 &motion, const ConvexPiece &b)
{
    const double length = motion.norm();
    if (!(length > 0.0) || !std::isfinite(length))
        throw std::invalid_argument("directionalPenetration: motion must be finite and non-zero");
    // The LP below finds the largest s of the interval of s for which A - s m meets B; it is the
    // answer only when that interval contains 0, i.e. when the pieces intersect now.
    if (!intersectConvexPieces(a, b).intersecting)
        return 0.0;
    const Vec3 m = motion / length;

    // Working frame x = center + scale * x' with every vertex of both pieces in |x'_i| <= 1.
    const Vec3 center = 0.5 * (a.centroid + b.centroid);
    double scale = 0.0;
    for (const ConvexPiece *p : {&a, &b})
        for (const Vec3 &v : p->vertices)
            scale = std::max(scale, (v - center).cwiseAbs().maxCoeff());
    if (!(scale > 0.0))  // both pieces one and the same point: nothing to move back
        return 0.0;

    // x' in B, x' + s' m in A (s' = s / scale): B's rows (n, 0), A's rows (n, n . m).
    std::vector<Halfspace<4>> rows;  // not on a hot path: a list per call
    appendWorkingFrameRows(rows, b, center, scale, Vec3::Zero());
    appendWorkingFrameRows(rows, a, center, scale, m);

    const Eigen::Vector4d objective(0.0, 0.0, 0.0, 1.0);
    const Eigen::Vector4d lower(-kBox, -kBox, -kBox, 0.0), upper(kBox, kBox, kBox, kMaxBack);
    const LpSolution<4> lp = solveSmallLp<4>(rows, objective, lower, upper, kLpTolerance);
    // Infeasible at s = 0 although the narrow phase says intersecting: touching within its
    // tolerance, so there is nothing to move back.
    if (lp.status != LpStatus::Optimal)
        return 0.0;
    return std::max(0.0, lp.x[3]) * scale;
}
}  // namespace hcd
