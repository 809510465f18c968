#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Pictures of problems with their paths: for each .cfg, NAME.png in OUT_DIR, drawn with the path
# beside the .cfg (NAME.path, as OMPL.app ships them) or, without one, a path solved by
# `hybridcd solve` into OUT_DIR/NAME.path. A problem that is not solved in time is drawn without
# a path, and one that cannot be loaded is reported; the script then exits 1 at the end.
# Usage: scripts/render_problems.sh OUT_DIR [PROBLEM.cfg...]
#   Without problems: problems/*.cfg and, when present, OMPL.app's 2D/ and 3D/ problems
#   ($HYBRIDCD_OMPLAPP_RESOURCES, else ../shared/omplapp-resources beside the source tree).
#   $HYBRIDCD_CLI names the tool (default build/hybridcd); $SOLVE_TIME the seconds per solve (30).
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
[ $# -ge 1 ] || { sed -n 3,10p "$0" >&2; exit 1; }
out=$1
shift
cli=${HYBRIDCD_CLI:-$root/build/hybridcd}
[ -x "$cli" ] || { echo "render_problems: no hybridcd tool at $cli (build it, or set HYBRIDCD_CLI)" >&2; exit 1; }
mkdir -p "$out" || exit 1
problems=("$@")
if [ ${#problems[@]} -eq 0 ]; then
  problems=("$root"/problems/*.cfg)
  resources=${HYBRIDCD_OMPLAPP_RESOURCES:-$root/../shared/omplapp-resources}
  [ -d "$resources" ] && problems+=("$resources"/2D/*.cfg "$resources"/3D/*.cfg)
fi

failed=0
for cfg in "${problems[@]}"; do
  name=$(basename "$cfg" .cfg)
  path=$(dirname "$cfg")/$name.path
  note="path $path"
  if [ ! -f "$path" ]; then
    path=$out/$name.path
    if "$cli" solve "$cfg" --seed 1 --time "${SOLVE_TIME:-30}" --out "$path" >"$out/$name.solve.txt" 2>&1; then
      note="path solved into $path"
    else
      note="no path ($(grep -m 1 -E '^solved:|error:' "$out/$name.solve.txt" || tail -n 1 "$out/$name.solve.txt"))"
      path=
    fi
  fi
  if "$cli" render "$cfg" ${path:+--path "$path"} --out "$out/$name.png" >/dev/null 2>"$out/$name.render.txt"; then
    rm -f "$out/$name.render.txt"
    echo "$name: $out/$name.png, $note"
  else
    echo "$name: not drawn: $(tail -n 1 "$out/$name.render.txt")" >&2
    failed=1
  fi
done
exit $failed
