"""SRDF vs URDF: names exist, chains valid, subgroups acyclic, end effectors and virtual joints sane."""

from __future__ import annotations

from collections import Counter

from marm_setup.collision.pairs import link_pair
from marm_setup.findings import Finding, error, warning
from marm_setup.robot.model import RobotModel
from marm_setup.setup.groups import group_links, groups_by_name
from marm_setup.setup.model import Group

VIRTUAL_JOINT_TYPES = ("fixed", "floating", "planar")


def check_srdf(srdf, robot: RobotModel, file: str, srdf_text: str | None = None) -> list[Finding]:
    """Every SRDF-vs-URDF rule."""
    out = check_robot_name(srdf, robot, file)
    out += check_groups(srdf, robot, file)
    out += check_subgroup_cycles(srdf, file)
    out += check_end_effectors(srdf, robot, file)
    out += check_virtual_joints(srdf, robot, file)
    out += check_passive_joints(srdf, robot, file)
    out += check_disabled_pairs(srdf, robot, file, srdf_text)
    return out


def check_robot_name(srdf, robot: RobotModel, file: str) -> list[Finding]:
    if srdf.robot_name == robot.name:
        return []
    return [
        error(
            "srdf.robot-name",
            file,
            "robot",
            f"SRDF is for robot '{srdf.robot_name}', the URDF is '{robot.name}'",
            hint=f'set <robot name="{robot.name}"> in the SRDF',
        )
    ]


def _link_error(file: str, where: str, link: str, robot: RobotModel) -> Finding:
    return error(
        "srdf.unknown-link", file, where, f"unknown link '{link}'", hint=_known(link, robot.link_map)
    )


def _joint_error(file: str, where: str, joint: str, robot: RobotModel) -> Finding:
    return error(
        "srdf.unknown-joint", file, where, f"unknown joint '{joint}'", hint=_known(joint, robot.joint_map)
    )


def _known(name: str, names) -> str:
    import difflib

    close = difflib.get_close_matches(name, list(names), n=3)
    return f"did you mean {', '.join(close)}?" if close else ""


def check_groups(srdf, robot: RobotModel, file: str) -> list[Finding]:
    out: list[Finding] = []
    counts = Counter(g.name for g in srdf.groups)
    for name in sorted(n for n, c in counts.items() if c > 1):
        out.append(
            error(
                "srdf.duplicate-group", file, f"group[{name}]", f"group '{name}' defined {counts[name]} times"
            )
        )
    names = set(counts)
    for group in srdf.groups:
        out += _check_group(group, names, robot, file)
    by_name = groups_by_name(srdf.groups)
    for group in srdf.groups:
        if not group_links(group, by_name, robot) and not any(
            f.element.startswith(f"group[{group.name}]") for f in out
        ):
            out.append(
                warning("srdf.empty-group", file, f"group[{group.name}]", "group has no links or joints")
            )
    return out


def _check_group(group: Group, names: set[str], robot: RobotModel, file: str) -> list[Finding]:
    where = f"group[{group.name}]"
    out: list[Finding] = []
    if group.chain is not None:
        out += _check_chain(group, robot, file)
    out += [_joint_error(file, f"{where}.joint", j, robot) for j in group.joints if j not in robot.joint_map]
    out += [
        _link_error(file, f"{where}.link", link, robot) for link in group.links if link not in robot.link_map
    ]
    for sub in group.subgroups:
        if sub not in names:
            out.append(
                error(
                    "srdf.unknown-subgroup",
                    file,
                    f"{where}.group",
                    f"unknown subgroup '{sub}'",
                    _known(sub, names),
                )
            )
    return out


def _check_chain(group: Group, robot: RobotModel, file: str) -> list[Finding]:
    where = f"group[{group.name}].chain"
    base, tip = group.chain.base, group.chain.tip
    missing = [_link_error(file, where, link, robot) for link in (base, tip) if link not in robot.link_map]
    if missing:
        return missing
    if base == tip or robot.chain(base, tip) is None:
        return [
            error(
                "srdf.chain-invalid",
                file,
                where,
                f"tip_link '{tip}' is not below base_link '{base}'",
                hint="base_link must be an ancestor of tip_link in the URDF tree",
            )
        ]
    return []


