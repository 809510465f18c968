#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Fails when a code block of README.md differs from the file it shows.

A block shows a file when the line before its opening fence is `<!-- file: PATH -->` (PATH relative
to the repository root); the block's text must be the file's text exactly. The examples that the
test command runs (REQUIRED) must each be shown: the library example, tests/consumer/main.cpp, and
the Python example, python/example.py.

Usage: python3 scripts/check_readme_files.py [SOURCE_ROOT]
"""
import difflib
import pathlib
import re
import sys

MARKER = re.compile(r"^<!--\s*file:\s*(\S+)\s*-->$")
# Files README.md must show, each run by scripts/test_consumer.sh.
REQUIRED = ["tests/consumer/main.cpp", "python/example.py"]


def shown_files(readme):
    """(path, README line number, block text) for each marked block."""
    lines = readme.splitlines(keepends=True)
    for index, line in enumerate(lines):
        match = MARKER.match(line.strip())
        if not match:
            continue
        if index + 1 >= len(lines) or not lines[index + 1].startswith("```"):
            yield match.group(1), index + 1, None
            continue
        body = []
        for inner in lines[index + 2:]:
            if inner.startswith("```"):
                break
            body.append(inner)
        else:
            yield match.group(1), index + 1, None
            continue
        yield match.group(1), index + 1, "".join(body)


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parent.parent)
    readme = (root / "README.md").read_text(encoding="utf-8")
    failures = 0
    checked = 0
    shown = set()
    for path, line, block in shown_files(readme):
        checked += 1
        shown.add(path)
        if block is None:
            print(f"README.md:{line}: the marker for {path} is not followed by a closed code block", file=sys.stderr)
            failures += 1
            continue
        file = root / path
        if not file.is_file():
            print(f"README.md:{line}: {path} does not exist", file=sys.stderr)
            failures += 1
            continue
        text = file.read_text(encoding="utf-8")
        if text != block:
            print(f"README.md:{line}: the block differs from {path}:", file=sys.stderr)
            sys.stderr.writelines(difflib.unified_diff(block.splitlines(keepends=True), text.splitlines(keepends=True),
                                                       "README.md", path))
            failures += 1
    if checked == 0:
        print("check_readme_files: README.md marks no block with <!-- file: PATH -->", file=sys.stderr)
        return 1
    for path in REQUIRED:
        if path not in shown:
            print(f"README.md: no block shows {path} (mark one with <!-- file: {path} -->)", file=sys.stderr)
            failures += 1
    if failures:
        return 1
    print(f"check_readme_files: {checked} README block(s) equal their files")
    return 0


if __name__ == "__main__":
    sys.exit(main())
