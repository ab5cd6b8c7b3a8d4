"""Porting the per-group and per-joint settings: IK solvers (`kinematics.yaml`), joint-limit
overrides (`joint_limits.yaml`) and OMPL defaults (`ompl_planning.yaml`), from any layout's
sections as validate's discovery reads them."""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import Any

from marm_setup.port.report import PortLog, where
from marm_setup.robot.model import RobotModel, limit_slack
from marm_setup.setup.domain import DEFAULT_PLANNER, KDL_PLUGIN, OMPL_PLANNER_NAMES, OMPL_PLANNERS
from marm_setup.setup.model import JointLimitOverride, Kinematics, PlannerDefaults
from marm_setup.validate.discovery import ConfigSection

# MoveIt's kinematics.yaml keys per group -> Kinematics field
KINEMATICS_KEYS = {
    "kinematics_solver": "solver",
    "kinematics_solver_search_resolution": "search_resolution",
    "kinematics_solver_timeout": "timeout",
    "kinematics_solver_attempts": "attempts",
}
OMPL_TYPES = {ompl_type: name for name, ompl_type in OMPL_PLANNERS}
GROUP_OMPL_KEYS = ("default_planner_config", "planner_configs", "longest_valid_segment_fraction")
# joint_limits.yaml's default scaling factors -> SetupModel field
SCALING_KEYS = {
    "default_velocity_scaling_factor": "default_velocity_scaling",
    "default_acceleration_scaling_factor": "default_acceleration_scaling",
}


def _number(value: Any) -> float | None:
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        return None
    return float(value)


def _mapping(value: Any) -> dict:
    return value if isinstance(value, dict) else {}


# -- kinematics --------------------------------------------------------------------------------


def port_kinematics(
    section: ConfigSection | None, groups: Iterable[str], log: PortLog
) -> tuple[Kinematics, ...]:
    """One Kinematics per group entry that names a solver; everything else reported."""
    if section is None:
        log.changed("kinematics", "", "no kinematics.yaml: no group has an IK solver (as in the source)")
        return ()
    known = set(groups)
    out = []
    for group, entry in _mapping(section.data).items():
        src = where(section.file, section.element(group))
        if group not in known:
            log.dropped(f"kinematics[{group}]", src, "no planning group of that name in the SRDF")
        elif not isinstance(entry, dict) or not entry.get("kinematics_solver"):
            log.dropped(f"kinematics[{group}]", src, "names no kinematics_solver: MoveIt loads none")
        else:
            out.append(_kinematics(str(group), entry, src, log))
    return tuple(sorted(out, key=lambda k: k.group))


def _kinematics(group: str, entry: dict, src: str, log: PortLog) -> Kinematics:
    values: dict = {"group": group}
    for key, value in entry.items():
        field = KINEMATICS_KEYS.get(str(key))
        setting = f"kinematics[{group}].{key}"
        if field is None:
            log.dropped(
                setting,
                src,
                f"{value!r}: solver-specific key marm_setup.yaml has no place for; add it by hand",
            )
            continue
        number = _number(value)
        if field == "solver":
            values[field] = str(value)
        elif field == "attempts" and number is not None and number == int(number) and number > 0:
            values[field] = int(number)
            log.carried(
                setting, src, f"{int(number)} (kept in marm_setup.yaml; MoveIt >= 1.0 reads no attempts)"
            )
            continue
        elif number is not None and number > 0:
            values[field] = number
        else:
            log.dropped(setting, src, f"{value!r} is not a positive number; the default applies")
            continue
        log.carried(setting, src, str(values[field]))
    if values["solver"] != KDL_PLUGIN:
        log.todo(
            f"kinematics[{group}].kinematics_solver",
            src,
            f"{values['solver']}: the new package.xml depends on moveit_kinematics (KDL) only; "
            "install and depend on this plugin's package for the target distro",
        )
    return Kinematics(**values)


# -- joint limits ------------------------------------------------------------------------------


