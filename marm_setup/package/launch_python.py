"""MoveIt 2 Python launch files, read statically (parsed with `ast`, never executed).

What is read: each `MoveItConfigsBuilder(robot_name, robot_description=..., package_name=...)`
chain (with the module the name is imported from: only moveit_configs_utils' is MoveIt's, `builder_origins`) and the files its methods name (`.robot_description(file_path, mappings)`,
`.robot_description_semantic(file_path, mappings)`, `.robot_description_kinematics(file_path)`,
`.joint_limits(file_path)`, `.trajectory_execution(file_path)`, `.planning_pipelines(pipelines,
default_planning_pipeline)`, `.sensors_3d(file_path)`, `.pilz_cartesian_limits(file_path)`),
the parameter files handed to a `ros2_control_node` (`Node(package="controller_manager",
executable="ros2_control_node", parameters=[...])`), and the descriptions a launch file builds
itself: `{"robot_description": Command([FindExecutable(name="xacro"), " ", <file>, " arg:=",
value, ...])}` (also through a name, `ParameterValue(...)`, and for `robot_description_semantic`). An argument counts only when its value is
known without running anything: literals, names bound to literals, `+`, f-strings, `Path(...) /
...`, `os.path.join`, `get_package_share_directory("pkg")`, `FindPackageShare("pkg")`,
`PathJoinSubstitution([...])` and a `LaunchConfiguration` whose `DeclareLaunchArgument` has a
literal default; a xacro argument whose value is not known is listed as such (`unread_args`),
and a command file under a package no package path holds names that package (`unheld`). The builder's conventions for what it loads
when a method is not called are in `package.builder`.
"""

from __future__ import annotations

import ast
import os
import re
import shlex
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

BUILDER = "MoveItConfigsBuilder"
MOVEIT_BUILDER_PACKAGE = "moveit_configs_utils"  # moveit/moveit2 moveit_configs_utils/
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


PYTHON_LAUNCH_BYTES = 2 << 20  # a Python launch file (the largest real MoveIt one is ~30 kB)
MAX_AST_NODES = 200_000  # syntax tree nodes of one launch file
MAX_AST_DEPTH = 150  # nesting of its syntax tree (static() recurses along it)
STATIC_ITEMS = 1 << 20  # characters of a string, items of a list, computed without running


class Unknown(Exception):
    """A value only running the launch file would give."""


class UnheldPackage(Unknown):
    """A value under `get_package_share_directory("pkg")` / `FindPackageShare("pkg")` of a
    package no package path holds (`package`): known once that package is found."""

    def __init__(self, package: str) -> None:
        super().__init__(package)
        self.package = package


class Unreadable(Exception):
    """A launch file validate does not read statically (the message says why)."""


@dataclass(frozen=True, slots=True)
class BuilderCall:
    """One MoveItConfigsBuilder chain of a launch file: its constructor and its method calls."""

    launch: str
    robot_name: str | None
    package_name: str | None
    robot_description: str = "robot_description"
    files: tuple[tuple[str, str], ...] = ()  # (method, file_path as written)
    mappings: tuple[tuple[str, tuple[tuple[str, str], ...]], ...] = ()  # (method, known xacro args)
    unread: tuple[tuple[str, tuple[str, ...]], ...] = ()  # (method, xacro args of unknown value)
    pipelines: tuple[str, ...] | None = None
    default_pipeline: str | None = None
    computed: tuple[str, ...] = ()  # methods given a file_path only the run time computes
    origin: str = MOVEIT_BUILDER_PACKAGE  # the module the builder comes from (builder_origins)
    methods: tuple[str, ...] = ()  # every method the chain calls
    starts_move_group: bool = False  # its launch file starts move_group (_starts_move_group)

    @property
    def is_moveit(self) -> bool:
        """MoveIt's own builder (moveit_configs_utils'), whose conventions `package.builder` holds."""
        return is_moveit_builder(self.origin)

    def file(self, method: str) -> str | None:
        return dict(self.files).get(method)

    def mapping(self, method: str) -> tuple[tuple[str, str], ...] | None:
        return dict(self.mappings).get(method)

    def unread_args(self, method: str) -> tuple[str, ...]:
        return dict(self.unread).get(method, ())


@dataclass(frozen=True, slots=True)
class XacroCommand:
    """`{parameter: Command(["xacro", " ", file, " name:=", value, ...])}` in a launch file: the
    file (None when not known statically) and the args, those whose value is not known apart."""

    launch: str
    parameter: str  # robot_description | robot_description_semantic
    file: str | None
    args: tuple[tuple[str, str], ...] = ()
    unread_args: tuple[str, ...] = ()
    unheld: str | None = None  # the package no package path holds that its file lies in


