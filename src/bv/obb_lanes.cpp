// SPDX-License-Identifier: BSD-3-Clause
// One box against four (ObbLanes), compiled by Highway for each x86 instruction set (SSE2 to
// AVX-512) and dispatched at run time to the widest the machine has.
#include "hybridcd/bv/obb_lanes.h"

#include <cstddef>
#include <cstdint>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "src/bv/obb_lanes.cpp"
#include "hwy/foreach_target.h"  // re-includes this file once per instruction set
#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace hcd
{
namespace HWY_NAMESPACE
{
namespace hn = hwy::HWY_NAMESPACE;

// obbsOverlap's separating-axis test, written lane by lane in the same order with the same
// arithmetic (no fused multiply-adds), in b's box frame: R = B^T A, t = B^T (ca - cb).
unsigned SeparatedLanes(const ObbLanes &lanes, const Obb &a, double aRadius, double tolerance)
{
    const hn::CappedTag<double, ObbLanes::kLanes> d;
    const std::size_t n = hn::Lanes(d);
    using V = hn::Vec<decltype(d)>;
    const V tol = hn::Set(d, tolerance);
    const V epsilon = hn::Set(d, 1e-12);
    unsigned separated = 0;
    for (std::size_t base = 0; base < std::size_t(ObbLanes::kLanes); base += n)
    {
        const V dx = hn::Sub(hn::Set(d, a.center.x()), hn::LoadU(d, lanes.center[0] + base));
        const V dy = hn::Sub(hn::Set(d, a.center.y()), hn::LoadU(d, lanes.center[1] + base));
        const V dz = hn::Sub(hn::Set(d, a.center.z()), hn::LoadU(d, lanes.center[2] + base));
        // Spheres first, as the scalar traversal tests them.
        const V reach = hn::Add(hn::Add(hn::Set(d, aRadius), hn::LoadU(d, lanes.radius + base)), tol);
        auto out = hn::Gt(hn::Add(hn::Add(hn::Mul(dx, dx), hn::Mul(dy, dy)), hn::Mul(dz, dz)), hn::Mul(reach, reach));
        V bAxis[3][3];  // bAxis[r][i]: row r of b's axis i
        for (int r = 0; r < 3; ++r)
            for (int i = 0; i < 3; ++i)
                bAxis[r][i] = hn::LoadU(d, lanes.axes[r][i] + base);
        V eb[3];
        for (int i = 0; i < 3; ++i)
            eb[i] = hn::LoadU(d, lanes.halfExtents[i] + base);
        V t[3], r[3][3], absR[3][3];
        for (int i = 0; i < 3; ++i)
        {
            t[i] = hn::Add(hn::Add(hn::Mul(bAxis[0][i], dx), hn::Mul(bAxis[1][i], dy)), hn::Mul(bAxis[2][i], dz));
            for (int j = 0; j < 3; ++j)
            {
                r[i][j] = hn::Add(hn::Add(hn::Mul(bAxis[0][i], hn::Set(d, a.axes(0, j))),
                                          hn::Mul(bAxis[1][i], hn::Set(d, a.axes(1, j)))),
                                  hn::Mul(bAxis[2][i], hn::Set(d, a.axes(2, j))));
                absR[i][j] = hn::Add(hn::Abs(r[i][j]), epsilon);
            }
        }
        V ea[3];
        for (int j = 0; j < 3; ++j)
            ea[j] = hn::Set(d, a.halfExtents[j]);
        // b's face axes.
        for (int i = 0; i < 3; ++i)
        {
            const V ra =
                hn::Add(hn::Add(hn::Mul(absR[i][0], ea[0]), hn::Mul(absR[i][1], ea[1])), hn::Mul(absR[i][2], ea[2]));
            out = hn::Or(out, hn::Gt(hn::Abs(t[i]), hn::Add(hn::Add(eb[i], ra), tol)));
        }
        if (!hn::AllTrue(d, out))
        {
            // a's face axes.
            for (int j = 0; j < 3; ++j)
            {
                const V along =
                    hn::Add(hn::Add(hn::Mul(t[0], r[0][j]), hn::Mul(t[1], r[1][j])), hn::Mul(t[2], r[2][j]));
                const V rb = hn::Add(hn::Add(hn::Mul(absR[0][j], eb[0]), hn::Mul(absR[1][j], eb[1])),
                                     hn::Mul(absR[2][j], eb[2]));
                out = hn::Or(out, hn::Gt(hn::Abs(along), hn::Add(hn::Add(ea[j], rb), tol)));
            }
            // Cross products of b's axis i with a's axis j.
            for (int i = 0; i < 3 && !hn::AllTrue(d, out); ++i)
            {
                const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
                for (int j = 0; j < 3; ++j)
                {
                    const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
                    const V ra = hn::Add(hn::Mul(ea[j1], absR[i][j2]), hn::Mul(ea[j2], absR[i][j1]));
                    const V rb = hn::Add(hn::Mul(eb[i1], absR[i2][j]), hn::Mul(eb[i2], absR[i1][j]));
                    const V gap = hn::Sub(hn::Mul(t[i2], r[i1][j]), hn::Mul(t[i1], r[i2][j]));
                    out = hn::Or(out, hn::Gt(hn::Abs(gap), hn::Add(hn::Add(ra, rb), tol)));
                }
            }
        }
        std::uint8_t bits[8] = {};
        hn::StoreMaskBits(d, out, bits);
        separated |= unsigned(bits[0]) << base;
    }
    return separated;
}
}  // namespace HWY_NAMESPACE
}  // namespace hcd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace hcd
{
HWY_EXPORT(SeparatedLanes);

void ObbLanes::add(const Obb &box, double sphereRadius, std::uint32_t nodeIndex)
{
    const int k = count++;
    for (int c = 0; c < 3; ++c)
    {
        center[c][k] = box.center[c];
        halfExtents[c][k] = box.halfExtents[c];
        for (int i = 0; i < 3; ++i)
            axes[c][i][k] = box.axes(c, i);
    }
    radius[k] = sphereRadius;
    node[k] = nodeIndex;
}

void ObbLanes::fill()
{
    for (int k = count; k < kLanes; ++k)
    {
        for (int c = 0; c < 3; ++c)
        {
            center[c][k] = center[c][0];
            halfExtents[c][k] = halfExtents[c][0];
            for (int i = 0; i < 3; ++i)
                axes[c][i][k] = axes[c][i][0];
        }
        radius[k] = radius[0];
        node[k] = node[0];
    }
}

unsigned obbLanesOverlap(const ObbLanes &lanes, const Obb &a, double aRadius, double tolerance)
{
    const unsigned used = (1u << lanes.count) - 1u;
    return ~HWY_DYNAMIC_DISPATCH(SeparatedLanes)(lanes, a, aRadius, tolerance) & used;
}

unsigned obbLanesOverlapReference(const ObbLanes &lanes, const Obb &a, double aRadius, double tolerance)
{
    unsigned bits = 0;
    for (int k = 0; k < lanes.count; ++k)
    {
        Obb b;
        for (int c = 0; c < 3; ++c)
        {
            b.center[c] = lanes.center[c][k];
            b.halfExtents[c] = lanes.halfExtents[c][k];
            for (int i = 0; i < 3; ++i)
                b.axes(c, i) = lanes.axes[c][i][k];
        }
        const double reach = aRadius + lanes.radius[k] + tolerance;
        if ((a.center - b.center).squaredNorm() > reach * reach || !obbsOverlap(a, b, tolerance))
            continue;
        bits |= 1u << k;
    }
    return bits;
}
}  // namespace hcd
#endif  // HWY_ONCE
