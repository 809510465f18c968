// SPDX-License-Identifier: BSD-3-Clause
// What `solve` shows while it plans: a line a second on stderr (or one updating bar when stderr is
// a terminal) with the elapsed time, the planner's iterations, the collision checks and the best
// cost so far, then a summary line. Everything shown is read from atomic counters, written by the
// planning thread (and OMPL's parallel planners' threads) and read by the reporting thread.
#pragma once

#include "hybridcd/ompl/planning_problem.h"

#include <ompl/base/PlannerTerminationCondition.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <iosfwd>
#include <mutex>
#include <string>
#include <thread>

namespace hcd::cli
{
/// Counters of one planning run, shared between the planner's threads and the reporter.
struct SolveCounters
{
    /// Evaluations of the termination condition: OMPL's planners evaluate it once per iteration
    /// of their main loop (a few evaluate it more often).
    std::atomic<std::uint64_t> iterations{0};
    /// Improved solutions reported by an optimizing planner, and the cost of the last one.
    std::atomic<std::uint64_t> improvements{0};
    std::atomic<double> bestCost{0.0};
};

/// Reports a planning run while it lasts. start() installs the counting hooks and starts the
/// reporting thread; the termination condition it returns must be passed to the planner's solve();
/// finish() stops the thread (also done by the destructor) and prints the summary line.
class SolveProgress
{
public:
    struct Options
    {
        double timeLimit = 10.0;     ///< seconds, as given to solve
        bool quiet = false;          ///< nothing is printed at all
        bool terminal = false;       ///< one bar rewritten in place instead of a line per period
        double periodSeconds = 1.0;  ///< between two lines (a bar is redrawn 5 times as often)
    };

    SolveProgress(PlanningProblem &planning, std::ostream &out, Options options);
    ~SolveProgress();
    SolveProgress(const SolveProgress &) = delete;
    SolveProgress &operator=(const SolveProgress &) = delete;

    /// The termination condition to plan with: the time limit, counting iterations.
    ompl::base::PlannerTerminationCondition start();

    /// Stops reporting and prints "solve: OUTCOME after T s: ..." with the final counts.
    void finish(const std::string &outcome);

    const SolveCounters &counters() const { return counters_; }

private:
    std::string status() const;
    void report();

    PlanningProblem &planning_;
    std::ostream &out_;
    Options options_;
    SolveCounters counters_;
    std::chrono::steady_clock::time_point start_;
    std::mutex mutex_;
    std::condition_variable wake_;
    bool stop_ = false;
    std::thread reporter_;
};
}  // namespace hcd::cli
