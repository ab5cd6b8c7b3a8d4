"""Planner benchmark: our RRT-Connect against OMPL's RRTConnect on the same validity checker.

Queries per robot: the named-pose pairs of the arm group (both directions; poses in collision
skipped) plus N random collision-free start/goal pairs (group joints uniform within limits,
other joints at the package's initial state). Every planner gets the same checker
(`CollisionScene.first_collisions` under the package's SRDF), the same edge resolution
(`max_step`, Euclidean in joint space) and the same extension range, and 10 s per query.

OMPL runs twice: with a per-state validity checker (OMPL's DiscreteMotionValidator calls it
state by state, as MoveIt's OMPL plugin does), and with a Python MotionValidator that hands
each whole edge to the checker in one batch, as our planner does. Times are split alike:
search (to the first path: OMPL's solve(); ours up to RRT-Connect's path) and smoothing
(ours: shortcutting and the final segment verification; OMPL: reduceVertices plus
partialShortcutPath); ratios are given for the search and for the total.

Most random pairs of these arms are joined by a free straight line, so `--hard N` adds up to
N pairs (out of 40 N random ones) whose straight line collides: the ones that need the trees.

Run: .venv/bin/python benchmarks/bench_planner.py [--queries 50] [--hard 10] [--robot marm|panda|all]
(needs the `bench` extra: `pip install -e '.[bench]'`; ompl prints harmless nanobind "leaked"
lines at exit.)
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from marm_setup.collision.scene import CollisionScene
from marm_setup.package.read import read_package
from marm_setup.plan.planner import (
    PlanFound,
    PlannerOptions,
    group_space,
    path_length,
    plan_joint_path,
    state_problem,
)
from marm_setup.plan.problem import planning_problem
from marm_setup.robot.load import load_robot

ROOT = Path(__file__).resolve().parent.parent
PANDA = ROOT.parent / "shared" / "realworld" / "ros1" / "panda_moveit_config"
OPTIONS = PlannerOptions(max_time_s=10.0)


@dataclass(frozen=True)
class Query:
    name: str
    q_start: np.ndarray
    q_goal: np.ndarray


@dataclass(frozen=True)
class Run:
    success: bool
    seconds: float
    length: float
    extra_seconds: float = 0.0  # OMPL: simplification


def load(package_dir: Path, group: str):
    package = read_package(package_dir)
    robot = load_robot(package.description_file, dict(package.xacro_args), list(package.package_paths))
    scene = CollisionScene(robot)
    return robot, planning_problem(package, robot, scene, group)


def marm_package(out: Path) -> Path:
    cmd = [sys.executable, "-m", "marm_setup", "init", str(ROOT / "fixtures/marm/urdf/marm.urdf.xacro")]
    cmd += ["--out", str(out), "--setup", str(ROOT / "fixtures/marm/marm_setup.yaml")]
    subprocess.run(cmd, check=True, capture_output=True)
    return out


def queries(robot, problem, rng: np.random.Generator, n: int) -> list[Query]:
    """Named-pose pairs (both ways, usable poses only), then `n` random collision-free pairs."""
    ok = [
        name
        for name in sorted(problem.poses)
        if state_problem(robot, problem.check, problem.poses[name], problem.joint_names) is None
    ]
    out = [Query(f"{a}->{b}", problem.poses[a], problem.poses[b]) for a in ok for b in ok if a != b]
    base = problem.poses[ok[0]]
    space = group_space(robot, problem.joint_names, base)
    free: list[np.ndarray] = []
    while len(free) < 2 * n:
        q = space.to_full(space.lower + rng.random((64, len(space.index))) * (space.upper - space.lower))
        free += [row for row, hit in zip(q, problem.check(q), strict=True) if hit is None]
    out += [Query(f"random{k}", free[2 * k], free[2 * k + 1]) for k in range(n)]
    return out


def hard_queries(robot, problem, rng: np.random.Generator, n: int, candidates: int) -> list[Query]:
    """Up to `n` random collision-free pairs whose straight line collides (out of `candidates`)."""
    out: list[Query] = []
    for item in queries(robot, problem, rng, candidates)[-candidates:]:
        if len(out) == n:
            break
        if not problem_is_direct(robot, problem, item):
            out.append(Query(f"hard-{item.name}", item.q_start, item.q_goal))
    return out


def run_ours(robot, problem, item: Query, seed: int) -> Run:
    """Search time = up to the first path (like OMPL's solve); extra = shortcutting + verification."""
    rng = np.random.default_rng(seed)
    t0 = time.perf_counter()
    result = plan_joint_path(
        robot, problem.check, item.q_start, item.q_goal, problem.joint_names, rng, OPTIONS
    )
    total = time.perf_counter() - t0
    found = isinstance(result, PlanFound)
    length = path_length(result.q_path) if isinstance(result, PlanFound) else np.nan
    return Run(found, result.search_time_s, length, total - result.search_time_s)


def _ompl_setup(robot, problem, item: Query, batched: bool):
    from ompl import base as ob
    from ompl import geometric as og

    space = group_space(robot, problem.joint_names, item.q_start)
    n = len(space.index)
    state_space = ob.RealVectorStateSpace(n)
    bounds = ob.RealVectorBounds(n)
    for i in range(n):
        bounds.setLow(i, float(space.lower[i]))
        bounds.setHigh(i, float(space.upper[i]))
    state_space.setBounds(bounds)
    si = ob.SpaceInformation(state_space)

    def values(state) -> np.ndarray:
        return np.array([state[i] for i in range(n)])

    si.setStateValidityChecker(lambda s: problem.check(space.to_full(values(s)))[0] is None)
    state_space.setLongestValidSegmentFraction(OPTIONS.max_step / state_space.getMaximumExtent())
    if batched:
        si.setMotionValidator(_batched_validator(ob, si, space, problem.check, values))
    si.setup()
    pdef = ob.ProblemDefinition(si)
    start, goal = si.allocState(), si.allocState()
    for i in range(n):
        start[i] = float(item.q_start[space.index[i]])
        goal[i] = float(item.q_goal[space.index[i]])
    pdef.setStartAndGoalStates(start, goal)
    planner = og.RRTConnect(si)
    planner.setRange(OPTIONS.max_range)
    planner.setProblemDefinition(pdef)
    planner.setup()
    return si, pdef, planner, (start, goal)


def _batched_validator(ob, si, space, check, values):
    from marm_setup.plan.rrt import interpolate

    class BatchedMotionValidator(ob.MotionValidator):  # type: ignore[name-defined]  # ob: ompl.base
        """Checks a whole edge (after its first state) in one checker call."""

        def checkMotion(self, s1, s2):  # noqa: N802 (OMPL's name)
            q = interpolate(values(s1), values(s2), OPTIONS.max_step)
            return all(hit is None for hit in check(space.to_full(q)))

    return BatchedMotionValidator(si)


def run_ompl(robot, problem, item: Query, batched: bool) -> Run:
    from ompl import geometric as og

    si, pdef, planner, _keep = _ompl_setup(robot, problem, item, batched)
    t0 = time.perf_counter()
    status = planner.solve(OPTIONS.max_time_s)
    seconds = time.perf_counter() - t0
    if str(status) != "Exact solution":
        return Run(False, seconds, np.nan)
    path = pdef.getSolutionPath()
    t1 = time.perf_counter()
    simplifier = og.PathSimplifier(si)
    simplifier.reduceVertices(path)
    simplifier.partialShortcutPath(path)
    return Run(True, seconds, path.length(), time.perf_counter() - t1)


def summarize(label: str, runs: list[Run]) -> tuple[float, float]:
    """Print one line; return the median search time and median total time [ms]."""
    search = np.array([r.seconds for r in runs]) * 1000
    total = np.array([r.seconds + r.extra_seconds for r in runs]) * 1000
    smoothing = np.array([r.extra_seconds for r in runs if r.success]) * 1000
    success = 100.0 * sum(r.success for r in runs) / len(runs)
    print(
        f"  {label:<24} success {success:5.1f} %  search median {np.median(search):7.2f} ms "
        f"(p90 {np.percentile(search, 90):7.2f})  smoothing median {np.median(smoothing):7.2f} ms  "
        f"total median {np.median(total):7.2f} ms  mean length {np.nanmean([r.length for r in runs]):5.2f}"
    )
    return float(np.median(search)), float(np.median(total))


def bench(name: str, robot, problem, items: list[Query]) -> None:
    """Run the three planners query by query (interleaved, so machine load hits all alike)."""
    direct = sum(problem_is_direct(robot, problem, item) for item in items)
    print(
        f"{name}: group {problem.group} ({len(problem.joint_names)} joints), {len(items)} queries "
        f"({direct} solvable by the straight line), max_step {OPTIONS.max_step}, range {OPTIONS.max_range}"
    )
    runs: dict[str, list[Run]] = {
        "marm-setup RRT-Connect": [],
        "OMPL RRTConnect": [],
        "OMPL RRTConnect batched": [],
    }
    for k, item in enumerate(items):
        runs["marm-setup RRT-Connect"].append(run_ours(robot, problem, item, k))
        runs["OMPL RRTConnect"].append(run_ompl(robot, problem, item, batched=False))
        runs["OMPL RRTConnect batched"].append(run_ompl(robot, problem, item, batched=True))
    medians = {label: summarize(label, r) for label, r in runs.items()}
    ours = medians["marm-setup RRT-Connect"]
    for other in ("OMPL RRTConnect", "OMPL RRTConnect batched"):
        theirs = medians[other]
        print(
            f"  ratio of medians, ours / {other}: search {ours[0] / theirs[0]:.3f}, "
            f"total (with smoothing) {ours[1] / theirs[1]:.3f}"
        )


def bench_robot(name: str, robot, problem, n: int, n_hard: int) -> None:
    bench(name, robot, problem, queries(robot, problem, np.random.default_rng(0), n))
    if n_hard:
        hard = hard_queries(robot, problem, np.random.default_rng(1), n_hard, 40 * n_hard)
        if hard:
            bench(f"{name} (straight line blocked)", robot, problem, hard)
        else:
            print(f"{name}: no blocked straight line among {40 * n_hard} random pairs")


def problem_is_direct(robot, problem, item: Query) -> bool:
    from marm_setup.plan.rrt import interpolate

    space = group_space(robot, problem.joint_names, item.q_start)
    q = interpolate(item.q_start[space.index], item.q_goal[space.index], OPTIONS.max_step)
    return all(hit is None for hit in problem.check(space.to_full(q)))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--queries", type=int, default=50)
    parser.add_argument("--hard", type=int, default=10, help="extra queries whose straight line collides")
    parser.add_argument("--robot", choices=("marm", "panda", "all"), default="all")
    args = parser.parse_args()
    from ompl import util as ou

    ou.setLogLevel(ou.LOG_WARN)
    ou.RNG.setSeed(1)
    if args.robot in ("marm", "all"):
        with tempfile.TemporaryDirectory() as tmp:
            robot, problem = load(marm_package(Path(tmp) / "marm_moveit_config"), "arm")
            bench_robot("marm", robot, problem, args.queries, args.hard)
    if args.robot in ("panda", "all"):
        if PANDA.exists():
            robot, problem = load(PANDA, "panda_arm")
            bench_robot("panda", robot, problem, args.queries, args.hard)
        else:
            print(f"panda: skipped ({PANDA} not present)")


if __name__ == "__main__":
    main()
