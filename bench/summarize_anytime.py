#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Summarises optimizing (anytime) planners in an OMPL benchmark database (from
ompl_benchmark_statistics) as a Markdown table. An optimizing planner such as BIT* runs to its time
limit, so its solve time says nothing; what counts is when it first finds a path and how good its
path is at the end. Per experiment and planner[configuration]: runs, runs that found a path, the
median time to the first path (from the progress samples OMPL takes every 0.05 s; a run without a
path counts as the time limit), the median best cost at the end, and both against the same planner
in OMPL.app's set-up (`hybridcd bench` names it fcl+discrete(0.01)) on the same problem.

    python3 bench/summarize_anytime.py results.db
"""
import math
import sqlite3
import statistics
import sys

from summarize_benchmark import BASELINE


def main(path):
    db = sqlite3.connect(path)
    if not db.execute("SELECT name FROM sqlite_master WHERE type = 'table' AND name = 'progress'").fetchone():
        sys.exit("summarize_anytime: %s holds no progress samples (a log of planners that record none?)" % path)
    limits = dict(db.execute("SELECT id, timelimit FROM experiments"))
    first_path = {}
    for runid, time, cost in db.execute("SELECT runid, time, best_cost FROM progress ORDER BY runid, time"):
        if runid not in first_path and cost is not None and math.isfinite(cost):
            first_path[runid] = time
    groups = {}
    query = ("SELECT r.id, e.name, e.id, p.name, r.best_cost FROM runs r "
             "JOIN plannerConfigs p ON r.plannerid = p.id JOIN experiments e ON r.experimentid = e.id")
    for runid, experiment, experimentid, planner, cost in db.execute(query):
        found = runid in first_path
        groups.setdefault((experiment, planner), []).append(
            (found, first_path.get(runid, limits[experimentid]), cost if found and cost is not None else math.inf))

    def medians(rows):
        return statistics.median(t for _, t, _ in rows), statistics.median(c for _, _, c in rows)

    def ratio(a, b):
        return "%.2f" % (a / b) if b > 0 and math.isfinite(a) and math.isfinite(b) else "-"

    print("| problem | planner[configuration] | runs | found a path | median s to the first path | vs OMPL.app "
          "| median final cost | vs OMPL.app |")
    print("|---|---|---:|---:|---:|---:|---:|---:|")
    for (experiment, planner), rows in sorted(groups.items()):
        base = groups.get((experiment, planner.split("[")[0] + "[" + BASELINE + "]"))
        first, cost = medians(rows)
        base_first, base_cost = medians(base) if base else (math.nan, math.nan)
        print("| %s | %s | %d | %d | %.2f | %s | %.4g | %s |" %
              (experiment, planner.replace("geometric_", ""), len(rows), sum(1 for f, _, _ in rows if f), first,
               ratio(first, base_first), cost, ratio(cost, base_cost)))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: summarize_anytime.py RESULTS.db")
    main(sys.argv[1])
