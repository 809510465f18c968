// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/render/raster_layer.h"

#include <algorithm>
#include <cmath>

namespace hcd::render
{
namespace
{
constexpr double kEmpty = std::numeric_limits<double>::infinity();

// Twice the signed area of (a, b, p) in pixel coordinates.
double edge(const Vec3 &a, const Vec3 &b, double px, double py)
{
    return (b.x() - a.x()) * (py - a.y()) - (b.y() - a.y()) * (px - a.x());
}

// floor(v) and ceil(v) as pixel indices, clamped to [-1, limit + 1] first so that no far-away or
// huge coordinate overflows the conversion to int.
int floorIndex(double v, int limit) { return int(std::floor(std::clamp(v, -1.0, double(limit) + 1.0))); }
int ceilIndex(double v, int limit) { return int(std::ceil(std::clamp(v, -1.0, double(limit) + 1.0))); }

// Top-left fill rule, so that pixels on an edge shared by two triangles are drawn once.
bool isTopLeft(const Vec3 &a, const Vec3 &b, bool counterClockwise)
{
    const double dx = b.x() - a.x(), dy = b.y() - a.y();
    // In pixel coordinates (y down) with positive area, a top edge is horizontal going right and a
    // left edge goes up; flip for the other winding.
    const bool top = dy == 0.0 && (counterClockwise ? dx < 0.0 : dx > 0.0);
    const bool left = counterClockwise ? dy > 0.0 : dy < 0.0;
    return top || left;
}
}  // namespace

double flatShade(const Camera &camera, const Vec3 &normal)
{
    const Vec3 light = (-camera.forward() + 0.6 * camera.up() - 0.35 * camera.right()).normalized();
    return 0.3 + 0.7 * std::abs(normal.dot(light));
}

RasterLayer::RasterLayer(int width, int height)
    : width_(width),
      height_(height),
      depth_(std::size_t(width) * std::size_t(height), kEmpty),
      colour_(std::size_t(width) * std::size_t(height))
{
}

void RasterLayer::touch(int x0, int y0, int x1, int y1)
{
    if (touched_.empty())
        touched_ = {x0, y0, x1, y1};
    else
        touched_ = {std::min(touched_.x0, x0), std::min(touched_.y0, y0), std::max(touched_.x1, x1),
                    std::max(touched_.y1, y1)};
}

void RasterLayer::clear()
{
    for (int y = touched_.y0; y < touched_.y1; ++y)
        std::fill(depth_.begin() + std::ptrdiff_t(index(touched_.x0, y)),
                  depth_.begin() + std::ptrdiff_t(index(touched_.x1, y)), kEmpty);
    touched_ = {};
}

void RasterLayer::drawMesh(const Camera &camera, const TriangleMesh &mesh, const RigidTransform &worldFromMesh,
                           const Rgb &colour)
{
    std::vector<Vec3> world(mesh.vertices.size()), screen(mesh.vertices.size());
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
    {
        world[i] = worldFromMesh.apply(mesh.vertices[i]);
        screen[i] = camera.project(world[i]);
    }
    for (const TriangleMesh::Triangle &t : mesh.triangles)
    {
        const Vec3 &a = screen[t[0]], &b = screen[t[1]], &c = screen[t[2]];
        if (!a.allFinite() || !b.allFinite() || !c.allFinite())
            continue;
        const double area = edge(a, b, c.x(), c.y());
        if (area == 0.0)
            continue;  // seen edge-on
        const Vec3 normal = (world[t[1]] - world[t[0]]).cross(world[t[2]] - world[t[0]]);
        const double norm = normal.norm();
        if (!(norm > 0.0))
            continue;
        const double shade = flatShade(camera, normal / norm);
        const Rgb shaded{colour.r * shade, colour.g * shade, colour.b * shade};

        // Pixels whose centres (x + 0.5, y + 0.5) may lie inside.
        const int x0 = std::max(0, floorIndex(std::min({a.x(), b.x(), c.x()}) - 0.5, width_));
        const int x1 = std::min(width_, ceilIndex(std::max({a.x(), b.x(), c.x()}) - 0.5, width_) + 1);
        const int y0 = std::max(0, floorIndex(std::min({a.y(), b.y(), c.y()}) - 0.5, height_));
        const int y1 = std::min(height_, ceilIndex(std::max({a.y(), b.y(), c.y()}) - 0.5, height_) + 1);
        if (x0 >= x1 || y0 >= y1)
            continue;
        const bool ccw = area > 0.0;
        const bool tl[3] = {isTopLeft(b, c, ccw), isTopLeft(c, a, ccw), isTopLeft(a, b, ccw)};
        const double inverseArea = 1.0 / area;
        bool drew = false;
        for (int y = y0; y < y1; ++y)
        {
            const double py = y + 0.5;
            for (int x = x0; x < x1; ++x)
            {
                const double px = x + 0.5;
                const double w[3] = {edge(b, c, px, py) * inverseArea, edge(c, a, px, py) * inverseArea,
                                     edge(a, b, px, py) * inverseArea};
                bool inside = true;
                for (int k = 0; k < 3; ++k)
                    inside = inside && (w[k] > 0.0 || (w[k] == 0.0 && tl[k]));
                if (!inside)
                    continue;
                const double z = w[0] * a.z() + w[1] * b.z() + w[2] * c.z();
                double &stored = depth_[index(x, y)];
                if (z < stored)
                {
                    stored = z;
                    colour_[index(x, y)] = shaded;
                    drew = true;
                }
            }
        }
        if (drew)
            touch(x0, y0, x1, y1);
    }
}

void RasterLayer::drawSegment(const Camera &camera, const Vec3 &a, const Vec3 &b, double thickness, const Rgb &colour)
{
    const Vec3 p = camera.project(a), q = camera.project(b);
    if (!p.allFinite() || !q.allFinite())
        return;
    const double radius = 0.5 * thickness;
    const int x0 = std::max(0, floorIndex(std::min(p.x(), q.x()) - radius, width_));
    const int x1 = std::min(width_, ceilIndex(std::max(p.x(), q.x()) + radius, width_) + 1);
    const int y0 = std::max(0, floorIndex(std::min(p.y(), q.y()) - radius, height_));
    const int y1 = std::min(height_, ceilIndex(std::max(p.y(), q.y()) + radius, height_) + 1);
    const double dx = q.x() - p.x(), dy = q.y() - p.y(), length2 = dx * dx + dy * dy;
    bool drew = false;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x)
        {
            const double px = x + 0.5 - p.x(), py = y + 0.5 - p.y();
            const double s = length2 > 0.0 ? std::clamp((px * dx + py * dy) / length2, 0.0, 1.0) : 0.0;
            const double ex = px - s * dx, ey = py - s * dy;
            if (ex * ex + ey * ey > radius * radius)
                continue;
            const double z = p.z() + s * (q.z() - p.z());
            double &stored = depth_[index(x, y)];
            if (z < stored)
            {
                stored = z;
                colour_[index(x, y)] = colour;
                drew = true;
            }
        }
    if (drew)
        touch(x0, y0, x1, y1);
}
}  // namespace hcd::render
