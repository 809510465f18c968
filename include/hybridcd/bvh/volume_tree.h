// SPDX-License-Identifier: BSD-3-Clause
// A binary bounding-volume hierarchy over the triangles of one mesh, for any volume type.
//
// Build: top-down. Each node's volume is fitted to the corners of its triangles (VolumeTraits<V>::fit),
// or, for k-DOPs, bottom-up: tight slabs at the leaves, each parent the union of its children's,
// and fit()'s margin added last, which gives the same volumes without revisiting the corners.
// The node's triangles are split across the volume's split axis (its longest direction, or the
// principal axis of the corners for volumes without one) at the mean
// of their centroids (Gottschalk's rule); if every centroid lands on one side, at the median
// instead. Boxes (OBBs, AABBs) weigh that split against planes across the box's own three axes,
// at the mean and at even steps between the extreme centroids, by the surface area heuristic, and
// take the cheapest (the other volumes, the hybrid and C-tree ones included, keep Gottschalk's
// rule). Nodes are stored in one array with the two children of a node adjacent; leaves hold a run
// of the tree's reordered triangle list. The same code builds every tree, so they differ only in
// their volumes and in that choice.
#pragma once

#include "hybridcd/bv/principal_axis.h"
#include "hybridcd/bvh/volume_traits.h"
#include "hybridcd/geometry/triangle_mesh.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <numeric>
#include <type_traits>
#include <utility>

namespace hcd
{
template <class Volume>
class VolumeTree
{
public:
    using Traits = VolumeTraits<Volume>;

    struct Node
    {
        Volume volume;
        double radius = 0.0;           ///< circumscribed sphere about Traits::center(volume), for a cheap first reject
        std::int32_t firstChild = -1;  ///< index of the left child (right = +1), -1 for a leaf
        std::uint32_t firstTriangle = 0;  ///< first index into triangleOrder() of the subtree's run
        std::uint32_t triangleCount = 0;

        bool isLeaf() const { return firstChild < 0; }
    };

    /// Builds over `mesh` (kept alive by the tree). Leaves hold at most `maxLeafTriangles`.
    explicit VolumeTree(std::shared_ptr<const TriangleMesh> mesh, unsigned maxLeafTriangles = 1)
        : mesh_(std::move(mesh)),
          maxLeafTriangles_(std::max(1u, maxLeafTriangles))
    {
        const auto start = std::chrono::steady_clock::now();
        const std::size_t n = mesh_->triangleCount();
        if (n == 0)
            return;
        order_.resize(n);
        std::iota(order_.begin(), order_.end(), 0u);
        std::vector<Vec3> centroids(n);
        for (std::size_t t = 0; t < n; ++t)
            centroids[t] = (mesh_->corner(t, 0) + mesh_->corner(t, 1) + mesh_->corner(t, 2)) / 3.0;
        nodes_.reserve(2 * n);
        nodes_.emplace_back();
        std::vector<Vec3> scratch, local;
        build(0, 0, std::uint32_t(n), 1, centroids, scratch, local);
        if constexpr (kMergeable)
            for (Node &node : nodes_)
            {
                node.volume = Traits::withMargin(node.volume);
                node.radius = Traits::radius(node.volume);
            }
        buildSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }

    const TriangleMesh &mesh() const { return *mesh_; }
    const std::vector<Node> &nodes() const { return nodes_; }
    bool empty() const { return nodes_.empty(); }
    /// Mesh triangle indices in leaf order.
    const std::vector<std::uint32_t> &triangleOrder() const { return order_; }
    std::size_t depth() const { return depth_; }
    double buildSeconds() const { return buildSeconds_; }
    /// Counts later work on the volumes (refitVolumes) as part of the build.
    void addBuildSeconds(double seconds) { buildSeconds_ += seconds; }
    std::size_t memoryBytes() const
    {
        return nodes_.capacity() * sizeof(Node) + order_.capacity() * sizeof(std::uint32_t);
    }

