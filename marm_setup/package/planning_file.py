"""Planning pipeline files (`<pipeline>_planning.yaml`, MoveIt 2's `planning_pipelines`): the
pipeline's settings, OMPL's planner configurations and the per-group entries."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from marm_setup.package.where import Located, Param, Where, freeze, thaw

# Keys of a pipeline file that are the pipeline's own settings, never a group (`totg`: Jazzy's
# AddTimeOptimalParameterization response adapter reads its parameters in that sub-namespace,
# moveit2 jazzy planning_response_adapter_plugins/res/default_response_adapter_params.yaml).
GLOBAL_KEYS = frozenset(
    {
        "totg",
        "planner_configs",
        "planning_plugin",
        "planning_plugins",
        "request_adapters",
        "response_adapters",
        "start_state_max_bounds_error",
        "jiggle_fraction",
        "max_sampling_attempts",
    }
)


# The planner configurations MoveItConfigsBuilder adds to an ompl pipeline whose file has no
# `planner_configs` (moveit_configs_utils moveit_configs_builder.py planning_pipelines, humble
# l.475-479, the same on jazzy; default_configs/ompl_defaults.yaml, identical on both): each
# `<name>` of type `geometric::<name>`.
BUILDER_OMPL_DEFAULTS_FILE = "moveit_configs_utils/default_configs/ompl_defaults.yaml"
BUILDER_OMPL_DEFAULTS = [
    "AnytimePathShortening",
    "SBL",
    "EST",
    "LBKPIECE",
    "BKPIECE",
    "KPIECE",
    "RRT",
    "RRTConnect",
    "RRTstar",
    "TRRT",
    "PRM",
    "PRMstar",
    "FMT",
    "BFMT",
    "PDST",
    "STRIDE",
    "BiTRRT",
    "LBTRRT",
    "BiEST",
    "ProjEST",
    "LazyPRM",
    "LazyPRMstar",
    "SPARS",
    "SPARStwo",
]


@dataclass(frozen=True, slots=True)
class PlannerConfig:
    """An OMPL `planner_configs` entry: its type (`geometric::RRTConnect`) and parameters;
    `params` None when the entry is not a mapping."""

    name: str
    where: Where
    params: tuple[Param, ...] | None

    @property
    def type(self) -> str | None:
        found = next((p for p in self.params or () if p.key == "type"), None)
        return None if found is None or found.value is None else str(found.value)

    @property
    def parameters(self) -> tuple[Param, ...]:
        """Every key but `type`."""
        return tuple(p for p in self.params or () if p.key != "type")


@dataclass(frozen=True, slots=True)
class GroupPlanning:
    """A group's entry: default_planner_config, planner_configs, projection_evaluator, ..."""

    group: str
    where: Where
    params: tuple[Param, ...]

    def param(self, key: str) -> Param | None:
        return next((p for p in self.params if p.key == key), None)


@dataclass(frozen=True, slots=True)
class PlanningPipeline:
    """One pipeline's parameters; `is_mapping` false when the file is not a mapping, and
    `planner_configs` None when that key is not a mapping."""

    name: str
    where: Where
    is_mapping: bool
    planner_configs: tuple[PlannerConfig, ...] | None = ()
    groups: tuple[GroupPlanning, ...] = ()
    settings: tuple[Param, ...] = ()  # every key that is not a group (planning_plugin, adapters, ...)

    def setting(self, key: str) -> Param | None:
        return next((p for p in self.settings if p.key == key), None)

    @property
    def data(self) -> dict[str, Any]:
        """The pipeline's namespace as YAML gave it (settings and group entries; not planner_configs)."""
        out = {p.key: thaw(p.value) for p in self.settings}
        out.update({g.group: {p.key: thaw(p.value) for p in g.params} for g in self.groups})
        return out

    def config(self, name: str) -> PlannerConfig | None:
        return next((c for c in self.planner_configs or () if c.name == name), None)

    def group(self, name: str) -> GroupPlanning | None:
        return next((g for g in self.groups if g.group == name), None)


def read_pipeline(name: str, doc: Located) -> PlanningPipeline:
    if not doc.is_mapping:
        return PlanningPipeline(name, doc.where, False)
    configs = doc.get("planner_configs")
    planner_configs: tuple[PlannerConfig, ...] | None = ()
    if configs.is_mapping:
        planner_configs = tuple(
            PlannerConfig(n, c.where, c.params() if c.is_mapping else None) for n, c in configs.items()
        )
    elif configs.data:  # present but not a mapping
        planner_configs = None
    groups, settings = [], []
    for key, value in doc.items():
        if key not in GLOBAL_KEYS and value.is_mapping:
            groups.append(GroupPlanning(key, value.where, value.params(flat=False)))
        elif key != "planner_configs":
            settings.append(Param(key, freeze(value.data), value.where))
    return PlanningPipeline(name, doc.where, True, planner_configs, tuple(groups), tuple(settings))


def with_builder_ompl_defaults(pipeline: PlanningPipeline) -> PlanningPipeline:
    """The ompl pipeline MoveItConfigsBuilder hands move_group from a file without
    `planner_configs`: the file's, plus BUILDER_OMPL_DEFAULTS (from moveit_configs_utils' file)."""
    from dataclasses import replace

    where = Where(BUILDER_OMPL_DEFAULTS_FILE, ("planner_configs",))
    configs = tuple(
        PlannerConfig(
            name, where.child(name), (Param("type", f"geometric::{name}", where.child(name, "type")),)
        )
        for name in BUILDER_OMPL_DEFAULTS
    )
    return replace(pipeline, planner_configs=configs)
