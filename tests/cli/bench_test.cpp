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
    EXPECT_EQ(summarize(dir + "/small.db"), "geometric_KPIECE1[obb+ccd]|2|0,1;geometric_RRTConnect[obb+ccd]|2|0,1\n");
}

TEST(Bench, ShardsSplitRunsWithoutOverlapOrLoss)
{
    if (!haveStatisticsScript())
        HYBRIDCD_SKIP_OR_FAIL_IN_CI("ompl_benchmark_statistics not installed (package ompl-demos)");
    const std::string dir = tempDir();
    const std::string base = std::string(HYBRIDCD_CLI) + " bench " + hcd::test::sourcePath("problems/corridor_2d.cfg") +
                             " --planner rrtconnect --checker obb,bruteforce --runs 5 --time 1";
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
        "geometric_RRTConnect[bruteforce+ccd]|5|0,1,2,3,4;geometric_RRTConnect[obb+ccd]|5|0,1,2,3,4\n";
    EXPECT_EQ(summarize(dir + "/shards.db"), expected);
    EXPECT_EQ(summarize(dir + "/whole.db"), expected);
    EXPECT_NE(shell(base + " --shard 3/3").status, 0);
}
