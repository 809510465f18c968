#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Checks every C++ source of the repository against .clang-format (clang-format 14, Debian 12's);
# lists the files that differ and exits 1 when any does. `bash scripts/check_format.sh --fix`
# rewrites them instead.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
command -v clang-format >/dev/null || { echo "check_format: clang-format missing (scripts/install-deps.sh installs it)" >&2; exit 1; }
mapfile -t files < <(git ls-files '*.cpp' '*.h' 2>/dev/null || find include src tests bench fuzz python -name '*.cpp' -o -name '*.h')
if [ "${1:-}" = "--fix" ]; then
  clang-format -i "${files[@]}"
  exit 0
fi
differ=()
for f in "${files[@]}"; do
  clang-format --dry-run --Werror "$f" >/dev/null 2>&1 || differ+=("$f")
done
if [ ${#differ[@]} -gt 0 ]; then
  echo "check_format: ${#differ[@]} file(s) differ from .clang-format (bash scripts/check_format.sh --fix):" >&2
  printf '  %s\n' "${differ[@]}" >&2
  exit 1
fi
echo "check_format: ${#files[@]} files match .clang-format"
