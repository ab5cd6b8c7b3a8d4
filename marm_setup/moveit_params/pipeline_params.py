"""The parameters MoveIt 2 reads in a planning pipeline's namespace, per distro, as MoveIt's
declared-parameter tables hold them (data/<family>.yaml, built by regenerate.py from the pinned
MoveIt sources: names, types, bounds, defaults, source lines); marm-setup's defaults; and the
check of a setup's `pipeline_parameters` (unknown names are errors naming the valid ones).

A table row belongs to a pipeline's namespace when its name starts with `<pipeline>.`, or, for a
planner that reads a fixed namespace (CHOMP reads `chomp.<name>` whatever its pipeline's name:
chomp_interface.cpp, humble l.50-80, jazzy l.57-87), with that planner's namespace. Whose
parameter it is shows in the source file that declares or reads it: a file of a planner's
(moveit_planners/<planner>/) is read only in that planner's pipelines, any other (the
PlanningPipeline, its adapters, move_group) in every pipeline.
- Humble reads with rclcpp's typed getters, which throw "expected [double] got [integer]" on a
  value of another type: PlanningPipeline's `planning_plugin` and `request_adapters` (ONE
  space-separated string), its adapters' settings (PlanningRequestAdapter::getParam), CHOMP's;
  these rows are curated.yaml's, each citing the line that reads it.
- Jazzy declares them with generate_parameter_library (PlanningPipeline, its request and
  response adapters, STOMP's res/stomp_moveit.yaml), which refuses an override of another type or
  out of its bounds; regenerate.py reads those files as data (gpl.py). STOMP's root key
  `stomp_moveit` is the C++ namespace of the generated code, not part of a parameter's name: a
  `stomp_moveit:` block under the pipeline (MoveIt's own example configs write one) is never read.
- STOMP is in no Humble binary (moveit2's humble branch has no moveit_planners/stomp): a Humble
  user builds it from the newer source, whose declarations the jazzy table holds.
- move_group's capabilities: Jazzy reads `<pipeline>.capabilities` (move_group.cpp l.166);
  Humble looks them up as "planning_pipelines/<name>/capabilities", no valid ROS 2 parameter name
  (same file, humble l.151; moveit/moveit2#1393), and reads only the top-level `capabilities`
  string (l.139): marm-setup takes a pipeline's capabilities and writes them there.
- Pilz reads nothing in its namespace but its plugin and adapters; MoveIt's own default config
  writes `default_planner_config: PTP` (moveit_configs_utils/default_configs/
  pilz_industrial_motion_planner_planning.yaml, humble l.3, jazzy l.3), and so does marm-setup.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from functools import cache

from marm_setup.moveit_params.tables import LOGS, THROWS, ParamRow, load_table
from marm_setup.moveit_params.vocabulary import PIPELINES
from marm_setup.ros import DISTROS, distro_row

# a value of a planning pipeline parameter (`value_problem` checks it against its type)
PipelineParameterValue = float | int | bool | str | tuple[str, ...]

DOUBLE, INT, BOOL, STRING, STRINGS = "double", "int", "bool", "string", "string list"
# a table row's type -> the setup's
TYPES = {"double": DOUBLE, "int": INT, "bool": BOOL, "string": STRING, "string_array": STRINGS}


@dataclass(frozen=True, slots=True)
class PipelineParameter:
    """One parameter of a pipeline's namespace (`totg.path_tolerance`: in a sub-namespace)."""

    name: str
    type: str
    minimum: float | None = None  # generate_parameter_library `gt_eq`: below it the planner fails
    maximum: float | None = None  # ... `lt_eq`: above it
    choices: tuple[str, ...] = ()  # values MoveIt takes (another: it logs an error, uses its default)
    default: PipelineParameterValue | None = None  # MoveIt's, where it declares one
    source: str = ""  # MoveIt's file:line at the table's pinned commit (marm-setup's own: its reason)
    on_wrong: str = THROWS  # what MoveIt does with a value of another type or out of its bounds
    namespace: str = ""  # where MoveIt reads it whatever the pipeline's name (CHOMP: chomp)


