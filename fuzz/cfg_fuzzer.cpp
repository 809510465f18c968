// SPDX-License-Identifier: BSD-3-Clause
// Harness for the .cfg reader: any text either parses into a usable problem or is an InputError.
#include "fuzz_target.h"

#include "hybridcd/io/input_error.h"
#include "hybridcd/io/problem_config.h"

#include <cmath>

namespace hcd::fuzz
{
namespace
{
// The start and goal become OMPL states through these transforms (see planning_problem.cpp).
void checkPose(const ConfigPose &p, bool planar)
{
    check(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && std::isfinite(p.theta),
          "config pose numbers are finite");
    checkRigid(planar ? RigidTransform::fromPlanarPose(p.x, p.y, p.theta)
                      : RigidTransform::fromAxisAngle(Vec3::Zero(), Vec3(p.axisX, p.axisY, p.axisZ), p.theta));
}

void checkRange(const std::optional<std::pair<double, double>> &range)
{
    if (range)
        check(std::isfinite(range->first) && std::isfinite(range->second) && range->first <= range->second,
              "volume ranges are finite and ordered");
}
}  // namespace

int fuzzOne(const std::uint8_t *data, std::size_t size)
{
    try
    {
        // A relative name, so that mesh paths resolve without touching the file system.
        const ProblemConfig cfg = parseProblemConfig(asText(data, size), "fuzz/problem.cfg");
        check(!cfg.robotMesh.empty() && cfg.robotLine > 0, "an accepted problem names its robot mesh");
        check(cfg.worldMesh.empty() == (cfg.worldLine == 0), "a world mesh comes with its line");
        checkPose(cfg.start, cfg.planar);
        checkPose(cfg.goal, cfg.planar);
        checkRange(cfg.volumeX);
        checkRange(cfg.volumeY);
        checkRange(cfg.volumeZ);
        check(cfg.benchmark.runCount >= 1, "run_count is positive");
        check(std::isfinite(cfg.benchmark.timeLimit) && std::isfinite(cfg.benchmark.memoryLimit),
              "benchmark limits are finite");
        for (const PlannerRequest &r : cfg.planners)
            check(!r.type.empty(), "planners have a type");
    }
    catch (const InputError &)
    {
    }
    return 0;
}
}  // namespace hcd::fuzz
