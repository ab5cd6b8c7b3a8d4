"""Porting the OMPL defaults: each group's default planner, segment fraction and projection,
and the planner configurations (their parameters are OMPL's defaults in the new package)."""

from __future__ import annotations

from collections.abc import Callable, Iterable

from marm_setup.moveit_params import DEFAULT_PLANNER, OMPL_PLANNER_NAMES, OMPL_PLANNERS
from marm_setup.package import FrozenMapping, GroupPlanning, PlanningPipeline, Value
from marm_setup.port.kinematics import short, yaml_text
from marm_setup.port.port_log import PortLog
from marm_setup.setup import PlannerDefaults

OMPL_TYPES = {ompl_type: name for name, ompl_type in OMPL_PLANNERS}
GROUP_OMPL_KEYS = (
    "default_planner_config",
    "planner_configs",
    "longest_valid_segment_fraction",
    "projection_evaluator",
)


# -- OMPL ----------------------------------------------------------------------------------------


def port_planners(
    ompl: PlanningPipeline | None,
    groups: Iterable[str],
    projection: Callable[[str], str | None],
    log: PortLog,
) -> tuple[PlannerDefaults, ...]:
    """Per-group OMPL defaults; planner parameters and keys without a place are reported.
    `projection(group)` is the projection_evaluator the new package writes for a group."""
    if ompl is None:
        detail = f"no OMPL pipeline file: every group gets {DEFAULT_PLANNER} and OMPL's defaults"
        log.changed("planners", "", detail, "planners")
        return ()
    _report_configs(ompl, log)  # its settings: port.pipelines
    known = set(groups)
    out = []
    for entry in ompl.groups:
        if entry.group in known:
            out.append(_group_planner(entry, ompl, projection(entry.group), log))
        else:
            log.dropped(
                f"ompl.{entry.group}", entry.where, "no planning group of that name in the SRDF", "planners"
            )
    return tuple(sorted(out, key=lambda p: p.group))


def _report_configs(ompl: PlanningPipeline, log: PortLog) -> None:
    for config in ompl.planner_configs or ():
        setting = f"ompl.planner_configs.{config.name}"
        ours = OMPL_TYPES.get(str(config.type))
        params = ", ".join(f"{p.key}: {_value(p.value)}" for p in config.parameters)
        if ours is None:
            detail = f"{config.type}: not among the OMPL planners marm-setup writes ({', '.join(OMPL_PLANNER_NAMES)})"
            log.dropped(setting, config.where, detail, "planners")
        elif params:
            detail = f"{ours} is written with OMPL's defaults; its parameters are not carried ({params})"
            log.dropped(setting, config.where, detail, "planners")
        else:
            log.carried(setting, config.where, ours, "planners")


def _value(value: Value) -> str:
    if isinstance(value, FrozenMapping):
        return "{" + ", ".join(f"{k}: {_value(v)}" for k, v in value) + "}"
    return yaml_text(value)


def _group_planner(
    entry: GroupPlanning, ompl: PlanningPipeline, projection: str | None, log: PortLog
) -> PlannerDefaults:
    values: dict = {"group": entry.group}
    setting, src = f"planners[{entry.group}]", entry.where
    default = _default_planner(entry, ompl, setting, log)
    if default is not None:
        values["default_planner"] = default
    fraction = entry.param("longest_valid_segment_fraction")
    number = fraction.number if fraction is not None else None
    if number is not None and 0 < number <= 1:
        values["longest_valid_segment_fraction"] = number
        log.carried(f"{setting}.longest_valid_segment_fraction", src, f"{number:g}", "planners")
    if entry.param("planner_configs") is not None:
        detail = "every planner marm-setup writes is offered to the group"
        log.carried(f"{setting}.planner_configs", src, detail, "planners")
    _projection(entry, projection, setting, log)
    for param in entry.params:
        if param.key not in GROUP_OMPL_KEYS:
            detail = f"{short(param.value)}: marm_setup.yaml has no place for it; add it by hand"
            log.dropped(f"{setting}.{param.key}", src, detail, "planners")
    return PlannerDefaults(**values)


def _default_planner(entry: GroupPlanning, ompl: PlanningPipeline, setting: str, log: PortLog) -> str | None:
    """The group's default planner as one the new package writes, or None (the default one)."""
    default = entry.param("default_planner_config")
    if default is None:
        return None
    name = str(default.value)
    config = ompl.config(name)
    ompl_type = (config.type if config is not None else None) or f"geometric::{name}"
    ours = OMPL_TYPES.get(ompl_type)
    if ours is None:
        detail = f"{name} ({ompl_type}) is not written: {DEFAULT_PLANNER} instead"
        log.changed(f"{setting}.default_planner", entry.where, detail, "planners")
        return None
    log.carried(
        f"{setting}.default_planner", entry.where, ours if ours == name else f"{name} -> {ours}", "planners"
    )
    return ours


def _projection(entry: GroupPlanning, ours: str | None, setting: str, log: PortLog) -> None:
    """The new package writes `joints(<first two active joints>)`, as the Setup Assistant does."""
    given = entry.param("projection_evaluator")
    if given is None:
        return
    text = "".join(str(given.value).split())
    if ours is not None and text == ours:
        log.carried(f"{setting}.projection_evaluator", entry.where, str(given.value), "planners")
    else:
        written = (
            f"{ours} is written" if ours else "none is written (the group has fewer than two active joints)"
        )
        log.changed(
            f"{setting}.projection_evaluator",
            entry.where,
            f"{given.value}: {written}; set it by hand if it matters",
            "planners",
        )
