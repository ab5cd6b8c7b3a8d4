"""Porting the controller wiring: MoveIt's controller list (ros1 `controller_list`, ros2
`controller_names`) and the driver side (ros_control `ros_controllers.yaml`, ros2_control
`ros2_controllers.yaml`, ArbotiX `arbotix.yaml`), read with validate's own readers."""

from __future__ import annotations

import dataclasses
import math
from typing import Any

from marm_setup.bounded_read import YAML_BYTES, FileTooLarge, read_text
from marm_setup.port.report import PortLog, where
from marm_setup.robot.model import RobotModel
from marm_setup.safe_yaml import load_yaml
from marm_setup.setup.domain import (
    DRIVER_ACTION_NS,
    DRIVER_CONTROLLERS,
    FOLLOW_JOINT_TRAJECTORY,
    FOLLOW_JOINT_TRAJECTORY_NS,
    GRIPPER_COMMAND,
    MOVEIT_CONTROLLER_TYPES,
    ROS2_CONTROLLER_TYPES,
)
from marm_setup.setup.groups import active_group_joints, groups_by_name
from marm_setup.setup.model import ArbotixJoint, Controller, SetupModel
from marm_setup.validate.discovery import ConfigPackage, ConfigSection
from marm_setup.validate.rules.controller_rules import (
    MoveItController,
    moveit_controllers,
    ros1_driver_controllers,
    ros2_driver_controllers,
)

# What the new package's driver side is, per SetupModel.driver_key (ros2_control, the ros1
# driver, or none: a ros1 package without driver files).
TARGET_DRIVER = {
    "ros2": "ros2_controllers.yaml (ros2_control, mock_components/GenericSystem hardware)",
    "arbotix": "arbotix.yaml (ArbotiX driver)",
    None: "your driver's configuration (the new ros1 package writes no driver files)",
}
TARGET_DRIVER_TYPES = {
    **{("ros2", kind): plugin for kind, plugin in ROS2_CONTROLLER_TYPES.items()},
    ("arbotix", FOLLOW_JOINT_TRAJECTORY): "ArbotiX follow_controller",
    ("arbotix", GRIPPER_COMMAND): "arbotix_controllers gripper_controller node",
}
STATE_PUBLISHERS = ("JointStateBroadcaster", "JointStateController")


def port_controllers(
    pkg: ConfigPackage, model: SetupModel, robot: RobotModel, log: PortLog
) -> tuple[Controller, ...]:
    """MoveIt's controllers, fitted to the target's driver; every entry reported."""
    section = pkg.moveit_controllers
    if section is None:
        log.changed(
            "controllers", "", "no MoveIt controller list: one controller per group is written, as init does"
        )
        return ()
    out: list[Controller] = []
    for i, sec in enumerate((section, *pkg.alt_moveit_controllers)):
        _report_manager_settings(pkg, sec, log)
        found, problems = moveit_controllers(sec)
        for f in problems:
            log.dropped(f"controllers ({f.element})", where(f.file, f.element), f.message)
        for c in found:
            if i and any(o.name == c.name and set(o.joints) == set(c.joints) for o in out):
                log.carried(
                    f"controllers[{c.name}]", where(sec.file, c.element), "the same as in " + section.file
                )
                continue
            ported = _controller(c, sec.file, model, robot, {o.name for o in out}, log)
            if ported is not None:
                out.append(ported)
                if i:
                    log.changed(
                        f"controllers[{c.name}]",
                        where(sec.file, c.element),
                        f"from an alternative controller file the source launches instead of {section.file}: "
                        "the new package has one set holding both",
                    )
    return tuple(out)


# Keys of a MoveIt controllers file the port reads (the rest is the target's own settings).
CONTROLLER_LIST_KEYS = ("controller_list", "controller_names", "moveit_simple_controller_manager")


def _report_manager_settings(pkg: ConfigPackage, section: ConfigSection, log: PortLog) -> None:
    """Other keys of the controllers file (trajectory_execution, the manager plugin, ...): the
    new package writes its own."""
    import yaml

    try:
        raw = load_yaml(read_text(pkg.path(section.file), YAML_BYTES))
    except (OSError, UnicodeDecodeError, yaml.YAMLError, FileTooLarge):
        return
    if (
        not isinstance(raw, dict)
        or (raw.keys() & {"controller_list", "moveit_simple_controller_manager"}) == set()
    ):
        return
    for key in sorted(set(raw) - set(CONTROLLER_LIST_KEYS), key=str):
        log.changed(
            f"moveit_controllers file: {key}",
            where(section.file, str(key)),
            "the new package writes its own value",
        )


