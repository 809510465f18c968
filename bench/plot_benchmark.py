#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Plots an OMPL benchmark database (made from `hybridcd bench` logs by ompl_benchmark_statistics,
or by bench/merge_shards.py --db) as Planner Arena does: per experiment, one figure of four panels,
success rate, solve time, path length and collision checks, with one bar or box per planner and
checker configuration (the `[...]` in the planner's name, e.g. RRTConnect[obb+continuous]; the
colour tells the configuration). Written as NAME_benchmark.png and NAME_benchmark.pdf.

    /usr/bin/python3 bench/plot_benchmark.py RESULTS.db OUTPUT_FOLDER [--format png,pdf] [--print]

Experiments of the same name (separate logs of one problem) are drawn together. Path length is that
of the exact solutions (OMPL's "simplified solution length" when the log has it, else "solution
length"; for control planners OMPL records the path's duration in seconds there); solve time and
collision checks count every run. --print writes the plotted numbers, one
tab-separated line per experiment and planner[configuration]: experiment, planner, configuration,
runs, solved runs, success rate (%), median solve time (s), median path length, median collision
checks ("nan" where there is nothing to take the median of). Needs Debian's python3-matplotlib.
"""
import argparse
import math
import os
import sqlite3
import statistics
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def split_name(name):
    """ "geometric_RRTConnect[obb+continuous]" -> ("RRTConnect", "obb+continuous"); the same for
    control planners ("control_KPIECE1[obb+discrete(0.2s)]")."""
    for prefix in ("geometric_", "control_"):
        if name.startswith(prefix):
            name = name[len(prefix):]
            break
    if name.endswith("]") and "[" in name:
        at = name.index("[")
        return name[:at], name[at + 1:-1]
    return name, ""


def median(values):
    return statistics.median(values) if values else math.nan


def load(path):
    if not os.path.isfile(path):
        sys.exit("plot_benchmark: %s: no such database" % path)
    db = sqlite3.connect("file:%s?mode=ro" % path, uri=True)
    try:
        columns = {row[1] for row in db.execute("PRAGMA table_info(runs)")}
    except sqlite3.DatabaseError as e:
        sys.exit("plot_benchmark: %s: not an SQLite database (%s)" % (path, e))
    if not {"time", "solved"} <= columns:
        sys.exit("plot_benchmark: %s: no runs table of an OMPL benchmark database" % path)
    length = ("simplified_solution_length" if "simplified_solution_length" in columns else
              "solution_length" if "solution_length" in columns else "NULL")
    checks = "collision_checks" if "collision_checks" in columns else "NULL"
    query = ("SELECT e.name, p.name, r.solved, r.time, %s, %s FROM runs r JOIN plannerConfigs p "
             "ON r.plannerid = p.id JOIN experiments e ON r.experimentid = e.id ORDER BY r.id" % (length, checks))
    experiments = {}
    for experiment, planner, solved, time, path_length, check_count in db.execute(query):
        group = experiments.setdefault(experiment, {}).setdefault(
            planner, {"solved": [], "time": [], "length": [], "checks": []})
        group["solved"].append(bool(solved))
        if time is not None:
            group["time"].append(float(time))
        if solved and path_length is not None:
            group["length"].append(float(path_length))
        if check_count is not None:
            group["checks"].append(float(check_count))
    limits = {name: (limit, runs) for name, limit, runs in
              db.execute("SELECT name, MAX(timelimit), SUM(runcount) FROM experiments GROUP BY name")}
    return experiments, limits


def summary(experiments):
    rows = []
    for experiment in sorted(experiments):
        for planner in sorted(experiments[experiment]):
            g = experiments[experiment][planner]
            base, configuration = split_name(planner)
            runs, solved = len(g["solved"]), sum(g["solved"])
            rows.append((experiment, base, configuration, runs, solved, 100.0 * solved / runs if runs else math.nan,
                         median(g["time"]), median(g["length"]), median(g["checks"])))
    return rows


def plot(experiment, planners, limit, out_dir, formats):
    names = sorted(planners, key=lambda p: (split_name(p)[0], split_name(p)[1]))
    configurations = sorted({split_name(p)[1] for p in names})
    colours = {c: plt.get_cmap("tab10")(i % 10) for i, c in enumerate(configurations)}
    labels = [split_name(p)[0] + ("\n" + split_name(p)[1] if split_name(p)[1] else "") for p in names]
    positions = list(range(1, len(names) + 1))
    fig, axes = plt.subplots(2, 2, figsize=(max(9.0, 0.75 * len(names) + 4.0), 7.5), sharex=True)

    def boxes(ax, key, ylabel, log):
        data = [planners[p][key] for p in names]
        shown = [(pos, d, p) for pos, d, p in zip(positions, data, names) if d]
        if shown:
            parts = ax.boxplot([d for _, d, _ in shown], positions=[pos for pos, _, _ in shown], widths=0.6,
                               patch_artist=True, showfliers=True, flierprops={"markersize": 3})
            for patch, (_, _, p) in zip(parts["boxes"], shown):
                patch.set_facecolor(colours[split_name(p)[1]])
                patch.set_alpha(0.75)
            for line in parts["medians"]:
                line.set_color("black")
        for pos, d in zip(positions, data):
            if not d:
                ax.text(pos, 0.5, "none", transform=ax.get_xaxis_transform(), ha="center", fontsize=7, color="grey")
        if log and any(v > 0 for d in data for v in d):
            ax.set_yscale("log")
        ax.set_ylabel(ylabel)
        ax.grid(axis="y", alpha=0.3)

    success = [100.0 * sum(planners[p]["solved"]) / len(planners[p]["solved"]) for p in names]
    ax = axes[0][0]
    ax.bar(positions, success, width=0.6, color=[colours[split_name(p)[1]] for p in names], alpha=0.75)
    for pos, value in zip(positions, success):
        ax.text(pos, value + 1.5, "%.0f" % value, ha="center", fontsize=7)
    ax.set_ylim(0, 110)
    ax.set_ylabel("success rate (%)")
    ax.grid(axis="y", alpha=0.3)
    boxes(axes[0][1], "time", "solve time (s)" + (", limit %g s" % limit if limit else ""), True)
    boxes(axes[1][0], "length", "path length (exact solutions)", False)
    boxes(axes[1][1], "checks", "collision checks per run", True)
    for ax in axes[1]:
        ax.set_xticks(positions)
        ax.set_xticklabels(labels, rotation=40, ha="right", fontsize=7)
    handles = [plt.Rectangle((0, 0), 1, 1, color=colours[c], alpha=0.75) for c in configurations]
    fig.legend(handles, [c or "(no configuration)" for c in configurations], loc="upper center",
               ncol=min(4, len(configurations)), fontsize=8, frameon=False, bbox_to_anchor=(0.5, 0.965))
    runs = max(len(planners[p]["solved"]) for p in names)
    fig.suptitle("%s: %d run%s per planner and configuration" % (experiment, runs, "s" if runs != 1 else ""),
                 fontsize=11)
    fig.tight_layout(rect=(0, 0, 1, 0.93))
    written = []
    for fmt in formats:
        target = os.path.join(out_dir, "%s_benchmark.%s" % (experiment, fmt))
        fig.savefig(target, dpi=90)
        written.append(target)
    plt.close(fig)
    return written


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("database")
    parser.add_argument("out_dir")
    parser.add_argument("--format", default="png,pdf", help="comma-separated: png, pdf, svg (default png,pdf)")
    parser.add_argument("--print", action="store_true", help="print the plotted numbers (tab-separated)")
    args = parser.parse_args(argv)
    formats = [f for f in args.format.split(",") if f]
    if not formats or any(f not in ("png", "pdf", "svg") for f in formats):
        sys.exit("plot_benchmark: --format expects png, pdf and/or svg, got '%s'" % args.format)
    experiments, limits = load(args.database)
    if not experiments:
        sys.exit("plot_benchmark: %s: no runs to plot" % args.database)
    os.makedirs(args.out_dir, exist_ok=True)
    for experiment in sorted(experiments):
        for target in plot(experiment, experiments[experiment], limits.get(experiment, (None, 0))[0], args.out_dir,
                           formats):
            print(target, file=sys.stderr if args.print else sys.stdout)
    if args.print:
        print("experiment\tplanner\tconfiguration\truns\tsolved\tsuccess %\tmedian time s\tmedian length\t"
              "median collision checks")
        for row in summary(experiments):
            print("%s\t%s\t%s\t%d\t%d\t%.6g\t%.6g\t%.6g\t%.6g" % row)


if __name__ == "__main__":
    main(sys.argv[1:])
