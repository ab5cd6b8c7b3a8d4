"""Controllers: MoveIt's controller list vs the robot, the groups, and the driver side.

Driver sides understood: ROS 2 `ros2_controllers.yaml` (controller_manager), ROS 1 ros_control
`ros_controllers.yaml`, ArbotiX `arbotix.yaml` plus the `gripper_controller` node in launch XML,
and MoveIt 1's `fake_controllers.yaml`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from marm_setup.findings import Finding, error, warning
from marm_setup.robot.model import RobotModel
from marm_setup.setup.domain import (
    ARBOTIX_GRIPPER_ACTION_NS,
    DRIVER_CONTROLLERS,
    FOLLOW_JOINT_TRAJECTORY,
    FOLLOW_JOINT_TRAJECTORY_NS,
    GRIPPER_CMD_NS,
    GRIPPER_COMMAND,
    JOINT_DRIVER_CONTROLLERS,
    MOVEIT_CONTROLLER_TYPES,
)
from marm_setup.setup.groups import active_group_joints, groups_by_name
from marm_setup.validate.rules.controller_selection import select_controllers

if TYPE_CHECKING:
    from marm_setup.setup.srdf import Srdf
    from marm_setup.validate.discovery import ConfigSection


@dataclass(frozen=True, slots=True)
class MoveItController:
    name: str
    type: str
    action_ns: str | None
    default: bool
    joints: tuple[str, ...]
    element: str

    @property
    def action(self) -> str:
        """The action MoveIt connects to: `name/action_ns`, or `name` when action_ns is empty
        (`getActionName` in moveit_simple_controller_manager's action_based_controller_handle.h);
        an empty name gives `/action_ns`, the ROS-Industrial convention."""
        return f"{self.name}/{self.action_ns}" if self.action_ns else self.name


# MoveIt 1 moveit_simple_controller_manager.cpp (constructor, ~l.75) skips an entry unless it
# has all four keys; `name` may be empty. MoveIt 2's initialize() reads `<name>.action_ns`,
# `<name>.type` and a non-empty `<name>.joints` under `moveit_simple_controller_manager`.
REQUIRED_KEYS = ("name", "joints", "action_ns", "type")
# moveit_fake_controller_manager.cpp (MoveIt 1, constructor): only name and joints.
FAKE_KEYS = ("name", "joints")


def moveit_controllers(
    section: ConfigSection, required: tuple[str, ...] = REQUIRED_KEYS
) -> tuple[list[MoveItController], list[Finding]]:
    """Controllers from a ros1 `controller_list` or a ros2 `controller_names` section, as
    MoveIt's simple controller manager reads them; entries it would skip are findings."""
    data = section.data if isinstance(section.data, dict) else {}
    if isinstance(data.get("controller_list"), list):
        items = [(section.element(f"controller_list[{i}]"), c) for i, c in enumerate(data["controller_list"])]
    elif isinstance(data.get("controller_names"), list):
        names = [str(n) for n in data["controller_names"]]
        items = [(section.element(n), {"name": n, **_mapping(data.get(n))}) for n in names]
    else:
        return [], [
            error(
                "controller.malformed",
                section.file,
                section.element(),
                "no controller_list / controller_names",
            )
        ]
    out, problems = [], []
    for where, entry in items:
        missing = _missing_keys(entry, required)
        if missing:
            problems.append(_skipped(section.file, where, missing))
        else:
            out.append(_controller(entry, where))
    return out, problems


def _missing_keys(entry, required: tuple[str, ...]) -> list[str]:
    if not isinstance(entry, dict):
        return list(required)
    missing = [k for k in required if k not in entry or entry[k] is None]
    if "joints" not in missing and (not isinstance(entry["joints"], list) or not entry["joints"]):
        missing.append("joints")
    return missing


def _skipped(file: str, where: str, missing: list[str]) -> Finding:
    if missing == ["action_ns"]:
        msg = "no action_ns: MoveIt skips this controller (an empty action_ns is allowed)"
        return error(
            "controller.missing-action-ns", file, where, msg, f"add action_ns: {FOLLOW_JOINT_TRAJECTORY_NS}"
        )
    msg = f"MoveIt skips this controller: a key it needs is missing or empty ({', '.join(missing)})"
    return error("controller.malformed", file, where, msg)


def _controller(entry: dict, where: str) -> MoveItController:
    default = entry.get("default", False)
    return MoveItController(
        name=str(entry["name"]),
        type=str(entry.get("type", "")),
        action_ns=None if entry.get("action_ns") is None else str(entry["action_ns"]),
        default=default is True or str(default).lower() == "true",
        joints=tuple(str(j) for j in entry["joints"]),
        element=where,
    )


SIMPLE_MANAGER = "moveit_simple_controller_manager"


def check_ros2_namespace(section: ConfigSection) -> list[Finding]:
    """MoveIt 2: the simple controller manager reads `moveit_simple_controller_manager.controller_names`
    (moveit2 moveit_simple_controller_manager.cpp, `initialize`: PARAM_BASE_NAME prefix, "No
    controller_names specified" otherwise), and MoveItConfigsBuilder.trajectory_execution loads
    the file's keys as they are: top-level `controller_names` give MoveIt no controllers.
    Ros2ControlManager asks ros2_control for its controllers instead and needs no list."""
    data = section.data if isinstance(section.data, dict) else {}
    manager = str(data.get("moveit_controller_manager", ""))
    if section.prefix or "controller_names" not in data or "Ros2ControlManager" in manager:
        return []
    msg = f"controller_names is not under '{SIMPLE_MANAGER}': MoveIt 2 finds no controllers"
    hint = f"indent controller_names and the controllers under '{SIMPLE_MANAGER}:'"
    return [error("controller.no-namespace", section.file, "controller_names", msg, hint)]


# -- MoveIt side -------------------------------------------------------------------------------


def check_moveit_controllers(
    section: ConfigSection, ctrls, robot: RobotModel, real: bool = True
) -> list[Finding]:
    """Joints exist; for real (non-fake) controllers: known type, action_ns present and plausible."""
    out: list[Finding] = []
    for c in ctrls:
        for joint in c.joints:
            if joint not in robot.joint_map:
                out.append(
                    error("controller.unknown-joint", section.file, c.element, f"unknown joint '{joint}'")
                )
        if real:
            out += _check_type(section, c)
    return out


def _check_type(section: ConfigSection, c: MoveItController) -> list[Finding]:
    if c.type not in MOVEIT_CONTROLLER_TYPES:
        msg = f"type '{c.type}' is not one MoveIt's simple controller manager knows ({', '.join(MOVEIT_CONTROLLER_TYPES)})"
        return [error("controller.unknown-type", section.file, c.element, msg)]
    if c.action_ns and _implausible(c.type, c.action_ns):
        msg = f"action_ns '{c.action_ns}' is implausible for a {c.type} controller"
        hint = (
            FOLLOW_JOINT_TRAJECTORY_NS
            if c.type == FOLLOW_JOINT_TRAJECTORY
            else f"{GRIPPER_CMD_NS} (ros2_control) or {ARBOTIX_GRIPPER_ACTION_NS} (ArbotiX)"
        )
        return [warning("controller.action-ns", section.file, c.element, msg, f"usually {hint}")]
    return []


def _implausible(type_: str, action_ns: str) -> bool:
    """A trajectory controller on a gripper namespace, or a gripper on a trajectory namespace."""
    if type_ == FOLLOW_JOINT_TRAJECTORY:
        return "gripper" in action_ns
    return FOLLOW_JOINT_TRAJECTORY_NS in action_ns


def check_coverage(
    section: ConfigSection, ctrls, srdf: Srdf, robot: RobotModel, alternatives=()
) -> list[Finding]:
    """Every active group joint is in some controller, and each group's joints can be executed
    by MoveIt's own controller selection (see `controller_selection`)."""
    out: list[Finding] = []
    covered = {j for c in ctrls for j in c.joints}
    for joint, groups in sorted(_group_joints(srdf, robot).items()):
        if joint not in covered:
            label = f"joint '{joint}' (group {', '.join(groups)})"
            out.append(_uncovered(section, section.element(f"joint[{joint}]"), label, joint, alternatives))
    by_name = groups_by_name(srdf.groups)
    for group in srdf.groups:
        joints = active_group_joints(group, by_name, robot, tuple(srdf.passive_joints))
        if joints and set(joints) <= covered:
            out += _check_selection(section, group.name, joints, ctrls)
    return out


def _check_selection(section: ConfigSection, group: str, joints, ctrls) -> list[Finding]:
    where = section.element(f"group[{group}]")
    pick = select_controllers(joints, ctrls)
    if pick is None:
        msg = (
            f"no set of controllers without shared joints covers group '{group}': MoveIt cannot "
            "execute its motions ('Unable to identify any set of controllers')"
        )
        return [error("controller.no-combination", section.file, where, msg)]
    if pick.tied:
        options = " or ".join("+".join(repr(n) for n in o) for o in (pick.chosen, *pick.tied))
        msg = (
            f"MoveIt picks arbitrarily between {options} for group '{group}' (same defaults and joint count)"
        )
        hint = "set default: true on the one to use"
        return [warning("controller.ambiguous", section.file, where, msg, hint)]
    return []


def _uncovered(section: ConfigSection, where, label, joint, alternatives) -> Finding:
    for alt in alternatives:
        ctrls, _ = moveit_controllers(alt)
        if any(joint in c.joints for c in ctrls):
            msg = f"{label} has no controller here; only {alt.file} covers it"
            return warning(
                "controller.uncovered-joint",
                section.file,
                where,
                msg,
                f"launch with {alt.file} to execute it",
            )
    msg = f"{label} has no controller: MoveIt cannot execute motions of it"
    return error("controller.uncovered-joint", section.file, where, msg, "add it to a controller's joints")


def _group_joints(srdf: Srdf, robot: RobotModel) -> dict[str, list[str]]:
    by_name = groups_by_name(srdf.groups)
    out: dict[str, list[str]] = {}
    for group in srdf.groups:
        for joint in active_group_joints(group, by_name, robot, tuple(srdf.passive_joints)):
            out.setdefault(joint, []).append(group.name)
    return out


# -- driver side: ros2_control / ros_control ---------------------------------------------------------


def ros2_driver_controllers(section: ConfigSection) -> dict[str, tuple[str, tuple[str, ...] | None, str]]:
    """name -> (type, joints or None, element) from a ros2_controllers.yaml."""
    data = section.data if isinstance(section.data, dict) else {}
    manager = _mapping(_mapping(data.get("controller_manager")).get("ros__parameters"))
    out = {}
    for name, entry in manager.items():
        if isinstance(entry, dict) and "type" in entry:
            params = _mapping(_mapping(data.get(name)).get("ros__parameters"))
            out[name] = (
                str(entry["type"]),
                _driver_joints(params),
                f"controller_manager.ros__parameters.{name}",
            )
    return out


def ros1_driver_controllers(section: ConfigSection) -> dict[str, tuple[str, tuple[str, ...] | None, str]]:
    """name -> (type, joints or None, element) from a ros_control ros_controllers.yaml."""
    data = section.data if isinstance(section.data, dict) else {}
    return {
        name: (str(entry["type"]), _driver_joints(entry), name)
        for name, entry in data.items()
        if isinstance(entry, dict) and "type" in entry
    }


def _mapping(value) -> dict:
    """`value` when it is a mapping, else an empty one (malformed YAML reads as absent)."""
    return value if isinstance(value, dict) else {}


def _driver_joints(params: dict) -> tuple[str, ...] | None:
    if isinstance(params.get("joints"), list):
        return tuple(str(j) for j in params["joints"])
    if params.get("joint"):
        return (str(params["joint"]),)
    return None


def check_driver_controllers(
    moveit_section: ConfigSection, section: ConfigSection, driver, ctrls, robot: RobotModel
) -> list[Finding]:
    """MoveIt's controllers exist in the driver file with a matching type, joints and action."""
    if not driver:
        return [
            error(
                "controller.driver-malformed", section.file, "", "no controllers (entries with a type) found"
            )
        ]
    out: list[Finding] = []
    for _name, (dtype, joints, where) in sorted(driver.items()):
        if dtype.rsplit("/", 1)[-1] not in JOINT_DRIVER_CONTROLLERS:
            continue  # e.g. a twist controller's `joint` names a Cartesian frame, not a URDF joint
        for joint in joints or ():
            if joint not in robot.joint_map:
                out.append(error("controller.unknown-joint", section.file, where, f"unknown joint '{joint}'"))
    for c in ctrls:
        out += _check_against_driver(moveit_section, section, driver, c)
    return out


def _check_against_driver(
    moveit_section: ConfigSection, section: ConfigSection, driver, c: MoveItController
) -> list[Finding]:
    file = section.file
    if c.name not in driver:
        known = ", ".join(sorted(driver)) or "none"
        msg = f"controller '{c.name}' is not in {file} (has: {known})"
        return [error("controller.driver-missing", moveit_section.file, c.element, msg)]
    dtype, djoints, where = driver[c.name]
    suffix = dtype.rsplit("/", 1)[-1]
    if suffix not in DRIVER_CONTROLLERS:
        return []  # a driver type we do not know: no claim either way
    expected_type, served_ns = DRIVER_CONTROLLERS[suffix]
    out = []
    if c.type in MOVEIT_CONTROLLER_TYPES and c.type != expected_type:
        msg = f"MoveIt expects a {c.type} action but '{c.name}' is a {dtype}"
        out.append(error("controller.driver-type", file, where, msg))
    elif c.action != f"{c.name}/{served_ns}":
        msg = f"{dtype} serves '{c.name}/{served_ns}', MoveIt connects to '{c.action}'"
        out.append(error("controller.driver-action", file, where, msg, f"set action_ns: {served_ns}"))
    if djoints is None:
        msg = f"'{c.name}' names no joints ({dtype} needs them; MoveIt's has {list(c.joints)})"
        out.append(error("controller.driver-joints", file, where, msg))
    elif set(djoints) != set(c.joints):
        msg = f"joints {list(djoints)} differ from MoveIt's {list(c.joints)} for '{c.name}'"
        out.append(error("controller.driver-joints", file, where, msg))
    return out


# -- driver side: ArbotiX ----------------------------------------------------------------------------


def check_arbotix(
    section: ConfigSection, ctrls, robot: RobotModel, gripper_nodes: dict[str, tuple[str, str]]
) -> list[Finding]:
    """arbotix.yaml joints exist; FollowJointTrajectory controllers match `controllers` by
    name, action_name and joints; GripperCommand controllers match a gripper_controller node."""
    data = section.data if isinstance(section.data, dict) else {}
    out: list[Finding] = []
    for joint in sorted(str(j) for j in _mapping(data.get("joints"))):
        if joint not in robot.joint_map:
            out.append(
                error("controller.unknown-joint", section.file, f"joints.{joint}", f"unknown joint '{joint}'")
            )
    drivers = _mapping(data.get("controllers"))
    for c in ctrls:
        if c.type == GRIPPER_COMMAND:
            out += _check_gripper_node(section, c, gripper_nodes)
        elif c.type == FOLLOW_JOINT_TRAJECTORY:
            out += _check_arbotix_follow(section, c, drivers)
    return out


def _check_arbotix_follow(section: ConfigSection, c: MoveItController, drivers: dict) -> list[Finding]:
    entry = drivers.get(c.name)
    where = f"controllers.{c.name}"
    if not isinstance(entry, dict):
        known = ", ".join(sorted(drivers)) or "none"
        return [
            error(
                "controller.driver-missing",
                section.file,
                "controllers",
                f"no ArbotiX controller '{c.name}' (has: {known})",
            )
        ]
    out = []
    action = entry.get("action_name", FOLLOW_JOINT_TRAJECTORY_NS)
    expected = c.action
    if action != expected:
        msg = f"action_name '{action}' differs from MoveIt's '{expected}'"
        out.append(
            error(
                "controller.driver-action",
                section.file,
                f"{where}.action_name",
                msg,
                f"set action_name: {expected}",
            )
        )
    joints = entry.get("joints")
    if isinstance(joints, list) and set(map(str, joints)) != set(c.joints):
        msg = f"joints {joints} differ from MoveIt's {list(c.joints)}"
        out.append(error("controller.driver-joints", section.file, f"{where}.joints", msg))
    return out


def _check_gripper_node(
    section: ConfigSection, c: MoveItController, nodes: dict[str, tuple[str, str]]
) -> list[Finding]:
    """`nodes`: gripper_controller node name -> (launch file, its `joint` param)."""
    if c.name not in nodes:
        known = ", ".join(sorted(nodes)) or "none"
        msg = f"no gripper_controller node named '{c.name}' in the launch files (found: {known})"
        return [error("controller.driver-missing", section.file, "controllers", msg)]
    launch, joint = nodes[c.name]
    if joint and joint not in c.joints:
        msg = (
            f"gripper_controller '{c.name}' drives joint '{joint}', MoveIt's controller has {list(c.joints)}"
        )
        return [error("controller.gripper-joint", launch, f"node[{c.name}]", msg)]
    return []


# -- fake controllers (MoveIt 1) ----------------------------------------------------------------------


def check_fake_controllers(section: ConfigSection, srdf: Srdf, robot: RobotModel) -> list[Finding]:
    """Joints exist, every group's active joints are covered, `initial` poses exist."""
    ctrls, out = moveit_controllers(section, FAKE_KEYS)
    out += check_moveit_controllers(section, ctrls, robot, real=False)
    covered = {j for c in ctrls for j in c.joints}
    for joint, groups in sorted(_group_joints(srdf, robot).items()):
        if joint not in covered:
            msg = f"joint '{joint}' (group {', '.join(groups)}) is in no fake controller"
            out.append(
                error("controller.fake-uncovered", section.file, section.element(f"joint[{joint}]"), msg)
            )
    out += _check_initial(section, srdf)
    return out


def _check_initial(section: ConfigSection, srdf: Srdf) -> list[Finding]:
    data = section.data if isinstance(section.data, dict) else {}
    groups = {g.name for g in srdf.groups}
    states = {(s.group, s.name) for s in srdf.group_states}
    out = []
    initial = data.get("initial")
    if initial is not None and not isinstance(initial, list):
        return [
            error("controller.fake-initial-pose", section.file, section.element("initial"), "expected a list")
        ]
    for i, item in enumerate(initial or []):
        where = section.element(f"initial[{i}]")
        item = _mapping(item)
        group, pose = str(item.get("group")), str(item.get("pose"))
        if group not in groups:
            out.append(error("controller.fake-initial-pose", section.file, where, f"unknown group '{group}'"))
        elif (group, pose) not in states:
            out.append(
                error(
                    "controller.fake-initial-pose",
                    section.file,
                    where,
                    f"group '{group}' has no pose '{pose}'",
                )
            )
    return out
