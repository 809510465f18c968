// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/io/mesh_loader.h"

#include "hybridcd/io/input_error.h"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <iterator>

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

// OMPL.app's post-processing, for files and buffers alike.
constexpr unsigned kPostProcessing = aiProcess_GenNormals | aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                     aiProcess_SortByPType | aiProcess_OptimizeGraph;

// Finishes an import made with aiProcess_ValidateDataStructure only. Three guards against
// malformed files that otherwise reach a failed assertion in assimp's triangulation, which aborts
// the process: validation rejects e.g. an OFF file whose last face lost its line; a face without
// any vertex index (a PLY face list cut short reads "0 0 0" as empty faces, which assimp's
// validation lets through when the reader left the primitive types unset) is an error here; and
// the primitive-type flags are recomputed from the faces, since triangulation asserts that a mesh
// flagged as holding polygons holds one. None of this changes a valid scene; the post-processing
// that follows is OMPL.app's, as ReadFile would have applied it.
const aiScene *postProcess(Assimp::Importer &importer, const aiScene *scene, const std::string &path)
{
    if (scene == nullptr)
        return nullptr;
    for (unsigned i = 0; i < scene->mNumMeshes; ++i)
    {
        aiMesh *m = scene->mMeshes[i];
        unsigned types = 0;
        for (unsigned f = 0; f < m->mNumFaces; ++f)
        {
            const unsigned n = m->mFaces[f].mNumIndices;
            if (n == 0 || m->mFaces[f].mIndices == nullptr)
                throw InputError(path, 0, "malformed mesh: face " + std::to_string(f) + " of mesh " +
                                              std::to_string(i) + " has no vertex index");
            types |= n == 1 ? aiPrimitiveType_POINT
                     : n == 2 ? aiPrimitiveType_LINE
                     : n == 3 ? aiPrimitiveType_TRIANGLE
                              : aiPrimitiveType_POLYGON;
        }
        m->mPrimitiveTypes = types;
    }
    return importer.ApplyPostProcessing(kPostProcessing);
}

// assimp 5.2's PLY reader never returns on a header without "end_header": it keeps asking for
// the next line past the end of the data (found by fuzzing,
// tests/fuzz_corpus/mesh/regression_ply_no_end_header.ply). Data that goes to that reader, by its
// format (`format` is the extension or hint) or by starting with "ply", is refused before import.
void rejectPlyWithoutHeaderEnd(std::string_view data, std::string format, const std::string &path)
{
    std::transform(format.begin(), format.end(), format.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    const auto first = data.find_first_not_of(" \t\r\n");
    const bool ply = format == "ply" || (first != std::string_view::npos && data.substr(first, 3) == "ply");
    if (ply && data.find("end_header") == std::string_view::npos)
        throw InputError(path, 0, "malformed PLY file: its header has no end_header line");
}

std::string extensionOf(const std::string &path)
{
    const auto dot = path.find_last_of('.');
    const auto slash = path.find_last_of("/\\");
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
        return {};
    return path.substr(dot + 1);
}

// The triangles of an imported scene, placed for `role`; `path` names the source in errors.
LoadedMesh meshOfScene(const aiScene *scene, const Assimp::Importer &importer, const std::string &path, MeshRole role)
{
    if (scene == nullptr)
        throw InputError(path, 0, std::string("cannot read mesh: ") + importer.GetErrorString());
    if (!scene->HasMeshes() || scene->mRootNode == nullptr)
        throw InputError(path, 0, "mesh file holds no geometry");

    LoadedMesh out;
    std::vector<aiVector3D> corners;  // three per triangle, in single precision as OMPL.app has them
    aiVector3D vertexSum(0.0f, 0.0f, 0.0f);
    std::size_t vertexCount = 0;
    visitNodes(scene, scene->mRootNode, aiMatrix4x4(), [&](const aiMesh *m, const aiMatrix4x4 &transform) {
        for (unsigned v = 0; v < m->mNumVertices; ++v)
        {
            vertexSum += transform * m->mVertices[v];
            ++vertexCount;
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
                corners.push_back(transform * m->mVertices[face.mIndices[k]]);
        }
    });
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

    TriangleMesh &mesh = out.mesh;
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
    return out;
}
}  // namespace

MeshImporter::MeshImporter() : importer_(std::make_unique<Assimp::Importer>()) {}

MeshImporter::~MeshImporter() = default;

LoadedMesh loadMesh(MeshImporter &context, const std::string &path, MeshRole role)
{
    if (!std::ifstream(path).good())
        throw InputError(path, 0, "cannot open mesh file (missing or unreadable)");
    {
        std::ifstream in(path, std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        rejectPlyWithoutHeaderEnd(bytes, extensionOf(path), path);
    }
    Assimp::Importer &importer = *context.importer_;
    return meshOfScene(postProcess(importer, importer.ReadFile(path, aiProcess_ValidateDataStructure), path), importer,
                       path, role);
}

LoadedMesh loadMeshFromMemory(MeshImporter &context, std::string_view data, const std::string &formatHint,
                              MeshRole role, const std::string &sourceName)
{
    // assimp refuses an empty buffer without saying why.
    if (data.empty())
        throw InputError(sourceName, 0, "mesh data is empty");
    rejectPlyWithoutHeaderEnd(data, formatHint, sourceName);
    Assimp::Importer &importer = *context.importer_;
    const aiScene *scene =
        importer.ReadFileFromMemory(data.data(), data.size(), aiProcess_ValidateDataStructure, formatHint.c_str());
    return meshOfScene(postProcess(importer, scene, sourceName), importer, sourceName, role);
}

LoadedMesh loadMesh(const std::string &path, MeshRole role)
{
    MeshImporter importer;
    return loadMesh(importer, path, role);
}

LoadedMesh loadMeshFromMemory(std::string_view data, const std::string &formatHint, MeshRole role,
                              const std::string &sourceName)
{
    MeshImporter importer;
    return loadMeshFromMemory(importer, data, formatHint, role, sourceName);
}
}  // namespace hcd
