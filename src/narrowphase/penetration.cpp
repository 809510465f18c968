// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/narrowphase/penetration.h"

#include "hybridcd/narrowphase/candidate_axes.h"

#include "hybridcd/narrowphase/linear_program.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace hcd
{
namespace
{
// Seidel's tolerance in the unit working frame, as in `intersectConvexPieces`.
constexpr double kLpTolerance = 1e-12;
// Box on the working coordinates: four times the data's extent, never active at the optimum.
constexpr double kBox = 4.0;
// Upper bound on the working-frame distance moved back: both pieces lie in the unit cube, so a
// translation that keeps them meeting is at most its diagonal, 2 sqrt 3 < 4.
constexpr double kMaxBack = 8.0;

// Minimum over candidate directions of h(n) = max_B n.b - min_A n.a (see the header).
class CandidateSearch
{
public:
    CandidateSearch(const ConvexPiece &a, const ConvexPiece &b) : a_(a), b_(b) {}

    Penetration run()
    {
        forEachCandidateAxis(a_, b_, [this](const Vec3 &axis) { consider(axis); });

        Penetration result;
        const double tolerance =
            kNarrowPhaseRelativeTolerance * std::max(a_.magnitude(), b_.magnitude()) + 1e-300;
        // best_ < 0 means some axis separates the projections, by -best_.
        result.intersecting = best_ >= -tolerance;
        result.direction = bestDirection_;
        result.depth = result.intersecting ? std::max(0.0, best_) : 0.0;
        return result;
    }

private:
    // Both orientations of one axis: A pushed along +n needs hiB - loA, along -n needs hiA - loB.
    void consider(const Vec3 &u)
    {
        const double length = u.norm();
        if (!(length > 0.0) || !std::isfinite(length))
            return;
        const Vec3 n = u / length;
        double loA, hiA, loB, hiB;
        projectOnto(a_.vertices, n, loA, hiA);
        projectOnto(b_.vertices, n, loB, hiB);
        if (hiB - loA < best_)
            best_ = hiB - loA, bestDirection_ = n;
        if (hiA - loB < best_)
            best_ = hiA - loB, bestDirection_ = -n;
    }

    const ConvexPiece &a_, &b_;
    double best_ = std::numeric_limits<double>::infinity();
    Vec3 bestDirection_ = Vec3::UnitX();
};
}  // namespace

Penetration penetrationDepth(const ConvexPiece &a, const ConvexPiece &b)
{
    return CandidateSearch(a, b).run();
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
