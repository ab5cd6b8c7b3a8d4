"""Forward kinematics of one side of a link pair (`collision/pair_chain.py`): the joints from
the pair's common ancestor down to one link, at a batch of states of the pair's box.

The chain is built once (`chain_kinematics`): each moving joint's fixed origin is folded with
its motion into three constant 3x3 matrices A, B, C, so that its rotation at value v is
A + sin(v) B + (1 - cos(v)) C (Rodrigues: A = origin, B = origin K, C = origin K^2, K the
axis' cross-product matrix; a sliding joint has only A). At K states, all the joints' local
rotations come out of one array expression, and walking the chain costs one batched 3x3
product per joint: the proofs evaluate small batches (a box, 16 descents) tens of thousands
of times, and their cost is numpy's per-call overhead far more than arithmetic. A chain is
built with the robot's active joints as its columns and `placed` in each pair's box: the
pairs that share an ancestor and a link share it.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from functools import cached_property

import numpy as np

MOVING = ("revolute", "continuous", "prismatic")
_EYE = np.eye(3)


@dataclass(frozen=True, eq=False)
class Step:
    """One joint from the common ancestor towards a link."""

    origin: np.ndarray  # 4x4
    kind: str  # "revolute" (also continuous), "prismatic" or "fixed"
    axis: np.ndarray  # unit
    column: int  # the robot's active joint that drives it (-1: fixed)
    multiplier: float = 1.0
    offset: float = 0.0


@dataclass(frozen=True, eq=False)
class Frames:
    """One chain at K states: the link's pose in the common ancestor's frame (K, 4, 4) and its
    moving joints' axis lines there (through `origins` (K, J, 3) along unit `axes` (K, J, 3)),
    with the box column driving each, its multiplier, and whether it turns (else it slides)."""

    pose: np.ndarray
    origins: np.ndarray
    axes: np.ndarray
    columns: np.ndarray  # (J,)
    multipliers: np.ndarray  # (J,)
    turning: np.ndarray  # (J,) bool
    _spread: np.ndarray  # (J, m)

    def rates(self, rows: np.ndarray, points: np.ndarray, directions: np.ndarray) -> np.ndarray:
        """(R, m): how fast each point (R, 3), fixed to the link, moves along its direction
        (R, 3) per unit of each box column, at the states `rows` (R,) (a row of the columns'
        Jacobian at those points, projected)."""
        axes = self.axes[rows]
        arm = points[:, None, :] - self.origins[rows]
        along = directions[:, None, :]
        moved = np.where(self.turning, np.vecdot(cross(axes, arm), along), np.vecdot(axes, along))
        return moved @ self._spread


@dataclass(frozen=True, eq=False)
class ChainKinematics:
    """A chain's constants (see the module doc), per moving joint j: the column driving it (the
    robot's active joint, or once `placed`, the pair's box column), its multiplier and offset,
    whether it turns, its origin's translation `shift` (J, 3) and its axis in its parent's
    frame `pivot_axes` (J, 3), its rotation's matrices `rotations` (J, 3, 9) as rows A, B, C;
    the fixed joints after the last moving one folded into `tail` (4x4, None when there are
    none)."""

    columns: np.ndarray
    multipliers: np.ndarray
    offsets: np.ndarray
    turning: np.ndarray
    shift: np.ndarray
    pivot_axes: np.ndarray
    rotations: np.ndarray
    tail: np.ndarray | None
    spread: np.ndarray  # (J, m): column weights of each joint (the Jacobian's; once placed)

    @cached_property
    def lines(self) -> np.ndarray:
        """(J, 3, 2): each joint's `shift` and `pivot_axes` as the columns of one matrix."""
        return np.stack([self.shift, self.pivot_axes], axis=2)

    def placed(self, position: np.ndarray, dims: int) -> ChainKinematics:
        """The chain in a pair's box of `dims` variables, `position[c]` the box column of the
        robot's active joint c (one chain serves every pair with the same ancestor and link)."""
        columns = position[self.columns]
        spread = np.zeros((len(columns), dims))
        spread[np.arange(len(columns)), columns] = self.multipliers
        return dataclasses.replace(self, columns=columns, spread=spread)

    def frames(self, q: np.ndarray) -> Frames:
        """The chain at the states `q` (K, m) of the box's variables."""
        count, joints = len(q), len(self.columns)
        values = q[:, self.columns] * self.multipliers + self.offsets  # (K, J)
        fixed, sine, versine = self.rotations[:, 0], self.rotations[:, 1], self.rotations[:, 2]
        local = fixed + np.sin(values)[..., None] * sine + (1.0 - np.cos(values))[..., None] * versine
        local = local.reshape(count, joints, 3, 3)
        rotation, translation = _EYE, np.zeros(3)  # broadcast to (K, ...) by the first joint
        origins, axes = np.empty((count, joints, 3)), np.empty((count, joints, 3))
        for j in range(joints):
            moved = rotation @ self.lines[j]  # the joint's origin offset and axis, in one product
            translation = translation + moved[..., 0]
            axis = moved[..., 1]
            origins[:, j], axes[:, j] = translation, axis
            if not self.turning[j]:
                translation = translation + axis * values[:, j, None]
            rotation = rotation @ local[:, j]
        if self.tail is not None:
            translation = translation + rotation @ self.tail[:3, 3]
            rotation = rotation @ self.tail[:3, :3]
        pose = np.zeros((count, 4, 4))
        pose[:, :3, :3], pose[:, :3, 3], pose[:, 3, 3] = rotation, translation, 1.0
        return Frames(pose, origins, axes, self.columns, self.multipliers, self.turning, self.spread)


