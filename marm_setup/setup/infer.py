"""Infer a setup for `init` (DESIGN.md §2): arm chain, gripper group, end effector, home pose,
controllers, kinematics; and merge a partial SPEC over it.

The arm is the serial chain from the root while exactly one child subtree moves; its tip is the
last arm link extended through fixed joints to geometry-less frames (`grasping_frame`, a
flange). The gripper is every actuated joint below the arm's last joint, with the links below it
that are not on the arm (mimic joints included).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

from marm_setup.errors import InputError
from marm_setup.robot.model import Joint, RobotModel
from marm_setup.setup.domain import (
    DRIVER_ACTION_NS,
    FOLLOW_JOINT_TRAJECTORY,
    FOLLOW_JOINT_TRAJECTORY_NS,
    GRIPPER_COMMAND,
)
from marm_setup.setup.groups import active_group_joints, groups_by_name
from marm_setup.setup.model import (
    ArbotixJoint,
    Chain,
    Controller,
    EndEffector,
    Group,
    GroupState,
    Kinematics,
    PlannerDefaults,
    RobotSource,
    SetupModel,
    VirtualJoint,
)
from marm_setup.setup.yaml_io import ITEM_KEYS

ARM, GRIPPER, END_EFFECTOR, HOME = "arm", "gripper", "robot_gripper", "home"


@dataclass(frozen=True, slots=True)
class ArmGuess:
    """The inferred arm: its chain, the link after its last actuated joint, the gripper parts."""

    chain: Chain
    last_link: str
    gripper_joints: tuple[str, ...]
    gripper_links: tuple[str, ...]


def infer_setup(
    robot: RobotModel,
    *,
    package_name: str,
    source: RobotSource,
    target: str = "ros2",
    arm_required: bool = True,
) -> SetupModel:
    """A complete setup for `robot` (collision matrix left empty: `init` computes it).

    Without a serial arm from the root (a dual-arm robot) this is an InputError, or, when not
    `arm_required` (a SPEC or SRDF gives the groups), a setup with no groups.
    """
    model = SetupModel(
        package_name=package_name,
        robot_name=robot.name,
        robot=source,
        target=target,
        virtual_joints=(VirtualJoint("virtual_joint", "fixed", "world", robot.root),),
    )
    if not arm_required and not any(j.is_actuated for j in _serial_path(robot)):
        return model
    guess = infer_arm(robot)
    groups = [Group(ARM, chain=guess.chain)]
    end_effectors: tuple[EndEffector, ...] = ()
    if guess.gripper_joints:
        groups.append(Group(GRIPPER, joints=guess.gripper_joints, links=guess.gripper_links))
        end_effectors = (EndEffector(END_EFFECTOR, GRIPPER, guess.chain.tip),)
    model = dataclasses.replace(model, groups=tuple(groups), end_effectors=end_effectors)
    model = dataclasses.replace(model, group_states=(home_pose(model, robot),))
    return derive_group_settings(model, robot)


def infer_arm(robot: RobotModel) -> ArmGuess:
    """The arm chain from the root to the tool frame, and the actuated joints below it."""
    path = _serial_path(robot)
    actuated = [j for j in path if j.is_actuated]
    if not actuated:
        raise InputError(
            "no actuated joints on a serial chain from the root: nothing to plan for", path=robot.source
        )
    last_link = actuated[-1].child
    tip = tool_frame(robot, last_link)
    arm_links = {j.child for j in robot.chain(last_link, tip) or ()} | {last_link}
    below = robot.subtree_joints(last_link)
    gripper_joints = tuple(j.name for j in below if j.is_actuated)
    gripper_links: tuple[str, ...] = ()
    if gripper_joints:
        gripper_links = tuple(link for link in robot.subtree_links(last_link) if link not in arm_links)
    return ArmGuess(Chain(robot.root, tip), last_link, gripper_joints, gripper_links)


def _serial_path(robot: RobotModel) -> list[Joint]:
    """Joints from the root while exactly one child joint leads to something that moves."""
    moving = _moving_subtrees(robot)
    path: list[Joint] = []
    link = robot.root
    while True:
        children = [j for j in robot.child_joints_of[link] if j.is_actuated or moving[j.child]]
        if len(children) != 1:
            return path
        path.append(children[0])
        link = children[0].child


def _moving_subtrees(robot: RobotModel) -> dict[str, bool]:
    """link -> whether any actuated joint is below it."""
    out: dict[str, bool] = {}
    for link in reversed(robot.links_in_tree_order):
        out[link] = any(j.is_actuated or out[j.child] for j in robot.child_joints_of[link])
    return out


def tool_frame(robot: RobotModel, link: str) -> str:
    """`link` extended through fixed joints to geometry-less frames (first such child each step)."""
    while True:
        frames = [
            j.child
            for j in robot.child_joints_of[link]
            if j.type == "fixed" and not robot.link(j.child).has_geometry
        ]
        if not frames:
            return link
        link = frames[0]


def home_pose(model: SetupModel, robot: RobotModel) -> GroupState:
    """`home` for the first group: zero for every active joint, clamped into its limits."""
    group = model.groups[0]
    joints = active_group_joints(group, groups_by_name(model.groups), robot, model.passive_joints)
    return GroupState(HOME, group.name, tuple((j, _clamp(0.0, robot.joint(j).bounds)) for j in joints))


def _clamp(value: float, bounds: tuple[float, float]) -> float:
    return min(max(value, bounds[0]), bounds[1])


def fill_group_settings(model: SetupModel, robot: RobotModel) -> SetupModel:
    """`derive_group_settings` for the lists (controllers, kinematics, ...) the setup left empty."""
    derived = derive_group_settings(model, robot)
    names = ("controllers", "kinematics", "planners", "arbotix_joints")
    return dataclasses.replace(model, **{n: getattr(model, n) or getattr(derived, n) for n in names})


def derive_group_settings(model: SetupModel, robot: RobotModel) -> SetupModel:
    """Controllers, KDL kinematics, planner defaults (and ArbotiX ids for ros1) for the groups."""
    controllers = _controllers(model, robot)
    kinematics = tuple(Kinematics(g.name) for g in model.groups if g.chain is not None)
    planners = tuple(PlannerDefaults(g.name) for g in model.groups)
    arbotix: tuple[ArbotixJoint, ...] = ()
    if model.target == "ros1":
        joints = [j for c in controllers for j in c.joints]
        arbotix = tuple(ArbotixJoint(j, i) for i, j in enumerate(joints, start=1))
    return dataclasses.replace(
        model, controllers=controllers, kinematics=kinematics, planners=planners, arbotix_joints=arbotix
    )


def _controllers(model: SetupModel, robot: RobotModel) -> tuple[Controller, ...]:
    """One controller per group without subgroups: GripperCommand for end-effector groups."""
    by_name = groups_by_name(model.groups)
    ee_groups = {ee.group for ee in model.end_effectors}
    out = []
    for group in model.groups:
        joints = active_group_joints(group, by_name, robot, model.passive_joints)
        if group.subgroups or not joints:
            continue
        gripper = group.name in ee_groups
        kind = GRIPPER_COMMAND if gripper else FOLLOW_JOINT_TRAJECTORY
        action_ns = DRIVER_ACTION_NS.get((model.target, kind), FOLLOW_JOINT_TRAJECTORY_NS)
        joints = joints[:1] if gripper else joints
        out.append(Controller(f"{group.name}_controller", kind, action_ns, joints, group.name))
    return tuple(out)


# -- SPEC merge ----------------------------------------------------------------------------------


def merge_spec(base: dict, spec: dict) -> dict:
    """Overlay a partial SPEC on an inferred setup (both as YAML dicts).

    Mappings merge key by key; lists of named items (name / group / joint) merge by that key,
    a SPEC item replacing the inferred one of the same key and new items appended; any other
    value in the SPEC replaces the inferred one.
    """
    out = dict(base)
    for key, value in spec.items():
        old = out.get(key)
        if isinstance(old, dict) and isinstance(value, dict):
            out[key] = merge_spec(old, value)
        elif isinstance(old, list) and isinstance(value, list):
            out[key] = _merge_items(old, value)
        else:
            out[key] = value
    return out


def _item_key(item) -> str | None:
    if isinstance(item, dict):
        for key in ITEM_KEYS:
            if isinstance(item.get(key), str):
                return f"{key}={item[key]}"
    return None


def _merge_items(old: list, new: list) -> list:
    """Inferred items in place, replaced by the SPEC's of the same key; the SPEC's others appended
    (duplicates in the SPEC are kept, so the model checks report them)."""
    if not all(_item_key(i) is not None for i in (*old, *new)):
        return new
    first_new: dict[str | None, int] = {}
    for index, item in enumerate(new):
        first_new.setdefault(_item_key(item), index)
    used = {first_new[_item_key(o)] for o in old if _item_key(o) in first_new}
    out = [new[first_new[_item_key(o)]] if _item_key(o) in first_new else o for o in old]
    return out + [item for index, item in enumerate(new) if index not in used]


def describe_setup(model: SetupModel) -> list[str]:
    """Human lines saying what a setup holds (for `init` to print)."""
    lines = []
    for g in model.groups:
        parts = [f"chain {g.chain.base} -> {g.chain.tip}"] if g.chain else []
        parts += [f"joints {', '.join(g.joints)}"] if g.joints else []
        parts += [f"links {', '.join(g.links)}"] if g.links else []
        parts += [f"subgroups {', '.join(g.subgroups)}"] if g.subgroups else []
        lines.append(f"group {g.name}: {'; '.join(parts)}")
    for s in model.group_states:
        values = ", ".join(f"{j}={v:g}" for j, v in s.values)
        lines.append(f"pose {s.name} ({s.group}): {values}")
    for ee in model.end_effectors:
        lines.append(f"end effector {ee.name}: group {ee.group}, parent link {ee.parent_link}")
    for vj in model.virtual_joints:
        lines.append(f"virtual joint {vj.name}: {vj.type} {vj.parent_frame} -> {vj.child_link}")
    for c in model.controllers:
        lines.append(f"controller {c.name}/{c.action_ns} ({c.type}): {', '.join(c.joints)}")
    for k in model.kinematics:
        lines.append(
            f"kinematics {k.group}: {k.solver} (resolution {k.search_resolution}, timeout {k.timeout})"
        )
    return lines
