// SPDX-License-Identifier: BSD-3-Clause
#include "planner_watchdog.h"

#include <cstdio>
#include <cstdlib>
#include <sstream>

namespace hcd::cli
{
PlannerWatchdog::PlannerWatchdog(int exitStatus) : exitStatus_(exitStatus), thread_([this] { watch(); }) {}

PlannerWatchdog::~PlannerWatchdog()
{
    {
        const std::lock_guard<std::mutex> lock(mutex_);
        stopping_ = true;
    }
    changed_.notify_all();
    thread_.join();
}

void PlannerWatchdog::arm(const std::string &name, double timeLimit) { arm(name, timeLimit, graceSeconds(timeLimit)); }

void PlannerWatchdog::arm(const std::string &name, double timeLimit, double grace)
{
    {
        const std::lock_guard<std::mutex> lock(mutex_);
        name_ = name;
        timeLimit_ = timeLimit;
        grace_ = grace;
        const double seconds = timeLimit + grace;
        deadline_ = std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                           std::chrono::duration<double>(seconds));
    }
    changed_.notify_all();
}

void PlannerWatchdog::disarm()
{
    {
        const std::lock_guard<std::mutex> lock(mutex_);
        deadline_.reset();
    }
    changed_.notify_all();
}

void PlannerWatchdog::watch()
{
    std::unique_lock<std::mutex> lock(mutex_);
    while (!stopping_)
    {
        if (!deadline_)
        {
            changed_.wait(lock);
            continue;
        }
        if (changed_.wait_until(lock, *deadline_) != std::cv_status::timeout)
            continue;  // re-armed, disarmed or stopping: look again
        if (!deadline_ || std::chrono::steady_clock::now() < *deadline_)
            continue;
        // One write, so that the line is not interleaved with the planner's progress output.
        std::ostringstream message;
        message << "hybridcd: error: planner " << name_ << " did not return within " << grace_
                << " s after its limit of --time " << timeLimit_
                << " s (it samples in a loop that ignores the limit); nothing was written\n";
        std::fputs(message.str().c_str(), stderr);
        std::fflush(stderr);
        // The planner's thread cannot be stopped: the process ends here, without destructors that
        // would wait for it.
        std::_Exit(exitStatus_);
    }
}
}  // namespace hcd::cli
