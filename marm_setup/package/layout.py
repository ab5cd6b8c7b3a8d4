"""Which file of a package feeds each MoveIt file kind, and reading them.

ROS 1: the files the launch files load (`launch_ros1`), by the namespace they land in
(`<robot_description>_kinematics`, `<robot_description>_planning`), the controller manager
loaded beside them, and their file name; where no launch file loads a kind, the Setup
Assistant's file name (`config/kinematics.yaml`, ...). ROS 2: the parameter files XML launch
files hand to a node (`<param from>`, by the parameters they hold), else what
MoveItConfigsBuilder loads (`builder`), else the Setup Assistant's file names.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field, replace
from pathlib import Path

from marm_setup.findings import Finding, warning
from marm_setup.package.builder import BuilderFiles, Chosen, chosen_file, controllers_file, planning_pipelines
from marm_setup.package.controllers_file import (
    FAKE_KEYS,
    SIMPLE_MANAGER,
    SIMPLE_MANAGER_CLASS,
    ControllersFile,
    ListLoad,
    read_controllers,
)
from marm_setup.package.driver_file import (
    read_arbotix,
    read_initial_positions,
    read_ros2_controllers,
    read_ros_controllers,
)
from marm_setup.package.files import PackageFiles
from marm_setup.package.joint_limits_file import read_joint_limits
from marm_setup.package.kinematics_file import KinematicsFile, read_kinematics
from marm_setup.package.launch_python import launch_yaml_key
from marm_setup.package.launch_ros1 import MANAGER_PARAM, LaunchParam, YamlLoad
from marm_setup.package.model import Source
from marm_setup.package.perception_files import ServoConfig, read_sensors, read_servo
from marm_setup.package.planning_file import PlanningPipeline, read_pipeline, with_builder_ompl_defaults
from marm_setup.package.where import Located, Param, Where, unwrap_parameters

DRIVER_FILES = {
    "ros2_controllers": "config/ros2_controllers.yaml",
    "ros_controllers": "config/ros_controllers.yaml",
    "arbotix": "config/arbotix.yaml",
    "initial_positions": "config/initial_positions.yaml",
}
DEFAULT_FILES = {
    "kinematics": "config/kinematics.yaml",
    "joint_limits": "config/joint_limits.yaml",
    "fake_controllers": "config/fake_controllers.yaml",
    "sensors": "config/sensors_3d.yaml",
}
ROS1_MOVEIT_CONTROLLERS = (
    "config/controllers.yaml",
    "config/simple_moveit_controllers.yaml",
    "config/ros_controllers.yaml",  # old Setup Assistant (controller_list inside)
)
SA_NAME = "the Setup Assistant's file name"
MOVE_GROUP = "move_group"  # the node (XML launch: its name, else its exec) MoveIt's parameters go to
MARM_MOVEIT_YAML = "config/moveit.yaml"


@dataclass
class Kinds:
    """The typed files of a package, and where each came from (built by `read_kinds`)."""

    values: dict[str, object] = field(default_factory=dict)
    sources: list[Source] = field(default_factory=list)

    def put(self, kind: str, value: object, doc: Located | None, how: str) -> None:
        if value is None or doc is None:
            return
        self.values[kind] = value
        self.sources = [s for s in self.sources if s.kind != kind] + [Source(kind, doc.where.file, how)]


def _named(files: PackageFiles, rel: str) -> Located | None:
    return files.yaml(rel) if files.is_file(rel) else None


def _loaded_by(load: YamlLoad) -> str:
    into = f" into {load.ns}" if load.ns else ""
    return f"loaded by {load.launch}{into}" + (
        " (on a branch the launch args' defaults do not take)" if load.conditional else ""
    )


def _by_preference(loads: list[YamlLoad]) -> list[YamlLoad]:
    return sorted(loads, key=lambda load: load.conditional)


# -- ROS 1 ------------------------------------------------------------------------------------


def read_ros1_kinds(
    files: PackageFiles,
    loads: tuple[YamlLoad, ...],
    move_groups: tuple[str, ...] = (),
    managers: tuple[str, ...] = (),
    taken_managers: tuple[LaunchParam, ...] = (),
) -> Kinds:
    """`move_groups`: the move_group nodes' full names; `managers`: every
    `moveit_controller_manager` value the launch files set, `taken_managers` those set on the
    branches an entry point's defaults take (launch_ros1.Ros1Launch)."""
    kinds = Kinds()
    for kind, ns_suffix, base, reader in (
        ("kinematics", "_kinematics", "kinematics.yaml", read_kinematics),
        ("joint_limits", "_planning", "joint_limits.yaml", read_joint_limits),
    ):
        doc, how = _ros1_file(
            files, loads, ns_suffix, base, "joint_limits" if kind == "joint_limits" else None
        )
        kinds.put(kind, reader(doc) if doc is not None else None, doc, how)
    _ros1_pipelines(files, loads, kinds)
    _ros1_controllers(files, loads, kinds, move_groups, (managers, taken_managers))
    _drivers(files, kinds, loads)
    doc, how = _ros1_sensors(files, loads)
    kinds.put("sensors", read_sensors(doc) if doc is not None else None, doc, how)
    kinds.values["servo"] = _servo(files, [load.file for load in loads])
    return kinds


