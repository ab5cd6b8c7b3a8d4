"""Where a limb ends: an arm at its tool frame (fixed, geometry-less frames after its last
link), a leg at its foot (a sole, foot or toe frame fixed to it), a torso at its last link."""

from __future__ import annotations

from marm_setup.robot.model import RobotModel
from marm_setup.setup.limb_words import FOOT_WORDS, MOUNT_WORDS, TOOL_WORDS, tokens


def limb_tip(robot: RobotModel, kind: str, last: str) -> str:
    """Where a limb of `kind` whose last joint moves `last` ends: a torso there, a leg at its foot,
    any other at its tool frame."""
    if kind == "torso":
        return last
    return foot_frame(robot, last) if kind == "leg" else tool_frame(robot, last)


def tool_frame(robot: RobotModel, link: str) -> str:
    """`link` extended through fixed joints to geometry-less frames: the only such child, or
    the one named like a tool frame (`tool0`, `tcp`, `grasping_frame`, `end_effector`)."""
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
