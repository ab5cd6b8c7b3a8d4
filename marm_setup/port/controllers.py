"""Porting the controller wiring: MoveIt's controller list (ros1 `controller_list`, ros2
`controller_names`) and the driver side (ros_control `ros_controllers.yaml`, ros2_control
`ros2_controllers.yaml`, ArbotiX `arbotix.yaml`), as the package model reads them."""

from __future__ import annotations

import math

from marm_setup.moveit_params import (
    DRIVER_ACTION_NS,
    DRIVER_CONTROLLERS,
    FOLLOW_JOINT_TRAJECTORY,
    FOLLOW_JOINT_TRAJECTORY_NS,
    GRIPPER_COMMAND,
    MOVEIT_CONTROLLER_TYPES,
    ROS2_CONTROLLER_TYPES,
)
from marm_setup.package import (
    ArbotixFile,
    ArbotixServo,
    ControllersFile,
    DriverController,
    MoveItController,
    MoveItPackage,
    SkippedController,
)
from marm_setup.port.port_log import PortLog
from marm_setup.robot import RobotModel
from marm_setup.ros import Target
from marm_setup.setup import ArbotixJoint, Controller, SetupModel, active_group_joints, groups_by_name

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
    pkg: MoveItPackage, model: SetupModel, robot: RobotModel, log: PortLog
) -> tuple[Controller, ...]:
    """MoveIt's controllers, fitted to the target's driver; every entry reported."""
    moveit = pkg.managed_controllers
    if moveit is None:
        detail = "no MoveIt controller list: one controller per group is written, as init does"
        log.changed("controllers", "", detail, "controllers")
        return ()
    if moveit is not pkg.moveit_controllers:
        names = ", ".join(c.name for c in moveit.controllers) or "none"
        detail = (
            f"{moveit.manager} takes ros2_control's controllers ({names}): "
            "the new package lists them for moveit_simple_controller_manager"
        )
        log.changed("controllers", moveit.where, detail, "controllers")
    out: list[Controller] = []
    merged = pkg.alt_moveit_controllers if pkg.target == Target.ROS2 else ()
    for i, listed in enumerate((moveit, *merged)):
        _report_manager_settings(listed, log)
        for skipped in listed.skipped:
            log.dropped(
                f"controllers ({skipped.where.element})", skipped.where, skipped_text(skipped), "controllers"
            )
        for c in listed.controllers:
            if i and any(o.name == c.name and set(o.joints) == set(c.joints) for o in out):
                log.carried(
                    f"controllers[{c.name}]", c.where, "the same as in " + moveit.where.file, "controllers"
                )
                continue
            ported = _controller(c, model, robot, {o.name for o in out}, log)
            if ported is not None:
                out.append(ported)
                if i:
                    detail = (
                        f"from an alternative controller file the source launches instead of {moveit.where.file}: "
                        "the new package has one set holding both"
                    )
                    log.changed(f"controllers[{c.name}]", c.where, detail, "controllers")
    if pkg.target == Target.ROS1:
        _report_conditional(pkg, out, log)
    return tuple(out)


def _report_conditional(pkg: MoveItPackage, ours: list[Controller], log: PortLog) -> None:
    """MoveIt 1: controller lists the launch files load only on a branch their args' defaults do
    not take (`gazebo_sim:=true`, ...): not carried, each said."""
    for listed in pkg.alt_moveit_controllers:
        for c in listed.controllers:
            if any(o.name == c.name and set(o.joints) == set(c.joints) for o in ours):
                continue
            detail = (
                f"{c.type} on {', '.join(c.joints)}: {listed.where.file} is loaded only with launch args other "
                "than their defaults; not carried (add it by hand if you launch that way)"
            )
            log.dropped(f"controllers[{c.name}]", c.where, detail, "controllers")


def skipped_text(skipped: SkippedController) -> str:
    if skipped.missing == ("action_ns",):
        return "no action_ns: MoveIt skips this controller (an empty action_ns is allowed)"
    return f"MoveIt skips this controller: a key it needs is missing or empty ({', '.join(skipped.missing)})"