Loads = tuple[YamlLoad, ...]


def _ros1_file(
    files: PackageFiles, loads: Loads, ns_suffix: str, base: str, key: str | None
) -> tuple[Located | None, str]:
    """The file loaded into `*<ns_suffix>` (holding `key`, when given), else `config/<base>`,
    else a file of that name some launch file loads (e.g. `config/7dof/joint_limits.yaml`)."""
    for load in _by_preference([lo for lo in loads if lo.ns.rsplit("/", 1)[-1].endswith(ns_suffix)]):
        doc = files.yaml(load.file)
        if doc is not None and (key is None or (doc.is_mapping and key in doc.data)):
            return doc, _loaded_by(load)
    doc = _named(files, f"config/{base}")
    if doc is not None:
        return doc, SA_NAME
    for load in _by_preference([lo for lo in loads if Path(lo.file).name == base]):
        doc = files.yaml(load.file)
        if doc is not None:
            return doc, _loaded_by(load)
    return None, ""


def _ros1_pipelines(files: PackageFiles, loads: Loads, kinds: Kinds) -> None:
    """OMPL (and every other `<pipeline>_planning.yaml` launch files load or config/ holds)."""
    found: dict[str, tuple[Located, str]] = {}
    for load in _by_preference([lo for lo in loads if lo.file.endswith("_planning.yaml")]):
        name = Path(load.file).name[: -len("_planning.yaml")]
        doc = files.yaml(load.file) if name not in found else None
        if doc is not None:
            found[name] = (doc, _loaded_by(load))
    for rel in files.glob("config/*_planning.yaml"):
        name = Path(rel).name[: -len("_planning.yaml")]
        if name not in found and (doc := files.yaml(rel)) is not None:
            found[name] = (doc, SA_NAME)
    pipelines = []
    for name in sorted(found, key=lambda n: (n != "ompl", n)):
        doc, how = found[name]
        pipelines.append(read_pipeline(name, doc))
        kinds.sources.append(Source(f"pipeline:{name}", doc.where.file, how))
    kinds.values["pipelines"] = tuple(pipelines)


def _controller_loads(files: PackageFiles, loads: Loads, fake: bool) -> list[tuple[YamlLoad, Located]]:
    """Loads of a `controller_list` file by the simple (or, `fake`, the fake) controller manager."""
    out = []
    for load in _by_preference(list(loads)):
        doc = files.yaml(load.file)
        if doc is None or not doc.is_mapping or "controller_list" not in doc.data:
            continue
        is_fake = "fake" in load.manager.lower() or (not load.manager and "fake" in Path(load.file).name)
        if is_fake == fake:
            out.append((load, doc))
    return out


