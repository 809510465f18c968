// SPDX-License-Identifier: BSD-3-Clause
// Mesh components, closedness and exact point-in-solid queries.
//
// Point queries are checked against analytic references on boxes, a tetrahedron, an octahedron
// and non-convex prisms. Point coordinates are multiples of 2^-20 drawn half from a small set of
// special values (face planes, edges, vertices, diagonals of faces), so that many points lie
// exactly on the surface or on a face's plane outside the face, many +x rays graze edges and
// vertices or run within faces, and every reference inequality is evaluated exactly. On OMPL.app's
// Home and Abstract the accelerated query is compared with plain parity over all triangles.
#include "hybridcd/geometry/solid_components.h"

#include "hybridcd/geometry/triangle_intersection.h"
#include "hybridcd/io/mesh_loader.h"
#include "support/test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <iostream>
#include <memory>
#include <random>
#include <vector>

using namespace hcd;

namespace
{
using Reference = std::function<bool(const Vec3 &)>;

TriangleMesh merged(const TriangleMesh &a, const TriangleMesh &b)
{
    TriangleMesh m = a;
    const auto offset = std::uint32_t(a.vertices.size());
    m.vertices.insert(m.vertices.end(), b.vertices.begin(), b.vertices.end());
    for (const auto &t : b.triangles)
        m.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
    return m;
}

// Every face twice, the copy reversed, as SketchUp exports them.
TriangleMesh withReversedDuplicates(TriangleMesh m)
{
    const std::size_t n = m.triangles.size();
    for (std::size_t i = 0; i < n; ++i)
    {
        const auto t = m.triangles[i];
        m.triangles.push_back({t[0], t[2], t[1]});
    }
    return m;
}

// Every triangle with its own three vertices (no sharing by index).
TriangleMesh unwelded(const TriangleMesh &m)
{
    TriangleMesh out;
    for (std::size_t t = 0; t < m.triangles.size(); ++t)
    {
        const auto base = std::uint32_t(out.vertices.size());
        for (int k = 0; k < 3; ++k)
            out.vertices.push_back(m.corner(t, k));
        out.triangles.push_back({base, base + 1, base + 2});
    }
    return out;
}

// The box [lo, hi] with each face cut into k x k squares of two triangles. Faces do not share
// vertex indices along the box's edges (only coordinates), as in many exported meshes.
TriangleMesh tessellatedBox(const Vec3 &lo, const Vec3 &hi, int k)
{
    TriangleMesh m;
    for (int axis = 0; axis < 3; ++axis)
        for (double side : {lo[axis], hi[axis]})
        {
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            const auto base = std::uint32_t(m.vertices.size());
            for (int i = 0; i <= k; ++i)
                for (int j = 0; j <= k; ++j)
                {
                    Vec3 p;
                    p[axis] = side;
                    p[u] = lo[u] + (hi[u] - lo[u]) * i / k;
                    p[v] = lo[v] + (hi[v] - lo[v]) * j / k;
                    m.vertices.push_back(p);
                }
            const auto at = [&](int i, int j) { return base + std::uint32_t(i * (k + 1) + j); };
            for (int i = 0; i < k; ++i)
                for (int j = 0; j < k; ++j)
                {
                    m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
                    m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
                }
        }
    return m;
}

TriangleMesh tetrahedron(const Vec3 &a, const Vec3 &b, const Vec3 &c, const Vec3 &d)
{
    TriangleMesh m;
    m.vertices = {a, b, c, d};
    m.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
    return m;
}

// |x| + |y| + |z| <= r.
TriangleMesh octahedron(double r)
{
    TriangleMesh m;
    m.vertices = {Vec3(r, 0, 0), Vec3(-r, 0, 0), Vec3(0, r, 0), Vec3(0, -r, 0), Vec3(0, 0, r), Vec3(0, 0, -r)};
    for (std::uint32_t x : {0u, 1u})
        for (std::uint32_t y : {2u, 3u})
            for (std::uint32_t z : {4u, 5u})
                m.triangles.push_back({x, y, z});
    return m;
}

// The prism polygon x [z0, z1], given the polygon's vertices (x, y) and a triangulation of it.
TriangleMesh prism(const std::vector<std::array<double, 2>> &polygon, const std::vector<TriangleMesh::Triangle> &fan,
                   double z0, double z1)
{
    TriangleMesh m;
    const auto n = std::uint32_t(polygon.size());
    for (double z : {z0, z1})
        for (const auto &v : polygon)
            m.vertices.emplace_back(v[0], v[1], z);
    for (const auto &t : fan)
    {
        m.triangles.push_back({t[0], t[2], t[1]});
        m.triangles.push_back({t[0] + n, t[1] + n, t[2] + n});
    }
    for (std::uint32_t i = 0; i < n; ++i)
    {
        const std::uint32_t j = (i + 1) % n;
        m.triangles.push_back({i, j, j + n});
        m.triangles.push_back({i, j + n, i + n});
    }
    return m;
}

// A 3 x 2 block with a 1 x 1 notch cut from the middle of its top side, z in [0, 1].
TriangleMesh uPrism()
{
    return prism({{0, 0}, {3, 0}, {3, 2}, {2, 2}, {2, 1}, {1, 1}, {1, 2}, {0, 2}},
                 {{0, 1, 4}, {1, 2, 3}, {1, 3, 4}, {0, 4, 5}, {0, 5, 6}, {0, 6, 7}}, 0.0, 1.0);
}

bool inUPrism(const Vec3 &p)
{
    const double x = p.x(), y = p.y(), z = p.z();
    if (z < 0 || z > 1 || x < 0 || x > 3 || y < 0 || y > 2)
        return false;
    return y <= 1 || x <= 1 || x >= 2;
}

// An L: [0, 2] x [0, 1] united with [0, 1] x [0, 2], z in [-1, 0.5].
TriangleMesh lPrism()
{
    return prism({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}, {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}}, -1.0,
                 0.5);
}

