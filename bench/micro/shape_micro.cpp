// SPDX-License-Identifier: BSD-3-Clause
// Pair queries between implicit shapes: hybridcd's pair table (narrowphase/shape_pair.h) against
// FCL 0.7's primitives (fcl::collide / fcl::distance with default requests), per pair of kinds,
// on the same 256 random poses (about half of them colliding). FCL has no convex hull of bare
// points without faces, so the convex kind is timed for hybridcd only, and FCL's distance has no
// half-space routine (it crashes), so half-space distances are hybridcd's only.
//
//   hybridcd_bench_shape_micro --benchmark_filter=box/cylinder
#include "hybridcd/geometry/shape.h"
#include "hybridcd/narrowphase/shape_pair.h"

#include <benchmark/benchmark.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/halfspace.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <memory>
#include <random>
#include <string>
#include <vector>

namespace
{
using hcd::RigidTransform;
using hcd::Shape;
using hcd::ShapeKind;
using hcd::Vec3;

struct Pose
{
    RigidTransform a, b;
};

// The benchmark's shapes: sizes near 1, so that poses within 1.8 collide about half the time.
Shape makeShape(ShapeKind kind)
{
    switch (kind)
    {
    case ShapeKind::Sphere:
        return Shape::sphere(0.6);
    case ShapeKind::Box:
        return Shape::box(Vec3(0.6, 0.4, 0.3));
    case ShapeKind::Capsule:
        return Shape::capsule(0.3, 0.4);
    case ShapeKind::Cylinder:
        return Shape::cylinder(0.4, 0.5);
    case ShapeKind::Cone:
        return Shape::cone(0.5, 0.5);
    case ShapeKind::Ellipsoid:
        return Shape::ellipsoid(Vec3(0.7, 0.5, 0.3));
    case ShapeKind::Halfspace:
        return Shape::halfspace(Vec3(0, 0, 1), 0.0);
    default:
        break;
    }
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-0.6, 0.6);
    std::vector<Vec3> points;
    for (int i = 0; i < 24; ++i)
        points.emplace_back(u(rng), u(rng), u(rng));
    return Shape::convex(points);
}

// FCL's equivalent (its cylinders, cones and capsules take full lengths along z).
std::shared_ptr<fcl::CollisionGeometryd> toFcl(const Shape &s)
{
    switch (s.kind())
    {
    case ShapeKind::Sphere:
        return std::make_shared<fcl::Sphered>(s.radius());
    case ShapeKind::Box:
        return std::make_shared<fcl::Boxd>(2.0 * s.extents());
    case ShapeKind::Capsule:
        return std::make_shared<fcl::Capsuled>(s.radius(), 2.0 * s.halfLength());
    case ShapeKind::Cylinder:
        return std::make_shared<fcl::Cylinderd>(s.radius(), 2.0 * s.halfLength());
    case ShapeKind::Cone:
        return std::make_shared<fcl::Coned>(s.radius(), 2.0 * s.halfLength());
    case ShapeKind::Ellipsoid:
        return std::make_shared<fcl::Ellipsoidd>(s.extents());
    case ShapeKind::Halfspace:
        return std::make_shared<fcl::Halfspaced>(s.normal(), s.offset());
    default:
        return nullptr;
    }
}

fcl::Transform3d toFcl(const RigidTransform &pose)
{
    fcl::Transform3d tf = fcl::Transform3d::Identity();
    tf.linear() = pose.rotation;
    tf.translation() = pose.translation;
    return tf;
}

std::vector<Pose> makePoses()
{
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<Pose> poses;
    while (poses.size() < 256)
    {
        const Vec3 t(u(rng), u(rng), u(rng));
        if (t.squaredNorm() > 1.0)
            continue;
        auto rotation = [&] {
            return RigidTransform::fromAxisAngle(Vec3::Zero(), Vec3(u(rng), u(rng), u(rng)), 3.0 * u(rng)).rotation;
        };
        poses.push_back({{rotation(), Vec3::Zero()}, {rotation(), 1.8 * t}});
    }
    return poses;
}

