"""What ROS 1 launch files load, evaluated as roslaunch does (without running anything).

Every launch file of the package is an entry point (a user may start any of them) and is
walked in document order with its own arg defaults; `<include>` passes `<arg>` children (and
every arg with `pass_all_args`) down, as roslaunch's xmlloader.py `_include_tag` does; `<group
ns>`, `<include ns>` and `<node>` set the namespace. `if` / `unless` decide a branch from the
args; a branch the defaults do not take is still walked, its loads marked `conditional` (a file
a launch may load instead, e.g. with `gazebo_sim:=true`). What it records:

- each YAML file a `<rosparam command="load" file=...>` loads, with the namespace it lands in,
  the args in scope (for `subst_value`), and the `moveit_controller_manager` param set beside
  it (roslaunch xmlloader.py `_rosparam_tag`, loader.py `load_rosparam`);
- the URDF a `robot_description` param loads and the SRDF its `_semantic` loads, from
  `textfile=` or a xacro `command=` read as xacro reads it (`$(find xacro)/xacro --inorder
  a:=b FILE c:=d`: robot/xacro_cli.py), with those xacro args, in this package or another one
  `$(find)` leads to (MoveIt 1 planning_context.launch; move_group reads both params), also
  when a launch file of another package sets it (`<include file="$(find x_description)/launch/
  upload.launch">`: roslaunch includes any file, xmlloader.py `_include_tag`); of such a file
  only these two params are kept, the rest being that package's business;
- `<param name value>` values (their full names), and every `moveit_controller_manager` value;
- the full name of each `move_group` node (`<node type="move_group">` below the enclosing
  `<group ns>` / `<include ns>` / its own `ns`): the private namespace its plugins read `~`
  parameters from (MoveIt 1's simple controller manager reads `~controller_list` there).
"""

from __future__ import annotations

import dataclasses
import os
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING

from marm_setup.package.launch_xml import LaunchXml, condition, package_file, parse_launch, substituted
from marm_setup.package.substitution import Scope, SubstitutionError, substitute, truth

if TYPE_CHECKING:
    from lxml import etree

MAX_DEPTH = 20
MAX_VISITS = 2000  # file walks per entry point: a file that includes itself with new args each time
MANAGER_PARAM = "moveit_controller_manager"
MOVE_GROUP = "move_group"  # the node type of moveit_ros_move_group
DESCRIPTION = "robot_description"


@dataclass(frozen=True, slots=True)
class YamlLoad:
    """A YAML file a launch file loads onto the parameter server."""

    file: str  # relative to the package
    ns: str  # the namespace it lands in ('' for the root), e.g. robot_description_planning
    launch: str  # the launch file holding the <rosparam>
    scope: Scope | None  # the substitutions in scope, when loaded with subst_value
    manager: str = ""  # the moveit_controller_manager param set beside it
    conditional: bool = False  # only on a branch the arg defaults do not take
    line: int = 0  # the <rosparam>'s line in `launch`
    entry: str = ""  # the entry point (launch file a user starts) whose walk reached it first


@dataclass(frozen=True, slots=True)
class DescriptionLoad:
    """The file a launch file sets as `robot_description` (URDF) or `robot_description_semantic`
    (SRDF), with the xacro args its command passes. `file` is relative to the package (`../`
    when a `$(find)` leads into another package), None when the launch names none statically."""

    file: str | None
    xacro_args: tuple[tuple[str, str], ...]
    launch: str
    unread_args: tuple[str, ...] = ()  # xacro args given values only the run time has
    missing_package: str | None = None  # the `$(find pkg)` no package path holds
    conditional: bool = False  # set only on a branch the arg defaults do not take


@dataclass(frozen=True, slots=True)
class LaunchParam:
    """A `<param name value>` a launch file sets (name with its namespace, no leading /)."""

    name: str
    value: str
    launch: str


@dataclass(frozen=True)
class Ros1Launch:
    loads: tuple[YamlLoad, ...] = ()  # first reach of each (file, ns), entry points in order
    semantic: DescriptionLoad | None = None
    params: tuple[LaunchParam, ...] = ()
    description: DescriptionLoad | None = None  # robot_description as a user's entry launch sets it
    stopped: tuple[str, ...] = ()  # entry points whose includes went past MAX_VISITS walks
    move_groups: tuple[str, ...] = ()  # full names of the move_group nodes (their private namespaces)
    managers: tuple[str, ...] = ()  # every moveit_controller_manager value a launch file sets
    # each moveit_controller_manager param set on a branch an entry point's defaults take
    taken_managers: tuple[LaunchParam, ...] = ()


