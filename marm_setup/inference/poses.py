"""Named poses that work (DESIGN.md §2): a collision-free `home` for every group and a second
pose, `ready`, for every limb group, so `validate` and `plan` have a pose pair out of the box.

`home` is every group's joints at zero, kept a tenth of their range (at most 0.3) inside
their limits (a hand's joints only within them: a gripper rests open or closed); when that
state is in collision under the setup's matrix, the nearest collision-free state found by a
seeded search around it, inside the same band. `ready` bends each joint of a limb group away from home (other joints at home) and
is kept only when it and the straight path to it are collision-free; else a seeded random
pose near home is taken. All values are rounded to 4 decimals before they are checked.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np

from marm_setup.robot import RobotModel, default_configuration
from marm_setup.setup import (
    GroupState,
    SetupModel,
    StartPose,
    active_group_joints,
    allowed_pairs,
    groups_by_name,
    model_start_values,
    pose_configuration,
    setup_to_srdf,
    start_configuration,
    start_pose,
)

if TYPE_CHECKING:
    from marm_setup.collision import CollisionScene

HOME, READY = "home", "ready"
SEARCH_SCALES = (0.05, 0.1, 0.2, 0.4, 0.8)  # [rad] (or that share of a prismatic joint's range)
BATCH = 64
HOME_MARGIN = 0.3  # [rad or m]: at most this far inside a limit is far enough for home
READY_BEND = 0.4  # [rad]: how far `ready` bends each joint from home
MIN_MOVE = 0.1  # [rad]: `ready` moves some joint at least this far
PATH_STEPS = 12
DECIMALS = 4


@dataclass(frozen=True)
class PoseResult:
    states: tuple[GroupState, ...]
    notes: tuple[str, ...]


class _Space:
    """The robot's active joints, a base state, and collision checks under the setup's matrix."""

    def __init__(self, model: SetupModel, robot: RobotModel, scene: CollisionScene) -> None:
        self.robot, self.scene = robot, scene
        self.names = robot.active_joint_names
        self.index = {n: i for i, n in enumerate(self.names)}
        self.lo = np.array([robot.joint(n).bounds[0] for n in self.names])
        self.hi = np.array([robot.joint(n).bounds[1] for n in self.names])
        allowed = allowed_pairs(setup_to_srdf(model), scene.candidate_pairs)
        self.pairs = tuple(p for p in scene.candidate_pairs if p not in allowed)

    def round(self, q: np.ndarray) -> np.ndarray:
        return np.clip(np.round(q, DECIMALS), self.lo, self.hi)

    def hits(self, q: np.ndarray) -> list:
        """Per configuration (rows of q), the first colliding pair or None."""
        return (
            self.scene.first_collisions(np.atleast_2d(q), self.pairs)
            if self.pairs
            else [None] * len(np.atleast_2d(q))
        )

    def steps(self, idx: np.ndarray, scale: float) -> np.ndarray:
        span = np.minimum(self.hi[idx] - self.lo[idx], 1.0)
        return scale * span


def infer_poses(model: SetupModel, robot: RobotModel, scene: CollisionScene, *, seed: int = 0) -> PoseResult:
    """`home` for each group without subgroups (collision-free together), `ready` for each of
    them with two or more joints that is not an end effector."""
    space = _Space(model, robot, scene)
    by_name = groups_by_name(model.groups)
    leaves = [g for g in model.groups if not g.subgroups]
    joints = {g.name: active_group_joints(g, by_name, robot, model.passive_joints) for g in leaves}
    leaves = [g for g in leaves if joints[g.name]]
    rng = np.random.default_rng(seed)
    hands = {ee.group for ee in model.end_effectors}
    at_limits = {j for g in leaves if g.name in hands for j in joints[g.name]}
    q, notes = _home(space, [j for g in leaves for j in joints[g.name]], at_limits, rng)
    states = [_state(HOME, g.name, joints[g.name], q, space) for g in leaves]
    for group in (g for g in leaves if g.name not in hands and len(joints[g.name]) > 1):
        ready, note = _ready(space, q, joints[group.name], rng)
        notes += [f"group {group.name}: {note}"] if note else []
        if ready is not None:
            states.append(_state(READY, group.name, joints[group.name], ready, space))
    return PoseResult(tuple(states), tuple(notes))


def _state(name: str, group: str, joints: tuple[str, ...], q: np.ndarray, space: _Space) -> GroupState:
    return GroupState(name, group, tuple((j, float(q[space.index[j]])) for j in joints))


def _home(
    space: _Space, joints: list[str], at_limits: set[str], rng: np.random.Generator
) -> tuple[np.ndarray, list[str]]:
    """Zeros kept off the limits (`home_band`; the `at_limits` joints, a hand's, only within
    them), or the nearest collision-free state found around them inside the same band."""
    q = default_configuration(space.robot)
    idx = np.array([space.index[j] for j in joints], dtype=np.intp)
    lo, hi = home_band(space.lo[idx], space.hi[idx])
    hand = np.array([j in at_limits for j in joints], dtype=bool)
    lo, hi = np.where(hand, space.lo[idx], lo), np.where(hand, space.hi[idx], hi)
    q[idx] = np.clip(0.0, lo, hi)
    q = space.round(q)
    moved = [f"{j} {q[i]:g}" for j, i in zip(joints, idx, strict=True) if q[i] != 0.0]
    notes = (
        [f"home: {', '.join(moved)} (zero is on or near a limit of each: home keeps off them)"]
        if moved
        else []
    )
    hit = space.hits(q)[0]
    if hit is None:
        return q, notes
    for scale in SEARCH_SCALES:
        found = _nearest_free(space, q, idx, scale, rng, (lo, hi))
        if found is not None:
            moved_by = float(np.max(np.abs(found - q)))
            return found, [
                *notes,
                f"home: zeros are in collision ({hit[0]} - {hit[1]}); moved up to {moved_by:.3g} from "
                + ("there" if moved else "zero"),
            ]
    return q, [
        *notes,
        f"home is in collision ({hit[0]} - {hit[1]}) and no free state was found near it: give one in a SPEC",
    ]


def home_value(bounds: tuple[float, float], *, at_limits: bool = False) -> float:
    """A joint's home: zero kept inside `home_band` (within `bounds` only, `at_limits`)."""
    lo, hi = bounds if at_limits else home_band(np.array(bounds[0]), np.array(bounds[1]))
    return round(float(np.clip(0.0, lo, hi)), DECIMALS)


