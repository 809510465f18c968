// SPDX-License-Identifier: BSD-3-Clause
#include "support/test_support.h"

#include "hybridcd/bv/box_lanes.h"
#include "hybridcd/bvh/volume_tree.h"
#include "hybridcd/io/mesh_loader.h"
#include "hybridcd/narrowphase/gjk.h"

#include <gtest/gtest.h>

using namespace hcd;

namespace
{
// Every node's box holds every corner of every triangle below it (checked in the box frame).
template <class Volume, class Contains>
void expectContainsSubtree(const VolumeTree<Volume> &tree, const Contains &contains)
{
    const auto &nodes = tree.nodes();
    std::vector<std::size_t> counted(nodes.size(), 0);
    for (std::size_t i = 0; i < nodes.size(); ++i)
    {
        const auto &n = nodes[i];
        for (std::uint32_t k = 0; k < n.triangleCount; ++k)
        {
            const std::uint32_t t = tree.triangleOrder()[n.firstTriangle + k];
            for (int c = 0; c < 3; ++c)
                ASSERT_TRUE(contains(n.volume, tree.mesh().corner(t, c))) << "node " << i << " triangle " << t;
        }
        if (!n.isLeaf())
        {
            // Children partition the parent's run.
            const auto &l = nodes[n.firstChild], &r = nodes[n.firstChild + 1];
            EXPECT_EQ(l.firstTriangle, n.firstTriangle);
            EXPECT_EQ(l.triangleCount + r.triangleCount, n.triangleCount);
            EXPECT_EQ(r.firstTriangle, l.firstTriangle + l.triangleCount);
        }
    }
    EXPECT_EQ(nodes.front().triangleCount, tree.mesh().triangleCount());
}
const auto obbContains = [](const Obb &b, const Vec3 &p) { return b.contains(p); };

// `count` small triangles (corners within 0.5 of a centre) scattered over [-10, 10]^3.
std::shared_ptr<TriangleMesh> randomSoup(test::TestRandom &rng, int count)
{
    std::uniform_real_distribution<double> u(-10, 10), s(-0.5, 0.5);
    auto mesh = std::make_shared<TriangleMesh>();
    for (int t = 0; t < count; ++t)
    {
        const Vec3 c(u(rng), u(rng), u(rng));
        for (int k = 0; k < 3; ++k)
            mesh->vertices.push_back(c + Vec3(s(rng), s(rng), s(rng)));
        mesh->triangles.push_back({std::uint32_t(3 * t), std::uint32_t(3 * t + 1), std::uint32_t(3 * t + 2)});
    }
    return mesh;
}

// A flat square grid of side-1 cells, `cells` on a side, scaled by `scale` and moved far from the origin.
std::shared_ptr<TriangleMesh> flatGrid(int cells, double scale)
{
    const std::uint32_t n = std::uint32_t(cells) + 1;
    auto mesh = std::make_shared<TriangleMesh>();
    for (std::uint32_t i = 0; i < n; ++i)
        for (std::uint32_t j = 0; j < n; ++j)
            mesh->vertices.push_back(scale * Vec3(i, j, 0.0) + Vec3(3e3 * scale, -7e2 * scale, 0));
    for (std::uint32_t i = 0; i + 1 < n; ++i)
        for (std::uint32_t j = 0; j + 1 < n; ++j)
        {
            mesh->triangles.push_back({i * n + j, (i + 1) * n + j, i * n + j + 1});
            mesh->triangles.push_back({(i + 1) * n + j, (i + 1) * n + j + 1, i * n + j + 1});
        }
    return mesh;
}
}  // namespace

TEST(ObbTree, ContainsEveryTriangleOfItsSubtreeOnRandomSoup)
{
    test::TestRandom rng(7);
    const auto mesh = randomSoup(rng, 2000);
    for (unsigned leaf : {1u, 4u})
        expectContainsSubtree(VolumeTree<Obb>(mesh, leaf), obbContains);
}

TEST(ObbTree, ContainsEveryTriangleOnFlatAndHugeMeshes)
{
    // Coplanar triangles give zero-thickness boxes; huge coordinates stress the containment margin.
    for (double scale : {1e-6, 1.0, 1e9})
    {
        auto mesh = std::make_shared<TriangleMesh>();
        for (int i = 0; i < 30; ++i)
            for (int j = 0; j < 30; ++j)
                mesh->vertices.push_back(scale * Vec3(i, j, 0.0) + Vec3(3e3 * scale, 0, 0));
        for (std::uint32_t i = 0; i + 1 < 30; ++i)
            for (std::uint32_t j = 0; j + 1 < 30; ++j)
            {
                mesh->triangles.push_back({i * 30 + j, (i + 1) * 30 + j, i * 30 + j + 1});
                mesh->triangles.push_back({(i + 1) * 30 + j, (i + 1) * 30 + j + 1, i * 30 + j + 1});
            }
        expectContainsSubtree(VolumeTree<Obb>(mesh), obbContains);
    }
}

