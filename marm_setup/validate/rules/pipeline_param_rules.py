"""A planning pipeline's parameters as its distro's MoveIt reads them (ROS 2 packages whose
distro is known; names, types, bounds and sources: MoveIt's declared-parameter tables,
moveit_params/data/<family>.yaml, as moveit_params/pipeline_params.py reads them).

- A value of another type than MoveIt reads is an error: Humble's rclcpp typed getters throw
  "expected [double] got [integer]" (its adapters' getParam, planning_request_adapter.h l.99;
  CHOMP's get_parameter_or), Jazzy's generate_parameter_library declarations refuse an override
  of another type, and STOMP's refuses one below its `gt_eq` bounds (res/stomp_moveit.yaml): the
  pipeline or move_group fails to load.
- A CHOMP trajectory_initialization_method it does not know: a warning (CHOMP logs an error and
  uses quintic-spline, chomp_interface.cpp humble l.71-77).
- A `stomp_moveit:` block in a STOMP pipeline: a warning, STOMP never reads it (its parameters
  are declared in the pipeline's namespace).
- A name only the other distro reads, or, where every adapter is MoveIt's own (an adapter of the
  user's own may read any name), a name MoveIt reads nowhere there: a warning. So is a CHOMP
  setting in a pipeline not named chomp: CHOMP reads `chomp.<name>` whatever its pipeline's name
  (chomp_interface.cpp humble l.50-80, jazzy l.57-87), so the value is never read.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import TYPE_CHECKING

from marm_setup.findings import Finding, error, warning
from marm_setup.moveit_params import (
    ADAPTER_FAMILIES,
    LOGS,
    PIPELINES,
    STRUCTURE_KEYS,
    bounds_problem,
    flatten,
    kind_problem,
    known_parameters,
    other_distros_reading,
    parameter,
    unknown_name_hint,
)

if TYPE_CHECKING:
    from marm_setup.package import PlanningPipeline

# checked by distro_rules' format rules
FORMAT_KEYS = frozenset({"request_adapters", "response_adapters", "capabilities"})


def check_pipeline_parameters(pipeline: PlanningPipeline, distro: str) -> list[Finding]:
    """The parameters of one pipeline (a known planner's) of a package for `distro`."""
    data = pipeline.data if pipeline.is_mapping else None
    key = planner_key(data) if data is not None else None
    if data is None or key is None:
        return []
    file = pipeline.where.file
    out: list[Finding] = []
    for name, value in _parameters(data, key):
        where = pipeline.where.child(*name.split(".")).element
        if name.startswith("stomp_moveit."):
            msg = f"STOMP never reads {name}: it declares {name.split('.', 1)[1]} in the pipeline's namespace"
            out.append(warning("pipeline.stomp-namespace", file, where, msg, f"move it up one level ({key})"))
            continue
        unread = _fixed_namespace(file, key, distro, name, where, pipeline.name)
        out += unread or _check_one(file, key, distro, name, value, where, own_adapters_only(data))
    return out


def _fixed_namespace(
    file: str, key: str, distro: str, name: str, where: str, namespace: str
) -> list[Finding]:
    """A parameter the planner reads in a namespace of its own whatever its pipeline's name
    (CHOMP: `chomp.<name>`, chomp_interface.cpp humble l.50-80, jazzy l.57-87), given in a
    pipeline of another name: never read, the planner keeps its default."""
    known = parameter(key, distro, name)
    if known is None or not known.namespace or known.namespace == namespace:
        return []
    msg = (
        f"{key.upper()} reads {known.namespace}.{name} whatever its pipeline's name: "
        f"{namespace}.{name} is never read (it uses {known.default!r})"
    )
    hint = (
        f"give it under {known.namespace}: at move_group's top level, or name the pipeline {known.namespace}"
    )
    return [warning("pipeline.unknown-parameter", file, where, msg, hint)]


def _check_one(
    file: str, key: str, distro: str, name: str, value: object, where: str, all_moveit: bool
) -> list[Finding]:
    known = parameter(key, distro, name)
    if known is None:
        others = other_distros_reading(key, distro, name)
        if others:
            msg = f"{distro}'s MoveIt does not read {name} ({', '.join(others)}'s does)"
            return [warning("pipeline.other-distro-parameter", file, where, msg)]
        if not all_moveit:
            return []
        msg = f"MoveIt reads no {name} in a {key} pipeline's namespace on {distro}"
        return [warning("pipeline.unknown-parameter", file, where, msg, unknown_name_hint(key, distro, name))]
    problem = kind_problem(known, value, int_as_double=False)
    if problem is None and (problem := bounds_problem(known, value)) is not None and known.on_wrong == LOGS:
        return [warning("pipeline.parameter-value", file, where, problem)]  # MoveIt takes its default
    if problem is None:
        return []
    return [error("pipeline.parameter-type", file, where, f"{problem}: the pipeline fails to load")]


def _parameters(data: dict, key: str) -> Iterator[tuple[str, object]]:
    """(dotted name, value) of the settings in a pipeline's namespace: not its plugin, adapters,
    OMPL's planner configurations or its groups' mappings."""
    for name, value in data.items():
        if name in STRUCTURE_KEYS or name in FORMAT_KEYS:
            continue
        if isinstance(value, dict):
            if name == "stomp_moveit" or any(n.startswith(f"{name}.") for n in _all_names(key)):
                yield from flatten(value, f"{name}.")
            continue  # an OMPL group's settings
        yield str(name), value


def _all_names(key: str) -> set[str]:
    """The names any ROS 2 distro's MoveIt reads in a `key` pipeline's namespace."""
    return {p.name for distro in ADAPTER_FAMILIES for p in known_parameters(key, distro)}


def planner_key(data: dict) -> str | None:
    """The setup name of the pipeline's planner (ompl, chomp, stomp, pilz) from its plugin."""
    plugins = data.get("planning_plugins") or [data.get("planning_plugin")]
    plugin = plugins[0] if isinstance(plugins, list) and plugins else None
    return next((k for k, p in PIPELINES.items() if p.plugin_ros2 == plugin), None)


def own_adapters_only(data: dict) -> bool:
    """Every adapter of the pipeline is one of MoveIt's own (no plugin of the user's reads names)."""
    names: list[str] = []
    for key in ("request_adapters", "response_adapters"):
        value = data.get(key)
        names += value.split() if isinstance(value, str) else [str(v) for v in value or []]
    families = tuple(f for fam in ADAPTER_FAMILIES.values() for f in fam)
    return all(n.startswith(families) for n in names)
