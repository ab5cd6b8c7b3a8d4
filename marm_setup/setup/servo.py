"""MoveIt Servo per arm group: the default servos of a setup, what each resolves to (group,
frames, the controller its output reaches), and the checks of the setup's `servo` key.

Frames. moveit_servo (noetic servo_calcs.cpp, humble servo_calcs.cpp cartesianServoCalcs) turns
a twist into joint motion with `RobotState::getJacobian(group)`, which is expressed in the frame
of the parent link of the group's first joint (moveit2 humble robot_state.cpp l.1311-1315;
Jazzy's servo uses the IK solver's base frame instead, servo.cpp l.403, the same link for a KDL
chain), so that link is the planning frame: the twist is first transformed into
`planning_frame`, and the two must agree. Every frame must be a link of the robot model:
`getGlobalLinkTransform(name)` throws "Invalid link" on any other name (humble robot_state.h
l.1345-1349; noetic dereferences the null link). So a virtual joint's parent frame (`world`,
not a link of MoveIt's model) cannot be servo's planning frame; the group's base link is, and
for a fixed virtual joint it is rigidly attached to that world frame.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping

from marm_setup.errors import InputError
from marm_setup.moveit_params import (
    FOLLOW_JOINT_TRAJECTORY,
    FORWARD_POSITION,
    SERVO_POSITION,
    SERVO_TRAJECTORY,
)
from marm_setup.names import did_you_mean, with_hint
from marm_setup.robot import RobotModel, name_kinds
from marm_setup.ros import ControllerKind, DistroRow, Target
from marm_setup.setup.groups import active_group_joints, group_joints, groups_by_name, is_chain
from marm_setup.setup.model import Controller, Group, Servo, SetupModel

# Group names that say a limb servo is not for (a leg, a head, a torso, a hand); `arm` wins.
NOT_ARM_KINDS = frozenset({"leg", "head", "torso", "hand", "wheel", "rotor"})


@dataclasses.dataclass(frozen=True, slots=True)
class ServoPlan:
    """One servo, resolved: the setup's entry, its frames, joints and where its output goes.

    `output_controller` is the FollowJointTrajectory controller's name (`trajectory`) or the
    forward position controller's (`position`); `trajectory_controller` is the group's
    FollowJointTrajectory controller either way ('' when it has none)."""

    servo: Servo
    planning_frame: str
    ee_frame: str
    command_frame: str
    joints: tuple[str, ...]
    output_controller: str
    trajectory_controller: str

    @property
    def group(self) -> str:
        return self.servo.group

    @property
    def is_trajectory(self) -> bool:
        return self.servo.command_out == SERVO_TRAJECTORY


def servo_entries(model: SetupModel, robot: RobotModel) -> tuple[Servo, ...]:
    """The setup's servos: its `servo` list, or (none given) one per arm group."""
    return model.servo if model.servo is not None else default_servos(model, robot)


def default_servos(model: SetupModel, robot: RobotModel) -> tuple[Servo, ...]:
    """A trajectory servo for every arm group: a MoveIt chain with an IK solver whose joints one
    FollowJointTrajectory controller drives, not named for a leg, head, torso or hand."""
    by_name = groups_by_name(model.groups)
    solved = {k.group for k in model.kinematics}
    out = []
    for group in by_name.values():
        kinds = name_kinds(group.name)
        if group.name not in solved or ("arm" not in kinds and kinds & NOT_ARM_KINDS):
            continue
        if group.chain is None or not is_chain(group, by_name, robot, model.passive_joints):
            continue
        if trajectory_controller(model, robot, group) is not None:
            out.append(Servo(group.name))
    return tuple(out)


def trajectory_controller(model: SetupModel, robot: RobotModel, group: Group) -> Controller | None:
    """The FollowJointTrajectory controller whose joints are exactly the group's active joints
    (JointTrajectoryController, ROS 1 and 2, rejects a trajectory naming joints it does not own
    and, unless allow_partial_joints_goal, one leaving some of its joints out); the group's own
    controller first."""
    joints = set(active_group_joints(group, groups_by_name(model.groups), robot, model.passive_joints))
    fits = [c for c in model.controllers if c.type == FOLLOW_JOINT_TRAJECTORY and set(c.joints) == joints]
    return next((c for c in fits if c.group == group.name), fits[0] if fits else None)