    /// Replaces every node's volume by `refit(node index, corners of the node's triangles)`, which
    /// must contain those corners (volumes placed by more than their content: bvh/medial_axis.h).
    template <class Refit>
    void refitVolumes(Refit &&refit)
    {
        std::vector<Vec3> corners;
        for (std::size_t i = 0; i < nodes_.size(); ++i)
        {
            Node &n = nodes_[i];
            corners.clear();
            for (std::uint32_t k = 0; k < n.triangleCount; ++k)
                for (int c = 0; c < 3; ++c)
                    corners.push_back(mesh_->corner(order_[n.firstTriangle + k], c));
            n.volume = refit(i, corners);
            n.radius = Traits::radius(n.volume);
        }
    }

private:
    void build(std::uint32_t node, std::uint32_t begin, std::uint32_t end, std::size_t level,
               const std::vector<Vec3> &centroids, std::vector<Vec3> &scratch, std::vector<Vec3> &local)
    {
        depth_ = std::max(depth_, level);
        Node &self = nodes_[node];
        self.firstTriangle = begin;
        self.triangleCount = end - begin;
        const bool leaf = end - begin <= maxLeafTriangles_;
        Vec3 axis;
        bool hasCut = false;
        double cut = 0.0;
        if constexpr (kMergeable)
        {
            // Inner nodes are merged from their children below, so only leaves visit their
            // corners; the split axis needs the same regular sample principalAxis() would take.
            if (leaf)
            {
                gatherCorners(begin, end, 1, scratch);
                self.volume = Traits::tight(scratch);  // margins and radii once the tree is built
                return;
            }
            gatherCorners(begin, end, principalAxisStride(3 * std::size_t(end - begin)), scratch);
            axis = principalAxis(scratch);
        }
        else
        {
            gatherCorners(begin, end, 1, scratch);
            self.volume = Traits::fit(scratch);
            self.radius = Traits::radius(self.volume);
            if (leaf)
                return;
            axis = Traits::splitAxis(self.volume, scratch);
            if constexpr (HasSplitFrame<Traits>::value)
            {
                const SplitPlane plane = surfaceAreaSplit(Traits::splitFrame(self.volume), axis, scratch, local);
                axis = plane.axis;
                hasCut = plane.hasCut;
                cut = plane.cut;
            }
        }

        if (!hasCut)
        {
            cut = 0.0;  // the mean centroid
            for (std::uint32_t i = begin; i < end; ++i)
                cut += axis.dot(centroids[order_[i]]);
            cut /= double(end - begin);
        }
        auto first = order_.begin() + begin, last = order_.begin() + end;
        auto middle = std::partition(first, last, [&](std::uint32_t t) { return axis.dot(centroids[t]) < cut; });
        if (middle == first || middle == last)
        {
            middle = first + (end - begin) / 2;
            std::nth_element(first, middle, last, [&](std::uint32_t a, std::uint32_t b) {
                return axis.dot(centroids[a]) < axis.dot(centroids[b]);
            });
        }
        const std::uint32_t split = std::uint32_t(middle - order_.begin());
        const std::uint32_t left = std::uint32_t(nodes_.size());
        nodes_[node].firstChild = std::int32_t(left);  // `self` may dangle after the emplace below
        nodes_.emplace_back();
        nodes_.emplace_back();
        build(left, begin, split, level + 1, centroids, scratch, local);
        build(left + 1, split, end, level + 1, centroids, scratch, local);
        if constexpr (kMergeable)
            nodes_[node].volume = Traits::tightUnion(nodes_[left].volume, nodes_[left + 1].volume);
    }

    // Where a box node splits: along `axis` (world), its triangles with axis . centroid < cut on one
    // side; without a cut, at the mean centroid.
    struct SplitPlane
    {
        Vec3 axis;
        bool hasCut = false;
        double cut = 0.0;
    };

    // A child's part of a split's cost: its box's surface area (half of it) times its triangle count.
    static double childCost(const Vec3 &lo, const Vec3 &hi, double count)
    {
        const Vec3 e = hi - lo;
        return (e.x() * e.y() + e.y() * e.z() + e.z() * e.x()) * count;
    }

