"""Reach balls: per link, a ball holding it at every state, in the frame of each of its
ancestors (`ancestor_balls`), so that pairs whose links can never come near each other are
proved without a branch and bound of their own (`far_apart`).

Going up from the link one joint at a time, the ball (centre in the child's frame, radius) is
moved into the parent's frame by the joint's origin, then swept over the joint's whole range
exactly as `pair_chain` sweeps a box's half-width: a turning joint moves the centre to its
range's middle angle and sweeps it over the half-range (the chord's midpoint and rho sin h up to
pi/2, the axis and rho beyond); a sliding joint moves it to its mid travel and adds the half
travel. A mimic joint moves over its leader's range times its multiplier, plus its offset. Two
links whose balls in their common ancestor's frame are apart by more than the padding (and
coal's tolerance) never collide: the pair is proved over every state.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping

import numpy as np

from marm_setup.collision.chain_kinematics import MOVING, rotation_about
from marm_setup.collision.levers import LeverPoints
from marm_setup.collision.pair_chain import ball_round, swept_ball
from marm_setup.robot import Joint, RobotModel, origin_matrix


def ancestor_balls(robot: RobotModel, link: str, levers: LeverPoints) -> dict[str, tuple[np.ndarray, float]]:
    """Ancestor (the link itself included) -> (centre in its frame, radius) of a ball holding
    `link` at every state of the joints between them."""
    centre, radius = ball_round(levers)
    out = {link: (centre, radius)}
    joints = {j.name: j for j in robot.joints}
    for joint in robot.path_to_root(link):
        origin = origin_matrix(joint.origin)
        centre = origin[:3, :3] @ centre + origin[:3, 3]
        if joint.type in MOVING:
            centre, radius = _swept_over_range(joint, joints, origin, centre, radius)
        out[joint.parent] = (centre, radius)
    return out


def _swept_over_range(
    joint: Joint, joints: Mapping[str, Joint], origin: np.ndarray, centre: np.ndarray, radius: float
) -> tuple[np.ndarray, float]:
    low, high = _value_range(joint, joints)
    axis = np.asarray(joint.axis, dtype=float)
    norm = np.linalg.norm(axis)
    axis = origin[:3, :3] @ (axis / norm if norm > 0 else np.array([1.0, 0.0, 0.0]))
    middle, half = (low + high) / 2.0, (high - low) / 2.0
    if joint.type == "prismatic":
        return centre + axis * middle, radius + half
    pivot = origin[:3, 3]
    centre = pivot + rotation_about(axis, middle) @ (centre - pivot)
    return swept_ball(centre, radius, pivot, axis, half)


def _value_range(joint: Joint, joints: Mapping[str, Joint]) -> tuple[float, float]:
    """The joint's own values over its leader's bounds (a mimic: multiplier x + offset)."""
    if joint.mimic is None:
        return joint.bounds
    low, high = joints[joint.mimic.joint].bounds
    ends = sorted(
        (
            joint.mimic.multiplier * low + joint.mimic.offset,
            joint.mimic.multiplier * high + joint.mimic.offset,
        )
    )
    return ends[0], ends[1]


def far_apart(
    robot: RobotModel, pairs: Iterable[tuple[str, str]], levers: Mapping[str, LeverPoints], threshold: float
) -> set[tuple[str, str]]:
    """The pairs of `pairs` whose reach balls, in their links' common ancestor's frame, are
    more than `threshold` apart."""
    balls: dict[str, dict[str, tuple[np.ndarray, float]]] = {}
    out = set()
    for a, b in pairs:
        for link in (a, b):
            if link not in balls:
                balls[link] = ancestor_balls(robot, link, levers[link])
        above_b = balls[b]
        common = next(x for x in balls[a] if x in above_b)  # nearest ancestor of a above b too
        (centre_a, radius_a), (centre_b, radius_b) = balls[a][common], above_b[common]
        if np.linalg.norm(centre_a - centre_b) - radius_a - radius_b > threshold:
            out.add((a, b))
    return out
