// SPDX-License-Identifier: BSD-3-Clause
#pragma once
#include <ompl/base/State.h>
#include <ompl/base/StateSpace.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
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
    /// 1 by more than 1e-9, a yaw outside [-pi, pi]. PoseNearestNeighbors measures such an element
    /// on every search, and such a query against every element.
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
    /// derived from them, which may measure differently); nullopt for any other space. The
    /// subspace weights are read now: a later setSubspaceWeight on the space is not seen.
    static std::optional<PoseMetric> of(const ompl::base::StateSpace &space);

    bool planar() const { return planar_; }
    /// 3 (planar) or 7 (spatial).
    int dimensions() const { return planar_ ? 3 : 7; }
    /// The coordinates of a state of the space this metric was made from.
    PoseCoordinates coordinates(const ompl::base::State *state) const;
    /// A lower bound on the distance from p to any pose whose coordinates lie in [low, high]
    /// (both of dimensions() values) and whose rotation is boundable. A search may pass the
    /// distance it no longer needs to beat as `enough`: once the translation's part reaches it,
    /// that part is returned (still a lower bound) without the rotation's.
    double lowerBound(const PoseCoordinates &p, const double *low, const double *high,
                      double enough = std::numeric_limits<double>::infinity()) const
    {
        bool rotationLeftOut = false;
        return bound<false>(p, low, high, enough, rotationLeftOut);
    }
    /// lowerBound, or its translation's part alone (`rotationLeftOut` set) when `enough` is
    /// finite and even the largest rotation part could not lift the bound to it: a search that
    /// compares the bound with `enough` then decides as with the whole bound, without the
    /// rotation's gaps and square root. Before comparing such a bound with a lower bar, the search
    /// completes it with lowerBound.
    double lowerBoundBelow(const PoseCoordinates &p, const double *low, const double *high, double enough,
                           bool &rotationLeftOut) const
    {
        rotationLeftOut = false;
        return bound<true>(p, low, high, enough, rotationLeftOut);
    }
    /// The most the rotation's part of a bound can add: the weight times the largest chord
    /// between unit quaternions (sqrt(2), for q or -q), or the largest wrapped yaw (pi).
    double largestRotationPart() const { return rotationWeight_ * (planar_ ? kPi : kSqrt2); }
    /// lowerBound(p, point, point) for each of `count` points (without its early return, which
    /// only changes values above `enough`), into bounds[0, count). p's rotation must be
    /// boundable. Branch-free.
    void pointLowerBounds(const PoseCoordinates &p, const std::array<double, 7> *points, std::size_t count,
                          double *bounds) const
    {
        const auto &v = p.values;
        if (planar_)
        {
            for (std::size_t k = 0; k < count; ++k)
            {
                const double *q = points[k].data();
                const double dx = v[0] - q[0], dy = v[1] - q[1];
                const double yaw = std::fabs(v[2] - q[2]);
                const double wrapped = yaw > kPi ? 2.0 * kPi - yaw : yaw;
                const double angle = std::max(wrapped - kWrappedYawSlack, 0.0);
                bounds[k] = (translationWeight_ * std::sqrt(dx * dx + dy * dy) + rotationWeight_ * angle) *
                            (1.0 - kWeightedSumSlack);
            }
            return;
        }
        for (std::size_t k = 0; k < count; ++k)
        {
            const double *q = points[k].data();
            const double dx = v[0] - q[0], dy = v[1] - q[1], dz = v[2] - q[2];
            double plus = 0.0, minus = 0.0;
            for (int i = 3; i < 7; ++i)
            {
                plus += (v[i] - q[i]) * (v[i] - q[i]);
                minus += (v[i] + q[i]) * (v[i] + q[i]);
            }
            const double angle = std::max(std::sqrt(std::min(plus, minus)) - kChordSlack, 0.0);
            bounds[k] = (translationWeight_ * std::sqrt(dx * dx + dy * dy + dz * dz) + rotationWeight_ * angle) *
                        (1.0 - kWeightedSumSlack);
        }
    }

    /// Whether the translation's part alone puts `point` beyond `enough`: the test lowerBound
    /// returns early on (squares compared with slack, only where they neither overflow nor
    /// underflow), so a pose it rules out has a lower bound above `enough` as well. It spares a
    /// search the rotation's part (two square roots) for most poses of a leaf.
    bool translationBeyond(const PoseCoordinates &p, const std::array<double, 7> &point, double enough) const
    {
        const auto &v = p.values;
        const double dx = v[0] - point[0], dy = v[1] - point[1], dz = planar_ ? 0.0 : v[2] - point[2];
        return squaredTranslationBeyond(dx * dx + dy * dy + dz * dz, enough);
    }

    /// Whether a gap of `gap` along one coordinate puts every pose beyond `enough` on its own: true
    /// only for a translation coordinate (a rotation's gap counts for q or -q), with slack for the
    /// rounding of the bound that would include it.
    bool coordinateGapBeyond(int dimension, double gap, double enough) const
    {
        return dimension < (planar_ ? 2 : 3) && enough > 0.0 && enough < 1e300 &&
               translationWeight_ * gap > enough * (1.0 + kSquaredComparisonSlack);
    }

    /// dimensions() weights that make a coordinate's spread comparable with the others' when
    /// choosing where to split: the translation weight, then the rotation's.
    double spreadWeight(int dimension) const;

    static constexpr double kPi = 3.14159265358979323846;

