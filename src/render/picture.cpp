// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/render/picture.h"

#include "hybridcd/render/raster_layer.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace hcd::render
{
namespace
{
constexpr double kMarginFraction = 0.04;
constexpr double kVolumeOpacity = 0.4, kVolumeHiddenOpacity = 0.15;
constexpr double kLineHiddenOpacity = 0.35;

void addCorners(std::vector<Vec3> &points, const BoundingBox &box, const RigidTransform &placement)
{
    if (box.empty())
        return;
    for (int i = 0; i < 8; ++i)
        points.push_back(placement.apply(Vec3(i & 1 ? box.max.x() : box.min.x(), i & 2 ? box.max.y() : box.min.y(),
                                              i & 4 ? box.max.z() : box.min.z())));
}

std::vector<Vec3> scenePoints(const PictureRequest &request)
{
    std::vector<Vec3> points;
    if (request.environment)
        addCorners(points, request.environment->bounds(), RigidTransform::identity());
    const BoundingBox robotBox = request.robot->bounds();
    for (const RobotPlacement &p : request.placements)
        addCorners(points, p.mesh ? p.mesh->bounds() : robotBox, p.worldFromRobot);
    if (request.volumes)
        points.insert(points.end(), request.volumes->vertices.begin(), request.volumes->vertices.end());
    points.insert(points.end(), request.pathLine.begin(), request.pathLine.end());
    for (const std::vector<Vec3> &line : request.morePathLines)
        points.insert(points.end(), line.begin(), line.end());
    return points;
}

Camera fittedCamera(const PictureRequest &request, int scale)
{
    const std::vector<Vec3> points = scenePoints(request);
    const double margin = kMarginFraction * std::min(request.width, request.height);
    return Camera(request.view, points, request.width * scale, request.height * scale, margin * scale);
}

// Blends `layer` over (colour, depth): `opacity` where the layer is nearer, `hiddenOpacity` where
// it is behind (by more than `depthSlack`); an opaque layer in front also takes over the depth, so
// it hides what follows.
void composite(const RasterLayer &layer, std::vector<Rgb> &colour, std::vector<double> &depth, double opacity,
               double hiddenOpacity, double depthSlack = 0.0)
{
    const PixelRect r = layer.touched();
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x)
        {
            if (!layer.covered(x, y))
                continue;
            const std::size_t i = std::size_t(y) * std::size_t(layer.width()) + std::size_t(x);
            const bool front = layer.depth(x, y) < depth[i] + depthSlack;
            const double a = front ? opacity : hiddenOpacity;
            const Rgb &c = layer.colour(x, y);
            colour[i] = {colour[i].r + a * (c.r - colour[i].r), colour[i].g + a * (c.g - colour[i].g),
                         colour[i].b + a * (c.b - colour[i].b)};
            if (front && opacity >= 1.0)
                depth[i] = layer.depth(x, y);
        }
}

std::uint8_t toByte(double v) { return std::uint8_t(std::lround(255.0 * std::clamp(v, 0.0, 1.0))); }
}  // namespace

Camera pictureCamera(const PictureRequest &request) { return fittedCamera(request, 1); }

