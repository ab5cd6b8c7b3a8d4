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
- the SRDF a `*_semantic` param loads, from `textfile=` or `command="xacro FILE a:=b"` with
  those xacro args (MoveIt 1 planning_context.launch);
- `<param name value>` values (their full names).
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING

from marm_setup.package.launch_xml import LaunchXml, condition, package_file, package_relative, substituted
from marm_setup.package.substitution import Scope, SubstitutionError, substitute, truth

if TYPE_CHECKING:
    from lxml import etree

MAX_DEPTH = 20
MANAGER_PARAM = "moveit_controller_manager"


@dataclass(frozen=True, slots=True)
class YamlLoad:
    """A YAML file a launch file loads onto the parameter server."""

    file: str  # relative to the package
    ns: str  # the namespace it lands in ('' for the root), e.g. robot_description_planning
    launch: str  # the launch file holding the <rosparam>
    scope: Scope | None  # the substitutions in scope, when loaded with subst_value
    manager: str = ""  # the moveit_controller_manager param set beside it
    conditional: bool = False  # only on a branch the arg defaults do not take


@dataclass(frozen=True, slots=True)
class SemanticLoad:
    """The SRDF a launch file sets as `<robot_description>_semantic`, with its xacro args."""

    file: str
    xacro_args: tuple[tuple[str, str], ...]
    launch: str


@dataclass(frozen=True, slots=True)
class LaunchParam:
    """A `<param name value>` a launch file sets (name with its namespace, no leading /)."""

    name: str
    value: str
    launch: str


@dataclass(frozen=True)
class Ros1Launch:
    loads: tuple[YamlLoad, ...] = ()  # first reach of each (file, ns), entry points in order
    semantic: SemanticLoad | None = None
    params: tuple[LaunchParam, ...] = ()


@dataclass
class _Walk:
    """What one entry point's walk collects."""

    root: Path
    trees: Mapping[str, LaunchXml]
    find: Callable[[str], str | None]
    loads: list[YamlLoad] = field(default_factory=list)
    semantic: list[tuple[SemanticLoad, bool]] = field(default_factory=list)
    params: list[LaunchParam] = field(default_factory=list)
    included: set[str] = field(default_factory=set)


@dataclass(frozen=True)
class _Context:
    file: str
    scope: Scope
    ns: str = ""
    conditional: bool = False
    manager: str = ""
    depth: int = 0


def evaluate_ros1(
    root: Path, trees: Mapping[str, LaunchXml], find: Callable[[str], str | None]
) -> Ros1Launch:
    """Walk every launch file as an entry point and merge what they load: first the files no
    other launch file includes (what a user starts: demo.launch, move_group.launch, in name
    order), whose args reach the included ones as roslaunch passes them, then the included
    files on their own defaults."""
    loads: dict[tuple[str, str], YamlLoad] = {}
    semantic: list[tuple[SemanticLoad, bool]] = []
    params: dict[str, LaunchParam] = {}
    walks = {rel: _Walk(root, trees, find) for rel in sorted(trees)}
    for rel, walk in walks.items():
        _walk_file(walk, rel, {}, "", False, "", 0)
    included = set().union(*(w.included for w in walks.values()))
    for rel in sorted(walks, key=lambda r: (r in included, r)):
        walk = walks[rel]
        for load in walk.loads:
            known = loads.get((load.file, load.ns))
            if known is None or (known.conditional and not load.conditional):
                loads[load.file, load.ns] = load
        semantic += walk.semantic
        for p in walk.params:
            params.setdefault(p.name, p)
    chosen = next((s for s, conditional in semantic if not conditional), None)
    return Ros1Launch(
        tuple(loads.values()), chosen or next((s for s, _ in semantic), None), tuple(params.values())
    )


def _walk_file(
    walk: _Walk, rel: str, passed: Mapping[str, str], ns: str, conditional: bool, manager: str, depth: int
) -> None:
    tree = walk.trees.get(rel)
    if tree is None or tree.root is None or depth > MAX_DEPTH:
        return
    dirname = str((walk.root / rel).parent)
    scope = Scope(dict(passed), walk.find, dirname)
    ctx = _Context(rel, scope, ns, conditional, manager, depth)
    _walk_children(walk, tree.root, ctx, dict(passed), set())


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
    _walk_children(walk, elem, inner, passed, set(declared))


def _include(
    walk: _Walk, elem: etree._Element, ctx: _Context, passed: dict[str, str], declared: set[str]
) -> None:
    target = _package_file(elem.get("file"), ctx, walk.root)
    if target is None or target not in walk.trees:
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
    if (elem.get("command") or "load") != "load":
        return
    target = _package_file(elem.get("file"), ctx, walk.root)
    if target is None:
        return
    ns = _ns(ctx, elem.get("ns"))
    if elem.get("param"):
        ns = _ns(replace(ctx, ns=ns), elem.get("param"))
    scope = ctx.scope if truth(elem.get("subst_value") or "") else None
    walk.loads.append(YamlLoad(target, ns, ctx.file, scope, ctx.manager, ctx.conditional))


def _param(
    walk: _Walk, elem: etree._Element, ctx: _Context, passed: dict[str, str], declared: set[str]
) -> _Context:
    name = _text(elem.get("name"), ctx)
    if not name:
        return ctx
    full = _ns(ctx, name)
    if name.endswith("_semantic"):
        found = _semantic(elem, ctx, walk.root)
        if found is not None:
            walk.semantic.append((found, ctx.conditional))
    value = _text(elem.get("value"), ctx) if elem.get("value") is not None else None
    if value is None:
        return ctx
    if not ctx.conditional:
        walk.params.append(LaunchParam(full, value, ctx.file))
    return replace(ctx, manager=value) if full.rsplit("/", 1)[-1] == MANAGER_PARAM else ctx


_HANDLERS: dict[str, Callable] = {
    "arg": _arg,
    "group": _group,
    "node": _node,
    "include": _include,
    "rosparam": _rosparam,
    "param": _param,
}


def _semantic(elem: etree._Element, ctx: _Context, root: Path) -> SemanticLoad | None:
    if elem.get("textfile"):
        target = _package_file(elem.get("textfile"), ctx, root)
        return SemanticLoad(target, (), ctx.file) if target is not None else None
    command = elem.get("command")
    if not command:
        return None
    # `$(find xacro)/xacro`: the tool's own package need not be on the package path
    lenient = replace(
        ctx, scope=Scope(ctx.scope.args, lambda n: ctx.scope.find(n) or f"/{n}", ctx.scope.dirname)
    )
    text = _text(command, lenient)
    if text is None:
        return None
    words = text.replace("'", " ").replace('"', " ").split()
    files = [w for w in words if w.endswith((".xacro", ".srdf"))]
    target = package_relative(files[-1], root) if files else None
    if target is None:
        return None
    mappings = tuple(sorted(tuple(w.split(":=", 1)) for w in words if ":=" in w and not w.startswith("__")))
    return SemanticLoad(target, mappings, ctx.file)  # type: ignore[arg-type]


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
