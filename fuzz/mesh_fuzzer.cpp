// SPDX-License-Identifier: BSD-3-Clause
// Harness for the mesh loader, through assimp's in-memory import with the loader's own
// post-processing and placement. Only the formats hybridcd's problems use are fuzzed: the format
// hint is sniffed from the first bytes (OFF, PLY, STL, COLLADA, else OBJ), so seeds are plain mesh
// files. Left to itself assimp would try every one of its ~40 readers on unknown data.
//
// All inputs go through one MeshImporter, as a caller loading many meshes would: constructing
// assimp's importer (every reader and post-processing step) costs more than reading a small mesh.
// MeshLoader.OneImporterLoadsAsFreshOnes checks that reuse changes no result; the corpus replay in
// CTest feeds each finding to the same code.
#include "fuzz_target.h"

#include "hybridcd/io/input_error.h"
#include "hybridcd/io/mesh_loader.h"

#include <cctype>

namespace hcd::fuzz
{
namespace
{
bool startsWith(std::string_view text, std::string_view prefix) { return text.substr(0, prefix.size()) == prefix; }

const char *formatOf(std::string_view text)
{
    const auto first = text.find_first_not_of(" \t\r\n");
    const std::string_view body = first == std::string_view::npos ? std::string_view() : text.substr(first);
    if (startsWith(body, "OFF") || startsWith(body, "COFF") || startsWith(body, "NOFF"))
        return "off";
    if (startsWith(body, "ply"))
        return "ply";
    if (startsWith(body, "<"))
        return "dae";
    // ASCII STL starts with "solid"; binary STL with an 80-byte header of any bytes.
    if (startsWith(body, "solid") || (!text.empty() && !std::isprint(static_cast<unsigned char>(text[0])) &&
                                      !std::isspace(static_cast<unsigned char>(text[0]))))
        return "stl";
    return "obj";
}
}  // namespace

int fuzzOne(const std::uint8_t *data, std::size_t size)
{
    const std::string_view text = asText(data, size);
    try
    {
        static MeshImporter importer;
        const LoadedMesh m = loadMeshFromMemory(importer, text, formatOf(text), MeshRole::Robot3D, "fuzz/mesh");
        check(m.mesh->triangleCount() > 0, "an accepted mesh has a triangle");
        check(m.centeringShift.allFinite(), "the centring shift is finite");
        for (const Vec3 &v : m.mesh->vertices)
            check(v.allFinite(), "vertices are finite");
        for (const auto &t : m.mesh->triangles)
            for (const auto i : t)
                check(i < m.mesh->vertices.size(), "triangle corners index vertices");
    }
    catch (const InputError &)
    {
    }
    return 0;
}
}  // namespace hcd::fuzz
