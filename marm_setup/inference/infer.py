"""Infer a setup for `init` (DESIGN.md §2) for any kinematic tree, and merge a partial SPEC over it.

The limbs come from `inference.limbs`: a chain group per limb (arms to their tool frame), a hand
group (actuated joints after the wrist, with the links they move) and an end effector per arm
with a hand, composite groups (`arms`, `legs`, `whole_body`) where there are several limbs, and
a virtual joint that fits the base: none when the root is `world`, floating for a flying
(rotors, names) or legged base, planar for a wheeled one, else fixed to `world`. Poses here are zeros clamped into the limits;
`inference.poses` makes them collision-free once the collision matrix is known.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Collection

from marm_setup.errors import InputError
from marm_setup.inference.limbs import Limbs, find_limbs
from marm_setup.moveit_params import DEFAULT_ACTION_NS, FOLLOW_JOINT_TRAJECTORY, GRIPPER_COMMAND
from marm_setup.robot import RobotModel, tokens
from marm_setup.ros import Target
from marm_setup.setup import (
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
    active_group_joints,
    groups_by_name,
    is_chain,
)

HOME = "home"
REFERENCE = "docs/setup-file.md"
COMPOSITES = (("arms", "arm"), ("legs", "leg"))
FLYING_WORDS = (
    "drone", "quadrotor", "quadcopter", "hexacopter", "octocopter", "multirotor", "multicopter",
    "copter", "uav", "aerial", "flying", "hexarotor",
)  # fmt: skip


@dataclasses.dataclass(frozen=True, slots=True)
class Inference:
    """An inferred setup and what was guessed on the way (one line each)."""

    model: SetupModel
    notes: tuple[str, ...] = ()


def infer_setup(
    robot: RobotModel,
    *,
    package_name: str,
    source: RobotSource,
    target: Target = Target.ROS2,
    arm_required: bool = True,
    driver: str | None = None,
) -> Inference:
    """A complete setup for `robot` (collision matrix left empty: `init` computes it) and the
    guesses made on the way. Nothing that moves is an InputError when
    `arm_required` (a SPEC or SRDF may give the groups instead)."""
    limbs = find_limbs(robot)
    groups, end_effectors = _groups(limbs)
    vjoints, base_note = _virtual_joints(robot, limbs)
    model = SetupModel(
        package_name=package_name,
        robot_name=robot.name,
        robot=source,
        target=target,
        driver=driver,
        virtual_joints=vjoints,
        groups=groups,
        end_effectors=end_effectors,
    )
    if not groups:
        if arm_required:
            raise InputError(
                f"no actuated joints that form a limb: nothing to plan for (give the groups in a SPEC: see {REFERENCE})",
                path=robot.source,
            )
        return Inference(model)
    model = dataclasses.replace(model, group_states=home_poses(model, robot))
    notes = [*limbs.notes, *([base_note] if base_note else []), *_left_out(limbs)]
    if notes:
        notes.append(f"to change any of this, give a SPEC with --setup (see {REFERENCE})")
    return Inference(derive_group_settings(model, robot), tuple(notes))


def _groups(limbs: Limbs) -> tuple[tuple[Group, ...], tuple[EndEffector, ...]]:
    """A chain group per limb, a hand group per hand, composites; end effectors on hands."""
    groups: list[Group] = []
    ees: list[EndEffector] = []
    for limb in limbs.limbs:
        groups.append(Group(limb.name, chain=Chain(limb.base, limb.tip)))
        if limb.hand is not None:
            groups.append(Group(limb.hand.name, joints=limb.hand.joints, links=limb.hand.links))
            ees.append(EndEffector(limb.hand.name, limb.hand.name, limb.tip, limb.name))
    groups += [Group(h.name, joints=h.joints, links=h.links) for h in limbs.hands]
    for name, kind in COMPOSITES:
        members = tuple(limb.name for limb in limbs.limbs if limb.kind == kind)
        if len(members) > 1:
            groups.append(Group(name, subgroups=members))
    if len(limbs.limbs) > 1:
        groups.append(Group("whole_body", subgroups=tuple(limb.name for limb in limbs.limbs)))
    return tuple(groups), tuple(ees)


def _virtual_joints(robot: RobotModel, limbs: Limbs) -> tuple[tuple[VirtualJoint, ...], str]:
    """(virtual joints, a note on the choice): none when the root is `world`; floating for a
    flying or legged base, planar for a wheeled one, else fixed to `world`."""
    if robot.root.lower() == "world":
        return (), ""
    legs = sum(limb.kind == "leg" for limb in limbs.limbs)
    floating = (VirtualJoint("virtual_joint", "floating", "odom", robot.root),)
    if flying := _flying(robot, limbs):
        return floating, f"guessed: a flying base ({flying}): floating virtual joint odom -> {robot.root}"
    if legs > 1:
        return floating, f"guessed: a legged base ({legs} legs): floating virtual joint odom -> {robot.root}"
    if limbs.wheels:
        note = f"guessed: a wheeled base ({len(limbs.wheels)} wheel joints): planar virtual joint odom -> {robot.root}"
        return (VirtualJoint("virtual_joint", "planar", "odom", robot.root),), note
    return (VirtualJoint("virtual_joint", "fixed", "world", robot.root),), ""


def _flying(robot: RobotModel, limbs: Limbs) -> str:
    """Why the base flies ('' when it does not): rotor joints, or names that say so."""
    if limbs.rotors:
        return f"{len(limbs.rotors)} rotor joints"
    names = (robot.name, *(link.name for link in robot.links))
    words = sorted({t for n in names for t in tokens(n)} & set(FLYING_WORDS))
    return f"named '{words[0]}'" if words else ""


def _left_out(limbs: Limbs) -> list[str]:
    out = []
    if limbs.wheels:
        out.append(f"left out of every group: wheel joints {', '.join(limbs.wheels)}")
    if limbs.rotors:
        out.append(f"left out of every group: rotor joints {', '.join(limbs.rotors)}")
    if limbs.skipped:
        out.append(f"left out of every group: single joints {', '.join(limbs.skipped)} (not a limb)")
    return out


def home_poses(model: SetupModel, robot: RobotModel) -> tuple[GroupState, ...]:
    """`home` for every group without subgroups: zero for each active joint, kept off its limits
    as `inference.poses.home_value` says (an end effector's group only within them)."""
    from marm_setup.inference.poses import home_value

    by_name = groups_by_name(model.groups)
    hands = {ee.group for ee in model.end_effectors}
    out = []
    for group in by_name.values():  # one pose per name (duplicate groups are the checks' to report)
        joints = active_group_joints(group, by_name, robot, model.passive_joints)
        if joints and not group.subgroups:
            values = tuple(
                (j, home_value(robot.joint(j).bounds, at_limits=group.name in hands)) for j in joints
            )
            out.append(GroupState(HOME, group.name, values))
    return tuple(out)


def fill_group_settings(model: SetupModel, robot: RobotModel) -> SetupModel:
    """`derive_group_settings` for the lists (controllers, kinematics, ...) the setup left empty."""
    derived = derive_group_settings(model, robot)
    names = ("controllers", "kinematics", "planners", "arbotix_joints")
    return dataclasses.replace(model, **{n: getattr(model, n) or getattr(derived, n) for n in names})


def derive_group_settings(model: SetupModel, robot: RobotModel) -> SetupModel:
    """Controllers, KDL kinematics, planner defaults (and ArbotiX ids when it is the driver)."""
    controllers = _controllers(model, robot)
    groups = groups_by_name(model.groups).values()  # one each (duplicates are the checks' to report)
    # KDL only where MoveIt's KDL plugin initialises: a chain in JointModelGroup's sense (a
    # <chain> element can name a tree: up from the tip to the common root and down to the base)
    by_name = groups_by_name(model.groups)
    kinematics = tuple(
        Kinematics(g.name)
        for g in groups
        if g.chain is not None and is_chain(g, by_name, robot, model.passive_joints)
    )
    planners = tuple(PlannerDefaults(g.name) for g in groups)
    arbotix: tuple[ArbotixJoint, ...] = ()
    if model.target == Target.ROS1 and model.driver == "arbotix":
        joints = [j for c in controllers for j in c.joints]
        arbotix = tuple(ArbotixJoint(j, i) for i, j in enumerate(joints, start=1))
    return dataclasses.replace(
        model, controllers=controllers, kinematics=kinematics, planners=planners, arbotix_joints=arbotix
    )


def _controllers(model: SetupModel, robot: RobotModel) -> tuple[Controller, ...]:
    """One controller per group without subgroups, each joint in one controller only.

    GripperCommand for an end-effector group that commands one joint (others mimic it): the
    gripper action moves one joint; any other group gets a FollowJointTrajectory controller.
    A group whose joints are all taken by earlier groups gets none.
    """
    by_name = groups_by_name(model.groups)
    ee_groups = {ee.group for ee in model.end_effectors}
    taken: set[str] = set()
    out = []
    for group in by_name.values():  # one per name (duplicate groups are the checks' to report)
        joints = active_group_joints(group, by_name, robot, model.passive_joints)
        joints = tuple(j for j in joints if j not in taken)
        if group.subgroups and not (group.joints or group.chain or group.links) or not joints:
            continue
        kind = GRIPPER_COMMAND if group.name in ee_groups and len(joints) == 1 else FOLLOW_JOINT_TRAJECTORY
        action_ns = model.served_action_ns(kind) or DEFAULT_ACTION_NS[kind]
        taken.update(joints)
        out.append(Controller(f"{group.name}_controller", kind, action_ns, joints, group.name))
    return tuple(out)


# -- SPEC merge ----------------------------------------------------------------------------------

DERIVED_LISTS = ("controllers", "kinematics", "planners", "arbotix_joints")


def fit_to_spec(model: SetupModel, robot: RobotModel, keys: Collection[str]) -> SetupModel:
    """A merged setup made whole (`inference.spec_overlay.without_replaced` has taken out what the
    SPEC replaced): the lists the SPEC's `keys` do not name (controllers, kinematics, ...)
    derived again for the final groups."""
    derived = derive_group_settings(model, robot)
    return dataclasses.replace(model, **{n: getattr(derived, n) for n in DERIVED_LISTS if n not in keys})


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
