// SPDX-License-Identifier: BSD-3-Clause
// A node volume holding both an oriented box and an ellipsoid: the set tested is their intersection.
#pragma once

#include "hybridcd/bv/ellipsoid.h"
#include "hybridcd/bv/obb.h"

namespace hcd
{
/// Both volumes enclose the same points, so two nodes are disjoint as soon as either pair of
/// volumes is; `EllipsoidFirst` picks which test runs first (the cheaper one to reject, measured in
/// bench/: the box test costs a few tens of nanoseconds, the ellipsoid test a few hundred).
template <bool EllipsoidFirst>
struct HybridVolume
{
    Obb box;
    Ellipsoid ellipsoid;
};
}  // namespace hcd
