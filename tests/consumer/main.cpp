// SPDX-License-Identifier: BSD-3-Clause
// hybridcd as a library: load an OMPL.app problem, query a checker, plan with OMPL.
// Usage: consumer PROBLEM.cfg (e.g. problems/window_3d.cfg). Built against an installed hybridcd.
#include "hybridcd/io/problem_scene.h"
#include "hybridcd/ompl/planning_problem.h"
#include "hybridcd/planners/planner_catalogue.h"
#include "hybridcd/query/checker_catalogue.h"

#include <iostream>
#include <memory>

int main(int argc, char **argv)
{
    if (argc != 2)
    {
        std::cerr << "usage: " << argv[0] << " PROBLEM.cfg\n";
        return 1;
    }
    hcd::LoadedProblem problem = hcd::loadProblem(argv[1]);  // throws hcd::InputError on bad input
    std::shared_ptr<const hcd::CollisionChecker> checker = hcd::makeChecker("obb", problem.scene);
    const hcd::RigidTransform pose = hcd::RigidTransform::fromTranslationQuaternion(hcd::Vec3(1, 2, 3), 1, 0, 0, 0);
    const bool hit = checker->collides(pose);        // thread-safe; solids by default
    const double d = checker->distance(pose);        // 0 in contact
    const auto parts = checker->contacts(pose, 10);  // intersecting triangle pairs + witnesses
    const auto surface = hcd::makeChecker("obb", problem.scene, hcd::ContactSemantics::SurfaceOnly);
    std::cout << "collides: " << hit << ", distance: " << d << ", contacts: " << parts.size()
              << ", surface-only collides: " << surface->collides(pose) << '\n';

    hcd::PlanningProblem planning = hcd::makePlanningProblem(problem, checker);  // OMPL SimpleSetup
    planning.setup->setPlanner(hcd::makePlanner({"rrtconnect", "", {}}, planning.setup->getSpaceInformation()));
    const bool solved = bool(planning.setup->solve(10.0));
    std::cout << "solved: " << solved << '\n';
    return solved ? 0 : 2;
}
