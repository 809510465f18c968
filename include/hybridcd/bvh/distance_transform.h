// SPDX-License-Identifier: BSD-3-Clause
// Exact squared Euclidean distance transform of a grid of seed cells: for every cell, the squared
// distance (in cells) from its centre to the nearest seed cell's centre. The clearance grid's
// distance bounds come from it (bvh/clearance_grid.h).
#pragma once

#include <cstdint>
#include <vector>

namespace hcd
{
/// What the brute-force transform gives a cell when the grid holds no seed at all (the fast one
/// gives its cap).
inline constexpr double kNoSeedSquaredDistance = 1e20;

/// `seeds` holds nx * ny * nz flags, x fastest (index (z * ny + y) * nx + x), nonzero for a seed.
/// Returns, per cell, the squared distance in cells between its centre and the nearest seed's
/// centre (an integer), or `cap` where that is `cap` or more (and everywhere without seeds).
/// Separable: nearest seeds along x by two scans, then Felzenszwalb and Huttenlocher's lower
/// envelope of parabolas along y and along z, over the cells already reached only. The cap is what
/// lets the values live in 16 or 32 bits: the clearance grid's codes saturate anyway, and only
/// parabolas whose apex lies below the cap enter an envelope. Instantiated for std::uint16_t and
/// std::uint32_t.
template <class Value>
std::vector<Value> squaredDistanceTransform(const std::vector<std::uint8_t> &seeds, int nx, int ny, int nz, Value cap);

/// The same by brute force: every cell against every seed. The reference for the above in tests.
std::vector<double> squaredDistanceTransformBruteForce(const std::vector<std::uint8_t> &seeds, int nx, int ny, int nz);
}  // namespace hcd
