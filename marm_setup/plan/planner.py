"""A minimal joint-space planner: RRT-Connect over a group's active joints, then shortcutting.

The planner sees the world only through a validity checker: a function taking full-robot
configurations (N, n_active) and returning, per row, the first colliding link pair or None
(`CollisionScene.first_collisions` with the SRDF's enabled pairs). Joints outside the group
stay at the start state; mimic joints follow their leaders inside the FK. Edges are checked
at a fixed joint step (Euclidean, in [rad] or [m]), in batches, so one checker call covers
many states.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np

from marm_setup.plan.rrt import interpolate, rrt_connect, shortcut, verify_path
from marm_setup.plan.space import GroupSpace, PlannerOptions, group_space
from marm_setup.robot import LIMIT_TOLERANCE, RobotModel

Pair = tuple[str, str]
ValidityChecker = Callable[[np.ndarray], Sequence[Pair | None]]

__all__ = [
    "GroupSpace",
    "PlanFailed",
    "PlanFound",
    "PlanResult",
    "PlannerOptions",
    "ValidityChecker",
    "discretize_path",
    "group_space",
    "interpolate",
    "path_length",
    "plan_joint_path",
    "state_problem",
]


@dataclass(frozen=True, eq=False)
class PlanFound:
    """A path of waypoints (M, n_group) from start to goal in the group's joints."""

    joint_names: tuple[str, ...]
    q_path: np.ndarray
    iterations: int = 0
    planning_time_s: float = 0.0  # everything: checks, search, shortcutting, verification
    search_time_s: float = 0.0  # up to the first path (what OMPL's solve() measures)


@dataclass(frozen=True, eq=False)
class PlanFailed:
    """Why there is no path; `colliding_pair` when the start or goal state is in collision."""

    joint_names: tuple[str, ...]
    reason: str
    colliding_pair: Pair | None = None
    iterations: int = 0
    planning_time_s: float = 0.0
    search_time_s: float = 0.0


PlanResult = PlanFound | PlanFailed


def discretize_path(q_path: np.ndarray, max_step: float) -> np.ndarray:
    """The whole path, consecutive states at most `max_step` apart, waypoints kept."""
    parts = [q_path[:1]] + [interpolate(a, b, max_step) for a, b in zip(q_path[:-1], q_path[1:], strict=True)]
    return np.concatenate(parts)


def path_length(q_path: np.ndarray) -> float:
    """Sum of Euclidean segment lengths in joint space."""
    return float(np.sum(np.linalg.norm(np.diff(q_path, axis=0), axis=1)))


@dataclass
class _Checker:
    """Counts calls and states; finds the first invalid state along a line in at most two calls.

    The first call checks every `coarse_stride`-th state (collisions are usually wider than a
    few steps, so it finds most of them); the second checks the states left before the first
    coarse hit (or all the rest), so the result is the exact first invalid state.
    """

    space: GroupSpace
    check: ValidityChecker
    options: PlannerOptions
    calls: int = 0
    states: int = 0
    valid_lines: set[tuple[bytes, bytes]] = field(
        default_factory=set
    )  # (q_a, q_b) bytes of lines found valid

    def _hits(self, q: np.ndarray) -> list:
        self.calls += 1
        self.states += len(q)
        return list(self.check(self.space.to_full(q)))

    def first_invalid(self, q: np.ndarray) -> tuple[int | None, Pair | None]:
        n, stride = len(q), self.options.coarse_stride
        if n <= 4 * stride:  # short lines: one call beats two
            hits = self._hits(q)
            bad = next((k for k, hit in enumerate(hits) if hit is not None), None)
            return (None, None) if bad is None else (bad, tuple(hits[bad]))
        coarse = np.unique(np.append(np.arange(stride - 1, n, stride), n - 1))
        hits = self._hits(q[coarse])
        bad = next((k for k, hit in enumerate(hits) if hit is not None), None)
        first, pair = (n, None) if bad is None else (int(coarse[bad]), hits[bad])
        fine = np.setdiff1d(np.arange(first), coarse)
        if len(fine):
            fine_hits = self._hits(q[fine])
            k = next((k for k, hit in enumerate(fine_hits) if hit is not None), None)
            if k is not None:
                first, pair = int(fine[k]), fine_hits[k]
        return (None, None) if pair is None else (first, tuple(pair))

    def line_valid(self, q_a: np.ndarray, q_b: np.ndarray) -> bool:
        key = (q_a.tobytes(), q_b.tobytes())
        if key in self.valid_lines:
            return True
        ok = self.first_invalid(interpolate(q_a, q_b, self.options.max_step))[0] is None
        if ok:
            self.valid_lines.add(key)
        return ok