TEST(ObbTree, ContainsEveryTriangleOnOmplAppMeshes)
{
    HYBRIDCD_REQUIRE_OMPLAPP(cfg, "3D/alpha_env-1.5.dae");
    auto mesh = std::make_shared<TriangleMesh>(*loadMesh(cfg, MeshRole::Environment).mesh);
    expectContainsSubtree(VolumeTree<Obb>(mesh), obbContains);
}

namespace
{
const auto aabbContains = [](const Aabb &b, const Vec3 &p) { return b.contains(p); };

// Two rows of 100 small triangles, each row 40 long in x, 10 apart in y: the mesh's longest
// direction is x, yet the cheap split puts each row in a child of its own.
std::shared_ptr<TriangleMesh> twoRows()
{
    auto mesh = std::make_shared<TriangleMesh>();
    for (double y : {-5.0, 5.0})
        for (int i = 0; i < 100; ++i)
        {
            const double x = -20.0 + 0.4 * i;
            const std::uint32_t v = std::uint32_t(mesh->vertices.size());
            mesh->vertices.push_back(Vec3(x, y, 0.0));
            mesh->vertices.push_back(Vec3(x + 0.3, y + 0.5, 0.0));
            mesh->vertices.push_back(Vec3(x + 0.1, y, 0.5));
            mesh->triangles.push_back({v, v + 1, v + 2});
        }
    return mesh;
}

// Whether each child of the root holds the triangles of one row only.
template <class Volume>
bool rootSplitsTheRows(const VolumeTree<Volume> &tree)
{
    const auto &nodes = tree.nodes();
    for (int child = 0; child < 2; ++child)
    {
        const auto &n = nodes[std::size_t(nodes[0].firstChild + child)];
        int rowsSeen[2] = {0, 0};
        for (std::uint32_t k = 0; k < n.triangleCount; ++k)
            ++rowsSeen[tree.mesh().corner(tree.triangleOrder()[n.firstTriangle + k], 0).y() > 0.0 ? 1 : 0];
        if (rowsSeen[0] > 0 && rowsSeen[1] > 0)
            return false;
    }
    return true;
}
}  // namespace

TEST(AabbTree, ContainsEveryTriangleOfItsSubtree)
{
    // A random soup (one and four triangles per leaf), flat grids at tiny and huge scales, two rows.
    test::TestRandom rng(11);
    std::vector<std::pair<std::shared_ptr<TriangleMesh>, unsigned>> cases{{randomSoup(rng, 2000), 1u}, {twoRows(), 1u}};
    cases.emplace_back(cases.front().first, 4u);
    for (double scale : {1e-6, 1.0, 1e9})
        cases.emplace_back(flatGrid(29, scale), 1u);
    for (const auto &[mesh, leaf] : cases)
        expectContainsSubtree(VolumeTree<Aabb>(mesh, leaf), aabbContains);
}

TEST(BoxTrees, SplitWhereTheChildrenAreSmallestNotAlongTheLongestDirection)
{
    // Gottschalk's rule alone would cut both rows across x; the surface area heuristic separates them.
    const auto mesh = twoRows();
    const VolumeTree<Obb> obbs(mesh);
    const VolumeTree<Aabb> aabbs(mesh);
    expectContainsSubtree(obbs, obbContains);
    EXPECT_TRUE(rootSplitsTheRows(obbs));
    EXPECT_TRUE(rootSplitsTheRows(aabbs));
}

TEST(BoxTrees, SplitPlanesNeedNotPassThroughTheMeanCentroid)
{
    // A row of 100 small triangles over x in [0, 10] and one triangle at x = 100: the mean centroid
    // (x near 6) would cut the row in two and leave one child spanning [6, 100]; the cheapest plane
    // leaves the far triangle alone.
    auto mesh = std::make_shared<TriangleMesh>();
    const auto addTriangle = [&](double x) {
        const std::uint32_t v = std::uint32_t(mesh->vertices.size());
        mesh->vertices.push_back(Vec3(x, 0.0, 0.0));
        mesh->vertices.push_back(Vec3(x + 0.1, 0.5, 0.0));
        mesh->vertices.push_back(Vec3(x, 0.2, 0.4));
        mesh->triangles.push_back({v, v + 1, v + 2});
    };
    for (int i = 0; i < 100; ++i)
        addTriangle(0.1 * i);
    addTriangle(100.0);
    const auto farTriangleAlone = [](const auto &tree) {
        const auto &nodes = tree.nodes();
        const auto &a = nodes[std::size_t(nodes[0].firstChild)], &b = nodes[std::size_t(nodes[0].firstChild + 1)];
        const auto &single = a.triangleCount == 1 ? a : b;
        return single.triangleCount == 1 && tree.triangleOrder()[single.firstTriangle] == 100u;
    };
    const VolumeTree<Obb> obbs(mesh);
    const VolumeTree<Aabb> aabbs(mesh);
    expectContainsSubtree(obbs, obbContains);
    expectContainsSubtree(aabbs, aabbContains);
    EXPECT_TRUE(farTriangleAlone(obbs));
    EXPECT_TRUE(farTriangleAlone(aabbs));
}

