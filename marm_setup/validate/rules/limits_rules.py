"""joint_limits.yaml: every active group joint, positive limits, not above the URDF, floats in ROS 2.

What MoveIt reads: MoveIt 2 `moveit_ros/planning/robot_model_loader/src/robot_model_loader.cpp`
(`configure`, the `_planning.joint_limits.<joint>.` loop, humble l.133-239, jazzy l.138-244)
gets max_position and min_position, then has_velocity_limits, has_acceleration_limits and
has_jerk_limits, then max_velocity, max_acceleration and max_jerk each only when its flag is
true (never max_effort), each as a typed parameter: an integer where it reads a double throws
ParameterTypeException, which it logs as an error and which skips the rest of that joint's keys
(`limits.not-float`, `_read_as_double`). MoveIt 1's robot_model_loader.cpp (same loop,
`nh.getParam`, moveit/moveit l.120-156) reads max/min_position, max_velocity,
has_velocity_limits, max_acceleration, has_acceleration_limits in that order, and roscpp hands an
integer to a double (ros_comm roscpp param.cpp getImpl(double&): TypeInt is converted): no
integer rule there. A max_acceleration sets has_acceleration_limits, and a later
`has_acceleration_limits: false` clears it again, so `max_acceleration: 0` beside it (the Setup
Assistant's own default) is never used.

Which overrides apply (what `limits.above-urdf` compares with the URDF): min/max_position
whenever given, in both (`has_position_limits` is never read: moveit/moveit robot_model_loader.cpp
l.120-136, moveit/moveit2 l.138-165); max_velocity in MoveIt 1 whenever given unless
`has_velocity_limits: false` follows (l.138-146), in MoveIt 2 only under `has_velocity_limits:
true` (l.169-176, l.196-208). Values may be written in rosparam's `!degrees` (package.rosparam).
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from numbers import Real
from typing import TYPE_CHECKING, TypeGuard

from marm_setup.findings import Finding, error, warning
from marm_setup.package import JointLimitEntry, JointLimitsFile, Param
from marm_setup.robot import Joint, RobotModel, limit_slack
from marm_setup.ros import Target
from marm_setup.setup import planning_joints, timing_problem

if TYPE_CHECKING:
    from marm_setup.package import PlanningPipeline
    from marm_setup.setup import Srdf

FLAGS = {
    "max_velocity": "has_velocity_limits",
    "max_acceleration": "has_acceleration_limits",
    "max_jerk": "has_jerk_limits",
    "max_effort": "has_effort_limits",
}
POSITION_KEYS = ("min_position", "max_position")
NUMERIC_KEYS = (*FLAGS, *POSITION_KEYS)


def _above(value: float, limit: float) -> bool:
    """Above the URDF's limit by more than rounding (`limit_slack`)."""
    return value > limit + limit_slack(limit)


def _below(value: float, limit: float) -> bool:
    return value < limit - limit_slack(limit)


def check_joint_limits(
    limits: JointLimitsFile, srdf: Srdf, robot: RobotModel | None, target: Target, *, pilz: bool = False
) -> list[Finding]:
    """Every rule on a `robot_description_planning`-style file (`{joint_limits: {...}}`); without
    the robot (a description only the run time gives) the rules that compare with it are skipped.
    `pilz`: a planning pipeline loads Pilz's planner (which reads the limits too)."""
    file = limits.where.file
    if limits.joints is None:
        return [
            error(
                "limits.malformed",
                file,
                limits.where.child("joint_limits").element,
                "no joint_limits mapping",
            )
        ]
    out = _check_coverage(limits, srdf, robot) if robot is not None else []
    for entry in sorted(limits.joints, key=lambda e: e.joint):
        where = entry.where.element
        if robot is None:
            if entry.params is None:
                out.append(error("limits.malformed", file, where, "expected a mapping"))
        elif entry.joint not in robot.joint_map:
            msg = f"unknown joint '{entry.joint}' (MoveIt ignores it)"
            out.append(warning("limits.unknown-joint", file, where, msg))
        elif entry.params is None:
            out.append(error("limits.malformed", file, where, "expected a mapping"))
        else:
            out += _check_entry(file, entry, robot.joint(entry.joint), target)
    out += _check_timing(limits)
    if target == Target.ROS2:
        out += _check_floats(limits, robot, pilz)
    return out