@dataclass
class _Walk:
    """What one entry point's walk collects."""

    root: Path
    trees: Mapping[str, LaunchXml]
    find: Callable[[str], str | None]
    loads: list[YamlLoad] = field(default_factory=list)
    semantic: list[tuple[DescriptionLoad, bool]] = field(default_factory=list)
    description: list[tuple[DescriptionLoad, bool]] = field(default_factory=list)
    params: list[LaunchParam] = field(default_factory=list)
    move_groups: list[str] = field(default_factory=list)
    managers: list[str] = field(default_factory=list)
    taken_managers: list[LaunchParam] = field(default_factory=list)
    included: set[str] = field(default_factory=set)
    foreign: dict[str, LaunchXml] = field(default_factory=dict)  # other packages' files, parsed once
    names: frozenset[str] = frozenset({DESCRIPTION})  # the description params (_description_names)
    walked: set[tuple] = field(default_factory=set)  # (file, args, ns, conditional, manager) walked
    visits: int = 0


@dataclass(frozen=True)
class _Context:
    file: str
    scope: Scope
    ns: str = ""
    conditional: bool = False
    manager: str = ""
    depth: int = 0


def evaluate_ros1(
    root: Path,
    trees: Mapping[str, LaunchXml],
    find: Callable[[str], str | None],
    args: Mapping[str, str] | None = None,
) -> Ros1Launch:
    """Walk every launch file as an entry point and merge what they load: first the files no
    other launch file includes (what a user starts: demo.launch, move_group.launch, in name
    order), whose args reach the included ones as roslaunch passes them, then the included
    files on their own defaults; each entry point given `args` as `roslaunch FILE name:=value`;
    the robot description in `_description_order`."""
    loads: dict[tuple[str, str], YamlLoad] = {}
    semantic: list[tuple[DescriptionLoad, bool]] = []
    description: list[tuple[DescriptionLoad, bool]] = []
    params: dict[str, LaunchParam] = {}
    move_groups: dict[str, None] = {}
    managers: dict[str, None] = {}
    taken_managers: dict[LaunchParam, None] = {}
    names = _description_names(trees)
    walks = {rel: _Walk(root, trees, find, names=names) for rel in sorted(trees)}
    for rel, walk in walks.items():
        _walk_file(walk, rel, dict(args or {}), "", False, "", 0)
    stopped = tuple(rel for rel, walk in walks.items() if walk.visits > MAX_VISITS)
    included = set().union(*(w.included for w in walks.values()))
    for rel in sorted(walks, key=lambda r: (r in included, r)):
        walk = walks[rel]
        for load in walk.loads:
            known = loads.get((load.file, load.ns))
            if known is None or (known.conditional and not load.conditional):
                loads[load.file, load.ns] = replace(load, entry=rel)
        semantic += walk.semantic
        for p in walk.params:
            params.setdefault(p.name, p)
        move_groups.update(dict.fromkeys(walk.move_groups))
        managers.update(dict.fromkeys(walk.managers))
        taken_managers.update(dict.fromkeys(walk.taken_managers))
    for rel in sorted(walks, key=lambda r: _description_order(r, walks, included)):
        description += walks[rel].description
    return Ros1Launch(
        tuple(loads.values()),
        first_taken(semantic),
        tuple(params.values()),
        first_taken(description),
        stopped,
        tuple(move_groups),
        tuple(managers),
        tuple(taken_managers),
    )


def _description_names(trees: Mapping[str, LaunchXml]) -> frozenset[str]:
    """robot_description, and the name a `<remap from="robot_description" to="...">` gives it
    for move_group (a child of a move_group `<node>`, or beside one in its file): MoveIt 1 then
    reads the URDF from that name and the SRDF from that name + `_semantic` (moveit
    rdf_loader.cpp RDFLoader l.67-81: `searchParam` applies the node's remappings, ros_comm
    roscpp param.cpp search l.757-765). human_moveit_config's move_group.launch remaps it to
    human_description, the name its planning_context.launch loads."""
    names = {DESCRIPTION}
    for tree in trees.values():
        if tree.root is None or not any(n.get("type") == MOVE_GROUP for n in tree.root.iter("node")):
            continue
        for remap in tree.root.iter("remap"):
            parent = remap.getparent()
            other_node = parent is not None and parent.tag == "node" and parent.get("type") != MOVE_GROUP
            if remap.get("from") != DESCRIPTION or other_node:
                continue
            to = remap.get("to") or ""
            if to and "$(" not in to:
                names.add(to.rsplit("/", 1)[-1])
    return frozenset(names)


