// SPDX-License-Identifier: BSD-3-Clause
// The convex decomposition behind the LP checker: every leaf triangle lies in its leaf's piece
// (on OMPL.app meshes and random soups at several scales), the reported concavity agrees with an
// independent brute-force measurement over the hull's surface, and the approximate mode it
// enables is conservative: it never calls a pose free that the brute-force reference calls
// colliding, and at tolerance 0 it agrees with the reference exactly.
#include "hybridcd/io/mesh_loader.h"
#include "hybridcd/narrowphase/convex_decomposition.h"
#include "hybridcd/query/checker_catalogue.h"
#include "hybridcd/query/leaf_decomposition.h"
#include "support/test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <random>
#include <string>
#include <vector>

using namespace hcd;

namespace
{
using test::TestRandom;
using Tree = VolumeTree<Obb>;

// ---------------------------------------------------------------------------------------------
// Independent geometry (deliberately not the library's): point-to-triangle distance, the hull's
// facets from its planes and vertices, and samples on its surface.

double pointSegmentDistance(const Vec3 &p, const Vec3 &a, const Vec3 &b)
{
    const Vec3 ab = b - a;
    const double length2 = ab.squaredNorm();
    const double t = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
    return (p - (a + t * ab)).norm();
}

// Closed triangle: the plane distance when the projection falls inside, else the nearest edge.
double pointTriangleDistance(const Vec3 &p, const Vec3 &a, const Vec3 &b, const Vec3 &c)
{
    const Vec3 n = (b - a).cross(c - a);
    const double n2 = n.squaredNorm();
    if (n2 > 0.0)
    {
        const double h = (p - a).dot(n) / n2;
        const Vec3 q = p - h * n;
        if ((b - a).cross(q - a).dot(n) >= 0.0 && (c - b).cross(q - b).dot(n) >= 0.0 &&
            (a - c).cross(q - c).dot(n) >= 0.0)
            return std::fabs(h) * std::sqrt(n2);
    }
    return std::min({pointSegmentDistance(p, a, b), pointSegmentDistance(p, b, c), pointSegmentDistance(p, c, a)});
}

double distanceToTriangles(const Vec3 &p, const TriangleMesh &mesh, const std::vector<std::uint32_t> &triangles)
{
    double best = std::numeric_limits<double>::infinity();
    for (std::uint32_t t : triangles)
        best = std::min(best, pointTriangleDistance(p, mesh.corner(t, 0), mesh.corner(t, 1), mesh.corner(t, 2)));
    return best;
}

std::vector<std::uint32_t> leafTriangles(const Tree &tree, const Tree::Node &node)
{
    return {tree.triangleOrder().begin() + node.firstTriangle,
            tree.triangleOrder().begin() + node.firstTriangle + node.triangleCount};
}

// The vertices of `piece` on each of its planes (within rounding), for planes holding at least
// three: the facets of a solid piece, or twice the polygon of a flat one.
struct Facet
{
    Vec3 normal;
    std::vector<Vec3> vertices;
};

std::vector<Facet> hullFacets(const ConvexPiece &piece)
{
    std::vector<Facet> facets;
    const double tolerance = 1e-9 * (1.0 + piece.magnitude());
    for (std::size_t f = 0; f < piece.normals.size(); ++f)
    {
        Facet facet{piece.normals[f], {}};
        for (const Vec3 &v : piece.vertices)
            if (std::fabs(piece.normals[f].dot(v) - piece.offsets[f]) <= tolerance)
                facet.vertices.push_back(v);
        if (facet.vertices.size() >= 3)
            facets.push_back(std::move(facet));
    }
    return facets;
}

struct SurfaceTriangle
{
    Vec3 a, b, c;
};

// The hull's surface as triangles: each facet's convex polygon (Andrew's monotone chain in the
// facet's plane, collinear points dropped) fanned from its first corner.
std::vector<SurfaceTriangle> hullSurface(const ConvexPiece &piece)
{
    std::vector<SurfaceTriangle> surface;
    for (const Facet &facet : hullFacets(piece))
    {
        const std::vector<Vec3> &points = facet.vertices;
        const Vec3 u = facet.normal.unitOrthogonal(), w = facet.normal.cross(u).normalized();
        std::vector<Eigen::Vector2d> uv(points.size());
        std::vector<std::size_t> order(points.size());
        for (std::size_t i = 0; i < points.size(); ++i)
        {
            uv[i] = {u.dot(points[i] - points[0]), w.dot(points[i] - points[0])};
            order[i] = i;
        }
        std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
            return uv[a].x() < uv[b].x() || (uv[a].x() == uv[b].x() && uv[a].y() < uv[b].y());
        });
        const auto turn = [&](std::size_t o, std::size_t a, std::size_t b) {
            const Eigen::Vector2d oa = uv[a] - uv[o], ob = uv[b] - uv[o];
            return oa.x() * ob.y() - oa.y() * ob.x();
        };
        std::vector<std::size_t> hull(2 * points.size());
        std::size_t m = 0;
        for (std::size_t i = 0; i < order.size(); ++i)
        {
            while (m >= 2 && turn(hull[m - 2], hull[m - 1], order[i]) <= 0.0)
                --m;
            hull[m++] = order[i];
        }
        for (std::size_t i = order.size() - 1, lower = m + 1; i-- > 0;)
        {
            while (m >= lower && turn(hull[m - 2], hull[m - 1], order[i]) <= 0.0)
                --m;
            hull[m++] = order[i];
        }
        hull.resize(m > 0 ? m - 1 : 0);
        for (std::size_t i = 1; i + 1 < hull.size(); ++i)
            surface.push_back({points[hull[0]], points[hull[i]], points[hull[i + 1]]});
    }
    return surface;
}

