"""SRDF values: read every srdfdom element with lxml; `setup_to_srdf` is what a setup renders to.

`read_srdf` gives an `Srdf` value (document order for groups, states, end effectors and
virtual joints; pairs and other order-free lists sorted), so read -> render -> read is exact.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from os import PathLike
from pathlib import Path
from typing import TYPE_CHECKING

from marm_setup import bounded_read
from marm_setup.collision import DisabledPair, DisabledReason, link_pair
from marm_setup.errors import InputError
from marm_setup.robot import strict_float

if TYPE_CHECKING:
    from lxml import etree

from marm_setup.setup.model import (
    Chain,
    CollisionPair,
    EndEffector,
    Group,
    GroupState,
    JointProperty,
    LinkSpheres,
    SetupModel,
    SphereApprox,
    SrdfExtras,
    VirtualJoint,
)

if TYPE_CHECKING:
    from marm_setup.robot import XacroOutput


@dataclass(frozen=True, slots=True)
class Srdf:
    """Everything an SRDF holds (srdfdom's elements), as setup-model values."""

    robot_name: str
    groups: tuple[Group, ...] = ()
    group_states: tuple[GroupState, ...] = ()
    end_effectors: tuple[EndEffector, ...] = ()
    virtual_joints: tuple[VirtualJoint, ...] = ()
    passive_joints: tuple[str, ...] = ()
    disabled: tuple[DisabledPair, ...] = ()
    extras: SrdfExtras = field(default_factory=SrdfExtras)


class _Reader:
    """Attribute access that raises an InputError naming the file and element; with `skipped`
    (a list), `each` drops an element that fails and records the error there instead."""

    def __init__(self, path: str, skipped: list[InputError] | None = None):
        self.path = path
        self.skipped = skipped

    def each(self, elems, parse) -> list:
        """`parse(self, elem)` for each element; failures raise, or are skipped and recorded."""
        out = []
        for elem in elems:
            try:
                out.append(parse(self, elem))
            except InputError as exc:
                if self.skipped is None:
                    raise
                self.skipped.append(exc)
        return out

    def attr(self, elem, name: str, where: str) -> str:
        value = elem.get(name)
        if value is None or value == "":
            raise InputError(f"missing attribute '{name}'", path=self.path, element=where)
        return value

    def number(self, text: str, where: str) -> float:
        try:
            value = strict_float(text)
        except ValueError:
            raise InputError(f"not a number: '{text}'", path=self.path, element=where) from None
        if not math.isfinite(value):
            raise InputError(f"expected a finite number, got '{text}'", path=self.path, element=where)
        return value

    def fail(self, message: str, where: str) -> InputError:
        return InputError(message, path=self.path, element=where)


def read_srdf(path: str | PathLike, skipped: list[InputError] | None = None) -> Srdf:
    """Parse an SRDF file (path as the user typed it, for messages); with `skipped`, elements
    that cannot be read are left out and their errors recorded there (as srdfdom does)."""

    shown = str(path)
    try:
        data = bounded_read.read_bytes(path, bounded_read.XML_BYTES, shown=shown)
    except OSError as exc:
        raise InputError(f"cannot read: {exc}", path=shown) from None
    return parse_srdf_document(data, shown, skipped)[0]


def expand_srdf_xacro(
    path: str | PathLike,
    xacro_args: Mapping[str, str],
    package_paths: Iterable[str | PathLike] = (),
    *,
    shown: str | None = None,
) -> XacroOutput:
    """The SRDF a `.srdf.xacro` makes: the real xacro with `xacro_args`, `$(find pkg)` from
    `package_paths` and the folders around it, in the bounded child process (robot/xacro_expand)."""
    from marm_setup.robot import find_packages, run_xacro

    file = Path(path)
    packages = find_packages([Path(p) for p in package_paths], near=file)
    return run_xacro(file, xacro_args, packages, shown=str(path) if shown is None else shown)


def load_srdf(
    path: str | PathLike,
    skipped: list[InputError] | None = None,
    *,
    xacro_args: Mapping[str, str] | None = None,
    package_paths: Iterable[str | PathLike] = (),
) -> tuple[Srdf, frozenset[str] | None]:
    """`read_srdf`, a `.xacro` expanded first (`expand_srdf_xacro`); with the arguments the
    xacro takes (None for a plain SRDF)."""
    if Path(path).suffix != ".xacro":
        return read_srdf(path, skipped), None
    if not Path(path).is_file():
        raise InputError("file not found", path=str(path))
    expanded = expand_srdf_xacro(path, xacro_args or {}, package_paths)
    return parse_srdf_string(expanded.xml, str(path), skipped), expanded.declared


def parse_srdf_string(text: str, path: str = "<srdf>", skipped: list[InputError] | None = None) -> Srdf:
    return parse_srdf_document(text, path, skipped)[0]


def parse_srdf_document(
    text: str | bytes, path: str = "<srdf>", skipped: list[InputError] | None = None
) -> tuple[Srdf, etree._Element]:
    """(the SRDF, its XML root): the one place SRDF text is parsed (read_srdf reads a file into
    it), as srdfdom's tinyxml2 parses it (`--` inside a comment is read: robot.tinyxml_comments);
    the root is for what only the XML shows (pairs written twice, misplaced elements)."""
    from lxml import etree

    from marm_setup.robot import tinyxml_comments

    try:
        data = tinyxml_comments(text.encode() if isinstance(text, str) else text)
        root = etree.fromstring(data, etree.XMLParser(remove_comments=True))
    except etree.XMLSyntaxError as exc:
        raise srdf_syntax_error(exc, path) from None
    return parse_srdf_root(root, path, skipped), root


def srdf_syntax_error(exc, shown: str) -> InputError:
    """libxml2's complaint on one line, the element naming its line (as for a URDF)."""
    from marm_setup.robot import xml_syntax_message

    return InputError(
        f"not well-formed XML: {xml_syntax_message(exc)}", path=shown, element=f"line {exc.lineno}"
    )


def parse_srdf_root(root, path: str, skipped: list[InputError] | None = None) -> Srdf:
    """The SRDF of an lxml root; with `skipped`, an element that cannot be read is left out and
    its error recorded there (as srdfdom logs and skips it), so the rest can still be checked."""
    r = _Reader(path, skipped)
    if root.tag != "robot":
        raise r.fail(f"root element is <{root.tag}>, expected <robot>", "robot")
    return Srdf(
        robot_name=root.get("name", ""),
        groups=tuple(r.each(root.iterchildren("group"), _group)),
        group_states=tuple(r.each(root.iterchildren("group_state"), _group_state)),
        end_effectors=tuple(r.each(root.iterchildren("end_effector"), _end_effector)),
        virtual_joints=tuple(r.each(root.iterchildren("virtual_joint"), _virtual_joint)),
        passive_joints=tuple(r.each(root.iterchildren("passive_joint"), _passive_joint)),
        disabled=_disabled(r, root),
        extras=SrdfExtras(
            enable_collisions=_enabled(r, root),
            disable_default_collisions=tuple(
                sorted(set(r.each(root.iterchildren("disable_default_collisions"), _default_off)))
            ),
            joint_properties=tuple(
                sorted(r.each(root.iterchildren("joint_property"), _joint_property), key=_jp_key)
            ),
            link_sphere_approximations=tuple(
                sorted(
                    r.each(root.iterchildren("link_sphere_approximation"), _link_spheres),
                    key=lambda s: s.link,
                )
            ),
        ),
    )


def _passive_joint(r: _Reader, elem) -> str:
    return r.attr(elem, "name", "passive_joint")


def _default_off(r: _Reader, elem) -> str:
    return r.attr(elem, "link", "disable_default_collisions")


def _group(r: _Reader, elem) -> Group:
    name = r.attr(elem, "name", "group")
    where = f"group[{name}]"
    chains = [
        Chain(r.attr(c, "base_link", f"{where}.chain"), r.attr(c, "tip_link", f"{where}.chain"))
        for c in elem.iterchildren("chain")
    ]
    if len(chains) > 1:
        raise r.fail("more than one <chain> in a group is not supported", where)
    return Group(
        name=name,
        chain=chains[0] if chains else None,
        joints=tuple(r.attr(j, "name", f"{where}.joint") for j in elem.iterchildren("joint")),
        links=tuple(r.attr(j, "name", f"{where}.link") for j in elem.iterchildren("link")),
        subgroups=tuple(r.attr(j, "name", f"{where}.group") for j in elem.iterchildren("group")),
    )


def _group_state(r: _Reader, elem) -> GroupState:
    name = r.attr(elem, "name", "group_state")
    where = f"group_state[{name}]"

    def value(r: _Reader, j) -> tuple[str, tuple[float, ...]]:
        joint = r.attr(j, "name", f"{where}.joint")
        text = r.attr(j, "value", f"{where}.joint[{joint}]").split()
        return joint, tuple(r.number(t, f"{where}.joint[{joint}]") for t in text)

    # srdfdom model.cpp loadGroupStates reads a value list per joint (several for a multi-DOF
    # joint) and skips only the bad <joint>
    read = r.each(elem.iterchildren("joint"), value)
    values = tuple((joint, numbers[0]) for joint, numbers in read if len(numbers) == 1)
    multi = tuple((joint, numbers) for joint, numbers in read if len(numbers) != 1)
    return GroupState(name=name, group=r.attr(elem, "group", where), values=values, multi_dof=multi)


def _end_effector(r: _Reader, elem) -> EndEffector:
    name = r.attr(elem, "name", "end_effector")
    where = f"end_effector[{name}]"
    return EndEffector(
        name=name,
        group=r.attr(elem, "group", where),
        parent_link=r.attr(elem, "parent_link", where),
        parent_group=elem.get("parent_group") or None,
    )


def _virtual_joint(r: _Reader, elem) -> VirtualJoint:
    name = r.attr(elem, "name", "virtual_joint")
    where = f"virtual_joint[{name}]"
    return VirtualJoint(
        name=name,
        type=r.attr(elem, "type", where),
        parent_frame=r.attr(elem, "parent_frame", where),
        child_link=r.attr(elem, "child_link", where),
    )


def _disabled(r: _Reader, root) -> tuple[DisabledPair, ...]:
    """`disable_collisions` pairs, canonical and sorted.

    A missing or unknown reason counts as User, as in the Setup Assistant: kept, never recomputed.
    """
    known = {m.value for m in DisabledReason}
    pairs: dict[tuple[str, str], DisabledPair] = {}
    for a, b, reason in r.each(root.iterchildren("disable_collisions"), _pair_attrs):
        reason = reason if reason in known else DisabledReason.USER.value
        pairs.setdefault(link_pair(a, b), DisabledPair.of(a, b, reason))
    return tuple(sorted(pairs.values()))


def _pair_attrs(r: _Reader, e) -> tuple[str, str, str]:
    where = str(e.tag)
    return r.attr(e, "link1", where), r.attr(e, "link2", where), e.get("reason") or ""


def _enabled(r: _Reader, root) -> tuple[CollisionPair, ...]:
    pairs: dict[tuple[str, str], CollisionPair] = {}
    for a1, b1, reason in r.each(root.iterchildren("enable_collisions"), _pair_attrs):
        a, b = link_pair(a1, b1)
        pairs.setdefault((a, b), CollisionPair(a, b, reason))
    return tuple(pairs[k] for k in sorted(pairs))


def _joint_property(r: _Reader, elem) -> JointProperty:
    return JointProperty(
        joint=r.attr(elem, "joint_name", "joint_property"),
        property=r.attr(elem, "property_name", "joint_property"),
        value=elem.get("value", ""),
    )


def _jp_key(p: JointProperty) -> tuple[str, str]:
    return (p.joint, p.property)


def _link_spheres(r: _Reader, elem) -> LinkSpheres:
    link = r.attr(elem, "link", "link_sphere_approximation")
    where = f"link_sphere_approximation[{link}]"
    spheres = []
    for s in elem.iterchildren("sphere"):
        center = [r.number(t, where) for t in r.attr(s, "center", where).split()]
        if len(center) != 3:
            raise r.fail("sphere center needs 3 numbers", where)
        x, y, z = center
        spheres.append(SphereApprox(center=(x, y, z), radius=r.number(r.attr(s, "radius", where), where)))
    return LinkSpheres(link=link, spheres=tuple(spheres))


def allowed_pairs(srdf: Srdf, candidates) -> frozenset[tuple[str, str]]:
    """The `candidates` pairs MoveIt never checks under this SRDF, built as MoveIt builds its
    allowed collision matrix from srdfdom (model.h: `getNoDefaultCollisionLinks` "disabled by
    default, and only selectively enabled", then `getEnabledCollisionPairs` re-enabled, then
    `getDisabledCollisionPairs` disabled): a disabled pair, or a pair touching a
    `disable_default_collisions` link that no `enable_collisions` re-enables."""
    disabled = {p.pair for p in srdf.disabled}
    enabled = {link_pair(p.link1, p.link2) for p in srdf.extras.enable_collisions}
    off = set(srdf.extras.disable_default_collisions)
    return frozenset(
        pair
        for pair in (link_pair(a, b) for a, b in candidates)
        if pair in disabled or ((pair[0] in off or pair[1] in off) and pair not in enabled)
    )


# -- between Srdf and SetupModel ---------------------------------------------------------------


def srdf_to_setup(srdf: Srdf, base: SetupModel) -> SetupModel:
    """Import an SRDF into a setup: its semantic parts replace the base's, the rest is kept. An
    SRDF without groups (one that only carries the collision matrix) keeps the base's groups,
    poses, end effectors and joints, and gives its pairs and extras."""
    if not srdf.groups:
        collision = dataclasses.replace(base.collision, disabled=srdf.disabled)
        return dataclasses.replace(base, collision=collision, srdf_extras=srdf.extras)
    return dataclasses.replace(
        base,
        groups=srdf.groups,
        group_states=srdf.group_states,
        end_effectors=srdf.end_effectors,
        virtual_joints=srdf.virtual_joints,
        passive_joints=srdf.passive_joints,
        collision=dataclasses.replace(base.collision, disabled=srdf.disabled),
        srdf_extras=srdf.extras,
    )


def setup_to_srdf(model: SetupModel) -> Srdf:
    """The SRDF a setup renders to, as a value (pairs in the setup's order: `read_srdf` of the
    rendered file gives them sorted)."""
    return Srdf(
        robot_name=model.robot_name,
        groups=model.groups,
        group_states=model.group_states,
        end_effectors=model.end_effectors,
        virtual_joints=model.virtual_joints,
        passive_joints=model.passive_joints,
        disabled=model.collision.disabled,
        extras=model.srdf_extras,
    )
