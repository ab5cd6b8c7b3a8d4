"""Porting perception and teleoperation: the source's 3D sensors (`sensors`, setup.sensors) and
MoveIt Servo configurations (`servo`, setup.servo), each key carried where the setup has a place
for it, every other one reported exactly. An entry the setup's own checks refuse (a servo on a
group that is no chain, ...) is dropped with their reason: the new package must load."""

from __future__ import annotations

import dataclasses
from collections.abc import Callable

from marm_setup.errors import InputError
from marm_setup.moveit_params import SENSOR_TYPES, SERVO_POSITION, SERVO_TRAJECTORY
from marm_setup.package import MoveItPackage, Param, ServoConfig
from marm_setup.package import Sensor as SourceSensor
from marm_setup.port.kinematics import short
from marm_setup.port.port_log import PortLog
from marm_setup.robot import RobotModel
from marm_setup.ros import Target
from marm_setup.setup import Sensor, Servo, ServoScale, SetupModel

PLUGIN_TYPES = {kind.plugin: name for name, kind in SENSOR_TYPES.items()}
SENSOR_FIELDS = {f.name for f in dataclasses.fields(Sensor)} - {"name", "type", "topic"}
# moveit_servo's parameter -> Servo field (noetic and humble servo parameter names)
SERVO_KEYS = {
    "planning_frame": ("planning_frame", str),
    "ee_frame_name": ("ee_frame", str),
    "robot_link_command_frame": ("command_frame", str),
    "command_in_type": ("command_in_type", str),
    "publish_period": ("publish_period", float),
    "check_collisions": ("check_collisions", bool),
}
SCALE_KEYS = {"scale.linear": "linear", "scale.rotational": "rotational", "scale.joint": "joint"}
OUTPUT_TYPES = {
    "trajectory_msgs/JointTrajectory": SERVO_TRAJECTORY,
    "std_msgs/Float64MultiArray": SERVO_POSITION,
}


def port_perception(pkg: MoveItPackage, model: SetupModel, robot: RobotModel, log: PortLog) -> SetupModel:
    """`model` with the source's sensors and servos the setup's checks take."""
    from marm_setup.setup import check_sensors, check_servos

    sensors: list[Sensor] = []
    for index, found in enumerate(pkg.sensors.sensors if pkg.sensors is not None else ()):
        sensor = _sensor(found, index, log)
        if sensor is not None and _accepted(
            lambda m: check_sensors(m, None),
            model,
            "sensors",
            (*sensors, sensor),
            sensor.name,
            found.where,
            log,
        ):
            sensors.append(sensor)
    servos: list[Servo] = []
    for config in pkg.servo:
        servo = _servo(config, log)
        servo = _for_target(servo, model, config, log) if servo is not None else None
        if servo is not None and _accepted(
            lambda m: check_servos(m, robot, None),
            model,
            "servo",
            (*servos, servo),
            servo.group,
            config.where,
            log,
        ):
            servos.append(servo)
    if pkg.sensors is not None and not pkg.sensors.sensors:
        log.carried("sensors", pkg.sensors.where, "none configured (an empty list)", "perception")
    model = dataclasses.replace(model, sensors=tuple(sensors))
    if pkg.servo:
        model = dataclasses.replace(model, servo=_or_default(tuple(servos), model, robot))
    return model


# What the servo templates write for a key the setup leaves None (templates/*/config/servo.yaml.j2).
SERVO_DEFAULTS = {"command_in_type": "unitless", "check_collisions": True, "command_out": SERVO_TRAJECTORY}
SCALE_DEFAULTS = {"linear": 0.4, "rotational": 0.8, "joint": 0.5}


def _or_default(servos: tuple[Servo, ...], model: SetupModel, robot: RobotModel) -> tuple[Servo, ...] | None:
    """None (the target's default servos) when the ported ones are exactly what it writes by
    default, so a package marm-setup wrote ports back to the same marm_setup.yaml; else them."""
    from marm_setup.setup import default_servos, plan_servos

    default = default_servos(model, robot)
    plans = {p.group: p for p in plan_servos(dataclasses.replace(model, servo=default), robot)}
    period = model.row.servo_publish_period
    bare = []
    for servo in servos:
        plan = plans.get(servo.group)
        resolved = (
            (plan.planning_frame, plan.ee_frame, plan.command_frame, plan.output_controller) if plan else ()
        )
        given = (servo.planning_frame, servo.ee_frame, servo.command_frame, servo.controller)
        scale = {k: getattr(servo.scale, k) for k in SCALE_DEFAULTS}
        if any(g not in (None, r) for g, r in zip(given, resolved, strict=False)) or plan is None:
            return servos
        if any(v not in (None, SCALE_DEFAULTS[k]) for k, v in scale.items()) or servo.publish_period not in (
            None,
            period,
        ):
            return servos
        if any(getattr(servo, k) not in (None, v) for k, v in SERVO_DEFAULTS.items()):
            return servos
        bare.append(Servo(servo.group))
    return None if tuple(bare) == default else servos


