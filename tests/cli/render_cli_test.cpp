// SPDX-License-Identifier: BSD-3-Clause
// `hybridcd render` as a user runs it: the picture's content on a problem written here (so the
// expected pixels follow from its numbers), the glTF read back, and clear errors on bad input.
#include "support/test_support.h"

#include "hybridcd/io/path_file.h"

#include <gtest/gtest.h>
#include <stb_image.h>
#include <tiny_gltf.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

using namespace hcd;

namespace
{
using CliRun = test::ShellResult;

CliRun run(const std::string &args) { return test::runShell(std::string(HYBRIDCD_CLI) + " " + args); }

std::string objText(const TriangleMesh &mesh)
{
    std::ostringstream s;
    s.precision(17);
    for (const Vec3 &v : mesh.vertices)
        s << "v " << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
    for (const auto &t : mesh.triangles)
        s << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
    return s.str();
}

// A planar problem: a 20 x 10 m floor slab, a 2 x 1 m block robot, start at (4, 3), goal at
// (16, 7) turned a quarter; its path goes by (10, 3).
struct FloorProblem
{
    std::string cfg, path;
    FloorProblem()
    {
        test::writeTempFile("render_env.obj", objText(test::boxMesh(Vec3(0, 0, -1), Vec3(20, 10, 0))));
        test::writeTempFile("render_robot.obj", objText(test::boxMesh(Vec3(-1, -0.5, 0), Vec3(1, 0.5, 1))));
        cfg = test::writeTempFile("render.cfg", "[problem]\nrobot = render_robot.obj\nworld = render_env.obj\n"
                                                "start.x = 4\nstart.y = 3\nstart.theta = 0\n"
                                                "goal.x = 16\ngoal.y = 7\ngoal.theta = 1.5707963267948966\n");
        path = test::writeTempFile("render.path", "4 3 0\n10 3 0.5\n16 7 1.5707963267948966\n");
    }
};

struct Decoded
{
    int width = 0, height = 0;
    std::vector<unsigned char> rgb;
    const unsigned char *at(int x, int y) const { return &rgb[(std::size_t(y) * std::size_t(width) + x) * 3]; }
};

Decoded decodePng(const std::string &file)
{
    Decoded d;
    int channels = 0;
    unsigned char *data = stbi_load(file.c_str(), &d.width, &d.height, &channels, 3);
    EXPECT_NE(data, nullptr) << file << ": " << stbi_failure_reason();
    if (data)
        d.rgb.assign(data, data + std::size_t(d.width) * std::size_t(d.height) * 3);
    stbi_image_free(data);
    return d;
}

// The 400 x 240 top view of FloorProblem: the floor's 20 m span 400 less 2 x 4% of 240 pixels
// (the height leaves more room: 10 m in 240 - 19.2), centred. Pixel centre of world (x, y).
std::pair<int, int> pixelOf(double x, double y)
{
    const double scale = (400.0 - 2 * 0.04 * 240.0) / 20.0;
    return {int(200.0 + (x - 10.0) * scale), int(120.0 - (y - 5.0) * scale)};
}

bool isGreen(const unsigned char *p) { return p[1] > p[0] + 40 && p[1] > p[2] + 40; }
bool isRed(const unsigned char *p) { return p[0] > p[1] + 40 && p[0] > p[2] + 40; }
bool isGrey(const unsigned char *p) { return p[0] == p[1] && p[1] == p[2] && p[0] < 255; }
bool isWhite(const unsigned char *p) { return p[0] == 255 && p[1] == 255 && p[2] == 255; }
std::string rgbText(const unsigned char *p)
{
    return std::to_string(p[0]) + " " + std::to_string(p[1]) + " " + std::to_string(p[2]);
}
}  // namespace

