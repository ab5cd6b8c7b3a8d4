"""ompl_planning.yaml: groups exist, referenced planner configs exist, default planner config exists.

A group the SRDF lacks is only a warning: OMPL reads the file per group of the robot model and
never looks at other keys (moveit/moveit `moveit_planners/ompl/ompl_interface/src/
ompl_interface.cpp` l.176 and moveit/moveit2 the same file l.164, `loadPlannerConfigurations`
loops over `robot_model_->getJointModelGroupNames()`); such a key is a leftover or a typo.
"""

from __future__ import annotations

import difflib
from collections.abc import Collection
from typing import TYPE_CHECKING

from marm_setup.findings import Finding, Location, error, warning
from marm_setup.package import FrozenMapping, GroupPlanning, PlanningPipeline

if TYPE_CHECKING:
    from marm_setup.setup import Srdf


def check_ompl(
    ompl: PlanningPipeline, srdf: Srdf, planners: Collection[str] = (), *, moveit1: bool = False
) -> list[Finding]:
    """Every rule on an OMPL pipeline (`{planner_configs: {...}, <group>: {...}}`); `planners`:
    the planner types this MoveIt's OMPL registers (none given: not checked); `moveit1`: MoveIt 1
    reads the file."""
    file = ompl.where.file
    if not ompl.is_mapping:
        return [error("ompl.malformed", file, ompl.where.element, "expected a mapping")]
    if ompl.planner_configs is None:
        return [
            error("ompl.malformed", file, ompl.where.child("planner_configs").element, "expected a mapping")
        ]
    groups = {g.name for g in srdf.groups}
    configs = {c.name for c in ompl.planner_configs}
    out: list[Finding] = []
    for entry in sorted(ompl.groups, key=lambda g: g.group):
        if entry.group not in groups:
            known = ", ".join(sorted(groups)) or "none"
            msg = f"unknown group '{entry.group}' (groups: {known}): OMPL never reads it"
            at = Location("ompl", entry.group, ("group", entry.group))
            hint = "a leftover or a typo: rename it to a group of the SRDF, or remove it"
            out.append(warning("ompl.unknown-group", file, entry.where.element, msg, hint, at=at))
            continue
        out += _check_group(file, entry, configs, moveit1)
    return out + (_check_types(ompl, groups, planners) if planners else [])


def _check_types(ompl: PlanningPipeline, groups: set[str], planners: Collection[str]) -> list[Finding]:
    """A planner config a group uses whose `type` OMPL does not register: planning with it fails
    ("Unknown planner", planning_context_manager.cpp plannerSelector; the registered types are
    the tables' `ompl_planners`). An error for a group's default config, else a warning."""
    used = [g for g in ompl.groups if g.group in groups]
    defaults = {str(p.value) for g in used if (p := g.param("default_planner_config")) is not None}
    listed = {
        str(name)
        for g in used
        if (p := g.param("planner_configs")) is not None and isinstance(p.value, tuple)
        for name in p.value
    }
    out: list[Finding] = []
    for config in ompl.planner_configs or ():
        if config.name not in defaults | listed or config.type is None or config.type in planners:
            continue
        close = difflib.get_close_matches(config.type, sorted(planners), n=1)
        hint = f"did you mean {close[0]}?" if close else "known: " + ", ".join(sorted(planners)[:8])
        element = config.where.child("type").element
        if config.name in defaults:
            msg = (
                f"planner type '{config.type}' is not OMPL's: planning with the group's default config fails"
            )
            out.append(error("ompl.unknown-planner-type", ompl.where.file, element, msg, hint))
        else:
            msg = f"planner type '{config.type}' is not OMPL's: planning with config '{config.name}' fails"
            out.append(warning("ompl.unknown-planner-type", ompl.where.file, element, msg, hint))
    return out


def _check_group(file: str, entry: GroupPlanning, configs: set[str], moveit1: bool) -> list[Finding]:
    out: list[Finding] = []
    where = entry.where.element
    param = entry.param("planner_configs")
    listed = param.value if param is not None and param.value else ()
    if not isinstance(listed, tuple) or isinstance(listed, FrozenMapping):
        listed = ()
        out.append(error("ompl.malformed", file, f"{where}.planner_configs", "expected a list"))
    for name in map(str, listed):
        if name not in configs:
            msg = f"planner config '{name}' is not defined under planner_configs"
            out.append(error("ompl.unknown-planner-config", file, f"{where}.planner_configs", msg))
    default = entry.param("default_planner_config")
    if default is not None and str(default.value) not in configs and not (moveit1 and default.value == ""):
        # MoveIt 1 reads '' as `planner_configs/`, which roscpp cleans to the planner_configs map
        # itself (ros_comm names.cpp clean l.99-116, resolve l.177): loadPlannerConfiguration
        # finds it and logs nothing, and the group gets RRTConnect as with no key
        # (ompl_interface.cpp noetic l.135, l.227-237). MoveIt 2 lists `planner_configs.` + '',
        # finds nothing and logs the error (moveit2 ompl_interface.cpp l.132-138).
        # MoveIt logs "Could not find the planner configuration" and plans the group with
        # geometric::RRTConnect instead (ompl_interface.cpp noetic l.224-238, jazzy l.216-229)
        msg = (
            f"default_planner_config '{default.value}' is not defined under planner_configs: MoveIt logs "
            "an error and plans this group with RRTConnect instead"
        )
        hint = "known: " + ", ".join(sorted(configs)[:8]) if configs else ""
        out.append(
            warning("ompl.unknown-default-planner", file, f"{where}.default_planner_config", msg, hint)
        )
    return out
