"""What a planning group holds (joints, active joints, links), resolved against the robot."""

from __future__ import annotations

from collections.abc import Mapping

from marm_setup.robot.model import RobotModel
from marm_setup.setup.model import Group


def _expand(
    group: Group, groups: Mapping[str, Group], robot: RobotModel, seen: frozenset[str]
) -> tuple[list[str], list[str]]:
    """(joints, links) of a group and its subgroups, duplicates allowed (callers order them).

    Each group reachable through subgroups is expanded once, whatever the shape (a diamond of
    subgroups is not exponential) or depth (iterative), and cycles end where they close.
    """
    joints: list[str] = []
    links: list[str] = []
    visited = set(seen) | {group.name}
    stack = [group]
    while stack:
        current = stack.pop()
        own_joints, own_links = _own_members(current, robot)
        joints += own_joints
        links += own_links
        for sub in current.subgroups:
            if sub in groups and sub not in visited:
                visited.add(sub)
                stack.append(groups[sub])
    return joints, links


def _own_members(group: Group, robot: RobotModel) -> tuple[list[str], list[str]]:
    """(joints, links) the group names itself: its chain, joints and links (with parent joints)."""
    joints: list[str] = []
    links: list[str] = []
    if group.chain is not None:
        chain = chain_joint_names(robot, group.chain.base, group.chain.tip)
        joints += chain
        links += [robot.joint(j).child for j in chain]
    joints += [j for j in group.joints if j in robot.joint_map]
    links += [robot.joint(j).child for j in group.joints if j in robot.joint_map]
    for link in group.links:
        if link in robot.link_map:
            links.append(link)
            parent = robot.parent_joint_of.get(link)
            if parent is not None:
                joints.append(parent.name)
    return joints, links


def chain_joint_names(robot: RobotModel, base: str, tip: str) -> tuple[str, ...]:
    """The joints MoveIt gives a group for `<chain base_link tip_link>` (moveit_core
    robot_model.cpp, RobotModel::addJointModelGroup): up from the tip to the base; when the base is
    not above the tip ("from one end-effector to another ... the root is in between"), up from the
    tip to where the base's own path up meets it, the joint above that meeting link included (as
    MoveIt's walk does), plus the base's path up to there. The root link's joint is the virtual
    joint, not a URDF joint: left out. Unknown links give nothing (srdfdom skips the chain)."""
    if base not in robot.link_map or tip not in robot.link_map:
        return ()
    from_tip = _parent_joints_up(robot, tip, stop=base)
    if not from_tip or from_tip[-1] != "":  # reached the base (or base == tip)
        return tuple(reversed(from_tip))
    index = {name: i for i, name in enumerate(from_tip)}
    from_base = _parent_joints_up(robot, base, stop=None)
    meet = next(k for k, name in enumerate(from_base) if name in index)
    names = from_tip[: index[from_base[meet]] + 1] + from_base[:meet]
    return tuple(n for n in names if n)


def _parent_joints_up(robot: RobotModel, link: str, stop: str | None) -> list[str]:
    """Parent joint names from `link` up to `stop` (excluded) or to the root, whose joint (the
    virtual joint) is "" and ends the list."""
    out = []
    while link != stop:
        joint = robot.parent_joint_of.get(link)
        out.append(joint.name if joint is not None else "")
        if joint is None:
            break
        link = joint.parent
    return out


def _tree_ordered(names: list[str], order: tuple[str, ...]) -> tuple[str, ...]:
    rank = {name: i for i, name in enumerate(order)}
    return tuple(sorted(set(names), key=lambda n: rank.get(n, len(rank))))


def group_joints(group: Group, groups: Mapping[str, Group], robot: RobotModel) -> tuple[str, ...]:
    """Every joint of the group (fixed and mimic included), in tree order."""
    joints, _ = _expand(group, groups, robot, frozenset({group.name}))
    return _tree_ordered(joints, tuple(j.name for j in robot.joints_in_tree_order))


def group_links(group: Group, groups: Mapping[str, Group], robot: RobotModel) -> tuple[str, ...]:
    """Every link of the group, in tree order."""
    _, links = _expand(group, groups, robot, frozenset({group.name}))
    return _tree_ordered(links, robot.links_in_tree_order)


def active_group_joints(
    group: Group, groups: Mapping[str, Group], robot: RobotModel, passive: tuple[str, ...] = ()
) -> tuple[str, ...]:
    """The group's variables: actuated, non-mimic, non-passive joints, in tree order."""
    return tuple(
        name
        for name in group_joints(group, groups, robot)
        if robot.joint(name).is_active and name not in passive
    )


def is_chain(
    group: Group, groups: Mapping[str, Group], robot: RobotModel, passive: tuple[str, ...] = ()
) -> bool:
    """MoveIt's JointModelGroup::isChain, what KDL can solve: the group's joints (fixed and mimic
    included, as MoveIt counts them) lie on one root-to-tip path, and at least one moves
    (moveit_core joint_model_group.cpp: one joint root, each joint the parent of the next)."""
    joints = group_joints(group, groups, robot)
    if not active_group_joints(group, groups, robot, passive):
        return False
    depth = {name: len(robot.path_to_root(robot.joint(name).child)) for name in joints}
    deepest = max(joints, key=lambda n: depth[n])
    on_path = {j.name for j in robot.path_to_root(robot.joint(deepest).child)}
    return all(name in on_path for name in joints)


def planning_joints(
    groups: tuple[Group, ...], robot: RobotModel, passive: tuple[str, ...] = ()
) -> tuple[str, ...]:
    """Every active joint of any group, sorted by name (the joints that need planning limits)."""
    by_name = groups_by_name(groups)
    names: set[str] = set()
    for group in groups:
        names.update(active_group_joints(group, by_name, robot, passive))
    return tuple(sorted(names))


def groups_by_name(groups: tuple[Group, ...]) -> dict[str, Group]:
    return {g.name: g for g in groups}
