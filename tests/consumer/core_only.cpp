// SPDX-License-Identifier: BSD-3-Clause
// The core library alone, without OMPL: built with `pkg-config --cflags --libs hybridcd` only.
// Usage: core_only PROBLEM.cfg; exits 0 when the start pose is collision-free, as it must be.
#include "hybridcd/io/problem_scene.h"
#include "hybridcd/query/checker_catalogue.h"

#include <iostream>

int main(int argc, char **argv)
{
    if (argc != 2)
    {
        std::cerr << "usage: " << argv[0] << " PROBLEM.cfg\n";
        return 1;
    }
    const hcd::LoadedProblem problem = hcd::loadProblem(argv[1]);
    const hcd::ConfigPose &s = problem.config.start;
    const hcd::RigidTransform start =
        problem.config.planar ? hcd::RigidTransform::fromPlanarPose(s.x, s.y, s.theta)
                              : hcd::RigidTransform::fromAxisAngle(hcd::Vec3(s.x, s.y, s.z),
                                                                   hcd::Vec3(s.axisX, s.axisY, s.axisZ), s.theta);
    const bool hit = hcd::makeChecker("obb", problem.scene)->collides(start);
    std::cout << "start collides: " << hit << '\n';
    return hit ? 1 : 0;
}
