"""Find a robot's limbs (DESIGN.md §2): serial chains of actuated joints between branch points
and tips, what each one is (arm, leg, head, torso, hand, wheel, rotor) and what to call it.

Pure tree analysis of a RobotModel. The words that name a limb's kind come from the joint and
link names (`r_shoulder_pan_joint`, `LF_HAA`, `arm_left_joint_1_s`), a joint's own name before
its child link's; where names say nothing the structure decides (a chain with limbs after it is
a torso, one with a hand is an arm, a long one is an arm) and the guess is reported in
`Limbs.notes`. Wheels (with what carries them) and rotors belong to the base, not to a limb.
"""

from __future__ import annotations

import math
from collections import Counter
from dataclasses import dataclass, field

from marm_setup.inference.limb_tips import limb_tip
from marm_setup.robot import (
    BASE_KINDS,
    KIND_WORDS,
    MOUNT_WORDS,
    VISION_WORDS,
    Joint,
    RobotModel,
    common_prefix,
    is_kind,
    joint_kinds,
    name_kinds,
    name_words,
    side_of,
    tokens,
    votes_for,
)

MIN_LIMB_JOINTS = 2  # fewer, and no name that says what it is: a sensor mount, not a limb
MIN_ARM_JOINTS = 3  # an unnamed leaf chain with this many joints is taken for an arm
MAX_FINGER_JOINTS = 3  # unnamed leaf chains after an arm with at most this many: its fingers
MAX_HAND_JOINTS = 5  # a bare hand's fingers have at most this many joints
MAX_WRIST_JOINTS = 2  # and the wrist before them at most this many
MAX_FINGER_LENGTH = 0.2  # [m] joint offsets along a finger after its first joint, at most


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
    hands: tuple[Hand, ...] = ()  # hands on no arm (a robot that is only a gripper or a hand)
    wheels: tuple[str, ...] = ()  # wheel joints and the joints that carry them (suspensions)
    rotors: tuple[str, ...] = ()  # rotor and propeller joints
    skipped: tuple[str, ...] = ()  # joints of short unnamed chains (sensor mounts) left out of every group
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


def _base_kind(seg: _Segment) -> str:
    """'wheel' or 'rotor' when `seg` belongs to the base: its joints wheels, rotors or unnamed
    (a suspension), with a wheel or rotor in it or in every chain after it; else ''."""
    kinds = [joint_kinds(j) for j in seg.active]
    if any(k - set(BASE_KINDS) for k in kinds):
        return ""
    below = [_base_kind(c) for c in seg.children]
    if not all(below):
        return ""
    found = [b for k in kinds for b in BASE_KINDS if b in k] + below
    return found[0] if found else ""


def find_limbs(robot: RobotModel) -> Limbs:
    """The robot's limbs, hands, wheels, rotors, and what was guessed."""
    finder = _Finder(robot)
    segments = _segments(robot, robot.root, _moving(robot))
    hand = _whole_hand(robot, segments)
    if hand:
        finder.notes.append(f"guessed: the robot is a hand ({hand}): one hand group")
        finder.loose_hands += segments
    for seg in [] if hand else segments:
        finder.visit(seg)
    return finder.result()


def _whole_hand(robot: RobotModel, segments: list[_Segment]) -> str:
    """Why the whole robot is one hand ('' when it is not): nothing but short chains (fingers,
    a wrist of at most two joints before them) named for no limb, and its name or its palm's
    says hand, or (a guess) three or more short fingers hang from one link."""
    flat = [s for seg in segments for s in _flatten(seg)]
    if not flat or any(votes_for(s.joints) or _base_kind(s) for s in flat):
        return ""
    most = [MAX_WRIST_JOINTS if s.children else MAX_HAND_JOINTS for s in flat]
    if any(len(s.active) > limit for s, limit in zip(flat, most, strict=True)):
        return ""
    named = [n for n in (robot.name, robot.root, *(s.start for s in flat)) if "hand" in name_kinds(n)]
    if named:
        return f"named {named[0]}"
    fingers = [s for s in flat if not s.children and _finger_length(s) <= MAX_FINGER_LENGTH]
    starts = Counter(s.start for s in fingers)
    if len(fingers) == sum(not s.children for s in flat) and max(starts.values(), default=0) >= 3:
        return f"{len(fingers)} short fingers"
    return ""


