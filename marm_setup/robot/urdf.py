"""URDF XML (lxml element) -> RobotModel, with element-level InputErrors for bad structure."""

from __future__ import annotations

import dataclasses
import math
import re
from pathlib import Path

from lxml import etree

from marm_setup.errors import InputError
from marm_setup.names import did_you_mean, with_hint
from marm_setup.robot.model import (
    Box,
    CollisionShape,
    Cylinder,
    Geometry,
    Joint,
    Link,
    Mesh,
    Mimic,
    Origin,
    RobotModel,
    Sphere,
    Vec3,
)
from marm_setup.robot.ros_packages import PackageMap, resolve_uri

# No real robot has a length, limit, scale or effort beyond this; near 1e308 sums and products
# of poses overflow to inf and NaN, and every collision check then says "no contact".
MAX_MAGNITUDE = 1e9
AXIS_EPS = 1e-9  # an axis shorter than this (1e-320 1e-320 0) has no direction
MAX_LIMIT = 1e16  # joint position limits: sdformat's "unbounded" value, which SDF -> URDF writes
# A number as urdfdom's strToDouble (a C++ stream) and srdfdom's lexical_cast read it: ASCII
# digits, a point, an exponent; not Python's extras (`1_0`, other scripts' digits, ' 1 ').
NUMBER = re.compile(r"[+-]?([0-9]+(\.[0-9]*)?|\.[0-9]+)([eE][+-]?[0-9]+)?")
NON_FINITE = re.compile(r"[+-]?(nan|inf|infinity)", re.IGNORECASE)


def strict_float(text: str) -> float:
    """`text` as a C++ reader takes a number (nan / inf spelled out pass, for the caller to
    refuse as not finite); ValueError otherwise."""
    if NUMBER.fullmatch(text) or NON_FINITE.fullmatch(text):
        return float(text)
    raise ValueError(f"not a number: {text!r}")


JOINT_TYPES = ("revolute", "continuous", "prismatic", "fixed", "floating", "planar")


class _Ctx:
    """What every parse step needs to name errors and resolve meshes."""

    def __init__(self, shown: str, base_dir: Path, packages: PackageMap):
        self.shown, self.base_dir, self.packages = shown, base_dir, packages

    def error(self, element: str, message: str) -> InputError:
        return InputError(message, path=self.shown, element=element)


def parse_urdf(
    root: etree._Element, xml: str, base_dir: Path, packages: PackageMap, *, shown: str
) -> RobotModel:
    """Convert a parsed `<robot>` element; checks names, tree shape and limits."""
    ctx = _Ctx(shown, base_dir, packages)
    if root.tag != "robot":
        raise ctx.error(f"<{root.tag!s}>", "root element must be <robot>")
    links = tuple(_parse_link(el, ctx) for el in root.findall("link"))
    joints = tuple(_parse_joint(el, ctx) for el in root.findall("joint"))
    _check_unique(links, "link", ctx)
    _check_unique(joints, "joint", ctx)
    root_link = _check_tree(links, joints, ctx)
    _check_mimics(joints, ctx)
    return RobotModel(
        name=root.get("name", ""),
        links=links,
        joints=joints,
        root=root_link,
        source=shown,
        urdf_xml=xml,
    )


def _floats(
    text: str | None,
    n: int,
    element: str,
    ctx: _Ctx,
    default: tuple[float, ...] | None = None,
    magnitude: float = MAX_MAGNITUDE,
) -> tuple[float, ...]:
    if text is None:
        if default is None:
            raise ctx.error(element, "missing value")
        return default
    try:
        values = tuple(strict_float(v) for v in text.split())
    except ValueError:
        raise ctx.error(element, f"expected {n} numbers, got '{text}'") from None
    if len(values) != n:
        raise ctx.error(element, f"expected {n} numbers, got '{text}'")
    if not all(math.isfinite(v) for v in values):
        raise ctx.error(element, f"expected finite numbers, got '{text}'")
    if any(abs(v) > magnitude for v in values):
        raise ctx.error(
            element, f"'{text}' is out of range (|value| <= {magnitude:g}: metres, radians, N, m/s)"
        )
    return values


def _vec3(text: str | None, element: str, ctx: _Ctx, default: Vec3 | None = None) -> Vec3:
    x, y, z = _floats(text, 3, element, ctx, default)
    return (x, y, z)