def _ros1_controllers(
    files: PackageFiles,
    loads: Loads,
    kinds: Kinds,
    move_groups: tuple[str, ...],
    managers: tuple[tuple[str, ...], tuple[LaunchParam, ...]],
) -> None:
    """The simple manager's list: the one loaded into move_group's private namespace, where
    moveit_simple_controller_manager.cpp reads it (`node_handle_("~")`, `controller_list`); when
    several are, the last on a branch the defaults take of the first launch file a user starts
    that loads one (a later load overwrites the key; other entry points are other runs). Else
    the first the launch files load elsewhere (what MoveIt would read, were it where it belongs:
    `ControllersFile.elsewhere` says it is not), else the Setup Assistant's file names; others
    they load are alternatives; when no launch file loads one at all, the launch file that makes
    the simple manager move_group's (`controller_list_unloaded`). And the fake manager's.
    `managers`: every moveit_controller_manager value, and those set on default branches."""
    every_manager, taken_managers = managers
    kinds.values["controller_managers"] = taken_managers
    real = _controller_loads(files, loads, fake=False)
    landed = [(lo, d) for lo, d in real if lo.ns in move_groups]
    if real:
        taken = [x for x in landed if not x[0].conditional] or landed
        one_launch = [x for x in taken if x[0].entry == taken[0][0].entry]  # overwrites within one run
        used, doc = one_launch[-1] if one_launch else real[0]
        listed = read_controllers(doc)
        if move_groups and not landed and _simple_manager(real, every_manager):
            away = tuple(ListLoad(lo.launch, lo.line, lo.ns) for lo, _ in real)
            listed = replace(listed, elsewhere=away, read_at=move_groups)
        kinds.put("moveit_controllers", listed, doc, _loaded_by(used))
        others = {lo.file: d for lo, d in real if lo.file != used.file}
        kinds.values["alt_moveit_controllers"] = tuple(read_controllers(d) for d in others.values())
    else:
        named = [d for rel in ROS1_MOVEIT_CONTROLLERS if (d := _named(files, rel)) is not None]
        listed_files = [d for d in named if d.is_mapping and "controller_list" in d.data]
        fallback = [d for d in named if d.where.file in ROS1_MOVEIT_CONTROLLERS[:2]]
        found = (listed_files or fallback)[0] if listed_files or fallback else None
        kinds.put(
            "moveit_controllers", read_controllers(found) if found is not None else None, found, SA_NAME
        )
        kinds.values["controller_list_unloaded"] = _simple_set_by(taken_managers, move_groups)
    fake = _controller_loads(files, loads, fake=True)
    fake_doc, how = (
        (fake[0][1], _loaded_by(fake[0][0]))
        if fake
        else (_named(files, DEFAULT_FILES["fake_controllers"]), SA_NAME)
    )
    kinds.put(
        "fake_controllers",
        read_controllers(fake_doc, FAKE_KEYS) if fake_doc is not None else None,
        fake_doc,
        how,
    )


def _simple_set_by(taken_managers: tuple[LaunchParam, ...], move_groups: tuple[str, ...]) -> str:
    """The launch file that sets a move_group node's `~moveit_controller_manager` to the simple
    controller manager on a branch the defaults take ('' for none)."""
    for param in taken_managers:
        ns, _, leaf = param.name.rpartition("/")
        if leaf == MANAGER_PARAM and ns in move_groups and SIMPLE_MANAGER_CLASS in param.value:
            return param.launch
    return ""


def _simple_manager(real: list[tuple[YamlLoad, Located]], managers: tuple[str, ...]) -> bool:
    """A launch file makes moveit_simple_controller_manager move_group's manager (beside a
    controller list load, or anywhere: `<param name="moveit_controller_manager">`)."""
    return any(SIMPLE_MANAGER_CLASS in m for m in (*managers, *(lo.manager for lo, _ in real)))


