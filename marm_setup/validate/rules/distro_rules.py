"""What a ROS 2 package must get right for its distro and at run time: the planning pipelines'
parameter format, the planning scene publishing flags, OMPL projection evaluators, and one
ros2_control system per joint.

Sources (moveit/moveit2 humble and jazzy branches, ros-controls/ros2_control):
- Humble's PlanningPipeline reads `<pipeline>.planning_plugin` (one string; absent -> the first
  declared planner class, whichever) and `<pipeline>.request_adapters` into ONE std::string split
  at spaces; a list there throws a parameter type exception and move_group dies
  (humble moveit_ros/planning/planning_pipeline/src/planning_pipeline.cpp l.58-77). An adapter
  class it cannot load is logged as an error and skipped (same file, configure()).
- Jazzy's reads the string arrays `planning_plugins`, `request_adapters`, `response_adapters`
  (planning_pipeline_parameters.yaml) and throws "Planning plugin name is empty or not defined"
  when planning_plugins is empty (jazzy planning_pipeline.cpp, PlanningPipeline::configure).
- Humble's move_group looks a pipeline's own capabilities up as
  "planning_pipelines/<name>/capabilities", no valid ROS 2 parameter name, so they never load
  (moveit/moveit2#1393, #2707); only the top-level `capabilities` string does. Jazzy reads
  `<pipeline>.capabilities` (jazzy move_group.cpp, configureCapabilities).
- The planning scene monitor declares publish_planning_scene / _geometry_updates /
  _state_updates / _transforms_updates false (planning_scene_monitor.cpp, initialize()).
- OMPL's KPIECE family, EST, SBL, ProjEST, PDST and STRIDE plan on a projection, which MoveIt
  sets from the group's `projection_evaluator` (ompl_interface model_based_planning_context.cpp).
- The controller manager refuses a second hardware interface of a joint (ros2_control
  resource_manager.cpp: the interface is already registered).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING

from marm_setup.findings import Finding, error, warning
from marm_setup.package import GroupPlanning, MoveItPackage, Param, PlanningPipeline, Ros2ControlFile
from marm_setup.ros import DISTROS, Distro, Target, distro_row
from marm_setup.setup import active_group_joints, group_joints, groups_by_name

if TYPE_CHECKING:
    from marm_setup.robot import RobotModel
    from marm_setup.setup import Srdf

PUBLISH_FLAGS = (
    "publish_planning_scene",
    "publish_geometry_updates",
    "publish_state_updates",
    "publish_transforms_updates",
)
# OMPL planner types that need a projection (geometric::<type>).
PROJECTION_PLANNERS = frozenset({"KPIECE", "BKPIECE", "LBKPIECE", "EST", "SBL", "ProjEST", "PDST", "STRIDE"})
HUMBLE_ADAPTERS = "default_planner_request_adapters/"
JAZZY_ADAPTERS = ("default_planning_request_adapters/", "default_planning_response_adapters/")


def check_pipeline_format(pipeline: PlanningPipeline, distro: Distro) -> list[Finding]:
    """One pipeline's planner and adapter parameters as `distro` reads them (its row's
    parameter format: humble or jazzy)."""
    if not pipeline.is_mapping:
        return []
    data = pipeline.data

    def where(*keys: object) -> str:
        return pipeline.where.child(*keys).element

    if distro_row(distro).params == "humble":
        return _humble_format(pipeline.name, data, pipeline.where.file, where)
    return _jazzy_format(pipeline.name, data, pipeline.where.file, where)


def _humble_format(name: str, data: dict, file: str, where: Callable[..., str]) -> list[Finding]:
    out = []
    if not isinstance(data.get("planning_plugin"), str):
        found = " (this is Jazzy's planning_plugins list)" if "planning_plugins" in data else ""
        msg = f"Humble reads one planning_plugin string{found}: move_group takes whichever planner is declared first"
        out.append(error("distro.pipeline-format", file, where("planning_plugin"), msg))
    adapters = data.get("request_adapters")
    if adapters is not None and not isinstance(adapters, str):
        msg = "Humble reads request_adapters as one space-separated string: a list stops move_group"
        out.append(error("distro.pipeline-format", file, where("request_adapters"), msg))
    names = adapters.split() if isinstance(adapters, str) else []
    for adapter in names:
        if adapter.startswith(JAZZY_ADAPTERS):
            msg = f"'{adapter}' is Jazzy's; Humble cannot load it and plans without it"
            out.append(
                error("distro.adapter", file, where("request_adapters"), msg, f"use {HUMBLE_ADAPTERS}...")
            )
    out += _built_from_source(data.get("planning_plugin"), file, where)
    if data.get("capabilities"):
        msg = f"Humble's move_group never reads a pipeline's capabilities: {data['capabilities']} do not load"
        hint = "list them in the top-level capabilities string"
        out.append(warning("distro.pipeline-capabilities", file, where("capabilities"), msg, hint))
    return out


def _built_from_source(plugin: object, file: str, where: Callable[..., str]) -> list[Finding]:
    """A planner Humble's binaries lack (STOMP: moveit2's humble branch has no
    moveit_planners/stomp; moveit/moveit2#2550, #2742): move_group loads it only where the user
    built it from source."""
    from marm_setup.moveit_params import PIPELINES

    from_source = {k for r in DISTROS.values() if r.params == "humble" for k in r.planners_from_source}
    found = next((p for k, p in PIPELINES.items() if p.plugin_ros2 == plugin and k in from_source), None)
    if found is None:
        return []
    msg = f"{plugin} is not in MoveIt's Humble binaries: move_group loads it only where {found.package} is built from moveit2's source"
    return [
        warning(
            "distro.planner-from-source", file, where("planning_plugin"), msg, "moveit/moveit2#2550, #2742"
        )
    ]


def _jazzy_format(name: str, data: dict, file: str, where: Callable[..., str]) -> list[Finding]:
    out = []
    plugins = data.get("planning_plugins")
    if not (isinstance(plugins, list) and plugins):
        found = " (this is Humble's planning_plugin string)" if "planning_plugin" in data else ""
        msg = f"Jazzy reads a planning_plugins list{found}: move_group throws 'Planning plugin name is empty'"
        out.append(error("distro.pipeline-format", file, where("planning_plugins"), msg))
    for key in ("request_adapters", "response_adapters"):
        value = data.get(key)
        if value is not None and not isinstance(value, list):
            msg = f"Jazzy reads {key} as a list of plugin names: a string stops move_group"
            out.append(error("distro.pipeline-format", file, where(key), msg))
        for adapter in value if isinstance(value, list) else ():
            if str(adapter).startswith(HUMBLE_ADAPTERS):
                msg = f"'{adapter}' is Humble's; Jazzy has no such adapter plugin"
                out.append(
                    error("distro.adapter", file, where(key), msg, "use default_planning_*_adapters/...")
                )
    return out + _unvalidated(data, file, where)


VALIDATE_SOLUTION = "default_planning_response_adapters/ValidateSolution"


def _unvalidated(data: dict, file: str, where: Callable[..., str]) -> list[Finding]:
    """Jazzy+: a pipeline whose responses skip ValidateSolution hands its path to execution
    without a collision check (validate_path.cpp jazzy l.101 checks `isPathValid`); MoveIt's own
    default configs end every planner's responses with it (moveit_configs_utils/default_configs/
    ompl_planning.yaml l.11, chomp_planning.yaml l.12, pilz_industrial_motion_planner_planning.yaml
    l.10, stomp_planning.yaml l.10)."""
    value = data.get("response_adapters")
    if not isinstance(value, list | type(None)) or VALIDATE_SOLUTION in (value or []):
        return []
    msg = "response_adapters lack ValidateSolution: a path reaches execution without a collision check"
    hint = f"add {VALIDATE_SOLUTION}, as MoveIt's default configs do"
    return [warning("pipeline.no-validate-solution", file, where("response_adapters"), msg, hint)]


def check_publish_flags(params: tuple[Param, ...], file: str, prefix: str) -> list[Finding]:
    """move_group's four planning scene publishing flags (declared false by MoveIt)."""
    given = {p.key: p.value for p in params}
    off = [flag for flag in PUBLISH_FLAGS if given.get(flag) is not True]
    if not off:
        return []
    msg = f"{', '.join(off)} not true: RViz does not see the robot move or the world change"
    return [
        warning(
            "moveit.publish-flags", file, prefix, msg, "set all four to true, as the Setup Assistant does"
        )
    ]