def home_band(lo: np.ndarray, hi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Where a home value may lie: a tenth of the joint's range (at most HOME_MARGIN) inside each
    limit. A pose on a limit is one a real arm stops short of (soft limits, the controller's
    position tolerance) and from which `ready` and every plan can leave only one way."""
    margin = np.minimum(0.1 * (hi - lo), HOME_MARGIN)
    return lo + margin, hi - margin


def _nearest_free(
    space: _Space,
    q: np.ndarray,
    idx: np.ndarray,
    scale: float,
    rng: np.random.Generator,
    band: tuple[np.ndarray, np.ndarray],
) -> np.ndarray | None:
    cand = np.repeat(q[None], BATCH, axis=0)
    cand[:, idx] += rng.uniform(-1.0, 1.0, (BATCH, len(idx))) * space.steps(idx, scale)
    cand[:, idx] = np.clip(cand[:, idx], *band)
    cand = space.round(cand)
    free = [k for k, hit in enumerate(space.hits(cand)) if hit is None]
    if not free:
        return None
    return cand[min(free, key=lambda k: float(np.linalg.norm(cand[k] - q)))]


def _ready(
    space: _Space, home: np.ndarray, joints: tuple[str, ...], rng: np.random.Generator
) -> tuple[np.ndarray | None, str]:
    """A second pose for a chain group: a bend away from home, or a random one near it."""
    idx = np.array([space.index[j] for j in joints], dtype=np.intp)
    bent = _bend(space, home, idx)
    if bent is not None and _free_path(space, home, bent):
        return bent, ""
    for scale in SEARCH_SCALES[2:]:
        cand = np.repeat(home[None], BATCH, axis=0)
        cand[:, idx] += rng.uniform(-1.0, 1.0, (BATCH, len(idx))) * space.steps(idx, scale * 2)
        cand = space.round(cand)
        for k in np.argsort(-np.max(np.abs(cand - home), axis=1)):
            if np.max(np.abs(cand[k] - home)) >= MIN_MOVE and _free_path(space, home, cand[k]):
                return cand[
                    k
                ], f"'{READY}' is a random collision-free pose near home (bending the joints collides)"
    return (
        None,
        f"no collision-free second pose found near home: give one in a SPEC to plan '{HOME}' -> another pose",
    )


def _bend(space: _Space, home: np.ndarray, idx: np.ndarray) -> np.ndarray | None:
    """Each joint bent by READY_BEND, alternating in sign, turned back where a limit is in the way."""
    q = home.copy()
    for k, i in enumerate(idx):
        step = min(READY_BEND, 0.25 * (space.hi[i] - space.lo[i]))
        sign = 1.0 if k % 2 == 0 else -1.0
        if not space.lo[i] <= home[i] + sign * step <= space.hi[i]:
            sign = -sign
        q[i] = home[i] + sign * step
    q = space.round(q)
    return q if np.max(np.abs(q - home)) >= MIN_MOVE * 0.5 else None


def _free_path(space: _Space, a: np.ndarray, b: np.ndarray) -> bool:
    """`b` and the straight joint-space path from `a` to it are collision-free."""
    t = np.linspace(0.0, 1.0, PATH_STEPS + 1)[1:, None]
    return all(hit is None for hit in space.hits(a[None] + t * (b - a)[None]))


def choose_start_poses(
    model: SetupModel, robot: RobotModel, scene: CollisionScene
) -> tuple[tuple[StartPose, ...] | None, tuple[str, ...]]:
    """The setup's `start_poses`, changed when the demo would start in collision, and a note.

    A start is scored by the enabled pairs in collision at it, then by the named poses that
    collide when applied over it (what validate checks). When the setup's start has a collision,
    each group in turn tries each of its poses and none (its joints at their defaults), keeping
    the choice that scores best (deterministic, greedy); the start poses change only when the
    start is then free of collisions."""
    space = _Space(model, robot, scene)
    score = _start_score(model, robot, space)
    if not score[0]:
        return model.start_poses, ()
    chosen: dict[str, str | None] = {
        g.name: pose.name for g in model.groups if (pose := start_pose(model, g.name))
    }
    first, best = score, score
    for group in model.groups:
        for name in [s.name for s in model.group_states if s.group == group.name] + [None]:
            trial = {**chosen, group.name: name}
            found = _start_score(_with_start(model, trial), robot, space)
            if found < best:
                chosen, best = trial, found
    a, b = first[2]
    if best[0]:
        note = (
            f"warning: the demo starts in collision ({a} - {b}) whatever given poses it starts at: "
            "give a collision-free pose and name it in start_poses"
        )
        return model.start_poses, (note,)
    starts = _with_start(model, chosen).start_poses or ()
    listed = ", ".join(f"{s.group}: {s.pose}" for s in starts) or "every joint's default"
    return starts, (f"the default start poses collide ({a} - {b}): the demo starts at {listed}",)


def _with_start(model: SetupModel, chosen: dict[str, str | None]) -> SetupModel:
    starts = tuple(StartPose(g.name, pose) for g in model.groups if (pose := chosen.get(g.name)))
    return replace(model, start_poses=starts)


def _start_score(model: SetupModel, robot: RobotModel, space: _Space) -> tuple[int, int, tuple[str, str]]:
    """(pairs in collision at the start, named poses in collision over it, the first pair): the
    start state and each pose over it as validate's pose rules build them."""
    start_values = model_start_values(model, robot)
    poses = [pose_configuration(s, robot, start_values) for s in model.group_states]
    states = [start_configuration(robot, start_values), *poses]
    hits = space.hits(np.array(states))
    return (int(hits[0] is not None), sum(h is not None for h in hits[1:]), hits[0] or ("", ""))
