// SPDX-License-Identifier: BSD-3-Clause
// `hybridcd bench` produces logs that OMPL's ompl_benchmark_statistics reads, and shards split runs
// without overlap or loss.
#include "support/test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

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
              "geometric_KPIECE1[auto+continuous]|2|0,1;geometric_KPIECE1[fcl+discrete(0.01)]|2|0,1;"
              "geometric_RRTConnect[auto+continuous]|2|0,1;geometric_RRTConnect[fcl+discrete(0.01)]|2|0,1\n");
    // The baseline really ran OMPL's DiscreteMotionValidator, whose motion counters give OMPL's
    // "valid segment fraction" (hybridcd's validator keeps its own, so OMPL's reads 0), at the
    // resolution 0.01 every configuration records among its settings.
    const std::string py =
        "import sqlite3,sys; c=sqlite3.connect(sys.argv[1]); "
        "print(';'.join('%s|%d|%d' % r for r in c.execute('select p.name, min(r.valid_segment_fraction > 0), "
        "p.settings like \\'%longest_valid_segment_fraction = 0.01%\\' from runs r join plannerConfigs p on "
        "r.plannerid = p.id group by p.name order by p.name')))";
    EXPECT_EQ(shell("python3 -c \"" + py + "\" " + dir + "/small.db").output,
              "geometric_KPIECE1[auto+continuous]|0|1;geometric_KPIECE1[fcl+discrete(0.01)]|1|1;"
              "geometric_RRTConnect[auto+continuous]|0|1;geometric_RRTConnect[fcl+discrete(0.01)]|1|1\n");
}

TEST(Bench, AnytimeSummaryTakesTheFirstPathAndTheFinalCost)
{
    // A database in ompl_benchmark_statistics' layout, with answers worked out by hand: BIT* under
    // OMPL.app's set-up finds paths at 0.4 and 0.2 s (costs 10 and 12) and none in a third run (the
    // time limit, 5 s, counts; cost infinite); under hybridcd's, at 0.1 and 0.3 s (costs 9 and 11).
    const std::string dir = tempDir() + "/anytime";
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    const std::string py =
        "import sqlite3,sys; c=sqlite3.connect(sys.argv[1]); "
        "c.execute('create table experiments (id integer primary key, name varchar(512), timelimit real)'); "
        "c.execute('create table plannerConfigs (id integer primary key, name varchar(512), settings text)'); "
        "c.execute('create table runs (id integer primary key, experimentid integer, plannerid integer, best_cost "
        "double)'); "
        "c.execute('create table progress (runid integer, time real, best_cost double)'); "
        "c.execute('insert into experiments values (1, \\'window\\', 5.0)'); "
        "c.executemany('insert into plannerConfigs values (?, ?, \\'\\')', [(1, "
        "'geometric_BITstar[fcl+discrete(0.01)]'), (2, 'geometric_BITstar[auto+continuous]')]); "
        "c.executemany('insert into runs values (?, 1, ?, ?)', [(1, 1, 10.0), (2, 1, 12.0), (3, 1, None), (4, 2, "
        "9.0), (5, 2, 11.0)]); "
        "inf = float('inf'); "
        "c.executemany('insert into progress values (?, ?, ?)', [(1, 0.2, inf), (1, 0.4, 10.5), (1, 0.6, 10.0), (2, "
        "0.2, 12.0), (3, 0.2, inf), (3, 0.4, inf), (4, 0.05, inf), (4, 0.1, 9.5), (5, 0.3, 11.0)]); "
        "c.commit()";
    ASSERT_EQ(shell("python3 -c \"" + py + "\" " + dir + "/a.db").status, 0);
    const std::string summarize = "python3 " + hcd::test::sourcePath("bench/summarize_anytime.py") + " ";
    const Output summary = shell(summarize + dir + "/a.db");
    ASSERT_EQ(summary.status, 0) << summary.output;
    // Medians: OMPL.app's first paths 0.2, 0.4, 5 -> 0.4 s, costs 10, 12, inf -> 12; hybridcd's
    // 0.1, 0.3 -> 0.2 s, costs 9, 11 -> 10.
    EXPECT_NE(summary.output.find("| window | BITstar[fcl+discrete(0.01)] | 3 | 2 | 0.40 | 1.00 | 12 | 1.00 |"),
              std::string::npos)
        << summary.output;
    EXPECT_NE(summary.output.find("| window | BITstar[auto+continuous] | 2 | 2 | 0.20 | 0.50 | 10 | 0.83 |"),
              std::string::npos)
        << summary.output;
    // A database without progress samples (a log of planners that record none) is refused.
    ASSERT_EQ(shell("python3 -c \"import sqlite3,sys; sqlite3.connect(sys.argv[1]).execute('create table runs (id "
                    "integer)')\" " +
                    dir + "/none.db")
                  .status,
              0);
    const Output none = shell(summarize + dir + "/none.db");
    EXPECT_EQ(none.status, 1) << none.output;
    EXPECT_NE(none.output.find("no progress samples"), std::string::npos) << none.output;
}

