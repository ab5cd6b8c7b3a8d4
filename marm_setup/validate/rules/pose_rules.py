"""Named poses (`group_state`) collision-free, and ros2_control's initial positions.

A pose's values (group, joints, limits) are checked by the shared rules in `setup.rules`.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING

from marm_setup.findings import Evidence, Finding, error, warning
from marm_setup.package import InitialPositions
from marm_setup.robot import RobotModel
from marm_setup.setup import (
    allowed_pairs,
    group_joints,
    groups_by_name,
    pose_configuration,
    start_configuration,
)

if TYPE_CHECKING:
    from marm_setup.collision import CollisionScene
    from marm_setup.setup import Srdf


def check_pose_collisions(
    srdf: Srdf, robot: RobotModel, scene: CollisionScene, file: str, base: Mapping[str, float] | None = None
) -> list[Finding]:
    """Each pose, other joints at `base` (the package's initial state) or their defaults, is free
    of the collisions MoveIt would check.

    Only pairs whose relative pose the group's joints change count: a hand pose is not blamed
    for where the arm happens to be.
    """
    by_name = groups_by_name(srdf.groups)
    states = [
        s for s in srdf.group_states if s.group in by_name and all(j in robot.joint_map for j, _ in s.values)
    ]
    pairs = scene.enabled_pairs(allowed_pairs(srdf, scene.candidate_pairs))
    if not states or not pairs:
        return []
    out = []
    for state in states:
        moved = {j for j in group_joints(by_name[state.group], by_name, robot) if robot.joint(j).is_actuated}
        mine = [p for p in pairs if _moves_pair(p, moved, robot)]
        q = pose_configuration(state, robot, base)
        hit = scene.first_collisions(q[None], mine)[0] if mine else None
        if hit is not None:
            out.append(
                error(
                    "pose.collision",
                    file,
                    f"group_state[{state.name}]",
                    f"in collision: {hit[0]} - {hit[1]}{_context(base)}",
                    hint="move the pose, or disable the pair if the contact is intended",
                    evidence=Evidence.of(hit, robot.active_joint_names, q),
                )
            )
    return out


def _moves_pair(pair: tuple[str, str], moved: set[str], robot: RobotModel) -> bool:
    """Some joint in `moved` lies between the two links (changes their relative pose)."""
    up_a = {j.name for j in robot.path_to_root(pair[0])}
    up_b = {j.name for j in robot.path_to_root(pair[1])}
    return bool((up_a ^ up_b) & moved)


def _context(base: Mapping[str, float] | None) -> str:
    return " (other joints at the initial state)" if base else " (other joints at their default values)"


def check_initial_positions(positions: InitialPositions, robot: RobotModel) -> list[Finding]:
    """ros2_control's `initial_positions.yaml`: known joints, numbers, inside the limits."""
    file = positions.where.file
    if positions.values is None:
        return [error("pose.initial-malformed", file, positions.where.element, "expected a mapping")]
    out = []
    for param in sorted(positions.values, key=lambda p: p.key):
        joint, value, where = param.key, param.value, param.where.element
        if joint not in robot.joint_map:
            msg = f"unknown joint '{joint}': no joint reads this value"
            out.append(warning("pose.initial-unknown-joint", file, where, msg))
        elif isinstance(value, bool) or not isinstance(value, (int, float)):
            out.append(error("pose.initial-malformed", file, where, f"not a number: {value!r}"))
        elif not robot.joint(joint).within_limits(value):
            lo, hi = robot.joint(joint).bounds
            msg = f"initial position {value:g} is outside the limits [{lo:g}, {hi:g}]"
            out.append(error("pose.initial-out-of-limits", file, where, msg))
    return out


def check_start_state(
    srdf: Srdf, robot: RobotModel, scene: CollisionScene, file: str, base: Mapping[str, float]
) -> list[Finding]:
    """The demo's start state (`base` over the defaults) is free of the collisions MoveIt checks:
    MoveIt 2's CheckStartStateCollision adapter refuses every plan from a state in collision
    (default_planning_request_adapters, check_start_state_collision.cpp), MoveIt 1's
    FixStartStateCollision only tries small random moves of it."""

    if not base:
        return []
    pairs = scene.enabled_pairs(allowed_pairs(srdf, scene.candidate_pairs))
    # a pair touching at the default state too is the collision matrix's problem, not the start's
    default = start_configuration(robot)[None]
    while pairs and (touching := scene.first_collisions(default, pairs)[0]) is not None:
        pairs = tuple(p for p in pairs if p != touching)
    q = start_configuration(robot, base)
    hit = scene.first_collisions(q[None], pairs)[0] if pairs else None
    if hit is None:
        return []
    msg = f"the demo starts in collision: {hit[0]} - {hit[1]}; MoveIt refuses to plan from it"
    hint = "start at a collision-free named pose"
    evidence = Evidence.of(hit, robot.active_joint_names, q)
    return [error("pose.start-collision", file, "initial state", msg, hint, evidence)]