// `count` points uniform (by area) on the surface.
std::vector<Vec3> uniformSurfaceSamples(const std::vector<SurfaceTriangle> &surface, int count, TestRandom &rng)
{
    std::vector<double> cumulative;
    double total = 0.0;
    for (const SurfaceTriangle &t : surface)
        cumulative.push_back(total += 0.5 * (t.b - t.a).cross(t.c - t.a).norm());
    std::vector<Vec3> samples;
    if (surface.empty() || !(total > 0.0))
        return samples;
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int i = 0; i < count; ++i)
    {
        const double pick = unit(rng) * total;
        const std::size_t k =
            std::min(surface.size() - 1,
                     std::size_t(std::lower_bound(cumulative.begin(), cumulative.end(), pick) - cumulative.begin()));
        const double r = std::sqrt(unit(rng)), s = unit(rng);
        const SurfaceTriangle &t = surface[k];
        samples.push_back((1.0 - r) * t.a + r * (1.0 - s) * t.b + r * s * t.c);
    }
    return samples;
}

// A grid of `perEdge` steps over the fan of each facet from the mean of its vertices, the
// vertices in angular order: for perEdge a multiple of 4 this contains the points the library
// measures (its 4-step grid on the same fans), so its maximum bounds the reported one from above.
std::vector<Vec3> fanGridSamples(const ConvexPiece &piece, int perEdge)
{
    std::vector<Vec3> samples;
    for (Facet &f : hullFacets(piece))
    {
        std::vector<Vec3> &facet = f.vertices;
        Vec3 centre = Vec3::Zero();
        for (const Vec3 &v : facet)
            centre += v / double(facet.size());
        const Vec3 u = (facet[0] - centre).normalized(), w = f.normal.cross(u);
        const auto angle = [&](const Vec3 &p) { return std::atan2((p - centre).dot(w), (p - centre).dot(u)); };
        std::sort(facet.begin(), facet.end(), [&](const Vec3 &a, const Vec3 &b) { return angle(a) < angle(b); });
        for (std::size_t i = 0; i < facet.size(); ++i)
        {
            const Vec3 &a = facet[i], &b = facet[(i + 1) % facet.size()];
            for (int s = 0; s <= perEdge; ++s)
                for (int t = 0; s + t <= perEdge; ++t)
                    samples.push_back(centre + double(s) / perEdge * (a - centre) + double(t) / perEdge * (b - centre));
        }
    }
    return samples;
}

