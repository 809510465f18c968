// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/render/camera.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace hcd::render
{
View viewByName(const std::string &name)
{
    if (name == "iso")
        return View::Isometric;
    if (name == "top")
        return View::Top;
    if (name == "front")
        return View::Front;
    if (name == "side")
        return View::Side;
    throw std::invalid_argument("unknown view '" + name + "' (iso, top, front or side)");
}

Camera::Camera(View view, const std::vector<Vec3> &points, int width, int height, double marginPixels)
    : width_(width),
      height_(height)
{
    Vec3 upHint = Vec3::UnitZ();
    switch (view)
    {
    case View::Isometric:
        forward_ = Vec3(-1.0, 1.25, -0.9).normalized();
        break;
    case View::Top:
        forward_ = -Vec3::UnitZ();
        upHint = Vec3::UnitY();
        break;
    case View::Front:
        forward_ = Vec3::UnitY();
        break;
    case View::Side:
        forward_ = -Vec3::UnitX();
        break;
    }
    right_ = forward_.cross(upHint).normalized();
    up_ = right_.cross(forward_);

    double lo[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    double hi[2] = {-lo[0], -lo[1]};
    for (const Vec3 &p : points)
    {
        if (!p.allFinite())
            continue;
        const double s[2] = {right_.dot(p), up_.dot(p)};
        for (int i = 0; i < 2; ++i)
        {
            lo[i] = std::min(lo[i], s[i]);
            hi[i] = std::max(hi[i], s[i]);
        }
    }
    if (!(lo[0] <= hi[0]))  // nothing to fit: a unit square about the origin
    {
        lo[0] = lo[1] = -1.0;
        hi[0] = hi[1] = 1.0;
    }
    centerX_ = 0.5 * (lo[0] + hi[0]);
    centerY_ = 0.5 * (lo[1] + hi[1]);
    const double usableX = std::max(1.0, width - 2.0 * marginPixels),
                 usableY = std::max(1.0, height - 2.0 * marginPixels);
    const double spanX = std::max(hi[0] - lo[0], 1e-12), spanY = std::max(hi[1] - lo[1], 1e-12);
    scale_ = std::min(usableX / spanX, usableY / spanY);
}
}  // namespace hcd::render
