"""Find a robot's limbs (DESIGN.md §2): serial chains of actuated joints between branch points
and tips, what each one is (arm, leg, head, torso, hand, wheel) and what to call it.

Pure tree analysis of a RobotModel. The words that name a limb's kind come from the joint and
link names (`r_shoulder_pan_joint`, `LF_HFE`, `arm_left_joint_1_s`); where names say nothing
the structure decides (a chain with limbs after it is a torso, one with a hand is an arm) and
the guess is reported in `Limbs.notes`.
"""

from __future__ import annotations

import re
from collections import Counter
from dataclasses import dataclass, field

from marm_setup.robot.model import Joint, RobotModel

KIND_WORDS = {
    "hand": ("finger", "gripper", "hand", "thumb", "knuckle", "jaw", "claw", "palm", "robotiq", "pinch"),
    "wheel": ("wheel", "caster", "castor"),
    "leg": ("leg", "hip", "thigh", "shank", "knee", "calf", "ankle", "foot", "haa", "hfe", "kfe", "tibia"),
    "head": ("head", "neck", "gaze"),
    "torso": ("torso", "waist", "chest", "trunk", "spine", "pelvis"),
    "arm": ("arm", "shoulder", "elbow", "wrist", "forearm", "manipulator"),
}
SIDES = {"l": "left", "left": "left", "r": "right", "right": "right"}
CORNERS = {"f": "front", "h": "hind", "b": "back", "r": "rear"}
TOOL_WORDS = ("tool", "tcp", "grasp", "grasping", "end", "effector", "ee", "flange", "tip")
MIN_LIMB_JOINTS = 2  # fewer, and no name that says what it is: a sensor mount, not a limb
MIN_ARM_JOINTS = 3  # an unnamed leaf chain with this many joints is taken for an arm
MAX_FINGER_JOINTS = 3  # unnamed leaf chains after an arm with at most this many: its fingers


@dataclass(frozen=True, slots=True)
class Hand:
    """Actuated joints (mimic included) after an arm's last joint, and the links they move."""

    name: str
    joints: tuple[str, ...]
    links: tuple[str, ...]
    active: tuple[str, ...]


@dataclass(frozen=True, slots=True)
class Limb:
    """A serial chain of actuated joints: chain `base` -> `tip`, its active joints in order."""

    name: str
    kind: str  # arm | leg | head | torso | chain
    base: str
    tip: str
    joints: tuple[str, ...]
    hand: Hand | None = None


@dataclass(frozen=True, slots=True)
class Limbs:
    limbs: tuple[Limb, ...] = ()
    hands: tuple[Hand, ...] = ()  # hands on no arm (a robot that is only a gripper)
    wheels: tuple[str, ...] = ()
    skipped: tuple[str, ...] = ()  # single unnamed joints left out of every group
    notes: tuple[str, ...] = ()


@dataclass
class _Segment:
    """Joints from a branch point (or the root) to the next branch point or tip."""

    start: str
    joints: list[Joint]
    children: list[_Segment] = field(default_factory=list)

    @property
    def end(self) -> str:
        return self.joints[-1].child

    @property
    def active(self) -> list[Joint]:
        return [j for j in self.joints if j.is_active]

    def subtree_active(self) -> int:
        return len(self.active) + sum(c.subtree_active() for c in self.children)


def tokens(name: str) -> list[str]:
    """`LArmShoulder_pitch2` -> ['l', 'arm', 'shoulder', 'pitch', '2'] (lowercase)."""
    parts = re.findall(r"[A-Z]+(?=[A-Z][a-z]|\b|_|\d|$)|[A-Z]?[a-z]+|[A-Z]+|\d+", name)
    return [p.lower() for p in parts]


def _words(joints: list[Joint]) -> list[str]:
    return [t for j in joints for name in (j.name, j.child) for t in tokens(name)]


def _kind_votes(joints: list[Joint]) -> Counter:
    words = _words(joints)
    return Counter({kind: sum(w in vocab for w in words) for kind, vocab in KIND_WORDS.items()})


def _is_kind(joints: list[Joint], kind: str) -> bool:
    """Every active joint's name or child link has a word of `kind`."""
    active = [j for j in joints if j.is_active] or joints
    return bool(active) and all(_kind_votes([j])[kind] for j in active)


def find_limbs(robot: RobotModel) -> Limbs:
    """The robot's limbs, hands, wheels, and what was guessed."""
    finder = _Finder(robot)
    for seg in _segments(robot, robot.root, _moving(robot)):
        finder.visit(seg)
    return finder.result()


def _moving(robot: RobotModel) -> dict[str, bool]:
    """link -> whether an actuated joint (mimic included) is below it."""
    out: dict[str, bool] = {}
    for link in reversed(robot.links_in_tree_order):
        out[link] = any(j.is_actuated or out[j.child] for j in robot.child_joints_of[link])
    return out