// ---------------------------------------------------------------------------------------------
// Meshes.

TriangleMesh loadEnvironmentMesh(const std::string &path) { return *loadMesh(path, MeshRole::Environment).mesh; }

std::size_t leafCount(const Tree &tree)
{
    return std::size_t(
        std::count_if(tree.nodes().begin(), tree.nodes().end(), [](const Tree::Node &n) { return n.isLeaf(); }));
}

enum class Soup
{
    Scattered,  ///< independent random triangles in a box
    Surface,    ///< a random height field: neighbours share edges, many nearly coplanar
    Flat,       ///< every triangle in one tilted plane (flat pieces, planes hit only up to rounding)
    Thin,       ///< a slab 1e-10 of the size thick: just above the flat threshold (Qhull on slivers)
};

// Random triangles of size ~`scale` around `centre` (no zero-area ones).
TriangleMesh randomSoup(Soup kind, int count, double scale, const Vec3 &centre, TestRandom &rng)
{
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    TriangleMesh mesh;
    const Mat3 tilt = test::randomRotation(rng);
    if (kind == Soup::Surface)
    {
        const int side = std::max(2, int(std::sqrt(count / 2.0)) + 1);
        for (int i = 0; i < side; ++i)
            for (int j = 0; j < side; ++j)
                mesh.vertices.push_back(centre + scale * tilt * Vec3(double(i) / side, double(j) / side, 0.1 * u(rng)));
        for (int i = 0; i + 1 < side; ++i)
            for (int j = 0; j + 1 < side; ++j)
            {
                const std::uint32_t a = std::uint32_t(i * side + j), b = a + 1, c = a + std::uint32_t(side), d = c + 1;
                mesh.triangles.push_back({a, b, d});
                mesh.triangles.push_back({a, d, c});
            }
        return mesh;
    }
    for (int t = 0; t < count; ++t)
    {
        const Vec3 base(u(rng), u(rng), u(rng));
        for (int k = 0; k < 3; ++k)
        {
            Vec3 local = base + 0.3 * Vec3(u(rng), u(rng), u(rng));
            if (kind == Soup::Flat)
                local.z() = 0.0;
            if (kind == Soup::Thin)
                local.z() = 1e-10 * u(rng);
            mesh.vertices.push_back(centre + scale * tilt * local);
        }
        const std::uint32_t first = std::uint32_t(3 * t);
        mesh.triangles.push_back({first, first + 1, first + 2});
    }
    return mesh;
}

// ---------------------------------------------------------------------------------------------
// 1. Coverage: every corner of every triangle satisfies every inequality of its leaf's piece.

struct Coverage
{
    std::size_t pieces = 0;
    std::size_t byDimension[4] = {0, 0, 0, 0};  ///< pieces by affine dimension
    double worstRelativeViolation = 0.0;        ///< max over corners of maxViolation / coordinates' magnitude
};

