// SPDX-License-Identifier: BSD-3-Clause
// orient3d / orient2d against determinants evaluated in exact rational arithmetic. The reference
// uses the homogeneous 4x4 (3x3) determinant, a different formula from the library's, so that a
// shared slip in the expansion cannot hide. Inputs stress the floating-point filter: generic
// points, exactly coplanar and collinear ones, points one ulp off a plane, and extreme scales.
#include "hybridcd/geometry/exact_predicates.h"

#include "support/test_support.h"

#include <boost/multiprecision/cpp_int.hpp>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace
{
using hcd::Vec3;
using hcd::test::TestRandom;
using Rational = boost::multiprecision::cpp_rational;

// det [[a 1], [b 1], [c 1], [d 1]] equals -det [b - a, c - a, d - a], hence the minus sign.
int referenceOrient3d(const Vec3 &a, const Vec3 &b, const Vec3 &c, const Vec3 &d)
{
    const std::array<const Vec3 *, 4> rows = {&a, &b, &c, &d};
    Rational m[4][4];
    for (int i = 0; i < 4; ++i)
    {
        for (int k = 0; k < 3; ++k)
            m[i][k] = Rational((*rows[i])[k]);
        m[i][3] = 1;
    }
    // Laplace expansion by the first two rows against the last two.
    auto minor2 = [&](int r0, int r1, int c0, int c1) { return m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0]; };
    const int pairs[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
    Rational det = 0;
    for (int p = 0; p < 6; ++p)
    {
        const int c0 = pairs[p][0], c1 = pairs[p][1];
        const int o0 = pairs[5 - p][0], o1 = pairs[5 - p][1];
        const int sign = ((c0 + c1) % 2 == 0) ? -1 : 1;  // (-1)^((0 + 1) + (c0 + c1)), 0-based
        det += sign * minor2(0, 1, c0, c1) * minor2(2, 3, o0, o1);
    }
    return -det.sign();
}

// det [[a 1], [b 1], [c 1]] equals det [b - a, c - a].
int referenceOrient2d(double ax, double ay, double bx, double by, double cx, double cy)
{
    const Rational rax(ax), ray(ay), rbx(bx), rby(by), rcx(cx), rcy(cy);
    const Rational det = rax * (rby - rcy) - ray * (rbx - rcx) + (rbx * rcy - rby * rcx);
    return det.sign();
}

double unitDouble(TestRandom &rng) { return static_cast<double>(rng() >> 11) * 0x1p-53; }

int integerIn(TestRandom &rng, int lo, int hi)
{
    return lo + static_cast<int>(rng() % static_cast<std::uint64_t>(hi - lo + 1));
}

Vec3 unitPoint(TestRandom &rng) { return Vec3(unitDouble(rng), unitDouble(rng), unitDouble(rng)); }

Vec3 gridPoint(TestRandom &rng, int lo, int hi)
{
    return Vec3(integerIn(rng, lo, hi), integerIn(rng, lo, hi), integerIn(rng, lo, hi));
}

// Random sign, mantissa and binary exponent in [lo, hi]: magnitudes spread over many decades.
double spreadDouble(TestRandom &rng, int lo, int hi)
{
    const double v = std::ldexp(1.0 + unitDouble(rng), integerIn(rng, lo, hi));
    return (rng() & 1) ? v : -v;
}

// Multiples of 2^-20 in [-1, 1]: sums and halves of a few of them stay exact.
double dyadic(TestRandom &rng) { return std::ldexp(static_cast<double>(integerIn(rng, -(1 << 20), 1 << 20)), -20); }

Vec3 dyadicPoint(TestRandom &rng) { return Vec3(dyadic(rng), dyadic(rng), dyadic(rng)); }

std::string describe(std::initializer_list<Vec3> points)
{
    std::ostringstream out;
    char buffer[128];
    for (const Vec3 &p : points)
    {
        std::snprintf(buffer, sizeof buffer, "(%a, %a, %a) ", p.x(), p.y(), p.z());
        out << buffer;
    }
    return out.str();
}

// Counts agreement per category and reports the first few mismatches in full.
struct Tally
{
    std::string name;
    long cases = 0, zero = 0, mismatches = 0, certified = 0;

    void orient3d(const Vec3 &a, const Vec3 &b, const Vec3 &c, const Vec3 &d)
    {
        const int expected = referenceOrient3d(a, b, c, d), got = hcd::orient3d(a, b, c, d);
        ++cases;
        zero += expected == 0 ? 1 : 0;
        if (got != expected && ++mismatches <= 5)
            ADD_FAILURE() << name << ": orient3d gives " << got << ", exact sign " << expected << " for "
                          << describe({a, b, c, d});
        // The filter alone (one normal per plane): a sign it certifies is the exact one.
        const int filtered = hcd::PlaneOrientationFilter(a, b, c).side(d);
        if (filtered != 0 && filtered != expected && ++mismatches <= 5)
            ADD_FAILURE() << name << ": PlaneOrientationFilter certifies " << filtered << ", exact sign " << expected
                          << " for " << describe({a, b, c, d});
        certified += filtered != 0 ? 1 : 0;
    }

    void orient2d(double ax, double ay, double bx, double by, double cx, double cy)
    {
        const int expected = referenceOrient2d(ax, ay, bx, by, cx, cy), got = hcd::orient2d(ax, ay, bx, by, cx, cy);
        ++cases;
        zero += expected == 0 ? 1 : 0;
        if (got != expected && ++mismatches <= 5)
            ADD_FAILURE() << name << ": orient2d gives " << got << ", exact sign " << expected << " for "
                          << describe({Vec3(ax, ay, 0), Vec3(bx, by, 0), Vec3(cx, cy, 0)});
    }

    ~Tally()
    {
        std::cout << "[ category ] " << name << ": " << cases << " cases, " << zero << " exactly zero, " << mismatches
                  << " mismatches";
        if (name.rfind("orient3d", 0) == 0)
            std::cout << ", " << certified << " settled by the plane filter alone";
        std::cout << std::endl;
        EXPECT_EQ(mismatches, 0) << name;
    }
};

// Puts d exactly on the plane through grid points a, b, c (integer combination).
Vec3 onGridPlane(const Vec3 &a, const Vec3 &b, const Vec3 &c, TestRandom &rng)
{
    return a + integerIn(rng, -50, 50) * (b - a) + integerIn(rng, -50, 50) * (c - a);
}

Vec3 nudged(Vec3 p, int axis, int ulps)
{
    for (; ulps > 0; --ulps)
        p[axis] = std::nextafter(p[axis], std::numeric_limits<double>::infinity());
    for (; ulps < 0; ++ulps)
        p[axis] = std::nextafter(p[axis], -std::numeric_limits<double>::infinity());
    return p;
}
}  // namespace

