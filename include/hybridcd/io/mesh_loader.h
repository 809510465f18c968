// SPDX-License-Identifier: BSD-3-Clause
// Loads triangle meshes with assimp, placing them exactly as OMPL.app does.
//
// OMPL.app's conventions, reproduced bit for bit so that its .cfg and .path files mean the same
// poses here: the scene is post-processed with GenNormals, Triangulate, JoinIdenticalVertices,
// SortByPType and OptimizeGraph; every node's vertices are mapped by the accumulated single-precision
// transform parent x node; only faces with exactly three indices are triangles (SketchUp exports
// edges as line primitives). A robot is shifted by minus the single-precision mean of all its
// instanced vertices, with the shift's z zeroed for planar problems; an environment is not moved.
#pragma once

#include "hybridcd/geometry/triangle_mesh.h"

#include <memory>
#include <string>
#include <string_view>

namespace Assimp
{
class Importer;
}

namespace hcd
{
enum class MeshRole
{
    Environment,  ///< kept in its file's coordinates
    Robot3D,      ///< centred on its vertex mean
    RobotPlanar,  ///< centred on its vertex mean in x and y only
};

struct LoadedMesh
{
    TriangleMesh mesh;
    Vec3 centeringShift = Vec3::Zero();  ///< what was subtracted from every vertex
    std::size_t sourceTriangles = 0;      ///< three-index faces found in the file
    std::size_t skippedNonTriangles = 0;  ///< points and lines, ignored
    std::size_t droppedDegenerate = 0;    ///< zero-area triangles, dropped after welding
};

/// What loading keeps from one mesh to the next: one assimp importer, whose construction (it
/// instantiates every reader and post-processing step assimp has) costs more than reading a small
/// mesh. The overloads below taking one load exactly as the one-shot functions, which make a fresh
/// MeshImporter per call; worth it when many small meshes are read. Not thread-safe: one per thread.
class MeshImporter
{
public:
    MeshImporter();
    ~MeshImporter();
    MeshImporter(const MeshImporter &) = delete;
    MeshImporter &operator=(const MeshImporter &) = delete;

private:
    friend LoadedMesh loadMesh(MeshImporter &, const std::string &, MeshRole);
    friend LoadedMesh loadMeshFromMemory(MeshImporter &, std::string_view, const std::string &, MeshRole,
                                         const std::string &);
    std::unique_ptr<Assimp::Importer> importer_;
};

/// Loads any format assimp reads (COLLADA, OBJ, STL, PLY, OFF, ...). Throws InputError naming the
/// file when it is missing, unreadable, or holds no triangle.
LoadedMesh loadMesh(const std::string &path, MeshRole role);

/// Loads a mesh file's contents held in memory, with the same post-processing, placement and
/// errors as loadMesh. `formatHint` is the file extension assimp picks its reader by ("obj",
/// "dae", ...; assimp sniffs the content when it is empty or unknown); `sourceName` names the
/// data in errors. Files the data refers to (materials, textures) are looked up in the current
/// folder. Throws InputError when the data is empty, unreadable, or holds no triangle.
LoadedMesh loadMeshFromMemory(std::string_view data, const std::string &formatHint, MeshRole role,
                              const std::string &sourceName);

/// loadMesh and loadMeshFromMemory through the caller's importer (see MeshImporter).
LoadedMesh loadMesh(MeshImporter &importer, const std::string &path, MeshRole role);
LoadedMesh loadMeshFromMemory(MeshImporter &importer, std::string_view data, const std::string &formatHint,
                              MeshRole role, const std::string &sourceName);
}  // namespace hcd
