// SPDX-License-Identifier: BSD-3-Clause
// `hybridcd render`: a picture of a problem (PNG) and its scene with the path animated (glTF).
#include "command_line.h"
#include "commands.h"
#include "problem_checks.h"

#include "hybridcd/io/atomic_file.h"
#include "hybridcd/io/input_error.h"
#include "hybridcd/io/path_file.h"
#include "hybridcd/io/pose_codec.h"
#include "hybridcd/io/problem_scene.h"
#include "hybridcd/render/gltf_scene.h"
#include "hybridcd/render/picture.h"
#include "hybridcd/scene/problem_bodies.h"
#include "hybridcd/scene/scene_mesh.h"

#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>
#include <optional>
#include <sstream>

namespace hcd::cli
{
namespace
{
// Where --volumes-at puts the robot's volumes: the start, the goal, or a path state.
RigidTransform volumePose(const CommandLine &cl, const ProblemConfig &cfg, const std::vector<RigidTransform> &path)
{
    const std::string at = cl.text("volumes-at", "start");
    if (at == "start")
        return transformOfConfigPose(cfg.start, cfg.planar);
    if (at == "goal")
        return transformOfConfigPose(cfg.goal, cfg.planar);
    const bool digits = !at.empty() && at.size() < 10 && at.find_first_not_of("0123456789") == std::string::npos;
    const long long index = digits ? std::stoll(at) : -1;
    if (digits && path.empty())
        throw UsageError("option --volumes-at " + at + " names a path state, but no --path is given");
    if (index < 0 || std::size_t(index) >= path.size())
        throw UsageError("option --volumes-at needs start, goal or a path state from 0 to " +
                         std::to_string(path.size() - 1) + ", got '" + at + "'");
    return path[std::size_t(index)];
}

TriangleMesh placedVolumes(const ExportMesh &volumes, const RigidTransform &worldFromRobot)
{
    TriangleMesh mesh;
    mesh.vertices.reserve(volumes.vertices.size());
    for (const Vec3 &v : volumes.vertices)
        mesh.vertices.push_back(worldFromRobot.apply(v));
    for (const auto &t : volumes.triangles)
        mesh.triangles.push_back({std::uint32_t(t[0]), std::uint32_t(t[1]), std::uint32_t(t[2])});
    return mesh;
}
}  // namespace

namespace
{
// A scene problem: its static bodies, every robot at the start (green) and goal (red) and at
// states along the path, and each robot's path line.
void renderScene(const LoadedProblem &problem, const std::string &pathFile, std::size_t samples,
                 const std::optional<render::View> &view, int width, int height, const std::string &out)
{
    const ProblemConfig &cfg = problem.config;
    const std::size_t robots = cfg.robotCount(), columns = poseColumns(cfg.planar);
    std::vector<std::vector<RigidTransform>> states;
    if (!pathFile.empty())
    {
        for (const PoseRecord &r : readPoses(pathFile, cfg.planar, robots))
        {
            std::vector<RigidTransform> state;
            for (std::size_t k = 0; k < robots; ++k)
                state.push_back(transformOfRow(r.values.data() + k * columns, cfg.planar));
            states.push_back(std::move(state));
        }
        if (states.empty())
            throw InputError(pathFile, 0, "the path has no states");
    }
    SceneOptions options;
    options.bruteForce = true;  // no checkers are needed to draw
    const auto scene = makeProblemScene(problem, options);
    std::vector<std::vector<RigidTransform>> shown = {problemStart(cfg), problemGoal(cfg)};
    // States spread evenly by index between the path's ends.
    for (std::size_t k = 1; states.size() > 2 && k <= samples; ++k)
        shown.push_back(states[k * (states.size() - 1) / (samples + 1)]);
    std::vector<std::vector<RigidTransform>> extent = shown;
    extent.insert(extent.end(), states.begin(), states.end());
    const TriangleMesh environment = staticBodiesMesh(*scene, sceneClipBox(*scene, extent));
    std::vector<TriangleMesh> robotMeshes;
    for (const std::vector<RigidTransform> &state : shown)
        robotMeshes.push_back(robotBodiesMesh(*scene, state.data()));

    render::PictureRequest request;
    request.environment = &environment;
    request.robot = &robotMeshes.front();
    request.view = view.value_or(cfg.planar ? render::View::Top : render::View::Isometric);
    request.width = width;
    request.height = height;
    request.placements.push_back({RigidTransform(), request.palette.start, 1.0, 0.35, &robotMeshes[0]});
    request.placements.push_back({RigidTransform(), request.palette.goal, 1.0, 0.35, &robotMeshes[1]});
    for (std::size_t k = 2; k < shown.size(); ++k)
        request.placements.push_back({RigidTransform(),
                                      render::rampColour(request.palette, double(k - 1) / double(shown.size() - 1)),
                                      0.55, 0.2, &robotMeshes[k]});
    for (std::size_t r = 0; r < robots && !states.empty(); ++r)
    {
        std::vector<Vec3> line;
        for (const std::vector<RigidTransform> &state : states)
            line.push_back(state[r].translation);
        (r == 0 ? request.pathLine : request.morePathLines.emplace_back()) = std::move(line);
    }
    const std::string png = render::encodePng(render::renderPicture(request));
    AtomicFile f(out);
    f.stream().write(png.data(), std::streamsize(png.size()));
    f.commit();
}
}  // namespace

void declareRender(CommandLine &cl)
{
    cl.positionals("PROBLEM.cfg", "the problem (OMPL.app's .cfg format)")
        .option("out", "FILE.png", "write a picture: the environment, the robot at start (green) and goal (red)")
        .option("gltf", "FILE.glb", "write the scene as binary glTF 2.0, the path as the robot's animation")
        .option("path", "FILE", "a path (.path format) to draw: its line and robots along it")
        .option("samples", "N", "robots drawn along the path between start and goal (default 6)")
        .option("level", "K", "draw the volumes of level K of the robot's tree around the robot (root 0)")
        .option("volumes-at", "WHERE", "where those volumes sit: start (default), goal, or a path state's index")
        .option("view", "VIEW", "iso (default in 3D), top (default in the plane), front or side")
        .option("width", "PIXELS", "picture width (default 800)")
        .option("height", "PIXELS", "picture height (default 600)");
    addCheckerOptions(cl, false);
    cl.footer(R"(
The picture is drawn by a software rasterizer (no display or GPU needed): flat shading, an
orthographic camera fitted to the scene, robots hidden by the environment shown faintly.

Examples:
  hybridcd render problems/window_3d.cfg --out window.png
  hybridcd solve problems/window_3d.cfg --out window.path
  hybridcd render problems/window_3d.cfg --path window.path --out window.png --gltf window.glb
  hybridcd render problems/window_3d.cfg --checker obb --level 2 --out boxes.png
)");
}

int runRender(const CommandLine &cl, const CheckerCatalogue &checkers)
{
    if (!cl.has("out") && !cl.has("gltf"))
        throw UsageError("render needs --out FILE.png, --gltf FILE.glb or both");
    const CheckerOptions checkerOptions = checkerOptionsOf(cl);
    std::optional<std::string> checkerName;
    if (cl.has("level") || cl.has("checker"))
        checkerName = checkerNamesOf(cl, checkers, checkerOptions).front();
    if (cl.has("checker") && !cl.has("level"))
        throw UsageError("option --checker chooses whose tree --level draws; give --level K too");
    const int level = treeLevelOf(cl);
    const long long width = cl.positiveInteger("width", 800), height = cl.positiveInteger("height", 600);
    for (const auto &[name, value] : {std::pair<const char *, long long>{"width", width}, {"height", height}})
        if (value < 16 || value > 8192)
            throw UsageError(std::string("option --") + name + " needs 16 to 8192 pixels, got " +
                             std::to_string(value));
    const long long samples = cl.has("samples") ? cl.integer("samples", 6) : 6;
    if (samples < 0 || samples > 1000)
        throw UsageError("option --samples needs a count from 0 to 1000, got '" + cl.text("samples", "") + "'");
    std::optional<render::View> view;
    if (cl.has("view"))
    {
        try
        {
            view = render::viewByName(cl.text("view", ""));
        }
        catch (const std::invalid_argument &e)
        {
            throw UsageError(std::string("option --view: ") + e.what());
        }
    }
    const std::string out = cl.text("out", ""), gltf = cl.text("gltf", "");
    for (const auto &[option, name] : {std::pair<const char *, const std::string &>{"out", out}, {"gltf", gltf}})
        if (cl.has(option) && name.empty())
            checkOutputPath(name, std::string("--") + option, {});  // refuses the empty name
    if (!out.empty() && !gltf.empty())
    {
        // The same file however written ("r/a" and "./r/a", or two links to one file).
        std::error_code outError, gltfError, linkError;
        const std::filesystem::path outPath = std::filesystem::weakly_canonical(out, outError),
                                    gltfPath = std::filesystem::weakly_canonical(gltf, gltfError);
        const bool same = out == gltf || (!outError && !gltfError && outPath == gltfPath) ||
                          std::filesystem::equivalent(out, gltf, linkError);
        if (same)
            throw UsageError("options --out and --gltf name the same file ('" + out + "', '" + gltf + "')");
    }

    const LoadedProblem problem = loadProblemFor(cl);
    const ProblemConfig &cfg = problem.config;
    if (cfg.isScene())
    {
        if (!gltf.empty())
            throw UsageError("option --gltf draws one robot; " + cfg.name + " is a scene of " +
                             std::to_string(cfg.robotCount()) + " robots: use --out FILE.png");
        if (checkerName)
            throw UsageError("option --level draws one robot's tree; " + cfg.name + " is a scene problem");
    }
    std::vector<std::string> inputs = inputFilesOf(problem);
    if (cl.has("path"))
        inputs.push_back(cl.text("path", ""));
    if (!out.empty())
        checkOutputPath(out, "--out", inputs);
    if (!gltf.empty())
        checkOutputPath(gltf, "--gltf", inputs);

    if (cfg.isScene())
    {
        renderScene(problem, cl.has("path") ? cl.text("path", "") : "", std::size_t(samples), view, int(width),
                    int(height), out);
        std::cout << "picture written to " << out << " (" << width << "x" << height << ")\n";
        return kSuccess;
    }

    std::vector<RigidTransform> path;
    if (cl.has("path"))
    {
        const std::string file = cl.text("path", "");
        for (const PoseRecord &r : readPoses(file, cfg.planar))
        {
            // glTF stores single-precision floats: a coordinate beyond them would become infinite.
            if (!gltf.empty())
                for (std::size_t k = 0; k < (cfg.planar ? 2 : 3); ++k)
                    if (std::abs(r.values[k]) > double(std::numeric_limits<float>::max()))
                    {
                        std::ostringstream message;
                        message << "the coordinate " << r.values[k]
                                << " is beyond the single precision of glTF (--gltf)";
                        throw InputError(file, r.line, message.str());
                    }
            path.push_back(transformOfRow(r.values.data(), cfg.planar));
        }
        if (path.empty())
            throw InputError(file, 0, "the path has no poses");
    }
    const RigidTransform start = transformOfConfigPose(cfg.start, cfg.planar);
    const RigidTransform goal = transformOfConfigPose(cfg.goal, cfg.planar);

    std::optional<TriangleMesh> volumes;
    if (checkerName)
    {
        const auto checker = checkers.make(*checkerName, problem.scene, checkerOptions);
        const std::optional<LevelVolumes> level_ = checker->levelVolumes(level);
        if (!level_)
            throw UsageError("checker '" + *checkerName + "' has no hierarchy to draw; choose one with a tree (" +
                             "e.g. obb, ellipsoid)");
        if (std::size_t(level) >= level_->robotDepth)
            throw UsageError("option --level " + std::to_string(level) + " is beyond the robot's " + level_->kind +
                             " tree, whose levels are 0 to " + std::to_string(level_->robotDepth - 1));
        volumes = placedVolumes(level_->robot, volumePose(cl, cfg, path));
    }

    std::string png;
    if (!out.empty())
    {
        render::PictureRequest request;
        request.environment = problem.world.mesh.get();
        request.robot = problem.robot.mesh.get();
        request.view = view.value_or(cfg.planar ? render::View::Top : render::View::Isometric);
        request.width = int(width);
        request.height = int(height);
        request.placements.push_back({start, request.palette.start, 1.0, 0.35});
        request.placements.push_back({goal, request.palette.goal, 1.0, 0.35});
        if (!path.empty())
        {
            // The sampled poses between the path's ends (which the start and goal already show).
            const std::vector<RigidTransform> along = render::samplePath(path, std::size_t(samples) + 2);
            for (std::size_t k = 1; k + 1 < along.size(); ++k)
                request.placements.push_back(
                    {along[k], render::rampColour(request.palette, double(k) / double(along.size() - 1)), 0.55, 0.2});
            for (const RigidTransform &p : path)
                request.pathLine.push_back(p.translation);
        }
        if (volumes)
            request.volumes = &*volumes;
        png = render::encodePng(render::renderPicture(request));
    }
    std::string glb;
    if (!gltf.empty())
    {
        render::GltfRequest request;
        request.environment = problem.world.mesh.get();
        request.robot = problem.robot.mesh.get();
        request.start = start;
        request.path = path;
        glb = render::glbBytes(request);
    }

    // Both files are made in memory first, so a failure leaves neither half-written.
    for (const auto &[file, bytes] : {std::pair<const std::string &, const std::string &>{out, png}, {gltf, glb}})
    {
        if (file.empty())
            continue;
        AtomicFile f(file);
        f.stream().write(bytes.data(), std::streamsize(bytes.size()));
        f.commit();
    }
    if (!out.empty())
        std::cout << "picture written to " << out << " (" << width << "x" << height << ")\n";
    if (!gltf.empty())
        std::cout << "glTF scene written to " << gltf << " (" << path.size() << " keyframes)\n";
    return kSuccess;
}
}  // namespace hcd::cli