// The conventions stated in the header, on the unit simplex.
TEST(ExactPredicates, SignConventions)
{
    const Vec3 o(0, 0, 0), x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
    EXPECT_EQ(hcd::orient3d(o, x, y, z), 1);
    EXPECT_EQ(hcd::orient3d(o, y, x, z), -1);
    EXPECT_EQ(hcd::orient3d(o, x, y, Vec3(0.3, 0.3, 0)), 0);
    EXPECT_EQ(referenceOrient3d(o, x, y, z), 1);
    EXPECT_EQ(referenceOrient3d(o, y, x, z), -1);
    EXPECT_EQ(hcd::orient2d(0, 0, 1, 0, 0, 1), 1);
    EXPECT_EQ(hcd::orient2d(0, 0, 0, 1, 1, 0), -1);
    EXPECT_EQ(hcd::orient2d(0, 0, 1, 1, 2, 2), 0);
    EXPECT_EQ(referenceOrient2d(0, 0, 1, 0, 0, 1), 1);
    EXPECT_EQ(referenceOrient2d(0, 0, 0, 1, 1, 0), -1);
}

TEST(ExactPredicates, RandomPointsMatchExactDeterminant)
{
    TestRandom rng(1001);
    {
        Tally t3{"orient3d, unit cube"}, t2{"orient2d, unit square"};
        for (int i = 0; i < 20000; ++i)
        {
            t3.orient3d(unitPoint(rng), unitPoint(rng), unitPoint(rng), unitPoint(rng));
            t2.orient2d(unitDouble(rng), unitDouble(rng), unitDouble(rng), unitDouble(rng), unitDouble(rng),
                        unitDouble(rng));
        }
    }
    {
        // Coordinates spread over 2^-30 .. 2^30: sums and products of very different sizes.
        Tally t3{"orient3d, spread magnitudes"}, t2{"orient2d, spread magnitudes"};
        auto s = [&rng]() { return spreadDouble(rng, -30, 30); };
        for (int i = 0; i < 10000; ++i)
        {
            t3.orient3d(Vec3(s(), s(), s()), Vec3(s(), s(), s()), Vec3(s(), s(), s()), Vec3(s(), s(), s()));
            t2.orient2d(s(), s(), s(), s(), s(), s());
        }
    }
}

