// SPDX-License-Identifier: BSD-3-Clause
// Scenes of many bodies side by side with FCL: state checks (hybridcd's sweep and prune and shape
// narrow phase, its brute-force reference, FCL's dynamic AABB tree manager over FCL's primitives
// and OBBRSS meshes), and motions of all robots at once (hybridcd's continuous check against
// FCL states sampled at OMPL's resolution, as OMPL's DiscreteMotionValidator would), plus pure
// translations with and without the time-augmented LP. A Markdown table on stdout.
#include "bench_support.h"

#include "hybridcd/io/problem_scene.h"
#include "hybridcd/scene/problem_bodies.h"
#include "hybridcd/scene/scene.h"
#include "hybridcd/scene/scene_motion.h"

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/halfspace.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>

#include <chrono>
#include <iomanip>
#include <iostream>
#include <random>

namespace
{
using namespace hcd;
using Clock = std::chrono::steady_clock;

fcl::Transform3d toFcl(const RigidTransform &pose)
{
    fcl::Transform3d tf = fcl::Transform3d::Identity();
    tf.linear() = pose.rotation;
    tf.translation() = pose.translation;
    return tf;
}

// The FCL geometry of a body, as FCL users set such scenes up (OBBRSS for meshes, as OMPL.app).
std::shared_ptr<fcl::CollisionGeometryd> fclGeometry(const Shape &shape)
{
    switch (shape.kind())
    {
    case ShapeKind::Sphere:
        return std::make_shared<fcl::Sphered>(shape.radius());
    case ShapeKind::Box:
        return std::make_shared<fcl::Boxd>(2.0 * shape.extents());
    case ShapeKind::Capsule:
        return std::make_shared<fcl::Capsuled>(shape.radius(), 2.0 * shape.halfLength());
    case ShapeKind::Cylinder:
        return std::make_shared<fcl::Cylinderd>(shape.radius(), 2.0 * shape.halfLength());
    case ShapeKind::Cone:
        return std::make_shared<fcl::Coned>(shape.radius(), 2.0 * shape.halfLength());
    case ShapeKind::Ellipsoid:
        return std::make_shared<fcl::Ellipsoidd>(shape.extents());
    case ShapeKind::Halfspace:
        return std::make_shared<fcl::Halfspaced>(shape.normal(), shape.offset());
    case ShapeKind::Mesh:
    {
        auto model = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
        const TriangleMesh &mesh = *shape.meshPointer();
        std::vector<fcl::Vector3d> points(mesh.vertices.begin(), mesh.vertices.end());
        std::vector<fcl::Triangle> triangles;
        for (const auto &t : mesh.triangles)
            triangles.emplace_back(t[0], t[1], t[2]);
        model->beginModel();
        model->addSubModel(points, triangles);
        model->endModel();
        model->computeLocalAABB();
        return model;
    }
    default:
        throw std::invalid_argument(std::string("no FCL geometry for ") + shapeKindName(shape.kind()));
    }
}

// The scene in FCL: statics in one manager, robot bodies in another.
struct FclScene
{
    std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects;
    std::vector<int> robotOf;  // per object
    std::vector<RigidTransform> ownerFromBody;
    fcl::DynamicAABBTreeCollisionManagerd statics, robots;

    explicit FclScene(const Scene &scene)
    {
        for (const SceneBody &body : scene.bodies())
        {
            objects.push_back(std::make_unique<fcl::CollisionObjectd>(fclGeometry(body.geometry->shape()),
                                                                      toFcl(body.ownerFromBody)));
            objects.back()->computeAABB();
            robotOf.push_back(body.robot);
            ownerFromBody.push_back(body.ownerFromBody);
            (body.robot < 0 ? statics : robots).registerObject(objects.back().get());
        }
        statics.setup();
        robots.setup();
    }

