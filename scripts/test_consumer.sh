#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Installs hybridcd into a temporary prefix and uses it from outside, as any project would:
# tests/consumer (the README's library example) through find_package(hybridcd), and a core-only
# program through pkg-config. Reuses ./build (or $HYBRIDCD_BUILD_DIR) when it is configured, else
# configures it; a build without OMPL is tested through the core alone. When the build has the
# Python module, `import hybridcd` and the README's Python example (python/example.py) run from
# the prefix too, with the interpreter the build was configured with.
# Usage: scripts/test_consumer.sh [PROBLEM.cfg]   (default problems/window_3d.cfg)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
problem=$(realpath "${1:-$root/problems/window_3d.cfg}")
build=${HYBRIDCD_BUILD_DIR:-$root/build}

if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DHYBRIDCD_BUILD_TESTS=OFF -DHYBRIDCD_BUILD_BENCH=OFF >/dev/null
fi
cmake --build "$build" -j"$(nproc)" >/dev/null

work=$(mktemp -d "${TMPDIR:-/tmp}/hybridcd-consumer.XXXXXX")
trap 'rm -rf "$work"' EXIT
prefix=$work/prefix
cmake --install "$build" --prefix "$prefix" >/dev/null
echo "consumer: installed into $prefix"

# CMake: find_package(hybridcd), then the README's example and the core alone on a problem.
core_only=OFF
[ -d "$prefix/include/hybridcd/ompl" ] || core_only=ON
cmake -S "$root/tests/consumer" -B "$work/consumer" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release \
  -DCORE_ONLY=$core_only >/dev/null
cmake --build "$work/consumer" -j"$(nproc)" >/dev/null
[ "$core_only" = ON ] || "$work/consumer/consumer" "$problem"
"$work/consumer/core_only" "$problem"

# pkg-config: the core library alone, without OMPL.
pcdir=$(dirname "$(find "$prefix" -name hybridcd.pc -print -quit)")
export PKG_CONFIG_PATH="$pcdir${PKG_CONFIG_PATH:+:$PKG_CONFIG_PATH}"
flags=$(pkg-config --cflags --libs hybridcd)
echo "consumer: pkg-config --cflags --libs hybridcd: $flags"
# shellcheck disable=SC2086  # the flags are meant to split
"${CXX:-c++}" -std=c++17 -O1 "$root/tests/consumer/core_only.cpp" -o "$work/core_only" $flags \
  -Wl,-rpath,"$(pkg-config --variable=libdir hybridcd)"
"$work/core_only" "$problem"
# Python: the installed module, found through PYTHONPATH as the README says.
module=$(find "$prefix" -name 'hybridcd.*.so' -path '*python*' -print -quit)
if [ -n "$module" ]; then
  python=$(sed -n 's/^_Python3_EXECUTABLE:INTERNAL=//p' "$build/CMakeCache.txt")
  pydir=$(dirname "$module")
  echo "consumer: Python module in $pydir (${python:-python3})"
  (cd "$work" && PYTHONPATH="$pydir" "${python:-python3}" -c 'import hybridcd; print("consumer: import hybridcd from", hybridcd.__file__)')
  (cd "$work" && PYTHONPATH="$pydir" "${python:-python3}" "$root/python/example.py" "$problem")
else
  echo "consumer: no Python module in this build"
fi
echo "consumer: OK"
