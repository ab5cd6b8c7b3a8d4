"""The semantic rules of an SRDF against its URDF, one set for every entry point.

Groups, named poses, end effectors, virtual and passive joints and disabled pairs of an SRDF
and of a SetupModel are the same values (`Srdf`), so one rule serves both: `check_setup` (init,
render) raises the first error, `validate` reports every finding. Only the element naming
differs: key paths of `marm_setup.yaml` (`groups[arm].chain.tip`, `setup_element`) or SRDF
elements (`group[arm].chain`, `srdf_element`).
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass

from marm_setup.findings import Finding, Location, error, warning
from marm_setup.moveit_params import VIRTUAL_JOINT_TYPES
from marm_setup.names import did_you_mean
from marm_setup.robot import RobotModel
from marm_setup.setup.groups import active_group_joints, group_joints, group_links, groups_by_name
from marm_setup.setup.model import EndEffector, Group, GroupState, VirtualJoint
from marm_setup.setup.srdf import Srdf


@dataclass(frozen=True, slots=True)
class Where:
    """An element, whatever the file: `kind` (`group`, `group_state`, ...), its name, the path
    inside it (`("chain", "tip")`, `("joints", 1)`) and, for unnamed list items, its index."""

    kind: str
    name: str = ""
    part: tuple[str | int, ...] = ()
    index: int | None = None


Style = Callable[[Where], str]

_SETUP_LISTS = {
    "robot": "robot_name",
    "group": "groups",
    "group_state": "group_states",
    "end_effector": "end_effectors",
    "virtual_joint": "virtual_joints",
    "passive_joint": "passive_joints",
    "disable_collisions": "collision.disabled",
}
_SRDF_GROUP_PARTS = {"chain": ".chain", "joints": ".joint", "links": ".link", "subgroups": ".group"}


def setup_element(w: Where) -> str:
    """`marm_setup.yaml` key paths: `groups[arm].joints[1]`, `group_states[home].values.joint1`."""
    head = _SETUP_LISTS[w.kind]
    if w.kind != "robot":
        head += f"[{w.name if w.index is None else w.index}]"
    return head + "".join(f"[{p}]" if isinstance(p, int) else f".{p}" for p in w.part)


def srdf_element(w: Where) -> str:
    """SRDF element names: `group[arm].joint`, `group_state[home].joint[joint1]`."""
    if w.kind == "robot":
        return "robot"
    head = f"{w.kind}[{w.name}]"
    if w.kind == "group" and w.part and (w.part[0] != "subgroups" or len(w.part) > 1):
        return head + _SRDF_GROUP_PARTS[str(w.part[0])]
    if w.kind == "group_state" and len(w.part) > 1:
        return f"{head}.joint[{w.part[1]}]"
    return head


class _SrdfRules:
    """Finding makers bound to one file and style (the rules that read only the SRDF)."""

    def __init__(self, srdf: Srdf, file: str, style: Style):
        self.srdf, self.file, self.style = srdf, file, style
        self.groups = groups_by_name(srdf.groups)

    def error(
        self, rule: str, where: Where, message: str, hint: str = "", refers: tuple[str, str] | None = None
    ) -> Finding:
        return error(
            rule, self.file, self.style(where), message, hint, at=Location(where.kind, where.name, refers)
        )

    def warning(self, rule: str, where: Where, message: str, hint: str = "") -> Finding:
        return warning(rule, self.file, self.style(where), message, hint, at=Location(where.kind, where.name))

    def unknown(self, rule: str, kind: str, name: str, known: Iterable[str], where: Where) -> list[Finding]:
        """[the unknown-name finding] when `name` is not in `known`, else []."""
        known = tuple(known)
        if name in known:
            return []
        refers = ("group" if kind.endswith("group") else kind, name)
        return [self.error(rule, where, f"unknown {kind} '{name}'", did_you_mean(name, known), refers)]

    def group(self, name: str, where: Where, rule: str, kind: str = "group") -> list[Finding]:
        return self.unknown(rule, kind, name, self.groups, where)


class _Rules(_SrdfRules):
    """Finding makers bound to one file, robot and style."""

    def __init__(self, srdf: Srdf, robot: RobotModel, file: str, style: Style, virtual_tfs: bool = True):
        super().__init__(srdf, file, style)
        self.robot = robot
        self.virtual_tfs = virtual_tfs  # a launch file publishes the virtual joints' transforms

    def link(self, name: str, where: Where) -> list[Finding]:
        return self.unknown("srdf.unknown-link", "link", name, self.robot.link_map, where)

    def joint(self, name: str, where: Where, rule: str = "srdf.unknown-joint") -> list[Finding]:
        """srdfdom model.cpp `isValidJoint`: a URDF joint or one of the SRDF's virtual joints."""
        known = (*self.robot.joint_map, *(vj.name for vj in self.srdf.virtual_joints))
        return self.unknown(rule, "joint", name, known, where)


