#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Carries a verified path from a wider puzzle to a narrower one by continuation.

A path that solves one problem is repaired, stage by stage, for environments that move towards the
target problem's. At each stage:
  1. every colliding pose is retracted to the nearest free pose found among random perturbations
     of growing size (translation in the problem's units, rotation scaled by the robot's reach);
  2. every motion between consecutive poses that continuous checking (`check-motion`) does not
     certify free gets its midpoint (translation lerp, rotation slerp),
     retracted the same way, and the halves are checked again, down to a depth limit.
A stage that cannot be repaired is split in two. The final stage is the target problem itself, so
the path written is verified by hybridcd's own `check` and `check-motion` on the target's meshes.

The intermediate environments come from `--stages alpha`: OMPL.app's alpha puzzles differ only in
the gap of the obstacle, which alpha_env-1.X.dae draws as the same raw geometry with y scaled by
1.X and a shifted node; the stages put the 1.1 mesh's raw geometry under node matrices that move,
linearly, from 1.1's placement to the one matching 1.0's bounding box.

Usage: continue_path.py --from-cfg alpha-1.1.cfg --from-path alpha-1.1.path --to-cfg alpha-1.0.cfg
                        --stages alpha --out alpha-1.0.path [--seed N] [--cli build/hybridcd]
All randomness is seeded (default seed 1), so a run is reproducible.
"""
import argparse
import math
import os
import random
import re
import subprocess
import sys
import tempfile


def quat_mul(a, b):
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw,
            aw * bw - ax * bx - ay * by - az * bz)


def quat_normalized(q):
    n = math.sqrt(sum(c * c for c in q))
    return tuple(c / n for c in q)


def quat_from_rotation_vector(v):
    angle = math.sqrt(sum(c * c for c in v))
    if angle < 1e-300:
        return (0.0, 0.0, 0.0, 1.0)
    s = math.sin(angle / 2) / angle
    return (v[0] * s, v[1] * s, v[2] * s, math.cos(angle / 2))


def slerp(a, b, t):
    """OMPL's SO(3) interpolation: the shorter arc from a to b."""
    dot = sum(x * y for x, y in zip(a, b))
    if dot < 0:
        b = tuple(-c for c in b)
        dot = -dot
    if dot > 1 - 1e-12:
        return quat_normalized(tuple(x + t * (y - x) for x, y in zip(a, b)))
    theta = math.acos(min(1.0, dot))
    s = math.sin(theta)
    wa = math.sin((1 - t) * theta) / s
    wb = math.sin(t * theta) / s
    return quat_normalized(tuple(wa * x + wb * y for x, y in zip(a, b)))


def midpoint(p, q):
    return tuple((x + y) / 2 for x, y in zip(p[:3], q[:3])) + slerp(p[3:], q[3:], 0.5)


def pose_text(p):
    return ' '.join(repr(float(c)) for c in p)


def read_path(filename):
    """The poses of a 3D .path file (x y z qx qy qz qw per line; '#' lines and blank lines skipped)."""
    poses = []
    with open(filename) as f:
        for number, line in enumerate(f, 1):
            line = line.strip()
            if not line or line.startswith('#'):
                continue
            try:
                values = [float(v) for v in line.split()]
            except ValueError:
                sys.exit(f'{filename}:{number}: a pose holds numbers only (x y z qx qy qz qw)')
            if len(values) != 7:
                sys.exit(f'{filename}:{number}: expected 7 numbers per pose (x y z qx qy qz qw), got {len(values)}')
            if not all(math.isfinite(v) for v in values) or not any(values[3:]):
                sys.exit(f'{filename}:{number}: numbers must be finite and the quaternion non-zero')
            poses.append(tuple(values[:3]) + quat_normalized(tuple(values[3:])))
    if len(poses) < 2:
        sys.exit(f'{filename}: a path needs at least two poses, found {len(poses)}')
    return poses


class Checker:
    """Runs hybridcd's `check` and `check-motion` on batches of poses and motions of one problem."""

    def __init__(self, cli, cfg, workdir):
        self.cli, self.cfg, self.workdir = cli, cfg, workdir

    def _run(self, command, option, lines):
        listing = os.path.join(self.workdir, 'batch.txt')
        with open(listing, 'w') as f:
            f.write('\n'.join(lines) + '\n')
        result = subprocess.run([self.cli, command, self.cfg, option, listing],
                                capture_output=True, text=True)
        if result.returncode != 0:
            sys.exit(f'{command} failed on {self.cfg}: {result.stderr.strip()}')
        return result.stdout.split('\n')

    def free(self, poses):
        if not poses:
            return []
        out = self._run('check', '--states', [pose_text(p) for p in poses])
        return [line.strip() == '1' for line in out[:len(poses)]]

    def motions_free(self, pairs):
        if not pairs:
            return []
        out = self._run('check-motion', '--motions',
                        [pose_text(a) + ' ' + pose_text(b) for a, b in pairs])
        return [line.split()[0] == '1' for line in out[:len(pairs)]]


