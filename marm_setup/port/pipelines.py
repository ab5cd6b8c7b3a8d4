"""Porting the planning pipelines: which planners move_group loads (the setup's
`planning_pipelines`) and the parameters of each pipeline's namespace (`pipeline_parameters`),
as the target distro's MoveIt reads them (moveit_params/pipeline_params.py: names, types, defaults).

A pipeline is carried when marm-setup writes its planner for the target distro; one the distro's
binaries lack (STOMP on Humble) only from a marm-setup package, whose setup chose it (init then
warns what to build). A parameter is carried when the target reads it with a value of its type;
a value equal to what the target writes by default is carried as that default (not repeated in
marm_setup.yaml). Adapter lists are carried between packages of one adapter format only (Humble's
space-separated string of `default_planner_request_adapters/`, Jazzy's request and response
lists): the two families have no one-to-one mapping. Humble's time parameterization settings and
Jazzy's `totg.` ones are the same adapter's (AddTimeOptimalParameterization): renamed.
"""

from __future__ import annotations

import dataclasses
import re

from marm_setup.moveit_params import (
    PIPELINES,
    effective_parameters,
    infinite_problem,
    parameter,
    value_problem,
)
from marm_setup.package import FrozenMapping, MoveItPackage, Param, PlanningPipeline, Where
from marm_setup.port.kinematics import short
from marm_setup.port.port_log import PortLog
from marm_setup.ros import Target, distro_row
from marm_setup.setup import SetupModel

ADAPTER_KEYS = ("request_adapters", "response_adapters")
STRUCTURE = frozenset({"planning_plugin", "planning_plugins", "planner_configs"})
# Humble's AddTimeOptimalParameterization settings <-> Jazzy's (moveit_params/pipeline_params.py)
RENAMED = {
    "path_tolerance": "totg.path_tolerance",
    "resample_dt": "totg.resample_dt",
    "min_angle_change": "totg.min_angle_change",
}
RENAMED.update({v: k for k, v in RENAMED.items()})
AREA = "planners"
# a pipeline's file: config/<name>_planning.yaml, MoveIt 1's launch/<name>_planning_pipeline.launch.xml
PIPELINE_FILE = re.compile(r"^(?:config|launch)/([a-z0-9_]+?)_planning(?:_pipeline\.launch\.xml|\.yaml)$")


def pipeline_key(pipeline: PlanningPipeline) -> str | None:
    """The setup's name of a source pipeline (ompl, chomp, pilz, stomp): by its planner plugin
    (MoveIt 1 or 2 class name), else by its namespace."""
    plugins: list[object] = []
    for key in ("planning_plugin", "planning_plugins"):
        found = pipeline.setting(key)
        value = found.value if found is not None else None
        plugins += list(value) if isinstance(value, tuple) else [value]
    for key, known in PIPELINES.items():
        if known.plugin_ros2 in plugins or (known.plugin_ros1 and known.plugin_ros1 in plugins):
            return key
    return next((k for k, p in PIPELINES.items() if pipeline.name in (k, p.namespace)), None)


def port_pipelines(pkg: MoveItPackage, model: SetupModel, log: PortLog) -> SetupModel:
    """`model` with the source's pipelines the target can run and their parameters."""
    names: list[str] = []
    params: list[tuple[str, tuple]] = []
    for pipeline in _in_move_group_order(pkg):
        key = _carried_pipeline(pipeline, pkg, model, names, log)
        if key is None:
            continue
        names.append(key)
        given = _port_parameters(pipeline, key, _source_distro(pkg, pipeline), model, log)
        if given:
            params.append((key, given))
    if not names:
        log.changed(
            "planning_pipelines", "", f"none to carry: {', '.join(model.planning_pipelines)} written", AREA
        )
        return model
    return dataclasses.replace(model, planning_pipelines=tuple(names), pipeline_parameters=tuple(params))


def _in_move_group_order(pkg: MoveItPackage) -> list[PlanningPipeline]:
    """The source's pipelines, move_group's default (`default_planning_pipeline`, else OMPL) first,
    then in the order move_group lists them."""
    top = {p.key: p.value for p in pkg.move_group or ()}
    listed = top.get("planning_pipelines")
    if isinstance(listed, FrozenMapping):
        listed = dict(listed).get("pipeline_names")
    order = [str(n) for n in listed] if isinstance(listed, tuple) else []
    default = top.get("default_planning_pipeline")
    order = [str(default), *order] if isinstance(default, str) else order
    rank = {name: i for i, name in reversed(list(enumerate(order)))}
    read = {p.name for p in pkg.pipelines}
    only_files = {  # MoveIt 1's Pilz: its launch file sets the plugin, no YAML
        m.group(1): PlanningPipeline(m.group(1), Where(rel), False)
        for rel in pkg.files
        if (m := PIPELINE_FILE.match(rel)) and m.group(1) not in read
    }
    found = [*pkg.pipelines, *only_files.values()]
    return sorted(found, key=lambda p: (rank.get(p.name, len(rank)), p.name != "ompl", p.name))