Coverage checkCoverage(const TriangleMesh &mesh, unsigned leafSize, const std::string &label)
{
    const Tree tree(std::make_shared<const TriangleMesh>(mesh), leafSize);
    const ConvexDecomposition d = decomposeLeaves(tree);
    Coverage c;
    c.pieces = d.pieces.size();
    EXPECT_EQ(d.pieces.size(), leafCount(tree)) << label;
    EXPECT_EQ(d.concavity.size(), d.pieces.size()) << label;
    EXPECT_EQ(d.pieceOfNode.size(), tree.nodes().size()) << label;
    if (d.pieceOfNode.size() != tree.nodes().size())
        return c;
    std::vector<int> uses(d.pieces.size(), 0), seen(mesh.triangleCount(), 0);
    for (std::size_t i = 0; i < tree.nodes().size(); ++i)
    {
        const Tree::Node &node = tree.nodes()[i];
        const std::int32_t p = d.pieceOfNode[i];
        if (!node.isLeaf())
        {
            EXPECT_EQ(p, -1) << label << ": internal node " << i;
            continue;
        }
        EXPECT_TRUE(p >= 0 && std::size_t(p) < d.pieces.size()) << label << ": leaf " << i << " has no piece";
        if (p < 0 || std::size_t(p) >= d.pieces.size())
            continue;
        ++uses[std::size_t(p)];
        const ConvexPiece &piece = d.pieces[std::size_t(p)];
        ++c.byDimension[std::clamp(piece.dimension, 0, 3)];
        EXPECT_TRUE(std::isfinite(d.concavity[std::size_t(p)]) && d.concavity[std::size_t(p)] >= 0.0) << label;
        for (std::uint32_t t : leafTriangles(tree, node))
        {
            ++seen[t];
            for (int k = 0; k < 3; ++k)
            {
                const Vec3 &corner = mesh.corner(t, k);
                const double magnitude = std::max(corner.cwiseAbs().maxCoeff(), piece.magnitude());
                const double relative = piece.maxViolation(corner) / magnitude;
                c.worstRelativeViolation = std::max(c.worstRelativeViolation, relative);
                EXPECT_LE(relative, 1e-9) << label << ": corner " << k << " of triangle " << t
                                          << " outside its piece by " << piece.maxViolation(corner);
            }
        }
    }
    for (std::size_t p = 0; p < uses.size(); ++p)
        EXPECT_EQ(uses[p], 1) << label << ": piece " << p << " is used by " << uses[p] << " leaves";
    for (std::size_t t = 0; t < seen.size(); ++t)
        EXPECT_EQ(seen[t], 1) << label << ": triangle " << t << " is in " << seen[t] << " leaves";
    return c;
}

// ---------------------------------------------------------------------------------------------
// 2. Concavity against brute force.

struct ConcavityAgreement
{
    std::size_t pieces = 0, concavePieces = 0;
    double smallestRatio = std::numeric_limits<double>::infinity();   ///< reported / brute force, concave pieces
    double largestExcess = -std::numeric_limits<double>::infinity();  ///< reported - dense brute force
};

void checkConcavity(const TriangleMesh &mesh, unsigned leafSize, const std::string &label,
                    ConcavityAgreement &agreement, int uniformSamples = 2000)
{
    const Tree tree(std::make_shared<const TriangleMesh>(mesh), leafSize);
    const ConvexDecomposition d = decomposeLeaves(tree);
    TestRandom rng(99);
    for (std::size_t i = 0; i < tree.nodes().size(); ++i)
    {
        const Tree::Node &node = tree.nodes()[i];
        if (!node.isLeaf())
            continue;
        const std::size_t p = std::size_t(d.pieceOfNode[i]);
        const ConvexPiece &piece = d.pieces[p];
        const std::vector<std::uint32_t> triangles = leafTriangles(tree, node);
        const double reported = d.concavity[p];
        const double eps = 1e-9 * (1.0 + piece.magnitude());

        // Brute force: uniform samples on the hull's surface, then that set densified with a fine
        // grid on the library's own fans (which holds every point the library measured).
        double uniform = 0.0;
        for (const Vec3 &s : uniformSurfaceSamples(hullSurface(piece), uniformSamples, rng))
            uniform = std::max(uniform, distanceToTriangles(s, mesh, triangles));
        double dense = uniform;
        // Twice the library's density: a superset of the points it measured.
        for (const Vec3 &s : fanGridSamples(piece, 2 * concavitySamplesPerEdge(piece)))
            dense = std::max(dense, distanceToTriangles(s, mesh, triangles));

        ++agreement.pieces;
        agreement.largestExcess = std::max(agreement.largestExcess, reported - dense);
        // A maximum over points of the surface never exceeds the maximum over a superset of them.
        EXPECT_LE(reported, dense + eps) << label << ": piece " << p << " (" << triangles.size() << " triangles)";
        // Coarser sampling, but not wildly below: within a factor two of the brute force.
        EXPECT_GE(reported, 0.5 * uniform - eps)
            << label << ": piece " << p << " (" << triangles.size() << " triangles), dense brute force " << dense;
        if (uniform > eps)
        {
            ++agreement.concavePieces;
            agreement.smallestRatio = std::min(agreement.smallestRatio, reported / uniform);
        }
    }
}

