// SPDX-License-Identifier: BSD-3-Clause
// Orientation predicates with exact signs for double-precision input.
//
// Each predicate first evaluates the determinant in floating point together with a forward
// error bound (Shewchuk's static filter). When the magnitude of the result exceeds the bound,
// its sign is certain. Otherwise -- near-degenerate input, or magnitudes so huge or tiny that
// the bound itself overflows or underflows -- the determinant is recomputed in exact rational
// arithmetic. The exact path is rare on generic input and makes touching, coplanar and
// collinear configurations decide the same way every time.
#pragma once

#include "hybridcd/geometry/rigid_transform.h"

namespace hcd
{
/// Sign (-1, 0, +1) of det[b-a, c-a, d-a]: positive when d lies on the side of the plane
/// through a, b, c that its normal (b-a) x (c-a) points to.
int orient3d(const Vec3 &a, const Vec3 &b, const Vec3 &c, const Vec3 &d);

/// orient3d()'s floating-point filter for many points against one plane: the normal
/// (b - a) x (c - a) is computed once, then each point costs one dot product and its error bound.
/// side() is +1 or -1 when that certifies orient3d(a, b, c, d)'s sign, and 0 when it does not (near
/// the plane, or magnitudes where the bound may under- or overflow): orient3d() decides those.
class PlaneOrientationFilter
{
public:
    PlaneOrientationFilter(const Vec3 &a, const Vec3 &b, const Vec3 &c);

    /// The certified sign, or 0. `offset` receives n . (d - a) and `bound` its error bound (only
    /// meaningful when the sign is certified). Inline: the triangle tests call it in their inner loops.
    int side(const Vec3 &d, double *offset = nullptr, double *bound = nullptr) const
    {
        // det[b-a, c-a, d-a] = ((b-a) x (c-a)) . (d-a): orient3d()'s expansion along its third column.
        const Vec3 e = d - origin_;
        const double det = normal_.dot(e);
        const double permanent = magnitude_.dot(e.cwiseAbs());
        const double errorBound = kRelativeError * permanent;
        if (offset)
            *offset = det;
        if (bound)
            *bound = errorBound;
        if (!usable_ || !(permanent > kTinyPermanent) || !(permanent < kHugePermanent))
            return 0;
        return det > errorBound ? 1 : det < -errorBound ? -1 : 0;
    }

    const Vec3 &normal() const { return normal_; }
    /// The sums of the absolute products making up each component of normal(): each component of
    /// the exact normal lies within kRelativeError times its entry of the computed one.
    const Vec3 &normalMagnitude() const { return magnitude_; }
    /// The filter's relative error bound (Shewchuk's for orient3d, rounded up), and the range of
    /// permanents within which it holds (below, products may be subnormal; above, overflow).
    static constexpr double kRelativeError = 1.0e-15;
    static constexpr double kTinyPermanent = 1.0e-250;
    static constexpr double kHugePermanent = 1.0e300;

private:
    Vec3 origin_, normal_, magnitude_;
    bool usable_ = false;  ///< no product of the normal can have lost its relative accuracy, all finite
};

/// Sign (-1, 0, +1) of the 2D determinant det[b-a, c-a] for points (x, y): positive when a, b, c
/// turn counter-clockwise.
int orient2d(double ax, double ay, double bx, double by, double cx, double cy);

/// How often the exact fallback has run in this process, all threads together (for tests and
/// benchmarks: compare two readings taken around single-threaded work).
unsigned long long exactPredicateFallbacks();
}  // namespace hcd
