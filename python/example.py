# SPDX-License-Identifier: BSD-3-Clause
# hybridcd from Python: load an OMPL.app problem, check a batch of poses and motions.
# Usage: python3 example.py PROBLEM.cfg (e.g. problems/window_3d.cfg), with the module on PYTHONPATH.
import sys

import numpy as np

import hybridcd

problem = hybridcd.Problem.load(sys.argv[1])  # raises hybridcd.InputError (a ValueError) on bad input
checker = hybridcd.Checker(problem, name="obb")  # solids by default; surface_only=True as FCL

# One pose per row, in .path column order: x y z qx qy qz qw (3D) or x y yaw (planar).
rng = np.random.default_rng(1)
low, high = problem.bounds
poses = np.tile(problem.start, (1000, 1))
poses[:, :len(low)] = rng.uniform(low, high, size=(1000, len(low)))
hit = checker.collides(poses)  # bool array; the batch runs without the GIL
clearance = checker.clearance(poses)  # distance when free, minus a penetration estimate when not
print(f"{hit.sum()} of {len(poses)} poses collide; largest clearance {clearance.max():.3f}")

# Continuous motion checks: True where no point of the motion touches the environment.
free, last_free = checker.check_motions([problem.start], [problem.goal], last_free=True)
print(f"start to goal in one motion: {'free' if free[0] else f'blocked after {last_free[0]:.3f} of it'}")
