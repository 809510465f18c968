// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/render/gltf_scene.h"

#include "hybridcd/io/atomic_file.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace hcd::render
{
namespace
{
// Appends `count` elements of `type` (VEC3, SCALAR...) to the model's one buffer, 4-byte aligned,
// and returns the accessor's index.
template <class T>
int addAccessor(tinygltf::Model &model, const std::vector<T> &values, int componentType, int type, std::size_t count,
                int target, std::vector<double> min = {}, std::vector<double> max = {})
{
    std::vector<unsigned char> &data = model.buffers[0].data;
    data.resize((data.size() + 3) / 4 * 4, 0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = data.size();
    view.byteLength = values.size() * sizeof(T);
    view.target = target;
    const auto *bytes = reinterpret_cast<const unsigned char *>(values.data());
    data.insert(data.end(), bytes, bytes + view.byteLength);
    model.bufferViews.push_back(view);

    tinygltf::Accessor accessor;
    accessor.bufferView = int(model.bufferViews.size()) - 1;
    accessor.byteOffset = 0;
    accessor.componentType = componentType;
    accessor.type = type;
    accessor.count = count;
    accessor.minValues = std::move(min);
    accessor.maxValues = std::move(max);
    model.accessors.push_back(accessor);
    return int(model.accessors.size()) - 1;
}

int addMesh(tinygltf::Model &model, const TriangleMesh &mesh, const char *name, const std::vector<double> &colour)
{
    std::vector<float> positions;
    positions.reserve(mesh.vertices.size() * 3);
    std::vector<double> lo(3, std::numeric_limits<double>::infinity()), hi(3, -std::numeric_limits<double>::infinity());
    for (const Vec3 &v : mesh.vertices)
        for (int k = 0; k < 3; ++k)
        {
            const float f = float(v[k]);
            positions.push_back(f);
            lo[k] = std::min(lo[k], double(f));
            hi[k] = std::max(hi[k], double(f));
        }
    std::vector<std::uint32_t> indices;
    indices.reserve(mesh.triangles.size() * 3);
    for (const TriangleMesh::Triangle &t : mesh.triangles)
        indices.insert(indices.end(), t.begin(), t.end());

    tinygltf::Material material;
    material.name = std::string(name) + " material";
    material.pbrMetallicRoughness.baseColorFactor = colour;
    material.pbrMetallicRoughness.metallicFactor = 0.0;
    material.pbrMetallicRoughness.roughnessFactor = 0.8;
    material.doubleSided = true;  // meshes need not be consistently oriented
    model.materials.push_back(material);

    tinygltf::Primitive primitive;
    primitive.attributes["POSITION"] = addAccessor(model, positions, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3,
                                                   mesh.vertices.size(), TINYGLTF_TARGET_ARRAY_BUFFER, lo, hi);
    primitive.indices = addAccessor(model, indices, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR,
                                    indices.size(), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    primitive.material = int(model.materials.size()) - 1;
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    tinygltf::Mesh m;
    m.name = name;
    m.primitives.push_back(primitive);
    model.meshes.push_back(m);
    return int(model.meshes.size()) - 1;
}

// (x, y, z, w) as glTF orders quaternions, with the sign of `previous` kept where possible so that
// interpolation between keyframes takes the short way.
std::vector<double> quaternionOf(const RigidTransform &pose, const std::vector<double> *previous)
{
    Eigen::Quaterniond q(pose.rotation);
    q.normalize();
    std::vector<double> xyzw = {q.x(), q.y(), q.z(), q.w()};
    if (previous &&
        xyzw[0] * (*previous)[0] + xyzw[1] * (*previous)[1] + xyzw[2] * (*previous)[2] + xyzw[3] * (*previous)[3] < 0.0)
        for (double &c : xyzw)
            c = -c;
    return xyzw;
}
}  // namespace

std::string glbBytes(const GltfRequest &request)
{
    if (!request.robot)
        throw std::invalid_argument("glbBytes: no robot mesh");
    tinygltf::Model model;
    model.asset.version = "2.0";
    model.asset.generator = "hybridcd render";
    model.buffers.emplace_back();

    tinygltf::Node root;
    root.name = "scene (z up)";
    root.rotation = {-std::sqrt(0.5), 0.0, 0.0, std::sqrt(0.5)};
    model.nodes.push_back(root);

    if (request.environment && !request.environment->empty())
    {
        tinygltf::Node environment;
        environment.name = "environment";
        environment.mesh = addMesh(model, *request.environment, "environment", {0.78, 0.78, 0.78, 1.0});
        model.nodes.push_back(environment);
        model.nodes[0].children.push_back(int(model.nodes.size()) - 1);
    }

    const RigidTransform &first = request.path.empty() ? request.start : request.path.front();
    tinygltf::Node robot;
    robot.name = "robot";
    robot.mesh = addMesh(model, *request.robot, "robot", {0.95, 0.45, 0.10, 1.0});
    robot.translation = {first.translation.x(), first.translation.y(), first.translation.z()};
    robot.rotation = quaternionOf(first, nullptr);
    model.nodes.push_back(robot);
    const int robotNode = int(model.nodes.size()) - 1;
    model.nodes[0].children.push_back(robotNode);

    if (!request.path.empty())
    {
        const std::size_t n = request.path.size();
        // Times follow the distance travelled, with a floor so that they strictly increase.
        std::vector<double> along(n, 0.0);
        for (std::size_t i = 1; i < n; ++i)
            along[i] = along[i - 1] + (request.path[i].translation - request.path[i - 1].translation).norm();
        const double total = along.back();
        const double duration = request.durationSeconds > 0.0 ? request.durationSeconds : 10.0;
        const double floor = duration / double(std::max<std::size_t>(n, 2) - 1) * 1e-3;
        std::vector<float> times(n), translations, rotations;
        double t = 0.0;
        for (std::size_t i = 0; i < n; ++i)
        {
            if (i > 0)
            {
                const double share =
                    total > 0.0 && std::isfinite(total) ? (along[i] - along[i - 1]) / total : 1.0 / double(n - 1);
                t += std::max(floor, duration * share);
            }
            times[i] = float(t);
            if (i > 0 && !(times[i] > times[i - 1]))  // float rounding may merge close times
                times[i] = std::nextafter(times[i - 1], std::numeric_limits<float>::infinity());
        }
        std::vector<double> previous;
        for (std::size_t i = 0; i < n; ++i)
        {
            const RigidTransform &p = request.path[i];
            for (int k = 0; k < 3; ++k)
                translations.push_back(float(p.translation[k]));
            previous = quaternionOf(p, i > 0 ? &previous : nullptr);
            for (double c : previous)
                rotations.push_back(float(c));
        }
        const int input = addAccessor(model, times, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR, n, 0,
                                      {double(times.front())}, {double(times.back())});
        const int translationOutput =
            addAccessor(model, translations, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, n, 0);
        const int rotationOutput =
            addAccessor(model, rotations, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4, n, 0);
        tinygltf::Animation animation;
        animation.name = "path";
        for (const auto &[output, channelPath] :
             {std::pair<int, const char *>{translationOutput, "translation"}, {rotationOutput, "rotation"}})
        {
            tinygltf::AnimationSampler sampler;
            sampler.input = input;
            sampler.output = output;
            sampler.interpolation = "LINEAR";
            animation.samplers.push_back(sampler);
            tinygltf::AnimationChannel channel;
            channel.sampler = int(animation.samplers.size()) - 1;
            channel.target_node = robotNode;
            channel.target_path = channelPath;
            animation.channels.push_back(channel);
        }
        model.animations.push_back(animation);
    }
    model.buffers[0].data.resize((model.buffers[0].data.size() + 3) / 4 * 4, 0);

    tinygltf::Scene scene;
    scene.name = "problem";
    scene.nodes = {0};
    model.scenes.push_back(scene);
    model.defaultScene = 0;

    std::ostringstream out;
    tinygltf::TinyGLTF writer;
    if (!writer.WriteGltfSceneToStream(&model, out, false, true))
        throw std::runtime_error("glbBytes: glTF serialisation failed");
    return out.str();
}

void writeGlb(const GltfRequest &request, const std::string &path)
{
    const std::string bytes = glbBytes(request);
    AtomicFile file(path);
    file.stream().write(bytes.data(), std::streamsize(bytes.size()));
    file.commit();
}
}  // namespace hcd::render
