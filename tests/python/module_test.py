# SPDX-License-Identifier: BSD-3-Clause
"""The Python module against the command-line tool: the same seeded random poses and motions,
written to files for `hybridcd check`, `clearance` and `check-motion`, must get the same answers
from hybridcd.Checker. Also the module's own contracts: shapes, NaN rows, errors, the GIL.

Environment: HYBRIDCD_CLI (the tool), HYBRIDCD_SOURCE_DIR, HYBRIDCD_OMPLAPP_RESOURCES (OMPL.app's
problems; their tests skip when it is absent, and fail when CI=true). PYTHONPATH finds the module.
Run: python3 tests/python/module_test.py -v (or the CTest test PythonModule).
"""
import os
import pathlib
import subprocess
import tempfile
import threading
import time
import unittest

import numpy as np

import hybridcd

CLI = os.environ.get("HYBRIDCD_CLI", "")
SOURCE_DIR = pathlib.Path(os.environ.get("HYBRIDCD_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
OMPLAPP = pathlib.Path(os.environ.get("HYBRIDCD_OMPLAPP_RESOURCES", SOURCE_DIR.parent / "shared" / "omplapp-resources"))
SEED = 20240611
POSES = 300
MOTIONS = 40


def random_poses(rng, problem, count):
    """Poses in the problem's bounds (a little beyond, so some leave the environment)."""
    low, high = problem.bounds
    margin = 0.05 * (high - low)
    position = rng.uniform(low - margin, high + margin, size=(count, len(low)))
    if problem.planar:
        return np.column_stack([position, rng.uniform(-np.pi, np.pi, size=count)])
    # Uniform rotations: normalised Gaussian quaternions (qx qy qz qw).
    quaternion = rng.normal(size=(count, 4))
    quaternion /= np.linalg.norm(quaternion, axis=1, keepdims=True)
    return np.column_stack([position, quaternion])


def nearby_poses(rng, problem, poses):
    """Motion goals: each pose moved by up to a tenth of the bounds and turned a little."""
    low, high = problem.bounds
    step = 0.1 * (high - low)
    goals = poses.copy()
    goals[:, :len(low)] += rng.uniform(-step, step, size=(len(poses), len(low)))
    if problem.planar:
        goals[:, 2] += rng.uniform(-0.5, 0.5, size=len(poses))
    else:
        goals[:, 3:] += rng.normal(scale=0.2, size=(len(poses), 4))
        goals[:, 3:] /= np.linalg.norm(goals[:, 3:], axis=1, keepdims=True)
    return goals


def write_rows(path, rows):
    with open(path, "w", encoding="utf-8") as out:
        for row in rows:
            out.write(" ".join(repr(float(v)) for v in row) + "\n")


def run_cli(*args):
    result = subprocess.run([CLI, *map(str, args)], capture_output=True, text=True, check=False)
    if result.returncode != 0:
        raise AssertionError(f"hybridcd {' '.join(map(str, args))} failed ({result.returncode}): {result.stderr}")
    return result.stdout.split("\n")[:-1]


class AgainstCli:
    """Mixin: compares every batch query with the tool on one problem (`cfg`, set by subclasses)."""

    cfg = None
    checker_name = "obb"

    @classmethod
    def setUpClass(cls):
        if not CLI:
            raise unittest.SkipTest("HYBRIDCD_CLI is not set")
        path = pathlib.Path(cls.cfg)
        if not path.is_file():
            if os.environ.get("CI") == "true":
                raise AssertionError(f"{path} is missing (CI=true)")
            raise unittest.SkipTest(f"{path} is missing")
        cls.problem = hybridcd.Problem.load(str(path))
        cls.checker = hybridcd.Checker(cls.problem, name=cls.checker_name)
        rng = np.random.default_rng(SEED)
        cls.poses = random_poses(rng, cls.problem, POSES)
        cls.starts = random_poses(rng, cls.problem, MOTIONS)
        cls.goals = nearby_poses(rng, cls.problem, cls.starts)
        cls.work = tempfile.TemporaryDirectory(prefix="hybridcd-python-test.")
        cls.states_file = pathlib.Path(cls.work.name) / "states.path"
        cls.motions_file = pathlib.Path(cls.work.name) / "motions.txt"
        write_rows(cls.states_file, cls.poses)
        write_rows(cls.motions_file, np.hstack([cls.starts, cls.goals]))

    @classmethod
    def tearDownClass(cls):
        cls.work.cleanup()

    def cli(self, command, *args):
        return run_cli(command, self.cfg, "--checker", self.checker_name, *args)

    def test_collides_matches_check(self):
        lines = self.cli("check", "--states", self.states_file)
        expected = np.array([line == "0" for line in lines])
        got = self.checker.collides(self.poses)
        self.assertEqual(got.dtype, np.bool_)
        self.assertEqual(got.shape, (POSES,))
        np.testing.assert_array_equal(got, expected)
        # The poses are informative: both answers occur often.
        self.assertTrue(0.05 < got.mean() < 0.95, f"colliding fraction {got.mean()}")

    def test_clearance_matches_clearance(self):
        expected = np.array([float(line) for line in self.cli("clearance", "--states", self.states_file)])
        got = self.checker.clearance(self.poses)
        self.assertEqual(got.shape, (POSES,))
        np.testing.assert_allclose(got, expected, rtol=1e-12, atol=1e-12)
        # Positive exactly where free.
        np.testing.assert_array_equal(got > 0, ~self.checker.collides(self.poses))

    def test_check_motions_matches_verdict_only(self):
        lines = self.cli("check-motion", "--motions", self.motions_file, "--verdict-only")
        expected = np.array([line == "1" for line in lines])
        got = self.checker.check_motions(self.starts, self.goals)
        np.testing.assert_array_equal(got, expected)
        self.assertTrue(0.0 < got.mean() < 1.0, f"free fraction {got.mean()}")

    def test_check_motions_last_free_matches_check_motion(self):
        lines = self.cli("check-motion", "--motions", self.motions_file)
        expected_free = np.array([line.split()[0] == "1" for line in lines])
        expected_fraction = np.array([1.0 if line == "1" else float(line.split()[1]) for line in lines])
        free, fraction = self.checker.check_motions(self.starts, self.goals, last_free=True)
        np.testing.assert_array_equal(free, expected_free)
        np.testing.assert_allclose(fraction, expected_fraction, rtol=0, atol=1e-15)


class Window3d(AgainstCli, unittest.TestCase):
    cfg = SOURCE_DIR / "problems" / "window_3d.cfg"


class Window3dBruteForce(AgainstCli, unittest.TestCase):
    cfg = SOURCE_DIR / "problems" / "window_3d.cfg"
    checker_name = "bruteforce"


class Corridor2d(AgainstCli, unittest.TestCase):
    cfg = SOURCE_DIR / "problems" / "corridor_2d.cfg"


class OmplappCubicles(AgainstCli, unittest.TestCase):
    cfg = OMPLAPP / "3D" / "cubicles.cfg"


class OmplappBugTrap(AgainstCli, unittest.TestCase):
    cfg = OMPLAPP / "2D" / "BugTrap_planar.cfg"


class Contracts(unittest.TestCase):
    """The module's own promises, on problems/window_3d.cfg and problems/corridor_2d.cfg."""

    @classmethod
    def setUpClass(cls):
        cls.problem = hybridcd.load_problem(str(SOURCE_DIR / "problems" / "window_3d.cfg"))
        cls.planar = hybridcd.Problem.load(str(SOURCE_DIR / "problems" / "corridor_2d.cfg"))
        cls.checker = hybridcd.Checker(cls.problem)

    def test_problem_fields(self):
        self.assertFalse(self.problem.planar)
        self.assertEqual(self.problem.pose_size, 7)
        self.assertEqual(self.problem.name, "window_3d")
        self.assertEqual(self.problem.start.shape, (7,))
        self.assertTrue(self.planar.planar)
        self.assertEqual(self.planar.pose_size, 3)
        self.assertEqual(self.planar.goal.shape, (3,))
        low, high = self.problem.bounds
        self.assertTrue(np.all(low < high))
        # Start and goal are free, as the problem requires.
        ends = np.array([self.problem.start, self.problem.goal])
        np.testing.assert_array_equal(self.checker.collides(ends), [False, False])

    def test_scene_from_meshes_is_the_problem(self):
        scene = hybridcd.Scene.from_meshes(self.problem.robot_mesh, self.problem.environment_mesh)
        self.assertEqual(scene.robot_triangles, self.problem.robot_triangles)
        poses = random_poses(np.random.default_rng(SEED), self.problem, 200)
        np.testing.assert_array_equal(hybridcd.Checker(scene).collides(poses), self.checker.collides(poses))

    def test_shapes_are_checked(self):
        for bad in (np.zeros((2, 3)), np.zeros(7), np.zeros((2, 7, 1)), np.zeros((0, 6))):
            with self.assertRaisesRegex(ValueError, r"N x 7 \(x, y, z, qx, qy, qz, qw\)"):
                self.checker.collides(bad)
        with self.assertRaisesRegex(ValueError, "N x 3"):
            hybridcd.Checker(self.planar).clearance(np.zeros((1, 7)))
        with self.assertRaisesRegex(ValueError, "same number of rows"):
            self.checker.check_motions(np.tile(self.problem.start, (2, 1)), np.tile(self.problem.goal, (3, 1)))
        self.assertEqual(self.checker.collides(np.zeros((0, 7))).shape, (0,))

    def test_quaternions_are_checked(self):
        pose = np.array([self.problem.start])
        pose[0, 3:] = [0, 0, 0, 2]
        with self.assertRaisesRegex(ValueError, r"poses\[0\]: the quaternion \(qx qy qz qw\) has norm 2"):
            self.checker.collides(pose)
        pose[0, 3:] = 0
        with self.assertRaisesRegex(ValueError, "has norm 0"):
            self.checker.clearance(pose)

    def test_non_finite_rows_collide(self):
        free = np.array([self.problem.start])
        for value in (np.nan, np.inf):
            bad = free.copy()
            bad[0, 1] = value
            self.assertTrue(self.checker.collides(bad)[0])
            self.assertLessEqual(self.checker.clearance(bad)[0], 0.0)
            verdict, fraction = self.checker.check_motions(free, bad, last_free=True)
            self.assertFalse(verdict[0])
            self.assertEqual(fraction[0], 0.0)

    def test_lists_are_accepted(self):
        self.assertFalse(self.checker.collides([list(self.problem.start)])[0])

    def test_library_errors_keep_their_message(self):
        with self.assertRaisesRegex(hybridcd.InputError, r"^/nonexistent/problem\.cfg: cannot open"):
            hybridcd.Problem.load("/nonexistent/problem.cfg")
        self.assertTrue(issubclass(hybridcd.InputError, ValueError))
        with self.assertRaisesRegex(ValueError, "unknown checker 'nope'; valid checkers: obb"):
            hybridcd.Checker(self.problem, name="nope")
        with self.assertRaises(hybridcd.InputError):
            hybridcd.Scene.from_meshes("/nonexistent/robot.obj", self.problem.environment_mesh)

    def test_scenes_and_missing_scenes_are_refused(self):
        # A scene's other robots and primitive obstacles are not the environment mesh a Checker
        # tests: its answers would be wrong, so it is refused by name.
        with self.assertRaisesRegex(hybridcd.InputError, r"crossing_2d\.cfg: a scene problem .* use the command line"):
            hybridcd.Problem.load(str(SOURCE_DIR / "problems" / "crossing_2d.cfg"))
        with self.assertRaisesRegex(TypeError, "Checker needs a Scene or a Problem, got None"):
            hybridcd.Checker(None)
        with self.assertRaisesRegex(ValueError, "zero byte"):
            hybridcd.Problem.load(str(SOURCE_DIR / "problems" / "window_3d.cfg") + "\x00junk")

    def test_batches_run_without_the_gil(self):
        # While one thread checks a long batch, another must keep running Python.
        poses = np.tile(random_poses(np.random.default_rng(SEED), self.problem, 500), (1, 1))
        checker = hybridcd.Checker(self.problem, name="bruteforce")
        started = time.monotonic()
        checker.clearance(poses[:50])
        per_pose = (time.monotonic() - started) / 50
        poses = np.tile(poses, (max(1, int(0.5 / max(per_pose, 1e-7) / len(poses))) + 1, 1))
        ticks = []
        done = threading.Event()
        worker = threading.Thread(target=lambda: (checker.clearance(poses), done.set()))
        worker.start()
        while not done.is_set():
            time.sleep(0.001)
            ticks.append(time.monotonic())
        worker.join()
        self.assertGreater(len(ticks), 20, "the main thread did not run during the batch")


if __name__ == "__main__":
    unittest.main()