def _description_order(rel: str, walks: Mapping[str, _Walk], included: set[str]) -> tuple[int, str]:
    """Where `rel`'s walk comes in the search for robot_description: first a launch starting
    move_group that another launch starting move_group includes (the demo.launch that the
    Setup Assistant's demo_gazebo.launch wraps after its gazebo.launch sets the gazebo copy of
    the URDF, passing load_robot_description:=false: moveit_setup_assistant templates/
    moveit_config_pkg_template/launch/demo_gazebo.launch l.13-20; the wrapper is a variant of
    the demo a user starts), then the files no launch file includes, then the other included
    files on their own defaults."""
    wrapped = bool(walks[rel].move_groups) and any(
        rel in w.included for other, w in walks.items() if other != rel and w.move_groups
    )
    return (0 if wrapped else 1 if rel not in included else 2, rel)


def first_taken(found: list[tuple[DescriptionLoad, bool]]) -> DescriptionLoad | None:
    """The first load on a branch the arg defaults take, else the first at all (a launch that
    loads the description only with `load_robot_description:=true` still names MoveIt's robot).
    Of the taken ones, the package's own before another package's launch file: a launch that
    includes that file and then sets the param itself keeps its own (roslaunch config.py
    add_param l.301-313 keeps the last value a param is given); the reverse order, rarer, is
    read the same way."""
    taken = [d for d, conditional in found if not conditional]
    own = next((d for d in taken if not _foreign(d.launch)), None)
    return (
        own
        or next(iter(taken), None)
        or next((dataclasses.replace(d, conditional=True) for d, _ in found), None)
    )


def _walk_file(
    walk: _Walk, rel: str, passed: Mapping[str, str], ns: str, conditional: bool, manager: str, depth: int
) -> None:
    tree = _tree(walk, rel)
    if (
        tree is None
        or tree.root is None
        or depth > MAX_DEPTH
        or not _first_walk(walk, rel, passed, ns, conditional, manager)
    ):
        return
    dirname = str((walk.root / rel).parent)
    scope = Scope(dict(passed), walk.find, dirname)
    ctx = _Context(rel, scope, ns, conditional, manager, depth)
    _walk_children(walk, tree.root, ctx, dict(passed), set())


def _tree(walk: _Walk, rel: str) -> LaunchXml | None:
    """The package's launch file `rel`, or another package's (`../` from the package root),
    parsed on first reach; None when there is none."""
    if rel in walk.trees or not _foreign(rel):
        return walk.trees.get(rel)
    if rel not in walk.foreign:
        path = walk.root / rel
        if not path.is_file():
            return None
        walk.foreign[rel] = parse_launch(path, rel)
    return walk.foreign[rel]


def _foreign(rel: str) -> bool:
    """A file outside the package (its path relative to the package root leaves it)."""
    return rel == ".." or rel.startswith("../")


def _first_walk(walk: _Walk, rel: str, passed: Mapping[str, str], *how: object) -> bool:
    """Whether `rel` is walked: not when it was walked with the same args in the same place (a
    walk is a function of them: a file included twice by itself is walked once per args), nor
    past MAX_VISITS walks of the entry point (`walk.visits` then says so)."""
    key = (rel, tuple(sorted(passed.items())), *how)
    if key in walk.walked or walk.visits > MAX_VISITS:
        return False
    walk.walked.add(key)
    walk.visits += 1
    return walk.visits <= MAX_VISITS


def _walk_children(
    walk: _Walk, elem: etree._Element, ctx: _Context, passed: dict[str, str], declared: set[str]
) -> _Context:
    """Walk `elem`'s children in order; returns the context after them (args and manager set)."""
    for child in elem:
        if not isinstance(child.tag, str):
            continue
        taken = _condition(child, ctx)  # None: undecidable (an unknown arg), as a branch not taken
        if taken is not True and child.tag == "arg":
            continue
        inner = ctx if taken else replace(ctx, conditional=True)
        handler = _HANDLERS.get(child.tag)
        if handler is not None:
            after = handler(walk, child, inner, passed, declared)
            if taken and after is not None:
                ctx = after
    return ctx


