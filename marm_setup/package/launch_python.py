"""MoveIt 2 Python launch files, read statically (parsed with `ast`, never executed).

What is read: each `MoveItConfigsBuilder(robot_name, robot_description=..., package_name=...)`
chain and the files its methods name (`.robot_description(file_path, mappings)`,
`.robot_description_semantic(file_path, mappings)`, `.robot_description_kinematics(file_path)`,
`.joint_limits(file_path)`, `.trajectory_execution(file_path)`, `.planning_pipelines(pipelines,
default_planning_pipeline)`, `.sensors_3d(file_path)`, `.pilz_cartesian_limits(file_path)`),
and the parameter files handed to a `ros2_control_node` (`Node(package="controller_manager",
executable="ros2_control_node", parameters=[...])`). An argument counts only when its value is
known without running anything: literals, names bound to literals, `+`, f-strings, `Path(...) /
...`, `os.path.join`, `get_package_share_directory("pkg")` and a `LaunchConfiguration` whose
`DeclareLaunchArgument` has a literal default. The builder's conventions for what it loads
when a method is not called are in `package.builder`.
"""

from __future__ import annotations

import ast
import os
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

BUILDER = "MoveItConfigsBuilder"
FILE_METHODS = (
    "robot_description",
    "robot_description_semantic",
    "robot_description_kinematics",
    "joint_limits",
    "trajectory_execution",
    "sensors_3d",
    "pilz_cartesian_limits",
    "moveit_cpp",
)


class Unknown(Exception):
    """A value only running the launch file would give."""


@dataclass(frozen=True, slots=True)
class BuilderCall:
    """One MoveItConfigsBuilder chain of a launch file: its constructor and its method calls."""

    launch: str
    robot_name: str | None
    package_name: str | None
    robot_description: str = "robot_description"
    files: tuple[tuple[str, str], ...] = ()  # (method, file_path as written)
    mappings: tuple[tuple[str, tuple[tuple[str, str], ...]], ...] = ()  # (method, known xacro args)
    pipelines: tuple[str, ...] | None = None
    default_pipeline: str | None = None

    def file(self, method: str) -> str | None:
        return dict(self.files).get(method)

    def mapping(self, method: str) -> tuple[tuple[str, str], ...] | None:
        return dict(self.mappings).get(method)


@dataclass(frozen=True)
class PythonLaunch:
    builders: tuple[BuilderCall, ...] = ()
    control_files: tuple[tuple[str, str], ...] = ()  # (parameter file path, launch file)


@dataclass
class _Env:
    """Names bound to static values in a module, and the launch arguments' literal defaults."""

    values: dict[str, Any] = field(default_factory=dict)
    defaults: dict[str, str] = field(default_factory=dict)
    find: Callable[[str], str | None] = lambda _name: None


def read_python_launch(root: Path, files: tuple[str, ...], find: Callable[[str], str | None]) -> PythonLaunch:
    from marm_setup.bounded_read import XML_BYTES, FileTooLarge, read_text  # a launch file's bound

    builders: list[BuilderCall] = []
    control: list[tuple[str, str]] = []
    for rel in files:
        try:
            tree = ast.parse(read_text(root / rel, XML_BYTES, shown=rel), rel)
        except (OSError, UnicodeDecodeError, SyntaxError, ValueError, FileTooLarge):
            continue
        env = _environment(tree, find)
        builders += [_builder(call, rel, env) for call in _builder_chains(tree)]
        control += [(path, rel) for path in _control_files(tree, env)]
    return PythonLaunch(tuple(builders), tuple(control))


def _environment(tree: ast.AST, find: Callable[[str], str | None]) -> _Env:
    env = _Env(find=find)
    for node in ast.walk(tree):
        if isinstance(node, ast.Call) and _name(node.func) == "DeclareLaunchArgument" and node.args:
            try:
                name = static(node.args[0], env)
                default = _keyword(node, "default_value")
                if default is not None and isinstance(name, str):
                    env.defaults[name] = str(static(default, env))
            except Unknown:
                continue
    for node in ast.walk(tree):  # simple `name = value` bindings, in source order
        if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name):
            try:
                env.values[node.targets[0].id] = static(node.value, env)
            except Unknown:
                env.values.pop(node.targets[0].id, None)
    return env


def static(node: ast.AST | None, env: _Env) -> Any:
    """The value of an expression known without running it; Unknown otherwise."""
    if isinstance(node, ast.Constant) and isinstance(node.value, str | int | float | bool):
        return node.value
    if isinstance(node, ast.Name) and node.id in env.values:
        return env.values[node.id]
    if isinstance(node, ast.List | ast.Tuple):
        return [static(e, env) for e in node.elts]
    if isinstance(node, ast.Dict):
        return {_key(k, env): _lenient(v, env) for k, v in zip(node.keys, node.values, strict=True)}
    if isinstance(node, ast.JoinedStr):
        return "".join(
            str(static(v.value if isinstance(v, ast.FormattedValue) else v, env)) for v in node.values
        )
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add | ast.Div):
        left, right = static(node.left, env), static(node.right, env)
        if isinstance(node.op, ast.Div):
            return os.path.join(str(left), str(right))
        return left + right
    if isinstance(node, ast.Call):
        return _static_call(node, env)
    raise Unknown