bool inLPrism(const Vec3 &p)
{
    const double x = p.x(), y = p.y(), z = p.z();
    if (z < -1 || z > 0.5 || x < 0 || y < 0)
        return false;
    return (x <= 2 && y <= 1) || (x <= 1 && y <= 2);
}

Reference inBox(const Vec3 &lo, const Vec3 &hi)
{
    return [lo, hi](const Vec3 &p) { return (p.array() >= lo.array()).all() && (p.array() <= hi.array()).all(); };
}

// A coordinate: half the time one of `specials`, otherwise a multiple of 2^-20 in [lo, hi].
double coordinate(test::TestRandom &rng, const std::vector<double> &specials, double lo, double hi)
{
    if (rng() % 2 == 0)
        return specials[rng() % specials.size()];
    const double u = double(rng() >> 11) * 0x1.0p-53;
    return std::round((lo + u * (hi - lo)) * 0x1.0p20) * 0x1.0p-20;
}

// Compares the query with `reference` on n points, also swapping coordinates between axes so that
// every axis sees the special values. Returns how many points were on the surface or inside.
std::size_t expectMatchesReference(const char *name, const TriangleMesh &mesh, const Reference &reference,
                                   const std::vector<double> &specials, double lo, double hi, std::size_t n,
                                   std::uint64_t seed)
{
    const SolidQuery query(std::make_shared<TriangleMesh>(mesh));
    EXPECT_GE(query.closedComponentCount(), 1u) << name;
    test::TestRandom rng(seed);
    std::size_t mismatches = 0, inside = 0;
    for (std::size_t i = 0; i < n; ++i)
    {
        const Vec3 p(coordinate(rng, specials, lo, hi), coordinate(rng, specials, lo, hi),
                     coordinate(rng, specials, lo, hi));
        const bool expected = reference(p);
        inside += expected ? 1 : 0;
        if (query.insideAnySolid(p) != expected && ++mismatches <= 10)
            ADD_FAILURE() << name << ": point (" << p.transpose() << ") should be "
                          << (expected ? "inside" : "outside");
    }
    EXPECT_EQ(mismatches, 0u) << name;
    return inside;
}

