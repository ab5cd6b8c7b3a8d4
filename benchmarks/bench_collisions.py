"""Benchmark: compute_collision_matrix against a plain loop calling coal on every pair of every sample.

Run: `.venv/bin/python benchmarks/bench_collisions.py [--trials 10000] [--jobs 1]`.
For the marm fixture and (when present) the shared real-world panda, prints the wall time of
our algorithm and of the plain loop over the same samples (default state, Always rounds and
trials), their ratio, the narrow-phase (coal collide) call counts, and whether both give the
same matrix. Single process unless --jobs is given.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from marm_setup.collision.matrix import ROUND, compute_collision_matrix, trial_samples  # noqa: E402
from marm_setup.collision.pairs import DisabledPair, DisabledReason  # noqa: E402
from marm_setup.collision.scene import CollisionScene  # noqa: E402
from marm_setup.robot.kinematics import default_configuration, sample_configurations  # noqa: E402
from marm_setup.robot.load import load_robot  # noqa: E402

ROBOTS = {
    "marm": ROOT / "fixtures/marm/urdf/marm.urdf.xacro",
    "panda": ROOT.parent / "shared/realworld/ros1/panda_description/urdf/panda_arm_hand.urdf.xacro",
}


def plain_table(scene: CollisionScene, q: np.ndarray) -> np.ndarray:
    """(N, P) collision table: coal on every candidate pair of every state (FK batched)."""
    poses = scene.link_poses(q)
    table = np.zeros((len(q), len(scene.candidate_pairs)), dtype=bool)
    for n in range(len(q)):
        for k in range(len(scene.candidate_pairs)):
            table[n, k] = scene.collide(poses[n], k)
    return table


def plain_matrix(robot, scene: CollisionScene, trials: int, seed: int, fraction: float = 0.95):
    """The same phases as compute_collision_matrix, every pair checked in every sample."""
    pairs = scene.candidate_pairs
    reasons = {p: DisabledReason.ADJACENT for p in robot.adjacent_geometry_pairs()}
    default_hits = plain_table(scene, default_configuration(robot)[None, :])[0]
    reasons.update(
        {
            p: DisabledReason.DEFAULT
            for p, h in zip(pairs, default_hits, strict=True)
            if h and p not in reasons
        }
    )
    rng = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(0,)))
    seen = set()
    while True:
        counts = plain_table(scene, sample_configurations(robot, rng, ROUND)).sum(axis=0)
        seen |= {p for p, c in zip(pairs, counts, strict=True) if c and p not in reasons}
        new = [
            p for p, c in zip(pairs, counts, strict=True) if p not in reasons and c >= fraction * ROUND - 1e-9
        ]
        reasons.update(dict.fromkeys(new, DisabledReason.ALWAYS))
        if not new:
            break
    hit = plain_table(scene, trial_samples(robot, seed, trials)).any(axis=0)
    seen |= {p for p, h in zip(pairs, hit, strict=True) if h}
    reasons.update({p: DisabledReason.NEVER for p in pairs if p not in reasons and p not in seen})
    return tuple(sorted(DisabledPair.of(*p, r) for p, r in reasons.items()))


def bench(name: str, path: Path, trials: int, jobs: int) -> None:
    started = time.perf_counter()
    robot = load_robot(path)
    loaded = time.perf_counter()
    scene = CollisionScene(robot)
    built = time.perf_counter()
    matrix = compute_collision_matrix(robot, scene, trials=trials, seed=0, jobs=jobs)
    ours = time.perf_counter() - built
    calls_before = scene.narrow_calls
    plain_started = time.perf_counter()
    plain = plain_matrix(robot, scene, trials, seed=0)
    plain_time = time.perf_counter() - plain_started
    plain_calls = scene.narrow_calls - calls_before
    print(
        f"{name}: {len(scene.links)} geometry links, {len(scene.candidate_pairs)} candidate pairs, {trials} trials"
    )
    print(f"  load robot {loaded - started:.2f} s, build scene {built - loaded:.2f} s")
    print(f"  ours:       {ours:8.2f} s  narrow-phase calls {matrix.narrow_calls:>10,}  (jobs={jobs})")
    print(f"  plain loop: {plain_time:8.2f} s  narrow-phase calls {plain_calls:>10,}")
    print(f"  ratio: {plain_time / ours:.1f}x faster; same matrix: {plain == matrix.disabled}")
    if plain != matrix.disabled:
        print(f"    only ours:  {sorted(set(matrix.disabled) - set(plain))}")
        print(f"    only plain: {sorted(set(plain) - set(matrix.disabled))}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--trials", type=int, default=10000)
    parser.add_argument("--jobs", type=int, default=1)
    parser.add_argument("--robot", choices=sorted(ROBOTS), action="append")
    args = parser.parse_args()
    for name in args.robot or list(ROBOTS):
        if not ROBOTS[name].exists():
            print(f"{name}: {ROBOTS[name]} not present, skipped")
            continue
        bench(name, ROBOTS[name], args.trials, args.jobs)


if __name__ == "__main__":
    main()