def _segments(robot: RobotModel, link: str, moving: dict[str, bool]) -> list[_Segment]:
    """The segments starting at `link`; a segment without an active joint is looked through."""
    out: list[_Segment] = []
    for first in robot.child_joints_of[link]:
        if not (first.is_actuated or moving[first.child]):
            continue
        seg = _Segment(link, [first])
        while True:
            kids = [j for j in robot.child_joints_of[seg.end] if j.is_actuated or moving[j.child]]
            if len(kids) != 1:
                break
            seg.joints.append(kids[0])
        seg.children = _segments(robot, seg.end, moving)
        out.extend([seg] if seg.active else seg.children)
    return out


@dataclass
class _RawLimb:
    kind: str
    base: str
    joints: list[Joint]  # up to the limb's last active joint
    has_hand: bool


class _Finder:
    """Walks the segment tree, sorting segments into limbs, hands and wheels."""

    def __init__(self, robot: RobotModel):
        self.robot = robot
        self.raw: list[_RawLimb] = []
        self.loose_hands: list[_Segment] = []
        self.wheels: list[str] = []
        self.skipped: list[str] = []
        self.skipped_raw: list[_RawLimb] = []
        self.notes: list[str] = []

    def visit(self, seg: _Segment) -> None:
        if _is_kind(seg.joints, "wheel"):
            self.wheels += [j.name for s in _flatten(seg) for j in s.active]
        elif _is_kind(seg.joints, "hand"):
            self.loose_hands.append(seg)
        else:
            seg = self._split_torso(seg)
            own, tail = _split_hand(seg.joints)
            if tail or self._ends_in_fingers(seg, own):
                self.raw.append(_RawLimb("arm", seg.start, own, True))
                return
            self._add_limb(seg, own)
            for child in seg.children:
                self.visit(child)

    def _split_torso(self, seg: _Segment) -> _Segment:
        """Leading torso-named joints (`torso_lift_joint` before an arm) become a torso limb; the
        rest of the segment starts after them."""
        active = [i for i, j in enumerate(seg.joints) if j.is_active]
        lead = 0
        while lead < len(active) and _is_kind([seg.joints[active[lead]]], "torso"):
            lead += 1
        if lead == 0 or lead == len(active):
            return seg
        cut = active[lead - 1] + 1
        self.raw.append(_RawLimb("torso", seg.start, seg.joints[:cut], False))
        return _Segment(seg.joints[cut - 1].child, seg.joints[cut:], seg.children)

    def _ends_in_fingers(self, seg: _Segment, own: list[Joint]) -> bool:
        """Every chain after `seg` is a finger: named so, or (a guess) short unnamed leaves."""
        kids = seg.children
        if not kids:
            return False
        if all(_is_kind(c.joints, "hand") for c in kids):
            return True
        short = all(not c.children and len(c.active) <= MAX_FINGER_JOINTS for c in kids)
        if short and sum(j.is_active for j in own) > MAX_FINGER_JOINTS and _votes_for(own) != "leg":
            names = ", ".join(j.name for c in kids for j in c.active)
            self.notes.append(f"guessed: {names} (short chains after {seg.end}) are the fingers of a hand")
            return True
        return False

    def _add_limb(self, seg: _Segment, own: list[Joint]) -> None:
        active = [j for j in own if j.is_active]
        limb_kids = [c for c in seg.children if not _is_kind(c.joints, "wheel")]
        moved = self.robot.subtree_links(active[0].child)
        if not limb_kids and not any(self.robot.link(x).has_geometry for x in moved):
            self._skip(seg, own)  # a transmission or sensor frame: moves nothing visible
            return
        kind = _votes_for(own) or ("torso" if limb_kids else "")
        names = ", ".join(j.name for j in active)
        if not kind and len(active) >= MIN_ARM_JOINTS:
            kind = "arm"
            self.notes.append(f"guessed: {names} form an arm (no arm/leg/head naming, no hand)")
        elif not kind and len(active) >= MIN_LIMB_JOINTS:
            kind = "chain"
            self.notes.append(f"guessed: {names} form a chain of unknown kind")
        elif not kind:
            self._skip(seg, own)
            return
        self.raw.append(_RawLimb(kind, seg.start, own, False))

    def _skip(self, seg: _Segment, own: list[Joint]) -> None:
        self.skipped += [j.name for j in own if j.is_active]
        self.skipped_raw.append(_RawLimb("chain", seg.start, own, False))

    def result(self) -> Limbs:
        if not self.raw and not self.loose_hands and self.skipped:  # nothing but small chains
            self.notes.append(f"guessed: {', '.join(self.skipped)} are limbs (nothing else moves)")
            self.raw, self.skipped = self.skipped_raw, []
        names = _limb_names(self.raw)
        limbs = tuple(self._limb(raw, name) for raw, name in zip(self.raw, names, strict=True))
        hands = tuple(self._loose_hand(seg, len(self.loose_hands)) for seg in self.loose_hands)
        return Limbs(limbs, hands, tuple(self.wheels), tuple(self.skipped), tuple(self.notes))

    def _limb(self, raw: _RawLimb, name: str) -> Limb:
        last = raw.joints[-1].child
        tip = last if raw.kind == "torso" else tool_frame(self.robot, last)
        active = tuple(j.name for j in raw.joints if j.is_active)
        hand = self._hand(name, last, tip) if raw.has_hand else None
        return Limb(name, raw.kind, raw.base, tip, active, hand)

    def _hand(self, arm: str, last: str, tip: str) -> Hand:
        robot = self.robot
        arm_links = {j.child for j in robot.chain(last, tip) or ()} | {last}
        joints = [j for j in robot.subtree_joints(last) if j.is_actuated]
        links = tuple(link for link in robot.subtree_links(last) if link not in arm_links)
        word = _hand_word(joints)
        parts = tokens(arm)
        name = "_".join(word if t == "arm" else t for t in parts) if "arm" in parts else f"{arm}_{word}"
        name = word if arm == "arm" else name
        return Hand(name, tuple(j.name for j in joints), links, tuple(j.name for j in joints if j.is_active))

    def _loose_hand(self, seg: _Segment, count: int) -> Hand:
        joints = [j for s in _flatten(seg) for j in s.joints if j.is_actuated]
        links = (seg.joints[0].child, *(j.child for s in _flatten(seg) for j in s.joints))
        word = _hand_word(joints)
        name = word if count == 1 else f"{word}_{self.loose_hands.index(seg) + 1}"
        active = tuple(j.name for j in joints if j.is_active)
        return Hand(name, tuple(j.name for j in joints), tuple(dict.fromkeys(links)), active)