void hybridcdPair(benchmark::State &state, ShapeKind ka, ShapeKind kb, hcd::ShapePairQuery query)
{
    const Shape a = makeShape(ka), b = makeShape(kb);
    const std::vector<Pose> poses = makePoses();
    hcd::ShapePairScratch scratch;
    std::size_t i = 0, hits = 0;
    for (auto _ : state)
    {
        const Pose &p = poses[i++ & 255];
        const hcd::ShapePairResult r = hcd::shapePair(a, p.a, b, p.b, query, scratch);
        hits += r.intersecting;
        benchmark::DoNotOptimize(r);
    }
    state.counters["hit_rate"] = double(hits) / double(std::max<std::size_t>(i, 1));
    state.counters["gjk_iterations"] =
        double(scratch.gjkIterations) / double(std::max<std::uint64_t>(scratch.gjkQueries, 1));
}

void fclPair(benchmark::State &state, ShapeKind ka, ShapeKind kb, bool distance)
{
    const auto a = toFcl(makeShape(ka)), b = toFcl(makeShape(kb));
    const std::vector<Pose> poses = makePoses();
    std::vector<std::pair<fcl::Transform3d, fcl::Transform3d>> tfs;
    for (const Pose &p : poses)
        tfs.emplace_back(toFcl(p.a), toFcl(p.b));
    std::size_t i = 0, hits = 0;
    for (auto _ : state)
    {
        const auto &tf = tfs[i++ & 255];
        if (distance)
        {
            fcl::DistanceRequestd request;
            fcl::DistanceResultd result;
            const double d = fcl::distance(a.get(), tf.first, b.get(), tf.second, request, result);
            hits += d <= 0.0;
            benchmark::DoNotOptimize(d);
        }
        else
        {
            fcl::CollisionRequestd request;
            fcl::CollisionResultd result;
            hits += fcl::collide(a.get(), tf.first, b.get(), tf.second, request, result) > 0;
        }
    }
    state.counters["hit_rate"] = double(hits) / double(std::max<std::size_t>(i, 1));
}

const bool registered = [] {
    const std::vector<ShapeKind> kinds{ShapeKind::Sphere,    ShapeKind::Box,   ShapeKind::Capsule,
                                       ShapeKind::Cylinder,  ShapeKind::Cone,  ShapeKind::Ellipsoid,
                                       ShapeKind::Halfspace, ShapeKind::Convex};
    for (std::size_t i = 0; i < kinds.size(); ++i)
        for (std::size_t j = i; j < kinds.size(); ++j)
        {
            const ShapeKind ka = kinds[i], kb = kinds[j];
            if (ka == ShapeKind::Halfspace && kb == ShapeKind::Halfspace)
                continue;
            const std::string pair = std::string(hcd::shapeKindName(ka)) + "/" + hcd::shapeKindName(kb);
            benchmark::RegisterBenchmark(("collide/hybridcd/" + pair).c_str(), hybridcdPair, ka, kb,
                                         hcd::ShapePairQuery::Intersection);
            benchmark::RegisterBenchmark(("distance/hybridcd/" + pair).c_str(), hybridcdPair, ka, kb,
                                         hcd::ShapePairQuery::Distance);
            if (ka == ShapeKind::Convex || kb == ShapeKind::Convex)
                continue;
            benchmark::RegisterBenchmark(("collide/fcl/" + pair).c_str(), fclPair, ka, kb, false);
            // FCL 0.7's fcl::distance crashes on half-spaces (no distance routine for them).
            if (kb != ShapeKind::Halfspace)
                benchmark::RegisterBenchmark(("distance/fcl/" + pair).c_str(), fclPair, ka, kb, true);
        }
    return true;
}();
}  // namespace
