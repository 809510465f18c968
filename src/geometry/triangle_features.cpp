// SPDX-License-Identifier: BSD-3-Clause
// The fifteen features of a triangle pair (triangle_features.h): the six vertex-to-face distances
// in two vectors and the nine edge pairs in three, compiled by Google Highway for each x86
// instruction set it targets (its portable path, SSSE3, SSE4, AVX2, AVX-512) and dispatched at run
// time to the widest the machine has; and the same arithmetic one feature at a time.
#include "hybridcd/geometry/triangle_features.h"

#include <cmath>
#include <cstddef>
#include <limits>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "src/geometry/triangle_features.cpp"
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

// u . v with its three products added left to right, as the reference adds them.
HWY_INLINE V Dot(const V u[3], const V v[3])
{
    return hn::Add(hn::Add(hn::Mul(u[0], v[0]), hn::Mul(u[1], v[1])), hn::Mul(u[2], v[2]));
}

// x clamped to [0, 1] by the comparisons the reference makes (so that NaN and -0 go alike).
HWY_INLINE V Clamp01(D d, V x)
{
    const V zero = hn::Zero(d), one = hn::Set(d, 1.0);
    x = hn::IfThenElse(hn::Gt(x, zero), x, zero);
    return hn::IfThenElse(hn::Lt(x, one), x, one);
}

// Squared distances of the points in the lanes of p to the triangle t (corners as rows), where a
// point projects inside it; +infinity in the others.
HWY_INLINE V VertexFace(D d, const V p[3], const double (&t)[3][3])
{
    V ab[3], ac[3], ap[3], bp[3], cp[3];
    for (int c = 0; c < 3; ++c)
    {
        ab[c] = hn::Set(d, t[1][c] - t[0][c]);
        ac[c] = hn::Set(d, t[2][c] - t[0][c]);
        ap[c] = hn::Sub(p[c], hn::Set(d, t[0][c]));
        bp[c] = hn::Sub(p[c], hn::Set(d, t[1][c]));
        cp[c] = hn::Sub(p[c], hn::Set(d, t[2][c]));
    }
    const V d1 = Dot(ab, ap), d2 = Dot(ac, ap), d3 = Dot(ab, bp), d4 = Dot(ac, bp), d5 = Dot(ab, cp), d6 = Dot(ac, cp);
    const V va = hn::Sub(hn::Mul(d3, d6), hn::Mul(d5, d4));
    const V vb = hn::Sub(hn::Mul(d5, d2), hn::Mul(d1, d6));
    const V vc = hn::Sub(hn::Mul(d1, d4), hn::Mul(d3, d2));
    const V sum = hn::Add(hn::Add(va, vb), vc);
    const V zero = hn::Zero(d);
    const auto inside =
        hn::And(hn::And(hn::Ge(va, zero), hn::Ge(vb, zero)), hn::And(hn::Ge(vc, zero), hn::Gt(sum, zero)));
    const V v = hn::Div(vb, sum), w = hn::Div(vc, sum);
    V gap[3];
    for (int c = 0; c < 3; ++c)
        gap[c] = hn::Sub(p[c], hn::Add(hn::Add(hn::Set(d, t[0][c]), hn::Mul(ab[c], v)), hn::Mul(ac[c], w)));
    return hn::IfThenElse(inside, Dot(gap, gap), hn::Set(d, std::numeric_limits<double>::infinity()));
}

// u x v, component by component as the reference writes it.
HWY_INLINE void Cross(const V u[3], const V v[3], V out[3])
{
    out[0] = hn::Sub(hn::Mul(u[1], v[2]), hn::Mul(u[2], v[1]));
    out[1] = hn::Sub(hn::Mul(u[2], v[0]), hn::Mul(u[0], v[2]));
    out[2] = hn::Sub(hn::Mul(u[0], v[1]), hn::Mul(u[1], v[0]));
}

