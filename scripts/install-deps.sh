#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Installs the Debian 12 packages hybridcd needs, skipping apt entirely when all are present.
# With --fuzz, also clang and its libFuzzer/sanitizer runtimes (for scripts/fuzz.sh).
set -euo pipefail

packages=(
  cmake g++ make pkg-config
  libompl-dev libeigen3-dev libassimp-dev libnlopt-cxx-dev libgtest-dev
  # Debian's omplConfig.cmake links these Boost libraries by file name.
  libboost-serialization-dev libboost-filesystem-dev libboost-system-dev
  libqhull-dev libfcl-dev libbenchmark-dev
  # SIMD kernels with the instruction set picked at run time.
  libhwy-dev
  # The command line of the tool and the benchmark programs (header-only).
  libcli11-dev
  # ompl_benchmark_statistics reads the benchmark logs into SQLite.
  ompl-demos python3
  # scripts/check_format.sh
  clang-format
  # `hybridcd render`: PNG pictures and glTF scenes.
  libstb-dev libtinygltf-dev
  # The Python module and its test.
  pybind11-dev python3-dev python3-numpy
  # Benchmark shards run side by side or over ssh (bench/README.md), and their plots.
  parallel python3-matplotlib
)
if [ "${1:-}" = "--fuzz" ]; then
  packages+=(clang libclang-rt-14-dev)
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "hybridcd: installing ${missing[*]}" >&2
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "hybridcd: need root (or sudo) to install: ${missing[*]}" >&2; exit 1; }
  sudo_cmd=(sudo)
fi
"${sudo_cmd[@]}" apt-get update -qq
DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