    bool collides(const std::vector<RigidTransform> &worldFromRobot)
    {
        for (std::size_t i = 0; i < objects.size(); ++i)
            if (robotOf[i] >= 0)
            {
                objects[i]->setTransform(toFcl(worldFromRobot[std::size_t(robotOf[i])] * ownerFromBody[i]));
                objects[i]->computeAABB();
            }
        robots.update();
        bool hit = false;
        auto callback = [](fcl::CollisionObjectd *a, fcl::CollisionObjectd *b, void *data) {
            bool &found = *static_cast<bool *>(data);
            fcl::CollisionRequestd request;
            fcl::CollisionResultd result;
            fcl::collide(a, b, request, result);
            found = found || result.isCollision();
            return found;  // stop at the first contact
        };
        robots.collide(&statics, &hit, callback);
        if (!hit)
            robots.collide(&hit, callback);
        return hit;
    }
};

std::vector<RigidTransform> randomState(const Scene &scene, const Vec3 &lo, const Vec3 &hi, bool planar,
                                        std::mt19937_64 &rng)
{
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<RigidTransform> poses(scene.robotCount());
    for (RigidTransform &pose : poses)
    {
        const Vec3 t = lo + Vec3(unit(rng), unit(rng), unit(rng)).cwiseProduct(hi - lo);
        if (planar)
            pose = RigidTransform::fromPlanarPose(t.x(), t.y(), (2.0 * unit(rng) - 1.0) * 3.141592653589793);
        else
        {
            std::normal_distribution<double> normal(0.0, 1.0);
            const Eigen::Quaterniond q(normal(rng), normal(rng), normal(rng), normal(rng));
            pose = RigidTransform{q.normalized().toRotationMatrix(), t};
        }
    }
    return poses;
}

template <class Body>
double timeNs(const Body &body)
{
    const auto t0 = Clock::now();
    body();
    return std::chrono::duration<double, std::nano>(Clock::now() - t0).count();
}

int run(const cli::CommandLine &cl)
{
    const std::size_t stateCount = std::size_t(cl.positiveInteger("states", 20000));
    const std::size_t motionCount = std::size_t(cl.positiveInteger("motions", 500));
    const LoadedProblem problem = loadProblem(cl.problem());
    const ProblemConfig &config = problem.config;
    const auto scene = makeProblemScene(problem);
    SceneOptions referenceOptions;
    referenceOptions.bruteForce = true;
    const auto reference = makeProblemScene(problem, referenceOptions);
    FclScene fclScene(*scene);

    // Positions over the volume (or the start-goal box grown by the scene's size).
    Vec3 lo(config.volumeX ? config.volumeX->first : -scene->scale(),
            config.volumeY ? config.volumeY->first : -scene->scale(),
            config.volumeZ ? config.volumeZ->first : (config.planar ? 0.0 : -scene->scale()));
    Vec3 hi(config.volumeX ? config.volumeX->second : scene->scale(),
            config.volumeY ? config.volumeY->second : scene->scale(),
            config.volumeZ ? config.volumeZ->second : (config.planar ? 0.0 : scene->scale()));
    std::mt19937_64 rng(1);
    std::vector<std::vector<RigidTransform>> states;
    for (std::size_t i = 0; i < stateCount; ++i)
        states.push_back(randomState(*scene, lo, hi, config.planar, rng));

    QueryContext context;
    std::vector<double> fastNs, slowNs, fclNs;
    std::size_t colliding = 0, fclDisagreements = 0, referenceDisagreements = 0;
    for (const auto &state : states)
    {
        bool fast = false, slow = false, viaFcl = false;
        fastNs.push_back(timeNs([&] { fast = scene->collides(state, context); }));
        slowNs.push_back(timeNs([&] { slow = reference->collides(state, context); }));
        fclNs.push_back(timeNs([&] { viaFcl = fclScene.collides(state); }));
        colliding += fast ? 1 : 0;
        referenceDisagreements += fast != slow ? 1 : 0;
        fclDisagreements += fast != viaFcl ? 1 : 0;
    }
    const double fast = bench::median(fastNs), slow = bench::median(slowNs), viaFcl = bench::median(fclNs);
    std::cout << std::fixed << std::setprecision(0) << "## " << config.name << ": " << scene->robotCount()
              << " robots, " << scene->bodies().size() << " bodies, " << scene->pairs().size() << " pairs\n\n"
              << "State checks: " << stateCount << " uniform states, " << colliding << " colliding\n\n"
              << "| checker | median ns/state | FCL's time / this | disagreements |\n|---|---:|---:|---:|\n"
              << "| hybridcd scene (sweep and prune) | " << fast << " | " << std::setprecision(2) << viaFcl / fast
              << " | " << std::setprecision(0) << referenceDisagreements << " with the reference |\n"
              << "| hybridcd brute-force scene | " << slow << " | " << std::setprecision(2) << viaFcl / slow
              << " | reference |\n"
              << "| FCL dynamic AABB tree | " << std::setprecision(0) << viaFcl << " | 1.00 | " << fclDisagreements
              << " with the reference |\n\n";

    // Motions from free states, each robot moving at most 0.2 of the extent (RRTConnect's range).
    const double extent = (hi - lo).norm();
    const double resolution = 0.01 * extent;  // OMPL's default validity resolution
    std::normal_distribution<double> step(0.0, 0.08 * extent);
    std::vector<double> continuousNs, lastValidNs, discreteNs, lpNs, noLpNs;
    std::size_t missedByDiscrete = 0, rejected = 0;
    SceneMotionOptions noLp;
    noLp.translationLp = false;
    std::vector<RigidTransform> poses;
    for (std::size_t m = 0, tries = 0; m < motionCount && tries < 100 * motionCount; ++tries)
    {
        const auto start = randomState(*scene, lo, hi, config.planar, rng);
        if (scene->collides(start, context))
            continue;
        ++m;
        std::vector<RigidTransform> goal = start, shifted = start;
        double longest = 0.0;
        for (std::size_t r = 0; r < goal.size(); ++r)
        {
            const Vec3 d(step(rng), step(rng), config.planar ? 0.0 : step(rng));
            const double yaw = step(rng) / extent;
            goal[r] =
                config.planar
                    ? RigidTransform::fromPlanarPose(start[r].translation.x() + d.x(), start[r].translation.y() + d.y(),
                                                     std::atan2(start[r].rotation(1, 0), start[r].rotation(0, 0)) + yaw)
                    : RigidTransform{start[r].rotation, start[r].translation + d};
            shifted[r] = RigidTransform{start[r].rotation, start[r].translation + d};
            longest = std::max(longest, d.norm());
        }
        SceneMotionResult result;
        SceneMotionOptions verdict;
        verdict.verdictOnly = true;
        continuousNs.push_back(timeNs([&] { result = checkSceneMotion(*scene, start, goal, context, verdict); }));
        lastValidNs.push_back(timeNs([&] { checkSceneMotion(*scene, start, goal, context); }));
        rejected += result.valid ? 0 : 1;
        if (continuousNs.back() > 1e7)
            std::cerr << "slow motion: " << continuousNs.back() / 1e3 << " us, " << result.distanceQueries
                      << " distance queries, " << result.boundSteps << " box steps, valid " << result.valid << ", pair "
                      << scene->pairLabel(result.pair) << " at " << result.contactTime << "\n";
        // FCL at OMPL's resolution: states every `resolution` of the longest robot's travel.
        const std::size_t samples = std::max<std::size_t>(1, std::size_t(std::ceil(longest / resolution)));
        bool discreteValid = true;
        discreteNs.push_back(timeNs([&] {
            for (std::size_t k = 1; k <= samples && discreteValid; ++k)
            {
                interpolateScenePoses(start, goal, double(k) / double(samples), poses);
                discreteValid = !fclScene.collides(poses);
            }
        }));
        missedByDiscrete += (discreteValid && !result.valid) ? 1 : 0;
        // Pure translations: the time-augmented LP for polytope pairs, or advancement for all.
        lpNs.push_back(timeNs([&] { checkSceneMotion(*scene, start, shifted, context); }));
        noLpNs.push_back(timeNs([&] { checkSceneMotion(*scene, start, shifted, context, noLp); }));
    }
    auto mean = [](const std::vector<double> &v) {
        double sum = 0.0;
        for (double x : v)
            sum += x;
        return v.empty() ? 0.0 : sum / double(v.size());
    };
    std::cerr << "continuous: mean " << mean(continuousNs) / 1e3 << " us, max "
              << *std::max_element(continuousNs.begin(), continuousNs.end()) / 1e3 << " us; discrete: mean "
              << mean(discreteNs) / 1e3 << " us\n";
    std::cout << "Motions: " << continuousNs.size() << " from free states, each robot moving up to about 0.2 of "
              << "the extent; " << rejected << " touch somewhere\n\n"
              << "| motion check | median us/motion | vs FCL discrete |\n|---|---:|---:|\n"
              << std::setprecision(1) << "| hybridcd continuous, verdict (raked states, advancement, LP) | "
              << bench::median(continuousNs) / 1e3 << " | " << std::setprecision(2)
              << bench::median(continuousNs) / bench::median(discreteNs) << " |\n"
              << std::setprecision(1) << "| hybridcd continuous, with lastValid | " << bench::median(lastValidNs) / 1e3
              << " | " << std::setprecision(2) << bench::median(lastValidNs) / bench::median(discreteNs) << " |\n"
              << std::setprecision(1) << "| FCL discrete at 0.01 of the extent (misses " << missedByDiscrete
              << " touching motions) | " << bench::median(discreteNs) / 1e3 << " | 1.00 |\n"
              << "| translations: time-augmented LP for polytope pairs | " << bench::median(lpNs) / 1e3 << " | "
              << std::setprecision(2) << bench::median(lpNs) / bench::median(discreteNs) << " |\n"
              << std::setprecision(1) << "| translations: advancement only | " << bench::median(noLpNs) / 1e3 << " | "
              << std::setprecision(2) << bench::median(noLpNs) / bench::median(discreteNs) << " |\n";
    return 0;
}
}  // namespace

int main(int argc, char **argv)
{
    CLI::App app("Scene problems side by side with FCL: state checks and motions of all robots at once.",
                 "hybridcd_bench_scene");
    cli::configureApp(app);
    cli::CommandLine cl(app);
    cl.positionals("PROBLEM.cfg", "a scene problem (robot.K, obstacle.K)")
        .option("states", "N", "uniform states (default 20000)")
        .option("motions", "N", "motions from free states (default 500)")
        .footer("\nExample:\n  hybridcd_bench_scene problems/crossing_2d.cfg --states 20000 --motions 500\n");
    return bench::runProgram(app, cl, argc, argv, [&] { return run(cl); });
}
