// SPDX-License-Identifier: BSD-3-Clause
// Shapes: parameter validation, kind names, support points (in the shape and maximal over dense
// samples of it), world bounds and bounding radii (holding every sample), and the inner/outer
// tessellations (inner points in the shape, outer hull holding random points of the shape).
#include "hybridcd/geometry/shape.h"
#include "support/shape_reference.h"
#include "support/test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace hcd
{
namespace
{
using test::cases;
using test::TestRandom;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Random points of the shape by rejection from its box (closed-form kinds).
std::vector<Vec3> samplesInside(const Shape &shape, int count, TestRandom &rng)
{
    const double r = boundingRadius(shape);
    std::uniform_real_distribution<double> u(-r, r);
    std::vector<Vec3> points;
    while (static_cast<int>(points.size()) < count)
    {
        const Vec3 p(u(rng), u(rng), u(rng));
        if (containsPoint(shape, p))
            points.push_back(p);
    }
    return points;
}

TEST(Shape, RejectsInvalidParameters)
{
    // Non-positive, non-finite, and lengths whose squares would over- or underflow.
    for (double bad : {0.0, -1.0, kNaN, kInf, 1e101, 1e-101})
    {
        EXPECT_THROW(Shape::sphere(bad), std::invalid_argument);
        EXPECT_THROW(Shape::box(Vec3(1, bad, 1)), std::invalid_argument);
        EXPECT_THROW(Shape::capsule(bad, 1), std::invalid_argument);
        EXPECT_THROW(Shape::capsule(1, bad), std::invalid_argument);
        EXPECT_THROW(Shape::cylinder(bad, 1), std::invalid_argument);
        EXPECT_THROW(Shape::cone(1, bad), std::invalid_argument);
        EXPECT_THROW(Shape::ellipsoid(Vec3(bad, 1, 1)), std::invalid_argument);
    }
    EXPECT_THROW(Shape::halfspace(Vec3::Zero(), 0.0), std::invalid_argument);
    EXPECT_THROW(Shape::halfspace(Vec3(0, 0, 1), kNaN), std::invalid_argument);
    EXPECT_THROW(Shape::halfspace(Vec3(0, 0, 1), 1e101), std::invalid_argument);
    EXPECT_THROW(Shape::convex({}), std::invalid_argument);
    EXPECT_THROW(Shape::convex({Vec3(0, kInf, 0)}), std::invalid_argument);
    EXPECT_THROW(Shape::mesh(nullptr), std::invalid_argument);
    EXPECT_THROW(Shape::mesh(std::make_shared<TriangleMesh>()), std::invalid_argument);
    EXPECT_THROW(supportPoint(Shape::halfspace(Vec3(0, 0, 1), 0), Vec3::UnitX()), std::invalid_argument);
}

TEST(Shape, KindNamesRoundTrip)
{
    for (int k = 0; k < kShapeKindCount; ++k)
    {
        const ShapeKind kind = static_cast<ShapeKind>(k);
        const auto parsed = shapeKindFromName(shapeKindName(kind));
        ASSERT_TRUE(parsed.has_value()) << shapeKindName(kind);
        EXPECT_EQ(*parsed, kind);
    }
    EXPECT_FALSE(shapeKindFromName("torus").has_value());
    EXPECT_STREQ(shapeKindName(ShapeKind::Cone), "cone");
}

TEST(Shape, HalfspaceIsNormalised)
{
    const Shape h = Shape::halfspace(Vec3(0, 0, 2), 3.0);
    EXPECT_DOUBLE_EQ(h.normal().z(), 1.0);
    EXPECT_DOUBLE_EQ(h.offset(), 1.5);
    EXPECT_TRUE(containsPoint(h, Vec3(5, 5, 1.5)));
    EXPECT_FALSE(containsPoint(h, Vec3(5, 5, 1.5000001)));
    EXPECT_EQ(boundingRadius(h), kInf);
    const BoundingBox b = worldBounds(h, RigidTransform::identity());
    EXPECT_EQ(b.min.z(), -kInf);
    EXPECT_NEAR(b.max.z(), 1.5, 1e-9);
    EXPECT_EQ(b.max.x(), kInf);

    // Normals whose squares underflow or overflow (found by a held-out probe: 1e-160 gave a unit
    // normal off by 1e-5, and a clearance that much too large): the same plane as a unit normal.
    for (const double scale : {1e-160, 1e-300, 1e200, 1e300})
    {
        const Shape scaled = Shape::halfspace(Vec3(scale, 0, 0), scale);
        EXPECT_EQ(scaled.normal(), Vec3(1, 0, 0)) << scale;
        EXPECT_EQ(scaled.offset(), 1.0) << scale;
        const Shape skew = Shape::halfspace(Vec3(3 * scale, 4 * scale, 0), 10 * scale);
        EXPECT_NEAR(skew.normal().x(), 0.6, 1e-15) << scale;
        EXPECT_NEAR(skew.normal().y(), 0.8, 1e-15) << scale;
        EXPECT_NEAR(skew.offset(), 2.0, 1e-15) << scale;
    }
}

// Support points lie in the shape and beat every sampled point of it; bounds hold the samples.
TEST(Shape, SupportPointsBoundsAndTessellations)
{
    TestRandom rng(test::seeded(21));
    for (ShapeKind kind : test::compactKinds())
    {
        const Shape shape = test::randomShape(kind, rng);
        const bool closedForm = kind != ShapeKind::Convex;
        const std::vector<Vec3> inner = tessellationPoints(shape, 8, TessellationSide::Inner);
        const ConvexPiece outer = ConvexPiece::hullOf(tessellationPoints(shape, 8, TessellationSide::Outer));
        std::vector<Vec3> samples = inner;
        if (closedForm)
        {
            const std::vector<Vec3> more = samplesInside(shape, 2000, rng);
            samples.insert(samples.end(), more.begin(), more.end());
            for (const Vec3 &p : inner)  // the inner tessellation lies in the shape
                ASSERT_TRUE(containsPoint(shape, p * (1.0 - 1e-12))) << shapeKindName(kind);
            for (const Vec3 &p : more)  // the outer hull holds the shape
                ASSERT_LE(outer.maxViolation(p), 1e-12) << shapeKindName(kind);
        }
        std::normal_distribution<double> n;
        for (int i = 0; i < cases(300); ++i)
        {
            const Vec3 d(n(rng), n(rng), n(rng));
            const Vec3 s = supportPoint(shape, d);
            if (closedForm)
            {
                ASSERT_TRUE(containsPoint(shape, s * (1.0 - 1e-12))) << shapeKindName(kind);
            }
            for (const Vec3 &p : samples)
                ASSERT_GE(d.dot(s), d.dot(p) - 1e-12 * d.norm()) << shapeKindName(kind);
        }
        const double radius = boundingRadius(shape);
        for (int i = 0; i < cases(20); ++i)
        {
            const RigidTransform pose = test::randomPose(rng, 5.0);
            const BoundingBox box = worldBounds(shape, pose);
            for (const Vec3 &p : samples)
            {
                const Vec3 w = pose.apply(p);
                ASSERT_TRUE((w.array() >= box.min.array()).all() && (w.array() <= box.max.array()).all())
                    << shapeKindName(kind);
                ASSERT_LE(p.norm(), radius * (1.0 + 1e-12)) << shapeKindName(kind);
            }
            // Tight up to the samples' coverage: the box is no wider than the samples' by 5%.
            BoundingBox sampled;
            for (const Vec3 &p : inner)
                sampled.extend(pose.apply(p));
            EXPECT_LE((box.max - box.min).maxCoeff(), 1.05 * (sampled.max - sampled.min).maxCoeff() + 1e-9);
        }
    }
}

TEST(Shape, TessellationErrorBoundShrinksWithResolution)
{
    EXPECT_GT(tessellationRelativeError(2), tessellationRelativeError(8));
    EXPECT_LT(tessellationRelativeError(16), 2e-3);
    // The outer points are the inner ones scaled by at most 1 + the stated error.
    const Shape ball = Shape::sphere(2.0);
    const auto inner = tessellationPoints(ball, 6, TessellationSide::Inner);
    const auto outer = tessellationPoints(ball, 6, TessellationSide::Outer);
    ASSERT_EQ(inner.size(), outer.size());
    for (std::size_t i = 0; i < inner.size(); ++i)
        EXPECT_LE(outer[i].norm(), inner[i].norm() * (1.0 + tessellationRelativeError(6)) + 1e-12);
}

TEST(Shape, ConeAndCylinderClosedForms)
{
    const Shape cone = Shape::cone(1.0, 2.0);
    EXPECT_EQ(supportPoint(cone, Vec3(0, 0, 1)), Vec3(0, 0, 2));
    EXPECT_NEAR(supportPoint(cone, Vec3(1, 0, -1)).x(), 1.0, 1e-15);
    EXPECT_TRUE(containsPoint(cone, Vec3(0.5, 0, 0)));  // radius at z = 0 is 0.5
    EXPECT_FALSE(containsPoint(cone, Vec3(0.51, 0, 0)));
    const Shape cylinder = Shape::cylinder(1.0, 2.0);
    EXPECT_TRUE(containsPoint(cylinder, Vec3(0.6, 0.8, -2)));
    EXPECT_FALSE(containsPoint(cylinder, Vec3(0.6, 0.8, -2.001)));
    EXPECT_DOUBLE_EQ(boundingRadius(cylinder), std::sqrt(5.0));
}
}  // namespace
}  // namespace hcd
