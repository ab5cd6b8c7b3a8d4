"""compute_collision_matrix: MoveIt Setup Assistant's self-collision matrix, seeded and fast.

Phases in MoveIt's order (a pair keeps the first reason it gets): Adjacent, Default (in
collision at the default state), Always (in collision in >= `min_collision_fraction` of a
round of 200 samples; rounds repeat until one adds nothing), Never (not seen in collision in
`trials` random states). Pairs seen in collision in any sample stay enabled.

Randomness: the Always rounds draw from `SeedSequence(seed, spawn_key=(0,))`; trial chunk i
(fixed size CHUNK) from `SeedSequence(seed, spawn_key=(1, i))`. So N trials are a prefix of
N + k, and the result does not depend on `jobs` (chunks are the same, only who runs them).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from marm_setup.collision.pairs import DisabledPair, DisabledReason
from marm_setup.robot.kinematics import default_configuration, sample_configurations
from marm_setup.robot.model import RobotModel

Pair = tuple[str, str]
ROUND = 200  # samples per Always round, as MoveIt
CHUNK = 1000  # trial samples per chunk (fixed: independent of jobs and CPU count)
CLOSEST = 8  # samples per Never pair (smallest bounding-sphere gap) where the distance is measured
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
    narrow_calls: int = field(default=0, compare=False)

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
) -> CollisionMatrix:
    """MoveIt's matrix for `robot` (scene: a CollisionScene, built when None)."""
    if scene is None:
        from marm_setup.collision.scene import CollisionScene

        scene = CollisionScene(robot)
    calls0 = scene.narrow_calls
    reasons = {pair: DisabledReason.ADJACENT for pair in robot.adjacent_geometry_pairs()}
    if check_default:
        q0 = default_configuration(robot) if default_q is None else np.asarray(default_q, dtype=float)
        _disable_default(scene, q0, reasons)
    counts = _disable_always(scene, seed, min_collision_fraction, reasons) if check_always else {}
    remaining = tuple(p for p in scene.candidate_pairs if p not in reasons)
    seen = {p for p, (hits, _) in counts.items() if hits}  # hit in an Always round: no more checks
    q = trial_samples(robot, seed, trials)
    seen_in_trials, closest = _run_trials(
        scene, q, tuple(p for p in remaining if p not in seen), jobs, progress
    )
    seen |= seen_in_trials
    never = [p for p in remaining if p not in seen]
    reasons.update(dict.fromkeys(never, DisabledReason.NEVER))
    distances = _never_distances(scene, q, never, closest)
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
        narrow_calls=scene.narrow_calls - calls0,
    )


def trial_samples(robot: RobotModel, seed: int, trials: int) -> np.ndarray:
    """The (trials, n_active) random states of the Never phase, chunk by fixed-size chunk."""
    parts = []
    for i in range(math.ceil(trials / CHUNK)):
        rng = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(1, i)))
        parts.append(sample_configurations(robot, rng, min(CHUNK, trials - i * CHUNK)))
    return np.concatenate(parts) if parts else np.empty((0, len(robot.active_joints)))


def _disable_default(scene, q0: np.ndarray, reasons: dict[Pair, DisabledReason]) -> None:
    pairs = tuple(p for p in scene.candidate_pairs if p not in reasons)
    if not pairs:
        return
    hits = scene.collision_counts(scene.link_poses(q0[None, :]), scene.pair_ids(pairs))
    reasons.update({p: DisabledReason.DEFAULT for p, h in zip(pairs, hits, strict=True) if h})


def _disable_always(scene, seed: int, fraction: float, reasons) -> dict[Pair, tuple[int, int]]:
    """Rounds of ROUND samples until a round disables nothing; returns (hits, samples) per pair."""
    rng = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(0,)))
    counts: dict[Pair, tuple[int, int]] = {}
    while True:
        pairs = tuple(p for p in scene.candidate_pairs if p not in reasons)
        if not pairs:
            return counts
        poses = scene.link_poses(sample_configurations(scene.robot, rng, ROUND))
        hits = scene.collision_counts(poses, scene.pair_ids(pairs))
        added = 0
        for pair, h in zip(pairs, hits.tolist(), strict=True):
            old_hits, old_samples = counts.get(pair, (0, 0))
            counts[pair] = (old_hits + h, old_samples + ROUND)
            if h >= fraction * ROUND - 1e-9:
                reasons[pair] = DisabledReason.ALWAYS
                added += 1
        if not added:
            return counts