// Points on the closed surface of the box [lo, hi]: on faces, edges and vertices, exactly.
std::size_t countOnBoxSurface(const Vec3 &lo, const Vec3 &hi, const std::vector<double> &specials, double a, double b,
                              std::size_t n, std::uint64_t seed)
{
    test::TestRandom rng(seed);
    std::size_t count = 0;
    const Reference closed = inBox(lo, hi);
    for (std::size_t i = 0; i < n; ++i)
    {
        const Vec3 p(coordinate(rng, specials, a, b), coordinate(rng, specials, a, b), coordinate(rng, specials, a, b));
        if (closed(p) && ((p.array() == lo.array()).any() || (p.array() == hi.array()).any()))
            ++count;
    }
    return count;
}

constexpr std::size_t kPoints = 100000;
}  // namespace

TEST(MeshComponents, BoxIsOneClosedComponent)
{
    const TriangleMesh box = test::boxMesh(Vec3(0, 0, 0), Vec3(1, 2, 3));
    const auto components = meshComponents(box);
    ASSERT_EQ(components.size(), 1u);
    EXPECT_TRUE(components[0].closed);
    EXPECT_EQ(components[0].triangles.size(), 12u);
    EXPECT_EQ(components[0].bounds.min, Vec3(0, 0, 0));
    EXPECT_EQ(components[0].bounds.max, Vec3(1, 2, 3));
}

TEST(MeshComponents, BoxWithATriangleRemovedIsOpen)
{
    TriangleMesh box = test::boxMesh(Vec3(0, 0, 0), Vec3(1, 1, 1));
    box.triangles.erase(box.triangles.begin() + 5);
    const auto components = meshComponents(box);
    ASSERT_EQ(components.size(), 1u);
    EXPECT_FALSE(components[0].closed);

    const SolidQuery query(std::make_shared<TriangleMesh>(box));
    EXPECT_EQ(query.closedComponentCount(), 0u);
    EXPECT_FALSE(query.insideAnySolid(Vec3(0.5, 0.5, 0.5)));
    EXPECT_FALSE(query.insideComponent(0, Vec3(0.5, 0.5, 0.5)));
    EXPECT_EQ(query.solidVolumeFraction(1000, 1), 0.0);
}

TEST(MeshComponents, TwoDisjointBoxesAreTwoComponents)
{
    const TriangleMesh boxes =
        merged(test::boxMesh(Vec3(0, 0, 0), Vec3(1, 1, 1)), test::boxMesh(Vec3(2, 0, 0), Vec3(3, 1, 1)));
    const auto components = meshComponents(boxes);
    ASSERT_EQ(components.size(), 2u);
    for (std::size_t c = 0; c < 2; ++c)
    {
        EXPECT_TRUE(components[c].closed);
        ASSERT_EQ(components[c].triangles.size(), 12u);
        for (std::uint32_t t : components[c].triangles)
            EXPECT_EQ(t / 12, c);
    }
    EXPECT_EQ(components[1].bounds.min, Vec3(2, 0, 0));

    const SolidQuery query(std::make_shared<TriangleMesh>(boxes));
    EXPECT_EQ(query.closedComponentCount(), 2u);
    EXPECT_EQ(query.solidContaining(Vec3(0.5, 0.5, 0.5)), 0);
    EXPECT_EQ(query.solidContaining(Vec3(2.5, 0.5, 0.5)), 1);
    EXPECT_EQ(query.solidContaining(Vec3(1.5, 0.5, 0.5)), -1);
    EXPECT_EQ(query.solidContaining(Vec3(3.0, 1.0, 1.0)), 1);  // a vertex: touching counts
}

TEST(MeshComponents, ReversedDuplicatesKeepABoxClosed)
{
    const TriangleMesh box = withReversedDuplicates(test::boxMesh(Vec3(0, 0, 0), Vec3(1, 1, 1)));
    const auto components = meshComponents(box);
    ASSERT_EQ(components.size(), 1u);
    EXPECT_TRUE(components[0].closed);
    EXPECT_EQ(components[0].triangles.size(), 24u);
}

TEST(MeshComponents, UnweldedVerticesStillConnect)
{
    const TriangleMesh box = unwelded(test::boxMesh(Vec3(0, 0, 0), Vec3(1, 1, 1)));
    const auto components = meshComponents(box);
    ASSERT_EQ(components.size(), 1u);
    EXPECT_TRUE(components[0].closed);
}