def forward_controller_name(group: str) -> str:
    return f"{group}_position_controller"


def plan_servos(model: SetupModel, robot: RobotModel) -> list[ServoPlan]:
    """Every servo of the setup, resolved (the setup has passed `check_servos`)."""
    by_name = groups_by_name(model.groups)
    return [_plan(model, robot, by_name, s) for s in servo_entries(model, robot)]


def _plan(model: SetupModel, robot: RobotModel, by_name: Mapping[str, Group], servo: Servo) -> ServoPlan:
    group = by_name[servo.group]
    joints = group_joints(group, by_name, robot)
    base = robot.joint(joints[0]).parent  # getJacobian's reference link
    tip = robot.joint(joints[-1]).child  # the chain's deepest link
    planning = servo.planning_frame or base
    found = trajectory_controller(model, robot, group)
    if servo.command_out == SERVO_POSITION:
        output = servo.controller or forward_controller_name(group.name)
        trajectory = found.name if found else ""
    else:
        output = trajectory = servo.controller or (found.name if found else "")
    return ServoPlan(
        servo=servo,
        planning_frame=planning,
        ee_frame=servo.ee_frame or tip,
        command_frame=servo.command_frame or planning,
        joints=active_group_joints(group, by_name, robot, model.passive_joints),
        output_controller=output,
        trajectory_controller=trajectory,
    )


@dataclasses.dataclass(frozen=True, slots=True)
class ForwardController:
    """A ros2_control forward position controller for servo's `position` output; `replaces` is
    the trajectory controller claiming the same joints ('' when there is none); `kind` the
    distro's controller (type, package, interface_name)."""

    name: str
    kind: ControllerKind
    joints: tuple[str, ...]
    replaces: str

    @property
    def type(self) -> str:
        return self.kind.type


def forward_controllers(plans: list[ServoPlan], row: DistroRow) -> list[ForwardController]:
    """The forward position controllers the servos need, in servo order, of `row`'s ros2_controllers."""
    wanted = [p for p in plans if not p.is_trajectory]
    if not wanted:
        return []
    kind = row.controller(FORWARD_POSITION)
    return [ForwardController(p.output_controller, kind, p.joints, p.trajectory_controller) for p in wanted]


# -- checks --------------------------------------------------------------------------------------


def check_servos(model: SetupModel, robot: RobotModel, path: str | None) -> None:
    """Raise InputError for the first servo moveit_servo could not run or whose output would
    reach no controller."""
    by_name = groups_by_name(model.groups)
    seen: set[str] = set()
    forward: set[str] = set()
    for servo in model.servo or ():
        where = f"servo[{servo.group}]"
        if servo.group in seen:
            raise InputError(f"duplicate servo for group '{servo.group}'", path=path, element=where)
        seen.add(servo.group)
        _check_group(model, robot, by_name, servo, path, where)
        _check_frames(robot, servo, path, where)
        if servo.command_out == SERVO_POSITION:
            _check_position_output(model, servo, forward, path, where)
        else:
            _check_trajectory_output(model, robot, by_name[servo.group], servo, path, where)
        _check_numbers(servo, path, where)


def _fail(message: str, path: str | None, where: str) -> InputError:
    return InputError(message, path=path, element=where)


def _check_group(
    model: SetupModel,
    robot: RobotModel,
    by_name: Mapping[str, Group],
    servo: Servo,
    path: str | None,
    where: str,
) -> None:
    """A group of the setup that MoveIt sees as a chain (servo's Jacobian needs one:
    RobotState::getJacobian fails on any other group, humble robot_state.cpp l.1298-1302);
    Jazzy's servo takes its frames from the group's IK solver (servo.cpp l.403-432)."""
    if servo.group not in by_name:
        hint = did_you_mean(servo.group, by_name)
        raise _fail(with_hint(f"unknown group '{servo.group}'", hint), path, f"{where}.group")
    if not is_chain(by_name[servo.group], by_name, robot, model.passive_joints):
        raise _fail(
            f"group '{servo.group}' is not a chain: servo's Jacobian (RobotState::getJacobian) needs one",
            path,
            f"{where}.group",
        )
    if model.row.servo_needs_kinematics and servo.group not in {k.group for k in model.kinematics}:
        raise _fail(
            f"group '{servo.group}' has no IK solver (kinematics): {model.distro.capitalize()}'s servo takes its planning "
            "and end-effector frames from it",
            path,
            f"{where}.group",
        )