def chain_kinematics(steps: tuple[Step, ...]) -> ChainKinematics:
    """The ChainKinematics of folded `steps` (each fixed joint's origin folded into the next
    moving joint's; at most one fixed step, the last), columns as the steps give them."""
    moving = [step for step in steps if step.column >= 0]
    tail = steps[-1].origin if steps and steps[-1].column < 0 else None
    rotations = np.zeros((len(moving), 3, 9))
    for j, step in enumerate(moving):
        turn = _cross_matrix(step.axis) if step.kind == "revolute" else np.zeros((3, 3))
        origin = step.origin[:3, :3]
        rotations[j] = [origin.ravel(), (origin @ turn).ravel(), (origin @ turn @ turn).ravel()]
    return ChainKinematics(
        np.array([s.column for s in moving], dtype=np.intp),
        np.array([s.multiplier for s in moving], dtype=float),
        np.array([s.offset for s in moving], dtype=float),
        np.array([s.kind == "revolute" for s in moving], dtype=bool),
        np.array([s.origin[:3, 3] for s in moving], dtype=float).reshape(-1, 3),
        np.array([s.origin[:3, :3] @ s.axis for s in moving], dtype=float).reshape(-1, 3),
        rotations,
        tail,
        np.zeros((len(moving), 0)),
    )


def folded(steps: list[Step]) -> tuple[Step, ...]:
    """The same chain with each fixed joint's origin folded into the next joint's (fixed joints
    at the end become one): fewer matrix products per state, the same poses."""
    out, carried = [], np.eye(4)
    for step in steps:
        carried = carried @ step.origin
        if step.column >= 0:
            out.append(dataclasses.replace(step, origin=carried))
            carried = np.eye(4)
    if not np.array_equal(carried, np.eye(4)):
        out.append(Step(carried, "fixed", np.zeros(3), -1))
    return tuple(out)


def _cross_matrix(axis: np.ndarray) -> np.ndarray:
    """The cross-product matrix of `axis` (Rodrigues' K)."""
    x, y, z = axis
    return np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])


def rotation_about(axis: np.ndarray, angle: float) -> np.ndarray:
    """The rotation (3, 3) by `angle` about unit `axis`."""
    turn = _cross_matrix(axis)
    return np.sin(angle) * turn + (1.0 - np.cos(angle)) * (turn @ turn) + np.eye(3)


def cross(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Cross product over the last axis (np.cross costs more in its axis handling)."""
    return np.stack(
        [
            u[..., 1] * v[..., 2] - u[..., 2] * v[..., 1],
            u[..., 2] * v[..., 0] - u[..., 0] * v[..., 2],
            u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0],
        ],
        axis=-1,
    )
