// SPDX-License-Identifier: BSD-3-Clause
// hcd::trianglesIntersect against an independent, slower formulation in exact rational
// arithmetic. The library decides with orientation predicates ("an edge of one triangle meets the
// other", or Devillers and Guigue's two orientations when each triangle strictly straddles the
// other's plane); the reference here instead intersects the two triangles with the common line of
// their planes (Moeller's interval method) or, for coplanar pairs, runs a separating axis test,
// both with exact rationals and without any library predicate. Degenerate triangles are checked
// against a third formulation: a small exact linear program per pair of edge and convex piece.
#include "hybridcd/geometry/triangle_intersection.h"

#include "support/test_support.h"

#include <boost/multiprecision/cpp_int.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace
{
using hcd::Vec3;
using hcd::test::TestRandom;
using Integer = boost::multiprecision::cpp_int;
using Rational = boost::multiprecision::cpp_rational;

// ---------------------------------------------------------------------------------------------
// Exact vectors.

struct RVec
{
    Rational x, y, z;
};

RVec operator-(const RVec &a, const RVec &b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
RVec operator+(const RVec &a, const RVec &b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
RVec operator-(const RVec &a) { return {-a.x, -a.y, -a.z}; }
Rational dot(const RVec &a, const RVec &b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
RVec cross(const RVec &a, const RVec &b)
{
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
bool isZero(const RVec &a) { return a.x.is_zero() && a.y.is_zero() && a.z.is_zero(); }

using RTriangle = std::array<RVec, 3>;

struct Triangle
{
    Vec3 v[3];
};

// Every double is m * 2^e with an integer m of at most 53 bits. Scaling all points of a pair by
// one common power of two makes every coordinate an integer; intersection does not change under
// uniform scaling, and integer-valued rationals keep the reference fast (no large denominators).
struct Dyadic
{
    std::int64_t mantissa;
    int exponent;
};

Dyadic splitDouble(double x)
{
    if (x == 0.0)
        return {0, 0};
    int e = 0;
    const double f = std::frexp(x, &e);
    return {static_cast<std::int64_t>(std::ldexp(f, 53)), e - 53};
}

std::array<RTriangle, 2> exactPair(const Triangle &a, const Triangle &b)
{
    std::array<Dyadic, 18> parts;
    int lowest = std::numeric_limits<int>::max();
    for (int t = 0; t < 2; ++t)
        for (int i = 0; i < 3; ++i)
            for (int k = 0; k < 3; ++k)
            {
                const Dyadic d = splitDouble((t == 0 ? a : b).v[i][k]);
                parts[t * 9 + i * 3 + k] = d;
                if (d.mantissa != 0)
                    lowest = std::min(lowest, d.exponent);
            }
    auto toExact = [&](const Dyadic &d) -> Rational {
        if (d.mantissa == 0)
            return Rational(0);
        Integer m = d.mantissa < 0 ? Integer(-d.mantissa) : Integer(d.mantissa);
        m <<= static_cast<unsigned>(d.exponent - lowest);
        return Rational(d.mantissa < 0 ? Integer(-m) : m);
    };
    std::array<RTriangle, 2> out;
    for (int t = 0; t < 2; ++t)
        for (int i = 0; i < 3; ++i)
            out[t][i] = {toExact(parts[t * 9 + i * 3]), toExact(parts[t * 9 + i * 3 + 1]),
                         toExact(parts[t * 9 + i * 3 + 2])};
    return out;
}

bool exactlyDegenerate(const RTriangle &t) { return isZero(cross(t[1] - t[0], t[2] - t[0])); }

// ---------------------------------------------------------------------------------------------
// Reference 1 (non-degenerate triangles): plane rejection, interval overlap on the common line of
// the two planes, separating axes for coplanar pairs. All comparisons are closed, so touching in
// a single point counts as intersecting.

bool strictlyOneSide(const Rational d[3])
{
    return (d[0].sign() > 0 && d[1].sign() > 0 && d[2].sign() > 0) ||
           (d[0].sign() < 0 && d[1].sign() < 0 && d[2].sign() < 0);
}

// The points of triangle v lying on the other plane (where the signed distances d vanish) form a
// segment of the common line; its end points are vertices with d = 0 or edge crossings. Returns
// that segment as an interval of the line parameter D . X.
std::pair<Rational, Rational> lineInterval(const RTriangle &v, const Rational d[3], const RVec &D)
{
    const Rational p[3] = {dot(D, v[0]), dot(D, v[1]), dot(D, v[2])};
    std::vector<Rational> ts;
    for (int i = 0; i < 3; ++i)
    {
        const int j = (i + 1) % 3;
        if (d[i].is_zero())
            ts.push_back(p[i]);
        if (d[i].sign() * d[j].sign() < 0)
            ts.push_back(p[i] + (p[j] - p[i]) * (d[i] / (d[i] - d[j])));
    }
    // Non-empty: the caller has rejected triangles strictly on one side of the other plane.
    const auto [lo, hi] = std::minmax_element(ts.begin(), ts.end());
    return {*lo, *hi};
}

// Coplanar convex polygons are disjoint iff some edge normal (within the plane) separates them.
bool separatedInPlane(const RTriangle &a, const RTriangle &b, const RVec &normal)
{
    for (const RTriangle *t : {&a, &b})
        for (int i = 0; i < 3; ++i)
        {
            const RVec axis = cross(normal, (*t)[(i + 1) % 3] - (*t)[i]);
            Rational pa[3], pb[3];
            for (int k = 0; k < 3; ++k)
            {
                pa[k] = dot(axis, a[k]);
                pb[k] = dot(axis, b[k]);
            }
            const auto [aLo, aHi] = std::minmax_element(pa, pa + 3);
            const auto [bLo, bHi] = std::minmax_element(pb, pb + 3);
            if (*aHi < *bLo || *bHi < *aLo)
                return true;
        }
    return false;
}

bool referenceIntervals(const RTriangle &a, const RTriangle &b)
{
    const RVec na = cross(a[1] - a[0], a[2] - a[0]);
    const RVec nb = cross(b[1] - b[0], b[2] - b[0]);
    const Rational db[3] = {dot(na, b[0] - a[0]), dot(na, b[1] - a[0]), dot(na, b[2] - a[0])};
    const Rational da[3] = {dot(nb, a[0] - b[0]), dot(nb, a[1] - b[0]), dot(nb, a[2] - b[0])};
    if (strictlyOneSide(db) || strictlyOneSide(da))
        return false;
    const RVec D = cross(na, nb);
    // Parallel planes that are not coplanar put b strictly on one side of a's plane (rejected
    // above), so parallel here means coplanar.
    if (isZero(D))
        return !separatedInPlane(a, b, na);
    const auto [aLo, aHi] = lineInterval(a, da, D);
    const auto [bLo, bHi] = lineInterval(b, db, D);
    return aLo <= bHi && bLo <= aHi;
}

// ---------------------------------------------------------------------------------------------
// Reference 2 (any triangles): closed triangles meet iff an edge of one meets the other, and a
// degenerate triangle is the union of its edges. Each convex piece (proper triangle, segment or
// point) is written as linear constraints; an edge X(s) = p + s (q - p), s in [0, 1], meets the
// piece iff the constraints leave a non-empty interval of s.

struct Constraint
{
    RVec normal;
    Rational offset;  // normal . X == offset, or normal . X >= offset
    bool equality;
};
using ConvexPiece = std::vector<Constraint>;

ConvexPiece trianglePiece(const RTriangle &t)
{
    const RVec n = cross(t[1] - t[0], t[2] - t[0]);
    ConvexPiece piece{{n, dot(n, t[0]), true}};
    for (int i = 0; i < 3; ++i)
    {
        const RVec inward = cross(n, t[(i + 1) % 3] - t[i]);
        piece.push_back({inward, dot(inward, t[i]), false});
    }
    return piece;
}

ConvexPiece segmentPiece(const RVec &r, const RVec &s)
{
    const RVec axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    ConvexPiece piece;
    const RVec v = s - r;
    if (isZero(v))
    {
        for (const RVec &e : axes)
            piece.push_back({e, dot(e, r), true});
        return piece;
    }
    // (X - r) x v = 0 componentwise, i.e. (v x e_k) . (X - r) = 0, and r <= X <= s along v.
    for (const RVec &e : axes)
    {
        const RVec n = cross(v, e);
        if (!isZero(n))
            piece.push_back({n, dot(n, r), true});
    }
    piece.push_back({v, dot(v, r), false});
    piece.push_back({-v, -dot(v, s), false});
    return piece;
}

bool edgeMeetsPiece(const RVec &p, const RVec &q, const ConvexPiece &piece)
{
    Rational lo(0), hi(1);
    const RVec dir = q - p;
    for (const Constraint &c : piece)
    {
        const Rational alpha = dot(c.normal, p) - c.offset, beta = dot(c.normal, dir);
        if (beta.is_zero())
        {
            if (c.equality ? !alpha.is_zero() : alpha.sign() < 0)
                return false;
            continue;
        }
        const Rational s = -alpha / beta;
        if (c.equality || beta.sign() > 0)
            lo = std::max(lo, s);
        if (c.equality || beta.sign() < 0)
            hi = std::min(hi, s);
        if (lo > hi)
            return false;
    }
    return true;
}

std::vector<ConvexPiece> piecesOf(const RTriangle &t)
{
    if (!exactlyDegenerate(t))
        return {trianglePiece(t)};
    return {segmentPiece(t[0], t[1]), segmentPiece(t[1], t[2]), segmentPiece(t[2], t[0])};
}

bool referenceEdges(const RTriangle &a, const RTriangle &b)
{
    const std::vector<ConvexPiece> pa = piecesOf(a), pb = piecesOf(b);
    for (int i = 0; i < 3; ++i)
    {
        for (const ConvexPiece &piece : pb)
            if (edgeMeetsPiece(a[i], a[(i + 1) % 3], piece))
                return true;
        for (const ConvexPiece &piece : pa)
            if (edgeMeetsPiece(b[i], b[(i + 1) % 3], piece))
                return true;
    }
    return false;
}

// The reference used for comparisons: intervals for proper triangles, edges otherwise.
bool reference(const Triangle &a, const Triangle &b)
{
    const auto exact = exactPair(a, b);
    if (exactlyDegenerate(exact[0]) || exactlyDegenerate(exact[1]))
        return referenceEdges(exact[0], exact[1]);
    return referenceIntervals(exact[0], exact[1]);
}

bool library(const Triangle &a, const Triangle &b)
{
    return hcd::trianglesIntersect(a.v[0], a.v[1], a.v[2], b.v[0], b.v[1], b.v[2]);
}

// ---------------------------------------------------------------------------------------------
// Random input, independent of the standard library's distributions so that the cases are the
// same everywhere.

double unitDouble(TestRandom &rng) { return static_cast<double>(rng() >> 11) * 0x1p-53; }

int integerIn(TestRandom &rng, int lo, int hi)
{
    return lo + static_cast<int>(rng() % static_cast<std::uint64_t>(hi - lo + 1));
}

Vec3 gridPoint(TestRandom &rng, int lo, int hi)
{
    return Vec3(integerIn(rng, lo, hi), integerIn(rng, lo, hi), integerIn(rng, lo, hi));
}

// Exact for small integer (or few-bit dyadic) coordinates, whose products are exact.
bool gridDegenerate(const Triangle &t) { return (t.v[1] - t.v[0]).cross(t.v[2] - t.v[0]) == Vec3::Zero(); }

// Exact for any coordinates.
bool exactDegenerate(const Triangle &t) { return exactlyDegenerate(exactPair(t, t)[0]); }

Triangle randomGridTriangle(TestRandom &rng, int lo, int hi)
{
    for (;;)
    {
        Triangle t{{gridPoint(rng, lo, hi), gridPoint(rng, lo, hi), gridPoint(rng, lo, hi)}};
        if (!gridDegenerate(t))
            return t;
    }
}

Triangle rotated(const Triangle &t) { return {{t.v[1], t.v[2], t.v[0]}}; }
Triangle reversed(const Triangle &t) { return {{t.v[0], t.v[2], t.v[1]}}; }

Triangle randomRelabel(const Triangle &t, TestRandom &rng)
{
    Triangle out = t;
    for (int k = integerIn(rng, 0, 2); k > 0; --k)
        out = rotated(out);
    return integerIn(rng, 0, 1) ? reversed(out) : out;
}

std::string describe(const Triangle &a, const Triangle &b)
{
    std::ostringstream out;
    char buffer[64];
    for (const Triangle *t : {&a, &b})
    {
        out << (t == &a ? "A =" : " B =");
        for (const Vec3 &p : t->v)
        {
            out << " (";
            for (int k = 0; k < 3; ++k)
            {
                std::snprintf(buffer, sizeof buffer, "%a", p[k]);
                out << buffer << (k < 2 ? ", " : ")");
            }
        }
    }
    return out.str();
}

// Per-category bookkeeping, printed at the end of each test.
struct Tally
{
    std::string name;
    long pairs = 0, intersecting = 0, agreements = 0, disagreements = 0, asymmetric = 0;

    void report() const
    {
        std::cout << "[ category ] " << name << ": " << pairs << " pairs, " << intersecting << " intersecting, "
                  << agreements << " agree, " << disagreements << " disagree, " << asymmetric << " violate symmetry"
                  << std::endl;
    }
};

// The answer must not depend on argument order, vertex labelling or orientation. Four variants
// cover the swap, both cyclic shifts and reversal of either triangle.
bool symmetric(const Triangle &a, const Triangle &b, bool expected)
{
    const Triangle ra = rotated(a), rb = rotated(b);
    return library(b, a) == expected && library(ra, reversed(b)) == expected && library(rotated(ra), rb) == expected &&
           library(reversed(rb), reversed(a)) == expected;
}

// Compares one pair; returns the library's answer.
bool check(Tally &tally, const Triangle &a, const Triangle &b, bool expected)
{
    const bool got = library(a, b);
    ++tally.pairs;
    tally.intersecting += expected ? 1 : 0;
    if (got == expected)
        ++tally.agreements;
    else if (++tally.disagreements <= 5)
        ADD_FAILURE() << tally.name << ": library says " << got << ", reference says " << expected << " for "
                      << describe(a, b);
    if (!symmetric(a, b, got) && ++tally.asymmetric <= 5)
        ADD_FAILURE() << tally.name << ": answer changes under relabelling for " << describe(a, b);
    return got;
}

void expectClean(const Tally &tally)
{
    tally.report();
    EXPECT_EQ(tally.disagreements, 0) << tally.name;
    EXPECT_EQ(tally.asymmetric, 0) << tally.name;
}

// ---------------------------------------------------------------------------------------------
// Constructed configurations: each builds a pair from a random grid triangle and states what the
// answer must be. Coordinates are small dyadic rationals, so every construction is exact.

struct Construction
{
    std::string name;
    std::function<std::pair<Triangle, Triangle>(TestRandom &)> build;
    bool expected;
};

// A plane through o spanned by integer vectors u, v; local dyadic (x, y) map exactly to 3D.
struct PlaneFrame
{
    Vec3 o, u, v;
    Vec3 at(double x, double y) const { return o + x * u + y * v; }
};

PlaneFrame randomFrame(TestRandom &rng)
{
    for (;;)
    {
        PlaneFrame f{gridPoint(rng, -3, 3), gridPoint(rng, -3, 3), gridPoint(rng, -3, 3)};
        if (!f.u.cross(f.v).isZero(0.0))
            return f;
    }
}

// Local triangle (0,0), (1,0), (0,1) of a frame; its edge from (1,0) to (0,1) lies on x + y = 1.
Triangle frameTriangle(const PlaneFrame &f) { return {{f.at(0, 0), f.at(1, 0), f.at(0, 1)}}; }

// Eighths in [lo, hi] / 8.
double eighth(TestRandom &rng, int lo, int hi) { return integerIn(rng, lo, hi) / 8.0; }

// A point of the frame's plane strictly beyond the frame triangle's edge x + y = 1 (eighths).
Vec3 beyondHypotenuse(const PlaneFrame &f, TestRandom &rng)
{
    const double x = eighth(rng, -16, 16);
    return f.at(x, 1.0 - x + eighth(rng, 1, 8));
}

// 1 or -1: a side of a plane.
int randomSide(TestRandom &rng) { return integerIn(rng, 0, 1) ? 1 : -1; }

// A random interior point with positive dyadic barycentric weights (eighths).
Vec3 interiorPoint(const Triangle &t, TestRandom &rng)
{
    const int w0 = integerIn(rng, 1, 6), w1 = integerIn(rng, 1, 7 - w0), w2 = 8 - w0 - w1;
    return (w0 * t.v[0] + w1 * t.v[1] + w2 * t.v[2]) / 8.0;
}

Vec3 gridNormal(const Triangle &t) { return (t.v[1] - t.v[0]).cross(t.v[2] - t.v[0]); }

// A grid point strictly on the given side of the triangle's plane (exact: small integers).
Vec3 gridPointOnSide(const Triangle &t, int side, TestRandom &rng)
{
    const Vec3 n = gridNormal(t);
    for (;;)
    {
        const Vec3 p = gridPoint(rng, -5, 5);
        if ((n.dot(p - t.v[0]) > 0 ? 1 : n.dot(p - t.v[0]) < 0 ? -1 : 0) == side)
            return p;
    }
}

std::vector<Construction> constructions()
{
    std::vector<Construction> c;
    c.push_back({"shared edge",
                 [](TestRandom &rng) {
                     const Triangle a = randomGridTriangle(rng, -4, 4);
                     const int i = integerIn(rng, 0, 2), j = (i + integerIn(rng, 1, 2)) % 3;
                     for (;;)
                     {
                         const Triangle b{{a.v[i], a.v[j], gridPoint(rng, -4, 4)}};
                         if (!gridDegenerate(b))
                             return std::make_pair(a, randomRelabel(b, rng));
                     }
                 },
                 true});
    // The other triangle stays strictly on the far side of a plane through the shared vertex
    // that has the first triangle on its near side, so only the vertex is common.
    c.push_back({"shared vertex only",
                 [](TestRandom &rng) {
                     const Triangle a = randomRelabel(randomGridTriangle(rng, -4, 4), rng);
                     Vec3 m;
                     do
                         m = gridPoint(rng, -3, 3);
                     while (m.dot(a.v[1] - a.v[0]) <= 0 || m.dot(a.v[2] - a.v[0]) <= 0);
                     for (;;)
                     {
                         const Vec3 p = gridPoint(rng, -5, 5), q = gridPoint(rng, -5, 5);
                         const Triangle b{{a.v[0], p, q}};
                         if (m.dot(p - a.v[0]) < 0 && m.dot(q - a.v[0]) < 0 && !gridDegenerate(b))
                             return std::make_pair(a, randomRelabel(b, rng));
                     }
                 },
                 true});
    // Coplanar, in the opposite cone at the shared vertex.
    c.push_back({"coplanar shared vertex",
                 [](TestRandom &rng) {
                     const Triangle a = randomRelabel(randomGridTriangle(rng, -4, 4), rng);
                     const Vec3 e1 = a.v[1] - a.v[0], e2 = a.v[2] - a.v[0];
                     for (;;)
                     {
                         const Vec3 p = a.v[0] - integerIn(rng, 0, 2) * e1 - integerIn(rng, 0, 2) * e2;
                         const Vec3 q = a.v[0] - integerIn(rng, 0, 2) * e1 - integerIn(rng, 0, 2) * e2;
                         const Triangle b{{a.v[0], p, q}};
                         if (!gridDegenerate(b))
                             return std::make_pair(a, randomRelabel(b, rng));
                     }
                 },
                 true});
    c.push_back({"coplanar overlapping",
                 [](TestRandom &rng) {
                     const PlaneFrame f = randomFrame(rng);
                     const Triangle a = frameTriangle(f);
                     for (;;)
                     {
                         const Triangle b{{interiorPoint(a, rng), f.at(eighth(rng, -16, 24), eighth(rng, -16, 24)),
                                           f.at(eighth(rng, -16, 24), eighth(rng, -16, 24))}};
                         if (!gridDegenerate(b))
                             return std::make_pair(randomRelabel(a, rng), randomRelabel(b, rng));
                     }
                 },
                 true});
    // Two vertices on the line x + y = 1 (one of them on the edge itself), the third beyond it.
    c.push_back({"coplanar touching at an edge",
                 [](TestRandom &rng) {
                     const PlaneFrame f = randomFrame(rng);
                     const Triangle a = frameTriangle(f);
                     for (;;)
                     {
                         const double t1 = eighth(rng, 0, 8), t2 = eighth(rng, -8, 16);
                         const double t3 = eighth(rng, -8, 16), beyond = eighth(rng, 1, 16);
                         const Triangle b{
                             {f.at(t1, 1 - t1), f.at(t2, 1 - t2 + (t2 == t1 ? beyond : 0)), f.at(t3, 1 - t3 + beyond)}};
                         if (!gridDegenerate(b))
                             return std::make_pair(randomRelabel(a, rng), randomRelabel(b, rng));
                     }
                 },
                 true});
    // Two vertices on x + y = 1 + gap, the third further out: disjoint by exactly the gap.
    c.push_back({"coplanar tiny gap",
                 [](TestRandom &rng) {
                     const PlaneFrame f = randomFrame(rng);
                     const Triangle a = frameTriangle(f);
                     const double gap = std::ldexp(1.0, -integerIn(rng, 20, 30));
                     const double t1 = eighth(rng, -8, 16), t2 = t1 + eighth(rng, 1, 16), t3 = eighth(rng, -8, 16);
                     const Triangle b{
                         {f.at(t1, 1 + gap - t1), f.at(t2, 1 + gap - t2), f.at(t3, 1 + gap - t3 + eighth(rng, 1, 16))}};
                     return std::make_pair(randomRelabel(a, rng), randomRelabel(b, rng));
                 },
                 false});
    // The same gap measured across planes: a parallel copy offset by a tiny multiple of the normal.
    c.push_back({"parallel tiny offset",
                 [](TestRandom &rng) {
                     const PlaneFrame f = randomFrame(rng);
                     const Triangle a = frameTriangle(f);
                     const Vec3 shift = std::ldexp(1.0, -integerIn(rng, 20, 30)) * f.u.cross(f.v);
                     for (;;)
                     {
                         const Triangle b{{interiorPoint(a, rng), f.at(eighth(rng, -16, 24), eighth(rng, -16, 24)),
                                           f.at(eighth(rng, -16, 24), eighth(rng, -16, 24))}};
                         if (!gridDegenerate(b))
                             return std::make_pair(
                                 randomRelabel(a, rng),
                                 randomRelabel({{b.v[0] + shift, b.v[1] + shift, b.v[2] + shift}}, rng));
                     }
                 },
                 false});
    // Barycentric point with weights 1/4, 1/4, 1/2 (in random order) on the face, the other two
    // vertices strictly on one side of the plane.
    c.push_back({"vertex on face",
                 [](TestRandom &rng) {
                     const Triangle a = randomRelabel(randomGridTriangle(rng, -4, 4), rng);
                     const Vec3 p = 0.25 * a.v[0] + 0.25 * a.v[1] + 0.5 * a.v[2];
                     const int side = randomSide(rng);
                     for (;;)
                     {
                         const Triangle b{{p, gridPointOnSide(a, side, rng), gridPointOnSide(a, side, rng)}};
                         if (!gridDegenerate(b))
                             return std::make_pair(a, randomRelabel(b, rng));
                     }
                 },
                 true});
    // As above, but the vertex hovers a tiny multiple of the normal above the face.
    c.push_back({"vertex just above face",
                 [](TestRandom &rng) {
                     const Triangle a = randomRelabel(randomGridTriangle(rng, -4, 4), rng);
                     const int side = randomSide(rng);
                     const Vec3 p =
                         interiorPoint(a, rng) + side * std::ldexp(1.0, -integerIn(rng, 20, 30)) * gridNormal(a);
                     for (;;)
                     {
                         const Triangle b{{p, gridPointOnSide(a, side, rng), gridPointOnSide(a, side, rng)}};
                         if (!exactDegenerate(b))
                             return std::make_pair(a, randomRelabel(b, rng));
                     }
                 },
                 false});
    // An edge whose midpoint is an interior point of the other triangle and which is not in its plane.
    c.push_back({"pierced through the interior",
                 [](TestRandom &rng) {
                     const Triangle a = randomRelabel(randomGridTriangle(rng, -4, 4), rng);
                     const Vec3 p = interiorPoint(a, rng);
                     for (;;)
                     {
                         const Vec3 m = gridPoint(rng, -3, 3);
                         const Triangle b{{p + m, p - m, gridPoint(rng, -5, 5)}};
                         if (gridNormal(a).dot(m) != 0 && !gridDegenerate(b))
                             return std::make_pair(a, randomRelabel(b, rng));
                     }
                 },
                 true});
    // One triangle meets the other's plane only in an edge (its third vertex off the plane) or a
    // vertex (the other two on one side), as side faces of prisms standing on one floor meet the
    // others' bottom faces: the edge crosses the face's edge x = 0 at height y, or lies beyond its
    // edge x + y = 1; the vertex lies beyond that edge.
    c.push_back({"edge on the plane, across the face",
                 [](TestRandom &rng) {
                     const PlaneFrame f = randomFrame(rng);
                     const Triangle a = randomRelabel(frameTriangle(f), rng);
                     const double y = eighth(rng, 1, 7);
                     const Vec3 p = f.at(-eighth(rng, 1, 16), y), q = f.at(eighth(rng, 1, 16), y);
                     const Triangle b{{p, q, gridPointOnSide(a, randomSide(rng), rng)}};
                     return std::make_pair(a, randomRelabel(b, rng));
                 },
                 true});
    c.push_back({"edge on the plane, beside the face",
                 [](TestRandom &rng) {
                     const PlaneFrame f = randomFrame(rng);
                     const Triangle a = randomRelabel(frameTriangle(f), rng);
                     for (;;)
                     {
                         const Vec3 p = beyondHypotenuse(f, rng), q = beyondHypotenuse(f, rng);
                         if (p != q)
                         {
                             const Triangle b{{p, q, gridPointOnSide(a, randomSide(rng), rng)}};
                             return std::make_pair(a, randomRelabel(b, rng));
                         }
                     }
                 },
                 false});
    c.push_back({"vertex on the plane, beside the face",
                 [](TestRandom &rng) {
                     const PlaneFrame f = randomFrame(rng);
                     const Triangle a = randomRelabel(frameTriangle(f), rng);
                     const Vec3 p = beyondHypotenuse(f, rng);
                     const int side = randomSide(rng);
                     for (;;)
                     {
                         const Triangle b{{p, gridPointOnSide(a, side, rng), gridPointOnSide(a, side, rng)}};
                         if (!gridDegenerate(b))
                             return std::make_pair(a, randomRelabel(b, rng));
                     }
                 },
                 false});
    return c;
}

// Placements of a constructed pair. Powers of two and the translation by 1e6 keep every
// coordinate exact (checked through the inverse map), so the constructed answer still holds;
// scaling by 1e-200 and 1e+200 rounds, so there only the reference decides.
struct Placement
{
    std::string name;
    std::function<Vec3(const Vec3 &)> map;
    std::function<Vec3(const Vec3 &)> inverse;  // exact inverse where `map` is exact
};

std::vector<Placement> placements()
{
    const Vec3 shift(1e6, -1e6, 1e6);
    const double tiny = std::ldexp(1.0, -664), huge = std::ldexp(1.0, 664);
    return {{"as built", [](const Vec3 &p) { return p; }, [](const Vec3 &p) { return p; }},
            {"scaled by 2^-664", [=](const Vec3 &p) -> Vec3 { return tiny * p; },
             [=](const Vec3 &p) -> Vec3 { return huge * p; }},
            {"scaled by 2^+664", [=](const Vec3 &p) -> Vec3 { return huge * p; },
             [=](const Vec3 &p) -> Vec3 { return tiny * p; }},
            // (p + t) - t is exact by Sterbenz's lemma, so it recovers p iff p + t was exact.
            {"translated by 1e6", [=](const Vec3 &p) -> Vec3 { return p + shift; },
             [=](const Vec3 &p) -> Vec3 { return p - shift; }},
            {"scaled by 1e-200", [](const Vec3 &p) -> Vec3 { return 1e-200 * p; }, nullptr},
            {"scaled by 1e+200", [](const Vec3 &p) -> Vec3 { return 1e200 * p; }, nullptr}};
}

Triangle place(const Triangle &t, const Placement &where)
{
    return {{where.map(t.v[0]), where.map(t.v[1]), where.map(t.v[2])}};
}

bool placedExactly(const Triangle &t, const Triangle &placed, const Placement &where)
{
    for (int i = 0; i < 3; ++i)
        if (where.inverse(placed.v[i]) != t.v[i])
            return false;
    return true;
}

}  // namespace

// ---------------------------------------------------------------------------------------------

// Hand-checked cases pin down both the reference and the library on the classic configurations.
TEST(TriangleIntersection, HandPickedCases)
{
    const Vec3 o(0, 0, 0), x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
    struct Case
    {
        const char *what;
        Triangle a, b;
        bool expected;
    };
    const Case cases[] = {
        {"identical", {{o, x, y}}, {{o, x, y}}, true},
        {"shared vertex, perpendicular", {{o, x, y}}, {{o, -x, z}}, true},
        {"shared edge, perpendicular", {{o, x, y}}, {{o, x, z}}, true},
        {"vertex on face", {{o, x, y}}, {{Vec3(0.25, 0.25, 0), Vec3(0, 0, 1), Vec3(1, 1, 1)}}, true},
        {"vertex on edge", {{o, x, y}}, {{Vec3(0.5, 0, 0), Vec3(0.5, -1, 1), Vec3(0.5, -1, -1)}}, true},
        {"edge crossing edge", {{o, x, y}}, {{Vec3(0.5, -1, 0), Vec3(0.5, 1, 0), Vec3(0.5, 0, 1)}}, true},
        {"pierced", {{o, x, y}}, {{Vec3(0.2, 0.2, -1), Vec3(0.2, 0.2, 1), Vec3(3, 3, 0)}}, true},
        {"parallel planes", {{o, x, y}}, {{z, x + z, y + z}}, false},
        {"above the face", {{o, x, y}}, {{Vec3(0.25, 0.25, 1e-9), Vec3(0, 0, 1), Vec3(1, 1, 1)}}, false},
        {"coplanar, disjoint", {{o, x, y}}, {{Vec3(1, 1, 0), Vec3(2, 1, 0), Vec3(1, 2, 0)}}, false},
        {"coplanar, touching at a vertex", {{o, x, y}}, {{x, Vec3(2, 0, 0), Vec3(1, 1, 0)}}, true},
        {"coplanar, contained", {{o, 4 * x, 4 * y}}, {{Vec3(1, 1, 0), Vec3(2, 1, 0), Vec3(1, 2, 0)}}, true},
        {"coplanar, star of David",
         {{o, Vec3(2, 0, 0), Vec3(1, 2, 0)}},
         {{Vec3(0, 1.5, 0), Vec3(2, 1.5, 0), Vec3(1, -0.5, 0)}},
         true},
        {"crossing planes, intervals disjoint", {{o, x, y}}, {{Vec3(2, 2, -1), Vec3(2, 2, 1), Vec3(3, 3, 0)}}, false},
    };
    for (const Case &c : cases)
    {
        EXPECT_EQ(reference(c.a, c.b), c.expected) << "reference: " << c.what;
        EXPECT_EQ(referenceEdges(exactPair(c.a, c.b)[0], exactPair(c.a, c.b)[1]), c.expected)
            << "edge reference: " << c.what;
        EXPECT_EQ(library(c.a, c.b), c.expected) << c.what;
        EXPECT_TRUE(symmetric(c.a, c.b, c.expected)) << c.what;
    }
}

// Generic position: almost every predicate is settled by the floating-point filter.
TEST(TriangleIntersection, RandomUnitCubeMatchesExactReference)
{
    TestRandom rng(20240611);
    Tally tally{"random unit cube"};
    for (int i = 0; i < 40000; ++i)
    {
        Triangle t[2];
        for (Triangle &tri : t)
            for (Vec3 &p : tri.v)
                p = Vec3(unitDouble(rng), unitDouble(rng), unitDouble(rng));
        check(tally, t[0], t[1], reference(t[0], t[1]));
    }
    expectClean(tally);
    // The generator is informative only if both answers are common.
    EXPECT_GT(tally.intersecting, tally.pairs / 20);
    EXPECT_LT(tally.intersecting, tally.pairs - tally.pairs / 20);
}

// Small integer coordinates: coplanar pairs, shared edges and vertices, vertices on edges and
// faces all occur by chance. Both exact references must agree here as well.
TEST(TriangleIntersection, IntegerGridMatchesExactReference)
{
    TestRandom rng(77);
    Tally tally{"integer grid [-3, 3]"};
    long referenceConflicts = 0;
    while (tally.pairs < hcd::test::cases(40000))
    {
        const Triangle a{{gridPoint(rng, -3, 3), gridPoint(rng, -3, 3), gridPoint(rng, -3, 3)}};
        const Triangle b{{gridPoint(rng, -3, 3), gridPoint(rng, -3, 3), gridPoint(rng, -3, 3)}};
        if (gridDegenerate(a) || gridDegenerate(b))
            continue;
        const auto exact = exactPair(a, b);
        const bool expected = referenceIntervals(exact[0], exact[1]);
        if (referenceEdges(exact[0], exact[1]) != expected && ++referenceConflicts <= 5)
            ADD_FAILURE() << "the two references disagree for " << describe(a, b);
        check(tally, a, b, expected);
    }
    expectClean(tally);
    EXPECT_EQ(referenceConflicts, 0);
    EXPECT_GT(tally.intersecting, tally.pairs / 20);
    EXPECT_LT(tally.intersecting, tally.pairs - tally.pairs / 20);
}

// Touching, nearly touching and coplanar configurations whose answer is known by construction,
// also at tiny and huge scales and far from the origin.
TEST(TriangleIntersection, ConstructedConfigurationsMatchExactReference)
{
    TestRandom rng(4242);
    const std::vector<Placement> where = placements();
    long total = 0;
    for (const Construction &construction : constructions())
    {
        std::vector<Tally> tallies;
        for (const Placement &p : where)
            tallies.push_back({construction.name + ", " + p.name});
        long referenceWrong = 0;
        for (int i = 0; i < hcd::test::cases(600); ++i)
        {
            const auto [a, b] = construction.build(rng);
            for (std::size_t k = 0; k < where.size(); ++k)
            {
                const Triangle pa = place(a, where[k]), pb = place(b, where[k]);
                bool expected = reference(pa, pb);
                if (where[k].inverse)
                {
                    ASSERT_TRUE(placedExactly(a, pa, where[k]) && placedExactly(b, pb, where[k]))
                        << construction.name << ", " << where[k].name << ": placement rounds " << describe(a, b);
                    if (expected != construction.expected && ++referenceWrong <= 5)
                        ADD_FAILURE() << construction.name << ", " << where[k].name
                                      << ": reference contradicts the construction for " << describe(pa, pb);
                    expected = construction.expected;
                }
                check(tallies[k], pa, pb, expected);
            }
        }
        EXPECT_EQ(referenceWrong, 0) << construction.name;
        for (const Tally &t : tallies)
        {
            expectClean(t);
            total += t.pairs;
        }
    }
    std::cout << "[ category ] constructed, all: " << total << " pairs" << std::endl;
}

// Collinear and repeated vertices: the library handles them as segments; the reference is the
// union of their edges.
TEST(TriangleIntersection, DegenerateTrianglesMatchSegmentReference)
{
    TestRandom rng(31337);
    Tally collinear{"degenerate vs proper"}, both{"degenerate vs degenerate"};
    auto degenerateTriangle = [&rng]() {
        const Vec3 p = gridPoint(rng, -3, 3), d = gridPoint(rng, -2, 2);
        return Triangle{{p + integerIn(rng, -2, 2) * d, p + integerIn(rng, -2, 2) * d, p + integerIn(rng, -2, 2) * d}};
    };
    for (int i = 0; i < 3000; ++i)
    {
        const Triangle a = degenerateTriangle();
        const Triangle b = randomGridTriangle(rng, -3, 3);
        check(collinear, a, b, reference(a, b));
        const Triangle c = degenerateTriangle();
        check(both, a, c, reference(a, c));
    }
    expectClean(collinear);
    expectClean(both);
    EXPECT_GT(collinear.intersecting, 0);
    EXPECT_GT(both.intersecting, 0);
}

// Coordinates close to the largest double: the configuration is decided the same way as at any
// other scale (the exact reference has no range limit).
TEST(TriangleIntersection, CoordinatesNearOverflow)
{
    const Vec3 o(0, 0, 0), x(1e308, 0, 0), y(0, 1e308, 0);
    struct Case
    {
        const char *what;
        Triangle a, b;
    };
    const Case cases[] = {
        {"parallel copy", {{o, x, y}}, {{Vec3(0, 0, 1e308), Vec3(1e308, 0, 1e308), Vec3(0, 1e308, 1e308)}}},
        {"above the face", {{o, x, y}}, {{Vec3(0, 0, 1.7e308), Vec3(1e307, 1e307, 1e308), Vec3(1e307, 2e307, 1e308)}}},
        {"vertex on face",
         {{o, x, y}},
         {{Vec3(1e307, 1e307, 0), Vec3(1e307, 1e307, 1e308), Vec3(2e307, 1e307, 1e308)}}},
        {"pierced", {{o, x, y}}, {{Vec3(1e307, 1e307, -1e308), Vec3(1e307, 1e307, 1e308), Vec3(1e308, 1e308, 0)}}},
    };
    for (const Case &c : cases)
    {
        const bool expected = reference(c.a, c.b);
        EXPECT_EQ(library(c.a, c.b), expected) << c.what << ": " << describe(c.a, c.b);
    }
}

// Coordinates near 2^664, 2^120, 1 and 2^-535 in one pair: products inside the predicates' filter
// underflow to subnormals while the error bound stays large. The first three pairs were found by
// random search and are kept as regressions.
TEST(TriangleIntersection, MixedMagnitudeCoordinates)
{
    const Triangle found[][2] = {
        {{{Vec3(0x1.60611baf7a79ap+664, -0x1.eda7e7e3dfd72p+664, 0), Vec3(0x1.f896d8bd5b23ap-535, 0, 0),
           Vec3(-0x1.ef3dcfc5b0e5ap-537, -0x1.87cd00370dbb8p+0, 0)}},
         {{Vec3(0x1.8f3e0157b8ea8p+664, -0x1.ae02b6f12544p-535, 0x1.93448c6597e8ep-535),
           Vec3(-0x1.6103f30b9dee8p+120, 0, 0), Vec3(0, -0x1.8749f703a863cp-537, -0x1.3b428e2ab3e62p-535)}}},
        {{{Vec3(0x1.9276d94fb26eap-535, 0x1.b2c7d1c183724p+120, 0),
           Vec3(-0x1.e534b32c7cf24p+664, 0x1.08ee24c871ebep+0, -0x1.fde52fc42fbeep+120),
           Vec3(0, -0x1.0baa421b3e47p+664, 0)}},
         {{Vec3(0x1.9bf884bfa98dp-535, 0, 0),
           Vec3(0x1.60abfd0940f5cp-537, 0x1.a312e0e358e3bp+120, 0x1.c0084ff2ce49p-537),
           Vec3(-0x1.88dce6e49bc92p+120, -0x1.c3c517a296046p+0, 0x1.ffc0f64cc0968p+120)}}},
        {{{Vec3(0, -0x1.c6c4ea182d5bbp+664, 0x1.65e57784cfe44p-535),
           Vec3(0x1.11e91752400f8p-537, -0x1.ca04e99702cb6p-537, 0),
           Vec3(0x1.512472072dfefp-537, 0x1.679f6723070a2p+0, 0x1.ac4ad7fde193cp-537)}},
         {{Vec3(0x1.d92f7c534a8a2p-537, -0x1.a5ab3d120692p+0, -0x1.1d4a96ba8aaeap+0),
           Vec3(0x1.322c07d45c784p+120, -0x1.85ea7eb873062p+0, 0x1.f945acef88f74p+0),
           Vec3(0x1.1340f4d6226e1p-537, -0x1.35670ab7fc1ccp-535, 0)}}},
    };
    Tally tally{"mixed magnitudes"};
    for (const auto &pair : found)
    {
        const auto exact = exactPair(pair[0], pair[1]);
        ASSERT_EQ(referenceIntervals(exact[0], exact[1]), referenceEdges(exact[0], exact[1]));
        check(tally, pair[0], pair[1], reference(pair[0], pair[1]));
    }
    TestRandom rng(9001);
    auto coordinate = [&rng]() {
        const int k = integerIn(rng, 0, 5);
        if (k == 5)
            return 0.0;
        const int exponents[] = {664, 120, 0, -535, -537};
        const double v = std::ldexp(1.0 + unitDouble(rng), exponents[k]);
        return (rng() & 1) ? v : -v;
    };
    for (int i = 0; i < 300; ++i)
    {
        Triangle t[2];
        for (Triangle &tri : t)
            for (Vec3 &p : tri.v)
                p = Vec3(coordinate(), coordinate(), coordinate());
        check(tally, t[0], t[1], reference(t[0], t[1]));
    }
    expectClean(tally);
}

// Non-finite input has no position, so it can never be shown apart: every test reports contact,
// wherever the bad point sits and however far away the other part is.
TEST(TriangleIntersection, NonFiniteInputIsReportedAsContact)
{
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    const Vec3 o(0, 0, 0), x(1, 0, 0), y(0, 1, 0);
    const Vec3 f0(5, 5, 5), f1(6, 5, 5), f2(5, 6, 7);  // far from o, x, y
    for (const Vec3 &bad : {Vec3(nan, 0, 0), Vec3(0, nan, nan), Vec3(inf, 0, 0), Vec3(-inf, inf, 0), Vec3(0, 0, -inf)})
    {
        EXPECT_TRUE(hcd::trianglesIntersect(o, x, bad, f0, f1, f2));
        EXPECT_TRUE(hcd::trianglesIntersect(bad, x, y, f0, f1, f2));
        EXPECT_TRUE(hcd::trianglesIntersect(f0, f1, f2, o, bad, y));
        EXPECT_TRUE(hcd::trianglesIntersect(o, x, y, f0, f1, bad));
        EXPECT_TRUE(hcd::trianglesIntersect(bad, bad, bad, bad, bad, bad));
        EXPECT_TRUE(hcd::segmentIntersectsTriangle(bad, f0, o, x, y));
        EXPECT_TRUE(hcd::segmentIntersectsTriangle(f0, f1, o, bad, y));
        EXPECT_TRUE(hcd::segmentsIntersect(bad, f0, x, y));
        EXPECT_TRUE(hcd::segmentsIntersect(f0, f1, x, bad));
    }
    // A triangle with one non-finite vertex whose finite corners still span a proper triangle in a
    // projection: every sign against its (undefined) plane is zero, but not every sign of its own
    // corners against the finite triangle's plane. Touching in either order, wherever the finite
    // triangle lies.
    const Vec3 a0(5, -10, -10), a1(5, 30, -10), a2(5, -10, 30);
    for (const Vec3 &bad : {Vec3(nan, 0, 0), Vec3(inf, 0, 0), Vec3(-inf, 0, 0)})
    {
        EXPECT_TRUE(hcd::trianglesIntersect(a0, a1, a2, bad, Vec3(0, 1, 0), Vec3(0, 0, 1)));
        EXPECT_TRUE(hcd::trianglesIntersect(bad, Vec3(0, 1, 0), Vec3(0, 0, 1), a0, a1, a2));
        EXPECT_TRUE(hcd::trianglesIntersect(Vec3(5, 10, 10), Vec3(5, 11, 10), Vec3(5, 10, 11), bad, Vec3(0, 1, 0),
                                            Vec3(0, 0, 1)));
    }
}