@dataclass(frozen=True)
class PythonLaunch:
    builders: tuple[BuilderCall, ...] = ()
    control_files: tuple[tuple[str, str], ...] = ()  # (parameter file path, launch file)
    commands: tuple[XacroCommand, ...] = ()

    def command(self, parameter: str) -> XacroCommand | None:
        """The first launch file's xacro command for `parameter` (launch files sorted)."""
        return next((c for c in self.commands if c.parameter == parameter), None)

    named_yaml: tuple[tuple[str, str], ...] = ()  # (a YAML path written as a literal, launch file)
    unread: tuple[tuple[str, str], ...] = ()  # (launch file, why it was not read: Unreadable)
    # builders of another module than moveit_configs_utils (a vendor's: uf_ros_lib's), whose
    # conventions validate does not know
    other_builders: tuple[BuilderCall, ...] = ()
    # (parameter file path, the launch arguments' defaults) of ParameterFile(..., allow_substs=True)
    substituted: tuple[tuple[str, tuple[tuple[str, str], ...]], ...] = ()
    # (YAML path, its (key, value) replacements) of ReplaceString(source_file, replacements)
    replaced: tuple[tuple[str, tuple[tuple[str, str], ...]], ...] = ()


@dataclass
class _Env:
    """Names bound to static values in a module, and the launch arguments' literal defaults."""

    values: dict[str, Any] = field(default_factory=dict)
    defaults: dict[str, str] = field(default_factory=dict)
    unheld: dict[str, str] = field(default_factory=dict)  # name -> the unheld package its value needs
    find: Callable[[str], str | None] = lambda _name: None


def read_python_launch(
    root: Path,
    files: tuple[str, ...],
    find: Callable[[str], str | None],
    args: Mapping[str, str] | None = None,
) -> PythonLaunch:
    """What the Python launch files `files` load, with the launch arguments `args` given as
    `ros2 launch` takes them (over their declared defaults)."""
    builders: list[BuilderCall] = []
    control: list[tuple[str, str]] = []
    commands: list[XacroCommand] = []
    named: list[tuple[str, str]] = []
    unread: list[tuple[str, str]] = []
    substituted: list[tuple[str, tuple[tuple[str, str], ...]]] = []
    replaced: list[tuple[str, tuple[tuple[str, str], ...]]] = []
    for rel in files:
        try:
            tree = parse_launch_module(root / rel, rel)
            env = _environment(tree, find, args)
            mover = _starts_move_group(tree, env)
            found = (
                []
                if _setup_assistant_only(tree)
                else [
                    replace(_builder(chain, rel, env, origin), starts_move_group=mover)
                    for chain, origin in _builder_chains(tree)
                ],
                [(path, rel) for path in _control_files(tree, env)],
                xacro_commands(tree, rel, env),
                [(path, rel) for path in _named_yaml(tree, env)],
                [(path, tuple(sorted(env.defaults.items()))) for path in _substituted_files(tree, env)],
                list(_replaced_files(tree, env)),
            )
        except Unreadable as exc:
            if str(exc):
                unread.append((rel, str(exc)))
            continue
        except RecursionError:  # a bound missed: still a finding, never an internal error
            unread.append((rel, "its expressions nest too deeply to read statically"))
            continue
        builders += found[0]
        control += found[1]
        commands += found[2]
        named += found[3]
        substituted += found[4]
        replaced += found[5]
    return PythonLaunch(
        builders=tuple(b for b in builders if b.is_moveit),
        control_files=tuple(control),
        commands=tuple(commands),
        named_yaml=tuple(named),
        unread=tuple(unread),
        other_builders=tuple(b for b in builders if not b.is_moveit),
        substituted=tuple(substituted),
        replaced=tuple(replaced),
    )


def _setup_assistant_only(tree: ast.AST) -> bool:
    """The module hands its MoveIt config to generate_setup_assistant_launch alone: the Setup
    Assistant node, given the package name and none of the config's parameters (moveit2
    moveit_configs_utils launches.py generate_setup_assistant_launch), so its builder loads
    nothing into a move_group. Any node it starts, or other generate_*_launch, and it counts."""
    called = {_name(n.func) for n in ast.walk(tree) if isinstance(n, ast.Call)}
    launches = {name for name in called if name.startswith("generate_") and name.endswith("_launch")}
    return launches == {"generate_setup_assistant_launch"} and not called & {
        "Node",
        "IncludeLaunchDescription",
    }


def _starts_move_group(tree: ast.AST, env: _Env) -> bool:
    """The module starts move_group: it calls generate_move_group_launch (a move_group Node
    given `moveit_config.to_dict()`; moveit2 moveit_configs_utils launches.py l.190-255) or
    starts one itself (`Node(executable="move_group")`, `add_debuggable_node(...)`).
    generate_demo_launch starts none of its own: it includes the package's
    launch/move_group.launch.py (launches.py l.258-318)."""
    return any(
        isinstance(node, ast.Call)
        and (
            _name(node.func) == "generate_move_group_launch"
            or _try(_keyword(node, "executable"), env) == "move_group"
        )
        for node in ast.walk(tree)
    )


