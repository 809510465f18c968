// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/bv/ctree_volume.h"

#include <algorithm>
#include <cmath>

namespace hcd
{
CTreeVolume CTreeVolume::fit(const std::vector<Vec3> &points)
{
    CTreeVolume v;
    v.sphere = Sphere::fit(points);
    v.box = Obb::fit(points);
    v.kind = v.sphere.volume() < v.box.volume() ? Kind::Sphere : Kind::Box;
    return v;
}

double CTreeVolume::boundingRadius() const
{
    return kind == Kind::Sphere ? sphere.radius : box.halfExtents.norm() * (1.0 + 1e-12);
}

CTreeVolume CTreeVolume::transformed(const RigidTransform &pose) const
{
    CTreeVolume v = *this;
    if (kind == Kind::Sphere)
        v.sphere = sphere.transformed(pose);
    else
        v.box = box.transformed(pose);
    return v;
}

double sphereBoxDistance(const Sphere &s, const Obb &b)
{
    const Vec3 local = b.axes.transpose() * (s.center - b.center);
    const Vec3 outside = (local.cwiseAbs() - b.halfExtents).cwiseMax(0.0);
    return std::max(0.0, outside.norm() - s.radius);
}

namespace
{
// The gap between a sphere and a box, less the tolerance and a relative margin for the rounding of
// the change of frame (1e-12 of the coordinates' magnitude).
double sphereBoxGap(const Sphere &s, const Obb &b, double tolerance)
{
    const double magnitude =
        std::max(s.center.cwiseAbs().maxCoeff(), b.center.cwiseAbs().maxCoeff()) + b.halfExtents.norm() + s.radius;
    return sphereBoxDistance(s, b) - tolerance - 1e-12 * magnitude;
}
}  // namespace

bool ctreeVolumesOverlap(const CTreeVolume &a, const CTreeVolume &b, double tolerance)
{
    using K = CTreeVolume::Kind;
    if (a.kind == K::Sphere && b.kind == K::Sphere)
        return spheresOverlap(a.sphere, b.sphere, tolerance);
    if (a.kind == K::Box && b.kind == K::Box)
        return obbsOverlap(a.box, b.box, tolerance);
    const Sphere &s = a.kind == K::Sphere ? a.sphere : b.sphere;
    const Obb &box = a.kind == K::Box ? a.box : b.box;
    return sphereBoxGap(s, box, tolerance) <= 0.0;
}

double ctreeDistanceLowerBound(const CTreeVolume &a, const CTreeVolume &b, double tolerance)
{
    using K = CTreeVolume::Kind;
    if (a.kind == K::Sphere && b.kind == K::Sphere)
        return sphereDistanceLowerBound(a.sphere, b.sphere, tolerance);
    if (a.kind == K::Box && b.kind == K::Box)
        return obbDistanceLowerBound(a.box, b.box, tolerance);
    const Sphere &s = a.kind == K::Sphere ? a.sphere : b.sphere;
    const Obb &box = a.kind == K::Box ? a.box : b.box;
    return std::max(0.0, sphereBoxGap(s, box, tolerance));
}
}  // namespace hcd
