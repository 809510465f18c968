#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Build time, memory and size of every hierarchy (OBB, ellipsoid, hybrid trees; LP pieces) on
# OMPL.app meshes, from `hybridcd inspect`, as a Markdown table.
#   bash bench/hierarchy_table.sh
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
resources=${HYBRIDCD_OMPLAPP_RESOURCES:-$root/../shared/omplapp-resources}
echo "| problem | checker: hierarchy | nodes or pieces | depth | build ms | memory KiB | volume ratio node/content |"
echo "|---|---|---:|---:|---:|---:|---:|"
for problem in 3D/cubicles 3D/Twistycool 3D/alpha-1.5 3D/Home 3D/Abstract 3D/Apartment 2D/Maze_planar; do
  cfg=$resources/$problem.cfg
  [ -f "$cfg" ] || continue
  "$root/build/hybridcd" inspect "$cfg" --checker obb,ellipsoid,hybrid,lp | awk -v p="$(basename "$problem")" '
    /^checker / { checker = $2; sub(/:$/, "", checker) }
    /^  (robot|environment) .*(tree|pieces):/ {
      line = $0; sub(/^  /, "", line); split(line, parts, ": ");
      label = parts[1]; rest = parts[2];
      nodes = rest; sub(/ nodes.*/, "", nodes);
      depth = rest; sub(/.*depth /, "", depth); sub(/,.*/, "", depth);
      build = rest; sub(/.*build /, "", build); sub(/ ms.*/, "", build);
      mem = rest; sub(/.*memory /, "", mem); sub(/ KiB.*/, "", mem);
      ratio = "-"; if (rest ~ /volume ratio/) { ratio = rest; sub(/.*content /, "", ratio); sub(/ .*/, "", ratio); }
      printf "| %s | %s: %s | %s | %s | %.1f | %.0f | %s |\n", p, checker, label, nodes, depth, build, mem, ratio }'
done
