"""The parameters MoveIt 2 reads in a planning pipeline's namespace, per distro: names, types,
bounds and the source that reads them; marm-setup's defaults; and the check of a setup's
`pipeline_parameters` (unknown names are errors naming the valid ones).

Sources (moveit/moveit2 humble 2b2030dd, jazzy 4d841063; paths below moveit_ros/planning/ unless
given otherwise). Humble reads with rclcpp's typed getters, which throw "expected [double] got
[integer]" on a value of another type; Jazzy's generate_parameter_library declares each
parameter with its type and refuses an override of another type or out of its bounds.
- Humble's PlanningPipeline: `planning_plugin`, `request_adapters` as ONE space-separated string
  (planning_pipeline/src/planning_pipeline.cpp l.58-77). Its adapters read their parameters in
  the pipeline's namespace (planning_request_adapter.h l.99 getParam): AddTimeOptimalParameterization
  path_tolerance, resample_dt, min_angle_change (add_time_optimal_parameterization.cpp l.57-59);
  FixStartStateBounds start_state_max_bounds_error, start_state_max_dt (fix_start_state_bounds.cpp
  l.60-61, 202-203); FixStartStateCollision start_state_max_dt, jiggle_fraction,
  max_sampling_attempts (fix_start_state_collision.cpp l.60-62, 176-178); FixWorkspaceBounds
  default_workspace_bounds (fix_workspace_bounds.cpp l.56, 91).
- Jazzy's: planning_plugins, request_adapters, response_adapters, progress_topic
  (planning_pipeline/res/planning_pipeline_parameters.yaml l.2-20); its request adapters
  fix_start_state, default_workspace_bounds (planning_request_adapter_plugins/res/
  default_request_adapter_params.yaml l.3, 8), its response adapters totg.path_tolerance,
  totg.resample_dt, totg.min_angle_change, display_path_topic, display_contacts_topic
  (planning_response_adapter_plugins/res/default_response_adapter_params.yaml l.3-24).
- move_group's capabilities: Jazzy reads `<pipeline>.capabilities` (moveit_ros/move_group/src/
  move_group.cpp l.166); Humble looks them up as "planning_pipelines/<name>/capabilities", no
  valid ROS 2 parameter name (same file, humble l.151; moveit/moveit2#1393), and reads only the
  top-level `capabilities` string (l.139): marm-setup writes a pipeline's capabilities there.
- CHOMP reads `chomp.<name>` whatever its pipeline's name (moveit_planners/chomp/chomp_interface/
  src/chomp_interface.cpp humble l.50-80, jazzy l.57-87).
- STOMP (moveit_planners/stomp, Iron on; on Humble built from that source) declares its
  parameters directly in the pipeline's namespace: ParamListener(node, parameter_namespace)
  (stomp_moveit_planner_plugin.cpp l.72) over res/stomp_moveit.yaml l.2-60, whose root key
  `stomp_moveit` is the C++ namespace of the generated code, not part of a parameter's name
  (PickNikRobotics/generate_parameter_library parse_yaml.py: `nested_name_list[1:]`). A
  `stomp_moveit:` block under the pipeline (MoveIt's own example configs write one) is never read.
- Pilz reads nothing in its namespace but its plugin and adapters; MoveIt's own default config
  writes `default_planner_config: PTP` (moveit_configs_utils/default_configs/
  pilz_industrial_motion_planner_planning.yaml, humble l.3, jazzy l.3).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Iterator
from dataclasses import dataclass

from marm_setup.ros import DISTROS, distro_row

# a value of a planning pipeline parameter (`value_problem` checks it against its type)
PipelineParameterValue = float | int | bool | str | tuple[str, ...]

DOUBLE, INT, BOOL, STRING, STRINGS = "double", "int", "bool", "string", "string list"


@dataclass(frozen=True, slots=True)
class PipelineParameter:
    """One parameter of a pipeline's namespace (`totg.path_tolerance`: in a sub-namespace)."""

    name: str
    type: str
    minimum: float | None = None  # generate_parameter_library `gt_eq`: below it the planner fails
    choices: tuple[str, ...] = ()  # values MoveIt takes (another: it logs an error, uses its default)


def _params(type_: str, *names: str) -> tuple[PipelineParameter, ...]:
    return tuple(PipelineParameter(n, type_) for n in names)