PLACEHOLDER = "<pipeline>."
# where each planner's code lives in moveit/moveit2 (a row's source file shows whose it is)
PLANNER_SOURCES = {
    "ompl": "moveit_planners/ompl/",
    "chomp": "moveit_planners/chomp/",
    "stomp": "moveit_planners/stomp/",
    "pilz": "moveit_planners/pilz_industrial_motion_planner/",
}
MOVE_GROUP_SOURCES = "moveit_ros/move_group/"
# the adapter lists: the setup lists them, whichever distro (Humble's template joins them into
# the one string its PlanningPipeline reads)
ADAPTER_LISTS = frozenset({"request_adapters", "response_adapters"})
# keys a pipeline's namespace holds that are not settings of it: the plugin, OMPL's planner list
STRUCTURE_KEYS = frozenset({"planning_plugin", "planning_plugins", "planner_configs"})
# marm-setup's own parameters of a pipeline, which no MoveIt row declares: per parameter format,
# every pipeline's; per planner, that planner's
OWN_COMMON = {
    "humble": (
        PipelineParameter(
            "capabilities", STRING, source="marm-setup writes them into move_group's top-level capabilities"
        ),
    ),
}
OWN_PLANNER = {
    "pilz": (
        PipelineParameter(
            "default_planner_config",
            STRING,
            source="moveit_configs_utils/default_configs/pilz_industrial_motion_planner_planning.yaml:3",
        ),
    ),
}
# per parameter format: the prefixes of the adapter plugins its MoveIt exports
# (planning_request_adapters_plugin_description.xml and, Jazzy on,
# planning_response_adapters_plugin_description.xml): a name of another format's cannot be loaded
ADAPTER_FAMILIES = {r.params: r.adapter_families for r in DISTROS.values() if r.adapter_families}


def parameter_of(row: ParamRow, name: str, namespace: str = "") -> PipelineParameter:
    """A table row as the parameter `name` of a pipeline's namespace (`namespace`: the one MoveIt
    reads it in whatever the pipeline's name, CHOMP's `chomp`)."""
    args = dict(row.validation)
    choices = args.get("one_of", ())
    return PipelineParameter(
        name,
        STRINGS if name in ADAPTER_LISTS else TYPES[row.type],
        minimum=_bound(args, "gt_eq"),
        maximum=_bound(args, "lt_eq"),
        choices=tuple(choices[0]) if choices else (),
        default=row.default,  # type: ignore[arg-type]
        source=row.source,
        on_wrong=row.on_wrong,
        namespace=namespace,
    )


def _bound(args: dict[str, tuple], validator: str) -> float | None:
    return float(args[validator][0]) if args.get(validator) else None


def _table_family(pipeline: str, distro: str) -> str:
    """The table holding `pipeline`'s planner rows on `distro`: the distro's, but the jazzy one
    for a planner its binaries lack (built from moveit2's newer source)."""
    row = distro_row(distro)
    return "jazzy" if pipeline in row.planners_from_source else row.params


def _in_namespace(row: ParamRow, pipeline: str) -> tuple[str, str] | None:
    """The row's name inside the namespace of a `pipeline` pipeline and the fixed namespace MoveIt
    reads it in ('' for the pipeline's own); None: not in it, or not a setting of it."""
    planner = planner_of(row)
    if planner not in (None, pipeline):
        return None
    fixed = PIPELINES[planner].namespace if planner else ""
    if row.name.startswith(PLACEHOLDER):
        name, fixed = row.name[len(PLACEHOLDER) :], ""
    elif fixed and row.name.startswith(f"{fixed}."):
        name = row.name[len(fixed) + 1 :]
    else:
        return None
    return None if name in STRUCTURE_KEYS else (name, fixed)


def planner_of(row: ParamRow) -> str | None:
    """The planner (setup name) whose code declares or reads the row (None: no planner's)."""
    return next((k for k, path in PLANNER_SOURCES.items() if row.source.startswith(path)), None)


def _source_order(row: ParamRow) -> tuple[bool, str, int]:
    """The pipeline's and its planner's files first (read as the pipeline loads), move_group's
    after (its capabilities, read once the pipelines are built: configureCapabilities); by file,
    then line."""
    path, _, line = row.source.rpartition(":")
    return path.startswith(MOVE_GROUP_SOURCES), path, int(line) if line.isdigit() else 0


def _rows(family: str, pipeline: str, *, planner: bool) -> tuple[PipelineParameter, ...]:
    """The rows of the family's table in a `pipeline` pipeline's namespace, the planner's own or
    every pipeline's, in the order MoveIt's sources list them."""
    rows = sorted(load_table(family).rows("move_group"), key=_source_order)
    out = []
    for row in rows:
        found = _in_namespace(row, pipeline)
        if found is not None and (planner_of(row) is not None) == planner:
            out.append(parameter_of(row, *found))
    return tuple(out)


# -- defaults ------------------------------------------------------------------------------------

