// SPDX-License-Identifier: BSD-3-Clause
// Ellipsoids as bounding volumes: containment, the Perram–Wertheim overlap test and distance.
#pragma once

#include "hybridcd/geometry/rigid_transform.h"

namespace hcd
{
/// The solid ellipsoid E(c, A) = {x : (x - c)^T A (x - c) <= 1}, A symmetric positive definite.
/// Lengths are in the units of the coordinates, all members in one frame.
///
/// The principal form (`axes`, `semiAxes`) is the authoritative one: A = axes diag(1/semiAxes^2) axes^T.
/// Every query below evaluates through it, because very thin ellipsoids (such as those fitted to flat
/// point sets, with semi-axis ratios near 1e-9) have a shape matrix too ill-conditioned to be used
/// directly. `shape` is kept in step by the factories; callers that edit members must keep both forms
/// consistent (use fromShape or fromAxes).
struct Ellipsoid
{
    Vec3 center = Vec3::Zero();
    Mat3 shape = Mat3::Identity();  ///< A
    Mat3 axes = Mat3::Identity();   ///< orthonormal columns: principal directions of A
    Vec3 semiAxes = Vec3::Ones();   ///< semi-axis length along each column of `axes` (1/sqrt of A's eigenvalues)

    /// From a centre and a shape matrix A (precondition: symmetric positive definite; only its symmetric
    /// part is used). Fills the principal form by an eigen-decomposition.
    static Ellipsoid fromShape(const Vec3 &center, const Mat3 &shape);

    /// From a centre, orthonormal principal directions (columns) and positive semi-axis lengths.
    static Ellipsoid fromAxes(const Vec3 &center, const Mat3 &axes, const Vec3 &semiAxes);

    /// Radius of the smallest ball about `center` holding the ellipsoid: the largest semi-axis.
    double boundingRadius() const { return semiAxes.maxCoeff(); }

    /// 4/3 pi times the product of the semi-axes.
    double volume() const;

    /// (p - c)^T A (p - c), evaluated as |diag(1/semiAxes) axes^T (p - c)|^2; <= 1 means inside.
    double normalizedRadiusSquared(const Vec3 &p) const;

    /// True when (p - c)^T A (p - c) <= 1 + slack (inclusive; slack 0 is the exact test as evaluated).
    bool contains(const Vec3 &p, double slack = 0.0) const { return normalizedRadiusSquared(p) <= 1.0 + slack; }

    /// max over x in E of direction . (x - c) = sqrt(n^T A^{-1} n): the support function less n . c.
    /// `direction` need not be unit length (the value scales with it).
    double supportRadius(const Vec3 &direction) const
    {
        return semiAxes.cwiseProduct(axes.transpose() * direction).norm();
    }

    /// max over x in E of direction . x = direction . c + supportRadius(direction).
    double support(const Vec3 &direction) const { return direction.dot(center) + supportRadius(direction); }

    /// The same ellipsoid mapped by `pose`: c' = pose.apply(c), A' = R A R^T (semi-axes unchanged).
    Ellipsoid transformed(const RigidTransform &pose) const;

    /// A^{-1} = axes diag(semiAxes^2) axes^T, which stays accurate however thin the ellipsoid is.
    Mat3 inverseShape() const;
};

/// Overlap test for two ellipsoids given in one frame. Conservative in the one direction that matters:
/// it never reports "disjoint" (false) for ellipsoids that share a point. It reports disjoint only with
/// a certificate: a bounding-sphere gap, or a Perram–Wertheim contact value F(l) > 1 + 1e-9 at some
/// l in [0, 1] whose normal ((1-l) A^{-1} + l B^{-1})^{-1} (cb - ca) is then checked to separate the two
/// ellipsoids through their support functions with a 1e-9 relative margin. Rounding can therefore only
/// turn "disjoint" into "overlap", for pairs that scaling both about their centres by 1 + 1e-9 would
/// make touch. Stable for thin ellipsoids (semi-axis ratios down to 1e-9), and symmetric: (a, b) and
/// (b, a) always get the same answer. A few microseconds per call. `slack` (>= 0, absolute) widens
/// what counts as overlap to every pair closer than it, for rounding elsewhere or proximity queries.
bool ellipsoidsOverlap(const Ellipsoid &a, const Ellipsoid &b, double slack = 0.0);

/// A lower bound on the Euclidean distance between two ellipsoids in one frame (0 when
/// ellipsoidsOverlap says they overlap). It is the gap along the best separating direction found
/// (NLopt L-BFGS over unit normals, started at the Perram–Wertheim normal), so any direction yields a
/// valid bound; the result never exceeds the true distance by more than rounding (about 1e-14
/// relative), and in tests it is within 1e-11 relative of the true distance.
double ellipsoidDistance(const Ellipsoid &a, const Ellipsoid &b);
}  // namespace hcd
