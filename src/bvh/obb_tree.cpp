// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/bvh/obb_tree.h"

#include <algorithm>
#include <chrono>
#include <numeric>

namespace hcd
{
ObbTree::ObbTree(std::shared_ptr<const TriangleMesh> mesh, unsigned maxLeafTriangles)
    : mesh_(std::move(mesh)), maxLeafTriangles_(std::max(1u, maxLeafTriangles))
{
    const auto start = std::chrono::steady_clock::now();
    const std::size_t n = mesh_->triangleCount();
    if (n == 0)
        return;
    order_.resize(n);
    std::iota(order_.begin(), order_.end(), 0u);
    centroids_.resize(n);
    for (std::size_t t = 0; t < n; ++t)
        centroids_[t] = (mesh_->corner(t, 0) + mesh_->corner(t, 1) + mesh_->corner(t, 2)) / 3.0;
    nodes_.reserve(2 * n);
    nodes_.emplace_back();
    std::vector<Vec3> scratch;
    build(0, 0, std::uint32_t(n), 1, scratch);
    centroids_.clear();
    centroids_.shrink_to_fit();
    buildSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void ObbTree::build(std::uint32_t node, std::uint32_t begin, std::uint32_t end, std::size_t level,
                    std::vector<Vec3> &scratch)
{
    depth_ = std::max(depth_, level);
    scratch.clear();
    for (std::uint32_t i = begin; i < end; ++i)
        for (int k = 0; k < 3; ++k)
            scratch.push_back(mesh_->corner(order_[i], k));
    nodes_[node].box = Obb::fit(scratch);
    nodes_[node].radius = nodes_[node].box.halfExtents.norm() * (1.0 + 1e-12);
    nodes_[node].firstTriangle = begin;
    nodes_[node].triangleCount = end - begin;
    if (end - begin <= maxLeafTriangles_)
        return;

    const Obb &box = nodes_[node].box;
    int longest = 0;
    box.halfExtents.maxCoeff(&longest);
    const Vec3 axis = box.axes.col(longest);
    double mean = 0.0;
    for (std::uint32_t i = begin; i < end; ++i)
        mean += axis.dot(centroids_[order_[i]]);
    mean /= double(end - begin);
    auto first = order_.begin() + begin, last = order_.begin() + end;
    auto middle = std::partition(first, last, [&](std::uint32_t t) { return axis.dot(centroids_[t]) < mean; });
    if (middle == first || middle == last)
    {
        middle = first + (end - begin) / 2;
        std::nth_element(first, middle, last, [&](std::uint32_t a, std::uint32_t b) {
            return axis.dot(centroids_[a]) < axis.dot(centroids_[b]);
        });
    }
    const std::uint32_t split = std::uint32_t(middle - order_.begin());
    const std::uint32_t left = std::uint32_t(nodes_.size());
    nodes_[node].firstChild = std::int32_t(left);
    nodes_.emplace_back();
    nodes_.emplace_back();
    build(left, begin, split, level + 1, scratch);
    build(left + 1, split, end, level + 1, scratch);
}

std::size_t ObbTree::memoryBytes() const
{
    return nodes_.capacity() * sizeof(Node) + order_.capacity() * sizeof(std::uint32_t);
}
}  // namespace hcd
