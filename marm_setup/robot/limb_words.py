"""The words a limb's kind and name are read from: tokens of joint and link names, what each
word says (arm, leg, head, torso, hand, wheel, rotor), sides and corners (`l`, `FR`, `LH`).
A joint's own name counts before its child link's (`l_wrist_yaw` moving `l_hand` is the arm's)."""

from __future__ import annotations

import re
from collections import Counter

from marm_setup.robot import Joint

KIND_WORDS = {
    "hand": ("finger", "gripper", "hand", "thumb", "knuckle", "jaw", "claw", "palm", "robotiq", "pinch"),
    "wheel": ("wheel", "caster", "castor"),
    "rotor": ("rotor", "propeller", "prop"),
    "leg": ("leg", "hip", "thigh", "shank", "knee", "calf", "ankle", "foot", "haa", "hfe", "kfe", "tibia"),
    "head": ("head", "neck", "gaze"),
    "torso": ("torso", "waist", "chest", "trunk", "spine", "pelvis"),
    "arm": ("arm", "shoulder", "elbow", "wrist", "forearm", "manipulator"),
}
LIMB_KINDS = ("arm", "leg", "head", "torso")
BASE_KINDS = ("wheel", "rotor")  # joints of the base itself: never in a planning group
# A joint named so is a hand joint whatever else its name says; `gripper_yaw`, `hand_roll`
# without one of these turn the hand: they are the wrist's.
FINGER_WORDS = ("finger", "thumb", "knuckle", "jaw", "claw", "pinch", "robotiq")
TURN_WORDS = ("wrist", "yaw", "roll", "pitch", "rotate", "rotation", "twist")
# Sensors and transmissions: what a short chain without collision geometry moves when it is no limb
MOUNT_WORDS = (
    "camera", "cam", "laser", "lidar", "imu", "sensor", "sonar", "kinect", "xtion", "realsense", "hokuyo",
    "velodyne", "rgbd", "depth", "optical", "ft", "fsr", "motor", "screw", "transmission", "gear", "belt",
)  # fmt: skip
# Sensors that see (their bodies on a hand are not the hand: a grasped object may not touch them)
VISION_WORDS = (
    "camera", "cam", "kinect", "xtion", "realsense", "rgbd", "depth", "optical", "laser", "lidar", "hokuyo",
    "velodyne", "sonar",
)  # fmt: skip
FOOT_WORDS = ("sole", "foot", "toe")  # a leg's tip frame, in this order of preference
SIDES = {"l": "left", "left": "left", "r": "right", "right": "right"}
CORNERS = {"f": "front", "h": "hind", "b": "back", "r": "rear"}
TOOL_WORDS = ("tool", "tcp", "grasp", "grasping", "end", "effector", "ee", "flange", "tip", "gripper")
# An arm's tool frame by its name, best first: the grasp point, the tool / end effector frame,
# a gripper frame (a gripper's body is the hand), the flange (limb_tips.tool_frame)
TOOL_RANKS = (
    ("tcp", "grasp", "grasping", "grasptarget"),
    ("tool", "tool0", "effector", "ee", "eef", "tip"),
    ("gripper",),
    ("flange",),
)


def tokens(name: str) -> list[str]:
    """`LArmShoulder_pitch2` -> ['l', 'arm', 'shoulder', 'pitch', '2'] (lowercase)."""
    parts = re.findall(r"[A-Z]+(?=[A-Z][a-z]|\b|_|\d|$)|[A-Z]?[a-z]+|[A-Z]+|\d+", name)
    return [p.lower() for p in parts]


def name_words(joints: list[Joint]) -> list[str]:
    return [t for j in joints for name in (j.name, j.child) for t in tokens(name)]


def kind_votes(joints: list[Joint]) -> Counter:
    words = name_words(joints)
    return Counter({kind: sum(w in vocab for w in words) for kind, vocab in KIND_WORDS.items()})


def name_kinds(name: str) -> set[str]:
    words = set(tokens(name))
    return {kind for kind, vocab in KIND_WORDS.items() if words & set(vocab)}


def joint_kinds(joint: Joint) -> set[str]:
    """The kinds a joint's own name says (a hand-named joint that turns, `gripper_yaw`, is the
    wrist's: arm), else those its child link's name says."""
    kinds = name_kinds(joint.name)
    words = set(tokens(joint.name))
    if "hand" in kinds and not words & set(FINGER_WORDS) and words & set(TURN_WORDS):
        kinds = (kinds - {"hand"}) | {"arm"}
    return kinds or name_kinds(joint.child)


def is_kind(joints: list[Joint], kind: str) -> bool:
    """Every active joint says `kind` (by its own name, else its child link's)."""
    active = [j for j in joints if j.is_active] or joints
    return bool(active) and all(kind in joint_kinds(j) for j in active)


def common_prefix(names: list[str]) -> list[str]:
    """The leading tokens all `names` share, without a trailing `joint`."""
    lists = [tokens(n) for n in names]
    out: list[str] = []
    for column in zip(*lists, strict=False):
        if len(set(column)) != 1:
            break
        out.append(column[0])
    while out and out[-1] in ("joint", "jnt", "j"):
        out.pop()
    return out


def side_of(prefix: list[str]) -> str:
    """`left` / `right` / `front_left` ... from prefix tokens: `l`, `right`, `rleg` (a side
    glued to a limb word), corner codes `FL`, `RR` (front/rear first, then the side) and `LF`,
    `RH` (the side first, then front/hind)."""
    for t in prefix:
        if t in SIDES:
            return SIDES[t]
        if len(t) > 2 and t[0] in "lr" and t[1:] in LIMB_KINDS:
            return SIDES[t[0]]
        if len(t) == 2 and t[1] in "lr" and t[0] in CORNERS:
            return f"{CORNERS[t[0]]}_{SIDES[t[1]]}"
        if len(t) == 2 and t[0] in "lr" and t[1] in CORNERS:
            return f"{CORNERS[t[1]]}_{SIDES[t[0]]}"
    return ""


def votes_for(joints: list[Joint]) -> str:
    """The limb kind the names vote for (arm, leg, head, torso), or '' when they say nothing."""
    votes = kind_votes(joints)
    best = max(LIMB_KINDS, key=lambda k: votes[k])
    return best if votes[best] else ""