// Squared distances of the segment p0 + s d1 (s in [0, 1]) to the segments in the lanes of q0, d2.
HWY_INLINE V EdgeEdge(D d, const V p0[3], const V d1[3], const V q0[3], const V d2[3])
{
    const V zero = hn::Zero(d), one = hn::Set(d, 1.0);
    V r[3];
    for (int c = 0; c < 3; ++c)
        r[c] = hn::Sub(p0[c], q0[c]);
    const V a = Dot(d1, d1), e = Dot(d2, d2), f = Dot(d2, r), c = Dot(d1, r), b = Dot(d1, d2);
    // The lines' nearest point on the first, from cross products (see edgeEdge).
    V g[3], n[3], w[3];
    for (int k = 0; k < 3; ++k)
        g[k] = hn::Neg(r[k]);
    Cross(d1, d2, n);
    Cross(g, d2, w);
    const V denom = Dot(n, n);
    const V sGeneral = hn::IfThenElseZero(hn::Gt(denom, zero), Clamp01(d, hn::Div(Dot(w, n), denom)));
    const V tGeneral = hn::Div(hn::Add(hn::Mul(b, sGeneral), f), e);
    const V sLow = Clamp01(d, hn::Div(hn::Neg(c), a));
    const V sHigh = Clamp01(d, hn::Div(hn::Sub(b, c), a));
    const auto below = hn::Lt(tGeneral, zero), above = hn::Gt(tGeneral, one);
    V s = hn::IfThenElse(below, sLow, hn::IfThenElse(above, sHigh, sGeneral));
    V t = hn::IfThenElse(below, zero, hn::IfThenElse(above, one, tGeneral));
    // Points for segments: a point segment keeps s = 0, a point second segment t = 0.
    const auto pLong = hn::Gt(a, zero), qLong = hn::Gt(e, zero);
    s = hn::IfThenElse(pLong, hn::IfThenElse(qLong, s, sLow), zero);
    t = hn::IfThenElse(pLong, hn::IfThenElseZero(qLong, t), hn::IfThenElseZero(qLong, Clamp01(d, hn::Div(f, e))));
    V gap[3];
    for (int k = 0; k < 3; ++k)
        gap[k] = hn::Sub(hn::Add(p0[k], hn::Mul(s, d1[k])), hn::Add(q0[k], hn::Mul(t, d2[k])));
    return Dot(gap, gap);
}

// x where it is below `least`, else `least` (NaN passed over, as the reference does). A function,
// not a lambda: clang's target attributes do not reach lambdas without HWY_ATTR.
HWY_INLINE V Lesser(V x, V least) { return hn::IfThenElse(hn::Lt(x, least), x, least); }