def _check_frames(robot: RobotModel, servo: Servo, path: str | None, where: str) -> None:
    """Every frame a link of the robot (moveit_servo looks each up with getGlobalLinkTransform)."""
    for key in ("planning_frame", "ee_frame", "command_frame"):
        frame = getattr(servo, key)
        if frame is not None and frame not in robot.link_map:
            hint = did_you_mean(frame, robot.link_map)
            message = f"'{frame}' is not a link of the robot: moveit_servo computes its transform from the robot model"
            raise _fail(with_hint(message, hint), path, f"{where}.{key}")


def _check_trajectory_output(
    model: SetupModel, robot: RobotModel, group: Group, servo: Servo, path: str | None, where: str
) -> None:
    """The output reaches a FollowJointTrajectory controller that owns exactly the group's joints."""
    joints = set(active_group_joints(group, groups_by_name(model.groups), robot, model.passive_joints))
    if servo.controller is None:
        if trajectory_controller(model, robot, group) is None:
            raise _fail(
                f"no FollowJointTrajectory controller drives exactly the joints of group '{group.name}': "
                "servo's output would reach no controller (add one, or name one with servo[].controller)",
                path,
                f"{where}.controller",
            )
        return
    by_name = {c.name: c for c in model.controllers}
    controller = by_name.get(servo.controller)
    if controller is None:
        hint = did_you_mean(servo.controller, by_name)
        raise _fail(with_hint(f"unknown controller '{servo.controller}'", hint), path, f"{where}.controller")
    if controller.type != FOLLOW_JOINT_TRAJECTORY:
        raise _fail(
            f"'{controller.name}' is a {controller.type} controller: servo publishes a joint trajectory",
            path,
            f"{where}.controller",
        )
    if set(controller.joints) != joints:
        raise _fail(
            f"'{controller.name}' drives {', '.join(controller.joints)}, not the joints of group "
            f"'{group.name}' ({', '.join(sorted(joints))}): its trajectory controller would reject servo's commands",
            path,
            f"{where}.controller",
        )


def _check_position_output(
    model: SetupModel, servo: Servo, forward: set[str], path: str | None, where: str
) -> None:
    """A forward position controller exists only in ros2_control, claims position commands, and
    has a name of its own (added to `forward`)."""
    if model.target != Target.ROS2:
        raise _fail(
            "a forward position controller is a ros2_control one: a ros1 package has none "
            "(use command_out: trajectory)",
            path,
            f"{where}.command_out",
        )
    interfaces = model.ros2_control.command_interfaces if model.ros2_control else ("position",)
    if "position" not in interfaces:
        raise _fail(
            "the hardware has no 'position' command interface for the forward position controller",
            path,
            f"{where}.command_out",
        )
    name = servo.controller or forward_controller_name(servo.group)
    if name in {c.name for c in model.controllers} | forward | {"joint_state_broadcaster"}:
        raise _fail(f"'{name}' already names another controller", path, f"{where}.controller")
    forward.add(name)


def _check_numbers(servo: Servo, path: str | None, where: str) -> None:
    """Scales and the publish period positive (moveit_servo refuses a period <= 0)."""
    values = {
        "publish_period": servo.publish_period,
        "scale.linear": servo.scale.linear,
        "scale.rotational": servo.scale.rotational,
        "scale.joint": servo.scale.joint,
    }
    for key, value in values.items():
        if value is not None and value <= 0:
            raise _fail(f"must be > 0, got {value:g}", path, f"{where}.{key}")