TEST(ObbOverlap, NeverMissesOverlapFoundBySampling)
{
    // Reference: a shared point found by sampling one box proves overlap; the SAT must agree.
    test::TestRandom rng(11);
    std::uniform_real_distribution<double> u(-1, 1), e(0.01, 1.0);
    int overlaps = 0, disjoint = 0;
    for (int trial = 0; trial < 3000; ++trial)
    {
        Obb a, b;
        a.axes = test::randomRotation(rng);
        b.axes = test::randomRotation(rng);
        a.halfExtents = Vec3(e(rng), e(rng), e(rng));
        b.halfExtents = Vec3(e(rng), e(rng), e(rng));
        b.center = Vec3(u(rng), u(rng), u(rng)) * 1.5;
        const RigidTransform pose{test::randomRotation(rng), Vec3(u(rng), u(rng), u(rng))};
        bool sampledHit = false;
        for (int k = 0; k < 400 && !sampledHit; ++k)
        {
            const Vec3 local = a.center + a.axes * a.halfExtents.cwiseProduct(Vec3(u(rng), u(rng), u(rng)));
            sampledHit = b.contains(pose.apply(local));
        }
        const bool sat = obbsOverlap(a, pose, b, 1e-12);
        if (sampledHit)
            ASSERT_TRUE(sat) << "trial " << trial;
        (sat ? overlaps : disjoint) += 1;
    }
    EXPECT_GT(overlaps, 300);
    EXPECT_GT(disjoint, 300);
}

// The distance bound of two boxes against GJK's distance between them (an upper bracket within 1e-10
// of it): never above it, on random boxes, flat ones (a triangle's) and long thin ones, at scales
// 1e-6 to 1e6. The form with a threshold gives either the full bound or a value at least the
// threshold, never more than the full bound.
TEST(ObbDistance, LowerBoundNeverExceedsTheDistance)
{
    test::TestRandom rng(test::seeded(13));
    std::uniform_real_distribution<double> u(-1, 1), e(0.01, 1.0);
    int separated = 0, tight = 0;
    for (int trial = 0; trial < test::cases(4000); ++trial)
    {
        const double scale = std::pow(10.0, double(trial % 13) - 6.0);
        Obb a, b;
        a.axes = test::randomRotation(rng);
        b.axes = test::randomRotation(rng);
        a.halfExtents = scale * Vec3(e(rng), e(rng), trial % 3 == 0 ? 1e-9 : e(rng));
        b.halfExtents = scale * Vec3(trial % 4 == 1 ? 30.0 : e(rng), e(rng), trial % 5 == 0 ? 1e-9 : e(rng));
        a.center = scale * 2.0 * Vec3(u(rng), u(rng), u(rng));
        b.center = scale * 2.0 * Vec3(u(rng), u(rng), u(rng));
        const Shape boxA = Shape::box(a.halfExtents), boxB = Shape::box(b.halfExtents);
        GjkWarmStart warm;
        const GjkResult exact = gjkDistance(GjkBody::placed(boxA, {a.axes, a.center}),
                                            GjkBody::placed(boxB, {b.axes, b.center}), GjkRequest{}, warm);
        const double bound = obbDistanceLowerBound(a, b, 0.0);
        ASSERT_LE(bound, exact.upperBound * (1.0 + 1e-9) + 1e-12 * scale) << "trial " << trial;
        separated += exact.upperBound > 0.0 ? 1 : 0;
        tight += bound >= 0.7 * exact.upperBound ? 1 : 0;
        for (const double enough : {0.0, 0.5 * bound, bound, 2.0 * bound + scale})
        {
            const double early = obbDistanceLowerBound(a, b, 0.0, enough);
            ASSERT_LE(early, bound) << "trial " << trial;
            ASSERT_TRUE(early == bound || early >= enough) << "trial " << trial;
        }
    }
    EXPECT_GT(separated, test::cases(4000) / 2);
    EXPECT_GT(tight, separated / 2);  // a bound that is not idle
}