def _check_timing(limits: JointLimitsFile) -> list[Finding]:
    """A positive rate so small (1.0e-320) that, times the package's default scaling factor,
    no trajectory can be timed: the same rule `init` and the planner apply (setup/limits.py
    timing_problem), here without planning (`validate --no-plan`)."""
    out = []
    for entry in sorted(limits.joints or (), key=lambda e: e.joint):
        for key, scaling in (
            ("max_velocity", limits.velocity_scaling),
            ("max_acceleration", limits.acceleration_scaling),
        ):
            value = entry.param(key)
            if not _truthy(entry.param(FLAGS[key])) or value is None or not _number(value.value):
                continue
            factor = scaling.value if scaling is not None and _number(scaling.value) else 1.0
            if problem := timing_problem(entry.joint, key, value.value, factor):
                out.append(
                    error("limits.untimeable", limits.where.file, f"{entry.where.element}.{key}", problem)
                )
    return out


def _check_coverage(limits: JointLimitsFile, srdf: Srdf, robot: RobotModel) -> list[Finding]:
    wanted = planning_joints(tuple(srdf.groups), robot, tuple(srdf.passive_joints))
    given = {e.joint for e in limits.joints or ()}
    return [
        warning(
            "limits.missing-joint",
            limits.where.file,
            limits.where.child("joint_limits", joint).element,
            f"no limits for active group joint '{joint}' (MoveIt falls back to the URDF, no acceleration limit)",
            hint="add an entry with has_velocity_limits/max_velocity and has_acceleration_limits/max_acceleration",
        )
        for joint in sorted(set(wanted) - given)
    ]


def _truthy(param: Param | None) -> bool:
    """The flag as the rules always read it (`entry.get(flag, False)` truthiness)."""
    return param is not None and bool(param.value)


def _velocity_applies(entry: JointLimitEntry, target: Target) -> bool:
    """Whether MoveIt uses the entry's max_velocity (see the module docstring)."""
    flag = entry.param("has_velocity_limits")
    if target == Target.ROS2:
        return _truthy(flag)
    return flag is None or bool(flag.value)


def _check_entry(file: str, entry: JointLimitEntry, joint: Joint, target: Target) -> list[Finding]:
    out: list[Finding] = []
    where = entry.where.element
    for key, flag in FLAGS.items():
        if not _truthy(entry.param(flag)):
            continue
        value = entry.param(key)
        if value is None:
            msg = f"{flag} is true but {key} is missing"
            out.append(error("limits.missing-value", file, f"{where}.{key}", msg))
        elif not _number(value.value) or not 0 < value.value < math.inf:  # also nan and .inf
            msg = f"{key} must be positive, got {value.value!r}"
            out.append(error("limits.non-positive", file, f"{where}.{key}", msg))
    velocity = entry.param("max_velocity")
    if (
        _velocity_applies(entry, target)
        and velocity is not None
        and _number(velocity.value)
        and joint.velocity
        and _above(velocity.value, joint.velocity)
    ):
        msg = f"max_velocity {velocity.value:g} is above the URDF's {joint.velocity:g}"
        out.append(warning("limits.above-urdf", file, f"{where}.max_velocity", msg))
    out += _check_positions(file, entry, joint)
    return out


def _check_positions(file: str, entry: JointLimitEntry, joint: Joint) -> list[Finding]:
    if joint.lower is None or joint.upper is None:
        return []
    out = []
    where = entry.where.element
    lo, hi = entry.param("min_position"), entry.param("max_position")
    if lo is not None and _number(lo.value) and _below(lo.value, joint.lower):
        msg = f"min_position {lo.value:g} is below the URDF's {joint.lower:g}"
        out.append(warning("limits.above-urdf", file, f"{where}.min_position", msg))
    if hi is not None and _number(hi.value) and _above(hi.value, joint.upper):
        msg = f"max_position {hi.value:g} is above the URDF's {joint.upper:g}"
        out.append(warning("limits.above-urdf", file, f"{where}.max_position", msg))
    return out


def _number(value: object) -> TypeGuard[float]:
    return isinstance(value, Real) and not isinstance(value, bool)


def _check_floats(limits: JointLimitsFile, robot: RobotModel | None, pilz: bool) -> list[Finding]:
    """ROS 2 parameters are typed: an integer where MoveIt 2 reads a double throws
    ParameterTypeException. Only the values it reads count (`_read_as_double`); a joint the
    robot lacks is never read (robot_model_loader loops over the model's joints)."""
    out = [_not_float(limits, param, "") for param in limits.settings if _integer_in(param, _SCALARS)]
    for entry in limits.joints or ():
        if robot is not None and entry.joint not in robot.joint_map:
            continue
        for param in entry.params or ():
            if _integer_in(param, NUMERIC_KEYS) and (does := _read_as_double(entry, param.key, pilz)):
                out.append(_not_float(limits, param, does))
    return out


