// SPDX-License-Identifier: BSD-3-Clause
// Repeated faces (SketchUp exports every face twice, once reversed) are dropped from the query
// structures. The point set is unchanged, so a mesh with every face doubled must give exactly the
// answers of the single mesh, for every checker and for the brute-force reference, with solid
// semantics unchanged: a doubled closed box is still a solid, a doubled open sheet is still not.
#include "support/test_support.h"

#include "hybridcd/geometry/solid_components.h"
#include "hybridcd/geometry/triangle_intersection.h"
#include "hybridcd/query/checker_catalogue.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace hcd;

namespace
{
// Every face once more, reversed; with `sameOrientationToo`, a third, identical copy as well.
TriangleMesh doubled(const TriangleMesh &mesh, bool sameOrientationToo = false)
{
    TriangleMesh out = mesh;
    for (const TriangleMesh::Triangle &t : mesh.triangles)
        out.triangles.push_back({t[0], t[2], t[1]});
    if (sameOrientationToo)
        for (const TriangleMesh::Triangle &t : mesh.triangles)
            out.triangles.push_back({t[1], t[2], t[0]});
    return out;
}

CollisionScene sceneOf(TriangleMesh robot, TriangleMesh environment)
{
    CollisionScene s;
    s.robot = std::make_shared<const TriangleMesh>(std::move(robot));
    s.environment = std::make_shared<const TriangleMesh>(std::move(environment));
    return s;
}

// Appends `part` to `mesh` (vertices renumbered).
void append(TriangleMesh &mesh, const TriangleMesh &part)
{
    const auto base = std::uint32_t(mesh.vertices.size());
    mesh.vertices.insert(mesh.vertices.end(), part.vertices.begin(), part.vertices.end());
    for (const TriangleMesh::Triangle &t : part.triangles)
        mesh.triangles.push_back({base + t[0], base + t[1], base + t[2]});
}

TriangleMesh sheet(const Vec3 &a, const Vec3 &b, const Vec3 &c, const Vec3 &d)
{
    TriangleMesh m;
    m.vertices = {a, b, c, d};
    m.triangles = {{0, 1, 2}, {0, 2, 3}};
    return m;
}

// A closed box, an open sheet and an open box (one face missing): solids and surfaces together.
TriangleMesh mixedEnvironment()
{
    TriangleMesh env = test::boxMesh(Vec3(0, 0, 0), Vec3(10, 10, 10));
    append(env, sheet(Vec3(15, 0, 0), Vec3(15, 10, 0), Vec3(15, 10, 10), Vec3(15, 0, 10)));
    TriangleMesh openBox = test::boxMesh(Vec3(20, 0, 0), Vec3(30, 10, 10));
    openBox.triangles.resize(openBox.triangles.size() - 2);
    append(env, openBox);
    return env;
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> trianglePairs(const std::vector<ContactPair> &contacts)
{
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
    for (const ContactPair &c : contacts)
        if (c.kind == ContactPair::Kind::Triangles)
            pairs.emplace_back(c.robotElement, c.environmentElement);
    std::sort(pairs.begin(), pairs.end());
    return pairs;
}

// Every checker on the doubled scene against the brute-force reference on the single one.
void expectSameAnswers(const CollisionScene &single, const CollisionScene &twice,
                       const std::vector<RigidTransform> &poses, std::size_t &colliding, std::size_t &free)
{
    const auto reference = makeChecker("bruteforce", single);
    const auto referenceSurface = makeChecker("bruteforce", single, ContactSemantics::SurfaceOnly);
    std::vector<char> truth;
    std::vector<double> distances;
    for (const RigidTransform &pose : poses)
    {
        truth.push_back(reference->collides(pose));
        distances.push_back(reference->distance(pose));
        (truth.back() ? colliding : free) += 1;
    }
    for (const std::string &name : CheckerCatalogue::builtIn().names())
    {
        if (name == "fcl")
            continue;  // FCL keeps the mesh as given (surface semantics, every copy)
        const auto checker = makeChecker(name, twice);
        const auto surface = makeChecker(name, twice, ContactSemantics::SurfaceOnly);
        const auto singleSurface = makeChecker(name, single, ContactSemantics::SurfaceOnly);
        for (std::size_t i = 0; i < poses.size(); ++i)
        {
            const RigidTransform &pose = poses[i];
            ASSERT_EQ(checker->collides(pose), bool(truth[i])) << name << " pose " << i;
            const double d = checker->distance(pose);
            EXPECT_EQ(d == 0.0, distances[i] == 0.0) << name << " pose " << i;
            EXPECT_NEAR(d, distances[i], 1e-9 * (1.0 + distances[i])) << name << " pose " << i;
            if (name == "lp")
                continue;  // approximate pieces are not triangles
            const auto found = surface->contacts(pose, 100000);
            const auto expected = referenceSurface->contacts(pose, 100000);
            ASSERT_EQ(found.size(), expected.size()) << name << " pose " << i;
            EXPECT_EQ(trianglePairs(found), trianglePairs(singleSurface->contacts(pose, 100000)))
                << name << " pose " << i;
            // Contacts name triangles of the source (doubled) mesh, and those triangles do meet.
            for (const ContactPair &c : found)
            {
                const TriangleMesh &r = *twice.robot, &e = *twice.environment;
                ASSERT_LT(c.robotElement, r.triangleCount());
                ASSERT_LT(c.environmentElement, e.triangleCount());
                EXPECT_TRUE(
                    trianglesIntersect(pose.apply(r.corner(c.robotElement, 0)), pose.apply(r.corner(c.robotElement, 1)),
                                       pose.apply(r.corner(c.robotElement, 2)), e.corner(c.environmentElement, 0),
                                       e.corner(c.environmentElement, 1), e.corner(c.environmentElement, 2)));
            }
        }
    }
}
}  // namespace

TEST(RepeatedFaces, DroppedOnceKeepingTheFirstCopyInOrder)
{
    const TriangleMesh box = test::boxMesh(Vec3(0, 0, 0), Vec3(1, 1, 1));
    const auto twice = std::make_shared<const TriangleMesh>(doubled(box, true));
    const DistinctFaceMesh distinct = withoutRepeatedFaces(twice);
    EXPECT_EQ(distinct.dropped, 2 * box.triangleCount());
    ASSERT_EQ(distinct.mesh->triangleCount(), box.triangleCount());
    for (std::uint32_t t = 0; t < box.triangleCount(); ++t)
    {
        EXPECT_EQ(distinct.mesh->triangles[t], box.triangles[t]);
        EXPECT_EQ(distinct.source(t), t);
    }
    EXPECT_EQ(distinct.mesh->vertices, box.vertices);

    // Nothing repeated: the same mesh, shared, and an identity map.
    const auto single = std::make_shared<const TriangleMesh>(box);
    const DistinctFaceMesh same = withoutRepeatedFaces(single);
    EXPECT_EQ(same.mesh, single);
    EXPECT_EQ(same.dropped, 0u);
    EXPECT_EQ(same.source(5), 5u);
    EXPECT_FALSE(withoutRepeatedFaces(nullptr).mesh);
}

TEST(RepeatedFaces, ClosednessAndComponentsUnchanged)
{
    const TriangleMesh env = mixedEnvironment();
    const TriangleMesh twice = doubled(env);
    EXPECT_EQ(isClosed(env), isClosed(twice));
    const auto before = meshComponents(env), after = meshComponents(twice);
    const auto distinct = meshComponents(*withoutRepeatedFaces(std::make_shared<const TriangleMesh>(twice)).mesh);
    ASSERT_EQ(before.size(), 3u);
    ASSERT_EQ(after.size(), before.size());
    ASSERT_EQ(distinct.size(), before.size());
    for (std::size_t c = 0; c < before.size(); ++c)
    {
        EXPECT_EQ(after[c].closed, before[c].closed) << c;
        EXPECT_EQ(distinct[c].closed, before[c].closed) << c;
    }
    EXPECT_TRUE(before[0].closed);   // the box
    EXPECT_FALSE(before[1].closed);  // the sheet, doubled or not
    EXPECT_FALSE(before[2].closed);  // the open box
}

TEST(RepeatedFaces, DoubledMeshesGiveTheSingleMeshAnswersOnRandomPoses)
{
    const TriangleMesh robot = test::boxMesh(Vec3(-1, -2, -0.5), Vec3(1, 2, 0.5));
    const TriangleMesh env = mixedEnvironment();
    const CollisionScene single = sceneOf(robot, env);
    const CollisionScene twice = sceneOf(doubled(robot, true), doubled(env));
    test::TestRandom rng(11);
    std::uniform_real_distribution<double> x(-3.0, 33.0), yz(-3.0, 13.0);
    std::vector<RigidTransform> poses;
    for (int i = 0; i < test::cases(400); ++i)
        poses.push_back({test::randomRotation(rng), Vec3(x(rng), yz(rng), yz(rng))});
    // Wholly inside the closed box (a collision: solid semantics), inside the open box (free).
    poses.push_back({test::randomRotation(rng), Vec3(5, 5, 5)});
    poses.push_back({Mat3::Identity(), Vec3(25, 5, 5)});
    std::size_t colliding = 0, free = 0;
    expectSameAnswers(single, twice, poses, colliding, free);
    EXPECT_GT(colliding, poses.size() / 10);
    EXPECT_GT(free, poses.size() / 10);

    for (const std::string &name : CheckerCatalogue::builtIn().names())
    {
        if (name == "fcl")
            continue;
        const auto checker = makeChecker(name, twice);
        EXPECT_TRUE(checker->collides(poses[poses.size() - 2])) << name;  // inside the doubled closed box
        EXPECT_EQ(checker->distance(poses[poses.size() - 2]), 0.0) << name;
        EXPECT_FALSE(checker->collides(poses.back())) << name;  // inside the doubled open box
    }
}

TEST(RepeatedFaces, DoubledMeshesGiveTheSingleMeshAnswersOnTouchingPoses)
{
    // Unit cubes face to face, edge to edge, corner to corner, and one ulp apart; a doubled sheet
    // touched by a face and crossed by the robot.
    TriangleMesh env = test::boxMesh(Vec3(0, 0, 0), Vec3(1, 1, 1));
    append(env, sheet(Vec3(3, 0, 0), Vec3(3, 1, 0), Vec3(3, 1, 1), Vec3(3, 0, 1)));
    const TriangleMesh robot = test::boxMesh(Vec3(-0.5, -0.5, -0.5), Vec3(0.5, 0.5, 0.5));
    const CollisionScene single = sceneOf(robot, env);
    const CollisionScene twice = sceneOf(doubled(robot), doubled(env, true));
    const double gap = std::nextafter(-0.5, -1.0);
    const std::vector<RigidTransform> poses = {
        {Mat3::Identity(), Vec3(-0.5, 0.5, 0.5)},      {Mat3::Identity(), Vec3(gap, 0.5, 0.5)},
        {Mat3::Identity(), Vec3(-0.5, -0.5, 0.5)},     {Mat3::Identity(), Vec3(-0.5, -0.5, -0.5)},
        {Mat3::Identity(), Vec3(0.5, 0.5, 0.5)},       {Mat3::Identity(), Vec3(2.5, 0.5, 0.5)},
        {Mat3::Identity(), Vec3(3.0, 0.5, 0.5)},       {Mat3::Identity(), Vec3(std::nextafter(2.5, 0.0), 0.5, 0.5)},
        {Mat3::Identity(), Vec3(0.5, 0.5, 0.5 + 1e-3)}};
    std::size_t colliding = 0, free = 0;
    expectSameAnswers(single, twice, poses, colliding, free);
    EXPECT_EQ(colliding, 7u);
    EXPECT_EQ(free, 2u);
}

TEST(RepeatedFaces, OmplAppStyleProblemMeshesDoubledAgree)
{
    const LoadedProblem problem = loadProblem(test::sourcePath("problems/window_3d.cfg"));
    const CollisionScene twice = sceneOf(doubled(*problem.robot.mesh), doubled(*problem.world.mesh));
    test::TestRandom rng(3);
    const auto poses = test::randomPoses(problem, std::size_t(test::cases(150)), rng);
    std::size_t colliding = 0, free = 0;
    expectSameAnswers(problem.scene, twice, poses, colliding, free);
    EXPECT_GT(colliding, 0u);
    EXPECT_GT(free, 0u);
}