double TriangleFeaturesSquared(const double (&a)[3][3], const double (&b)[3][3])
{
    const D d;
    // Slot k holds vertex k (the fourth repeats the first) and, for b, the edge from it to the next;
    // a vector holds Lanes(d) slots (four with AVX2 and AVX-512, two with SSE).
    double aVertex[3][4], bVertex[3][4], bEdge[3][4];
    for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 4; ++k)
        {
            aVertex[c][k] = a[k % 3][c];
            bVertex[c][k] = b[k % 3][c];
            bEdge[c][k] = b[(k + 1) % 3][c] - b[k % 3][c];
        }
    V least = hn::Set(d, std::numeric_limits<double>::infinity());
    for (std::size_t base = 0; base < 3; base += hn::Lanes(d))
    {
        V p[3], q[3], edge[3];
        for (int c = 0; c < 3; ++c)
        {
            p[c] = hn::LoadU(d, aVertex[c] + base);
            q[c] = hn::LoadU(d, bVertex[c] + base);
            edge[c] = hn::LoadU(d, bEdge[c] + base);
        }
        least = Lesser(VertexFace(d, p, b), least);
        least = Lesser(VertexFace(d, q, a), least);
        for (int i = 0; i < 3; ++i)
        {
            V p0[3], d1[3];
            for (int c = 0; c < 3; ++c)
            {
                p0[c] = hn::Set(d, a[i][c]);
                d1[c] = hn::Set(d, a[(i + 1) % 3][c] - a[i][c]);
            }
            least = Lesser(EdgeEdge(d, p0, d1, q, edge), least);
        }
    }
    double lanes[4];
    const std::size_t n = hn::Lanes(d) < 4 ? hn::Lanes(d) : 4;
    hn::StoreU(least, d, lanes);
    double result = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < n; ++k)
        result = lanes[k] < result ? lanes[k] : result;
    return result;
}
}  // namespace HWY_NAMESPACE
}  // namespace hcd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace hcd
{
HWY_EXPORT(TriangleFeaturesSquared);

namespace
{
using Corners = double[3][3];

double dot(const double *u, const double *v) { return (u[0] * v[0] + u[1] * v[1]) + u[2] * v[2]; }

void cross(const double *u, const double *v, double *out)
{
    out[0] = u[1] * v[2] - u[2] * v[1];
    out[1] = u[2] * v[0] - u[0] * v[2];
    out[2] = u[0] * v[1] - u[1] * v[0];
}

double clamp01(double x)
{
    x = x > 0.0 ? x : 0.0;
    return x < 1.0 ? x : 1.0;
}

void copyCorners(const Vec3 &p0, const Vec3 &p1, const Vec3 &p2, Corners &out)
{
    for (int c = 0; c < 3; ++c)
    {
        out[0][c] = p0[c];
        out[1][c] = p1[c];
        out[2][c] = p2[c];
    }
}

// VertexFace for one point.
double vertexFace(const double *p, const Corners &t)
{
    double ab[3], ac[3], ap[3], bp[3], cp[3];
    for (int c = 0; c < 3; ++c)
    {
        ab[c] = t[1][c] - t[0][c];
        ac[c] = t[2][c] - t[0][c];
        ap[c] = p[c] - t[0][c];
        bp[c] = p[c] - t[1][c];
        cp[c] = p[c] - t[2][c];
    }
    const double d1 = dot(ab, ap), d2 = dot(ac, ap), d3 = dot(ab, bp), d4 = dot(ac, bp), d5 = dot(ab, cp),
                 d6 = dot(ac, cp);
    const double va = d3 * d6 - d5 * d4, vb = d5 * d2 - d1 * d6, vc = d1 * d4 - d3 * d2;
    const double sum = (va + vb) + vc;
    if (!(va >= 0.0 && vb >= 0.0 && vc >= 0.0 && sum > 0.0))
        return std::numeric_limits<double>::infinity();
    const double v = vb / sum, w = vc / sum;
    double gap[3];
    for (int c = 0; c < 3; ++c)
        gap[c] = p[c] - ((t[0][c] + ab[c] * v) + ac[c] * w);
    return dot(gap, gap);
}

// EdgeEdge for one pair of segments.
double edgeEdge(const double *p0, const double *d1, const double *q0, const double *d2)
{
    const double r[3] = {p0[0] - q0[0], p0[1] - q0[1], p0[2] - q0[2]};
    const double a = dot(d1, d1), e = dot(d2, d2), f = dot(d2, r);
    double s = 0.0, t = 0.0;
    if (!(a > 0.0))
        t = e > 0.0 ? clamp01(f / e) : 0.0;
    else
    {
        const double c = dot(d1, r);
        const double sLow = clamp01(-c / a);
        if (!(e > 0.0))
            s = sLow;
        else
        {
            // The lines' nearest point on the first: ((q0 - p0) x d2) . n / |n|^2 with n = d1 x d2,
            // which is (b f - c e) / (a e - b^2) (Lagrange's identity) without that difference's
            // cancellation: for edges 1e-9 from parallel it moved the point by up to 1e-8 of their
            // length (TriangleFeatures.NearlyParallelEdgesAgainstExactRationals).
            const double b = dot(d1, d2);
            const double g[3] = {-r[0], -r[1], -r[2]};
            double n[3], w[3];
            cross(d1, d2, n);
            cross(g, d2, w);
            const double denom = dot(n, n);
            s = denom > 0.0 ? clamp01(dot(w, n) / denom) : 0.0;
            t = (b * s + f) / e;
            if (t < 0.0)
            {
                t = 0.0;
                s = sLow;
            }
            else if (t > 1.0)
            {
                t = 1.0;
                s = clamp01((b - c) / a);
            }
        }
    }
    double gap[3];
    for (int k = 0; k < 3; ++k)
        gap[k] = (p0[k] + s * d1[k]) - (q0[k] + t * d2[k]);
    return dot(gap, gap);
}

// Coordinates up to this magnitude keep every product of the features finite (the largest is of
// degree four).
constexpr double kLaneMagnitude = 1e75;
}  // namespace

double triangleFeaturesSquaredReference(const Vec3 &a0, const Vec3 &a1, const Vec3 &a2, const Vec3 &b0, const Vec3 &b1,
                                        const Vec3 &b2)
{
    Corners a, b;
    copyCorners(a0, a1, a2, a);
    copyCorners(b0, b1, b2, b);
    double least = std::numeric_limits<double>::infinity();
    const auto keep = [&](double x) { least = x < least ? x : least; };
    for (int k = 0; k < 3; ++k)
    {
        keep(vertexFace(a[k], b));
        keep(vertexFace(b[k], a));
    }
    for (int i = 0; i < 3; ++i)
    {
        const double d1[3] = {a[(i + 1) % 3][0] - a[i][0], a[(i + 1) % 3][1] - a[i][1], a[(i + 1) % 3][2] - a[i][2]};
        for (int j = 0; j < 3; ++j)
        {
            const double d2[3] = {b[(j + 1) % 3][0] - b[j][0], b[(j + 1) % 3][1] - b[j][1],
                                  b[(j + 1) % 3][2] - b[j][2]};
            keep(edgeEdge(a[i], d1, b[j], d2));
        }
    }
    return least;
}

double triangleFeaturesSquared(const Vec3 &a0, const Vec3 &a1, const Vec3 &a2, const Vec3 &b0, const Vec3 &b1,
                               const Vec3 &b2)
{
    Corners a, b;
    copyCorners(a0, a1, a2, a);
    copyCorners(b0, b1, b2, b);
    double magnitude = 0.0;
    for (const Corners *t : {&a, &b})
        for (const auto &corner : *t)
            for (const double x : corner)
                magnitude = std::fabs(x) > magnitude ? std::fabs(x) : magnitude;
    // (NaN compares false, and so leaves magnitude below the limit: tested apart.)
    bool finite = true;
    for (const Corners *t : {&a, &b})
        for (const auto &corner : *t)
            for (const double x : corner)
                finite = finite && std::isfinite(x);
    if (!finite || !(magnitude <= kLaneMagnitude))
        return triangleFeaturesSquaredReference(a0, a1, a2, b0, b1, b2);
    return HWY_DYNAMIC_DISPATCH(TriangleFeaturesSquared)(a, b);
}
}  // namespace hcd
#endif  // HWY_ONCE
