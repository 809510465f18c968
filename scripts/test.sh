#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Installs, builds (with tests) and runs the whole suite with CTest, then the layer and README
# checks and the consumer test (an installed hybridcd used through find_package and pkg-config).
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

# ...then the whole suite...
(cd "$root/build" && ctest --output-on-failure -j"$(nproc)" --timeout 900)

# ...the layering of the includes and the README's copy of the library example...
python3 "$root/scripts/check_layers.py" "$root"
python3 "$root/scripts/check_readme_files.py" "$root"

# ...and hybridcd as a consumer sees it: installed into a temporary prefix, found by CMake and pkg-config.
bash "$root/scripts/test_consumer.sh" "$root/problems/window_3d.cfg"