def _run_trials(scene, q: np.ndarray, pairs: tuple[Pair, ...], jobs: int, progress: Progress | None):
    """Pairs seen colliding over all trial states, and per pair its CLOSEST nearest states."""
    starts = list(range(0, len(q), CHUNK))
    seen: set[Pair] = set()
    closest: dict[Pair, list[tuple[float, int]]] = {p: [] for p in pairs}
    if progress:
        progress(0, len(q))
    for done, (start, (chunk_seen, chunk_closest)) in enumerate(
        _chunk_results(scene, q, pairs, starts, jobs)
    ):
        seen |= chunk_seen
        for pair, items in chunk_closest.items():
            closest[pair] = sorted(closest[pair] + [(g, i + start) for g, i in items])[:CLOSEST]
        if progress:
            progress(min(len(q), starts[done] + CHUNK), len(q))
    return seen, closest


def _chunk_results(scene, q, pairs, starts, jobs):
    """(start, check_chunk result) per chunk, in chunk order; processes when jobs > 1."""
    if jobs <= 1 or len(starts) <= 1 or not pairs:
        unseen = pairs
        for start in starts:
            chunk_seen, chunk_closest = check_chunk(scene, q[start : start + CHUNK], unseen)
            unseen = tuple(p for p in unseen if p not in chunk_seen)
            yield start, (chunk_seen, chunk_closest)
        return
    yield from zip(starts, _map_chunks(scene, q, pairs, starts, jobs), strict=True)


def check_chunk(scene, q: np.ndarray, pairs: tuple[Pair, ...]):
    """Pairs of `pairs` seen colliding in states `q`, and each pair's CLOSEST smallest-gap states.

    A pair stops being checked at its first collision; its candidate states are tried in order of
    deepest bounding-sphere overlap, so sometimes-colliding pairs are found in a few calls.
    """
    if not pairs or not len(q):
        return set(), {}
    ids = scene.pair_ids(pairs)
    poses = scene.link_poses(q)
    gaps = scene.sphere_gaps(poses, ids)
    maybe = scene.maybe_colliding(poses, ids, gaps)
    seen = set()
    for k, pair in enumerate(pairs):
        candidates = np.flatnonzero(maybe[:, k])
        for n in candidates[np.argsort(gaps[candidates, k], kind="stable")]:
            if scene.collide(poses[n], ids[k]):
                seen.add(pair)
                break
    order = np.argsort(gaps, axis=0, kind="stable")[:CLOSEST]
    closest = {
        p: [(float(gaps[n, k]), int(n)) for n in order[:, k]] for k, p in enumerate(pairs) if p not in seen
    }
    return seen, closest


_WORKER_SCENE = None  # the scene of a worker process (set by fork or by _init_worker)


def _init_worker(robot: RobotModel, padding: float) -> None:
    global _WORKER_SCENE
    if _WORKER_SCENE is None:
        from marm_setup.collision.scene import CollisionScene

        _WORKER_SCENE = CollisionScene(robot, padding)


def _worker_chunk(args):
    return check_chunk(_WORKER_SCENE, *args)


def _map_chunks(scene, q, pairs, starts, jobs):
    """check_chunk over chunks in `jobs` processes, results in chunk order."""
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor

    global _WORKER_SCENE
    fork = "fork" in multiprocessing.get_all_start_methods()
    context = multiprocessing.get_context("fork" if fork else "spawn")
    _WORKER_SCENE = scene if fork else None  # forked workers inherit the built scene
    try:
        with ProcessPoolExecutor(
            jobs, mp_context=context, initializer=_init_worker, initargs=(scene.robot, scene.padding)
        ) as pool:
            yield from pool.map(_worker_chunk, [(q[s : s + CHUNK], pairs) for s in starts])
    finally:
        _WORKER_SCENE = None


def _never_distances(scene, q, never: list[Pair], closest) -> dict[Pair, float]:
    """Smallest exact distance [m] of each Never pair over its CLOSEST nearest-looking states."""
    rows = sorted({i for pair in never for _, i in closest.get(pair, [])})
    if not rows:
        return {}
    poses = dict(zip(rows, scene.link_poses(q[rows]), strict=True))
    out = {}
    for pair in never:
        if closest.get(pair):
            pair_id = int(scene.pair_ids((pair,))[0])
            out[pair] = min(scene.distance(poses[i], pair_id) for _, i in closest[pair])
    return out
