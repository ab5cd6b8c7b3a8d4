"""What ROS 2 XML launch files load (launch_xml / launch_ros), evaluated without running them.

Every XML launch file is an entry point, walked in document order with its `<arg default>` /
`<let value>` values; `<include file>` passes its `<arg name value>` children. Recorded: each
parameter file a `<node>` loads with `<param from="...">` (launch_ros `Node`'s parameter
files), and the URDF and SRDF a node's `robot_description` / `robot_description_semantic`
param reads (`$(command 'cat FILE')` or `'xacro FILE a:=b'`, launch_ros1.description_load). `if` / `unless` branches the defaults do not take are marked conditional.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING

from marm_setup.package.launch_ros1 import (
    DESCRIPTION,
    DescriptionLoad,
    YamlLoad,
    description_load,
    first_taken,
)
from marm_setup.package.launch_xml import LaunchXml, condition, package_file, substituted
from marm_setup.package.substitution import Scope

if TYPE_CHECKING:
    from lxml import etree

MAX_DEPTH = 20
MAX_VISITS = 2000  # file walks per entry point: a file that includes itself with new args each time
COMMAND = re.compile(r"\$\(command\s+(['\"])(.*?)\1\s*\)")


@dataclass(frozen=True)
class Ros2XmlLaunch:
    loads: tuple[YamlLoad, ...] = ()
    semantic: DescriptionLoad | None = None
    description: DescriptionLoad | None = None
    stopped: tuple[str, ...] = ()  # entry points whose includes went past MAX_VISITS walks


@dataclass(frozen=True)
class _Context:
    file: str
    scope: Scope
    node: str = ""
    conditional: bool = False
    depth: int = 0


@dataclass
class _Walk:
    """The files and what one entry point's walk collects."""

    root: Path
    trees: Mapping[str, LaunchXml]
    loads: list[YamlLoad] = field(default_factory=list)
    semantic: list[tuple[DescriptionLoad, bool]] = field(default_factory=list)
    description: list[tuple[DescriptionLoad, bool]] = field(default_factory=list)
    walked: set[tuple] = field(default_factory=set)  # (file, args, conditional) walked
    visits: int = 0


def evaluate_ros2_xml(
    root: Path,
    trees: Mapping[str, LaunchXml],
    find: Callable[[str], str | None],
    args: Mapping[str, str] | None = None,
) -> Ros2XmlLaunch:
    """Walk every XML launch file as an entry point given `args` (as `ros2 launch` passes them)."""
    loads: dict[tuple[str, str], YamlLoad] = {}
    semantic: list[tuple[DescriptionLoad, bool]] = []
    description: list[tuple[DescriptionLoad, bool]] = []
    stopped: list[str] = []
    for rel in sorted(trees):
        walk = _Walk(root, trees)
        _walk_file(walk, find, rel, dict(args or {}), False, 0)
        if walk.visits > MAX_VISITS:
            stopped.append(rel)
        for load in walk.loads:
            known = loads.get((load.file, load.ns))
            if known is None or (known.conditional and not load.conditional):
                loads[load.file, load.ns] = load
        semantic += walk.semantic
        description += walk.description
    return Ros2XmlLaunch(
        tuple(loads.values()), first_taken(semantic), first_taken(description), tuple(stopped)
    )


def _walk_file(
    walk: _Walk,
    find: Callable[[str], str | None],
    rel: str,
    passed: Mapping[str, str],
    conditional: bool,
    depth: int,
) -> None:
    tree = walk.trees.get(rel)
    if (
        tree is None
        or tree.root is None
        or depth > MAX_DEPTH
        or not _first_walk(walk, rel, passed, conditional)
    ):
        return
    scope = Scope(dict(passed), find, str((walk.root / rel).parent), ros2=True)
    _walk_children(walk, tree.root, _Context(rel, scope, "", conditional, depth), passed)


def _first_walk(walk: _Walk, rel: str, passed: Mapping[str, str], conditional: bool) -> bool:
    """Whether `rel` is walked: not again with the same args (a file including itself twice is
    walked once per args), nor past MAX_VISITS walks of the entry point (`visits` says so)."""
    key = (rel, tuple(sorted(passed.items())), conditional)
    if key in walk.walked or walk.visits > MAX_VISITS:
        return False
    walk.walked.add(key)
    walk.visits += 1
    return walk.visits <= MAX_VISITS


def _walk_children(walk: _Walk, elem: etree._Element, ctx: _Context, passed: Mapping[str, str]) -> _Context:
    for child in elem:
        if not isinstance(child.tag, str):
            continue
        taken = _condition(child, ctx)
        if taken is not True and child.tag in ("arg", "let"):
            continue
        inner = ctx if taken else replace(ctx, conditional=True)
        if child.tag in ("arg", "let"):
            ctx = _arg(child, ctx, passed)
        elif child.tag == "include":
            _include(walk, child, inner)
        elif child.tag in ("group", "node"):
            node = (child.get("name") or child.get("exec") or "") if child.tag == "node" else inner.node
            after = _walk_children(walk, child, replace(inner, node=node), passed)
            if taken and child.tag == "group":
                ctx = replace(ctx, scope=after.scope)
        elif child.tag == "param":
            _param(walk, child, inner)
    return ctx


def _condition(elem: etree._Element, ctx: _Context) -> bool | None:
    return condition(elem, ctx.scope)


def _arg(elem: etree._Element, ctx: _Context, passed: Mapping[str, str]) -> _Context:
    name = elem.get("name")
    if not name:
        return ctx
    value = elem.get("value") if elem.tag == "let" else passed.get(name, elem.get("default"))
    resolved = _text(value, ctx) if value is not None else None
    if resolved is None:
        return ctx
    return replace(ctx, scope=ctx.scope.with_args({**ctx.scope.args, name: resolved}))


def _include(walk: _Walk, elem: etree._Element, ctx: _Context) -> None:
    target = _file(elem.get("file"), ctx, walk.root)
    if target is None or target not in walk.trees:
        return
    given: dict[str, str] = {}
    for arg in elem.iterchildren("arg"):
        name, value = arg.get("name"), _text(arg.get("value"), ctx)
        if name and value is not None:
            given[name] = value
    _walk_file(walk, ctx.scope.find, target, given, ctx.conditional, ctx.depth + 1)


def _param(walk: _Walk, elem: etree._Element, ctx: _Context) -> None:
    if elem.get("from"):
        target = _file(elem.get("from"), ctx, walk.root)
        if target is not None:
            walk.loads.append(YamlLoad(target, ctx.node, ctx.file, None, "", ctx.conditional))
        return
    value = elem.get("value")
    leaf = (_text(elem.get("name"), ctx) or "").rsplit(".", 1)[-1]
    if leaf not in (DESCRIPTION, f"{DESCRIPTION}_semantic") or not value:
        return
    match = COMMAND.search(value)
    found = description_load(match.group(2) if match else value, ctx.scope, walk.root, ctx.file)
    if found is not None:
        kept = walk.semantic if leaf.endswith("_semantic") else walk.description
        kept.append((found, ctx.conditional))


def _text(text: str | None, ctx: _Context) -> str | None:
    return substituted(text, ctx.scope)


def _file(attr: str | None, ctx: _Context, root: Path) -> str | None:
    return package_file(attr, ctx.scope, root)
