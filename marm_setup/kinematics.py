"""Pure numpy kinematics: origins, mimic expansion, batched forward kinematics, sampling.

A configuration `q` holds the robot's active joints (`robot.active_joint_names`, tree order);
batches are arrays of shape (N, n_active). Link poses come out as (N, n_links, 4, 4) in
`robot.links_in_tree_order`.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from marm_setup.robot_model import Joint, Origin, RobotModel


def origin_matrix(origin: Origin) -> np.ndarray:
    """4x4 homogeneous transform of a URDF origin (fixed-axis roll, pitch, yaw)."""
    r, p, y = origin.rpy
    cr, sr, cp, sp, cy, sy = np.cos(r), np.sin(r), np.cos(p), np.sin(p), np.cos(y), np.sin(y)
    out = np.eye(4)
    out[:3, :3] = [
        [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
        [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
        [-sp, cp * sr, cp * cr],
    ]
    out[:3, 3] = origin.xyz
    return out


def _axis_rotations(axis: np.ndarray, angles: np.ndarray) -> np.ndarray:
    """(N, 3, 3) rotations about a unit `axis` by `angles` [rad] (Rodrigues)."""
    x, y, z = axis
    k = np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])
    s, c = np.sin(angles)[:, None, None], np.cos(angles)[:, None, None]
    return np.eye(3) + s * k + (1.0 - c) * (k @ k)


def joint_motions(joint: Joint, values: np.ndarray) -> np.ndarray | None:
    """(N, 4, 4) motion of `joint` at `values`, or None for a joint that does not move."""
    axis = np.asarray(joint.axis, dtype=float)
    norm = np.linalg.norm(axis)
    axis = axis / norm if norm > 0 else np.array([1.0, 0.0, 0.0])
    if joint.type in ("revolute", "continuous"):
        out = np.broadcast_to(np.eye(4), (len(values), 4, 4)).copy()
        out[:, :3, :3] = _axis_rotations(axis, values)
        return out
    if joint.type == "prismatic":
        out = np.broadcast_to(np.eye(4), (len(values), 4, 4)).copy()
        out[:, :3, 3] = values[:, None] * axis
        return out
    return None


@dataclass(frozen=True)
class _FkPlan:
    """Precomputed per robot: joint origins, parent link index and value source per joint."""

    link_names: tuple[str, ...]
    steps: tuple[tuple[Joint, int, int, np.ndarray], ...]  # joint, parent idx, child idx, origin


@lru_cache(maxsize=16)
def _fk_plan(robot: RobotModel) -> _FkPlan:
    link_names = robot.links_in_tree_order
    index = {name: i for i, name in enumerate(link_names)}
    steps = tuple(
        (j, index[j.parent], index[j.child], origin_matrix(j.origin)) for j in robot.joints_in_tree_order
    )
    return _FkPlan(link_names, steps)


def link_index(robot: RobotModel) -> dict[str, int]:
    """Position of each link in the FK output."""
    return {name: i for i, name in enumerate(robot.links_in_tree_order)}


def joint_values(robot: RobotModel, q: np.ndarray) -> dict[str, np.ndarray]:
    """Values (N,) of every actuated joint, mimic joints as `multiplier * leader + offset`."""
    q = np.atleast_2d(np.asarray(q, dtype=float))
    values = {name: q[:, i] for i, name in enumerate(robot.active_joint_names)}
    for joint in robot.joints:
        if joint.is_actuated and joint.mimic is not None:
            values[joint.name] = joint.mimic.multiplier * values[joint.mimic.joint] + joint.mimic.offset
    return values


def forward_kinematics(robot: RobotModel, q: np.ndarray) -> np.ndarray:
    """World poses (N, n_links, 4, 4) of every link for a batch of configurations."""
    q = np.atleast_2d(np.asarray(q, dtype=float))
    plan = _fk_plan(robot)
    values = joint_values(robot, q)
    poses = np.empty((len(q), len(plan.link_names), 4, 4))
    poses[:, 0] = np.eye(4)
    for joint, parent, child, origin in plan.steps:
        pose = poses[:, parent] @ origin
        motion = joint_motions(joint, values[joint.name]) if joint.is_actuated else None
        poses[:, child] = pose if motion is None else pose @ motion
    return poses


def bounds(robot: RobotModel) -> tuple[np.ndarray, np.ndarray]:
    """Lower and upper bounds of the active joints (soft limits applied; continuous: +-pi)."""
    pairs = [j.bounds for j in robot.active_joints]
    return np.array([p[0] for p in pairs]), np.array([p[1] for p in pairs])


def default_configuration(robot: RobotModel) -> np.ndarray:
    """MoveIt's default state: 0, or mid-range where 0 is outside the bounds."""
    return np.array([j.default_position for j in robot.active_joints])


def sample_configurations(robot: RobotModel, rng: np.random.Generator, n: int) -> np.ndarray:
    """`n` configurations uniform within the bounds; row i depends only on the rng stream."""
    lower, upper = bounds(robot)
    return lower + rng.random((n, len(lower))) * (upper - lower)


def within_bounds(robot: RobotModel, q: np.ndarray, tol: float = 1e-9) -> np.ndarray:
    """Boolean per configuration: every active joint inside its bounds (+- tol)."""
    lower, upper = bounds(robot)
    q = np.atleast_2d(q)
    return np.all((q >= lower - tol) & (q <= upper + tol), axis=1)