def _hand_word(joints: list[Joint]) -> str:
    words = _words(joints)
    return "gripper" if words.count("gripper") + words.count("robotiq") > words.count("hand") else "hand"


def _limb_names(raw: list[_RawLimb]) -> list[str]:
    """A name per limb from the robot's own naming (see `_limb_name`), made unique."""
    kinds = Counter(r.kind for r in raw)
    numbers: Counter = Counter()
    out: list[str] = []
    for r in raw:
        numbers[r.kind] += 1
        name = _limb_name(r, kinds[r.kind] == 1, numbers[r.kind])
        while name in out:
            name = f"{name}_{numbers[r.kind]}"
        out.append(name)
    return out


def _limb_name(raw: _RawLimb, unique: bool, number: int) -> str:
    """`arm` when the robot has one; else the joints' common prefix when it names the kind
    (`arm_left`), a side (`right_arm`, `front_left_leg`), the prefix itself (`panda_1`), `arm_2`."""
    if raw.kind == "chain":
        return f"chain_{number}"
    if unique:
        return raw.kind
    prefix = common_prefix([j.name for j in raw.joints if j.is_active])
    if any(t in KIND_WORDS[raw.kind] for t in prefix):
        return "_".join(prefix)
    side = _side(prefix)
    if side:
        return f"{side}_{raw.kind}"
    return "_".join(prefix) if prefix else f"{raw.kind}_{number}"


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


def _side(prefix: list[str]) -> str:
    """`left` / `right` / `front_left` ... from prefix tokens (`l`, `right`, `FL`, `LH`)."""
    for t in prefix:
        if t in SIDES:
            return SIDES[t]
        if len(t) == 2 and {t[0], t[1]} & set("lr") and {t[0], t[1]} & set(CORNERS):
            a, b = t[0], t[1]
            names = [SIDES.get(c) or CORNERS[c] for c in (a, b)]
            if a in "lr" and b in CORNERS and b != "r":
                return f"{CORNERS[b]}_{SIDES[a]}"
            return "_".join(names)
    return ""


def _votes_for(joints: list[Joint]) -> str:
    """The limb kind the names vote for (arm, leg, head, torso), or '' when they say nothing."""
    votes = _kind_votes(joints)
    best = max(("arm", "leg", "head", "torso"), key=lambda k: votes[k])
    return best if votes[best] else ""


def _split_hand(joints: list[Joint]) -> tuple[list[Joint], list[Joint]]:
    """(limb joints, trailing hand-named joints) of a segment that does not start as a hand."""
    last = max((i for i, j in enumerate(joints) if j.is_active and not _kind_votes([j])["hand"]), default=-1)
    return joints[: last + 1], joints[last + 1 :]


def _flatten(seg: _Segment) -> list[_Segment]:
    return [seg, *(s for c in seg.children for s in _flatten(c))]


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
