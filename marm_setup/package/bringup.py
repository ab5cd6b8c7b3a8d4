"""The robot a launch file of another package gives a config package that has none of its own.

Vendors often ship a config package with no launch file that sets `robot_description`: a
bringup package starts move_group (or a MoveItCpp node) with the config's SRDF and YAML and
its own robot description. What MoveIt loads is that description: the RDFLoader reads the
node's `robot_description` and `robot_description_semantic` parameters, whichever launch file
set them (moveit/moveit2 moveit_ros/planning/rdf_loader/src/rdf_loader.cpp l.86-99 at 8fcb5d2).

A launch file qualifies when it lies in `launch/` of a package the package paths hold (not the
config package itself), names the config package (`get_package_share_directory("X")`,
`FindPackageShare("X")`, also through a launch argument's default, the name passed to a helper
such as `load_yaml("X", ...)`, `MoveItConfigsBuilder(..., package_name="X")`, `$(find X)`,
`$(find-pkg-share X)`), starts a MoveIt node (`move_group`, or a node handed
`robot_description_semantic`), and sets `robot_description` to a file validate can read
statically: a xacro command or xacro's Python API, the builder's `.robot_description(file_path)`
(relative paths are the config package's: the builder joins them to its package path, moveit2
moveit_configs_utils/moveit_configs_builder.py `robot_description`), or an XML launch file's
`robot_description` param. Of several, the one with the fewest xacro args of unknown value
wins, then the package path order, then the file path.
"""

from __future__ import annotations

import ast
import dataclasses
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from marm_setup.ros import Target
from marm_setup.untrusted import inside, readable

if TYPE_CHECKING:
    from marm_setup.package.launch_python import BuilderCall, PythonLaunch
    from marm_setup.package.launch_ros1 import DescriptionLoad
    from marm_setup.robot import PackageIndex


Found = tuple[Path, tuple[tuple[str, str], ...], tuple[str, ...]]  # (file, xacro args, unread args)
Robot = tuple[Found, Found | None, tuple[str, ...] | None]  # description, SRDF, files loaded by hand

MOVEIT_NODE_WORDS = ("move_group", "robot_description_semantic")


@dataclass(frozen=True, slots=True)
class BringupRobot:
    """The description a bringup launch file sets: its file, its xacro args (those of unknown
    value apart), the launch file (shown as `<package>/<path>`) and how many launch files
    qualified."""

    urdf: Path
    args: tuple[tuple[str, str], ...]
    unread_args: tuple[str, ...]
    semantic: Found | None  # the SRDF the same launch file sets, when validate can read it
    launch: str
    qualified: int = 1
    launch_path: Path | None = None  # the launch file itself
    # the config package's YAML files (relative to it) the launch file loads by hand, when it
    # loads none through MoveItConfigsBuilder: what MoveIt gets of the package (None: unknown)
    hand_loaded: tuple[str, ...] | None = None

    @property
    def origin(self) -> str:
        """How validate's summary says where the robot came from."""
        why = "a launch file of another package that starts MoveIt with this config package"
        if self.qualified > 1:
            why += (
                f"; chosen among {self.qualified} such files: fewest xacro args of unknown value, "
                "then package path order"
            )
        return f"robot_description in {self.launch} ({why})"


def find_bringup_robot(
    name: str, root: Path, paths: tuple[Path, ...], target: Target, args: Mapping[str, str] | None = None
) -> BringupRobot | None:
    """The robot the bringup launch files of the packages under `paths` give the config
    package `name` at `root` (module docstring), each launch file given the launch arguments
    `args`, or None when no launch file qualifies."""
    from marm_setup.robot import find_packages

    index = find_packages(paths, environ={})
    find = _finder(index)
    found: list[tuple[tuple[int, int, str], BringupRobot]] = []
    for package, folder in index.manifests.items():
        order = next((i for i, p in enumerate(paths) if inside(folder, (p,))), None)
        if order is None or folder.resolve() == root.resolve():
            continue
        for rel, robot in _package_robots(folder, package, name, root, find, (target, args or {})):
            found.append(((len(robot.unread_args), order, f"{package}/{rel}"), robot))
    if not found:
        return None
    found.sort(key=lambda item: item[0])
    best = found[0][1]
    return dataclasses.replace(best, qualified=len(found))


@dataclass(frozen=True)
class _Query:
    """What a bringup launch file is read for: the config package `name` at `root`, the package
    finder (recording the packages it is `asked` for), the target, and the launch arguments."""

    name: str
    root: Path
    find: Callable[[str], str | None]
    target: Target
    args: Mapping[str, str]
    asked: set[str]


def _finder(index: PackageIndex) -> Callable[[str], str | None]:
    return lambda pkg: str(index[pkg]) if pkg in index else None


