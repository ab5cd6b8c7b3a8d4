"""Every parameter a ROS 2 package hands move_group and servo, against MoveIt's declared
parameters of the package's distro family (marm_setup/moveit_params, pinned MoveIt sources).

- params.type: a value of another type than MoveIt declares, an integer for a double included:
  rclcpp refuses it (rclcpp node_parameters.cpp declare_parameter: InvalidParameterTypeException;
  get_parameter<double>: ParameterValue::get throws ParameterTypeException). An error where MoveIt
  then throws (move_group or servo_node dies at start-up, e.g. trajectory_execution_manager.cpp
  jazzy l.208-216) or drops the item (moveit_simple_controller_manager.cpp jazzy l.121-243
  catches it and skips the controller); a warning where it only logs (planning_scene_monitor.cpp
  jazzy l.300-305).
- params.bounds: a value outside a generate_parameter_library validator (gt_eq, one_of, ...):
  the ParamListener throws, the node stops; severity as for params.type.
- params.unknown (warning): a key MoveIt never reads inside a namespace it owns
  (trajectory_execution, moveit_simple_controller_manager.<controller>, ...), with a did-you-mean.
- A planner's parameters in a namespace of its own (CHOMP reads `chomp.<name>` whatever its
  pipeline's name: chomp_interface.cpp humble l.50-80, jazzy l.57-87) are checked only where a
  pipeline loads that planner; with none, nothing reads them.
- params.plugin (error): a planner, adapter, kinematics solver, controller manager, capability
  or servo smoothing filter class that the family's pluginlib files do not export and that is no
  known third-party plugin: pluginlib cannot load it.

Left to other rules (one finding per defect): a pipeline's own parameters
(pipeline_param_rules, distro_rules: adapters of the other distro), sensors (perception_rules),
joint and Cartesian limits given as integers (limits_rules), non-positive IK timeouts
(kinematics_rules), a controller's type (controller_rules), servo's command_out_type
(perception_rules) and empty lists (ros2_params_rules).
"""

from __future__ import annotations

import difflib
import re
from collections.abc import Callable, Collection, Mapping
from typing import TYPE_CHECKING

from marm_setup.findings import Finding, error, warning
from marm_setup.moveit_params import (
    LOGS,
    PIPELINES,
    ParamRow,
    Table,
    family_of,
    load_table,
    planner_of,
    type_problem,
    validator_problem,
)
from marm_setup.package import received_parameters

if TYPE_CHECKING:
    from marm_setup.package import MoveItPackage, Received

# the names limits_rules checks for integers (NUMERIC_KEYS, _SCALARS there)
LIMIT_NUMBERS = frozenset(
    {"max_velocity", "max_acceleration", "max_jerk", "min_position", "max_position",
     "default_velocity_scaling_factor", "default_acceleration_scaling_factor",
     "max_trans_vel", "max_trans_acc", "max_trans_dec", "max_rot_vel"}
)  # fmt: skip
CHECKED_ELSEWHERE = (  # controller_rules, perception_rules, distro_rules (moveit.publish-flags)
    "moveit_simple_controller_manager.<controller>.type", "command_out_type",
    "publish_planning_scene", "publish_geometry_updates", "publish_state_updates", "publish_transforms_updates",
)  # fmt: skip
# IKFast solvers are generated per robot (<robot>_<group>_ikfast_plugin/IKFastKinematicsPlugin)
IKFAST = re.compile(r"\w+/IKFastKinematicsPlugin")
PLUGIN_KEYS = (  # (name pattern, plugin kind)
    (re.compile(r"[^.]+\.planning_plugins?"), "planner"),
    (re.compile(r"[^.]+\.request_adapters"), "request_adapter"),
    (re.compile(r"[^.]+\.response_adapters"), "response_adapter"),
    (re.compile(r"robot_description_kinematics\.[^.]+\.kinematics_solver"), "kinematics"),
    (re.compile(r"moveit_controller_manager"), "controller_manager"),
    (re.compile(r"(disable_)?capabilities|[^.]+\.capabilities"), "capability"),
    (re.compile(r"smoothing_filter_plugin_name"), "smoothing_filter"),
)


def check_declared_parameters(pkg: MoveItPackage, distro: str | None) -> list[Finding]:
    """The findings on every parameter move_group and servo receive from a ROS 2 package; with
    no known distro, the family its format shows, else only what Jazzy's and Humble's agree on."""
    received = [r for r in received_parameters(pkg) if not _unread_group(r, pkg)]
    built, exported = package_finder(pkg), exported_classes(pkg)
    family = family_of(distro) or inferred_family(received)
    given = {r.name: r for r in received if r.node == "move_group"}
    listed = check_default_pipeline(given) + check_listed_pipelines(given, family, pkg.files)
    if family is not None:
        return _check_all(received, load_table(family), built, exported) + listed
    found = [_check_all(received, load_table(f), built, exported) for f in ("jazzy", "humble")]
    agreed = {(f.rule, f.file, f.element) for f in found[1]}
    return [f for f in found[0] if (f.rule, f.file, f.element) in agreed] + listed


