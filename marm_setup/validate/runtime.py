"""Runtime validation rules: plan between every two named poses of each group and fake-execute.

A group with more than ALL_PAIRS_POSES usable poses is planned from each pose to the next and
back, in name order around a ring (every pose planned from and to twice, 2n plans), not between
all n(n-1) pairs (200 poses were 39,800 plans, over two minutes, with no output); the summary
says how many pairs were left out.

Rules (in the SRDF's file): `runtime.pose-skipped` (warning: a named pose cannot be planned
from, being out of limits or in self-collision, which the pose rules report as errors; plans
from and to it are skipped), and the errors `runtime.no-plan` (no
collision-free path between two poses within the budget), `runtime.execution` (the timed
trajectory breaks a limit, collides between checked states, or misses the goal) and
`runtime.limits` (the group's limits are unusable).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass
from itertools import permutations
from typing import TYPE_CHECKING

import numpy as np

from marm_setup.errors import InputError
from marm_setup.findings import Finding, error, warning
from marm_setup.plan import (
    PlanFailed,
    PlannerOptions,
    PlanningProblem,
    group_names_with_poses,
    plan_between,
    planning_problem,
    state_problem,
)
from marm_setup.robot import RobotModel

if TYPE_CHECKING:
    from marm_setup.collision import CollisionScene
    from marm_setup.package import MoveItPackage
    from marm_setup.plan import Executed

RUNTIME_OPTIONS = PlannerOptions(max_time_s=5.0)
Progress = Callable[[int, int], None]  # (pose pairs done, pose pairs in all)
ALL_PAIRS_POSES = 10  # a group with up to this many usable poses is planned between all pairs (90)


@dataclass(frozen=True, eq=False)
class PlannedPair:
    """One pose pair the runtime checks planned: the group, the two poses, the full start
    configuration (joints outside the group stay there) and the outcome (a timed,
    fake-executed trajectory of the group's joints, or why there is none)."""

    group: str
    start: str
    goal: str
    q_start: np.ndarray
    outcome: Executed | PlanFailed


def check_runtime(
    package: MoveItPackage,
    robot: RobotModel,
    scene: CollisionScene,
    *,
    seed: int = 0,
    options: PlannerOptions = RUNTIME_OPTIONS,
    planned: list[PlannedPair] | None = None,
    progress: Progress | None = None,
) -> list[Finding]:
    """Findings for every group with two or more named poses (see the module docstring);
    `planned`, when given, receives every pose pair planned; `progress` hears of each pair."""
    findings: list[Finding] = []
    srdf_file = package.srdf_path or package.shown
    groups = group_names_with_poses(package)
    tick = _ticker(package, groups, progress)
    for group in groups:
        try:
            problem = planning_problem(package, robot, scene, group)
        except InputError as exc:
            findings.append(error("runtime.limits", exc.path or srdf_file, f"group[{group}]", exc.message))
            tick(group, None)
            continue
        if problem.limits.unbounded:
            joints = ", ".join(problem.limits.unbounded)
            message = (
                f"no velocity limit for {joints}: MoveIt times trajectories at its default 1 rad/s (m/s)"
            )
            hint = "set max_velocity in joint_limits.yaml (or the URDF)"
            findings.append(warning("runtime.default-velocity", srdf_file, f"group[{group}]", message, hint))
        findings += _check_group(problem, robot, srdf_file, seed, options, planned, tick)
    return findings


def _ticker(
    package: MoveItPackage, groups: tuple[str, ...], progress: Progress | None
) -> Callable[[str, int | None], None]:
    """`tick(group, pairs)`: `pairs` more pose pairs of `group` are done (None: all of them)."""
    states = package.srdf.group_states if package.srdf is not None else ()
    sizes = {g: len({s.name for s in states if s.group == g}) for g in groups}
    pairs = {g: pair_count(n) for g, n in sizes.items()}
    total, done = sum(pairs.values()), [0]

    def tick(group: str, n: int | None) -> None:
        done[0] += pairs[group] if n is None else n
        if progress is not None:
            progress(min(done[0], total), total)

    return tick


def _check_group(
    problem: PlanningProblem,
    robot: RobotModel,
    srdf_file: str,
    seed: int,
    options: PlannerOptions,
    planned: list[PlannedPair] | None = None,
    tick: Callable[[str, int | None], None] = lambda group, n: None,
) -> list[Finding]:
    findings, usable = [], []
    for name in sorted(problem.poses):
        found = state_problem(robot, problem.check, problem.poses[name], problem.joint_names, "pose")
        if found is None:
            usable.append(name)
            continue
        element = f"group_state[{name}]"
        message = f"plans from and to '{name}' skipped: {found[0]}"
        findings.append(warning("runtime.pose-skipped", srdf_file, element, message))
    pairs = pose_pairs(usable)
    tick(problem.group, pair_count(len(problem.poses)) - len(pairs))
    for a, b in pairs:
        outcome = plan_between(problem, robot, problem.poses[a], problem.poses[b], seed, options)
        if planned is not None:
            planned.append(PlannedPair(problem.group, a, b, problem.poses[a], outcome))
        tick(problem.group, 1)
        element = f"group[{problem.group}]/{a} -> {b}"
        if isinstance(outcome, PlanFailed):
            findings.append(error("runtime.no-plan", srdf_file, element, f"no plan: {outcome.reason}"))
        elif not outcome.execution.ok:
            message = "fake execution failed: " + "; ".join(outcome.execution.violations)
            findings.append(error("runtime.execution", srdf_file, element, message))
    return findings


def pair_count(poses: int) -> int:
    """How many pose pairs `pose_pairs` gives for `poses` poses."""
    return poses * (poses - 1) if poses <= ALL_PAIRS_POSES else 2 * poses


def pose_pairs(names: list[str]) -> list[tuple[str, str]]:
    """The (from, to) pose pairs planned: all of them up to ALL_PAIRS_POSES poses, else each
    pose to the next around the ring of `names` and back (2n pairs)."""
    if len(names) <= ALL_PAIRS_POSES:
        return list(permutations(names, 2))
    ring = list(zip(names, names[1:] + names[:1], strict=True))
    return ring + [(b, a) for a, b in ring]


def unplanned_pairs(planned: Iterable[PlannedPair]) -> list[str]:
    """A sentence per group whose pose pairs were not all planned (over ALL_PAIRS_POSES poses)."""
    poses: dict[str, set[str]] = {}
    counts: dict[str, int] = {}
    for pair in planned:
        poses.setdefault(pair.group, set()).update((pair.start, pair.goal))
        counts[pair.group] = counts.get(pair.group, 0) + 1
    out = []
    for group in sorted(poses):
        every = len(poses[group]) * (len(poses[group]) - 1)
        if counts[group] < every:
            out.append(
                f"planning {every - counts[group]:,} of the {every:,} pose pairs of group {group} (over "
                f"{ALL_PAIRS_POSES} poses: each pose is planned to and from its neighbours in name order)"
            )
    return out