// The filter should settle generic input on its own; the exact path is for hard cases.
TEST(ExactPredicates, FilterSettlesGenericInput)
{
    TestRandom rng(1002);
    const unsigned long long before = hcd::exactPredicateFallbacks();
    for (int i = 0; i < 10000; ++i)
    {
        (void)hcd::orient3d(unitPoint(rng), unitPoint(rng), unitPoint(rng), unitPoint(rng));
        (void)hcd::orient2d(unitDouble(rng), unitDouble(rng), unitDouble(rng), unitDouble(rng), unitDouble(rng),
                            unitDouble(rng));
    }
    EXPECT_LT(hcd::exactPredicateFallbacks() - before, 200u);
}

// Exactly degenerate input must give exactly zero, every time.
TEST(ExactPredicates, ConstructedCoplanarAndCollinearGiveZero)
{
    TestRandom rng(1003);
    Tally grid3{"orient3d, small grid"}, grid2{"orient2d, small grid"};
    Tally plane{"orient3d, integer combinations"}, line{"orient2d, integer combinations"};
    Tally shared{"orient3d, shared coordinate"}, mid3{"orient3d, dyadic midpoints"}, mid2{"orient2d, dyadic midpoints"};
    for (int i = 0; i < 5000; ++i)
    {
        // Coordinates in [-2, 2]: a large share of the quadruples is coplanar by chance.
        grid3.orient3d(gridPoint(rng, -2, 2), gridPoint(rng, -2, 2), gridPoint(rng, -2, 2), gridPoint(rng, -2, 2));
        grid2.orient2d(integerIn(rng, -2, 2), integerIn(rng, -2, 2), integerIn(rng, -2, 2), integerIn(rng, -2, 2),
                       integerIn(rng, -2, 2), integerIn(rng, -2, 2));

        const Vec3 a = gridPoint(rng, -1000, 1000), b = gridPoint(rng, -1000, 1000), c = gridPoint(rng, -1000, 1000);
        const Vec3 d = onGridPlane(a, b, c, rng);
        plane.orient3d(a, b, c, d);
        plane.orient3d(d, a, c, b);
        const double t = integerIn(rng, -50, 50);
        line.orient2d(a.x(), a.y(), b.x(), b.y(), a.x() + t * (b.x() - a.x()), a.y() + t * (b.y() - a.y()));

        // Random doubles sharing one coordinate (all x, all y or all z equal).
        Vec3 p[4] = {unitPoint(rng), unitPoint(rng), unitPoint(rng), unitPoint(rng)};
        const int axis = integerIn(rng, 0, 2);
        for (Vec3 &q : p)
            q[axis] = p[0][axis];
        shared.orient3d(p[0], p[1], p[2], p[3]);

        // Midpoints and quarter points of dyadic points are exact, hence exactly coplanar/collinear.
        const Vec3 e = dyadicPoint(rng), f = dyadicPoint(rng), g = dyadicPoint(rng);
        mid3.orient3d(e, f, g, (e + f) / 2);
        mid3.orient3d(e, f, g, (e + f + 2 * g) / 4);
        mid3.orient3d((f + g) / 2, e, g, f);
        mid2.orient2d(e.x(), e.y(), f.x(), f.y(), (e.x() + f.x()) / 2, (e.y() + f.y()) / 2);
        mid2.orient2d((3 * e.x() + f.x()) / 4, (3 * e.y() + f.y()) / 4, e.x(), e.y(), f.x(), f.y());
    }
    EXPECT_GT(grid3.zero, grid3.cases / 10);
    EXPECT_GT(grid2.zero, grid2.cases / 10);
    EXPECT_EQ(plane.zero, plane.cases);
    EXPECT_EQ(line.zero, line.cases);
    EXPECT_EQ(shared.zero, shared.cases);
    EXPECT_EQ(mid3.zero, mid3.cases);
    EXPECT_EQ(mid2.zero, mid2.cases);
}

