#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Planning comparison: RRTConnect, KPIECE and PRM over RUNS runs with each checker, on OMPL.app
# problems, written as OMPL benchmark logs, merged into one SQLite database, summarised as Markdown.
#   bash bench/planning_comparison.sh [RUNS] [SECONDS] [OUTPUT_FOLDER]
# Two configurations per problem: OMPL.app's own (discrete motion checks) with obb and fcl, and
# hybridcd's continuous motion validation with obb.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
runs=${1:-10}
seconds=${2:-10}
out=${3:-$root/build/bench-results}
resources=${HYBRIDCD_OMPLAPP_RESOURCES:-$root/../shared/omplapp-resources}
cli=$root/build/hybridcd
mkdir -p "$out"
logs=()
for problem in 3D/cubicles 3D/Easy 3D/Abstract 2D/Maze_planar; do
  cfg=$resources/$problem.cfg
  [ -f "$cfg" ] || { echo "skipping $problem: $cfg not found" >&2; continue; }
  name=$(basename "$problem")
  "$cli" bench "$cfg" --checker obb,fcl --motion discrete --planner rrtconnect,kpiece,prm \
    --runs "$runs" --time "$seconds" --seed 1 --out "$out/${name}_discrete.log"
  "$cli" bench "$cfg" --checker obb --motion continuous --planner rrtconnect,kpiece,prm \
    --runs "$runs" --time "$seconds" --seed 1 --out "$out/${name}_continuous.log"
  logs+=("$out/${name}_discrete.log" "$out/${name}_continuous.log")
done
rm -f "$out/planning.db"
ompl_benchmark_statistics "${logs[@]}" -d "$out/planning.db" >/dev/null
python3 "$root/bench/summarize_benchmark.py" "$out/planning.db"
