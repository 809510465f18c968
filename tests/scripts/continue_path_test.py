#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""scripts/continue_path.py against hybridcd's own answers and OMPL.app's alpha-1.0 meshes.

Environment: HYBRIDCD_CLI (the tool), HYBRIDCD_SOURCE_DIR, HYBRIDCD_OMPLAPP_RESOURCES.
"""
import math
import os
import random
import subprocess
import sys
import tempfile
import unittest

SOURCE = os.environ.get('HYBRIDCD_SOURCE_DIR', os.path.join(os.path.dirname(__file__), '..', '..'))
sys.path.insert(0, os.path.join(SOURCE, 'scripts'))
import continue_path  # noqa: E402

CLI = os.environ.get('HYBRIDCD_CLI', os.path.join(SOURCE, 'build', 'hybridcd'))
RESOURCES = os.environ.get('HYBRIDCD_OMPLAPP_RESOURCES', os.path.join(SOURCE, '..', 'shared', 'omplapp-resources'))
ALPHA = os.path.join(RESOURCES, '3D')
WINDOW = os.path.join(SOURCE, 'problems', 'window_3d.cfg')


def rotation_angle(a, b):
    dot = abs(sum(x * y for x, y in zip(a, b)))
    return 2.0 * math.acos(min(1.0, dot))


class Rotations(unittest.TestCase):
    def test_slerp_keeps_the_ends_and_halves_the_angle(self):
        rng = random.Random(5)
        for _ in range(200):
            a = continue_path.quat_normalized(tuple(rng.gauss(0, 1) for _ in range(4)))
            b = continue_path.quat_normalized(tuple(rng.gauss(0, 1) for _ in range(4)))
            self.assertLess(rotation_angle(continue_path.slerp(a, b, 0.0), a), 1e-6)
            self.assertLess(rotation_angle(continue_path.slerp(a, b, 1.0), b), 1e-6)
            middle = continue_path.slerp(a, b, 0.5)
            self.assertAlmostEqual(sum(c * c for c in middle), 1.0, places=12)
            # The shorter arc: the middle is half the angle from each end.
            whole = rotation_angle(a, b)
            self.assertAlmostEqual(rotation_angle(a, middle), whole / 2, places=6)
            self.assertAlmostEqual(rotation_angle(middle, b), whole / 2, places=6)

    def test_rotation_vector_turns_by_its_length(self):
        q = continue_path.quat_from_rotation_vector((0.0, 0.0, math.pi / 2))
        self.assertAlmostEqual(q[2], math.sin(math.pi / 4), places=12)
        self.assertAlmostEqual(q[3], math.cos(math.pi / 4), places=12)
        self.assertEqual(continue_path.quat_from_rotation_vector((0.0, 0.0, 0.0)), (0.0, 0.0, 0.0, 1.0))


class WithTheTool(unittest.TestCase):
    def setUp(self):
        self.assertTrue(os.path.exists(CLI), f'no hybridcd tool at {CLI}')
        self.folder = tempfile.mkdtemp()

    def run_tool(self, *args):
        result = subprocess.run([CLI, *args], capture_output=True, text=True)
        self.assertEqual(result.returncode, 0, result.stderr)
        return result.stdout.split()

    def write_poses(self, poses):
        name = os.path.join(self.folder, 'poses.txt')
        with open(name, 'w') as f:
            f.write('\n'.join(continue_path.pose_text(p) for p in poses) + '\n')
        return name

    def test_endpoints_are_the_poses_solve_starts_and_ends_at(self):
        out = os.path.join(self.folder, 'window.path')
        self.run_tool('solve', WINDOW, '--seed', '1', '--time', '5', '--quiet', '--out', out)
        path = continue_path.read_path(out)
        for which, pose in (('start', path[0]), ('goal', path[-1])):
            mine = continue_path.endpoint(WINDOW, which)
            self.assertLess(max(abs(a - b) for a, b in zip(mine[:3], pose[:3])), 1e-9, which)
            self.assertLess(rotation_angle(mine[3:], pose[3:]), 1e-6, which)

    def test_retraction_returns_free_poses_near_colliding_ones(self):
        rng = random.Random(3)
        checker = continue_path.Checker(CLI, WINDOW, self.folder)
        poses = [(rng.uniform(-45, 45), rng.uniform(-25, 25), rng.uniform(5, 35)) +
                 continue_path.quat_normalized(tuple(rng.gauss(0, 1) for _ in range(4))) for _ in range(400)]
        colliding = [p for p, free in zip(poses, checker.free(poses)) if not free][:20]
        self.assertGreaterEqual(len(colliding), 10)
        moved = continue_path.retract(checker, colliding, random.Random(1), reach=5.0)
        found = [(p, q) for p, q in zip(colliding, moved) if q is not None]
        self.assertGreaterEqual(len(found), 5)
        # Free by a separate call of `check`, with another checker, and within the largest scale's reach.
        verdicts = self.run_tool('check', WINDOW, '--checker', 'obb', '--no-grid', '--states',
                                 self.write_poses([q for _, q in found]))
        self.assertEqual(verdicts, ['1'] * len(found))
        for p, q in found:
            self.assertLess(math.dist(p[:3], q[:3]), 6 * 4.0)

    def test_the_last_alpha_stage_is_alpha_1_0(self):
        shipped = continue_path.read_path(os.path.join(ALPHA, 'alpha-1.1.path'))
        listing = self.write_poses(shipped)
        stages = continue_path.AlphaStages(os.path.join(ALPHA, 'alpha-1.1.cfg'), os.path.join(ALPHA, 'alpha-1.0.cfg'))
        first, last = stages.files(self.folder, [0.0, 1.0])
        target = self.run_tool('check', os.path.join(ALPHA, 'alpha-1.0.cfg'), '--states', listing)
        self.assertEqual(self.run_tool('check', first, '--states', listing), ['1'] * len(shipped))
        self.assertEqual(self.run_tool('check', last, '--states', listing), target)
        self.assertIn('0', target)  # alpha-1.1's path does not fit alpha-1.0: the stages matter

    def test_bad_input_is_refused_with_file_and_line_and_nothing_written(self):
        script = os.path.join(SOURCE, 'scripts', 'continue_path.py')
        bad = os.path.join(self.folder, 'bad.path')
        out = os.path.join(self.folder, 'out.path')
        cases = [('1 2 3 0 0 0 1\n1 2 x 0 0 0 1\n', f'{bad}:2:'),
                 ('1 2 3 0 0 0 1\n1 2 3 0 0 1\n', f'{bad}:2: expected 7 numbers'),
                 ('1 2 3 0 0 0 0\n1 2 3 0 0 0 1\n', f'{bad}:1: numbers must be finite'),
                 ('1 2 3 0 0 0 1\n', 'at least two poses')]
        for text, message in cases:
            with open(bad, 'w') as f:
                f.write(text)
            result = subprocess.run([sys.executable, script, '--from-cfg', os.path.join(ALPHA, 'alpha-1.1.cfg'),
                                     '--from-path', bad, '--to-cfg', os.path.join(ALPHA, 'alpha-1.0.cfg'),
                                     '--stages', 'alpha', '--out', out, '--cli', CLI], capture_output=True, text=True)
            self.assertEqual(result.returncode, 1, result.stderr)
            self.assertIn(message, result.stderr)
            self.assertFalse(os.path.exists(out))
        # A problem whose obstacle is not an alpha puzzle's is refused before any stage runs.
        result = subprocess.run([sys.executable, script, '--from-cfg', os.path.join(ALPHA, 'alpha-1.1.cfg'),
                                 '--from-path', os.path.join(ALPHA, 'alpha-1.1.path'), '--to-cfg',
                                 os.path.join(ALPHA, 'Easy.cfg'), '--stages', 'alpha', '--steps', '1', '--out', out,
                                 '--cli', CLI],
                                capture_output=True, text=True)
        self.assertEqual(result.returncode, 1)
        self.assertIn('Easy_env.dae', result.stderr)
        self.assertNotIn('stage', result.stdout)
        self.assertFalse(os.path.exists(out))

    def test_the_gallery_path_of_alpha_1_0_is_free(self):
        cfg = os.path.join(ALPHA, 'alpha-1.0.cfg')
        path = continue_path.read_path(os.path.join(SOURCE, 'docs', 'gallery', 'alpha-1.0.path'))
        self.assertEqual(path[0], continue_path.endpoint(cfg, 'start'))
        self.assertEqual(path[-1], continue_path.endpoint(cfg, 'goal'))
        self.assertEqual(self.run_tool('check', cfg, '--states', self.write_poses(path)), ['1'] * len(path))
        motions = os.path.join(self.folder, 'motions.txt')
        with open(motions, 'w') as f:
            for a, b in zip(path[:-1], path[1:]):
                f.write(continue_path.pose_text(a) + ' ' + continue_path.pose_text(b) + '\n')
        self.assertEqual(self.run_tool('check-motion', cfg, '--verdict-only', '--motions', motions),
                         ['1'] * (len(path) - 1))


if __name__ == '__main__':
    unittest.main()