def parse_launch_module(path: Path, rel: str) -> ast.Module:
    """The syntax tree of the launch file at `path`, within the bounds above; Unreadable says
    why not (empty for a file that is not there or not Python: the launcher reports those)."""
    from marm_setup.bounded_read import FileTooLarge, read_text

    try:
        tree = ast.parse(read_text(path, PYTHON_LAUNCH_BYTES, shown=rel), rel)
    except FileTooLarge as exc:
        raise Unreadable(f"{exc.message}: not read") from None
    except (OSError, UnicodeDecodeError, SyntaxError, ValueError):
        raise Unreadable("") from None
    except (RecursionError, MemoryError):  # CPython's parser: 'during ast construction'
        raise Unreadable("its expressions nest too deeply for the Python parser: not read") from None
    _check_tree_size(tree)
    return tree


def _check_tree_size(tree: ast.AST) -> None:
    """Unreadable past MAX_AST_NODES nodes or MAX_AST_DEPTH levels (walked without recursion)."""
    stack, count = [(tree, 0)], 0
    while stack:
        node, depth = stack.pop()
        count += 1
        if count > MAX_AST_NODES:
            raise Unreadable(f"more than {MAX_AST_NODES:,} syntax tree nodes: not read")
        if depth > MAX_AST_DEPTH:
            raise Unreadable(f"expressions nested more than {MAX_AST_DEPTH} deep: not read")
        stack += [(child, depth + 1) for child in ast.iter_child_nodes(node)]


def _environment(
    tree: ast.AST, find: Callable[[str], str | None], args: Mapping[str, str] | None = None
) -> _Env:
    """The names a launch module binds and its launch arguments' values: their declared
    defaults, `args` (given on the command line) over them."""
    env = _Env(find=find)
    _bind(tree, env)  # names first: `DeclareLaunchArgument(ip_name, ...)` names its argument by one
    for node in ast.walk(tree):
        if isinstance(node, ast.Call) and _name(node.func) == "DeclareLaunchArgument" and node.args:
            try:
                name = static(node.args[0], env)
                default = _keyword(node, "default_value")
                if default is not None and isinstance(name, str):
                    env.defaults[name] = _scalar(static(default, env))
            except Unknown:
                continue
    env.defaults.update(args or {})
    _bind(tree, env)  # again, now with the launch arguments' values
    return env


def _assignments(tree: ast.AST) -> Iterator[tuple[str, ast.AST]]:
    """(name, value) of each simple `name = value` of a module, in ast.walk's order (the later of
    two bindings of a name wins where they are put in one dict)."""
    for node in ast.walk(tree):
        if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name):
            yield node.targets[0].id, node.value


def _bind(tree: ast.AST, env: _Env) -> None:
    for name, value in _assignments(tree):
        try:
            env.values[name] = static(value, env)
            env.unheld.pop(name, None)
        except UnheldPackage as exc:
            env.values.pop(name, None)
            env.unheld[name] = exc.package
        except Unknown:
            env.values.pop(name, None)
            env.unheld.pop(name, None)


def static(node: ast.AST | None, env: _Env) -> Any:
    """The value of an expression known without running it; Unknown otherwise."""
    if isinstance(node, ast.Constant) and isinstance(node.value, str | int | float | bool):
        return node.value
    if isinstance(node, ast.Name) and node.id in env.values:
        return env.values[node.id]
    if isinstance(node, ast.Name) and node.id in env.unheld:
        raise UnheldPackage(env.unheld[node.id])
    if isinstance(node, ast.List | ast.Tuple):
        return [static(e, env) for e in node.elts]
    if isinstance(node, ast.Dict):
        return {_key(k, env): _lenient(v, env) for k, v in zip(node.keys, node.values, strict=True)}
    if isinstance(node, ast.JoinedStr):
        parts = [
            _scalar(static(v.value if isinstance(v, ast.FormattedValue) else v, env)) for v in node.values
        ]
        return _joined("", parts)
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add | ast.Div):
        left, right = static(node.left, env), static(node.right, env)
        if isinstance(node.op, ast.Div):
            return _joined(os.sep, [_scalar(left), _scalar(right)])
        if isinstance(left, str | list) and isinstance(right, str | list):
            _check_items(len(left) + len(right))
        return left + right
    if isinstance(node, ast.Call):
        return _static_call(node, env)
    raise Unknown


def _static_call(node: ast.Call, env: _Env) -> Any:
    name = _name(node.func)
    args = [static(a, env) for a in node.args]
    if name in ("Path", "PurePath", "join", "PathJoinSubstitution") and all(isinstance(a, str) for a in args):
        _check_items(sum(map(len, args)) + len(args))
        return os.path.join(*args) if args else ""
    if name == "PathJoinSubstitution" and len(args) == 1 and isinstance(args[0], list):
        parts = [_scalar(a) for a in args[0]]
        _check_items(sum(map(len, parts)) + len(parts))
        return os.path.join(*parts)
    if name == "str" and len(args) == 1:
        return _scalar(args[0])
    if name in ("get_package_share_directory", "FindPackageShare") and len(args) == 1:
        found = env.find(str(args[0]))
        if found is None:
            raise UnheldPackage(str(args[0]))
        return found
    if name == "LaunchConfiguration" and len(args) == 1 and str(args[0]) in env.defaults:
        return env.defaults[str(args[0])]
    raise Unknown


