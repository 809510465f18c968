#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Fuzzes hybridcd's input readers with libFuzzer (Debian's clang, AddressSanitizer and
# UndefinedBehaviorSanitizer), one harness after the other:
#
#   bash scripts/fuzz.sh [HARNESS...]     # cfg mesh pose motion path (default: all five)
#
# Installs clang if missing (apt, through install-deps.sh --fuzz), builds the harnesses of fuzz/ in
# ./build-fuzz, then runs each on a temporary copy of its seed corpus tests/fuzz_corpus/HARNESS/
# (plus OMPL.app's .cfg files and small meshes when ../shared/omplapp-resources or
# $HYBRIDCD_OMPLAPP_RESOURCES holds them; they are never copied into the repository).
# Prints, per harness, the executions done, crashes found and the time taken; exits non-zero when
# a harness crashed (or fell short of its executions). Crashing inputs are kept in
# build-fuzz/findings/HARNESS/; replay one with `build-fuzz/fuzz/HARNESS_fuzzer FILE`.
#
# The mesh harness fuzzes with UndefinedBehaviorSanitizer only (a second build in
# ./build-fuzz-mesh), then replays the whole corpus it grew, every input that reached new code,
# through the AddressSanitizer build ("mesh+asan" in the summary) and through the UBSan build with
# glibc's heap checks ("mesh+heap"), and keeps it in ./build-fuzz/corpus/mesh. The reason is assimp's OBJ
# reader: it allocates and fills a 16 MB buffer for every file it reads, whatever the file's size,
# and under AddressSanitizer each such allocation is a fresh mapping (about 12 ms a read instead of
# 0.4 ms), which caps the harness at about 300 executions a second.
#
# Environment:
#   FUZZ_RUNS=N       executions per harness (default 1000000)
#   FUZZ_MAX_LEN=N    largest input in bytes (default 4096; the mesh harness uses 2048, as assimp
#                     is slower per byte than the line readers)
#   FUZZ_TIMEOUT=S    seconds one input may take before it counts as a hang (default 10)
#   FUZZ_LOCK=FILE    take this flock(1) lock around the build and around each harness run, so
#                     that other builds on a shared machine can interleave
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
runs=${FUZZ_RUNS:-1000000}
timeout=${FUZZ_TIMEOUT:-10}
resources=${HYBRIDCD_OMPLAPP_RESOURCES:-$root/../shared/omplapp-resources}
build=$root/build-fuzz
all=(cfg mesh pose motion path)
harnesses=("${all[@]}")
[ $# -eq 0 ] || harnesses=("$@")
for h in "${harnesses[@]}"; do
  [[ " ${all[*]} " == *" $h "* ]] || { echo "fuzz.sh: unknown harness '$h' (known: ${all[*]})" >&2; exit 2; }
done

locked() {
  if [ -n "${FUZZ_LOCK:-}" ]; then flock "$FUZZ_LOCK" "$@"; else "$@"; fi
}

bash "$root/scripts/install-deps.sh" --fuzz
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  -DHYBRIDCD_BUILD_FUZZERS=ON -DHYBRIDCD_BUILD_CLI=OFF -DHYBRIDCD_BUILD_TESTS=OFF -DHYBRIDCD_BUILD_BENCH=OFF \
  -DHYBRIDCD_WITH_FCL=OFF >/dev/null
locked cmake --build "$build" -j"$(nproc)" --target hybridcd_fuzzers
if [[ " ${harnesses[*]} " == *" mesh "* ]]; then
  cmake -S "$root" -B "$root/build-fuzz-mesh" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
    -DHYBRIDCD_BUILD_FUZZERS=ON -DHYBRIDCD_FUZZ_SANITIZERS=undefined -DHYBRIDCD_BUILD_CLI=OFF \
    -DHYBRIDCD_BUILD_TESTS=OFF -DHYBRIDCD_BUILD_BENCH=OFF -DHYBRIDCD_WITH_FCL=OFF >/dev/null
  locked cmake --build "$root/build-fuzz-mesh" -j"$(nproc)" --target mesh_fuzzer
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Extra seeds from OMPL.app, when present: its problem files, and meshes small enough to mutate.
extra_seeds() {
  local harness=$1 max_len=$2
  [ -d "$resources" ] || return 0
  case $harness in
    cfg) find "$resources" -name '*.cfg' -size -"$max_len"c -exec cp {} "$work/$harness/" \; ;;
    mesh) find "$resources" \( -iname '*.dae' -o -iname '*.obj' -o -iname '*.stl' -o -iname '*.ply' -o -iname '*.off' \) \
            -size -"$max_len"c -exec cp {} "$work/$harness/" \; ;;
  esac
}