def check_projection_evaluators(ompl: PlanningPipeline, srdf: Srdf, robot: RobotModel) -> list[Finding]:
    """A group of two or more joints whose default OMPL planner needs a projection has one, and
    a projection_evaluator names what MoveIt can project on (`_projection_problem`)."""
    by_name = groups_by_name(srdf.groups)
    out = []
    for entry in sorted(ompl.groups, key=lambda g: g.group):
        if entry.group not in by_name:
            continue
        default = entry.param("default_planner_config")
        config = ompl.config(str(default.value if default is not None else None))
        kind = (
            str(config.type or "").rsplit("::", 1)[-1]
            if config is not None and config.params is not None
            else ""
        )
        joints = active_group_joints(by_name[entry.group], by_name, robot, tuple(srdf.passive_joints))
        given = entry.param("projection_evaluator")
        if given is not None:
            members = group_joints(by_name[entry.group], by_name, robot)
            out += _projection_problem(
                ompl.where.file, entry, str(given.value), (joints, members), robot, kind
            )
            continue
        if kind in PROJECTION_PLANNERS and len(joints) >= 2:
            msg = f"default planner {kind} needs a projection_evaluator: every plan of this group fails"
            hint = f"projection_evaluator: joints({joints[0]},{joints[1]})"
            out.append(error("ompl.projection-missing", ompl.where.file, entry.where.element, msg, hint))
    return out


