#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Installs, builds (with tests) and runs the whole suite with CTest:
#   1. Release build, the whole suite;
#   2. AddressSanitizer + UndefinedBehaviorSanitizer build, the suite but for its twelve heaviest
#      tests (below);
#   3. ThreadSanitizer build, the concurrency tests (8 threads on every checker and every query).
#   4. the layering of the includes, the layout of the sources (.clang-format), the README's copies
#      of the library and Python examples, and hybridcd as a consumer sees it: installed into a
#      temporary prefix, found by CMake, pkg-config and python3.
# HYBRIDCD_SANITIZERS=0 skips 2 and 3 (a quick local run; CI always runs them).
# OMPL.app's problems are read from ../shared/omplapp-resources, or $HYBRIDCD_OMPLAPP_RESOURCES;
# tests that need them skip with a message when they are absent, and fail when CI=true.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
jobs=$(nproc)
started=$(date +%s)
# Each step says how long the run has taken so far (CI keeps the whole run under 30 minutes).
step() { echo "== hybridcd test: $* ($(( $(date +%s) - started )) s in)" >&2; }

step "release build and suite"
bash "$root/scripts/build.sh" -DHYBRIDCD_BUILD_TESTS=ON -DHYBRIDCD_BUILD_BENCH=OFF
(cd "$root/build" && ctest --output-on-failure -j"$jobs" --timeout 900)

step "include layers, README example, installed package"
python3 "$root/scripts/check_layers.py" "$root"
bash "$root/scripts/check_format.sh"
python3 "$root/scripts/check_readme_files.py" "$root"
bash "$root/scripts/test_consumer.sh" "$root/problems/window_3d.cfg"

if [ "${HYBRIDCD_SANITIZERS:-1}" != 0 ]; then
  # Sanitizer builds keep assertions and use -O1: compile time matters more than speed here.
  sanitizer_flags=(-DCMAKE_BUILD_TYPE=Sanitize "-DCMAKE_CXX_FLAGS_SANITIZE=-O1 -g1" -DHYBRIDCD_BUILD_BENCH=OFF)

  # The sanitizer run leaves to the Release run its twelve heaviest tests (each 30-120 s under
  # AddressSanitizer, a third of the run): they repeat the code paths of the smaller cases beside
  # them (VolumeAgreement on seven other problems, CheckerAgreement on four, the other
  # MedialSpheres, BruteForce, Solve, Bench, TriangleIntersection and ConvexDecomposition tests) on
  # more triangles or more runs.
  release_only="VolumeAgreement\.(Apartment|Alpha15|Bugtrap|OrganicBone3d|OrganicBones2d)$"
  release_only+="|CheckerAgreement\.Alpha15$|MedialSpheres\.ApproximateModeErrsOnlyTowardCollisionWithinTolerance$"
  release_only+="|Solve\.OrganicProblems$|BruteForce\.SweepMatchesAllPairsOnSnappedSoups$"
  release_only+="|Bench\.ShardsSplitRunsWithoutOverlapOrLoss$"
  release_only+="|TriangleIntersection\.ConstructedConfigurationsMatchExactReference$"
  release_only+="|ConvexDecomposition\.ConcavityMatchesBruteForceOnOmplappMeshes$"

  step "AddressSanitizer + UndefinedBehaviorSanitizer build and suite"
  cmake -S "$root" -B "$root/build-asan" "${sanitizer_flags[@]}" -DHYBRIDCD_SANITIZE=address,undefined \
    -DHYBRIDCD_BUILD_TESTS=ON >/dev/null
  cmake --build "$root/build-asan" -j"$jobs"
  (cd "$root/build-asan" && ASAN_OPTIONS="detect_leaks=1:abort_on_error=1" \
    LSAN_OPTIONS="suppressions=$root/tests/sanitizers/lsan.supp" UBSAN_OPTIONS="print_stacktrace=1" \
    ctest --output-on-failure -j"$jobs" --timeout 1800 -E "$release_only")

  step "ThreadSanitizer build and concurrency tests"
  cmake -S "$root" -B "$root/build-tsan" "${sanitizer_flags[@]}" -DHYBRIDCD_SANITIZE=thread \
    -DHYBRIDCD_BUILD_TESTS=ON -DHYBRIDCD_BUILD_CLI=OFF >/dev/null
  cmake --build "$root/build-tsan" -j"$jobs" --target concurrency_test validity_checker_test query_context_test
  (cd "$root/build-tsan" && TSAN_OPTIONS="halt_on_error=1" \
    ctest --output-on-failure -R "Concurrency|ValidityChecker|QueryContext" --timeout 1800)
fi
step "all passed"