def _scalar(value: Any) -> str:
    """`str(value)` of a string, number or bool (a list or dict: Unknown, as a list doubling
    itself by reference would print 2**n items)."""
    if isinstance(value, str | int | float | bool):
        return str(value)
    raise Unknown


def _joined(separator: str, parts: list[str]) -> str:
    _check_items(sum(map(len, parts)) + len(separator) * len(parts))
    return separator.join(parts)


def _check_items(size: int) -> None:
    """Unreadable past STATIC_ITEMS: `a = a + a` forty times is a terabyte when run."""
    if size > STATIC_ITEMS:
        raise Unreadable(
            f"a value it builds grows past {STATIC_ITEMS:,} characters or items (built from itself over "
            "and over?): not read"
        )


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


def _builder_chains(tree: ast.AST) -> Iterator[tuple[list[ast.Call], str]]:
    """Each outermost call chain that starts at a MoveItConfigsBuilder(...), innermost first,
    with the module that builder comes from (`builder_origins`)."""
    origins = builder_origins(tree)
    inner: set[int] = set()
    chains = []
    for node in ast.walk(tree):
        if not isinstance(node, ast.Call) or id(node) in inner:
            continue
        chain = _chain(node, origins)
        if chain:
            inner.update(id(c) for c in chain[0])
            chains.append(chain)
    yield from chains


def _chain(call: ast.Call, origins: dict[str, str]) -> tuple[list[ast.Call], str] | None:
    out = [call]
    node: ast.AST = call
    while isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute):
        node = node.func.value
        if isinstance(node, ast.Call):
            out.append(node)
    first = out[-1].func
    if isinstance(first, ast.Name) and first.id in origins:  # MoveItConfigsBuilder(...), B(...)
        return list(reversed(out)), origins[first.id]
    if isinstance(first, ast.Attribute) and first.attr == BUILDER:  # module.MoveItConfigsBuilder(...)
        base: ast.AST = first.value
        while isinstance(base, ast.Attribute):
            base = base.value
        module = origins.get(f"import {base.id}", "") if isinstance(base, ast.Name) else ""
        return list(reversed(out)), module
    if isinstance(first, ast.Name) and first.id == BUILDER:  # a name nothing imports
        return list(reversed(out)), ""
    return None


def builder_origins(tree: ast.AST) -> dict[str, str]:
    """Where the names a MoveItConfigsBuilder call may start with come from: `from M import
    MoveItConfigsBuilder [as B]` maps B (else MoveItConfigsBuilder) to M; `import M [as A]` maps
    'import A' (else 'import ' + M's first part) to M; a class of that name defined in the file
    maps it to '<this launch file>'; a star import of MoveIt's module maps MoveItConfigsBuilder."""
    out: dict[str, str] = {}
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.module:
            for alias in node.names:
                if alias.name == BUILDER:
                    out[alias.asname or BUILDER] = node.module
                elif alias.name == "*" and is_moveit_builder(node.module):
                    out.setdefault(BUILDER, node.module)
        elif isinstance(node, ast.Import):
            for alias in node.names:
                out[f"import {alias.asname or alias.name.split('.')[0]}"] = alias.name
        elif isinstance(node, ast.ClassDef) and node.name == BUILDER:
            out[BUILDER] = "<this launch file>"
    return out


def is_moveit_builder(origin: str) -> bool:
    """Whether a builder of that origin is MoveIt's own (moveit_configs_utils')."""
    return origin.split(".")[0] == MOVEIT_BUILDER_PACKAGE


def _builder(chain: list[ast.Call], rel: str, env: _Env, origin: str = MOVEIT_BUILDER_PACKAGE) -> BuilderCall:
    ctor = chain[0]
    robot = _try(ctor.args[0] if ctor.args else _keyword(ctor, "robot_name"), env)
    description = _try(ctor.args[1] if len(ctor.args) > 1 else _keyword(ctor, "robot_description"), env)
    package = _try(ctor.args[2] if len(ctor.args) > 2 else _keyword(ctor, "package_name"), env)
    files, mappings, unread, pipelines, default = [], [], [], None, None
    computed = []
    for call in chain[1:]:
        method = _name(call.func)
        if method in FILE_METHODS:
            given = call.args[0] if call.args else _keyword(call, "file_path")
            path = _try(given, env)
            if isinstance(path, str):
                files.append((method, path))
            elif given is not None and not (isinstance(given, ast.Constant) and given.value is None):
                computed.append(method)
            known = _mappings(call, env)
            if known is not None:
                mappings.append((method, known[0]))
                unread.append((method, known[1]))
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
        tuple(unread),
        pipelines,
        default,
        tuple(computed),
        origin,
        tuple(_name(call.func) for call in chain[1:]),
    )