// One ulp off an exactly representable plane or line: the sign must follow the offset, far below
// what the floating-point determinant can resolve.
TEST(ExactPredicates, OneUlpOffDegenerateConfigurations)
{
    TestRandom rng(1004);
    Tally grid{"orient3d, ulps off a grid plane"}, rounded{"orient3d, ulps off a rounded plane point"};
    Tally grid2{"orient2d, ulps off a grid line"}, rounded2{"orient2d, ulps off a rounded line point"};
    long nonzero = 0;
    for (int i = 0; i < 3000; ++i)
    {
        const Vec3 a = gridPoint(rng, -1000, 1000), b = gridPoint(rng, -1000, 1000), c = gridPoint(rng, -1000, 1000);
        const Vec3 d = onGridPlane(a, b, c, rng);
        const int axis = integerIn(rng, 0, 2);
        for (int ulps : {-2, -1, 1, 2})
        {
            const Vec3 off = nudged(d, axis, ulps);
            grid.orient3d(a, b, c, off);
            nonzero += referenceOrient3d(a, b, c, off) != 0 ? 1 : 0;
        }
        const double t = integerIn(rng, -50, 50);
        const double cx = a.x() + t * (b.x() - a.x()), cy = a.y() + t * (b.y() - a.y());
        for (int ulps : {-1, 1})
            grid2.orient2d(a.x(), a.y(), b.x(), b.y(), cx, nudged(Vec3(cx, cy, 0), 1, ulps).y());

        // A point computed on the plane of random doubles in floating point: rounding leaves it
        // within a few ulps of the plane, on either side or on it.
        const Vec3 p = unitPoint(rng), q = unitPoint(rng), r = unitPoint(rng);
        const double u = unitDouble(rng), v = unitDouble(rng);
        const Vec3 s = p + u * (q - p) + v * (r - p);
        for (int ulps = -3; ulps <= 3; ++ulps)
            rounded.orient3d(p, q, r, nudged(s, axis, ulps));
        const double sx = p.x() + u * (q.x() - p.x()), sy = p.y() + u * (q.y() - p.y());
        for (int ulps = -3; ulps <= 3; ++ulps)
            rounded2.orient2d(p.x(), p.y(), q.x(), q.y(), sx, nudged(Vec3(sx, sy, 0), 1, ulps).y());
    }
    EXPECT_GT(nonzero, 0);
}

