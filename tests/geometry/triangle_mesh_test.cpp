// SPDX-License-Identifier: BSD-3-Clause
#include "support/test_support.h"

#include "hybridcd/geometry/triangle_mesh.h"

#include <gtest/gtest.h>

using namespace hcd;

TEST(TriangleMesh, BoxIsClosedAndOpenBoxIsNot)
{
    TriangleMesh box = test::boxMesh(Vec3(0, 0, 0), Vec3(1, 2, 3));
    EXPECT_TRUE(isClosed(box));
    box.triangles.pop_back();
    EXPECT_FALSE(isClosed(box));
}

TEST(TriangleMesh, ReversedDuplicatesDoNotBreakClosedness)
{
    // SketchUp exports every face twice, once reversed: closedness is judged without the copies.
    TriangleMesh box = test::boxMesh(Vec3(0, 0, 0), Vec3(1, 1, 1));
    const auto n = box.triangles.size();
    for (std::size_t i = 0; i < n; ++i)
    {
        auto t = box.triangles[i];
        box.triangles.push_back({t[0], t[2], t[1]});
    }
    EXPECT_TRUE(isClosed(box));
}

TEST(TriangleMesh, WeldMergesIdenticalVerticesAndDropsDegenerates)
{
    TriangleMesh m;
    m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(0, 0, 0)};
    m.triangles = {{0, 1, 2}, {3, 4, 5}, {0, 5, 1}};  // second is collinear, third repeats a vertex
    EXPECT_EQ(weldAndDropDegenerate(m), 2u);
    ASSERT_EQ(m.triangles.size(), 1u);
    EXPECT_EQ(m.vertices.size(), 4u);
}

TEST(TriangleMesh, BoundsAndRadius)
{
    const TriangleMesh box = test::boxMesh(Vec3(-1, -2, -3), Vec3(1, 2, 3));
    EXPECT_EQ(box.bounds().min, Vec3(-1, -2, -3));
    EXPECT_EQ(box.bounds().max, Vec3(1, 2, 3));
    EXPECT_DOUBLE_EQ(box.radiusAboutOrigin(), std::sqrt(14.0));
    EXPECT_TRUE(TriangleMesh().bounds().empty());
}
