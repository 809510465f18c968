// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/bvh/volume_traits.h"

#include <cmath>

namespace hcd
{
void appendMappedSphere(ExportMesh &mesh, const Vec3 &center, const Mat3 &linear)
{
    // 16 x 8 UV sphere: enough to see an envelope's shape.
    constexpr int kSlices = 16, kStacks = 8;
    const std::size_t base = mesh.vertices.size();
    for (int i = 0; i <= kStacks; ++i)
    {
        const double phi = M_PI * i / kStacks;
        for (int j = 0; j < kSlices; ++j)
        {
            const double theta = 2.0 * M_PI * j / kSlices;
            mesh.vertices.push_back(center + linear * Vec3(std::sin(phi) * std::cos(theta),
                                                           std::sin(phi) * std::sin(theta), std::cos(phi)));
        }
    }
    for (int i = 0; i < kStacks; ++i)
        for (int j = 0; j < kSlices; ++j)
        {
            const std::size_t a = base + std::size_t(i * kSlices + j),
                              b = base + std::size_t(i * kSlices + (j + 1) % kSlices);
            const std::size_t c = a + kSlices, d = b + kSlices;
            if (i > 0)
                mesh.triangles.push_back({a, b, d});
            if (i + 1 < kStacks)
                mesh.triangles.push_back({a, d, c});
        }
}

void appendMappedCube(ExportMesh &mesh, const Vec3 &center, const Mat3 &linear)
{
    const std::size_t base = mesh.vertices.size();
    for (int i = 0; i < 8; ++i)
        mesh.vertices.push_back(center + linear * Vec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1));
    const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto &f : faces)
    {
        mesh.triangles.push_back({base + std::size_t(f[0]), base + std::size_t(f[1]), base + std::size_t(f[2])});
        mesh.triangles.push_back({base + std::size_t(f[0]), base + std::size_t(f[2]), base + std::size_t(f[3])});
    }
}

void appendPolygons(ExportMesh &mesh, const std::vector<std::vector<Vec3>> &polygons)
{
    for (const auto &polygon : polygons)
    {
        const std::size_t base = mesh.vertices.size();
        mesh.vertices.insert(mesh.vertices.end(), polygon.begin(), polygon.end());
        for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
            mesh.triangles.push_back({base, base + k, base + k + 1});
    }
}
}  // namespace hcd
