#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# One table over every bounding volume (obb, ellipsoid, hybrid, sphere, aabb, aabb-fixed, kdop14,
# kdop18, kdop26, ssv, octree, medial, ctree) on OMPL.app's problems and the project's organic ones: node/content volume ratio, build time and memory (from
# `hybridcd inspect`), nanoseconds per volume test (hybridcd_bench_micro's BM_VolumeOverlap and
# BM_VolumeTransform), node pairs tested and median nanoseconds per check and the ratio to FCL
# (hybridcd_bench_checkers on the same uniform states). Needs the bench build
# (-DHYBRIDCD_BUILD_BENCH=ON, with FCL).
#   bash bench/hierarchy_table.sh [--states N] [PROBLEM ...]
# PROBLEM is a .cfg path or a name under OMPL.app's resources such as 3D/cubicles; by default the
# ten problems of bench/README.md and the project's three organic ones, 2000 states each.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
resources=${HYBRIDCD_OMPLAPP_RESOURCES:-$root/../shared/omplapp-resources}
checkers=obb,ellipsoid,hybrid,sphere,aabb,aabb-fixed,kdop14,kdop18,kdop26
# Swept spheres, and the environment octree (robot OBB tree against cells; its volume test is an
# OBB against a cube, BM_VolumeOverlap/octree, and its environment has no volume ratio).
checkers=$checkers,ssv,octree
checkers+=,medial  # spheres on the medial axis of closed solids (exact mode)
checkers+=,ctree   # C-trees: a sphere or a box per node, whichever is smaller
states=2000
problems=()
while [ $# -gt 0 ]; do
  case "$1" in
    --states) states=$2; shift 2 ;;
    -h|--help) sed -n '2,12p' "$0"; exit 0 ;;
    *) problems+=("$1"); shift ;;
  esac
done
if [ ${#problems[@]} -eq 0 ]; then
  problems=(3D/cubicles 3D/Easy 3D/Twistycool 3D/alpha-1.5 3D/Apartment 3D/Home 3D/bugtrap 3D/Abstract
            2D/Maze_planar 2D/BugTrap_planar)
  # The project's organic problems (smooth closed meshes, problems/README.md).
  problems+=("$root/problems/bone_3d.cfg" "$root/problems/ribcage_3d.cfg" "$root/problems/bones_2d.cfg")
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# Per volume: ns of one node-pair test, and of placing one robot node in the world frame.
"$root/build/bench/hybridcd_bench_micro" --benchmark_filter='BM_Volume' --benchmark_format=csv 2>/dev/null |
  awk -F, '/^"BM_Volume/ { name = $1; gsub(/"/, "", name); split(name, p, "/");
                           kind = (p[1] == "BM_VolumeOverlap") ? "overlap" : "place"; print p[2], kind, $4 }' \
  > "$tmp/micro.txt"

echo "| problem | checker | volume ratio node/content robot / env | build ms | memory KiB | ns per volume test (+ placing a robot node) | node pairs tested per check | median ns per check | vs FCL |"
echo "|---|---|---:|---:|---:|---:|---:|---:|---:|"
for problem in "${problems[@]}"; do
  cfg=$problem
  [ -f "$cfg" ] || cfg=$resources/$problem.cfg
  [ -f "$cfg" ] || { echo "hierarchy_table.sh: no problem file $problem" >&2; exit 1; }
  name=$(basename "$cfg" .cfg)
  "$root/build/hybridcd" inspect "$cfg" --no-grid --checker "$checkers" | awk '
    /^checker / { checker = $2; sub(/:$/, "", checker) }
    /^  (robot|environment) .*(tree:|octree \()/ {
      side = ($1 == "robot") ? "r" : "e";
      line = $0;
      build = line; sub(/.*build /, "", build); sub(/ ms.*/, "", build);
      mem = line; sub(/.*memory /, "", mem); sub(/ KiB.*/, "", mem);
      ratio = "-"; if (line ~ /volume ratio/) { ratio = line; sub(/.*content /, "", ratio); sub(/ .*/, "", ratio) }
      b[checker] += build; m[checker] += mem; r[checker, side] = ratio; seen[checker] = 1 }
    END { for (c in seen) printf "%s %s %s %.2f %.0f\n", c, r[c, "r"], r[c, "e"], b[c], m[c] }' > "$tmp/inspect.txt"
  "$root/build/bench/hybridcd_bench_checkers" --states "$states" --raw-times --no-reference --no-grid --checker "$checkers,fcl" "$cfg" |
    awk -F'|' 'NR > 2 && /^[|]/ { gsub(/ /, "", $3); gsub(/ /, "", $4); gsub(/ /, "", $6); gsub(/ /, "", $10);
                        print $3, $4, $6, $10 }' > "$tmp/checks.txt"
  awk -v p="$name" '
    FILENAME ~ /micro/ { ns[$1, $2] = $3; next }
    FILENAME ~ /inspect/ { rr[$1] = $2; re[$1] = $3; build[$1] = $4; mem[$1] = $5; next }
    { c = $1; med = $2; vs = $3; pairs = $4;
      if (c == "fcl") { printf "| %s | fcl (OBBRSS) | - | - | - | - | - | %s | 1.00 |\n", p, med; next }
      ratio = sprintf("%s / %s", rr[c] == "-" ? "-" : sprintf("%.3g", rr[c]), re[c] == "-" ? "-" : sprintf("%.3g", re[c]));
      vt = sprintf("%.1f (+ %.1f)", ns[c, "overlap"], ns[c, "place"]);
      printf "| %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", p, c, ratio, build[c], mem[c], vt, pairs, med, vs }
  ' "$tmp/micro.txt" "$tmp/inspect.txt" "$tmp/checks.txt"
done
