// SPDX-License-Identifier: BSD-3-Clause
#pragma once
#include <ompl/base/State.h>
#include <ompl/base/StateSpace.h>

#include <array>
#include <optional>

namespace hcd
{

/// A pose as plain numbers, for bounding OMPL's distance between poses from below.
/// Planar: x, y (world units), yaw (radians). Spatial: x, y, z (world units), then the unit
/// quaternion x, y, z, w, its sign chosen so that w >= 0 (OMPL's SO(3) distance is the same for q
/// and -q).
struct PoseCoordinates
{
    std::array<double, 7> values{};
    /// false when a value is not finite.
    bool finite = true;
    /// false when the rotation is not one the bound is sound for: a quaternion whose norm is off
    /// 1 by more than 1e-9, a yaw outside [-pi, pi]. A query's rotation is then bounded by 0; an
    /// element's is not bounded at all (PoseNearestNeighbors measures it on every search).
    bool rotationBoundable = true;
};

/// OMPL's metric on SE(2) or SE(3), as a lower bound over boxes of coordinates. OMPL measures
/// w_t * |t1 - t2| + w_r * angle, the angle being the wrapped yaw difference (SO(2)) or
/// acos|q1 . q2| (SO(3)); the bound is never above that value, so a search that prunes by it
/// finds what a search of every element finds.
class PoseMetric
{
public:
    /// The metric of space when it is OMPL's SE2StateSpace or SE3StateSpace itself (not a class
    /// derived from them, which may measure differently); nullopt for any other space.
    static std::optional<PoseMetric> of(const ompl::base::StateSpace &space);

    bool planar() const { return planar_; }
    /// 3 (planar) or 7 (spatial).
    int dimensions() const { return planar_ ? 3 : 7; }
    /// The coordinates of a state of the space this metric was made from.
    PoseCoordinates coordinates(const ompl::base::State *state) const;
    /// A lower bound on the distance from p to any pose whose coordinates lie in [low, high]
    /// (both of dimensions() values) and whose rotation is boundable.
    double lowerBound(const PoseCoordinates &p, const double *low, const double *high) const;
    /// dimensions() weights that make a coordinate's spread comparable with the others' when
    /// choosing where to split: the translation weight, then the rotation's.
    double spreadWeight(int dimension) const;

private:
    PoseMetric(bool planar, double translationWeight, double rotationWeight)
        : planar_(planar), translationWeight_(translationWeight), rotationWeight_(rotationWeight)
    {
    }

    bool planar_;
    double translationWeight_;
    double rotationWeight_;
};

}  // namespace hcd