def retract(checker, poses, rng, reach, candidates_per_scale=48):
    """For each pose: itself when free, else the free perturbation of smallest scale found (None if none)."""
    result = list(poses)
    free = checker.free(poses)
    pending = [i for i, f in enumerate(free) if not f]
    scale = 0.01
    while pending and scale <= 4.0:
        batch, owner = [], []
        for i in pending:
            p = poses[i]
            for _ in range(candidates_per_scale):
                t = tuple(c + rng.gauss(0, scale) for c in p[:3])
                turn = quat_from_rotation_vector(tuple(rng.gauss(0, scale / reach) for _ in range(3)))
                batch.append(t + quat_normalized(quat_mul(turn, p[3:])))
                owner.append(i)
        verdicts = checker.free(batch)
        best = {}
        for candidate, i, ok in zip(batch, owner, verdicts):
            if not ok:
                continue
            d = sum((a - b) ** 2 for a, b in zip(candidate[:3], poses[i][:3]))
            if i not in best or d < best[i][0]:
                best[i] = (d, candidate)
        for i, (_, candidate) in best.items():
            result[i] = candidate
        pending = [i for i in pending if i not in best]
        scale *= 2
    for i in pending:
        result[i] = None
    return result


def repair(checker, path, rng, reach, max_depth):
    """The path with every pose free and every motion certified, or None."""
    path = retract(checker, path, rng, reach)
    if any(p is None for p in path):
        return None
    for depth in range(max_depth + 1):
        pairs = list(zip(path[:-1], path[1:]))
        verdicts = checker.motions_free(pairs)
        failing = [i for i, ok in enumerate(verdicts) if not ok]
        if not failing:
            return path
        if depth == max_depth:
            return None
        middles = retract(checker, [midpoint(*pairs[i]) for i in failing], rng, reach)
        if any(m is None for m in middles):
            return None
        insert_after = dict(zip(failing, middles))
        repaired = []
        for i, p in enumerate(path):
            repaired.append(p)
            if i in insert_after:
                repaired.append(insert_after[i])
        path = repaired
    return None


def cfg_values(cfg):
    """The key = value lines of a .cfg file (sections ignored)."""
    values = {}
    with open(cfg) as f:
        for line in f:
            if '=' in line:
                key, value = line.split('=', 1)
                values[key.strip()] = value.strip()
    return values


class AlphaStages:
    """Problem files whose environment moves from from_cfg's alpha mesh towards to_cfg's. Both
    meshes are read and checked once, here; each stage only writes a new node matrix."""

    def __init__(self, from_cfg, to_cfg):
        def not_alpha(dae, what):
            sys.exit(f'{dae}: {what}: --stages alpha needs two of OMPL.app\'s alpha_env-1.X.dae meshes')

        def node_matrix(dae):
            with open(dae) as f:
                text = f.read()
            found = re.search(r'<matrix>([^<]*)</matrix>', text)
            if not found or len(found.group(1).split()) != 16:
                not_alpha(dae, 'no node matrix of 16 numbers')
            return text, [float(v) for v in found.group(1).split()]

        def raw_ranges(dae, text):
            """Per raw axis, the (min, max) of the vertex array ID11."""
            found = re.search(r'<float_array id="ID11"[^>]*>([^<]*)<', text)
            if not found or len(found.group(1).split()) < 3:
                not_alpha(dae, 'no vertex array ID11')
            values = [float(v) for v in found.group(1).split()]
            return [(min(values[axis::3]), max(values[axis::3])) for axis in range(3)]

        self.folder = os.path.dirname(os.path.abspath(to_cfg))
        source_values, target_values = cfg_values(from_cfg), cfg_values(to_cfg)
        for cfg, values in ((from_cfg, source_values), (to_cfg, target_values)):
            if 'world' not in values:
                sys.exit(f'{cfg}: no "world = ..." line')
        self.source_text, self.m_from = node_matrix(os.path.join(self.folder, source_values['world']))
        target_text, self.m_to = node_matrix(os.path.join(self.folder, target_values['world']))
        ranges_from = raw_ranges(source_values['world'], self.source_text)
        ranges_to = raw_ranges(target_values['world'], target_text)
        # The alpha puzzles' obstacles differ only along raw y (the gap); anything else is not a pair.
        for axis in (0, 2):
            if any(abs(a - b) > 1e-6 * (1.0 + abs(a)) for a, b in zip(ranges_from[axis], ranges_to[axis])):
                not_alpha(target_values['world'],
                          f'its raw extent along axis {axis} differs from {source_values["world"]}\'s')
        (y_lo_from, y_hi_from), (y_lo_to, y_hi_to) = ranges_from[1], ranges_to[1]
        # World y of the target: m_to[5] * raw + m_to[7]. The source's raw range maps onto it with
        # scale k and offset b.
        self.k = self.m_to[5] * (y_hi_to - y_lo_to) / (y_hi_from - y_lo_from)
        self.b = self.m_to[5] * y_lo_to + self.m_to[7] - self.k * y_lo_from
        with open(from_cfg) as f:
            self.template = f.read()

    def files(self, workdir, fractions):
        """One .cfg per fraction (0: from_cfg's obstacle, 1: to_cfg's placement), written into workdir."""
        m_from, m_to = self.m_from, self.m_to
        files = []
        for n, f in enumerate(fractions):
            m = list(m_from)
            m[3] = m_from[3] + f * (m_to[3] - m_from[3])
            m[5] = m_from[5] + f * (self.k - m_from[5])
            m[7] = m_from[7] + f * (self.b - m_from[7])
            m[11] = m_from[11] + f * (m_to[11] - m_from[11])
            matrix = ' '.join(f'{v:.9f}' for v in m)
            dae = os.path.join(workdir, f'stage{n}_env.dae')
            with open(dae, 'w') as out:
                out.write(re.sub(r'<matrix>[^<]*</matrix>', f'<matrix>{matrix}</matrix>', self.source_text, count=1))
            cfg = os.path.join(workdir, f'stage{n}.cfg')
            text = re.sub(r'(?m)^world\s*=.*$', f'world = {dae}', self.template)
            text = re.sub(r'(?m)^robot\s*=\s*(.*)$',
                          lambda r: f'robot = {os.path.join(self.folder, r.group(1).strip())}', text)
            with open(cfg, 'w') as out:
                out.write(text)
            files.append(cfg)
        return files


