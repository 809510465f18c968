// SPDX-License-Identifier: BSD-3-Clause
// Medial-axis sphere trees (`--checker medial`): the spheres' own promises checked independently
// (inscribed balls inside their solid and free of surface, covering balls holding their
// triangles, the open-mesh fallback), and approximate mode against brute force and the OBB
// checker's distance: never free when brute force collides, colliding only within the tolerance.
#include "support/test_support.h"

#include "hybridcd/bvh/medial_axis.h"
#include "hybridcd/geometry/solid_components.h"
#include "hybridcd/geometry/triangle_distance.h"
#include "hybridcd/query/checker_catalogue.h"

#include <gtest/gtest.h>

#include <filesystem>

using namespace hcd;

namespace
{
double distanceToMesh(const TriangleMesh &mesh, const Vec3 &p)
{
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
        best = std::min(
            best, (closestPointOnTriangle(p, mesh.corner(t, 0), mesh.corner(t, 1), mesh.corner(t, 2)) - p).norm());
    return best;
}

// Every node's ball holds the corners of its triangles; every ball with an inscribed radius has its
// centre inside a solid, no surface point nearer than that radius (brute force over triangles).
// Returns the number of nodes with an inscribed ball.
std::size_t expectMedialTree(const VolumeTree<MedialSphere> &tree, const SolidQuery &solids)
{
    const TriangleMesh &mesh = tree.mesh();
    std::size_t medial = 0;
    for (const auto &node : tree.nodes())
    {
        for (std::uint32_t k = 0; k < node.triangleCount; ++k)
            for (int c = 0; c < 3; ++c)
                EXPECT_TRUE(node.volume.ball.contains(mesh.corner(tree.triangleOrder()[node.firstTriangle + k], c)));
        if (node.volume.inner <= 0.0)
            continue;
        ++medial;
        EXPECT_TRUE(solids.insideAnySolid(node.volume.ball.center));
        EXPECT_GE(distanceToMesh(mesh, node.volume.ball.center), node.volume.inner * (1.0 - 1e-12));
        EXPECT_LE(node.volume.approximationBound(), node.volume.ball.radius);
    }
    return medial;
}
}  // namespace

TEST(MedialSpheres, InscribedAndCovering)
{
    for (const char *cfg : {"problems/bone_3d.cfg", "problems/ribcage_3d.cfg", "problems/window_3d.cfg"})
    {
        const LoadedProblem problem = loadProblem(test::sourcePath(cfg));
        for (const auto &mesh : {problem.scene.robot, problem.scene.environment})
        {
            VolumeTree<MedialSphere> tree(mesh, 8);
            placeOnMedialAxis(tree, mesh);
            std::size_t leaves = 0;
            for (const auto &node : tree.nodes())
                leaves += node.isLeaf() ? 1 : 0;
            const std::size_t medial = expectMedialTree(tree, SolidQuery(mesh));
            // Closed meshes: (nearly) every leaf sits on the medial axis.
            EXPECT_GE(medial, leaves * 9 / 10) << cfg;
        }
    }
}

// An open mesh (a closed one less a triangle) has no solid: every node keeps its fitted ball, inner 0.
TEST(MedialSpheres, OpenMeshesFallBackToFittedSpheres)
{
    const LoadedProblem problem = loadProblem(test::sourcePath("problems/bone_3d.cfg"));
    auto open = std::make_shared<TriangleMesh>(*problem.scene.robot);
    open->triangles.pop_back();
    VolumeTree<MedialSphere> tree(open, 8);
    const VolumeTree<MedialSphere> fitted(open, 8);
    placeOnMedialAxis(tree, open);
    EXPECT_EQ(expectMedialTree(tree, SolidQuery(open)), 0u);
    for (std::size_t i = 0; i < tree.nodes().size(); ++i)
    {
        EXPECT_EQ(tree.nodes()[i].volume.ball.center, fitted.nodes()[i].volume.ball.center);
        EXPECT_EQ(tree.nodes()[i].volume.approximationBound(), 2.0 * fitted.nodes()[i].volume.ball.radius);
    }
}

