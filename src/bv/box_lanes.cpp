// SPDX-License-Identifier: BSD-3-Clause
// One box against four (box_lanes.h), compiled by Google Highway for each x86 instruction set it
// targets (its portable path, SSSE3, SSE4, AVX2, AVX-512) and dispatched at run time to the widest
// the machine has.
#include "hybridcd/bv/box_lanes.h"

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
M SpheresApart(D d, const V gap[3], double aRadius, const double *radius, V tol)
{
    const V reach = hn::Add(hn::Add(hn::Set(d, aRadius), hn::LoadU(d, radius)), tol);
    const V squared = hn::Add(hn::Add(hn::Mul(gap[0], gap[0]), hn::Mul(gap[1], gap[1])), hn::Mul(gap[2], gap[2]));
    return hn::Gt(squared, hn::Mul(reach, reach));
}

// Number f of the lanes from `base` on.
V Field(D d, const ObbLanes &lanes, int f, std::size_t base) { return hn::LoadU(d, lanes.field[f] + base); }

// Lanes [base, base + Lanes(d)) as bits at their own positions.
unsigned BitsAt(D d, M m, std::size_t base)
{
    std::uint8_t bits[8] = {};
    hn::StoreMaskBits(d, m, bits);
    return unsigned(bits[0]) << base;
}

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
        V gap[3];
        for (int c = 0; c < 3; ++c)
            gap[c] = hn::Sub(hn::Set(d, a.center[c]), Field(d, lanes, ObbLanes::kCenter + c, base));
        M out = SpheresApart(d, gap, aRadius, lanes.radius + base, tol);
        V t[3], r[3][3], absR[3][3], ea[3], eb[3];
        for (int i = 0; i < 3; ++i)
        {
            const V b0 = Field(d, lanes, ObbLanes::kAxes + i, base),
                    b1 = Field(d, lanes, ObbLanes::kAxes + 3 + i, base),
                    b2 = Field(d, lanes, ObbLanes::kAxes + 6 + i, base);  // rows of the lane box's axis i
            t[i] = hn::Add(hn::Add(hn::Mul(b0, gap[0]), hn::Mul(b1, gap[1])), hn::Mul(b2, gap[2]));
            for (int j = 0; j < 3; ++j)
            {
                r[i][j] = hn::Add(hn::Add(hn::Mul(b0, hn::Set(d, a.axes(0, j))), hn::Mul(b1, hn::Set(d, a.axes(1, j)))),
                                  hn::Mul(b2, hn::Set(d, a.axes(2, j))));
                absR[i][j] = hn::Add(hn::Abs(r[i][j]), epsilon);
            }
            ea[i] = hn::Set(d, a.halfExtents[i]);
            eb[i] = Field(d, lanes, ObbLanes::kHalfExtents + i, base);
        }
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
}  // namespace HWY_NAMESPACE
}  // namespace hcd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace hcd
{
HWY_EXPORT(SeparatedObbLanes);
HWY_EXPORT(SeparatedAabbLanes);

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
}  // namespace hcd
#endif  // HWY_ONCE
