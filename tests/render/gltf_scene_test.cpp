// SPDX-License-Identifier: BSD-3-Clause
// The .glb read back by tinygltf: its nodes, meshes and the path's keyframes.
#include "support/test_support.h"

#include "hybridcd/render/gltf_scene.h"

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cstring>
#include <fstream>

using namespace hcd;
using namespace hcd::render;

namespace
{
tinygltf::Model load(const std::string &bytes)
{
    const std::string file = test::writeTempFile("scene.glb", "");
    std::ofstream(file, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    std::string error, warning;
    EXPECT_TRUE(loader.LoadBinaryFromFile(&model, &error, &warning, file)) << error << warning;
    EXPECT_EQ(error, "");
    return model;
}

// The floats of accessor `index` (tightly packed, as the writer stores them).
std::vector<float> floats(const tinygltf::Model &model, int index)
{
    const tinygltf::Accessor &a = model.accessors.at(std::size_t(index));
    EXPECT_EQ(a.componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
    const tinygltf::BufferView &v = model.bufferViews.at(std::size_t(a.bufferView));
    const int components = tinygltf::GetNumComponentsInType(std::uint32_t(a.type));
    std::vector<float> out(a.count * std::size_t(components));
    std::memcpy(out.data(), model.buffers.at(std::size_t(v.buffer)).data.data() + v.byteOffset + a.byteOffset,
                out.size() * sizeof(float));
    return out;
}

std::size_t vertexCount(const tinygltf::Model &model, int node)
{
    const tinygltf::Mesh &mesh = model.meshes.at(std::size_t(model.nodes.at(std::size_t(node)).mesh));
    return model.accessors.at(std::size_t(mesh.primitives.at(0).attributes.at("POSITION"))).count;
}

int nodeNamed(const tinygltf::Model &model, const std::string &name)
{
    for (std::size_t i = 0; i < model.nodes.size(); ++i)
        if (model.nodes[i].name == name)
            return int(i);
    ADD_FAILURE() << "no node " << name;
    return -1;
}
}  // namespace

TEST(GltfScene, PathBecomesOneKeyframePerStateOnTheRobotNode)
{
    const TriangleMesh environment = test::boxMesh(Vec3(-10, -10, -1), Vec3(10, 10, 0));
    TriangleMesh robot = test::boxMesh(Vec3(-1, -0.5, 0), Vec3(1, 0.5, 0.5));
    robot.triangles.pop_back();  // so that the two meshes differ in size
    std::vector<RigidTransform> path;
    test::TestRandom rng(test::seeded(5));
    std::uniform_real_distribution<double> coordinate(-5.0, 5.0);
    for (int i = 0; i < 7; ++i)
        path.push_back({test::randomRotation(rng), Vec3(coordinate(rng), coordinate(rng), coordinate(rng))});
    path.push_back(path.back());  // a repeated state still gets its own, later keyframe

    GltfRequest request;
    request.environment = &environment;
    request.robot = &robot;
    request.path = path;
    const tinygltf::Model model = load(glbBytes(request));

    ASSERT_EQ(model.nodes.size(), 3u);
    ASSERT_EQ(model.scenes.size(), 1u);
    EXPECT_EQ(model.scenes[0].nodes, std::vector<int>{0});
    const int robotNode = nodeNamed(model, "robot"), environmentNode = nodeNamed(model, "environment");
    EXPECT_EQ(model.nodes[0].children.size(), 2u);
    EXPECT_EQ(vertexCount(model, environmentNode), environment.vertices.size());
    EXPECT_EQ(vertexCount(model, robotNode), robot.vertices.size());
    const tinygltf::Mesh &robotMesh = model.meshes.at(std::size_t(model.nodes[std::size_t(robotNode)].mesh));
    EXPECT_EQ(model.accessors.at(std::size_t(robotMesh.primitives[0].indices)).count, robot.triangles.size() * 3);
    // Vertices as written, in the robot's frame.
    const std::vector<float> positions = floats(model, robotMesh.primitives[0].attributes.at("POSITION"));
    for (std::size_t i = 0; i < robot.vertices.size(); ++i)
        for (int k = 0; k < 3; ++k)
            EXPECT_EQ(positions[3 * i + std::size_t(k)], float(robot.vertices[i][k]));

    ASSERT_EQ(model.animations.size(), 1u);
    const tinygltf::Animation &animation = model.animations[0];
    ASSERT_EQ(animation.channels.size(), 2u);
    for (const tinygltf::AnimationChannel &channel : animation.channels)
    {
        EXPECT_EQ(channel.target_node, robotNode);
        const tinygltf::AnimationSampler &sampler = animation.samplers.at(std::size_t(channel.sampler));
        const std::vector<float> times = floats(model, sampler.input);
        ASSERT_EQ(times.size(), path.size());
        EXPECT_EQ(times.front(), 0.0f);
        for (std::size_t i = 1; i < times.size(); ++i)
            EXPECT_GT(times[i], times[i - 1]);
        const std::vector<float> values = floats(model, sampler.output);
        if (channel.target_path == "translation")
        {
            ASSERT_EQ(values.size(), 3 * path.size());
            for (std::size_t i = 0; i < path.size(); ++i)
                for (int k = 0; k < 3; ++k)
                    EXPECT_EQ(values[3 * i + std::size_t(k)], float(path[i].translation[k])) << i;
        }
        else
        {
            ASSERT_EQ(channel.target_path, "rotation");
            ASSERT_EQ(values.size(), 4 * path.size());
            for (std::size_t i = 0; i < path.size(); ++i)
            {
                // glTF's (x, y, z, w); q and -q are the same rotation.
                const Eigen::Quaterniond q(values[4 * i + 3], values[4 * i], values[4 * i + 1], values[4 * i + 2]);
                EXPECT_NEAR(q.norm(), 1.0, 1e-6);
                EXPECT_LT((q.normalized().toRotationMatrix() - path[i].rotation).norm(), 1e-6) << i;
                if (i > 0)  // consecutive keyframes on the same hemisphere: interpolation takes the short way
                    EXPECT_GE(values[4 * i] * values[4 * i - 4] + values[4 * i + 1] * values[4 * i - 3] +
                                  values[4 * i + 2] * values[4 * i - 2] + values[4 * i + 3] * values[4 * i - 1],
                              0.0f);
            }
        }
    }
    // At rest the robot stands at the first state.
    const tinygltf::Node &r = model.nodes[std::size_t(robotNode)];
    ASSERT_EQ(r.translation.size(), 3u);
    for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(r.translation[std::size_t(k)], path[0].translation[k], 1e-12);
}

TEST(GltfScene, WithoutPathTheRobotStandsAtTheStart)
{
    const TriangleMesh robot = test::boxMesh(Vec3(-1, -1, -1), Vec3(1, 1, 1));
    GltfRequest request;
    request.robot = &robot;
    request.start = RigidTransform::fromPlanarPose(3, 4, M_PI / 2);
    const tinygltf::Model model = load(glbBytes(request));
    EXPECT_EQ(model.nodes.size(), 2u);  // no environment node
    EXPECT_TRUE(model.animations.empty());
    const tinygltf::Node &r = model.nodes.at(std::size_t(nodeNamed(model, "robot")));
    EXPECT_EQ(r.translation, (std::vector<double>{3, 4, 0}));
    ASSERT_EQ(r.rotation.size(), 4u);
    EXPECT_NEAR(std::abs(r.rotation[2]), std::sqrt(0.5), 1e-12);  // a quarter turn about z
    EXPECT_NEAR(std::abs(r.rotation[3]), std::sqrt(0.5), 1e-12);
    // The root turns z-up into glTF's y-up: -90 degrees about x.
    const tinygltf::Node &root = model.nodes[0];
    ASSERT_EQ(root.rotation.size(), 4u);
    EXPECT_NEAR(root.rotation[0], -std::sqrt(0.5), 1e-12);
    EXPECT_NEAR(root.rotation[3], std::sqrt(0.5), 1e-12);
    EXPECT_THROW(glbBytes(GltfRequest{}), std::invalid_argument);
}
