// SPDX-License-Identifier: BSD-3-Clause
// The picture's content: each object lands on the pixels its geometry projects to, in its colour,
// with the background elsewhere; checked on the decoded PNG against a projection worked out here
// from the scene's bounds, independently of the renderer's camera.
#include "support/test_support.h"

#include "hybridcd/render/camera.h"
#include "hybridcd/render/image.h"
#include "hybridcd/render/picture.h"

#include <gtest/gtest.h>
#include <stb_image.h>

#include <cmath>

using namespace hcd;
using namespace hcd::render;

namespace
{
enum class Kind
{
    Background,
    Environment,
    Start,
    Goal,
    Other
};

// Classifies a pixel by colour: white background, grey (r = g = b) environment, green-dominant
// start, red-dominant goal.
Kind classify(const std::uint8_t *p)
{
    const int r = p[0], g = p[1], b = p[2];
    if (r == 255 && g == 255 && b == 255)
        return Kind::Background;
    if (r == g && g == b)
        return Kind::Environment;
    if (g > r + 40 && g > b + 40)
        return Kind::Start;
    if (r > g + 40 && r > b + 40)
        return Kind::Goal;
    return Kind::Other;
}

Image decode(const std::string &png)
{
    int w = 0, h = 0, channels = 0;
    unsigned char *data = stbi_load_from_memory(reinterpret_cast<const unsigned char *>(png.data()), int(png.size()),
                                                &w, &h, &channels, 3);
    EXPECT_NE(data, nullptr) << stbi_failure_reason();
    Image image(w, h);
    if (data)
        std::copy(data, data + std::size_t(w) * std::size_t(h) * 3, image.pixels.begin());
    stbi_image_free(data);
    return image;
}

// A 10 x 10 m floor slab with the robot (a 1 x 1 m block) standing on it at the start and goal.
struct FloorScene
{
    TriangleMesh floor = test::boxMesh(Vec3(0, 0, -1), Vec3(10, 10, 0));
    TriangleMesh robot = test::boxMesh(Vec3(-0.5, -0.5, 0), Vec3(0.5, 0.5, 1));
    Vec3 start{2.5, 3.0, 0.0}, goal{7.5, 6.5, 0.0};

    PictureRequest request(int supersample) const
    {
        PictureRequest r;
        r.environment = &floor;
        r.robot = &robot;
        r.view = View::Top;
        r.width = 240;
        r.height = 200;
        r.supersample = supersample;
        r.placements.push_back({RigidTransform::fromPlanarPose(start.x(), start.y(), 0.0), r.palette.start});
        r.placements.push_back({RigidTransform::fromPlanarPose(goal.x(), goal.y(), 0.0), r.palette.goal});
        return r;
    }
};
}  // namespace

TEST(Picture, TopViewPutsEnvironmentRobotsAndBackgroundWhereTheyProject)
{
    const FloorScene scene;
    for (const int supersample : {1, 2})
    {
        const Image image = decode(encodePng(renderPicture(scene.request(supersample))));
        ASSERT_EQ(image.width, 240);
        ASSERT_EQ(image.height, 200);
        // The fit worked out by hand: the floor's 10 m fill the 200-pixel height less a 4% margin
        // (8 pixels) at each side; x is centred on the 240-pixel width. Pixel centres at +0.5.
        const double scale = (200.0 - 16.0) / 10.0;
        const auto world = [&](int px, int py) {
            return Vec3(5.0 + (px + 0.5 - 120.0) / scale, 5.0 - (py + 0.5 - 100.0) / scale, 0.0);
        };
        // Pixels within 1.5 pixels of an outline may be blended; every other one is checked.
        const double slack = 1.5 / scale;
        const auto inside = [&](const Vec3 &p, const Vec3 &lo, const Vec3 &hi, double grow) {
            return p.x() > lo.x() - grow && p.x() < hi.x() + grow && p.y() > lo.y() - grow && p.y() < hi.y() + grow;
        };
        int counts[5] = {0, 0, 0, 0, 0};
        for (int y = 0; y < image.height; ++y)
            for (int x = 0; x < image.width; ++x)
            {
                const Vec3 p = world(x, y);
                const Kind kind = classify(image.at(x, y));
                ++counts[int(kind)];
                const Vec3 half(0.5, 0.5, 0.0);
                if (inside(p, scene.start - half, scene.start + half, -slack))
                    EXPECT_EQ(kind, Kind::Start) << x << ", " << y;
                else if (inside(p, scene.goal - half, scene.goal + half, -slack))
                    EXPECT_EQ(kind, Kind::Goal) << x << ", " << y;
                else if (inside(p, Vec3(0, 0, 0), Vec3(10, 10, 0), -slack) &&
                         !inside(p, scene.start - half, scene.start + half, slack) &&
                         !inside(p, scene.goal - half, scene.goal + half, slack))
                    EXPECT_EQ(kind, Kind::Environment) << x << ", " << y;
                else if (!inside(p, Vec3(0, 0, 0), Vec3(10, 10, 0), slack))
                    EXPECT_EQ(kind, Kind::Background) << x << ", " << y;
            }
        // Each robot covers about 1 m^2 = scale^2 pixels.
        EXPECT_NEAR(counts[int(Kind::Start)], scale * scale, 4 * scale) << "supersample " << supersample;
        EXPECT_NEAR(counts[int(Kind::Goal)], scale * scale, 4 * scale) << "supersample " << supersample;
    }
}

