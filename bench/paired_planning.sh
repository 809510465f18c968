#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Planning with the same seed under each checker set-up: with one seed OMPL draws the same samples,
# and where the set-ups give the same answers the planner grows the same tree in the same number of
# iterations, so the times differ only by what the checks cost. Prints a Markdown table.
# Usage: bench/paired_planning.sh SEEDS SECONDS PROBLEM.cfg...
#   SEEDS: how many seeds (1..SEEDS); SECONDS: the time limit of each run.
#   $CONFIGS: the set-ups as CHECKER:MOTION words (default "fcl:discrete auto:discrete auto:continuous",
#   the first is the reference of the ratios); $PLANNER (default rrtconnect); $HYBRIDCD_CLI (default
#   build/hybridcd); $NEIGHBORS, the nearest-neighbour search of every set-up (default poses, so that
#   the set-ups differ in their checks alone; ompl for OMPL's GNAT, as OMPL.app plans). Either
#   search finds the same neighbours, so the trees stay the same.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
[ $# -ge 3 ] || { sed -n 3,12p "$0" >&2; exit 1; }
seeds=$1
limit=$2
shift 2
cli=${HYBRIDCD_CLI:-$root/build/hybridcd}
planner=${PLANNER:-rrtconnect}
neighbors=${NEIGHBORS:-poses}
read -r -a configs <<<"${CONFIGS:-fcl:discrete auto:discrete auto:continuous}"
[ -x "$cli" ] || { echo "paired_planning: no hybridcd tool at $cli (build it, or set HYBRIDCD_CLI)" >&2; exit 1; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

header="| problem | seed |"
rule="|---|---:|"
for c in "${configs[@]}"; do
  header+=" $c: iterations, s (checks s) |"
  rule+="---:|"
done
for c in "${configs[@]:1}"; do
  header+=" $c / ${configs[0]} |"
  rule+="---:|"
done
echo "$header"
echo "$rule"
for cfg in "$@"; do
  name=$(basename "$cfg" .cfg)
  for seed in $(seq 1 "$seeds"); do
    row="| $name | $seed |"
    times=()
    for c in "${configs[@]}"; do
      checker=${c%%:*}
      motion=${c##*:}
      log="$out/run.log"
      "$cli" solve "$cfg" --planner "$planner" --seed "$seed" --time "$limit" --checker "$checker" \
        --motion "$motion" --neighbors "$neighbors" --out "$out/path" >"$log" 2>&1 || true
      # "solve: exact solution after T s: N iterations, ..., C s in collision checks"
      line=$(grep -m1 '^solve: exact solution after' "$log" || true)
      if [ -n "$line" ]; then
        it=$(echo "$line" | sed -E 's/.*: ([0-9]+) iterations.*/\1/')
        t=$(sed -nE 's/^solve time: ([0-9.e+-]+) s.*/\1/p' "$log")
        ct=$(sed -nE 's/^collision checking time: ([0-9.e+-]+) s.*/\1/p' "$log")
        row+=" $it, $(printf '%.3f (%.3f)' "$t" "$ct") |"
        times+=("$t")
      else
        row+=" unsolved in $limit s |"
        times+=("-")
      fi
    done
    for t in "${times[@]:1}"; do
      if [ "$t" = - ] || [ "${times[0]}" = - ]; then
        row+=" - |"
      else
        row+=" $(awk -v a="$t" -v b="${times[0]}" 'BEGIN { printf "%.2f", a / b }') |"
      fi
    done
    echo "$row"
  done
done
