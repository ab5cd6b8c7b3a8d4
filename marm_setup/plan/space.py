"""What a plan runs in: the planner's settings and the box of a group's joints (the other active
joints held at a base configuration). The RRT (`rrt`) and the planner (`planner`) both read them."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from marm_setup.robot import RobotModel, bounds


@dataclass(frozen=True, slots=True)
class PlannerOptions:
    """Planner settings: steps in joint units ([rad] or [m], Euclidean), budgets in count and [s]."""

    max_step: float = 0.02  # edge collision-check resolution
    max_range: float = 0.6  # longest tree extension
    max_iterations: int = 20000
    max_time_s: float = 10.0
    shortcut_iterations: int = 30
    shortcut_patience: int = 5  # stop shortcutting after this many failed attempts in a row
    coarse_stride: int = 8  # a line's every 8th state is checked first, in one call; then the rest


@dataclass(frozen=True, eq=False)
class GroupSpace:
    """The planning space: group joint indices among the active joints, bounds, held joints."""

    joint_names: tuple[str, ...]
    index: np.ndarray
    lower: np.ndarray
    upper: np.ndarray
    q_base: np.ndarray  # full configuration supplying every joint outside the group

    def to_full(self, q: np.ndarray) -> np.ndarray:
        q = np.atleast_2d(q)
        full = np.repeat(self.q_base[None, :], len(q), axis=0)
        full[:, self.index] = q
        return full


def group_space(robot: RobotModel, joint_names: Sequence[str], q_base: np.ndarray) -> GroupSpace:
    """The space of `joint_names` (active joints of `robot`), others held at `q_base`."""
    names = robot.active_joint_names
    unknown = [n for n in joint_names if n not in names]
    if unknown:
        raise ValueError(f"not active joints: {', '.join(unknown)}")
    index = np.array([names.index(n) for n in joint_names], dtype=int)
    lower, upper = bounds(robot)
    q_base = np.asarray(q_base, dtype=float)
    return GroupSpace(tuple(joint_names), index, lower[index], upper[index], q_base.copy())
