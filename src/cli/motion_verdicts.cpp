// SPDX-License-Identifier: BSD-3-Clause
#include "motion_verdicts.h"

#include <iomanip>
#include <iostream>
#include <limits>

namespace hcd::cli
{
MotionVerdicts::MotionVerdicts(bool verdictOnly) : verdictOnly_(verdictOnly)
{
    lines_ << std::setprecision(std::numeric_limits<double>::max_digits10);
}

void MotionVerdicts::add(bool free, double lastValid)
{
    const std::size_t index = motions_++;
    if (free)
    {
        ++free_;
        lines_ << "1\n";
        return;
    }
    if (!firstBlocked_)
        firstBlocked_ = index;
    if (verdictOnly_)
        lines_ << "0\n";
    else
        lines_ << "0 " << lastValid << '\n';
}

void MotionVerdicts::print(const std::string &checkerName, double seconds, const std::string &detail) const
{
    std::cout << lines_.str() << std::flush;
    std::cerr << "checked " << motions_ << " motions with '" << checkerName << "': " << free_ << " free, "
              << motions_ - free_ << " colliding; mean " << (motions_ == 0 ? 0.0 : 1e6 * seconds / double(motions_))
              << " us per motion" << detail << '\n';
}
}  // namespace hcd::cli
