"""Benchmark: `marm-setup collisions` as a whole process, next to the bare-import floor.

Run: `.venv/bin/python benchmarks/bench_collisions.py [--trials 10000] [--runs 3] [--jobs N]
[--robot marm|panda|pr2 ...] [--exhaustive] [--prove off|on|exhaustive]`.

For the marm fixture, the shared real-world panda and the PR2 (`../shared/realworld`, skipped
when absent) it prints, measured in the same run and interleaved so load hits both alike:
- the median wall time of the whole `marm-setup collisions URDF --trials N --prove P` process,
  of the same with `--prove off` (sampling alone: MoveIt's rule) and of
  `python -c "import numpy, coal, lxml.etree"` (the floor any Python tool pays), and the ratios;
- the matrix phase alone (compute_collision_matrix in this process) and its work: exact coal
  checks, certificate distance queries, states a certificate proved, hull tests and rejections;
- with --exhaustive, the same phase with the shortcuts off (every state checked exactly) and
  whether both matrices are identical.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from marm_setup.collision.matrix import compute_collision_matrix  # noqa: E402
from marm_setup.collision.scene import CollisionScene  # noqa: E402
from marm_setup.robot.load import load_robot  # noqa: E402

REALWORLD = ROOT.parent / "shared" / "realworld" / "ros1"
ROBOTS = {
    "marm": ROOT / "fixtures/marm/urdf/marm.urdf.xacro",
    "panda": REALWORLD / "panda_description/urdf/panda_arm_hand.urdf.xacro",
    "pr2": REALWORLD / "pr2_description/urdf/robot.xml",
}
FLOOR = [sys.executable, "-c", "import numpy, coal, lxml.etree"]


def wall(argv: list[str]) -> float:
    """Wall time [s] of `argv`, without the proof cache (every run proves from scratch)."""
    started = time.perf_counter()
    env = dict(os.environ, MARM_SETUP_CACHE="off")
    subprocess.run(argv, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env)
    return time.perf_counter() - started


def whole_process(
    path: Path, trials: int, jobs: int | None, runs: int, prove: str
) -> tuple[float, float, float]:
    """Median wall time [s] of the collisions process (--prove `prove`, then off) and of the
    floor, runs interleaved."""
    command = [sys.executable, "-m", "marm_setup", "collisions", str(path), "--trials", str(trials)]
    if jobs is not None:
        command += ["--jobs", str(jobs)]
    floors, processes, sampled = [], [], []
    for _ in range(runs):
        floors.append(wall(FLOOR))
        processes.append(wall([*command, "--prove", prove]))
        sampled.append(wall([*command, "--prove", "off"]))
    return statistics.median(processes), statistics.median(sampled), statistics.median(floors)


def matrix_phase(robot, trials: int, jobs: int, shortcuts: bool, prove: str = "off"):
    scene = CollisionScene(robot)
    started = time.perf_counter()
    matrix = compute_collision_matrix(
        robot, scene, trials=trials, jobs=jobs, shortcuts=shortcuts, prove=prove
    )
    return matrix, time.perf_counter() - started


def bench(name: str, path: Path, args) -> None:
    jobs = args.jobs or len(os.sched_getaffinity(0))
    process, sampled, floor = whole_process(path, args.trials, args.jobs, args.runs, args.prove)
    robot = load_robot(path)
    matrix, seconds = matrix_phase(robot, args.trials, jobs, shortcuts=True, prove=args.prove)
    work = matrix.work
    print(
        f"{name}: {len(matrix.stats)} candidate pairs, {args.trials} trials, jobs {jobs}, --prove {args.prove}"
    )
    print(
        f"  whole process {process:6.2f} s   --prove off {sampled:6.2f} s (ratio {process / sampled:4.2f})"
        f"   import floor {floor:5.2f} s   (medians of {args.runs})"
    )
    never = [s for s in matrix.stats if s.reason is not None and s.reason.value == "Never"]
    proved = sum(1 for s in never if s.proof is not None and s.proof.outcome == "proved")
    found = sum(
        1
        for s in matrix.stats
        if s.proof is not None and s.proof.outcome == "collides" and not s.seen_colliding
    )
    print(
        f"  matrix phase  {seconds:6.2f} s   Never {len(never)}, proved {proved}, enabled by a proof {found}"
    )
    print(
        f"  exact checks {work.exact_checks:,}   certificate queries {work.certificate_queries:,}"
        f"   proven by certificates {work.certified:,}"
        f"   hull tests {work.hull_checks:,} (rejected {work.hull_rejections:,})   proof units {work.proof_units:,}"
    )
    if args.exhaustive:
        exact, exact_seconds = matrix_phase(robot, args.trials, jobs, shortcuts=False)
        print(
            f"  exhaustive    {exact_seconds:6.2f} s   exact checks {exact.work.exact_checks:,}"
            f"   same matrix: {exact == matrix}"
        )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--trials", type=int, default=10000)
    parser.add_argument("--runs", type=int, default=3, help="whole-process runs (median)")
    parser.add_argument("--jobs", type=int, default=None, help="default: as marm-setup (CPU count)")
    parser.add_argument("--robot", choices=sorted(ROBOTS), action="append")
    parser.add_argument("--exhaustive", action="store_true", help="also time the shortcut-free check")
    parser.add_argument("--prove", choices=("off", "on", "exhaustive"), default="on")
    args = parser.parse_args()
    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} CPUs")
    for name in args.robot or list(ROBOTS):
        if not ROBOTS[name].exists():
            print(f"{name}: {ROBOTS[name]} not present, skipped")
            continue
        bench(name, ROBOTS[name], args)


if __name__ == "__main__":
    main()