HUMBLE_COMMON = (
    PipelineParameter("request_adapters", STRINGS),
    *_params(DOUBLE, "start_state_max_bounds_error", "start_state_max_dt", "jiggle_fraction"),
    PipelineParameter("max_sampling_attempts", INT),
    *_params(DOUBLE, "default_workspace_bounds", "path_tolerance", "resample_dt", "min_angle_change"),
    PipelineParameter("capabilities", STRING),
)
JAZZY_COMMON = (
    *_params(STRINGS, "request_adapters", "response_adapters"),
    PipelineParameter("progress_topic", STRING),
    PipelineParameter("fix_start_state", BOOL),
    *_params(DOUBLE, "default_workspace_bounds", "totg.path_tolerance", "totg.resample_dt", "totg.min_angle_change"),
    *_params(STRING, "display_path_topic", "display_contacts_topic", "capabilities"),
)  # fmt: skip
CHOMP = (
    PipelineParameter("planning_time_limit", DOUBLE),
    *_params(INT, "max_iterations", "max_iterations_after_collision_free"),
    *_params(DOUBLE, "smoothness_cost_weight", "obstacle_cost_weight", "learning_rate", "smoothness_cost_velocity",
             "smoothness_cost_acceleration", "smoothness_cost_jerk", "ridge_factor"),
    PipelineParameter("use_pseudo_inverse", BOOL),
    *_params(DOUBLE, "pseudo_inverse_ridge_factor", "joint_update_limit", "collision_clearance", "collision_threshold"),
    PipelineParameter("use_stochastic_descent", BOOL),
    # chomp_motion_planner chomp_parameters.cpp VALID_INITIALIZATION_METHODS
    PipelineParameter("trajectory_initialization_method", STRING,
                      choices=("quintic-spline", "linear", "cubic", "fillTrajectory")),
    PipelineParameter("enable_failure_recovery", BOOL),
    PipelineParameter("max_recovery_attempts", INT),
)  # fmt: skip
STOMP = (
    PipelineParameter("num_iterations", INT, 1),
    PipelineParameter("num_iterations_after_valid", INT, 0),
    PipelineParameter("num_rollouts", INT, 1),
    PipelineParameter("max_rollouts", INT, 1),
    PipelineParameter("num_timesteps", INT, 3),
    PipelineParameter("exponentiated_cost_sensitivity", DOUBLE, 0.0),
    *_params(DOUBLE, "control_cost_weight", "delta_t"),
    PipelineParameter("path_marker_topic", STRING),
)
PLANNER_PARAMS = {
    "ompl": (),
    "chomp": CHOMP,
    "stomp": STOMP,
    "pilz": (PipelineParameter("default_planner_config", STRING),),
}
# per MoveIt parameter format (a DistroRow's `params`)
COMMON = {"humble": HUMBLE_COMMON, "jazzy": JAZZY_COMMON}
# per parameter format: the prefixes of the adapter plugins its MoveIt exports
# (planning_request_adapters_plugin_description.xml and, Jazzy on,
# planning_response_adapters_plugin_description.xml): a name of another format's cannot be loaded
ADAPTER_FAMILIES = {r.params: r.adapter_families for r in DISTROS.values() if r.adapter_families}
# keys a pipeline's namespace holds that are not settings of it: the plugin, OMPL's planner list
STRUCTURE_KEYS = frozenset({"planning_plugin", "planning_plugins", "planner_configs"})

# -- defaults ------------------------------------------------------------------------------------

PILZ_CAPABILITIES = "pilz_industrial_motion_planner/MoveGroupSequenceAction pilz_industrial_motion_planner/MoveGroupSequenceService"
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


def known_parameters(pipeline: str, distro: str) -> tuple[PipelineParameter, ...]:
    """The parameters `distro`'s MoveIt reads in the namespace of a pipeline (a setup name)."""
    return (*COMMON[parameter_format(distro)], *PLANNER_PARAMS.get(pipeline, ()))


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
    number = isinstance(value, int | float) and not isinstance(value, bool)
    expected = {
        DOUBLE: isinstance(value, float) or (number and int_as_double),
        INT: isinstance(value, int) and not isinstance(value, bool),
        BOOL: isinstance(value, bool),
        STRING: isinstance(value, str),
        STRINGS: isinstance(value, list | tuple) and all(isinstance(v, str) for v in value),
    }[p.type]
    if not expected:
        article = "an" if p.type[0] in "aeiou" else "a"
        return f"expected {article} {p.type}, got {value!r}"
    if p.minimum is not None and number and value < p.minimum:  # type: ignore[operator]
        return f"must be at least {p.minimum:g}, got {value!r}"
    if p.choices and value not in p.choices:
        return (
            f"'{value}' is not one of: {', '.join(p.choices)} (MoveIt logs an error and uses {p.choices[0]})"
        )
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
        d for f, d in first.items() if f in COMMON and f != mine and parameter(pipeline, d, name) is not None
    )


def flatten(data: dict, prefix: str = "") -> Iterator[tuple[str, object]]:
    """(dotted name, value) of every leaf of a parameter mapping."""
    for key, value in data.items():
        name = f"{prefix}{key}"
        if isinstance(value, dict):
            yield from flatten(value, f"{name}.")
        else:
            yield name, value
