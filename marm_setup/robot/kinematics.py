"""Pure numpy kinematics: origins, mimic expansion, batched forward kinematics, sampling.

A configuration `q` holds the robot's active joints (`robot.active_joint_names`, tree order);
batches are arrays of shape (N, n_active). Link poses come out as (N, n_links, 4, 4) in
`robot.links_in_tree_order`.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np

from marm_setup.robot.model import GOAL_JOINT_TOLERANCE, Joint, Origin, RobotModel


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


def _unit(axis: tuple[float, float, float]) -> np.ndarray:
    vec = np.asarray(axis, dtype=float)
    norm = np.linalg.norm(vec)
    return vec / norm if norm > 0 else np.array([1.0, 0.0, 0.0])


def _cross_matrix(axis: np.ndarray) -> np.ndarray:
    x, y, z = axis
    return np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])


@dataclass(frozen=True)
class _FkStep:
    """One joint of the FK sweep: where its value comes from and its constant parts."""

    kind: str  # "revolute" (also continuous), "prismatic" or "fixed"
    parent: int
    child: int
    origin: np.ndarray  # 4x4
    axis: np.ndarray  # unit vector
    k: np.ndarray  # cross-product matrix of the axis (Rodrigues)
    k2: np.ndarray
    variable: int  # column of q driving the joint (-1: fixed)
    multiplier: float = 1.0
    offset: float = 0.0


def _fk_step(joint: Joint, index: dict[str, int], variables: dict[str, int]) -> _FkStep:
    kind = {"continuous": "revolute", "revolute": "revolute", "prismatic": "prismatic"}.get(
        joint.type, "fixed"
    )
    axis = _unit(joint.axis)
    k = _cross_matrix(axis)
    leader, multiplier, offset = joint.name, 1.0, 0.0
    if joint.mimic is not None:
        leader, multiplier, offset = joint.mimic.joint, joint.mimic.multiplier, joint.mimic.offset
    variable = variables.get(leader, -1) if kind != "fixed" else -1
    return _FkStep(kind, index[joint.parent], index[joint.child], origin_matrix(joint.origin), axis, k, k @ k,
                   variable, multiplier, offset)  # fmt: skip


def _fk_plan(robot: RobotModel) -> tuple[_FkStep, ...]:
    """The FK sweep for `robot`, built once and kept on the (immutable) robot instance."""
    plan = robot.__dict__.get("_fk_plan")
    if plan is None:
        index = link_index(robot)
        variables = {name: i for i, name in enumerate(robot.active_joint_names)}
        plan = tuple(_fk_step(j, index, variables) for j in robot.joints_in_tree_order)
        robot.__dict__["_fk_plan"] = plan  # a cache, like functools.cached_property
    return plan


def link_index(robot: RobotModel) -> dict[str, int]:
    """Position of each link in the FK output."""
    return {name: i for i, name in enumerate(robot.links_in_tree_order)}


def forward_kinematics(robot: RobotModel, q: np.ndarray, links: Iterable[int] | None = None) -> np.ndarray:
    """World poses (N, n_links, 4, 4) of every link for a batch of configurations; with
    `links` (indices in `link_index` order), of those links and their ancestors only (the
    same values, the same operations; the other poses stay zero)."""
    q = np.atleast_2d(np.asarray(q, dtype=float))
    plan = _fk_plan(robot)
    wanted = None if links is None else _with_ancestors(plan, links)
    poses = np.zeros((len(q), len(plan) + 1, 4, 4))
    poses[:, 0] = np.eye(4)
    for step in plan:
        if wanted is not None and step.child not in wanted:
            continue
        pose = poses[:, step.parent] @ step.origin
        child = poses[:, step.child]
        child[:] = pose
        if step.variable < 0:
            continue
        value = q[:, step.variable] * step.multiplier + step.offset
        if step.kind == "revolute":
            s, c = np.sin(value)[:, None, None], np.cos(value)[:, None, None]
            child[:, :3, :3] = pose[:, :3, :3] @ (np.eye(3) + s * step.k + (1.0 - c) * step.k2)
        else:
            child[:, :3, 3] += pose[:, :3, :3] @ step.axis * value[:, None]
    return poses


def _with_ancestors(plan: tuple[_FkStep, ...], links: Iterable[int]) -> set[int]:
    """The link indices `links` and every link above them."""
    parent = {step.child: step.parent for step in plan}
    out: set[int] = set()
    for link in links:
        while link not in out:
            out.add(link)
            link = parent.get(link, link)
    return out


def bounds(robot: RobotModel) -> tuple[np.ndarray, np.ndarray]:
    """Lower and upper bounds of the active joints (soft limits applied; continuous: +-pi)."""
    pairs = [j.bounds for j in robot.active_joints]
    return np.array([p[0] for p in pairs]), np.array([p[1] for p in pairs])


def default_configuration(robot: RobotModel) -> np.ndarray:
    """MoveIt's default state: 0, or mid-range where 0 is outside the bounds."""
    return np.array([j.default_position for j in robot.active_joints])


def wrap_continuous(robot: RobotModel, q: np.ndarray) -> np.ndarray:
    """`q` with continuous joints wrapped into [-pi, pi): the same angle, as MoveIt's enforceBounds."""
    q = np.array(q, dtype=float)
    cols = [i for i, j in enumerate(robot.active_joints) if j.type == "continuous"]
    q[..., cols] = (q[..., cols] + np.pi) % (2.0 * np.pi) - np.pi
    return q


def onto_bounds(robot: RobotModel, q: np.ndarray) -> np.ndarray:
    """`q` with each value at most GOAL_JOINT_TOLERANCE past a bound moved onto it: the state
    that meets a joint goal there within its tolerance and the bounds (`Joint.reaches`)."""
    lower, upper = bounds(robot)
    q = np.array(q, dtype=float)
    near = (q >= lower - GOAL_JOINT_TOLERANCE) & (q <= upper + GOAL_JOINT_TOLERANCE)
    return np.where(near, np.clip(q, lower, upper), q)


def sample_configurations(robot: RobotModel, rng: np.random.Generator, n: int) -> np.ndarray:
    """`n` configurations uniform within the bounds; row i depends only on the rng stream."""
    lower, upper = bounds(robot)
    return lower + rng.random((n, len(lower))) * (upper - lower)