def endpoint(cfg, which):
    """The start or goal pose of an SE(3) .cfg (theta about axis), as x y z qx qy qz qw."""
    values = cfg_values(cfg)

    def get(key):
        try:
            return float(values[f'{which}.{key}'])
        except (KeyError, ValueError):
            sys.exit(f'{cfg}: no number for {which}.{key} (continue_path plans SE(3) problems)')

    axis = (get('axis.x'), get('axis.y'), get('axis.z'))
    norm = math.sqrt(sum(c * c for c in axis))
    theta = get('theta')
    rotation = quat_from_rotation_vector(tuple(c / norm * theta for c in axis))
    return (get('x'), get('y'), get('z')) + rotation


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('--from-cfg', required=True)
    parser.add_argument('--from-path', required=True)
    parser.add_argument('--to-cfg', required=True)
    parser.add_argument('--stages', choices=['alpha'], required=True)
    parser.add_argument('--out', required=True)
    parser.add_argument('--seed', type=int, default=1)
    parser.add_argument('--steps', type=int, default=10, help='initial number of stages')
    parser.add_argument('--max-depth', type=int, default=10, help='bisections per motion and stage')
    parser.add_argument('--reach', type=float, default=100.0,
                        help='robot radius converting rotation to distance for perturbations')
    parser.add_argument('--cli', default=os.path.join(os.path.dirname(os.path.abspath(__file__)), '..',
                                                      'build', 'hybridcd'))
    args = parser.parse_args()
    if args.steps < 1 or args.max_depth < 0 or not args.reach > 0:
        sys.exit('continue_path: --steps must be at least 1, --max-depth at least 0 and --reach positive')
    if not os.access(args.cli, os.X_OK):
        sys.exit(f'continue_path: no hybridcd tool at {args.cli} (build it, or name it with --cli)')
    out_folder = os.path.dirname(os.path.abspath(args.out))
    if not os.path.isdir(out_folder) or not os.access(out_folder, os.W_OK):
        sys.exit(f'continue_path: cannot write into {out_folder}')
    try:
        run(args)
    except OSError as error:
        sys.exit(f'continue_path: {error.filename}: {error.strerror}')


def run(args):
    rng = random.Random(args.seed)
    path = read_path(args.from_path)
    start, goal = endpoint(args.to_cfg, 'start'), endpoint(args.to_cfg, 'goal')
    stages = AlphaStages(args.from_cfg, args.to_cfg)  # refuses a pair that is not alpha puzzles
    with tempfile.TemporaryDirectory() as workdir:
        done, step = 0.0, 1.0 / args.steps
        while done < 1.0:
            target = min(1.0, done + step)
            if target >= 1.0 - 1e-12:
                cfg = os.path.abspath(args.to_cfg)
                # The target's own start and goal close the path; the motions to them are repaired too.
                candidate = [start] + path[1:-1] + [goal]
            else:
                cfg = stages.files(workdir, [target])[0]
                candidate = path
            repaired = repair(Checker(args.cli, cfg, tempfile.mkdtemp(dir=workdir)), candidate, rng, args.reach,
                              args.max_depth)
            if repaired is None:
                step /= 2
                print(f'stage {target:.4f} failed; step now {step:.5f}', flush=True)
                if step < 1e-3:
                    sys.exit('continuation stalled: no repair at the smallest step; nothing written')
                continue
            path, done = repaired, target
            print(f'stage {done:.4f}: {len(path)} poses', flush=True)
            step = min(step * 1.5, 0.25)
    # The last stage is the target problem itself, and repair() returns a path only when each of
    # its poses was found free and every motion between them certified there: it is verified.
    tmp = args.out + '.tmp'
    try:
        with open(tmp, 'w') as f:
            for p in path:
                f.write(pose_text(p) + '\n')
        os.replace(tmp, args.out)
    except OSError:
        if os.path.exists(tmp):
            os.remove(tmp)
        raise
    print(f'wrote {args.out}: {len(path)} poses, every pose free and every motion certified')


if __name__ == '__main__':
    main()