private:
    // lowerBound; with LeaveOutRotation, lowerBoundBelow.
    template <bool LeaveOutRotation>
    double bound(const PoseCoordinates &p, const double *low, const double *high, double enough,
                 bool &rotationLeftOut) const
    {
        const auto &v = p.values;
        double squared = 0.0;
        for (int i = 0; i < (planar_ ? 2 : 3); ++i)
        {
            const double g = intervalGap(v[i], low[i], high[i]);
            squared += g * g;
        }
        if (squaredTranslationBeyond(squared, enough))
            return enough * (1.0 + 0.1 * kSquaredComparisonSlack);
        const double translation = translationWeight_ * std::sqrt(squared);
        if (!p.rotationBoundable || translation >= enough)
            return translation * (1.0 - kWeightedSumSlack);
        if constexpr (LeaveOutRotation)
        {
            // Compared with slack, since largestRotationPart() is rounded too; a bound left
            // lower than it could be costs only pruning, never an answer. Not while nothing
            // bounds the search yet (enough infinite): the bound then only orders the boxes, and
            // boxes split along a rotation coordinate differ in their rotation part alone.
            if (enough < std::numeric_limits<double>::infinity() &&
                (translation + largestRotationPart()) * (1.0 + kSquaredComparisonSlack) < enough)
            {
                rotationLeftOut = true;
                return translation * (1.0 - kWeightedSumSlack);
            }
        }
        double angle = 0.0;
        if (planar_)
        {
            if (v[2] < low[2] || v[2] > high[2])
                angle = std::min(wrappedYawDifference(v[2], low[2]), wrappedYawDifference(v[2], high[2])) -
                        kWrappedYawSlack;
        }
        else
        {
            // For unit quaternions the chord min(|q1 - q2|, |q1 + q2|) = 2 sin(angle / 2) is at
            // most the angle, and the box's nearest point to q (or to -q) is at most the chord.
            double plus = 0.0;
            double minus = 0.0;
            for (int i = 3; i < 7; ++i)
            {
                const double g = intervalGap(v[i], low[i], high[i]);
                const double h = intervalGap(-v[i], low[i], high[i]);
                plus += g * g;
                minus += h * h;
            }
            angle = std::sqrt(std::min(plus, minus)) - kChordSlack;
        }
        return (translation + rotationWeight_ * std::max(angle, 0.0)) * (1.0 - kWeightedSumSlack);
    }
    static constexpr double kSqrt2 = 1.41421356237309504880;
    // OMPL's SO(3) distance is 0 where |q1 . q2| > 1 - 1e-9, i.e. below an angle of 4.5e-5 rad,
    // and quaternions whose norm is off 1 by 1e-9 move the angle by up to 6.3e-5 rad: the chord
    // bound gives up this much so that it stays below OMPL's value.
    static constexpr double kChordSlack = 2e-4;
    // The wrapped yaw difference is a subtraction and a comparison; its rounding is far below this.
    static constexpr double kWrappedYawSlack = 1e-9;
    // Rounding of the weighted sum.
    static constexpr double kWeightedSumSlack = 1e-12;
    // Rounding of a squared translation against a squared bar.
    static constexpr double kSquaredComparisonSlack = 1e-9;

    // Far enough by the translation alone, its squared length `squared` compared in squares (no
    // root): a value just above `enough` is then still below the distance. Only where the squares
    // neither underflow nor overflow, and `enough` is positive (a bound of `enough` itself would not
    // rule out).
    bool squaredTranslationBeyond(double squared, double enough) const
    {
        return enough > 1e-150 && enough < 1e150 &&
               translationWeight_ * translationWeight_ * squared > enough * enough * (1.0 + kSquaredComparisonSlack);
    }

    // Distance from v to the interval [low, high] (0 inside).
    static double intervalGap(double v, double low, double high)
    {
        const double outside = low - v > v - high ? low - v : v - high;
        return outside > 0.0 ? outside : 0.0;
    }

    // OMPL's SO(2) distance.
    static double wrappedYawDifference(double a, double b)
    {
        const double d = std::fabs(a - b);
        return d > kPi ? 2.0 * kPi - d : d;
    }

    PoseMetric(bool planar, double translationWeight, double rotationWeight)
        : planar_(planar),
          translationWeight_(translationWeight),
          rotationWeight_(rotationWeight)
    {
    }

    bool planar_;
    double translationWeight_;
    double rotationWeight_;
};

}  // namespace hcd