PILZ_CAPABILITIES = "pilz_industrial_motion_planner/MoveGroupSequenceAction pilz_industrial_motion_planner/MoveGroupSequenceService"
# CHOMP's own fallbacks (the table's defaults: chomp_interface.cpp get_parameter_or), written out
CHOMP_DEFAULTS = (
    ("planning_time_limit", 10.0), ("max_iterations", 200), ("max_iterations_after_collision_free", 5),
    ("smoothness_cost_weight", 0.1), ("obstacle_cost_weight", 1.0), ("learning_rate", 0.01),
    ("smoothness_cost_velocity", 0.0), ("smoothness_cost_acceleration", 1.0), ("smoothness_cost_jerk", 0.0),
    ("ridge_factor", 0.0), ("use_pseudo_inverse", False), ("pseudo_inverse_ridge_factor", 1.0e-4),
    ("joint_update_limit", 0.1), ("collision_clearance", 0.2), ("collision_threshold", 0.07),
    ("use_stochastic_descent", True), ("enable_failure_recovery", False), ("max_recovery_attempts", 5),
)  # fmt: skip
# MoveIt's default STOMP settings (moveit_configs_utils/default_configs/stomp_planning.yaml, jazzy)
STOMP_DEFAULTS = (
    ("num_timesteps", 60), ("num_iterations", 40), ("num_iterations_after_valid", 0), ("num_rollouts", 30),
    ("max_rollouts", 30), ("exponentiated_cost_sensitivity", 0.8), ("control_cost_weight", 0.1), ("delta_t", 0.1),
)  # fmt: skip
# What marm-setup writes where the setup gives nothing: the distro's adapter defaults (its row,
# marm_setup.ros DISTROS `adapter_defaults`), then the planner's.
PLANNER_DEFAULTS: dict[str, tuple[tuple[str, PipelineParameterValue], ...]] = {
    "chomp": CHOMP_DEFAULTS,
    "stomp": STOMP_DEFAULTS,
    "pilz": (("capabilities", PILZ_CAPABILITIES), ("default_planner_config", "PTP")),
}


def defaults(pipeline: str, distro: str) -> tuple[tuple[str, PipelineParameterValue], ...]:
    """marm-setup's parameters for `pipeline` on `distro` where the setup gives none."""
    return (*distro_row(distro).adapters(pipeline), *PLANNER_DEFAULTS.get(pipeline, ()))


def parameter_format(distro: str) -> str:
    """The MoveIt parameter format `distro` reads (its row's `params`); InputError when unknown."""
    return distro_row(distro).params


@cache
def known_parameters(pipeline: str, distro: str) -> tuple[PipelineParameter, ...]:
    """The parameters `distro`'s MoveIt reads in the namespace of a pipeline (a setup name):
    every pipeline's, then the planner's, each in its sources' order, marm-setup's own after."""
    params = parameter_format(distro)
    return (
        *_rows(params, pipeline, planner=False),
        *OWN_COMMON.get(params, ()),
        *_rows(_table_family(pipeline, distro), pipeline, planner=True),
        *OWN_PLANNER.get(pipeline, ()),
    )


def parameter(pipeline: str, distro: str, name: str) -> PipelineParameter | None:
    return next((p for p in known_parameters(pipeline, distro) if p.name == name), None)


def effective_parameters(
    pipeline: str, distro: str, given: Iterable[tuple[str, PipelineParameterValue]]
) -> tuple[tuple[str, PipelineParameterValue], ...]:
    """marm-setup's defaults for the pipeline overlaid with the setup's values that `distro`
    reads, in the order MoveIt's sources list them; each value of its parameter's type."""
    values = dict(defaults(pipeline, distro))
    values.update((n, v) for n, v in given if parameter(pipeline, distro, n) is not None)
    out = []
    for p in known_parameters(pipeline, distro):
        if p.name in values:
            value = values[p.name]
            out.append(
                (p.name, float(value) if p.type == DOUBLE and isinstance(value, int | float) else value)
            )
    return tuple(out)


# -- checks --------------------------------------------------------------------------------------


def parameter_problem(pipeline: str, distro: str, name: str, value: object) -> str | None:
    """Why a setup's parameter is an error on `distro` (None: it is not; a name only another
    distro's MoveIt reads is left out with a warning)."""
    known = parameter(pipeline, distro, name)
    if known is None:
        if other_distros_reading(pipeline, distro, name):
            return None
        return (
            f"unknown parameter '{name}' of pipeline {pipeline} ({unknown_name_hint(pipeline, distro, name)})"
        )
    problem = value_problem(known, value) or infinite_problem(value)
    if problem is None and known.name.endswith("_adapters") and isinstance(value, tuple | list):
        problem = next(filter(None, (adapter_problem(str(a), distro) for a in value)), None)
    return problem


