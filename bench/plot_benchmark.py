#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Turns an OMPL benchmark database into PNG plots like Planner Arena's: one box plot of solve
times per experiment, one box per planner[checker], with the success rate written under each box.
Needs matplotlib (Debian: python3-matplotlib).

    python3 bench/plot_benchmark.py results.db OUTPUT_FOLDER
"""
import os
import sqlite3
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(path, out_dir):
    os.makedirs(out_dir, exist_ok=True)
    db = sqlite3.connect(path)
    experiments = db.execute("SELECT id, name FROM experiments").fetchall()
    by_name = {}
    for eid, name in experiments:
        by_name.setdefault(name, []).append(eid)
    for name, ids in sorted(by_name.items()):
        rows = db.execute(
            "SELECT p.name, r.time, r.solved FROM runs r JOIN plannerConfigs p ON r.plannerid = p.id "
            "WHERE r.experimentid IN (%s)" % ",".join("?" * len(ids)), ids).fetchall()
        planners = sorted({p for p, _, _ in rows})
        times = [[t for p, t, _ in rows if p == planner] for planner in planners]
        success = [sum(1 for p, _, s in rows if p == planner and s) / max(1, len(t)) for planner, t in
                   zip(planners, times)]
        fig, ax = plt.subplots(figsize=(max(6, 1.1 * len(planners)), 4.5))
        ax.boxplot(times, showfliers=True)
        ax.set_xticks(range(1, len(planners) + 1))
        ax.set_xticklabels(["%s\n%.0f%% solved" % (p.replace("geometric_", ""), 100 * s)
                            for p, s in zip(planners, success)], rotation=30, ha="right", fontsize=8)
        ax.set_ylabel("solve time (s)")
        ax.set_yscale("log")
        ax.set_title("%s: solve time per planner[checker]" % name)
        fig.tight_layout()
        target = os.path.join(out_dir, "%s_solve_time.png" % name)
        fig.savefig(target, dpi=110)
        plt.close(fig)
        print(target)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: plot_benchmark.py RESULTS.db OUTPUT_FOLDER")
    main(sys.argv[1], sys.argv[2])