// About 1e+250 and 1e-250: the filter's products overflow or underflow, so the exact path decides.
// Scaling by 2^+-830 is exact and must not change any sign; scaling by 1e+-250 rounds, so there
// only the exact determinant decides.
TEST(ExactPredicates, HugeAndTinyScales)
{
    TestRandom rng(1005);
    const double powers[] = {std::ldexp(1.0, 830), std::ldexp(1.0, -830)};
    const double decimals[] = {1e250, 1e-250};
    Tally exact{"orient3d, scaled by 2^+-830"}, exact2{"orient2d, scaled by 2^+-830"};
    Tally rounded{"orient3d, scaled by 1e+-250"}, rounded2{"orient2d, scaled by 1e+-250"};
    long signChanges = 0;
    for (int i = 0; i < 2000; ++i)
    {
        const Vec3 a = gridPoint(rng, -1000, 1000), b = gridPoint(rng, -1000, 1000), c = gridPoint(rng, -1000, 1000);
        // On the plane, one ulp off it, or generic.
        Vec3 d = onGridPlane(a, b, c, rng);
        if (i % 3 == 1)
            d = nudged(d, integerIn(rng, 0, 2), (rng() & 1) ? 1 : -1);
        else if (i % 3 == 2)
            d = gridPoint(rng, -1000, 1000);
        const int unscaled = hcd::orient3d(a, b, c, d);
        const int unscaled2 = hcd::orient2d(a.x(), a.y(), b.x(), b.y(), d.x(), d.y());
        for (double s : powers)
        {
            exact.orient3d(s * a, s * b, s * c, s * d);
            exact2.orient2d(s * a.x(), s * a.y(), s * b.x(), s * b.y(), s * d.x(), s * d.y());
            signChanges += hcd::orient3d(s * a, s * b, s * c, s * d) != unscaled ? 1 : 0;
            signChanges += hcd::orient2d(s * a.x(), s * a.y(), s * b.x(), s * b.y(), s * d.x(), s * d.y()) != unscaled2;
        }
        for (double s : decimals)
        {
            rounded.orient3d(s * a, s * b, s * c, s * d);
            rounded2.orient2d(s * a.x(), s * a.y(), s * b.x(), s * b.y(), s * d.x(), s * d.y());
            // Random points at that scale too.
            rounded.orient3d(s * unitPoint(rng), s * unitPoint(rng), s * unitPoint(rng), s * unitPoint(rng));
        }
    }
    EXPECT_EQ(signChanges, 0);
}

// Swapping two arguments negates the sign; this must hold exactly, also for degenerate input.
TEST(ExactPredicates, AntisymmetricUnderSwaps)
{
    TestRandom rng(1006);
    long cases = 0, violations = 0;
    for (int i = 0; i < 6000; ++i)
    {
        Vec3 p[4];
        const int kind = i % 3;
        for (Vec3 &q : p)
            q = kind == 0 ? unitPoint(rng) : gridPoint(rng, -2, 2);
        if (kind == 2)
            p[3] = nudged(onGridPlane(p[0], p[1], p[2], rng), integerIn(rng, 0, 2), 1);
        const int s = hcd::orient3d(p[0], p[1], p[2], p[3]);
        for (int j = 0; j < 4; ++j)
            for (int k = j + 1; k < 4; ++k)
            {
                Vec3 w[4] = {p[0], p[1], p[2], p[3]};
                std::swap(w[j], w[k]);
                ++cases;
                if (hcd::orient3d(w[0], w[1], w[2], w[3]) != -s && ++violations <= 5)
                    ADD_FAILURE() << "orient3d not antisymmetric in arguments " << j << ", " << k << " for "
                                  << describe({p[0], p[1], p[2], p[3]});
            }
        // orient2d on the x, y coordinates of the first three points.
        const double x[3] = {p[0].x(), p[1].x(), p[2].x()}, y[3] = {p[0].y(), p[1].y(), p[2].y()};
        const int s2 = hcd::orient2d(x[0], y[0], x[1], y[1], x[2], y[2]);
        const int swapped[3] = {hcd::orient2d(x[1], y[1], x[0], y[0], x[2], y[2]),
                                hcd::orient2d(x[2], y[2], x[1], y[1], x[0], y[0]),
                                hcd::orient2d(x[0], y[0], x[2], y[2], x[1], y[1])};
        for (int v : swapped)
        {
            ++cases;
            if (v != -s2 && ++violations <= 5)
                ADD_FAILURE() << "orient2d not antisymmetric for " << describe({p[0], p[1], p[2]});
        }
    }
    std::cout << "[ category ] antisymmetry: " << cases << " swaps, " << violations << " violations" << std::endl;
    EXPECT_EQ(violations, 0);
}

