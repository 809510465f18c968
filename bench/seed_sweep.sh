#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Runs tests over many seeds: every test draws its samples from HYBRIDCD_TEST_SEED (OMPL's generator
# is reseeded with it before each test, and random-case tests mix it into their own seeds), so a
# sweep explores far more cases than CI's single seed. Prints each failing seed with its failure.
#
#   bash bench/seed_sweep.sh [FIRST LAST [GTEST_FILTER [TEST_PROGRAM...]]]
#   bash bench/seed_sweep.sh 1 500 '*FirstContactIsBracketed*' motion_validator_test
#
# Defaults: seeds 1..200, the motion-validator and swept-distance tests. Needs a build with tests
# (bash scripts/build.sh -DHYBRIDCD_BUILD_TESTS=ON).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
first=${1:-1}
last=${2:-200}
filter=${3:-*}
shift $(( $# < 3 ? $# : 3 ))
programs=("$@")
[ ${#programs[@]} -eq 0 ] && programs=(motion_validator_test swept_distance_test brute_force_test)

failures=0
runs=0
for program in "${programs[@]}"; do
  exe="$root/build/tests/$program"
  [ -x "$exe" ] || { echo "missing $exe: build with tests first" >&2; exit 1; }
  for seed in $(seq "$first" "$last"); do
    runs=$((runs + 1))
    if ! out=$(HYBRIDCD_TEST_SEED=$seed "$exe" --gtest_filter="$filter" 2>&1); then
      failures=$((failures + 1))
      echo "== $program seed $seed failed"
      echo "$out" | grep -A4 -E "Failure|FAILED  \]" | head -20
    fi
  done
done
echo "seed sweep: $runs runs ($first..$last over ${#programs[@]} programs, filter '$filter'), $failures failed"
[ "$failures" -eq 0 ]