def _condition(elem: etree._Element, ctx: _Context) -> bool | None:
    return condition(elem, ctx.scope)


def _arg(
    walk: _Walk, elem: etree._Element, ctx: _Context, passed: dict[str, str], declared: set[str]
) -> _Context:
    """`<arg name default|value>`: a passed value beats a default; a `value` is fixed."""
    name = elem.get("name")
    if not name or name in declared:
        return ctx
    value = elem.get("value")
    if value is None:
        value = passed.get(name, elem.get("default"))
    elif name in passed:
        value = passed[name]
    if value is None:
        return ctx
    declared.add(name)
    try:
        resolved = substitute(value, ctx.scope)
    except SubstitutionError:
        return ctx
    return replace(ctx, scope=ctx.scope.with_args({**ctx.scope.args, name: resolved}))


def _group(
    walk: _Walk, elem: etree._Element, ctx: _Context, passed: dict[str, str], declared: set[str]
) -> _Context:
    inner = replace(ctx, ns=_ns(ctx, elem.get("ns")))
    after = _walk_children(walk, elem, inner, passed, declared)
    return replace(ctx, scope=after.scope)  # args stay file-wide, the namespace and manager do not


def _node(
    walk: _Walk, elem: etree._Element, ctx: _Context, passed: dict[str, str], declared: set[str]
) -> None:
    name = _text(elem.get("name"), ctx) or ""
    inner = replace(ctx, ns=_ns(replace(ctx, ns=_ns(ctx, elem.get("ns"))), name))
    if elem.get("type") == MOVE_GROUP and name and not _foreign(ctx.file):
        walk.move_groups.append(inner.ns)  # its private namespace (`~`), on any branch
    _walk_children(walk, elem, inner, passed, set(declared))


def _include(
    walk: _Walk, elem: etree._Element, ctx: _Context, passed: dict[str, str], declared: set[str]
) -> None:
    text = _text(elem.get("file"), ctx) if elem.get("file") else None
    target = _relative_anywhere(text, walk.root) if text else None
    if target is None or not (target in walk.trees or _foreign(target)):
        return
    given = dict(ctx.scope.args) if truth(elem.get("pass_all_args") or "") else {}
    for arg in elem.iterchildren("arg"):
        name = arg.get("name")
        if _condition(arg, ctx) is False or not name or arg.get("value") is None:
            continue
        value = _text(arg.get("value"), ctx)
        if value is not None:
            given[name] = value
    ns = _ns(ctx, elem.get("ns"))
    walk.included.add(target)
    _walk_file(walk, target, given, ns, ctx.conditional, ctx.manager, ctx.depth + 1)


def _rosparam(
    walk: _Walk, elem: etree._Element, ctx: _Context, passed: dict[str, str], declared: set[str]
) -> None:
    if (elem.get("command") or "load") != "load" or _foreign(ctx.file):
        return
    target = _package_file(elem.get("file"), ctx, walk.root)
    if target is None:
        return
    ns = _ns(ctx, elem.get("ns"))
    if elem.get("param"):
        ns = _ns(replace(ctx, ns=ns), elem.get("param"))
    scope = ctx.scope if truth(elem.get("subst_value") or "") else None
    line = elem.sourceline or 0
    walk.loads.append(YamlLoad(target, ns, ctx.file, scope, ctx.manager, ctx.conditional, line))


def _param(
    walk: _Walk, elem: etree._Element, ctx: _Context, passed: dict[str, str], declared: set[str]
) -> _Context:
    name = _text(elem.get("name"), ctx)
    if not name:
        return ctx
    full = _ns(ctx, name)
    leaf = full.rsplit("/", 1)[-1]
    if leaf in walk.names or leaf.removesuffix("_semantic") in walk.names:
        found = _description(elem, ctx, walk.root)
        if found is not None:
            kept = walk.semantic if leaf.endswith("_semantic") else walk.description
            kept.append((found, ctx.conditional))
    value = _text(elem.get("value"), ctx) if elem.get("value") is not None else None
    if value is None or _foreign(ctx.file):
        return ctx
    if not ctx.conditional:
        walk.params.append(LaunchParam(full, value, ctx.file))
    if leaf != MANAGER_PARAM:
        return ctx
    walk.managers.append(value)
    if not ctx.conditional:
        walk.taken_managers.append(LaunchParam(full, value, ctx.file))
    return replace(ctx, manager=value)