def _mappings(call: ast.Call, env: _Env) -> tuple[tuple[tuple[str, str], ...], tuple[str, ...]] | None:
    """(the mappings whose value is known, the names of those whose value is not)."""
    found = _try(_keyword(call, "mappings") or (call.args[1] if len(call.args) > 1 else None), env)
    if not isinstance(found, dict):
        return None
    named = {str(k): v for k, v in found.items() if isinstance(k, str | int | float | bool)}
    known = tuple(sorted((k, _text(v)) for k, v in named.items() if isinstance(v, str | int | float | bool)))
    return known, tuple(sorted(k for k, v in named.items() if not isinstance(v, str | int | float | bool)))


def _text(value: Any) -> str:
    if isinstance(value, bool):
        return str(value).lower()
    return _scalar(value)


def _try(node: ast.AST | None, env: _Env) -> Any:
    if node is None:
        return None
    try:
        return static(node, env)
    except Unknown:
        return None


def _control_files(tree: ast.AST, env: _Env) -> Iterator[str]:
    """Parameter files of `Node(package="controller_manager", executable="ros2_control_node")`."""
    for item in _node_parameters(tree, env, "ros2_control_node"):
        value = _try(item, env)
        if isinstance(value, str) and value.endswith((".yaml", ".yml")):
            yield value


def _node_parameters(tree: ast.AST, env: _Env, executable: str) -> Iterator[ast.expr]:
    """The items of the `parameters=[...]` list of each `Node(executable=...)` in `tree`."""
    for node in ast.walk(tree):
        if not (isinstance(node, ast.Call) and _name(node.func) == "Node"):
            continue
        if _try(_keyword(node, "executable"), env) != executable:
            continue
        params = _keyword(node, "parameters")
        yield from params.elts if isinstance(params, ast.List | ast.Tuple) else ()


def _substituted_files(tree: ast.AST, env: _Env) -> Iterator[str]:
    """Paths of `ParameterFile(path, allow_substs=True)`: launch_ros substitutes the file's text
    with the launch configurations before rcl reads it (launch_ros parameter_descriptions.py
    ParameterFile.evaluate, `allow_substs`)."""
    for node in ast.walk(tree):
        if not (isinstance(node, ast.Call) and _name(node.func) == "ParameterFile"):
            continue
        allow = _keyword(node, "allow_substs")
        if not (isinstance(allow, ast.Constant) and allow.value is True):
            continue
        value = _try(node.args[0] if node.args else _keyword(node, "param_file"), env)
        if isinstance(value, str) and value.endswith((".yaml", ".yml")):
            yield value


def _replaced_files(tree: ast.AST, env: _Env) -> Iterator[tuple[str, tuple[tuple[str, str], ...]]]:
    """(path, (key, value) pairs) of `ReplaceString(source_file=path, replacements={key: value})`
    (nav2_common's substitution, ros-navigation/navigation2 nav2_common/launch/replace_string.py):
    it writes a copy of the file with each key replaced by its value, line by line
    (`ReplaceString.replace`), and evaluates to that copy's path. Only a call whose path and every
    value are known statically, and without a `condition` (a false one hands over the file as it
    is, `ReplaceString.perform`)."""
    for node in ast.walk(tree):
        if not (isinstance(node, ast.Call) and _name(node.func) == "ReplaceString"):
            continue
        if _keyword(node, "condition") is not None or len(node.args) > 2:
            continue
        source = _try(node.args[0] if node.args else _keyword(node, "source_file"), env)
        pairs = _try(node.args[1] if len(node.args) > 1 else _keyword(node, "replacements"), env)
        if not (isinstance(source, str) and source.endswith((".yaml", ".yml")) and isinstance(pairs, dict)):
            continue
        known = [(key, _substitutions_text(value)) for key, value in pairs.items()]
        if all(isinstance(key, str) and key and value is not None for key, value in known):
            yield source, tuple((key, str(value)) for key, value in known)


def _substitutions_text(value: Any) -> str | None:
    """What launch performs a value to: a string, or a list of them joined
    (launch.utilities.perform_substitutions); None when not known statically."""
    if isinstance(value, str):
        return value
    if isinstance(value, list) and all(isinstance(v, str) for v in value):
        return "".join(value)
    return None


DESCRIPTION_PARAMETERS = ("robot_description", "robot_description_semantic")
_UNREAD = "\x00"  # stands for a part of a command only the run time gives


