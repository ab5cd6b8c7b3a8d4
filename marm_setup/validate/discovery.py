"""Find and read the artefacts of a MoveIt config package (ours, or the Setup Assistant's).

`discover_package(path, urdf=None, xacro_args=(), package_paths=())` returns a frozen
`ConfigPackage`. It reads files but never judges them: problems reading a file (bad YAML, a
broken SRDF) are returned in `ConfigPackage.problems` as findings; only a folder that is not a
config package at all raises `InputError` (exit 2).

`ConfigPackage` fields (read by validate rules and by the runtime planner checks):

- `root` (Path, absolute) and `shown` (the folder as the user typed it).
- `name`: `<name>` from package.xml, or the folder name. `package_xml`: its relative path or None.
- `target`: `ros1` (catkin, MoveIt 1) or `ros2` (ament, MoveIt 2).
- `layout`: `moveit1` (one YAML per concern), `moveit2` (MoveIt 2 Setup Assistant files) or
  `marm_ros2` (our single `config/moveit.yaml`).
- `urdf` (Path), `urdf_origin` (`--urdf`, `marm_setup.yaml`, `.setup_assistant` or
  `config/<robot>.urdf.xacro`), `xacro_args` (tuple of (name, value)), `package_paths`
  (tuple of Path for `$(find ...)`: this package first, so `$(find <itself>)` is this copy,
  then the user's, then marm_setup.yaml's `robot.package_paths`, then the folder holding this
  package).
- `srdf_path` (relative str | None) and `srdf` (a `marm_setup.setup.srdf.Srdf`, as `read_srdf` gives, or None
  when absent/unreadable; a `.srdf.xacro` is expanded first); `srdf_text` the (expanded) XML.
- Parsed YAML sections, each a `ConfigSection(file, data, prefix)` or None: `file` is the path
  relative to the package, `data` the mapping MoveIt reads, `prefix` the dotted key path of that
  mapping inside the file (`""` for a whole file; e.g. `robot_description_kinematics` in
  `config/moveit.yaml`), so findings can name `prefix.key`:
  `kinematics` ({group: {kinematics_solver, ...}}), `joint_limits` ({joint_limits: {...},
  default_*_scaling_factor}), `ompl` ({planner_configs: {...}, group: {...}}),
  `moveit_controllers` (MoveIt's controller manager: ros1 `{controller_list: [...]}` or ros2
  `{controller_names: [...], <name>: {...}}`), `alt_moveit_controllers` (tuple: other
  `*moveit_controllers.yaml` files a launch may choose instead), `fake_controllers` (ros1
  `{controller_list, initial}`), `ros2_controllers` (the `controller_manager` file, whole),
  `ros_controllers` (ros1 ros_control file, whole), `arbotix` (ArbotiX driver file, whole),
  `initial_positions` ({initial_positions: {joint: value}}), `marm_setup` (marm_setup.yaml).
- `launch_files`: relative paths of `launch/*.launch`, `*.launch.xml`, `*.xml`.
- `problems`: findings for files that could not be read (rule ids `yaml.parse`, `srdf.parse`).

`ConfigPackage.path(rel)` gives the absolute path of a relative one.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import yaml

from marm_setup.bounded_read import YAML_BYTES, FileTooLarge, read_text
from marm_setup.errors import InputError
from marm_setup.findings import Finding, error, warning
from marm_setup.robot.ros_packages import package_name
from marm_setup.validate.roslaunch_yaml import (
    SubstitutionError,
    launch_srdf,
    load_ros_yaml,
    loaded_files,
    subst_contexts,
    substitute,
)
from marm_setup.validate.sources import (
    MARM_MOVEIT_YAML,
    detect_target,
    find_srdf,
    find_urdf,
    marm_package_paths,
    read_srdf_source,
    srdf_robot_name,
)

YAML_NAMES = {
    "kinematics": ("config/kinematics.yaml",),
    "joint_limits": ("config/joint_limits.yaml",),
    "ompl": ("config/ompl_planning.yaml",),
    "fake_controllers": ("config/fake_controllers.yaml",),
    "ros2_controllers": ("config/ros2_controllers.yaml",),
    "ros_controllers": ("config/ros_controllers.yaml",),
    "arbotix": ("config/arbotix.yaml",),
    "initial_positions": ("config/initial_positions.yaml",),
}
ROS1_MOVEIT_CONTROLLERS = (
    "config/controllers.yaml",
    "config/simple_moveit_controllers.yaml",
    "config/ros_controllers.yaml",  # old Setup Assistant (controller_list inside)
)
ROS2_MOVEIT_CONTROLLERS = ("config/moveit_controllers.yaml",)


@dataclass(frozen=True, slots=True)
class ConfigSection:
    """A parsed YAML mapping: `file` relative to the package, `prefix` its key path in the file."""

    file: str
    data: Any
    prefix: str = ""

    def element(self, *keys: object) -> str:
        """Dotted element name for findings: `prefix.key1.key2`."""
        return ".".join(str(k) for k in (self.prefix, *keys) if str(k))


@dataclass(frozen=True)
class ConfigPackage:
    root: Path
    shown: str
    name: str
    target: str
    layout: str
    urdf: Path  # discovery fails (InputError) when there is none
    urdf_origin: str
    xacro_args: tuple[tuple[str, str], ...] = ()
    package_paths: tuple[Path, ...] = ()
    package_xml: str | None = None
    srdf_path: str | None = None
    srdf: Any = None
    srdf_text: str | None = None
    kinematics: ConfigSection | None = None
    joint_limits: ConfigSection | None = None
    ompl: ConfigSection | None = None
    moveit_controllers: ConfigSection | None = None
    alt_moveit_controllers: tuple[ConfigSection, ...] = ()
    fake_controllers: ConfigSection | None = None
    ros2_controllers: ConfigSection | None = None
    ros_controllers: ConfigSection | None = None
    arbotix: ConfigSection | None = None
    initial_positions: ConfigSection | None = None
    marm_setup: ConfigSection | None = None
    launch_files: tuple[str, ...] = ()
    problems: tuple[Finding, ...] = ()

    def path(self, rel: str) -> Path:
        return self.root / rel

    def user_path(self, rel: str | None) -> str:
        """A package file as the user would type it (`DIR/rel`), for error messages."""
        return str(Path(self.shown) / rel) if rel else self.shown


# -- entry point -------------------------------------------------------------------------------


def discover_package(
    path: str | Path,
    *,
    urdf: str | Path | None = None,
    srdf: str | Path | None = None,
    xacro_args: Mapping[str, str] | None = None,
    package_paths: Iterable[str | Path] = (),
) -> ConfigPackage:
    """Read a config package folder; InputError when it is not one."""
    shown = str(path)
    root = Path(path).resolve()
    if not root.is_dir():
        raise InputError("not a folder", path=shown)
    problems: list[Finding] = []
    reader = _YamlReader(root, problems)
    marm = reader.section("marm_setup.yaml")
    marm_data = marm.data if marm is not None else None
    setup_assistant = reader.raw(".setup_assistant")
    pkg_xml = "package.xml" if (root / "package.xml").is_file() else None
    user_paths = tuple(Path(p).resolve() for p in package_paths)
    paths = (root, *user_paths, *marm_package_paths(root, marm_data), root.parent)
    target = detect_target(root, marm_data)
    launch_files = _launch_files(root)
    _prepare_launch(reader, root, launch_files, paths, target)
    srdf_rel, srdf_args = _srdf_choice(root, srdf, marm_data, setup_assistant, reader, problems)
    if pkg_xml is None and srdf_rel is None:
        raise InputError("not a MoveIt config package (no package.xml and no config/*.srdf)", path=shown)
    robot_name = srdf_robot_name(root, srdf_rel)
    urdf_path, origin, args = find_urdf(
        root, shown, urdf, xacro_args, marm_data, setup_assistant, paths, robot_name
    )
    moveit_yaml = reader.raw(MARM_MOVEIT_YAML) if target == "ros2" else None
    sections = _read_sections(reader, target, moveit_yaml)
    srdf_xacro_args = {**dict(srdf_args), **dict(xacro_args or {})}
    parsed, srdf_text = (
        read_srdf_source(root, srdf_rel, paths, problems, srdf_xacro_args) if srdf_rel else (None, None)
    )
    return ConfigPackage(
        root=root,
        shown=shown,
        name=package_name(root) or root.name,
        target=target,
        layout="marm_ros2" if moveit_yaml is not None else ("moveit2" if target == "ros2" else "moveit1"),
        urdf=urdf_path,
        urdf_origin=origin,
        xacro_args=args,
        package_paths=paths,
        package_xml=pkg_xml,
        srdf_path=srdf_rel,
        srdf=parsed,
        srdf_text=srdf_text,
        marm_setup=marm,
        launch_files=launch_files,
        problems=tuple(problems),
        **sections,
    )


def _srdf_choice(root, given, marm_data, setup_assistant, reader, problems):
    """(relative SRDF path or None, its xacro args): `--srdf` when given, else `find_srdf`."""
    if given is None:
        return find_srdf(root, marm_data, setup_assistant, reader.launch_srdf, problems)
    if not Path(given).is_file():
        raise InputError("file not found", path=str(given), element="--srdf")
    return Path(os.path.relpath(Path(given).resolve(), root)).as_posix(), ()


def _prepare_launch(
    reader: _YamlReader, root: Path, launch_files: tuple[str, ...], paths: tuple[Path, ...], target: str
) -> None:
    """What the ROS 1 launch files load: subst_value files and their args, rosparam files, the SRDF."""
    if target != "ros1":
        return
    from marm_setup.robot.ros_packages import PackageIndex, find_packages

    try:
        packages = find_packages(paths)
    except InputError:
        packages = PackageIndex()
    reader.find = lambda name: str(packages[name]) if name in packages else None
    reader.contexts = subst_contexts(root, launch_files, reader.find)
    reader.loaded = tuple(loaded_files(root, launch_files, reader.find))
    reader.launch_srdf = launch_srdf(root, launch_files, reader.find)


# -- YAML --------------------------------------------------------------------------------------


class _YamlReader:
    """Reads YAML files under `root` once, as roslaunch would (rosparam's angle tags; the
    substitutions of a `subst_value` load), recording failures as findings."""

    def __init__(self, root: Path, problems: list[Finding]):
        self.root = root
        self.problems = problems
        self.cache: dict[str, Any] = {}
        self.contexts: dict[str, tuple[dict[str, str], str]] = {}
        self.find: Callable[[str], str | None] = lambda _name: None
        self.loaded: tuple[str, ...] = ()  # files the launch files load with <rosparam file=...>
        self.launch_srdf: tuple[str, tuple[tuple[str, str], ...]] | None = None

    def raw(self, rel: str) -> Any:
        if rel not in self.cache:
            self.cache[rel] = self._load(rel)
        return self.cache[rel]

    def _load(self, rel: str) -> Any:
        file = self.root / rel
        if not file.is_file():
            return None
        try:
            data = load_ros_yaml(self._text(rel, read_text(file, YAML_BYTES, shown=rel)))
        except yaml.YAMLError as exc:
            mark = getattr(exc, "problem_mark", None)
            where = f"line {mark.line + 1}" if mark is not None else ""
            self.problems.append(error("yaml.parse", rel, where, f"malformed YAML: {_yaml_msg(exc)}"))
            return None
        except SubstitutionError as exc:
            msg = f"cannot evaluate {exc} (loaded with subst_value): its rules were skipped"
            self.problems.append(warning("yaml.substitution", rel, "", msg))
            return None
        except (OSError, UnicodeDecodeError) as exc:
            self.problems.append(error("yaml.parse", rel, "", f"cannot read: {exc}"))
            return None
        except FileTooLarge as exc:
            self.problems.append(error("yaml.parse", rel, "", f"cannot read: {exc.message}"))
            return None
        return {} if data is None else data

    def _text(self, rel: str, text: str) -> str:
        if rel not in self.contexts:
            return text
        args, dirname = self.contexts[rel]
        return substitute(text, args, self.find, dirname)

    def section(self, rel: str) -> ConfigSection | None:
        data = self.raw(rel)
        return None if data is None else ConfigSection(rel, data)


def _yaml_msg(exc: yaml.YAMLError) -> str:
    problem = getattr(exc, "problem", None)
    return str(problem) if problem else str(exc).splitlines()[0]


def _read_sections(reader: _YamlReader, target: str, moveit_yaml: Any) -> dict[str, Any]:
    out: dict[str, Any] = {key: _first(reader, names) for key, names in YAML_NAMES.items()}
    if target == "ros2":
        out["moveit_controllers"] = _ros2_moveit_controllers(reader)
        out["alt_moveit_controllers"] = _alt_controllers(reader, out["moveit_controllers"])
    else:
        out["moveit_controllers"] = _first_with(reader, ROS1_MOVEIT_CONTROLLERS, "controller_list") or _first(
            reader, ROS1_MOVEIT_CONTROLLERS[:2]
        )
        out["alt_moveit_controllers"] = ()
    if moveit_yaml is not None:
        reader.problems.extend(ros2_parameter_file_problems(moveit_yaml, MARM_MOVEIT_YAML))
        out.update(_marm_moveit_sections(moveit_yaml, out))
    return out


def ros2_parameter_file_problems(raw: Any, file: str) -> list[Finding]:
    """A ROS 2 parameter file maps node names (or `/**`), optionally under a namespace, to
    `{ros__parameters: {...}}` (ros2/rcl rcl_yaml_param_parser/README.md); rcl rejects anything
    else and the node does not start."""
    if not isinstance(raw, dict) or not raw:
        return [error("yaml.ros2-params", file, "", "expected a mapping of node names to ros__parameters")]
    return [
        error("yaml.ros2-params", file, str(node), "expected {ros__parameters: {...}} under a node name")
        for node, value in raw.items()
        if not (
            _node_params(value)
            or (isinstance(value, dict) and value and all(map(_node_params, value.values())))
        )
    ]


def _node_params(value: Any) -> bool:
    return isinstance(value, dict) and isinstance(value.get("ros__parameters"), dict)


def _first(reader: _YamlReader, names: tuple[str, ...]) -> ConfigSection | None:
    """The first of `names` that exists, else a file of the same name in a sub-folder that a
    launch file loads (e.g. `config/7dof/joint_limits.yaml`)."""
    basenames = {Path(n).name for n in names}
    for rel in (*names, *(f for f in reader.loaded if Path(f).name in basenames)):
        section = reader.section(rel)
        if section is not None:
            return section
    return None


def _first_with(reader: _YamlReader, names: tuple[str, ...], key: str) -> ConfigSection | None:
    for rel in names:
        section = reader.section(rel)
        if section is not None and isinstance(section.data, dict) and key in section.data:
            return section
    return None


def _ros2_moveit_controllers(reader: _YamlReader) -> ConfigSection | None:
    for rel in ROS2_MOVEIT_CONTROLLERS:
        section = reader.section(rel)
        if section is not None:
            return _simple_manager(section)
    return None


def _simple_manager(section: ConfigSection) -> ConfigSection:
    """The `moveit_simple_controller_manager` mapping of a ros2 controllers file, if present."""
    data = _unwrap_ros_parameters(section.data)
    if isinstance(data, dict) and isinstance(data.get("moveit_simple_controller_manager"), dict):
        prefix = "moveit_simple_controller_manager"
        return ConfigSection(section.file, data[prefix], _join(section.prefix, prefix))
    return section


def _alt_controllers(reader: _YamlReader, primary: ConfigSection | None) -> tuple[ConfigSection, ...]:
    out = []
    for file in sorted((reader.root / "config").glob("*moveit_controllers.yaml")):
        rel = file.relative_to(reader.root).as_posix()
        if primary is not None and rel == primary.file:
            continue
        section = reader.section(rel)
        if section is not None:
            out.append(_simple_manager(section))
    return tuple(out)


def _unwrap_ros_parameters(data: Any) -> Any:
    """`{node: {ros__parameters: X}}` (or `/**`) -> X; anything else unchanged."""
    if isinstance(data, dict) and len(data) == 1:
        (value,) = data.values()
        if isinstance(value, dict) and "ros__parameters" in value:
            return value["ros__parameters"]
    return data


def _join(*parts: str) -> str:
    return ".".join(p for p in parts if p)


def _marm_moveit_sections(raw: Any, current: dict[str, Any]) -> dict[str, Any]:
    """Sections of our single-file ros2 layout (`config/moveit.yaml`)."""
    prefix = ""
    data = raw
    if isinstance(raw, dict) and len(raw) == 1:
        (node,) = raw
        if isinstance(raw[node], dict) and "ros__parameters" in raw[node]:
            prefix, data = f"{node}.ros__parameters", raw[node]["ros__parameters"]
    if not isinstance(data, dict):
        return {}

    def sub(key: str) -> ConfigSection | None:
        value = data.get(key)
        return None if value is None else ConfigSection(MARM_MOVEIT_YAML, value, _join(prefix, key))

    out: dict[str, Any] = {}
    for field, key in (
        ("kinematics", "robot_description_kinematics"),
        ("joint_limits", "robot_description_planning"),
        ("ompl", "ompl"),
        ("moveit_controllers", "moveit_simple_controller_manager"),
    ):
        section = sub(key)
        if section is not None or current.get(field) is None:
            out[field] = section
    return out


def _launch_files(root: Path) -> tuple[str, ...]:
    folder = root / "launch"
    if not folder.is_dir():
        return ()
    files = [p for p in folder.rglob("*") if p.is_file() and (p.suffix in (".launch", ".xml"))]
    return tuple(sorted(p.relative_to(root).as_posix() for p in files))