void printConcavity(const std::string &label, const ConcavityAgreement &a)
{
    std::cout << "[ concavity ] " << label << ": " << a.pieces << " pieces, " << a.concavePieces
              << " concave, smallest reported/brute-force " << a.smallestRatio << ", largest reported - dense "
              << a.largestExcess << "\n";
}

// ---------------------------------------------------------------------------------------------
// 3. Approximate mode against brute force.

struct ModeCount
{
    std::size_t missed = 0;  ///< free here, colliding for brute force
    std::size_t extra = 0;   ///< colliding here, free for brute force
    double maxExtraDistance = 0.0;
};

CollisionScene sceneOf(TriangleMesh robot, TriangleMesh environment)
{
    CollisionScene s;
    s.robot = std::make_shared<const TriangleMesh>(std::move(robot));
    s.environment = std::make_shared<const TriangleMesh>(std::move(environment));
    return s;
}

void checkApproximateMode(const std::string &cfg, std::size_t poseCount)
{
    const auto start = std::chrono::steady_clock::now();
    const LoadedProblem problem = loadProblem(cfg);
    const std::string name = std::filesystem::path(cfg).filename().string();
    TestRandom rng(31);
    const auto poses = test::randomPoses(problem, poseCount, rng);
    const auto reference = makeChecker("bruteforce", problem.scene);
    std::vector<char> truth(poses.size());
    std::size_t colliding = 0;
    for (std::size_t i = 0; i < poses.size(); ++i)
        colliding += (truth[i] = reference->collides(poses[i])) ? 1 : 0;
    // Both outcomes well represented, or the comparison proves little.
    EXPECT_GT(colliding, poseCount / 10) << name;
    EXPECT_GT(poseCount - colliding, poseCount / 10) << name;

    // Distances of the extra contacts: the OBB tree's branch and bound (it equals brute force's
    // distance, which is O(triangle pairs) per pose and too slow for the larger meshes here).
    const auto distances = makeChecker("obb", problem.scene);
    const double scale =
        1.0 + problem.scene.environment->radiusAboutOrigin() + problem.scene.robot->radiusAboutOrigin();
    const auto run = [&](const CheckerOptions &options) {
        const auto checker = makeChecker("lp", problem.scene, options);
        ModeCount c;
        for (std::size_t i = 0; i < poses.size(); ++i)
        {
            const bool says = checker->collides(poses[i]);
            if (says == bool(truth[i]))
                continue;
            if (truth[i])
                ++c.missed;
            else
            {
                ++c.extra;
                c.maxExtraDistance = std::max(c.maxExtraDistance, distances->distance(poses[i]));
            }
        }
        return c;
    };

    // Exact mode: the LP only prunes, triangles decide, so the answers are the reference's.
    const ModeCount exact = run(CheckerOptions{});
    EXPECT_EQ(exact.missed, 0u) << name << " exact";
    EXPECT_EQ(exact.extra, 0u) << name << " exact";
    std::cout << "[ approx ] " << name << ": " << poseCount << " poses, " << colliding
              << " colliding; exact: " << exact.missed << " missed, " << exact.extra << " extra\n";

    // The pieces the LP checker builds (leaves of 8 triangles), to say how many decide alone.
    const ConvexDecomposition robotPieces = decomposeLeaves(Tree(problem.scene.robot, 8));
    const ConvexDecomposition environmentPieces = decomposeLeaves(Tree(problem.scene.environment, 8));
    const auto atMost = [](const ConvexDecomposition &d, double t) {
        return std::count_if(d.approximationBound.begin(), d.approximationBound.end(),
                             [t](double c) { return c <= t; });
    };

    // The last tolerance lets every piece decide alone: the plain convex-hull test, which must
    // still never miss a contact.
    for (const double tolerance : {0.0, 0.5, 5.0, 1e300})
    {
        CheckerOptions options;
        options.approximateTolerance = tolerance;
        const ModeCount c = run(options);
        // Never a missed contact: a piece pair's LP says intersecting whenever its triangles do.
        EXPECT_EQ(c.missed, 0u) << name << " T=" << tolerance;
        if (tolerance == 0.0)
        {
            // With T = 0 only single-triangle pieces (bound 0) decide alone, and for two triangles
            // the LP answer is the triangle test's.
            EXPECT_EQ(c.extra, 0u) << name << " T=0";
        }
        // Early contacts only within the tolerance.
        EXPECT_LE(c.maxExtraDistance, tolerance + 1e-9 * scale) << name << " T=" << tolerance;
        std::cout << "[ approx ] " << name << " T=" << tolerance << ": pieces deciding alone "
                  << atMost(robotPieces, tolerance) << "/" << robotPieces.pieces.size() << " robot, "
                  << atMost(environmentPieces, tolerance) << "/" << environmentPieces.pieces.size() << " environment; "
                  << c.missed << " missed, " << c.extra << " early contacts (max true distance " << c.maxExtraDistance
                  << ")\n";
    }
    std::cout << "[ approx ] " << name << ": "
              << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s\n";
}
}  // namespace

