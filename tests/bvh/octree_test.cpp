// SPDX-License-Identifier: BSD-3-Clause
// The environment octree: the triangle/cube test against an exact reference (a corner inside the
// cube, or the triangle meeting one of the cube's twelve surface triangles), including triangles
// lying on faces, along edges and at corners; and every leaf lists every triangle touching it.
#include "support/test_support.h"

#include "hybridcd/bvh/octree.h"
#include "hybridcd/geometry/triangle_distance.h"
#include "hybridcd/geometry/triangle_intersection.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace hcd;

namespace
{
double uniform(test::TestRandom &rng, double lo, double hi)
{
    return std::uniform_real_distribution<double>(lo, hi)(rng);
}

// The cube's surface as twelve triangles.
std::vector<std::array<Vec3, 3>> cubeTriangles(const Vec3 &c, double h)
{
    const auto corner = [&](int i) -> Vec3 { return c + h * Vec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1); };
    const int faces[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};
    std::vector<std::array<Vec3, 3>> out;
    for (const auto &f : faces)
    {
        out.push_back({corner(f[0]), corner(f[1]), corner(f[2])});
        out.push_back({corner(f[0]), corner(f[2]), corner(f[3])});
    }
    return out;
}

// Exact: a corner of the triangle in the closed cube, or the triangle meeting its surface.
bool exactlyTouches(const Vec3 &a, const Vec3 &b, const Vec3 &c, const Vec3 &center, double h)
{
    for (const Vec3 *p : {&a, &b, &c})
        if (((*p - center).cwiseAbs().array() <= h).all())
            return true;
    for (const auto &t : cubeTriangles(center, h))
        if (trianglesIntersect(a, b, c, t[0], t[1], t[2]))
            return true;
    return false;
}

double distanceToCube(const Vec3 &a, const Vec3 &b, const Vec3 &c, const Vec3 &center, double h)
{
    double best = std::numeric_limits<double>::infinity();
    for (const auto &t : cubeTriangles(center, h))
        best = std::min(best, triangleDistance(a, b, c, t[0], t[1], t[2]));
    return best;
}
}  // namespace

TEST(Octree, TriangleCubeTestMatchesExactReference)
{
    test::TestRandom rng(test::seeded(4101));
    int touching = 0, apart = 0;
    for (int trial = 0; trial < test::cases(4000); ++trial)
    {
        const double scale = std::pow(10.0, double(trial % 9) - 4.0);
        const Vec3 center = scale * Vec3(uniform(rng, -5, 5), uniform(rng, -5, 5), uniform(rng, -5, 5));
        const double h = scale * uniform(rng, 0.1, 1.0);
        const auto corner = [&](int i) -> Vec3 {
            return center + h * Vec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
        };
        Vec3 p[3];
        const int shape = trial % 4;
        for (Vec3 &q : p)
            q = center + scale * Vec3(uniform(rng, -2, 2), uniform(rng, -2, 2), uniform(rng, -2, 2));
        if (shape == 1)
            for (Vec3 &q : p)
                q.z() = center.z() + h;  // in the plane of a face
        else if (shape == 2)
            p[0] = corner(int(rng() % 8));  // a corner of the triangle on a corner of the cube
        else if (shape == 3)
        {
            // An edge of the triangle along the line of a cube edge, the rest outside.
            const Vec3 e0 = corner(0), e1 = corner(1);
            p[0] = e0 + uniform(rng, -1, 2) * (e1 - e0);
            p[1] = e0 + uniform(rng, -1, 2) * (e1 - e0);
            p[2] = e0 - scale * Vec3(0, uniform(rng, 0, 2), uniform(rng, 0, 2));
        }
        const double tolerance = 1e-9 * (center.cwiseAbs().maxCoeff() + 3 * scale);
        const bool exact = exactlyTouches(p[0], p[1], p[2], center, h);
        const bool reported = triangleTouchesCube(p[0], p[1], p[2], center, h, tolerance);
        if (exact)
        {
            ASSERT_TRUE(reported) << "a touching triangle was dropped, trial " << trial;
            ++touching;
        }
        else if (distanceToCube(p[0], p[1], p[2], center, h) > 1e-6 * scale)
        {
            EXPECT_FALSE(reported) << "separated by more than the tolerance, trial " << trial;
            ++apart;
        }
    }
    EXPECT_GT(touching, test::cases(4000) / 5);
    EXPECT_GT(apart, test::cases(4000) / 5);
}