def _sizes(el: etree._Element, keys: tuple[str, ...], element: str, ctx: _Ctx) -> tuple[float, ...]:
    """Non-negative shape dimensions from attributes `keys` (one number each, `size` three)."""
    out: list[float] = []
    for key in keys:
        n = 3 if key == "size" else 1
        values = _floats(el.get(key), n, f"{element}@{key}", ctx)
        if any(v < 0 for v in values):
            raise ctx.error(f"{element}@{key}", f"must not be negative, got '{el.get(key)}'")
        out.extend(values)
    return tuple(out)


def _origin(el: etree._Element | None, element: str, ctx: _Ctx) -> Origin:
    if el is None:
        return Origin()
    zero = (0.0, 0.0, 0.0)
    return Origin(
        xyz=_vec3(el.get("xyz"), f"{element}/origin@xyz", ctx, zero),
        rpy=_vec3(el.get("rpy"), f"{element}/origin@rpy", ctx, zero),
    )


def _parse_link(el: etree._Element, ctx: _Ctx) -> Link:
    name = el.get("name")
    if not name:
        raise ctx.error(f"line {el.sourceline}: <link>", "missing name")
    shapes = []
    for i, col in enumerate(el.findall("collision")):
        element = f"link[{name}]/collision[{i}]"
        geom = col.find("geometry")
        if geom is None or len(geom) == 0:
            raise ctx.error(element, "missing <geometry>")
        shapes.append(
            CollisionShape(_geometry(geom[0], element, ctx), _origin(col.find("origin"), element, ctx))
        )
    return Link(name=name, collisions=tuple(shapes), has_visual=el.find("visual") is not None)


def _geometry(el: etree._Element, element: str, ctx: _Ctx) -> Geometry:
    element = f"{element}/{el.tag!s}"
    if el.tag == "box":
        x, y, z = _sizes(el, ("size",), element, ctx)
        return Box((x, y, z))
    if el.tag == "cylinder":
        return Cylinder(*_sizes(el, ("radius", "length"), element, ctx))
    if el.tag == "sphere":
        return Sphere(*_sizes(el, ("radius",), element, ctx))
    if el.tag == "mesh":
        uri = el.get("filename")
        if not uri:
            raise ctx.error(element, "missing filename")
        path = resolve_uri(uri, ctx.base_dir, ctx.packages, path=ctx.shown, element=element)
        scale = _vec3(el.get("scale"), f"{element}@scale", ctx, (1.0, 1.0, 1.0))
        return Mesh(uri=uri, path=str(path), scale=scale)
    raise ctx.error(element, "unknown geometry; expected box, cylinder, sphere or mesh")


def _attr(el: etree._Element | None, key: str, element: str, ctx: _Ctx) -> float | None:
    if el is None or el.get(key) is None:
        return None
    magnitude = (
        MAX_LIMIT if key in ("lower", "upper", "soft_lower_limit", "soft_upper_limit") else MAX_MAGNITUDE
    )
    return _floats(el.get(key), 1, f"{element}@{key}", ctx, magnitude=magnitude)[0]


def _parse_joint(el: etree._Element, ctx: _Ctx) -> Joint:
    name = el.get("name")
    if not name:
        raise ctx.error(f"line {el.sourceline}: <joint>", "missing name")
    element = f"joint[{name}]"
    jtype = el.get("type")
    if jtype not in JOINT_TYPES:
        raise ctx.error(element, f"unknown type '{jtype}'; expected one of {', '.join(JOINT_TYPES)}")
    parent, child = (e.get("link") if e is not None else None for e in (el.find("parent"), el.find("child")))
    if not parent or not child:
        raise ctx.error(element, "needs <parent link=...> and <child link=...>")
    limit, safety, mimic = el.find("limit"), el.find("safety_controller"), el.find("mimic")
    axis = el.find("axis")
    joint = Joint(
        name=name,
        type=jtype,
        parent=parent,
        child=child,
        origin=_origin(el.find("origin"), element, ctx),
        axis=_vec3(None if axis is None else axis.get("xyz"), f"{element}/axis", ctx, (1.0, 0.0, 0.0)),
        lower=_attr(limit, "lower", f"{element}/limit", ctx),
        upper=_attr(limit, "upper", f"{element}/limit", ctx),
        velocity=_attr(limit, "velocity", f"{element}/limit", ctx),
        effort=_attr(limit, "effort", f"{element}/limit", ctx),
        mimic=_mimic(mimic, element, ctx),
        soft_lower=_attr(safety, "soft_lower_limit", f"{element}/safety_controller", ctx),
        soft_upper=_attr(safety, "soft_upper_limit", f"{element}/safety_controller", ctx),
    )
    if joint.is_actuated and max(abs(v) for v in joint.axis) < AXIS_EPS:
        raise ctx.error(f"{element}/axis", "axis must not be zero")
    return _check_limits(joint, limit, ctx)


