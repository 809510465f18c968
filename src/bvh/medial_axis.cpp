// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/bvh/medial_axis.h"

#include "hybridcd/geometry/solid_components.h"
#include "hybridcd/geometry/triangle_distance.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace hcd
{
struct MedialAxisSampler::Impl
{
    std::shared_ptr<const TriangleMesh> mesh;
    SolidQuery solids;
    VolumeTree<Aabb> boxes;                 ///< for nearest-surface-point queries
    std::vector<std::int32_t> componentOf;  ///< per triangle: its component if closed, else -1
    std::vector<double> componentDiagonal;  ///< per component: its bounding-box diagonal

    explicit Impl(std::shared_ptr<const TriangleMesh> m)
        : mesh(m),
          solids(m),
          boxes(m, 4),
          componentOf(m->triangleCount(), -1)
    {
        const auto &components = solids.components();
        for (std::size_t c = 0; c < components.size(); ++c)
        {
            componentDiagonal.push_back(
                components[c].bounds.empty() ? 0.0 : (components[c].bounds.max - components[c].bounds.min).norm());
            if (components[c].closed)
                for (std::uint32_t t : components[c].triangles)
                    componentOf[t] = std::int32_t(c);
        }
    }

    // The surface point nearest to p (branch and bound over the box tree), and its distance.
    std::pair<Vec3, double> nearest(const Vec3 &p) const
    {
        const auto &nodes = boxes.nodes();
        double best = std::numeric_limits<double>::infinity();
        Vec3 bestPoint = p;
        std::vector<std::uint32_t> stack{0};
        const auto gap = [&](std::uint32_t n) {
            const Aabb &b = nodes[n].volume;
            return ((p - b.center).cwiseAbs() - b.halfExtents).cwiseMax(0.0).norm();
        };
        while (!stack.empty())
        {
            const std::uint32_t n = stack.back();
            stack.pop_back();
            if (gap(n) >= best)
                continue;
            const auto &node = nodes[n];
            if (node.isLeaf())
            {
                for (std::uint32_t k = 0; k < node.triangleCount; ++k)
                {
                    const std::uint32_t t = boxes.triangleOrder()[node.firstTriangle + k];
                    const Vec3 q =
                        closestPointOnTriangle(p, mesh->corner(t, 0), mesh->corner(t, 1), mesh->corner(t, 2));
                    const double d = (q - p).norm();
                    if (d < best)
                    {
                        best = d;
                        bestPoint = q;
                    }
                }
                continue;
            }
            const std::uint32_t a = std::uint32_t(node.firstChild), b = a + 1;
            // Nearer child last, so it is popped first.
            if (gap(a) < gap(b))
            {
                stack.push_back(b);
                stack.push_back(a);
            }
            else
            {
                stack.push_back(a);
                stack.push_back(b);
            }
        }
        return {bestPoint, best};
    }
};

MedialAxisSampler::MedialAxisSampler(std::shared_ptr<const TriangleMesh> mesh)
    : impl_(std::make_unique<Impl>(std::move(mesh)))
{
}

MedialAxisSampler::~MedialAxisSampler() = default;

std::optional<MedialPoint> MedialAxisSampler::ofTriangle(std::uint32_t t) const
{
    const Impl &m = *impl_;
    const std::int32_t component = m.componentOf[t];
    if (component < 0)
        return std::nullopt;
    const Vec3 &a = m.mesh->corner(t, 0), &b = m.mesh->corner(t, 1), &c = m.mesh->corner(t, 2);
    const Vec3 p = (a + b + c) / 3.0;
    const Vec3 cross = (b - a).cross(c - a);
    if (!(cross.norm() > 0.0))
        return std::nullopt;
    const double size = m.componentDiagonal[std::size_t(component)];
    // Which side is inside: orientation may be inconsistent, so ask the solid (exact parity).
    const Vec3 n = cross.normalized();
    const double step = 1e-7 * size;
    Vec3 d;
    if (m.solids.insideComponent(std::size_t(component), p - step * n) &&
        !m.solids.insideComponent(std::size_t(component), p + step * n))
        d = -n;
    else if (m.solids.insideComponent(std::size_t(component), p + step * n) &&
             !m.solids.insideComponent(std::size_t(component), p - step * n))
        d = n;
    else
        return std::nullopt;
    // Shrinking ball (Ma, Bae and Choi): the ball touching p with centre p + r d shrinks to pass
    // through the surface point nearest its centre until no surface point is nearer than r.
    double r = size;
    for (int i = 0; i < 100; ++i)
    {
        const auto [q, distance] = m.nearest(p + r * d);
        if (distance >= r * (1.0 - 1e-9))
            break;
        const double along = 2.0 * d.dot(q - p);
        if (!(along > 0.0))
            break;
        const double shrunk = (q - p).squaredNorm() / along;
        if (!(shrunk < r) || shrunk < 1e-9 * size)
        {
            r = std::min(r, shrunk);
            break;
        }
        r = shrunk;
    }
    const Vec3 center = p + r * d;
    // The inscribed radius is the exact distance to the surface, whatever the iteration reached;
    // the centre must be inside the solid for the ball to be.
    const double inner = m.nearest(center).second;
    if (!(inner > 1e-9 * size) || !m.solids.insideComponent(std::size_t(component), center))
        return std::nullopt;
    return MedialPoint{center, inner};
}

namespace
{
// The ball about `center` holding every corner, grown for rounding.
double coveringRadius(const Vec3 &center, const std::vector<Vec3> &corners)
{
    double farthest = 0.0, magnitude = center.cwiseAbs().maxCoeff();
    for (const Vec3 &p : corners)
    {
        farthest = std::max(farthest, (p - center).squaredNorm());
        magnitude = std::max(magnitude, p.cwiseAbs().maxCoeff());
    }
    return std::sqrt(farthest) * (1.0 + 1e-12) + 1e-9 * magnitude;
}
}  // namespace

void placeOnMedialAxis(VolumeTree<MedialSphere> &tree, std::shared_ptr<const TriangleMesh> mesh)
{
    if (tree.empty())
        return;
    const auto start = std::chrono::steady_clock::now();
    const MedialAxisSampler sampler(mesh);
    // Candidates by position in the tree's triangle order: two triangles per leaf.
    std::vector<std::pair<std::uint32_t, MedialPoint>> candidates;
    for (const auto &node : tree.nodes())
    {
        if (!node.isLeaf())
            continue;
        for (std::uint32_t k : {0u, node.triangleCount / 2})
        {
            const std::uint32_t position = node.firstTriangle + k;
            if (!candidates.empty() && candidates.back().first == position)
                continue;  // a one-triangle leaf names its triangle twice
            if (const auto point = sampler.ofTriangle(tree.triangleOrder()[position]))
                candidates.push_back({position, *point});
        }
    }
    std::sort(candidates.begin(), candidates.end(), [](const auto &x, const auto &y) { return x.first < y.first; });
    candidates.erase(std::unique(candidates.begin(), candidates.end(),
                                 [](const auto &x, const auto &y) { return x.first == y.first; }),
                     candidates.end());

    const auto &nodes = tree.nodes();
    tree.refitVolumes([&](std::size_t index, const std::vector<Vec3> &corners) {
        const auto &node = nodes[index];
        MedialSphere best = node.volume;  // the fitted sphere, inner 0
        const auto first = std::lower_bound(candidates.begin(), candidates.end(), node.firstTriangle,
                                            [](const auto &c, std::uint32_t p) { return c.first < p; });
        const auto last =
            std::lower_bound(candidates.begin(), candidates.end(), node.firstTriangle + node.triangleCount,
                             [](const auto &c, std::uint32_t p) { return c.first < p; });
        const std::size_t count = std::size_t(last - first);
        if (count == 0)
            return best;
        const std::size_t step = std::max<std::size_t>(1, count / 16);
        bool chosen = false;
        for (std::size_t i = 0; i < count; i += step)
        {
            const MedialPoint &m = (first + std::ptrdiff_t(i))->second;
            const MedialSphere s{{m.center, coveringRadius(m.center, corners)}, m.inner};
            // Leaves: the least approximation bound; internal nodes: the smallest ball.
            const bool better = node.isLeaf() ? (!chosen || s.approximationBound() < best.approximationBound())
                                              : s.ball.radius < best.ball.radius;
            if (better)
            {
                best = s;
                chosen = true;
            }
        }
        return best;
    });
    tree.addBuildSeconds(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}
}  // namespace hcd