TEST(RenderCli, PictureShowsFloorRobotsAndPathWhereTheyProject)
{
    const FloorProblem problem;
    const std::string out = test::writeTempFile("render.png", "");
    std::filesystem::remove(out);
    const CliRun r =
        run("render " + problem.cfg + " --path " + problem.path + " --samples 0 --width 400 --height 240 --out " + out);
    ASSERT_EQ(r.status, 0) << r.output;
    const Decoded image = decodePng(out);
    ASSERT_EQ(image.width, 400);
    ASSERT_EQ(image.height, 240);
    // The start robot (2 x 1 m, unturned) and the goal robot (turned: 1 x 2 m).
    for (const auto &[dx, dy] : {std::pair<double, double>{0, 0}, {0.8, 0.35}, {-0.8, -0.35}})
    {
        const auto [sx, sy] = pixelOf(4 + dx, 3 + dy);
        EXPECT_TRUE(isGreen(image.at(sx, sy))) << sx << "," << sy << ": " << rgbText(image.at(sx, sy));
        const auto [gx, gy] = pixelOf(16 + dy, 7 + dx);
        EXPECT_TRUE(isRed(image.at(gx, gy))) << gx << "," << gy << ": " << rgbText(image.at(gx, gy));
    }
    // Beside the goal along its short side: floor, since it is turned.
    const auto [fx, fy] = pixelOf(16 + 0.9, 7);
    EXPECT_TRUE(isGrey(image.at(fx, fy))) << rgbText(image.at(fx, fy));
    // Floor far from everything, and the background outside it.
    const auto [ex, ey] = pixelOf(2, 8);
    EXPECT_TRUE(isGrey(image.at(ex, ey))) << rgbText(image.at(ex, ey));
    EXPECT_TRUE(isWhite(image.at(2, 2))) << rgbText(image.at(2, 2));
    EXPECT_TRUE(isWhite(image.at(200, 236))) << rgbText(image.at(200, 236));
    // The path's line between (4, 3) and (10, 3): dark blue, not floor.
    const auto [lx, ly] = pixelOf(7, 3);
    const unsigned char *line = image.at(lx, ly);
    EXPECT_GT(line[2], line[0] + 40) << rgbText(line);
    const auto [nx, ny] = pixelOf(7, 4);
    EXPECT_TRUE(isGrey(image.at(nx, ny))) << rgbText(image.at(nx, ny));
}

TEST(RenderCli, LevelVolumesSitAroundTheRobotAtItsPose)
{
    const FloorProblem problem;
    const std::string plain = test::writeTempFile("plain.png", ""), boxed = test::writeTempFile("boxed.png", "");
    ASSERT_EQ(run("render " + problem.cfg + " --width 400 --height 240 --out " + plain).status, 0);
    for (const std::string where : {"start", "goal", "1"})
    {
        const CliRun r =
            run("render " + problem.cfg + " --path " + problem.path + " --samples 0 --checker obb --level 0 " +
                "--volumes-at " + where + " --width 400 --height 240 --out " + boxed);
        ASSERT_EQ(r.status, 0) << r.output;
        const Decoded before = decodePng(plain), after = decodePng(boxed);
        // The root box of the robot is the robot's own box: amber blends over the robot there.
        const std::pair<double, double> at = where == "start"  ? std::pair{4.0, 3.0}
                                             : where == "goal" ? std::pair{16.0, 7.0}
                                                               : std::pair{10.0, 3.0};
        const auto [x, y] = pixelOf(at.first, at.second);
        const unsigned char *p = after.at(x, y);
        const unsigned char *q = before.at(x, y);
        // The pixel moves towards the volumes' amber (0.95, 0.75, 0.10).
        const auto fromAmber = [](const unsigned char *c) {
            return std::hypot(c[0] - 242.0, c[1] - 191.0, c[2] - 25.0);
        };
        EXPECT_LT(fromAmber(p), fromAmber(q) - 25) << where << ": " << rgbText(q) << " -> " << rgbText(p);
        // And nowhere near the origin of the robot's frame, where the volumes used to come out.
        const auto [ox, oy] = pixelOf(0.3, 0.3);
        EXPECT_EQ(rgbText(after.at(ox, oy)), rgbText(before.at(ox, oy))) << where;
    }
}

