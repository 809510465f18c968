// SPDX-License-Identifier: BSD-3-Clause
// FCL as a checker, set up the way OMPL.app sets it up, for side-by-side comparisons.
#pragma once

#include "hybridcd/query/checker_catalogue.h"
#include "hybridcd/query/collision_checker.h"

#include <memory>

namespace hcd
{
/// FCL's `BVHModel<OBBRSS>` for robot and environment and `fcl::collide` with one contact, as in
/// OMPL.app's FCLStateValidityChecker; `distance` uses `fcl::distance`. FCL treats meshes as
/// surfaces and decides with floating-point tests, so it may differ from `bruteforce` on exact
/// touching; it is here to be measured against, not relied upon.
class FclChecker final : public CollisionChecker
{
public:
    explicit FclChecker(const CollisionScene &scene);
    ~FclChecker() override;
    std::string name() const override { return "fcl"; }
    std::vector<HierarchyReport> hierarchies(bool withVolumeRatios = false) const override;

private:
    bool doCollides(const RigidTransform &worldFromRobot, QueryContext &context) const override;
    double doDistance(const RigidTransform &worldFromRobot, QueryContext &context) const override;

    struct Models;
    std::unique_ptr<Models> models_;
};

/// The "fcl" entry for a CheckerCatalogue: `catalogue.add(fclCheckerEntry())`. It keeps FCL's own
/// surface semantics and has no approximate mode.
CheckerEntry fclCheckerEntry();

/// CheckerCatalogue::builtIn() with "fcl" added, for programs that compare against FCL.
CheckerCatalogue checkersWithFcl();
}  // namespace hcd
