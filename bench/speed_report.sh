#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The speed report: hybridcd against FCL and OMPL.app's set-up, measured in the same runs, per
# OMPL.app problem, with the ratios and each speed target's line (bench/summarize_speed.py).
#   bash bench/speed_report.sh states  [OUTPUT_FOLDER]  # state checks, clearance, scaling (about 20 min)
#   bash bench/speed_report.sh motions [OUTPUT_FOLDER]  # motions (about 15 min), then planning (1-2 h)
#   bash bench/speed_report.sh all     [OUTPUT_FOLDER]
# The raw tables stay in the folder (default build/speed-report); the summary is printed and
# written to summary.md there. Environment overrides (defaults in brackets): STATES [20000] and
# DISTANCE_STATES [2000] random states per problem, MAX_TRIANGLES [2000000] for the scaling table,
# MOTIONS [2000] timed motions per problem (each timed by its fastest of three passes) and
# TOUCHING_MOTIONS [150] checked against brute force, RUNS [10] runs of PLAN_SECONDS [30] per planner and set-up,
# PLANNERS [rrtconnect,kpiece,prm]; HYBRIDCD_OMPLAPP_RESOURCES [../shared/omplapp-resources].
# Builds the benchmark programs first when they are missing.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
part=${1:-}
out=${2:-$root/build/speed-report}
case "$part" in
  states | motions | all) ;;
  *)
    sed -n '3,6p' "$0" | sed 's/^# //' >&2
    exit 1
    ;;
esac
resources=${HYBRIDCD_OMPLAPP_RESOURCES:-$root/../shared/omplapp-resources}
[ -d "$resources/3D" ] || { echo "speed_report: OMPL.app's resources not found at $resources" >&2; exit 1; }
bench=$root/build/bench
if [ ! -x "$bench/hybridcd_bench_checkers" ] || [ ! -x "$bench/hybridcd_bench_motions" ] ||
  [ ! -x "$bench/hybridcd_bench_scaling" ] || [ ! -x "$root/build/hybridcd" ]; then
  bash "$root/scripts/build.sh" -DHYBRIDCD_BUILD_BENCH=ON
fi
mkdir -p "$out"
ten=()
for p in 3D/cubicles 3D/Easy 3D/Twistycool 3D/alpha-1.5 3D/Apartment 3D/Home 3D/bugtrap 3D/Abstract \
  2D/Maze_planar 2D/BugTrap_planar; do
  ten+=("$resources/$p.cfg")
done
# Each table goes to a temporary file first, so that an interrupted run leaves no partial table.
table() {
  local name=$1
  shift
  echo "speed_report: $name ($*)" >&2
  "$@" > "$out/$name.partial"
  mv "$out/$name.partial" "$out/$name"
}
if [ "$part" != motions ]; then
  table states.md "$bench/hybridcd_bench_checkers" --states "${STATES:-20000}" --checker auto,fcl "${ten[@]}"
  table distance.md "$bench/hybridcd_bench_checkers" --distance --states "${DISTANCE_STATES:-2000}" \
    --checker auto,fcl "${ten[@]}"
  table scaling.md "$bench/hybridcd_bench_scaling" --states 1000 --max-triangles "${MAX_TRIANGLES:-2000000}" \
    --checker auto,fcl "$root/problems/window_3d.cfg"
fi
if [ "$part" != states ]; then
  table touching.md "$bench/hybridcd_bench_motions" --motions "${TOUCHING_MOTIONS:-150}" "${ten[@]}"
  table motions.md "$bench/hybridcd_bench_motions" --no-touching --repeat 3 --motions "${MOTIONS:-2000}" "${ten[@]}"
  echo "speed_report: planning (bench/planning_comparison.sh)" >&2
  PROBLEMS="3D/cubicles 3D/Easy 3D/Home 3D/Twistycool 3D/alpha-1.5 2D/Maze_planar 2D/BugTrap_planar" \
    PLANNERS=${PLANNERS:-rrtconnect,kpiece,prm} CHECKER=auto MOTIONS=continuous \
    bash "$root/bench/planning_comparison.sh" "${RUNS:-10}" "${PLAN_SECONDS:-30}" "$out/planning" |
    grep '^|' > "$out/planning.partial"
  mv "$out/planning.partial" "$out/planning.md"
fi
python3 "$root/bench/summarize_speed.py" "$out" | tee "$out/summary.md"