def _projection_problem(
    file: str,
    entry: GroupPlanning,
    given: str,
    joints: tuple[Sequence[str], Sequence[str]],
    robot: RobotModel,
    kind: str,
) -> list[Finding]:
    """`link(<link>)` of a link of the robot, or `joints(<a>,<b>,...)` of joints of the group:
    anything else MoveIt logs as an error and the group has no projection
    (model_based_planning_context.cpp getProjectionEvaluator, jazzy l.166-231, the same in
    humble and moveit/moveit noetic). `joints` is (the group's active joints, every joint of the
    group): MoveIt takes any joint the group has (JointModelGroup::hasJointModel, mimic and
    passive ones included) with variables, skips a fixed one ("Ignoring joint ... since it has 0
    DOF", a warning) and logs an error for one outside the group. An error when the group's
    default planner needs the projection and none is left, else a warning."""
    active, members = joints
    text = given.strip()
    element = f"{entry.where.element}.projection_evaluator"
    if text.startswith("link(") and text.endswith(")"):
        bad = [] if text[5:-1] in robot.link_map else [f"'{text[5:-1]}' (not a link of the robot)"]
        usable = not bad
    elif text.startswith("joints(") and text.endswith(")"):
        names = text[7:-1].replace(",", " ").split()
        moving = [n for n in names if n in members and robot.joint(n).type != "fixed"]
        bad = [
            f"'{n}' (a fixed joint, 0 DOF)" if n in members else f"'{n}' (not a joint of the group)"
            for n in names
            if n not in moving
        ]
        usable = bool(moving)
    else:
        bad, usable = [f"'{text}'"], False
    if not bad:
        return []
    said = ", ".join(bad)
    hint = f"projection_evaluator: joints({','.join(active[:2])})" if len(active) >= 2 else ""
    if not usable and kind in PROJECTION_PLANNERS:
        msg = (
            f"MoveIt cannot project on {said}: the default planner {kind} has no projection, every plan fails"
        )
        return [error("ompl.projection-invalid", file, element, msg, hint)]
    logged = "logs an error" if any("(a fixed joint" not in b for b in bad) else "warns"
    tail = "the group has no projection" if not usable else f"MoveIt {logged} and skips it"
    return [
        warning("ompl.projection-invalid", file, element, f"MoveIt cannot project on {said}: {tail}", hint)
    ]