def xacro_commands(tree: ast.AST, rel: str, env: _Env) -> list[XacroCommand]:
    """`{"robot_description": <xacro Command>}` dicts of a module (the value directly, through a
    name bound to it, or wrapped in `ParameterValue(..., value_type=str)`), and those whose value
    is the XML of xacro's Python API (`_xacro_api`)."""
    bound = dict(_assignments(tree))
    out = []
    for node in ast.walk(tree):
        if not isinstance(node, ast.Dict):
            continue
        for key, value in zip(node.keys, node.values, strict=True):
            parameter = _try(key, env)
            if parameter in DESCRIPTION_PARAMETERS:
                command = _command_call(value, bound)
                if command is not None and (found := _xacro_command(command, rel, parameter, env)):
                    out.append(found)
                elif (api := _xacro_api(value, bound, tree, env)) is not None:
                    out.append(XacroCommand(rel, parameter, *api))
                elif (text_file := _loaded_text(value, bound, env)) is not None:
                    out.append(XacroCommand(rel, parameter, text_file))
    return out


TEXT_FILES = (".urdf", ".srdf")  # read as they are (a .xacro read so would reach MoveIt unexpanded)


def _loaded_text(value: ast.AST, bound: dict[str, ast.AST], env: _Env) -> str | None:
    """The file of `load_file("pkg", "path")`, the helper MoveIt 2's early tutorials and many
    hand-written launch files define to read a file of a package's share folder as text
    (`open(os.path.join(get_package_share_directory(pkg), path)).read()`): a plain URDF or SRDF
    handed to move_group as it is. None for any other value, or a package no path holds."""
    call = _followed(value, bound)
    if not (isinstance(call, ast.Call) and _name(call.func) == "load_file" and len(call.args) == 2):
        return None
    package, path = (_try(arg, env) for arg in call.args)
    if not (isinstance(package, str) and isinstance(path, str) and path.endswith(TEXT_FILES)):
        return None
    share = env.find(package)
    return os.path.join(share, path) if share is not None else None


def _xacro_api(
    value: ast.AST, bound: dict[str, ast.AST], tree: ast.AST, env: _Env
) -> tuple[str | None, tuple[tuple[str, str], ...], tuple[str, ...]] | None:
    """(file, args, unread args) of `xacro.process_file(path, mappings={...}).toxml()`, or of
    `doc = xacro.parse(open(path))`, `xacro.process_doc(doc, mappings={...})`, `doc.toxml()`
    (xacro's Python API: xacro/__init__.py process_file, parse, process_doc), directly or through
    names; None when `value` is neither."""
    xml = _followed(value, bound)
    if not (isinstance(xml, ast.Call) and _name(xml.func) == "toxml" and isinstance(xml.func, ast.Attribute)):
        return None
    made = _followed(xml.func.value, bound)
    if not isinstance(made, ast.Call) or not made.args:
        return None
    path: ast.AST | None
    if _name(made.func) == "process_file":
        path, mappings = made.args[0], _keyword(made, "mappings")
    elif (
        _name(made.func) == "parse"
        and isinstance(opened := made.args[0], ast.Call)
        and _name(opened.func) == "open"
    ):
        doc = xml.func.value.id if isinstance(xml.func.value, ast.Name) else None
        path, mappings = opened.args[0] if opened.args else None, _process_doc_mappings(tree, doc)
    else:
        return None
    file = _try(path, env)
    given = mappings.keys if isinstance(mappings, ast.Dict) else []
    pairs = [
        (_try(k, env), _try(v, env)) for k, v in zip(given, getattr(mappings, "values", []), strict=True)
    ]
    args = tuple(
        sorted(
            (k, _text(v)) for k, v in pairs if isinstance(k, str) and isinstance(v, str | int | float | bool)
        )
    )
    unread = tuple(
        sorted(k for k, v in pairs if isinstance(k, str) and not isinstance(v, str | int | float | bool))
    )
    return (file if isinstance(file, str) and os.path.isabs(file) else None), args, unread


def _followed(node: ast.AST, bound: dict[str, ast.AST]) -> ast.AST:
    """`node`, or what the name it is is bound to (a few steps)."""
    for _ in range(8):
        if not (isinstance(node, ast.Name) and node.id in bound):
            break
        node = bound[node.id]
    return node


def _process_doc_mappings(tree: ast.AST, doc: str | None) -> ast.AST | None:
    """The `mappings=` of the `xacro.process_doc(doc, mappings=...)` call on the name `doc`."""
    for node in ast.walk(tree):
        if not (isinstance(node, ast.Call) and _name(node.func) == "process_doc" and node.args):
            continue
        if isinstance(node.args[0], ast.Name) and node.args[0].id == doc:
            return _keyword(node, "mappings")
    return None


def _command_call(node: ast.AST, bound: dict[str, ast.AST]) -> ast.Call | None:
    for _ in range(8):  # a name, a ParameterValue, a name again...
        if isinstance(node, ast.Name) and node.id in bound:
            node = bound[node.id]
        elif isinstance(node, ast.Call) and _name(node.func) == "ParameterValue" and node.args:
            node = node.args[0]
        else:
            break
    return node if isinstance(node, ast.Call) and _name(node.func) == "Command" else None


