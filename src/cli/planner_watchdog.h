// SPDX-License-Identifier: BSD-3-Clause
// Ends the process when a planner overruns its time limit by far. Some of OMPL 1.5's planners
// sample in loops that never look at the termination condition: SORRT*'s ordered batches once it
// holds a shortest possible path (start and goal joined by one free straight motion), and BIT*'s
// pruning of samples after an improved path. Such a run would never return, whatever --time says.
// The commands write their outputs whole after planning, so ending the process then loses nothing
// but the run.
#pragma once

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

namespace hcd::cli
{
class PlannerWatchdog
{
public:
    /// `exitStatus`: the process's status when a planner overruns.
    explicit PlannerWatchdog(int exitStatus);
    ~PlannerWatchdog();
    PlannerWatchdog(const PlannerWatchdog &) = delete;
    PlannerWatchdog &operator=(const PlannerWatchdog &) = delete;

    /// Watches planner `name`, given `timeLimit` seconds: if it is still planning after the limit
    /// and `grace` seconds more (graceSeconds(timeLimit) unless given), the process prints why on
    /// stderr and ends. Replaces any watch armed before.
    void arm(const std::string &name, double timeLimit);
    void arm(const std::string &name, double timeLimit, double grace);
    /// The planner returned.
    void disarm();

    /// How long past its limit a planner may run: 2 s and half the limit (OMPL's planners return
    /// within milliseconds of it; PRM joins its roadmap thread).
    static double graceSeconds(double timeLimit) { return 2.0 + 0.5 * timeLimit; }
    /// The same for a benchmark run, which also simplifies its path within the watch (OMPL's
    /// Benchmark, without a limit of its own): 30 s and the limit.
    static double benchmarkGraceSeconds(double timeLimit) { return 30.0 + timeLimit; }

private:
    void watch();

    const int exitStatus_;
    std::mutex mutex_;
    std::condition_variable changed_;
    std::optional<std::chrono::steady_clock::time_point> deadline_;
    std::string name_;
    double timeLimit_ = 0.0;
    double grace_ = 0.0;
    bool stopping_ = false;
    std::thread thread_;
};

/// Arms `watchdog` for one planner's run and disarms it when the scope ends (also by exception).
class WatchedRun
{
public:
    WatchedRun(PlannerWatchdog &watchdog, const std::string &name, double timeLimit) : watchdog_(watchdog)
    {
        watchdog_.arm(name, timeLimit);
    }
    ~WatchedRun() { watchdog_.disarm(); }
    WatchedRun(const WatchedRun &) = delete;
    WatchedRun &operator=(const WatchedRun &) = delete;

private:
    PlannerWatchdog &watchdog_;
};

/// setup.solve(termination) (OMPL's SimpleSetup, geometric or control) under a watch of
/// `timeLimit` seconds that ends the process with `exitStatus` if its planner overruns.
template <class Setup, class Termination>
auto solveWatched(Setup &setup, const Termination &termination, double timeLimit, int exitStatus)
{
    PlannerWatchdog watchdog(exitStatus);
    const WatchedRun run(watchdog, setup.getPlanner()->getName(), timeLimit);
    return setup.solve(termination);
}
}  // namespace hcd::cli