def check_ros2_control_systems(
    files: tuple[Ros2ControlFile, ...], described: frozenset[str]
) -> list[Finding]:
    """Each joint in one ros2_control system: the package's `*.ros2_control.xacro` files against
    each other and against the systems the robot description already declares."""
    seen: dict[str, str] = {j: "the robot description" for j in described}
    out = []
    for found in sorted(files, key=lambda f: f.file):
        for joint in found.joints:
            if joint in seen:
                msg = f"joint '{joint}' is already in a ros2_control system of {seen[joint]}"
                hint = "the controller manager refuses a second interface of the same joint"
                out.append(error("ros2_control.duplicate-joint", found.file, f"joint[{joint}]", msg, hint))
            else:
                seen[joint] = found.file
    return out


def check_package_runtime(pkg: MoveItPackage, robot: RobotModel | None) -> list[Finding]:
    """The rules above on a config package: projection evaluators (both targets), then for ROS 2
    the distro's pipeline format (the distro marm_setup.yaml names), publishing flags and
    ros2_control systems; those reading the robot only when it is known."""
    from marm_setup.robot import described_joints

    out: list[Finding] = []
    if pkg.ompl is not None and pkg.srdf is not None and robot is not None:
        out += check_projection_evaluators(pkg.ompl, pkg.srdf, robot)
    if pkg.target != Target.ROS2:
        return out
    distro = pkg.ros_distro
    if distro in DISTROS and DISTROS[distro].params in ("humble", "jazzy"):
        from marm_setup.validate.rules.pipeline_param_rules import check_pipeline_parameters

        for pipeline in _ros2_pipelines(pkg):
            out += check_pipeline_format(pipeline, distro)
            out += check_pipeline_parameters(pipeline, distro)
    if pkg.move_group is not None:
        out += check_publish_flags(pkg.move_group, MOVEIT_YAML, "/**.ros__parameters")
    if robot is None:
        return out
    out += check_expanded_systems(robot)
    if pkg.urdf is not None and not pkg.urdf.resolve().is_relative_to(
        pkg.root.resolve()
    ):  # our layout: the user's description
        out += check_ros2_control_systems(pkg.ros2_control_files, described_joints(robot))
    return out


def check_expanded_systems(robot: RobotModel) -> list[Finding]:
    """A joint in two `<ros2_control>` systems of the URDF the package loads."""
    from marm_setup.robot import described_systems

    seen: dict[str, str] = {}
    out = []
    for system in described_systems(robot):
        for joint in system.joints:
            if joint in seen and seen[joint] != system.name:
                msg = f"joint '{joint}' is in ros2_control systems {seen[joint]} and {system.name}"
                hint = "the controller manager refuses a second interface of the same joint"
                out.append(error("ros2_control.duplicate-joint", robot.source, f"joint[{joint}]", msg, hint))
            seen.setdefault(joint, system.name)
    return out


MOVEIT_YAML = "config/moveit.yaml"


def _ros2_pipelines(pkg: MoveItPackage) -> tuple[PlanningPipeline, ...]:
    """Our config/moveit.yaml's pipelines, else the OMPL pipeline discovery found."""
    if pkg.move_group is not None:
        return tuple(p for p in pkg.pipelines if p.where.file == MOVEIT_YAML)
    return (pkg.ompl,) if pkg.ompl is not None else ()
