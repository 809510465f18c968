// SPDX-License-Identifier: BSD-3-Clause
// Minimum-volume enclosing ellipsoids (MVEE) of point sets, with an optimality certificate.
#pragma once

#include "hybridcd/bv/ellipsoid.h"

#include <cstddef>
#include <vector>

namespace hcd
{
struct MveeOptions
{
    /// Stop when the certificate `MveeResult::optimalityGap` is at most this, i.e. when the fitted
    /// ellipsoid's volume is provably within (1 + tolerance)^(d/2) of the minimum (d = 3, or the
    /// dimension of the points' affine hull for flat sets). Must be > 0.
    double tolerance = 1e-3;
    /// Cap on Frank–Wolfe / away steps; when reached the result is still valid (every point inside),
    /// and its gap says how close to optimal it is.
    int maxIterations = 2000;
    /// Start from the vertices of the convex hull (Qhull) instead of all points.
    bool useHullCandidates = true;
    /// Drop points that provably cannot support the optimal ellipsoid (Harman–Pronzato test).
    bool cardinalityReduction = true;
};

struct MveeResult
{
    /// The fitted ellipsoid, after the exact-containment inflation: every input point p satisfies
    /// ellipsoid.contains(p) with slack 0.
    Ellipsoid ellipsoid;
    /// Certificate of near-optimality: max_i (x_i - c)^T S^{-1} (x_i - c) / d - 1 over all input points,
    /// where c and S are the weighted mean and covariance of the final design weights (Khachiyan's
    /// ellipsoid is S^{-1}/d). By weak duality the fitted ellipsoid's volume is within (1 + gap)^(d/2) of the
    /// minimum (up to the tiny containment margins). For flat or collinear sets d is the dimension of the
    /// affine hull and the statement is about the in-hull section; 0 for a single point.
    double optimalityGap = 0.0;
    /// Factor (>= 1) by which Khachiyan's shape S^{-1}/d was divided so that every point is inside
    /// (semi-axes grow by its square root); 1 + optimalityGap up to the containment margins.
    double inflation = 1.0;
    int iterations = 0;          ///< Frank–Wolfe plus away steps taken
    std::size_t candidates = 0;  ///< points the iteration started from (hull vertices, or all points)
    std::size_t removed = 0;     ///< candidates eliminated by cardinality reduction
    int dimension = 3;           ///< dimension of the points' affine hull as detected (0 to 3)
};

/// Minimum-volume enclosing ellipsoid of `points` (any count >= 1; all coordinates finite, else
/// std::invalid_argument). First-order Khachiyan / Todd–Yildirim method with Kumar–Yildirim
/// initialisation and away steps (WA-TY) on the lifted points (x, 1), run in whitened coordinates so
/// that the result does not depend on the set's position or scale, accelerated by Harman–Pronzato
/// cardinality reduction. Sets whose affine hull is a plane, line or point (to about 1e-9 of their
/// extent) are fitted in that hull and given a small thickness (about 1e-9 of the extent, or 1e-12
/// absolute for a single point) in the missing directions, so the result is always positive definite.
MveeResult fitMinimumVolumeEllipsoid(const std::vector<Vec3> &points, const MveeOptions &options = {});
}  // namespace hcd
