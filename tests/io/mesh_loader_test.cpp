// SPDX-License-Identifier: BSD-3-Clause
#include "support/test_support.h"

#include "hybridcd/io/input_error.h"
#include "hybridcd/io/mesh_loader.h"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <utility>

#include <sstream>

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
    std::ifstream in(test::sourcePath("tests/fuzz_corpus/mesh/tet.dae"));
    const std::string tet((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
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
    std::ifstream in(test::sourcePath("tests/fuzz_corpus/mesh/tet.dae"));
    const std::string tet((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
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