_HANDLERS: dict[str, Callable] = {
    "arg": _arg,
    "group": _group,
    "node": _node,
    "include": _include,
    "rosparam": _rosparam,
    "param": _param,
}


def _description(elem: etree._Element, ctx: _Context, root: Path) -> DescriptionLoad | None:
    """The file a `robot_description[_semantic]` param loads: `textfile=`, or a `command=`."""
    textfile = elem.get("textfile")
    text = textfile or elem.get("command")
    return description_load(text, ctx.scope, root, ctx.file, textfile=bool(textfile)) if text else None


def description_load(
    text: str, scope: Scope, root: Path, launch: str, *, textfile: bool = False
) -> DescriptionLoad | None:
    """The file a description command (or `textfile`) names: the input of a xacro command with
    its mappings (robot/xacro_cli.py reads it as xacro does), or the file of `cat FILE`. A
    `$(find pkg)` no package path holds and args without a value are kept as such, not lost;
    None for a command that is neither."""
    from marm_setup.robot import parse_xacro_command, split_command

    lenient = _Lenient(scope)
    expanded = substituted(text, lenient.scope())
    if not expanded:
        return None
    words = split_command(expanded)
    if not textfile and len(words) == 2 and words[0] == "cat":
        textfile, expanded = True, words[1]
    call = None if textfile else parse_xacro_command(words)
    file = expanded.strip() if textfile else call.file if call is not None else None
    args = call.args if call is not None else ()
    missing = next((p for p in lenient.packages if file and f"{MISSING}{p}" in file), None)
    unread = tuple(sorted(k for k, v in args if UNREAD in v))
    rel = None if file is None or missing else _relative_anywhere(file, root)
    known = tuple((k, v) for k, v in args if UNREAD not in v)
    return DescriptionLoad(rel, known, launch, unread, missing)


MISSING = "/\x00missing-package:"  # stands for a `$(find pkg)` no package path holds
UNREAD = "\x00unread-arg"  # stands for an `$(arg)` the launch gives no value


class _Lenient:
    """A scope whose unknown packages and args resolve to markers, recording the packages."""

    def __init__(self, scope: Scope):
        self.base = scope
        self.packages: list[str] = []

    def find(self, name: str) -> str:
        found = self.base.find(name)
        if found is None and name == "xacro":
            return "/xacro"  # `$(find xacro)/xacro`: the tool need not be on the package path
        if found is None:
            self.packages.append(name)
            return f"{MISSING}{name}"
        return found

    def scope(self) -> Scope:
        base = self.base
        return Scope(_ArgsWithUnread(base.args), self.find, base.dirname, base.ros2, base.environ)


class _ArgsWithUnread(dict):
    """Launch args where one without a value reads as the UNREAD marker."""

    def __contains__(self, key: object) -> bool:
        return True

    def __missing__(self, key: str) -> str:
        return UNREAD


def _relative_anywhere(path: str, root: Path) -> str:
    """`path` (absolute, or relative to `root`) relative to the package, `../` when outside."""
    full = os.path.normpath(os.path.join(str(root), path))
    return os.path.relpath(full, root).replace(os.sep, "/")


def _text(text: str | None, ctx: _Context) -> str | None:
    return substituted(text, ctx.scope)


def _package_file(attr: str | None, ctx: _Context, root: Path) -> str | None:
    return package_file(attr, ctx.scope, root)


def _ns(ctx: _Context, ns: str | None) -> str:
    """roslaunch's namespace join: a relative name below the current namespace, a global one as is."""
    text = _text(ns, ctx) if ns else None
    if not text:
        return ctx.ns
    if text.startswith("/"):
        return text.strip("/")
    return "/".join(p for p in (ctx.ns, text.strip("/")) if p)


def launch_nodes(trees: Mapping[str, LaunchXml]) -> Iterator[tuple[str, object]]:
    """(launch file, `<node>` element) for every node of every launch file, in file order."""
    for rel in sorted(trees):
        tree = trees[rel]
        if tree.root is not None:
            for node in tree.root.iter("node"):
                yield rel, node