def port_joint_limits(
    section: ConfigSection | None,
    robot: RobotModel,
    planning: Iterable[str],
    default_acceleration: float,
    log: PortLog,
) -> tuple[tuple[JointLimitOverride, ...], dict[str, float]]:
    """(overrides, default scaling factors) of a joint_limits section.

    An override is kept where the value differs from what the new package writes without one:
    the URDF velocity, and `default_acceleration` for the acceleration.
    """
    if section is None:
        log.changed(
            "joint_limits", "", "no joint_limits.yaml: the URDF velocities and default_acceleration apply"
        )
        return (), {}
    data = _mapping(section.data)
    scaling = _scaling(section, data, log)
    for key in sorted(set(data) - {"joint_limits", *SCALING_KEYS}, key=str):
        src = where(section.file, section.element(key))
        if key == "cartesian_limits":
            log.changed(
                f"{key}", src, "the target's Pilz cartesian limits are written with MoveIt's defaults"
            )
        else:
            log.dropped(
                f"joint_limits file: {key}", src, f"{_short(data[key])}: marm_setup.yaml has no place for it"
            )
    planning = set(planning)
    out = []
    for joint, entry in _mapping(data.get("joint_limits")).items():
        src = where(section.file, section.element("joint_limits", joint))
        if joint not in robot.joint_map:
            log.dropped(f"joint_limits[{joint}]", src, "no joint of that name in the URDF")
        elif joint not in planning:
            log.dropped(
                f"joint_limits[{joint}]", src, "not in any planning group: MoveIt plans nothing for it"
            )
        elif isinstance(entry, dict):
            override = _limit(joint, entry, robot, default_acceleration, src, log)
            if override != JointLimitOverride(joint):
                out.append(override)
    return tuple(sorted(out, key=lambda o: o.joint)), scaling


def _scaling(section: ConfigSection, data: dict, log: PortLog) -> dict[str, float]:
    out = {}
    for key, field in SCALING_KEYS.items():
        if key not in data:
            continue
        value = _number(data[key])
        src = where(section.file, section.element(key))
        if value is not None and 0 < value <= 1:
            out[field] = value
            log.carried(field, src, str(value))
        else:
            log.dropped(field, src, f"{data[key]!r} is not in (0, 1]; the default 0.1 applies")
    return out


def _same(a: float, b: float | None) -> bool:
    """`a` is `b` up to the rounding of a limit written in a file (`limit_slack`)."""
    return b is not None and abs(a - b) <= limit_slack(b)


def _limit(
    joint: str, entry: dict, robot: RobotModel, default_acc: float, src: str, log: PortLog
) -> JointLimitOverride:
    """One joint's override; each key reported."""
    urdf_velocity = robot.joint(joint).velocity or None
    velocity = _flagged(entry, "velocity")
    acceleration = _flagged(entry, "acceleration")
    jerk = _flagged(entry, "jerk")
    name = f"joint_limits[{joint}]"
    if velocity is None:
        log.changed(
            f"{name}.max_velocity", src, f"no velocity limit given: the URDF's ({urdf_velocity}) applies"
        )
    elif _same(velocity, urdf_velocity):
        log.carried(f"{name}.max_velocity", src, f"{velocity} (the URDF's)")
        velocity = None
    else:
        log.carried(f"{name}.max_velocity", src, f"{velocity} (URDF: {urdf_velocity})")
    if acceleration is None:
        log.changed(
            f"{name}.max_acceleration",
            src,
            f"no acceleration limit given: default_acceleration {default_acc} is written "
            "(time parameterisation needs one)",
        )
    else:
        log.carried(f"{name}.max_acceleration", src, str(acceleration))
        acceleration = None if _same(acceleration, default_acc) else acceleration
    if jerk is not None:
        log.carried(f"{name}.max_jerk", src, str(jerk))
    for key in ("max_position", "min_position"):
        if key in entry:
            log.dropped(
                f"{name}.{key}",
                src,
                f"{entry[key]!r}: marm_setup.yaml has no position override; the URDF's limits apply",
            )
    return JointLimitOverride(joint, velocity, acceleration, jerk)


