// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/bv/sphere.h"

#include <algorithm>
#include <cmath>

namespace hcd
{
namespace
{
// Index of the point farthest from `c`, and its distance.
std::pair<std::size_t, double> farthest(const std::vector<Vec3> &points, const Vec3 &c)
{
    std::size_t best = 0;
    double bestSquared = -1.0;
    for (std::size_t i = 0; i < points.size(); ++i)
    {
        const double d = (points[i] - c).squaredNorm();
        if (d > bestSquared)
        {
            bestSquared = d;
            best = i;
        }
    }
    return {best, std::sqrt(bestSquared)};
}
}  // namespace

double Sphere::volume() const { return 4.0 / 3.0 * M_PI * radius * radius * radius; }

Sphere Sphere::fit(const std::vector<Vec3> &points)
{
    double magnitude = 0.0;
    for (const Vec3 &p : points)
        magnitude = std::max(magnitude, p.cwiseAbs().maxCoeff());

    // Ritter: a far pair gives the first ball, grown to take in each point left outside.
    const std::size_t a = farthest(points, points[0]).first;
    const std::size_t b = farthest(points, points[a]).first;
    Vec3 center = 0.5 * (points[a] + points[b]);
    double radius = 0.5 * (points[a] - points[b]).norm();
    for (const Vec3 &p : points)
    {
        const double d = (p - center).norm();
        if (d > radius)
        {
            const double grown = 0.5 * (radius + d);
            center += (d - grown) / d * (p - center);
            radius = grown;
        }
    }
    // Shrinking passes (Badoiu-Clarkson): step the centre towards the farthest point by 1/(i+2)
    // of the way; the ball about each centre reaching its farthest point is always valid.
    Vec3 bestCenter = center;
    double bestRadius = farthest(points, center).second;
    Vec3 c = center;
    for (int i = 0; i < 64; ++i)
    {
        const auto [index, reach] = farthest(points, c);
        if (reach < bestRadius)
        {
            bestRadius = reach;
            bestCenter = c;
        }
        c += (points[index] - c) / double(i + 2);
    }
    const double exact = farthest(points, bestCenter).second;
    return {bestCenter, exact * (1.0 + 1e-12) + 1e-9 * magnitude + 1e-300};
}

bool spheresOverlap(const Sphere &a, const Sphere &b, double tolerance)
{
    const double reach = a.radius + b.radius + tolerance;
    return (a.center - b.center).squaredNorm() <= reach * reach;
}

double sphereDistanceLowerBound(const Sphere &a, const Sphere &b, double tolerance)
{
    return std::max(0.0, (a.center - b.center).norm() - a.radius - b.radius - tolerance);
}
}  // namespace hcd