namespace
{
// Approximate mode with tolerance T: on uniform poses and on poses at chosen distances from
// contact (0 to 3 T, along random directions), never free where brute force (solid semantics)
// collides, and colliding where brute force is free only when the OBB checker's exact distance is
// at most T. Returns how many free poses approximate mode called colliding.
std::size_t checkApproximate(const std::string &cfg, double tolerance, std::size_t uniformCount, std::size_t nearCount)
{
    const LoadedProblem problem = loadProblem(cfg);
    test::TestRandom rng(test::seeded(2213));
    const auto reference = makeChecker("bruteforce", problem.scene);
    const auto exactDistance = makeChecker("obb", problem.scene);
    CheckerOptions options;
    options.approximateTolerance = tolerance;
    const auto approximate = makeChecker("medial", problem.scene, options);
    const auto exact = makeChecker("medial", problem.scene);

    std::vector<RigidTransform> poses = test::randomPoses(problem, uniformCount, rng);
    // Near contact: from a colliding pose straight out until free (bisection to 1e-9), then
    // stepped out by fractions of T.
    const double reach =
        2.0 * (problem.scene.environment->radiusAboutOrigin() + problem.scene.robot->radiusAboutOrigin());
    std::size_t near = 0;
    for (const RigidTransform &pose : test::randomPoses(problem, 40 * nearCount, rng))
    {
        if (near >= nearCount)
            break;
        if (!exactDistance->collides(pose))
            continue;
        Vec3 direction = test::randomRotation(rng).col(0);
        if (problem.config.planar)
            direction.z() = 0.0;
        if (!(direction.norm() > 0.1))
            continue;
        direction.normalize();
        Vec3 in = pose.translation, out = pose.translation + (reach + pose.translation.norm()) * direction;
        if (exactDistance->collides({pose.rotation, out}))
            continue;
        while ((out - in).norm() > 1e-9)
        {
            const Vec3 mid = 0.5 * (in + out);
            (exactDistance->collides({pose.rotation, mid}) ? in : out) = mid;
        }
        for (double f : {0.0, 0.1, 0.3, 0.6, 0.9, 1.2, 2.0, 3.0})
            poses.push_back({pose.rotation, out + f * tolerance * direction});
        ++near;
    }
    EXPECT_GE(near, nearCount / 2) << cfg;

    std::size_t colliding = 0, widened = 0;
    for (std::size_t i = 0; i < poses.size(); ++i)
    {
        const bool truth = reference->collides(poses[i]);
        const bool answer = approximate->collides(poses[i]);
        EXPECT_EQ(exact->collides(poses[i]), truth) << "exact mode, pose " << i << " of " << cfg;
        colliding += truth ? 1 : 0;
        if (truth)
            EXPECT_TRUE(answer) << "approximate mode missed a collision, pose " << i << " of " << cfg;
        else if (answer)
        {
            ++widened;
            EXPECT_LE(exactDistance->distance(poses[i]), tolerance * (1.0 + 1e-9))
                << "approximate mode reported collision beyond T = " << tolerance << ", pose " << i << " of " << cfg;
        }
    }
    EXPECT_GT(colliding, poses.size() / 10) << cfg;
    std::cout << "[ medial approximate ] " << std::filesystem::path(cfg).filename().string() << ", T = " << tolerance
              << ": " << poses.size() << " poses, " << colliding << " colliding, " << widened
              << " free poses reported colliding (within T)\n";
    return widened;
}
}  // namespace

TEST(MedialSpheres, ApproximateModeErrsOnlyTowardCollisionWithinTolerance)
{
    const char *problems[] = {"problems/bone_3d.cfg", "problems/ribcage_3d.cfg", "problems/bones_2d.cfg"};
    const double tolerances[] = {0.3, 1.5};
    std::size_t widened = 0;
    for (int p = 0; p < 3; ++p)
        for (int t = 0; t < 2; ++t)
        {
            // Sanitizer builds take one tolerance per problem, alternating (each build costs ~5 s there).
            if (test::kSanitizerCaseDivisor > 1 && (p + t) % 2 != 0)
                continue;
            widened +=
                checkApproximate(test::sourcePath(problems[p]), tolerances[t], test::cases(200), test::cases(25));
        }
    // The spheres did decide alone somewhere (else the mode would be untested).
    EXPECT_GT(widened, 0u);
}

// OMPL.app's meshes are mostly open: the fallback spheres (bound 2 radius) keep the promise too.
TEST(MedialSpheres, ApproximateModeOnOmplAppMeshes)
{
    HYBRIDCD_REQUIRE_OMPLAPP(cfg, "3D/cubicles.cfg");
    checkApproximate(cfg, 5.0, test::cases(200), test::cases(25));
}
