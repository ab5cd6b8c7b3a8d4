"""The state a package's demo starts in, as MoveIt's demo sets it: one definition for the files
render writes, the planner's held joints and validate's pose checks.

- ros1: MoveIt 1's fake controller manager starts from the default state and applies each
  `initial` (group, pose) entry of fake_controllers.yaml in order, setting that group's active
  joints to the named pose; an unknown group or pose is skipped with a warning (moveit/moveit
  moveit_plugins/moveit_fake_controller_manager/src/moveit_fake_controller_manager.cpp,
  loadInitialJointValues). initial_positions.yaml means nothing to a MoveIt 1 demo.
- ros2: the demo's ros2_control mock hardware starts each joint at its `initial_value`, which the
  ros2_control xacro reads from initial_positions.yaml; a joint it does not list stays at its
  default. MoveIt 2's demo has no fake controller manager reading `initial`.
Joints neither sets stay at MoveIt's default (0, or mid-range where 0 is outside the limits).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping

import numpy as np

from marm_setup.robot import RobotModel
from marm_setup.ros import Target
from marm_setup.setup.groups import group_joints, groups_by_name
from marm_setup.setup.model import GroupState, SetupModel
from marm_setup.setup.srdf import Srdf, setup_to_srdf


def start_pose(model: SetupModel, group: str) -> GroupState | None:
    """The pose a setup's group starts at. With `start_poses` (the whole `initial` list) its
    entry, or none when it has none; without, its `home`, else its first pose."""
    states = [s for s in model.group_states if s.group == group]
    if model.start_poses is not None:
        chosen = {s.group: s.pose for s in model.start_poses}.get(group)
        return next((s for s in states if s.name == chosen), None)
    named = [s for s in states if s.name == "home"]
    return (named or states)[0] if states else None


def model_start_values(model: SetupModel, robot: RobotModel) -> dict[str, float]:
    """The state both targets' demos start in, for a setup: each joint's default, overlaid in
    group order by each group's start pose as ros1's fake controllers apply their `initial` list
    (ros2's initial_positions.yaml writes the result out); mimic joints follow their leaders."""
    q = {j.name: j.default_position for j in robot.joints if j.is_actuated}
    poses = [(g.name, pose.name) for g in model.groups if (pose := start_pose(model, g.name))]
    q.update(initial_pose_values(setup_to_srdf(model), robot, poses))
    for joint in robot.joints:
        if joint.mimic is not None and joint.name in q and joint.mimic.joint in q:
            q[joint.name] = joint.mimic.multiplier * q[joint.mimic.joint] + joint.mimic.offset
    return q


def pose_configuration(
    state: GroupState, robot: RobotModel, base: Mapping[str, float] | None = None
) -> np.ndarray:
    """The full active configuration of a named pose: its values over `base` over the default state."""
    from marm_setup.robot import default_configuration

    q = default_configuration(robot)
    index = {name: i for i, name in enumerate(robot.active_joint_names)}
    for joint, value in [*(base or {}).items(), *state.values]:
        if joint in index:
            q[index[joint]] = value
    return q


def start_configuration(robot: RobotModel, values: Mapping[str, float] | None = None) -> np.ndarray:
    """The full active configuration of `values` (a start state) over the default state."""
    return pose_configuration(GroupState("start", "", ()), robot, values)


def demo_start_values(
    target: Target,
    srdf: Srdf | None,
    robot: RobotModel,
    initial: Iterable[tuple[str, str]],
    positions: Mapping[str, object],
) -> dict[str, float]:
    """Joint values a package's demo sets at start (others stay at their defaults): for ros1
    the `initial` (group, pose) entries of fake_controllers.yaml, for ros2 the values of
    initial_positions.yaml (`positions`, joint -> value as written)."""
    if target == Target.ROS1:
        return initial_pose_values(srdf, robot, initial)
    return initial_position_values(positions, robot)


def initial_pose_values(
    srdf: Srdf | None, robot: RobotModel, poses: Iterable[tuple[str, str]]
) -> dict[str, float]:
    """Each (group, pose) in order sets the group's active joints to the named pose's values."""
    if srdf is None:
        return {}
    groups = groups_by_name(srdf.groups)
    states = {(s.group, s.name): s for s in srdf.group_states}
    out: dict[str, float] = {}
    for group, pose in poses:
        if group not in groups or (group, pose) not in states:
            continue
        active = {j for j in group_joints(groups[group], groups, robot) if robot.joint(j).is_active}
        out.update((joint, value) for joint, value in states[group, pose].values if joint in active)
    return out


def initial_position_values(positions: Mapping[str, object], robot: RobotModel) -> dict[str, float]:
    """The numbers `positions` gives active joints of the robot."""
    return {
        str(joint): float(value)
        for joint, value in positions.items()
        if joint in robot.joint_map
        and robot.joint(joint).is_active
        and isinstance(value, int | float)
        and not isinstance(value, bool)
    }