def _static_call(node: ast.Call, env: _Env) -> Any:
    name = _name(node.func)
    args = [static(a, env) for a in node.args]
    if name in ("Path", "PurePath", "join", "PathJoinSubstitution") and all(isinstance(a, str) for a in args):
        return os.path.join(*args) if args else ""
    if name == "PathJoinSubstitution" and len(args) == 1 and isinstance(args[0], list):
        return os.path.join(*map(str, args[0]))
    if name == "str" and len(args) == 1:
        return str(args[0])
    if name in ("get_package_share_directory", "FindPackageShare") and len(args) == 1:
        found = env.find(str(args[0]))
        if found is None:
            raise Unknown
        return found
    if name == "LaunchConfiguration" and len(args) == 1 and str(args[0]) in env.defaults:
        return env.defaults[str(args[0])]
    raise Unknown


def _lenient(node: ast.AST | None, env: _Env) -> Any:
    """A dict value: Unknown ones are kept out later (a mapping with some known args)."""
    try:
        return static(node, env)
    except Unknown:
        return Unknown


def _key(node: ast.AST | None, env: _Env) -> Any:
    return static(node, env) if node is not None else None


def _name(node: ast.AST) -> str:
    if isinstance(node, ast.Name):
        return node.id
    if isinstance(node, ast.Attribute):
        return node.attr
    return ""


def _keyword(call: ast.Call, name: str) -> ast.AST | None:
    return next((k.value for k in call.keywords if k.arg == name), None)


def _builder_chains(tree: ast.AST) -> Iterator[list[ast.Call]]:
    """Each outermost call chain that starts at MoveItConfigsBuilder(...), innermost first."""
    inner: set[int] = set()
    chains = []
    for node in ast.walk(tree):
        if not isinstance(node, ast.Call) or id(node) in inner:
            continue
        chain = _chain(node)
        if chain:
            inner.update(id(c) for c in chain)
            chains.append(chain)
    yield from chains


def _chain(call: ast.Call) -> list[ast.Call] | None:
    out = [call]
    node: ast.AST = call
    while isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute):
        node = node.func.value
        if isinstance(node, ast.Call):
            out.append(node)
    first = out[-1]
    return list(reversed(out)) if _name(first.func) == BUILDER else None


def _builder(chain: list[ast.Call], rel: str, env: _Env) -> BuilderCall:
    ctor = chain[0]
    robot = _try(ctor.args[0] if ctor.args else _keyword(ctor, "robot_name"), env)
    description = _try(ctor.args[1] if len(ctor.args) > 1 else _keyword(ctor, "robot_description"), env)
    package = _try(ctor.args[2] if len(ctor.args) > 2 else _keyword(ctor, "package_name"), env)
    files, mappings, pipelines, default = [], [], None, None
    for call in chain[1:]:
        method = _name(call.func)
        if method in FILE_METHODS:
            path = _try(call.args[0] if call.args else _keyword(call, "file_path"), env)
            if isinstance(path, str):
                files.append((method, path))
            known = _mappings(call, env)
            if known is not None:
                mappings.append((method, known))
        elif method == "planning_pipelines":
            found = _try(_keyword(call, "pipelines") or (call.args[1] if len(call.args) > 1 else None), env)
            pipelines = tuple(map(str, found)) if isinstance(found, list) else None
            chosen = _try(
                _keyword(call, "default_planning_pipeline") or (call.args[0] if call.args else None), env
            )
            default = chosen if isinstance(chosen, str) else None
    return BuilderCall(
        rel,
        robot if isinstance(robot, str) else None,
        package if isinstance(package, str) else None,
        description if isinstance(description, str) else "robot_description",
        tuple(files),
        tuple(mappings),
        pipelines,
        default,
    )


def _mappings(call: ast.Call, env: _Env) -> tuple[tuple[str, str], ...] | None:
    found = _try(_keyword(call, "mappings") or (call.args[1] if len(call.args) > 1 else None), env)
    if not isinstance(found, dict):
        return None
    return tuple(sorted((str(k), _text(v)) for k, v in found.items() if v is not Unknown and k is not None))


def _text(value: Any) -> str:
    if isinstance(value, bool):
        return str(value).lower()
    return str(value)


def _try(node: ast.AST | None, env: _Env) -> Any:
    if node is None:
        return None
    try:
        return static(node, env)
    except Unknown:
        return None


def _control_files(tree: ast.AST, env: _Env) -> Iterator[str]:
    """Parameter files of `Node(package="controller_manager", executable="ros2_control_node")`."""
    for node in ast.walk(tree):
        if not (isinstance(node, ast.Call) and _name(node.func) == "Node"):
            continue
        if _try(_keyword(node, "executable"), env) != "ros2_control_node":
            continue
        params = _keyword(node, "parameters")
        for item in params.elts if isinstance(params, ast.List | ast.Tuple) else ():
            value = _try(item, env)
            if isinstance(value, str) and value.endswith((".yaml", ".yml")):
                yield value