summary=()
failed=0
# run HARNESS LABEL BINARY WANT LOG ARGS...: one libFuzzer run on the harness's corpus, counted into
# the summary; WANT is the executions it must reach.
run() {
  local h=$1 label=$2 binary=$3 want=$4 log=$5
  shift 5
  local before start status=0 seconds execs rate crashes
  before=$(find "$build/findings/$h" -type f | wc -l)
  start=$(date +%s)
  # -print_final_stats gives the counts below.
  # Leaks count too, except assimp's own (fuzz/lsan.supp says which and why).
  ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1} LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$root/fuzz/lsan.supp} \
    locked "$binary" "$@" -timeout="$timeout" -print_final_stats=1 -artifact_prefix="$build/findings/$h/" \
    "$work/$h" >"$log" 2>&1 || status=$?
  seconds=$(( $(date +%s) - start ))
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  crashes=$(( $(find "$build/findings/$h" -type f | wc -l) - before ))
  if [ "$status" -ne 0 ] && [ "$crashes" -eq 0 ]; then crashes=1; fi  # died without writing an input
  if [ "$crashes" -gt 0 ] || [ "${execs:-0}" -lt "$want" ]; then
    failed=1
    tail -n 40 "$log" >&2
  fi
  summary+=("$(printf '%-9s %12s %10s %8s %8ss' "$label" "${execs:-?}" "${rate:-?}" "$crashes" "$seconds")")
}

for h in "${harnesses[@]}"; do
  max_len=${FUZZ_MAX_LEN:-4096}
  [ "$h" = mesh ] && max_len=${FUZZ_MAX_LEN:-2048}
  mkdir -p "$work/$h" "$build/findings/$h"
  cp "$root/tests/fuzz_corpus/$h/"* "$work/$h/"
  extra_seeds "$h" "$max_len"
  seeds=$(find "$work/$h" -type f | wc -l)
  echo "== $h: $runs runs from $seeds seeds (max_len $max_len)" >&2
  if [ "$h" = mesh ]; then
    run mesh mesh "$root/build-fuzz-mesh/fuzz/mesh_fuzzer" "$runs" "$build/findings/mesh.log" \
      -runs="$runs" -max_len="$max_len"
    corpus=$(find "$work/mesh" -type f | wc -l)
    echo "== mesh: replaying the $corpus corpus inputs with AddressSanitizer" >&2
    # -runs=0: run the corpus once, no mutation.
    run mesh mesh+asan "$build/fuzz/mesh_fuzzer" "$corpus" "$build/findings/mesh-asan.log" -runs=0
    # And through the UBSan build with glibc's heap checks, which see writes past a block's end
    # inside assimp (not instrumented) when the block is freed; too slow to fuzz with (20 times).
    malloc_debug=$(find /usr/lib /lib -name 'libc_malloc_debug.so.0' 2>/dev/null | head -1)
    if [ -n "$malloc_debug" ]; then
      echo "== mesh: replaying the $corpus corpus inputs with glibc's heap checks" >&2
      MALLOC_CHECK_=3 LD_PRELOAD=$malloc_debug run mesh mesh+heap "$root/build-fuzz-mesh/fuzz/mesh_fuzzer" "$corpus" \
        "$build/findings/mesh-heap.log" -runs=0
    fi
    # Kept for other replays (e.g. valgrind, which sees inside assimp: see bench/README.md).
    rm -rf "$build/corpus/mesh" && mkdir -p "$build/corpus" && cp -r "$work/mesh" "$build/corpus/mesh"
  else
    run "$h" "$h" "$build/fuzz/${h}_fuzzer" "$runs" "$build/findings/$h.log" -runs="$runs" -max_len="$max_len"
  fi
done

printf '%-9s %12s %10s %8s %9s\n' harness executions exec/s crashes time
printf '%s\n' "${summary[@]}"
[ "$failed" -eq 0 ] || { echo "fuzz.sh: findings or short runs; logs and inputs in $build/findings/" >&2; exit 1; }