def _finger_length(seg: _Segment) -> float:
    """[m] the joint offsets along `seg` after its first joint (the finger's own length)."""
    return sum(math.dist((0.0, 0.0, 0.0), j.origin.xyz) for j in seg.joints[1:])


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
    """Walks the segment tree, sorting segments into limbs, hands, wheels and rotors."""

    def __init__(self, robot: RobotModel):
        self.robot = robot
        self.raw: list[_RawLimb] = []
        self.loose_hands: list[_Segment] = []
        self.base_joints: dict[str, list[str]] = {kind: [] for kind in BASE_KINDS}
        self.skipped: list[str] = []
        self.skipped_raw: list[_RawLimb] = []
        self.notes: list[str] = []

    def visit(self, seg: _Segment) -> None:
        base = _base_kind(seg)
        if base:
            self.base_joints[base] += [j.name for s in _flatten(seg) for j in s.active]
        elif is_kind(seg.joints, "hand"):
            self.loose_hands.append(seg)
        else:
            seg = self._split_wheel(self._split_torso(seg))
            own, tail = _split_tail(seg.joints, "hand")
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
        while lead < len(active) and is_kind([seg.joints[active[lead]]], "torso"):
            lead += 1
        if lead == 0 or lead == len(active):
            return seg
        cut = active[lead - 1] + 1
        self.raw.append(_RawLimb("torso", seg.start, seg.joints[:cut], False))
        return _Segment(seg.joints[cut - 1].child, seg.joints[cut:], seg.children)

    def _split_wheel(self, seg: _Segment) -> _Segment:
        """A limb that ends in wheels (a leg on a wheel): the wheel joints go to the base."""
        own, tail = _split_tail(seg.joints, "wheel")
        wheels = [j.name for j in tail if j.is_active]
        if not own or not wheels:
            return seg
        self.base_joints["wheel"] += wheels
        return _Segment(seg.start, own, seg.children)

    def _ends_in_fingers(self, seg: _Segment, own: list[Joint]) -> bool:
        """Every chain after `seg` is a finger: named so, or (a guess) short unnamed leaves."""
        kids = seg.children
        if not kids:
            return False
        if all(is_kind(c.joints, "hand") for c in kids):
            return True
        short = all(not c.children and len(c.active) <= MAX_FINGER_JOINTS for c in kids)
        if short and sum(j.is_active for j in own) > MAX_FINGER_JOINTS and votes_for(own) != "leg":
            names = ", ".join(j.name for c in kids for j in c.active)
            self.notes.append(f"guessed: {names} (short chains after {seg.end}) are the fingers of a hand")
            return True
        return False

    def _add_limb(self, seg: _Segment, own: list[Joint]) -> None:
        active = [j for j in own if j.is_active]
        limb_kids = [c for c in seg.children if not _base_kind(c)]
        if not limb_kids and not self._is_body_part(active):
            self._skip(seg, own)  # a transmission or sensor mount
            return
        kind = votes_for(own) or ("torso" if limb_kids else "")
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

    def _is_body_part(self, active: list[Joint]) -> bool:
        """A leaf chain is a limb when it moves collision geometry, has several joints, or its
        names say which limb it is and not a sensor or transmission (a camera's pan-tilt is no limb)."""
        if any(self.robot.link(x).has_geometry for x in self.robot.subtree_links(active[0].child)):
            return True
        if len(active) >= MIN_ARM_JOINTS:
            return True
        return bool(votes_for(active)) and not set(name_words(active)) & set(MOUNT_WORDS)

    def _skip(self, seg: _Segment, own: list[Joint]) -> None:
        self.skipped += [j.name for j in own if j.is_active]
        self.skipped_raw.append(_RawLimb("chain", seg.start, own, False))

    def result(self) -> Limbs:
        if not self.raw and not self.loose_hands and self.skipped:  # nothing but small chains
            self.notes.append(f"guessed: {', '.join(self.skipped)} are limbs (nothing else moves)")
            self.raw, self.skipped = self.skipped_raw, []
        names = _limb_names(self.raw)
        limbs = tuple(self._limb(raw, name) for raw, name in zip(self.raw, names, strict=True))
        wheels, rotors = (tuple(self.base_joints[kind]) for kind in BASE_KINDS)
        return Limbs(limbs, self._loose_hands(), wheels, rotors, tuple(self.skipped), tuple(self.notes))

    def _limb(self, raw: _RawLimb, name: str) -> Limb:
        last = raw.joints[-1].child
        tip = limb_tip(self.robot, raw.kind, last)
        active = tuple(j.name for j in raw.joints if j.is_active)
        hand = self._hand(name, last) if raw.has_hand else None
        return Limb(name, raw.kind, raw.base, tip, active, hand)

    def _hand(self, arm: str, last: str) -> Hand:
        """The hand after an arm whose last joint moves `last`: its actuated joints, the links
        they move, and the bodies fixed to it (a palm); not the frames without geometry (a
        flange, a TCP, a camera's optical frame) nor a sensor's body, as MoveIt's panda hand
        group holds panda_hand and its fingers, not panda_link8 or panda_hand_tcp."""
        robot = self.robot
        joints = [j for j in robot.subtree_joints(last) if j.is_actuated]
        moved = {link for j in joints for link in robot.subtree_links(j.child)}
        links = tuple(
            link for link in robot.subtree_links(last)[1:] if link in moved or _is_body(robot, link)
        )
        word = _hand_word(joints)
        parts = tokens(arm)
        name = "_".join(word if t == "arm" else t for t in parts) if "arm" in parts else f"{arm}_{word}"
        name = word if arm == "arm" else name
        return Hand(name, tuple(j.name for j in joints), links, tuple(j.name for j in joints if j.is_active))

    def _loose_hands(self) -> tuple[Hand, ...]:
        """A hand per link that hand chains hang from (the fingers of one palm are one hand)."""
        palms: dict[str, list[_Segment]] = {}
        for seg in self.loose_hands:
            palms.setdefault(seg.start, []).append(seg)
        numbers = [0] if len(palms) == 1 else list(range(1, len(palms) + 1))
        return tuple(_loose_hand(segs, n) for segs, n in zip(palms.values(), numbers, strict=True))


