// SPDX-License-Identifier: BSD-3-Clause
// A z-buffered layer of flat-shaded triangles: the software rasterizer. One layer holds one object
// (the environment, or one placement of the robot) so that layers can be composited with depth.
#pragma once

#include "hybridcd/geometry/triangle_mesh.h"
#include "hybridcd/render/camera.h"
#include "hybridcd/render/image.h"

#include <limits>
#include <vector>

namespace hcd::render
{
/// The rectangle of pixels a layer has touched since its last clear: [x0, x1) x [y0, y1).
struct PixelRect
{
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    bool empty() const { return x0 >= x1 || y0 >= y1; }
};

class RasterLayer
{
public:
    RasterLayer(int width, int height);

    int width() const { return width_; }
    int height() const { return height_; }

    /// Empties the touched pixels (depth +infinity).
    void clear();

    /// Draws `mesh` placed by `worldFromMesh`, each triangle in `colour` times the flat shading of
    /// its normal under a light fixed to the camera (two-sided: meshes need not be oriented).
    /// A pixel is covered when its centre lies inside the projected triangle (top-left rule).
    void drawMesh(const Camera &camera, const TriangleMesh &mesh, const RigidTransform &worldFromMesh,
                  const Rgb &colour);

    /// Draws a segment of `thickness` pixels between two world points, in front of everything on
    /// this layer's depth scale that lies behind it (depth is interpolated along the segment).
    void drawSegment(const Camera &camera, const Vec3 &a, const Vec3 &b, double thickness, const Rgb &colour);

    bool covered(int x, int y) const { return depth_[index(x, y)] < std::numeric_limits<double>::infinity(); }
    double depth(int x, int y) const { return depth_[index(x, y)]; }
    const Rgb &colour(int x, int y) const { return colour_[index(x, y)]; }
    const PixelRect &touched() const { return touched_; }

private:
    std::size_t index(int x, int y) const { return std::size_t(y) * std::size_t(width_) + std::size_t(x); }
    void touch(int x0, int y0, int x1, int y1);

    int width_, height_;
    std::vector<double> depth_;
    std::vector<Rgb> colour_;
    PixelRect touched_;
};

/// The shading factor of a face with unit normal `normal`, in [0.3, 1]: ambient plus two-sided
/// diffuse under a light from above-left of the camera.
double flatShade(const Camera &camera, const Vec3 &normal);
}  // namespace hcd::render
