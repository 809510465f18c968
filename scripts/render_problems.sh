#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Pictures of problems with verified paths: for each .cfg, NAME.png in OUT_DIR with the first of
#   1. the path shipped beside the .cfg (NAME.path, as OMPL.app ships them), when hybridcd verifies it;
#   2. OUT_DIR/NAME.path left by an earlier run (or put there by hand, with a first line
#      "# source: ..." saying how it was made), when hybridcd verifies it;
#   3. a path solved by `hybridcd solve` into OUT_DIR/NAME.path, trying the problem's planners in turn.
# OUT_DIR/index.md lists every problem with its picture and where its path came from.
# Verified: every pose collision-free (`check`) and, for geometric problems, every motion between
# consecutive poses certified free (`check-motion --verdict-only`). Problems whose meshes are missing
# are listed with the file; a problem left without a verified path is drawn bare and reported; one
# that cannot be loaded is reported. The script exits 1 at the end if any problem with its meshes
# present got no verified path.
# Usage: scripts/render_problems.sh OUT_DIR [PROBLEM.cfg...]
#   Without problems: problems/*.cfg and, when present, OMPL.app's 2D/ and 3D/ problems
#   ($HYBRIDCD_OMPLAPP_RESOURCES, else ../shared/omplapp-resources beside the source tree).
#   $HYBRIDCD_CLI names the tool (default build/hybridcd); $SOLVE_TIME, when set, replaces every
#   attempt's time limit in seconds (attempts_for below gives the per-problem planners and times);
#   $RENDER_WIDTH and $RENDER_HEIGHT set the pictures' size in pixels (default 800 x 600).
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
[ $# -ge 1 ] || { sed -n 3,16p "$0" >&2; exit 1; }
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

# One attempt per line, "PLANNER SECONDS [extra solve options, --seed N among them]", tried in order. The defaults solve
# most problems; the hard ones get the planner that solved them when measured and more time.
attempts_for() {
  case $1 in
    Abstract) printf '%s\n' "kpiece 60" "rrtconnect 120" ;;
    alpha-1.0) printf '%s\n' "rrtconnect 300" "kpiece 300" ;;
    bugtrap) printf '%s\n' "rrtconnect 120" "kpiece 120" "bkpiece 120" ;;
    BugTrap_dcar) printf '%s\n' "kpiece 120 --seed 3" "rrt 120 --goal-threshold 0.5 --propagation-step 0.1 --control-steps 1,10" "sst 120" ;;
    quadrotor_window) printf '%s\n' "kpiece 60 --goal-threshold 1.5" "rrt 60 --goal-threshold 1.5" ;;
    Maze_kcar | corridor_kcar) printf '%s\n' "rrt 60" "kpiece 60" ;;
    *) printf '%s\n' "rrtconnect 30" "kpiece 30" ;;
  esac
}

