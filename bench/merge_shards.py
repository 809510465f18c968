#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Merges the logs of the shards of one `hybridcd bench --shard I/N` benchmark into one OMPL
benchmark log: one experiment, with the shards' runs in run-index order and the run counts summed,
so that `ompl_benchmark_statistics` makes ONE experiment of it (given the shard logs directly, it
makes one experiment per shard).

    python3 bench/merge_shards.py --out merged.log shard0.log shard1.log ... [--db results.db]

Every shard must come from the same command with another --shard I/N: the same experiment name,
planners, properties, limits and total run count, each index 0..N-1 exactly once, and each seeded
with the seed derived from the base seed (SplitMix64 of base * 2^32 + I, folded into 1..2^32-1,
as `hybridcd bench` does). A shard that breaks this is refused with its file and line (exit
status 1), and nothing is written. The merged log names the base seed as its random seed and lists
the shards' seeds in the experiment property shard_seeds. With --db, ompl_benchmark_statistics
then adds the merged log to that database (as OMPL does, beside any experiments already in it).
"""
import argparse
import os
import subprocess
import sys
import tempfile

MASK64 = (1 << 64) - 1


def shard_seed(base, index, count):
    """The seed `hybridcd bench` gives shard `index` of `count` (see src/cli/command_bench.cpp)."""
    if count == 1:
        return base
    z = (((base << 32) | index) + 0x9E3779B97F4A7C15) & MASK64
    z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & MASK64
    z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & MASK64
    z ^= z >> 31
    return z % 4294967295 + 1


class LogError(Exception):
    def __init__(self, path, line, message):
        # Line 0: the log as a whole.
        super().__init__("%s:%d: %s" % (path, line, message) if line else "%s: %s" % (path, message))


class Reader:
    """The lines of one log, read in order, with errors naming the file and line."""

    def __init__(self, path):
        self.path = path
        try:
            with open(path, encoding="utf-8") as f:
                self.lines = f.read().split("\n")
        except (OSError, UnicodeDecodeError) as e:
            raise LogError(path, 0, "cannot read the benchmark log (%s)" % e)
        if self.lines and self.lines[-1] == "":
            self.lines.pop()
        self.at = 0

    def fail(self, message, line=None):
        raise LogError(self.path, self.at if line is None else line, message)

    def next(self, what):
        if self.at >= len(self.lines):
            self.fail("the log ends where %s was expected" % what)
        self.at += 1
        return self.lines[self.at - 1]

    def count(self, suffix):
        """A line "N SUFFIX"; returns N."""
        line = self.next('"N %s"' % suffix)
        head, _, tail = line.partition(" ")
        if tail != suffix or not head.isdigit():
            self.fail('expected "N %s", got "%s"' % (suffix, line))
        return int(head)

    def prefixed(self, prefix):
        line = self.next('"%s..."' % prefix)
        if not line.startswith(prefix):
            self.fail('expected "%s...", got "%s"' % (prefix, line))
        return line[len(prefix):]

    def suffixed(self, suffix):
        line = self.next('"... %s"' % suffix)
        if not line.endswith(" " + suffix):
            self.fail('expected "... %s", got "%s"' % (suffix, line))
        return line[:-len(suffix) - 1]

    def block(self):
        """A multi-line value between "<<<|" and "|>>>", as its lines."""
        if self.next('"<<<|"') != "<<<|":
            self.fail('expected "<<<|"')
        lines = []
        while True:
            line = self.next('"|>>>"')
            if line == "|>>>":
                return lines
            lines.append(line)


def read_log(path):
    r = Reader(path)
    log = {"path": path}
    log["version"] = r.prefixed("OMPL version")
    log["name"] = r.prefixed("Experiment ")
    log["properties"] = {}
    for _ in range(r.count("experiment properties")):
        line = r.next("an experiment property")
        key, sep, value = line.partition(" = ")
        if not sep:
            r.fail('expected "NAME TYPE = VALUE", got "%s"' % line)
        log["properties"][key] = (value, r.at)
    log["host"] = r.prefixed("Running on ")
    log["date"] = r.prefixed("Starting at ")
    log["setup"] = r.block()
    log["cpu"] = r.block()
    log["seed_line"] = r.at + 1
    log["seed"] = r.suffixed("is the random seed")
    log["time_limit"] = r.suffixed("seconds per run")
    log["memory_limit"] = r.suffixed("MB per run")
    log["runs_line"] = r.at + 1
    log["runs"] = int(r.suffixed("runs per planner"))
    log["total_time"] = float(r.suffixed("seconds spent to collect the data"))
    enums = r.next('"N enum type(s)"')
    count = enums.split(" ")[0]
    if not count.isdigit() or not enums.endswith((" enum type", " enum types")):
        r.fail('expected "N enum types", got "%s"' % enums)
    log["enum_header"] = enums
    log["enums"] = [r.next("an enum") for _ in range(int(count))]
    log["planners"] = []
    for _ in range(r.count("planners")):
        planner = {"name": r.next("a planner name"), "line": r.at}
        planner["common"] = [r.next("a common property") for _ in range(r.count("common properties"))]
        planner["properties"] = [r.next("a run property") for _ in range(r.count("properties for each run"))]
        runs_line = r.at + 1
        planner["runs"] = [r.next("a run") for _ in range(r.count("runs"))]
        planner["runs_line"] = runs_line
        planner["progress_properties"] = None
        planner["progress"] = [None] * len(planner["runs"])
        line = r.next('"." or progress data')
        if line != ".":
            r.at -= 1
            planner["progress_properties"] = [r.next("a progress property")
                                              for _ in range(r.count("progress properties for each run"))]
            progress = [r.next("a run's progress") for _ in range(r.count("runs"))]
            if len(progress) != len(planner["runs"]):
                r.fail("%d runs of progress data for %d runs" % (len(progress), len(planner["runs"])))
            planner["progress"] = progress
            if r.next('"."') != ".":
                r.fail('expected "." after the progress data')
        log["planners"].append(planner)
    if r.at != len(r.lines):
        r.fail("unexpected text after the last planner", r.at + 1)
    return log


def prop(log, key):
    """The value of experiment property `key` (written "key TYPE = value"), or None."""
    for name, (value, _) in log["properties"].items():
        if name.rsplit(" ", 1)[0] == key:
            return value
    return None


def integer_prop(log, key):
    value = prop(log, key)
    if value is None or not value.lstrip("-").isdigit():
        raise LogError(log["path"], 0, "not a log of `hybridcd bench`: no %s property" % key)
    return int(value)


def merge(logs):
    first = logs[0]
    count = integer_prop(first, "shard_count")
    total = integer_prop(first, "total_runs")
    base = integer_prop(first, "base_seed")
    per_shard = {"shard_index", "shard_seed"}
    shared = {k: v for k, (v, _) in first["properties"].items() if k.rsplit(" ", 1)[0] not in per_shard}
    by_index = {}
    for log in logs:
        path = log["path"]
        mine = {k: v for k, (v, _) in log["properties"].items() if k.rsplit(" ", 1)[0] not in per_shard}
        for key in sorted(set(mine) | set(shared)):
            if mine.get(key) != shared.get(key):
                line = log["properties"].get(key, (None, 0))[1]
                raise LogError(path, line, "experiment property %s is %s here, %s in %s" %
                               (key, mine.get(key), shared.get(key), first["path"]))
        index = integer_prop(log, "shard_index")
        if index in by_index:
            raise LogError(path, 0, "shard %d/%d is also %s" % (index, count, by_index[index]["path"]))
        by_index[index] = log
        for key, what in (("name", "experiment name"), ("version", "OMPL version"), ("time_limit", "time limit"),
                          ("memory_limit", "memory limit"), ("enums", "status enums")):
            if log[key] != first[key]:
                raise LogError(path, 0, "the %s differs from %s's" % (what, first["path"]))
        if not 0 <= index < count:
            raise LogError(path, 0, "shard index %d is not below the shard count %d" % (index, count))
        expected_seed = shard_seed(base, index, count)
        if log["seed"] != str(expected_seed):
            raise LogError(path, log["seed_line"], "seed %s, but shard %d/%d of base seed %d is seeded with %d" %
                           (log["seed"], index, count, base, expected_seed))
        expected_runs = (total - index + count - 1) // count
        if log["runs"] != expected_runs:
            raise LogError(path, log["runs_line"], "%d runs per planner, but shard %d/%d of %d runs has %d" %
                           (log["runs"], index, count, total, expected_runs))
        if [p["name"] for p in log["planners"]] != [p["name"] for p in first["planners"]]:
            raise LogError(path, 0, "the planners differ from %s's" % first["path"])
        for mine, theirs in zip(log["planners"], first["planners"]):
            for key in ("common", "properties", "progress_properties"):
                if mine[key] != theirs[key]:
                    raise LogError(path, mine["line"], "planner %s: its %s differ from %s's" %
                                   (mine["name"], key.replace("_", " "), first["path"]))
            if len(mine["runs"]) != expected_runs:
                raise LogError(path, mine["runs_line"], "planner %s has %d runs, not %d" %
                               (mine["name"], len(mine["runs"]), expected_runs))
    missing = [i for i in range(count) if i not in by_index]
    if missing:
        raise LogError(logs[0]["path"], 0, "shards %s of %d are missing" % (", ".join(map(str, missing)), count))

    ordered = [by_index[i] for i in range(count)]
    out = ["OMPL version" + first["version"], "Experiment " + first["name"]]
    properties = dict(shared)
    properties["shard_seeds VARCHAR(1024)"] = ",".join(log["seed"] for log in ordered)
    out.append("%d experiment properties" % len(properties))
    out += ["%s = %s" % (k, v) for k, v in sorted(properties.items())]
    hosts = []
    for log in ordered:
        if log["host"] not in hosts:
            hosts.append(log["host"])
    out.append("Running on " + ",".join(hosts))
    out.append("Starting at " + min(log["date"] for log in ordered))
    out += ["<<<|"] + first["setup"] + ["|>>>", "<<<|"] + first["cpu"] + ["|>>>"]
    out.append("%d is the random seed" % base)
    out.append("%s seconds per run" % first["time_limit"])
    out.append("%s MB per run" % first["memory_limit"])
    out.append("%d runs per planner" % total)
    out.append("%g seconds spent to collect the data" % sum(log["total_time"] for log in ordered))
    out += [first["enum_header"]] + first["enums"]
    out.append("%d planners" % len(first["planners"]))
    for p, planner in enumerate(first["planners"]):
        out.append(planner["name"])
        out.append("%d common properties" % len(planner["common"]))
        out += planner["common"]
        out.append("%d properties for each run" % len(planner["properties"]))
        out += planner["properties"]
        if "run index INTEGER" not in planner["properties"]:
            raise LogError(first["path"], planner["line"], "planner %s has no run index" % planner["name"])
        column = planner["properties"].index("run index INTEGER")
        rows = []
        for log in ordered:
            mine = log["planners"][p]
            for r, run in enumerate(mine["runs"]):
                fields = run.split("; ")
                index = int(fields[column]) if len(fields) > column and fields[column].isdigit() else -1
                shard = integer_prop(log, "shard_index")
                if index % count != shard or index >= total:
                    raise LogError(log["path"], mine["runs_line"] + 1 + r,
                                   "run index %s does not belong to shard %d/%d" % (fields[column], shard, count))
                rows.append((index, run, mine["progress"][r]))
        rows.sort(key=lambda row: row[0])
        out.append("%d runs" % len(rows))
        out += [run for _, run, _ in rows]
        if planner["progress_properties"] is not None:
            out.append("%d progress properties for each run" % len(planner["progress_properties"]))
            out += planner["progress_properties"]
            out.append("%d runs" % len(rows))
            out += [progress for _, _, progress in rows]
        out.append(".")
    return "\n".join(out) + "\n"


def write_atomically(path, text):
    folder = os.path.dirname(os.path.abspath(path))
    handle, temporary = tempfile.mkstemp(prefix="." + os.path.basename(path) + ".tmp.", dir=folder)
    try:
        with os.fdopen(handle, "w", encoding="utf-8") as f:
            f.write(text)
        os.replace(temporary, path)
    except BaseException:
        os.unlink(temporary)
        raise


class Parser(argparse.ArgumentParser):
    def error(self, message):  # misuse exits 1, as hybridcd's commands do
        self.print_usage(sys.stderr)
        sys.exit("%s: %s" % (self.prog, message))


def main(argv):
    parser = Parser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", required=True, help="the merged OMPL benchmark log")
    parser.add_argument("--db", help="then add the merged log to this SQLite database (ompl_benchmark_statistics)")
    parser.add_argument("shards", nargs="+", help="the shards' logs (hybridcd bench --shard I/N)")
    args = parser.parse_args(argv)
    try:
        text = merge([read_log(path) for path in args.shards])
    except LogError as e:
        sys.exit("merge_shards: %s" % e)
    if os.path.abspath(args.out) in map(os.path.abspath, args.shards):
        sys.exit("merge_shards: --out %s is one of the shards" % args.out)
    try:
        write_atomically(args.out, text)
    except OSError as e:
        sys.exit("merge_shards: cannot write %s: %s" % (args.out, e))
    print("merged %d shards into %s" % (len(args.shards), args.out))
    if args.db:
        result = subprocess.run(["ompl_benchmark_statistics", args.out, "-d", args.db], stdout=subprocess.DEVNULL)
        if result.returncode != 0:
            sys.exit("merge_shards: ompl_benchmark_statistics failed on %s" % args.out)
        print("added to %s" % args.db)


if __name__ == "__main__":
    main(sys.argv[1:])