TEST(MeshComponents, OpenPartsBesideASolidAreNotSolid)
{
    TriangleMesh sheet;
    sheet.vertices = {Vec3(5, 0, 0), Vec3(6, 0, 0), Vec3(5, 1, 0), Vec3(6, 1, 0)};
    sheet.triangles = {{0, 1, 2}, {1, 3, 2}};
    const TriangleMesh mesh = merged(sheet, test::boxMesh(Vec3(0, 0, 0), Vec3(1, 1, 1)));
    const SolidQuery query(std::make_shared<TriangleMesh>(mesh));
    ASSERT_EQ(query.components().size(), 2u);
    EXPECT_FALSE(query.components()[0].closed);
    EXPECT_TRUE(query.components()[1].closed);
    EXPECT_EQ(query.closedComponentCount(), 1u);
    EXPECT_EQ(query.solidContaining(Vec3(0.25, 0.5, 0.75)), 1);
    EXPECT_EQ(query.solidContaining(Vec3(5.5, 0.5, 0.0)), -1);  // on the open sheet
    // The box is 1/6 of the joint bounds [0, 6] x [0, 1] x [0, 1].
    EXPECT_NEAR(query.solidVolumeFraction(60000, 7), 1.0 / 6.0, 0.01);
}

TEST(SolidQuery, BoxesAgainstAnalyticReference)
{
    // Face diagonals run along y = z and y = -z, so with these values the +x ray often runs
    // exactly along a diagonal edge, a box edge, or within a face.
    const std::vector<double> specials = {-2, -1.5, -1, -0.5, -0.25, 0, 0.25, 0.5, 1, 1.5, 2};
    const Vec3 lo(-1, -1, -1), hi(1, 1, 1);
    expectMatchesReference("cube", test::boxMesh(lo, hi), inBox(lo, hi), specials, -2, 2, kPoints, 1);
    EXPECT_GT(countOnBoxSurface(lo, hi, specials, -2, 2, kPoints, 1), kPoints / 20);

    const Vec3 lo2(-0.5, -1, 0), hi2(1.5, 0.25, 2);
    expectMatchesReference("box", test::boxMesh(lo2, hi2), inBox(lo2, hi2), specials, -2, 2, kPoints, 2);
    expectMatchesReference("box, SketchUp duplicates", withReversedDuplicates(test::boxMesh(lo2, hi2)), inBox(lo2, hi2),
                           specials, -2, 2, kPoints, 3);
    expectMatchesReference("box, unwelded", unwelded(test::boxMesh(lo, hi)), inBox(lo, hi), specials, -2, 2, kPoints,
                           4);

    // Thousands of triangles, so the ray grid has many cells; the specials hit its inner edges.
    const TriangleMesh fine = tessellatedBox(lo, hi, 16);
    ASSERT_EQ(meshComponents(fine).size(), 1u);
    EXPECT_TRUE(meshComponents(fine)[0].closed);
    std::vector<double> fineSpecials;
    for (int i = -12; i <= 12; ++i)
        fineSpecials.push_back(0.125 * i);
    expectMatchesReference("tessellated cube", fine, inBox(lo, hi), fineSpecials, -1.5, 1.5, kPoints, 7);

    // Far from the origin (still exactly representable lattice points).
    const Vec3 offset = Vec3::Constant(1048576.25);
    std::vector<double> farSpecials;
    for (double s : specials)
        farSpecials.push_back(s + offset.x());
    expectMatchesReference("box far from the origin", test::boxMesh(lo + offset, hi + offset),
                           inBox(lo + offset, hi + offset), farSpecials, offset.x() - 2, offset.x() + 2, kPoints, 8);

    // Two boxes sharing part of a face, and so vertices (one component whose parity is still the
    // union), and a box nested in another (two components): the union counts.
    const TriangleMesh pair = merged(test::boxMesh(lo, hi), test::boxMesh(Vec3(1, -1, -1), Vec3(2, 1, 0)));
    const Reference inPair = [&](const Vec3 &p) {
        return inBox(lo, hi)(p) || inBox(Vec3(1, -1, -1), Vec3(2, 1, 0))(p);
    };
    expectMatchesReference("two touching boxes", pair, inPair, specials, -2, 2.5, kPoints, 5);
    const TriangleMesh nested =
        merged(test::boxMesh(lo, hi), test::boxMesh(Vec3(-0.5, -0.5, -0.5), Vec3(0.5, 0.5, 0.5)));
    expectMatchesReference("nested boxes", nested, inBox(lo, hi), specials, -2, 2, kPoints, 6);
}