def _report_manager_settings(listed: ControllersFile, log: PortLog) -> None:
    """Other keys of the controllers file (trajectory_execution, the manager plugin, ...): the
    new package writes its own."""
    if listed.form != "controller_list" and not listed.namespaced:
        return
    for key in dict.fromkeys(p.key.split(".")[0] for p in listed.settings):
        source = f"{listed.where.file}: {key}"
        log.changed(
            f"moveit_controllers file: {key}", source, "the new package writes its own value", "controllers"
        )


def _controller(
    c: MoveItController, model: SetupModel, robot: RobotModel, taken: set[str], log: PortLog
) -> Controller | None:
    src, setting, area = str(c.where), f"controllers[{c.name}]", "controllers"
    if c.type not in MOVEIT_CONTROLLER_TYPES:
        detail = f"type {c.type}: marm-setup writes {' and '.join(MOVEIT_CONTROLLER_TYPES)} controllers only"
        log.dropped(setting, src, detail, area)
        return None
    joints = tuple(j for j in c.joints if _commandable(robot, j))
    for j in sorted(set(c.joints) - set(joints)):
        log.dropped(
            f"{setting}.joints[{j}]",
            src,
            "not an actuated, non-mimic joint of the URDF: nothing to command",
            area,
        )
    if not joints:
        log.dropped(setting, src, "no joint left to command", area)
        return None
    group = _group_of(joints, model, robot)
    name = c.name or f"{group or 'robot'}_controller"
    if name in taken:
        log.dropped(setting, src, f"a second controller named {name!r}", area)
        return None
    if name != c.name:
        log.changed(
            f"{setting}.name",
            src,
            f"an empty name is renamed {name!r}: the target's driver needs a name",
            area,
        )
    kind = _kind(c.type, joints, model.target, setting, src, log)
    action_ns = _action_ns(c, kind, model.driver_key, setting, src, log)
    log.carried(setting, src, f"{kind} on {', '.join(joints)} (default: {str(c.default).lower()})", area)
    return Controller(name, kind, action_ns, joints, group, c.default)


def _kind(kind: str, joints: tuple[str, ...], target: Target, setting: str, src: str, log: PortLog) -> str:
    """ros2_control's GripperActionController drives one joint (`joint`): a GripperCommand
    controller of several joints becomes a JointTrajectoryController over all of them."""
    if target == Target.ROS2 and kind == GRIPPER_COMMAND and len(joints) > 1:
        detail = (
            f"GripperCommand -> FollowJointTrajectory: ros2_control's GripperActionController drives one joint, "
            f"a JointTrajectoryController drives all {len(joints)}"
        )
        log.changed(f"{setting}.type", src, detail, "controllers")
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
        detail = (
            f"{c.action_ns!r} -> {served!r}: the {driver} driver's {kind} controller serves <name>/{served}"
        )
        log.changed(f"{setting}.action_ns", src, detail, "controllers")
        return served
    if not c.action_ns:
        detail = (
            f"empty -> '{FOLLOW_JOINT_TRAJECTORY_NS}' (the new package's controllers need a name/namespace)"
        )
        log.changed(f"{setting}.action_ns", src, detail, "controllers")
        return FOLLOW_JOINT_TRAJECTORY_NS
    return c.action_ns


# -- driver side ---------------------------------------------------------------------------------


def report_shared_joints(controllers: tuple[Controller, ...], target: Target, log: PortLog) -> None:
    """ros2_control lends each command interface to one active controller (hardware_interface
    resource_manager.hpp `command_interface_is_claimed`: "Any command interface can only be claimed
    by a single instance"; controller_manager.cpp refuses to activate a controller whose interface
    is claimed, "Resource conflict"): controllers that share joints cannot all be active."""
    if target != Target.ROS2:
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
                    "controllers",
                )