// Non-finite input has no orientation: the predicates answer 0 (degenerate), which every caller
// reads as "cannot be separated", never as a side.
TEST(ExactPredicates, NonFiniteInputIsDegenerate)
{
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    const Vec3 o(0, 0, 0), x(1, 0, 0), y(0, 1, 0);
    for (const Vec3 &bad : {Vec3(nan, 0, 0), Vec3(0, nan, nan), Vec3(inf, 0, 0), Vec3(-inf, inf, nan)})
    {
        for (int s : {hcd::orient3d(bad, o, x, y), hcd::orient3d(o, bad, x, y), hcd::orient3d(o, x, y, bad),
                      hcd::orient3d(bad, bad, bad, bad), hcd::orient2d(bad.x(), bad.y(), 0, 0, 1, 0),
                      hcd::orient2d(0, 0, bad.x(), 0, 1, bad.y())})
            EXPECT_EQ(s, 0);
    }
}

// Huge and tiny coordinates in one call: products in the filter underflow to subnormals (losing
// their relative accuracy) while the error bound, dominated by the large terms, stays normal.
TEST(ExactPredicates, MixedMagnitudesWithUnderflowingProducts)
{
    // det = 2^664 * (3 * 2^-1076) + (-7 * 2^124) * 2^-537 = -2^-413 < 0, but 3 * 2^-1076 rounds
    // to the subnormal 2^-1074, which flips the sign of the floating-point value.
    const Vec3 a(0, 0, 0), b(0x1p664, 0, -7 * 0x1p124), c(1, 3 * 0x1p-539, 0), d(0, 0x1p-537, 0x1p-537);
    EXPECT_EQ(referenceOrient3d(a, b, c, d), -1);
    EXPECT_EQ(hcd::orient3d(a, b, c, d), -1) << describe({a, b, c, d});

    // The same pattern with random mantissas.
    TestRandom rng(1007);
    Tally tally{"orient3d, mixed huge and subnormal products"};
    for (int i = 0; i < 5000; ++i)
    {
        const Vec3 p(0, 0, 0), q(std::ldexp(1.0 + unitDouble(rng), 664), 0, spreadDouble(rng, 119, 121));
        const Vec3 r(1, std::ldexp(1.0 + unitDouble(rng), -535), std::ldexp(1.0 + unitDouble(rng), -535));
        const Vec3 s(0, std::ldexp(1.0 + unitDouble(rng), -535), std::ldexp(1.0 + unitDouble(rng), -535));
        tally.orient3d(p, q, r, s);
    }
}

// Finite coordinates near the largest double: intermediate sums overflow, the input does not.
TEST(ExactPredicates, CoordinatesNearOverflow)
{
    const Vec3 o(0, 0, 0), x(1e308, 0, 0), y(0, 1e308, 0), z(0, 0, 1e308);
    EXPECT_EQ(hcd::orient3d(o, x, y, z), 1);
    EXPECT_EQ(hcd::orient3d(o, y, x, z), -1);
    EXPECT_EQ(hcd::orient2d(0, 0, 1e308, 0, 0, 1e308), 1);
    EXPECT_EQ(hcd::orient2d(0, 0, 0, 1e308, 1e308, 0), -1);

    TestRandom rng(1008);
    Tally t3{"orient3d, near overflow"}, t2{"orient2d, near overflow"};
    auto s = [&rng]() { return spreadDouble(rng, 1019, 1023); };
    for (int i = 0; i < 2000; ++i)
    {
        t3.orient3d(Vec3(s(), s(), s()), Vec3(s(), s(), s()), Vec3(s(), s(), s()), Vec3(s(), s(), s()));
        t2.orient2d(s(), s(), s(), s(), s(), s());
    }
}