TEST(SolidQuery, ShellsMeetingAtACornerOrAnEdgeEachHoldASolid)
{
    // A tetrahedron inside a cube, touching it only at the cube's corner or along one of its edges:
    // one connected component, two closed shells. Parity over both would call the points inside
    // the tetrahedron outside; each shell is a solid, so the union (the cube) is inside.
    const Vec3 lo(0, 0, 0), hi(4, 4, 4);
    const std::vector<double> specials = {-1, 0, 0.5, 1, 1.5, 2, 3, 4, 5};
    struct Case
    {
        const char *name;
        TriangleMesh tetra;
        Vec3 inTetra;
    };
    const Case cases[] = {
        {"tetrahedron at a corner", tetrahedron(Vec3(0, 0, 0), Vec3(3, 1.5, 1.5), Vec3(1.5, 3, 1.5), Vec3(1.5, 1.5, 3)),
         Vec3(1.5, 1.5, 1.5)},
        {"tetrahedron along an edge", tetrahedron(Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(2, 3, 1), Vec3(2, 1, 3)),
         Vec3(2, 1, 1)},
    };
    for (const Case &c : cases)
    {
        for (const TriangleMesh &mesh :
             {merged(test::boxMesh(lo, hi), c.tetra), withReversedDuplicates(merged(c.tetra, test::boxMesh(lo, hi)))})
        {
            const auto components = meshComponents(mesh);
            ASSERT_EQ(components.size(), 2u) << c.name;
            EXPECT_TRUE(components[0].closed && components[1].closed) << c.name;
            EXPECT_LT(components[0].triangles.front(), components[1].triangles.front()) << c.name;
            const SolidQuery query(std::make_shared<TriangleMesh>(mesh));
            EXPECT_EQ(query.closedComponentCount(), 2u) << c.name;
            EXPECT_TRUE(query.insideAnySolid(c.inTetra)) << c.name;
            const std::size_t inside =
                expectMatchesReference(c.name, mesh, inBox(lo, hi), specials, -1, 5, kPoints, 31);
            EXPECT_GT(inside, kPoints / 10) << c.name;
        }
    }

    // A surface that closes only as a whole stays one solid: two open boxes (a face missing from
    // each) glued along the rims of the missing faces.
    TriangleMesh a = test::boxMesh(lo, Vec3(2, 4, 4)), b = test::boxMesh(Vec3(2, 0, 0), Vec3(4, 4, 4));
    a.triangles.erase(a.triangles.begin() + 10, a.triangles.begin() + 12);  // a's face x = 2
    b.triangles.erase(b.triangles.begin() + 8, b.triangles.begin() + 10);   // b's face x = 2
    const TriangleMesh glued = merged(a, b);
    const auto components = meshComponents(glued);
    ASSERT_EQ(components.size(), 1u);
    EXPECT_TRUE(components[0].closed);
    expectMatchesReference("two open boxes closing together", glued, inBox(lo, hi), specials, -1, 5, kPoints / 4, 32);
}

