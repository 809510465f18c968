// SPDX-License-Identifier: BSD-3-Clause
// Loads triangle meshes with assimp, placing them exactly as OMPL.app does.
//
// OMPL.app's conventions, reproduced bit for bit so that its .cfg and .path files mean the same
// poses here: the scene is post-processed with GenNormals, Triangulate, JoinIdenticalVertices,
// SortByPType and OptimizeGraph; every node's vertices are mapped by the accumulated single-precision
// transform parent x node; only faces with exactly three indices are triangles (SketchUp exports
// edges as line primitives). A robot is shifted by minus the single-precision mean of all its
// instanced vertices, with the shift's z zeroed for planar problems; an environment is not moved.
//
// One deliberate difference: assimp's JoinIdenticalVertices merges distinct vertices of meshes a
// few hundred-millionths across (it collapsed triangles of a 1e-9 box in tests), so a mesh smaller
// than kTinyMeshExtent is imported again without that step, and its robot shift is the mean of
// that import's vertices. OMPL.app would see a broken mesh there, so no compatibility is lost.
#pragma once

#include "hybridcd/geometry/triangle_mesh.h"

#include <cstddef>
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

/// Bounding-box diagonal below which a mesh is imported without assimp's vertex joining.
constexpr double kTinyMeshExtent = 1e-3;

/// Deepest nesting accepted in a COLLADA file, for its XML elements and for its node hierarchy with
/// instanced nodes (<instance_node>) expanded: assimp walks both recursively, at 1-2 KB of stack
/// per level (5,000 levels overflow a 4 MB stack, 10,000 an 8 MB one). OMPL.app's files nest 12
/// elements deep at most.
constexpr std::size_t kMaxColladaDepth = 1000;

/// Most nodes accepted in a COLLADA scene, counted with instanced nodes expanded: assimp builds a
/// node of over 1 KB for each (a file doubling one node 24 times asked for 33 million, 4 GB).
/// OMPL.app's largest scene (Apartment_env.dae) has 167.
constexpr std::size_t kMaxColladaNodes = 100'000;

/// Most vertices of one face: assimp's own limit (AI_MAX_FACE_INDICES), and the bound on the
/// length of a PLY list, which assimp allocates before reading its values.
constexpr std::size_t kMaxFaceVertices = 32767;

/// Triangulating a face of n vertices costs assimp about n^2 steps (a 20,000-vertex face takes
/// seconds): the sum of n^2 over faces of more than three vertices is bounded by this many per
/// triangle allowed (MeshLimits::maxTriangles), 1e8 by default (about a second).
constexpr std::size_t kPolygonWorkPerTriangle = 50;

/// Bounds on what loadMesh accepts, so that a huge or hostile file fails at once with a message
/// instead of exhausting memory. Peak memory is about 0.7 KB per triangle with the obb checker
/// (a 1e6-triangle mesh: 684 MB resident during `inspect`), so the default bounds a run near 1.5 GB.
struct MeshLimits
{
    /// Triangles per mesh, counted over every instance in the scene graph before any is copied.
    std::size_t maxTriangles = 2'000'000;
    /// File size allowed per allowed triangle, checked before the file is read (ASCII STL takes
    /// about 250 bytes per triangle, binary STL 50, COLLADA and OBJ less with shared vertices).
    std::size_t bytesPerTriangle = 128;
};

struct LoadedMesh
{
    /// Never null (an empty mesh until loaded); immutable, so a CollisionScene can share it.
    std::shared_ptr<const TriangleMesh> mesh = std::make_shared<const TriangleMesh>();
    Vec3 centeringShift = Vec3::Zero();   ///< what was subtracted from every vertex
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
    friend LoadedMesh loadMesh(MeshImporter &, const std::string &, MeshRole, const MeshLimits &);
    friend LoadedMesh loadMeshFromMemory(MeshImporter &, std::string_view, const std::string &, MeshRole,
                                         const std::string &, const MeshLimits &);
    std::unique_ptr<Assimp::Importer> importer_;
};

/// Loads any format assimp reads (COLLADA, OBJ, STL, PLY, OFF, ...). Throws InputError naming the
/// file when it is missing, a folder or another file that is not a regular one (a pipe, device or
/// socket), unreadable, beyond `limits` or the bounds above, malformed in a way assimp would not
/// survive or would read wrongly, holds no triangle, or only degenerate ones. Non-manifold meshes load: their closed
/// components are solids, the rest surfaces.
LoadedMesh loadMesh(const std::string &path, MeshRole role, const MeshLimits &limits = {});

/// Loads a mesh file's contents held in memory, with the same post-processing, placement, limits
/// and errors as loadMesh. `formatHint` is the file extension assimp picks its reader by ("obj",
/// "dae", ...; assimp sniffs the content when it is empty or unknown); `sourceName` names the
/// data in errors. Files the data refers to (materials, textures) are looked up in the current
/// folder. Throws InputError when the data is empty, unreadable, or holds no triangle.
LoadedMesh loadMeshFromMemory(std::string_view data, const std::string &formatHint, MeshRole role,
                              const std::string &sourceName, const MeshLimits &limits = {});

/// loadMesh and loadMeshFromMemory through the caller's importer (see MeshImporter).
LoadedMesh loadMesh(MeshImporter &importer, const std::string &path, MeshRole role, const MeshLimits &limits = {});
LoadedMesh loadMeshFromMemory(MeshImporter &importer, std::string_view data, const std::string &formatHint,
                              MeshRole role, const std::string &sourceName, const MeshLimits &limits = {});
}  // namespace hcd