def report_driver(
    pkg: MoveItPackage, controllers: tuple[Controller, ...], driver: str | None, log: PortLog
) -> None:
    """What becomes of the source driver's controllers (ros_control / ros2_control)."""
    by_name = {c.name: c for c in controllers}
    for found in (pkg.ros2_controllers, pkg.ros_controllers):
        for d in found.controllers if found is not None else ():
            _driver_item(d, by_name.get(d.name), driver, log)


def _driver_item(d: DriverController, ours: Controller | None, driver: str | None, log: PortLog) -> None:
    setting, src, kind = f"driver.{d.name}", str(d.where), d.type
    suffix = kind.rpartition("/")[2]
    if suffix in STATE_PUBLISHERS:
        log.carried(setting, src, f"{kind}: the new package publishes joint states its own way", "driver")
        return
    if ours is None:
        detail = (
            f"{kind}: no MoveIt controller of that name uses it; add it to {TARGET_DRIVER[driver]} by hand"
        )
        log.dropped(setting, src, detail, "driver")
        return
    new = TARGET_DRIVER_TYPES.get((driver, ours.type)) if driver else None
    if new is None:
        log.todo(setting, src, f"{kind}: keep it in {TARGET_DRIVER[driver]}", "driver")
        return
    if kind == new:
        log.carried(setting, src, kind, "driver")
    else:
        log.changed(setting, src, f"{kind} -> {new} in {TARGET_DRIVER[driver]}", "driver")
    if d.parameters:
        detail = (
            f"{', '.join(d.parameters)}: not carried (the new driver file has its own); "
            "set gains/tolerances on the real hardware by hand"
        )
        log.todo(f"{setting} parameters", src, detail, "driver")
    if suffix not in DRIVER_CONTROLLERS and kind != new:
        log.todo(
            setting,
            src,
            f"{kind} is not a trajectory or gripper action controller: check {new} fits",
            "driver",
        )


# -- ArbotiX ---------------------------------------------------------------------------------------


def port_arbotix(
    pkg: MoveItPackage, robot: RobotModel, target: Target, log: PortLog
) -> tuple[ArbotixJoint, ...]:
    """Servo ids and speeds of `arbotix.yaml` (ros1 only); the rest of the file reported."""
    arbotix: ArbotixFile | None = pkg.arbotix
    if arbotix is None:
        return ()
    if target != Target.ROS1:
        detail = (
            "ROS 2 has no ArbotiX driver: the new package drives ros2_control mock hardware; "
            "write your hardware interface by hand"
        )
        log.dropped("arbotix", arbotix.where.file, detail, "driver")
        return ()
    out = [servo for s in arbotix.servos if (servo := _servo(s, robot, log)) is not None]
    for param in sorted(arbotix.settings, key=lambda p: p.key):
        log.changed(
            f"arbotix.{param.key}",
            f"{arbotix.where.file}: {param.key}",
            f"{param.value!r}: the template's value is written",
            "driver",
        )
    return tuple(out)


def _servo(servo: ArbotixServo, robot: RobotModel, log: PortLog) -> ArbotixJoint | None:
    src, setting = str(servo.where), f"arbotix_joints[{servo.joint}]"
    servo_id = servo.param("id")
    number = servo_id.value if servo_id is not None else None
    if servo.joint not in robot.joint_map or not isinstance(number, int) or isinstance(number, bool):
        log.dropped(setting, src, "not a URDF joint with an integer servo id", "driver")
        return None
    found = servo.param("max_speed")
    speed = found.number if found is not None else None
    derived = robot.joint(servo.joint).velocity
    if speed is not None and derived and math.isclose(speed, round(math.degrees(derived), 3), abs_tol=1e-3):
        speed = None  # the URDF's velocity, which the template writes anyway
    log.carried(setting, src, f"id {number}" + (f", max_speed {speed}" if speed else ""), "limits")
    for param in sorted(servo.params, key=lambda p: p.key):
        if param.key not in ("id", "max_speed", "min_angle", "max_angle"):
            log.dropped(
                f"{setting}.{param.key}",
                src,
                f"{param.value!r}: marm_setup.yaml has no place for it",
                "driver",
            )
    return ArbotixJoint(servo.joint, number, speed)
