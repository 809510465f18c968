#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Installs, builds (with tests) and runs the whole suite with CTest.
# OMPL.app's problems are read from ../shared/omplapp-resources, or $HYBRIDCD_OMPLAPP_RESOURCES;
# tests that need them skip with a message when they are absent.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/build.sh" -DHYBRIDCD_BUILD_TESTS=ON -DHYBRIDCD_BUILD_BENCH=OFF

# First the concurrency tests under ThreadSanitizer (checkers are queried from many threads)...
cmake -S "$root" -B "$root/build-tsan" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DHYBRIDCD_SANITIZE=thread \
  -DHYBRIDCD_BUILD_TESTS=ON -DHYBRIDCD_BUILD_BENCH=OFF -DHYBRIDCD_BUILD_CLI=OFF >/dev/null
cmake --build "$root/build-tsan" -j"$(nproc)" --target validity_checker_test
(cd "$root/build-tsan" && TSAN_OPTIONS="halt_on_error=1" ctest --output-on-failure -R ValidityChecker --timeout 900)

# ...then the whole suite.
cd "$root/build"
ctest --output-on-failure -j"$(nproc)" --timeout 900