def check_listed_pipelines(
    given: Mapping[str, Received], family: str | None, files: Collection[str]
) -> list[Finding]:
    """A pipeline of `planning_pipelines` (in `given`, move_group's parameters by name) with no
    parameter in its namespace (and no `config/<name>_planning.yaml`, which a launch file may
    load in ways not modelled here). Jazzy's PlanningPipeline throws "Planning plugin name is
    empty" from its constructor, uncaught by createPlanningPipelineMap: move_group stops
    (planning_pipeline.cpp jazzy l.136-140, planning_pipeline_interfaces.cpp jazzy l.187).
    Humble's guesses a plugin: the only one installed, else the first with a warning
    (planning_pipeline.cpp humble l.117-134)."""
    listed = given.get("planning_pipelines")
    if listed is None or not isinstance(listed.value, list):
        return []
    spaces = {name.split(".", 1)[0] for name in given if "." in name}
    out = []
    for name in dict.fromkeys(str(n) for n in listed.value):
        if name in spaces or f"config/{name}_planning.yaml" in files:
            continue
        if family == "humble":
            does, hint, finding = (
                "Humble's move_group plans with whichever planner plugin it finds first",
                f"add {name}.planning_plugin",
                warning,
            )
        else:
            does, hint, finding = (
                "move_group stops ('Planning plugin name is empty')",
                f"add {name}.planning_plugins or drop '{name}'",
                error,
            )
        msg = f"pipeline '{name}' has no parameters: {does}"
        out.append(finding("pipeline.not-configured", listed.file, listed.element, msg, hint))
    return out


def check_default_pipeline(given: Mapping[str, Received]) -> list[Finding]:
    """`default_planning_pipeline` naming no pipeline of `planning_pipelines` (in `given`,
    move_group's parameters by name): move_group warns and plans with the first pipeline instead
    (move_group.cpp main, humble l.234-260, jazzy l.249-275: "not configured in
    ~planning_pipelines", the id reset, the first one taken)."""
    default, listed = given.get("default_planning_pipeline"), given.get("planning_pipelines")
    if default is None or listed is None or not isinstance(listed.value, list) or not listed.value:
        return []
    names = [str(n) for n in listed.value]
    if str(default.value) in names:
        return []
    meant = difflib.get_close_matches(str(default.value), names, n=1)
    msg = (
        f"default_planning_pipeline '{default.value}' is not in planning_pipelines ({', '.join(names)}): "
        f"move_group plans with '{names[0]}' instead"
    )
    hint = f"did you mean '{meant[0]}'?" if meant else f"name one of: {', '.join(names)}"
    return [warning("moveit.default-pipeline", default.file, default.element, msg, hint)]


def _unread_group(r: Received, pkg: MoveItPackage) -> bool:
    """A kinematics entry of a group the SRDF lacks: MoveIt loads a solver per group of the
    robot model only (kinematics_plugin_loader.cpp, getLoaderFunction over the SRDF's groups), so
    it never reads it (kinematics_rules' kinematics.unknown-group says so)."""
    srdf = pkg.srdf
    parts = r.name.split(".")
    if srdf is None or parts[0] != "robot_description_kinematics" or len(parts) < 3:
        return False
    return parts[1] not in {g.name for g in srdf.groups}


def inferred_family(received: list[Received]) -> str | None:
    """jazzy when a pipeline is written as Jazzy writes it (planning_plugins, response_adapters),
    humble for Humble's planning_plugin string; None when neither shows."""
    tails = {r.name.rsplit(".", 1)[-1] for r in received if r.node == "move_group"}
    if tails & {"planning_plugins", "response_adapters"}:
        return "jazzy"
    return "humble" if "planning_plugin" in tails else None


def package_finder(pkg: MoveItPackage) -> Callable[[str], bool]:
    """Whether a ROS package of that name is on the package paths (it may export a plugin)."""
    from marm_setup.robot import find_packages

    packages = find_packages(pkg.package_paths)
    return lambda name: name in packages


def exported_classes(pkg: MoveItPackage) -> frozenset[str]:
    """The plugin classes the packages on the package paths export (robot.exported_plugin_classes)."""
    from marm_setup.robot import exported_plugin_classes, find_packages

    return exported_plugin_classes(find_packages(pkg.package_paths))


def _check_all(
    received: list[Received], table: Table, built: Callable[[str], bool], exported: frozenset[str]
) -> list[Finding]:
    instances = _instances(received)
    out: list[Finding] = []
    for r in received:
        out += check_plugin_param(r, table, built, exported)
        if not _elsewhere(r, instances):
            out += _check_one(r, table, instances)
    return out


