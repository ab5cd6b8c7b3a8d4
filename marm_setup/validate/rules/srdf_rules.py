"""SRDF vs URDF: the shared rule set of `setup.rules` (names, chains, subgroup cycles, poses,
end effectors, virtual and passive joints, disabled pairs), plus what only a file shows."""

from __future__ import annotations

from collections import Counter

from marm_setup.collision.pairs import link_pair
from marm_setup.findings import Finding, warning
from marm_setup.robot.model import RobotModel
from marm_setup.setup.rules import check_semantics, srdf_element
from marm_setup.setup.srdf import Srdf


def check_srdf(srdf: Srdf, robot: RobotModel, file: str, srdf_text: str | None = None) -> list[Finding]:
    """Every SRDF-vs-URDF rule, named pose values included."""
    out = check_semantics(srdf, robot, file, srdf_element)
    if srdf_text:
        out += _duplicate_pairs(srdf_text, file)
    return out


def _duplicate_pairs(text: str, file: str) -> list[Finding]:
    """`disable_collisions` pairs written more than once (in either order)."""
    from lxml import etree

    try:
        root = etree.fromstring(text.encode("utf-8"), etree.XMLParser(remove_comments=True))
    except etree.XMLSyntaxError:
        return []
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