// --- 1. Coverage -------------------------------------------------------------------------------

TEST(ConvexDecomposition, CoversOmplappMeshes)
{
    HYBRIDCD_REQUIRE_OMPLAPP(cubicles, "3D/cubicles_env.dae");
    HYBRIDCD_REQUIRE_OMPLAPP(twisty, "3D/Twistycool_env.dae");
    HYBRIDCD_REQUIRE_OMPLAPP(alpha, "3D/alpha_env-1.5.dae");
    HYBRIDCD_REQUIRE_OMPLAPP(alphaRobot, "3D/alpha_robot.dae");
    for (const std::string &path : {cubicles, twisty, alpha, alphaRobot})
    {
        const TriangleMesh mesh = loadEnvironmentMesh(path);
        const std::string label = std::filesystem::path(path).filename().string();
        const Coverage c = checkCoverage(mesh, 8, label);
        std::cout << "[ coverage ] " << label << ": " << mesh.triangleCount() << " triangles, " << c.pieces
                  << " pieces, worst relative violation " << c.worstRelativeViolation << "\n";
    }
}

TEST(ConvexDecomposition, CoversRandomSoups)
{
    // Flat, sliver-thin and far-from-origin clusters at tiny, unit and huge scales, with leaves of
    // one triangle (flat pieces) up to sixteen.
    TestRandom rng(17);
    double worst = 0.0;
    std::size_t pieces = 0, byDimension[4] = {0, 0, 0, 0};
    for (const Soup kind : {Soup::Scattered, Soup::Surface, Soup::Flat, Soup::Thin})
        for (const double scale : {1e-6, 1.0, 1e6})
            for (const Vec3 &offset : {Vec3(0, 0, 0), Vec3(1e3, -2e3, 5e2)})
                for (const unsigned leaf : {1u, 3u, 8u, 16u})
                {
                    const TriangleMesh soup = randomSoup(kind, 150, scale, scale * offset, rng);
                    const Coverage c = checkCoverage(soup, leaf,
                                                     "soup " + std::to_string(int(kind)) + " scale " +
                                                         std::to_string(scale) + " leaf " + std::to_string(leaf));
                    worst = std::max(worst, c.worstRelativeViolation);
                    pieces += c.pieces;
                    for (int k = 0; k < 4; ++k)
                        byDimension[k] += c.byDimension[k];
                }
    std::cout << "[ coverage ] random soups: " << pieces << " pieces (" << byDimension[3] << " solid, "
              << byDimension[2] << " flat, " << byDimension[1] + byDimension[0] << " lower), worst relative violation "
              << worst << "\n";
    EXPECT_GT(byDimension[3], 0u);
    EXPECT_GT(byDimension[2], 0u);
}

// --- 2. Concavity ------------------------------------------------------------------------------

