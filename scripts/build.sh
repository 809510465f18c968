#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Installs what is missing, then configures and builds hybridcd (Release) in ./build.
# Extra arguments go to CMake, e.g. -DHYBRIDCD_BUILD_BENCH=OFF; with none, everything is built
# (library, CLI, tests, benchmarks).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/install-deps.sh"
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build "$root/build" -j"$(nproc)"
