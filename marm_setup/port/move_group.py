"""Porting move_group's own parameters: every `<param>` a ROS 1 package's launch files set in
move_group's namespace (package/launch_ros1.py LaunchParam, as `roslaunch --dump-params` gives
them), and MoveIt 1's default for a trajectory execution setting left unset, become the setup's
`move_group_parameters` (same meaning in MoveIt 2: moveit_params/move_group_params.py) or are reported
dropped with the reason. A ROS 2 source's move_group parameters (our moveit.yaml) are carried by
name. Pipelines, controllers and sensors are the other ports' (their parameters are named here
only to say so)."""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from typing import TYPE_CHECKING

from marm_setup.moveit_params import BY_ROS1_NAME, MOVE_GROUP_PARAMS, parameter, written_values
from marm_setup.package import MoveItPackage
from marm_setup.port.port_log import PortLog
from marm_setup.ros import Target
from marm_setup.setup import SetupModel

if TYPE_CHECKING:
    from marm_setup.package import LaunchParam

NODE = "move_group/"
AREA = "execution"
# read by the pipelines, controllers and perception ports (their files and launch files)
ELSEWHERE = (
    "planning_plugin", "request_adapters", "default_planning_pipeline", "planning_pipelines/",
    "moveit_controller_manager", "controller_list", "octomap_resolution", "octomap_frame", "sensors",
    "initial", "planner_configs/", "use_controller_manager",
)  # fmt: skip
# MoveIt 1's Fix* start-state adapters read these in their pipeline's namespace (move_group's own in
# a package without planning_pipelines): fix_start_state_collision.cpp l.66, fix_start_state_bounds.cpp l.212
FIX_ADAPTER_PARAMS = ("jiggle_fraction", "start_state_max_bounds_error", "max_sampling_attempts")
_TEM1 = "moveit trajectory_execution_manager.cpp l.64 reads trajectory_execution/<name>"
DROPPED = {
    "max_safe_path_cost": (
        "MoveIt 1 reads only sense_for_plan/max_safe_path_cost (plan_with_sensing.cpp l.53), and "
        "MoveIt 2 has no plan-with-sensing at all: no effect in either"
    ),
    "sense_for_plan/max_safe_path_cost": (
        "MoveIt 1's PlanWithSensing (plan_with_sensing.cpp l.53, l.206) re-senses costly paths; "
        "moveit2 has no plan_with_sensing.cpp: MoveIt 2 plans without it"
    ),
    "max_range": (
        "MoveIt 1's occupancy map monitor reads no top-level max_range (occupancy_map_monitor.cpp "
        "l.83-106: octomap_resolution, octomap_frame, sensors); a sensor's own is in its sensors entry"
    ),
    "allowed_execution_duration_scaling": f"not read by MoveIt 1 either ({_TEM1}): MoveIt 1's default held",
    "allowed_goal_duration_margin": f"not read by MoveIt 1 either ({_TEM1}): MoveIt 1's default held",
    "allowed_start_tolerance": f"not read by MoveIt 1 either ({_TEM1}): MoveIt 1's default held",
}


def ros1_value(text: str) -> bool | int | float | str:
    """A `<param value>` without `type`, as roslaunch types it (loader.py convert_value 'auto'):
    an int, else a float, else true/false, else the string."""
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    lowered = text.strip().lower()
    return {"true": True, "false": False}.get(lowered, text)


def port_move_group(pkg: MoveItPackage, model: SetupModel, log: PortLog) -> SetupModel:
    """`model` with the source's move_group parameters that MoveIt 2 reads, each reported."""
    if pkg.target == Target.ROS2:
        return _from_ros2(pkg, model, log)
    given: dict[str, object] = {}
    seen = set()
    for param in pkg.launch_params:
        if not param.name.startswith(NODE):
            continue
        key = param.name[len(NODE) :]
        seen.add(key)
        model = _one(key, param, model, given, log)
    for known in MOVE_GROUP_PARAMS:
        unset = known.ros1 not in seen and known.ros1.startswith("trajectory_execution/")
        if unset and known.written is not None and known.written != known.moveit1_default:
            given[known.name] = known.moveit1_default
            detail = (
                f"not set: MoveIt 1's default {known.moveit1_default} held, and is written ({known.source})"
            )
            log.carried(known.name, "launch files", detail, AREA)
    return _with_parameters(model, given)