TEST(RenderCli, GltfHoldsTheMeshesAndThePathAsKeyframes)
{
    const FloorProblem problem;
    const std::string glb = test::writeTempFile("render.glb", "");
    const CliRun r = run("render " + problem.cfg + " --path " + problem.path + " --gltf " + glb);
    ASSERT_EQ(r.status, 0) << r.output;
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    std::string error, warning;
    ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &error, &warning, glb)) << error;
    ASSERT_EQ(model.nodes.size(), 3u);
    ASSERT_EQ(model.animations.size(), 1u);
    const std::vector<PoseRecord> poses = readPoses(problem.path, true);
    for (const tinygltf::AnimationChannel &channel : model.animations[0].channels)
    {
        const tinygltf::AnimationSampler &sampler = model.animations[0].samplers.at(std::size_t(channel.sampler));
        EXPECT_EQ(model.accessors.at(std::size_t(sampler.input)).count, poses.size());
        const tinygltf::Accessor &a = model.accessors.at(std::size_t(sampler.output));
        const tinygltf::BufferView &v = model.bufferViews.at(std::size_t(a.bufferView));
        const float *values = reinterpret_cast<const float *>(model.buffers[0].data.data() + v.byteOffset);
        for (std::size_t i = 0; i < poses.size(); ++i)
        {
            const double x = poses[i].values[0], y = poses[i].values[1], yaw = poses[i].values[2];
            if (channel.target_path == "translation")
            {
                EXPECT_EQ(values[3 * i], float(x));
                EXPECT_EQ(values[3 * i + 1], float(y));
                EXPECT_EQ(values[3 * i + 2], 0.0f);
            }
            else  // a turn by yaw about z: (0, 0, sin(yaw/2), cos(yaw/2)) up to sign
            {
                const double sign = values[4 * i + 3] < 0 ? -1.0 : 1.0;
                EXPECT_NEAR(values[4 * i], 0.0, 1e-7);
                EXPECT_NEAR(values[4 * i + 1], 0.0, 1e-7);
                EXPECT_NEAR(sign * values[4 * i + 2], std::sin(yaw / 2), 1e-6);
                EXPECT_NEAR(sign * values[4 * i + 3], std::cos(yaw / 2), 1e-6);
            }
        }
    }
    const tinygltf::Mesh &robot = model.meshes.at(std::size_t(model.nodes.back().mesh));
    EXPECT_EQ(model.accessors.at(std::size_t(robot.primitives[0].attributes.at("POSITION"))).count, 8u);
}

TEST(RenderCli, BadInputExitsOneAndWritesNothing)
{
    const FloorProblem problem;
    const std::string badPath = test::writeTempFile("bad_render.path", "4 3 0\n10 three 0\n");
    const std::string emptyPath = test::writeTempFile("empty_render.path", "# nothing\n");
    const std::string out = (std::filesystem::path(problem.cfg).parent_path() / "never.png").string();
    const std::string glb = (std::filesystem::path(problem.cfg).parent_path() / "never.glb").string();
    struct Case
    {
        std::string args, expected;
    };
    const Case cases[] = {
        {"render /no/such/problem.cfg --out " + out, "/no/such/problem.cfg"},
        {"render " + problem.cfg + " --path /no/such/file.path --out " + out, "/no/such/file.path"},
        {"render " + problem.cfg + " --path " + badPath + " --out " + out, "bad_render.path:2:"},
        {"render " + problem.cfg + " --path " + emptyPath + " --out " + out, "the path has no poses"},
        {"render " + problem.cfg + " --checker nosuch --level 1 --out " + out, "valid checkers: obb"},
        {"render " + problem.cfg + " --checker obb --level 40 --out " + out,
         "--level 40 is beyond the robot's OBB tree"},
        {"render " + problem.cfg + " --checker bruteforce --level 0 --out " + out, "has no hierarchy"},
        {"render " + problem.cfg + " --level -1 --out " + out, "non-negative"},
        {"render " + problem.cfg + " --checker obb --out " + out, "give --level K too"},
        {"render " + problem.cfg + " --path " + problem.path + " --level 0 --volumes-at 7 --out " + out,
         "a path state from 0 to 2"},
        {"render " + problem.cfg + " --level 0 --volumes-at 1 --out " + out, "no --path"},
        {"render " + problem.cfg + " --view diagonal --out " + out, "unknown view 'diagonal'"},
        {"render " + problem.cfg + " --width 5 --out " + out, "16 to 8192"},
        {"render " + problem.cfg, "needs --out"},
        {"render " + problem.cfg + " --out " + problem.cfg, "render.cfg"},
        {"render " + problem.cfg + " --out " + out + " --gltf " + out, "the same file"},
        {"render " + problem.cfg + " --out /no/such/dir/x.png", "/no/such/dir"},
        {"render " + problem.cfg + " --gltf " + glb + " --path " + badPath, "bad_render.path:2:"},
    };
    for (const Case &c : cases)
    {
        const CliRun r = run(c.args);
        EXPECT_EQ(r.status, 1) << c.args << "\n" << r.output;
        EXPECT_NE(r.output.find(c.expected), std::string::npos) << c.args << "\n" << r.output;
        EXPECT_FALSE(std::filesystem::exists(out)) << c.args;
        EXPECT_FALSE(std::filesystem::exists(glb)) << c.args;
    }
    // The problem file itself was not replaced.
    std::ifstream cfg(problem.cfg);
    std::string first;
    std::getline(cfg, first);
    EXPECT_EQ(first, "[problem]");
}

