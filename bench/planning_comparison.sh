#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Planning comparison: RRTConnect, KPIECE and PRM over RUNS runs with each checker, on OMPL.app
# problems, written as OMPL benchmark logs, merged into one SQLite database, summarised as Markdown.
#   bash bench/planning_comparison.sh [RUNS] [SECONDS] [OUTPUT_FOLDER]
# Environment overrides (defaults in brackets): PROBLEMS, names under OMPL.app's resources
# ["3D/cubicles 3D/Easy 3D/Abstract 2D/Maze_planar"]; PLANNERS [rrtconnect,kpiece,prm];
# CHECKER [obb]; MOTIONS [continuous,discrete].
# Three configurations per problem, in one log: OMPL.app's own set-up (the baseline,
# fcl+discrete(0.01): FCL and OMPL's DiscreteMotionValidator at resolution 0.01), hybridcd's obb
# checker with the same discrete motion checks (obb+discrete(0.01)), and with hybridcd's continuous
# motion validation (obb+continuous).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
runs=${1:-10}
seconds=${2:-10}
out=${3:-$root/build/bench-results}
resources=${HYBRIDCD_OMPLAPP_RESOURCES:-$root/../shared/omplapp-resources}
cli=$root/build/hybridcd
mkdir -p "$out"
logs=()
problems=${PROBLEMS:-3D/cubicles 3D/Easy 3D/Abstract 2D/Maze_planar}
# shellcheck disable=SC2086 # one name per word
for problem in $problems; do
  cfg=$resources/$problem.cfg
  [ -f "$cfg" ] || { echo "skipping $problem: $cfg not found" >&2; continue; }
  name=$(basename "$problem")
  "$cli" bench "$cfg" --checker "${CHECKER:-obb}" --motion "${MOTIONS:-continuous,discrete}" --baseline omplapp \
    --planner "${PLANNERS:-rrtconnect,kpiece,prm}" --runs "$runs" --time "$seconds" --seed 1 --out "$out/$name.log"
  logs+=("$out/$name.log")
done
rm -f "$out/planning.db"
ompl_benchmark_statistics "${logs[@]}" -d "$out/planning.db" >/dev/null
python3 "$root/bench/summarize_benchmark.py" "$out/planning.db"