def _limit_reason(space: GroupSpace, q: np.ndarray, what: str) -> str | None:
    for name, v, lo, hi in zip(space.joint_names, q, space.lower, space.upper, strict=True):
        if not lo - LIMIT_TOLERANCE <= v <= hi + LIMIT_TOLERANCE:
            return f"{what} out of limits: {name} = {v:.6g} not in [{lo:.6g}, {hi:.6g}]"
    return None


def _endpoint_failure(
    space: GroupSpace, checker: _Checker, q_start: np.ndarray, q_goal: np.ndarray
) -> PlanFailed | None:
    for q, what in ((q_start, "start"), (q_goal, "goal")):
        reason = _limit_reason(space, q, what)
        if reason:
            return PlanFailed(space.joint_names, reason)
    hits = checker._hits(np.array([q_start, q_goal]))
    for hit, what in zip(hits, ("start", "goal"), strict=True):
        if hit is not None:
            return PlanFailed(
                space.joint_names, f"{what} in collision: {hit[0]} - {hit[1]}", (hit[0], hit[1])
            )
    return None


def state_problem(
    robot: RobotModel, check: ValidityChecker, q: np.ndarray, joint_names: Sequence[str], what: str = "state"
) -> tuple[str, Pair | None] | None:
    """Why the full configuration `q` cannot be planned from or to (limits, collision), or None."""
    space = group_space(robot, joint_names, q)
    q = np.asarray(q, dtype=float)
    reason = _limit_reason(space, q[space.index], what)
    if reason:
        return reason, None
    hit = check(q[None, :])[0]
    return None if hit is None else (f"{what} in collision: {hit[0]} - {hit[1]}", (hit[0], hit[1]))


def plan_joint_path(
    robot: RobotModel,
    check: ValidityChecker,
    q_start: np.ndarray,
    q_goal: np.ndarray,
    joint_names: Sequence[str],
    rng: np.random.Generator,
    options: PlannerOptions = PlannerOptions(),
) -> PlanResult:
    """Plan from `q_start` to `q_goal` (full configurations) moving only `joint_names`.

    Joints outside the group stay at `q_start`'s values; only the group's values of `q_goal`
    are used. Returns waypoints in the group's joints, or why there are none.
    """
    t0 = time.perf_counter()
    space = group_space(robot, joint_names, q_start)
    checker = _Checker(space, check, options)
    qs, qg = np.asarray(q_start, float)[space.index], np.asarray(q_goal, float)[space.index]
    failure = _endpoint_failure(space, checker, qs, qg)
    if failure is not None:
        return failure
    q_path, iterations = rrt_connect(checker, qs, qg, rng, t0)
    if q_path is None:
        reason = f"no path within budget ({iterations} iterations, {time.perf_counter() - t0:.2f} s)"
        return PlanFailed(space.joint_names, reason, None, iterations, time.perf_counter() - t0)
    t_search = time.perf_counter() - t0
    q_path = verify_path(checker, shortcut(checker, q_path, rng), rng, t0)
    if q_path is None:
        reason = f"no path verified within budget ({time.perf_counter() - t0:.2f} s)"
        return PlanFailed(space.joint_names, reason, None, iterations, time.perf_counter() - t0, t_search)
    return PlanFound(space.joint_names, q_path, iterations, time.perf_counter() - t0, t_search)