def _ros1_sensors(files: PackageFiles, loads: Loads) -> tuple[Located | None, str]:
    """The file a launch file loads holding a `sensors` list, else the Setup Assistant's
    `config/sensors_3d.yaml` only when the launch files load no YAML this package's reader can
    follow (a bare config folder). Where they load the package's YAML and none of it is a
    sensors list (xarm_ros: sensor_manager.launch.xml's load commented out), move_group finds
    no `sensors` parameter and loads no updater (moveit/moveit moveit_ros/occupancy_map_monitor/
    src/occupancy_map_monitor.cpp l.106 and l.184 at fdb79ac): the file is never read."""
    for load in _by_preference(list(loads)):
        doc = files.yaml(load.file)
        if doc is not None and doc.is_mapping and isinstance(doc.data.get("sensors"), list):
            return doc, _loaded_by(load)
    if loads:
        return None, ""
    return _named(files, DEFAULT_FILES["sensors"]), SA_NAME


def _drivers(files: PackageFiles, kinds: Kinds, loads: Loads = ()) -> None:
    readers: dict[str, Callable[[Located], object]] = {
        "ros2_controllers": read_ros2_controllers,
        "ros_controllers": read_ros_controllers,
        "arbotix": read_arbotix,
        "initial_positions": read_initial_positions,
    }
    for kind, rel in DRIVER_FILES.items():
        if kind in kinds.values:
            continue
        doc, how = _named(files, rel), SA_NAME
        base = Path(rel).name
        loaded = next((lo for lo in _by_preference(list(loads)) if Path(lo.file).name == base), None)
        if doc is None and loaded is not None:
            doc, how = files.yaml(loaded.file), _loaded_by(loaded)
        if (
            kind == "initial_positions"
            and how == SA_NAME
            and doc is not None
            and not _names_initial_positions(files)
        ):
            doc = None
        kinds.put(kind, readers[kind](doc) if doc is not None else None, doc, how)


INITIAL_POSITIONS_READERS = (".xacro", ".urdf", ".py", ".xml", ".launch")


def _names_initial_positions(files: PackageFiles) -> bool:
    """Whether a xacro, URDF or launch file of the package names `initial_positions`: the mock
    hardware takes initial values from the URDF only (ros2_control mock_components
    generic_system.cpp, `initial_value`), and config/initial_positions.yaml gets there through
    a xacro loading it (moveit2 moveit_setup_assistant/moveit_setup_controllers
    templates/config/ros2_control.xacro l.3-4, src/control_xacro_config.cpp l.94). A file no
    such file names is read by nothing. A file too large to read counts as naming it."""
    from marm_setup.package.files import FileProblem

    for rel in files.listing():
        if not rel.endswith(INITIAL_POSITIONS_READERS):
            continue
        try:
            text = files.text(rel)
        except FileProblem:
            return True
        if text is not None and "initial_positions" in text:
            return True
    return False


def _servo(files: PackageFiles, loaded: list[str]) -> tuple[ServoConfig, ...]:
    """Servo configurations: files named `*servo*` in config/ and any loaded file holding one."""
    names = dict.fromkeys([*(f for f in files.glob("config/**/*.yaml") if "servo" in Path(f).name), *loaded])
    out = []
    for rel in names:
        doc = files.yaml(rel) if rel in loaded or files.is_file(rel) else None
        found = read_servo(doc) if doc is not None else None
        if found is not None:
            out.append(found)
    return tuple(out)


# -- ROS 2 ------------------------------------------------------------------------------------


