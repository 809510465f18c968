#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Solves OMPL.app's kinodynamic problems with each control planner over a few seeds and prints one
# Markdown row per run (the table in bench/README.md, section 7). Each run takes the shared build
# lock on its own, so other builds are never held up for long.
#
#   bash bench/kinodynamic_runs.sh [RESOURCES [SEEDS [TIME [PLANNERS [MOTIONS [PROBLEMS]]]]]]
#   bash bench/kinodynamic_runs.sh ../shared/omplapp-resources "1 2 3" 60 "kpiece rrt sst" continuous
#
# Defaults: ../shared/omplapp-resources beside the source tree, seeds 1 2 3, 60 s per run,
# planners kpiece rrt sst, motion check continuous, problems 2D/Maze_kcar.cfg 2D/BugTrap_dcar.cfg.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
resources=${1:-$root/../shared/omplapp-resources}
seeds=${2:-1 2 3}
time_limit=${3:-60}
planners=${4:-kpiece rrt sst}
motions=${5:-continuous}
problems=${6:-2D/Maze_kcar.cfg 2D/BugTrap_dcar.cfg}
exe="$root/build/hybridcd"
[ -x "$exe" ] || { echo "missing $exe: build first (bash scripts/build.sh)" >&2; exit 1; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

echo "| problem | planner | motion check | seed | solved | solve time (s) | collision checks | controls |"
echo "|---|---|---|---|---|---|---|---|"
for problem in $problems; do
  for planner in $planners; do
    for motion in $motions; do
      for seed in $seeds; do
        log=$(flock /tmp/hybridcd-build.lock "$exe" solve "$resources/$problem" --planner "$planner" \
          --motion "$motion" --seed "$seed" --time "$time_limit" --out "$out/path" 2>&1 || true)
        field() { sed -n "s/^$1: \([^ ]*\).*/\1/p" <<<"$log" | head -1; }
        echo "| $(basename "$problem" .cfg) | $planner | $motion | $seed | $(field solved) | $(field 'solve time') |" \
          "$(field 'collision checks') | $(field controls) |"
      done
    done
  done
done