namespace
{
// Each leaf lists exactly the triangles that touch it (and possibly a few within the rounding
// tolerance), children nest in their parents, and every triangle is listed somewhere.
void checkLeaves(const Octree &tree, const TriangleMesh &mesh)
{
    const auto &cells = tree.cells();
    std::vector<int> listedIn(mesh.triangleCount(), 0);
    std::size_t leaves = 0;
    for (const Octree::Cell &cell : cells)
    {
        if (!cell.isLeaf())
        {
            ASSERT_GE(cell.childCount, 1u);
            ASSERT_LE(cell.childCount, 8u);
            for (std::uint32_t k = 0; k < cell.childCount; ++k)
            {
                const Octree::Cell &child = cells[std::size_t(cell.firstChild) + k];
                EXPECT_EQ(child.halfSide, 0.5 * cell.halfSide);
                EXPECT_LE((child.center - cell.center).cwiseAbs().maxCoeff(), 0.5 * cell.halfSide * (1 + 1e-12));
            }
            continue;
        }
        ++leaves;
        std::vector<std::uint32_t> listed(tree.triangleReferences().begin() + cell.firstTriangle,
                                          tree.triangleReferences().begin() + cell.firstTriangle + cell.triangleCount);
        std::sort(listed.begin(), listed.end());
        for (std::uint32_t t = 0; t < mesh.triangleCount(); ++t)
        {
            const bool inList = std::binary_search(listed.begin(), listed.end(), t);
            listedIn[t] += inList ? 1 : 0;
            if (exactlyTouches(mesh.corner(t, 0), mesh.corner(t, 1), mesh.corner(t, 2), cell.center, cell.halfSide))
                ASSERT_TRUE(inList) << "triangle " << t << " touches a leaf that does not list it";
        }
    }
    EXPECT_EQ(leaves, tree.leafCount());
    for (int n : listedIn)
        EXPECT_GE(n, 1);
    // Every point of the environment is inside the root cube.
    for (const Vec3 &v : mesh.vertices)
        EXPECT_LE((v - cells[0].center).cwiseAbs().maxCoeff(), cells[0].halfSide);
}

// A soup of triangles of the given sizes, centred within [-10, 10]^3.
std::shared_ptr<TriangleMesh> soup(test::TestRandom &rng, int count, double small, double large, int largeEvery)
{
    auto mesh = std::make_shared<TriangleMesh>();
    for (int t = 0; t < count; ++t)
    {
        const Vec3 c(uniform(rng, -10, 10), uniform(rng, -10, 10), uniform(rng, -10, 10));
        const double size = t % largeEvery == 0 ? large : small;
        for (int k = 0; k < 3; ++k)
            mesh->vertices.push_back(c + size * Vec3(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)));
        mesh->triangles.push_back({std::uint32_t(3 * t), std::uint32_t(3 * t + 1), std::uint32_t(3 * t + 2)});
    }
    return mesh;
}
}  // namespace

TEST(Octree, LeavesListEveryTouchingTriangle)
{
    // Small and a few large triangles, so cells are split and triangles span cells.
    test::TestRandom rng(test::seeded(4102));
    const auto mesh = soup(rng, 400, 0.8, 8.0, 40);
    const Octree tree(mesh, {6, 4});
    ASSERT_GT(tree.cells().size(), 50u);
    checkLeaves(tree, *mesh);
}

TEST(Octree, CrossingTrianglesStayWithinTheMemoryBound)
{
    // Large triangles crossing each other everywhere: splitting never parts them, and the cells
    // stop at 32 listings per triangle on average while still listing every touching triangle.
    test::TestRandom rng(test::seeded(4103));
    const auto mesh = soup(rng, 150, 12.0, 12.0, 1);
    const Octree tree(mesh, {10, 1});
    EXPECT_LE(tree.triangleReferences().size(), 33 * mesh->triangleCount());
    checkLeaves(tree, *mesh);
}