def _integer_in(param: Param, keys: tuple[str, ...]) -> bool:
    value = param.value
    return isinstance(value, int) and not isinstance(value, bool) and param.key.rsplit(".", 1)[-1] in keys


def _read_as_double(entry: JointLimitEntry, key: str, pilz: bool) -> str:
    """What MoveIt 2 does with an integer at `key` of the joint's entry ('' when it never reads
    it). robot_model_loader.cpp (humble l.133-239, jazzy and later l.138-244) reads max_position
    and min_position always, then the has_* flags, then max_velocity, max_acceleration and
    max_jerk each only when its flag is true, never max_effort; a ParameterTypeException ends the
    joint's loop (caught and logged, l.236-239 / l.241-244). Pilz's copy of ros2_control's
    joint_limits_rosparam.hpp (pilz_industrial_motion_planner/include/joint_limits_copy/, jazzy
    l.150-236) reads each max_* (max_effort too) and min/max_position only under its true flag
    (has_position_limits for the positions), unguarded: the
    exception leaves CommandPlanner::initialize and PlanningPipeline's constructor
    (planning_pipeline.cpp jazzy l.170), and move_group stops."""

    def flagged(flag: str | None) -> bool:
        return flag is not None and (set_to := entry.param(flag)) is not None and set_to.value is True

    loader = key in POSITION_KEYS or (key != "max_effort" and flagged(FLAGS.get(key)))
    stops = pilz and flagged(FLAGS.get(key, "has_position_limits" if key in POSITION_KEYS else None))
    if not loader and not stops:
        return ""
    does = (
        "MoveIt 2 logs a ParameterTypeException and keeps none of the joint's limits from there on"
        if loader
        else ""
    )
    if stops:
        does += ("; " if does else "") + "Pilz's planner throws at start-up and move_group stops"
    return does


def _not_float(limits: JointLimitsFile, param: Param, does: str) -> Finding:
    key = param.key.rsplit(".", 1)[-1]
    msg = f"{key} is the integer {param.value}; " + (
        f"MoveIt 2 reads a double here: {does}" if does else "ROS 2 needs a double here"
    )
    return error("limits.not-float", limits.where.file, param.where.element, msg, f"write {param.value}.0")


_SCALARS = (
    "default_velocity_scaling_factor",
    "default_acceleration_scaling_factor",
    "max_trans_vel",
    "max_trans_acc",
    "max_trans_dec",
    "max_rot_vel",
)

# Pilz's Cartesian limits that time LIN and CIRC motions (max_trans_dec, max_rot_acc and
# max_rot_dec are only logged: limits_container.cpp jazzy l.69-75)
CARTESIAN_RATES = ("max_trans_vel", "max_trans_acc", "max_rot_vel")


def uses_pilz(pipelines: Iterable[PlanningPipeline]) -> bool:
    """Whether a pipeline loads Pilz's planner (planning_plugin(s) naming its CommandPlanner)."""
    return any(
        "pilz_industrial_motion_planner" in str(p.value)
        for pipeline in pipelines
        for p in pipeline.settings
        if p.key in ("planning_plugin", "planning_plugins")
    )


def check_cartesian_limits(limits: JointLimitsFile) -> list[Finding]:
    """Pilz's `cartesian_limits` rates as its LIN and CIRC generators use them: the translational
    velocity and acceleration make the motion's trapezoidal profile (trajectory_generator.cpp
    jazzy l.284-287, KDL::VelocityProfile_Trap) and max_trans_vel / max_rot_vel the path's
    equivalent radius (trajectory_generator_lin.cpp l.183-184, _circ.cpp l.244-245; the same in
    humble and noetic). Pilz checks none of them: NaN times every motion with NaN, zero divides
    by zero, a negative rate makes a profile that ignores the limit. Non-numbers are params.type's."""
    out = []
    for key in CARTESIAN_RATES:
        param = limits.setting(f"cartesian_limits.{key}")
        if param is None or not _number(param.value) or 0 < param.value < math.inf:
            continue
        msg = (
            f"{key} must be a positive finite number, got {param.value!r}: Pilz times every LIN "
            "and CIRC motion with it and checks nothing (NaN or 0: no valid trajectory; negative: "
            "the limit is not kept)"
        )
        out.append(error("limits.cartesian", limits.where.file, param.where.element, msg))
    return out