TEST(ConvexDecomposition, ConcavityMatchesBruteForceOnOmplappMeshes)
{
    HYBRIDCD_REQUIRE_OMPLAPP(cubiclesRobot, "3D/cubicles_robot.dae");
    HYBRIDCD_REQUIRE_OMPLAPP(cubicles, "3D/cubicles_env.dae");
    HYBRIDCD_REQUIRE_OMPLAPP(twistyRobot, "3D/Twistycool_robot.dae");
    HYBRIDCD_REQUIRE_OMPLAPP(twisty, "3D/Twistycool_env.dae");
    HYBRIDCD_REQUIRE_OMPLAPP(alphaRobot, "3D/alpha_robot.dae");
    HYBRIDCD_REQUIRE_OMPLAPP(alpha, "3D/alpha_env-1.5.dae");
    for (const std::string &path : {cubiclesRobot, cubicles, twistyRobot, twisty, alphaRobot, alpha})
    {
        ConcavityAgreement a;
        const std::string label = std::filesystem::path(path).filename().string();
        checkConcavity(loadEnvironmentMesh(path), 8, label, a);
        printConcavity(label, a);
    }
}

TEST(ConvexDecomposition, ConcavityMatchesBruteForceOnRandomSoups)
{
    TestRandom rng(23);
    for (const Soup kind : {Soup::Scattered, Soup::Surface, Soup::Flat})
    {
        ConcavityAgreement a;
        const std::string label = "soup " + std::to_string(int(kind));
        for (const double scale : {1e-3, 1.0, 1e3})
            checkConcavity(randomSoup(kind, 120, scale, Vec3(0, 0, 0), rng), 8, label, a);
        printConcavity(label, a);
    }
}

TEST(ConvexDecomposition, ConvexClosedPiecesHaveNoConcavity)
{
    // The triangles are the hull's whole surface: nothing stands out.
    TriangleMesh triangle;
    triangle.vertices = {Vec3(1, 2, 3), Vec3(4, -1, 2), Vec3(0.5, 0.25, -3)};
    triangle.triangles = {{0, 1, 2}};
    const TriangleMesh box = test::boxMesh(Vec3(-3, 1, 2), Vec3(7, 1.5, 40));
    TriangleMesh octahedron;
    octahedron.vertices = {Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(0, 1, 0), Vec3(0, -1, 0), Vec3(0, 0, 1), Vec3(0, 0, -1)};
    for (std::uint32_t x : {0u, 1u})
        for (std::uint32_t y : {2u, 3u})
            for (std::uint32_t z : {4u, 5u})
                octahedron.triangles.push_back({x, y, z});
    TriangleMesh quad;  // two coplanar triangles forming a convex quadrilateral: a flat piece
    quad.vertices = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(2, 1, 0), Vec3(0, 1, 0)};
    quad.triangles = {{0, 1, 2}, {0, 2, 3}};
    for (const auto &[label, mesh] : {std::pair<const char *, const TriangleMesh *>{"triangle", &triangle},
                                      {"box", &box},
                                      {"octahedron", &octahedron},
                                      {"quad", &quad}})
    {
        const Tree tree(std::make_shared<const TriangleMesh>(*mesh), 12);  // one leaf
        const ConvexDecomposition d = decomposeLeaves(tree);
        ASSERT_EQ(d.pieces.size(), 1u) << label;
        EXPECT_LE(d.concavity[0], 1e-9) << label;
        ConcavityAgreement a;
        checkConcavity(*mesh, 12, label, a);
    }
}

