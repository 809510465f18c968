// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/fcl/fcl_checker.h"

#include "hybridcd/query/checker_catalogue.h"

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <chrono>

namespace hcd
{
namespace
{
using Model = fcl::BVHModel<fcl::OBBRSSd>;

// One FCL vertex triple per triangle, as OMPL.app feeds FCL.
std::shared_ptr<Model> buildModel(const TriangleMesh &mesh, double &seconds)
{
    const auto start = std::chrono::steady_clock::now();
    auto model = std::make_shared<Model>();
    std::vector<fcl::Vector3d> points;
    std::vector<fcl::Triangle> triangles;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
    {
        for (int k = 0; k < 3; ++k)
            points.push_back(mesh.corner(t, k));
        triangles.emplace_back(3 * t, 3 * t + 1, 3 * t + 2);
    }
    model->beginModel();
    if (!triangles.empty())
        model->addSubModel(points, triangles);
    model->endModel();
    model->computeLocalAABB();
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return model;
}

fcl::Transform3d toFcl(const RigidTransform &pose)
{
    fcl::Transform3d tf = fcl::Transform3d::Identity();
    tf.linear() = pose.rotation;
    tf.translation() = pose.translation;
    return tf;
}
}  // namespace

struct FclChecker::Models
{
    std::shared_ptr<Model> robot, environment;
    double robotSeconds = 0.0, environmentSeconds = 0.0;
};

FclChecker::FclChecker(const CollisionScene &scene) : models_(std::make_unique<Models>())
{
    models_->robot = buildModel(*scene.robot, models_->robotSeconds);
    models_->environment = buildModel(*scene.environment, models_->environmentSeconds);
}

FclChecker::~FclChecker() = default;

bool FclChecker::doCollides(const RigidTransform &worldFromRobot, QueryContext &) const
{
    if (!worldFromRobot.isFinite())
        return true;
    if (models_->robot->num_tris == 0 || models_->environment->num_tris == 0)
        return false;
    fcl::CollisionRequestd request;  // one contact, as OMPL.app asks
    fcl::CollisionResultd result;
    return fcl::collide(models_->robot.get(), toFcl(worldFromRobot), models_->environment.get(),
                        fcl::Transform3d::Identity(), request, result) > 0;
}

double FclChecker::doDistance(const RigidTransform &worldFromRobot, QueryContext &) const
{
    if (!worldFromRobot.isFinite())
        return 0.0;
    if (models_->robot->num_tris == 0 || models_->environment->num_tris == 0)
        return std::numeric_limits<double>::infinity();
    fcl::DistanceRequestd request;
    fcl::DistanceResultd result;
    fcl::distance(models_->robot.get(), toFcl(worldFromRobot), models_->environment.get(), fcl::Transform3d::Identity(),
                  request, result);
    return std::max(0.0, result.min_distance);
}

std::vector<HierarchyReport> FclChecker::hierarchies(bool) const
{
    const auto report = [](const char *label, const Model &m, double seconds) {
        return HierarchyReport{label, std::size_t(m.getNumBVs()), 0, seconds,
                               std::size_t(m.getNumBVs()) * sizeof(fcl::BVNode<fcl::OBBRSSd>) +
                                   std::size_t(m.num_vertices) * sizeof(fcl::Vector3d) +
                                   std::size_t(m.num_tris) * sizeof(fcl::Triangle)};
    };
    return {report("robot FCL OBBRSS tree", *models_->robot, models_->robotSeconds),
            report("environment FCL OBBRSS tree", *models_->environment, models_->environmentSeconds)};
}

CheckerEntry fclCheckerEntry()
{
    return {"fcl", "FCL's OBBRSS trees as OMPL.app sets them up; meshes are surfaces (for comparisons)",
            [](const CollisionScene &s, const CheckerOptions &) { return std::make_unique<FclChecker>(s); }, true,
            false};
}

CheckerCatalogue checkersWithFcl()
{
    CheckerCatalogue catalogue = CheckerCatalogue::builtIn();
    catalogue.add(fclCheckerEntry());
    return catalogue;
}
}  // namespace hcd