TEST(RenderCli, InspectExportPlacesTheRobotsVolumesAtTheStart)
{
    const FloorProblem problem;
    const std::string obj = test::writeTempFile("levels.obj", "");
    const CliRun r = run("inspect " + problem.cfg + " --level 0 --export " + obj);
    ASSERT_EQ(r.status, 0) << r.output;
    std::ifstream in(obj);
    std::string line, group;
    Vec3 sum = Vec3::Zero();
    int count = 0;
    while (std::getline(in, line))
    {
        if (line.rfind("g ", 0) == 0)
            group = line.substr(2);
        else if (line.rfind("v ", 0) == 0 && group == "robot")
        {
            std::istringstream s(line.substr(2));
            Vec3 v;
            s >> v.x() >> v.y() >> v.z();
            sum += v;
            ++count;
        }
    }
    ASSERT_EQ(count, 8);  // the root box
    const Vec3 mean = sum / count;
    EXPECT_NEAR(mean.x(), 4.0, 1e-4);
    EXPECT_NEAR(mean.y(), 3.0, 1e-4);
}

TEST(RenderCli, ScriptDrawsEveryProblemWithASolvedPath)
{
    // scripts/render_problems.sh on the project's problems: no .path beside them, so each is solved.
    const std::string folder =
        (std::filesystem::path(test::writeTempFile("pictures.keep", "")).parent_path() / "pictures").string();
    std::filesystem::remove_all(folder);
    const CliRun r = test::runShell(
        "HYBRIDCD_CLI=" + std::string(HYBRIDCD_CLI) + " bash " + test::sourcePath("scripts/render_problems.sh") + " " +
        folder + " " + test::sourcePath("problems/corridor_2d.cfg") + " " + test::sourcePath("problems/window_3d.cfg"));
    ASSERT_EQ(r.status, 0) << r.output;
    for (const char *name : {"corridor_2d", "window_3d"})
    {
        EXPECT_NE(r.output.find(std::string(name) + ": " + folder + "/" + name + ".png, path solved into"),
                  std::string::npos)
            << r.output;
        const std::string cfg = test::sourcePath(std::string("problems/") + name + ".cfg");
        const bool planar = std::string(name) == "corridor_2d";
        EXPECT_GE(readPoses(folder + "/" + name + ".path", planar).size(), 2u) << name;
        // The path shows: the picture differs from the problem's picture without it.
        const std::string bare = folder + "/" + name + ".bare.png";
        ASSERT_EQ(run("render " + cfg + " --out " + bare).status, 0);
        const Decoded with = decodePng(folder + "/" + name + ".png"), without = decodePng(bare);
        ASSERT_EQ(with.width, 800);
        ASSERT_EQ(with.height, 600);
        ASSERT_EQ(with.rgb.size(), without.rgb.size());
        std::size_t differing = 0;
        for (std::size_t i = 0; i < with.rgb.size(); i += 3)
            differing += std::memcmp(&with.rgb[i], &without.rgb[i], 3) != 0;
        EXPECT_GT(differing, 500u) << name;
    }
    // The index lists each problem with its picture and where its path came from.
    std::ifstream indexFile(folder + "/index.md");
    std::stringstream indexText;
    indexText << indexFile.rdbuf();
    const std::string index = indexText.str();
    for (const char *name : {"corridor_2d", "window_3d"})
        EXPECT_NE(index.find(std::string("| ![") + name + "](" + name + ".png) | " + name + " | path solved into " +
                             name + ".path"),
                  std::string::npos)
            << index;
    // A second run keeps the verified paths of the first (no solving) and draws at the size asked for.
    const CliRun again = test::runShell("RENDER_WIDTH=200 RENDER_HEIGHT=150 HYBRIDCD_CLI=" + std::string(HYBRIDCD_CLI) +
                                        " bash " + test::sourcePath("scripts/render_problems.sh") + " " + folder + " " +
                                        test::sourcePath("problems/corridor_2d.cfg"));
    ASSERT_EQ(again.status, 0) << again.output;
    EXPECT_NE(again.output.find("(from an earlier run), verified:"), std::string::npos) << again.output;
    const Decoded small = decodePng(folder + "/corridor_2d.png");
    EXPECT_EQ(small.width, 200);
    EXPECT_EQ(small.height, 150);
    // A path placed by hand says how it was made on its first line; the index repeats it.
    {
        std::ifstream in(folder + "/corridor_2d.path");
        std::stringstream poses;
        poses << in.rdbuf();
        std::ofstream(folder + "/corridor_2d.path") << "# source: placed by hand for this test\n" << poses.str();
    }
    const CliRun byHand = test::runShell("HYBRIDCD_CLI=" + std::string(HYBRIDCD_CLI) + " bash " +
                                         test::sourcePath("scripts/render_problems.sh") + " " + folder + " " +
                                         test::sourcePath("problems/corridor_2d.cfg"));
    ASSERT_EQ(byHand.status, 0) << byHand.output;
    EXPECT_NE(byHand.output.find("(placed by hand for this test), verified:"), std::string::npos) << byHand.output;
    // A problem that cannot be loaded is reported, and the script fails.
    const CliRun bad =
        test::runShell("HYBRIDCD_CLI=" + std::string(HYBRIDCD_CLI) + " bash " +
                       test::sourcePath("scripts/render_problems.sh") + " " + folder + " /no/such/problem.cfg");
    EXPECT_EQ(bad.status, 1) << bad.output;
    EXPECT_NE(bad.output.find("problem: not drawn:"), std::string::npos) << bad.output;
}