# The mesh files a .cfg names (robot = ..., world = ...), relative to its folder, that do not exist.
missing_meshes() {
  local cfg=$1 dir key value
  dir=$(dirname "$cfg")
  while IFS='=' read -r key value; do
    key=$(echo "$key" | tr -d '[:space:]')
    value=$(echo "$value" | sed 's/^[[:space:]]*//; s/[[:space:]]*$//')
    case $key in robot | world) ;; *) continue ;; esac
    [ -n "$value" ] || continue
    case $value in /*) ;; *) value=$dir/$value ;; esac
    [ -f "$value" ] || echo "$key mesh $value"
  done <"$cfg"
}

# Verifies PATH for CFG with hybridcd: prints "N poses[ and M motions] collision-free", or why not
# (exit 1). Kinodynamic paths (extra columns: velocities, controls) are checked pose by pose; their
# trajectories between rows were certified when they were planned.
verify_path() {
  local cfg=$1 path=$2 kinodynamic=$3 verdicts poses bad motions
  verdicts=$("$cli" check "$cfg" --states "$path" 2>/dev/null) || { echo "hybridcd check refused the path"; return 1; }
  poses=$(echo "$verdicts" | grep -c .)
  bad=$(echo "$verdicts" | grep -vc '^1$')
  [ "$poses" -ge 2 ] || { echo "the path has $poses poses"; return 1; }
  [ "$bad" -eq 0 ] || { echo "$bad of $poses poses collide"; return 1; }
  if [ "$kinodynamic" = 1 ]; then
    echo "$poses poses collision-free"
    return 0
  fi
  # Every motion between consecutive poses.
  motions=$("$cli" check-motion "$cfg" --path "$path" --verdict-only 2>/dev/null) ||
    { echo "hybridcd check-motion refused the path"; return 1; }
  bad=$(echo "$motions" | grep -vc '^1$')
  [ "$bad" -eq 0 ] || { echo "$bad of $((poses - 1)) motions touch the environment"; return 1; }
  echo "$poses poses and $((poses - 1)) motions collision-free"
}

failed=0
missing=()
index=()
for cfg in "${problems[@]}"; do
  name=$(basename "$cfg" .cfg)
  if [ -f "$cfg" ] && lacking=$(missing_meshes "$cfg") && [ -n "$lacking" ]; then
    echo "$name: not drawn: $(echo "$lacking" | paste -sd ';' | sed 's/;/; /g') missing" >&2
    missing+=("$name")
    continue
  fi
  kinodynamic=0
  [ -f "$cfg" ] && grep -q '^[[:space:]]*control[[:space:]]*=' "$cfg" && kinodynamic=1
  path=
  note=
  shipped=$(dirname "$cfg")/$name.path
  if [ -f "$shipped" ]; then
    if verdict=$(verify_path "$cfg" "$shipped" "$kinodynamic"); then
      path=$shipped
      note="path $shipped (shipped), verified: $verdict"
    else
      note="shipped path $shipped rejected ($verdict); "
    fi
  fi
  earlier=$out/$name.path
  if [ -z "$path" ] && [ -f "$earlier" ] && [ "$earlier" != "$shipped" ]; then
    if verdict=$(verify_path "$cfg" "$earlier" "$kinodynamic"); then
      path=$earlier
      # A path put there by hand says where it came from on a first line "# source: ...".
      origin=$(sed -n '1s/^# source: //p' "$earlier")
      note="${note}path $earlier (${origin:-from an earlier run}), verified: $verdict"
    else
      note="${note}earlier path $earlier rejected ($verdict); "
    fi
  fi
  if [ -z "$path" ] && [ -f "$cfg" ]; then
    while read -r planner seconds extra; do
      seconds=${SOLVE_TIME:-$seconds}
      # An attempt may name its seed ("--seed N" among its options); seed 1 otherwise.
      seed=1
      if [[ $extra =~ --seed\ ([0-9]+) ]]; then
        seed=${BASH_REMATCH[1]}
        extra=${extra/--seed $seed/}
      fi
      candidate=$out/$name.path
      # shellcheck disable=SC2086 # extra holds several options
      if "$cli" solve "$cfg" --planner "$planner" --seed "$seed" --time "$seconds" $extra --quiet --out "$candidate" \
        >"$out/$name.solve.txt" 2>&1 </dev/null; then
        if verdict=$(verify_path "$cfg" "$candidate" "$kinodynamic"); then
          path=$candidate
          note="${note}path solved into $candidate ($planner, seed $seed, $(grep -m 1 '^solve time:' \
            "$out/$name.solve.txt" | sed 's/^solve time: //')), verified: $verdict"
          break
        fi
        note="${note}$planner's path rejected ($verdict); "
      else
        note="${note}$planner in $seconds s: $(grep -m 1 -E '^solved:|error:' "$out/$name.solve.txt" ||
          tail -n 1 "$out/$name.solve.txt"); "
      fi
    done < <(attempts_for "$name")
    if [ -z "$path" ]; then
      rm -f "$out/$name.path"
      note="no verified path (${note%; })"
      failed=1
    fi
  fi
  if "$cli" render "$cfg" ${path:+--path "$path"} ${RENDER_WIDTH:+--width "$RENDER_WIDTH"} \
    ${RENDER_HEIGHT:+--height "$RENDER_HEIGHT"} --out "$out/$name.png" >/dev/null 2>"$out/$name.render.txt"; then
    rm -f "$out/$name.render.txt" "$out/$name.solve.txt"
    echo "$name: $out/$name.png, $note"
    # The index names files relative to OUT_DIR and to the problem's folder.
    short=${note//$out\//}
    short=${short//$(dirname "$cfg")\//}
    index+=("| ![$name]($name.png) | $name | ${short//|/\\|} |")
  else
    echo "$name: not drawn: $(tail -n 1 "$out/$name.render.txt")" >&2
    failed=1
  fi
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "render_problems: not drawn, meshes missing: ${missing[*]}" >&2
fi
{
  echo "# Problems and their paths"
  echo
  echo "Drawn by \`scripts/render_problems.sh\` (green: start, red: goal, the path's line and robots along"
  echo "it). Every path was verified before it was drawn: each pose collision-free and, for geometric"
  echo "problems, each motion between consecutive poses certified free by continuous checking."
  echo
  echo "| picture | problem | path |"
  echo "|---|---|---|"
  printf '%s\n' "${index[@]}"
  if [ ${#missing[@]} -gt 0 ]; then
    echo
    echo "Not drawn, meshes missing: ${missing[*]}."
  fi
} >"$out/index.md.$$" && mv "$out/index.md.$$" "$out/index.md"
exit $failed
