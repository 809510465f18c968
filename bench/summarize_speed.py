#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Summarises the tables bench/speed_report.sh writes into one folder as the speed report: per
problem, hybridcd's figures against FCL's and OMPL.app's set-up measured in the same run, the
ratios, and each issue target's line with whether it is met.

    python3 bench/summarize_speed.py FOLDER

Reads whichever of these the folder holds (each the Markdown output of a bench program):
states.md and distance.md (hybridcd_bench_checkers with --checker auto,fcl, the second with
--distance), scaling.md (hybridcd_bench_scaling), motions.md and touching.md
(hybridcd_bench_motions, timing and the brute-force pass), planning.md (summarize_benchmark.py).
"""
import math
import os
import statistics
import sys


def tables(path):
    """The Markdown tables of a file, each a list of rows, each row a dict by column header."""
    out, header = [], None
    with open(path, encoding="utf-8") as f:
        for line in f:
            line = line.strip()
            if not line.startswith("|"):
                header = None
                continue
            cells = [c.strip() for c in line.strip("|").split("|")]
            if header is None:
                header = cells
                out.append([])
            elif not all(set(c) <= set("-:") for c in cells):
                out[-1].append(dict(zip(header, cells)))
    return out


def number(text):
    try:
        return float(text.replace(",", ""))
    except ValueError:
        return math.nan


def rows_of(folder, name):
    path = os.path.join(folder, name)
    if not os.path.exists(path):
        return None
    return [row for table in tables(path) for row in table]


def verdict(met):
    return "**met**" if met else "not met"


def per_check(folder, name, unit, target_median, target_each):
    """State checks or clearance: hybridcd auto against fcl per problem, speed-ups FCL / auto."""
    rows = rows_of(folder, name)
    if rows is None:
        return
    median_key = "median ns/" + unit
    mean_key = "mean ns/" + unit
    by_problem = {}
    for row in rows:
        by_problem.setdefault(row["problem"], {})[row["checker"]] = row
    print("| problem | auto median ns | fcl median ns | FCL / auto (median) | auto mean ns | fcl mean ns "
          "| FCL / auto (mean) |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    speedups = []
    for problem, checkers in by_problem.items():
        if "auto" not in checkers or "fcl" not in checkers:
            continue
        a, f = checkers["auto"], checkers["fcl"]
        median_speedup = number(f[median_key]) / number(a[median_key])
        mean_speedup = number(f[mean_key]) / number(a[mean_key])
        speedups.append((problem, median_speedup))
        print("| %s | %s | %s | %.1fx | %s | %s | %.1fx |" % (problem, a[median_key], f[median_key], median_speedup,
                                                            a[mean_key], f[mean_key], mean_speedup))
    if not speedups:
        return
    values = [s for _, s in speedups]
    least = min(speedups, key=lambda p: p[1])
    middle = statistics.median(values)
    print()
    line = "FCL / auto at the median per %s: **%.1fx at the median over the %d problems**, at least %.1fx (%s)." % (
        unit, middle, len(values), least[1], least[0])
    if target_median:
        line += " Target: at least %gx at the median over them and %gx on every one: %s." % (
            target_median, target_each, verdict(middle >= target_median and least[1] >= target_each))
    else:
        short = [p for p, s in speedups if s < target_each]
        line += " Target: at least %gx on every one: %s%s." % (
            target_each, verdict(not short), "" if not short else " (short on " + ", ".join(short) + ")")
    print(line)


def scaling(folder):
    rows = rows_of(folder, "scaling.md")
    if rows is None:
        return
    sizes = {}
    for row in rows:
        sizes.setdefault(int(number(row["environment triangles"])), {})[row["checker"]] = row
    print("| environment triangles | auto ns/check | fcl ns/check | auto build ms | fcl build ms | build auto / fcl "
          "| auto MiB | fcl MiB | memory auto / fcl |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    points = []
    for size in sorted(sizes):
        checkers = sizes[size]
        if "auto" not in checkers or "fcl" not in checkers:
            continue
        a, f = checkers["auto"], checkers["fcl"]
        build = number(a["build ms"]) / number(f["build ms"])
        memory = number(a["memory MiB"]) / number(f["memory MiB"])
        points.append((size, number(a["median ns/check"]), build, memory))
        print("| %d | %s | %s | %s | %s | %.2f | %s | %s | %.2f |" % (size, a["median ns/check"], f["median ns/check"],
                                                                   a["build ms"], f["build ms"], build,
                                                                   a["memory MiB"], f["memory MiB"], memory))
    if len(points) < 2:
        return
    first, last = points[0], points[-1]
    growth = last[1] / first[1]
    log_growth = math.log(last[0]) / math.log(first[0])
    at_or_below = [p[0] for p in points if p[2] <= 1.0 and p[3] <= 1.0]
    print()
    print("ns per check grows %.2fx from %d to %d triangles, against log(triangles)'s %.2fx: %s. Build time and "
          "memory at or below FCL's at %d of %d sizes%s: %s." % (
              growth, first[0], last[0], log_growth, verdict(growth <= log_growth), len(at_or_below), len(points),
              " (" + ", ".join(str(s) for s in at_or_below) + " triangles)" if at_or_below else "",
              verdict(len(at_or_below) == len(points))))


def motions(folder):
    rows = rows_of(folder, "motions.md")
    if rows is None:
        return
    touching_rows = rows_of(folder, "touching.md") or []
    touching = {(r["problem"], r["validator"], r["state checker"]): r["accepted but touching"] for r in touching_rows}
    by_problem = {}
    for row in rows:
        by_problem.setdefault(row["problem"], {})[(row["validator"], row["state checker"])] = row
    print("| problem | verdict median us | discrete+fcl median us | verdict / discrete (median) | verdict / discrete "
          "(mean) | lastValid / verdict (mean) | touching accepted: continuous / discrete+fcl |")
    print("|---|---:|---:|---:|---:|---:|---|")
    verdicts, last_valid = [], []
    for problem, validators in by_problem.items():
        verdict_row = next((r for (v, _), r in validators.items() if v == "continuous"), None)
        last_row = next((r for (v, _), r in validators.items() if v == "continuous, lastValid"), None)
        fcl = validators.get(("discrete", "fcl"))
        if not verdict_row or not fcl:
            continue
        median_ratio = number(verdict_row["median us/motion"]) / number(fcl["median us/motion"])
        mean_ratio = number(verdict_row["mean us/motion"]) / number(fcl["mean us/motion"])
        last_ratio = (number(last_row["mean us/motion"]) / number(verdict_row["mean us/motion"])
                      if last_row else math.nan)
        verdicts.append((problem, median_ratio))
        last_valid.append((problem, last_ratio))
        checker = next(c for (v, c) in validators if v == "continuous")
        accepted = "%s / %s" % (touching.get((problem, "continuous", checker), "-"),
                                touching.get((problem, "discrete", "fcl"), "-"))
        print("| %s | %s | %s | %.2f | %.2f | %.2f | %s |" % (problem, verdict_row["median us/motion"],
                                                           fcl["median us/motion"], median_ratio, mean_ratio,
                                                           last_ratio, accepted))
    if not verdicts:
        return
    values = [r for _, r in verdicts]
    middle = statistics.median(values)
    worst = max(verdicts, key=lambda p: p[1])
    over_two = [p for p, r in last_valid if not r <= 2.0]
    print()
    print("Continuous verdict against the discrete validator with FCL at the median per motion: **%.2fx at the "
          "median over the %d problems** (%.0fx cheaper), at most %.2fx (%s). Target: cheaper on every one and at "
          "least 5x cheaper at the median: %s. lastValid at most twice the verdict (mean): %s%s." % (
              middle, len(values), 1.0 / middle, worst[1], worst[0], verdict(worst[1] < 1.0 and middle <= 0.2),
              verdict(not over_two), "" if not over_two else " (over on " + ", ".join(over_two) + ")"))


def main(folder):
    sections = [
        ("State checks (FCL's `collide` / hybridcd's `auto`, same states)", lambda: per_check(
            folder, "states.md", "check", 10, 3)),
        ("Clearance (`fcl::distance` / hybridcd's `distance()`, same states)", lambda: per_check(
            folder, "distance.md", "distance", None, 10)),
        ("Scaling (one scene subdivided)", lambda: scaling(folder)),
        ("Motions (continuous verdict and lastValid against OMPL's discrete validator with FCL)",
         lambda: motions(folder)),
    ]
    for title, section in sections:
        print("### " + title)
        print()
        section()
        print()
    planning_summary(folder)


def planning_summary(folder):
    """summarize_benchmark.py's table, then per planner the certified set-up against OMPL.app's."""
    rows = rows_of(folder, "planning.md")
    if rows is None:
        return
    print("### Planning (OMPL benchmark runs; vs OMPL.app: median solve time over OMPL.app's set-up's)")
    print()
    with open(os.path.join(folder, "planning.md"), encoding="utf-8") as f:
        print(f.read().rstrip())
    print()
    runs = {}
    for row in rows:
        planner, _, configuration = row["planner[configuration]"].partition("[")
        solved = round(number(row["runs"]) * number(row["solved"].rstrip("%")) / 100.0)
        runs.setdefault(planner, {})[(row["problem"], configuration.rstrip("]"))] = (
            solved, int(number(row["runs"])), number(row["vs OMPL.app"]))
    for planner, cells in sorted(runs.items()):
        problems = sorted({p for p, c in cells if c == "auto+continuous"})
        parts, ratios, fewer = [], [], []
        for problem in problems:
            mine = cells[(problem, "auto+continuous")]
            theirs = cells.get((problem, "fcl+discrete(0.01)"))
            if not theirs:
                continue
            ratios.append(mine[2])
            if mine[0] < theirs[0]:
                fewer.append(problem)
            parts.append("%s %.2fx (%d/%d against %d/%d)" % (problem, mine[2], mine[0], mine[1], theirs[0],
                                                            theirs[1]))
        if not parts:
            continue
        line = "%s, certified motions against OMPL.app's set-up, median solve time: %s. " % (planner, "; ".join(parts))
        if planner == "RRTConnect":
            line += ("Target: solved at least as often everywhere and at most 0.2x on every one: %s%s." % (
                verdict(not fewer and max(ratios) <= 0.2),
                "" if not fewer else " (fewer solved on " + ", ".join(fewer) + ")"))
        else:
            line += "Target: no slower on every one: %s." % verdict(max(ratios) <= 1.0 and not fewer)
        print(line)
        print()


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
