// SPDX-License-Identifier: BSD-3-Clause
// `hybridcd bench` produces logs that OMPL's ompl_benchmark_statistics reads, and shards split runs
// without overlap or loss.
#include "support/test_support.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <set>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

namespace
{
using Output = hcd::test::ShellResult;

Output shell(const std::string &command) { return hcd::test::runShell(command); }

bool haveStatisticsScript() { return shell("command -v ompl_benchmark_statistics").status == 0; }

// Rows "planner|count|sorted run indices" from the runs table, via Python's sqlite3.
std::string summarize(const std::string &db)
{
    const std::string py =
        "import sqlite3,sys; c=sqlite3.connect(sys.argv[1]); "
        "rows=c.execute('select p.name, r.run_index from runs r join plannerConfigs p on "
        "r.plannerid=p.id').fetchall(); "
        "d={}; [d.setdefault(n,[]).append(int(i)) for n,i in rows]; "
        "print(';'.join('%s|%d|%s'%(n,len(v),','.join(map(str,sorted(v)))) for n,v in sorted(d.items())))";
    return shell("python3 -c \"" + py + "\" " + db).output;
}

std::string tempDir()
{
    const auto dir = std::filesystem::temp_directory_path() / ("hybridcd-bench-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    return dir.string();
}
}  // namespace

TEST(Bench, LogIsReadByOmplBenchmarkStatistics)
{
    if (!haveStatisticsScript())
        HYBRIDCD_SKIP_OR_FAIL_IN_CI("ompl_benchmark_statistics not installed (package ompl-demos)");
    const std::string dir = tempDir();
    const Output run = shell(std::string(HYBRIDCD_CLI) + " bench " + hcd::test::sourcePath("problems/corridor_2d.cfg") +
                             " --planner rrtconnect,kpiece --runs 2 --time 1 --out " + dir + "/small.log");
    ASSERT_EQ(run.status, 0) << run.output;
    const Output stats = shell("cd " + dir + " && ompl_benchmark_statistics small.log -d small.db");
    ASSERT_EQ(stats.status, 0) << stats.output;
    // By default hybridcd's set-up runs beside OMPL.app's (FCL, discrete motion checks at 0.01).
    EXPECT_EQ(summarize(dir + "/small.db"),
              "geometric_KPIECE1[fcl+discrete(0.01)]|2|0,1;geometric_KPIECE1[obb+continuous]|2|0,1;"
              "geometric_RRTConnect[fcl+discrete(0.01)]|2|0,1;geometric_RRTConnect[obb+continuous]|2|0,1\n");
}

// Planner names "planner[configuration]" of a log, in its order (the lines after "N planners").
std::string configurationsOf(const std::string &log)
{
    return shell("awk '/^[0-9]+ planners$/{n=$1; next} n>0 && /^geometric_/{printf \"%s;\", $0; n--}' " + log).output;
}

TEST(Bench, ConfigurationsAreCheckerTimesMotionPlusTheOmplAppBaseline)
{
    const std::string dir = tempDir();
    const std::string base = std::string(HYBRIDCD_CLI) + " bench " + hcd::test::sourcePath("problems/corridor_2d.cfg") +
                             " --planner rrtconnect --runs 1 --time 0.2 --seed 1";
    const Output both = shell(base + " --checker obb --motion continuous,discrete --out " + dir + "/both.log");
    ASSERT_EQ(both.status, 0) << both.output;
    EXPECT_EQ(configurationsOf(dir + "/both.log"),
              "geometric_RRTConnect[obb+continuous];geometric_RRTConnect[obb+discrete(0.01)];"
              "geometric_RRTConnect[fcl+discrete(0.01)];");
    // OMPL.app's set-up asked for by hand is the baseline itself, not a second copy of it.
    const Output fcl = shell(base + " --checker fcl --motion discrete --out " + dir + "/fcl.log");
    ASSERT_EQ(fcl.status, 0) << fcl.output;
    EXPECT_EQ(configurationsOf(dir + "/fcl.log"), "geometric_RRTConnect[fcl+discrete(0.01)];");
    // Options that change a checker's answers are part of its name; FCL's never change.
    const Output none = shell(base + " --checker obb --surface-only --baseline none --out " + dir + "/surface.log");
    ASSERT_EQ(none.status, 0) << none.output;
    EXPECT_EQ(configurationsOf(dir + "/surface.log"), "geometric_RRTConnect[obb-surface+continuous];");
    const Output lp =
        shell(base + " --checker lp --mode approximate --tolerance 0.5 --motion discrete --out " + dir + "/lp.log");
    ASSERT_EQ(lp.status, 0) << lp.output;
    EXPECT_EQ(configurationsOf(dir + "/lp.log"),
              "geometric_RRTConnect[lp-approx(0.5)+discrete(0.01)];geometric_RRTConnect[fcl+discrete(0.01)];");

    for (const char *bad : {" --baseline fcl", " --motion sideways", " --motion ,", " --checker obb,obb"})
    {
        const Output r = shell(base + bad + " --out " + dir + "/bad.log");
        EXPECT_EQ(r.status, 1) << bad << ": " << r.output;
        EXPECT_FALSE(std::filesystem::exists(dir + "/bad.log")) << bad;
    }
}

TEST(Bench, ShardsSplitRunsWithoutOverlapOrLoss)
{
    if (!haveStatisticsScript())
        HYBRIDCD_SKIP_OR_FAIL_IN_CI("ompl_benchmark_statistics not installed (package ompl-demos)");
    const std::string dir = tempDir();
    const std::string base = std::string(HYBRIDCD_CLI) + " bench " + hcd::test::sourcePath("problems/corridor_2d.cfg") +
                             " --planner rrtconnect --checker obb,bruteforce --baseline none --runs 5 --time 1";
    for (int shard = 0; shard < 3; ++shard)
    {
        const Output r = shell(base + " --shard " + std::to_string(shard) + "/3 --seed " + std::to_string(shard + 1) +
                               " --out " + dir + "/shard" + std::to_string(shard) + ".log");
        ASSERT_EQ(r.status, 0) << r.output;
    }
    const Output whole = shell(base + " --out " + dir + "/whole.log");
    ASSERT_EQ(whole.status, 0) << whole.output;
    ASSERT_EQ(shell("cd " + dir + " && ompl_benchmark_statistics shard0.log shard1.log shard2.log -d shards.db").status,
              0);
    ASSERT_EQ(shell("cd " + dir + " && ompl_benchmark_statistics whole.log -d whole.db").status, 0);
    const std::string expected =
        "geometric_RRTConnect[bruteforce+continuous]|5|0,1,2,3,4;geometric_RRTConnect[obb+continuous]|5|0,1,2,3,4\n";
    EXPECT_EQ(summarize(dir + "/shards.db"), expected);
    EXPECT_EQ(summarize(dir + "/whole.db"), expected);
    EXPECT_NE(shell(base + " --shard 3/3").status, 0);
}