def _controller(
    c: MoveItController, file: str, model: SetupModel, robot: RobotModel, taken: set[str], log: PortLog
) -> Controller | None:
    src = where(file, c.element)
    setting = f"controllers[{c.name}]"
    if c.type not in MOVEIT_CONTROLLER_TYPES:
        log.dropped(
            setting,
            src,
            f"type {c.type}: marm-setup writes {' and '.join(MOVEIT_CONTROLLER_TYPES)} controllers only",
        )
        return None
    joints = tuple(j for j in c.joints if _commandable(robot, j))
    for j in sorted(set(c.joints) - set(joints)):
        log.dropped(
            f"{setting}.joints[{j}]", src, "not an actuated, non-mimic joint of the URDF: nothing to command"
        )
    if not joints:
        log.dropped(setting, src, "no joint left to command")
        return None
    group = _group_of(joints, model, robot)
    name = c.name or f"{group or 'robot'}_controller"
    if name in taken:
        log.dropped(setting, src, f"a second controller named {name!r}")
        return None
    if name != c.name:
        log.changed(
            f"{setting}.name", src, f"an empty name is renamed {name!r}: the target's driver needs a name"
        )
    kind = _kind(c.type, joints, model.target, setting, src, log)
    action_ns = _action_ns(c, kind, model.driver_key, setting, src, log)
    log.carried(setting, src, f"{kind} on {', '.join(joints)} (default: {str(c.default).lower()})")
    return Controller(name, kind, action_ns, joints, group, c.default)


def _kind(kind: str, joints: tuple[str, ...], target: str, setting: str, src: str, log: PortLog) -> str:
    """ros2_control's GripperActionController drives one joint (`joint`): a GripperCommand
    controller of several joints becomes a JointTrajectoryController over all of them."""
    if target == "ros2" and kind == GRIPPER_COMMAND and len(joints) > 1:
        log.changed(
            f"{setting}.type",
            src,
            f"GripperCommand -> FollowJointTrajectory: ros2_control's GripperActionController drives one joint, "
            f"a JointTrajectoryController drives all {len(joints)}",
        )
        return FOLLOW_JOINT_TRAJECTORY
    return kind


def _commandable(robot: RobotModel, joint: str) -> bool:
    j = robot.joint_map.get(joint)
    return j is not None and j.is_actuated and j.mimic is None


def _group_of(joints: tuple[str, ...], model: SetupModel, robot: RobotModel) -> str | None:
    """The first group whose active joints are exactly the controller's (or hold them all)."""
    by_name = groups_by_name(model.groups)
    active = {g.name: set(active_group_joints(g, by_name, robot, model.passive_joints)) for g in model.groups}
    return next((g for g, js in active.items() if js == set(joints)), None)


def _action_ns(
    c: MoveItController, kind: str, driver: str | None, setting: str, src: str, log: PortLog
) -> str:
    served = DRIVER_ACTION_NS.get((driver, kind)) if driver else None
    if served is not None and c.action_ns != served:
        log.changed(
            f"{setting}.action_ns",
            src,
            f"{c.action_ns!r} -> {served!r}: the {driver} driver's {kind} controller serves <name>/{served}",
        )
        return served
    if not c.action_ns:
        log.changed(
            f"{setting}.action_ns",
            src,
            f"empty -> '{FOLLOW_JOINT_TRAJECTORY_NS}' (the new package's controllers need a name/namespace)",
        )
        return FOLLOW_JOINT_TRAJECTORY_NS
    return c.action_ns


# -- driver side ---------------------------------------------------------------------------------


def report_shared_joints(controllers: tuple[Controller, ...], target: str, log: PortLog) -> None:
    """ros2_control lends each command interface to one active controller (hardware_interface
    resource_manager.hpp `command_interface_is_claimed`: "Any command interface can only be claimed
    by a single instance"; controller_manager.cpp refuses to activate a controller whose interface
    is claimed, "Resource conflict"): controllers that share joints cannot all be active."""
    if target != "ros2":
        return
    for i, a in enumerate(controllers):
        for b in controllers[i + 1 :]:
            shared = [j for j in a.joints if j in b.joints]
            if shared:
                log.todo(
                    f"controllers[{a.name}], controllers[{b.name}]",
                    "",
                    f"share {', '.join(shared)}: ros2_control activates one controller per joint, so the demo's "
                    "spawners cannot activate both; spawn one --inactive and switch controllers as needed",
                )


