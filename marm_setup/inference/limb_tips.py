"""Where a limb ends: an arm at its tool frame (a TCP, tool or flange frame fixed below its last
link, past a hand's palm), a leg at its foot (a sole, foot or toe frame fixed to it), a torso at
its last link."""

from __future__ import annotations

from marm_setup.robot import FINGER_WORDS, FOOT_WORDS, MOUNT_WORDS, TOOL_RANKS, TOOL_WORDS, RobotModel, tokens


def limb_tip(robot: RobotModel, kind: str, last: str) -> str:
    """Where a limb of `kind` whose last joint moves `last` ends: a torso there, a leg at its foot,
    any other at its tool frame."""
    if kind == "torso":
        return last
    return foot_frame(robot, last) if kind == "leg" else tool_frame(robot, last)


def tool_frame(robot: RobotModel, link: str) -> str:
    """Where an arm whose last joint moves `link` ends: its tool frame, the best-named link
    fixed below it, through a hand's palm too (as MoveIt's panda_manipulator ends at
    panda_hand_tcp, past panda_hand): a TCP or grasp frame before a tool / end-effector frame
    before a gripper frame before a flange, then a frame without geometry before a link with
    it, the farthest first (Kinova's tool_frame, the TCP, below its end_effector_link); sensors
    and fingertips are none. Without one, the geometry-less
    frames fixed to `link` (the only one, or the one named like a tool frame: a flange)."""
    named = [
        (rank, robot.link(frame).has_geometry, -depth, order, frame)
        for order, (depth, frame) in enumerate(_fixed_frames(robot, link)[1:])
        if (rank := _tool_rank(robot, frame)) is not None
    ]
    return min(named)[-1] if named else _bare_frame(robot, link)


def _tool_rank(robot: RobotModel, frame: str) -> int | None:
    """How well `frame`'s name says tool frame (TOOL_RANKS, lower is better); None: not at all."""
    words = set(tokens(frame))
    if words & set(FINGER_WORDS) or words & set(MOUNT_WORDS):
        return None
    for rank, vocabulary in enumerate(TOOL_RANKS):
        if words & set(vocabulary):
            body = robot.link(frame).has_geometry and "gripper" in vocabulary  # the gripper itself
            return None if body else rank
    return None


def _bare_frame(robot: RobotModel, link: str) -> str:
    """`link` extended through fixed joints to geometry-less frames: the only such child, or
    the one named like a tool frame."""
    while True:
        frames = [
            j.child
            for j in robot.child_joints_of[link]
            if j.type == "fixed" and not robot.link(j.child).has_geometry
        ]
        named = [f for f in frames if set(tokens(f)) & set(TOOL_WORDS)]
        if len(frames) == 1:
            link = frames[0]
        elif named:
            link = named[0]
        else:
            return link


def foot_frame(robot: RobotModel, link: str) -> str:
    """A leg's tip: the sole, foot or toe frame fixed to `link` (or `link` itself), geometry or
    not, a sole before a foot before a toe and the nearest first; else `tool_frame`."""
    feet = [
        (rank, depth, order, frame)
        for order, (depth, frame) in enumerate(_fixed_frames(robot, link))
        if not set(tokens(frame)) & set(MOUNT_WORDS)
        for rank, word in enumerate(FOOT_WORDS)
        if word in tokens(frame)
    ]
    return min(feet)[-1] if feet else tool_frame(robot, link)


def _fixed_frames(robot: RobotModel, link: str) -> list[tuple[int, str]]:
    """(depth, frame) for `link` and every frame fixed to it, breadth first."""
    out = [(0, link)]
    for depth, frame in out:  # the list grows as it is read
        out += [(depth + 1, j.child) for j in robot.child_joints_of[frame] if j.type == "fixed"]
    return out
