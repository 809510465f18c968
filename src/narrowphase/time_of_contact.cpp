// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/narrowphase/time_of_contact.h"

#include "hybridcd/narrowphase/linear_program.h"

#include "working_frame.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace hcd
{
TimeOfContact translationalTimeOfContact(const ConvexPiece &moving, const Vec3 &displacement, const ConvexPiece &fixed)
{
    if (!displacement.allFinite())
        throw std::invalid_argument("translationalTimeOfContact: non-finite displacement");

    // Working frame x = center + scale * x': every vertex of the fixed piece and of the moving
    // piece at both ends of the step lies in |x'_i| <= 1 (so do the whole sweep and the witness).
    const Vec3 center = 0.5 * (fixed.centroid + moving.centroid + 0.5 * displacement);
    double scale = 0.0;
    for (const Vec3 &v : fixed.vertices)
        scale = std::max(scale, (v - center).cwiseAbs().maxCoeff());
    for (const Vec3 &v : moving.vertices)
        scale =
            std::max({scale, (v - center).cwiseAbs().maxCoeff(), (v + displacement - center).cwiseAbs().maxCoeff()});
    if (!(scale > 0.0))  // both pieces the same single point, not moving
        scale = std::max(1.0, std::max(moving.magnitude(), fixed.magnitude()));

    // Time as distance travelled in the working frame, u = t * travel, so that the moving rows
    // (n, -n . direction) have coefficients of order one whatever the speed.
    const double length = displacement.norm();
    const double travel = length / scale;
    const Vec3 direction = length > 0.0 ? Vec3(displacement / length) : Vec3::Zero();

    std::vector<Halfspace<4>> rows;  // not on a hot path: a list per call
    appendWorkingFrameRows(rows, fixed, center, scale, Vec3::Zero());
    appendWorkingFrameRows(rows, moving, center, scale, -direction);

    // Minimise u, i.e. maximise -u.
    const Eigen::Vector4d objective(0.0, 0.0, 0.0, -1.0);
    const Eigen::Vector4d lower(-kBox, -kBox, -kBox, 0.0), upper(kBox, kBox, kBox, travel);
    const LpSolution<4> lp = solveSmallLp<4>(rows, objective, lower, upper, kLpTolerance);

    TimeOfContact result;
    if (lp.status != LpStatus::Optimal)
        return result;
    result.contact = true;
    result.time = travel > 0.0 ? std::clamp(lp.x[3] / travel, 0.0, 1.0) : 0.0;
    result.point = center + scale * lp.x.head<3>();
    return result;
}
}  // namespace hcd