def _one(key: str, param: LaunchParam, model: SetupModel, given: dict, log: PortLog) -> SetupModel:
    source = f"{param.launch}: {param.name}"
    value = ros1_value(param.value)
    known = BY_ROS1_NAME.get(key)
    if known is not None:
        problem = _type_problem(known.type, value)
        if problem:
            log.dropped(known.name, source, f"{param.value!r}: {problem}; MoveIt 1 ignored it too", AREA)
        else:
            given[known.name] = float(value) if known.type is float else value
            log.carried(known.name, source, f"{param.value} ({known.source})", AREA)
    elif key.rsplit("/", 1)[-1] in FIX_ADAPTER_PARAMS:
        model = _fix_adapter(key, value, source, model, log)
    elif key in DROPPED:
        log.dropped(key, source, f"{param.value}: {DROPPED[key]}", AREA)
    elif key.rsplit("/", 1)[-1] == "request_adapters":
        _adapters(key, str(param.value), source, model, log)
    elif key in ("capabilities", "disable_capabilities"):
        _capabilities(key, str(param.value), source, model, log)
    elif key.startswith(ELSEWHERE) or key in ELSEWHERE:
        return model
    else:
        log.dropped(key, source, f"{param.value}: not a move_group parameter MoveIt 2 reads", AREA)
    return model


def _type_problem(kind: type, value: object) -> str | None:
    if kind is bool:
        return None if isinstance(value, bool) else "not a bool"
    return None if isinstance(value, int | float) and not isinstance(value, bool) else "not a number"


def _fix_adapter(key: str, value: object, source: str, model: SetupModel, log: PortLog) -> SetupModel:
    """A Fix* start-state adapter's setting: kept in its pipeline where the target reads it
    (Humble), else dropped: Jazzy's Check* adapters reject such a start state instead."""
    name = key.rsplit("/", 1)[-1]
    parts = key.split("/")
    pipeline = parts[1] if len(parts) == 3 and parts[0] == "planning_pipelines" else "ompl"
    pipeline = "pilz" if pipeline.startswith("pilz") else pipeline
    setting = f"{pipeline}.{name}"
    if model.target != Target.ROS2:
        log.carried(
            setting, source, f"{value}: noetic's pipeline launch files write MoveIt's default", "planners"
        )
        return model
    if parameter(pipeline, model.distro, name) is None:
        detail = (
            f"{value}: {model.distro}'s MoveIt has no FixStartState* adapters; CheckStartStateBounds and "
            "CheckStartStateCollision reject a start state out of bounds or in collision instead of repairing it "
            "(moveit2 jazzy moveit_ros/planning/default_request_adapters_plugin_description.xml l.3-15)"
        )
        log.changed(setting, source, detail, "planners")
        return model
    params = dict(model.pipeline_parameters)
    if pipeline not in params and pipeline not in model.planning_pipelines:
        return model
    merged = {**dict(params.get(pipeline, ())), name: value}
    params[pipeline] = tuple(merged.items())  # type: ignore[arg-type]
    log.carried(setting, source, f"{value}", "planners")
    return dataclasses.replace(model, pipeline_parameters=tuple(params.items()))


