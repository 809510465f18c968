// SPDX-License-Identifier: BSD-3-Clause
#include "support/test_support.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sys/wait.h>
#include <unistd.h>

namespace hcd::test
{
std::uint64_t seed()
{
    const char *env = std::getenv("HYBRIDCD_TEST_SEED");
    if (!env || !*env)
        return 1;
    char *end = nullptr;
    const unsigned long long value = std::strtoull(env, &end, 10);
    if (*end != '\0' || value == 0)
    {
        std::fprintf(stderr, "HYBRIDCD_TEST_SEED must be a positive integer, got '%s'\n", env);
        std::exit(2);
    }
    return value;
}

std::uint64_t seeded(std::uint64_t base)
{
    const std::uint64_t s = seed();
    if (s == 1)
        return base;
    // SplitMix64 finaliser: nearby seeds give unrelated streams.
    std::uint64_t z = base + 0x9E3779B97F4A7C15ull * s;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

bool inContinuousIntegration()
{
    const char *ci = std::getenv("CI");
    return ci && (std::string(ci) == "true" || std::string(ci) == "1");
}

std::string omplappResources()
{
    const char *env = std::getenv("HYBRIDCD_OMPLAPP_RESOURCES");
    const std::string dir = env && *env ? env : HYBRIDCD_DEFAULT_OMPLAPP_RESOURCES;
    return std::filesystem::is_directory(dir) ? dir : std::string();
}

std::optional<std::string> omplappProblem(const std::string &relative)
{
    const std::string dir = omplappResources();
    if (dir.empty())
        return std::nullopt;
    const std::string path = dir + "/" + relative;
    if (!std::filesystem::exists(path))
        return std::nullopt;
    return path;
}

std::string sourcePath(const std::string &relative) { return std::string(HYBRIDCD_SOURCE_DIR) + "/" + relative; }

Mat3 randomRotation(TestRandom &rng)
{
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const double u1 = u(rng), u2 = 2.0 * M_PI * u(rng), u3 = 2.0 * M_PI * u(rng);
    const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
    const Eigen::Quaterniond q(b * std::cos(u3), a * std::sin(u2), a * std::cos(u2), b * std::sin(u3));
    return q.normalized().toRotationMatrix();
}

std::vector<RigidTransform> randomPoses(const LoadedProblem &problem, std::size_t count, TestRandom &rng)
{
    const TriangleMesh &env = *problem.world.mesh;
    const BoundingBox box = env.bounds();
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const double robotRadius = problem.robot.mesh->radiusAboutOrigin();
    std::vector<RigidTransform> poses;
    poses.reserve(count);
    for (std::size_t i = 0; i < count; ++i)
    {
        Vec3 centre;
        if (i % 2 == 0)
            centre = box.min + (box.max - box.min).cwiseProduct(Vec3(u(rng), u(rng), u(rng)));
        else
        {
            const Vec3 &v = env.vertices[std::size_t(u(rng) * double(env.vertices.size())) % env.vertices.size()];
            centre = v + robotRadius * Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
        }
        if (problem.config.planar)
            poses.push_back(RigidTransform::fromPlanarPose(centre.x(), centre.y(), 2.0 * M_PI * u(rng)));
        else
            poses.push_back({randomRotation(rng), centre});
    }
    return poses;
}

TriangleMesh boxMesh(const Vec3 &lo, const Vec3 &hi)
{
    TriangleMesh m;
    for (int i = 0; i < 8; ++i)
        m.vertices.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
    const std::uint32_t faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                       {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto &f : faces)
    {
        m.triangles.push_back({f[0], f[1], f[2]});
        m.triangles.push_back({f[0], f[2], f[3]});
    }
    return m;
}

ShellResult runShell(const std::string &command)
{
    FILE *pipe = popen((command + " 2>&1").c_str(), "r");
    if (!pipe)
        return {-1, "popen failed for: " + command};
    std::string out;
    std::array<char, 4096> buffer{};
    while (std::size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe))
        out.append(buffer.data(), n);
    const int raw = pclose(pipe);
    return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, out};
}

std::string writeTempFile(const std::string &name, const std::string &text)
{
    const auto dir = std::filesystem::temp_directory_path() / ("hybridcd-tests-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const auto path = dir / name;
    std::ofstream(path) << text;
    return path.string();
}

std::string fileText(const std::string &path)
{
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}
}  // namespace hcd::test
