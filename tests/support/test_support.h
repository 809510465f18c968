// SPDX-License-Identifier: BSD-3-Clause
// Shared helpers for the tests: where OMPL.app's problems are, random poses, scene builders.
#pragma once

#include "hybridcd/geometry/rigid_transform.h"
#include "hybridcd/geometry/triangle_mesh.h"
#include "hybridcd/io/problem_scene.h"

#include <cstdint>
#include <optional>
#include <random>
#include <string>

namespace hcd::test
{
/// Pinned generator type so sequences are the same on every platform.
using TestRandom = std::mt19937_64;

/// The run's seed: $HYBRIDCD_TEST_SEED, else 1. OMPL's generator is reseeded with it before every
/// test (tests/support/test_main.cpp), and tests that draw their own samples may mix it into their
/// fixed seeds with seeded(). A failing test prints it.
std::uint64_t seed();

/// `base` when the run's seed is the default (1), otherwise a mix of both: the same test with
/// another HYBRIDCD_TEST_SEED explores other samples, and with none it is unchanged.
std::uint64_t seeded(std::uint64_t base);

/// How much fewer random cases the heaviest tests draw in sanitizer builds, where each case costs
/// 10-50x more (exact arithmetic above all): the same checks on fewer cases keep CI within its time.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
inline constexpr int kSanitizerCaseDivisor = 8;
#else
inline constexpr int kSanitizerCaseDivisor = 1;
#endif

/// `count` random cases, or an eighth of them (at least one) in sanitizer builds.
constexpr int cases(int count) { return count / kSanitizerCaseDivisor > 0 ? count / kSanitizerCaseDivisor : 1; }

/// True when running in CI ($CI is "true" or "1"): missing OMPL.app resources are then a failure,
/// since a quarter of the suite would otherwise be skipped without a trace.
bool inContinuousIntegration();

/// Folder holding OMPL.app's 2D/ and 3D/ problems: $HYBRIDCD_OMPLAPP_RESOURCES, else the
/// configured default (../shared/omplapp-resources beside the source tree). Empty if absent.
std::string omplappResources();

/// Full path of an OMPL.app problem such as "3D/cubicles.cfg", or nullopt if the resources are
/// absent (tests then GTEST_SKIP with a message naming the variable to set).
std::optional<std::string> omplappProblem(const std::string &relative);

/// Path of a file in the source tree, e.g. "problems/window_3d.cfg".
std::string sourcePath(const std::string &relative);

/// A uniformly random rotation (Shoemake's method).
Mat3 randomRotation(TestRandom &rng);

/// Random poses for a problem: half with the robot centre uniform in the environment's bounding
/// box, half near a random environment vertex, so that free and colliding poses both occur often.
/// Planar problems get planar poses (rotation about z only).
std::vector<RigidTransform> randomPoses(const LoadedProblem &problem, std::size_t count, TestRandom &rng);

/// An axis-aligned closed box [lo, hi] as 12 triangles.
TriangleMesh boxMesh(const Vec3 &lo, const Vec3 &hi);

/// Exit status and combined stdout + stderr of a shell command (-1 when it did not exit normally).
struct ShellResult
{
    int status;
    std::string output;
};
ShellResult runShell(const std::string &command);

/// Writes `text` to a fresh file in the test's temporary folder and returns its path.
std::string writeTempFile(const std::string &name, const std::string &text);

/// The bytes of the file at `path`, read as they are (empty when it cannot be opened).
std::string fileText(const std::string &path);

/// Skips the test with `message`, or fails it in CI where nothing may be skipped silently.
#define HYBRIDCD_SKIP_OR_FAIL_IN_CI(message)                                                                           \
    do                                                                                                                 \
    {                                                                                                                  \
        if (::hcd::test::inContinuousIntegration())                                                                    \
            FAIL() << message;                                                                                         \
        GTEST_SKIP() << message;                                                                                       \
    } while (false)

/// Binds `var` to the folder of OMPL.app's problems; skips (fails in CI) when it is absent.
#define HYBRIDCD_REQUIRE_OMPLAPP_ROOT(var)                                                                             \
    const std::string var = ::hcd::test::omplappResources();                                                           \
    if (var.empty())                                                                                                   \
    HYBRIDCD_SKIP_OR_FAIL_IN_CI("OMPL.app resources not found; set HYBRIDCD_OMPLAPP_RESOURCES")

/// Message for a missing OMPL.app resource.
#define HYBRIDCD_OMPLAPP_MISSING(relative)                                                                             \
    "OMPL.app resources not found; set HYBRIDCD_OMPLAPP_RESOURCES to the folder holding 2D/ and 3D/ "                  \
    "(looked for " relative ")"

/// Skips the test when an OMPL.app resource is absent, or fails it in CI.
#define HYBRIDCD_REQUIRE_OMPLAPP(var, relative)                                                                        \
    const auto var##_opt = ::hcd::test::omplappProblem(relative);                                                      \
    if (!var##_opt)                                                                                                    \
        HYBRIDCD_SKIP_OR_FAIL_IN_CI(HYBRIDCD_OMPLAPP_MISSING(relative));                                               \
    const std::string var = *var##_opt
}  // namespace hcd::test