def read_ros2_kinds(
    files: PackageFiles,
    loads: tuple[YamlLoad, ...],
    builder: BuilderFiles,
    control_files: tuple[str, ...],
    named_yaml: tuple[tuple[str, str], ...] = (),
    by_hand: tuple[str, ...] | None = None,
) -> Kinds:
    """What the builder loads, then the files XML launch files hand to nodes over it. `by_hand`:
    the files the launch file of another package that starts MoveIt with this one loads by hand
    (no MoveItConfigsBuilder): a file of the Setup Assistant's name it does not load is not
    MoveIt's (None: how the package is launched is not known)."""
    kinds = Kinds()
    root = files.root
    opaque = _opaque_kinds(builder)
    kinds.values["opaque"] = opaque_summary(builder, opaque)
    kinds.values["opaque_methods"] = opaque
    for kind, method, reader in (
        ("kinematics", "robot_description_kinematics", read_kinematics),
        ("joint_limits", "joint_limits", read_joint_limits),
    ):
        if method in opaque:
            continue
        chosen = _loaded(chosen_file(builder, method, root), by_hand)
        doc = _named(files, chosen.file) if chosen is not None else None
        top_level_by = ""
        if doc is not None and kind == "kinematics" and not builder.calls:
            doc, top_level_by = _node_kinematics(files, doc, loads, named_yaml)
        if doc is not None and kind == "joint_limits" and not builder.calls:
            doc = _node_joint_limits(files, doc, named_yaml)
        value = reader(doc) if doc is not None else None
        if isinstance(value, KinematicsFile) and top_level_by:
            value = replace(value, top_level_by=top_level_by)
        kinds.put(kind, value, doc, chosen.how if chosen else SA_NAME)
    if "trajectory_execution" not in opaque:
        _ros2_controllers(files, builder, kinds, named_yaml)
    if "planning_pipelines" not in opaque:
        _ros2_pipelines(files, builder, kinds, named_yaml)
    chosen = (
        _loaded(chosen_file(builder, "sensors_3d", root), by_hand) if "sensors_3d" not in opaque else None
    )
    doc = _named(files, chosen.file) if chosen is not None else None
    kinds.put("sensors", read_sensors(doc) if doc is not None else None, doc, chosen.how if chosen else "")
    for rel in control_files:
        doc = _named(files, rel)
        if doc is not None and "ros2_controllers" not in kinds.values:
            kinds.put(
                "ros2_controllers",
                read_ros2_controllers(doc),
                doc,
                "handed to ros2_control_node by a launch file",
            )
    _drivers(files, kinds)
    _ros2_sensor_loads(files, loads, kinds)
    # No fake_controllers.yaml: MoveIt 2 has no fake controller manager to read one (deleted by
    # moveit/moveit2#471, 2021; humble and jazzy moveit_plugins/ hold only
    # moveit_simple_controller_manager and moveit_ros_control_interface). Such a file in a ROS 2
    # package is another node's parameters or a MoveIt 1 leftover, never move_group's.
    kinds.values["servo"] = _servo(files, [load.file for load in loads])
    return kinds


def _loaded(chosen: Chosen | None, by_hand: tuple[str, ...] | None) -> Chosen | None:
    """`chosen`, unless the package's launcher loads files by hand and not this one."""
    if chosen is None or by_hand is None or chosen.file in by_hand:
        return chosen
    return None


OPAQUE_METHODS = (  # MoveItConfigsBuilder methods whose files validate reads as one kind
    ("robot_description_kinematics", "kinematics"),
    ("joint_limits", "joint limits"),
    ("trajectory_execution", "MoveIt's controller list"),
    ("planning_pipelines", "planning pipelines"),
    ("sensors_3d", "3D sensors"),
)


def _opaque_kinds(builder: BuilderFiles) -> tuple[str, ...]:
    """The builder methods (OPAQUE_METHODS) only a foreign builder calls: what it loads for them,
    where it puts it and what it merges in are its own code's (package/builder.py), so those
    kinds are not read through it."""
    return tuple(method for method, _ in OPAQUE_METHODS if builder.opaque(method) is not None)


def opaque_summary(builder: BuilderFiles, methods: tuple[str, ...]) -> tuple[str, ...]:
    """The summary's line per foreign builder call for what validate did not read through it."""
    out = []
    for call in dict.fromkeys(c for m in methods if (c := builder.opaque(m)) is not None):
        kinds = ", ".join(
            what for method, what in OPAQUE_METHODS if method in methods and method in call.methods
        )
        out.append(
            f"the {kinds} of {call.launch}'s MoveItConfigsBuilder from {call.origin or 'no import'} "
            "(not moveit_configs_utils': validate cannot see what it loads or where it puts it)"
        )
    return tuple(out)


