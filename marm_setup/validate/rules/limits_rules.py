"""joint_limits.yaml: every active group joint, positive limits, not above the URDF, floats in ROS 2.

What MoveIt reads: MoveIt 2 `moveit_ros/planning/robot_model_loader/src/robot_model_loader.cpp`
(`configure`, the `_planning/joint_limits/<joint>/` loop) gets max/min_position, max_velocity,
has_velocity_limits, max_acceleration, has_acceleration_limits in that order, each as a typed
parameter: an integer where it reads a double throws ParameterTypeException, which it logs as
an error and which skips the rest of that joint's keys. MoveIt 1's robot_model_loader.cpp
(same loop, `nh.getParam`) reads them in the same order: a max_acceleration sets
has_acceleration_limits, and a later `has_acceleration_limits: false` clears it again, so
`max_acceleration: 0` beside it (the Setup Assistant's own default) is never used.
"""

from __future__ import annotations

import math
from numbers import Real
from typing import TYPE_CHECKING, Any, TypeGuard

from marm_setup.findings import Finding, error, warning
from marm_setup.robot.model import Joint, RobotModel, limit_slack
from marm_setup.setup.groups import planning_joints

if TYPE_CHECKING:
    from marm_setup.setup.srdf import Srdf
    from marm_setup.validate.discovery import ConfigSection

FLAGS = {
    "max_velocity": "has_velocity_limits",
    "max_acceleration": "has_acceleration_limits",
    "max_jerk": "has_jerk_limits",
    "max_effort": "has_effort_limits",
}
NUMERIC_KEYS = (*FLAGS, "min_position", "max_position")


def _above(value: float, limit: float) -> bool:
    """Above the URDF's limit by more than rounding (`limit_slack`)."""
    return value > limit + limit_slack(limit)


def _below(value: float, limit: float) -> bool:
    return value < limit - limit_slack(limit)


def check_joint_limits(section: ConfigSection, srdf: Srdf, robot: RobotModel, target: str) -> list[Finding]:
    """Every rule on a `robot_description_planning`-style section (`{joint_limits: {...}}`)."""
    data = section.data
    limits = data.get("joint_limits") if isinstance(data, dict) else None
    if not isinstance(limits, dict):
        return [
            error(
                "limits.malformed", section.file, section.element("joint_limits"), "no joint_limits mapping"
            )
        ]
    out = _check_coverage(section, limits, srdf, robot)
    for joint in sorted(limits, key=str):
        entry = limits[joint]
        where = section.element("joint_limits", joint)
        if joint not in robot.joint_map:
            out.append(
                warning(
                    "limits.unknown-joint",
                    section.file,
                    where,
                    f"unknown joint '{joint}' (MoveIt ignores it)",
                )
            )
            continue
        if not isinstance(entry, dict):
            out.append(error("limits.malformed", section.file, where, "expected a mapping"))
            continue
        out += _check_entry(section, where, entry, robot.joint(joint), target)
    if target == "ros2":
        out += _check_floats(section, data)
    return out


def _check_coverage(section: ConfigSection, limits: dict, srdf: Srdf, robot: RobotModel) -> list[Finding]:
    wanted = planning_joints(tuple(srdf.groups), robot, tuple(srdf.passive_joints))
    return [
        warning(
            "limits.missing-joint",
            section.file,
            section.element("joint_limits", joint),
            f"no limits for active group joint '{joint}' (MoveIt falls back to the URDF, no acceleration limit)",
            hint="add an entry with has_velocity_limits/max_velocity and has_acceleration_limits/max_acceleration",
        )
        for joint in sorted(set(wanted) - set(limits))
    ]


def _check_entry(section: ConfigSection, where: str, entry: dict, joint: Joint, target: str) -> list[Finding]:
    out: list[Finding] = []
    for key, flag in FLAGS.items():
        if not entry.get(flag, False):
            continue
        value = entry.get(key)
        if value is None:
            out.append(
                error(
                    "limits.missing-value",
                    section.file,
                    f"{where}.{key}",
                    f"{flag} is true but {key} is missing",
                )
            )
        elif not _number(value) or not 0 < value < math.inf:  # also nan and .inf
            out.append(
                error(
                    "limits.non-positive",
                    section.file,
                    f"{where}.{key}",
                    f"{key} must be positive, got {value!r}",
                )
            )
    velocity = entry.get("max_velocity")
    if (
        entry.get("has_velocity_limits")
        and _number(velocity)
        and joint.velocity
        and _above(velocity, joint.velocity)
    ):
        msg = f"max_velocity {velocity:g} is above the URDF's {joint.velocity:g}"
        out.append(warning("limits.above-urdf", section.file, f"{where}.max_velocity", msg))
    out += _check_positions(section, where, entry, joint)
    return out


def _check_positions(section: ConfigSection, where: str, entry: dict, joint: Joint) -> list[Finding]:
    if not entry.get("has_position_limits", False) or joint.lower is None or joint.upper is None:
        return []
    out = []
    lo, hi = entry.get("min_position"), entry.get("max_position")
    if _number(lo) and _below(lo, joint.lower):
        msg = f"min_position {lo:g} is below the URDF's {joint.lower:g}"
        out.append(warning("limits.above-urdf", section.file, f"{where}.min_position", msg))
    if _number(hi) and _above(hi, joint.upper):
        msg = f"max_position {hi:g} is above the URDF's {joint.upper:g}"
        out.append(warning("limits.above-urdf", section.file, f"{where}.max_position", msg))
    return out


def _number(value: object) -> TypeGuard[float]:
    return isinstance(value, Real) and not isinstance(value, bool)


def _check_floats(section: ConfigSection, data: dict) -> list[Finding]:
    """ROS 2 parameters are typed: an integer where MoveIt reads a double is an error it logs,
    losing the joint's later keys; only a warning when the value's has_* flag is false (nothing
    after max_acceleration is lost then but that false flag, which is the URDF's default)."""
    out = []
    for path, value in _walk(data):
        if isinstance(value, int) and not isinstance(value, bool) and path[-1] in (*NUMERIC_KEYS, *_SCALARS):
            msg = f"{path[-1]} is the integer {value}; ROS 2 needs a double here"
            unused = _flag_off(data, path)
            make = warning if unused else error
            msg += f" (MoveIt 2 logs an error; harmless while {FLAGS[path[-1]]} is false)" if unused else ""
            out.append(
                make("limits.not-float", section.file, section.element(*path), msg, f"write {value}.0")
            )
    return out


def _flag_off(data: dict, path: tuple) -> bool:
    """The value at `path` is a limit whose has_* flag in the same entry is explicitly false."""
    flag = FLAGS.get(path[-1])
    entry: Any = data
    for key in path[:-1]:
        entry = entry.get(key) if isinstance(entry, dict) else None
    return flag is not None and isinstance(entry, dict) and entry.get(flag) is False


_SCALARS = (
    "default_velocity_scaling_factor",
    "default_acceleration_scaling_factor",
    "max_trans_vel",
    "max_trans_acc",
    "max_trans_dec",
    "max_rot_vel",
)


def _walk(data, path=()):
    if isinstance(data, dict):
        for key, value in data.items():
            yield from _walk(value, (*path, key))
    else:
        yield path, data
