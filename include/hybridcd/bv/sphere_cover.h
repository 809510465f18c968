// SPDX-License-Identifier: BSD-3-Clause
// A small sphere tree whose every level holds the whole surface of a mesh: the robot as a first
// layer sees it (a cheap test against a clearance grid before any hierarchy).
#pragma once

#include "hybridcd/geometry/triangle_mesh.h"

#include <vector>

namespace hcd
{
/// One sphere of a cover tree, in the mesh's own frame.
struct CoverSphere
{
    Vec3 center = Vec3::Zero();
    double radius = 0.0;        ///< holds every point of its part of the surface, rounded outward
    Vec3 probe = Vec3::Zero();  ///< a vertex of the mesh inside this sphere (a point of the surface)
    int firstChild = -1;        ///< children at firstChild and firstChild + 1; -1 for a leaf
};

/// A binary tree of spheres, root first, whose leaves (at most `maxLeaves`) together hold every
/// point of every triangle of `mesh`, and each inner sphere every point its children hold. Large
/// triangles are cut (midpoint subdivision, the same point set) into pieces no longer than an
/// eighth of the mesh's size, so that spheres can shrink below a triangle; pieces are split at the
/// median centroid along the widest axis. Empty for an empty mesh.
std::vector<CoverSphere> sphereCover(const TriangleMesh &mesh, std::size_t maxLeaves);
}  // namespace hcd