def _node_kinematics(
    files: PackageFiles, doc: Located, loads: Loads, named_yaml: tuple[tuple[str, str], ...]
) -> tuple[Located, str]:
    """A kinematics file no MoveItConfigsBuilder wraps (a launch hands it to move_group itself),
    and the launch file that hands its groups to move_group as top-level parameters ('' when
    they land under robot_description_kinematics, or no launch file shows where they land).
    A ROS 2 parameter file (`/**: ros__parameters:`) holds move_group's own parameters, where
    MoveIt reads `<group>.kinematics_solver` (Humble, before robot_description_kinematics.<group>:
    humble kinematics_plugin_loader.cpp l.306-319) or `robot_description_kinematics.<group>`
    (humble; jazzy kinematics_plugin_loader.cpp l.260, the only place Jazzy and later look). A
    plain file a Python launch lists itself among move_group's parameters (`load_yaml(...)`, not
    `{"robot_description_kinematics": load_yaml(...)}`) is top-level too."""
    from marm_setup.package.launch_python import hands_bare_to_move_group

    rel = doc.where.file
    bare = _bare_namespace(files, doc, "robot_description_kinematics", named_yaml)
    if bare is not None:
        return bare, ""
    params = unwrap_parameters(doc)
    if params is not doc:
        nested = params.get("robot_description_kinematics")
        if nested.is_mapping:
            return nested, ""
        by = [lo.launch for lo in loads if lo.file == rel and lo.ns == MOVE_GROUP and not lo.conditional]
        doc = params
    else:
        by = []
    by += [
        launch for r, launch in named_yaml if r == rel and hands_bare_to_move_group(files.root, launch, rel)
    ]
    return doc, by[0] if by else ""


def _node_joint_limits(files: PackageFiles, doc: Located, named_yaml: tuple[tuple[str, str], ...]) -> Located:
    """A joint limits file no MoveItConfigsBuilder wraps, as a ROS 2 parameter file
    (`/**/move_group: ros__parameters:`): move_group's own parameters, where MoveIt reads
    `robot_description_planning.joint_limits.<joint>` (moveit2 robot_model_loader.cpp l.133);
    or a plain file a launch hands over as it is, holding that namespace itself."""
    bare = _bare_namespace(files, doc, "robot_description_planning", named_yaml)
    if bare is not None:
        return bare
    params = unwrap_parameters(doc)
    if params is doc:
        return doc
    nested = params.get("robot_description_planning")
    return nested if nested.is_mapping else params


def _bare_namespace(
    files: PackageFiles, doc: Located, key: str, named_yaml: tuple[tuple[str, str], ...]
) -> Located | None:
    """The `key` section of a plain YAML file (no `ros__parameters`) whose top level holds that
    parameter namespace, when the Python launch files that name it hand its dict over as it is
    (`params.update(load_yaml(path))`, not `{key: load_yaml(path)}`): its top-level keys become
    the node's parameters, so `key.<...>` is where MoveIt reads. None otherwise."""
    from marm_setup.package.launch_python import launch_yaml_key

    if unwrap_parameters(doc) is not doc or not doc.get(key).is_mapping:
        return None
    rel = doc.where.file
    launches = {launch for r, launch in named_yaml if r == rel}
    if not launches or any(launch_yaml_key(files.root, launch, rel) is not None for launch in launches):
        return None
    return doc.get(key)


def _ros2_sensor_loads(files: PackageFiles, loads: Loads, kinds: Kinds) -> None:
    """A parameter file an XML launch file hands to a node (`<param from>`, as our
    move_group.launch.xml does with config/sensors_3d.yaml) holding a `sensors` list, over the
    builder's."""
    for load in _by_preference(list(loads)):
        doc = files.yaml(load.file)
        params = unwrap_parameters(doc) if doc is not None else None
        if params is not None and params.is_mapping and isinstance(params.data.get("sensors"), list):
            kinds.put(
                "sensors", read_sensors(params), params, f"handed to {load.ns or 'a node'} by {load.launch}"
            )
            return


