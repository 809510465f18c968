// SPDX-License-Identifier: BSD-3-Clause
// Body pair queries against independent references:
//  - every pair of non-mesh kinds (half-spaces included) against the inner/outer tessellation
//    reference decided by the LP, or the half-space's closed form on the tessellation points;
//  - distances against closed forms (spheres, capsules through segmentSegmentDistanceSquared,
//    sphere-box by clamping) and box-box against the brute-force distance between the boxes'
//    twelve triangles (exact for polytopes);
//  - shape-triangle against the LP on the tessellations and the triangle;
//  - shape-mesh against a flat loop over every triangle plus point-in-solid containment, for
//    closed and open meshes, and half-space-mesh against the lowest vertex;
//  - adversarial cases: exact face contact, containment both ways, tiny and huge scales, thin
//    boxes, coplanar faces; mesh-mesh pairs throw.
#include "hybridcd/query/body_geometry.h"

#include "hybridcd/geometry/solid_components.h"
#include "hybridcd/geometry/triangle_distance.h"
#include "hybridcd/narrowphase/shape_pair.h"
#include "support/shape_reference.h"
#include "support/test_support.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <string>
#include <thread>

namespace hcd
{
namespace
{
using test::cases;
using test::TestRandom;

RigidTransform at(const Vec3 &t) { return {Mat3::Identity(), t}; }

std::vector<ShapeKind> nonMeshKinds()
{
    std::vector<ShapeKind> kinds = test::compactKinds();
    kinds.push_back(ShapeKind::Halfspace);
    return kinds;
}

// The reference verdict for any pair of non-mesh kinds.
test::Reference reference(const Shape &a, const test::ShapeHulls *ha, const RigidTransform &wa, const Shape &b,
                          const test::ShapeHulls *hb, const RigidTransform &wb, LpWorkspace &lp)
{
    const bool halfA = a.kind() == ShapeKind::Halfspace, halfB = b.kind() == ShapeKind::Halfspace;
    if (halfA && halfB)
    {
        const Vec3 na = wa.rotation * a.normal(), nb = wb.rotation * b.normal();
        if (na != -nb)
            return test::Reference::Intersecting;
        const double oa = a.offset() + na.dot(wa.translation), ob = b.offset() + nb.dot(wb.translation);
        return -ob <= oa ? test::Reference::Intersecting : test::Reference::Disjoint;
    }
    if (halfA)
        return test::referenceHalfspace(*hb, wb, a, wa);
    if (halfB)
        return test::referenceHalfspace(*ha, wa, b, wb);
    return test::referenceVerdict(*ha, wa, *hb, wb, lp);
}

TEST(BodyGeometry, EveryNonMeshPairAgreesWithReference)
{
    TestRandom rng(test::seeded(31));
    LpWorkspace lp;
    QueryContext context;
    for (ShapeKind ka : nonMeshKinds())
        for (ShapeKind kb : nonMeshKinds())
        {
            const Shape sa = test::randomShape(ka, rng), sb = test::randomShape(kb, rng);
            const BodyGeometry a(sa), b(sb);
            std::optional<test::ShapeHulls> ha, hb;
            if (ka != ShapeKind::Halfspace)
                ha = test::hullsOf(sa, 6);
            if (kb != ShapeKind::Halfspace)
                hb = test::hullsOf(sb, 6);
            // A half-space through its frame's origin: place the other body around it.
            const double reach =
                std::isfinite(a.boundingRadius() + b.boundingRadius())
                    ? 0.7 * (a.boundingRadius() + b.boundingRadius()) +
                          0.5 * (test::meanHalfWidth(sa) + test::meanHalfWidth(sb))
                    : 5.0 * (ka == ShapeKind::Halfspace ? (kb == ShapeKind::Halfspace ? 1.0 : test::meanHalfWidth(sb))
                                                        : test::meanHalfWidth(sa));
            int hits = 0, known = 0;
            const int n = cases(120);
            for (int i = 0; i < n; ++i)
            {
                const RigidTransform wa = test::randomPose(rng, 0.1), wb = test::randomPose(rng, reach);
                const test::Reference ref = reference(sa, ha ? &*ha : nullptr, wa, sb, hb ? &*hb : nullptr, wb, lp);
                const BodyPairResult hit = bodiesIntersect(a, wa, b, wb, context);
                const BodyPairResult dist = bodiesDistance(a, wa, b, wb, context);
                const std::string where =
                    std::string(shapeKindName(ka)) + "-" + shapeKindName(kb) + " case " + std::to_string(i);
                ASSERT_EQ(hit.intersecting, dist.intersecting) << where;
                if (ref == test::Reference::Intersecting)
                {
                    ASSERT_TRUE(hit.intersecting) << where;
                    ASSERT_EQ(dist.distance, 0.0) << where;
                }
                else if (ref == test::Reference::Disjoint)
                {
                    ASSERT_FALSE(hit.intersecting) << where;
                    ASSERT_GT(hit.distance, 0.0) << where;
                    ASSERT_GT(dist.distance, 0.0) << where;
                    // The distance's points are the bodies' (within the outer tessellation).
                    EXPECT_NEAR((dist.pointA - dist.pointB).norm(), dist.distance, 1e-8 * dist.distance + 1e-10)
                        << where;
                }
                hits += ref == test::Reference::Intersecting;
                known += ref != test::Reference::Unknown;
            }
            const std::string pair = std::string(shapeKindName(ka)) + "-" + shapeKindName(kb);
            EXPECT_GE(known, 8 * n / 10) << pair;
            // Per pair only with enough cases (sanitizer builds run fewer); random planes always meet.
            if (n >= 50 && !(ka == ShapeKind::Halfspace && kb == ShapeKind::Halfspace))
            {
                EXPECT_GE(hits, 10 * known / 100) << pair;
                EXPECT_LE(hits, 90 * known / 100) << pair;
            }
        }
}

// Distances with closed forms, written here independently of the library's closed forms.
TEST(BodyGeometry, DistancesMatchClosedForms)
{
    TestRandom rng(test::seeded(32));
    QueryContext context;
    int separated = 0;
    const int n = cases(1500);
    for (int i = 0; i < n; ++i)
    {
        const Shape ca = test::randomShape(ShapeKind::Capsule, rng), cb = test::randomShape(ShapeKind::Capsule, rng);
        const Shape s = test::randomShape(ShapeKind::Sphere, rng), box = test::randomShape(ShapeKind::Box, rng);
        const RigidTransform wa = test::randomPose(rng, 1.5), wb = test::randomPose(rng, 1.5);
        auto axis = [](const Shape &c, const RigidTransform &w, int end) {
            return w.apply(Vec3(0, 0, end ? c.halfLength() : -c.halfLength()));
        };
        // capsule-capsule
        const double capsules = std::sqrt(segmentSegmentDistanceSquared(axis(ca, wa, 0), axis(ca, wa, 1),
                                                                        axis(cb, wb, 0), axis(cb, wb, 1))) -
                                ca.radius() - cb.radius();
        // sphere-capsule
        const double sphereCapsule =
            std::sqrt(segmentSegmentDistanceSquared(wa.translation, wa.translation, axis(cb, wb, 0), axis(cb, wb, 1))) -
            s.radius() - cb.radius();
        // sphere-box
        const Vec3 local = wb.rotation.transpose() * (wa.translation - wb.translation);
        const double sphereBox = (local - local.cwiseMax(-box.extents()).cwiseMin(box.extents())).norm() - s.radius();
        const std::array<std::tuple<Shape, Shape, double>, 3> pairs{
            {{ca, cb, capsules}, {s, cb, sphereCapsule}, {s, box, sphereBox}}};
        for (const auto &[x, y, exact] : pairs)
        {
            const BodyPairResult r = bodiesDistance(BodyGeometry(x), wa, BodyGeometry(y), wb, context);
            const std::string where =
                std::string(shapeKindName(x.kind())) + "-" + shapeKindName(y.kind()) + " case " + std::to_string(i);
            if (exact > 1e-9)
            {
                ++separated;
                ASSERT_FALSE(r.intersecting) << where;
                EXPECT_NEAR(r.distance, exact, 1e-9 * exact + 1e-11) << where;
                EXPECT_LE(r.distance, exact * (1 + 1e-9) + 1e-12) << where;
            }
            else if (exact < -1e-9)
            {
                ASSERT_TRUE(r.intersecting) << where;
            }
        }
    }
    EXPECT_GT(separated, 3 * n / 5);
    EXPECT_LT(separated, 12 * n / 5);
}

// Box-box distance against the brute-force distance over the boxes' triangles (exact for boxes).
TEST(BodyGeometry, BoxBoxAgainstTriangleBruteForce)
{
    TestRandom rng(test::seeded(33));
    QueryContext context;
    int separated = 0;
    const int n = cases(800);
    for (int i = 0; i < n; ++i)
    {
        const Shape a = test::randomShape(ShapeKind::Box, rng), b = test::randomShape(ShapeKind::Box, rng);
        const RigidTransform wa = test::randomPose(rng, 0.1), wb = test::randomPose(rng, 2.4);
        const TriangleMesh ma = test::boxMesh(-a.extents(), a.extents()), mb = test::boxMesh(-b.extents(), b.extents());
        double brute = std::numeric_limits<double>::infinity();
        for (std::size_t s = 0; s < ma.triangleCount(); ++s)
            for (std::size_t t = 0; t < mb.triangleCount(); ++t)
                brute = std::min(brute, triangleDistance(wa.apply(ma.corner(s, 0)), wa.apply(ma.corner(s, 1)),
                                                         wa.apply(ma.corner(s, 2)), wb.apply(mb.corner(t, 0)),
                                                         wb.apply(mb.corner(t, 1)), wb.apply(mb.corner(t, 2))));
        // Surfaces apart may still be nested: a corner of one inside the other.
        const bool nested = containsPoint(a, wa.inverse().apply(wb.translation)) ||
                            containsPoint(b, wb.inverse().apply(wa.translation));
        const BodyPairResult hit = bodiesIntersect(BodyGeometry(a), wa, BodyGeometry(b), wb, context);
        const BodyPairResult r = bodiesDistance(BodyGeometry(a), wa, BodyGeometry(b), wb, context);
        if (brute > 1e-9 && !nested)
        {
            ++separated;
            ASSERT_FALSE(hit.intersecting) << i;
            EXPECT_NEAR(r.distance, brute, 1e-9 * brute + 1e-11) << i;
        }
        else if (brute == 0.0 || nested)
        {
            ASSERT_TRUE(hit.intersecting) << i;
            ASSERT_TRUE(r.intersecting) << i;
        }
    }
    EXPECT_GT(separated, n / 5);
    EXPECT_LT(separated, 4 * n / 5);
}

TEST(BodyGeometry, ShapeTriangleAgreesWithReference)
{
    TestRandom rng(test::seeded(34));
    LpWorkspace lp;
    ShapePairScratch scratch;
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (ShapeKind kind : test::compactKinds())
    {
        const Shape shape = test::randomShape(kind, rng);
        const double reach = test::meanHalfWidth(shape) + 0.4;
        const test::ShapeHulls hulls = test::hullsOf(shape, 6);
        int hits = 0, known = 0;
        const int n = cases(300);
        for (int i = 0; i < n; ++i)
        {
            const RigidTransform pose = test::randomPose(rng, 0.2);
            const Vec3 c = test::randomPose(rng, reach).translation;
            const Vec3 t0 = c + 0.5 * Vec3(u(rng), u(rng), u(rng)), t1 = c + 0.5 * Vec3(u(rng), u(rng), u(rng)),
                       t2 = c + 0.5 * Vec3(u(rng), u(rng), u(rng));
            const ConvexPiece triangle = ConvexPiece::hullOf({t0, t1, t2});
            test::Reference ref = test::Reference::Unknown;
            if (intersectConvexPieces(hulls.inner.transformed(pose), triangle, lp).intersecting)
                ref = test::Reference::Intersecting;
            else if (!intersectConvexPieces(hulls.outer.transformed(pose), triangle, lp).intersecting)
                ref = test::Reference::Disjoint;
            const std::string where = std::string(shapeKindName(kind)) + " case " + std::to_string(i);
            for (ShapePairQuery q : {ShapePairQuery::Intersection, ShapePairQuery::Distance})
            {
                const ShapePairResult r = shapeTriangle(shape, pose, t0, t1, t2, q, scratch);
                if (ref == test::Reference::Intersecting)
                {
                    ASSERT_TRUE(r.intersecting) << where;
                }
                else if (ref == test::Reference::Disjoint)
                {
                    ASSERT_FALSE(r.intersecting) << where;
                }
                if (q == ShapePairQuery::Distance && !r.intersecting)
                {
                    // pointB is on the triangle, and no vertex of the triangle is nearer the shape's
                    // inner tessellation than the reported distance.
                    EXPECT_LE((closestPointOnTriangle(r.pointB, t0, t1, t2) - r.pointB).norm(), 1e-9) << where;
                    double nearest = std::numeric_limits<double>::infinity();
                    for (const Vec3 &p : hulls.innerPoints)
                        nearest = std::min(nearest,
                                           (closestPointOnTriangle(pose.apply(p), t0, t1, t2) - pose.apply(p)).norm());
                    EXPECT_LE(r.distance, nearest + 1e-9) << where;
                }
            }
            hits += ref == test::Reference::Intersecting;
            known += ref != test::Reference::Unknown;
        }
        EXPECT_GE(hits, 15 * known / 100) << shapeKindName(kind);
        EXPECT_LE(hits, 85 * known / 100) << shapeKindName(kind);
    }
}

// A closed box mesh, and an open one (the box without its top).
std::shared_ptr<const TriangleMesh> closedBox(double half)
{
    return std::make_shared<const TriangleMesh>(test::boxMesh(Vec3::Constant(-half), Vec3::Constant(half)));
}

std::shared_ptr<const TriangleMesh> openBox(double half)
{
    TriangleMesh mesh = test::boxMesh(Vec3::Constant(-half), Vec3::Constant(half));
    std::vector<TriangleMesh::Triangle> kept;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
    {
        const bool top =
            mesh.corner(t, 0).z() == half && mesh.corner(t, 1).z() == half && mesh.corner(t, 2).z() == half;
        if (!top)
            kept.push_back(mesh.triangles[t]);
    }
    mesh.triangles = kept;
    return std::make_shared<const TriangleMesh>(mesh);
}

// A bumpy closed surface with 432 triangles: a cube-sphere grid on an ellipsoid, each vertex
// pushed radially by a smooth function of its grid position (so the copies on the cube's seams
// coincide and welding closes the surface).
std::shared_ptr<const TriangleMesh> lumpyMesh()
{
    const Vec3 semiAxes(1.2, 0.8, 0.6);
    TriangleMesh mesh;
    const int cells = 6;
    auto index = [&](int face, int i, int j) {
        return static_cast<std::uint32_t>((face * (cells + 1) + i) * (cells + 1) + j);
    };
    for (int face = 0; face < 6; ++face)
        for (int i = 0; i <= cells; ++i)
            for (int j = 0; j <= cells; ++j)
            {
                const int axis = face / 2;
                Vec3 q;
                q[axis] = face % 2 ? 1.0 : -1.0;
                q[(axis + 1) % 3] = -1.0 + 2.0 * i / cells;
                q[(axis + 2) % 3] = -1.0 + 2.0 * j / cells;
                const double bump = 1.0 + 0.1 * std::sin(3.0 * q.x() + 5.0 * q.y() + 7.0 * q.z());
                mesh.vertices.push_back(semiAxes.cwiseProduct(q.normalized()) * bump);
            }
    for (int face = 0; face < 6; ++face)
        for (int i = 0; i < cells; ++i)
            for (int j = 0; j < cells; ++j)
            {
                mesh.triangles.push_back({index(face, i, j), index(face, i + 1, j), index(face, i + 1, j + 1)});
                mesh.triangles.push_back({index(face, i, j), index(face, i + 1, j + 1), index(face, i, j + 1)});
            }
    weldAndDropDegenerate(mesh);
    return std::make_shared<const TriangleMesh>(mesh);
}

// Reference for shape-mesh: every triangle through shapeTriangle, plus containment of the shape
// in a closed component.
bool meshReference(const Shape &shape, const RigidTransform &worldFromShape, const TriangleMesh &mesh,
                   const RigidTransform &worldFromMesh, const SolidQuery &solids, ShapePairScratch &scratch)
{
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
        if (shapeTriangle(shape, worldFromShape, worldFromMesh.apply(mesh.corner(t, 0)),
                          worldFromMesh.apply(mesh.corner(t, 1)), worldFromMesh.apply(mesh.corner(t, 2)),
                          ShapePairQuery::Intersection, scratch)
                .intersecting)
            return true;
    const Vec3 p = worldFromMesh.inverse().apply(worldFromShape.apply(supportPoint(shape, Vec3::UnitX())));
    return solids.insideAnySolid(p);
}

TEST(BodyGeometry, ShapeAgainstMeshMatchesFlatLoopAndContainment)
{
    TestRandom rng(test::seeded(35));
    QueryContext context;
    ShapePairScratch scratch;
    std::vector<std::shared_ptr<const TriangleMesh>> meshes{closedBox(0.8), openBox(0.8), lumpyMesh()};
    ASSERT_TRUE(isClosed(*meshes[2]));
    ASSERT_FALSE(isClosed(*meshes[1]));
    for (std::size_t m = 0; m < meshes.size(); ++m)
    {
        const BodyGeometry meshBody(Shape::mesh(meshes[m]));
        const SolidQuery solids(meshes[m]);
        for (ShapeKind kind : test::compactKinds())
        {
            int hits = 0;
            const int n = cases(200);
            for (int i = 0; i < n; ++i)
            {
                const Shape shape = test::randomShape(kind, rng, i % 4 == 0 ? 0.2 : 0.7);
                const BodyGeometry body(shape);
                const RigidTransform wm = test::randomPose(rng, 0.2), ws = test::randomPose(rng, 2.0);
                const bool expected = meshReference(shape, ws, *meshes[m], wm, solids, scratch);
                const std::string where =
                    "mesh " + std::to_string(m) + " " + shapeKindName(kind) + " case " + std::to_string(i);
                const BodyPairResult ab = bodiesIntersect(body, ws, meshBody, wm, context);
                const BodyPairResult ba = bodiesIntersect(meshBody, wm, body, ws, context);
                ASSERT_EQ(ab.intersecting, expected) << where;
                ASSERT_EQ(ba.intersecting, expected) << where;
                const BodyPairResult d = bodiesDistance(body, ws, meshBody, wm, context);
                ASSERT_EQ(d.intersecting, expected) << where;
                if (!expected)
                {
                    // Never above the distance to any mesh vertex, and the points are that far apart.
                    double nearest = std::numeric_limits<double>::infinity();
                    for (const Vec3 &v : meshes[m]->vertices)
                    {
                        const ShapePairResult r = shapeTriangle(shape, ws, wm.apply(v), wm.apply(v), wm.apply(v),
                                                                ShapePairQuery::Distance, scratch);
                        nearest = std::min(nearest, r.distance);
                    }
                    // (Both are GJK's certified lower bounds, each within a few 1e-9 relative.)
                    const double relative = 1e-8;
                    EXPECT_LE(d.distance, nearest * (1 + relative) + 1e-12) << where;
                    EXPECT_GT(d.distance, 0.0) << where;
                    EXPECT_NEAR((d.pointA - d.pointB).norm(), d.distance, 1e-8 * d.distance + 1e-10) << where;
                }
                hits += expected;
            }
            EXPECT_GE(hits, n / 10) << m << " " << shapeKindName(kind);
            EXPECT_LE(hits, 9 * n / 10) << m << " " << shapeKindName(kind);
        }
    }
}

TEST(BodyGeometry, ContainmentBothWaysAndOpenMeshes)
{
    QueryContext context;
    const BodyGeometry closed(Shape::mesh(closedBox(1.0))), open(Shape::mesh(openBox(1.0)));
    const BodyGeometry smallBall(Shape::sphere(0.1)), bigBall(Shape::sphere(5.0));
    const BodyGeometry smallCone(Shape::cone(0.1, 0.2));
    // A small shape inside the closed box: colliding; inside the open box: only a surface, free.
    EXPECT_TRUE(
        bodiesIntersect(smallBall, at(Vec3(0.2, 0.1, 0)), closed, RigidTransform::identity(), context).intersecting);
    EXPECT_TRUE(
        bodiesIntersect(closed, RigidTransform::identity(), smallCone, at(Vec3(0.2, 0.1, 0)), context).intersecting);
    EXPECT_EQ(bodiesDistance(smallCone, at(Vec3(0.2, 0.1, 0)), closed, RigidTransform::identity(), context).distance,
              0.0);
    EXPECT_FALSE(
        bodiesIntersect(smallBall, at(Vec3(0.2, 0.1, 0)), open, RigidTransform::identity(), context).intersecting);
    EXPECT_NEAR(bodiesDistance(smallBall, at(Vec3(0.2, 0.1, 0)), open, RigidTransform::identity(), context).distance,
                0.8 - 0.1, 1e-12);
    // The mesh inside a big shape: colliding whether the mesh is closed or open.
    EXPECT_TRUE(
        bodiesIntersect(bigBall, RigidTransform::identity(), closed, RigidTransform::identity(), context).intersecting);
    EXPECT_TRUE(
        bodiesIntersect(open, RigidTransform::identity(), bigBall, RigidTransform::identity(), context).intersecting);
    // Compact shapes nested both ways.
    const BodyGeometry box(Shape::box(Vec3(2, 2, 2))), ellipsoid(Shape::ellipsoid(Vec3(0.3, 0.2, 0.1)));
    EXPECT_TRUE(
        bodiesIntersect(box, RigidTransform::identity(), ellipsoid, at(Vec3(0.5, 0.5, 0.5)), context).intersecting);
    EXPECT_TRUE(
        bodiesIntersect(ellipsoid, at(Vec3(0.5, 0.5, 0.5)), box, RigidTransform::identity(), context).intersecting);
}

TEST(BodyGeometry, ExactContactThinAndCoplanar)
{
    QueryContext context;
    const BodyGeometry cube(Shape::box(Vec3(0.5, 0.5, 0.5)));
    const RigidTransform rotated = RigidTransform::fromAxisAngle(Vec3::Zero(), Vec3(0, 0, 1), M_PI / 2);  // exact in z
    // Face to face (dyadic offsets), with one box turned a quarter about the contact normal.
    for (const Vec3 &offset : {Vec3(1, 0, 0), Vec3(0, 0, 1), Vec3(1, 1, 1), Vec3(0.25, 1, 0)})
    {
        RigidTransform other = rotated;
        other.translation = offset;
        EXPECT_TRUE(bodiesIntersect(cube, RigidTransform::identity(), cube, other, context).intersecting)
            << offset.transpose();
        EXPECT_TRUE(bodiesIntersect(cube, RigidTransform::identity(), cube, at(offset), context).intersecting);
        EXPECT_FALSE(
            bodiesIntersect(cube, RigidTransform::identity(), cube, at(offset * (1 + 1e-9)), context).intersecting);
    }
    // Thin boxes (1e-6 thick): crossing, stacked with coplanar faces, and a hair apart.
    const BodyGeometry plate(Shape::box(Vec3(1, 1, 0.5e-6)));
    EXPECT_TRUE(bodiesIntersect(plate, RigidTransform::identity(), plate,
                                RigidTransform::fromAxisAngle(Vec3::Zero(), Vec3(1, 0, 0), M_PI / 2), context)
                    .intersecting);
    EXPECT_TRUE(
        bodiesIntersect(plate, RigidTransform::identity(), plate, at(Vec3(0.5, 0, 1e-6)), context).intersecting);
    EXPECT_FALSE(
        bodiesIntersect(plate, RigidTransform::identity(), plate, at(Vec3(0.5, 0, 2e-6)), context).intersecting);
    // A sphere touching a box face, a cylinder standing on a half-space.
    EXPECT_TRUE(
        bodiesIntersect(BodyGeometry(Shape::sphere(0.5)), at(Vec3(0, 0, 1)), cube, RigidTransform::identity(), context)
            .intersecting);
    const BodyGeometry ground(Shape::halfspace(Vec3(0, 0, 1), 0.0));
    EXPECT_TRUE(bodiesIntersect(BodyGeometry(Shape::cylinder(0.3, 0.5)), at(Vec3(4, 1, 0.5)), ground,
                                RigidTransform::identity(), context)
                    .intersecting);
    EXPECT_NEAR(bodiesDistance(BodyGeometry(Shape::cylinder(0.3, 0.5)), at(Vec3(4, 1, 0.75)), ground,
                               RigidTransform::identity(), context)
                    .distance,
                0.25, 1e-12);
    // Half-space against a mesh: the lowest vertex decides, touching included.
    const BodyGeometry closed(Shape::mesh(closedBox(1.0)));
    EXPECT_TRUE(bodiesIntersect(ground, at(Vec3(0, 0, -1)), closed, RigidTransform::identity(), context).intersecting);
    EXPECT_FALSE(
        bodiesIntersect(ground, at(Vec3(0, 0, -1.001)), closed, RigidTransform::identity(), context).intersecting);
    EXPECT_NEAR(bodiesDistance(closed, RigidTransform::identity(), ground, at(Vec3(0, 0, -1.5)), context).distance, 0.5,
                1e-12);
}

TEST(BodyGeometry, TinyAndHugeScales)
{
    TestRandom rng(test::seeded(36));
    QueryContext context;
    LpWorkspace lp;
    for (double scale : {1e-6, 1e6})
    {
        int hits = 0, total = 0;
        for (ShapeKind ka : {ShapeKind::Box, ShapeKind::Cylinder, ShapeKind::Ellipsoid})
            for (ShapeKind kb : {ShapeKind::Convex, ShapeKind::Cone, ShapeKind::Capsule})
            {
                const Shape a = test::randomShape(ka, rng, scale), b = test::randomShape(kb, rng, scale);
                const test::ShapeHulls ha = test::hullsOf(a, 6), hb = test::hullsOf(b, 6);
                const int n = cases(60);
                total += n;
                for (int i = 0; i < n; ++i)
                {
                    const RigidTransform wa = test::randomPose(rng, 0.1 * scale),
                                         wb = test::randomPose(rng, 1.6 * scale);
                    const test::Reference ref = test::referenceVerdict(ha, wa, hb, wb, lp);
                    const bool hit = bodiesIntersect(BodyGeometry(a), wa, BodyGeometry(b), wb, context).intersecting;
                    if (ref == test::Reference::Intersecting)
                    {
                        ASSERT_TRUE(hit) << scale << " " << i;
                    }
                    else if (ref == test::Reference::Disjoint)
                    {
                        ASSERT_FALSE(hit) << scale << " " << i;
                    }
                    hits += ref == test::Reference::Intersecting;
                }
            }
        EXPECT_GT(hits, total / 5) << scale;
        EXPECT_LT(hits, 4 * total / 5) << scale;
    }
}

// Shared immutable geometry, one context per thread: the same answers as a serial run.
TEST(BodyGeometry, ThreadsWithTheirOwnContextsAgreeWithSerial)
{
    TestRandom rng(test::seeded(38));
    std::vector<BodyGeometry> bodies;
    for (ShapeKind kind : test::compactKinds())
        bodies.emplace_back(test::randomShape(kind, rng));
    bodies.emplace_back(Shape::mesh(closedBox(0.8)));
    bodies.emplace_back(Shape::halfspace(Vec3(0, 0, 1), 0.0));
    const int n = cases(400);
    std::vector<RigidTransform> poses;
    for (int i = 0; i < 2 * n; ++i)
        poses.push_back(test::randomPose(rng, 1.5));
    auto answer = [&](int i, QueryContext &context) {
        const BodyGeometry &a = bodies[static_cast<std::size_t>(i) % bodies.size()];
        const BodyGeometry &b = bodies[static_cast<std::size_t>(i / 3) % (bodies.size() - 1)];
        if (a.shape().kind() == ShapeKind::Mesh && b.shape().kind() == ShapeKind::Mesh)
            return -1.0;
        return bodiesDistance(a, poses[2 * i], b, poses[2 * i + 1], context).distance;
    };
    std::vector<double> serial(static_cast<std::size_t>(n)), parallel(static_cast<std::size_t>(n));
    QueryContext context;
    for (int i = 0; i < n; ++i)
        serial[i] = answer(i, context);
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
        threads.emplace_back([&, t] {
            QueryContext own;
            for (int i = t; i < n; i += 4)
                parallel[i] = answer(i, own);
        });
    for (std::thread &thread : threads)
        thread.join();
    for (int i = 0; i < n; ++i)
        ASSERT_NEAR(parallel[i], serial[i], 3e-9 * std::max(1.0, serial[i])) << i;  // warm starts differ
}

TEST(BodyGeometry, BoundsMeshPairsAndCounters)
{
    TestRandom rng(test::seeded(37));
    QueryContext context;
    const BodyGeometry mesh(Shape::mesh(closedBox(1.0)));
    EXPECT_THROW(bodiesIntersect(mesh, RigidTransform::identity(), mesh, RigidTransform::identity(), context),
                 std::invalid_argument);
    EXPECT_THROW(bodiesDistance(mesh, RigidTransform::identity(), mesh, RigidTransform::identity(), context),
                 std::invalid_argument);
    EXPECT_NEAR(mesh.boundingRadius(), std::sqrt(3.0), 1e-15);
    const BodyGeometry half(Shape::halfspace(Vec3(1, 1, 0), 0.0));
    EXPECT_TRUE(std::isinf(half.boundingRadius()));
    EXPECT_TRUE(std::isinf(half.worldBounds(RigidTransform::identity()).halfExtents.x()));
    for (ShapeKind kind : test::compactKinds())
    {
        const Shape shape = test::randomShape(kind, rng);
        const BodyGeometry body(shape);
        const std::vector<Vec3> points = tessellationPoints(shape, 6, TessellationSide::Inner);
        for (int i = 0; i < cases(20); ++i)
        {
            const RigidTransform pose = test::randomPose(rng, 3.0);
            const Aabb box = body.worldBounds(pose);
            for (const Vec3 &p : points)
                ASSERT_TRUE(box.contains(pose.apply(p))) << shapeKindName(kind);
        }
    }
    // Curved pairs go through GJK and are counted; nothing here is undecided.
    bodiesDistance(BodyGeometry(Shape::cone(0.3, 0.4)), at(Vec3(2, 0, 0)), BodyGeometry(Shape::cylinder(0.2, 0.5)),
                   RigidTransform::identity(), context);
    EXPECT_GT(bodyQueryCounters(context).gjkQueries, 0u);
    EXPECT_GT(bodyQueryCounters(context).gjkIterations, 0u);
    EXPECT_EQ(bodyQueryCounters(context).undecided, 0u);
    const std::uint64_t before = context.stats.primitiveTests;
    bodiesIntersect(BodyGeometry(Shape::sphere(0.3)), at(Vec3(0.9, 0, 0)), mesh, RigidTransform::identity(), context);
    EXPECT_GT(context.stats.primitiveTests, before);
}
}  // namespace
}  // namespace hcd
