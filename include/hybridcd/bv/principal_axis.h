// SPDX-License-Identifier: BSD-3-Clause
// The direction of largest spread of a point set, for splitting hierarchy nodes.
#pragma once

#include "hybridcd/geometry/rigid_transform.h"

#include <vector>

namespace hcd
{
/// The unit eigenvector of the points' covariance with the largest eigenvalue (the axis the OBB
/// tree splits along), or the x axis when the points do not define one. Volumes without an
/// orientation of their own (spheres, axis-aligned boxes, k-DOPs) split along it, so every tree
/// partitions triangles alike and the trees differ in their volumes only. Sets of more than 4096
/// points are sampled at a regular stride (at least 4096 of them).
Vec3 principalAxis(const std::vector<Vec3> &points);
}  // namespace hcd
