// SPDX-License-Identifier: BSD-3-Clause
// The direction of largest spread of a point set, for splitting hierarchy nodes.
#pragma once

#include "hybridcd/geometry/rigid_transform.h"

#include <cstddef>
#include <vector>

namespace hcd
{
/// The unit eigenvector of the points' covariance with the largest eigenvalue (the axis the OBB
/// tree splits along), or the x axis when the points do not define one. Volumes without an
/// orientation of their own (spheres, axis-aligned boxes, k-DOPs) split along it, so every tree
/// partitions triangles alike and the trees differ in their volumes only. Larger sets are
/// sampled: every principalAxisStride(points.size())-th point, from the first.
Vec3 principalAxis(const std::vector<Vec3> &points);

/// How many points principalAxis() samples at least before it strides over a larger set.
inline constexpr std::size_t kPrincipalAxisSamples = 4096;

/// The stride principalAxis() samples `count` points at (1: all of them), so that a caller that
/// gathers its points itself (a tree build) can gather only those.
inline std::size_t principalAxisStride(std::size_t count)
{
    return count > kPrincipalAxisSamples ? count / kPrincipalAxisSamples : 1;
}
}  // namespace hcd