def _instances(received: list[Received]) -> dict[str, set[str]]:
    """The names placeholders may take: pipelines, sensors, controllers, controller managers."""

    def listed(name: str) -> set[str]:
        values = [r.value for r in received if r.node == "move_group" and r.name == name]
        return {str(v) for value in values if isinstance(value, list) for v in value}

    loading = [r for r in received if r.name.endswith((".planning_plugin", ".planning_plugins"))]
    return {
        "pipeline": listed("planning_pipelines") | {r.name.split(".", 1)[0] for r in loading},
        # not a placeholder: the planner plugins the pipelines load
        "planner_plugin": {
            str(v) for r in loading for v in (r.value if isinstance(r.value, list) else [r.value])
        },
        "sensor": listed("sensors"),
        "controller": listed("moveit_simple_controller_manager.controller_names"),
        "plugin_package": {"moveit_simple_controller_manager", "moveit_ros_control_interface"},
    }


def _elsewhere(r: Received, instances: dict[str, set[str]]) -> bool:
    """Whether other rules check this parameter (pipelines' and sensors' namespaces)."""
    head = r.name.split(".", 1)[0]
    return r.node == "move_group" and "." in r.name and head in instances["pipeline"] | instances["sensor"]


def _row(r: Received, table: Table, instances: dict[str, set[str]]) -> ParamRow | None:
    """The most specific row `r` is an instance of (placeholders bound to known names)."""
    fitting = []
    for row in table.rows(r.node):
        if _binds(row, r.name, instances):
            fitting.append((len(row.bindings(r.name) or {}), row))
    return min(fitting, key=lambda f: f[0])[1] if fitting else None


def _binds(row: ParamRow, name: str, instances: dict[str, set[str]]) -> bool:
    bound = row.bindings(name)
    return bound is not None and all(v in instances.get(k, {v}) for k, v in bound.items())


def _check_one(r: Received, table: Table, instances: dict[str, set[str]]) -> list[Finding]:
    row = _row(r, table, instances)
    if row is None:
        return _unknown(r, table, instances)
    if _unloaded_planner(row, instances):
        return []
    if row.name.endswith(CHECKED_ELSEWHERE) or r.value in ([], {}, None):  # empty: ros2_params_rules
        return []
    problem = type_problem(row, r.value)
    if problem and _limits_rules_integer(r, row):
        return []
    rule = "params.type"
    if problem is None:
        rule, problem = "params.bounds", validator_problem(row, r.value)
        if problem is None or r.name.startswith("robot_description_kinematics."):
            return []  # kinematics_rules reports non-positive timeouts and resolutions
    make = warning if row.on_wrong == LOGS else error
    return [make(rule, r.file, r.element, f"{problem}: {_consequence(row)}", _cite(row, table))]


def _unloaded_planner(row: ParamRow, instances: dict[str, set[str]]) -> bool:
    """A row a planner reads in a namespace of its own (CHOMP's `chomp.<name>`, whatever its
    pipeline's name: chomp_interface.cpp) while no pipeline loads that planner: nothing reads it."""
    planner = planner_of(row)
    if planner is None or not row.name.startswith(f"{PIPELINES[planner].namespace}."):
        return False
    return PIPELINES[planner].plugin_ros2 not in instances["planner_plugin"]


def _limits_rules_integer(r: Received, row: ParamRow) -> bool:
    integer = isinstance(r.value, int) and not isinstance(r.value, bool)
    return (
        integer
        and row.type == "double"
        and r.name.startswith("robot_description_planning.")
        and r.name.rsplit(".", 1)[-1] in LIMIT_NUMBERS
    ) or (integer and r.name.startswith("robot_description_kinematics.") and r.value <= 0)


def _consequence(row: ParamRow) -> str:
    node = "servo_node" if row.node == "servo" else "move_group"
    return {
        "throws": f"{node} stops at start-up",
        "drops": "MoveIt drops that item (e.g. the controller)",
    }.get(row.on_wrong, "MoveIt logs an error and ignores it")


def _cite(row: ParamRow, table: Table) -> str:
    repo, ref, sha = table.pinned[0]
    note = f"; {row.note}" if row.note else ""
    return f"declared as {row.type} at {repo}@{sha[:8]} ({ref}) {row.source}{note}"


def _not_a_mapping(r: Received, table: Table) -> list[Finding]:
    """A value where MoveIt declares a namespace (servo's `scale: 5` for scale.linear, ...): the
    node declares only the names inside it, so rclcpp never hands it this one (an override of an
    undeclared parameter is ignored: servo_node does not declare parameters from overrides) and
    each inside keeps its default."""
    inside = [row for row in table.rows(r.node) if row.name.startswith(r.name + ".")]
    if not inside:
        return []
    defaults = ", ".join(f"{row.name.rsplit('.', 1)[-1]} {row.default!r}" for row in inside)
    msg = f"expected a mapping, got {r.value!r}: MoveIt never reads it and keeps its defaults ({defaults})"
    return [warning("params.type", r.file, r.element, msg, _cite(inside[0], table))]


