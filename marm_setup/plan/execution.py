"""Fake execution: what a trajectory controller would do with a timed trajectory, checked finely.

Like an ArbotiX `follow_controller` (or MoveIt's fake controllers), the executor moves between
consecutive points with the constant acceleration that takes one point's velocity to the
next's. Every state along the way is checked against the position, velocity and acceleration
limits and for self-collision under the SRDF's matrix, at a joint step finer than the
planner's; the trajectory must be self-consistent and end at the goal, at rest.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from marm_setup.plan.planner import GroupSpace, ValidityChecker
from marm_setup.plan.timing import JointLimits, TimedTrajectory
from marm_setup.robot import LIMIT_TOLERANCE


@dataclass(frozen=True, slots=True)
class ExecutionOptions:
    """Sampling step [rad or m, Euclidean], goal tolerance (per joint), relative limit slack."""

    max_step: float = 0.005
    goal_tolerance: float = 1e-3
    limit_slack: float = 1e-6
    consistency_tolerance: float = 1e-4  # points vs. the motion between them [rad or m]


@dataclass(frozen=True, slots=True)
class ExecutionReport:
    """Violations found (at most one per kind, the first in time) and how many states were checked."""

    violations: tuple[str, ...]
    samples: int
    duration_s: float

    @property
    def ok(self) -> bool:
        return not self.violations


def _first_over(
    values: np.ndarray, limit: np.ndarray, times: np.ndarray, names: tuple[str, ...], what: str, slack: float
) -> str | None:
    over = np.abs(values) > limit * (1.0 + slack) + 1e-12
    if not over.any():
        return None
    k, j = np.argwhere(over)[0]
    return f"{what} limit: {names[j]} at t={times[k]:.3f} s: |{values[k, j]:.6g}| > {limit[j]:.6g}"


def _structure(traj: TimedTrajectory, space: GroupSpace) -> str | None:
    if tuple(traj.joint_names) != tuple(space.joint_names):
        return f"joint names {list(traj.joint_names)} are not the group's {list(space.joint_names)}"
    if len(traj.times) < 1 or traj.times[0] != 0.0 or np.any(np.diff(traj.times) <= 0):
        return "time_from_start must start at 0 and increase strictly, with at least 1 point"
    return None


def _consistency(traj: TimedTrajectory, tol: float) -> str | None:
    if len(traj.times) < 2:
        return None
    dt = np.diff(traj.times)[:, None]
    reached = traj.positions[:-1] + 0.5 * (traj.velocities[:-1] + traj.velocities[1:]) * dt
    err = np.abs(reached - traj.positions[1:])
    if err.max() <= tol:
        return None
    k, j = np.unravel_index(np.argmax(err), err.shape)
    return f"inconsistent points: {traj.joint_names[j]} reaches {reached[k, j]:.6g} at t={traj.times[k + 1]:.3f} s, point says {traj.positions[k + 1, j]:.6g}"


def sample_times(traj: TimedTrajectory, max_step: float) -> np.ndarray:
    """Times [s] at which no joint state moves more than `max_step` (Euclidean) between samples."""
    dt = np.diff(traj.times)
    speed = np.maximum(
        np.linalg.norm(traj.velocities[:-1], axis=1), np.linalg.norm(traj.velocities[1:], axis=1)
    )
    counts = np.maximum(1, np.ceil(speed * dt / max_step).astype(int))
    parts = [
        t0 + (t1 - t0) * np.arange(n) / n
        for t0, t1, n in zip(traj.times[:-1], traj.times[1:], counts, strict=True)
    ]
    return np.concatenate([*parts, traj.times[-1:]])


def _limits(
    traj: TimedTrajectory,
    space: GroupSpace,
    limits: JointLimits,
    t: np.ndarray,
    q: np.ndarray,
    v: np.ndarray,
    a: np.ndarray,
    slack: float,
) -> list[str]:
    names = traj.joint_names
    out = [
        _first_over(v, limits.max_velocity, t, names, "velocity", slack),
        _first_over(a, limits.max_acceleration, t, names, "acceleration", slack),
        _first_over(traj.accelerations, limits.max_acceleration, traj.times, names, "acceleration", slack),
    ]
    low, high = q < space.lower - LIMIT_TOLERANCE, q > space.upper + LIMIT_TOLERANCE
    if (low | high).any():
        k, j = np.argwhere(low | high)[0]
        lo, hi = space.lower[j], space.upper[j]
        out.append(f"position limit: {names[j]} at t={t[k]:.3f} s: {q[k, j]:.6g} not in [{lo:.6g}, {hi:.6g}]")
    return [m for m in dict.fromkeys(out) if m]


def _collision(check: ValidityChecker, space: GroupSpace, t: np.ndarray, q: np.ndarray) -> str | None:
    for start in range(0, len(q), 256):
        hits = check(space.to_full(q[start : start + 256]))
        for i, hit in enumerate(hits):
            if hit is not None:
                return f"collision at t={t[start + i]:.3f} s: {hit[0]} - {hit[1]}"
    return None


def _goal(traj: TimedTrajectory, q_goal: np.ndarray, tol: float) -> str | None:
    err = np.abs(traj.positions[-1] - q_goal)
    if err.max() > tol:
        j = int(np.argmax(err))
        return f"misses the goal: {traj.joint_names[j]} ends at {traj.positions[-1, j]:.6g}, goal {q_goal[j]:.6g}"
    if np.abs(traj.velocities[-1]).max() > tol:
        return "does not end at rest"
    return None


def fake_execute(
    traj: TimedTrajectory,
    space: GroupSpace,
    limits: JointLimits,
    check: ValidityChecker,
    q_goal: np.ndarray,
    options: ExecutionOptions = ExecutionOptions(),
) -> ExecutionReport:
    """Execute `traj` (the group's joints; others held at `space.q_base`) and report violations."""
    problem = _structure(traj, space)
    if problem:
        return ExecutionReport((problem,), 0, 0.0)
    t = sample_times(traj, options.max_step)
    q, v, a = traj.sample(t)
    found = [_consistency(traj, options.consistency_tolerance)]
    found += _limits(traj, space, limits, t, q, v, a, options.limit_slack)
    found += [_collision(check, space, t, q), _goal(traj, np.asarray(q_goal, float), options.goal_tolerance)]
    return ExecutionReport(tuple(m for m in found if m), len(t), traj.duration)
