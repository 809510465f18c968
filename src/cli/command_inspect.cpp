// SPDX-License-Identifier: BSD-3-Clause
// `hybridcd inspect`: what was loaded, and what each checker builds from it.
#include "command_line.h"
#include "commands.h"
#include "problem_checks.h"

#include "hybridcd/geometry/solid_components.h"
#include "hybridcd/io/atomic_file.h"
#include "hybridcd/io/input_error.h"
#include "hybridcd/io/pose_codec.h"
#include "hybridcd/io/problem_scene.h"
#include "hybridcd/query/checker_catalogue.h"

#include <chrono>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace hcd::cli
{
namespace
{
std::string formatVec(const Vec3 &v)
{
    std::ostringstream s;
    s << std::setprecision(7) << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
    return s.str();
}

// "N (K closed, i.e. solids: #i (T triangles), ...)".
std::string solidSummary(const TriangleMesh &mesh)
{
    const std::vector<MeshComponent> components = meshComponents(mesh);
    std::ostringstream s;
    std::size_t closed = 0;
    std::string list;
    for (std::size_t i = 0; i < components.size(); ++i)
        if (components[i].closed)
        {
            ++closed;
            if (closed <= 12)
                list += (list.empty() ? "" : ", ") + std::string("#") + std::to_string(i) + " (" +
                        std::to_string(components[i].triangles.size()) + " triangles)";
        }
    // Connected parts, with closed shells that touch only at vertices or shared edges apart.
    s << components.size() << " connected, " << closed << " closed (solids; touching shells apart)";
    if (closed > 0)
        s << ": " << list << (closed > 12 ? ", ..." : "");
    return s.str();
}

void describeMesh(const char *role, const std::string &file, const LoadedMesh &m)
{
    std::cout << role << ": " << (file.empty() ? "(none)" : file) << '\n';
    if (file.empty())
        return;
    const BoundingBox box = m.mesh->bounds();
    std::cout << "  triangles: " << m.mesh->triangleCount() << " (file: " << m.sourceTriangles
              << ", degenerate dropped: " << m.droppedDegenerate
              << ", non-triangle primitives skipped: " << m.skippedNonTriangles << ")\n"
              << "  repeated faces (same corners, either orientation; dropped from the query structures): "
              << withoutRepeatedFaces(m.mesh).dropped << '\n'
              << "  vertices: " << m.mesh->vertices.size() << " (after welding identical ones)\n"
              << "  closed (watertight): " << (isClosed(*m.mesh) ? "yes" : "no") << '\n'
              << "  components: " << solidSummary(*m.mesh) << '\n'
              << "  bounding box: min " << formatVec(box.min) << " max " << formatVec(box.max) << '\n'
              << "  centring shift subtracted: " << formatVec(m.centeringShift) << '\n'
              << "  mesh memory: " << m.mesh->memoryBytes() / 1024.0 << " KiB\n";
}
}  // namespace

void declareInspect(CommandLine &cl)
{
    cl.positionals("PROBLEM.cfg", "the problem (OMPL.app's .cfg format)")
        .option("level", "K", "the tree level --export writes (default 0, the root)")
        .option("export", "FILE.obj", "write the volumes of tree level K as a mesh (the robot's at its start pose)");
    addCheckerOptions(cl, true);
    cl.footer(R"(
Examples:
  hybridcd inspect problems/window_3d.cfg --checker obb,ellipsoid,lp
  hybridcd inspect problems/window_3d.cfg --level 3 --export level3.obj
)");
}

int runInspect(const CommandLine &cl, const CheckerCatalogue &checkers)
{
    const CheckerOptions checkerOptions = checkerOptionsOf(cl);
    const std::vector<std::string> checkerNames = checkerNamesOf(cl, checkers, checkerOptions);
    const int level = treeLevelOf(cl);
    const LoadedProblem problem = loadProblemFor(cl);
    const ProblemConfig &cfg = problem.config;
    if (cl.has("export"))
        checkOutputPath(cl.text("export", ""), "--export", inputFilesOf(problem));
    std::cout << "problem: " << cfg.name << " (" << cfg.path << ")\n"
              << "state space: " << (cfg.planar ? "SE2" : "SE3") << '\n';
    if (!cfg.control.empty())
        std::cout << "control model: " << cfg.control << " (kinodynamic: `solve` plans it with a control planner)\n";
    describeMesh("robot", cfg.robotMesh, problem.robot);
    describeMesh("environment", cfg.worldMesh, problem.world);

    for (const std::string &name : checkerNames)
    {
        const auto start = std::chrono::steady_clock::now();
        const auto checker = checkers.make(name, problem.scene, checkerOptions);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::cout << "checker " << checker->name() << ": built in " << seconds * 1e3 << " ms\n";
        for (const HierarchyReport &h : checker->hierarchies(true))
        {
            std::cout << "  " << h.label << ": " << h.nodes << " nodes, depth " << h.depth << ", build "
                      << h.buildSeconds * 1e3 << " ms, memory " << h.memoryBytes / 1024.0 << " KiB";
            if (h.ratioNodes > 0)
                std::cout << ", mean volume ratio node/content " << h.meanVolumeRatio << " (over " << h.ratioNodes
                          << " non-flat nodes)";
            std::cout << '\n';
        }
        if (cl.has("export"))
        {
            const std::string path = cl.text("export", "");
            AtomicFile obj(path);
            if (!checker->exportLevel(level, obj.stream(), transformOfConfigPose(cfg.start, cfg.planar)))
                throw UsageError("checker '" + name + "' has no hierarchy to export");
            obj.commit();
            std::cout << "  level " << level << " volumes written to " << path << '\n';
        }
    }
    return kSuccess;
}
}  // namespace hcd::cli
