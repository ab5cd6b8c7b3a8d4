"""An SRDF as srdfdom and MoveIt load it: what they skip (logging an error) is dropped here too,
with one line each, so `init --from-srdf` imports what MoveIt would run with.

What is skipped, from the sources:
- srdfdom model.cpp: `initXml` logs a robot name that is not the URDF's and reads on;
  `loadGroups` skips a group member naming an unknown joint or link and a
  chain with an unknown link, then removes every group whose subgroups are not all known
  ("has unsatisfied subgroups": unknown ones, or a subgroup cycle); `loadGroupStates` skips a
  state of an unknown group and a value of an unknown joint; `loadEndEffectors` one whose group
  or parent link is unknown; `loadVirtualJoints` one whose child link is unknown;
  `loadPassiveJoints` an unknown joint; `loadCollisionPairs` a pair naming an unknown link.
  Elements missing an attribute are skipped while reading
  (`parse_srdf_root(..., skipped)`).
- moveit_core robot_model.cpp: `addJointModelGroup` keeps the first of two groups of one name
  ("already exists. Not adding"); `buildGroupStates` drops a value of a joint outside the group
  ("that joint is not part of group") and adds no state left without values (`if
  (!state.empty())`); an end effector's unknown parent group is ignored.
- A value outside its joint's limits by no more than START_BOUNDS_TOLERANCE is clamped: what
  MoveIt's FixStartStateBounds adapter does to a start state by default
  (`start_state_max_bounds_error`, 0.05); a larger violation stays for the rules to refuse.
A group left with nothing stays (srdfdom keeps it; the setup keeps it with a warning, so an
SRDF round-trips), though MoveIt's RobotModel will not build it.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping

from marm_setup.moveit_params import VIRTUAL_JOINT_TYPES
from marm_setup.robot import RobotModel
from marm_setup.setup.groups import group_joints, groups_by_name
from marm_setup.setup.model import EndEffector, Group, GroupState, VirtualJoint
from marm_setup.setup.srdf import Srdf

START_BOUNDS_TOLERANCE = 0.05  # [rad or m] MoveIt's default start_state_max_bounds_error


def as_moveit_loads(srdf: Srdf, robot: RobotModel) -> tuple[Srdf, tuple[str, ...]]:
    """`srdf` without what srdfdom and MoveIt skip, and a line per element dropped or changed."""
    notes: list[str] = []
    if srdf.robot_name != robot.name:  # srdfdom logs "not specified for the same robot" and loads it
        notes.append(f"robot: '{srdf.robot_name}' is not the URDF's robot name '{robot.name}'")
    virtual = tuple(vj for vj in srdf.virtual_joints if vj.child_link in robot.link_map)
    notes += [
        f"virtual_joint[{vj.name}]: unknown child link '{vj.child_link}'"
        for vj in srdf.virtual_joints
        if vj not in virtual
    ]
    joints = {*robot.joint_map, *(vj.name for vj in virtual)}
    groups = _loaded_groups(srdf.groups, robot, joints, notes)
    by_name = groups_by_name(groups)
    states = tuple(
        s for s in (_loaded_state(s, by_name, robot, joints, notes) for s in srdf.group_states) if s
    )
    effectors = tuple(
        e for e in (_loaded_effector(e, by_name, robot, notes) for e in srdf.end_effectors) if e
    )
    passive = tuple(j for j in srdf.passive_joints if j in joints)
    notes += [f"passive_joint[{j}]: unknown joint" for j in srdf.passive_joints if j not in joints]
    known = set(robot.link_map)
    disabled = tuple(p for p in srdf.disabled if {p.link1, p.link2} <= known)
    notes += [
        f"disable_collisions[{p.link1} {p.link2}]: unknown link" for p in srdf.disabled if p not in disabled
    ]
    loaded = dataclasses.replace(
        srdf,
        groups=groups,
        group_states=states,
        end_effectors=effectors,
        virtual_joints=virtual,
        passive_joints=passive,
        disabled=disabled,
    )
    return loaded, tuple(notes)


def root_virtual_joint(virtual_joints: tuple[VirtualJoint, ...], robot: RobotModel) -> VirtualJoint | None:
    """The virtual joint MoveIt builds as the robot's root joint: the first whose child is the
    URDF's root link, with a parent frame and a known type (moveit/moveit2 moveit_core
    robot_model.cpp `buildJointModel` l.985-1035, 8fcb5d2: a virtual joint whose child is not the
    root is skipped, "does not match the URDF frame", as its child already has a URDF parent
    joint; a fixed one onto a geometry-less URDF root `world`, l.989-996, only names that root's
    joint). The others move nothing in MoveIt; a TF for one would give a link a second parent."""
    return next(
        (
            vj
            for vj in virtual_joints
            if vj.child_link == robot.root and vj.parent_frame and vj.type in VIRTUAL_JOINT_TYPES
        ),
        None,
    )


def _loaded_groups(
    groups: tuple[Group, ...], robot: RobotModel, joints: set[str], notes: list[str]
) -> tuple[Group, ...]:
    """Members that exist; the first group of a name; groups whose subgroups all load."""
    kept: dict[str, Group] = {}
    for group in groups:
        if group.name in kept:
            notes.append(f"group[{group.name}]: a second group of that name (MoveIt keeps the first)")
        else:
            kept[group.name] = _loaded_members(group, robot, joints, notes)
    known: set[str] = set()
    while more := {n for n, g in kept.items() if n not in known and set(g.subgroups) <= known}:
        known |= more
    for name in kept:
        if name not in known:
            notes.append(f"group[{name}]: subgroups that do not all load (unknown, or a cycle)")
    return tuple(g for name, g in kept.items() if name in known)


def _loaded_members(group: Group, robot: RobotModel, joints: set[str], notes: list[str]) -> Group:
    where = f"group[{group.name}]"
    chain = group.chain
    if chain is not None and not {chain.base, chain.tip} <= set(robot.link_map):
        notes.append(f"{where}.chain: unknown link in '{chain.base}' -> '{chain.tip}'")
        chain = None
    kept_joints = tuple(j for j in group.joints if j in joints)
    kept_links = tuple(x for x in group.links if x in robot.link_map)
    notes += [f"{where}.joint: unknown joint '{j}'" for j in group.joints if j not in joints]
    notes += [f"{where}.link: unknown link '{x}'" for x in group.links if x not in robot.link_map]
    return dataclasses.replace(group, chain=chain, joints=kept_joints, links=kept_links)


def _loaded_state(
    state: GroupState, groups: Mapping[str, Group], robot: RobotModel, joints: set[str], notes: list[str]
) -> GroupState | None:
    where = f"group_state[{state.name}]"
    group = groups.get(state.group)
    if group is None:
        notes.append(f"{where}: group '{state.group}' is not loaded")
        return None
    members = set(group_joints(group, groups, robot)) | {j for j in group.joints if j in joints}
    values = []
    for joint, value in state.values:
        if joint not in joints:
            notes.append(f"{where}.joint[{joint}]: unknown joint")
        elif joint not in members:
            notes.append(f"{where}.joint[{joint}]: not part of group '{state.group}'")
        else:
            values.append((joint, _clamped(robot, joint, value, f"{where}.joint[{joint}]", notes)))
    multi = tuple((j, v) for j, v in state.multi_dof if j in joints)
    notes += [f"{where}.joint[{j}]: unknown joint" for j, _ in state.multi_dof if j not in joints]
    if not values and not multi:  # robot_model.cpp buildGroupStates: `if (!state.empty())` only
        notes.append(f"{where}: no joint value left (MoveIt adds no such state)")
        return None
    return dataclasses.replace(state, values=tuple(values), multi_dof=multi)


def _clamped(robot: RobotModel, joint: str, value: float, where: str, notes: list[str]) -> float:
    j = robot.joint_map.get(joint)
    if j is None or j.within_limits(value):
        return value
    lo, hi = j.bounds
    near = min(max(value, lo), hi)
    if abs(near - value) > START_BOUNDS_TOLERANCE:
        return value
    notes.append(f"{where}: {value:g} clamped to the limits [{lo:g}, {hi:g}] (changed)")
    return near


def _loaded_effector(
    ee: EndEffector, groups: Mapping[str, Group], robot: RobotModel, notes: list[str]
) -> EndEffector | None:
    where = f"end_effector[{ee.name}]"
    if ee.group not in groups:
        notes.append(f"{where}: group '{ee.group}' is not loaded")
        return None
    if ee.parent_link not in robot.link_map:
        notes.append(f"{where}: unknown parent link '{ee.parent_link}'")
        return None
    if ee.parent_group is not None and ee.parent_group not in groups:
        notes.append(f"{where}: parent group '{ee.parent_group}' is not loaded (ignored)")
        return dataclasses.replace(ee, parent_group=None)
    return ee
