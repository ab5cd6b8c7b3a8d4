"""SRDF vs URDF: the shared rule set of `setup.rules` (names, chains, subgroup cycles, poses,
end effectors, virtual and passive joints, disabled pairs), plus what only a file shows."""

from __future__ import annotations

from collections import Counter
from typing import TYPE_CHECKING

from marm_setup.collision.pairs import link_pair
from marm_setup.findings import Finding, error, warning
from marm_setup.robot.model import RobotModel
from marm_setup.setup.rules import check_semantics, srdf_element
from marm_setup.setup.srdf import Srdf

if TYPE_CHECKING:
    from lxml import etree


def check_srdf(srdf: Srdf, robot: RobotModel, file: str, srdf_text: str | None = None) -> list[Finding]:
    """Every SRDF-vs-URDF rule, named pose values included."""
    out = check_semantics(srdf, robot, file, srdf_element)
    root = _xml(srdf_text) if srdf_text else None
    if root is not None:
        out += _duplicate_pairs(root, file)
        out += _nested_passive_joints(root, file, robot)
    return out


def _xml(text: str) -> etree._Element | None:
    from lxml import etree

    try:
        return etree.fromstring(text.encode("utf-8"), etree.XMLParser(remove_comments=True))
    except etree.XMLSyntaxError:
        return None


def _nested_passive_joints(root: etree._Element, file: str, robot: RobotModel) -> list[Finding]:
    """A `<passive_joint>` inside a `<group>`: srdfdom model.cpp reads passive joints only as
    children of `<robot>` (`loadPassiveJoints`) and `loadGroups` skips unknown children, so the
    joint silently stays active: MoveIt plans for it and expects a controller and joint states
    (an error). For a mimic or fixed joint, which MoveIt never plans for, it is only a warning."""
    out = []
    for group in root.iterchildren("group"):
        for elem in group.iterchildren("passive_joint"):
            name = elem.get("name", "")
            where = f"group[{group.get('name', '')}].passive_joint"
            active = name in robot.joint_map and robot.joint(name).is_active
            make = error if active else warning
            what = "the joint stays active" if active else "harmless here (not an active joint)"
            msg = f"passive_joint '{name}' inside a group is ignored by srdfdom: {what}"
            out.append(make("srdf.nested-passive-joint", file, where, msg, "move it under <robot>"))
    return out


def _duplicate_pairs(root: etree._Element, file: str) -> list[Finding]:
    """`disable_collisions` pairs written more than once (in either order)."""
    counts = Counter(
        link_pair(e.get("link1", ""), e.get("link2", "")) for e in root.iterchildren("disable_collisions")
    )
    return [
        warning(
            "srdf.duplicate-pair",
            file,
            f"disable_collisions[{a} {b}]",
            f"pair listed {n} times",
            hint="keep one entry (MoveIt uses the last reason)",
        )
        for (a, b), n in sorted(counts.items())
        if n > 1
    ]