def _carried_pipeline(
    pipeline: PlanningPipeline, pkg: MoveItPackage, model: SetupModel, names: list[str], log: PortLog
) -> str | None:
    setting, distro = f"planning_pipelines.{pipeline.name}", model.distro
    files = {
        pipeline.where.file,
        *(f for f in pkg.files if (m := PIPELINE_FILE.match(f)) and m.group(1) == pipeline.name),
    }
    src = ", ".join(sorted(files))
    key = pipeline_key(pipeline)
    if key is None:
        ours = ", ".join(PIPELINES)
        log.dropped(setting, src, f"not a planner marm-setup writes ({ours}); configure it by hand", AREA)
        return None
    if key in names:
        log.dropped(setting, src, f"a second {key} pipeline: the new package has one", AREA)
        return None
    known, row = PIPELINES[key], distro_row(distro)
    if key in row.planners_from_source and pkg.marm_setup is None:
        detail = f"{distro}'s MoveIt binaries lack {known.package}: build it from source and add {key} to planning_pipelines"
        log.dropped(setting, src, detail, AREA)
        return None
    if key not in row.planners + row.planners_from_source:
        log.dropped(setting, src, f"{distro}'s MoveIt has no {key} planner", AREA)
        return None
    log.carried(setting, src, f"as {key}", AREA)
    return key


def _source_distro(pkg: MoveItPackage, pipeline: PlanningPipeline) -> str | None:
    """The MoveIt parameter format (a DistroRow `params`) the source pipeline is written in:
    Humble's planning_plugin string or Jazzy's planning_plugins list (None: a MoveIt 1 package)."""
    if pkg.target != Target.ROS2:
        return None
    return "jazzy" if pipeline.setting("planning_plugins") is not None else "humble"


def _namespace(pipeline: PlanningPipeline, key: str, log: PortLog) -> list[Param]:
    """The settings of a pipeline's namespace, sub-namespaces flattened (`totg.path_tolerance`,
    a `stomp_moveit` block); not its plugin nor OMPL's planner configurations and group entries
    (port.planners). Another pipeline's mapping (MoveIt 1 STOMP's `stomp/<group>`) is reported."""
    out = []
    for p in pipeline.settings:
        if isinstance(p.value, FrozenMapping):
            out += [Param(f"{p.key}.{k}", v, p.where.child(k)) for k, v in p.value]
        elif p.key not in STRUCTURE:
            out.append(p)
    for entry in pipeline.groups:
        if entry.group == "stomp_moveit":
            out += [Param(f"{entry.group}.{p.key}", p.value, p.where) for p in entry.params]
        elif key != "ompl":
            detail = f"{len(entry.params)} settings in a sub-namespace MoveIt 2's {key} does not read; set pipeline_parameters.{key} by hand"
            log.dropped(f"{pipeline.name}.{entry.group}", entry.where, detail, AREA)
    return out


def _port_parameters(
    pipeline: PlanningPipeline, key: str, source: str | None, model: SetupModel, log: PortLog
) -> tuple:
    """The pipeline's parameters the target reads that differ from what it writes by default."""
    distro = model.distro
    defaults = dict(effective_parameters(key, distro, ())) if model.target == Target.ROS2 else {}
    out = []
    for param in _namespace(pipeline, key, log):
        setting = f"{pipeline.name}.{param.key}"
        carried = _parameter(param, key, source, model, setting, log)
        if carried is None:
            continue
        name, value = carried
        if defaults.get(name) == value or (name not in defaults and _is_unset(value)):
            log.carried(setting, param.where, f"{short(param.value)} (the target's default)", AREA)
            continue
        log.carried(setting, param.where, short(param.value) if name == param.key else f"as {name}", AREA)
        out.append((name, value))
    return tuple(out)


def _is_unset(value: object) -> bool:
    return value == ()


def _parameter(
    param: Param, key: str, source: str | None, model: SetupModel, setting: str, log: PortLog
) -> tuple[str, object] | None:
    """(name, value) as the target's pipeline_parameters take it, else None (reported)."""
    distro = model.distro
    if model.target != Target.ROS2:
        log.dropped(
            setting, param.where, f"{short(param.value)}: noetic's pipelines keep MoveIt's defaults", AREA
        )
        return None
    if param.key.startswith("stomp_moveit."):
        detail = f"{short(param.value)}: STOMP never reads a stomp_moveit block (it declares its parameters in the pipeline's namespace); set pipeline_parameters.stomp by hand"
        log.dropped(setting, param.where, detail, AREA)
        return None
    name = param.key if parameter(key, distro, param.key) is not None else RENAMED.get(param.key, param.key)
    known = parameter(key, distro, name)
    if known is None:
        log.dropped(setting, param.where, f"{short(param.value)}: {distro}'s MoveIt does not read it", AREA)
        return None
    value = _value(param, name)
    if name in ADAPTER_KEYS and source != model.row.params:
        detail = f"{short(param.value)}: {distro}'s adapters are written (the adapter lists of {source or 'MoveIt 1'} and {distro} differ)"
        log.changed(setting, param.where, detail, AREA)
        return None
    problem = value_problem(known, value, int_as_double=False)
    if problem is not None:
        log.dropped(setting, param.where, f"{problem}: MoveIt would not load it", AREA)
        return None
    if (infinite := infinite_problem(value)) is not None:
        log.dropped(setting, param.where, f"{infinite}: not carried", AREA)
        return None
    return name, value


def _value(param: Param, name: str) -> object:
    """Humble's adapters are one space-separated string: the setup holds a list."""
    if name in ADAPTER_KEYS and isinstance(param.value, str):
        return tuple(param.value.split())
    return param.value
