"""Porting the joint limits and default scaling factors, as the source's MoveIt reads them
(`package.limits`): an override where the value differs from what the new package writes
without one, every key reported with its value."""

from __future__ import annotations

from collections.abc import Iterable

from marm_setup.package import JointLimitEntry, JointLimitsFile, LoadedLimit, Where, effective_limits
from marm_setup.port.kinematics import short
from marm_setup.port.port_log import PortLog
from marm_setup.robot import RobotModel
from marm_setup.setup import JointLimitOverride

# joint_limits' default scaling factors -> SetupModel field
SCALING_KEYS = {
    "default_velocity_scaling_factor": "default_velocity_scaling",
    "default_acceleration_scaling_factor": "default_acceleration_scaling",
}
LIMIT_KEYS = frozenset(
    {"has_velocity_limits", "max_velocity", "has_acceleration_limits", "max_acceleration", "has_jerk_limits"}
    | {"max_jerk", "has_position_limits", "min_position", "max_position"}
)


# -- joint limits ------------------------------------------------------------------------------


def port_joint_limits(
    limits: JointLimitsFile | None,
    robot: RobotModel,
    planning: Iterable[str],
    default_acceleration: float,
    source_ros2: bool,
    log: PortLog,
) -> tuple[tuple[JointLimitOverride, ...], dict[str, float]]:
    """(overrides, default scaling factors) of a joint limits file, read as the source's MoveIt
    reads it. An override is kept where the value differs from what the new package writes
    without one: the URDF's velocity and position limits, and `default_acceleration`."""
    if limits is None:
        detail = "no joint limits file: the URDF velocities and default_acceleration apply"
        log.changed("joint_limits", "", detail, "limits")
        return (), {}
    scaling = _scaling(limits, log)
    _report_settings(limits, log)
    planning = set(planning)
    read = effective_limits(limits, source_ros2)
    out = []
    for entry in limits.joints or ():
        setting = f"joint_limits[{entry.joint}]"
        if entry.joint not in robot.joint_map:
            log.dropped(setting, entry.where, "no joint of that name in the URDF", "limits")
        elif entry.joint not in planning:
            log.dropped(
                setting, entry.where, "not in any planning group: MoveIt plans nothing for it", "limits"
            )
        elif entry.params is None:
            log.dropped(setting, entry.where, "not a mapping: MoveIt reads nothing from it", "limits")
        else:
            override = _limit(entry, read[entry.joint], robot, default_acceleration, log)
            if override != JointLimitOverride(entry.joint):
                out.append(override)
    return tuple(sorted(out, key=lambda o: o.joint)), scaling


def _scaling(limits: JointLimitsFile, log: PortLog) -> dict[str, float]:
    out = {}
    for key, field in SCALING_KEYS.items():
        param = limits.setting(key)
        if param is None:
            continue
        value = param.number
        if value is not None and 0 < value <= 1:
            out[field] = value
            log.carried(field, param.where, f"{value:g}", "scaling")
        else:
            log.dropped(
                field,
                param.where,
                f"{short(param.value)} is not in (0, 1]; the default 0.1 applies",
                "scaling",
            )
    return out


def _report_settings(limits: JointLimitsFile, log: PortLog) -> None:
    """The file's other top-level keys: Pilz's cartesian limits are the target's own."""
    for param in limits.settings:
        if param.key in SCALING_KEYS:
            continue
        if param.key.startswith("cartesian_limits"):
            detail = (
                f"{short(param.value)}: the target's Pilz cartesian limits are written with MoveIt's defaults"
            )
            log.changed(param.key, param.where, detail, "limits")
        else:
            log.dropped(
                f"joint_limits file: {param.key}",
                param.where,
                f"{short(param.value)}: marm_setup.yaml has no place for it",
            )


def _same(a: float, b: float | None) -> bool:
    """`a` is `b` exactly. MoveIt moves with the file's value, not the URDF's (moveit/moveit
    robot_model_loader.cpp l.139-142 sets max_velocity from the parameter as given): 9.6 rad/s
    next to a URDF's 9.599311 (radians(550)) is carried as an override, not replaced by the
    URDF's within rounding (`limit_slack` serves validate's above-the-URDF rules)."""
    return b is not None and a == b


def _limit(
    entry: JointLimitEntry, read: LoadedLimit, robot: RobotModel, default_acc: float, log: PortLog
) -> JointLimitOverride:
    """One joint's override, each key reported with its value as MoveIt read it."""
    joint = robot.joint(entry.joint)
    name, src = f"joint_limits[{entry.joint}]", entry.where
    velocity = _velocity(name, src, read, joint.velocity or None, log)
    acceleration = read.max_acceleration
    if acceleration is None:
        detail = f"no acceleration limit given: default_acceleration {default_acc:g} is written (time parameterisation needs one)"
        log.changed(f"{name}.max_acceleration", src, detail, "limits")
    else:
        log.carried(f"{name}.max_acceleration", src, f"{acceleration:g}", "limits")
        acceleration = None if _same(acceleration, default_acc) else acceleration
    jerk = _jerk(entry)
    if jerk is not None:
        log.carried(f"{name}.max_jerk", src, f"{jerk:g}", "limits")
    low, high = (
        _position(name, src, key, value, urdf, log)
        for key, value, urdf in (
            ("min_position", read.min_position, joint.lower),
            ("max_position", read.max_position, joint.upper),
        )
    )
    for param in entry.params or ():
        if param.key not in LIMIT_KEYS:
            log.dropped(
                f"{name}.{param.key}",
                src,
                f"{short(param.value)}: MoveIt plans without it; not carried",
                "limits",
            )
    return JointLimitOverride(entry.joint, velocity, acceleration, jerk, low, high)


def _velocity(name: str, src: Where, read: LoadedLimit, urdf: float | None, log: PortLog) -> float | None:
    velocity = read.max_velocity
    if velocity is None and read.velocity_off:
        detail = f"has_velocity_limits is false: the URDF's ({urdf}) applies"
        log.changed(f"{name}.max_velocity", src, detail, "limits")
        return None
    if velocity is None:  # MoveIt keeps the URDF's, and so does the new package
        log.carried(
            f"{name}.max_velocity", src, f"the URDF's ({urdf}): no velocity limit MoveIt reads", "limits"
        )
        return None
    if _same(velocity, urdf):
        log.carried(f"{name}.max_velocity", src, f"{velocity:g} (the URDF's)", "limits")
        return None
    log.carried(f"{name}.max_velocity", src, f"{velocity:g} (URDF: {urdf})", "limits")
    return velocity


def _jerk(entry: JointLimitEntry) -> float | None:
    """`max_jerk` when `has_jerk_limits` is true and the value a positive number (MoveIt 2
    reads it; a MoveIt 1 file's jerk is carried as written)."""
    flag, value = entry.param("has_jerk_limits"), entry.param("max_jerk")
    number = value.number if value is not None else None
    return number if flag is not None and flag.flag is True and number is not None and number > 0 else None


def _position(
    name: str, src: Where, key: str, value: float | None, urdf: float | None, log: PortLog
) -> float | None:
    if value is None:
        return None
    if urdf is not None and _same(value, urdf):
        log.carried(f"{name}.{key}", src, f"{value:g} (the URDF's)", "limits")
        return None
    log.carried(f"{name}.{key}", src, f"{value:g} (URDF: {urdf})", "limits")
    return value
