"""What a planning group holds (joints, active joints, links), resolved against the robot."""

from __future__ import annotations

from collections.abc import Iterator, Mapping

from marm_setup.robot import RobotModel
from marm_setup.setup.model import Group


def _expand(group: Group, groups: Mapping[str, Group], robot: RobotModel) -> tuple[list[str], list[str]]:
    """(joints, links) of a group and its subgroups (callers order them and drop repeats).

    Every group is expanded together with all of `groups`, whatever the shape (a diamond of
    subgroups is not exponential, a 3000-deep chain not quadratic) or depth; cycles end where
    they close. A GroupIndex (`groups_by_name`) keeps that expansion per robot, so asking it for
    every group costs one expansion. A group that is not the mapping's own (an edited copy) is
    expanded with it in the mapping's place."""
    if groups.get(group.name) is not group:
        members = _expand_all({**groups, group.name: group}, robot)
    elif isinstance(groups, GroupIndex):
        members = groups.members(robot)
    else:
        members = _expand_all(groups, robot)
    return list(members[group.name][0]), list(members[group.name][1])


Members = dict[str, tuple[tuple[str, ...], tuple[str, ...]]]


class GroupIndex(Mapping[str, Group]):
    """Groups by name (the last of a repeated name), read-only, with each robot's expansion of
    them (`members`) computed once and kept here, as long as the index lives."""

    def __init__(self, groups: tuple[Group, ...]) -> None:
        self._by_name = {g.name: g for g in groups}
        self._members: list[tuple[RobotModel, Members]] = []  # by robot identity

    def __getitem__(self, name: str) -> Group:
        return self._by_name[name]

    def __iter__(self) -> Iterator[str]:
        return iter(self._by_name)

    def __len__(self) -> int:
        return len(self._by_name)

    def members(self, robot: RobotModel) -> Members:
        """(joints, links) of every group with its subgroups, on `robot`."""
        for known, members in self._members:
            if known is robot:
                return members
        members = _expand_all(self._by_name, robot)
        self._members.append((robot, members))
        return members


def _expand_all(groups: Mapping[str, Group], robot: RobotModel) -> Members:
    """Each strongly connected set of groups (one group, or a subgroup cycle) in turn, subgroups
    first: its own members plus its subgroups', without repeats."""
    groups = {name: groups[name] for name in groups}  # one lookup per group, whatever the mapping
    out: Members = {}
    for component in _components(groups):
        joints: dict[str, None] = {}
        links: dict[str, None] = {}
        for name in component:
            own_joints, own_links = _own_members(groups[name], robot)
            joints.update(dict.fromkeys(own_joints))
            links.update(dict.fromkeys(own_links))
            for sub in groups[name].subgroups:
                if sub in out:  # an earlier component (a later one in this: a cycle member)
                    joints.update(dict.fromkeys(out[sub][0]))
                    links.update(dict.fromkeys(out[sub][1]))
        for name in component:
            out[name] = (tuple(joints), tuple(links))
    return out


def _components(groups: Mapping[str, Group]) -> list[list[str]]:
    """The subgroup graph's strongly connected components, each after those it reaches
    (Tarjan's algorithm, iterative; unknown subgroups ignored)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    out: list[list[str]] = []
    for start in groups:
        if start in index:
            continue
        work = [(start, iter(groups[start].subgroups))]
        index[start] = low[start] = len(index)
        stack.append(start)
        on_stack.add(start)
        while work:
            node, children = work[-1]
            child = next((c for c in children if c in groups), None)
            if child is None:
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[node])
                if low[node] == index[node]:
                    component = []
                    while True:
                        member = stack.pop()
                        on_stack.discard(member)
                        component.append(member)
                        if member == node:
                            break
                    out.append(component)
            elif child not in index:
                index[child] = low[child] = len(index)
                stack.append(child)
                on_stack.add(child)
                work.append((child, iter(groups[child].subgroups)))
            elif child in on_stack:
                low[node] = min(low[node], index[child])
    return out


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
    MoveIt's walk does), plus the base's path up to there. Where the paths meet at the root,
    MoveIt's walk also takes the root's joint, the virtual joint: not a URDF joint, it is left
    out here (a planar or floating one gives MoveIt's group more variables than ours). Unknown
    links give nothing (srdfdom skips the chain)."""
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
    joints, _ = _expand(group, groups, robot)
    return _tree_ordered(joints, tuple(j.name for j in robot.joints_in_tree_order))


def group_links(group: Group, groups: Mapping[str, Group], robot: RobotModel) -> tuple[str, ...]:
    """Every link of the group, in tree order."""
    _, links = _expand(group, groups, robot)
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


def groups_by_name(groups: tuple[Group, ...]) -> GroupIndex:
    """Groups by name (the last of a repeated name), read-only; it keeps their expansions."""
    return GroupIndex(groups)
