// SPDX-License-Identifier: BSD-3-Clause
// The search over the candidate axes (candidate_axes.h) behind the separating-axis test, the LP
// narrow phase's fallback certificate and the penetration depth. All three want the same number:
// the largest gap between the pieces' vertex projections, with its axis. The penetration depth is
// minus that gap, and its direction (the push on A that separates the pieces) minus that axis.
#pragma once

#include "hybridcd/narrowphase/candidate_axes.h"

#include <cmath>
#include <limits>

namespace hcd
{
// Largest gap over the candidate axes, the axis oriented so that A projects below B, stopping
// early once some axis gives a gap above `stopAbove`.
class AxisSearch
{
public:
    // Which orientation wins when an axis gives both the same gap (pieces whose projections share
    // a midpoint, such as concentric ones). Separation has always kept +n, the penetration depth
    // -n (its direction +n); each keeps its own so that neither answer changes.
    enum class Ties
    {
        Positive,
        Negative
    };

    AxisSearch(const ConvexPiece &a, const ConvexPiece &b, double stopAbove = std::numeric_limits<double>::infinity(),
               Ties ties = Ties::Positive)
        : a_(a),
          b_(b),
          stopAbove_(stopAbove),
          ties_(ties)
    {
    }

    // The largest gap (-inf when no axis is usable, and then `axis` is +x).
    double run(Vec3 *axis)
    {
        forEachCandidateAxis(a_, b_, [this](const Vec3 &u) { consider(u); });
        if (axis)
            *axis = bestAxis_;
        return best_;
    }

private:
    void consider(const Vec3 &u)
    {
        if (best_ > stopAbove_)
            return;
        const double length = u.norm();
        if (!(length > 0.0) || !std::isfinite(length))
            return;
        const Vec3 n = u / length;
        double loA, hiA, loB, hiB;
        projectOnto(a_.vertices, n, loA, hiA);
        projectOnto(b_.vertices, n, loB, hiB);
        // The gaps with A below B along n and along -n.
        const double above = loB - hiA, below = loA - hiB;
        if (ties_ == Ties::Negative)
        {
            // Each orientation on its own, -n first (the order the penetration depth always
            // took): a gap that is NaN is skipped rather than hiding the other.
            if (below > best_)
                best_ = below, bestAxis_ = -n;
            if (above > best_)
                best_ = above, bestAxis_ = n;
        }
        else if (above >= below)
        {
            if (above > best_)
                best_ = above, bestAxis_ = n;
        }
        else if (below > best_)
            best_ = below, bestAxis_ = -n;
    }

    const ConvexPiece &a_, &b_;
    double stopAbove_;
    Ties ties_;
    double best_ = -std::numeric_limits<double>::infinity();
    Vec3 bestAxis_ = Vec3::UnitX();
};
}  // namespace hcd