def check_semantics(
    srdf: Srdf, robot: RobotModel, file: str, style: Style = srdf_element, virtual_tfs: bool = True
) -> list[Finding]:
    """Every rule, in a fixed order (the setup check raises the first error). `virtual_tfs`: a
    launch file publishes the virtual joints' transforms (what we render always does)."""
    r = _Rules(srdf, robot, file, style, virtual_tfs)
    out = check_robot_name(r)
    out += check_duplicate_groups(r)
    out += check_virtual_joints(r)
    out += check_groups(r)
    out += check_subgroup_cycles(r)
    out += check_group_states(r)
    out += check_end_effectors(r)
    out += check_passive_joints(r)
    out += check_disabled_links(r)
    return out


def check_semantics_without_robot(srdf: Srdf, file: str, style: Style = srdf_element) -> list[Finding]:
    """The rules that read only the SRDF (duplicate groups, subgroups and end effectors naming
    groups, subgroup cycles, self pairs), for a package whose robot description only the run
    time gives."""
    r = _SrdfRules(srdf, file, style)
    out = check_duplicate_groups(r)
    for group in srdf.groups:
        for i, sub in enumerate(group.subgroups):
            out += r.group(sub, Where("group", group.name, ("subgroups", i)), "srdf.unknown-subgroup")
    out += check_subgroup_cycles(r)
    for ee in srdf.end_effectors:
        out += r.group(ee.group, Where("end_effector", ee.name, ("group",)), "srdf.ee-unknown-group")
        if ee.parent_group is not None:
            at = Where("end_effector", ee.name, ("parent_group",))
            out += r.group(ee.parent_group, at, "srdf.ee-unknown-parent-group", "parent group")
    return out + [
        _self_pair(r, f"{p.link1} {p.link2}", i) for i, p in enumerate(srdf.disabled) if p.link1 == p.link2
    ]


def check_robot_name(r: _Rules) -> list[Finding]:
    if r.srdf.robot_name == r.robot.name:
        return []
    msg = f"'{r.srdf.robot_name}' is not the URDF's robot name '{r.robot.name}'"
    return [r.error("srdf.robot-name", Where("robot"), msg)]


def check_duplicate_groups(r: _SrdfRules) -> list[Finding]:
    counts = Counter(g.name for g in r.srdf.groups)
    return [
        r.error("srdf.duplicate-group", Where("group", name), f"group '{name}' defined {n} times")
        for name, n in counts.items()
        if n > 1
    ]


def check_virtual_joints(r: _Rules) -> list[Finding]:
    out: list[Finding] = []
    for vj in r.srdf.virtual_joints:
        if vj.type not in VIRTUAL_JOINT_TYPES:
            where = Where("virtual_joint", vj.name, ("type",))
            msg = f"unknown type '{vj.type}'"
            out.append(
                r.error("srdf.virtual-joint-type", where, msg, did_you_mean(vj.type, VIRTUAL_JOINT_TYPES))
            )
        where = Where("virtual_joint", vj.name, ("child_link",))
        missing = r.link(vj.child_link, where)
        out += missing
        if not missing and vj.child_link != r.robot.root:
            out += _virtual_joint_off_root(r, vj, where)
        if vj.parent_frame in r.robot.link_map and vj.parent_frame not in (r.robot.root, vj.child_link):
            out.append(_virtual_joint_on_own_link(r, vj))
    return out


def _virtual_joint_on_own_link(r: _Rules, vj: VirtualJoint) -> Finding:
    """robot_state_publisher puts the parent link below the root; the virtual joint's TF would
    put the root below it: a loop tf2 refuses. A parent frame that is the child link itself is an
    identity (robot_model.cpp l.953-968 in moveit/moveit; tf2's TF_SELF_TRANSFORM): not here.
    For a planar or floating joint the parent frame is MoveIt's model frame, which TF places; for
    a fixed one MoveIt keeps the root link ("for fixed frames we still use the robot root link",
    robot_model.cpp l.963 moveit, l.1027 moveit2), so only a launch file publishing the virtual
    joint's transform makes the loop: without one it is a likely mistake (a warning)."""
    where = Where("virtual_joint", vj.name, ("parent_frame",))
    msg = f"parent frame '{vj.parent_frame}' is one of the robot's own links"
    if vj.type != "fixed" or r.virtual_tfs:
        return r.error("srdf.virtual-joint-parent", where, f"{msg}: TF would form a loop")
    msg += (
        ": MoveIt ignores a fixed virtual joint's parent frame and no launch file of the package "
        "publishes its transform; one that did would make a TF loop"
    )
    return r.warning(
        "srdf.virtual-joint-parent", where, msg, 'use a parent frame outside the robot (parent_frame="world")'
    )