// Two thin rods whose nearest points are on their long edges, apart along the edges' common
// perpendicular, which is a face axis of neither box: only the edge-edge axis gives a tight bound.
// The edge axes are compared by squares, so at tiny scales, where those squares underflow, the bound
// may only lose tightness, never exceed the distance; above that it finds the axis, up to the
// scales distances are computed at (about 1e75: triangle distances multiply four coordinates). The
// SIMD lanes give the same number.
TEST(ObbDistance, EdgeAxisBoundAtHugeAndTinyScales)
{
    const Vec3 u = Vec3(-1, 1, 0).normalized(), v = Vec3(1, 1, -2).normalized();
    const Vec3 f1 = Vec3(1, 1, 1).normalized();
    const double phi = 0.5;  // the rod's cross axes turned away from u
    const Vec3 f2 = std::cos(phi) * u + std::sin(phi) * v, f3 = f1.cross(f2);
    for (const double scale : {1e-165, 1e-160, 1e-150, 1e-100, 1e-6, 1.0, 1e6, 1e40, 1e75})
    {
        SCOPED_TRACE(scale);
        const double thin = 1e-3, gapBetween = 0.5;
        Obb a;
        a.axes = Mat3::Identity();
        a.center = Vec3::Zero();
        a.halfExtents = scale * Vec3(thin, thin, 1.0);  // along z
        Obb b;
        b.axes.col(0) = f1;
        b.axes.col(1) = f2;
        b.axes.col(2) = f3;
        b.halfExtents = scale * Vec3(1.0, thin, thin);  // along f1
        // Slid along both rods (off the line through the centres, which would find the gap too); the
        // nearest points stay inside both.
        b.center = scale * ((gapBetween + 4.0 * thin) * u + 0.3 * f1 + 0.4 * Vec3(0, 0, 1));
        // The distance of the rods' axes (segments) less both rods' reach across them bounds the
        // boxes' distance from below; their axes' distance bounds it from above.
        const double axesApart = scale * (gapBetween + 4.0 * thin);
        const double bound = obbDistanceLowerBound(a, b, 0.0);
        ASSERT_LE(bound, axesApart * (1.0 + 1e-12));
        ASSERT_GE(bound, 0.0);
        if (scale >= 1e-150)
            EXPECT_GE(bound, axesApart - scale * 4.0 * thin * 1.8);  // the edge axis, not a face axis
        ObbLanes lanes;
        lanes.add(b, b.halfExtents.norm(), 0);
        lanes.fill();
        double simd[ObbLanes::kLanes];
        lanesDistanceLowerBound(lanes, a, a.halfExtents.norm(), 0.0, simd);
        EXPECT_EQ(simd[0], std::max(bound, (a.center - b.center).norm() - a.halfExtents.norm() - b.halfExtents.norm()));
    }
}

// k-DOP trees build each parent from its children's slabs: every node's volume is still fit() of
// its subtree's corners, bit for bit, on a random soup and on flat meshes at three scales.
template <int K>
void expectKDopNodesEqualTheirFit(const VolumeTree<KDop<K>> &tree)
{
    expectContainsSubtree(tree, [](const KDop<K> &d, const Vec3 &p) { return d.contains(p); });
    for (const auto &n : tree.nodes())
    {
        std::vector<Vec3> corners;
        for (std::uint32_t k = 0; k < n.triangleCount; ++k)
            for (int c = 0; c < 3; ++c)
                corners.push_back(tree.mesh().corner(tree.triangleOrder()[n.firstTriangle + k], c));
        const KDop<K> fitted = KDop<K>::fit(corners);
        ASSERT_EQ(n.volume.lo, fitted.lo);
        ASSERT_EQ(n.volume.hi, fitted.hi);
        ASSERT_EQ(n.volume.center, fitted.center);
        ASSERT_EQ(n.radius, VolumeTraits<KDop<K>>::radius(fitted));
    }
}

TEST(KDopTree, NodesEqualTheFitOfTheirSubtree)
{
    test::TestRandom rng(test::seeded(77));
    std::vector<std::shared_ptr<TriangleMesh>> meshes = {randomSoup(rng, 3000)};
    for (double scale : {1e-6, 1.0, 1e9})
        meshes.push_back(flatGrid(39, scale));
    for (const auto &mesh : meshes)
        for (unsigned leaf : {1u, 3u})
        {
            expectKDopNodesEqualTheirFit(VolumeTree<KDop<14>>(mesh, leaf));
            expectKDopNodesEqualTheirFit(VolumeTree<KDop<18>>(mesh, leaf));
            expectKDopNodesEqualTheirFit(VolumeTree<KDop<26>>(mesh, leaf));
        }
}