def _check_limits(joint: Joint, limit: etree._Element | None, ctx: _Ctx) -> Joint:
    element = f"joint[{joint.name}]/limit"
    if joint.type in ("revolute", "prismatic"):
        if limit is None:
            raise ctx.error(element, f"a {joint.type} joint needs <limit>")
        lower, upper = joint.lower or 0.0, joint.upper or 0.0
        if joint.lower is None or joint.upper is None:
            joint = _replace_limits(joint, lower, upper)
        if lower > upper:
            raise ctx.error(element, f"lower {lower} > upper {upper}")
        lo, hi = joint.bounds
        if lo > hi:
            raise ctx.error(
                f"joint[{joint.name}]/safety_controller",
                f"soft limits leave no range inside [{lower}, {upper}]",
            )
    if joint.velocity is not None and joint.velocity < 0:
        raise ctx.error(element, f"negative velocity {joint.velocity}")
    return joint


def _replace_limits(joint: Joint, lower: float, upper: float) -> Joint:
    return dataclasses.replace(joint, lower=lower, upper=upper)


def _mimic(el: etree._Element | None, element: str, ctx: _Ctx) -> Mimic | None:
    if el is None:
        return None
    leader = el.get("joint")
    if not leader:
        raise ctx.error(f"{element}/mimic", "missing joint")
    multiplier = _attr(el, "multiplier", f"{element}/mimic", ctx)
    offset = _attr(el, "offset", f"{element}/mimic", ctx)
    return Mimic(
        joint=leader,
        multiplier=1.0 if multiplier is None else multiplier,
        offset=0.0 if offset is None else offset,
    )


def _check_unique(items: tuple[Link, ...] | tuple[Joint, ...], kind: str, ctx: _Ctx) -> None:
    seen: set[str] = set()
    for item in items:
        if item.name in seen:
            raise ctx.error(f"{kind}[{item.name}]", f"duplicate {kind} name")
        seen.add(item.name)


def _check_tree(links: tuple[Link, ...], joints: tuple[Joint, ...], ctx: _Ctx) -> str:
    """Every joint names known links, every link has at most one parent, one root, no cycle."""
    names = {link.name for link in links}
    if not names:
        raise ctx.error("robot", "no <link> elements")
    parent_of: dict[str, str] = {}
    for joint in joints:
        for role, link in (("parent", joint.parent), ("child", joint.child)):
            if link not in names:
                raise ctx.error(
                    f"joint[{joint.name}]/{role}",
                    with_hint(f"unknown link '{link}'", did_you_mean(link, names, few=0)),
                )
        if joint.child in parent_of:
            raise ctx.error(f"joint[{joint.name}]/child", f"link '{joint.child}' already has a parent joint")
        parent_of[joint.child] = joint.parent
    roots = sorted(names - parent_of.keys())
    if len(roots) != 1:
        what = (
            "several root links: " + ", ".join(roots) if roots else "no root link (the joints form a cycle)"
        )
        raise ctx.error("robot", what)
    rooted: set[str] = set()  # links whose ancestors end at the root: each walked once
    for link in sorted(parent_of):
        _check_no_cycle(link, parent_of, rooted, ctx)
    return roots[0]


def _check_no_cycle(link: str, parent_of: dict[str, str], rooted: set[str], ctx: _Ctx) -> None:
    """Walk up from `link` to the root or to a link already known to reach it (so a long chain
    costs linear time, not quadratic), else to a link seen twice: a cycle."""
    seen = {link}
    while link in parent_of and link not in rooted:
        link = parent_of[link]
        if link in seen:
            raise ctx.error(f"link[{link}]", "the joints form a cycle through this link")
        seen.add(link)
    rooted |= seen


def _check_mimics(joints: tuple[Joint, ...], ctx: _Ctx) -> None:
    by_name = {j.name: j for j in joints}
    for joint in joints:
        if joint.mimic is None:
            continue
        leader = by_name.get(joint.mimic.joint)
        if leader is None:
            raise ctx.error(f"joint[{joint.name}]/mimic", f"unknown joint '{joint.mimic.joint}'")
        if leader.mimic is not None:
            raise ctx.error(f"joint[{joint.name}]/mimic", f"'{leader.name}' is itself a mimic joint")
        if not leader.is_actuated:
            raise ctx.error(
                f"joint[{joint.name}]/mimic",
                f"follows '{leader.name}', a {leader.type} joint; a mimic must follow a moving joint",
            )