def _ros2_controllers(
    files: PackageFiles, builder: BuilderFiles, kinds: Kinds, named_yaml: tuple[tuple[str, str], ...]
) -> None:
    """MoveIt's controllers: the builder's file; else the YAML with a MoveIt controller list
    that a Python launch names (one that loads it by hand). When no launch file calls
    MoveItConfigsBuilder, the file a launch loads by hand comes first: the builder's guess
    among `config/*_controllers.yaml` (moveit_configs_utils moveit_configs_builder.py
    `trajectory_execution`) only runs inside a builder, so a `fake_controllers.yaml` beside a
    hand-loaded `controllers.yaml` is not what move_group gets."""
    chosen, into = (controllers_file(builder, files.root), "") if builder.calls else (None, "")
    if chosen is None:
        chosen, into = _named_controllers(files, named_yaml)
    unknown = chosen is None and not builder.calls
    if unknown:
        chosen = controllers_file(builder, files.root)
    if chosen is None and (launch := builder.computed("trajectory_execution")):
        files.problems.append(_runtime_controllers(launch))
    doc = _named(files, chosen.file) if chosen is not None else None
    if doc is not None and chosen is not None:
        listed = replace(read_controllers(unwrap_parameters(doc)), loaded_into=into, load_unknown=unknown)
        kinds.put("moveit_controllers", listed, doc, chosen.how)
    alternatives = []
    for rel in files.glob("config/*_controllers.yaml"):
        other = _named(files, rel) if chosen is None or rel != chosen.file else None
        if other is not None and _is_moveit_controllers(unwrap_parameters(other)):
            alternatives.append(read_controllers(unwrap_parameters(other)))
    kinds.values["alt_moveit_controllers"] = tuple(alternatives)


def _runtime_controllers(launch: str) -> Finding:
    msg = (
        f"MoveIt's controller list is the file {launch} passes to "
        "MoveItConfigsBuilder.trajectory_execution, a path only the run time computes: the controller rules are skipped"
    )
    return warning("controller.runtime-only", launch, "trajectory_execution", msg)


def _named_controllers(
    files: PackageFiles, named_yaml: tuple[tuple[str, str], ...]
) -> tuple[Chosen | None, str]:
    """The controller list a Python launch loads by hand, and the key it puts it under ('' for
    none: `{"moveit_simple_controller_manager": load_yaml(...)}` gives that key)."""
    for rel, launch in named_yaml:
        doc = _named(files, rel)
        if doc is not None and _is_moveit_controllers(unwrap_parameters(doc)):
            into = launch_yaml_key(files.root, launch, rel) or ""
            where = f" under {into}" if into else ""
            how = f"loaded by hand (named in {launch}){where} as moveit_simple_controller_manager's list"
            return Chosen(rel, how), into
    return None, ""


def _is_moveit_controllers(doc: Located) -> bool:
    data = doc.data if isinstance(doc.data, dict) else {}
    return isinstance(data.get(SIMPLE_MANAGER), dict) or isinstance(data.get("controller_names"), list)


def _ros2_pipelines(
    files: PackageFiles, builder: BuilderFiles, kinds: Kinds, named_yaml: tuple[tuple[str, str], ...] = ()
) -> None:
    pipelines: list[PlanningPipeline] = []
    for name in planning_pipelines(builder, files.root):
        doc = _named(files, f"config/{name}_planning.yaml")
        if doc is not None:
            params = unwrap_parameters(doc)
            pipeline = read_pipeline(name, params)
            if not builder.calls:
                pipeline = _with_launch_settings(files, pipeline, named_yaml)
            elif name == "ompl" and params.is_mapping and "planner_configs" not in params.data:
                pipeline = with_builder_ompl_defaults(pipeline)
            pipelines.append(pipeline)
            how = "MoveItConfigsBuilder.planning_pipelines" + (
                " (the pipelines a launch file names)"
                if builder.pipelines is not None
                else " (every config/*_planning.yaml)"
            )
            kinds.sources.append(Source(f"pipeline:{name}", doc.where.file, how))
    kinds.values["pipelines"] = tuple(sorted(pipelines, key=lambda p: (p.name != "ompl", p.name)))