def _virtual_joint_off_root(r: _Rules, vj: VirtualJoint, where: Where) -> list[Finding]:
    """MoveIt's robot_model.cpp (the URDF root: moveit l.931-945, moveit2 l.989-1003) skips a
    virtual joint whose child is not the root, with a warning ("Skipping virtual joint ... does
    not match the URDF frame"), and assumes a fixed joint. Except Gazebo's form: a fixed virtual
    joint onto a URDF whose root is a `world` link without collision or visual geometry is built
    silently, whatever its parent frame. Skipping a planar or floating joint loses the base's
    freedom: an error; a fixed one only renames a frame."""
    root = r.robot.link(r.robot.root)
    if vj.type == "fixed" and root.name == "world" and not root.collisions and not root.has_visual:
        return []
    msg = f"child link '{vj.child_link}' is not the URDF's root link '{r.robot.root}': MoveIt skips it"
    if vj.type in ("planar", "floating"):
        return [r.error("srdf.virtual-joint-child", where, f"{msg} and the base's {vj.type} motion")]
    return [r.warning("srdf.virtual-joint-child", where, msg, f'use child_link="{r.robot.root}"')]


def check_groups(r: _Rules) -> list[Finding]:
    """Names exist, chains run down the tree; a group that holds nothing is a warning."""
    out: list[Finding] = []
    for group in r.srdf.groups:
        found = _check_group(r, group)
        if not found and not group_links(group, r.groups, r.robot):
            found.append(
                r.warning("srdf.empty-group", Where("group", group.name), "group has no links or joints")
            )
        out += found
    return out


def _check_group(r: _Rules, group: Group) -> list[Finding]:
    def at(*part: str | int) -> Where:
        return Where("group", group.name, part)

    out: list[Finding] = []
    if group.chain is not None:
        base, tip = group.chain.base, group.chain.tip
        missing = r.link(base, at("chain", "base")) + r.link(tip, at("chain", "tip"))
        out += missing
        # a tip not below its base is a chain through the common root, which MoveIt builds
        # (robot_model.cpp addJointModelGroup; see setup.groups.chain_joint_names)
        if not missing and base == tip:
            msg = f"chain base and tip are the same link '{tip}': the chain holds no joints"
            out.append(r.warning("srdf.chain-empty", at("chain", "tip"), msg))
    for i, joint in enumerate(group.joints):
        out += r.joint(joint, at("joints", i))
    for i, link in enumerate(group.links):
        out += r.link(link, at("links", i))
    for i, sub in enumerate(group.subgroups):
        out += r.group(sub, at("subgroups", i), "srdf.unknown-subgroup")
    return out


def check_subgroup_cycles(r: _SrdfRules) -> list[Finding]:
    """A group that (through subgroups) contains itself: one finding per group on a cycle."""
    edges = {g.name: tuple(g.subgroups) for g in r.srdf.groups}
    out = []
    for start in sorted(edges):
        cycle = subgroup_cycle(start, edges)
        if cycle:
            msg = f"subgroups form a cycle: {' -> '.join(cycle)}"
            out.append(r.error("srdf.subgroup-cycle", Where("group", start, ("subgroups",)), msg))
    return out


def subgroup_cycle(start: str, edges: Mapping[str, Iterable[str]]) -> tuple[str, ...] | None:
    """A path of subgroup edges from `start` back to itself, or None; each group is visited once
    (iterative, so diamond-shaped subgroup graphs stay linear)."""
    parent: dict[str, str | None] = {start: None}
    stack = [start]
    while stack:
        node = stack.pop()
        for nxt in edges.get(node, ()):
            if nxt == start:
                path = [node]
                while (up := parent[path[-1]]) is not None:
                    path.append(up)
                return (*reversed(path), start)
            if nxt not in parent:
                parent[nxt] = node
                stack.append(nxt)
    return None


def check_group_states(r: _Rules) -> list[Finding]:
    """Group exists, joints exist and belong to it, every active joint given, within limits."""
    out: list[Finding] = []
    for state in r.srdf.group_states:
        unknown = r.group(state.group, Where("group_state", state.name, ("group",)), "pose.unknown-group")
        out += unknown or _check_state(r, state)
    return out


def _check_state(r: _Rules, state: GroupState) -> list[Finding]:
    group = r.groups[state.group]
    members = set(group_joints(group, r.groups, r.robot))
    out: list[Finding] = []
    for joint, value in state.values:
        where = Where("group_state", state.name, ("values", joint))
        out += r.joint(joint, where, "pose.unknown-joint") or _check_value(r, state, joint, value, members)
    given = {joint for joint, _ in state.values}
    active = active_group_joints(group, r.groups, r.robot, tuple(r.srdf.passive_joints))
    missing = [j for j in active if j not in given]
    if missing:  # robot_model.cpp buildGroupStates warns "doesn't specify all group joints"
        msg = f"no value for joint(s) {', '.join(missing)} of group '{state.group}' (MoveIt warns)"
        out.append(r.warning("pose.missing-joint", Where("group_state", state.name, ("values",)), msg))
    return out


