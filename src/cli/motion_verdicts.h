// SPDX-License-Identifier: BSD-3-Clause
// check-motion's answers, one line per motion, as both its single-robot and scene forms print them.
#pragma once

#include <cstddef>
#include <optional>
#include <sstream>
#include <string>

namespace hcd::cli
{
/// check-motion's answers as they are printed, one line per motion: "1" (free), "0" (verdict
/// only) or "0 T" (T the last valid fraction); the free ones counted, the first blocked one kept.
class MotionVerdicts
{
public:
    explicit MotionVerdicts(bool verdictOnly);
    /// The next motion is free, or blocked with `[0, lastValid]` proven free.
    void add(bool free, double lastValid);
    /// The lines on stdout, then "checked N motions with 'CHECKER': F free, C colliding; mean
    /// X us per motion" and `detail` (e.g. " (...)") on stderr.
    void print(const std::string &checkerName, double seconds, const std::string &detail = {}) const;
    std::optional<std::size_t> firstBlocked() const { return firstBlocked_; }

private:
    bool verdictOnly_;
    std::ostringstream lines_;
    std::size_t motions_ = 0, free_ = 0;
    std::optional<std::size_t> firstBlocked_;
};
}  // namespace hcd::cli
