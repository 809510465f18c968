// SPDX-License-Identifier: BSD-3-Clause
#include "solve_progress.h"

#include "hybridcd/ompl/continuous_motion_validator.h"

#include <algorithm>
#include <cstdio>
#include <ostream>
#include <sstream>

namespace hcd::cli
{
namespace
{
double secondsSince(std::chrono::steady_clock::time_point t)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

std::string fixed(double value, int digits)
{
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", digits, value);
    return text;
}
}  // namespace

SolveProgress::SolveProgress(PlanningProblem &planning, std::ostream &out, Options options)
    : planning_(planning),
      out_(out),
      options_(options)
{
}

SolveProgress::~SolveProgress()
{
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
    }
    wake_.notify_all();
    if (reporter_.joinable())
        reporter_.join();
    // The hook points at this object's counters: it must not outlive them.
    planning_.setup->getProblemDefinition()->setIntermediateSolutionCallback(nullptr);
}

ompl::base::PlannerTerminationCondition SolveProgress::start()
{
    // Optimizing planners report each better solution from their own thread.
    planning_.setup->getProblemDefinition()->setIntermediateSolutionCallback(
        [this](const ompl::base::Planner *, const std::vector<const ompl::base::State *> &,
               const ompl::base::Cost cost) {
            counters_.bestCost.store(cost.value());
            counters_.improvements.fetch_add(1);
        });
    start_ = std::chrono::steady_clock::now();
    const auto deadline = start_ + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                       std::chrono::duration<double>(options_.timeLimit));
    if (!options_.quiet)
        reporter_ = std::thread([this] { report(); });
    return ompl::base::PlannerTerminationCondition([this, deadline] {
        counters_.iterations.fetch_add(1, std::memory_order_relaxed);
        return std::chrono::steady_clock::now() >= deadline;
    });
}

std::string SolveProgress::status() const
{
    std::ostringstream s;
    s << counters_.iterations.load(std::memory_order_relaxed) << " iterations, " << planning_.validity->checkCount()
      << " collision checks";
    if (planning_.continuousValidator)
        s << ", " << planning_.continuousValidator->validMotions() + planning_.continuousValidator->invalidMotions()
          << " motions certified or refused";
    if (counters_.improvements.load() > 0)
        s << ", best cost " << counters_.bestCost.load() << " (" << counters_.improvements.load() << " improvements)";
    // Summed over the planner's threads: a parallel planner may spend more than the elapsed time.
    s << ", " << fixed(planning_.validity->checkSeconds(), 2) << " s in collision checks";
    return s.str();
}

void SolveProgress::report()
{
    const double period = options_.terminal ? options_.periodSeconds / 5.0 : options_.periodSeconds;
    std::unique_lock<std::mutex> lock(mutex_);
    for (int tick = 1;; ++tick)
    {
        const auto due = start_ + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                      std::chrono::duration<double>(tick * period));
        if (wake_.wait_until(lock, due, [this] { return stop_; }))
            return;
        const double elapsed = secondsSince(start_);
        if (options_.terminal)
        {
            const int width = 20;
            const int filled = int(width * std::min(1.0, elapsed / options_.timeLimit));
            // \r and "erase to the end of the line": the bar is redrawn in place.
            out_ << "\r\033[K[" << std::string(std::size_t(filled), '#')
                 << std::string(std::size_t(width - filled), '.') << "] " << fixed(elapsed, 1) << "/"
                 << options_.timeLimit << " s, " << status() << std::flush;
        }
        else
            out_ << "solve: " << fixed(elapsed, 1) << " s of " << options_.timeLimit << ", " << status() << std::endl;
    }
}

void SolveProgress::finish(const std::string &outcome)
{
    const double elapsed = secondsSince(start_);
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
    }
    wake_.notify_all();
    if (reporter_.joinable())
        reporter_.join();
    if (options_.quiet)
        return;
    if (options_.terminal)
        out_ << "\r\033[K";
    out_ << "solve: " << outcome << " after " << fixed(elapsed, 2) << " s: " << status() << std::endl;
}
}  // namespace hcd::cli
