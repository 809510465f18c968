// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/geometry/exact_predicates.h"

#include <boost/multiprecision/cpp_int.hpp>

#include <atomic>
#include <cmath>

namespace hcd
{
namespace
{
using Rational = boost::multiprecision::cpp_rational;

// Process-wide count of exact evaluations: rare (none on OMPL.app's problems), so a relaxed
// atomic increment costs nothing measurable and needs no per-thread state.
std::atomic<unsigned long long> fallbackCount{0};

// Shewchuk's bounds are (7 + 56 eps) eps and (3 + 16 eps) eps with eps = 2^-53; we round up
// generously, which only sends slightly more cases to the exact path.
constexpr double kOrient3dErrorBound = PlaneOrientationFilter::kRelativeError;
constexpr double kOrient2dErrorBound = 4.0e-16;
// Below this the filter's products may be denormal and the bound is no longer valid.
constexpr double kTinyPermanent = PlaneOrientationFilter::kTinyPermanent;

int sign(const Rational &r) { return r.sign(); }

// A product that lands in the subnormal range (or flushes to zero from nonzero factors) has lost
// its relative accuracy; multiplied by a huge third factor, that error can exceed the static
// bound, so such inputs take the exact path.
bool productUnderflows(double x, double y)
{
    const double p = std::fabs(x * y);
    return p < 0x1p-969 && x != 0.0 && y != 0.0;
}

bool anyUnderflow(double cx, double cy, double cz, double dx, double dy, double dz)
{
    return productUnderflows(cy, dz) || productUnderflows(cz, dy) || productUnderflows(cx, dz) ||
           productUnderflows(cz, dx) || productUnderflows(cx, dy) || productUnderflows(cy, dx);
}

int orient3dExact(const Vec3 &a, const Vec3 &b, const Vec3 &c, const Vec3 &d)
{
    fallbackCount.fetch_add(1, std::memory_order_relaxed);
    const Rational ax(a.x()), ay(a.y()), az(a.z());
    const Rational bx = Rational(b.x()) - ax, by = Rational(b.y()) - ay, bz = Rational(b.z()) - az;
    const Rational cx = Rational(c.x()) - ax, cy = Rational(c.y()) - ay, cz = Rational(c.z()) - az;
    const Rational dx = Rational(d.x()) - ax, dy = Rational(d.y()) - ay, dz = Rational(d.z()) - az;
    const Rational det = bx * (cy * dz - cz * dy) - by * (cx * dz - cz * dx) + bz * (cx * dy - cy * dx);
    return sign(det);
}

int orient2dExact(double ax, double ay, double bx, double by, double cx, double cy)
{
    fallbackCount.fetch_add(1, std::memory_order_relaxed);
    const Rational rax(ax), ray(ay);
    const Rational det = (Rational(bx) - rax) * (Rational(cy) - ray) - (Rational(by) - ray) * (Rational(cx) - rax);
    return sign(det);
}
}  // namespace

int orient3d(const Vec3 &a, const Vec3 &b, const Vec3 &c, const Vec3 &d)
{
    const double bx = b.x() - a.x(), by = b.y() - a.y(), bz = b.z() - a.z();
    const double cx = c.x() - a.x(), cy = c.y() - a.y(), cz = c.z() - a.z();
    const double dx = d.x() - a.x(), dy = d.y() - a.y(), dz = d.z() - a.z();
    const double m1 = cy * dz, m2 = cz * dy, m3 = cx * dz, m4 = cz * dx, m5 = cx * dy, m6 = cy * dx;
    const double det = bx * (m1 - m2) - by * (m3 - m4) + bz * (m5 - m6);
    const double permanent = std::fabs(bx) * (std::fabs(m1) + std::fabs(m2)) +
                             std::fabs(by) * (std::fabs(m3) + std::fabs(m4)) +
                             std::fabs(bz) * (std::fabs(m5) + std::fabs(m6));
    const double bound = kOrient3dErrorBound * permanent;
    if (std::isfinite(permanent) && permanent > kTinyPermanent && !anyUnderflow(cx, cy, cz, dx, dy, dz))
    {
        if (det > bound)
            return 1;
        if (det < -bound)
            return -1;
    }
    if (!(a.allFinite() && b.allFinite() && c.allFinite() && d.allFinite()))
        return 0;  // NaN/inf input has no orientation; callers reject such poses earlier.
    // Four points sharing one coordinate exactly are coplanar (a zero column): the common case of
    // planar problems, whose robot and walls share their bottom plane, needs no exact arithmetic.
    for (int k = 0; k < 3; ++k)
        if (a[k] == b[k] && a[k] == c[k] && a[k] == d[k])
            return 0;
    return orient3dExact(a, b, c, d);
}

PlaneOrientationFilter::PlaneOrientationFilter(const Vec3 &a, const Vec3 &b, const Vec3 &c) : origin_(a)
{
    const double bx = b.x() - a.x(), by = b.y() - a.y(), bz = b.z() - a.z();
    const double cx = c.x() - a.x(), cy = c.y() - a.y(), cz = c.z() - a.z();
    const double m1 = by * cz, m2 = bz * cy, m3 = bz * cx, m4 = bx * cz, m5 = bx * cy, m6 = by * cx;
    normal_ = Vec3(m1 - m2, m3 - m4, m5 - m6);
    magnitude_ = Vec3(std::fabs(m1) + std::fabs(m2), std::fabs(m3) + std::fabs(m4), std::fabs(m5) + std::fabs(m6));
    // A product of two differences of at least 2^-484 each (or with a zero factor) stays normal:
    // the cheap test orient3d()'s finer one (productUnderflows) implies. Tinier differences leave
    // the filter unusable and orient3d() decides.
    constexpr double kSmallestFactor = 0x1p-484;
    const auto fine = [](double v) { return v == 0.0 || std::fabs(v) >= kSmallestFactor; };
    usable_ = magnitude_.allFinite() && fine(bx) && fine(by) && fine(bz) && fine(cx) && fine(cy) && fine(cz);
}

int orient2d(double ax, double ay, double bx, double by, double cx, double cy)
{
    const double l = (bx - ax) * (cy - ay), r = (by - ay) * (cx - ax);
    const double det = l - r;
    const double permanent = std::fabs(l) + std::fabs(r);
    if (std::isfinite(permanent) && permanent > kTinyPermanent)
    {
        const double bound = kOrient2dErrorBound * permanent;
        if (det > bound)
            return 1;
        if (det < -bound)
            return -1;
    }
    if (!(std::isfinite(ax) && std::isfinite(ay) && std::isfinite(bx) && std::isfinite(by) && std::isfinite(cx) &&
          std::isfinite(cy)))
        return 0;
    // Both products have an exactly zero factor (a difference of doubles is zero only for equal
    // values): the determinant is exactly zero. Common for axis-aligned faces seen edge-on.
    if ((bx == ax || cy == ay) && (by == ay || cx == ax))
        return 0;
    return orient2dExact(ax, ay, bx, by, cx, cy);
}

unsigned long long exactPredicateFallbacks() { return fallbackCount.load(std::memory_order_relaxed); }
}  // namespace hcd
