// SPDX-License-Identifier: BSD-3-Clause
#include "support/test_support.h"

#include "hybridcd/io/input_error.h"
#include "hybridcd/io/mesh_loader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fcntl.h>
#include <fstream>
#include <iterator>
#include <sstream>
#include <sys/stat.h>
#include <thread>
#include <unistd.h>
#include <utility>

using namespace hcd;

namespace
{
// A tetrahedron with vertex mean (1, 1, 1) in several formats assimp reads.
const char *kObj = "v 0 0 0\nv 4 0 0\nv 0 4 0\nv 0 0 4\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
const char *kOff = "OFF\n4 4 0\n0 0 0\n4 0 0\n0 4 0\n0 0 4\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
const char *kPly = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                   "element face 4\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n4 0 0\n0 4 0\n0 0 4\n"
                   "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";

std::string stlText()
{
    const double v[4][3] = {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {0, 0, 4}};
    const int f[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    std::ostringstream s;
    s << "solid tet\n";
    for (const auto &t : f)
    {
        s << " facet normal 0 0 0\n  outer loop\n";
        for (int k : t)
            s << "   vertex " << v[k][0] << ' ' << v[k][1] << ' ' << v[k][2] << '\n';
        s << "  endloop\n endfacet\n";
    }
    s << "endsolid tet\n";
    return s.str();
}
}  // namespace

TEST(MeshLoader, ReadsCommonFormats)
{
    const std::pair<std::string, std::string> files[] = {
        {"tet.obj", kObj}, {"tet.off", kOff}, {"tet.ply", kPly}, {"tet.stl", stlText()}};
    for (const auto &[name, text] : files)
    {
        const LoadedMesh m = loadMesh(test::writeTempFile(name, text), MeshRole::Environment);
        EXPECT_EQ(m.mesh->triangleCount(), 4u) << name;
        EXPECT_TRUE(isClosed(*m.mesh)) << name;
        EXPECT_EQ(m.mesh->bounds().max, Vec3(4, 4, 4)) << name;
    }
}

TEST(MeshLoader, LoadsFromMemoryAsFromFiles)
{
    const std::pair<std::string, std::string> files[] = {
        {"obj", kObj}, {"off", kOff}, {"ply", kPly}, {"stl", stlText()}};
    for (const auto &[format, text] : files)
    {
        const LoadedMesh fromFile = loadMesh(test::writeTempFile("memory." + format, text), MeshRole::Robot3D);
        const LoadedMesh fromMemory = loadMeshFromMemory(text, format, MeshRole::Robot3D, "memory");
        EXPECT_EQ(fromMemory.mesh->vertices, fromFile.mesh->vertices) << format;
        EXPECT_EQ(fromMemory.mesh->triangles, fromFile.mesh->triangles) << format;
        EXPECT_EQ(fromMemory.centeringShift, fromFile.centeringShift) << format;
    }
    for (const std::string &bad : {std::string(), std::string("v 0 0 0\n")})
    {
        try
        {
            loadMeshFromMemory(bad, "obj", MeshRole::Environment, "buffer.obj");
            FAIL() << "no error for '" << bad << "'";
        }
        catch (const InputError &e)
        {
            EXPECT_NE(std::string(e.what()).find("buffer.obj: "), std::string::npos) << e.what();
        }
    }
}

// The fuzz harness reads every input through one importer; reuse must not change what a load
// gives, whatever was read before (errors and the two past findings included).
TEST(MeshLoader, OneImporterLoadsAsFreshOnes)
{
    const std::pair<std::string, std::string> inputs[] = {
        {"obj", kObj},
        {"obj", "v 0 0 0\n"},
        {"off", kOff},
        {"off", "OFF\n4 4 0\n0 0 00 4 0\n0 0 4\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n"},
        {"ply", "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                "element face 4\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n4 0 0\n0 4 0\n4 4 0\n"
                "0 0 00 4 0\n0 0 4\n3 0 2 1\n3 0 1 3"},
        {"ply", kPly},
        {"stl", stlText()},
        {"stl", "solid x\n facet normal 0 0 0\n  outer loop\n   vertex 0 0"},
        {"obj", kObj},
        {"stl", stlText()},
    };
    MeshImporter importer;
    for (int pass = 0; pass < 2; ++pass)
        for (const auto &[format, text] : inputs)
        {
            std::string freshError, reusedError;
            LoadedMesh fresh, reused;
            try
            {
                fresh = loadMeshFromMemory(text, format, MeshRole::Robot3D, "mesh");
            }
            catch (const InputError &e)
            {
                freshError = e.what();
            }
            try
            {
                reused = loadMeshFromMemory(importer, text, format, MeshRole::Robot3D, "mesh");
            }
            catch (const InputError &e)
            {
                reusedError = e.what();
            }
            EXPECT_EQ(reusedError, freshError) << format << ": " << text;
            EXPECT_EQ(reused.mesh->vertices, fresh.mesh->vertices) << format << ": " << text;
            EXPECT_EQ(reused.mesh->triangles, fresh.mesh->triangles) << format << ": " << text;
            EXPECT_EQ(reused.centeringShift, fresh.centeringShift) << format << ": " << text;
            EXPECT_EQ(reused.skippedNonTriangles, fresh.skippedNonTriangles) << format << ": " << text;
            EXPECT_EQ(reused.droppedDegenerate, fresh.droppedDegenerate) << format << ": " << text;
        }
    const std::string path = test::writeTempFile("reused.obj", kObj);
    EXPECT_EQ(loadMesh(importer, path, MeshRole::Environment).mesh->vertices,
              loadMesh(path, MeshRole::Environment).mesh->vertices);
}

// Found by fuzzing (tests/fuzz_corpus/mesh/regression_off_short_face.off): with a vertex line
// missing, the faces shift by one line and the last has none; assimp's OFF reader then hands a
// face without indices to its triangulation, which fails an assertion and aborts the process.
// Validating the scene first turns that into an error naming the file.
TEST(MeshLoader, MalformedOffIsAnErrorNotAnAbort)
{
    const std::string text = "OFF\n4 4 0\n0 0 00 4 0\n0 0 4\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
    const std::string path = test::writeTempFile("short_face.off", text);
    EXPECT_THROW(loadMesh(path, MeshRole::Robot3D), InputError);
    EXPECT_THROW(loadMeshFromMemory(text, "off", MeshRole::Robot3D, "short_face.off"), InputError);
}

// Found by fuzzing (tests/fuzz_corpus/mesh/regression_ply_truncated_faces.ply): in a PLY file
// whose vertex list lost a line, the face list reads "0 0 0" as two faces without any vertex index.
// assimp's validation lets them through (the reader leaves the primitive types unset), they count
// as polygons, and the triangulation fails an assertion and aborts. The loader now rejects a face
// without indices before post-processing.
TEST(MeshLoader, PlyFaceWithoutIndicesIsAnErrorNotAnAbort)
{
    const std::string text = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                             "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n"
                             "0 0 0\n4 0 0\n0 4 0\n4 4 0\n0 0 00 4 0\n0 0 4\n3 0 2 1\n3 0 1 3";
    try
    {
        loadMeshFromMemory(text, "ply", MeshRole::Environment, "truncated.ply");
        FAIL() << "no error";
    }
    catch (const InputError &e)
    {
        EXPECT_NE(std::string(e.what()).find("truncated.ply: malformed mesh: face 0 of mesh 0 has no vertex index"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_THROW(loadMesh(test::writeTempFile("truncated.ply", text), MeshRole::Environment), InputError);
}

// Found by fuzzing (tests/fuzz_corpus/mesh/regression_ply_no_end_header.ply): assimp's PLY reader
// never returns when the header has no end_header line. The loader refuses such data first.
TEST(MeshLoader, PlyWithoutHeaderEndIsAnErrorNotAHang)
{
    const std::string text = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                             "property float z\nelement face 1\nproperty list uchar int vertex_indices\nen 0\n"
                             "vd_header\n0 0 0\n4 0 0\n0 4 0\n3 0 1 2\n";
    for (const std::string format : {"ply", "PLY", ""})
        EXPECT_THROW(loadMeshFromMemory(text, format, MeshRole::Environment, "no_end.ply"), InputError) << format;
    EXPECT_THROW(loadMesh(test::writeTempFile("no_end.ply", text), MeshRole::Environment), InputError);
    // The word glued to the end of another line does not end the header either (found by fuzzing,
    // tests/fuzz_corpus/mesh/regression_ply_glued_end_header.ply).
    std::string glued = text;
    glued.replace(glued.find("vertex_indices\nen 0\nvd_header"), 29, "vertex_indicesend_header");
    EXPECT_THROW(loadMeshFromMemory(glued, "ply", MeshRole::Environment, "glued.ply"), InputError);
    // So does a header with bytes that are not text, or an end_header line ended by another control
    // character (found by fuzzing, tests/fuzz_corpus/mesh/regression_ply_header_control_bytes.ply).
    std::string fixedHeader = text;
    fixedHeader.replace(fixedHeader.find("en 0\nvd_header"), 14, "end_header");
    for (const auto &[from, to] :
         {std::pair<std::string, std::string>{"ascii 1.0\n", std::string("ascii 1.0\x03\0\n", 12)},
          {"end_header\n", "end_header\x0b"},
          {"float x", "flo\xe9t x"}})
    {
        std::string broken = fixedHeader;
        broken.replace(broken.find(from), from.size(), to);
        EXPECT_THROW(loadMeshFromMemory(broken, "ply", MeshRole::Environment, "broken.ply"), InputError) << to;
    }
    // Header lines the format does not define, and element counts the data cannot hold (a garbled
    // format line made assimp read the ASCII body as binary and allocate gigabytes, found by
    // fuzzing: tests/fuzz_corpus/mesh/regression_ply_garbled_format_line.ply).
    for (const auto &[from, to] : {std::pair<std::string, std::string>{"format ascii 1.0", "format ascii 1.s[ii 1.0"},
                                   {"property float y", "t y"},
                                   {"element vertex 3", "element vertex 88888888888"},
                                   {"property list uchar int vertex_indices", "property list uchar vertex_indices"}})
    {
        std::string broken = fixedHeader;
        broken.replace(broken.find(from), from.size(), to);
        EXPECT_THROW(loadMeshFromMemory(broken, "ply", MeshRole::Environment, "broken.ply"), InputError) << to;
    }
    std::string commented = fixedHeader;
    commented.replace(commented.find("element vertex"), 0, "comment made by hand\nobj_info one triangle\n");
    EXPECT_EQ(loadMeshFromMemory(commented, "ply", MeshRole::Environment, "ok.ply").mesh->triangleCount(), 1u);
    // Windows line ends and trailing blanks are text.
    std::string crlf = fixedHeader;
    for (std::size_t at = crlf.find('\n'); at != std::string::npos; at = crlf.find('\n', at + 2))
        crlf.replace(at, 1, "\r\n");
    EXPECT_EQ(loadMeshFromMemory(crlf, "ply", MeshRole::Environment, "crlf.ply").mesh->triangleCount(), 1u);
    // With the line, the same triangle loads.
    std::string fixed = text;
    fixed.replace(fixed.find("en 0\nvd_header"), 14, "end_header");
    EXPECT_EQ(loadMeshFromMemory(fixed, "ply", MeshRole::Environment, "end.ply").mesh->triangleCount(), 1u);
}

// Found by fuzzing (tests/fuzz_corpus/mesh/regression_off_huge_face_count.off): assimp's OFF reader
// allocates every face its header announces before reading any, so a header announcing billions
// of faces exhausts memory. The loader refuses counts that the data's bytes cannot hold.
TEST(MeshLoader, OffAnnouncingMoreThanItsBytesHoldIsAnError)
{
    const std::string body = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    const std::string huge = "88888888888888888888888888888888";
    for (const std::string &header :
         std::vector<std::string>{"OFF\n3 " + huge + " 0\n", "OFF\n" + huge + " 1 0\n", "COFF 3 " + huge + " 0\n",
                                  "nOFF 3\n3 " + huge + " 0\n", "NOFF4 " + huge + "i8888 1 0\n",
                                  "OFF" + huge + "\n4 4 1\n", "# comment\nOFF\n3 4000000000 0\n"})
    {
        const std::string text = header + body;
        for (const std::string format : {"off", "OFF", ""})
        {
            try
            {
                loadMeshFromMemory(text, format, MeshRole::Environment, "huge.off");
                ADD_FAILURE() << "accepted: " << header << " as " << format;
            }
            catch (const InputError &e)
            {
                EXPECT_NE(std::string(e.what()).find("malformed OFF file: its header announces"), std::string::npos)
                    << e.what();
            }
        }
        EXPECT_THROW(loadMesh(test::writeTempFile("huge.off", text), MeshRole::Environment), InputError);
    }
    // Counts the data can hold load as before, comments and all.
    for (const std::string header : {"OFF\n3 1 0\n", "OFF 3 1 0\n", "OFF\n# 99999999999 faces\n3 1 0\n"})
        EXPECT_EQ(loadMeshFromMemory(header + body, "off", MeshRole::Environment, "ok.off").mesh->triangleCount(), 1u)
            << header;
}

// Found by fuzzing (the heap corruption of tests/fuzz_corpus/mesh/regression_obj_line_with_one_index.obj):
// assimp 5.2's OBJ reader counts a line statement with one vertex as no segment but stores its
// vertex, so after two of them it copies the middle vertex of a longer line past the end of its
// vertex array. Nothing failed at once: glibc aborted loads later. FuzzCorpus.mesh replays the input
// with glibc's heap checks (MALLOC_CHECK_=3), which abort on it without this guard.
TEST(MeshLoader, ObjLineWithFewerThanTwoIndicesIsRefusedBeforeImport)
{
    const std::string head = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n";
    const std::pair<std::string, std::string> refused[] = {
        {head + "l 1\nl 2\nl 1 2 3\n", "obj:6: malformed OBJ file: its line statement ('l') has 1 vertex index"},
        {head + "l -1\n", "obj:6: malformed OBJ file: its line statement ('l') has 1 vertex index"},
        {head + "l\n", "obj:6: malformed OBJ file: its line statement ('l') has 0 vertex indexes"},
        {head + "l /1 2\n", "obj:6: malformed OBJ file: its line statement ('l') has 1 vertex index"},
        // Any line starting with 'l' is a line statement to the reader, whatever its first word.
        {head + "lod 1\n", "obj:6: malformed OBJ file: its line statement ('l') has 1 vertex index"},
        {head + "l 1 x2\n", "obj:6: malformed OBJ file: its line statement ('l') holds 'x2', not a vertex index"},
        // A number the reader's atoi() overflows on.
        {head + "l 1 6442450944\n", "obj:6: malformed OBJ file: its line statement ('l') holds '6442450944'"},
        // The reader also ends lines at \r, \f and zero bytes, and skips a backslash-ended one.
        {"v 0 0 0\rl 1\r", "obj:1: malformed OBJ file: its line statement ('l') has 1 vertex index"},
        {head + std::string("f 1 2 3\0l 1\n", 12), "obj:6: malformed OBJ file"},
        {head + "f 1 2 \\\n3\nl 1\n", "obj:8: malformed OBJ file"},
        {head + "l 1 \\\n\nl 2\n", "obj:6: malformed OBJ file: its line statement ('l') has 1 vertex index"},
        {head + "l 1 \\ 2\n", "obj:6: malformed OBJ file: its line statement ('l') holds '\\'"},
        {head + "l 1\\\r\n2\n", "obj:6: malformed OBJ file: its line statement ('l') has 1 vertex index"},
    };
    for (const auto &[text, message] : refused)
        for (const std::string format : {"obj", "OBJ", "", "txt"})
        {
            try
            {
                loadMeshFromMemory(text, format, MeshRole::Environment, "obj");
                ADD_FAILURE() << "accepted as '" << format << "': " << text;
            }
            catch (const InputError &e)
            {
                EXPECT_EQ(std::string(e.what()).rfind(message, 0), 0u) << e.what() << "\nfor: " << text;
            }
        }
    EXPECT_THROW(loadMesh(test::writeTempFile("one_index.obj", head + "l 1\nl 2\nl 1 2 3\n"), MeshRole::Environment),
                 InputError);
    // Well-formed line statements load as before; their segments are skipped, not triangles.
    for (const std::string lines :
         {"l 1 2\n", "l 1 2 3 4\n", "l -1 -2\n", "l 1/1 2/1\n", "l 1\t2\r\n", "l 1 \\\n 2\n", "l 1 \\\r\n2\n"})
    {
        const LoadedMesh m = loadMeshFromMemory("vt 0 0\n" + head + lines, "obj", MeshRole::Environment, "lines.obj");
        EXPECT_EQ(m.mesh->triangleCount(), 1u) << lines;
        EXPECT_GE(m.skippedNonTriangles, 1u) << lines;
    }
    // Data for another reader is not read as OBJ.
    EXPECT_EQ(
        loadMeshFromMemory("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\nl 1\n", "off", MeshRole::Environment, "l.off")
            .mesh->triangleCount(),
        1u);
}

TEST(MeshLoader, ObjVerticesTheReaderWouldMisreadAreRefusedWithTheirLine)
{
    // The reader read "nan" as some number (the face through it then vanished as degenerate, with
    // no error) and shifted the vertices after a statement of 5 or 7 numbers.
    const std::string faces = "f 1 2 3\nf 1 2 4\n";
    const std::pair<std::string, std::string> refused[] = {
        {"v 4 -5 -5\nv 6 -5 -5\nv nan 5 -5\nv 5 5 5\n" + faces,
         "obj:3: malformed OBJ file: its vertex statement ('v') holds 'nan', not a finite number"},
        {"v 4 -5 -5\nv 6 -5 -5\nv 0 5 -5\nv 5 5 1e999\n" + faces,
         "obj:4: malformed OBJ file: its vertex statement ('v') holds '1e999', not a finite number"},
        {"v 4 -5 -5\r\n# v 1\r\nv 6 -5 -5 x\r\nv 0 5 -5\r\nv 5 5 5\r\n" + faces,
         "obj:3: malformed OBJ file: its vertex statement ('v') holds 'x', which the OBJ reader does not read as a "
         "number"},
        // The reader counts only words starting with a digit, '+' or '-', comments included.
        {"v 4 -5 -5\nv 6 -5 -5\nv .5 5 -5\nv 5 5 5\n" + faces,
         "obj:3: malformed OBJ file: its vertex statement ('v') holds '.5', which the OBJ reader does not read as a "
         "number"},
        {"v 4 -5 -5 # 7 8\nv 6 -5 -5\nv 0 5 -5\nv 5 5 5\n" + faces,
         "obj:1: malformed OBJ file: its vertex statement ('v') has a number in its comment"},
        {"v 4 -5 -5\nv 0x6 -5 -5\nv 0 5 -5\nv 5 5 5\n" + faces,
         "obj:2: malformed OBJ file: its vertex statement ('v') holds '0x6', not a finite number"},
        {"v 4 -5 -5 1 0 0 1\nv 6 -5 -5\nv 0 5 -5\nv 5 5 5\n" + faces,
         "obj:1: malformed OBJ file: its vertex statement ('v') holds 7 numbers"},
        {"v 4 -5 -5\nv 6 -5\nv 0 5 -5\nv 5 5 5\n" + faces,
         "obj:2: malformed OBJ file: its vertex statement ('v') holds 2 numbers"},
        {"v 4 -5 -5\nv 6 -5 -5\n\tv 0 5 -5\nv 5 5 5\n" + faces,
         "obj:3: malformed OBJ file: its vertex statement ('v') is indented"},
        {"v inf 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n",
         "obj:1: malformed OBJ file: its vertex statement ('v') holds 'inf', not a finite number"},
        // Face indices the reader refused without a line, or a face it dropped without a word.
        {"v 4 -5 -5\nv 6 -5 -5\nv 0 5 -5\nf 1 2 5\n",
         "obj:4: malformed OBJ file: its face statement ('f') holds '5', not the index of one of the file's 3 "
         "vertices"},
        {"v 4 -5 -5\nv 6 -5 -5\nf 1 2 -3\nv 0 5 -5\n",
         "obj:3: malformed OBJ file: its face statement ('f') holds '-3', not the index of one of the file's 3 "
         "vertices (counted back from the face)"},
        {"v 4 -5 -5\nv 6 -5 -5\nv 0 5 -5\nf 1 2 0\n", "obj:4: malformed OBJ file: its face statement ('f') holds '0'"},
        {"v 4 -5 -5\nv 6 -5 -5\nv 0 5 -5\nf 1 2 3.5\n",
         "obj:4: malformed OBJ file: its face statement ('f') holds '3.5'"},
        {"v 4 -5 -5\nv 6 -5 -5\nv 0 5 -5\nf 1 2 3 # c\n",
         "obj:4: malformed OBJ file: its face statement ('f') holds '#'"},
        {"v 4 -5 -5\nv 6 -5 -5\nv 0 5 -5\nv 5 5 5\nf 1 2 3\n f 1 2 4\n",
         "obj:6: malformed OBJ file: its face statement ('f') is indented"},
    };
    for (const auto &[text, message] : refused)
        for (const std::string format : {"obj", ""})
        {
            try
            {
                loadMeshFromMemory(text, format, MeshRole::Environment, "obj");
                ADD_FAILURE() << "accepted as '" << format << "': " << text;
            }
            catch (const InputError &e)
            {
                EXPECT_EQ(std::string(e.what()).rfind(message, 0), 0u) << e.what() << "\nfor: " << text;
            }
        }

    // What the reader takes: 3, 4 (w) or 6 (colour) numbers, blanks, comments and line ends of
    // every kind; each gives the same mesh as the plain statements.
    const std::string plain = "v 4 -5 -5\nv 6 -5 -5\nv 0 5 -5\nv 5 5 5\n" + faces;
    const LoadedMesh expected = loadMeshFromMemory(plain, "obj", MeshRole::Environment, "plain.obj");
    ASSERT_EQ(expected.mesh->triangleCount(), 2u);
    for (const std::string text :
         {"v 4 -5 -5 1\nv 6 -5 -5 1\nv 0 5 -5 1\nv 5 5 5 1\n" + faces,
          "v 4 -5 -5 1 0 0\nv 6 -5 -5 0 1 0\nv 0 5 -5 0 0 1\nv 5 5 5 1 1 1\n" + faces,
          "v\t4 -5 -5 # first\r\nv 6 -5 -5\rv 0 5 -5\t\nv 5 5 5\n# v nan\n" + faces,
          "v 4e0 -5.0 -.5e1\nv +6 -5 -5\nv 0 5 -5\nv 5 5 5\nvn 0 0 1\nvt 0.5 0.5\n" + faces,
          // Faces before their vertices, indices counted back, texture and normal indices.
          faces + "v 4 -5 -5\nv 6 -5 -5\nv 0 5 -5\nv 5 5 5\n",
          std::string("v 4 -5 -5\nv 6 -5 -5\nv 0 5 -5\nf -3 -2 -1\nv 5 5 5\nf -4/1 -3//1 -1/1/1\nvt 0 0\nvn 0 0 1\n")})
    {
        const LoadedMesh m = loadMeshFromMemory(text, "obj", MeshRole::Environment, "variant.obj");
        EXPECT_EQ(m.mesh->vertices, expected.mesh->vertices) << text;
        EXPECT_EQ(m.mesh->triangles, expected.mesh->triangles) << text;
    }

    // A UTF-8 byte order mark, which the reader took for part of the first statement (the first
    // vertex was lost and every face index shifted), from memory and from a file alike.
    const std::string marked = "\xEF\xBB\xBF" + plain;
    const LoadedMesh fromMemory = loadMeshFromMemory(marked, "obj", MeshRole::Environment, "bom.obj");
    EXPECT_EQ(fromMemory.mesh->vertices, expected.mesh->vertices);
    EXPECT_EQ(fromMemory.mesh->triangles, expected.mesh->triangles);
    const LoadedMesh fromFile = loadMesh(test::writeTempFile("bom.obj", marked), MeshRole::Environment);
    EXPECT_EQ(fromFile.mesh->vertices, expected.mesh->vertices);
    EXPECT_EQ(fromFile.mesh->triangles, expected.mesh->triangles);
    // Data no reader claims by its name goes to the reader assimp picks by content, the OBJ reader
    // here: the mark is left out for it too.
    for (const LoadedMesh &m : {loadMeshFromMemory(marked, "", MeshRole::Environment, "bom"),
                                loadMesh(test::writeTempFile("bom.txt", marked), MeshRole::Environment)})
    {
        EXPECT_EQ(m.mesh->vertices, expected.mesh->vertices);
        EXPECT_EQ(m.mesh->triangles, expected.mesh->triangles);
    }
    // The first line's statement is checked as the reader will read it, without the mark.
    try
    {
        loadMeshFromMemory("\xEF\xBB\xBFl 1\n" + plain, "obj", MeshRole::Environment, "obj");
        ADD_FAILURE() << "a marked file's first line statement is checked too";
    }
    catch (const InputError &e)
    {
        EXPECT_EQ(std::string(e.what()).rfind("obj:1: malformed OBJ file: its line statement ('l') has 1", 0), 0u)
            << e.what();
    }
    try
    {
        loadMesh(test::writeTempFile("bom_nan.obj", "\xEF\xBB\xBFv nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
                 MeshRole::Environment);
        ADD_FAILURE() << "a marked file's first vertex is checked too";
    }
    catch (const InputError &e)
    {
        EXPECT_NE(std::string(e.what()).find("bom_nan.obj:1: malformed OBJ file"), std::string::npos) << e.what();
    }
}

TEST(MeshLoader, RobotIsCentredOnItsVertexMean)
{
    const std::string path = test::writeTempFile("robot.obj", kObj);
    const LoadedMesh robot = loadMesh(path, MeshRole::Robot3D);
    EXPECT_EQ(robot.centeringShift, Vec3(1, 1, 1));
    EXPECT_EQ(robot.mesh->bounds().min, Vec3(-1, -1, -1));
    const LoadedMesh planar = loadMesh(path, MeshRole::RobotPlanar);
    EXPECT_EQ(planar.centeringShift, Vec3(1, 1, 0));
}

TEST(MeshLoader, DropsAndCountsDegenerateTriangles)
{
    const LoadedMesh m =
        loadMesh(test::writeTempFile("degenerate.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\n"),
                 MeshRole::Environment);
    EXPECT_EQ(m.mesh->triangleCount(), 1u);
    EXPECT_EQ(m.droppedDegenerate, 1u);
}

TEST(MeshLoader, BadFilesGiveErrorsNamingTheFile)
{
    const std::string missing = "/nonexistent/folder/mesh.dae";
    try
    {
        loadMesh(missing, MeshRole::Environment);
        FAIL() << "no error for a missing file";
    }
    catch (const InputError &e)
    {
        EXPECT_NE(std::string(e.what()).find(missing), std::string::npos);
    }
    for (const auto &[name, text] : std::vector<std::pair<std::string, std::string>>{
             {"empty.obj", ""}, {"garbage.dae", "<COLLADA this is not xml"}, {"points.obj", "v 0 0 0\nv 1 1 1\n"}})
    {
        const std::string path = test::writeTempFile(name, text);
        try
        {
            loadMesh(path, MeshRole::Environment);
            FAIL() << "no error for " << name;
        }
        catch (const InputError &e)
        {
            EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
        }
    }
}

TEST(MeshLoader, MatchesOmplAppGeometryOnCubicles)
{
    HYBRIDCD_REQUIRE_OMPLAPP(robotPath, "3D/cubicles_robot.dae");
    const LoadedMesh robot = loadMesh(robotPath, MeshRole::Robot3D);
    // The robot shift is the float mean of the instanced vertices; the start pose of cubicles.cfg
    // (-4.96, -40.62, 70.57) was chosen by OMPL.app's authors at that centre.
    EXPECT_NEAR(robot.centeringShift.x(), -4.96, 0.01);
    EXPECT_NEAR(robot.centeringShift.y(), -40.62, 0.01);
    EXPECT_NEAR(robot.centeringShift.z(), 70.57, 0.01);
    // Geometry is Z-up after the importer's and the nodes' transforms.
    HYBRIDCD_REQUIRE_OMPLAPP(mazePath, "2D/Maze_planar_env.dae");
    const BoundingBox maze = loadMesh(mazePath, MeshRole::Environment).mesh->bounds();
    EXPECT_NEAR(maze.max.x() - maze.min.x(), 110.0, 1e-3);
    EXPECT_NEAR(maze.max.y() - maze.min.y(), 110.0, 1e-3);
    EXPECT_LT(maze.max.z() - maze.min.z(), 20.0);
}

// Found by fuzzing (tests/fuzz_corpus/mesh/regression_collada_array_without_count.dae): assimp's
// COLLADA reader crashes on an array element without a count. The loader refuses such data, and
// counts above what the data can hold, before import.
TEST(MeshLoader, ColladaArraysNeedACountTheDataCanHold)
{
    const std::string tet = test::fileText(test::sourcePath("tests/fuzz_corpus/mesh/tet.dae"));
    const std::string::size_type at = tet.find("count=\"12\"");
    ASSERT_NE(at, std::string::npos);
    EXPECT_EQ(loadMeshFromMemory(tet, "dae", MeshRole::Environment, "tet.dae").mesh->triangleCount(), 4u);
    for (const std::string &replacement : {"cou3d=\"12\"", "count=\"\"", "count=\"-4\"", "count=\"99999999999999\""})
    {
        std::string broken = tet;
        broken.replace(at, 10, replacement);
        for (const std::string format : {"dae", ""})
        {
            try
            {
                loadMeshFromMemory(broken, format, MeshRole::Environment, "broken.dae");
                ADD_FAILURE() << "accepted " << replacement;
            }
            catch (const InputError &e)
            {
                EXPECT_NE(std::string(e.what()).find("malformed COLLADA file"), std::string::npos) << e.what();
            }
        }
        EXPECT_THROW(loadMesh(test::writeTempFile("broken.dae", broken), MeshRole::Environment), InputError);
    }
}

// Found by fuzzing (tests/fuzz_corpus/mesh/regression_collada_index_not_a_number.dae): a '$' in a
// COLLADA index list made assimp allocate gigabytes. Index lists must hold whole numbers that the
// data's size can hold.
TEST(MeshLoader, ColladaIndexListsHoldWholeNumbers)
{
    const std::string tet = test::fileText(test::sourcePath("tests/fuzz_corpus/mesh/tet.dae"));
    const std::string::size_type at = tet.find("<p>0 2 1");
    ASSERT_NE(at, std::string::npos);
    for (const std::string &replacement : {"<p>$ 2 1", "<p>0 -2 1", "<p>0 2.5 1", "<p>0 99999999999999 1"})
    {
        std::string broken = tet;
        broken.replace(at, 8, replacement);
        try
        {
            loadMeshFromMemory(broken, "dae", MeshRole::Environment, "broken.dae");
            ADD_FAILURE() << "accepted " << replacement;
        }
        catch (const InputError &e)
        {
            EXPECT_NE(std::string(e.what()).find("malformed COLLADA file: an index list <p>"), std::string::npos)
                << e.what();
        }
    }
}

namespace
{
// A COLLADA file of one box (8 vertices, 12 triangles), its scene nodes and library nodes given.
std::string colladaBox(const std::string &sceneNodes, const std::string &libraryNodes = "",
                       const std::string &floatArray = "<float_array id=\"PA\" count=\"24\">",
                       const std::string &accessor = "<accessor count=\"8\" source=\"#PA\" stride=\"3\">")
{
    return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
           "<COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" version=\"1.4.1\">\n"
           "<asset><up_axis>Z_UP</up_axis></asset>\n" +
           (libraryNodes.empty() ? "" : "<library_nodes>" + libraryNodes + "</library_nodes>") +
           "\n<library_visual_scenes><visual_scene id=\"S1\">" + sceneNodes +
           "</visual_scene></library_visual_scenes>\n"
           "<library_geometries><geometry id=\"G1\"><mesh>\n<source id=\"P\">" +
           floatArray + "4 -5 -5 6 -5 -5 4 5 -5 6 5 -5 4 -5 5 6 -5 5 4 5 5 6 5 5</float_array>\n<technique_common>" +
           accessor +
           "<param name=\"X\" type=\"float\"/><param name=\"Y\" type=\"float\"/><param name=\"Z\" type=\"float\"/>"
           "</accessor></technique_common></source>\n"
           "<vertices id=\"V\"><input semantic=\"POSITION\" source=\"#P\"/></vertices>\n"
           "<triangles count=\"12\"><input offset=\"0\" semantic=\"VERTEX\" source=\"#V\"/><p>0 2 3 0 3 1 4 5 7 4 "
           "7 6 0 1 5 0 5 4 2 6 7 2 7 3 0 4 6 0 6 2 1 3 7 1 7 5</p></triangles>\n"
           "</mesh></geometry></library_geometries>\n<scene><instance_visual_scene url=\"#S1\"/></scene>\n"
           "</COLLADA>\n";
}

const std::string kBoxNode = "<node id=\"N1\"><instance_geometry url=\"#G1\"/></node>";

// The message of the InputError loading `text` as `format` throws ("" when it loads).
std::string loadError(const std::string &text, const std::string &format, const MeshLimits &limits = {})
{
    try
    {
        loadMeshFromMemory(text, format, MeshRole::Robot3D, "mesh", limits);
    }
    catch (const InputError &e)
    {
        return e.what();
    }
    return {};
}

std::string repeat(const std::string &text, int times)
{
    std::string out;
    for (int i = 0; i < times; ++i)
        out += text;
    return out;
}
}  // namespace

// Found by a hostile-input probe: assimp 5.2 expands <instance_node> references recursively, so a
// node that instances itself (directly, or L1 -> L2 -> L1) overflowed the stack (SIGSEGV), as did
// 20,000 nested <node>s and a chain of instances as deep. All are refused before assimp reads them.
TEST(MeshLoader, ColladaInstanceCyclesAndDeepNestingAreRefused)
{
    const std::string instanceL1 = "<node id=\"N1\"><instance_node url=\"#L1\"/></node>";
    const std::pair<std::string, std::string> refused[] = {
        {colladaBox(instanceL1, "<node id=\"L1\"><instance_geometry url=\"#G1\"/><instance_node url=\"#L1\"/></node>"),
         "mesh:4: malformed COLLADA file: its node 'L1' contains itself through <instance_node> references"},
        {colladaBox(instanceL1, "<node id=\"L1\"><instance_geometry url=\"#G1\"/><instance_node url=\"#L2\"/></node>"
                                "<node id=\"L2\"><instance_node url=\"#L1\"/></node>"),
         "contains itself through <instance_node> references"},
        // Through a child node, and through an id spelled with a character reference.
        {colladaBox(instanceL1, "<node id=\"L1\"><node id=\"C\"><instance_node url=\"#L1\"/></node></node>"),
         "contains itself"},
        {colladaBox(instanceL1, "<node id=\"L&#49;\" name=\"x id='Z'\"><instance_node url=\"#L1\"/></node>"),
         "contains itself"},
        // A scene node instancing itself by name, as assimp resolves an id it does not find.
        {colladaBox("<node name=\"Named\"><instance_geometry url=\"#G1\"/><instance_node url=\"#Named\"/></node>"),
         "its node 'Named' contains itself"},
        {colladaBox(repeat("<node>", 20000) + "<instance_geometry url=\"#G1\"/>" + repeat("</node>", 20000)),
         "mesh:5: malformed COLLADA file: its elements nest deeper than 1000 levels (the limit)"},
        {colladaBox(kBoxNode + "<extra>" + repeat("<a>", 1000) + repeat("</a>", 1000) + "</extra>"),
         "its elements nest deeper than 1000 levels"},
    };
    for (const auto &[text, message] : refused)
    {
        const std::string error = loadError(text, "dae");
        EXPECT_NE(error.find(message), std::string::npos) << error;
        EXPECT_THROW(loadMesh(test::writeTempFile("refused.dae", text), MeshRole::Environment), InputError);
    }
    // A chain of 2,000 library nodes each instancing the next, and 24 nodes each instancing the
    // previous twice (2^24 copies, 4 GB in assimp before it failed).
    std::string chain = "<node id=\"C0\"><instance_geometry url=\"#G1\"/></node>";
    for (int i = 1; i < 2000; ++i)
        chain +=
            "<node id=\"C" + std::to_string(i) + "\"><instance_node url=\"#C" + std::to_string(i - 1) + "\"/></node>";
    EXPECT_NE(loadError(colladaBox("<node><instance_node url=\"#C1999\"/></node>", chain), "dae")
                  .find("its node hierarchy, with instanced nodes expanded, is deeper than 1000 levels"),
              std::string::npos);
    std::string doubling = "<node id=\"E0\"><instance_geometry url=\"#G1\"/></node>";
    for (int i = 1; i < 25; ++i)
        doubling += "<node id=\"E" + std::to_string(i) + "\"><instance_node url=\"#E" + std::to_string(i - 1) +
                    "\"/><instance_node url=\"#E" + std::to_string(i - 1) + "\"/></node>";
    EXPECT_NE(loadError(colladaBox("<node><instance_node url=\"#E24\"/></node>", doubling), "dae")
                  .find("its scene has more than 100000 nodes with instanced nodes expanded"),
              std::string::npos);
    // Within the bounds, instances, nesting and comments load as before: the box instanced twice,
    // 900 levels deep, and cycles in comments or CDATA that XML readers skip.
    const std::string twice =
        colladaBox("<node><instance_node url=\"#L1\"/></node><node><matrix>1 0 0 20 0 1 0 0 0 0 1 0 0 0 0 1</matrix>"
                   "<instance_node url=\"#L1\"/></node><!-- <node id=\"X\"><instance_node url=\"#X\"/></node> -->"
                   "<extra><![CDATA[<node id=\"Y\"><instance_node url=\"#Y\"/></node>]]></extra>",
                   "<node id=\"L1\" name=\"L1\"><instance_geometry url=\"#G1\"/></node>");
    EXPECT_EQ(loadMeshFromMemory(twice, "dae", MeshRole::Environment, "twice.dae").mesh->triangleCount(), 24u);
    const std::string deep =
        colladaBox(repeat("<node>", 900) + "<instance_geometry url=\"#G1\"/>" + repeat("</node>", 900));
    EXPECT_EQ(loadMeshFromMemory(deep, "dae", MeshRole::Environment, "deep.dae").mesh->triangleCount(), 12u);
}

// Found by a hostile-input probe: assimp keeps `count` values of a COLLADA array and reads what
// its accessor asks for, so a <float_array count="6"> read by an accessor of 8 vertices of stride 3
// read past its buffer (garbage vertices; valgrind: invalid read), and an accessor of 4,000,000
// vertices over 3 values crashed.
TEST(MeshLoader, ColladaAccessorsStayWithinTheirArrays)
{
    EXPECT_EQ(loadError(colladaBox(kBoxNode), "dae"), "");
    const std::pair<std::string, std::string> refused[] = {
        {colladaBox(kBoxNode, "", "<float_array id=\"PA\" count=\"6\">"),
         "mesh:8: malformed COLLADA file: an accessor of '#PA' reading 8 elements of stride 3 from offset 0, 24 "
         "values, past the array's count of 6"},
        {colladaBox(kBoxNode, "", "<float_array id=\"PA\" count=\"3\">",
                    "<accessor count=\"4000000\" source=\"#PA\" stride=\"3\">"),
         "mesh:8: malformed COLLADA file: an accessor of '#PA' reading 4000000 elements"},
        {colladaBox(kBoxNode, "", "<float_array id=\"PA\" count=\"24\">",
                    "<accessor count=\"8\" offset=\"1\" source=\"#PA\" stride=\"3\">"),
         "25 values, past the array's count of 24"},
        // Three parameters read from each element of stride 1: the last reads two values further.
        {colladaBox(kBoxNode, "", "<float_array id=\"PA\" count=\"24\">",
                    "<accessor count=\"23\" source=\"#PA\" stride=\"1\">"),
         "25 values, past the array's count of 24"},
        {colladaBox(kBoxNode, "", "<float_array id=\"PA\" count=\"30\">"),
         "mesh:7: malformed COLLADA file: an array 'PA' holding 24 values, fewer than its count of 30"},
        {colladaBox(kBoxNode, "", "<float_array id=\"PA\" count=\"24\">",
                    "<accessor count=\"-8\" source=\"#PA\" stride=\"3\">"),
         "an accessor whose count '-8' is not a whole number"},
    };
    for (const auto &[text, message] : refused)
    {
        const std::string error = loadError(text, "dae");
        EXPECT_NE(error.find(message), std::string::npos) << error;
    }
    // An accessor reading exactly to its array's end loads.
    EXPECT_EQ(loadError(colladaBox(kBoxNode, "", "<float_array id=\"PA\" count=\"24\">",
                                   "<accessor count=\"22\" source=\"#PA\" stride=\"1\">"),
                        "dae"),
              "");
}

// Found by a hostile-input probe: a mesh path naming a pipe (mkfifo) hung the loader, which opened
// it and waited for a writer. Pipes, devices and sockets are refused before opening. Should the
// loader open the pipe, a writer that opens and closes it ends the wait, so the test fails instead
// of hanging.
TEST(MeshLoader, MeshFilesThatAreNotRegularFilesAreRefusedBeforeOpening)
{
    const std::string pipe = test::writeTempFile("pipe_mesh.obj", "") + ".fifo";
    std::remove(pipe.c_str());
    ASSERT_EQ(::mkfifo(pipe.c_str(), 0600), 0);
    std::atomic<bool> finished{false};
    std::thread writer([&] {
        while (!finished)
        {
            const int fd = ::open(pipe.c_str(), O_WRONLY | O_NONBLOCK);
            if (fd >= 0)
            {
                ::close(fd);
                return;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
    });
    std::string error;
    try
    {
        loadMesh(pipe, MeshRole::Environment);
    }
    catch (const InputError &e)
    {
        error = e.what();
    }
    finished = true;
    writer.join();
    std::remove(pipe.c_str());
    EXPECT_NE(error.find(pipe + ": is not a regular file (a device, pipe or socket); a mesh file is expected"),
              std::string::npos)
        << error;
    for (const std::string device : {"/dev/null", "/dev/zero"})
        try
        {
            loadMesh(device, MeshRole::Environment);
            ADD_FAILURE() << "accepted " << device;
        }
        catch (const InputError &e)
        {
            EXPECT_NE(std::string(e.what()).find("is not a regular file"), std::string::npos) << e.what();
        }
}

// Found by a hostile-input probe: assimp's PLY reader sizes a list by its count before reading the
// values, so a 200-byte ASCII file with a face list count of 500,000,000 allocated 4 GB. Lists are
// bounded by kMaxFaceVertices, in ASCII and binary data, and lists cut short are refused.
TEST(MeshLoader, PlyListsAreBoundedAndComplete)
{
    const std::string header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                               "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                               "0 0 0\n1 0 0\n0 1 0\n";
    EXPECT_EQ(loadError(header + "3 0 1 2\n", "ply"), "");
    const std::pair<std::string, std::string> refused[] = {
        {header + "500000000 0 1 2\n",
         "mesh:13: malformed PLY file: its list 'vertex_indices' of face element 0 is a list of 500000000 values, "
         "above the limit of 32767"},
        {header + "255 0 1 2\n", "mesh:13: malformed PLY file: its list 'vertex_indices' of face element 0 announces "
                                 "255 values but holds 3"},
        {header + "3 0 1 x\n", "mesh:13: malformed PLY file: its value 'x' in the list"},
        {header.substr(0, header.size() - 6) + "0 1\n3 0 1 2\n",
         "mesh:12: malformed PLY file: its line has no value for 'z' of vertex element 2"},
        {header.substr(0, header.size() - 6), "malformed PLY file: its data ends after 2 of its 3 vertex elements"},
    };
    for (const auto &[text, message] : refused)
    {
        const std::string error = loadError(text, "ply");
        EXPECT_NE(error.find(message), std::string::npos) << error;
    }
    // Binary data, both byte orders and "\r\n" header lines: a tetrahedron loads, a list count of
    // 40,000 or a negative one is refused, as is data cut short.
    for (const bool bigEndian : {false, true})
        for (const std::string lineEnd : {"\n", "\r\n"})
        {
            std::string binaryHeader = "ply\nformat binary_" + std::string(bigEndian ? "big" : "little") +
                                       "_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty "
                                       "float z\nelement face 4\nproperty list int int vertex_indices\nend_header";
            for (std::size_t at = binaryHeader.find('\n'); at != std::string::npos;
                 at = binaryHeader.find('\n', at + lineEnd.size()))
                binaryHeader.replace(at, 1, lineEnd);
            binaryHeader += lineEnd;
            const auto bytes = [&](const void *value, std::size_t size) {
                std::string out(static_cast<const char *>(value), size);
                if (bigEndian)
                    std::reverse(out.begin(), out.end());
                return out;
            };
            const auto face = [&](std::int32_t count, std::vector<std::int32_t> indices) {
                std::string out = bytes(&count, 4);
                for (const std::int32_t i : indices)
                    out += bytes(&i, 4);
                return out;
            };
            std::string vertices;
            for (const float v : {0.f, 0.f, 0.f, 4.f, 0.f, 0.f, 0.f, 4.f, 0.f, 0.f, 0.f, 4.f})
                vertices += bytes(&v, 4);
            const std::string faces = face(3, {0, 2, 1}) + face(3, {0, 1, 3}) + face(3, {0, 3, 2});
            const std::string tet = binaryHeader + vertices + faces + face(3, {1, 2, 3});
            EXPECT_EQ(loadMeshFromMemory(tet, "ply", MeshRole::Environment, "tet.ply").mesh->triangleCount(), 4u)
                << bigEndian << lineEnd.size();
            EXPECT_NE(loadError(binaryHeader + vertices + faces + face(40000, {1, 2, 3}), "ply")
                          .find("malformed PLY file: its list 'vertex_indices' of face element 3 is a list of 40000 "
                                "values, above the limit of 32767"),
                      std::string::npos);
            EXPECT_NE(
                loadError(binaryHeader + vertices + faces + face(-3, {1, 2, 3}), "ply").find("has a negative count"),
                std::string::npos);
            EXPECT_NE(loadError(binaryHeader + vertices + faces + face(3, {1, 2}), "ply")
                          .find("its data ends after 3 of its 4 face elements"),
                      std::string::npos);
        }
}

// Found by a hostile-input probe: a PLY vertex element without an x property loaded, every x read
// as 0.
TEST(MeshLoader, PlyVerticesNeedXYZ)
{
    for (const char *axis : {"x", "y", "z"})
    {
        const std::string text = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float " +
                                 std::string(axis == std::string("x") ? "w" : "x") + "\nproperty float " +
                                 std::string(axis == std::string("y") ? "w" : "y") + "\nproperty float " +
                                 std::string(axis == std::string("z") ? "w" : "z") +
                                 "\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                                 "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
        EXPECT_NE(
            loadError(text, "ply")
                .find(std::string("mesh:3: malformed PLY file: its vertex element has no '") + axis + "' property"),
            std::string::npos)
            << axis;
    }
}

// Found by a hostile-input probe: assimp's OFF reader replaced a face index out of range by the
// last vertex's, silently (OBJ and PLY refuse such an index), and read a missing index as 0.
TEST(MeshLoader, OffFaceIndicesMustNameVertices)
{
    const std::string head = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n";
    EXPECT_EQ(loadError(head + "3 0 1 2\n", "off"), "");
    const std::pair<std::string, std::string> refused[] = {
        {head + "3 0 1 5\n", "mesh:6: malformed OFF file: its face has the vertex index 5, out of range for its 3 "
                             "vertices (numbered from 0)"},
        {head + "3 0 1\n", "mesh:6: malformed OFF file: its face of 3 vertices has only 2 vertex indices"},
        {head + "3 0 -1 2\n", "mesh:6: malformed OFF file: its face of 3 vertices has '-' where vertex index 2"},
        // Comments and blank lines in the header, and faces the reader skips, are read as it reads them.
        {"# c\nOFF\n\n# 3 vertices\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n0\n3 0 1 2\n3 0 1 3\n", "mesh:11: malformed OFF"},
        {head + "3 0 1 2 " + std::string(5000, ' ') + "\n", "mesh:6: malformed OFF file: its line of 5008 bytes"},
    };
    for (const auto &[text, message] : refused)
    {
        const std::string error = loadError(text, "off");
        EXPECT_NE(error.find(message), std::string::npos) << error;
    }
}

// Found by a hostile-input probe: triangulating a face of n vertices takes assimp about n^2 steps,
// so eight 32,000-vertex OBJ faces (2.8 MB) took over a minute. The sum of n^2 is bounded by
// kPolygonWorkPerTriangle per triangle allowed.
TEST(MeshLoader, PolygonTriangulationWorkIsBounded)
{
    std::string polygon;
    std::string face = "f";
    for (int i = 0; i < 200; ++i)
    {
        const double angle = 2 * 3.141592653589793 * i / 200;
        polygon += "v " + std::to_string(std::cos(angle)) + " " + std::to_string(std::sin(angle)) + " 0\n";
        face += " " + std::to_string(i + 1);
    }
    polygon += face + "\n";
    EXPECT_EQ(loadMeshFromMemory(polygon, "obj", MeshRole::Environment, "polygon.obj").mesh->triangleCount(), 198u);
    MeshLimits limits;
    limits.maxTriangles = 500;  // 25,000 steps; the face takes 40,000
    EXPECT_NE(loadError(polygon, "obj", limits)
                  .find("mesh: the mesh's polygons are too large to triangulate: the sum over its faces of more than "
                        "three vertices of (vertices per face)^2 is 40000, above the limit of 25000"),
              std::string::npos);
}

// Found by a hostile-input probe: a robot near the end of the float range (3e38, finite) was
// refused as "non-finite", because the float sum of its vertices for the centring overflowed.
TEST(MeshLoader, RobotNearTheFloatRangeEndIsCentred)
{
    const std::string far = "v 3e38 0 0\nv 3e38 1 0\nv 3e38 0 1\nf 1 2 3\n";
    const LoadedMesh robot = loadMeshFromMemory(far, "obj", MeshRole::Robot3D, "far.obj");
    EXPECT_FLOAT_EQ(float(robot.centeringShift.x()), 3e38f);
    EXPECT_TRUE(robot.mesh->bounds().max.allFinite());
    // Coordinates that the centring itself takes past the float range are named as such.
    EXPECT_NE(loadError("v 3e38 0 0\nv -3e38 1 0\nv -3e38 0 1\nf 1 2 3\n", "obj")
                  .find("the robot's vertex coordinates, centred on their mean, exceed single precision"),
              std::string::npos);
    // Beyond the float range (a finite double, infinite once read as a float): the OBJ pre-check
    // names the statement, which the reader would read as infinity.
    EXPECT_NE(loadError("v 1e39 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n", "obj")
                  .find(":1: malformed OBJ file: its vertex statement ('v') holds '1e39', beyond the OBJ reader's "
                        "single precision"),
              std::string::npos);
    // The largest float itself is read (no rounding past it).
    EXPECT_TRUE(loadMeshFromMemory("v 3.4028234e38 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n", "obj", MeshRole::Environment,
                                   "largest.obj")
                    .mesh->bounds()
                    .max.allFinite());
}

// Cases a review of the pre-checks found still crashing assimp or reading past its buffers, kept
// in the fuzz corpus: each is refused with its reason, or (the PLY line ends) loads or is refused
// without reading outside the data.
TEST(MeshLoader, PreCheckGapsFoundInReviewAreClosed)
{
    const auto corpusFile = [](const std::string &file) {
        return test::fileText(test::sourcePath("tests/fuzz_corpus/mesh/" + file));
    };
    const std::pair<std::string, std::string> refused[] = {
        // An <instance_node url="#"> finds any node without a name; a visual scene without a name
        // is called "Scene": both cycles.
        {"regression_collada_instance_of_empty_url.dae", "contains itself through <instance_node> references"},
        {"regression_collada_instance_of_default_scene_name.dae", "contains itself through <instance_node>"},
        // source="#" names an array without an id; positions read from an array of names.
        {"regression_collada_accessor_of_array_without_id.dae", "past the array's count of 24"},
        {"regression_collada_positions_from_name_array.dae", "reading numbers from an array of names"},
        {"regression_ply_lines_end_in_returns_only.ply", "its data ends after 1 of its 3 vertex elements"},
    };
    for (const auto &[file, message] : refused)
    {
        const std::string format = file.substr(file.rfind('.') + 1);
        const std::string error = loadError(corpusFile(file), format);
        EXPECT_NE(error.find(message), std::string::npos) << file << ": " << error;
    }
    EXPECT_NE(loadError(corpusFile("regression_zae_holding_instance_cycle.zae"), "zae").find("a zip archive"),
              std::string::npos);
    EXPECT_EQ(loadError(corpusFile("regression_ply_last_line_ends_in_two_returns.ply"), "ply"), "");
    EXPECT_EQ(loadError(corpusFile("regression_ply_trailing_zero_byte.ply"), "ply"), "");
}