// Two closed boxes side by side hold their shared face twice, once in each orientation (found by
// a held-out input). Taken as one double-sided face it left the pair open, and a robot inside
// either box was free; the faces without a reverse close, and bound the union of the two.
TEST(SolidQuery, SolidsSharingAFaceHoldTheirUnion)
{
    const Vec3 lo(0, 0, 0), hi(4, 4, 4);
    const std::vector<double> specials = {-1, 0, 0.5, 1, 2, 3, 4, 5};
    const TriangleMesh a = test::boxMesh(lo, Vec3(2, 4, 4)), b = test::boxMesh(Vec3(2, 0, 0), hi);
    TriangleMesh pair = merged(a, b);
    weldAndDropDegenerate(pair);  // as the loader does
    ASSERT_EQ(withoutRepeatedFaces(std::make_shared<TriangleMesh>(pair)).dropped, 2u) << "the shared face, reversed";
    auto components = meshComponents(pair);
    ASSERT_EQ(components.size(), 1u);
    EXPECT_TRUE(components[0].closed);
    const SolidQuery query(std::make_shared<TriangleMesh>(pair));
    EXPECT_TRUE(query.insideAnySolid(Vec3(1, 1, 1)));
    EXPECT_TRUE(query.insideAnySolid(Vec3(3, 1, 1)));
    EXPECT_TRUE(query.insideAnySolid(Vec3(2, 1, 1)));  // on the shared face
    expectMatchesReference("two boxes sharing a face", pair, inBox(lo, hi), specials, -1, 5, kPoints / 2, 41);

    // A closed box with a double-sided fin along one of its edges: the box is the solid, the fin a
    // surface (points beside it are outside).
    TriangleMesh finned = test::boxMesh(lo, hi);
    const auto corner = [&](const Vec3 &p) {
        finned.vertices.push_back(p);
        return std::uint32_t(finned.vertices.size() - 1);
    };
    const std::uint32_t f0 = corner(Vec3(4, 0, 0)), f1 = corner(Vec3(4, 0, 4)), f2 = corner(Vec3(8, 0, 4)),
                        f3 = corner(Vec3(8, 0, 0));
    finned.triangles.push_back({f0, f1, f2});
    finned.triangles.push_back({f0, f2, f3});
    finned.triangles.push_back({f2, f1, f0});
    finned.triangles.push_back({f3, f2, f0});
    components = meshComponents(finned);
    ASSERT_EQ(components.size(), 1u);
    EXPECT_TRUE(components[0].closed);
    expectMatchesReference("a box with a double-sided fin", finned, inBox(lo, hi), specials, -1, 9, kPoints / 2, 42);

    // An open double-sided sheet alone has no face without its reverse: a surface, not a solid.
    TriangleMesh sheet;
    sheet.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
    sheet.triangles = {{0, 1, 2}, {0, 2, 3}, {2, 1, 0}, {3, 2, 0}};
    components = meshComponents(sheet);
    ASSERT_EQ(components.size(), 1u);
    EXPECT_FALSE(components[0].closed);
    EXPECT_EQ(SolidQuery(std::make_shared<TriangleMesh>(sheet)).closedComponentCount(), 0u);
}

TEST(SolidQuery, TetrahedronAgainstAnalyticReference)
{
    const std::vector<double> specials = {-1, -0.5, 0, 0.5, 1, 1.5, 2, 2.5, 3, 4, 4.5};
    const TriangleMesh tet = tetrahedron(Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(0, 4, 0), Vec3(0, 0, 4));
    const auto inside = [](const Vec3 &p) { return p.x() >= 0 && p.y() >= 0 && p.z() >= 0 && p.sum() <= 4; };
    expectMatchesReference("tetrahedron", tet, inside, specials, -1, 5, kPoints, 11);
    expectMatchesReference("tetrahedron, SketchUp duplicates", withReversedDuplicates(tet), inside, specials, -1, 5,
                           kPoints / 4, 12);

    // Points on the slanted face, its edges and vertices, and on its plane outside the face.
    const SolidQuery query(std::make_shared<TriangleMesh>(tet));
    EXPECT_TRUE(query.insideAnySolid(Vec3(1, 1, 2)));
    EXPECT_TRUE(query.insideAnySolid(Vec3(2, 2, 0)));
    EXPECT_TRUE(query.insideAnySolid(Vec3(0, 0, 4)));
    EXPECT_TRUE(query.insideAnySolid(Vec3(0, 0, 0)));
    EXPECT_FALSE(query.insideAnySolid(Vec3(-1, 1, 4)));
    EXPECT_FALSE(query.insideAnySolid(Vec3(5, -1, 0)));
    EXPECT_FALSE(query.insideAnySolid(Vec3(-1, 2, 2)));  // +x ray through the edge (0,4,0)-(0,0,4)
    EXPECT_FALSE(query.insideAnySolid(Vec3(-1, 0, 0)));  // +x ray along the edge on the x axis
}

