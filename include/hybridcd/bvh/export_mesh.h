// SPDX-License-Identifier: BSD-3-Clause
// Bounding volumes as plain triangle meshes, to look at (inspect --export, render --level).
#pragma once

#include "hybridcd/geometry/rigid_transform.h"

#include <array>
#include <cstddef>
#include <vector>

namespace hcd
{
/// Vertices and triangles (0-based) to which volumes are appended for export.
struct ExportMesh
{
    std::vector<Vec3> vertices;
    std::vector<std::array<std::size_t, 3>> triangles;
};
}  // namespace hcd
