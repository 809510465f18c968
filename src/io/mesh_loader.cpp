// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/io/mesh_loader.h"

#include "hybridcd/io/input_error.h"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <system_error>
#include <utility>

namespace hcd
{
namespace
{
// Depth-first over the node graph in the order OMPL.app walks it, transform = parent * node.
template <typename Visit>
void visitNodes(const aiScene *scene, const aiNode *node, aiMatrix4x4 transform, const Visit &visit)
{
    transform *= node->mTransformation;
    for (unsigned i = 0; i < node->mNumMeshes; ++i)
        visit(scene->mMeshes[node->mMeshes[i]], transform);
    for (unsigned c = 0; c < node->mNumChildren; ++c)
        visitNodes(scene, node->mChildren[c], transform, visit);
}

// What the loader takes from one assimp import: triangle corners in single precision, as
// OMPL.app has them, and the sum and count of all instanced vertices for the robot's centring.
struct Imported
{
    std::vector<aiVector3D> corners;  // three per triangle
    aiVector3D vertexSum{0.0f, 0.0f, 0.0f};
    std::size_t vertexCount = 0;
    std::size_t skippedNonTriangles = 0;
};

// Imports `path` with `flags`; throws InputError naming the file when assimp fails, when the file
// holds no geometry, or when its instanced triangles exceed the limit (counted before any copy).
Imported import(const std::string &path, unsigned flags, const MeshLimits &limits)
{
    Assimp::Importer importer;
    const aiScene *scene = importer.ReadFile(path, flags);
    if (scene == nullptr)
        throw InputError(path, 0, std::string("cannot read mesh: ") + importer.GetErrorString());
    if (!scene->HasMeshes() || scene->mRootNode == nullptr)
        throw InputError(path, 0, "mesh file holds no geometry");

    std::size_t triangles = 0;
    visitNodes(scene, scene->mRootNode, aiMatrix4x4(), [&](const aiMesh *m, const aiMatrix4x4 &) {
        triangles += m->mNumFaces;
    });
    if (triangles > limits.maxTriangles)
        throw InputError(path, 0,
                         "the mesh has " + std::to_string(triangles) + " faces, above the limit of " +
                             std::to_string(limits.maxTriangles) +
                             " triangles per mesh (about 0.7 KB of memory each; the command line's "
                             "--max-triangles raises it)");

    Imported out;
    out.corners.reserve(3 * triangles);
    visitNodes(scene, scene->mRootNode, aiMatrix4x4(), [&](const aiMesh *m, const aiMatrix4x4 &transform) {
        for (unsigned v = 0; v < m->mNumVertices; ++v)
        {
            out.vertexSum += transform * m->mVertices[v];
            ++out.vertexCount;
        }
        for (unsigned f = 0; f < m->mNumFaces; ++f)
        {
            const aiFace &face = m->mFaces[f];
            if (face.mNumIndices != 3)
            {
                ++out.skippedNonTriangles;
                continue;
            }
            for (int k = 0; k < 3; ++k)
                out.corners.push_back(transform * m->mVertices[face.mIndices[k]]);
        }
    });
    return out;
}

// Diagonal of the corners' bounding box (in double, so tiny meshes are measured exactly).
double extentOf(const std::vector<aiVector3D> &corners)
{
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const aiVector3D &c : corners)
    {
        const Vec3 p(c.x, c.y, c.z);
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    return corners.empty() ? 0.0 : (hi - lo).norm();
}
}  // namespace

LoadedMesh loadMesh(const std::string &path, MeshRole role, const MeshLimits &limits)
{
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw InputError(path, 0, "is a folder, not a mesh file");
    if (!std::ifstream(path).good())
        throw InputError(path, 0, "cannot open mesh file (missing or unreadable)");
    // Refused before assimp reads it: assimp holds the whole file and more in memory.
    const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
    const std::uintmax_t maxBytes = std::uintmax_t(limits.maxTriangles) * limits.bytesPerTriangle;
    if (!ec && bytes > maxBytes)
        throw InputError(path, 0,
                         "the mesh file has " + std::to_string(bytes) + " bytes, above the limit of " +
                             std::to_string(maxBytes) + " (" + std::to_string(limits.bytesPerTriangle) +
                             " bytes for each of the " + std::to_string(limits.maxTriangles) +
                             " triangles allowed per mesh; the command line's --max-triangles raises it)");

    const unsigned joined = aiProcess_GenNormals | aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                            aiProcess_SortByPType | aiProcess_OptimizeGraph;
    Imported imported = import(path, joined, limits);
    if (!imported.corners.empty() && extentOf(imported.corners) < kTinyMeshExtent)
        imported = import(path, joined & ~unsigned(aiProcess_JoinIdenticalVertices), limits);

    LoadedMesh out;
    out.skippedNonTriangles = imported.skippedNonTriangles;
    const std::vector<aiVector3D> &corners = imported.corners;
    const aiVector3D vertexSum = imported.vertexSum;
    const std::size_t vertexCount = imported.vertexCount;
    out.sourceTriangles = corners.size() / 3;
    if (corners.empty())
        throw InputError(path, 0, "mesh file holds no triangle (" + std::to_string(out.skippedNonTriangles) +
                                      " point or line primitives only)");

    aiVector3D shift(0.0f, 0.0f, 0.0f);
    if (role != MeshRole::Environment)
    {
        shift = vertexSum / float(vertexCount);
        if (role == MeshRole::RobotPlanar)
            shift.z = 0.0f;
    }
    out.centeringShift = Vec3(shift.x, shift.y, shift.z);

    TriangleMesh mesh;
    mesh.vertices.reserve(corners.size());
    for (const aiVector3D &c : corners)
    {
        const aiVector3D p = c - shift;  // subtracted in float, exactly as OMPL.app does
        mesh.vertices.emplace_back(p.x, p.y, p.z);
    }
    for (std::uint32_t t = 0; t < out.sourceTriangles; ++t)
        mesh.triangles.push_back({3 * t, 3 * t + 1, 3 * t + 2});
    for (const Vec3 &v : mesh.vertices)
        if (!v.allFinite())
            throw InputError(path, 0, "mesh has a non-finite vertex coordinate");
    out.droppedDegenerate = weldAndDropDegenerate(mesh);
    if (mesh.empty())
        throw InputError(path, 0, "every triangle of the mesh is degenerate (zero area)");
    out.mesh = std::make_shared<const TriangleMesh>(std::move(mesh));
    return out;
}
}  // namespace hcd