TEST(SolidQuery, OctahedronAgainstAnalyticReference)
{
    const std::vector<double> specials = {-3, -2, -1.5, -1, -0.5, 0, 0.5, 1, 1.5, 2, 3};
    const auto inside = [](const Vec3 &p) { return p.cwiseAbs().sum() <= 2; };
    expectMatchesReference("octahedron", octahedron(2), inside, specials, -3, 3, kPoints, 21);
}

TEST(SolidQuery, NonConvexPrismsAgainstAnalyticReference)
{
    const std::vector<double> specials = {-1, -0.5, 0, 0.5, 1, 1.5, 2, 2.5, 3, 3.5};
    expectMatchesReference("U prism", uPrism(), inUPrism, specials, -1, 4, kPoints, 31);
    expectMatchesReference("U prism, SketchUp duplicates", withReversedDuplicates(uPrism()), inUPrism, specials, -1, 4,
                           kPoints / 4, 32);
    expectMatchesReference("L prism", lPrism(), inLPrism, specials, -1.5, 3, kPoints, 33);

    // A +x ray from the left arm crosses the notch: four crossings in all, even, so outside.
    const SolidQuery query(std::make_shared<TriangleMesh>(uPrism()));
    EXPECT_TRUE(query.insideAnySolid(Vec3(0.5, 1.5, 0.5)));
    EXPECT_FALSE(query.insideAnySolid(Vec3(1.5, 1.5, 0.5)));
    EXPECT_FALSE(query.insideAnySolid(Vec3(-0.5, 1.5, 0.5)));
    EXPECT_TRUE(query.insideAnySolid(Vec3(1.5, 1.0, 0.5)));  // on the notch floor
    EXPECT_TRUE(query.insideAnySolid(Vec3(1.0, 1.5, 1.0)));  // on an edge of the top
}

