// SPDX-License-Identifier: BSD-3-Clause
// Spheres on the medial axis of closed solids (the seed's section 3.2 and eq. 5): shrinking balls
// from surface points give approximate medial-axis points with their inscribed radii, and each node
// of a sphere tree is moved onto one of them, grown to cover the node's triangles.
#pragma once

#include "hybridcd/bvh/volume_tree.h"

#include <memory>
#include <optional>

namespace hcd
{
/// An approximate medial-axis point: `inner` is its exact distance to the mesh's surface, and the
/// ball of that radius lies inside a closed component of the mesh.
struct MedialPoint
{
    Vec3 center = Vec3::Zero();
    double inner = 0.0;
};

/// Shrinking-ball medial point for triangle `t` of `mesh`: the largest ball found that touches the
/// triangle's centroid, lies on its inner side and holds no surface point inside. Inner side and
/// containment are decided by `solids` (exact parity). Nullopt for a triangle of an open component,
/// or when the ball found is not inside a solid. Lengths in the mesh frame.
class MedialAxisSampler
{
public:
    explicit MedialAxisSampler(std::shared_ptr<const TriangleMesh> mesh);
    ~MedialAxisSampler();
    std::optional<MedialPoint> ofTriangle(std::uint32_t t) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// Moves every node of `tree` (built over `mesh`) onto the medial axis. Candidates are the medial
/// points of two triangles per leaf. A leaf takes the candidate whose covering radius less its
/// inscribed radius is least (its approximationBound()); an internal node takes the candidate with
/// the smallest covering radius among up to 16 of its subtree, or keeps its fitted sphere when that
/// is smaller. Every ball is grown to contain the node's triangle corners (plus 1e-9 of the
/// coordinates' magnitude for rounding), so the tree stays conservative. Nodes with no candidate
/// (open meshes: no solid to be inside) keep the sphere fitted to their corners, with inner 0: the
/// documented fallback, a sphere tree over surface samples. The time is added to the build time.
void placeOnMedialAxis(VolumeTree<MedialSphere> &tree, std::shared_ptr<const TriangleMesh> mesh);
}  // namespace hcd