_HUMBLE_XML = "moveit2 humble moveit_ros/planning/planning_request_adapters_plugin_description.xml l.3-40"
_JAZZY_XML = "moveit2 jazzy moveit_ros/planning/default_request_adapters_plugin_description.xml"
# a MoveIt 1 adapter -> (what the target does instead, humble or jazzy family), or None: the same
ADAPTER_CHANGES = {
    "AddTimeParameterization": (
        f"IPTP (iterative parabolic) -> TOTG (AddTimeOptimalParameterization): {_HUMBLE_XML} has no IPTP adapter",
        f"IPTP (iterative parabolic) -> TOTG (response adapter AddTimeOptimalParameterization): {_JAZZY_XML} l.3-27 "
        "and default_response_adapters_plugin_description.xml l.3 have no IPTP",
    ),
    "AddIterativeSplineParameterization": (
        f"ISTP -> TOTG: {_HUMBLE_XML} has no spline adapter",
        "ISTP -> TOTG: jazzy's response adapters (default_response_adapters_plugin_description.xml l.3-21) have none",
    ),
    "FixWorkspaceBounds": (None, f"-> ValidateWorkspaceBounds (same default workspace; {_JAZZY_XML} l.9)"),
    "FixStartStateBounds": (
        None,
        f"repair -> rejection: CheckStartStateBounds refuses a start state out of bounds instead of moving it in ({_JAZZY_XML} l.3)",
    ),
    "FixStartStateCollision": (
        None,
        f"repair -> rejection: CheckStartStateCollision refuses a colliding start state instead of jiggling it free ({_JAZZY_XML} l.15)",
    ),
    "FixStartStatePathConstraints": (
        None,
        f"dropped: jazzy has no adapter that plans to a start satisfying the path constraints ({_JAZZY_XML} l.3-27)",
    ),
}


def _adapters(key: str, text: str, source: str, model: SetupModel, log: PortLog) -> None:
    """What becomes of each MoveIt 1 planning request adapter on the target: the same adapter,
    or the change the target's adapter set forces (time parameterization, start-state repair)."""
    parts = key.split("/")
    pipeline = parts[1] if len(parts) == 3 and parts[0] == "planning_pipelines" else "ompl"
    jazzy = model.target == Target.ROS2 and model.row.params == "jazzy"
    for name in text.split():
        short = name.rsplit("/", 1)[-1]
        change = ADAPTER_CHANGES.get(short)
        detail = (change[1] if jazzy else change[0]) if change and model.target == Target.ROS2 else None
        setting = f"{pipeline}.request_adapters[{short}]"
        if detail is None:
            log.carried(setting, source, f"{model.distro} has {short}", "planners")
        else:
            log.changed(setting, source, detail, "planners")


def _capabilities(key: str, text: str, source: str, model: SetupModel, log: PortLog) -> None:
    """move_group loads MoveIt's default capabilities anyway (move_group.cpp, both: the list is
    in addition to them); one MoveIt 2 lacks (PickPlace: moveit2 has no moveit_ros_manipulation)
    is dropped, any other is left to the user."""
    from marm_setup.moveit_params import family_of, load_table

    names = text.split()
    if not names:
        log.carried(key, source, "empty", AREA)
        return
    family = family_of(model.distro) if model.target == Target.ROS2 else "noetic"
    known = set(load_table(family or "jazzy").classes("capability"))
    for name in names:
        if name not in known:
            log.dropped(f"{key}[{name}]", source, f"{model.distro}'s MoveIt has no {name} capability", AREA)
        elif key == "capabilities":
            log.carried(
                f"{key}[{name}]",
                source,
                "loaded by move_group (a default capability or its pipeline's)",
                AREA,
            )
        else:
            log.todo(
                f"{key}[{name}]", source, "marm_setup.yaml has no disable_capabilities: set it by hand", AREA
            )


def _from_ros2(pkg: MoveItPackage, model: SetupModel, log: PortLog) -> SetupModel:
    from marm_setup.moveit_params import move_group_problem

    given = {}
    for param in pkg.move_group or ():
        if move_group_problem(param.key, param.value) is None:
            given[param.key] = param.value
            log.carried(param.key, param.where, str(param.value), AREA)
    return _with_parameters(model, given)


def _with_parameters(model: SetupModel, given: Mapping[str, object]) -> SetupModel:
    """`model` recording the `given` values that differ from what marm-setup writes anyway (a
    port of a generated package reproduces its marm_setup.yaml)."""
    written = written_values(model.target)
    kept = {k: v for k, v in given.items() if written.get(k) != v or type(written.get(k)) is not type(v)}
    return dataclasses.replace(model, move_group_parameters=tuple(sorted(kept.items())))  # type: ignore[arg-type]