    // The surface area heuristic (a pair test reaches a child about as often as its surface is met,
    // and then costs about its triangle count): of the planes across the frame's three axes and
    // `fallback` (world directions) at the mean centroid and at kSplitBins - 1 even steps between
    // the extreme centroids, the one whose children have the smallest box surface area times
    // triangle count, boxes measured along the frame's axes. `corners` holds the node's triangles'
    // corners, three per triangle; `local` is scratch. Nodes of 2 * kSplitSample triangles or more
    // are judged on one triangle in every triangles / kSplitSample (1,024 to 2,047 of them).
    // Measured in bench/README.md (section 1, "Clearance").
    SplitPlane surfaceAreaSplit(const Mat3 &frame, const Vec3 &fallback, const std::vector<Vec3> &corners,
                                std::vector<Vec3> &local) const
    {
        constexpr std::size_t kSplitSample = 1024;
        constexpr int kSplitBins = 8;
        constexpr double kInfinity = std::numeric_limits<double>::infinity();
        const std::size_t triangles = corners.size() / 3;
        const std::size_t stride = std::max<std::size_t>(1, triangles / kSplitSample);
        // Per sampled triangle, in frame coordinates: its box and three times its centroid.
        local.clear();
        Vec3 sum = Vec3::Zero();
        for (std::size_t t = 0; t < triangles; t += stride)
        {
            const Vec3 q0 = frame.transpose() * corners[3 * t], q1 = frame.transpose() * corners[3 * t + 1],
                       q2 = frame.transpose() * corners[3 * t + 2];
            local.push_back(q0.cwiseMin(q1).cwiseMin(q2));
            local.push_back(q0.cwiseMax(q1).cwiseMax(q2));
            local.push_back(q0 + q1 + q2);
            sum += local.back();
        }
        const std::size_t sampled = local.size() / 3;
        const Vec3 mean3 = sum / double(sampled);
        // The fallback in frame coordinates; an OBB's is one of its own axes, measured once.
        const Vec3 own = frame.transpose() * fallback;
        const bool fallbackIsAnAxis = (own.cwiseAbs().array() > 1.0 - 1e-12).any();
        const std::array<Vec3, 4> candidates{own, Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
        SplitPlane best{fallback};
        double bestCost = kInfinity;
        for (std::size_t c = fallbackIsAnAxis ? 1 : 0; c < candidates.size(); ++c)
        {
            const Vec3 &d = candidates[c];  // frame coordinates
            const Vec3 axis = c == 0 ? fallback : Vec3(frame.col(Eigen::Index(c - 1)));
            // At the mean: the rule the node falls back on.
            const double mean = d.dot(mean3);
            Vec3 lo[2] = {Vec3::Constant(kInfinity), Vec3::Constant(kInfinity)};
            Vec3 hi[2] = {Vec3::Constant(-kInfinity), Vec3::Constant(-kInfinity)};
            double count[2] = {0.0, 0.0};
            double lowest = kInfinity, highest = -kInfinity;
            for (std::size_t t = 0; t < sampled; ++t)
            {
                const double p = d.dot(local[3 * t + 2]);
                lowest = std::min(lowest, p);
                highest = std::max(highest, p);
                const int side = p < mean ? 0 : 1;
                count[side] += 1.0;
                lo[side] = lo[side].cwiseMin(local[3 * t]);
                hi[side] = hi[side].cwiseMax(local[3 * t + 1]);
            }
            if (count[0] > 0.0 && count[1] > 0.0)
            {
                const double cost = childCost(lo[0], hi[0], count[0]) + childCost(lo[1], hi[1], count[1]);
                if (cost < bestCost)
                {
                    bestCost = cost;
                    best = {axis};
                }
            }
            if (!(highest > lowest))
                continue;  // every centroid at one place along this axis
            // Even steps: bins of centroids, then each plane between bins from both ends.
            std::array<Vec3, kSplitBins> binLo, binHi;
            std::array<double, kSplitBins> binCount{};
            binLo.fill(Vec3::Constant(kInfinity));
            binHi.fill(Vec3::Constant(-kInfinity));
            const double perBin = kSplitBins / (highest - lowest);
            if (!(perBin > 0.0) || !std::isfinite(perBin))
                continue;  // a spread too small or too large to divide: the planes at the mean decide
            for (std::size_t t = 0; t < sampled; ++t)
            {
                // Clamped before the conversion, so that no value (NaN included) leaves the bins.
                const double at = (d.dot(local[3 * t + 2]) - lowest) * perBin;
                const int b = at >= kSplitBins - 1 ? kSplitBins - 1 : at > 0.0 ? int(at) : 0;
                binCount[std::size_t(b)] += 1.0;
                binLo[std::size_t(b)] = binLo[std::size_t(b)].cwiseMin(local[3 * t]);
                binHi[std::size_t(b)] = binHi[std::size_t(b)].cwiseMax(local[3 * t + 1]);
            }
            // Above each plane b (between bins b - 1 and b): box and count.
            std::array<Vec3, kSplitBins> aboveLo, aboveHi;
            std::array<double, kSplitBins> aboveCount{};
            Vec3 runLo = Vec3::Constant(kInfinity), runHi = Vec3::Constant(-kInfinity);
            double runCount = 0.0;
            for (int b = kSplitBins - 1; b > 0; --b)
            {
                runLo = runLo.cwiseMin(binLo[std::size_t(b)]);
                runHi = runHi.cwiseMax(binHi[std::size_t(b)]);
                runCount += binCount[std::size_t(b)];
                aboveLo[std::size_t(b)] = runLo;
                aboveHi[std::size_t(b)] = runHi;
                aboveCount[std::size_t(b)] = runCount;
            }
            runLo = Vec3::Constant(kInfinity);
            runHi = Vec3::Constant(-kInfinity);
            runCount = 0.0;
            for (int b = 1; b < kSplitBins; ++b)
            {
                runLo = runLo.cwiseMin(binLo[std::size_t(b - 1)]);
                runHi = runHi.cwiseMax(binHi[std::size_t(b - 1)]);
                runCount += binCount[std::size_t(b - 1)];
                if (runCount == 0.0 || aboveCount[std::size_t(b)] == 0.0)
                    continue;
                const double cost =
                    childCost(runLo, runHi, runCount) +
                    childCost(aboveLo[std::size_t(b)], aboveHi[std::size_t(b)], aboveCount[std::size_t(b)]);
                if (cost < bestCost)
                {
                    bestCost = cost;
                    // Back to world units: the projections are three times the centroids'.
                    best = {axis, true, (lowest + b / perBin) / 3.0};
                }
            }
        }
        return best;
    }

    // Every `stride`-th corner of the triangles order_[begin, end), in order.
    void gatherCorners(std::uint32_t begin, std::uint32_t end, std::size_t stride, std::vector<Vec3> &out) const
    {
        out.clear();
        const std::size_t corners = 3 * std::size_t(end - begin);
        for (std::size_t i = 0; i < corners; i += stride)
            out.push_back(mesh_->corner(order_[begin + i / 3], int(i % 3)));
    }

    // Volumes whose splits are chosen by surface area, among the axes of VolumeTraits::splitFrame.
    template <class T, class = void>
    struct HasSplitFrame : std::false_type
    {
    };
    template <class T>
    struct HasSplitFrame<T, std::void_t<decltype(T::splitFrame(std::declval<const Volume &>()))>> : std::true_type
    {
    };

    // Volumes whose parent is the union of its children's (k-DOPs: tight slabs, a margin last);
    // they split along the corners' principal axis, as their splitAxis() does.
    template <class T, class = void>
    struct HasTightUnion : std::false_type
    {
    };
    template <class T>
    struct HasTightUnion<
        T, std::void_t<decltype(T::tightUnion(std::declval<const Volume &>(), std::declval<const Volume &>()))>>
        : std::true_type
    {
    };
    static constexpr bool kMergeable = HasTightUnion<Traits>::value;

    std::shared_ptr<const TriangleMesh> mesh_;
    unsigned maxLeafTriangles_;
    std::vector<Node> nodes_;
    std::vector<std::uint32_t> order_;
    std::size_t depth_ = 0;
    double buildSeconds_ = 0.0;
};
}  // namespace hcd
