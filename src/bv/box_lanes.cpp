// SPDX-License-Identifier: BSD-3-Clause
// One box against four (box_lanes.h), compiled by Google Highway for each x86 instruction set it
// targets (its portable path, SSSE3, SSE4, AVX2, AVX-512) and dispatched at run time to the widest
// the machine has.
#include "hybridcd/bv/box_lanes.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "src/bv/box_lanes.cpp"
#include "hwy/foreach_target.h"  // re-includes this file once per instruction set
#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace hcd
{
namespace HWY_NAMESPACE
{
namespace hn = hwy::HWY_NAMESPACE;
using D = hn::CappedTag<double, 4>;
using V = hn::Vec<D>;
using M = hn::Mask<D>;

// Whether the spheres about the centres (offset `gap` = a's centre minus the lane's) are farther
// apart than the radii and the tolerance: the traversal's first test.
HWY_INLINE M SpheresApart(D d, const V gap[3], double aRadius, const double *radius, V tol)
{
    const V reach = hn::Add(hn::Add(hn::Set(d, aRadius), hn::LoadU(d, radius)), tol);
    const V squared = hn::Add(hn::Add(hn::Mul(gap[0], gap[0]), hn::Mul(gap[1], gap[1])), hn::Mul(gap[2], gap[2]));
    return hn::Gt(squared, hn::Mul(reach, reach));
}

// Number f of the lanes from `base` on.
HWY_INLINE V Field(D d, const ObbLanes &lanes, int f, std::size_t base) { return hn::LoadU(d, lanes.field[f] + base); }

// Lanes [base, base + Lanes(d)) as bits at their own positions.
HWY_INLINE unsigned BitsAt(D d, M m, std::size_t base)
{
    std::uint8_t bits[8] = {};
    hn::StoreMaskBits(d, m, bits);
    return unsigned(bits[0]) << base;
}

// Box `a` in the frame of each lane's box, from lane `base` on: the centres' offset (world frame),
// t = B^T (ca - cb), R = B^T A, and both boxes' half extents.
struct LaneFrame
{
    V gap[3], t[3], r[3][3], ea[3], eb[3];

    HWY_INLINE LaneFrame(D d, const ObbLanes &lanes, const Obb &a, std::size_t base)
    {
        for (int c = 0; c < 3; ++c)
            gap[c] = hn::Sub(hn::Set(d, a.center[c]), Field(d, lanes, ObbLanes::kCenter + c, base));
        for (int i = 0; i < 3; ++i)
        {
            const V b0 = Field(d, lanes, ObbLanes::kAxes + i, base),
                    b1 = Field(d, lanes, ObbLanes::kAxes + 3 + i, base),
                    b2 = Field(d, lanes, ObbLanes::kAxes + 6 + i, base);  // rows of the lane box's axis i
            t[i] = hn::Add(hn::Add(hn::Mul(b0, gap[0]), hn::Mul(b1, gap[1])), hn::Mul(b2, gap[2]));
            for (int j = 0; j < 3; ++j)
                r[i][j] = hn::Add(hn::Add(hn::Mul(b0, hn::Set(d, a.axes(0, j))), hn::Mul(b1, hn::Set(d, a.axes(1, j)))),
                                  hn::Mul(b2, hn::Set(d, a.axes(2, j))));
            ea[i] = hn::Set(d, a.halfExtents[i]);
            eb[i] = Field(d, lanes, ObbLanes::kHalfExtents + i, base);
        }
    }
};

// obbsOverlap's separating-axis test lane by lane, in the same order with the same arithmetic (no
// fused multiply-adds), in the lane box's frame: R = B^T A, t = B^T (ca - cb).
unsigned SeparatedObbLanes(const ObbLanes &lanes, const Obb &a, double aRadius, double tolerance)
{
    const D d;
    const V tol = hn::Set(d, tolerance);
    const V epsilon = hn::Set(d, 1e-12);
    unsigned separated = 0;
    for (std::size_t base = 0; base < std::size_t(ObbLanes::kLanes); base += hn::Lanes(d))
    {
        const LaneFrame f(d, lanes, a, base);
        const V(&gap)[3] = f.gap;
        const V(&t)[3] = f.t;
        const V(&r)[3][3] = f.r;
        const V(&ea)[3] = f.ea;
        const V(&eb)[3] = f.eb;
        M out = SpheresApart(d, gap, aRadius, lanes.radius + base, tol);
        V absR[3][3];
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                absR[i][j] = hn::Add(hn::Abs(r[i][j]), epsilon);
        // The lane box's face axes.
        for (int i = 0; i < 3; ++i)
        {
            const V ra =
                hn::Add(hn::Add(hn::Mul(absR[i][0], ea[0]), hn::Mul(absR[i][1], ea[1])), hn::Mul(absR[i][2], ea[2]));
            out = hn::Or(out, hn::Gt(hn::Abs(t[i]), hn::Add(hn::Add(eb[i], ra), tol)));
        }
        // a's face axes, then the cross products of the lane box's axis i with a's axis j, while
        // some lane is still not separated.
        for (int j = 0; j < 3 && !hn::AllTrue(d, out); ++j)
        {
            const V along = hn::Add(hn::Add(hn::Mul(t[0], r[0][j]), hn::Mul(t[1], r[1][j])), hn::Mul(t[2], r[2][j]));
            const V rb =
                hn::Add(hn::Add(hn::Mul(absR[0][j], eb[0]), hn::Mul(absR[1][j], eb[1])), hn::Mul(absR[2][j], eb[2]));
            out = hn::Or(out, hn::Gt(hn::Abs(along), hn::Add(hn::Add(ea[j], rb), tol)));
        }
        for (int i = 0; i < 3 && !hn::AllTrue(d, out); ++i)
        {
            const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
            for (int j = 0; j < 3; ++j)
            {
                const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
                const V ra = hn::Add(hn::Mul(ea[j1], absR[i][j2]), hn::Mul(ea[j2], absR[i][j1]));
                const V rb = hn::Add(hn::Mul(eb[i1], absR[i2][j]), hn::Mul(eb[i2], absR[i1][j]));
                const V along = hn::Sub(hn::Mul(t[i2], r[i1][j]), hn::Mul(t[i1], r[i2][j]));
                out = hn::Or(out, hn::Gt(hn::Abs(along), hn::Add(hn::Add(ra, rb), tol)));
            }
        }
        separated |= BitsAt(d, out, base);
    }
    return separated;
}

// aabbsOverlap's test lane by lane: |ca - cb| > ha + hb + tolerance along some world axis.
unsigned SeparatedAabbLanes(const AabbLanes &lanes, const Aabb &a, double aRadius, double tolerance)
{
    const D d;
    const V tol = hn::Set(d, tolerance);
    unsigned separated = 0;
    for (std::size_t base = 0; base < std::size_t(AabbLanes::kLanes); base += hn::Lanes(d))
    {
        V gap[3];
        for (int c = 0; c < 3; ++c)
            gap[c] = hn::Sub(hn::Set(d, a.center[c]), hn::LoadU(d, lanes.field[AabbLanes::kCenter + c] + base));
        M out = SpheresApart(d, gap, aRadius, lanes.radius + base, tol);
        for (int c = 0; c < 3; ++c)
        {
            const V extents =
                hn::Add(hn::Set(d, a.halfExtents[c]), hn::LoadU(d, lanes.field[AabbLanes::kHalfExtents + c] + base));
            out = hn::Or(out, hn::Gt(hn::Abs(gap[c]), hn::Add(extents, tol)));
        }
        separated |= BitsAt(d, out, base);
    }
    return separated;
}

// The sphere gap |ca - cb| - (aRadius + radius) - tolerance per lane, as the distance search
// computes it.
HWY_INLINE V SphereGap(D d, const V gap[3], double aRadius, const double *radius, V tol)
{
    const V reach = hn::Add(hn::Add(hn::Set(d, aRadius), hn::LoadU(d, radius)), tol);
    const V squared = hn::Add(hn::Add(hn::Mul(gap[0], gap[0]), hn::Mul(gap[1], gap[1])), hn::Mul(gap[2], gap[2]));
    return hn::Sub(hn::Sqrt(squared), reach);
}

// obbDistanceLowerBound(a, lane box, tolerance) with all its stages, lane by lane, in the same
// order with the same arithmetic, and the sphere gap: the larger of the two.
void ObbLanesDistance(const ObbLanes &lanes, const Obb &a, double aRadius, double tolerance, double *bound)
{
    const D d;
    const V tol = hn::Set(d, tolerance);
    const V zero = hn::Zero(d), one = hn::Set(d, 1.0), parallel = hn::Set(d, 1e-6);
    for (std::size_t base = 0; base < std::size_t(ObbLanes::kLanes); base += hn::Lanes(d))
    {
        const LaneFrame f(d, lanes, a, base);
        const V(&t)[3] = f.t;
        const V(&r)[3][3] = f.r;
        const V(&ea)[3] = f.ea;
        const V(&eb)[3] = f.eb;
        const V sphereGap = SphereGap(d, f.gap, aRadius, lanes.radius + base, tol);
        V absR[3][3];
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                absR[i][j] = hn::Abs(r[i][j]);
        // Face axes of both frames, their gaps added in squares.
        V inB = zero, inA = zero;
        for (int i = 0; i < 3; ++i)
        {
            const V widthB =
                hn::Add(hn::Add(hn::Mul(absR[i][0], ea[0]), hn::Mul(absR[i][1], ea[1])), hn::Mul(absR[i][2], ea[2]));
            const V gapB = hn::Max(zero, hn::Sub(hn::Sub(hn::Abs(t[i]), eb[i]), widthB));
            const V along = hn::Add(hn::Add(hn::Mul(t[0], r[0][i]), hn::Mul(t[1], r[1][i])), hn::Mul(t[2], r[2][i]));
            const V widthA =
                hn::Add(hn::Add(hn::Mul(absR[0][i], eb[0]), hn::Mul(absR[1][i], eb[1])), hn::Mul(absR[2][i], eb[2]));
            const V gapA = hn::Max(zero, hn::Sub(hn::Sub(hn::Abs(along), ea[i]), widthA));
            inB = i == 0 ? hn::Mul(gapB, gapB) : hn::Add(inB, hn::Mul(gapB, gapB));
            inA = i == 0 ? hn::Mul(gapA, gapA) : hn::Add(inA, hn::Mul(gapA, gapA));
        }
        V result = hn::Sqrt(hn::Max(inA, inB));
        // The axis through the centres (where they differ).
        const V centres = hn::Sqrt(hn::Add(hn::Add(hn::Mul(t[0], t[0]), hn::Mul(t[1], t[1])), hn::Mul(t[2], t[2])));
        const M apart = hn::Gt(centres, zero);
        V axis[3];
        const V inverse = hn::Div(one, centres);
        for (int i = 0; i < 3; ++i)
            axis[i] = hn::Mul(t[i], inverse);
        V inA2 = zero;
        for (int j = 0; j < 3; ++j)
        {
            const V turned =
                hn::Add(hn::Add(hn::Mul(r[0][j], axis[0]), hn::Mul(r[1][j], axis[1])), hn::Mul(r[2][j], axis[2]));
            const V term = hn::Mul(ea[j], hn::Abs(turned));
            inA2 = j == 0 ? term : hn::Add(inA2, term);
        }
        const V inB2 = hn::Add(hn::Add(hn::Mul(eb[0], hn::Abs(axis[0])), hn::Mul(eb[1], hn::Abs(axis[1]))),
                               hn::Mul(eb[2], hn::Abs(axis[2])));
        const V alongCentres = hn::Sub(hn::Sub(centres, inB2), inA2);
        result = hn::IfThenElse(hn::And(apart, hn::Lt(result, alongCentres)), alongCentres, result);
        // The nine edge-edge axes, in the same order; nearly parallel edges skipped. The largest gap
        // by squares, then one division and one root (as obbDistanceLowerBound).
        V bestExcess = result, bestLengthSquared = one;
        for (int i = 0; i < 3; ++i)
        {
            const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
            for (int j = 0; j < 3; ++j)
            {
                const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
                const V lengthSquared = hn::Sub(one, hn::Mul(r[i][j], r[i][j]));
                const V along = hn::Abs(hn::Sub(hn::Mul(t[i2], r[i1][j]), hn::Mul(t[i1], r[i2][j])));
                const V halfWidths =
                    hn::Add(hn::Add(hn::Add(hn::Mul(eb[i1], absR[i2][j]), hn::Mul(eb[i2], absR[i1][j])),
                                    hn::Mul(ea[j1], absR[i][j2])),
                            hn::Mul(ea[j2], absR[i][j1]));
                const V excess = hn::Sub(along, halfWidths);
                const M larger = hn::And(hn::And(hn::Gt(lengthSquared, parallel), hn::Gt(excess, zero)),
                                         hn::Gt(hn::Mul(hn::Mul(excess, excess), bestLengthSquared),
                                                hn::Mul(hn::Mul(bestExcess, bestExcess), lengthSquared)));
                bestExcess = hn::IfThenElse(larger, excess, bestExcess);
                bestLengthSquared = hn::IfThenElse(larger, lengthSquared, bestLengthSquared);
            }
        }
        result = hn::Max(result, hn::Div(bestExcess, hn::Sqrt(bestLengthSquared)));
        result = hn::Max(zero, hn::Sub(result, tol));
        hn::StoreU(hn::Max(sphereGap, result), d, bound + base);
    }
}

// aabbDistanceLowerBound(a, lane box, tolerance) lane by lane and the sphere gap: the larger.
void AabbLanesDistance(const AabbLanes &lanes, const Aabb &a, double aRadius, double tolerance, double *bound)
{
    const D d;
    const V tol = hn::Set(d, tolerance);
    const V zero = hn::Zero(d);
    for (std::size_t base = 0; base < std::size_t(AabbLanes::kLanes); base += hn::Lanes(d))
    {
        V gap[3], outside[3];
        for (int c = 0; c < 3; ++c)
        {
            gap[c] = hn::Sub(hn::Set(d, a.center[c]), hn::LoadU(d, lanes.field[AabbLanes::kCenter + c] + base));
            const V extents =
                hn::Add(hn::Set(d, a.halfExtents[c]), hn::LoadU(d, lanes.field[AabbLanes::kHalfExtents + c] + base));
            outside[c] = hn::Max(hn::Sub(hn::Abs(gap[c]), extents), zero);
        }
        const V sphereGap = SphereGap(d, gap, aRadius, lanes.radius + base, tol);
        const V norm = hn::Sqrt(hn::Add(hn::Add(hn::Mul(outside[0], outside[0]), hn::Mul(outside[1], outside[1])),
                                        hn::Mul(outside[2], outside[2])));
        hn::StoreU(hn::Max(sphereGap, hn::Max(zero, hn::Sub(norm, tol))), d, bound + base);
    }
}
}  // namespace HWY_NAMESPACE
}  // namespace hcd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace hcd
{
HWY_EXPORT(SeparatedObbLanes);
HWY_EXPORT(SeparatedAabbLanes);
HWY_EXPORT(ObbLanesDistance);
HWY_EXPORT(AabbLanesDistance);

namespace
{
// Lane k's bit when the box in that lane passes the sphere test and `overlap`.
template <class Lanes, class Box, class Overlap>
unsigned referenceBits(const Lanes &lanes, const Box &a, double aRadius, double tolerance, Overlap overlap)
{
    unsigned bits = 0;
    for (int k = 0; k < lanes.count; ++k)
    {
        const Box b = lanes.box(k);
        const double reach = aRadius + lanes.radius[k] + tolerance;
        if ((a.center - b.center).squaredNorm() <= reach * reach && overlap(a, b, tolerance))
            bits |= 1u << k;
    }
    return bits;
}

unsigned usedLanes(int count) { return (1u << count) - 1u; }

// Lane k's bound as the distance search computes it from the sphere gap and `lowerBound`.
template <class Lanes, class Box, class LowerBound>
void referenceBounds(const Lanes &lanes, const Box &a, double aRadius, double tolerance, double *bound,
                     LowerBound lowerBound)
{
    for (int k = 0; k < lanes.count; ++k)
    {
        const Box b = lanes.box(k);
        const double sphereGap =
            std::sqrt((a.center - b.center).squaredNorm()) - (aRadius + lanes.radius[k] + tolerance);
        bound[k] = std::max(sphereGap, lowerBound(a, b, tolerance));
    }
}
}  // namespace

void ObbLanes::add(const Obb &box, double sphereRadius, std::uint32_t nodeIndex)
{
    const int k = count++;
    for (int c = 0; c < 3; ++c)
    {
        field[kCenter + c][k] = box.center[c];
        field[kHalfExtents + c][k] = box.halfExtents[c];
        for (int a = 0; a < 3; ++a)
            field[kAxes + 3 * c + a][k] = box.axes(c, a);
    }
    radius[k] = sphereRadius;
    node[k] = nodeIndex;
}

Obb ObbLanes::box(int k) const
{
    Obb b;
    for (int c = 0; c < 3; ++c)
    {
        b.center[c] = field[kCenter + c][k];
        b.halfExtents[c] = field[kHalfExtents + c][k];
        for (int a = 0; a < 3; ++a)
            b.axes(c, a) = field[kAxes + 3 * c + a][k];
    }
    return b;
}

void AabbLanes::add(const Aabb &box, double sphereRadius, std::uint32_t nodeIndex)
{
    const int k = count++;
    for (int c = 0; c < 3; ++c)
    {
        field[kCenter + c][k] = box.center[c];
        field[kHalfExtents + c][k] = box.halfExtents[c];
    }
    radius[k] = sphereRadius;
    node[k] = nodeIndex;
}

Aabb AabbLanes::box(int k) const
{
    Aabb b;
    for (int c = 0; c < 3; ++c)
    {
        b.center[c] = field[kCenter + c][k];
        b.halfExtents[c] = field[kHalfExtents + c][k];
    }
    return b;
}

unsigned lanesOverlap(const ObbLanes &lanes, const Obb &a, double aRadius, double tolerance)
{
    return ~HWY_DYNAMIC_DISPATCH(SeparatedObbLanes)(lanes, a, aRadius, tolerance) & usedLanes(lanes.count);
}

unsigned lanesOverlap(const AabbLanes &lanes, const Aabb &a, double aRadius, double tolerance)
{
    return ~HWY_DYNAMIC_DISPATCH(SeparatedAabbLanes)(lanes, a, aRadius, tolerance) & usedLanes(lanes.count);
}

unsigned lanesOverlapReference(const ObbLanes &lanes, const Obb &a, double aRadius, double tolerance)
{
    return referenceBits(lanes, a, aRadius, tolerance,
                         [](const Obb &x, const Obb &y, double t) { return obbsOverlap(x, y, t); });
}

unsigned lanesOverlapReference(const AabbLanes &lanes, const Aabb &a, double aRadius, double tolerance)
{
    return referenceBits(lanes, a, aRadius, tolerance,
                         [](const Aabb &x, const Aabb &y, double t) { return aabbsOverlap(x, y, t); });
}

void lanesDistanceLowerBound(const ObbLanes &lanes, const Obb &a, double aRadius, double tolerance, double *bound)
{
    HWY_DYNAMIC_DISPATCH(ObbLanesDistance)(lanes, a, aRadius, tolerance, bound);
}

void lanesDistanceLowerBound(const AabbLanes &lanes, const Aabb &a, double aRadius, double tolerance, double *bound)
{
    HWY_DYNAMIC_DISPATCH(AabbLanesDistance)(lanes, a, aRadius, tolerance, bound);
}

void lanesDistanceLowerBoundReference(const ObbLanes &lanes, const Obb &a, double aRadius, double tolerance,
                                      double *bound)
{
    referenceBounds(lanes, a, aRadius, tolerance, bound,
                    [](const Obb &x, const Obb &y, double t) { return obbDistanceLowerBound(x, y, t); });
}

void lanesDistanceLowerBoundReference(const AabbLanes &lanes, const Aabb &a, double aRadius, double tolerance,
                                      double *bound)
{
    referenceBounds(lanes, a, aRadius, tolerance, bound,
                    [](const Aabb &x, const Aabb &y, double t) { return aabbDistanceLowerBound(x, y, t); });
}
}  // namespace hcd
#endif  // HWY_ONCE