def _under_a_value(r: Received, table: Table, instances: dict[str, set[str]]) -> list[Finding]:
    """A mapping where MoveIt declares one value (`max_trans_vel: {x: 1.0}`): rcl flattens it
    into names below the declared one, so the declared parameter itself is never given."""
    parts = r.name.split(".")
    for end in range(len(parts) - 1, 0, -1):
        head = ".".join(parts[:end])
        row = next((row for row in table.rows(r.node) if _binds(row, head, instances)), None)
        if row is not None:
            make = warning if row.on_wrong == LOGS else error
            msg = f"expected {row.type.replace('_', ' ')} at {head}, got a mapping: {_consequence(row)}"
            return [make("params.type", r.file, r.element, msg, _cite(row, table))]
    return []


def _unknown(r: Received, table: Table, instances: dict[str, set[str]]) -> list[Finding]:
    """A key MoveIt never reads in a namespace it owns, with the nearest name it reads."""
    if found := _not_a_mapping(r, table) or _under_a_value(r, table, instances):
        return found
    for prefix, source in table.owned:
        bound = re.compile(ParamRow("", prefix + "<rest>", "", "", "").pattern.pattern)
        match = bound.fullmatch(r.name)
        if match is None or not all(
            v in instances.get(k, {v}) for k, v in match.groupdict().items() if k != "rest"
        ):
            continue
        names = [_instance(row.name, match.groupdict()) for row in table.rows(r.node)]
        known = [n for n in names if n.startswith(r.name[: len(r.name) - len(match["rest"])])]
        close = difflib.get_close_matches(r.name, known, n=1, cutoff=0.6)
        hint = f"did you mean {close[0].rsplit('.', 1)[-1]}?" if close else f"MoveIt reads: {_short(known)}"
        msg = f"MoveIt reads no {match['rest']} here ({source}): it is ignored"
        return [warning("params.unknown", r.file, r.element, msg, hint)]
    return []


def _instance(pattern: str, bound: dict[str, str]) -> str:
    return re.sub(r"<(\w+)>", lambda m: bound.get(m[1], m[0]), pattern)


def _short(names: list[str]) -> str:
    tails = sorted({n.rsplit(".", 1)[-1] for n in names})
    return ", ".join(tails[:12]) + (", ..." if len(tails) > 12 else "")


def check_plugin_param(
    r: Received, table: Table, built: Callable[[str], bool], exported: frozenset[str] = frozenset()
) -> list[Finding]:
    """Plugin class names pluginlib cannot load in this family: an error, but a warning for a
    class of another package the package paths hold (pluginlib loads it once that is built), and
    nothing for a class a package on the package paths exports (`exported`: pluginlib finds a
    class by its lookup name in the exported description files, whatever its prefix)."""
    kind = next((k for pattern, k in PLUGIN_KEYS if pattern.fullmatch(r.name)), None)
    if kind is None:
        return []
    known = table.classes(kind)
    out = []
    for name in _plugin_names(r.value):
        if (
            name in known
            or name in exported
            or (kind == "kinematics" and IKFAST.fullmatch(name))
            or _other_family(name, kind, table)
        ):
            continue
        close = difflib.get_close_matches(name, known, n=1, cutoff=0.6)
        hint = f"did you mean {close[0]}?" if close else f"known: {', '.join(known[:8])}"
        owner = name.split("/", 1)[0]
        label = f"{kind.replace('_', ' ')} plugin '{name}'"
        if close or owner in {c.split("/", 1)[0] for c in known} or not built(owner):
            msg = (
                f"no {label} in MoveIt ({table.family}) nor a known third-party one: pluginlib cannot load it"
            )
            out.append(error("params.plugin", r.file, r.element, msg, hint))
        else:
            msg = f"{label} is not MoveIt's ({table.family}): package '{owner}' must export it (pluginlib)"
            out.append(warning("params.plugin", r.file, r.element, msg, hint))
    return out


def _plugin_names(value: object) -> list[str]:
    if isinstance(value, str):
        return value.split()
    return [v for v in value if isinstance(v, str)] if isinstance(value, list) else []


def _other_family(name: str, kind: str, table: Table) -> bool:
    """A class of another family's (distro_rules reports the other distro's adapters)."""
    others = (f for f in ("jazzy", "humble") if f != table.family)
    return any(
        name in load_table(f).classes(k)
        for f in others
        for k in (kind, "request_adapter", "response_adapter")
    )
