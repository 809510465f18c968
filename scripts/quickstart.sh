#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Installs, builds, and solves the default problem shipped in problems/ (or the .cfg given).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/build.sh" -DHYBRIDCD_BUILD_TESTS=OFF -DHYBRIDCD_BUILD_BENCH=OFF
problem=${1:-$root/problems/window_3d.cfg}
"$root/build/hybridcd" inspect "$problem"
"$root/build/hybridcd" solve "$problem" --seed 1  # writes NAME.solution.path here
