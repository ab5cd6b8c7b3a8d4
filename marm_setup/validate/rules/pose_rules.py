"""Named poses (`group_state`): every group joint given, within limits, collision-free."""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from marm_setup.findings import Finding, error
from marm_setup.robot.model import RobotModel
from marm_setup.setup.groups import active_group_joints, group_joints, groups_by_name

LIMIT_TOL = 1e-9  # [rad] or [m]


def check_pose_values(srdf, robot: RobotModel, file: str) -> list[Finding]:
    """Group exists, joints exist and belong to the group, all active joints given, within bounds."""
    by_name = groups_by_name(srdf.groups)
    out: list[Finding] = []
    for state in srdf.group_states:
        where = f"group_state[{state.name}]"
        if state.group not in by_name:
            out.append(error("pose.unknown-group", file, where, f"unknown group '{state.group}'"))
            continue
        group = by_name[state.group]
        members = set(group_joints(group, by_name, robot))
        given = dict(state.values)
        for joint, value in state.values:
            out += _check_value(joint, value, members, state.group, robot, file, where)
        active = active_group_joints(group, by_name, robot, tuple(srdf.passive_joints))
        missing = [j for j in active if j not in given]
        if missing:
            msg = f"no value for joint(s) {', '.join(missing)} of group '{state.group}'"
            out.append(error("pose.missing-joint", file, where, msg, "give every joint of the group"))
    return out


def _check_value(joint, value, members, group, robot, file, where) -> list[Finding]:
    elem = f"{where}.joint[{joint}]"
    if joint not in robot.joint_map:
        return [error("pose.unknown-joint", file, elem, f"unknown joint '{joint}'")]
    if joint not in members:
        return [
            error("pose.joint-not-in-group", file, elem, f"joint '{joint}' is not part of group '{group}'")
        ]
    j = robot.joint(joint)
    if j.type == "continuous" or not j.is_actuated:
        return []
    lo, hi = j.bounds
    if lo - LIMIT_TOL <= value <= hi + LIMIT_TOL:
        return []
    msg = f"value {value:g} is outside the limits [{lo:g}, {hi:g}]"
    return [error("pose.out-of-limits", file, elem, msg, f"use a value in [{lo:g}, {hi:g}]")]


def pose_configuration(state, robot: RobotModel, base: Mapping[str, float] | None = None) -> np.ndarray:
    """The full active configuration of a named pose: its values over `base` over the default state."""
    from marm_setup.robot.kinematics import default_configuration

    q = default_configuration(robot)
    index = {name: i for i, name in enumerate(robot.active_joint_names)}
    for joint, value in [*(base or {}).items(), *state.values]:
        if joint in index:
            q[index[joint]] = value
    return q


def initial_values(srdf, initial_poses=(), initial_positions: Mapping | None = None) -> dict[str, float]:
    """The state a demo starts in: `initial` (group, pose) pairs of fake_controllers.yaml, or
    ros2_control's initial_positions; joints not given stay at their defaults."""
    out: dict[str, float] = {}
    states = {(s.group, s.name): s for s in srdf.group_states}
    for group, pose in initial_poses:
        if (group, pose) in states:
            out.update(states[group, pose].values)
    for joint, value in (initial_positions or {}).items():
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            out[str(joint)] = float(value)
    return out


def check_pose_collisions(
    srdf, robot: RobotModel, scene, file: str, base: Mapping[str, float] | None = None
) -> list[Finding]:
    """Each pose, other joints at `base` (the package's initial state) or their defaults, is free
    of the collisions MoveIt would check.

    Only pairs whose relative pose the group's joints change count: a hand pose is not blamed
    for where the arm happens to be.
    """
    by_name = groups_by_name(srdf.groups)
    states = [
        s for s in srdf.group_states if s.group in by_name and all(j in robot.joint_map for j, _ in s.values)
    ]
    pairs = scene.enabled_pairs([p.pair for p in srdf.disabled])
    if not states or not pairs:
        return []
    out = []
    for state in states:
        moved = {j for j in group_joints(by_name[state.group], by_name, robot) if robot.joint(j).is_actuated}
        mine = [p for p in pairs if _moves_pair(p, moved, robot)]
        q = pose_configuration(state, robot, base)[None]
        hit = scene.first_collisions(q, mine)[0] if mine else None
        if hit is not None:
            out.append(
                error(
                    "pose.collision",
                    file,
                    f"group_state[{state.name}]",
                    f"in collision: {hit[0]} - {hit[1]}{_context(base)}",
                    hint="move the pose, or disable the pair if the contact is intended",
                )
            )
    return out


def _moves_pair(pair, moved: set[str], robot: RobotModel) -> bool:
    """Some joint in `moved` lies between the two links (changes their relative pose)."""
    up_a = {j.name for j in robot.path_to_root(pair[0])}
    up_b = {j.name for j in robot.path_to_root(pair[1])}
    return bool((up_a ^ up_b) & moved)


def _context(base: Mapping[str, float] | None) -> str:
    return " (other joints at the initial state)" if base else " (other joints at their default values)"


def check_initial_positions(section, robot: RobotModel) -> list[Finding]:
    """ros2_control's `initial_positions.yaml`: known joints, numbers, inside the limits."""
    data = section.data if isinstance(section.data, dict) else {}
    values = data.get("initial_positions", data)
    if not isinstance(values, dict):
        return [
            error(
                "pose.initial-malformed",
                section.file,
                section.element("initial_positions"),
                "expected a mapping",
            )
        ]
    out = []
    for joint, value in sorted(values.items(), key=lambda kv: str(kv[0])):
        where = section.element("initial_positions", joint)
        if joint not in robot.joint_map:
            out.append(error("pose.initial-unknown-joint", section.file, where, f"unknown joint '{joint}'"))
        elif isinstance(value, bool) or not isinstance(value, (int, float)):
            out.append(error("pose.initial-malformed", section.file, where, f"not a number: {value!r}"))
        elif robot.joint(joint).is_actuated and robot.joint(joint).type != "continuous":
            lo, hi = robot.joint(joint).bounds
            if not lo - LIMIT_TOL <= value <= hi + LIMIT_TOL:
                msg = f"initial position {value:g} is outside the limits [{lo:g}, {hi:g}]"
                out.append(error("pose.initial-out-of-limits", section.file, where, msg))
    return out
