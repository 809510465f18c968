#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Fails, listing each one, on any include that runs against hybridcd's layers.

The folders under include/hybridcd/ and src/ form the levels below (lowest first). A file may
include headers of its own folder and of folders on lower levels; never of another folder on its
own level or of a folder above. README.md ("Architecture") shows the same picture.

Usage: python3 scripts/check_layers.py [SOURCE_ROOT]
"""
import pathlib
import re
import sys

LEVELS = [
    ["geometry"],             # transforms, exact predicates, triangle tests, meshes, CollisionScene
    ["bv", "narrowphase"],    # bounding volumes; convex pieces and linear programs
    ["bvh", "broadphase"],    # volume trees over any bounding volume; sweep and prune over body boxes
    ["query", "io"],          # collision checkers; problem files and meshes
    ["scene"],                # scenes of many bodies: broad phase, pair checks, motions
    ["ompl", "fcl", "render"],  # OMPL adapters; FCL as a checker; pictures and glTF scenes
    ["planners"],             # OMPL's geometric and control planners by OMPL.app's names
    ["cli"],                  # the hybridcd tool (src/ only)
]
LEVEL = {folder: level for level, folders in enumerate(LEVELS) for folder in folders}
SOURCE_SUFFIXES = {".h", ".hpp", ".cpp", ".cc", ".cxx", ".inl"}
INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]hybridcd/([^/">]+)/')


def layer_files(root):
    """(folder, path) for every source file under include/hybridcd/<folder> and src/<folder>."""
    for base in (root / "include" / "hybridcd", root / "src"):
        if not base.is_dir():
            continue
        for path in sorted(base.rglob("*")):
            if path.is_file() and path.suffix in SOURCE_SUFFIXES:
                relative = path.relative_to(base)
                folder = relative.parts[0] if len(relative.parts) > 1 else ""
                yield folder, path


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parent.parent)
    problems = []
    files = 0
    for folder, path in layer_files(root):
        files += 1
        shown = path.relative_to(root)
        if folder not in LEVEL:
            problems.append(f"{shown}: folder '{folder}' has no level; add it to LEVELS in scripts/check_layers.py")
            continue
        for number, line in enumerate(path.read_text(encoding="utf-8", errors="replace").splitlines(), 1):
            match = INCLUDE.match(line)
            if not match:
                continue
            target = match.group(1)
            if target == folder:
                continue
            if target not in LEVEL:
                problems.append(f"{shown}:{number}: includes unknown layer '{target}'")
            elif LEVEL[target] >= LEVEL[folder]:
                where = "its own level" if LEVEL[target] == LEVEL[folder] else "above"
                problems.append(f"{shown}:{number}: {folder} (level {LEVEL[folder]}) includes {target} "
                                f"(level {LEVEL[target]}, {where})")
    if files == 0:
        print(f"check_layers: no sources under {root}/include/hybridcd or {root}/src", file=sys.stderr)
        return 1
    if problems:
        print(f"check_layers: {len(problems)} include(s) against the layers:", file=sys.stderr)
        for problem in problems:
            print("  " + problem, file=sys.stderr)
        return 1
    print(f"check_layers: {files} files, no include against the layers")
    return 0


if __name__ == "__main__":
    sys.exit(main())
