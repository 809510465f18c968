// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/bv/kdop.h"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>

namespace hcd
{
namespace
{
template <int K>
std::array<Vec3, K / 2> makeDirections()
{
    std::vector<Vec3> d = {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
    if (K == 14 || K == 26)
        for (const Vec3 &v : {Vec3(1, 1, 1), Vec3(1, 1, -1), Vec3(1, -1, 1), Vec3(-1, 1, 1)})
            d.push_back(v.normalized());
    if (K == 18 || K == 26)
        for (const Vec3 &v :
             {Vec3(1, 1, 0), Vec3(1, 0, 1), Vec3(0, 1, 1), Vec3(1, -1, 0), Vec3(1, 0, -1), Vec3(0, 1, -1)})
            d.push_back(v.normalized());
    std::array<Vec3, K / 2> out;
    std::copy(d.begin(), d.end(), out.begin());
    return out;
}

// The cones of the k directions +-n_i: the facets (as triangles) of their convex hull. Every
// direction u lies in the cone of some facet, where it is a non-negative combination of the
// facet's three directions, the tightest the slabs give.
struct Cone
{
    std::array<int, 3> slab;     ///< slab index of each direction
    std::array<double, 3> sign;  ///< +1 for n_i, -1 for -n_i
    Mat3 inverse;                ///< maps u to its coefficients on the three directions
};

// The cones, and for each of the k directions (+n_i as i, -n_i as i + k/2) the cones it spans.
template <int K>
struct ConeTable
{
    std::vector<Cone> cones;
    std::array<std::vector<int>, K> incident;
};

template <int K>
const ConeTable<K> &cones()
{
    static const ConeTable<K> table = [] {
        constexpr int n = K / 2;
        const auto &dirs = kdopDirections<K>();
        std::vector<Vec3> points;
        for (int s = 0; s < 2; ++s)
            for (int i = 0; i < n; ++i)
                points.push_back(s == 0 ? dirs[i] : Vec3(-dirs[i]));
        ConeTable<K> out;
        for (int a = 0; a < K; ++a)
            for (int b = a + 1; b < K; ++b)
                for (int c = b + 1; c < K; ++c)
                {
                    Vec3 normal = (points[b] - points[a]).cross(points[c] - points[a]);
                    if (normal.norm() < 1e-9)
                        continue;
                    normal.normalize();
                    double offset = normal.dot(points[a]);
                    if (offset < 0)
                    {
                        normal = -normal;
                        offset = -offset;
                    }
                    if (offset < 1e-9 || std::any_of(points.begin(), points.end(),
                                                     [&](const Vec3 &p) { return normal.dot(p) > offset + 1e-9; }))
                        continue;
                    Mat3 m;
                    m << points[a], points[b], points[c];
                    Cone cone{};
                    for (int k = 0; k < 3; ++k)
                    {
                        const int id = k == 0 ? a : k == 1 ? b : c;
                        cone.slab[k] = id % n;
                        cone.sign[k] = id < n ? 1.0 : -1.0;
                    }
                    cone.inverse = m.inverse();
                    for (const int id : {a, b, c})
                        out.incident[std::size_t(id)].push_back(int(out.cones.size()));
                    out.cones.push_back(cone);
                }
        return out;
    }();
    return table;
}

}  // namespace

template <int K>
KDopRotation<K> KDopRotation<K>::of(const RigidTransform &pose)
{
    KDopRotation mapping;
    mapping.pose = pose;
    const Mat3 &rotation = pose.rotation;
    const auto &dirs = kdopDirections<K>();
    const auto &table = cones<K>();
    for (int m = 0; m < K / 2; ++m)
    {
        const Vec3 u = rotation.transpose() * dirs[m];
        // The cone holding u is searched among those of u's nearest direction (any cone gives a
        // valid bound; the one holding u, all coefficients >= 0, gives the tightest): the one
        // with the largest smallest coefficient.
        int nearest = 0;
        double nearestDot = -std::numeric_limits<double>::infinity();
        for (int i = 0; i < K / 2; ++i)
        {
            const double d = u.dot(dirs[i]);
            if (d > nearestDot)
                nearestDot = d, nearest = i;
            if (-d > nearestDot)
                nearestDot = -d, nearest = i + K / 2;
        }
        const Cone *best = nullptr;
        double bestMin = -std::numeric_limits<double>::infinity();
        Vec3 bestCoef = Vec3::Zero();
        for (const int f : table.incident[std::size_t(nearest)])
        {
            const Cone &c = table.cones[std::size_t(f)];
            const Vec3 coef = c.inverse * u;
            if (coef.minCoeff() > bestMin)
            {
                bestMin = coef.minCoeff();
                best = &c;
                bestCoef = coef;
            }
        }
        if (!best)  // a non-finite rotation: the axes span any direction (a valid, loose bound)
        {
            for (int k = 0; k < 3; ++k)
            {
                mapping.slab[m][k] = k;
                mapping.coef[m][k] = u[k];
            }
            continue;
        }
        for (int k = 0; k < 3; ++k)
        {
            mapping.slab[m][k] = best->slab[k];
            mapping.coef[m][k] = best->sign[k] * bestCoef[k];
        }
    }
    return mapping;
}

namespace
{

template <int K>
double magnitudeOf(const KDop<K> &d)
{
    double m = 0.0;
    for (int i = 0; i < K / 2; ++i)
        m = std::max({m, std::abs(d.lo[i]), std::abs(d.hi[i])});
    return m;
}
}  // namespace

template <int K>
const std::array<Vec3, K / 2> &kdopDirections()
{
    static const std::array<Vec3, K / 2> dirs = makeDirections<K>();
    return dirs;
}

template <int K>
KDop<K> KDop<K>::tight(const std::vector<Vec3> &points)
{
    const auto &dirs = kdopDirections<K>();
    KDop d;
    d.lo.fill(std::numeric_limits<double>::infinity());
    d.hi.fill(-std::numeric_limits<double>::infinity());
    for (const Vec3 &p : points)
        for (int i = 0; i < kSlabs; ++i)
        {
            const double s = dirs[i].dot(p);
            d.lo[i] = std::min(d.lo[i], s);
            d.hi[i] = std::max(d.hi[i], s);
        }
    return d;
}

template <int K>
KDop<K> KDop<K>::tightUnion(const KDop &a, const KDop &b)
{
    KDop d;
    for (int i = 0; i < kSlabs; ++i)
    {
        d.lo[i] = std::min(a.lo[i], b.lo[i]);
        d.hi[i] = std::max(a.hi[i], b.hi[i]);
    }
    return d;
}

template <int K>
KDop<K> KDop<K>::withMargin(KDop d)
{
    // The first three directions are the axes, exactly: their slabs are the points' extreme
    // coordinates, so this is the largest coordinate magnitude of the points.
    double magnitude = 0.0;
    for (int i = 0; i < 3; ++i)
        magnitude = std::max({magnitude, std::fabs(d.lo[i]), std::fabs(d.hi[i])});
    const double margin = 1e-9 * magnitude + 1e-300;
    for (int i = 0; i < kSlabs; ++i)
    {
        d.lo[i] -= margin;
        d.hi[i] += margin;
    }
    d.center = 0.5 * Vec3(d.lo[0] + d.hi[0], d.lo[1] + d.hi[1], d.lo[2] + d.hi[2]);
    return d;
}

template <int K>
KDop<K> KDop<K>::fit(const std::vector<Vec3> &points)
{
    return withMargin(tight(points));
}

template <int K>
bool KDop<K>::contains(const Vec3 &p) const
{
    const auto &dirs = kdopDirections<K>();
    for (int i = 0; i < kSlabs; ++i)
    {
        const double s = dirs[i].dot(p);
        if (s < lo[i] || s > hi[i])
            return false;
    }
    return true;
}

template <int K>
KDop<K> KDop<K>::transformed(const RigidTransform &pose) const
{
    return transformed(KDopRotation<K>::of(pose));
}

template <int K>
KDop<K> KDop<K>::transformed(const KDopRotation<K> &comb) const
{
    const auto &dirs = kdopDirections<K>();
    const RigidTransform &pose = comb.pose;
    // Rounding in R^T n_m, the coefficients and the sums below is a few 1e-16 of the terms
    // (coefficients are at most ~2); 1e-12 of the magnitudes covers it many times.
    const double local = magnitudeOf(*this);
    KDop out;
    for (int m = 0; m < kSlabs; ++m)
    {
        double up = 0.0, down = 0.0;
        for (int k = 0; k < 3; ++k)
        {
            const double c = comb.coef[m][k];
            const int i = comb.slab[m][k];
            const double toHi = c * hi[i], toLo = c * lo[i];  // branch-free: signs vary per rotation
            up += std::max(toHi, toLo);
            down += std::min(toHi, toLo);
        }
        const double shift = dirs[m].dot(pose.translation);
        const double pad = 1e-12 * (4.0 * local + std::abs(shift)) + 1e-300;
        out.lo[m] = shift + down - pad;
        out.hi[m] = shift + up + pad;
    }
    // The sphere of the hierarchy is about the mapped centre (it still holds the content).
    out.center = pose.apply(center);
    return out;
}

template <int K>
std::vector<Vec3> KDop<K>::vertices() const
{
    const auto &dirs = kdopDirections<K>();
    std::vector<Vec3> normals;
    std::vector<double> offsets;
    for (int i = 0; i < kSlabs; ++i)
    {
        normals.push_back(dirs[i]);
        offsets.push_back(hi[i]);
        normals.push_back(-dirs[i]);
        offsets.push_back(-lo[i]);
    }
    const double tol = 1e-12 * magnitudeOf(*this) + 1e-300;
    std::vector<Vec3> out;
    const int n = int(normals.size());
    for (int a = 0; a < n; ++a)
        for (int b = a + 1; b < n; ++b)
            for (int c = b + 1; c < n; ++c)
            {
                Mat3 m;
                m << normals[a].transpose(), normals[b].transpose(), normals[c].transpose();
                if (std::abs(m.determinant()) < 1e-9)
                    continue;
                const Vec3 p = m.inverse() * Vec3(offsets[a], offsets[b], offsets[c]);
                bool inside = true;
                for (int j = 0; j < n && inside; ++j)
                    inside = normals[j].dot(p) <= offsets[j] + 16 * tol;
                if (inside &&
                    std::none_of(out.begin(), out.end(), [&](const Vec3 &q) { return (q - p).norm() <= 16 * tol; }))
                    out.push_back(p);
            }
    return out;
}

template <int K>
std::vector<std::vector<Vec3>> KDop<K>::faces() const
{
    const auto &dirs = kdopDirections<K>();
    const std::vector<Vec3> corners = vertices();
    const double tol = 64e-12 * magnitudeOf(*this) + 1e-300;
    std::vector<std::vector<Vec3>> out;
    for (int i = 0; i < kSlabs; ++i)
        for (int s = 0; s < 2; ++s)
        {
            const Vec3 normal = s == 0 ? dirs[i] : Vec3(-dirs[i]);
            const double offset = s == 0 ? hi[i] : -lo[i];
            std::vector<Vec3> face;
            for (const Vec3 &p : corners)
                if (std::abs(normal.dot(p) - offset) <= tol)
                    face.push_back(p);
            if (face.size() < 3)
                continue;
            Vec3 mid = Vec3::Zero();
            for (const Vec3 &p : face)
                mid += p;
            mid /= double(face.size());
            const Vec3 u = normal.unitOrthogonal(), v = normal.cross(u);
            std::sort(face.begin(), face.end(), [&](const Vec3 &a, const Vec3 &b) {
                return std::atan2(v.dot(a - mid), u.dot(a - mid)) < std::atan2(v.dot(b - mid), u.dot(b - mid));
            });
            out.push_back(std::move(face));
        }
    return out;
}

template <int K>
double KDop<K>::volume() const
{
    const std::vector<Vec3> corners = vertices();
    if (corners.size() < 4)
        return 0.0;
    Vec3 inner = Vec3::Zero();
    for (const Vec3 &p : corners)
        inner += p;
    inner /= double(corners.size());
    // Sum of pyramids from an inner point over the faces (each face a convex polygon).
    double sum = 0.0;
    for (const auto &face : faces())
    {
        Vec3 area = Vec3::Zero();
        for (std::size_t k = 1; k + 1 < face.size(); ++k)
            area += (face[k] - face[0]).cross(face[k + 1] - face[0]);
        sum += std::abs(area.dot(face[0] - inner)) / 6.0;
    }
    return sum;
}

template <int K>
bool kdopsOverlap(const KDop<K> &a, const KDop<K> &b, double tolerance)
{
    for (int i = 0; i < K / 2; ++i)
        if (a.lo[i] > b.hi[i] + tolerance || b.lo[i] > a.hi[i] + tolerance)
            return false;
    return true;
}

template <int K>
double kdopDistanceLowerBound(const KDop<K> &a, const KDop<K> &b, double tolerance)
{
    double gap = 0.0;
    for (int i = 0; i < K / 2; ++i)
        gap = std::max({gap, a.lo[i] - b.hi[i], b.lo[i] - a.hi[i]});
    return std::max(0.0, gap - tolerance);
}

#define HCD_KDOP(K)                                                                                                    \
    template struct KDop<K>;                                                                                           \
    template struct KDopRotation<K>;                                                                                   \
    template const std::array<Vec3, K / 2> &kdopDirections<K>();                                                       \
    template bool kdopsOverlap<K>(const KDop<K> &, const KDop<K> &, double);                                           \
    template double kdopDistanceLowerBound<K>(const KDop<K> &, const KDop<K> &, double);
HCD_KDOP(14)
HCD_KDOP(18)
HCD_KDOP(26)
#undef HCD_KDOP
}  // namespace hcd