def _is_body(robot: RobotModel, link: str) -> bool:
    """A link with collision geometry that is no camera or range sensor (one on the hand is not
    the hand: MoveIt lets an object the end effector holds touch its links)."""
    return robot.link(link).has_geometry and not set(tokens(link)) & set(VISION_WORDS)


def _loose_hand(segs: list[_Segment], number: int) -> Hand:
    """One hand of the chains `segs`, numbered in its name unless `number` is 0."""
    flat = [s for seg in segs for s in _flatten(seg)]
    joints = [j for s in flat for j in s.joints if j.is_actuated]
    links = (*(seg.joints[0].child for seg in segs), *(j.child for s in flat for j in s.joints))
    word = _hand_word(joints)
    name = f"{word}_{number}" if number else word
    active = tuple(j.name for j in joints if j.is_active)
    return Hand(name, tuple(j.name for j in joints), tuple(dict.fromkeys(links)), active)


def _hand_word(joints: list[Joint]) -> str:
    words = name_words(joints)
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
    side = side_of(prefix)
    if side:
        return f"{side}_{raw.kind}"
    return "_".join(prefix) if prefix else f"{raw.kind}_{number}"


def _split_tail(joints: list[Joint], kind: str) -> tuple[list[Joint], list[Joint]]:
    """`joints` cut after the last active joint that is not of `kind` (a joint's own name decides
    before its child link's: `wrist_3_joint` stays in the arm whatever its link is called)."""
    last = max((i for i, j in enumerate(joints) if j.is_active and kind not in joint_kinds(j)), default=-1)
    return joints[: last + 1], joints[last + 1 :]


def _flatten(seg: _Segment) -> list[_Segment]:
    return [seg, *(s for c in seg.children for s in _flatten(c))]