def _flagged(entry: dict, kind: str) -> float | None:
    """`max_<kind>` when `has_<kind>_limits` is true and the value a positive number."""
    flag = entry.get(f"has_{kind}_limits")
    value = _number(entry.get(f"max_{kind}"))
    if flag is not True and str(flag).lower() != "true":
        return None
    return value if value is not None and value > 0 else None


# -- OMPL ----------------------------------------------------------------------------------------


def port_planners(
    section: ConfigSection | None, groups: Iterable[str], log: PortLog
) -> tuple[PlannerDefaults, ...]:
    """Per-group OMPL defaults; planner parameters and keys without a place are reported."""
    if section is None:
        log.changed(
            "planners", "", f"no ompl_planning.yaml: every group gets {DEFAULT_PLANNER} and OMPL's defaults"
        )
        return ()
    data = _mapping(section.data)
    configs = _mapping(data.get("planner_configs"))
    _report_configs(section, configs, log)
    groups = list(groups)
    out = []
    for key, value in data.items():
        src = where(section.file, section.element(key))
        if key == "planner_configs":
            continue
        if key in groups and isinstance(value, dict):
            out.append(_group_planner(str(key), value, configs, src, log))
        else:
            log.changed(
                f"ompl.{key}",
                src,
                f"{_short(value)}: the pipeline settings are the target's own (marm-setup writes them)",
            )
    return tuple(sorted(out, key=lambda p: p.group))


def _report_configs(section: ConfigSection, configs: dict, log: PortLog) -> None:
    for name, entry in configs.items():
        src = where(section.file, section.element("planner_configs", name))
        entry = _mapping(entry)
        ours = OMPL_TYPES.get(str(entry.get("type")))
        params = sorted(str(k) for k in entry if k != "type")
        if ours is None:
            log.dropped(
                f"ompl.planner_configs.{name}",
                src,
                f"{entry.get('type')}: not among the OMPL planners marm-setup writes ({', '.join(OMPL_PLANNER_NAMES)})",
            )
        elif params:
            log.dropped(
                f"ompl.planner_configs.{name}",
                src,
                f"{ours} is written with OMPL's defaults; its parameters ({', '.join(params)}) are not carried",
            )
        else:
            log.carried(f"ompl.planner_configs.{name}", src, ours)


def _group_planner(group: str, entry: dict, configs: dict, src: str, log: PortLog) -> PlannerDefaults:
    values: dict = {"group": group}
    default = entry.get("default_planner_config")
    setting = f"planners[{group}]"
    if default is not None:
        ompl_type = _mapping(configs.get(default)).get("type") or f"geometric::{default}"
        ours = OMPL_TYPES.get(str(ompl_type))
        if ours is None:
            log.changed(
                f"{setting}.default_planner",
                src,
                f"{default} ({ompl_type}) is not written: {DEFAULT_PLANNER} instead",
            )
        else:
            values["default_planner"] = ours
            log.carried(
                f"{setting}.default_planner", src, ours if ours == default else f"{default} -> {ours}"
            )
    fraction = _number(entry.get("longest_valid_segment_fraction"))
    if fraction is not None and 0 < fraction <= 1:
        values["longest_valid_segment_fraction"] = fraction
        log.carried(f"{setting}.longest_valid_segment_fraction", src, str(fraction))
    if "planner_configs" in entry:
        log.carried(
            f"{setting}.planner_configs", src, "every planner marm-setup writes is offered to the group"
        )
    for key in sorted(set(entry) - set(GROUP_OMPL_KEYS)):
        log.dropped(
            f"{setting}.{key}",
            src,
            f"{_short(entry[key])}: marm_setup.yaml has no place for it; add it by hand",
        )
    return PlannerDefaults(**values)


def _short(value: Any) -> str:
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."