// Planner names "planner[configuration]" of a log, in its order (the lines after "N planners").
std::string configurationsOf(const std::string &log)
{
    return shell("awk '/^[0-9]+ planners$/{n=$1; next} n>0 && /^geometric_/{printf \"%s;\", $0; n--}' " + log).output;
}

// bench/summarize_speed.py on tables worked out by hand: the ratios against FCL and OMPL.app's
// set-up per problem, the medians over problems, and each target's line.
TEST(Bench, SpeedSummaryTakesRatiosFromTheTablesOfOneRun)
{
    const std::string dir = tempDir() + "/speed";
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    const auto write = [&](const std::string &name, const std::string &text) {
        std::ofstream(dir + "/" + name) << text;
    };
    write("states.md",
          "| problem | checker | median ns/check | mean ns/check | median vs fcl |\n|---|---|---:|---:|---:|\n"
          "| a | auto | 100 | 200 | 0.1 |\n| a | fcl | 1500 | 1000 | 1.00 |\n"
          "| b | auto | 100 | 100 | 0.5 |\n| b | fcl | 200 | 300 | 1.00 |\n"
          "| c | auto | 10 | 100 | 0.1 |\n| c | fcl | 120 | 150 | 1.00 |\n");
    write("distance.md", "| problem | checker | median ns/distance | mean ns/distance |\n|---|---|---:|---:|\n"
                         "| a | auto | 10 | 10 |\n| a | fcl | 200 | 100 |\n");
    write("scaling.md",
          "| environment triangles | robot triangles | checker | build ms | memory MiB | median ns/check | vs "
          "fcl |\n|---:|---:|---|---:|---:|---:|---:|\n"
          "| 1000 | 10 | auto | 2.0 | 1.0 | 100 | 0.1 |\n| 1000 | 10 | fcl | 1.0 | 2.0 | 1000 | 1.00 |\n"
          "| 1000000 | 10 | auto | 50.0 | 1.0 | 150 | 0.1 |\n| 1000000 | 10 | fcl | 100.0 | 2.0 | 2000 | 1.00 "
          "|\n");
    write("motions.md",
          "| problem | validator | state checker | median us/motion | vs discrete+fcl | mean us/motion | vs "
          "discrete+fcl | accepted | accepted but touching |\n|---|---|---|---:|---:|---:|---:|---:|---:|\n"
          "| a | continuous | obb | 1.0 | 0.1 | 2.0 | 0.1 | 9 | - |\n"
          "| a | continuous, lastValid | obb | 1.5 | 0.15 | 5.0 | 0.25 | 9 | - |\n"
          "| a | discrete | fcl | 10.0 | 1.00 | 20.0 | 1.00 | 9 | - |\n");
    write(
        "touching.md",
        "| problem | validator | state checker | median us/motion | accepted but touching |\n|---|---|---|---:|---:|\n"
        "| a | continuous | obb | 1.0 | 0 |\n| a | discrete | fcl | 10.0 | 2 |\n");
    write("planning.md",
          "| problem | planner[configuration] | runs | solved | median solve s | vs OMPL.app | median checks | "
          "median check s |\n|---|---|---:|---:|---:|---:|---:|---:|\n"
          "| a | RRTConnect[auto+continuous] | 10 | 90% | 0.1 | 0.10 | 1 | 0.1 |\n"
          "| a | RRTConnect[fcl+discrete(0.01)] | 10 | 100% | 1.0 | 1.00 | 1 | 0.9 |\n");
    const Output summary = shell("python3 " + hcd::test::sourcePath("bench/summarize_speed.py") + " " + dir);
    ASSERT_EQ(summary.status, 0) << summary.output;
    for (const char *expected :
         {"| a | 100 | 1500 | 15.0x | 200 | 1000 | 5.0x |", "| b | 100 | 200 | 2.0x | 100 | 300 | 3.0x |",
          // Speed-ups 15, 2 and 12: the median 12, the least 2 (b), under 3.
          "**12.0x at the median over the 3 problems**, at least 2.0x (b). Target: at least 10x at the median over "
          "them and 3x on every one: not met.",
          "**20.0x at the median over the 1 problems**, at least 20.0x (a). Target: at least 10x on every one: "
          "**met**.",
          // 100 -> 150 ns (1.5x) against log(1e6) / log(1e3) = 2; builds 2x FCL's at 1,000 triangles.
          "grows 1.50x from 1000 to 1000000 triangles, against log(triangles)'s 2.00x: **met**. Build time and memory "
          "at or below FCL's at 1 of 2 sizes (1000000 triangles): not met.",
          "| a | 1.0 | 10.0 | 0.10 | 0.10 | 2.50 | 0 / 2 |",
          "lastValid at most twice the verdict (mean): not met (over on a).",
          "RRTConnect, certified motions against OMPL.app's set-up, median solve time: a 0.10x (9/10 against 10/10). "
          "Target: solved at least as often everywhere and at most 0.2x on every one: not met (fewer solved on a)."})
        EXPECT_NE(summary.output.find(expected), std::string::npos) << expected << "\n" << summary.output;
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
        const Output r = shell(base + " --shard " + std::to_string(shard) + "/3 --seed 4" + " --out " + dir + "/shard" +
                               std::to_string(shard) + ".log");
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

namespace
{
// "name|runcount" per experiment of a database, then summarize()'s planner rows.
std::string experimentsOf(const std::string &db)
{
    const std::string py = "import sqlite3,sys; c=sqlite3.connect(sys.argv[1]); "
                           "print(';'.join('%s|%d'%r for r in c.execute('select name, runcount from experiments')))";
    return shell("python3 -c \"" + py + "\" " + db).output + summarize(db);
}
}  // namespace

TEST(Bench, ShardsUnderGnuParallelAndSlurmMergeIntoTheUnshardedExperiment)
{
    if (!haveStatisticsScript())
        HYBRIDCD_SKIP_OR_FAIL_IN_CI("ompl_benchmark_statistics not installed (package ompl-demos)");
    if (shell("command -v parallel").status != 0)
        HYBRIDCD_SKIP_OR_FAIL_IN_CI("GNU parallel not installed (package parallel)");
    const std::string dir = tempDir() + "/sharded";
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    const std::string cli = HYBRIDCD_CLI;
    const std::string merge = "python3 " + hcd::test::sourcePath("bench/merge_shards.py");
    const std::string options = " --planner rrtconnect,kpiece --runs 5 --time 0.3 --seed 5";
    const std::string cfg = hcd::test::sourcePath("problems/corridor_2d.cfg");

    const Output whole = shell(cli + " bench " + cfg + options + " --out " + dir + "/whole.log");
    ASSERT_EQ(whole.status, 0) << whole.output;
    ASSERT_EQ(shell("ompl_benchmark_statistics " + dir + "/whole.log -d " + dir + "/whole.db").status, 0);
    const std::string expected = experimentsOf(dir + "/whole.db");
    ASSERT_EQ(expected,
              "corridor_2d|5\n"
              "geometric_KPIECE1[auto+continuous]|5|0,1,2,3,4;geometric_KPIECE1[fcl+discrete(0.01)]|5|0,1,2,3,4;"
              "geometric_RRTConnect[auto+continuous]|5|0,1,2,3,4;"
              "geometric_RRTConnect[fcl+discrete(0.01)]|5|0,1,2,3,4\n");

    // Three shards side by side under GNU parallel (-S 2/: is parallel's local "ssh login", two jobs).
    const Output sharded = shell("parallel -S 2/: --halt now,fail=1 " + cli + " bench " + cfg + options +
                                 " --shard {}/3 --out " + dir + "/p{}.log ::: 0 1 2");
    ASSERT_EQ(sharded.status, 0) << sharded.output;
    const std::string shards = " " + dir + "/p0.log " + dir + "/p1.log " + dir + "/p2.log";
    const Output merged = shell(merge + " --out " + dir + "/p.log --db " + dir + "/p.db" + shards);
    ASSERT_EQ(merged.status, 0) << merged.output;
    EXPECT_EQ(experimentsOf(dir + "/p.db"), expected);
    // Each shard's seed is derived from the base seed and printed; the merged log keeps them all.
    EXPECT_NE(sharded.output.find("shard 1/3: seed "), std::string::npos) << sharded.output;
    EXPECT_EQ(shell("grep -c '^5 is the random seed$' " + dir + "/p.log").output, "1\n");
    EXPECT_EQ(shell("grep -c '^shard_seeds VARCHAR(1024) = [0-9]*,[0-9]*,[0-9]*$' " + dir + "/p.log").output, "1\n");

    // The same shards as a SLURM job array, each task run by hand as SLURM would run it.
    const std::string sbatch = hcd::test::sourcePath("bench/slurm/bench_array.sbatch");
    ASSERT_EQ(shell("bash -n " + sbatch).status, 0);
    for (int task = 0; task < 3; ++task)
    {
        const Output r =
            shell("SLURM_ARRAY_TASK_ID=" + std::to_string(task) +
                  " SLURM_ARRAY_TASK_MIN=0 SLURM_ARRAY_TASK_MAX=2 SLURM_ARRAY_TASK_COUNT=3 HYBRIDCD=" + cli + " bash " +
                  sbatch + " " + dir + "/slurm " + cfg + options);
        ASSERT_EQ(r.status, 0) << r.output;
    }
    const Output slurm = shell(merge + " --out " + dir + "/s.log --db " + dir + "/s.db " + dir + "/slurm/shard*.log");
    ASSERT_EQ(slurm.status, 0) << slurm.output;
    EXPECT_EQ(experimentsOf(dir + "/s.db"), expected);
    // The same seeds whichever engine ran the shards.
    EXPECT_EQ(shell("grep shard_seeds " + dir + "/s.log").output, shell("grep shard_seeds " + dir + "/p.log").output);

    // Shards that do not make one benchmark are refused, naming the file, and nothing is written.
    const Output reseeded =
        shell(cli + " bench " + cfg + " --planner rrtconnect,kpiece --runs 5 --time 0.3 --seed 6 --shard 2/3 --out " +
              dir + "/other2.log");
    ASSERT_EQ(reseeded.status, 0) << reseeded.output;
    ASSERT_EQ(
        shell("sed 's/^[0-9]* is the random seed$/123 is the random seed/' " + dir + "/p2.log > " + dir + "/seed2.log")
            .status,
        0);
    const struct
    {
        std::string shards, message;
    } bad[] = {
        {dir + "/p0.log " + dir + "/p1.log", "shards 2 of 3 are missing"},
        {dir + "/p0.log " + dir + "/p1.log " + dir + "/p1.log", "p1.log: shard 1/3 is also"},
        {dir + "/p0.log " + dir + "/p1.log " + dir + "/other2.log", "other2.log:4: experiment property base_seed"},
        {dir + "/p0.log " + dir + "/p1.log " + dir + "/seed2.log", "seed2.log:"},
        {dir + "/p0.log " + dir + "/p1.log " + dir + "/seed2.log",
         ": seed 123, but shard 2/3 of base seed 5 is seeded with"},
        {dir + "/p0.log " + dir + "/p1.log " + dir + "/whole.log",
         "whole.log:8: experiment property shard_count INTEGER is 1 here, 3 in"},
        {dir + "/p0.log " + dir + "/p1.log /no/such.log", "/no/such.log: cannot read"},
    };
    for (const auto &b : bad)
    {
        const Output r = shell(merge + " --out " + dir + "/bad.log " + b.shards);
        EXPECT_EQ(r.status, 1) << b.shards << ": " << r.output;
        EXPECT_NE(r.output.find(b.message), std::string::npos) << b.shards << ": " << r.output;
        EXPECT_FALSE(std::filesystem::exists(dir + "/bad.log")) << b.shards;
    }
}

TEST(Bench, KinodynamicProblemsRunControlPlannersUnderEveryConfiguration)
{
    if (!haveStatisticsScript())
        HYBRIDCD_SKIP_OR_FAIL_IN_CI("ompl_benchmark_statistics not installed (package ompl-demos)");
    const std::string dir = tempDir() + "/kinodynamic";
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    const std::string base =
        std::string(HYBRIDCD_CLI) + " bench " + hcd::test::sourcePath("problems/corridor_kcar.cfg");
    const Output run =
        shell(base + " --checker obb --planner kpiece,rrt --runs 3 --time 1 --seed 3 --out " + dir + "/k.log");
    ASSERT_EQ(run.status, 0) << run.output;
    // The log names control planners, every one under hybridcd's set-up and OMPL.app's (FCL, states
    // checked at the 0.2 s propagation steps only).
    EXPECT_EQ(
        shell("awk '/^[0-9]+ planners$/{n=$1; next} n>0 && /^control_/{printf \"%s;\", $0; n--}' " + dir + "/k.log")
            .output,
        "control_KPIECE1[obb+continuous];control_RRT[obb+continuous];control_KPIECE1[fcl+discrete(0.2s)];"
        "control_RRT[fcl+discrete(0.2s)];");
    EXPECT_EQ(shell("grep -c '^control VARCHAR(32) = kinematic_car$' " + dir + "/k.log").output, "1\n");
    ASSERT_EQ(shell("ompl_benchmark_statistics " + dir + "/k.log -d " + dir + "/k.db").status, 0);
    EXPECT_EQ(experimentsOf(dir + "/k.db"),
              "corridor_kcar|3\n"
              "control_KPIECE1[fcl+discrete(0.2s)]|3|0,1,2;control_KPIECE1[obb+continuous]|3|0,1,2;"
              "control_RRT[fcl+discrete(0.2s)]|3|0,1,2;control_RRT[obb+continuous]|3|0,1,2\n");
    // Every run counted its collision checks, and the continuous runs certified trajectories with
    // hybridcd's checker while the baseline's went through FCL.
    const std::string py = "import sqlite3,sys; c=sqlite3.connect(sys.argv[1]); "
                           "print(';'.join('%s|%d|%s' % r for r in c.execute('select p.name, min(r.collision_checks > "
                           "0), min(r.checker) from runs r join plannerConfigs p on r.plannerid = p.id group by p.name "
                           "order by p.name')))";
    EXPECT_EQ(shell("python3 -c \"" + py + "\" " + dir + "/k.db").output,
              "control_KPIECE1[fcl+discrete(0.2s)]|1|fcl;control_KPIECE1[obb+continuous]|1|obb;"
              "control_RRT[fcl+discrete(0.2s)]|1|fcl;control_RRT[obb+continuous]|1|obb\n");
    // The plot script reads control planners' names as it reads geometric ones.
    if (shell("/usr/bin/python3 -c 'import matplotlib'").status == 0)
    {
        const Output plot = shell("/usr/bin/python3 " + hcd::test::sourcePath("bench/plot_benchmark.py") + " " + dir +
                                  "/k.db " + dir + "/plots --print 2>/dev/null");
        ASSERT_EQ(plot.status, 0) << plot.output;
        EXPECT_NE(plot.output.find("corridor_kcar\tKPIECE1\tobb+continuous\t3\t"), std::string::npos) << plot.output;
        EXPECT_NE(plot.output.find("corridor_kcar\tRRT\tfcl+discrete(0.2s)\t3\t"), std::string::npos) << plot.output;
        EXPECT_TRUE(std::filesystem::exists(dir + "/plots/corridor_kcar_benchmark.png"));
    }
    // A geometric planner is refused before anything runs, and no log is written.
    const Output bad = shell(base + " --planner rrtconnect --runs 1 --time 1 --out " + dir + "/bad.log");
    EXPECT_EQ(bad.status, 1) << bad.output;
    EXPECT_NE(bad.output.find("unknown control planner 'rrtconnect'"), std::string::npos) << bad.output;
    EXPECT_FALSE(std::filesystem::exists(dir + "/bad.log"));
}

namespace
{
struct PlotRow
{
    int runs = 0, solved = 0;
    double success = 0, time = 0, length = 0, checks = 0;
};

double medianOf(std::vector<double> v)
{
    if (v.empty())
        return std::nan("");
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

bool close(double a, double b)
{
    return (std::isnan(a) && std::isnan(b)) || std::abs(a - b) <= 1e-5 * std::max(1.0, std::abs(b));
}
}  // namespace

TEST(Bench, PlotsShowWhatTheDatabaseHolds)
{
    if (!haveStatisticsScript())
        HYBRIDCD_SKIP_OR_FAIL_IN_CI("ompl_benchmark_statistics not installed (package ompl-demos)");
    if (shell("/usr/bin/python3 -c 'import matplotlib'").status != 0)
        HYBRIDCD_SKIP_OR_FAIL_IN_CI("matplotlib not installed for /usr/bin/python3 (package python3-matplotlib)");
    const std::string dir = tempDir() + "/plots";
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    // The sealed problem of cli_test is not at hand here: a tenth of a second leaves some KPIECE
    // runs of window_3d unsolved, so the success rates differ.
    const Output run = shell(std::string(HYBRIDCD_CLI) + " bench " + hcd::test::sourcePath("problems/window_3d.cfg") +
                             " --planner rrtconnect,kpiece --runs 4 --time 0.1 --seed 2 --out " + dir + "/w.log");
    ASSERT_EQ(run.status, 0) << run.output;
    ASSERT_EQ(shell("ompl_benchmark_statistics " + dir + "/w.log -d " + dir + "/w.db").status, 0);
    const Output plot = shell("{ /usr/bin/python3 " + hcd::test::sourcePath("bench/plot_benchmark.py") + " " + dir +
                              "/w.db " + dir + "/out --print 2>/dev/null; }");
    ASSERT_EQ(plot.status, 0) << plot.output;

    // The printed numbers are the database's, computed here from its raw runs.
    const std::string py =
        "import sqlite3,sys; c=sqlite3.connect(sys.argv[1]); "
        "[print('%s|%d|%r|%r|%r'%r) for r in c.execute('select p.name, r.solved, r.time, "
        "r.simplified_solution_length, r.collision_checks from runs r join plannerConfigs p on r.plannerid=p.id')]";
    std::map<std::string, std::array<std::vector<double>, 4>> raw;  // solved, time, length, checks
    std::istringstream rows(shell("python3 -c \"" + py + "\" " + dir + "/w.db").output);
    for (std::string line; std::getline(rows, line);)
    {
        std::vector<std::string> f;
        std::stringstream s(line);
        for (std::string item; std::getline(s, item, '|');)
            f.push_back(item);
        ASSERT_EQ(f.size(), 5u) << line;
        std::string name = f[0].substr(f[0].find('_') + 1);
        auto &g = raw[name];
        const bool solved = f[1] == "1";
        g[0].push_back(solved);
        g[1].push_back(std::stod(f[2]));
        if (solved && f[3] != "None")
            g[2].push_back(std::stod(f[3]));
        g[3].push_back(std::stod(f[4]));
    }
    ASSERT_EQ(raw.size(), 4u);
    std::istringstream printed(plot.output);
    std::string header;
    std::getline(printed, header);
    EXPECT_EQ(header.rfind("experiment\tplanner\tconfiguration\truns\tsolved\t", 0), 0u) << plot.output;
    std::size_t lines = 0;
    int runsAll = 0;
    for (std::string line; std::getline(printed, line); ++lines)
    {
        std::vector<std::string> f;
        std::stringstream s(line);
        for (std::string item; std::getline(s, item, '\t');)
            f.push_back(item);
        ASSERT_EQ(f.size(), 9u) << line;
        EXPECT_EQ(f[0], "window_3d");
        const auto &g = raw.at(f[1] + "[" + f[2] + "]");
        const int solved = int(std::count(g[0].begin(), g[0].end(), 1.0));
        EXPECT_EQ(std::stoi(f[3]), int(g[0].size())) << line;
        EXPECT_EQ(std::stoi(f[4]), solved) << line;
        EXPECT_TRUE(close(std::stod(f[5]), 100.0 * solved / double(g[0].size()))) << line;
        EXPECT_TRUE(close(std::stod(f[6]), medianOf(g[1]))) << line;
        EXPECT_TRUE(close(std::stod(f[7]), medianOf(g[2]))) << line;
        EXPECT_TRUE(close(std::stod(f[8]), medianOf(g[3]))) << line;
        runsAll += int(g[0].size());
    }
    EXPECT_EQ(lines, 4u) << plot.output;
    EXPECT_EQ(runsAll, 16);

    // PNG and PDF, each a real picture: the PNG's size in its header, both configurations' colours
    // (tab10 blue and orange at 75% over white) on many pixels.
    const std::string png = dir + "/out/window_3d_benchmark.png", pdf = dir + "/out/window_3d_benchmark.pdf";
    ASSERT_TRUE(std::filesystem::exists(png) && std::filesystem::exists(pdf)) << plot.output;
    EXPECT_GT(std::filesystem::file_size(png), 20000u);
    EXPECT_GT(std::filesystem::file_size(pdf), 8000u);
    EXPECT_EQ(shell("head -c 4 " + pdf).output, "%PDF");
    const std::string pixels = "import matplotlib.image as m, numpy as n, sys; a=m.imread(sys.argv[1])[:,:,:3]; "
                               "near=lambda c: int((abs(a-n.array(c)).max(axis=2)<0.02).sum()); "
                               "print(a.shape[1], a.shape[0], near((0.341,0.600,0.779)), near((1.0,0.624,0.291)))";
    std::istringstream image(shell("/usr/bin/python3 -c \"" + pixels + "\" " + png).output);
    int width = 0, height = 0, blue = 0, orange = 0;
    image >> width >> height >> blue >> orange;
    EXPECT_GE(width, 800);
    EXPECT_GE(height, 600);
    EXPECT_GT(blue, 2000);
    EXPECT_GT(orange, 2000);
}
