// SPDX-License-Identifier: BSD-3-Clause
// OMPL.app's .path format: one pose per line, "x y z qx qy qz qw" (SE3) or "x y theta" (SE2).
#pragma once

#include "hybridcd/io/pose_codec.h"

#include <cstdint>
#include <iosfwd>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace hcd
{
/// The largest pose, motion or path file read: 256 MiB, over a million poses at full precision.
/// Larger files are refused rather than held in memory whole.
constexpr std::uintmax_t kMaxPoseFileBytes = std::uintmax_t(256) << 20;

/// The numbers of one pose line, in file order (7 for SE3, 3 for SE2): a pose row (pose_codec.h).
struct PoseRecord
{
    std::vector<double> values;
    int line = 0;
};

/// Reads poses; blank lines and '#' comments are skipped, columns after the pose are ignored, and
/// a UTF-8 byte-order mark at the start is skipped.
/// Throws InputError("FILE:LINE: ...") on a short line, a malformed or non-finite number, or a
/// quaternion whose norm is 0 or differs from 1 by more than kQuaternionNormTolerance; accepted
/// quaternions are normalised (normaliseRowQuaternion). A folder, a file that is not a regular file
/// (a device, a pipe), one that cannot be opened, or one above kMaxPoseFileBytes is an InputError
/// too (readInputFile, atomic_file.h).
/// With `robots` > 1 (a scene problem), each line holds that many poses one after the other, and
/// each record all of them.
std::vector<PoseRecord> readPoses(const std::string &path, bool planar, std::size_t robots = 1);

/// Parses pose lines held in memory, as readPoses does a file; errors name `sourceName`.
std::vector<PoseRecord> parsePoses(std::string_view text, const std::string &sourceName, bool planar,
                                   std::size_t robots = 1);

/// Reads motions: two poses per line (14 numbers in 3D, 6 in the plane). Throws as readPoses does.
/// With `robots` > 1, each state of a motion holds that many poses.
std::vector<std::pair<PoseRecord, PoseRecord>> readMotions(const std::string &path, bool planar,
                                                           std::size_t robots = 1);

/// Parses motion lines held in memory, as readMotions does a file; errors name `sourceName`.
std::vector<std::pair<PoseRecord, PoseRecord>> parseMotions(std::string_view text, const std::string &sourceName,
                                                            bool planar, std::size_t robots = 1);

/// Reads a path (one state per line, as readPoses does) as the motions between consecutive states:
/// each motion's two records keep their own lines. Throws InputError("FILE: ...") when the file
/// holds fewer than two states or when every line holds exactly two states (a motions file), and
/// as readPoses does otherwise.
std::vector<std::pair<PoseRecord, PoseRecord>> readPathMotions(const std::string &path, bool planar,
                                                               std::size_t robots = 1);

/// Writes one pose per line with full round-trip precision.
void writePoses(std::ostream &out, const std::vector<std::vector<double>> &poses);
}  // namespace hcd