def _package_robots(
    folder: Path,
    package: str,
    name: str,
    root: Path,
    find: Callable[[str], str | None],
    how: tuple[Target, Mapping[str, str]],
) -> list[tuple[str, BringupRobot]]:
    from marm_setup.package.launch_xml import launch_file_names, python_launch_names

    out = []
    for rel in (*python_launch_names(folder), *launch_file_names(folder)):
        if not readable(folder / rel) or not _mentions(folder / rel, name):
            continue
        asked: set[str] = set()

        def recording(pkg: str, asked: set[str] = asked) -> str | None:
            asked.add(pkg)
            return find(pkg)

        read = _python_robot if rel.endswith(".py") else _xml_robot
        robot = read(folder, rel, _Query(name, root, recording, how[0], how[1], asked))
        if robot is not None:
            (urdf, args, unread), semantic, hand = robot
            label, path = f"{package}/{rel}", folder / rel
            out.append((rel, BringupRobot(urdf, args, unread, semantic, label, 1, path, hand)))
    return out


def _mentions(path: Path, name: str) -> bool:
    """Whether the launch file's text holds the package name at all (every form above writes
    it literally): the cheap test before any file is parsed."""
    from marm_setup.bounded_read import XML_BYTES, FileTooLarge, read_bytes

    try:
        return name.encode() in read_bytes(path, XML_BYTES)
    except (OSError, FileTooLarge):
        return False


def _python_robot(folder: Path, rel: str, query: _Query) -> Robot | None:
    from marm_setup.package.launch_python import Unreadable, parse_launch_module, read_python_launch

    try:
        tree = parse_launch_module(folder / rel, rel)
    except Unreadable:
        return None
    words = _call_strings(tree)
    if not any(w in MOVEIT_NODE_WORDS for w in _strings(tree)):
        return None
    launch = read_python_launch(folder, (rel,), query.find, query.args)
    name, root = query.name, query.root
    builders = [b for b in launch.builders if b.package_name == name]
    if name not in query.asked and name not in words and not builders:
        return None
    robot = _python_file(launch, builders, root, "robot_description")
    if robot is None:
        return None
    hand = None if builders else _hand_loaded(launch, root)
    return robot, _python_file(launch, builders, root, "robot_description_semantic"), hand


def _hand_loaded(launch: PythonLaunch, root: Path) -> tuple[str, ...]:
    """The YAML files of the config package at `root` (relative to it) that the launch file
    names by hand (`load_yaml("X", "config/kinematics.yaml")`, a path joined to its share
    folder): a relative path is taken as the package's when the package holds it."""
    out = set()
    for path, _ in launch.named_yaml:
        file = Path(path)
        rel = file.relative_to(root).as_posix() if file.is_absolute() and inside(file, (root,)) else path
        if not Path(rel).is_absolute() and readable(root / rel) and (root / rel).is_file():
            out.add(Path(rel).as_posix())
    return tuple(sorted(out))


def _python_file(
    launch: PythonLaunch, builders: list[BuilderCall], root: Path, parameter: str
) -> Found | None:
    """What a Python launch file sets `parameter` to: its xacro command's file, else the
    file its builder of the config package names (relative paths are the package's)."""
    command = launch.command(parameter)
    if command is not None and command.file and Path(command.file).is_file():
        return Path(command.file), command.args, command.unread_args
    for builder in builders:
        file = builder.file(parameter)
        path = root / file if file is not None else None
        if path is not None and path.is_file():
            return path, builder.mapping(parameter) or (), builder.unread_args(parameter)
    return None


def _strings(tree: ast.AST) -> set[str]:
    return {n.value for n in ast.walk(tree) if isinstance(n, ast.Constant) and isinstance(n.value, str)}


def _call_strings(tree: ast.AST) -> set[str]:
    """The string literals passed to a call (`load_yaml("X", "config/k.yaml")`)."""
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Call):
            for arg in (*node.args, *(k.value for k in node.keywords)):
                if isinstance(arg, ast.Constant) and isinstance(arg.value, str):
                    out.add(arg.value)
    return out


def _xml_robot(folder: Path, rel: str, query: _Query) -> Robot | None:
    from marm_setup.bounded_read import XML_BYTES, FileTooLarge, read_text
    from marm_setup.package.launch_ros1 import evaluate_ros1
    from marm_setup.package.launch_ros2 import evaluate_ros2_xml
    from marm_setup.package.launch_xml import parse_launch

    try:
        text = read_text(folder / rel, XML_BYTES, shown=rel)
    except (OSError, UnicodeDecodeError, FileTooLarge):
        return None
    if not any(w in text for w in MOVEIT_NODE_WORDS):
        return None
    trees = {rel: parse_launch(folder / rel, rel)}
    evaluate = evaluate_ros1 if query.target == Target.ROS1 else evaluate_ros2_xml
    launch = evaluate(folder, trees, query.find, query.args)
    name = query.name
    named = name in query.asked or re.search(rf"\$\((find|find-pkg-share)\s+{re.escape(name)}\)", text)
    robot = _xml_file(folder, launch.description)
    return (robot, _xml_file(folder, launch.semantic), None) if robot is not None and named else None


def _xml_file(folder: Path, load: DescriptionLoad | None) -> Found | None:
    if load is None or load.file is None or load.missing_package is not None:
        return None
    path = (folder / load.file).resolve()
    return (path, load.xacro_args, load.unread_args) if path.is_file() else None