TEST(RenderCli, DrawsASceneProblemWithEveryRobotAndObstacle)
{
    // problems/crossing_2d.cfg: three robots among half-space walls and primitive obstacles.
    const std::string cfg = test::sourcePath("problems/crossing_2d.cfg");
    const std::string bare = test::writeTempFile("crossing.png", ""),
                      withPath = test::writeTempFile("crossing_path.png", "");
    ASSERT_EQ(run("render " + cfg + " --out " + bare + " --width 400 --height 260").status, 0);
    const Decoded image = decodePng(bare);
    ASSERT_EQ(image.width, 400);
    // Grey obstacles, green robots at the start and red ones at the goal, each a real share of the picture.
    std::size_t grey = 0, green = 0, red = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
        {
            const unsigned char *p = image.at(x, y);
            grey += p[0] == p[1] && p[1] == p[2] && p[0] < 235 ? 1 : 0;
            green += p[1] > p[0] + 60 && p[1] > p[2] + 60 ? 1 : 0;
            red += p[0] > p[1] + 80 && p[0] > p[2] + 80 ? 1 : 0;
        }
    const std::size_t pixels = std::size_t(image.width) * std::size_t(image.height);
    EXPECT_GT(grey, pixels / 10);
    EXPECT_GT(green, pixels / 200);
    EXPECT_GT(red, pixels / 200);
    // The middle wall box stands at the centre of the hall, which is the centre of the top view.
    const unsigned char *centre = image.at(image.width / 2, image.height / 2);
    EXPECT_TRUE(centre[0] == centre[1] && centre[1] == centre[2] && centre[0] < 235)
        << int(centre[0]) << " " << int(centre[1]) << " " << int(centre[2]);
    // A path of all three robots (start to goal, straight) adds its lines and robots.
    const std::string path = test::writeTempFile(
        "crossing_line.path", "-15 -8 0 -15 8 0 15 0 0\n0 0 0 0 0 0 0 0 0\n15 8 0 15 -8 1.5707963267948966 -15 0 0\n");
    ASSERT_EQ(run("render " + cfg + " --path " + path + " --out " + withPath + " --width 400 --height 260").status, 0);
    const Decoded lined = decodePng(withPath);
    std::size_t differing = 0;
    for (std::size_t i = 0; i < lined.rgb.size(); i += 3)
        differing += std::memcmp(&lined.rgb[i], &image.rgb[i], 3) != 0;
    EXPECT_GT(differing, 500u);
    // One robot's glTF animation cannot hold a scene: refused, nothing written.
    const CliRun gltf = run("render " + cfg + " --gltf " + test::writeTempFile("crossing.glb", "") + " 2>&1");
    EXPECT_EQ(gltf.status, 1) << gltf.output;
    EXPECT_NE(gltf.output.find("scene of 3 robots"), std::string::npos) << gltf.output;
}