def _for_target(servo: Servo, model: SetupModel, config: ServoConfig, log: PortLog) -> Servo:
    """A forward position output on ros1 becomes a trajectory one: the forward position
    controller is a ros2_control one (setup.servo), the group's trajectory controller takes
    servo's JointTrajectory on either target."""
    if model.target != Target.ROS1 or servo.command_out != SERVO_POSITION:
        return servo
    detail = (
        "position -> trajectory: a ros1 package has no forward position controller (ros2_control's); "
        "servo publishes trajectory_msgs/JointTrajectory to the group's trajectory controller"
    )
    log.changed(f"servo[{servo.group}].command_out_type", config.where, detail, "perception")
    return dataclasses.replace(servo, command_out=SERVO_TRAJECTORY, controller=None)


def _accepted(
    check: Callable[[SetupModel], None],
    model: SetupModel,
    field: str,
    items: tuple,
    name: str,
    where: object,
    log: PortLog,
) -> bool:
    try:
        check(dataclasses.replace(model, **{field: items}))  # type: ignore[arg-type]
    except InputError as exc:
        log.dropped(f"{field}[{name}]", where, f"{exc.message} (left out of the new package)", "perception")
        return False
    return True


def _sensor(found: SourceSensor, index: int, log: PortLog) -> Sensor | None:
    kind = PLUGIN_TYPES.get(str(found.plugin))
    setting = f"sensors[{found.name}]"
    if kind is None:
        detail = f"{found.plugin}: not an updater marm-setup writes ({', '.join(sorted(PLUGIN_TYPES))}); copy it by hand"
        log.dropped(setting, found.where, detail, "perception")
        return None
    params = {p.key: p for p in found.params}
    topic = params.pop(SENSOR_TYPES[kind].topic_key, None)
    if topic is None or not isinstance(topic.value, str):
        log.dropped(
            setting, found.where, f"no {SENSOR_TYPES[kind].topic_key}: MoveIt cannot start it", "perception"
        )
        return None
    name = found.name if not found.name.isdigit() else f"{kind}_{index}"
    values = {key: p.value for key, p in params.items() if key in SENSOR_FIELDS and _scalar(p)}
    for key, p in params.items():
        if key not in values:
            log.dropped(
                f"{setting}.{key}",
                p.where,
                f"{short(p.value)}: marm_setup.yaml's sensors have no place for it",
                "perception",
            )
    renamed = f" (named {name}: MoveIt 1 sensors have no name)" if name != found.name else ""
    log.carried(
        setting, found.where, f"{kind} on {topic.value}, {len(values)} parameters{renamed}", "perception"
    )
    return Sensor(name, kind, topic.value, **values)  # type: ignore[arg-type]


def _scalar(param: Param) -> bool:
    return isinstance(param.value, str | int | float) and not isinstance(param.value, bool)


def _servo(config: ServoConfig, log: PortLog) -> Servo | None:
    group = config.group
    if group is None:
        log.dropped(
            "servo", config.where, "names no move_group_name: servo has no group to move", "perception"
        )
        return None
    values: dict[str, object] = {}
    scale: dict[str, float] = {}
    for param in config.params:
        value = _typed(param)
        if param.key in SCALE_KEYS and param.number is not None:
            scale[SCALE_KEYS[param.key]] = param.number
        elif param.key in SERVO_KEYS and value is not None:
            values[SERVO_KEYS[param.key][0]] = value
        elif param.key == "command_out_type" and str(param.value) in OUTPUT_TYPES:
            values["command_out"] = OUTPUT_TYPES[str(param.value)]
        elif param.key == "command_out_topic" and _controller(param.value):
            values["controller"] = _controller(param.value)
        elif param.key != "move_group_name":
            detail = f"{short(param.value)}: the target's moveit_servo value is written"
            log.dropped(f"servo[{group}].{param.key}", param.where, detail, "perception")
    log.carried(
        f"servo[{group}]", config.where, f"{len(values) + len(scale)} moveit_servo parameters", "perception"
    )
    return Servo(group, scale=ServoScale(**scale), **values)  # type: ignore[arg-type]


def _typed(param: Param) -> object:
    """The value as the Servo field of its key takes it, else None."""
    kind = SERVO_KEYS.get(param.key, (None, None))[1]
    if kind is float:
        return param.number
    if kind is bool:
        return param.value if isinstance(param.value, bool) else None
    return param.value if kind is str and isinstance(param.value, str) and param.value else None


def _controller(topic: object) -> str | None:
    """The controller a servo output topic reaches: `/<controller>/joint_trajectory` (trajectory)
    or `/<controller>/commands` (a forward position controller)."""
    parts = str(topic).strip("/").split("/")
    return parts[-2] if len(parts) >= 2 and parts[-1] in ("joint_trajectory", "commands", "command") else None
