"""compute_collision_matrix: MoveIt Setup Assistant's self-collision matrix, seeded and fast.

Phases in MoveIt's order (a pair keeps the first reason it gets): Adjacent, Default (in
collision at the default state), Always (in collision in >= `min_collision_fraction` of a
round of 200 samples; rounds repeat until one adds nothing), Never (not seen in collision in
`trials` random states). Pairs seen in collision in any sample stay enabled.

Randomness: the Always rounds draw from `SeedSequence(seed, spawn_key=(0,))`; the trials come
in fixed chunks (`collision/trials.py`), streamed, the same whoever checks them (`--jobs`).

Exactness: the answer is "does coal find the pair in collision in any sampled state". The
shortcuts (hull test, distance certificates; `collision/prover.py`) only skip exact checks
they prove would say "no collision", so `shortcuts=False` gives the same bytes.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from marm_setup.collision.pairs import DisabledPair, DisabledReason
from marm_setup.collision.trials import CHUNK, CLOSEST, TrialChecker, Work, trial_samples
from marm_setup.collision.workers import Workers
from marm_setup.robot.kinematics import default_configuration, sample_configurations
from marm_setup.robot.model import RobotModel

__all__ = ["CHUNK", "CollisionMatrix", "PairStats", "compute_collision_matrix", "trial_samples"]

Pair = tuple[str, str]
ROUND = 200  # samples per Always round, as MoveIt
Progress = Callable[[int, int], None]


@dataclass(frozen=True, slots=True)
class PairStats:
    """One candidate pair: its reason (None: enabled), hits in the fully counted Always-round
    samples (`hits` of `samples`), whether any sample showed it in collision, and for Never
    pairs the smallest distance [m] measured over its closest-looking trial states."""

    link1: str
    link2: str
    reason: DisabledReason | None
    hits: int = 0
    samples: int = 0
    seen_colliding: bool = False
    min_distance: float | None = None

    @property
    def pair(self) -> Pair:
        return (self.link1, self.link2)


@dataclass(frozen=True)
class CollisionMatrix:
    """The result: `disabled` sorted, `enabled` the sometimes-colliding pairs, `stats` per pair."""

    disabled: tuple[DisabledPair, ...]
    enabled: tuple[Pair, ...]
    stats: tuple[PairStats, ...]
    trials: int
    seed: int
    min_collision_fraction: float
    padding: float
    work: Work = field(default=Work(), compare=False)

    @property
    def narrow_calls(self) -> int:
        """Exact coal checks, every worker process included."""
        return self.work.exact_checks

    def count(self, reason: DisabledReason) -> int:
        return sum(1 for d in self.disabled if d.reason is reason)


def compute_collision_matrix(
    robot: RobotModel,
    scene=None,
    *,
    trials: int = 10000,
    seed: int = 0,
    min_collision_fraction: float = 0.95,
    check_default: bool = True,
    check_always: bool = True,
    default_q: np.ndarray | None = None,
    jobs: int = 1,
    progress: Progress | None = None,
    shortcuts: bool = True,
) -> CollisionMatrix:
    """MoveIt's matrix for `robot` (scene: a CollisionScene, built when None).

    `shortcuts=False` checks every state that passes the bounding volumes exactly (no hull
    test, no certificates): the reference the shortcuts must match byte for byte.
    """
    if scene is None:
        from marm_setup.collision.scene import CollisionScene

        scene = CollisionScene(robot)
    before = Work.of(scene)
    reasons = {pair: DisabledReason.ADJACENT for pair in robot.adjacent_geometry_pairs()}
    if check_default:
        q0 = default_configuration(robot) if default_q is None else np.asarray(default_q, dtype=float)
        _disable_default(scene, q0, reasons, shortcuts)
    counts = _disable_always(scene, seed, min_collision_fraction, reasons, shortcuts) if check_always else {}
    remaining = tuple(p for p in scene.candidate_pairs if p not in reasons)
    seen = {p for p, (hits, _) in counts.items() if hits}  # hit in an Always round: no more checks
    trial_pairs = tuple(p for p in remaining if p not in seen)
    with Workers(TrialChecker(scene, seed, trials, shortcuts, jobs), jobs) as workers:
        seen_in_trials, closest, others = _run_trials(workers, trial_pairs, progress)
        seen |= seen_in_trials
        never = [p for p in remaining if p not in seen]
        reasons.update(dict.fromkeys(never, DisabledReason.NEVER))
        items = [(p, [i for _, i in closest[p]]) for p in never if closest.get(p)]
        distances, distance_work = workers.distances(items)
    stats = tuple(
        PairStats(p[0], p[1], reasons.get(p), *counts.get(p, (0, 0)), p in seen, distances.get(p))
        for p in scene.candidate_pairs
    )
    return CollisionMatrix(
        disabled=tuple(sorted(DisabledPair.of(*p, r) for p, r in reasons.items())),
        enabled=tuple(p for p in remaining if p in seen),
        stats=stats,
        trials=trials,
        seed=seed,
        min_collision_fraction=min_collision_fraction,
        padding=scene.padding,
        work=Work.of(scene) - before + others + distance_work,
    )


def _disable_default(scene, q0: np.ndarray, reasons: dict[Pair, DisabledReason], hulls: bool) -> None:
    pairs = tuple(p for p in scene.candidate_pairs if p not in reasons)
    if not pairs:
        return
    hits = scene.collision_counts(scene.link_poses(q0[None, :]), scene.pair_ids(pairs), hulls)
    reasons.update({p: DisabledReason.DEFAULT for p, h in zip(pairs, hits, strict=True) if h})


def _disable_always(scene, seed: int, fraction: float, reasons, hulls: bool) -> dict[Pair, tuple[int, int]]:
    """Rounds of ROUND samples until a round disables nothing; returns (hits, samples) per pair."""
    rng = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(0,)))
    counts: dict[Pair, tuple[int, int]] = {}
    while True:
        pairs = tuple(p for p in scene.candidate_pairs if p not in reasons)
        if not pairs:
            return counts
        poses = scene.link_poses(sample_configurations(scene.robot, rng, ROUND))
        hits = scene.collision_counts(poses, scene.pair_ids(pairs), hulls)
        added = 0
        for pair, h in zip(pairs, hits.tolist(), strict=True):
            old_hits, old_samples = counts.get(pair, (0, 0))
            counts[pair] = (old_hits + h, old_samples + ROUND)
            if h >= fraction * ROUND - 1e-9:
                reasons[pair] = DisabledReason.ALWAYS
                added += 1
        if not added:
            return counts


def _run_trials(workers: Workers, pairs: tuple[Pair, ...], progress: Progress | None):
    """Pairs seen colliding over all trial states, per pair its CLOSEST nearest states (gap,
    global row), and the work of worker processes (the parent's own is on its scene)."""
    trials = workers.checker.trials
    seen: set[Pair] = set()
    closest: dict[Pair, list[tuple[float, int]]] = {p: [] for p in pairs}
    others = Work()
    if progress:
        progress(0, trials)
    for index, (chunk_seen, chunk_closest, work) in enumerate(workers.chunks(pairs)):
        seen |= chunk_seen
        others += work
        for pair, items in chunk_closest.items():
            closest[pair] = sorted(closest[pair] + items)[:CLOSEST]
        if progress:
            progress(min(trials, (index + 1) * CHUNK), trials)
    return seen, closest, others
