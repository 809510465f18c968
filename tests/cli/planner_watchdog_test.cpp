// SPDX-License-Identifier: BSD-3-Clause
// The planner watchdog: a run far past its time limit ends the process with the status given and
// a line naming the planner; a run that returns in time, or one disarmed, is left alone.
#include "planner_watchdog.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <thread>

using hcd::cli::PlannerWatchdog;
using hcd::cli::WatchedRun;

TEST(PlannerWatchdogDeathTest, EndsTheProcessWhenAPlannerOverrunsFarBeyondItsLimit)
{
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_EXIT(
        {
            PlannerWatchdog watchdog(7);
            const WatchedRun run(watchdog, "Stuck", 0.01);
            std::this_thread::sleep_for(std::chrono::seconds(30));  // a planner that never returns
            std::exit(0);
        },
        ::testing::ExitedWithCode(7),
        "planner Stuck did not return within 2.005 s after its limit of --time 0.01 s .*nothing was written");
}

TEST(PlannerWatchdog, RunsThatReturnOrAreRearmedAreLeftAlone)
{
    PlannerWatchdog watchdog(7);
    {
        const WatchedRun run(watchdog, "Quick", 0.01);
    }
    // Well past the first watch's deadline (2.01 s): disarmed, it ends nothing.
    std::this_thread::sleep_for(std::chrono::milliseconds(2300));
    // A watch re-armed with a longer limit replaces the shorter one.
    watchdog.arm("First", 0.01);
    watchdog.arm("Second", 10.0);
    std::this_thread::sleep_for(std::chrono::milliseconds(2300));
    watchdog.disarm();
    EXPECT_EQ(PlannerWatchdog::graceSeconds(10.0), 7.0);
}
