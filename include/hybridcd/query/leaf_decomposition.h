// SPDX-License-Identifier: BSD-3-Clause
// The LP checker's convex pieces: one per leaf of a volume tree (see narrowphase/convex_decomposition.h).
#pragma once

#include "hybridcd/bvh/volume_tree.h"
#include "hybridcd/narrowphase/convex_decomposition.h"

#include <vector>

namespace hcd
{
/// Hull of every leaf of `tree` (in node order) and its concavity; `pieceOfNode` maps tree nodes.
template <class Volume>
ConvexDecomposition decomposeLeaves(const VolumeTree<Volume> &tree)
{
    std::vector<TriangleCluster> leaves;
    for (std::size_t i = 0; i < tree.nodes().size(); ++i)
    {
        const auto &node = tree.nodes()[i];
        if (node.isLeaf())
            leaves.push_back({i, node.firstTriangle, node.triangleCount});
    }
    return decomposeClusters(tree.mesh(), tree.triangleOrder(), leaves, tree.nodes().size());
}
}  // namespace hcd
