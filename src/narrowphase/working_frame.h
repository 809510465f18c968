// SPDX-License-Identifier: BSD-3-Clause
// The working frame of a pair of convex pieces, in which the narrow phase's LPs are posed: the
// data translated to the pieces' mid-centroid and scaled to unit size, so that one absolute
// tolerance means the same at every scale.
#pragma once

#include "hybridcd/narrowphase/convex_piece.h"
#include "hybridcd/narrowphase/separating_axes.h"

#include <algorithm>

namespace hcd
{
// The pair's scale for tolerances: the largest absolute vertex coordinate.
inline double pairTolerance(const ConvexPiece &a, const ConvexPiece &b)
{
    return kNarrowPhaseRelativeTolerance * std::max(a.magnitude(), b.magnitude()) + 1e-300;
}

// Working frame: x = center + scale * x', with every vertex in |x'_i| <= 1.
struct Frame
{
    Vec3 center;
    double scale;
};

// The working frame and, in the same pass over the vertices, `pairTolerance`.
inline Frame workingFrame(const ConvexPiece &a, const ConvexPiece &b, double *tolerance = nullptr)
{
    Frame f{0.5 * (a.centroid + b.centroid), 0.0};
    Vec3 extent = Vec3::Zero(), magnitude = Vec3::Zero();
    for (const ConvexPiece *p : {&a, &b})
        for (const Vec3 &v : p->vertices)
        {
            extent = extent.cwiseMax((v - f.center).cwiseAbs());
            magnitude = magnitude.cwiseMax(v.cwiseAbs());
        }
    f.scale = extent.maxCoeff();
    const double largest = magnitude.maxCoeff();  // max(a.magnitude(), b.magnitude())
    if (!(f.scale > 0.0))                         // both pieces one and the same point
        f.scale = std::max(1.0, largest);
    if (tolerance)
        *tolerance = kNarrowPhaseRelativeTolerance * largest + 1e-300;
    return f;
}

// n . x <= d in working coordinates, with n made unit: n . x' <= (d - n . center) / scale.
template <typename Emit>
void forEachScaledPlane(const ConvexPiece &p, const Frame &f, Emit emit)
{
    const double inverseScale = 1.0 / f.scale;
    for (std::size_t i = 0; i < p.normals.size(); ++i)
    {
        const double length = p.normals[i].norm();
        if (!(length > 0.0))
            continue;
        // Multiplying by the inverse (the normals are unit, so it is one up to rounding) is
        // several times cheaper than dividing; a length so small that the inverse overflows
        // divides instead.
        const double inverse = 1.0 / length;
        if (inverse <= 1e300)
        {
            const Vec3 n = p.normals[i] * inverse;
            emit(n, (p.offsets[i] * inverse - n.dot(f.center)) * inverseScale);
        }
        else
        {
            const Vec3 n = p.normals[i] / length;
            emit(n, (p.offsets[i] / length - n.dot(f.center)) / f.scale);
        }
    }
}

// Box of the working frame: four times the data's extent, so never active where it matters.
constexpr double kBox = 4.0;
// Seidel's tolerance in the working frame (unit size): far above rounding, far below the
// narrow phase's 1e-9.
constexpr double kLpTolerance = 1e-12;
// A witness violating a constraint by less than this fraction of the tolerance (1e-13 relative)
// is rounding: exactly touching pieces land there.
constexpr double kRoundingFraction = 1e-4;
}  // namespace hcd