namespace
{
// Plain parity over every distinct triangle of one closed component, with a separately written
// crossing test: on a triangle counts as inside, and crossings are counted towards p + reach * d.
bool bruteForceInside(const TriangleMesh &mesh, const MeshComponent &component, const Vec3 &p, const Vec3 &d,
                      double reach)
{
    std::vector<TriangleMesh::Triangle> seen;
    const Vec3 q = p + reach * d;
    bool odd = false;
    for (std::uint32_t t : component.triangles)
    {
        auto key = mesh.triangles[t];
        std::sort(key.begin(), key.end());
        if (std::find(seen.begin(), seen.end(), key) != seen.end())
            continue;
        seen.push_back(key);
        const Vec3 &a = mesh.corner(t, 0), &b = mesh.corner(t, 1), &c = mesh.corner(t, 2);
        if (segmentIntersectsTriangle(p, p, a, b, c))
            return true;
        if (segmentIntersectsTriangle(p, q, a, b, c))
            odd = !odd;
    }
    return odd;
}

Vec3 randomDirection(test::TestRandom &rng)
{
    std::normal_distribution<double> normal;
    for (;;)
    {
        const Vec3 d(normal(rng), normal(rng), normal(rng));
        if (d.norm() > 1e-3)
            return d.normalized();
    }
}

// Inside any closed component by plain parity; two random rays must agree (a disagreement would
// mean one of them grazed an edge).
bool bruteForceInsideAny(const TriangleMesh &mesh, const std::vector<MeshComponent> &components, const Vec3 &p,
                         test::TestRandom &rng)
{
    const BoundingBox box = mesh.bounds();
    const double reach = 2.0 * (box.max - box.min).norm() + 1.0;
    const Vec3 d1 = randomDirection(rng), d2 = randomDirection(rng);
    bool inside = false;
    for (const MeshComponent &c : components)
    {
        if (!c.closed)
            continue;
        const bool first = bruteForceInside(mesh, c, p, d1, reach);
        EXPECT_EQ(first, bruteForceInside(mesh, c, p, d2, reach)) << "at (" << p.transpose() << ")";
        inside = inside || first;
    }
    return inside;
}

void checkOmplappEnvironment(const std::string &path, double expectedFraction)
{
    const auto mesh = std::make_shared<TriangleMesh>(*loadMesh(path, MeshRole::Environment).mesh);
    const SolidQuery query(mesh);
    const BoundingBox box = mesh->bounds();

    std::size_t closedTriangles = 0, largest = 0;
    for (const MeshComponent &c : query.components())
        if (c.closed)
        {
            closedTriangles += c.triangles.size();
            largest = std::max(largest, c.triangles.size());
        }
    const double fraction = query.solidVolumeFraction(200000, 42);
    std::cout << path << ": " << mesh->triangleCount() << " triangles, " << query.components().size() << " components, "
              << query.closedComponentCount() << " closed (" << closedTriangles << " triangles, largest " << largest
              << "); solid volume fraction " << fraction << "\n";
    EXPECT_GT(query.closedComponentCount(), 0u);
    EXPECT_NEAR(fraction, expectedFraction, 0.06);

    // solidVolumeFraction on 3000 points equals plain parity over all triangles on the same
    // points (drawn as documented), and point by point the two agree.
    const std::size_t n = 3000;
    const std::uint64_t seed = 2024;
    std::mt19937_64 sampler(seed);
    const auto unit = [&sampler] { return double(sampler() >> 11) * 0x1.0p-53; };
    test::TestRandom rng(99);
    std::size_t bruteInside = 0, mismatches = 0;
    for (std::size_t i = 0; i < n; ++i)
    {
        const double u = unit(), v = unit(), w = unit();
        const Vec3 p(box.min.x() + u * (box.max.x() - box.min.x()), box.min.y() + v * (box.max.y() - box.min.y()),
                     box.min.z() + w * (box.max.z() - box.min.z()));
        const bool expected = bruteForceInsideAny(*mesh, query.components(), p, rng);
        bruteInside += expected ? 1 : 0;
        if (query.insideAnySolid(p) != expected && ++mismatches <= 10)
            ADD_FAILURE() << "point (" << p.transpose() << ") should be " << (expected ? "inside" : "outside");
    }
    EXPECT_EQ(mismatches, 0u);
    EXPECT_EQ(query.solidVolumeFraction(n, seed), double(bruteInside) / double(n));

    // Vertices are on the surface; points just beside a vertex along x send the +x ray through
    // it, and points beside an edge midpoint graze that edge.
    mismatches = 0;
    std::size_t checked = 0;
    for (const MeshComponent &c : query.components())
    {
        if (!c.closed)
            continue;
        for (std::size_t k = 0; k < c.triangles.size(); k += 7)
        {
            const auto &t = mesh->triangles[c.triangles[k]];
            const Vec3 &a = mesh->vertices[t[0]], &b = mesh->vertices[t[1]];
            EXPECT_TRUE(query.insideAnySolid(a));
            const double step = 1e-3 * (box.max - box.min).norm();
            for (const Vec3 &p : {Vec3(a - Vec3(step, 0, 0)), Vec3(a + Vec3(step, 0, 0)), Vec3(0.5 * (a + b)),
                                  Vec3(0.5 * (a + b) - Vec3(step, 0, 0)), Vec3(0.5 * (a + b) - Vec3(0, step, 0))})
            {
                ++checked;
                const bool expected = bruteForceInsideAny(*mesh, query.components(), p, rng);
                if (query.insideAnySolid(p) != expected && ++mismatches <= 10)
                    ADD_FAILURE() << "point (" << p.transpose() << ") should be " << (expected ? "inside" : "outside");
            }
        }
    }
    EXPECT_EQ(mismatches, 0u) << "of " << checked << " points near vertices and edges";
}
}  // namespace

TEST(SolidQuery, HomeEnvironment)
{
    HYBRIDCD_REQUIRE_OMPLAPP(path, "3D/Home_env.dae");
    checkOmplappEnvironment(path, 0.32);
}

TEST(SolidQuery, AbstractEnvironment)
{
    HYBRIDCD_REQUIRE_OMPLAPP(path, "3D/Abstract_env.dae");
    checkOmplappEnvironment(path, 0.18);
}
