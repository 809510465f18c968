// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/bv/obb.h"

#include <Eigen/Eigenvalues>

#include <cmath>

namespace hcd
{
Obb Obb::fitWithAxes(const std::vector<Vec3> &points, const Mat3 &axes)
{
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
    Vec3 hi = -lo;
    double magnitude = 0.0;
    for (const Vec3 &p : points)
    {
        const Vec3 local = axes.transpose() * p;
        lo = lo.cwiseMin(local);
        hi = hi.cwiseMax(local);
        magnitude = std::max(magnitude, p.cwiseAbs().maxCoeff());
    }
    Obb box;
    box.axes = axes;
    box.center = axes * (0.5 * (lo + hi));
    const double margin = 1e-9 * magnitude + 1e-300;
    box.halfExtents = (0.5 * (hi - lo)).array() + margin;
    return box;
}

Obb Obb::fit(const std::vector<Vec3> &points)
{
    // One pass for the mean and the axis-aligned box (what fitWithAxes gives for the identity), a
    // second for the covariance about the mean (two passes: no cancellation far from the origin).
    Vec3 mean = Vec3::Zero();
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
    Vec3 hi = -lo;
    double magnitude = 0.0;
    for (const Vec3 &p : points)
    {
        mean += p;
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
        magnitude = std::max(magnitude, p.cwiseAbs().maxCoeff());
    }
    mean /= double(points.size());
    Mat3 covariance = Mat3::Zero();
    for (const Vec3 &p : points)
    {
        const Vec3 d = p - mean;
        covariance.noalias() += d * d.transpose();
    }

    Obb best;
    best.axes = Mat3::Identity();
    best.center = 0.5 * (lo + hi);
    best.halfExtents = (0.5 * (hi - lo)).array() + (1e-9 * magnitude + 1e-300);
    Eigen::SelfAdjointEigenSolver<Mat3> solver(covariance);
    if (solver.info() == Eigen::Success && solver.eigenvectors().allFinite())
    {
        Mat3 axes = solver.eigenvectors();
        axes.col(2) = axes.col(0).cross(axes.col(1)).normalized();  // exactly right-handed, orthonormal
        axes.col(1) = axes.col(2).cross(axes.col(0)).normalized();
        axes.col(0).normalize();
        const Obb principal = fitWithAxes(points, axes);
        if (principal.volume() < best.volume())
            best = principal;
    }
    return best;
}

bool Obb::contains(const Vec3 &p) const
{
    const Vec3 local = axes.transpose() * (p - center);
    return (local.cwiseAbs().array() <= halfExtents.array()).all();
}

bool obbsOverlap(const Obb &a, const RigidTransform &worldFromA, const Obb &b, double tolerance)
{
    return obbsOverlap(a.transformed(worldFromA), b, tolerance);
}

bool obbsOverlap(const Obb &a, const Obb &b, double tolerance)
{
    // Express a's axes and centre in b's box frame: R = B^T A, t = B^T (ca - cb), R row by row, as
    // b's face axes need them: a pair most often separates along one of those, before the rest of
    // R is needed.
    const Vec3 t = b.axes.transpose() * (a.center - b.center);
    const Vec3 &ea = a.halfExtents, &eb = b.halfExtents;
    Mat3 r, absR;
    for (int i = 0; i < 3; ++i)
    {
        r.row(i) = b.axes.col(i).transpose() * a.axes;
        // The small constant keeps near-parallel edge-cross axes (which degenerate) conservative.
        absR.row(i) = r.row(i).cwiseAbs().array() + 1e-12;
        if (std::fabs(t[i]) > eb[i] + absR.row(i).dot(ea) + tolerance)
            return false;  // b's face axis i
    }
    // a's face axes.
    for (int j = 0; j < 3; ++j)
        if (std::fabs(t.dot(r.col(j))) > ea[j] + absR.col(j).dot(eb) + tolerance)
            return false;
    // Cross products of b's axis i with a's axis j.
    for (int i = 0; i < 3; ++i)
    {
        const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
        for (int j = 0; j < 3; ++j)
        {
            const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
            const double ra = ea[j1] * absR(i, j2) + ea[j2] * absR(i, j1);
            const double rb = eb[i1] * absR(i2, j) + eb[i2] * absR(i1, j);
            const double d = t[i2] * r(i1, j) - t[i1] * r(i2, j);
            if (std::fabs(d) > ra + rb + tolerance)
                return false;
        }
    }
    return true;
}

double obbDistanceLowerBound(const Obb &a, const RigidTransform &worldFromA, const Obb &b, double tolerance)
{
    return obbDistanceLowerBound(a.transformed(worldFromA), b, tolerance);
}

double obbDistanceLowerBound(const Obb &a, const Obb &b, double tolerance)
{
    return obbDistanceLowerBound(a, b, tolerance, std::numeric_limits<double>::infinity());
}

double obbDistanceLowerBound(const Obb &a, const Obb &b, double tolerance, double enough)
{
    // Sums of three products are written out, added left to right, so that the SIMD lanes
    // (lanesDistanceLowerBound) compute the same numbers.
    const auto sum3 = [](double x0, double y0, double x1, double y1, double x2, double y2) {
        return (x0 * y0 + x1 * y1) + x2 * y2;
    };
    const Vec3 offset = a.center - b.center;
    Mat3 r, absR;
    Vec3 t;
    for (int i = 0; i < 3; ++i)
    {
        t[i] = sum3(b.axes(0, i), offset[0], b.axes(1, i), offset[1], b.axes(2, i), offset[2]);
        for (int j = 0; j < 3; ++j)
        {
            r(i, j) = sum3(b.axes(0, i), a.axes(0, j), b.axes(1, i), a.axes(1, j), b.axes(2, i), a.axes(2, j));
            absR(i, j) = std::fabs(r(i, j));
        }
    }
    const Vec3 &ha = a.halfExtents, &hb = b.halfExtents;
    // Along each frame's three face axes: the gaps on orthonormal axes add in squares, since every
    // pair of points differs by at least each positive gap along its axis.
    double inB = 0.0, inA = 0.0;
    for (int i = 0; i < 3; ++i)
    {
        const double gapB =
            std::max(0.0, std::fabs(t[i]) - hb[i] - sum3(absR(i, 0), ha[0], absR(i, 1), ha[1], absR(i, 2), ha[2]));
        const double along = sum3(t[0], r(0, i), t[1], r(1, i), t[2], r(2, i));
        const double gapA =
            std::max(0.0, std::fabs(along) - ha[i] - sum3(absR(0, i), hb[0], absR(1, i), hb[1], absR(2, i), hb[2]));
        inB += gapB * gapB;
        inA += gapA * gapA;
    }
    double gap = std::sqrt(std::max(inA, inB));
    if (gap - tolerance >= enough)
        return gap - tolerance;
    // The axis through the two centres, where boxes far apart in a skew pose are nearly farthest.
    const double centres = std::sqrt(sum3(t[0], t[0], t[1], t[1], t[2], t[2]));
    if (centres > 0.0)
    {
        const Vec3 axis = t * (1.0 / centres);  // b's frame (one division, as the SIMD lanes do)
        const double widthB = sum3(hb[0], std::fabs(axis[0]), hb[1], std::fabs(axis[1]), hb[2], std::fabs(axis[2]));
        double widthA = 0.0;
        for (int j = 0; j < 3; ++j)
        {
            const double turned = sum3(r(0, j), axis[0], r(1, j), axis[1], r(2, j), axis[2]);  // a's frame
            widthA = j == 0 ? ha[j] * std::fabs(turned) : widthA + ha[j] * std::fabs(turned);
        }
        gap = std::max(gap, centres - widthB - widthA);
        if (gap - tolerance >= enough)
            return gap - tolerance;
    }
    // The nine edge-edge axes b_i x a_j (in b's frame e_i x r.col(j)), of length sin(angle): the
    // gap along an unnormalised axis L is (|t . L| - a's and b's half widths along L) / |L|. Flat
    // boxes (one triangle each) in skew poses are often farthest apart along one of these. The
    // largest is found by comparing squares (positive excesses only), so that only the winner is
    // divided and rooted: every axis's gap is a lower bound, and a comparison that rounds,
    // overflows or underflows can only pick a smaller one.
    double bestExcess = gap, bestLengthSquared = 1.0;
    for (int i = 0; i < 3; ++i)
    {
        const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
        for (int j = 0; j < 3; ++j)
        {
            const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
            const double lengthSquared = 1.0 - r(i, j) * r(i, j);
            if (!(lengthSquared > 1e-6))
                continue;  // nearly parallel edges: the face axes bound this direction already
            const double along = std::fabs(t[i2] * r(i1, j) - t[i1] * r(i2, j));
            const double halfWidths =
                hb[i1] * absR(i2, j) + hb[i2] * absR(i1, j) + ha[j1] * absR(i, j2) + ha[j2] * absR(i, j1);
            const double excess = along - halfWidths;
            if (excess > 0.0 && excess * excess * bestLengthSquared > bestExcess * bestExcess * lengthSquared)
            {
                bestExcess = excess;
                bestLengthSquared = lengthSquared;
            }
        }
    }
    gap = std::max(gap, bestExcess / std::sqrt(bestLengthSquared));
    return std::max(0.0, gap - tolerance);
}
}  // namespace hcd