def _xacro_command(call: ast.Call, rel: str, parameter: str, env: _Env) -> XacroCommand | None:
    """launch's Command joins its parts and splits the text like a shell (ros2/launch
    launch/launch/substitutions/command.py `perform` l.92-98: shlex.split); a part only the run
    time gives is `_UNREAD`."""
    given = call.args[0] if call.args else _keyword(call, "command")
    parts = given.elts if isinstance(given, ast.List | ast.Tuple) else [given]
    try:
        words = shlex.split("".join(_command_part(p, env) for p in parts if p is not None))
    except ValueError:
        return None
    if not words or os.path.basename(words[0]) not in ("xacro", "xacro.py"):
        return None
    files = [w for w in words[1:] if ":=" not in w and not w.startswith("-")]
    pairs = [w.split(":=", 1) for w in words[1:] if ":=" in w and _UNREAD not in w.split(":=", 1)[0]]
    # a relative file is relative to where the user starts the launch: not known statically
    file = files[0] if files and _UNREAD not in files[0] and os.path.isabs(files[0]) else None
    args = tuple(sorted((k, v) for k, v in pairs if _UNREAD not in v))
    unheld = next((m[1] for m in _UNHELD.finditer(files[0])), None) if files else None
    unread = tuple(sorted(k for k, v in pairs if _UNREAD in v))
    return XacroCommand(rel, parameter, file, args, unread, unheld)


_UNHELD = re.compile("\x00\x01([^\x01]+)\x01")  # a part under a package no package path holds


def _command_part(node: ast.AST, env: _Env) -> str:
    try:
        return _known_part(node, env)
    except UnheldPackage as exc:  # unknown like _UNREAD, naming the package
        return f"{_UNREAD}\x01{exc.package}\x01"


def _known_part(node: ast.AST, env: _Env) -> str:
    node = _sole_joined(node)
    if isinstance(node, ast.Call) and _name(node.func) == "FindExecutable":
        name = _try(_keyword(node, "name") or (node.args[0] if node.args else None), env)
        return str(name) if isinstance(name, str) else _UNREAD
    try:
        value = static(node, env)
    except UnheldPackage:
        raise
    except Unknown:
        return _UNREAD
    return _text(value) if isinstance(value, str | int | float | bool) else _UNREAD


def _sole_joined(node: ast.AST) -> ast.AST:
    """The one part of `PathJoinSubstitution([part])`, which launch joins into that part's own
    text (ros2/launch path_join_substitution.py `perform`: os.path.join of the parts), else `node`:
    `PathJoinSubstitution([FindExecutable(name="xacro")])` runs xacro."""
    if isinstance(node, ast.Call) and _name(node.func) == "PathJoinSubstitution" and len(node.args) == 1:
        parts = node.args[0]
        if isinstance(parts, ast.List | ast.Tuple) and len(parts.elts) == 1:
            return parts.elts[0]
    return node


def undefined_unread_arg(message: str, unread: tuple[str, ...]) -> str | None:
    """The xacro arg a failed expansion names as undefined (robot/xacro_expand.py) when it is
    one whose value only the launch file's run time gives, else None."""
    import re

    found = re.search(r"undefined xacro arg '([^']+)'", message)
    return found.group(1) if found and found.group(1) in unread else None


def launch_yaml_key(root: Path, launch: str, rel: str) -> str | None:
    """The key of the dict the Python launch file `launch` puts the YAML file `rel` under, as
    `{"moveit_simple_controller_manager": load_yaml("pkg", "config/c.yaml")}` does (also through
    names bound to the load, or to a file opened by hand: `with open(path) as f: x =
    yaml.safe_load(f)`); None when it hands the file over as it is (or cannot be read)."""
    from marm_setup.package.launch_xml import package_relative
    from marm_setup.robot import package_name

    try:
        tree = parse_launch_module(root / launch, launch)
    except Unreadable:
        return None
    own = package_name(root)
    env = _environment(tree, lambda name: str(root) if name == own else None)
    keys = _yaml_keys(tree, env)
    return next((key for path, key in keys.items() if package_relative(path, root) == rel), None)


def hands_bare_to_move_group(root: Path, launch: str, rel: str) -> bool:
    """Whether the Python launch file `launch` lists the YAML file `rel` itself as an item of a
    move_group Node's `parameters` (`parameters=[robot_description, kinematics_yaml]` with
    `kinematics_yaml = load_yaml("pkg", "config/kinematics.yaml")`, or the file's path): its keys
    become move_group's own top-level parameters. A dict item (`{"robot_description_kinematics":
    kinematics_yaml}`) puts them under its key instead; False also for an unreadable launch."""
    from marm_setup.package.launch_xml import package_relative

    try:
        tree = parse_launch_module(root / launch, launch)
    except Unreadable:
        return False
    env = _environment(tree, lambda _name: None)
    bound = dict(_assignments(tree))
    for item in _node_parameters(tree, env, "move_group"):
        held = bound.get(item.id, item) if isinstance(item, ast.Name) else item
        if not isinstance(held, ast.Dict) and any(
            package_relative(path, root) == rel for path in _named_yaml(held)
        ):
            return True
    return False