TEST(ConvexDecomposition, OpenBoxHasItsMissingFaceAsConcavity)
{
    // A unit cube without its top face: the top facet's centre is 0.5 from the side walls, and
    // that centre is one of the measured points, so the concavity is exactly 0.5.
    TriangleMesh openBox = test::boxMesh(Vec3(0, 0, 0), Vec3(1, 1, 1));
    openBox.triangles.erase(openBox.triangles.begin() + 2, openBox.triangles.begin() + 4);  // z = 1 face
    const Tree tree(std::make_shared<const TriangleMesh>(openBox), 12);
    const ConvexDecomposition d = decomposeLeaves(tree);
    ASSERT_EQ(d.pieces.size(), 1u);
    EXPECT_NEAR(d.concavity[0], 0.5, 1e-12);
    // A flat L shape (not convex): its hull's missing corner stands out of the triangles.
    TriangleMesh ell;
    ell.vertices = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(2, 1, 0), Vec3(1, 1, 0), Vec3(1, 2, 0), Vec3(0, 2, 0)};
    ell.triangles = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}};
    std::vector<std::uint32_t> all = {0, 1, 2, 3};
    std::vector<Vec3> corners = ell.vertices;
    const ConvexPiece hull = ConvexPiece::hullOf(corners);
    const double c = measureConcavity(hull, ell, all);
    // True value 0.5: the midpoint (1.5, 1.5) of the hull's edge (2,1)-(1,2), from the L's inner edges.
    EXPECT_GT(c, 0.1);
    EXPECT_LE(c, 0.5 + 1e-12);
    ConcavityAgreement a;
    checkConcavity(openBox, 12, "open box", a);
    checkConcavity(ell, 8, "L", a);
}

// --- 3. Approximate mode -----------------------------------------------------------------------

TEST(ConvexDecomposition, ApproximateModeIsConservativeCubicles)
{
    HYBRIDCD_REQUIRE_OMPLAPP(cfg, "3D/cubicles.cfg");
    checkApproximateMode(cfg, test::cases(3000));
}
TEST(ConvexDecomposition, ApproximateModeIsConservativeTwistycool)
{
    HYBRIDCD_REQUIRE_OMPLAPP(cfg, "3D/Twistycool.cfg");
    checkApproximateMode(cfg, test::cases(3000));
}
TEST(ConvexDecomposition, ApproximateModeIsConservativeAlpha15)
{
    HYBRIDCD_REQUIRE_OMPLAPP(cfg, "3D/alpha-1.5.cfg");
    checkApproximateMode(cfg, test::cases(3000));
}
TEST(ConvexDecomposition, ApproximateModeIsConservativeMazePlanar)
{
    HYBRIDCD_REQUIRE_OMPLAPP(cfg, "2D/Maze_planar.cfg");
    checkApproximateMode(cfg, test::cases(3000));
}

TEST(ConvexDecomposition, ApproximateModeInsideAnOpenHull)
{
    // Concavity measures only the hull's surface, yet a piece lying inside another's hull meets it:
    // the approximate mode must rely on a bound over the whole hull. A tetrahedron whose bottom face
    // is split at a T-junction (edge BC against BM and MC) has the whole tetrahedron as hull
    // (concavity 0) but is not edge-manifold closed, so it is no solid: a small robot deep inside
    // is free for brute force at distance 0.8, and approximate mode must not report contact there.
    TriangleMesh env;
    env.vertices = {Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(0, 4, 0), Vec3(0, 0, 4), Vec3(2, 2, 0)};
    env.triangles = {{0, 1, 4}, {0, 4, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
    TriangleMesh robot;
    robot.vertices = {Vec3(0, 0, 0), Vec3(0.1, 0, 0), Vec3(0, 0.1, 0), Vec3(0, 0, 0.1)};
    robot.triangles = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
    const CollisionScene scene = sceneOf(robot, env);
    const RigidTransform pose{Mat3::Identity(), Vec3(0.8, 0.8, 0.8)};
    const auto reference = makeChecker("bruteforce", scene);
    ASSERT_FALSE(reference->collides(pose));
    ASSERT_FALSE(makeChecker("lp", scene)->collides(pose));  // exact mode is right
    const double distance = reference->distance(pose);
    CheckerOptions options;
    options.approximateTolerance = 1e-6;
    const bool approximate = makeChecker("lp", scene, options)->collides(pose);
    EXPECT_FALSE(approximate && distance > *options.approximateTolerance)
        << "contact reported at true distance " << distance << " with T = " << *options.approximateTolerance;
}