def check_subgroup_cycles(srdf, file: str) -> list[Finding]:
    """A group that (through subgroups) contains itself."""
    edges = {g.name: tuple(g.subgroups) for g in srdf.groups}
    out = []
    for start in sorted(edges):
        cycle = _find_cycle(start, edges)
        if cycle:
            out.append(
                error(
                    "srdf.subgroup-cycle",
                    file,
                    f"group[{start}]",
                    f"subgroups form a cycle: {' -> '.join(cycle)}",
                )
            )
    return out


def _find_cycle(start: str, edges: dict[str, tuple[str, ...]]) -> list[str] | None:
    stack = [(start, [start])]
    seen: set[str] = set()
    while stack:
        node, path = stack.pop()
        for nxt in edges.get(node, ()):
            if nxt == start:
                return [*path, start]
            if nxt not in seen:
                seen.add(nxt)
                stack.append((nxt, [*path, nxt]))
    return None


def check_end_effectors(srdf, robot: RobotModel, file: str) -> list[Finding]:
    by_name = groups_by_name(srdf.groups)
    out: list[Finding] = []
    for ee in srdf.end_effectors:
        out += _check_end_effector(ee, by_name, robot, file)
    return out


def _check_end_effector(ee, by_name: dict[str, Group], robot: RobotModel, file: str) -> list[Finding]:
    where = f"end_effector[{ee.name}]"
    out: list[Finding] = []
    if ee.group not in by_name:
        out.append(
            error(
                "srdf.ee-unknown-group", file, where, f"unknown group '{ee.group}'", _known(ee.group, by_name)
            )
        )
    if ee.parent_link not in robot.link_map:
        out.append(_link_error(file, where, ee.parent_link, robot))
    if ee.parent_group is not None and ee.parent_group not in by_name:
        msg = f"unknown parent_group '{ee.parent_group}'"
        out.append(error("srdf.ee-unknown-parent-group", file, where, msg, _known(ee.parent_group, by_name)))
    if out:
        return out
    if ee.parent_link in group_links(by_name[ee.group], by_name, robot):
        msg = f"parent_link '{ee.parent_link}' is part of the end-effector group '{ee.group}'"
        out.append(
            error("srdf.ee-parent-in-group", file, where, msg, "use the link the end effector is attached to")
        )
    if ee.parent_group is not None and ee.parent_link not in group_links(
        by_name[ee.parent_group], by_name, robot
    ):
        msg = f"parent_link '{ee.parent_link}' is not in parent_group '{ee.parent_group}'"
        out.append(error("srdf.ee-parent-not-in-parent-group", file, where, msg))
    return out


def check_virtual_joints(srdf, robot: RobotModel, file: str) -> list[Finding]:
    out: list[Finding] = []
    for vj in srdf.virtual_joints:
        where = f"virtual_joint[{vj.name}]"
        if vj.type not in VIRTUAL_JOINT_TYPES:
            msg = f"unknown type '{vj.type}' (valid: {', '.join(VIRTUAL_JOINT_TYPES)})"
            out.append(error("srdf.virtual-joint-type", file, where, msg))
        if vj.child_link not in robot.link_map:
            out.append(_link_error(file, where, vj.child_link, robot))
        elif vj.child_link != robot.root:
            msg = f"child_link '{vj.child_link}' is not the URDF root '{robot.root}'"
            out.append(error("srdf.virtual-joint-child", file, where, msg, f'use child_link="{robot.root}"'))
    return out


def check_passive_joints(srdf, robot: RobotModel, file: str) -> list[Finding]:
    return [
        _joint_error(file, f"passive_joint[{j}]", j, robot)
        for j in srdf.passive_joints
        if j not in robot.joint_map
    ]


def check_disabled_pairs(srdf, robot: RobotModel, file: str, srdf_text: str | None = None) -> list[Finding]:
    out: list[Finding] = []
    for pair in srdf.disabled:
        where = f"disable_collisions[{pair.link1} {pair.link2}]"
        out += [_link_error(file, where, link, robot) for link in pair.pair if link not in robot.link_map]
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