def infinite_problem(value: object) -> str | None:
    """Why a setup cannot hold `value`: a NaN or infinite number (marm-setup writes finite numbers
    only; templating.fmt_float), else None."""
    if isinstance(value, float) and not math.isfinite(value):
        return f"must be a finite number, got {value!r} (marm-setup writes finite numbers only)"
    return None


def value_problem(p: PipelineParameter, value: object, *, int_as_double: bool = True) -> str | None:
    """Why `value` does not fit `p` as MoveIt reads it (None: it does). An integer passes for a
    double where marm-setup writes it (`int_as_double`); in a parameter file MoveIt refuses it."""
    return kind_problem(p, value, int_as_double=int_as_double) or bounds_problem(p, value)


def kind_problem(p: PipelineParameter, value: object, *, int_as_double: bool = True) -> str | None:
    """Why `value` is not of `p`'s type (None: it is)."""
    number = isinstance(value, int | float) and not isinstance(value, bool)
    expected = {
        DOUBLE: isinstance(value, float) or (number and int_as_double),
        INT: isinstance(value, int) and not isinstance(value, bool),
        BOOL: isinstance(value, bool),
        STRING: isinstance(value, str),
        STRINGS: isinstance(value, list | tuple) and all(isinstance(v, str) for v in value),
    }[p.type]
    if expected:
        return None
    article = "an" if p.type[0] in "aeiou" else "a"
    return f"expected {article} {p.type}, got {value!r}"


def bounds_problem(p: PipelineParameter, value: object) -> str | None:
    """Why `value` (of `p`'s type) is outside what MoveIt takes: its declared gt_eq, lt_eq,
    one_of (None: it is not)."""
    number = isinstance(value, int | float) and not isinstance(value, bool)
    if p.minimum is not None and number and value < p.minimum:  # type: ignore[operator]
        return f"must be at least {p.minimum:g}, got {value!r}"
    if p.maximum is not None and number and value > p.maximum:  # type: ignore[operator]
        return f"must be at most {p.maximum:g}, got {value!r}"
    if p.choices and value not in p.choices:
        fallback = p.default if p.default is not None else p.choices[0]
        does = f" (MoveIt logs an error and uses {fallback})" if p.on_wrong == LOGS else ""
        return f"'{value}' is not one of: {', '.join(p.choices)}{does}"
    return None


def adapter_problem(name: str, distro: str) -> str | None:
    """Why `distro`'s MoveIt cannot load the adapter plugin `name` (None: it can, or it is a
    plugin of the user's own)."""
    mine = distro_row(distro).adapter_families
    other = next(
        (
            r.name
            for r in DISTROS.values()
            if r.adapter_families and r.adapter_families != mine and name.startswith(r.adapter_families)
        ),
        None,
    )
    if other is None:
        return None
    return f"'{name}' is {other.capitalize()}'s adapter: {distro.capitalize()} has none such (its adapters: {' '.join(mine)}...)"


def unknown_name_hint(pipeline: str, distro: str, name: str) -> str:
    """The valid names, and what a `stomp_moveit.` prefix means."""
    valid = ", ".join(p.name for p in known_parameters(pipeline, distro))
    if name.startswith("stomp_moveit."):
        return (
            f"STOMP declares its parameters in the pipeline's namespace: write {name.split('.', 1)[1]} "
            "(the stomp_moveit key of its stomp_moveit.yaml is the C++ namespace of its code); valid: "
            + valid
        )
    return f"valid on {distro}: {valid}"


def other_distros_reading(pipeline: str, distro: str, name: str) -> tuple[str, ...]:
    """The other ROS 2 parameter formats whose MoveIt reads `name` in this pipeline's
    namespace, each named by its first distro (`jazzy` for Jazzy, Kilted and Rolling)."""
    mine = parameter_format(distro)
    first: dict[str, str] = {}
    for r in DISTROS.values():
        first.setdefault(r.params, r.name)
    return tuple(
        d
        for f, d in first.items()
        if f in ADAPTER_FAMILIES and f != mine and parameter(pipeline, d, name) is not None
    )


def flatten(data: dict, prefix: str = "") -> Iterator[tuple[str, object]]:
    """(dotted name, value) of every leaf of a parameter mapping."""
    for key, value in data.items():
        name = f"{prefix}{key}"
        if isinstance(value, dict):
            yield from flatten(value, f"{name}.")
        else:
            yield name, value