def _check_value(r: _Rules, state: GroupState, joint: str, value: float, members: set[str]) -> list[Finding]:
    where = Where("group_state", state.name, ("values", joint))
    if joint not in members:
        msg = f"joint '{joint}' is not part of group '{state.group}'"
        return [r.error("pose.joint-not-in-group", where, msg)]
    j = r.robot.joint(joint)
    if j.reaches(value):  # MoveIt's goal tolerance holds a pose written rounded past its bound
        return []
    lo, hi = j.bounds
    return [r.error("pose.out-of-limits", where, f"value {value:g} is outside the limits [{lo:g}, {hi:g}]")]


def check_end_effectors(r: _Rules) -> list[Finding]:
    out: list[Finding] = []
    for ee in r.srdf.end_effectors:
        out += _check_end_effector(r, ee)
    return out


def _check_end_effector(r: _Rules, ee: EndEffector) -> list[Finding]:
    def at(part: str) -> Where:
        return Where("end_effector", ee.name, (part,))

    out = r.group(ee.group, at("group"), "srdf.ee-unknown-group")
    out += r.link(ee.parent_link, at("parent_link"))
    if ee.parent_group is not None:
        out += r.group(ee.parent_group, at("parent_group"), "srdf.ee-unknown-parent-group", "parent group")
    if out:
        return out
    if ee.parent_link in group_links(r.groups[ee.group], r.groups, r.robot):
        # a likely mistake, not an error: the Setup Assistant's own check is commented out
        # (moveit_setup_assistant end_effectors_widget.cpp `doneEditing`) and MoveIt loads it
        msg = f"parent link '{ee.parent_link}' is inside the end effector's own group '{ee.group}'"
        out.append(
            r.warning("srdf.ee-parent-in-group", at("parent_link"), msg, "use the link it is attached to")
        )
    if ee.parent_group is not None and ee.parent_link not in group_links(
        r.groups[ee.parent_group], r.groups, r.robot
    ):
        msg = f"parent link '{ee.parent_link}' is not in parent group '{ee.parent_group}'"
        out.append(r.error("srdf.ee-parent-not-in-parent-group", at("parent_link"), msg))
    return out


def check_passive_joints(r: _Rules) -> list[Finding]:
    out: list[Finding] = []
    for i, joint in enumerate(r.srdf.passive_joints):
        out += r.joint(joint, Where("passive_joint", joint, index=i))
    return out


def check_disabled_links(r: _Rules) -> list[Finding]:
    """srdfdom model.cpp `loadCollisionPairs` only warns about a pair naming an unknown link and
    drops it ("Cannot disable/enable collisions"): a warning, the pair does nothing. One warning
    per unknown link, at its first pair, counting the pairs that name it (an SRDF written for
    another variant of the robot names a few links in hundreds of pairs)."""
    out: list[Finding] = []
    unknown: dict[str, list[int]] = {}  # link -> [its finding's place in out, pairs naming it]
    for i, pair in enumerate(r.srdf.disabled):
        name = f"{pair.link1} {pair.link2}"
        if pair.link1 == pair.link2:
            out.append(_self_pair(r, name, i))
        for n, link in ((1, pair.link1), (2, pair.link2))[: 1 if pair.link1 == pair.link2 else 2]:
            if link in unknown:
                unknown[link][1] += 1
            elif found := r.link(link, Where("disable_collisions", name, (f"link{n}",), i)):
                unknown[link] = [len(out), 1]
                out.append(found[0])
    for at, count in unknown.values():
        f = out[at]
        named = "the pair" if count == 1 else f"the {count} pairs naming it"
        out[at] = warning(f.rule, f.file, f.element, f"{f.message} (srdfdom ignores {named})", f.hint)
    return out


def _self_pair(r: _SrdfRules, name: str, index: int) -> Finding:
    """A `disable_collisions` of a link with itself (xacro macros emit them): srdfdom keeps it
    (model.cpp `loadCollisionPairs` checks only that both links exist) and MoveIt's allowed
    collision matrix gets an entry no check ever asks for (a link is never checked against
    itself), so it is harmless: a warning, a likely slip in the macro."""
    where = Where("disable_collisions", name, (), index)
    msg = "a link paired with itself: the entry does nothing (MoveIt never checks a link against itself)"
    return r.warning("srdf.self-pair", where, msg, "remove it, or name the other link")