Image renderPicture(const PictureRequest &request)
{
    if (!request.robot)
        throw std::invalid_argument("renderPicture: no robot mesh");
    for (const int size : {request.width, request.height})
        if (size < 16 || size > 8192)
            throw std::invalid_argument("renderPicture: image sizes must be 16 to 8192 pixels, got " +
                                        std::to_string(size));
    const int s = std::clamp(request.supersample, 1, 4);
    const int w = request.width * s, h = request.height * s;
    const Camera camera = fittedCamera(request, s);
    const Palette &palette = request.palette;
    // Volumes touch the robot's faces and a path may run along a floor: within this slack (a
    // hundred-thousandth of the scene's size, metres) they count as in front, not hidden.
    BoundingBox sceneBox;
    for (const Vec3 &p : scenePoints(request))
        if (p.allFinite())
            sceneBox.extend(p);
    const double slack = sceneBox.empty() ? 0.0 : 1e-5 * (sceneBox.max - sceneBox.min).norm();

    RasterLayer layer(w, h);
    if (request.environment)
        layer.drawMesh(camera, *request.environment, RigidTransform::identity(), palette.environment);
    std::vector<Rgb> colour(std::size_t(w) * std::size_t(h), palette.background);
    std::vector<double> depth(colour.size(), std::numeric_limits<double>::infinity());
    {
        const PixelRect r = layer.touched();
        for (int y = r.y0; y < r.y1; ++y)
            for (int x = r.x0; x < r.x1; ++x)
                if (layer.covered(x, y))
                {
                    const std::size_t i = std::size_t(y) * std::size_t(w) + std::size_t(x);
                    colour[i] = layer.colour(x, y);
                    depth[i] = layer.depth(x, y);
                }
    }
    for (const RobotPlacement &p : request.placements)
    {
        layer.clear();
        layer.drawMesh(camera, p.mesh ? *p.mesh : *request.robot, p.worldFromRobot, p.colour);
        composite(layer, colour, depth, p.opacity, p.hiddenOpacity);
    }
    if (request.pathLine.size() >= 2 || !request.morePathLines.empty())
    {
        layer.clear();
        const double thickness = std::max(2.5, 0.004 * std::min(w, h));
        auto drawLine = [&](const std::vector<Vec3> &line) {
            for (std::size_t i = 0; i + 1 < line.size(); ++i)
                layer.drawSegment(camera, line[i], line[i + 1], thickness, palette.pathLine);
        };
        drawLine(request.pathLine);
        for (const std::vector<Vec3> &line : request.morePathLines)
            drawLine(line);
        composite(layer, colour, depth, 1.0, kLineHiddenOpacity, slack);
    }
    if (request.volumes && !request.volumes->empty())
    {
        layer.clear();
        layer.drawMesh(camera, *request.volumes, RigidTransform::identity(), palette.volumes);
        composite(layer, colour, depth, kVolumeOpacity, kVolumeHiddenOpacity, slack);
    }

    Image image(request.width, request.height);
    const double weight = 1.0 / double(s * s);
    for (int y = 0; y < request.height; ++y)
        for (int x = 0; x < request.width; ++x)
        {
            double sum[3] = {0.0, 0.0, 0.0};
            for (int dy = 0; dy < s; ++dy)
                for (int dx = 0; dx < s; ++dx)
                {
                    const Rgb &c = colour[std::size_t(y * s + dy) * std::size_t(w) + std::size_t(x * s + dx)];
                    sum[0] += c.r;
                    sum[1] += c.g;
                    sum[2] += c.b;
                }
            std::uint8_t *out = image.at(x, y);
            for (int k = 0; k < 3; ++k)
                out[k] = toByte(sum[k] * weight);
        }
    return image;
}

std::vector<RigidTransform> samplePath(const std::vector<RigidTransform> &path, std::size_t count)
{
    std::vector<RigidTransform> samples;
    if (path.empty() || count == 0)
        return samples;
    if (path.size() == 1 || count == 1)
        return std::vector<RigidTransform>(count, path.front());
    // Parameter of each state: distance travelled, or the state index when the origin stays put.
    std::vector<double> along(path.size(), 0.0);
    for (std::size_t i = 1; i < path.size(); ++i)
        along[i] = along[i - 1] + (path[i].translation - path[i - 1].translation).norm();
    if (!(along.back() > 0.0) || !std::isfinite(along.back()))
        for (std::size_t i = 0; i < path.size(); ++i)
            along[i] = double(i);
    for (std::size_t k = 0; k < count; ++k)
    {
        if (k + 1 == count)
        {
            samples.push_back(path.back());
            break;
        }
        const double target = along.back() * double(k) / double(count - 1);
        const std::size_t i = std::size_t(std::upper_bound(along.begin(), along.end(), target) - along.begin()) - 1;
        const std::size_t j = std::min(i + 1, path.size() - 1);
        const double span = along[j] - along[i];
        const double t = span > 0.0 ? (target - along[i]) / span : 0.0;
        const Eigen::Quaterniond qa(path[i].rotation), qb(path[j].rotation);
        RigidTransform pose;
        pose.rotation = qa.slerp(t, qb).toRotationMatrix();
        pose.translation = path[i].translation + t * (path[j].translation - path[i].translation);
        samples.push_back(pose);
    }
    return samples;
}

Rgb rampColour(const Palette &palette, double t)
{
    t = std::clamp(t, 0.0, 1.0);
    return {palette.start.r + t * (palette.goal.r - palette.start.r),
            palette.start.g + t * (palette.goal.g - palette.start.g),
            palette.start.b + t * (palette.goal.b - palette.start.b)};
}
}  // namespace hcd::render
