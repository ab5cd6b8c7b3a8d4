"""What MoveIt makes of a joint_limits file: each joint's limits after the overrides.

MoveIt 1 (moveit/moveit `moveit_ros/planning/robot_model_loader/src/robot_model_loader.cpp`,
the `_planning/joint_limits/<joint>/` loop) reads max_position and min_position; a max_velocity
sets a velocity limit and a `has_velocity_limits` after it may switch it on or off; the same
for acceleration. It reads no jerk.

MoveIt 2 (moveit/moveit2 humble and jazzy, same file, `RobotModelLoader::configure`) reads, in
order, max_position, min_position, has_velocity_limits, has_acceleration_limits,
has_jerk_limits, then max_velocity / max_acceleration / max_jerk only where their flag is true
(a max_velocity without `has_velocity_limits: true` is never read). Each is a typed parameter:
an integer where it reads a double (or a non-bool flag) throws, which MoveIt logs, and the
joint's remaining keys are not read.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from marm_setup.package.joint_limits_file import JointLimitEntry, JointLimitsFile
from marm_setup.package.where import finite_number

ROS2_ORDER = (
    "max_position",
    "min_position",
    "has_velocity_limits",
    "has_acceleration_limits",
    "has_jerk_limits",
)


@dataclass(frozen=True, slots=True)
class LoadedLimit:
    """One joint's limits after the file: a value, or None where the URDF's (or none) stays;
    `velocity_off` / `acceleration_off` where the file switches the limit off."""

    joint: str
    max_velocity: float | None = None
    max_acceleration: float | None = None
    max_jerk: float | None = None
    min_position: float | None = None
    max_position: float | None = None
    velocity_off: bool = False
    acceleration_off: bool = False
    unreadable: tuple[tuple[str, object], ...] = ()  # limits MoveIt would read that are no number


def _unreadable(entry: JointLimitEntry, ros2: bool) -> tuple[tuple[str, object], ...]:
    """(key, value) of a velocity or acceleration limit MoveIt reads (its flag not switched off;
    in MoveIt 2 switched on) whose value is no number: MoveIt cannot use it."""
    out = []
    for key, flag in (
        ("max_velocity", "has_velocity_limits"),
        ("max_acceleration", "has_acceleration_limits"),
    ):
        param, on = entry.param(key), entry.param(flag)
        read = on is not None and on.flag is True if ros2 else not (on is not None and on.flag is False)
        if param is not None and read and param.number is None:
            out.append((key, param.value))
    return tuple(out)


def effective_limits(limits: JointLimitsFile | None, ros2: bool) -> dict[str, LoadedLimit]:
    """Each joint of the file as MoveIt reads it (see the module docstring)."""
    if limits is None:
        return {}
    read = _ros2_limit if ros2 else _ros1_limit
    return {
        e.joint: replace(read(e), unreadable=_unreadable(e, ros2))
        for e in limits.joints or ()
        if e.params is not None
    }


def _ros1_limit(entry: JointLimitEntry) -> LoadedLimit:
    values: dict[str, object] = {}
    for kind in ("velocity", "acceleration"):
        number = _number(entry, f"max_{kind}")
        on = number is not None
        flag = entry.param(f"has_{kind}_limits")
        if flag is not None and flag.flag is not None:
            on = flag.flag
        values[f"max_{kind}"] = number if on else None
        values[f"{kind}_off"] = not on and flag is not None and flag.flag is False
    return LoadedLimit(
        entry.joint,
        min_position=_number(entry, "min_position"),
        max_position=_number(entry, "max_position"),
        **values,  # type: ignore[arg-type]
    )


def _ros2_limit(entry: JointLimitEntry) -> LoadedLimit:
    got: dict[str, object] = {}
    for key in ROS2_ORDER:
        param = entry.param(key)
        if param is None:
            continue
        value = param.value
        if key.startswith("has_") and not isinstance(value, bool):
            return _ros2_result(entry.joint, got)  # a type MoveIt cannot read: it stops here
        if not key.startswith("has_") and not isinstance(value, float):
            return _ros2_result(entry.joint, got)
        got[key] = value
    for kind in ("velocity", "acceleration", "jerk"):
        if got.get(f"has_{kind}_limits") is True:
            param = entry.param(f"max_{kind}")
            if param is not None and not isinstance(param.value, float):
                return _ros2_result(entry.joint, got)
            if param is not None:
                got[f"max_{kind}"] = param.value
    return _ros2_result(entry.joint, got)


def _ros2_result(joint: str, got: dict[str, object]) -> LoadedLimit:
    def number(key: str) -> float | None:
        return finite_number(got.get(key))

    return LoadedLimit(
        joint,
        max_velocity=number("max_velocity") if got.get("has_velocity_limits") is True else None,
        max_acceleration=number("max_acceleration") if got.get("has_acceleration_limits") is True else None,
        max_jerk=number("max_jerk") if got.get("has_jerk_limits") is True else None,
        min_position=number("min_position"),
        max_position=number("max_position"),
        velocity_off=got.get("has_velocity_limits") is False,
        acceleration_off=got.get("has_acceleration_limits") is False,
    )


def _number(entry: JointLimitEntry, key: str) -> float | None:
    param = entry.param(key)
    return param.number if param is not None else None
