// SPDX-License-Identifier: BSD-3-Clause
// An orthographic camera fitted to a scene's bounds: world points (metres) to pixels and depth.
#pragma once

#include "hybridcd/geometry/rigid_transform.h"

#include <string>
#include <vector>

namespace hcd::render
{
/// Where the camera looks from. The world's +z is up in every view but Top, where +y is up.
enum class View
{
    Isometric,  ///< from above, in front and to the right: (+x, -y, +z) towards the scene
    Top,        ///< straight down -z (planar problems)
    Front,      ///< along +y
    Side,       ///< along -x
};

/// "iso", "top", "front" or "side"; throws std::invalid_argument naming the word otherwise.
View viewByName(const std::string &name);

/// Maps world points to pixel coordinates (x right, y down, pixel centres at +0.5) and a depth that
/// grows away from the camera (metres along the viewing direction).
class Camera
{
public:
    /// Fits `points` (e.g. the corners of the scene's bounds) into a width x height image with
    /// `marginPixels` of border, keeping the aspect ratio; the scene is centred.
    Camera(View view, const std::vector<Vec3> &points, int width, int height, double marginPixels);

    /// (pixel x, pixel y, depth).
    Vec3 project(const Vec3 &world) const
    {
        return {width_ * 0.5 + (right_.dot(world) - centerX_) * scale_,
                height_ * 0.5 - (up_.dot(world) - centerY_) * scale_, forward_.dot(world)};
    }

    /// Unit vector from the camera into the scene.
    const Vec3 &forward() const { return forward_; }
    const Vec3 &right() const { return right_; }
    const Vec3 &up() const { return up_; }
    /// Pixels per metre.
    double scale() const { return scale_; }

private:
    Vec3 forward_, right_, up_;
    double centerX_ = 0.0, centerY_ = 0.0;
    double scale_ = 1.0;
    int width_, height_;
};
}  // namespace hcd::render