def report_driver(
    pkg: ConfigPackage, controllers: tuple[Controller, ...], driver: str | None, log: PortLog
) -> None:
    """What becomes of the source driver's controllers (ros_control / ros2_control)."""
    by_name = {c.name: c for c in controllers}
    for section, reader in (
        (pkg.ros2_controllers, ros2_driver_controllers),
        (pkg.ros_controllers, ros1_driver_controllers),
    ):
        if section is None:
            continue
        for name, (kind, _, element) in reader(section).items():
            src = where(section.file, element)
            _driver_item(name, kind, by_name.get(name), driver, src, section, log)


def _driver_item(
    name: str,
    kind: str,
    ours: Controller | None,
    driver: str | None,
    src: str,
    section: ConfigSection,
    log: PortLog,
) -> None:
    setting = f"driver.{name}"
    suffix = kind.rpartition("/")[2]
    if suffix in STATE_PUBLISHERS:
        log.carried(setting, src, f"{kind}: the new package publishes joint states its own way")
        return
    if ours is None:
        log.dropped(
            setting,
            src,
            f"{kind}: no MoveIt controller of that name uses it; add it to {TARGET_DRIVER[driver]} by hand",
        )
        return
    new = TARGET_DRIVER_TYPES.get((driver, ours.type)) if driver else None
    if new is None:
        log.todo(setting, src, f"{kind}: keep it in {TARGET_DRIVER[driver]}")
        return
    if kind == new:
        log.carried(setting, src, kind)
    else:
        log.changed(setting, src, f"{kind} -> {new} in {TARGET_DRIVER[driver]}")
    params = _driver_params(section, name)
    if params:
        log.todo(
            f"{setting} parameters",
            src,
            f"{', '.join(params)}: not carried (the new driver file has its own); set gains/tolerances on the real hardware by hand",
        )
    if suffix not in DRIVER_CONTROLLERS and kind != new:
        log.todo(setting, src, f"{kind} is not a trajectory or gripper action controller: check {new} fits")


def _driver_params(section: ConfigSection, name: str) -> list[str]:
    data = section.data if isinstance(section.data, dict) else {}
    entry = data.get(name) if isinstance(data.get(name), dict) else {}
    entry = entry.get("ros__parameters", entry) if isinstance(entry, dict) else {}
    return sorted(str(k) for k in entry if k not in ("type", "joints", "joint"))


# -- ArbotiX ---------------------------------------------------------------------------------------


def port_arbotix(
    pkg: ConfigPackage, robot: RobotModel, target: str, log: PortLog
) -> tuple[ArbotixJoint, ...]:
    """Servo ids and speeds of `arbotix.yaml` (ros1 only); the rest of the file reported."""
    section = pkg.arbotix
    if section is None:
        return ()
    data = section.data if isinstance(section.data, dict) else {}
    if target != "ros1":
        log.dropped(
            "arbotix",
            section.file,
            "ROS 2 has no ArbotiX driver: the new package drives ros2_control mock hardware; "
            "write your hardware interface by hand",
        )
        return ()
    out = []
    joints = data["joints"] if isinstance(data.get("joints"), dict) else {}
    for joint, entry in joints.items():
        src = where(section.file, section.element("joints", joint))
        servo = _servo(str(joint), entry, robot, src, log)
        if servo is not None:
            out.append(servo)
    for key in sorted(k for k in data if k not in ("joints", "controllers")):
        log.changed(
            f"arbotix.{key}", where(section.file, key), f"{data[key]!r}: the template's value is written"
        )
    return tuple(out)


def _servo(joint: str, entry: Any, robot: RobotModel, src: str, log: PortLog) -> ArbotixJoint | None:
    entry = entry if isinstance(entry, dict) else {}
    servo_id = entry.get("id")
    if joint not in robot.joint_map or not isinstance(servo_id, int) or isinstance(servo_id, bool):
        log.dropped(f"arbotix_joints[{joint}]", src, "not a URDF joint with an integer servo id")
        return None
    speed = entry.get("max_speed")
    speed = float(speed) if isinstance(speed, int | float) and not isinstance(speed, bool) else None
    derived = robot.joint(joint).velocity
    if speed is not None and derived and math.isclose(speed, round(math.degrees(derived), 3), abs_tol=1e-3):
        speed = None  # the URDF's velocity, which the template writes anyway
    log.carried(f"arbotix_joints[{joint}]", src, f"id {servo_id}" + (f", max_speed {speed}" if speed else ""))
    for key in sorted(k for k in entry if k not in ("id", "max_speed", "min_angle", "max_angle")):
        log.dropped(
            f"arbotix_joints[{joint}].{key}", src, f"{entry[key]!r}: marm_setup.yaml has no place for it"
        )
    return ArbotixJoint(joint, servo_id, speed)


def with_controllers(model: SetupModel, controllers: tuple[Controller, ...]) -> SetupModel:
    return dataclasses.replace(model, controllers=controllers)
