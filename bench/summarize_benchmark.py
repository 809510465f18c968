#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Summarises an OMPL benchmark database (from ompl_benchmark_statistics) as a Markdown table:
per experiment and planner[checker], runs, success rate, median solve time, median collision
checks and time in collision checking, and the ratio of median solve time to the same planner
in OMPL.app's set-up (FCL, OMPL's DiscreteMotionValidator at resolution 0.01: the configuration
`hybridcd bench` names fcl+discrete(0.01)) on the same problem.

    python3 bench/summarize_benchmark.py results.db
"""
import sqlite3
import statistics
import sys

BASELINE = "fcl+discrete(0.01)"


def main(path):
    db = sqlite3.connect(path)
    columns = {row[1] for row in db.execute("PRAGMA table_info(runs)")}
    has_checks = "collision_checks" in columns
    query = ("SELECT e.name, p.name, r.solved, r.time" +
             (", r.collision_checks, r.collision_checking_time" if has_checks else ", NULL, NULL") +
             " FROM runs r JOIN plannerConfigs p ON r.plannerid = p.id JOIN experiments e ON r.experimentid = e.id")
    groups = {}
    for experiment, planner, solved, time, checks, check_time in db.execute(query):
        groups.setdefault((experiment, planner), []).append((solved, time, checks, check_time))

    def median_time(rows):
        return statistics.median(t for _, t, _, _ in rows)

    print("| problem | planner[configuration] | runs | solved | median solve s | vs OMPL.app | median checks "
          "| median check s |")
    print("|---|---|---:|---:|---:|---:|---:|---:|")
    for (experiment, planner), rows in sorted(groups.items()):
        base = planner.split("[")[0]
        fcl = groups.get((experiment, base + "[" + BASELINE + "]"))
        ratio = "%.2f" % (median_time(rows) / median_time(fcl)) if fcl and median_time(fcl) > 0 else "-"
        solved = sum(1 for s, _, _, _ in rows if s) / len(rows)
        checks = statistics.median(c for _, _, c, _ in rows) if has_checks else float("nan")
        check_s = statistics.median(c for _, _, _, c in rows) if has_checks else float("nan")
        print("| %s | %s | %d | %.0f%% | %.3f | %s | %.0f | %.3f |" %
              (experiment, planner.replace("geometric_", ""), len(rows), 100 * solved, median_time(rows), ratio,
               checks, check_s))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: summarize_benchmark.py RESULTS.db")
    main(sys.argv[1])
