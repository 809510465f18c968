// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/geometry/shape.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace hcd
{
namespace
{
constexpr double kInfinity = std::numeric_limits<double>::infinity();

const char *const kKindNames[kShapeKindCount] = {"sphere",    "box",       "capsule", "cylinder", "cone",
                                                 "ellipsoid", "halfspace", "convex",  "mesh"};

// Lengths are squared and multiplied by the pair tests: beyond these they would over- or underflow.
constexpr double kLargestLength = 1e100;
constexpr double kSmallestLength = 1e-100;

void requirePositive(double value, const char *what)
{
    if (!std::isfinite(value) || !(value > 0.0))
        throw std::invalid_argument(std::string("Shape: ") + what + " must be finite and positive");
    if (value > kLargestLength || value < kSmallestLength)
        throw std::invalid_argument(std::string("Shape: ") + what + " must be of magnitude 1e-100 to 1e100");
}

void requirePositive(const Vec3 &value, const char *what)
{
    for (int i = 0; i < 3; ++i)
        requirePositive(value[i], what);
}

const std::vector<Vec3> &emptyPoints()
{
    static const std::vector<Vec3> empty;
    return empty;
}

// Sign with sign(0) = +1, so that support points of a box are corners for every direction.
double signOf(double x) { return x < 0.0 ? -1.0 : 1.0; }

// The unit vector of (x, y) in the plane, or (1, 0) for the zero vector (every rim point then
// maximises the direction equally).
Eigen::Vector2d planarUnit(double x, double y)
{
    const double n = std::hypot(x, y);
    if (!(n > 0.0))
        return {1.0, 0.0};
    return {x / n, y / n};
}

// Cube-sphere grid: (cells + 1)^2 points per cube face, radially projected to the unit sphere.
// Every point of the sphere is within angle 2 asin(sqrt(2) / (2 cells)) of one of them (the
// radial projection is 1-Lipschitz outside the unit ball, and each point of the cube's surface is
// within sqrt(2) / cells of a grid point).
std::vector<Vec3> unitSphereNet(int cells)
{
    std::vector<Vec3> points;
    for (int axis = 0; axis < 3; ++axis)
        for (double side : {-1.0, 1.0})
            for (int i = 0; i <= cells; ++i)
                for (int j = 0; j <= cells; ++j)
                {
                    Vec3 q;
                    q[axis] = side;
                    q[(axis + 1) % 3] = -1.0 + 2.0 * i / cells;
                    q[(axis + 2) % 3] = -1.0 + 2.0 * j / cells;
                    points.push_back(q.normalized());
                }
    return points;
}

double sphereNetCos(int cells) { return std::cos(2.0 * std::asin(std::sqrt(2.0) / (2.0 * cells))); }
}  // namespace

const char *shapeKindName(ShapeKind kind)
{
    const int k = static_cast<int>(kind);
    return k >= 0 && k < kShapeKindCount ? kKindNames[k] : "unknown";
}

std::optional<ShapeKind> shapeKindFromName(const std::string &name)
{
    for (int k = 0; k < kShapeKindCount; ++k)
        if (name == kKindNames[k])
            return static_cast<ShapeKind>(k);
    return std::nullopt;
}

Shape Shape::sphere(double radius)
{
    requirePositive(radius, "sphere radius");
    Shape s;
    s.kind_ = ShapeKind::Sphere;
    s.radius_ = radius;
    return s;
}

Shape Shape::box(const Vec3 &halfExtents)
{
    requirePositive(halfExtents, "box half-extents");
    Shape s;
    s.kind_ = ShapeKind::Box;
    s.extents_ = halfExtents;
    return s;
}

Shape Shape::capsule(double radius, double halfLength)
{
    requirePositive(radius, "capsule radius");
    requirePositive(halfLength, "capsule half-length");
    Shape s;
    s.kind_ = ShapeKind::Capsule;
    s.radius_ = radius;
    s.halfLength_ = halfLength;
    return s;
}

Shape Shape::cylinder(double radius, double halfLength)
{
    requirePositive(radius, "cylinder radius");
    requirePositive(halfLength, "cylinder half-length");
    Shape s;
    s.kind_ = ShapeKind::Cylinder;
    s.radius_ = radius;
    s.halfLength_ = halfLength;
    return s;
}

Shape Shape::cone(double baseRadius, double halfHeight)
{
    requirePositive(baseRadius, "cone base radius");
    requirePositive(halfHeight, "cone half-height");
    Shape s;
    s.kind_ = ShapeKind::Cone;
    s.radius_ = baseRadius;
    s.halfLength_ = halfHeight;
    return s;
}

Shape Shape::ellipsoid(const Vec3 &semiAxes)
{
    requirePositive(semiAxes, "ellipsoid semi-axes");
    Shape s;
    s.kind_ = ShapeKind::Ellipsoid;
    s.extents_ = semiAxes;
    return s;
}

Shape Shape::halfspace(const Vec3 &normal, double offset)
{
    // Scaled by its largest component first: the squares of a normal of 1e-160 are subnormal, and
    // its length from them was off by 1e-5 (a clearance then came out that much too large).
    const double largest = normal.cwiseAbs().maxCoeff();
    if (!normal.allFinite() || !std::isfinite(offset) || !(largest > 0.0))
        throw std::invalid_argument("Shape: half-space normal must be finite and non-zero, offset finite");
    const Vec3 scaled = normal / largest;
    const double length = scaled.norm();  // in [1, sqrt(3)]
    const double unitOffset = offset / largest / length;
    if (!(std::fabs(unitOffset) <= kLargestLength))
        throw std::invalid_argument(
            "Shape: half-space offset over the normal's length must be of magnitude at most 1e100");
    Shape s;
    s.kind_ = ShapeKind::Halfspace;
    s.normal_ = scaled / length;
    s.offset_ = unitOffset;
    return s;
}

Shape Shape::convex(std::vector<Vec3> points)
{
    if (points.empty())
        throw std::invalid_argument("Shape: convex shape needs at least one point");
    for (const Vec3 &p : points)
        if (!p.allFinite())
            throw std::invalid_argument("Shape: convex shape points must be finite");
    Shape s;
    s.kind_ = ShapeKind::Convex;
    s.points_ = std::make_shared<const std::vector<Vec3>>(std::move(points));
    return s;
}

Shape Shape::mesh(std::shared_ptr<const TriangleMesh> mesh)
{
    if (!mesh || mesh->empty())
        throw std::invalid_argument("Shape: mesh shape needs a non-empty mesh");
    for (const Vec3 &p : mesh->vertices)
        if (!p.allFinite())
            throw std::invalid_argument("Shape: mesh vertices must be finite");
    Shape s;
    s.kind_ = ShapeKind::Mesh;
    s.mesh_ = std::move(mesh);
    return s;
}

const std::vector<Vec3> &Shape::points() const { return points_ ? *points_ : emptyPoints(); }

Vec3 supportPoint(const Shape &shape, const Vec3 &d)
{
    const double h = shape.halfLength();
    switch (shape.kind())
    {
    case ShapeKind::Sphere:
    {
        const double n = d.norm();
        return n > 0.0 ? Vec3(d * (shape.radius() / n)) : Vec3(shape.radius(), 0.0, 0.0);
    }
    case ShapeKind::Box:
        return Vec3(signOf(d.x()) * shape.extents().x(), signOf(d.y()) * shape.extents().y(),
                    signOf(d.z()) * shape.extents().z());
    case ShapeKind::Capsule:
    {
        const double n = d.norm();
        const Vec3 ball = n > 0.0 ? Vec3(d * (shape.radius() / n)) : Vec3(shape.radius(), 0.0, 0.0);
        return ball + Vec3(0.0, 0.0, signOf(d.z()) * h);
    }
    case ShapeKind::Cylinder:
    {
        const Eigen::Vector2d u = planarUnit(d.x(), d.y()) * shape.radius();
        return Vec3(u.x(), u.y(), signOf(d.z()) * h);
    }
    case ShapeKind::Cone:
    {
        // The cone is the hull of its apex and its base circle: the better of the two.
        const Eigen::Vector2d u = planarUnit(d.x(), d.y()) * shape.radius();
        const Vec3 rim(u.x(), u.y(), -h);
        const Vec3 apex(0.0, 0.0, h);
        return d.dot(apex) >= d.dot(rim) ? apex : rim;
    }
    case ShapeKind::Ellipsoid:
    {
        // x = A^2 d / |A d| with A = diag(semi-axes): the normal at x is parallel to d.
        const Vec3 ad = shape.extents().cwiseProduct(d);
        const double n = ad.norm();
        if (!(n > 0.0))
            return Vec3(shape.extents().x(), 0.0, 0.0);
        return shape.extents().cwiseProduct(ad) / n;
    }
    case ShapeKind::Convex:
    {
        const std::vector<Vec3> &points = shape.points();
        std::size_t best = 0;
        double bestValue = d.dot(points[0]);
        for (std::size_t i = 1; i < points.size(); ++i)
        {
            const double v = d.dot(points[i]);
            if (v > bestValue)
            {
                bestValue = v;
                best = i;
            }
        }
        return points[best];
    }
    case ShapeKind::Halfspace:
    case ShapeKind::Mesh:
        break;
    }
    throw std::invalid_argument(std::string("supportPoint: no support mapping for a ") + shapeKindName(shape.kind()));
}

double boundingRadius(const Shape &shape)
{
    const double r = shape.radius(), h = shape.halfLength();
    switch (shape.kind())
    {
    case ShapeKind::Sphere:
        return r;
    case ShapeKind::Box:
        return shape.extents().norm();
    case ShapeKind::Capsule:
        return r + h;
    case ShapeKind::Cylinder:
    case ShapeKind::Cone:
        return std::hypot(r, h);
    case ShapeKind::Ellipsoid:
        return shape.extents().maxCoeff();
    case ShapeKind::Halfspace:
        return kInfinity;
    case ShapeKind::Convex:
    {
        double m = 0.0;
        for (const Vec3 &p : shape.points())
            m = std::max(m, p.norm());
        return m;
    }
    case ShapeKind::Mesh:
        return shape.meshPointer()->radiusAboutOrigin();
    }
    return kInfinity;
}

BoundingBox worldBounds(const Shape &shape, const RigidTransform &worldFromShape)
{
    BoundingBox box;
    const Mat3 &rotation = worldFromShape.rotation;
    const Vec3 &t = worldFromShape.translation;
    if (shape.kind() == ShapeKind::Halfspace)
    {
        box.min = Vec3::Constant(-kInfinity);
        box.max = Vec3::Constant(kInfinity);
        const Vec3 n = rotation * shape.normal();
        const double offset = shape.offset() + n.dot(t);
        for (int i = 0; i < 3; ++i)
        {
            // Bounded along axis i only when the normal is exactly +-e_i: then x_i <= offset (or >= -offset).
            const bool axisAligned = n[(i + 1) % 3] == 0.0 && n[(i + 2) % 3] == 0.0 && std::abs(n[i]) == 1.0;
            if (!axisAligned)
                continue;
            const double bound = n[i] * offset;
            const double grow = 1e-12 * (std::abs(offset) + t.cwiseAbs().maxCoeff()) + 1e-300;
            if (n[i] > 0.0)
                box.max[i] = bound + grow;
            else
                box.min[i] = bound - grow;
        }
        return box;
    }
    if (shape.kind() == ShapeKind::Mesh)
    {
        const BoundingBox local = shape.meshPointer()->bounds();
        const Vec3 centre = 0.5 * (local.min + local.max), half = 0.5 * (local.max - local.min);
        const Vec3 c = worldFromShape.apply(centre);
        const Vec3 e = rotation.cwiseAbs() * half;
        const double grow = 1e-12 * (c.cwiseAbs().maxCoeff() + e.maxCoeff() + local.max.cwiseAbs().maxCoeff() +
                                     local.min.cwiseAbs().maxCoeff());
        box.min = c - e - Vec3::Constant(grow);
        box.max = c + e + Vec3::Constant(grow);
        return box;
    }
    // Support-mapped: the extreme points along each world axis.
    for (int i = 0; i < 3; ++i)
    {
        const Vec3 axisLocal = rotation.row(i).transpose();  // R^T e_i
        box.max[i] = t[i] + axisLocal.dot(supportPoint(shape, axisLocal));
        box.min[i] = t[i] + axisLocal.dot(supportPoint(shape, -axisLocal));
    }
    const double grow = 1e-12 * (t.cwiseAbs().maxCoeff() + boundingRadius(shape));
    box.min -= Vec3::Constant(grow);
    box.max += Vec3::Constant(grow);
    return box;
}

bool containsPoint(const Shape &shape, const Vec3 &p)
{
    const double r = shape.radius(), h = shape.halfLength();
    switch (shape.kind())
    {
    case ShapeKind::Sphere:
        return p.squaredNorm() <= r * r;
    case ShapeKind::Box:
        return (p.cwiseAbs().array() <= shape.extents().array()).all();
    case ShapeKind::Capsule:
    {
        const double z = std::clamp(p.z(), -h, h);
        return (p - Vec3(0.0, 0.0, z)).squaredNorm() <= r * r;
    }
    case ShapeKind::Cylinder:
        return std::abs(p.z()) <= h && p.x() * p.x() + p.y() * p.y() <= r * r;
    case ShapeKind::Cone:
    {
        if (std::abs(p.z()) > h)
            return false;
        const double radiusAtZ = r * (h - p.z()) / (2.0 * h);
        return std::hypot(p.x(), p.y()) <= radiusAtZ;
    }
    case ShapeKind::Ellipsoid:
        return p.cwiseQuotient(shape.extents()).squaredNorm() <= 1.0;
    case ShapeKind::Halfspace:
        return shape.normal().dot(p) <= shape.offset();
    case ShapeKind::Convex:
    case ShapeKind::Mesh:
        break;
    }
    throw std::invalid_argument(std::string("containsPoint: not a closed-form kind: ") + shapeKindName(shape.kind()));
}

double tessellationRelativeError(int resolution)
{
    resolution = std::max(resolution, 2);
    const double sphere = 1.0 / sphereNetCos(2 * resolution) - 1.0;
    const double circle = 1.0 / std::cos(M_PI / (4.0 * resolution)) - 1.0;
    return std::max(sphere, circle);
}

std::vector<Vec3> tessellationPoints(const Shape &shape, int resolution, TessellationSide side)
{
    resolution = std::max(resolution, 2);
    const bool outer = side == TessellationSide::Outer;
    const int cells = 2 * resolution;
    const double sphereScale = outer ? 1.0 / sphereNetCos(cells) : 1.0;
    const int circleCount = 4 * resolution;
    const double circleScale = outer ? 1.0 / std::cos(M_PI / circleCount) : 1.0;
    const double r = shape.radius(), h = shape.halfLength();
    std::vector<Vec3> points;
    auto circle = [&](double radius, double z) {
        for (int k = 0; k < circleCount; ++k)
        {
            const double angle = 2.0 * M_PI * k / circleCount;
            points.emplace_back(radius * std::cos(angle), radius * std::sin(angle), z);
        }
    };
    switch (shape.kind())
    {
    case ShapeKind::Sphere:
        for (const Vec3 &u : unitSphereNet(cells))
            points.push_back(u * (r * sphereScale));
        break;
    case ShapeKind::Ellipsoid:
        for (const Vec3 &u : unitSphereNet(cells))
            points.push_back(shape.extents().cwiseProduct(u) * sphereScale);
        break;
    case ShapeKind::Capsule:
        for (const Vec3 &u : unitSphereNet(cells))
            for (double z : {-h, h})
                points.push_back(u * (r * sphereScale) + Vec3(0.0, 0.0, z));
        break;
    case ShapeKind::Cylinder:
        circle(r * circleScale, -h);
        circle(r * circleScale, h);
        break;
    case ShapeKind::Cone:
        circle(r * circleScale, -h);
        points.emplace_back(0.0, 0.0, h);
        break;
    case ShapeKind::Box:
        for (int corner = 0; corner < 8; ++corner)
            points.emplace_back((corner & 1 ? 1.0 : -1.0) * shape.extents().x(),
                                (corner & 2 ? 1.0 : -1.0) * shape.extents().y(),
                                (corner & 4 ? 1.0 : -1.0) * shape.extents().z());
        break;
    case ShapeKind::Convex:
        points = shape.points();
        break;
    case ShapeKind::Halfspace:
    case ShapeKind::Mesh:
        throw std::invalid_argument(std::string("tessellationPoints: not a compact convex kind: ") +
                                    shapeKindName(shape.kind()));
    }
    return points;
}
}  // namespace hcd