PIPELINE_PLUGIN_KEYS = ("planning_plugin", "planning_plugins")


def launch_pipeline_settings(root: Path, launch: str) -> tuple[tuple[str, Any], ...]:
    """The literal entries of the dict the Python launch file `launch` sets a planning plugin in
    (`{"move_group": {"planning_plugin": "ompl_interface/OMPLPlanner", "request_adapters": "..."}}`,
    which it then updates with a `*_planning.yaml` it loads by hand): what move_group gets beside
    the file. None read: () (also for an unreadable launch file)."""
    try:
        tree = parse_launch_module(root / launch, launch)
    except Unreadable:
        return ()
    for node in ast.walk(tree):
        if not isinstance(node, ast.Dict):
            continue
        entries = {
            k.value: v
            for k, v in zip(node.keys, node.values, strict=True)
            if isinstance(k, ast.Constant) and isinstance(k.value, str)
        }
        if any(key in entries for key in PIPELINE_PLUGIN_KEYS):
            return tuple((key, value) for key, v in entries.items() if (value := _setting(v)) is not None)
    return ()


def _str_constant(node: ast.AST | None) -> bool:
    return isinstance(node, ast.Constant) and isinstance(node.value, str)


def _setting(node: ast.AST) -> Any:
    """A literal scalar, or a list of strings as a tuple; None for anything else."""
    if isinstance(node, ast.Constant) and isinstance(node.value, (str, int, float, bool)):
        return node.value
    if isinstance(node, ast.List) and all(_str_constant(e) for e in node.elts):
        return tuple(e.value for e in node.elts)  # type: ignore[attr-defined]
    return None


def _yaml_keys(tree: ast.AST, env: _Env | None = None) -> dict[str, str]:
    """YAML path -> the key of the innermost dict entry holding it (ast.walk goes outside in, so
    inner entries overwrite), following names bound by `=` or `with ... as` (a few steps)."""
    bound = _bound_names(tree)
    out: dict[str, str] = {}
    for node in ast.walk(tree):
        if not isinstance(node, ast.Dict):
            continue
        for key, value in zip(node.keys, node.values, strict=True):
            if isinstance(key, ast.Constant) and isinstance(key.value, str):
                for held in _through_names(value, bound):
                    out.update(dict.fromkeys(_named_yaml(held, env), key.value))
    return out


def _bound_names(tree: ast.AST) -> dict[str, list[ast.AST]]:
    """`name = value` and `with value as name` of a module: the name -> every expression bound to
    it (the branches of an `if` each bind theirs: `x = load_yaml(a)` / `else: x = load_yaml(b)`)."""
    bound: dict[str, list[ast.AST]] = {}
    for name, value in _assignments(tree):
        bound.setdefault(name, []).append(value)
    for node in ast.walk(tree):
        if isinstance(node, ast.With):
            for item in node.items:
                if isinstance(item.optional_vars, ast.Name):
                    bound.setdefault(item.optional_vars.id, []).append(item.context_expr)
    return bound


def _through_names(node: ast.AST, bound: dict[str, list[ast.AST]], steps: int = 4) -> list[ast.AST]:
    """`node`, and what the names in it are bound to, and theirs, `steps` deep."""
    out, frontier = [node], [node]
    for _ in range(steps):
        names = {n.id for f in frontier for n in ast.walk(f) if isinstance(n, ast.Name) and n.id in bound}
        frontier = [value for name in sorted(names) for value in bound[name] if value not in out]
        out += frontier
    return out


def _named_yaml(tree: ast.AST, env: _Env | None = None) -> Iterator[str]:
    """YAML paths a launch file writes as string literals: the files it loads by hand
    (`load_yaml("pkg", "config/x_controllers.yaml")`) rather than through MoveItConfigsBuilder,
    also joined from literals (`os.path.join("config", "x.yaml")`) or, given `env`, from what it
    knows statically (`os.path.join(get_package_share_directory("pkg"), "config", "x.yaml")`)."""
    for node in ast.walk(tree):
        value = node.value if isinstance(node, ast.Constant) else _literal_join(node)
        if value is None and env is not None and isinstance(node, ast.Call):
            value = _try(node, env) if _name(node.func) in ("join", "PathJoinSubstitution") else None
        if isinstance(value, str) and value.endswith((".yaml", ".yml")):
            yield value


def _literal_join(node: ast.AST) -> str | None:
    """`os.path.join("config", "x.yaml")` (or PathJoinSubstitution of a list) of string literals
    only: the path; else None."""
    if not (isinstance(node, ast.Call) and _name(node.func) in ("join", "PathJoinSubstitution")):
        return None
    parts = node.args[0].elts if len(node.args) == 1 and isinstance(node.args[0], ast.List) else node.args
    if len(parts) < 2 or not all(_str_constant(p) for p in parts):
        return None
    return os.path.join(*(p.value for p in parts))  # type: ignore[attr-defined]