def _with_launch_settings(
    files: PackageFiles, pipeline: PlanningPipeline, named_yaml: tuple[tuple[str, str], ...]
) -> PlanningPipeline:
    """A pipeline file a Python launch loads by hand into a dict where it sets the planning
    plugin itself (`{"move_group": {"planning_plugin": ..., "request_adapters": ...}}` updated with
    the file, as MoveIt 2's Humble-era tutorials do): move_group gets those settings too, the
    file's own winning as dict.update gives them. Humble's move_group without a
    `planning_pipelines` parameter plans with that `move_group` namespace (humble
    moveit_ros/move_group/src/move_group.cpp l.254-267)."""
    from marm_setup.package.launch_python import launch_pipeline_settings

    if not pipeline.is_mapping:
        return pipeline
    launch = next((lf for rel, lf in named_yaml if rel == pipeline.where.file), None)
    if launch is None:
        return pipeline
    have = {p.key for p in pipeline.settings}
    extra = tuple(
        Param(key, value, Where(launch, (key,)))
        for key, value in launch_pipeline_settings(files.root, launch)
        if key not in have
    )
    return replace(pipeline, settings=(*pipeline.settings, *extra)) if extra else pipeline


def read_move_group_file(files: PackageFiles, kinds: Kinds, rel: str, how: str) -> tuple[Param, ...] | None:
    """The sections of a move_group parameter file (our `config/moveit.yaml`), over the kinds
    found so far: each section it holds replaces the file-based one. Returns move_group's own
    top-level parameters, or None when the file is not one node's `ros__parameters`."""
    raw = files.yaml(rel)
    if raw is None:
        return None
    params = unwrap_parameters(raw)
    if params is raw or not params.is_mapping:
        return None
    for kind, key, reader in (
        ("kinematics", "robot_description_kinematics", read_kinematics),
        ("joint_limits", "robot_description_planning", read_joint_limits),
        ("moveit_controllers", SIMPLE_MANAGER, _read_manager),
    ):
        section = params.get(key)
        if section.data is not None:
            kinds.put(kind, reader(section), section, how)
    _move_group_pipelines(params, kinds, how)
    sensors = read_sensors(params)
    kinds.put("sensors", sensors, params if sensors is not None else None, how)
    return tuple(p for p in params.params() if "." not in p.key)


def _read_manager(section: Located) -> ControllersFile:
    return read_controllers(
        Located(
            Where(section.where.file, section.where.keys[:-1]),
            {SIMPLE_MANAGER: section.data},
            section.lines,
            section.raw[:-1],
        )
    )


def _move_group_pipelines(params: Located, kinds: Kinds, how: str) -> None:
    names = params.get("planning_pipelines").data
    names = names.get("pipeline_names", []) if isinstance(names, dict) else names
    listed = [str(n) for n in names] if isinstance(names, list) else []
    if "ompl" not in listed and params.get("ompl").data is not None:
        listed.insert(0, "ompl")
    pipelines = [read_pipeline(n, params.get(n)) for n in listed if params.get(n).is_mapping]
    if pipelines:
        kinds.values["pipelines"] = tuple(sorted(pipelines, key=lambda p: (p.name != "ompl", p.name)))
        kinds.sources = [s for s in kinds.sources if not s.kind.startswith("pipeline:")]
        kinds.sources += [Source(f"pipeline:{p.name}", p.where.file, how) for p in pipelines]


__all__ = [
    "Chosen",
    "Kinds",
    "read_move_group_file",
    "read_ros1_kinds",
    "read_ros2_kinds",
    "unwrap_parameters",
]
