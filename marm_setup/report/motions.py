"""The trajectories validate's runtime checks planned between named poses, sampled for playback."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from marm_setup.plan import PlanFailed, group_space
from marm_setup.report.frames import link_frames, trajectory_samples
from marm_setup.robot import RobotModel

if TYPE_CHECKING:
    from marm_setup.validate import PlannedPair


@dataclass(frozen=True, eq=False)
class Motion:
    """One planned pose pair: `problem` why it failed or what fake execution found ("" when it
    ran clean); `times` [s]; `still` the first frame of every drawn link (links * 12), `moving`
    the indices of the links that move and `frames` (len(times), len(moving) * 12) their poses;
    all empty when there is no plan."""

    group: str
    start: str
    goal: str
    problem: str
    duration: float
    times: np.ndarray
    still: np.ndarray
    moving: tuple[int, ...]
    frames: np.ndarray


def motions(robot: RobotModel, plans: Sequence[PlannedPair], links: tuple[str, ...]) -> tuple[Motion, ...]:
    """Every planned pair in the order planned, sampled at the page's frame rate."""
    return tuple(_motion(robot, plan, links) for plan in plans)


def _motion(robot: RobotModel, plan: PlannedPair, links: tuple[str, ...]) -> Motion:
    outcome = plan.outcome
    if isinstance(outcome, PlanFailed):
        empty = np.zeros((0,), dtype=np.float32)
        reason = f"no plan: {outcome.reason}"
        return Motion(plan.group, plan.start, plan.goal, reason, 0.0, empty, empty, (), empty)
    trajectory = outcome.trajectory
    times, positions = trajectory_samples(trajectory)
    q = group_space(robot, trajectory.joint_names, plan.q_start).to_full(positions)
    problem = "; ".join(outcome.execution.violations)
    problem = f"fake execution failed: {problem}" if problem else ""
    every = link_frames(robot, q, links).reshape(len(times), len(links), 12)
    moving = tuple(int(k) for k in np.flatnonzero(np.ptp(every, axis=0).max(axis=1) > 0))
    frames = every[:, list(moving)].reshape(len(times), -1)
    return Motion(
        plan.group,
        plan.start,
        plan.goal,
        problem,
        trajectory.duration,
        times,
        every[0].ravel(),
        moving,
        frames,
    )