TEST(Picture, RobotHiddenInsideAClosedRoomShowsThroughFaintly)
{
    // A closed box room around the robot: from any view the robot is behind a wall.
    const TriangleMesh room = test::boxMesh(Vec3(-5, -5, -5), Vec3(5, 5, 5));
    const TriangleMesh robot = test::boxMesh(Vec3(-1, -1, -1), Vec3(1, 1, 1));
    PictureRequest r;
    r.environment = &room;
    r.robot = &robot;
    r.view = View::Isometric;
    r.width = r.height = 100;
    r.placements.push_back({RigidTransform::identity(), r.palette.start, 1.0, 0.3});
    const Image image = renderPicture(r);
    const Camera camera = pictureCamera(r);
    const Vec3 c = camera.project(Vec3::Zero());
    const std::uint8_t *p = image.at(int(c.x()), int(c.y()));
    // Neither the wall's grey nor the robot's full green: a blend, tinted green.
    EXPECT_GT(p[1], p[0]) << int(p[0]) << " " << int(p[1]) << " " << int(p[2]);
    EXPECT_GT(p[1], p[2]);
    EXPECT_LT(p[1] - p[0], int(255 * (r.palette.start.g - r.palette.start.r) * 0.5));
    // Fully hidden (opacity 0 behind walls): the room alone.
    r.placements[0].hiddenOpacity = 0.0;
    const Image hidden = renderPicture(r);
    const std::uint8_t *q = hidden.at(int(c.x()), int(c.y()));
    EXPECT_TRUE(q[0] == q[1] && q[1] == q[2]) << int(q[0]) << " " << int(q[1]) << " " << int(q[2]);
}

TEST(Picture, NearerOpaqueRobotHidesAFartherOne)
{
    // Top view: the goal placement above the start one covers it, whatever the drawing order.
    const TriangleMesh robot = test::boxMesh(Vec3(-1, -1, 0), Vec3(1, 1, 1));
    for (const bool goalFirst : {false, true})
    {
        PictureRequest r;
        r.robot = &robot;
        r.view = View::Top;
        r.width = r.height = 64;
        const RobotPlacement low{RigidTransform::identity(), r.palette.start};
        const RobotPlacement high{RigidTransform{Mat3::Identity(), Vec3(0, 0, 3)}, r.palette.goal};
        r.placements = goalFirst ? std::vector<RobotPlacement>{high, low} : std::vector<RobotPlacement>{low, high};
        const Image image = renderPicture(r);
        EXPECT_EQ(classify(image.at(32, 32)), Kind::Goal) << "goal first: " << goalFirst;
    }
}

TEST(Picture, SameRequestSameBytes)
{
    const FloorScene scene;
    PictureRequest r = scene.request(2);
    r.pathLine = {scene.start, Vec3(5, 5, 1), scene.goal};
    EXPECT_EQ(encodePng(renderPicture(r)), encodePng(renderPicture(r)));
}

TEST(Picture, PngDecodesToTheSamePixels)
{
    Image image(37, 23);
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        image.pixels[i] = std::uint8_t((i * 7919) % 251);
    const Image back = decode(encodePng(image));
    EXPECT_EQ(back.width, 37);
    EXPECT_EQ(back.height, 23);
    EXPECT_EQ(back.pixels, image.pixels);
}

TEST(Picture, BadSizesAndMissingRobotAreRefused)
{
    const FloorScene scene;
    PictureRequest r = scene.request(1);
    r.width = 8;
    EXPECT_THROW(renderPicture(r), std::invalid_argument);
    r = scene.request(1);
    r.robot = nullptr;
    EXPECT_THROW(renderPicture(r), std::invalid_argument);
    EXPECT_THROW(viewByName("diagonal"), std::invalid_argument);
}

TEST(Picture, SamplePathSpreadsPosesByDistanceTravelled)
{
    // Three states: 1 m along x, then 3 m along y with a quarter turn about z.
    const std::vector<RigidTransform> path = {RigidTransform::fromPlanarPose(0, 0, 0),
                                              RigidTransform::fromPlanarPose(1, 0, 0),
                                              RigidTransform::fromPlanarPose(1, 3, M_PI / 2)};
    const std::vector<RigidTransform> samples = samplePath(path, 5);  // every 1 m of the 4 m
    ASSERT_EQ(samples.size(), 5u);
    const Vec3 expected[5] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {1, 2, 0}, {1, 3, 0}};
    const double yaw[5] = {0, 0, M_PI / 6, M_PI / 3, M_PI / 2};
    for (int k = 0; k < 5; ++k)
    {
        EXPECT_LT((samples[k].translation - expected[k]).norm(), 1e-12) << k;
        EXPECT_LT((samples[k].rotation - RigidTransform::fromPlanarPose(0, 0, yaw[k]).rotation).norm(), 1e-12) << k;
    }
    EXPECT_TRUE(samplePath({}, 4).empty());
    EXPECT_EQ(samplePath(path, 1).size(), 1u);
    // A path that turns in place is spread by state index.
    const std::vector<RigidTransform> turn = {RigidTransform::fromPlanarPose(0, 0, 0),
                                              RigidTransform::fromPlanarPose(0, 0, 1.0)};
    const std::vector<RigidTransform> halves = samplePath(turn, 3);
    EXPECT_LT((halves[1].rotation - RigidTransform::fromPlanarPose(0, 0, 0.5).rotation).norm(), 1e-12);
}
